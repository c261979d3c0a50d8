/* tests/case_format.c — reads tests/cases/NAME.case (format: tests/cases/README.md). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case_format.h"
#include "softrast_private.h"

#define CASE_LINE_MAX 4096
#define CASE_TOKENS_MAX 64

static const char *const stat_names[CASE_STAT_COUNT] = { "triangles", "rejected", "nonfinite", "clipped",
                                                         "culled",    "drawn",    "fragments" };

const char *case_stat_name(case_stat s)
{
    return (unsigned)s < CASE_STAT_COUNT ? stat_names[s] : "?";
}

const char *case_plane_name(int plane)
{
    return plane >= 0 && plane < SR_CLIP_PLANES ? sr_clip_plane_table[plane].name : "?";
}

void case_root_path(const char *relative, char out[CASE_PATH_MAX])
{
    const char *root = getenv("SOFTRAST_ROOT");
    bool prefix = root && root[0] && relative[0] != '/';
    snprintf(out, CASE_PATH_MAX, "%s%s%s", prefix ? root : "", prefix ? "/" : "", relative);
}

/* ---- small parsers; each returns false on malformed text ---- */

/* strtod accepts nan, inf, -inf, 1e30 and hex floats: exactly what the cases need. */
static bool parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    *out = strtod(s, &end);
    return end != s && *end == '\0';
}

static bool parse_float(const char *s, float *out)
{
    double d;
    if (!parse_double(s, &d))
        return false;
    *out = (float)d; /* 1e39 becomes inf on purpose: cases may want that */
    return true;
}

static bool parse_u32(const char *s, uint32_t *out)
{
    char *end;
    errno = 0;
    unsigned long v = strtoul(s, &end, 10);
    if (end == s || *end != '\0' || errno || v > UINT32_MAX || s[0] == '-')
        return false;
    *out = (uint32_t)v;
    return true;
}

static bool parse_vec3(const char *s, vec3 out)
{
    char buf[CASE_TEXT_MAX], *save = NULL;
    snprintf(buf, sizeof buf, "%.*s", (int)sizeof buf - 1, s);
    char *parts[4];
    int n = 0;
    for (char *t = strtok_r(buf, ",", &save); t && n < 4; t = strtok_r(NULL, ",", &save))
        parts[n++] = t;
    if (n != 3)
        return false;
    for (int k = 0; k < 3; k++)
        if (!parse_float(parts[k], &out[k]))
            return false;
    return true;
}

static int parse_plane(const char *s)
{
    for (int p = 0; p < SR_CLIP_PLANES; p++)
        if (strcmp(s, sr_clip_plane_table[p].name) == 0)
            return p;
    return -1;
}

/* ---- inline vertex data ---- */

/* v X Y Z [rgb R G B] [uv U V] [n X Y Z], or vclip X Y Z W [...] in clip
 * space; absent attributes are white, 0, 0. */
static const char *parse_vertex(case_inline *in, char **tok, int n)
{
    bool clip = strcmp(tok[0], "vclip") == 0;
    int coords = clip ? 4 : 3;
    if (in->vertices.count > 0 && in->clip_space != clip)
        return "a case has either v or vclip lines, not both";
    in->clip_space = clip;
    if (n < 1 + coords)
        return clip ? "vclip needs X Y Z W" : "v needs X Y Z";
    case_vertex *v = sr_array_push(&in->vertices, sizeof *v);
    if (!v)
        return "out of memory";
    float *p = v->pos, *rgb = v->rgb, *uv = v->uv, *nrm = v->nrm;
    rgb[0] = rgb[1] = rgb[2] = 1.0f;
    uv[0] = uv[1] = 0.0f;
    nrm[0] = nrm[1] = nrm[2] = 0.0f;
    p[3] = 1.0f;
    for (int k = 0; k < coords; k++)
        if (!parse_float(tok[1 + k], &p[k]))
            return "bad vertex coordinate";
    for (int i = 1 + coords; i < n;) {
        int size = strcmp(tok[i], "rgb") == 0 ? 3 : strcmp(tok[i], "uv") == 0 ? 2 : strcmp(tok[i], "n") == 0 ? 3 : 0;
        float *dst = size == 0 ? NULL : tok[i][0] == 'r' ? rgb : tok[i][0] == 'u' ? uv : nrm;
        if (!dst || i + size >= n)
            return "expected rgb R G B, uv U V or n X Y Z after the position";
        for (int k = 0; k < size; k++)
            if (!parse_float(tok[i + 1 + k], &dst[k]))
                return "bad vertex attribute";
        in->has_rgb |= dst == rgb;
        in->has_uv |= dst == uv;
        in->has_nrm |= dst == nrm;
        i += 1 + size;
    }
    return NULL;
}

