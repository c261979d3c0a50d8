/* What an AMF file holds that Assimp 5.2 reads wrong (amf_read.h). */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "amf_read.h"
#include "amf_xml.h"
#include "core/error.h"

/* The units <amf unit="..."> may state, in metres. */
static const struct {
    const char *name;
    double metres;
} UNITS[] = { { "millimeter", 0.001 }, { "inch", 0.0254 }, { "feet", 0.3048 }, { "meter", 1.0 }, { "micron", 1e-6 } };

/* A placement's names, in the order of sr_amf_instance's values. */
static const char *const PLACEMENTS[6] = { "deltax", "deltay", "deltaz", "rx", "ry", "rz" };

typedef struct reader {
    sr_amf_file *file;
    const char *path;
    sr_error *err;
    size_t objects;       /* the root's objects so far */
    uint32_t volumes;     /* the current object's volumes with triangles */
    uint32_t vertices;    /* the most any of its meshes lists */
    uint32_t mesh_vertices;
    bool volume_has_triangles;
    sr_amf_instance instance;
    char number[SR_AMF_MAX_NAME]; /* a placement's text, "" once too long */
    size_t number_len;
} reader;

/* An id into a name: "" when too long to match a node. */
static void copy_name(char name[SR_AMF_MAX_NAME], const char *id)
{
    const size_t len = strlen(id);
    memcpy(name, id, len < SR_AMF_MAX_NAME ? len + 1 : 1);
    name[len < SR_AMF_MAX_NAME ? len : 0] = '\0';
}

static void *push(reader *r, sr_array *list, size_t elem)
{
    void *at = list->count < SR_AMF_MAX_ENTRIES ? sr_array_push(list, elem) : NULL;
    if (!at)
        sr_error_set(r->err, "%s: out of memory, or more than %u AMF constellations, instances or objects of "
                     "several volumes", r->path, SR_AMF_MAX_ENTRIES);
    return at;
}

static bool on_start(void *user, sr_amf_kind kind, const char *name, const char **attributes)
{
    (void)name;
    reader *r = user;
    if (kind == SR_AMF_OBJECT || kind == SR_AMF_CONSTELLATION)
        r->file->hash_in_id |= strchr(sr_amf_attribute(attributes, "id"), '#') != NULL;
    if (kind == SR_AMF_ROOT) {
        for (size_t i = 0; i < sizeof UNITS / sizeof *UNITS; i++)
            if (strcasecmp(sr_amf_attribute(attributes, "unit"), UNITS[i].name) == 0)
                r->file->metres_per_unit = UNITS[i].metres;
    } else if (kind == SR_AMF_OBJECT) {
        r->volumes = r->vertices = 0;
    } else if (kind == SR_AMF_MESH) {
        r->mesh_vertices = 0;
    } else if (kind == SR_AMF_VERTEX) {
        r->mesh_vertices += r->mesh_vertices < UINT32_MAX;
        r->vertices = r->mesh_vertices > r->vertices ? r->mesh_vertices : r->vertices;
    } else if (kind == SR_AMF_VOLUME) {
        r->volume_has_triangles = false;
    } else if (kind == SR_AMF_TRIANGLE) {
        r->volumes += !r->volume_has_triangles;
        r->volume_has_triangles = true;
    } else if (kind == SR_AMF_CONSTELLATION) {
        sr_amf_constellation *con = push(r, &r->file->constellations, sizeof *con);
        if (!con)
            return false;
        *con = (sr_amf_constellation){ .first = r->file->instances.count };
        copy_name(con->id, sr_amf_attribute(attributes, "id"));
    } else if (kind == SR_AMF_INSTANCE) {
        r->instance = (sr_amf_instance){ .value = { 0 } };
        copy_name(r->instance.objectid, sr_amf_attribute(attributes, "objectid"));
    } else if (kind == SR_AMF_PLACEMENT) {
        r->number[0] = '\0';
        r->number_len = 0;
    }
    return true;
}

static bool on_text(void *user, sr_amf_kind kind, const char *text, size_t len)
{
    reader *r = user;
    for (size_t i = 0; kind == SR_AMF_PLACEMENT && i < len; i++) {
        if (r->number_len == 0 && isspace((unsigned char)text[i]))
            continue;
        if (r->number_len < SR_AMF_MAX_NAME - 1) {
            r->number[r->number_len++] = text[i];
            r->number[r->number_len] = '\0';
        } else {
            r->number_len = SR_AMF_MAX_NAME; /* too long: never grows again */
            r->number[0] = '\0';
        }
    }
    return true;
}

static bool on_end(void *user, sr_amf_kind kind, const char *name)
{
    reader *r = user;
    if (kind == SR_AMF_OBJECT) {
        if (r->volumes > 1) {
            sr_amf_split *split = push(r, &r->file->splits, sizeof *split);
            if (!split)
                return false;
            *split = (sr_amf_split){ .object = r->objects, .vertices = r->vertices };
        }
        r->objects++;
    } else if (kind == SR_AMF_INSTANCE) {
        sr_amf_instance *in = push(r, &r->file->instances, sizeof *in);
        if (!in)
            return false;
        *in = r->instance;
        ((sr_amf_constellation *)r->file->constellations.data)[r->file->constellations.count - 1].count++;
    } else if (kind == SR_AMF_PLACEMENT) {
        char *end;
        const double v = strtod(r->number, &end);
        for (int i = 0; i < 6; i++)
            if (strcmp(name, PLACEMENTS[i]) == 0 && end != r->number && isfinite(v))
                r->instance.value[i] = v;
    }
    return true;
}

bool sr_amf_read(const char *path, sr_amf_file *out, sr_error *err)
{
    *out = (sr_amf_file){ 0 };
    reader r = { .file = out, .path = path, .err = err };
    const sr_amf_walk walk = { &r, on_start, on_text, on_end };
    if (sr_amf_xml_walk(path, &walk, &out->bytes, err))
        return true;
    sr_amf_file_free(out);
    return false;
}

void sr_amf_file_free(sr_amf_file *file)
{
    sr_array_free(&file->constellations);
    sr_array_free(&file->instances);
    sr_array_free(&file->splits);
    *file = (sr_amf_file){ 0 };
}
