/* Stages 7–8 called directly: sr_raster_triangle must cover exactly the
 * pixels of the reference in raster_reference.h, on thousands of random,
 * tiny, sliver and grid-aligned triangles of either winding, within any
 * rect, up to the largest framebuffer side. test_raster_draw.c checks the
 * same through sr_draw. Depth comes from the plane through the unsnapped
 * vertices (x_off, y_off), finite and in [0, 1] even where snapping turned
 * a sliver over.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <criterion/criterion.h>

#include "raster_reference.h"

static const sr_shade_context id_shade = { .layout = { .count = 0, .color = -1, .uv = -1, .normal = -1 } };

static uint64_t raster_direct(sr_framebuffer *fb, sr_raster_rect rect, const ref_point v[3])
{
    sr_screen_vertex s[3];
    for (int k = 0; k < 3; k++)
        s[k] = (sr_screen_vertex){ .x = v[k].x, .y = v[k].y, .z = TRIANGLE_Z, .inv_w = 1.0f };
    return sr_raster_triangle(fb, rect, SR_SUBPIXEL_BITS, SR_SHADE_ID, &id_shade, s, ref_turn(v[0], v[1], v[2]), 0);
}

/* Rasterizes v within rect on a cleared fb and expects exactly the reference
 * pixels drawn (none outside rect), one fragment each. */
static void expect_reference_raster(const char *name, int t, kind k, const ref_point v[3], sr_framebuffer *fb,
                                    sr_raster_rect rect)
{
    static unsigned char want[FB_W * FB_H];
    sr_framebuffer_clear(fb, SCENE_BACKGROUND);
    memset(want, 0, sizeof want);
    uint64_t fragments = raster_direct(fb, rect, v);
    size_t count = ref_mask(v, FB_W, rect, want);
    expect_mask(name, t, k, v, fb, want);
    cr_assert_eq(fragments, count, "triangle %d: %llu fragments, %zu pixels", t, (unsigned long long)fragments,
                 count);
}

Test(raster, covers_exactly_the_reference_pixels_of_random_triangles)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, FB_W, FB_H);
    test_rng rng = { RANDOM_SEED };
    int drawn = 0;
    for (int t = 0; t < RANDOM_TRIANGLES; t++) {
        kind k = (kind)(t % KIND_COUNT);
        ref_point v[3];
        random_triangle(&rng, k, FB_W, FB_H, v);
        if (ref_turn(v[0], v[1], v[2]) == 0)
            continue; /* sr_raster_triangle takes nonzero area only */
        expect_reference_raster("raster_covers_exactly_the_reference_pixels_of_random_triangles", t, k, v, &fb,
                                full_rect);
        drawn++;
    }
    cr_expect_gt(drawn, RANDOM_TRIANGLES * 9 / 10, "too many degenerate triangles: %d drawn", drawn);
    sr_framebuffer_destroy(&fb);
}

/* Boxes up to and just past the ones whose pixels the set-up tests before
 * the depth plane (sr_tri_setup.tiny: up to 7 wide and 8 tall), of either
 * winding, with vertices anywhere or on pixel centres (edges through
 * centres: the top-left rule decides), within the framebuffer or a rect
 * that cuts their boxes. */
Test(raster, boxes_up_to_and_past_the_tiny_ones_cover_exactly_the_reference_pixels)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, FB_W, FB_H);
    test_rng rng = { RANDOM_SEED + 1 };
    const sr_raster_rect inner = { 3, 2, FB_W - 5, FB_H - 4 };
    for (int t = 0; t < RANDOM_TRIANGLES; t++) {
        int64_t reach_x = rng_range(&rng, 0, 10 * ONE), reach_y = rng_range(&rng, 0, 10 * ONE);
        int64_t x0 = rng_range(&rng, 0, FB_W * ONE - reach_x), y0 = rng_range(&rng, 0, FB_H * ONE - reach_y);
        ref_point v[3];
        for (int i = 0; i < 3; i++) {
            v[i] = (ref_point){ x0 + rng_range(&rng, 0, reach_x), y0 + rng_range(&rng, 0, reach_y) };
            if (t % 2)
                v[i] = (ref_point){ v[i].x / ONE * ONE + HALF, v[i].y / ONE * ONE + HALF };
        }
        if (ref_turn(v[0], v[1], v[2]) == 0)
            continue;
        expect_reference_raster("raster_boxes_up_to_and_past_the_tiny_ones_cover_exactly_the_reference_pixels", t,
                                t % 2 ? KIND_CENTRES : KIND_TINY, v, &fb, t % 3 ? full_rect : inner);
    }
    sr_framebuffer_destroy(&fb);
}

