/* The tiled path, on one thread or several: set up triangles in chunks of
 * slots, bin the fan triangles into tiles, draw each tile on one thread in
 * submission order. A tile's pixels see the same triangles in the same
 * order with the same edge values as on the direct path, so the image is
 * bit-identical. */
#include <stdatomic.h>
#include <stdlib.h>

#include "draw_state.h"
#include "pipeline/07_cull.h"
#include "pipeline/08_raster/raster.h"
#include "pipeline/08_raster/triangle_setup.h"
#include "pipeline/08_raster/tiny_queue.h"
#include "target/framebuffer.h"

/* Slots go to the threads in chunks, about 8 a thread, so one that waits
 * for a core leaves its share to the others, but no smaller than the first
 * bound nor larger than the second: a thread walks the vertices of its
 * chunk in order, and a short chunk breaks that walk off sooner, so small
 * chunks cost the set-up more CPU. */
#define SETUP_CHUNKS_PER_THREAD 8
#define SETUP_CHUNK_MIN 256
#define SETUP_CHUNK_MAX 16384

static uint32_t setup_chunk(const sr_draw_state *st)
{
    if (st->study.chunk_slots)
        return st->study.chunk_slots;
    uint32_t size = st->slots / (SETUP_CHUNKS_PER_THREAD * (uint32_t)st->threads);
    return size < SETUP_CHUNK_MIN ? SETUP_CHUNK_MIN : size > SETUP_CHUNK_MAX ? SETUP_CHUNK_MAX : size;
}

typedef struct setup_phase {
    sr_draw_state *st;
    sr_chunks slots;
} setup_phase;

