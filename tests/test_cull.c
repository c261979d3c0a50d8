/* Stage 7 as the user sees it: which windings --cull and --front keep, zero
 * area dropped, facing decided after clipping on every fan triangle, and the
 * conventions end to end (a clockwise world triangle is a front face).
 */
#include <string.h>

#include <criterion/criterion.h>

#include "scene_helpers.h"

#define FLAT 32 /* pixel-space scenes (a power of two) */
#define VIEW_W 64
#define VIEW_H 48
#define FLAT_Z 0.5f

/* Clockwise on screen (y down): top-left, top-right, bottom-left. */
static const float cw[3][2] = { { 4, 4 }, { 28, 5 }, { 5, 27 } };
static const float ccw[3][2] = { { 4, 4 }, { 5, 27 }, { 28, 5 } };

/* Whether the triangle is drawn (and counted culled if not) under a mode. */
static bool drawn_with(const float xy[3][2], sr_cull cull, sr_front front)
{
    sr_framebuffer fb;
    sr_mesh mesh;
    scene_fb_make(&fb, FLAT, FLAT);
    scene_pixel_triangle(&mesh, xy, FLAT_Z);
    sr_stats stats = scene_draw_pixel_space(&fb, &mesh, SR_SHADE_ID, cull, front);
    size_t pixels = scene_count_drawn(&fb);
    cr_expect_eq(stats.triangles, 1);
    cr_expect_eq(stats.fragments, pixels);
    cr_expect_eq(stats.culled, pixels ? 0u : 1u, "drawn %zu pixels and culled %llu", pixels,
                 (unsigned long long)stats.culled);
    sr_mesh_free(&mesh);
    sr_framebuffer_destroy(&fb);
    return pixels > 0;
}

Test(cull, back_keeps_clockwise_and_drops_counterclockwise)
{
    cr_expect(drawn_with(cw, SR_CULL_BACK, SR_FRONT_CW), "clockwise front face dropped");
    cr_expect_not(drawn_with(ccw, SR_CULL_BACK, SR_FRONT_CW), "counterclockwise back face drawn");
}

Test(cull, front_drops_clockwise_and_keeps_counterclockwise)
{
    cr_expect_not(drawn_with(cw, SR_CULL_FRONT, SR_FRONT_CW));
    cr_expect(drawn_with(ccw, SR_CULL_FRONT, SR_FRONT_CW));
}

Test(cull, front_ccw_flips_which_faces_are_culled)
{
    cr_expect_not(drawn_with(cw, SR_CULL_BACK, SR_FRONT_CCW), "cw is a back face with --front ccw");
    cr_expect(drawn_with(ccw, SR_CULL_BACK, SR_FRONT_CCW), "ccw is a front face with --front ccw");
    cr_expect(drawn_with(cw, SR_CULL_FRONT, SR_FRONT_CCW));
    cr_expect_not(drawn_with(ccw, SR_CULL_FRONT, SR_FRONT_CCW));
}

Test(cull, none_keeps_both_windings)
{
    cr_expect(drawn_with(cw, SR_CULL_NONE, SR_FRONT_CW));
    cr_expect(drawn_with(ccw, SR_CULL_NONE, SR_FRONT_CW));
    cr_expect(drawn_with(cw, SR_CULL_NONE, SR_FRONT_CCW));
    cr_expect(drawn_with(ccw, SR_CULL_NONE, SR_FRONT_CCW));
}

Test(cull, zero_area_triangles_are_culled_and_counted)
{
    const float collinear[3][2] = { { 2, 2 }, { 16, 16 }, { 30, 30 } };
    /* Distinct in float, one point after snapping to 1/256 px. */
    const float snap_to_one[3][2] = { { 10, 10 }, { 10.001f, 10 }, { 10, 10.001f } };
    cr_expect_not(drawn_with(collinear, SR_CULL_NONE, SR_FRONT_CW));
    cr_expect_not(drawn_with(snap_to_one, SR_CULL_NONE, SR_FRONT_CW));
}

/* The conventions end to end: left-handed world, camera at -z looking +z,
 * a triangle whose vertices go bottom-left, top, bottom-right as the camera
 * sees them is clockwise on screen, hence a front face. */
Test(cull, clockwise_world_triangle_seen_by_a_perspective_camera_is_a_front_face)
{
    const float pos[3][3] = { { -1, -1, 5 }, { 0, 1, 5 }, { 1, -1, 5 } };
    const uint32_t front[3] = { 0, 1, 2 }, back[3] = { 0, 2, 1 };
    sr_camera cam = sr_camera_default();
    for (int facing = 0; facing < 2; facing++) {
        sr_mesh mesh;
        scene_mesh_make(&mesh, &(scene_mesh_arrays){ .vertex_count = 3, .positions = pos, .index_count = 3,
                                                     .indices = facing ? back : front });
        sr_framebuffer fb;
        scene_fb_make(&fb, VIEW_W, VIEW_H);
        sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_ID };
        scene_camera_desc(&desc, &cam, VIEW_W, VIEW_H);
        sr_stats stats = { 0 };
        cr_assert(sr_draw(&fb, &desc, &stats, NULL));
        if (facing == 0)
            cr_expect_gt(stats.fragments, 0, "the front face was not drawn");
        else
            cr_expect(stats.fragments == 0 && stats.culled == 1, "the back face was drawn");
        sr_mesh_free(&mesh);
        sr_framebuffer_destroy(&fb);
    }
}

static void count_fan(void *user, const sr_screen_vertex tri[3], bool clipped, uint32_t id)
{
    (void)tri;
    (void)id;
    if (clipped)
        ++*(int *)user;
}

/* A triangle clipped into a polygon is fanned; facing away, every fan
 * triangle is culled and counted. */
Test(cull, every_fan_triangle_of_a_clipped_back_face_is_culled_and_counted)
{
    const float xy[3][2] = { { -20, -9 }, { 50, 3 }, { 2, 45 } }; /* crosses left, top, right, bottom */
    sr_mesh mesh;
    scene_pixel_triangle(&mesh, xy, FLAT_Z);
    sr_framebuffer fb;
    scene_fb_make(&fb, FLAT, FLAT);
    int fans = 0;
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_ID, .cull = SR_CULL_NONE,
                          .study = &(sr_draw_study){ .observer = count_fan, .observer_user = &fans } };
    scene_pixel_ortho(&desc, FLAT, FLAT);
    sr_stats stats = { 0 };
    cr_assert(sr_draw(&fb, &desc, &stats, NULL));
    cr_assert_geq(fans, 3, "the polygon was fanned into only %d triangles", fans);
    cr_expect_eq(stats.clipped, 1);
    sr_stats culled = { 0 };
    desc.cull = SR_CULL_FRONT; /* the triangle is clockwise: a front face */
    sr_framebuffer_clear(&fb, SCENE_BACKGROUND);
    cr_assert(sr_draw(&fb, &desc, &culled, NULL));
    cr_expect_eq(culled.culled, (uint64_t)fans, "%llu culled of %d fan triangles",
                 (unsigned long long)culled.culled, fans);
    cr_expect_eq(culled.fragments, 0);
    cr_expect_eq(scene_count_drawn(&fb), 0);
    sr_mesh_free(&mesh);
    sr_framebuffer_destroy(&fb);
}
