#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "wireframe.h"
#include "core/clock.h"
#include "core/dmat4.h"
#include "core/error.h"
#include "pipeline/01_vertex.h"
#include "pipeline/02_assemble.h"
#include "scene/frame.h"

/* The mesh's arrays under another topology and `count` new indices. */
static bool borrow(const sr_mesh *mesh, sr_mesh *out, size_t count, sr_topology topology, sr_error *err)
{
    *out = *mesh;
    out->parts = NULL;
    out->part_count = 0;
    out->texture_path = NULL;
    out->topology = topology;
    out->index_count = (uint32_t)count;
    out->indices = malloc((count ? count : 1) * sizeof *out->indices);
    if (count > UINT32_MAX || !out->indices) {
        free(out->indices);
        *out = (sr_mesh){ 0 };
        return sr_error_set(err, "out of memory for %zu indices", count);
    }
    return true;
}

bool sr_wireframe_points(const sr_mesh *mesh, sr_mesh *points, sr_error *err)
{
    if (!borrow(mesh, points, mesh->vertex_count, SR_POINT_LIST, err))
        return false;
    for (uint32_t i = 0; i < mesh->vertex_count; i++)
        points->indices[i] = i;
    return true;
}

/* An edge as its two ends' first vertices of their positions, smaller
 * first, and where it first appeared. */
typedef struct edge {
    uint64_t key;
    size_t first;
} edge;

static int by_key_then_first(const void *a, const void *b)
{
    const edge *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return (x->first > y->first) - (x->first < y->first);
}

static int by_first(const void *a, const void *b)
{
    const edge *x = a, *y = b;
    return (x->first > y->first) - (x->first < y->first);
}

static uint64_t edge_key(uint32_t a, uint32_t b)
{
    return a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
}

/* A vertex's position, for sorting: its three floats' bits. */
static const vec3 *sorted_positions;

static int by_position(const void *a, const void *b)
{
    int c = memcmp(sorted_positions[*(const uint32_t *)a], sorted_positions[*(const uint32_t *)b], sizeof(vec3));
    return c ? c : (*(const uint32_t *)a > *(const uint32_t *)b) - (*(const uint32_t *)a < *(const uint32_t *)b);
}

/* Each vertex's first vertex of the same position (bit for bit), so the
 * copies a loader makes of a position (one per normal or uv: each face of
 * a cube) share their edges; a clip-space mesh by its own indices. */
static uint32_t *same_position(const sr_mesh *mesh)
{
    uint32_t n = mesh->vertex_count, *order = malloc(((size_t)n + 1) * sizeof *order),
             *first = malloc(((size_t)n + 1) * sizeof *first);
    if (!order || !first) {
        free(order);
        free(first);
        return NULL;
    }
    for (uint32_t i = 0; i < n; i++)
        order[i] = first[i] = i;
    if (mesh->positions) {
        sorted_positions = (const vec3 *)mesh->positions;
        qsort(order, n, sizeof *order, by_position);
        for (uint32_t i = 1; i < n; i++)
            if (memcmp(mesh->positions[order[i]], mesh->positions[order[i - 1]], sizeof(vec3)) == 0)
                first[order[i]] = first[order[i - 1]];
    }
    free(order);
    return first;
}

bool sr_wireframe_edges(const sr_mesh *mesh, sr_mesh *lines, sr_error *err)
{
    uint32_t slots = sr_assemble_slots(mesh), *first = same_position(mesh);
    edge *edges = malloc(((size_t)slots * 3 + 1) * sizeof *edges);
    uint32_t *ends = malloc(((size_t)slots * 6 + 1) * sizeof *ends);
    if (!edges || !first || !ends) {
        free(edges);
        free(first);
        free(ends);
        return sr_error_set(err, "out of memory for the edges of %u triangles", slots);
    }
    size_t n = 0;
    for (uint32_t k = 0; k < slots; k++) {
        uint32_t idx[3];
        if (!sr_assemble_triangle(mesh, k, idx))
            continue;
        for (int e = 0; e < 3; e++, n++) {
            uint32_t a = idx[e], b = idx[(e + 1) % 3];
            edges[n] = (edge){ edge_key(first[a], first[b]), n };
            ends[2 * n] = a < b ? a : b;
            ends[2 * n + 1] = a < b ? b : a;
        }
    }
    free(first);
    qsort(edges, n, sizeof *edges, by_key_then_first);
    size_t unique = 0;
    for (size_t i = 0; i < n; i++)
        if (i == 0 || edges[i].key != edges[i - 1].key)
            edges[unique++] = edges[i];
    qsort(edges, unique, sizeof *edges, by_first);
    bool ok = borrow(mesh, lines, 2 * unique, SR_LINE_LIST, err);
    for (size_t i = 0; ok && i < unique; i++) {
        lines->indices[2 * i] = ends[2 * edges[i].first];
        lines->indices[2 * i + 1] = ends[2 * edges[i].first + 1];
    }
    free(edges);
    free(ends);
    return ok;
}

