/* Stage 10: varyings are interpolated perspective-correctly, and each
 * shading mode turns them into the documented color.
 *
 * The perspective scenes draw a quad that recedes steeply from the camera.
 * The expected uv at a pixel is computed from the geometry alone: intersect
 * the ray through the pixel centre with the quad's plane and read uv off the
 * quad's parametrisation there. Interpolating uv linearly in screen space
 * (without 1/w) is off by tens of texels on this quad.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <criterion/criterion.h>

#include "softrast_private.h"
#include "scene_helpers.h"

#define VIEW_W 96
#define VIEW_H 72
#define UNDRAWN 0xFF000000u /* no shading mode writes the top byte */

/* A texture whose texel value is its own address: x << 12 | y, so a pixel
 * drawn with nearest filtering says which texel (hence which uv) it sampled. */
#define CODE_SIZE 1024
#define CODE_X_SHIFT 12
#define CODE_MASK (CODE_SIZE - 1)
/* uv read back from a texel is its centre; the exact uv may lie anywhere in
 * the texel, plus rounding: 1.5 texels. */
#define UV_TOLERANCE (1.5 / CODE_SIZE)
/* The bilinear filter's 8-bit weights and rounded lerps (10_shade.h). */
#define BILINEAR_TOLERANCE (2.0 / 255)
#define UV_MARGIN 0.01 /* skip pixels this close to the quad's border (wrap) */
#define CHANNEL_TOLERANCE 1 /* 8-bit color channels: one step */

static sr_texture code_texture(void)
{
    sr_texture tex = { CODE_SIZE, CODE_SIZE, malloc((size_t)CODE_SIZE * CODE_SIZE * sizeof(uint32_t)) };
    cr_assert_not_null(tex.texels);
    for (uint32_t y = 0; y < CODE_SIZE; y++)
        for (uint32_t x = 0; x < CODE_SIZE; x++)
            tex.texels[y * CODE_SIZE + x] = x << CODE_X_SHIFT | y;
    return tex;
}

/* The receding quad: bottom edge 1.2 in front of the eye, top edge 9 away;
 * corners Q0 (uv 0,0) bottom-left, Q1 (1,0) bottom-right, Q2 (1,1), Q3 (0,1).
 * Q1 - Q0 and Q3 - Q0 are orthogonal, so uv is the projection on them. */
static const float quad_pos[4][3] = { { -1.0f, -1.0f, 1.2f }, { 1.0f, -1.0f, 1.2f }, { 1.0f, 0.6f, 9.0f },
                                      { -1.0f, 0.6f, 9.0f } };
static const float quad_uv[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
static const float quad_color[4][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } }; /* (u, v, 0) */
static const uint32_t quad_idx[6] = { 0, 3, 2, 0, 2, 1 }; /* clockwise on screen */

static const sr_camera *quad_camera(void)
{
    static sr_camera cam;
    cam = scene_camera(0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 60.0f, 0.1f, 100.0f);
    return &cam;
}

/* The uv where the ray through (i + 0.5, j + 0.5) meets the quad's plane. */
static void quad_uv_at(int i, int j, double uv[2])
{
    const sr_camera *cam = quad_camera();
    double dir[3], e1[3], e2[3], n[3];
    scene_pixel_ray(cam, VIEW_W, VIEW_H, i + 0.5, j + 0.5, dir);
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)quad_pos[1][k] - quad_pos[0][k];
        e2[k] = (double)quad_pos[3][k] - quad_pos[0][k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double num = 0, den = 0;
    for (int k = 0; k < 3; k++) {
        num += n[k] * (quad_pos[0][k] - cam->eye[k]);
        den += n[k] * dir[k];
    }
    double t = num / den, dot1 = 0, dot2 = 0, len1 = 0, len2 = 0;
    for (int k = 0; k < 3; k++) {
        double q = cam->eye[k] + t * dir[k] - quad_pos[0][k];
        dot1 += q * e1[k];
        dot2 += q * e2[k];
        len1 += e1[k] * e1[k];
        len2 += e2[k] * e2[k];
    }
    uv[0] = dot1 / len1;
    uv[1] = dot2 / len2;
}

