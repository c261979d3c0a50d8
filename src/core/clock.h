/* clock.h — milliseconds on one of the POSIX clocks: the draw's phase
 * timing (CLOCK_MONOTONIC, CLOCK_THREAD_CPUTIME_ID), the studies' frame
 * timing and the program's load progress. */
#ifndef SOFTRAST_CORE_CLOCK_H
#define SOFTRAST_CORE_CLOCK_H

#include <time.h>

double sr_clock_ms(clockid_t clock);

/* The monotonic clock, for elapsed times. */
static inline double sr_now_ms(void)
{
    return sr_clock_ms(CLOCK_MONOTONIC);
}

#endif
