/* The threaded paths (tiles, row bands) draw exactly what the one-thread path draws:
 * the same ids, colors and depths, bit for bit, and the same counts, for
 * every thread count. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "draw/draw_state.h"
#include "softrast_private.h"
#include "test_rng.h"

typedef struct drawn {
    sr_framebuffer fb;
    sr_stats stats;
} drawn;

static void draw_split(const sr_draw_desc *base, int width, int height, bool reversed, int threads,
                       sr_draw_path path, uint32_t chunk_slots, drawn *out)
{
    sr_error err;
    cr_assert(sr_framebuffer_create(&out->fb, width, height, &err), "%s", err.message);
    out->fb.reversed_z = reversed;
    sr_framebuffer_clear(&out->fb, 0x123456);
    sr_draw_desc desc = *base;
    sr_draw_study study = base->study ? *base->study : (sr_draw_study){ 0 };
    study.path = path; /* not the cost estimate's choice: every path on these small scenes */
    study.chunk_slots = chunk_slots;
    desc.study = &study;
    desc.threads = threads;
    out->stats = (sr_stats){ 0 };
    cr_assert(sr_draw(&out->fb, &desc, &out->stats, &err), "%s", err.message);
}

static void draw_with_threads(const sr_draw_desc *base, int width, int height, bool reversed, int threads,
                              sr_draw_path path, drawn *out)
{
    draw_split(base, width, height, reversed, threads, path, 0, out);
}

static void assert_same_drawing(const drawn *one, const drawn *many, int threads)
{
    size_t n = (size_t)one->fb.width * one->fb.height;
    cr_assert_eq(memcmp(one->fb.color, many->fb.color, n * sizeof *one->fb.color), 0, "color differs with %d threads",
                 threads);
    cr_assert_eq(memcmp(one->fb.depth, many->fb.depth, n * sizeof *one->fb.depth), 0, "depth differs with %d threads",
                 threads);
    cr_assert_eq(memcmp(&one->stats, &many->stats, sizeof one->stats), 0, "stats differ with %d threads", threads);
}

/* The threaded paths: the tiles, and each thread drawing its band of rows. */
static const sr_draw_path threaded_paths[] = { SR_PATH_TILES, SR_PATH_ROWS };
#define THREADED_PATHS (sizeof threaded_paths / sizeof *threaded_paths)

static void assert_same_for_all_thread_counts(const sr_draw_desc *desc, int width, int height, bool reversed)
{
    static const int counts[] = { 1, 2, 3, 4, 7, 16 };
    drawn one;
    draw_with_threads(desc, width, height, reversed, 1, SR_PATH_DIRECT, &one);
    for (size_t p = 0; p < THREADED_PATHS; p++)
        for (size_t c = 0; c < sizeof counts / sizeof *counts; c++) {
            drawn many;
            draw_with_threads(desc, width, height, reversed, counts[c], threaded_paths[p], &many);
            assert_same_drawing(&one, &many, counts[c]);
            sr_framebuffer_destroy(&many.fb);
            /* Chunks of 3 slots: every thread's list of a tile in many
             * segments, the threads' interleaved slot by slot. */
            draw_split(desc, width, height, reversed, counts[c], threaded_paths[p], 3, &many);
            assert_same_drawing(&one, &many, counts[c]);
            sr_framebuffer_destroy(&many.fb);
        }
    cr_assert_gt(one.stats.fragments, 0, "the scene drew nothing: the comparison would prove nothing");
    sr_framebuffer_destroy(&one.fb);
}

static void look_reversed(sr_draw_desc *desc, vec3 eye, vec3 target, float fov, float aspect, bool reversed)
{
    sr_camera cam = sr_camera_default();
    cam.reversed_z = reversed;
    glm_vec3_copy(eye, cam.eye);
    glm_vec3_copy(target, cam.target);
    cam.fov_deg = fov;
    sr_camera_view(&cam, desc->view);
    sr_camera_projection(&cam, aspect, desc->projection);
}

static void look(sr_draw_desc *desc, vec3 eye, vec3 target, float fov, float aspect)
{
    look_reversed(desc, eye, target, fov, aspect, false);
}

/* The tests' dense torus (14 400 triangles), and the camera that looks
 * down on it from above and in front. */
static void torus_make(sr_mesh *torus)
{
    sr_error err;
    cr_assert(sr_shape_torus(torus, 1.0f, 0.4f, 120, 60, &err), "%s", err.message);
}

