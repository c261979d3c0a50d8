/* 10_shade.h — stage 10: shading a fragment from its varyings.
 *
 * sr_shade_fragment is inline so the rasterizer's per-pixel loop, specialised
 * per mode with a constant `mode`, compiles to straight-line code with no
 * switch per pixel. Colors are 0x00RRGGBB; every conversion clamps and maps
 * NaN to 0. (A triangle with a NaN or inf in a varying the mode reads never
 * gets here: the vertex phase drops it and counts it non-finite.)
 * Textures wrap (repeat); uv (0, 0) is the bottom-left of the image.
 */
#ifndef SOFTRAST_PIPELINE_SHADE_H
#define SOFTRAST_PIPELINE_SHADE_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "softrast/softrast.h"
#include "srgb.h"
#include "stages.h"

#define SR_LAMBERT_AMBIENT 0.2f
#define SR_LAMBERT_GRAY 0.8f

/* What a material's triangles draw of themselves (sr_shade_context.cut). */
typedef enum sr_shade_cut {
    SR_CUT_NONE,  /* every fragment, or in lambert and texture shading those alpha_min passes */
    SR_CUT_ALL,   /* none: MASK whose alpha is below the cutoff everywhere */
    SR_CUT_TEXELS /* those whose texel alpha passes alpha_min, in a mode that samples no texture */
} sr_shade_cut;

/* The shading of a draw, or of one material of a mesh with materials
 * (draw/materials.c makes one context per material, each with the draw's
 * layout, light, filter and loop, and picks a triangle's by its part). A
 * material's albedo and alpha are folded here into what the loops test
 * per pixel: a texture or not (layout.uv), a colour factor or not
 * (tinted), an alpha floor or not (alpha_min). */
typedef struct sr_shade_context {
    sr_varying_layout layout; /* a material without a texture has uv -1, one with has color -1 */
    const sr_texture *texture;
    sr_filter filter;
    float light_dir[3]; /* unit vector toward the light, world space */
    sr_simd simd;       /* which per-pixel loop runs the shading */
    bool srgb;          /* SR_COLOR_SRGB: texels decoded to linear, colours encoded to sRGB (srgb.h) */
    float albedo[3];    /* without texture or vertex colours: SR_LAMBERT_GRAY, or a material's colour */
    float tint[3];      /* times each texel and vertex colour: 1, 1, 1 but for a material's */
    bool tinted;        /* tint is not 1, 1, 1 */
    /* MASK on a texture with alpha: a fragment whose texel alpha (0..255,
     * filtered) is below it is discarded; 0: none is. */
    uint32_t alpha_min;
    /* Tested once per triangle. Lambert and texture shading test alpha_min
     * in their own loops; id, depth, normal and colour shading, which sample
     * no texture, draw a triangle cut by its texels apart (raster.c,
     * cut_triangle), so that their loops, and every draw without such a
     * material, test nothing per pixel; their coverage is then the colour
     * image's. */
    sr_shade_cut cut;
    /* The output merger's (11_merge.h): the draw's blend, whether it
     * writes depth and ids, whether either differs from a replacing draw
     * that writes them (merges: the scalar loop merges each fragment),
     * and the fragment's alpha, alpha_scale (0..256) times the texel's
     * where alpha_texel. */
    sr_blend blend;
    bool depth_write;
    bool merges;
    uint32_t alpha_scale;
    bool alpha_texel;
    /* The draw's base context only: a mesh's per-material contexts
     * (material_count of them, 0: none) and its parts, by which a
     * triangle's is found (sr_shade_context_of). */
    const struct sr_shade_context *materials;
    uint32_t material_count;
    const sr_mesh_part *parts;
    uint32_t part_count;
} sr_shade_context;

/* The context that shades triangle `id`: its part's material's (10_shade.c;
 * material 0 for a triangle in no part, so material 0 for every triangle
 * of a draw given no parts), or c itself for a draw without materials. */
const sr_shade_context *sr_shade_material_of(const sr_shade_context *c, uint32_t id);

static inline const sr_shade_context *sr_shade_context_of(const sr_shade_context *c, uint32_t id)
{
    return !c->material_count ? c : c->part_count ? sr_shade_material_of(c, id) : c->materials;
}

