/* The clipper's exact and adaptive intersections against GNU MP rationals:
 * the cut vertex of the same float end points, computed with no rounding at
 * all and rounded once at the end. */
#include <criterion/criterion.h>
#include <float.h>
#include <gmp.h>
#include <math.h>

#include "clip_helpers.h"
#include "exact_cut.h"
#include "softrast_private.h"

#define EDGES 4000

static test_rng rng = { 0x9E3779B97F4A7C15ull };

static double uniform(void)
{
    return rng_unit(&rng);
}

/* A float of random sign with magnitude 10^e, e uniform in [lo, hi]. */
static float magnitude(double lo, double hi)
{
    return (float)((uniform() < 0.5 ? -1.0 : 1.0) * pow(10.0, lo + (hi - lo) * uniform()));
}

/* The exact distance of a float clip-space point to a plane, as a rational. */
static void exact_float_distance(sr_clip_plane plane, const float *c, mpq_t d)
{
    static const sr_clip_depth none = { .on = false };
    mpq_t q[4];
    for (int i = 0; i < 4; i++) {
        mpq_init(q[i]);
        mpq_set_d(q[i], c[i]);
    }
    exact_distance(plane, q, &none, d);
    for (int i = 0; i < 4; i++)
        mpq_clear(q[i]);
}

/* Coordinate i of the exact cut point a + t(b − a), t = d_a / (d_a − d_b). */
static double exact_cut(sr_clip_plane plane, const sr_vertex_out *a, const sr_vertex_out *b, int i)
{
    mpq_t da, db;
    mpq_inits(da, db, NULL);
    exact_float_distance(plane, a->v, da);
    exact_float_distance(plane, b->v, db);
    double r = exact_cut_coordinate(da, db, a->v[i], b->v[i]);
    mpq_clears(da, db, NULL);
    return r;
}

/* An edge crossing the plane with end points of wildly different sizes:
 * inside end first. */
static void random_edge(sr_clip_plane plane, sr_vertex_out *in, sr_vertex_out *out)
{
    do {
        for (int i = 0; i < 4; i++) {
            in->v[i] = magnitude(-30, 30);
            out->v[i] = magnitude(-30, 30);
        }
        in->v[SR_W] = fabsf(in->v[SR_W]);
    } while (!(sr_clip_distance(plane, in->v) >= 0.0 && sr_clip_distance(plane, out->v) < 0.0));
}

/* The plane's own coordinate is placed on the plane afterwards; compare the
 * others. */
static bool placed_coordinate(sr_clip_plane plane, int i)
{
    return i == sr_clip_plane_table[plane].axis;
}

Test(clip_exact, exact_cut_is_the_rational_cut_rounded_to_float)
{
    for (int e = 0; e < EDGES; e++) {
        sr_clip_plane plane = (sr_clip_plane)(e % SR_CLIP_PLANES);
        sr_vertex_out in, out, cut;
        random_edge(plane, &in, &out);
        sr_clip_intersect(plane, &in, &out, 4, &(sr_clip_config){ .precision = SR_CLIP_EXACT }, &cut);
        for (int i = 0; i < 4; i++) {
            if (placed_coordinate(plane, i))
                continue;
            double ref = exact_cut(plane, &in, &out, i);
            float want = (float)ref;
            /* One rounding of a quotient accurate to ~1e-16: the nearest float,
             * or its neighbour when ref lies within that of a tie (the
             * midpoint of the two), never a neighbour otherwise. */
            bool ok = cut.v[i] == want;
            if (!ok && (cut.v[i] == nextafterf(want, INFINITY) || cut.v[i] == nextafterf(want, -INFINITY))) {
                double tie = ((double)want + (double)cut.v[i]) / 2;
                ok = fabs(ref - tie) <= 1e-15 * fabs(ref);
            }
            cr_assert(ok, "edge %d plane %d coord %d: got %a, exact %a", e, plane, i, cut.v[i], ref);
        }
    }
}

/* Where the cut is much smaller than the end points, a + t(b − a) in double
 * loses digits that the exact path keeps: on random edges spanning 60
 * decades, double misses the correctly rounded float by more than 16 units
 * in the last place somewhere, exact never does (test above). */
