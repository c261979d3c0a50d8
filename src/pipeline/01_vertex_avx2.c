/* The vertex phase's classifying loop eight vertices at a time in AVX2
 * lanes (01_vertex.c's fours at twice the width), built with -mavx2 (the
 * Makefile adds it for this file on x86-64, never -mfma) and chosen only
 * where the draw's SIMD level has AVX2. */
#include "01_vertex_lanes.h"

#if defined(__AVX2__)
#include <immintrin.h>
#include <string.h>

/* x, y and z of 24 floats, eight positions: each 128-bit half of a, b and
 * c holds four positions' 12 floats (vertices 0-3 low, 4-7 high), and the
 * fours' shuffles work within halves, so each half deinterleaves as the
 * fours' loop does. */
static SR_ALWAYS_INLINE void deinterleave(const float *p, __m256 *x, __m256 *y, __m256 *z)
{
    __m256 a = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p)), _mm_loadu_ps(p + 12), 1);
    __m256 b = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p + 4)), _mm_loadu_ps(p + 16), 1);
    __m256 c = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p + 8)), _mm_loadu_ps(p + 20), 1);
    __m256 x1_y1 = _mm256_shuffle_ps(a, b, _MM_SHUFFLE(0, 0, 3, 3));
    __m256 xy01 = _mm256_shuffle_ps(a, x1_y1, _MM_SHUFFLE(2, 0, 1, 0));
    __m256 xy23 = _mm256_shuffle_ps(b, c, _MM_SHUFFLE(2, 1, 3, 2));
    __m256 z01 = _mm256_shuffle_ps(a, b, _MM_SHUFFLE(1, 1, 2, 2)), z23 = _mm256_shuffle_ps(c, c, _MM_SHUFFLE(3, 3, 0, 0));
    *x = _mm256_shuffle_ps(xy01, xy23, _MM_SHUFFLE(2, 0, 2, 0));
    *y = _mm256_shuffle_ps(xy01, xy23, _MM_SHUFFLE(3, 1, 3, 1));
    *z = _mm256_shuffle_ps(z01, z23, _MM_SHUFFLE(2, 0, 2, 0));
}

uint32_t sr_vertex_eights_inside(const float (*positions)[3], const float clip_from_object[4][4],
                                 const sr_clip_depth *depth, uint32_t count, sr_vertex_out *out,
                                 unsigned char *codes)
{
    __m256 column[4][4]; /* column[c][r]: clip_from_object[c][r] in every lane */
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            column[c][r] = _mm256_set1_ps(clip_from_object[c][r]);
    uint32_t k = 0;
    for (; count - k >= 8; k += 8) {
        if (count - k > SR_VERTEX_POSITIONS_AHEAD)
            __builtin_prefetch(positions[k + SR_VERTEX_POSITIONS_AHEAD]);
        __m256 x, y, z;
        deinterleave(positions[k], &x, &y, &z);
        __m256 clip[4];
#pragma GCC unroll 4
        for (int r = 0; r < 4; r++) /* cglm's order: ((m3 + m2·z) + m1·y) + m0·x */
            clip[r] = _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(column[3][r], _mm256_mul_ps(column[2][r], z)),
                                                  _mm256_mul_ps(column[1][r], y)),
                                    _mm256_mul_ps(column[0][r], x));
#pragma GCC unroll 2
        for (int half = 0; half < 2; half++) {
            __m128 c[4];
#pragma GCC unroll 4
            for (int r = 0; r < 4; r++)
                c[r] = half ? _mm256_extractf128_ps(clip[r], 1) : _mm256_castps256_ps128(clip[r]);
            uint32_t four = sr_clip_outcodes_four(c, depth);
            memcpy(codes + k + 4 * half, &four, sizeof four);
            _MM_TRANSPOSE4_PS(c[0], c[1], c[2], c[3]);
#pragma GCC unroll 4
            for (int j = 0; j < 4; j++)
                _mm_store_ps(out[k + 4 * (uint32_t)half + (uint32_t)j].v, c[j]);
        }
    }
    return k;
}
#else
uint32_t sr_vertex_eights_inside(const float (*positions)[3], const float clip_from_object[4][4],
                                 const sr_clip_depth *depth, uint32_t count, sr_vertex_out *out,
                                 unsigned char *codes)
{
    (void)positions, (void)clip_from_object, (void)depth, (void)count, (void)out, (void)codes;
    return 0;
}
#endif
