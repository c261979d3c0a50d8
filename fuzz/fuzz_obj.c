/* fuzz/fuzz_obj.c — libFuzzer target for the OBJ/MTL loader.
 *
 * The input is an OBJ file; if it holds a line "#mtl", everything after that
 * line is written beside it as the material library "m.mtl" (so `mtllib
 * m.mtl` finds it), otherwise no m.mtl exists. Both live in a folder of this
 * process's own, /tmp/softrast-fuzz-obj-PID/, rewritten for every input so a
 * run depends on the input alone. Inputs with an `mtllib` line naming a path
 * with '/' are skipped (returned -1), so the loader never reads files outside
 * that folder (/dev/stdin would block, /proc changes from run to run).
 *
 * sr_obj_load must then either succeed with a consistent mesh (obj.h): a
 * TriangleList whose indices are in range, every vertex used by a face, every
 * attribute finite — which sr_draw must accept — or fail with a "FILE:LINE:
 * what" or "FILE: what" message naming the OBJ or its library and leave the
 * mesh zeroed, whatever it held before.
 */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cglm/cglm.h>
#include <cglm/clipspace/persp_lh_zo.h>
#include <cglm/clipspace/view_lh.h>

#include "softrast_private.h"

#include "fuzz_common.h"    /* fail(), CHECK() */
#include "fuzz_materials.h" /* check_materials() */

#define MTL_SEPARATOR "\n#mtl\n"
#define MTL_NAME "m.mtl"
#define DRAW_SIDE 16
#define DRAW_MAX_VERTICES 4096 /* keeps each run fast; the loader's limits are tested by tests/ */

static char dir[64], obj_path[96], mtl_path[96];

/* ---- the scratch folder ------------------------------------------------- */

static void remove_scratch(void)
{
    unlink(obj_path);
    unlink(mtl_path);
    rmdir(dir);
}

/* A run that crashed (that is what fuzzing is for) never reached atexit:
 * remove the folders of processes that no longer exist. */
static void remove_stale_scratch(void)
{
    DIR *tmp = opendir("/tmp");
    if (!tmp)
        return;
    for (struct dirent *e; (e = readdir(tmp));) {
        long pid;
        char tail;
        if (sscanf(e->d_name, "softrast-fuzz-obj-%ld%c", &pid, &tail) != 1 || pid <= 0)
            continue;
        if (kill((pid_t)pid, 0) == 0 || errno != ESRCH)
            continue;
        char path[sizeof dir + 16];
        const char *files[] = { "in.obj", MTL_NAME };
        for (int i = 0; i < 2; i++) {
            snprintf(path, sizeof path, "/tmp/%.40s/%s", e->d_name, files[i]);
            unlink(path);
        }
        snprintf(path, sizeof path, "/tmp/%.40s", e->d_name);
        rmdir(path);
    }
    closedir(tmp);
}

int LLVMFuzzerInitialize(int *argc, char ***argv);

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    remove_stale_scratch();
    snprintf(dir, sizeof dir, "/tmp/softrast-fuzz-obj-%ld", (long)getpid());
    snprintf(obj_path, sizeof obj_path, "%s/in.obj", dir);
    snprintf(mtl_path, sizeof mtl_path, "%s/%s", dir, MTL_NAME);
    if (mkdir(dir, 0700) != 0) {
        perror(dir);
        exit(1);
    }
    atexit(remove_scratch);
    return 0;
}

static void write_file(const char *path, const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL, "cannot create %s", path);
    CHECK(size == 0 || fwrite(data, 1, size, f) == size, "cannot write %s", path);
    CHECK(fclose(f) == 0, "cannot close %s", path);
}

static const uint8_t *find_bytes(const uint8_t *hay, size_t n, const char *needle)
{
    size_t m = strlen(needle);
    for (size_t i = 0; m <= n && i <= n - m; i++)
        if (memcmp(hay + i, needle, m) == 0)
            return hay + i;
    return NULL;
}

/* Whether some line's first token is `f` (tokens end at a blank or a '#',
 * as the loader's do; the first line may open with a UTF-8 BOM): the file
 * has a face statement. */
