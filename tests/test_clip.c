/* Stages 3 and 4: outcodes, clipping against one plane for every in/out
 * pattern of a triangle's vertices, the vertex bound, and one t for position
 * and varyings (DESIGN.md, "Clipping: the numerical contract"). The watertight
 * and all-plane tests are in test_clip_random.c, divide, viewport and fan in
 * test_clip_viewport.c. Random inputs use fixed seeds, so a failure
 * reproduces. */
#include <float.h>
#include <math.h>
#include <string.h>

#include <criterion/criterion.h>

#include "clip_helpers.h"

/* Relative tolerance for "inside a plane": a cut vertex is rounded to float
 * once per coordinate, so its distance to a plane it was not placed on is
 * off by a few ulps of |w| (2^-24 ≈ 6e-8); 1e-6·|w| leaves a wide margin. */
#define INSIDE_REL_TOL 1e-6

#define REPS_PER_PATTERN 64

/* ---- outcodes ---------------------------------------------------------- */

Test(outcode, sets_each_plane_bit_exactly_when_its_distance_is_negative)
{
    test_rng r = { 1 };
    for (int n = 0; n < 20000; n++) {
        float w = (float)rng_uniform(&r, -2, 2);
        float c[4] = { (float)rng_uniform(&r, -3, 3), (float)rng_uniform(&r, -3, 3), (float)rng_uniform(&r, -3, 3), w };
        /* Put one coordinate on a plane, or one ulp either side of it. */
        int axis = rng_below(&r, 3), side = rng_below(&r, 3);
        c[axis] = axis == SR_Z && side == 0 ? 0.0f : (rng_below(&r, 2) ? w : -w);
        if (side == 1)
            c[axis] = nextafterf(c[axis], INFINITY);
        else if (side == 2)
            c[axis] = nextafterf(c[axis], -INFINITY);
        double d[4] = { c[0], c[1], c[2], c[3] };
        unsigned code = sr_clip_outcode(c);
        for (int p = 0; p < SR_CLIP_PLANES; p++)
            cr_assert_eq((code >> p) & 1u, ref_distance(p, d) < 0.0, "plane %s, point (%a, %a, %a, %a), code %#x",
                         plane_name(p), c[0], c[1], c[2], c[3], code);
        cr_assert_eq(code & ~SR_OUT_PLANES, 0u, "finite point has extra bits %#x", code);
    }
}

Test(outcode, bit_of_each_plane_is_one_shifted_by_its_index)
{
    /* One point outside exactly one plane each, in sr_clip_plane order. */
    const float pts[SR_CLIP_PLANES][4] = {
        { 0, 0, -0.5f, 1 }, { 0, 0, 1.5f, 1 }, { -1.5f, 0, 0.5f, 1 },
        { 1.5f, 0, 0.5f, 1 }, { 0, -1.5f, 0.5f, 1 }, { 0, 1.5f, 0.5f, 1 },
    };
    for (int p = 0; p < SR_CLIP_PLANES; p++)
        cr_assert_eq(sr_clip_outcode(pts[p]), 1u << p, "plane %s", plane_name(p));
}

Test(outcode, points_exactly_on_planes_are_inside)
{
    const float ws[] = { 1.0f, 0.3f, 3.7f, 1e-20f, 1e20f, FLT_TRUE_MIN, FLT_MAX };
    for (size_t i = 0; i < sizeof ws / sizeof ws[0]; i++) {
        float w = ws[i];
        const float zs[2] = { 0.0f, w }, xs[3] = { -w, 0.0f, w };
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                for (int k = 0; k < 2; k++) {
                    float c[4] = { xs[a], xs[b], zs[k], w };
                    cr_assert_eq(sr_clip_outcode(c), 0u, "(%a, %a, %a, %a)", c[0], c[1], c[2], c[3]);
                }
    }
    cr_assert_eq(sr_clip_outcode((float[4]){ -0.0f, 0.0f, -0.0f, 0.0f }), 0u, "clip-space origin");
}

