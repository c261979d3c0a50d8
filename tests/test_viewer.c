/* The viewer's controls, driven by the same SDL events the window feeds it,
 * with no window. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "app/view/viewer.h"

/* The controls' numbers as README's key table documents them, not the
 * viewer's own constants: a constant changed by mistake must fail here. */
#define SHIFT_FACTOR 4.0f   /* "4× faster while held" */
#define WHEEL_FACTOR 1.25f  /* "the speed ×1.25 or ÷1.25 a notch" */
#define LOOK_DEG 0.15f      /* "look (0.15° a pixel)" */
#define NEAREST_NEAR 1e-6f  /* "near plane ÷2 ×2 (down to 1e−6)" */
#define FARTHEST_FAR 1e30f  /* "far plane ÷2 ×2 (up to 1e30)" */

static sr_viewer viewer;

static void open_room(void)
{
    sr_scene_setup setup;
    sr_error err;
    sr_scene_setup_defaults(&setup);
    setup.mesh_path = "assets/room.obj";
    setup.size[0] = 64;
    setup.size[1] = 36;
    memcpy(setup.eye, (double[3]){ -8.0, 3.0, -8.0 }, sizeof setup.eye); /* as --eye and --target set them */
    memcpy(setup.target, (double[3]){ -8.0, 3.0, 0.0 }, sizeof setup.target);
    setup.eye_set = setup.target_set = true;
    cr_assert(sr_viewer_init(&viewer, &setup, &err), "%s", err.message);
    viewer.speed = 2.0f;
}

static void close_room(void)
{
    sr_viewer_free(&viewer);
}

TestSuite(viewer, .init = open_room, .fini = close_room);

static void key(SDL_Keycode sym, Uint16 mod, bool down)
{
    SDL_Event e = { .key = { .type = down ? SDL_KEYDOWN : SDL_KEYUP, .keysym = { .sym = sym, .mod = mod } } };
    sr_viewer_handle_event(&viewer, &e);
}

static void press(SDL_Keycode sym, Uint16 mod)
{
    key(sym, mod, true);
    key(sym, mod, false);
}

static void assert_eye(float x, float y, float z)
{
    const float *e = viewer.setup.camera.eye;
    cr_assert(fabsf(e[0] - x) < 1e-4f && fabsf(e[1] - y) < 1e-4f && fabsf(e[2] - z) < 1e-4f,
              "eye is %g %g %g, want %g %g %g", e[0], e[1], e[2], x, y, z);
}

Test(viewer, w_held_for_one_second_moves_forward_by_the_speed)
{
    key(SDLK_w, 0, true);
    sr_viewer_advance(&viewer, 1.0);
    assert_eye(-8.0f, 3.0f, -6.0f); /* looking along +z */
    key(SDLK_w, 0, false);
    sr_viewer_advance(&viewer, 1.0);
    assert_eye(-8.0f, 3.0f, -6.0f);
}

Test(viewer, a_d_q_e_strafe_left_right_down_up)
{
    key(SDLK_d, 0, true);
    key(SDLK_e, 0, true);
    sr_viewer_advance(&viewer, 0.5);
    assert_eye(-7.0f, 4.0f, -8.0f); /* +x is right when looking along +z (left-handed) */
    key(SDLK_d, 0, false);
    key(SDLK_e, 0, false);
    key(SDLK_a, 0, true);
    key(SDLK_q, 0, true);
    sr_viewer_advance(&viewer, 0.5);
    assert_eye(-8.0f, 3.0f, -8.0f);
}

Test(viewer, shift_moves_four_times_faster)
{
    key(SDLK_LSHIFT, 0, true);
    key(SDLK_s, 0, true);
    sr_viewer_advance(&viewer, 0.25);
    assert_eye(-8.0f, 3.0f, -8.0f - SHIFT_FACTOR * 0.5f);
}

Test(viewer, wheel_scales_the_speed)
{
    SDL_Event up = { .wheel = { .type = SDL_MOUSEWHEEL, .y = 1 } };
    SDL_Event down = { .wheel = { .type = SDL_MOUSEWHEEL, .y = -1 } };
    sr_viewer_handle_event(&viewer, &up);
    cr_assert_float_eq(viewer.speed, 2.0f * WHEEL_FACTOR, 1e-6f);
    sr_viewer_handle_event(&viewer, &down);
    sr_viewer_handle_event(&viewer, &down);
    cr_assert_float_eq(viewer.speed, 2.0f / WHEEL_FACTOR, 1e-6f);
}

