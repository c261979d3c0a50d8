/* subpixel_body.h — the body of the sub-pixel lanes (subpixel.h), one
 * source compiled at three widths like the span kernels: four lanes of SSE2
 * (subpixel_sse2.c), eight of AVX2 (subpixel_avx2.c, built with -mavx2) and
 * sixteen of AVX-512 (subpixel_avx512.c). The
 * includer defines SUBPIXEL_LANES and SUBPIXEL_GROUPS, the name of the
 * function it makes: sr_subpixel_verdict SUBPIXEL_GROUPS(const
 * sr_subpixel_batch *, int n, const sr_subpixel_rules *). Every width
 * computes the same exact integers, so the same verdicts. */
#include <string.h>
#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "pipeline/stages.h"
#include "subpixel_lanes.h"

typedef int32_t lanes __attribute__((vector_size(SUBPIXEL_LANES * sizeof(int32_t))));
/* Products and their sums, which may wrap in a lane whose result is not
 * used (a triangle too large for the lanes, or a box with no centre to
 * test): unsigned, whose wrap is defined. Every other value is a
 * difference of coordinates below 2^30, or of pixel indices. */
typedef uint32_t ulanes __attribute__((vector_size(SUBPIXEL_LANES * sizeof(uint32_t))));
#include "lane_boxes.h"

static SR_ALWAYS_INLINE lanes load(const int32_t *p)
{
    lanes v;
    memcpy(&v, p, sizeof v);
    return v;
}

/* Bit i set where lane i of m is all ones. */
static SR_ALWAYS_INLINE uint64_t lane_bits(lanes m)
{
#if defined(__AVX512F__) && SUBPIXEL_LANES == 16
    return (uint64_t)_mm512_movepi32_mask((__m512i)m);
#elif defined(__AVX2__) && SUBPIXEL_LANES == 8
    return (uint64_t)_mm256_movemask_ps((__m256)m);
#elif defined(__SSE2__) && SUBPIXEL_LANES == 4
    return (uint64_t)_mm_movemask_ps((__m128)m);
#else
    uint64_t bits = 0;
    for (int i = 0; i < SUBPIXEL_LANES; i++)
        bits |= (uint64_t)(m[i] & 1) << i;
    return bits;
#endif
}

/* The verdicts of the triangles (x0, y0) (x1, y1) (x2, y2), one a lane. */
static SR_ALWAYS_INLINE sr_subpixel_verdict verdict_of(lanes x0, lanes y0, lanes x1, lanes y1, lanes x2, lanes y2,
                                                       const sr_subpixel_rules *r)
{
    const lanes zero = { 0 };
    int bits = r->bits;
    lanes half = zero + ((int32_t)1 << bits) / 2;
    lanes lo_x = min_of(min_of(x0, x1), x2), hi_x = max_of(max_of(x0, x1), x2);
    lanes lo_y = min_of(min_of(y0, y1), y2), hi_y = max_of(max_of(y0, y1), y2);
    /* Within SR_SUBPIXEL_SPAN pixels on each axis: the lanes below hold
     * every value exactly. */
    lanes span = zero + (SR_SUBPIXEL_SPAN << bits);
    lanes small = (hi_x - lo_x < span) & (hi_y - lo_y < span);
    /* The scan box over the framebuffer. */
    lanes box_x0, box_x1, box_y0, box_y1;
    scan_span(lo_x, hi_x, bits, 0, r->width, &box_x0, &box_x1);
    scan_span(lo_y, hi_y, bits, 0, r->height, &box_y0, &box_y1);
    lanes empty = (box_x0 >= box_x1) | (box_y0 >= box_y1);
    lanes one_centre = (box_x1 - box_x0 == 1) & (box_y1 - box_y0 == 1);
    /* Stage 7's area and verdict (07_cull.h). */
    lanes area2 = (lanes)(minus(x1, x0) * minus(y2, y0) - minus(y1, y0) * minus(x2, x0));
    lanes cw = area2 > zero;
    lanes keeps = (cw & (zero - (int32_t)r->keep_cw)) | ((area2 < zero) & (zero - (int32_t)r->keep_ccw));
    /* The box's one centre against the three edges, of the triangle in
     * clockwise order as the set-up orders it (vertices 1 and 2 swapped
     * where the area is negative). */
    lanes cx = (lanes)(((ulanes)box_x0 << bits) + (ulanes)half), cy = (lanes)(((ulanes)box_y0 << bits) + (ulanes)half);
    lanes sx1 = pick(cw, x1, x2), sy1 = pick(cw, y1, y2), sx2 = pick(cw, x2, x1), sy2 = pick(cw, y2, y1);
    lanes outside = (edge_at(x0, y0, sx1, sy1, cx, cy) | edge_at(sx1, sy1, sx2, sy2, cx, cy) |
                     edge_at(sx2, sy2, x0, y0, cx, cy)) < zero;
    lanes misses = empty | (one_centre & outside);
    return (sr_subpixel_verdict){ .culled = lane_bits(small & ~keeps),
                                  .drawn = lane_bits(small & keeps & misses),
                                  .one_pixel = lane_bits(small & keeps & one_centre & ~outside),
                                  .small_box = lane_bits(small & keeps & ~empty & ~one_centre) };
}

