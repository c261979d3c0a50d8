/* Helpers shared by tests/test_clip.c and tests/test_clip_random.c: a seeded
 * random generator, plane distances from the plane table, an independent reference
 * clipper in double precision, and polygon area and convexity checks.
 *
 * Everything here is static inline so each test file stands alone. */
#ifndef SOFTRAST_TESTS_CLIP_HELPERS_H
#define SOFTRAST_TESTS_CLIP_HELPERS_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "softrast_private.h"
#include "test_rng.h"

/* ---- random numbers (test_rng.h) -------------------------------------- */

/* Uniform in log between lo and hi (both > 0). */
static inline double log_uniform(test_rng *r, double lo, double hi)
{
    return lo * pow(hi / lo, rng_unit(r));
}

/* ±10^e with e uniform in [lo_exp, hi_exp]: magnitudes spread over decades. */
static inline double rng_log_signed(test_rng *r, double lo_exp, double hi_exp)
{
    double m = pow(10.0, rng_uniform(r, lo_exp, hi_exp));
    return rng_below(r, 2) ? m : -m;
}

/* The error a draw lets a cut vertex carry (sr_clip_config.ndc_tolerance):
 * half a subpixel step in NDC over the framebuffer's longer side, no guard
 * band (draw.c, sr_draw). */
static inline double draw_clip_tolerance(int width, int height)
{
    return 1.0 / ((double)SR_SUBPIXEL_ONE * (width > height ? width : height));
}

/* ---- vertices ---------------------------------------------------------- */

static inline sr_vertex_out vert4(double x, double y, double z, double w)
{
    sr_vertex_out v;
    memset(&v, 0, sizeof v);
    v.v[SR_X] = (float)x;
    v.v[SR_Y] = (float)y;
    v.v[SR_Z] = (float)z;
    v.v[SR_W] = (float)w;
    return v;
}

static inline sr_polygon poly3(sr_vertex_out a, sr_vertex_out b, sr_vertex_out c)
{
    sr_polygon p;
    memset(&p, 0, sizeof p);
    p.count = 3;
    p.vert[0] = a;
    p.vert[1] = b;
    p.vert[2] = c;
    return p;
}

static inline bool floats_identical(const float *a, const float *b, int n)
{
    return memcmp(a, b, (size_t)n * sizeof(float)) == 0;
}

/* ---- plane distances from the plane table (clip.h) ------------------- */

static inline double ref_distance(int plane, const double c[4])
{
    return sr_clip_plane_distance((sr_clip_plane)plane, c[sr_clip_plane_table[plane].axis], c[SR_W]);
}

static inline void to_double4(const sr_vertex_out *v, double out[4])
{
    for (int i = 0; i < 4; i++)
        out[i] = v->v[i];
}

static inline double ref_distance_f(int plane, const sr_vertex_out *v)
{
    double c[4];
    to_double4(v, c);
    return ref_distance(plane, c);
}

static inline const char *plane_name(int plane)
{
    return plane >= 0 && plane < SR_CLIP_PLANES ? sr_clip_plane_table[plane].name : "?";
}

/* ---- reference clipper: Sutherland–Hodgman in double ------------------ */

#define REF_MAX_VERTS 32

typedef struct ref_poly {
    int n;
    double v[REF_MAX_VERTS][4];
} ref_poly;

static inline ref_poly ref_from_sr(const sr_polygon *p)
{
    ref_poly r = { .n = p->count };
    for (int i = 0; i < p->count; i++)
        to_double4(&p->vert[i], r.v[i]);
    return r;
}

/* Written independently of src/pipeline/clip.c: a plain double-precision
 * pass per plane, no placement, no bound. Close enough to exact for area
 * comparisons at float tolerance. */
static inline void ref_clip(ref_poly *p, unsigned planes)
{
    for (int plane = 0; plane < SR_CLIP_PLANES; plane++) {
        if (!(planes & (1u << plane)) || p->n == 0)
            continue;
        ref_poly out = { .n = 0 };
        for (int i = 0; i < p->n; i++) {
            const double *cur = p->v[i], *nxt = p->v[(i + 1) % p->n];
            double dc = ref_distance(plane, cur), dn = ref_distance(plane, nxt);
            if (dc >= 0)
                memcpy(out.v[out.n++], cur, sizeof out.v[0]);
            if ((dc >= 0) != (dn >= 0)) {
                double s = dc / (dc - dn);
                for (int k = 0; k < 4; k++)
                    out.v[out.n][k] = cur[k] + s * (nxt[k] - cur[k]);
                out.n++;
            }
        }
        *p = out;
    }
    if (p->n < 3)
        p->n = 0;
}

/* ---- area and convexity ------------------------------------------------- */

#define TEST_PI 3.14159265358979323846

