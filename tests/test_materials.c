/* Materials per part in one draw (softrast.h, sr_material): each part's
 * triangles shaded with its own colour, texture, tint and alpha mode, on
 * small pixel-space scenes whose every pixel is known, in every per-pixel
 * loop; MASK leaves holes through which what is behind shows, in colour,
 * depth and ids, the same in every shading; and the draw refuses a table
 * it cannot take. */
#include <criterion/criterion.h>
#include <string.h>

#include "scene_helpers.h"

#define W 32
#define H 16

/* Quads in pixel space (x0..x1 by 0..H at depth z, uv u 0..1 across), one
 * part each, in the order given. */
typedef struct quad {
    float x0, x1, z;
    uint32_t material;
} quad;

static void quads_make(sr_mesh *mesh, const quad *q, uint32_t n, sr_mesh_part *parts)
{
    sr_error err = { "" };
    cr_assert(sr_mesh_alloc(mesh, 4 * n, 6 * n, true, true, false, &err), "%s", err.message);
    for (uint32_t i = 0; i < n; i++) {
        const float xs[4] = { q[i].x0, q[i].x1, q[i].x0, q[i].x1 }, ys[4] = { 0, 0, H, H };
        for (uint32_t k = 0; k < 4; k++) {
            uint32_t v = 4 * i + k;
            glm_vec3_copy((vec3){ xs[k], ys[k], q[i].z }, mesh->positions[v]);
            glm_vec3_copy((vec3){ 0.0f, 0.0f, -1.0f }, mesh->normals[v]);
            mesh->uvs[v][0] = k % 2 ? 1.0f : 0.0f;
            mesh->uvs[v][1] = k < 2 ? 1.0f : 0.0f;
        }
        const uint32_t idx[6] = { 4 * i, 4 * i + 1, 4 * i + 2, 4 * i + 1, 4 * i + 3, 4 * i + 2 };
        memcpy(mesh->indices + 6 * i, idx, sizeof idx);
        parts[i] = (sr_mesh_part){ 2 * i, 2, q[i].material };
    }
    mesh->parts = parts;
    mesh->part_count = n;
}

/* quads_make, with the caller's materials. */
static void quads_with(sr_mesh *mesh, const quad *q, uint32_t n, sr_mesh_part *parts, sr_material *materials,
                       uint32_t material_count)
{
    quads_make(mesh, q, n, parts);
    mesh->materials = materials;
    mesh->material_count = material_count;
}

/* The mesh's arrays, not the caller's parts and materials. */
static void quads_free(sr_mesh *mesh)
{
    mesh->parts = NULL;
    mesh->materials = NULL;
    sr_mesh_free(mesh);
}

/* Draws mesh on every loop available (one thread, and three on the tiles
 * and the row bands), asserting they agree, into fb. */
static sr_stats draw_everywhere(sr_framebuffer *fb, const sr_mesh *mesh, sr_shade shade, sr_filter filter)
{
    sr_draw_desc desc = { .mesh = mesh, .shade = shade, .filter = filter, .cull = SR_CULL_NONE };
    scene_pixel_ortho(&desc, W, H);
    sr_stats first = { 0 };
    sr_simd loops[SCENE_LOOPS];
    size_t n = scene_available_loops(loops);
    static const struct {
        int threads;
        sr_draw_path path;
    } ways[] = { { 1, SR_PATH_DIRECT }, { 3, SR_PATH_TILES }, { 3, SR_PATH_ROWS } };
    for (size_t l = 0; l < n; l++)
        for (size_t w = 0; w < sizeof ways / sizeof *ways; w++) {
            sr_framebuffer out;
            sr_stats stats;
            scene_fb_make(&out, W, H);
            scene_draw_on_loop(&out, &desc, loops[l], ways[w].threads, ways[w].path, &stats);
            if (l == 0 && w == 0) {
                memcpy(fb->color, out.color, W * H * sizeof *fb->color);
                memcpy(fb->depth, out.depth, W * H * sizeof *fb->depth);
                first = stats;
            } else {
                cr_assert_eq(memcmp(fb->color, out.color, W * H * sizeof *fb->color), 0, "%s, %d threads: colours",
                             sr_simd_name(loops[l]), ways[w].threads);
                cr_assert_eq(memcmp(fb->depth, out.depth, W * H * sizeof *fb->depth), 0, "%s, %d threads: depths",
                             sr_simd_name(loops[l]), ways[w].threads);
                cr_assert_eq(stats.fragments, first.fragments);
            }
            sr_framebuffer_destroy(&out);
        }
    return first;
}

