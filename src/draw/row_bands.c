/* The row-band path: each of the draw's threads owns a band of whole rows
 * of the framebuffer and draws, in submission order, every triangle that
 * may cover one of its rows, straight into them as the one-thread path
 * does. A first phase gives each triangle slot its verdict once (rejected
 * slots are counted there and go to no thread) and the threads whose rows
 * it may cover: from the rows of its vertices' snapped points, which the
 * vertex phase noted, or every thread where a vertex lies outside a plane;
 * where the vertex phase mapped only the float half, a second phase maps
 * the double half of the vertices the verdicts marked (on one thread the
 * verdicts map them as they go). The
 * rows are split where the estimated cost reaches equal shares: the kept
 * triangles inside every plane, counted at their first band, each weighed
 * by the CPU time per triangle that the last draw of the mesh with the
 * workspace took on that band (evenly by bands when there are none). The
 * weights change only who draws which rows, never a pixel.
 * A pixel sees the same triangles in the same order with the same edge
 * values as on the one-thread path, so the image is bit-identical; a
 * triangle over several bands is set up by each of their threads, and
 * counted by the first (docs/performance.md, "Row bands"). */
#include <math.h>
#include <string.h>

#include "draw_state.h"
#include "core/clock.h"
#include "pipeline/08_raster/tiny_queue.h"
#include "target/framebuffer.h"

/* Slots per chunk of the verdicts. */
#define VERDICT_CHUNK 16384

typedef struct rows_phase {
    sr_draw_state *st;
    sr_chunks slots, vertices; /* vertices: of the double halves */
    uint32_t chunks; /* of the verdicts */
    int first_band[SR_MAX_THREADS + 1]; /* thread t draws bands first_band[t] .. first_band[t + 1] - 1 */
} rows_phase;

/* How a snapped y finds its band: its row, clamped to the framebuffer,
 * over the band's rows. A value, not the draw state: the verdicts' stores
 * of kept slots could alias the state and reload it for each. */
typedef struct band_rule {
    int shift, last_row;
    unsigned rows;
} band_rule;

static unsigned band_of(band_rule r, int32_t y)
{
    int row = y < 0 ? 0 : y >> r.shift;
    return (unsigned)(row < r.last_row ? row : r.last_row) / r.rows;
}

/* The bands a kept slot's triangle may cover: from its highest vertex's
 * to its lowest one's (its covered pixel centres lie between their rows),
 * or every band when a vertex lies outside a plane (its clipped polygon
 * may reach anywhere). */
static sr_band_span span_of(band_rule r, const sr_snapped_point *points, const uint32_t idx[3], unsigned planes)
{
    if (planes)
        return sr_every_band();
    int32_t a = sr_snapped_point_y(points[idx[0]]), b = sr_snapped_point_y(points[idx[1]]),
            c = sr_snapped_point_y(points[idx[2]]);
    int32_t lo = a < b ? a : b, hi = a < b ? b : a;
    return (sr_band_span){ (unsigned char)band_of(r, c < lo ? c : lo), (unsigned char)band_of(r, c > hi ? c : hi) };
}

static void verdicts(void *ctx, int t)
{
    rows_phase *ph = ctx;
    const sr_draw_state *st = ph->st;
    const sr_snapped_point *points = st->ws->snapped_points.data;
    band_rule rule = { st->vp.subpixel_bits, st->fb->height - 1, (unsigned)st->band_rows };
    sr_band_slot *slots = st->ws->band_slots.data;
    uint32_t *chunk_kept = st->ws->chunk_kept.data;
    /* Local: stores to the thread's would alias every pointer above. */
    sr_stats counted = { 0 };
    uint32_t per_band[SR_ROW_BANDS] = { 0 };
    uint32_t first, end;
    while (sr_chunks_take(&ph->slots, &first, &end)) {
        uint32_t kept_in_chunk = 0;
        for (uint32_t batch = first; batch < end;) {
            uint32_t batch_end = end - batch > SR_VERDICT_BATCH ? batch + SR_VERDICT_BATCH : end;
            sr_kept_slot kept[SR_VERDICT_BATCH];
            int count = sr_draw_verdicts(st, batch, batch_end, end, &counted, kept);
            for (int j = 0; j < count; j++) {
                sr_band_span span = span_of(rule, points, kept[j].idx, kept[j].planes);
                sr_band_slot *b = &slots[first + kept_in_chunk++];
                *b = (sr_band_slot){ .k = kept[j].k, .span = span, .planes = (unsigned char)kept[j].planes,
                                     .box = kept[j].box };
                memcpy(b->idx, kept[j].idx, sizeof b->idx);
                if (kept[j].planes == 0)
                    per_band[span.first]++;
            }
            batch = batch_end;
        }
        chunk_kept[first / ph->slots.size] = kept_in_chunk;
    }
    sr_thread_work *w = &st->ws->threads[t];
    sr_stats_add(&w->stats, &counted);
    memcpy(w->band_triangles, per_band, sizeof per_band);
}

/* Vertices per chunk of the double halves. */
#define DOUBLE_HALVES_CHUNK 16384

/* The double halves the verdicts marked wanted (sr_draw_double_halves). */
static void double_halves(void *ctx, int t)
{
    (void)t;
    rows_phase *ph = ctx;
    uint32_t first, end;
    while (sr_chunks_take(&ph->vertices, &first, &end))
        sr_draw_double_halves(ph->st, first, end);
}

