/* Wavefront OBJ -> sr_mesh, in one pass over the file.
 *
 * Attribute lines (v, vt, vn) are kept as read. Each face corner is resolved
 * against the attributes read so far (as the format requires, which also
 * fixes what a negative index means) and interned: a hash map from the
 * (v, vt, vn) triple to its mesh vertex keeps the whole load O(n). The
 * right-to-left-handed flip happens where triangles and vertices are written:
 * z is negated and each fan triangle (c0, ck, ck+1) is emitted as
 * (c0, ck+1, ck). Positions are read in double; a mesh far from the world
 * origin (mesh.h: SR_MESH_RECENTRE_RATIO) is stored relative to the centre
 * of its bounds, computed in double, with the centre as the mesh's origin.
 * A file without faces is a point cloud (as scanners and CloudCompare
 * write one): every vertex is kept, in file order, with its colour, and
 * with the normal of the same number when the file has one `vn` a `v`.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "softrast/files.h"

#include "load_report.h"
#include "mtl.h"
#include "obj_parse.h"
#include "core/error.h"
#include "mesh_origin.h"

#define NONE UINT32_MAX            /* a corner without vt or vn */
#define MAX_ITEMS (UINT32_MAX - 1) /* so every index fits in uint32_t and NONE stays free */
#define MAP_MIN_CAP 1024u

typedef double dvec3[3];

typedef struct corner {
    uint32_t v, vt, vn; /* 0-based into the attributes as read, or NONE */
} corner;

typedef struct obj_reader {
    sr_line_reader in;
    sr_error *err;
    sr_array positions, colors, uvs, normals; /* dvec3, vec3, vec2, vec3 as read */
    sr_array corners;                         /* corner per mesh vertex */
    sr_array indices;                         /* uint32_t, three per triangle */
    sr_array file_faces;                      /* uint32_t per triangle, its f line's index; kept from the
                                                 first polygon on (before it, triangle i is face i) */
    uint32_t faces;                           /* f lines so far */
    uint32_t *map;                            /* open addressing: corner id + 1, 0 = free */
    size_t map_cap;                           /* a power of two, kept at least half free */
    bool any_uv, any_normal;
    sr_mtl_libs materials;
    bool has_mtllib;
    ptrdiff_t material;  /* selected by usemtl, or -1 */
    const char *texture; /* first map_Kd used by a face; owned by materials */
    sr_load_report *report; /* NULL: nobody asked */
    ptrdiff_t run_material; /* the material of the report's last part */
    /* The mesh's parts: runs of faces of one `o`/`g` group and one
     * material; and its materials, each library material that a face
     * uses once, in order of first use, and the default one (a face
     * without a material, or of a name no library has). */
    sr_array parts;         /* sr_mesh_part */
    sr_array used;          /* ptrdiff_t: the library material of each mesh material, -1 the default */
    uint32_t group;         /* `o` and `g` statements so far */
    uint32_t part_group;    /* the last part's */
    int64_t default_material; /* the default's mesh material, or -1 */
    bool any_material;      /* some face uses a library's material */
} obj_reader;

static bool out_of_memory(const obj_reader *o)
{
    return sr_line_fail(&o->in, o->err, "out of memory");
}

/* ---- attribute lines ---- */

static void *push_attribute(obj_reader *o, sr_array *g, size_t size, const char *what)
{
    if (g->count >= MAX_ITEMS) {
        sr_line_fail(&o->in, o->err, "more than %u %s", MAX_ITEMS, what);
        return NULL;
    }
    void *at = sr_array_push(g, size);
    if (!at)
        out_of_memory(o);
    return at;
}

/* Keeps colors in step with positions once any vertex has a color; the
 * vertices before the first colored one, and any without a color, are white. */
static bool push_color(obj_reader *o, const float *rgb)
{
    if (!rgb && o->colors.count == 0)
        return true;
    size_t missing = o->positions.count - o->colors.count;
    vec3 *c = sr_array_grow(&o->colors, missing, sizeof(vec3));
    if (!c)
        return out_of_memory(o);
    for (size_t i = 0; i < missing; i++)
        glm_vec3_one(c[i]);
    if (rgb)
        glm_vec3_copy((float *)rgb, c[missing - 1]);
    return true;
}

