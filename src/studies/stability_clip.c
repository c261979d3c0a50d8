/* Section 1 of the stability report: how far the clipper's cut vertices are
 * from the exact ones. Each random triangle is transformed to clip space in
 * float exactly as the vertex stage does and walked through Sutherland–
 * Hodgman against the planes its outcodes name, every cut made by
 * sr_clip_intersect; the walk is checked to give bit for bit what
 * sr_clip_polygon gives. Each cut is compared with the exact intersection of
 * the same float edge with the same plane. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "timing.h"
#include "stability.h"

#define CLIPPED_TRIANGLES 100000 /* clipped triangles measured per case */
#define MAX_ATTEMPTS (50 * CLIPPED_TRIANGLES)
#define PERCENTILE 0.99
#define SEED 0x5EEDC11Bu
#define TOLERANCE_SCREEN_SIDE 1920 /* pixels: the benchmark's width */
#define EXACT_TERMS 8              /* 2 distances × 2 parts × (product + its error) */

/* ---- the exact cut: error-free sums and products of the float inputs ---- */

/* s + e = a + b exactly (Knuth's two-sum). */
static void two_sum(double a, double b, double *s, double *e)
{
    *s = a + b;
    double bv = *s - a;
    *e = (a - (*s - bv)) + (b - bv);
}

/* Adds x to the expansion terms[0..n) exactly (Shewchuk's grow-expansion). */
static int grow(double *terms, int n, double x)
{
    for (int i = 0; i < n; i++)
        two_sum(x, terms[i], &x, &terms[i]);
    terms[n] = x;
    return n + 1;
}

static int add_product(double *terms, int n, double a, double b)
{
    double p = a * b;
    n = grow(terms, n, fma(a, b, -p)); /* the product's rounding error, exactly */
    return grow(terms, n, p);
}

/* A plane distance of a float vertex, exactly, as hi + lo. */
static void exact_distance(sr_clip_plane plane, const float *c, double d[2])
{
    static const int axis[SR_CLIP_PLANES] = { SR_Z, SR_Z, SR_X, SR_X, SR_Y, SR_Y };
    static const double w_part[SR_CLIP_PLANES] = { 0, 1, 1, 1, 1, 1 };
    static const double axis_part[SR_CLIP_PLANES] = { 1, -1, 1, -1, 1, -1 };
    two_sum(w_part[plane] * c[SR_W], axis_part[plane] * c[axis[plane]], &d[0], &d[1]);
}

static long double expansion_value(const double *terms, int n)
{
    long double v = 0.0L;
    for (int i = 0; i < n; i++)
        v += terms[i];
    return v;
}

/* v = (d_in·b − d_out·a) / (d_in − d_out), the point a + t(b − a) with both
 * sums exact, so only the quotient rounds (d_in ≥ 0 > d_out: no cancellation
 * below). */
static void exact_cut(sr_clip_plane plane, const float *in, const float *out, long double cut[4])
{
    double d_in[2], d_out[2], den[4];
    exact_distance(plane, in, d_in);
    exact_distance(plane, out, d_out);
    int dn = grow(den, grow(den, grow(den, grow(den, 0, d_in[1]), d_in[0]), -d_out[1]), -d_out[0]);
    long double denominator = expansion_value(den, dn);
    for (int i = 0; i < 4; i++) {
        double num[EXACT_TERMS];
        int n = 0;
        for (int k = 0; k < 2; k++) {
            n = add_product(num, n, d_in[k], out[i]);
            n = add_product(num, n, -d_out[k], in[i]);
        }
        cut[i] = expansion_value(num, n) / denominator;
    }
}

static long double max_norm(const long double v[4])
{
    long double m = 0.0L;
    for (int i = 0; i < 4; i++)
        m = fabsl(v[i]) > m ? fabsl(v[i]) : m;
    return m;
}

/* ‖cut − exact‖∞ / ‖exact‖∞. Inside the clip volume ‖exact‖∞ = w, so this
 * is the error relative to |w| (NDC-sized); a cut vertex that later planes
 * clip away may have |x| ≫ w, and there it is the plain relative error. */
