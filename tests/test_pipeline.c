/* The draw call as a whole: list and strip assembly giving the same picture,
 * and the statistics sr_draw counts. Culling as the user sees it is in
 * test_cull.c, the errors sr_draw reports instead of drawing in
 * test_draw_errors.c.
 */
#include <math.h>
#include <string.h>

#include <criterion/criterion.h>

#include "scene_helpers.h"

#define FLAT 32 /* pixel-space scenes (a power of two) */
#define VIEW_W 64
#define VIEW_H 48
#define FLAT_Z 0.5f

/* Clockwise on screen (y down): top-left, top-right, bottom-left. */
static const float cw[3][2] = { { 4, 4 }, { 28, 5 }, { 5, 27 } };

static void pixel_triangle(sr_mesh *mesh, const float xy[3][2])
{
    scene_pixel_triangle(mesh, xy, FLAT_Z);
}

static sr_stats draw_pixel_space(sr_framebuffer *fb, const sr_mesh *mesh, sr_cull cull, sr_front front)
{
    return scene_draw_pixel_space(fb, mesh, SR_SHADE_ID, cull, front);
}

/* ---- list and strip ---- */

/* The 3 x 3 grid: vertex row * 3 + col at x = col - 1, y = 1 - row. */
static const uint32_t strip_idx[14] = { 3, 0, 4, 1, 5, 2, 2, 6, 6, 3, 7, 4, 8, 5 };
/* The strip's eight triangles in its order and winding: slot k = (i[k],
 * i[k+1], i[k+2]) with the last two swapped for odd k; slots 4–7 repeat an
 * index and are skipped. */
static const uint32_t list_idx[24] = { 3, 0, 4, 0, 1, 4, 4, 1, 5, 1, 2, 5,
                                       6, 3, 7, 3, 4, 7, 7, 4, 8, 4, 5, 8 };
static const uint32_t strip_slot_of_list_slot[8] = { 0, 1, 2, 3, 8, 9, 10, 11 };

static void grid_mesh(sr_mesh *mesh, sr_topology topology)
{
    float pos[9][3], colors[9][3];
    for (int i = 0; i < 9; i++) {
        int row = i / 3, col = i % 3;
        pos[i][0] = (float)(col - 1);
        pos[i][1] = (float)(1 - row);
        pos[i][2] = 0.3f + 0.1f * (float)row + 0.05f * (float)col;
        colors[i][0] = (float)(i + 1) / 9.0f;
        colors[i][1] = (float)(9 - i) / 9.0f;
        colors[i][2] = (float)((i * 5) % 9) / 9.0f;
    }
    bool strip = topology == SR_TRIANGLE_STRIP;
    scene_mesh_make(mesh, &(scene_mesh_arrays){ .vertex_count = 9, .positions = (const float(*)[3])pos,
                                                .colors = (const float(*)[3])colors, .index_count = strip ? 14 : 24,
                                                .indices = strip ? strip_idx : list_idx, .topology = topology });
}

/* Identity view and projection (zero matrices); the world shrinks the grid
 * to 80% so its border is inside the picture. Back faces culled. */
static sr_stats draw_grid(sr_framebuffer *fb, sr_topology topology, sr_shade shade)
{
    sr_mesh mesh;
    grid_mesh(&mesh, topology);
    scene_fb_make(fb, VIEW_W, VIEW_H);
    sr_draw_desc desc = { .mesh = &mesh, .shade = shade };
    glm_scale_make(desc.world, (vec3){ 0.8f, 0.8f, 1.0f });
    sr_stats stats = { 0 };
    sr_error err = { "" };
    cr_assert(sr_draw(fb, &desc, &stats, &err), "sr_draw: %s", err.message);
    sr_mesh_free(&mesh);
    return stats;
}

Test(draw, strip_and_list_of_the_same_triangles_give_identical_color_and_depth)
{
    sr_framebuffer list, strip;
    sr_stats list_stats = draw_grid(&list, SR_TRIANGLE_LIST, SR_SHADE_COLOR);
    sr_stats strip_stats = draw_grid(&strip, SR_TRIANGLE_STRIP, SR_SHADE_COLOR);
    scene_expect_images_equal("draw_strip_and_list_color", strip.color, list.color, VIEW_W, VIEW_H);
    cr_expect_eq(memcmp(strip.depth, list.depth, scene_pixel_count(&list) * sizeof(float)), 0,
                 "depth buffers differ");
    cr_expect_eq(strip_stats.fragments, list_stats.fragments);
    /* 80% of the picture, every pixel once, none culled. */
    cr_expect_eq(list_stats.fragments, scene_count_depth_written(&list));
    cr_expect_eq(list_stats.culled, 0, "the grid's faces should be front faces");
    cr_expect_gt(list_stats.fragments, VIEW_W * VIEW_H / 2);
    sr_framebuffer_destroy(&list);
    sr_framebuffer_destroy(&strip);
}

