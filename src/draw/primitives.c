/* Stages 2 to 7 for a range of triangle slots, shared by the one-thread and
 * the binned paths so both see exactly the same fan triangles. */
#include "draw_state.h"
#include "pipeline/02_assemble.h"
#include "pipeline/04_clip/clip.h"
#include "pipeline/07_cull.h"
#include "pipeline/01_vertex.h"
#include "pipeline/06_viewport.h"
#include "pipeline/08_raster/lane_pixels.h"
#include "pipeline/08_raster/raster.h"

/* Stage 7 for one fan triangle whose vertices are *tri[] (refs name them
 * for the sink). */
static void cull_and_emit(sr_fan_sink *sink, const sr_screen_vertex *const tri[3], const uint32_t ref[3],
                          uint32_t id, bool clipped, bool one_pixel)
{
    const sr_draw_desc *d = sink->st->desc;
    int64_t area2 = sr_cull_area2(tri[0], tri[1], tri[2]);
    if (!sr_cull_keeps(area2, d->cull, d->front)) {
        sink->work->stats.culled++;
        return;
    }
    sink->work->stats.drawn++;
    sink->triangle(sink, tri, ref, area2, id, clipped, one_pixel);
}

/* Stages 5 and 6 for the polygon clipped from triangle idx: map every
 * vertex once, its depth from the triangle's clip positions in double
 * (sr_viewport_map_polygon), store them with the sink, fan (v0, vi, vi+1).
 * A vertex the viewport refuses (a divide past float range) drops the
 * polygon, counted rejected and non-finite as the vertex phase counts such
 * vertices. */
static void emit_polygon(sr_fan_sink *sink, const sr_polygon *poly, const uint32_t idx[3], uint32_t id)
{
    const sr_draw_state *st = sink->st;
    if (poly->count < 3)
        return;
    double tri_d[3][4];
    for (int k = 0; k < 3; k++)
        sr_vertex_mesh_clip_d(st->desc->mesh, idx[k], st->xf, tri_d[k]);
    sr_screen_vertex screen[SR_MAX_CLIP_VERTS];
    if (!sr_viewport_map_polygon(poly, tri_d, st->shade.layout.count, &st->vp, screen)) {
        sink->work->stats.rejected++;
        sink->work->stats.nonfinite++;
        return;
    }
    uint32_t base = sink->store(sink, screen, poly->count);
    for (int i = 1; i + 1 < poly->count; i++) {
        const uint32_t ref[3] = { base, base + (uint32_t)i, base + (uint32_t)i + 1 };
        cull_and_emit(sink, (const sr_screen_vertex *const[3]){ &screen[0], &screen[i], &screen[i + 1] }, ref, id,
                      true, false);
    }
}

/* An unclipped triangle uses the screen vertices the vertex phase mapped. */
static void emit_inside(sr_fan_sink *sink, const uint32_t idx[3], uint32_t id, bool one_pixel)
{
    const sr_draw_state *st = sink->st;
    cull_and_emit(sink,
                  (const sr_screen_vertex *const[3]){ sr_screen_at(st, idx[0]), sr_screen_at(st, idx[1]),
                                                      sr_screen_at(st, idx[2]) },
                  idx, id, false, one_pixel);
}

/* Stages 4 to 6 for triangle slot k, which crosses the planes in `planes`.
 * Out of emit_kept's line: its polygons (1 KB of stack) made every slot's
 * call save and reserve them, though most slots of a dense mesh are not
 * clipped. */
