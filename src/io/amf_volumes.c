/* An AMF file's objects of several volumes, rewritten one object per
 * volume (amf_volumes.h). Elements outside those objects are written back
 * as they were read: comments, processing instructions and the document
 * type are left out, which Assimp reads nothing of. */
#include <ctype.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "amf_volumes.h"
#include "amf_xml.h"
#include "core/error.h"

/* Elements deeper than an object's mesh's volume's triangle's corner (6)
 * go where their parent's went: one sink per depth up to here. */
#define SINK_DEPTH 8
/* Bytes the rewrite may hold, over 8 times the file's. */
#define SLACK_BYTES ((size_t)16 << 20)

/* One volume of the current mesh: where its text ends, which of the used
 * list are its vertices. */
typedef struct volume_mark {
    size_t end;
    size_t used_first, used_count;
    bool has_triangles;
} volume_mark;

typedef struct splitter {
    const sr_amf_file *file;
    const char *path;
    sr_error *err;
    size_t spent, cap; /* bytes written into any buffer, and the most allowed */
    sr_array out;      /* of char: the document */
    size_t depth;
    sr_array *sinks[SINK_DEPTH]; /* where each open element's text goes, NULL left out */
    size_t objects;              /* the root's objects so far */
    size_t next;                 /* the next of file->splits */
    bool splitting;              /* the current object is one to split */
    /* The object being split. */
    sr_array id;          /* of char, NUL-terminated */
    sr_array head;        /* of char: its children but its mesh */
    sr_array pieces;      /* of char: one mesh per volume */
    sr_array piece_ends;  /* of size_t */
    sr_array vertices;    /* of char: its mesh's vertices */
    sr_array vertex_ends; /* of size_t */
    sr_array volumes;     /* of char: its mesh's volumes, corners renumbered */
    sr_array marks;       /* of volume_mark */
    sr_array used;        /* of uint32_t: each volume's vertices by first use */
    uint32_t *renumber;   /* by the mesh's index: the volume's, valid where */
    uint32_t *stamp;      /* stamp is the volume's number */
    uint32_t volume;      /* the object's volumes so far, numbered from 1 */
    char corner[SR_AMF_MAX_NAME];
    size_t corner_len; /* SR_AMF_MAX_NAME once too long */
} splitter;

static bool put(splitter *s, sr_array *to, const char *text, size_t len)
{
    if (!to || len == 0)
        return true;
    char *at = len <= s->cap - s->spent ? sr_array_grow(to, len, 1) : NULL;
    if (!at)
        return sr_error_set(s->err, "%s: out of memory, or splitting its AMF objects' volumes apart would take more "
                            "than %zu MiB", s->path, s->cap >> 20);
    memcpy(at, text, len);
    s->spent += len;
    return true;
}

static bool puts_to(splitter *s, sr_array *to, const char *text)
{
    return put(s, to, text, strlen(text));
}

/* Text or an attribute's value with XML's special characters escaped. */
static bool put_escaped(splitter *s, sr_array *to, const char *text, size_t len)
{
    size_t from = 0;
    for (size_t i = 0; i < len; i++) {
        const char *entity = text[i] == '&' ? "&amp;" : text[i] == '<' ? "&lt;" : text[i] == '>' ? "&gt;"
                                                      : text[i] == '"' ? "&quot;" : NULL;
        if (entity && !(put(s, to, text + from, i - from) && puts_to(s, to, entity)))
            return false;
        from = entity ? i + 1 : from;
    }
    return put(s, to, text + from, len - from);
}

static bool put_start(splitter *s, sr_array *to, const char *name, const char **attributes)
{
    bool ok = puts_to(s, to, "<") && puts_to(s, to, name);
    for (; ok && attributes[0]; attributes += 2)
        ok = puts_to(s, to, " ") && puts_to(s, to, attributes[0]) && puts_to(s, to, "=\"") &&
             put_escaped(s, to, attributes[1], strlen(attributes[1])) && puts_to(s, to, "\"");
    return ok && puts_to(s, to, ">");
}

static bool put_end(splitter *s, sr_array *to, const char *name)
{
    return puts_to(s, to, "</") && puts_to(s, to, name) && puts_to(s, to, ">");
}

static bool push_offset(splitter *s, sr_array *list, size_t value)
{
    size_t *at = sr_array_push(list, sizeof *at);
    if (at)
        *at = value;
    return at || sr_error_set(s->err, "%s: out of memory splitting AMF volumes", s->path);
}

