/* Log-log SVG plots for the studies (svg_plot.h). */
#include <math.h>

#include "svg_plot.h"

#define DASH " stroke-dasharray='7 4'"

bool sr_svg_begin(sr_doc *file, const char *path, int width, int height, const char *title, sr_error *err)
{
    if (!sr_doc_open(file, path, err))
        return false;
    fprintf(file->f, "<svg xmlns='http://www.w3.org/2000/svg' width='%d' height='%d' font-family='sans-serif'>\n",
            width, height);
    fprintf(file->f, "<rect width='100%%' height='100%%' fill='white'/>\n");
    fprintf(file->f, "<text x='%d' y='22' font-size='14' text-anchor='middle'>%s</text>\n", width / 2, title);
    return true;
}

bool sr_svg_end(sr_doc *file, sr_error *err)
{
    fprintf(file->f, "</svg>\n");
    return sr_doc_close(file, err);
}

static double panel_x(const sr_svg_panel *p, double v)
{
    return p->left + p->width * (log10(v) - p->x_lo) / (p->x_hi - p->x_lo);
}

static double panel_y(const sr_svg_panel *p, double v)
{
    return p->top + p->height * (1.0 - (log10(v) - p->y_lo) / (p->y_hi - p->y_lo));
}

/* 10^d as a count: 1, 10, 100, 1k … 100k, 1M … */
static void decade_label(int d, const char *unit, char *out, size_t size)
{
    static const char *const SUFFIX[] = { "", "k", "M", "G" };
    if (d >= 0 && d < 12)
        snprintf(out, size, "%g%s%s%s", pow(10.0, d % 3), SUFFIX[d / 3], unit ? " " : "", unit ? unit : "");
    else
        snprintf(out, size, "1e%d%s%s", d, unit ? " " : "", unit ? unit : "");
}

void sr_svg_panel_draw(sr_svg_panel *p, double x_lo, double x_hi, double y_lo, double y_hi, const char *x_title,
                       const char *y_title, const char *y_unit)
{
    FILE *f = p->file->f;
    p->x_lo = floor(log10(x_lo));
    p->x_hi = fmax(ceil(log10(x_hi)), p->x_lo + 1.0);
    p->y_lo = floor(log10(y_lo));
    p->y_hi = fmax(ceil(log10(y_hi)), p->y_lo + 1.0);
    char label[32];
    for (int d = (int)p->x_lo; d <= (int)p->x_hi; d++) {
        double x = panel_x(p, pow(10.0, d));
        decade_label(d, NULL, label, sizeof label);
        fprintf(f, "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='#ddd'/>\n", x, p->top, x, p->top + p->height);
        fprintf(f, "<text x='%.1f' y='%.1f' font-size='11' text-anchor='middle'>%s</text>\n", x,
                p->top + p->height + 16, label);
    }
    for (int d = (int)p->y_lo; d <= (int)p->y_hi; d++) {
        double y = panel_y(p, pow(10.0, d));
        decade_label(d, y_unit, label, sizeof label);
        fprintf(f, "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='#ddd'/>\n", p->left, y, p->left + p->width, y);
        fprintf(f, "<text x='%.1f' y='%.1f' font-size='11' text-anchor='end'>%s</text>\n", p->left - 6, y + 4, label);
    }
    fprintf(f, "<rect x='%.1f' y='%.1f' width='%.1f' height='%.1f' fill='none' stroke='black'/>\n", p->left, p->top,
            p->width, p->height);
    fprintf(f, "<text x='%.1f' y='%.1f' font-size='13' text-anchor='middle'>%s</text>\n", p->left + p->width / 2,
            p->top + p->height + 38, x_title);
    double ty = p->top + p->height / 2, tx = p->left - 58;
    fprintf(f, "<text x='%.1f' y='%.1f' font-size='13' transform='rotate(-90 %.1f %.1f)' text-anchor='middle'>%s"
               "</text>\n", tx, ty, tx, ty, y_title);
}

void sr_svg_series_draw(const sr_svg_panel *p, const sr_svg_series *s)
{
    FILE *f = p->file->f;
    if (s->joined) {
        fprintf(f, "<polyline fill='none' stroke='%s' stroke-width='1.5'%s points='", s->color, s->dashed ? DASH : "");
        for (int i = 0; i < s->count; i++)
            fprintf(f, "%.1f,%.1f ", panel_x(p, s->x[i]), panel_y(p, s->y[i]));
        fprintf(f, "'/>\n");
    }
    for (int i = 0; s->dots && i < s->count; i++)
        fprintf(f, "<circle cx='%.1f' cy='%.1f' r='3.5' fill='%s'/>\n", panel_x(p, s->x[i]), panel_y(p, s->y[i]),
                s->color);
}

void sr_svg_legend(const sr_svg_panel *p, int legend_row, const char *color, bool dashed, const char *text)
{
    double x = p->left + 14, y = p->top + 20 + 18 * legend_row;
    fprintf(p->file->f, "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='%s' stroke-width='2'%s/>\n", x, y - 4,
            x + 26, y - 4, color, dashed ? DASH : "");
    fprintf(p->file->f, "<text x='%.1f' y='%.1f' font-size='12' fill='%s'>%s</text>\n", x + 32, y, color, text);
}