Test(raster, coverage_is_the_same_for_all_six_vertex_orders)
{
    static const int orders[6][3] = { { 0, 1, 2 }, { 1, 2, 0 }, { 2, 0, 1 }, { 0, 2, 1 }, { 2, 1, 0 }, { 1, 0, 2 } };
    sr_framebuffer fb;
    scene_fb_make(&fb, FB_W, FB_H);
    unsigned char first[FB_W * FB_H];
    test_rng rng = { RANDOM_SEED + 2 };
    for (int t = 0; t < RANDOM_TRIANGLES / 10; t++) {
        kind k = (kind)(t % KIND_COUNT);
        ref_point v[3];
        random_triangle(&rng, k, FB_W, FB_H, v);
        if (ref_turn(v[0], v[1], v[2]) == 0)
            continue;
        for (int o = 0; o < 6; o++) {
            ref_point p[3] = { v[orders[o][0]], v[orders[o][1]], v[orders[o][2]] };
            sr_framebuffer_clear(&fb, SCENE_BACKGROUND);
            raster_direct(&fb, full_rect, p);
            if (o == 0) {
                for (size_t i = 0; i < sizeof first; i++)
                    first[i] = fb.color[i] != SCENE_BACKGROUND;
                continue;
            }
            expect_mask("raster_coverage_is_the_same_for_all_six_vertex_orders", t * 6 + o, k, p, &fb, first);
        }
    }
    sr_framebuffer_destroy(&fb);
}

Test(raster, writes_only_inside_rect_for_overhanging_triangles)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, FB_W, FB_H);
    test_rng rng = { RANDOM_SEED + 3 };
    for (int t = 0; t < RANDOM_TRIANGLES / 3; t++) {
        kind k = (kind)(t % KIND_COUNT);
        ref_point v[3];
        random_triangle(&rng, k, FB_W, FB_H, v);
        overhang(&rng, FB_W, FB_H, v);
        if (ref_turn(v[0], v[1], v[2]) == 0)
            continue;
        /* Every third triangle uses the whole image; the others a random tile. */
        sr_raster_rect rect = full_rect;
        if (t % 3) {
            int x0 = (int)rng_range(&rng, 0, FB_W - 1), y0 = (int)rng_range(&rng, 0, FB_H - 1);
            rect = (sr_raster_rect){ x0, y0, (int)rng_range(&rng, x0 + 1, FB_W),
                                     (int)rng_range(&rng, y0 + 1, FB_H) };
        }
        expect_reference_raster("raster_writes_only_inside_rect_for_overhanging_triangles", t, k, v, &fb, rect);
    }
    sr_framebuffer_destroy(&fb);
}

/* A rectangle with corners on pixel centres (2.5, 1.5) – (6.5, 4.5), split
 * along either diagonal: its top row and left column of centres are on top
 * and left edges (drawn), its bottom row and right column on bottom and right
 * edges (not drawn), so exactly pixels [2, 6) x [1, 4) are drawn, each once. */
Test(raster, rectangle_on_pixel_centres_draws_top_left_rows_and_columns_once)
{
    const int64_t x0 = 2 * ONE + HALF, x1 = 6 * ONE + HALF, y0 = 1 * ONE + HALF, y1 = 4 * ONE + HALF;
    const ref_point a = { x0, y0 }, b = { x1, y0 }, c = { x1, y1 }, d = { x0, y1 };
    const ref_point halves[2][2][3] = { { { a, b, d }, { b, c, d } }, { { a, b, c }, { a, c, d } } };
    sr_framebuffer fb;
    scene_fb_make(&fb, FB_W, FB_H);
    for (int diagonal = 0; diagonal < 2; diagonal++) {
        uint32_t hits[FB_W * FB_H] = { 0 }, want[FB_W * FB_H] = { 0 };
        for (int half = 0; half < 2; half++) {
            sr_framebuffer_clear(&fb, SCENE_BACKGROUND);
            raster_direct(&fb, full_rect, halves[diagonal][half]);
            for (int i = 0; i < FB_W * FB_H; i++)
                hits[i] += fb.color[i] != SCENE_BACKGROUND ? 0x808080u : 0u; /* two hits: 0x101010 */
        }
        for (int j = 1; j < 4; j++)
            for (int i = 2; i < 6; i++)
                want[j * FB_W + i] = 0x808080u;
        scene_expect_images_equal(diagonal ? "raster_rectangle_on_pixel_centres_diagonal_ac"
                                           : "raster_rectangle_on_pixel_centres_diagonal_bd",
                                  hits, want, FB_W, FB_H);
    }
    sr_framebuffer_destroy(&fb);
}