/* The line's numbers, narrowed to float. */
static int parse_floats(obj_reader *o, char *cursor, float *out, int max)
{
    double d[6];
    int n = sr_obj_parse_numbers(&o->in, cursor, d, max, o->err);
    for (int i = 0; i < n; i++)
        out[i] = (float)d[i];
    return n;
}

static bool parse_vertex(obj_reader *o, char *cursor)
{
    double d[6];
    int n = sr_obj_parse_numbers(&o->in, cursor, d, 6, o->err);
    if (n < 0)
        return false;
    if (n != 3 && n != 4 && n != 6)
        return sr_line_fail(&o->in, o->err,
                            "'v' needs x y z, x y z w or x y z r g b, got %d numbers", n);
    dvec3 *p = push_attribute(o, &o->positions, sizeof *p, "vertices");
    if (!p)
        return false;
    memcpy(*p, d, sizeof *p); /* a w (n == 4) only matters for rational curves */
    vec3 rgb = { (float)d[3], (float)d[4], (float)d[5] };
    return push_color(o, n == 6 ? rgb : NULL);
}

/* A 'vt' or 'vn' line: at least `least` numbers (at most 3), the first
 * size / sizeof(float) of them, as floats, pushed onto g. */
static bool parse_float_attribute(obj_reader *o, char *cursor, sr_array *g, size_t size, int least,
                                  const char *needs, const char *what)
{
    float f[3];
    int n = parse_floats(o, cursor, f, 3);
    if (n < 0)
        return false;
    if (n < least)
        return sr_line_fail(&o->in, o->err, "%s, got %d numbers", needs, n);
    void *at = push_attribute(o, g, size, what);
    if (!at)
        return false;
    memcpy(at, f, size);
    return true;
}

/* ---- corners: parse, resolve, intern ---- */

/* One index of a face corner: its value (clamped to long's range, still out
 * of any range) and its text as written, for messages. */
typedef struct face_index {
    long value;
    const char *text;
    int length;
} face_index;

static bool parse_index(const char **s, face_index *idx)
{
    idx->text = *s;
    if (!sr_obj_parse_long(s, &idx->value))
        return false;
    idx->length = (int)(*s - idx->text);
    return true;
}

/* "v", "v/vt", "v//vn" or "v/vt/vn"; has[1], has[2] say which were given. */
static bool split_corner(const char *s, face_index idx[3], bool has[3])
{
    if (!parse_index(&s, &idx[0]))
        return false;
    if (*s == '\0')
        return true;
    if (*s++ != '/')
        return false;
    if (*s != '/') {
        if (!parse_index(&s, &idx[1]))
            return false;
        has[1] = true;
        if (*s == '\0')
            return true;
        if (*s != '/')
            return false;
    }
    s++;
    if (!parse_index(&s, &idx[2]))
        return false;
    has[2] = true;
    return *s == '\0';
}

/* OBJ counts from 1; a negative index counts back from the last element read
 * so far (-1 is the latest). Written so that no value of idx can overflow. */
static bool resolve_index(obj_reader *o, face_index idx, size_t count, const char *what,
                          uint32_t *out)
{
    if (idx.value == 0)
        return sr_line_fail(&o->in, o->err, "%s index 0 is invalid (OBJ counts from 1)", what);
    unsigned long magnitude = idx.value > 0 ? (unsigned long)idx.value : (unsigned long)-(idx.value + 1) + 1;
    if (magnitude > count)
        return sr_line_fail(&o->in, o->err, "%s index %.*s is out of range (%zu defined so far)",
                            what, idx.length, idx.text, count);
    *out = (uint32_t)(idx.value > 0 ? magnitude - 1 : count - magnitude);
    return true;
}

static uint32_t hash_corner(corner c)
{
    uint32_t h = c.v * 0x9E3779B1u ^ c.vt * 0x85EBCA77u ^ c.vn * 0xC2B2AE3Du;
    h ^= h >> 16; /* murmur3's finaliser: spreads the low bits the mask keeps */
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
    return h;
}

static bool same_corner(corner a, corner b)
{
    return a.v == b.v && a.vt == b.vt && a.vn == b.vn;
}

/* The slot holding c, or the free slot where it belongs. */
static size_t find_slot(const obj_reader *o, corner c)
{
    const corner *known = o->corners.data;
    size_t mask = o->map_cap - 1;
    size_t i = hash_corner(c) & mask;
    while (o->map[i] != 0 && !same_corner(known[o->map[i] - 1], c))
        i = (i + 1) & mask;
    return i;
}

