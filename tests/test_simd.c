/* The SIMD per-pixel loops (SSE2; AVX2 and AVX-512 where the CPU has them)
 * draw exactly what the scalar loop draws: the same colors, depths and
 * counts, bit for bit, in every shading mode, filter and depth convention,
 * one thread or several, on random triangles large enough to take the SIMD
 * path (uvs up to past 2^23, textures down to 1x1) and on the room seen
 * through its walls; and the kernels really draw (the workspace counts
 * their calls). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pipeline/07_cull.h"
#include "draw/draw_state.h"
#include "pipeline/08_raster/kernels.h"
#include "pipeline/08_raster/triangle_setup.h"
#include "softrast_private.h"
#include "scene_helpers.h"

#define SOUP_TRIANGLES 60
#define NARROW_SOUP_TRIANGLES 3000
#define SOUP_SEED 0x51D51D
#define TINY_REACH 0.02 /* triangles up to about 3 pixels wide: each one a tiny box */
#define FB_SIDE (5 * SR_TILE_ROWS_MAX + 1) /* odd, so rows end in partial groups of lanes; 5 tiles and a row */
#define HUGE_UV 3e7f /* past 2^23, where a float has no fraction left to wrap */
#define TILED_THREADS 3

static const sr_simd vector_loops[] = { SR_SIMD_SSE2, SR_SIMD_AVX2, SR_SIMD_AVX512 };

/* Random triangles in front of the camera, many wider than the span
 * threshold, with random normals (some zero; with `flat`, every other
 * triangle has one normal at its three vertices, which an orthographic
 * camera shades once per triangle, and a perspective one too from 32
 * pixels), uvs well outside [0, 1] (wrapping; one triangle in 13 at a tiny
 * negative uv, whose fraction rounds to 1) and colors outside [0, 1]
 * (clamping). With `reach` > 0, a triangle's second and third
 * vertices lie within reach · depth of its first on each axis (at 90° and
 * FB_SIDE pixels, reach 0.15 makes triangles up to about 24 pixels wide). */
static void soup_make(sr_mesh *mesh, int triangles, bool flat, double reach)
{
    sr_error err;
    cr_assert(sr_mesh_alloc(mesh, 3 * (uint32_t)triangles, 3 * (uint32_t)triangles, true, true, true, &err), "%s",
              err.message);
    test_rng rng = { SOUP_SEED };
    for (uint32_t i = 0; i < mesh->vertex_count; i++) {
        float depth = (float)rng_uniform(&rng, 1.0, 6.0);
        glm_vec3_copy((vec3){ (float)rng_uniform(&rng, -1.5, 1.5) * depth, (float)rng_uniform(&rng, -1.5, 1.5) * depth,
                              depth },
                      mesh->positions[i]);
        if (reach > 0.0 && i % 3 > 0) {
            const float *first = mesh->positions[i - i % 3];
            for (int k = 0; k < 3; k++)
                mesh->positions[i][k] = first[k] + (float)rng_uniform(&rng, -reach, reach) * first[2];
        }
        for (int k = 0; k < 3; k++) {
            mesh->normals[i][k] = i % 17 == 0 ? 0.0f : (float)rng_uniform(&rng, -1.0, 1.0);
            mesh->colors[i][k] = (float)rng_uniform(&rng, -0.3, 1.3);
        }
        mesh->uvs[i][0] = i % 23 == 0 ? HUGE_UV : (float)rng_uniform(&rng, -3.0, 3.0);
        mesh->uvs[i][1] = i % 29 == 0 ? -HUGE_UV : (float)rng_uniform(&rng, -3.0, 3.0);
        if ((i / 3) % 13 == 5) /* a triangle at a tiny negative uv: its fraction rounds to 1 */
            mesh->uvs[i][0] = mesh->uvs[i][1] = -0x1p-30f;
        mesh->indices[i] = i;
        if (flat && i % 6 >= 3 && i % 3 > 0)
            glm_vec3_copy(mesh->normals[i - i % 3], mesh->normals[i]);
    }
}

/* A draw with this loop and thread count (one: the direct path; more: the
 * tiles); returns how many rasterizer calls a SIMD kernel made. */
static uint64_t draw_with(const sr_draw_desc *base, sr_simd simd, int threads, bool reversed, sr_framebuffer *fb,
                          sr_stats *stats)
{
    scene_fb_make(fb, FB_SIDE, FB_SIDE);
    fb->reversed_z = reversed;
    sr_framebuffer_clear(fb, 0x123456);
    return scene_draw_on_loop(fb, base, simd, threads, threads == 1 ? SR_PATH_DIRECT : SR_PATH_TILES, stats);
}

static void assert_same_as(const sr_framebuffer *want, const sr_stats *want_stats, const sr_framebuffer *fb,
                           const sr_stats *stats, const char *what, const char *how)
{
    size_t n = scene_pixel_count(want);
    cr_assert_eq(memcmp(fb->color, want->color, n * sizeof *fb->color), 0, "%s: %s colors differ", what, how);
    cr_assert_eq(memcmp(fb->depth, want->depth, n * sizeof *fb->depth), 0, "%s: %s depths differ", what, how);
    cr_assert_eq(memcmp(stats, want_stats, sizeof *stats), 0, "%s: %s counts differ", what, how);
}

/* The scalar loop's draw on one thread, which must make no kernel call. */
static void draw_scalar(const sr_draw_desc *desc, bool reversed, sr_framebuffer *scalar, sr_stats *scalar_stats,
                        const char *what)
{
    cr_assert_eq(draw_with(desc, SR_SIMD_SCALAR, 1, reversed, scalar, scalar_stats), 0u,
                 "%s: the scalar loop called a kernel", what);
}

/* Each vector loop, on one thread and on tiles, against the scalar loop's
 * draw; each must make some kernel call. */
static void assert_vector_loops_match(const sr_draw_desc *desc, bool reversed, const sr_framebuffer *scalar,
                                      const sr_stats *scalar_stats, const char *what)
{
    for (size_t i = 0; i < sizeof vector_loops / sizeof *vector_loops; i++) {
        const char *name = sr_simd_name(sr_raster_simd_resolve(vector_loops[i]));
        for (int threads = 1; threads <= TILED_THREADS; threads += TILED_THREADS - 1) {
            sr_framebuffer fb;
            sr_stats stats;
            uint64_t draws = draw_with(desc, vector_loops[i], threads, reversed, &fb, &stats);
            cr_assert_gt(draws, 0u, "%s: the %s loop on %d threads never ran", what, name, threads);
            assert_same_as(scalar, scalar_stats, &fb, &stats, what, name);
            sr_framebuffer_destroy(&fb);
        }
    }
}

/* The vector loops against the scalar loop on a scene that draws at least
 * a quarter of the framebuffer's pixels. */
