/* The 8-lane span kernels, built with -mavx2 (the Makefile adds it for this
 * file on x86-64) and chosen at run time only on a CPU that has AVX2. No
 * -mfma: a fused multiply-add would round differently from the scalar path. */
#include "kernels.h"

#if defined(__AVX2__)
#include <immintrin.h>
#define SPAN_SQRT(x) ((vf)_mm256_sqrt_ps((__m256)(x)))
#define SPAN_MOVEMASK(mask) _mm256_movemask_ps((__m256)(mask))
#define SPAN_GATHER(texels, index) ((vi)_mm256_i32gather_epi32((const int *)(texels), (__m256i)(index), 4))
#define SPAN_LANE_INDICES 0, 1, 2, 3, 4, 5, 6, 7
#define SPAN_FLOOR(x) ((vf)_mm256_floor_ps((__m256)(x)))
#define SPAN_STORE_WHERE(p, mask, v) _mm256_maskstore_epi32((int *)(p), (__m256i)(mask), (__m256i)(v))
#define SPAN_PERMUTE(v, index) ((vf)_mm256_permutevar8x32_ps((__m256)(v), (__m256i)(index)))
#define SPAN_MULHRS(a, b) ((vu16)_mm256_mulhrs_epi16((__m256i)(a), (__m256i)(b)))
#define SPAN_LANES 8
#define SPAN_KERNEL_GETTER sr_span_kernel_avx2
#define SPAN_TINY_GETTER sr_tiny_shader_avx2
#include "span_kernel.h"
#else
SR_SPAN_KERNEL_ABSENT(sr_span_kernel_avx2)
SR_TINY_SHADER_ABSENT(sr_tiny_shader_avx2)
#endif
