#include <math.h>
#include <stdlib.h>

#include "raster.h"
#include "raster_lines.h"

typedef __int128 wide_int;

/* floor(n / d) for d > 0. */
static int64_t floor_div(wide_int n, wide_int d)
{
    wide_int q = n / d;
    return (int64_t)(q - (n % d != 0 && n < 0));
}

/* The depth, varyings and shading of one fragment at parameter t of the
 * segment a -> b (a point: a = b, t = 0); 1 if it passed the depth test. */
static uint64_t fragment(const sr_point_line_target *t, int x, int y, const sr_screen_vertex *a,
                         const sr_screen_vertex *b, double s, uint32_t id)
{
    sr_framebuffer *fb = t->fb;
    size_t at = (size_t)y * (size_t)fb->width + (size_t)x;
    if (t->mode == SR_RASTER_COUNT_HITS) {
        fb->color[at]++;
        return 1;
    }
    double z = (double)a->z + s * ((double)b->z - (double)a->z);
    z = fb->reversed_z ? z + t->depth_bias : z - t->depth_bias;
    float zf = z > 0.0 ? (z < 1.0 ? (float)z : 1.0f) : 0.0f;
    if (!sr_depth_passes(zf, fb->depth[at], fb->reversed_z))
        return 0;
    fb->depth[at] = zf;
    if (fb->ids)
        fb->ids[at] = id + 1u;
    if (t->mode == SR_SHADE_DEPTH)
        return 1;
    float var[SR_MAX_VARYINGS];
    double inv_w = (double)a->inv_w + s * ((double)b->inv_w - (double)a->inv_w);
    for (int k = 0; k < t->shade->layout.count; k++)
        var[k] = (float)(((double)a->var_w[k] + s * ((double)b->var_w[k] - (double)a->var_w[k])) / inv_w);
    fb->color[at] = sr_shade_fragment(t->mode, t->shade, var, id);
    return 1;
}

static bool on_screen(const sr_framebuffer *fb, int64_t x, int64_t y)
{
    return x >= 0 && y >= 0 && x < fb->width && y < fb->height;
}

/* Whether (px, py) lies in pixel (i, j)'s diamond (raster_lines.h). */
static bool in_diamond(int64_t px, int64_t py, int64_t i, int64_t j, int64_t one, bool y_major)
{
    int64_t h = one / 2, u = px - (i * one + h), v = py - (j * one + h);
    int64_t f = llabs(u) + llabs(v);
    return f < h || (f == h && (v > 0 || (y_major && v == 0 && u == h)));
}

/* A segment in the frame of its major axis: `along` the major coordinate,
 * `across` the minor one, so one loop serves x- and y-major lines. */
typedef struct axes {
    int64_t a0, c0, a1, c1; /* major and minor coordinates of the two ends */
    bool y_major;
} axes;

static void pixel_of(const axes *ax, int64_t along, int64_t across, int64_t *x, int64_t *y)
{
    *x = ax->y_major ? across : along;
    *y = ax->y_major ? along : across;
}

/* The fragments of pixel (along, across) and its copies across a wide line. */
static uint64_t emit(const sr_point_line_target *t, const axes *ax, int64_t along, int64_t across, int width,
                     const sr_screen_vertex *a, const sr_screen_vertex *b, uint32_t id)
{
    int64_t one = (int64_t)1 << t->subpixel_bits, h = one / 2, x, y;
    pixel_of(ax, along, across, &x, &y);
    /* The centre's projection on the segment, in the snapped coordinates. */
    double dx = (double)(b->x - a->x), dy = (double)(b->y - a->y);
    double cx = (double)(x * one + h - a->x), cy = (double)(y * one + h - a->y);
    double s = (cx * dx + cy * dy) / (dx * dx + dy * dy);
    s = s > 0.0 ? (s < 1.0 ? s : 1.0) : 0.0;
    uint64_t passed = 0;
    int64_t first = -(int64_t)((width - 1) / 2);
    for (int64_t k = first; k < first + width; k++) {
        int64_t px, py;
        pixel_of(ax, along, across + k, &px, &py);
        if (on_screen(t->fb, px, py))
            passed += fragment(t, (int)px, (int)py, a, b, s, id);
    }
    return passed;
}