static bool begin_object(splitter *s, const char **attributes)
{
    const sr_amf_split *split = s->file->splits.data;
    s->splitting = s->next < s->file->splits.count && split[s->next].object == s->objects;
    if (!s->splitting)
        return true;
    const uint32_t n = split[s->next].vertices;
    s->id.count = s->head.count = s->pieces.count = s->piece_ends.count = 0;
    s->volume = 0;
    free(s->renumber);
    free(s->stamp);
    s->renumber = malloc((n ? n : 1) * sizeof *s->renumber);
    s->stamp = calloc(n ? n : 1, sizeof *s->stamp);
    const char *id = sr_amf_attribute(attributes, "id");
    return (s->renumber && s->stamp && put(s, &s->id, id, strlen(id) + 1)) ||
           sr_error_set(s->err, "%s: out of memory splitting AMF volumes", s->path);
}

/* Where an element opening in the object being split goes. */
static sr_array *split_sink(splitter *s, sr_amf_kind kind, sr_array *parent)
{
    switch (kind) {
    case SR_AMF_MESH:
        s->vertices.count = s->vertex_ends.count = s->volumes.count = s->marks.count = s->used.count = 0;
        return NULL;
    case SR_AMF_VERTICES:
        return NULL;
    case SR_AMF_VERTEX:
        return &s->vertices;
    case SR_AMF_VOLUME: {
        volume_mark *m = sr_array_push(&s->marks, sizeof *m);
        if (m)
            *m = (volume_mark){ .used_first = s->used.count };
        s->volume++;
        return m ? &s->volumes : NULL; /* out of memory: on_start reports it */
    }
    case SR_AMF_TRIANGLE:
        ((volume_mark *)s->marks.data)[s->marks.count - 1].has_triangles = true;
        return parent;
    case SR_AMF_CORNER:
        s->corner_len = 0;
        return parent;
    default:
        return s->depth == 3 ? &s->head : parent; /* the object's other children */
    }
}

static bool on_start(void *user, sr_amf_kind kind, const char *name, const char **attributes)
{
    splitter *s = user;
    sr_array *parent = s->sinks[s->depth < SINK_DEPTH ? s->depth : SINK_DEPTH - 1];
    s->depth++;
    if (kind == SR_AMF_OBJECT && !begin_object(s, attributes))
        return false;
    sr_array *sink = parent;
    if (kind == SR_AMF_ROOT)
        sink = &s->out;
    else if (kind == SR_AMF_OBJECT && s->splitting)
        sink = NULL;
    else if (s->splitting && s->depth > 2) {
        sink = split_sink(s, kind, parent);
        if (kind == SR_AMF_VOLUME && !sink)
            return sr_error_set(s->err, "%s: out of memory splitting AMF volumes", s->path);
    }
    if (s->depth < SINK_DEPTH)
        s->sinks[s->depth] = sink;
    return put_start(s, sink, name, attributes);
}

static bool on_text(void *user, sr_amf_kind kind, const char *text, size_t len)
{
    splitter *s = user;
    if (s->splitting && kind == SR_AMF_CORNER) {
        const bool fits = s->corner_len + len < SR_AMF_MAX_NAME;
        if (fits)
            memcpy(s->corner + s->corner_len, text, len);
        s->corner_len = fits ? s->corner_len + len : SR_AMF_MAX_NAME;
        return true;
    }
    return put_escaped(s, s->sinks[s->depth < SINK_DEPTH ? s->depth : SINK_DEPTH - 1], text, len);
}

/* A corner's vertex index as the volume's own: the next one the first
 * time the volume names it. */
static bool put_corner(splitter *s, sr_array *sink)
{
    const bool fits = s->corner_len < SR_AMF_MAX_NAME;
    s->corner[fits ? s->corner_len : SR_AMF_MAX_NAME - 1] = '\0';
    const char *digits = s->corner;
    while (isspace((unsigned char)*digits))
        digits++;
    const unsigned long index = fits && isdigit((unsigned char)*digits) ? strtoul(digits, NULL, 10) : ULONG_MAX;
    const sr_amf_split *split = (const sr_amf_split *)s->file->splits.data + s->next;
    if (index >= split->vertices)
        return sr_error_set(s->err, "%s: AMF object \"%.32s\" has a triangle corner \"%.32s\", not one of its %u "
                            "vertices", s->path, (const char *)s->id.data, s->corner, split->vertices);
    volume_mark *m = (volume_mark *)s->marks.data + s->marks.count - 1;
    if (s->stamp[index] != s->volume) {
        uint32_t *at = sr_array_push(&s->used, sizeof *at);
        if (!at)
            return sr_error_set(s->err, "%s: out of memory splitting AMF volumes", s->path);
        *at = (uint32_t)index;
        s->stamp[index] = s->volume;
        s->renumber[index] = (uint32_t)m->used_count++;
    }
    char number[16];
    snprintf(number, sizeof number, "%u", s->renumber[index]);
    return puts_to(s, sink, number);
}

/* The current mesh's volumes of triangles, each a mesh of the vertices it
 * uses, into the pieces. */
