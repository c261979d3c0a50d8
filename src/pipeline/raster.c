#include <string.h>

#include "softrast/raster.h"


/* E(P) = a·Px + b·Py + c, the edge function of a → b in subpixel units: >= 0
 * on the inside of a clockwise (area2 > 0) triangle. `bias` is 0 on a top or
 * left edge and 1 otherwise, so E >= bias decides coverage with the
 * top-left rule in exact integers. */
typedef struct edge {
    int64_t a, b, c, bias;
} edge;

static edge edge_make(const sr_screen_vertex *p, const sr_screen_vertex *q)
{
    int64_t dx = q->x - p->x, dy = q->y - p->y;
    bool top = dy == 0 && dx > 0; /* horizontal, interior below (y down) */
    bool left = dy < 0;           /* going up on screen: interior to its right */
    return (edge){ .a = -dy, .b = dx, .c = dy * p->x - dx * p->y, .bias = (top || left) ? 0 : 1 };
}

static int64_t edge_at(const edge *e, int64_t px, int64_t py)
{
    return e->a * px + e->b * py + e->c;
}

/* Orders the vertices clockwise (area2 > 0) so one inside test fits both windings. */
static void order_clockwise(const sr_screen_vertex in[3], int64_t area2, sr_screen_vertex out[3])
{
    out[0] = in[0];
    out[1] = in[area2 > 0 ? 1 : 2];
    out[2] = in[area2 > 0 ? 2 : 1];
}

/* Edge k is the one opposite vertex k, so E_k / area2 is barycentric λ_k. */
static void edges_make(const sr_screen_vertex v[3], edge e[3])
{
    e[0] = edge_make(&v[1], &v[2]);
    e[1] = edge_make(&v[2], &v[0]);
    e[2] = edge_make(&v[0], &v[1]);
}

/* Pixel i's centre, i + 0.5, in subpixel units of `bits` fractional bits. */
static int64_t subpixel_centre(int i, int bits)
{
    return ((int64_t)i << bits) + ((int64_t)1 << (bits - 1));
}

/* Everything the per-pixel loop reads, set up once per triangle. Attributes
 * are a0 + λ1·d1 + λ2·d2, with λ from the exact edge values. */
typedef struct setup {
    edge e[3];
    float inv_area2;
    float z0, dz1, dz2;
    float iw0, diw1, diw2;
    int varyings;
    float var0[SR_MAX_VARYINGS], dvar1[SR_MAX_VARYINGS], dvar2[SR_MAX_VARYINGS];
    sr_raster_rect box;
    int bits; /* subpixel bits of the vertices */
} setup;

/* floor(a / 2^bits): an arithmetic shift, which gcc and clang define for
 * negative a (vertices may lie a hair left of or above the framebuffer). */
static int64_t floor_shift(int64_t a, int bits)
{
    return a >> bits;
}

static int clamp_int(int64_t v, int lo, int hi)
{
    return (int)(v < lo ? lo : v > hi ? hi : v);
}

sr_raster_rect sr_raster_scan_box(const sr_screen_vertex v[3], sr_raster_rect rect, int bits)
{
    int64_t one = (int64_t)1 << bits, half = one / 2;
    int64_t lo_x = v[0].x, hi_x = v[0].x, lo_y = v[0].y, hi_y = v[0].y;
    for (int k = 1; k < 3; k++) {
        lo_x = v[k].x < lo_x ? v[k].x : lo_x;
        hi_x = v[k].x > hi_x ? v[k].x : hi_x;
        lo_y = v[k].y < lo_y ? v[k].y : lo_y;
        hi_y = v[k].y > hi_y ? v[k].y : hi_y;
    }
    return (sr_raster_rect){
        .x0 = clamp_int(floor_shift(lo_x - half + one - 1, bits), rect.x0, rect.x1),
        .x1 = clamp_int(floor_shift(hi_x - half, bits) + 1, rect.x0, rect.x1),
        .y0 = clamp_int(floor_shift(lo_y - half + one - 1, bits), rect.y0, rect.y1),
        .y1 = clamp_int(floor_shift(hi_y - half, bits) + 1, rect.y0, rect.y1),
    };
}

