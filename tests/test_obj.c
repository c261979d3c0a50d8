/* sr_obj_load: each test writes its OBJ (and MTL) inline into a fresh temp
 * folder, loads it and checks one property. Error tests check the exact
 * "FILE:LINE: " prefix and that the mesh is left zeroed. */
#include <dirent.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <criterion/criterion.h>

#include "io/load_report.h"
#include "softrast_private.h"

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SR_TEST_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(SR_TEST_ASAN)
#include <sanitizer/lsan_interface.h>
/* Criterion ignores LeakSanitizer's exit status, so a leak would pass
 * silently; aborting in teardown makes the whole run exit non-zero. */
static void check_leaks(void)
{
    if (__lsan_do_recoverable_leak_check())
        abort();
}
#else
static void check_leaks(void)
{
}
#endif

#define TMP_DIR_TEMPLATE "/tmp/softrast-test-obj-XXXXXX"
#define OBJ_NAME "mesh.obj"

static char tmp_dir[sizeof TMP_DIR_TEMPLATE];

static void make_tmp_dir(void)
{
    memcpy(tmp_dir, TMP_DIR_TEMPLATE, sizeof tmp_dir);
    cr_assert_not_null(mkdtemp(tmp_dir), "mkdtemp failed");
}

static void remove_tree(const char *path)
{
    struct stat st;
    if (lstat(path, &st) != 0)
        return;
    if (S_ISDIR(st.st_mode)) {
        DIR *d = opendir(path);
        for (struct dirent *e; d && (e = readdir(d));) {
            if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
                char child[1024];
                snprintf(child, sizeof child, "%s/%s", path, e->d_name);
                remove_tree(child);
            }
        }
        if (d)
            closedir(d);
    }
    remove(path);
}

static void remove_tmp_dir(void)
{
    remove_tree(tmp_dir);
    check_leaks();
}

TestSuite(obj, .init = make_tmp_dir, .fini = remove_tmp_dir);

/* tmp_dir/name, in a static buffer (one of a few, so two can be in use). */
static const char *tmp_path(const char *name)
{
    static char bufs[4][1024];
    static int next;
    char *buf = bufs[next++ % 4];
    snprintf(buf, sizeof bufs[0], "%s/%s", tmp_dir, name);
    return buf;
}

/* Writes `size` bytes to tmp_dir/name, making one level of subfolder. */
static void write_bytes(const char *name, const char *data, size_t size)
{
    const char *slash = strchr(name, '/');
    if (slash) {
        char sub[256];
        snprintf(sub, sizeof sub, "%.*s", (int)(slash - name), name);
        mkdir(tmp_path(sub), 0700);
    }
    FILE *f = fopen(tmp_path(name), "wb");
    cr_assert_not_null(f, "cannot create %s", tmp_path(name));
    cr_assert_eq(fwrite(data, 1, size, f), size);
    cr_assert_eq(fclose(f), 0);
}

static void write_text(const char *name, const char *text)
{
    write_bytes(name, text, strlen(text));
}

/* Loads `text` as tmp_dir/mesh.obj and asserts that it succeeds. */
static sr_mesh load_ok(const char *text)
{
    write_text(OBJ_NAME, text);
    sr_mesh m;
    sr_error e = { "" };
    bool ok = sr_obj_load(&m, tmp_path(OBJ_NAME), &e);
    cr_assert(ok, "load failed: %s", e.message);
    cr_assert_eq(m.topology, SR_TRIANGLE_LIST);
    return m;
}

static void assert_zeroed(const sr_mesh *m)
{
    cr_assert_eq(m->vertex_count, 0);
    cr_assert_eq(m->index_count, 0);
    cr_assert_null(m->positions);
    cr_assert_null(m->normals);
    cr_assert_null(m->uvs);
    cr_assert_null(m->colors);
    cr_assert_null(m->indices);
    cr_assert_null(m->texture_path);
}

/* Loads tmp_dir/name, expects failure with a message starting "PATH:LINE: "
 * (or "PATH: " for line 0) and containing `what`, and a zeroed mesh. */
static void assert_file_fails(const char *name, int line, const char *what)
{
    sr_mesh m;
    memset(&m, 0xA5, sizeof m); /* garbage in: the loader must zero it */
    sr_error e = { "" };
    cr_assert_not(sr_obj_load(&m, tmp_path(name), &e), "load should fail");
    char prefix[1100];
    if (line > 0)
        snprintf(prefix, sizeof prefix, "%s:%d: ", tmp_path(name), line);
    else
        snprintf(prefix, sizeof prefix, "%s: ", tmp_path(name));
    cr_assert(strncmp(e.message, prefix, strlen(prefix)) == 0,
              "message '%s' should start with '%s'", e.message, prefix);
    cr_assert_not_null(strstr(e.message, what), "message '%s' should say '%s'", e.message, what);
    assert_zeroed(&m);
}

