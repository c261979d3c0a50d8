/* The 16-lane span kernels, built with AVX-512 (F, BW, DQ, VL; the Makefile
 * adds the flags for this file on x86-64) and chosen at run time only on a
 * CPU that has them, for boxes at least SR_AVX512_MIN_WIDTH wide
 * (simd_select.c). No FMA, as in span_avx2.c. No tiny queue shader: the
 * queue takes the AVX2 one. */
#include "kernels.h"

#if defined(__AVX512F__) && defined(__AVX512DQ__) && defined(__AVX512BW__) && defined(__AVX512VL__)
#include <immintrin.h>
#define SPAN_SQRT(x) ((vf)_mm512_sqrt_ps((__m512)(x)))
#define SPAN_MOVEMASK(mask) _mm512_movepi32_mask((__m512i)(mask))
#define SPAN_GATHER(texels, index) ((vi)_mm512_i32gather_epi32((__m512i)(index), (const void *)(texels), 4))
#define SPAN_FLOOR(x) ((vf)_mm512_roundscale_ps((__m512)(x), _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC))
#define SPAN_LOAD_FIRST(p, n) ((vi)_mm512_maskz_loadu_epi32((__mmask16)((1u << (n)) - 1u), (p)))
#define SPAN_STORE_WHERE(p, mask, v) _mm512_mask_storeu_epi32((p), _mm512_movepi32_mask((__m512i)(mask)), (__m512i)(v))
#define SPAN_LANE_INDICES 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15
#define SPAN_MULHRS(a, b) ((vu16)_mm512_mulhrs_epi16((__m512i)(a), (__m512i)(b)))
#define SPAN_LANES 16
#define SPAN_KERNEL_GETTER sr_span_kernel_avx512
#include "span_kernel.h"
#else
SR_SPAN_KERNEL_ABSENT(sr_span_kernel_avx512)
#endif
