/* The depth-plane inputs of a clipped polygon's vertices against GNU MP.
 * The viewport snaps every polygon vertex from its float clip position but
 * takes its unsnapped point (x + x_off, y + y_off) and z from the
 * triangle's point on the vertex's two lines, computed from the triangle's
 * clip positions in double (sr_viewport_map_polygon; docs/precision.md,
 * "Depth from the unsnapped vertices"). Here, on random triangles across
 * the side planes and near or far (with and without the depth model),
 * clipped at every precision: each cut's point in rationals, from the same
 * double clip positions, mapped exactly, and the drawn vertex within a
 * bound of the double evaluation's rounding (past the float rounding of
 * x_off, y_off and z); each corner of the triangle mapped bit for bit as
 * the vertex phase maps it. The float vertices differ from the double ones
 * as the vertex stage's float product does (a few units in the last
 * place): the same cuts mapped from float miss the bound on most of them
 * (all but corners of two side planes under the depth model, whose x/w,
 * y/w are exact and whose z rounds alike), so the bound sees a cut mapped
 * from float. Then a cut of an edge two triangles share, the same screen
 * vertex in both. Last, lines that do not meet in front of the eye. */
#include <criterion/criterion.h>
#include <float.h>
#include <gmp.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clip_helpers.h"
#include "exact_cut.h"
#include "pipeline/06_viewport.h"

#define TRIANGLES 3000
#define VIEW_W 1920
#define VIEW_H 1080
/* The double evaluation's bound takes first-order terms only: twice it
 * covers the rest. */
#define SAFETY 2.0
static const double U = DBL_EPSILON / 2.0; /* a double rounding, relative */
static const double F = FLT_EPSILON / 2.0; /* a float rounding, relative */

/* ---- random triangles in clip space, double and float ---- */

/* x/w or y/w: mostly near the screen, one in four up to 30000 outside. */
static double screen_ratio(test_rng *r)
{
    double m = rng_below(r, 4) ? rng_uniform(r, 0.0, 3.0) : log_uniform(r, 1.0, 30000.0);
    return rng_below(r, 2) ? m : -m;
}

/* Three vertices in double with w over [0.2, 16); z/w linear on the screen
 * across near and far, or (one triangle in two) a perspective depth model
 * whose near or far plane runs through the triangle's range of w. The
 * float vertices are the double ones off by up to 4 units in the last
 * place, as the vertex stage's float product leaves them. */
static void random_triangle(test_rng *r, double tri_d[3][4], sr_vertex_out v[3], sr_clip_depth *depth)
{
    double alpha = rng_uniform(r, -1, 1), beta = rng_uniform(r, -1, 1), gamma = rng_uniform(r, -0.5, 1.5);
    for (int k = 0; k < 3; k++) {
        double w = log_uniform(r, 0.2, 16.0), x = screen_ratio(r), y = screen_ratio(r);
        double c[4] = { x * w, y * w, (alpha * x + beta * y + gamma) * w, w };
        for (int i = 0; i < 4; i++)
            tri_d[k][i] = c[i];
    }
    *depth = (sr_clip_depth){ .on = false };
    if (rng_below(r, 2)) {
        double w_mid = log_uniform(r, 0.3, 10.0);
        bool far_cut = rng_below(r, 2);
        float n = (float)(far_cut ? w_mid / 100.0 : w_mid), f = n * 100.0f;
        *depth = (sr_clip_depth){ .on = true, .a = f / (f - n), .b = -n * f / (f - n) };
        for (int k = 0; k < 3; k++)
            tri_d[k][SR_Z] = (double)depth->a * tri_d[k][SR_W] + depth->b;
    }
    for (int k = 0; k < 3; k++) {
        v[k] = vert4(0, 0, 0, 0);
        for (int i = 0; i < 4; i++)
            v[k].v[i] = (float)(tri_d[k][i] * (1.0 + rng_uniform(r, -4.0, 4.0) * FLT_EPSILON));
    }
}

/* ---- the exact point on two lines, and the bound on its double twin ---- */

