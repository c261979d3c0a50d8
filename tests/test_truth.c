/* The truth renderer (src/studies/truth.h): closed forms on small scenes,
 * its exact predicates against GNU MP rationals, and brute force over every
 * triangle on random scenes. */
#include <gmp.h>

#include "scene_helpers.h"
#include "studies/truth.h"
#include "studies/truth_exact.h"

#define NEAR 1.0f
#define FAR 10.0f
#define RANDOM_TRIANGLES 60
#define RANDOM_SCENES 6
#define BRUTE_SIDE 48
#define CLEAR_MARGIN 1e-9 /* the brute force's double results count only this far from a decision */

/* View = world = identity (left all zero, which the truth must read as
 * sr_draw does) and a perspective projection with x_ndc = x/z, y_ndc = y/z:
 * pixel centres of a power-of-two image lie on exact view rays. */
static void unit_lens_desc(sr_draw_desc *desc, const sr_mesh *mesh, sr_cull cull)
{
    *desc = (sr_draw_desc){ .mesh = mesh, .shade = SR_SHADE_ID, .cull = cull };
    glm_perspective_lh_zo(glm_rad(90.0f), 1.0f, NEAR, FAR, desc->projection);
    desc->projection[0][0] = desc->projection[1][1] = 1.0f;
}

static void truth_of(const sr_draw_desc *desc, int side, sr_truth_image *t)
{
    sr_error err = { "" };
    cr_assert(sr_truth_render(desc, side, side, t, &err), "sr_truth_render: %s", err.message);
}

static void mesh_of(sr_mesh *mesh, const float (*pos)[3], uint32_t vertices, const uint32_t *idx, uint32_t triangles)
{
    scene_mesh_make(mesh, &(scene_mesh_arrays){ .vertex_count = vertices, .positions = pos,
                                                .index_count = 3 * triangles, .indices = idx });
}

/* The truth of one triangle at 64x64 under the unit lens. */
static void one_triangle_truth(const float pos[3][3], sr_cull cull, sr_mesh *mesh, sr_draw_desc *desc,
                               sr_truth_image *t)
{
    scene_triangle_make(mesh, pos);
    unit_lens_desc(desc, mesh, cull);
    truth_of(desc, 64, t);
}

/* The pixel centre's view ray direction under unit_lens_desc: (X, Y, 1). */
static void centre_ndc(int side, int x, int y, double *nx, double *ny)
{
    *nx = (2.0 * x + 1.0 - side) / side;
    *ny = (side - 2.0 * y - 1.0) / side;
}

Test(truth, a_facing_triangle_has_its_closed_form_ids_and_depth_and_softrast_agrees)
{
    /* Clockwise on screen (a front face), in the plane z = 2. */
    const float pos[3][3] = { { -1.5f, -1.5f, 2.0f }, { 0.25f, 1.5f, 2.0f }, { 1.5f, -1.0f, 2.0f } };
    sr_mesh mesh;
    sr_draw_desc desc;
    sr_truth_image t;
    one_triangle_truth(pos, SR_CULL_BACK, &mesh, &desc, &t);
    double z_ndc = (double)desc.projection[2][2] + (double)desc.projection[3][2] / 2.0;
    size_t covered = 0;
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++) {
            double nx, ny, e[3];
            centre_ndc(64, x, y, &nx, &ny);
            double px = 2.0 * nx, py = 2.0 * ny; /* the ray meets z = 2 there */
            for (int k = 0; k < 3; k++) {
                const float *a = pos[(k + 1) % 3], *b = pos[(k + 2) % 3];
                e[k] = (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0]);
            }
            bool inside = e[0] < 0 && e[1] < 0 && e[2] < 0;
            size_t i = (size_t)y * 64 + x;
            cr_assert_eq(t.ids[i], inside ? 1u : 0u, "pixel (%d, %d)", x, y);
            covered += inside;
            if (inside)
                cr_assert_eq(sr_truth_z_ndc(desc.projection, t.distance[i]), z_ndc, "pixel (%d, %d)", x, y);
        }
    cr_assert_gt(covered, 500);

    sr_framebuffer fb;
    scene_fb_make(&fb, 64, 64);
    sr_error err = { "" };
    cr_assert(sr_draw(&fb, &desc, NULL, &err), "%s", err.message);
    cr_assert_eq(scene_compare_images("truth_facing", fb.color, t.ids, 64, 64, NULL, 0), 0);
    sr_framebuffer_destroy(&fb);

    desc.cull = SR_CULL_FRONT;
    sr_truth_image_free(&t);
    truth_of(&desc, 64, &t);
    for (size_t i = 0; i < 64 * 64; i++)
        cr_assert_eq(t.ids[i], 0u, "a front face culled as front still covers pixel %zu", i);
    sr_truth_image_free(&t);
    sr_mesh_free(&mesh);
}

