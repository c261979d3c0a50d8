#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "draw.h"
#include "draw_state.h"
#include "materials.h"
#include "pipeline/02_assemble.h"
#include "pipeline/04_clip/clip.h"
#include "pipeline/01_vertex.h"
#include "pipeline/06_viewport.h"
#include "pipeline/07_cull.h"
#include "pipeline/11_merge.h"
#include "core/error.h"
#include "core/clock.h"
#include "core/dmat4.h"
#include "pipeline/08_raster/raster.h"
#include "pipeline/08_raster/simd_select.h"
#include "pipeline/08_raster/tiny_queue.h"

static int subpixel_bits(const sr_draw_study *d)
{
    return d->subpixel_bits ? d->subpixel_bits : SR_SUBPIXEL_BITS;
}

static float guard_band(const sr_draw_study *d)
{
    return d->guard_band > 1.0f ? d->guard_band : 1.0f;
}

/* The knobs must keep every snapped coordinate below 2^SR_FIXED_POINT_BITS. */
static bool check_accuracy_knobs(const sr_framebuffer *fb, const sr_draw_study *d, sr_error *err)
{
    int bits = subpixel_bits(d);
    if (bits < SR_MIN_SUBPIXEL_BITS || bits > SR_MAX_SUBPIXEL_BITS)
        return sr_error_set(err, "subpixel bits %d outside %d..%d", bits, SR_MIN_SUBPIXEL_BITS, SR_MAX_SUBPIXEL_BITS);
    if (!(d->guard_band >= 0.0f && d->guard_band <= SR_MAX_GUARD_BAND))
        return sr_error_set(err, "guard band %g outside 0..%g", d->guard_band, SR_MAX_GUARD_BAND);
    if ((unsigned)d->simd >= SR_SIMD_COUNT)
        return sr_error_set(err, "unknown SIMD choice %d", (int)d->simd);
    if ((unsigned)d->clip_precision >= SR_CLIP_PRECISIONS)
        return sr_error_set(err, "unknown clip precision %d", (int)d->clip_precision);
    if ((unsigned)d->path > SR_PATH_ROWS)
        return sr_error_set(err, "unknown draw path %d", (int)d->path);
    int side = fb->width > fb->height ? fb->width : fb->height;
    double extent = ceil(guard_band(d)) * side * (double)((int64_t)1 << bits);
    if (extent > (double)((int64_t)1 << SR_FIXED_POINT_BITS))
        return sr_error_set(err, "%d subpixel bits with a guard band of %g do not fit a %d-pixel framebuffer",
                            bits, guard_band(d), side);
    return true;
}

static bool check_inputs(const sr_framebuffer *fb, const sr_draw_desc *d, const sr_draw_study *study,
                         const sr_varying_layout *l, sr_error *err)
{
    if (!fb || !fb->color || !fb->depth || fb->width < 1 || fb->height < 1 ||
        fb->width > SR_MAX_FRAMEBUFFER_SIDE || fb->height > SR_MAX_FRAMEBUFFER_SIDE)
        return sr_error_set(err, "draw into a framebuffer without buffers or of a bad size");
    if (!d->mesh)
        return sr_error_set(err, "draw without a mesh");
    if ((unsigned)d->shade >= SR_SHADE_COUNT || (unsigned)d->cull > SR_CULL_NONE ||
        (unsigned)d->front > SR_FRONT_CCW || (unsigned)d->filter > SR_FILTER_NEAREST ||
        (unsigned)d->color_space > SR_COLOR_SRGB || (unsigned)d->blend > SR_BLEND_PREMULTIPLIED)
        return sr_error_set(err, "draw with an unknown shading, culling, front, filter mode, colour space or blend");
    if (!check_accuracy_knobs(fb, study, err) || !sr_points_lines_check(d, err))
        return false;
    const double *o = d->mesh->origin;
    if (!isfinite(o[0]) || !isfinite(o[1]) || !isfinite(o[2]))
        return sr_error_set(err, "mesh origin (%g, %g, %g) is not finite", o[0], o[1], o[2]);
    if (d->mesh->vertex_count == 0)
        return true; /* nothing to shade: an empty mesh needs no attributes */
    if (!d->mesh->positions && !d->mesh->clip_positions)
        return sr_error_set(err, "mesh has neither positions nor clip-space positions");
    if (l->normal >= 0 && !d->mesh->normals)
        return sr_error_set(err, "this shading mode needs vertex normals and the mesh has none");
    if (l->color >= 0 && !d->mesh->colors)
        return sr_error_set(err, "color shading needs vertex colors and the mesh has none");
    bool materials = d->mesh->material_count > 0;
    if (materials && !sr_materials_check(d->mesh, err))
        return false;
    bool material_textures = materials && sr_assemble_triangles(d->mesh); /* draw_layout */
    if (l->uv >= 0 && (!d->mesh->uvs || (!material_textures && (!d->texture || !d->texture->texels))))
        return sr_error_set(err, "texture shading needs texture coordinates and a texture");
    if (d->texture && d->texture->texels &&
        (d->texture->width < 1 || d->texture->height < 1 || d->texture->width > SR_MAX_TEXTURE_SIDE ||
         d->texture->height > SR_MAX_TEXTURE_SIDE))
        return sr_error_set(err, "texture of size %dx%d cannot be sampled (each side 1..%d)", d->texture->width,
                            d->texture->height, SR_MAX_TEXTURE_SIDE);
    return true;
}

