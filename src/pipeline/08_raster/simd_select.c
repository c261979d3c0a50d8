/* Which per-pixel loop runs: the CPU probed once, a request resolved to
 * what it has, and the SIMD kernel or tiny queue shader for a draw's mode
 * and layout in that loop. */
#include <stdatomic.h>

#include "kernels.h"
#include "simd_select.h"

/* The best loop this build and this CPU have. */
static sr_simd simd_probe(void)
{
    static const sr_shade_context none = { .layout = { .count = 0, .color = -1, .uv = -1, .normal = -1 } };
    bool avx512 = sr_span_kernel_avx512(SR_SHADE_ID, false, false, &none) != NULL;
    bool avx2 = sr_span_kernel_avx2(SR_SHADE_ID, false, false, &none) != NULL;
#if defined(__x86_64__) || defined(__i386__)
    avx2 = avx2 && __builtin_cpu_supports("avx2");
    /* The AVX-512 loop runs the AVX2 kernels on narrow work too. */
    avx512 = avx512 && avx2 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
             __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl");
#endif
    return avx512 ? SR_SIMD_AVX512 : avx2 ? SR_SIMD_AVX2 : SR_SIMD_SSE2;
}

/* Probed once; threads racing on the first draw all store the same value. */
static sr_simd simd_best(void)
{
    static _Atomic int best = SR_SIMD_AUTO;
    int b = atomic_load_explicit(&best, memory_order_relaxed);
    if (b == SR_SIMD_AUTO) {
        b = simd_probe();
        atomic_store_explicit(&best, b, memory_order_relaxed);
    }
    return (sr_simd)b;
}

sr_simd sr_raster_simd_resolve(sr_simd want)
{
    sr_simd best = simd_best();
    if (want == SR_SIMD_AUTO || want >= SR_SIMD_COUNT)
        return best;
    return want > best ? best : want;
}

const char *const sr_simd_names[SR_SIMD_COUNT + 1] = { "auto", "scalar", "sse2", "avx2", "avx512", NULL };

const char *sr_simd_name(sr_simd simd)
{
    return (unsigned)simd < SR_SIMD_COUNT ? sr_simd_names[simd] : "unknown";
}

/* The AVX-512 loop's narrow work goes to the AVX2 kernels: boxes under
 * this many pixels wide, and the tiny queue. A 16-lane group is more than
 * such a row or queue fills, and on pixel-sized triangles the AVX2 loop
 * drew faster than the AVX-512 one (docs/performance.md, "The per-pixel
 * loops"). */
#define SR_AVX512_MIN_WIDTH 16

/* A draw that blends or keeps its depth (shade->merges) takes the scalar
 * loop, which merges its fragments in submission order (11_merge.h). */
sr_span_kernel sr_span_kernel_for(const sr_shade_context *shade, sr_shade mode, bool greater, bool with_ids,
                                  int width)
{
    if (shade->merges)
        return NULL;
    switch (sr_raster_simd_resolve(shade->simd)) {
    case SR_SIMD_AVX512:
        return width >= SR_AVX512_MIN_WIDTH ? sr_span_kernel_avx512(mode, greater, with_ids, shade)
                                            : sr_span_kernel_avx2(mode, greater, with_ids, shade);
    case SR_SIMD_AVX2: return sr_span_kernel_avx2(mode, greater, with_ids, shade);
    case SR_SIMD_SSE2: return sr_span_kernel_sse2(mode, greater, with_ids, shade);
    default:           return NULL;
    }
}

sr_tiny_shader sr_tiny_shader_for(const sr_shade_context *shade, sr_shade mode)
{
    if (shade->merges)
        return NULL;
    switch (sr_raster_simd_resolve(shade->simd)) {
    case SR_SIMD_AVX512: /* the AVX2 shader: see SR_AVX512_MIN_WIDTH */
    case SR_SIMD_AVX2: return sr_tiny_shader_avx2(mode, shade);
    case SR_SIMD_SSE2: return sr_tiny_shader_sse2(mode, shade);
    default:           return NULL;
    }
}
