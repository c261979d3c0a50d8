/* clip_exact.h — the clipper's exact-enough intersection, for edges whose
 * end points are far larger than the visible piece (a triangle of extent
 * 1e30 seen from a few units away): plane distances and the numerator
 * d_in·b − d_out·a are carried as exact floating-point expansions (two-sum,
 * two-product, Shewchuk's grow-expansion, expansion.h) and rounded once at
 * the end. */
#ifndef SOFTRAST_CLIP_EXACT_H
#define SOFTRAST_CLIP_EXACT_H

#include "clip.h"

/* The longest distance expansion: far under the depth model, w − a·w − b. */
#define SR_CLIP_DISTANCE_TERMS 3

/* The plane distance of a clip-space point, exactly, as an expansion d[0..n)
 * (smallest first); under the depth model (depth on, NULL: off) near and far
 * come from w. Returns n. */
int sr_clip_distance_exact(sr_clip_plane plane, const float *c, const sr_clip_depth *depth,
                           double d[SR_CLIP_DISTANCE_TERMS]);

void sr_clip_intersect_exact(sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                             int floats, const sr_clip_depth *depth, sr_vertex_out *cut);

#endif
