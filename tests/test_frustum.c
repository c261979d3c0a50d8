/* Leaving out what the scene does not need: a mesh whose bounds are inside
 * the view skips classification and clipping, one outside is skipped whole;
 * either way the image, depth and counts are those of the full path. */
#include <criterion/criterion.h>
#include <string.h>

#include "softrast_private.h"
#include "scene_helpers.h"

#define W 96
#define H 64

typedef struct drawn {
    sr_framebuffer fb;
    sr_stats stats;
} drawn;

static void draw_from_threads(sr_mesh *mesh, vec3 eye, vec3 target, int threads, drawn *out)
{
    sr_error err;
    sr_camera cam = sr_camera_default();
    glm_vec3_copy(eye, cam.eye);
    glm_vec3_copy(target, cam.target);
    sr_draw_desc desc = { .mesh = mesh, .shade = SR_SHADE_ID, .cull = SR_CULL_NONE, .threads = threads };
    sr_camera_view(&cam, desc.view);
    sr_camera_projection(&cam, (float)W / H, desc.projection);
    cr_assert(sr_framebuffer_create(&out->fb, W, H, &err), "%s", err.message);
    sr_framebuffer_clear(&out->fb, 0);
    out->stats = (sr_stats){ 0 };
    cr_assert(sr_draw(&out->fb, &desc, &out->stats, &err), "%s", err.message);
}

static void draw_from(sr_mesh *mesh, vec3 eye, vec3 target, drawn *out)
{
    draw_from_threads(mesh, eye, target, 1, out);
}

/* The same draw with and without the mesh's bounds must agree bit for bit. */
static sr_stats assert_bounds_change_nothing(vec3 eye, vec3 target)
{
    sr_mesh torus;
    sr_error err;
    cr_assert(sr_shape_torus(&torus, 1.0f, 0.4f, 40, 20, &err), "%s", err.message);
    cr_assert(torus.bounded, "shapes store their bounds");
    drawn with, without;
    draw_from(&torus, eye, target, &with);
    torus.bounded = false;
    draw_from(&torus, eye, target, &without);
    cr_assert_eq(memcmp(with.fb.color, without.fb.color, sizeof(uint32_t) * W * H), 0);
    cr_assert_eq(memcmp(with.fb.depth, without.fb.depth, sizeof(float) * W * H), 0);
    cr_assert_eq(memcmp(&with.stats, &without.stats, sizeof with.stats), 0, "stats differ");
    sr_framebuffer_destroy(&with.fb);
    sr_framebuffer_destroy(&without.fb);
    sr_mesh_free(&torus);
    return with.stats;
}

Test(frustum, mesh_inside_the_view_draws_as_if_classified)
{
    sr_stats s = assert_bounds_change_nothing((vec3){ 0.0f, 1.0f, -6.0f }, (vec3){ 0.0f, 0.0f, 0.0f });
    cr_assert_eq(s.clipped, 0, "the torus was meant to be inside the view");
    cr_assert_gt(s.fragments, 0);
}

Test(frustum, mesh_outside_the_view_is_rejected_whole)
{
    sr_stats s = assert_bounds_change_nothing((vec3){ 0.0f, 0.0f, 6.0f }, (vec3){ 0.0f, 0.0f, 20.0f }); /* looking away */
    cr_assert_eq(s.rejected, s.triangles);
    cr_assert_eq(s.fragments, 0);
}

Test(frustum, mesh_crossing_the_view_is_clipped_as_before)
{
    sr_stats s = assert_bounds_change_nothing((vec3){ 0.6f, 0.0f, -1.3f }, (vec3){ 0.0f, 0.0f, 0.0f });
    cr_assert_gt(s.clipped, 0);
}

