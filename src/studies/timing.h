/* timing.h — how the studies and the program time a frame: the clock
 * (core/clock.h), one frame as a viewer pays for it, and the median of
 * repeated runs. */
#ifndef SOFTRAST_STUDIES_TIMING_H
#define SOFTRAST_STUDIES_TIMING_H

#include <stdbool.h>
#include <stddef.h>

#include "core/clock.h" /* sr_now_ms */
#include "softrast_private.h"

/* One frame as a viewer pays for it, timed into *ms: clear color (to 0) and
 * depth, then the draw. stats, when given, is zeroed first. */
bool sr_study_draw_frame(sr_framebuffer *fb, const sr_draw_desc *desc, sr_stats *stats, double *ms, sr_error *err);

/* Sorts v[0..n) ascending. */
void sr_study_sort_doubles(double *v, size_t n);

/* Sorts ms[0..n) and gives its median and minimum (n >= 1). */
void sr_study_median_min(double *ms, int n, double *median, double *min);

#endif