/* At the largest framebuffer side the edge functions reach 2^44 and must
 * still be exact: long slivers across a 16384 x 2 and a 2 x 16384 image. */
Test(raster, matches_reference_at_maximum_framebuffer_side)
{
    const int sizes[2][2] = { { SR_MAX_FRAMEBUFFER_SIDE, 2 }, { 2, SR_MAX_FRAMEBUFFER_SIDE } };
    test_rng rng = { RANDOM_SEED + 4 };
    for (int s = 0; s < 2; s++) {
        int w = sizes[s][0], h = sizes[s][1];
        sr_framebuffer fb;
        scene_fb_make(&fb, w, h);
        unsigned char *want = calloc((size_t)w * (size_t)h, 1);
        cr_assert_not_null(want);
        for (int t = 0; t < 40; t++) {
            ref_point v[3];
            kind k = t % 2 ? KIND_ANY : KIND_SLIVER;
            random_triangle(&rng, k, w, h, v);
            if (ref_turn(v[0], v[1], v[2]) == 0)
                continue;
            sr_framebuffer_clear(&fb, SCENE_BACKGROUND);
            uint64_t fragments = raster_direct(&fb, (sr_raster_rect){ 0, 0, w, h }, v);
            size_t count = ref_mask(v, w, (sr_raster_rect){ 0, 0, w, h }, want);
            expect_mask("raster_matches_reference_at_maximum_framebuffer_side", s * 100 + t, k, v, &fb, want);
            cr_assert_eq(fragments, count);
        }
        free(want);
        sr_framebuffer_destroy(&fb);
    }
}

#define STEEP_TRIANGLES 2000
#define STEEP_REACH (6 * ONE) /* vertices within 6 px: depth slopes of ~0.3 per pixel, far more on slivers */
/* The drawn depth is the row's z, rounded to float at the pixel of vertex 0,
 * plus a float step times the columns from there: a few float roundings of
 * values up to 1 + the slope times the box's width (measured worst 4.1e-7,
 * on a sliver). The snapped plane was off by up to half a subpixel step
 * times the slope, ~6e-4 on these. */
#define ROUNDINGS_ALLOWED 4.0

/* The plane through the unsnapped points (subpixel units) at pixel (i, j)'s
 * centre, clamped to [0, 1] as stored depths are; *slope: its |dz/dx| +
 * |dz/dy| per pixel. */
