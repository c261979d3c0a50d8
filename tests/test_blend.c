/* Blending (softrast.h, sr_blend; src/pipeline/11_merge.h): exact pixels
 * of each blend in both colour spaces on small pixel-space scenes, depth
 * and ids kept by no_depth_write, submission order, and the same bits on
 * every loop, path and thread count. */
#include <criterion/criterion.h>
#include <string.h>

#include "scene_helpers.h"

#define W 32
#define H 16
#define QUADS 3

/* Full-framebuffer quads in pixel space, quad i at depth z[i] and in part
 * i, drawn in that order, with the materials given (texture shading draws
 * a material's colour unlit, so every pixel is known). */
typedef struct quads {
    sr_mesh mesh;
    sr_mesh_part parts[QUADS];
    sr_material materials[QUADS];
} quads;

static void quads_make(quads *q, const float z[QUADS], const sr_material m[QUADS])
{
    sr_error err = { "" };
    cr_assert(sr_mesh_alloc(&q->mesh, 4 * QUADS, 6 * QUADS, true, false, false, &err), "%s", err.message);
    for (uint32_t i = 0; i < QUADS; i++) {
        const float xs[4] = { 0, W, 0, W }, ys[4] = { 0, 0, H, H };
        for (uint32_t k = 0; k < 4; k++) {
            glm_vec3_copy((vec3){ xs[k], ys[k], z[i] }, q->mesh.positions[4 * i + k]);
            glm_vec3_copy((vec3){ 0.0f, 0.0f, -1.0f }, q->mesh.normals[4 * i + k]);
        }
        const uint32_t idx[6] = { 4 * i, 4 * i + 1, 4 * i + 2, 4 * i + 1, 4 * i + 3, 4 * i + 2 };
        memcpy(q->mesh.indices + 6 * i, idx, sizeof idx);
        q->parts[i] = (sr_mesh_part){ 2 * i, 2, i };
        q->materials[i] = m[i];
    }
    q->mesh.parts = q->parts;
    q->mesh.part_count = QUADS;
    q->mesh.materials = q->materials;
    q->mesh.material_count = QUADS;
}

static void quads_free(quads *q)
{
    q->mesh.parts = NULL;
    q->mesh.materials = NULL;
    sr_mesh_free(&q->mesh);
}

#define OPAQUE_RED { .base_color = { 1, 0, 0, 1 } }
#define CLEAR { .base_color = { 0, 0, 0, 0 }, .alpha_mode = SR_ALPHA_BLEND } /* draws nothing it blends */

static sr_material blend_of(float r, float g, float b, float a)
{
    return (sr_material){ .base_color = { r, g, b, a }, .alpha_mode = SR_ALPHA_BLEND };
}

/* desc drawn into a fresh framebuffer (cleared to black, with ids) on every
 * loop the CPU has, one thread and three (tiles, row bands), all asserted
 * equal; fb gets the first. */
static void draw_everywhere(const sr_draw_desc *base, sr_framebuffer *fb)
{
    sr_draw_desc desc = *base;
    desc.cull = SR_CULL_NONE;
    desc.shade = SR_SHADE_TEXTURE;
    scene_pixel_ortho(&desc, W, H);
    sr_simd loops[SCENE_LOOPS];
    size_t n = scene_available_loops(loops);
    static const sr_draw_path paths[] = { SR_PATH_DIRECT, SR_PATH_TILES, SR_PATH_ROWS };
    sr_error err = { "" };
    for (size_t l = 0; l < n; l++)
        for (size_t p = 0; p < sizeof paths / sizeof *paths; p++) {
            sr_framebuffer out;
            sr_stats stats;
            scene_fb_make(&out, W, H);
            cr_assert(sr_framebuffer_create_ids(&out, &err), "%s", err.message);
            scene_draw_on_loop(&out, &desc, loops[l], paths[p] == SR_PATH_DIRECT ? 1 : 3, paths[p], &stats);
            if (l == 0 && p == 0) {
                *fb = out;
                continue;
            }
            cr_assert_eq(memcmp(fb->color, out.color, W * H * sizeof(uint32_t)), 0, "%s, path %d: colours",
                         sr_simd_name(loops[l]), (int)paths[p]);
            cr_assert_eq(memcmp(fb->depth, out.depth, W * H * sizeof(float)), 0, "depths");
            cr_assert_eq(memcmp(fb->ids, out.ids, W * H * sizeof(uint32_t)), 0, "ids");
            sr_framebuffer_destroy(&out);
        }
}

