#include <float.h>
#include <math.h>
#include <string.h>

#include "clip_corner.h"
#include "clip_exact.h"
#include "expansion.h"

/* The error of a position Σ λ_k·v_k in double, in units of DBL_EPSILON ·
 * Σ λ_k·|v_k|: each λ_k = c_k / Σ c is within 6 roundings (the weight's and
 * the sum's values, two each, and the division: the sum never cancels, as
 * every c_k has its sign), the products and sums add 3, with room to spare. */
#define POSITION_ROUNDING 16.0

/* The triangle in an order of its positions' bits (never its varyings', so
 * what the shading mode carries cannot change a corner). */
static void canonical_order(const sr_vertex_out tri[3], sr_vertex_out ordered[3])
{
    static const int pairs[3][2] = { { 0, 1 }, { 1, 2 }, { 0, 1 } };
    for (int k = 0; k < 3; k++)
        ordered[k] = tri[k];
    for (int s = 0; s < 3; s++) {
        sr_vertex_out *a = &ordered[pairs[s][0]], *b = &ordered[pairs[s][1]];
        if (memcmp(a->v, b->v, SR_VARYINGS_AT * sizeof(float)) > 0) {
            sr_vertex_out t = *a;
            *a = *b;
            *b = t;
        }
    }
}

/* λ_k = c_k / Σ c, all >= 0; false when Σ c is 0 or a weight has the
 * other sign (the corner is off the triangle), decided exactly. */
static bool barycentric(const sr_clip_exact_corner *corner, double lambda[3])
{
    double sum = expansion_signed_value(corner->denominator, corner->denominator_terms);
    if (sum == 0.0)
        return false;
    for (int k = 0; k < 3; k++) {
        double c = expansion_signed_value(corner->weight[k], corner->weight_terms[k]);
        if ((c < 0.0 && sum > 0.0) || (c > 0.0 && sum < 0.0))
            return false;
        lambda[k] = c;
    }
    double total = lambda[0] + lambda[1] + lambda[2];
    for (int k = 0; k < 3; k++)
        lambda[k] /= total;
    return true;
}

/* The position in double; returns a bound on its error in NDC (infinite
 * where w may be <= 0). */
static double position_double(const sr_vertex_out tri[3], const double lambda[3], float out[SR_VARYINGS_AT])
{
    double err = 0.0, m = 0.0, w = 0.0;
    for (int i = 0; i < SR_VARYINGS_AT; i++) {
        double v = 0.0, size = 0.0;
        for (int k = 0; k < 3; k++) {
            v += lambda[k] * tri[k].v[i];
            size += lambda[k] * fabs((double)tri[k].v[i]);
        }
        out[i] = (float)v;
        err = fmax(err, POSITION_ROUNDING * DBL_EPSILON * size);
        m = fmax(m, fabs(v));
        w = i == SR_W ? v : w;
    }
    double w_low = w - err, ndc = err * (1.0 + m / w_low) / w_low;
    return w_low > 0.0 && isfinite(ndc) ? ndc : INFINITY;
}

static void position_exact(const sr_vertex_out tri[3], const sr_clip_exact_corner *corner, float out[SR_VARYINGS_AT])
{
    double denominator = expansion_value(corner->denominator, corner->denominator_terms);
    for (int i = 0; i < SR_VARYINGS_AT; i++) {
        double num[SR_CLIP_CORNER_NUMERATOR_TERMS];
        int n = sr_clip_exact_corner_numerator(corner, tri, i, num);
        out[i] = (float)(expansion_value(num, n) / denominator);
    }
}

/* Each varying with the position's weights, within the vertices' range. */
static void varyings(const sr_vertex_out tri[3], const double lambda[3], int floats, float *out)
{
    for (int i = SR_VARYINGS_AT; i < floats; i++) {
        double a = tri[0].v[i], b = tri[1].v[i], c = tri[2].v[i];
        double v = lambda[0] * a + lambda[1] * b + lambda[2] * c;
        out[i] = (float)fmin(fmax(v, fmin(fmin(a, b), c)), fmax(fmax(a, b), c));
    }
}

sr_clip_precision sr_clip_corner(const sr_vertex_out tri[3], sr_clip_plane first, sr_clip_plane plane, int floats,
                                 sr_clip_precision precision, double tolerance, const sr_clip_depth *depth,
                                 sr_vertex_out *cut)
{
    sr_vertex_out ordered[3];
    canonical_order(tri, ordered);
    sr_clip_exact_corner corner;
    sr_clip_exact_corner_of(ordered, first, plane, depth, &corner);
    double lambda[3];
    if (!barycentric(&corner, lambda))
        return SR_CLIP_ADAPTIVE;
    sr_clip_precision used = SR_CLIP_DOUBLE;
    if (precision != SR_CLIP_ADAPTIVE || !(position_double(ordered, lambda, cut->v) <= tolerance)) {
        position_exact(ordered, &corner, cut->v);
        used = SR_CLIP_EXACT;
    }
    varyings(ordered, lambda, floats, cut->v);
    sr_clip_place_on_plane(first, depth, cut->v);
    sr_clip_place_on_plane(plane, depth, cut->v);
    return used;
}

/* A line's vector over the vertices (clip_exact.h), in double. */
static void line_vector_d(const double tri_d[3][4], int line, const sr_clip_depth *depth, double v[3])
{
    for (int k = 0; k < 3; k++)
        v[k] = line >= SR_CLIP_ON_PLANE ? sr_clip_distance_d((sr_clip_plane)(line - SR_CLIP_ON_PLANE), tri_d[k], depth)
                                        : (double)(k == (line + 2) % 3);
}

void sr_clip_point_on_lines_d(const double tri_d[3][4], int line1, int line2, const sr_clip_depth *depth,
                              double out[4])
{
    double p[3], q[3], c[3];
    line_vector_d(tri_d, line1, depth, p);
    line_vector_d(tri_d, line2, depth, q);
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        c[k] = p[i] * q[j] - p[j] * q[i];
    }
    double sum = c[0] + c[1] + c[2];
    for (int r = 0; r < 4; r++)
        out[r] = (c[0] * tri_d[0][r] + c[1] * tri_d[1][r] + c[2] * tri_d[2][r]) / sum;
}
