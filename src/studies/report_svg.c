#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "report_svg.h"

#define PLOT_W 820
#define PLOT_H 520
#define MARGIN 70
#define ERROR_FLOOR 1e-7 /* "no pixel differs" is drawn on this line */

static const char *const SCENE_COLORS[SR_REPORT_SCENES] = { "#1f77b4", "#d62728", "#2ca02c" };

static void write_table(FILE *f, const sr_report_scene *s)
{
    const sr_report_point *base = &s->points[0];
    fprintf(f, "\n### %s — %s (%d camera%s)\n\n", s->name, s->what, s->frames, s->frames > 1 ? "s" : "");
    fprintf(f, "| knob | ms median | time / default | ids differing | largest depth difference |\n");
    fprintf(f, "| --- | ---: | ---: | ---: | ---: |\n");
    for (int k = 0; k < SR_REPORT_KNOBS; k++) {
        const sr_report_point *p = &s->points[k];
        fprintf(f, "| %s | %.2f | %.2f | %.4f%% | %.3g |\n", p->knob, p->ms, p->ms / base->ms, 100.0 * p->id_error,
                p->depth_error);
    }
}

static void write_truth_table(FILE *f, const sr_report_scene *s)
{
    fprintf(f, "\n### %s against the truth (%d camera%s)\n\n", s->name, s->frames, s->frames > 1 ? "s" : "");
    sr_truth_errors_write_header(f, "knob");
    for (int k = 0; k < SR_REPORT_KNOBS; k++)
        sr_truth_errors_write_row(f, s->points[k].knob, &s->points[k].truth);
}

static bool write_markdown(const char *path, const sr_report_scene *scenes, const sr_report_simd_scene *loops,
                           int frames, sr_error *err)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return sr_error_set(err, "%s: cannot write: %s", path, strerror(errno));
    fprintf(f, "# Error against run time\n\n"
               "Regenerate: `./build/softrast bench --report --frames %d` (or `make report`), from the\n"
               "project's root; it writes this file and [report.svg](report.svg).\n\n"
               "Every knob is measured against a reference render of the same frames with exact clipping,\n"
               "16 subpixel bits and reversed z. *ids differing*: the fraction of pixels whose\n"
               "triangle id (`--shade id`) differs from the reference; *largest depth difference*: in\n"
               "standard z_ndc, over pixels where both drew the same triangle. Times are medians over %d draws of each camera,\n"
               "id shading, 1920x1080, on this machine (2 cores, shared: compare ratios, not absolutes).\n",
            frames, frames);
    for (int i = 0; i < SR_REPORT_SCENES; i++)
        write_table(f, &scenes[i]);
    fprintf(f, "\n![id error against time](report.svg)\n");
    sr_report_truth_intro(f);
    for (int i = 0; i < SR_REPORT_SCENES; i++)
        write_truth_table(f, &scenes[i]);
    sr_report_simd_write(f, loops);
    return fclose(f) == 0 ? true : sr_error_set(err, "%s: cannot write: %s", path, strerror(errno));
}

typedef struct plot_range {
    double ms_lo, ms_hi, err_lo, err_hi;
} plot_range;

static double plot_x(const plot_range *r, double ms)
{
    return MARGIN + (PLOT_W - 2 * MARGIN) * (log10(ms) - log10(r->ms_lo)) / (log10(r->ms_hi) - log10(r->ms_lo));
}

static double plot_y(const plot_range *r, double error)
{
    double e = error > ERROR_FLOOR ? error : ERROR_FLOOR;
    return PLOT_H - MARGIN -
           (PLOT_H - 2 * MARGIN) * (log10(e) - log10(r->err_lo)) / (log10(r->err_hi) - log10(r->err_lo));
}

static plot_range find_range(const sr_report_scene *scenes)
{
    plot_range r = { INFINITY, 0.0, ERROR_FLOOR, 1e-2 };
    for (int i = 0; i < SR_REPORT_SCENES; i++) {
        for (int k = 0; k < SR_REPORT_KNOBS; k++) {
            const sr_report_point *p = &scenes[i].points[k];
            r.ms_lo = p->ms < r.ms_lo ? p->ms : r.ms_lo;
            r.ms_hi = p->ms > r.ms_hi ? p->ms : r.ms_hi;
            r.err_hi = p->id_error > r.err_hi ? p->id_error : r.err_hi;
        }
    }
    r.ms_lo *= 0.8;
    r.ms_hi *= 1.25;
    r.err_hi *= 2.0;
    return r;
}

