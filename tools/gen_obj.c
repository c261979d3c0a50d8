/* tools/gen_obj.c — the OBJ writer of gen-assets.
 *
 * Writes ordinary right-handed Wavefront OBJ as Blender does: per object its
 * new v, vt and vn lines, then its usemtl and f lines, indices counted from
 * the start of the file. Identical lines are written once (see obj_pool), so
 * faces that meet share their corners exactly.
 */
#include "gen_assets.h"

#include <errno.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define NUM_TEXT 32              /* "%.6f" of any coordinate, plus NUL */
#define LINE_TEXT (6 * NUM_TEXT) /* at most six numbers: v x y z r g b */
#define POOL_MIN_CAP 1024        /* power of two */
#define TEXT_MIN_CAP 4096

/* ---- text gathered before writing --------------------------------------- */

static void text_printf(text_buf *b, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

static void text_printf(text_buf *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0)
        gen_fail("cannot format an OBJ line");
    if (b->len + (size_t)n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : TEXT_MIN_CAP;
        while (b->len + (size_t)n + 1 > cap)
            cap *= 2;
        char *data = realloc(b->data, cap);
        if (!data)
            gen_fail("out of memory");
        b->data = data;
        b->cap = cap;
    }
    va_start(ap, fmt);
    vsnprintf(b->data + b->len, (size_t)n + 1, fmt, ap);
    va_end(ap);
    b->len += (size_t)n;
}

static void text_write(obj_writer *w, text_buf *b)
{
    if (b->len && fwrite(b->data, 1, b->len, w->file) != b->len)
        gen_fail("cannot write %s: %s", w->path, strerror(errno));
    b->len = 0;
}

static void text_free(text_buf *b)
{
    free(b->data);
    *b = (text_buf){0};
}

/* Writes what the current object has gathered: v, vt, vn, then faces. */
static void obj_flush(obj_writer *w)
{
    text_write(w, &w->v_text);
    text_write(w, &w->vt_text);
    text_write(w, &w->vn_text);
    text_write(w, &w->body);
}

/* ---- pools of printed lines --------------------------------------------- */

static uint32_t text_hash(const char *s)
{
    uint32_t h = 2166136261u; /* FNV-1a: simple and deterministic */
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * 16777619u;
    return h;
}

static void pool_grow(obj_pool *pool)
{
    size_t cap = pool->cap ? pool->cap * 2 : POOL_MIN_CAP;
    char **keys = calloc(cap, sizeof *keys);
    long *ids = calloc(cap, sizeof *ids);
    if (!keys || !ids)
        gen_fail("out of memory");
    for (size_t i = 0; i < pool->cap; i++) {
        if (!pool->keys[i])
            continue;
        size_t j = text_hash(pool->keys[i]) & (cap - 1);
        while (keys[j])
            j = (j + 1) & (cap - 1);
        keys[j] = pool->keys[i];
        ids[j] = pool->ids[i];
    }
    free(pool->keys);
    free(pool->ids);
    pool->keys = keys;
    pool->ids = ids;
    pool->cap = cap;
}

/* The id of `text`, adding the line "prefix text" to `out` if it is new. */
static long pool_id(obj_pool *pool, text_buf *out, const char *prefix,
                    const char *text)
{
    if (2 * (pool->count + 1) > pool->cap) /* keep the load under one half */
        pool_grow(pool);
    size_t j = text_hash(text) & (pool->cap - 1);
    for (; pool->keys[j]; j = (j + 1) & (pool->cap - 1))
        if (strcmp(pool->keys[j], text) == 0)
            return pool->ids[j];
    pool->keys[j] = strdup(text);
    if (!pool->keys[j])
        gen_fail("out of memory");
    pool->ids[j] = (long)++pool->count;
    text_printf(out, "%s %s\n", prefix, text);
    return pool->ids[j];
}

static void pool_free(obj_pool *pool)
{
    for (size_t i = 0; i < pool->cap; i++)
        free(pool->keys[i]);
    free(pool->keys);
    free(pool->ids);
    *pool = (obj_pool){0};
}

/* "%.6f" without "-0.000000", so a point on a plane prints one way only. */
static void format_number(char *buf, float x)
{
    int n = snprintf(buf, NUM_TEXT, "%.6f", (double)x);
    if (n < 0 || n >= NUM_TEXT)
        gen_fail("coordinate %g is out of range", (double)x);
    if (strcmp(buf, "-0.000000") == 0)
        memmove(buf, buf + 1, strlen(buf));
}

