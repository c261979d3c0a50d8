/* truth_exact.h — the truth renderer's predicates in exact arithmetic, for
 * the cases its double-precision error bounds cannot decide. Inputs are the
 * doubles the truth works with: view-space vertices and the ray through a
 * pixel centre, whose components are exact two-part expansions (an integer
 * times a float). Expansion arithmetic (src/pipeline/expansion.h). */
#ifndef SOFTRAST_STUDIES_TRUTH_EXACT_H
#define SOFTRAST_STUDIES_TRUTH_EXACT_H

/* The ray from the eye through a pixel centre: component i is d[i][0] + d[i][1]
 * exactly (smaller part first). */
typedef struct sr_truth_ray {
    double d[3][2];
} sr_truth_ray;

/* A triangle's three view-space vertices. */
typedef struct sr_truth_corners {
    const double *v[3];
} sr_truth_corners;

/* Sign of a · (b × c): positive when the triangle (a, b, c) seen from the
 * eye at the origin turns counter-clockwise on screen. */
int sr_truth_orient_exact(const double a[3], const double b[3], const double c[3]);

/* Sign of d · (a × b): which side of the plane through the eye and the edge
 * a → b the ray passes. */
int sr_truth_side_exact(const sr_truth_ray *ray, const double a[3], const double b[3]);

/* Sign of component `axis` (0: x, 1: y) of a × b. */
int sr_truth_cross_sign(const double a[3], const double b[3], int axis);

/* Sign of (a_hi + a_lo)·d_z·det + b·S for the triangle t, where det =
 * v0 · (v1 × v2) and S = d · (v1×v2 + v2×v0 + v0×v1): with view z = d_z·det/S
 * the hit, the sign of a + b/z times the sign of det. */
int sr_truth_depth_plane_exact(const sr_truth_ray *ray, const sr_truth_corners *t, double a_hi, double a_lo, double b);

/* Sign of t1's hit distance minus t2's along the ray, both hits in front of
 * the eye: negative when t1 is nearer. */
int sr_truth_nearer_exact(const sr_truth_ray *ray, const sr_truth_corners *t1, const sr_truth_corners *t2);

#endif