static void shade_context_make(const sr_draw_desc *d, sr_simd simd, const sr_varying_layout *l,
                               sr_shade_context *c)
{
    vec3 light = SR_DEFAULT_LIGHT;
    if (!glm_vec3_eq(((float *)d->light_dir), 0.0f))
        glm_vec3_copy((float *)d->light_dir, light);
    glm_vec3_normalize(light);
    *c = (sr_shade_context){ .layout = *l, .texture = d->texture, .filter = d->filter,
                             .simd = sr_raster_simd_resolve(simd), .srgb = d->color_space == SR_COLOR_SRGB,
                             .albedo = { SR_LAMBERT_GRAY, SR_LAMBERT_GRAY, SR_LAMBERT_GRAY },
                             .tint = { 1.0f, 1.0f, 1.0f }, .blend = d->blend, .depth_write = !d->no_depth_write,
                             .merges = d->blend != SR_BLEND_REPLACE || d->no_depth_write,
                             .alpha_scale = SR_MERGE_ALPHA_ONE,
                             .alpha_texel = l->uv >= 0 && d->texture && d->texture->texels && d->texture->alpha };
    glm_vec3_copy(light, c->light_dir);
}

/* Vertices and indices go to the threads in chunks of these. */
#define VERTEX_CHUNK 4096
/* The clip vertices a chunk keeps at a time, on the stack (12 KB): only
 * the outcodes and the screen vertices outlive the vertex phase, and the
 * clipper transforms a clipped triangle's corners again (primitives.c), so
 * a draw keeps no array of them. */
#define VERTEX_BLOCK 256
#define INDEX_CHUNK 65536

typedef struct vertex_phase {
    const sr_draw_state *st;
    sr_vertex_transform xf;
    bool inside; /* the mesh's bounds are inside every plane: no classification */
    sr_chunks vertices, indices;
} vertex_phase;

/* Stage 6 for vertex i, inside every plane: its unsnapped point and depth
 * from the clip position in double. */
static bool map_inside(const vertex_phase *ph, const sr_vertex_out *v, uint32_t i, sr_screen_vertex *out)
{
    const sr_draw_state *st = ph->st;
    double clip_d[4];
    sr_vertex_mesh_clip_d(st->desc->mesh, i, &ph->xf, clip_d);
    return sr_viewport_map_d(v, clip_d, st->shade.layout.count, &st->vp, out);
}

/* The outcodes of vertices [block, block + n) from their codes, each
 * vertex outside a plane checked for non-finite varyings and, without
 * st->double_later, each inside mapped whole, its snapped point noted
 * where the draw wants them (vertex_chunk). */
