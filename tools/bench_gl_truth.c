/* bench_gl_truth.c — llvmpipe against the truth image on the report's scenes:
 * the same cameras `softrast bench --report` compares, ids from
 * gl_PrimitiveID, depth read back as float32, tallied as the report tallies
 * softrast's knobs (src/studies/report_truth.h), and timed as the report
 * times them: the median of `frames` draws of each camera. */
#include <stdio.h>
#include <stdlib.h>

#include "bench_gl.h"
#include "studies/report.h"
#include "core/clock.h"

/* The truth of frame f of n, with the camera llvmpipe draws it from. */
static bool frame_truth(const sr_bench_scene *s, int f, int n, sr_truth_image *truth, mat4 projection,
                        sr_error *err)
{
    sr_draw_desc desc = { .mesh = &s->mesh };
    bench_gl_frame_camera(s, f, n, desc.view, desc.projection);
    glm_mat4_copy(desc.projection, projection);
    return sr_truth_render(&desc, s->width, s->height, truth, err);
}

/* The first draw of each camera (untimed: it warms up and is read back)
 * goes to the tally, the next `frames` draws to ms. */
static bool tally_frames(bench_gl_scene *g, const sr_bench_scene *s, int frames, sr_framebuffer *fb,
                         sr_truth_tally *tally, double *ms, sr_error *err)
{
    int n = sr_report_scene_frames(s);
    bool ok = true;
    for (int f = 0; ok && f < n; f++) {
        sr_truth_image truth = { 0 };
        mat4 projection;
        ok = bench_gl_scene_prepare(g, s, f, n, err) && bench_gl_scene_draw(g, err) &&
             bench_gl_scene_read(g, fb->color, fb->depth, err) && frame_truth(s, f, n, &truth, projection, err);
        ok = ok && sr_truth_tally_add(tally, &truth, projection, fb, err);
        sr_truth_image_free(&truth);
        for (int r = 0; ok && r < frames; r++) {
            double start = sr_now_ms();
            ok = bench_gl_scene_draw(g, err);
            ms[f * frames + r] = sr_now_ms() - start;
        }
    }
    return ok;
}

bool bench_gl_truth(sr_bench_scene *s, int lp_threads, int frames, sr_report_peer_row *out, sr_error *err)
{
    bench_gl_context *ctx = NULL;
    bench_gl_scene *g = NULL;
    sr_framebuffer fb = { 0 };
    sr_truth_tally tally = { .coverage_tolerance = sr_truth_coverage_tolerance(SR_SUBPIXEL_BITS) };
    int timed = sr_report_scene_frames(s) * frames;
    double *ms = malloc((size_t)timed * sizeof *ms), min;
    s->shade = SR_SHADE_ID;
    bool ok = (ms || sr_error_set(err, "out of memory for %d frame times", timed)) &&
              sr_framebuffer_create(&fb, s->width, s->height, err) &&
              bench_gl_context_create(&ctx, lp_threads, err) && bench_gl_scene_create(&g, s, err) &&
              tally_frames(g, s, frames, &fb, &tally, ms, err);
    *out = (sr_report_peer_row){ .truth = sr_truth_tally_finish(&tally) };
    snprintf(out->scene, sizeof out->scene, "%s", s->name);
    if (ok)
        sr_median_min(ms, timed, &out->ms, &min);
    free(ms);
    bench_gl_scene_destroy(g);
    bench_gl_context_destroy(ctx);
    if (fb.color)
        sr_framebuffer_destroy(&fb);
    return ok;
}
