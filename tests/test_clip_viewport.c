/* Stages 5 and 6: the fan (v0, vi, vi+1) of a clipped polygon, and the
 * divide + viewport mapping: NDC to 1/256-pixel units with a top-left origin,
 * 1/w kept, varyings divided by w, and refusal of anything that would divide
 * by w <= 0 or produce inf or NaN (DESIGN.md, conventions and "Clipping: the
 * numerical contract"). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include <cglm/cglm.h>
#include <cglm/clipspace/persp_lh_zo.h>
#include <criterion/criterion.h>

#include "clip_helpers.h"

#define FB_W 640
#define FB_H 480
#define ONE SR_SUBPIXEL_ONE

/* ---- viewport mapping -------------------------------------------------- */

static sr_screen_vertex map_ok(double x, double y, double z, double w, int width, int height)
{
    sr_vertex_out v = vert4(x, y, z, w);
    sr_screen_vertex s;
    cr_assert(sr_viewport_map(&v, 0, &(sr_viewport){ width, height, SR_SUBPIXEL_BITS, 1.0f }, &s), "(%g, %g, %g, %g) refused", x, y, z, w);
    return s;
}

static bool map_refuses(float x, float y, float z, float w)
{
    sr_vertex_out v = vert4(0, 0, 0, 1);
    v.v[SR_X] = x;
    v.v[SR_Y] = y;
    v.v[SR_Z] = z;
    v.v[SR_W] = w;
    sr_screen_vertex s;
    return !sr_viewport_map(&v, 0, &(sr_viewport){ FB_W, FB_H, SR_SUBPIXEL_BITS, 1.0f }, &s);
}

Test(viewport, maps_top_left_ndc_corner_to_the_origin)
{
    const double ws[] = { 1.0, 3.0, 0.1, 1e-6, 1e6 };
    for (size_t i = 0; i < sizeof ws / sizeof ws[0]; i++) {
        sr_screen_vertex s = map_ok(-ws[i], ws[i], 0, ws[i], FB_W, FB_H);
        cr_assert(s.x == 0 && s.y == 0, "w = %g: (%lld, %lld)", ws[i], (long long)s.x, (long long)s.y);
    }
}

Test(viewport, maps_bottom_right_ndc_corner_to_the_full_size_in_subpixels)
{
    const double ws[] = { 1.0, 3.0, 0.1, 1e-6, 1e6 };
    for (size_t i = 0; i < sizeof ws / sizeof ws[0]; i++) {
        sr_screen_vertex s = map_ok(ws[i], -ws[i], ws[i], ws[i], FB_W, FB_H);
        cr_assert(s.x == (int64_t)FB_W * ONE && s.y == (int64_t)FB_H * ONE, "w = %g: (%lld, %lld)", ws[i],
                  (long long)s.x, (long long)s.y);
    }
}

Test(viewport, maps_pixel_centres_to_half_a_pixel_past_their_corner)
{
    /* Pixel (i, j) covers [i, i+1) × [j, j+1), row 0 at the top; its centre
     * (i + 0.5, j + 0.5) is at NDC x = 2(i + 0.5)/W - 1, y = 1 - 2(j + 0.5)/H. */
    const int sizes[][2] = { { 7, 5 }, { FB_W, FB_H }, { 1, 1 }, { 1920, 1080 } };
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        int W = sizes[k][0], H = sizes[k][1];
        for (int j = 0; j < H; j += 1 + H / 7)
            for (int i = 0; i < W; i += 1 + W / 9) {
                double w = 2.5, x = 2.0 * (i + 0.5) / W - 1.0, y = 1.0 - 2.0 * (j + 0.5) / H;
                sr_screen_vertex s = map_ok(x * w, y * w, 0.5 * w, w, W, H);
                cr_assert(s.x == (int64_t)i * ONE + ONE / 2 && s.y == (int64_t)j * ONE + ONE / 2,
                          "%dx%d pixel (%d, %d) -> (%lld, %lld)", W, H, i, j, (long long)s.x, (long long)s.y);
            }
    }
}

Test(viewport, keeps_z_ndc_and_inverse_w)
{
    sr_screen_vertex s = map_ok(0.5, -0.25, 0.75, 2.0, FB_W, FB_H);
    cr_assert_eq(s.z, 0.375f);
    cr_assert_eq(s.inv_w, 0.5f);
}