static void assert_text_fails(const char *text, int line, const char *what)
{
    write_text(OBJ_NAME, text);
    assert_file_fails(OBJ_NAME, line, what);
}

static void assert_vec3(const float *got, float x, float y, float z)
{
    cr_assert(got[0] == x && got[1] == y && got[2] == z, "got (%g, %g, %g), want (%g, %g, %g)",
              (double)got[0], (double)got[1], (double)got[2], (double)x, (double)y, (double)z);
}

static void assert_triangle(const sr_mesh *m, uint32_t k, uint32_t a, uint32_t b, uint32_t c)
{
    cr_assert_lt(3 * k + 2, m->index_count);
    const uint32_t *t = m->indices + 3 * k;
    cr_assert(t[0] == a && t[1] == b && t[2] == c, "triangle %u is (%u, %u, %u), want (%u, %u, %u)",
              k, t[0], t[1], t[2], a, b, c);
}

/* ---- what is read ---- */

Test(obj, reads_all_four_face_forms)
{
    sr_mesh m = load_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                        "vt 0.25 0.5\nvt 1 0\nvt 0 1\n"
                        "vn 0 1 0\n"
                        "f 1 2 3\n"
                        "f 1/1 2/2 3/3\n"
                        "f 1//1 2//1 3//1\n"
                        "f 1/1/1 2/2/1 3/3/1\n");
    cr_assert_eq(m.index_count, 4 * 3);
    cr_assert_eq(m.vertex_count, 4 * 3); /* each form makes different triples */
    cr_assert_not_null(m.uvs);
    cr_assert_not_null(m.normals);
    /* Triangle 3 is (c0, c2, c1) = vertices 9, 11, 10; c0 is 1/1/1. */
    assert_triangle(&m, 3, 9, 11, 10);
    assert_vec3(m.positions[9], 0, 0, -0.0f);
    cr_assert(m.uvs[9][0] == 0.25f && m.uvs[9][1] == 0.5f);
    assert_vec3(m.normals[9], 0, 1, -0.0f);
    sr_mesh_free(&m);
}

Test(obj, negative_indices_count_from_the_end)
{
    sr_mesh m = load_ok("v 1 0 0\nv 2 0 0\nv 3 0 0\nvt 0.5 0.5\nvn 0 0 1\n"
                        "f -3/-1/-1 -2/-1/-1 -1/-1/-1\n"
                        "v 4 0 0\n"
                        "f -4 -2 -1\n"); /* -1 is now the 4th vertex */
    cr_assert_eq(m.index_count, 6);
    assert_vec3(m.positions[m.indices[0]], 1, 0, -0.0f);
    assert_vec3(m.positions[m.indices[1]], 3, 0, -0.0f);
    assert_vec3(m.positions[m.indices[2]], 2, 0, -0.0f);
    assert_vec3(m.positions[m.indices[3]], 1, 0, -0.0f);
    assert_vec3(m.positions[m.indices[4]], 4, 0, -0.0f);
    assert_vec3(m.positions[m.indices[5]], 3, 0, -0.0f);
    sr_mesh_free(&m);
}

Test(obj, negates_z_and_reverses_winding)
{
    sr_mesh m = load_ok("v 0 0 1\nv 1 0 2\nv 0 1 3\nvn 0.5 0 1\n"
                        "f 1//1 2//1 3//1\n");
    cr_assert_eq(m.vertex_count, 3);
    assert_vec3(m.positions[0], 0, 0, -1);
    assert_vec3(m.positions[1], 1, 0, -2);
    assert_vec3(m.positions[2], 0, 1, -3);
    assert_vec3(m.normals[0], 0.5f, 0, -1);
    assert_triangle(&m, 0, 0, 2, 1);
    sr_mesh_free(&m);
}

Test(obj, polygon_becomes_fan_in_file_order)
{
    sr_mesh m = load_ok("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 1 0\n"
                        "f 1 2 3 4\n"      /* triangles 0, 1 */
                        "f 5 4 3 2 1\n");  /* triangles 2, 3, 4 */
    cr_assert_eq(m.index_count, 5 * 3);
    /* quad c0..c3 = vertices 0..3: fan (0,1,2), (0,2,3), each reversed */
    assert_triangle(&m, 0, 0, 2, 1);
    assert_triangle(&m, 1, 0, 3, 2);
    /* pentagon c = 4 3 2 1 0 (vertex ids of v5 v4 v3 v2 v1) */
    assert_triangle(&m, 2, 4, 2, 3);
    assert_triangle(&m, 3, 4, 1, 2);
    assert_triangle(&m, 4, 4, 0, 1);
    sr_mesh_free(&m);
}

/* Triangles, quads and pentagons mixed: each fan triangle names the f
 * line it came from, the triangles before the first polygon included. */