static bool inside_margin(const double uv[2])
{
    return uv[0] > UV_MARGIN && uv[0] < 1 - UV_MARGIN && uv[1] > UV_MARGIN && uv[1] < 1 - UV_MARGIN;
}

static void draw_quad(sr_framebuffer *fb, sr_shade shade, const sr_texture *tex, const float light[3])
{
    static const float normals[4][3] = { { 0, 7.8f, -1.6f }, { 0, 7.8f, -1.6f }, { 0, 7.8f, -1.6f },
                                         { 0, 7.8f, -1.6f } }; /* facing the eye */
    sr_mesh mesh;
    scene_mesh_make(&mesh, &(scene_mesh_arrays){ .vertex_count = 4, .positions = quad_pos, .normals = normals,
                                                 .uvs = quad_uv, .colors = quad_color, .index_count = 6,
                                                 .indices = quad_idx });
    scene_fb_make(fb, VIEW_W, VIEW_H);
    sr_framebuffer_clear(fb, UNDRAWN);
    sr_draw_desc desc = { .mesh = &mesh, .shade = shade, .texture = tex, .filter = SR_FILTER_NEAREST };
    if (light)
        glm_vec3_copy((float *)light, desc.light_dir);
    scene_camera_desc(&desc, quad_camera(), VIEW_W, VIEW_H);
    sr_error err = { "" };
    sr_stats stats = { 0 };
    cr_assert(sr_draw(fb, &desc, &stats, &err), "sr_draw: %s", err.message);
    cr_assert_gt(stats.fragments, 0);
    sr_mesh_free(&mesh);
}

/* Reads uv back from the code texture at every pixel well inside the quad. */
static void expect_code_uv_matches_geometry(const sr_framebuffer *fb)
{
    int checked = 0, bad = 0;
    double worst = 0;
    for (int j = 0; j < VIEW_H; j++) {
        for (int i = 0; i < VIEW_W; i++) {
            double uv[2];
            quad_uv_at(i, j, uv);
            if (!inside_margin(uv))
                continue;
            uint32_t c = fb->color[j * VIEW_W + i];
            cr_assert_neq(c, UNDRAWN, "pixel (%d, %d) inside the quad (uv %.3f, %.3f) not drawn", i, j, uv[0], uv[1]);
            double u = (((c >> CODE_X_SHIFT) & CODE_MASK) + 0.5) / CODE_SIZE;
            double v = 1.0 - ((c & CODE_MASK) + 0.5) / CODE_SIZE; /* texel rows count from the top */
            double err = fmax(fabs(u - uv[0]), fabs(v - uv[1]));
            worst = fmax(worst, err);
            checked++;
            if (err > UV_TOLERANCE && bad++ < 5)
                cr_log_error("pixel (%d, %d): sampled uv (%.4f, %.4f), exact (%.4f, %.4f)", i, j, u, v, uv[0], uv[1]);
        }
    }
    cr_expect_eq(bad, 0, "%d of %d pixels sampled the wrong texel (worst %.1f texels)", bad, checked,
                 worst * CODE_SIZE);
    cr_expect_gt(checked, VIEW_W * VIEW_H / 4, "only %d pixels checked", checked);
}

Test(shading, texture_uv_is_perspective_correct_on_a_receding_quad)
{
    sr_texture tex = code_texture();
    sr_framebuffer fb;
    draw_quad(&fb, SR_SHADE_TEXTURE, &tex, NULL);
    expect_code_uv_matches_geometry(&fb);
    sr_framebuffer_destroy(&fb);
    free(tex.texels);
}