static void expect_columns(const sr_framebuffer *fb, int x0, int x1, uint32_t color, float depth)
{
    for (int y = 0; y < H; y++)
        for (int x = x0; x < x1; x++) {
            cr_assert_eq(fb->color[y * W + x], color, "pixel (%d, %d) is %06x, not %06x", x, y, fb->color[y * W + x],
                         color);
            cr_assert_eq(fb->depth[y * W + x], depth, "pixel (%d, %d) has depth %g, not %g", x, y,
                         fb->depth[y * W + x], depth);
        }
}

Test(materials, two_parts_draw_their_own_colours)
{
    sr_mesh mesh;
    sr_mesh_part parts[2];
    sr_material materials[2] = { { .base_color = { 0, 1, 0, 1 } }, { .base_color = { 1, 0, 0, 1 } } };
    quads_with(&mesh, (const quad[2]){ { 0, 16, 0.25f, 1 }, { 16, 32, 0.5f, 0 } }, 2, parts, materials, 2);
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    sr_stats stats = draw_everywhere(&fb, &mesh, SR_SHADE_TEXTURE, SR_FILTER_NEAREST);
    expect_columns(&fb, 0, 16, 0xFF0000, 0.25f);
    expect_columns(&fb, 16, 32, 0x00FF00, 0.5f);
    cr_expect_eq(stats.fragments, (uint64_t)W * H);
    /* Lambert: each colour lit; a gray material draws as no material does. */
    draw_everywhere(&fb, &mesh, SR_SHADE_LAMBERT, SR_FILTER_NEAREST);
    double n[3] = { 0, 0, -1 }, l[3] = SR_DEFAULT_LIGHT;
    double len = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    for (int k = 0; k < 3; k++)
        l[k] /= len;
    double k = scene_lambert(n, l);
    uint32_t red = fb.color[0], green = fb.color[W - 1];
    cr_expect_eq(red & 0xFFFF, 0u, "red part: %06x", red);
    cr_expect(abs((int)(red >> 16) - (int)scene_channel(k)) <= 1, "red part: %06x, lit %g", red, k);
    cr_expect_eq(green & 0xFF00FF, 0u, "green part: %06x", green);
    sr_framebuffer plain;
    scene_fb_make(&plain, W, H);
    materials[0] = materials[1] = (sr_material){ .base_color = { SCENE_LAMBERT_GRAY, SCENE_LAMBERT_GRAY,
                                                                 SCENE_LAMBERT_GRAY, 1 } };
    draw_everywhere(&fb, &mesh, SR_SHADE_LAMBERT, SR_FILTER_NEAREST);
    mesh.material_count = 0;
    draw_everywhere(&plain, &mesh, SR_SHADE_LAMBERT, SR_FILTER_NEAREST);
    cr_expect_eq(memcmp(fb.color, plain.color, W * H * sizeof *fb.color), 0, "gray material differs from none");
    sr_framebuffer_destroy(&plain);
    sr_framebuffer_destroy(&fb);
    quads_free(&mesh);
}

/* A triangle in no part takes material 0; parts that all take material 0
 * are not looked up per triangle (draw/materials.c), and draw as the
 * lookup would: every quad green. One part naming material 1 turns its
 * quad red, the others staying green. */
