/* bench-gl — softrast against Mesa's llvmpipe: the same scenes, matrices,
 * size and thread count; prints softrast/llvmpipe time ratios. See bench_gl.h
 * and docs/bench-compare.md. */
#include <stdio.h>
#include <stdlib.h>

#include "bench_gl.h"
#include "app/options.h"
#include "app/scene_setup.h"
#include "studies/report.h"

#define DEFAULT_FRAMES 10
#define DEFAULT_FILL_FRAMES 3 /* llvmpipe is slow on fill (docs/bench-compare.md) */
#define DEFAULT_THREADS 2
#define MAX_FRAMES 10000
#define MAX_THREADS 64
#define GL_NAME_CHARS 100 /* GL_RENDERER, GL_VERSION: llvmpipe's are 66 */

static const char *const SCENE_NAMES[] = { "all",   "dense",  "fly",  "fill",   "fill-flat",
                                           "depth", "inside", "scan", "points", NULL };
enum { SCENE_ALL, SCENE_DENSE, SCENE_FLY, SCENE_FILL, SCENE_FILL_FLAT, SCENE_DEPTH, SCENE_INSIDE, SCENE_SCAN,
       SCENE_POINTS, SCENE_KINDS };

typedef struct job {
    int scene, frames, fill_frames, threads, simd;
    bool lp_raster_all; /* LP_NUM_THREADS = threads, not threads - 1 */
    bool sequential;
    bool truth; /* llvmpipe against the truth image on the report's scenes, instead of timing */
    const char *truth_file; /* where --truth writes its rows */
} job;

/* LP_NUM_THREADS for `threads` threads in all. */
static int lp_threads(const job *j, int threads)
{
    return j->lp_raster_all ? threads : threads - 1;
}

static const char USAGE[] =
    "usage: bench-gl [options]\n"
    "Draws softrast's benchmark scenes with softrast and with Mesa's llvmpipe (offscreen EGL),\n"
    "same matrices, size and threads in all (the calling thread included), and prints\n"
    "softrast/llvmpipe time ratios. Run it from the project's root (fly reads assets/).";

static const char LEGEND[] =
    "ms: median ms per frame (clear color + depth, draw; glFinish for llvmpipe) over the timed frames,\n"
    "    after one untimed warm-up frame\n"
    "ratio: softrast ms / llvmpipe ms (above 1: softrast is slower)\n"
    "cpu: process CPU time / wall time over the timed frames (cores kept busy)\n"
    "lp: LP_NUM_THREADS = llvmpipe rasterizer threads counted in /proc (the calling thread bins)\n"
    "fragments: depth-test passes in the last frame (softrast stats / GL_SAMPLES_PASSED)\n"
    "differing px: covered by one renderer only / color off by more than %d of 255; max dz where both drew\n"
    "order: %s\n";

static void print_table_header(void)
{
    printf("  %3s %3s %10s %10s %7s %6s %6s %12s %12s %17s %9s\n", "thr", "lp", "softrast", "llvmpipe", "ratio",
           "sr cpu", "lp cpu", "sr fragments", "lp fragments", "differing px", "max dz");
}

static void print_row(const bench_gl_run *run, const bench_gl_result *r)
{
    const bench_gl_timing *sr = &r->softrast, *lp = &r->llvmpipe;
    char differing[32];
    snprintf(differing, sizeof differing, "%llu / %llu", (unsigned long long)r->diff.coverage,
             (unsigned long long)r->diff.color);
    printf("  %3d %3d %10.2f %10.2f %6.2fx %6.2f %6.2f %12llu %12llu %17s %9.2e\n", run->threads, run->lp_threads,
           sr->median, lp->median, sr->median / lp->median, sr->cpu_per_wall, lp->cpu_per_wall,
           (unsigned long long)sr->fragments, (unsigned long long)lp->fragments, differing, r->diff.max_dz);
    fflush(stdout);
}

