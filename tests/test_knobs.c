/* The accuracy knobs of sr_draw_study: their defaults are the contract's
 * settings exactly, other settings stay close to a fine reference, and
 * settings that could overflow the fixed point are refused. */
#include <criterion/criterion.h>
#include <string.h>

#include "softrast_private.h"

#define W 160
#define H 100

static sr_mesh room;
static sr_framebuffer fb;

static void setup(void)
{
    sr_error err;
    cr_assert(sr_obj_load(&room, "assets/room.obj", &err), "%s", err.message);
    cr_assert(sr_framebuffer_create(&fb, W, H, &err), "%s", err.message);
}

static void teardown(void)
{
    sr_mesh_free(&room);
    sr_framebuffer_destroy(&fb);
}

TestSuite(knobs, .init = setup, .fini = teardown);

/* Ids and depths of the room seen from a camera that clips on every side. */
static bool draw_threads(sr_draw_study study, int threads, uint32_t *ids, float *depth, sr_error *err)
{
    sr_draw_desc desc = { .study = &study, .threads = threads };
    sr_camera cam = sr_camera_default();
    glm_vec3_copy((vec3){ -9.0f, 1.0f, -9.5f }, cam.eye);
    glm_vec3_copy((vec3){ 3.0f, 2.0f, 4.0f }, cam.target);
    cam.fov_deg = 100.0f;
    desc.mesh = &room;
    desc.shade = SR_SHADE_ID;
    sr_camera_view(&cam, desc.view);
    sr_camera_projection(&cam, (float)W / H, desc.projection);
    sr_framebuffer_clear(&fb, 0);
    if (!sr_draw(&fb, &desc, NULL, err))
        return false;
    memcpy(ids, fb.color, sizeof(uint32_t) * W * H);
    memcpy(depth, fb.depth, sizeof(float) * W * H);
    return true;
}

static bool draw(sr_draw_study study, uint32_t *ids, float *depth, sr_error *err)
{
    return draw_threads(study, 1, ids, depth, err);
}

static int differing(const uint32_t *a, const uint32_t *b)
{
    int n = 0;
    for (int i = 0; i < W * H; i++)
        n += a[i] != b[i];
    return n;
}

Test(knobs, explicit_defaults_draw_exactly_the_default_image)
{
    static uint32_t ids0[W * H], ids1[W * H];
    static float depth0[W * H], depth1[W * H];
    sr_error err;
    cr_assert(draw((sr_draw_study){ 0 }, ids0, depth0, &err), "%s", err.message);
    cr_assert(draw((sr_draw_study){ .subpixel_bits = SR_SUBPIXEL_BITS, .clip_precision = SR_CLIP_ADAPTIVE,
                                    .guard_band = 1.0f },
                   ids1, depth1, &err),
              "%s", err.message);
    static const uint32_t blank[W * H];
    cr_assert_gt(differing(ids0, blank), 0, "the default draw drew nothing to compare");
    cr_assert_eq(memcmp(ids0, ids1, sizeof ids0), 0);
    cr_assert_eq(memcmp(depth0, depth1, sizeof depth0), 0);
}

/* Each knob moves few pixels against 16 subpixel bits: at this size a
 * percent would mean a broken edge, not rounding. */
Test(knobs, every_setting_stays_within_a_percent_of_the_fine_reference)
{
    static uint32_t ref[W * H], ids[W * H];
    static float ref_depth[W * H], depth[W * H];
    sr_error err;
    cr_assert(draw((sr_draw_study){ .subpixel_bits = SR_MAX_SUBPIXEL_BITS }, ref, ref_depth, &err), "%s", err.message);
    const sr_draw_study settings[] = { { .subpixel_bits = 4 }, { .subpixel_bits = 12 },
                                       { .clip_precision = SR_CLIP_FLOAT }, { .clip_precision = SR_CLIP_DOUBLE },
                                       { .clip_precision = SR_CLIP_EXACT }, { .guard_band = 2.0f },
                                       { .guard_band = 8.0f }, { .subpixel_bits = 12 } };
    for (size_t i = 0; i < sizeof settings / sizeof *settings; i++) {
        int threads = i + 1 == sizeof settings / sizeof *settings ? 2 : 1;
        cr_assert(draw_threads(settings[i], threads, ids, depth, &err), "%s", err.message);
        cr_assert_lt(differing(ref, ids), W * H / 100, "setting %zu: %d pixels differ", i, differing(ref, ids));
    }
}

Test(knobs, settings_that_could_overflow_are_refused)
{
    static uint32_t ids[W * H];
    static float depth[W * H];
    sr_error err;
    cr_assert_not(draw((sr_draw_study){ .subpixel_bits = 1 }, ids, depth, &err));
    cr_assert_not(draw((sr_draw_study){ .subpixel_bits = SR_MAX_SUBPIXEL_BITS + 1 }, ids, depth, &err));
    cr_assert_not(draw((sr_draw_study){ .guard_band = -1.0f }, ids, depth, &err));
    cr_assert_not(draw((sr_draw_study){ .guard_band = SR_MAX_GUARD_BAND * 2 }, ids, depth, &err));
    cr_assert_not(draw((sr_draw_study){ .clip_precision = (sr_clip_precision)7 }, ids, depth, &err));
    cr_assert(draw((sr_draw_study){ .path = SR_PATH_ROWS }, ids, depth, &err), "%s", err.message);
    cr_assert_not(draw((sr_draw_study){ .path = (sr_draw_path)(SR_PATH_ROWS + 1) }, ids, depth, &err));
    cr_assert_not_null(strstr(err.message, "unknown draw path"), "%s", err.message);
    sr_framebuffer big;
    cr_assert(sr_framebuffer_create(&big, 16384, 1, &err), "%s", err.message);
    sr_draw_desc desc = { .mesh = &room, .study = &(sr_draw_study){ .subpixel_bits = 16, .guard_band = 2.0f } };
    cr_assert_not(sr_draw(&big, &desc, NULL, &err), "16 bits x guard 2 x 16384 px passes 2^30");
    cr_assert_not_null(strstr(err.message, "do not fit"), "%s", err.message);
    sr_framebuffer_destroy(&big);
}
