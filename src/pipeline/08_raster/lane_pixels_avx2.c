/* The lane pixels at the AVX2 width, built with -mavx2 (the Makefile adds
 * it for this file on x86-64) and chosen only where the draw's SIMD level
 * has AVX2. */
#if defined(__AVX2__)
#define LANE_PIXELS sr_lane_pixels_avx2
#include "lane_pixels_body.h"
#else
#include "lane_pixels.h"

void sr_lane_pixels_avx2(const char *screen, size_t stride, const uint32_t (*tri)[3], int n, uint64_t one_pixel,
                         int bits, sr_raster_rect rect, int width, sr_lane_pixels *out)
{
    sr_lane_pixels_sse2(screen, stride, tri, n, one_pixel, bits, rect, width, out);
}
#endif
