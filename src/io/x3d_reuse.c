/* An X3D file's reused nodes written out whole (x3d_reuse.h). */
#include <expat.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/array.h"
#include "core/error.h"
#include "core/input_file.h"
#include "x3d_reuse.h"

/* A file larger than this is left to Assimp whole: its rewrite's own
 * bound would pass a gigabyte. */
#define LARGEST_FILE ((size_t)256 << 20)
/* The rewrite's bound: this many times the file, and this much more. */
#define GROWTH 16
#define SLACK ((size_t)64 << 20)

/* Bytes [start, end) of the file: an element from its '<' to past its end tag. */
typedef struct span {
    size_t start, end;
} span;

/* An element that DEFines a name, or one that USEs one. */
typedef struct named {
    char *name;
    span at;
    size_t order; /* of its start in the file: of two DEFs of a name, the later wins */
} named;

/* An open element: where it starts, its start tag's length, and its DEF or
 * USE (an index into defs or uses, or SIZE_MAX). */
typedef struct open_element {
    size_t start, start_length, def, use;
} open_element;

typedef struct reader {
    XML_Parser parser;
    sr_array open; /* open_element */
    sr_array defs, uses; /* named, each in the order its element starts */
    bool failed;   /* out of memory, or an entity declared: left to Assimp */
} reader;

static const char *attribute(const XML_Char **attributes, const char *name)
{
    for (; attributes[0]; attributes += 2)
        if (strcmp(attributes[0], name) == 0)
            return attributes[1];
    return NULL;
}

static void fail(reader *r)
{
    r->failed = true;
    XML_StopParser(r->parser, XML_FALSE);
}

/* A new entry of list named name, starting at start; its index, or SIZE_MAX. */
static size_t add_named(reader *r, sr_array *list, const char *name, size_t start)
{
    named *n = sr_array_push(list, sizeof *n);
    char *copy = strdup(name);
    if (!n || !copy) {
        free(copy);
        if (n)
            list->count--;
        fail(r);
        return SIZE_MAX;
    }
    *n = (named){ .name = copy, .at = { start, start }, .order = start };
    return list->count - 1;
}

static void XMLCALL on_start(void *user, const XML_Char *name, const XML_Char **attributes)
{
    (void)name;
    reader *r = user;
    if (r->failed)
        return;
    size_t start = (size_t)XML_GetCurrentByteIndex(r->parser);
    open_element *e = sr_array_push(&r->open, sizeof *e);
    if (!e) {
        fail(r);
        return;
    }
    *e = (open_element){ .start = start, .start_length = (size_t)XML_GetCurrentByteCount(r->parser),
                         .def = SIZE_MAX, .use = SIZE_MAX };
    const char *def = attribute(attributes, "DEF"), *use = attribute(attributes, "USE");
    if (def && *def)
        e->def = add_named(r, &r->defs, def, start);
    if (use && *use)
        e->use = add_named(r, &r->uses, use, start);
}

static void XMLCALL on_end(void *user, const XML_Char *name)
{
    (void)name;
    reader *r = user;
    if (r->failed)
        return;
    open_element e = ((open_element *)r->open.data)[--r->open.count];
    /* An empty element's end is an event of no bytes: its start tag is all of it. */
    int count = XML_GetCurrentByteCount(r->parser);
    size_t end = count > 0 ? (size_t)XML_GetCurrentByteIndex(r->parser) + (size_t)count : e.start + e.start_length;
    if (e.def != SIZE_MAX)
        ((named *)r->defs.data)[e.def].at.end = end;
    if (e.use != SIZE_MAX)
        ((named *)r->uses.data)[e.use].at.end = end;
}

static void XMLCALL on_entity(void *user, const XML_Char *name, int parameter, const XML_Char *value, int value_len,
                              const XML_Char *base, const XML_Char *system_id, const XML_Char *public_id,
                              const XML_Char *notation)
{
    (void)name, (void)parameter, (void)value, (void)value_len, (void)base, (void)system_id, (void)public_id,
        (void)notation;
    fail(user); /* the byte spans of an entity's text are not the file's */
}

static int by_name_then_order(const void *a, const void *b)
{
    const named *x = a, *y = b;
    int c = strcmp(x->name, y->name);
    return c ? c : (x->order > y->order) - (x->order < y->order);
}