/* 0..1 to 0..255, clamped; NaN gives 0. */
static inline uint32_t sr_shade_channel(float c)
{
    float clamped = c > 0.0f ? (c < 1.0f ? c : 1.0f) : 0.0f;
    return (uint32_t)(clamped * 255.0f + 0.5f);
}

static inline uint32_t sr_shade_pack(float r, float g, float b)
{
    return sr_shade_channel(r) << 16 | sr_shade_channel(g) << 8 | sr_shade_channel(b);
}

/* A colour (not a normal) packed in the draw's colour space: linear
 * channels encoded to sRGB under SR_COLOR_SRGB, else as sr_shade_pack. */
static inline uint32_t sr_shade_pack_colour(const sr_shade_context *c, float r, float g, float b)
{
    if (!c->srgb)
        return sr_shade_pack(r, g, b);
    return sr_srgb_channel(r) << 16 | sr_srgb_channel(g) << 8 | sr_srgb_channel(b);
}

/* Texture sampling, inline for the per-pixel loops. */
#define SR_SHADE_CHANNEL_SCALE (1.0f / 255.0f)

/* Float has no fraction left from here on, and int conversion stays safe. */
#define SR_SHADE_NO_FRACTION 8388608.0f /* 2^23 */

/* floor for |x| < 2^31, without a libm call in the per-pixel path. */
static inline int sr_shade_floor_int(float x)
{
    int i = (int)x;
    return i - (x < (float)i);
}

/* The fractional part in [0, 1): wrap = repeat. NaN, inf and values too big
 * to have a fraction give 0, so the texel indices below never overflow. */
static inline float sr_shade_wrap_unit(float t)
{
    if (!(fabsf(t) < SR_SHADE_NO_FRACTION))
        return 0.0f;
    float f = t - (float)sr_shade_floor_int(t);
    return f < 1.0f ? f : 0.0f;
}

/* A packed 0x00RRGGBB color as 0..1 floats. */
static inline void sr_shade_unpack(uint32_t t, float rgb[3])
{
    rgb[0] = (float)((t >> 16) & 0xFF) * SR_SHADE_CHANNEL_SCALE;
    rgb[1] = (float)((t >> 8) & 0xFF) * SR_SHADE_CHANNEL_SCALE;
    rgb[2] = (float)(t & 0xFF) * SR_SHADE_CHANNEL_SCALE;
}

/* A texel as stored, its alpha in the top byte where the texture has one. */
static inline uint32_t sr_shade_texel_raw(const sr_texture *tex, int x, int y)
{
    return tex->texels[(size_t)y * (size_t)tex->width + (size_t)x];
}

static inline uint32_t sr_shade_texel(const sr_texture *tex, int x, int y)
{
    return sr_shade_texel_raw(tex, x, y) & 0xFFFFFFu;
}

/* The texel a wrapped coordinate in [0, 1) falls in; a texel's lower edge
 * belongs to it. Rounding may carry f·n up to n, hence the clamp. */
static inline int sr_shade_texel_index(float f, int n)
{
    int i = (int)(f * (float)n);
    return i < n ? i : n - 1;
}

/* Rows count from the bottom as v does, so v = k/H picks row k from the
 * bottom exactly as u = k/W picks column k. */
static inline uint32_t sr_shade_sample_nearest(const sr_texture *tex, float fu, float fv)
{
    return sr_shade_texel(tex, sr_shade_texel_index(fu, tex->width), tex->height - 1 - sr_shade_texel_index(fv, tex->height));
}

/* Bilinear weights are fixed point with SR_SHADE_WEIGHT_BITS fraction bits
 * (Direct3D asks for at least 8), rounded to nearest. */
#define SR_SHADE_WEIGHT_BITS 8
#define SR_SHADE_WEIGHT_ONE (1u << SR_SHADE_WEIGHT_BITS)

