/* Lines through the near plane, the far plane and the eye, from a
 * perspective camera, clipped as triangle edges are: under exact precision
 * each cut end is the GNU MP cut of the whole segment on its plane rounded
 * once to float (tests/exact_cut.h), the cut lies inside every other plane
 * exactly, and a triangle with the segment as an edge has the same cut
 * vertex bit for bit, under exact and adaptive precision alike
 * (docs/conventions.md, "A line is cut where the triangle edge under it
 * is"). */
#include <criterion/criterion.h>
#include <gmp.h>
#include <math.h>
#include <string.h>

#include "clip_helpers.h"
#include "exact_cut.h"
#include "pipeline/04_clip/clip_corner.h"
#include "pipeline/04_clip/clip_segment.h"

#define CASES 6000
#define NEAR 0.1
#define FAR 100.0

enum { THROUGH_NEAR, THROUGH_FAR, THROUGH_EYE, KINDS };

/* The clip position of view-space (x, y, z) under a left-handed
 * perspective projection with near NEAR and far FAR (z_ndc = A + B/w). */
static sr_vertex_out clip_of(double x, double y, double z, double fx, double fy)
{
    double a = FAR / (FAR - NEAR), b = -NEAR * FAR / (FAR - NEAR);
    sr_vertex_out v = vert4((float)(fx * x), (float)(fy * y), (float)(a * z + b), (float)z);
    v.v[SR_VARYINGS_AT] = v.v[SR_X];
    return v;
}

/* A view-space point at depth z inside the side planes of the projection
 * with focal scales fx, fy, at most 0.9 of the way to each. */
static void inside_point(test_rng *r, double z, double fx, double fy, double p[3])
{
    p[0] = rng_uniform(r, -0.9, 0.9) * z / fx;
    p[1] = rng_uniform(r, -0.9, 0.9) * z / fy;
    p[2] = z;
}

/* A segment from inside the view to a point between the eye and the near
 * plane, past the far plane, or behind the eye on the line from the inside
 * point through the eye (a hair off it, rounded to float); each leaves the
 * view through near or far, never a side. */
static void random_segment(test_rng *r, int kind, double fx, double fy, sr_vertex_out ends[2])
{
    double a[3], b[3];
    inside_point(r, log_uniform(r, 2 * NEAR, FAR / 2), fx, fy, a);
    if (kind == THROUGH_NEAR) {
        inside_point(r, rng_uniform(r, 0.01 * NEAR, 0.99 * NEAR), fx, fy, b);
    } else if (kind == THROUGH_FAR) {
        inside_point(r, log_uniform(r, FAR * 1.01, FAR * 100), fx, fy, b);
    } else {
        double s = log_uniform(r, 1e-3, 1e3);
        for (int c = 0; c < 3; c++)
            b[c] = -s * a[c];
    }
    ends[0] = clip_of(a[0], a[1], a[2], fx, fy);
    ends[1] = clip_of(b[0], b[1], b[2], fx, fy);
}

/* The exact cut of ends[0] -> ends[1] on `plane`, coordinate i, as a
 * double (one rounding of the rational). */
static double exact_cut(int plane, const sr_vertex_out ends[2], const sr_clip_depth *depth, int i)
{
    mpq_t c[2][4], d[2];
    for (int k = 0; k < 2; k++) {
        mpq_init(d[k]);
        for (int j = 0; j < 4; j++) {
            mpq_init(c[k][j]);
            mpq_set_d(c[k][j], ends[k].v[j]);
        }
        exact_distance(plane, c[k], depth, d[k]);
    }
    double r = exact_cut_coordinate(d[0], d[1], ends[0].v[i], ends[1].v[i]);
    for (int k = 0; k < 2; k++) {
        mpq_clear(d[k]);
        for (int j = 0; j < 4; j++)
            mpq_clear(c[k][j]);
    }
    return r;
}

/* got is the float nearest to ref, or its neighbour when ref lies within
 * a rounding of the midpoint of the two (test_clip_exact.c). */
static bool rounded_once(float got, double ref)
{
    float want = (float)ref;
    if (got == want)
        return true;
    if (got != nextafterf(want, INFINITY) && got != nextafterf(want, -INFINITY))
        return false;
    return fabs(ref - ((double)want + (double)got) / 2) <= 1e-15 * fabs(ref);
}

/* Whether the float point lies inside `plane` exactly (distance >= 0 in
 * rationals). */
static bool exactly_inside(int plane, const sr_vertex_out *v, const sr_clip_depth *depth)
{
    mpq_t c[4], d;
    mpq_init(d);
    for (int j = 0; j < 4; j++) {
        mpq_init(c[j]);
        mpq_set_d(c[j], v->v[j]);
    }
    exact_distance(plane, c, depth, d);
    bool inside = mpq_sgn(d) >= 0;
    mpq_clear(d);
    for (int j = 0; j < 4; j++)
        mpq_clear(c[j]);
    return inside;
}

