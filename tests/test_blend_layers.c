/* glTF BLEND materials drawn as the file means them (sr_draw_layered, src/scene/layers.c):
 * opaque parts first, then the BLEND parts farthest first, alpha-blended
 * and writing no depth; `render --blend` and `--depth-write` draw the whole
 * mesh in one draw instead. Exact pixels on a small scene of squares. */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "gltf_square.h"
#include "run_helpers.h"
#include "softrast/files.h"
#include "temp_dir.h"

TestSuite(blend_layers, .init = temp_dir_make, .fini = temp_dir_remove);

/* A unit square in z = 0 (glTF's frame, front side +z) drawn by three
 * nodes, listed nearest the camera (at +z) first, so the file's order is
 * not back to front: a green BLEND square of alpha 0.5 at z = 2 over
 * [−0.5, 0.5]², a blue one at z = 1 over [−1, 0] × [−0.5, 0.5], and an
 * opaque red one at z = 0 over [−2, 2]². */
static const char SQUARES_GLTF[] =
    "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0,1,2]}],"
    "\"nodes\":[{\"mesh\":2,\"translation\":[-0.5,-0.5,2]},{\"mesh\":1,\"translation\":[-1,-0.5,1]},"
    "{\"mesh\":0,\"translation\":[-2,-2,0],\"scale\":[4,4,1]}],"
    "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,0,0,1]}},"
    "{\"alphaMode\":\"BLEND\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,1,0.5]}},"
    "{\"alphaMode\":\"BLEND\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,1,0,0.5]}}],"
    "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"material\":0}]},"
    "{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"material\":1}]},"
    "{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"material\":2}]}],"
    GLTF_UNIT_SQUARE_ARRAYS "}";

/* Seen from +z (softrast's −z: the loader negates z) orthographically,
 * 4 units high on 40 pixels, unlit and raw: pixel column c is at x = (c +
 * 0.5)/10 − 2, and the mirror of z leaves x as it is. */
#define SIDE 40
#define CAMERA "--eye 0,0,-10 --target 0,0,0 --ortho 4 --size 40x40 --shade texture --color-space raw --cull none"

static void render(const char *options, sr_texture *image)
{
    char path[600], args[1400];
    write_text(temp_dir, "squares.gltf", SQUARES_GLTF);
    snprintf(args, sizeof args, "render '%s' " CAMERA " %s --out '%s' --quiet",
             temp_path(path, sizeof path, "squares.gltf"), options, temp_path(path + 300, 300, "out.png"));
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "softrast %s: %s", args, r.err);
    sr_error err = { "" };
    cr_assert(sr_texture_load(image, temp_path(path, sizeof path, "out.png"), &err), "%s", err.message);
    cr_assert(image->width == SIDE && image->height == SIDE);
}

/* Which squares cover the centre of pixel (c, r), row 0 at the top, seen
 * from the camera's plane z = 10: at the square's distance d from it,
 * pixel column c is at x = (c − 19.5)·d/100 (ORTHO: d = 10 for all). */
#define ORTHO ((const double[2]){ 10.0, 10.0 })
static bool inside(int c, int r, double d, double x0, double x1, double y0, double y1)
{
    double x = (c - 19.5) * d / 100.0, y = (19.5 - r) * d / 100.0;
    return x > x0 && x < x1 && y > y0 && y < y1;
}

/* Every pixel of the image against its colour under both translucent
 * squares, under blue alone, under green alone, and elsewhere; the blue
 * and the green square at distances[0] and [1] (ORTHO, or a pinhole's). */
