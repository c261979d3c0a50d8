/* The depth model (types.h, docs/precision.md): near and far distances from
 * w under a perspective projection, against GNU MP rationals — the model
 * read off the projections, exact sign tests, the exact path's cut vertices
 * for edges reaching w of 1e30, the adaptive bound, the watertight rule on
 * near and far in every precision, the viewport's z_ndc and the mesh-bounds
 * classification. */
#include <criterion/criterion.h>
#include <float.h>
#include <gmp.h>
#include <math.h>
#include <string.h>

#include "softrast_private.h"
#include "clip_helpers.h"
#include "exact_cut.h"

#define EDGES 3000
#define MODELS 5

static test_rng rng = { 0x2545F4914F6CDD1Dull };

static double uniform(void)
{
    return rng_unit(&rng);
}

/* 10^e, e uniform in [lo, hi]. */
static double decade(double lo, double hi)
{
    return pow(10.0, lo + (hi - lo) * uniform());
}

static sr_camera camera(float far, bool reversed)
{
    sr_camera cam = sr_camera_default();
    cam.near = 0.1f;
    cam.far = far;
    cam.reversed_z = reversed;
    return cam;
}

/* Standard far 100 and 1e4, standard far inf, reversed far 100, reversed inf. */
static sr_camera model_camera(int k)
{
    static const float fars[MODELS] = { 100.0f, 1e4f, INFINITY, 100.0f, INFINITY };
    return camera(fars[k], k >= 3);
}

static sr_clip_depth model(int k)
{
    mat4 p;
    sr_camera cam = model_camera(k);
    sr_camera_projection(&cam, 16.0f / 9.0f, p);
    sr_clip_depth d = sr_clip_depth_of(p);
    cr_assert(d.on, "model %d is off for a perspective camera", k);
    return d;
}

/* The exact distance of a point at clip w to near or far under the model. */
static void exact_depth_distance(sr_clip_plane plane, const sr_clip_depth *m, double w, mpq_t d)
{
    mpq_t c[4];
    for (int i = 0; i < 4; i++)
        mpq_init(c[i]);
    mpq_set_d(c[SR_W], w);
    exact_distance(plane, c, m, d);
    for (int i = 0; i < 4; i++)
        mpq_clear(c[i]);
}

static int exact_sign(sr_clip_plane plane, const sr_clip_depth *m, double w)
{
    mpq_t d;
    mpq_init(d);
    exact_depth_distance(plane, m, w, d);
    int s = mpq_sgn(d);
    mpq_clear(d);
    return s;
}

/* The w where the plane lies, in double: near a·w + b = 0, far (1 − a)·w = b. */
static double plane_w(sr_clip_plane plane, const sr_clip_depth *m)
{
    return plane == SR_PLANE_NEAR ? -(double)m->b / m->a : (double)m->b / (1.0 - m->a);
}

Test(clip_depth, perspective_projections_have_a_model_that_puts_near_and_far_where_the_camera_says)
{
    for (int k = 0; k < MODELS; k++) {
        sr_clip_depth m = model(k);
        sr_camera cam = model_camera(k);
        /* Reversed z swaps which of z = 0 and z = w is the near plane. */
        sr_clip_plane at_near = cam.reversed_z ? SR_PLANE_FAR : SR_PLANE_NEAR;
        sr_clip_plane at_far = cam.reversed_z ? SR_PLANE_NEAR : SR_PLANE_FAR;
        cr_assert_float_eq(plane_w(at_near, &m), cam.near, 1e-6 * cam.near, "model %d: near at %g", k,
                           plane_w(at_near, &m));
        if (isinf(cam.far))
            cr_assert(cam.reversed_z ? m.a == 0.0f && m.b == cam.near : m.a == 1.0f && m.b == -cam.near,
                      "model %d: a %a, b %a", k, m.a, m.b);
        else /* a = f/(f − n) rounded to float moves far by up to ε·f/n relative */
            cr_assert_float_eq(plane_w(at_far, &m), cam.far, 2.0 * FLT_EPSILON * cam.far / cam.near * cam.far,
                               "model %d: far at %g", k, plane_w(at_far, &m));
    }
    mat4 p, zero = { { 0 } };
    sr_camera ortho = camera(100.0f, false);
    ortho.ortho_height = 4.0f;
    sr_camera_projection(&ortho, 1.0f, p);
    cr_assert_not(sr_clip_depth_of(p).on, "orthographic");
    cr_assert_not(sr_clip_depth_of(GLM_MAT4_IDENTITY).on, "identity");
    cr_assert_not(sr_clip_depth_of(zero).on, "zero");
    /* w = −z_view (a right-handed projection: column 2 negated): a = A/s
     * with s = −1 is the same a. */
    sr_camera lh = camera(100.0f, false);
    sr_camera_projection(&lh, 1.0f, p);
    sr_clip_depth want = sr_clip_depth_of(p);
    glm_vec4_negate(p[2]);
    sr_clip_depth rh = sr_clip_depth_of(p);
    cr_assert(rh.on && rh.a == want.a && rh.b == want.b, "right-handed: a %a, b %a", rh.a, rh.b);
}