static void check_and_map(const vertex_phase *ph, uint32_t block, uint32_t n, const sr_vertex_out *verts,
                          const unsigned char *codes, unsigned char *outcodes, unsigned *outcodes_and)
{
    const sr_draw_state *st = ph->st;
    const sr_mesh *mesh = st->desc->mesh;
    const sr_varying_layout *layout = &st->shade.layout;
    bool double_later = st->double_later;
    sr_snapped_point *points = st->ws->snapped_points.data;
    int block_finite = -1; /* not yet known */
    for (uint32_t j = 0; j < n; j++) {
        uint32_t i = block + j;
        unsigned code = codes[j];
        if (code != 0 && code != SR_OUT_NONFINITE) {
            if (block_finite < 0)
                block_finite = sr_vertex_block_finite(mesh, &ph->xf, layout, block, n);
            if (!block_finite && !sr_vertex_varyings_finite(mesh, &ph->xf, layout, i))
                code = SR_OUT_NONFINITE;
        }
        if (!double_later) {
            sr_screen_vertex *v = sr_screen_at(st, i);
            if (code == 0 && !map_inside(ph, &verts[j], i, v))
                code = SR_OUT_NONFINITE;
            if (st->snapped_points)
                points[i] = code ? SR_SNAPPED_OUTSIDE : sr_snapped_point_of(v->x, v->y);
        }
        outcodes[i] = (unsigned char)code;
        *outcodes_and &= code;
    }
}

/* Whether every code of codes[0 .. n) is 0, in words where the compiler
 * vectorises the OR. */
static bool all_inside(const unsigned char *codes, uint32_t n)
{
    unsigned char any = 0;
    for (uint32_t j = 0; j < n; j++)
        any |= codes[j];
    return any == 0;
}

/* Stages 1 and 3 per unique vertex, and stage 6 for those inside every
 * plane, so an unclipped triangle maps none of its corners again. Only a
 * vertex inside gets its varyings: a clipped triangle transforms its
 * corners again (primitives.c). A NaN or inf varying marks a vertex
 * non-finite, inside or not (it decides how a rejected triangle is
 * counted): outside, it is told from the mesh's values, a block at a time
 * where they are all plainly finite (01_vertex.h); inside, by the mapping,
 * whose varyings divided by w are then not finite, and which fails as well
 * where the divide does (w below 2^-128): the triangles that use such a
 * vertex are dropped and counted. For the slot lanes and the row bands,
 * each vertex gets its snapped point (stages.h). With st->double_later a
 * vertex inside gets only the float half of its mapping here
 * (06_viewport.h), which decides its refusal, and notes the snapped
 * points: the verdicts map the double half of the vertices of the
 * triangles they keep, or on several threads mark them for a phase after
 * theirs (primitives.c, sr_draw_double_halves); the check after may only find a
 * vertex outside a plane non-finite, whose point is the outside one
 * already. */
static void vertex_chunk(const vertex_phase *ph, uint32_t first, uint32_t end, unsigned *outcodes_and)
{
    const sr_draw_state *st = ph->st;
    const sr_mesh *mesh = st->desc->mesh;
    const sr_varying_layout *layout = &st->shade.layout;
    unsigned char *outcodes = st->ws->outcodes.data;
    atomic_uchar *double_wanted = st->ws->double_wanted.data;
    bool double_later = st->double_later; /* a local: the loop's byte stores may alias *st */
    for (uint32_t block = first; block < end; block += VERTEX_BLOCK) {
        _Alignas(16) sr_vertex_out verts[VERTEX_BLOCK];
        uint32_t n = end - block < VERTEX_BLOCK ? end - block : VERTEX_BLOCK;
        unsigned char codes[VERTEX_BLOCK]; /* each vertex's outcode, 0 for all when the mesh is inside */
        if (ph->inside) {
            memset(codes, 0, n);
            sr_vertex_run(mesh, &ph->xf, layout, block, n, verts);
        } else {
            sr_vertex_run_inside(mesh, &ph->xf, layout, &st->vp.depth, st->shade.simd >= SR_SIMD_AVX2, block, n,
                                 verts, codes);
        }
        /* Most vertices of a dense mesh at a small size are of triangles
         * the sub-pixel lanes drop, which read only the snapped point. */
        if (double_later) {
            sr_viewport_map_float_block(verts, n, layout->count, &st->vp, st->shade.simd >= SR_SIMD_AVX2, codes,
                                        sr_screen_at(st, block), st->screen_stride,
                                        st->snapped_points ? (sr_snapped_point *)st->ws->snapped_points.data + block
                                                           : NULL);
            for (uint32_t j = 0; j < n; j++)
                atomic_init(&double_wanted[block + j], 0);
        }
        if (double_later && all_inside(codes, n)) { /* nothing to check or map: the float half is done */
            memcpy(outcodes + block, codes, n);
            *outcodes_and = 0;
        } else {
            check_and_map(ph, block, n, verts, codes, outcodes, outcodes_and);
        }
    }
}

