/* A draw of the point and line topologies: stages 1 to 9 per primitive,
 * with the triangles' transform, outcodes, clipper arithmetic
 * (clip_segment.h), viewport and shading. docs/conventions.md, "Points and
 * lines". On one thread every fragment is stored as it comes; on several,
 * thread t takes the t-th run of slots and bins its fragments by band of
 * rows, then each band is stored by one thread from the bins in slot order
 * (raster_lines.h): the same pixels on every thread count. A run of points
 * whose vertices are consecutive is transformed, classified and mapped in
 * blocks, in lanes (sr_vertex_run_inside, 06_viewport.h's blocks), and a
 * point of size 1 takes its pixel without the square's set-up
 * (sr_raster_point_pixel): the same arithmetic, one loop instead of many.
 * docs/performance.md, "Points and lines". */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "draw_state.h"
#include "core/error.h"
#include "pipeline/04_clip/clip_corner.h"
#include "pipeline/04_clip/clip_segment.h"
#include "pipeline/08_raster/raster_lines.h"
#include "target/framebuffer.h"

#define NEAR_FAR ((1u << SR_PLANE_NEAR) | (1u << SR_PLANE_FAR))
#define SIDES (SR_OUT_PLANES & ~NEAR_FAR)

bool sr_points_lines_check(const sr_draw_desc *d, sr_error *err)
{
    if ((unsigned)d->mesh->topology > SR_LINE_STRIP)
        return sr_error_set(err, "unknown topology %d", (int)d->mesh->topology);
    if (d->point_size != 0.0f && !(d->point_size >= 1.0f && d->point_size <= SR_MAX_POINT_SIZE))
        return sr_error_set(err, "point size %g outside 1..%g", d->point_size, SR_MAX_POINT_SIZE);
    if (d->line_width != 0.0f && !(d->line_width >= 1.0f && d->line_width <= SR_MAX_LINE_WIDTH))
        return sr_error_set(err, "line width %g outside 1..%g", d->line_width, SR_MAX_LINE_WIDTH);
    if (!(d->depth_bias >= 0.0f && d->depth_bias <= 1.0f))
        return sr_error_set(err, "depth bias %g outside 0..1", d->depth_bias);
    return true;
}

typedef struct point_line_draw {
    const sr_draw_state *st;
    sr_thread_work *work;
    sr_point_line_target target;
} point_line_draw;

/* Stages 1 and 3 for mesh vertex i: its clip position and varyings, and
 * its outcode, SR_OUT_NONFINITE also for a varying the shading reads that
 * is not finite (the rule of the triangles' vertex phase). */
static unsigned vertex_of(const sr_draw_state *st, uint32_t i, sr_vertex_out *v)
{
    const sr_mesh *mesh = st->desc->mesh;
    sr_vertex_run(mesh, st->xf, &st->shade.layout, i, 1, v);
    unsigned code = sr_clip_outcode_with(v->v, &st->vp.depth);
    if (code != SR_OUT_NONFINITE && !sr_vertex_varyings_finite(mesh, st->xf, &st->shade.layout, i))
        code = SR_OUT_NONFINITE;
    return code;
}

static void count_nonfinite(sr_stats *stats)
{
    stats->rejected++;
    stats->nonfinite++;
}

/* A primitive whose vertices' outcodes or'd are `any` and and'ed `all`:
 * dropped and counted if a vertex is not finite or every vertex is
 * outside one plane of `all`. */
static bool outcodes_keep(sr_stats *stats, unsigned any, unsigned all)
{
    if (any & SR_OUT_NONFINITE) {
        count_nonfinite(stats);
        return false;
    }
    if (all) {
        sr_clip_count_rejected(stats, all, 1);
        return false;
    }
    return true;
}

/* The raster of a point mapped to p, shading with its vertex's own
 * varyings v (raster_lines.h), counted drawn. */
