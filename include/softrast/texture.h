/* softrast/texture.h — an RGB texture in memory, loaded from PNG.
 *
 * Texels are 0x00RRGGBB, row 0 at the top of the image. Sampling (nearest and
 * bilinear, wrap = repeat) lives in the shading stage (softrast/shade.h); this
 * header only loads and frees. Loading uses SDL2_image and fails with one line
 * in err for a missing file or anything that is not a readable image.
 */
#ifndef SOFTRAST_TEXTURE_H
#define SOFTRAST_TEXTURE_H

#include <stdbool.h>
#include <stdint.h>

#include "error.h"

/* Sides up to this (the GPU-common limit) keep every texel index below 2^28,
 * within the SIMD kernels' 32-bit lanes; the loader refuses larger images
 * and a draw refuses a larger texture. */
#define SR_MAX_TEXTURE_SIDE 16384

typedef struct sr_texture {
    int width, height;
    uint32_t *texels; /* width * height, row-major, top row first */
} sr_texture;

bool sr_texture_load(sr_texture *tex, const char *path, sr_error *err);
void sr_texture_free(sr_texture *tex);

#endif