void sr_wireframe_free(sr_mesh *borrowed)
{
    free(borrowed->indices);
    *borrowed = (sr_mesh){ 0 };
}

/* Three pixels' width of view depth: a line pixel's centre lies up to 0.7
 * pixel off the line, and a face at 75° to the view changes depth by
 * tan 75° ≈ 3.7 widths per width across. */
#define BIAS_PIXELS 3.0

/* The view depth of the mesh's nearest bounding-box corner, through the
 * desc's world and view (and the mesh's origin), in double. */
static double nearest_depth(const sr_draw_desc *desc)
{
    const sr_mesh *mesh = desc->mesh;
    vec3 lo, hi;
    if (!sr_mesh_bounds(mesh, lo, hi))
        return INFINITY;
    sr_dmat4 world = sr_dmat4_desc_matrix(&desc->world_d, desc->world);
    sr_dmat4 view = sr_dmat4_desc_matrix(&desc->view_d, desc->view), none = sr_dmat4_identity();
    sr_vertex_transform xf;
    sr_vertex_make_transform_d(&world, &view, &none, mesh->origin, &xf);
    double nearest = INFINITY;
    for (int k = 0; k < 8; k++) {
        const float corner[3] = { (k & 1) ? hi[0] : lo[0], (k & 2) ? hi[1] : lo[1], (k & 4) ? hi[2] : lo[2] };
        double c[4];
        sr_vertex_clip_d(corner, &xf, c);
        nearest = fmin(nearest, c[SR_Z]);
    }
    return nearest;
}

float sr_wireframe_depth_bias(const sr_draw_desc *desc, int height)
{
    const float(*p)[4] = (const float(*)[4])desc->projection;
    /* z_ndc and w of view depth d from the projection's z and w rows; the
     * near plane is the nearer of the depths where z_ndc is 0 and 1
     * (standard or reversed). */
    double planes[2] = { -(double)p[3][2] / p[2][2], ((double)p[3][3] - p[3][2]) / ((double)p[2][2] - p[2][3]) };
    double near = INFINITY;
    for (int k = 0; k < 2; k++)
        if (planes[k] > 0.0 && isfinite(planes[k]))
            near = fmin(near, planes[k]);
    double d = nearest_depth(desc);
    if (!(d >= near))
        d = near;
    double w = p[2][3] * d + p[3][3];
    double width = 2.0 * w / (height * (double)p[1][1]);
    double e = d + BIAS_PIXELS * fabs(width);
    double z0 = (p[2][2] * d + p[3][2]) / w, z1 = (p[2][2] * e + p[3][2]) / (p[2][3] * e + p[3][3]);
    double bias = fabs(z1 - z0);
    return isfinite(bias) ? (float)fmin(bias, 1.0) : 0.0f;
}

bool sr_wireframe_frame(sr_framebuffer *fb, const sr_draw_desc *fill, const sr_draw_desc *lines, sr_stats *fill_stats,
                        sr_stats *line_stats, double *ms, sr_error *err)
{
    sr_draw_desc depth_only = *fill;
    depth_only.shade = SR_SHADE_DEPTH;
    double start = sr_now_ms(), fill_ms;
    *line_stats = (sr_stats){ 0 };
    bool ok = sr_frame_draw_timed(fb, &depth_only, fill_stats, &fill_ms, err) && sr_draw(fb, lines, line_stats, err);
    *ms = sr_now_ms() - start;
    return ok;
}
