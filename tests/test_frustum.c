/* Leaving out what the scene does not need: a mesh whose bounds are inside
 * the view skips classification and clipping, one outside is skipped whole;
 * either way the image, depth and counts are those of the full path. */
#include <criterion/criterion.h>
#include <string.h>

#include "softrast_private.h"

#define W 96
#define H 64

typedef struct drawn {
    sr_framebuffer fb;
    sr_stats stats;
} drawn;

static void draw_from(sr_mesh *mesh, vec3 eye, vec3 target, drawn *out)
{
    sr_error err;
    sr_camera cam = sr_camera_default();
    glm_vec3_copy(eye, cam.eye);
    glm_vec3_copy(target, cam.target);
    sr_draw_desc desc = { .mesh = mesh, .shade = SR_SHADE_ID, .cull = SR_CULL_NONE };
    sr_camera_view(&cam, desc.view);
    sr_camera_projection(&cam, (float)W / H, desc.projection);
    cr_assert(sr_framebuffer_create(&out->fb, W, H, &err), "%s", err.message);
    sr_framebuffer_clear(&out->fb, 0);
    out->stats = (sr_stats){ 0 };
    cr_assert(sr_draw(&out->fb, &desc, &out->stats, &err), "%s", err.message);
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