sr_subpixel_verdict SUBPIXEL_GROUPS(const sr_subpixel_batch *b, int n, const sr_subpixel_rules *rules)
{
    sr_subpixel_verdict v = { 0, 0, 0, 0 };
    for (int at = 0; at < n; at += SUBPIXEL_LANES) {
        sr_subpixel_verdict g = verdict_of(load(b->x[0] + at), load(b->y[0] + at), load(b->x[1] + at),
                                           load(b->y[1] + at), load(b->x[2] + at), load(b->y[2] + at), rules);
        v.culled |= g.culled << at;
        v.drawn |= g.drawn << at;
        v.one_pixel |= g.one_pixel << at;
        v.small_box |= g.small_box << at;
    }
    return v;
}

#if SUBPIXEL_LANES == 8 && defined(__AVX2__)
/* Lane i from a where bit i of the blend is clear, from b where set. */
#define BLEND(a, b, bits) _mm256_blend_epi32((a), (b), (bits))

/* The x and the y of the points of the eight slots whose corner indices
 * are i, in the order 0 1 4 5 2 3 6 7: two gathers of four points, whose
 * x and y the shuffles take apart in slot order. */
static SR_ALWAYS_INLINE void gather_points(const sr_snapped_point *points, lanes i, lanes *x, lanes *y)
{
    __m256 lo = _mm256_castsi256_ps(_mm256_i32gather_epi64((const long long *)points,
                                                           _mm256_castsi256_si128((__m256i)i), 8));
    __m256 hi = _mm256_castsi256_ps(_mm256_i32gather_epi64((const long long *)points,
                                                           _mm256_extracti128_si256((__m256i)i, 1), 8));
    *x = (lanes)_mm256_castps_si256(_mm256_shuffle_ps(lo, hi, 0x88));
    *y = (lanes)_mm256_castps_si256(_mm256_shuffle_ps(lo, hi, 0xdd));
}

#endif

#if SUBPIXEL_LANES == 16 && defined(__AVX512F__)
/* The x and the y of the points of the sixteen slots whose corner indices
 * are i, in slot order: two gathers of eight points, whose x and y two
 * permutes take apart. */
static SR_ALWAYS_INLINE void gather_points(const sr_snapped_point *points, lanes i, lanes *x, lanes *y)
{
    __m512i lo = _mm512_i32gather_epi64(_mm512_castsi512_si256((__m512i)i), (const long long *)points, 8);
    __m512i hi = _mm512_i32gather_epi64(_mm512_extracti64x4_epi64((__m512i)i, 1), (const long long *)points, 8);
    const __m512i evens = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    const __m512i odds = _mm512_setr_epi32(1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31);
    *x = (lanes)_mm512_permutex2var_epi32(lo, evens, hi);
    *y = (lanes)_mm512_permutex2var_epi32(lo, odds, hi);
}

/* Corner k of the sixteen slots whose 48 indices are a, b, c: index
 * 3j + k in lane j, from the first 32 (a and b) where it lies there,
 * then from c. */
