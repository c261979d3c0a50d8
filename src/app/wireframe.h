/* wireframe.h — a mesh's vertices as points, and its edges as lines with
 * the triangles that own each (what the hidden-line frame reads,
 * hidden_lines.h). */
#ifndef SOFTRAST_APP_WIREFRAME_H
#define SOFTRAST_APP_WIREFRAME_H

#include "softrast_private.h"

/* A mesh of the same vertex arrays (borrowed: free it with
 * sr_wireframe_free, never sr_mesh_free) drawn as SR_POINT_LIST, every
 * vertex once in order. False, with a message, when out of memory. */
bool sr_wireframe_points(const sr_mesh *mesh, sr_mesh *points, sr_error *err);
void sr_wireframe_free(sr_mesh *borrowed);

/* A triangle edge of no line: the edges of a slot that holds no triangle. */
#define SR_WIREFRAME_NO_EDGE UINT32_MAX

/* A mesh's wireframe. edges: the same vertex arrays (borrowed) drawn as
 * SR_LINE_LIST of the triangles' edges, each once, in the order of their
 * first appearance (triangle slots in order, edges v0-v1, v1-v2, v2-v0),
 * so line id k + 1 names the k-th; an edge is its two end positions, so
 * the copies of a vertex that a loader makes (one per face normal or uv)
 * give one line, the first one's, its smaller index first.
 * triangle_edges: 3 per triangle slot, the lines of its edges v0-v1,
 * v1-v2, v2-v0 (every triangle with both ends of a line owns it). */
typedef struct sr_wireframe {
    sr_mesh edges;
    uint32_t *triangle_edges;
    uint32_t triangle_slots;
} sr_wireframe;

/* False, with a message, when out of memory (then w is all zero). */
bool sr_wireframe_make(const sr_mesh *mesh, sr_wireframe *w, sr_error *err);
void sr_wireframe_destroy(sr_wireframe *w);

#endif