/* Every pixel of the scene drawn with this blend and colour space. */
static uint32_t colour_of(const quads *q, sr_blend blend, sr_color_space space)
{
    sr_framebuffer fb;
    draw_everywhere(&(sr_draw_desc){ .mesh = &q->mesh, .blend = blend, .color_space = space }, &fb);
    uint32_t c = fb.color[0];
    cr_assert_eq(scene_count_color(&fb, c), (size_t)W * H, "not one colour: %06x at 0", c);
    sr_framebuffer_destroy(&fb);
    return c;
}

/* Blue at alpha 0.5 (128/256) over opaque red. Raw: red 255·128/256 →
 * 128, blue the same. sRGB: 4095 (red, linear) · ½ = 2048, encoded 188.
 * Added: red stays, blue is half. A draw that replaces draws BLEND as
 * MASK at 0.5: blue whole. */
Test(blend, each_blend_over_red_in_both_colour_spaces)
{
    quads q;
    quads_make(&q, (const float[QUADS]){ 0.5f, 0.25f, 0.2f },
               (const sr_material[QUADS]){ OPAQUE_RED, blend_of(0, 0, 1, 0.5f), CLEAR });
    cr_expect_eq(colour_of(&q, SR_BLEND_ALPHA, SR_COLOR_RAW), 0x800080u);
    cr_expect_eq(colour_of(&q, SR_BLEND_ALPHA, SR_COLOR_SRGB), 0xBC00BCu);
    cr_expect_eq(colour_of(&q, SR_BLEND_ADD, SR_COLOR_RAW), 0xFF0080u);
    cr_expect_eq(colour_of(&q, SR_BLEND_ADD, SR_COLOR_SRGB), 0xFF00BCu);
    cr_expect_eq(colour_of(&q, SR_BLEND_REPLACE, SR_COLOR_RAW), 0x0000FFu);
    /* Premultiplied: the source is blue 0.5 already times its alpha. */
    q.materials[1] = blend_of(0, 0, 0.5f, 0.5f);
    cr_expect_eq(colour_of(&q, SR_BLEND_PREMULTIPLIED, SR_COLOR_RAW), 0x800080u);
    cr_expect_eq(colour_of(&q, SR_BLEND_PREMULTIPLIED, SR_COLOR_SRGB), 0xBC00BCu);
    /* Added past 1: clamped. */
    q.materials[1] = blend_of(1, 1, 1, 1);
    cr_expect_eq(colour_of(&q, SR_BLEND_ADD, SR_COLOR_RAW), 0xFFFFFFu);
    quads_free(&q);
}

/* Alpha blending is not commutative: green then blue over red is (64,
 * 64, 128), blue then green (64, 128, 64); each layer halves what is
 * below (128·128/256 = 64). */
Test(blend, layers_blend_in_submission_order)
{
    quads q;
    quads_make(&q, (const float[QUADS]){ 0.5f, 0.3f, 0.25f },
               (const sr_material[QUADS]){ OPAQUE_RED, blend_of(0, 1, 0, 0.5f), blend_of(0, 0, 1, 0.5f) });
    cr_expect_eq(colour_of(&q, SR_BLEND_ALPHA, SR_COLOR_RAW), 0x404080u);
    q.materials[1] = blend_of(0, 0, 1, 0.5f);
    q.materials[2] = blend_of(0, 1, 0, 0.5f);
    cr_expect_eq(colour_of(&q, SR_BLEND_ALPHA, SR_COLOR_RAW), 0x408040u);
    quads_free(&q);
}

