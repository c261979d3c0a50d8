/* raster.h — stages 8 and 9: a triangle's coverage and depth test, its
 * pixels drawn after its set-up (triangle_setup.h).
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

/* Draws one triangle of nonzero signed area2 (either winding) into fb within
 * rect, its vertices in units of 2^-subpixel_bits pixel (SR_SUBPIXEL_BITS
 * unless the draw asked for another precision) in a shading mode or
 * SR_RASTER_COUNT_HITS; returns the number of fragments that passed the
 * depth test. */
uint64_t sr_raster_triangle(sr_framebuffer *fb, sr_raster_rect rect, int subpixel_bits, sr_shade mode,
                            const sr_shade_context *shade, const sr_screen_vertex tri[3], int64_t area2,
                            uint32_t triangle_id);

/* sr_raster_triangle on vertices the caller holds elsewhere (no copies),
 * telling also whether a SIMD kernel drew. Neither it nor the calls below
 * count a tiny triangle the tiny queue takes: its fragments and draw count
 * when the queue is shaded (sr_tiny_queue_flush). */
uint64_t sr_raster_triangle_on(sr_framebuffer *fb, sr_raster_rect rect, int subpixel_bits, sr_shade mode,
                               const sr_shade_context *shade, const sr_screen_vertex *const tri[3], int64_t area2,
                               uint32_t triangle_id, bool *simd);

/* Draws the pixels in s->box of a triangle set up by sr_raster_setup
 * (triangle_setup.h), with a SIMD kernel where the box is wide enough and
 * its edge values fit doubles (*simd), and returns the fragments that
 * passed the depth test. */
uint64_t sr_raster_setup_draw(sr_framebuffer *fb, const sr_tri_setup *s, sr_shade mode,
                              const sr_shade_context *shade, uint32_t triangle_id, bool *simd);

/* sr_raster_triangle_on with the scan box already found (sr_raster_scan_box_of
 * clamped to the rectangle drawn): the tile of a one-tile triangle finds it
 * from the vertices it reads anyway. */
uint64_t sr_raster_triangle_in_box(sr_framebuffer *fb, sr_raster_rect box, int subpixel_bits, sr_shade mode,
                                   const sr_shade_context *shade, const sr_screen_vertex *const tri[3],
                                   int64_t area2, uint32_t triangle_id, bool *simd);

/* sr_raster_triangle_in_box for a tiny box (sr_raster_box_is_tiny) whose
 * covered pixel centres the binned path found while binning
 * (sr_raster_tiny_mask, non-zero): it takes the mask instead of testing
 * again, and in a mode that reads no varyings makes no edges (e, step_x
 * are left unset: the tiny loop reads them only for varyings). */
uint64_t sr_raster_tiny_triangle(sr_framebuffer *fb, sr_raster_rect box, int subpixel_bits, sr_shade mode,
                                 const sr_shade_context *shade, const sr_screen_vertex *const tri[3], int64_t area2,
                                 uint64_t mask, uint32_t triangle_id, bool *simd);

/* sr_raster_triangle_on for a triangle known to cover the one pixel centre
 * its scan box holds (the sub-pixel lanes' one_pixel), in a mode with
 * varyings: drawn as sr_raster_tiny_triangle draws that box's one-bit
 * mask, or not at all where the box is outside rect. */
uint64_t sr_raster_one_pixel(sr_framebuffer *fb, sr_raster_rect rect, int subpixel_bits, sr_shade mode,
                             const sr_shade_context *shade, const sr_screen_vertex *const tri[3], int64_t area2,
                             uint32_t triangle_id, bool *simd);

/* The fragments of triangles the sub-pixel lanes found small, in a mode
 * without varyings (ID, DEPTH or counting hits), of triangle_id[i] at
 * pixel at[i] and depth z[i], i < n, as a batch found them
 * (lane_pixels.h): each depth-tested and written in order, as the tiny
 * loop would; returns the fragments that passed. */
uint64_t sr_raster_lane_fragments(sr_framebuffer *fb, sr_shade mode, const sr_shade_context *shade,
                                  const uint32_t *triangle_id, const size_t *at, const float *z, int n);

#endif
