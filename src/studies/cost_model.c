/* The cost model of the dense scene (cost_model.h). */
#include <math.h>
#include <stdio.h>

#include "bench_scenes.h"
#include "bench_time.h"
#include "cost_model.h"
#include "doc_file.h"
#include "svg_plot.h"

#define TRIANGLE_POINTS 7
#define PIXEL_POINTS 5
#define MAX_POINTS TRIANGLE_POINTS
#define RUNS 2 /* one thread, then the threads asked for */

static const double TRIANGLE_COUNTS[TRIANGLE_POINTS] = { 1e4, 3e4, 1e5, 3e5, 1e6, 3e6, 1e7 };
static const int SIZES[PIXEL_POINTS][2] = { { 640, 360 }, { 1280, 720 }, { 1920, 1080 }, { 2560, 1440 },
                                            { 3840, 2160 } };
static const char *const RUN_COLORS[RUNS] = { "#1f77b4", "#d62728" };

typedef struct cost_point {
    double work; /* triangles assembled, or pixels */
    double ms;   /* median per frame, clear included */
    double fragments;
    sr_draw_times phases; /* means per frame */
} cost_point;

typedef struct cost_series {
    int threads, count;
    cost_point points[MAX_POINTS];
    double slope, scale; /* ms ≈ scale · work^slope, least squares in log-log */
} cost_series;

typedef struct cost_model {
    int frames, runs;
    cost_series triangles[RUNS], pixels[RUNS];
} cost_model;

static void fit(cost_series *s)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0, n = s->count;
    for (int i = 0; i < s->count; i++) {
        double x = log(s->points[i].work), y = log(s->points[i].ms);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    s->slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    s->scale = exp((sy - s->slope * sx) / n);
}

static void phases_per_frame(sr_draw_times *t, int frames)
{
    sr_phase_time *p[] = { &t->vertex, &t->primitives, &t->raster };
    for (int i = 0; i < 3; i++) {
        p[i]->wall /= frames;
        p[i]->cpu /= frames;
    }
    t->total /= frames;
}

static bool measure(const sr_bench_scene *s, int frames, int threads, double work, cost_point *p, sr_error *err)
{
    sr_bench_result r;
    *p = (cost_point){ .work = work };
    sr_bench_run run = { .frames = frames, .threads = threads, .times = &p->phases };
    if (!sr_bench_time(s, &run, NULL, &r, err))
        return false;
    p->ms = r.median;
    p->fragments = (double)r.stats.fragments;
    phases_per_frame(&p->phases, frames);
    fprintf(stderr, "cost model: %d thread%s, %dx%d, %.0f triangles: %.2f ms\n", threads, threads > 1 ? "s" : "",
            s->width, s->height, (double)(s->mesh.index_count / 3), r.median);
    return true;
}

static bool measure_triangles(cost_model *m, const int *threads, sr_error *err)
{
    for (int i = 0; i < TRIANGLE_POINTS; i++) {
        sr_bench_scene s;
        if (!sr_bench_dense(&s, (uint64_t)TRIANGLE_COUNTS[i], 1920, 1080, SR_SHADE_LAMBERT, err))
            return false;
        bool ok = true;
        for (int k = 0; ok && k < m->runs; k++)
            ok = measure(&s, m->frames, threads[k], (double)(s.mesh.index_count / 3),
                         &m->triangles[k].points[m->triangles[k].count++], err);
        sr_bench_scene_free(&s);
        if (!ok)
            return false;
    }
    return true;
}

static bool measure_pixels(cost_model *m, const int *threads, sr_error *err)
{
    sr_bench_scene s;
    if (!sr_bench_dense(&s, SR_BENCH_DENSE_TRIANGLES, 1920, 1080, SR_SHADE_LAMBERT, err))
        return false;
    bool ok = true;
    for (int i = 0; ok && i < PIXEL_POINTS; i++) {
        s.width = SIZES[i][0];
        s.height = SIZES[i][1];
        for (int k = 0; ok && k < m->runs; k++)
            ok = measure(&s, m->frames, threads[k], (double)s.width * s.height,
                         &m->pixels[k].points[m->pixels[k].count++], err);
    }
    sr_bench_scene_free(&s);
    return ok;
}

static void write_series_table(FILE *f, const cost_series *s, const char *work_name)
{
    fprintf(f, "\n| %s | threads | ms | fragments | vertex wall / cpu | primitives wall / cpu | raster wall / cpu |\n"
               "| ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n", work_name);
    for (int i = 0; i < s->count; i++) {
        const cost_point *p = &s->points[i];
        fprintf(f, "| %.0f | %d | %.2f | %.0f | %.2f / %.2f | %.2f / %.2f | %.2f / %.2f |\n", p->work, s->threads,
                p->ms, p->fragments, p->phases.vertex.wall, p->phases.vertex.cpu, p->phases.primitives.wall,
                p->phases.primitives.cpu, p->phases.raster.wall, p->phases.raster.cpu);
    }
}

/* The marginal cost between the two largest points: what one more unit of
 * work costs once the fixed costs are paid. */
static double marginal(const cost_series *s)
{
    const cost_point *a = &s->points[s->count - 2], *b = &s->points[s->count - 1];
    return (b->ms - a->ms) / (b->work - a->work);
}