/* The vertex chunks, then the check of the indices, which sr_draw would
 * otherwise make serially before it starts (nothing is drawn before the
 * verdict). */
static void vertex_phase_run(void *ctx, int t)
{
    vertex_phase *ph = ctx;
    const sr_draw_state *st = ph->st;
    uint32_t first, end;
    unsigned outcodes_and = ~0u;
    while (sr_chunks_take(&ph->vertices, &first, &end))
        vertex_chunk(ph, first, end, &outcodes_and);
    st->ws->threads[t].outcodes_and = outcodes_and;
    bool past_end = false;
    while (sr_chunks_take(&ph->indices, &first, &end))
        past_end = past_end || !sr_assemble_indices_valid_in(st->desc->mesh, first, end);
    st->ws->threads[t].index_past_end = past_end;
}

static void make_transform(const sr_draw_state *st, sr_vertex_transform *xf)
{
    const sr_draw_desc *d = st->desc;
    static const sr_dmat4 not_given;
    sr_dmat4 world = sr_dmat4_desc_matrix(&d->world_d, d->world), view = sr_dmat4_desc_matrix(&d->view_d, d->view);
    sr_dmat4 projection = sr_dmat4_desc_matrix(&not_given, d->projection);
    /* A guard band clips x and y at ±G·w: squeeze x and y by 1/G here, clip
     * at ±w as always, and let the viewport scale them back. */
    for (int col = 0; col < 4; col++) {
        projection.m[col][0] /= st->vp.guard;
        projection.m[col][1] /= st->vp.guard;
    }
    sr_vertex_make_transform_d(&world, &view, &projection, d->mesh->origin, xf);
}

static bool index_error(const sr_draw_state *st, sr_error *err)
{
    return sr_error_set(err, "mesh has an index past its %u vertices", st->vertex_count);
}

static bool run_vertex_phase(const sr_draw_state *st, vertex_phase *ph, sr_error *err)
{
    uint32_t n = st->vertex_count;
    sr_workspace *ws = st->ws;
    if (!sr_array_reserve(&ws->outcodes, n, sizeof(unsigned char)) ||
        (st->snapped_points && !sr_array_reserve(&ws->snapped_points, n, sizeof(sr_snapped_point))) ||
        (st->double_later && !sr_array_reserve(&ws->double_wanted, n, sizeof(atomic_uchar))) ||
        n > SIZE_MAX / st->screen_stride || !sr_array_reserve(&ws->screen, n * st->screen_stride, 1))
        return sr_error_set(err, "out of memory for %u transformed vertices", n);
    sr_draw_times *times = st->study.times;
    sr_chunks_init(&ph->vertices, n, VERTEX_CHUNK);
    sr_chunks_init(&ph->indices, st->desc->mesh->index_count, INDEX_CHUNK);
    sr_parallel_run(&ws->pool, st->threads, vertex_phase_run, ph, times ? &times->vertex : NULL);
    for (int t = 0; t < st->threads; t++)
        if (st->ws->threads[t].index_past_end)
            return index_error(st, err);
    return true;
}

/* The cost estimate that picks one thread or the tiles (docs/performance.md,
 * "Which path a draw takes"). Before the vertex phase: a draw of fewer slots
 * into fewer pixels than these ran faster on one thread at every size
 * measured (thread start-up and per-tile costs outweigh the split). */
#define TILES_MIN_SLOTS 32768u
#define TILES_MIN_PIXELS (1280 * 720)

static int64_t pixel_count(const sr_draw_state *st)
{
    return (int64_t)st->fb->width * st->fb->height;
}

