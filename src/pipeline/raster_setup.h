/* raster_setup.h — a triangle as the per-pixel loops read it, shared by the
 * scalar loop (raster.c) and the SIMD span kernels (span_*.c). Not public API.
 *
 * Edge k is the one opposite vertex k, so E_k / area2 is barycentric λ_k;
 * attributes are a0 + λ1·d1 + λ2·d2 with λ from the exact edge values. Every
 * path evaluates these in the same float operations in the same order, so a
 * pixel comes out bit-identical whichever path draws it. */
#ifndef SOFTRAST_RASTER_SETUP_H
#define SOFTRAST_RASTER_SETUP_H

#include "softrast/raster.h"

/* E(P) = a·Px + b·Py + c, the edge function of a → b in subpixel units: >= 0
 * on the inside of a clockwise (area2 > 0) triangle. `bias` is 0 on a top or
 * left edge and 1 otherwise, so E >= bias decides coverage with the
 * top-left rule in exact integers. */
typedef struct sr_edge {
    int64_t a, b, c, bias;
} sr_edge;

typedef struct sr_tri_setup {
    sr_edge e[3];
    int64_t step_x[3]; /* E's change from one pixel to the next on a row */
    float inv_area2;
    float z0, dz1, dz2;
    float iw0, diw1, diw2;
    int varyings;
    float var0[SR_MAX_VARYINGS], dvar1[SR_MAX_VARYINGS], dvar2[SR_MAX_VARYINGS];
    sr_raster_rect box;
    int bits; /* subpixel bits of the vertices */
} sr_tri_setup;

/* A row of a SIMD kernel: pixels at, at + 1, …, at + count − 1 of fb, all
 * inside the triangle, the first with edge values e[] (e[0] unused). The caller
 * guarantees every edge value of the scan box (and a few pixels past it)
 * is below 2^52 in magnitude, so doubles hold them exactly. Returns the
 * fragments that passed the depth test. */
typedef uint64_t (*sr_span_kernel)(const sr_tri_setup *s, const sr_shade_context *c, sr_framebuffer *fb,
                                   uint32_t id, size_t at, int count, const int64_t e[3]);

/* The kernel for a shading mode, depth test and varying layout (each kernel
 * is compiled for one layout, so its varyings stay in registers), or NULL
 * where the instruction set is not built in (AVX2 off x86-64) or the layout
 * is not one sr_vertex_layout makes (the scalar loop draws those). */
sr_span_kernel sr_span_kernel_sse2(sr_shade mode, bool greater, const sr_varying_layout *layout);
sr_span_kernel sr_span_kernel_avx2(sr_shade mode, bool greater, const sr_varying_layout *layout);
sr_span_kernel sr_span_kernel_avx512(sr_shade mode, bool greater, const sr_varying_layout *layout);

#endif