/* Edge e's plane: near and far in turn, but never the one an infinite far
 * puts at infinity (nothing crosses it). */
static sr_clip_plane edge_plane(int e, const sr_clip_depth *m)
{
    sr_clip_plane plane = (e / MODELS) % 2 ? SR_PLANE_FAR : SR_PLANE_NEAR;
    if (isfinite(plane_w(plane, m)))
        return plane;
    return plane == SR_PLANE_FAR ? SR_PLANE_NEAR : SR_PLANE_FAR;
}

/* A float w within a few ulps of the plane, or anywhere from 1e-3 to 1e30,
 * of either sign. */
static float random_w(sr_clip_plane plane, const sr_clip_depth *m)
{
    double at = plane_w(plane, m);
    if (uniform() < 0.5 && isfinite(at) && at != 0.0) {
        float w = (float)at;
        for (int steps = (int)(8.0 * uniform()) - 4; steps != 0; steps += steps < 0 ? 1 : -1)
            w = nextafterf(w, steps < 0 ? -INFINITY : INFINITY);
        return w;
    }
    return (float)((uniform() < 0.2 ? -1.0 : 1.0) * decade(-3, 30));
}

Test(clip_depth, outcodes_and_distances_under_the_model_are_exact)
{
    int near_zero = 0;
    for (int e = 0; e < 20 * EDGES; e++) {
        sr_clip_depth m = model(e % MODELS);
        sr_clip_plane plane = edge_plane(e, &m);
        float w = random_w(plane, &m);
        /* z is garbage on purpose: the model never reads it. */
        float c[4] = { 0.0f, 0.0f, (float)(uniform() - 0.5) * 1e3f, w };
        int want = exact_sign(plane, &m, w);
        double d = sr_clip_distance_with(plane, c, &m);
        cr_assert_eq((d > 0.0) - (d < 0.0), want, "model %d plane %d w %a: distance %a", e % MODELS, plane, w, d);
        unsigned bit = (sr_clip_outcode_with(c, &m) >> plane) & 1u;
        cr_assert_eq(bit, (unsigned)(want < 0), "model %d plane %d w %a", e % MODELS, plane, w);
        mpq_t q;
        mpq_init(q);
        exact_depth_distance(plane, &m, w, q);
        double ref = mpq_get_d(q);
        mpq_clear(q);
        cr_assert(fabs(d - ref) <= 2.0 * DBL_EPSILON * fabs(ref), "w %a: distance %a, exact %a", w, d, ref);
        near_zero += fabs(ref) < 1e-6 && want != 0;
    }
    cr_assert_gt(near_zero, 100, "too few points next to a plane: the test is too tame");
}

#if defined(__SSE2__)
/* A coordinate for a point at w: on a plane (±w) or next to it, anywhere
 * between, well outside, or now and then NaN or an inf. */
