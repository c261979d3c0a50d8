/* Cut vertices after several planes against GNU MP: conformance-style
 * clip-space triangles (corners up to 30000·w outside three planes, w over
 * [0.2, 16) and over eight decades) clipped by sr_clip_polygon, each output
 * vertex snapped by the viewport stage, against the triangle clipped in
 * rationals (Sutherland–Hodgman with no rounding at all) and snapped from
 * the exact point. A vertex cut by two planes is the triangle's point on
 * both (clip_corner.h); when the first cut was rounded to float before the
 * second, the worst vertex was hundreds of subpixel steps off under exact
 * clipping and under adaptive (issue 12, item 3; docs/precision.md). Then
 * the corner clipper's own promises: varyings with the positions' weights
 * and within the vertices' range, positions that no varying can change, and
 * the triangles it hands back to edge-by-edge clipping. */
#include <criterion/criterion.h>
#include <gmp.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "clip_helpers.h"
#include "exact_cut.h"
#include "pipeline/04_clip/clip_corner.h"
#include "pipeline/06_viewport.h"

#define TRIANGLES 3000
#define VIEW_W 1920
#define VIEW_H 1080
/* An exact point this close (in subpixel steps) to a rounding tie may snap
 * to either side: the float vertex itself (x, w rounded once each) moves
 * the snapped point by about 1920·128·2^-23 steps. */
#define TIE_STEPS 0.05

/* ---- the exact clipper: rationals, the planes of clip.h ---- */

typedef struct exact_poly {
    int n;
    mpq_t v[REF_MAX_VERTS][4];
} exact_poly;

static void exact_poly_init(exact_poly *p)
{
    for (int i = 0; i < REF_MAX_VERTS; i++)
        for (int k = 0; k < 4; k++)
            mpq_init(p->v[i][k]);
    p->n = 0;
}

static void exact_poly_clear(exact_poly *p)
{
    for (int i = 0; i < REF_MAX_VERTS; i++)
        for (int k = 0; k < 4; k++)
            mpq_clear(p->v[i][k]);
}

static void exact_clip(exact_poly *p, unsigned planes, const sr_clip_depth *depth, exact_poly *scratch)
{
    mpq_t dc, dn, t, s;
    mpq_inits(dc, dn, t, s, NULL);
    for (int plane = 0; plane < SR_CLIP_PLANES && p->n > 0; plane++) {
        if (!(planes & (1u << plane)))
            continue;
        scratch->n = 0;
        for (int i = 0; i < p->n; i++) {
            mpq_t *cur = p->v[i], *nxt = p->v[(i + 1) % p->n];
            exact_distance(plane, cur, depth, dc);
            exact_distance(plane, nxt, depth, dn);
            if (mpq_sgn(dc) >= 0) {
                for (int k = 0; k < 4; k++)
                    mpq_set(scratch->v[scratch->n][k], cur[k]);
                scratch->n++;
            }
            if ((mpq_sgn(dc) >= 0) != (mpq_sgn(dn) >= 0)) {
                mpq_sub(s, dc, dn);
                mpq_div(s, dc, s);
                for (int k = 0; k < 4; k++) {
                    mpq_sub(t, nxt[k], cur[k]);
                    mpq_mul(t, t, s);
                    mpq_add(scratch->v[scratch->n][k], cur[k], t);
                }
                scratch->n++;
            }
        }
        p->n = scratch->n < 3 ? 0 : scratch->n;
        for (int i = 0; i < p->n; i++)
            for (int k = 0; k < 4; k++)
                mpq_set(p->v[i][k], scratch->v[i][k]);
    }
    mpq_clears(dc, dn, t, s, NULL);
}

/* The viewport's subpixel coordinate (x/w + 1)·W/2·2^bits of an exact
 * point, as a double (exact to far below a step). */
static double exact_subpixel(mpq_t along, mpq_t w, int size, double sign)
{
    mpq_t q;
    mpq_init(q);
    mpq_div(q, along, w);
    double r = (sign * mpq_get_d(q) + 1.0) * 0.5 * size * SR_SUBPIXEL_ONE;
    if (fabs(r) > 1e6) { /* far from the screen: the double quotient will do */
        mpq_clear(q);
        return r;
    }
    mpq_t h;
    mpq_init(h);
    mpq_set_si(h, size * SR_SUBPIXEL_ONE, 2);
    if (sign < 0)
        mpq_neg(q, q);
    mpq_mul(q, q, h);
    mpq_add(q, q, h);
    r = mpq_get_d(q);
    mpq_clears(q, h, NULL);
    return r;
}

/* Steps between the snapped vertex and the exact point's snap; a point
 * within TIE_STEPS of a tie may take either neighbour. */
