/* app.h — the softrast program's subcommands. Each returns the exit status. */
#ifndef SOFTRAST_APP_H
#define SOFTRAST_APP_H

#include "softrast/softrast.h"

int sr_app_render(int argc, char **argv);
int sr_app_view(int argc, char **argv);
int sr_app_bench(int argc, char **argv);

/* Prints "softrast: error: <message>" on stderr and returns the exit status 1. */
int sr_app_fail(const char *message);

/* A monotonic clock in milliseconds. */
double sr_app_now_ms(void);

/* One frame as a viewer pays for it, timed into *ms: clear color (to 0) and
 * depth, then the draw. stats, when given, is zeroed first. */
bool sr_app_draw_frame(sr_framebuffer *fb, const sr_draw_desc *desc, sr_stats *stats, double *ms, sr_error *err);

/* Sorts v[0..n) ascending. */
void sr_app_sort_doubles(double *v, size_t n);

/* Sorts ms[0..n) and gives its median and minimum (n >= 1). */
void sr_app_median_min(double *ms, int n, double *median, double *min);

#endif
