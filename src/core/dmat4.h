/* dmat4.h — double-precision 4x4 matrices for large world coordinates.
 *
 * A float matrix that moves a point by 1e7 holds that translation to about a
 * unit. The draw therefore composes clip_from_object = P·V·W·T(origin) in
 * double, where the huge translations of the world (and a mesh's origin)
 * and of the view cancel, and rounds the product to float once
 * (docs/precision.md). sr_dmat4 is laid out as cglm's mat4 (m[column][row],
 * column vectors; softrast/softrast.h).
 */
#ifndef SOFTRAST_CORE_DMAT4_H
#define SOFTRAST_CORE_DMAT4_H

#include <stdbool.h>
#include <cglm/cglm.h>

#include "softrast/softrast.h"

sr_dmat4 sr_dmat4_identity(void);
bool sr_dmat4_is_zero(const sr_dmat4 *a);
sr_dmat4 sr_dmat4_from_mat4(const mat4 a);
/* A draw desc's matrix in double: d when it is not all zero, else f, an
 * all-zero f being the identity (sr_draw_desc's defaults). */
sr_dmat4 sr_dmat4_desc_matrix(const sr_dmat4 *d, const mat4 f);
/* a · b */
sr_dmat4 sr_dmat4_mul(const sr_dmat4 *a, const sr_dmat4 *b);
/* a · T(t): a applied after a translation by t */
sr_dmat4 sr_dmat4_translate(const sr_dmat4 *a, const double t[3]);
/* d rounded to the nearest float; beyond float range ±inf (as float
 * arithmetic would overflow, where a plain cast is undefined), NaN stays NaN. */
float sr_double_to_float(double d);
/* |a − b| computed in double, then rounded by sr_double_to_float: float
 * points up to float's range apart do not overflow, as glm_vec3_distance's
 * squares do past about 1.8e19. */
float sr_vec3_distance_d(const vec3 a, const vec3 b);
/* Each entry rounded to float once, by sr_double_to_float. */
void sr_dmat4_to_mat4(const sr_dmat4 *a, mat4 out);

/* Double 3-vectors, for what must not round to float on the way. */
static inline double sr_dvec3_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void sr_dvec3_cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

#endif