/* Lambert has its own specialised loop; with the light along the normal the
 * intensity is 1 and the albedo comes through unchanged. */
Test(shading, lambert_texture_uv_is_perspective_correct_on_a_receding_quad)
{
    sr_texture tex = code_texture();
    sr_framebuffer fb;
    draw_quad(&fb, SR_SHADE_LAMBERT, &tex, (const float[3]){ 0, 7.8f, -1.6f });
    expect_code_uv_matches_geometry(&fb);
    sr_framebuffer_destroy(&fb);
    free(tex.texels);
}

Test(shading, color_is_perspective_correct_on_a_receding_quad)
{
    sr_framebuffer fb;
    draw_quad(&fb, SR_SHADE_COLOR, NULL, NULL);
    int checked = 0, bad = 0;
    for (int j = 0; j < VIEW_H; j++) {
        for (int i = 0; i < VIEW_W; i++) {
            double uv[2];
            quad_uv_at(i, j, uv);
            if (!inside_margin(uv))
                continue;
            uint32_t c = fb.color[j * VIEW_W + i];
            int r = (int)(c >> 16 & 0xFF), g = (int)(c >> 8 & 0xFF), b = (int)(c & 0xFF);
            int want_r = (int)lround(uv[0] * 255), want_g = (int)lround(uv[1] * 255);
            checked++;
            if ((abs(r - want_r) > CHANNEL_TOLERANCE || abs(g - want_g) > CHANNEL_TOLERANCE || b != 0) && bad++ < 5)
                cr_log_error("pixel (%d, %d): color 0x%06x, want r %d g %d b 0", i, j, c, want_r, want_g);
        }
    }
    cr_expect_eq(bad, 0, "%d of %d pixels have the wrong color", bad, checked);
    cr_expect_gt(checked, VIEW_W * VIEW_H / 4);
    sr_framebuffer_destroy(&fb);
}

/* ---- one color per mode on a quad facing the camera ---- */

#define FLAT 32

/* A quad filling the middle of a 32 x 32 view from 2 units away; every
 * vertex has the same normal, color and uv, so every pixel is alike. */
static sr_framebuffer facing_quad(sr_shade shade, const float normal[3], const float color[3], const sr_texture *tex,
                                  const float light[3], const mat4 world)
{
    const float pos[4][3] = { { -0.5f, -0.5f, 2 }, { -0.5f, 0.5f, 2 }, { 0.5f, 0.5f, 2 }, { 0.5f, -0.5f, 2 } };
    float normals[4][3], colors[4][3], uvs[4][2];
    for (int k = 0; k < 4; k++) {
        memcpy(normals[k], normal, sizeof normals[k]);
        memcpy(colors[k], color, sizeof colors[k]);
        uvs[k][0] = 0.3f;
        uvs[k][1] = 0.3f;
    }
    const uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    sr_mesh mesh;
    scene_mesh_make(&mesh, &(scene_mesh_arrays){ .vertex_count = 4, .positions = pos, .normals = normals,
                                                 .uvs = uvs, .colors = colors, .index_count = 6, .indices = idx });
    sr_framebuffer fb;
    scene_fb_make(&fb, FLAT, FLAT);
    sr_framebuffer_clear(&fb, UNDRAWN);
    sr_camera cam = scene_camera(0, 0, 0, 0, 0, 1, 60.0f, 0.1f, 10.0f);
    sr_draw_desc desc = { .mesh = &mesh, .shade = shade, .texture = tex, .cull = SR_CULL_NONE };
    scene_camera_desc(&desc, &cam, FLAT, FLAT);
    if (world)
        glm_mat4_copy((vec4 *)world, desc.world);
    if (light)
        glm_vec3_copy((float *)light, desc.light_dir);
    sr_error err = { "" };
    cr_assert(sr_draw(&fb, &desc, NULL, &err), "sr_draw: %s", err.message);
    sr_mesh_free(&mesh);
    cr_assert_gt(scene_pixel_count(&fb) - scene_count_color(&fb, UNDRAWN), 0, "nothing drawn");
    return fb;
}