static void assert_vector_loops_match_scalar(const sr_draw_desc *desc, bool reversed, const char *what)
{
    sr_framebuffer scalar;
    sr_stats scalar_stats;
    draw_scalar(desc, reversed, &scalar, &scalar_stats, what);
    cr_assert_gt(scalar_stats.fragments, (uint64_t)FB_SIDE * FB_SIDE / 4, "%s: too little drawn to compare", what);
    assert_vector_loops_match(desc, reversed, &scalar, &scalar_stats, what);
    sr_framebuffer_destroy(&scalar);
}

/* A perspective camera, or with ortho_height > 0 an orthographic one. */
static void look_ortho(sr_draw_desc *desc, const float e[6], float fov, float ortho_height, bool reversed)
{
    sr_camera cam = scene_camera(e[0], e[1], e[2], e[3], e[4], e[5], fov, SR_CAMERA_NEAR, SR_CAMERA_FAR);
    cam.reversed_z = reversed;
    cam.ortho_height = ortho_height;
    scene_camera_desc(desc, &cam, FB_SIDE, FB_SIDE);
}

static void look(sr_draw_desc *desc, const float e[6], float fov, bool reversed)
{
    sr_camera cam = scene_camera(e[0], e[1], e[2], e[3], e[4], e[5], fov, SR_CAMERA_NEAR, SR_CAMERA_FAR);
    cam.reversed_z = reversed;
    scene_camera_desc(desc, &cam, FB_SIDE, FB_SIDE);
}

/* Every layout the vertex stage makes (each mode, lambert with a texture,
 * vertex colors or neither) has a kernel, so no drawable scene silently
 * falls back to the scalar loop. */
Test(simd, every_mode_and_varying_layout_has_a_kernel)
{
    sr_mesh mesh = { .normals = (vec3[1]){ { 0 } }, .uvs = (vec2[1]){ { 0 } }, .colors = (vec3[1]){ { 0 } } };
    for (int mode = 0; mode < SR_SHADE_COUNT; mode++) {
        for (int albedo = 0; albedo < 3; albedo++) {
            sr_mesh m = mesh;
            m.colors = albedo == 2 ? NULL : m.colors;
            sr_shade_context l = { .layout = sr_vertex_layout((sr_shade)mode, &m, albedo == 0) };
            for (int k = 0; k < 4; k++) {
                bool greater = k & 1, ids = k & 2;
                cr_assert_not_null(sr_span_kernel_sse2((sr_shade)mode, greater, ids, &l),
                                   "no 4-lane kernel for mode %d, albedo case %d (%d varyings), ids %d", mode,
                                   albedo, l.layout.count, ids);
                cr_assert(sr_raster_simd_resolve(SR_SIMD_AVX2) != SR_SIMD_AVX2 ||
                              sr_span_kernel_avx2((sr_shade)mode, greater, ids, &l),
                          "no AVX2 kernel for mode %d, albedo case %d, ids %d", mode, albedo, ids);
                cr_assert(sr_raster_simd_resolve(SR_SIMD_AVX512) != SR_SIMD_AVX512 ||
                              sr_span_kernel_avx512((sr_shade)mode, greater, ids, &l),
                          "no AVX-512 kernel for mode %d, albedo case %d, ids %d", mode, albedo, ids);
            }
        }
    }
}

/* AUTO is the best loop the CPU has; one asked for that it lacks falls back
 * to the best below it, never above. */
Test(simd, auto_picks_the_best_loop_the_cpu_has)
{
    cr_assert_eq(sr_raster_simd_resolve(SR_SIMD_SCALAR), SR_SIMD_SCALAR);
    cr_assert_eq(sr_raster_simd_resolve(SR_SIMD_SSE2), SR_SIMD_SSE2);
#if defined(__x86_64__)
    bool avx512 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("avx512f") &&
                  __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
                  __builtin_cpu_supports("avx512vl");
    sr_simd best = avx512 ? SR_SIMD_AVX512 : __builtin_cpu_supports("avx2") ? SR_SIMD_AVX2 : SR_SIMD_SSE2;
#else
    sr_simd best = SR_SIMD_SSE2;
#endif
    cr_assert_eq(sr_raster_simd_resolve(SR_SIMD_AUTO), best, "AUTO gave %s, the CPU's best is %s",
                 sr_simd_name(sr_raster_simd_resolve(SR_SIMD_AUTO)), sr_simd_name(best));
    for (int s = SR_SIMD_SCALAR; s < SR_SIMD_COUNT; s++)
        cr_assert_eq(sr_raster_simd_resolve((sr_simd)s), s <= (int)best ? (sr_simd)s : best, "%s",
                     sr_simd_name((sr_simd)s));
}

Test(simd, random_triangles_match_the_scalar_loop_in_every_mode)
{
    static const uint32_t texels[15] = { 0xFF0000, 0x00FF00, 0x0000FF, 0xFFFFFF, 0x000000, 0x808080, 0x123456, 0xABCDEF,
                                         0xFEDCBA, 0x010203, 0x7F7F7F, 0x80FF00, 0x00FF80, 0xFF0080, 0x3C3C3C };
    static const uint32_t one_texel = 0xC0FFEE;
    sr_texture tex = { .width = 5, .height = 3, .texels = (uint32_t *)texels };
    sr_texture tiny = { .width = 1, .height = 1, .texels = (uint32_t *)&one_texel };
    sr_mesh soup;
    soup_make(&soup, SOUP_TRIANGLES, false, 0.0);
    const struct {
        sr_shade shade;
        sr_filter filter;
        const sr_texture *texture;
    } modes[] = {
        { SR_SHADE_ID, 0, NULL },      { SR_SHADE_DEPTH, 0, NULL },   { SR_SHADE_COLOR, 0, NULL },
        { SR_SHADE_NORMAL, 0, NULL },  { SR_SHADE_LAMBERT, 0, NULL }, { SR_SHADE_LAMBERT, SR_FILTER_BILINEAR, &tex },
        { SR_SHADE_LAMBERT, SR_FILTER_NEAREST, &tex },  { SR_SHADE_LAMBERT, SR_FILTER_BILINEAR, &tiny },
        { SR_SHADE_LAMBERT, SR_FILTER_NEAREST, &tiny }, { SR_SHADE_TEXTURE, SR_FILTER_BILINEAR, &tex },
        { SR_SHADE_TEXTURE, SR_FILTER_NEAREST, &tex },
        { SR_SHADE_TEXTURE, SR_FILTER_BILINEAR, &tiny }, { SR_SHADE_TEXTURE, SR_FILTER_NEAREST, &tiny },
    };
    for (size_t m = 0; m < sizeof modes / sizeof *modes; m++) {
        /* raw both depth conventions, sRGB one (the depth test is the same code) */
        for (int run = 0; run < 3; run++) {
            bool reversed = run == 1, srgb = run == 2;
            sr_draw_desc desc = { .mesh = &soup, .shade = modes[m].shade, .filter = modes[m].filter,
                                  .texture = modes[m].texture, .cull = SR_CULL_NONE,
                                  .color_space = srgb ? SR_COLOR_SRGB : SR_COLOR_RAW };
            look(&desc, (const float[6]){ 0, 0, 0, 0, 0, 1 }, 90.0f, reversed);
            char what[80];
            snprintf(what, sizeof what, "mode %d filter %d texture %dx%d%s%s", modes[m].shade, modes[m].filter,
                     modes[m].texture ? modes[m].texture->width : 0, modes[m].texture ? modes[m].texture->height : 0,
                     reversed ? " reversed" : "", srgb ? " srgb" : "");
            assert_vector_loops_match_scalar(&desc, reversed, what);
        }
    }
    sr_mesh_free(&soup);
}