static void expect_pixels(const sr_texture *image, const double distances[2], const uint32_t want[4],
                          const char *what)
{
    for (int r = 0; r < SIDE; r++)
        for (int c = 0; c < SIDE; c++) {
            bool blue = inside(c, r, distances[0], -1, 0, -0.5, 0.5),
                 green = inside(c, r, distances[1], -0.5, 0.5, -0.5, 0.5);
            uint32_t w = want[blue && green ? 0 : blue ? 1 : green ? 2 : 3];
            uint32_t got = image->texels[r * SIDE + c] & 0xFFFFFFu;
            cr_assert_eq(got, w, "%s: pixel (%d, %d) is %06x, not %06x", what, c, r, got, w);
        }
}

static void expect_render(const char *options, const uint32_t want[4])
{
    sr_texture image;
    render(options, &image);
    expect_pixels(&image, ORTHO, want, options);
    sr_texture_free(&image);
}

/* By hand (alpha 0.5 is 128/256; a channel is (s·128 + d·128 + 128) >> 8):
 * red under blue (128, 0, 128), under green (128, 128, 0), and under both,
 * farthest first (blue, then green over it), (64, 128, 64). */
Test(blend_layers, blend_parts_are_drawn_farthest_first_over_the_opaque_ones)
{
    expect_render("", (const uint32_t[4]){ 0x408040u, 0x800080u, 0x808000u, 0xFF0000u });
}

/* One draw in the file's order, green, blue, red. --blend alpha: green
 * blends over the black clear and writes its depth, hiding what is behind
 * it; blue blends over black where green is not; red fills the rest.
 * --depth-write off: red, drawn last, opaque and in front of no written
 * depth, replaces everything. */
Test(blend_layers, one_blended_draw_keeps_the_files_order)
{
    expect_render("--blend alpha", (const uint32_t[4]){ 0x008000u, 0x000080u, 0x008000u, 0xFF0000u });
    expect_render("--blend alpha --depth-write on", (const uint32_t[4]){ 0x008000u, 0x000080u, 0x008000u, 0xFF0000u });
    expect_render("--blend alpha --depth-write off", (const uint32_t[4]){ 0xFF0000u, 0xFF0000u, 0xFF0000u, 0xFF0000u });
}

/* --blend replace draws BLEND as MASK at 0.5, as a replacing draw does:
 * each translucent square whole, the nearest (green) in front. */
Test(blend_layers, one_replacing_draw_draws_blend_as_mask)
{
    expect_render("--blend replace", (const uint32_t[4]){ 0x00FF00u, 0x0000FFu, 0x00FF00u, 0xFF0000u });
}

Test(blend_layers, bad_blend_options_are_one_line_errors)
{
    static const struct {
        const char *options, *message;
    } cases[] = {
        { "--blend over", "bad value 'over' for --blend" },
        { "--blend alpha --depth-write maybe", "bad value 'maybe' for --depth-write" },
        { "--depth-write off", "--depth-write goes with --blend" },
        { "--blend additive --view-depth d.npy --pose-w2c 1,0,0,0,0,1,0,0,0,0,1,5,0,0,0,1 --intrinsics 40,40,19.5,19.5",
          "--blend draws the color image" },
    };
    char path[600];
    write_text(temp_dir, "squares.gltf", SQUARES_GLTF);
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char args[1200];
        snprintf(args, sizeof args, "render '%s' %s --out '%s/out.png'", temp_path(path, sizeof path, "squares.gltf"),
                 cases[i].options, temp_dir);
        run_result r = run_softrast(temp_dir, args);
        cr_assert_neq(r.status, 0, "%s: succeeded", cases[i].options);
        cr_assert_not_null(strstr(r.err, cases[i].message), "%s: %s", cases[i].options, r.err);
        cr_assert_eq(count_lines(r.err), 1, "%s: %s", cases[i].options, r.err);
    }
}

/* The float depth buffer of a W x H render (PFM). */
static void read_depth(const char *name, float *depth, int w, int h)
{
    char path[600];
    FILE *f = fopen(temp_path(path, sizeof path, name), "rb");
    cr_assert_not_null(f, "no %s", path);
    int fw, fh;
    float scale;
    cr_assert_eq(fscanf(f, "Pf %d %d %f", &fw, &fh, &scale), 3);
    fgetc(f);
    cr_assert(fw == w && fh == h, "%s is %dx%d", name, fw, fh);
    cr_assert_eq(fread(depth, sizeof(float), (size_t)w * h, f), (size_t)w * h);
    fclose(f);
}

