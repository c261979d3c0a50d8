/* one_pixel_body.h — the body of the one-pixel depths (one_pixel.h), one
 * source compiled twice like the sub-pixel lanes: with SSE2
 * (one_pixel_sse2.c) and with AVX2 (one_pixel_avx2.c, built with -mavx2,
 * never -mfma). Four lanes either way: vectors of four doubles are two
 * registers of SSE2, one of AVX2, the same operations.
 * The includer defines ONE_PIXEL_DEPTHS, the name of the function it
 * makes. */
#include <string.h>
#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "one_pixel.h"
#include "triangle_setup.h"

#define LANES 4
/* Without AVX, gcc warns that a function returning four doubles would
 * pass them differently from a build with it; every such function here
 * is static and inlined, so no call between the two builds exists. */
#if !defined(__AVX__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
typedef int32_t ilanes __attribute__((vector_size(LANES * sizeof(int32_t))));
typedef float flanes __attribute__((vector_size(LANES * sizeof(float))));
typedef double dlanes __attribute__((vector_size(LANES * sizeof(double))));
typedef int64_t dmask __attribute__((vector_size(LANES * sizeof(int64_t))));

/* A group's triangles as the vertex phase mapped them: each vertex's
 * snapped point (inside every plane, so its coordinates fit 32 bits) and
 * the offsets its snap took off, and its depth. */
typedef struct group {
    ilanes x[3], y[3];
    flanes off_x[3], off_y[3], z[3];
} group;

/* Lane l holds triangle g + l, or the last one, n − 1, past it. Each
 * vector is put together from scalar loads: AVX2's gathers took longer
 * (perf), and scalar stores read back as a vector stall. */
static SR_ALWAYS_INLINE void read_group(const char *screen, size_t stride, const uint32_t (*tri)[3], int g, int n,
                                        group *r)
{
    const uint32_t *t0 = tri[g], *t1 = tri[g + 1 < n ? g + 1 : n - 1], *t2 = tri[g + 2 < n ? g + 2 : n - 1],
                   *t3 = tri[g + 3 < n ? g + 3 : n - 1];
    for (int k = 0; k < 3; k++) {
        const sr_screen_vertex *v0 = (const sr_screen_vertex *)(screen + t0[k] * stride),
                               *v1 = (const sr_screen_vertex *)(screen + t1[k] * stride),
                               *v2 = (const sr_screen_vertex *)(screen + t2[k] * stride),
                               *v3 = (const sr_screen_vertex *)(screen + t3[k] * stride);
        r->x[k] = (ilanes){ (int32_t)v0->x, (int32_t)v1->x, (int32_t)v2->x, (int32_t)v3->x };
        r->y[k] = (ilanes){ (int32_t)v0->y, (int32_t)v1->y, (int32_t)v2->y, (int32_t)v3->y };
        r->z[k] = (flanes){ v0->z, v1->z, v2->z, v3->z };
        r->off_x[k] = (flanes){ v0->x_off, v1->x_off, v2->x_off, v3->x_off };
        r->off_y[k] = (flanes){ v0->y_off, v1->y_off, v2->y_off, v3->y_off };
    }
}

/* a where m is all ones, b where it is 0. */
static SR_ALWAYS_INLINE ilanes pick_i(ilanes m, ilanes a, ilanes b)
{
    return (a & m) | (b & ~m);
}

static SR_ALWAYS_INLINE flanes pick_f(ilanes m, flanes a, flanes b)
{
    return (flanes)pick_i(m, (ilanes)a, (ilanes)b);
}

static SR_ALWAYS_INLINE dlanes pick_d(dmask m, dlanes a, dlanes b)
{
    return (dlanes)(((dmask)a & m) | ((dmask)b & ~m));
}

static SR_ALWAYS_INLINE ilanes min_i(ilanes a, ilanes b)
{
    return pick_i(a < b, a, b);
}

/* The conversions, one instruction each with AVX: gcc 12 builds the
 * generic ones lane by lane. */
static SR_ALWAYS_INLINE dlanes to_double(ilanes v)
{
#if defined(__AVX__)
    return (dlanes)_mm256_cvtepi32_pd((__m128i)v);
#else
    return __builtin_convertvector(v, dlanes);
#endif
}

static SR_ALWAYS_INLINE dlanes widen(flanes v)
{
#if defined(__AVX__)
    return (dlanes)_mm256_cvtps_pd((__m128)v);
#else
    return __builtin_convertvector(v, dlanes);
#endif
}

static SR_ALWAYS_INLINE flanes narrow(dlanes v)
{
#if defined(__AVX__)
    return (flanes)_mm256_cvtpd_ps((__m256d)v);
#else
    return __builtin_convertvector(v, flanes);
#endif
}

/* Each lane's pixel: row · width + column where inside, else
 * SR_ONE_PIXEL_OUTSIDE (all ones). The columns and rows are >= 0. */
static SR_ALWAYS_INLINE void store_pixels(ilanes x, ilanes y, ilanes inside, int width, size_t *at)
{
#if defined(__AVX2__)
    __m256i row = _mm256_mul_epu32(_mm256_cvtepu32_epi64((__m128i)y), _mm256_set1_epi64x(width));
    __m256i pixel = _mm256_add_epi64(row, _mm256_cvtepu32_epi64((__m128i)x));
    pixel = _mm256_or_si256(pixel, _mm256_xor_si256(_mm256_cvtepi32_epi64((__m128i)inside), _mm256_set1_epi64x(-1)));
    _mm256_storeu_si256((__m256i *)at, pixel);
#else
    for (int l = 0; l < LANES; l++)
        at[l] = inside[l] ? (size_t)y[l] * (size_t)width + (size_t)x[l] : SR_ONE_PIXEL_OUTSIDE;
#endif
}

