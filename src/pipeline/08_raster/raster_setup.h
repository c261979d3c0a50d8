/* raster_setup.h — a triangle as the per-pixel loops read it, set up by
 * triangle_setup.h and shared by the scalar loop (raster.c) and the SIMD
 * span kernels (span_*.c). Not public API.
 *
 * Edge k is the one opposite vertex k, so E_k / area2 is barycentric λ_k;
 * attributes are a0 + λ1·d1 + λ2·d2 with λ from the exact edge values.
 * Depth is not: it comes from the plane through the unsnapped vertices
 * (snapping moves a steep triangle's plane by up to half a subpixel step
 * times its slope), fitted in double per triangle, taken in double at each
 * row's reference pixel and stepped along the row in float. Every path
 * evaluates these in the same float operations in the same order, so a
 * pixel comes out bit-identical whichever path draws it. */
#ifndef SOFTRAST_RASTER_SETUP_H
#define SOFTRAST_RASTER_SETUP_H

#include "pipeline/10_shade.h"
#include "pipeline/stages.h"

/* The tiled path draws in tiles that are strips of whole rows,
 * SR_TILE_ROWS(width) each: SR_TILE_ROWS_MAX, or fewer on a framebuffer
 * wider than SR_TILE_PIXELS / SR_TILE_ROWS_MAX so that a strip's color and
 * depth stay within SR_TILE_PIXELS pixels (docs/performance.md). Tests
 * and the fuzzer size their framebuffers by it. */
#define SR_TILE_ROWS_MAX 32
#define SR_TILE_PIXELS 65536
#define SR_TILE_ROWS(width) \
    ((width) <= SR_TILE_PIXELS / SR_TILE_ROWS_MAX ? SR_TILE_ROWS_MAX : SR_TILE_PIXELS / (width))

/* The rasterizer's mode for sr_draw_study.count_hits, past the public
 * shading modes: every covered pixel adds 1 to its color, with no depth test
 * or write and no varyings. No SIMD kernel has it, so the scalar loop draws. */
#define SR_RASTER_COUNT_HITS ((sr_shade)SR_SHADE_COUNT)

/* The mode shades from the interpolated varyings (a set-up makes them). */
static inline bool sr_mode_reads_varyings(sr_shade mode)
{
    return mode != SR_SHADE_ID && mode != SR_SHADE_DEPTH && mode != SR_RASTER_COUNT_HITS;
}

/* The pixels [x0, x1) × [y0, y1) a call may touch (the framebuffer, or a tile). */
typedef struct sr_raster_rect {
    int x0, y0, x1, y1;
} sr_raster_rect;

/* E(P) = a·Px + b·Py + c, the edge function of a → b in subpixel units: >= 0
 * on the inside of a clockwise (area2 > 0) triangle. `bias` is 0 on a top or
 * left edge and 1 otherwise, so E >= bias decides coverage with the
 * top-left rule in exact integers. */
typedef struct sr_edge {
    int64_t a, b, c, bias;
} sr_edge;

/* What a triangle lets the per-pixel loops leave out, chosen once per
 * triangle in its set-up (sr_interp_choose), the same choice in every loop,
 * path and thread count. Each choice but SR_INTERP_PERSPECTIVE_FLAT_NORMAL
 * computes per triangle exactly the float values the general loop would
 * compute per pixel, so the image does not depend on it; that one may put
 * an 8-bit channel one step from where the general loop would. */
typedef enum sr_interp {
    SR_INTERP_PERSPECTIVE, /* 1/w varies: one division per pixel */
    /* The three 1/w equal (an orthographic camera, or a triangle facing the
     * camera square-on): 1/w interpolates to exactly iw0 everywhere (the
     * differences are 0), so w = 1/iw0 once per triangle. */
    SR_INTERP_AFFINE,
    /* Affine, lambert, and the normal's varyings equal at the three vertices:
     * the interpolated normal is var0 · w at every pixel, so its lambert
     * intensity is computed once per triangle. */
    SR_INTERP_FLAT_NORMAL,
    /* Perspective, lambert, a triangle of 32 pixels or more
     * (FLAT_TEST_MIN_PIXELS in triangle_setup.c), and the three vertices'
     * normals pointing the same way (their normal/w varyings parallel:
     * normals_parallel in triangle_setup.c): the interpolated normal points
     * that way at every pixel, and the intensity does not see its length, so it
     * is computed once per triangle, from vertex 0's normal/w made unit
     * length; the varyings after the normal divide by 1/w per pixel as
     * under SR_INTERP_PERSPECTIVE. A faceted mesh (face normals) seen in
     * perspective. Per pixel, the normal would carry the rounding of its
     * interpolation, so a channel on a rounding boundary can come out one
     * step apart from the general loop's. */
    SR_INTERP_PERSPECTIVE_FLAT_NORMAL,
} sr_interp;