Test(materials, parts_all_of_material_0_and_triangles_in_none_draw_in_it)
{
    sr_mesh mesh;
    sr_mesh_part parts[3];
    sr_material materials[2] = { { .base_color = { 0, 1, 0, 1 } }, { .base_color = { 1, 0, 0, 1 } } };
    const quad q[3] = { { 0, 8, 0.25f, 0 }, { 8, 16, 0.25f, 0 }, { 16, 32, 0.25f, 0 } };
    quads_with(&mesh, q, 3, parts, materials, 2);
    mesh.part_count = 2; /* the third quad in no part */
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    draw_everywhere(&fb, &mesh, SR_SHADE_TEXTURE, SR_FILTER_NEAREST);
    expect_columns(&fb, 0, 32, 0x00FF00, 0.25f);
    parts[1].material = 1;
    draw_everywhere(&fb, &mesh, SR_SHADE_TEXTURE, SR_FILTER_NEAREST);
    expect_columns(&fb, 0, 8, 0x00FF00, 0.25f);
    expect_columns(&fb, 8, 16, 0xFF0000, 0.25f);
    expect_columns(&fb, 16, 32, 0x00FF00, 0.25f);
    sr_framebuffer_destroy(&fb);
    quads_free(&mesh);
}

/* A texel times the material's colour: each channel times its factor in
 * 8.8 fixed point, rounded (0x80 · 0.5 → 0x40, 0x40 · 0.25 → 0x10). */
Test(materials, a_texture_is_tinted_by_the_base_colour)
{
    static uint32_t texel = 0x80FF40;
    sr_texture tex = { .width = 1, .height = 1, .texels = &texel };
    sr_mesh mesh;
    sr_mesh_part parts[2];
    sr_material materials[2] = { { .base_color = { 0.5f, 1, 0.25f, 1 }, .texture = &tex },
                                 { .base_color = { 1, 1, 1, 1 }, .texture = &tex } };
    quads_with(&mesh, (const quad[2]){ { 0, 16, 0.5f, 0 }, { 16, 32, 0.5f, 1 } }, 2, parts, materials, 2);
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    draw_everywhere(&fb, &mesh, SR_SHADE_TEXTURE, SR_FILTER_BILINEAR);
    expect_columns(&fb, 0, 16, 0x40FF10, 0.5f);
    expect_columns(&fb, 16, 32, 0x80FF40, 0.5f);
    sr_framebuffer_destroy(&fb);
    quads_free(&mesh);
}

/* A cut-out: a 2x1 texture whose left texel has alpha 0 on a quad at
 * depth 0.25, in front of a blue wall at 0.75 drawn after it. */
static uint32_t cutout_texels[2] = { 0x00FF0000, 0xFF00FF00 };

static void cutout_make(sr_mesh *mesh, sr_mesh_part parts[2], sr_material materials[2], sr_texture *tex)
{
    *tex = (sr_texture){ .width = 2, .height = 1, .texels = cutout_texels, .alpha = true };
    materials[0] = (sr_material){ .base_color = { 1, 1, 1, 1 }, .texture = tex, .alpha_mode = SR_ALPHA_MASK,
                                  .alpha_cutoff = 0.5f };
    materials[1] = (sr_material){ .base_color = { 0, 0, 1, 1 } };
    quads_with(mesh, (const quad[2]){ { 0, 32, 0.25f, 0 }, { 0, 32, 0.75f, 1 } }, 2, parts, materials, 2);
}

/* A cut-out: a 2x1 texture whose left texel has alpha 0, in front of a
 * blue wall drawn after it. The hole writes no depth, so the wall shows
 * through it at its own depth and, in id shading, with its own ids; the
 * opaque half hides the wall. */
