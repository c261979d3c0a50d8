/* Clip-space input (sr_mesh.clip_positions), as conformance suites write
 * their cases: vertices placed at any w directly, drawn with no matrix and
 * clipped as transformed ones are. */
#include <criterion/criterion.h>
#include <string.h>

#include "scene_helpers.h"
#include "softrast_private.h"

#define W 48
#define H 32

/* A mesh of `n` triangles whose clip-space corners are ndc[k]·w[k] (x, y)
 * with z = zn·w[k]. */
static void clip_mesh(sr_mesh *m, const float (*ndc)[2], const float *w, float zn, uint32_t n)
{
    scene_mesh_alloc(m, 3 * n, n, false);
    m->clip_positions = malloc(3 * n * sizeof *m->clip_positions);
    cr_assert_not_null(m->clip_positions);
    for (uint32_t k = 0; k < 3 * n; k++) {
        glm_vec4_copy((vec4){ ndc[k][0] * w[k], ndc[k][1] * w[k], zn * w[k], w[k] }, m->clip_positions[k]);
        m->indices[k] = k;
    }
}

static void draw(sr_framebuffer *fb, const sr_mesh *m, bool count_hits, sr_stats *stats)
{
    sr_draw_desc desc = { .mesh = m, .shade = SR_SHADE_ID, .cull = SR_CULL_NONE,
                          .study = &(sr_draw_study){ .count_hits = count_hits } };
    /* Matrices a clip-space mesh must ignore. */
    glm_translate_make(desc.world, (vec3){ 5.0f, -3.0f, 2.0f });
    glm_scale_make(desc.projection, (vec3){ 0.1f, 7.0f, -1.0f });
    sr_framebuffer_clear(fb, 0);
    sr_error err = { "" };
    *stats = (sr_stats){ 0 };
    cr_assert(sr_draw(fb, &desc, stats, &err), "%s", err.message);
}

/* Scaling a vertex by a power of two changes nothing after the divide, so
 * the same triangle at w = 1, 2^-24 (1e-7) and 2^17 (1e5) draws the same
 * pixels and depths, bit for bit. */
Test(clip_space, the_same_triangle_at_any_w_draws_alike)
{
    static const float ndc[3][2] = { { -0.8f, -0.7f }, { 0.9f, -0.2f }, { -0.1f, 0.85f } };
    static const float scales[] = { 1.0f, 0x1p-24f, 0x1p17f };
    sr_framebuffer ref, fb;
    scene_fb_make(&ref, W, H);
    scene_fb_make(&fb, W, H);
    for (size_t s = 0; s < sizeof scales / sizeof *scales; s++) {
        const float w[3] = { scales[s], scales[s], scales[s] };
        sr_mesh m;
        clip_mesh(&m, ndc, w, 0.25f, 1);
        sr_stats stats;
        draw(s == 0 ? &ref : &fb, &m, false, &stats);
        cr_assert_eq(stats.clipped, 0);
        if (s > 0) {
            cr_assert_eq(memcmp(ref.color, fb.color, sizeof(uint32_t) * W * H), 0, "w = %g: colors differ", w[0]);
            cr_assert_eq(memcmp(ref.depth, fb.depth, sizeof(float) * W * H), 0, "w = %g: depths differ", w[0]);
        }
        sr_mesh_free(&m);
    }
    cr_assert_gt(scene_count_drawn(&ref), W * H / 5, "the triangle covers a good part of the frame");
    cr_assert_float_eq(ref.depth[(H / 2) * W + W / 2], 0.25f, 0.0f, "z_ndc = z / w exactly");
    sr_framebuffer_destroy(&ref);
    sr_framebuffer_destroy(&fb);
}

/* A conformance-style triangle: corners 10^4·w outside several planes at w
 * from 0.2 to 15.5. Its projection contains the whole viewport, so after
 * clipping against left, right, bottom and top every pixel is covered
 * exactly once. */
Test(clip_space, a_triangle_far_outside_three_planes_covers_the_viewport_once)
{
    static const float ndc[3][2] = { { -1e4f, -1e4f }, { 3e4f, -1e4f }, { -1e4f, 3e4f } };
    static const float w[3] = { 0.2f, 7.0f, 15.5f };
    sr_mesh m;
    clip_mesh(&m, ndc, w, 0.5f, 1);
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    sr_stats stats;
    draw(&fb, &m, true, &stats);
    cr_assert_eq(stats.clipped, 1);
    for (int i = 0; i < W * H; i++)
        cr_assert_eq(fb.color[i], 1u, "pixel %d hit %u times", i, fb.color[i]);
    sr_framebuffer_destroy(&fb);
    sr_mesh_free(&m);
}

Test(clip_space, a_mesh_without_positions_of_either_kind_is_refused)
{
    sr_mesh m;
    scene_mesh_alloc(&m, 3, 1, false);
    free(m.positions);
    m.positions = NULL;
    sr_framebuffer fb;
    scene_fb_make(&fb, 4, 4);
    sr_draw_desc desc = { .mesh = &m, .shade = SR_SHADE_ID };
    sr_error err = { "" };
    cr_assert_not(sr_draw(&fb, &desc, NULL, &err));
    cr_assert_not_null(strstr(err.message, "neither positions nor clip-space positions"), "%s", err.message);
    sr_framebuffer_destroy(&fb);
    sr_mesh_free(&m);
}
