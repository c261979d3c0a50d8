/* direct.c — the direct path: each fan triangle straight to the rasterizer,
 * in submission order, as it leaves the primitive stages. */
#include <string.h>

#include "draw_state.h"
#include "pipeline/08_raster/raster.h"
#include "pipeline/08_raster/tiny_queue.h"

/* The direct path, on one thread: every fan triangle goes straight to the
 * rasterizer, over the whole framebuffer, in submission order. */
static uint32_t store_in_place(sr_fan_sink *sink, const sr_screen_vertex *v, int n)
{
    (void)sink, (void)v, (void)n;
    return 0; /* the rasterizer gets the vertices themselves, no references */
}

/* The observer's copy of a fan triangle: its vertices whole, with 0 in the
 * varyings past the layout's (a shared vertex is only
 * sr_draw_state.screen_stride bytes long, a clipped one whole). */
static void observe(const sr_draw_state *st, const sr_screen_vertex *const tri[3], bool clipped, uint32_t id)
{
    sr_screen_vertex copy[3] = { { 0 } };
    for (int k = 0; k < 3; k++)
        memcpy(&copy[k], tri[k], sr_screen_used(st->shade.layout.count));
    st->study.observer(st->study.observer_user, copy, clipped, id);
}

/* A triangle the sub-pixel lanes found covers the one pixel centre of its
 * scan box (one_pixel), in a mode with varyings, is drawn from that
 * one-bit mask, as the tiles draw a tiny triangle they tested while
 * binning: no coverage test. */
static void raster_now(sr_fan_sink *sink, const sr_screen_vertex *const tri[3], const uint32_t ref[3],
                       int64_t area2, uint32_t id, bool clipped, bool one_pixel)
{
    (void)ref;
    const sr_draw_state *st = sink->st;
    const sr_draw_study *s = &st->study;
    if (s->observer)
        observe(st, tri, clipped, id);
    bool simd = false;
    sink->pixels->stats.fragments +=
        (one_pixel ? sr_raster_one_pixel : sr_raster_triangle_on)(st->fb, sink->rect, st->vp.subpixel_bits, st->mode,
                                                                  &st->shade, tri, area2, id, &simd);
    sink->pixels->simd_draws += simd;
}

sr_fan_sink sr_direct_sink(const sr_draw_state *st, sr_thread_work *work, sr_raster_rect rect,
                           sr_thread_work *pixels)
{
    return (sr_fan_sink){ .store = store_in_place, .triangle = raster_now, .st = st, .work = work, .rect = rect,
                          .pixels = pixels,
                          .lane_pixels = st->subpixel_lanes && !sr_mode_reads_varyings(st->mode) };
}

/* Every slot on the direct path, counted in thread 0's work. */
void sr_draw_direct(void *ctx, int t)
{
    (void)t;
    sr_draw_state *st = ctx;
    sr_thread_work *w = &st->ws->threads[0];
    sr_fan_sink sink = sr_direct_sink(st, w, (sr_raster_rect){ 0, 0, st->fb->width, st->fb->height }, w);
    sr_draw_primitives(&sink, 0, st->slots);
    sr_tiny_queue_flush(&w->stats.fragments, &w->simd_draws);
}
