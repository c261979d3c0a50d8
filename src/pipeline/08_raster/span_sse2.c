/* The 4-lane span kernels: SSE2 on x86-64 (every x86-64 CPU has it), the
 * compiler's 128-bit vectors elsewhere. Left out (SR_SPAN_SSE2_UNUSED) of
 * the fuzz build on a CPU with AVX2, where the fuzzers' draws, which take
 * the loop the CPU picks, never run them (the Makefile). */
#include "kernels.h"

#if defined(SR_SPAN_SSE2_UNUSED)
SR_SPAN_KERNEL_ABSENT(sr_span_kernel_sse2)
SR_TINY_SHADER_ABSENT(sr_tiny_shader_sse2)
#else
#if defined(__SSE2__)
#include <emmintrin.h>
#define SPAN_SQRT(x) ((vf)_mm_sqrt_ps((__m128)(x)))
#define SPAN_MOVEMASK(mask) _mm_movemask_ps((__m128)(mask))
#endif
#define SPAN_LANE_INDICES 0, 1, 2, 3
#define SPAN_LANES 4
#define SPAN_KERNEL_GETTER sr_span_kernel_sse2
#define SPAN_TINY_GETTER sr_tiny_shader_sse2
#include "span_kernel.h"
#endif
