/* softrast bench — the benchmark scenes, timed as a viewer pays for a frame. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app.h"
#include "studies/bench_scenes.h"
#include "studies/bench_time.h"
#include "studies/cost_model.h"
#include "options.h"
#include "studies/report.h"
#include "scene_setup.h"
#include "studies/stability.h"

#define MAX_FRAMES 10000

static const char *const SCENE_NAMES[] = { "all",   "dense",  "fly",  "fill",   "fill-flat",
                                           "depth", "inside", "scan", "points", NULL };
enum { SCENE_ALL, SCENE_DENSE, SCENE_FLY, SCENE_FILL, SCENE_FILL_FLAT, SCENE_DEPTH, SCENE_INSIDE, SCENE_SCAN,
       SCENE_POINTS };

typedef struct bench_job {
    int scene, frames, threads, simd, shade; /* shade: -1 for each scene's own */
    bool report, stability, cost_model, stages;
    const char *report_dir;
} bench_job;

typedef sr_bench_result bench_result;

static const char USAGE[] =
    "usage: softrast bench [options]\n"
    "Times the benchmark scenes: median and minimum ms per frame over --frames frames\n"
    "(after one untimed warm-up), a frame being clear + draw, as in the viewer. The fly\n"
    "scene reads assets/room.obj from the program's data (docs/cli.md, \"Data files\").";

static bool parse_job(bench_job *job, int argc, char **argv, bool *help, sr_error *err)
{
    const sr_option table[] = {
        { "--scene", SR_OPT_CHOICE, &job->scene, "all|dense|fly|fill|fill-flat|depth|inside|scan|points", "which scenes (default all)", .choices = SCENE_NAMES },
        { "--frames", SR_OPT_INT, &job->frames, "N", "timed frames per scene (default 10)", 1, MAX_FRAMES },
        { "--threads", SR_OPT_INT, &job->threads, "N", "threads in all (default: all cores)", 1, SR_MAX_THREAD_OPTION },
        { "--simd", SR_OPT_CHOICE, &job->simd, SR_SIMD_CHOICES, SR_SIMD_HELP, .choices = sr_simd_names },
        { "--shade", SR_OPT_CHOICE, &job->shade, "lambert|id|color|normal|texture|depth", "draw every scene in this shading mode instead of its own (a scene without what the mode reads is skipped)", .choices = SR_SHADE_NAMES },
        { "--stages", SR_OPT_FLAG, &job->stages, NULL, "print where a frame's time goes, per phase of the draw, as a Markdown table (docs/performance.md)" },
        { "--report", SR_OPT_FLAG, &job->report, NULL, "measure error against time for every accuracy knob instead" },
        { "--stability", SR_OPT_FLAG, &job->stability, NULL, "measure clipping error, cracks and depth precision under stiff cameras instead (docs/stability.md)" },
        { "--cost-model", SR_OPT_FLAG, &job->cost_model, NULL, "time the dense torus against 10k … 10M triangles and 640x360 … 3840x2160 pixels, at 1 thread and at --threads, instead (docs/cost-model.md)" },
        { "--report-dir", SR_OPT_STRING, &job->report_dir, "DIR", "where --report, --stability and --cost-model write their .md and .svg (default docs)" },
        { 0 },
    };
    int positional = 0;
    return sr_options_parse(table, USAGE, argc, argv, 2, NULL, 0, &positional, help, err);
}