static __attribute__((noinline)) void emit_clipped(sr_fan_sink *sink, const uint32_t idx[3], unsigned planes,
                                                   uint32_t k)
{
    const sr_draw_state *st = sink->st;
    sr_polygon poly = { .count = 3 };
    for (int c = 0; c < 3; c++) { /* the vertex phase kept none: transformed again, the same bits */
        _Alignas(16) sr_vertex_out corner;
        sr_vertex_run(st->desc->mesh, st->xf, &st->shade.layout, idx[c], 1, &corner);
        poly.vert[c] = corner;
    }
    sink->work->stats.clipped++;
    sr_clip_config cfg = { .precision = st->precision, .ndc_tolerance = st->clip_tolerance,
                           .counts = &sink->work->cuts, .depth = st->vp.depth };
    sr_clip_polygon(&poly, planes, SR_VARYINGS_AT + st->shade.layout.count, &cfg);
    emit_polygon(sink, &poly, idx, k);
}

/* Stage 4, when `planes` (the OR of its outcodes) says it crosses one, and
 * on to the sink for a slot the verdict kept. */
static void emit_kept(sr_fan_sink *sink, const uint32_t idx[3], unsigned planes, uint32_t k, bool one_pixel)
{
    if (!planes)
        emit_inside(sink, idx, k, one_pixel);
    else
        emit_clipped(sink, idx, planes, k);
}

/* Prefetches the screen vertices of the triangle whose indices are idx[]:
 * the vertex phase wrote them all (32 to 64 bytes each, megabytes for a
 * dense mesh) long before, so without it the culling's first read of a
 * vertex waited for memory (docs/performance.md, "From slot to set-up").
 * A macro, three prefetches in the caller's loop: gcc 12 dropped a loop of
 * them, and a call of a function of them, as having no side effects. */
#define PREFETCH_TRIANGLE(screen, stride, idx)                                                                 \
    do {                                                                                                       \
        const uint32_t *tri_ = (idx);                                                                          \
        __builtin_prefetch((screen) + tri_[0] * (stride));                                                     \
        __builtin_prefetch((screen) + tri_[1] * (stride));                                                     \
        __builtin_prefetch((screen) + tri_[2] * (stride));                                                     \
    } while (0)

/* Stages 2 and 3 for the slots of [first, end): those the verdict keeps
 * into kept[], the screen vertices of those inside every plane
 * prefetched; returns how many it kept. The indices are prefetched up to
 * the draw's last slot, before `last_end`. */
static int take_verdicts(const sr_draw_state *st, uint32_t first, uint32_t end, uint32_t last_end, sr_stats *stats,
                         sr_kept_slot *kept)
{
    const char *screen = st->ws->screen.data;
    size_t stride = st->screen_stride;
    const sr_mesh *mesh = st->desc->mesh;
    const unsigned char *outcodes = st->ws->outcodes.data;
    int count = 0;
    for (uint32_t k = first; k < end; k++) {
        SR_PREFETCH_SLOT_INDICES(mesh, k, last_end);
        sr_kept_slot *s = &kept[count];
        s->planes = sr_slot_verdict(mesh, outcodes, stats, k, s->idx);
        if (s->planes == SR_SLOT_GONE)
            continue;
        if (!s->planes)
            PREFETCH_TRIANGLE(screen, stride, s->idx);
        s->k = k;
        s->box = SR_LANE_BOX_UNKNOWN;
        count++;
    }
    return count;
}

/* The triangles of kept[0 .. count) inside every plane that the sub-pixel
 * lanes find draw no pixel (subpixel.h) are counted in stats as stage 7
 * counts them and dropped; the others stay, in order, marked with what
 * the lanes found of their box (sr_lane_box), and their count is
 * returned. */
