/* Large world coordinates (docs/precision.md, issue 7): a torus and a camera
 * a few units from it, both 1e6 or 1e7 from the world origin, draw the
 * triangle ids and depths they draw at the origin when the mesh's positions
 * are relative to a double origin and the view is composed in double; the
 * same scene in absolute float coordinates does not. Set
 * SOFTRAST_LARGE_WORLD_VERBOSE=1 to print the measured differences. */
#include <stdio.h>

#include "run_helpers.h"
#include "scene_helpers.h"
#include "softrast_private.h"
#include "temp_dir.h"

#define WIDTH 320
#define HEIGHT 240
#define MAX_ID_FRACTION 0.001 /* of the pixels may show another triangle id */
#define MAX_DEPTH_DIFF 1e-6   /* where the ids agree */

/* The eye relative to the torus's centre; it looks at the centre. */
static const float EYE[3] = { 0.9f, 1.7f, -2.4f };

TestSuite(large_world, .init = temp_dir_make, .fini = temp_dir_remove);

typedef struct difference {
    size_t ids;   /* pixels whose triangle id (or background) differs */
    double depth; /* largest depth difference where the ids agree */
} difference;

static void make_torus(sr_mesh *m)
{
    sr_error err = { "" };
    cr_assert(sr_shape_torus(m, 1.0f, 0.4f, 48, 24, &err), "%s", err.message);
}

/* distance along a unit direction, plus digits below a float's spacing there */
static void far_point(double distance, double out[3])
{
    const double dir[3] = { 0.8, 0.36, -0.48 }, jitter[3] = { 0.37, -0.71, 0.13 };
    for (int k = 0; k < 3; k++)
        out[k] = distance * dir[k] + jitter[k];
}

static sr_camera camera_at(const double origin[3], const float eye[3], const float target[3])
{
    sr_camera cam = scene_camera(eye[0], eye[1], eye[2], target[0], target[1], target[2], SR_CAMERA_FOV,
                                 SR_CAMERA_NEAR, SR_CAMERA_FAR);
    for (int k = 0; k < 3; k++)
        cam.origin[k] = origin[k];
    return cam;
}

static void draw(sr_framebuffer *fb, const sr_mesh *mesh, const sr_camera *cam, bool view_in_double)
{
    sr_draw_desc desc = { .mesh = mesh, .shade = SR_SHADE_ID };
    scene_camera_desc(&desc, cam, WIDTH, HEIGHT);
    if (view_in_double)
        sr_camera_view_d(cam, &desc.view_d);
    sr_error err = { "" };
    sr_framebuffer_clear(fb, SCENE_BACKGROUND);
    cr_assert(sr_draw(fb, &desc, NULL, &err), "sr_draw: %s", err.message);
}

/* The reference: the torus at the origin, the camera at EYE. */
static void draw_at_origin(sr_framebuffer *fb, const sr_mesh *mesh)
{
    static const double zero[3];
    const float target[3] = { 0 };
    sr_camera cam = camera_at(zero, EYE, target);
    draw(fb, mesh, &cam, true);
}

/* The camera EYE from `centre`, as the CLI places it: its origin at the eye,
 * looking back at the centre; the view in double. */
static void draw_near(sr_framebuffer *fb, const sr_mesh *mesh, const double centre[3])
{
    double origin[3];
    float eye[3] = { 0 }, target[3];
    for (int k = 0; k < 3; k++) {
        origin[k] = centre[k] + EYE[k];
        target[k] = -EYE[k];
    }
    sr_camera cam = camera_at(origin, eye, target);
    draw(fb, mesh, &cam, true);
}

/* The same scene with no origin anywhere: absolute float positions and eye. */
static void draw_absolute(sr_framebuffer *fb, const sr_mesh *at_origin, const double centre[3])
{
    sr_mesh m;
    make_torus(&m);
    for (uint32_t i = 0; i < m.vertex_count; i++)
        for (int k = 0; k < 3; k++)
            m.positions[i][k] = (float)(centre[k] + at_origin->positions[i][k]);
    sr_mesh_update_bounds(&m);
    static const double zero[3];
    float eye[3], target[3];
    for (int k = 0; k < 3; k++) {
        eye[k] = (float)(centre[k] + EYE[k]);
        target[k] = (float)centre[k];
    }
    sr_camera cam = camera_at(zero, eye, target);
    draw(fb, &m, &cam, false);
    sr_mesh_free(&m);
}

static difference compare(const sr_framebuffer *a, const sr_framebuffer *b)
{
    difference d = { 0, 0.0 };
    for (size_t i = 0; i < scene_pixel_count(a); i++) {
        if (a->color[i] != b->color[i])
            d.ids++;
        else
            d.depth = fmax(d.depth, fabs((double)a->depth[i] - b->depth[i]));
    }
    return d;
}

static bool within_bounds(difference d)
{
    return d.ids <= MAX_ID_FRACTION * WIDTH * HEIGHT && d.depth <= MAX_DEPTH_DIFF;
}

