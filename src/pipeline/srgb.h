/* srgb.h — the sRGB transfer function as two tables, for a draw in
 * SR_COLOR_SRGB (softrast.h): a texel's 8-bit channel decoded to linear
 * light where it is sampled (10_shade.h), a lit linear channel encoded to
 * 8 bits where the fragment's colour is made. Not public API.
 *
 * Linear light is fixed point, SR_LINEAR_ONE (12 bits) for 1: fine enough
 * that the darkest sRGB steps stay apart (decoding then encoding gives
 * back every 8-bit value), coarse enough that the encode table (16 KB)
 * stays in the L1 cache beside the texture. Tables, not arithmetic, so
 * the scalar loop and the SIMD kernels (which gather from the same
 * tables) give the same bits; each entry is the exact function rounded to
 * nearest (tools/gen_srgb.py writes srgb_tables.c). */
#ifndef SOFTRAST_PIPELINE_SRGB_H
#define SOFTRAST_PIPELINE_SRGB_H

#include <stdint.h>

#define SR_LINEAR_BITS 12
#define SR_LINEAR_ONE ((1u << SR_LINEAR_BITS) - 1u)

/* round(SR_LINEAR_ONE · decode(v / 255)) for each 8-bit sRGB value v. */
extern const uint32_t sr_srgb_to_linear[256];
/* round(255 · encode(l / SR_LINEAR_ONE)) for each linear value l. */
extern const uint32_t sr_linear_to_srgb[SR_LINEAR_ONE + 1];

/* A linear channel 0..1 in fixed point, clamped; NaN gives 0 (as
 * sr_shade_channel does for 8 bits). */
static inline uint32_t sr_linear_fixed(float c)
{
    float clamped = c > 0.0f ? (c < 1.0f ? c : 1.0f) : 0.0f;
    return (uint32_t)(clamped * (float)SR_LINEAR_ONE + 0.5f);
}

/* A linear channel 0..1 encoded to an 8-bit sRGB value. */
static inline uint32_t sr_srgb_channel(float c)
{
    return sr_linear_to_srgb[sr_linear_fixed(c)];
}

#endif
