#include <float.h>
#include <math.h>
#include <string.h>

#include "01_vertex.h"
#include "01_vertex_lanes.h"
#include "03_classify.h"
#include "core/dmat4.h"

static void add_varying(sr_varying_layout *l, int *slot, int size)
{
    *slot = l->count;
    l->count += size;
}

sr_varying_layout sr_vertex_layout(sr_shade shade, const sr_mesh *mesh, bool textured)
{
    sr_varying_layout l = { .count = 0, .color = -1, .uv = -1, .normal = -1 };
    bool uv_albedo = textured && mesh->uvs;
    switch (shade) {
    case SR_SHADE_COLOR:
        add_varying(&l, &l.color, 3);
        break;
    case SR_SHADE_NORMAL:
        add_varying(&l, &l.normal, 3);
        break;
    case SR_SHADE_TEXTURE:
        add_varying(&l, &l.uv, 2);
        break;
    case SR_SHADE_LAMBERT:
        add_varying(&l, &l.normal, 3);
        if (uv_albedo)
            add_varying(&l, &l.uv, 2);
        else if (mesh->colors)
            add_varying(&l, &l.color, 3);
        break;
    default:
        break;
    }
    return l;
}

/* Normals go through the cofactor matrix of W's upper 3x3 (columns
 * a1×a2, a2×a0, a0×a1), which is det·(W⁻¹)ᵀ: the inverse transpose up to a
 * positive scale once multiplied by the sign of det, and finite even for a
 * singular W (a mesh flattened by a zero scale keeps its normals). The
 * vertex stage normalises. */
static void normal_matrix(const mat4 world, mat3 out)
{
    vec3 a[3];
    for (int c = 0; c < 3; c++)
        glm_vec3_copy((float *)world[c], a[c]);
    glm_vec3_cross(a[1], a[2], out[0]);
    glm_vec3_cross(a[2], a[0], out[1]);
    glm_vec3_cross(a[0], a[1], out[2]);
    if (glm_vec3_dot(a[0], out[0]) < 0.0f)
        glm_mat3_scale(out, -1.0f);
}

/* The largest component a normal may have for the normal matrix to keep
 * it finite: FLT_MAX over four times the largest row sum of |m|, so no
 * sum of products rounds past float range, and at most FLT_MAX, so an
 * infinite component is never within it; -1 (none) for a matrix with a
 * non-finite entry. */
static float normal_bound(const mat3 m)
{
    double largest = 0.0;
    for (int r = 0; r < 3; r++) {
        double row = fabs((double)m[0][r]) + fabs((double)m[1][r]) + fabs((double)m[2][r]);
        if (!isfinite(row))
            return -1.0f;
        largest = row > largest ? row : largest;
    }
    double bound = FLT_MAX / (4.0 * largest);
    return bound < FLT_MAX ? (float)bound : FLT_MAX;
}

void sr_vertex_make_transform_d(const sr_dmat4 *world, const sr_dmat4 *view, const sr_dmat4 *projection,
                                const double origin[3], sr_vertex_transform *xf)
{
    sr_dmat4 placed = sr_dmat4_translate(world, origin);
    sr_dmat4 vw = sr_dmat4_mul(view, &placed);
    xf->clip_from_object_d = sr_dmat4_mul(projection, &vw);
    sr_dmat4_to_mat4(&xf->clip_from_object_d, xf->clip_from_object);
    mat4 world_f;
    sr_dmat4_to_mat4(world, world_f);
    normal_matrix(world_f, xf->normal_matrix);
    xf->normal_bound = normal_bound(xf->normal_matrix);
}

void sr_vertex_make_transform(const mat4 world, const mat4 view, const mat4 projection,
                              sr_vertex_transform *xf)
{
    static const double no_origin[3];
    sr_dmat4 w = sr_dmat4_from_mat4(world), v = sr_dmat4_from_mat4(view), p = sr_dmat4_from_mat4(projection);
    sr_vertex_make_transform_d(&w, &v, &p, no_origin, xf);
}

static void copy_varying(float *dst, int slot, const float *src, int size)
{
    if (slot >= 0)
        memcpy(dst + SR_VARYINGS_AT + slot, src, (size_t)size * sizeof(float));
}

/* The position with w = 1, written as one 16-byte store where the compiler
 * has vector types: built by scalar stores, it reached the matrix product's
 * 16-byte load through a failed store forwarding, a stall on every
 * vertex. */
static inline void position_w1(const float *xyz, vec4 out)
{
#if defined(__GNUC__)
    typedef float four_floats __attribute__((vector_size(16)));
    four_floats p = { xyz[0], xyz[1], xyz[2], 1.0f };
    memcpy(out, &p, sizeof p);
#else
    glm_vec4((float *)xyz, 1.0f, out);
#endif
}