_Static_assert(SR_ONE_PIXEL_BATCH % LANES == 0, "a batch holds its last group's lanes");

void ONE_PIXEL_DEPTHS(const char *screen, size_t stride, const uint32_t (*tri)[3], int n, int bits,
                      sr_raster_rect rect, int width, sr_one_pixels *out)
{
    const ilanes zero_i = { 0 }, one_i = zero_i + ((int32_t)1 << bits), half_i = zero_i + ((int32_t)1 << bits) / 2;
    const dlanes zero = { 0 }, one = to_double(one_i);
    for (int g = 0; g < n; g += LANES) {
        group r;
        read_group(screen, stride, tri, g, n, &r);
        /* sr_cull_area2, and sr_order_clockwise: vertices 1 and 2 swapped
         * where it is negative (never 0: stage 7 drops those). */
        ilanes area2 = (r.x[1] - r.x[0]) * (r.y[2] - r.y[0]) - (r.y[1] - r.y[0]) * (r.x[2] - r.x[0]);
        ilanes cw = area2 > zero_i;
        ilanes x1 = pick_i(cw, r.x[1], r.x[2]), y1 = pick_i(cw, r.y[1], r.y[2]);
        ilanes x2 = pick_i(cw, r.x[2], r.x[1]), y2 = pick_i(cw, r.y[2], r.y[1]);
        flanes ox1 = pick_f(cw, r.off_x[1], r.off_x[2]), oy1 = pick_f(cw, r.off_y[1], r.off_y[2]);
        flanes ox2 = pick_f(cw, r.off_x[2], r.off_x[1]), oy2 = pick_f(cw, r.off_y[2], r.off_y[1]);
        flanes z1 = pick_f(cw, r.z[1], r.z[2]), z2 = pick_f(cw, r.z[2], r.z[1]);
        /* sr_one_pixel_box's corner, and the reference pixel of
         * sr_depth_plane (vertex 0's); ref·one + half − x0 as its low bits
         * give it. */
        ilanes box_x = (min_i(min_i(r.x[0], r.x[1]), r.x[2]) - half_i + one_i - 1) >> bits,
               box_y = (min_i(min_i(r.y[0], r.y[1]), r.y[2]) - half_i + one_i - 1) >> bits;
        box_x = pick_i(box_x > zero_i, box_x, zero_i), box_y = pick_i(box_y > zero_i, box_y, zero_i);
        ilanes ref_x = r.x[0] >> bits, ref_y = r.y[0] >> bits;
        /* sr_depth_plane: sr_plane_points unsnapped, and where the snap
         * turned a sliver over or grew it too much, the snapped points
         * (their differences plus 0, the same doubles). */
        dlanes sx1 = to_double(x1 - r.x[0]), sy1 = to_double(y1 - r.y[0]), sx2 = to_double(x2 - r.x[0]),
               sy2 = to_double(y2 - r.y[0]), area = to_double(pick_i(cw, area2, -area2));
        dlanes p0x = zero + widen(r.off_x[0]), p0y = zero + widen(r.off_y[0]);
        dlanes px1 = (sx1 + widen(ox1)) - p0x, py1 = (sy1 + widen(oy1)) - p0y, px2 = (sx2 + widen(ox2)) - p0x,
               py2 = (sy2 + widen(oy2)) - p0y;
        dlanes det = px1 * py2 - px2 * py1;
        dmask unsnapped = det * SR_SLIVER_GROWTH >= area;
        px1 = pick_d(unsnapped, px1, sx1), py1 = pick_d(unsnapped, py1, sy1);
        px2 = pick_d(unsnapped, px2, sx2), py2 = pick_d(unsnapped, py2, sy2);
        det = pick_d(unsnapped, det, area);
        p0x = pick_d(unsnapped, p0x, zero), p0y = pick_d(unsnapped, p0y, zero);
        dlanes z0 = widen(r.z[0]), dz1 = widen(z1) - z0, dz2 = widen(z2) - z0;
        dlanes inv_both = 1.0 / (det * area), inv_det = area * inv_both;
        dlanes gx = (dz1 * py2 - dz2 * py1) * inv_det, gy = (dz2 * px1 - dz1 * px2) * inv_det;
        dlanes ox = to_double(half_i - (r.x[0] & (one_i - 1))) - p0x,
               oy = to_double(half_i - (r.y[0] & (one_i - 1))) - p0y;
        dlanes z_ref = z0 + gx * ox + gy * oy, dz_row = gy * one, dz_pixel = gx * one;
        /* sr_row_z at the pixel's row, then sr_depth_at k pixels along it. */
        flanes z_row = narrow(z_ref + dz_row * to_double(box_y - ref_y));
        flanes z = z_row + narrow(dz_pixel) * __builtin_convertvector(box_x - ref_x, flanes);
        /* sr_depth_clamp: NaN to 0. */
        const flanes zero_f = { 0 }, one_f = zero_f + 1.0f;
        z = pick_f(z > zero_f, pick_f(z < one_f, z, one_f), zero_f);
        memcpy(&out->z[g], &z, sizeof z);
        /* A group past n stores lanes a batch has room for: g + LANES <= SR_ONE_PIXEL_BATCH. */
        ilanes inside = (box_x >= rect.x0) & (box_x < rect.x1) & (box_y >= rect.y0) & (box_y < rect.y1);
        store_pixels(box_x, box_y, inside, width, &out->at[g]);
    }
}
