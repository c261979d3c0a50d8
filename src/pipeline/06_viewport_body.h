/* 06_viewport_body.h — the body of the float half's lanes
 * (06_viewport_lanes.h), one source compiled at two widths like the
 * sub-pixel lanes: two lanes of double with SSE2 (06_viewport_sse2.c) and
 * four with AVX2 (06_viewport_avx2.c, built with -mavx2, never -mfma). The
 * includer defines VIEWPORT_LANES, and VIEWPORT_FLOAT_LANES and
 * VIEWPORT_DOUBLE_LANES, the names of the functions it makes. Each lane
 * takes 06_viewport.c's map_float or map_double steps on the same values
 * (a float made double, one division each for 1/w and b/w, the same
 * products and sums in the same order), so every width maps the bits of
 * the scalar map. */
#include <math.h>
#include <string.h>
#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "pipeline/03_classify.h"
#include "06_viewport_lanes.h"

typedef double dlanes __attribute__((vector_size(VIEWPORT_LANES * sizeof(double))));
typedef int64_t ilanes __attribute__((vector_size(VIEWPORT_LANES * sizeof(int64_t))));
typedef float flanes __attribute__((vector_size(VIEWPORT_LANES * sizeof(float))));
typedef int32_t fmask __attribute__((vector_size(VIEWPORT_LANES * sizeof(int32_t))));

/* All ones in the lanes where lo <= v <= hi (never for a NaN). */
static SR_ALWAYS_INLINE ilanes within(dlanes v, double lo, double hi)
{
    return (v >= lo) & (v <= hi);
}

/* All ones in the lanes whose value is finite (not inf, not NaN). */
static SR_ALWAYS_INLINE ilanes finite_d(dlanes v)
{
    return (dlanes)((ilanes)v & INT64_MAX) < INFINITY;
}

static SR_ALWAYS_INLINE fmask finite_f(flanes v)
{
    return (flanes)((fmask)v & INT32_MAX) < INFINITY;
}

/* Bit k set where lane k is all ones. */
static SR_ALWAYS_INLINE unsigned lane_bits(ilanes m)
{
#if VIEWPORT_LANES == 4 && defined(__AVX__)
    return (unsigned)_mm256_movemask_pd((__m256d)m);
#elif VIEWPORT_LANES == 2 && defined(__SSE2__)
    return (unsigned)_mm_movemask_pd((__m128d)m);
#else
    unsigned bits = 0;
    for (int k = 0; k < VIEWPORT_LANES; k++)
        bits |= (unsigned)(m[k] & 1) << k;
    return bits;
#endif
}

/* 06_viewport.c's round_to_integer in lanes of |v| < 2^51: v + 1.5·2^52
 * has an exponent of 52, so its bits less those of 1.5·2^52 are the
 * integer. */
static SR_ALWAYS_INLINE ilanes round_to_integers(dlanes v)
{
    const double no_fraction = 6755399441055744.0;
    ilanes magic;
    dlanes m = (dlanes){ 0 } + no_fraction;
    memcpy(&magic, &m, sizeof magic);
    return (ilanes)(v + no_fraction) - magic;
}

typedef float four_floats __attribute__((vector_size(4 * sizeof(float))));

/* The positions of v[0 .. VIEWPORT_LANES) by coordinate, from whole loads
 * and shuffles: lanes filled one at a time went through the stack, and a
 * whole load of lanes stored one by one waits on a failed store
 * forwarding. */
static SR_ALWAYS_INLINE void load_positions(const sr_vertex_out *v, dlanes *x, dlanes *y, dlanes *z, dlanes *w)
{
    four_floats r[VIEWPORT_LANES];
    for (int k = 0; k < VIEWPORT_LANES; k++)
        memcpy(&r[k], v[k].v, sizeof r[k]);
#if VIEWPORT_LANES == 4
    four_floats xy01 = __builtin_shufflevector(r[0], r[1], 0, 4, 1, 5), xy23 = __builtin_shufflevector(r[2], r[3], 0, 4, 1, 5);
    four_floats zw01 = __builtin_shufflevector(r[0], r[1], 2, 6, 3, 7), zw23 = __builtin_shufflevector(r[2], r[3], 2, 6, 3, 7);
    *x = __builtin_convertvector(__builtin_shufflevector(xy01, xy23, 0, 1, 4, 5), dlanes);
    *y = __builtin_convertvector(__builtin_shufflevector(xy01, xy23, 2, 3, 6, 7), dlanes);
    *z = __builtin_convertvector(__builtin_shufflevector(zw01, zw23, 0, 1, 4, 5), dlanes);
    *w = __builtin_convertvector(__builtin_shufflevector(zw01, zw23, 2, 3, 6, 7), dlanes);
#else
    four_floats xy = __builtin_shufflevector(r[0], r[1], 0, 4, 1, 5), zw = __builtin_shufflevector(r[0], r[1], 2, 6, 3, 7);
    *x = __builtin_convertvector(__builtin_shufflevector(xy, xy, 0, 1), dlanes);
    *y = __builtin_convertvector(__builtin_shufflevector(xy, xy, 2, 3), dlanes);
    *z = __builtin_convertvector(__builtin_shufflevector(zw, zw, 0, 1), dlanes);
    *w = __builtin_convertvector(__builtin_shufflevector(zw, zw, 2, 3), dlanes);
#endif
}