static void report(const char *what, double distance, difference d, const sr_framebuffer *far,
                   const sr_framebuffer *ref)
{
    if (getenv("SOFTRAST_LARGE_WORLD_VERBOSE"))
        fprintf(stderr, "%s at %g: %zu of %d pixels differ in id, max depth difference %.3g; drawn %zu, at the "
                        "origin %zu\n", what, distance, d.ids, WIDTH * HEIGHT, d.depth, scene_count_drawn(far),
                scene_count_drawn(ref));
}

/* Draws the reference and the torus `distance` away (far_mesh with its
 * origin, or in absolute float coordinates) and compares them; leaves
 * pictures when a scene with an origin misses the bound. */
static difference far_against_origin(double distance, const sr_mesh *far_mesh, bool absolute, const char *name)
{
    sr_mesh ref;
    make_torus(&ref);
    sr_framebuffer fb_ref, fb_far;
    scene_fb_make(&fb_ref, WIDTH, HEIGHT);
    scene_fb_make(&fb_far, WIDTH, HEIGHT);
    draw_at_origin(&fb_ref, &ref);
    cr_assert_gt(scene_count_drawn(&fb_ref), (size_t)(WIDTH * HEIGHT / 10), "the torus fills a good part of the view");
    double centre[3];
    far_point(distance, centre);
    if (absolute)
        draw_absolute(&fb_far, &ref, centre);
    else
        draw_near(&fb_far, far_mesh, centre);
    difference d = compare(&fb_far, &fb_ref);
    report(name, distance, d, &fb_far, &fb_ref);
    if (!absolute && !within_bounds(d))
        scene_compare_images(name, fb_far.color, fb_ref.color, WIDTH, HEIGHT, NULL, 0);
    sr_framebuffer_destroy(&fb_ref);
    sr_framebuffer_destroy(&fb_far);
    sr_mesh_free(&ref);
    return d;
}

static void expect_same_as_at_origin(double distance, const char *name)
{
    sr_mesh m;
    make_torus(&m);
    double centre[3];
    far_point(distance, centre);
    sr_error err = { "" };
    cr_assert(sr_mesh_set_origin(&m, centre, &err), "%s", err.message);
    difference d = far_against_origin(distance, &m, false, name);
    cr_expect_leq(d.ids, MAX_ID_FRACTION * WIDTH * HEIGHT, "%zu pixels differ in id at %g", d.ids, distance);
    cr_expect_leq(d.depth, MAX_DEPTH_DIFF, "depth differs by %g at %g", d.depth, distance);
    sr_mesh_free(&m);
}

Test(large_world, a_torus_1e6_away_with_its_origin_draws_as_at_the_origin)
{
    expect_same_as_at_origin(1e6, "large-world-1e6");
}

Test(large_world, a_torus_1e7_away_with_its_origin_draws_as_at_the_origin)
{
    expect_same_as_at_origin(1e7, "large-world-1e7");
}

/* The control: the bound above is one the float pipeline fails. */
Test(large_world, absolute_float_coordinates_1e6_away_miss_the_bound)
{
    difference d = far_against_origin(1e6, NULL, true, "large-world-absolute-1e6");
    cr_expect_not(within_bounds(d), "absolute float coordinates at 1e6 passed: %zu ids, depth %g", d.ids, d.depth);
}

Test(large_world, absolute_float_coordinates_1e7_away_miss_the_bound)
{
    difference d = far_against_origin(1e7, NULL, true, "large-world-absolute-1e7");
    cr_expect_not(within_bounds(d), "absolute float coordinates at 1e7 passed: %zu ids, depth %g", d.ids, d.depth);
}

/* The torus written as an OBJ at `centre` (right-handed: z negated, each
 * face's winding reversed, so it loads as the same triangles in order). */
static const char *write_torus_obj(const double centre[3], const char *name, char *path, size_t size)
{
    sr_mesh m;
    make_torus(&m);
    FILE *f = fopen(temp_path(path, size, name), "w");
    cr_assert_not_null(f);
    for (uint32_t i = 0; i < m.vertex_count; i++)
        fprintf(f, "v %.17g %.17g %.17g\n", centre[0] + m.positions[i][0], centre[1] + m.positions[i][1],
                -(centre[2] + m.positions[i][2]));
    for (uint32_t t = 0; t + 2 < m.index_count; t += 3)
        fprintf(f, "f %u %u %u\n", m.indices[t] + 1, m.indices[t + 2] + 1, m.indices[t + 1] + 1);
    cr_assert_eq(fclose(f), 0);
    sr_mesh_free(&m);
    return path;
}

static void load_torus_at(double distance, sr_mesh *m)
{
    double centre[3];
    char path[256];
    far_point(distance, centre);
    sr_error err = { "" };
    cr_assert(sr_obj_load(m, write_torus_obj(centre, "far.obj", path, sizeof path), &err), "%s", err.message);
}