static bool write_markdown(const char *path, const cost_model *m, sr_error *err)
{
    sr_doc doc;
    if (!sr_doc_open(&doc, path, err))
        return false;
    FILE *f = doc.f;
    fprintf(f, "# Cost model of the dense scene\n\n"
               "Written by `./build/softrast bench --cost-model --frames %d` (src/studies/cost_model.c); read it\n"
               "with docs/performance.md. The closed torus of the dense scene, lambert, back faces culled: time\n"
               "per frame (median, clear included) against its triangles at 1920x1080, and against the\n"
               "framebuffer's pixels at 1M triangles. Phases: mean ms per frame, wall / CPU summed over\n"
               "threads (sr_draw_times). The plot: [cost-model.svg](cost-model.svg).\n\n"
               "| series | threads | slope (ms ~ work^slope) | marginal cost |\n| --- | ---: | ---: | ---: |\n",
            m->frames);
    for (int k = 0; k < m->runs; k++) {
        fprintf(f, "| triangles | %d | %.2f | %.1f ns per triangle |\n", m->triangles[k].threads,
                m->triangles[k].slope, 1e6 * marginal(&m->triangles[k]));
        fprintf(f, "| pixels | %d | %.2f | %.2f ns per pixel |\n", m->pixels[k].threads, m->pixels[k].slope,
                1e6 * marginal(&m->pixels[k]));
    }
    fprintf(f, "\n## Against triangles (1920x1080)\n");
    for (int k = 0; k < m->runs; k++)
        write_series_table(f, &m->triangles[k], "triangles");
    fprintf(f, "\n## Against pixels (1M triangles)\n");
    for (int k = 0; k < m->runs; k++)
        write_series_table(f, &m->pixels[k], "pixels");
    return sr_doc_close(&doc, err);
}

static void series_range(const cost_series *s, int runs, double r[4])
{
    r[0] = r[2] = INFINITY;
    r[1] = r[3] = 0.0;
    for (int k = 0; k < runs; k++)
        for (int i = 0; i < s[k].count; i++) {
            r[0] = fmin(r[0], s[k].points[i].work);
            r[1] = fmax(r[1], s[k].points[i].work);
            r[2] = fmin(r[2], s[k].points[i].ms);
            r[3] = fmax(r[3], s[k].points[i].ms);
        }
}

static void plot_panel(sr_svg_panel *p, const cost_series *s, int runs, const char *x_title)
{
    double r[4];
    series_range(s, runs, r);
    sr_svg_panel_draw(p, r[0], r[1], r[2], r[3], x_title, "ms per frame (log)", "ms");
    for (int k = 0; k < runs; k++) {
        double x[MAX_POINTS], y[MAX_POINTS], fitted[MAX_POINTS];
        for (int i = 0; i < s[k].count; i++) {
            x[i] = s[k].points[i].work;
            y[i] = s[k].points[i].ms;
            fitted[i] = s[k].scale * pow(x[i], s[k].slope);
        }
        sr_svg_series_draw(p, &(sr_svg_series){ x, y, s[k].count, RUN_COLORS[k], .joined = true, .dots = true });
        sr_svg_series_draw(p, &(sr_svg_series){ x, fitted, s[k].count, RUN_COLORS[k], .dashed = true,
                                                .joined = true });
        char text[96];
        snprintf(text, sizeof text, "%d thread%s: slope %.2f (dashed: the fit)", s[k].threads,
                 s[k].threads > 1 ? "s" : "", s[k].slope);
        sr_svg_legend(p, k, RUN_COLORS[k], false, text);
    }
}

static bool write_svg(const char *path, const cost_model *m, sr_error *err)
{
    sr_doc file;
    char title[160];
    snprintf(title, sizeof title, "softrast: the dense torus's time per frame, log-log "
             "(./build/softrast bench --cost-model --frames %d)", m->frames);
    if (!sr_svg_begin(&file, path, 1100, 500, title, err))
        return false;
    sr_svg_panel left = { .file = &file, .left = 90, .top = 50, .width = 420, .height = 370 };
    sr_svg_panel right = { .file = &file, .left = 640, .top = 50, .width = 420, .height = 370 };
    plot_panel(&left, m->triangles, m->runs, "triangles at 1920x1080 (log)");
    plot_panel(&right, m->pixels, m->runs, "pixels at 1M triangles (log)");
    return sr_svg_end(&file, err);
}

bool sr_cost_model_write(const char *dir, int frames, int threads, sr_error *err)
{
    int thread_counts[RUNS] = { 1, threads };
    cost_model m = { .frames = frames, .runs = threads > 1 ? 2 : 1 };
    for (int k = 0; k < m.runs; k++)
        m.triangles[k].threads = m.pixels[k].threads = thread_counts[k];
    if (!measure_triangles(&m, thread_counts, err) || !measure_pixels(&m, thread_counts, err))
        return false;
    for (int k = 0; k < m.runs; k++) {
        fit(&m.triangles[k]);
        fit(&m.pixels[k]);
    }
    char md[1024], svg[1024];
    snprintf(md, sizeof md, "%s/cost-model.md", dir);
    snprintf(svg, sizeof svg, "%s/cost-model.svg", dir);
    return write_markdown(md, &m, err) && write_svg(svg, &m, err);
}
