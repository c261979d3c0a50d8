/* Stage 4 on random and adversarial input: the watertight contract on
 * thousands of shared edges, all six planes on random triangles against an
 * independent reference clipper, and perspective scenes that span the eye,
 * touch it or use a near plane of 1e-6 (DESIGN.md, "Clipping: the numerical
 * contract"). Fixed seeds; failing inputs are printed as hex floats. */
#include <float.h>
#include <math.h>
#include <string.h>

#include <cglm/cglm.h>
#include <cglm/clipspace/persp_lh_zo.h>
#include <criterion/criterion.h>

#include "clip_helpers.h"

#define FB_W 640
#define FB_H 480

/* ---- the watertight contract ------------------------------------------- */

/* One end point of a shared edge, drawn from one of several families: the
 * ordinary case and the adversarial ones the contract is written for. */
static sr_vertex_out edge_vertex(test_rng *r, int family)
{
    sr_vertex_out v = vert4(rng_uniform(r, -3, 3), rng_uniform(r, -3, 3), rng_uniform(r, -2, 3), rng_uniform(r, 0.2, 3));
    float *c = v.v;
    switch (family) {
    case 1: /* magnitudes spread over 12 decades, any sign of w */
        for (int k = 0; k < 4; k++)
            c[k] = (float)rng_log_signed(r, -6, 6);
        break;
    case 2: { /* on a plane, or a few ulps either side */
        int plane = rng_below(r, SR_CLIP_PLANES), ulps = rng_below(r, 7) - 3;
        int k = sr_clip_plane_table[plane].axis;
        c[k] = sr_clip_plane_coordinate_at((sr_clip_plane)plane, c[SR_W]);
        for (; ulps > 0; ulps--)
            c[k] = nextafterf(c[k], INFINITY);
        for (; ulps < 0; ulps++)
            c[k] = nextafterf(c[k], -INFINITY);
        break;
    }
    case 3: { /* w at or next to 0 */
        const float ws[] = { 0.0f, -0.0f, 1e-30f, -1e-30f, FLT_TRUE_MIN, -FLT_TRUE_MIN, 1e-7f, -1e-7f };
        c[SR_W] = ws[rng_below(r, 8)];
        break;
    }
    case 4: /* behind the eye: w < 0, z following w as a perspective matrix does */
        c[SR_W] = (float)-rng_uniform(r, 0.01, 50);
        c[SR_Z] = (float)(1.001 * c[SR_W] - 0.1);
        break;
    case 5: { /* a perspective projection (near 0.1, far 100) of a view-space point */
        double vz = rng_uniform(r, -20, 40);
        c[SR_X] = (float)(1.3 * rng_uniform(r, -10, 10));
        c[SR_Y] = (float)(1.7 * rng_uniform(r, -10, 10));
        c[SR_Z] = (float)(100.0 / 99.9 * vz - 10.0 / 99.9);
        c[SR_W] = (float)vz;
        break;
    }
    default: break;
    }
    return v;
}

#define WATERTIGHT_FAMILIES 6
#define TAG SR_VARYINGS_AT /* a varying (the third vertex's weight), compared bit for bit too */

static unsigned mask_for(const sr_polygon *p, bool outcode_mask)
{
    if (!outcode_mask)
        return SR_OUT_PLANES;
    return sr_clip_outcode(p->vert[0].v) | sr_clip_outcode(p->vert[1].v) | sr_clip_outcode(p->vert[2].v);
}

/* What survives of segment a-b after the planes in `mask`, in the fixed
 * plane order, each cut made by sr_clip_intersect from the inside end toward
 * the outside one, as the contract says. Returns 0 (nothing left) or 2. */
