#include <math.h>

#include "clip_exact.h"
#include "expansion.h"
#include "clip.h"

/* Near a·w + b and far w − a·w − b: a·w of two floats is exact in double,
 * so one two-sum or two make them exact. */
static int depth_distance(sr_clip_plane plane, double w, const sr_clip_depth *depth, double d[])
{
    double aw = (double)depth->a * w;
    if (!sr_clip_plane_table[plane].bounded_by_w) {
        two_sum(aw, depth->b, &d[1], &d[0]);
        return 2;
    }
    two_sum(w, -aw, &d[1], &d[0]);
    return grow(d, 2, -(double)depth->b);
}

int sr_clip_distance_exact(sr_clip_plane plane, const float *c, const sr_clip_depth *depth,
                           double d[SR_CLIP_DISTANCE_TERMS])
{
    double w = c[SR_W];
    if (depth && depth->on && sr_clip_plane_in_depth_model(plane))
        return depth_distance(plane, w, depth, d);
    const sr_clip_plane_row *row = &sr_clip_plane_table[plane];
    double along = row->sign * (double)c[row->axis];
    if (!row->bounded_by_w) {
        d[0] = along;
        return 1;
    }
    two_sum(w, along, &d[1], &d[0]);
    return 2;
}

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
