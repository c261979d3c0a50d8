/* The resolve's triangle lanes in AVX2 registers, built with -mavx2 (the
 * Makefile adds it for this file on x86-64) and called only where the CPU
 * has AVX2. */
#if defined(__AVX2__)
#define PINHOLE_TRIANGLES sr_pinhole_triangles_avx2
#include "pinhole_triangles_body.h"
#else
#include "pinhole_triangles.h"

void sr_pinhole_triangles_avx2(const camera_frame *f, const float (*positions)[3], const uint32_t (*corners)[3],
                               resolved_triangle *const *to, uint32_t n)
{
    sr_pinhole_triangles_sse2(f, positions, corners, to, n);
}
#endif
