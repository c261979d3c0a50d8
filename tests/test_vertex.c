/* The vertex stage: clip = P·V·W·p, and unit world normals through the
 * inverse transpose of W, also for a W that flattens the mesh. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <string.h>

#include "softrast_private.h"
#include "test_rng.h"

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

/* ---- finite varyings decided without transforming ---- */

static const float EXTREMES[] = { 0.0f, 1.0f, -1.0f, 1e-40f, -3e-39f, 1e19f, -1e19f, 1e30f, 3e37f, -1e38f,
                                  FLT_MAX, -FLT_MAX, INFINITY, -INFINITY, NAN };
#define EXTREME_COUNT (sizeof EXTREMES / sizeof EXTREMES[0])

static float extreme_or_plain(test_rng *r)
{
    return rng_next(r) % 3 ? EXTREMES[rng_next(r) % EXTREME_COUNT] : (float)rng_uniform(r, -2.0, 2.0);
}

/* A world matrix of plain, huge, tiny, zero or non-finite entries. */
static void random_world(test_rng *r, mat4 world)
{
    static const float scales[] = { 1.0f, 1e20f, 1e-20f, 1e38f, 0.0f, -3.0f };
    glm_mat4_identity(world);
    for (int c = 0; c < 3; c++)
        for (int row = 0; row < 3; row++)
            world[c][row] = (float)rng_uniform(r, -1.0, 1.0) * scales[rng_next(r) % 6];
    if (rng_next(r) % 16 == 0)
        world[rng_next(r) % 3][rng_next(r) % 3] = rng_next(r) % 2 ? NAN : INFINITY;
}

static bool all_finite(const float *v, int n)
{
    for (int k = 0; k < n; k++)
        if (!isfinite(v[k]))
            return false;
    return true;
}

/* sr_vertex_varyings_finite says what the transform would give (the vertex
 * phase's rule for a vertex outside a plane, whose varyings it does not
 * compute), and sr_vertex_block_finite never says finite for a block that
 * holds a vertex whose varyings are not. */
Test(vertex, finite_varyings_are_decided_as_the_transform_decides_them)
{
    enum { VERTICES = 64, ROUNDS = 4000 };
    test_rng r = { 77 };
    sr_mesh m;
    sr_error err;
    cr_assert(sr_mesh_alloc(&m, VERTICES, 0, true, true, true, &err), "%s", err.message);
    const sr_varying_layout layouts[] = {
        { .count = 3, .normal = 0, .uv = -1, .color = -1 },
        { .count = 5, .normal = 0, .uv = 3, .color = -1 },
        { .count = 6, .normal = 0, .uv = -1, .color = 3 },
        { .count = 2, .normal = -1, .uv = 0, .color = -1 },
    };
    mat4 identity = GLM_MAT4_IDENTITY_INIT;
    int decided_nonfinite = 0, blocks_finite = 0;
    for (int round = 0; round < ROUNDS; round++) {
        mat4 world;
        random_world(&r, world);
        sr_vertex_transform xf;
        sr_vertex_make_transform(world, identity, identity, &xf);
        const sr_varying_layout *l = &layouts[round % 4];
        /* Most rounds plain, so that whole blocks are finite too. */
        bool plain = round % 3 == 0;
        for (uint32_t i = 0; i < VERTICES; i++)
            for (int k = 0; k < 3; k++) {
                m.normals[i][k] = plain ? (float)rng_uniform(&r, -1.0, 1.0) : extreme_or_plain(&r);
                m.colors[i][k] = plain ? 0.5f : extreme_or_plain(&r);
                if (k < 2)
                    m.uvs[i][k] = plain ? 0.25f : extreme_or_plain(&r);
            }
        bool every = true;
        for (uint32_t i = 0; i < VERTICES; i++) {
            _Alignas(16) sr_vertex_out v = { { 0 } };
            sr_vertex_run(&m, &xf, l, i, 1, &v);
            bool finite = all_finite(v.v + SR_VARYINGS_AT, l->count);
            cr_assert_eq(sr_vertex_varyings_finite(&m, &xf, l, i), finite,
                         "round %d vertex %u: normal (%g, %g, %g), uv (%g, %g), color (%g, %g, %g)", round, i,
                         m.normals[i][0], m.normals[i][1], m.normals[i][2], m.uvs[i][0], m.uvs[i][1], m.colors[i][0],
                         m.colors[i][1], m.colors[i][2]);
            decided_nonfinite += !finite;
            every = every && finite;
        }
        if (sr_vertex_block_finite(&m, &xf, l, 0, VERTICES)) {
            cr_assert(every, "round %d: a block with a non-finite varying was called finite", round);
            blocks_finite++;
        }
    }
    cr_expect_gt(decided_nonfinite, 0);
    cr_expect_gt(blocks_finite, 0);
    sr_mesh_free(&m);
}