/* Vertex i's varyings into v, after its position. */
static SR_ALWAYS_INLINE void write_varyings(const sr_mesh *m, const sr_varying_layout *l, mat3 normal_matrix,
                                            uint32_t i, float *v)
{
    if (l->normal >= 0) {
        vec3 n;
        glm_mat3_mulv(normal_matrix, m->normals[i], n);
        glm_vec3_normalize(n);
        copy_varying(v, l->normal, n, 3);
    }
    if (l->uv >= 0)
        copy_varying(v, l->uv, m->uvs[i], 2);
    if (l->color >= 0)
        copy_varying(v, l->color, m->colors[i], 3);
}

#if defined(__SSE2__)
/* The vertices of [first, first + count) four at a time, as many as make
 * whole fours (returned), one lane each: the positions by coordinate, each
 * clip coordinate as cglm's product makes it, ((m3 + m2·z) + m1·y) + m0·x
 * with w = 1 (glm_mat4_mulv_sse2 with glmm_fmadd a multiply and an add), so
 * every lane is bit for bit the one-vertex loop's; then the four outcodes
 * at once (sr_clip_outcodes_four), and the varyings of those inside. One
 * at a time, the outcode's compares and bits were most of this loop's time
 * where most vertices carry no varyings (the inside scene): four lanes
 * share them (docs/performance.md, "The vertex phase"). */
static uint32_t run_fours_inside(const sr_mesh *m, const sr_varying_layout *l, mat4 clip_from_object,
                                 mat3 normal_matrix, const sr_clip_depth *d, uint32_t first, uint32_t count,
                                 sr_vertex_out *out, unsigned char *codes)
{
    __m128 column[4][4]; /* column[c][r]: clip_from_object[c][r] in every lane */
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            column[c][r] = _mm_set1_ps(clip_from_object[c][r]);
    uint32_t k = 0;
    for (; count - k >= 4; k += 4) {
        uint32_t i = first + k;
        if (k + SR_VERTEX_POSITIONS_AHEAD < count)
            __builtin_prefetch(m->positions[i + SR_VERTEX_POSITIONS_AHEAD]);
        /* x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3 into x, y and z by lane */
        const float *p = m->positions[i];
        __m128 a = _mm_loadu_ps(p), b = _mm_loadu_ps(p + 4), c = _mm_loadu_ps(p + 8);
        __m128 x1_y1 = _mm_shuffle_ps(a, b, _MM_SHUFFLE(0, 0, 3, 3));
        __m128 xy01 = _mm_shuffle_ps(a, x1_y1, _MM_SHUFFLE(2, 0, 1, 0));
        __m128 xy23 = _mm_shuffle_ps(b, c, _MM_SHUFFLE(2, 1, 3, 2));
        __m128 z01 = _mm_shuffle_ps(a, b, _MM_SHUFFLE(1, 1, 2, 2)), z23 = _mm_shuffle_ps(c, c, _MM_SHUFFLE(3, 3, 0, 0));
        __m128 x = _mm_shuffle_ps(xy01, xy23, _MM_SHUFFLE(2, 0, 2, 0));
        __m128 y = _mm_shuffle_ps(xy01, xy23, _MM_SHUFFLE(3, 1, 3, 1));
        __m128 z = _mm_shuffle_ps(z01, z23, _MM_SHUFFLE(2, 0, 2, 0));
        __m128 clip[4];
#pragma GCC unroll 4
        for (int r = 0; r < 4; r++)
            clip[r] = _mm_add_ps(_mm_add_ps(_mm_add_ps(column[3][r], _mm_mul_ps(column[2][r], z)),
                                            _mm_mul_ps(column[1][r], y)),
                                 _mm_mul_ps(column[0][r], x));
        uint32_t four = sr_clip_outcodes_four(clip, d);
        memcpy(codes + k, &four, sizeof four);
        __m128 v0 = clip[0], v1 = clip[1], v2 = clip[2], v3 = clip[3];
        _MM_TRANSPOSE4_PS(v0, v1, v2, v3);
        _mm_store_ps(out[k].v, v0);
        _mm_store_ps(out[k + 1].v, v1);
        _mm_store_ps(out[k + 2].v, v2);
        _mm_store_ps(out[k + 3].v, v3);
        for (int j = 0; l->count > 0 && j < 4; j++) /* none at all in id and depth shading */
            if (codes[k + j] == 0)
                write_varyings(m, l, normal_matrix, i + (uint32_t)j, out[k + j].v);
    }
    return k;
}
#endif

/* The mesh, the layout and the matrices are read into locals
 * first: the loop's float stores to out could alias them as far as the
 * compiler knows, and it would load them again for every vertex. With
 * codes, each position's outcode under *depth goes there, and only a
 * vertex inside every plane gets its varyings. Inlined into both callers,
 * so the one without codes tests none. */