static bool grow_map(obj_reader *o)
{
    size_t cap = o->map_cap ? 2 * o->map_cap : MAP_MIN_CAP;
    uint32_t *map = calloc(cap, sizeof *map);
    if (!map)
        return out_of_memory(o);
    free(o->map);
    o->map = map;
    o->map_cap = cap;
    const corner *known = o->corners.data;
    for (size_t id = 0; id < o->corners.count; id++)
        o->map[find_slot(o, known[id])] = (uint32_t)id + 1;
    return true;
}

/* The mesh vertex for c, made on first sight. */
static bool intern_corner(obj_reader *o, corner c, uint32_t *id)
{
    if (2 * (o->corners.count + 1) > o->map_cap && !grow_map(o))
        return false;
    size_t slot = find_slot(o, c);
    if (o->map[slot] != 0) {
        *id = o->map[slot] - 1;
        return true;
    }
    corner *fresh = push_attribute(o, &o->corners, sizeof *fresh, "distinct face vertices");
    if (!fresh)
        return false;
    *fresh = c;
    *id = (uint32_t)(o->corners.count - 1);
    o->map[slot] = *id + 1;
    return true;
}

static bool parse_face_corner(obj_reader *o, const char *tok, uint32_t *id)
{
    face_index idx[3] = { { 0 } };
    bool has[3] = { true, false, false };
    if (!split_corner(tok, idx, has))
        return sr_line_fail(&o->in, o->err,
                            "malformed face vertex '%.40s' (expected v, v/vt, v//vn or v/vt/vn)",
                            tok);
    corner c = { NONE, NONE, NONE };
    if (!resolve_index(o, idx[0], o->positions.count, "vertex", &c.v))
        return false;
    if (has[1] && !resolve_index(o, idx[1], o->uvs.count, "texture coordinate", &c.vt))
        return false;
    if (has[2] && !resolve_index(o, idx[2], o->normals.count, "normal", &c.vn))
        return false;
    o->any_uv |= has[1];
    o->any_normal |= has[2];
    return intern_corner(o, c, id);
}

/* ---- faces ---- */

static bool emit_triangle(obj_reader *o, uint32_t a, uint32_t b, uint32_t c)
{
    if (o->indices.count > UINT32_MAX - 3)
        return sr_line_fail(&o->in, o->err, "more than %u triangles", UINT32_MAX / 3);
    uint32_t *t = sr_array_grow(&o->indices, 3, sizeof *t);
    if (!t)
        return out_of_memory(o);
    t[0] = a;
    t[1] = b;
    t[2] = c;
    return true;
}

/* The library material usemtl selected, NULL for none. */
static sr_mtl_material *selected_material(obj_reader *o)
{
    return o->material >= 0 ? (sr_mtl_material *)o->materials.materials.data + o->material : NULL;
}

/* The material faces use now, its texture looked for; NULL for none. */
static const sr_mtl_material *current_material(obj_reader *o)
{
    sr_mtl_material *m = selected_material(o);
    if (m)
        sr_mtl_find_texture(m);
    return m;
}

/* The report's parts are the runs of faces drawn with one material (an
 * OBJ has no meshes of its own); each material's texture is listed once. */
static bool report_face(obj_reader *o, size_t first_index)
{
    sr_load_report *r = o->report;
    uint32_t first = (uint32_t)(first_index / 3), added = (uint32_t)((o->indices.count - first_index) / 3);
    if (!r || added == 0)
        return true;
    if (r->part_count > 0 && o->run_material == o->material && r->parts_unlisted == 0) {
        r->parts[r->part_count - 1].triangle_count += added;
        return true;
    }
    const sr_mtl_material *m = current_material(o);
    int32_t texture = -1;
    if (m && m->map_kd)
        texture = sr_report_add_texture(r, m->map_kd_written, m->map_kd_found ? m->map_kd : NULL,
                                    m->map_kd_found ? SR_TEXTURE_FOUND : SR_TEXTURE_MISSING);
    o->run_material = o->material;
    return sr_report_add_part(r, first, added, m ? m->name : "", texture) || out_of_memory(o);
}

/* The mesh material of the current library material (-1: the default),
 * made on first use; -1 when out of memory. */
