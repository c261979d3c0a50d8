/* lane_pixels_body.h — the body of the lane pixels (lane_pixels.h), one
 * source compiled twice like the sub-pixel lanes: with SSE2
 * (lane_pixels_sse2.c) and with AVX2 (lane_pixels_avx2.c, built with
 * -mavx2, never -mfma). Four lanes either way: vectors of four doubles are
 * two registers of SSE2, one of AVX2, the same operations.
 * The includer defines LANE_PIXELS, the name of the function it makes. */
#include <string.h>
#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "lane_pixels.h"
#include "triangle_setup.h"

#define LANES 4
/* Without AVX, gcc warns that a function returning four doubles would
 * pass them differently from a build with it; every such function here
 * is static and inlined, so no call between the two builds exists. */
#if !defined(__AVX__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
typedef int32_t lanes __attribute__((vector_size(LANES * sizeof(int32_t))));
/* Edge values, which may wrap in a lane whose result is not used (a
 * centre past its own box, in a group of larger boxes). */
typedef uint32_t ulanes __attribute__((vector_size(LANES * sizeof(uint32_t))));
typedef float flanes __attribute__((vector_size(LANES * sizeof(float))));
typedef double dlanes __attribute__((vector_size(LANES * sizeof(double))));
typedef int64_t dmask __attribute__((vector_size(LANES * sizeof(int64_t))));
#include "lane_boxes.h"

/* A group's triangles as the vertex phase mapped them: each vertex's
 * snapped point (inside every plane, so its coordinates fit 32 bits) and
 * the offsets its snap took off, and its depth. */
typedef struct group {
    lanes x[3], y[3];
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
        r->x[k] = (lanes){ (int32_t)v0->x, (int32_t)v1->x, (int32_t)v2->x, (int32_t)v3->x };
        r->y[k] = (lanes){ (int32_t)v0->y, (int32_t)v1->y, (int32_t)v2->y, (int32_t)v3->y };
        r->z[k] = (flanes){ v0->z, v1->z, v2->z, v3->z };
        r->off_x[k] = (flanes){ v0->x_off, v1->x_off, v2->x_off, v3->x_off };
        r->off_y[k] = (flanes){ v0->y_off, v1->y_off, v2->y_off, v3->y_off };
    }
}

/* pick on floats and doubles: a where m is all ones, b where it is 0. */
static SR_ALWAYS_INLINE flanes pick_f(lanes m, flanes a, flanes b)
{
    return (flanes)pick(m, (lanes)a, (lanes)b);
}

static SR_ALWAYS_INLINE dlanes pick_d(dmask m, dlanes a, dlanes b)
{
    return (dlanes)(((dmask)a & m) | ((dmask)b & ~m));
}

/* The largest lane, or 0. */
static SR_ALWAYS_INLINE int widest(lanes v)
{
    int most = 0;
    for (int l = 0; l < LANES; l++)
        most = v[l] > most ? v[l] : most;
    return most;
}

/* The conversions, one instruction each with AVX: gcc 12 builds the
 * generic ones lane by lane. */
static SR_ALWAYS_INLINE dlanes to_double(lanes v)
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

/* The index of each lane's lowest bit, below SR_LANE_PIXELS_CENTRES, from
 * the exponent of that bit as a float (exact: a power of two); any such
 * index where none is set. */
static SR_ALWAYS_INLINE lanes lowest_centre(lanes m)
{
    lanes exponent = (lanes)__builtin_convertvector(m & -m, flanes) >> 23;
    return (exponent - 127) & (SR_LANE_PIXELS_CENTRES - 1);
}

/* Each lane's pixel index: row · width + column, both >= 0. */
static SR_ALWAYS_INLINE void store_pixels(lanes x, lanes y, int width, size_t *at)
{
#if defined(__AVX2__)
    __m256i row = _mm256_mul_epu32(_mm256_cvtepu32_epi64((__m128i)y), _mm256_set1_epi64x(width));
    _mm256_storeu_si256((__m256i *)at, _mm256_add_epi64(row, _mm256_cvtepu32_epi64((__m128i)x)));
#else
    for (int l = 0; l < LANES; l++)
        at[l] = (size_t)y[l] * (size_t)width + (size_t)x[l];
#endif
}

