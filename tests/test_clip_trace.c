/* The clipper's trace hook, and sr_clip_polygon against an independent
 * Sutherland–Hodgman walk: the walk cuts each edge crossing a plane with
 * sr_clip_intersect, inside end first, in the fixed plane order, and must
 * give bit for bit what sr_clip_polygon gives where it clips edge by edge
 * (the float and double knobs, one plane, or a triangle the corner clipper
 * hands back), while the hook must report exactly the walk's cuts, in order.
 * Where it cuts from the triangle, every cut the hook reports must be the
 * whole triangle edge's cut or the triangle's corner, and every output
 * vertex a vertex of the triangle or a reported cut. (The stability study
 * used to check this at run time; it now measures through the hook.) */
#include <criterion/criterion.h>

#include "pipeline/04_clip/clip_corner.h"
#include "clip_helpers.h"

#define TRIANGLES 20000
#define MAX_CUTS (SR_CLIP_PLANES * SR_MAX_CLIP_VERTS)
#define FLOATS (SR_VARYINGS_AT + 1) /* position and one varying */
#define TOLERANCE 1e-3               /* NDC: loose enough that the adaptive clipper picks float too */

/* A cut as values, so the walk's and the hook's can be compared. */
typedef struct cut_record {
    sr_clip_plane plane;
    sr_vertex_out inside, outside, cut;
    sr_clip_precision precision;
    bool corner;
    sr_clip_plane first;
} cut_record;

typedef struct cut_log {
    int n;
    cut_record cut[MAX_CUTS];
} cut_log;

static void record(cut_log *log, sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                   const sr_vertex_out *cut, sr_clip_precision precision)
{
    cr_assert_lt(log->n, MAX_CUTS);
    log->cut[log->n++] = (cut_record){ plane, *inside, *outside, *cut, precision, false, plane };
}

static void trace_into_log(void *context, const sr_clip_cut *c)
{
    cut_log *log = context;
    record(log, c->plane, c->inside, c->outside, c->cut, c->precision);
    log->cut[log->n - 1].corner = c->corner;
    log->cut[log->n - 1].first = c->first;
    cr_assert_eq(c->triangle != NULL, c->corner, "a corner names its triangle, an edge cut none");
}

/* One plane; -1 where the output would pass SR_MAX_CLIP_VERTS. */
static int walk_plane(const sr_vertex_out *in, int n, sr_clip_plane plane, const sr_clip_config *cfg, cut_log *log,
                      sr_vertex_out *out)
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        const sr_vertex_out *a = &in[i], *b = &in[i + 1 < n ? i + 1 : 0];
        bool a_in = ref_distance_f(plane, a) >= 0.0, b_in = ref_distance_f(plane, b) >= 0.0;
        if (m + a_in + (a_in != b_in) > SR_MAX_CLIP_VERTS)
            return -1;
        if (a_in)
            out[m++] = *a;
        if (a_in != b_in) {
            const sr_vertex_out *inside = a_in ? a : b, *outside = a_in ? b : a;
            sr_clip_precision p = sr_clip_intersect(plane, inside, outside, FLOATS, cfg, &out[m]);
            record(log, plane, inside, outside, &out[m++], p);
        }
    }
    return m;
}

static void walk_polygon(sr_polygon *poly, unsigned planes, const sr_clip_config *cfg, cut_log *log)
{
    sr_vertex_out scratch[SR_MAX_CLIP_VERTS];
    /* A triangle wholly outside one plane is dropped before any cut. */
    for (int p = 0; p < SR_CLIP_PLANES; p++) {
        bool outside = planes & (1u << p);
        for (int i = 0; i < poly->count; i++)
            outside = outside && sr_clip_distance((sr_clip_plane)p, poly->vert[i].v) < 0.0;
        if (outside)
            poly->count = 0;
    }
    for (int p = 0; p < SR_CLIP_PLANES && poly->count >= 3; p++) {
        if (!(planes & (1u << p)))
            continue;
        int n = walk_plane(poly->vert, poly->count, (sr_clip_plane)p, cfg, log, scratch);
        poly->count = n < 3 ? 0 : n;
        memcpy(poly->vert, scratch, (size_t)poly->count * sizeof scratch[0]);
    }
    for (int i = 0; i < poly->count; i++) /* what reaches w <= 0 inside every plane is the eye: dropped */
        if (!(poly->vert[i].v[SR_W] > 0.0f))
            poly->count = 0;
}

static bool same_cut(const cut_record *a, const cut_record *b)
{
    return a->plane == b->plane && a->precision == b->precision && floats_identical(a->inside.v, b->inside.v, FLOATS) &&
           floats_identical(a->outside.v, b->outside.v, FLOATS) && floats_identical(a->cut.v, b->cut.v, FLOATS);
}

static bool is_vertex_of(const sr_vertex_out *v, const sr_polygon *tri)
{
    for (int k = 0; k < 3; k++)
        if (floats_identical(v->v, tri->vert[k].v, FLOATS))
            return true;
    return false;
}

/* A cut the hook reported under cutting from the triangle, made again: the
 * whole edge's cut (its end points the triangle's, inside first) or the
 * triangle's corner. */
