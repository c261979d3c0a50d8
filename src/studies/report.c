#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/clock.h"
#include "scene/frame.h"
#include "bench_scenes.h"
#include "report.h"
#include "report_peer.h"
#include "report_svg.h"

#define REFERENCE_BITS 16
#define REPORT_THREADS_MANY 2
#define MAX_PATH_FRAMES 8

/* One setting of the knobs; the first row is softrast's default. */
typedef struct knob {
    const char *name;
    int subpixel_bits;
    sr_clip_precision clip;
    float guard;
    bool reversed;
    int threads;
} knob;

static const knob KNOBS[SR_REPORT_KNOBS] = {
    { "default: 8 bits, adaptive clip, 6 planes, standard z, 1 thread, best SIMD", 8, SR_CLIP_ADAPTIVE, 0.0f, false, 1 },
    { "4 subpixel bits", 4, SR_CLIP_ADAPTIVE, 0.0f, false, 1 },
    { "12 subpixel bits", 12, SR_CLIP_ADAPTIVE, 0.0f, false, 1 },
    { "float clipping", 8, SR_CLIP_FLOAT, 0.0f, false, 1 },
    { "double clipping", 8, SR_CLIP_DOUBLE, 0.0f, false, 1 },
    { "exact clipping", 8, SR_CLIP_EXACT, 0.0f, false, 1 },
    { "guard band 2 (x, y clipped at 2w)", 8, SR_CLIP_ADAPTIVE, 2.0f, false, 1 },
    { "reversed z", 8, SR_CLIP_ADAPTIVE, 0.0f, true, 1 },
    { "2 threads", 8, SR_CLIP_ADAPTIVE, 0.0f, false, REPORT_THREADS_MANY },
};

/* Reversed z in the reference: with near 1e-6 and far 1e9 the standard
 * mapping rounds whole walls to the clear depth and loses them. */
static const knob REFERENCE = { "reference: 16 bits, exact clip, reversed z", REFERENCE_BITS, SR_CLIP_EXACT, 0.0f,
                                true, 1 };

const sr_report_scene_make sr_report_scene_makers[SR_REPORT_SCENES] = {
    sr_bench_dense_default, sr_bench_fly, sr_bench_stiff, sr_bench_scan_dragon, sr_bench_scan_close, sr_bench_scan_stiff,
};

int sr_report_scene_frames(const sr_bench_scene *s)
{
    return s->path.count ? (s->path.count < MAX_PATH_FRAMES ? s->path.count : MAX_PATH_FRAMES) : 1;
}

/* The desc of knob k's draw of frame f into fb (its size and depth convention set). */
static sr_draw_desc knob_desc(const sr_bench_scene *s, const knob *k, int f, sr_framebuffer *fb, sr_workspace *ws,
                              sr_draw_study *study)
{
    sr_camera cam;
    sr_bench_scene_camera(s, f, sr_report_scene_frames(s), &cam);
    cam.reversed_z = k->reversed;
    fb->reversed_z = k->reversed;
    *study = (sr_draw_study){ .subpixel_bits = k->subpixel_bits, .clip_precision = k->clip, .guard_band = k->guard };
    sr_draw_desc desc = { .mesh = &s->mesh, .shade = SR_SHADE_ID, .threads = k->threads, .workspace = ws,
                          .study = study };
    sr_camera_view(&cam, desc.view);
    sr_camera_projection(&cam, (float)fb->width / (float)fb->height, desc.projection);
    return desc;
}

static bool draw_ids(const sr_bench_scene *s, const knob *k, int f, sr_framebuffer *fb, sr_workspace *ws,
                     double *ms, sr_error *err)
{
    sr_draw_study study;
    sr_draw_desc desc = knob_desc(s, k, f, fb, ws, &study);
    return sr_frame_draw_timed(fb, &desc, NULL, ms, err);
}

/* The truth of frame f for the standard (0) and the reversed (1) projection. */
typedef struct frame_truth {
    sr_truth_image image[2];
    mat4 projection[2];
} frame_truth;

static bool render_truths(const sr_bench_scene *s, int f, sr_framebuffer *fb, frame_truth *out, sr_error *err)
{
    bool ok = true;
    for (int reversed = 0; ok && reversed < 2; reversed++) {
        knob k = REFERENCE;
        k.reversed = reversed;
        sr_draw_study study;
        sr_draw_desc desc = knob_desc(s, &k, f, fb, NULL, &study);
        glm_mat4_copy(desc.projection, out->projection[reversed]);
        ok = sr_truth_render(&desc, s->width, s->height, &out->image[reversed], err);
    }
    return ok;
}

static double standard_depth(const sr_framebuffer *fb, size_t i)
{
    return fb->reversed_z ? 1.0 - fb->depth[i] : fb->depth[i];
}