/* With no_depth_write a blended layer over an opaque draw leaves the
 * opaque depth and ids; blended with depth writes, the layer's own. */
Test(blend, no_depth_write_keeps_the_opaque_depth_and_ids)
{
    quads q;
    quads_make(&q, (const float[QUADS]){ 0.5f, 0.25f, 0.2f },
               (const sr_material[QUADS]){ OPAQUE_RED, blend_of(0, 0, 1, 0.5f), CLEAR });
    for (int keep = 0; keep < 2; keep++) {
        sr_framebuffer fb;
        draw_everywhere(&(sr_draw_desc){ .mesh = &q.mesh, .blend = SR_BLEND_ALPHA, .no_depth_write = keep }, &fb);
        for (int i = 0; i < W * H; i++) {
            cr_assert_eq(fb.color[i], 0x800080u, "pixel %d: %06x", i, fb.color[i]);
            if (keep) { /* nothing wrote depth or ids: the clear values */
                cr_assert_eq(fb.depth[i], 1.0f, "pixel %d: depth %g", i, fb.depth[i]);
                cr_assert_eq(fb.ids[i], 0u, "pixel %d: id %u", i, fb.ids[i]);
            } else { /* the nearest layer's, the clear one at 0.2 (slots 4 and 5) */
                cr_assert_eq(fb.depth[i], 0.2f, "pixel %d: depth %g", i, fb.depth[i]);
                cr_assert(fb.ids[i] == 5u || fb.ids[i] == 6u, "pixel %d: id %u", i, fb.ids[i]);
            }
        }
        sr_framebuffer_destroy(&fb);
    }
    quads_free(&q);
}

/* The scene drawn on the scalar loop, one thread, direct, against every
 * loop the CPU has (each takes the scalar loop: no kernel or tiny queue
 * call), on the direct path and on the tiles and the row bands at every
 * thread count from 1 to 16: the same colours, depths and counts. */
static void assert_the_same_everywhere(const sr_draw_desc *desc, int width, int height, const char *what)
{
    sr_framebuffer one;
    sr_stats one_stats;
    scene_fb_make(&one, width, height);
    scene_draw_on_loop(&one, desc, SR_SIMD_SCALAR, 1, SR_PATH_DIRECT, &one_stats);
    cr_assert_gt(one_stats.fragments, (uint64_t)width * height / 4, "%s: too little drawn to compare", what);
    sr_simd loops[SCENE_LOOPS];
    size_t n = scene_available_loops(loops);
    static const sr_draw_path paths[] = { SR_PATH_DIRECT, SR_PATH_TILES, SR_PATH_ROWS };
    for (size_t l = 0; l < n; l++)
        for (size_t p = 0; p < sizeof paths / sizeof *paths; p++)
            for (int threads = 1; threads <= 16; threads++) {
                if (paths[p] == SR_PATH_DIRECT && threads > 1)
                    break;
                if (l > 0 && threads > 4 && threads < 16) /* every count once, on the loop the CPU picks */
                    continue;
                sr_framebuffer many;
                sr_stats stats;
                scene_fb_make(&many, width, height);
                uint64_t vector_calls = scene_draw_on_loop(&many, desc, loops[l], threads, paths[p], &stats);
                cr_assert_eq(vector_calls, 0u, "%s: the %s loop called a kernel", what, sr_simd_name(loops[l]));
                cr_assert_eq(memcmp(one.color, many.color, (size_t)width * height * sizeof(uint32_t)), 0,
                             "%s, %s, path %d, %d threads: colours", what, sr_simd_name(loops[l]), (int)paths[p],
                             threads);
                cr_assert_eq(memcmp(one.depth, many.depth, (size_t)width * height * sizeof(float)), 0, "depths");
                cr_assert_eq(memcmp(&one_stats, &stats, sizeof stats), 0, "counts");
                sr_framebuffer_destroy(&many);
            }
    sr_framebuffer_destroy(&one);
}

