/* Section 1 of the stability report: how far the clipper's cut vertices are
 * from the exact ones. Each random triangle is transformed to clip space in
 * float exactly as the vertex stage does and clipped by sr_clip_polygon
 * against the planes its outcodes name; its trace hook hands over each cut,
 * which is compared with the exact intersection of the same float edge with
 * the same plane or, for a corner, with the triangle's exact point on both
 * planes (clip_exact.h, summed in long double). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pipeline/04_clip/clip_exact.h"
#include "pipeline/04_clip/expansion.h"
#include "core/clock.h"
#include "stability_clip.h"

#define CLIPPED_TRIANGLES 100000 /* clipped triangles measured per case */
#define MAX_ATTEMPTS (50 * CLIPPED_TRIANGLES)
#define PERCENTILE 0.99
#define SEED 0x5EEDC11Bu
#define TOLERANCE_SCREEN_SIDE 1920 /* pixels: the benchmark's width */

/* The exact cut of the traced edge, or the exact corner of the traced
 * triangle, rounded once from the exact quotient's parts in long double. */
static void exact_cut(const sr_clip_cut *c, long double cut[4])
{
    if (c->corner) {
        sr_clip_exact_corner corner;
        sr_clip_exact_corner_of(c->triangle, c->first, c->plane, NULL, &corner);
        long double denominator = expansion_value_long(corner.denominator, corner.denominator_terms);
        for (int i = 0; i < 4; i++) {
            double num[SR_CLIP_CORNER_NUMERATOR_TERMS];
            int n = sr_clip_exact_corner_numerator(&corner, c->triangle, i, num);
            cut[i] = expansion_value_long(num, n) / denominator;
        }
        return;
    }
    sr_clip_exact_edge edge;
    sr_clip_exact_edge_of(c->plane, c->inside, c->outside, NULL, &edge);
    long double denominator = expansion_value_long(edge.denominator, edge.denominator_terms);
    for (int i = 0; i < 4; i++) {
        double num[SR_CLIP_NUMERATOR_TERMS];
        int n = sr_clip_exact_numerator(&edge, c->inside->v[i], c->outside->v[i], num);
        cut[i] = expansion_value_long(num, n) / denominator;
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

/* ---- the trace: each cut of one triangle, against the exact one ---- */

typedef struct worst_cut {
    double error;  /* largest cut error so far */
    double w;      /* exact w of that cut */
    double spread; /* its end points' size over its own */
} worst_cut;

static double spread(const float *in, const float *out, const long double exact[4])
{
    long double ends[4];
    for (int i = 0; i < 4; i++)
        ends[i] = fabsl((long double)in[i]) > fabsl((long double)out[i]) ? in[i] : out[i];
    return (double)(max_norm(ends) / max_norm(exact));
}

static void measure_cut(void *context, const sr_clip_cut *c)
{
    worst_cut *worst = context;
    long double exact[4];
    exact_cut(c, exact);
    double e = cut_error(c->cut->v, exact);
    if (e > worst->error)
        *worst = (worst_cut){ .error = e, .w = (double)exact[SR_W], .spread = spread(c->inside->v, c->outside->v, exact) };
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
    worst_cut worst = { 0 };
    sr_clip_config cfg = { .precision = clipper->precision, .ndc_tolerance = sr_stability_clip_tolerance(),
                           .counts = &s->cuts, .trace = measure_cut, .trace_context = &worst };
    sr_polygon clipped = *input;
    sr_clip_polygon(&clipped, planes, SR_VARYINGS_AT, &cfg);
    if (worst.error > s->max || s->triangles == 0) {
        s->max = worst.error;
        s->worst_w = worst.w;
        s->worst_spread = worst.spread;
    }
    errors[s->triangles++] = worst.error;
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
            sr_sort_doubles(errors[i], (size_t)out[i].triangles);
            out[i].p99 = errors[i][(size_t)(PERCENTILE * (double)(out[i].triangles - 1))];
        }
        free(errors[i]);
    }
    return ok ? true : sr_error_set(err, "out of memory for the clipper's errors");
}
