/* bench_gl.h — softrast against Mesa's llvmpipe on the same benchmark scenes.
 *
 * build/bench-gl (`make bench-compare`) builds each scene with the code
 * `softrast bench` uses (src/app/bench_scenes.c), draws it with softrast and
 * with llvmpipe through an offscreen EGL context (surfaceless platform, a
 * framebuffer object, no window), with the same clip = P·V·W matrices, size
 * and thread count, and prints softrast/llvmpipe time ratios. The files:
 *
 *   bench_gl.c          options, the scene loop, the table
 *   bench_gl_run.c      both renderers on one scene: frames, clocks, picture check
 *   bench_gl_context.c  llvmpipe forced and sized by environment, EGL context
 *   bench_gl_scene.c    the scene on the GL side: buffers, shaders, frames
 *   bench_gl_truth.c    llvmpipe's ids and depths against the truth image (--truth)
 *
 * docs/bench-compare.md says what it measures and what it measured here.
 */
#ifndef SOFTRAST_TOOLS_BENCH_GL_H
#define SOFTRAST_TOOLS_BENCH_GL_H

#include <stdbool.h>
#include <stdint.h>

#include "studies/bench_scenes.h"
#include "studies/report_peer.h"
#include "studies/report_truth.h"
#include "softrast_private.h"

/* One renderer's result over the timed frames of one scene. */
typedef struct bench_gl_timing {
    double median, min;  /* ms per frame */
    double cpu_per_wall; /* process CPU time / wall time in its timed frames: cores kept busy */
    uint64_t fragments;  /* of the last frame's camera: passed the depth test */
} bench_gl_timing;

/* How the two pictures of the last frame differ. */
typedef struct bench_gl_diff {
    uint64_t coverage; /* pixels drawn by one renderer only */
    uint64_t color;    /* pixels drawn by both, a channel off by more than BENCH_GL_COLOR_TOLERANCE */
    double max_dz;     /* largest depth difference where both drew */
} bench_gl_diff;

#define BENCH_GL_COLOR_TOLERANCE 2 /* of 255: rounding, llvmpipe's 8-bit filter weights */

/* One scene at one thread count. */
typedef struct bench_gl_run {
    int frames, threads, lp_threads; /* threads in all for softrast; LP_NUM_THREADS */
    sr_simd simd;                    /* softrast's per-pixel loop */
    bool sequential;                 /* all softrast frames, then all llvmpipe frames */
} bench_gl_run;

typedef struct bench_gl_result {
    bench_gl_timing softrast, llvmpipe;
    bench_gl_diff diff;
} bench_gl_result;

/* --- bench_gl_run.c: both renderers on one scene --- */

/* Times run->frames frames of each renderer after one untimed warm-up each,
 * alternating softrast and llvmpipe frame by frame (unless sequential) so
 * that a burst of load from other processes hits both; then compares the
 * pictures of the last frame. */
bool bench_gl_compare(const sr_bench_scene *s, const bench_gl_run *run, bench_gl_result *r, sr_error *err);

/* --- bench_gl_context.c: an llvmpipe context on the calling thread --- */

typedef struct bench_gl_context bench_gl_context;

/* Forces llvmpipe with LP_NUM_THREADS = lp_threads before EGL loads the
 * driver (llvmpipe reads it once, when its screen is made), then makes a
 * surfaceless GL 4.5 core context current. False, with one line in err (and
 * nothing left to destroy), when any step fails or the renderer is not llvmpipe. */
bool bench_gl_context_create(bench_gl_context **out, int lp_threads, sr_error *err);
void bench_gl_context_destroy(bench_gl_context *c);

/* GL_RENDERER and GL_VERSION of the current context. */
const char *bench_gl_context_renderer(const bench_gl_context *c);
const char *bench_gl_context_version(const bench_gl_context *c);

/* Threads of this process named "llvmpipe-N": llvmpipe's rasterizer threads. */
int bench_gl_count_raster_threads(void);

/* False, with "WHAT: GL_ERROR_NAME" in err, if glGetError reports an error. */
bool bench_gl_check(const char *what, sr_error *err);

/* --- bench_gl_scene.c: one scene uploaded once, drawn per frame --- */

typedef struct bench_gl_scene bench_gl_scene;

/* Uploads the mesh (positions, and normals and uvs when the shading reads
 * them) and texture once, compiles the scene's shader and makes a
 * width × height framebuffer object with RGBA8 color and float32 depth. */
bool bench_gl_scene_create(bench_gl_scene **out, const sr_bench_scene *s, sr_error *err);
void bench_gl_scene_destroy(bench_gl_scene *g);

/* Sets the uniforms of frame f of n (the program, vertex array and
 * framebuffer object are bound too). Untimed: softrast's bench also makes
 * its matrices before the clock starts. */
bool bench_gl_scene_prepare(bench_gl_scene *g, const sr_bench_scene *s, int f, int n, sr_error *err);

/* One frame, the part that is timed: clear color and depth, draw, glFinish. */
bool bench_gl_scene_draw(bench_gl_scene *g, sr_error *err);

/* The prepared frame once more under a GL_SAMPLES_PASSED query. */
bool bench_gl_scene_count_fragments(bench_gl_scene *g, uint64_t *fragments, sr_error *err);

/* The framebuffer as softrast stores it: row 0 at the top, color
 * 0x00RRGGBB, depth z_ndc. color and depth hold width × height each. */
bool bench_gl_scene_read(bench_gl_scene *g, uint32_t *color, float *depth, sr_error *err);

/* View and projection of frame f of n, as `softrast bench` makes them (the
 * warm-up frame, f < 0, uses frame 0's camera). World is the identity. */
void bench_gl_frame_camera(const sr_bench_scene *s, int f, int n, mat4 view, mat4 projection);

/* --- bench_gl_truth.c: llvmpipe against the truth image --- */

/* Draws the scene's report cameras (sr_report_scene_frames) with llvmpipe in
 * id shading (s->shade becomes SR_SHADE_ID), tallies them against the truth
 * of each camera as the report tallies softrast's knobs, and times `frames`
 * more draws of each (clear, draw, glFinish): out gets the scene's name,
 * the median ms and the errors. */
bool bench_gl_truth(sr_bench_scene *s, int lp_threads, int frames, sr_report_peer_row *out, sr_error *err);

#endif
