/* The errors sr_draw reports instead of drawing: a desc that cannot be
 * drawn gives false and one line naming the problem, and leaves the
 * framebuffer and the stats untouched. (Bad geometry is not an error; see
 * test_pipeline.c.)
 */
#include <ctype.h>
#include <string.h>

#include <criterion/criterion.h>

#include "scene_helpers.h"
#include "softrast_private.h"

#define FLAT 32
#define FLAT_Z 0.5f

/* Clockwise on screen (y down): top-left, top-right, bottom-left. */
static const float cw[3][2] = { { 4, 4 }, { 28, 5 }, { 5, 27 } };

static void pixel_triangle(sr_mesh *mesh, const float xy[3][2])
{
    scene_pixel_triangle(mesh, xy, FLAT_Z);
}

static bool contains_word(const char *text, const char *word)
{
    for (const char *p = text; *p; p++) {
        size_t i = 0;
        while (word[i] && tolower((unsigned char)p[i]) == tolower((unsigned char)word[i]))
            i++;
        if (!word[i])
            return true;
    }
    return false;
}

/* sr_draw fails with a message naming `word`, and touches neither the
 * framebuffer nor the stats. */
static void expect_draw_fails(const sr_draw_desc *desc, const char *word)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, FLAT, FLAT);
    sr_framebuffer_clear(&fb, 0xABCDEFu);
    sr_stats s = { .triangles = 7 };
    sr_error err = { "" };
    cr_expect_not(sr_draw(&fb, desc, &s, &err), "sr_draw accepted a desc it cannot draw (%s)", word);
    cr_expect_neq(err.message[0], '\0', "no message");
    cr_expect(contains_word(err.message, word), "message \"%s\" does not mention %s", err.message, word);
    cr_expect_null(strstr(err.message, "softrast: error"), "message has the program's prefix");
    cr_expect_eq(scene_count_color(&fb, 0xABCDEFu), scene_pixel_count(&fb), "a failed draw wrote pixels");
    cr_expect_eq(scene_count_depth_written(&fb), 0, "a failed draw wrote depth");
    cr_expect(s.triangles == 7 && s.fragments == 0 && s.rejected == 0, "a failed draw changed the stats");
    cr_expect_not(sr_draw(&fb, desc, NULL, NULL), "fails the same with NULL stats and error");
    sr_framebuffer_destroy(&fb);
}

Test(draw, fails_without_a_mesh)
{
    expect_draw_fails(&(sr_draw_desc){ .shade = SR_SHADE_ID }, "mesh");
}

Test(draw, fails_on_an_index_out_of_range)
{
    sr_mesh mesh;
    pixel_triangle(&mesh, cw);
    mesh.indices[2] = 3; /* vertex_count is 3 */
    expect_draw_fails(&(sr_draw_desc){ .mesh = &mesh, .shade = SR_SHADE_ID }, "index");
    mesh.indices[2] = UINT32_MAX;
    expect_draw_fails(&(sr_draw_desc){ .mesh = &mesh, .shade = SR_SHADE_ID }, "index");
    sr_mesh_free(&mesh);
}

/* The check reads the indices in blocks: one index past the end is found
 * wherever it sits (in a block, in the tail, at any start of a thread's
 * share), as vertex_count itself and as UINT32_MAX, and none is reported
 * where there is none. */
#define CHECKED_INDICES 150 /* two 64-index blocks and a tail */

Test(draw, index_check_finds_one_index_past_the_end_at_every_position)
{
    uint32_t idx[CHECKED_INDICES];
    sr_mesh mesh = { .indices = idx, .index_count = CHECKED_INDICES, .vertex_count = 1000 };
    for (int i = 0; i < CHECKED_INDICES; i++)
        idx[i] = (uint32_t)(i * 7) % mesh.vertex_count;
    idx[CHECKED_INDICES - 1] = mesh.vertex_count - 1;
    static const uint32_t firsts[] = { 0, 1, 13, 64, 100 };
    for (size_t f = 0; f < sizeof firsts / sizeof firsts[0]; f++)
        cr_assert(sr_assemble_indices_valid_in(&mesh, firsts[f], CHECKED_INDICES), "from %u", firsts[f]);
    static const uint32_t past[] = { 1000, 1001, UINT32_MAX / 2 + 1, UINT32_MAX };
    for (int at = 0; at < CHECKED_INDICES; at++)
        for (size_t p = 0; p < sizeof past / sizeof past[0]; p++) {
            uint32_t kept = idx[at];
            idx[at] = past[p];
            for (size_t f = 0; f < sizeof firsts / sizeof firsts[0]; f++)
                cr_assert_eq(sr_assemble_indices_valid_in(&mesh, firsts[f], CHECKED_INDICES), (uint32_t)at < firsts[f],
                             "index %u at %d, checked from %u", past[p], at, firsts[f]);
            idx[at] = kept;
        }
}

Test(draw, fails_on_normal_and_lambert_shading_without_normals)
{
    sr_mesh mesh;
    pixel_triangle(&mesh, cw);
    expect_draw_fails(&(sr_draw_desc){ .mesh = &mesh, .shade = SR_SHADE_NORMAL }, "normal");
    expect_draw_fails(&(sr_draw_desc){ .mesh = &mesh, .shade = SR_SHADE_LAMBERT }, "normal");
    sr_mesh_free(&mesh);
}

