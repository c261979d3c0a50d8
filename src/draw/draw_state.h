/* draw_state.h — what the draw call's own files share: the per-draw
 * state, the workspace's layout, and the fan-triangle sink that lets one
 * primitive stage (assembly to culling) feed either the rasterizer directly
 * (the direct path, one thread) or the tile bins (the tiled path, one
 * thread or several). Not public API. */
#ifndef SOFTRAST_DRAW_INTERNAL_H
#define SOFTRAST_DRAW_INTERNAL_H

#include <pthread.h>
#include <stdatomic.h>
#include <stddef.h>

#include "pipeline/02_assemble.h"
#include "pipeline/04_clip/clip.h"
#include "core/array.h"
#include "pipeline/08_raster/raster.h"
#include "pipeline/08_raster/raster_setup.h"
#include "pipeline/08_raster/subpixel.h"
#include "softrast/softrast.h"
#include "softrast/study.h"
#include "pipeline/01_vertex.h"
#include "pipeline/06_viewport.h"

#define SR_MAX_THREADS 64
/* The row-band path (row_bands.c) splits the rows between its threads in bands
 * of ⌈height / SR_ROW_BANDS⌉ rows, at most this many (below 255, the band
 * of none). */
#define SR_ROW_BANDS 254

/* The rows of each band of a framebuffer `height` rows tall, and its bands. */
static inline int sr_band_rows(int height)
{
    return (height + SR_ROW_BANDS - 1) / SR_ROW_BANDS;
}

static inline int sr_band_count(int height)
{
    int rows = sr_band_rows(height);
    return (height + rows - 1) / rows;
}
/* The fragments a point or line draw on several threads bins at most
 * before it stores them, all its threads together (16 bytes each;
 * points_lines.c): the slots go in rounds that cannot bin more (rounds in
 * slot order keep each band's fragments in it), and a thread whose bins
 * keep room for more than its share frees them before the next draw. So
 * no input, and no run of draws on one workspace, makes the bins take
 * gigabytes. */
#define SR_FRAGMENT_BIN_BUDGET ((size_t)1 << 23)

/* Snapped coordinates stay below 2^SR_FIXED_POINT_BITS so the 64-bit edge
 * functions cannot overflow whatever the precision asked for. */
#define SR_FIXED_POINT_BITS 30

/* A fan triangle in a tile's bin: its id and either, for one within the
 * tile, its three vertices as references (below the mesh's vertex count:
 * the shared screen vertex; from there on: the binning thread's clip
 * vertices), from which the tile finds its scan box and area and sets it
 * up, and a tiny box's covered pixels (0 for a box that is not tiny), or,
 * for one whose box spans tiles (SR_BIN_STORED in its id), its set-up in
 * the binning thread's `setups`, which holds its scan box, and whether the
 * tile's share of that box is covered whole (sr_raster_classify), so its
 * rows need no solving. 24 bytes, written into the bin itself: the tile
 * reads its bin from start to end, with no record elsewhere to wait for,
 * and what it can find again from the vertices it reads anyway is not
 * written and read back through memory. */
typedef struct sr_bin_entry {
    union {
        uint32_t ref[3];
        struct {
            uint32_t setup;
            uint32_t covered;
        } stored;
    };
    uint32_t id;   /* the slot's, SR_BIN_STORED or'd in: draws of more than 2^31 slots take the direct path */
    uint64_t tiny; /* sr_raster_tiny_mask, never 0 for a tiny box */
} sr_bin_entry;

/* An entry's id flag: its triangle was set up while binning (`stored`). */
#define SR_BIN_STORED 0x80000000u

/* One thread's list of a tile: bin entries, and the estimated cost of
 * drawing them (tiles.c, tile_cost), which orders the tiles. */
typedef struct sr_bin {
    sr_array entries; /* sr_bin_entry */
    uint64_t cost;
} sr_bin;

/* One thread's share of a draw: its counts, and in the binned path the clip
 * vertices, set-ups and per-tile bins it made. Aligned
 * apart so one thread's counters never share a cache line with another's. */