static const char *parse_indices(case_inline *in, char **tok, int n, bool strip)
{
    if (strip ? n < 4 : n != 4)
        return strip ? "strip needs at least 3 indices" : "t needs 3 indices";
    if (in->indices.count && in->strip != strip)
        return "a case has either t lines or one strip, not both";
    if (strip && in->indices.count)
        return "only one strip line per case";
    in->strip = strip;
    for (int k = 1; k < n; k++) {
        uint32_t i;
        if (!parse_u32(tok[k], &i))
            return "bad index";
        uint32_t *slot = sr_array_push(&in->indices, sizeof *slot);
        if (!slot)
            return "out of memory";
        *slot = i;
    }
    return NULL;
}

/* ---- scene lines ---- */

static const char *parse_mesh(case_desc *c, char **tok, int n)
{
    static const struct { const char *name; case_mesh_kind kind; int args; } kinds[] = {
        { "inline", CASE_MESH_INLINE, 0 }, { "obj", CASE_MESH_OBJ, 1 },
        { "torus", CASE_MESH_TORUS, 4 },   { "quads", CASE_MESH_QUADS, 4 } };
    for (size_t k = 0; n >= 2 && k < sizeof kinds / sizeof kinds[0]; k++) {
        if (strcmp(tok[1], kinds[k].name) != 0)
            continue;
        if (n != 2 + kinds[k].args)
            return "wrong number of mesh arguments";
        c->mesh_kind = kinds[k].kind;
        if (c->mesh_kind == CASE_MESH_OBJ)
            snprintf(c->mesh_path, sizeof c->mesh_path, "%.*s", CASE_PATH_MAX - 1, tok[2]);
        for (int i = 0; c->mesh_kind != CASE_MESH_OBJ && i < kinds[k].args; i++)
            if (!parse_double(tok[2 + i], &c->mesh_args[i]))
                return "bad mesh argument";
        return NULL;
    }
    return "mesh inline | obj PATH | torus MAJOR MINOR SEGMENTS SIDES | quads COUNT SIZE FIRST_Z STEP";
}

static const char *parse_camera(case_desc *c, char **tok, int n)
{
    sr_camera *cam = &c->camera;
    *cam = sr_camera_default();
    c->has_camera = true;
    for (int i = 1; i < n; i++) {
        const char *key = tok[i], *val = i + 1 < n ? tok[i + 1] : NULL;
        bool ok = true;
        if (strcmp(key, "reversed") == 0) {
            cam->reversed_z = true;
            continue;
        }
        if (!val)
            return "camera option without a value";
        if (strcmp(key, "eye") == 0) ok = parse_vec3(val, cam->eye);
        else if (strcmp(key, "target") == 0) ok = parse_vec3(val, cam->target);
        else if (strcmp(key, "up") == 0) ok = parse_vec3(val, cam->up);
        else if (strcmp(key, "fov") == 0) ok = parse_float(val, &cam->fov_deg);
        else if (strcmp(key, "near") == 0) ok = parse_float(val, &cam->near);
        else if (strcmp(key, "far") == 0) ok = parse_float(val, &cam->far);
        else if (strcmp(key, "ortho") == 0) ok = parse_float(val, &cam->ortho_height);
        else return "unknown camera option";
        if (!ok)
            return "bad camera value";
        i++;
    }
    return NULL;
}

static const char *parse_matrix(case_desc *c, char **tok, int n)
{
    static const char *const names[CASE_MATRICES] = { "world", "view", "projection" };
    int which = -1;
    for (int k = 0; n >= 2 && k < CASE_MATRICES; k++)
        if (strcmp(tok[1], names[k]) == 0)
            which = k;
    if (which < 0)
        return "matrix world|view|projection identity|16 numbers";
    float *m = c->matrix[which][0];
    if (n == 3 && strcmp(tok[2], "identity") == 0) {
        glm_mat4_identity(c->matrix[which]);
    } else if (n == 18) {
        for (int k = 0; k < 16; k++) /* column-major, as cglm stores it */
            if (!parse_float(tok[2 + k], &m[k]))
                return "bad matrix element";
    } else {
        return "a matrix is `identity` or 16 numbers, column-major";
    }
    c->matrix_set[which] = true;
    return NULL;
}

