#include <math.h>

#include "clip_exact.h"

#define MAX_TERMS 8 /* two double-double distances times one float: 2 × 2 × 2 products */

/* s + e = a + b exactly (Knuth). */
static void two_sum(double a, double b, double *s, double *e)
{
    *s = a + b;
    double bv = *s - a;
    *e = (a - (*s - bv)) + (b - bv);
}

/* p + e = a · b exactly (the fused multiply-add gives the rounding error). */
static void two_product(double a, double b, double *p, double *e)
{
    *p = a * b;
    *e = fma(a, b, -*p);
}

/* Adds b to the nonoverlapping expansion e[0..n) (smallest first), exactly:
 * Shewchuk's Grow-Expansion, in place. Returns the new length. */
static int grow(double *e, int n, double b)
{
    double q = b;
    for (int i = 0; i < n; i++) {
        double s, err;
        two_sum(q, e[i], &s, &err);
        e[i] = err;
        q = s;
    }
    e[n] = q;
    return n + 1;
}

/* The expansion's value to about one rounding: smallest parts first. */
static double value(const double *e, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        s += e[i];
    return s;
}

/* The plane distance of two floats, as an exact pair hi + lo. */
static void distance_exact(sr_clip_plane plane, const float *c, double d[2])
{
    double w = c[SR_W];
    switch (plane) {
    case SR_PLANE_NEAR:   d[0] = c[SR_Z], d[1] = 0.0; return;
    case SR_PLANE_FAR:    two_sum(w, -(double)c[SR_Z], &d[0], &d[1]); return;
    case SR_PLANE_LEFT:   two_sum(w, c[SR_X], &d[0], &d[1]); return;
    case SR_PLANE_RIGHT:  two_sum(w, -(double)c[SR_X], &d[0], &d[1]); return;
    case SR_PLANE_BOTTOM: two_sum(w, c[SR_Y], &d[0], &d[1]); return;
    case SR_PLANE_TOP:    two_sum(w, -(double)c[SR_Y], &d[0], &d[1]); return;
    }
}

/* Adds d · x to the expansion, exactly. */
static int add_product(double *e, int n, const double d[2], double x)
{
    for (int k = 0; k < 2; k++) {
        double p, err;
        two_product(d[k], x, &p, &err);
        n = grow(e, n, err);
        n = grow(e, n, p);
    }
    return n;
}

/* v = (d_in·b − d_out·a) / (d_in − d_out): the same point as a + t(b − a),
 * written so that both sums are exact and only the quotient rounds. The
 * denominator is a sum of two non-negative parts and never cancels. */
void sr_clip_intersect_exact(sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                             int floats, sr_vertex_out *cut)
{
    double d_in[2], d_out[2], neg_out[2], den[4];
    distance_exact(plane, inside->v, d_in);
    distance_exact(plane, outside->v, d_out);
    neg_out[0] = -d_out[0];
    neg_out[1] = -d_out[1];
    int dn = 0;
    dn = grow(den, dn, d_in[1]);
    dn = grow(den, dn, d_in[0]);
    dn = grow(den, dn, neg_out[1]);
    dn = grow(den, dn, neg_out[0]);
    double denominator = value(den, dn);
    for (int i = 0; i < floats; i++) {
        double num[MAX_TERMS];
        int n = add_product(num, 0, d_in, outside->v[i]);
        n = add_product(num, n, neg_out, inside->v[i]);
        cut->v[i] = (float)(value(num, n) / denominator);
    }
}