/* A line's vector over the triangle (stages.h, SR_CLIP_ON_PLANE), exact, and
 * the size each entry's double evaluation rounds against (0: exact). */
static void exact_line(mpq_t e[3][4], int line, const sr_clip_depth *depth, mpq_t v[3], double size[3])
{
    for (int k = 0; k < 3; k++) {
        if (line < SR_CLIP_ON_PLANE) {
            mpq_set_si(v[k], k == (line + 2) % 3, 1);
            size[k] = 0.0;
            continue;
        }
        int plane = line - SR_CLIP_ON_PLANE;
        exact_distance(plane, e[k], depth, v[k]);
        const sr_clip_plane_row *row = &sr_clip_plane_table[plane];
        double w = fabs(mpq_get_d(e[k][SR_W]));
        if (depth->on && row->axis == SR_Z)
            size[k] = w + fabs(depth->a * w) + fabs(depth->b);
        else
            size[k] = w + fabs(mpq_get_d(e[k][row->axis]));
    }
}

typedef struct exact_point {
    double ndc[3];  /* x/w, y/w and z_ndc of the exact point */
    double bound[3]; /* the double evaluation's error bound on each, first order */
} exact_point;

/* The triangle's point on two lines, c = P × Q, X = Σ c_k·E_k / Σ c_k in
 * rationals; false where the lines do not meet. The bound: each distance
 * within 3 roundings of its size, so each weight within
 * 3u(|P_i|·S^Q_j + …) + 2u(|P_i·Q_j| + |P_j·Q_i|); a weight's error moves X
 * by its share of (E_k − X); the sums and the division add their own. */
static bool exact_point_on_lines(const double tri_d[3][4], int line1, int line2, const sr_clip_depth *depth,
                                 exact_point *out)
{
    mpq_t e[3][4], p[3], q[3], c[3], sum, t, x[4];
    double sp[3], sq[3], cd[3], ec[3], csum = 0.0;
    for (int k = 0; k < 3; k++) {
        for (int i = 0; i < 4; i++) {
            mpq_init(e[k][i]);
            mpq_set_d(e[k][i], tri_d[k][i]);
        }
        mpq_inits(p[k], q[k], c[k], NULL);
    }
    mpq_inits(sum, t, x[0], x[1], x[2], x[3], NULL);
    exact_line(e, line1, depth, p, sp);
    exact_line(e, line2, depth, q, sq);
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        mpq_mul(c[k], p[i], q[j]);
        mpq_mul(t, p[j], q[i]);
        mpq_sub(c[k], c[k], t);
        mpq_add(sum, sum, c[k]);
        double pi = fabs(mpq_get_d(p[i])), pj = fabs(mpq_get_d(p[j])), qi = fabs(mpq_get_d(q[i])),
               qj = fabs(mpq_get_d(q[j]));
        ec[k] = 3.0 * U * (pi * sq[j] + qj * sp[i] + pj * sq[i] + qi * sp[j]) + 2.0 * U * (pi * qj + pj * qi);
        cd[k] = mpq_get_d(c[k]);
        csum += fabs(cd[k]);
    }
    bool meet = mpq_sgn(sum) != 0;
    double X[4], eX[4];
    for (int r = 0; r < 4 && meet; r++) {
        mpq_set_ui(x[r], 0, 1);
        for (int k = 0; k < 3; k++) {
            mpq_mul(t, c[k], e[k][r]);
            mpq_add(x[r], x[r], t);
        }
        mpq_div(x[r], x[r], sum);
        X[r] = mpq_get_d(x[r]);
        double moved = 0.0, terms = 0.0, s = fabs(mpq_get_d(sum));
        for (int k = 0; k < 3; k++) {
            moved += ec[k] * fabs(tri_d[k][r] - X[r]);
            terms += fabs(cd[k] * tri_d[k][r]);
        }
        eX[r] = (moved + 3.0 * U * terms + 2.0 * U * csum * fabs(X[r])) / s + U * fabs(X[r]);
    }
    if (meet) {
        double w = X[SR_W];
        for (int a = 0; a < 2; a++) {
            mpq_div(t, x[a], x[SR_W]);
            out->ndc[a] = mpq_get_d(t);
            out->bound[a] = (eX[a] + fabs(out->ndc[a]) * eX[SR_W]) / fabs(w) + U * fabs(out->ndc[a]);
        }
        if (depth->on) { /* z_ndc = a + b/w */
            mpq_set_d(t, depth->b);
            mpq_div(t, t, x[SR_W]);
            double b_over_w = mpq_get_d(t);
            mpq_set_d(sum, depth->a);
            mpq_add(t, t, sum);
            out->ndc[2] = mpq_get_d(t);
            out->bound[2] = fabs(b_over_w) * eX[SR_W] / fabs(w) + 2.0 * U * (fabs(b_over_w) + fabs(out->ndc[2]));
        } else {
            mpq_div(t, x[SR_Z], x[SR_W]);
            out->ndc[2] = mpq_get_d(t);
            out->bound[2] = (eX[SR_Z] + fabs(out->ndc[2]) * eX[SR_W]) / fabs(w) + U * fabs(out->ndc[2]);
        }
    }
    for (int k = 0; k < 3; k++) {
        for (int i = 0; i < 4; i++)
            mpq_clear(e[k][i]);
        mpq_clears(p[k], q[k], c[k], NULL);
    }
    mpq_clears(sum, t, x[0], x[1], x[2], x[3], NULL);
    return meet;
}

