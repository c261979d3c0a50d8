/* fuzz/fuzz_draw.c — libFuzzer target for the draw call and the clipper.
 *
 * The input decodes into one of two tests (byte 0 picks: 3 mod 4 is the
 * clipper, anything else a draw):
 *
 *   draw   a framebuffer of 1..64 × 1..64, a mesh of 1..16 vertices with raw
 *          float positions (NaN, inf, huge, denormal included), optional
 *          normals, uvs, colors and texture, 0..48 indices as a list or a
 *          strip (sometimes out of range), world/view/projection matrices
 *          either raw floats or built with cglm from decoded camera
 *          parameters (near down to 1e-30, far up to 1e30), shading, cull
 *          and front. It is drawn four times: in SR_SHADE_ID with cull none,
 *          back and front, then in the decoded shading and cull mode.
 *   clip   three finite clip-space vertices (coordinates free, or on a plane
 *          give or take a few ulps) with 0..8 varyings, and a plane mask
 *          (the OR of the outcodes, as the pipeline passes, or any mask).
 *
 * Every invariant below is one the headers or DESIGN.md promise; a broken one
 * prints what and where, then abort()s so libFuzzer saves the input.
 */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cglm/cglm.h>
#include <cglm/clipspace/ortho_lh_zo.h>
#include <cglm/clipspace/persp_lh_zo.h>
#include <cglm/clipspace/view_lh.h>

#include "softrast/camera.h"
#include "softrast/clip.h"
#include "softrast/framebuffer.h"
#include "softrast/mesh.h"
#include "softrast/pipeline.h"
#include "softrast/texture.h"
#include "softrast/vertex.h"
#include "softrast/viewport.h"

#include "fuzz_common.h" /* fail(), CHECK() */

#define MAX_SIDE 64
#define MAX_VERTS 16
#define MAX_INDICES 48
#define MAX_TEXTURE_SIDE 4
#define CULL_MODES 3

/* The clipper's outputs lie inside each plane it clipped against, up to
 * rounding: every cut vertex is rounded to float once per coordinate per
 * plane, a few ulps (2^-24 ≈ 6e-8) of the vertex's largest coordinate. */
#define CLIP_INSIDE_REL_TOL 1e-5
/* Interpolated values stay within the inputs' range up to float rounding of
 * the largest input magnitude (t rounds to 1 when d_out ≪ d_in). */
#define CLIP_RANGE_REL_TOL 1e-6

/* A finding already reported and waiting for a fix in src/ can be let
 * through by naming its tag in FUZZ_TOLERATE (comma-separated), so a long run
 * keeps looking for new ones; see fuzz/README.md for the tags. */
static bool tolerated(const char *tag)
{
    const char *list = getenv("FUZZ_TOLERATE");
    size_t n = strlen(tag);
    for (const char *at = list; at && (at = strstr(at, tag)); at += n)
        if ((at == list || at[-1] == ',') && (at[n] == '\0' || at[n] == ','))
            return true;
    return false;
}