static bool has_face_statement(const uint8_t *data, size_t size)
{
    size_t i = size >= 3 && memcmp(data, "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;
    bool line_start = true;
    for (; i < size; i++) {
        uint8_t c = data[i];
        if (c == '\n' || c == '\r') {
            line_start = true;
            continue;
        }
        if (line_start && (c == ' ' || c == '\t' || c == '\v' || c == '\f'))
            continue;
        if (line_start && c == 'f' &&
            (i + 1 == size || strchr(" \t\v\f\r\n#", data[i + 1]) != NULL)) /* strchr finds '\0' too */
            return true;
        line_start = false;
    }
    return false;
}

/* True if some line mentions mtllib and a '/' (any such line, to stay on the
 * safe side of how the loader tokenizes). */
static bool names_outside_path(const uint8_t *data, size_t size)
{
    size_t start = 0;
    while (start < size) {
        const uint8_t *nl = memchr(data + start, '\n', size - start);
        size_t end = nl ? (size_t)(nl - data) : size;
        if (find_bytes(data + start, end - start, "mtllib") && memchr(data + start, '/', end - start))
            return true;
        start = end + 1;
    }
    return false;
}

/* Lines as the loader counts them: each ends at "\n", "\r\n" or a lone "\r". */
static size_t count_lines(const uint8_t *data, size_t size)
{
    size_t n = 1;
    for (size_t i = 0; i < size; i++)
        n += data[i] == '\n' || (data[i] == '\r' && (i + 1 == size || data[i + 1] != '\n'));
    return n;
}

/* ---- checks ------------------------------------------------------------- */

static bool finite_n(const float *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return false;
    return true;
}

static void check_mesh(const sr_mesh *m, bool has_usemtl, bool has_faces)
{
    CHECK(m->topology == SR_TRIANGLE_LIST, "topology %d", m->topology);
    CHECK(m->index_count % 3 == 0, "%u indices", m->index_count);
    CHECK(m->index_count == 0 || m->vertex_count > 0, "%u vertices, %u indices", m->vertex_count, m->index_count);
    /* a file without faces is a point cloud: its vertices, no uvs (only a face corner names one), normals
       only paired one to a vertex; a file with faces that loads has triangles */
    CHECK(m->index_count > 0 || !m->uvs, "a cloud of %u vertices with uvs", m->vertex_count);
    CHECK(m->index_count > 0 || m->vertex_count == 0 || !has_faces, "faces loaded as a cloud of %u vertices",
          m->vertex_count);
    CHECK((m->positions != NULL) == (m->vertex_count > 0), "positions %p for %u vertices", (void *)m->positions,
          m->vertex_count);
    CHECK(m->index_count == 0 || m->indices != NULL, "no index array for %u indices", m->index_count);
    CHECK(m->vertex_count > 0 || (!m->normals && !m->uvs && !m->colors), "attributes without vertices");
    bool *used = calloc(m->vertex_count ? m->vertex_count : 1, sizeof *used);
    CHECK(used != NULL, "out of memory");
    for (uint32_t i = 0; i < m->index_count; i++) {
        CHECK(m->indices[i] < m->vertex_count, "index %u = %u of %u vertices", i, m->indices[i], m->vertex_count);
        used[m->indices[i]] = true;
    }
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        CHECK(used[v] || m->index_count == 0, "vertex %u is not used by any face (vertices are face corners)", v);
        CHECK(finite_n(m->positions[v], 3), "position %u (%a, %a, %a)", v, m->positions[v][0], m->positions[v][1],
              m->positions[v][2]);
        CHECK(!m->normals || finite_n(m->normals[v], 3), "normal %u not finite", v);
        CHECK(!m->uvs || finite_n(m->uvs[v], 2), "uv %u not finite", v);
        CHECK(!m->colors || finite_n(m->colors[v], 3), "color %u not finite", v);
    }
    free(used);
    CHECK(!m->texture_path || (m->texture_path[0] != '\0' && has_usemtl), "texture path '%s'",
          m->texture_path ? m->texture_path : "(null)");
    if (m->vertex_count > 0) {
        vec3 lo, hi;
        CHECK(sr_mesh_bounds(m, lo, hi), "no bounds for %u finite vertices", m->vertex_count);
    }
}

/* A loaded mesh is drawable: in-range indices are all sr_draw asks for in id
 * mode, and whatever the positions, depth stays in [0, 1]. */
