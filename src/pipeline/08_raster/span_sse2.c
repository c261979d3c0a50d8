/* The 4-lane span kernels: SSE2 on x86-64 (every x86-64 CPU has it), the
 * compiler's 128-bit vectors elsewhere. */
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
