/* hidden_lines.h — the hidden-line frame of `render --lines` and the
 * viewer's wireframe (F6): a mesh's triangles fill depth and their ids,
 * then its edges are drawn, each line fragment kept only where a triangle
 * that owns the line shows at its pixel or next to it and the face seen
 * at the pixel does not hide it (docs/conventions.md, "Points and lines":
 * the rule and its ties). */
#ifndef SOFTRAST_APP_HIDDEN_LINES_H
#define SOFTRAST_APP_HIDDEN_LINES_H

#include "softrast_private.h"
#include "wireframe.h"

/* A mesh's wireframe and what its frames need: the lines' width, and of
 * the last frame the fill's planes, the mesh's clip positions and which
 * lines border a face culling keeps. */
typedef struct sr_hidden_lines {
    sr_wireframe wire;
    float line_width;   /* sr_draw_desc.line_width: 0 is 1 */
    uint32_t *fill_ids; /* triangle id + 1 per pixel, 0: none */
    float *fill_depth;
    size_t pixels; /* of the fill planes */
    double (*clip)[4]; /* per vertex */
    bool *kept;        /* per line */
} sr_hidden_lines;

/* The wireframe of mesh (borrowed: it must outlive h), no planes yet.
 * False, with a message, when out of memory (then h is all zero). */
bool sr_hidden_lines_make(const sr_mesh *mesh, sr_hidden_lines *h, sr_error *err);
void sr_hidden_lines_destroy(sr_hidden_lines *h);

/* One frame into fb: `fill` (the mesh's triangles, their camera and
 * culling) cleared to color 0 and drawn into depth and h's fill planes
 * alone, then h's edges with fill's camera, shading, threads and study
 * (but its observer: a clipping diagnostic is the triangles'), each
 * fragment kept by the rule, drawn a hair in front of the fill at its
 * pixel and depth-tested against the other lines (fb's ids, if it has
 * them, get the lines' alone). The same pixels on every thread count and
 * path. The counts of each draw into fill_stats and line_stats (zeroed
 * first), the time of both into *ms. */
bool sr_hidden_lines_frame(sr_hidden_lines *h, sr_framebuffer *fb, const sr_draw_desc *fill, sr_stats *fill_stats,
                           sr_stats *line_stats, double *ms, sr_error *err);

#endif
