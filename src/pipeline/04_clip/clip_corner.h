/* clip_corner.h — the point of a triangle on two clip planes, for a vertex
 * that a second plane cuts from the first plane's cut line.
 *
 * With P_k and Q_k the distances of the triangle's vertices to the two
 * planes, the weights c = P × Q give the corner Σ c_k·v_k / Σ c_k
 * (clip_exact.h). The weights depend on the positions alone and are taken
 * exactly, from the vertices in an order of their positions' bits, so a
 * corner is the same bits whichever vertex the triangle starts from,
 * whichever way it winds and whatever varyings it carries. A corner is made
 * only where every weight has the sign of their sum (Σ c_k != 0): the point
 * then lies in the triangle, its position is a convex combination of the
 * vertices' and each varying is interpolated with the same weights and kept
 * within the vertices' range. Otherwise (a degenerate triangle, lines that
 * are parallel in it, or a polygon edge that rounding put on the wrong
 * line) there is no corner and the caller clips the triangle edge by edge.
 */
#ifndef SOFTRAST_PIPELINE_CLIP_CORNER_H
#define SOFTRAST_PIPELINE_CLIP_CORNER_H

#include "pipeline/03_classify.h"

/* The corner of tri on `first` and `plane`, its position in double where
 * an error bound allows `tolerance` (NDC) and precision is adaptive, else
 * from exact expansions (numerator and denominator each rounded, then
 * divided: within a few ulp); floats = 4 + varyings. Placed on both planes.
 * Returns the precision of its position, or SR_CLIP_ADAPTIVE when there is
 * no corner (cut untouched). */
sr_clip_precision sr_clip_corner(const sr_vertex_out tri[3], sr_clip_plane first, sr_clip_plane plane, int floats,
                                 sr_clip_precision precision, double tolerance, const sr_clip_depth *depth,
                                 sr_vertex_out *cut);

/* The triangle's point on two of its lines (sr_polygon.line: an edge, or a
 * plane's cut line) from its vertices' clip positions in double, tri_d:
 * Σ c_k·v_k / Σ c_k with c = P × Q, the lines' vectors over the vertices
 * (an edge k's is the unit vector of vertex k + 2, a plane's its
 * distances, sr_clip_distance_d), all in double. On two edges it is their
 * common vertex, bit for bit; on an edge and a plane the edge's cut
 * (Q_j·v_i − Q_i·v_j) / (Q_j − Q_i), its weights exact from the
 * distances. For the depth of a cut vertex (docs/precision.md): whatever
 * its weights' rounding, the point lies in the plane of tri_d's triangle.
 * Where the lines do not meet in one point (Σ c_k = 0) it is not finite. */
void sr_clip_point_on_lines_d(const double tri_d[3][4], int line1, int line2, const sr_clip_depth *depth,
                              double out[4]);

#endif
