/* raster.h — stages 8 and 9: triangle setup, coverage, depth test.
 *
 * Edge functions are evaluated exactly in 64-bit integers on vertices snapped
 * to 1/256 pixel (or another SR_MIN..SR_MAX_SUBPIXEL_BITS precision), at pixel centres (i + 0.5, j + 0.5). A centre on an edge is
 * covered only if the edge is a top or left edge (the top-left rule of
 * Direct3D and OpenGL), so pixels on an edge shared by two triangles are drawn
 * exactly once. Depth is z_ndc interpolated linearly in screen space, tested
 * LESS (GREATER in a reversed_z framebuffer); varyings are interpolated perspective-correctly through 1/w, and the
 * loop is specialised per shading mode. Rows of triangles at least a few
 * pixels wide go 4, 8 or 16 pixels at a time through SIMD kernels (SSE2,
 * AVX2, AVX-512, chosen at run time; sr_shade_context.simd) that compute
 * exactly what the scalar loop computes, bit for bit.
 */
#ifndef SOFTRAST_PIPELINE_RASTER_H
#define SOFTRAST_PIPELINE_RASTER_H

#include <stdint.h>

#include "softrast/softrast.h"
#include "raster_setup.h"


/* The pixels whose centres can lie in the triangle, clamped to rect (the
 * rectangle, never the vertices: moving one would move a shared edge);
 * empty (x0 >= x1 or y0 >= y1) when none can. */
sr_raster_rect sr_raster_scan_box(const sr_screen_vertex tri[3], sr_raster_rect rect, int subpixel_bits);


/* The rasterizer's mode for sr_draw_study.count_hits, past the public
 * shading modes: every covered pixel adds 1 to its color, with no depth test
 * or write and no varyings. No SIMD kernel has it, so the scalar loop draws. */
#define SR_RASTER_COUNT_HITS ((sr_shade)SR_SHADE_COUNT)

/* Draws one triangle of nonzero signed area2 (either winding) into fb within
 * rect, its vertices in units of 2^-subpixel_bits pixel (SR_SUBPIXEL_BITS
 * unless the draw asked for another precision) in a shading mode or
 * SR_RASTER_COUNT_HITS; returns the number of fragments that passed the
 * depth test. */
uint64_t sr_raster_triangle(sr_framebuffer *fb, sr_raster_rect rect, int subpixel_bits, sr_shade mode,
                            const sr_shade_context *shade, const sr_screen_vertex tri[3], int64_t area2,
                            uint32_t triangle_id);

/* sr_raster_triangle and sr_raster_scan_box on vertices the caller holds
 * elsewhere (no copies); the first also tells whether a SIMD kernel drew.
 * Neither it nor the calls below count a tiny triangle the tiny queue
 * takes: its fragments and draw count when the queue is shaded
 * (sr_tiny_queue_flush). */
uint64_t sr_raster_triangle_on(sr_framebuffer *fb, sr_raster_rect rect, int subpixel_bits, sr_shade mode,
                               const sr_shade_context *shade, const sr_screen_vertex *const tri[3], int64_t area2,
                               uint32_t triangle_id, bool *simd);
sr_raster_rect sr_raster_scan_box_of(const sr_screen_vertex *const tri[3], sr_raster_rect rect, int subpixel_bits);

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

/* Draws a set-up triangle's pixels in s->box (a SIMD kernel where the box
 * is wide enough and its edge values fit doubles: *simd) and returns the
 * fragments that passed the depth test. */
uint64_t sr_raster_setup_draw(sr_framebuffer *fb, const sr_tri_setup *s, sr_shade mode,
                              const sr_shade_context *shade, uint32_t triangle_id, bool *simd);

/* sr_raster_triangle_on with the scan box already found (sr_raster_scan_box_of
 * clamped to the rectangle drawn): the tile of a one-tile triangle finds it
 * from the vertices it reads anyway. */
uint64_t sr_raster_triangle_in_box(sr_framebuffer *fb, sr_raster_rect box, int subpixel_bits, sr_shade mode,
                                   const sr_shade_context *shade, const sr_screen_vertex *const tri[3],
                                   int64_t area2, uint32_t triangle_id, bool *simd);

/* Whether a scan box is tiny (sr_tri_setup.tiny), and such a box's covered
 * pixel centres: the mask the set-up makes. The binned path tests a tiny
 * triangle within one tile while binning, drops it when the mask is empty
 * and draws it with sr_raster_tiny_triangle, which takes the mask (non-zero,
 * of a box that sr_raster_box_is_tiny) instead of testing again; in a mode
 * that reads no varyings it then makes no edges (e, step_x are left unset:
 * the tiny loop reads them only for varyings). */
bool sr_raster_box_is_tiny(sr_raster_rect box);
uint64_t sr_raster_tiny_mask(const sr_screen_vertex *const tri[3], int64_t area2, sr_raster_rect box,
                             int subpixel_bits);
uint64_t sr_raster_tiny_triangle(sr_framebuffer *fb, sr_raster_rect box, int subpixel_bits, sr_shade mode,
                                 const sr_shade_context *shade, const sr_screen_vertex *const tri[3], int64_t area2,
                                 uint64_t mask, uint32_t triangle_id, bool *simd);

/* sr_raster_triangle_on for a triangle known to cover the one pixel centre
 * its scan box holds (the sub-pixel lanes' one_pixel): drawn as
 * sr_raster_tiny_triangle draws that box's one-bit mask, or not at all
 * where the box is outside rect. */
uint64_t sr_raster_one_pixel(sr_framebuffer *fb, sr_raster_rect rect, int subpixel_bits, sr_shade mode,
                             const sr_shade_context *shade, const sr_screen_vertex *const tri[3], int64_t area2,
                             uint32_t triangle_id, bool *simd);

#endif
