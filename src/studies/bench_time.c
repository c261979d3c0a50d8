#include <stdlib.h>

#include "core/clock.h"
#include "scene/frame.h"
#include "bench_time.h"

static bool time_frames(const sr_bench_scene *s, const sr_bench_run *run, sr_framebuffer *fb, sr_workspace *ws,
                        double *ms, sr_bench_result *r, sr_error *err)
{
    bool ok = true;
    for (int f = -1; ok && f < run->frames; f++) { /* frame -1 is the warm-up */
        sr_camera cam;
        sr_draw_study study = { .simd = run->simd, .times = f < 0 ? NULL : run->times };
        sr_draw_desc desc = { .mesh = &s->mesh, .shade = s->shade, .cull = s->cull,
                              .texture = s->texture.texels ? &s->texture : NULL, .threads = run->threads,
                              .workspace = ws, .study = &study };
        sr_bench_scene_camera(s, f < 0 ? 0 : f, run->frames, &cam);
        sr_camera_view(&cam, desc.view);
        sr_camera_projection(&cam, (float)s->width / (float)s->height, desc.projection);
        double warm_up;
        ok = sr_frame_draw_timed(fb, &desc, &r->stats, f < 0 ? &warm_up : &ms[f], err);
    }
    if (!ok)
        return false;
    r->mean = 0.0;
    for (int f = 0; f < run->frames; f++)
        r->mean += ms[f] / run->frames;
    sr_median_min(ms, run->frames, &r->median, &r->min);
    return true;
}

bool sr_bench_time(const sr_bench_scene *s, const sr_bench_run *run, sr_framebuffer *fb, sr_bench_result *r,
                   sr_error *err)
{
    sr_framebuffer own = { 0 };
    if (!fb && !sr_framebuffer_create(&own, s->width, s->height, err))
        return false;
    sr_workspace *ws = sr_workspace_create();
    double *ms = malloc((size_t)run->frames * sizeof *ms);
    bool ok = ms && ws ? time_frames(s, run, fb ? fb : &own, ws, ms, r, err)
                       : sr_error_set(err, "out of memory for the benchmark");
    free(ms);
    sr_workspace_destroy(ws);
    if (own.color)
        sr_framebuffer_destroy(&own);
    return ok;
}