/* Every drawn pixel within one step per channel of want. */
static void expect_all_drawn(const sr_framebuffer *fb, uint32_t want, const char *what)
{
    for (size_t i = 0; i < scene_pixel_count(fb); i++) {
        uint32_t c = fb->color[i];
        if (c == UNDRAWN)
            continue;
        for (int s = 0; s <= 16; s += 8) {
            int got = (int)(c >> s & 0xFF), exp = (int)(want >> s & 0xFF);
            cr_assert_leq(abs(got - exp), CHANNEL_TOLERANCE, "%s: pixel %zu is 0x%06x, want 0x%06x", what, i, c, want);
        }
    }
}

static const float toward_eye[3] = { 0, 0, -1 }, white[3] = { 1, 1, 1 }, tint[3] = { 0.9f, 0.5f, 0.25f };

Test(shading, id_writes_triangle_slot_plus_one)
{
    sr_framebuffer fb = facing_quad(SR_SHADE_ID, toward_eye, white, NULL, NULL, NULL);
    size_t ones = scene_count_color(&fb, 1), twos = scene_count_color(&fb, 2);
    cr_expect_gt(ones, 0);
    cr_expect_gt(twos, 0);
    cr_expect_eq(ones + twos + scene_count_color(&fb, UNDRAWN), scene_pixel_count(&fb));
    sr_framebuffer_destroy(&fb);
}

/* World rotation by 30° about +y turns the normal (0, 0, -1) into
 * (-sin 30°, 0, -cos 30°): the normal view shows the world normal. */
Test(shading, normal_shows_the_world_space_normal)
{
    mat4 world;
    glm_rotate_make(world, glm_rad(30.0f), (vec3){ 0, 1, 0 });
    sr_framebuffer fb = facing_quad(SR_SHADE_NORMAL, toward_eye, white, NULL, NULL, world);
    double n[3] = { -sin(GLM_PI / 6), 0, -cos(GLM_PI / 6) };
    expect_all_drawn(&fb, scene_rgb(0.5 + 0.5 * n[0], 0.5 + 0.5 * n[1], 0.5 + 0.5 * n[2]), "normal");
    sr_framebuffer_destroy(&fb);
}

Test(shading, color_shows_the_vertex_color)
{
    sr_framebuffer fb = facing_quad(SR_SHADE_COLOR, toward_eye, tint, NULL, NULL, NULL);
    expect_all_drawn(&fb, scene_rgb(0.9, 0.5, 0.25), "color");
    sr_framebuffer_destroy(&fb);
}

Test(shading, lambert_with_the_light_along_the_normal_is_the_full_albedo)
{
    sr_framebuffer fb = facing_quad(SR_SHADE_LAMBERT, toward_eye, tint, NULL, toward_eye, NULL);
    expect_all_drawn(&fb, scene_rgb(0.9, 0.5, 0.25), "lambert, light along the normal");
    sr_framebuffer_destroy(&fb);
}

Test(shading, lambert_with_the_light_at_60_degrees_is_ambient_plus_half)
{
    const float light[3] = { (float)sin(GLM_PI / 3), 0, (float)-cos(GLM_PI / 3) };
    sr_framebuffer fb = facing_quad(SR_SHADE_LAMBERT, toward_eye, white, NULL, light, NULL);
    double k = SCENE_LAMBERT_AMBIENT + (1 - SCENE_LAMBERT_AMBIENT) * 0.5;
    expect_all_drawn(&fb, scene_rgb(k, k, k), "lambert at 60 degrees");
    sr_framebuffer_destroy(&fb);
}