static bool end_mesh(splitter *s)
{
    const volume_mark *m = s->marks.data;
    const uint32_t *used = s->used.data;
    const size_t *vertex_end = s->vertex_ends.data;
    const char *vertices = s->vertices.data, *volumes = s->volumes.data;
    for (size_t v = 0; v < s->marks.count; v++) {
        if (!m[v].has_triangles)
            continue;
        bool ok = puts_to(s, &s->pieces, "<mesh><vertices>");
        for (size_t i = m[v].used_first; ok && i < m[v].used_first + m[v].used_count; i++) {
            if (used[i] >= s->vertex_ends.count)
                return sr_error_set(s->err, "%s: AMF object \"%.32s\" has a triangle corner %u, not one of the %zu "
                                    "vertices of its mesh", s->path, (const char *)s->id.data, used[i],
                                    s->vertex_ends.count);
            const size_t from = used[i] ? vertex_end[used[i] - 1] : 0;
            ok = put(s, &s->pieces, vertices + from, vertex_end[used[i]] - from);
        }
        const size_t from = v ? m[v - 1].end : 0;
        if (!(ok && puts_to(s, &s->pieces, "</vertices>") && put(s, &s->pieces, volumes + from, m[v].end - from) &&
              puts_to(s, &s->pieces, "</mesh>") && push_offset(s, &s->piece_ends, s->pieces.count)))
            return false;
    }
    return true;
}

/* The object as one object per piece and a constellation of its id. */
static bool end_object(splitter *s)
{
    const char *id = s->id.data;
    const size_t *piece_end = s->piece_ends.data;
    bool ok = true;
    for (size_t p = 0; ok && p < s->piece_ends.count; p++) {
        char number[32];
        snprintf(number, sizeof number, "#%zu\">", p + 1);
        const size_t from = p ? piece_end[p - 1] : 0;
        ok = puts_to(s, &s->out, "<object id=\"") && put_escaped(s, &s->out, id, strlen(id)) &&
             puts_to(s, &s->out, number) && put(s, &s->out, s->head.data, s->head.count) &&
             put(s, &s->out, (const char *)s->pieces.data + from, piece_end[p] - from) &&
             puts_to(s, &s->out, "</object>\n");
    }
    ok = ok && puts_to(s, &s->out, "<constellation id=\"") && put_escaped(s, &s->out, id, strlen(id)) &&
         puts_to(s, &s->out, "\">");
    for (size_t p = 0; ok && p < s->piece_ends.count; p++) {
        char number[32];
        snprintf(number, sizeof number, "#%zu\"/>", p + 1);
        ok = puts_to(s, &s->out, "<instance objectid=\"") && put_escaped(s, &s->out, id, strlen(id)) &&
             puts_to(s, &s->out, number);
    }
    s->splitting = false;
    s->next++;
    return ok && puts_to(s, &s->out, "</constellation>\n");
}

static bool on_end(void *user, sr_amf_kind kind, const char *name)
{
    splitter *s = user;
    sr_array *sink = s->sinks[s->depth < SINK_DEPTH ? s->depth : SINK_DEPTH - 1];
    s->depth--;
    if (s->splitting && kind == SR_AMF_CORNER && !put_corner(s, sink))
        return false;
    if (!put_end(s, sink, name))
        return false;
    if (s->splitting && kind == SR_AMF_VERTEX)
        return push_offset(s, &s->vertex_ends, s->vertices.count);
    if (s->splitting && kind == SR_AMF_VOLUME)
        ((volume_mark *)s->marks.data)[s->marks.count - 1].end = s->volumes.count;
    if (s->splitting && kind == SR_AMF_MESH)
        return end_mesh(s);
    if (kind == SR_AMF_OBJECT) {
        s->objects++;
        return !s->splitting || end_object(s);
    }
    return true;
}

bool sr_amf_split_volumes(const char *path, const sr_amf_file *file, char **text, size_t *size, sr_error *err)
{
    *text = NULL;
    *size = 0;
    if (file->hash_in_id)
        return sr_error_set(err, "%s: an AMF object or constellation id holds '#', which splitting its objects' "
                            "volumes apart needs for ids of its own", path);
    splitter s = { .file = file, .path = path, .err = err };
    s.cap = file->bytes > (UINT_MAX - SLACK_BYTES) / 8 ? UINT_MAX : 8 * file->bytes + SLACK_BYTES; /* Assimp's limit */
    const sr_amf_walk walk = { &s, on_start, on_text, on_end };
    bool ok = puts_to(&s, &s.out, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n") &&
              sr_amf_xml_walk(path, &walk, NULL, err);
    sr_array *scratch[] = { &s.id, &s.head, &s.pieces, &s.piece_ends, &s.vertices, &s.vertex_ends,
                            &s.volumes, &s.marks, &s.used };
    for (size_t i = 0; i < sizeof scratch / sizeof *scratch; i++)
        sr_array_free(scratch[i]);
    free(s.renumber);
    free(s.stamp);
    if (!ok) {
        sr_array_free(&s.out);
        return false;
    }
    *text = s.out.data;
    *size = s.out.count;
    return true;
}
