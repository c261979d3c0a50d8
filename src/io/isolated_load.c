/* A loader run in a child process, its mesh sent back through a pipe.
 *
 * Third-party importers (Assimp) cannot be made crash- and hang-free from
 * outside: a hostile file may crash one or loop for ever. In a child, a
 * crash is a signal the parent reads and reports, and a loop ends at the
 * child's CPU-time limit (SIGXCPU), a read that blocks (a glTF naming a FIFO
 * as its buffer) at its alarm (SIGALRM). The child writes a header, then the
 * mesh's arrays and materials or the error message; the parent checks the counts against
 * the documented limits before it allocates, so a lying child cannot make
 * it allocate more than those allow.
 */
#include <errno.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/error.h"
#include "isolated_load.h"

typedef struct wire_header {
    uint32_t ok;
    uint32_t vertex_count, index_count;
    uint32_t has_normals, has_uvs, has_colors, part_count;
    uint32_t texture_width, texture_height; /* 0: no texture */
    uint32_t text_len; /* the texture path (ok) or the message (not ok), without its NUL */
    uint32_t has_report; /* a report follows the arrays */
    uint32_t material_count; /* wire_materials follow the arrays, each with its texture path */
    double origin[3];
} wire_header;

/* A material on the wire: its texture is the embedded one (the loader's
 * texture), a path of path_len bytes after it, or none. */
typedef struct wire_material {
    float base_color[4];
    uint32_t alpha_mode;
    float alpha_cutoff;
    uint32_t embedded;
    uint32_t path_len;
} wire_material;

/* A texture path longer than this is refused (no file system has one). */
#define WIRE_PATH_MAX 65536

/* The loader the child runs: one of the two kinds. */
typedef struct child_loader {
    sr_isolated_loader plain;
    sr_isolated_report_loader reporting;
} child_loader;

/* Moves n bytes through the pipe, whole: write when `out`, else read. */
static bool transfer(int fd, void *data, size_t n, bool out)
{
    char *p = data;
    while (n > 0) {
        ssize_t done = out ? write(fd, p, n) : read(fd, p, n);
        if (done < 0 && errno == EINTR)
            continue;
        if (done <= 0)
            return false;
        p += done;
        n -= (size_t)done;
    }
    return true;
}

static bool write_all(int fd, const void *data, size_t n)
{
    return transfer(fd, (void *)data, n, true);
}

static bool read_all(int fd, void *data, size_t n)
{
    return transfer(fd, data, n, false);
}

/* Each optional array: its element size, and where it sits in the mesh. */
typedef struct wire_array {
    void **data;
    size_t elem;
    uint32_t count;
} wire_array;

#define WIRE_ARRAYS 7

static int wire_arrays(sr_mesh *m, sr_texture *t, wire_array out[WIRE_ARRAYS])
{
    int n = 0;
    out[n++] = (wire_array){ (void **)&m->positions, sizeof *m->positions, m->vertex_count };
    if (m->normals)
        out[n++] = (wire_array){ (void **)&m->normals, sizeof *m->normals, m->vertex_count };
    if (m->uvs)
        out[n++] = (wire_array){ (void **)&m->uvs, sizeof *m->uvs, m->vertex_count };
    if (m->colors)
        out[n++] = (wire_array){ (void **)&m->colors, sizeof *m->colors, m->vertex_count };
    out[n++] = (wire_array){ (void **)&m->indices, sizeof *m->indices, m->index_count };
    if (m->parts)
        out[n++] = (wire_array){ (void **)&m->parts, sizeof *m->parts, m->part_count };
    if (t->texels)
        out[n++] = (wire_array){ (void **)&t->texels, sizeof *t->texels, (uint32_t)t->width * (uint32_t)t->height };
    return n;
}

/* The report's fixed part, then its parts and textures. */
static bool send_report(int fd, const sr_load_report *r)
{
    return write_all(fd, r, sizeof *r) && write_all(fd, r->parts, r->part_count * sizeof *r->parts) &&
           write_all(fd, r->textures, r->texture_count * sizeof *r->textures);
}