static int drop_subpixel(const sr_draw_state *st, sr_kept_slot *kept, int count, sr_stats *stats)
{
    if (count == 0)
        return 0;
    sr_subpixel_batch b = { { { 0 } } }; /* the last group's lanes past count, defined */
    uint64_t inside = 0;
    const char *screen = st->ws->screen.data;
    size_t stride = st->screen_stride;
    for (int j = 0; j < count; j++) {
        /* A vertex outside a plane has no screen vertex this draw: its
         * triangle's lane holds zeros, and `inside` ignores it. Inside every
         * plane a coordinate is below 2^30 (SR_FIXED_POINT_BITS), so exact
         * in 32 bits. */
        const sr_kept_slot *s = &kept[j];
        const sr_screen_vertex *v0 = (const sr_screen_vertex *)(screen + s->idx[0] * stride),
                               *v1 = (const sr_screen_vertex *)(screen + s->idx[1] * stride),
                               *v2 = (const sr_screen_vertex *)(screen + s->idx[2] * stride);
        bool in = s->planes == 0;
        b.x[0][j] = in ? (int32_t)v0->x : 0, b.y[0][j] = in ? (int32_t)v0->y : 0;
        b.x[1][j] = in ? (int32_t)v1->x : 0, b.y[1][j] = in ? (int32_t)v1->y : 0;
        b.x[2][j] = in ? (int32_t)v2->x : 0, b.y[2][j] = in ? (int32_t)v2->y : 0;
        inside |= (uint64_t)in << j;
    }
    sr_subpixel_verdict v = sr_subpixel_reject(&b, count, &st->subpixel);
    uint64_t culled = v.culled & inside, drawn = v.drawn & inside;
    v.one_pixel &= inside;
    v.small_box &= inside;
    stats->culled += (uint64_t)__builtin_popcountll(culled);
    stats->drawn += (uint64_t)__builtin_popcountll(drawn);
    int n = 0;
    uint64_t used = count == SR_SUBPIXEL_BATCH ? ~(uint64_t)0 : ((uint64_t)1 << count) - 1;
    for (uint64_t m = ~(culled | drawn) & used; m; m &= m - 1) {
        int j = __builtin_ctzll(m);
        kept[n] = kept[j];
        kept[n++].box = sr_lane_box_of(&v, j);
    }
    return n;
}

/* The double half of the vertices of the triangles inside every plane of
 * kept slots, each vertex once, by the one thread that takes every
 * verdict: the vertex phase mapped their float half (st->double_later).
 * No one reads a member the double half writes before the triangles are
 * drawn: the lanes read the snapped points. The vertices are listed first
 * (take_double_halves: those of kept[0 .. count) no one has taken into
 * taken[], marked and their positions prefetched) and only then mapped
 * (map_taken). */
static int take_double_halves(const sr_draw_state *st, const sr_kept_slot *kept, int count, uint32_t *taken)
{
    atomic_uchar *wanted = st->ws->double_wanted.data;
    const sr_mesh *source = st->desc->mesh;
    const char *positions = source->clip_positions ? (const char *)source->clip_positions
                                                   : (const char *)source->positions;
    size_t position_size = source->clip_positions ? sizeof *source->clip_positions : sizeof *source->positions;
    const char *screen = st->ws->screen.data;
    size_t stride = st->screen_stride;
    int n = 0;
    for (int j = 0; j < count; j++) {
        if (kept[j].planes)
            continue;
        for (int c = 0; c < 3; c++) { /* no branch on the flag: its loads overlap */
            uint32_t i = kept[j].idx[c];
            __builtin_prefetch(positions + i * position_size);
            __builtin_prefetch(screen + i * stride, 1);
            taken[n] = i; /* a vertex listed twice sees its own store */
            n += !atomic_load_explicit(&wanted[i], memory_order_relaxed);
            atomic_store_explicit(&wanted[i], 1, memory_order_relaxed);
        }
    }
    return n;
}

static void map_taken(const sr_draw_state *st, const uint32_t *taken, int n)
{
    sr_viewport_map_double_block(st->desc->mesh, st->xf, taken, (uint32_t)n, &st->vp, st->shade.simd >= SR_SIMD_AVX2,
                                 st->ws->screen.data, st->screen_stride);
}

/* Both, for a batch of verdicts (the row bands on one thread). Out of
 * line: its array on the stack made every batch's verdicts of a draw
 * without it pay for it. */
static __attribute__((noinline)) void map_double_halves(const sr_draw_state *st, const sr_kept_slot *kept,
                                                         int count)
{
    uint32_t taken[3 * SR_VERDICT_BATCH];
    map_taken(st, taken, take_double_halves(st, kept, count, taken));
}