Test(large_world, an_obj_1e7_away_loads_relative_to_its_centre_and_draws_as_at_the_origin)
{
    sr_mesh m;
    load_torus_at(1e7, &m);
    double centre[3];
    far_point(1e7, centre);
    for (int k = 0; k < 3; k++)
        cr_expect(fabs(m.origin[k] - centre[k]) < 1e-6, "origin[%d] %.17g, centre %.17g", k, m.origin[k],
                  centre[k]);
    cr_expect(m.bounded && m.bounds_hi[0] < 1.5f && m.bounds_lo[0] > -1.5f, "positions are relative to the centre");
    difference d = far_against_origin(1e7, &m, false, "large-world-obj-1e7");
    cr_expect_leq(d.ids, MAX_ID_FRACTION * WIDTH * HEIGHT, "%zu pixels differ in id", d.ids);
    cr_expect_leq(d.depth, MAX_DEPTH_DIFF, "depth differs by %g", d.depth);
    sr_mesh_free(&m);
}

/* `softrast render OBJ --shade id` with the eye EYE from the torus at centre,
 * looking at it; the image in out. */
static void render_ids(const double centre[3], const char *name, sr_texture *out)
{
    char obj[256], png[272], args[1024];
    write_torus_obj(centre, name, obj, sizeof obj);
    snprintf(png, sizeof png, "%s.png", obj);
    snprintf(args, sizeof args,
             "render %s --size %dx%d --shade id --eye %.17g,%.17g,%.17g --target %.17g,%.17g,%.17g --out %s", obj,
             WIDTH, HEIGHT, centre[0] + EYE[0], centre[1] + EYE[1], centre[2] + EYE[2], centre[0], centre[1],
             centre[2], png);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "softrast %s: %s", args, r.err);
    sr_error err = { "" };
    cr_assert(sr_texture_load(out, png, &err), "%s", err.message);
}

Test(large_world, softrast_render_of_an_obj_1e7_away_with_the_eye_beside_it_draws_as_at_the_origin)
{
    static const double zero[3];
    double centre[3];
    far_point(1e7, centre);
    sr_texture near, far;
    render_ids(zero, "near.obj", &near);
    render_ids(centre, "far.obj", &far);
    size_t differ = 0, drawn = 0;
    for (size_t i = 0; i < (size_t)WIDTH * HEIGHT; i++) {
        differ += near.texels[i] != far.texels[i];
        drawn += near.texels[i] != near.texels[0]; /* the corner is background */
    }
    cr_assert_gt(drawn, (size_t)(WIDTH * HEIGHT / 10), "the torus fills a good part of the view");
    cr_expect_leq(differ, MAX_ID_FRACTION * WIDTH * HEIGHT, "%zu pixels differ in id", differ);
    sr_texture_free(&near);
    sr_texture_free(&far);
}

/* The torus spans 2.8, and 16 times that is 44.8 (SR_MESH_RECENTRE_RATIO);
 * its centre's largest coordinate is 0.8 of the distance. */
Test(large_world, an_obj_keeps_absolute_positions_within_sixteen_sizes_of_the_origin)
{
    sr_mesh near, far;
    load_torus_at(40.0, &near);
    load_torus_at(70.0, &far);
    cr_expect(near.origin[0] == 0.0 && near.origin[1] == 0.0 && near.origin[2] == 0.0, "40 away: origin zero");
    cr_expect(far.origin[0] != 0.0 && far.origin[1] != 0.0 && far.origin[2] != 0.0, "70 away: origin set");
    cr_expect(near.bounds_hi[0] > 30.0f && far.bounds_hi[0] < 1.5f);
    sr_mesh_free(&near);
    sr_mesh_free(&far);
}

Test(large_world, a_non_finite_origin_is_refused_in_one_line)
{
    sr_mesh m;
    make_torus(&m);
    sr_error err = { "" };
    cr_assert_not(sr_mesh_set_origin(&m, (double[3]){ 0.0, NAN, 0.0 }, &err));
    cr_expect(strstr(err.message, "mesh origin") && !strchr(err.message, '\n'), "got '%s'", err.message);
    cr_expect(m.origin[1] == 0.0, "the mesh is unchanged");
    m.origin[2] = INFINITY; /* set directly: the draw refuses it too */
    sr_framebuffer fb;
    scene_fb_make(&fb, 8, 8);
    cr_expect_not(sr_draw(&fb, &(sr_draw_desc){ .mesh = &m }, NULL, &err));
    cr_expect(strstr(err.message, "mesh origin"), "got '%s'", err.message);
    sr_camera cam = sr_camera_default();
    cam.origin[0] = NAN;
    cr_expect_not(sr_camera_check(&cam, &err));
    cr_expect(strstr(err.message, "camera origin"), "got '%s'", err.message);
    sr_framebuffer_destroy(&fb);
    sr_mesh_free(&m);
}
