/* clip.h — stage 4: clipping.
 *
 * A triangle whose outcodes (classify.h) cross a plane is clipped with Sutherland–Hodgman
 * against exactly the planes in the OR of the outcodes, in the fixed order of
 * sr_clip_plane. The result is a convex polygon of at most SR_MAX_CLIP_VERTS
 * vertices, still in clip space; fan it as (v0, vi, vi+1) before the divide.
 *
 * The watertight rule (DESIGN.md): every cut vertex is interpolated from the
 * inside end point toward the outside one, t = d_in / (d_in - d_out), in
 * the precision sr_clip_config asks for, and its coordinate for the plane is then set exactly on
 * the plane (x = -w for left, z = 0 for near, ...; under a depth model a near
 * or far cut gets z = a·w + b of its w, rounded once). Two triangles sharing an
 * edge therefore get bit-identical cut vertices whichever way they walk it.
 *
 * Under adaptive and exact precision a triangle that crosses two planes or
 * more is cut from its own vertices, never from an earlier cut rounded to
 * float: a polygon edge on an edge of the triangle is cut as that whole edge
 * (the end points are the triangle's vertices, so a shared edge cuts alike
 * after any planes), one on an earlier plane's cut line at the triangle's
 * point on both planes (clip_corner.h), rounded once. Where that cannot be
 * done (no corner: a degenerate triangle, or lines parallel in it) the
 * triangle is clipped edge by edge, as the fixed float and double knobs
 * always do, and counted. Every polygon vertex is classified against the
 * next plane by the exact point it was rounded from (sr_clip_exact_side), so
 * the polygon is the exact one.
 */
#ifndef SOFTRAST_PIPELINE_CLIP_H
#define SOFTRAST_PIPELINE_CLIP_H

#include <stdint.h>

#include "pipeline/03_classify.h"

/* How many cut vertices each precision made (index: sr_clip_precision). */
typedef struct sr_clip_counts {
    uint64_t cuts[SR_CLIP_PRECISIONS];
    uint64_t edge_by_edge; /* triangles on two planes or more not cut from the triangle (clip.h's head) */
} sr_clip_counts;

/* The error a cut vertex may carry, in NDC units, when no tolerance is
 * given: half a 1/256-pixel step on a 16384-pixel side. */
#define SR_CLIP_DEFAULT_TOLERANCE (1.0 / (256.0 * 16384.0))

/* One cut vertex as the clipper made it, for a trace hook. A cut of an
 * edge: inside and outside are the end points it was interpolated between.
 * A corner: the triangle's point on `plane` and on `first`, the earlier
 * plane whose cut line the polygon edge inside -> outside runs along
 * (`triangle`: the three vertices it is made from); its precision is its
 * position's, double or exact. */
typedef struct sr_clip_cut {
    sr_clip_plane plane;
    const sr_vertex_out *inside, *outside; /* the edge's end points */
    const sr_vertex_out *cut;              /* the cut vertex, placed on the plane */
    sr_clip_precision precision;           /* the precision it was made in */
    bool corner;                           /* true: on `first` too */
    sr_clip_plane first;
    const sr_vertex_out *triangle; /* a corner's triangle; NULL for an edge cut */
} sr_clip_cut;

typedef void sr_clip_trace(void *context, const sr_clip_cut *cut);

typedef struct sr_clip_config {
    sr_clip_precision precision;
    double ndc_tolerance;  /* adaptive: allowed error in NDC; 0: SR_CLIP_DEFAULT_TOLERANCE */
    sr_clip_counts *counts; /* optional: incremented per cut vertex */
    sr_clip_depth depth;    /* the projection's depth model (sr_clip_depth_of); zero: off */
    sr_clip_trace *trace;   /* optional: called with each cut vertex, in the order they are made */
    void *trace_context;    /* passed to trace */
} sr_clip_config;

/* The cut vertex of edge inside -> outside (d_in >= 0 > d_out) on a plane;
 * floats = 4 + number of varyings to interpolate. cfg may be NULL (adaptive,
 * default tolerance). Returns the precision it used. */
sr_clip_precision sr_clip_intersect(sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                                    int floats, const sr_clip_config *cfg, sr_vertex_out *cut);

/* Clips poly in place against the planes whose bits are set in `planes`;
 * given a triangle, it records the line each edge of the result runs
 * along (sr_polygon.line), whichever precision cut it. Returns the vertex
 * count (0: nothing left, or a degenerate sliver whose rounding made it
 * non-convex past the bound; never more than SR_MAX_CLIP_VERTS). */
int sr_clip_polygon(sr_polygon *poly, unsigned planes, int floats, const sr_clip_config *cfg);

#endif