#define SR_CACHE_LINE 128
typedef struct sr_thread_work {
    _Alignas(SR_CACHE_LINE) sr_stats stats;
    sr_clip_counts cuts;
    uint64_t simd_draws; /* rasterizer calls a SIMD kernel made */
    sr_array clip_verts; /* sr_screen_vertex */
    sr_array setups;     /* sr_tri_setup, of the triangles that span tiles */
    sr_bin *bins;        /* one per tile */
    size_t bin_count;
    sr_array *fragment_bins; /* sr_fragment, one per band of rows: a point or line draw's on several threads */
    size_t fragment_bin_count;
    bool out_of_memory;
    bool index_past_end; /* in the thread's share of the indices */
    unsigned outcodes_and; /* of the thread's vertices: a plane all are outside of */
    uint32_t band_triangles[SR_ROW_BANDS]; /* of the slots it gave a verdict, kept ones inside every plane per first band (row_bands.c) */
    double band_cpu_ms; /* the CPU time it drew its band of rows in (row_bands.c) */
} sr_thread_work;

/* A worker thread of the pool: its index t, and the phases it is handed.
 * Each on its own cache line: a waiting worker polls its `go`. */
typedef struct sr_worker {
    _Alignas(SR_CACHE_LINE) atomic_uint_fast64_t go; /* the last phase handed to it */
    uint64_t seen;       /* the last phase it ran: its own */
    pthread_cond_t wake; /* go moved on, or the pool is stopping */
    bool sleeping;       /* in pthread_cond_wait on wake: under the pool's lock */
    pthread_t id;
    struct sr_pool *pool;
    int t;
    double cpu_ms; /* its CPU time in the phase's fn, when timed */
} sr_worker;

/* The workspace's threads 1 .. started-1 (threads.c): started the first
 * time a draw asks for more threads than there are, asleep between draws,
 * joined when the workspace is destroyed. */
typedef struct sr_pool {
    pthread_mutex_t lock;
    pthread_cond_t done;   /* pending reached 0 */
    bool caller_sleeping;  /* in pthread_cond_wait on done: under lock */
    bool stopping;         /* under lock */
    atomic_int pending;    /* the phase's workers whose fn has not returned */
    int started;           /* 0 (lock and done not initialized yet), or 1 + the workers running: the caller's */
    uint64_t phase;        /* phases handed out: the caller's */
    void (*fn)(void *ctx, int t); /* the phase's, written before go moves on */
    void *ctx;
    bool timed;
    sr_worker workers[SR_MAX_THREADS]; /* [0] unused: thread 0 is the caller */
} sr_pool;

/* What the row-band path's last draw with the workspace measured
 * (row_bands.c): each band's CPU time per kept triangle inside, that of the
 * thread that drew it. The next draw of the same mesh into as many rows
 * splits them by it (a frame of several meshes splits each by counts). */
typedef struct sr_band_costs {
    int height; /* the framebuffer's, of the draw that measured them; 0: none yet */
    const sr_mesh *mesh; /* the draw's, and its slots */
    uint32_t slots;
    double per_triangle[SR_ROW_BANDS];
} sr_band_costs;

struct sr_workspace {
    sr_pool pool;
    sr_array outcodes; /* unsigned char */
    sr_array snapped_points; /* sr_snapped_point of each vertex, when st->snapped_points */
    sr_array screen;   /* screen vertices, sr_draw_state.screen_stride bytes apart, valid where the outcode is 0 */
    sr_array tile_order; /* int: the binned path's tiles in the order they are handed out */
    sr_array double_wanted; /* atomic_uchar: whether a kept triangle uses a vertex inside, which then needs its
                               double half (mapped as the verdicts keep it on one thread, in a phase after them
                               on several), when st->double_later */
    sr_array band_slots;   /* sr_band_slot: the row-band path's kept slots, each chunk's from its first slot on */
    sr_array chunk_kept;   /* uint32_t: how many slots each chunk of the verdicts kept in band_slots */
    sr_array material_shades; /* sr_shade_context: a mesh's materials' (materials.c) */
    sr_band_costs band_costs; /* of the row-band path's last draw */
    sr_thread_work threads[SR_MAX_THREADS];
};

