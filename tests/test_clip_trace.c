/* The clipper's trace hook, and sr_clip_polygon against an independent
 * Sutherland–Hodgman walk: the walk cuts each edge crossing a plane with
 * sr_clip_intersect, inside end first, in the fixed plane order, and must
 * give bit for bit what sr_clip_polygon gives, while the hook must report
 * exactly the walk's cuts, in order. (The stability study used to check
 * this at run time; it now measures through the hook.) */
#include <criterion/criterion.h>

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
} cut_record;

typedef struct cut_log {
    int n;
    cut_record cut[MAX_CUTS];
} cut_log;

static void record(cut_log *log, sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                   const sr_vertex_out *cut, sr_clip_precision precision)
{
    cr_assert_lt(log->n, MAX_CUTS);
    log->cut[log->n++] = (cut_record){ plane, *inside, *outside, *cut, precision };
}

static void trace_into_log(void *context, const sr_clip_cut *c)
{
    record(context, c->plane, c->inside, c->outside, c->cut, c->precision);
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
            }
        }
    }
    for (int p = SR_CLIP_ADAPTIVE + 1; p < SR_CLIP_PRECISIONS; p++)
        cr_assert_gt(cuts[p], 100u, "the adaptive clipper chose precision %d only %llu times: the test is too tame", p,
                     (unsigned long long)cuts[p]);
}