typedef struct raster_phase {
    sr_draw_state *st;
    atomic_int next_tile; /* the next turn: an index into the workspace's tile_order */
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

static int clamp_to(int v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* A scan box clamped to a tile: what sr_raster_scan_box_of gives on the
 * tile, since the tile lies inside the framebuffer. */
static sr_raster_rect box_in(sr_raster_rect box, sr_raster_rect tile)
{
    return (sr_raster_rect){ clamp_to(box.x0, tile.x0, tile.x1), clamp_to(box.y0, tile.y0, tile.y1),
                             clamp_to(box.x1, tile.x0, tile.x1), clamp_to(box.y1, tile.y0, tile.y1) };
}

/* Tile t: rows t * tile_rows on, across the whole framebuffer. */
static sr_raster_rect tile_rect(const sr_draw_state *st, int tile)
{
    int y1 = (tile + 1) * st->tile_rows;
    return (sr_raster_rect){ 0, tile * st->tile_rows, st->fb->width, y1 < st->fb->height ? y1 : st->fb->height };
}

/* A tile's estimated cost, in pixels drawn: a triangle costs as much as
 * this many pixels to set up and start, and draws all of its share's
 * pixels when it covers the share whole, about half otherwise. */
#define SETUP_PIXELS 64

static uint64_t entry_cost(sr_raster_rect share, sr_box_cover c)
{
    uint64_t area = (uint64_t)(share.x1 - share.x0) * (uint64_t)(share.y1 - share.y0);
    return SETUP_PIXELS + (c == SR_COVER_ALL ? area : area / 2);
}

/* A new entry at the end of a tile's bin, its estimated cost counted;
 * NULL when out of memory. */
static sr_bin_entry *bin_push(sr_thread_work *w, sr_bin *bin, uint64_t cost)
{
    sr_bin_entry *e = sr_array_push(&bin->entries, sizeof *e);
    if (!e) {
        w->out_of_memory = true;
        return NULL;
    }
    bin->cost += cost;
    return e;
}

/* A triangle whose scan box spans several tiles is set up here, once (as
 * llvmpipe's set-up does before binning), and goes only to the tiles whose
 * share of the box its edges reach, each entry saying whether the share is
 * covered whole. One within a tile is set up by the tile, from its entry;
 * if its box is tiny, its pixel centres are tested here, while its vertices
 * are in L1: one that covers none gets no entry (many do, in a dense
 * mesh), and the others' entries carry the mask, so the tile does not
 * test them again. */
static void bin_triangle(sr_fan_sink *sink, const sr_screen_vertex *const tri[3], const uint32_t ref[3],
                         int64_t area2, uint32_t id, bool clipped, bool one_pixel)
{
    (void)clipped, (void)one_pixel; /* a tiny triangle's mask is found while binning */
    sr_thread_work *w = sink->work;
    const sr_draw_state *st = sink->st;
    sr_raster_rect all = { 0, 0, st->fb->width, st->fb->height };
    sr_raster_rect box = sr_raster_scan_box_of(tri, all, st->vp.subpixel_bits);
    if (box.x0 >= box.x1 || box.y0 >= box.y1)
        return; /* covers no pixel centre: no entry */
    int first = box.y0 / st->tile_rows, last = (box.y1 - 1) / st->tile_rows;
    if (first == last) {
        bool tiny_box = sr_raster_box_is_tiny(box);
        uint64_t tiny = tiny_box ? sr_raster_tiny_mask(tri, area2, box, st->vp.subpixel_bits) : 0;
        if (tiny_box && !tiny)
            return; /* covers no pixel centre: no entry */
        sr_bin_entry *e = bin_push(w, &w->bins[first], entry_cost(box, SR_COVER_PARTIAL));
        if (e)
            *e = (sr_bin_entry){ .ref = { ref[0], ref[1], ref[2] }, .id = id, .tiny = tiny };
        return;
    }
    /* Past UINT32_MAX set-ups an entry could not name the next. */
    sr_tri_setup *setup = w->setups.count < UINT32_MAX ? sr_array_push(&w->setups, sizeof *setup) : NULL;
    if (!setup) {
        w->out_of_memory = true;
        return;
    }
    if (!sr_raster_setup(tri, area2, box, st->vp.subpixel_bits, st->mode, &st->shade, setup)) {
        w->setups.count--; /* no pixel of the box is inside: no entry */
        return;
    }
    uint32_t index = (uint32_t)(w->setups.count - 1);
    for (int tile = first; tile <= last; tile++) {
        sr_raster_rect share = box_in(box, tile_rect(st, tile));
        sr_box_cover c = sr_raster_classify(setup, share);
        sr_bin_entry *e = c != SR_COVER_NONE ? bin_push(w, &w->bins[tile], entry_cost(share, c)) : NULL;
        if (e)
            *e = (sr_bin_entry){ .stored = { index, c == SR_COVER_ALL }, .id = id | SR_BIN_STORED };
    }
}

static bool work_reset(sr_thread_work *w, size_t tiles)
{
    if (w->bin_count < tiles) {
        sr_bin *bins = realloc(w->bins, tiles * sizeof *bins);
        if (!bins)
            return false;
        for (size_t i = w->bin_count; i < tiles; i++)
            bins[i] = (sr_bin){ { 0 } };
        w->bins = bins;
        w->bin_count = tiles;
    }
    for (size_t i = 0; i < tiles; i++) {
        w->bins[i].entries.count = 0;
        w->bins[i].cost = 0;
    }
    w->clip_verts.count = 0;
    w->setups.count = 0;
    w->out_of_memory = false;
    return true;
}

static void setup_chunks(void *ctx, int t)
{
    setup_phase *ph = ctx;
    sr_draw_state *st = ph->st;
    sr_thread_work *w = &st->ws->threads[t];
    if (!work_reset(w, (size_t)st->tiles)) {
        w->out_of_memory = true;
        return;
    }
    uint32_t first, end;
    sr_fan_sink sink = { .store = store_clip_verts, .triangle = bin_triangle, .st = st, .work = w };
    while (sr_chunks_take(&ph->slots, &first, &end))
        sr_draw_primitives(&sink, first, end);
}

static const sr_screen_vertex *vertex_of(const sr_draw_state *st, const sr_thread_work *binner, uint32_t ref)
{
    if (ref < st->vertex_count)
        return sr_screen_at(st, ref);
    return &((const sr_screen_vertex *)binner->clip_verts.data)[ref - st->vertex_count];
}

static const sr_bin_entry *entry_at(const sr_thread_work *w, int tile, size_t i)
{
    return &((const sr_bin_entry *)w->bins[tile].entries.data)[i];
}

static uint32_t id_of(const sr_bin_entry *e)
{
    return e->id & ~SR_BIN_STORED;
}

/* One bin entry's triangle over the tile's share of its scan box. */
static uint64_t raster_entry(const sr_draw_state *st, const sr_thread_work *w, const sr_bin_entry *e,
                             sr_raster_rect tile, bool *simd)
{
    if (e->id & SR_BIN_STORED) {
        sr_tri_setup s = ((const sr_tri_setup *)w->setups.data)[e->stored.setup];
        sr_raster_setup_share(&s, box_in(s.box, tile), e->stored.covered);
        return sr_raster_setup_draw(st->fb, &s, st->mode, &st->shade, id_of(e), simd);
    }
    const sr_screen_vertex *const tri[3] = { vertex_of(st, w, e->ref[0]), vertex_of(st, w, e->ref[1]),
                                             vertex_of(st, w, e->ref[2]) };
    /* The box lies within the tile: clamped to it, it is the one binned. */
    sr_raster_rect box = sr_raster_scan_box_of(tri, tile, st->vp.subpixel_bits);
    int64_t area2 = sr_cull_area2(tri[0], tri[1], tri[2]);
    if (e->tiny)
        return sr_raster_tiny_triangle(st->fb, box, st->vp.subpixel_bits, st->mode, &st->shade, tri, area2,
                                       e->tiny, e->id, simd);
    return sr_raster_triangle_in_box(st->fb, box, st->vp.subpixel_bits, st->mode, &st->shade, tri, area2,
                                     e->id, simd);
}

/* A tile prefetches the screen vertices (or the stored set-up) of the
 * entry this many entries ahead: its triangles are set up from vertices
 * and set-ups the binning wrote and read long before, which have left the
 * cache since; without the prefetch the tile waits for each of them, the
 * copy of a stored set-up most of all. */
#define PREFETCH_ENTRIES 8

/* The binning threads' lists for the tile merged by slot: a slot's fan
 * triangles are all one thread's, each walked in slot order, so the merge
 * is submission order. */
static uint64_t raster_tile(const sr_draw_state *st, int tile, uint64_t *simd_draws)
{
    sr_raster_rect rect = tile_rect(st, tile);
    if (st->desc->clear)
        sr_framebuffer_clear_rows(st->fb, rect.y0, rect.y1, st->desc->clear_color);
    uint64_t fragments = 0;
    size_t at[SR_MAX_THREADS] = { 0 }; /* each thread's next entry in the tile's list */
    for (;;) {
        /* The thread whose next entry comes first, drawn up to the first
         * entry of the others'. */
        int from = -1;
        uint32_t first_id = 0, others_id = UINT32_MAX;
        for (int t = 0; t < st->threads; t++) {
            const sr_thread_work *u = &st->ws->threads[t];
            if (at[t] == u->bins[tile].entries.count)
                continue;
            uint32_t id = id_of(entry_at(u, tile, at[t]));
            if (from < 0 || id < first_id) {
                others_id = from < 0 ? others_id : first_id;
                from = t;
                first_id = id;
            } else if (id < others_id) {
                others_id = id;
            }
        }
        if (from < 0) {
            sr_tiny_queue_flush(&fragments, simd_draws);
            return fragments;
        }
        const sr_thread_work *w = &st->ws->threads[from];
        size_t *b = &at[from], end = w->bins[tile].entries.count;
        for (; *b < end; (*b)++) {
            /* In the loop's body: gcc drops a call of a function of prefetches. */
            if (end - *b > PREFETCH_ENTRIES) {
                const sr_bin_entry *ahead = entry_at(w, tile, *b + PREFETCH_ENTRIES);
                if (!(ahead->id & SR_BIN_STORED)) {
                    __builtin_prefetch(vertex_of(st, w, ahead->ref[0]));
                    __builtin_prefetch(vertex_of(st, w, ahead->ref[1]));
                    __builtin_prefetch(vertex_of(st, w, ahead->ref[2]));
                } else {
                    const char *setup =
                        (const char *)&((const sr_tri_setup *)w->setups.data)[ahead->stored.setup];
                    for (size_t line = 0; line < sizeof(sr_tri_setup); line += 64)
                        __builtin_prefetch(setup + line);
                }
            }
            const sr_bin_entry *entry = entry_at(w, tile, *b);
            if (id_of(entry) > others_id)
                break;
            bool simd = false;
            fragments += raster_entry(st, w, entry, rect, &simd);
            *simd_draws += simd;
        }
    }
}

/* Tiles go out from one counter, the costliest first, so that when a few
 * tiles hold most of the work (a small dense mesh) they start at once and
 * the cheap ones fill in around them; no thread is left drawing a heavy
 * tile alone at the end. Tiles of about the same cost (within a factor of
 * two) go in turns over one band of tiles per thread, not screen order:
 * turn k is tile k / T of band k % T. Handed out in screen order, the tile
 * one thread draws borders another's, and the hardware prefetcher of one
 * core keeps reading the rows the other core is writing (square tiles had
 * that border on every row: docs/performance.md, "Tried and not kept").
 * Strips of whole rows border each other once per strip, not once per row. */
static int tile_of_turn(const sr_draw_state *st, int turn, int band_tiles)
{
    return turn % st->threads * band_tiles + turn / st->threads;
}

static uint64_t tile_cost(const sr_draw_state *st, int tile)
{
    uint64_t cost = 0;
    for (int t = 0; t < st->threads; t++)
        cost += st->ws->threads[t].bins[tile].cost;
    return cost;
}

#define COST_CLASSES 64 /* bit lengths of a 64-bit cost */

static int cost_class(uint64_t cost)
{
    return cost ? 63 - __builtin_clzll(cost) : 0;
}

/* The tiles by class of cost, costliest first, band turns within a class
 * (a counting sort: two passes over the tiles). */
static bool order_tiles(sr_draw_state *st)
{
    int tiles = st->tiles, band_tiles = (tiles + st->threads - 1) / st->threads;
    if (!sr_array_reserve(&st->ws->tile_order, (size_t)tiles, sizeof(int)))
        return false;
    int *order = st->ws->tile_order.data;
    int start[COST_CLASSES + 1] = { 0 };
    for (int turn = 0; turn < band_tiles * st->threads; turn++) {
        int tile = tile_of_turn(st, turn, band_tiles);
        if (tile < tiles) /* the last band may be short */
            start[COST_CLASSES - 1 - cost_class(tile_cost(st, tile)) + 1]++;
    }
    for (int c = 0; c < COST_CLASSES; c++)
        start[c + 1] += start[c];
    for (int turn = 0; turn < band_tiles * st->threads; turn++) {
        int tile = tile_of_turn(st, turn, band_tiles);
        if (tile < tiles)
            order[start[COST_CLASSES - 1 - cost_class(tile_cost(st, tile))]++] = tile;
    }
    return true;
}

static void raster_tiles(void *ctx, int t)
{
    raster_phase *ph = ctx;
    const sr_draw_state *st = ph->st;
    int tiles = st->tiles;
    const int *order = st->ws->tile_order.data;
    sr_thread_work *w = &st->ws->threads[t];
    for (int turn = atomic_fetch_add(&ph->next_tile, 1); turn < tiles; turn = atomic_fetch_add(&ph->next_tile, 1))
        w->stats.fragments += raster_tile(st, order[turn], &w->simd_draws);
}

bool sr_draw_binned(sr_draw_state *st)
{
    sr_draw_times *times = st->study.times;
    setup_phase setup = { .st = st };
    sr_chunks_init(&setup.slots, st->slots, setup_chunk(st));
    sr_parallel_run(&st->ws->pool, st->threads, setup_chunks, &setup, times ? &times->primitives : NULL);
    for (int t = 0; t < st->threads; t++)
        if (st->ws->threads[t].out_of_memory)
            return false;
    if (!order_tiles(st))
        return false;
    raster_phase ph = { .st = st };
    atomic_init(&ph.next_tile, 0);
    sr_parallel_run(&st->ws->pool, st->threads, raster_tiles, &ph, times ? &times->raster : NULL);
    return true;
}