/* Whether one of the clipped triangle's vertices is v, bit for bit in x, y
 * and w (z too without a depth model). */
static bool triangle_has(const sr_polygon *poly, int count, const sr_vertex_out *v, bool with_z)
{
    for (int i = 0; i < count; i++)
        if (memcmp(&poly->vert[i].v[SR_X], &v->v[SR_X], 2 * sizeof(float)) == 0 &&
            poly->vert[i].v[SR_W] == v->v[SR_W] && (!with_z || poly->vert[i].v[SR_Z] == v->v[SR_Z]))
            return true;
    return false;
}

Test(line_clip_exact, lines_through_near_far_and_the_eye_are_cut_as_exactly_as_triangle_edges)
{
    test_rng r = { 0x36 };
    const sr_clip_depth depths[2] = { { .on = false },
                                      { .on = true, .a = (float)(FAR / (FAR - NEAR)),
                                        .b = (float)(-NEAR * FAR / (FAR - NEAR)) } };
    int cuts[KINDS] = { 0 }, on_triangle = 0;
    for (int n = 0; n < CASES; n++) {
        int kind = n % KINDS;
        const sr_clip_depth *depth = &depths[n / KINDS % 2];
        sr_clip_precision precision = n / (2 * KINDS) % 2 ? SR_CLIP_EXACT : SR_CLIP_ADAPTIVE;
        double fx = log_uniform(&r, 0.5, 3), fy = fx * rng_uniform(&r, 1, 2);
        sr_vertex_out ends[2], out[2];
        random_segment(&r, kind, fx, fy, ends);
        if (depth->on)
            for (int k = 0; k < 2; k++)
                sr_clip_z_from_w(depth, ends[k].v);
        unsigned c0 = sr_clip_outcode_with(ends[0].v, depth), c1 = sr_clip_outcode_with(ends[1].v, depth);
        cr_assert_eq(c0, 0u, "case %d: the first end is inside", n);
        cr_assert(c1 & ((1u << SR_PLANE_NEAR) | (1u << SR_PLANE_FAR)), "case %d: the second end is past near or far",
                  n);
        sr_clip_config cfg = { .precision = precision, .ndc_tolerance = 1.0 / (256.0 * 2048.0), .depth = *depth };
        int cut[2];
        cr_assert(sr_clip_segment(ends, c1, SR_VARYINGS_AT + 1, &cfg, out, cut), "case %d: nothing kept", n);
        cr_assert_eq(cut[0], SR_SEGMENT_END_GIVEN, "case %d", n);
        int want_plane = kind == THROUGH_FAR ? SR_PLANE_FAR : SR_PLANE_NEAR;
        cr_assert_eq(cut[1], want_plane, "case %d (kind %d): cut on plane %d", n, kind, cut[1]);
        cr_assert(memcmp(&out[0], &ends[0], sizeof out[0]) == 0, "case %d: the inside end is kept as given", n);
        if (precision == SR_CLIP_EXACT)
            for (int i = 0; i < 4; i++)
                if (i != SR_Z) /* placed on the plane, or a·w + b under the depth model */
                    cr_assert(rounded_once(out[1].v[i], exact_cut(cut[1], ends, depth, i)),
                              "case %d (kind %d, depth %d): coordinate %d %a, exact %a", n, kind, depth->on, i,
                              out[1].v[i], exact_cut(cut[1], ends, depth, i));
        for (int plane = 0; plane < SR_CLIP_PLANES; plane++)
            if (plane != cut[1] && precision == SR_CLIP_EXACT)
                cr_assert(exactly_inside(plane, &out[1], depth), "case %d: the cut lies outside plane %d", n, plane);
        /* The triangle (a, b, c) with c inside: the cut on its edge a-b. */
        double c_view[3];
        inside_point(&r, log_uniform(&r, 2 * NEAR, FAR / 2), fx, fy, c_view);
        sr_vertex_out third = clip_of(c_view[0], c_view[1], c_view[2], fx, fy);
        if (depth->on)
            sr_clip_z_from_w(depth, third.v);
        sr_clip_counts counts = { { 0 } };
        cfg.counts = &counts;
        sr_polygon poly = poly3(ends[0], ends[1], third);
        int count = sr_clip_polygon(&poly, c1, SR_VARYINGS_AT + 1, &cfg);
        if (counts.edge_by_edge) /* a degenerate triangle: its own cuts */
            continue;
        cr_assert(triangle_has(&poly, count, &out[1], !depth->on),
                  "case %d (kind %d, depth %d, precision %d): the triangle's edge is cut elsewhere", n, kind,
                  depth->on, (int)precision);
        on_triangle++;
        cuts[kind]++;
    }
    for (int k = 0; k < KINDS; k++)
        cr_assert_gt(cuts[k], CASES / KINDS * 9 / 10, "kind %d: %d cases compared", k, cuts[k]);
    cr_assert_gt(on_triangle, CASES * 9 / 10);
}