static double unsnapped_plane_at(const sr_screen_vertex s[3], int i, int j, double *slope)
{
    double x[3], y[3];
    for (int k = 0; k < 3; k++) {
        x[k] = (double)s[k].x + s[k].x_off;
        y[k] = (double)s[k].y + s[k].y_off;
    }
    double px = (double)(i * ONE + HALF), py = (double)(j * ONE + HALF);
    double det = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    double l1 = ((px - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (py - y[0])) / det;
    double l2 = ((x[1] - x[0]) * (py - y[0]) - (px - x[0]) * (y[1] - y[0])) / det;
    double dz1 = (double)s[1].z - s[0].z, dz2 = (double)s[2].z - s[0].z;
    *slope = (fabs(dz1 * (y[2] - y[0]) - dz2 * (y[1] - y[0])) + fabs(dz2 * (x[1] - x[0]) - dz1 * (x[2] - x[0]))) *
             ONE / fabs(det);
    return fmin(fmax(s[0].z + l1 * ((double)s[1].z - s[0].z) + l2 * ((double)s[2].z - s[0].z), 0.0), 1.0);
}

static uint64_t raster_depth(sr_framebuffer *fb, const sr_screen_vertex s[3])
{
    int64_t area2 = sr_cull_area2(&s[0], &s[1], &s[2]);
    cr_assert_neq(area2, 0);
    sr_framebuffer_clear(fb, SCENE_BACKGROUND);
    return sr_raster_triangle(fb, full_rect, SR_SUBPIXEL_BITS, SR_SHADE_DEPTH, &id_shade, s, area2, 0);
}

Test(raster, depth_is_the_plane_through_the_unsnapped_vertices_on_steep_triangles)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, FB_W, FB_H);
    test_rng rng = { RANDOM_SEED + 5 };
    int checked = 0;
    double worst = 0.0;
    for (int t = 0; t < STEEP_TRIANGLES; t++) {
        sr_screen_vertex s[3];
        int64_t x0 = (int64_t)rng_uniform(&rng, 0, FB_W * ONE), y0 = (int64_t)rng_uniform(&rng, 0, FB_H * ONE);
        for (int k = 0; k < 3; k++)
            s[k] = (sr_screen_vertex){ .x = x0 + (k ? (int64_t)rng_uniform(&rng, -STEEP_REACH, STEEP_REACH) : 0),
                                       .y = y0 + (k ? (int64_t)rng_uniform(&rng, -STEEP_REACH, STEEP_REACH) : 0),
                                       .x_off = (float)rng_uniform(&rng, -0.5, 0.5),
                                       .y_off = (float)rng_uniform(&rng, -0.5, 0.5),
                                       .z = (float)rng_uniform(&rng, 0.05, 0.95),
                                       .inv_w = 1.0f };
        if (sr_cull_area2(&s[0], &s[1], &s[2]) == 0)
            continue;
        raster_depth(&fb, s);
        const ref_point v[3] = { { s[0].x, s[0].y }, { s[1].x, s[1].y }, { s[2].x, s[2].y } };
        for (int j = 0; j < FB_H; j++)
            for (int i = 0; i < FB_W; i++) {
                float got = fb.depth[j * FB_W + i];
                /* Drawn or not by the reference coverage, not by the value:
                 * a covered pixel may be drawn at exactly the clear depth. */
                if (!ref_covers(v, (ref_point){ (int64_t)i * ONE + HALF, (int64_t)j * ONE + HALF }))
                    continue;
                double slope, err = fabs(got - unsnapped_plane_at(s, i, j, &slope));
                double tolerance = ROUNDINGS_ALLOWED * 0x1p-24 * (1.0 + slope * 2.0 * STEEP_REACH / ONE);
                worst = fmax(worst, err);
                checked++;
                cr_expect_leq(err, tolerance, "triangle %d, pixel (%d, %d): depth %.9g, plane off by %.3g (slope %.3g)",
                              t, i, j, got, err, slope);
            }
    }
    cr_expect_gt(checked, STEEP_TRIANGLES, "only %d pixels checked", checked);
    cr_log_info("unsnapped plane: %d pixels, worst %.3g", checked, worst);
    sr_framebuffer_destroy(&fb);
}

/* A sliver one subpixel high on a row of pixel centres (its top edge on
 * them), whose unsnapped points lie on a line, turned over, or all but on a
 * line: depth stays finite and in [0, 1] at every pixel it draws. */
Test(raster, slivers_that_snapping_turned_over_draw_finite_depth_in_unit_range)
{
    static const float apex_off[] = { -0.5f, -0.5f + 1e-6f, -0.5f + 1e-3f };
    static const float base_off[] = { 0.5f, 0.5f - 1e-6f };
    sr_framebuffer fb;
    scene_fb_make(&fb, FB_W, FB_H);
    for (size_t a = 0; a < sizeof apex_off / sizeof apex_off[0]; a++)
        for (size_t b = 0; b < sizeof base_off / sizeof base_off[0]; b++) {
            sr_screen_vertex s[3] = {
                { .x = 0, .y = HALF, .y_off = base_off[b], .z = 0.0f, .inv_w = 1.0f },
                { .x = FB_W * ONE, .y = HALF, .y_off = base_off[b], .z = 1.0f, .inv_w = 1.0f },
                { .x = FB_W * ONE / 2, .y = HALF + 1, .y_off = apex_off[a], .z = 0.9f, .inv_w = 1.0f },
            };
            cr_expect_eq(raster_depth(&fb, s), FB_W, "apex %g, base %g", apex_off[a], base_off[b]);
            for (int i = 0; i < FB_W; i++) {
                float z = fb.depth[HALF / ONE * FB_W + i];
                cr_expect(isfinite(z) && z >= 0.0f && z <= 1.0f, "apex %g, base %g, pixel %d: depth %g", apex_off[a],
                          base_off[b], i, z);
            }
        }
    sr_framebuffer_destroy(&fb);
}