static SR_ALWAYS_INLINE lanes corner(__m512i a, __m512i b, __m512i c, int k)
{
    static const int32_t from_ab[3][16] = {
        { 0, 3, 6, 9, 12, 15, 18, 21, 24, 27, 30, 0, 0, 0, 0, 0 },
        { 1, 4, 7, 10, 13, 16, 19, 22, 25, 28, 31, 0, 0, 0, 0, 0 },
        { 2, 5, 8, 11, 14, 17, 20, 23, 26, 29, 0, 0, 0, 0, 0, 0 },
    };
    static const int32_t then_c[3][16] = { /* l: lane l so far; 16 + m: c's m */
        { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 17, 20, 23, 26, 29 },
        { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 18, 21, 24, 27, 30 },
        { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 16, 19, 22, 25, 28, 31 },
    };
    __m512i t = _mm512_permutex2var_epi32(a, _mm512_loadu_si512(from_ab[k]), b);
    return (lanes)_mm512_permutex2var_epi32(t, _mm512_loadu_si512(then_c[k]), c);
}
#endif

#if (SUBPIXEL_LANES == 8 && defined(__AVX2__)) || (SUBPIXEL_LANES == 16 && defined(__AVX512F__))
/* The slots whose corner indices are i0, i1, i2, their points gathered:
 * plain when each is sr_slot_verdict's triangle inside every plane (three
 * distinct indices, each vertex inside), then the lanes' verdicts. */
static SR_ALWAYS_INLINE sr_subpixel_slots slots_of(const sr_snapped_point *points, lanes i0, lanes i1, lanes i2,
                                                   const sr_subpixel_rules *rules)
{
    lanes x0, y0, x1, y1, x2, y2;
    gather_points(points, i0, &x0, &y0);
    gather_points(points, i1, &x1, &y1);
    gather_points(points, i2, &x2, &y2);
    const lanes outside = (lanes){ 0 } + INT32_MIN; /* SR_SNAPPED_OUTSIDE's x */
    lanes plain = (i0 != i1) & (i1 != i2) & (i0 != i2) & (x0 != outside) & (x1 != outside) & (x2 != outside);
    if (lane_bits(plain) != ((uint64_t)1 << SUBPIXEL_LANES) - 1)
        return (sr_subpixel_slots){ .plain = false };
    return (sr_subpixel_slots){ .plain = true, .verdict = verdict_of(x0, y0, x1, y1, x2, y2, rules) };
}
#endif

#if SUBPIXEL_LANES == 8 && defined(__AVX2__)
sr_subpixel_slots sr_subpixel_slot_group_avx2(const uint32_t *indices, const sr_snapped_point *points,
                                              const sr_subpixel_rules *rules)
{
    /* i0 i1 i2 of the slots in the order gather_points takes them, from
     * three loads: each corner into its own lanes by two blends and a
     * permute. */
    __m256i a = _mm256_loadu_si256((const __m256i *)indices), b = _mm256_loadu_si256((const __m256i *)(indices + 8)),
            c = _mm256_loadu_si256((const __m256i *)(indices + 16));
    lanes i0 = (lanes)_mm256_permutevar8x32_epi32(BLEND(BLEND(a, b, 0x92), c, 0x24),
                                                  _mm256_setr_epi32(0, 3, 4, 7, 6, 1, 2, 5));
    lanes i1 = (lanes)_mm256_permutevar8x32_epi32(BLEND(BLEND(a, b, 0x24), c, 0x49),
                                                  _mm256_setr_epi32(1, 4, 5, 0, 7, 2, 3, 6));
    lanes i2 = (lanes)_mm256_permutevar8x32_epi32(BLEND(BLEND(a, b, 0x49), c, 0x92),
                                                  _mm256_setr_epi32(2, 5, 6, 1, 0, 3, 4, 7));
    return slots_of(points, i0, i1, i2, rules);
}
#endif

#if SUBPIXEL_LANES == 16 && defined(__AVX512F__)
sr_subpixel_slots sr_subpixel_slot_group_avx512(const uint32_t *indices, const sr_snapped_point *points,
                                                const sr_subpixel_rules *rules)
{
    __m512i a = _mm512_loadu_si512(indices), b = _mm512_loadu_si512(indices + 16),
            c = _mm512_loadu_si512(indices + 32);
    lanes i0 = corner(a, b, c, 0), i1 = corner(a, b, c, 1), i2 = corner(a, b, c, 2);
    return slots_of(points, i0, i1, i2, rules);
}
#endif
