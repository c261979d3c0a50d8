/* The vertex stage: clip = P·V·W·p, and unit world normals through the
 * inverse transpose of W, also for a W that flattens the mesh. */
#include <criterion/criterion.h>
#include <math.h>

#include "softrast_private.h"

static void transform_normal(const mat4 world, vec3 n, vec3 out)
{
    sr_vertex_transform xf;
    mat4 identity = GLM_MAT4_IDENTITY_INIT;
    sr_vertex_make_transform(world, identity, identity, &xf);
    glm_mat3_mulv(xf.normal_matrix, n, out);
    glm_vec3_normalize(out);
}

Test(vertex, normals_turn_with_a_rotation)
{
    mat4 world;
    glm_rotate_make(world, glm_rad(90.0f), (vec3){ 0, 1, 0 });
    vec3 n;
    transform_normal(world, (vec3){ 0, 0, 1 }, n);
    cr_assert(fabsf(n[0] - 1.0f) < 1e-6f && fabsf(n[1]) < 1e-6f && fabsf(n[2]) < 1e-6f, "got %g %g %g", n[0], n[1],
              n[2]);
}

Test(vertex, normals_follow_the_inverse_transpose_of_a_stretch)
{
    mat4 world = GLM_MAT4_IDENTITY_INIT;
    world[0][0] = 4.0f; /* stretch x: a 45° normal in xy leans toward y */
    vec3 n;
    transform_normal(world, (vec3){ 1, 1, 0 }, n);
    cr_assert(fabsf(n[1] / n[0] - 4.0f) < 1e-5f, "got %g %g %g", n[0], n[1], n[2]);
}

Test(vertex, a_mirror_keeps_normals_pointing_out)
{
    mat4 world = GLM_MAT4_IDENTITY_INIT;
    world[0][0] = -1.0f;
    vec3 n;
    transform_normal(world, (vec3){ 1, 0, 0 }, n);
    cr_assert(fabsf(n[0] + 1.0f) < 1e-6f, "a mirrored +x normal points to -x, got %g", n[0]);
}

/* A zero scale is finite input: the flattened mesh draws, lit, with the
 * pixels the id view draws. */
Test(vertex, a_flattening_world_keeps_finite_normals_and_draws)
{
    sr_mesh m;
    sr_error err;
    cr_assert(sr_shape_torus(&m, 1.0f, 0.4f, 16, 8, &err), "%s", err.message);
    sr_framebuffer fb;
    cr_assert(sr_framebuffer_create(&fb, 64, 64, &err), "%s", err.message);
    sr_camera cam = sr_camera_default();
    glm_vec3_copy((vec3){ 0, 3, -0.5f }, cam.eye);
    sr_draw_desc desc = { .mesh = &m, .cull = SR_CULL_NONE };
    glm_mat4_identity(desc.world);
    desc.world[1][1] = 0.0f; /* flatten y */
    sr_camera_view(&cam, desc.view);
    sr_camera_projection(&cam, 1.0f, desc.projection);
    uint64_t fragments[2];
    for (int pass = 0; pass < 2; pass++) {
        sr_stats stats = { 0 };
        desc.shade = pass ? SR_SHADE_LAMBERT : SR_SHADE_ID;
        sr_framebuffer_clear(&fb, 0);
        cr_assert(sr_draw(&fb, &desc, &stats, &err), "%s", err.message);
        cr_assert_eq(stats.nonfinite, 0);
        fragments[pass] = stats.fragments;
    }
    cr_assert_gt(fragments[0], 0);
    cr_assert_eq(fragments[0], fragments[1]);
    sr_framebuffer_destroy(&fb);
    sr_mesh_free(&m);
}
