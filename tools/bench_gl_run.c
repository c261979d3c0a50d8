/* bench_gl_run.c — one scene at one thread count through both renderers:
 * the frames, their clocks, and the check that both drew the same picture. */
#include <math.h>
#include <stdlib.h>
#include <time.h>

#include "core/clock.h"
#include "bench_gl.h"

#define WARM_UP (-1) /* frame index of the untimed first frame */

typedef struct clock_mark {
    double wall, cpu;
} clock_mark;

/* One renderer's timed frames. */
typedef struct frame_clock {
    double *ms;      /* per timed frame */
    double wall, cpu; /* summed over the timed frames */
} frame_clock;

typedef struct softrast_side {
    sr_framebuffer fb; /* keeps the last frame for the picture check */
    sr_workspace *ws;
    sr_stats stats; /* of the last frame */
    frame_clock clock;
} softrast_side;

typedef struct llvmpipe_side {
    bench_gl_context *ctx; /* a context per run: LP_NUM_THREADS is read when it is made */
    bench_gl_scene *scene;
    frame_clock clock;
} llvmpipe_side;

static clock_mark clock_now(void)
{
    return (clock_mark){ sr_clock_ms(CLOCK_MONOTONIC), sr_clock_ms(CLOCK_PROCESS_CPUTIME_ID) };
}

static void clock_record(frame_clock *c, int f, clock_mark start)
{
    clock_mark end = clock_now();
    if (f == WARM_UP)
        return;
    c->ms[f] = end.wall - start.wall;
    c->wall += end.wall - start.wall;
    c->cpu += end.cpu - start.cpu;
}

static void clock_summary(frame_clock *c, int n, bench_gl_timing *t)
{
    sr_median_min(c->ms, n, &t->median, &t->min);
    t->cpu_per_wall = c->wall > 0 ? c->cpu / c->wall : 0;
}

void bench_gl_frame_camera(const sr_bench_scene *s, int f, int n, mat4 view, mat4 projection)
{
    sr_camera cam;
    sr_bench_scene_camera(s, f == WARM_UP ? 0 : f, n, &cam);
    sr_camera_view(&cam, view);
    sr_camera_projection(&cam, (float)s->width / (float)s->height, projection);
}

/* A frame as `softrast bench` times it: clear color and depth, draw (the clear
 * inside the draw: sr_draw_desc.clear). */
static bool softrast_frame(softrast_side *sr, const sr_bench_scene *s, const bench_gl_run *run, int f,
                           sr_error *err)
{
    sr_draw_desc desc = { .mesh = &s->mesh, .shade = s->shade, .cull = s->cull, .threads = run->threads,
                          .workspace = sr->ws,
                          .texture = s->texture.texels ? &s->texture : NULL,
                          .study = &(sr_draw_study){ .simd = run->simd }, .clear = true };
    bench_gl_frame_camera(s, f, run->frames, desc.view, desc.projection);
    clock_mark start = clock_now();
    sr->stats = (sr_stats){ 0 };
    bool ok = sr_draw(&sr->fb, &desc, &sr->stats, err);
    clock_record(&sr->clock, f, start);
    return ok;
}

static bool llvmpipe_frame(llvmpipe_side *lp, const sr_bench_scene *s, const bench_gl_run *run, int f,
                           sr_error *err)
{
    if (!bench_gl_scene_prepare(lp->scene, s, f, run->frames, err))
        return false;
    clock_mark start = clock_now();
    bool ok = bench_gl_scene_draw(lp->scene, err);
    clock_record(&lp->clock, f, start);
    return ok;
}

static bool run_frames(softrast_side *sr, llvmpipe_side *lp, const sr_bench_scene *s, const bench_gl_run *run,
                       sr_error *err)
{
    bool ok = true;
    if (run->sequential) {
        for (int f = WARM_UP; ok && f < run->frames; f++)
            ok = softrast_frame(sr, s, run, f, err);
        for (int f = WARM_UP; ok && f < run->frames; f++)
            ok = llvmpipe_frame(lp, s, run, f, err);
        return ok;
    }
    for (int f = WARM_UP; ok && f < run->frames; f++)
        ok = softrast_frame(sr, s, run, f, err) && llvmpipe_frame(lp, s, run, f, err);
    return ok;
}

