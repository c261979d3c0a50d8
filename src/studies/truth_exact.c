#include "pipeline/04_clip/expansion.h"
#include "truth_exact.h"

/* A triple product of doubles has 6 terms of 3 factors, 4 parts each exact;
 * with a two-part first factor, twice that. */
#define POINT_TRIPLE_MAX 24
#define RAY_TRIPLE_MAX 48
#define RAY_SUM_MAX (3 * RAY_TRIPLE_MAX)
#define PRODUCT_MAX (2 * POINT_TRIPLE_MAX * RAY_SUM_MAX)

/* The sign of a nonoverlapping expansion: its largest nonzero part's. */
static int sign_of(const double *e, int n)
{
    for (int i = n - 1; i >= 0; i--)
        if (e[i] != 0.0)
            return e[i] > 0.0 ? 1 : -1;
    return 0;
}

/* Adds x·y·z to e[0..n) exactly; returns the new length. */
static int add_product3(double *e, int n, double x, double y, double z)
{
    double p, q, p_hi, p_lo, q_hi, q_lo;
    two_product(y, z, &p, &q);
    two_product(x, p, &p_hi, &p_lo);
    two_product(x, q, &q_hi, &q_lo);
    n = grow(e, n, q_lo);
    n = grow(e, n, p_lo);
    n = grow(e, n, q_hi);
    return grow(e, n, p_hi);
}

/* Adds x · (b × c) to e[0..n); component i of x is the sum of its `parts`
 * parts x[i·parts ..]. */
static int add_triple(const double *x, int parts, const double b[3], const double c[3], double *e, int n)
{
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3, k = (i + 2) % 3;
        for (int p = 0; p < parts; p++) {
            n = add_product3(e, n, x[i * parts + p], b[j], c[k]);
            n = add_product3(e, n, -x[i * parts + p], b[k], c[j]);
        }
    }
    return n;
}

/* h = e · f, compressed; h holds 2·ne·nf parts. */
static int multiply(const double *e, int ne, const double *f, int nf, double *h)
{
    int n = 0;
    for (int i = 0; i < ne; i++)
        for (int j = 0; j < nf; j++) {
            double p, q;
            two_product(e[i], f[j], &p, &q);
            n = grow(h, n, q);
            n = grow(h, n, p);
        }
    return compress(h, n);
}

/* e[0..ne) += sign · f, compressed. */
static int add_scaled(double *e, int ne, const double *f, int nf, double sign)
{
    for (int j = 0; j < nf; j++)
        ne = grow(e, ne, sign * f[j]);
    return compress(e, ne);
}

static int determinant(const sr_truth_corners *t, double *e)
{
    return compress(e, add_triple(t->v[0], 1, t->v[1], t->v[2], e, 0));
}

/* d · (v1×v2 + v2×v0 + v0×v1): the denominator of the hit distance. */
static int ray_sum(const sr_truth_ray *ray, const sr_truth_corners *t, double *e)
{
    int n = 0;
    for (int k = 0; k < 3; k++)
        n = add_triple(&ray->d[0][0], 2, t->v[(k + 1) % 3], t->v[(k + 2) % 3], e, n);
    return compress(e, n);
}

int sr_truth_orient_exact(const double a[3], const double b[3], const double c[3])
{
    double e[POINT_TRIPLE_MAX];
    return sign_of(e, determinant(&(sr_truth_corners){ { a, b, c } }, e));
}

int sr_truth_side_exact(const sr_truth_ray *ray, const double a[3], const double b[3])
{
    double e[RAY_TRIPLE_MAX];
    return sign_of(e, add_triple(&ray->d[0][0], 2, a, b, e, 0));
}

int sr_truth_cross_sign(const double a[3], const double b[3], int axis)
{
    int j = (axis + 1) % 3, k = (axis + 2) % 3;
    double e[4];
    int n = 0;
    double p, q;
    two_product(a[j], b[k], &p, &q);
    n = grow(e, n, q);
    n = grow(e, n, p);
    two_product(-a[k], b[j], &p, &q);
    n = grow(e, n, q);
    n = grow(e, n, p);
    return sign_of(e, n);
}

int sr_truth_depth_plane_exact(const sr_truth_ray *ray, const sr_truth_corners *t, double a_hi, double a_lo, double b)
{
    double det[POINT_TRIPLE_MAX], sum[RAY_SUM_MAX], scale[8], h[2 * PRODUCT_MAX], bs[2 * RAY_SUM_MAX];
    int n_det = determinant(t, det), n_sum = ray_sum(ray, t, sum);
    int n_scale = multiply((const double[2]){ a_lo, a_hi }, 2, ray->d[2], 2, scale);
    int n = multiply(scale, n_scale, det, n_det, h);
    int n_bs = multiply(sum, n_sum, &b, 1, bs);
    return sign_of(h, add_scaled(h, n, bs, n_bs, 1.0));
}

int sr_truth_nearer_exact(const sr_truth_ray *ray, const sr_truth_corners *t1, const sr_truth_corners *t2)
{
    double det1[POINT_TRIPLE_MAX], det2[POINT_TRIPLE_MAX], sum1[RAY_SUM_MAX], sum2[RAY_SUM_MAX];
    double h[2 * PRODUCT_MAX], other[PRODUCT_MAX];
    int n_det1 = determinant(t1, det1), n_det2 = determinant(t2, det2);
    int n_sum1 = ray_sum(ray, t1, sum1), n_sum2 = ray_sum(ray, t2, sum2);
    /* t_i = det_i / S_i, so t1 - t2 has the sign of det1·S2 - det2·S1 times S1·S2's. */
    int n = multiply(det1, n_det1, sum2, n_sum2, h);
    int n_other = multiply(det2, n_det2, sum1, n_sum1, other);
    return sign_of(h, add_scaled(h, n, other, n_other, -1.0)) * sign_of(sum1, n_sum1) * sign_of(sum2, n_sum2);
}