Test(viewport, divides_varyings_by_w)
{
    sr_vertex_out v = vert4(0.5, -0.25, 0.75, 4.0);
    for (int i = 0; i < SR_MAX_VARYINGS; i++)
        v.v[SR_VARYINGS_AT + i] = (float)(i - 3);
    sr_screen_vertex s;
    cr_assert(sr_viewport_map(&v, SR_MAX_VARYINGS, &(sr_viewport){ FB_W, FB_H, SR_SUBPIXEL_BITS, 1.0f }, &s));
    for (int i = 0; i < SR_MAX_VARYINGS; i++)
        cr_assert_eq(s.var_w[i], (float)(i - 3) / 4.0f, "varying %d", i);
}

Test(viewport, refuses_w_zero_or_negative)
{
    const float ws[] = { 0.0f, -0.0f, -FLT_TRUE_MIN, -1e-30f, -1.0f, -INFINITY };
    for (size_t i = 0; i < sizeof ws / sizeof ws[0]; i++)
        cr_assert(map_refuses(0, 0, 0, ws[i]), "w = %a accepted", ws[i]);
    cr_assert(map_refuses(-1, 1, 0, -1), "(-1, 1, 0, -1): x/w, y/w, z/w look inside, but w < 0");
}

Test(viewport, refuses_nan_or_inf_in_any_position_coordinate)
{
    const float bad[3] = { NAN, INFINITY, -INFINITY };
    for (int k = 0; k < 4; k++)
        for (int j = 0; j < 3; j++) {
            float c[4] = { 0.25f, 0.25f, 0.5f, 1.0f };
            c[k] = bad[j];
            cr_assert(map_refuses(c[0], c[1], c[2], c[3]), "coordinate %d = %f accepted", k, c[k]);
        }
}

Test(viewport, refuses_points_past_the_ndc_slack)
{
    double past = 1.0 + 2 * SR_NDC_SLACK;
    cr_assert(map_refuses((float)past, 0, 0.5f, 1), "x past right");
    cr_assert(map_refuses((float)-past, 0, 0.5f, 1), "x past left");
    cr_assert(map_refuses(0, (float)past, 0.5f, 1), "y past top");
    cr_assert(map_refuses(0, (float)-past, 0.5f, 1), "y past bottom");
    cr_assert(map_refuses(0, 0, (float)past, 1), "z past far");
    cr_assert(map_refuses(0, 0, (float)(-2 * SR_NDC_SLACK), 1), "z before near");
}

Test(viewport, accepts_points_a_rounding_hair_outside)
{
    float hair = (float)(1.0 + SR_NDC_SLACK / 2);
    cr_assert_not(map_refuses(hair, -hair, hair, 1));
    cr_assert_not(map_refuses(-hair, hair, (float)(-SR_NDC_SLACK / 2), 1));
}

Test(viewport, never_returns_an_infinite_inverse_w_or_varying)
{
    /* Inside the volume (|x|, |y|, z <= w) with w so small that 1/w, or a
     * varying divided by w, overflows float: refuse, or return finite values;
     * where 1/w fits a float (1e-30, 1e-38), map it, so the test cannot
     * pass by refusing everything. */
    const float ws[] = { 1e-30f, 1e-38f, 1e-39f, 1e-44f, FLT_TRUE_MIN };
    for (size_t i = 0; i < sizeof ws / sizeof ws[0]; i++) {
        sr_vertex_out v = vert4(0, 0, 0, 1);
        v.v[SR_W] = ws[i];
        v.v[SR_VARYINGS_AT] = 1.0f;
        sr_screen_vertex s;
        bool fits = 1.0 / (double)ws[i] <= FLT_MAX;
        bool mapped = sr_viewport_map(&v, 1, &(sr_viewport){ FB_W, FB_H, SR_SUBPIXEL_BITS, 1.0f }, &s);
        cr_assert(mapped || !fits, "w = %a refused, though 1/w = %g fits a float", ws[i], 1.0 / (double)ws[i]);
        if (mapped)
            cr_assert(isfinite(s.inv_w) && isfinite(s.var_w[0]), "w = %a: 1/w = %a, varying/w = %a", ws[i],
                      s.inv_w, s.var_w[0]);
    }
}

