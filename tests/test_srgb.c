/* The sRGB colour space (softrast.h, sr_color_space; src/pipeline/srgb.h):
 * the transfer tables against the IEC 61966-2-1 formulas, exact pixels on
 * small pixel-space scenes under both colour spaces, in every per-pixel
 * loop and path, and the outputs that must not change with it. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "scene_helpers.h"

#define W 32
#define H 16

static double srgb_to_linear(double s)
{
    return s <= 0.04045 ? s / 12.92 : pow((s + 0.055) / 1.055, 2.4);
}

static double linear_to_srgb(double l)
{
    return l <= 0.0031308 ? l * 12.92 : 1.055 * pow(l, 1.0 / 2.4) - 0.055;
}

Test(srgb, decoding_then_encoding_gives_every_value_back)
{
    for (uint32_t v = 0; v < 256; v++)
        cr_assert_eq(sr_linear_to_srgb[sr_srgb_to_linear[v]], v, "%u decodes to %u, which encodes to %u", v,
                     sr_srgb_to_linear[v], sr_linear_to_srgb[sr_srgb_to_linear[v]]);
}

/* Each entry is the exact function rounded to nearest; both tables rise. */
Test(srgb, the_tables_are_the_transfer_function_rounded)
{
    for (uint32_t v = 0; v < 256; v++) {
        double exact = SR_LINEAR_ONE * srgb_to_linear(v / 255.0);
        cr_assert_leq(fabs(sr_srgb_to_linear[v] - exact), 0.5, "decode %u: %u for %.4f", v, sr_srgb_to_linear[v],
                      exact);
        cr_assert(v == 0 || sr_srgb_to_linear[v] > sr_srgb_to_linear[v - 1], "decode %u does not rise", v);
    }
    for (uint32_t l = 0; l <= SR_LINEAR_ONE; l++) {
        double exact = 255.0 * linear_to_srgb(l / (double)SR_LINEAR_ONE);
        cr_assert_leq(fabs(sr_linear_to_srgb[l] - exact), 0.5, "encode %u: %u for %.4f", l, sr_linear_to_srgb[l],
                      exact);
        cr_assert(l == 0 || sr_linear_to_srgb[l] >= sr_linear_to_srgb[l - 1], "encode %u falls", l);
    }
    cr_assert_eq(sr_linear_to_srgb[SR_LINEAR_ONE], 255u);
}

/* A lit texel within 1.2 steps of the exact arithmetic (decode, times the
 * intensity, encode, in double) for every 8-bit value and every intensity
 * the 8.8 fixed point holds: the rounding of the decoded value to 12 bits
 * costs up to 0.6 of a step near black, the final rounding half a step. */
Test(srgb, a_lit_texel_is_within_a_step_of_the_exact_arithmetic)
{
    for (uint32_t v = 0; v < 256; v++)
        for (uint32_t k = 0; k <= SR_SHADE_LIT_ONE; k++) {
            float intensity = (float)k / (float)SR_SHADE_LIT_ONE;
            uint32_t t = v << 16 | v << 8 | v, lit = sr_shade_lit_texel_srgb(t, intensity, NULL);
            double exact = 255.0 * linear_to_srgb(srgb_to_linear(v / 255.0) * k / SR_SHADE_LIT_ONE);
            cr_assert_eq(lit, (lit & 0xFF) * 0x010101u, "the channels of %06x differ", lit);
            cr_assert_leq(fabs((double)(lit & 0xFF) - exact), 1.2, "%u at %u/256: %u, exact %.3f", v, k, lit & 0xFF,
                          exact);
        }
}

/* A quad over the whole W x H framebuffer in pixel space, facing the
 * camera (normal −z), uv 0..1, in vertex colour `rgb`. */