static bool worth_threads(const sr_draw_state *st)
{
    if (st->study.path != SR_PATH_BY_COST)
        return st->study.path != SR_PATH_DIRECT;
    return st->slots >= TILES_MIN_SLOTS || pixel_count(st) >= TILES_MIN_PIXELS;
}

/* After it: every vertex outside one plane (a view that looks away from the
 * mesh while its bounds straddle the camera) leaves every triangle
 * rejected, which one thread does faster than the tiles clear the screen. */
static bool all_outside_one_plane(const sr_draw_state *st)
{
    unsigned outcodes_and = ~0u;
    for (int t = 0; t < st->threads; t++)
        outcodes_and &= st->ws->threads[t].outcodes_and;
    return outcodes_and != 0;
}

/* On one thread, the tiles pay for a large framebuffer and few triangle
 * slots for its pixels: large triangles drawn over each other keep a
 * tile's color and depth in the core's cache where the direct path streams
 * the whole framebuffer through memory per triangle, while pixel-sized
 * triangles pay the binning and gain nothing. */
#define TILES_ONE_THREAD_PIXELS_PER_SLOT 64

static bool pixel_sized_slots(const sr_draw_state *st)
{
    return (int64_t)st->slots * TILES_ONE_THREAD_PIXELS_PER_SLOT > pixel_count(st);
}

/* Whatever the path asked: an observer sees every triangle, in order, from
 * the direct path, and a bin entry names slots below 2^31 (a strip's can
 * reach 2^32 - 3). */
static bool direct_only(const sr_draw_state *st)
{
    return st->study.observer || st->slots > SR_BIN_STORED;
}

/* Before the vertex phase: the study's path, or the cost estimate's. The
 * row bands want the vertex phase to note each vertex's snapped point. */
static sr_draw_path planned_path(const sr_draw_state *st)
{
    if (direct_only(st))
        return SR_PATH_DIRECT;
    if (st->study.path != SR_PATH_BY_COST)
        return st->study.path;
    if (st->threads > 1)
        return pixel_sized_slots(st) ? SR_PATH_ROWS : SR_PATH_TILES;
    return pixel_count(st) >= TILES_MIN_PIXELS && !pixel_sized_slots(st) ? SR_PATH_TILES : SR_PATH_DIRECT;
}

/* After it: the planned path, or the direct one where the estimate finds
 * every vertex outside one plane. */
static sr_draw_path path_of(const sr_draw_state *st, sr_draw_path planned)
{
    if (!direct_only(st) && st->study.path == SR_PATH_BY_COST && all_outside_one_plane(st))
        return SR_PATH_DIRECT;
    return planned;
}

/* Triangles the sub-pixel lanes' estimate looks at: evenly spaced slots,
 * a few microseconds. From SUBPIXEL_SAMPLED_MIN_SLOTS slots on that is
 * little beside the draw where its triangles are large and the estimate
 * wasted, and far less than it saves where they are sub-pixel: the
 * one-by-one path sets every triangle up, the lanes drop most unset. */
#define SUBPIXEL_SAMPLES 256
#define SUBPIXEL_SAMPLED_MIN_SLOTS 4096

/* Whether most of the sampled triangles in front of the eye have less than
 * a pixel's area on screen: most then cover no pixel centre. Areas in
 * NDC, where a pixel is 2/(guard·width) wide and 2/(guard·height) high. */