static bool send_materials(int fd, const sr_mesh *m, const sr_texture *t)
{
    for (uint32_t i = 0; i < m->material_count; i++) {
        const sr_material *s = &m->materials[i];
        wire_material w = { .alpha_mode = (uint32_t)s->alpha_mode, .alpha_cutoff = s->alpha_cutoff,
                            .embedded = s->texture == t && t->texels,
                            .path_len = s->texture_path ? (uint32_t)strlen(s->texture_path) : 0 };
        memcpy(w.base_color, s->base_color, sizeof w.base_color);
        if (!write_all(fd, &w, sizeof w) || !write_all(fd, s->texture_path, w.path_len))
            return false;
    }
    return true;
}

/* The child's materials, checked as the draw would check them (the alpha
 * mode; a part naming one past the table), into mesh; the embedded texture
 * is `texture`. */
static bool receive_materials(int fd, uint32_t count, sr_mesh *mesh, sr_texture *texture)
{
    mesh->materials = calloc(count ? count : 1, sizeof *mesh->materials);
    if (!mesh->materials)
        return false;
    mesh->material_count = count;
    for (uint32_t i = 0; i < count; i++) {
        sr_material *m = &mesh->materials[i];
        wire_material w;
        if (!read_all(fd, &w, sizeof w) || w.alpha_mode > SR_ALPHA_BLEND || w.path_len > WIRE_PATH_MAX)
            return false;
        *m = (sr_material){ .alpha_mode = (sr_alpha_mode)w.alpha_mode, .alpha_cutoff = w.alpha_cutoff,
                            .texture = w.embedded && texture->texels ? texture : NULL };
        memcpy(m->base_color, w.base_color, sizeof m->base_color);
        if (w.path_len > 0) {
            m->texture_path = malloc((size_t)w.path_len + 1);
            if (!m->texture_path || !read_all(fd, m->texture_path, w.path_len))
                return false;
            m->texture_path[w.path_len] = '\0';
        }
    }
    for (uint32_t i = 0; i < mesh->part_count; i++)
        if (count > 0 && mesh->parts[i].material >= count)
            return false;
    return true;
}

static void terminate(char *text)
{
    text[SR_REPORT_TEXT - 1] = '\0';
}

/* The child's report, checked: counts within the limits, enumerations in
 * range, every text ended. */
static bool receive_report(int fd, sr_load_report *r)
{
    sr_load_report got;
    if (!read_all(fd, &got, sizeof got) || got.part_count > SR_REPORT_MAX_PARTS ||
        got.texture_count > SR_REPORT_MAX_TEXTURES || got.up >= SR_AXIS_COUNT || got.up_found > SR_FOUND_READ ||
        got.units_found > SR_FOUND_READ)
        return false;
    got.parts = calloc(got.part_count ? got.part_count : 1, sizeof *got.parts);
    got.textures = calloc(got.texture_count ? got.texture_count : 1, sizeof *got.textures);
    bool ok = got.parts && got.textures && read_all(fd, got.parts, got.part_count * sizeof *got.parts) &&
              read_all(fd, got.textures, got.texture_count * sizeof *got.textures);
    terminate(got.format);
    terminate(got.up_why);
    terminate(got.units_why);
    for (uint32_t i = 0; i < SR_REPORT_MAX_WARNINGS; i++)
        terminate(got.warnings[i]);
    for (uint32_t i = 0; ok && i < got.part_count; i++) {
        terminate(got.parts[i].material);
        if (got.parts[i].texture < -1 || got.parts[i].texture >= (int32_t)got.texture_count)
            got.parts[i].texture = -1;
    }
    for (uint32_t i = 0; ok && i < got.texture_count; i++) {
        terminate(got.textures[i].name);
        terminate(got.textures[i].path);
        ok = got.textures[i].status <= SR_TEXTURE_MISSING;
    }
    if (!ok) {
        sr_load_report_free(&got);
        return false;
    }
    *r = got;
    return true;
}

