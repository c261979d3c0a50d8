/* triangle_setup.h — stage 8's set-up of one triangle for the per-pixel
 * loops (raster_setup.h): its scan box, its edges, a tiny box's covered
 * pixels, the depth plane, 1/w and the varyings, and what the loops may
 * leave out per pixel. Not public API.
 *
 * The steps are static inline here, not calls of triangle_setup.c: a dense
 * mesh sets up a triangle for every pixel or two, and raster.c inlines them
 * into each of its entry points, specialised on what the entry point knows
 * (a tiny box's mask, the mode), with the box in registers
 * (docs/performance.md, "From slot to set-up"). triangle_setup.c holds what
 * the binned path calls and what runs out of line either way. */
#ifndef SOFTRAST_PIPELINE_TRIANGLE_SETUP_H
#define SOFTRAST_PIPELINE_TRIANGLE_SETUP_H

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "raster_setup.h"

/* A box of pixels against the triangle's edges, from its four corner
 * pixels: all four outside one edge, the box holds no pixel of the triangle
 * (an edge function is linear, so no pixel between the corners is inside
 * either); all four inside every edge, every pixel is (its rows need no
 * solving). A tile of a large triangle is usually one or the other. Small
 * boxes are not classified: partial. */
typedef enum sr_box_cover { SR_COVER_PARTIAL, SR_COVER_NONE, SR_COVER_ALL } sr_box_cover;
sr_box_cover sr_raster_classify(const sr_tri_setup *s, sr_raster_rect box);

/* Sets the triangle up over its scan box (non-empty; sr_raster_scan_box_of
 * clamped to the rectangle drawn): the edges, and unless the box holds none
 * of its pixels (then false) the depth plane, 1/w and the varyings the mode
 * reads. The binned path sets a triangle that spans tiles up once and
 * draws it per tile with the box and `covered` of the tile's share. */
bool sr_raster_setup(const sr_screen_vertex *const tri[3], int64_t area2, sr_raster_rect box, int subpixel_bits,
                     sr_shade mode, const sr_shade_context *shade, sr_tri_setup *s);

/* Makes a triangle set up over a larger box draw only its share of it (a
 * tile's), covered whole or not, by rows. */
void sr_raster_setup_share(sr_tri_setup *s, sr_raster_rect share, bool covered);

/* A tiny box's covered pixel centres (sr_raster_box_is_tiny below): the
 * mask the set-up makes. The binned path tests a tiny triangle within one
 * tile while binning, drops it when the mask is empty and draws it with
 * sr_raster_tiny_triangle (raster.h), which takes the mask instead of
 * testing again. */
uint64_t sr_raster_tiny_mask(const sr_screen_vertex *const tri[3], int64_t area2, sr_raster_rect box,
                             int subpixel_bits);

/* What the triangle lets the loops leave out per pixel (s->interp, and
 * s->w or s->lambert where it needs them), from its set-up with the
 * interpolants, its vertices in set-up order and its area2 (positive). */
void sr_interp_choose(sr_tri_setup *s, const sr_screen_vertex *const v[3], int64_t area2, sr_shade mode,
                      const sr_shade_context *shade);

/* The edge function of p → q (sr_edge). */
static inline sr_edge sr_edge_make(const sr_screen_vertex *p, const sr_screen_vertex *q)
{
    int64_t dx = q->x - p->x, dy = q->y - p->y;
    bool top = dy == 0 && dx > 0; /* horizontal, interior below (y down) */
    bool left = dy < 0;           /* going up on screen: interior to its right */
    return (sr_edge){ .a = -dy, .b = dx, .c = dy * p->x - dx * p->y, .bias = (top || left) ? 0 : 1 };
}

/* Orders the vertices clockwise (area2 > 0) so one inside test fits both windings. */
static inline void sr_order_clockwise(const sr_screen_vertex *const in[3], int64_t area2,
                                      const sr_screen_vertex *out[3])
{
    out[0] = in[0];
    out[1] = in[area2 > 0 ? 1 : 2];
    out[2] = in[area2 > 0 ? 2 : 1];
}

/* Edge k is the one opposite vertex k, so E_k / area2 is barycentric λ_k. */
static SR_ALWAYS_INLINE void sr_edges_make(const sr_screen_vertex *const v[3], sr_edge e[3])
{
    e[0] = sr_edge_make(v[1], v[2]);
    e[1] = sr_edge_make(v[2], v[0]);
    e[2] = sr_edge_make(v[0], v[1]);
}

/* floor(a / 2^bits): an arithmetic shift, which gcc and clang define for
 * negative a (vertices may lie a hair left of or above the framebuffer). */
static inline int64_t sr_floor_shift(int64_t a, int bits)
{
    return a >> bits;
}