/* ---- the mapping against DESIGN.md's formula ------------------------- */

/* What DESIGN.md's conventions give for a clip position c (x, y, z, w):
 * NDC = c / w (z_ndc = a + b/w under a depth model), px = (g·x_ndc + 1)·W/2,
 * py = (1 − g·y_ndc)·H/2 (g the guard band's scale, 1 without one), in
 * units of 2^-bits pixel; 1/w and each varying / w. In long double, from
 * the formula alone. */
typedef struct rule_point {
    long double sx, sy, z, inv_w;
} rule_point;

static rule_point rule_map(const double c[4], const sr_viewport *vp)
{
    long double w = c[SR_W], x = c[SR_X] / w, y = c[SR_Y] / w, units = ldexpl(1.0L, vp->subpixel_bits);
    long double z = vp->depth.on ? (long double)vp->depth.a + (long double)vp->depth.b / w : c[SR_Z] / w;
    return (rule_point){ .sx = ((long double)vp->guard * x + 1.0L) * vp->width / 2.0L * units,
                         .sy = (1.0L - (long double)vp->guard * y) * vp->height / 2.0L * units, .z = z,
                         .inv_w = 1.0L / w };
}

/* Whether v lies this close to the edge of what the mapping accepts (the
 * NDC slack, float's range for 1/w and the varyings / w) that the double
 * arithmetic of the stage and the long double of the rule may decide it
 * apart. */
#define CLOSE_CALL 1e-9L

static bool close_to_a_limit(long double value, long double limit)
{
    return fabsl(fabsl(value) - limit) <= CLOSE_CALL * limit;
}

/* The rule's verdict: refused iff w <= 0 or not finite, NDC past the
 * slack, or 1/w or a varying / w past float's range; -1 for a close call. */
static int rule_accepts(const sr_vertex_out *v, int varyings, const sr_viewport *vp)
{
    double c[4] = { v->v[SR_X], v->v[SR_Y], v->v[SR_Z], v->v[SR_W] };
    if (!(c[SR_W] > 0.0) || !isfinite(c[SR_W]))
        return 0;
    rule_point r = rule_map(c, vp);
    long double x = c[SR_X] / (long double)c[SR_W], y = c[SR_Y] / (long double)c[SR_W];
    long double ndc[3] = { x, y, r.z }, lo[3] = { -1.0L, -1.0L, 0.0L };
    bool close = close_to_a_limit(r.inv_w, FLT_MAX);
    bool inside = fabsl(r.inv_w) < FLT_MAX;
    for (int k = 0; k < 3; k++) {
        close = close || fabsl(ndc[k] - (lo[k] - SR_NDC_SLACK)) <= CLOSE_CALL ||
                fabsl(ndc[k] - (1.0L + SR_NDC_SLACK)) <= CLOSE_CALL;
        inside = inside && ndc[k] >= lo[k] - SR_NDC_SLACK && ndc[k] <= 1.0L + SR_NDC_SLACK;
    }
    for (int i = 0; i < varyings; i++) {
        long double q = v->v[SR_VARYINGS_AT + i] * r.inv_w;
        close = close || close_to_a_limit(q, FLT_MAX);
        inside = inside && fabsl(q) < FLT_MAX;
    }
    return close ? -1 : inside;
}

/* |got − want| within `ulps` float roundings of want, or of `scale` (the
 * size of the terms a result cancelled from), and a subnormal's step. */
static bool near_float(long double got, long double want, long double scale, double ulps)
{
    return fabsl(got - want) <= ulps * 0x1p-24L * (fabsl(want) + scale) + FLT_TRUE_MIN;
}

/* A mapped vertex against the rule: the snapped point the nearest integer
 * to the float position's unsnapped one, the offset (with clip_d, to
 * clip_d's point), z, 1/w and varyings / w within a rounding or two. */