static void write_axes(FILE *f, const plot_range *r)
{
    fprintf(f, "<line x1='%d' y1='%d' x2='%d' y2='%d' stroke='black'/>\n", MARGIN, PLOT_H - MARGIN,
            PLOT_W - MARGIN, PLOT_H - MARGIN);
    fprintf(f, "<line x1='%d' y1='%d' x2='%d' y2='%d' stroke='black'/>\n", MARGIN, MARGIN, MARGIN, PLOT_H - MARGIN);
    for (double e = r->err_lo; e <= r->err_hi * 1.0001; e *= 10.0)
        fprintf(f, "<text x='%d' y='%.1f' font-size='11' text-anchor='end'>%s%.0e</text>\n", MARGIN - 4,
                plot_y(r, e) + 4, e <= ERROR_FLOOR ? "&#8804;" : "", e);
    static const double steps[] = { 1.0, 2.0, 5.0 };
    for (double decade = pow(10.0, floor(log10(r->ms_lo))); decade <= r->ms_hi; decade *= 10.0)
        for (int i = 0; i < 3; i++)
            if (decade * steps[i] >= r->ms_lo && decade * steps[i] <= r->ms_hi)
                fprintf(f, "<text x='%.1f' y='%d' font-size='11' text-anchor='middle'>%g ms</text>\n",
                        plot_x(r, decade * steps[i]), PLOT_H - MARGIN + 16, decade * steps[i]);
    fprintf(f, "<text x='%d' y='%d' font-size='13' text-anchor='middle'>ms per frame (log)</text>\n", PLOT_W / 2,
            PLOT_H - 20);
    fprintf(f, "<text x='16' y='%d' font-size='13' transform='rotate(-90 16 %d)' text-anchor='middle'>"
               "fraction of pixels with a wrong id (log)</text>\n", PLOT_H / 2, PLOT_H / 2);
}

static void write_points(FILE *f, const plot_range *r, const sr_report_scene *scenes)
{
    for (int i = 0; i < SR_REPORT_SCENES; i++) {
        fprintf(f, "<text x='%d' y='%d' font-size='13' fill='%s'>%s</text>\n", PLOT_W - MARGIN - 60,
                MARGIN + 16 * i, SCENE_COLORS[i], scenes[i].name);
        for (int k = 0; k < SR_REPORT_KNOBS; k++) {
            const sr_report_point *p = &scenes[i].points[k];
            double x = plot_x(r, p->ms), y = plot_y(r, p->id_error);
            fprintf(f, "<circle cx='%.1f' cy='%.1f' r='4' fill='%s'/>\n", x, y, SCENE_COLORS[i]);
            fprintf(f, "<text x='%.1f' y='%.1f' font-size='9' fill='%s'>%.22s</text>\n", x + 6, y - 4,
                    SCENE_COLORS[i], k == 0 ? "default" : p->knob);
        }
    }
}

static bool write_svg(const char *path, const sr_report_scene *scenes, int frames, sr_error *err)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return sr_error_set(err, "%s: cannot write: %s", path, strerror(errno));
    plot_range r = find_range(scenes);
    fprintf(f, "<svg xmlns='http://www.w3.org/2000/svg' width='%d' height='%d' font-family='sans-serif'>\n", PLOT_W,
            PLOT_H);
    fprintf(f, "<rect width='100%%' height='100%%' fill='white'/>\n");
    fprintf(f, "<text x='%d' y='24' font-size='14' text-anchor='middle'>softrast: id error against time per knob "
               "(./build/softrast bench --report --frames %d)</text>\n", PLOT_W / 2, frames);
    write_axes(f, &r);
    write_points(f, &r, scenes);
    fprintf(f, "</svg>\n");
    return fclose(f) == 0 ? true : sr_error_set(err, "%s: cannot write: %s", path, strerror(errno));
}

bool sr_report_files(const char *dir, const sr_report_scene *scenes, const sr_report_simd_scene *loops, int frames,
                     sr_error *err)
{
    char md[1024], svg[1024];
    snprintf(md, sizeof md, "%s/report.md", dir);
    snprintf(svg, sizeof svg, "%s/report.svg", dir);
    return write_markdown(md, scenes, loops, frames, err) && write_svg(svg, scenes, frames, err);
}