static void raster_point(point_line_draw *d, uint32_t k, const sr_screen_vertex *p, const sr_vertex_out *v)
{
    sr_stats *stats = &d->work->stats;
    stats->drawn++;
    const float *var = v->v + SR_VARYINGS_AT;
    float size = d->st->desc->point_size > 0.0f ? d->st->desc->point_size : 1.0f;
    stats->fragments += size == 1.0f ? sr_raster_point_pixel(&d->target, p, var, k)
                                     : sr_raster_point(&d->target, p, var, size, k);
}

/* Stage 6 and the raster of a point with clip position clip_d in double
 * under viewport vp: its snapped position and depth, and no varyings over
 * w, since a point shades with its vertex's own; so it is dropped as not
 * finite only for a w whose 1/w is not. */
static void map_and_raster_point(point_line_draw *d, uint32_t k, const sr_vertex_out *v, const double clip_d[4],
                                 const sr_viewport *vp)
{
    sr_screen_vertex p;
    if (!sr_viewport_map_d(v, clip_d, 0, vp, &p)) {
        count_nonfinite(&d->work->stats);
        return;
    }
    raster_point(d, k, &p, v);
}

/* A point is kept or dropped by its position: outside the near or far
 * plane it is dropped; past a side plane it is kept while its square can
 * reach the framebuffer, tested in a clip space squeezed by the band
 * 1 + (size + 2)/min(W, H) (half the size and a pixel to spare), in
 * which it is then mapped; the raster cuts its square to the framebuffer. */
static void draw_point(point_line_draw *d, uint32_t k)
{
    const sr_draw_state *st = d->st;
    sr_stats *stats = &d->work->stats;
    uint32_t i = st->desc->mesh->indices[k];
    _Alignas(16) sr_vertex_out v;
    unsigned code = vertex_of(st, i, &v);
    stats->points++;
    if (!outcodes_keep(stats, code, code & NEAR_FAR))
        return;
    double clip_d[4];
    sr_vertex_mesh_clip_d(st->desc->mesh, i, st->xf, clip_d);
    sr_viewport vp = st->vp;
    if (code & SIDES) {
        float size = st->desc->point_size > 0.0f ? st->desc->point_size : 1.0f;
        int side = st->fb->width < st->fb->height ? st->fb->width : st->fb->height;
        float band = 1.0f + (size + 2.0f) / (float)side;
        for (int c = SR_X; c <= SR_Y; c++) {
            v.v[c] /= band;
            clip_d[c] /= band;
        }
        unsigned still = sr_clip_outcode_with(v.v, &st->vp.depth) & SIDES;
        if (still) {
            sr_clip_count_rejected(stats, still, 1);
            return;
        }
        vp.guard *= band;
    }
    map_and_raster_point(d, k, &v, clip_d, &vp);
}

/* Points per block of the fast path: its vertices, outcodes and screen
 * vertices on the stack. */
#define POINT_BLOCK 64

/* Whether slots [k, k + n) index consecutive vertices. */
static bool consecutive(const uint32_t *indices, uint32_t k, uint32_t n)
{
    for (uint32_t j = 1; j < n; j++)
        if (indices[k + j] != indices[k] + j)
            return false;
    return true;
}

/* Stage 6 for the block's vertices i .. i + n − 1 (v) inside every plane
 * (mapped[j] 0), as map_and_raster_point maps them, in lanes
 * (06_viewport.h): the float half, which makes mapped[j] SR_OUT_NONFINITE
 * where it refuses one, then the double half of the others, into
 * screen[j]. */
static void map_block(const sr_draw_state *st, uint32_t i, uint32_t n, const sr_vertex_out *v,
                      unsigned char *mapped, sr_screen_vertex *screen)
{
    bool avx2 = st->shade.simd >= SR_SIMD_AVX2;
    sr_viewport_map_float_block(v, n, 0, &st->vp, avx2, mapped, screen, sizeof *screen, NULL);
    uint32_t index[POINT_BLOCK], m = 0;
    for (uint32_t j = 0; j < n; j++)
        if (mapped[j] == 0)
            index[m++] = j;
    /* The double half reads mesh vertex index[j] and writes screen vertex
     * index[j]: the block's vertices counted from 0, as its screen ones. */
    sr_mesh block = *st->desc->mesh;
    if (block.positions)
        block.positions += i;
    if (block.clip_positions)
        block.clip_positions += i;
    sr_viewport_map_double_block(&block, st->xf, index, m, &st->vp, avx2, screen, sizeof *screen);
}

