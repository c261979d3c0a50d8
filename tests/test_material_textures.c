/* sr_material_textures_load (softrast/files.h): every material's texture
 * file loaded once however many materials name it, and a file that does
 * not load one warning and its materials' paths dropped, so they draw their
 * base colour and never desc's texture. */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "softrast/files.h"
#include "temp_dir.h"

TestSuite(material_textures, .init = temp_dir_make, .fini = temp_dir_remove);

/* A 2×2 PNG of one colour at temp_dir/name. */
static void write_texture(const char *name, uint32_t rgb)
{
    char path[256];
    sr_error err;
    const uint32_t texels[4] = { rgb, rgb, rgb, rgb };
    cr_assert(sr_image_write_png(temp_path(path, sizeof path, name), texels, 2, 2, &err), "%s", err.message);
}

/* A mesh with no geometry and these materials: a file name in temp_dir,
 * or NULL for none. */
static sr_mesh mesh_of(const char *const names[], uint32_t count)
{
    sr_mesh mesh = { .material_count = count, .materials = calloc(count, sizeof(sr_material)) };
    cr_assert_not_null(mesh.materials);
    for (uint32_t i = 0; i < count; i++) {
        char path[256];
        mesh.materials[i].base_color[0] = 1.0f;
        mesh.materials[i].texture_path = names[i] ? strdup(temp_path(path, sizeof path, names[i])) : NULL;
    }
    return mesh;
}

typedef struct warnings {
    int count;
    char first[sizeof(sr_error)];
} warnings;

static void note(void *context, const sr_error *why)
{
    warnings *w = context;
    if (w->count++ == 0)
        memcpy(w->first, why->message, sizeof w->first);
}

Test(material_textures, each_file_is_loaded_once_and_hung_on_every_material_that_names_it)
{
    write_texture("red.png", 0xff0000);
    write_texture("blue.png", 0x0000ff);
    const char *const names[] = { "blue.png", "red.png", NULL, "blue.png", "blue.png" };
    sr_mesh mesh = mesh_of(names, 5);
    sr_material_textures t = { 0 };
    warnings w = { 0 };
    sr_error err;
    cr_assert(sr_material_textures_load(&mesh, &t, note, &w, &err), "%s", err.message);
    cr_assert_eq(w.count, 0, "%s", w.first);
    cr_assert_eq(t.count, 2);
    const sr_material *m = mesh.materials;
    cr_assert_not_null(m[0].texture);
    cr_assert(m[0].texture == m[3].texture && m[0].texture == m[4].texture);
    cr_assert_null(m[2].texture);
    cr_assert(m[1].texture != m[0].texture);
    cr_assert(m[0].texture >= t.textures && m[0].texture < t.textures + t.count);
    cr_assert(m[1].texture >= t.textures && m[1].texture < t.textures + t.count);
    cr_assert_eq(m[0].texture->texels[0] & 0xffffff, 0x0000ff);
    cr_assert_eq(m[1].texture->texels[3] & 0xffffff, 0xff0000);
    cr_assert_not_null(m[0].texture_path);
    sr_material_textures_free(&t);
    cr_assert_eq(t.count, 0);
    cr_assert_null(t.textures);
    sr_mesh_free(&mesh);
}

Test(material_textures, a_file_that_does_not_load_warns_once_and_its_materials_lose_their_path)
{
    write_texture("red.png", 0xff0000);
    const char *const names[] = { "gone.png", "red.png", "gone.png" };
    sr_mesh mesh = mesh_of(names, 3);
    sr_texture embedded = { 0 };
    mesh.materials[1].texture = &embedded; /* replaced by the file's */
    sr_material_textures t = { 0 };
    warnings w = { 0 };
    sr_error err;
    cr_assert(sr_material_textures_load(&mesh, &t, note, &w, &err), "%s", err.message);
    cr_assert_eq(w.count, 1);
    cr_assert_not_null(strstr(w.first, "gone.png"), "%s", w.first);
    for (int i = 0; i < 3; i += 2) {
        cr_assert_null(mesh.materials[i].texture_path, "material %d", i);
        cr_assert_null(mesh.materials[i].texture, "material %d", i);
    }
    cr_assert_not_null(mesh.materials[1].texture_path);
    cr_assert(mesh.materials[1].texture != &embedded && mesh.materials[1].texture->texels);
    /* Loading again empties out first. */
    cr_assert(sr_material_textures_load(&mesh, &t, NULL, NULL, &err), "%s", err.message);
    cr_assert_eq(t.count, 1);
    sr_material_textures_free(&t);
    sr_mesh_free(&mesh);
}

Test(material_textures, a_mesh_without_texture_paths_loads_nothing)
{
    const char *const names[] = { NULL, NULL };
    sr_mesh mesh = mesh_of(names, 2);
    sr_material_textures t = { 0 };
    sr_error err;
    cr_assert(sr_material_textures_load(&mesh, &t, NULL, NULL, &err));
    cr_assert_eq(t.count, 0);
    cr_assert_null(t.textures);
    sr_mesh empty = { 0 };
    cr_assert(sr_material_textures_load(&empty, &t, NULL, NULL, &err));
    cr_assert_eq(t.count, 0);
    sr_mesh_free(&mesh);
}