/* ClearCoatTest.gltf's one BLEND material, Partial_Coating (the "coating
 * only" tile of the second row: a black texture of striped alpha, over
 * the black clear), drawn blended: the colours are those of one replacing
 * draw (black over black either way), but the coating writes no depth,
 * where a replacing draw wrote its stripes of alpha >= 0.5 as MASK. */
Test(blend_layers, clearcoat_blends_its_coating_and_writes_no_depth_for_it)
{
    static const char file[] = "/usr/share/assimp/models/glTF2/ClearCoat-glTF/ClearCoatTest.gltf";
    enum { W = 320, H = 240 };
    char args[1600], png[600], pfm[600], name[32];
    const char *runs[2][2] = { { "", "layers" }, { "--blend replace", "replace" } };
    for (int i = 0; i < 2; i++) {
        snprintf(name, sizeof name, "%s.png", runs[i][1]);
        temp_path(png, sizeof png, name);
        snprintf(name, sizeof name, "%s.pfm", runs[i][1]);
        temp_path(pfm, sizeof pfm, name);
        snprintf(args, sizeof args, "render %s --size 320x240 %s --out '%s' --depth '%s' --quiet", file, runs[i][0],
                 png, pfm);
        run_result r = run_softrast(temp_dir, args);
        cr_assert_eq(r.status, 0, "softrast %s: %s", args, r.err);
    }
    char a[600], b[600], cmd[1300];
    snprintf(cmd, sizeof cmd, "cmp -s '%s' '%s'", temp_path(a, sizeof a, "layers.png"),
             temp_path(b, sizeof b, "replace.png"));
    cr_assert_eq(system(cmd), 0, "the colours differ");
    static float layers[W * H], replace[W * H];
    read_depth("layers.pfm", layers, W, H);
    read_depth("replace.pfm", replace, W, H);
    size_t coating = 0;
    for (int i = 0; i < W * H; i++) {
        if (layers[i] == replace[i])
            continue;
        cr_assert(layers[i] == 1.0f && replace[i] < 1.0f, "pixel %d: depth %g blended, %g replaced", i, layers[i],
                  replace[i]);
        coating++;
    }
    cr_assert_gt(coating, 100u, "the coating's stripes: %zu pixels", coating);
}

/* One frame: a pinhole at z = 10 looking down −z (glTF's frame; cx, cy
 * from the top-left pixel's corner). */
static const char POSES[] = "{\"fl_x\": 100, \"fl_y\": 100, \"cx\": 20, \"cy\": 20, \"w\": 40, \"h\": 40, "
                            "\"frames\": [{\"transform_matrix\": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 10], "
                            "[0, 0, 0, 1]]}]}";

/* A camera dataset draws the BLEND parts as `render` does: frame 0 of a
 * --poses dataset, a pinhole at z = 10 looking down −z (glTF's frame;
 * cx, cy from the top-left pixel's corner), is the single image of the
 * same camera, colour, depth and part ids byte for byte; its colours are
 * the layers' by hand (the blue square 9 from the camera, the green 8),
 * and its depth is the opaque square's, 10, under the translucent ones
 * too: they write no depth and no ids, in id shading as well. */