/* A torus of translucent triangles seen through itself (no culling, no
 * depth writes: every layer blends over the ones before), lambert lit, in
 * both colour spaces and each blend; then a dense one, most of its
 * triangles smaller than a pixel (the tiny queue's and the sub-pixel
 * tests' triangles), with depth writes, so each pixel's layers depend on
 * which came first. */
Test(blend, a_translucent_torus_is_the_same_on_every_loop_path_and_thread_count)
{
    static const struct {
        int rings, sides;
        sr_blend blend;
        bool keep_depth;
        sr_color_space space;
    } cases[] = {
        { 60, 30, SR_BLEND_ALPHA, true, SR_COLOR_RAW },        { 60, 30, SR_BLEND_ALPHA, true, SR_COLOR_SRGB },
        { 60, 30, SR_BLEND_ADD, true, SR_COLOR_SRGB },         { 60, 30, SR_BLEND_PREMULTIPLIED, true, SR_COLOR_RAW },
        { 60, 30, SR_BLEND_REPLACE, true, SR_COLOR_RAW },      { 400, 200, SR_BLEND_ALPHA, false, SR_COLOR_SRGB },
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        sr_mesh torus;
        sr_error err = { "" };
        cr_assert(sr_shape_torus(&torus, 1.0f, 0.4f, cases[i].rings, cases[i].sides, &err), "%s", err.message);
        sr_material glass = blend_of(0.9f, 0.5f, 0.2f, 0.6f); /* over MASK's 0.5: replacing draws it */
        sr_mesh_part all = { 0, sr_mesh_triangle_slots(&torus), 0 };
        torus.materials = &glass;
        torus.material_count = 1;
        torus.parts = &all;
        torus.part_count = 1;
        sr_camera cam = scene_camera(0, 1.1f, -1.9f, 0, 0, 0, 60.0f, SR_CAMERA_NEAR, SR_CAMERA_FAR);
        sr_draw_desc desc = { .mesh = &torus, .blend = cases[i].blend, .no_depth_write = cases[i].keep_depth,
                              .cull = SR_CULL_NONE, .color_space = cases[i].space };
        scene_camera_desc(&desc, &cam, 160, 96);
        char what[64];
        snprintf(what, sizeof what, "case %zu", i);
        assert_the_same_everywhere(&desc, 160, 96, what);
        torus.materials = NULL;
        torus.parts = NULL;
        sr_mesh_free(&torus);
    }
}

/* Points and lines merge as triangles do, with the draw's alpha: its
 * texture's (they take no material), 1 without one. Over a red clear: an
 * additive blue point and an additive white line (saturating: 255 + 255
 * is 255), and a point of a texture of alpha 128 blended: 128 is
 * 128 + 1 = 129 out of 256, so red 255·127/256 → 127 and blue
 * 255·129/256 → 128 (each rounded to nearest). None writes depth. */