static long long snap_error(long long snapped, double exact)
{
    long long nearest = llrint(exact), off = llabs(snapped - nearest);
    double frac = exact - floor(exact);
    return off == 1 && fabs(frac - 0.5) < TIE_STEPS ? 0 : off;
}

/* How many of the planes an exact point lies on. */
static int planes_through(mpq_t *const c, unsigned planes, const sr_clip_depth *depth)
{
    mpq_t d;
    mpq_init(d);
    int on = 0;
    for (int p = 0; p < SR_CLIP_PLANES; p++) {
        exact_distance(p, c, depth, d);
        on += (planes >> p & 1u) && mpq_sgn(d) == 0;
    }
    mpq_clear(d);
    return on;
}

/* ---- conformance-style triangles ---- */

/* x/w, y/w up to 30000 outside the sides (half of them at 15000 to 30000,
 * as conformance suites place corners). */
static double conformance_ratio(test_rng *r)
{
    double m = rng_below(r, 2) ? rng_uniform(r, 15000.0, 30000.0) : log_uniform(r, 0.01, 30000.0);
    return rng_below(r, 2) ? m : -m;
}

/* The triangle's w where it covers the centre of the screen (x = y = 0),
 * or 0 where it does not. */
static double w_at_centre(const sr_vertex_out v[3])
{
    double l[3], sum = 0.0, w = 0.0;
    for (int k = 0; k < 3; k++) {
        const float *p = v[(k + 1) % 3].v, *q = v[(k + 2) % 3].v;
        l[k] = (double)p[SR_X] * q[SR_Y] - (double)q[SR_X] * p[SR_Y];
        sum += l[k];
    }
    for (int k = 0; k < 3; k++)
        w += l[k] / sum * v[k].v[SR_W];
    return sum != 0.0 && w > 0.0 ? w : 0.0;
}

/* Three vertices outside the sides and (two triangles in three) near or
 * far too: z/w = αx/w + βy/w + γ, linear on the screen, so the near and far
 * lines cross it; the third triangle gets a perspective depth model with
 * its near or far plane at about the triangle's w on the screen. */
static void conformance_triangle(test_rng *r, int n, double w_max, sr_vertex_out v[3], sr_clip_depth *depth)
{
    double alpha = rng_uniform(r, -1, 1), beta = rng_uniform(r, -1, 1), gamma = rng_uniform(r, -0.5, 1.5);
    for (int k = 0; k < 3; k++) {
        double w = log_uniform(r, 0.2 * 16.0 / w_max, w_max), x = conformance_ratio(r), y = conformance_ratio(r);
        v[k] = vert4(x * w, y * w, (alpha * x + beta * y + gamma) * w, w);
    }
    *depth = (sr_clip_depth){ .on = false };
    double centre = w_at_centre(v);
    if (n % 3 || !(centre > 0.0))
        return;
    bool far_cut = rng_below(r, 2);
    double near = far_cut ? centre * rng_uniform(r, 0.5, 2.0) / 100.0 : centre * rng_uniform(r, 0.5, 2.0);
    float nf = (float)near, ff = (float)(near * 100.0);
    *depth = (sr_clip_depth){ .on = true, .a = ff / (ff - nf), .b = -nf * ff / (ff - nf) };
}

typedef struct corner_errors {
    long long max;    /* steps, over every vertex */
    long long max_cut_twice; /* over the vertices the exact clipper cut more than once */
    int vertices, twice, unpaired;
} corner_errors;

/* Clips TRIANGLES triangles at one precision, their vertices' w over
 * [3.2 / w_max, w_max); each vertex's snapped error. */