static void check_cut_from_triangle(const cut_record *c, const sr_polygon *tri, const sr_clip_config *cfg, int n)
{
    sr_vertex_out again;
    if (c->corner) {
        sr_clip_precision p = sr_clip_corner(tri->vert, c->first, c->plane, FLOATS, cfg->precision, cfg->ndc_tolerance,
                                             &cfg->depth, &again);
        cr_assert_eq(p, c->precision, "triangle %d: corner made in precision %d, again in %d", n, c->precision, p);
    } else {
        cr_assert(is_vertex_of(&c->inside, tri) && is_vertex_of(&c->outside, tri),
                  "triangle %d: a cut from the triangle between vertices not its own", n);
        cr_assert(ref_distance_f(c->plane, &c->inside) >= 0.0 && ref_distance_f(c->plane, &c->outside) < 0.0);
        cr_assert_eq(sr_clip_intersect(c->plane, &c->inside, &c->outside, FLOATS, cfg, &again), c->precision);
    }
    cr_assert(floats_identical(again.v, c->cut.v, FLOATS), "triangle %d: a reported cut made again differs", n);
}

static void check_from_triangle(const sr_polygon *input, const sr_polygon *clipped, const cut_log *traced,
                                const sr_clip_config *cfg, int n)
{
    for (int k = 0; k < traced->n; k++)
        check_cut_from_triangle(&traced->cut[k], input, cfg, n);
    for (int i = 0; i < clipped->count; i++) {
        bool found = is_vertex_of(&clipped->vert[i], input);
        for (int k = 0; k < traced->n && !found; k++)
            found = floats_identical(clipped->vert[i].v, traced->cut[k].cut.v, FLOATS);
        cr_assert(found, "triangle %d: output vertex %d is neither the triangle's nor a reported cut", n, i);
    }
}

/* Vertices with magnitudes over 12 decades and either sign, so that every
 * plane is crossed and the adaptive clipper picks each precision. */
static sr_polygon random_triangle(test_rng *r)
{
    sr_vertex_out v[3];
    for (int i = 0; i < 3; i++) {
        v[i] = vert4(rng_log_signed(r, -6, 6), rng_log_signed(r, -6, 6), rng_log_signed(r, -6, 6),
                     rng_log_signed(r, -6, 6));
        v[i].v[SR_VARYINGS_AT] = (float)i;
    }
    return poly3(v[0], v[1], v[2]);
}

Test(clip_trace, polygon_equals_an_independent_walk_and_the_hook_reports_its_cuts)
{
    test_rng r = { 7 };
    uint64_t cuts[SR_CLIP_PRECISIONS] = { 0 };
    int from_triangle = 0;
    for (int n = 0; n < TRIANGLES; n++) {
        sr_polygon input = random_triangle(&r);
        unsigned planes = 0;
        for (int i = 0; i < 3; i++)
            planes |= sr_clip_outcode(input.vert[i].v);
        for (int precision = 0; precision < SR_CLIP_PRECISIONS; precision++) {
            static cut_log walked_cuts, traced_cuts;
            walked_cuts.n = traced_cuts.n = 0;
            sr_clip_counts counts = { { 0 } };
            sr_clip_config cfg = { .precision = (sr_clip_precision)precision, .ndc_tolerance = TOLERANCE };
            sr_clip_config traced = { .precision = (sr_clip_precision)precision,
                                      .ndc_tolerance = TOLERANCE,
                                      .counts = &counts,
                                      .trace = trace_into_log,
                                      .trace_context = &traced_cuts };
            sr_polygon walked = input, clipped = input;
            sr_clip_polygon(&clipped, planes, FLOATS, &traced);
            uint64_t counted = 0;
            for (int p = 0; p < SR_CLIP_PRECISIONS; p++)
                counted += counts.cuts[p];
            cr_assert_eq(counted, (uint64_t)traced_cuts.n, "triangle %d: every cut counted once", n);
            for (int k = 0; k < traced_cuts.n; k++)
                cuts[traced_cuts.cut[k].precision] += precision == SR_CLIP_ADAPTIVE;
            bool two_planes = (planes & SR_OUT_PLANES & ((planes & SR_OUT_PLANES) - 1u)) != 0;
            bool promised = precision == SR_CLIP_ADAPTIVE || precision == SR_CLIP_EXACT;
            if (promised && two_planes && counts.edge_by_edge == 0) {
                from_triangle++;
                check_from_triangle(&input, &clipped, &traced_cuts, &cfg, n);
                continue;
            }
            walk_polygon(&walked, planes, &cfg, &walked_cuts);
            cr_assert_eq(clipped.count, walked.count, "triangle %d precision %d", n, precision);
            for (int i = 0; i < walked.count; i++)
                cr_assert(floats_identical(clipped.vert[i].v, walked.vert[i].v, FLOATS),
                          "triangle %d precision %d vertex %d", n, precision, i);
            cr_assert_eq(traced_cuts.n, walked_cuts.n, "triangle %d precision %d", n, precision);
            for (int k = 0; k < walked_cuts.n; k++)
                cr_assert(same_cut(&traced_cuts.cut[k], &walked_cuts.cut[k]), "triangle %d precision %d cut %d", n,
                          precision, k);
        }
    }
    cr_assert_gt(from_triangle, 1000, "only %d triangles were cut from the triangle: the test is too tame", from_triangle);
    for (int p = SR_CLIP_ADAPTIVE + 1; p < SR_CLIP_PRECISIONS; p++)
        cr_assert_gt(cuts[p], 100u, "the adaptive clipper chose precision %d only %llu times: the test is too tame", p,
                     (unsigned long long)cuts[p]);
}
