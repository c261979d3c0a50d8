/* 02_assemble.h — stage 2: primitive assembly.
 *
 * Turns a mesh's index array into triangles (points and lines: below). TriangleList: triangle k is
 * (i[3k], i[3k+1], i[3k+2]). TriangleStrip: triangle k is (i[k], i[k+1],
 * i[k+2]) with the last two swapped for odd k, so all keep one winding. A
 * triangle with a repeated index is degenerate and is skipped (the strip's
 * way of restarting).
 */
#ifndef SOFTRAST_PIPELINE_ASSEMBLE_H
#define SOFTRAST_PIPELINE_ASSEMBLE_H

#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "softrast/softrast.h"

/* Whether the mesh draws triangles (else points or lines: points_lines.c). */
static inline bool sr_assemble_triangles(const sr_mesh *mesh)
{
    return mesh->topology == SR_TRIANGLE_LIST || mesh->topology == SR_TRIANGLE_STRIP;
}

/* How many triangle slots the mesh's indices make: a list's triples, a
 * strip's windows of three; none for points and lines. */
static inline uint32_t sr_assemble_slots(const sr_mesh *mesh)
{
    if (mesh->topology == SR_TRIANGLE_STRIP)
        return mesh->index_count >= 3 ? mesh->index_count - 2 : 0;
    return mesh->topology == SR_TRIANGLE_LIST ? mesh->index_count / 3 : 0;
}

/* How many point or line slots: every index a point; a line list's pairs,
 * a line strip's windows of two. */
static inline uint32_t sr_assemble_point_line_slots(const sr_mesh *mesh)
{
    if (mesh->topology == SR_POINT_LIST)
        return mesh->index_count;
    if (mesh->topology == SR_LINE_STRIP)
        return mesh->index_count >= 2 ? mesh->index_count - 1 : 0;
    return mesh->index_count / 2;
}

/* Writes line k's two vertex indices (a strip's k and k + 1, so
 * neighbours share a vertex); false if it is degenerate (a repeated
 * index: a strip's way of restarting, as for triangles). */
static inline bool sr_assemble_line(const sr_mesh *mesh, uint32_t k, uint32_t out[2])
{
    size_t first = mesh->topology == SR_LINE_STRIP ? (size_t)k : 2 * (size_t)k;
    out[0] = mesh->indices[first];
    out[1] = mesh->indices[first + 1];
    return out[0] != out[1];
}

/* Writes triangle k's three vertex indices; false if it is degenerate.
 * k must be below sr_assemble_slots(mesh). Inline: called once per
 * triangle slot. */
static inline bool sr_assemble_triangle(const sr_mesh *mesh, uint32_t k, uint32_t out[3])
{
    if (mesh->topology == SR_TRIANGLE_STRIP) {
        uint32_t odd = k & 1;
        out[0] = mesh->indices[k];
        out[1] = mesh->indices[k + 1 + odd];
        out[2] = mesh->indices[k + 2 - odd];
    } else {
        memcpy(out, &mesh->indices[3 * (size_t)k], 3 * sizeof(uint32_t));
    }
    return out[0] != out[1] && out[1] != out[2] && out[0] != out[2];
}

/* Where triangle k's three indices sit, in some order (list: 3k, 3k+1,
 * 3k+2; strip: k, k+1, k+2): enough to prefetch its vertices. */
static inline const uint32_t *sr_assemble_slot_indices(const sr_mesh *mesh, uint32_t k)
{
    return mesh->indices + (mesh->topology == SR_TRIANGLE_STRIP ? (size_t)k : 3 * (size_t)k);
}

/* A loop over slots [k, end) prefetches the indices of the slot
 * SR_INDICES_AHEAD on (1.5 KB on in a triangle list), or near the end its
 * own again: the hardware prefetcher left the loops over slots waiting on
 * the index stream (docs/performance.md, "From slot to
 * set-up"). A macro for the reason PREFETCH_TRIANGLE is one
 * (primitives.c). */
#define SR_INDICES_AHEAD 128
#define SR_PREFETCH_SLOT_INDICES(mesh, k, end)                                                                \
    __builtin_prefetch(                                                                                        \
        sr_assemble_slot_indices((mesh), (end) - (k) > SR_INDICES_AHEAD ? (k) + SR_INDICES_AHEAD : (k)))

/* True if every index is below vertex_count (checked once per draw). */
bool sr_assemble_indices_valid(const sr_mesh *mesh);

/* The same for indices [first, end): a draw's threads check a share each. */
bool sr_assemble_indices_valid_in(const sr_mesh *mesh, uint32_t first, uint32_t end);

#endif