/* ---- the drawn vertex against it ---- */

/* Subpixel units per NDC unit, and the screen coordinate of an NDC one. */
#define X_UNITS (VIEW_W * 0.5 * SR_SUBPIXEL_ONE)
#define Y_UNITS (VIEW_H * 0.5 * SR_SUBPIXEL_ONE)

/* How far the vertex's depth-plane inputs lie from the exact point, past
 * the float rounding of x_off, y_off and z (half a unit in their last
 * place), in units of the double evaluation's bound (x and y in subpixel
 * units, z in z_ndc): the largest of the three. */
static double over_double_bound(const sr_screen_vertex *s, const exact_point *e)
{
    double sx = (e->ndc[0] + 1.0) * X_UNITS, sy = (1.0 - e->ndc[1]) * Y_UNITS;
    double got[3] = { (double)s->x + s->x_off, (double)s->y + s->y_off, s->z };
    double want[3] = { sx, sy, e->ndc[2] };
    double to_float[3] = { F * fabs(s->x_off), F * fabs(s->y_off), F * fabs(e->ndc[2]) };
    double bound[3] = { X_UNITS * e->bound[0] + 3.0 * U * fabs(sx), Y_UNITS * e->bound[1] + 3.0 * U * fabs(sy),
                        e->bound[2] };
    double worst = 0.0;
    for (int a = 0; a < 3; a++)
        worst = fmax(worst, fmax(0.0, fabs(got[a] - want[a]) - to_float[a]) / bound[a]);
    return worst;
}

typedef struct cut_tally {
    int vertices, cuts, on_two_planes, on_near_far, from_float_within;
    double worst;           /* over_double_bound's largest */
    double largest_bound_x; /* subpixels */
} cut_tally;

/* A clipped polygon's vertex, s as sr_viewport_map_polygon mapped it. */
typedef struct polygon_vertex {
    const sr_vertex_out *clip; /* its float clip position */
    const sr_screen_vertex *s;
    int line1, line2; /* the lines it lies on */
} polygon_vertex;

/* Two mappings of a vertex alike, bit for bit. */
static bool same_mapping(const sr_screen_vertex *a, const sr_screen_vertex *b)
{
    return a->x == b->x && a->y == b->y && a->x_off == b->x_off && a->y_off == b->y_off && a->z == b->z &&
           a->inv_w == b->inv_w;
}

/* A corner of the triangle (on two of its edges) maps as the vertex phase
 * maps that vertex, bit for bit. */
static void check_corner(const double tri_d[3][4], const polygon_vertex *v, const sr_viewport *vp, int n)
{
    int k = (v->line1 + 1) % 3 == v->line2 ? v->line2 : v->line1; /* edge k runs from vertex k to k + 1 */
    sr_screen_vertex want;
    cr_assert(sr_viewport_map_d(v->clip, tri_d[k], 0, vp, &want));
    cr_assert(same_mapping(v->s, &want), "triangle %d: its vertex %d maps otherwise than the vertex phase maps it", n,
              k);
}