static int clip_segment(sr_vertex_out a, sr_vertex_out b, unsigned mask, sr_vertex_out ends[2])
{
    for (int p = 0; p < SR_CLIP_PLANES; p++) {
        if (!(mask & (1u << p)))
            continue;
        bool a_in = ref_distance_f(p, &a) >= 0, b_in = ref_distance_f(p, &b) >= 0;
        if (!a_in && !b_in)
            return 0;
        sr_vertex_out cut;
        if (a_in && !b_in) {
            sr_clip_intersect((sr_clip_plane)p, &a, &b, SR_VARYINGS_AT + 1, &(sr_clip_config){ .precision = SR_CLIP_DOUBLE }, &cut);
            b = cut;
        } else if (!a_in && b_in) {
            sr_clip_intersect((sr_clip_plane)p, &b, &a, SR_VARYINGS_AT + 1, &(sr_clip_config){ .precision = SR_CLIP_DOUBLE }, &cut);
            a = cut;
        }
    }
    ends[0] = a;
    ends[1] = b;
    return 2;
}

static bool polygon_has(const sr_polygon *p, const sr_vertex_out *v)
{
    for (int i = 0; i < p->count; i++)
        if (floats_identical(p->vert[i].v, v->v, SR_VARYINGS_AT + 1))
            return true;
    return false;
}

/* Clips (a, b, c) and (b, a, d), which walk edge a-b in opposite directions,
 * and checks that the end points of what survives of a-b (its cut vertices,
 * or a and b themselves) are in both outputs bit for bit, position and the
 * varying. Returns the number of cut vertices checked, or -1 if skipped. */
static int check_shared_edge(sr_vertex_out a, sr_vertex_out b, sr_vertex_out c, sr_vertex_out d, bool outcode_mask)
{
    a.v[TAG] = b.v[TAG] = 0.0f;
    c.v[TAG] = d.v[TAG] = 1.0f;
    sr_polygon p[2] = { poly3(a, b, c), poly3(b, a, d) };
    unsigned mask[2];
    for (int s = 0; s < 2; s++) {
        mask[s] = mask_for(&p[s], outcode_mask);
        unsigned all = sr_clip_outcode(p[s].vert[0].v) & sr_clip_outcode(p[s].vert[1].v) &
                       sr_clip_outcode(p[s].vert[2].v);
        if (outcode_mask && (mask[s] & SR_OUT_NONFINITE || all))
            return -1; /* the pipeline rejects it before clipping */
        sr_clip_polygon(&p[s], mask[s], SR_VARYINGS_AT + 1, &(sr_clip_config){ .precision = SR_CLIP_DOUBLE });
    }
    int cuts = 0;
    for (int s = 0; s < 2; s++) {
        sr_vertex_out ends[2];
        if (!clip_segment(a, b, mask[s], ends))
            continue;
        for (int e = 0; e < 2; e++) {
            const float *v = ends[e].v;
            for (int t = 0; t < 2; t++)
                cr_assert(polygon_has(&p[t], &ends[e]),
                          "cut (%a, %a, %a, %a | %a) of edge a-b under the planes of triangle %d is missing from triangle %d;"
                          " a = (%a, %a, %a, %a), b = (%a, %a, %a, %a), c = (%a, %a, %a, %a), d = (%a, %a, %a, %a)",
                          v[0], v[1], v[2], v[3], v[TAG], s, t, a.v[0], a.v[1], a.v[2], a.v[3], b.v[0], b.v[1],
                          b.v[2], b.v[3], c.v[0], c.v[1], c.v[2], c.v[3], d.v[0], d.v[1], d.v[2], d.v[3]);
            cuts += !floats_identical(v, a.v, SR_VARYINGS_AT + 1) && !floats_identical(v, b.v, SR_VARYINGS_AT + 1);
        }
    }
    return cuts;
}

static void check_many_shared_edges(uint64_t seed, bool outcode_mask)
{
    test_rng r = { seed };
    int compared[WATERTIGHT_FAMILIES] = { 0 };
    for (int n = 0; n < 24000; n++) {
        int fa = n % WATERTIGHT_FAMILIES, fb = rng_below(&r, WATERTIGHT_FAMILIES);
        sr_vertex_out a = edge_vertex(&r, fa), b = edge_vertex(&r, fb);
        sr_vertex_out c = edge_vertex(&r, rng_below(&r, 2) ? 0 : 5), d = edge_vertex(&r, rng_below(&r, 2) ? 0 : 5);
        int k = check_shared_edge(a, b, c, d, outcode_mask);
        if (k > 0)
            compared[fa] += k;
    }
    /* Not vacuous: every family produced plenty of cut vertices to compare. */
    for (int f = 0; f < WATERTIGHT_FAMILIES; f++)
        cr_assert_gt(compared[f], 1000, "family %d compared only %d cut vertices", f, compared[f]);
}

