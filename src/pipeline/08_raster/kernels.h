/* kernels.h — the SIMD per-pixel loops' entry points, one getter per
 * instruction set (span_sse2.c, span_avx2.c, span_avx512.c, each the
 * template span_kernel.h compiled for its lanes); simd_select.h picks
 * among them. Not public API. */
#ifndef SOFTRAST_PIPELINE_KERNELS_H
#define SOFTRAST_PIPELINE_KERNELS_H

#include "tiny_batch.h"

/* The kernel for a shading mode, depth test, ids plane or none
 * (sr_framebuffer.ids) and context: its varying layout (each kernel is
 * compiled for one, so its varyings stay in registers) and a material's
 * tint and alpha test. NULL where the instruction set is not built in
 * (AVX2 and AVX-512 off x86-64; SSE2 in the fuzz build on a CPU with AVX2,
 * the Makefile) or the layout is not one sr_vertex_layout makes (the
 * scalar loop draws those). */
sr_span_kernel sr_span_kernel_sse2(sr_shade mode, bool greater, bool with_ids, const sr_shade_context *c);

/* The getters of a kernel file built without its kernels. */
#define SR_SPAN_KERNEL_ABSENT(getter)                                                                         \
    sr_span_kernel getter(sr_shade mode, bool greater, bool with_ids, const sr_shade_context *c)             \
    {                                                                                                         \
        (void)mode, (void)greater, (void)with_ids, (void)c;                                                   \
        return NULL;                                                                                          \
    }
#define SR_TINY_SHADER_ABSENT(getter)                                                                         \
    sr_tiny_shader getter(sr_shade mode, const sr_shade_context *c)                                           \
    {                                                                                                         \
        (void)mode, (void)c;                                                                                  \
        return NULL;                                                                                          \
    }

sr_span_kernel sr_span_kernel_avx2(sr_shade mode, bool greater, bool with_ids, const sr_shade_context *c);
sr_span_kernel sr_span_kernel_avx512(sr_shade mode, bool greater, bool with_ids, const sr_shade_context *c);

/* The tiny queue's shader for a mode and layout, as the span kernels'
 * getters give theirs, or NULL (a mode without varyings; a layout no shader
 * was compiled for). */
sr_tiny_shader sr_tiny_shader_sse2(sr_shade mode, const sr_shade_context *c);
sr_tiny_shader sr_tiny_shader_avx2(sr_shade mode, const sr_shade_context *c);

#endif