Test(draw, fails_on_texture_shading_without_a_texture_or_uvs)
{
    uint32_t texel = 0xFFFFFFu;
    sr_texture tex = { 1, 1, &texel };
    sr_mesh with_uvs, without_uvs;
    const float pos[3][3] = { { 2, 2, 0.5f }, { 30, 2, 0.5f }, { 2, 30, 0.5f } }, uv[3][2] = { { 0 } };
    const uint32_t idx[3] = { 0, 1, 2 };
    scene_mesh_make(&with_uvs, &(scene_mesh_arrays){ .vertex_count = 3, .positions = pos, .uvs = uv,
                                                     .index_count = 3, .indices = idx });
    scene_triangle_make(&without_uvs, pos);
    expect_draw_fails(&(sr_draw_desc){ .mesh = &with_uvs, .shade = SR_SHADE_TEXTURE }, "texture");
    expect_draw_fails(&(sr_draw_desc){ .mesh = &with_uvs, .shade = SR_SHADE_TEXTURE, .texture = &(sr_texture){ 0 } },
                      "texture");
    expect_draw_fails(&(sr_draw_desc){ .mesh = &without_uvs, .shade = SR_SHADE_TEXTURE, .texture = &tex },
                      "texture coordinates");
    sr_mesh_free(&with_uvs);
    sr_mesh_free(&without_uvs);
}

/* A texture the caller filled in by hand with no size: sampling it would
 * divide by zero (wrap = repeat takes the index modulo the size). */
Test(draw, fails_on_a_texture_of_zero_size)
{
    uint32_t texel = 0xFFFFFFu;
    const float pos[3][3] = { { 2, 2, 0.5f }, { 30, 2, 0.5f }, { 2, 30, 0.5f } }, uv[3][2] = { { 0 } };
    const float normals[3][3] = { { 0, 0, -1 }, { 0, 0, -1 }, { 0, 0, -1 } };
    const uint32_t idx[3] = { 0, 1, 2 };
    sr_mesh mesh;
    scene_mesh_make(&mesh, &(scene_mesh_arrays){ .vertex_count = 3, .positions = pos, .normals = normals, .uvs = uv,
                                                 .index_count = 3, .indices = idx });
    const sr_texture empty[3] = { { 0, 1, &texel }, { 1, 0, &texel }, { -1, 1, &texel } };
    for (int k = 0; k < 3; k++) {
        sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_TEXTURE, .texture = &empty[k] };
        scene_pixel_ortho(&desc, FLAT, FLAT);
        expect_draw_fails(&desc, "texture");
        desc.shade = SR_SHADE_LAMBERT; /* lambert samples a given texture too */
        expect_draw_fails(&desc, "texture");
    }
    sr_mesh_free(&mesh);
}

Test(draw, fails_without_a_description_or_on_a_framebuffer_without_buffers)
{
    sr_mesh mesh;
    pixel_triangle(&mesh, cw);
    sr_error err = { "" };
    sr_framebuffer fb;
    scene_fb_make(&fb, FLAT, FLAT);
    cr_expect_not(sr_draw(&fb, NULL, NULL, &err));
    cr_expect_neq(err.message[0], '\0');
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_ID };
    scene_pixel_ortho(&desc, FLAT, FLAT); /* the triangle is on screen: a draw would write */
    cr_assert(sr_draw(&fb, &desc, NULL, &err), "sr_draw: %s", err.message);
    cr_assert_gt(scene_count_drawn(&fb), 0);
    sr_framebuffer empty = { .width = FLAT, .height = FLAT };
    err.message[0] = '\0';
    cr_expect_not(sr_draw(&empty, &desc, NULL, &err));
    cr_expect_neq(err.message[0], '\0');
    err.message[0] = '\0';
    cr_expect_not(sr_draw(NULL, &desc, NULL, &err));
    cr_expect_neq(err.message[0], '\0');
    sr_framebuffer_destroy(&fb);
    sr_mesh_free(&mesh);
}

Test(draw, fails_on_an_unknown_mode)
{
    sr_mesh mesh;
    pixel_triangle(&mesh, cw);
    expect_draw_fails(&(sr_draw_desc){ .mesh = &mesh, .shade = SR_SHADE_COUNT }, "shading");
    expect_draw_fails(&(sr_draw_desc){ .mesh = &mesh, .shade = SR_SHADE_ID, .cull = (sr_cull)7 }, "culling");
    expect_draw_fails(&(sr_draw_desc){ .mesh = &mesh, .shade = SR_SHADE_ID, .front = (sr_front)2 }, "front");
    expect_draw_fails(&(sr_draw_desc){ .mesh = &mesh, .shade = SR_SHADE_ID, .filter = (sr_filter)2 }, "filter");
    sr_mesh_free(&mesh);
}

Test(draw, fails_on_color_shading_without_colors)
{
    const float pos[3][3] = { { 2, 2, 0.5f }, { 30, 2, 0.5f }, { 2, 30, 0.5f } };
    sr_mesh mesh;
    scene_triangle_make(&mesh, pos);
    expect_draw_fails(&(sr_draw_desc){ .mesh = &mesh, .shade = SR_SHADE_COLOR }, "color");
    sr_mesh_free(&mesh);
}
