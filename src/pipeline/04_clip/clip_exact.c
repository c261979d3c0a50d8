#include <float.h>
#include <math.h>

#include "clip_exact.h"
#include "expansion.h"
#include "pipeline/03_classify.h"

/* Adds d · x to the expansion, exactly. */
static int add_product(double *e, int n, const double *d, int dn, double x)
{
    for (int k = 0; k < dn; k++) {
        double p, err;
        two_product(d[k], x, &p, &err);
        n = grow(e, n, err);
        n = grow(e, n, p);
    }
    return n;
}

/* The denominator is a sum of two non-negative parts and never cancels. */
void sr_clip_exact_edge_of(sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                           const sr_clip_depth *depth, sr_clip_exact_edge *edge)
{
    edge->d_in_terms = sr_clip_distance_exact(plane, inside->v, depth, edge->d_in);
    edge->d_out_terms = sr_clip_distance_exact(plane, outside->v, depth, edge->neg_d_out);
    int n = 0;
    for (int k = 0; k < edge->d_in_terms; k++)
        n = grow(edge->denominator, n, edge->d_in[k]);
    for (int k = 0; k < edge->d_out_terms; k++) {
        edge->neg_d_out[k] = -edge->neg_d_out[k];
        n = grow(edge->denominator, n, edge->neg_d_out[k]);
    }
    edge->denominator_terms = n;
}

int sr_clip_exact_numerator(const sr_clip_exact_edge *edge, float a, float b, double num[SR_CLIP_NUMERATOR_TERMS])
{
    int n = add_product(num, 0, edge->d_in, edge->d_in_terms, b);
    return add_product(num, n, edge->neg_d_out, edge->d_out_terms, a);
}

/* v = (d_in·b − d_out·a) / (d_in − d_out): the same point as a + t(b − a),
 * written so that both sums are exact and only the quotient rounds. */
void sr_clip_intersect_exact(sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                             int floats, const sr_clip_depth *depth, sr_vertex_out *cut)
{
    sr_clip_exact_edge edge;
    sr_clip_exact_edge_of(plane, inside, outside, depth, &edge);
    double denominator = expansion_value(edge.denominator, edge.denominator_terms);
    for (int i = 0; i < floats; i++) {
        double num[SR_CLIP_NUMERATOR_TERMS];
        int n = sr_clip_exact_numerator(&edge, inside->v[i], outside->v[i], num);
        cut->v[i] = (float)(expansion_value(num, n) / denominator);
    }
}

/* A line's vector over the triangle's vertices (clip_exact.h), exactly. */
static void line_vector(const sr_vertex_out tri[3], int line, const sr_clip_depth *depth,
                        double v[3][SR_CLIP_DISTANCE_TERMS], int n[3])
{
    for (int k = 0; k < 3; k++) {
        if (line >= SR_CLIP_ON_PLANE) {
            n[k] = sr_clip_distance_exact((sr_clip_plane)(line - SR_CLIP_ON_PLANE), tri[k].v, depth, v[k]);
        } else {
            v[k][0] = k == (line + 2) % 3 ? 1.0 : 0.0;
            n[k] = 1;
        }
    }
}

/* c_k = P_i·Q_j − P_j·Q_i, (i, j) = (k + 1, k + 2) mod 3: four exact
 * products of expansions, compressed. */
static void lines_cross(const sr_vertex_out tri[3], int line1, int line2, const sr_clip_depth *depth,
                        sr_clip_exact_corner *corner)
{
    double p[3][SR_CLIP_DISTANCE_TERMS], q[3][SR_CLIP_DISTANCE_TERMS], neg_q[SR_CLIP_DISTANCE_TERMS];
    int pn[3], qn[3];
    line_vector(tri, line1, depth, p, pn);
    line_vector(tri, line2, depth, q, qn);
    corner->denominator_terms = 0;
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3, n = 0;
        double *c = corner->weight[k];
        for (int t = 0; t < qn[i]; t++)
            neg_q[t] = -q[i][t];
        for (int t = 0; t < qn[j]; t++)
            n = add_product(c, n, p[i], pn[i], q[j][t]);
        for (int t = 0; t < qn[i]; t++)
            n = add_product(c, n, p[j], pn[j], neg_q[t]);
        corner->weight_terms[k] = n = compress(c, n);
        for (int t = 0; t < n; t++)
            corner->denominator_terms = grow(corner->denominator, corner->denominator_terms, c[t]);
    }
    corner->denominator_terms = compress(corner->denominator, corner->denominator_terms);
}

