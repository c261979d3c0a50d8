/* 11_merge.h — the output merger: a fragment that passed its depth test
 * meeting the framebuffer (sr_draw_desc.blend, no_depth_write), in the
 * draw's colour space. Not public API.
 *
 * The loops keep a replacing draw's stores as they were (a draw that
 * neither blends nor keeps its depth never calls in here); a draw that
 * does takes the scalar loop, which merges each fragment in submission
 * order, as points and lines do (simd_select.c hands it no kernel). Under
 * SR_COLOR_SRGB the source (the shaded colour) and the destination are
 * decoded to linear light by srgb.h's table, blended there and encoded;
 * under SR_COLOR_RAW they blend as stored. Alpha is 0..SR_MERGE_ALPHA_ONE
 * (an 8-bit alpha a becomes a + a/128, so 0 and 255 are 0 and 1
 * exactly), and each blend is rounded to nearest in integers. */
#ifndef SOFTRAST_PIPELINE_MERGE_H
#define SOFTRAST_PIPELINE_MERGE_H

#include "10_shade.h"

#define SR_MERGE_ALPHA_BITS 8
#define SR_MERGE_ALPHA_ONE (1u << SR_MERGE_ALPHA_BITS)

/* An 8-bit alpha (0..255) as 0..SR_MERGE_ALPHA_ONE. */
static inline uint32_t sr_merge_alpha_of_byte(uint32_t a)
{
    return a + (a >> 7);
}

/* The texel's 8-bit alpha where alpha_texel (a texture with alpha; var
 * holds the varyings then, as a mode with a texture reads them), else
 * 255. */
static inline uint32_t sr_merge_texel_alpha(const sr_shade_context *c, const float *var)
{
    return c->alpha_texel ? sr_shade_sample_alpha(c->texture, c->filter, var[c->layout.uv], var[c->layout.uv + 1])
                          : 0xFFu;
}

/* The fragment's alpha: the context's alpha_scale times the texel's. */
static inline uint32_t sr_merge_alpha(const sr_shade_context *c, const float *var)
{
    if (!c->alpha_texel)
        return c->alpha_scale;
    return (sr_merge_alpha_of_byte(sr_merge_texel_alpha(c, var)) * c->alpha_scale + SR_MERGE_ALPHA_ONE / 2) >>
           SR_MERGE_ALPHA_BITS;
}

/* One channel of source s over destination d (both 0..one) at alpha a. */
static inline uint32_t sr_merge_channel(sr_blend blend, uint32_t s, uint32_t d, uint32_t a, uint32_t one)
{
    const uint32_t half = SR_MERGE_ALPHA_ONE / 2, rest = SR_MERGE_ALPHA_ONE - a;
    uint32_t v;
    switch (blend) {
    case SR_BLEND_ALPHA:         return (s * a + d * rest + half) >> SR_MERGE_ALPHA_BITS;
    case SR_BLEND_ADD:           v = d + ((s * a + half) >> SR_MERGE_ALPHA_BITS); break;
    case SR_BLEND_PREMULTIPLIED: v = s + ((d * rest + half) >> SR_MERGE_ALPHA_BITS); break;
    default:                     return s;
    }
    return v < one ? v : one;
}

/* src blended over dst (both 0x00RRGGBB as the framebuffer holds them). */
static inline uint32_t sr_merge_colour(const sr_shade_context *c, uint32_t src, uint32_t a, uint32_t dst)
{
    uint32_t out = 0;
    for (int shift = 16; shift >= 0; shift -= 8) {
        uint32_t s = (src >> shift) & 0xFF, d = (dst >> shift) & 0xFF;
        if (c->srgb)
            s = sr_linear_to_srgb[sr_merge_channel(c->blend, sr_srgb_to_linear[s], sr_srgb_to_linear[d], a,
                                                   SR_LINEAR_ONE)];
        else
            s = sr_merge_channel(c->blend, s, d, a, 0xFF);
        out |= s << shift;
    }
    return out;
}

/* A fragment of a merging draw that passed its depth test at pixel `at`:
 * its depth and id + 1 (with_ids) written unless the draw keeps its
 * depth, and, where `coloured`, its colour merged at alpha a (unused by a
 * draw that replaces). */
static inline void sr_merge_fragment(sr_framebuffer *fb, const sr_shade_context *c, size_t at, float z,
                                     bool with_ids, uint32_t id, bool coloured, uint32_t colour, uint32_t a)
{
    if (c->depth_write) {
        fb->depth[at] = z;
        if (with_ids)
            fb->ids[at] = id + 1u;
    }
    if (coloured)
        fb->color[at] = c->blend == SR_BLEND_REPLACE ? colour : sr_merge_colour(c, colour, a, fb->color[at]);
}

#endif