static void quad_make(sr_mesh *mesh, float rgb)
{
    sr_error err = { "" };
    cr_assert(sr_mesh_alloc(mesh, 4, 6, true, true, true, &err), "%s", err.message);
    const float xs[4] = { 0, W, 0, W }, ys[4] = { 0, 0, H, H };
    for (uint32_t k = 0; k < 4; k++) {
        glm_vec3_copy((vec3){ xs[k], ys[k], 0.5f }, mesh->positions[k]);
        glm_vec3_copy((vec3){ 0.0f, 0.0f, -1.0f }, mesh->normals[k]);
        glm_vec3_copy((vec3){ rgb, rgb, rgb }, mesh->colors[k]);
        mesh->uvs[k][0] = k % 2 ? 1.0f : 0.0f;
        mesh->uvs[k][1] = k < 2 ? 1.0f : 0.0f;
    }
    memcpy(mesh->indices, (const uint32_t[6]){ 0, 1, 2, 1, 3, 2 }, sizeof(uint32_t[6]));
}

/* desc drawn on every loop the CPU has, one thread and three (tiles and
 * row bands), all asserted equal; the colour every pixel must have is
 * `want`. */
static void expect_everywhere(const sr_draw_desc *base, uint32_t want, const char *what)
{
    sr_draw_desc desc = *base;
    desc.cull = SR_CULL_NONE;
    scene_pixel_ortho(&desc, W, H);
    sr_simd loops[SCENE_LOOPS];
    size_t n = scene_available_loops(loops);
    static const sr_draw_path paths[] = { SR_PATH_DIRECT, SR_PATH_TILES, SR_PATH_ROWS };
    for (size_t l = 0; l < n; l++)
        for (size_t p = 0; p < sizeof paths / sizeof *paths; p++) {
            sr_framebuffer fb;
            sr_stats stats;
            scene_fb_make(&fb, W, H);
            scene_draw_on_loop(&fb, &desc, loops[l], paths[p] == SR_PATH_DIRECT ? 1 : 3, paths[p], &stats);
            for (int i = 0; i < W * H; i++)
                cr_assert_eq(fb.color[i], want, "%s, %s loop, path %d: pixel %d is %06x, not %06x", what,
                             sr_simd_name(loops[l]), (int)paths[p], i, fb.color[i], want);
            sr_framebuffer_destroy(&fb);
        }
}

#define TOWARD_CAMERA { 0.0f, 0.0f, -1.0f } /* the quad's normal: lit fully, intensity 1 */
#define BEHIND { 0.0f, 0.0f, 1.0f }         /* ambient alone, 0.2 (51/256 in 8.8) */

/* A 50 % grey texel (128, 0.216 in linear light) lit fully stays 128 in
 * both spaces. By ambient light alone, raw is 128·51/256 → 26; sRGB
 * decodes 128 to 884/4095, times 51/256 is 176, which encodes to 58 (the
 * exact arithmetic: 58.6). */
Test(srgb, a_mid_grey_texture_lit_fully_stays_128)
{
    static const uint32_t grey = 0x808080;
    sr_texture tex = { .width = 1, .height = 1, .texels = (uint32_t *)&grey };
    sr_mesh mesh;
    quad_make(&mesh, 1.0f);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_LAMBERT, .texture = &tex, .light_dir = TOWARD_CAMERA };
    expect_everywhere(&desc, 0x808080, "raw, lit");
    desc.color_space = SR_COLOR_SRGB;
    expect_everywhere(&desc, 0x808080, "srgb, lit");
    glm_vec3_copy((vec3)BEHIND, desc.light_dir);
    expect_everywhere(&desc, 0x3A3A3A, "srgb, ambient");
    cr_assert_leq(fabs(58.0 - 255.0 * linear_to_srgb(0.2 * srgb_to_linear(128.0 / 255.0))), 1.0);
    desc.color_space = SR_COLOR_RAW;
    expect_everywhere(&desc, 0x1A1A1A, "raw, ambient");
    /* Texture shading draws a texel as it is in both. */
    desc.shade = SR_SHADE_TEXTURE;
    expect_everywhere(&desc, 0x808080, "raw, texture");
    desc.color_space = SR_COLOR_SRGB;
    expect_everywhere(&desc, 0x808080, "srgb, texture");
    sr_mesh_free(&mesh);
}