/* Whether any lane is nonzero. */
static SR_ALWAYS_INLINE bool any_set(lanes v)
{
    lanes all = v;
    for (int l = 1; l < LANES; l++)
        all[0] |= v[l];
    return all[0] != 0;
}

/* Which centres of each box (box_x0, box_y0) wide × tall the clockwise
 * triangle (x0, y0) (x1, y1) (x2, y2) covers: the edges opposite vertices
 * 0, 1 and 2 at the box's first centre, stepped a pixel right and a row
 * down, as many as the group's largest box holds. */
static SR_ALWAYS_INLINE lanes centres_covered(lanes x0, lanes y0, lanes x1, lanes y1, lanes x2, lanes y2,
                                              lanes box_x0, lanes box_y0, lanes wide, lanes tall, int bits)
{
    const lanes zero = { 0 }, half = zero + ((int32_t)1 << bits) / 2;
    lanes cx = (lanes)(((ulanes)box_x0 << bits) + (ulanes)half), cy = (lanes)(((ulanes)box_y0 << bits) + (ulanes)half);
    ulanes e[3] = { (ulanes)edge_at(x1, y1, x2, y2, cx, cy), (ulanes)edge_at(x2, y2, x0, y0, cx, cy),
                    (ulanes)edge_at(x0, y0, x1, y1, cx, cy) };
    ulanes right[3] = { minus(y1, y2) << bits, minus(y2, y0) << bits, minus(y0, y1) << bits };
    ulanes down[3] = { minus(x2, x1) << bits, minus(x0, x2) << bits, minus(x1, x0) << bits };
    lanes covered = zero;
    int columns = widest(wide), rows = widest(tall);
    for (int j = 0; j < rows; j++) {
        lanes row = zero + j < tall;
        ulanes at[3] = { e[0], e[1], e[2] };
        for (int i = 0; i < columns; i++) {
            lanes inside = (lanes)(at[0] | at[1] | at[2]) >= zero;
            covered |= inside & row & (zero + i < wide) & (zero + (1 << (j * SR_SUBPIXEL_SPAN + i)));
            for (int k = 0; k < 3; k++)
                at[k] += right[k];
        }
        for (int k = 0; k < 3; k++)
            e[k] += down[k];
    }
    return covered;
}

/* A group's boxes and depth planes, as sr_lane_pixels holds them. */
typedef struct box_plane {
    dlanes z_ref, dz_row;
    flanes dz_pixel;
    lanes first_row, first_k, box_x0, box_y0;
} box_plane;

/* The pixel index and depth of centre c of each box, as sr_lane_pixel_at
 * and sr_lane_pixel_z find them. */
static SR_ALWAYS_INLINE void put_centre(const box_plane *b, lanes c, int width, size_t *at, float *depth)
{
    lanes row = (lanes)((ulanes)c / SR_SUBPIXEL_SPAN), column = (lanes)((ulanes)c % SR_SUBPIXEL_SPAN);
    flanes z_row = narrow(b->z_ref + b->dz_row * to_double(b->first_row + row));
    flanes z = z_row + b->dz_pixel * __builtin_convertvector(b->first_k + column, flanes);
    /* sr_depth_clamp: NaN to 0. */
    const flanes zero = { 0 }, one = zero + 1.0f;
    z = pick_f(z > zero, pick_f(z < one, z, one), zero);
    memcpy(depth, &z, sizeof z);
    store_pixels(b->box_x0 + column, b->box_y0 + row, width, at);
}

_Static_assert(SR_LANE_PIXELS_BATCH % LANES == 0, "a batch holds its last group's lanes");

