/* clock.c — the clock and medians (clock.h). */
#include "clock.h"

#include <stdlib.h>

double sr_clock_ms(clockid_t clock)
{
    struct timespec t;
    clock_gettime(clock, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void sr_sort_doubles(double *v, size_t n)
{
    qsort(v, n, sizeof *v, compare_double);
}

void sr_median_min(double *ms, int n, double *median, double *min)
{
    sr_sort_doubles(ms, (size_t)n);
    *min = ms[0];
    *median = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
}