/* The element that DEFines name (the later of two), or NULL. */
static const named *def_of(const sr_array *defs, const char *name)
{
    const named *d = defs->data;
    size_t lo = 0, hi = defs->count; /* the first entry past name's */
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (strcmp(d[mid].name, name) <= 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo > 0 && strcmp(d[lo - 1].name, name) == 0 ? &d[lo - 1] : NULL;
}

typedef struct writer {
    const char *file;
    const sr_array *defs, *uses;
    bool *expanding; /* by def: its text is being written, so a USE of it inside is left as it is */
    sr_array out;    /* char */
    size_t limit;
    bool too_large, out_of_memory;
} writer;

static bool put(writer *w, const char *bytes, size_t n)
{
    if (n > w->limit - w->out.count) {
        w->too_large = true;
        return false;
    }
    char *to = sr_array_grow(&w->out, n, 1);
    if (!to) {
        w->out_of_memory = true;
        return false;
    }
    memcpy(to, bytes, n);
    return true;
}

/* The file's bytes in `at`, each USE element in it written as the element
 * its DEF names, itself written so; a USE inside the element it names, or
 * inside one being written for it, as nothing: a node cannot hold itself,
 * and Assimp 5.2 crashes on one that tries. */
static bool write_span(writer *w, span at)
{
    const named *uses = w->uses->data;
    size_t lo = 0, hi = w->uses->count; /* the first USE starting at or after at.start */
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (uses[mid].at.start < at.start)
            lo = mid + 1;
        else
            hi = mid;
    }
    size_t pos = at.start;
    for (size_t u = lo; u < w->uses->count && uses[u].at.start < at.end; u++) {
        if (uses[u].at.start < pos) /* inside a USE element already replaced */
            continue;
        const named *def = def_of(w->defs, uses[u].name);
        if (!def)
            continue;
        size_t k = (size_t)(def - (const named *)w->defs->data);
        bool inside_itself = def->at.start <= uses[u].at.start && uses[u].at.end <= def->at.end;
        if (!put(w, w->file + pos, uses[u].at.start - pos))
            return false;
        if (!inside_itself && !w->expanding[k]) {
            w->expanding[k] = true;
            bool ok = write_span(w, def->at);
            w->expanding[k] = false;
            if (!ok)
                return false;
        }
        pos = uses[u].at.end;
    }
    return put(w, w->file + pos, at.end - pos);
}

/* Whether any USE names a DEF of the file. */
static bool reuses(const sr_array *defs, const sr_array *uses)
{
    for (size_t u = 0; u < uses->count; u++)
        if (def_of(defs, ((const named *)uses->data)[u].name))
            return true;
    return false;
}

/* The whole file at path into *bytes (malloc'd), or NULL past LARGEST_FILE. */
static bool read_whole(const char *path, char **bytes, size_t *size, sr_error *err)
{
    *bytes = NULL;
    const char *why;
    FILE *f = sr_input_open(path, &why);
    if (!f)
        return sr_error_set(err, "%s: %s", path, why);
    sr_array buf = { 0 };
    bool ok = true;
    for (;;) {
        char *to = buf.count < LARGEST_FILE ? sr_array_grow(&buf, 64 * 1024, 1) : NULL;
        if (!to) {
            ok = buf.count >= LARGEST_FILE || sr_error_set(err, "%s: out of memory reading the X3D", path);
            sr_array_free(&buf);
            break;
        }
        size_t n = fread(to, 1, 64 * 1024, f);
        buf.count -= 64 * 1024 - n;
        if (ferror(f)) {
            ok = sr_error_set(err, "%s: read error", path);
            sr_array_free(&buf);
            break;
        }
        if (n < 64 * 1024)
            break;
    }
    fclose(f);
    *bytes = buf.data;
    *size = buf.count;
    return ok;
}

static void free_names(sr_array *list)
{
    for (size_t i = 0; i < list->count; i++)
        free(((named *)list->data)[i].name);
    sr_array_free(list);
}

bool sr_x3d_write_out_reuses(const char *path, char **text, size_t *size, sr_error *err)
{
    *text = NULL;
    *size = 0;
    char *file;
    size_t file_size;
    if (!read_whole(path, &file, &file_size, err))
        return false;
    if (!file) /* past LARGEST_FILE */
        return true;
    reader r = { .parser = XML_ParserCreate(NULL) };
    bool parsed = false;
    if (r.parser) {
        XML_SetUserData(r.parser, &r);
        XML_SetElementHandler(r.parser, on_start, on_end);
        XML_SetEntityDeclHandler(r.parser, on_entity);
        parsed = XML_Parse(r.parser, file, (int)file_size, XML_TRUE) == XML_STATUS_OK && !r.failed;
        XML_ParserFree(r.parser);
    }
    sr_array_free(&r.open);
    bool ok = true;
    if (parsed) {
        qsort(r.defs.data, r.defs.count, sizeof(named), by_name_then_order);
        if (reuses(&r.defs, &r.uses)) {
            writer w = { .file = file, .defs = &r.defs, .uses = &r.uses,
                         .expanding = calloc(r.defs.count + 1, sizeof(bool)),
                         .limit = file_size <= (SIZE_MAX - SLACK) / GROWTH ? file_size * GROWTH + SLACK : SIZE_MAX };
            ok = w.expanding && write_span(&w, (span){ 0, file_size });
            if (ok) {
                *text = w.out.data;
                *size = w.out.count;
            } else {
                sr_array_free(&w.out);
                ok = w.too_large ? sr_error_set(err, "%s: its reused nodes (USE) written out pass %zu MiB", path,
                                                w.limit >> 20)
                                 : sr_error_set(err, "%s: out of memory writing out the X3D's reused nodes", path);
            }
            free(w.expanding);
        }
    }
    free_names(&r.defs);
    free_names(&r.uses);
    free(file);
    return ok;
}