static void look_at_torus(sr_draw_desc *desc, float aspect, bool reversed)
{
    look_reversed(desc, (vec3){ 0, 1.1f, -1.9f }, (vec3){ 0, 0, 0 }, 60.0f, aspect, reversed);
}

Test(threads, room_ids_and_depth_match_one_thread_through_walls)
{
    sr_mesh room;
    sr_error err;
    cr_assert(sr_obj_load(&room, "assets/room.obj", &err), "%s", err.message);
    static float eyes[][6] = { { -8, 3, -8, 4, 1.5f, 6 }, { -10, 2, 0.3f, 10, 2, 0.3f }, { -5, 2, 0, -25, 2, 0 },
                               { 2, 5.9f, 2, 2, 0, 2.001f } };
    for (size_t i = 0; i < sizeof eyes / sizeof *eyes; i++) {
        sr_draw_desc desc = { .mesh = &room, .shade = SR_SHADE_ID };
        look(&desc, eyes[i], eyes[i] + 3, 75.0f, 392.0f / 258.0f);
        assert_same_for_all_thread_counts(&desc, 392, 258, false); /* 9 tiles of 32 rows, the last of 2 */
    }
    sr_mesh_free(&room);
}

/* Inside a wide guard band a vertex inside every plane may lie far off the
 * framebuffer: the row bands clamp its row, the tiles its box. Coarse
 * snapping and a forced loop on top. */
Test(threads, room_through_a_guard_band_matches_one_thread)
{
    sr_mesh room;
    sr_error err;
    cr_assert(sr_obj_load(&room, "assets/room.obj", &err), "%s", err.message);
    static float eyes[][6] = { { -8, 3, -8, 4, 1.5f, 6 }, { -5, 2, 0, -25, 2, 0 } };
    const sr_draw_study knobs[] = { { .guard_band = 8.0f }, { .guard_band = 64.0f, .subpixel_bits = 4 },
                                    { .guard_band = 1.5f, .simd = SR_SIMD_SCALAR } };
    for (size_t i = 0; i < sizeof eyes / sizeof *eyes; i++)
        for (size_t k = 0; k < sizeof knobs / sizeof *knobs; k++) {
            sr_draw_desc desc = { .mesh = &room, .shade = SR_SHADE_DEPTH, .study = &knobs[k] };
            look(&desc, eyes[i], eyes[i] + 3, 100.0f, 200.0f / 131.0f);
            assert_same_for_all_thread_counts(&desc, 200, 131, false);
        }
    sr_mesh_free(&room);
}

Test(threads, dense_torus_lambert_matches_one_thread)
{
    sr_mesh torus;
    torus_make(&torus);
    sr_draw_desc desc = { .mesh = &torus, .shade = SR_SHADE_LAMBERT };
    look_at_torus(&desc, 301.0f / 173.0f, false);
    assert_same_for_all_thread_counts(&desc, 301, 173, false);
    desc.shade = SR_SHADE_DEPTH;
    assert_same_for_all_thread_counts(&desc, 301, 173, false);
    sr_mesh_free(&torus);
}

/* Under sRGB (its own kernels and tiny queue shaders): the torus in gray,
 * the room in its texture. */
Test(threads, srgb_lambert_matches_one_thread)
{
    sr_mesh torus, room;
    sr_texture tex;
    sr_error err;
    torus_make(&torus);
    sr_draw_desc desc = { .mesh = &torus, .shade = SR_SHADE_LAMBERT, .color_space = SR_COLOR_SRGB };
    look_at_torus(&desc, 301.0f / 173.0f, false);
    assert_same_for_all_thread_counts(&desc, 301, 173, false);
    sr_mesh_free(&torus);
    cr_assert(sr_obj_load(&room, "assets/room.obj", &err), "%s", err.message);
    cr_assert(sr_texture_load(&tex, "assets/room.png", &err), "%s", err.message);
    desc = (sr_draw_desc){ .mesh = &room, .shade = SR_SHADE_LAMBERT, .texture = &tex, .color_space = SR_COLOR_SRGB };
    look(&desc, (vec3){ -8, 3, -8 }, (vec3){ 4, 1.5f, 6 }, 75.0f, 392.0f / 258.0f);
    assert_same_for_all_thread_counts(&desc, 392, 258, false);
    sr_texture_free(&tex);
    sr_mesh_free(&room);
}

/* The cost estimate's own choice on a mesh of pixel-sized triangles, wholly
 * in view and from inside it (most vertices outside a plane): the row
 * bands. Either way what the one-thread direct path draws, with the clear
 * inside the draw and without. */