void sr_clip_exact_corner_of(const sr_vertex_out tri[3], sr_clip_plane first, sr_clip_plane plane,
                             const sr_clip_depth *depth, sr_clip_exact_corner *corner)
{
    lines_cross(tri, SR_CLIP_ON_PLANE + (int)first, SR_CLIP_ON_PLANE + (int)plane, depth, corner);
}

/* A line's vector in double: each distance within 2 roundings of its
 * exact value (clip.h), the unit vector of an edge exact. */
static void line_vector_double(const sr_vertex_out tri[3], int line, const sr_clip_depth *depth, double v[3])
{
    for (int k = 0; k < 3; k++)
        v[k] = line >= SR_CLIP_ON_PLANE ? sr_clip_distance_with((sr_clip_plane)(line - SR_CLIP_ON_PLANE), tri[k].v, depth)
                                        : (double)(k == (line + 2) % 3);
}

/* The side from doubles where an error bound decides it (1 or 0), else -1.
 * Every input is within 2ε of its own value; a triple product of them
 * with two roundings is within 8ε, and the difference in each weight and
 * the sum of three add 4 more roundings of the terms' sizes: 16ε of the
 * sum of the terms' magnitudes bounds the error of Σ c_k·R_k and of Σ c_k. */
#define SIDE_ROUNDING (16.0 * DBL_EPSILON)
static int side_double(const sr_vertex_out tri[3], int line1, int line2, sr_clip_plane plane,
                       const sr_clip_depth *depth)
{
    double p[3], q[3], r[3], distance = 0.0, distance_size = 0.0, sum = 0.0, sum_size = 0.0;
    line_vector_double(tri, line1, depth, p);
    line_vector_double(tri, line2, depth, q);
    for (int k = 0; k < 3; k++)
        r[k] = sr_clip_distance_with(plane, tri[k].v, depth);
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        double c = p[i] * q[j] - p[j] * q[i], size = fabs(p[i] * q[j]) + fabs(p[j] * q[i]);
        distance += c * r[k];
        distance_size += size * fabs(r[k]);
        sum += c;
        sum_size += size;
    }
    if (!(fabs(sum) > SIDE_ROUNDING * sum_size) || !(fabs(distance) > SIDE_ROUNDING * distance_size))
        return -1;
    return (distance > 0.0) == (sum > 0.0);
}

/* Σ_k c_k·R_k over Σ c_k: the sign of the point's distance, from doubles
 * where their error bound decides it, else exactly. */
int sr_clip_exact_side(const sr_vertex_out tri[3], int line1, int line2, sr_clip_plane plane,
                       const sr_clip_depth *depth)
{
    int side = side_double(tri, line1, line2, plane, depth);
    if (side >= 0)
        return side;
    sr_clip_exact_corner point;
    lines_cross(tri, line1, line2, depth, &point);
    double sum = expansion_signed_value(point.denominator, point.denominator_terms);
    if (sum == 0.0)
        return -1;
    double r[SR_CLIP_DISTANCE_TERMS], distance[SR_CLIP_SIDE_TERMS];
    int n = 0;
    for (int k = 0; k < 3; k++) {
        int rn = sr_clip_distance_exact(plane, tri[k].v, depth, r);
        for (int t = 0; t < rn; t++)
            n = add_product(distance, n, point.weight[k], point.weight_terms[k], r[t]);
    }
    double d = expansion_signed_value(distance, n);
    return (d >= 0.0 && sum > 0.0) || (d <= 0.0 && sum < 0.0);
}

int sr_clip_exact_corner_numerator(const sr_clip_exact_corner *corner, const sr_vertex_out tri[3], int i,
                                   double num[SR_CLIP_CORNER_NUMERATOR_TERMS])
{
    int n = 0;
    for (int k = 0; k < 3; k++)
        n = add_product(num, n, corner->weight[k], corner->weight_terms[k], tri[k].v[i]);
    return n;
}