Test(clip, keeps_shared_edges_bit_identical)
{
    check_many_shared_edges(30, false);
}

Test(clip, keeps_shared_edges_bit_identical_under_outcode_masks)
{
    /* The pipeline clips each triangle only against the planes its own
     * outcodes name, so the two neighbours may use different plane sets. */
    check_many_shared_edges(31, true);
}

/* ---- all six planes, random triangles with w = 1 ------------------------ */

#define RANDOM_TRIANGLES 5000

/* Vertices span well outside the volume [-1, 1]² × [0, 1]; w = 1 keeps clip
 * space affine, so areas and convexity are those of ordinary 3D polygons. */
static void random_w1_triangle(test_rng *r, sr_vertex_out tri[3])
{
    for (int i = 0; i < 3; i++)
        tri[i] = vert4(rng_uniform(r, -4, 4), rng_uniform(r, -4, 4), rng_uniform(r, -3.5, 4.5), 1.0);
}

typedef void all_planes_check(const sr_vertex_out tri[3], const sr_polygon *poly);

/* Clips RANDOM_TRIANGLES triangles against all planes and checks each; fails
 * unless a tenth of them kept something, so no test using it is vacuous. */
static void for_each_random_triangle(uint64_t seed, all_planes_check *check)
{
    test_rng r = { seed };
    int kept = 0;
    for (int n = 0; n < RANDOM_TRIANGLES; n++) {
        sr_vertex_out tri[3];
        random_w1_triangle(&r, tri);
        sr_polygon poly = poly3(tri[0], tri[1], tri[2]);
        sr_clip_polygon(&poly, SR_OUT_PLANES, SR_VARYINGS_AT, &(sr_clip_config){ .precision = SR_CLIP_DOUBLE });
        kept += poly.count > 0;
        check(tri, &poly);
    }
    cr_assert_gt(kept, RANDOM_TRIANGLES / 10, "only %d of %d triangles kept anything", kept, RANDOM_TRIANGLES);
}

static void at_most_nine(const sr_vertex_out tri[3], const sr_polygon *poly)
{
    (void)tri;
    cr_assert(poly->count == 0 || (poly->count >= 3 && poly->count <= SR_MAX_CLIP_VERTS), "%d vertices", poly->count);
}

Test(clip_random, all_planes_output_never_exceeds_nine_vertices)
{
    cr_assert_eq(SR_MAX_CLIP_VERTS, 9);
    for_each_random_triangle(40, at_most_nine);
}

/* Inside tolerance: 1e-6·|w|. A cut vertex is rounded to float once per
 * coordinate, so it can sit a few ulps (2^-24 ≈ 6e-8 relative) outside a plane
 * it was not placed on; 1e-6 is a wide margin that still catches any real
 * escape. */
static void inside_volume(const sr_vertex_out tri[3], const sr_polygon *poly)
{
    (void)tri;
    for (int i = 0; i < poly->count; i++)
        for (int p = 0; p < SR_CLIP_PLANES; p++) {
            double d = ref_distance_f(p, &poly->vert[i]);
            cr_assert_geq(d, -1e-6 * fabs(poly->vert[i].v[SR_W]), "vertex %d outside %s by %g", i, plane_name(p), d);
        }
}

Test(clip_random, all_planes_output_is_inside_the_volume)
{
    for_each_random_triangle(41, inside_volume);
}

static void convex(const sr_vertex_out tri[3], const sr_polygon *poly)
{
    cr_assert(convex_in_triangle_plane(poly, &tri[0], &tri[1], &tri[2]), "%d vertices", poly->count);
}

