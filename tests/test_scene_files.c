/* Scenes drawn as their files mean them (issue 33, first slice): `softrast
 * info`, the upright turn, textures found as people expect, a usemtl
 * without a material, mirrored meshes. Each scene is written at test time. */
#include <cJSON.h>
#include <math.h>
#include <criterion/criterion.h>
#include <string.h>
#include <sys/stat.h>

#include "app/upright.h"
#include "case_format.h"
#include "io/texture_find.h"
#include "run_helpers.h"
#include "softrast_private.h"
#include "temp_dir.h"

#define SIDE 64

TestSuite(scene_files, .init = temp_dir_make, .fini = temp_dir_remove);

/* A triangle 2 wide at z = 0 and 3 tall up +z, facing -y: upright for a
 * +z-up file, Blender's front toward the viewer. */
static const char TRIANGLE_STL[] = "solid t\nfacet normal 0 -1 0\nouter loop\nvertex -1 0 0\nvertex 1 0 0\n"
                                   "vertex 0 0 3\nendloop\nendfacet\nendsolid t\n";

static const char TRIANGLE_ZUP_DAE[] =
    "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
    "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
    "<asset><unit name=\"meter\" meter=\"1\"/><up_axis>Z_UP</up_axis></asset>\n"
    "<library_geometries><geometry id=\"tri\"><mesh>\n"
    "<source id=\"pos\"><float_array id=\"pos-a\" count=\"9\">-1 0 0 1 0 0 0 0 3</float_array>\n"
    "<technique_common><accessor source=\"#pos-a\" count=\"3\" stride=\"3\"><param name=\"X\" type=\"float\"/>"
    "<param name=\"Y\" type=\"float\"/><param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
    "<vertices id=\"v\"><input semantic=\"POSITION\" source=\"#pos\"/></vertices>\n"
    "<triangles count=\"1\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/><p>0 1 2</p></triangles>\n"
    "</mesh></geometry></library_geometries>\n"
    "<library_visual_scenes><visual_scene id=\"s\"><node id=\"n\"><instance_geometry url=\"#tri\"/></node>"
    "</visual_scene></library_visual_scenes>\n"
    "<scene><instance_visual_scene url=\"#s\"/></scene>\n</COLLADA>\n";

static const char TRIANGLE_OBJ[] = "v -1 0 0\nv 1 0 0\nv 0 0 3\nf 1 2 3\n";

static cJSON *info_json(const char *name)
{
    char args[1024];
    snprintf(args, sizeof args, "info --json %s/%s", temp_dir, name);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "softrast %s: %s", args, r.err);
    cJSON *o = cJSON_Parse(r.out);
    cr_assert_not_null(o, "not JSON: %s", r.out);
    return o;
}

static const char *json_string(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    cr_assert(cJSON_IsString(v), "no string \"%s\"", key);
    return v->valuestring;
}

/* Writes text as `name`; its info --json, whose up axis must be `axis`,
 * read or guessed as `found` says. */
static cJSON *info_with_up(const char *name, const char *text, const char *axis, const char *found)
{
    write_text(temp_dir, name, text);
    cJSON *o = info_json(name);
    cr_assert_str_eq(json_string(o, "up_axis"), axis, "%s", name);
    cr_assert_str_eq(json_string(o, "up_found"), found, "%s", name);
    return o;
}

/* Drawn pixels in each row of an id render (--cull none: facing aside). */
typedef struct row_counts {
    int count[SIDE];
    int top, bottom; /* first and last rows drawn */
} row_counts;

static row_counts render_rows(const char *name, const char *extra)
{
    char args[1024], out[600];
    snprintf(out, sizeof out, "%s/ids.png", temp_dir);
    snprintf(args, sizeof args, "render %s/%s --size %dx%d --shade id --cull none --quiet --out %s %s", temp_dir,
             name, SIDE, SIDE, out, extra);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "softrast %s: %s", args, r.err);
    sr_texture image;
    sr_error err;
    cr_assert(sr_texture_load(&image, out, &err), "%s", err.message);
    row_counts rows = { .top = -1, .bottom = -1 };
    for (int y = 0; y < SIDE; y++) {
        for (int x = 0; x < SIDE; x++)
            rows.count[y] += image.texels[y * SIDE + x] != 0;
        if (rows.count[y] && rows.top < 0)
            rows.top = y;
        if (rows.count[y])
            rows.bottom = y;
    }
    sr_texture_free(&image);
    cr_assert(rows.top >= 0, "nothing drawn for %s", name);
    return rows;
}

/* The apex (+z of the file) is narrow and on top, the base wide below. */
static void assert_apex_up(const row_counts *rows)
{
    cr_assert_lt(rows->count[rows->top], rows->count[rows->bottom], "apex row %d has %d pixels, base row %d has %d",
                 rows->top, rows->count[rows->top], rows->bottom, rows->count[rows->bottom]);
    cr_assert_gt(rows->bottom - rows->top, SIDE / 2, "the triangle should stand tall: rows %d to %d", rows->top,
                 rows->bottom);
}

Test(scene_files, info_json_says_an_stl_is_guessed_z_up)
{
    cJSON *o = info_with_up("t.stl", TRIANGLE_STL, "+z", "guessed");
    cr_assert_eq(cJSON_GetObjectItem(o, "triangles")->valueint, 1);
    const cJSON *file_max = cJSON_GetObjectItem(cJSON_GetObjectItem(o, "bounds_file"), "max");
    const cJSON *world_min = cJSON_GetObjectItem(cJSON_GetObjectItem(o, "bounds_world"), "min");
    cr_assert_eq(cJSON_GetArrayItem(file_max, 2)->valuedouble, 3.0);   /* the file's frame */
    cr_assert_eq(cJSON_GetArrayItem(world_min, 2)->valuedouble, -3.0); /* softrast's: z negated */
    cJSON_Delete(o);
}

