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
#include "shade.h"
#include "stages.h"

/* The tiled path draws in tiles that are strips of whole rows,
 * SR_TILE_ROWS(width) each: SR_TILE_ROWS_MAX, or fewer on a framebuffer
 * wider than SR_TILE_PIXELS / SR_TILE_ROWS_MAX so that a strip's color and
 * depth stay within SR_TILE_PIXELS pixels (docs/performance.md). Tests
 * and the fuzzer size their framebuffers by it. */
#define SR_TILE_ROWS_MAX 32
#define SR_TILE_PIXELS 65536
#define SR_TILE_ROWS(width) \
    ((width) <= SR_TILE_PIXELS / SR_TILE_ROWS_MAX ? SR_TILE_ROWS_MAX : SR_TILE_PIXELS / (width))

/* The pixels [x0, x1) × [y0, y1) a call may touch (the framebuffer, or a tile). */
typedef struct sr_raster_rect {
    int x0, y0, x1, y1;
} sr_raster_rect;

/* The pixels whose centres can lie in the triangle, clamped to rect (the
 * rectangle, never the vertices: moving one would move a shared edge);
 * empty (x0 >= x1 or y0 >= y1) when none can. */
sr_raster_rect sr_raster_scan_box(const sr_screen_vertex tri[3], sr_raster_rect rect, int subpixel_bits);

/* The per-pixel loop a request gets on this CPU: AUTO (or anything
 * unknown) is the best it has; one it lacks falls back to the best below
 * (AVX-512 to AVX2 to SSE2). Off x86-64 "sse2" is the compiler's 4-lane
 * vectors. */
sr_simd sr_raster_simd_resolve(sr_simd want);
const char *sr_simd_name(sr_simd simd); /* "auto", "scalar", "sse2", "avx2", "avx512" */
extern const char *const sr_simd_names[SR_SIMD_COUNT + 1]; /* indexed by sr_simd, NULL-terminated */

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

#endif
