/* The look-at camera: sr_camera_frame_bounds and sr_camera_fit_clip fit
 * near and far to a scene of any size, so the library's first picture is
 * never empty, and keep the contract's planes while the scene lies between
 * them; sr_camera_projection's depth row is the correctly rounded one. */
#include <criterion/criterion.h>

#include "softrast_private.h"

/* The view-axis distances of the bounding sphere of [lo, hi] from cam. */
static void sphere_span(const sr_camera *cam, const vec3 lo, const vec3 hi, float *nearest, float *farthest)
{
    vec3 centre, axis, to_centre;
    glm_vec3_center((float *)lo, (float *)hi, centre);
    glm_vec3_sub((float *)cam->target, (float *)cam->eye, axis);
    glm_vec3_normalize(axis);
    glm_vec3_sub(centre, (float *)cam->eye, to_centre);
    float radius = 0.5f * glm_vec3_distance((float *)lo, (float *)hi);
    *nearest = glm_vec3_dot(to_centre, axis) - radius;
    *farthest = glm_vec3_dot(to_centre, axis) + radius;
}

static void assert_planes_hold(const sr_camera *cam, const vec3 lo, const vec3 hi)
{
    float nearest, farthest;
    sphere_span(cam, lo, hi, &nearest, &farthest);
    cr_expect_lt(cam->near, nearest, "near %g cuts the sphere from %g", cam->near, nearest);
    cr_expect_gt(cam->far, farthest, "far %g cuts the sphere to %g", cam->far, farthest);
    cr_expect_gt(cam->near, 0.0f);
}

Test(camera_fit, framing_fits_planes_to_meshes_of_any_size)
{
    static const float scales[] = { 1e-4f, 1e-2f, 1e3f, 1e6f };
    for (size_t i = 0; i < sizeof scales / sizeof scales[0]; i++) {
        float s = scales[i];
        vec3 lo = { 2.0f * s, -s, 0.0f }, hi = { 3.0f * s, s, 0.5f * s };
        sr_camera cam = sr_camera_default();
        sr_camera_frame_bounds(&cam, lo, hi, 4.0f / 3.0f);
        assert_planes_hold(&cam, lo, hi);
        /* Hugging the sphere: the planes are within a few percent of it. */
        float nearest, farthest;
        sphere_span(&cam, lo, hi, &nearest, &farthest);
        cr_expect_gt(cam.near, 0.9f * nearest, "scale %g: near %g, sphere from %g", s, cam.near, nearest);
        cr_expect_lt(cam.far, 1.1f * farthest, "scale %g: far %g, sphere to %g", s, cam.far, farthest);
    }
}

/* A unit mesh lies between the contract's 0.1 and 100: its images stay. */
Test(camera_fit, contract_planes_kept_while_the_scene_lies_between_them)
{
    vec3 lo = { -1.0f, -1.0f, -1.0f }, hi = { 1.0f, 1.0f, 1.0f };
    sr_camera cam = sr_camera_default();
    sr_camera_frame_bounds(&cam, lo, hi, 1.0f);
    cr_expect_eq(cam.near, SR_CAMERA_NEAR);
    cr_expect_eq(cam.far, SR_CAMERA_FAR);
}

/* Flying inside a scene: near stays (there is no nearest point to hug),
 * far reaches past the scene. */
Test(camera_fit, eye_inside_keeps_near_and_reaches_past_the_scene)
{
    vec3 lo = { -500.0f, -500.0f, -500.0f }, hi = { 500.0f, 500.0f, 500.0f };
    sr_camera cam = sr_camera_default();
    glm_vec3_copy((vec3){ 10.0f, 0.0f, 0.0f }, cam.eye);
    glm_vec3_copy((vec3){ 20.0f, 5.0f, 3.0f }, cam.target);
    sr_camera_fit_clip(&cam, lo, hi);
    float nearest, farthest;
    sphere_span(&cam, lo, hi, &nearest, &farthest);
    cr_expect_eq(cam.near, SR_CAMERA_NEAR);
    cr_expect_gt(cam.far, farthest);
}