/* Textures 1 to 4 texels wide and 1 to 3 high, whose texels carry junk in
 * their unused top byte, bilinear, in texture and lambert shading: under the
 * random uvs many lanes wrap (x0 = width − 1, x1 = 0; the same for rows);
 * under an orthographic camera, triangles of one uv each put every pixel
 * exactly on a seam: u or v at 0, −0, 1, just below 1, and half a texel in
 * from either edge. */
Test(simd, bilinear_seams_and_narrow_textures_match_the_scalar_loop)
{
    static const uint32_t texels[12] = { 0xFFFF0000, 0x0100FF00, 0x800000FF, 0x7FFFFFFF, 0x00000000, 0xC0808080,
                                         0x12123456, 0xABABCDEF, 0x55FEDCBA, 0xEE010203, 0x407F7F7F, 0x0280FF00 };
    sr_mesh soup, seams;
    soup_make(&soup, SOUP_TRIANGLES, false, 0.0);
    soup_make(&seams, SOUP_TRIANGLES, false, 0.0);
    for (int w = 1; w <= 4; w++) {
        for (int h = 1; h <= 3; h++) {
            sr_texture tex = { .width = w, .height = h, .texels = (uint32_t *)texels };
            const float seam[] = { 0.0f, -0.0f, 1.0f, nextafterf(1.0f, 0.0f), 0.5f / (float)w, 1.0f - 0.5f / (float)w,
                                   0.5f / (float)h, 1.0f - 0.5f / (float)h };
            const int seam_count = (int)(sizeof seam / sizeof *seam);
            for (uint32_t i = 0; i < seams.vertex_count; i++) {
                uint32_t t = i / 3;
                seams.uvs[i][0] = seam[t % seam_count];
                seams.uvs[i][1] = seam[t / seam_count % seam_count];
            }
            const struct {
                const sr_mesh *mesh;
                sr_shade shade;
                float ortho_height;
            } draws[] = { { &soup, SR_SHADE_TEXTURE, 0.0f },
                          { &soup, SR_SHADE_LAMBERT, 0.0f },
                          { &seams, SR_SHADE_TEXTURE, 12.0f },
                          { &seams, SR_SHADE_LAMBERT, 12.0f } };
            for (size_t d = 0; d < sizeof draws / sizeof *draws; d++) {
                sr_draw_desc desc = { .mesh = draws[d].mesh, .shade = draws[d].shade, .texture = &tex,
                                      .filter = SR_FILTER_BILINEAR, .cull = SR_CULL_NONE };
                look_ortho(&desc, (const float[6]){ 0, 0, 0, 0, 0, 1 }, 90.0f, draws[d].ortho_height, false);
                char what[64];
                snprintf(what, sizeof what, "texture %dx%d, mode %d, %s uvs", w, h, draws[d].shade,
                         draws[d].mesh == &soup ? "random" : "seam");
                assert_vector_loops_match_scalar(&desc, false, what);
            }
        }
    }
    sr_mesh_free(&seams);
    sr_mesh_free(&soup);
}

/* Narrow triangles, 1 to about 24 pixels wide: the scalar loop tests each
 * pixel of a box narrower than its span threshold, the kernels take boxes
 * from SR_SIMD_MIN_WIDTH up (triangle_setup.h), so both thresholds are crossed, and
 * the vector loops defer the shading of tiny boxes to the tiny queue in
 * every mode with varyings (tiny_queue.h, sr_tiny_queue). */
Test(simd, narrow_triangles_match_the_scalar_loop)
{
    static const uint32_t texels[6] = { 0xFF0000, 0x00FF00, 0x0000FF, 0xFFFFFF, 0x123456, 0xABCDEF };
    sr_texture tex = { .width = 3, .height = 2, .texels = (uint32_t *)texels };
    sr_mesh soup;
    soup_make(&soup, NARROW_SOUP_TRIANGLES, false, 0.15);
    sr_mesh gray = soup; /* lambert of no vertex colors: gray */
    gray.colors = NULL;
    static const struct {
        sr_shade shade;
        bool textured, gray;
        sr_filter filter;
    } modes[] = { { SR_SHADE_DEPTH, false, false, 0 },
                  { SR_SHADE_NORMAL, false, false, 0 },
                  { SR_SHADE_LAMBERT, false, false, 0 },
                  { SR_SHADE_LAMBERT, false, true, 0 },
                  { SR_SHADE_COLOR, false, false, 0 },
                  { SR_SHADE_TEXTURE, true, false, SR_FILTER_BILINEAR },
                  { SR_SHADE_TEXTURE, true, false, SR_FILTER_NEAREST },
                  { SR_SHADE_LAMBERT, true, false, SR_FILTER_BILINEAR } };
    for (size_t m = 0; m < sizeof modes / sizeof *modes; m++) {
        for (int reversed = 0; reversed < 2; reversed++) {
            sr_draw_desc desc = { .mesh = modes[m].gray ? &gray : &soup, .shade = modes[m].shade,
                                  .cull = SR_CULL_NONE, .texture = modes[m].textured ? &tex : NULL,
                                  .filter = modes[m].filter };
            look(&desc, (const float[6]){ 0, 0, 0, 0, 0, 1 }, 90.0f, reversed);
            char what[80];
            snprintf(what, sizeof what, "narrow triangles, mode %d%s%s filter %d%s", modes[m].shade,
                     modes[m].gray ? " gray" : "", modes[m].textured ? " textured" : "", modes[m].filter,
                     reversed ? " reversed" : "");
            assert_vector_loops_match_scalar(&desc, reversed, what);
        }
    }
    sr_mesh_free(&soup);
}

/* Slivers: the narrow soup squeezed to a fifth of its width and a
 * twentieth of its depth about each triangle's first vertex, so every box
 * is under the kernels' 8 columns and many have more rows than a tiny box
 * holds (up to about 24). Such a
 * box takes a kernel: in depth shading, which queues no tiny triangle,
 * the vector loops' calls (asserted) are theirs alone. */
