/* The upright turn (upright.h). */
#include <string.h>

#include "upright.h"

sr_axis sr_upright_default_front(sr_axis up)
{
    return up == SR_AXIS_PZ ? SR_AXIS_NY : up == SR_AXIS_NZ ? SR_AXIS_PY : SR_AXIS_PZ;
}

static void axis_vector(sr_axis a, vec3 v)
{
    glm_vec3_zero(v);
    v[a / 2] = a % 2 ? -1.0f : 1.0f;
}

void sr_upright_matrix(sr_axis up, sr_axis front, bool z_negated, mat4 out)
{
    glm_mat4_identity(out);
    if ((unsigned)up >= SR_AXIS_COUNT)
        return;
    if ((unsigned)front >= SR_AXIS_COUNT || front / 2 == up / 2)
        front = sr_upright_default_front(up);
    /* Rows of the turn in the file's frame: y is up, z the front, x = y × z
     * (a rotation, whatever the axes). */
    vec3 rows[3];
    axis_vector(up, rows[1]);
    axis_vector(front, rows[2]);
    glm_vec3_cross(rows[1], rows[2], rows[0]);
    /* S·F·S with S = diag(1, 1, -1) the loader's flip: entry (r, c) of F
     * changes sign when exactly one of r, c is z. */
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            float f = rows[r][c];
            out[c][r] = f != 0.0f && z_negated && ((r == 2) != (c == 2)) ? -f : f; /* cglm: out[column][row] */
        }
}

void sr_upright_bounds(const mat4 m, vec3 lo, vec3 hi, double origin[3])
{
    vec3 a, b;
    double o[3] = { 0, 0, 0 };
    for (int r = 0; r < 3; r++) {
        a[r] = b[r] = 0.0f;
        for (int c = 0; c < 3; c++) {
            float e = m[c][r];
            a[r] += e > 0 ? e * lo[c] : e < 0 ? e * hi[c] : 0.0f;
            b[r] += e > 0 ? e * hi[c] : e < 0 ? e * lo[c] : 0.0f;
            o[r] += (double)e * origin[c];
        }
    }
    glm_vec3_copy(a, lo);
    glm_vec3_copy(b, hi);
    memcpy(origin, o, sizeof o);
}