Test(materials, mask_cuts_holes_that_show_what_is_behind)
{
    sr_texture tex;
    sr_mesh mesh;
    sr_mesh_part parts[2];
    sr_material materials[2];
    cutout_make(&mesh, parts, materials, &tex);
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    sr_stats stats = draw_everywhere(&fb, &mesh, SR_SHADE_TEXTURE, SR_FILTER_NEAREST);
    expect_columns(&fb, 0, 16, 0x0000FF, 0.75f);
    expect_columns(&fb, 16, 32, 0x00FF00, 0.25f);
    cr_expect_eq(stats.fragments, (uint64_t)W * H, "the front half, then the wall in the hole");
    /* Lambert keeps the holes; BLEND is MASK at 0.5 whatever the cutoff says. */
    materials[0].alpha_mode = SR_ALPHA_BLEND;
    materials[0].alpha_cutoff = 0.0f;
    draw_everywhere(&fb, &mesh, SR_SHADE_LAMBERT, SR_FILTER_NEAREST);
    for (int y = 0; y < H; y++) {
        cr_assert_eq(fb.color[y * W] & 0xFFFF00, 0u, "the hole shows the blue wall: %06x", fb.color[y * W]);
        cr_assert_eq(fb.depth[y * W], 0.75f);
        cr_assert_eq(fb.color[y * W + W - 1] & 0xFF00FF, 0u, "the green half: %06x", fb.color[y * W + W - 1]);
        cr_assert_eq(fb.depth[y * W + W - 1], 0.25f);
    }
    /* Id shading: through the hole, the wall's triangles (ids 3, 4) at its depth. */
    stats = draw_everywhere(&fb, &mesh, SR_SHADE_ID, SR_FILTER_NEAREST);
    cr_expect_eq(stats.fragments, (uint64_t)W * H);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            uint32_t id = fb.color[y * W + x];
            float d = fb.depth[y * W + x];
            cr_assert(x < 16 ? (id == 3 || id == 4) && d == 0.75f : (id == 1 || id == 2) && d == 0.25f,
                      "id shading: pixel (%d, %d) shows triangle %u at depth %g", x, y, id - 1, d);
        }
    /* A texture without alpha is opaque: the whole front quad is drawn. */
    tex.alpha = false;
    draw_everywhere(&fb, &mesh, SR_SHADE_TEXTURE, SR_FILTER_NEAREST);
    expect_columns(&fb, 0, 16, 0xFF0000, 0.25f);
    sr_framebuffer_destroy(&fb);
    quads_free(&mesh);
}

/* MASK with a constant alpha under the cutoff (no texture alpha): the part
 * draws nothing at all, in colour or depth; at or above it, everything. */
Test(materials, a_material_below_its_cutoff_draws_nothing)
{
    sr_mesh mesh;
    sr_mesh_part parts[2];
    sr_material materials[2] = {
        { .base_color = { 1, 0, 0, 0.2f }, .alpha_mode = SR_ALPHA_MASK, .alpha_cutoff = 0.5f },
        { .base_color = { 0, 1, 0, 0.4f }, .alpha_mode = SR_ALPHA_BLEND, .alpha_cutoff = 0.1f },
    };
    quads_with(&mesh, (const quad[2]){ { 0, 32, 0.25f, 0 }, { 8, 24, 0.5f, 1 } }, 2, parts, materials, 2);
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    sr_stats stats = draw_everywhere(&fb, &mesh, SR_SHADE_LAMBERT, SR_FILTER_BILINEAR);
    cr_expect_eq(stats.fragments, 0u);
    cr_expect_eq(scene_count_drawn(&fb), 0u);
    cr_expect_eq(scene_count_depth_written(&fb), 0u);
    materials[0].base_color[3] = 0.5f; /* at the cutoff: drawn */
    draw_everywhere(&fb, &mesh, SR_SHADE_TEXTURE, SR_FILTER_BILINEAR);
    expect_columns(&fb, 0, 32, 0xFF0000, 0.25f);
    sr_framebuffer_destroy(&fb);
    quads_free(&mesh);
}

/* Whether each pixel of fb was drawn (its depth written) where want's was. */
static void expect_same_coverage(const sr_framebuffer *fb, const sr_framebuffer *want, const char *what)
{
    for (int i = 0; i < W * H; i++)
        cr_assert_eq(fb->depth[i] < SR_DEPTH_CLEAR, want->depth[i] < SR_DEPTH_CLEAR,
                     "%s: pixel (%d, %d) drawn %d, lambert's %d", what, i % W, i / W, fb->depth[i] < SR_DEPTH_CLEAR,
                     want->depth[i] < SR_DEPTH_CLEAR);
}