static int64_t mesh_material(obj_reader *o)
{
    sr_mtl_material *m = selected_material(o);
    int64_t *index = m ? &m->mesh_material : &o->default_material;
    if (*index >= 0)
        return *index;
    ptrdiff_t *slot = sr_array_push(&o->used, sizeof *slot);
    if (!slot)
        return -1;
    *slot = o->material;
    *index = (int64_t)o->used.count - 1;
    o->any_material |= m != NULL;
    return *index;
}

/* The face's triangles (from first_index on) join the last part, or begin
 * a part when the group or the material changed. */
static bool add_to_part(obj_reader *o, size_t first_index)
{
    uint32_t first = (uint32_t)(first_index / 3), added = (uint32_t)((o->indices.count - first_index) / 3);
    int64_t material = mesh_material(o);
    if (material < 0)
        return out_of_memory(o);
    sr_mesh_part *last = o->parts.count ? (sr_mesh_part *)o->parts.data + o->parts.count - 1 : NULL;
    if (last && last->material == (uint32_t)material && o->part_group == o->group) {
        last->triangle_count += added;
        return true;
    }
    sr_mesh_part *p = sr_array_push(&o->parts, sizeof *p);
    if (!p)
        return out_of_memory(o);
    *p = (sr_mesh_part){ first, added, (uint32_t)material };
    o->part_group = o->group;
    return true;
}

/* The face's triangles (from first_index on) in the face map: a polygon
 * is fanned into several, and from the first one on, each triangle names
 * its face (the triangles before it are the faces before it). */
static bool map_face(obj_reader *o, size_t first_index)
{
    size_t before = first_index / 3, added = (o->indices.count - first_index) / 3;
    if (o->file_faces.count == 0 && added == 1)
        return true;
    size_t from = o->file_faces.count == 0 ? 0 : before;
    uint32_t *map = sr_array_grow(&o->file_faces, before + added - from, sizeof *map);
    if (!map)
        return out_of_memory(o);
    for (size_t i = from; i < before; i++)
        map[i - from] = (uint32_t)i;
    for (size_t i = 0; i < added; i++)
        map[before - from + i] = o->faces;
    return true;
}

/* Streams the fan: on reading corner k >= 2 the fan triangle (c0, c(k-1), ck)
 * is complete, and it is written reversed as (c0, ck, c(k-1)). */
static bool parse_face(obj_reader *o, char *cursor)
{
    uint32_t first = 0, prev = 0;
    size_t n = 0, first_index = o->indices.count;
    for (char *tok; (tok = sr_obj_next_token(&cursor)); n++) {
        uint32_t id = 0; /* set by parse_face_corner; -O2 cannot see it */
        if (!parse_face_corner(o, tok, &id))
            return false;
        if (n == 0)
            first = id;
        else if (n >= 2 && !emit_triangle(o, first, id, prev))
            return false;
        prev = id;
    }
    if (n < 3)
        return sr_line_fail(&o->in, o->err, "a face needs at least 3 vertices, got %zu", n);
    if (!o->texture && o->material >= 0)
        o->texture = current_material(o)->map_kd;
    if (!map_face(o, first_index))
        return false;
    o->faces++;
    return add_to_part(o, first_index) && report_face(o, first_index);
}

/* ---- materials ---- */

static bool parse_mtllib(obj_reader *o, char *cursor)
{
    o->has_mtllib = true;
    return sr_mtl_load(&o->materials, &o->in, sr_obj_rest(cursor), o->err);
}

/* Without any mtllib, usemtl only names a group; with one, a name missing
 * from every library draws its faces with the default material (no
 * texture), as other viewers do, and is one warning in the report. */
static bool parse_usemtl(obj_reader *o, char *cursor)
{
    const char *name = sr_obj_rest(cursor);
    if (!o->has_mtllib)
        return true;
    o->material = sr_mtl_find(&o->materials, name);
    if (o->material < 0 && o->report)
        sr_report_warn(o->report, "%s:%zu: material '%.80s' is not in any material library; its faces are drawn "
                                  "with the default material", o->in.path, o->in.line, name);
    return true;
}

/* ---- the file ---- */