static inline int sr_clamp_int(int64_t v, int lo, int hi)
{
    return (int)(v < lo ? lo : v > hi ? hi : v);
}

/* The pixels whose centres can lie in the triangle, clamped to rect (the
 * rectangle, never the vertices: moving one would move a shared edge);
 * empty (x0 >= x1 or y0 >= y1) when none can. Inlined into the one-thread
 * path with the set-up, so the box stays in registers. */
static SR_ALWAYS_INLINE sr_raster_rect sr_raster_scan_box_of(const sr_screen_vertex *const v[3], sr_raster_rect rect,
                                                             int bits)
{
    int64_t one = (int64_t)1 << bits, half = one / 2;
    int64_t lo_x = v[0]->x, hi_x = v[0]->x, lo_y = v[0]->y, hi_y = v[0]->y;
    for (int k = 1; k < 3; k++) {
        lo_x = v[k]->x < lo_x ? v[k]->x : lo_x;
        hi_x = v[k]->x > hi_x ? v[k]->x : hi_x;
        lo_y = v[k]->y < lo_y ? v[k]->y : lo_y;
        hi_y = v[k]->y > hi_y ? v[k]->y : hi_y;
    }
    return (sr_raster_rect){
        .x0 = sr_clamp_int(sr_floor_shift(lo_x - half + one - 1, bits), rect.x0, rect.x1),
        .x1 = sr_clamp_int(sr_floor_shift(hi_x - half, bits) + 1, rect.x0, rect.x1),
        .y0 = sr_clamp_int(sr_floor_shift(lo_y - half + one - 1, bits), rect.y0, rect.y1),
        .y1 = sr_clamp_int(sr_floor_shift(hi_y - half, bits) + 1, rect.y0, rect.y1),
    };
}

/* sr_raster_scan_box_of on vertices held in an array. */
static inline sr_raster_rect sr_raster_scan_box(const sr_screen_vertex tri[3], sr_raster_rect rect, int subpixel_bits)
{
    return sr_raster_scan_box_of((const sr_screen_vertex *const[3]){ &tri[0], &tri[1], &tri[2] }, rect,
                                 subpixel_bits);
}

/* The vertices relative to vertex 0's snapped point, in subpixel units,
 * before snapping (unsnapped) or after: the integer differences are exact in
 * double, the offsets add their 24 bits. Inlined, so each call is
 * specialised on `unsnapped` and pays neither a call nor a branch on it:
 * it runs for every triangle. */
static SR_ALWAYS_INLINE void sr_plane_points(const sr_screen_vertex *const v[3], bool unsnapped, double p[3][2])
{
    for (int k = 0; k < 3; k++) {
        p[k][0] = (double)(v[k]->x - v[0]->x) + (unsnapped ? (double)v[k]->x_off : 0.0);
        p[k][1] = (double)(v[k]->y - v[0]->y) + (unsnapped ? (double)v[k]->y_off : 0.0);
    }
}

/* The depth plane through the unsnapped vertices, in double, and 1/area2
 * for the barycentrics: the z gradient solves a 2×2 system whose
 * determinant is the unsnapped area2 (one division gives both
 * reciprocals). Where
 * snapping turned a sliver over or grew it more than SR_SLIVER_GROWTH times,
 * the snapped vertices give the plane, with their exact integer area2 >= 1:
 * the gradient stays far inside float range (|z| <= 1, positions below 2^35
 * subpixels), so depth stays finite. Needs s->bits. */
#define SR_SLIVER_GROWTH 65536.0
static SR_ALWAYS_INLINE void sr_depth_plane(const sr_screen_vertex *const v[3], int64_t area2, sr_tri_setup *s)
{
    double p[3][2];
    sr_plane_points(v, true, p);
    double x1 = p[1][0] - p[0][0], y1 = p[1][1] - p[0][1], x2 = p[2][0] - p[0][0], y2 = p[2][1] - p[0][1];
    double det = x1 * y2 - x2 * y1;
    if (!(det * SR_SLIVER_GROWTH >= (double)area2)) {
        sr_plane_points(v, false, p);
        x1 = p[1][0], y1 = p[1][1], x2 = p[2][0], y2 = p[2][1];
        det = (double)area2;
    }
    double dz1 = (double)v[1]->z - (double)v[0]->z, dz2 = (double)v[2]->z - (double)v[0]->z;
    double inv_both = 1.0 / (det * (double)area2), inv_det = (double)area2 * inv_both;
    s->inv_area2 = (float)(det * inv_both);
    double gx = (dz1 * y2 - dz2 * y1) * inv_det, gy = (dz2 * x1 - dz1 * x2) * inv_det;
    s->ref_x = sr_floor_shift(v[0]->x, s->bits);
    s->ref_y = sr_floor_shift(v[0]->y, s->bits);
    int64_t one = (int64_t)1 << s->bits; /* a multiply below: ref_x may be negative */
    double ox = (double)(s->ref_x * one + one / 2 - v[0]->x) - p[0][0],
           oy = (double)(s->ref_y * one + one / 2 - v[0]->y) - p[0][1];
    s->z_ref = (double)v[0]->z + gx * ox + gy * oy;
    s->dz_row = gy * (double)one;
    s->dz_pixel = (float)(gx * (double)one);
}

