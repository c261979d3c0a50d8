/* clock.h — milliseconds on one of the POSIX clocks (the draw's phase
 * timing, a timed frame, the program's load progress) and the median of
 * repeated timings. */
#ifndef SOFTRAST_CORE_CLOCK_H
#define SOFTRAST_CORE_CLOCK_H

#include <stddef.h>
#include <time.h>

double sr_clock_ms(clockid_t clock);

/* The monotonic clock, for elapsed times. */
static inline double sr_now_ms(void)
{
    return sr_clock_ms(CLOCK_MONOTONIC);
}

/* Sorts v[0..n) ascending. */
void sr_sort_doubles(double *v, size_t n);

/* Sorts ms[0..n) and gives its median and minimum (n >= 1). */
void sr_median_min(double *ms, int n, double *median, double *min);

#endif