/* A triangle in the plane z = 0 of its OBJ: its z bounds are 0 in both
 * frames, printed and in JSON, never -0 (the file's z is the world's
 * negated, and -(0) is -0). */
Test(scene_files, info_prints_a_zero_bound_as_0_not_minus_0)
{
    write_text(temp_dir, "flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    char args[1024];
    snprintf(args, sizeof args, "info %s/flat.obj", temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "softrast %s: %s", args, r.err);
    cr_assert_not_null(strstr(r.out, "bounds: file's frame 0,0,0 to 1,1,0; softrast's world (z negated) 0,0,0 to "
                                     "1,1,0\n"),
                       "%s", r.out);
    cJSON *o = info_json("flat.obj");
    char *text = cJSON_PrintUnformatted(o);
    cr_assert_not_null(text);
    cr_assert_not_null(strstr(text, "\"bounds_file\":{\"min\":[0,0,0],\"max\":[1,1,0]}"), "%s", text);
    for (int k = 0; k < 2; k++) {
        const cJSON *box = cJSON_GetObjectItem(o, k ? "bounds_world" : "bounds_file");
        for (int m = 0; m < 2; m++) {
            double z = cJSON_GetArrayItem(cJSON_GetObjectItem(box, m ? "max" : "min"), 2)->valuedouble;
            cr_assert(z == 0.0 && !signbit(z), "%s %s z is %g", k ? "world" : "file", m ? "max" : "min", z);
        }
    }
    cJSON_free(text);
    cJSON_Delete(o);
}

Test(scene_files, a_z_up_stl_stands_upright_by_default)
{
    write_text(temp_dir, "t.stl", TRIANGLE_STL);
    row_counts rows = render_rows("t.stl", "");
    assert_apex_up(&rows);
}

Test(scene_files, up_axis_minus_z_turns_it_upside_down)
{
    write_text(temp_dir, "t.stl", TRIANGLE_STL);
    row_counts rows = render_rows("t.stl", "--up-axis -z");
    cr_assert_gt(rows.count[rows.top], rows.count[rows.bottom], "the base should be on top");
}

Test(scene_files, an_obj_is_y_up_unless_told)
{
    cJSON *o = info_with_up("t.obj", TRIANGLE_OBJ, "+y", "guessed");
    cr_assert_str_eq(json_string(o, "format"), "Wavefront OBJ");
    cJSON_Delete(o);
    row_counts rows = render_rows("t.obj", "--up-axis z");
    assert_apex_up(&rows);
}

/* Assimp turns a COLLADA Z_UP scene to +y itself: what arrives is y up. */
Test(scene_files, a_z_up_collada_arrives_upright)
{
    cJSON *o = info_with_up("t.dae", TRIANGLE_ZUP_DAE, "+y", "read");
    cJSON_Delete(o);
    row_counts rows = render_rows("t.dae", "");
    assert_apex_up(&rows);
}

/* The pinhole camera speaks the file's frame: the turn is the look-at
 * camera's alone, and --up-axis with a pose is refused. */
Test(scene_files, up_axis_is_the_look_at_cameras)
{
    write_text(temp_dir, "t.stl", TRIANGLE_STL);
    char args[1024];
    snprintf(args, sizeof args,
             "render %s/t.stl --up-axis z --pose-w2c 1,0,0,0,0,1,0,0,0,0,1,5,0,0,0,1 --out %s/p.png", temp_dir,
             temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_neq(r.status, 0);
    cr_assert_not_null(strstr(r.err, "--up-axis"), "%s", r.err);
    cr_assert_eq(count_lines(r.err), 1, "%s", r.err);
}

static void write_red_png(const char *name)
{
    uint32_t red[4] = { 0xFF0000, 0xFF0000, 0xFF0000, 0xFF0000 };
    char path[600];
    sr_error err;
    snprintf(path, sizeof path, "%s/%s", temp_dir, name);
    cr_assert(sr_image_write_png(path, red, 2, 2, &err), "%s", err.message);
}

static const char QUAD_OBJ[] = "mtllib m.mtl\nusemtl skin\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                               "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n";

/* Renders name (in temp_dir) at w x h with the extra options into image,
 * asserting it draws without a warning. */
static void render_image(const char *name, int w, int h, const char *extra, sr_texture *image)
{
    char args[1024], out[600];
    snprintf(out, sizeof out, "%s/image.png", temp_dir);
    snprintf(args, sizeof args, "render %s/%s --size %dx%d --cull none --quiet --out %s %s", temp_dir, name, w, h,
             out, extra);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_assert_eq(r.err[0], '\0', "no warning expected: %s", r.err);
    sr_error err;
    cr_assert(sr_texture_load(image, out, &err), "%s", err.message);
}

/* The texture's colour at the centre of a texture-shaded render. */
static uint32_t centre_texel(const char *obj)
{
    sr_texture image;
    render_image(obj, 16, 16, "--shade texture", &image);
    uint32_t c = image.texels[8 * 16 + 8];
    sr_texture_free(&image);
    return c;
}

Test(scene_files, a_texture_named_in_another_case_is_found)
{
    write_text(temp_dir, "m.obj", QUAD_OBJ);
    write_text(temp_dir, "m.mtl", "newmtl skin\nmap_Kd IMAGE1.JPG\n");
    write_red_png("image1.jpg"); /* a PNG by its bytes, as some files are */
    cJSON *o = info_json("m.obj");
    const cJSON *t = cJSON_GetArrayItem(cJSON_GetObjectItem(o, "textures"), 0);
    cr_assert_str_eq(json_string(t, "name"), "IMAGE1.JPG");
    cr_assert_str_eq(json_string(t, "status"), "found");
    cr_assert_not_null(strstr(json_string(t, "path"), "/image1.jpg"));
    const cJSON *part = cJSON_GetArrayItem(cJSON_GetObjectItem(o, "parts"), 0);
    cr_assert_str_eq(json_string(part, "material"), "skin");
    cr_assert_eq(cJSON_GetObjectItem(part, "texture")->valueint, 0);
    cJSON_Delete(o);
    cr_assert_eq(centre_texel("m.obj"), 0xFF0000u);
}

Test(scene_files, a_windows_path_is_found_by_base_name_in_textures)
{
    write_text(temp_dir, "m.obj", QUAD_OBJ);
    write_text(temp_dir, "m.mtl", "newmtl skin\nmap_Kd D:\\projects\\art\\Skin.tga\n");
    char dir[600];
    snprintf(dir, sizeof dir, "%s/Textures", temp_dir);
    cr_assert_eq(mkdir(dir, 0700), 0);
    write_red_png("Textures/skin.png");
    cr_assert_eq(centre_texel("m.obj"), 0xFF0000u);
}

/* earthCylindrical.DAE names "..\\LWO\\…\\EarthCylindric.jpg" where
 * earthCylindric.jpg lies: the folder a path names is searched in any
 * case too, before the model's own. */
Test(scene_files, a_texture_in_the_folder_it_names_is_found_in_any_case)
{
    char dir[600], model[640];
    snprintf(dir, sizeof dir, "%s/maps", temp_dir);
    cr_assert_eq(mkdir(dir, 0700), 0);
    write_red_png("maps/earth.jpg");
    write_red_png("Earth.png"); /* beside the model: found only by base name, after */
    snprintf(model, sizeof model, "%s/m.dae", temp_dir);
    char *found = sr_texture_find(model, "maps\\Earth.jpg");
    cr_assert_not_null(found);
    cr_expect_not_null(strstr(found, "/maps/earth.jpg"), "%s", found);
    free(found);
}

/* The upright turn takes the up axis to +y and the front to +z (facing
 * the default camera), for every pair of axes, as a rotation; a front
 * along the up axis, or none, is the up axis's default; the loader's z
 * flip conjugates it. */
Test(scene_files, the_upright_turn_takes_up_to_y_and_front_to_z)
{
    for (int up = 0; up < SR_AXIS_COUNT; up++)
        for (int front = 0; front <= SR_AXIS_COUNT; front++) {
            int want_front = front < SR_AXIS_COUNT && front / 2 != up / 2 ? front : (int)sr_upright_default_front((sr_axis)up);
            cr_assert_neq(want_front / 2, up / 2);
            mat4 plain, flipped;
            sr_upright_matrix((sr_axis)up, (sr_axis)front, false, plain);
            sr_upright_matrix((sr_axis)up, (sr_axis)front, true, flipped);
            vec3 u = { 0 }, f = { 0 }, tu, tf;
            u[up / 2] = up % 2 ? -1.0f : 1.0f;
            f[want_front / 2] = want_front % 2 ? -1.0f : 1.0f;
            glm_mat4_mulv3(plain, u, 0.0f, tu);
            glm_mat4_mulv3(plain, f, 0.0f, tf);
            cr_expect(glm_vec3_eqv(tu, (vec3){ 0, 1, 0 }) && glm_vec3_eqv(tf, (vec3){ 0, 0, 1 }),
                      "up %s front %s: up to %g,%g,%g, front to %g,%g,%g", SR_AXIS_SIGNED[up],
                      SR_AXIS_SIGNED[want_front], tu[0], tu[1], tu[2], tf[0], tf[1], tf[2]);
            cr_expect_float_eq(glm_mat4_det(plain), 1.0f, 0.0f, "a rotation");
            for (int r = 0; r < 3; r++)
                for (int c = 0; c < 3; c++)
                    cr_expect_eq(flipped[c][r], ((r == 2) != (c == 2) ? -1.0f : 1.0f) * plain[c][r]);
        }
}

/* A small MD2 (Quake 2's frame: +z up, models facing +x) of two
 * triangles 2 wide and 2 tall, wound as Quake winds them (clockwise seen
 * from outside): id 1 facing +x, the model's front; id 2 facing -y, the
 * model's right, where a front of +z after Assimp's turn to +y up lies. */
static void write_two_faced_md2(const char *name)
{
    enum { HEADER = 68, ST = 4, TRIS = 2 * 12, FRAME = 40 + 6 * 4, END = HEADER + ST + TRIS + FRAME + 4 };
    const int32_t header[16] = { 8, 8, 8, FRAME, 0, 6, 1, 2, 1, 1, HEADER, HEADER, HEADER + ST, HEADER + ST + TRIS,
                                 HEADER + ST + TRIS + FRAME, END };
    const uint16_t tris[12] = { 1, 0, 2, 0, 0, 0, 4, 3, 5, 0, 0, 0 };
    const float scale_translate[6] = { 1, 1, 1, -1, -1, 0 };
    /* + translate: (0,-1,0) (0,1,0) (0,0,2) at x = 0; (-1,3,0) (1,3,0) (0,3,2) at y = 3 */
    const uint8_t verts[6][4] = { { 1, 0, 0 }, { 1, 2, 0 }, { 1, 1, 2 }, { 0, 4, 0 }, { 2, 4, 0 }, { 1, 4, 2 } };
    uint8_t file[END] = { 'I', 'D', 'P', '2' }; /* x86: the format's little-endian words as they lie */
    memcpy(file + 4, header, sizeof header);
    memcpy(file + HEADER + ST, tris, sizeof tris);
    memcpy(file + HEADER + ST + TRIS, scale_translate, sizeof scale_translate);
    memcpy(file + HEADER + ST + TRIS + 40, verts, sizeof verts);
    char path[600];
    snprintf(path, sizeof path, "%s/%s", temp_dir, name);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    cr_assert_eq(fwrite(file, sizeof file, 1, f), 1u);
    fclose(f);
}

/* The default camera sees an MD2 from its front (+x), not its side. */
Test(scene_files, an_md2_faces_the_default_camera)
{
    write_two_faced_md2("two.md2");
    cJSON *o = info_json("two.md2");
    cr_expect_str_eq(json_string(o, "up_axis"), "+y");
    cr_expect_str_eq(json_string(o, "front_axis"), "+x");
    cJSON_Delete(o);
    char args[1024], out[600];
    snprintf(out, sizeof out, "%s/ids.png", temp_dir);
    snprintf(args, sizeof args, "render %s/two.md2 --size %dx%d --shade id --quiet --out %s", temp_dir, SIDE, SIDE, out);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "softrast %s: %s", args, r.err);
    sr_texture image;
    sr_error err;
    cr_assert(sr_texture_load(&image, out, &err), "%s", err.message);
    int seen[3] = { 0 };
    for (int i = 0; i < SIDE * SIDE; i++)
        seen[(image.texels[i] & 0xFFFFFFu) < 3 ? image.texels[i] & 0xFFFFFFu : 0]++;
    sr_texture_free(&image);
    cr_expect_gt(seen[1], SIDE * SIDE / 40, "the front: %d pixels", seen[1]);
    cr_expect_eq(seen[2], 0, "the side facing away: %d pixels", seen[2]);
}

/* An X3D url list, joined by Assimp as "a""b": the first name found. */
Test(scene_files, an_x3d_url_list_is_its_first_texture_found)
{
    char model[640];
    snprintf(model, sizeof model, "%s/scene.x3d", temp_dir);
    write_red_png("b.png");
    char *found = sr_texture_find(model, "a.png\"\"b.png\"\"c.gif");
    cr_assert_not_null(found);
    cr_expect_not_null(strstr(found, "/b.png"), "%s", found);
    free(found);
    write_red_png("a.png");
    found = sr_texture_find(model, "a.png\"\"b.png");
    cr_assert_not_null(found);
    cr_expect_not_null(strstr(found, "/a.png"), "%s", found);
    free(found);
    cr_expect_null(sr_texture_find(model, "c.gif\"\"d.gif"), "neither lies beside it");
}

/* Assimp names an MD2 skin the file does not name "$texture_dummy.bmp";
 * viewers find sydney.md2's skin as sydney.bmp beside it. */
Test(scene_files, an_unnamed_md2_skin_is_the_models_stem)
{
    char model[640];
    write_red_png("Sydney.BMP");
    snprintf(model, sizeof model, "%s/sydney.md2", temp_dir);
    char *found = sr_texture_find(model, "$texture_dummy.bmp");
    cr_assert_not_null(found);
    cr_expect_not_null(strstr(found, "/Sydney.BMP"), "%s", found);
    free(found);
    snprintf(model, sizeof model, "%s/faerie.md2", temp_dir);
    cr_expect_null(sr_texture_find(model, "$texture_dummy.bmp"), "no faerie.* lies beside it");
}

Test(scene_files, a_missing_texture_is_one_warning_and_drawn_untextured)
{
    write_text(temp_dir, "m.obj", QUAD_OBJ);
    write_text(temp_dir, "m.mtl", "newmtl skin\nmap_Kd gone.png\n");
    char args[1024];
    snprintf(args, sizeof args, "render %s/m.obj --size 16x16 --quiet --out %s/o.png", temp_dir, temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_assert_eq(count_lines(r.err), 1, "%s", r.err);
    cr_assert_eq(strncmp(r.err, "softrast: warning: ", 19), 0, "%s", r.err);
    cr_assert_not_null(strstr(r.err, "gone.png"), "%s", r.err);
    cJSON *o = info_json("m.obj");
    const cJSON *t = cJSON_GetArrayItem(cJSON_GetObjectItem(o, "textures"), 0);
    cr_assert_str_eq(json_string(t, "status"), "missing");
    cJSON_Delete(o);
}

Test(scene_files, a_usemtl_without_a_material_is_one_warning)
{
    write_text(temp_dir, "m.obj", "mtllib m.mtl\nusemtl nowhere\nv -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
    write_text(temp_dir, "m.mtl", "newmtl skin\n");
    char args[1024];
    snprintf(args, sizeof args, "render %s/m.obj --size 16x16 --quiet --out %s/o.png", temp_dir, temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_assert_eq(count_lines(r.err), 1, "%s", r.err);
    cr_assert_eq(strncmp(r.err, "softrast: warning: ", 19), 0, "%s", r.err);
    cr_assert_not_null(strstr(r.err, "m.obj:2: material 'nowhere' is not in any material library"), "%s", r.err);
}

/* A glTF node with scale -1 mirrors its tetrahedron: drawn right side out,
 * back-face culling changes nothing, as glTF requires. */
static const char MIRRORED_GLTF[] =
    "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
    "\"nodes\":[{\"mesh\":0,\"scale\":[-1,1,1]}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},"
    "\"indices\":1}]}],\"buffers\":[{\"byteLength\":72,\"uri\":\"data:application/octet-stream;base64,"
    "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAACAAEAAAABAAMAAAADAAIAAQACAAMA\"}],"
    "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},{\"buffer\":0,\"byteOffset\":48,"
    "\"byteLength\":24}],\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
    "\"min\":[0,0,0],\"max\":[1,1,1]},{\"bufferView\":1,\"componentType\":5123,\"count\":12,\"type\":\"SCALAR\"}]}";

Test(scene_files, a_mirrored_node_keeps_its_faces_outward)
{
    write_text(temp_dir, "m.gltf", MIRRORED_GLTF);
    cJSON *o = info_json("m.gltf");
    cr_assert_eq(cJSON_GetObjectItem(o, "mirrored_meshes")->valueint, 1);
    cJSON_Delete(o);
    char args[1024];
    const char *const culls[] = { "back", "none" };
    sr_texture depth[2];
    for (int i = 0; i < 2; i++) {
        char out[600];
        sr_error err;
        snprintf(out, sizeof out, "%s/%s.png", temp_dir, culls[i]);
        snprintf(args, sizeof args, "render %s/m.gltf --size 32x32 --eye 2,3,-4 --target 0,0,0 --shade depth --cull %s "
                 "--quiet --out %s", temp_dir, culls[i], out);
        run_result r = run_softrast(temp_dir, args);
        cr_assert_eq(r.status, 0, "%s", r.err);
        cr_assert(sr_texture_load(&depth[i], out, &err), "%s", err.message);
    }
    cr_assert_eq(memcmp(depth[0].texels, depth[1].texels, 32 * 32 * sizeof(uint32_t)), 0,
                 "culling back faces changed the picture: the mirrored mesh is inside out");
    sr_texture_free(&depth[0]);
    sr_texture_free(&depth[1]);
}

/* Two usemtl runs, each drawn with its own material in one draw: a Kd
 * colour left, a texture right (before materials, the first map_Kd lay
 * over the whole mesh); `info` lists both parts. */
Test(scene_files, each_material_of_an_obj_draws_its_own_part)
{
    uint32_t blue[4] = { 0x0000FF, 0x0000FF, 0x0000FF, 0x0000FF };
    char path[600], args[1024], out[600];
    sr_error err;
    snprintf(path, sizeof path, "%s/blue.png", temp_dir);
    cr_assert(sr_image_write_png(path, blue, 2, 2, &err), "%s", err.message);
    write_text(temp_dir, "m.mtl", "newmtl red\nKd 1 0 0\nnewmtl cloth\nKd 0.5 0.5 0.5\nmap_Kd blue.png\n");
    write_text(temp_dir, "m.obj", "mtllib m.mtl\nv -2 -1 0\nv 0 -1 0\nv 0 1 0\nv -2 1 0\nv 2 -1 0\nv 2 1 0\n"
                                  "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                  "usemtl red\nf 1/1 2/2 3/3 4/4\nusemtl cloth\nf 2/1 5/2 6/3 3/4\n");
    snprintf(out, sizeof out, "%s/two.png", temp_dir);
    snprintf(args, sizeof args, "render %s/m.obj --size 64x32 --shade texture --cull none --quiet --out %s", temp_dir,
             out);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_assert_eq(r.err[0], '\0', "no warning expected: %s", r.err);
    sr_texture image;
    cr_assert(sr_texture_load(&image, out, &err), "%s", err.message);
    /* The texture is drawn as it is: its map_Kd over white, not Kd. */
    uint32_t left = image.texels[16 * 64 + 24], right = image.texels[16 * 64 + 40];
    sr_texture_free(&image);
    cr_expect(left == 0xFF0000u && right == 0x0000FFu, "left %06x, right %06x", left, right);
    cJSON *o = info_json("m.obj");
    const cJSON *parts = cJSON_GetObjectItem(o, "parts");
    cr_assert_eq(cJSON_GetArraySize(parts), 2);
    cr_expect_str_eq(json_string(cJSON_GetArrayItem(parts, 0), "material"), "red");
    cr_expect_str_eq(json_string(cJSON_GetArrayItem(parts, 1), "material"), "cloth");
    cJSON_Delete(o);
}

/* A thousand materials naming one missing texture: one warning, as the
 * file is looked for once, and each part drawn in its colour. */
Test(scene_files, a_thousand_materials_sharing_a_missing_texture_warn_once)
{
    enum { MATERIALS = 1000 };
    static char mtl[MATERIALS * 48], obj[MATERIALS * 32 + 256];
    size_t m = 0, o = (size_t)snprintf(obj, sizeof obj, "mtllib m.mtl\nv -1 -1 0\nv 1 -1 0\nv 0 1 0\n");
    for (int i = 0; i < MATERIALS; i++) {
        m += (size_t)snprintf(mtl + m, sizeof mtl - m, "newmtl m%d\nKd 1 0 0\nmap_Kd gone.png\n", i);
        o += (size_t)snprintf(obj + o, sizeof obj - o, "usemtl m%d\nf 1 2 3\n", i);
    }
    write_text(temp_dir, "m.mtl", mtl);
    write_text(temp_dir, "m.obj", obj);
    char args[1024];
    snprintf(args, sizeof args, "render %s/m.obj --size 16x16 --cull none --quiet --out %s/o.png", temp_dir,
             temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "%s", r.err);
    /* Only warnings counted: a slow build (the sanitizers') adds the
     * loader's progress lines. */
    const char *first = strstr(r.err, "softrast: warning: ");
    cr_assert_not_null(first, "%s", r.err);
    cr_expect_null(strstr(first + 1, "softrast: warning: "), "more than one warning: %s", r.err);
    cr_expect_not_null(strstr(first, "gone.png"), "%s", r.err);
}

/* ---- glTF and AMF materials ---- */

/* Two quads facing +z, side by side (x -2..0 and 0..2, y -1..1), each a
 * primitive of its own with uvs 0..1, in two.bin beside two.gltf; their
 * materials are the JSON array `materials` (the left quad's first), which
 * may use texture 0, red.png. */
static void write_two_quads(const char *materials)
{
    write_red_png("red.png");
    struct {
        float pos[8][3], uv[8][2];
        uint16_t idx[6];
    } bin = { { { -2, -1, 0 }, { 0, -1, 0 }, { 0, 1, 0 }, { -2, 1, 0 }, { 0, -1, 0 }, { 2, -1, 0 }, { 2, 1, 0 }, { 0, 1, 0 } },
              { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 }, { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } },
              { 0, 1, 2, 0, 2, 3 } };
    char path[600], gltf[4096];
    snprintf(path, sizeof path, "%s/two.bin", temp_dir);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    cr_assert_eq(fwrite(&bin, sizeof bin, 1, f), 1u);
    fclose(f);
    snprintf(gltf, sizeof gltf,
             "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":2},\"indices\":4,"
             "\"material\":0},{\"attributes\":{\"POSITION\":1,\"TEXCOORD_0\":3},\"indices\":4,\"material\":1}]}],"
             "\"materials\":%s,\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"red.png\"}],\"buffers\":[{\"byteLength\":%zu,\"uri\":\"two.bin\"}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":96},{\"buffer\":0,\"byteOffset\":96,"
             "\"byteLength\":64},{\"buffer\":0,\"byteOffset\":160,\"byteLength\":12}],\"accessors\":["
             "{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\",\"min\":[-2,-1,0],\"max\":[0,1,0]},"
             "{\"bufferView\":0,\"byteOffset\":48,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\",\"min\":[0,-1,0],"
             "\"max\":[2,1,0]},{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},"
             "{\"bufferView\":1,\"byteOffset\":32,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},"
             "{\"bufferView\":2,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}]}",
             materials, sizeof bin);
    write_text(temp_dir, "two.gltf", gltf);
}

/* The colours at the middle of the left and right quads of two.gltf,
 * texture-shaded and seen face on (the quads span pixels 18 to 45), are
 * these. */
static void expect_left_and_right(uint32_t left, uint32_t right)
{
    sr_texture image;
    render_image("two.gltf", 64, 32, "--shade texture --eye 0,0,-4", &image);
    uint32_t l = image.texels[16 * 64 + 22] & 0xFFFFFFu, r = image.texels[16 * 64 + 42] & 0xFFFFFFu;
    sr_texture_free(&image);
    cr_expect(l == left && r == right, "left %06x, right %06x", l, r);
}

Test(scene_files, each_material_of_a_gltf_draws_its_own_quad)
{
    write_two_quads("[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,1,1]}},"
                    "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}]");
    expect_left_and_right(0x0000FFu, 0xFF0000u);
    cJSON *o = info_json("two.gltf");
    const cJSON *parts = cJSON_GetObjectItem(o, "parts");
    cr_assert_eq(cJSON_GetArraySize(parts), 2);
    cr_expect(cJSON_IsNull(cJSON_GetObjectItem(cJSON_GetArrayItem(parts, 0), "texture")));
    cr_expect_eq(cJSON_GetObjectItem(cJSON_GetArrayItem(parts, 1), "texture")->valueint, 0);
    cJSON_Delete(o);
}

/* ClearCoatTest.gltf's labels: a black base colour and an emissive
 * texture. Lambert has no emission: the texture is drawn in its place
 * (before, the labels were black on black); a black material without one
 * stays black. */
Test(scene_files, a_material_shown_by_emission_draws_its_emissive_texture)
{
    write_two_quads("[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1]}},"
                    "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1]},\"emissiveFactor\":[1,1,1],"
                    "\"emissiveTexture\":{\"index\":0}}]");
    expect_left_and_right(0x000000u, 0xFF0000u);
    cJSON *o = info_json("two.gltf");
    const cJSON *t = cJSON_GetArrayItem(cJSON_GetObjectItem(o, "textures"), 0);
    cr_assert_str_eq(json_string(t, "name"), "red.png");
    cr_assert_str_eq(json_string(t, "status"), "found");
    cJSON_Delete(o);
}

/* An AMF triangle in the build plate (z = 0, facing +z: up), of vertex
 * colours when `color` is given (an <r><g><b> body), else of none. */
static void write_amf(const char *color)
{
    char text[2048], vertex_color[160] = "";
    if (color)
        snprintf(vertex_color, sizeof vertex_color, "<color>%s</color>", color);
    snprintf(text, sizeof text,
             "<?xml version=\"1.0\"?>\n<amf><object id=\"1\"><mesh><vertices>"
             "<vertex>%s<coordinates><x>-1</x><y>-1</y><z>0</z></coordinates></vertex>"
             "<vertex>%s<coordinates><x>1</x><y>-1</y><z>0</z></coordinates></vertex>"
             "<vertex>%s<coordinates><x>0</x><y>1</y><z>0</z></coordinates></vertex></vertices><volume>"
             "<triangle><v1>0</v1><v2>1</v2><v3>2</v3></triangle></volume></mesh></object></amf>\n",
             vertex_color, vertex_color, vertex_color);
    write_text(temp_dir, "t.amf", text);
}

/* The lambert colour at the middle of the triangle, seen from above: its
 * normal is softrast's +y, n.l = 0.8, so the intensity is 0.2 + 0.8 * 0.8. */
static void lit_from_above(const char *name, int rgb[3])
{
    sr_texture image;
    render_image(name, 32, 32, "--eye 0,4,-1 --target 0,0,0 --color-space raw", &image);
    uint32_t c = image.texels[16 * 32 + 16];
    sr_texture_free(&image);
    for (int k = 0; k < 3; k++)
        rgb[k] = (int)(c >> (16 - 8 * k) & 0xFFu);
}

/* Assimp gives an AMF mesh of no colours a set of transparent black ones,
 * and every AMF mesh its default material's gray 0.6: the file's colours
 * are drawn as given, a file of none in softrast's default gray 0.8 (in
 * raw arithmetic: what is asked here is the loader's colours, not the
 * colour space, which tests/test_srgb.c holds). */
Test(scene_files, an_amf_draws_its_colours_as_given_and_none_in_gray)
{
    const double lit = (0.2 + 0.8 * 0.8) * 255.0;
    int rgb[3];
    write_amf("<r>1</r><g>0.5</g><b>0</b>");
    lit_from_above("t.amf", rgb);
    cr_expect(abs(rgb[0] - (int)lit) <= 2 && abs(rgb[1] - (int)(lit / 2)) <= 2 && rgb[2] == 0, "%d %d %d", rgb[0],
              rgb[1], rgb[2]);
    write_amf(NULL);
    lit_from_above("t.amf", rgb);
    cr_expect(abs(rgb[0] - (int)(0.8 * lit)) <= 2 && rgb[1] == rgb[0] && rgb[2] == rgb[0], "%d %d %d", rgb[0], rgb[1],
              rgb[2]);
}

/* AMF (as 3MF) stores a solid's facets, no normals, its corners shared:
 * each triangle is shaded by its own outward normal, the same at its three
 * corners, never one averaged over a corner (a box's sides would shade as
 * gradients). */
Test(scene_files, an_amf_solid_is_shaded_by_its_facets)
{
    write_text(temp_dir, "tetra.amf",
               "<?xml version=\"1.0\"?>\n<amf><object id=\"1\"><mesh><vertices>"
               "<vertex><coordinates><x>0</x><y>0</y><z>0</z></coordinates></vertex>"
               "<vertex><coordinates><x>1</x><y>0</y><z>0</z></coordinates></vertex>"
               "<vertex><coordinates><x>0</x><y>2</y><z>0</z></coordinates></vertex>"
               "<vertex><coordinates><x>0</x><y>0</y><z>3</z></coordinates></vertex></vertices><volume>"
               "<triangle><v1>0</v1><v2>2</v2><v3>1</v3></triangle><triangle><v1>0</v1><v2>1</v2><v3>3</v3></triangle>"
               "<triangle><v1>0</v1><v2>3</v2><v3>2</v3></triangle><triangle><v1>1</v1><v2>2</v2><v3>3</v3></triangle>"
               "</volume></mesh></object></amf>\n");
    sr_mesh m;
    sr_texture tex = { 0 };
    sr_error err = { "" };
    char path[600];
    cr_assert(sr_mesh_load(&m, &tex, temp_path(path, sizeof path, "tetra.amf"), &err), "%s", err.message);
    cr_assert_eq(m.index_count, 12u);
    cr_assert_not_null(m.normals);
    vec3 centre = { 0, 0, 0 };
    for (uint32_t i = 0; i < m.index_count; i++)
        glm_vec3_muladds(m.positions[m.indices[i]], 1.0f / 12.0f, centre);
    for (uint32_t t = 0; t < 4; t++) {
        const uint32_t *v = &m.indices[3 * t];
        vec3 e1, e2, face, out;
        glm_vec3_sub(m.positions[v[1]], m.positions[v[0]], e1);
        glm_vec3_sub(m.positions[v[2]], m.positions[v[0]], e2);
        glm_vec3_cross(e1, e2, face);
        glm_vec3_normalize(face);
        glm_vec3_sub(m.positions[v[0]], centre, out);
        cr_expect_gt(glm_vec3_dot(face, out), 0.0f, "triangle %u winds inward", t);
        for (int c = 0; c < 3; c++)
            cr_expect(glm_vec3_distance(m.normals[v[c]], face) < 1e-6f,
                      "triangle %u corner %d: normal (%g, %g, %g), its face's (%g, %g, %g)", t, c, m.normals[v[c]][0],
                      m.normals[v[c]][1], m.normals[v[c]][2], face[0], face[1], face[2]);
    }
    sr_mesh_free(&m);
    sr_texture_free(&tex);
}

/* A triangle whose one morph target lifts its apex by 2, at a default
 * weight of 0.5 (the glTF mesh's "weights"): drawn with the apex at
 * 1 + 0.5 * 2; `info` says what was posed. */
Test(scene_files, morph_targets_are_drawn_at_their_default_weights)
{
    const float bin[2][3][3] = { { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } }, { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 2, 0 } } };
    char path[600];
    snprintf(path, sizeof path, "%s/m.bin", temp_dir);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    cr_assert_eq(fwrite(bin, sizeof bin, 1, f), 1u);
    fclose(f);
    write_text(temp_dir, "m.gltf",
               "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
               "\"meshes\":[{\"weights\":[0.5],\"primitives\":[{\"attributes\":{\"POSITION\":0},"
               "\"targets\":[{\"POSITION\":1}]}]}],\"buffers\":[{\"byteLength\":72,\"uri\":\"m.bin\"}],"
               "\"bufferViews\":[{\"buffer\":0,\"byteLength\":72}],\"accessors\":["
               "{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]},"
               "{\"bufferView\":0,\"byteOffset\":36,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
               "\"min\":[0,0,0],\"max\":[0,2,0]}]}");
    cJSON *o = info_json("m.gltf");
    const cJSON *max = cJSON_GetObjectItem(cJSON_GetObjectItem(o, "bounds_file"), "max");
    cr_expect_eq(cJSON_GetArrayItem(max, 1)->valuedouble, 2.0);
    cr_expect_eq(cJSON_GetObjectItem(o, "morphed_meshes")->valueint, 1);
    cJSON_Delete(o);
}

/* A triangle skinned to two joints, (0,0,0) to the first alone, (1,0,0) to
 * the second alone, (0,1,0) half to each. The first joint's node stands at
 * (0,2,0) with an identity inverse bind matrix; the second's at (0,0,3)
 * with one that moves by (0,0,-1). The mesh's own node, moved by (5,0,0),
 * does not place a skinned mesh (glTF's skinning): the vertices are drawn
 * at (0,2,0), (1,0,2) and (0,2,1), softrast's world negating z. */
Test(scene_files, a_skinned_mesh_is_posed_by_its_joints_nodes)
{
    static const struct {
        float positions[3][3];
        uint16_t indices[4];        /* three, and padding */
        uint8_t joints[3][4];
        float weights[3][4];
        float inverse_bind[2][16];  /* column-major */
    } bin = { { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } },
              { 0, 1, 2, 0 },
              { { 0, 0, 0, 0 }, { 1, 0, 0, 0 }, { 0, 1, 0, 0 } },
              { { 1, 0, 0, 0 }, { 1, 0, 0, 0 }, { 0.5f, 0.5f, 0, 0 } },
              { { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 }, { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -1, 1 } } };
    cr_assert_eq(sizeof bin, 232u);
    char path[600];
    snprintf(path, sizeof path, "%s/s.bin", temp_dir);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    cr_assert_eq(fwrite(&bin, sizeof bin, 1, f), 1u);
    fclose(f);
    write_text(temp_dir, "s.gltf",
               "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0,1,2]}],"
               "\"nodes\":[{\"mesh\":0,\"skin\":0,\"translation\":[5,0,0]},{\"translation\":[0,2,0]},"
               "{\"translation\":[0,0,3]}],\"skins\":[{\"joints\":[1,2],\"inverseBindMatrices\":4}],"
               "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"JOINTS_0\":2,\"WEIGHTS_0\":3},"
               "\"indices\":1}]}],\"buffers\":[{\"byteLength\":232,\"uri\":\"s.bin\"}],"
               "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6},"
               "{\"buffer\":0,\"byteOffset\":44,\"byteLength\":12},{\"buffer\":0,\"byteOffset\":56,\"byteLength\":48},"
               "{\"buffer\":0,\"byteOffset\":104,\"byteLength\":128}],\"accessors\":["
               "{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]},"
               "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"},"
               "{\"bufferView\":2,\"componentType\":5121,\"count\":3,\"type\":\"VEC4\"},"
               "{\"bufferView\":3,\"componentType\":5126,\"count\":3,\"type\":\"VEC4\"},"
               "{\"bufferView\":4,\"componentType\":5126,\"count\":2,\"type\":\"MAT4\"}]}");
    sr_mesh m;
    sr_texture tex = { 0 };
    sr_error err = { "" };
    cr_assert(sr_mesh_load(&m, &tex, temp_path(path, sizeof path, "s.gltf"), &err), "%s", err.message);
    cr_assert_eq(m.index_count, 3u);
    static const double want[3][3] = { { 0, 2, 0 }, { 1, 0, -2 }, { 0, 2, -1 } };
    for (int w = 0; w < 3; w++) {
        bool seen = false;
        for (uint32_t i = 0; i < m.index_count; i++) {
            const float *p = m.positions[m.indices[i]];
            seen |= m.origin[0] + p[0] == want[w][0] && m.origin[1] + p[1] == want[w][1] &&
                    m.origin[2] + p[2] == want[w][2];
        }
        cr_expect(seen, "no corner at (%g, %g, %g)", want[w][0], want[w][1], want[w][2]);
    }
    sr_mesh_free(&m);
    sr_texture_free(&tex);
    cJSON *o = info_json("s.gltf");
    cr_expect_eq(cJSON_GetObjectItem(o, "skinned_meshes")->valueint, 1);
    cJSON_Delete(o);
}