/* Id, depth, normal and colour shading draw a MASK material's coverage as
 * lambert does, so depth and ids agree with the colour image: a quad alone
 * whose left texel has alpha 0. With the nearest filter the cut is at the
 * texel boundary, column 16: the left half keeps the clear colour and
 * depth, the right half is the quad's; with the bilinear filter (alpha
 * lerped, wrapping at u = 0) the coverage is lambert's, pixel for pixel.
 * Every loop, path and thread count draws the same (draw_everywhere). */
Test(materials, mask_cuts_the_same_holes_in_every_shading)
{
    sr_texture tex = { .width = 2, .height = 1, .texels = cutout_texels, .alpha = true };
    sr_material mask = { .base_color = { 1, 1, 1, 1 }, .texture = &tex, .alpha_mode = SR_ALPHA_MASK,
                         .alpha_cutoff = 0.5f };
    sr_mesh mesh;
    sr_mesh_part parts[1];
    quads_with(&mesh, (const quad[1]){ { 0, 32, 0.5f, 0 } }, 1, parts, &mask, 1);
    mesh.colors = malloc(mesh.vertex_count * sizeof *mesh.colors);
    cr_assert_not_null(mesh.colors);
    for (uint32_t v = 0; v < mesh.vertex_count; v++)
        glm_vec3_copy((vec3){ 0.2f, 0.4f, 0.6f }, mesh.colors[v]);
    static const sr_shade coverage[] = { SR_SHADE_ID, SR_SHADE_DEPTH, SR_SHADE_NORMAL, SR_SHADE_COLOR };
    sr_framebuffer lit, fb;
    scene_fb_make(&lit, W, H);
    scene_fb_make(&fb, W, H);
    for (int filter = 0; filter < 2; filter++) {
        sr_stats lit_stats = draw_everywhere(&lit, &mesh, SR_SHADE_LAMBERT, (sr_filter)filter);
        for (size_t m = 0; m < sizeof coverage / sizeof *coverage; m++) {
            char what[48];
            snprintf(what, sizeof what, "mode %d, filter %d", coverage[m], filter);
            sr_stats stats = draw_everywhere(&fb, &mesh, coverage[m], (sr_filter)filter);
            expect_same_coverage(&fb, &lit, what);
            cr_expect_eq(stats.fragments, lit_stats.fragments, "%s", what);
            if (filter == SR_FILTER_NEAREST) {
                cr_expect_eq(stats.fragments, (uint64_t)W * H / 2, "%s", what);
                for (int y = 0; y < H; y++)
                    for (int x = 0; x < W; x++) {
                        uint32_t c = fb.color[y * W + x];
                        float d = fb.depth[y * W + x];
                        cr_assert(x < 16 ? c == SCENE_BACKGROUND && d == SR_DEPTH_CLEAR : d == 0.5f,
                                  "%s: pixel (%d, %d) is %06x at depth %g", what, x, y, c, d);
                        if (coverage[m] == SR_SHADE_ID && x >= 16)
                            cr_assert(c == 1 || c == 2, "%s: pixel (%d, %d) is id %u", what, x, y, c);
                    }
            }
        }
    }
    /* The ids plane, on the tiles: written where the id colour is, 0 in the holes. */
    cr_assert(sr_framebuffer_create_ids(&fb, &(sr_error){ "" }));
    sr_framebuffer_clear(&fb, SCENE_BACKGROUND);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_ID, .filter = SR_FILTER_NEAREST, .cull = SR_CULL_NONE };
    scene_pixel_ortho(&desc, W, H);
    sr_stats stats;
    scene_draw_on_loop(&fb, &desc, SR_SIMD_AUTO, 3, SR_PATH_TILES, &stats);
    for (int i = 0; i < W * H; i++)
        cr_assert_eq(fb.ids[i], i % W < 16 ? 0u : fb.color[i], "pixel (%d, %d): id %u", i % W, i / W, fb.ids[i]);
    sr_framebuffer_destroy(&fb);
    sr_framebuffer_destroy(&lit);
    quads_free(&mesh);
}

