/* bench_time.h — timing a benchmark scene as a viewer pays for a frame,
 * shared by `softrast bench` and its error-against-time report. */
#ifndef SOFTRAST_APP_BENCH_TIME_H
#define SOFTRAST_APP_BENCH_TIME_H

#include "bench_scenes.h"

typedef struct sr_bench_run {
    int frames, threads;
    sr_simd simd;
    sr_draw_times *times; /* optional: the timed frames' draws add their phases here */
} sr_bench_run;

typedef struct sr_bench_result {
    double median, min, mean; /* ms per frame */
    sr_stats stats;     /* of the last frame */
} sr_bench_result;

/* Times run->frames frames of the scene (after one untimed warm-up), a
 * frame being clear + draw as in the viewer. The frames are drawn into fb
 * when given (of the scene's size; it then holds the last frame), else into
 * a framebuffer of its own. */
bool sr_bench_time(const sr_bench_scene *s, const sr_bench_run *run, sr_framebuffer *fb, sr_bench_result *r,
                   sr_error *err);

#endif