/* The per-draw state every stage reads. */
typedef struct sr_draw_state {
    sr_framebuffer *fb;
    const sr_draw_desc *desc;
    sr_draw_study study; /* desc's, or the defaults */
    sr_shade mode;       /* desc's shading, or SR_RASTER_COUNT_HITS */
    sr_shade_context shade;
    sr_viewport vp;
    size_t screen_stride; /* sr_screen_stride of the layout */
    const sr_vertex_transform *xf; /* the vertex phase's: clip from object, float and double */
    sr_clip_precision precision;
    double clip_tolerance; /* NDC error a cut vertex may carry: half a subpixel step */
    sr_workspace *ws;
    int threads;
    uint32_t vertex_count, slots;
    int tile_rows, tiles; /* the binned path's tiles: strips of whole rows */
    int band_rows;        /* > 0: the row bands' rows a band, from each kept slot's snapped points */
    bool subpixel_lanes;  /* the sub-pixel lanes drop the triangles that draw nothing (primitives.c) */
    bool slot_lanes;      /* and take a triangle list's verdicts eight slots at a time (primitives.c) */
    bool snapped_points;  /* the vertex phase notes each vertex's snapped point: for the slot lanes, the row bands */
    bool double_later;    /* the vertex phase maps the float half of the vertices inside, the verdicts
                             the double half of those of the triangles they keep, or a phase after
                             them (double_phase; primitives.c) */
    bool double_phase;    /* with double_later, the row bands' several threads: the verdicts mark the
                             vertices wanted and a phase after them maps them (sr_draw_double_halves);
                             else the one thread that takes every verdict maps them as it keeps triangles */
    sr_subpixel_rules subpixel;
    const struct sr_line_filter *line_filter; /* a line draw's, or NULL (draw.h) */
} sr_draw_state;

/* The bytes of an sr_screen_vertex up to its last varying, with
 * `varyings` of them: all that a draw's rasterizer reads of it. */
static inline size_t sr_screen_used(int varyings)
{
    _Static_assert(offsetof(sr_screen_vertex, var_w) + sizeof(((sr_screen_vertex *)0)->var_w) ==
                       sizeof(sr_screen_vertex),
                   "var_w is the screen vertex's last member: the stride cuts the vertex after its varyings");
    return offsetof(sr_screen_vertex, var_w) + (size_t)varyings * sizeof(float);
}

/* The bytes between the shared screen vertices of a draw whose layout has
 * `varyings` varyings: an sr_screen_vertex up to its last varying, rounded
 * up to 16 bytes (32 in depth and id shading; 48 in texture, color, normal
 * and gray lambert; 64 in lambert with a uv or colors). The vertex phase
 * writes them and the rasterizer reads them only up to
 * var_w[varyings − 1], so a smaller array carries the same vertices: less
 * memory to write and read back (docs/performance.md, "The vertex
 * phase"). A pointer to one (sr_screen_at) points at fewer
 * bytes than an sr_screen_vertex: read its members, never copy it whole. */
static inline size_t sr_screen_stride(int varyings)
{
    return (sr_screen_used(varyings) + 15) / 16 * 16;
}

/* The shared screen vertex i of the draw. */
static inline sr_screen_vertex *sr_screen_at(const sr_draw_state *st, uint32_t i)
{
    return (sr_screen_vertex *)((char *)st->ws->screen.data + (size_t)i * st->screen_stride);
}

/* Receives the fan triangles that survive culling. `store` keeps a clipped
 * polygon's screen vertices for the triangles that follow and returns the
 * reference of the first (refs count on from there). */
typedef struct sr_fan_sink sr_fan_sink;
struct sr_fan_sink {
    uint32_t (*store)(sr_fan_sink *sink, const sr_screen_vertex *v, int n);
    /* one_pixel: the sub-pixel lanes found its scan box holds one pixel
     * centre, which it covers (sr_kept_slot.box), so its edges need not be
     * tested again. */
    void (*triangle)(sr_fan_sink *sink, const sr_screen_vertex *const tri[3], const uint32_t ref[3], int64_t area2,
                     uint32_t id, bool clipped, bool one_pixel);
    const sr_draw_state *st;
    sr_thread_work *work; /* counts the triangles */
    /* Drawing as they come (draw.c's direct path, row_bands.c): the rows
     * drawn, and the work that counts their fragments. */
    sr_raster_rect rect;
    sr_thread_work *pixels;
    /* And in a mode without varyings, the triangles the sub-pixel lanes
     * found small (sr_kept_slot.box) are not handed to `triangle`: their
     * batch's pixels and depths are found together
     * (pipeline/08_raster/lane_pixels.h), then each is drawn from those. */
    bool lane_pixels;
};