static bool sides_open(softrast_side *sr, llvmpipe_side *lp, const sr_bench_scene *s, const bench_gl_run *run,
                       sr_error *err)
{
    sr->ws = sr_workspace_create();
    sr->clock.ms = malloc((size_t)run->frames * sizeof *sr->clock.ms);
    lp->clock.ms = malloc((size_t)run->frames * sizeof *lp->clock.ms);
    if (!sr->ws || !sr->clock.ms || !lp->clock.ms)
        return sr_error_set(err, "out of memory for %d frames", run->frames);
    return sr_framebuffer_create(&sr->fb, s->width, s->height, err) &&
           bench_gl_context_create(&lp->ctx, run->lp_threads, err) && bench_gl_scene_create(&lp->scene, s, err);
}

static void sides_close(softrast_side *sr, llvmpipe_side *lp)
{
    bench_gl_scene_destroy(lp->scene);
    bench_gl_context_destroy(lp->ctx);
    free(lp->clock.ms);
    sr_framebuffer_destroy(&sr->fb);
    sr_workspace_destroy(sr->ws);
    free(sr->clock.ms);
}

static int channel_diff(uint32_t a, uint32_t b, int shift)
{
    return abs((int)((a >> shift) & 0xFF) - (int)((b >> shift) & 0xFF));
}

static bool colors_differ(uint32_t a, uint32_t b)
{
    return channel_diff(a, b, 16) > BENCH_GL_COLOR_TOLERANCE || channel_diff(a, b, 8) > BENCH_GL_COLOR_TOLERANCE ||
           channel_diff(a, b, 0) > BENCH_GL_COLOR_TOLERANCE;
}

static bench_gl_diff compare_pictures(const sr_framebuffer *fb, const uint32_t *color, const float *depth)
{
    bench_gl_diff d = { 0 };
    for (size_t i = 0; i < (size_t)fb->width * fb->height; i++) {
        bool sr_drew = fb->depth[i] < SR_DEPTH_CLEAR, gl_drew = depth[i] < SR_DEPTH_CLEAR;
        if (sr_drew != gl_drew)
            d.coverage++;
        if (!sr_drew || !gl_drew)
            continue;
        d.max_dz = fmax(d.max_dz, fabs((double)fb->depth[i] - (double)depth[i]));
        d.color += colors_differ(fb->color[i], color[i]);
    }
    return d;
}

/* llvmpipe's picture of the last frame (drawn again under the fragment
 * query) against the one softrast's framebuffer still holds. */
static bool check_pictures(softrast_side *sr, llvmpipe_side *lp, const sr_bench_scene *s, const bench_gl_run *run,
                           bench_gl_result *r, sr_error *err)
{
    size_t pixels = (size_t)s->width * s->height;
    uint32_t *color = malloc(pixels * sizeof *color);
    float *depth = malloc(pixels * sizeof *depth);
    bool ok = (color && depth) || sr_error_set(err, "out of memory for the read-back pictures");
    ok = ok && bench_gl_scene_prepare(lp->scene, s, run->frames - 1, run->frames, err) &&
         bench_gl_scene_count_fragments(lp->scene, &r->llvmpipe.fragments, err) &&
         bench_gl_scene_read(lp->scene, color, depth, err);
    if (ok) {
        r->softrast.fragments = sr->stats.fragments;
        r->diff = compare_pictures(&sr->fb, color, depth);
    }
    free(color);
    free(depth);
    return ok;
}

/* Counted after the frames: each rasterizer thread names itself once it runs. */
static bool check_raster_threads(const bench_gl_run *run, sr_error *err)
{
    int counted = bench_gl_count_raster_threads();
    return counted == run->lp_threads ||
           sr_error_set(err, "LP_NUM_THREADS=%d but llvmpipe runs %d rasterizer threads", run->lp_threads, counted);
}

bool bench_gl_compare(const sr_bench_scene *s, const bench_gl_run *run, bench_gl_result *r, sr_error *err)
{
    softrast_side sr = { 0 };
    llvmpipe_side lp = { 0 };
    *r = (bench_gl_result){ 0 };
    bool ok = sides_open(&sr, &lp, s, run, err) && run_frames(&sr, &lp, s, run, err) &&
              check_raster_threads(run, err) && check_pictures(&sr, &lp, s, run, r, err);
    if (ok) {
        clock_summary(&sr.clock, run->frames, &r->softrast);
        clock_summary(&lp.clock, run->frames, &r->llvmpipe);
    }
    sides_close(&sr, &lp);
    return ok;
}
