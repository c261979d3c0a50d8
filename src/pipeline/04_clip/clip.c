#include <float.h>
#include <math.h>
#include <stddef.h>

#include "clip_corner.h"
#include "clip_exact.h"
#include "expansion.h"
#include "clip.h"

/* The rounding error of a + t(b − a) with t = d_in / (d_in − d_out) is at
 * most this many units in the last place of |a| + |t|(|a| + |b|): one each
 * for the two distances, the subtraction (which never cancels: d_in >= 0 >
 * d_out), the division, b − a, the product and the sum, with room to spare. */
#define ROUNDING_BOUND 8.0
/* Below this scale float products go subnormal and lose the relative
 * precision the bound assumes: such edges go exact. */
#define TINY_SCALE 1e-30f

static void intersect_double(sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                             int floats, const sr_clip_depth *depth, sr_vertex_out *cut)
{
    double d_in = sr_clip_distance_with(plane, inside->v, depth);
    double d_out = sr_clip_distance_with(plane, outside->v, depth);
    double t = d_in / (d_in - d_out);
    for (int i = 0; i < floats; i++) {
        double a = inside->v[i], b = outside->v[i];
        cut->v[i] = (float)(a + t * (b - a));
    }
}

static void intersect_float(sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                            int floats, const sr_clip_depth *depth, sr_vertex_out *cut)
{
    float d_in = (float)sr_clip_distance_with(plane, inside->v, depth);
    float d_out = (float)sr_clip_distance_with(plane, outside->v, depth);
    float t = d_in / (d_in - d_out);
    for (int i = 0; i < floats; i++)
        cut->v[i] = inside->v[i] + t * (outside->v[i] - inside->v[i]);
}

/* The adaptive choice, from a float estimate: the error bound of a
 * precision is ROUNDING_BOUND · ε · M / w over the coordinates, M = |a| +
 * |t|(|a| + |b|), w the cut vertex's w (NDC error = clip error / w), taken
 * at its smallest. A cut that may be at w <= 0, or any overflow, goes exact. */
static sr_clip_precision choose_precision(sr_clip_plane plane, const sr_vertex_out *inside,
                                          const sr_vertex_out *outside, const sr_clip_depth *depth,
                                          double tolerance)
{
    float d_in = (float)sr_clip_distance_with(plane, inside->v, depth);
    float d_out = (float)sr_clip_distance_with(plane, outside->v, depth);
    float t = d_in / (d_in - d_out), m = 0.0f;
    bool overflowed = !isfinite(t); /* float ran out of range: the estimate says nothing */
    for (int i = 0; i < SR_VARYINGS_AT; i++) {
        float a = fabsf(inside->v[i]), b = fabsf(outside->v[i]);
        float bound = a + t * (a + b);
        overflowed = overflowed || !isfinite(bound) || !isfinite(a + b);
        m = bound > m ? bound : m;
    }
    /* The estimated w is itself a + t(b − a) in float: divide by the least w
     * its own error bound allows, so a w that cancelled cannot pass for a
     * large one and let float through. */
    float w = inside->v[SR_W] + t * (outside->v[SR_W] - inside->v[SR_W]);
    float w_low = w - (float)ROUNDING_BOUND * FLT_EPSILON * m;
    double relative = (double)m / (double)w_low;
    if (overflowed || !(w_low > 0.0f) || !isfinite(relative) || !isfinite(d_in - d_out) || m < TINY_SCALE)
        return SR_CLIP_EXACT;
    if (ROUNDING_BOUND * FLT_EPSILON * relative <= tolerance)
        return SR_CLIP_FLOAT;
    if (ROUNDING_BOUND * DBL_EPSILON * relative <= tolerance)
        return SR_CLIP_DOUBLE;
    return SR_CLIP_EXACT;
}

static double clip_tolerance(const sr_clip_config *cfg)
{
    return cfg && cfg->ndc_tolerance > 0.0 ? cfg->ndc_tolerance : SR_CLIP_DEFAULT_TOLERANCE;
}

/* The cut vertex, neither counted nor traced. */
static sr_clip_precision intersect(sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                                   int floats, const sr_clip_config *cfg, sr_vertex_out *cut)
{
    sr_clip_precision p = cfg ? cfg->precision : SR_CLIP_ADAPTIVE;
    const sr_clip_depth *depth = cfg ? &cfg->depth : NULL;
    if (p == SR_CLIP_ADAPTIVE)
        p = choose_precision(plane, inside, outside, depth, clip_tolerance(cfg));
    if (p == SR_CLIP_FLOAT)
        intersect_float(plane, inside, outside, floats, depth, cut);
    else if (p == SR_CLIP_DOUBLE)
        intersect_double(plane, inside, outside, floats, depth, cut);
    else
        sr_clip_intersect_exact(plane, inside, outside, floats, depth, cut);
    sr_clip_place_on_plane(plane, depth, cut->v);
    return p;
}