Test(clip_exact, double_loses_digits_that_exact_keeps)
{
    int worse = 0;
    for (int e = 0; e < EDGES; e++) {
        sr_clip_plane plane = (sr_clip_plane)(e % SR_CLIP_PLANES);
        sr_vertex_out in, out, cut;
        random_edge(plane, &in, &out);
        sr_clip_intersect(plane, &in, &out, 4, &(sr_clip_config){ .precision = SR_CLIP_DOUBLE }, &cut);
        for (int i = 0; i < 4; i++) {
            float want = (float)exact_cut(plane, &in, &out, i);
            float ulp = nextafterf(fabsf(want), INFINITY) - fabsf(want);
            worse += !placed_coordinate(plane, i) && fabsf(cut.v[i] - want) > 16.0f * ulp;
        }
    }
    cr_assert_gt(worse, 0, "no edge needed the exact path: the test edges are too tame");
}

/* Adaptive keeps every cut vertex within its tolerance in NDC (x/w, y/w,
 * z/w of the exact point), whichever precision it picks, and picks exact
 * only when the cheaper ones could not promise that. */
Test(clip_exact, adaptive_stays_within_tolerance_and_counts_its_choices)
{
    const double tolerance = 1.0 / (256.0 * 2048.0);
    sr_clip_counts counts = { { 0 } };
    sr_clip_config cfg = { .precision = SR_CLIP_ADAPTIVE, .ndc_tolerance = tolerance, .counts = &counts };
    int in_ndc = 0;
    for (int e = 0; e < EDGES; e++) {
        sr_clip_plane plane = (sr_clip_plane)(e % SR_CLIP_PLANES);
        sr_vertex_out in, out, cut;
        if (e % 2)
            random_edge(plane, &in, &out);
        else /* ordinary edges near the view, so float and double get chosen too */
            do {
                for (int i = 0; i < 4; i++) {
                    in.v[i] = (float)(4.0 * uniform() - 2.0);
                    out.v[i] = (float)(4.0 * uniform() - 2.0);
                }
                in.v[SR_W] = 1.0f + (float)uniform();
            } while (!(sr_clip_distance(plane, in.v) >= 0.0 && sr_clip_distance(plane, out.v) < 0.0));
        sr_clip_intersect(plane, &in, &out, 4, &cfg, &cut);
        double w = exact_cut(plane, &in, &out, SR_W);
        if (!(w > 1e-30))
            continue; /* a cut through the eye: no NDC to speak of */
        in_ndc++;
        for (int i = 0; i < 3; i++) {
            double err = fabs(cut.v[i] - exact_cut(plane, &in, &out, i)) / w;
            double scale = fabs(exact_cut(plane, &in, &out, i)) / w;
            /* The stored float itself rounds by FLT_EPSILON of the coordinate. */
            cr_assert(err <= tolerance + 2.0 * FLT_EPSILON * (1.0 + scale) ||
                          placed_coordinate(plane, i),
                      "edge %d coord %d: NDC error %g", e, i, err);
        }
    }
    cr_assert_gt(in_ndc, EDGES / 2, "only %d of %d cuts had an NDC position to check", in_ndc, EDGES);
    cr_assert_gt(counts.cuts[SR_CLIP_FLOAT], 0);
    cr_assert_gt(counts.cuts[SR_CLIP_EXACT], 0);
    cr_assert_eq(counts.cuts[SR_CLIP_FLOAT] + counts.cuts[SR_CLIP_DOUBLE] + counts.cuts[SR_CLIP_EXACT], EDGES);
}

/* The watertight rule on every path: the same edge reached from either of
 * its triangles gives the same bits, whatever precision the edge needs. */
Test(clip_exact, shared_edges_stay_bit_identical_on_every_path)
{
    int checked = 0;
    for (int e = 0; e < EDGES / 4; e++) {
        sr_clip_plane plane = (sr_clip_plane)(e % SR_CLIP_PLANES);
        sr_vertex_out in, out;
        random_edge(plane, &in, &out);
        for (int p = SR_CLIP_ADAPTIVE; p < SR_CLIP_PRECISIONS; p++) {
            const sr_vertex_out third_a = { .v = { 0, 0, 0.5f, 1 } }, third_b = { .v = { 0.1f, -0.1f, 0.5f, 1 } };
            sr_clip_config cfg = { .precision = (sr_clip_precision)p };
            bool standing;
            cr_assert(clip_same_cut_both_ways(plane, &in, &out, &third_a, &third_b, &cfg, &standing),
                      "edge %d, precision %d: the cut vertex differs between the two walks", e, p);
            checked += standing;
        }
    }
    cr_assert_gt(checked, EDGES / 4, "too few edges left both polygons standing");
}