/* A triangle behind the camera, one of whose normals the world's stretch
 * takes past float range, is dropped as non-finite as one in view would
 * be; a normal as long that the stretch leaves finite keeps it counted
 * under the near plane. A second triangle in view makes the draw
 * classify every vertex. */
static sr_stats draw_behind_with_normal(float world_x_scale, const float normal[3])
{
    const float pos[6][3] = { { 0, -1, 5 }, { 0, 1, 5 }, { 0.5f, 0, 5 }, { 0, -1, -5 }, { 0, 1, -5 }, { 0, 0, -6 } };
    float normals[6][3] = { { 0, 0, -1 }, { 0, 0, -1 }, { 0, 0, -1 }, { 0, 0, -1 }, { 0, 0, -1 }, { 0, 0, -1 } };
    memcpy(normals[4], normal, sizeof normals[4]);
    const uint32_t idx[6] = { 0, 1, 2, 3, 4, 5 };
    sr_mesh mesh;
    sr_error err;
    cr_assert(sr_mesh_alloc(&mesh, 6, 6, true, false, false, &err), "%s", err.message);
    memcpy(mesh.positions, pos, sizeof pos);
    memcpy(mesh.normals, normals, sizeof normals);
    memcpy(mesh.indices, idx, sizeof idx);
    sr_mesh_update_bounds(&mesh);
    sr_framebuffer fb;
    cr_assert(sr_framebuffer_create(&fb, 32, 32, &err), "%s", err.message);
    sr_framebuffer_clear(&fb, 0);
    sr_camera cam = sr_camera_default();
    glm_vec3_copy((vec3){ 0, 0, 0 }, cam.eye);
    glm_vec3_copy((vec3){ 0, 0, 1 }, cam.target);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_LAMBERT, .cull = SR_CULL_NONE };
    glm_mat4_identity(desc.world);
    desc.world[0][0] = world_x_scale; /* x is 0 behind the camera: only the normals change */
    sr_camera_view(&cam, desc.view);
    sr_camera_projection(&cam, 1.0f, desc.projection);
    sr_stats s = { 0 };
    cr_assert(sr_draw(&fb, &desc, &s, &err), "%s", err.message);
    sr_mesh_free(&mesh);
    sr_framebuffer_destroy(&fb);
    return s;
}

Test(vertex, a_normal_the_world_takes_past_float_range_drops_its_triangle_outside_the_view)
{
    /* Cofactors of diag(1e20, 1, 1): diag(1, 1e20, 1e20). */
    sr_stats over = draw_behind_with_normal(1e20f, (const float[3]){ 0, 1e30f, 0 });
    cr_expect(over.triangles == 2 && over.rejected == 1 && over.nonfinite == 1 &&
                  over.rejected_by_plane[SR_PLANE_NEAR] == 0,
              "rejected %llu nonfinite %llu near %llu", (unsigned long long)over.rejected,
              (unsigned long long)over.nonfinite, (unsigned long long)over.rejected_by_plane[SR_PLANE_NEAR]);
    sr_stats kept = draw_behind_with_normal(1e20f, (const float[3]){ 1e30f, 0, 0 });
    cr_expect(kept.triangles == 2 && kept.rejected == 1 && kept.nonfinite == 0 &&
                  kept.rejected_by_plane[SR_PLANE_NEAR] == 1,
              "rejected %llu nonfinite %llu near %llu", (unsigned long long)kept.rejected,
              (unsigned long long)kept.nonfinite, (unsigned long long)kept.rejected_by_plane[SR_PLANE_NEAR]);
    sr_stats nan = draw_behind_with_normal(1.0f, (const float[3]){ 0, NAN, 0 });
    cr_expect(nan.rejected == 1 && nan.nonfinite == 1, "rejected %llu nonfinite %llu",
              (unsigned long long)nan.rejected, (unsigned long long)nan.nonfinite);
}