Test(shading, lambert_with_the_light_behind_is_ambient)
{
    const float behind[3] = { 0.3f, 0.2f, 1.0f };
    sr_framebuffer fb = facing_quad(SR_SHADE_LAMBERT, toward_eye, white, NULL, behind, NULL);
    expect_all_drawn(&fb, scene_rgb(SCENE_LAMBERT_AMBIENT, SCENE_LAMBERT_AMBIENT, SCENE_LAMBERT_AMBIENT), "lambert, light behind");
    sr_framebuffer_destroy(&fb);
}

Test(shading, lambert_zero_light_dir_is_the_default_light)
{
    const float light[3] = SR_DEFAULT_LIGHT;
    sr_framebuffer with_zero = facing_quad(SR_SHADE_LAMBERT, toward_eye, white, NULL, NULL, NULL);
    sr_framebuffer with_default = facing_quad(SR_SHADE_LAMBERT, toward_eye, white, NULL, light, NULL);
    double len = sqrt(light[0] * light[0] + light[1] * light[1] + light[2] * light[2]);
    double k = SCENE_LAMBERT_AMBIENT + (1 - SCENE_LAMBERT_AMBIENT) * fmax(0.0, -light[2] / len);
    expect_all_drawn(&with_zero, scene_rgb(k, k, k), "lambert, default light");
    scene_expect_images_equal("shading_lambert_zero_light_dir_is_the_default_light", with_zero.color,
                              with_default.color, FLAT, FLAT);
    sr_framebuffer_destroy(&with_zero);
    sr_framebuffer_destroy(&with_default);
}

Test(shading, lambert_without_texture_or_colors_is_gray)
{
    const float pos[3][3] = { { -0.5f, -0.5f, 2 }, { 0, 0.5f, 2 }, { 0.5f, -0.5f, 2 } };
    const float normals[3][3] = { { 0, 0, -1 }, { 0, 0, -1 }, { 0, 0, -1 } };
    const uint32_t idx[3] = { 0, 1, 2 };
    sr_mesh mesh;
    scene_mesh_make(&mesh, &(scene_mesh_arrays){ .vertex_count = 3, .positions = pos, .normals = normals,
                                                 .index_count = 3, .indices = idx });
    sr_framebuffer fb;
    scene_fb_make(&fb, FLAT, FLAT);
    sr_framebuffer_clear(&fb, UNDRAWN);
    sr_camera cam = scene_camera(0, 0, 0, 0, 0, 1, 60.0f, 0.1f, 10.0f);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_LAMBERT, .light_dir = { 0, 0, -1 } };
    scene_camera_desc(&desc, &cam, FLAT, FLAT);
    cr_assert(sr_draw(&fb, &desc, NULL, NULL));
    cr_assert_gt(scene_pixel_count(&fb) - scene_count_color(&fb, UNDRAWN), 0);
    expect_all_drawn(&fb, scene_rgb(SCENE_LAMBERT_GRAY, SCENE_LAMBERT_GRAY, SCENE_LAMBERT_GRAY), "lambert gray");
    sr_mesh_free(&mesh);
    sr_framebuffer_destroy(&fb);
}

/* ---- sampling ---- */

/* uv (0, 0) is the image's bottom-left corner, and nearest sampling at the
 * corner (k/W, k/H) of a texel takes the texel above and to the right of it,
 * in v as in u: column k, row k counted from the bottom. */
Test(shading, nearest_sample_at_a_texel_corner_takes_the_texel_above_and_right)
{
    enum { SIZE = 8 };
    uint32_t texels[SIZE * SIZE];
    for (uint32_t y = 0; y < SIZE; y++)
        for (uint32_t x = 0; x < SIZE; x++)
            texels[y * SIZE + x] = x << 8 | (SIZE - 1 - y); /* green = column, blue = row from the bottom */
    sr_texture tex = { SIZE, SIZE, texels };
    for (int k = 0; k < SIZE; k++) {
        float rgbf[3];
        sr_shade_sample(&tex, SR_FILTER_NEAREST, (float)k / SIZE, (float)k / SIZE, rgbf);
        int column = (int)lroundf(rgbf[1] * 255), row = (int)lroundf(rgbf[2] * 255);
        cr_expect_eq(column, k, "u = %d/%d: column %d", k, SIZE, column);
        cr_expect_eq(row, k, "v = %d/%d: row %d from the bottom", k, SIZE, row);
    }
}