/* The quad of mask_cuts_the_same_holes_in_every_shading as a grid of
 * pixel cells, two triangles each: more triangles than pixels, so the
 * draw's sub-pixel lanes find the one-pixel triangles, which id and depth
 * shading draw by a loop of their own (raster.c, sr_raster_lane_fragments). */
static void grid_make(sr_mesh *mesh, sr_mesh_part *part, sr_material *material)
{
    sr_error err = { "" };
    cr_assert(sr_mesh_alloc(mesh, (W + 1) * (H + 1), 6 * W * H, true, true, false, &err), "%s", err.message);
    for (uint32_t y = 0; y <= H; y++)
        for (uint32_t x = 0; x <= W; x++) {
            uint32_t v = y * (W + 1) + x;
            glm_vec3_copy((vec3){ (float)x, (float)y, 0.5f }, mesh->positions[v]);
            glm_vec3_copy((vec3){ 0.0f, 0.0f, -1.0f }, mesh->normals[v]);
            mesh->uvs[v][0] = (float)x / W;
            mesh->uvs[v][1] = 1.0f - (float)y / H;
        }
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            uint32_t v = y * (W + 1) + x, *idx = mesh->indices + 6 * (y * W + x);
            const uint32_t cell[6] = { v, v + 1, v + W + 1, v + 1, v + W + 2, v + W + 1 };
            memcpy(idx, cell, sizeof cell);
        }
    *part = (sr_mesh_part){ 0, 2 * W * H, 0 };
    mesh->parts = part;
    mesh->part_count = 1;
    mesh->materials = material;
    mesh->material_count = 1;
}

Test(materials, mask_cuts_one_pixel_triangles_too)
{
    sr_texture tex = { .width = 2, .height = 1, .texels = cutout_texels, .alpha = true };
    sr_material mask = { .base_color = { 1, 1, 1, 1 }, .texture = &tex, .alpha_mode = SR_ALPHA_MASK,
                         .alpha_cutoff = 0.5f };
    sr_mesh mesh;
    sr_mesh_part part;
    grid_make(&mesh, &part, &mask);
    sr_framebuffer lit, fb;
    scene_fb_make(&lit, W, H);
    scene_fb_make(&fb, W, H);
    sr_stats lit_stats = draw_everywhere(&lit, &mesh, SR_SHADE_LAMBERT, SR_FILTER_NEAREST);
    cr_expect_eq(lit_stats.fragments, (uint64_t)W * H / 2);
    static const sr_shade coverage[] = { SR_SHADE_ID, SR_SHADE_DEPTH };
    for (size_t m = 0; m < sizeof coverage / sizeof *coverage; m++) {
        sr_stats stats = draw_everywhere(&fb, &mesh, coverage[m], SR_FILTER_NEAREST);
        cr_expect_eq(stats.fragments, lit_stats.fragments, "mode %d", coverage[m]);
        cr_assert_eq(memcmp(fb.depth, lit.depth, W * H * sizeof *fb.depth), 0, "mode %d: not lambert's depths",
                     coverage[m]);
        for (int i = 0; i < W * H; i++)
            cr_assert_eq(fb.depth[i] < SR_DEPTH_CLEAR, i % W >= 16, "mode %d: pixel (%d, %d)", coverage[m], i % W,
                         i / W);
    }
    sr_framebuffer_destroy(&fb);
    sr_framebuffer_destroy(&lit);
    mesh.parts = NULL;
    mesh.materials = NULL;
    sr_mesh_free(&mesh);
}

/* A material whose alpha is below its cutoff everywhere draws nothing in
 * id and depth shading either; an opaque table's draw ignores materials. */
