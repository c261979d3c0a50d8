/* softrast/shade.h — stage 10: shading a fragment from its varyings.
 *
 * sr_shade_fragment is inline so the rasterizer's per-pixel loop, specialised
 * per mode with a constant `mode`, compiles to straight-line code with no
 * switch per pixel. Colors are 0x00RRGGBB; every conversion clamps and maps
 * NaN to 0. (A triangle with a NaN or inf in a varying the mode reads never
 * gets here: the vertex phase drops it and counts it non-finite.)
 * Textures wrap (repeat); uv (0, 0) is the bottom-left of the image.
 */
#ifndef SOFTRAST_SHADE_H
#define SOFTRAST_SHADE_H

#include <math.h>
#include <stdint.h>

#include "texture.h"
#include "types.h"

#define SR_LAMBERT_AMBIENT 0.2f
#define SR_LAMBERT_GRAY 0.8f

typedef struct sr_shade_context {
    sr_varying_layout layout;
    const sr_texture *texture;
    sr_filter filter;
    float light_dir[3]; /* unit vector toward the light, world space */
} sr_shade_context;

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

/* Texture color at (u, v) as linear 0..1 RGB. */
void sr_shade_sample(const sr_texture *tex, sr_filter filter, float u, float v, float rgb[3]);

static inline float sr_shade_lambert_intensity(const sr_shade_context *c, const float *n)
{
    float len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (!(len2 > 0.0f))
        return SR_LAMBERT_AMBIENT;
    float d = (n[0] * c->light_dir[0] + n[1] * c->light_dir[1] + n[2] * c->light_dir[2]) / sqrtf(len2);
    return SR_LAMBERT_AMBIENT + (1.0f - SR_LAMBERT_AMBIENT) * (d > 0.0f ? d : 0.0f);
}

static inline void sr_shade_albedo(const sr_shade_context *c, const float *var, float rgb[3])
{
    if (c->layout.uv >= 0) {
        sr_shade_sample(c->texture, c->filter, var[c->layout.uv], var[c->layout.uv + 1], rgb);
    } else if (c->layout.color >= 0) {
        for (int i = 0; i < 3; i++)
            rgb[i] = var[c->layout.color + i];
    } else {
        rgb[0] = rgb[1] = rgb[2] = SR_LAMBERT_GRAY;
    }
}

/* The color of one fragment; `var` holds the perspective-correct varyings. */
static inline uint32_t sr_shade_fragment(sr_shade mode, const sr_shade_context *c, const float *var,
                                         uint32_t triangle_id)
{
    float rgb[3];
    switch (mode) {
    case SR_SHADE_ID:
        return (triangle_id + 1u) & 0xFFFFFFu;
    case SR_SHADE_COLOR:
        return sr_shade_pack(var[c->layout.color], var[c->layout.color + 1], var[c->layout.color + 2]);
    case SR_SHADE_NORMAL: {
        const float *n = var + c->layout.normal;
        return sr_shade_pack(0.5f + 0.5f * n[0], 0.5f + 0.5f * n[1], 0.5f + 0.5f * n[2]);
    }
    case SR_SHADE_TEXTURE:
        sr_shade_sample(c->texture, c->filter, var[c->layout.uv], var[c->layout.uv + 1], rgb);
        return sr_shade_pack(rgb[0], rgb[1], rgb[2]);
    case SR_SHADE_LAMBERT: {
        float k = sr_shade_lambert_intensity(c, var + c->layout.normal);
        sr_shade_albedo(c, var, rgb);
        return sr_shade_pack(k * rgb[0], k * rgb[1], k * rgb[2]);
    }
    default:
        return 0;
    }
}

#endif