Test(simd, tall_slivers_take_the_kernels_and_match_the_scalar_loop)
{
    sr_mesh slivers;
    soup_make(&slivers, NARROW_SOUP_TRIANGLES, false, 0.15);
    for (uint32_t i = 0; i < slivers.vertex_count; i++)
        if (i % 3 > 0) {
            const float *first = slivers.positions[i - i % 3];
            slivers.positions[i][0] = first[0] + 0.2f * (slivers.positions[i][0] - first[0]);
            /* nearly its depth: a farther x would land columns apart */
            slivers.positions[i][2] = first[2] + 0.05f * (slivers.positions[i][2] - first[2]);
        }
    static const sr_shade modes[] = { SR_SHADE_DEPTH, SR_SHADE_LAMBERT };
    for (size_t m = 0; m < sizeof modes / sizeof *modes; m++)
        for (int reversed = 0; reversed < 2; reversed++) {
            sr_draw_desc desc = { .mesh = &slivers, .shade = modes[m], .cull = SR_CULL_NONE };
            look(&desc, (const float[6]){ 0, 0, 0, 0, 0, 1 }, 90.0f, reversed);
            char what[64];
            snprintf(what, sizeof what, "tall slivers, mode %d%s", modes[m], reversed ? " reversed" : "");
            assert_vector_loops_match_scalar(&desc, reversed, what);
        }
    sr_mesh_free(&slivers);
}

/* A tilted grid of quads 4 to 7 pixels on a side (depth 1.7 to 3.3), each
 * two triangles of about 12 pixels that all pass the depth test: the tiny
 * queue fills by its pixels (448) long before its triangles (128) and is
 * shaded then, as the scalar loop shades them. */
#define GRID_QUADS 26
Test(simd, tiny_boxes_of_many_pixels_match_the_scalar_loop)
{
    sr_mesh grid;
    sr_error err;
    uint32_t side = GRID_QUADS + 1;
    cr_assert(sr_mesh_alloc(&grid, side * side, 6 * GRID_QUADS * GRID_QUADS, true, false, true, &err), "%s",
              err.message);
    test_rng rng = { SOUP_SEED };
    for (uint32_t r = 0; r < side; r++)
        for (uint32_t c = 0; c < side; c++) {
            uint32_t i = r * side + c;
            float x = -2.0f + 4.0f * (float)c / GRID_QUADS, y = -2.0f + 4.0f * (float)r / GRID_QUADS;
            glm_vec3_copy((vec3){ x, y, 2.5f + 0.4f * x }, grid.positions[i]); /* tilted: 1/w varies */
            for (int k = 0; k < 3; k++) {
                grid.normals[i][k] = (float)rng_uniform(&rng, -1.0, 1.0);
                grid.colors[i][k] = (float)rng_uniform(&rng, 0.0, 1.0);
            }
        }
    uint32_t *idx = grid.indices;
    for (uint32_t r = 0; r < GRID_QUADS; r++)
        for (uint32_t c = 0; c < GRID_QUADS; c++) {
            uint32_t v = r * side + c;
            const uint32_t quad[6] = { v, v + 1, v + side, v + 1, v + side + 1, v + side };
            memcpy(idx, quad, sizeof quad);
            idx += 6;
        }
    sr_draw_desc desc = { .mesh = &grid, .shade = SR_SHADE_LAMBERT, .cull = SR_CULL_NONE };
    look(&desc, (const float[6]){ 0, 0, 0, 0, 0, 1 }, 90.0f, false);
    assert_vector_loops_match_scalar(&desc, false, "tiny boxes of many pixels");
    sr_mesh_free(&grid);
}

/* Tiny triangles stacked over the same few pixels at random depths (each
 * about 3 pixels, sloped in depth), in both depth conventions, gray and
 * with vertex colors: in the tiny queue, pixels that pass and fail their
 * depth tests alternate within one queue, and triangles left with no
 * pixel between ones with some; each vector loop, on one thread and on
 * tiles, must test them in submission order and shade the survivors with
 * their own triangles' interpolants, as the scalar loop does one triangle
 * at a time. */
#define STACKED_TINY 600
Test(simd, a_stack_of_tiny_triangles_is_depth_tested_in_submission_order)
{
    sr_mesh stack;
    sr_error err;
    cr_assert(sr_mesh_alloc(&stack, 3 * STACKED_TINY, 3 * STACKED_TINY, true, false, true, &err), "%s",
              err.message);
    test_rng rng = { SOUP_SEED };
    static const float corner[3][2] = { { 0.0f, 0.0f }, { 0.04f, 0.005f }, { 0.008f, 0.04f } };
    for (uint32_t i = 0; i < stack.vertex_count; i++) {
        if (i % 3 == 0)
            stack.positions[i][2] = (float)rng_uniform(&rng, 1.5, 4.0);
        float depth = stack.positions[i - i % 3][2] * (float)rng_uniform(&rng, 0.97, 1.03);
        for (int k = 0; k < 2; k++)
            stack.positions[i][k] = (corner[i % 3][k] + (float)rng_uniform(&rng, -0.01, 0.01)) * depth;
        stack.positions[i][2] = depth;
        for (int k = 0; k < 3; k++) {
            stack.normals[i][k] = (float)rng_uniform(&rng, -1.0, 1.0);
            stack.colors[i][k] = (float)rng_uniform(&rng, 0.0, 1.0);
        }
        stack.indices[i] = i;
    }
    sr_mesh gray = stack;
    gray.colors = NULL;
    const sr_mesh *meshes[2] = { &gray, &stack };
    for (int m = 0; m < 2; m++)
        for (int reversed = 0; reversed < 2; reversed++) {
            sr_draw_desc desc = { .mesh = meshes[m], .shade = SR_SHADE_LAMBERT, .cull = SR_CULL_NONE };
            look(&desc, (const float[6]){ 0, 0, 0, 0, 0, 1 }, 90.0f, reversed);
            sr_framebuffer scalar;
            sr_stats scalar_stats;
            const char *what = m ? "colored stack" : "gray stack";
            draw_scalar(&desc, reversed, &scalar, &scalar_stats, what);
            /* A pixel under k of the triangles, in random depth order, passes
             * about ln k + 0.58 times: about 6 at the centre, once or twice
             * at the edges; most triangles pass nowhere. */
            size_t covered = 0, n = scene_pixel_count(&scalar);
            for (size_t i = 0; i < n; i++)
                covered += scalar.color[i] != 0x123456u;
            cr_assert(covered >= 4 && scalar_stats.fragments >= 2 * covered &&
                          scalar_stats.fragments <= 20 * covered,
                      "%zu pixels covered, %llu fragments: not a stack", covered,
                      (unsigned long long)scalar_stats.fragments);
            assert_vector_loops_match(&desc, reversed, &scalar, &scalar_stats, what);
            sr_framebuffer_destroy(&scalar);
        }
    sr_mesh_free(&stack);
}

/* Two draws of tiny triangles into one framebuffer, in the same mode
 * with two varying layouts (gray lambert, then lambert of the vertex
 * colors), against the scalar loop after each draw: a draw's tiny
 * triangles are all shaded, with its own layout, when it returns (the
 * tiny queue is one per thread and outlives a draw). */