/* Points [first, end): a block of consecutive vertices transformed,
 * classified and, those inside every plane, mapped at once, then each of
 * those rastered as draw_point would; any other point, and every point of
 * another block, through draw_point. */
static void draw_points(point_line_draw *d, uint32_t first, uint32_t end)
{
    const sr_draw_state *st = d->st;
    const sr_mesh *mesh = st->desc->mesh;
    _Alignas(16) sr_vertex_out v[POINT_BLOCK];
    sr_screen_vertex screen[POINT_BLOCK];
    unsigned char codes[POINT_BLOCK], mapped[POINT_BLOCK];
    for (uint32_t k = first; k < end; k += POINT_BLOCK) {
        uint32_t n = end - k < POINT_BLOCK ? end - k : POINT_BLOCK, i = mesh->indices[k];
        if (!consecutive(mesh->indices, k, n) ||
            !sr_vertex_block_finite(mesh, st->xf, &st->shade.layout, i, n)) {
            for (uint32_t j = 0; j < n; j++)
                draw_point(d, k + j);
            continue;
        }
        sr_vertex_run_inside(mesh, st->xf, &st->shade.layout, &st->vp.depth, st->shade.simd >= SR_SIMD_AVX2, i,
                             n, v, codes);
        memcpy(mapped, codes, n);
        map_block(st, i, n, v, mapped, screen);
        for (uint32_t j = 0; j < n; j++) {
            if (codes[j]) {
                draw_point(d, k + j);
                continue;
            }
            d->work->stats.points++;
            if (mapped[j])
                count_nonfinite(&d->work->stats);
            else
                raster_point(d, k + j, &screen[j], &v[j]);
        }
    }
}

/* Stage 6 for a clipped line's end k: a given end from its mesh vertex's
 * clip position in double, a cut from the segment's point on the plane in
 * double (sr_clip_point_on_lines_d, as a triangle's cut on that edge). */
static bool map_end(const sr_draw_state *st, const sr_vertex_out *end, int cut_plane, const double seg_d[3][4],
                    int k, sr_screen_vertex *out)
{
    int varyings = st->shade.layout.count;
    if (cut_plane == SR_SEGMENT_END_GIVEN)
        return sr_viewport_map_d(end, seg_d[k], varyings, &st->vp, out);
    double point[4];
    sr_clip_point_on_lines_d(seg_d, 0, SR_CLIP_ON_PLANE + cut_plane, &st->vp.depth, point);
    return sr_viewport_map_checked_d(end, point, varyings, &st->vp, out);
}

