/* one_pixel.h — the triangles the sub-pixel lanes found to cover the one
 * pixel centre of their scan box (sr_subpixel_verdict.one_pixel), drawn in
 * a mode without varyings: the pixels and depths of a batch's found four
 * at a time, a triangle a lane of double, before any is drawn; then they
 * are depth-tested and written in submission order, each run between two
 * other triangles in one loop (sr_raster_one_pixels, raster.h). Not
 * public API.
 *
 * Half of what a dense scan draws is such a triangle. One at a time, each
 * paid for a call into the rasterizer, a depth plane fitted in scalar
 * double with its division, and its depth load's miss with the branch on
 * it. Here four planes share each division, and a batch's pixels are
 * known before its first test, so the caller can prefetch them
 * (docs/performance.md, "Sub-pixel triangles").
 *
 * Exactness: a lane takes triangle_setup.h's steps for the one pixel
 * (sr_order_clockwise, sr_depth_plane on |area2| with its sliver branch,
 * sr_row_z, sr_depth_at) in the same double and float operations in the
 * same order, with no fused multiply-add (the Makefile builds every file
 * with -ffp-contract=off), so each depth is the bits the set-up gives. */
#ifndef SOFTRAST_PIPELINE_ONE_PIXEL_H
#define SOFTRAST_PIPELINE_ONE_PIXEL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "raster_setup.h"

/* The triangles a call takes at most: a batch of the verdicts. */
#define SR_ONE_PIXEL_BATCH 64

/* A one-pixel triangle's pixel: its index in the framebuffer, or
 * SR_ONE_PIXEL_OUTSIDE where it lies outside the rectangle drawn (a tile
 * or band of rows other than the caller's); and its depth there. */
#define SR_ONE_PIXEL_OUTSIDE SIZE_MAX
typedef struct sr_one_pixels {
    size_t at[SR_ONE_PIXEL_BATCH];
    float z[SR_ONE_PIXEL_BATCH];
} sr_one_pixels;

/* The pixel and depth of each triangle tri[j], j < n <= SR_ONE_PIXEL_BATCH,
 * into out->at[j] and out->z[j] (and lanes of the last group past n),
 * whose vertices are the screen vertices tri[j][k]·stride bytes into
 * screen: inside every plane, its area nonzero and its scan box over a
 * framebuffer `width` pixels wide holding one pixel centre, which it
 * covers (what the lanes' one_pixel promises), at `bits` subpixel bits.
 * Built for SSE2, and for AVX2 (taken only where the draw's SIMD level has
 * it); the same bits. */
void sr_one_pixel_depths_sse2(const char *screen, size_t stride, const uint32_t (*tri)[3], int n, int bits,
                              sr_raster_rect rect, int width, sr_one_pixels *out);
void sr_one_pixel_depths_avx2(const char *screen, size_t stride, const uint32_t (*tri)[3], int n, int bits,
                              sr_raster_rect rect, int width, sr_one_pixels *out);

#endif