static corner_errors measure(sr_clip_precision precision, uint64_t seed, double w_max)
{
    test_rng r = { seed };
    corner_errors e = { 0 };
    static exact_poly exact, scratch;
    exact_poly_init(&exact);
    exact_poly_init(&scratch);
    sr_viewport vp = { .width = VIEW_W, .height = VIEW_H, .subpixel_bits = SR_SUBPIXEL_BITS, .guard = 1.0f };
    double tolerance = 0.5 / ((double)SR_SUBPIXEL_ONE * VIEW_W);
    for (int n = 0; n < TRIANGLES; n++) {
        sr_vertex_out v[3];
        sr_clip_depth depth;
        conformance_triangle(&r, n, w_max, v, &depth);
        unsigned any = 0, all = SR_OUT_PLANES;
        for (int k = 0; k < 3; k++) {
            unsigned c = sr_clip_outcode_with(v[k].v, &depth);
            any |= c;
            all &= c;
        }
        if (!any || all)
            continue;
        sr_polygon poly = poly3(v[0], v[1], v[2]);
        vp.depth = depth;
        sr_clip_config cfg = { .precision = precision, .ndc_tolerance = tolerance, .depth = depth };
        sr_clip_polygon(&poly, any, 4, &cfg);
        exact.n = 3;
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < 4; i++)
                mpq_set_d(exact.v[k][i], v[k].v[i]);
        exact_clip(&exact, any, &depth, &scratch);
        if (poly.count != exact.n) { /* every vertex is classified exactly: only w <= 0 may drop one */
            e.unpaired++;
            continue;
        }
        for (int i = 0; i < poly.count; i++) {
            sr_screen_vertex s;
            cr_assert(sr_viewport_map(&poly.vert[i], 0, &vp, &s), "triangle %d vertex %d: %a %a %a %a", n, i,
                      poly.vert[i].v[0], poly.vert[i].v[1], poly.vert[i].v[2], poly.vert[i].v[3]);
            long long err = snap_error(s.x, exact_subpixel(exact.v[i][SR_X], exact.v[i][SR_W], VIEW_W, 1.0));
            long long ey = snap_error(s.y, exact_subpixel(exact.v[i][SR_Y], exact.v[i][SR_W], VIEW_H, -1.0));
            err = ey > err ? ey : err;
            bool twice = planes_through(exact.v[i], any, &depth) >= 2;
            e.max = err > e.max ? err : e.max;
            e.vertices++;
            if (twice) {
                e.twice++;
                e.max_cut_twice = err > e.max_cut_twice ? err : e.max_cut_twice;
            }
        }
    }
    exact_poly_clear(&exact);
    exact_poly_clear(&scratch);
    if (getenv("SOFTRAST_CORNERS_VERBOSE"))
        printf("precision %d: %d vertices (%d on two planes, %d polygons unpaired), max %lld steps (on two planes %lld)\n",
               precision, e.vertices, e.twice, e.unpaired, e.max, e.max_cut_twice);
    return e;
}

Test(clip_corners, exact_snaps_every_vertex_to_the_exact_points_subpixel)
{
    corner_errors e = measure(SR_CLIP_EXACT, 0xC0A1E5ull, 16.0);
    cr_assert_gt(e.twice, 200, "only %d vertices on two planes: the triangles are too tame", e.twice);
    cr_assert_eq(e.unpaired, 0, "%d polygons with another vertex count than the exact one", e.unpaired);
    cr_assert_eq(e.max, 0, "a vertex snapped %lld steps from the exact one (%d vertices)", e.max, e.vertices);
}

Test(clip_corners, adaptive_snaps_every_vertex_within_one_step)
{
    corner_errors e = measure(SR_CLIP_ADAPTIVE, 0xC0A1E6ull, 16.0);
    cr_assert_gt(e.twice, 200, "only %d vertices on two planes: the triangles are too tame", e.twice);
    cr_assert_eq(e.unpaired, 0, "%d polygons with another vertex count than the exact one", e.unpaired);
    cr_assert_leq(e.max, 1, "a vertex snapped %lld steps from the exact one (%d vertices)", e.max, e.vertices);
}

/* The same with w over eight decades, [3.2e-4, 1e4). */
Test(clip_corners, both_hold_with_w_over_eight_decades)
{
    corner_errors exact = measure(SR_CLIP_EXACT, 0xC0A1E7ull, 1e4);
    corner_errors adaptive = measure(SR_CLIP_ADAPTIVE, 0xC0A1E8ull, 1e4);
    cr_assert_gt(exact.twice, 200, "only %d vertices on two planes", exact.twice);
    cr_assert_eq(exact.max, 0, "exact: a vertex snapped %lld steps from the exact one", exact.max);
    cr_assert_leq(adaptive.max, 1, "adaptive: a vertex snapped %lld steps from the exact one", adaptive.max);
}

/* ---- the corner clipper's own promises ---- */

/* A triangle across the left and top planes whose corner on both lies
 * inside it, with `varyings` varyings of the given values. */
static sr_polygon corner_triangle(int varyings, const float values[3][SR_MAX_VARYINGS])
{
    sr_polygon p = poly3(vert4(-7.0, 0.25, 0.5, 1.0), vert4(0.5, 9.0, 0.5, 3.0), vert4(0.25, -0.5, 0.5, 2.0));
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < varyings; i++)
            p.vert[k].v[SR_VARYINGS_AT + i] = values[k][i];
    return p;
}

static const unsigned LEFT_TOP = 1u << SR_PLANE_LEFT | 1u << SR_PLANE_TOP;