/* Vertex colours and material colours are linear: 0.5 encodes to 188
 * (2048/4095 in linear light; the exact 187.5 rounds to 188 too), 1 to
 * 255, where raw writes 128 and 255. Lit by ambient alone, 0.5 · 0.2 =
 * 0.1 in linear light encodes to 89. */
Test(srgb, vertex_and_material_colours_are_linear)
{
    sr_mesh mesh;
    quad_make(&mesh, 0.5f);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_COLOR };
    expect_everywhere(&desc, 0x808080, "raw, vertex colour");
    desc.color_space = SR_COLOR_SRGB;
    expect_everywhere(&desc, 0xBCBCBC, "srgb, vertex colour");
    desc.shade = SR_SHADE_LAMBERT;
    glm_vec3_copy((vec3)TOWARD_CAMERA, desc.light_dir);
    expect_everywhere(&desc, 0xBCBCBC, "srgb, vertex colour lit");
    glm_vec3_copy((vec3)BEHIND, desc.light_dir);
    expect_everywhere(&desc, 0x595959, "srgb, vertex colour by ambient light");
    cr_assert_eq(lround(255.0 * linear_to_srgb(0.1)), 89);
    sr_material red = { .base_color = { 1.0f, 0.5f, 0.0f, 1.0f } };
    sr_mesh_part part = { 0, 2, 0 };
    mesh.materials = &red;
    mesh.material_count = 1;
    mesh.parts = &part;
    mesh.part_count = 1;
    glm_vec3_copy((vec3)TOWARD_CAMERA, desc.light_dir);
    expect_everywhere(&desc, 0xBC8900, "srgb, vertex colour times a material's"); /* 0.5 and 0.25 */
    cr_assert_eq(lround(255.0 * linear_to_srgb(0.25)), 0x89);
    vec3 *colors = mesh.colors;
    mesh.colors = NULL;
    expect_everywhere(&desc, 0xFFBC00, "srgb, a material's colour");
    desc.color_space = SR_COLOR_RAW;
    expect_everywhere(&desc, 0xFF8000, "raw, a material's colour");
    mesh.colors = colors;
    mesh.materials = NULL;
    mesh.parts = NULL;
    sr_mesh_free(&mesh);
}

/* id, normal and depth shading, and the depth and ids planes of any
 * shading, are the same bits in both colour spaces. */
Test(srgb, ids_normals_and_depth_do_not_change)
{
    sr_mesh mesh;
    quad_make(&mesh, 0.5f);
    static const sr_shade shades[] = { SR_SHADE_ID, SR_SHADE_NORMAL, SR_SHADE_DEPTH, SR_SHADE_LAMBERT };
    for (size_t s = 0; s < sizeof shades / sizeof *shades; s++) {
        sr_framebuffer fb[2];
        for (int space = 0; space < 2; space++) {
            sr_draw_desc desc = { .mesh = &mesh, .shade = shades[s], .color_space = (sr_color_space)space,
                                  .cull = SR_CULL_NONE };
            scene_pixel_ortho(&desc, W, H);
            sr_error err = { "" };
            scene_fb_make(&fb[space], W, H);
            cr_assert(sr_framebuffer_create_ids(&fb[space], &err), "%s", err.message);
            cr_assert(sr_draw(&fb[space], &desc, NULL, &err), "%s", err.message);
        }
        bool colour = shades[s] == SR_SHADE_LAMBERT;
        cr_expect_eq(memcmp(fb[0].color, fb[1].color, W * H * sizeof(uint32_t)) != 0, colour,
                     "mode %d: the colours %s", (int)shades[s], colour ? "did not change" : "changed");
        cr_expect_eq(memcmp(fb[0].depth, fb[1].depth, W * H * sizeof(float)), 0, "mode %d: depth", (int)shades[s]);
        cr_expect_eq(memcmp(fb[0].ids, fb[1].ids, W * H * sizeof(uint32_t)), 0, "mode %d: ids", (int)shades[s]);
        sr_framebuffer_destroy(&fb[0]);
        sr_framebuffer_destroy(&fb[1]);
    }
    sr_mesh_free(&mesh);
}

