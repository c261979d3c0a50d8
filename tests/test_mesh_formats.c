/* sr_mesh_load on the formats Assimp reads, with real files from Debian's
 * assimp-testmodels: the counts, bounds and textures a person would check,
 * the same box as OBJ (own loader) and as glTF and GLB (Assimp) drawing
 * the same coverage and depth, and a broken file getting one error line. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "run_helpers.h"
#include "scene_helpers.h"
#include "softrast_private.h"
#include "temp_dir.h"

#define MODELS "/usr/share/assimp/models/"
#define SIDE 96

static sr_mesh load(const char *path)
{
    sr_mesh m;
    sr_error err = { "" };
    cr_assert(sr_mesh_load(&m, NULL, path, &err), "%s: %s", path, err.message);
    return m;
}

static void expect_bounds(const sr_mesh *m, const float lo[3], const float hi[3], float tol)
{
    vec3 a, b;
    cr_assert(sr_mesh_bounds(m, a, b));
    for (int k = 0; k < 3; k++) {
        cr_expect_float_eq(a[k], lo[k], tol, "lo[%d] = %g, want %g", k, a[k], lo[k]);
        cr_expect_float_eq(b[k], hi[k], tol, "hi[%d] = %g, want %g", k, b[k], hi[k]);
    }
}

Test(mesh_formats, each_format_gives_the_expected_triangles_and_attributes)
{
    static const struct {
        const char *path;
        uint32_t triangles;
        bool uvs, texture;
    } files[] = {
        { MODELS "PLY/cube.ply", 12, false, false },
        { MODELS "PLY/cube_binary.ply", 12, false, false },
        { MODELS "STL/Spider_ascii.stl", 1368, false, false },
        { MODELS "STL/Spider_binary.stl", 1368, false, false },
        { MODELS "glTF2/BoxTextured-glTF/BoxTextured.gltf", 12, true, true },
        { MODELS "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb", 12, true, false }, /* embedded: no file named */
        { MODELS "FBX/box.fbx", 12, false, false },
        { MODELS "Collada/duck.dae", 4212, true, true },
    };
    for (size_t i = 0; i < sizeof files / sizeof *files; i++) {
        sr_mesh m = load(files[i].path);
        cr_expect_eq(sr_mesh_triangle_slots(&m), files[i].triangles, "%s: %u triangles", files[i].path,
                     sr_mesh_triangle_slots(&m));
        cr_expect_not_null(m.normals, "%s: normals are generated when absent", files[i].path);
        cr_expect_eq(m.uvs != NULL, files[i].uvs, "%s: uvs", files[i].path);
        cr_expect_eq(m.texture_path != NULL, files[i].texture, "%s: texture %s", files[i].path,
                     m.texture_path ? m.texture_path : "(none)");
        cr_expect(m.bounded, "%s: bounds stored", files[i].path);
        sr_mesh_free(&m);
    }
}

/* The STL spider in both encodings is the same mesh; the glTF box is the
 * unit cube around the origin. */
Test(mesh_formats, bounds_are_the_models_and_agree_across_encodings)
{
    sr_mesh ascii = load(MODELS "STL/Spider_ascii.stl"), binary = load(MODELS "STL/Spider_binary.stl");
    vec3 lo, hi;
    cr_assert(sr_mesh_bounds(&ascii, lo, hi));
    expect_bounds(&binary, lo, hi, 1e-4f);
    sr_mesh box = load(MODELS "glTF2/BoxTextured-glTF/BoxTextured.gltf");
    expect_bounds(&box, (float[3]){ -0.5f, -0.5f, -0.5f }, (float[3]){ 0.5f, 0.5f, 0.5f }, 1e-6f);
    sr_mesh_free(&ascii);
    sr_mesh_free(&binary);
    sr_mesh_free(&box);
}

static void draw_depth(const sr_mesh *m, sr_framebuffer *fb)
{
    scene_fb_make(fb, SIDE, SIDE);
    sr_camera cam = scene_camera(1.3f, 1.1f, -1.9f, 0.0f, 0.0f, 0.0f, 50.0f, 0.1f, 10.0f);
    sr_draw_desc desc = { .mesh = m, .shade = SR_SHADE_DEPTH };
    scene_camera_desc(&desc, &cam, SIDE, SIDE);
    sr_error err = { "" };
    sr_framebuffer_clear(fb, 0);
    cr_assert(sr_draw(fb, &desc, NULL, &err), "%s", err.message);
}

/* Triangle order and the diagonal each face is split on may differ, so
 * coverage must match exactly and depth to a few float steps. */
