#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "mtl.h"
#include "texture_find.h"

static bool out_of_memory(const sr_line_reader *in, sr_error *err)
{
    return sr_line_fail(in, err, "out of memory");
}

static bool parse_newmtl(sr_array *lib, sr_line_reader *in, char *cursor, sr_error *err)
{
    /* The whole rest is the name: exporters write names with spaces. */
    const char *name = sr_obj_rest(cursor);
    if (!*name)
        return sr_line_fail(in, err, "'newmtl' needs a material name");
    char *copy = strdup(name);
    sr_mtl_material *m = copy ? sr_array_push(lib, sizeof *m) : NULL;
    if (!m) {
        free(copy);
        return out_of_memory(in, err);
    }
    *m = (sr_mtl_material){ .name = copy, .mesh_material = -1 };
    return true;
}

/* Options (-s 1 1 1, -clamp on, -bm 0.5, …) precede the file name and take
 * different numbers of arguments; when there are options the name is the last
 * token, otherwise it is the whole rest, which may contain spaces. */
static const char *map_file_name(char *rest)
{
    if (rest[0] != '-')
        return rest;
    const char *name = rest;
    for (const char *s = rest; *s; s++)
        if ((s[0] == ' ' || s[0] == '\t') && s[1] && s[1] != ' ' && s[1] != '\t')
            name = s + 1;
    return name;
}

static bool parse_map_kd(sr_array *lib, sr_line_reader *in, char *cursor, sr_error *err)
{
    if (lib->count == 0)
        return sr_line_fail(in, err, "'map_Kd' before any 'newmtl'");
    const char *file = map_file_name(sr_obj_rest(cursor));
    if (!*file || file[0] == '-')
        return sr_line_fail(in, err, "'map_Kd' needs a file name");
    sr_mtl_material *m = (sr_mtl_material *)lib->data + lib->count - 1;
    char *path = sr_obj_path_beside(in->path, file), *written = strdup(file), *library = strdup(in->path);
    if (!path || !written || !library) {
        free(path);
        free(written);
        free(library);
        return out_of_memory(in, err);
    }
    free(m->map_kd); /* a repeated map_Kd overrides, as in other readers */
    free(m->map_kd_written);
    free(m->library);
    m->map_kd = path;
    m->map_kd_written = written;
    m->library = library;
    return true;
}

/* `Kd r g b`, or `Kd r` for a gray; the spectral and CIE XYZ forms
 * (`Kd spectral …`, `Kd xyz …`) are read past. */
static bool parse_kd(sr_array *lib, sr_line_reader *in, char *cursor, sr_error *err)
{
    if (lib->count == 0)
        return sr_line_fail(in, err, "'Kd' before any 'newmtl'");
    const char *rest = cursor + strspn(cursor, " \t");
    if (*rest >= 'a' && *rest <= 'z')
        return true;
    double d[3];
    int n = sr_obj_parse_numbers(in, cursor, d, 3, err);
    if (n < 0)
        return false;
    if (n != 1 && n != 3)
        return sr_line_fail(in, err, "'Kd' needs r g b or one gray, got %d numbers", n);
    sr_mtl_material *m = (sr_mtl_material *)lib->data + lib->count - 1;
    for (int k = 0; k < 3; k++)
        m->kd[k] = (float)d[n == 3 ? k : 0];
    m->has_kd = true;
    return true;
}

static bool parse_mtl_statement(sr_array *lib, sr_line_reader *in, char *line,
                                sr_error *err)
{
    char *cursor = line;
    const char *keyword = sr_obj_next_token(&cursor);
    if (!keyword)
        return true;
    if (strcmp(keyword, "newmtl") == 0)
        return parse_newmtl(lib, in, cursor, err);
    /* Some exporters write "map_kd"; the keyword means the same. */
    if (strcasecmp(keyword, "map_Kd") == 0)
        return parse_map_kd(lib, in, cursor, err);
    if (strcmp(keyword, "Kd") == 0)
        return parse_kd(lib, in, cursor, err);
    return true;
}