static const char *parse_draw(case_desc *c, char **tok, int n)
{
    static const char *const shades[] = { "lambert", "id", "color", "normal", "texture", "depth" };
    static const char *const culls[] = { "back", "front", "none" };
    for (int i = 1; i + 1 < n; i += 2) {
        const char *key = tok[i], *val = tok[i + 1];
        int found = -1;
        if (strcmp(key, "shade") == 0) {
            for (int k = 0; k < SR_SHADE_COUNT; k++)
                found = strcmp(val, shades[k]) == 0 ? k : found;
            if (found < 0 || found == SR_SHADE_TEXTURE)
                return "shade id|depth|color|normal|lambert";
            c->shade = (sr_shade)found;
        } else if (strcmp(key, "cull") == 0) {
            for (int k = 0; k < 3; k++)
                found = strcmp(val, culls[k]) == 0 ? k : found;
            if (found < 0)
                return "cull back|front|none";
            c->cull = (sr_cull)found;
        } else if (strcmp(key, "front") == 0) {
            if (strcmp(val, "cw") != 0 && strcmp(val, "ccw") != 0)
                return "front cw|ccw";
            c->front = strcmp(val, "cw") == 0 ? SR_FRONT_CW : SR_FRONT_CCW;
        } else if (strcmp(key, "depth") == 0) {
            if (strcmp(val, "standard") != 0 && strcmp(val, "reversed") != 0)
                return "depth standard|reversed";
            c->reversed_z = strcmp(val, "reversed") == 0;
        } else {
            return "draw [shade MODE] [cull MODE] [front cw|ccw] [depth standard|reversed]";
        }
    }
    return n % 2 == 1 ? NULL : "draw options come in pairs";
}

static const char *parse_stats(case_expect *e, char **tok, int n)
{
    for (int i = 2; i < n; i++) {
        if (e->stat_count == CASE_MAX_STATS)
            return "too many stats on one line";
        case_stat_check *s = &e->stats[e->stat_count++];
        char *op = strpbrk(tok[i], "<>=");
        if (!op)
            return "stats NAME=V, NAME<=V or NAME>=V";
        s->op = op[0] == '<' ? CASE_OP_LE : op[0] == '>' ? CASE_OP_GE : CASE_OP_EQ;
        const char *value = op + (op[0] == '=' ? 1 : 2);
        if (op[0] != '=' && op[1] != '=')
            return "stats comparisons are =, <= and >=";
        *op = '\0';
        int found = -1;
        for (int k = 0; k < CASE_STAT_COUNT; k++)
            found = strcmp(tok[i], stat_names[k]) == 0 ? k : found;
        uint32_t v;
        if (found < 0 || !parse_u32(value, &v))
            return "unknown stat or bad value";
        s->stat = (case_stat)found;
        s->value = v;
    }
    return e->stat_count ? NULL : "expect stats needs at least one comparison";
}

static const char *parse_planes(case_expect *e, char **tok, int n)
{
    for (int i = 2; i < n; i++) {
        int p = parse_plane(tok[i]);
        if (strcmp(tok[i], "all") == 0)
            e->planes |= SR_OUT_PLANES;
        else if (p < 0)
            return "planes are near far left right bottom top (or all)";
        else
            e->planes |= 1u << p;
    }
    return e->planes ? NULL : "name at least one plane";
}