static void move_mouse(int dx, int dy)
{
    SDL_Event e = { .motion = { .type = SDL_MOUSEMOTION, .xrel = dx, .yrel = dy } };
    sr_viewer_handle_event(&viewer, &e);
}

Test(viewer, mouse_turns_only_in_look_mode)
{
    move_mouse(100, 0);
    cr_assert_float_eq(viewer.fly.yaw, 0.0f, 1e-6f);
    press(SDLK_TAB, 0);
    move_mouse(100, -50);
    cr_assert_float_eq(viewer.fly.yaw, 100 * LOOK_DEG, 1e-4f);
    cr_assert_float_eq(viewer.fly.pitch, 50 * LOOK_DEG, 1e-4f);
    press(SDLK_TAB, 0);
    move_mouse(100, 0);
    cr_assert_float_eq(viewer.fly.yaw, 100 * LOOK_DEG, 1e-4f);
}

Test(viewer, right_button_holds_look_mode)
{
    SDL_Event down = { .button = { .type = SDL_MOUSEBUTTONDOWN, .button = SDL_BUTTON_RIGHT } };
    SDL_Event up = { .button = { .type = SDL_MOUSEBUTTONUP, .button = SDL_BUTTON_RIGHT } };
    sr_viewer_handle_event(&viewer, &down);
    cr_assert(viewer.mouse_look);
    sr_viewer_handle_event(&viewer, &up);
    cr_assert_not(viewer.mouse_look);
}

Test(viewer, looking_straight_up_and_down_stays_defined)
{
    sr_error err;
    press(SDLK_TAB, 0);
    for (int pitch_dir = -1; pitch_dir <= 1; pitch_dir += 2) {
        move_mouse(0, pitch_dir * 100000);
        sr_viewer_advance(&viewer, 0.0);
        cr_assert_float_eq(fabsf(viewer.fly.pitch), SR_FLYCAM_MAX_PITCH, 1e-4f);
        cr_assert(sr_camera_check(&viewer.setup.camera, &err), "%s", err.message);
        cr_assert(sr_viewer_draw(&viewer, true, &err), "%s", err.message);
        cr_assert_gt(viewer.stats.fragments, 0);
    }
}

Test(viewer, r_resets_the_camera)
{
    key(SDLK_w, 0, true);
    sr_viewer_advance(&viewer, 3.0);
    key(SDLK_w, 0, false);
    press(SDLK_r, 0);
    sr_viewer_advance(&viewer, 0.0);
    assert_eye(-8.0f, 3.0f, -8.0f);
}

Test(viewer, f_keys_toggle_views_and_cycle_modes)
{
    press(SDLK_F1, 0);
    press(SDLK_F2, 0);
    press(SDLK_F4, 0);
    press(SDLK_l, 0);
    cr_assert(viewer.help && viewer.wireframe && viewer.show_depth && viewer.depth_linear);
    press(SDLK_F5, 0);
    cr_assert_eq(viewer.setup.cull, SR_CULL_FRONT);
    press(SDLK_F5, 0);
    press(SDLK_F5, 0);
    cr_assert_eq(viewer.setup.cull, SR_CULL_BACK);
    press(SDLK_F12, 0);
    cr_assert(viewer.screenshot_wanted);
}

Test(viewer, f3_cycles_only_through_modes_the_mesh_supports)
{
    /* The room has normals, uvs and a texture but no vertex colors. */
    int seen[SR_SHADE_COUNT] = { 0 };
    for (int i = 0; i < 2 * (SR_SHADE_COUNT - 1); i++) {
        press(SDLK_F3, 0);
        seen[viewer.setup.shade]++;
    }
    cr_assert_eq(seen[SR_SHADE_COLOR], 0);
    for (int m = 0; m < SR_SHADE_COUNT; m++)
        if (m != SR_SHADE_COLOR)
            cr_assert_eq(seen[m], 2, "mode %d seen %d times", m, seen[m]);
}