/* The two texels around wrapped coordinate f in [0, 1] along a side of n
 * texels (texel centres at half-integers), wrapped, and the weight of the
 * second in 0..SR_SHADE_WEIGHT_ONE − 1. One conversion gives both: the
 * position f·n in units of 1/SR_SHADE_WEIGHT_ONE texel, rounded to nearest
 * (halves up), plus half a texel (so it is never negative), has the texel
 * past the left one in its top bits and the weight in its low bits. f·n·ONE
 * stays within 2^22 (SR_MAX_TEXTURE_SIDE·ONE), where a float still holds
 * halves, so adding ½ rounds nothing (the product itself is rounded where
 * n is not a power of two). The SIMD kernels do the same operations
 * (span_kernel.h, bilinear_pair_lanes). */
static inline uint32_t sr_shade_bilinear_pair(float f, int n, int *i0, int *i1)
{
    int q = (int)(f * (float)(n * (int)SR_SHADE_WEIGHT_ONE) + 0.5f) + (int)SR_SHADE_WEIGHT_ONE / 2;
    int lo = (q >> SR_SHADE_WEIGHT_BITS) - 1;
    *i0 = lo < 0 ? n - 1 : lo;
    *i1 = lo + 1 >= n ? 0 : lo + 1;
    return (uint32_t)q & (SR_SHADE_WEIGHT_ONE - 1);
}

/* (a·(1 − w) + b·w) per channel of two packed texels, in exact integers,
 * rounded to nearest: red and blue share one 32-bit multiply in separate
 * 16-bit halves (a channel times a weight stays below 2^16, so neither half
 * carries into the other). The SIMD kernels compute the same values in
 * another form (span_kernel.h, lerp_halves). */
static inline uint32_t sr_shade_lerp_texels(uint32_t a, uint32_t b, uint32_t w)
{
    uint32_t v = SR_SHADE_WEIGHT_ONE - w;
    uint32_t rb = ((a & 0xFF00FFu) * v + (b & 0xFF00FFu) * w + 0x800080u) >> SR_SHADE_WEIGHT_BITS & 0xFF00FFu;
    uint32_t g = (((a >> 8) & 0xFFu) * v + ((b >> 8) & 0xFFu) * w + 0x80u) >> SR_SHADE_WEIGHT_BITS;
    return rb | g << 8;
}

/* Within 2/255 of the exact bilinear filter (tests/test_shading.c): half a
 * step from each weight's rounding and from each lerp's. */
static inline uint32_t sr_shade_sample_bilinear(const sr_texture *tex, float fu, float fv)
{
    int x0, x1, y0, y1;
    uint32_t wx = sr_shade_bilinear_pair(fu, tex->width, &x0, &x1);
    /* Image rows run top down, v bottom up. */
    uint32_t wy = sr_shade_bilinear_pair(1.0f - fv, tex->height, &y0, &y1);
    uint32_t top = sr_shade_lerp_texels(sr_shade_texel(tex, x0, y0), sr_shade_texel(tex, x1, y0), wx);
    uint32_t bottom = sr_shade_lerp_texels(sr_shade_texel(tex, x0, y1), sr_shade_texel(tex, x1, y1), wx);
    return sr_shade_lerp_texels(top, bottom, wy);
}

/* The filtered texel at (u, v), packed 0x00RRGGBB. */
static inline uint32_t sr_shade_sample_packed(const sr_texture *tex, sr_filter filter, float u, float v)
{
    float fu = sr_shade_wrap_unit(u), fv = sr_shade_wrap_unit(v);
    return filter == SR_FILTER_NEAREST ? sr_shade_sample_nearest(tex, fu, fv) : sr_shade_sample_bilinear(tex, fu, fv);
}

static inline void sr_shade_sample(const sr_texture *tex, sr_filter filter, float u, float v, float rgb[3])
{
    sr_shade_unpack(sr_shade_sample_packed(tex, filter, u, v), rgb);
}

/* The filtered alpha (0..255) at (u, v) of a texture with alpha: the top
 * bytes lerped as sr_shade_lerp_texels lerps a channel, in the same
 * order, as the SIMD kernels lerp it beside green (span_kernel.h,
 * split_lanes). */