Test(shading, nearest_sample_at_a_texel_centre_is_that_texel)
{
    enum { SIZE = 8 };
    uint32_t texels[SIZE * SIZE];
    for (uint32_t y = 0; y < SIZE; y++)
        for (uint32_t x = 0; x < SIZE; x++)
            texels[y * SIZE + x] = x << 8 | (SIZE - 1 - y);
    sr_texture tex = { SIZE, SIZE, texels };
    for (int k = 0; k < SIZE; k++) {
        float rgbf[3], c = (k + 0.5f) / SIZE;
        sr_shade_sample(&tex, SR_FILTER_NEAREST, c, 1.0f - c, rgbf);
        cr_expect_eq((int)lroundf(rgbf[1] * 255), k);
        cr_expect_eq((int)lroundf(rgbf[2] * 255), SIZE - 1 - k);
    }
}

Test(shading, bilinear_sample_at_a_texel_centre_is_that_texel_and_halfway_is_the_mean)
{
    const uint32_t texels[4] = { 0x000000u, 0xC8C8C8u, 0x646464u, 0xFFFFFFu }; /* 2 x 2, top row first */
    sr_texture tex = { 2, 2, (uint32_t *)texels };
    float c[3];
    sr_shade_sample(&tex, SR_FILTER_BILINEAR, 0.75f, 0.75f, c); /* top-right texel centre */
    cr_expect_float_eq(c[0], 200.0f / 255, 1e-6);
    sr_shade_sample(&tex, SR_FILTER_BILINEAR, 0.25f, 0.25f, c); /* bottom-left */
    cr_expect_float_eq(c[0], 100.0f / 255, 1e-6);
    sr_shade_sample(&tex, SR_FILTER_BILINEAR, 0.5f, 0.5f, c); /* the middle: all four alike */
    cr_expect_float_eq(c[0], (0 + 200 + 100 + 255) / 4.0f / 255, BILINEAR_TOLERANCE);
}

/* The exact bilinear filter in double, channel `shift` of the texels: the
 * reference the 8-bit fixed-point filter of 10_shade.h must stay within
 * BILINEAR_TOLERANCE of. */
static double exact_bilinear(const sr_texture *tex, double fu, double fv, int shift)
{
    double cx = fu * tex->width - 0.5, cy = (1.0 - fv) * tex->height - 0.5;
    double lx = floor(cx), ly = floor(cy), ax = cx - lx, ay = cy - ly;
    int x[2] = { ((int)lx + tex->width) % tex->width, ((int)lx + 1) % tex->width };
    int y[2] = { ((int)ly + tex->height) % tex->height, ((int)ly + 1) % tex->height };
    double c[2][2];
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++)
            c[j][i] = (double)((tex->texels[y[j] * tex->width + x[i]] >> shift) & 0xFF);
    double top = c[0][0] + ax * (c[0][1] - c[0][0]), bottom = c[1][0] + ax * (c[1][1] - c[1][0]);
    return (top + ay * (bottom - top)) / 255.0;
}