/* On several threads the verdicts only mark the vertices of the kept
 * triangles inside every plane wanted, a plain store each: taking each
 * vertex with an atomic exchange, so that one thread alone mapped it,
 * waited on every exchange, and the two threads' exchanges on the same
 * lines; sr_draw_double_halves maps them in a phase after. */
static void mark_double_halves(const sr_draw_state *st, const sr_kept_slot *kept, int count)
{
    atomic_uchar *wanted = st->ws->double_wanted.data;
    for (int j = 0; j < count; j++)
        for (int c = 0; c < 3 && !kept[j].planes; c++)
            atomic_store_explicit(&wanted[kept[j].idx[c]], 1, memory_order_relaxed);
}

/* The vertices sr_draw_double_halves looks at for each call of the lanes. */
#define DOUBLE_HALVES_BATCH 256

void sr_draw_double_halves(const sr_draw_state *st, uint32_t first, uint32_t end)
{
    const atomic_uchar *wanted = st->ws->double_wanted.data;
    uint32_t taken[DOUBLE_HALVES_BATCH];
    for (uint32_t block = first; block < end; block += DOUBLE_HALVES_BATCH) {
        uint32_t block_end = end - block > DOUBLE_HALVES_BATCH ? block + DOUBLE_HALVES_BATCH : end, n = 0;
        for (uint32_t i = block; i < block_end; i++) {
            taken[n] = i;
            n += atomic_load_explicit(&wanted[i], memory_order_relaxed);
        }
        sr_viewport_map_double_block(st->desc->mesh, st->xf, taken, n, &st->vp, st->shade.simd >= SR_SIMD_AVX2,
                                     st->ws->screen.data, st->screen_stride);
    }
}

/* The verdicts of slots [first, end) of a triangle list with the
 * sub-pixel lanes (st->slot_lanes), eight slots at a time (sixteen with
 * AVX-512: sr_subpixel_slot_group_avx512) straight from
 * the indices and the snapped points (sr_subpixel_slot_group_avx2): no
 * kept slot is written for a triangle the lanes drop, and no vertex is
 * read twice. A group with a degenerate triangle or a vertex outside a
 * plane, and the last few slots, take the verdicts one at a time and the
 * lanes after them, as every other draw does; so the kept slots and the
 * counts are the same. The snapped points are not prefetched: a mesh's
 * vertices numbered in first use lie near those the groups before read,
 * and three prefetches a slot cost more than the gathers waited. */
static int take_verdicts_in_lanes(const sr_draw_state *st, uint32_t first, uint32_t end, uint32_t last_end,
                                  sr_stats *stats, sr_kept_slot *kept)
{
    const uint32_t *indices = st->desc->mesh->indices;
    const sr_snapped_point *points = st->ws->snapped_points.data;
    int count = 0;
    uint64_t culled = 0, drawn = 0; /* of the slots from first on: counted once, a call of libgcc's where the
                                       build has no popcnt instruction */
    bool wide = st->subpixel.avx512;
    uint32_t group = wide ? SR_SUBPIXEL_SLOT_GROUP_AVX512 : SR_SUBPIXEL_SLOT_GROUP;
    sr_subpixel_slots (*slot_group)(const uint32_t *, const sr_snapped_point *, const sr_subpixel_rules *) =
        wide ? sr_subpixel_slot_group_avx512 : sr_subpixel_slot_group_avx2;
    for (uint32_t g = first; g < end; g += group) {
        uint32_t g_end = end - g > group ? g + group : end;
        const uint32_t *idx = indices + 3 * (size_t)g;
        if (last_end - g > SR_INDICES_AHEAD + group) { /* a group's 96 or 192 bytes span two to four lines */
            for (uint32_t at = 0; at + 16 <= 3 * group; at += 16)
                __builtin_prefetch(idx + 3 * SR_INDICES_AHEAD + at);
            __builtin_prefetch(idx + 3 * SR_INDICES_AHEAD + 3 * group - 1);
        }
        sr_subpixel_slots v = { .plain = false };
        if (g_end - g == group)
            v = slot_group(idx, points, &st->subpixel);
        if (!v.plain) {
            int n = take_verdicts(st, g, g_end, last_end, stats, kept + count);
            count += drop_subpixel(st, kept + count, n, stats);
            continue;
        }
        stats->triangles += group;
        culled |= v.verdict.culled << (g - first);
        drawn |= v.verdict.drawn << (g - first);
        uint64_t left = ~(v.verdict.culled | v.verdict.drawn) & ((1u << group) - 1);
        for (; left; left &= left - 1) {
            int j = __builtin_ctzll(left);
            sr_kept_slot *s = &kept[count++];
            s->k = g + (uint32_t)j;
            memcpy(s->idx, idx + 3 * j, sizeof s->idx);
            s->planes = 0;
            s->box = sr_lane_box_of(&v.verdict, j);
        }
    }
    stats->culled += (uint64_t)__builtin_popcountll(culled);
    stats->drawn += (uint64_t)__builtin_popcountll(drawn);
    return count;
}