static double cut_error(const float *cut, const long double exact[4])
{
    long double diff[4];
    for (int i = 0; i < 4; i++)
        diff[i] = (long double)cut[i] - exact[i];
    return (double)(max_norm(diff) / max_norm(exact));
}

/* ---- the walk: sr_clip_polygon's Sutherland–Hodgman, watching each cut ---- */

typedef struct walk {
    const sr_clip_config *cfg;
    double worst;   /* largest cut error so far */
    double worst_w; /* exact w of that cut */
    double worst_spread; /* its end points' size over its own */
} walk;

static double spread(const float *in, const float *out, const long double exact[4])
{
    long double ends[4];
    for (int i = 0; i < 4; i++)
        ends[i] = fabsl((long double)in[i]) > fabsl((long double)out[i]) ? in[i] : out[i];
    return (double)(max_norm(ends) / max_norm(exact));
}

static void walk_cut(walk *wk, sr_clip_plane plane, const sr_vertex_out *in, const sr_vertex_out *out,
                     sr_vertex_out *cut)
{
    long double exact[4];
    sr_clip_intersect(plane, in, out, SR_VARYINGS_AT, wk->cfg, cut);
    exact_cut(plane, in->v, out->v, exact);
    double e = cut_error(cut->v, exact);
    if (e > wk->worst) {
        wk->worst = e;
        wk->worst_w = (double)exact[SR_W];
        wk->worst_spread = spread(in->v, out->v, exact);
    }
}

/* One plane; -1 where sr_clip_polygon would give up (past the vertex bound). */
static int walk_plane(walk *wk, const sr_vertex_out *in, int n, sr_clip_plane plane, sr_vertex_out *out)
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        const sr_vertex_out *a = &in[i], *b = &in[i + 1 < n ? i + 1 : 0];
        bool a_in = sr_clip_distance(plane, a->v) >= 0.0, b_in = sr_clip_distance(plane, b->v) >= 0.0;
        if (m + a_in + (a_in != b_in) > SR_MAX_CLIP_VERTS)
            return -1;
        if (a_in)
            out[m++] = *a;
        if (a_in != b_in)
            walk_cut(wk, plane, a_in ? a : b, a_in ? b : a, &out[m++]); /* inside → outside, always */
    }
    return m;
}

static void walk_polygon(walk *wk, sr_polygon *poly, unsigned planes)
{
    sr_vertex_out scratch[SR_MAX_CLIP_VERTS];
    for (int p = 0; p < SR_CLIP_PLANES && poly->count >= 3; p++) {
        if (!(planes & (1u << p)))
            continue;
        int n = walk_plane(wk, poly->vert, poly->count, (sr_clip_plane)p, scratch);
        poly->count = n < 3 ? 0 : n;
        memcpy(poly->vert, scratch, (size_t)poly->count * sizeof scratch[0]);
    }
    for (int i = 0; i < poly->count; i++) /* sr_clip_polygon drops what reaches w <= 0 */
        if (!(poly->vert[i].v[SR_W] > 0.0f))
            poly->count = 0;
}

/* Bit for bit, position only (the cuts write no varyings here). */
static bool same_polygon(const sr_polygon *a, const sr_polygon *b)
{
    bool same = a->count == b->count;
    for (int i = 0; same && i < a->count; i++)
        same = memcmp(a->vert[i].v, b->vert[i].v, SR_VARYINGS_AT * sizeof(float)) == 0;
    return same;
}

/* ---- per case ---- */

/* Half a subpixel step, as sr_draw asks of the adaptive clipper. */
double sr_stability_clip_tolerance(void)
{
    return 1.0 / ((double)SR_SUBPIXEL_ONE * TOLERANCE_SCREEN_SIDE);
}

/* The triangle in clip space and the planes it crosses; false if the
 * pipeline would not clip it (accepted, rejected or non-finite). */
