/* The one-pixel depths at the AVX2 width, built with -mavx2 (the Makefile
 * adds it for this file on x86-64) and chosen only where the draw's SIMD
 * level has AVX2. */
#if defined(__AVX2__)
#define ONE_PIXEL_DEPTHS sr_one_pixel_depths_avx2
#include "one_pixel_body.h"
#else
#include "one_pixel.h"

void sr_one_pixel_depths_avx2(const char *screen, size_t stride, const uint32_t (*tri)[3], int n, int bits,
                              sr_raster_rect rect, int width, sr_one_pixels *out)
{
    sr_one_pixel_depths_sse2(screen, stride, tri, n, bits, rect, width, out);
}
#endif
