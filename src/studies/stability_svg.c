/* The depth table of the stability report as a log-log plot: smallest
 * ordered separation s/d against far/near, one colour per distance, solid
 * for the standard mapping and dashed for reversed z. Cells where no
 * separation is ordered sit on a "none" row above the plot. */
#include <math.h>
#include <stdio.h>

#include "stability_svg.h"
#include "svg_plot.h"

#define PLOT_W 820
#define PLOT_H 540
#define MARGIN 80
#define NONE_ROW (MARGIN - 30) /* y of the "no separation is ordered" row */
#define LOG_LO (-8.0)          /* s/d axis: 1e-8 … */
#define LOG_HI 0.0             /* … 1 */
#define LEGEND_X (MARGIN + 20) /* the upper left stays empty: every curve starts low */
#define LEGEND_Y (MARGIN + 30)

static const char *const COLORS[SR_STABILITY_DISTANCES] = { "#1f77b4", "#2ca02c", "#ff7f0e", "#d62728" };
static const char *const DASHES[SR_STABILITY_MAPPINGS] = { "", " stroke-dasharray='7 4'" };
static const char *const MAPPING_LABELS[SR_STABILITY_MAPPINGS] = { "standard", "reversed z" };

static double plot_x(const sr_stability_depth *d, int r)
{
    double lo = log10(d->ratio[0]), hi = log10(d->ratio[SR_STABILITY_RATIOS - 1]);
    return MARGIN + (PLOT_W - 2 * MARGIN) * (log10(d->ratio[r]) - lo) / (hi - lo);
}

static double plot_y(double separation)
{
    if (isnan(separation))
        return NONE_ROW;
    double l = fmin(fmax(log10(separation), LOG_LO), LOG_HI);
    return PLOT_H - MARGIN - (PLOT_H - 2 * MARGIN) * (l - LOG_LO) / (LOG_HI - LOG_LO);
}

static void write_axes(FILE *f, const sr_stability_depth *d)
{
    fprintf(f, "<line x1='%d' y1='%d' x2='%d' y2='%d' stroke='black'/>\n", MARGIN, PLOT_H - MARGIN,
            PLOT_W - MARGIN, PLOT_H - MARGIN);
    fprintf(f, "<line x1='%d' y1='%d' x2='%d' y2='%d' stroke='black'/>\n", MARGIN, MARGIN, MARGIN, PLOT_H - MARGIN);
    for (double l = LOG_LO; l <= LOG_HI; l += 1.0) {
        fprintf(f, "<line x1='%d' y1='%.1f' x2='%d' y2='%.1f' stroke='#ddd'/>\n", MARGIN, plot_y(pow(10, l)),
                PLOT_W - MARGIN, plot_y(pow(10, l)));
        fprintf(f, "<text x='%d' y='%.1f' font-size='11' text-anchor='end'>1e%d</text>\n", MARGIN - 6,
                plot_y(pow(10, l)) + 4, (int)l);
    }
    fprintf(f, "<text x='%d' y='%d' font-size='11' text-anchor='end'>none</text>\n", MARGIN - 6, NONE_ROW + 4);
    fprintf(f, "<text x='%d' y='%d' font-size='10' fill='#555'>(not ordered even at s = d)</text>\n", MARGIN + 4,
            NONE_ROW - 8);
    for (int r = 0; r < SR_STABILITY_RATIOS; r++)
        fprintf(f, "<text x='%.1f' y='%d' font-size='11' text-anchor='middle'>1e%d</text>\n", plot_x(d, r),
                PLOT_H - MARGIN + 16, (int)lround(log10(d->ratio[r])));
    fprintf(f, "<text x='%d' y='%d' font-size='13' text-anchor='middle'>far / near (log)</text>\n", PLOT_W / 2,
            PLOT_H - MARGIN + 40);
    fprintf(f, "<text x='18' y='%d' font-size='13' transform='rotate(-90 18 %d)' text-anchor='middle'>"
               "smallest plane separation the depth test orders, s / d (log)</text>\n", PLOT_H / 2, PLOT_H / 2);
}

static void write_series(FILE *f, const sr_stability_depth *d, int k, int m)
{
    fprintf(f, "<polyline fill='none' stroke='%s' stroke-width='2'%s points='", COLORS[k], DASHES[m]);
    for (int r = 0; r < SR_STABILITY_RATIOS; r++)
        fprintf(f, "%.1f,%.1f ", plot_x(d, r), plot_y(d->separation[r][k][m]));
    fprintf(f, "'/>\n");
    for (int r = 0; r < SR_STABILITY_RATIOS; r++)
        fprintf(f, "<circle cx='%.1f' cy='%.1f' r='3' fill='%s'/>\n", plot_x(d, r), plot_y(d->separation[r][k][m]),
                COLORS[k]);
}

static void write_legend(FILE *f, const sr_stability_depth *d)
{
    int y = LEGEND_Y;
    for (int k = 0; k < SR_STABILITY_DISTANCES; k++, y += 20)
        fprintf(f, "<text x='%d' y='%d' font-size='12' fill='%s'>d at %g%% of near → far</text>\n", LEGEND_X, y,
                COLORS[k], 100.0 * d->fraction[k]);
    for (int m = 0; m < SR_STABILITY_MAPPINGS; m++, y += 20) {
        fprintf(f, "<line x1='%d' y1='%d' x2='%d' y2='%d' stroke='black' stroke-width='2'%s/>\n", LEGEND_X, y - 4,
                LEGEND_X + 30, y - 4, DASHES[m]);
        fprintf(f, "<text x='%d' y='%d' font-size='12'>%s</text>\n", LEGEND_X + 36, y, MAPPING_LABELS[m]);
    }
}

bool sr_stability_svg(const char *path, const sr_stability_depth *d, sr_error *err)
{
    sr_doc file;
    if (!sr_svg_begin(&file, path, PLOT_W, PLOT_H, "softrast: depth resolution, standard against reversed z "
                      "(./build/softrast bench --stability)", err))
        return false;
    FILE *f = file.f;
    write_axes(f, d);
    for (int m = 0; m < SR_STABILITY_MAPPINGS; m++)
        for (int k = 0; k < SR_STABILITY_DISTANCES; k++)
            write_series(f, d, k, m);
    write_legend(f, d);
    return sr_svg_end(&file, err);
}