static const char *parse_expect(case_desc *c, char **tok, int n, int line, const char *text)
{
    static const struct { const char *name; case_expect_kind kind; int numbers; } kinds[] = {
        { "stats", CASE_EXPECT_STATS, -1 },          { "area", CASE_EXPECT_AREA, 2 },
        { "covered-all", CASE_EXPECT_COVERED_ALL, 0 }, { "hit-at-most-once", CASE_EXPECT_HIT_AT_MOST_ONCE, 0 },
        { "raycast", CASE_EXPECT_RAYCAST, 0 },       { "clip-vertices", CASE_EXPECT_CLIP_VERTICES, 1 },
        { "crosses", CASE_EXPECT_CROSSES, -1 },      { "on-plane", CASE_EXPECT_ON_PLANE, -1 },
        { "depth-at", CASE_EXPECT_DEPTH_AT, 4 },     { "camera-invalid", CASE_EXPECT_CAMERA_INVALID, 0 } };
    if (n >= 3 && strcmp(tok[1], "clip-tolerance") == 0)
        return n == 3 && parse_double(tok[2], &c->clip_tolerance) && c->clip_tolerance >= 0
                   ? NULL : "clip-tolerance needs one relative tolerance";
    if (c->expect_count == CASE_MAX_EXPECT)
        return "too many expect lines";
    case_expect *e = &c->expect[c->expect_count];
    *e = (case_expect){ .line = line };
    snprintf(e->text, sizeof e->text, "%.*s", CASE_TEXT_MAX - 1, text);
    for (size_t k = 0; n >= 2 && k < sizeof kinds / sizeof kinds[0]; k++) {
        if (strcmp(tok[1], kinds[k].name) != 0)
            continue;
        e->kind = kinds[k].kind;
        const char *why = NULL;
        if (e->kind == CASE_EXPECT_STATS)
            why = parse_stats(e, tok, n);
        else if (e->kind == CASE_EXPECT_CROSSES || e->kind == CASE_EXPECT_ON_PLANE)
            why = parse_planes(e, tok, n);
        else if (n != 2 + kinds[k].numbers)
            why = "wrong number of arguments";
        double *nums[4] = { &e->a, &e->b, &e->c, &e->d };
        for (int i = 0; !why && kinds[k].numbers > 0 && i < kinds[k].numbers; i++)
            if (!parse_double(tok[2 + i], nums[i]))
                why = "bad number";
        if (!why)
            c->expect_count++;
        return why;
    }
    return "unknown expectation";
}

/* ---- the file ---- */

static const char *parse_line(case_desc *c, char *line, int number)
{
    char text[CASE_TEXT_MAX], *tok[CASE_TOKENS_MAX], *save = NULL;
    snprintf(text, sizeof text, "%.*s", CASE_TEXT_MAX - 1, line);
    text[strcspn(text, "\r\n")] = '\0';
    int n = 0;
    for (char *t = strtok_r(line, " \t\r\n", &save); t; t = strtok_r(NULL, " \t\r\n", &save)) {
        if (n == CASE_TOKENS_MAX)
            return "too many words on one line";
        tok[n++] = t;
    }
    if (n == 0)
        return NULL;
    if (strcmp(tok[0], "mesh") == 0) return parse_mesh(c, tok, n);
    if (strcmp(tok[0], "v") == 0 || strcmp(tok[0], "vclip") == 0) return parse_vertex(&c->in, tok, n);
    if (strcmp(tok[0], "t") == 0) return parse_indices(&c->in, tok, n, false);
    if (strcmp(tok[0], "strip") == 0) return parse_indices(&c->in, tok, n, true);
    if (strcmp(tok[0], "camera") == 0) return parse_camera(c, tok, n);
    if (strcmp(tok[0], "matrix") == 0) return parse_matrix(c, tok, n);
    if (strcmp(tok[0], "draw") == 0) return parse_draw(c, tok, n);
    if (strcmp(tok[0], "expect") == 0) return parse_expect(c, tok, n, number, text);
    if (strcmp(tok[0], "size") == 0)
        return n == 2 && sscanf(tok[1], "%dx%d", &c->width, &c->height) == 2 && c->width > 0 && c->height > 0
                   ? NULL : "size WxH";
    return "unknown statement";
}

