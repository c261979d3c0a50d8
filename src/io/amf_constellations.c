/* An AMF file's constellations, read from the file and set on the nodes
 * Assimp made for them (amf_constellations.h). The reader knows as much
 * XML as a constellation needs: elements, attributes in either quote,
 * comments, CDATA and declarations skipped. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "amf_constellations.h"
#include "core/array.h"
#include "core/input_file.h"

/* Names and ids longer than this are kept as "", matching no node. */
#define MAX_NAME 32
/* A file of more constellations or instances than this is left to
 * Assimp's placement. */
#define MAX_INSTANCES (1u << 20)
/* A hostile hierarchy is walked no deeper than this. */
#define MAX_NODE_DEPTH 1024

/* The instance's numbers, in the order of its elements' names. */
static const char *const VALUE_NAMES[6] = { "deltax", "deltay", "deltaz", "rx", "ry", "rz" };

typedef struct amf_instance {
    char objectid[MAX_NAME];
    double value[6]; /* the displacement, then the angles in degrees */
} amf_instance;

typedef struct amf_constellation {
    char id[MAX_NAME];
    size_t first, count; /* its instances in the reader's list */
} amf_constellation;

typedef struct reader {
    FILE *f;
    sr_array constellations; /* of amf_constellation */
    sr_array instances;      /* of amf_instance */
    bool failed;             /* out of memory or past MAX_INSTANCES */
} reader;

/* Reads past the first occurrence of end (at most 3 characters); false at
 * the end of the file. */
static bool skip_past(FILE *f, const char *end)
{
    const size_t n = strlen(end);
    char last[3] = { 0 };
    for (int c; (c = getc(f)) != EOF;) {
        memmove(last, last + 1, n - 1);
        last[n - 1] = (char)c;
        if (memcmp(last, end, n) == 0)
            return true;
    }
    return false;
}

/* Appends c to a name being read, which becomes "" for good once too long. */
static void name_add(char name[MAX_NAME], size_t *len, int c)
{
    if (*len < MAX_NAME - 1) {
        name[(*len)++] = (char)c;
        name[*len] = '\0';
    } else {
        *len = MAX_NAME; /* too long: never grows again */
        name[0] = '\0';
    }
}

/* An element's name; returns the character after it. */
static int read_name(FILE *f, char name[MAX_NAME])
{
    size_t len = 0;
    name[0] = '\0';
    int c;
    while ((c = getc(f)) != EOF && !isspace(c) && c != '>' && c != '/')
        name_add(name, &len, c);
    return c;
}

/* A start tag's attributes, from c (the character after its name) up to
 * its '>': the value of the attribute named want into value ("" when
 * absent); *empty when the tag closes itself. False at the end of the
 * file. */
static bool read_attributes(FILE *f, int c, const char *want, char value[MAX_NAME], bool *empty)
{
    char word[MAX_NAME] = "";
    size_t word_len = 0;
    bool in_word = false;
    int prev = 0;
    value[0] = '\0';
    for (; c != EOF; prev = c, c = getc(f)) {
        if (c == '>') {
            *empty = prev == '/';
            return true;
        }
        if (c == '"' || c == '\'') {
            const int quote = c;
            const bool wanted = strcmp(word, want) == 0;
            size_t len = 0;
            while ((c = getc(f)) != EOF && c != quote)
                if (wanted)
                    name_add(value, &len, c);
            in_word = false;
            continue;
        }
        const bool word_char = !isspace(c) && c != '=' && c != '/';
        if (word_char && !in_word)
            word_len = 0;
        if (word_char)
            name_add(word, &word_len, c);
        in_word = word_char;
    }
    return false;
}

/* The index in VALUE_NAMES of an element's name, -1 when none. */
static int value_index(const char *name)
{
    for (int i = 0; i < 6; i++)
        if (strcmp(name, VALUE_NAMES[i]) == 0)
            return i;
    return -1;
}