static void assert_estimate_takes(const sr_draw_desc *desc, sr_draw_path want)
{
    sr_error err;
    drawn one;
    draw_with_threads(desc, 301, 173, false, 1, SR_PATH_DIRECT, &one);
    cr_assert_gt(one.stats.fragments, 0, "the scene drew nothing: the comparison would prove nothing");
    for (int clear = 0; clear < 2; clear++)
        for (int threads = 2; threads <= 16; threads *= 2) {
            drawn many;
            cr_assert(sr_framebuffer_create(&many.fb, 301, 173, &err), "%s", err.message);
            sr_framebuffer_clear(&many.fb, clear ? 0xABCDEF : 0x123456);
            sr_draw_times times = { 0 };
            sr_draw_desc d = *desc;
            d.threads = threads;
            d.clear = clear;
            d.study = &(sr_draw_study){ .times = &times };
            many.stats = (sr_stats){ 0 };
            cr_assert(sr_draw(&many.fb, &d, &many.stats, &err), "%s", err.message);
            cr_assert_eq(times.path, want, "%d threads took path %d", threads, (int)times.path);
            assert_same_drawing(&one, &many, threads);
            sr_framebuffer_destroy(&many.fb);
        }
    sr_framebuffer_destroy(&one.fb);
}

Test(threads, cost_estimate_on_a_dense_mesh_matches_one_thread)
{
    sr_mesh torus;
    sr_error err;
    cr_assert(sr_shape_torus(&torus, 1.0f, 0.4f, 200, 100, &err), "%s", err.message);
    sr_draw_desc desc = { .mesh = &torus, .shade = SR_SHADE_LAMBERT, .clear_color = 0x123456 };
    look(&desc, (vec3){ 0, 2.5f, -4.5f }, (vec3){ 0, 0, 0 }, 60.0f, 301.0f / 173.0f);
    assert_estimate_takes(&desc, SR_PATH_ROWS);
    desc.cull = SR_CULL_NONE; /* in the tube, along it, as the bench's inside scene */
    look(&desc, (vec3){ 1.1f, 0.1f, 0.0f }, (vec3){ 0.9f, 0.0f, 1.0f }, 60.0f, 301.0f / 173.0f);
    assert_estimate_takes(&desc, SR_PATH_ROWS);
    sr_mesh_free(&torus);
}

/* A workspace keeps its worker threads from draw to draw (threads.c):
 * draws with one workspace whose thread count goes up and down draw what
 * the one-thread direct path draws. */
Test(threads, one_workspace_matches_one_thread_as_the_thread_count_changes)
{
    static const int counts[] = { 1, 2, 7, 3, 16, 1, 2, 16, 4, 1, 3 };
    sr_mesh torus;
    torus_make(&torus);
    sr_draw_desc desc = { .mesh = &torus, .shade = SR_SHADE_LAMBERT };
    look_at_torus(&desc, 301.0f / 173.0f, false);
    drawn one;
    draw_with_threads(&desc, 301, 173, false, 1, SR_PATH_DIRECT, &one);
    cr_assert_gt(one.stats.fragments, 0, "the scene drew nothing: the comparison would prove nothing");
    desc.workspace = sr_workspace_create();
    cr_assert_not_null(desc.workspace);
    for (size_t c = 0; c < sizeof counts / sizeof *counts; c++) {
        drawn many;
        draw_with_threads(&desc, 301, 173, false, counts[c], threaded_paths[c % THREADED_PATHS], &many);
        assert_same_drawing(&one, &many, counts[c]);
        sr_framebuffer_destroy(&many.fb);
    }
    sr_workspace_destroy(desc.workspace);
    sr_framebuffer_destroy(&one.fb);
    sr_mesh_free(&torus);
}

/* The row bands split the rows by the costs the last draw with the
 * workspace measured, kept per mesh and framebuffer height: draws of other
 * scenes, into other heights, on other thread counts, with one workspace,
 * each draw what the one-thread path draws. */