static void assert_mapped_by_the_rule(int k, const sr_vertex_out *v, const double *clip_d, int varyings,
                                      const sr_viewport *vp, const sr_screen_vertex *got)
{
    double c[4] = { v->v[SR_X], v->v[SR_Y], v->v[SR_Z], v->v[SR_W] };
    rule_point snap = rule_map(c, vp), fine = clip_d ? rule_map(clip_d, vp) : snap;
    /* The stage's sx in double is within a few ulps of the rule's, up to
     * 2^30 units: a tie may round either way. */
    long double slop = 0.5L + 0x1p-48L * (fabsl(snap.sx) + fabsl(snap.sy) + 1.0L);
    cr_assert(fabsl((long double)got->x - snap.sx) <= slop && fabsl((long double)got->y - snap.sy) <= slop,
              "case %d: snapped to (%lld, %lld), the rule's point is (%.6Lf, %.6Lf)", k, (long long)got->x,
              (long long)got->y, snap.sx, snap.sy);
    long double unsnapped = 0x1p-48L * (fabsl(fine.sx) + fabsl(fine.sy) + 1.0L);
    cr_assert(near_float((long double)got->x + got->x_off, fine.sx, unsnapped, 1.0) &&
                  near_float((long double)got->y + got->y_off, fine.sy, unsnapped, 1.0),
              "case %d: unsnapped (%lld%+a, %lld%+a), the rule's (%.9Lf, %.9Lf)", k, (long long)got->x, got->x_off,
              (long long)got->y, got->y_off, fine.sx, fine.sy);
    long double terms = vp->depth.on ? fabsl((long double)vp->depth.a) * 0x1p-26L : 0.0L;
    cr_assert(near_float(got->z, fine.z, terms, 1.0), "case %d: z %a, the rule's %.12Lg", k, got->z, fine.z);
    cr_assert(near_float(got->inv_w, snap.inv_w, 0.0L, 1.0), "case %d: 1/w %a, the rule's %.12Lg", k, got->inv_w,
              snap.inv_w);
    for (int i = 0; i < varyings; i++) {
        long double want = v->v[SR_VARYINGS_AT + i] * snap.inv_w;
        cr_assert(near_float(got->var_w[i], want, 0.0L, 1.0), "case %d: varying %d / w %a, the rule's %.12Lg", k, i,
                  got->var_w[i], want);
    }
}

/* A random viewport the draw accepts: snapped coordinates below
 * 2^SR_FIXED_POINT_BITS, and a perspective depth model or none. */
static sr_viewport random_viewport(test_rng *r)
{
    sr_viewport vp = { .width = 1 + rng_below(r, 4096), .height = 1 + rng_below(r, 4096),
                       .guard = rng_below(r, 2) ? 1.0f : (float)rng_uniform(r, 1.0, 8.0) };
    int side = vp.width > vp.height ? vp.width : vp.height;
    do
        vp.subpixel_bits = SR_MIN_SUBPIXEL_BITS + rng_below(r, SR_MAX_SUBPIXEL_BITS - SR_MIN_SUBPIXEL_BITS + 1);
    while (ceil(vp.guard) * side * (double)((int64_t)1 << vp.subpixel_bits) > (double)((int64_t)1 << 30));
    if (rng_below(r, 2)) {
        float near = (float)pow(10.0, rng_uniform(r, -6, 1)), far = near * (float)pow(10.0, rng_uniform(r, 1, 9));
        vp.depth = (sr_clip_depth){ .on = true, .a = far / (far - near), .b = -far * near / (far - near) };
    }
    return vp;
}

/* Return value and every field against the rule, on vertices whose w
 * spans 1e-30 … 1e30, at and a hair past the slack, with varyings up to
 * 1e38; close calls at the limits are left out (and counted). */