Test(obj, the_face_map_names_each_triangles_file_face)
{
    sr_mesh m = load_ok("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 1 0\n"
                        "f 1 2 3\n"       /* face 0: triangle 0 */
                        "f 1 2 3 4\n"     /* face 1: triangles 1, 2 */
                        "f 5 4 3 2 1\n"   /* face 2: triangles 3, 4, 5 */
                        "f 2 3 4\n"       /* face 3: triangle 6 */
                        "f 4 3 2 1\n");   /* face 4: triangles 7, 8 */
    static const uint32_t want[] = { 0, 1, 1, 2, 2, 2, 3, 4, 4 };
    cr_assert_eq(m.index_count, 3 * 9);
    cr_assert_not_null(m.file_faces);
    for (uint32_t t = 0; t < 9; t++)
        cr_assert_eq(m.file_faces[t], want[t], "triangle %u: face %u, not %u", t, m.file_faces[t], want[t]);
    sr_mesh_free(&m);
}

/* A file of triangles alone needs no map: triangle i is face i. */
Test(obj, a_file_of_triangles_has_no_face_map)
{
    sr_mesh m = load_ok("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
    cr_assert_eq(m.index_count, 6);
    cr_assert_null(m.file_faces);
    sr_mesh_free(&m);
}

Test(obj, crlf_comments_blank_lines_and_whitespace)
{
    sr_mesh m = load_ok("# a comment\r\n"
                        "\r\n"
                        "   \t\r\n"
                        "  v 1 2 3  \r\n"
                        "v\t4\t5\t6\r\n"
                        "v 7 8 9 # trailing comment\r\n"
                        "\tf 1 2 3\t\r\n"
                        "#f 1 1 1\r\n"
                        "f 3 2 1"); /* no line end at the end of the file */
    cr_assert_eq(m.vertex_count, 3);
    cr_assert_eq(m.index_count, 6);
    assert_vec3(m.positions[0], 1, 2, -3);
    assert_vec3(m.positions[1], 4, 5, -6);
    assert_vec3(m.positions[2], 7, 8, -9);
    assert_triangle(&m, 1, 2, 0, 1);
    sr_mesh_free(&m);
}

/* "0#c" used to be "'0#c' is not a number": a comment may follow data with
 * no blank before it. */
Test(obj, comment_right_after_data_ends_the_token)
{
    sr_mesh m = load_ok("v 1 0 0#c\nv 0 1 0# two\nv 0 0 1#\nf 1 2 3#face\n");
    cr_assert_eq(m.vertex_count, 3);
    cr_assert_eq(m.index_count, 3);
    assert_vec3(m.positions[0], 1, 0, 0);
    assert_vec3(m.positions[2], 0, 0, -1);
    sr_mesh_free(&m);
}

/* Old Mac files end lines with a lone CR: they used to fail on line 1. */
Test(obj, cr_only_line_ends)
{
    sr_mesh m = load_ok("v 1 0 0\rv 0 1 0\r\rv 0 0 1\rf 1 2 3\r");
    cr_assert_eq(m.vertex_count, 3);
    cr_assert_eq(m.index_count, 3);
    sr_mesh_free(&m);
    assert_text_fails("v 0 0 0\rv 1 0 0\rf 1 2 9\r", 3, "out of range");
}

/* A "\r\n" split between two reads (the reader's first read is 256 KiB:
 * 9 + 32766·8 + 6 puts a "\r" on its last byte) is still one line end, so
 * the line numbers stay right. */
Test(obj, crlf_across_a_read_is_one_line_end)
{
    size_t lines = 40000, size = 9 + 8 * lines + 64;
    char *text = malloc(size), *p = text;
    cr_assert_not_null(text);
    p += sprintf(p, "#abcdef\r\n");
    for (size_t i = 0; i < lines; i++)
        p += sprintf(p, "# abcd\r\n");
    sprintf(p, "v 0 0 0\r\nf 1 1 x\r\n");
    assert_text_fails(text, (int)lines + 3, "malformed face vertex");
    free(text);
}

Test(obj, utf8_byte_order_mark_is_skipped)
{
    sr_mesh m = load_ok("\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    cr_assert_eq(m.vertex_count, 3);
    sr_mesh_free(&m);
}

Test(obj, ignores_other_statements)
{
    sr_mesh m = load_ok("mtllib_not_a_keyword x\no thing\ng group\ns 1\ns off\n"
                        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvp 0.5\n"
                        "usemtl no_library_so_just_a_group_name\nusemap x\n"
                        "l 1 2\np 1\ncstype bezier\nf 1 2 3\n");
    cr_assert_eq(m.index_count, 3);
    cr_assert_null(m.texture_path);
    sr_mesh_free(&m);
}

Test(obj, optional_w_of_v_and_vt_is_ignored)
{
    sr_mesh m = load_ok("v 0 0 0 1\nv 1 0 0 0.5\nv 0 1 0 2\nvt 0.5 0.25 9\n"
                        "f 1/1 2/1 3/1\n");
    assert_vec3(m.positions[1], 1, 0, -0.0f);
    cr_assert(m.uvs[0][0] == 0.5f && m.uvs[0][1] == 0.25f);
    cr_assert_null(m.colors);
    sr_mesh_free(&m);
}

Test(obj, vertex_colors)
{
    sr_mesh m = load_ok("v 0 0 0\n"               /* before the first color: white */
                        "v 1 0 0 1 0 0\n"
                        "v 0 1 0 0 0.5 1\n"
                        "v 1 1 0\n"               /* after: white too */
                        "f 1 2 3 4\n");
    cr_assert_not_null(m.colors);
    assert_vec3(m.colors[0], 1, 1, 1);
    assert_vec3(m.colors[1], 1, 0, 0);
    assert_vec3(m.colors[2], 0, 0.5f, 1);
    assert_vec3(m.colors[3], 1, 1, 1);
    sr_mesh_free(&m);
}

Test(obj, without_colors_or_uvs_or_normals_those_arrays_are_null)
{
    sr_mesh m = load_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1 2 3\n");
    cr_assert_null(m.colors);
    cr_assert_null(m.uvs); /* vt and vn lines exist, but no face uses them */
    cr_assert_null(m.normals);
    sr_mesh_free(&m);
}

Test(obj, dedups_identical_corners)
{
    sr_mesh m = load_ok("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\n"
                        "f 1/1 2/1 3/1\n"
                        "f 1/1 3/1 4/1\n"   /* shares 1/1 and 3/1 */
                        "f -4/1 -2/1 -1/1\n" /* the same triples written relatively */
                        "f 1/2 3/1 4/1\n");  /* 1/2 is a new vertex */
    cr_assert_eq(m.vertex_count, 5);
    cr_assert_eq(m.index_count, 12);
    assert_triangle(&m, 2, 0, 3, 2);
    assert_triangle(&m, 3, 4, 3, 2);
    sr_mesh_free(&m);
}

Test(obj, grid_shares_every_vertex_across_map_growth)
{
    enum { N = 120 }; /* (N+1)^2 vertices: several rehashes of the corner map */
    size_t cap = (size_t)(N + 1) * (N + 1) * 40 + (size_t)N * N * 40;
    char *text = malloc(cap), *p = text;
    cr_assert_not_null(text);
    for (int y = 0; y <= N; y++)
        for (int x = 0; x <= N; x++)
            p += sprintf(p, "v %d %d 0\n", x, y);
    for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++) {
            int a = y * (N + 1) + x + 1;
            p += sprintf(p, "f %d %d %d %d\n", a, a + 1, a + N + 2, a + N + 1);
        }
    sr_mesh m = load_ok(text);
    free(text);
    cr_assert_eq(m.vertex_count, (N + 1) * (N + 1));
    cr_assert_eq(m.index_count, N * N * 6);
    for (uint32_t i = 0; i < m.index_count; i++)
        cr_assert_lt(m.indices[i], m.vertex_count);
    sr_mesh_free(&m);
}

Test(obj, missing_uv_or_normal_of_a_corner_is_zero)
{
    sr_mesh m = load_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 0.5\nvn 0 0 1\n"
                        "f 1/1/1 2/1 3//1\n");
    cr_assert_not_null(m.uvs);
    cr_assert_not_null(m.normals);
    cr_assert(m.uvs[2][0] == 0 && m.uvs[2][1] == 0); /* 3//1 has no vt */
    assert_vec3(m.normals[1], 0, 0, 0);            /* 2/1 has no vn */
    assert_vec3(m.normals[0], 0, 0, -1);
    sr_mesh_free(&m);
}

