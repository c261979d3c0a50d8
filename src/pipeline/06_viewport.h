/* 06_viewport.h — stage 6: perspective divide and viewport mapping.
 *
 * NDC (x, y in [-1, 1], z in [0, 1]) to pixels: px = (x + 1)·W/2,
 * py = (1 - y)·H/2 (top-left origin, y down), snapped to 1/256 pixel (or
 * 2^-subpixel_bits). 1/w is kept, and the varyings are stored divided by w
 * for perspective-correct interpolation.
 *
 * A guard band G > 1 means clip space was squeezed by 1/G in x and y before
 * clipping (the draw's guard-band mode), so the side planes sat at ±G·w: the
 * divide scales x and y back by G, and vertices land up to (G − 1)·W/2 pixels
 * outside the framebuffer, still bounded for the fixed-point conversion.
 */
#ifndef SOFTRAST_PIPELINE_VIEWPORT_H
#define SOFTRAST_PIPELINE_VIEWPORT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "01_vertex.h"
#include "stages.h"

/* How far past [-1, 1] a clipped vertex may land from rounding before it is
 * treated as broken input rather than a hair outside (DESIGN.md: the scan
 * rectangle is clamped, vertices are never moved). */
#define SR_NDC_SLACK 1e-3

typedef struct sr_viewport {
    int width, height;
    int subpixel_bits; /* SR_SUBPIXEL_BITS */
    float guard;       /* 1: no guard band */
    sr_clip_depth depth; /* on: z_ndc = a + b/w (types.h); zero: z/w */
} sr_viewport;

/* False when w <= 0, when 1/w or a varying/w is not finite (NaN or inf in a
 * varying, or w below 2^-128), or when x, y, z lie past the slack: the caller
 * drops the polygon and counts it. Never false for a vertex with finite
 * varyings that the clipper left inside. */
bool sr_viewport_map(const sr_vertex_out *v, int varyings, const sr_viewport *vp, sr_screen_vertex *out);

/* sr_viewport_map for a vertex of the mesh, whose clip position the vertex
 * stage can give in double as well (clip_d, sr_vertex_clip_d): the
 * unsnapped point and z come from it, since the float position is off by up
 * to about 1e-4 px, enough to tilt a steep sliver's depth plane past 1e-6
 * (docs/precision.md, "Depth from the unsnapped vertices"). The snapped
 * point, so coverage, is the float position's, as sr_viewport_map makes it
 * for the clipper's copy of the same vertex. */
bool sr_viewport_map_d(const sr_vertex_out *v, const double clip_d[4], int varyings, const sr_viewport *vp,
                       sr_screen_vertex *out);

/* sr_viewport_map_d in two halves, for a draw that needs the second only
 * for some of its vertices (those of the triangles the sub-pixel lanes
 * keep, primitives.c). The float half, of each v[k] (k < n) whose codes[k]
 * is 0, into the screen vertex k·stride bytes into out: the snapped point,
 * 1/w and the varyings divided by w (x, y, inv_w, var_w), from the float
 * position; codes[k] becomes SR_OUT_NONFINITE exactly where
 * sr_viewport_map_d would refuse v[k]; with points, every k's snapped
 * point into points[k] (stages.h: SR_SNAPPED_OUTSIDE where codes[k] is
 * not 0 at the end). The double half, of the n mesh
 * vertices index[k] whose float half is in the screen vertex
 * index[k]·stride bytes into screen: x_off, y_off and z from their clip
 * positions in double (sr_vertex_mesh_clip_d under xf). Each takes two
 * vertices at a time in SSE2 lanes of double, four in AVX2 ones with avx2
 * (06_viewport_lanes.h), the scalar map's operations in each. Neither
 * writes a member the other writes, so one thread may read a vertex's
 * snapped point while another maps its double half. */
void sr_viewport_map_float_block(const sr_vertex_out *v, uint32_t n, int varyings, const sr_viewport *vp, bool avx2,
                                 unsigned char *codes, void *out, size_t stride, sr_snapped_point *points);
void sr_viewport_map_double_block(const sr_mesh *mesh, const sr_vertex_transform *xf, const uint32_t *index,
                                  uint32_t n, const sr_viewport *vp, bool avx2, void *screen, size_t stride);

/* sr_viewport_map_d for a clip position in double that may not be of use
 * (a cut's point from its lines, which may barely meet): where it is not
 * finite, has w <= 0 or lies past the slack, the vertex maps from its
 * float position alone. A clipped line's cut ends map so
 * (points_lines.c), as a clipped triangle's vertices do below. */
bool sr_viewport_map_checked_d(const sr_vertex_out *v, const double clip_d[4], int varyings, const sr_viewport *vp,
                               sr_screen_vertex *out);

/* Maps the polygon the clipper made from a triangle (sr_clip_polygon) whose
 * vertices' clip positions in double are tri_d, into out[0 .. count): each
 * vertex as sr_viewport_map_d maps it with the triangle's point on its two
 * lines (sr_clip_point_on_lines_d) for clip_d, so a corner of the triangle
 * maps as the vertex phase maps it and a cut takes its depth from the
 * triangle in double. Where that point is not finite, has w <= 0 or lies
 * past the slack (lines that barely meet), the vertex maps from its float
 * position alone, as sr_viewport_map does. False as soon as a vertex is
 * refused. */
bool sr_viewport_map_polygon(const sr_polygon *poly, const double tri_d[3][4], int varyings, const sr_viewport *vp,
                             sr_screen_vertex *out);

#endif