static void setup_make(const sr_screen_vertex v[3], int64_t area2, int varyings, sr_raster_rect box, int bits,
                       setup *s)
{
    s->bits = bits;
    s->box = box;
    edges_make(v, s->e);
    s->inv_area2 = (float)(1.0 / (double)area2);
    s->z0 = v[0].z;
    s->dz1 = v[1].z - v[0].z;
    s->dz2 = v[2].z - v[0].z;
    s->iw0 = v[0].inv_w;
    s->diw1 = v[1].inv_w - v[0].inv_w;
    s->diw2 = v[2].inv_w - v[0].inv_w;
    s->varyings = varyings;
    for (int k = 0; k < varyings; k++) {
        s->var0[k] = v[0].var_w[k];
        s->dvar1[k] = v[1].var_w[k] - v[0].var_w[k];
        s->dvar2[k] = v[2].var_w[k] - v[0].var_w[k];
    }
}

static inline float depth_at(const setup *s, float l1, float l2)
{
    float z = s->z0 + l1 * s->dz1 + l2 * s->dz2;
    return z > 0.0f ? (z < 1.0f ? z : 1.0f) : 0.0f; /* rounding may step a hair outside [0, 1] */
}

static inline void varyings_at(const setup *s, float l1, float l2, float *var)
{
    float w = 1.0f / (s->iw0 + l1 * s->diw1 + l2 * s->diw2);
    for (int k = 0; k < s->varyings; k++)
        var[k] = (s->var0[k] + l1 * s->dvar1[k] + l2 * s->dvar2[k]) * w;
}

static inline bool mode_reads_varyings(sr_shade mode)
{
    return mode != SR_SHADE_ID && mode != SR_SHADE_DEPTH;
}

/* LESS for the standard depth convention, GREATER for reversed z. */
static inline bool depth_passes(float z, float stored, bool greater)
{
    return greater ? z > stored : z < stored;
}

/* Depth test, depth write and shading of covered pixel i of a row; returns
 * 1 if the fragment passed. */
static inline __attribute__((always_inline)) uint64_t
fill_pixel(const setup *s, sr_framebuffer *fb, sr_shade mode, bool greater, const sr_shade_context *shade,
           uint32_t id, size_t at, int64_t e1, int64_t e2)
{
    float l1 = (float)e1 * s->inv_area2, l2 = (float)e2 * s->inv_area2;
    float z = depth_at(s, l1, l2);
    if (!depth_passes(z, fb->depth[at], greater))
        return 0;
    fb->depth[at] = z;
    if (mode != SR_SHADE_DEPTH) {
        float var[SR_MAX_VARYINGS];
        if (mode_reads_varyings(mode))
            varyings_at(s, l1, l2, var);
        fb->color[at] = sr_shade_fragment(mode, shade, var, id);
    }
    return 1;
}

/* Triangles at least this wide in pixels find each row's covered span by
 * division instead of testing every pixel of the scan box (half of which a
 * large triangle does not cover); narrower ones test pixel by pixel. */
#define SPAN_MIN_WIDTH 16