/* 1/w is interpolated and divided per pixel. */
static inline bool sr_interp_divides(sr_interp interp)
{
    return interp == SR_INTERP_PERSPECTIVE || interp == SR_INTERP_PERSPECTIVE_FLAT_NORMAL;
}

/* The lambert intensity is the triangle's (sr_tri_setup.lambert). */
static inline bool sr_interp_flat_normal(sr_interp interp)
{
    return interp == SR_INTERP_FLAT_NORMAL || interp == SR_INTERP_PERSPECTIVE_FLAT_NORMAL;
}

/* The rows of a tiny box and the stride of its mask (sr_tri_setup.tiny):
 * 64 bits hold 8 × 8 pixels. */
#define SR_TINY_SIDE 8

typedef struct sr_tri_setup {
    sr_edge e[3];
    int64_t step_x[3]; /* E's change from one pixel to the next on a row */
    float inv_area2;
    /* The depth plane: z at the centre of pixel (ref_x, ref_y), the pixel of
     * vertex 0 (so every tile of a triangle steps from the same point), its
     * change per row and per pixel. */
    int64_t ref_x, ref_y;
    double z_ref, dz_row;
    float dz_pixel;
    float iw0, diw1, diw2;
    int varyings;
    float var0[SR_MAX_VARYINGS], dvar1[SR_MAX_VARYINGS], dvar2[SR_MAX_VARYINGS];
    sr_raster_rect box;
    int bits;     /* subpixel bits of the vertices */
    bool covered; /* every pixel centre of the box is inside: rows need no solving or tests */
    /* A tiny box (too narrow for the SIMD kernels, at most SR_TINY_SIDE
     * rows): its covered pixel centres, bit (j − y0)·SR_TINY_SIDE + (i − x0)
     * for pixel (i, j), found before the depth plane and drawn bit by bit.
     * 0: the rows are solved and tested as for any box. */
    uint64_t tiny;
    sr_interp interp;
    float w;       /* 1/iw0, when interp does not divide (sr_interp_divides) */
    float lambert; /* the intensity, when sr_interp_flat_normal */
} sr_tri_setup;

static inline int64_t sr_edge_at(const sr_edge *e, int64_t px, int64_t py)
{
    return e->a * px + e->b * py + e->c;
}

/* Pixel i's centre, i + 0.5, in subpixel units of `bits` fractional bits. */
static inline int64_t sr_subpixel_centre(int i, int bits)
{
    return ((int64_t)i << bits) + ((int64_t)1 << (bits - 1));
}