Test(truth, pixel_centres_on_a_shared_edge_go_by_the_top_left_rule)
{
    /* At 8x8 under the unit lens, column 4's centres lie on x = z/8 and row
     * 4's on y = -z/8. A vertical edge there is the left edge of the
     * triangle to its right; a horizontal one the top edge of the one below. */
    const float pos[][3] = {
        { -0.75f, -0.75f, 1.0f }, { 0.125f, 0.75f, 1.0f }, { 0.125f, -0.75f, 1.0f }, { 0.75f, 0.0f, 1.0f },
        { -1.5f, -0.25f, 2.0f }, { 0.0f, 1.5f, 2.0f }, { 1.5f, -0.25f, 2.0f }, { 0.0f, -1.5f, 2.0f },
    };
    const uint32_t vertical[] = { 0, 1, 2, 2, 1, 3 }, horizontal[] = { 4, 5, 6, 4, 6, 7 };
    const uint32_t *lists[2] = { vertical, horizontal };
    for (int which = 0; which < 2; which++) {
        sr_mesh mesh;
        sr_draw_desc desc;
        sr_truth_image t;
        mesh_of(&mesh, pos, 8, lists[which], 2);
        unit_lens_desc(&desc, &mesh, SR_CULL_NONE);
        truth_of(&desc, 8, &t);
        for (int k = 1; k < 7; k++) {
            size_t on_edge = which == 0 ? (size_t)k * 8 + 4 : 4 * 8 + (size_t)k;
            cr_assert_eq(t.ids[on_edge], 2u, "%s edge, pixel %zu: the %s triangle takes it",
                         which == 0 ? "vertical" : "horizontal", on_edge, which == 0 ? "right" : "lower");
        }
        /* The vertices sit on softrast's subpixel grid, so it draws the same ids. */
        sr_framebuffer fb;
        scene_fb_make(&fb, 8, 8);
        sr_error err = { "" };
        cr_assert(sr_draw(&fb, &desc, NULL, &err), "%s", err.message);
        cr_assert_eq(scene_compare_images(which == 0 ? "truth_vertical" : "truth_horizontal", fb.color, t.ids, 8, 8, NULL, 0),
                     0);
        sr_framebuffer_destroy(&fb);
        sr_truth_image_free(&t);
        sr_mesh_free(&mesh);
    }
}

Test(truth, a_triangle_crossing_the_near_plane_shows_its_part_beyond_it)
{
    /* A floor at y = -0.5 from z = -1 (behind the eye) to z = 30 (past far):
     * the ray through (X, Y), Y < 0, meets it at z = -0.5 / Y. */
    const float pos[3][3] = { { -40.0f, -0.5f, -1.0f }, { 0.0f, -0.5f, 30.0f }, { 40.0f, -0.5f, -1.0f } };
    sr_mesh mesh;
    sr_draw_desc desc;
    sr_truth_image t;
    one_triangle_truth(pos, SR_CULL_NONE, &mesh, &desc, &t);
    double a = desc.projection[2][2], b = desc.projection[3][2];
    size_t near_cut = 0, drawn = 0;
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++) {
            double nx, ny;
            centre_ndc(64, x, y, &nx, &ny);
            size_t i = (size_t)y * 64 + x;
            if (ny >= 0.0) {
                cr_assert_eq(t.ids[i], 0u, "pixel (%d, %d) above the horizon", x, y);
                continue;
            }
            double z = -0.5 / ny, depth = a + b / z;
            /* Inside the triangle's sides: |x| <= 40·(30 - z)/31 at x = X·z. */
            bool sides = fabs(nx * z) < 40.0 * (30.0 - z) / 31.0;
            bool expected = sides && depth >= 0.0 && depth <= 1.0;
            near_cut += sides && depth < 0.0;
            drawn += expected;
            cr_assert_eq(t.ids[i], expected ? 1u : 0u, "pixel (%d, %d), z %g", x, y, z);
            if (expected)
                cr_assert_float_eq(sr_truth_z_ndc(desc.projection, t.distance[i]), depth, 1e-14);
        }
    cr_assert_gt(near_cut, 0, "some rows meet the floor before the near plane");
    cr_assert_gt(drawn, 0);
    sr_truth_image_free(&t);
    sr_mesh_free(&mesh);
}