Test(viewport, maps_every_vertex_as_the_design_formula_says)
{
    test_rng r = { 1414 };
    int mapped = 0, refused = 0, close = 0;
    for (int k = 0; k < 200000; k++) {
        sr_viewport vp = random_viewport(&r);
        double w = pow(10.0, rng_uniform(&r, -30, 30)) * (rng_below(&r, 50) ? 1.0 : -1.0);
        double reach = rng_below(&r, 4) ? 1.0 : 1.0 + 2.0 * SR_NDC_SLACK;
        double ndc_z = vp.depth.on ? rng_uniform(&r, -0.01, 1.01) : rng_uniform(&r, -reach, reach);
        sr_vertex_out v = vert4(rng_uniform(&r, -reach, reach) * w, rng_uniform(&r, -reach, reach) * w, ndc_z * w, w);
        int varyings = rng_below(&r, SR_MAX_VARYINGS + 1);
        for (int i = 0; i < varyings; i++)
            v.v[SR_VARYINGS_AT + i] = (float)(rng_uniform(&r, -1, 1) * pow(10.0, rng_uniform(&r, -30, 38)));
        double clip_d[4];
        for (int i = 0; i < 4; i++)
            clip_d[i] = v.v[i] * (1.0 + rng_uniform(&r, -1e-7, 1e-7));
        int want = rule_accepts(&v, varyings, &vp);
        if (want < 0) {
            close++;
            continue;
        }
        for (int given = 0; given < 2; given++) {
            sr_screen_vertex got;
            memset(&got, 0, sizeof got);
            bool ok = given ? sr_viewport_map_d(&v, clip_d, varyings, &vp, &got) : sr_viewport_map(&v, varyings, &vp, &got);
            cr_assert_eq(ok, want, "case %d (%a, %a, %a, %a): mapped %d, the rule says %d", k, v.v[SR_X], v.v[SR_Y],
                         v.v[SR_Z], v.v[SR_W], ok, want);
            if (ok)
                assert_mapped_by_the_rule(k, &v, given ? clip_d : NULL, varyings, &vp, &got);
            mapped += ok;
            refused += !ok;
        }
    }
    cr_assert_gt(mapped, 100000);
    cr_assert_gt(refused, 10000);
    cr_assert_lt(close, 100, "%d close calls left out", close);
}

/* The double half of a block of mesh vertices (sr_viewport_map_double_block:
 * two SSE2 or four AVX2 lanes at a time, the last few one by one) writes
 * each vertex's x_off, y_off and z with the bits sr_viewport_map_d gives
 * it from the clip position in double of sr_vertex_mesh_clip_d, whatever
 * the vertices' order and count, the matrix's scale and the depth model. */
Test(viewport, the_double_half_in_lanes_maps_as_one_vertex_does)
{
    enum { VERTICES = 61 };
    test_rng r = { 2727 };
    float positions[VERTICES][3];
    sr_mesh mesh = { .positions = positions, .vertex_count = VERTICES };
    sr_varying_layout none = { .color = -1, .uv = -1, .normal = -1 };
    bool avx2 = sr_raster_simd_resolve(SR_SIMD_AVX2) == SR_SIMD_AVX2;
    int compared = 0;
    for (int round = 0; round < 2000; round++) {
        sr_viewport vp = random_viewport(&r);
        /* Clip x, y and z of a few tenths of w, w near 1, all scaled by
         * one power of ten: most vertices map, a few pass the slack. */
        sr_dmat4 world = sr_dmat4_identity(), same = sr_dmat4_identity();
        double scale = pow(10.0, rng_uniform(&r, -20, 20));
        for (int c = 0; c < 4; c++)
            for (int row = 0; row < 4; row++)
                world.m[c][row] = scale * (row == 3 ? (c == 3 ? 1.0 : 0.1) * rng_uniform(&r, 0.5, 1.0)
                                                    : rng_uniform(&r, -0.4, 0.4));
        static const double no_origin[3];
        sr_vertex_transform xf;
        sr_vertex_make_transform_d(&world, &same, &same, no_origin, &xf);
        for (int i = 0; i < VERTICES; i++)
            for (int k = 0; k < 3; k++)
                positions[i][k] = (float)rng_uniform(&r, -1.0, 1.0);
        sr_screen_vertex want[VERTICES], got[VERTICES];
        uint32_t index[VERTICES];
        uint32_t n = 0;
        for (uint32_t i = 0; i < VERTICES; i++) {
            _Alignas(16) sr_vertex_out v;
            double clip_d[4];
            sr_vertex_run(&mesh, &xf, &none, i, 1, &v);
            sr_vertex_mesh_clip_d(&mesh, i, &xf, clip_d);
            memset(&got[i], 0x5a, sizeof got[i]);
            if (!sr_viewport_map_d(&v, clip_d, 0, &vp, &want[i]))
                continue;
            got[i].x = want[i].x;
            got[i].y = want[i].y;
            index[n++] = i;
        }
        for (uint32_t k = n; k > 1; k--) { /* in no order, as a batch's vertices come */
            uint32_t j = (uint32_t)rng_below(&r, (int)k), t = index[k - 1];
            index[k - 1] = index[j], index[j] = t;
        }
        n -= (uint32_t)rng_below(&r, n < 4 ? (int)n + 1 : 4); /* every count modulo the lanes */
        for (int lanes = 0; lanes < 1 + avx2; lanes++) {
            sr_viewport_map_double_block(&mesh, &xf, index, n, &vp, lanes == 1, got, sizeof got[0]);
            for (uint32_t k = 0; k < n; k++) {
                uint32_t i = index[k];
                cr_assert(memcmp(&got[i].x_off, &want[i].x_off, sizeof want[i].x_off) == 0 &&
                              memcmp(&got[i].y_off, &want[i].y_off, sizeof want[i].y_off) == 0 &&
                              memcmp(&got[i].z, &want[i].z, sizeof want[i].z) == 0,
                          "round %d, vertex %u, %s: (%a, %a, %a), one at a time (%a, %a, %a)", round, i,
                          lanes ? "avx2" : "sse2", got[i].x_off, got[i].y_off, got[i].z, want[i].x_off,
                          want[i].y_off, want[i].z);
                compared++;
            }
        }
    }
    cr_assert_gt(compared, 50000);
}