/* A cut: its depth-plane inputs within the bound of the exact point on its
 * lines, from tri_d; under adaptive and exact, its snapped point within a
 * step of the float triangle's exact point on them (test_clip_corners.c),
 * so the lines are the vertex's. */
static void check_cut(sr_clip_precision precision, const double tri_d[3][4], const double tri_f[3][4],
                      const polygon_vertex *v, const sr_viewport *vp, int n, cut_tally *tally)
{
    int l1 = v->line1, l2 = v->line2;
    exact_point e;
    cr_assert(exact_point_on_lines(tri_d, l1, l2, &vp->depth, &e), "triangle %d: lines %d, %d do not meet", n, l1,
              l2);
    if (precision == SR_CLIP_ADAPTIVE || precision == SR_CLIP_EXACT) {
        exact_point f;
        cr_assert(exact_point_on_lines(tri_f, l1, l2, &vp->depth, &f));
        cr_assert(llabs(v->s->x - llrint((f.ndc[0] + 1.0) * X_UNITS)) <= 1 &&
                      llabs(v->s->y - llrint((1.0 - f.ndc[1]) * Y_UNITS)) <= 1,
                  "triangle %d: a vertex snapped more than a step from its lines' point", n);
    }
    double over = over_double_bound(v->s, &e);
    cr_assert_leq(over, SAFETY, "triangle %d, the vertex on lines %d, %d: %.3g times the bound", n, l1, l2, over);
    sr_screen_vertex from_float;
    cr_assert(sr_viewport_map(v->clip, 0, vp, &from_float));
    tally->from_float_within += over_double_bound(&from_float, &e) <= SAFETY;
    tally->cuts++;
    tally->on_two_planes += l1 >= SR_CLIP_ON_PLANE && l2 >= SR_CLIP_ON_PLANE;
    for (int p = SR_PLANE_NEAR; p <= SR_PLANE_FAR; p++)
        tally->on_near_far += l1 == SR_CLIP_ON_PLANE + p || l2 == SR_CLIP_ON_PLANE + p;
    tally->worst = fmax(tally->worst, over);
    tally->largest_bound_x = fmax(tally->largest_bound_x, X_UNITS * e.bound[0]);
}

/* Triangle tri (tri_d in double, v in float) clipped at this precision and
 * mapped as the draw maps it; false where nothing is clipped or left. */
static bool clip_and_map(sr_clip_precision precision, const double tri_d[3][4], const sr_vertex_out v[3],
                         const sr_viewport *vp, sr_polygon *poly, sr_screen_vertex *s)
{
    unsigned any = 0, all = SR_OUT_PLANES;
    for (int k = 0; k < 3; k++) {
        unsigned c = sr_clip_outcode_with(v[k].v, &vp->depth);
        any |= c;
        all &= c;
    }
    if (!any || all)
        return false;
    *poly = poly3(v[0], v[1], v[2]);
    sr_clip_config cfg = { .precision = precision, .ndc_tolerance = draw_clip_tolerance(VIEW_W, VIEW_H),
                           .depth = vp->depth };
    if (sr_clip_polygon(poly, any, SR_VARYINGS_AT, &cfg) < 3)
        return false;
    cr_assert(sr_viewport_map_polygon(poly, tri_d, 0, vp, s), "a clipped triangle refused");
    return true;
}