Test(outcode, nan_or_inf_in_any_coordinate_gives_nonfinite)
{
    const float bad[3] = { NAN, INFINITY, -INFINITY };
    const float bases[2][4] = { { 0.1f, 0.2f, 0.3f, 1.0f }, { 5.0f, -5.0f, -1.0f, 1.0f } };
    for (int b = 0; b < 2; b++)
        for (int k = 0; k < 4; k++)
            for (int j = 0; j < 3; j++) {
                float c[4];
                memcpy(c, bases[b], sizeof c);
                c[k] = bad[j];
                cr_assert(sr_clip_outcode(c) & SR_OUT_NONFINITE, "coordinate %d = %f", k, c[k]);
            }
}

/* The plane table against the convention (DESIGN.md), written out as
 * examples: 0 <= z <= w, -w <= x <= w, -w <= y <= w. */
Test(outcode, plane_table_is_the_convention)
{
    const float c[4] = { 0.25f, -0.5f, 0.125f, 2.0f };
    const double want[SR_CLIP_PLANES] = { 0.125, 1.875, 2.25, 1.75, 1.5, 2.5 };
    for (int p = 0; p < SR_CLIP_PLANES; p++)
        cr_assert_eq(sr_clip_distance((sr_clip_plane)p, c), want[p], "plane %s", plane_name(p));
}

/* ---- one plane, every in/out pattern ------------------------------------ */

/* w = 1, so clip space is affine. Sets the coordinate that `plane` reads so
 * that the distance to it is d (other coordinates stay inside the volume). */
static void set_plane_distance(int plane, sr_vertex_out *v, double d)
{
    const sr_clip_plane_row *row = &sr_clip_plane_table[plane];
    v->v[row->axis] = (float)(row->sign * (d - (row->bounded_by_w ? 1.0 : 0.0))); /* d = w + sign·c, w = 1 */
}

/* Bit i of `pattern` set: vertex i is outside `plane` (distance in
 * [-1, -0.05]); clear: inside (distance in [0.05, 1]). */
static void pattern_triangle(test_rng *r, int plane, int pattern, sr_vertex_out tri[3])
{
    for (int i = 0; i < 3; i++) {
        tri[i] = vert4(rng_uniform(r, -0.9, 0.9), rng_uniform(r, -0.9, 0.9), rng_uniform(r, 0.1, 0.9), 1.0);
        double d = rng_uniform(r, 0.05, 1.0);
        set_plane_distance(plane, &tri[i], (pattern >> i) & 1 ? -d : d);
    }
}

static int outside_count(int pattern)
{
    return (pattern & 1) + ((pattern >> 1) & 1) + ((pattern >> 2) & 1);
}

static int input_index(const sr_vertex_out *v, const sr_vertex_out tri[3])
{
    for (int i = 0; i < 3; i++)
        if (floats_identical(v->v, tri[i].v, SR_VARYINGS_AT))
            return i;
    return -1;
}

/* Calls check on REPS_PER_PATTERN random triangles of each of the
 * 8 patterns × 6 planes, after clipping each against its one plane. */
typedef void pattern_check(int plane, int pattern, const sr_vertex_out tri[3], const sr_polygon *poly);

static void for_each_pattern(uint64_t seed, pattern_check *check)
{
    test_rng r = { seed };
    for (int plane = 0; plane < SR_CLIP_PLANES; plane++)
        for (int pattern = 0; pattern < 8; pattern++)
            for (int rep = 0; rep < REPS_PER_PATTERN; rep++) {
                sr_vertex_out tri[3];
                pattern_triangle(&r, plane, pattern, tri);
                sr_polygon poly = poly3(tri[0], tri[1], tri[2]);
                int n = sr_clip_polygon(&poly, 1u << plane, SR_VARYINGS_AT, &(sr_clip_config){ .precision = SR_CLIP_DOUBLE });
                cr_assert_eq(n, poly.count, "return value %d, count %d", n, poly.count);
                check(plane, pattern, tri, &poly);
            }
}

