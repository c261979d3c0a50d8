/* timing.c — one timed frame, medians. */
#include <stdio.h>
#include <stdlib.h>

#include "timing.h"

bool sr_study_draw_frame(sr_framebuffer *fb, const sr_draw_desc *desc, sr_stats *stats, double *ms, sr_error *err)
{
    double start = sr_now_ms();
    if (stats)
        *stats = (sr_stats){ 0 };
    sr_draw_desc clearing = *desc;
    clearing.clear = true; /* to color 0, inside the draw (each tile by its thread) */
    bool ok = sr_draw(fb, &clearing, stats, err);
    *ms = sr_now_ms() - start;
    return ok;
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void sr_study_sort_doubles(double *v, size_t n)
{
    qsort(v, n, sizeof *v, compare_double);
}

void sr_study_median_min(double *ms, int n, double *median, double *min)
{
    sr_study_sort_doubles(ms, (size_t)n);
    *min = ms[0];
    *median = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
}
