#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "pipeline/11_merge.h"
#include "raster.h"
#include "simd_select.h"
#include "tiny_queue.h"

typedef sr_edge edge;

static edge edge_make(const sr_screen_vertex *p, const sr_screen_vertex *q)
{
    int64_t dx = q->x - p->x, dy = q->y - p->y;
    bool top = dy == 0 && dx > 0; /* horizontal, interior below (y down) */
    bool left = dy < 0;           /* going up on screen: interior to its right */
    return (edge){ .a = -dy, .b = dx, .c = dy * p->x - dx * p->y, .bias = (top || left) ? 0 : 1 };
}

/* Orders the vertices clockwise (area2 > 0) so one inside test fits both windings. */
static void order_clockwise(const sr_screen_vertex *const in[3], int64_t area2, const sr_screen_vertex *out[3])
{
    out[0] = in[0];
    out[1] = in[area2 > 0 ? 1 : 2];
    out[2] = in[area2 > 0 ? 2 : 1];
}

/* Edge k is the one opposite vertex k, so E_k / area2 is barycentric λ_k. */
static SR_ALWAYS_INLINE void edges_make(const sr_screen_vertex *const v[3], edge e[3])
{
    e[0] = edge_make(v[1], v[2]);
    e[1] = edge_make(v[2], v[0]);
    e[2] = edge_make(v[0], v[1]);
}

typedef sr_tri_setup setup;

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

sr_raster_rect sr_raster_scan_box(const sr_screen_vertex tri[3], sr_raster_rect rect, int subpixel_bits)
{
    return sr_raster_scan_box_of((const sr_screen_vertex *const[3]){ &tri[0], &tri[1], &tri[2] }, rect,
                                 subpixel_bits);
}

/* Inlined into the one-thread path with the set-up (below), so the box
 * stays in registers. */
static SR_ALWAYS_INLINE sr_raster_rect scan_box(const sr_screen_vertex *const v[3], sr_raster_rect rect, int bits)
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
        .x0 = clamp_int(floor_shift(lo_x - half + one - 1, bits), rect.x0, rect.x1),
        .x1 = clamp_int(floor_shift(hi_x - half, bits) + 1, rect.x0, rect.x1),
        .y0 = clamp_int(floor_shift(lo_y - half + one - 1, bits), rect.y0, rect.y1),
        .y1 = clamp_int(floor_shift(hi_y - half, bits) + 1, rect.y0, rect.y1),
    };
}

/* scan_box of a triangle whose box over the framebuffer holds one pixel
 * centre (sr_raster_one_pixel): its corner from the smallest x and y,
 * clamped to the framebuffer's, which a triangle in a guard band may
 * pass (the box's far side is then the framebuffer's first pixel's). */
static SR_ALWAYS_INLINE sr_raster_rect one_pixel_box(const sr_screen_vertex *const v[3], int bits)
{
    int64_t one = (int64_t)1 << bits, half = one / 2;
    int64_t lo_x = v[0]->x < v[1]->x ? v[0]->x : v[1]->x, lo_y = v[0]->y < v[1]->y ? v[0]->y : v[1]->y;
    lo_x = v[2]->x < lo_x ? v[2]->x : lo_x;
    lo_y = v[2]->y < lo_y ? v[2]->y : lo_y;
    int x = clamp_int(floor_shift(lo_x - half + one - 1, bits), 0, INT32_MAX),
        y = clamp_int(floor_shift(lo_y - half + one - 1, bits), 0, INT32_MAX);
    return (sr_raster_rect){ x, y, x + 1, y + 1 };
}

sr_raster_rect sr_raster_scan_box_of(const sr_screen_vertex *const v[3], sr_raster_rect rect, int bits)
{
    return scan_box(v, rect, bits);
}

/* The vertices relative to vertex 0's snapped point, in subpixel units,
 * before snapping (unsnapped) or after: the integer differences are exact in
 * double, the offsets add their 24 bits. Inlined, so each call is
 * specialised on `unsnapped` and pays neither a call nor a branch on it:
 * it runs for every triangle. */
static SR_ALWAYS_INLINE void plane_points(const sr_screen_vertex *const v[3], bool unsnapped, double p[3][2])
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
 * snapping turned a sliver over or grew it more than SLIVER_GROWTH times,
 * the snapped vertices give the plane, with their exact integer area2 >= 1:
 * the gradient stays far inside float range (|z| <= 1, positions below 2^35
 * subpixels), so depth stays finite. */