static bool parse_statement(obj_reader *o, char *line)
{
    char *cursor = line;
    const char *keyword = sr_obj_next_token(&cursor);
    if (!keyword)
        return true; /* blank line or comment */
    if (strcmp(keyword, "v") == 0)
        return parse_vertex(o, cursor);
    if (strcmp(keyword, "vt") == 0)
        return parse_float_attribute(o, cursor, &o->uvs, sizeof(vec2), 2, "'vt' needs u v or u v w",
                                     "texture coordinates");
    if (strcmp(keyword, "vn") == 0)
        return parse_float_attribute(o, cursor, &o->normals, sizeof(vec3), 3, "'vn' needs x y z", "normals");
    if (strcmp(keyword, "f") == 0)
        return parse_face(o, cursor);
    if (strcmp(keyword, "mtllib") == 0)
        return parse_mtllib(o, cursor);
    if (strcmp(keyword, "usemtl") == 0)
        return parse_usemtl(o, cursor);
    if (strcmp(keyword, "o") == 0 || strcmp(keyword, "g") == 0) {
        o->group++;
        return true;
    }
    if (o->report && strcmp(keyword, "l") == 0)
        o->report->lines++;
    if (o->report && strcmp(keyword, "p") == 0)
        o->report->points++;
    return true; /* s, l, p, vp, curves, …: nothing softrast draws */
}

static bool read_statements(obj_reader *o)
{
    for (;;) {
        char *line;
        if (!sr_line_reader_next(&o->in, &line, o->err))
            return false;
        if (!line)
            return true;
        if (!parse_statement(o, line))
            return false;
    }
}

/* Vertex i's position in the left-handed world (z flipped), in double. */
static void world_position(const obj_reader *o, uint32_t i, double out[3])
{
    corner c = ((const corner *)o->corners.data)[i];
    const dvec3 *p = o->positions.data;
    out[0] = p[c.v][0];
    out[1] = p[c.v][1];
    out[2] = -p[c.v][2];
}

/* The mesh's origin by the rule of mesh.h, from the bounds of the vertices
 * the faces use. */
static void choose_origin(const obj_reader *o, sr_mesh *mesh)
{
    uint32_t count = (uint32_t)o->corners.count;
    double lo[3], hi[3], p[3];
    if (count == 0)
        return;
    world_position(o, 0, lo);
    world_position(o, 0, hi);
    for (uint32_t i = 1; i < count; i++) {
        world_position(o, i, p);
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], p[k]);
            hi[k] = fmax(hi[k], p[k]);
        }
    }
    sr_mesh_origin_for_bounds(lo, hi, mesh->origin);
}

/* Writes vertex i from its corner: its position relative to the mesh's
 * origin, rounded to float once. A corner without vt or vn gets (0, 0) or
 * (0, 0, 0) when others have them. */
static void write_vertex(const obj_reader *o, sr_mesh *mesh, uint32_t i)
{
    corner c = ((const corner *)o->corners.data)[i];
    double p[3];
    world_position(o, i, p);
    for (int k = 0; k < 3; k++)
        mesh->positions[i][k] = (float)(p[k] - mesh->origin[k]);
    if (mesh->colors)
        glm_vec3_copy(((vec3 *)o->colors.data)[c.v], mesh->colors[i]);
    if (mesh->uvs && c.vt != NONE)
        glm_vec2_copy(((vec2 *)o->uvs.data)[c.vt], mesh->uvs[i]);
    if (mesh->normals && c.vn != NONE) {
        glm_vec3_copy(((vec3 *)o->normals.data)[c.vn], mesh->normals[i]);
        mesh->normals[i][2] = -mesh->normals[i][2];
    }
}

/* A used library material as the draw takes it: its texture (found as
 * map_Kd's rules say, else named as written, for the warning) over white,
 * as it drew before materials, or else its Kd; the default material is
 * SR_LAMBERT_GRAY's gray, white over vertex colours (which it then shows
 * as they are). */
static bool make_material(const obj_reader *o, ptrdiff_t library, bool colors, sr_material *out)
{
    const sr_mtl_material *m = library >= 0 ? (const sr_mtl_material *)o->materials.materials.data + library : NULL;
    float gray = colors ? 1.0f : 0.8f;
    *out = (sr_material){ .base_color = { gray, gray, gray, 1.0f } };
    if (m && m->map_kd) {
        out->base_color[0] = out->base_color[1] = out->base_color[2] = 1.0f;
        return (out->texture_path = strdup(m->map_kd)) != NULL;
    }
    if (m && m->has_kd)
        for (int k = 0; k < 3; k++)
            out->base_color[k] = m->kd[k];
    return true;
}