static inline uint32_t sr_shade_lerp_alpha(uint32_t a, uint32_t b, uint32_t w)
{
    return ((a >> 24) * (SR_SHADE_WEIGHT_ONE - w) + (b >> 24) * w + SR_SHADE_WEIGHT_ONE / 2) >> SR_SHADE_WEIGHT_BITS;
}

static inline uint32_t sr_shade_sample_alpha(const sr_texture *tex, sr_filter filter, float u, float v)
{
    float fu = sr_shade_wrap_unit(u), fv = sr_shade_wrap_unit(v);
    if (filter == SR_FILTER_NEAREST)
        return sr_shade_texel_raw(tex, sr_shade_texel_index(fu, tex->width),
                                  tex->height - 1 - sr_shade_texel_index(fv, tex->height)) >> 24;
    int x0, x1, y0, y1;
    uint32_t wx = sr_shade_bilinear_pair(fu, tex->width, &x0, &x1);
    uint32_t wy = sr_shade_bilinear_pair(1.0f - fv, tex->height, &y0, &y1);
    uint32_t top = sr_shade_lerp_alpha(sr_shade_texel_raw(tex, x0, y0), sr_shade_texel_raw(tex, x1, y0), wx);
    uint32_t bottom = sr_shade_lerp_alpha(sr_shade_texel_raw(tex, x0, y1), sr_shade_texel_raw(tex, x1, y1), wx);
    return sr_shade_lerp_alpha(top << 24, bottom << 24, wy);
}

/* Whether a fragment at these varyings survives its material's MASK. */
static inline bool sr_shade_alpha_passes(const sr_shade_context *c, const float *var)
{
    return sr_shade_sample_alpha(c->texture, c->filter, var[c->layout.uv], var[c->layout.uv + 1]) >= c->alpha_min;
}

static inline float sr_shade_lambert_intensity(const sr_shade_context *c, const float *n)
{
    float len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (!(len2 > 0.0f))
        return SR_LAMBERT_AMBIENT;
    float d = (n[0] * c->light_dir[0] + n[1] * c->light_dir[1] + n[2] * c->light_dir[2]) / sqrtf(len2);
    return SR_LAMBERT_AMBIENT + (1.0f - SR_LAMBERT_AMBIENT) * (d > 0.0f ? d : 0.0f);
}

/* The albedo without a texture: the vertex colors (times a material's
 * tint), else the context's albedo. */
static inline void sr_shade_albedo(const sr_shade_context *c, const float *var, float rgb[3])
{
    for (int i = 0; i < 3; i++) {
        rgb[i] = c->layout.color >= 0 ? var[c->layout.color + i] : c->albedo[i];
        if (c->layout.color >= 0 && c->tinted)
            rgb[i] *= c->tint[i];
    }
}

/* A packed texel lit by intensity k: k in 8.8 fixed point (rounded to
 * nearest, at most 1), then each channel k·t rounded to nearest in
 * integers, within one step of k·t (half from each rounding). k is in
 * [0.2, 1] up to a rounding and never NaN; the clamp keeps a k past
 * 1 + 2^-9 (a normal too short to square in float) from carrying a channel
 * into the next. The SIMD kernels do the same operations on 16-bit halves
 * of the texel (span_kernel.h, lit_texel_lanes), where each channel went
 * to float and back (docs/performance.md, "The per-pixel loops"). */
#define SR_SHADE_LIT_BITS 8
#define SR_SHADE_LIT_ONE (1u << SR_SHADE_LIT_BITS)

static inline uint32_t sr_shade_lit_texel(uint32_t t, float k)
{
    uint32_t k_fixed = (uint32_t)(k * (float)SR_SHADE_LIT_ONE + 0.5f), out = 0;
    k_fixed = k_fixed < SR_SHADE_LIT_ONE ? k_fixed : SR_SHADE_LIT_ONE;
    for (int shift = 16; shift >= 0; shift -= 8)
        out |= ((((t >> shift) & 0xFF) * k_fixed + SR_SHADE_LIT_ONE / 2) >> SR_SHADE_LIT_BITS) << shift;
    return out;
}

/* k in 8.8 fixed point as sr_shade_lit_texel makes it. */
static inline uint32_t sr_shade_lit_fixed(float k)
{
    uint32_t k_fixed = (uint32_t)(k * (float)SR_SHADE_LIT_ONE + 0.5f);
    return k_fixed < SR_SHADE_LIT_ONE ? k_fixed : SR_SHADE_LIT_ONE;
}

