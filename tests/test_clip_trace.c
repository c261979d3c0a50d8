/* The clipper's trace hook, and sr_clip_polygon against an independent
 * Sutherland–Hodgman walk: the walk keeps what each polygon edge runs along
 * (an edge of the triangle, or the cut line of an earlier plane) and cuts
 * each edge crossing a plane in the fixed plane order, inside end first;
 * adaptive and exact on an edge of the triangle with sr_clip_intersect of
 * that whole edge (of the polygon edge where rounding left only that
 * crossing the plane), on a cut line with sr_clip_corner; the fixed float
 * and double knobs each polygon edge as it stands. It must give bit for bit what
 * sr_clip_polygon gives, while the hook must report exactly the walk's
 * cuts, in order. (The stability study used to check this at run time; it
 * now measures through the hook.) */
#include <criterion/criterion.h>

#include "clip_helpers.h"

#define TRIANGLES 20000
#define MAX_CUTS (SR_CLIP_PLANES * SR_MAX_CLIP_VERTS)
#define FLOATS (SR_VARYINGS_AT + 1) /* position and one varying */
#define TOLERANCE 1e-3               /* NDC: loose enough that the adaptive clipper picks float too */
#define ON_CUT_LINE 3                /* lines from here on: the cut line of plane line − ON_CUT_LINE */

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

static void record(cut_log *log, const sr_clip_cut *c)
{
    cr_assert_lt(log->n, MAX_CUTS);
    log->cut[log->n++] = (cut_record){ c->plane, *c->inside, *c->outside, *c->cut, c->precision, c->corner,
                                       c->corner ? c->first : SR_PLANE_NEAR };
}

static void trace_into_log(void *context, const sr_clip_cut *c)
{
    record(context, c);
}

/* The cut of polygon edge inside -> outside, which runs along `line`;
 * forward: inside is the edge's start. */
static void walk_cut(const sr_vertex_out tri[3], int line, sr_clip_plane plane, const sr_vertex_out *inside,
                     const sr_vertex_out *outside, bool forward, const sr_clip_config *cfg, cut_log *log,
                     sr_vertex_out *cut)
{
    sr_clip_cut c = { .plane = plane, .cut = cut, .inside = inside, .outside = outside };
    if (line >= ON_CUT_LINE) {
        c.first = (sr_clip_plane)(line - ON_CUT_LINE);
        c.precision = sr_clip_corner(tri, c.first, plane, inside, outside, FLOATS, cfg, cut);
        c.corner = c.precision != SR_CLIP_ADAPTIVE;
    } else if (cfg->precision == SR_CLIP_ADAPTIVE || cfg->precision == SR_CLIP_EXACT) {
        const sr_vertex_out *start = &tri[line], *end = &tri[(line + 1) % 3];
        const sr_vertex_out *in = forward ? start : end, *out = forward ? end : start;
        if (ref_distance_f(plane, in) >= 0.0 && ref_distance_f(plane, out) < 0.0) {
            c.inside = in;
            c.outside = out;
        }
    }
    if (!c.corner)
        c.precision = sr_clip_intersect(plane, c.inside, c.outside, FLOATS, cfg, cut);
    record(log, &c);
}

/* One plane; -1 where the output would pass SR_MAX_CLIP_VERTS. */
static int walk_plane(const sr_vertex_out tri[3], const sr_vertex_out *in, const int *in_line, int n,
                      sr_clip_plane plane, const sr_clip_config *cfg, cut_log *log, sr_vertex_out *out, int *out_line)
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        const sr_vertex_out *a = &in[i], *b = &in[i + 1 < n ? i + 1 : 0];
        bool a_in = ref_distance_f(plane, a) >= 0.0, b_in = ref_distance_f(plane, b) >= 0.0;
        if (m + a_in + (a_in != b_in) > SR_MAX_CLIP_VERTS)
            return -1;
        if (a_in) {
            out_line[m] = in_line[i];
            out[m++] = *a;
        }
        if (a_in != b_in) {
            walk_cut(tri, in_line[i], plane, a_in ? a : b, a_in ? b : a, a_in, cfg, log, &out[m]);
            out_line[m++] = a_in ? ON_CUT_LINE + (int)plane : in_line[i];
        }
    }
    return m;
}