static float random_coordinate(float w)
{
    double u = uniform();
    if (u < 0.02)
        return u < 0.01 ? NAN : (u < 0.015 ? INFINITY : -INFINITY);
    float on = uniform() < 0.5 ? w : -w;
    if (u < 0.4)
        return on;
    if (u < 0.6)
        return nextafterf(on, uniform() < 0.5 ? -INFINITY : INFINITY);
    return (float)((2.0 * uniform() - 1.0) * 1.5 * (double)fabsf(w));
}

/* Models from the cameras, two made by hand whose far plane lies at a
 * float w (2 and 1.5: there the double far distance is 0, too close to
 * call, and the expansion decides), and none. */
#define FOUR_LANE_MODELS (MODELS + 3)

static const sr_clip_depth *four_lane_model(int k, sr_clip_depth *m)
{
    if (k < MODELS)
        *m = model(k);
    else if (k == MODELS)
        *m = (sr_clip_depth){ .on = true, .a = 0.5f, .b = 1.0f };
    else if (k == MODELS + 1)
        *m = (sr_clip_depth){ .on = true, .a = -1.0f, .b = 3.0f };
    else
        return NULL;
    return m;
}

/* The four-lane outcode against the one-position outcode under every model
 * and without one, on points near every plane: w within a few ulps of near
 * or far half the time, x, y and z on or next to ±w, now and then NaN or
 * an inf in one coordinate. */
Test(clip_depth, four_lanes_give_each_position_its_one_position_outcode)
{
    int on_far = 0, nonfinite = 0;
    for (int e = 0; e < 10 * EDGES; e++) {
        sr_clip_depth storage, near_far = model(0);
        const sr_clip_depth *m = four_lane_model(e % FOUR_LANE_MODELS, &storage);
        const sr_clip_depth *placed = m ? m : &near_far; /* where w is put near a plane */
        float lanes[4][4]; /* lanes[coordinate][position] */
        for (int j = 0; j < 4; j++) {
            float w = random_w(edge_plane(e / FOUR_LANE_MODELS + j, placed), placed);
            for (int c = 0; c < 3; c++)
                lanes[c][j] = random_coordinate(w);
            lanes[SR_W][j] = uniform() < 0.01 ? NAN : w;
        }
        __m128 c[4];
        for (int r = 0; r < 4; r++)
            c[r] = _mm_loadu_ps(lanes[r]);
        uint32_t four = sr_clip_outcodes_four(c, m);
        for (int j = 0; j < 4; j++) {
            float position[4] = { lanes[0][j], lanes[1][j], lanes[2][j], lanes[3][j] };
            unsigned want = sr_clip_outcode_with(position, m);
            cr_assert_eq(four >> 8 * j & 0xFFu, want, "model %d lane %d (%a, %a, %a, %a)", e % FOUR_LANE_MODELS, j,
                         position[0], position[1], position[2], position[3]);
            on_far += m && want != SR_OUT_NONFINITE && sr_clip_distance_with(SR_PLANE_FAR, position, m) == 0.0;
            nonfinite += want == SR_OUT_NONFINITE;
        }
    }
    cr_assert_gt(on_far, 100, "too few points on the far plane: the test is too tame");
    cr_assert_gt(nonfinite, 100, "too few non-finite positions: the test is too tame");
}
#endif

/* An edge from inside the plane to outside it, the outside end as far as
 * w = 1e30 (or behind the eye for near): the ground's edges. */
static void random_edge(sr_clip_plane plane, const sr_clip_depth *m, sr_vertex_out *in, sr_vertex_out *out)
{
    memset(in, 0, sizeof *in);
    memset(out, 0, sizeof *out);
    do {
        in->v[SR_W] = (float)decade(-1, 2);
        out->v[SR_W] = (float)((uniform() < 0.5 ? -1.0 : 1.0) * decade(-1, 30));
        for (int i = 0; i < 2; i++) {
            in->v[i] = (float)((2.0 * uniform() - 1.0) * in->v[SR_W]);
            out->v[i] = (float)((2.0 * uniform() - 1.0) * fabsf(out->v[SR_W]));
        }
        in->v[SR_Z] = (float)((double)m->a * in->v[SR_W] + m->b);
        out->v[SR_Z] = (float)((double)m->a * out->v[SR_W] + m->b);
    } while (!(exact_sign(plane, m, in->v[SR_W]) >= 0 && exact_sign(plane, m, out->v[SR_W]) < 0));
}