/* Parts and materials, when there is more than one part or a face uses a
 * library's material: a file of plain faces keeps a mesh of one part and
 * no materials, drawn as always. */
static bool build_parts(obj_reader *o, sr_mesh *mesh)
{
    if (o->parts.count < 2 && !o->any_material)
        return true;
    mesh->part_count = (uint32_t)o->parts.count;
    mesh->parts = o->parts.data;
    o->parts = (sr_array){ 0 };
    if (!o->any_material)
        return true;
    mesh->materials = calloc(o->used.count, sizeof *mesh->materials);
    if (!mesh->materials)
        return false;
    mesh->material_count = (uint32_t)o->used.count;
    const ptrdiff_t *used = o->used.data;
    for (size_t i = 0; i < o->used.count; i++)
        if (!make_material(o, used[i], mesh->colors != NULL, &mesh->materials[i]))
            return false;
    return true;
}

/* A file without faces: every vertex a mesh vertex of its own, in file
 * order, as the faces would have named them; vn i its normal when there
 * are as many as vertices (a cloud's exporter writes them in pairs, and
 * no face corner is there to pair them). */
static bool corners_of_cloud(obj_reader *o)
{
    size_t count = o->positions.count;
    corner *c = count ? sr_array_grow(&o->corners, count, sizeof *c) : NULL;
    if (count && !c)
        return sr_error_set(o->err, "%s: out of memory", o->in.path);
    bool normals = o->normals.count == count;
    for (size_t i = 0; i < count; i++)
        c[i] = (corner){ (uint32_t)i, NONE, normals ? (uint32_t)i : NONE };
    o->any_normal = normals && count > 0;
    return true;
}

static bool build_mesh(obj_reader *o, sr_mesh *mesh)
{
    uint32_t count = (uint32_t)o->corners.count;
    if (!sr_mesh_alloc(mesh, count, 0, o->any_normal, o->any_uv, o->colors.count > 0, o->err))
        return false;
    choose_origin(o, mesh);
    for (uint32_t i = 0; i < count; i++)
        write_vertex(o, mesh, i); /* sr_mesh_alloc zeroed what a corner lacks */
    if ((o->texture && !(mesh->texture_path = strdup(o->texture))) || !build_parts(o, mesh)) {
        sr_mesh_free(mesh);
        return sr_error_set(o->err, "%s: out of memory", o->in.path);
    }
    /* Hand the index array and face map over rather than copy them:
     * sr_mesh_free frees them. */
    mesh->file_faces = o->file_faces.data;
    o->file_faces = (sr_array){ 0 };
    mesh->indices = o->indices.data;
    mesh->index_count = (uint32_t)o->indices.count;
    mesh->topology = SR_TRIANGLE_LIST;
    o->indices = (sr_array){ 0 };
    return true;
}

static void obj_reader_free(obj_reader *o)
{
    sr_line_reader_close(&o->in);
    sr_array_free(&o->positions);
    sr_array_free(&o->colors);
    sr_array_free(&o->uvs);
    sr_array_free(&o->normals);
    sr_array_free(&o->corners);
    sr_array_free(&o->indices);
    sr_array_free(&o->file_faces);
    sr_array_free(&o->parts);
    sr_array_free(&o->used);
    free(o->map);
    sr_mtl_free(&o->materials);
}

bool sr_obj_load_report(sr_mesh *mesh, const char *path, sr_load_report *report, sr_error *err)
{
    *mesh = (sr_mesh){ 0 };
    obj_reader o = { .err = err, .material = -1, .report = report, .run_material = -2, .default_material = -1 };
    if (report)
        sr_report_obj_format(report);
    if (!sr_line_reader_open(&o.in, path))
        return sr_error_set(err, "%s: cannot open: %s", path, o.in.why);
    bool ok = read_statements(&o) && (o.faces > 0 || corners_of_cloud(&o)) && build_mesh(&o, mesh);
    obj_reader_free(&o);
    if (ok) {
        sr_mesh_update_bounds(mesh);
        mesh->z_negated = true;
    }
    return ok;
}

bool sr_obj_load(sr_mesh *mesh, const char *path, sr_error *err)
{
    return sr_obj_load_report(mesh, path, NULL, err);
}