static SR_ALWAYS_INLINE void run(const sr_mesh *mesh, const sr_vertex_transform *xf, const sr_varying_layout *layout,
                                 const sr_clip_depth *depth, bool avx2, uint32_t first, uint32_t count,
                                 sr_vertex_out *out, unsigned char *codes)
{
    const sr_mesh m = *mesh;
    const sr_varying_layout l = *layout;
    const sr_clip_depth d = depth ? *depth : (sr_clip_depth){ .on = false };
    CGLM_ALIGN_MAT mat4 clip_from_object;
    mat3 normal_matrix;
    glm_mat4_copy((vec4 *)xf->clip_from_object, clip_from_object);
    glm_mat3_copy((vec3 *)xf->normal_matrix, normal_matrix);
    uint32_t k = 0;
#if defined(__SSE2__)
    if (codes && !m.clip_positions) {
        if (avx2) {
            k = sr_vertex_eights_inside((const float(*)[3])(m.positions + first), (const float(*)[4])clip_from_object,
                                        &d, count, out, codes);
            for (uint32_t j = 0; l.count > 0 && j < k; j++)
                if (codes[j] == 0)
                    write_varyings(&m, &l, normal_matrix, first + j, out[j].v);
        }
        k += run_fours_inside(&m, &l, clip_from_object, normal_matrix, &d, first + k, count - k, out + k, codes + k);
    }
#else
    (void)avx2;
#endif
    for (; k < count; k++) {
        uint32_t i = first + k;
        float *v = out[k].v;
        if (m.clip_positions) {
            glm_vec4_copy(m.clip_positions[i], v);
        } else {
            if (codes && k + SR_VERTEX_POSITIONS_AHEAD < count)
                __builtin_prefetch(m.positions[i + SR_VERTEX_POSITIONS_AHEAD]);
            CGLM_ALIGN(16) vec4 p;
            position_w1(m.positions[i], p);
            glm_mat4_mulv(clip_from_object, p, v);
        }
        if (codes) {
            codes[k] = (unsigned char)sr_clip_outcode_with(v, &d);
            if (codes[k])
                continue;
        }
        write_varyings(&m, &l, normal_matrix, i, v);
    }
}

void sr_vertex_run(const sr_mesh *mesh, const sr_vertex_transform *xf, const sr_varying_layout *layout,
                   uint32_t first, uint32_t count, sr_vertex_out *out)
{
    run(mesh, xf, layout, NULL, false, first, count, out, NULL);
}

void sr_vertex_run_inside(const sr_mesh *mesh, const sr_vertex_transform *xf, const sr_varying_layout *layout,
                          const sr_clip_depth *depth, bool avx2, uint32_t first, uint32_t count, sr_vertex_out *out,
                          unsigned char *codes)
{
    run(mesh, xf, layout, depth, avx2, first, count, out, codes);
}

/* Whether |v[k]| <= bound for k < n (never for a NaN; with FLT_MAX, whether
 * all are finite), four at a time where the compiler has vector types. */
static bool all_within(const float *v, size_t n, float bound)
{
    size_t k = 0;
    bool within = true;
#if defined(__GNUC__)
    typedef float four_floats __attribute__((vector_size(16)));
    typedef int32_t four_ints __attribute__((vector_size(16)));
    const four_floats limit = { bound, bound, bound, bound };
    const four_ints magnitude = { INT32_MAX, INT32_MAX, INT32_MAX, INT32_MAX };
    four_ints all = ~(four_ints){ 0 };
    for (; n - k >= 4; k += 4) {
        four_floats x;
        memcpy(&x, v + k, sizeof x);
        x = (four_floats)((four_ints)x & magnitude);
        all &= (four_ints)(x <= limit);
    }
    within = (all[0] & all[1] & all[2] & all[3]) != 0;
#endif
    for (; k < n; k++)
        within = within && fabsf(v[k]) <= bound;
    return within;
}

/* A normal whose components lie within xf->normal_bound stays finite
 * through the normal matrix, and so through the normalisation (which keeps
 * a finite vector finite: a zero length gives zeros, an overflowed one
 * scales by 0). Others are transformed to see. */
bool sr_vertex_varyings_finite(const sr_mesh *mesh, const sr_vertex_transform *xf, const sr_varying_layout *l,
                               uint32_t i)
{
    if ((l->uv >= 0 && !all_within(mesh->uvs[i], 2, FLT_MAX)) ||
        (l->color >= 0 && !all_within(mesh->colors[i], 3, FLT_MAX)))
        return false;
    if (l->normal >= 0 && !all_within(mesh->normals[i], 3, xf->normal_bound)) {
        _Alignas(16) sr_vertex_out v;
        sr_vertex_run(mesh, xf, l, i, 1, &v);
        return all_within(v.v + SR_VARYINGS_AT + l->normal, 3, FLT_MAX);
    }
    return true;
}

bool sr_vertex_block_finite(const sr_mesh *mesh, const sr_vertex_transform *xf, const sr_varying_layout *l,
                            uint32_t first, uint32_t count)
{
    return (l->normal < 0 || all_within(mesh->normals[first], 3 * (size_t)count, xf->normal_bound)) &&
           (l->uv < 0 || all_within(mesh->uvs[first], 2 * (size_t)count, FLT_MAX)) &&
           (l->color < 0 || all_within(mesh->colors[first], 3 * (size_t)count, FLT_MAX));
}