/* The glTF reproducers of fuzz/regressions/mesh (byte 0 picks the format,
 * the rest is the file): a material index out of range, a texture that is
 * a directory, a path through "..", a thousand materials sharing one
 * embedded texture. Each draws with at most one warning line, or fails
 * with one error line. */
Test(scene_files, hostile_material_and_texture_paths_are_one_line)
{
    static const char *const names[] = { "gltf_material_index_out_of_range", "gltf_texture_is_a_directory",
                                         "gltf_texture_path_dotdot", "gltf_thousand_materials_one_texture" };
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        char relative[200], path[CASE_PATH_MAX];
        snprintf(relative, sizeof relative, "fuzz/regressions/mesh/%s", names[i]);
        case_root_path(relative, path);
        FILE *f = fopen(path, "rb");
        cr_assert_not_null(f, "%s", path);
        static char text[1 << 18];
        size_t n = fread(text, 1, sizeof text - 1, f);
        fclose(f);
        text[n] = '\0';
        write_text(temp_dir, "h.gltf", text + 1);
        char args[1024];
        snprintf(args, sizeof args, "render %s/h.gltf --size 16x16 --quiet --out %s/h.png", temp_dir, temp_dir);
        run_result r = run_softrast(temp_dir, args);
        /* Only warnings and errors counted: a slow build (the sanitizers')
         * adds the loader's progress lines. */
        int said = 0;
        for (const char *c = r.err; (c = strstr(c, "softrast: ")); c++)
            said += strncmp(c, "softrast: warning: ", 19) == 0 || strncmp(c, "softrast: error: ", 17) == 0;
        cr_expect(r.status == 0 || r.status == 1, "%s: status %d", names[i], r.status);
        cr_expect_leq(said, 1, "%s: %s", names[i], r.err);
        cr_expect(r.status == 0 || strstr(r.err, "softrast: error: "), "%s: %s", names[i], r.err);
    }
}