static void print_header(const bench_job *job)
{
    if (job->stages) {
        printf("| scene | threads | frame | clear | vertex wall / cpu | primitives wall / cpu | raster wall / cpu "
               "| serial rest |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
        return;
    }
    printf("%-17s %10s %11s %10s %10s %10s %12s %8s\n", "scene", "triangles", "size", "ms median", "ms min",
           "Mtri/s", "Mfragment/s", "Gpix/s");
}

static void print_row(const char *name, const sr_bench_scene *s, const bench_result *r)
{
    char size[32];
    snprintf(size, sizeof size, "%dx%d", s->width, s->height);
    /* Gpix/s: fragments that passed the depth test, each shaded and written,
     * per second at the median frame. */
    double mfragments = r->stats.fragments / r->median / 1e3;
    printf("%-17s %10llu %11s %10.2f %10.2f %10.2f %12.1f %8.3f\n", name, (unsigned long long)r->stats.triangles,
           size, r->median, r->min, r->stats.triangles / r->median / 1e3, mfragments, mfragments / 1e3);
    fflush(stdout);
}

/* Mean ms per frame of each phase (sr_draw_times), wall / CPU summed over
 * threads; the clear is the frame's time outside the draw, the serial rest
 * the draw's outside its phases. */
static void print_stages(const char *name, const bench_job *job, const bench_result *r, const sr_draw_times *t)
{
    double n = job->frames, draw = t->total / n;
    const sr_phase_time *phases[] = { &t->vertex, &t->primitives, &t->raster };
    printf("| %s | %d | %.2f | %.2f |", name, job->threads, r->mean, r->mean - draw);
    double walls = 0.0;
    for (int i = 0; i < 3; i++) {
        printf(" %.2f / %.2f |", phases[i]->wall / n, phases[i]->cpu / n);
        walls += phases[i]->wall / n;
    }
    printf(" %.2f |\n", draw - walls);
    fflush(stdout);
}

static bool run_scene(sr_bench_scene *s, bool made, const bench_job *job, bench_result *r, sr_error *err)
{
    sr_draw_times times = { 0 };
    sr_bench_run how = { .frames = job->frames, .threads = job->threads, .simd = (sr_simd)job->simd,
                         .times = job->stages ? &times : NULL };
    if (made && job->shade >= 0 && !sr_shade_supported(&s->mesh, &s->texture, (sr_shade)job->shade)) {
        printf("%-9s skipped: it lacks what --shade %s reads\n", s->name, SR_SHADE_NAMES[job->shade]);
        sr_bench_scene_free(s);
        return true;
    }
    if (made && job->shade >= 0)
        s->shade = (sr_shade)job->shade;
    bool ok = made && sr_bench_time(s, &how, NULL, r, err);
    if (ok && job->stages)
        print_stages(s->name, job, r, &times);
    else if (ok)
        print_row(s->name, s, r);
    sr_bench_scene_free(s);
    return ok;
}

static bool wants(const bench_job *job, int scene)
{
    return job->scene == SCENE_ALL || job->scene == scene;
}

static bool run(const bench_job *job, sr_error *err)
{
    sr_bench_scene s;
    bench_result r;
    print_header(job);
    if (wants(job, SCENE_DENSE) && !run_scene(&s, sr_bench_dense(&s, SR_BENCH_DENSE_TRIANGLES, 1920, 1080,
                                                                 SR_SHADE_LAMBERT, err), job, &r, err))
        return false;
    if (wants(job, SCENE_FLY) && !run_scene(&s, sr_bench_fly(&s, err), job, &r, err))
        return false;
    if (wants(job, SCENE_FILL) && !run_scene(&s, sr_bench_fill(&s, err), job, &r, err))
        return false;
    if (wants(job, SCENE_FILL_FLAT) && !run_scene(&s, sr_bench_fill_flat(&s, err), job, &r, err))
        return false;
    if (wants(job, SCENE_DEPTH) && !run_scene(&s, sr_bench_dense(&s, SR_BENCH_DENSE_TRIANGLES, 1920, 1080,
                                                                 SR_SHADE_DEPTH, err), job, &r, err))
        return false;
    if (wants(job, SCENE_INSIDE) && !run_scene(&s, sr_bench_inside(&s, err), job, &r, err))
        return false;
    for (int v = 0; v < SR_BENCH_SCAN_VIEWS; v++)
        if (wants(job, SCENE_SCAN) && !run_scene(&s, sr_bench_scan_view(&s, v, err), job, &r, err))
            return false;
    if (wants(job, SCENE_POINTS) && !run_scene(&s, sr_bench_points(&s, err), job, &r, err))
        return false;
    return true;
}

/* The folder --report, --stability and --cost-model write to, checked
 * before the seconds of measuring rather than after. */
static bool report_dir_ok(const char *dir, sr_error *err)
{
    struct stat st;
    if (stat(dir, &st) != 0 || (S_ISDIR(st.st_mode) && access(dir, W_OK) != 0))
        return sr_error_set(err, "%s: cannot write the report there: %s", dir, strerror(errno));
    if (!S_ISDIR(st.st_mode))
        return sr_error_set(err, "%s: cannot write the report there: not a directory", dir);
    return true;
}

int sr_app_bench(int argc, char **argv)
{
    bench_job job = { .frames = 10, .shade = -1 };
    sr_error err = { { 0 } };
    bool help = false;
    job.threads = sr_scene_default_threads();
    if (!parse_job(&job, argc, argv, &help, &err))
        return sr_app_fail(err.message);
    if (help)
        return 0;
    const char *dir = job.report_dir ? job.report_dir : "docs";
    if ((job.stability || job.report || job.cost_model) && !report_dir_ok(dir, &err))
        return sr_app_fail(err.message);
    bool ok = job.stability ? sr_stability_write(dir, &err)
              : job.report     ? sr_report_write(dir, job.frames, &err)
              : job.cost_model ? sr_cost_model_write(dir, job.frames, job.threads, &err)
                               : run(&job, &err);
    return ok ? 0 : sr_app_fail(err.message);
}