static bool mostly_subpixel(const sr_draw_state *st, const sr_vertex_transform *xf)
{
    const sr_mesh *mesh = st->desc->mesh;
    double pixel_area2 = 8.0 / (st->vp.guard * st->vp.guard * st->fb->width * st->fb->height);
    int seen = 0, tiny = 0;
    for (uint32_t i = 0; i < SUBPIXEL_SAMPLES; i++) {
        uint32_t idx[3];
        if (!sr_assemble_triangle(mesh, (uint32_t)((uint64_t)st->slots * i / SUBPIXEL_SAMPLES), idx) ||
            idx[0] >= mesh->vertex_count || idx[1] >= mesh->vertex_count || idx[2] >= mesh->vertex_count)
            continue;
        double ndc[3][2];
        bool front = true;
        for (int c = 0; c < 3 && front; c++) {
            double clip[4];
            sr_vertex_mesh_clip_d(mesh, idx[c], xf, clip);
            ndc[c][0] = clip[SR_X] / clip[SR_W];
            ndc[c][1] = clip[SR_Y] / clip[SR_W];
            front = clip[SR_W] > 0.0 && isfinite(ndc[c][0]) && isfinite(ndc[c][1]);
        }
        if (!front)
            continue;
        double area2 = (ndc[1][0] - ndc[0][0]) * (ndc[2][1] - ndc[0][1]) -
                       (ndc[1][1] - ndc[0][1]) * (ndc[2][0] - ndc[0][0]);
        seen++;
        tiny += fabs(area2) < pixel_area2;
    }
    return 2 * tiny > seen;
}

/* The sub-pixel lanes (pipeline/08_raster/subpixel.h) pay where most
 * triangles cover no pixel centre: a draw of more triangle slots than
 * pixels, or of many slots most of which, sampled, are smaller than a
 * pixel (a scan seen whole in a third of the frame, with culling off, its
 * back faces as small as its front). With two pixels a front-facing
 * triangle (the dense torus at 1920x1080, back faces culled) too few drop
 * out to pay for the lanes. The observer sees every triangle that
 * survives culling, so a draw with one sets each up, as does a snap finer
 * than the lanes hold. */
static bool subpixel_lanes(const sr_draw_state *st, const sr_vertex_transform *xf)
{
    /* uvs in id or depth shading: a MASK material's alpha test, which the lane pixels' loop does not take */
    bool cuts = st->shade.layout.uv >= 0 && (st->mode == SR_SHADE_ID || st->mode == SR_SHADE_DEPTH);
    if (st->study.one_by_one || st->study.observer || st->vp.subpixel_bits > SR_SUBPIXEL_LANES_MAX_BITS || cuts)
        return false;
    return (int64_t)st->slots > pixel_count(st) ||
           (st->slots >= SUBPIXEL_SAMPLED_MIN_SLOTS && sr_assemble_triangles(st->desc->mesh) && mostly_subpixel(st, xf));
}

static sr_subpixel_rules subpixel_rules(const sr_draw_state *st)
{
    const sr_draw_desc *d = st->desc;
    return (sr_subpixel_rules){ .bits = st->vp.subpixel_bits, .width = st->fb->width, .height = st->fb->height,
                                .keep_cw = sr_cull_keeps(1, d->cull, d->front),
                                .keep_ccw = sr_cull_keeps(-1, d->cull, d->front),
                                .avx2 = st->shade.simd >= SR_SIMD_AVX2, .avx512 = st->shade.simd >= SR_SIMD_AVX512 };
}

/* The slot lanes (sr_subpixel_slot_group_avx2) gather a triangle list's
 * snapped points by signed 32-bit indices: with the sub-pixel lanes at
 * the AVX2 level or above, where every vertex's index fits. */
static bool slot_lanes(const sr_draw_state *st)
{
    return st->subpixel_lanes && st->subpixel.avx2 && st->desc->mesh->topology == SR_TRIANGLE_LIST &&
           st->vertex_count <= INT32_MAX;
}

/* A mesh outside the view: every assembled triangle is rejected, nothing
 * is transformed. */
static void reject_all(const sr_draw_state *st, unsigned outside)
{
    sr_stats *stats = &st->ws->threads[0].stats;
    uint32_t idx[3];
    for (uint32_t k = 0; k < st->slots; k++)
        stats->triangles += sr_assemble_triangle(st->desc->mesh, k, idx);
    sr_clip_count_rejected(stats, outside, stats->triangles);
}

/* Every thread's counts, and its cuts by precision, into stats. */
static void sum_counts(const sr_draw_state *st, sr_stats *stats)
{
    for (int t = 0; t < st->threads; t++) {
        sr_thread_work *w = &st->ws->threads[t];
        w->stats.cuts_float = w->cuts.cuts[SR_CLIP_FLOAT];
        w->stats.cuts_double = w->cuts.cuts[SR_CLIP_DOUBLE];
        w->stats.cuts_exact = w->cuts.cuts[SR_CLIP_EXACT];
        sr_stats_add(stats, &w->stats);
    }
}