static void draw_into(sr_framebuffer *fb, const sr_mesh *mesh, sr_simd simd, float eye_z)
{
    sr_error err;
    sr_workspace *ws = sr_workspace_create();
    cr_assert_not_null(ws);
    sr_draw_desc desc = { .mesh = mesh, .shade = SR_SHADE_LAMBERT, .cull = SR_CULL_NONE, .workspace = ws,
                          .study = &(sr_draw_study){ .simd = simd, .path = SR_PATH_DIRECT } };
    look(&desc, (const float[6]){ 0, 0, eye_z, 0, 0, 1 }, 90.0f, false);
    cr_assert(sr_draw(fb, &desc, NULL, &err), "%s", err.message);
    /* Every box is tiny here: the vector loops' draws are the queue's. */
    if (simd == SR_SIMD_SCALAR)
        cr_assert_eq(sr_workspace_simd_draws(ws), 0u, "the scalar loop used the tiny queue");
    else
        cr_assert_gt(sr_workspace_simd_draws(ws), 0u, "the tiny queue never shaded");
    sr_workspace_destroy(ws);
}

Test(simd, consecutive_draws_shade_their_own_tiny_triangles)
{
    sr_mesh soup;
    soup_make(&soup, NARROW_SOUP_TRIANGLES, false, TINY_REACH);
    sr_mesh gray = soup;
    gray.colors = NULL;
    const sr_mesh *meshes[2] = { &gray, &soup };
    for (size_t v = 0; v < sizeof vector_loops / sizeof *vector_loops; v++) {
        const char *name = sr_simd_name(sr_raster_simd_resolve(vector_loops[v]));
        sr_framebuffer want, fb;
        scene_fb_make(&want, FB_SIDE, FB_SIDE);
        scene_fb_make(&fb, FB_SIDE, FB_SIDE);
        sr_framebuffer_clear(&want, 0x123456);
        sr_framebuffer_clear(&fb, 0x123456);
        size_t n = scene_pixel_count(&want);
        uint32_t *first = malloc(n * sizeof *first);
        cr_assert_not_null(first);
        for (int d = 0; d < 2; d++) {
            draw_into(&want, meshes[d], SR_SIMD_SCALAR, -0.1f * (float)d);
            draw_into(&fb, meshes[d], vector_loops[v], -0.1f * (float)d);
            cr_assert_eq(memcmp(fb.color, want.color, n * sizeof *fb.color), 0, "%s, draw %d: colors differ", name, d);
            cr_assert_eq(memcmp(fb.depth, want.depth, n * sizeof *fb.depth), 0, "%s, draw %d: depths differ", name, d);
            if (d == 0)
                memcpy(first, want.color, n * sizeof *first);
        }
        size_t changed = 0;
        for (size_t i = 0; i < n; i++)
            changed += first[i] != want.color[i];
        cr_assert_gt(changed, n / 64, "the second draw changed only %zu pixels", changed);
        free(first);
        sr_framebuffer_destroy(&fb);
        sr_framebuffer_destroy(&want);
    }
    sr_mesh_free(&soup);
}

/* One shading context used for two tiny triangles, its layout changed
 * between them (gray lambert, then lambert of the vertex colors): the
 * second is shaded with the new layout, as the scalar loop shades it,
 * though the queue sees the same context, framebuffer and mode. */
static void draw_tiny_twice(sr_simd simd, sr_framebuffer *fb)
{
    sr_shade_context c = { .layout = { .count = 3, .normal = 0, .color = -1, .uv = -1 },
                           .light_dir = { 0.0f, 0.6f, 0.8f }, .simd = simd, .albedo = { 0.8f, 0.8f, 0.8f },
                           .tint = { 1.0f, 1.0f, 1.0f } };
    const float inv_w[3] = { 1.0f, 0.75f, 0.5f };
    sr_screen_vertex tri[3];
    for (int k = 0; k < 3; k++) {
        tri[k] = (sr_screen_vertex){ .x = (int64_t)((k == 1 ? 5 : 1) << SR_SUBPIXEL_BITS),
                                     .y = (int64_t)((k == 2 ? 5 : 1) << SR_SUBPIXEL_BITS), .z = 0.5f,
                                     .inv_w = inv_w[k] };
        const float var[6] = { 0.2f * (float)k, 0.5f, 1.0f, 1.0f, 0.25f * (float)k, 0.5f };
        for (int i = 0; i < 6; i++)
            tri[k].var_w[i] = var[i] * inv_w[k];
    }
    sr_raster_rect rect = { 0, 0, fb->width, fb->height };
    int64_t area2 = sr_cull_area2(&tri[0], &tri[1], &tri[2]);
    cr_assert_gt(sr_raster_triangle(fb, rect, SR_SUBPIXEL_BITS, SR_SHADE_LAMBERT, &c, tri, area2, 0), 0u);
    c.layout = (sr_varying_layout){ .count = 6, .normal = 0, .color = 3, .uv = -1 };
    for (int k = 0; k < 3; k++)
        tri[k].z = 0.25f; /* in front of the first */
    cr_assert_gt(sr_raster_triangle(fb, rect, SR_SUBPIXEL_BITS, SR_SHADE_LAMBERT, &c, tri, area2, 0), 0u);
}

Test(simd, a_context_used_again_is_shaded_with_its_new_layout)
{
    sr_framebuffer want;
    scene_fb_make(&want, 8, 8);
    sr_framebuffer_clear(&want, 0);
    draw_tiny_twice(SR_SIMD_SCALAR, &want);
    size_t n = scene_pixel_count(&want), gray = 0;
    for (size_t i = 0; i < n; i++) {
        uint32_t p = want.color[i];
        gray += p != 0 && (p >> 16 & 0xFF) == (p >> 8 & 0xFF) && (p >> 8 & 0xFF) == (p & 0xFF);
    }
    cr_assert_eq(gray, 0u, "a pixel of the second triangle is gray: the colors did not reach it");
    for (size_t v = 0; v < sizeof vector_loops / sizeof *vector_loops; v++) {
        sr_framebuffer fb;
        scene_fb_make(&fb, 8, 8);
        sr_framebuffer_clear(&fb, 0);
        draw_tiny_twice(vector_loops[v], &fb);
        cr_assert_eq(memcmp(fb.color, want.color, n * sizeof *fb.color), 0, "%s: colors differ",
                     sr_simd_name(sr_raster_simd_resolve(vector_loops[v])));
        sr_framebuffer_destroy(&fb);
    }
    sr_framebuffer_destroy(&want);
}

Test(simd, the_textured_room_through_its_walls_matches_the_scalar_loop)
{
    sr_mesh room;
    sr_texture tex;
    sr_error err;
    cr_assert(sr_obj_load(&room, "assets/room.obj", &err), "%s", err.message);
    cr_assert(sr_texture_load(&tex, "assets/room.png", &err), "%s", err.message);
    static float eyes[][6] = { { -8, 3, -8, 4, 1.5f, 6 }, { -10, 2, 0.3f, 10, 2, 0.3f }, { 2, 5.9f, 2, 2, 0, 2.001f } };
    for (size_t i = 0; i < sizeof eyes / sizeof *eyes; i++) {
        sr_draw_desc desc = { .mesh = &room, .shade = SR_SHADE_LAMBERT, .texture = &tex };
        look(&desc, eyes[i], 75.0f, false);
        assert_vector_loops_match_scalar(&desc, false, "room");
    }
    sr_texture_free(&tex);
    sr_mesh_free(&room);
}