static void draw_line(point_line_draw *d, uint32_t k)
{
    const sr_draw_state *st = d->st;
    const sr_mesh *mesh = st->desc->mesh;
    sr_stats *stats = &d->work->stats;
    uint32_t idx[2];
    if (!sr_assemble_line(mesh, k, idx))
        return;
    stats->lines++;
    _Alignas(16) sr_vertex_out ends[2];
    unsigned c0 = vertex_of(st, idx[0], &ends[0]), c1 = vertex_of(st, idx[1], &ends[1]);
    if (!outcodes_keep(stats, c0 | c1, c0 & c1))
        return;
    sr_vertex_out clipped[2];
    int cut_plane[2] = { SR_SEGMENT_END_GIVEN, SR_SEGMENT_END_GIVEN };
    if (c0 | c1) {
        stats->clipped++;
        sr_clip_config cfg = { .precision = st->precision, .ndc_tolerance = st->clip_tolerance,
                               .counts = &d->work->cuts, .depth = st->vp.depth };
        if (!sr_clip_segment(ends, c0 | c1, SR_VARYINGS_AT + st->shade.layout.count, &cfg, clipped, cut_plane))
            return;
    } else {
        clipped[0] = ends[0];
        clipped[1] = ends[1];
    }
    /* The segment as the triangle (a, b, a) in double, whose edge 0 it is. */
    double seg_d[3][4];
    sr_vertex_mesh_clip_d(mesh, idx[0], st->xf, seg_d[0]);
    sr_vertex_mesh_clip_d(mesh, idx[1], st->xf, seg_d[1]);
    for (int r = 0; r < 4; r++)
        seg_d[2][r] = seg_d[0][r];
    sr_screen_vertex a, b;
    if (!map_end(st, &clipped[0], cut_plane[0], seg_d, 0, &a) || !map_end(st, &clipped[1], cut_plane[1], seg_d, 1, &b)) {
        count_nonfinite(stats);
        return;
    }
    stats->drawn++;
    int width = st->desc->line_width > 0.0f ? (int)lrintf(st->desc->line_width) : 1;
    stats->fragments += sr_raster_line(&d->target, &a, &b, width, k);
}

/* The draw's two phases on st->threads threads, for slots [first, end). */
typedef struct point_line_phases {
    sr_draw_state *st;
    sr_point_line_target target; /* bins NULL: each thread sets its own */
    uint32_t first, end;
    bool clear; /* the bands phase clears its rows: the first round's */
    sr_chunks bands;
} point_line_phases;

/* Thread t's run of the slots, its fragments stored or binned. */
static void slots_phase(void *ctx, int t)
{
    point_line_phases *ph = ctx;
    sr_draw_state *st = ph->st;
    sr_thread_work *work = &st->ws->threads[t];
    point_line_draw d = { .st = st, .work = work, .target = ph->target };
    if (st->threads > 1)
        d.target.bins = work->fragment_bins;
    uint64_t slots = ph->end - ph->first;
    uint32_t first = ph->first + (uint32_t)(slots * (uint64_t)t / (uint64_t)st->threads);
    uint32_t end = ph->first + (uint32_t)(slots * (uint64_t)(t + 1) / (uint64_t)st->threads);
    if (st->desc->mesh->topology == SR_POINT_LIST)
        draw_points(&d, first, end);
    else
        for (uint32_t k = first; k < end; k++)
            draw_line(&d, k);
    work->out_of_memory = d.target.out_of_memory;
}

/* The bands thread t takes, each cleared in the first round if the draw
 * clears, then given every thread's bin of it in slot order. */
static void bands_phase(void *ctx, int t)
{
    point_line_phases *ph = ctx;
    const sr_draw_state *st = ph->st;
    int rows = ph->target.band_rows;
    uint64_t passed = 0;
    uint32_t first, end;
    while (sr_chunks_take(&ph->bands, &first, &end))
        for (uint32_t b = first; b < end; b++) {
            if (ph->clear) {
                int y1 = (int)(b + 1) * rows;
                sr_framebuffer_clear_rows(st->fb, (int)b * rows, y1 < st->fb->height ? y1 : st->fb->height,
                                          st->desc->clear_color);
            }
            for (int s = 0; s < st->threads; s++) {
                const sr_array *bin = &st->ws->threads[s].fragment_bins[b];
                passed += sr_raster_fragments(&ph->target, bin->data, bin->count);
            }
        }
    st->ws->threads[t].stats.fragments += passed;
}

/* Thread w's bins freed. */
static void bins_free(sr_thread_work *w)
{
    for (size_t b = 0; b < w->fragment_bin_count; b++)
        sr_array_free(&w->fragment_bins[b]);
}

/* Each thread's bins, one per band, emptied; those of a thread that keep
 * room for more than its share of SR_FRAGMENT_BIN_BUDGET freed. */