Test(threads, row_bands_of_one_workspace_match_one_thread_across_scenes_and_heights)
{
    static const struct {
        bool room;
        int height, threads;
    } draws[] = { { false, 173, 2 }, { true, 173, 2 }, { false, 173, 3 }, { false, 90, 2 },
                  { true, 173, 7 },  { false, 173, 2 }, { true, 90, 16 }, { false, 90, 1 } };
    sr_mesh torus, room;
    sr_error err;
    torus_make(&torus);
    cr_assert(sr_obj_load(&room, "assets/room.obj", &err), "%s", err.message);
    sr_workspace *ws = sr_workspace_create();
    cr_assert_not_null(ws);
    for (size_t i = 0; i < sizeof draws / sizeof *draws; i++) {
        sr_draw_desc desc = { .mesh = draws[i].room ? &room : &torus, .shade = SR_SHADE_DEPTH };
        float aspect = 301.0f / (float)draws[i].height;
        if (draws[i].room)
            look(&desc, (vec3){ -8, 3, -8 }, (vec3){ 4, 1.5f, 6 }, 75.0f, aspect);
        else
            look_at_torus(&desc, aspect, false);
        drawn one, many;
        draw_with_threads(&desc, 301, draws[i].height, false, 1, SR_PATH_DIRECT, &one);
        cr_assert_gt(one.stats.fragments, 0, "draw %zu drew nothing: the comparison would prove nothing", i);
        desc.workspace = ws;
        draw_with_threads(&desc, 301, draws[i].height, false, draws[i].threads, SR_PATH_ROWS, &many);
        assert_same_drawing(&one, &many, draws[i].threads);
        sr_framebuffer_destroy(&many.fb);
        sr_framebuffer_destroy(&one.fb);
    }
    sr_workspace_destroy(ws);
    sr_mesh_free(&room);
    sr_mesh_free(&torus);
}

/* Every band's measured cost of the last draw: finite, not negative, some
 * above zero, kept for this mesh and height. */
static void assert_costs_measured(const sr_workspace *ws, const sr_mesh *mesh, int height)
{
    const sr_band_costs *c = &ws->band_costs;
    cr_assert_eq(c->height, height);
    cr_assert_eq(c->mesh, mesh);
    cr_assert_eq(c->slots, sr_mesh_triangle_slots(mesh));
    double sum = 0.0;
    for (int b = 0; b < sr_band_count(height); b++) {
        cr_assert(isfinite(c->per_triangle[b]) && c->per_triangle[b] >= 0.0, "band %d's cost is %g", b,
                  c->per_triangle[b]);
        sum += c->per_triangle[b];
    }
    cr_assert_gt(sum, 0.0, "no band's cost was measured");
}

/* Whatever costs the workspace holds (one band heavier than all others
 * together, NaN, infinite, negative, none), the row bands draw what one
 * thread draws, and measure finite costs again. */
Test(threads, row_bands_draw_alike_whatever_costs_the_workspace_holds)
{
    sr_mesh torus;
    torus_make(&torus);
    sr_draw_desc desc = { .mesh = &torus, .shade = SR_SHADE_DEPTH };
    look_at_torus(&desc, 301.0f / 173.0f, false);
    drawn one, many;
    draw_with_threads(&desc, 301, 173, false, 1, SR_PATH_DIRECT, &one);
    desc.workspace = sr_workspace_create();
    cr_assert_not_null(desc.workspace);
    draw_with_threads(&desc, 301, 173, false, 2, SR_PATH_ROWS, &many);
    assert_same_drawing(&one, &many, 2);
    sr_framebuffer_destroy(&many.fb);
    assert_costs_measured(desc.workspace, &torus, 173);
    static const double poisons[] = { 1e300, NAN, INFINITY, -1.0, 0.0 };
    for (size_t p = 0; p < sizeof poisons / sizeof *poisons; p++)
        for (int threads = 2; threads <= 16; threads *= 2) {
            sr_band_costs *c = &desc.workspace->band_costs;
            for (int b = 0; b < SR_ROW_BANDS; b++) /* the first poisoned alone: it outweighs the rest */
                c->per_triangle[b] = p == 0 && b > 0 ? 1.0 : poisons[p];
            draw_with_threads(&desc, 301, 173, false, threads, SR_PATH_ROWS, &many);
            assert_same_drawing(&one, &many, threads);
            sr_framebuffer_destroy(&many.fb);
            assert_costs_measured(desc.workspace, &torus, 173);
        }
    sr_workspace_destroy(desc.workspace);
    sr_framebuffer_destroy(&one.fb);
    sr_mesh_free(&torus);
}

/* The cost before a border of the split, with costs c. */
static double cost_before(const double *c, int border)
{
    double sum = 0.0;
    for (int b = 0; b < border; b++)
        sum += c[b];
    return sum;
}

static void assert_split(const double *cost, int bands, int threads, const int *want)
{
    int got[SR_MAX_THREADS + 1];
    sr_rows_split(cost, bands, threads, got);
    for (int t = 0; t <= threads; t++)
        cr_assert_eq(got[t], want[t], "%d bands over %d threads: thread %d starts at band %d, not %d", bands,
                     threads, t, got[t], want[t]);
}