/* The scene of a kind; the scan kind has SR_BENCH_SCAN_VIEWS views. */
static bool make_scene(int kind, int view, sr_bench_scene *s, sr_error *err)
{
    switch (kind) {
    case SCENE_SCAN:
        return sr_bench_scan_view(s, view, err);
    case SCENE_DENSE:
        return sr_bench_dense(s, SR_BENCH_DENSE_TRIANGLES, 1920, 1080, SR_SHADE_LAMBERT, err);
    case SCENE_FLY:
        return sr_bench_fly(s, err);
    case SCENE_FILL:
        return sr_bench_fill(s, err);
    case SCENE_FILL_FLAT:
        return sr_bench_fill_flat(s, err);
    case SCENE_INSIDE:
        return sr_bench_inside(s, err);
    case SCENE_POINTS:
        return sr_bench_points(s, err);
    default:
        return sr_bench_dense(s, SR_BENCH_DENSE_TRIANGLES, 1920, 1080, SR_SHADE_DEPTH, err);
    }
}

static bool run_scene(const job *j, int kind, int view, sr_error *err)
{
    sr_bench_scene s;
    if (!make_scene(kind, view, &s, err))
        return false;
    bool fill = kind == SCENE_FILL || kind == SCENE_FILL_FLAT;
    int frames = fill && j->fill_frames < j->frames ? j->fill_frames : j->frames;
    printf("\n%s: %s; %u triangle slots, %dx%d, %d timed frames%s\n", s.name, s.what,
           sr_mesh_triangle_slots(&s.mesh), s.width, s.height, frames,
           frames < j->frames ? " (capped by --fill-frames)" : "");
    print_table_header();
    const int thread_counts[] = { 1, j->threads };
    bool ok = true;
    for (int i = 0; ok && i < (j->threads > 1 ? 2 : 1); i++) {
        int t = thread_counts[i];
        bench_gl_run run = { .frames = frames, .threads = t, .lp_threads = lp_threads(j, t),
                             .sequential = j->sequential, .simd = (sr_simd)j->simd };
        bench_gl_result r;
        ok = bench_gl_compare(&s, &run, &r, err);
        if (ok)
            print_row(&run, &r);
    }
    sr_bench_scene_free(&s);
    return ok;
}

/* llvmpipe's rows of docs/report.md's "Against the truth", one per report
 * scene, printed and written to j->truth_file for the report to read. */
static bool run_truth(const job *j, const char *renderer, sr_error *err)
{
    sr_report_peer peer = { .count = SR_REPORT_SCENES };
    snprintf(peer.renderer, sizeof peer.renderer, "%.*s, %d thread%s in all (LP_NUM_THREADS %d)",
             GL_NAME_CHARS - 1, renderer,
             j->threads, j->threads > 1 ? "s" : "", lp_threads(j, j->threads));
    printf("\n");
    sr_truth_errors_write_header(stdout, "llvmpipe (ms per frame)");
    bool ok = true;
    for (int i = 0; ok && i < SR_REPORT_SCENES; i++) {
        sr_bench_scene s;
        sr_report_peer_row *r = &peer.rows[i];
        ok = sr_report_scene_makers[i](&s, err) &&
             bench_gl_truth(&s, lp_threads(j, j->threads), j->frames, r, err);
        if (ok) {
            char label[96];
            int n = sr_report_scene_frames(&s);
            snprintf(label, sizeof label, "%s (%d camera%s, %.2f ms)", s.name, n, n > 1 ? "s" : "", r->ms);
            sr_truth_errors_write_row(stdout, label, &r->truth);
        }
        sr_bench_scene_free(&s);
    }
    if (ok)
        printf("\n%s: %s\n", j->truth_file, peer.renderer);
    return ok && sr_report_peer_write(j->truth_file, &peer, err);
}

/* A first context proves llvmpipe runs here before any scene is built;
 * renderer gets its GL_RENDERER and GL_VERSION. */
