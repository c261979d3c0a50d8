/* The two halves' lanes at the AVX2 width, built with -mavx2 (the
 * Makefile adds it for this file on x86-64) and chosen only where the
 * draw's SIMD level has AVX2. */
#if defined(__AVX2__)
#define VIEWPORT_LANES 4
#define VIEWPORT_FLOAT_LANES sr_viewport_float_lanes_avx2
#define VIEWPORT_DOUBLE_LANES sr_viewport_double_lanes_avx2
#include "06_viewport_body.h"
#else
#include "06_viewport_lanes.h"

uint32_t sr_viewport_float_lanes_avx2(const sr_vertex_out *v, uint32_t n, int varyings, const sr_viewport_lanes *r,
                                      unsigned char *codes, void *out, size_t stride, sr_snapped_point *points)
{
    return sr_viewport_float_lanes_sse2(v, n, varyings, r, codes, out, stride, points);
}

uint32_t sr_viewport_double_lanes_avx2(const float (*positions)[3], const double m[4][4], const uint32_t *index,
                                       uint32_t n, const sr_viewport_lanes *r, char *screen, size_t stride)
{
    return sr_viewport_double_lanes_sse2(positions, m, index, n, r, screen, stride);
}
#endif
