/* An AMF file's XML through libexpat, its elements named by what they are
 * in AMF (amf_xml.h). */
#include <expat.h>
#include <stdio.h>
#include <string.h>

#include "amf_xml.h"
#include "core/error.h"
#include "core/input_file.h"

/* Bytes handed to expat at a time. */
#define CHUNK (64 * 1024)
/* The deepest element whose kind can be other than SR_AMF_OTHER is a
 * corner, at depth 6; below depth KNOWN_DEPTH everything is. */
#define KNOWN_DEPTH 8

/* Which element, in which parent, is what. */
static const struct {
    sr_amf_kind parent;
    const char *name;
    sr_amf_kind kind;
} KINDS[] = {
    { SR_AMF_ROOT, "object", SR_AMF_OBJECT },
    { SR_AMF_OBJECT, "mesh", SR_AMF_MESH },
    { SR_AMF_MESH, "vertices", SR_AMF_VERTICES },
    { SR_AMF_VERTICES, "vertex", SR_AMF_VERTEX },
    { SR_AMF_MESH, "volume", SR_AMF_VOLUME },
    { SR_AMF_VOLUME, "triangle", SR_AMF_TRIANGLE },
    { SR_AMF_TRIANGLE, "v1", SR_AMF_CORNER },
    { SR_AMF_TRIANGLE, "v2", SR_AMF_CORNER },
    { SR_AMF_TRIANGLE, "v3", SR_AMF_CORNER },
    { SR_AMF_ROOT, "constellation", SR_AMF_CONSTELLATION },
    { SR_AMF_CONSTELLATION, "instance", SR_AMF_INSTANCE },
    { SR_AMF_INSTANCE, "deltax", SR_AMF_PLACEMENT },
    { SR_AMF_INSTANCE, "deltay", SR_AMF_PLACEMENT },
    { SR_AMF_INSTANCE, "deltaz", SR_AMF_PLACEMENT },
    { SR_AMF_INSTANCE, "rx", SR_AMF_PLACEMENT },
    { SR_AMF_INSTANCE, "ry", SR_AMF_PLACEMENT },
    { SR_AMF_INSTANCE, "rz", SR_AMF_PLACEMENT },
};

typedef struct driver {
    XML_Parser parser;
    const sr_amf_walk *walk;
    size_t depth;                   /* of the innermost open element, 0 outside the root */
    sr_amf_kind kinds[KNOWN_DEPTH]; /* of the open elements, by depth */
    bool stopped;                   /* by a handler or an entity: err is set */
    const char *path;
    sr_error *err;
} driver;

static sr_amf_kind current(const driver *d)
{
    return d->depth < KNOWN_DEPTH ? d->kinds[d->depth] : SR_AMF_OTHER;
}

static sr_amf_kind kind_of(const driver *d, const char *name)
{
    if (d->depth == 0)
        return strcmp(name, "amf") == 0 ? SR_AMF_ROOT : SR_AMF_OTHER;
    const sr_amf_kind parent = current(d);
    for (size_t i = 0; parent != SR_AMF_OTHER && i < sizeof KINDS / sizeof *KINDS; i++)
        if (KINDS[i].parent == parent && strcmp(KINDS[i].name, name) == 0)
            return KINDS[i].kind;
    return SR_AMF_OTHER;
}

static void stop(driver *d)
{
    d->stopped = true;
    XML_StopParser(d->parser, XML_FALSE);
}

static void XMLCALL on_start(void *user, const XML_Char *name, const XML_Char **attributes)
{
    driver *d = user;
    const sr_amf_kind kind = kind_of(d, name);
    if (++d->depth < KNOWN_DEPTH)
        d->kinds[d->depth] = kind;
    if (!d->walk->start(d->walk->user, kind, name, attributes))
        stop(d);
}

static void XMLCALL on_end(void *user, const XML_Char *name)
{
    driver *d = user;
    const sr_amf_kind kind = current(d);
    d->depth--;
    if (!d->walk->end(d->walk->user, kind, name))
        stop(d);
}

static void XMLCALL on_text(void *user, const XML_Char *text, int len)
{
    driver *d = user;
    if (len > 0 && !d->walk->text(d->walk->user, current(d), text, (size_t)len))
        stop(d);
}

static void XMLCALL on_entity(void *user, const XML_Char *name, int parameter, const XML_Char *value, int value_len,
                              const XML_Char *base, const XML_Char *system_id, const XML_Char *public_id,
                              const XML_Char *notation)
{
    (void)parameter, (void)value, (void)value_len, (void)base, (void)system_id, (void)public_id, (void)notation;
    driver *d = user;
    sr_error_set(d->err, "%s:%lu: the AMF declares an entity (%.64s), which softrast does not expand", d->path,
                 (unsigned long)XML_GetCurrentLineNumber(d->parser), name);
    stop(d);
}

/* Feeds the open file to the parser; false with err set. */
static bool feed(driver *d, FILE *f, size_t *bytes)
{
    for (bool first = true;; first = false) {
        char *buf = XML_GetBuffer(d->parser, CHUNK);
        if (!buf)
            return sr_error_set(d->err, "%s: out of memory reading the AMF", d->path);
        const size_t n = fread(buf, 1, CHUNK, f);
        if (ferror(f))
            return sr_error_set(d->err, "%s: read error", d->path);
        if (first && n >= 4 && memcmp(buf, "PK\3\4", 4) == 0)
            return sr_error_set(d->err, "%s: a zipped AMF, which Assimp 5.2 cannot read (unzip it first)", d->path);
        *bytes += n;
        const bool last = n < CHUNK;
        if (XML_ParseBuffer(d->parser, (int)n, last) != XML_STATUS_OK) {
            if (d->stopped)
                return false;
            return sr_error_set(d->err, "%s:%lu: not well-formed AMF XML (%s)", d->path,
                                (unsigned long)XML_GetCurrentLineNumber(d->parser),
                                XML_ErrorString(XML_GetErrorCode(d->parser)));
        }
        if (last)
            return true;
    }
}

const char *sr_amf_attribute(const char **attributes, const char *name)
{
    for (; attributes[0]; attributes += 2)
        if (strcmp(attributes[0], name) == 0)
            return attributes[1];
    return "";
}

bool sr_amf_xml_walk(const char *path, const sr_amf_walk *walk, size_t *bytes, sr_error *err)
{
    const char *why;
    FILE *f = sr_input_open(path, &why);
    if (!f)
        return sr_error_set(err, "%s: %s", path, why);
    driver d = { .parser = XML_ParserCreate(NULL), .walk = walk, .path = path, .err = err };
    size_t read = 0;
    bool ok = d.parser ? true : sr_error_set(err, "%s: out of memory reading the AMF", path);
    if (ok) {
        XML_SetUserData(d.parser, &d);
        XML_SetElementHandler(d.parser, on_start, on_end);
        XML_SetCharacterDataHandler(d.parser, on_text);
        XML_SetEntityDeclHandler(d.parser, on_entity);
        ok = feed(&d, f, &read);
        XML_ParserFree(d.parser);
    }
    fclose(f);
    if (bytes)
        *bytes = read;
    return ok;
}