Test(materials, a_hidden_material_is_hidden_in_id_and_depth_shading)
{
    sr_mesh mesh;
    sr_mesh_part parts[1];
    sr_material hidden = { .base_color = { 1, 1, 1, 0 }, .alpha_mode = SR_ALPHA_MASK, .alpha_cutoff = 0.5f };
    quads_with(&mesh, (const quad[1]){ { 0, 32, 0.5f, 0 } }, 1, parts, &hidden, 1);
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    cr_expect_eq(draw_everywhere(&fb, &mesh, SR_SHADE_ID, 0).fragments, 0u);
    cr_expect_eq(scene_count_depth_written(&fb), 0u);
    cr_expect_eq(draw_everywhere(&fb, &mesh, SR_SHADE_DEPTH, 0).fragments, 0u);
    hidden.alpha_mode = SR_ALPHA_OPAQUE;
    cr_expect_eq(draw_everywhere(&fb, &mesh, SR_SHADE_ID, 0).fragments, (uint64_t)W * H);
    cr_expect_eq(draw_everywhere(&fb, &mesh, SR_SHADE_DEPTH, 0).fragments, (uint64_t)W * H);
    sr_framebuffer_destroy(&fb);
    quads_free(&mesh);
}

static void expect_refused(const sr_mesh *mesh, const char *want)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    sr_framebuffer_clear(&fb, 0xABCDEF);
    sr_draw_desc desc = { .mesh = mesh, .shade = SR_SHADE_LAMBERT };
    scene_pixel_ortho(&desc, W, H);
    sr_error err = { "" };
    cr_assert_not(sr_draw(&fb, &desc, NULL, &err), "drawn; wanted \"%s\"", want);
    cr_expect_not_null(strstr(err.message, want), "message: %s", err.message);
    cr_expect_eq(scene_count_color(&fb, 0xABCDEF), (size_t)W * H, "the framebuffer was touched");
    sr_framebuffer_destroy(&fb);
}

Test(materials, a_table_the_draw_cannot_take_is_refused)
{
    sr_mesh mesh;
    sr_mesh_part parts[2];
    sr_material materials[2] = { { .base_color = { 1, 1, 1, 1 } }, { .base_color = { 1, 1, 1, 1 } } };
    quads_with(&mesh, (const quad[2]){ { 0, 16, 0.5f, 0 }, { 16, 32, 0.5f, 7 } }, 2, parts, materials, 2);
    expect_refused(&mesh, "part 1 names material 7 of 2");
    parts[1].material = 1;
    parts[1].first_triangle = 1;
    expect_refused(&mesh, "part 1 overlaps");
    parts[1].first_triangle = 2;
    materials[1].alpha_mode = (sr_alpha_mode)9;
    expect_refused(&mesh, "material 1 has an unknown alpha mode");
    materials[1].alpha_mode = SR_ALPHA_OPAQUE;
    materials[0].base_color[1] = NAN;
    expect_refused(&mesh, "material 0 has a base colour that is not finite");
    materials[0].base_color[1] = 1;
    mesh.materials = NULL;
    expect_refused(&mesh, "no material array");
    quads_free(&mesh);
}

/* A material that names a texture file but was given no texture draws the
 * desc's: a program that loads mesh->texture_path into desc->texture, as
 * before materials, draws what it drew. */
Test(materials, a_named_texture_not_given_is_the_descs)
{
    static uint32_t texels[2] = { 0x123456, 0xABCDEF };
    sr_texture tex = { .width = 2, .height = 1, .texels = texels };
    sr_mesh mesh;
    sr_mesh_part parts[2];
    sr_material named = { .base_color = { 1, 1, 1, 1 }, .texture_path = (char *)"room.png" };
    quads_with(&mesh, (const quad[2]){ { 0, 16, 0.5f, 0 }, { 16, 32, 0.5f, 0 } }, 2, parts, &named, 1);
    sr_framebuffer with, without;
    scene_fb_make(&with, W, H);
    scene_fb_make(&without, W, H);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_LAMBERT, .texture = &tex, .filter = SR_FILTER_NEAREST };
    scene_pixel_ortho(&desc, W, H);
    sr_error err = { "" };
    cr_assert(sr_draw(&with, &desc, NULL, &err), "%s", err.message);
    mesh.material_count = 0;
    cr_assert(sr_draw(&without, &desc, NULL, &err), "%s", err.message);
    cr_expect_eq(memcmp(with.color, without.color, W * H * sizeof *with.color), 0);
    cr_expect_neq(with.color[0] & 0xFF, with.color[W - 1] & 0xFF, "textured: the two texels differ");
    sr_framebuffer_destroy(&with);
    sr_framebuffer_destroy(&without);
    quads_free(&mesh);
}

