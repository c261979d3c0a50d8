#include <math.h>
#include <string.h>

#include <criterion/criterion.h>

#include "softrast_private.h"

#define BACKGROUND 0x000000u
#define WHITE 0xFFFFFFu
#define GRAY_FAR 0x303030u /* 48 */

static void expect_create_fails(int width, int height)
{
    sr_framebuffer fb = { .width = 7 };
    sr_error err = { "" };
    cr_assert_not(sr_framebuffer_create(&fb, width, height, &err), "%dx%d accepted", width, height);
    cr_expect_neq(err.message[0], '\0', "no message for %dx%d", width, height);
    cr_expect_null(strstr(err.message, "softrast: error"), "message has the program prefix");
    cr_expect_null(fb.color);
    cr_expect_null(fb.depth);
}

Test(framebuffer, create_rejects_zero_side_with_message)
{
    expect_create_fails(0, 10);
    expect_create_fails(10, 0);
}

Test(framebuffer, create_rejects_negative_side_with_message)
{
    expect_create_fails(-1, 10);
    expect_create_fails(10, -5);
}

Test(framebuffer, create_rejects_side_above_max_with_message)
{
    expect_create_fails(SR_MAX_FRAMEBUFFER_SIDE + 1, 1);
    expect_create_fails(1, SR_MAX_FRAMEBUFFER_SIDE + 1);
}

Test(framebuffer, create_accepts_max_side)
{
    sr_framebuffer fb;
    cr_assert(sr_framebuffer_create(&fb, SR_MAX_FRAMEBUFFER_SIDE, 1, NULL));
    cr_expect_eq(fb.width, SR_MAX_FRAMEBUFFER_SIDE);
    cr_expect_eq(fb.height, 1);
    sr_framebuffer_destroy(&fb);
}

Test(framebuffer, destroy_zeroes_struct)
{
    sr_framebuffer fb;
    cr_assert(sr_framebuffer_create(&fb, 3, 2, NULL));
    sr_framebuffer_destroy(&fb);
    cr_expect_null(fb.color);
    cr_expect_null(fb.depth);
    cr_expect_eq(fb.width, 0);
    cr_expect_eq(fb.height, 0);
}

Test(framebuffer, clear_sets_every_pixel_and_depth)
{
    sr_framebuffer fb;
    cr_assert(sr_framebuffer_create(&fb, 5, 3, NULL));
    for (int i = 0; i < 15; i++) {
        fb.color[i] = (uint32_t)i;
        fb.depth[i] = 0.5f;
    }
    sr_framebuffer_clear(&fb, 0x123456u);
    for (int i = 0; i < 15; i++) {
        cr_expect_eq(fb.color[i], 0x123456u, "color[%d] = %#x", i, fb.color[i]);
        cr_expect_eq(fb.depth[i], SR_DEPTH_CLEAR, "depth[%d] = %g", i, fb.depth[i]);
    }
    sr_framebuffer_destroy(&fb);
}

Test(framebuffer, depth_range_ignores_cleared_pixels)
{
    sr_framebuffer fb;
    cr_assert(sr_framebuffer_create(&fb, 4, 2, NULL));
    sr_framebuffer_clear(&fb, 0);
    fb.depth[1] = 0.75f;
    fb.depth[6] = 0.25f;
    float lo = -1.0f, hi = -1.0f;
    cr_assert(sr_framebuffer_depth_range(&fb, &lo, &hi));
    cr_expect_eq(lo, 0.25f);
    cr_expect_eq(hi, 0.75f);
    sr_framebuffer_destroy(&fb);
}

Test(framebuffer, depth_range_ignores_non_finite_depths)
{
    sr_framebuffer fb;
    cr_assert(sr_framebuffer_create(&fb, 4, 1, NULL));
    float depth[4] = { NAN, -INFINITY, 0.5f, INFINITY };
    memcpy(fb.depth, depth, sizeof depth);
    float lo, hi;
    cr_assert(sr_framebuffer_depth_range(&fb, &lo, &hi));
    cr_expect_eq(lo, 0.5f);
    cr_expect_eq(hi, 0.5f);
    sr_framebuffer_destroy(&fb);
}

Test(framebuffer, depth_range_is_false_when_nothing_was_written)
{
    sr_framebuffer fb;
    cr_assert(sr_framebuffer_create(&fb, 3, 3, NULL));
    sr_framebuffer_clear(&fb, 0);
    float lo = 0.0f, hi = 0.0f;
    cr_expect_not(sr_framebuffer_depth_range(&fb, &lo, &hi));
    sr_framebuffer_destroy(&fb);
}

/* The gray image of a 2x2 depth plane, pixel by pixel against expected. */
static void expect_depth_gray_2x2(const float depth[4], const uint32_t expected[4])
{
    float plane[4];
    memcpy(plane, depth, sizeof plane);
    uint32_t color[4] = { 0 };
    sr_framebuffer fb = { .width = 2, .height = 2, .color = color, .depth = plane };
    uint32_t gray[4];
    sr_framebuffer_depth_to_gray(&fb, gray);
    for (int i = 0; i < 4; i++)
        cr_expect_eq(gray[i], expected[i], "gray[%d] = %#08x, want %#08x", i, gray[i], expected[i]);
}

/* 2x2: near 0.25 → 255, far 0.75 → 48, 0.375 → 255 - 0.25 * 207 = 203.25 → 203,
 * cleared → black. All values are exact binary fractions. */
Test(framebuffer, depth_to_gray_maps_near_white_far_48_background_black)
{
    /* near, cleared, far, a quarter of the way */
    expect_depth_gray_2x2((const float[4]){ 0.25f, SR_DEPTH_CLEAR, 0.75f, 0.375f },
                          (const uint32_t[4]){ WHITE, BACKGROUND, GRAY_FAR, 0xCBCBCBu });
}

Test(framebuffer, depth_to_gray_equal_range_is_white)
{
    expect_depth_gray_2x2((const float[4]){ 0.5f, 0.5f, SR_DEPTH_CLEAR, 0.5f },
                          (const uint32_t[4]){ WHITE, WHITE, BACKGROUND, WHITE });
}

Test(framebuffer, depth_to_gray_non_finite_is_background)
{
    expect_depth_gray_2x2((const float[4]){ NAN, 0.25f, INFINITY, 0.75f },
                          (const uint32_t[4]){ BACKGROUND, WHITE, BACKGROUND, GRAY_FAR });
}