static bool read_library(sr_array *lib, sr_line_reader *in, sr_error *err)
{
    for (;;) {
        char *line;
        if (!sr_line_reader_next(in, &line, err))
            return false;
        if (!line)
            return true;
        if (!parse_mtl_statement(lib, in, line, err))
            return false;
    }
}

/* Whether the open library is one read before; if not, it is noted as read. */
static int already_read(sr_mtl_libs *libs, const sr_line_reader *in, const sr_line_reader *obj, sr_error *err)
{
    struct stat st;
    if (fstat(fileno(in->file), &st) != 0)
        return 0;
    sr_mtl_file_id id = { (unsigned long long)st.st_dev, (unsigned long long)st.st_ino };
    const sr_mtl_file_id *seen = libs->files.data;
    for (size_t i = 0; i < libs->files.count; i++)
        if (seen[i].dev == id.dev && seen[i].ino == id.ino)
            return 1;
    sr_mtl_file_id *slot = sr_array_push(&libs->files, sizeof *slot);
    if (!slot) {
        out_of_memory(obj, err);
        return -1;
    }
    *slot = id;
    return 0;
}

/* 1 loaded (or read before), 0 cannot open (*why says why), -1 error in the
 * library (err set). */
static int load_library(sr_mtl_libs *libs, const sr_line_reader *obj, const char *name,
                        const char **why, sr_error *err)
{
    char *path = sr_obj_path_beside(obj->path, name);
    if (!path) {
        out_of_memory(obj, err);
        return -1;
    }
    sr_line_reader in;
    int status = 0;
    if (sr_line_reader_open(&in, path)) {
        int seen = already_read(libs, &in, obj, err);
        status = seen != 0 ? seen : read_library(&libs->materials, &in, err) ? 1 : -1;
        sr_line_reader_close(&in);
    } else {
        *why = in.why;
    }
    free(path);
    return status;
}

static bool cannot_open(const sr_line_reader *obj, const char *name, const char *why, sr_error *err)
{
    return sr_line_fail(obj, err, "cannot open material library '%s': %s", name, why);
}

/* Usually one name, which may contain spaces (Blender names the library after
 * the OBJ); the format also allows several names separated by blanks, which
 * is tried when the whole rest is not a file. A missing library is an error:
 * softrast never drops a texture silently. */
bool sr_mtl_load(sr_mtl_libs *libs, const sr_line_reader *obj, char *names, sr_error *err)
{
    if (!*names)
        return sr_line_fail(obj, err, "'mtllib' needs a file name");
    const char *why = NULL;
    int status = load_library(libs, obj, names, &why, err);
    if (status != 0)
        return status > 0;
    if (!strpbrk(names, " \t"))
        return cannot_open(obj, names, why, err);
    for (char *name; (name = sr_obj_next_token(&names));) {
        status = load_library(libs, obj, name, &why, err);
        if (status == 0)
            return cannot_open(obj, name, why, err);
        if (status < 0)
            return false;
    }
    return true;
}

ptrdiff_t sr_mtl_find(const sr_mtl_libs *libs, const char *name)
{
    const sr_mtl_material *m = libs->materials.data;
    for (size_t i = 0; i < libs->materials.count; i++)
        if (strcmp(m[i].name, name) == 0)
            return (ptrdiff_t)i;
    return -1;
}

void sr_mtl_find_texture(sr_mtl_material *m)
{
    if (!m->map_kd || m->map_kd_searched)
        return;
    m->map_kd_searched = true;
    char *found = sr_texture_find(m->library, m->map_kd_written);
    if (found) {
        free(m->map_kd);
        m->map_kd = found;
        m->map_kd_found = true;
    }
}

void sr_mtl_free(sr_mtl_libs *libs)
{
    sr_mtl_material *m = libs->materials.data;
    for (size_t i = 0; i < libs->materials.count; i++) {
        free(m[i].name);
        free(m[i].map_kd);
        free(m[i].map_kd_written);
        free(m[i].library);
    }
    sr_array_free(&libs->materials);
    sr_array_free(&libs->files);
}