/* Counts the cut and hands it to the trace hook. */
static void report(const sr_clip_config *cfg, const sr_clip_cut *cut)
{
    if (cfg && cfg->counts)
        cfg->counts->cuts[cut->precision]++;
    if (cfg && cfg->trace)
        cfg->trace(cfg->trace_context, cut);
}

sr_clip_precision sr_clip_intersect(sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                                    int floats, const sr_clip_config *cfg, sr_vertex_out *cut)
{
    sr_clip_precision p = intersect(plane, inside, outside, floats, cfg, cut);
    report(cfg, &(sr_clip_cut){ .plane = plane, .inside = inside, .outside = outside, .cut = cut, .precision = p });
    return p;
}

/* The line of the output edge that leaves a cut vertex: where the input
 * edge leaves the plane (a_in), the plane's cut line; where it comes back
 * in, the rest of the input edge. */
static unsigned char line_after_cut(bool a_in, unsigned char edge_line, sr_clip_plane plane)
{
    return a_in ? (unsigned char)(SR_CLIP_ON_PLANE + plane) : edge_line;
}

/* Makes the cut of the polygon edge inside -> outside, which runs along
 * `line`; false where it cannot. */
typedef bool (*edge_cut)(void *ctx, int line, sr_clip_plane plane, const sr_vertex_out *inside,
                         const sr_vertex_out *outside, sr_vertex_out *cut);

#define PASS_OVERFLOW (-1) /* rounding made the polygon cross the plane more than twice */
#define PASS_NO_CUT (-2)   /* `cut` could not make a cut */

/* One Sutherland–Hodgman pass over the sides of the vertices (inside[i]),
 * carrying each edge's line (sr_polygon). Returns the output count, or
 * PASS_OVERFLOW when the output would pass the bound (only slivers thinner
 * than float precision do that), or PASS_NO_CUT. */
static int clip_pass(const sr_polygon *in, const bool *inside, sr_clip_plane plane, edge_cut cut, void *ctx,
                     sr_polygon *out)
{
    int n = in->count, m = 0;
    for (int i = 0; i < n; i++) {
        int j = i + 1 < n ? i + 1 : 0;
        const sr_vertex_out *a = &in->vert[i], *b = &in->vert[j];
        bool a_in = inside[i], b_in = inside[j];
        if (m + (a_in) + (a_in != b_in) > SR_MAX_CLIP_VERTS)
            return PASS_OVERFLOW;
        if (a_in) {
            out->line[m] = in->line[i];
            out->vert[m++] = *a;
        }
        if (a_in != b_in) {
            if (!cut(ctx, in->line[i], plane, a_in ? a : b, a_in ? b : a, &out->vert[m]))
                return PASS_NO_CUT;
            out->line[m++] = line_after_cut(a_in, in->line[i], plane);
        }
    }
    return m;
}

/* A pass's output, or nothing when it kept fewer than 3 vertices (or none:
 * a negative count), becomes the polygon. */
static void take_pass(sr_polygon *poly, const sr_polygon *out, int n)
{
    poly->count = n < 3 ? 0 : n;
    for (int i = 0; i < poly->count; i++) {
        poly->vert[i] = out->vert[i];
        poly->line[i] = out->line[i];
    }
}

typedef struct edge_by_edge {
    int floats;
    const sr_clip_config *cfg;
} edge_by_edge;

static bool cut_edge(void *ctx, int line, sr_clip_plane plane, const sr_vertex_out *inside,
                     const sr_vertex_out *outside, sr_vertex_out *cut)
{
    (void)line;
    const edge_by_edge *e = ctx;
    sr_clip_intersect(plane, inside, outside, e->floats, e->cfg, cut);
    return true;
}