/* ---- fan: (v0, vi, vi+1) after mapping ---------------------------------- */

#define FAN_TRIANGLES 4000

/* Twice the signed area in subpixel units², > 0 clockwise on screen (y down). */
static int64_t area2(const sr_screen_vertex *a, const sr_screen_vertex *b, const sr_screen_vertex *c)
{
    return (b->x - a->x) * (c->y - a->y) - (b->y - a->y) * (c->x - a->x);
}

/* Twice the area of the fan (s[0], s[i], s[i+1]) over an n-gon, summed. */
static int64_t fan_area2(const sr_screen_vertex s[], int n)
{
    int64_t sum = 0;
    for (int i = 1; i + 1 < n; i++)
        sum += area2(&s[0], &s[i], &s[i + 1]);
    return sum;
}

/* A perspective (near 0.1, far 100) view-space triangle, clipped as the
 * pipeline does and mapped. depth_inside keeps all three vertices between
 * near and far, so only the viewport sides clip. False if nothing is left. */
static bool clipped_screen_polygon(test_rng *r, bool depth_inside, sr_vertex_out tri[3], sr_screen_vertex s[],
                                   int *n)
{
    mat4 P;
    glm_perspective_lh_zo(glm_rad(60.0f), (float)FB_W / FB_H, 0.1f, 100.0f, P);
    for (int i = 0; i < 3; i++) {
        double z = depth_inside ? rng_uniform(r, 0.2, 90) : rng_uniform(r, -20, 40);
        vec4 view = { (float)(fabs(z) * rng_uniform(r, -2, 2)), (float)(fabs(z) * rng_uniform(r, -2, 2)), (float)z, 1 },
             clip;
        glm_mat4_mulv(P, view, clip);
        tri[i] = vert4(clip[0], clip[1], clip[2], clip[3]);
    }
    unsigned c[3] = { sr_clip_outcode(tri[0].v), sr_clip_outcode(tri[1].v), sr_clip_outcode(tri[2].v) };
    if (c[0] & c[1] & c[2])
        return false;
    sr_polygon poly = poly3(tri[0], tri[1], tri[2]);
    *n = sr_clip_polygon(&poly, c[0] | c[1] | c[2], SR_VARYINGS_AT, &(sr_clip_config){ .precision = SR_CLIP_DOUBLE });
    for (int i = 0; i < *n; i++)
        cr_assert(sr_viewport_map(&poly.vert[i], 0, &(sr_viewport){ FB_W, FB_H, SR_SUBPIXEL_BITS, 1.0f }, &s[i]), "vertex %d refused", i);
    return *n >= 3;
}

