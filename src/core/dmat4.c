#include <float.h>
#include <math.h>

#include "dmat4.h"

sr_dmat4 sr_dmat4_identity(void)
{
    return (sr_dmat4){ { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 0, 1 } } };
}

bool sr_dmat4_is_zero(const sr_dmat4 *a)
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            if (a->m[c][r] != 0.0)
                return false;
    return true;
}

sr_dmat4 sr_dmat4_from_mat4(const mat4 a)
{
    sr_dmat4 d;
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            d.m[c][r] = a[c][r];
    return d;
}

sr_dmat4 sr_dmat4_desc_matrix(const sr_dmat4 *d, const mat4 f)
{
    if (!sr_dmat4_is_zero(d))
        return *d;
    sr_dmat4 m = sr_dmat4_from_mat4(f);
    return sr_dmat4_is_zero(&m) ? sr_dmat4_identity() : m;
}

sr_dmat4 sr_dmat4_mul(const sr_dmat4 *a, const sr_dmat4 *b)
{
    sr_dmat4 p;
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++)
                s += a->m[k][r] * b->m[c][k];
            p.m[c][r] = s;
        }
    return p;
}

sr_dmat4 sr_dmat4_translate(const sr_dmat4 *a, const double t[3])
{
    sr_dmat4 p = *a;
    for (int r = 0; r < 4; r++)
        p.m[3][r] += a->m[0][r] * t[0] + a->m[1][r] * t[1] + a->m[2][r] * t[2];
    return p;
}

float sr_double_to_float(double d)
{
    if (fabs(d) > FLT_MAX)
        return (float)copysign(INFINITY, d);
    return (float)d;
}

float sr_vec3_distance_d(const vec3 a, const vec3 b)
{
    double sum = 0.0;
    for (int k = 0; k < 3; k++) {
        double d = (double)a[k] - (double)b[k];
        sum += d * d;
    }
    return sr_double_to_float(sqrt(sum));
}

void sr_dmat4_to_mat4(const sr_dmat4 *a, mat4 out)
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            out[c][r] = sr_double_to_float(a->m[c][r]);
}