/* The pixel of the major-axis column `along` whose diamond the segment
 * crosses on the column's centre line: the minor coordinate there lies in
 * (j·one, (j + 1)·one]. */
static int64_t crossing_pixel(const axes *ax, int64_t along, int64_t one)
{
    int64_t centre = along * one + one / 2;
    wide_int d = (wide_int)ax->a1 - ax->a0, n = (wide_int)ax->c0 * d + ((wide_int)centre - ax->a0) * (ax->c1 - ax->c0);
    if (d < 0) {
        d = -d;
        n = -n;
    }
    return floor_div(n - 1, d * one);
}

uint64_t sr_raster_line(const sr_point_line_target *t, const sr_screen_vertex *a, const sr_screen_vertex *b,
                        int width, uint32_t id)
{
    int64_t dx = b->x - a->x, dy = b->y - a->y;
    if (dx == 0 && dy == 0)
        return 0;
    bool y_major = llabs(dy) > llabs(dx);
    axes ax = y_major ? (axes){ a->y, a->x, b->y, b->x, true } : (axes){ a->x, a->y, b->x, b->y, false };
    int64_t one = (int64_t)1 << t->subpixel_bits, h = one / 2;
    int64_t lo = ax.a0 < ax.a1 ? ax.a0 : ax.a1, hi = ax.a0 < ax.a1 ? ax.a1 : ax.a0;
    int64_t side = y_major ? t->fb->height : t->fb->width;
    /* Columns whose centre line the segment reaches: centre in [lo, hi]. */
    int64_t first = floor_div((wide_int)lo - h + one - 1, one), last = floor_div((wide_int)hi - h, one);
    first = first > 0 ? first : 0;
    last = last < side - 1 ? last : side - 1;
    uint64_t passed = 0;
    for (int64_t along = first; along <= last; along++) {
        int64_t across = crossing_pixel(&ax, along, one), x, y;
        pixel_of(&ax, along, across, &x, &y);
        if (!in_diamond(b->x, b->y, x, y, one, y_major))
            passed += emit(t, &ax, along, across, width, a, b, id);
    }
    /* The start's own diamond, left before the segment reaches its centre
     * line: its pixel, or the one left of or above it (whose right or
     * bottom corner the start may sit on). */
    for (int64_t dj = -1; dj <= 0; dj++)
        for (int64_t di = -1; di <= 0; di++) {
            int64_t i = floor_div(a->x, one) + di, j = floor_div(a->y, one) + dj;
            int64_t along = y_major ? j : i, centre = along * one + h;
            if ((centre < lo || centre > hi) && in_diamond(a->x, a->y, i, j, one, y_major) &&
                !in_diamond(b->x, b->y, i, j, one, y_major))
                passed += emit(t, &ax, along, y_major ? i : j, width, a, b, id);
        }
    return passed;
}

uint64_t sr_raster_point(const sr_point_line_target *t, const sr_screen_vertex *p, float size, uint32_t id)
{
    double one = (double)((int64_t)1 << t->subpixel_bits), h = one / 2.0, half = (double)size * h;
    /* Centres c with −half <= c − p < half, c = i·one + h: exact in double. */
    double x0 = ceil(((double)p->x - half - h) / one), x1 = ceil(((double)p->x + half - h) / one) - 1.0;
    double y0 = ceil(((double)p->y - half - h) / one), y1 = ceil(((double)p->y + half - h) / one) - 1.0;
    x0 = x0 > 0.0 ? x0 : 0.0;
    y0 = y0 > 0.0 ? y0 : 0.0;
    x1 = x1 < t->fb->width - 1 ? x1 : t->fb->width - 1;
    y1 = y1 < t->fb->height - 1 ? y1 : t->fb->height - 1;
    uint64_t passed = 0;
    for (double y = y0; y <= y1; y++)
        for (double x = x0; x <= x1; x++)
            passed += fragment(t, (int)x, (int)y, p, p, 0.0, id);
    return passed;
}