Test(frustum, box_classification_keeps_a_margin)
{
    mat4 identity = GLM_MAT4_IDENTITY_INIT;
    cr_assert_eq(sr_clip_classify_box(identity, (vec3){ -0.5f, -0.5f, 0.1f }, (vec3){ 0.5f, 0.5f, 0.9f }),
                 SR_BOX_INSIDE);
    cr_assert_eq(sr_clip_classify_box(identity, (vec3){ -0.5f, -0.5f, 0.0f }, (vec3){ 0.5f, 0.5f, 0.9f }),
                 SR_BOX_CROSSES, "a corner on the near plane is too close to call inside");
    cr_assert_eq(sr_clip_classify_box(identity, (vec3){ 2.0f, -0.5f, 0.1f }, (vec3){ 3.0f, 0.5f, 0.9f }),
                 SR_BOX_OUTSIDE);
    mat4 broken = GLM_MAT4_IDENTITY_INIT;
    broken[0][0] = NAN;
    cr_assert_eq(sr_clip_classify_box(broken, (vec3){ -0.5f, -0.5f, 0.1f }, (vec3){ 0.5f, 0.5f, 0.9f }),
                 SR_BOX_CROSSES, "a non-finite transform decides nothing");
}

/* "Rejected by which planes": each triangle rejected whole is counted under
 * the first plane (near, far, left, right, bottom, top) all its corners are
 * outside, on one thread or several; a mesh rejected whole by its bounds
 * under the first plane its box is outside. */
Test(frustum, rejections_are_counted_by_plane)
{
    static const float pos[][3] = {
        { -0.5f, -0.5f, 0 }, { 0.5f, -0.5f, 0 }, { 0, 0.5f, 0 },    /* in view */
        { 0, 0, -10 },       { 1, 0, -10 },      { 0, 1, -10 },     /* behind the eye: near */
        { 0, 0, 500 },       { 1, 0, 500 },      { 0, 1, 500 },     /* past far */
        { -100, 0, 0 },      { -99, 0, 0 },      { -100, 1, 0 },    /* left */
        { 0, 100, 0 },       { 1, 100, 0 },      { 0, 101, 0 },     /* above: top */
    };
    uint32_t idx[15];
    for (uint32_t i = 0; i < 15; i++)
        idx[i] = i;
    sr_mesh mesh;
    scene_mesh_make(&mesh, &(scene_mesh_arrays){ .vertex_count = 15, .positions = pos, .index_count = 15,
                                                 .indices = idx });
    for (int threads = 1; threads <= 3; threads += 2) {
        drawn d;
        draw_from_threads(&mesh, (vec3){ 0, 0, -5 }, (vec3){ 0, 0, 0 }, threads, &d);
        const uint64_t want[SR_CLIP_PLANES] = { [SR_PLANE_NEAR] = 1, [SR_PLANE_FAR] = 1, [SR_PLANE_LEFT] = 1,
                                                [SR_PLANE_TOP] = 1 };
        for (int p = 0; p < SR_CLIP_PLANES; p++)
            cr_expect_eq(d.stats.rejected_by_plane[p], want[p], "%d threads, %s: %llu", threads,
                         sr_clip_plane_table[p].name, (unsigned long long)d.stats.rejected_by_plane[p]);
        cr_expect_eq(d.stats.rejected, 4);
        cr_expect_gt(d.stats.fragments, 0);
        sr_framebuffer_destroy(&d.fb);
    }
    sr_mesh_free(&mesh);
    sr_mesh torus;
    sr_error err;
    cr_assert(sr_shape_torus(&torus, 1.0f, 0.4f, 40, 20, &err), "%s", err.message);
    drawn away;
    draw_from(&torus, (vec3){ 0, 0, -500 }, (vec3){ 0, 0, 0 }, &away); /* far is 100 */
    cr_expect_eq(away.stats.rejected_by_plane[SR_PLANE_FAR], away.stats.triangles);
    cr_expect_eq(away.stats.rejected, away.stats.triangles);
    sr_framebuffer_destroy(&away.fb);
    sr_mesh_free(&torus);
}