Test(fan, triangles_of_a_clipped_polygon_all_have_the_same_sign)
{
    test_rng r = { 60 };
    int mixed_w = 0;
    for (int k = 0; k < FAN_TRIANGLES; k++) {
        sr_vertex_out tri[3];
        sr_screen_vertex s[SR_MAX_CLIP_VERTS];
        int n;
        if (!clipped_screen_polygon(&r, false, tri, s, &n))
            continue;
        mixed_w += tri[0].v[SR_W] < 0 || tri[1].v[SR_W] < 0 || tri[2].v[SR_W] < 0;
        int pos = 0, neg = 0, fans = 0;
        for (int i = 1; i + 1 < n; i++, fans++) {
            int64_t a = area2(&s[0], &s[i], &s[i + 1]);
            pos += a > 0;
            neg += a < 0;
        }
        cr_assert_eq(fans, n - 2);
        cr_assert(pos == 0 || neg == 0, "%d-gon fans into %d clockwise and %d counter-clockwise triangles", n, pos, neg);
    }
    cr_assert_gt(mixed_w, 100, "too few triangles across the eye plane");
}

Test(fan, areas_sum_to_the_screen_area_of_triangle_within_viewport)
{
    /* Independent reference: project the unclipped triangle (all w > 0, depth
     * inside) in double and clip it to the viewport rectangle in 2D. */
    test_rng r = { 61 };
    int checked = 0;
    for (int k = 0; k < FAN_TRIANGLES; k++) {
        sr_vertex_out tri[3];
        sr_screen_vertex s[SR_MAX_CLIP_VERTS];
        int n;
        if (!clipped_screen_polygon(&r, true, tri, s, &n))
            continue;
        int64_t sum = fan_area2(s, n);
        ref_poly ref = { .n = 3 };
        for (int i = 0; i < 3; i++) {
            double w = tri[i].v[SR_W];
            double ndc[4] = { tri[i].v[SR_X] / w, tri[i].v[SR_Y] / w, 0.5, 1.0 };
            memcpy(ref.v[i], ndc, sizeof ndc);
        }
        ref_clip(&ref, (1u << SR_PLANE_LEFT) | (1u << SR_PLANE_RIGHT) | (1u << SR_PLANE_BOTTOM) | (1u << SR_PLANE_TOP));
        double px[REF_MAX_VERTS], py[REF_MAX_VERTS], perimeter = 0;
        for (int i = 0; i < ref.n; i++) {
            px[i] = (ref.v[i][0] + 1) * FB_W / 2;
            py[i] = (1 - ref.v[i][1]) * FB_H / 2;
        }
        for (int i = 0; i < ref.n; i++)
            perimeter += hypot(px[(i + 1) % ref.n] - px[i], py[(i + 1) % ref.n] - py[i]);
        double want = fabs(shoelace(px, py, ref.n)), got = fabs((double)sum) / 2 / ((double)ONE * ONE);
        /* Snapping moves each vertex by at most 1/512 px per axis. */
        cr_assert(fabs(got - want) <= perimeter / 256 + 1e-6 * want, "fan area %.6f px², reference %.6f px²", got,
                  want);
        checked++;
    }
    cr_assert_gt(checked, FAN_TRIANGLES / 4);
}

Test(fan, winding_on_screen_matches_the_clip_space_determinant)
{
    /* With y down, a triangle's screen winding is -sign det[(x, y, w)_i]; the
     * clipped polygon must keep it even when some input w are negative. */
    test_rng r = { 62 };
    int mixed_w = 0;
    for (int k = 0; k < FAN_TRIANGLES; k++) {
        sr_vertex_out tri[3];
        sr_screen_vertex s[SR_MAX_CLIP_VERTS];
        int n;
        if (!clipped_screen_polygon(&r, false, tri, s, &n))
            continue;
        const float *a = tri[0].v, *b = tri[1].v, *c = tri[2].v;
        double det = (double)a[SR_X] * ((double)b[SR_Y] * c[SR_W] - (double)b[SR_W] * c[SR_Y]) -
                     (double)a[SR_Y] * ((double)b[SR_X] * c[SR_W] - (double)b[SR_W] * c[SR_X]) +
                     (double)a[SR_W] * ((double)b[SR_X] * c[SR_Y] - (double)b[SR_Y] * c[SR_X]);
        int64_t sum = fan_area2(s, n);
        if (sum == 0)
            continue;
        mixed_w += a[SR_W] < 0 || b[SR_W] < 0 || c[SR_W] < 0;
        cr_assert((sum > 0) == (det < 0), "area2 %lld, det %g", (long long)sum, det);
    }
    cr_assert_gt(mixed_w, 100, "too few triangles across the eye plane");
}