Test(clip_random, all_planes_output_is_convex)
{
    for_each_random_triangle(42, convex);
}

static void area_as_reference(const sr_vertex_out tri[3], const sr_polygon *poly)
{
    sr_polygon in = poly3(tri[0], tri[1], tri[2]);
    ref_poly ref = ref_from_sr(&in), got = ref_from_sr(poly);
    ref_clip(&ref, SR_OUT_PLANES);
    double a = ref_area3((const double(*)[4])got.v, got.n), b = ref_area3((const double(*)[4])ref.v, ref.n);
    /* Vertices rounded to float (coordinates <= 4.5, ulp 5e-7) move the area
     * by at most perimeter × ulp, well under 1e-5. */
    cr_assert(fabs(a - b) <= 1e-5, "area %.9g, reference %.9g; (%a %a %a) (%a %a %a) (%a %a %a)", a, b, tri[0].v[0],
              tri[0].v[1], tri[0].v[2], tri[1].v[0], tri[1].v[1], tri[1].v[2], tri[2].v[0], tri[2].v[1], tri[2].v[2]);
}

Test(clip_random, all_planes_area_matches_reference_clipper)
{
    for_each_random_triangle(43, area_as_reference);
}

static void outcode_mask_is_enough(const sr_vertex_out tri[3], const sr_polygon *poly)
{
    sr_polygon p = poly3(tri[0], tri[1], tri[2]);
    unsigned mask = sr_clip_outcode(tri[0].v) | sr_clip_outcode(tri[1].v) | sr_clip_outcode(tri[2].v);
    sr_clip_polygon(&p, mask, SR_VARYINGS_AT, &(sr_clip_config){ .precision = SR_CLIP_DOUBLE });
    cr_assert_eq(p.count, poly->count, "mask %#x", mask);
    for (int i = 0; i < p.count; i++)
        cr_assert(floats_identical(p.vert[i].v, poly->vert[i].v, SR_VARYINGS_AT), "vertex %d differs", i);
}

Test(clip_random, clipping_only_the_outcode_planes_equals_clipping_all)
{
    for_each_random_triangle(44, outcode_mask_is_enough);
}

/* ---- perspective scenes: across, at and through the eye ----------------- */

#define SCENE_RANDOM 4000

/* Left-handed view space, +z forward; the eye is at the origin. */
static const double eye_cases[][3][3] = {
    { { -1, -1, 5 }, { 1, -1, 5 }, { 0, 1, -3 } },         /* one vertex behind the eye */
    { { -1, -1, -5 }, { 1, -1, -5 }, { 0, 1, 3 } },        /* two behind */
    { { 0.5, 0.3, 0 }, { 1, -1, 4 }, { -1, -1, 4 } },      /* one in the eye plane: w = 0 exactly */
    { { 0, 0, 0 }, { 1, 0, 5 }, { 0, 1, 5 } },             /* one at the eye */
    { { 0, 0, 5 }, { 0, 0, -5 }, { 2, 1, 5 } },            /* an edge through the eye */
    { { -2, -1, -1 }, { 2, -1, -1 }, { 0, 2, 2 } },        /* the eye inside the triangle */
    { { -1, -1, 1 }, { 1, -1, 1 }, { 0, 1, -1000 } },      /* one far behind */
    { { -1, 0.5, 1e-6 }, { 1, 0.5, 1e-6 }, { 0, 0, -1000 } }, /* on a 1e-6 near plane, one far behind */
    { { 0, 0, 500 }, { 0, 0, -1000 }, { 1, 1, 500 } },    /* an edge along the view axis through the eye */
};

static sr_vertex_out project(mat4 P, const double view[3])
{
    vec4 in = { (float)view[0], (float)view[1], (float)view[2], 1.0f }, out;
    glm_mat4_mulv(P, in, out);
    return vert4(out[0], out[1], out[2], out[3]);
}

/* A random view-space triangle of one of the kinds the contract worries
 * about, with depths spread over the whole near..far range and behind. */