bool case_load(case_desc *c, const char *path, sr_error *err)
{
    *c = (case_desc){ .width = 64, .height = 48, .shade = SR_SHADE_ID, .reversed_z = -1,
                      .clip_tolerance = CASE_CLIP_TOLERANCE };
    snprintf(c->path, sizeof c->path, "%.*s", CASE_PATH_MAX - 1, path);
    FILE *f = fopen(path, "r");
    if (!f)
        return sr_error_set(err, "%s: cannot open: %s", path, strerror(errno));
    char line[CASE_LINE_MAX];
    int number = 0;
    const char *why = NULL;
    while (!why && fgets(line, sizeof line, f)) {
        number++;
        char *hash = strchr(line, '#');
        if (hash && !c->title[0]) {
            char *t = hash + 1 + strspn(hash + 1, " \t");
            snprintf(c->title, sizeof c->title, "%.*s", CASE_TEXT_MAX - 1, t);
            c->title[strcspn(c->title, "\r\n")] = '\0';
        }
        if (hash)
            *hash = '\0';
        why = parse_line(c, line, number);
    }
    fclose(f);
    if (!why && c->mesh_kind != CASE_MESH_INLINE && (c->in.vertices.count || c->in.indices.count))
        why = "v / t / strip lines need `mesh inline`", number = 0;
    if (!why && c->in.clip_space && case_wants(c, CASE_EXPECT_RAYCAST))
        why = "expect raycast casts rays through a camera: not for vclip vertices", number = 0;
    if (why) {
        sr_error_set(err, "%s:%d: %s", path, number, why);
        case_free(c);
        return false;
    }
    return true;
}

void case_free(case_desc *c)
{
    sr_array_free(&c->in.vertices);
    sr_array_free(&c->in.indices);
    c->in = (case_inline){ 0 };
}

static bool make_inline_mesh(const case_inline *in, sr_mesh *mesh, sr_error *err)
{
    uint32_t count = (uint32_t)in->vertices.count;
    const case_vertex *v = in->vertices.data;
    if (!sr_mesh_alloc(mesh, count, (uint32_t)in->indices.count, in->has_nrm, in->has_uv, in->has_rgb, err))
        return false;
    if (in->clip_space && !(mesh->clip_positions = malloc(count * sizeof *mesh->clip_positions)))
        return sr_error_set(err, "out of memory");
    for (uint32_t i = 0; i < count; i++) {
        glm_vec3_copy((float *)v[i].pos, mesh->positions[i]);
        if (in->clip_space)
            glm_vec4_copy((float *)v[i].pos, mesh->clip_positions[i]);
        if (in->has_nrm)
            glm_vec3_copy((float *)v[i].nrm, mesh->normals[i]);
        if (in->has_uv)
            glm_vec2_copy((float *)v[i].uv, mesh->uvs[i]);
        if (in->has_rgb)
            glm_vec3_copy((float *)v[i].rgb, mesh->colors[i]);
    }
    if (in->indices.count)
        memcpy(mesh->indices, in->indices.data, in->indices.count * sizeof(uint32_t));
    mesh->topology = in->strip ? SR_TRIANGLE_STRIP : SR_TRIANGLE_LIST;
    return true;
}

bool case_make_mesh(const case_desc *c, sr_mesh *mesh, sr_error *err)
{
    const double *a = c->mesh_args;
    switch (c->mesh_kind) {
    case CASE_MESH_OBJ: {
        char path[CASE_PATH_MAX];
        case_root_path(c->mesh_path, path);
        return sr_obj_load(mesh, path, err);
    }
    case CASE_MESH_TORUS:
        return sr_shape_torus(mesh, (float)a[0], (float)a[1], (uint32_t)a[2], (uint32_t)a[3], err);
    case CASE_MESH_QUADS:
        return sr_shape_quads(mesh, (uint32_t)a[0], (float)a[1], (float)a[2], (float)a[3], err);
    default:
        return make_inline_mesh(&c->in, mesh, err);
    }
}

void case_make_matrices(const case_desc *c, mat4 world, mat4 view, mat4 projection)
{
    glm_mat4_identity(world);
    glm_mat4_identity(view);
    glm_mat4_identity(projection);
    if (c->has_camera) {
        sr_camera_view(&c->camera, view);
        sr_camera_projection(&c->camera, (float)c->width / (float)c->height, projection);
    }
    vec4 *out[CASE_MATRICES] = { world, view, projection };
    for (int k = 0; k < CASE_MATRICES; k++)
        if (c->matrix_set[k])
            glm_mat4_copy((vec4 *)c->matrix[k], out[k]);
}

bool case_wants(const case_desc *c, case_expect_kind kind)
{
    for (int i = 0; i < c->expect_count; i++)
        if (c->expect[i].kind == kind)
            return true;
    return false;
}