/* What coverage needs: the edges within the scan box. */
static SR_ALWAYS_INLINE void sr_setup_edges(const sr_screen_vertex *const v[3], sr_raster_rect box, int bits,
                                            sr_tri_setup *s)
{
    s->bits = bits;
    s->box = box;
    sr_edges_make(v, s->e);
    for (int k = 0; k < 3; k++)
        s->step_x[k] = s->e[k].a * ((int64_t)1 << bits); /* a multiply: a may be negative */
}

/* What shading needs, for a box that may draw: depth, 1/w, the varyings. */
static SR_ALWAYS_INLINE void sr_setup_interpolants(const sr_screen_vertex *const v[3], int64_t area2, int varyings,
                                                   sr_tri_setup *s)
{
    sr_depth_plane(v, area2, s);
    s->iw0 = v[0]->inv_w;
    s->diw1 = v[1]->inv_w - v[0]->inv_w;
    s->diw2 = v[2]->inv_w - v[0]->inv_w;
    s->varyings = varyings;
    for (int k = 0; k < varyings; k++) {
        s->var0[k] = v[0]->var_w[k];
        s->dvar1[k] = v[1]->var_w[k] - v[0]->var_w[k];
        s->dvar2[k] = v[2]->var_w[k] - v[0]->var_w[k];
    }
}

/* Narrower boxes of at most SR_TINY_SIDE rows are tiny
 * (sr_raster_box_is_tiny): a SIMD kernel's per-row set-up costs more than
 * it saves on a few pixels. A narrower box of more rows, a sliver seen
 * along its length, takes a kernel all the same, which draws such boxes
 * for less than the scalar loop did (docs/performance.md, "The per-pixel
 * loops"). */
#define SR_SIMD_MIN_WIDTH 8

/* A tiny box (sr_tri_setup.tiny): narrower than the SIMD kernels take, and
 * at most SR_TINY_SIDE rows. Of the limits tried on dense meshes (boxes of
 * at most 3 × 3, 4 × 4 and 7 × 4), this one makes the tiny test and the
 * loops run the fewest instructions. */
static inline bool sr_raster_box_is_tiny(sr_raster_rect b)
{
    return b.x1 - b.x0 < SR_SIMD_MIN_WIDTH && b.y1 - b.y0 <= SR_TINY_SIDE;
}
_Static_assert(SR_SIMD_MIN_WIDTH <= SR_TINY_SIDE + 1, "a tiny box's row fits its row of the mask");

/* The covered pixel centres of a tiny box (sr_tri_setup.tiny), each tested
 * as the row loop tests it, E >= bias, here as E − bias >= 0 for the three
 * edges at once: the sign of their OR. The values are E − bias at pixel
 * centres of the box, stepped by the exact integer steps from an exact
 * corner value, so the same integers the per-pixel test sees (minus 0 or 1). */