/* Plain Sutherland–Hodgman: every polygon edge cut as it stands. */
static void clip_edge_by_edge(sr_polygon *poly, unsigned planes, int floats, const sr_clip_config *cfg)
{
    const sr_clip_depth *depth = cfg ? &cfg->depth : NULL;
    edge_by_edge ctx = { floats, cfg };
    sr_polygon scratch;
    for (int p = 0; p < SR_CLIP_PLANES && poly->count >= 3; p++) {
        if (!(planes & (1u << p)))
            continue;
        bool inside[SR_MAX_CLIP_VERTS];
        for (int i = 0; i < poly->count; i++)
            inside[i] = sr_clip_distance_with((sr_clip_plane)p, poly->vert[i].v, depth) >= 0.0;
        take_pass(poly, &scratch, clip_pass(poly, inside, (sr_clip_plane)p, cut_edge, &ctx, &scratch));
    }
}

/* ---- cutting from the triangle (adaptive and exact, two planes or more) ---- */

/* A cut kept until the whole triangle is clipped, so a triangle that falls
 * back to clipping edge by edge counts and traces only those cuts. */
typedef struct kept_cut {
    sr_clip_cut cut;
    sr_vertex_out inside, outside, vertex;
} kept_cut;

#define MAX_KEPT_CUTS (SR_CLIP_PLANES * SR_MAX_CLIP_VERTS)

typedef struct triangle_clip {
    const sr_vertex_out *tri; /* the triangle's three vertices */
    int floats;
    const sr_clip_config *cfg;
    bool failed; /* a cut could not be made from the triangle */
    int kept;
    kept_cut cuts[MAX_KEPT_CUTS];
} triangle_clip;

static void keep(triangle_clip *tc, const sr_clip_cut *made, const sr_vertex_out *vertex)
{
    kept_cut *k = &tc->cuts[tc->kept++];
    *k = (kept_cut){ .cut = *made, .inside = *made->inside, .outside = *made->outside, .vertex = *vertex };
}

/* The cut of the polygon edge inside -> outside, which runs along `line`:
 * on a triangle edge the whole edge's cut (its end points are the
 * triangle's vertices, so a shared edge cuts alike after any planes), on a
 * cut line the corner. False where there is none: the whole edge does not
 * cross the plane, or sr_clip_corner found no corner (with every side
 * decided exactly, neither happens on a triangle that is not degenerate). */
static bool cut_from_triangle(void *ctx, int line, sr_clip_plane plane, const sr_vertex_out *inside,
                              const sr_vertex_out *outside, sr_vertex_out *cut)
{
    triangle_clip *tc = ctx;
    const sr_clip_config *cfg = tc->cfg;
    const sr_clip_depth *depth = cfg ? &cfg->depth : NULL;
    sr_clip_cut made = { .plane = plane, .inside = inside, .outside = outside, .cut = cut };
    if (line >= SR_CLIP_ON_PLANE) {
        made.corner = true;
        made.first = (sr_clip_plane)(line - SR_CLIP_ON_PLANE);
        made.triangle = tc->tri;
        made.precision = sr_clip_corner(tc->tri, made.first, plane, tc->floats, cfg ? cfg->precision : SR_CLIP_ADAPTIVE,
                                        clip_tolerance(cfg), depth, cut);
        if (made.precision == SR_CLIP_ADAPTIVE)
            return false;
    } else {
        const sr_vertex_out *a = &tc->tri[line], *b = &tc->tri[(line + 1) % 3];
        bool a_in = sr_clip_distance_with(plane, a->v, depth) >= 0.0;
        if (a_in == (sr_clip_distance_with(plane, b->v, depth) >= 0.0))
            return false;
        made.inside = a_in ? a : b;
        made.outside = a_in ? b : a;
        made.precision = intersect(plane, made.inside, made.outside, tc->floats, cfg, cut);
    }
    /* A cut from the triangle may come from vertices far off, whose float z
     * (a·w + b rounded at their w) cannot carry b: under the depth model z
     * follows the cut's own w, on every plane (the edge-by-edge path
     * interpolates z on the side planes, so a cut's recorded z may differ
     * between the two paths; no pixel does: the viewport's z_ndc comes
     * from w). */
    if (depth && depth->on)
        sr_clip_z_from_w(depth, cut->v);
    keep(tc, &made, cut);
    return true;
}

/* Whether polygon vertex v, on lines `before` and `after`, is inside the
 * plane: a vertex of the triangle by its own distance, a cut vertex by the
 * exact point it was rounded from (so rounding never puts a vertex on the
 * wrong side and the polygon is the exact one); -1 when the lines do not
 * meet in one point. */
static int vertex_side(const triangle_clip *tc, int before, int after, sr_clip_plane plane, const sr_vertex_out *v)
{
    const sr_clip_depth *depth = tc->cfg ? &tc->cfg->depth : NULL;
    if (before < SR_CLIP_ON_PLANE && after < SR_CLIP_ON_PLANE && before != after)
        return sr_clip_distance_with(plane, v->v, depth) >= 0.0;
    return sr_clip_exact_side(tc->tri, before, after, plane, depth);
}