/* AMF states its unit on its root element; Assimp does not report it. */
Test(scene_files, an_amf_unit_is_read)
{
    write_amf(NULL);
    cJSON *o = info_json("t.amf");
    cr_expect_eq(cJSON_GetObjectItem(o, "metres_per_unit")->valuedouble, 0.001); /* AMF's default */
    cr_expect_str_eq(json_string(o, "units_found"), "guessed");
    cJSON_Delete(o);
    write_text(temp_dir, "i.amf",
               "<?xml version=\"1.0\"?>\n<amf unit=\"inch\" version=\"1.1\"><object id=\"1\"><mesh><vertices>"
               "<vertex><coordinates><x>0</x><y>0</y><z>0</z></coordinates></vertex>"
               "<vertex><coordinates><x>1</x><y>0</y><z>0</z></coordinates></vertex>"
               "<vertex><coordinates><x>0</x><y>1</y><z>0</z></coordinates></vertex></vertices><volume>"
               "<triangle><v1>0</v1><v2>1</v2><v3>2</v3></triangle></volume></mesh></object></amf>\n");
    o = info_json("i.amf");
    cr_expect_eq(cJSON_GetObjectItem(o, "metres_per_unit")->valuedouble, 0.0254);
    cr_expect_str_eq(json_string(o, "units_found"), "read");
    cJSON_Delete(o);
}