/* Each lane's snapped point (x, y) into its screen vertex as one 16-byte
 * store, from a shuffle of the two: through the bytes of one vector, the
 * pairs went through the stack. */
typedef int64_t two_int64 __attribute__((vector_size(2 * sizeof(int64_t))));
#define STORE_POINT(k)                                                                                         \
    do {                                                                                                       \
        two_int64 point_ = __builtin_shufflevector(sx, sy, k, (k) + VIEWPORT_LANES);                           \
        memcpy(&((sr_screen_vertex *)(out + (size_t)(k)*stride))->x, &point_, sizeof point_);                 \
    } while (0)

static SR_ALWAYS_INLINE void store_points(ilanes sx, ilanes sy, char *out, size_t stride)
{
    STORE_POINT(0);
    STORE_POINT(1);
#if VIEWPORT_LANES == 4
    STORE_POINT(2);
    STORE_POINT(3);
#endif
}

/* The snapped points of the lanes into points[0 .. VIEWPORT_LANES):
 * where `kept` is all ones, x low and y high; elsewhere SR_SNAPPED_OUTSIDE. */
static SR_ALWAYS_INLINE void store_snapped(ilanes sx, ilanes sy, ilanes kept, sr_snapped_point *points)
{
    typedef uint64_t ulanes __attribute__((vector_size(VIEWPORT_LANES * sizeof(uint64_t))));
    ilanes packed = (ilanes)(((ulanes)sx & 0xffffffffu) | ((ulanes)sy << 32));
    ilanes outside = (ilanes){ 0 } + (int64_t)SR_SNAPPED_OUTSIDE;
    ilanes p = (packed & kept) | (outside & ~kept);
    memcpy(points, &p, sizeof p);
}

/* All ones in lane k where bit k of bits is set. */
static SR_ALWAYS_INLINE ilanes lanes_of_bits(unsigned bits)
{
    ilanes m = { 0 };
    for (int k = 0; k < VIEWPORT_LANES; k++)
        m[k] = -(int64_t)((bits >> k) & 1);
    return m;
}

/* The float half of v[0 .. VIEWPORT_LANES) into the screen vertices stride
 * bytes apart from out: the mapped lanes' bits. A refused lane's screen
 * vertex is written all the same; nothing reads it. With points, the
 * snapped points of the lanes in `inside` that map (store_snapped). */
static SR_ALWAYS_INLINE unsigned map_group(const sr_vertex_out *v, int varyings, const sr_viewport_lanes *r,
                                           char *out, size_t stride, unsigned inside, sr_snapped_point *points)
{
    dlanes x, y, z, w;
    load_positions(v, &x, &y, &z, &w);
    ilanes ok = (w > 0.0) & finite_d(w);
    dlanes inv_w = 1.0 / w, b_over_w = r->b / w;
    x *= inv_w;
    y *= inv_w;
    z = r->depth_on ? r->a + b_over_w : z * inv_w;
    ok &= within(x, r->xy_lo, r->hi) & within(y, r->xy_lo, r->hi) & within(z, r->z_lo, r->hi);
    ilanes sx = round_to_integers((r->guard * x + 1.0) * r->x_units),
           sy = round_to_integers((1.0 - r->guard * y) * r->y_units);
    store_points(sx, sy, out, stride);
    flanes inv_w_f = __builtin_convertvector(inv_w, flanes);
    fmask finite = finite_f(inv_w_f);
#pragma GCC unroll 4
    for (int k = 0; k < VIEWPORT_LANES; k++)
        ((sr_screen_vertex *)(out + (size_t)k * stride))->inv_w = inv_w_f[k];
    for (int i = 0; i < varyings; i++) {
        dlanes var = { 0 };
#pragma GCC unroll 4
        for (int k = 0; k < VIEWPORT_LANES; k++)
            var[k] = v[k].v[SR_VARYINGS_AT + i];
        flanes var_w = __builtin_convertvector(var * inv_w, flanes);
        finite &= finite_f(var_w);
#pragma GCC unroll 4
        for (int k = 0; k < VIEWPORT_LANES; k++)
            ((sr_screen_vertex *)(out + (size_t)k * stride))->var_w[i] = var_w[k];
    }
    ok &= __builtin_convertvector(finite, ilanes);
    if (points) /* most groups are inside whole */
        store_snapped(sx, sy, inside == (1u << VIEWPORT_LANES) - 1 ? ok : ok & lanes_of_bits(inside), points);
    return lane_bits(ok);
}