static void child_run(int fd, const char *path, child_loader load, unsigned seconds)
{
    /* A crash must end the child with its signal, whatever handlers the
     * parent installed (a sanitizer's, a fuzzer's, an embedder's). */
    static const int deadly[] = { SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGPIPE, SIGXCPU, SIGALRM };
    for (size_t i = 0; i < sizeof deadly / sizeof *deadly; i++)
        signal(deadly[i], SIG_DFL);
    setrlimit(RLIMIT_CPU, &(struct rlimit){ seconds, seconds + 1 }); /* a loop */
    alarm(seconds);                                                  /* a read that blocks */
    sr_mesh m;
    sr_texture t = { 0 };
    sr_error err = { "" };
    sr_load_report report = { 0 };
    bool ok = load.reporting ? load.reporting(&m, &t, path, &report, &err) : load.plain(&m, &t, path, &err);
    const char *text = ok ? (m.texture_path ? m.texture_path : "") : err.message;
    wire_header h = { .ok = ok, .text_len = (uint32_t)strlen(text), .has_report = ok && load.reporting };
    if (ok) {
        h.vertex_count = m.vertex_count;
        h.index_count = m.index_count;
        h.has_normals = m.normals != NULL;
        h.has_uvs = m.uvs != NULL;
        h.has_colors = m.colors != NULL;
        h.part_count = m.parts ? m.part_count : 0;
        h.material_count = m.materials ? m.material_count : 0;
        h.texture_width = t.texels ? (uint32_t)t.width : 0;
        h.texture_height = t.texels ? (uint32_t)t.height : 0;
        memcpy(h.origin, m.origin, sizeof h.origin);
    }
    bool sent = write_all(fd, &h, sizeof h) && write_all(fd, text, h.text_len);
    wire_array arrays[WIRE_ARRAYS];
    for (int i = 0, n = ok ? wire_arrays(&m, &t, arrays) : 0; sent && i < n; i++)
        sent = write_all(fd, *arrays[i].data, arrays[i].elem * arrays[i].count);
    if (sent && ok)
        sent = send_materials(fd, &m, &t);
    if (sent && h.has_report)
        sent = send_report(fd, &report);
    _exit(sent ? 0 : 1); /* no atexit handlers of the parent's libraries in the child */
}

static bool texture_fits(uint32_t width, uint32_t height)
{
    return width <= SR_MAX_TEXTURE_SIDE && height <= SR_MAX_TEXTURE_SIDE &&
           (uint64_t)width * height <= SR_MAX_TEXTURE_TEXELS && (width == 0) == (height == 0);
}

static bool receive_mesh(int fd, const wire_header *h, sr_mesh *mesh, sr_texture *texture, const char *path,
                         sr_load_report *report, sr_error *err)
{
    if (h->vertex_count > SR_MAX_MESH_VERTICES || h->index_count / 3 > SR_MAX_MESH_TRIANGLES ||
        h->index_count % 3 != 0 || h->part_count > h->index_count / 3 || h->text_len > SR_ERROR_MAX * 8 ||
        h->material_count > SR_MAX_MESH_MATERIALS ||
        !texture_fits(h->texture_width, h->texture_height))
        return sr_error_set(err, "%s: the importer sent a mesh past the limits", path);
    if (!sr_mesh_alloc(mesh, h->vertex_count, h->index_count, h->has_normals, h->has_uvs, h->has_colors, err))
        return false;
    memcpy(mesh->origin, h->origin, sizeof mesh->origin);
    if (h->part_count > 0) {
        mesh->parts = malloc(h->part_count * sizeof *mesh->parts);
        if (!mesh->parts)
            return sr_error_set(err, "%s: out of memory for %u parts", path, h->part_count);
        mesh->part_count = h->part_count;
    }
    if (h->texture_width > 0) {
        texture->texels = malloc((size_t)h->texture_width * h->texture_height * sizeof *texture->texels);
        if (!texture->texels)
            return sr_error_set(err, "%s: out of memory for a %ux%u texture", path, h->texture_width,
                                h->texture_height);
        texture->width = (int)h->texture_width;
        texture->height = (int)h->texture_height;
    }
    char *texture_path = malloc((size_t)h->text_len + 1);
    bool ok = texture_path && read_all(fd, texture_path, h->text_len);
    if (ok && h->text_len > 0) {
        texture_path[h->text_len] = '\0';
        mesh->texture_path = texture_path;
    } else {
        free(texture_path);
    }
    wire_array arrays[WIRE_ARRAYS];
    for (int i = 0, n = wire_arrays(mesh, texture, arrays); ok && i < n; i++)
        ok = read_all(fd, *arrays[i].data, arrays[i].elem * arrays[i].count);
    if (!ok)
        return sr_error_set(err, "%s: the importer stopped while sending the mesh", path);
    if (h->material_count > 0 && !receive_materials(fd, h->material_count, mesh, texture))
        return sr_error_set(err, "%s: the importer sent materials past the limits", path);
    sr_load_report unwanted = { 0 };
    if (h->has_report && !receive_report(fd, report ? report : &unwanted))
        return sr_error_set(err, "%s: the importer sent a report past the limits", path);
    sr_load_report_free(&unwanted);
    return true;
}