Test(blend_layers, a_datasets_frame_is_renders_image_blended)
{
    static const char LOOK[] = "--shade texture --color-space raw --quiet";
    write_text(temp_dir, "squares.gltf", SQUARES_GLTF);
    write_text(temp_dir, "poses.json", POSES);
    const char *d = temp_dir;
    char args[2400];
    snprintf(args, sizeof args, "render '%s/squares.gltf' --poses '%s/poses.json' --out-dir '%s/ds' %s --out c.png "
                                "--view-depth d.pfm --part-ids p.png", d, d, d, LOOK);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "softrast %s: %s", args, r.err);
    snprintf(args, sizeof args, "render '%s/squares.gltf' --size 40x40 --intrinsics 100,100,19.5,19.5 "
                                "--pose-w2c 1,0,0,0,0,-1,0,0,0,0,-1,10,0,0,0,1 %s --out '%s/c.png' "
                                "--view-depth '%s/d.pfm' --part-ids '%s/p.png'", d, LOOK, d, d, d);
    r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "softrast %s: %s", args, r.err);
    /* id shading, which pictures the ids, measures the same surfaces */
    snprintf(args, sizeof args, "render '%s/squares.gltf' --size 40x40 --intrinsics 100,100,19.5,19.5 "
                                "--pose-w2c 1,0,0,0,0,-1,0,0,0,0,-1,10,0,0,0,1 --shade id --quiet "
                                "--view-depth '%s/id_d.pfm' --part-ids '%s/id_p.png'", d, d, d);
    r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "softrast %s: %s", args, r.err);
    char cmd[1600];
    snprintf(cmd, sizeof cmd, "cd '%s' && cmp c.png ds/c/frame_00000.png && cmp d.pfm ds/d/frame_00000.pfm && "
                              "cmp p.png ds/p/frame_00000.png && cmp d.pfm id_d.pfm && cmp p.png id_p.png", temp_dir);
    cr_assert_eq(system(cmd), 0, "the dataset's frame differs from the single image");
    sr_texture image;
    sr_error err = { "" };
    char path[600];
    cr_assert(sr_texture_load(&image, temp_path(path, sizeof path, "ds/c/frame_00000.png"), &err), "%s",
              err.message);
    expect_pixels(&image, (const double[2]){ 9.0, 8.0 },
                  (const uint32_t[4]){ 0x408040u, 0x800080u, 0x808000u, 0xFF0000u }, "the dataset's frame");
    sr_texture_free(&image);
    static float depth[SIDE * SIDE];
    read_depth("ds/d/frame_00000.pfm", depth, SIDE, SIDE);
    for (int i = 0; i < SIDE * SIDE; i++)
        cr_assert_float_eq(depth[i], 10.0f, 1e-5f, "pixel %d: depth %g, not the opaque square's", i, depth[i]);
}

/* Without --out (and --shade) no colour is written, so the measured outputs
 * come from a draw shaded in ids, which leaves the BLEND squares out (they would only
 * tint the colour): the same view depth and part ids as with --out, in a
 * single image and a dataset's frame, and --stats counts the opaque
 * square's two triangles where the draw with the colour counts six. */
Test(blend_layers, without_a_colour_output_the_draw_is_in_ids)
{
    static const char VIEW[] = "--size 40x40 --intrinsics 100,100,19.5,19.5 "
                               "--pose-w2c 1,0,0,0,0,-1,0,0,0,0,-1,10,0,0,0,1 --stats";
    write_text(temp_dir, "squares.gltf", SQUARES_GLTF);
    write_text(temp_dir, "poses.json", POSES);
    const char *d = temp_dir;
    char args[2400];
    const unsigned long long triangles[2] = { 2, 6 }; /* without the colour, with it */
    for (int colour = 1; colour >= 0; colour--) {
        snprintf(args, sizeof args,
                 "render '%s/squares.gltf' %s %s%s%s --view-depth '%s/d%d.pfm' --part-ids '%s/p%d.png'", d, VIEW,
                 colour ? "--out '" : "", colour ? d : "", colour ? "/c.png'" : "", d, colour, d, colour);
        run_result r = run_softrast(temp_dir, args);
        cr_assert_eq(r.status, 0, "softrast %s: %s", args, r.err);
        const char *at = strstr(r.out, "\"triangles\": ");
        cr_assert_not_null(at, "%s", r.out);
        cr_assert_eq(strtoull(at + strlen("\"triangles\": "), NULL, 10), triangles[colour], "%s: %s", args, r.out);
    }
    snprintf(args, sizeof args, "render '%s/squares.gltf' --poses '%s/poses.json' --out-dir '%s/ds' --quiet "
                                "--view-depth d.pfm --part-ids p.png", d, d, d);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "softrast %s: %s", args, r.err);
    char cmd[1600];
    snprintf(cmd, sizeof cmd, "cd '%s' && cmp d1.pfm d0.pfm && cmp p1.png p0.png && cmp d1.pfm ds/d/frame_00000.pfm && "
                              "cmp p1.png ds/p/frame_00000.png", temp_dir);
    cr_assert_eq(system(cmd), 0, "the outputs without the colour differ from those with it");
}