static int64_t floor_div_pos(int64_t a, int64_t b)
{
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

/* The offsets d >= 0 with e + d·step >= bias, intersected into [*lo, *hi]:
 * the same integers the per-pixel test accepts. */
static void edge_span(int64_t e, int64_t step, int64_t bias, int64_t *lo, int64_t *hi)
{
    if (step > 0) {
        int64_t first = -floor_div_pos(e - bias, step); /* ceil((bias - e) / step) */
        *lo = first > *lo ? first : *lo;
    } else if (step < 0) {
        int64_t last = floor_div_pos(e - bias, -step);
        *hi = last < *hi ? last : *hi;
    } else if (e < bias) {
        *hi = -1;
    }
}

/* The per-pixel loop; always inlined with a constant mode and depth test so
 * each combination gets its own loop with those branches folded away. */
static inline __attribute__((always_inline)) uint64_t
raster_loop(const setup *s, sr_framebuffer *fb, sr_shade mode, bool greater, const sr_shade_context *shade,
            uint32_t id)
{
    uint64_t fragments = 0;
    const int64_t one = (int64_t)1 << s->bits; /* a multiply: the coefficients may be negative */
    const int64_t step_x[3] = { s->e[0].a * one, s->e[1].a * one, s->e[2].a * one };
    bool spans = s->box.x1 - s->box.x0 >= SPAN_MIN_WIDTH;
    for (int j = s->box.y0; j < s->box.y1; j++) {
        int64_t px = subpixel_centre(s->box.x0, s->bits), py = subpixel_centre(j, s->bits);
        int64_t e0 = edge_at(&s->e[0], px, py), e1 = edge_at(&s->e[1], px, py), e2 = edge_at(&s->e[2], px, py);
        size_t row = (size_t)j * (size_t)fb->width + (size_t)s->box.x0;
        if (spans) {
            int64_t lo = 0, hi = s->box.x1 - s->box.x0 - 1;
            edge_span(e0, step_x[0], s->e[0].bias, &lo, &hi);
            edge_span(e1, step_x[1], s->e[1].bias, &lo, &hi);
            edge_span(e2, step_x[2], s->e[2].bias, &lo, &hi);
            e1 += lo * step_x[1];
            e2 += lo * step_x[2];
            for (int64_t d = lo; d <= hi; d++, e1 += step_x[1], e2 += step_x[2])
                fragments += fill_pixel(s, fb, mode, greater, shade, id, row + (size_t)d, e1, e2);
            continue;
        }
        for (int d = 0; d < s->box.x1 - s->box.x0; d++, e0 += step_x[0], e1 += step_x[1], e2 += step_x[2])
            if (e0 >= s->e[0].bias && e1 >= s->e[1].bias && e2 >= s->e[2].bias)
                fragments += fill_pixel(s, fb, mode, greater, shade, id, row + (size_t)d, e1, e2);
    }
    return fragments;
}

static inline __attribute__((always_inline)) uint64_t
raster_mode(const setup *s, sr_framebuffer *fb, sr_shade mode, const sr_shade_context *shade, uint32_t id)
{
    return fb->reversed_z ? raster_loop(s, fb, mode, true, shade, id) : raster_loop(s, fb, mode, false, shade, id);
}

uint64_t sr_raster_triangle(sr_framebuffer *fb, sr_raster_rect rect, int subpixel_bits, sr_shade mode,
                            const sr_shade_context *shade, const sr_screen_vertex tri[3], int64_t area2,
                            uint32_t triangle_id)
{
    /* Most triangles of a dense mesh cover no pixel centre: find that out
     * before any setup. */
    sr_raster_rect box = sr_raster_scan_box(tri, rect, subpixel_bits);
    if (box.x0 >= box.x1 || box.y0 >= box.y1)
        return 0;
    sr_screen_vertex v[3];
    setup s;
    order_clockwise(tri, area2, v);
    setup_make(v, area2 > 0 ? area2 : -area2, mode_reads_varyings(mode) ? shade->layout.count : 0, box,
               subpixel_bits, &s);
    switch (mode) {
    case SR_SHADE_ID:      return raster_mode(&s, fb, SR_SHADE_ID, shade, triangle_id);
    case SR_SHADE_COLOR:   return raster_mode(&s, fb, SR_SHADE_COLOR, shade, triangle_id);
    case SR_SHADE_NORMAL:  return raster_mode(&s, fb, SR_SHADE_NORMAL, shade, triangle_id);
    case SR_SHADE_TEXTURE: return raster_mode(&s, fb, SR_SHADE_TEXTURE, shade, triangle_id);
    case SR_SHADE_LAMBERT: return raster_mode(&s, fb, SR_SHADE_LAMBERT, shade, triangle_id);
    default:               return raster_mode(&s, fb, SR_SHADE_DEPTH, shade, triangle_id);
    }
}