static bool receive(int fd, sr_mesh *mesh, sr_texture *texture, const char *path, sr_load_report *report,
                    sr_error *err)
{
    wire_header h;
    if (!read_all(fd, &h, sizeof h))
        return sr_error_set(err, "%s: the importer sent nothing", path);
    if (h.ok)
        return receive_mesh(fd, &h, mesh, texture, path, report, err);
    char message[SR_ERROR_MAX] = "";
    size_t n = h.text_len < sizeof message - 1 ? h.text_len : sizeof message - 1;
    read_all(fd, message, n);
    return sr_error_set(err, "%s", message);
}

/* A child that died says why; one that exited cleanly said it through the pipe. */
static bool child_status(pid_t pid, const char *path, unsigned seconds, sr_error *err)
{
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return sr_error_set(err, "%s: lost the importer: %s", path, strerror(errno));
    if (WIFSIGNALED(status) && (WTERMSIG(status) == SIGXCPU || WTERMSIG(status) == SIGALRM))
        return sr_error_set(err, "%s: the importer took more than %u s", path, seconds);
    if (WIFSIGNALED(status))
        return sr_error_set(err, "%s: the importer crashed on this file (%s)", path, strsignal(WTERMSIG(status)));
    return true;
}

static bool isolated_load(sr_mesh *mesh, sr_texture *texture, const char *path, child_loader load, unsigned seconds,
                          sr_load_report *report, sr_error *err)
{
    *mesh = (sr_mesh){ 0 };
    *texture = (sr_texture){ 0 };
    int fds[2];
    if (pipe(fds) != 0)
        return sr_error_set(err, "%s: cannot start the importer: %s", path, strerror(errno));
    pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]);
        close(fds[1]);
        return sr_error_set(err, "%s: cannot start the importer: %s", path, strerror(errno));
    }
    if (pid == 0) {
        close(fds[0]);
        child_run(fds[1], path, load, seconds);
    }
    close(fds[1]);
    sr_error received = { "" }, died = { "" };
    bool ok = receive(fds[0], mesh, texture, path, report, &received);
    close(fds[0]);
    bool lived = child_status(pid, path, seconds, &died);
    if (lived && ok)
        return true;
    sr_mesh_free(mesh);
    sr_texture_free(texture);
    sr_load_report_free(report);
    return sr_error_set(err, "%s", lived ? received.message : died.message);
}

bool sr_isolated_load(sr_mesh *mesh, sr_texture *texture, const char *path, sr_isolated_loader load, unsigned seconds,
                      sr_error *err)
{
    return isolated_load(mesh, texture, path, (child_loader){ .plain = load }, seconds, NULL, err);
}

bool sr_isolated_load_report(sr_mesh *mesh, sr_texture *texture, const char *path, sr_isolated_report_loader load,
                             unsigned seconds, sr_load_report *report, sr_error *err)
{
    return isolated_load(mesh, texture, path, (child_loader){ .reporting = load }, seconds, report, err);
}