static void walk_polygon(sr_polygon *poly, unsigned planes, const sr_clip_config *cfg, cut_log *log)
{
    const sr_vertex_out tri[3] = { poly->vert[0], poly->vert[1], poly->vert[2] };
    sr_vertex_out scratch[SR_MAX_CLIP_VERTS];
    int line[SR_MAX_CLIP_VERTS] = { 0, 1, 2 }, scratch_line[SR_MAX_CLIP_VERTS];
    for (int p = 0; p < SR_CLIP_PLANES && poly->count >= 3; p++) {
        if (!(planes & (1u << p)))
            continue;
        int n = walk_plane(tri, poly->vert, line, poly->count, (sr_clip_plane)p, cfg, log, scratch, scratch_line);
        poly->count = n < 3 ? 0 : n;
        memcpy(poly->vert, scratch, (size_t)poly->count * sizeof scratch[0]);
        memcpy(line, scratch_line, (size_t)poly->count * sizeof scratch_line[0]);
    }
    for (int i = 0; i < poly->count; i++) /* what reaches w <= 0 inside every plane is the eye: dropped */
        if (!(poly->vert[i].v[SR_W] > 0.0f))
            poly->count = 0;
}

static bool same_cut(const cut_record *a, const cut_record *b)
{
    return a->plane == b->plane && a->precision == b->precision && a->corner == b->corner && a->first == b->first &&
           floats_identical(a->inside.v, b->inside.v, FLOATS) &&
           floats_identical(a->outside.v, b->outside.v, FLOATS) && floats_identical(a->cut.v, b->cut.v, FLOATS);
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
    uint64_t cuts[SR_CLIP_PRECISIONS] = { 0 }, corners = 0;
    for (int n = 0; n < TRIANGLES; n++) {
        sr_polygon input = random_triangle(&r);
        unsigned planes = 0;
        for (int i = 0; i < 3; i++)
            planes |= sr_clip_outcode(input.vert[i].v);
        for (int precision = 0; precision < SR_CLIP_PRECISIONS; precision++) {
            static cut_log walked_cuts, traced_cuts;
            walked_cuts.n = traced_cuts.n = 0;
            sr_clip_config cfg = { .precision = (sr_clip_precision)precision, .ndc_tolerance = TOLERANCE };
            sr_clip_config traced = { .precision = (sr_clip_precision)precision,
                                      .ndc_tolerance = TOLERANCE,
                                      .trace = trace_into_log,
                                      .trace_context = &traced_cuts };
            sr_polygon walked = input, clipped = input;
            walk_polygon(&walked, planes, &cfg, &walked_cuts);
            sr_clip_polygon(&clipped, planes, FLOATS, &traced);
            cr_assert_eq(clipped.count, walked.count, "triangle %d precision %d", n, precision);
            for (int i = 0; i < walked.count; i++)
                cr_assert(floats_identical(clipped.vert[i].v, walked.vert[i].v, FLOATS),
                          "triangle %d precision %d vertex %d", n, precision, i);
            cr_assert_eq(traced_cuts.n, walked_cuts.n, "triangle %d precision %d", n, precision);
            for (int k = 0; k < walked_cuts.n; k++) {
                cr_assert(same_cut(&traced_cuts.cut[k], &walked_cuts.cut[k]), "triangle %d precision %d cut %d", n,
                          precision, k);
                cuts[walked_cuts.cut[k].precision] += precision == SR_CLIP_ADAPTIVE;
                corners += walked_cuts.cut[k].corner;
            }
        }
    }
    for (int p = SR_CLIP_ADAPTIVE + 1; p < SR_CLIP_PRECISIONS; p++)
        cr_assert_gt(cuts[p], 100u, "the adaptive clipper chose precision %d only %llu times: the test is too tame", p,
                     (unsigned long long)cuts[p]);
    cr_assert_gt(corners, 1000u, "only %llu corners: the test is too tame", (unsigned long long)corners);
}