static void count_matches_pattern(int plane, int pattern, const sr_vertex_out tri[3], const sr_polygon *poly)
{
    static const int expected[4] = { 3, 4, 3, 0 }; /* by number of outside vertices */
    (void)tri;
    cr_assert_eq(poly->count, expected[outside_count(pattern)], "plane %s pattern %d: %d vertices", plane_name(plane),
                 pattern, poly->count);
}

Test(clip, one_plane_vertex_count_matches_in_out_pattern)
{
    for_each_pattern(10, count_matches_pattern);
}

static void count_within_bound(int plane, int pattern, const sr_vertex_out tri[3], const sr_polygon *poly)
{
    (void)tri;
    cr_assert(poly->count >= 0 && poly->count <= SR_MAX_CLIP_VERTS, "plane %s pattern %d: %d vertices",
              plane_name(plane), pattern, poly->count);
}

Test(clip, one_plane_output_never_exceeds_vertex_bound)
{
    for_each_pattern(11, count_within_bound);
}

static void inside_the_plane(int plane, int pattern, const sr_vertex_out tri[3], const sr_polygon *poly)
{
    (void)tri;
    for (int i = 0; i < poly->count; i++) {
        const sr_vertex_out *v = &poly->vert[i];
        cr_assert_geq(ref_distance_f(plane, v), -INSIDE_REL_TOL * fabs(v->v[SR_W]), "plane %s pattern %d vertex %d",
                      plane_name(plane), pattern, i);
    }
}

Test(clip, one_plane_output_is_inside_that_plane)
{
    for_each_pattern(12, inside_the_plane);
}

static void cuts_on_the_plane(int plane, int pattern, const sr_vertex_out tri[3], const sr_polygon *poly)
{
    int cuts = 0;
    for (int i = 0; i < poly->count; i++) {
        if (input_index(&poly->vert[i], tri) >= 0)
            continue;
        cuts++;
        double d = ref_distance_f(plane, &poly->vert[i]);
        cr_assert_eq(d, 0.0, "plane %s pattern %d vertex %d: distance %a", plane_name(plane), pattern, i, d);
    }
    int out = outside_count(pattern);
    cr_assert_eq(cuts, out == 1 || out == 2 ? 2 : 0, "plane %s pattern %d: %d cut vertices", plane_name(plane),
                 pattern, cuts);
}

Test(clip, one_plane_cut_vertices_lie_exactly_on_the_plane)
{
    for_each_pattern(13, cuts_on_the_plane);
}

static void inside_vertices_kept_in_order(int plane, int pattern, const sr_vertex_out tri[3], const sr_polygon *poly)
{
    int seen[SR_MAX_CLIP_VERTS], n_seen = 0, want[3], n_want = 0;
    for (int i = 0; i < poly->count; i++) {
        int k = input_index(&poly->vert[i], tri);
        if (k >= 0)
            seen[n_seen++] = k;
    }
    for (int i = 0; i < 3; i++)
        if (!((pattern >> i) & 1))
            want[n_want++] = i;
    cr_assert_eq(n_seen, n_want, "plane %s pattern %d", plane_name(plane), pattern);
    bool rotation = n_want == 0;
    for (int s = 0; s < n_want && !rotation; s++) {
        rotation = true;
        for (int i = 0; i < n_want; i++)
            rotation = rotation && seen[i] == want[(i + s) % n_want];
    }
    cr_assert(rotation, "plane %s pattern %d: inside vertices reordered", plane_name(plane), pattern);
}

Test(clip, one_plane_keeps_inside_vertices_bit_identical_in_walk_order)
{
    for_each_pattern(14, inside_vertices_kept_in_order);
}

static void output_convex(int plane, int pattern, const sr_vertex_out tri[3], const sr_polygon *poly)
{
    cr_assert(convex_in_triangle_plane(poly, &tri[0], &tri[1], &tri[2]), "plane %s pattern %d", plane_name(plane),
              pattern);
}

Test(clip, one_plane_output_is_convex)
{
    for_each_pattern(15, output_convex);
}