static bool draw_with(sr_draw_state *st, sr_stats *stats, sr_error *err)
{
    for (int t = 0; t < st->threads; t++) {
        st->ws->threads[t].stats = (sr_stats){ 0 };
        st->ws->threads[t].cuts = (sr_clip_counts){ { 0 } };
    }
    /* sr_workspace_simd_draws sums every thread's: an earlier draw on more
     * threads must leave nothing in those this one does not use. */
    for (int t = 0; t < SR_MAX_THREADS; t++)
        st->ws->threads[t].simd_draws = 0;
    vertex_phase ph = { .st = st };
    make_transform(st, &ph.xf);
    st->xf = &ph.xf;
    const sr_mesh *mesh = st->desc->mesh;
    if (!sr_assemble_triangles(mesh)) {
        bool drawn = sr_draw_points_lines(st, err);
        sum_counts(st, stats);
        return drawn;
    }
    /* Bounds are of the positions: clip-space input is classified per vertex. */
    unsigned outside = 0;
    sr_clip_box box = mesh->bounded && !mesh->clip_positions
                          ? sr_clip_classify_box_planes(ph.xf.clip_from_object, mesh->bounds_lo, mesh->bounds_hi,
                                                        &outside)
                          : SR_BOX_CROSSES;
    /* An empty mesh (valid indices: none) has nothing to draw. */
    bool draws = box != SR_BOX_OUTSIDE && st->vertex_count > 0;
    if (!draws && !sr_assemble_indices_valid(mesh)) /* else the vertex phase checks them */
        return index_error(st, err);
    st->subpixel_lanes = draws && subpixel_lanes(st, &ph.xf); /* no estimate for a mesh out of view */
    st->slot_lanes = slot_lanes(st);
    if (!worth_threads(st))
        st->threads = 1;
    sr_draw_path planned = planned_path(st);
    st->band_rows = planned == SR_PATH_ROWS ? sr_band_rows(st->fb->height) : 0;
    st->snapped_points = st->slot_lanes || st->band_rows;
    /* The tiles set a triangle up in the phase that keeps it, while another
     * thread may be mapping its vertices' double half: they map all. */
    st->double_later = st->subpixel_lanes && planned != SR_PATH_TILES;
    if (draws) {
        ph.inside = box == SR_BOX_INSIDE;
        if (!run_vertex_phase(st, &ph, err))
            return false;
    }
    sr_draw_path path = draws ? path_of(st, planned) : SR_PATH_DIRECT;
    if (st->study.times) {
        st->study.times->path = path;
        st->study.times->subpixel_lanes = st->subpixel_lanes;
    }
    bool direct = path == SR_PATH_DIRECT;
    /* double_later holds only for the direct path and the row bands (the
     * planned path, or direct in its place): on one thread the verdicts
     * map the double halves as they go, on the row bands' several a
     * phase after them maps what they mark. */
    st->double_phase = st->double_later && path == SR_PATH_ROWS && st->threads > 1;
    /* Nothing is written before every check has passed; the tiles and the
     * row bands clear the rows they draw, as they draw them. */
    if (st->desc->clear && direct)
        sr_framebuffer_clear(st->fb, st->desc->clear_color);
    if (box == SR_BOX_OUTSIDE) {
        reject_all(st, outside);
    } else if (draws) {
        if (direct) {
            sr_parallel_run(&st->ws->pool, 1, sr_draw_direct, st, st->study.times ? &st->study.times->primitives : NULL);
        } else if (path == SR_PATH_ROWS) {
            if (!sr_draw_rows(st))
                return sr_error_set(err, "out of memory for the row bands of %u triangles", st->slots);
        } else if (!sr_draw_binned(st)) {
            return sr_error_set(err, "out of memory for the tile bins of %u triangles", st->slots);
        }
    }
    sum_counts(st, stats);
    return true;
}

/* The projection's depth model (clip.h); off for clip-space input, whose z
 * no projection made. */