static int verdicts_of(const sr_draw_state *st, uint32_t first, uint32_t end, uint32_t last_end, sr_stats *stats,
                       sr_kept_slot *kept)
{
    if (st->slot_lanes)
        return take_verdicts_in_lanes(st, first, end, last_end, stats, kept);
    int count = take_verdicts(st, first, end, last_end, stats, kept);
    return st->subpixel_lanes ? drop_subpixel(st, kept, count, stats) : count;
}

int sr_draw_verdicts(const sr_draw_state *st, uint32_t first, uint32_t end, uint32_t last_end, sr_stats *stats,
                     sr_kept_slot *kept)
{
    int count = verdicts_of(st, first, end, last_end, stats, kept);
    if (st->double_later)
        (st->double_phase ? mark_double_halves : map_double_halves)(st, kept, count);
    return count;
}

/* The triangles of a window of kept slots that a sink draws from their
 * pixels and depths (sr_fan_sink.lane_pixels): their indices and ids as
 * the slots come, what sr_lane_pixels_* found, and their fragments in
 * order, fragments [first[t], first[t + 1]) triangle t's; then how far
 * they are taken in the slots' order and drawn. Not zeroed: a window sets
 * what it reads. */
#define LANE_FRAGMENTS (SR_LANE_PIXELS_BATCH * SR_LANE_PIXELS_CENTRES)
typedef struct lane_batch {
    uint32_t tri[SR_LANE_PIXELS_BATCH][3];
    uint32_t id[SR_LANE_PIXELS_BATCH];
    int count, taken, fragments_drawn;
    uint64_t one_pixel; /* bit t: tri[t] is a one_pixel triangle (sr_lane_box) */
    sr_lane_pixels found;
    int first[SR_LANE_PIXELS_BATCH + 1];
    /* Two past the most a window has: list_fragments writes two of each
     * triangle's, and keeps only as many as it covers. */
    size_t at[LANE_FRAGMENTS + 2];
    float z[LANE_FRAGMENTS + 2];
    uint32_t fragment_id[LANE_FRAGMENTS + 2];
} lane_batch;

static void lane_add(lane_batch *b, unsigned char box, const uint32_t idx[3], uint32_t id)
{
    memcpy(b->tri[b->count], idx, sizeof b->tri[0]);
    b->one_pixel |= (uint64_t)(box == SR_LANE_BOX_ONE_PIXEL) << b->count;
    b->id[b->count++] = id;
}

static void lanes_start(lane_batch *b)
{
    b->count = 0;
    b->one_pixel = 0;
}

/* The covered centres of every triangle, in order. Most cover none, one or
 * two: the lanes found those two, which are written whether covered or
 * not, and the count moves on by those covered, so no branch waits on
 * the coverage. */