static void area_matches_reference(int plane, int pattern, const sr_vertex_out tri[3], const sr_polygon *poly)
{
    sr_polygon in = poly3(tri[0], tri[1], tri[2]);
    ref_poly ref = ref_from_sr(&in), got = ref_from_sr(poly);
    ref_clip(&ref, 1u << plane);
    double a = ref_area3((const double(*)[4])got.v, got.n), b = ref_area3((const double(*)[4])ref.v, ref.n);
    /* Cut vertices are rounded to float (6e-8 relative, coordinates <= 2). */
    cr_assert(fabs(a - b) <= 1e-6, "plane %s pattern %d: area %.9g, reference %.9g", plane_name(plane), pattern, a, b);
}

Test(clip, one_plane_area_matches_reference_clipper)
{
    for_each_pattern(16, area_matches_reference);
}

Test(clip, vertices_exactly_on_the_plane_are_kept_unchanged)
{
    test_rng r = { 17 };
    for (int plane = 0; plane < SR_CLIP_PLANES; plane++)
        for (int on = 1; on < 8; on++) { /* bit i: vertex i on the plane, else inside */
            sr_vertex_out tri[3];
            pattern_triangle(&r, plane, 0, tri);
            for (int i = 0; i < 3; i++)
                if ((on >> i) & 1)
                    set_plane_distance(plane, &tri[i], 0.0);
            sr_polygon poly = poly3(tri[0], tri[1], tri[2]);
            cr_assert_eq(sr_clip_polygon(&poly, 1u << plane, SR_VARYINGS_AT, &(sr_clip_config){ .precision = SR_CLIP_DOUBLE }), 3, "plane %s on-mask %d",
                         plane_name(plane), on);
            for (int i = 0; i < 3; i++)
                cr_assert(floats_identical(poly.vert[i].v, tri[i].v, SR_VARYINGS_AT), "plane %s vertex %d moved",
                          plane_name(plane), i);
        }
}

Test(clip, planes_not_in_the_mask_are_ignored)
{
    /* Outside right and top, inside the others; only near is asked for. */
    sr_vertex_out tri[3] = { vert4(0, 0, 0.5, 1), vert4(3, 0, 0.5, 1), vert4(0, 3, 0.5, 1) };
    sr_polygon poly = poly3(tri[0], tri[1], tri[2]);
    cr_assert_eq(sr_clip_polygon(&poly, 1u << SR_PLANE_NEAR, SR_VARYINGS_AT, &(sr_clip_config){ .precision = SR_CLIP_DOUBLE }), 3);
    for (int i = 0; i < 3; i++)
        cr_assert(floats_identical(poly.vert[i].v, tri[i].v, SR_VARYINGS_AT), "vertex %d moved", i);
}

Test(clip, all_planes_reach_the_nine_vertex_bound_on_a_hexagonal_section)
{
    /* The plane u + v + s = 0 (u = x, v = y, s = 2z - 1, w = 1) cuts the clip
     * volume in a regular hexagon with corners at the permutations of
     * (1, -1, 0), listed below in order round it. An equilateral triangle in
     * that plane whose edges lie 1.3 from the centre, facing corners 0, 2
     * and 4 (at sqrt 2), cuts off those three corners: 6 + 3 = 9 vertices,
     * the bound, reached by a real triangle. */
    const double hex[6][3] = { { 1, -1, 0 }, { 1, 0, -1 }, { 0, 1, -1 }, { -1, 1, 0 }, { -1, 0, 1 }, { 0, -1, 1 } };
    sr_vertex_out tri[3];
    for (int i = 0; i < 3; i++) {
        const double *opp = hex[(2 * i + 3) % 6]; /* vertex i lies opposite corner 2i */
        double k = 2.6 / sqrt(2.0);
        tri[i] = vert4(k * opp[0], k * opp[1], (k * opp[2] + 1.0) / 2.0, 1.0);
    }
    sr_polygon poly = poly3(tri[0], tri[1], tri[2]);
    cr_assert_eq(sr_clip_polygon(&poly, SR_OUT_PLANES, SR_VARYINGS_AT, &(sr_clip_config){ .precision = SR_CLIP_DOUBLE }), SR_MAX_CLIP_VERTS);
    cr_assert_eq(SR_MAX_CLIP_VERTS, 9);
}