/* Coordinate i of the exact cut a + t(b − a), t from the model's distances. */
static double exact_cut(sr_clip_plane plane, const sr_clip_depth *m, const sr_vertex_out *a,
                        const sr_vertex_out *b, int i)
{
    mpq_t da, db;
    mpq_inits(da, db, NULL);
    exact_depth_distance(plane, m, a->v[SR_W], da);
    exact_depth_distance(plane, m, b->v[SR_W], db);
    double r = exact_cut_coordinate(da, db, a->v[i], b->v[i]);
    mpq_clears(da, db, NULL);
    return r;
}

static bool within_one_float_ulp(float got, double exact)
{
    float want = (float)exact;
    return got == want || got == nextafterf(want, INFINITY) || got == nextafterf(want, -INFINITY);
}

Test(clip_depth, exact_cuts_on_near_and_far_are_the_rational_cut_rounded_to_float)
{
    for (int e = 0; e < EDGES; e++) {
        sr_clip_depth m = model(e % MODELS);
        sr_clip_plane plane = edge_plane(e, &m);
        sr_vertex_out in, out, cut;
        random_edge(plane, &m, &in, &out);
        sr_clip_config cfg = { .precision = SR_CLIP_EXACT, .depth = m };
        sr_clip_intersect(plane, &in, &out, 4, &cfg, &cut);
        for (int i = 0; i < 4; i++)
            if (i != SR_Z)
                cr_assert(within_one_float_ulp(cut.v[i], exact_cut(plane, &m, &in, &out, i)),
                          "edge %d plane %d coord %d: got %a, exact %a", e, plane, i, cut.v[i],
                          exact_cut(plane, &m, &in, &out, i));
        float z = (float)((double)m.a * cut.v[SR_W] + m.b);
        cr_assert_eq(cut.v[SR_Z], z, "edge %d: the cut's z is not a·w + b of its w", e);
    }
}

/* Adaptive keeps x/w, y/w and w/w_exact within its tolerance on the same
 * edges, whichever precision it takes. */
Test(clip_depth, adaptive_cuts_on_near_and_far_stay_within_tolerance)
{
    const double tolerance = 1.0 / (256.0 * 1280.0);
    sr_clip_counts counts = { { 0 } };
    for (int e = 0; e < EDGES; e++) {
        sr_clip_depth m = model(e % MODELS);
        sr_clip_plane plane = edge_plane(e, &m);
        sr_vertex_out in, out, cut;
        random_edge(plane, &m, &in, &out);
        sr_clip_config cfg = { .ndc_tolerance = tolerance, .counts = &counts, .depth = m };
        sr_clip_intersect(plane, &in, &out, 4, &cfg, &cut);
        double w = exact_cut(plane, &m, &in, &out, SR_W);
        for (int i = 0; i < 2; i++) {
            double exact = exact_cut(plane, &m, &in, &out, i);
            double err = fabs(cut.v[i] / (double)cut.v[SR_W] - exact / w);
            cr_assert(err <= tolerance + 4.0 * FLT_EPSILON * (1.0 + fabs(exact / w)), "edge %d coord %d: NDC error %g",
                      e, i, err);
        }
        cr_assert(fabs(cut.v[SR_W] - w) <= tolerance * w + FLT_EPSILON * w, "edge %d: w %a, exact %a", e,
                  cut.v[SR_W], w);
    }
    cr_assert_gt(counts.cuts[SR_CLIP_EXACT] + counts.cuts[SR_CLIP_DOUBLE], 0);
}