static SR_ALWAYS_INLINE uint64_t sr_tiny_coverage(const sr_tri_setup *s)
{
    int64_t px = sr_subpixel_centre(s->box.x0, s->bits), py = sr_subpixel_centre(s->box.y0, s->bits);
    int64_t one = (int64_t)1 << s->bits; /* a multiply below: b may be negative */
    /* Three scalars, not arrays: gcc vectorised the arrays' row step into
     * 16-byte loads of values just stored 8 bytes at a time, which the CPU
     * cannot forward (a stall per row in perf). */
    int64_t r0 = sr_edge_at(&s->e[0], px, py) - s->e[0].bias, r1 = sr_edge_at(&s->e[1], px, py) - s->e[1].bias,
            r2 = sr_edge_at(&s->e[2], px, py) - s->e[2].bias;
    uint64_t mask = 0;
#if defined(__SSE2__)
    /* Two pixels of a row at a time, each lane the sum the loop below
     * makes; in a box of odd width, the lane past its last column is cut
     * off (its sum, a vector add, may wrap but is never undefined).
     * docs/performance.md, "From slot to set-up". */
    int width = s->box.x1 - s->box.x0;
    uint64_t row_cut = ((uint64_t)1 << width) - 1;
    __m128i pair0 = _mm_set1_epi64x(s->step_x[0]), pair1 = _mm_set1_epi64x(s->step_x[1]),
            pair2 = _mm_set1_epi64x(s->step_x[2]);
    __m128i row0 = _mm_add_epi64(_mm_set1_epi64x(r0), _mm_unpacklo_epi64(_mm_setzero_si128(), pair0)),
            row1 = _mm_add_epi64(_mm_set1_epi64x(r1), _mm_unpacklo_epi64(_mm_setzero_si128(), pair1)),
            row2 = _mm_add_epi64(_mm_set1_epi64x(r2), _mm_unpacklo_epi64(_mm_setzero_si128(), pair2));
    pair0 = _mm_add_epi64(pair0, pair0), pair1 = _mm_add_epi64(pair1, pair1), pair2 = _mm_add_epi64(pair2, pair2);
    __m128i down0 = _mm_set1_epi64x(s->e[0].b * one), down1 = _mm_set1_epi64x(s->e[1].b * one),
            down2 = _mm_set1_epi64x(s->e[2].b * one);
    for (int j = 0; j < s->box.y1 - s->box.y0; j++) {
        __m128i e0 = row0, e1 = row1, e2 = row2;
        unsigned outside = 0; /* a bit per pixel of the row, set where an edge's sum is negative */
        for (int i = 0; i < width; i += 2) {
            __m128i any = _mm_or_si128(_mm_or_si128(e0, e1), e2);
            outside |= (unsigned)_mm_movemask_pd(_mm_castsi128_pd(any)) << i;
            e0 = _mm_add_epi64(e0, pair0), e1 = _mm_add_epi64(e1, pair1), e2 = _mm_add_epi64(e2, pair2);
        }
        mask |= (~(uint64_t)outside & row_cut) << (j * SR_TINY_SIDE);
        row0 = _mm_add_epi64(row0, down0), row1 = _mm_add_epi64(row1, down1), row2 = _mm_add_epi64(row2, down2);
    }
#else
    for (int j = 0; j < s->box.y1 - s->box.y0; j++) {
        int64_t e0 = r0, e1 = r1, e2 = r2;
        for (int i = 0; i < s->box.x1 - s->box.x0; i++) {
            mask |= (uint64_t)((e0 | e1 | e2) >= 0) << (j * SR_TINY_SIDE + i);
            e0 += s->step_x[0], e1 += s->step_x[1], e2 += s->step_x[2];
        }
        r0 += s->e[0].b * one, r1 += s->e[1].b * one, r2 += s->e[2].b * one;
    }
#endif
    return mask;
}

/* Sets the triangle up over box, as sr_raster_setup: inlined where the box
 * was just found (passed by value to a call, gcc spilled it to the stack
 * and read it back 16 bytes at a time from two 8-byte stores, a
 * store-forwarding stall per triangle), with the edges, a tiny box's mask,
 * the depth plane and the interpolants inlined into it, and in raster.c
 * the branch after it that hands a tiny triangle to the tiny queue: a
 * dense mesh sets up a triangle for every pixel or two, so each call there
 * is paid per pixel (docs/performance.md, "From slot to set-up"). `cut`: a
 * triangle of a material cut by its texels, whose alpha test reads the
 * varyings in any mode; `mask_known`: the box is tiny and `mask` its
 * coverage, found while binning (sr_raster_tiny_mask). */
static SR_ALWAYS_INLINE bool sr_setup_triangle(const sr_screen_vertex *const tri[3], int64_t area2,
                                               sr_raster_rect box, int subpixel_bits, sr_shade mode, bool cut,
                                               const sr_shade_context *shade, bool mask_known, uint64_t mask,
                                               sr_tri_setup *s)
{
    const sr_screen_vertex *v[3];
    sr_order_clockwise(tri, area2, v);
    /* With the mask known, a mode that reads no varyings has no use for the
     * edges: the mask is the coverage (raster.c's tiny loop), and the depth
     * plane comes from the vertices. */
    bool varyings = sr_mode_reads_varyings(mode) || cut;
    if (mask_known && !varyings) {
        s->bits = subpixel_bits;
        s->box = box;
    } else {
        sr_setup_edges(v, box, subpixel_bits, s);
    }
    /* A tiny box's pixels are tested first, so a triangle that covers none
     * of them (many of a dense mesh's) skips the depth plane; the
     * binned path tests them while binning and passes the mask on. */
    bool tiny = sr_raster_box_is_tiny(box);
    s->tiny = !tiny ? 0 : mask_known ? mask : sr_tiny_coverage(s);
    sr_box_cover c = tiny ? (s->tiny ? SR_COVER_PARTIAL : SR_COVER_NONE) : sr_raster_classify(s, box);
    if (c == SR_COVER_NONE)
        return false;
    int64_t area2_abs = area2 > 0 ? area2 : -area2;
    sr_setup_interpolants(v, area2_abs, varyings ? shade->layout.count : 0, s);
    s->covered = c == SR_COVER_ALL;
    sr_interp_choose(s, v, area2_abs, mode, shade);
    return true;
}

#endif