/* The library's entry on a mesh of its own: a BLEND square of alpha 0.5
 * (blue, triangles 0 and 1, nearer: z 0.25) listed before an opaque one
 * (red, 2 and 3, z 0.5), both over the whole 4x4 view in clip space (the
 * matrices left as the identity). Texture shading, raw: blue blends over
 * red (0x800080 by hand, as above), and depth and ids are the red
 * square's, its ids the file's; id shading leaves the blue square out. */
Test(blend_layers, the_library_draws_a_meshs_layers)
{
    vec3 positions[8] = { { -1, -1, 0.25f }, { -1, 1, 0.25f }, { 1, 1, 0.25f }, { 1, -1, 0.25f },
                          { -1, -1, 0.5f },  { -1, 1, 0.5f },  { 1, 1, 0.5f },  { 1, -1, 0.5f } };
    uint32_t indices[12] = { 0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7 };
    sr_mesh_part parts[2] = { { 0, 2, 0 }, { 2, 2, 1 } };
    sr_material materials[2] = { { .base_color = { 0, 0, 1, 0.5f }, .alpha_mode = SR_ALPHA_BLEND },
                                 { .base_color = { 1, 0, 0, 1 } } };
    sr_mesh mesh = { .vertex_count = 8, .positions = positions, .index_count = 12, .indices = indices,
                     .part_count = 2, .parts = parts, .material_count = 2, .materials = materials };
    sr_framebuffer fb;
    sr_error err = { "" };
    cr_assert(sr_framebuffer_create(&fb, 4, 4, &err) && sr_framebuffer_create_ids(&fb, &err), "%s", err.message);
    for (int shade = 0; shade < 2; shade++) {
        sr_draw_desc desc = { .mesh = &mesh, .shade = shade ? SR_SHADE_ID : SR_SHADE_TEXTURE, .cull = SR_CULL_NONE,
                              .clear = true };
        sr_stats stats = { 0 };
        cr_assert(sr_draw_layered(&fb, &desc, &stats, &err), "%s", err.message);
        cr_assert_eq(stats.triangles, shade ? 2u : 4u, "each triangle drawn is counted once");
        for (int i = 0; i < 16; i++) {
            cr_assert(fb.ids[i] == 3 || fb.ids[i] == 4, "pixel %d shows triangle %u", i, fb.ids[i] - 1);
            cr_assert_eq(fb.depth[i], 0.5f, "pixel %d: depth %g", i, fb.depth[i]);
            cr_assert_eq(fb.color[i], shade ? fb.ids[i] : 0x800080u, "pixel %d: %06x", i, fb.color[i]);
        }
    }
    /* what sr_draw refuses, it refuses here with its one line */
    mesh.materials = NULL;
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_TEXTURE, .cull = SR_CULL_NONE };
    cr_assert_not(sr_draw_layered(&fb, &desc, NULL, &err));
    cr_assert_not_null(strstr(err.message, "no material array"), "%s", err.message);
    sr_framebuffer_destroy(&fb);
}