/* The per-triangle shortcuts (sr_interp): constant 1/w under an orthographic
 * camera, and a flat normal there and under a perspective camera, against
 * the scalar loop taking the same shortcuts, in every mode that reads
 * varyings. */
Test(simd, flat_normals_and_orthographic_triangles_match_the_scalar_loop)
{
    static const uint32_t texels[6] = { 0xFF0000, 0x00FF00, 0x0000FF, 0xFFFFFF, 0x123456, 0xABCDEF };
    sr_texture tex = { .width = 3, .height = 2, .texels = (uint32_t *)texels };
    sr_mesh soup, no_colors;
    soup_make(&soup, SOUP_TRIANGLES, true, 0.0);
    no_colors = soup;
    no_colors.colors = NULL;
    const struct {
        sr_shade shade;
        const sr_mesh *mesh;
        const sr_texture *texture;
    } modes[] = {
        { SR_SHADE_LAMBERT, &no_colors, NULL }, { SR_SHADE_LAMBERT, &soup, NULL }, { SR_SHADE_LAMBERT, &soup, &tex },
        { SR_SHADE_NORMAL, &soup, NULL },       { SR_SHADE_COLOR, &soup, NULL },   { SR_SHADE_TEXTURE, &soup, &tex },
    };
    for (size_t m = 0; m < sizeof modes / sizeof *modes; m++) {
        for (int ortho = 0; ortho < 2; ortho++) {
            for (int reversed = 0; reversed < 2; reversed++) {
                sr_draw_desc desc = { .mesh = modes[m].mesh, .shade = modes[m].shade, .texture = modes[m].texture,
                                      .filter = SR_FILTER_BILINEAR, .cull = SR_CULL_NONE };
                look_ortho(&desc, (const float[6]){ 0, 0, 0, 0, 0, 1 }, 90.0f, ortho ? 12.0f : 0.0f, reversed);
                char what[64];
                snprintf(what, sizeof what, "flat normals, mode %d%s%s%s", modes[m].shade,
                         modes[m].mesh->colors ? "" : " no colors", ortho ? " orthographic" : "",
                         reversed ? " reversed" : "");
                assert_vector_loops_match_scalar(&desc, reversed, what);
            }
        }
    }
    sr_mesh_free(&soup);
}

/* The set-up of a triangle of width × height / 2 pixels (its corners at
 * (0, 0), (width, 0), (0, height)) seen in perspective, 1/w differing at
 * its corners: its varyings are var_w (normal/w, or color/w), drawn in
 * `mode` with `layout`, lit from straight ahead. */
static sr_tri_setup perspective_setup(const float var_w[3][3], const float inv_w[3], int width, int height,
                                      sr_varying_layout layout, sr_shade mode)
{
    const int64_t xy[3][2] = { { 0, 0 }, { width, 0 }, { 0, height } };
    sr_screen_vertex v[3];
    for (int i = 0; i < 3; i++) {
        v[i] = (sr_screen_vertex){ .x = xy[i][0] << SR_SUBPIXEL_BITS, .y = xy[i][1] << SR_SUBPIXEL_BITS,
                                   .z = 0.5f, .inv_w = inv_w[i] };
        memcpy(v[i].var_w, var_w[i], 3 * sizeof(float));
    }
    const sr_screen_vertex *tri[3] = { &v[0], &v[1], &v[2] };
    sr_shade_context c = { .layout = layout, .light_dir = { 0.0f, 0.0f, -1.0f } };
    sr_raster_rect box = sr_raster_scan_box_of(tri, (sr_raster_rect){ 0, 0, 128, 128 }, SR_SUBPIXEL_BITS);
    sr_tri_setup s;
    cr_assert(sr_raster_setup(tri, sr_cull_area2(tri[0], tri[1], tri[2]), box, SR_SUBPIXEL_BITS, mode, &c, &s));
    return s;
}

static const sr_varying_layout NORMAL_ONLY = { .count = 3, .color = -1, .uv = -1, .normal = 0 };

/* Gray lambert with normals n[i] at the corners, as the vertex stage makes
 * the varyings: normal · 1/w. */
static sr_tri_setup lambert_setup(const float n[3][3], const float inv_w[3], int width, int height)
{
    float var_w[3][3];
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++)
            var_w[i][k] = n[i][k] * inv_w[i];
    return perspective_setup(var_w, inv_w, width, height, NORMAL_ONLY, SR_SHADE_LAMBERT);
}

/* N0 turned by `angle` radians about x. */
static void turned_normal(double angle, float out[3])
{
    double a = atan2(0.6, 0.8) + angle;
    out[0] = 0.0f;
    out[1] = (float)sin(a);
    out[2] = (float)-cos(a);
}

static const float N0[3] = { 0.0f, 0.6f, -0.8f };
static const float INV_W[3] = { 0.5f, 0.25f, 3.0f };

/* Normals that point one way, whatever their lengths and up to rounding,
 * light a triangle of 32 pixels or more once, with the unit normal's
 * intensity (made unit in double: here normal/w squared overflows a
 * float); normals 2^-18 radians apart or opposite are lit per pixel, and
 * so is a triangle of 31 pixels. */
Test(simd, perspective_flat_normals_are_lit_once)
{
    /* From the formula in double, lit from straight ahead (the set-up's light). */
    float want = (float)scene_lambert((const double[3]){ N0[0], N0[1], N0[2] }, (const double[3]){ 0.0, 0.0, -1.0 });
    cr_assert_gt(want, SCENE_LAMBERT_AMBIENT + 0.5, "the light must reach the normal for the test to tell");
    float near[3], apart[3];
    turned_normal(0x1p-22, near);
    turned_normal(0x1p-18, apart);
    const float longer[3] = { 0.0f, 1.5f, -2.0f }, opposite[3] = { 0.0f, -0.6f, 0.8f };
    sr_tri_setup s = lambert_setup((const float[3][3]){ { N0[0], N0[1], N0[2] }, { longer[0], longer[1], longer[2] },
                                                        { near[0], near[1], near[2] } },
                                   INV_W, 40, 30);
    cr_assert_eq(s.interp, SR_INTERP_PERSPECTIVE_FLAT_NORMAL, "normals 2^-22 apart, one longer");
    cr_assert_float_eq(s.lambert, want, 1e-6f, "lit once with %.9g, the normal's intensity is %.9g", s.lambert, want);
    s = lambert_setup((const float[3][3]){ { N0[0], N0[1], N0[2] }, { N0[0], N0[1], N0[2] }, { N0[0], N0[1], N0[2] } },
                      (const float[3]){ 1e25f, 0.25f, 3.0f }, 40, 30);
    cr_assert_eq(s.interp, SR_INTERP_PERSPECTIVE_FLAT_NORMAL, "1/w of 1e25 at a corner");
    cr_assert_float_eq(s.lambert, want, 1e-6f, "1/w of 1e25 at a corner: %.9g, not %.9g", s.lambert, want);
    s = lambert_setup((const float[3][3]){ { N0[0], N0[1], N0[2] }, { N0[0], N0[1], N0[2] },
                                           { apart[0], apart[1], apart[2] } },
                      INV_W, 40, 30);
    cr_assert_eq(s.interp, SR_INTERP_PERSPECTIVE, "normals 2^-18 apart");
    s = lambert_setup((const float[3][3]){ { N0[0], N0[1], N0[2] }, { opposite[0], opposite[1], opposite[2] },
                                           { N0[0], N0[1], N0[2] } },
                      INV_W, 40, 30);
    cr_assert_eq(s.interp, SR_INTERP_PERSPECTIVE, "opposite normals");
    const float same[3][3] = { { N0[0], N0[1], N0[2] }, { N0[0], N0[1], N0[2] }, { N0[0], N0[1], N0[2] } };
    cr_assert_eq(lambert_setup(same, INV_W, 64, 1).interp, SR_INTERP_PERSPECTIVE_FLAT_NORMAL, "32 pixels");
    cr_assert_eq(lambert_setup(same, INV_W, 62, 1).interp, SR_INTERP_PERSPECTIVE, "31 pixels");
}

