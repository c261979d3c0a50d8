/* clip_exact.h — the clipper's exact-enough intersection, for edges whose
 * end points are far larger than the visible piece (a triangle of extent
 * 1e30 seen from a few units away): plane distances and the numerator
 * d_in·b − d_out·a are carried as exact floating-point expansions (two-sum,
 * two-product, Shewchuk's grow-expansion) and rounded once at the end. */
#ifndef SOFTRAST_CLIP_EXACT_H
#define SOFTRAST_CLIP_EXACT_H

#include "softrast/clip.h"

void sr_clip_intersect_exact(sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                             int floats, sr_vertex_out *cut);

#endif