/* The classifying loop gives each vertex the clip position and outcode
 * of the one-vertex loop, four at a time (SSE2) and eight (AVX2, where the
 * CPU has it), over a block whose length is no multiple of either: points
 * far outside every plane, on them, non-finite, under a perspective
 * camera's depth model and without one. */
Test(vertex, the_classifying_lanes_give_each_vertex_its_own_outcode)
{
    enum { VERTICES = 203 };
    test_rng r = { 8181 };
    float positions[VERTICES][3];
    sr_mesh mesh = { .positions = positions, .vertex_count = VERTICES };
    sr_varying_layout none = { .color = -1, .uv = -1, .normal = -1 };
    bool avx2 = sr_raster_simd_resolve(SR_SIMD_AVX2) == SR_SIMD_AVX2;
    int outside = 0, inside = 0;
    for (int round = 0; round < 200; round++) {
        mat4 view, projection, identity = GLM_MAT4_IDENTITY_INIT;
        glm_lookat((vec3){ (float)rng_uniform(&r, -3, 3), (float)rng_uniform(&r, -3, 3), -4.0f }, (vec3){ 0, 0, 0 },
                   (vec3){ 0, 1, 0 }, view);
        if (round % 2)
            glm_perspective(glm_rad(60.0f), 1.3f, 0.5f, 9.0f, projection);
        else
            glm_ortho(-2.0f, 2.0f, -2.0f, 2.0f, 0.5f, 9.0f, projection);
        sr_clip_depth depth = sr_clip_depth_of((const float(*)[4])projection);
        sr_vertex_transform xf;
        sr_vertex_make_transform(identity, view, projection, &xf);
        for (int i = 0; i < VERTICES; i++)
            for (int k = 0; k < 3; k++)
                positions[i][k] = (float)(rng_uniform(&r, -3.0, 3.0) * (rng_below(&r, 20) ? 1.0 : 1e30));
        positions[round % VERTICES][round % 3] = round % 4 ? NAN : INFINITY;
        uint32_t first = (uint32_t)rng_below(&r, 9), count = VERTICES - first - (uint32_t)rng_below(&r, 9);
        _Alignas(16) sr_vertex_out want[VERTICES], got[VERTICES];
        unsigned char want_codes[VERTICES], got_codes[VERTICES];
        for (uint32_t k = 0; k < count; k++) {
            sr_vertex_run(&mesh, &xf, &none, first + k, 1, &want[k]);
            want_codes[k] = (unsigned char)sr_clip_outcode_with(want[k].v, &depth);
            outside += want_codes[k] != 0;
            inside += want_codes[k] == 0;
        }
        for (int lanes = 0; lanes < 1 + avx2; lanes++) {
            sr_vertex_run_inside(&mesh, &xf, &none, &depth, lanes == 1, first, count, got, got_codes);
            for (uint32_t k = 0; k < count; k++) {
                cr_assert_eq(got_codes[k], want_codes[k], "round %d, vertex %u, %s: outcode %#x, want %#x", round,
                             first + k, lanes ? "avx2" : "sse2", got_codes[k], want_codes[k]);
                cr_assert(memcmp(got[k].v, want[k].v, 4 * sizeof(float)) == 0, "round %d, vertex %u, %s: clip differs",
                          round, first + k, lanes ? "avx2" : "sse2");
            }
        }
    }
    cr_assert_gt(outside, 5000);
    cr_assert_gt(inside, 5000);
}