/* A layout without a normal (color shading) in perspective is never lit
 * as a flat normal, in color or lambert mode: its varyings are parallel at
 * the three corners, and so would be a "normal" read from varying −1 on
 * (inv_w, the float before var_w), so a set-up that looked for a normal
 * where the layout has none would take them for a flat one. (The fuzzer
 * found the first version forming the pointer to varying −1 before it
 * checked the layout, which clang's UBSan reports and GCC's does not:
 * fuzz/regressions/draw/perspective_flat_normal_of_no_normal.) */
Test(simd, perspective_color_has_no_normal_to_test)
{
    const float color_w[3][3] = { { 0.1f, 0.2f, 0.7f }, { 0.05f, 0.1f, 0.9f }, { 0.3f, 0.6f, 0.2f } };
    const sr_varying_layout color_only = { .count = 3, .color = 0, .uv = -1, .normal = -1 };
    const sr_shade modes[] = { SR_SHADE_COLOR, SR_SHADE_LAMBERT };
    for (size_t m = 0; m < sizeof modes / sizeof *modes; m++)
        cr_assert_eq(perspective_setup(color_w, (const float[3]){ 0.5f, 0.25f, 1.5f }, 40, 30, color_only, modes[m])
                         .interp,
                     SR_INTERP_PERSPECTIVE, "mode %d", modes[m]);
}

/* Gray lambert quads facing an orthographic camera come out one color per
 * quad, the intensity of their normal, in every loop and on tiles: the
 * per-triangle intensity is the value the per-pixel one would have been. */
Test(simd, orthographic_flat_lambert_is_the_intensity_of_the_normal)
{
    sr_mesh quads;
    sr_error err;
    cr_assert(sr_shape_quads(&quads, 3, 4.0f, 3.0f, -0.5f, &err), "%s", err.message);
    /* From the formula in double, rounded to 8 bits as the shader's contract says. */
    double k = scene_lambert((const double[3]){ 0.0, 0.0, -1.0 }, (const double[3]){ 0.6, 0.0, -0.8 });
    uint32_t want = scene_rgb(k * SCENE_LAMBERT_GRAY, k * SCENE_LAMBERT_GRAY, k * SCENE_LAMBERT_GRAY);
    sr_draw_desc desc = { .mesh = &quads, .shade = SR_SHADE_LAMBERT, .light_dir = { 0.6f, 0.0f, -0.8f } };
    look_ortho(&desc, (const float[6]){ 0, 0, 0, 0, 0, 1 }, 90.0f, 2.0f, false);
    const sr_simd loops[] = { SR_SIMD_SCALAR, SR_SIMD_SSE2, SR_SIMD_AVX2, SR_SIMD_AVX512 };
    for (size_t i = 0; i < sizeof loops / sizeof *loops; i++) {
        for (int threads = 1; threads <= TILED_THREADS; threads += TILED_THREADS - 1) {
            sr_framebuffer fb;
            sr_stats stats;
            draw_with(&desc, loops[i], threads, false, &fb, &stats);
            size_t right = scene_count_color(&fb, want);
            cr_assert_eq(right, scene_pixel_count(&fb), "%s on %d threads: %zu of %zu pixels are 0x%06X",
                         sr_simd_name(sr_raster_simd_resolve(loops[i])), threads, right, scene_pixel_count(&fb), want);
            sr_framebuffer_destroy(&fb);
        }
    }
    sr_mesh_free(&quads);
}

/* sr_workspace_simd_draws counts the last draw alone, whatever the draws
 * before it with the same workspace left in the counts of threads it does
 * not use (a viewer reuses one workspace while its thread count changes;
 * which threads of a tiled draw ran a kernel depends on the scheduler, so
 * the last thread's count is set as such a draw may leave it). */
Test(simd, kernel_calls_are_the_last_draws_alone)
{
    sr_mesh soup;
    soup_make(&soup, SOUP_TRIANGLES, false, 0.0);
    sr_framebuffer fb;
    scene_fb_make(&fb, FB_SIDE, FB_SIDE);
    sr_workspace *ws = sr_workspace_create();
    cr_assert_not_null(ws);
    sr_draw_desc desc = { .mesh = &soup, .shade = SR_SHADE_COLOR, .cull = SR_CULL_NONE, .threads = TILED_THREADS,
                          .workspace = ws, .study = &(sr_draw_study){ .simd = SR_SIMD_SSE2, .path = SR_PATH_TILES } };
    look(&desc, (const float[6]){ 0, 0, 0, 0, 0, 1 }, 90.0f, false);
    sr_error err;
    cr_assert(sr_draw(&fb, &desc, NULL, &err), "%s", err.message);
    cr_assert_gt(sr_workspace_simd_draws(ws), 0u, "the SSE2 loop never ran on %d threads", TILED_THREADS);
    ws->threads[TILED_THREADS - 1].simd_draws = 1;
    desc.threads = 1;
    desc.study = &(sr_draw_study){ .simd = SR_SIMD_SCALAR, .path = SR_PATH_DIRECT };
    cr_assert(sr_draw(&fb, &desc, NULL, &err), "%s", err.message);
    cr_assert_eq(sr_workspace_simd_draws(ws), 0u, "a scalar draw on one thread counts %llu kernel calls",
                 (unsigned long long)sr_workspace_simd_draws(ws));
    sr_workspace_destroy(ws);
    sr_framebuffer_destroy(&fb);
    sr_mesh_free(&soup);
}

/* A mesh with materials (materials.c): every loop, path and thread count
 * shades each part with its own material, bit for bit as the scalar loop
 * does: an untextured colour, a texture untinted and tinted, MASK on a
 * texture with alpha (the bilinear filter lerping alpha; nearest reading
 * it), BLEND drawn as MASK, and a material hidden by its alpha, on large
 * triangles (the span kernels) and narrow ones (the tiny queue, and the
 * tiny loop for MASK); and id, depth, normal and colour shading cut the
 * same holes (the cut triangles on the scalar loop, the others on the
 * kernels and the tiny queue), so every shading writes lambert's depths
 * and counts its fragments, one-pixel triangles included. */
