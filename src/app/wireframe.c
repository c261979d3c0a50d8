#include <stdlib.h>
#include <string.h>

#include "wireframe.h"
#include "core/error.h"
#include "pipeline/02_assemble.h"

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

/* A triangle's edge as its two ends' first vertices of their positions,
 * smaller first, and its place 3·slot + edge. */
typedef struct edge {
    uint64_t key;
    uint32_t at;
} edge;

static int by_key_then_place(const void *a, const void *b)
{
    const edge *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return (x->at > y->at) - (x->at < y->at);
}

static int by_place(const void *a, const void *b)
{
    const edge *x = a, *y = b;
    return (x->at > y->at) - (x->at < y->at);
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

/* The triangles' edges, at their places 3·slot + edge, sorted by key, and
 * their ends (2 per place, smaller index first); the count into *n. */
static edge *triangle_edges(const sr_mesh *mesh, uint32_t slots, uint32_t *ends, size_t *n)
{
    uint32_t *first = same_position(mesh);
    edge *edges = malloc(((size_t)slots * 3 + 1) * sizeof *edges);
    if (!first || !edges) {
        free(first);
        free(edges);
        return NULL;
    }
    *n = 0;
    for (uint32_t k = 0; k < slots; k++) {
        uint32_t idx[3];
        if (!sr_assemble_triangle(mesh, k, idx))
            continue;
        for (uint32_t e = 0; e < 3; e++) {
            uint32_t a = idx[e], b = idx[(e + 1) % 3], at = 3 * k + e;
            edges[(*n)++] = (edge){ edge_key(first[a], first[b]), at };
            ends[2 * (size_t)at] = a < b ? a : b;
            ends[2 * (size_t)at + 1] = a < b ? b : a;
        }
    }
    free(first);
    qsort(edges, *n, sizeof *edges, by_key_then_place);
    return edges;
}

bool sr_wireframe_make(const sr_mesh *mesh, sr_wireframe *w, sr_error *err)
{
    *w = (sr_wireframe){ .triangle_slots = sr_assemble_slots(mesh) };
    uint32_t slots = w->triangle_slots;
    size_t n = 0, unique = 0;
    uint32_t *ends = malloc(((size_t)slots * 6 + 1) * sizeof *ends);
    w->triangle_edges = malloc(((size_t)slots * 3 + 1) * sizeof *w->triangle_edges);
    edge *edges = ends && w->triangle_edges ? triangle_edges(mesh, slots, ends, &n) : NULL;
    uint32_t *line_of = edges ? malloc((n + 1) * sizeof *line_of) : NULL;
    if (!line_of) {
        free(ends);
        free(edges);
        free(w->triangle_edges);
        *w = (sr_wireframe){ 0 };
        return sr_error_set(err, "out of memory for the edges of %u triangles", slots);
    }
    for (size_t i = 0; i < (size_t)slots * 3; i++)
        w->triangle_edges[i] = SR_WIREFRAME_NO_EDGE;
    /* Each key's first place stands for it (its key now its rank by key);
     * every place of the key names that rank until the lines are known. */
    uint64_t previous = 0;
    for (size_t i = 0; i < n; i++) {
        uint64_t key = edges[i].key;
        uint32_t at = edges[i].at;
        if (i == 0 || key != previous) {
            edges[unique] = (edge){ unique, at };
            unique++;
        }
        previous = key;
        w->triangle_edges[at] = (uint32_t)(unique - 1);
    }
    qsort(edges, unique, sizeof *edges, by_place);
    bool ok = borrow(mesh, &w->edges, 2 * unique, SR_LINE_LIST, err);
    for (size_t line = 0; ok && line < unique; line++) {
        line_of[edges[line].key] = (uint32_t)line;
        w->edges.indices[2 * line] = ends[2 * (size_t)edges[line].at];
        w->edges.indices[2 * line + 1] = ends[2 * (size_t)edges[line].at + 1];
    }
    for (size_t i = 0; ok && i < (size_t)slots * 3; i++)
        if (w->triangle_edges[i] != SR_WIREFRAME_NO_EDGE)
            w->triangle_edges[i] = line_of[w->triangle_edges[i]];
    free(ends);
    free(edges);
    free(line_of);
    if (!ok)
        sr_wireframe_destroy(w);
    return ok;
}

void sr_wireframe_free(sr_mesh *borrowed)
{
    free(borrowed->indices);
    *borrowed = (sr_mesh){ 0 };
}

void sr_wireframe_destroy(sr_wireframe *w)
{
    free(w->edges.indices);
    free(w->triangle_edges);
    *w = (sr_wireframe){ 0 };
}
