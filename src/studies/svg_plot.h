/* svg_plot.h — log-log plots as SVG for the studies: a file holds one or
 * more panels side by side, each with decade grid lines, labelled axes and
 * series of points, joined or not, solid or dashed. */
#ifndef SOFTRAST_STUDIES_SVG_PLOT_H
#define SOFTRAST_STUDIES_SVG_PLOT_H

#include <stdbool.h>
#include <stdio.h>

#include "doc_file.h"
#include "softrast_private.h"

/* A panel: its rectangle in the file and the decades it shows (log10 of
 * the lowest and highest value on each axis). */
typedef struct sr_svg_panel {
    sr_doc *file;
    double left, top, width, height;
    double x_lo, x_hi, y_lo, y_hi;
} sr_svg_panel;

typedef struct sr_svg_series {
    const double *x, *y;
    int count;
    const char *color;
    bool dashed, joined, dots;
} sr_svg_series;

bool sr_svg_begin(sr_doc *file, const char *path, int width, int height, const char *title, sr_error *err);
bool sr_svg_end(sr_doc *file, sr_error *err);

/* The panel's decades, widened to whole decades around [lo, hi] of each
 * axis, its frame, grid and tick labels (1k, 10k, 1M … for counts; unit
 * appended when given), and the axis titles. */
void sr_svg_panel_draw(sr_svg_panel *p, double x_lo, double x_hi, double y_lo, double y_hi, const char *x_title,
                       const char *y_title, const char *y_unit);

void sr_svg_series_draw(const sr_svg_panel *p, const sr_svg_series *s);

/* Row legend_row of the legend in the panel's upper left: a short line in
 * the series' colour and dash, then the text. */
void sr_svg_legend(const sr_svg_panel *p, int legend_row, const char *color, bool dashed, const char *text);

#endif