#define CHECK_KNOWN(tag, cond, ...)                                 \
    do {                                                            \
        if (!(cond) && !tolerated(tag))                             \
            fail(__FILE__, __LINE__, #cond " [" tag "]", __VA_ARGS__); \
    } while (0)

/* ---- decoding ---------------------------------------------------------- */

/* Reads the input front to back; past the end every byte is 0. */
typedef struct reader {
    const uint8_t *data;
    size_t size, pos;
    float prev; /* the anchor that "a few ulps from the previous value" uses */
} reader;

static uint8_t take_u8(reader *r)
{
    return r->pos < r->size ? r->data[r->pos++] : 0;
}

static uint16_t take_u16(reader *r)
{
    uint16_t lo = take_u8(r);
    return (uint16_t)(lo | (uint16_t)take_u8(r) << 8);
}

static uint32_t take_u32(reader *r)
{
    uint32_t lo = take_u16(r);
    return lo | (uint32_t)take_u16(r) << 16;
}

static float float_from_bits(uint32_t bits)
{
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

static const float specials[32] = {
    0.0f, -0.0f, 1.0f, -1.0f, 0.5f, -0.5f, 2.0f, -2.0f,
    NAN, -NAN, INFINITY, -INFINITY, FLT_MAX, -FLT_MAX, FLT_MIN, -FLT_MIN,
    FLT_TRUE_MIN, -FLT_TRUE_MIN, 1e-30f, -1e-30f, 1e30f, -1e30f, 1e-6f, -1e-6f,
    1e6f, -1e6f, 0x1.fffffep-1f, 0x1.000002p+0f, 1e-38f, 3e38f, 1e-20f, 1e20f,
};

/* A float with a one-byte tag saying how it is coded, so the fuzzer finds
 * both ordinary scenes and every kind of hostile value:
 *   0x00–0x3F  int16 / 256        (±128, in 1/256 steps: ordinary geometry)
 *   0x40–0x5F  (tag & 31) − 16    (small integers)
 *   0x60–0x7F  raw IEEE bits      (NaN payloads, denormals, anything)
 *   0x80–0x9F  specials[tag & 31] (NaN, ±inf, FLT_MAX, FLT_TRUE_MIN, …)
 *   0xA0–0xBF  ±10^e, e = −46 … 39 from the next byte (every magnitude)
 *   0xC0–0xDF  int32 / 65536      (±32768)
 *   0xE0–0xFF  ±prev moved by (tag & 7) − 4 ulps (on a plane, or a hair off) */
static float take_float(reader *r)
{
    uint8_t tag = take_u8(r);
    float f;
    switch (tag >> 5) {
    case 0:
    case 1: f = (float)(int16_t)take_u16(r) / 256.0f; break;
    case 2: f = (float)((int)(tag & 31) - 16); break;
    case 3: f = float_from_bits(take_u32(r)); break;
    case 4: f = specials[tag & 31]; break;
    case 5: {
        double e = -46.0 + 85.0 * take_u8(r) / 255.0;
        double m = pow(10.0, e);
        f = (float)(m < FLT_MAX ? m : FLT_MAX);
        f = (tag & 1) ? -f : f;
        break;
    }
    case 6: f = (float)((double)(int32_t)take_u32(r) / 65536.0); break;
    default: {
        f = (tag & 8) ? -r->prev : r->prev;
        for (int k = (tag & 7) - 4; k > 0; k--)
            f = nextafterf(f, INFINITY);
        for (int k = (tag & 7) - 4; k < 0; k++)
            f = nextafterf(f, -INFINITY);
        break;
    }
    }
    r->prev = f;
    return f;
}

static float take_finite_float(reader *r)
{
    float f = take_float(r);
    return isfinite(f) ? f : 0.0f;
}

static void take_vec(reader *r, float *v, int n)
{
    for (int i = 0; i < n; i++)
        v[i] = take_float(r);
}

/* 10^e with e in [lo, hi] from one byte, or a raw float when the byte is 255. */
static float take_log_scale(reader *r, double lo, double hi)
{
    uint8_t b = take_u8(r);
    if (b == 255)
        return take_float(r);
    return (float)pow(10.0, lo + (hi - lo) * b / 254.0);
}

/* ---- the scene --------------------------------------------------------- */

typedef struct scene {
    int width, height;
    sr_mesh mesh;
    bool indices_valid;
    mat4 world, view, projection;
    bool matrices_finite; /* all three, after the all-zero = identity default */
    sr_shade shade;
    sr_cull cull;
    sr_front front;
    sr_filter filter;
    sr_texture texture;
    bool has_texture;
    vec3 light;
    bool reversed_z; /* the framebuffer's depth convention: clear 0, GREATER */
    int threads;     /* for the threaded draw compared with one thread, or 0: none */
    bool big;        /* that comparison on a framebuffer of several tiles */
} scene;

static void take_world(reader *r, mat4 m, int mode)
{
    switch (mode) {
    case 0: glm_mat4_zero(m); break; /* zero means identity */
    case 1: take_vec(r, m[0], 16); break;
    case 2: {
        vec3 t, axis, s;
        take_vec(r, t, 3);
        float angle = take_float(r);
        take_vec(r, axis, 3);
        take_vec(r, s, 3);
        glm_translate_make(m, t);
        glm_rotate(m, angle, axis);
        glm_scale(m, s);
        break;
    }
    default: glm_mat4_identity(m); break;
    }
}

static void take_view(reader *r, mat4 m, int mode)
{
    switch (mode) {
    case 0: glm_mat4_zero(m); break;
    case 1: take_vec(r, m[0], 16); break;
    case 2: {
        vec3 eye, target, up;
        take_vec(r, eye, 3);
        take_vec(r, target, 3);
        take_vec(r, up, 3);
        glm_lookat_lh(eye, target, up, m);
        break;
    }
    default: { /* a camera at -z looking at the origin, eye moved a little */
        vec3 eye = { 0.0f, 0.0f, -3.0f }, target = { 0.0f, 0.0f, 0.0f }, up = { 0.0f, 1.0f, 0.0f };
        eye[0] += (float)(int8_t)take_u8(r) / 32.0f;
        eye[1] += (float)(int8_t)take_u8(r) / 32.0f;
        eye[2] += (float)(int8_t)take_u8(r) / 32.0f;
        glm_lookat_lh(eye, target, up, m);
        break;
    }
    }
}

static void take_projection(reader *r, mat4 m, int mode, int width, int height)
{
    switch (mode) {
    case 0: glm_mat4_zero(m); break;
    case 1: take_vec(r, m[0], 16); break;
    case 2: {
        /* kind: bit 0 builds it through sr_camera_projection, which adds
         * bit 1 reversed z, bit 2 far at infinity, bit 3 orthographic */
        uint8_t kind = take_u8(r), f = take_u8(r);
        float fovy = f == 255 ? take_float(r) : 0.005f + 3.13f * f / 254.0f;
        float aspect = take_u8(r) & 1 ? take_float(r) : (float)width / (float)height;
        float near = take_log_scale(r, -30.0, 2.0);
        float far = take_log_scale(r, -30.0, 30.0);
        if (!(kind & 1)) {
            glm_perspective_lh_zo(fovy, aspect, near, far, m);
            break;
        }
        sr_camera cam = sr_camera_default();
        cam.fov_deg = glm_deg(fovy);
        cam.near = near;
        cam.far = kind & 4 ? INFINITY : far;
        cam.reversed_z = kind & 2;
        cam.ortho_height = kind & 8 ? take_float(r) : 0.0f;
        if (sr_camera_check(&cam, NULL))
            sr_camera_projection(&cam, aspect, m);
        else
            glm_mat4_zero(m); /* no matrix can be built from it (camera.h) */
        break;
    }
    default: {
        float left = take_float(r), right = take_float(r), bottom = take_float(r), top = take_float(r);
        float near = take_float(r), far = take_float(r);
        glm_ortho_lh_zo(left, right, bottom, top, near, far, m);
        break;
    }
    }
}

static bool matrix_is_zero(const mat4 m)
{
    static const mat4 zero;
    return memcmp(m, zero, sizeof zero) == 0;
}

static bool matrix_is_finite(const mat4 m)
{
    if (matrix_is_zero(m))
        return true; /* the identity, as far as sr_draw is concerned */
    for (int c = 0; c < 4; c++)
        for (int k = 0; k < 4; k++)
            if (!isfinite(m[c][k]))
                return false;
    return true;
}

static uint32_t take_index(reader *r, uint32_t vertex_count)
{
    uint8_t b = take_u8(r);
    if (b < 0xF8)
        return b % vertex_count;
    switch (b & 7) {
    case 0: return vertex_count;
    case 1: return vertex_count + 1;
    case 2: return UINT32_MAX;
    case 3: return 0x80000000u;
    case 4: return UINT32_MAX / 3;
    default: return vertex_count + (b & 7);
    }
}

/* Flag bits of the scene header. */
enum {
    F_STRIP = 1, F_NORMALS = 2, F_UVS = 4, F_COLORS = 8, F_TEXTURE = 16,
    F_CULL_SHIFT = 5, F_FRONT_CCW = 128,
};

static bool scene_decode(reader *r, scene *sc)
{
    memset(sc, 0, sizeof *sc);
    sc->width = 1 + take_u8(r) % MAX_SIDE;
    sc->height = 1 + take_u8(r) % MAX_SIDE;
    uint32_t n = 1 + take_u8(r) % MAX_VERTS;
    uint8_t flags = take_u8(r), modes = take_u8(r), matrices = take_u8(r);
    sc->cull = (sr_cull)(((flags >> F_CULL_SHIFT) & 3) % CULL_MODES);
    sc->front = flags & F_FRONT_CCW ? SR_FRONT_CCW : SR_FRONT_CW;
    sc->shade = (sr_shade)((modes & 0x7F) % SR_SHADE_COUNT);
    sc->filter = modes & 0x80 ? SR_FILTER_NEAREST : SR_FILTER_BILINEAR;

    uint32_t index_count = take_u8(r) % (MAX_INDICES + 1);
    if (!sr_mesh_alloc(&sc->mesh, n, index_count, flags & F_NORMALS, flags & F_UVS, flags & F_COLORS, NULL))
        return false;
    sc->mesh.topology = flags & F_STRIP ? SR_TRIANGLE_STRIP : SR_TRIANGLE_LIST;
    for (uint32_t i = 0; i < n; i++)
        take_vec(r, sc->mesh.positions[i], 3);
    for (uint32_t i = 0; sc->mesh.normals && i < n; i++)
        take_vec(r, sc->mesh.normals[i], 3);
    for (uint32_t i = 0; sc->mesh.uvs && i < n; i++)
        take_vec(r, sc->mesh.uvs[i], 2);
    for (uint32_t i = 0; sc->mesh.colors && i < n; i++)
        take_vec(r, sc->mesh.colors[i], 3);
    sc->indices_valid = true;
    for (uint32_t i = 0; i < index_count; i++) {
        sc->mesh.indices[i] = take_index(r, n);
        sc->indices_valid &= sc->mesh.indices[i] < n;
    }

    if (flags & F_TEXTURE) {
        int tw = 1 + take_u8(r) % MAX_TEXTURE_SIDE, th = 1 + take_u8(r) % MAX_TEXTURE_SIDE;
        sc->texture.texels = malloc((size_t)tw * (size_t)th * sizeof(uint32_t));
        if (!sc->texture.texels)
            return false;
        sc->texture.width = tw;
        sc->texture.height = th;
        for (int i = 0; i < tw * th; i++)
            sc->texture.texels[i] = take_u32(r) & 0xFFFFFFu;
        sc->has_texture = true;
    }
    sc->reversed_z = matrices & 0x80;
    if (matrices & 0x40)
        take_vec(r, sc->light, 3);
    take_world(r, sc->world, matrices & 3);
    take_view(r, sc->view, (matrices >> 2) & 3);
    take_projection(r, sc->projection, (matrices >> 4) & 3, sc->width, sc->height);
    sc->matrices_finite = matrix_is_finite(sc->world) && matrix_is_finite(sc->view) &&
                          matrix_is_finite(sc->projection);
    /* A quarter of the inputs (threads cost a spawn each) also draw threaded. */
    uint8_t t = take_u8(r);
    sc->threads = (t & 0x18) == 0x18 ? 2 + (t & 3) : 0;
    sc->big = t & 4;
    return true;
}

static void scene_free(scene *sc)
{
    sr_mesh_free(&sc->mesh);
    free(sc->texture.texels);
}

static uint32_t slot_count(const sr_mesh *m)
{
    if (m->topology == SR_TRIANGLE_STRIP)
        return m->index_count >= 3 ? m->index_count - 2 : 0;
    return m->index_count / 3;
}

/* Triangle k's vertex indices as DESIGN.md defines assembly (odd strip
 * triangles swap their last two); false if degenerate. */
static bool slot_triangle(const sr_mesh *m, uint32_t k, uint32_t t[3])
{
    if (m->topology == SR_TRIANGLE_STRIP) {
        t[0] = m->indices[k];
        t[1] = m->indices[k + 1 + (k & 1)];
        t[2] = m->indices[k + 2 - (k & 1)];
    } else {
        memcpy(t, &m->indices[3 * k], 3 * sizeof *t);
    }
    return t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
}

static bool position_finite(const sr_mesh *m, uint32_t i)
{
    return isfinite(m->positions[i][0]) && isfinite(m->positions[i][1]) && isfinite(m->positions[i][2]);
}

/* What the header promises sr_draw accepts: in-range indices and the inputs
 * the shading mode reads. */
static bool draw_should_succeed(const scene *sc, sr_shade shade)
{
    const sr_mesh *m = &sc->mesh;
    if (!sc->indices_valid)
        return false;
    switch (shade) {
    case SR_SHADE_NORMAL:
    case SR_SHADE_LAMBERT: return m->normals != NULL;
    case SR_SHADE_COLOR: return m->colors != NULL;
    case SR_SHADE_TEXTURE: return m->uvs != NULL && sc->has_texture;
    default: return true;
    }
}

static void print_polygon(const char *name, const sr_polygon *p, int floats);

/* Stage 6 as the draw runs it by default: 1/256 pixel, no guard band, z
 * from the projection's depth model (NULL: none). */
static bool map_vertex(const sr_vertex_out *v, int varyings, int width, int height, const sr_clip_depth *depth,
                       sr_screen_vertex *out)
{
    sr_viewport vp = { .width = width, .height = height, .subpixel_bits = SR_SUBPIXEL_BITS, .guard = 1.0f,
                       .depth = depth ? *depth : (sr_clip_depth){ .on = false } };
    return sr_viewport_map(v, varyings, &vp, out);
}

/* ---- one draw and its invariants --------------------------------------- */

typedef struct draw_run {
    const scene *sc;
    sr_shade shade;
    sr_cull cull;
    sr_framebuffer fb;
    sr_stats stats;
    bool ok;
    uint64_t observed;                /* observer calls */
    bool id_seen[MAX_INDICES];        /* triangle ids the observer saw */
} draw_run;

/* Every fan triangle that reaches the rasterizer: on screen (within the
 * slack viewport.h allows for rounding), 1/w finite and positive (DESIGN.md:
 * no division may produce inf or NaN), facing as the cull mode asks, and
 * never from non-finite input. */
static void observe(void *user, const sr_screen_vertex tri[3], bool clipped, uint32_t id)
{
    (void)clipped;
    draw_run *run = user;
    const scene *sc = run->sc;
    run->observed++;
    CHECK(id < slot_count(&sc->mesh), "id %u of %u slots", id, slot_count(&sc->mesh));
    run->id_seen[id] = true;
    uint32_t t[3];
    CHECK(slot_triangle(&sc->mesh, id, t), "observer saw degenerate slot %u", id);
    CHECK(sc->matrices_finite, "triangle %u reached the rasterizer through a non-finite matrix", id);
    for (int k = 0; k < 3; k++)
        CHECK(position_finite(&sc->mesh, t[k]), "triangle %u reached the rasterizer with non-finite vertex %u",
              id, t[k]);

    const int64_t one = SR_SUBPIXEL_ONE;
    const int64_t slack_x = (int64_t)ceil(SR_NDC_SLACK * 0.5 * sc->width * one) + 1;
    const int64_t slack_y = (int64_t)ceil(SR_NDC_SLACK * 0.5 * sc->height * one) + 1;
    const float z_slack = (float)SR_NDC_SLACK + 1e-6f;
    for (int k = 0; k < 3; k++) {
        const sr_screen_vertex *v = &tri[k];
        CHECK(v->x >= -slack_x && v->x <= sc->width * one + slack_x,
              "triangle %u vertex %d: x = %lld subpixels, framebuffer %d px wide", id, k, (long long)v->x,
              sc->width);
        CHECK(v->y >= -slack_y && v->y <= sc->height * one + slack_y,
              "triangle %u vertex %d: y = %lld subpixels, framebuffer %d px high", id, k, (long long)v->y,
              sc->height);
        CHECK(isfinite(v->z) && v->z >= -z_slack && v->z <= 1.0f + z_slack, "triangle %u vertex %d: z = %a",
              id, k, v->z);
        CHECK(isfinite(v->inv_w) && v->inv_w > 0.0f, "triangle %u vertex %d: 1/w = %a", id, k, v->inv_w);
    }

    int64_t area2 = (tri[1].x - tri[0].x) * (tri[2].y - tri[0].y) - (tri[1].y - tri[0].y) * (tri[2].x - tri[0].x);
    CHECK(area2 != 0, "triangle %u: zero-area fan triangle was not culled", id);
    bool clockwise = area2 > 0; /* y down */
    bool front = (sc->front == SR_FRONT_CW) == clockwise;
    CHECK(run->cull == SR_CULL_NONE || front == (run->cull == SR_CULL_BACK),
          "triangle %u: area2 %lld, front %d, cull %d, yet it was drawn", id, (long long)area2, sc->front,
          run->cull);
}

static bool framebuffer_untouched(const sr_framebuffer *fb)
{
    float clear = sr_framebuffer_depth_clear(fb);
    for (int i = 0; i < fb->width * fb->height; i++)
        if (fb->color[i] != 0 || memcmp(&fb->depth[i], &clear, sizeof clear) != 0)
            return false;
    return true;
}

/* A depth a draw wrote: it passed LESS against the clear value 1, or
 * GREATER against 0 in a reversed_z framebuffer (framebuffer.h). */
static bool depth_written(const sr_framebuffer *fb, float d)
{
    return fb->reversed_z ? d > SR_DEPTH_CLEAR_REVERSED : d < SR_DEPTH_CLEAR;
}

static bool stats_equal(const sr_stats *a, const sr_stats *b)
{
    return memcmp(a, b, sizeof *a) == 0;
}

static void stats_print(const char *name, const sr_stats *s)
{
    fprintf(stderr, "  %s: triangles %llu rejected %llu nonfinite %llu clipped %llu culled %llu drawn %llu "
                    "fragments %llu\n",
            name, (unsigned long long)s->triangles, (unsigned long long)s->rejected,
            (unsigned long long)s->nonfinite, (unsigned long long)s->clipped, (unsigned long long)s->culled,
            (unsigned long long)s->drawn, (unsigned long long)s->fragments);
}

/* FUZZ_VERBOSE=1 prints each decoded scene and its stats (for turning a
 * reproducer into a test, or checking that a seed draws what it should). */
static bool verbose(void)
{
    static int cached = -1;
    if (cached < 0)
        cached = getenv("FUZZ_VERBOSE") != NULL;
    return cached;
}

static void print_matrix(const char *name, const mat4 m)
{
    fprintf(stderr, "  %s:", name);
    for (int c = 0; c < 4; c++)
        fprintf(stderr, " [%a %a %a %a]", m[c][0], m[c][1], m[c][2], m[c][3]);
    fprintf(stderr, "\n");
}

static void scene_print(const scene *sc)
{
    const sr_mesh *m = &sc->mesh;
    fprintf(stderr, "scene %dx%d, %u vertices, %u indices (%s, valid %d), shade %d, cull %d, front %d, filter %d, "
                    "normals %d uvs %d colors %d texture %d reversed z %d\n",
            sc->width, sc->height, m->vertex_count, m->index_count,
            m->topology == SR_TRIANGLE_STRIP ? "strip" : "list", sc->indices_valid, sc->shade, sc->cull, sc->front,
            sc->filter, m->normals != NULL, m->uvs != NULL, m->colors != NULL, sc->has_texture, sc->reversed_z);
    for (uint32_t i = 0; i < m->vertex_count; i++)
        fprintf(stderr, "  position %u: %a %a %a\n", i, m->positions[i][0], m->positions[i][1], m->positions[i][2]);
    fprintf(stderr, "  indices:");
    for (uint32_t i = 0; i < m->index_count; i++)
        fprintf(stderr, " %u", m->indices[i]);
    fprintf(stderr, "\n");
    print_matrix("world", sc->world);
    print_matrix("view", sc->view);
    print_matrix("projection", sc->projection);
}

static void draw_run_free(draw_run *run)
{
    sr_framebuffer_destroy(&run->fb);
}

static void draw_and_check(const scene *sc, sr_shade shade, sr_cull cull, draw_run *run)
{
    memset(run, 0, sizeof *run);
    run->sc = sc;
    run->shade = shade;
    run->cull = cull;
    CHECK(sr_framebuffer_create(&run->fb, sc->width, sc->height, NULL), "framebuffer %dx%d", sc->width,
          sc->height);
    run->fb.reversed_z = sc->reversed_z;
    sr_framebuffer_clear(&run->fb, 0);

    sr_draw_desc desc = {
        .mesh = &sc->mesh, .shade = shade, .cull = cull, .front = sc->front, .filter = sc->filter,
        .texture = sc->has_texture ? &sc->texture : NULL, .observer = observe, .observer_user = run,
    };
    glm_mat4_copy((vec4 *)sc->world, desc.world);
    glm_mat4_copy((vec4 *)sc->view, desc.view);
    glm_mat4_copy((vec4 *)sc->projection, desc.projection);
    glm_vec3_copy((float *)sc->light, desc.light_dir);
    sr_error err = { .message = "" };
    run->ok = sr_draw(&run->fb, &desc, &run->stats, &err);

    bool expected = draw_should_succeed(sc, shade);
    CHECK(run->ok == expected, "sr_draw returned %d, expected %d (shade %d, indices valid %d): %s", run->ok,
          expected, shade, sc->indices_valid, err.message);
    if (!run->ok) {
        static const sr_stats zero;
        CHECK(err.message[0] != '\0', "sr_draw failed without a message");
        CHECK(framebuffer_untouched(&run->fb), "sr_draw failed (%s) but wrote pixels", err.message);
        CHECK(stats_equal(&run->stats, &zero), "sr_draw failed (%s) but counted", err.message);
        CHECK(run->observed == 0, "sr_draw failed (%s) but the observer saw triangles", err.message);
        return;
    }

    /* Depth: finite, in [0, 1]; in id mode on a color buffer cleared to 0,
     * a pixel has a color exactly when its depth was written (< 1). */
    const sr_framebuffer *fb = &run->fb;
    uint64_t written = 0;
    for (int j = 0; j < fb->height; j++)
        for (int i = 0; i < fb->width; i++) {
            size_t p = (size_t)j * (size_t)fb->width + (size_t)i;
            float d = fb->depth[p];
            CHECK(isfinite(d) && d >= 0.0f && d <= 1.0f, "pixel (%d, %d): depth %a", i, j, d);
            written += depth_written(fb, d);
            if (shade != SR_SHADE_ID)
                continue;
            uint32_t c = fb->color[p];
            CHECK((c != 0) == depth_written(fb, d), "pixel (%d, %d): color %#x, depth %a (reversed z %d)", i, j, c,
                  d, fb->reversed_z);
            CHECK(c == 0 || (c - 1 < MAX_INDICES && run->id_seen[c - 1]),
                  "pixel (%d, %d): color %#x is not a triangle the observer saw", i, j, c);
        }

    /* Stats (types.h): triangles counts the non-degenerate slots; the rest
     * are parts of it. */
    const sr_stats *s = &run->stats;
    uint64_t triangles = 0, with_bad_position = 0;
    for (uint32_t k = 0; k < slot_count(&sc->mesh); k++) {
        uint32_t t[3];
        if (!slot_triangle(&sc->mesh, k, t))
            continue;
        triangles++;
        with_bad_position += !position_finite(&sc->mesh, t[0]) || !position_finite(&sc->mesh, t[1]) ||
                             !position_finite(&sc->mesh, t[2]);
    }
    uint64_t pixels = (uint64_t)fb->width * (uint64_t)fb->height;
    bool consistent = s->triangles == triangles && s->rejected <= s->triangles && s->nonfinite <= s->rejected &&
                      s->clipped <= s->triangles && s->drawn == run->observed &&
                      s->culled + s->drawn <= (uint64_t)(SR_MAX_CLIP_VERTS - 2) * s->triangles &&
                      s->fragments <= pixels * s->drawn && s->fragments >= written &&
                      (s->fragments == 0) == (written == 0) && s->nonfinite >= with_bad_position &&
                      (sc->matrices_finite || (s->nonfinite == s->triangles && s->drawn == 0));
    if (!consistent) {
        stats_print("stats", s);
        fprintf(stderr, "  expected triangles %llu, with a non-finite position %llu, observer calls %llu, "
                        "pixels written %llu, matrices finite %d\n",
                (unsigned long long)triangles, (unsigned long long)with_bad_position,
                (unsigned long long)run->observed, (unsigned long long)written, sc->matrices_finite);
    }
    CHECK(consistent, "inconsistent stats (shade %d, cull %d)", shade, cull);
    if (verbose()) {
        fprintf(stderr, "  shade %d cull %d, %llu pixels written:\n", shade, cull, (unsigned long long)written);
        stats_print("stats", s);
    }
}

/* Culling only chooses among the same fan triangles: back and front split
 * what none draws, and none's depth is the nearer of the two at every pixel
 * (each pixel keeps the least z of the triangles covering it, or the
 * greatest in a reversed_z framebuffer). */
static void check_cull_partition(const draw_run run[CULL_MODES])
{
    const draw_run *none = &run[SR_CULL_NONE], *back = &run[SR_CULL_BACK], *front = &run[SR_CULL_FRONT];
    if (!none->ok)
        return;
    const sr_stats *n = &none->stats, *b = &back->stats, *f = &front->stats;
    bool same_geometry = n->triangles == b->triangles && n->triangles == f->triangles &&
                         n->rejected == b->rejected && n->rejected == f->rejected &&
                         n->nonfinite == b->nonfinite && n->nonfinite == f->nonfinite &&
                         n->clipped == b->clipped && n->clipped == f->clipped &&
                         n->culled + n->drawn == b->culled + b->drawn && n->culled + n->drawn == f->culled + f->drawn &&
                         n->drawn == b->drawn + f->drawn;
    if (!same_geometry) {
        stats_print("cull none", n);
        stats_print("cull back", b);
        stats_print("cull front", f);
    }
    CHECK(same_geometry, "cull modes disagree on the fan triangles");
    const sr_framebuffer *fb = &none->fb;
    for (int p = 0; p < fb->width * fb->height; p++) {
        float want = fb->reversed_z ? fmaxf(back->fb.depth[p], front->fb.depth[p])
                                    : fminf(back->fb.depth[p], front->fb.depth[p]);
        CHECK(memcmp(&fb->depth[p], &want, sizeof want) == 0,
              "pixel (%d, %d): depth %a with cull none, %a back, %a front", p % fb->width, p / fb->width,
              fb->depth[p], back->fb.depth[p], front->fb.depth[p]);
    }
}

/* Coverage and depth come from positions alone (DESIGN.md stages 3–9), so
 * the shading mode changes colors only, except that a triangle with a
 * non-finite varying the mode reads is dropped and counted non-finite
 * (shade.h). Where any vertex was non-finite the runs are not compared: a
 * triangle dropped before clipping in one mode (its varying/w overflowed) may
 * be clipped in the other and dropped only at a cut vertex, so even equal
 * nonfinite counts can come with different clipped counts
 * (fuzz/regressions/draw/shading_coverage_nonfinite_route). */
static void check_shading_independent(const draw_run *id_run, const draw_run *shaded)
{
    if (!shaded->ok || !id_run->ok || shaded->stats.nonfinite || id_run->stats.nonfinite)
        return;
    bool same = stats_equal(&id_run->stats, &shaded->stats);
    const sr_framebuffer *a = &id_run->fb, *b = &shaded->fb;
    int differ = -1;
    for (int p = 0; p < a->width * a->height && differ < 0; p++)
        if (memcmp(&a->depth[p], &b->depth[p], sizeof(float)) != 0)
            differ = p;
    if ((!same || differ >= 0) && !tolerated("shading_coverage")) {
        stats_print("id", &id_run->stats);
        stats_print("shaded", &shaded->stats);
    }
    CHECK_KNOWN("shading_coverage", same, "shading mode %d changed the stats", shaded->shade);
    CHECK_KNOWN("shading_coverage", differ < 0, "pixel (%d, %d): depth %a in id mode, %a in shading mode %d",
                differ % a->width, differ / a->width, a->depth[differ], b->depth[differ], shaded->shade);
}

/* viewport.h: a vertex with w below 2^-128 is refused (1/w overflows). */
#define VIEWPORT_MIN_W 0x1p-128
/* It also refuses one whose varying/w overflows float, which a finite
 * varying does for w up to |varying|·2^-128 (viewport.h only names the
 * w < 2^-128 case). */
static bool viewport_may_refuse(const float *v, int varyings)
{
    if (v[SR_W] < VIEWPORT_MIN_W)
        return true;
    for (int k = 0; k < varyings; k++)
        if (fabs((double)v[SR_VARYINGS_AT + k]) / v[SR_W] > FLT_MAX)
            return true;
    return false;
}

/* The reference clip's vertices must stay well clear of that. */
#define REFERENCE_MIN_W 0x1p-120
/* What the pipeline keeps of a triangle must cover the part of the screen
 * the exact clip covers (clip.h: adaptive keeps every cut vertex within
 * SR_CLIP_DEFAULT_TOLERANCE in NDC of it), in NDC area (the screen is 4). */
#define AREA_ABS_TOL 1e-4
#define AREA_REL_TOL 1e-4

/* Shoelace area of a clip-space polygon's NDC (x/w, y/w) outline; NAN if a
 * vertex has w too small to divide by. */
static double ndc_area(const sr_polygon *p)
{
    double twice = 0.0;
    for (int i = 0; i < p->count; i++) {
        const float *a = p->vert[i].v, *b = p->vert[(i + 1) % p->count].v;
        if (!(a[SR_W] >= REFERENCE_MIN_W))
            return NAN;
        twice += ((double)a[SR_X] / a[SR_W]) * ((double)b[SR_Y] / b[SR_W]) -
                 ((double)b[SR_X] / b[SR_W]) * ((double)a[SR_Y] / a[SR_W]);
    }
    return fabs(twice) * 0.5;
}

/* The NDC area of the exact clip of tri with every input coordinate moved
 * one ulp (up, down, or alternating), the largest change: how much the
 * float quantisation of the input alone decides. Near the eye a triangle
 * can be so ill-conditioned that this is large, and no float clipper can do
 * better; elsewhere it is tiny. */
static double exact_area(const sr_polygon *tri, unsigned planes, const sr_clip_depth *depth)
{
    sr_polygon ref = *tri;
    sr_clip_polygon(&ref, planes, SR_VARYINGS_AT, &(sr_clip_config){ .precision = SR_CLIP_EXACT, .depth = *depth });
    return ref.count >= 3 ? ndc_area(&ref) : 0.0;
}

static double area_sensitivity(const sr_polygon *tri, unsigned planes, const sr_clip_depth *depth, double area)
{
    double worst = 0.0;
    for (int pattern = 0; pattern < 3; pattern++) {
        sr_polygon moved = *tri;
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 4; k++) {
                bool up = pattern == 0 || (pattern == 2 && (i + k) % 2 == 0);
                float *c = &moved.vert[i].v[k];
                *c = nextafterf(*c, up ? INFINITY : -INFINITY);
                if (!isfinite(*c))
                    return INFINITY;
            }
        double a = exact_area(&moved, planes, depth);
        worst = isnan(a) ? INFINITY : fmax(worst, fabs(a - area));
    }
    return worst;
}

/* Compares what the pipeline draws of triangle `tri` (the clipper's `got`,
 * nothing if the viewport refuses one of its vertices) with the exact clip
 * (SR_CLIP_EXACT: exact expansions, rounded once), allowing for what one
 * ulp of input changes (area_sensitivity). Skipped when the exact clip
 * lands in the documented refusal zone of tiny w. */
/* The NDC perimeter of a polygon (NaN where a w is too small to divide). */
static double ndc_perimeter(const sr_polygon *p)
{
    double sum = 0.0;
    for (int i = 0; i < p->count; i++) {
        const float *a = p->vert[i].v, *b = p->vert[(i + 1) % p->count].v;
        sum += hypot((double)a[SR_X] / a[SR_W] - (double)b[SR_X] / b[SR_W],
                     (double)a[SR_Y] / a[SR_W] - (double)b[SR_Y] / b[SR_W]);
    }
    return sum;
}

/* vertex_tolerance: the NDC error the clipper may leave in a cut vertex
 * (the adaptive mode's tolerance; 0 for exact), which moves the area by at
 * most twice the perimeter times it. */
static void check_clip_area(const sr_polygon *tri, unsigned planes, const sr_polygon *got, double vertex_tolerance,
                            const sr_clip_depth *depth, const char *what)
{
    double want = exact_area(tri, planes, depth);
    if (isnan(want))
        return;
    bool drawn = got->count >= 3;
    for (int i = 0; i < got->count && drawn; i++) {
        sr_screen_vertex sv;
        drawn = map_vertex(&got->vert[i], 0, MAX_SIDE, MAX_SIDE, depth, &sv);
    }
    double have = drawn ? ndc_area(got) : 0.0;
    double promised = drawn ? 2.0 * ndc_perimeter(got) * vertex_tolerance : 0.0;
    double tolerance = AREA_ABS_TOL + AREA_REL_TOL * want + (isfinite(promised) ? promised : 0.0);
    if (fabs(have - want) <= tolerance)
        return;
    double sensitivity = area_sensitivity(tri, planes, depth, want);
    bool close = fabs(have - want) <= tolerance + 4.0 * sensitivity;
    if (!close && !tolerated("clip_precision")) {
        sr_polygon ref = *tri;
        sr_clip_polygon(&ref, planes, SR_VARYINGS_AT, &(sr_clip_config){ .precision = SR_CLIP_EXACT, .depth = *depth });
        print_polygon("triangle in clip space", tri, SR_VARYINGS_AT);
        print_polygon(drawn ? "clipped" : "clipped (dropped: refused or empty)", got, SR_VARYINGS_AT);
        print_polygon("exact clip", &ref, SR_VARYINGS_AT);
    }
    CHECK_KNOWN("clip_precision", close,
                "%s: the pipeline draws NDC area %.9g of this triangle, an exact clip %.9g (one input ulp moves "
                "it by %.3g)", what, have, want, sensitivity);
}

static void matrix_or_identity(const mat4 m, mat4 out)
{
    if (matrix_is_zero(m))
        glm_mat4_identity(out);
    else
        glm_mat4_copy((vec4 *)m, out);
}

/* Stages 1 to 6 again through their public headers, triangle by triangle:
 * what the clipper leaves of a triangle the pipeline clips, the viewport
 * stage must accept (viewport.h: all but w < 2^-128), and it must cover
 * what an exact clip covers (check_clip_area). Also ties sr_stats.rejected
 * to the stages: outcode and non-finite rejections plus refused polygons. */
static void check_stages(const scene *sc, const sr_stats *stats)
{
    const sr_mesh *m = &sc->mesh;
    if (!sc->indices_valid)
        return;
    mat4 world, view, projection;
    matrix_or_identity(sc->world, world);
    matrix_or_identity(sc->view, view);
    matrix_or_identity(sc->projection, projection);
    sr_vertex_transform xf;
    sr_vertex_make_transform(world, view, projection, &xf);
    sr_varying_layout layout = sr_vertex_layout(SR_SHADE_ID, m, false);
    sr_vertex_out verts[MAX_VERTS];
    sr_vertex_run(m, &xf, &layout, 0, m->vertex_count, verts);
    /* A vertex inside every plane is mapped once, up front; one the viewport
     * refuses drops every triangle that uses it (pipeline.c counts those as
     * non-finite). */
    unsigned codes[MAX_VERTS];
    sr_clip_depth depth = sr_clip_depth_of((const float(*)[4])projection);
    for (uint32_t i = 0; i < m->vertex_count; i++) {
        sr_screen_vertex sv;
        codes[i] = sr_clip_outcode_with(verts[i].v, &depth);
        if (codes[i] == 0 && !map_vertex(&verts[i], 0, sc->width, sc->height, &depth, &sv))
            codes[i] = SR_OUT_NONFINITE;
    }
    /* The draw's default clip: adaptive, within half a subpixel step in NDC
     * of the framebuffer's longer side (pipeline.c). */
    int side = sc->width > sc->height ? sc->width : sc->height;
    sr_clip_config cfg = { .precision = SR_CLIP_ADAPTIVE, .ndc_tolerance = 1.0 / ((double)SR_SUBPIXEL_ONE * side),
                           .depth = depth };
    uint64_t rejected = 0;
    for (uint32_t k = 0; k < slot_count(m); k++) {
        uint32_t t[3];
        if (!slot_triangle(m, k, t))
            continue;
        unsigned c0 = codes[t[0]], c1 = codes[t[1]], c2 = codes[t[2]];
        if (((c0 | c1 | c2) & SR_OUT_NONFINITE) || (c0 & c1 & c2)) {
            rejected++;
            continue;
        }
        sr_polygon poly = { .count = 3, .vert = { verts[t[0]], verts[t[1]], verts[t[2]] } };
        sr_polygon in = poly;
        if (c0 | c1 | c2)
            sr_clip_polygon(&poly, c0 | c1 | c2, SR_VARYINGS_AT, &cfg);
        bool refused = false;
        for (int i = 0; i < poly.count; i++) {
            sr_screen_vertex sv;
            if (!map_vertex(&poly.vert[i], 0, sc->width, sc->height, &depth, &sv)) {
                refused = true;
                if (viewport_may_refuse(poly.vert[i].v, 0))
                    continue;
                if (!tolerated("clip_precision")) {
                    print_polygon("triangle in clip space", &in, SR_VARYINGS_AT);
                    print_polygon("clipped", &poly, SR_VARYINGS_AT);
                }
                CHECK_KNOWN("clip_precision", false,
                            "triangle %u: clipped vertex %d (%a, %a, %a, %a) is refused by the viewport", k, i,
                            poly.vert[i].v[SR_X], poly.vert[i].v[SR_Y], poly.vert[i].v[SR_Z], poly.vert[i].v[SR_W]);
            }
        }
        char what[32];
        snprintf(what, sizeof what, "triangle %u", k);
        check_clip_area(&in, c0 | c1 | c2, &poly, cfg.ndc_tolerance, &depth, what);
        rejected += refused;
    }
    CHECK(stats->rejected == rejected || tolerated("clip_precision"),
          "sr_draw rejected %llu triangles, its stages %llu", (unsigned long long)stats->rejected,
          (unsigned long long)rejected);
}

/* One draw without an observer (which would force one thread). */
static bool draw_plain(const scene *sc, sr_shade shade, int threads, sr_workspace *ws, int width, int height,
                       sr_framebuffer *fb, sr_stats *stats)
{
    CHECK(sr_framebuffer_create(fb, width, height, NULL), "framebuffer %dx%d", width, height);
    fb->reversed_z = sc->reversed_z;
    sr_framebuffer_clear(fb, 0);
    sr_draw_desc desc = {
        .mesh = &sc->mesh, .shade = shade, .cull = sc->cull, .front = sc->front, .filter = sc->filter,
        .texture = sc->has_texture ? &sc->texture : NULL, .threads = threads, .workspace = ws,
    };
    glm_mat4_copy((vec4 *)sc->world, desc.world);
    glm_mat4_copy((vec4 *)sc->view, desc.view);
    glm_mat4_copy((vec4 *)sc->projection, desc.projection);
    glm_vec3_copy((float *)sc->light, desc.light_dir);
    *stats = (sr_stats){ 0 };
    return sr_draw(fb, &desc, stats, NULL);
}

/* pipeline.h: "The image and depth are bit-identical for every thread
 * count" (and so are the counts). Drawn in the decoded shading mode (id if
 * the mesh cannot be shaded so), on the scene's framebuffer or one of
 * several SR_TILE_SIDE tiles, the threaded draw reusing one workspace. */
static void check_threads(const scene *sc)
{
    if (!sc->indices_valid || sc->threads == 0)
        return;
    sr_shade shade = draw_should_succeed(sc, sc->shade) ? sc->shade : SR_SHADE_ID;
    int width = sc->width + (sc->big ? SR_TILE_SIDE + 13 : 0);
    int height = sc->height + (sc->big ? SR_TILE_SIDE + 7 : 0);
    sr_workspace *ws = sr_workspace_create();
    CHECK(ws != NULL, "no workspace");
    sr_framebuffer one, many;
    sr_stats one_stats, many_stats;
    bool one_ok = draw_plain(sc, shade, 1, NULL, width, height, &one, &one_stats);
    bool many_ok = draw_plain(sc, shade, sc->threads, ws, width, height, &many, &many_stats);
    bool again_ok = true;
    if (sc->big) { /* the workspace again, as a viewer reuses it every frame */
        sr_framebuffer_destroy(&many);
        again_ok = draw_plain(sc, shade, sc->threads, ws, width, height, &many, &many_stats);
    }
    CHECK(one_ok && many_ok && again_ok, "sr_draw failed: %d with one thread, %d/%d with %d", one_ok, many_ok,
          again_ok, sc->threads);
    if (!stats_equal(&one_stats, &many_stats)) {
        stats_print("one thread", &one_stats);
        stats_print("threads", &many_stats);
    }
    CHECK(stats_equal(&one_stats, &many_stats), "%d threads count differently from one (%dx%d, shade %d)",
          sc->threads, width, height, shade);
    for (int p = 0; p < width * height; p++)
        CHECK(one.color[p] == many.color[p] && memcmp(&one.depth[p], &many.depth[p], sizeof(float)) == 0,
              "pixel (%d, %d): color %#x depth %a with one thread, %#x %a with %d (%dx%d, shade %d)", p % width,
              p / width, one.color[p], one.depth[p], many.color[p], many.depth[p], sc->threads, width, height,
              shade);
    sr_framebuffer_destroy(&one);
    sr_framebuffer_destroy(&many);
    sr_workspace_destroy(ws);
}

static void fuzz_draw(reader *r)
{
    scene sc;
    if (!scene_decode(r, &sc)) {
        scene_free(&sc);
        return;
    }
    if (verbose())
        scene_print(&sc);
    draw_run id_runs[CULL_MODES], shaded;
    for (int c = 0; c < CULL_MODES; c++)
        draw_and_check(&sc, SR_SHADE_ID, (sr_cull)c, &id_runs[c]);
    check_cull_partition(id_runs);
    if (id_runs[SR_CULL_NONE].ok)
        check_stages(&sc, &id_runs[SR_CULL_NONE].stats);
    draw_and_check(&sc, sc.shade, sc.cull, &shaded);
    check_shading_independent(&id_runs[sc.cull], &shaded);
    check_threads(&sc);
    for (int c = 0; c < CULL_MODES; c++)
        draw_run_free(&id_runs[c]);
    draw_run_free(&shaded);
    scene_free(&sc);
}

/* ---- the clipper on its own --------------------------------------------- */

/* Distances from the convention table (DESIGN.md), not from the clipper. */
static double plane_distance(int plane, const float *c)
{
    double x = c[SR_X], y = c[SR_Y], z = c[SR_Z], w = c[SR_W];
    switch (plane) {
    case SR_PLANE_NEAR: return z;
    case SR_PLANE_FAR: return w - z;
    case SR_PLANE_LEFT: return w + x;
    case SR_PLANE_RIGHT: return w - x;
    case SR_PLANE_BOTTOM: return w + y;
    default: return w - y;
    }
}

/* w first, then x, y, z each either free or on a plane through w (tag
 * 0xE0–0xFF: ±w, a few ulps off), then the varyings. All finite: the
 * pipeline never hands the clipper anything else. */
static void take_clip_vertex(reader *r, sr_vertex_out *v, int varyings)
{
    memset(v, 0, sizeof *v);
    float w = take_finite_float(r);
    v->v[SR_W] = w;
    for (int k = SR_X; k <= SR_Z; k++) {
        r->prev = w;
        v->v[k] = take_finite_float(r);
    }
    for (int k = 0; k < varyings; k++)
        v->v[SR_VARYINGS_AT + k] = take_finite_float(r);
}

static bool vertices_identical(const sr_vertex_out *a, const sr_vertex_out *b, int floats)
{
    return memcmp(a->v, b->v, (size_t)floats * sizeof(float)) == 0;
}

/* True if b is a rotation of a (reversed: of a read backwards), bit for bit. */
static bool same_cycle(const sr_polygon *a, const sr_polygon *b, bool reversed, int floats)
{
    if (a->count != b->count)
        return false;
    int n = a->count;
    if (n == 0)
        return true;
    for (int shift = 0; shift < n; shift++) {
        bool all = true;
        for (int i = 0; i < n && all; i++) {
            int j = reversed ? ((shift - i) % n + n) % n : (shift + i) % n;
            all = vertices_identical(&a->vert[i], &b->vert[j], floats);
        }
        if (all)
            return true;
    }
    return false;
}

static void print_polygon(const char *name, const sr_polygon *p, int floats)
{
    fprintf(stderr, "  %s (%d vertices):\n", name, p->count);
    for (int i = 0; i < p->count; i++) {
        fprintf(stderr, "   ");
        for (int k = 0; k < floats; k++)
            fprintf(stderr, " %a", p->vert[i].v[k]);
        fprintf(stderr, "\n");
    }
}

static void fuzz_clip(reader *r)
{
    uint8_t mode = take_u8(r);
    int varyings = ((mode >> 1) & 0x1F) % (SR_MAX_VARYINGS + 1);
    /* Adaptive (the default) and exact promise accurate cut vertices; float
     * and double are knobs for measuring what accuracy costs, promised
     * nothing but the structural checks. */
    sr_clip_config cfg = { .precision = (sr_clip_precision)(mode >> 6) };
    sr_clip_precision precision = cfg.precision;
    bool exact = precision == SR_CLIP_ADAPTIVE || precision == SR_CLIP_EXACT;
    int floats = SR_VARYINGS_AT + varyings;
    sr_polygon in;
    memset(&in, 0, sizeof in);
    in.count = 3;
    for (int i = 0; i < 3; i++)
        take_clip_vertex(r, &in.vert[i], varyings);
    unsigned c0 = sr_clip_outcode(in.vert[0].v), c1 = sr_clip_outcode(in.vert[1].v),
             c2 = sr_clip_outcode(in.vert[2].v);
    bool as_pipeline = !(mode & 1); /* the mask the draw call would pass */
    unsigned planes = as_pipeline ? (c0 | c1 | c2) & SR_OUT_PLANES : take_u8(r) & SR_OUT_PLANES;
    if (as_pipeline && (c0 & c1 & c2))
        return; /* the pipeline rejects these without clipping */

    sr_polygon out = in, rotated = in, reversed = in;
    for (int i = 0; i < 3; i++) {
        rotated.vert[i] = in.vert[(i + 1) % 3];
        reversed.vert[i] = in.vert[2 - i];
    }
    int n = sr_clip_polygon(&out, planes, floats, &cfg);
    sr_clip_polygon(&rotated, planes, floats, &cfg);
    sr_clip_polygon(&reversed, planes, floats, &cfg);

    CHECK(n == out.count, "returned %d, polygon holds %d", n, out.count);
    CHECK(n == 0 || (n >= 3 && n <= SR_MAX_CLIP_VERTS), "%d vertices", n);

    /* Watertight (DESIGN.md): every cut is made from the inside end toward
     * the outside one, so walking the triangle from another vertex or the
     * other way round gives the same vertices, bit for bit. */
    bool tight = same_cycle(&out, &rotated, false, floats) && same_cycle(&out, &reversed, true, floats);
    if (!tight) {
        print_polygon("input", &in, floats);
        print_polygon("clipped", &out, floats);
        print_polygon("clipped from v1", &rotated, floats);
        print_polygon("clipped backwards", &reversed, floats);
    }
    CHECK(tight, "clipping depends on the walk order (planes %#x)", planes);

    /* All three inside every plane asked for: the triangle comes back as it was. */
    bool all_inside = true, one_plane_all_outside = false;
    for (int p = 0; p < SR_CLIP_PLANES; p++) {
        if (!(planes & (1u << p)))
            continue;
        int outside = 0;
        for (int i = 0; i < 3; i++)
            outside += plane_distance(p, in.vert[i].v) < 0.0;
        all_inside &= outside == 0;
        one_plane_all_outside |= outside == 3;
    }
    /* (A vertex at w <= 0 inside every plane is the eye itself, and such a
     * polygon, seen edge-on, may be dropped: clip.c.) */
    bool w_positive = in.vert[0].v[SR_W] > 0.0f && in.vert[1].v[SR_W] > 0.0f && in.vert[2].v[SR_W] > 0.0f;
    if (all_inside)
        CHECK((n == 0 && !w_positive) || (n == 3 && same_cycle(&in, &out, false, floats)),
              "a triangle inside planes %#x came back with %d vertices", planes, n);
    if (one_plane_all_outside)
        CHECK(n == 0, "a triangle outside one of planes %#x left %d vertices", planes, n);

    /* Each coordinate of the output lies within the inputs' range (every
     * vertex is a convex combination of the inputs), up to rounding. */
    float lo[SR_VERTEX_FLOATS], hi[SR_VERTEX_FLOATS];
    double pos_scale = 0.0;
    for (int k = 0; k < floats; k++) {
        lo[k] = fminf(fminf(in.vert[0].v[k], in.vert[1].v[k]), in.vert[2].v[k]);
        hi[k] = fmaxf(fmaxf(in.vert[0].v[k], in.vert[1].v[k]), in.vert[2].v[k]);
        if (k < SR_VARYINGS_AT)
            pos_scale = fmax(pos_scale, fmax(fabs(lo[k]), fabs(hi[k])));
    }
    for (int i = 0; i < n; i++) {
        const float *v = out.vert[i].v;
        for (int k = 0; k < floats; k++) {
            /* Forced float evaluates b − a in float, which overflows for end
             * points of opposite sign near FLT_MAX (the adaptive choice goes
             * exact there): fuzz/regressions/draw/clip_float_difference_overflow. */
            if (precision == SR_CLIP_FLOAT && (double)hi[k] - lo[k] > FLT_MAX)
                continue;
            double scale = k < SR_VARYINGS_AT ? pos_scale : fmax(fabs(lo[k]), fabs(hi[k]));
            double tol = CLIP_RANGE_REL_TOL * scale;
            CHECK(isfinite(v[k]) && v[k] >= lo[k] - tol && v[k] <= hi[k] + tol,
                  "vertex %d float %d = %a outside the inputs' [%a, %a] (precision %d)", i, k, v[k], lo[k], hi[k],
                  precision);
        }
        double mag = fmax(fmax(fabs(v[SR_X]), fabs(v[SR_Y])), fmax(fabs(v[SR_Z]), fabs(v[SR_W])));
        for (int p = 0; p < SR_CLIP_PLANES && exact; p++) {
            if (!(planes & (1u << p)))
                continue;
            double d = plane_distance(p, v);
            if (!(d >= -CLIP_INSIDE_REL_TOL * mag) && !tolerated("clip_precision")) {
                print_polygon("input", &in, floats);
                print_polygon("clipped", &out, floats);
            }
            CHECK_KNOWN("clip_precision", d >= -CLIP_INSIDE_REL_TOL * mag,
                        "vertex %d is %a outside plane %d (magnitude %a, planes %#x)", i, -d, p, mag, planes);
        }
        /* What the pipeline clips, the viewport stage must accept
         * (viewport.h: all but w < 2^-128) and map without an inf or NaN
         * (DESIGN.md). */
        if (as_pipeline && exact && !viewport_may_refuse(v, varyings)) {
            sr_screen_vertex sv;
            bool mapped = map_vertex(&out.vert[i], varyings, MAX_SIDE, MAX_SIDE, &cfg.depth, &sv);
            if (!mapped && !tolerated("clip_precision")) {
                print_polygon("input", &in, floats);
                print_polygon("clipped", &out, floats);
            }
            if (!mapped && tolerated("clip_precision"))
                continue;
            CHECK_KNOWN("clip_precision", mapped, "vertex %d (%a, %a, %a, %a) left by the clipper is refused by the viewport",
                        i, v[SR_X], v[SR_Y], v[SR_Z], v[SR_W]);
            CHECK(isfinite(sv.inv_w) && sv.inv_w > 0.0f && isfinite(sv.z), "vertex %d (%a, %a, %a, %a) maps to 1/w = %a, z = %a",
                  i, v[SR_X], v[SR_Y], v[SR_Z], v[SR_W], sv.inv_w, sv.z);
        }
    }
    if (as_pipeline && exact)
        check_clip_area(&in, planes, &out, precision == SR_CLIP_ADAPTIVE ? SR_CLIP_DEFAULT_TOLERANCE : 0.0, &cfg.depth,
                        "clip");
}

/* ---- entry point -------------------------------------------------------- */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    reader r = { .data = data, .size = size };
    if ((take_u8(&r) & 3) == 3)
        fuzz_clip(&r);
    else
        fuzz_draw(&r);
    return 0;
}