static inline int64_t sr_floor_div_pos(int64_t a, int64_t b)
{
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

/* The offsets d >= 0 with e + d·step >= bias, intersected into [*lo, *hi]:
 * the same integers the per-pixel test accepts. */
static inline void sr_edge_span(int64_t e, int64_t step, int64_t bias, int64_t *lo, int64_t *hi)
{
    if (step > 0) {
        int64_t first = -sr_floor_div_pos(e - bias, step); /* ceil((bias - e) / step) */
        *lo = first > *lo ? first : *lo;
    } else if (step < 0) {
        int64_t last = sr_floor_div_pos(e - bias, -step);
        *hi = last < *hi ? last : *hi;
    } else if (e < bias) {
        *hi = -1;
    }
}

/* z at the centre of row j's pixel ref_x, in double rounded to float: the
 * same value in every loop. */
static inline float sr_row_z(const sr_tri_setup *s, int j)
{
    return (float)(s->z_ref + s->dz_row * (double)(j - s->ref_y));
}

/* A depth clamped to [0, 1], NaN to 0. */
static inline float sr_depth_clamp(float z)
{
    return z > 0.0f ? (z < 1.0f ? z : 1.0f) : 0.0f;
}

/* z at the pixel k pixels right of the row's reference pixel, clamped: the
 * unsnapped triangle's plane may step a hair outside [0, 1] at a pixel the
 * snapped triangle covers and the unsnapped one does not, and rounding may. */
static inline float sr_depth_at(const sr_tri_setup *s, float z_row, float k)
{
    return sr_depth_clamp(z_row + s->dz_pixel * k);
}

/* LESS for the standard depth convention, GREATER for reversed z. */
static inline bool sr_depth_passes(float z, float stored, bool greater)
{
    return greater ? z > stored : z < stored;
}

/* Bit n of a tiny box's mask (sr_tri_setup.tiny): the pixel's index in fb,
 * its z_row and k, and its centre for the edges. The values are the row
 * loop's: z at row j is the same double rounded to float, k the same small
 * integer, and E at a pixel centre the same exact integer. */
typedef struct sr_tiny_pixel {
    size_t at;
    float z_row, k;
    int64_t px, py;
} sr_tiny_pixel;

static SR_ALWAYS_INLINE sr_tiny_pixel sr_tiny_pixel_of(const sr_tri_setup *s, const sr_framebuffer *fb, int n)
{
    int i = s->box.x0 + n % SR_TINY_SIDE, j = s->box.y0 + n / SR_TINY_SIDE;
    return (sr_tiny_pixel){ .at = (size_t)j * (size_t)fb->width + (size_t)i, .z_row = sr_row_z(s, j),
                            .k = (float)(i - s->ref_x), .px = sr_subpixel_centre(i, s->bits),
                            .py = sr_subpixel_centre(j, s->bits) };
}

/* Row j of the scan box: the pixel index and edge values where its
 * candidate pixels start, and how many there are: the whole row, or with
 * `spans` exactly the covered run, found by solving each edge's inequality
 * (all of a row's pixels outside the triangle are rejected, all inside
 * accepted, without a test per pixel). */
typedef struct sr_row_range {
    size_t at;
    int64_t e[3];
    int count;
    float z, k; /* z at the row's pixel ref_x; `at`'s pixel is k pixels right of it */
} sr_row_range;

/* Fills the caller's *r field by field: a struct built on the stack and
 * returned by value was copied with wide vector loads of narrower stores
 * just made, which the CPU cannot forward (a stall of every row, measured
 * in the span kernels' profile). With count 0 the other fields are unset. */
static SR_ALWAYS_INLINE void sr_row_make(const sr_tri_setup *s, const sr_framebuffer *fb, bool spans, int j,
                                         sr_row_range *r)
{
    int64_t px = sr_subpixel_centre(s->box.x0, s->bits), py = sr_subpixel_centre(j, s->bits);
    int64_t lo = 0, hi = s->box.x1 - s->box.x0 - 1;
    int64_t e[3];
    for (int k = 0; k < 3; k++) {
        e[k] = sr_edge_at(&s->e[k], px, py);
        if (spans && !s->covered)
            sr_edge_span(e[k], s->step_x[k], s->e[k].bias, &lo, &hi);
    }
    r->count = lo <= hi ? (int)(hi - lo + 1) : 0;
    if (r->count == 0)
        return;
    for (int k = 0; k < 3; k++)
        r->e[k] = e[k] + lo * s->step_x[k];
    r->at = (size_t)j * (size_t)fb->width + (size_t)s->box.x0 + (size_t)lo;
    r->z = sr_row_z(s, j);
    r->k = (float)(s->box.x0 + lo - s->ref_x); /* exact: boxes are far narrower than 2^24 pixels */
}

/* The widest kernel's lanes: edge values are checked exact this far past a
 * scan box's right side. */
#define SR_SIMD_MAX_LANES 16

/* A SIMD kernel draws a whole triangle, row span by row span, and returns
 * the fragments that passed the depth test. The caller guarantees every
 * edge value of the scan box (and a group of lanes past it) is below 2^52
 * in magnitude, so doubles hold them exactly. */
typedef uint64_t (*sr_span_kernel)(const sr_tri_setup *s, const sr_shade_context *c, sr_framebuffer *fb,
                                   uint32_t id);

#endif
