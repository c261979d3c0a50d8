/* tiny_batch.h — the tiny queue's pixels and triangles as its shaders read
 * them (tiny_queue.h queues them; the SIMD shaders in span_kernel.h color
 * them). Not public API. */
#ifndef SOFTRAST_PIPELINE_TINY_BATCH_H
#define SOFTRAST_PIPELINE_TINY_BATCH_H

#include "raster_setup.h"

#define SR_TINY_QUEUE_PIXELS 512
#define SR_TINY_QUEUE_TRIANGLES 128
enum {
    SR_TINY_IW0,
    SR_TINY_DIW1,
    SR_TINY_DIW2,
    SR_TINY_VAR0,
    SR_TINY_DVAR1 = SR_TINY_VAR0 + SR_MAX_VARYINGS,
    SR_TINY_DVAR2 = SR_TINY_DVAR1 + SR_MAX_VARYINGS,
    SR_TINY_PARAMS = SR_TINY_DVAR2 + SR_MAX_VARYINGS,
};

typedef struct sr_tiny_queue {
    int pixels, triangles;
    /* Per queued pixel, and a group of lanes past the last: the padding
     * repeats the last triangle with λ 0 and is never stored. */
    float l1[SR_TINY_QUEUE_PIXELS + SR_SIMD_MAX_LANES], l2[SR_TINY_QUEUE_PIXELS + SR_SIMD_MAX_LANES];
    int32_t triangle[SR_TINY_QUEUE_PIXELS + SR_SIMD_MAX_LANES];
    size_t at[SR_TINY_QUEUE_PIXELS + SR_SIMD_MAX_LANES];
    float z[SR_TINY_QUEUE_PIXELS]; /* the pixel's depth, tested when the queue is shaded */
    /* Per queued triangle, each interpolant a row (param[SR_TINY_VAR0 + k]
     * is var0[k]), a group of lanes long past the last: a group of pixels
     * spans at most SR_SIMD_MAX_LANES triangles, each having one pixel at
     * least, so a shader loads the group's first triangle's row on and
     * picks each lane's by its offset. */
    float param[SR_TINY_PARAMS][SR_TINY_QUEUE_TRIANGLES + SR_SIMD_MAX_LANES];
} sr_tiny_queue;

/* Colors the queue's pixels in fb (a shading mode with varyings, the
 * queued triangles' 1/w varying). */
typedef void (*sr_tiny_shader)(const sr_tiny_queue *q, const sr_shade_context *c, sr_framebuffer *fb);

#endif