static bool bins_ready(sr_draw_state *st, int bands)
{
    for (int t = 0; t < st->threads; t++) {
        sr_thread_work *w = &st->ws->threads[t];
        size_t room = 0;
        for (size_t b = 0; b < w->fragment_bin_count; b++)
            room += w->fragment_bins[b].capacity;
        if (room > SR_FRAGMENT_BIN_BUDGET / (size_t)st->threads)
            bins_free(w);
        if (w->fragment_bin_count < (size_t)bands) {
            sr_array *grown = realloc(w->fragment_bins, (size_t)bands * sizeof *grown);
            if (!grown)
                return false;
            for (size_t b = w->fragment_bin_count; b < (size_t)bands; b++)
                grown[b] = (sr_array){ 0 };
            w->fragment_bins = grown;
            w->fragment_bin_count = (size_t)bands;
        }
        for (int b = 0; b < bands; b++)
            w->fragment_bins[b].count = 0;
    }
    return true;
}

/* The most fragments one slot can make: a point's square, a line's width
 * along the longer side of the framebuffer, the raster cutting both to it. */
static uint64_t slot_fragments(const sr_draw_state *st)
{
    const sr_draw_desc *d = st->desc;
    if (d->mesh->topology == SR_POINT_LIST) {
        uint64_t side = d->point_size > 0.0f ? (uint64_t)ceilf(d->point_size) : 1;
        return side * side;
    }
    uint64_t width = d->line_width > 0.0f ? (uint64_t)lrintf(d->line_width) : 1;
    return width * (uint64_t)(st->fb->width + st->fb->height + 2);
}

bool sr_draw_points_lines(sr_draw_state *st, sr_error *err)
{
    const sr_mesh *mesh = st->desc->mesh;
    if (!sr_assemble_indices_valid(mesh))
        return sr_error_set(err, "mesh has an index past its %u vertices", st->vertex_count);
    uint32_t slots = sr_assemble_point_line_slots(mesh);
    bool binned = st->threads > 1;
    sr_draw_times *times = st->study.times;
    if (times)
        times->path = binned ? SR_PATH_ROWS : SR_PATH_DIRECT;
    point_line_phases ph = { .st = st, .end = slots,
                             .target = { .fb = st->fb, .mode = st->mode, .shade = &st->shade,
                                         .subpixel_bits = st->vp.subpixel_bits, .depth_bias = st->desc->depth_bias,
                                         .filter = st->line_filter,
                                         .band_rows = sr_band_rows(st->fb->height) } };
    if (!binned) {
        if (st->desc->clear)
            sr_framebuffer_clear(st->fb, st->desc->clear_color);
        if (st->vertex_count > 0)
            sr_parallel_run(&st->ws->pool, 1, slots_phase, &ph, times ? &times->primitives : NULL);
        return true;
    }
    int bands = sr_band_count(st->fb->height);
    uint64_t per_slot = slot_fragments(st), round = SR_FRAGMENT_BIN_BUDGET / per_slot;
    if (round == 0)
        round = 1;
    /* every round, even of no slots, so a draw that clears clears */
    for (uint64_t first = 0; first == 0 || first < slots; first += round) {
        if (!bins_ready(st, bands))
            return sr_error_set(err, "out of memory for the row bands of a point or line draw");
        ph.first = (uint32_t)first;
        ph.end = (uint32_t)(slots - first > round ? first + round : slots);
        ph.clear = first == 0 && st->desc->clear;
        sr_parallel_run(&st->ws->pool, st->threads, slots_phase, &ph, times ? &times->primitives : NULL);
        for (int t = 0; t < st->threads; t++)
            if (st->ws->threads[t].out_of_memory)
                return sr_error_set(err, "out of memory for the row bands of a point or line draw");
        sr_chunks_init(&ph.bands, (uint32_t)bands, 1);
        sr_parallel_run(&st->ws->pool, st->threads, bands_phase, &ph, times ? &times->raster : NULL);
    }
    return true;
}
