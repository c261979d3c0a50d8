/* The upright turn (upright.h). */
#include <string.h>

#include "upright.h"

/* Rows of the turn in the file's frame, per sr_axis: y-up coordinates of
 * the file's x, y, z. */
static const float FILE_TURNS[SR_AXIS_COUNT][3][3] = {
    [SR_AXIS_PX] = { { 0, -1, 0 }, { 1, 0, 0 }, { 0, 0, 1 } },
    [SR_AXIS_NX] = { { 0, 1, 0 }, { -1, 0, 0 }, { 0, 0, 1 } },
    [SR_AXIS_PY] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } },
    [SR_AXIS_NY] = { { -1, 0, 0 }, { 0, -1, 0 }, { 0, 0, 1 } },
    [SR_AXIS_PZ] = { { 1, 0, 0 }, { 0, 0, 1 }, { 0, -1, 0 } },
    [SR_AXIS_NZ] = { { 1, 0, 0 }, { 0, 0, -1 }, { 0, 1, 0 } },
};

void sr_upright_matrix(sr_axis up, bool z_negated, mat4 out)
{
    glm_mat4_identity(out);
    if ((unsigned)up >= SR_AXIS_COUNT)
        return;
    /* S·F·S with S = diag(1, 1, -1) the loader's flip: entry (r, c) of F
     * changes sign when exactly one of r, c is z. */
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            float f = FILE_TURNS[up][r][c];
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
