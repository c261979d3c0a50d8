/* softrast/framebuffer.h — the color and depth buffers a draw writes.
 *
 * Color is 0x00RRGGBB per pixel, row 0 at the top; depth is float32 z_ndc in
 * [0, 1]. The framebuffer owns the depth convention: standard (the default)
 * clears to 1.0 and keeps the nearer fragment with LESS; reversed_z clears to
 * 0.0 and tests GREATER, for a camera whose projection maps near to 1 and far
 * to 0 (sr_camera.reversed_z), which spreads float precision evenly over
 * distance. The caller owns the memory: either sr_framebuffer_create/destroy,
 * or fill the struct with buffers of its own.
 */
#ifndef SOFTRAST_FRAMEBUFFER_H
#define SOFTRAST_FRAMEBUFFER_H

#include <stdbool.h>
#include <stdint.h>

#include "error.h"

#define SR_MAX_FRAMEBUFFER_SIDE 16384
#define SR_DEPTH_CLEAR 1.0f          /* standard: nothing drawn */
#define SR_DEPTH_CLEAR_REVERSED 0.0f /* reversed_z: nothing drawn */

typedef struct sr_framebuffer {
    int width, height;
    uint32_t *color; /* width * height */
    float *depth;    /* width * height */
    bool reversed_z; /* clear to 0, test GREATER */
} sr_framebuffer;

/* False (with a message) for a side < 1 or > SR_MAX_FRAMEBUFFER_SIDE, or out of memory. */
bool sr_framebuffer_create(sr_framebuffer *fb, int width, int height, sr_error *err);
void sr_framebuffer_destroy(sr_framebuffer *fb);
/* Color to `color`, depth to the clear value of fb's convention. */
void sr_framebuffer_clear(sr_framebuffer *fb, uint32_t color);

/* The clear value of fb's depth convention. */
float sr_framebuffer_depth_clear(const sr_framebuffer *fb);

/* The range of depths actually written (finite and not the clear value); false if none. */
bool sr_framebuffer_depth_range(const sr_framebuffer *fb, float *lo, float *hi);

/* Depth as gray into out (width * height, 0x00RRGGBB): the written range
 * maps from white (near) to dark gray (far), whichever the convention;
 * background is black. */
void sr_framebuffer_depth_to_gray(const sr_framebuffer *fb, uint32_t *out);

/* The same view of a function of depth that increases with distance, such as
 * the linear view distance (sr_camera_view_distance): the written range of
 * map(depth) goes from white (smallest) to dark gray. */
typedef double (*sr_depth_map)(float depth, const void *ctx);
void sr_framebuffer_depth_to_gray_mapped(const sr_framebuffer *fb, sr_depth_map map, const void *ctx,
                                         uint32_t *out);

#endif