static bool to_clip_space(const mat4 clip_from_world, vec3 tri[3], sr_polygon *poly, unsigned *planes)
{
    unsigned all = SR_OUT_PLANES | SR_OUT_NONFINITE, any = 0;
    memset(poly, 0, sizeof *poly);
    poly->count = 3;
    for (int k = 0; k < 3; k++) {
        vec4 p = { tri[k][0], tri[k][1], tri[k][2], 1.0f }, clip; /* cglm stores 16-byte aligned */
        glm_mat4_mulv((vec4 *)clip_from_world, p, clip);
        memcpy(poly->vert[k].v, clip, sizeof clip);
        unsigned code = sr_clip_outcode(poly->vert[k].v);
        all &= code;
        any |= code;
    }
    *planes = any;
    return any && !all && !(any & SR_OUT_NONFINITE);
}

/* Clips one triangle with one clipper and adds what it finds to s; true if
 * nothing is left. */
static bool measure(const sr_polygon *input, unsigned planes, const sr_stability_clipper *clipper, double *errors,
                    sr_stability_clip_stats *s)
{
    sr_clip_config cfg = { .precision = clipper->precision, .ndc_tolerance = sr_stability_clip_tolerance(),
                           .counts = &s->cuts };
    sr_clip_config quiet = { .precision = clipper->precision, .ndc_tolerance = cfg.ndc_tolerance };
    walk wk = { .cfg = &cfg };
    sr_polygon walked = *input, clipped = *input;
    walk_polygon(&wk, &walked, planes);
    sr_clip_polygon(&clipped, planes, SR_VARYINGS_AT, &quiet);
    s->walk_differs += !same_polygon(&walked, &clipped);
    if (wk.worst > s->max || s->triangles == 0) {
        s->max = wk.worst;
        s->worst_w = wk.worst_w;
        s->worst_spread = wk.worst_spread;
    }
    errors[s->triangles++] = wk.worst;
    return clipped.count == 0;
}

/* Where the exact clipper sits in sr_stability_clippers: the judge of "lost". */
static int exact_clipper(void)
{
    for (int i = 0; i < SR_STABILITY_CLIPPERS; i++)
        if (sr_stability_clippers[i].precision == SR_CLIP_EXACT)
            return i;
    return 0;
}

bool sr_stability_clip_errors(const sr_stability_case *c, sr_stability_clip_stats out[SR_STABILITY_CLIPPERS],
                              sr_error *err)
{
    double *errors[SR_STABILITY_CLIPPERS];
    bool ok = true;
    for (int i = 0; i < SR_STABILITY_CLIPPERS; i++) {
        errors[i] = malloc(CLIPPED_TRIANGLES * sizeof(double));
        ok = ok && errors[i];
        out[i] = (sr_stability_clip_stats){ 0 };
    }
    sr_stability_rng rng = { SEED };
    mat4 clip_from_world;
    sr_stability_clip_matrix(&c->camera, clip_from_world);
    for (int attempt = 0; ok && attempt < MAX_ATTEMPTS && out[0].triangles < CLIPPED_TRIANGLES; attempt++) {
        vec3 tri[3];
        sr_polygon input;
        unsigned planes;
        c->triangle(c, &rng, tri);
        if (!to_clip_space(clip_from_world, tri, &input, &planes))
            continue;
        bool empty[SR_STABILITY_CLIPPERS];
        for (int i = 0; i < SR_STABILITY_CLIPPERS; i++)
            empty[i] = measure(&input, planes, &sr_stability_clippers[i], errors[i], &out[i]);
        for (int i = 0; i < SR_STABILITY_CLIPPERS; i++)
            out[i].lost += empty[i] && !empty[exact_clipper()];
    }
    for (int i = 0; i < SR_STABILITY_CLIPPERS; i++) {
        if (ok && out[i].triangles) {
            sr_study_sort_doubles(errors[i], (size_t)out[i].triangles);
            out[i].p99 = errors[i][(size_t)(PERCENTILE * (double)(out[i].triangles - 1))];
        }
        free(errors[i]);
    }
    return ok ? true : sr_error_set(err, "out of memory for the clipper's errors");
}
