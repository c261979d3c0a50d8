/* tiny_queue.h — the depth tests and shading of tiny triangles' pixels,
 * deferred. Not public API. A tiny triangle of SR_INTERP_PERSPECTIVE, in a
 * layout the kernels were compiled for, queues its covered pixels with
 * their depths, their λ1 and λ2 (as every loop computes them) and its own
 * interpolants. When the queue is shaded, its pixels are depth-tested and
 * written in the queue's order, which is submission order, so each tests
 * against what the pixels before it wrote, as if drawn one triangle at a
 * time; a SIMD shader then colors those that passed SPAN_LANES pixels at a
 * time (4 or 8: the AVX-512 loop takes the AVX2 shader, simd_select.c),
 * each lane with its own triangle's interpolants, and stores the colors in
 * the queue's order. One triangle's few pixels filled few lanes of a
 * vector division, which costs the divider as much as several scalar
 * ones. Tested at the push, each pixel's depth load held up the
 * triangles behind it; tested in the queue, the loads of hundreds of
 * pixels are in flight at once (docs/performance.md, "Tiny triangles and
 * their queue"). */
#ifndef SOFTRAST_PIPELINE_TINY_QUEUE_H
#define SOFTRAST_PIPELINE_TINY_QUEUE_H

#include "tiny_batch.h"

/* A tiny triangle of SR_INTERP_PERSPECTIVE in a mode with varyings (the
 * rasterizer's call): its covered pixels queued on this thread's queue,
 * with their depths and its id, to be tested (and the id + 1 written where
 * fb has an ids plane) when it is shaded; true. False, and
 * nothing done, where no shader takes fb, shade and mode: the tiny loop
 * draws it then. */
bool sr_tiny_queue_push(const sr_tri_setup *s, sr_framebuffer *fb, sr_shade mode, const sr_shade_context *shade,
                        uint32_t triangle_id);

/* Tests and shades this thread's queued pixels, if any, and keeps the
 * context their shader was looked up for: the rasterizer calls it before
 * anything else it draws, since that tests against and draws over what is
 * queued. */
void sr_tiny_queue_drain(void);

/* Tests and shades the queued pixels of this thread's tiny triangles, if
 * any, forgets the context their shader was looked up for, and adds to
 * *fragments the pixels that passed their depth tests and to *draws the
 * triangles with one at least (the draws of a SIMD shader) since this
 * thread's last flush: the direct path and every tile call it when they
 * are done. sr_raster_triangle_on, sr_raster_triangle_in_box,
 * sr_raster_tiny_triangle and sr_raster_setup_draw may return with pixels
 * still queued, which their counts leave out: until this thread's flush,
 * the caller must neither change the shading context or the framebuffer
 * they were given nor clear or read its colors, depths or ids. */
void sr_tiny_queue_flush(uint64_t *fragments, uint64_t *draws);

#endif