/* An eye of the caller's looking away from the scene: nothing can be
 * shown, and the planes are left as they were. */
Test(camera_fit, scene_behind_the_eye_leaves_the_planes)
{
    vec3 lo = { -1.0f, -1.0f, 500.0f }, hi = { 1.0f, 1.0f, 502.0f };
    sr_camera cam = sr_camera_default();
    glm_vec3_copy((vec3){ 0.0f, 0.0f, -1.0f }, cam.target);
    glm_vec3_copy((vec3){ 0.0f, 0.0f, 0.0f }, cam.eye);
    sr_camera_fit_clip(&cam, lo, hi);
    cr_expect_eq(cam.near, SR_CAMERA_NEAR);
    cr_expect_eq(cam.far, SR_CAMERA_FAR);
}

/* The first picture of a tiny mesh through the library is not empty (the
 * contract's near 0.1 once cut it whole). */
Test(camera_fit, framed_tiny_mesh_draws)
{
    vec3 positions[3] = { { 0.0f, 0.0f, 0.0f }, { 0.0f, 1e-3f, 0.0f }, { 1e-3f, 0.0f, 0.0f } };
    uint32_t indices[3] = { 0, 1, 2 };
    sr_mesh mesh = { .vertex_count = 3, .positions = positions, .index_count = 3, .indices = indices };
    uint32_t color[32 * 32];
    float depth[32 * 32];
    sr_framebuffer fb = { .width = 32, .height = 32, .color = color, .depth = depth };
    sr_framebuffer_clear(&fb, 0);
    vec3 lo, hi;
    cr_assert(sr_mesh_bounds(&mesh, lo, hi));
    sr_camera cam = sr_camera_default();
    sr_camera_frame_bounds(&cam, lo, hi, 1.0f);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_ID, .cull = SR_CULL_NONE };
    sr_camera_view(&cam, desc.view);
    sr_camera_projection(&cam, 1.0f, desc.projection);
    sr_stats stats = { 0 };
    cr_assert(sr_draw(&fb, &desc, &stats, NULL));
    cr_expect_eq(stats.rejected, 0);
    /* A fair share of the frame, seen from the framed three-quarter view. */
    cr_expect_gt(stats.fragments, 32 * 32 / 12, "%llu fragments", (unsigned long long)stats.fragments);
}

/* The depth row z_clip = a·z_view + b of every mode, a and b the double
 * values rounded once (cglm's float f/(f − n) is an ulp off, a bias every
 * depth carried). */
Test(camera_projection, depth_row_is_rounded_once_from_double)
{
    static const float planes[][2] = { { 0.1f, 100.0f }, { 1.0f, 2000.0f }, { 0.01f, 1e4f }, { 3.0f, 7.0f } };
    for (size_t i = 0; i < sizeof planes / sizeof planes[0]; i++)
        for (int mode = 0; mode < 4; mode++) {
            sr_camera cam = sr_camera_default();
            double n = cam.near = planes[i][0], f = cam.far = planes[i][1];
            cam.reversed_z = mode & 1;
            cam.ortho_height = (mode & 2) ? 2.0f : 0.0f;
            mat4 p;
            sr_camera_projection(&cam, 1.5f, p);
            double a, b;
            if (cam.ortho_height > 0.0f) {
                a = (cam.reversed_z ? -1.0 : 1.0) / (f - n);
                b = (cam.reversed_z ? f : -n) / (f - n);
            } else {
                a = (cam.reversed_z ? -n : f) / (f - n);
                b = (cam.reversed_z ? n * f : -n * f) / (f - n);
            }
            cr_expect_eq(p[2][2], (float)a, "near %g far %g mode %d: a %.9g, want %.9g", n, f, mode, p[2][2], a);
            cr_expect_eq(p[3][2], (float)b, "near %g far %g mode %d: b %.9g, want %.9g", n, f, mode, p[3][2], b);
        }
}
