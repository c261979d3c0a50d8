#include "clip_exact.h"
#include "clip_segment.h"

/* The segment as the triangle (a, b, a), whose edge 0 it is: the exact
 * side of a cut runs on a triangle's lines, and the third vertex's weight
 * on edge 0 is 0. */
static void segment_triangle(const sr_vertex_out ends[2], sr_vertex_out tri[3])
{
    tri[0] = ends[0];
    tri[1] = ends[1];
    tri[2] = ends[0];
}

/* Whether end k (a given end, or the cut on plane cut_plane[k] of the
 * whole segment) is inside `plane`: a given end by its distance, a cut by
 * the exact point it was rounded from, or with the fixed knobs by its
 * rounded self (-1: undecided, which no crossing segment gives). */
static int end_side(const sr_vertex_out tri[3], const sr_vertex_out *end, int cut_plane, bool exact,
                    sr_clip_plane plane, const sr_clip_depth *depth)
{
    if (cut_plane == SR_SEGMENT_END_GIVEN || !exact)
        return sr_clip_distance_with(plane, end->v, depth) >= 0.0;
    return sr_clip_exact_side(tri, 0, SR_CLIP_ON_PLANE + cut_plane, plane, depth);
}

bool sr_clip_segment(const sr_vertex_out ends[2], unsigned planes, int floats, const sr_clip_config *cfg,
                     sr_vertex_out out[2], int cut_plane[2])
{
    const sr_clip_depth *depth = cfg ? &cfg->depth : NULL;
    bool exact = !cfg || cfg->precision == SR_CLIP_ADAPTIVE || cfg->precision == SR_CLIP_EXACT;
    planes &= SR_OUT_PLANES;
    if (sr_clip_outcode_with(ends[0].v, depth) & sr_clip_outcode_with(ends[1].v, depth) & planes)
        return false;
    sr_vertex_out tri[3];
    segment_triangle(ends, tri);
    for (int k = 0; k < 2; k++) {
        out[k] = ends[k];
        cut_plane[k] = SR_SEGMENT_END_GIVEN;
    }
    for (int p = 0; p < SR_CLIP_PLANES; p++) {
        if (!(planes & (1u << p)))
            continue;
        sr_clip_plane plane = (sr_clip_plane)p;
        int in[2];
        for (int k = 0; k < 2; k++)
            in[k] = end_side(tri, &out[k], cut_plane[k], exact, plane, depth);
        if (in[0] < 0 || in[1] < 0 || (!in[0] && !in[1]))
            return false;
        if (in[0] && in[1])
            continue;
        int gone = in[0] ? 1 : 0;
        /* Exact sides: the whole segment crosses the plane as its
         * remaining piece does, and is cut as a triangle edge is. */
        const sr_vertex_out *inside = exact ? &ends[1 - gone] : &out[1 - gone];
        const sr_vertex_out *outside = exact ? &ends[gone] : &out[gone];
        sr_vertex_out cut;
        sr_clip_intersect(plane, inside, outside, floats, cfg, &cut);
        if (exact && depth && depth->on)
            sr_clip_z_from_w(depth, cut.v);
        out[gone] = cut;
        cut_plane[gone] = p;
    }
    return out[0].v[SR_W] > 0.0f && out[1].v[SR_W] > 0.0f;
}