Test(shading, bilinear_sample_is_within_two_steps_of_the_exact_filter)
{
    enum { W = 7, H = 5, SAMPLES = 20000 };
    uint32_t texels[W * H];
    test_rng rng = { 0xB1B1 };
    for (int i = 0; i < W * H; i++)
        texels[i] = (uint32_t)rng_next(&rng) & 0xFFFFFFu;
    sr_texture tex = { W, H, texels };
    double worst = 0;
    for (int k = 0; k < SAMPLES; k++) {
        float fu = (float)rng_unit(&rng), fv = (float)rng_unit(&rng);
        float c[3];
        sr_shade_sample(&tex, SR_FILTER_BILINEAR, fu, fv, c);
        for (int i = 0; i < 3; i++) {
            double d = fabs(c[i] - exact_bilinear(&tex, fu, fv, 16 - 8 * i));
            worst = d > worst ? d : worst;
        }
    }
    cr_expect_leq(worst, BILINEAR_TOLERANCE, "largest error %g (%g steps of 1/255)", worst, worst * 255);
    cr_expect_gt(worst, 0.1 / 255, "the fixed-point filter should differ from the exact one somewhere");
}

/* Texels are 0x00RRGGBB; one with its top byte set (an alpha channel a
 * caller kept) samples like the same texel without it, in both filters. */
Test(shading, a_texel_top_byte_never_reaches_the_color)
{
    enum { W = 3, H = 2, SAMPLES = 2000 };
    uint32_t plain[W * H], stray[W * H];
    test_rng rng = { 0x70B7 };
    for (int i = 0; i < W * H; i++) {
        plain[i] = (uint32_t)rng_next(&rng) & 0xFFFFFFu;
        stray[i] = plain[i] | 0xA5000000u;
    }
    sr_texture a = { W, H, plain }, b = { W, H, stray };
    for (int k = 0; k < SAMPLES; k++) {
        float u = (float)rng_uniform(&rng, -2.0, 2.0), v = (float)rng_uniform(&rng, -2.0, 2.0);
        for (int f = 0; f < 2; f++) {
            uint32_t want = sr_shade_sample_packed(&a, (sr_filter)f, u, v);
            uint32_t got = sr_shade_sample_packed(&b, (sr_filter)f, u, v);
            cr_assert_eq(got, want, "filter %d at (%g, %g): 0x%08x, without the top byte 0x%08x", f, u, v, got, want);
        }
    }
}

/* A lit texel is k·t per channel with k in 8.8 fixed point: the texel
 * itself at k = 1, and less than a step from k·t for k over the lambert
 * range (half a step from rounding the product, at most 255/512 from
 * rounding k), channel by channel, with no carry between channels. */
Test(shading, a_lit_texel_is_each_channel_times_the_intensity_rounded)
{
    test_rng rng = { 0x117E };
    for (int n = 0; n < 20000; n++) {
        uint32_t t = (uint32_t)rng_next(&rng) & 0xFFFFFFu;
        float k = n == 0 ? 1.0f : (float)rng_uniform(&rng, SCENE_LAMBERT_AMBIENT, 1.0);
        uint32_t lit = sr_shade_lit_texel(t, k);
        if (n == 0)
            cr_assert_eq(lit, t, "k = 1 changed 0x%06x to 0x%06x", t, lit);
        cr_assert_eq(lit >> 24, 0u, "0x%06x at k %g carried into the top byte", t, k);
        for (int shift = 0; shift <= 16; shift += 8) {
            double want = (double)k * ((t >> shift) & 0xFF), got = (lit >> shift) & 0xFF;
            cr_assert_leq(fabs(got - want), 0.5 + 255.0 / 512 + 1e-4, "channel at %d of 0x%06x, k %g: %g, not %g",
                          shift, t, k, got, want);
        }
    }
    /* 1 + 2^-9 is the smallest k whose 8.8 value rounds past 256 (to 257):
     * the first the clamp must catch, or 255 · 257 carries a channel over. */
    cr_assert_eq(sr_shade_lit_texel(0xFFFFFF, 1.0f + 0x1p-9f), 0xFFFFFFu, "k = 1 + 2^-9 must be clamped, not carried");
    cr_assert_eq(sr_shade_lit_texel(0xFFFFFF, 1.01f), 0xFFFFFFu, "k past 1 + 2^-9 must be clamped, not carried");
}