static cut_tally measure(sr_clip_precision precision, uint64_t seed)
{
    test_rng r = { seed };
    cut_tally tally = { 0 };
    sr_viewport vp = { .width = VIEW_W, .height = VIEW_H, .subpixel_bits = SR_SUBPIXEL_BITS, .guard = 1.0f };
    for (int n = 0; n < TRIANGLES; n++) {
        double tri_d[3][4], tri_f[3][4];
        sr_vertex_out v[3];
        random_triangle(&r, tri_d, v, &vp.depth);
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < 4; i++)
                tri_f[k][i] = v[k].v[i];
        sr_polygon poly;
        sr_screen_vertex s[SR_MAX_CLIP_VERTS];
        if (!clip_and_map(precision, tri_d, v, &vp, &poly, s))
            continue;
        for (int i = 0; i < poly.count; i++) {
            polygon_vertex pv = { &poly.vert[i], &s[i], poly.line[i > 0 ? i - 1 : poly.count - 1], poly.line[i] };
            tally.vertices++;
            if (pv.line1 < SR_CLIP_ON_PLANE && pv.line2 < SR_CLIP_ON_PLANE)
                check_corner(tri_d, &pv, &vp, n);
            else
                check_cut(precision, tri_d, tri_f, &pv, &vp, n, &tally);
        }
    }
    if (getenv("SOFTRAST_CUTS_VERBOSE"))
        printf("precision %d: %d vertices, %d cuts (%d on two planes, %d on near or far), worst %.3g of the bound "
               "(largest x bound %.3g subpixels); mapped from float, %d cuts within it\n",
               precision, tally.vertices, tally.cuts, tally.on_two_planes, tally.on_near_far, tally.worst,
               tally.largest_bound_x, tally.from_float_within);
    return tally;
}

static void check(sr_clip_precision precision, uint64_t seed)
{
    cut_tally t = measure(precision, seed);
    cr_assert_gt(t.cuts, 3000, "only %d cut vertices", t.cuts);
    cr_assert_gt(t.on_two_planes, 200, "only %d vertices on two planes", t.on_two_planes);
    cr_assert_gt(t.on_near_far, 500, "only %d vertices on near or far", t.on_near_far);
    cr_assert_lt(t.from_float_within, t.cuts / 4, "%d of %d cuts mapped from float are within the bound too",
                 t.from_float_within, t.cuts);
}

Test(cut_depth, adaptive_cuts_take_depth_from_the_exact_point_in_double)
{
    check(SR_CLIP_ADAPTIVE, 0xC07D0001ull);
}

Test(cut_depth, exact_cuts_take_depth_from_the_exact_point_in_double)
{
    check(SR_CLIP_EXACT, 0xC07D0002ull);
}

Test(cut_depth, double_cuts_take_depth_from_the_exact_point_in_double)
{
    check(SR_CLIP_DOUBLE, 0xC07D0003ull);
}

Test(cut_depth, float_cuts_take_depth_from_the_exact_point_in_double)
{
    check(SR_CLIP_FLOAT, 0xC07D0004ull);
}

/* The vertex of poly on lines edge and plane line p (either order); -1 if none. */
static int vertex_on_lines(const sr_polygon *poly, int edge, int p)
{
    for (int i = 0; i < poly->count; i++) {
        int l1 = poly->line[i > 0 ? i - 1 : poly->count - 1], l2 = poly->line[i];
        if ((l1 == edge && l2 == p) || (l1 == p && l2 == edge))
            return i;
    }
    return -1;
}

/* Two triangles that share an edge, (a, b, c) and (d, b, a) with d inside
 * the side planes, each clipped on its own (one may cross more planes than
 * the other, so one may cut from the triangle and the other edge by edge;
 * the precision goes round with the pair): a cut of the shared edge, its
 * edge 0 in one and edge 1, walked the other way, in the other, is the same
 * screen vertex in both, snapped point, offsets, z and 1/w, so neighbours
 * hand the rasterizer one depth plane along the edge at every precision. */