/* The ids plane has the MASK's holes: a pixel shows the id of the triangle
 * whose depth it holds, on every loop, path and thread count. */
Test(materials, the_ids_plane_keeps_the_mask_holes)
{
    sr_texture tex;
    sr_mesh mesh;
    sr_mesh_part parts[2];
    sr_material materials[2];
    cutout_make(&mesh, parts, materials, &tex);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_LAMBERT, .filter = SR_FILTER_NEAREST,
                          .cull = SR_CULL_NONE };
    scene_pixel_ortho(&desc, W, H);
    sr_simd loops[SCENE_LOOPS];
    size_t n = scene_available_loops(loops);
    for (size_t l = 0; l < n; l++)
        for (int path = 0; path < 3; path++) {
            sr_framebuffer fb;
            sr_stats stats;
            sr_error err = { "" };
            scene_fb_make(&fb, W, H);
            cr_assert(sr_framebuffer_create_ids(&fb, &err), "%s", err.message);
            sr_draw_path paths[3] = { SR_PATH_DIRECT, SR_PATH_TILES, SR_PATH_ROWS };
            scene_draw_on_loop(&fb, &desc, loops[l], path ? 3 : 1, paths[path], &stats);
            for (int y = 0; y < H; y++)
                for (int x = 0; x < W; x++) {
                    uint32_t id = fb.ids[y * W + x];
                    bool front = fb.depth[y * W + x] == 0.25f;
                    cr_assert(front ? id == 1 || id == 2 : id == 3 || id == 4,
                              "%s, path %d: pixel (%d, %d) at depth %g has id %u", sr_simd_name(loops[l]), path, x,
                              y, fb.depth[y * W + x], id);
                    cr_assert_eq(front, x >= 16, "pixel (%d, %d): the hole is the left half", x, y);
                }
            sr_framebuffer_destroy(&fb);
        }
    quads_free(&mesh);
}

/* Points and lines are drawn without the materials (they are the
 * triangles' parts): a textured material's mesh as lines draws as the
 * same lines without materials, and texture shading of it asks for the
 * desc's texture, with one line. */
Test(materials, lines_of_a_mesh_with_materials_ignore_them)
{
    static uint32_t texels[1] = { 0x00FF0000 };
    sr_texture tex = { .width = 1, .height = 1, .texels = texels };
    sr_mesh mesh;
    sr_mesh_part parts[1];
    sr_material materials[1] = { { .base_color = { 1, 1, 1, 1 }, .texture = &tex } };
    quads_with(&mesh, (const quad[1]){ { 2, 30, 0.5f, 0 } }, 1, parts, materials, 1);
    mesh.topology = SR_LINE_LIST;
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_LAMBERT, .cull = SR_CULL_NONE };
    scene_pixel_ortho(&desc, W, H);
    sr_framebuffer with, without;
    scene_fb_make(&with, W, H);
    scene_fb_make(&without, W, H);
    sr_error err = { "" };
    cr_assert(sr_draw(&with, &desc, NULL, &err), "%s", err.message);
    mesh.material_count = 0;
    cr_assert(sr_draw(&without, &desc, NULL, &err), "%s", err.message);
    cr_expect_eq(memcmp(with.color, without.color, W * H * sizeof *with.color), 0);
    cr_expect_eq(memcmp(with.depth, without.depth, W * H * sizeof *with.depth), 0);
    mesh.material_count = 1;
    desc.shade = SR_SHADE_TEXTURE;
    cr_expect_not(sr_draw(&with, &desc, NULL, &err));
    cr_expect_str_eq(err.message, "texture shading needs texture coordinates and a texture");
    sr_framebuffer_destroy(&with);
    sr_framebuffer_destroy(&without);
    quads_free(&mesh);
}