/* A band goes to the thread whose share it brings nearer: the border lies
 * before a heavy band whose middle is past the share (a border at the
 * first band past the share would give the first thread 5 of 6), and
 * after it when its middle is not; a band heavier than a share can leave a
 * thread none; no cost, or one that is not a number, splits by bands. */
Test(threads, row_split_puts_each_border_nearest_its_share)
{
    assert_split((const double[]){ 1, 1, 1, 1, 1, 1, 1, 1 }, 8, 2, (const int[]){ 0, 4, 8 });
    assert_split((const double[]){ 1, 1, 3, 1 }, 4, 2, (const int[]){ 0, 2, 4 });
    assert_split((const double[]){ 1, 3, 1, 1 }, 4, 2, (const int[]){ 0, 2, 4 });
    assert_split((const double[]){ 4, 1, 1, 1, 1 }, 5, 2, (const int[]){ 0, 1, 5 });
    assert_split((const double[]){ 9, 1, 1 }, 3, 3, (const int[]){ 0, 0, 1, 3 }); /* thread 0: none */
    assert_split((const double[]){ 0, 0, 0, 0, 0, 0 }, 6, 3, (const int[]){ 0, 2, 4, 6 });
    assert_split((const double[]){ 1, NAN, 1, 1 }, 4, 2, (const int[]){ 0, 2, 4 });
    assert_split((const double[]){ 1, INFINITY, 1, 1 }, 4, 2, (const int[]){ 0, 2, 4 });
    assert_split((const double[]){ 5, 5 }, 2, 5, (const int[]){ 0, 0, 1, 1, 2, 2 }); /* more threads than bands */
}

/* Random costs, 1 to 64 threads: the split is a partition of the bands in
 * order, and each border lies where the cost before it is nearest its
 * share of all, among every border between its neighbours. */
Test(threads, row_split_borders_are_nearest_their_shares_on_random_costs)
{
    test_rng rng = { 14 };
    for (int trial = 0; trial < 2000; trial++) {
        int bands = 1 + rng_below(&rng, SR_ROW_BANDS), threads = 1 + rng_below(&rng, SR_MAX_THREADS);
        double cost[SR_ROW_BANDS], total = 0.0;
        for (int b = 0; b < bands; b++) {
            /* some empty bands, some heavy ones */
            cost[b] = rng_below(&rng, 4) == 0 ? 0.0 : rng_uniform(&rng, 0.0, 1.0) * (rng_below(&rng, 8) ? 1 : 50);
            total += cost[b];
        }
        int first[SR_MAX_THREADS + 1];
        sr_rows_split(cost, bands, threads, first);
        cr_assert_eq(first[0], 0);
        cr_assert_eq(first[threads], bands, "trial %d: the threads end at band %d of %d", trial, first[threads],
                     bands);
        for (int t = 1; t <= threads; t++) {
            cr_assert_leq(first[t - 1], first[t], "trial %d: thread %d starts before thread %d", trial, t, t - 1);
            if (t == threads || !(total > 0.0))
                continue;
            double share = total * t / threads, here = fabs(cost_before(cost, first[t]) - share);
            for (int border = first[t - 1]; border <= first[t + 1] && border <= bands; border++)
                cr_assert_leq(here, fabs(cost_before(cost, border) - share) + 1e-9 * total,
                              "trial %d: thread %d starts at band %d, %g from its share; band %d is nearer", trial, t,
                              first[t], here, border);
        }
    }
}

/* Destroying a workspace joins its sleeping workers, or has none to join
 * (a hang here times out; the sanitizer build checks nothing leaks). */
Test(threads, workspace_destroys_right_after_creation, .timeout = 60)
{
    sr_workspace *ws = sr_workspace_create();
    cr_assert_not_null(ws);
    sr_workspace_destroy(ws);
}

Test(threads, workspace_destroys_right_after_a_threaded_draw, .timeout = 60)
{
    sr_mesh torus;
    sr_error err;
    cr_assert(sr_shape_torus(&torus, 1.0f, 0.4f, 40, 20, &err), "%s", err.message);
    sr_draw_desc desc = { .mesh = &torus, .shade = SR_SHADE_ID, .workspace = sr_workspace_create() };
    cr_assert_not_null(desc.workspace);
    look_at_torus(&desc, 1.0f, false);
    drawn many;
    draw_with_threads(&desc, 64, 64, false, 5, SR_PATH_TILES, &many);
    sr_workspace_destroy(desc.workspace);
    cr_assert_gt(many.stats.fragments, 0);
    sr_framebuffer_destroy(&many.fb);
    sr_mesh_free(&torus);
}