/* One pass (vertex i lies on lines line[i − 1] and line[i]); sets
 * tc->failed where a side or a cut cannot be decided from the triangle.
 * Returns clip_pass's count. */
static int pass_from_triangle(triangle_clip *tc, const sr_polygon *in, sr_clip_plane plane, sr_polygon *out)
{
    int n = in->count;
    bool inside[SR_MAX_CLIP_VERTS];
    for (int i = 0; i < n; i++) {
        int side = vertex_side(tc, in->line[i > 0 ? i - 1 : n - 1], in->line[i], plane, &in->vert[i]);
        if (side < 0) {
            tc->failed = true;
            return 0;
        }
        inside[i] = side;
    }
    int m = clip_pass(in, inside, plane, cut_from_triangle, tc, out);
    tc->failed = m == PASS_NO_CUT;
    return m;
}

/* Clips the triangle poly from its own vertices; false (poly untouched,
 * nothing counted) where a cut could not be made so. */
static bool clip_from_triangle(sr_polygon *poly, unsigned planes, int floats, const sr_clip_config *cfg)
{
    const sr_vertex_out tri[3] = { poly->vert[0], poly->vert[1], poly->vert[2] };
    triangle_clip tc; /* not zeroed: its cuts are written before they are read */
    tc.tri = tri;
    tc.floats = floats;
    tc.cfg = cfg;
    tc.failed = false;
    tc.kept = 0;
    sr_polygon clipped = *poly, scratch;
    for (int p = 0; p < SR_CLIP_PLANES && clipped.count >= 3; p++) {
        if (!(planes & (1u << p)))
            continue;
        int n = pass_from_triangle(&tc, &clipped, (sr_clip_plane)p, &scratch);
        if (tc.failed)
            return false;
        take_pass(&clipped, &scratch, n);
    }
    for (int i = 0; i < tc.kept; i++) {
        kept_cut *k = &tc.cuts[i];
        if (k->cut.corner) {
            k->cut.inside = &k->inside;
            k->cut.outside = &k->outside;
        }
        k->cut.cut = &k->vertex;
        report(cfg, &k->cut);
    }
    *poly = clipped;
    return true;
}

/* Adaptive and exact promise an error, and more than one plane may leave a
 * corner: those cut from the triangle. */
static bool cuts_from_triangle(const sr_polygon *poly, unsigned planes, const sr_clip_config *cfg)
{
    bool promised = !cfg || cfg->precision == SR_CLIP_ADAPTIVE || cfg->precision == SR_CLIP_EXACT;
    return promised && poly->count == 3 && (planes & (planes - 1u)) != 0;
}

int sr_clip_polygon(sr_polygon *poly, unsigned planes, int floats, const sr_clip_config *cfg)
{
    planes &= SR_OUT_PLANES;
    /* Wholly outside one of the planes: nothing is left, at every precision
     * (float cuts against the other planes could round a sliver back inside
     * it). The draw rejects these before clipping; a direct call may not. */
    unsigned outside_all = SR_OUT_PLANES;
    for (int i = 0; i < poly->count; i++)
        outside_all &= sr_clip_outcode_with(poly->vert[i].v, cfg ? &cfg->depth : NULL);
    if (outside_all & planes) {
        poly->count = 0;
        return 0;
    }
    if (poly->count == 3)
        for (int k = 0; k < 3; k++)
            poly->line[k] = (unsigned char)k;
    if (!cuts_from_triangle(poly, planes, cfg))
        clip_edge_by_edge(poly, planes, floats, cfg);
    else if (!clip_from_triangle(poly, planes, floats, cfg)) {
        if (cfg && cfg->counts)
            cfg->counts->edge_by_edge++;
        clip_edge_by_edge(poly, planes, floats, cfg);
    }
    if (poly->count < 3)
        poly->count = 0;
    /* Inside every plane, w <= 0 leaves only the clip-space origin (|x|, |y|,
     * z <= w and z >= 0): the triangle's plane then contains the eye and the
     * polygon has no area on screen, so dropping it loses no pixel, and the
     * divide never sees w <= 0. Rounding puts such a vertex there when an
     * edge runs through the eye and the near plane is tiny (1e-6). */
    for (int i = 0; i < poly->count; i++)
        if (!(poly->vert[i].v[SR_W] > 0.0f))
            poly->count = 0;
    return poly->count;
}