static void random_scene_triangle(test_rng *r, double near, double far, double v[3][3])
{
    int kind = rng_below(r, 5);
    for (int i = 0; i < 3; i++) {
        bool behind = (kind == 1 && i == 2) || (kind == 0 && rng_below(r, 3) == 0);
        double z = behind ? -pow(10.0, rng_uniform(r, -7, 6)) : near * pow(far / near, rng_uniform(r, 0, 1));
        v[i][0] = fabs(z) * rng_uniform(r, -3, 3);
        v[i][1] = fabs(z) * rng_uniform(r, -3, 3);
        v[i][2] = z;
    }
    if (kind == 2) /* one vertex in the eye plane: w = 0 */
        v[0][2] = 0.0;
    else if (kind == 3) { /* an edge through the eye, half the time along the view axis */
        double s = pow(10.0, rng_uniform(r, -3, 3));
        if (rng_below(r, 2))
            v[0][0] = v[0][1] = 0.0;
        for (int k = 0; k < 3; k++)
            v[1][k] = -s * v[0][k];
    } else if (kind == 4) /* a vertex a hair from the near plane */
        v[0][2] = near * (1.0 + rng_uniform(r, -1e-6, 1e-6));
}

/* Where a clipped polygon came from: the view-space triangle (printed on
 * failure) and its largest clip-space magnitude. */
typedef struct scene_input {
    double view[3][3];
    double magnitude;
} scene_input;

#define VIEW_FMT "view triangle (%.9g, %.9g, %.9g) (%.9g, %.9g, %.9g) (%.9g, %.9g, %.9g)"
#define VIEW_ARGS(in)                                                                                              \
    (in)->view[0][0], (in)->view[0][1], (in)->view[0][2], (in)->view[1][0], (in)->view[1][1], (in)->view[1][2],      \
        (in)->view[2][0], (in)->view[2][1], (in)->view[2][2]

typedef void scene_check(const sr_polygon *poly, const scene_input *in);

/* Classifies, rejects and clips as the pipeline does (only the planes the
 * outcodes name), and checks each polygon; fails unless a tenth of the random
 * triangles left a polygon, so no test using it is vacuous. */
static void for_each_scene_triangle(double near, double far, uint64_t seed, scene_check *check)
{
    mat4 P;
    glm_perspective_lh_zo(glm_rad(60.0f), (float)FB_W / FB_H, (float)near, (float)far, P);
    test_rng r = { seed };
    int n_fixed = (int)(sizeof eye_cases / sizeof eye_cases[0]), kept = 0;
    for (int n = 0; n < n_fixed + SCENE_RANDOM; n++) {
        scene_input in = { .magnitude = 0 };
        double(*v)[3] = in.view;
        if (n < n_fixed)
            memcpy(in.view, eye_cases[n], sizeof in.view);
        else
            random_scene_triangle(&r, near, far, v);
        sr_polygon poly = poly3(project(P, v[0]), project(P, v[1]), project(P, v[2]));
        unsigned c0 = sr_clip_outcode(poly.vert[0].v), c1 = sr_clip_outcode(poly.vert[1].v),
                 c2 = sr_clip_outcode(poly.vert[2].v);
        if ((c0 | c1 | c2) & SR_OUT_NONFINITE || (c0 & c1 & c2))
            continue;
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 4; k++)
                in.magnitude = fmax(in.magnitude, fabs(poly.vert[i].v[k]));
        if (c0 | c1 | c2)
            sr_clip_polygon(&poly, c0 | c1 | c2, SR_VARYINGS_AT, &(sr_clip_config){ .precision = SR_CLIP_DOUBLE });
        kept += poly.count > 0;
        check(&poly, &in);
    }
    cr_assert_gt(kept, SCENE_RANDOM / 10, "near %g far %g: only %d polygons were not empty", near, far, kept);
}