Test(threads, overlapping_textured_quads_match_one_thread)
{
    sr_mesh quads;
    sr_error err;
    uint32_t texels[4] = { 0xFF0000, 0x00FF00, 0x0000FF, 0xFFFFFF };
    sr_texture tex = { .width = 2, .height = 2, .texels = texels };
    cr_assert(sr_shape_quads(&quads, 8, 1.5f, 8.0f, -0.5f, &err), "%s", err.message);
    sr_draw_desc desc = { .mesh = &quads, .shade = SR_SHADE_TEXTURE, .texture = &tex };
    look(&desc, (vec3){ 0.3f, 0.2f, -1 }, (vec3){ 0, 0, 5 }, 60.0f, 1.0f);
    assert_same_for_all_thread_counts(&desc, 150, 150, false);
    sr_mesh_free(&quads);
}

Test(threads, reversed_z_matches_one_thread)
{
    sr_mesh torus;
    sr_error err;
    cr_assert(sr_shape_torus(&torus, 1.0f, 0.4f, 80, 40, &err), "%s", err.message);
    sr_draw_desc desc = { .mesh = &torus, .shade = SR_SHADE_DEPTH };
    look_reversed(&desc, (vec3){ 0, 0.3f, -1.2f }, (vec3){ 0, 0, 0 }, 90.0f, 1.5f, true);
    assert_same_for_all_thread_counts(&desc, 270, 180, true);
    sr_mesh_free(&torus);
}

typedef struct observed {
    uint64_t count;
    uint32_t last_id;
    bool in_order;
} observed;

static void observe(void *user, const sr_screen_vertex tri[3], bool clipped, uint32_t id)
{
    (void)tri, (void)clipped;
    observed *o = user;
    o->in_order = o->in_order && (o->count == 0 || id >= o->last_id);
    o->last_id = id;
    o->count++;
}

/* A draw with an observer runs on one thread whatever it asks for, so the
 * observer sees each drawn fan triangle once, in submission order. */
Test(threads, observer_sees_every_drawn_triangle_once_in_order)
{
    sr_mesh torus;
    sr_error err;
    cr_assert(sr_shape_torus(&torus, 1.0f, 0.4f, 24, 12, &err), "%s", err.message);
    observed seen = { .in_order = true };
    sr_draw_desc desc = { .mesh = &torus, .shade = SR_SHADE_ID,
                          .study = &(sr_draw_study){ .observer = observe, .observer_user = &seen } };
    look_at_torus(&desc, 1.0f, false);
    drawn out;
    draw_with_threads(&desc, 64, 64, false, 4, SR_PATH_TILES, &out);
    cr_assert_gt(out.stats.drawn, 0);
    cr_assert_eq(seen.count, out.stats.drawn);
    cr_assert(seen.in_order);
    sr_framebuffer_destroy(&out.fb);
    sr_mesh_free(&torus);
}

typedef struct varyings_seen {
    uint64_t triangles, clipped;
    unsigned nonzero; /* bit k: some vertex's var_w[k] was not 0 */
} varyings_seen;

static void observe_varyings(void *user, const sr_screen_vertex tri[3], bool clipped, uint32_t id)
{
    (void)id;
    varyings_seen *v = user;
    v->triangles++;
    v->clipped += clipped;
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < SR_MAX_VARYINGS; k++)
            v->nonzero |= (unsigned)(tri[i].var_w[k] != 0.0f) << k;
}

/* The vertex phase keeps only the layout's varyings (docs/performance.md,
 * "The vertex phase"); the observer still gets whole
 * vertices: each of the layout's varyings set somewhere (a normal's three
 * components), those past it 0 everywhere, also where the workspace's last
 * draw wrote a lambert normal there, and on clipped triangles. */