#define MATERIAL_PARTS 6
static void materials_set(sr_mesh *mesh, sr_material materials[MATERIAL_PARTS], sr_mesh_part parts[MATERIAL_PARTS],
                          const sr_texture *tex)
{
    const sr_material table[MATERIAL_PARTS] = {
        { .base_color = { 0.9f, 0.3f, 0.1f, 1.0f } },
        { .base_color = { 1.0f, 1.0f, 1.0f, 1.0f }, .texture = tex },
        { .base_color = { 0.5f, 1.0f, 0.25f, 1.0f }, .texture = tex },
        { .base_color = { 1.0f, 0.7f, 1.0f, 0.9f }, .texture = tex, .alpha_mode = SR_ALPHA_MASK, .alpha_cutoff = 0.4f },
        { .base_color = { 0.2f, 0.9f, 0.6f, 1.0f }, .texture = tex, .alpha_mode = SR_ALPHA_BLEND },
        { .base_color = { 0.3f, 0.3f, 0.9f, 0.1f }, .alpha_mode = SR_ALPHA_MASK, .alpha_cutoff = 0.5f },
    };
    uint32_t slots = sr_mesh_triangle_slots(mesh), per = slots / MATERIAL_PARTS;
    for (uint32_t p = 0; p < MATERIAL_PARTS; p++) {
        materials[p] = table[p];
        /* the parts in another order than the materials, the last taking the rest */
        parts[p] = (sr_mesh_part){ p * per, p + 1 < MATERIAL_PARTS ? per : slots - p * per, (p * 5 + 1) % MATERIAL_PARTS };
    }
    mesh->materials = materials;
    mesh->material_count = MATERIAL_PARTS;
    mesh->parts = parts;
    mesh->part_count = MATERIAL_PARTS;
}

Test(simd, each_part_keeps_its_material_in_every_loop)
{
    /* alpha from 0 to 255 over the texels, across MASK's floors */
    static const uint32_t texels[12] = { 0x00FF0000, 0x2000FF00, 0x400000FF, 0x60FFFFFF, 0x80000000, 0x9F808080,
                                         0xA0123456, 0xB0ABCDEF, 0xC0FEDCBA, 0xE0010203, 0xF07F7F7F, 0xFF80FF00 };
    sr_texture tex = { .width = 4, .height = 3, .texels = (uint32_t *)texels, .alpha = true };
    sr_material materials[MATERIAL_PARTS];
    sr_mesh_part parts[MATERIAL_PARTS];
    sr_mesh wide, narrow;
    soup_make(&wide, SOUP_TRIANGLES, true, 0.0);
    soup_make(&narrow, NARROW_SOUP_TRIANGLES, false, 0.15);
    sr_mesh *meshes[] = { &wide, &narrow };
    size_t pixels = (size_t)FB_SIDE * FB_SIDE;
    float *lit_depth = malloc(2 * 3 * pixels * sizeof *lit_depth); /* lambert's, [filter][run] */
    uint64_t lit_fragments[2][3];
    cr_assert_not_null(lit_depth);
    for (size_t m = 0; m < 2; m++) {
        sr_mesh mesh = *meshes[m];
        materials_set(&mesh, materials, parts, &tex);
        static const sr_shade shades[] = { SR_SHADE_LAMBERT, SR_SHADE_TEXTURE, SR_SHADE_ID,
                                           SR_SHADE_DEPTH,   SR_SHADE_NORMAL,  SR_SHADE_COLOR };
        for (size_t s = 0; s < sizeof shades / sizeof *shades; s++)
            for (int filter = 0; filter < 2; filter++)
                for (int run = 0; run < 3; run++) { /* raw both depth conventions, sRGB one */
                    bool reversed = run == 1, srgb = run == 2;
                    /* vertex colours only where no material has a texture (below), or to draw them */
                    mesh.colors = shades[s] == SR_SHADE_COLOR ? meshes[m]->colors : NULL;
                    sr_draw_desc desc = { .mesh = &mesh, .shade = shades[s], .filter = (sr_filter)filter,
                                          .cull = SR_CULL_NONE, .color_space = srgb ? SR_COLOR_SRGB : SR_COLOR_RAW };
                    look(&desc, (const float[6]){ 0, 0, 0, 0, 0, 1 }, 90.0f, reversed);
                    char what[96];
                    snprintf(what, sizeof what, "materials, %s triangles, mode %d filter %d%s%s",
                             m ? "narrow" : "wide", shades[s], filter, reversed ? " reversed" : "",
                             srgb ? " srgb" : "");
                    sr_framebuffer scalar, rows;
                    sr_stats scalar_stats, rows_stats;
                    draw_scalar(&desc, reversed, &scalar, &scalar_stats, what);
                    cr_assert_gt(scalar_stats.fragments, (uint64_t)FB_SIDE * FB_SIDE / 8, "%s: too little drawn",
                                 what);
                    assert_vector_loops_match(&desc, reversed, &scalar, &scalar_stats, what);
                    float *lit = lit_depth + (size_t)(3 * filter + run) * pixels;
                    if (shades[s] == SR_SHADE_LAMBERT) {
                        memcpy(lit, scalar.depth, pixels * sizeof *lit);
                        lit_fragments[filter][run] = scalar_stats.fragments;
                    } else {
                        cr_assert_eq(memcmp(scalar.depth, lit, pixels * sizeof *lit), 0, "%s: not lambert's depths",
                                     what);
                        cr_assert_eq(scalar_stats.fragments, lit_fragments[filter][run], "%s: not lambert's count",
                                     what);
                    }
                    scene_fb_make(&rows, FB_SIDE, FB_SIDE);
                    rows.reversed_z = reversed;
                    sr_framebuffer_clear(&rows, 0x123456);
                    scene_draw_on_loop(&rows, &desc, SR_SIMD_AUTO, TILED_THREADS, SR_PATH_ROWS, &rows_stats);
                    assert_same_as(&scalar, &scalar_stats, &rows, &rows_stats, what, "row bands");
                    sr_framebuffer_destroy(&rows);
                    sr_framebuffer_destroy(&scalar);
                }
        /* Vertex colours times each material's colour, where no material has a texture. */
        sr_mesh colored = *meshes[m];
        materials_set(&colored, materials, parts, NULL);
        for (int srgb = 0; srgb < 2; srgb++) {
            sr_draw_desc desc = { .mesh = &colored, .shade = SR_SHADE_LAMBERT, .cull = SR_CULL_NONE,
                                  .color_space = srgb ? SR_COLOR_SRGB : SR_COLOR_RAW };
            look(&desc, (const float[6]){ 0, 0, 0, 0, 0, 1 }, 90.0f, false);
            assert_vector_loops_match_scalar(&desc, false, m ? "narrow, vertex colours by material" :
                                                               "wide, vertex colours by material");
        }
    }
    free(lit_depth);
    sr_mesh_free(&narrow);
    sr_mesh_free(&wide);
}