Test(cut_depth, a_cut_of_a_shared_edge_maps_alike_in_both_triangles)
{
    test_rng r = { 0xC07D0005ull };
    sr_viewport vp = { .width = VIEW_W, .height = VIEW_H, .subpixel_bits = SR_SUBPIXEL_BITS, .guard = 1.0f };
    int shared = 0;
    for (int n = 0; n < TRIANGLES; n++) {
        double tri_d[3][4];
        sr_vertex_out v[3];
        random_triangle(&r, tri_d, v, &vp.depth);
        /* d: its z on the triangle's depth model, or anywhere in front */
        double w = log_uniform(&r, 0.2, 16.0), x = rng_uniform(&r, -0.9, 0.9), y = rng_uniform(&r, -0.9, 0.9);
        double z = vp.depth.on ? (double)vp.depth.a * w + vp.depth.b : rng_uniform(&r, 0.0, 1.0) * w;
        double nb_d[3][4] = { { x * w, y * w, z, w } };
        memcpy(nb_d[1], tri_d[1], sizeof nb_d[1]);
        memcpy(nb_d[2], tri_d[0], sizeof nb_d[2]);
        const sr_vertex_out nb[3] = { vert4(nb_d[0][0], nb_d[0][1], nb_d[0][2], nb_d[0][3]), v[1], v[0] };
        sr_clip_precision precision = (sr_clip_precision)(n % SR_CLIP_PRECISIONS);
        sr_polygon pa, pb;
        sr_screen_vertex sa[SR_MAX_CLIP_VERTS], sb[SR_MAX_CLIP_VERTS];
        if (!clip_and_map(precision, tri_d, v, &vp, &pa, sa) || !clip_and_map(precision, nb_d, nb, &vp, &pb, sb))
            continue;
        for (int p = SR_CLIP_ON_PLANE; p < SR_CLIP_ON_PLANE + SR_CLIP_PLANES; p++) {
            int i = vertex_on_lines(&pa, 0, p), j = vertex_on_lines(&pb, 1, p);
            if (i < 0 || j < 0)
                continue;
            const sr_screen_vertex *a = &sa[i], *b = &sb[j];
            cr_assert(a->x == b->x && a->y == b->y, "pair %d, precision %d, plane %d: snapped apart", n, precision,
                      p - SR_CLIP_ON_PLANE);
            cr_assert(same_mapping(a, b),
                      "pair %d, precision %d, plane %d: x_off %a / %a, y_off %a / %a, z %a / %a", n, precision,
                      p - SR_CLIP_ON_PLANE, a->x_off, b->x_off, a->y_off, b->y_off, a->z, b->z);
            shared++;
        }
    }
    cr_assert_gt(shared, 800, "only %d cuts of a shared edge", shared);
}

/* Lines that do not meet in the triangle (near and far where w is
 * constant: Σ c = 0) or meet behind the eye (left and right meet at w = 0):
 * the vertex maps from its float position alone. */
Test(cut_depth, a_vertex_whose_lines_do_not_meet_in_front_maps_from_its_float_position)
{
    static const int pairs[2][2] = { { SR_CLIP_ON_PLANE + SR_PLANE_NEAR, SR_CLIP_ON_PLANE + SR_PLANE_FAR },
                                     { SR_CLIP_ON_PLANE + SR_PLANE_LEFT, SR_CLIP_ON_PLANE + SR_PLANE_RIGHT } };
    double tri_d[3][4] = { { -0.5, -0.5, 0.25, 1.0 }, { 0.5, -0.25, 0.5, 1.0 }, { 0.0, 0.5, 0.75, 1.0 } };
    sr_viewport vp = { .width = VIEW_W, .height = VIEW_H, .subpixel_bits = SR_SUBPIXEL_BITS, .guard = 1.0f };
    for (int k = 0; k < 2; k++) {
        sr_polygon poly = poly3(vert4(-0.5, -0.5, 0.25, 1.0), vert4(0.25, 0.125, 0.5, 1.0), vert4(0, 0.5, 0.75, 1.0));
        poly.line[0] = (unsigned char)pairs[k][0];
        poly.line[1] = (unsigned char)pairs[k][1];
        poly.line[2] = 2;
        sr_screen_vertex s[3], want;
        cr_assert(sr_viewport_map_polygon(&poly, tri_d, 0, &vp, s));
        cr_assert(sr_viewport_map(&poly.vert[1], 0, &vp, &want));
        cr_assert(same_mapping(&s[1], &want),
                  "lines %d, %d: x_off %a, y_off %a, z %a; from float %a, %a, %a", pairs[k][0], pairs[k][1],
                  s[1].x_off, s[1].y_off, s[1].z, want.x_off, want.y_off, want.z);
    }
}