uint32_t VIEWPORT_FLOAT_LANES(const sr_vertex_out *v, uint32_t n, int varyings, const sr_viewport_lanes *r,
                              unsigned char *codes, void *out, size_t stride, sr_snapped_point *points)
{
    uint32_t k = 0;
    for (; n - k >= VIEWPORT_LANES; k += VIEWPORT_LANES) {
        unsigned inside = 0;
        for (uint32_t j = 0; j < VIEWPORT_LANES; j++)
            inside |= (unsigned)(codes[k + j] == 0) << j;
        if (!inside) {
            for (uint32_t j = 0; points && j < VIEWPORT_LANES; j++)
                points[k + j] = SR_SNAPPED_OUTSIDE;
            continue;
        }
        unsigned refused = inside & ~map_group(&v[k], varyings, r, (char *)out + k * stride, stride, inside,
                                               points ? points + k : NULL);
        for (; refused; refused &= refused - 1)
            codes[k + (uint32_t)__builtin_ctz(refused)] = SR_OUT_NONFINITE;
    }
    return k;
}

/* The double half of the mesh vertices index[0 .. n), rounded down to
 * whole groups of lanes (returned): each lane's clip position in double as
 * sr_vertex_clip_d makes it (((m0·x + m1·y) + m2·z) + m3, row by row),
 * then 06_viewport.c's map_double, unchecked, and place, into the screen
 * vertex index[k]·stride bytes into screen, whose snapped point the float
 * half wrote. */
uint32_t VIEWPORT_DOUBLE_LANES(const float (*positions)[3], const double m[4][4], const uint32_t *index, uint32_t n,
                               const sr_viewport_lanes *r, char *screen, size_t stride)
{
    uint32_t k = 0;
    for (; n - k >= VIEWPORT_LANES; k += VIEWPORT_LANES) {
        const float *p[VIEWPORT_LANES];
        sr_screen_vertex *o[VIEWPORT_LANES];
        for (int j = 0; j < VIEWPORT_LANES; j++) {
            p[j] = positions[index[k + (uint32_t)j]];
            o[j] = (sr_screen_vertex *)(screen + (size_t)index[k + (uint32_t)j] * stride);
        }
#if VIEWPORT_LANES == 4
        dlanes px = { p[0][0], p[1][0], p[2][0], p[3][0] }, py = { p[0][1], p[1][1], p[2][1], p[3][1] },
               pz = { p[0][2], p[1][2], p[2][2], p[3][2] };
        dlanes snapped_x = { (double)o[0]->x, (double)o[1]->x, (double)o[2]->x, (double)o[3]->x },
               snapped_y = { (double)o[0]->y, (double)o[1]->y, (double)o[2]->y, (double)o[3]->y };
#else
        dlanes px = { p[0][0], p[1][0] }, py = { p[0][1], p[1][1] }, pz = { p[0][2], p[1][2] };
        dlanes snapped_x = { (double)o[0]->x, (double)o[1]->x }, snapped_y = { (double)o[0]->y, (double)o[1]->y };
#endif
        dlanes c[4];
        for (int row = 0; row < 4; row++)
            c[row] = m[0][row] * px + m[1][row] * py + m[2][row] * pz + m[3][row];
        dlanes inv_w = 1.0 / c[SR_W], b_over_w = r->b / c[SR_W];
        dlanes x = c[SR_X] * inv_w, y = c[SR_Y] * inv_w;
        dlanes z = r->depth_on ? r->a + b_over_w : c[SR_Z] * inv_w;
        flanes x_off = __builtin_convertvector((r->guard * x + 1.0) * r->x_units - snapped_x, flanes),
               y_off = __builtin_convertvector((1.0 - r->guard * y) * r->y_units - snapped_y, flanes),
               z_f = __builtin_convertvector(z, flanes);
#pragma GCC unroll 4
        for (int j = 0; j < VIEWPORT_LANES; j++) {
            o[j]->x_off = x_off[j];
            o[j]->y_off = y_off[j];
            o[j]->z = z_f[j];
        }
    }
    return k;
}