static bool print_renderer(char *renderer, size_t cap, sr_error *err)
{
    bench_gl_context *ctx = NULL;
    if (!bench_gl_context_create(&ctx, 0, err))
        return false;
    printf("GL_RENDERER: %s\nGL_VERSION:  %s\n", bench_gl_context_renderer(ctx), bench_gl_context_version(ctx));
    snprintf(renderer, cap, "%s, %s", bench_gl_context_renderer(ctx), bench_gl_context_version(ctx));
    bench_gl_context_destroy(ctx);
    return true;
}

static bool parse_job(job *j, int argc, char **argv, bool *help, sr_error *err)
{
    const sr_option table[] = {
        { "--scene", SR_OPT_CHOICE, &j->scene, "all|dense|fly|fill|fill-flat|depth|inside|scan|points",
          "which scenes (default all)", .choices = SCENE_NAMES },
        { "--frames", SR_OPT_INT, &j->frames, "N", "timed frames per scene (default 10)", 1, MAX_FRAMES },
        { "--fill-frames", SR_OPT_INT, &j->fill_frames, "N",
          "at most N timed frames for fill and fill-flat (default 3)", 1, MAX_FRAMES },
        { "--threads", SR_OPT_INT, &j->threads, "N", "run at 1 and at N threads in all (default 2)", 1,
          MAX_THREADS },
        { "--lp-raster-all", SR_OPT_FLAG, &j->lp_raster_all, NULL,
          "LP_NUM_THREADS = N (N rasterizers + the calling thread), not N - 1" },
        { "--sequential", SR_OPT_FLAG, &j->sequential, NULL,
          "all softrast frames, then all llvmpipe frames (default: alternate frame by frame)" },
        { "--truth", SR_OPT_FLAG, &j->truth, NULL,
          "instead of the comparison: llvmpipe's errors against the truth image and its ms on the report's "
          "scenes, at --threads threads in all" },
        { "--truth-file", SR_OPT_STRING, &j->truth_file, "FILE",
          "where --truth writes its rows for the report (default docs/" SR_REPORT_PEER_FILE ")" },
        { "--simd", SR_OPT_CHOICE, &j->simd, SR_SIMD_CHOICES,
          "softrast's per-pixel loop (default auto: the best the CPU has)", .choices = sr_simd_names },
        { 0 },
    };
    int positional = 0;
    return sr_options_parse(table, USAGE, argc, argv, 1, NULL, 0, &positional, help, err);
}

static bool run(const job *j, sr_error *err)
{
    char renderer[GL_NAME_CHARS];
    if (!print_renderer(renderer, sizeof renderer, err))
        return false;
    if (j->truth)
        return run_truth(j, renderer, err);
    printf("softrast per-pixel loop: %s\n", sr_simd_name(sr_raster_simd_resolve((sr_simd)j->simd)));
    printf(LEGEND, BENCH_GL_COLOR_TOLERANCE,
           j->sequential ? "all softrast frames, then all llvmpipe frames (--sequential)"
                         : "softrast and llvmpipe frames alternate, so a burst of load hits both");
    for (int kind = SCENE_DENSE; kind < SCENE_KINDS; kind++)
        for (int view = 0; view < (kind == SCENE_SCAN ? SR_BENCH_SCAN_VIEWS : 1); view++)
            if ((j->scene == SCENE_ALL || j->scene == kind) && !run_scene(j, kind, view, err))
                return false;
    return true;
}

int main(int argc, char **argv)
{
    job j = { .frames = DEFAULT_FRAMES, .fill_frames = DEFAULT_FILL_FRAMES, .threads = DEFAULT_THREADS,
              .truth_file = "docs/" SR_REPORT_PEER_FILE };
    sr_error err = { { 0 } };
    bool help = false;
    if (!parse_job(&j, argc, argv, &help, &err) || (!help && !run(&j, &err))) {
        fprintf(stderr, "bench-gl: error: %s\n", err.message);
        return 1;
    }
    return 0;
}