Test(threads, observer_sees_the_layouts_varyings_and_zeros_past_them)
{
    sr_mesh torus;
    sr_error err;
    cr_assert(sr_shape_torus(&torus, 1.0f, 0.4f, 24, 12, &err), "%s", err.message);
    sr_workspace *ws = sr_workspace_create();
    cr_assert_not_null(ws);
    const struct {
        sr_shade shade;
        int layout_count;
    } draws[] = { { SR_SHADE_LAMBERT, 3 }, { SR_SHADE_DEPTH, 0 }, { SR_SHADE_ID, 0 }, { SR_SHADE_NORMAL, 3 } };
    for (size_t d = 0; d < sizeof draws / sizeof *draws; d++) {
        varyings_seen seen = { 0 };
        sr_draw_desc desc = { .mesh = &torus, .shade = draws[d].shade, .workspace = ws, .cull = SR_CULL_NONE,
                              .study = &(sr_draw_study){ .observer = observe_varyings, .observer_user = &seen } };
        look(&desc, (vec3){ 0, 0.2f, -1.0f }, (vec3){ 0, 0, 0 }, 90.0f, 1.0f); /* inside the ring's far side */
        sr_framebuffer fb;
        cr_assert(sr_framebuffer_create(&fb, 64, 64, &err), "%s", err.message);
        sr_framebuffer_clear(&fb, 0);
        sr_stats stats = { 0 };
        cr_assert(sr_draw(&fb, &desc, &stats, &err), "%s", err.message);
        cr_assert_gt(seen.clipped, 0, "shade %d: no clipped triangle, the test would prove less", draws[d].shade);
        cr_assert_eq(seen.triangles, stats.drawn);
        cr_assert_eq(seen.nonzero, (1u << draws[d].layout_count) - 1u,
                     "shade %d: varyings seen other than 0 (bit k: var_w[k]): %#x", draws[d].shade, seen.nonzero);
        sr_framebuffer_destroy(&fb);
    }
    sr_workspace_destroy(ws);
    sr_mesh_free(&torus);
}

/* desc.clear into buffers of the caller's own, exactly width * height (no
 * slack after the last row), holding another picture nearer than most of
 * the scene: on each threaded path, at one thread and at `threads`, what
 * the direct path drew after sr_framebuffer_clear (want), bit for bit. */
static void assert_cleared_by_the_draw(const sr_draw_desc *desc, const drawn *want, int threads)
{
    size_t n = (size_t)want->fb.width * want->fb.height;
    const int counts[] = { 1, threads };
    for (size_t p = 0; p < THREADED_PATHS; p++)
        for (size_t c = 0; c < sizeof counts / sizeof *counts; c++) {
            drawn cleared = { .fb = { .width = want->fb.width, .height = want->fb.height,
                                      .reversed_z = want->fb.reversed_z, .color = malloc(n * sizeof(uint32_t)),
                                      .depth = malloc(n * sizeof(float)) } };
            cr_assert(cleared.fb.color && cleared.fb.depth);
            for (size_t i = 0; i < n; i++) {
                cleared.fb.color[i] = 0xABCDEF;
                cleared.fb.depth[i] = 0.5f;
            }
            sr_draw_desc d = *desc;
            d.clear = true;
            d.threads = counts[c];
            d.study = &(sr_draw_study){ .path = threaded_paths[p] };
            sr_error err;
            cr_assert(sr_draw(&cleared.fb, &d, &cleared.stats, &err), "%s", err.message);
            assert_same_drawing(want, &cleared, counts[c]);
            free(cleared.fb.color);
            free(cleared.fb.depth);
        }
}

/* Tiles are strips of SR_TILE_ROWS(width) rows: fewer than SR_TILE_ROWS_MAX
 * past 2048 pixels wide, 4 at the widest framebuffer; one pixel wide or one
 * row tall, a single column or a single partial strip. Each size draws on
 * the tiles what it draws on the direct path, at every thread count, into
 * buffers of its own too, cleared by the draw. */
Test(threads, strips_of_every_width_match_one_thread)
{
    sr_mesh room;
    sr_error err;
    cr_assert(sr_obj_load(&room, "assets/room.obj", &err), "%s", err.message);
    static const int sizes[][2] = { { SR_MAX_FRAMEBUFFER_SIDE, 9 }, { 3001, 45 }, { 2049, 33 }, { 1, 70 }, { 70, 1 } };
    for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++) {
        int w = sizes[i][0], h = sizes[i][1];
        sr_draw_desc desc = { .mesh = &room, .shade = SR_SHADE_ID, .clear_color = 0x123456 };
        look(&desc, (vec3){ -8, 3, -8 }, (vec3){ 4, 1.5f, 6 }, 75.0f, (float)w / (float)h);
        assert_same_for_all_thread_counts(&desc, w, h, false);
        drawn direct;
        draw_with_threads(&desc, w, h, false, 1, SR_PATH_DIRECT, &direct);
        assert_cleared_by_the_draw(&desc, &direct, 3);
        sr_framebuffer_destroy(&direct.fb);
    }
    sr_mesh_free(&room);
}

