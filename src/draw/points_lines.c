/* A draw of the point and line topologies: stages 1 to 9 per primitive,
 * on one thread in submission order (a scalar loop: the same pixels for
 * every thread count and path a triangle draw could take), with the
 * triangles' transform, outcodes, clipper arithmetic (clip_segment.h),
 * viewport and shading. docs/conventions.md, "Points and lines". */
#include <math.h>

#include "draw_state.h"
#include "core/error.h"
#include "pipeline/04_clip/clip_corner.h"
#include "pipeline/04_clip/clip_segment.h"
#include "pipeline/08_raster/raster_lines.h"

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
    if (code & SR_OUT_NONFINITE) {
        count_nonfinite(stats);
        return;
    }
    if (code & NEAR_FAR) {
        sr_clip_count_rejected(stats, code & NEAR_FAR, 1);
        return;
    }
    double clip_d[4];
    sr_vertex_mesh_clip_d(st->desc->mesh, i, st->xf, clip_d);
    sr_viewport vp = st->vp;
    float size = st->desc->point_size > 0.0f ? st->desc->point_size : 1.0f;
    if (code & SIDES) {
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
    sr_screen_vertex p;
    if (!sr_viewport_map_d(&v, clip_d, st->shade.layout.count, &vp, &p)) {
        count_nonfinite(stats);
        return;
    }
    stats->drawn++;
    stats->fragments += sr_raster_point(&d->target, &p, size, k);
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
    if ((c0 | c1) & SR_OUT_NONFINITE) {
        count_nonfinite(stats);
        return;
    }
    if (c0 & c1) {
        sr_clip_count_rejected(stats, c0 & c1, 1);
        return;
    }
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

static void draw_all(void *ctx, int t)
{
    (void)t;
    point_line_draw *d = ctx;
    const sr_mesh *mesh = d->st->desc->mesh;
    uint32_t slots = sr_assemble_point_line_slots(mesh);
    for (uint32_t k = 0; k < slots; k++) {
        if (mesh->topology == SR_POINT_LIST)
            draw_point(d, k);
        else
            draw_line(d, k);
    }
}

bool sr_draw_points_lines(sr_draw_state *st, sr_error *err)
{
    const sr_mesh *mesh = st->desc->mesh;
    if (!sr_assemble_indices_valid(mesh))
        return sr_error_set(err, "mesh has an index past its %u vertices", st->vertex_count);
    st->threads = 1;
    if (st->study.times)
        st->study.times->path = SR_PATH_DIRECT;
    if (st->desc->clear)
        sr_framebuffer_clear(st->fb, st->desc->clear_color);
    point_line_draw d = { .st = st, .work = &st->ws->threads[0],
                          .target = { .fb = st->fb, .mode = st->mode, .shade = &st->shade,
                                      .subpixel_bits = st->vp.subpixel_bits, .depth_bias = st->desc->depth_bias } };
    if (st->vertex_count > 0)
        sr_parallel_run(&st->ws->pool, 1, draw_all, &d, st->study.times ? &st->study.times->primitives : NULL);
    return true;
}