/* A file of vertices alone is a point cloud (as scanners and CloudCompare
 * write one): every vertex in file order, z negated, with its colour (one
 * without a colour white, as among faces), and no triangles; a normal is
 * a vertex's only when there is one a vertex (then in the same order, z
 * negated), as no face corner pairs them. */
Test(obj, file_without_faces_is_a_point_cloud)
{
    sr_mesh paired = load_ok("v 0 0 1\nvn 0 0 1\nv 1 0 2\nvn 0 1 0\n");
    cr_assert_eq(paired.vertex_count, 2);
    cr_assert_not_null(paired.normals);
    assert_vec3(paired.normals[0], 0, 0, -1);
    assert_vec3(paired.normals[1], 0, 1, 0);
    sr_mesh_free(&paired);
    sr_mesh m = load_ok("v 0 0 1 1 0 0\nv 1 0 2\nv 0 1 3 0 0 1\nvn 0 0 1\nl 1 2\n");
    cr_assert_eq(m.vertex_count, 3);
    cr_assert_eq(m.index_count, 0);
    cr_assert_null(m.normals);
    assert_vec3(m.positions[0], 0, 0, -1);
    assert_vec3(m.positions[1], 1, 0, -2);
    assert_vec3(m.positions[2], 0, 1, -3);
    cr_assert_not_null(m.colors);
    assert_vec3(m.colors[0], 1, 0, 0);
    assert_vec3(m.colors[1], 1, 1, 1);
    assert_vec3(m.colors[2], 0, 0, 1);
    cr_assert(m.bounded);
    sr_mesh_free(&m);
}

