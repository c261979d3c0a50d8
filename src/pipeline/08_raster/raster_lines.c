#include <math.h>
#include <stdlib.h>

#include "pipeline/11_merge.h"
#include "raster.h"
#include "raster_lines.h"

typedef __int128 wide_int;

/* floor(n / d) for d > 0. */
static int64_t floor_div(wide_int n, wide_int d)
{
    wide_int q = n / d;
    return (int64_t)(q - (n % d != 0 && n < 0));
}

/* The depth test and the writes of one fragment; 1 if it passed. */
static inline uint64_t store(const sr_point_line_target *t, const sr_fragment *f)
{
    sr_framebuffer *fb = t->fb;
    if (t->mode == SR_RASTER_COUNT_HITS) {
        fb->color[f->at]++;
        return 1;
    }
    if (!sr_depth_passes(f->z, fb->depth[f->at], fb->reversed_z))
        return 0;
    sr_merge_fragment(fb, t->shade, f->at, f->z, fb->ids != NULL, f->id, t->mode != SR_SHADE_DEPTH,
                      f->color & 0xFFFFFFu, sr_merge_alpha_of_byte(f->color >> 24));
    return 1;
}

uint64_t sr_raster_fragments(const sr_point_line_target *t, const sr_fragment *f, size_t n)
{
    uint64_t passed = 0;
    for (size_t k = 0; k < n; k++)
        passed += store(t, &f[k]);
    return passed;
}

/* A fragment of row y stored now, or put in its band's bin. */
static inline uint64_t put(sr_point_line_target *t, int y, const sr_fragment *f)
{
    if (!t->bins)
        return store(t, f);
    sr_fragment *slot = sr_array_push(&t->bins[y / t->band_rows], sizeof *slot);
    if (slot)
        *slot = *f;
    else
        t->out_of_memory = true;
    return 0;
}

/* z moved depth_bias nearer, clamped to [0, 1]. */
static inline float biased_depth(const sr_point_line_target *t, double z)
{
    z = t->fb->reversed_z ? z + t->depth_bias : z - t->depth_bias;
    return z > 0.0 ? (z < 1.0 ? (float)z : 1.0f) : 0.0f;
}

static inline bool shades(const sr_point_line_target *t)
{
    return t->mode != SR_SHADE_DEPTH && t->mode != SR_RASTER_COUNT_HITS;
}

/* A fragment's colour, and in its top byte its alpha: its texel's, for
 * points and lines take no material's (a draw's base context has alpha_scale
 * 1), so 8 bits hold it exactly and a binned fragment stays 16 bytes. */
static inline uint32_t shaded_colour(const sr_point_line_target *t, const float *var, uint32_t id)
{
    return sr_shade_fragment(t->mode, t->shade, var, id) | sr_merge_texel_alpha(t->shade, var) << 24;
}

/* The fragment at (x, y) at parameter s of the segment a -> b. */
static uint64_t line_fragment(sr_point_line_target *t, int x, int y, const sr_screen_vertex *a,
                              const sr_screen_vertex *b, double s, uint32_t id)
{
    float z = biased_depth(t, (double)a->z + s * ((double)b->z - (double)a->z));
    if (t->filter && !t->filter->keep(t->filter->user, id, x, y, &z))
        return 0;
    sr_fragment f = { .at = (uint32_t)((size_t)y * (size_t)t->fb->width + (size_t)x), .z = z, .id = id };
    if (shades(t)) {
        float var[SR_MAX_VARYINGS];
        double inv_w = (double)a->inv_w + s * ((double)b->inv_w - (double)a->inv_w);
        for (int k = 0; k < t->shade->layout.count; k++)
            var[k] = (float)(((double)a->var_w[k] + s * ((double)b->var_w[k] - (double)a->var_w[k])) / inv_w);
        f.color = shaded_colour(t, var, id);
    }
    return put(t, y, &f);
}

/* A point's fragment, all but its pixel. */
static inline sr_fragment point_fragment(const sr_point_line_target *t, const sr_screen_vertex *p, const float *var,
                                         uint32_t id)
{
    return (sr_fragment){ .z = biased_depth(t, (double)p->z), .color = shades(t) ? shaded_colour(t, var, id) : 0,
                          .id = id };
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
static uint64_t emit(sr_point_line_target *t, const axes *ax, int64_t along, int64_t across, int width,
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
            passed += line_fragment(t, (int)px, (int)py, a, b, s, id);
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

uint64_t sr_raster_line(sr_point_line_target *t, const sr_screen_vertex *a, const sr_screen_vertex *b, int width,
                        uint32_t id)
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

uint64_t sr_raster_point(sr_point_line_target *t, const sr_screen_vertex *p, const float *var, float size,
                         uint32_t id)
{
    double one = (double)((int64_t)1 << t->subpixel_bits), h = one / 2.0, half = (double)size * h;
    /* Centres c with −half <= c − p < half, c = i·one + h: exact in double. */
    double x0 = ceil(((double)p->x - half - h) / one), x1 = ceil(((double)p->x + half - h) / one) - 1.0;
    double y0 = ceil(((double)p->y - half - h) / one), y1 = ceil(((double)p->y + half - h) / one) - 1.0;
    x0 = x0 > 0.0 ? x0 : 0.0;
    y0 = y0 > 0.0 ? y0 : 0.0;
    x1 = x1 < t->fb->width - 1 ? x1 : t->fb->width - 1;
    y1 = y1 < t->fb->height - 1 ? y1 : t->fb->height - 1;
    if (x0 > x1 || y0 > y1)
        return 0;
    sr_fragment f = point_fragment(t, p, var, id);
    uint64_t passed = 0;
    for (double y = y0; y <= y1; y++)
        for (double x = x0; x <= x1; x++) {
            f.at = (uint32_t)((size_t)y * (size_t)t->fb->width + (size_t)x);
            passed += put(t, (int)y, &f);
        }
    return passed;
}

/* Size 1: the centre c with −h <= c − p < h is i·one + h with
 * p − one <= i·one < p, so i = ⌊(p − 1) / one⌋, none left of column 0
 * for p = 0. */
uint64_t sr_raster_point_pixel(sr_point_line_target *t, const sr_screen_vertex *p, const float *var, uint32_t id)
{
    if (p->x <= 0 || p->y <= 0)
        return 0;
    int64_t x = (p->x - 1) >> t->subpixel_bits, y = (p->y - 1) >> t->subpixel_bits;
    if (x >= t->fb->width || y >= t->fb->height)
        return 0;
    sr_fragment f = point_fragment(t, p, var, id);
    f.at = (uint32_t)((size_t)y * (size_t)t->fb->width + (size_t)x);
    return put(t, (int)y, &f);
}
