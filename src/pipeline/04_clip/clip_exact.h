/* clip_exact.h — the clipper's exact-enough intersection, for edges whose
 * end points are far larger than the visible piece (a triangle of extent
 * 1e30 seen from a few units away): plane distances and the numerator
 * d_in·b − d_out·a are carried as exact floating-point expansions (two-sum,
 * two-product, Shewchuk's grow-expansion, expansion.h); numerator and
 * denominator are each rounded at the end, then divided (a few ulp). */
#ifndef SOFTRAST_CLIP_EXACT_H
#define SOFTRAST_CLIP_EXACT_H

#include "pipeline/03_classify.h"

/* The longest numerator expansion: two distances, each part times a float
 * coordinate as an exact product pair. */
#define SR_CLIP_NUMERATOR_TERMS (2 * SR_CLIP_DISTANCE_TERMS * 2)

/* An edge inside -> outside on a plane, ready for exact cuts: coordinate i
 * of the cut is (d_in·b − d_out·a) / (d_in − d_out), a and b the end
 * points' coordinates, the numerator (sr_clip_exact_numerator) and the
 * denominator exact expansions. */
typedef struct sr_clip_exact_edge {
    double d_in[SR_CLIP_DISTANCE_TERMS], neg_d_out[SR_CLIP_DISTANCE_TERMS];
    int d_in_terms, d_out_terms;
    double denominator[2 * SR_CLIP_DISTANCE_TERMS];
    int denominator_terms;
} sr_clip_exact_edge;

void sr_clip_exact_edge_of(sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                           const sr_clip_depth *depth, sr_clip_exact_edge *edge);

/* d_in·b − d_out·a as an expansion num[0..n); returns n. */
int sr_clip_exact_numerator(const sr_clip_exact_edge *edge, float a, float b, double num[SR_CLIP_NUMERATOR_TERMS]);

/* The cut vertex from sr_clip_exact_edge_of, each coordinate within a few ulp. */
void sr_clip_intersect_exact(sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                             int floats, const sr_clip_depth *depth, sr_vertex_out *cut);

/* The triangle's point on two planes, for a vertex cut by both: with P_k
 * and Q_k its vertices' distances to the planes, the weights c = P × Q
 * (c_0 = P_1·Q_2 − P_2·Q_1, ...) give the point Σ c_k·v_k / Σ c_k, whose
 * distance to either plane is 0. The weights and their sum are exact
 * expansions; Σ c_k is 0 when the planes' lines in the triangle are
 * parallel. */
#define SR_CLIP_CORNER_WEIGHT_TERMS (2 * 2 * SR_CLIP_DISTANCE_TERMS * SR_CLIP_DISTANCE_TERMS)
#define SR_CLIP_CORNER_NUMERATOR_TERMS (3 * 2 * SR_CLIP_CORNER_WEIGHT_TERMS)

typedef struct sr_clip_exact_corner {
    double weight[3][SR_CLIP_CORNER_WEIGHT_TERMS];
    int weight_terms[3];
    double denominator[3 * SR_CLIP_CORNER_WEIGHT_TERMS];
    int denominator_terms;
} sr_clip_exact_corner;

void sr_clip_exact_corner_of(const sr_vertex_out tri[3], sr_clip_plane first, sr_clip_plane plane,
                             const sr_clip_depth *depth, sr_clip_exact_corner *corner);

/* Σ c_k·v_k of coordinate i as an expansion num[0..n); returns n. */
int sr_clip_exact_corner_numerator(const sr_clip_exact_corner *corner, const sr_vertex_out tri[3], int i,
                                   double num[SR_CLIP_CORNER_NUMERATOR_TERMS]);

#define SR_CLIP_SIDE_TERMS (3 * SR_CLIP_CORNER_WEIGHT_TERMS * 2 * SR_CLIP_DISTANCE_TERMS)

/* Whether the triangle's point on two of its lines is inside `plane`
 * (distance >= 0), decided exactly: 1 inside, 0 outside, -1 when the lines
 * do not meet in one point (parallel in the triangle, or it is degenerate). */
int sr_clip_exact_side(const sr_vertex_out tri[3], int line1, int line2, sr_clip_plane plane,
                       const sr_clip_depth *depth);

#endif
