/* bench_gl_truth.c — llvmpipe against the truth image on the report's scenes:
 * the same cameras `softrast bench --report` compares, ids from
 * gl_PrimitiveID, depth read back as float32, tallied as the report tallies
 * softrast's knobs (src/studies/report_truth.h). */
#include <stdlib.h>

#include "bench_gl.h"
#include "studies/report.h"

/* The truth of frame f of n, with the camera llvmpipe draws it from. */
static bool frame_truth(const sr_bench_scene *s, int f, int n, sr_truth_image *truth, mat4 projection,
                        sr_error *err)
{
    sr_draw_desc desc = { .mesh = &s->mesh };
    bench_gl_frame_camera(s, f, n, desc.view, desc.projection);
    glm_mat4_copy(desc.projection, projection);
    return sr_truth_render(&desc, s->width, s->height, truth, err);
}

static bool tally_frames(bench_gl_scene *g, const sr_bench_scene *s, sr_framebuffer *fb, sr_truth_tally *tally,
                         sr_error *err)
{
    int n = sr_report_scene_frames(s);
    bool ok = true;
    for (int f = 0; ok && f < n; f++) {
        sr_truth_image truth;
        mat4 projection;
        ok = bench_gl_scene_prepare(g, s, f, n, err) && bench_gl_scene_draw(g, err) &&
             bench_gl_scene_read(g, fb->color, fb->depth, err) && frame_truth(s, f, n, &truth, projection, err);
        ok = ok && sr_truth_tally_add(tally, &truth, projection, fb, err);
        sr_truth_image_free(&truth);
    }
    return ok;
}

bool bench_gl_truth(sr_bench_scene *s, int lp_threads, sr_truth_errors *out, sr_error *err)
{
    bench_gl_context *ctx = NULL;
    bench_gl_scene *g = NULL;
    sr_framebuffer fb = { 0 };
    sr_truth_tally tally = { .coverage_tolerance = sr_truth_coverage_tolerance(SR_SUBPIXEL_BITS) };
    s->shade = SR_SHADE_ID;
    bool ok = sr_framebuffer_create(&fb, s->width, s->height, err) &&
              bench_gl_context_create(&ctx, lp_threads, err) && bench_gl_scene_create(&g, s, err) &&
              tally_frames(g, s, &fb, &tally, err);
    *out = sr_truth_tally_finish(&tally);
    bench_gl_scene_destroy(g);
    bench_gl_context_destroy(ctx);
    if (fb.color)
        sr_framebuffer_destroy(&fb);
    return ok;
}