/* Stages 2 to 7 for triangle slots [first, end): assembly, classification,
 * clipping, fan, viewport (of cut vertices) and culling, into sink. */
void sr_draw_primitives(sr_fan_sink *sink, uint32_t first, uint32_t end);

/* Stages 2 and 3 for slot k: its indices into idx, counted in stats, and
 * the OR of its vertices' outcodes (0: inside every plane), or
 * SR_SLOT_GONE when it has no triangle (a strip's degenerate or restart
 * slot) or was rejected (counted). */
#define SR_SLOT_GONE (~0u)
static inline unsigned sr_slot_verdict(const sr_mesh *mesh, const unsigned char *outcodes, sr_stats *stats,
                                       uint32_t k, uint32_t idx[3])
{
    if (!sr_assemble_triangle(mesh, k, idx))
        return SR_SLOT_GONE;
    stats->triangles++;
    unsigned c0 = outcodes[idx[0]], c1 = outcodes[idx[1]], c2 = outcodes[idx[2]], any = c0 | c1 | c2;
    if (any & SR_OUT_NONFINITE) {
        stats->rejected++;
        stats->nonfinite++;
        return SR_SLOT_GONE;
    }
    if (c0 & c1 & c2) {
        sr_clip_count_rejected(stats, c0 & c1 & c2, 1);
        return SR_SLOT_GONE;
    }
    return any;
}

/* What the sub-pixel lanes found of a kept triangle's scan box
 * (sr_subpixel_verdict): nothing (they did not decide it), one pixel
 * centre, which it covers (one_pixel), or two to SR_SUBPIXEL_SPAN ×
 * SR_SUBPIXEL_SPAN centres (small_box). */
typedef enum sr_lane_box { SR_LANE_BOX_UNKNOWN, SR_LANE_BOX_ONE_PIXEL, SR_LANE_BOX_SMALL } sr_lane_box;

/* The box a lane's verdict gives triangle j of its batch. */
static inline unsigned char sr_lane_box_of(const sr_subpixel_verdict *v, int j)
{
    return (v->one_pixel >> j & 1) ? SR_LANE_BOX_ONE_PIXEL
           : (v->small_box >> j & 1) ? SR_LANE_BOX_SMALL
                                      : SR_LANE_BOX_UNKNOWN;
}

/* A slot the verdicts kept: its triangle's indices, the OR of their
 * outcodes (sr_slot_verdict), and what the sub-pixel lanes found of its
 * scan box (sr_lane_box). */
typedef struct sr_kept_slot {
    uint32_t k, idx[3];
    unsigned planes;
    unsigned char box;
} sr_kept_slot;

/* The slots whose verdicts are taken at a time: the sub-pixel lanes' batch. */
#define SR_VERDICT_BATCH SR_SUBPIXEL_BATCH

/* Stages 2 and 3 for slots [first, end), at most SR_VERDICT_BATCH of them,
 * and with st->subpixel_lanes the sub-pixel lanes: the slots that may
 * draw into kept[], in order, their screen vertices prefetched, counted in
 * stats as far as decided (a triangle the lanes drop is counted culled or
 * drawn there); returns how many. The indices are prefetched up to the
 * draw's last slot, before last_end. */
int sr_draw_verdicts(const sr_draw_state *st, uint32_t first, uint32_t end, uint32_t last_end, sr_stats *stats,
                     sr_kept_slot *kept);

/* Adds every count of `from` to `to`. */
static inline void sr_stats_add(sr_stats *to, const sr_stats *from)
{
    to->triangles += from->triangles;
    to->rejected += from->rejected;
    to->nonfinite += from->nonfinite;
    to->clipped += from->clipped;
    to->culled += from->culled;
    to->drawn += from->drawn;
    to->fragments += from->fragments;
    to->cuts_float += from->cuts_float;
    to->cuts_double += from->cuts_double;
    to->cuts_exact += from->cuts_exact;
    for (int p = 0; p < SR_CLIP_PLANES; p++)
        to->rejected_by_plane[p] += from->rejected_by_plane[p];
    to->points += from->points;
    to->lines += from->lines;
}

/* The bands of rows a slot's triangle may cover: every band when a vertex
 * lies outside a plane. */
typedef struct sr_band_span {
    unsigned char first, last;
} sr_band_span;