/* desc.clear into a framebuffer holding another picture: the same pixels,
 * depths and counts as sr_framebuffer_clear then the direct path's draw, on
 * the tiles (each tile cleared by the thread that draws it) and drawing
 * directly first (the first thread clears before it draws), at one thread
 * and at several, in both depth conventions. */
Test(threads, clear_inside_the_draw_matches_clear_before_it)
{
    sr_mesh torus;
    torus_make(&torus);
    for (int reversed = 0; reversed < 2; reversed++) {
        sr_draw_desc desc = { .mesh = &torus, .shade = SR_SHADE_LAMBERT, .clear_color = 0x123456 };
        look_at_torus(&desc, 301.0f / 173.0f, reversed);
        drawn before;
        draw_with_threads(&desc, 301, 173, reversed, 1, SR_PATH_DIRECT, &before);
        assert_cleared_by_the_draw(&desc, &before, 4);
        sr_framebuffer_destroy(&before.fb);
    }
    sr_mesh_free(&torus);
}

/* sr_draw_study.times: every draw adds its phases (never clears them); the
 * direct path has no tile phase, the tiles have one; the draw's whole time
 * holds its phases. Which is faster is the bench's business, not a test's. */
Test(threads, draw_times_add_up_per_phase)
{
    sr_mesh torus;
    torus_make(&torus);
    for (int threads = 1; threads <= 2; threads++) {
        sr_draw_path path = threads == 1 ? SR_PATH_DIRECT : SR_PATH_TILES;
        sr_draw_times times = { { 0 } };
        sr_draw_desc desc = { .mesh = &torus, .threads = threads, .study = &(sr_draw_study){ .times = &times } };
        look_at_torus(&desc, 301.0f / 173.0f, false);
        drawn out;
        draw_with_threads(&desc, 301, 173, false, threads, path, &out);
        sr_draw_times once = times;
        sr_framebuffer_destroy(&out.fb);
        draw_with_threads(&desc, 301, 173, false, threads, path, &out);
        sr_framebuffer_destroy(&out.fb);
        cr_assert_gt(once.vertex.wall, 0.0);
        cr_assert_gt(once.primitives.cpu, 0.0);
        cr_assert(path == SR_PATH_DIRECT ? once.raster.wall == 0.0 : once.raster.wall > 0.0, "tile phase on %d threads",
                  threads);
        cr_assert_geq(once.total, once.vertex.wall + once.primitives.wall + once.raster.wall);
        cr_assert_gt(times.total, once.total, "a second draw adds to the times");
    }
    sr_mesh_free(&torus);
}

/* The cost estimate on one thread: a large framebuffer and few triangles
 * (a torus of 2880 slots at 1280x720) take the tiles, a small framebuffer
 * the direct path; both draw what the direct path draws. */
Test(threads, one_thread_takes_the_tiles_for_few_triangles_on_many_pixels)
{
    sr_mesh torus;
    sr_error err;
    cr_assert(sr_shape_torus(&torus, 1.0f, 0.4f, 48, 30, &err), "%s", err.message);
    static const int sizes[][2] = { { 1280, 720 }, { 320, 180 } };
    for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++) {
        int w = sizes[i][0], h = sizes[i][1];
        sr_draw_times times = { { 0 } };
        sr_draw_desc desc = { .mesh = &torus, .shade = SR_SHADE_LAMBERT,
                              .study = &(sr_draw_study){ .times = &times } };
        look_at_torus(&desc, (float)w / (float)h, false);
        drawn direct, by_cost = { .fb = { 0 } };
        draw_with_threads(&desc, w, h, false, 1, SR_PATH_DIRECT, &direct);
        cr_assert(sr_framebuffer_create(&by_cost.fb, w, h, &err), "%s", err.message);
        sr_framebuffer_clear(&by_cost.fb, 0x123456);
        times = (sr_draw_times){ { 0 } };
        cr_assert(sr_draw(&by_cost.fb, &desc, &by_cost.stats, &err), "%s", err.message);
        cr_assert_eq(times.raster.wall > 0.0, i == 0, "%dx%d: tiles taken %d", w, h, times.raster.wall > 0.0);
        cr_assert_eq(times.path, i == 0 ? SR_PATH_TILES : SR_PATH_DIRECT, "%dx%d: path %d", w, h, (int)times.path);
        assert_same_drawing(&direct, &by_cost, 1);
        cr_assert_gt(direct.stats.fragments, 0);
        sr_framebuffer_destroy(&direct.fb);
        sr_framebuffer_destroy(&by_cost.fb);
    }
    sr_mesh_free(&torus);
}