static void positive_w(const sr_polygon *poly, const scene_input *in)
{
    for (int i = 0; i < poly->count; i++) {
        const float *c = poly->vert[i].v;
        cr_assert(c[SR_W] > 0.0f && isfinite(1.0f / c[SR_W]), "vertex %d of %d: (%a, %a, %a, %a); " VIEW_FMT, i,
                  poly->count, c[0], c[1], c[2], c[3], VIEW_ARGS(in));
    }
}

/* Inside tolerance 1e-6·|w| + 1e-12·M, M the largest input magnitude: the
 * relative part is float rounding of the cut vertex (see above); the absolute
 * part covers the double-precision interpolation, whose error scales with the
 * parents (up to 1e6 here) rather than with the cut vertex (w down to 1e-6). */
static void inside_volume_scaled(const sr_polygon *poly, const scene_input *in)
{
    for (int i = 0; i < poly->count; i++)
        for (int p = 0; p < SR_CLIP_PLANES; p++) {
            double d = ref_distance_f(p, &poly->vert[i]);
            double tol = 1e-6 * fabs(poly->vert[i].v[SR_W]) + 1e-12 * in->magnitude;
            cr_assert_geq(d, -tol, "vertex %d outside %s by %g; " VIEW_FMT, i, plane_name(p), d, VIEW_ARGS(in));
        }
}

static void maps_into_viewport(const sr_polygon *poly, const scene_input *in)
{
    const double slack_x = SR_NDC_SLACK * FB_W / 2 * SR_SUBPIXEL_ONE, slack_y = SR_NDC_SLACK * FB_H / 2 * SR_SUBPIXEL_ONE;
    for (int i = 0; i < poly->count; i++) {
        const float *c = poly->vert[i].v;
        sr_screen_vertex s;
        cr_assert(sr_viewport_map(&poly->vert[i], 0, &(sr_viewport){ FB_W, FB_H, SR_SUBPIXEL_BITS, 1.0f }, &s), "vertex %d of %d refused: (%a, %a, %a, %a); " VIEW_FMT,
                  i, poly->count, c[0], c[1], c[2], c[3], VIEW_ARGS(in));
        cr_assert(s.x >= -slack_x && s.x <= FB_W * SR_SUBPIXEL_ONE + slack_x, "x = %lld", (long long)s.x);
        cr_assert(s.y >= -slack_y && s.y <= FB_H * SR_SUBPIXEL_ONE + slack_y, "y = %lld", (long long)s.y);
        cr_assert(isfinite(s.inv_w) && s.inv_w > 0 && isfinite(s.z), "1/w = %a, z = %a", s.inv_w, s.z);
    }
}

Test(clip_random, eye_spanning_output_has_positive_w)
{
    for_each_scene_triangle(0.1, 100, 50, positive_w);
}

Test(clip_random, eye_spanning_output_is_inside_the_volume)
{
    for_each_scene_triangle(0.1, 100, 51, inside_volume_scaled);
}

Test(clip_random, eye_spanning_output_maps_into_the_viewport)
{
    for_each_scene_triangle(0.1, 100, 52, maps_into_viewport);
}

Test(clip_random, near_plane_1e_6_output_has_positive_w_and_finite_inverse)
{
    for_each_scene_triangle(1e-6, 100, 53, positive_w);
}

Test(clip_random, near_plane_1e_6_output_is_inside_the_volume)
{
    for_each_scene_triangle(1e-6, 100, 54, inside_volume_scaled);
}

Test(clip_random, near_plane_1e_6_output_maps_into_the_viewport)
{
    for_each_scene_triangle(1e-6, 100, 55, maps_into_viewport);
}

Test(clip_random, far_over_near_1e9_output_has_positive_w_and_finite_inverse)
{
    for_each_scene_triangle(1e-6, 1e3, 56, positive_w);
    for_each_scene_triangle(1e-3, 1e6, 57, positive_w);
}

Test(clip_random, far_over_near_1e9_output_maps_into_the_viewport)
{
    for_each_scene_triangle(1e-6, 1e3, 58, maps_into_viewport);
    for_each_scene_triangle(1e-3, 1e6, 59, maps_into_viewport);
}
