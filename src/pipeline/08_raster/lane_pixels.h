/* lane_pixels.h — the pixels and depths of the triangles whose scan box
 * the sub-pixel lanes found small (sr_subpixel_verdict: one_pixel, a box
 * of one centre they cover; small_box, up to SR_SUBPIXEL_SPAN ×
 * SR_SUBPIXEL_SPAN centres), drawn in a mode without varyings: a window's
 * found four at a time, a triangle a lane, before any is drawn; then
 * they are depth-tested and written in submission order, each run between
 * two other triangles in one loop (sr_raster_lane_fragments, raster.h). Not
 * public API.
 *
 * Half of what a dense scan draws is a triangle of one pixel, and most of
 * what a mesh of a few hundred thousand triangles draws at a vision
 * user's size covers one to four. One at a time, each paid for a call
 * into the rasterizer, its edges and mask, a depth plane fitted in scalar
 * double with its division, and its depth loads' misses with the branches
 * on them. Here four planes share each division, the edges are tested at
 * a box's centres in lanes, and a window's fragments are tested in one
 * loop (docs/performance.md, "Sub-pixel triangles").
 *
 * Exactness: a lane takes triangle_setup.h's steps (sr_order_clockwise,
 * sr_raster_scan_box_of, the edge functions with the top-left rule,
 * sr_depth_plane on |area2| with its sliver branch, sr_row_z,
 * sr_depth_at) in the same integer, double and float operations in the
 * same order, with no fused multiply-add (the Makefile builds every file
 * with -ffp-contract=off), so each pixel and depth is the set-up's. */
#ifndef SOFTRAST_PIPELINE_LANE_PIXELS_H
#define SOFTRAST_PIPELINE_LANE_PIXELS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "raster_setup.h"
#include "subpixel_lanes.h"

/* The triangles a call takes at most: those of a window of kept slots. */
#define SR_LANE_PIXELS_BATCH 64
/* The centres of a box, row by row: bit r · SR_SUBPIXEL_SPAN + c is the
 * centre c pixels right of the box's first and r rows down. */
#define SR_LANE_PIXELS_CENTRES (SR_SUBPIXEL_SPAN * SR_SUBPIXEL_SPAN)

/* Triangle j's scan box within the rectangle drawn: which of its centres
 * the triangle covers (none where the box lies outside the rectangle),
 * and the pixel index and depth of the first two covered (unset past
 * those covered): a triangle covers one or two of the sixteen its lanes
 * test, so the depths are taken for those alone. The others come from
 * sr_lane_pixel_at and sr_lane_pixel_z, by the box's first pixel and its
 * depth plane there: its rows' and columns' offsets from the reference
 * pixel, and the plane's z there and changes a row and a pixel. */
typedef struct sr_lane_pixels {
    uint32_t covered[SR_LANE_PIXELS_BATCH];
    size_t at[2][SR_LANE_PIXELS_BATCH];
    float z[2][SR_LANE_PIXELS_BATCH];
    size_t corner[SR_LANE_PIXELS_BATCH];
    int32_t first_row[SR_LANE_PIXELS_BATCH], first_k[SR_LANE_PIXELS_BATCH];
    double z_ref[SR_LANE_PIXELS_BATCH], dz_row[SR_LANE_PIXELS_BATCH];
    float dz_pixel[SR_LANE_PIXELS_BATCH];
} sr_lane_pixels;

/* The pixel index of centre c of triangle j's box (bit c of covered) in a
 * framebuffer `width` pixels wide. */
static inline size_t sr_lane_pixel_at(const sr_lane_pixels *p, int j, unsigned c, size_t width)
{
    return p->corner[j] + c / SR_SUBPIXEL_SPAN * width + c % SR_SUBPIXEL_SPAN;
}

/* Its depth: sr_row_z at its row, then sr_depth_at along it. */
static inline float sr_lane_pixel_z(const sr_lane_pixels *p, int j, unsigned c)
{
    float z_row = (float)(p->z_ref[j] + p->dz_row[j] * (double)(p->first_row[j] + (int32_t)(c / SR_SUBPIXEL_SPAN)));
    return sr_depth_clamp(z_row + p->dz_pixel[j] * (float)(p->first_k[j] + (int32_t)(c % SR_SUBPIXEL_SPAN)));
}

/* The pixels and depths of each triangle tri[j], j < n <= SR_LANE_PIXELS_BATCH,
 * into out (and lanes of the last group past n), whose vertices are the
 * screen vertices tri[j][k]·stride bytes into screen: inside every plane,
 * its area nonzero and its vertices within SR_SUBPIXEL_SPAN pixels of each
 * other on each axis, at `bits` <= SR_SUBPIXEL_LANES_MAX_BITS subpixel
 * bits, over the rectangle `rect` of a framebuffer `width` pixels wide.
 * Bit j of one_pixel says tri[j] is a one_pixel triangle, which covers
 * its box's one centre: a group of four such is not tested, and any other
 * group is tested at as many rows and columns of centres as its largest
 * box holds. Built for SSE2, and for AVX2 (taken only where the draw's
 * SIMD level has it); the same bits. */
void sr_lane_pixels_sse2(const char *screen, size_t stride, const uint32_t (*tri)[3], int n, uint64_t one_pixel,
                         int bits, sr_raster_rect rect, int width, sr_lane_pixels *out);
void sr_lane_pixels_avx2(const char *screen, size_t stride, const uint32_t (*tri)[3], int n, uint64_t one_pixel,
                         int bits, sr_raster_rect rect, int width, sr_lane_pixels *out);

#endif