void sr_rows_split(const double *cost, int bands, int threads, int *first_band)
{
    double total = 0.0;
    for (int b = 0; b < bands; b++)
        total += cost[b];
    bool by_bands = !(total > 0.0 && isfinite(total));
    double whole = by_bands ? bands : total, before = 0.0;
    int t = 0;
    first_band[0] = 0;
    for (int b = 0; b < bands; b++) {
        double here = by_bands ? 1.0 : cost[b];
        while (t + 1 < threads && (before + here / 2) * threads >= (t + 1) * whole)
            first_band[++t] = b;
        before += here;
    }
    while (t < threads) /* the threads past the last band draw none */
        first_band[++t] = bands;
}

/* A band's cost: its kept triangles inside (counted at their first band)
 * times their cost as the last draw of the mesh into as many rows measured
 * it, or 1. */
static void split_bands(rows_phase *ph, const uint64_t count[SR_ROW_BANDS], int bands)
{
    const sr_draw_state *st = ph->st;
    const sr_band_costs *costs = &st->ws->band_costs;
    bool measured = costs->height == st->fb->height && costs->mesh == st->desc->mesh && costs->slots == st->slots;
    double cost[SR_ROW_BANDS];
    for (int b = 0; b < bands; b++)
        cost[b] = (double)count[b] * (measured ? costs->per_triangle[b] : 1.0);
    sr_rows_split(cost, bands, st->threads, ph->first_band);
}

/* Each band's cost per kept triangle: its thread's CPU time over the kept
 * triangles of its bands, or over all of them for a thread with none. */
static void measure_costs(const rows_phase *ph, const uint64_t count[SR_ROW_BANDS])
{
    const sr_draw_state *st = ph->st;
    sr_band_costs *costs = &st->ws->band_costs;
    uint64_t kept[SR_MAX_THREADS] = { 0 }, all_kept = 0;
    double all_ms = 0.0;
    for (int t = 0; t < st->threads; t++) {
        for (int b = ph->first_band[t]; b < ph->first_band[t + 1]; b++)
            kept[t] += count[b];
        all_kept += kept[t];
        all_ms += st->ws->threads[t].band_cpu_ms;
    }
    if (!all_kept) {
        costs->height = 0; /* nothing measured */
        return;
    }
    *costs = (sr_band_costs){ .height = st->fb->height, .mesh = st->desc->mesh, .slots = st->slots };
    for (int t = 0; t < st->threads; t++) {
        double per = kept[t] ? st->ws->threads[t].band_cpu_ms / (double)kept[t] : all_ms / (double)all_kept;
        for (int b = ph->first_band[t]; b < ph->first_band[t + 1]; b++)
            costs->per_triangle[b] = per;
    }
}

static void draw_band(void *ctx, int t)
{
    rows_phase *ph = ctx;
    const sr_draw_state *st = ph->st;
    int lo = ph->first_band[t], hi = ph->first_band[t + 1] - 1;
    sr_thread_work *w = &st->ws->threads[t];
    w->band_cpu_ms = 0.0;
    if (lo > hi)
        return;
    double start = sr_clock_ms(CLOCK_THREAD_CPUTIME_ID);
    int y1 = (hi + 1) * st->band_rows;
    sr_raster_rect rows = { 0, lo * st->band_rows, st->fb->width, y1 < st->fb->height ? y1 : st->fb->height };
    if (st->desc->clear)
        sr_framebuffer_clear_rows(st->fb, rows.y0, rows.y1, st->desc->clear_color);
    /* A slot another thread counts: its counts go nowhere, its fragments
     * (this thread's rows') to w. */
    sr_thread_work uncounted = { .stats = { 0 } };
    sr_fan_sink own = sr_direct_sink(st, w, rows, w), shared = sr_direct_sink(st, &uncounted, rows, w);
    /* The chunks in order, each's kept slots from its first slot on: every
     * kept slot in submission order, and only those. */
    const sr_band_slot *slots = st->ws->band_slots.data;
    const uint32_t *chunk_kept = st->ws->chunk_kept.data;
    for (uint32_t c = 0; c < ph->chunks; c++)
        sr_draw_kept_slots(&own, &shared, slots + (size_t)c * ph->slots.size, chunk_kept[c], (unsigned)lo,
                           (unsigned)hi);
    sr_tiny_queue_flush(&w->stats.fragments, &w->simd_draws);
    w->band_cpu_ms = sr_clock_ms(CLOCK_THREAD_CPUTIME_ID) - start;
}

bool sr_draw_rows(sr_draw_state *st)
{
    uint32_t chunk = st->study.chunk_slots ? st->study.chunk_slots : VERDICT_CHUNK;
    rows_phase ph = { .st = st, .chunks = st->slots / chunk + (st->slots % chunk != 0) };
    if (!sr_array_reserve(&st->ws->band_slots, st->slots, sizeof(sr_band_slot)) ||
        !sr_array_reserve(&st->ws->chunk_kept, ph.chunks, sizeof(uint32_t)))
        return false;
    sr_draw_times *times = st->study.times;
    sr_chunks_init(&ph.slots, st->slots, chunk);
    sr_parallel_run(&st->ws->pool, st->threads, verdicts, &ph, times ? &times->primitives : NULL);
    if (st->double_phase) {
        sr_chunks_init(&ph.vertices, st->vertex_count, DOUBLE_HALVES_CHUNK);
        sr_parallel_run(&st->ws->pool, st->threads, double_halves, &ph, times ? &times->primitives : NULL);
    }
    int bands = sr_band_count(st->fb->height);
    uint64_t count[SR_ROW_BANDS] = { 0 };
    for (int t = 0; t < st->threads; t++)
        for (int b = 0; b < bands; b++)
            count[b] += st->ws->threads[t].band_triangles[b];
    split_bands(&ph, count, bands);
    sr_parallel_run(&st->ws->pool, st->threads, draw_band, &ph, times ? &times->raster : NULL);
    measure_costs(&ph, count);
    return true;
}