Test(obj, empty_file_is_an_empty_mesh)
{
    sr_mesh m = load_ok("");
    assert_zeroed(&m);
}

Test(obj, line_of_exactly_64_kib_is_accepted)
{
    size_t len = 64 * 1024;
    char *text = malloc(len + 64);
    cr_assert_not_null(text);
    memset(text, ' ', len);
    memcpy(text, "# ", 2);
    strcpy(text + len, "\r\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    sr_mesh m = load_ok(text);
    free(text);
    cr_assert_eq(m.index_count, 3);
    sr_mesh_free(&m);
}

/* ---- materials ---- */

Test(obj, mtl_map_kd_sets_texture_path)
{
    /* The .mtl is found beside the .obj, the texture beside the .mtl. */
    write_text("mats/a.mtl", "newmtl wood\r\nKd 1 1 1\r\nmap_Kd tex/wood grain.png\r\n");
    sr_mesh m = load_ok("mtllib mats/a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                        "usemtl wood\nf 1 2 3\n");
    cr_assert_str_eq(m.texture_path, tmp_path("mats/tex/wood grain.png"));
    sr_mesh_free(&m);
}

/* MTL files written on Windows name ".\\tex\\wood.png"; that used to be
 * "cannot open" on the backslashes. */
Test(obj, windows_separators_in_mtl_paths_are_normalised)
{
    write_text("mats/a.mtl", "newmtl wood\nmap_Kd .\\tex\\wood.png\n");
    sr_mesh m = load_ok("mtllib mats\\a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl wood\nf 1 2 3\n");
    cr_assert_str_eq(m.texture_path, tmp_path("mats/./tex/wood.png"));
    sr_mesh_free(&m);
}

Test(obj, texture_is_the_first_map_kd_a_face_uses)
{
    write_text("a.mtl", "newmtl plain\nKd 1 0 0\n"
                        "newmtl b\nmap_Kd b.png\n"
                        "newmtl c\nmap_Kd c.png\n");
    sr_mesh m = load_ok("mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                        "usemtl c\n"            /* selected, but no face uses it */
                        "usemtl plain\nf 1 2 3\n" /* used, but has no map_Kd */
                        "usemtl b\nf 1 2 3\n"
                        "usemtl c\nf 1 2 3\n");
    cr_assert_str_eq(m.texture_path, tmp_path("b.png"));
    sr_mesh_free(&m);
}

Test(obj, map_kd_options_precede_the_file_name)
{
    write_text("a.mtl", "newmtl m\nmap_Kd -s 1 1 1 -clamp on wood.png\n");
    sr_mesh m = load_ok("mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n");
    cr_assert_str_eq(m.texture_path, tmp_path("wood.png"));
    sr_mesh_free(&m);
}

Test(obj, mtllib_may_name_several_libraries)
{
    write_text("a.mtl", "newmtl first\n");
    write_text("b.mtl", "newmtl second\nmap_Kd two.png\n");
    sr_mesh m = load_ok("mtllib a.mtl b.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                        "usemtl second\nf 1 2 3\n");
    cr_assert_str_eq(m.texture_path, tmp_path("two.png"));
    sr_mesh_free(&m);
}

Test(obj, mtllib_name_may_contain_spaces)
{
    write_text("my model.mtl", "newmtl m\nmap_Kd t.png\n");
    sr_mesh m = load_ok("mtllib my model.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n");
    cr_assert_str_eq(m.texture_path, tmp_path("t.png"));
    sr_mesh_free(&m);
}

Test(obj, without_usemtl_there_is_no_texture)
{
    write_text("a.mtl", "newmtl m\nmap_Kd t.png\n");
    sr_mesh m = load_ok("mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    cr_assert_null(m.texture_path);
    sr_mesh_free(&m);
}

/* ---- parts and materials ---- */

/* Runs of faces of one o/g group and one usemtl are parts; each library
 * material a face uses is one mesh material, in order of first use (a
 * texture over white, else Kd), and faces without one share the default. */
Test(obj, groups_and_materials_make_parts)
{
    write_text("a.mtl", "newmtl red\nKd 1 0 0\n"
                        "newmtl gray\nKd 0.5\n"
                        "newmtl wood\nKd 0.2 0.2 0.2\nmap_Kd wood.png\n"
                        "newmtl unused\nKd 0 1 0\n");
    sr_mesh m = load_ok("mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                        "f 1 2 3\n"                      /* part 0: the default material */
                        "usemtl wood\nf 1 2 3 4\n"       /* part 1: two triangles */
                        "usemtl red\nf 1 2 3\nf 2 4 3\n" /* part 2 */
                        "g top\nf 1 2 3\n"               /* part 3: a new group, still red */
                        "usemtl nowhere\nf 1 2 3\n"      /* part 4: the default again */
                        "usemtl red\no thing\nusemtl gray\nf 1 2 3\n");
    cr_assert_eq(m.part_count, 6);
    const sr_mesh_part want[6] = { { 0, 1, 0 }, { 1, 2, 1 }, { 3, 2, 2 }, { 5, 1, 2 }, { 6, 1, 0 }, { 7, 1, 3 } };
    for (int i = 0; i < 6; i++)
        cr_expect(m.parts[i].first_triangle == want[i].first_triangle &&
                      m.parts[i].triangle_count == want[i].triangle_count && m.parts[i].material == want[i].material,
                  "part %d: %u +%u material %u", i, m.parts[i].first_triangle, m.parts[i].triangle_count,
                  m.parts[i].material);
    cr_assert_eq(m.material_count, 4);
    const float gray = 0.8f;
    const float colors[4][4] = { { gray, gray, gray, 1 }, { 1, 1, 1, 1 }, { 1, 0, 0, 1 }, { 0.5f, 0.5f, 0.5f, 1 } };
    for (int i = 0; i < 4; i++) {
        cr_expect_arr_eq(m.materials[i].base_color, colors[i], sizeof colors[i], "material %d", i);
        cr_expect_eq(m.materials[i].alpha_mode, SR_ALPHA_OPAQUE);
        cr_expect_null(m.materials[i].texture);
    }
    cr_expect_str_eq(m.materials[1].texture_path, tmp_path("wood.png"), "as written, found or not");
    cr_expect_null(m.materials[0].texture_path);
    cr_expect_null(m.materials[2].texture_path);
    sr_mesh_free(&m);
}

/* Groups alone make parts (instance masks) but no materials: the mesh
 * draws as a mesh without parts does. A file of plain faces has neither. */
Test(obj, groups_without_materials_are_parts_only)
{
    sr_mesh m = load_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\no a\nf 1 2 3\nf 1 2 3\ng b\nf 1 2 3\n");
    cr_assert_eq(m.part_count, 2);
    cr_expect_eq(m.parts[1].first_triangle, 2);
    cr_expect_eq(m.material_count, 0);
    cr_expect_null(m.materials);
    sr_mesh_free(&m);
    m = load_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\ng only\nf 1 2 3\nf 1 2 3\n");
    cr_expect_eq(m.part_count, 0);
    cr_expect_null(m.parts);
    sr_mesh_free(&m);
}

/* Over vertex colours the default material is white: the colours show as
 * they are. */
Test(obj, the_default_material_is_white_over_vertex_colours)
{
    write_text("a.mtl", "newmtl red\nKd 1 0 0\n");
    sr_mesh m = load_ok("mtllib a.mtl\nv 0 0 0 0.5 0.5 0.5\nv 1 0 0\nv 0 1 0\nf 1 2 3\nusemtl red\nf 1 2 3\n");
    cr_assert_eq(m.material_count, 2);
    cr_expect_arr_eq(m.materials[0].base_color, ((float[4]){ 1, 1, 1, 1 }), 4 * sizeof(float), "the default");
    sr_mesh_free(&m);
}

/* An OBJ naming a.mtl, whose text fails at `line` with the message `what`. */
static void assert_mtl_fails(const char *mtl, int line, const char *what)
{
    write_text("a.mtl", mtl);
    write_text(OBJ_NAME, "mtllib a.mtl\n");
    sr_mesh m;
    sr_error e = { "" };
    cr_assert_not(sr_obj_load(&m, tmp_path(OBJ_NAME), &e));
    char want[1100];
    snprintf(want, sizeof want, "%s:%d: %s", tmp_path("a.mtl"), line, what);
    cr_assert_str_eq(e.message, want);
    assert_zeroed(&m);
}

Test(obj, a_malformed_kd_is_an_error_and_spectral_kd_is_read_past)
{
    assert_mtl_fails("newmtl m\nKd spectral x.rfl 1\nKd 1 2\n", 3, "'Kd' needs r g b or one gray, got 2 numbers");
}

/* ---- errors ---- */

Test(obj, missing_file_is_an_error)
{
    assert_file_fails("nowhere.obj", 0, "cannot open: No such file or directory");
}

Test(obj, directory_is_an_error)
{
    mkdir(tmp_path("folder.obj"), 0700);
    assert_file_fails("folder.obj", 0, "not a regular file (a directory)");
}

Test(obj, bad_number_is_an_error)
{
    assert_text_fails("v 0 0 0\nv 1 x 0\n", 2, "'x' is not a number");
}

Test(obj, number_with_trailing_garbage_is_an_error)
{
    assert_text_fails("v 0 0 0\n\nvt 0.5 1.0.0\n", 3, "'1.0.0' is not a number");
}

Test(obj, nan_is_an_error)
{
    assert_text_fails("v nan 0 0\n", 1, "not finite");
}

Test(obj, inf_is_an_error)
{
    assert_text_fails("# x\nvn 0 -inf 0\n", 2, "not finite");
}

Test(obj, number_beyond_double_range_is_an_error)
{
    assert_text_fails("v 0 0 1e999\n", 1, "not finite");
}

Test(obj, number_beyond_float_range_is_an_error)
{
    assert_text_fails("v 0 0 1e39\n", 1, "out of float range");
}

Test(obj, too_few_position_coordinates_is_an_error)
{
    assert_text_fails("v 0 0 0\nv 1 2\n", 2, "'v' needs");
}

Test(obj, five_position_numbers_is_an_error)
{
    assert_text_fails("v 0 0 0 1 1\n", 1, "got 5 numbers");
}

Test(obj, too_many_position_numbers_is_an_error)
{
    assert_text_fails("v 0 0 0 1 1 1 1\n", 1, "too many numbers");
}

Test(obj, too_few_uv_coordinates_is_an_error)
{
    assert_text_fails("vt 0.5\n", 1, "'vt' needs");
}

Test(obj, too_few_normal_coordinates_is_an_error)
{
    assert_text_fails("vn 0 1\n", 1, "'vn' needs");
}

Test(obj, index_zero_is_an_error)
{
    assert_text_fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4, "index 0 is invalid");
}

Test(obj, index_past_the_end_is_an_error)
{
    assert_text_fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", 4,
                      "vertex index 4 is out of range");
}

Test(obj, negative_index_before_the_start_is_an_error)
{
    assert_text_fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", 4,
                      "vertex index -4 is out of range");
}

Test(obj, huge_index_is_out_of_range)
{
    assert_text_fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999999\n", 4,
                      "out of range");
}

