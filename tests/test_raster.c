/* Stages 7–8 called directly: sr_raster_triangle must cover exactly the
 * pixels of the reference in raster_reference.h, on thousands of random,
 * tiny, sliver and grid-aligned triangles of either winding, within any
 * rect, up to the largest framebuffer side. test_raster_draw.c checks the
 * same through sr_draw.
 */
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