#define SLIVER_GROWTH 65536.0
static SR_ALWAYS_INLINE void depth_plane(const sr_screen_vertex *const v[3], int64_t area2, setup *s)
{
    double p[3][2];
    plane_points(v, true, p);
    double x1 = p[1][0] - p[0][0], y1 = p[1][1] - p[0][1], x2 = p[2][0] - p[0][0], y2 = p[2][1] - p[0][1];
    double det = x1 * y2 - x2 * y1;
    if (!(det * SLIVER_GROWTH >= (double)area2)) {
        plane_points(v, false, p);
        x1 = p[1][0], y1 = p[1][1], x2 = p[2][0], y2 = p[2][1];
        det = (double)area2;
    }
    double dz1 = (double)v[1]->z - (double)v[0]->z, dz2 = (double)v[2]->z - (double)v[0]->z;
    double inv_both = 1.0 / (det * (double)area2), inv_det = (double)area2 * inv_both;
    s->inv_area2 = (float)(det * inv_both);
    double gx = (dz1 * y2 - dz2 * y1) * inv_det, gy = (dz2 * x1 - dz1 * x2) * inv_det;
    s->ref_x = floor_shift(v[0]->x, s->bits);
    s->ref_y = floor_shift(v[0]->y, s->bits);
    int64_t one = (int64_t)1 << s->bits; /* a multiply below: ref_x may be negative */
    double ox = (double)(s->ref_x * one + one / 2 - v[0]->x) - p[0][0],
           oy = (double)(s->ref_y * one + one / 2 - v[0]->y) - p[0][1];
    s->z_ref = (double)v[0]->z + gx * ox + gy * oy;
    s->dz_row = gy * (double)one;
    s->dz_pixel = (float)(gx * (double)one);
}

/* What coverage needs: the edges within the scan box. */
static SR_ALWAYS_INLINE void setup_make(const sr_screen_vertex *const v[3], sr_raster_rect box, int bits, setup *s)
{
    s->bits = bits;
    s->box = box;
    edges_make(v, s->e);
    for (int k = 0; k < 3; k++)
        s->step_x[k] = s->e[k].a * ((int64_t)1 << bits); /* a multiply: a may be negative */
}