/* An index past long's range was reported as LONG_MAX (…807): the message
 * now quotes the index as written. */
Test(obj, index_past_long_is_reported_as_written)
{
    assert_text_fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9223372036854775808\n", 4,
                      "vertex index 9223372036854775808 is out of range (3 defined so far)");
    assert_text_fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//-9223372036854775809\n", 5,
                      "normal index -9223372036854775809 is out of range (1 defined so far)");
}

Test(obj, most_negative_index_is_out_of_range)
{
    assert_text_fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\n", 4,
                      "out of range");
}

Test(obj, uv_index_out_of_range_is_an_error)
{
    assert_text_fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/2\n", 5,
                      "texture coordinate index 2 is out of range");
}

Test(obj, normal_index_out_of_range_is_an_error)
{
    assert_text_fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n", 4,
                      "normal index 1 is out of range");
}

Test(obj, forward_reference_is_out_of_range)
{
    /* Indices refer to what was read before the face, as the format says. */
    assert_text_fails("v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n", 3, "out of range");
}

Test(obj, face_with_two_vertices_is_an_error)
{
    assert_text_fails("v 0 0 0\nv 1 0 0\nf 1 2\n", 3, "at least 3 vertices, got 2");
}

Test(obj, empty_face_is_an_error)
{
    assert_text_fails("f\n", 1, "at least 3 vertices, got 0");
}

