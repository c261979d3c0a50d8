/* The threaded path: set up triangles in slot ranges, bin the fan triangles
 * into tiles, draw each tile on one thread in submission order. A tile's
 * pixels see the same triangles in the same order with the same edge values
 * as in the one-thread path, so the image is bit-identical. */
#include <stdatomic.h>
#include <stdlib.h>

#include "draw_internal.h"
#include "raster.h"

typedef struct raster_phase {
    sr_draw_state *st;
    atomic_int next_tile;
} raster_phase;

static uint32_t store_clip_verts(sr_fan_sink *sink, const sr_screen_vertex *v, int n)
{
    sr_array *a = &sink->work->clip_verts;
    uint32_t first = sink->st->vertex_count + (uint32_t)a->count;
    if (!sr_array_reserve(a, a->count + (size_t)n, sizeof *v)) {
        sink->work->out_of_memory = true;
        return first;
    }
    for (int i = 0; i < n; i++)
        ((sr_screen_vertex *)a->data)[a->count++] = v[i];
    return first;
}

/* The tiles the triangle's scan box touches get its record index. */
static void bin_triangle(sr_fan_sink *sink, const sr_screen_vertex *const tri[3], const uint32_t ref[3],
                         int64_t area2, uint32_t id, bool clipped)
{
    (void)clipped;
    sr_thread_work *w = sink->work;
    const sr_draw_state *st = sink->st;
    sr_record *rec = sr_array_push(&w->records, sizeof *rec);
    if (!rec) {
        w->out_of_memory = true;
        return;
    }
    *rec = (sr_record){ .ref = { ref[0], ref[1], ref[2] }, .id = id, .area2 = area2 };
    uint32_t index = (uint32_t)(w->records.count - 1);
    sr_raster_rect all = { 0, 0, st->fb->width, st->fb->height };
    sr_raster_rect box = sr_raster_scan_box_of(tri, all, st->vp.subpixel_bits);
    if (box.x0 >= box.x1 || box.y0 >= box.y1)
        return; /* covers no pixel centre */
    int tx0 = box.x0 / SR_TILE_SIDE, tx1 = (box.x1 - 1) / SR_TILE_SIDE;
    int ty0 = box.y0 / SR_TILE_SIDE, ty1 = (box.y1 - 1) / SR_TILE_SIDE;
    for (int ty = ty0; ty <= ty1; ty++) {
        for (int tx = tx0; tx <= tx1; tx++) {
            uint32_t *slot = sr_array_push(&w->bins[ty * st->tiles_x + tx], sizeof *slot);
            if (!slot) {
                w->out_of_memory = true;
                return;
            }
            *slot = index;
        }
    }
}

static bool work_reset(sr_thread_work *w, size_t tiles)
{
    if (w->bin_count < tiles) {
        sr_array *bins = realloc(w->bins, tiles * sizeof *bins);
        if (!bins)
            return false;
        for (size_t i = w->bin_count; i < tiles; i++)
            bins[i] = (sr_array){ 0 };
        w->bins = bins;
        w->bin_count = tiles;
    }
    for (size_t i = 0; i < tiles; i++)
        w->bins[i].count = 0;
    w->clip_verts.count = 0;
    w->records.count = 0;
    w->out_of_memory = false;
    return true;
}

static void setup_range(void *ctx, int t)
{
    sr_draw_state *st = ctx;
    sr_thread_work *w = &st->ws->threads[t];
    if (!work_reset(w, (size_t)st->tiles_x * (size_t)st->tiles_y)) {
        w->out_of_memory = true;
        return;
    }
    sr_fan_sink sink = { .store = store_clip_verts, .triangle = bin_triangle, .st = st, .work = w };
    uint32_t first = (uint32_t)((uint64_t)st->slots * t / st->threads);
    uint32_t end = (uint32_t)((uint64_t)st->slots * (t + 1) / st->threads);
    sr_draw_primitives(&sink, first, end);
}

static const sr_screen_vertex *vertex_of(const sr_draw_state *st, const sr_thread_work *binner, uint32_t ref)
{
    if (ref < st->vertex_count)
        return &((const sr_screen_vertex *)st->ws->screen.data)[ref];
    return &((const sr_screen_vertex *)binner->clip_verts.data)[ref - st->vertex_count];
}

/* Every binning thread's list for the tile, in thread order: thread t set up
 * the slots before thread t + 1's, so this is submission order. */
static uint64_t raster_tile(const sr_draw_state *st, int tile, uint64_t *simd_draws)
{
    int tx = tile % st->tiles_x, ty = tile / st->tiles_x;
    sr_raster_rect rect = { tx * SR_TILE_SIDE, ty * SR_TILE_SIDE, (tx + 1) * SR_TILE_SIDE, (ty + 1) * SR_TILE_SIDE };
    rect.x1 = rect.x1 < st->fb->width ? rect.x1 : st->fb->width;
    rect.y1 = rect.y1 < st->fb->height ? rect.y1 : st->fb->height;
    uint64_t fragments = 0;
    for (int t = 0; t < st->threads; t++) {
        const sr_thread_work *w = &st->ws->threads[t];
        const uint32_t *list = w->bins[tile].data;
        for (size_t i = 0; i < w->bins[tile].count; i++) {
            const sr_record *rec = &((const sr_record *)w->records.data)[list[i]];
            const sr_screen_vertex *const tri[3] = { vertex_of(st, w, rec->ref[0]), vertex_of(st, w, rec->ref[1]),
                                                     vertex_of(st, w, rec->ref[2]) };
            bool simd = false;
            fragments += sr_raster_triangle_on(st->fb, rect, st->vp.subpixel_bits, st->mode, &st->shade,
                                               tri, rec->area2, rec->id, &simd);
            *simd_draws += simd;
        }
    }
    return fragments;
}

static void raster_tiles(void *ctx, int t)
{
    raster_phase *ph = ctx;
    const sr_draw_state *st = ph->st;
    int tiles = st->tiles_x * st->tiles_y;
    sr_thread_work *w = &st->ws->threads[t];
    for (int tile = atomic_fetch_add(&ph->next_tile, 1); tile < tiles; tile = atomic_fetch_add(&ph->next_tile, 1))
        w->stats.fragments += raster_tile(st, tile, &w->simd_draws);
}

bool sr_draw_binned(sr_draw_state *st)
{
    sr_draw_times *times = st->study.times;
    sr_parallel_run(st->threads, setup_range, st, times ? &times->primitives : NULL);
    for (int t = 0; t < st->threads; t++)
        if (st->ws->threads[t].out_of_memory)
            return false;
    raster_phase ph = { .st = st };
    atomic_init(&ph.next_tile, 0);
    sr_parallel_run(st->threads, raster_tiles, &ph, times ? &times->raster : NULL);
    return true;
}