/* Area of a planar polygon in 3D (x, y, z; w ignored), via the vector area. */
static inline double ref_area3(const double (*v)[4], int n)
{
    double s[3] = { 0, 0, 0 };
    for (int i = 0; i < n; i++) {
        const double *a = v[i], *b = v[(i + 1) % n];
        s[0] += a[1] * b[2] - a[2] * b[1];
        s[1] += a[2] * b[0] - a[0] * b[2];
        s[2] += a[0] * b[1] - a[1] * b[0];
    }
    return 0.5 * sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
}

/* Signed shoelace area of 2D points (x[i], y[i]). */
static inline double shoelace(const double *x, const double *y, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++) {
        int j = (i + 1) % n;
        s += x[i] * y[j] - x[j] * y[i];
    }
    return 0.5 * s;
}

/* Convex (weakly: collinear runs allowed) with a consistent turn direction
 * and a total turn of exactly one revolution, which also rules out stars.
 * Edges shorter than min_edge are merged (the clipper may emit duplicates);
 * a turn counts as reversed only if its sine is below -sin_tol. */
static inline bool convex2(const double *x0, const double *y0, int n0, double min_edge, double sin_tol)
{
    double x[REF_MAX_VERTS], y[REF_MAX_VERTS];
    int n = 0;
    for (int i = 0; i < n0; i++) {
        if (n > 0 && hypot(x0[i] - x[n - 1], y0[i] - y[n - 1]) < min_edge)
            continue;
        x[n] = x0[i];
        y[n] = y0[i];
        n++;
    }
    while (n > 1 && hypot(x[0] - x[n - 1], y[0] - y[n - 1]) < min_edge)
        n--;
    if (n < 3)
        return true; /* collapsed to a point or segment: degenerate, trivially convex */
    int sign = 0;
    double turn = 0;
    for (int i = 0; i < n; i++) {
        int j = (i + 1) % n, k = (i + 2) % n;
        double ex = x[j] - x[i], ey = y[j] - y[i], fx = x[k] - x[j], fy = y[k] - y[j];
        double cr = ex * fy - ey * fx, dt = ex * fx + ey * fy;
        double s = cr / (hypot(ex, ey) * hypot(fx, fy));
        turn += atan2(cr, dt);
        if (fabs(s) <= sin_tol)
            continue;
        int sg = s > 0 ? 1 : -1;
        if (sign == 0)
            sign = sg;
        else if (sg != sign)
            return false;
    }
    return sign == 0 || fabs(fabs(turn) - 2 * TEST_PI) < 1e-6;
}

/* Projects a clip-space polygon with w = 1 (so clip space is affine) to the
 * 2D plane of triangle (t0, t1, t2), dropping the axis along which the
 * triangle's normal is largest, and checks convexity there. */
static inline bool convex_in_triangle_plane(const sr_polygon *p, const sr_vertex_out *t0, const sr_vertex_out *t1,
                                            const sr_vertex_out *t2)
{
    double e1[3], e2[3], nrm[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)t1->v[k] - t0->v[k];
        e2[k] = (double)t2->v[k] - t0->v[k];
    }
    nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
    nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
    nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
    int drop = 0;
    for (int k = 1; k < 3; k++)
        if (fabs(nrm[k]) > fabs(nrm[drop]))
            drop = k;
    int u = drop == 0 ? 1 : 0, v = drop == 2 ? 1 : 2;
    double x[REF_MAX_VERTS], y[REF_MAX_VERTS];
    for (int i = 0; i < p->count; i++) {
        x[i] = p->vert[i].v[u];
        y[i] = p->vert[i].v[v];
    }
    return convex2(x, y, p->count, 1e-6, 1e-4);
}

/* The edge in -> out walked both ways: clips (in, out, third_a) and
 * (out, in, third_b) against the plane; true if both hold, bit for bit, the
 * cut vertex sr_clip_intersect makes (a polygon dropped whole, as one with a
 * vertex at w <= 0 is, holds it trivially). *standing: both polygons were
 * left standing. */
static inline bool clip_same_cut_both_ways(sr_clip_plane plane, const sr_vertex_out *in, const sr_vertex_out *out,
                                           const sr_vertex_out *third_a, const sr_vertex_out *third_b,
                                           const sr_clip_config *cfg, bool *standing)
{
    sr_polygon a = { .count = 3, .vert = { *in, *out, *third_a } };
    sr_polygon b = { .count = 3, .vert = { *out, *in, *third_b } };
    sr_clip_polygon(&a, 1u << plane, 4, cfg);
    sr_clip_polygon(&b, 1u << plane, 4, cfg);
    sr_vertex_out cut;
    sr_clip_intersect(plane, in, out, 4, cfg, &cut);
    bool in_a = a.count == 0, in_b = b.count == 0;
    for (int i = 0; i < a.count; i++)
        in_a = in_a || memcmp(a.vert[i].v, cut.v, 4 * sizeof(float)) == 0;
    for (int i = 0; i < b.count; i++)
        in_b = in_b || memcmp(b.vert[i].v, cut.v, 4 * sizeof(float)) == 0;
    *standing = a.count > 0 && b.count > 0;
    return in_a && in_b;
}

#endif