static bool push_instance(reader *r, const amf_instance *in)
{
    amf_instance *at = r->instances.count < MAX_INSTANCES ? sr_array_push(&r->instances, sizeof *at) : NULL;
    if (!at)
        return false;
    *at = *in;
    ((amf_constellation *)r->constellations.data)[r->constellations.count - 1].count++;
    return true;
}

/* One tag after its '<': a constellation opens or closes, an instance
 * opens or closes, one of an instance's numbers starts or ends. */
typedef struct parse_state {
    bool in_constellation, in_instance;
    int value;           /* the number being read (VALUE_NAMES), -1 none */
    char text[MAX_NAME]; /* its text so far */
    size_t text_len;
    amf_instance current;
} parse_state;

static bool read_tag(reader *r, parse_state *s)
{
    FILE *f = r->f;
    int c = getc(f);
    if (c == '!') { /* a comment, CDATA (no number of ours) or a declaration */
        int d = getc(f);
        return d == '-' ? skip_past(f, "-->") : d == '[' ? skip_past(f, "]]>") : skip_past(f, ">");
    }
    if (c == '?')
        return skip_past(f, "?>");
    char name[MAX_NAME], attribute[MAX_NAME];
    if (c == '/') { /* an end tag */
        c = read_name(f, name);
        if (s->value >= 0 && strcmp(name, VALUE_NAMES[s->value]) == 0) {
            char *end;
            double v = strtod(s->text, &end);
            if (end != s->text && isfinite(v))
                s->current.value[s->value] = v;
            s->value = -1;
        } else if (s->in_instance && strcmp(name, "instance") == 0) {
            s->in_instance = false;
            r->failed = !push_instance(r, &s->current);
        } else if (strcmp(name, "constellation") == 0) {
            s->in_constellation = false;
        }
        return c == '>' || skip_past(f, ">");
    }
    if (c == EOF)
        return false;
    ungetc(c, f);
    c = read_name(f, name);
    bool empty;
    const bool constellation = strcmp(name, "constellation") == 0;
    const bool instance = s->in_constellation && strcmp(name, "instance") == 0;
    if (!read_attributes(f, c, constellation ? "id" : "objectid", attribute, &empty))
        return false;
    if (constellation && !empty) {
        amf_constellation *con = r->constellations.count < MAX_INSTANCES
                                     ? sr_array_push(&r->constellations, sizeof *con)
                                     : NULL;
        r->failed = !con;
        if (con) {
            *con = (amf_constellation){ .first = r->instances.count };
            memcpy(con->id, attribute, sizeof con->id);
        }
        s->in_constellation = con != NULL;
    } else if (instance) {
        s->current = (amf_instance){ 0 };
        memcpy(s->current.objectid, attribute, sizeof s->current.objectid);
        s->in_instance = !empty;
        if (empty)
            r->failed = !push_instance(r, &s->current);
    } else if (s->in_instance && !empty) {
        s->value = value_index(name);
        s->text_len = 0;
        s->text[0] = '\0';
    }
    return true;
}

static void read_constellations(reader *r)
{
    parse_state s = { .value = -1 };
    for (int c; !r->failed && (c = getc(r->f)) != EOF;) {
        if (c == '<') {
            if (!read_tag(r, &s))
                return;
        } else if (s.value >= 0 && (s.text_len > 0 || !isspace(c))) {
            name_add(s.text, &s.text_len, c);
        }
    }
}

/* sin and cos of an angle in degrees, exact at quarter turns. */
static void sincos_degrees(double degrees, double *s, double *c)
{
    const double quarters = degrees / 90.0;
    if (quarters == floor(quarters) && fabs(quarters) < 1e15) {
        static const double SIN[4] = { 0, 1, 0, -1 }, COS[4] = { 1, 0, -1, 0 };
        int k = (int)fmod(quarters, 4.0);
        k += k < 0 ? 4 : 0;
        *s = SIN[k];
        *c = COS[k];
        return;
    }
    const double radians = degrees * (acos(-1.0) / 180.0);
    *s = sin(radians);
    *c = cos(radians);
}