Test(obj, face_token_with_four_parts_is_an_error)
{
    assert_text_fails("v 0 0 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 1/1/1/1 1/1/1\n", 4,
                      "malformed face vertex '1/1/1/1'");
}

Test(obj, face_token_with_empty_normal_is_an_error)
{
    assert_text_fails("v 0 0 0\nf 1// 1 1\n", 2, "malformed face vertex '1//'");
}

Test(obj, face_token_without_vertex_is_an_error)
{
    assert_text_fails("v 0 0 0\nvt 0 0\nf /1 1 1\n", 3, "malformed face vertex '/1'");
}

Test(obj, face_token_that_is_not_a_number_is_an_error)
{
    assert_text_fails("v 0 0 0\nf 1 a 1\n", 2, "malformed face vertex 'a'");
}

Test(obj, face_token_with_trailing_slash_is_an_error)
{
    assert_text_fails("v 0 0 0\nvt 0 0\nf 1/1/ 1 1\n", 3, "malformed face vertex '1/1/'");
}

Test(obj, face_token_with_garbage_after_index_is_an_error)
{
    assert_text_fails("v 0 0 0\nf 1x 1 1\n", 2, "malformed face vertex '1x'");
}

Test(obj, over_long_line_is_an_error)
{
    size_t len = 64 * 1024 + 1;
    char *text = malloc(len + 32);
    cr_assert_not_null(text);
    strcpy(text, "v 0 0 0\n");
    memset(text + 8, ' ', len);
    strcpy(text + 8 + len, "\nv 1 1 1\n");
    assert_text_fails(text, 2, "line longer than 65536 bytes");
    free(text);
}

