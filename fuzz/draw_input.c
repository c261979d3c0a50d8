/* fuzz/draw_input.c — decoding the fuzzer's bytes: the reader, special
 * floats, matrices, the scene (see fuzz_draw.c for the format). */
#include "fuzz_draw.h"

/* A finding already reported and waiting for a fix in src/ can be let
 * through by naming its tag in FUZZ_TOLERATE (comma-separated), so a long run
 * keeps looking for new ones; see fuzz/README.md for the tags. */
bool tolerated(const char *tag)
{
    const char *list = getenv("FUZZ_TOLERATE");
    size_t n = strlen(tag);
    for (const char *at = list; at && (at = strstr(at, tag)); at += n)
        if ((at == list || at[-1] == ',') && (at[n] == '\0' || at[n] == ','))
            return true;
    return false;
}


/* ---- decoding ---------------------------------------------------------- */


uint8_t take_u8(reader *r)
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

float take_finite_float(reader *r)
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

/* By value, as sr_draw tests it (core/dmat4.c): -0 is zero too. */
bool matrix_is_zero(const mat4 m)
{
    for (int c = 0; c < 4; c++)
        for (int k = 0; k < 4; k++)
            if (m[c][k] != 0.0f)
                return false;
    return true;
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

bool scene_decode(reader *r, scene *sc)
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
    sc->chunk_slots = t >> 5;
    return true;
}

void scene_free(scene *sc)
{
    sr_mesh_free(&sc->mesh);
    free(sc->texture.texels);
}

uint32_t slot_count(const sr_mesh *m)
{
    if (m->topology == SR_TRIANGLE_STRIP)
        return m->index_count >= 3 ? m->index_count - 2 : 0;
    return m->index_count / 3;
}

/* Triangle k's vertex indices as DESIGN.md defines assembly (odd strip
 * triangles swap their last two); false if degenerate. */
bool slot_triangle(const sr_mesh *m, uint32_t k, uint32_t t[3])
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

bool position_finite(const sr_mesh *m, uint32_t i)
{
    return isfinite(m->positions[i][0]) && isfinite(m->positions[i][1]) && isfinite(m->positions[i][2]);
}

/* What the header promises sr_draw accepts: in-range indices and the inputs
 * the shading mode reads. */
bool draw_should_succeed(const scene *sc, sr_shade shade)
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

/* Stage 6 as the draw runs it by default: 1/256 pixel, no guard band, z
 * from the projection's depth model (NULL: none). */
bool map_vertex(const sr_vertex_out *v, int varyings, int width, int height, const sr_clip_depth *depth,
                       sr_screen_vertex *out)
{
    sr_viewport vp = { .width = width, .height = height, .subpixel_bits = SR_SUBPIXEL_BITS, .guard = 1.0f,
                       .depth = depth ? *depth : (sr_clip_depth){ .on = false } };
    return sr_viewport_map(v, varyings, &vp, out);
}