static void list_fragments(lane_batch *b, size_t width)
{
    const sr_lane_pixels *p = &b->found;
    int n = 0;
    for (int t = 0; t < b->count; t++) {
        b->first[t] = n;
        uint32_t m = p->covered[t];
        for (int k = 0; k < 2; k++) {
            b->at[n] = p->at[k][t], b->z[n] = p->z[k][t], b->fragment_id[n] = b->id[t];
            n += m != 0;
            m &= m - 1;
        }
        for (; m; m &= m - 1, n++) {
            unsigned c = (unsigned)__builtin_ctz(m);
            b->at[n] = sr_lane_pixel_at(p, t, c, width), b->z[n] = sr_lane_pixel_z(p, t, c);
            b->fragment_id[n] = b->id[t];
        }
    }
    b->first[b->count] = n;
}

/* The window's pixels, depths and fragments. The depth lines are not
 * prefetched: the tests follow too soon for the lines to arrive, and a
 * window's prefetches held up the loads of the lanes. */
static void lanes_find(const sr_fan_sink *sink, lane_batch *b)
{
    const sr_draw_state *st = sink->st;
    b->taken = b->fragments_drawn = b->first[0] = 0;
    if (b->count == 0)
        return;
    (st->subpixel.avx2 ? sr_lane_pixels_avx2 : sr_lane_pixels_sse2)(st->ws->screen.data, st->screen_stride,
                                                                      (const uint32_t(*)[3])b->tri, b->count,
                                                                      b->one_pixel, st->vp.subpixel_bits, sink->rect,
                                                                      st->fb->width, &b->found);
    list_fragments(b, (size_t)st->fb->width);
}

/* Stage 7 of the window's next triangle with such a box, counted in
 * `sink`: kept, as the lanes applied its cull. Its fragments wait to be
 * drawn with the others taken after it (lanes_draw). */
static void lane_take(sr_fan_sink *sink, lane_batch *b)
{
    sink->work->stats.drawn++;
    b->taken++;
}

/* The fragments of the triangles taken and not yet drawn, in order:
 * before any other triangle is drawn, and at the window's end. */
static void lanes_draw(const sr_fan_sink *own, lane_batch *b)
{
    const sr_draw_state *st = own->st;
    int from = b->fragments_drawn, to = b->first[b->taken];
    if (to == from)
        return;
    own->pixels->stats.fragments += sr_raster_lane_fragments(st->fb, st->mode, &st->shade, b->fragment_id + from,
                                                             b->at + from, b->z + from, to - from);
    b->fragments_drawn = to;
}

/* The kept slots a window of verdicts holds: the verdicts of batches of
 * SR_VERDICT_BATCH slots while a whole batch's room is left, then their
 * double halves, then the slots drawn. A dense mesh keeps a few slots a
 * batch: a window of several batches maps their vertices' double halves
 * long after the verdicts prefetched them, and finds their small
 * triangles' pixels and depths in full lanes. */
#define KEPT_WINDOW (4 * SR_VERDICT_BATCH)

/* Kept slots [0, count) drawn in order, the pixels and depths of their
 * triangles the lanes found small found a window at a time. */
static void draw_kept(sr_fan_sink *sink, const sr_kept_slot *kept, int count)
{
    lane_batch lanes;
    for (int window = 0; window < count; window += SR_LANE_PIXELS_BATCH) {
        int window_end = count - window > SR_LANE_PIXELS_BATCH ? window + SR_LANE_PIXELS_BATCH : count;
        lanes_start(&lanes);
        for (int j = window; j < window_end && sink->lane_pixels; j++)
            if (kept[j].box != SR_LANE_BOX_UNKNOWN)
                lane_add(&lanes, kept[j].box, kept[j].idx, kept[j].k);
        lanes_find(sink, &lanes);
        for (int j = window; j < window_end; j++) {
            if (kept[j].box != SR_LANE_BOX_UNKNOWN && sink->lane_pixels) {
                lane_take(sink, &lanes);
            } else {
                lanes_draw(sink, &lanes);
                emit_kept(sink, kept[j].idx, kept[j].planes, kept[j].k, kept[j].box == SR_LANE_BOX_ONE_PIXEL);
            }
        }
        lanes_draw(sink, &lanes);
    }
}

