/* clip_segment.h — stage 4 for a line: a segment clipped against the
 * planes in the OR of its end points' outcodes, with the triangle edge's
 * own arithmetic, so a line drawn over a triangle's edge is cut where the
 * triangle is.
 *
 * Under adaptive and exact precision a triangle cut by two planes or more
 * cuts every polygon edge that lies on one of its edges as that whole edge
 * (clip.h), and decides each cut vertex's side of a later plane on the
 * exact point it was rounded from. The segment does the same: each end
 * that leaves the clipper is either an end it was given or the cut of the
 * whole segment on one plane (sr_clip_intersect: the same precision choice
 * and the same bits as the triangle edge's cut, whichever way either runs),
 * and the side of a cut is decided exactly (sr_clip_exact_side on the
 * segment as a triangle whose third vertex repeats the first, whose edge 0
 * it is). The fixed float and double knobs cut edge by edge, from the end
 * an earlier plane left, as the triangle clipper does under them. Under a
 * depth model every cut's z follows its w (a·w + b rounded once, as a
 * triangle's cuts from two planes or more do); the pixels depend on x, y
 * and w only, which are the triangle edge's.
 */
#ifndef SOFTRAST_PIPELINE_CLIP_SEGMENT_H
#define SOFTRAST_PIPELINE_CLIP_SEGMENT_H

#include "clip.h"

/* An end that is the one given, not a cut. */
#define SR_SEGMENT_END_GIVEN (-1)

/* Clips the segment ends[0] -> ends[1] against the planes whose bits are set
 * in `planes`, into out[0..1], each end's plane in cut_plane[] (a plane
 * index, or SR_SEGMENT_END_GIVEN where out[k] is ends[k]); floats = 4 +
 * varyings. False when nothing is left: the segment is outside a plane,
 * or an end is left at w <= 0 (inside every plane that is the clip-space
 * origin: the segment runs through the eye and covers no pixel). */
bool sr_clip_segment(const sr_vertex_out ends[2], unsigned planes, int floats, const sr_clip_config *cfg,
                     sr_vertex_out out[2], int cut_plane[2]);

#endif