/* A slot the row bands' verdicts kept, as sr_kept_slot has it, and its
 * span. The indices and planes are kept, not found again from k: each
 * thread walks every kept slot, and reading the mesh's indices by slot
 * there cost a load from far away per slot. */
typedef struct sr_band_slot {
    uint32_t k, idx[3];
    sr_band_span span;
    unsigned char planes; /* sr_slot_verdict's: below 2^8 (SR_OUT_NONFINITE's triangles are gone) */
    unsigned char box;
} sr_band_slot;

/* The span of a triangle that crosses a plane (its clipped polygon may
 * reach any row); a triangle inside every plane as tall as the
 * framebuffer has it too. */
static inline sr_band_span sr_every_band(void)
{
    return (sr_band_span){ 0, SR_ROW_BANDS - 1 };
}

static inline bool sr_band_span_is_every(sr_band_span s)
{
    return s.first == 0 && s.last == SR_ROW_BANDS - 1;
}

/* The double half of the vertices of [first, end) that the verdicts of
 * several threads marked wanted (sr_draw_state.double_wanted), after
 * them. */
void sr_draw_double_halves(const sr_draw_state *st, uint32_t first, uint32_t end);

/* Stages 4 to 7 for the kept slots[0 .. count) whose span meets bands
 * [lo, hi] (row_bands.c), in order: into `own` where the span starts
 * there, the thread that counts the slot, else into `shared`. */
void sr_draw_kept_slots(sr_fan_sink *own, sr_fan_sink *shared, const sr_band_slot *slots, uint32_t count,
                        unsigned lo, unsigned hi);

/* Runs fn(ctx, t) for t = 0 .. threads-1, t = 0 on the calling thread and
 * the others on the pool's workers (started as needed), and returns when
 * every fn has returned; adds the phase's wall time and its threads' CPU
 * time to *time when given. */
void sr_parallel_run(sr_pool *pool, int threads, void (*fn)(void *ctx, int t), void *ctx, sr_phase_time *time);

/* Wakes the pool's workers to end and joins them. */
void sr_pool_stop(sr_pool *pool);

/* Work handed out in chunks to whichever thread asks next, so a thread that
 * is slow (or waits for a core) leaves its share to the others; each thread
 * gets its chunks in increasing order. */
typedef struct sr_chunks {
    atomic_uint_fast64_t next; /* the next chunk to hand out (past the last: none left) */
    uint32_t count, size;
} sr_chunks;

void sr_chunks_init(sr_chunks *c, uint32_t count, uint32_t size);

/* The next chunk's items [first, end); false when none is left. */
bool sr_chunks_take(sr_chunks *c, uint32_t *first, uint32_t *end);

/* The binned path: primitives into per-thread tile bins, then each tile
 * rasterized by one thread in submission order. False when out of memory. */
bool sr_draw_binned(sr_draw_state *st);

/* A sink that draws each fan triangle as it comes over `rect`, its
 * fragments counted in `pixels` and its triangles in `work`. */
sr_fan_sink sr_direct_sink(const sr_draw_state *st, sr_thread_work *work, sr_raster_rect rect,
                           sr_thread_work *pixels);

/* The desc's point and line fields and its topology (points_lines.c);
 * false with a message for one out of range. */
bool sr_points_lines_check(const sr_draw_desc *d, sr_error *err);

/* A draw of points or lines (points_lines.c): every primitive through
 * stages 1 to 9, on one thread or binned by band of rows on several,
 * counted in the threads' work; false, with a message, for an index past
 * the vertices or out of memory (nothing drawn). */
bool sr_draw_points_lines(sr_draw_state *st, sr_error *err);

/* The direct path (direct.c): every slot through sr_direct_sink over the
 * whole framebuffer, on one thread, counted in thread 0's work; a
 * sr_parallel_run job of one thread. */
void sr_draw_direct(void *ctx, int t);

/* The row-band path (row_bands.c): every thread draws the triangles of its own
 * band of rows as they come, in submission order. */
bool sr_draw_rows(sr_draw_state *st);

/* Splits bands 0 .. bands-1 between `threads` threads by their costs:
 * thread t draws bands first_band[t] .. first_band[t + 1] - 1 (threads + 1
 * entries), a band going to the later of two threads when the middle of
 * its cost lies at or past their border's share; evenly by bands when the
 * costs sum to nothing or to no finite number. */
void sr_rows_split(const double *cost, int bands, int threads, int *first_band);

#endif