Test(viewer, brackets_move_near_and_far_within_bounds)
{
    press(SDLK_LEFTBRACKET, 0);
    cr_assert_float_eq(viewer.setup.camera.near, 0.05f, 1e-7f);
    for (int i = 0; i < 100; i++)
        press(SDLK_LEFTBRACKET, 0);
    cr_assert_float_eq(viewer.setup.camera.near, NEAREST_NEAR, 1e-12f);
    press(SDLK_RIGHTBRACKET, KMOD_LSHIFT);
    cr_assert_float_eq(viewer.setup.camera.far, 200.0f, 1e-3f);
    for (int i = 0; i < 200; i++)
        press(SDLK_LEFTBRACKET, KMOD_LSHIFT);
    cr_assert_gt(viewer.setup.camera.far, viewer.setup.camera.near);
    for (int i = 0; i < 200; i++)
        press(SDLK_RIGHTBRACKET, KMOD_RSHIFT);
    cr_assert_float_eq(viewer.setup.camera.far, FARTHEST_FAR, 1e24f);
}

Test(viewer, escape_and_window_close_quit)
{
    press(SDLK_ESCAPE, 0);
    cr_assert(viewer.quit);
    viewer.quit = false;
    SDL_Event e = { .type = SDL_QUIT };
    sr_viewer_handle_event(&viewer, &e);
    cr_assert(viewer.quit);
}

/* Near 1e-6, far 1e30, flying through a wall and a pillar: every frame draws
 * and every depth written is finite and in [0, 1]. */
Test(viewer, extreme_planes_through_walls_keep_depth_in_range)
{
    sr_error err;
    for (int i = 0; i < 100; i++) {
        press(SDLK_LEFTBRACKET, 0);
        press(SDLK_RIGHTBRACKET, KMOD_LSHIFT);
    }
    press(SDLK_F4, 0);
    key(SDLK_LSHIFT, 0, true);
    key(SDLK_w, 0, true);
    for (int frame = 0; frame < 40; frame++) {
        sr_viewer_advance(&viewer, 0.1); /* 0.8 units a frame: out through the far wall */
        cr_assert(sr_viewer_draw(&viewer, true, &err), "%s", err.message);
        const sr_framebuffer *fb = &viewer.scene.fb;
        for (int i = 0; i < fb->width * fb->height; i++)
            cr_assert(isfinite(fb->depth[i]) && fb->depth[i] >= 0.0f && fb->depth[i] <= 1.0f,
                      "frame %d pixel %d depth %g", frame, i, fb->depth[i]);
    }
    cr_assert_gt(viewer.setup.camera.eye[2], 10.0f, "the flight should have left the room");
}

Test(viewer, resize_changes_framebuffer_and_aspect)
{
    sr_error err;
    cr_assert(sr_viewer_resize(&viewer, 40, 80, &err), "%s", err.message);
    cr_assert(sr_viewer_draw(&viewer, true, &err), "%s", err.message);
    cr_assert_eq(viewer.scene.fb.width, 40);
    cr_assert_eq(viewer.scene.fb.height, 80);
    cr_assert_not(sr_viewer_resize(&viewer, 0, 80, &err));
    cr_assert_eq(viewer.scene.fb.width, 40, "a failed resize keeps the old framebuffer");
}

Test(viewer, status_line_reports_counts_and_planes)
{
    sr_error err;
    char status[512];
    cr_assert(sr_viewer_draw(&viewer, true, &err), "%s", err.message);
    sr_viewer_status(&viewer, status, sizeof status);
    char want[128];
    snprintf(want, sizeof want, "triangles %llu", (unsigned long long)viewer.stats.triangles);
    cr_assert_not_null(strstr(status, want), "%s", status);
    cr_assert_not_null(strstr(status, "near 0.1  far 100"), "%s", status);
}

Test(viewer, f6_draws_the_edges_with_hidden_lines_removed_and_f2_still_collects_triangles)
{
    sr_error err;
    cr_assert(sr_viewer_draw(&viewer, true, &err), "%s", err.message);
    uint64_t triangles = viewer.stats.triangles;
    cr_assert_gt(triangles, 0);
    press(SDLK_F6, 0);
    press(SDLK_F2, 0);
    cr_assert(sr_viewer_draw(&viewer, true, &err), "%s", err.message);
    cr_assert_eq(viewer.stats.triangles, 0);
    cr_assert_eq(viewer.stats.lines, viewer.wire.wire.edges.index_count / 2);
    cr_assert_gt(viewer.stats.fragments, 0);
    cr_assert_gt(viewer.wire_count, 0, "F2's fan triangles come from the depth pass");
    char status[512];
    sr_viewer_status(&viewer, status, sizeof status);
    cr_assert_not_null(strstr(status, "lines "), "%s", status);
    press(SDLK_F6, 0);
    cr_assert(sr_viewer_draw(&viewer, false, &err), "%s", err.message);
    cr_assert_eq(viewer.stats.triangles, triangles);
}