Test(blend, points_and_lines_merge_with_their_texture_alpha)
{
    sr_error err = { "" };
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    sr_framebuffer_clear(&fb, 0xFF0000u);
    sr_mesh m;
    cr_assert(sr_mesh_alloc(&m, 4, 2, false, true, true, &err), "%s", err.message);
    const float xyz[4][3] = { { 3.5f, 2.5f, 0.5f }, { 8.5f, 2.5f, 0.5f }, { 2.0f, 9.5f, 0.5f }, { 12.0f, 9.5f, 0.5f } };
    memcpy(m.positions, xyz, sizeof xyz);
    for (int i = 0; i < 4; i++)
        glm_vec3_copy(i < 2 ? (vec3){ 0, 0, 1 } : (vec3){ 1, 1, 1 }, m.colors[i]);
    m.indices[0] = 0;
    m.indices[1] = 1;
    m.topology = SR_POINT_LIST;
    sr_draw_desc desc = { .mesh = &m, .shade = SR_SHADE_COLOR, .blend = SR_BLEND_ADD, .no_depth_write = true };
    scene_pixel_ortho(&desc, W, H);
    cr_assert(sr_draw(&fb, &desc, NULL, &err), "%s", err.message);
    m.indices[0] = 2;
    m.indices[1] = 3;
    m.topology = SR_LINE_LIST; /* from pixel 2 up to 12, not including it (Direct3D's diamond exit) */
    cr_assert(sr_draw(&fb, &desc, NULL, &err), "%s", err.message);
    const uint32_t texel = 0x800000FFu; /* blue at alpha 128 */
    sr_texture half_blue = { .width = 1, .height = 1, .texels = (uint32_t *)&texel, .alpha = true };
    m.indices[0] = m.indices[1] = 1; /* the second point again, over its additive blue */
    m.topology = SR_POINT_LIST;
    desc = (sr_draw_desc){ .mesh = &m, .shade = SR_SHADE_TEXTURE, .texture = &half_blue, .filter = SR_FILTER_NEAREST,
                           .blend = SR_BLEND_ALPHA, .no_depth_write = true };
    scene_pixel_ortho(&desc, W, H);
    cr_assert(sr_draw(&fb, &desc, NULL, &err), "%s", err.message);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            /* (8, 2): additive blue, then blue at 128 over it twice: red 255 → 127 → 63 (127·127/256
             * rounded), blue 255 → 255 (255·127 + 255·129 = 255·256) */
            uint32_t want = x == 3 && y == 2             ? 0xFF00FFu
                            : x == 8 && y == 2           ? 0x3F00FFu
                            : y == 9 && x >= 2 && x < 12 ? 0xFFFFFFu
                                                         : 0xFF0000u;
            cr_assert_eq(fb.color[y * W + x], want, "(%d, %d): %06x, not %06x", x, y, fb.color[y * W + x], want);
            cr_assert_eq(fb.depth[y * W + x], 1.0f, "(%d, %d): depth written", x, y);
        }
    sr_framebuffer_destroy(&fb);
    sr_mesh_free(&m);
}

/* A torus's vertices as additive points and its edges as translucent
 * lines (lit, through one another, no depth writes): the same bits on
 * every path and thread count, binned or not. */
Test(blend, points_and_lines_are_the_same_on_every_path_and_thread_count)
{
    static const struct {
        sr_topology topology;
        sr_blend blend;
    } cases[] = { { SR_POINT_LIST, SR_BLEND_ADD }, { SR_LINE_LIST, SR_BLEND_ADD }, { SR_LINE_STRIP, SR_BLEND_PREMULTIPLIED } };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        sr_mesh torus;
        sr_error err = { "" };
        cr_assert(sr_shape_torus(&torus, 1.0f, 0.4f, 80, 40, &err), "%s", err.message);
        torus.topology = cases[i].topology;
        sr_camera cam = scene_camera(0, 1.1f, -1.9f, 0, 0, 0, 60.0f, SR_CAMERA_NEAR, SR_CAMERA_FAR);
        sr_draw_desc desc = { .mesh = &torus, .blend = cases[i].blend, .no_depth_write = true, .point_size = 3.0f,
                              .line_width = 2.0f, .color_space = SR_COLOR_SRGB };
        scene_camera_desc(&desc, &cam, 160, 96);
        char what[64];
        snprintf(what, sizeof what, "topology %d", (int)cases[i].topology);
        assert_the_same_everywhere(&desc, 160, 96, what);
        sr_mesh_free(&torus);
    }
}

Test(blend, an_unknown_blend_is_refused)
{
    quads q;
    quads_make(&q, (const float[QUADS]){ 0.5f, 0.25f, 0.2f },
               (const sr_material[QUADS]){ OPAQUE_RED, OPAQUE_RED, OPAQUE_RED });
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    sr_draw_desc desc = { .mesh = &q.mesh, .blend = (sr_blend)4 };
    scene_pixel_ortho(&desc, W, H);
    sr_error err = { "" };
    cr_assert_not(sr_draw(&fb, &desc, NULL, &err));
    cr_assert_not_null(strstr(err.message, "blend"), "%s", err.message);
    cr_assert_eq(scene_count_color(&fb, SCENE_BACKGROUND), (size_t)W * H, "the framebuffer was touched");
    sr_framebuffer_destroy(&fb);
    quads_free(&q);
}
