/* sr_isolated_load: a loader in a child process. Its mesh comes back whole,
 * its error comes back as it said it, and a crash or an endless loop in it
 * becomes one error line instead of taking the program down. */
#include <criterion/criterion.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/isolated_load.h"
#include "softrast_private.h"

static bool load_two_triangles(sr_mesh *m, sr_texture *t, const char *path, sr_error *err)
{
    (void)path;
    t->texels = malloc(3 * 2 * sizeof *t->texels);
    if (!t->texels)
        return false;
    for (int i = 0; i < 6; i++)
        t->texels[i] = 0x010203u * (uint32_t)i;
    t->width = 3;
    t->height = 2;
    if (!sr_mesh_alloc(m, 4, 6, true, false, true, err))
        return false;
    for (uint32_t i = 0; i < 4; i++) {
        glm_vec3_copy((vec3){ (float)(i & 1), (float)(i >> 1), 0.5f * (float)i }, m->positions[i]);
        glm_vec3_copy((vec3){ 0.0f, 0.0f, -1.0f }, m->normals[i]);
        glm_vec3_copy((vec3){ 0.25f * (float)i, 0.5f, 1.0f }, m->colors[i]);
    }
    static const uint32_t idx[6] = { 0, 2, 1, 1, 2, 3 };
    memcpy(m->indices, idx, sizeof idx);
    m->origin[0] = 1e7;
    m->texture_path = strdup("tex.png");
    m->parts = malloc(2 * sizeof *m->parts);
    if (!m->texture_path || !m->parts)
        return false;
    m->parts[0] = (sr_mesh_part){ 0, 1 };
    m->parts[1] = (sr_mesh_part){ 1, 1 };
    m->part_count = 2;
    return true;
}

static bool fail_politely(sr_mesh *m, sr_texture *t, const char *path, sr_error *err)
{
    (void)t;
    *m = (sr_mesh){ 0 };
    return sr_error_set(err, "%s: no faces here", path);
}

static bool crash(sr_mesh *m, sr_texture *t, const char *path, sr_error *err)
{
    (void)m, (void)t, (void)path, (void)err;
    abort();
}

static volatile bool spinning = true; /* never cleared: the child spins until its CPU limit */

static bool block(sr_mesh *m, sr_texture *t, const char *path, sr_error *err)
{
    (void)m, (void)t, (void)path, (void)err;
    pause(); /* as a read of a FIFO no one writes */
    return false;
}

static bool spin(sr_mesh *m, sr_texture *t, const char *path, sr_error *err)
{
    (void)m, (void)t, (void)path, (void)err;
    while (spinning)
        ;
    return false;
}

Test(isolated_load, the_childs_mesh_comes_back_whole)
{
    sr_mesh want, got;
    sr_texture want_tex = { 0 }, tex;
    sr_error err = { "" };
    cr_assert(load_two_triangles(&want, &want_tex, "x", &err));
    cr_assert(sr_isolated_load(&got, &tex, "x", load_two_triangles, 10, &err), "%s", err.message);
    cr_assert_eq(got.vertex_count, 4);
    cr_assert_eq(got.index_count, 6);
    cr_assert_null(got.uvs);
    cr_assert_eq(memcmp(got.positions, want.positions, sizeof(vec3) * 4), 0);
    cr_assert_eq(memcmp(got.normals, want.normals, sizeof(vec3) * 4), 0);
    cr_assert_eq(memcmp(got.colors, want.colors, sizeof(vec3) * 4), 0);
    cr_assert_eq(memcmp(got.indices, want.indices, sizeof(uint32_t) * 6), 0);
    cr_assert_eq(got.origin[0], 1e7);
    cr_assert_str_eq(got.texture_path, "tex.png");
    cr_assert_eq(got.part_count, 2);
    cr_assert_eq(memcmp(got.parts, want.parts, 2 * sizeof *got.parts), 0);
    cr_assert_eq(tex.width, 3);
    cr_assert_eq(tex.height, 2);
    cr_assert_eq(memcmp(tex.texels, want_tex.texels, 6 * sizeof *tex.texels), 0);
    sr_texture_free(&want_tex);
    sr_texture_free(&tex);
    sr_mesh_free(&want);
    sr_mesh_free(&got);
}

/* The load fails with `want` as its message (or, with a prefix, starting
 * with it), and leaves neither mesh nor texture. */
static void expect_failure(sr_isolated_loader load, const char *path, unsigned seconds, const char *want, bool prefix)
{
    sr_mesh m;
    sr_texture tex;
    sr_error err = { "" };
    cr_assert_not(sr_isolated_load(&m, &tex, path, load, seconds, &err));
    if (prefix)
        cr_assert_eq(strncmp(err.message, want, strlen(want)), 0, "%s", err.message);
    else
        cr_assert_str_eq(err.message, want);
    cr_assert_null(m.positions);
    cr_assert_null(tex.texels);
}

Test(isolated_load, the_childs_error_comes_back_as_it_said_it)
{
    expect_failure(fail_politely, "a.ply", 10, "a.ply: no faces here", false);
}

Test(isolated_load, a_crash_in_the_child_is_an_error_line)
{
    expect_failure(crash, "bad.fbx", 10, "bad.fbx: the importer crashed on this file", true);
}

Test(isolated_load, an_endless_loop_in_the_child_ends_at_the_time_limit)
{
    expect_failure(spin, "loop.dae", 1, "loop.dae: the importer took more than 1 s", false);
}

Test(isolated_load, a_child_that_blocks_ends_at_the_time_limit)
{
    expect_failure(block, "fifo.gltf", 1, "fifo.gltf: the importer took more than 1 s", false);
}