Test(draw, strip_skips_its_degenerate_triangles)
{
    sr_framebuffer list, strip;
    sr_stats list_stats = draw_grid(&list, SR_TRIANGLE_LIST, SR_SHADE_ID);
    sr_stats strip_stats = draw_grid(&strip, SR_TRIANGLE_STRIP, SR_SHADE_ID);
    cr_expect_eq(list_stats.triangles, 8);
    cr_expect_eq(strip_stats.triangles, 8, "strip assembled %llu triangles", (unsigned long long)strip_stats.triangles);
    cr_expect_eq(strip_stats.culled, 0);
    sr_framebuffer_destroy(&list);
    sr_framebuffer_destroy(&strip);
}

/* Ids are triangle slots: list slot k is strip slot strip_slot_of_list_slot[k]. */
Test(draw, strip_ids_are_strip_slots)
{
    sr_framebuffer list, strip;
    draw_grid(&list, SR_TRIANGLE_LIST, SR_SHADE_ID);
    draw_grid(&strip, SR_TRIANGLE_STRIP, SR_SHADE_ID);
    for (size_t i = 0; i < scene_pixel_count(&list); i++)
        if (list.color[i] != SCENE_BACKGROUND) {
            cr_assert_leq(list.color[i], 8u);
            list.color[i] = strip_slot_of_list_slot[list.color[i] - 1] + 1;
        }
    scene_expect_images_equal("draw_strip_ids_are_strip_slots", strip.color, list.color, VIEW_W, VIEW_H);
    sr_framebuffer_destroy(&list);
    sr_framebuffer_destroy(&strip);
}

/* ---- statistics ---- */

Test(draw, stats_triangle_outside_one_plane_is_rejected)
{
    const float xy[3][2] = { { -30, 2 }, { -1, 5 }, { -9, 30 } }; /* all left of x = 0 */
    sr_mesh mesh;
    pixel_triangle(&mesh, xy);
    sr_framebuffer fb;
    scene_fb_make(&fb, FLAT, FLAT);
    sr_stats s = draw_pixel_space(&fb, &mesh, SR_CULL_NONE, SR_FRONT_CW);
    cr_expect(s.triangles == 1 && s.rejected == 1 && s.nonfinite == 0 && s.clipped == 0 && s.culled == 0 &&
                  s.fragments == 0,
              "triangles %llu rejected %llu nonfinite %llu clipped %llu culled %llu fragments %llu",
              (unsigned long long)s.triangles, (unsigned long long)s.rejected, (unsigned long long)s.nonfinite,
              (unsigned long long)s.clipped, (unsigned long long)s.culled, (unsigned long long)s.fragments);
    cr_expect_eq(scene_count_drawn(&fb), 0);
    sr_mesh_free(&mesh);
    sr_framebuffer_destroy(&fb);
}

Test(draw, stats_triangle_crossing_a_plane_is_clipped_and_its_fragments_counted)
{
    const float xy[3][2] = { { -10, 2 }, { 20, 5 }, { 9, 30 } };
    sr_mesh mesh;
    pixel_triangle(&mesh, xy);
    sr_framebuffer fb;
    scene_fb_make(&fb, FLAT, FLAT);
    sr_stats s = draw_pixel_space(&fb, &mesh, SR_CULL_NONE, SR_FRONT_CW);
    cr_expect(s.triangles == 1 && s.rejected == 0 && s.clipped == 1 && s.culled == 0,
              "triangles %llu rejected %llu clipped %llu culled %llu", (unsigned long long)s.triangles,
              (unsigned long long)s.rejected, (unsigned long long)s.clipped, (unsigned long long)s.culled);
    cr_expect_eq(s.fragments, scene_count_drawn(&fb));
    cr_expect_gt(s.fragments, 100);
    sr_mesh_free(&mesh);
    sr_framebuffer_destroy(&fb);
}