/* ---- the exact predicates against GNU MP ---- */

static void mpq_triple(mpq_t out, const double x[3], const double b[3], const double c[3])
{
    mpq_t xs[3], bs[3], cs[3], term;
    mpq_init(term);
    for (int i = 0; i < 3; i++) {
        mpq_inits(xs[i], bs[i], cs[i], NULL);
        mpq_set_d(xs[i], x[i]);
        mpq_set_d(bs[i], b[i]);
        mpq_set_d(cs[i], c[i]);
    }
    mpq_set_ui(out, 0, 1);
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3, k = (i + 2) % 3;
        mpq_mul(term, bs[j], cs[k]);
        mpq_mul(term, term, xs[i]);
        mpq_add(out, out, term);
        mpq_mul(term, bs[k], cs[j]);
        mpq_mul(term, term, xs[i]);
        mpq_sub(out, out, term);
    }
    for (int i = 0; i < 3; i++)
        mpq_clears(xs[i], bs[i], cs[i], NULL);
    mpq_clear(term);
}

Test(truth, exact_orientation_and_side_match_gnu_mp_on_nearly_degenerate_input)
{
    test_rng rng = { 12 };
    mpq_t exact;
    mpq_init(exact);
    int zeros = 0;
    for (int n = 0; n < 4000; n++) {
        double a[3], b[3], c[3];
        for (int k = 0; k < 3; k++) {
            a[k] = rng_uniform(&rng, -10.0, 10.0);
            b[k] = rng_uniform(&rng, -10.0, 10.0);
        }
        /* c on the plane through the origin, a and b, nudged by a few ulps or not at all. */
        double s = rng_uniform(&rng, -2.0, 2.0), u = rng_uniform(&rng, -2.0, 2.0);
        int nudge = (int)(rng_next(&rng) % 5) - 2;
        for (int k = 0; k < 3; k++)
            c[k] = n % 4 == 0 ? ldexp(a[k], 3) : s * a[k] + u * b[k];
        c[n % 3] = nextafter(c[n % 3], nudge > 0 ? INFINITY : -INFINITY);
        if (nudge == 0)
            c[n % 3] = n % 4 == 0 ? ldexp(a[n % 3], 3) : c[n % 3];
        mpq_triple(exact, a, b, c);
        cr_assert_eq(sr_truth_orient_exact(a, b, c), mpq_sgn(exact), "case %d", n);
        sr_truth_ray ray = { { { 0.0, c[0] }, { 0.0, c[1] }, { 0.0, c[2] } } };
        mpq_triple(exact, c, a, b);
        cr_assert_eq(sr_truth_side_exact(&ray, a, b), mpq_sgn(exact), "case %d", n);
        zeros += mpq_sgn(exact) == 0;
    }
    cr_assert_gt(zeros, 100, "exact zeros were tested");
    mpq_clear(exact);
}

/* ---- brute force ---- */

/* Ray (X, Y, 1) against triangle v in double: the hit's z, or NAN when the
 * ray clearly misses; *clear is false when it is too close to call. */
static double brute_hit(const float (*v)[3], double nx, double ny, bool *clear)
{
    double d[3] = { nx, ny, 1.0 }, e[3], det = 0.0, sum = 0.0;
    for (int k = 0; k < 3; k++) {
        const float *a = v[(k + 1) % 3], *b = v[(k + 2) % 3];
        e[k] = d[0] * ((double)a[1] * b[2] - (double)a[2] * b[1]) + d[1] * ((double)a[2] * b[0] - (double)a[0] * b[2]) +
               d[2] * ((double)a[0] * b[1] - (double)a[1] * b[0]);
        sum += e[k];
    }
    for (int k = 0; k < 3; k++)
        det += v[0][k] * (double)((k == 0 ? v[1][1] * (double)v[2][2] - v[1][2] * (double)v[2][1]
                                   : k == 1 ? v[1][2] * (double)v[2][0] - v[1][0] * (double)v[2][2]
                                            : v[1][0] * (double)v[2][1] - v[1][1] * (double)v[2][0]));
    bool inside = true;
    for (int k = 0; k < 3; k++) {
        double side = (det > 0 ? e[k] : -e[k]) / fabs(sum);
        *clear = *clear && fabs(side) > CLEAR_MARGIN;
        inside = inside && side > 0.0;
    }
    return inside ? det / sum : NAN;
}

