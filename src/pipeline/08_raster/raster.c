/* The scalar per-pixel loop, the lane fragments' loop and the dispatch of a set-up
 * triangle to them, the SIMD kernels or the tiny queue (raster.h); the
 * set-up itself is triangle_setup.h's, inlined into each entry point. */
#include <stdlib.h>
#include <string.h>

#include "pipeline/11_merge.h"
#include "raster.h"
#include "simd_select.h"
#include "tiny_queue.h"
#include "triangle_setup.h"

typedef sr_tri_setup setup;

static inline void varyings_at(const setup *s, sr_interp interp, float l1, float l2, float *var)
{
    float w = sr_interp_divides(interp) ? 1.0f / (s->iw0 + l1 * s->diw1 + l2 * s->diw2) : s->w;
    for (int k = 0; k < s->varyings; k++)
        var[k] = (s->var0[k] + l1 * s->dvar1[k] + l2 * s->dvar2[k]) * w;
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
fill_fragment(const setup *s, sr_framebuffer *fb, sr_shade mode, bool cut, bool greater, bool with_ids,
              sr_interp interp, const sr_shade_context *shade, uint32_t id, size_t at, float z, int64_t e1, int64_t e2)
{
    if (mode == SR_RASTER_COUNT_HITS) {
        fb->color[at]++;
        return 1;
    }
    if (!sr_depth_passes(z, fb->depth[at], greater))
        return 0;
    float var[SR_MAX_VARYINGS];
    if (sr_mode_reads_varyings(mode) || cut) {
        varyings_at(s, interp, (float)e1 * s->inv_area2, (float)e2 * s->inv_area2, var);
        /* A MASK material's fragment under its alpha floor writes nothing. */
        if (shade->alpha_min && !sr_shade_alpha_passes(shade, var))
            return 0;
    }
    if (shade->merges) { /* a draw that blends or keeps its depth (11_merge.h) */
        bool coloured = mode != SR_SHADE_DEPTH;
        sr_merge_fragment(fb, shade, at, z, with_ids, id, coloured,
                          coloured ? fragment_colour(s, mode, interp, shade, var, id) : 0,
                          coloured && sr_mode_reads_varyings(mode) ? sr_merge_alpha(shade, var) : shade->alpha_scale);
        return 1;
    }
    fb->depth[at] = z;
    if (with_ids)
        fb->ids[at] = id + 1u;
    if (mode != SR_SHADE_DEPTH)
        fb->color[at] = fragment_colour(s, mode, interp, shade, var, id);
    return 1;
}

/* fill_fragment at the depth the plane gives pixel k of a row whose
 * reference pixel's depth is z_row. */
static inline __attribute__((always_inline)) uint64_t
fill_pixel(const setup *s, sr_framebuffer *fb, sr_shade mode, bool cut, bool greater, bool with_ids, sr_interp interp,
           const sr_shade_context *shade, uint32_t id, size_t at, float z_row, float k, int64_t e1, int64_t e2)
{
    float z = mode == SR_RASTER_COUNT_HITS ? 0.0f : sr_depth_at(s, z_row, k);
    return fill_fragment(s, fb, mode, cut, greater, with_ids, interp, shade, id, at, z, e1, e2);
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
         * when the mask came from binning (sr_setup_triangle). */
        bool edges = sr_mode_reads_varyings(mode) || cut;
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
    if ((sr_mode_reads_varyings(mode) || cut) && !sr_interp_divides(s->interp))
        return raster_interp(s, fb, mode, cut, SR_INTERP_AFFINE, shade, id);
    return raster_interp(s, fb, mode, cut, SR_INTERP_PERSPECTIVE, shade, id);
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

/* A set-up triangle that the tiny queue did not take: what is queued is
 * tested and shaded first (what comes later tests against it and draws
 * over it; a mode without varyings
 * queues nothing, and the queue is empty between draws), then a kernel or
 * the scalar loop draws it. */
static uint64_t draw_unqueued(sr_framebuffer *fb, const setup *s, sr_shade mode, const sr_shade_context *shade,
                              uint32_t triangle_id, bool *simd)
{
    if (sr_mode_reads_varyings(mode))
        sr_tiny_queue_drain();
    int width = s->box.x1 - s->box.x0;
    sr_span_kernel kernel =
        sr_raster_box_is_tiny(s->box) ? NULL : sr_span_kernel_for(shade, mode, fb->reversed_z, fb->ids, width);
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
    if (sr_mode_reads_varyings(mode))
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
    if (!sr_setup_triangle(tri, area2, box, subpixel_bits, mode, true, shade, mask_known, mask, &s))
        return 0;
    return draw_cut(fb, &s, mode, shade, triangle_id);
}

/* sr_raster_setup_draw, inlined where a triangle is set up and drawn at
 * once: a tiny triangle (the common case of a dense mesh) goes from its
 * set-up to the tiny queue's push with one call, not two. */
static SR_ALWAYS_INLINE uint64_t setup_draw(sr_framebuffer *fb, const setup *s, sr_shade mode,
                                            const sr_shade_context *shade, uint32_t triangle_id, bool *simd)
{
    if (s->tiny && s->interp == SR_INTERP_PERSPECTIVE && sr_mode_reads_varyings(mode) &&
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
    if (fetch_rows && !sr_raster_box_is_tiny(box)) {
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
    if (!sr_setup_triangle(tri, area2, box, subpixel_bits, mode, false, shade, mask_known, mask, &s))
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
    return triangle_in_box(fb, sr_raster_scan_box_of(tri, rect, subpixel_bits), subpixel_bits, mode, shade, tri,
                           area2, triangle_id, false, 0, true, simd);
}

/* The fragments of triangles the sub-pixel lanes found small, in a mode
 * without varyings, as tiny_loop draws their masks: fill_fragment at the
 * pixels and depths sr_lane_pixels_* found, with none of the set-up a
 * triangle needs, in one loop for the run. */
static SR_ALWAYS_INLINE uint64_t fragment_run(sr_framebuffer *fb, sr_shade mode, bool greater, bool with_ids,
                                              const sr_shade_context *shade, const uint32_t *id, const size_t *at,
                                              const float *z, int n)
{
    static const setup unused; /* read only for varyings, which these modes have none of */
    uint64_t fragments = 0;
    for (int i = 0; i < n; i++) {
        const sr_shade_context *c = sr_shade_context_of(shade, id[i]);
        /* Hidden whole: a draw that cuts by texels marks no small
         * triangles in these modes (draw.c, subpixel_lanes). */
        if (c->cut == SR_CUT_NONE)
            fragments += fill_fragment(&unused, fb, mode, false, greater, with_ids, SR_INTERP_PERSPECTIVE, c, id[i],
                                       at[i], z[i], 0, 0);
    }
    return fragments;
}

static SR_ALWAYS_INLINE uint64_t fragment_tests(sr_framebuffer *fb, sr_shade mode, const sr_shade_context *shade,
                                                const uint32_t *id, const size_t *at, const float *z, int n)
{
    if (fb->ids)
        return fb->reversed_z ? fragment_run(fb, mode, true, true, shade, id, at, z, n)
                              : fragment_run(fb, mode, false, true, shade, id, at, z, n);
    return fb->reversed_z ? fragment_run(fb, mode, true, false, shade, id, at, z, n)
                          : fragment_run(fb, mode, false, false, shade, id, at, z, n);
}

uint64_t sr_raster_one_pixel(sr_framebuffer *fb, sr_raster_rect rect, int subpixel_bits, sr_shade mode,
                             const sr_shade_context *shade, const sr_screen_vertex *const tri[3], int64_t area2,
                             uint32_t triangle_id, bool *simd)
{
    return triangle_in_box(fb, sr_raster_scan_box_of(tri, rect, subpixel_bits), subpixel_bits, mode, shade, tri,
                           area2, triangle_id, true, 1, false, simd);
}

uint64_t sr_raster_lane_fragments(sr_framebuffer *fb, sr_shade mode, const sr_shade_context *shade,
                                  const uint32_t *triangle_id, const size_t *at, const float *z, int n)
{
    switch (mode) {
    case SR_SHADE_ID:    return fragment_tests(fb, SR_SHADE_ID, shade, triangle_id, at, z, n);
    case SR_SHADE_DEPTH: return fragment_tests(fb, SR_SHADE_DEPTH, shade, triangle_id, at, z, n);
    default:             return fragment_tests(fb, SR_RASTER_COUNT_HITS, shade, triangle_id, at, z, n);
    }
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