Test(draw, stats_triangle_behind_the_eye_is_rejected)
{
    const float pos[3][3] = { { -1, -1, -5 }, { 0, 1, -5 }, { 1, -1, -5 } };
    sr_mesh mesh;
    scene_triangle_make(&mesh, pos);
    sr_framebuffer fb;
    scene_fb_make(&fb, VIEW_W, VIEW_H);
    sr_camera cam = scene_camera(0, 0, 0, 0, 0, 1, 60.0f, 0.1f, 100.0f);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_ID, .cull = SR_CULL_NONE };
    scene_camera_desc(&desc, &cam, VIEW_W, VIEW_H);
    sr_stats s = { 0 };
    cr_assert(sr_draw(&fb, &desc, &s, NULL));
    cr_expect(s.rejected == 1 && s.fragments == 0 && s.nonfinite == 0, "rejected %llu fragments %llu",
              (unsigned long long)s.rejected, (unsigned long long)s.fragments);
    cr_expect_eq(scene_count_drawn(&fb), 0);
    sr_mesh_free(&mesh);
    sr_framebuffer_destroy(&fb);
}

/* Two triangles, the second with one bad vertex: only the second is dropped. */
static void expect_bad_vertex_rejected(float bad)
{
    const float xy[3][2] = { { 2, 2 }, { 30, 3 }, { 3, 30 } };
    sr_mesh mesh;
    scene_mesh_alloc(&mesh, 4, 2, false);
    for (uint32_t k = 0; k < 3; k++) {
        mesh.positions[k][0] = xy[k][0];
        mesh.positions[k][1] = xy[k][1];
        mesh.positions[k][2] = FLAT_Z;
    }
    mesh.positions[3][0] = bad;
    mesh.positions[3][1] = 20;
    mesh.positions[3][2] = FLAT_Z;
    const uint32_t idx[6] = { 0, 1, 2, 1, 3, 2 };
    memcpy(mesh.indices, idx, sizeof idx);
    sr_framebuffer fb;
    scene_fb_make(&fb, FLAT, FLAT);
    sr_stats s = draw_pixel_space(&fb, &mesh, SR_CULL_NONE, SR_FRONT_CW);
    cr_expect(s.triangles == 2 && s.rejected == 1 && s.nonfinite == 1 && s.clipped == 0,
              "x = %g: triangles %llu rejected %llu nonfinite %llu clipped %llu", bad,
              (unsigned long long)s.triangles, (unsigned long long)s.rejected, (unsigned long long)s.nonfinite,
              (unsigned long long)s.clipped);
    cr_expect_eq(scene_count_color(&fb, 2), 0, "x = %g: the bad triangle drew pixels", bad);
    cr_expect_eq(s.fragments, scene_count_color(&fb, 1));
    cr_expect_gt(s.fragments, 0);
    sr_mesh_free(&mesh);
    sr_framebuffer_destroy(&fb);
}

Test(draw, stats_nan_vertex_is_rejected_as_nonfinite)
{
    expect_bad_vertex_rejected(NAN);
}

Test(draw, stats_infinite_vertex_is_rejected_as_nonfinite)
{
    expect_bad_vertex_rejected(INFINITY);
    expect_bad_vertex_rejected(-INFINITY);
}

/* A triangle inside every plane with a NaN or inf in one vertex's color,
 * drawn in color shading: its varying divided by w is not finite, so the
 * triangle is dropped and counted non-finite, whatever the vertex phase's
 * own checks. */
Test(draw, stats_nonfinite_varying_inside_is_rejected_as_nonfinite)
{
    const float bads[3] = { NAN, INFINITY, -INFINITY };
    for (int b = 0; b < 3; b++) {
        sr_mesh mesh;
        scene_pixel_triangle(&mesh, (const float[3][2]){ { 2, 2 }, { 30, 3 }, { 3, 30 } }, FLAT_Z);
        mesh.colors[1][1] = bads[b];
        sr_framebuffer fb;
        scene_fb_make(&fb, FLAT, FLAT);
        sr_stats s = scene_draw_pixel_space(&fb, &mesh, SR_SHADE_COLOR, SR_CULL_NONE, SR_FRONT_CW);
        cr_expect(s.triangles == 1 && s.rejected == 1 && s.nonfinite == 1 && s.fragments == 0,
                  "color %g: triangles %llu rejected %llu nonfinite %llu fragments %llu", bads[b],
                  (unsigned long long)s.triangles, (unsigned long long)s.rejected,
                  (unsigned long long)s.nonfinite, (unsigned long long)s.fragments);
        cr_expect_eq(scene_count_drawn(&fb), 0, "color %g: pixels drawn", bads[b]);
        sr_mesh_free(&mesh);
        sr_framebuffer_destroy(&fb);
    }
}