static void random_scene(test_rng *rng, float (*pos)[3], uint32_t *idx)
{
    for (int t = 0; t < RANDOM_TRIANGLES; t++) {
        double cx = rng_uniform(rng, -3.0, 3.0), cy = rng_uniform(rng, -3.0, 3.0), cz = rng_uniform(rng, 0.0, 12.0);
        for (int k = 0; k < 3; k++) {
            pos[3 * t + k][0] = (float)(cx + rng_uniform(rng, -1.5, 1.5));
            pos[3 * t + k][1] = (float)(cy + rng_uniform(rng, -1.5, 1.5));
            pos[3 * t + k][2] = (float)(cz + rng_uniform(rng, -1.5, 1.5));
            idx[3 * t + k] = (uint32_t)(3 * t + k);
        }
    }
}

Test(truth, agrees_with_brute_force_over_every_triangle_where_the_margin_is_clear)
{
    test_rng rng = { 1212 };
    static float pos[3 * RANDOM_TRIANGLES][3];
    static uint32_t idx[3 * RANDOM_TRIANGLES];
    size_t checked = 0, total = 0;
    for (int scene = 0; scene < RANDOM_SCENES; scene++) {
        sr_mesh mesh;
        sr_draw_desc desc;
        sr_truth_image t;
        random_scene(&rng, pos, idx);
        mesh_of(&mesh, pos, 3 * RANDOM_TRIANGLES, idx, RANDOM_TRIANGLES);
        unit_lens_desc(&desc, &mesh, scene % 2 ? SR_CULL_BACK : SR_CULL_NONE);
        truth_of(&desc, BRUTE_SIDE, &t);
        double a = desc.projection[2][2], b = desc.projection[3][2];
        for (int y = 0; y < BRUTE_SIDE; y++)
            for (int x = 0; x < BRUTE_SIDE; x++) {
                double nx, ny, best = INFINITY, second = INFINITY;
                uint32_t best_id = 0;
                bool clear = true;
                centre_ndc(BRUTE_SIDE, x, y, &nx, &ny);
                for (int k = 0; k < RANDOM_TRIANGLES; k++) {
                    const float(*v)[3] = &pos[3 * k];
                    double z = brute_hit(v, nx, ny, &clear);
                    double det = v[0][0] * ((double)v[1][1] * v[2][2] - (double)v[1][2] * v[2][1]) -
                                 v[0][1] * ((double)v[1][0] * v[2][2] - (double)v[1][2] * v[2][0]) +
                                 v[0][2] * ((double)v[1][0] * v[2][1] - (double)v[1][1] * v[2][0]);
                    if (isnan(z) || z <= 0.0 || (desc.cull == SR_CULL_BACK && det > 0.0))
                        continue;
                    double depth = a + b / z;
                    clear = clear && fabs(depth) > CLEAR_MARGIN && fabs(depth - 1.0) > CLEAR_MARGIN;
                    if (depth < 0.0 || depth > 1.0)
                        continue;
                    if (z < best) {
                        second = best, best = z, best_id = (uint32_t)k + 1;
                    } else {
                        second = fmin(second, z);
                    }
                }
                clear = clear && (isinf(second) || second - best > CLEAR_MARGIN * best);
                size_t i = (size_t)y * BRUTE_SIDE + x;
                total++;
                if (!clear)
                    continue;
                checked++;
                cr_assert_eq(t.ids[i], best_id, "scene %d, pixel (%d, %d)", scene, x, y);
                if (best_id)
                    cr_assert_float_eq(t.distance[i], best, 1e-12 * best, "scene %d, pixel (%d, %d)", scene, x, y);
            }
        sr_truth_image_free(&t);
        sr_mesh_free(&mesh);
    }
    cr_assert_gt(checked, total * 9 / 10, "%zu of %zu pixels had a clear margin", checked, total);
}