Test(obj, endless_line_is_an_error_not_an_overflow)
{
    size_t len = 1024 * 1024; /* no line end at all */
    char *text = malloc(len + 1);
    cr_assert_not_null(text);
    memset(text, '1', len);
    text[len] = '\0';
    assert_text_fails(text, 1, "line longer than");
    free(text);
}

Test(obj, nul_byte_is_an_error)
{
    write_bytes(OBJ_NAME, "v 0 0 0\nv 1\0 0 0\n", 17);
    assert_file_fails(OBJ_NAME, 2, "NUL byte");
}

Test(obj, missing_mtl_is_an_error)
{
    assert_text_fails("v 0 0 0\nmtllib x.mtl\n", 2,
                      "cannot open material library 'x.mtl'");
}

/* As other viewers do: the faces are drawn with the default material (no
 * texture), and the report carries one warning line for the program. */
Test(obj, unknown_material_is_a_warning_and_the_default_material)
{
    write_text("a.mtl", "newmtl m\nmap_Kd t.png\n");
    write_text(OBJ_NAME, "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl other\nf 1/1 2/1 3/1\n");
    sr_mesh m;
    sr_load_report r = { 0 };
    sr_error e = { "" };
    cr_assert(sr_mesh_load_report(&m, NULL, tmp_path(OBJ_NAME), &r, &e), "%s", e.message);
    cr_assert_eq(m.index_count, 3);
    cr_assert_null(m.texture_path);
    cr_assert_eq(r.warning_count, 1);
    cr_assert_not_null(strstr(r.warnings[0], ":6: material 'other' is not in any material library"), "%s",
                       r.warnings[0]);
    cr_assert_null(strchr(r.warnings[0], '\n'));
    cr_assert_eq(r.part_count, 1);
    cr_assert_str_eq(r.parts[0].material, "");
    sr_load_report_free(&r);
    sr_mesh_free(&m);
}

Test(obj, error_in_mtl_names_the_mtl_file_and_line)
{
    assert_mtl_fails("# materials\nmap_Kd t.png\n", 2, "'map_Kd' before any 'newmtl'");
}

Test(obj, late_error_leaves_no_half_mesh)
{
    write_text("a.mtl", "newmtl m\nmap_Kd t.png\n");
    assert_text_fails("mtllib a.mtl\nv 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
                      "usemtl m\nf 1/1/1 2/1/1 3/1/1\nf 1 2 3\nf 1 2 3\nf 1 2 5\n",
                      11, "out of range");
}

/* Each `mtllib` line read its library again and appended its materials
 * anew: 300 lines (4 KB) naming a 20000-material library (620 KB) took
 * 490 MB. A library read before, by any name, is not read again. */
Test(obj, a_library_named_again_is_not_read_again)
{
    enum { MATERIALS = 20000, LINES = 300 };
    char *lib = malloc((size_t)MATERIALS * 40), *obj = malloc((size_t)LINES * 40 + 200);
    cr_assert(lib && obj);
    size_t n = 0;
    for (int i = 0; i < MATERIALS; i++)
        n += (size_t)sprintf(lib + n, "newmtl m%d\nmap_Kd t%d.png\n", i, i);
    write_bytes("big.mtl", lib, n);
    n = 0;
    for (int i = 0; i < LINES; i++)
        n += (size_t)sprintf(obj + n, "mtllib %sbig.mtl\n", i % 2 ? "./" : "");
    sprintf(obj + n, "usemtl m19999\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n");
    sr_mesh m = load_ok(obj);
    free(lib);
    free(obj);
    cr_expect_str_eq(m.texture_path, tmp_path("t19999.png"));
    sr_mesh_free(&m);
    struct rusage use;
    cr_assert_eq(getrusage(RUSAGE_SELF, &use), 0);
    cr_expect_lt(use.ru_maxrss, 128L * 1024, "peak resident size %ld KiB", use.ru_maxrss);
}

Test(obj, null_error_is_allowed)
{
    write_text(OBJ_NAME, "f 1 2 3\n");
    sr_mesh m;
    cr_assert_not(sr_obj_load(&m, tmp_path(OBJ_NAME), NULL));
    assert_zeroed(&m);
}