/* Both walks of an edge hold the same cut vertex, in every precision. */
Test(clip_depth, near_and_far_cuts_are_bit_identical_both_ways_in_every_precision)
{
    int checked = 0;
    for (int e = 0; e < EDGES / 3; e++) {
        sr_clip_depth m = model(e % MODELS);
        sr_clip_plane plane = edge_plane(e, &m);
        sr_vertex_out in, out, third = { .v = { 0.0f, 0.0f, 0.0f, 1.0f } };
        random_edge(plane, &m, &in, &out);
        third.v[SR_Z] = (float)((double)m.a + m.b);
        for (int p = SR_CLIP_ADAPTIVE; p < SR_CLIP_PRECISIONS; p++) {
            sr_clip_config cfg = { .precision = (sr_clip_precision)p, .depth = m };
            bool standing;
            cr_assert(clip_same_cut_both_ways(plane, &in, &out, &third, &third, &cfg, &standing),
                      "edge %d, precision %d: the cut vertex differs between the two walks", e, p);
            checked += standing;
        }
    }
    cr_assert_gt(checked, EDGES / 3, "too few edges left both polygons standing");
}

Test(clip_depth, viewport_takes_z_ndc_from_w_under_the_model)
{
    sr_clip_depth m = model(0);
    sr_viewport vp = { .width = 64, .height = 48, .subpixel_bits = SR_SUBPIXEL_BITS, .guard = 1.0f, .depth = m };
    const float ws[] = { 0.1f, 1.0f, 50.0f, 100.0f };
    for (size_t k = 0; k < sizeof ws / sizeof ws[0]; k++) {
        /* z far from a·w + b: the viewport must not read it. */
        sr_vertex_out v = { .v = { 0.0f, 0.0f, 0.5f * ws[k], ws[k] } };
        sr_screen_vertex s;
        cr_assert(sr_viewport_map(&v, 0, &vp, &s));
        cr_assert_eq(s.z, (float)(m.a + m.b / (double)ws[k]), "w %g: z_ndc %a", ws[k], s.z);
    }
}

/* The mesh-bounds shortcut stays conservative under the model: it never
 * calls a box inside or outside that the model's outcodes disagree with. */
Test(clip_depth, box_classification_agrees_with_the_model_outcodes)
{
    sr_clip_depth m = model(0);
    mat4 p;
    sr_camera cam = model_camera(0);
    sr_camera_projection(&cam, 1.0f, p);
    static const float boxes[][2][3] = {
        { { -1e7f, 0.0f, -1e7f }, { 1e7f, 0.0f, 1e7f } },   /* the ground: crosses */
        { { -0.5f, -0.5f, 2.0f }, { 0.5f, 0.5f, 3.0f } },   /* inside */
        { { -0.5f, -0.5f, 200.0f }, { 0.5f, 0.5f, 300.0f } }, /* beyond far */
        { { -0.5f, -0.5f, 1e7f }, { 0.5f, 0.5f, 1.1e7f } }, /* far beyond far */
    };
    static const sr_clip_box want[] = { SR_BOX_CROSSES, SR_BOX_INSIDE, SR_BOX_OUTSIDE, SR_BOX_OUTSIDE };
    for (size_t k = 0; k < sizeof want / sizeof want[0]; k++) {
        sr_clip_box got = sr_clip_classify_box(p, boxes[k][0], boxes[k][1]);
        cr_assert_eq(got, want[k], "box %zu", k);
        unsigned all = SR_OUT_PLANES, any = 0;
        for (int c = 0; c < 8; c++) {
            vec4 o = { boxes[k][c & 1][0], boxes[k][(c >> 1) & 1][1], boxes[k][(c >> 2) & 1][2], 1.0f }, clip;
            glm_mat4_mulv(p, o, clip);
            unsigned code = sr_clip_outcode_with(clip, &m);
            all &= code;
            any |= code;
        }
        cr_assert(got != SR_BOX_INSIDE || any == 0, "box %zu inside, a corner's outcode %#x", k, any);
        cr_assert(got != SR_BOX_OUTSIDE || all != 0, "box %zu outside, but no plane has every corner", k);
    }
}