/* Windows of verdicts, each then drawn. The verdicts' counts stay in a
 * local: a slot drawn between two verdicts made them reload what the
 * drawing might have written. */
void sr_draw_primitives(sr_fan_sink *sink, uint32_t first, uint32_t end)
{
    const sr_draw_state *st = sink->st;
    sr_stats verdicts = { 0 };
    for (uint32_t batch = first; batch < end;) {
        sr_kept_slot kept[KEPT_WINDOW];
        uint32_t taken[3 * KEPT_WINDOW];
        int count = 0, n = 0;
        while (batch < end && count + SR_VERDICT_BATCH <= KEPT_WINDOW) {
            uint32_t batch_end = end - batch > SR_VERDICT_BATCH ? batch + SR_VERDICT_BATCH : end;
            int got = verdicts_of(st, batch, batch_end, end, &verdicts, kept + count);
            if (st->double_later)
                n += take_double_halves(st, kept + count, got, taken + n);
            count += got;
            batch = batch_end;
        }
        if (st->double_later)
            map_taken(st, taken, n);
        draw_kept(sink, kept, count);
    }
    sr_stats_add(&sink->work->stats, &verdicts);
}

/* The kept slots ahead whose screen vertices the row bands prefetch,
 * counted over every kept slot though a thread draws only those that meet
 * its rows: a shorter distance left the culling waiting on them, a longer
 * one gained nothing. */
#define PREFETCH_SLOTS 48

static bool span_meets(sr_band_span span, unsigned lo, unsigned hi)
{
    return span.first <= hi && span.last >= lo;
}

void sr_draw_kept_slots(sr_fan_sink *own, sr_fan_sink *shared, const sr_band_slot *slots, uint32_t count,
                        unsigned lo, unsigned hi)
{
    const sr_draw_state *st = own->st;
    const char *screen = st->ws->screen.data;
    size_t stride = st->screen_stride;
    /* A window of slots at a time: the pixels of its triangles the lanes
     * found small found first (the two sinks draw the same rows), then
     * every slot in order. */
    lane_batch lanes;
    for (uint32_t window = 0; window < count; window += SR_LANE_PIXELS_BATCH) {
        uint32_t window_end = count - window > SR_LANE_PIXELS_BATCH ? window + SR_LANE_PIXELS_BATCH : count;
        lanes_start(&lanes);
        for (uint32_t i = window; i < window_end && own->lane_pixels; i++)
            if (slots[i].box != SR_LANE_BOX_UNKNOWN && span_meets(slots[i].span, lo, hi))
                lane_add(&lanes, slots[i].box, slots[i].idx, slots[i].k);
        lanes_find(own, &lanes);
        for (uint32_t i = window; i < window_end; i++) {
            if (count - i > PREFETCH_SLOTS && span_meets(slots[i + PREFETCH_SLOTS].span, lo, hi))
                PREFETCH_TRIANGLE(screen, stride, slots[i + PREFETCH_SLOTS].idx);
            const sr_band_slot *s = &slots[i];
            if (!span_meets(s->span, lo, hi))
                continue;
            sr_fan_sink *sink = s->span.first >= lo ? own : shared;
            if (s->box != SR_LANE_BOX_UNKNOWN && own->lane_pixels) {
                lane_take(sink, &lanes);
            } else {
                lanes_draw(own, &lanes);
                emit_kept(sink, s->idx, s->planes, s->k, s->box == SR_LANE_BOX_ONE_PIXEL);
            }
        }
        lanes_draw(own, &lanes); /* both sinks count their fragments in the same work */
    }
}