static void check_drawable(const sr_mesh *m)
{
    if (m->vertex_count > DRAW_MAX_VERTICES)
        return;
    /* Known: drawing a mesh without vertices does arithmetic on a NULL
     * array (UBSan: src/draw/draw.c, vertex_range); see README. */
    if (m->vertex_count == 0 && getenv("FUZZ_TOLERATE") && strstr(getenv("FUZZ_TOLERATE"), "empty_draw"))
        return;
    sr_framebuffer fb;
    CHECK(sr_framebuffer_create(&fb, DRAW_SIDE, DRAW_SIDE, NULL), "framebuffer");
    sr_framebuffer_clear(&fb, 0);
    sr_draw_desc desc = { .mesh = m, .shade = SR_SHADE_ID, .cull = SR_CULL_NONE };
    glm_lookat_lh((vec3){ 0.0f, 0.0f, -3.0f }, (vec3){ 0.0f, 0.0f, 0.0f }, (vec3){ 0.0f, 1.0f, 0.0f }, desc.view);
    glm_perspective_lh_zo(glm_rad(60.0f), 1.0f, 0.1f, 100.0f, desc.projection);
    sr_stats stats = { 0 };
    sr_error err = { .message = "" };
    bool ok = sr_draw(&fb, &desc, &stats, &err);
    CHECK(ok, "sr_draw refused a loaded mesh: %s", err.message);
    CHECK(stats.triangles <= m->index_count / 3, "%llu triangles from %u indices",
          (unsigned long long)stats.triangles, m->index_count);
    for (int p = 0; p < DRAW_SIDE * DRAW_SIDE; p++)
        CHECK(isfinite(fb.depth[p]) && fb.depth[p] >= 0.0f && fb.depth[p] <= 1.0f, "depth %a", fb.depth[p]);
    sr_framebuffer_destroy(&fb);
}

/* "PATH:LINE: what" or "PATH: what", PATH the OBJ or (with an mtllib) a file
 * in the same folder; for the OBJ, LINE is one of its lines. */
static void check_message(const char *msg, size_t obj_lines, bool has_mtllib)
{
    CHECK(msg[0] != '\0', "failed without a message");
    size_t obj_len = strlen(obj_path), dir_len = strlen(dir);
    bool about_obj = strncmp(msg, obj_path, obj_len) == 0 && msg[obj_len] == ':';
    bool about_lib = has_mtllib && strncmp(msg, dir, dir_len) == 0 && msg[dir_len] == '/';
    CHECK(about_obj || about_lib, "message does not start with the file: '%s'", msg);
    const char *rest = about_obj ? msg + obj_len : strchr(msg + dir_len, ':');
    CHECK(rest && *rest == ':', "no ':' after the path: '%s'", msg);
    rest++;
    if (*rest == ' ') {
        CHECK(rest[1] != '\0', "empty message after the path: '%s'", msg);
        return;
    }
    char *end;
    unsigned long line = strtoul(rest, &end, 10);
    CHECK(end != rest && end[0] == ':' && end[1] == ' ' && end[2] != '\0', "not PATH:LINE: what: '%s'", msg);
    CHECK(line >= 1, "line 0: '%s'", msg);
    CHECK(!about_obj || line <= obj_lines, "line %lu of a %zu-line file: '%s'", line, obj_lines, msg);
}

static bool mesh_is_zero(const sr_mesh *m)
{
    return m->vertex_count == 0 && !m->positions && !m->normals && !m->uvs && !m->colors && m->index_count == 0 &&
           !m->indices && m->topology == SR_TRIANGLE_LIST && !m->texture_path;
}

/* ---- entry point -------------------------------------------------------- */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (names_outside_path(data, size))
        return -1;
    const uint8_t *sep = find_bytes(data, size, MTL_SEPARATOR);
    size_t obj_size = sep ? (size_t)(sep - data) + 1 : size; /* keep the '\n' that ends the OBJ */
    write_file(obj_path, data, obj_size);
    if (sep) {
        const uint8_t *mtl = sep + strlen(MTL_SEPARATOR);
        write_file(mtl_path, mtl, size - (size_t)(mtl - data));
    } else {
        unlink(mtl_path);
    }
    bool has_mtllib = find_bytes(data, obj_size, "mtllib") != NULL;
    bool has_usemtl = find_bytes(data, obj_size, "usemtl") != NULL;
    bool has_faces = has_face_statement(data, obj_size);

    /* Whatever the mesh held before, a failed load leaves it zeroed and a
     * load never frees it (obj.h): garbage that is not heap memory would
     * make ASan report a bad free. */
    static vec3 not_heap[1];
    sr_mesh mesh = { .vertex_count = 7, .positions = not_heap, .index_count = 3, .topology = SR_TRIANGLE_STRIP };
    sr_error err = { .message = "" };
    if (sr_obj_load(&mesh, obj_path, &err)) {
        check_mesh(&mesh, has_usemtl, has_faces);
        check_materials(&mesh);
        check_drawable(&mesh);
        sr_error ignored;
        sr_mesh_compute_normals(&mesh, &ignored); /* for the sanitizers: no claim on the result */
    } else {
        check_message(err.message, count_lines(data, obj_size), has_mtllib);
        CHECK(mesh_is_zero(&mesh), "failed load left the mesh non-zero: %s", err.message);
    }
    sr_mesh_free(&mesh);
    return 0;
}