Test(mesh_formats, the_same_box_as_obj_gltf_and_glb_draws_the_same_pixels)
{
    sr_mesh obj = load(MODELS "OBJ/box.obj");
    sr_framebuffer ref;
    draw_depth(&obj, &ref);
    cr_assert_gt(scene_count_depth_written(&ref), SIDE * SIDE / 10, "the box covers a good part of the frame");
    static const char *const others[] = { MODELS "glTF2/BoxTextured-glTF/BoxTextured.gltf",
                                          MODELS "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb" };
    for (size_t i = 0; i < sizeof others / sizeof *others; i++) {
        sr_mesh m = load(others[i]);
        sr_framebuffer fb;
        draw_depth(&m, &fb);
        for (int p = 0; p < SIDE * SIDE; p++) {
            bool a = ref.depth[p] < SR_DEPTH_CLEAR, b = fb.depth[p] < SR_DEPTH_CLEAR;
            cr_assert_eq(a, b, "%s: pixel %d covered %d, the OBJ's %d", others[i], p, b, a);
            cr_assert_float_eq(fb.depth[p], ref.depth[p], 1e-6f, "%s: pixel %d depth %.9g, the OBJ's %.9g",
                               others[i], p, fb.depth[p], ref.depth[p]);
        }
        sr_framebuffer_destroy(&fb);
        sr_mesh_free(&m);
    }
    sr_framebuffer_destroy(&ref);
    sr_mesh_free(&obj);
}

Test(mesh_formats, a_broken_file_is_one_error_line_without_assimps_log, .init = temp_dir_make,
     .fini = temp_dir_remove)
{
    write_text(temp_dir, "broken.glb", "glTF\x02\x00\x00\x00 not a real binary glTF");
    write_text(temp_dir, "broken.ply", "ply\nformat ascii 1.0\nelement vertex 99\nend_header\n1 2\n");
    static const char *const names[] = { "broken.glb", "broken.ply", "missing.stl" };
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        char args[600];
        snprintf(args, sizeof args, "render %s/%s --size 8x8", temp_dir, names[i]);
        run_result r = run_softrast(temp_dir, args);
        cr_assert(r.status != 0 && r.status < 128, "%s: exit %d", names[i], r.status);
        cr_assert_eq(count_lines(r.err), 1, "%s: want one line, stderr was: %s", names[i], r.err);
        cr_assert_eq(strncmp(r.err, "softrast: error: ", 17), 0, "%s: %s", names[i], r.err);
        cr_assert_not_null(strstr(r.err, names[i]), "%s: the path is named: %s", names[i], r.err);
    }
}

/* The engine's parts differ only by their materials' base colour: each
 * part names its own material, gray metal, blue caps, and more. */