void LANE_PIXELS(const char *screen, size_t stride, const uint32_t (*tri)[3], int n, uint64_t one_pixel, int bits,
                 sr_raster_rect rect, int width, sr_lane_pixels *out)
{
    const lanes zero_i = { 0 }, one_i = zero_i + ((int32_t)1 << bits), half_i = zero_i + ((int32_t)1 << bits) / 2;
    const dlanes zero = { 0 }, one = to_double(one_i);
    for (int g = 0; g < n; g += LANES) {
        group r;
        read_group(screen, stride, tri, g, n, &r);
        /* sr_cull_area2, and sr_order_clockwise: vertices 1 and 2 swapped
         * where it is negative (never 0: stage 7 drops those). */
        lanes area2 = (r.x[1] - r.x[0]) * (r.y[2] - r.y[0]) - (r.y[1] - r.y[0]) * (r.x[2] - r.x[0]);
        lanes cw = area2 > zero_i;
        lanes x1 = pick(cw, r.x[1], r.x[2]), y1 = pick(cw, r.y[1], r.y[2]);
        lanes x2 = pick(cw, r.x[2], r.x[1]), y2 = pick(cw, r.y[2], r.y[1]);
        flanes ox1 = pick_f(cw, r.off_x[1], r.off_x[2]), oy1 = pick_f(cw, r.off_y[1], r.off_y[2]);
        flanes ox2 = pick_f(cw, r.off_x[2], r.off_x[1]), oy2 = pick_f(cw, r.off_y[2], r.off_y[1]);
        flanes z1 = pick_f(cw, r.z[1], r.z[2]), z2 = pick_f(cw, r.z[2], r.z[1]);
        /* The scan box over rect. */
        lanes box_x0, box_x1, box_y0, box_y1;
        scan_span(min_of(min_of(r.x[0], x1), x2), max_of(max_of(r.x[0], x1), x2), bits, rect.x0, rect.x1, &box_x0,
                  &box_x1);
        scan_span(min_of(min_of(r.y[0], y1), y2), max_of(max_of(r.y[0], y1), y2), bits, rect.y0, rect.y1, &box_y0,
                  &box_y1);
        lanes ref_x = r.x[0] >> bits, ref_y = r.y[0] >> bits;
        /* sr_depth_plane: sr_plane_points unsnapped, and where the snap
         * turned a sliver over or grew it too much, the snapped points
         * (their differences plus 0, the same doubles); the reference
         * pixel is vertex 0's, and ref·one + half − x0 its low bits. */
        dlanes sx1 = to_double(x1 - r.x[0]), sy1 = to_double(y1 - r.y[0]), sx2 = to_double(x2 - r.x[0]),
               sy2 = to_double(y2 - r.y[0]), area = to_double(pick(cw, area2, -area2));
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
        dlanes z_ref = z0 + gx * ox + gy * oy, dz_row = gy * one;
        flanes dz_pixel = narrow(gx * one);
        lanes wide = box_x1 - box_x0, tall = box_y1 - box_y0;
        /* A group of one-pixel triangles covers its boxes' centres, those
         * within rect. */
        unsigned past_n = n - g >= LANES ? 0 : 0xfu << (n - g) & 0xfu;
        lanes covered = ((one_pixel >> g | past_n) & 0xfu) == 0xfu
                            ? (wide > zero_i) & (tall > zero_i) & (zero_i + 1)
                            : centres_covered(r.x[0], r.y[0], x1, y1, x2, y2, box_x0, box_y0, wide, tall, bits);
        /* A group past n stores lanes a batch has room for: g + LANES <= SR_LANE_PIXELS_BATCH. */
        lanes first_row = box_y0 - ref_y, first_k = box_x0 - ref_x;
        memcpy(&out->covered[g], &covered, sizeof covered);
        store_pixels(box_x0, box_y0, width, &out->corner[g]);
        memcpy(&out->first_row[g], &first_row, sizeof first_row);
        memcpy(&out->first_k[g], &first_k, sizeof first_k);
        memcpy(&out->z_ref[g], &z_ref, sizeof z_ref);
        memcpy(&out->dz_row[g], &dz_row, sizeof dz_row);
        memcpy(&out->dz_pixel[g], &dz_pixel, sizeof dz_pixel);
        /* The first two centres covered; where no lane covers two, the
         * first again, so that every value is set. */
        const box_plane b = { z_ref, dz_row, dz_pixel, first_row, first_k, box_x0, box_y0 };
        lanes second = covered & (covered - 1);
        put_centre(&b, lowest_centre(covered), width, &out->at[0][g], &out->z[0][g]);
        put_centre(&b, lowest_centre(any_set(second) ? second : covered), width, &out->at[1][g], &out->z[1][g]);
    }
}