/* A texel lit by k times a tint per channel: sr_shade_lit_texel with each
 * channel's k·tint (the same value where the tint is 1). */
static inline uint32_t sr_shade_lit_texel_tinted(uint32_t t, float k, const float tint[3])
{
    uint32_t out = 0;
    for (int c = 0; c < 3; c++) {
        int shift = 16 - 8 * c;
        out |= ((((t >> shift) & 0xFF) * sr_shade_lit_fixed(k * tint[c]) + SR_SHADE_LIT_ONE / 2) >> SR_SHADE_LIT_BITS)
               << shift;
    }
    return out;
}

/* sr_shade_lit_texel_tinted in linear light (SR_COLOR_SRGB): each channel
 * of the filtered texel decoded to SR_LINEAR_BITS, times its k·tint in 8.8
 * fixed point (k alone untinted: sr_shade_lit_texel's k_fixed), rounded,
 * and encoded. The SIMD kernels do the same operations per lane
 * (span_kernel.h, lit_srgb_lanes). */
static inline uint32_t sr_shade_lit_texel_srgb(uint32_t t, float k, const float *tint)
{
    uint32_t out = 0;
    for (int c = 0; c < 3; c++) {
        int shift = 16 - 8 * c;
        uint32_t k_fixed = sr_shade_lit_fixed(tint ? k * tint[c] : k);
        uint32_t linear = (sr_srgb_to_linear[(t >> shift) & 0xFF] * k_fixed + SR_SHADE_LIT_ONE / 2) >> SR_SHADE_LIT_BITS;
        out |= sr_linear_to_srgb[linear] << shift;
    }
    return out;
}

/* A fragment's albedo lit by intensity k (1 for unlit texture shading):
 * its texel or albedo times k, in the draw's colour space. */
static SR_ALWAYS_INLINE uint32_t sr_shade_lit(const sr_shade_context *c, const float *var, float k)
{
    if (c->layout.uv >= 0) {
        uint32_t texel = sr_shade_sample_packed(c->texture, c->filter, var[c->layout.uv], var[c->layout.uv + 1]);
        if (c->srgb)
            return sr_shade_lit_texel_srgb(texel, k, c->tinted ? c->tint : NULL);
        return c->tinted ? sr_shade_lit_texel_tinted(texel, k, c->tint) : sr_shade_lit_texel(texel, k);
    }
    float rgb[3];
    sr_shade_albedo(c, var, rgb);
    return sr_shade_pack_colour(c, k * rgb[0], k * rgb[1], k * rgb[2]);
}

/* The color of one fragment; `var` holds the perspective-correct varyings. */
static SR_ALWAYS_INLINE uint32_t sr_shade_fragment(sr_shade mode, const sr_shade_context *c, const float *var,
                                                    uint32_t triangle_id)
{
    switch (mode) {
    case SR_SHADE_ID:
        return triangle_id + 1u;
    case SR_SHADE_COLOR:
        return sr_shade_pack_colour(c, var[c->layout.color], var[c->layout.color + 1], var[c->layout.color + 2]);
    case SR_SHADE_NORMAL: {
        const float *n = var + c->layout.normal;
        return sr_shade_pack(0.5f + 0.5f * n[0], 0.5f + 0.5f * n[1], 0.5f + 0.5f * n[2]);
    }
    case SR_SHADE_TEXTURE:
        /* A material's colour, or its tinted texture; a texel alone is
         * itself in either colour space (decoded, then encoded: every
         * 8-bit value comes back, tests/test_srgb.c). */
        if (c->layout.uv < 0 || c->tinted)
            return sr_shade_lit(c, var, 1.0f);
        return sr_shade_sample_packed(c->texture, c->filter, var[c->layout.uv], var[c->layout.uv + 1]);
    case SR_SHADE_LAMBERT:
        return sr_shade_lit(c, var, sr_shade_lambert_intensity(c, var + c->layout.normal));
    default:
        return 0;
    }
}

#endif