Test(mesh_formats, each_part_names_its_materials_base_colour)
{
    sr_mesh m = load(MODELS "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
    cr_assert_null(m.colors, "no vertex colours in the file: the colours are the materials'");
    cr_assert_geq(m.material_count, 3u);
    const float *seen[16];
    int distinct = 0;
    bool blue = false;
    for (uint32_t p = 0; p < m.part_count && distinct < 16; p++) {
        cr_assert_lt(m.parts[p].material, m.material_count);
        const float *c = m.materials[m.parts[p].material].base_color;
        bool known = false;
        for (int i = 0; i < distinct && !known; i++)
            known = memcmp(seen[i], c, 3 * sizeof *c) == 0;
        if (!known)
            seen[distinct++] = c;
        blue |= c[2] > 0.5f && c[0] < 0.2f;
    }
    cr_expect_geq(distinct, 3, "%d distinct colours", distinct);
    cr_expect(blue, "the blue caps keep their colour");
    sr_mesh_free(&m);
}

/* Each of the engine's meshes is a part: runs of triangle ids that follow
 * each other and cover every slot, in the file's mesh order. */
Test(mesh_formats, the_parts_of_a_multi_mesh_file_cover_its_triangles_in_order)
{
    sr_mesh m = load(MODELS "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
    cr_assert_gt(m.part_count, 10, "%u parts", m.part_count);
    uint32_t next = 0;
    for (uint32_t i = 0; i < m.part_count; i++) {
        cr_assert_eq(m.parts[i].first_triangle, next, "part %u starts at %u", i, m.parts[i].first_triangle);
        cr_assert_gt(m.parts[i].triangle_count, 0);
        next += m.parts[i].triangle_count;
    }
    cr_assert_eq(next, sr_mesh_triangle_slots(&m));
    sr_mesh one = load(MODELS "STL/triangle.stl");
    cr_assert_eq(one.part_count, 1);
    cr_assert_eq(one.parts[0].triangle_count, 1);
    sr_mesh_free(&one);
    sr_mesh_free(&m);
}

/* The .glb carries the image the .gltf names beside it: decoded from memory
 * it is the same texels, and the textured box draws the same pixels. */
Test(mesh_formats, an_embedded_texture_is_the_image_the_gltf_names)
{
    sr_mesh glb, gltf;
    sr_texture inside, beside;
    sr_error err = { "" };
    cr_assert(sr_mesh_load(&glb, &inside, MODELS "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb", &err), "%s",
              err.message);
    cr_assert(sr_mesh_load(&gltf, NULL, MODELS "glTF2/BoxTextured-glTF/BoxTextured.gltf", &err), "%s", err.message);
    cr_assert_not_null(inside.texels, "the .glb's texture is decoded");
    cr_assert_null(glb.texture_path);
    /* One part, its material the box's (Assimp adds a default one after it). */
    sr_material *in_glb = &glb.materials[glb.parts[0].material], *in_gltf = &gltf.materials[gltf.parts[0].material];
    cr_assert_eq(in_glb->texture, &inside, "its material draws the decoded texture");
    cr_assert_not_null(in_gltf->texture_path, "the .gltf's names it beside");
    cr_assert_str_eq(in_gltf->texture_path, gltf.texture_path);
    cr_assert(sr_texture_load(&beside, gltf.texture_path, &err), "%s", err.message);
    in_gltf->texture = &beside;
    cr_assert_eq(inside.width, beside.width);
    cr_assert_eq(inside.height, beside.height);
    cr_assert_eq(memcmp(inside.texels, beside.texels, sizeof(uint32_t) * (size_t)beside.width * beside.height), 0);
    sr_framebuffer a, b;
    scene_fb_make(&a, SIDE, SIDE);
    scene_fb_make(&b, SIDE, SIDE);
    sr_camera cam = scene_camera(1.3f, 1.1f, -1.9f, 0.0f, 0.0f, 0.0f, 50.0f, 0.1f, 10.0f);
    sr_draw_desc da = { .mesh = &glb, .shade = SR_SHADE_TEXTURE, .texture = &inside };
    sr_draw_desc db = { .mesh = &gltf, .shade = SR_SHADE_TEXTURE, .texture = &beside };
    scene_camera_desc(&da, &cam, SIDE, SIDE);
    scene_camera_desc(&db, &cam, SIDE, SIDE);
    sr_framebuffer_clear(&a, 0);
    sr_framebuffer_clear(&b, 0);
    cr_assert(sr_draw(&a, &da, NULL, &err) && sr_draw(&b, &db, NULL, &err), "%s", err.message);
    cr_assert_gt(scene_count_drawn(&a), SIDE * SIDE / 10);
    cr_assert_eq(memcmp(a.color, b.color, sizeof(uint32_t) * SIDE * SIDE), 0, "the two boxes draw alike");
    sr_framebuffer_destroy(&a);
    sr_framebuffer_destroy(&b);
    sr_texture_free(&inside);
    sr_texture_free(&beside);
    sr_mesh_free(&glb);
    sr_mesh_free(&gltf);
}

/* glTF's materials as the file means them: ClearCoatTest's colour factors
 * (linear, as glTF stores them), its BLEND material with an alpha texture
 * beside the file, each texture file decoded with its alpha; the milk
 * truck's windows keep their own untextured material beside the body's
 * texture. */
Test(mesh_formats, gltf_materials_keep_their_factors_alpha_modes_and_textures)
{
    sr_mesh coat = load(MODELS "glTF2/ClearCoat-glTF/ClearCoatTest.gltf");
    bool red = false, blend = false;
    for (uint32_t i = 0; i < coat.material_count; i++) {
        const sr_material *m = &coat.materials[i];
        red |= m->base_color[0] == 0.5f && m->base_color[1] < 0.05f;
        if (m->alpha_mode == SR_ALPHA_BLEND && m->texture_path) {
            blend = strstr(m->texture_path, "PartialCoating_Alpha.png") != NULL;
            sr_texture t;
            sr_error err;
            cr_assert(sr_texture_load(&t, m->texture_path, &err), "%s", err.message);
            cr_expect(t.alpha, "the alpha texture keeps its alpha");
            sr_texture_free(&t);
        }
    }
    cr_expect(red, "a red factor");
    cr_expect(blend, "the BLEND material and its texture");
    sr_mesh_free(&coat);
    sr_mesh truck = load(MODELS "glTF/CesiumMilkTruck/CesiumMilkTruck.gltf");
    bool textured = false, plain = false;
    for (uint32_t p = 0; p < truck.part_count; p++) {
        const sr_material *m = &truck.materials[truck.parts[p].material];
        textured |= m->texture_path != NULL;
        plain |= m->texture_path == NULL && m->texture == NULL;
    }
    cr_expect(textured && plain, "the body textured, the windows not");
    sr_mesh_free(&truck);
}