/* What shading needs, for a box that may draw: depth, 1/w, the varyings. */
static SR_ALWAYS_INLINE void interpolants_make(const sr_screen_vertex *const v[3], int64_t area2, int varyings,
                                               setup *s)
{
    depth_plane(v, area2, s);
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

static inline void varyings_at(const setup *s, sr_interp interp, float l1, float l2, float *var)
{
    float w = sr_interp_divides(interp) ? 1.0f / (s->iw0 + l1 * s->diw1 + l2 * s->diw2) : s->w;
    for (int k = 0; k < s->varyings; k++)
        var[k] = (s->var0[k] + l1 * s->dvar1[k] + l2 * s->dvar2[k]) * w;
}

static inline bool mode_reads_varyings(sr_shade mode)
{
    return mode != SR_SHADE_ID && mode != SR_SHADE_DEPTH && mode != SR_RASTER_COUNT_HITS;
}

/* The shaded colour of a fragment at var. */
static inline __attribute__((always_inline)) uint32_t fragment_colour(const setup *s, sr_shade mode, sr_interp interp,
                                                                      const sr_shade_context *shade, const float *var,
                                                                      uint32_t id)
{
    return mode == SR_SHADE_LAMBERT && sr_interp_flat_normal(interp) ? sr_shade_lit(shade, var, s->lambert)
                                                                     : sr_shade_fragment(mode, shade, var, id);
}

/* Depth test, depth write, id write (with_ids: fb has an ids plane) and
 * shading of covered pixel i of a row; returns 1 if the fragment passed.
 * Counting hits, the pixel only counts one more. `cut`: a triangle of a
 * material cut by its texels (sr_shade_context.cut), whose varyings are
 * interpolated for the alpha test in a mode that reads none. */
static inline __attribute__((always_inline)) uint64_t
fill_pixel(const setup *s, sr_framebuffer *fb, sr_shade mode, bool cut, bool greater, bool with_ids, sr_interp interp,
           const sr_shade_context *shade, uint32_t id, size_t at, float z_row, float k, int64_t e1, int64_t e2)
{
    if (mode == SR_RASTER_COUNT_HITS) {
        fb->color[at]++;
        return 1;
    }
    float z = sr_depth_at(s, z_row, k);
    if (!sr_depth_passes(z, fb->depth[at], greater))
        return 0;
    float var[SR_MAX_VARYINGS];
    if (mode_reads_varyings(mode) || cut) {
        varyings_at(s, interp, (float)e1 * s->inv_area2, (float)e2 * s->inv_area2, var);
        /* A MASK material's fragment under its alpha floor writes nothing. */
        if (shade->alpha_min && !sr_shade_alpha_passes(shade, var))
            return 0;
    }
    if (shade->merges) { /* a draw that blends or keeps its depth (11_merge.h) */
        bool coloured = mode != SR_SHADE_DEPTH;
        sr_merge_fragment(fb, shade, at, z, with_ids, id, coloured,
                          coloured ? fragment_colour(s, mode, interp, shade, var, id) : 0,
                          coloured && mode_reads_varyings(mode) ? sr_merge_alpha(shade, var) : shade->alpha_scale);
        return 1;
    }
    fb->depth[at] = z;
    if (with_ids)
        fb->ids[at] = id + 1u;
    if (mode != SR_SHADE_DEPTH)
        fb->color[at] = fragment_colour(s, mode, interp, shade, var, id);
    return 1;
}

/* In the scalar loop, triangles at least this wide in pixels find each row's
 * covered span by division instead of testing every pixel of the scan box
 * (half of which a large triangle does not cover); narrower ones test pixel
 * by pixel. The SIMD kernels always take the span. */
#define SPAN_MIN_WIDTH 16

static inline bool wide(const setup *s)
{
    return s->box.x1 - s->box.x0 >= SPAN_MIN_WIDTH;
}

/* A tiny box's covered pixels, in the rows' order. */
static inline __attribute__((always_inline)) uint64_t
tiny_loop(const setup *s, sr_framebuffer *fb, sr_shade mode, bool cut, bool greater, bool with_ids, sr_interp interp,
          const sr_shade_context *shade, uint32_t id)
{
    uint64_t fragments = 0;
    for (uint64_t m = s->tiny; m; m &= m - 1) {
        sr_tiny_pixel p = sr_tiny_pixel_of(s, fb, __builtin_ctzll(m));
        /* The edges only for the varyings: a mode without leaves them unset
         * when the mask came from binning (setup_in). */
        bool edges = mode_reads_varyings(mode) || cut;
        fragments += fill_pixel(s, fb, mode, cut, greater, with_ids, interp, shade, id, p.at, p.z_row, p.k,
                                edges ? sr_edge_at(&s->e[1], p.px, p.py) : 0,
                                edges ? sr_edge_at(&s->e[2], p.px, p.py) : 0);
    }
    return fragments;
}

/* The scalar per-pixel loop; always inlined with a constant mode, depth
 * test and ids plane so each combination gets its own loop with those
 * branches folded away. */
static inline __attribute__((always_inline)) uint64_t
raster_loop(const setup *s, sr_framebuffer *fb, sr_shade mode, bool cut, bool greater, bool with_ids, sr_interp interp,
            const sr_shade_context *shade, uint32_t id)
{
    uint64_t fragments = 0;
    const int64_t *step = s->step_x;
    bool spans = wide(s);
    for (int j = s->box.y0; j < s->box.y1; j++) {
        sr_row_range r;
        sr_row_make(s, fb, spans, j, &r);
        int64_t e0 = r.e[0], e1 = r.e[1], e2 = r.e[2];
        float k = r.k;
        for (int d = 0; d < r.count; d++, e0 += step[0], e1 += step[1], e2 += step[2], k += 1.0f)
            if (spans || s->covered || (e0 >= s->e[0].bias && e1 >= s->e[1].bias && e2 >= s->e[2].bias))
                fragments += fill_pixel(s, fb, mode, cut, greater, with_ids, interp, shade, id, r.at + (size_t)d, r.z,
                                        k, e1, e2);
    }
    return fragments;
}

/* Doubles hold the edge values exactly below 2^53; the kernels need that over
 * the scan box and up to one group of lanes past its right side. An edge
 * function is linear, so its largest magnitude is at a corner. */
#define SIMD_EDGE_LIMIT ((int64_t)1 << 52)
/* Narrower boxes of at most SR_TINY_SIDE rows are tiny (box_is_tiny): a
 * kernel's per-row set-up costs more than it saves on a few pixels. A
 * narrower box of more rows, a sliver seen along its length, takes a
 * kernel all the same, which draws such boxes for less than the scalar
 * loop did (docs/performance.md, "The per-pixel loops"). */
#define SIMD_MIN_WIDTH 8

static bool edges_fit_double(const setup *s)
{
    int64_t xs[2] = { sr_subpixel_centre(s->box.x0, s->bits), sr_subpixel_centre(s->box.x1 - 1 + SR_SIMD_MAX_LANES, s->bits) };
    int64_t ys[2] = { sr_subpixel_centre(s->box.y0, s->bits), sr_subpixel_centre(s->box.y1 - 1, s->bits) };
    for (int k = 0; k < 3; k++)
        for (int c = 0; c < 4; c++)
            if (llabs(sr_edge_at(&s->e[k], xs[c & 1], ys[c >> 1])) >= SIMD_EDGE_LIMIT)
                return false;
    return true;
}

/* Narrower than the SIMD kernels take, and at most SR_TINY_SIDE rows: of
 * the limits tried on dense meshes (boxes of at most 3 × 3, 4 × 4 and
 * 7 × 4), this one makes the tiny test and the loops run the fewest
 * instructions. */
static bool box_is_tiny(sr_raster_rect b)
{
    return b.x1 - b.x0 < SIMD_MIN_WIDTH && b.y1 - b.y0 <= SR_TINY_SIDE;
}
_Static_assert(SIMD_MIN_WIDTH <= SR_TINY_SIDE + 1, "a tiny box's row fits its row of the mask");

/* The covered pixel centres of a tiny box (sr_tri_setup.tiny), each tested
 * as the row loop tests it, E >= bias, here as E − bias >= 0 for the three
 * edges at once: the sign of their OR. The values are E − bias at pixel
 * centres of the box, stepped by the exact integer steps from an exact
 * corner value, so the same integers the per-pixel test sees (minus 0 or 1). */
static SR_ALWAYS_INLINE uint64_t tiny_coverage(const setup *s)
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

/* Boxes smaller than this are not worth sr_raster_classify's twelve
 * evaluations: they count as partial. */
#define CLASSIFY_MIN_PIXELS 64

sr_box_cover sr_raster_classify(const setup *s, sr_raster_rect b)
{
    if ((int64_t)(b.x1 - b.x0) * (b.y1 - b.y0) < CLASSIFY_MIN_PIXELS)
        return SR_COVER_PARTIAL;
    int64_t xs[2] = { sr_subpixel_centre(b.x0, s->bits), sr_subpixel_centre(b.x1 - 1, s->bits) };
    int64_t ys[2] = { sr_subpixel_centre(b.y0, s->bits), sr_subpixel_centre(b.y1 - 1, s->bits) };
    bool covered = true;
    for (int k = 0; k < 3; k++) {
        int inside = 0;
        for (int c = 0; c < 4; c++)
            inside += sr_edge_at(&s->e[k], xs[c & 1], ys[c >> 1]) >= s->e[k].bias;
        if (inside == 0)
            return SR_COVER_NONE;
        covered = covered && inside == 4;
    }
    return covered ? SR_COVER_ALL : SR_COVER_PARTIAL;
}

static inline __attribute__((always_inline)) uint64_t
raster_pixels(const setup *s, sr_framebuffer *fb, sr_shade mode, bool cut, bool greater, bool with_ids,
              sr_interp interp, const sr_shade_context *shade, uint32_t id)
{
    return s->tiny ? tiny_loop(s, fb, mode, cut, greater, with_ids, interp, shade, id)
                   : raster_loop(s, fb, mode, cut, greater, with_ids, interp, shade, id);
}

static inline __attribute__((always_inline)) uint64_t
raster_tests(const setup *s, sr_framebuffer *fb, sr_shade mode, bool cut, bool with_ids, sr_interp interp,
             const sr_shade_context *shade, uint32_t id)
{
    return fb->reversed_z ? raster_pixels(s, fb, mode, cut, true, with_ids, interp, shade, id)
                          : raster_pixels(s, fb, mode, cut, false, with_ids, interp, shade, id);
}

static inline __attribute__((always_inline)) uint64_t
raster_interp(const setup *s, sr_framebuffer *fb, sr_shade mode, bool cut, sr_interp interp,
              const sr_shade_context *shade, uint32_t id)
{
    return fb->ids ? raster_tests(s, fb, mode, cut, true, interp, shade, id)
                   : raster_tests(s, fb, mode, cut, false, interp, shade, id);
}

/* One loop per interp for the modes that read varyings (and a cut
 * triangle's alpha test). */
static inline __attribute__((always_inline)) uint64_t
raster_mode(const setup *s, sr_framebuffer *fb, sr_shade mode, bool cut, const sr_shade_context *shade, uint32_t id)
{
    if (mode == SR_SHADE_LAMBERT && s->interp == SR_INTERP_FLAT_NORMAL)
        return raster_interp(s, fb, mode, cut, SR_INTERP_FLAT_NORMAL, shade, id);
    if (mode == SR_SHADE_LAMBERT && s->interp == SR_INTERP_PERSPECTIVE_FLAT_NORMAL)
        return raster_interp(s, fb, mode, cut, SR_INTERP_PERSPECTIVE_FLAT_NORMAL, shade, id);
    if ((mode_reads_varyings(mode) || cut) && !sr_interp_divides(s->interp))
        return raster_interp(s, fb, mode, cut, SR_INTERP_AFFINE, shade, id);
    return raster_interp(s, fb, mode, cut, SR_INTERP_PERSPECTIVE, shade, id);
}

/* The dot product of a and b, in double, where the products of floats are
 * exact. */
static double dot_d(const float a[3], const float b[3])
{
    return (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2];
}

/* Normals a and b point the same way: within about 2^-20 radians, which
 * the rounding of a normal/w varying to float (2^-24 relative per
 * component) stays inside, and which no mesh's smooth normals come near (a
 * torus of 10M triangles turns hers by 2^-8 to 2^-9 from vertex to
 * vertex). A subnormal varying (w past about 1e32) rounds more coarsely
 * and may fail the test: that triangle is lit per pixel. */
#define PARALLEL_SIN2 0x1p-40 /* the squared sine of that angle */

static bool normals_parallel(const float a[3], const float b[3])
{
    double c[3] = { (double)a[1] * b[2] - (double)a[2] * b[1], (double)a[2] * b[0] - (double)a[0] * b[2],
                    (double)a[0] * b[1] - (double)a[1] * b[0] };
    double sin2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    return dot_d(a, b) > 0.0 && sin2 <= PARALLEL_SIN2 * dot_d(a, a) * dot_d(b, b);
}

/* Under a perspective camera, only triangles of at least this many pixels
 * are tested for a flat normal. The test is two cross products and six
 * dot products in double, of the order of lighting one pixel (a dot
 * product, a square root, a division); on a dense mesh, whose smooth
 * triangles are a pixel or two and never pass, testing every triangle
 * cost a share of the frame and saved nothing; with this floor it costs
 * nothing visible, while fly's walls still pass. The triangle's area
 * decides, not its box (which a tile clips), so every path and thread
 * count decides alike; a face's triangles under the limit are lit per
 * pixel, which may differ from the once-per-triangle value by one step of
 * a channel (sr_interp). */
#define FLAT_TEST_MIN_PIXELS 32

/* What the triangle lets the loops leave out per pixel (sr_interp), from
 * its set-up, its vertices in set-up order and its area2 (positive). */
static void interp_choose(setup *s, const sr_screen_vertex *const v[3], int64_t area2, sr_shade mode,
                          const sr_shade_context *shade)
{
    s->interp = SR_INTERP_PERSPECTIVE;
    if (s->varyings == 0)
        return;
    int at = shade->layout.normal;
    bool lambert = mode == SR_SHADE_LAMBERT && at >= 0;
    if (s->diw1 != 0.0f || s->diw2 != 0.0f) {
        int64_t min_area2 = (int64_t)2 * FLAT_TEST_MIN_PIXELS << (2 * s->bits);
        if (!lambert || area2 < min_area2)
            return;
        /* normal/w at each vertex: parallel where the normals are. */
        const float *n0 = v[0]->var_w + at;
        if (normals_parallel(n0, v[1]->var_w + at) && normals_parallel(n0, v[2]->var_w + at)) {
            /* Unit length in double first: normal/w may be too long or
             * short for its squared length in float. */
            double length = sqrt(dot_d(n0, n0));
            float n[3] = { (float)(n0[0] / length), (float)(n0[1] / length), (float)(n0[2] / length) };
            s->interp = SR_INTERP_PERSPECTIVE_FLAT_NORMAL;
            s->lambert = sr_shade_lambert_intensity(shade, n);
        }
        return;
    }
    s->interp = SR_INTERP_AFFINE;
    s->w = 1.0f / s->iw0;
    if (!lambert)
        return;
    float n[3];
    for (int k = 0; k < 3; k++) {
        if (s->dvar1[at + k] != 0.0f || s->dvar2[at + k] != 0.0f)
            return;
        /* var0 + λ1·0 + λ2·0 is var0 up to the sign of a zero, which the
         * intensity does not see. */
        n[k] = s->var0[at + k] * s->w;
    }
    s->interp = SR_INTERP_FLAT_NORMAL;
    s->lambert = sr_shade_lambert_intensity(shade, n);
}

uint64_t sr_raster_triangle(sr_framebuffer *fb, sr_raster_rect rect, int subpixel_bits, sr_shade mode,
                            const sr_shade_context *shade, const sr_screen_vertex tri[3], int64_t area2,
                            uint32_t triangle_id)
{
    bool simd;
    uint64_t fragments = sr_raster_triangle_on(fb, rect, subpixel_bits, mode, shade,
                                               (const sr_screen_vertex *const[3]){ &tri[0], &tri[1], &tri[2] },
                                               area2, triangle_id, &simd),
             draws = 0;
    sr_tiny_queue_flush(&fragments, &draws);
    return fragments;
}

/* sr_raster_setup, inlined where the box was just found: passed by value
 * to a call, gcc spilled it to the stack and read it back 16 bytes at a
 * time from two 8-byte stores, a store-forwarding stall per triangle. The
 * edges and a tiny box's mask are inlined into it too, and so are the
 * depth plane, the interpolants and, after it, the branch that hands a
 * tiny triangle to the tiny queue (setup_draw): a dense mesh sets up a
 * triangle for every pixel or two, so each call there is paid per pixel
 * (docs/performance.md, "From slot to set-up"). */
static SR_ALWAYS_INLINE bool setup_in(const sr_screen_vertex *const tri[3], int64_t area2, sr_raster_rect box,
                                      int subpixel_bits, sr_shade mode, bool cut, const sr_shade_context *shade,
                                      bool mask_known, uint64_t mask, setup *s)
{
    const sr_screen_vertex *v[3];
    order_clockwise(tri, area2, v);
    /* With the mask known, a mode that reads no varyings has no use for the
     * edges: the mask is the coverage (tiny_loop), and the depth plane
     * comes from the vertices. */
    bool varyings = mode_reads_varyings(mode) || cut;
    if (mask_known && !varyings) {
        s->bits = subpixel_bits;
        s->box = box;
    } else {
        setup_make(v, box, subpixel_bits, s);
    }
    /* A tiny box's pixels are tested first, so a triangle that covers none
     * of them (many of a dense mesh's) skips the depth plane; the
     * binned path tests them while binning and passes the mask on. */
    bool tiny = box_is_tiny(box);
    s->tiny = !tiny ? 0 : mask_known ? mask : tiny_coverage(s);
    sr_box_cover c = tiny ? (s->tiny ? SR_COVER_PARTIAL : SR_COVER_NONE) : sr_raster_classify(s, box);
    if (c == SR_COVER_NONE)
        return false;
    int64_t area2_abs = area2 > 0 ? area2 : -area2;
    interpolants_make(v, area2_abs, varyings ? shade->layout.count : 0, s);
    s->covered = c == SR_COVER_ALL;
    interp_choose(s, v, area2_abs, mode, shade);
    return true;
}

/* A stored set-up serves every material's triangle: in a draw that cuts
 * by texels (its layout has uvs in a mode that reads none), with the
 * varyings. */
bool sr_raster_setup(const sr_screen_vertex *const tri[3], int64_t area2, sr_raster_rect box, int subpixel_bits,
                     sr_shade mode, const sr_shade_context *shade, setup *s)
{
    return setup_in(tri, area2, box, subpixel_bits, mode, shade->layout.uv >= 0, shade, false, 0, s);
}

bool sr_raster_box_is_tiny(sr_raster_rect box)
{
    return box_is_tiny(box);
}

uint64_t sr_raster_tiny_mask(const sr_screen_vertex *const tri[3], int64_t area2, sr_raster_rect box,
                             int subpixel_bits)
{
    const sr_screen_vertex *v[3];
    setup s;
    order_clockwise(tri, area2, v);
    setup_make(v, box, subpixel_bits, &s);
    return tiny_coverage(&s);
}

/* A set-up triangle that the tiny queue did not take: what is queued is
 * tested and shaded first (what comes later tests against it and draws
 * over it; a mode without varyings
 * queues nothing, and the queue is empty between draws), then a kernel or
 * the scalar loop draws it. */
static uint64_t draw_unqueued(sr_framebuffer *fb, const setup *s, sr_shade mode, const sr_shade_context *shade,
                              uint32_t triangle_id, bool *simd)
{
    if (mode_reads_varyings(mode))
        sr_tiny_queue_drain();
    int width = s->box.x1 - s->box.x0;
    sr_span_kernel kernel = box_is_tiny(s->box) ? NULL : sr_span_kernel_for(shade, mode, fb->reversed_z, fb->ids, width);
    *simd = kernel && edges_fit_double(s);
    if (*simd)
        return kernel(s, shade, fb, triangle_id);
    if (mode == SR_RASTER_COUNT_HITS) /* past the enum's cases, so not in the switch */
        return raster_pixels(s, fb, SR_RASTER_COUNT_HITS, false, false, false, SR_INTERP_PERSPECTIVE, shade,
                             triangle_id);
    switch (mode) {
    case SR_SHADE_ID:      return raster_mode(s, fb, SR_SHADE_ID, false, shade, triangle_id);
    case SR_SHADE_COLOR:   return raster_mode(s, fb, SR_SHADE_COLOR, false, shade, triangle_id);
    case SR_SHADE_NORMAL:  return raster_mode(s, fb, SR_SHADE_NORMAL, false, shade, triangle_id);
    case SR_SHADE_TEXTURE: return raster_mode(s, fb, SR_SHADE_TEXTURE, false, shade, triangle_id);
    case SR_SHADE_LAMBERT: return raster_mode(s, fb, SR_SHADE_LAMBERT, false, shade, triangle_id);
    default:               return raster_mode(s, fb, SR_SHADE_DEPTH, false, shade, triangle_id);
    }
}

/* A set-up triangle of a material cut by its texels in id, depth, normal
 * or colour shading (sr_shade_context.cut): the scalar loop with the alpha
 * test, after what the tiny queue holds (as draw_unqueued). Never a kernel
 * or the queue, so every per-pixel loop and thread count draws it alike;
 * out of line, so the loops of a draw without such a material are those
 * of a draw without materials. */
static __attribute__((noinline)) uint64_t draw_cut(sr_framebuffer *fb, const setup *s, sr_shade mode,
                                                   const sr_shade_context *shade, uint32_t triangle_id)
{
    if (mode_reads_varyings(mode))
        sr_tiny_queue_drain();
    switch (mode) {
    case SR_SHADE_ID:     return raster_mode(s, fb, SR_SHADE_ID, true, shade, triangle_id);
    case SR_SHADE_COLOR:  return raster_mode(s, fb, SR_SHADE_COLOR, true, shade, triangle_id);
    case SR_SHADE_NORMAL: return raster_mode(s, fb, SR_SHADE_NORMAL, true, shade, triangle_id);
    default:              return raster_mode(s, fb, SR_SHADE_DEPTH, true, shade, triangle_id);
    }
}

/* draw_cut from the vertices: set up with the varyings its alpha test
 * reads. Cold: kept out of the way of the entry points' usual path. */
static __attribute__((noinline, cold)) uint64_t
cut_triangle(sr_framebuffer *fb, sr_raster_rect box, int subpixel_bits, sr_shade mode, const sr_shade_context *shade,
             const sr_screen_vertex *const tri[3], int64_t area2, uint32_t triangle_id, bool mask_known, uint64_t mask)
{
    setup s;
    if (!setup_in(tri, area2, box, subpixel_bits, mode, true, shade, mask_known, mask, &s))
        return 0;
    return draw_cut(fb, &s, mode, shade, triangle_id);
}

/* sr_raster_setup_draw, inlined where a triangle is set up and drawn at
 * once: a tiny triangle (the common case of a dense mesh) goes from its
 * set-up to the tiny queue's push with one call, not two. */
static SR_ALWAYS_INLINE uint64_t setup_draw(sr_framebuffer *fb, const setup *s, sr_shade mode,
                                            const sr_shade_context *shade, uint32_t triangle_id, bool *simd)
{
    if (s->tiny && s->interp == SR_INTERP_PERSPECTIVE && mode_reads_varyings(mode) &&
        sr_tiny_queue_push(s, fb, mode, shade, triangle_id)) {
        *simd = false; /* the queue counts its draws and fragments when it is shaded */
        return 0;
    }
    return draw_unqueued(fb, s, mode, shade, triangle_id, simd);
}

/* The rows a box that is not tiny prefetches (FETCHED_ROWS) before its
 * set-up, from the framebuffer drawn into directly, not a tile's: its
 * first depth and color line of each row (and ids line, where fb has
 * them), the color and ids for writing. The
 * kernels' depth loads waited on memory, and the compare after them was
 * where the kernels' time went: fetched here, they arrive during the
 * set-up and the tiny queue's shading. A tile's rows are in the cache
 * already (docs/performance.md, "The direct path" and "The limits"). */
#define FETCHED_ROWS 32

static SR_ALWAYS_INLINE uint64_t triangle_in_box(sr_framebuffer *fb, sr_raster_rect box, int subpixel_bits,
                                                 sr_shade mode, const sr_shade_context *shade,
                                                 const sr_screen_vertex *const tri[3], int64_t area2,
                                                 uint32_t triangle_id, bool mask_known, uint64_t mask,
                                                 bool fetch_rows, bool *simd)
{
    *simd = false;
    /* Most triangles of a dense mesh cover no pixel centre: find that out
     * before any setup. */
    if (box.x0 >= box.x1 || box.y0 >= box.y1)
        return 0;
    shade = sr_shade_context_of(shade, triangle_id);
    if (shade->cut != SR_CUT_NONE)
        return shade->cut == SR_CUT_TEXELS
                   ? cut_triangle(fb, box, subpixel_bits, mode, shade, tri, area2, triangle_id, mask_known, mask)
                   : 0;
    if (fetch_rows && !box_is_tiny(box)) {
        /* In the body: gcc drops a call of a function of prefetches. */
        int rows = box.y1 - box.y0 < FETCHED_ROWS ? box.y1 - box.y0 : FETCHED_ROWS;
        size_t first = (size_t)box.y0 * (size_t)fb->width + (size_t)box.x0, at = first;
        for (int r = 0; r < rows; r++, at += (size_t)fb->width) {
            __builtin_prefetch(fb->depth + at);
            __builtin_prefetch(fb->color + at, 1);
        }
        for (int r = 0; fb->ids && r < rows; r++, first += (size_t)fb->width)
            __builtin_prefetch(fb->ids + first, 1);
    }
    setup s;
    if (!setup_in(tri, area2, box, subpixel_bits, mode, false, shade, mask_known, mask, &s))
        return 0;
    return setup_draw(fb, &s, mode, shade, triangle_id, simd);
}

uint64_t sr_raster_triangle_in_box(sr_framebuffer *fb, sr_raster_rect box, int subpixel_bits, sr_shade mode,
                                   const sr_shade_context *shade, const sr_screen_vertex *const tri[3],
                                   int64_t area2, uint32_t triangle_id, bool *simd)
{
    return triangle_in_box(fb, box, subpixel_bits, mode, shade, tri, area2, triangle_id, false, 0, false, simd);
}

uint64_t sr_raster_tiny_triangle(sr_framebuffer *fb, sr_raster_rect box, int subpixel_bits, sr_shade mode,
                                 const sr_shade_context *shade, const sr_screen_vertex *const tri[3], int64_t area2,
                                 uint64_t mask, uint32_t triangle_id, bool *simd)
{
    return triangle_in_box(fb, box, subpixel_bits, mode, shade, tri, area2, triangle_id, true, mask, false, simd);
}

uint64_t sr_raster_triangle_on(sr_framebuffer *fb, sr_raster_rect rect, int subpixel_bits, sr_shade mode,
                               const sr_shade_context *shade, const sr_screen_vertex *const tri[3], int64_t area2,
                               uint32_t triangle_id, bool *simd)
{
    return triangle_in_box(fb, scan_box(tri, rect, subpixel_bits), subpixel_bits, mode, shade, tri, area2,
                           triangle_id, false, 0, true, simd);
}

/* The one pixel of a box whose centre the triangle covers, in a mode
 * without varyings: the depth plane and fill_pixel, as tiny_loop takes
 * bit 0 of a one-bit mask, with none of the set-up and dispatch a box of
 * several pixels needs. Half of what a dense scan draws is such a pixel. */
static SR_ALWAYS_INLINE uint64_t plain_pixel(sr_framebuffer *fb, sr_raster_rect box, int subpixel_bits,
                                             sr_shade mode, const sr_shade_context *shade,
                                             const sr_screen_vertex *const tri[3], int64_t area2, uint32_t id)
{
    const sr_screen_vertex *v[3];
    order_clockwise(tri, area2, v);
    setup s;
    s.bits = subpixel_bits;
    depth_plane(v, area2, &s);
    size_t at = (size_t)box.y0 * (size_t)fb->width + (size_t)box.x0;
    float z_row = sr_row_z(&s, box.y0), k = (float)(box.x0 - s.ref_x);
    bool greater = fb->reversed_z;
    sr_interp interp = SR_INTERP_PERSPECTIVE;
    if (fb->ids)
        return greater ? fill_pixel(&s, fb, mode, false, true, true, interp, shade, id, at, z_row, k, 0, 0)
                       : fill_pixel(&s, fb, mode, false, false, true, interp, shade, id, at, z_row, k, 0, 0);
    return greater ? fill_pixel(&s, fb, mode, false, true, false, interp, shade, id, at, z_row, k, 0, 0)
                   : fill_pixel(&s, fb, mode, false, false, false, interp, shade, id, at, z_row, k, 0, 0);
}

uint64_t sr_raster_one_pixel(sr_framebuffer *fb, sr_raster_rect rect, int subpixel_bits, sr_shade mode,
                             const sr_shade_context *shade, const sr_screen_vertex *const tri[3], int64_t area2,
                             uint32_t triangle_id, bool *simd)
{
    if (mode_reads_varyings(mode))
        return triangle_in_box(fb, scan_box(tri, rect, subpixel_bits), subpixel_bits, mode, shade, tri, area2,
                               triangle_id, true, 1, false, simd);
    /* The box is one pixel of the framebuffer: its corner is scan_box's,
     * and a rect that misses it leaves scan_box's box empty. */
    *simd = false;
    sr_raster_rect box = one_pixel_box(tri, subpixel_bits);
    if (box.x0 < rect.x0 || box.x0 >= rect.x1 || box.y0 < rect.y0 || box.y0 >= rect.y1)
        return 0;
    shade = sr_shade_context_of(shade, triangle_id);
    /* Hidden whole: a draw that cuts by texels marks no one-pixel
     * triangles in these modes (draw.c, subpixel_lanes). */
    if (shade->cut != SR_CUT_NONE)
        return 0;
    switch (mode) {
    case SR_SHADE_ID:    return plain_pixel(fb, box, subpixel_bits, SR_SHADE_ID, shade, tri, area2, triangle_id);
    case SR_SHADE_DEPTH: return plain_pixel(fb, box, subpixel_bits, SR_SHADE_DEPTH, shade, tri, area2, triangle_id);
    default:             return plain_pixel(fb, box, subpixel_bits, SR_RASTER_COUNT_HITS, shade, tri, area2, triangle_id);
    }
}

void sr_raster_setup_share(setup *s, sr_raster_rect share, bool covered)
{
    s->box = share;
    s->covered = covered;
    s->tiny = 0; /* the mask is the whole box's */
}

uint64_t sr_raster_setup_draw(sr_framebuffer *fb, const setup *s, sr_shade mode, const sr_shade_context *shade,
                              uint32_t triangle_id, bool *simd)
{
    shade = sr_shade_context_of(shade, triangle_id);
    if (shade->cut != SR_CUT_NONE) {
        *simd = false;
        return shade->cut == SR_CUT_TEXELS ? draw_cut(fb, s, mode, shade, triangle_id) : 0;
    }
    return setup_draw(fb, s, mode, shade, triangle_id, simd);
}
