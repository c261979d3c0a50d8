/* wireframe.h — a mesh's vertices as points and its edges as lines, and
 * the hidden-line draw of `render --lines` and the viewer's wireframe:
 * the triangles fill depth first, then the edges pass the depth test with
 * a bias (docs/conventions.md, "Points and lines"). */
#ifndef SOFTRAST_APP_WIREFRAME_H
#define SOFTRAST_APP_WIREFRAME_H

#include "softrast_private.h"

/* A mesh of the same vertex arrays (borrowed: free it with
 * sr_wireframe_free, never sr_mesh_free) drawn as SR_POINT_LIST, every
 * vertex once in order, or as SR_LINE_LIST of the triangles' edges, each
 * once, in the order of their first appearance (triangle slots in order,
 * edges v0-v1, v1-v2, v2-v0), so line id k + 1 names the k-th; an edge is
 * its two end positions, so the copies of a vertex that a loader makes
 * (one per face normal or uv) give one line, the first one's, its smaller
 * index first. False, with a message, when out of memory. */
bool sr_wireframe_points(const sr_mesh *mesh, sr_mesh *points, sr_error *err);
bool sr_wireframe_edges(const sr_mesh *mesh, sr_mesh *lines, sr_error *err);
void sr_wireframe_free(sr_mesh *borrowed);

/* The lines' depth bias for desc's camera and mesh in a framebuffer
 * `height` rows tall: the z_ndc that three pixels' width of view depth
 * takes at the mesh's nearest point (no nearer than the camera's near
 * plane), which covers the tie of a line on a face turned up to about 75°
 * from the view (a line pixel's centre lies up to 0.7 pixel off the
 * line). */
float sr_wireframe_depth_bias(const sr_draw_desc *desc, int height);

/* One frame of hidden lines into fb: `fill` (its mesh's triangles, its
 * camera) cleared to color 0 and drawn into depth alone, then `lines`
 * with the bias. The counts of each draw into fill_stats and line_stats
 * (zeroed first), the time of both into *ms. */
bool sr_wireframe_frame(sr_framebuffer *fb, const sr_draw_desc *fill, const sr_draw_desc *lines, sr_stats *fill_stats,
                        sr_stats *line_stats, double *ms, sr_error *err);

#endif
