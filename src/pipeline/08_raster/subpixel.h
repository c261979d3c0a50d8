/* subpixel.h — the triangles of a dense mesh that cover no pixel centre,
 * found many at a time before any set-up. Not public API.
 *
 * Most triangles of a scan seen at a vision user's size are smaller than a
 * pixel: their scan box (sr_raster_scan_box) holds no pixel centre, or one
 * that they miss. Each such triangle changes nothing but the draw's counts,
 * culled or drawn as stage 7 counts it, yet one at a time it paid for a
 * call into the rasterizer, its box and its edges. Here four, eight or sixteen
 * triangles go through those tests at once, a triangle per lane of 32-bit integers (as
 * Intel's Masked Occlusion Culling rejects many triangles per instruction),
 * and the caller sends only the others on, those a mode without varyings
 * draws from their boxes' centres (lane_pixels.h) aside, to the
 * per-triangle set-up.
 *
 * Exactness: a lane decides only a triangle whose vertices span less than
 * SR_SUBPIXEL_SPAN (four) pixels on each axis, inside every plane (its
 * coordinates below 2^30: SR_FIXED_POINT_BITS). Every difference of its
 * coordinates, and of a pixel centre of its box and a vertex (the box's
 * centres lie within the vertices' extent), is below 2^14 at up to
 * SR_SUBPIXEL_LANES_MAX_BITS subpixel bits, so every product of two is
 * below 2^28 and every sum of two products fits a 32-bit integer. Its
 * signed area, its scan box over the whole
 * framebuffer and, for a box of one pixel centre, the three edge functions
 * at that centre with the top-left rule are the exact integers that stage 7
 * and the set-up compute (07_cull.h, triangle_setup.h), so the counts and pixels
 * are those of the one-at-a-time path at every SIMD level and thread count.
 * A box empty over the framebuffer is empty over any tile or band of rows
 * too, so every path may drop such a triangle. */
#ifndef SOFTRAST_PIPELINE_SUBPIXEL_H
#define SOFTRAST_PIPELINE_SUBPIXEL_H

#include <stdbool.h>
#include <stdint.h>

#include "subpixel_lanes.h"

/* The verdict on lanes [0, n) of b, n <= SR_SUBPIXEL_BATCH, at most
 * rules->bits <= SR_SUBPIXEL_LANES_MAX_BITS; lanes past n are ignored. */
sr_subpixel_verdict sr_subpixel_reject(const sr_subpixel_batch *b, int n, const sr_subpixel_rules *rules);

#endif