/* translate(delta) · Rz · Ry · Rx, the instance's transform. */
static void instance_transform(const amf_instance *in, struct aiMatrix4x4 *out)
{
    double sx, cx, sy, cy, sz, cz;
    sincos_degrees(in->value[3], &sx, &cx);
    sincos_degrees(in->value[4], &sy, &cy);
    sincos_degrees(in->value[5], &sz, &cz);
    const double rx[3][3] = { { 1, 0, 0 }, { 0, cx, -sx }, { 0, sx, cx } };
    const double ry[3][3] = { { cy, 0, sy }, { 0, 1, 0 }, { -sy, 0, cy } };
    const double rz[3][3] = { { cz, -sz, 0 }, { sz, cz, 0 }, { 0, 0, 1 } };
    double yx[3][3], m[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            yx[i][j] = ry[i][0] * rx[0][j] + ry[i][1] * rx[1][j] + ry[i][2] * rx[2][j];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            m[i][j] = rz[i][0] * yx[0][j] + rz[i][1] * yx[1][j] + rz[i][2] * yx[2][j];
    *out = (struct aiMatrix4x4){ (ai_real)m[0][0], (ai_real)m[0][1], (ai_real)m[0][2], (ai_real)in->value[0],
                                 (ai_real)m[1][0], (ai_real)m[1][1], (ai_real)m[1][2], (ai_real)in->value[1],
                                 (ai_real)m[2][0], (ai_real)m[2][1], (ai_real)m[2][2], (ai_real)in->value[2],
                                 0, 0, 0, 1 };
}

static int by_id(const void *a, const void *b)
{
    return strcmp(((const amf_constellation *)a)->id, ((const amf_constellation *)b)->id);
}

/* Assimp's node for a constellation: named by its id, one child per
 * instance, each holding one node named by the instance's object id. */
static bool is_placed_by(const reader *r, const struct aiNode *node, const amf_constellation *con)
{
    if (con->count != node->mNumChildren)
        return false;
    const amf_instance *in = (const amf_instance *)r->instances.data + con->first;
    for (size_t i = 0; i < con->count; i++) {
        const struct aiNode *t = node->mChildren[i];
        if (!t || t->mNumChildren != 1 || !t->mChildren[0] || strcmp(t->mChildren[0]->mName.data, in[i].objectid) != 0)
            return false;
    }
    return true;
}

static uint32_t place(const reader *r, struct aiNode *node, unsigned depth)
{
    if (!node || depth > MAX_NODE_DEPTH)
        return 0;
    uint32_t set = 0;
    const amf_constellation *con = NULL;
    if (node->mName.length > 0 && node->mName.length < MAX_NAME) {
        amf_constellation named = { .first = 0 };
        memcpy(named.id, node->mName.data, node->mName.length + 1);
        con = bsearch(&named, r->constellations.data, r->constellations.count, sizeof named, by_id);
    }
    if (con && is_placed_by(r, node, con)) {
        const amf_instance *in = (const amf_instance *)r->instances.data + con->first;
        for (size_t i = 0; i < con->count; i++, set++)
            instance_transform(&in[i], &node->mChildren[i]->mTransformation);
    }
    for (unsigned i = 0; i < node->mNumChildren; i++)
        set += place(r, node->mChildren[i], depth + 1);
    return set;
}

uint32_t sr_amf_place_instances(const struct aiScene *sc, const char *path)
{
    const char *why;
    reader r = { .f = sr_input_open(path, &why) };
    if (!r.f)
        return 0;
    read_constellations(&r);
    fclose(r.f);
    uint32_t set = 0;
    if (!r.failed) {
        amf_constellation *con = r.constellations.data;
        size_t kept = 0; /* those with an id: Assimp's node for one without matches nothing */
        for (size_t i = 0; i < r.constellations.count; i++)
            if (con[i].id[0])
                con[kept++] = con[i];
        r.constellations.count = kept;
        if (kept > 0) {
            qsort(con, kept, sizeof *con, by_id);
            set = place(&r, sc->mRootNode, 0); /* the child's own copy of the scene, ours to change */
        }
    }
    sr_array_free(&r.constellations);
    sr_array_free(&r.instances);
    return set;
}
