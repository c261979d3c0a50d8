/* simd_select.h — which per-pixel loop runs: the CPU probed once, a request
 * resolved to what it has, and the SIMD kernel or tiny queue shader for a
 * draw's mode and layout in that loop. Not public API. */
#ifndef SOFTRAST_PIPELINE_SIMD_SELECT_H
#define SOFTRAST_PIPELINE_SIMD_SELECT_H

#include "tiny_batch.h"

/* The per-pixel loop a request gets on this CPU: AUTO (or anything
 * unknown) is the best it has; one it lacks falls back to the best below
 * (AVX-512 to AVX2 to SSE2). Off x86-64 "sse2" is the compiler's 4-lane
 * vectors. */
sr_simd sr_raster_simd_resolve(sr_simd want);
const char *sr_simd_name(sr_simd simd); /* "auto", "scalar", "sse2", "avx2", "avx512" */
extern const char *const sr_simd_names[SR_SIMD_COUNT + 1]; /* indexed by sr_simd, NULL-terminated */

/* The kernel for the loop shade->simd resolves to on this CPU, a box
 * `width` pixels wide and a framebuffer with an ids plane or not, or NULL (the scalar loop; or a layout no kernel was
 * compiled for): the AVX-512 loop draws boxes under SR_AVX512_MIN_WIDTH
 * with the AVX2 kernels (simd_select.c). */
sr_span_kernel sr_span_kernel_for(const sr_shade_context *shade, sr_shade mode, bool greater, bool with_ids,
                                  int width);

/* The tiny queue's shader for the loop shade->simd resolves to on this
 * CPU, or NULL (the scalar loop; a mode without varyings; a layout no
 * shader was compiled for). */
sr_tiny_shader sr_tiny_shader_for(const sr_shade_context *shade, sr_shade mode);

#endif