Test(srgb, an_unknown_colour_space_is_refused)
{
    sr_mesh mesh;
    quad_make(&mesh, 0.5f);
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    sr_framebuffer_clear(&fb, 0xABCDEF);
    sr_draw_desc desc = { .mesh = &mesh, .color_space = (sr_color_space)2 };
    scene_pixel_ortho(&desc, W, H);
    sr_error err = { "" };
    cr_assert_not(sr_draw(&fb, &desc, NULL, &err));
    cr_assert_not_null(strstr(err.message, "colour space"), "%s", err.message);
    cr_assert_eq(scene_count_color(&fb, 0xABCDEF), (size_t)W * H, "the framebuffer was touched");
    sr_framebuffer_destroy(&fb);
    sr_mesh_free(&mesh);
}

/* ---- the command line ---- */

#include "run_helpers.h"
#include "softrast/files.h"
#include "temp_dir.h"

TestSuite(srgb_cli, .init = temp_dir_make, .fini = temp_dir_remove);

/* The colour at the centre of `render ARGS --size 16x16 --cull none --out`. */
static uint32_t centre_of(const char *args)
{
    char cmd[1024], out[600];
    snprintf(cmd, sizeof cmd, "render %s --size 16x16 --cull none --quiet --out %s", args,
             temp_path(out, sizeof out, "c.png"));
    run_result r = run_softrast(temp_dir, cmd);
    cr_assert_eq(r.status, 0, "%s: %s", cmd, r.err);
    sr_texture image;
    sr_error err;
    cr_assert(sr_texture_load(&image, out, &err), "%s", err.message);
    uint32_t c = image.texels[8 * 16 + 8] & 0xFFFFFF;
    sr_texture_free(&image);
    return c;
}

/* An MTL Kd of 0.5 is linear: 188 by default (srgb), 128 raw. A PLY's
 * grey 128 is a display value: decoded as the file is loaded, encoded
 * back, 128 under both (not decoded, it would be 188). */
Test(srgb_cli, kd_is_linear_and_ply_colours_are_display_values)
{
    write_text(temp_dir, "q.mtl", "newmtl half\nKd 0.5 0.5 0.5\n");
    write_text(temp_dir, "q.obj", "mtllib q.mtl\nusemtl half\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
    write_text(temp_dir, "q.ply",
               "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
               "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\n"
               "property list uchar int vertex_indices\nend_header\n"
               "-1 -1 0 128 128 128\n1 -1 0 128 128 128\n1 1 0 128 128 128\n-1 1 0 128 128 128\n4 0 1 2 3\n");
    char args[700];
    snprintf(args, sizeof args, "%s/q.obj --shade texture", temp_dir);
    cr_expect_eq(centre_of(args), 0xBCBCBCu);
    snprintf(args, sizeof args, "%s/q.obj --shade texture --color-space raw", temp_dir);
    cr_expect_eq(centre_of(args), 0x808080u);
    snprintf(args, sizeof args, "%s/q.ply --shade color", temp_dir);
    cr_expect_eq(centre_of(args), 0x808080u);
    snprintf(args, sizeof args, "%s/q.ply --shade color --color-space raw", temp_dir);
    cr_expect_eq(centre_of(args), 0x808080u);
}

Test(srgb_cli, an_unknown_colour_space_is_one_error_line)
{
    write_text(temp_dir, "t.obj", "v -1 0.2 0\nv 1 0.2 0\nv 0 1 0\nf 1 2 3\n");
    char args[700];
    snprintf(args, sizeof args, "render %s/t.obj --color-space linear", temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_neq(r.status, 0);
    cr_assert_eq(count_lines(r.err), 1, "%s", r.err);
    cr_assert_not_null(strstr(r.err, "raw|srgb"), "%s", r.err);
}