Test(draw, stats_nan_in_the_world_matrix_rejects_every_triangle_as_nonfinite)
{
    sr_mesh mesh;
    pixel_triangle(&mesh, cw);
    sr_framebuffer fb;
    scene_fb_make(&fb, FLAT, FLAT);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_ID };
    scene_pixel_ortho(&desc, FLAT, FLAT);
    desc.world[3][0] = NAN;
    sr_stats s = { 0 };
    cr_assert(sr_draw(&fb, &desc, &s, NULL), "bad geometry is not an error");
    cr_expect(s.rejected == 1 && s.nonfinite == 1 && s.fragments == 0);
    cr_expect_eq(scene_count_drawn(&fb), 0);
    sr_mesh_free(&mesh);
    sr_framebuffer_destroy(&fb);
}

/* Fragments are pixels that passed the depth test: drawing the same mesh
 * again at the same depth passes none, on every per-pixel loop this CPU
 * has (the triangle is wide enough for the span kernels). */
Test(draw, stats_fragments_count_only_pixels_that_pass_the_depth_test)
{
    sr_mesh mesh;
    pixel_triangle(&mesh, cw);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_ID, .cull = SR_CULL_BACK, .front = SR_FRONT_CW };
    scene_pixel_ortho(&desc, FLAT, FLAT);
    sr_simd loops[SCENE_LOOPS];
    size_t available = scene_available_loops(loops);
    for (size_t l = 0; l < available; l++) {
        const char *name = sr_simd_name(loops[l]);
        sr_framebuffer fb;
        sr_stats first, again;
        scene_draw_fresh_on_loop(&fb, FLAT, FLAT, &desc, loops[l], &first);
        scene_draw_on_loop(&fb, &desc, loops[l], 1, SR_PATH_DIRECT, &again);
        cr_expect_gt(first.fragments, 0, "%s: the first draw drew nothing, so the second proves nothing", name);
        cr_expect_eq(first.fragments, scene_count_drawn(&fb), "%s", name);
        cr_expect_eq(again.fragments, 0, "%s: %llu fragments passed LESS at equal depth", name,
                     (unsigned long long)again.fragments);
        cr_expect_eq(again.triangles, 1, "%s", name);
        sr_framebuffer_destroy(&fb);
    }
    sr_mesh_free(&mesh);
}

Test(draw, stats_add_up_across_draws)
{
    sr_mesh mesh;
    pixel_triangle(&mesh, cw);
    sr_framebuffer fb;
    scene_fb_make(&fb, FLAT, FLAT);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_ID };
    scene_pixel_ortho(&desc, FLAT, FLAT);
    sr_stats s = { .triangles = 100, .fragments = 1000 };
    cr_assert(sr_draw(&fb, &desc, &s, NULL));
    uint64_t once = s.fragments - 1000;
    sr_framebuffer_clear(&fb, SCENE_BACKGROUND);
    cr_assert(sr_draw(&fb, &desc, &s, NULL));
    cr_expect_eq(s.triangles, 102);
    cr_expect_eq(s.fragments, 1000 + 2 * once);
    cr_expect_gt(once, 0);
    cr_assert(sr_draw(&fb, &desc, NULL, NULL), "stats may be NULL");
    sr_mesh_free(&mesh);
    sr_framebuffer_destroy(&fb);
}

Test(draw, zero_matrices_are_the_identity)
{
    const float pos[3][3] = { { -0.5f, -0.5f, 0.5f }, { 0, 0.5f, 0.5f }, { 0.5f, -0.5f, 0.5f } };
    sr_mesh mesh;
    scene_triangle_make(&mesh, pos);
    sr_framebuffer zero, identity;
    scene_fb_make(&zero, FLAT, FLAT);
    scene_fb_make(&identity, FLAT, FLAT);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_ID };
    cr_assert(sr_draw(&zero, &desc, NULL, NULL));
    glm_mat4_identity(desc.world);
    glm_mat4_identity(desc.view);
    glm_mat4_identity(desc.projection);
    cr_assert(sr_draw(&identity, &desc, NULL, NULL));
    cr_expect_gt(scene_count_drawn(&zero), 0);
    scene_expect_images_equal("draw_zero_matrices_are_the_identity", zero.color, identity.color, FLAT, FLAT);
    sr_mesh_free(&mesh);
    sr_framebuffer_destroy(&zero);
    sr_framebuffer_destroy(&identity);
}