static void format_numbers(char *buf, const float *x, int count)
{
    char num[NUM_TEXT];
    buf[0] = '\0';
    for (int i = 0; i < count; i++) {
        format_number(num, x[i]);
        if (i > 0)
            strcat(buf, " ");
        strcat(buf, num);
    }
}

/* ---- the writer ----------------------------------------------------------- */

void obj_open(obj_writer *w, const char *path, const char *mtllib)
{
    *w = (obj_writer){.path = path};
    w->file = gen_open(path);
    obj_place_identity(w);
    gen_printf(w->file, path,
               "# softrast asset, written by tools/gen_assets.c (make assets); do not edit\n"
               "# right-handed, y up, faces counter-clockwise seen from outside\n");
    if (mtllib)
        gen_printf(w->file, path, "mtllib %s\n", mtllib);
}

void obj_close(obj_writer *w)
{
    obj_flush(w);
    gen_close(w->file, w->path);
    printf("wrote %s: %zu v, %zu vt, %zu vn, %ld triangles\n", w->path,
           w->v.count, w->vt.count, w->vn.count, w->triangles);
    pool_free(&w->v);
    pool_free(&w->vt);
    pool_free(&w->vn);
    text_free(&w->v_text);
    text_free(&w->vt_text);
    text_free(&w->vn_text);
    text_free(&w->body);
}

void obj_object(obj_writer *w, const char *name)
{
    obj_flush(w);
    gen_printf(w->file, w->path, "o %s\n", name);
}

void obj_usemtl(obj_writer *w, const char *material)
{
    text_printf(&w->body, "usemtl %s\n", material);
}

void obj_place(obj_writer *w, mat4 model, uv_map uv)
{
    mat3 linear;
    glm_mat4_copy(model, w->model);
    glm_mat4_pick3(model, linear);
    glm_mat3_inv(linear, w->normal_matrix);
    glm_mat3_transpose(w->normal_matrix);
    w->uv = uv;
}

void obj_place_identity(obj_writer *w)
{
    mat4 identity = GLM_MAT4_IDENTITY_INIT;
    obj_place(w, identity, UV_WHOLE);
}

long obj_vertex(obj_writer *w, vec3 p)
{
    vec3 world;
    char text[LINE_TEXT];
    glm_mat4_mulv3(w->model, p, 1.0f, world);
    format_numbers(text, world, 3);
    return pool_id(&w->v, &w->v_text, "v", text);
}

/* Colour is part of the key: the same point in two colours is two vertices. */
long obj_vertex_rgb(obj_writer *w, vec3 p, vec3 rgb)
{
    float xyzrgb[6];
    char text[LINE_TEXT];
    glm_mat4_mulv3(w->model, p, 1.0f, xyzrgb);
    glm_vec3_copy(rgb, xyzrgb + 3);
    format_numbers(text, xyzrgb, 6);
    return pool_id(&w->v, &w->v_text, "v", text);
}

long obj_uv(obj_writer *w, float u, float v)
{
    float uv[2] = {w->uv.u0 + w->uv.su * u, w->uv.v0 + w->uv.sv * v};
    char text[LINE_TEXT];
    format_numbers(text, uv, 2);
    return pool_id(&w->vt, &w->vt_text, "vt", text);
}

long obj_normal(obj_writer *w, vec3 n)
{
    vec3 world;
    char text[LINE_TEXT];
    glm_mat3_mulv(w->normal_matrix, n, world);
    glm_vec3_normalize(world);
    format_numbers(text, world, 3);
    return pool_id(&w->vn, &w->vn_text, "vn", text);
}

obj_corner obj_corner_at(obj_writer *w, vec3 p, vec3 n, float u, float v)
{
    return (obj_corner){obj_vertex(w, p), obj_uv(w, u, v), obj_normal(w, n)};
}

void obj_face(obj_writer *w, int count, const obj_corner *corners)
{
    text_printf(&w->body, "f");
    for (int i = 0; i < count; i++) {
        const obj_corner *c = &corners[i];
        if (c->vt && c->vn)
            text_printf(&w->body, " %ld/%ld/%ld", c->v, c->vt, c->vn);
        else if (c->vt)
            text_printf(&w->body, " %ld/%ld", c->v, c->vt);
        else
            text_printf(&w->body, " %ld", c->v);
    }
    text_printf(&w->body, "\n");
    w->triangles += count - 2;
}

void obj_tri(obj_writer *w, obj_corner a, obj_corner b, obj_corner c)
{
    obj_face(w, 3, (obj_corner[]){a, b, c});
}

void obj_quad(obj_writer *w, obj_corner a, obj_corner b, obj_corner c,
              obj_corner d)
{
    obj_tri(w, a, b, c);
    obj_tri(w, a, c, d);
}