/* Ids that differ, and the largest depth difference (as standard z_ndc)
 * where both drew the same triangle. */
static void compare(const sr_framebuffer *ref, const sr_framebuffer *fb, uint64_t *differ, double *depth)
{
    size_t n = (size_t)fb->width * (size_t)fb->height;
    for (size_t i = 0; i < n; i++) {
        *differ += ref->color[i] != fb->color[i];
        if (ref->color[i] && ref->color[i] == fb->color[i]) {
            double diff = fabs(standard_depth(fb, i) - standard_depth(ref, i));
            *depth = diff > *depth ? diff : *depth;
        }
    }
}

/* Times `frames` draws of every scene frame with knob k; compares the last
 * draw of each frame with its reference. */
static bool measure_knob(const sr_bench_scene *s, const sr_framebuffer *refs, const frame_truth *truths,
                         const knob *k, int frames, sr_report_point *out, sr_error *err)
{
    int scene_n = sr_report_scene_frames(s), timed = scene_n * frames;
    sr_framebuffer fb;
    sr_workspace *ws = sr_workspace_create();
    double *ms = malloc((size_t)timed * sizeof *ms);
    bool ok = ws && ms && sr_framebuffer_create(&fb, s->width, s->height, err);
    uint64_t differ = 0;
    sr_truth_tally tally = { .coverage_tolerance = sr_truth_coverage_tolerance(k->subpixel_bits) };
    *out = (sr_report_point){ .knob = k->name };
    for (int f = 0; ok && f < scene_n; f++) {
        for (int r = 0; ok && r < frames; r++)
            ok = draw_ids(s, k, f, &fb, ws, &ms[f * frames + r], err);
        if (ok)
            compare(&refs[f], &fb, &differ, &out->depth_error);
        ok = ok && sr_truth_tally_add(&tally, &truths[f].image[k->reversed], truths[f].projection[k->reversed], &fb,
                                      err);
    }
    out->truth = sr_truth_tally_finish(&tally);
    if (ok) {
        double min;
        sr_median_min(ms, timed, &out->ms, &min);
        out->id_error = (double)differ / ((double)scene_n * s->width * s->height);
    }
    if (!ws || !ms)
        sr_error_set(err, "out of memory for the report");
    if (fb.color)
        sr_framebuffer_destroy(&fb);
    free(ms);
    sr_workspace_destroy(ws);
    return ok;
}

static bool measure_scene(const sr_bench_scene *s, int frames, sr_report_scene *out, sr_error *err)
{
    int n = sr_report_scene_frames(s);
    sr_framebuffer refs[MAX_PATH_FRAMES] = { 0 };
    frame_truth truths[MAX_PATH_FRAMES] = { 0 };
    bool ok = true;
    for (int f = 0; ok && f < n; f++) {
        double ms;
        ok = sr_framebuffer_create(&refs[f], s->width, s->height, err) &&
             render_truths(s, f, &refs[f], &truths[f], err) && draw_ids(s, &REFERENCE, f, &refs[f], NULL, &ms, err);
    }
    *out = (sr_report_scene){ .name = s->name, .what = s->what, .frames = n };
    for (int k = 0; ok && k < SR_REPORT_KNOBS; k++) {
        ok = measure_knob(s, refs, truths, &KNOBS[k], frames, &out->points[k], err);
        if (ok)
            fprintf(stderr, "report: %s, %s: %.2f ms, %.3g%% ids differ, |z - truth| max %.3g\n", s->name,
                    KNOBS[k].name, out->points[k].ms, 100.0 * out->points[k].id_error, out->points[k].truth.z_max);
    }
    for (int f = 0; f < n; f++) {
        sr_framebuffer_destroy(&refs[f]);
        sr_truth_image_free(&truths[f].image[0]);
        sr_truth_image_free(&truths[f].image[1]);
    }
    return ok;
}

bool sr_report_write(const char *dir, int frames, sr_error *err)
{
    sr_report_scene scenes[SR_REPORT_SCENES];
    sr_bench_scene s;
    /* The peer's file first: a bad one fails at once, not after minutes. */
    char peer_path[1024];
    snprintf(peer_path, sizeof peer_path, "%s/" SR_REPORT_PEER_FILE, dir);
    sr_report_peer peer;
    if (!sr_report_peer_read(peer_path, &peer, err))
        return false;
    for (int i = 0; i < SR_REPORT_SCENES; i++) {
        bool ok = sr_report_scene_makers[i](&s, err) && measure_scene(&s, frames, &scenes[i], err);
        sr_bench_scene_free(&s);
        if (!ok)
            return false;
    }
    sr_report_simd_scene loops[SR_REPORT_SIMD_SCENES];
    return sr_report_simd_measure(frames, loops, err) && sr_report_files(dir, scenes, loops, &peer, frames, err);
}