Test(clip, polygon_that_would_pass_the_vertex_bound_is_dropped)
{
    /* A non-convex zigzag of 9 vertices crossing x = w eight times would
     * leave 5 + 8 = 13 vertices: the clipper must refuse, not overflow. */
    sr_polygon poly;
    memset(&poly, 0, sizeof poly);
    poly.count = SR_MAX_CLIP_VERTS;
    for (int i = 0; i < SR_MAX_CLIP_VERTS; i++)
        poly.vert[i] = vert4(i % 2 ? 1.5 : 0.5, -0.9 + 0.2 * i, 0.5, 1.0);
    cr_assert_eq(sr_clip_polygon(&poly, 1u << SR_PLANE_RIGHT, SR_VARYINGS_AT, &(sr_clip_config){ .precision = SR_CLIP_DOUBLE }), 0);
    cr_assert_eq(poly.count, 0);
}

/* ---- interpolation: one t for position and varyings -------------------- */

Test(clip, intersect_interpolates_varyings_with_the_position_t)
{
    /* Varyings 0..3 are copies of x, y, z, w: before placement the cut's
     * copy must equal its coordinate bit for bit. Placement changes only the
     * plane's own coordinate, whose copy must then be within rounding of it. */
    test_rng r = { 20 };
    int floats = SR_VARYINGS_AT + 4, done = 0;
    while (done < 6000) {
        int plane = rng_below(&r, SR_CLIP_PLANES);
        sr_vertex_out in, out;
        for (int k = 0; k < 4; k++) {
            in.v[k] = (float)(rng_below(&r, 3) ? rng_uniform(&r, -3, 3) : rng_log_signed(&r, -4, 4));
            out.v[k] = (float)(rng_below(&r, 3) ? rng_uniform(&r, -3, 3) : rng_log_signed(&r, -4, 4));
            in.v[SR_VARYINGS_AT + k] = in.v[k];
            out.v[SR_VARYINGS_AT + k] = out.v[k];
        }
        if (!(ref_distance_f(plane, &in) >= 0 && ref_distance_f(plane, &out) < 0))
            continue;
        done++;
        sr_vertex_out cut;
        sr_clip_intersect((sr_clip_plane)plane, &in, &out, floats, &(sr_clip_config){ .precision = SR_CLIP_DOUBLE }, &cut);
        double scale = 0;
        for (int k = 0; k < 4; k++)
            scale = fmax(scale, fmax(fabs(in.v[k]), fabs(out.v[k])));
        for (int k = 0; k < 4; k++) {
            float copy = cut.v[SR_VARYINGS_AT + k];
            if (k != sr_clip_plane_table[plane].axis)
                cr_assert(floats_identical(&copy, &cut.v[k], 1), "plane %s coordinate %d: %a vs varying %a",
                          plane_name(plane), k, cut.v[k], copy);
            else
                cr_assert_leq(fabs((double)copy - cut.v[k]), 1e-6 * scale, "plane %s: placement moved %a to %a",
                              plane_name(plane), copy, cut.v[k]);
        }
    }
}

static void varyings_follow_position(int plane, int pattern, const sr_vertex_out tri[3], const sr_polygon *poly)
{
    (void)poly;
    sr_polygon p = poly3(tri[0], tri[1], tri[2]);
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 4; k++)
            p.vert[i].v[SR_VARYINGS_AT + k] = p.vert[i].v[k];
    sr_clip_polygon(&p, 1u << plane, SR_VARYINGS_AT + 4, &(sr_clip_config){ .precision = SR_CLIP_DOUBLE });
    for (int i = 0; i < p.count; i++)
        for (int k = 0; k < 4; k++)
            if (k != sr_clip_plane_table[plane].axis)
                cr_assert(floats_identical(&p.vert[i].v[k], &p.vert[i].v[SR_VARYINGS_AT + k], 1),
                          "plane %s pattern %d vertex %d coordinate %d", plane_name(plane), pattern, i, k);
}

Test(clip, polygon_clip_interpolates_varyings_with_the_position_t)
{
    for_each_pattern(21, varyings_follow_position);
}