static sr_clip_depth clip_depth(const sr_draw_desc *d)
{
    if (d->mesh->clip_positions)
        return (sr_clip_depth){ .on = false };
    return sr_clip_depth_of((const float(*)[4])d->projection);
}

/* Several threads need the observer called in order from one thread, so a
 * draw with an observer runs on one. */
static int thread_count(const sr_draw_desc *d, const sr_draw_study *s)
{
    if (s->observer || d->threads <= 1)
        return 1;
    return d->threads < SR_MAX_THREADS ? d->threads : SR_MAX_THREADS;
}

/* The varyings the mode reads: a mesh with materials is textured where
 * one of them has a texture (and the mesh uvs); texture shading of one
 * whose materials have none draws their colours, from no varyings. Points
 * and lines are drawn without the materials (sr_materials_make). */
static sr_varying_layout draw_layout(sr_shade mode, const sr_draw_desc *d)
{
    const sr_mesh *mesh = d->mesh;
    if (mesh->material_count == 0 || !sr_assemble_triangles(mesh))
        return sr_vertex_layout(mode, mesh, d->texture && d->texture->texels);
    bool textured = mesh->materials && sr_materials_textured(mesh, d->texture) && mesh->uvs;
    if (mode == SR_SHADE_TEXTURE && !textured)
        return (sr_varying_layout){ .color = -1, .uv = -1, .normal = -1 };
    return sr_materials_layout(mode, d, sr_vertex_layout(mode, mesh, textured)); /* uvs for MASK's alpha */
}

static bool draw(sr_framebuffer *fb, const sr_draw_desc *desc, const sr_line_filter *filter, sr_stats *stats,
                 sr_error *err)
{
    if (!desc)
        return sr_error_set(err, "draw without a description");
    double start = sr_now_ms();
    const sr_draw_study study = desc->study ? *desc->study : (sr_draw_study){ 0 };
    sr_shade mode = study.count_hits ? SR_RASTER_COUNT_HITS : desc->shade;
    sr_varying_layout layout = { .color = -1, .uv = -1, .normal = -1 };
    if (desc->mesh)
        layout = draw_layout(mode, desc);
    if (!check_inputs(fb, desc, &study, &layout, err))
        return false;
    sr_workspace *ws = desc->workspace ? desc->workspace : sr_workspace_create();
    if (!ws)
        return sr_error_set(err, "out of memory for a workspace");
    sr_draw_state st = { .fb = fb, .desc = desc, .study = study, .mode = mode, .ws = ws,
                         .threads = thread_count(desc, &study),
                         .vertex_count = desc->mesh->vertex_count, .slots = sr_assemble_slots(desc->mesh),
                         .tile_rows = SR_TILE_ROWS(fb->width),
                         .vp = { fb->width, fb->height, subpixel_bits(&study), guard_band(&study),
                                 clip_depth(desc) },
                         .precision = study.clip_precision, .line_filter = filter };
    st.tiles = (fb->height + st.tile_rows - 1) / st.tile_rows;
    /* Half a subpixel step, in NDC of the squeezed clip space of a guard band. */
    int side = fb->width > fb->height ? fb->width : fb->height;
    st.clip_tolerance = 1.0 / ((double)((int64_t)1 << st.vp.subpixel_bits) * side * st.vp.guard);
    shade_context_make(desc, study.simd, &layout, &st.shade);
    st.screen_stride = sr_screen_stride(layout.count);
    st.subpixel = subpixel_rules(&st);
    sr_stats scratch = { 0 };
    bool ok = sr_materials_make(&st, err) && draw_with(&st, stats ? stats : &scratch, err);
    if (!desc->workspace)
        sr_workspace_destroy(ws);
    if (study.times)
        study.times->total += sr_now_ms() - start;
    return ok;
}

bool sr_draw(sr_framebuffer *fb, const sr_draw_desc *desc, sr_stats *stats, sr_error *err)
{
    return draw(fb, desc, NULL, stats, err);
}

bool sr_draw_lines_filtered(sr_framebuffer *fb, const sr_draw_desc *desc, const sr_line_filter *filter,
                            sr_stats *stats, sr_error *err)
{
    return draw(fb, desc, filter, stats, err);
}