Test(clip_corners, positions_do_not_depend_on_the_varyings)
{
    static const float none[3][SR_MAX_VARYINGS] = { { 0 } };
    static const float wild[3][SR_MAX_VARYINGS] = { { -32766.0f, 1e30f, 0.5f }, { 0.0f, -1e-30f, 7.0f },
                                                    { 3.0f, 2.0f, -1.0f } };
    for (int precision = SR_CLIP_ADAPTIVE; precision <= SR_CLIP_EXACT; precision += SR_CLIP_EXACT - SR_CLIP_ADAPTIVE) {
        sr_clip_counts plain_counts = { { 0 } }, shaded_counts = { { 0 } };
        sr_polygon plain = corner_triangle(0, none), shaded = corner_triangle(3, wild);
        sr_clip_polygon(&plain, LEFT_TOP, SR_VARYINGS_AT,
                        &(sr_clip_config){ .precision = (sr_clip_precision)precision, .counts = &plain_counts });
        sr_clip_polygon(&shaded, LEFT_TOP, SR_VARYINGS_AT + 3,
                        &(sr_clip_config){ .precision = (sr_clip_precision)precision, .counts = &shaded_counts });
        cr_assert_eq(plain.count, shaded.count);
        cr_assert_gt(plain.count, 3);
        for (int i = 0; i < plain.count; i++)
            cr_assert(floats_identical(plain.vert[i].v, shaded.vert[i].v, SR_VARYINGS_AT), "vertex %d", i);
        cr_assert(memcmp(&plain_counts, &shaded_counts, sizeof plain_counts) == 0, "the counts depend on the shading");
        cr_assert_eq(plain_counts.edge_by_edge, 0);
    }
}

/* The corner's varyings: Σ λ_k·f_k with the position's weights, inside the
 * vertices' range even where rounding of the weights would leave it. */
Test(clip_corners, corner_varyings_use_the_position_weights_and_stay_in_range)
{
    static const float values[3][SR_MAX_VARYINGS] = { { 1.0f, -32766.0f }, { 1.0f, 0.0f }, { 1.0f, -3.0f } };
    sr_polygon p = corner_triangle(2, values);
    sr_vertex_out corner;
    cr_assert_eq(sr_clip_corner(p.vert, SR_PLANE_LEFT, SR_PLANE_TOP, SR_VARYINGS_AT + 2, SR_CLIP_EXACT, 0.0, NULL,
                                &corner),
                 SR_CLIP_EXACT);
    cr_assert_eq(corner.v[SR_X], -corner.v[SR_W]);
    cr_assert_eq(corner.v[SR_Y], corner.v[SR_W]);
    cr_assert_eq(corner.v[SR_VARYINGS_AT], 1.0f, "a constant varying stays constant: %a", corner.v[SR_VARYINGS_AT]);
    /* The weights, from the distances: the same point in double. */
    double l[3], sum = 0.0, v = 0.0;
    for (int k = 0; k < 3; k++) {
        const float *a = p.vert[(k + 1) % 3].v, *b = p.vert[(k + 2) % 3].v;
        double pa = a[SR_W] + a[SR_X], pb = b[SR_W] + b[SR_X], qa = a[SR_W] - a[SR_Y], qb = b[SR_W] - b[SR_Y];
        l[k] = pa * qb - pb * qa;
        sum += l[k];
    }
    for (int k = 0; k < 3; k++) {
        cr_assert_geq(l[k] / sum, 0.0, "the corner lies in the triangle");
        v += l[k] / sum * values[k][1];
    }
    cr_assert_float_eq(corner.v[SR_VARYINGS_AT + 1], v, 1e-3);
    cr_assert(corner.v[SR_VARYINGS_AT + 1] >= -32766.0f && corner.v[SR_VARYINGS_AT + 1] <= 0.0f);
}

/* Two vertices at the same point: Σ c = 0 and no corner. (sr_clip_polygon
 * then clips the triangle edge by edge and counts it; with every vertex
 * classified exactly its walk never asks for such a corner: 10^6 random
 * small-integer triangles, a third of them degenerate, never fell back.) */
Test(clip_corners, no_corner_on_a_degenerate_triangle)
{
    sr_polygon p = poly3(vert4(-7.0, 9.0, 0.5, 1.0), vert4(0.5, 0.25, 0.5, 3.0), vert4(-7.0, 9.0, 0.5, 1.0));
    sr_vertex_out corner;
    cr_assert_eq(sr_clip_corner(p.vert, SR_PLANE_LEFT, SR_PLANE_TOP, SR_VARYINGS_AT, SR_CLIP_EXACT, 0.0, NULL, &corner),
                 SR_CLIP_ADAPTIVE);
}

/* A corner off the triangle (the two lines meet outside it): none is made. */
Test(clip_corners, no_corner_off_the_triangle)
{
    sr_polygon p = poly3(vert4(-0.5, 0.5, 0.5, 1.0), vert4(0.5, 0.5, 0.5, 1.0), vert4(-0.5, -0.5, 0.5, 1.0));
    sr_vertex_out corner;
    cr_assert_eq(sr_clip_corner(p.vert, SR_PLANE_LEFT, SR_PLANE_TOP, SR_VARYINGS_AT, SR_CLIP_EXACT, 0.0, NULL, &corner),
                 SR_CLIP_ADAPTIVE);
}
