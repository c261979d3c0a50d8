/* The framebuffer's ids plane (sr_framebuffer.ids): every per-pixel loop
 * (the scalar loop, the SSE2, AVX2 and AVX-512 kernels, the tiny queue),
 * on every path and thread count, writes there the id + 1 an SR_SHADE_ID
 * draw writes to color, while color and depth stay bit for bit what a draw
 * without the plane gives; and sr_pinhole_resolve from the plane of a
 * shaded draw, on any number of threads, gives bit for bit what it gives
 * from an id draw: one draw does the work of two. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/shapes.h"
#include "softrast_private.h"

TestSuite(ids_plane);

/* A way to draw: the per-pixel loop, the path and the threads. */
typedef struct way {
    sr_simd simd;
    sr_draw_path path;
    int threads;
} way;

static const way WAYS[] = {
    { SR_SIMD_SCALAR, SR_PATH_DIRECT, 1 }, { SR_SIMD_SSE2, SR_PATH_DIRECT, 1 }, { SR_SIMD_AVX2, SR_PATH_DIRECT, 1 },
    { SR_SIMD_AVX512, SR_PATH_DIRECT, 1 }, { SR_SIMD_SCALAR, SR_PATH_TILES, 3 }, { SR_SIMD_SSE2, SR_PATH_TILES, 2 },
    { SR_SIMD_AUTO, SR_PATH_TILES, 4 },    { SR_SIMD_SCALAR, SR_PATH_ROWS, 2 },  { SR_SIMD_AVX2, SR_PATH_ROWS, 3 },
    { SR_SIMD_AUTO, SR_PATH_ROWS, 7 },
};
#define WAY_COUNT (sizeof WAYS / sizeof *WAYS)

#define GARBAGE 0xDEADBEEFu

typedef struct drawn {
    sr_framebuffer fb;
    uint64_t simd_draws;
} drawn;

/* desc drawn the way w into a new framebuffer cleared to GARBAGE's colour
 * (and ids, where `ids`) by the draw or, for `clear_first`, by
 * sr_framebuffer_clear before it. */
static void draw_way(const sr_draw_desc *base, int width, int height, bool reversed, way w, bool ids,
                     bool clear_first, drawn *out)
{
    sr_error err = { "" };
    cr_assert(sr_framebuffer_create(&out->fb, width, height, &err), "%s", err.message);
    cr_assert(!ids || sr_framebuffer_create_ids(&out->fb, &err), "%s", err.message);
    out->fb.reversed_z = reversed;
    if (ids)
        for (size_t i = 0; i < (size_t)width * (size_t)height; i++)
            out->fb.ids[i] = GARBAGE;
    sr_draw_study study = { .simd = w.simd, .path = w.path };
    sr_draw_desc desc = *base;
    desc.study = &study;
    desc.threads = w.threads;
    desc.workspace = sr_workspace_create();
    desc.clear = !clear_first;
    desc.clear_color = GARBAGE & 0xFFFFFF;
    if (clear_first)
        sr_framebuffer_clear(&out->fb, GARBAGE & 0xFFFFFF);
    cr_assert(sr_draw(&out->fb, &desc, NULL, &err), "%s", err.message);
    out->simd_draws = sr_workspace_simd_draws(desc.workspace);
    sr_workspace_destroy(desc.workspace);
}

static void assert_same_plane(const void *a, const void *b, size_t n, const char *plane, sr_shade mode, way w)
{
    cr_assert_eq(memcmp(a, b, n * 4), 0, "%s differs: mode %d, simd %d, path %d, %d threads", plane, mode, w.simd,
                 w.path, w.threads);
}

/* desc in each mode with an ids plane, every way: color and depth as
 * without the plane, ids as the colors of an id draw (0 where nothing). */
static void assert_one_draw_is_two(const sr_draw_desc *base, const sr_shade *modes, int mode_count, int width,
                                   int height, bool reversed)
{
    size_t n = (size_t)width * (size_t)height;
    sr_draw_desc id_desc = *base;
    id_desc.shade = SR_SHADE_ID;
    drawn ids_ref;
    draw_way(&id_desc, width, height, reversed, WAYS[0], false, false, &ids_ref);
    uint32_t *want_ids = malloc(n * sizeof *want_ids);
    size_t drawn_pixels = 0;
    for (size_t i = 0; i < n; i++) {
        bool hit = ids_ref.fb.depth[i] != sr_framebuffer_depth_clear(&ids_ref.fb);
        want_ids[i] = hit ? ids_ref.fb.color[i] : 0;
        drawn_pixels += hit;
    }
    cr_assert_gt(drawn_pixels, n / 8, "the scene covers too little to prove anything");
    uint64_t simd_draws[WAY_COUNT] = { 0 };
    for (int m = 0; m < mode_count; m++) {
        sr_draw_desc desc = *base;
        desc.shade = modes[m];
        drawn plain;
        draw_way(&desc, width, height, reversed, WAYS[0], false, false, &plain);
        for (size_t k = 0; k < WAY_COUNT; k++) {
            drawn one;
            draw_way(&desc, width, height, reversed, WAYS[k], true, k % 2, &one);
            assert_same_plane(plain.fb.color, one.fb.color, n, "color", modes[m], WAYS[k]);
            assert_same_plane(plain.fb.depth, one.fb.depth, n, "depth", modes[m], WAYS[k]);
            assert_same_plane(want_ids, one.fb.ids, n, "ids", modes[m], WAYS[k]);
            simd_draws[k] += one.simd_draws;
            sr_framebuffer_destroy(&one.fb);
        }
        sr_framebuffer_destroy(&plain.fb);
    }
    /* The SIMD loops did draw triangles (else the scalar loop was tested
     * again); points and lines have one loop, whatever the way. */
    bool triangles = base->mesh->topology == SR_TRIANGLE_LIST || base->mesh->topology == SR_TRIANGLE_STRIP;
    for (size_t k = 0; triangles && k < WAY_COUNT; k++)
        cr_assert(WAYS[k].simd == SR_SIMD_SCALAR || simd_draws[k] > 0, "no SIMD draw the way %zu", k);
    free(want_ids);
    sr_framebuffer_destroy(&ids_ref.fb);
}

static void look(sr_draw_desc *desc, const float eye_target[6], float aspect, bool reversed)
{
    sr_camera cam = sr_camera_default();
    cam.reversed_z = reversed;
    glm_vec3_copy((float *)eye_target, cam.eye);
    glm_vec3_copy((float *)eye_target + 3, cam.target);
    cam.fov_deg = 70.0f;
    sr_camera_view(&cam, desc->view);
    sr_camera_projection(&cam, aspect, desc->projection);
}

/* A 4x4 texture of distinct texels. */
static const sr_texture *texture_4x4(void)
{
    static uint32_t texels[16];
    static sr_texture tex = { 4, 4, texels };
    for (uint32_t i = 0; i < 16; i++)
        texels[i] = 0x10305u * (i + 1);
    return &tex;
}

static const sr_shade ALL_MODES[] = { SR_SHADE_LAMBERT, SR_SHADE_ID,      SR_SHADE_COLOR,
                                     SR_SHADE_NORMAL,  SR_SHADE_TEXTURE, SR_SHADE_DEPTH };
#define ALL_MODE_COUNT ((int)(sizeof ALL_MODES / sizeof *ALL_MODES))

/* A torus of `around` x `across` segments with normals, uvs and colours
 * (the colour shading's). */
static void colored_torus(sr_mesh *torus, uint32_t around, uint32_t across)
{
    sr_error err = { "" };
    cr_assert(sr_shape_torus(torus, 1.0f, 0.4f, around, across, &err), "%s", err.message);
    torus->colors = malloc(torus->vertex_count * sizeof *torus->colors);
    for (uint32_t v = 0; v < torus->vertex_count; v++)
        for (int k = 0; k < 3; k++)
            torus->colors[v][k] = 0.5f + 0.35f * torus->positions[v][k];
}

/* A dense torus, many of its triangles tiny (the tiny queue's), in every
 * mode, with the standard and the reversed depth test. */
Test(ids_plane, every_loop_path_and_thread_count_writes_the_id_draws_ids_on_a_dense_torus)
{
    sr_mesh torus;
    colored_torus(&torus, 120, 60);
    for (int reversed = 0; reversed < 2; reversed++) {
        sr_draw_desc desc = { .mesh = &torus, .texture = texture_4x4() };
        look(&desc, (const float[6]){ 0, 1.1f, -1.9f, 0, 0, 0 }, 160.0f / 120.0f, reversed);
        assert_one_draw_is_two(&desc, ALL_MODES, ALL_MODE_COUNT, 160, 120, reversed);
    }
    sr_mesh_free(&torus);
}

/* The torus's corners as points 1 and 2 pixels square, and its triangles'
 * edges as lines and a strip 1 and 2 pixels wide, overlapping each other:
 * the ids plane holds the id + 1 of the point or line each pixel shows,
 * as an id draw's colour, and colour and depth are as without the plane. */
Test(ids_plane, points_and_lines_write_the_id_draws_ids)
{
    sr_mesh torus;
    colored_torus(&torus, 120, 60);
    static const sr_topology topologies[] = { SR_POINT_LIST, SR_LINE_LIST, SR_LINE_STRIP };
    for (size_t t = 0; t < 2 * sizeof topologies / sizeof *topologies; t++)
        for (int reversed = 0; reversed < 2; reversed++) {
            torus.topology = topologies[t / 2];
            const float size = 1.0f + (float)(t % 2);
            sr_draw_desc desc = { .mesh = &torus, .texture = texture_4x4(), .point_size = size, .line_width = size };
            look(&desc, (const float[6]){ 0, 1.1f, -1.9f, 0, 0, 0 }, 160.0f / 120.0f, reversed);
            assert_one_draw_is_two(&desc, ALL_MODES, ALL_MODE_COUNT, 160, 120, reversed);
        }
    sr_mesh_free(&torus);
}

/* The room: large triangles (the span kernels' rows), walls behind walls,
 * lambert with and without its texture. */
Test(ids_plane, every_loop_path_and_thread_count_writes_the_id_draws_ids_in_the_room)
{
    sr_mesh room;
    sr_error err = { "" };
    cr_assert(sr_obj_load(&room, "assets/room.obj", &err), "%s", err.message);
    static const sr_shade modes[] = { SR_SHADE_LAMBERT, SR_SHADE_DEPTH };
    sr_draw_desc desc = { .mesh = &room };
    look(&desc, (const float[6]){ -8, 3, -8, 4, 1.5f, 6 }, 200.0f / 130.0f, false);
    assert_one_draw_is_two(&desc, modes, 2, 200, 130, false);
    desc.texture = texture_4x4();
    assert_one_draw_is_two(&desc, modes, 1, 200, 130, false);
    sr_mesh_free(&room);
}

Test(ids_plane, clearing_zeroes_ids_and_a_second_create_keeps_the_plane)
{
    sr_framebuffer fb;
    sr_error err = { "" };
    cr_assert(sr_framebuffer_create(&fb, 5, 3, &err), "%s", err.message);
    cr_assert_null(fb.ids, "sr_framebuffer_create makes no ids plane");
    cr_assert(sr_framebuffer_create_ids(&fb, &err), "%s", err.message);
    uint32_t *plane = fb.ids;
    for (int i = 0; i < 15; i++)
        cr_assert_eq(fb.ids[i], 0u, "a new ids plane is zeroed");
    for (int i = 0; i < 15; i++)
        fb.ids[i] = GARBAGE;
    cr_assert(sr_framebuffer_create_ids(&fb, &err), "%s", err.message);
    cr_assert_eq(fb.ids, plane, "a second call keeps the plane");
    cr_assert_eq(fb.ids[7], GARBAGE, "and what it holds");
    sr_framebuffer_clear(&fb, 0x123456);
    for (int i = 0; i < 15; i++)
        cr_assert_eq(fb.ids[i], 0u, "pixel %d: clearing sets ids to 0", i);
    sr_framebuffer_destroy(&fb);
    cr_assert_null(fb.ids);
}

/* ---- the pinhole resolve ---- */

typedef struct resolved {
    float depth[2][64 * 41], range[2][64 * 41], normals[2][3 * 64 * 41];
    uint32_t face_ids[2][64 * 41], part_ids[2][64 * 41];
} resolved;

static sr_pinhole_outputs outputs_of(resolved *r, int k, bool interpolated, int threads)
{
    return (sr_pinhole_outputs){ .depth = r->depth[k], .range = r->range[k], .face_ids = r->face_ids[k],
                                 .part_ids = r->part_ids[k], .normals = r->normals[k],
                                 .interpolated_normals = interpolated, .invalid = NAN, .threads = threads };
}

static void assert_same_outputs(const resolved *r, int a, int b, const char *what)
{
    size_t n = 64 * 41;
    cr_assert_eq(memcmp(r->depth[a], r->depth[b], n * 4), 0, "depth differs: %s", what);
    cr_assert_eq(memcmp(r->range[a], r->range[b], n * 4), 0, "range differs: %s", what);
    cr_assert_eq(memcmp(r->face_ids[a], r->face_ids[b], n * 4), 0, "face ids differ: %s", what);
    cr_assert_eq(memcmp(r->part_ids[a], r->part_ids[b], n * 4), 0, "part ids differ: %s", what);
    cr_assert_eq(memcmp(r->normals[a], r->normals[b], 3 * n * 4), 0, "normals differ: %s", what);
}

/* The room through a pinhole camera at 64x41: the outputs resolved from a
 * lambert draw's ids plane on 1, 2, 3, 7, 41 and 100 threads (more than
 * rows) are those resolved from an id draw on one, bit for bit, both
 * normal kinds. */
Test(ids_plane, the_resolve_of_a_shaded_draws_ids_is_the_id_draws_on_any_threads)
{
    sr_mesh room;
    sr_error err = { "" };
    cr_assert(sr_obj_load(&room, "assets/room.obj", &err), "%s", err.message);
    cr_assert(sr_mesh_compute_normals(&room, &err), "%s", err.message);
    sr_pinhole cam = { .fx = 40.0, .fy = 37.0, .cx = 30.5, .cy = 21.25 };
    static const double c2w[4][4] = { { 0.8, 0, 0.6, -6 }, { 0, 1, 0, 2 }, { -0.6, 0, 0.8, -6 }, { 0, 0, 0, 1 } };
    cr_assert(sr_pinhole_pose_from_c2w(c2w, cam.w2c, &err), "%s", err.message);
    sr_pinhole_fit_clip(&cam, &room);
    sr_framebuffer id_fb, shaded_fb;
    cr_assert(sr_framebuffer_create(&id_fb, 64, 41, &err) && sr_framebuffer_create(&shaded_fb, 64, 41, &err) &&
                  sr_framebuffer_create_ids(&shaded_fb, &err),
              "%s", err.message);
    sr_draw_desc id_desc = { .mesh = &room, .shade = SR_SHADE_ID, .cull = SR_CULL_NONE, .clear = true };
    sr_pinhole_matrices(&cam, &room, &id_fb, &id_desc);
    sr_draw_desc shaded_desc = id_desc;
    shaded_desc.shade = SR_SHADE_LAMBERT;
    sr_pinhole_matrices(&cam, &room, &shaded_fb, &shaded_desc);
    cr_assert(sr_draw(&id_fb, &id_desc, NULL, &err) && sr_draw(&shaded_fb, &shaded_desc, NULL, &err), "%s",
              err.message);
    static resolved r;
    static const int threads[] = { 1, 2, 3, 7, 41, 100 };
    for (int interpolated = 0; interpolated < 2; interpolated++) {
        sr_pinhole_outputs want = outputs_of(&r, 0, interpolated, 1);
        cr_assert(sr_pinhole_resolve(&cam, &room, &id_fb, &want, &err), "%s", err.message);
        size_t seen = 0;
        for (int i = 0; i < 64 * 41; i++)
            seen += r.face_ids[0][i] != 0;
        cr_assert_gt(seen, 64 * 41 / 2, "the camera sees too little of the room to prove anything");
        for (size_t t = 0; t < sizeof threads / sizeof *threads; t++) {
            sr_pinhole_outputs got = outputs_of(&r, 1, interpolated, threads[t]);
            cr_assert(sr_pinhole_resolve(&cam, &room, &shaded_fb, &got, &err), "%s", err.message);
            char what[64];
            snprintf(what, sizeof what, "%d threads, interpolated normals %d", threads[t], interpolated);
            assert_same_outputs(&r, 0, 1, what);
        }
    }
    sr_framebuffer_destroy(&id_fb);
    sr_framebuffer_destroy(&shaded_fb);
    sr_mesh_free(&room);
}

/* The ids plane of a draw of points or lines names points or lines, and
 * the resolve reads them so (not as triangles): each drawn pixel's depth
 * is its point's camera z, or lies between its line's ends' z. */
Test(ids_plane, the_resolve_reads_points_and_lines_as_they_were_drawn)
{
    sr_mesh torus;
    sr_error err = { "" };
    cr_assert(sr_shape_torus(&torus, 1.0f, 0.4f, 12, 8, &err), "%s", err.message);
    sr_pinhole cam = { .fx = 40.0, .fy = 40.0, .cx = 15.5, .cy = 11.5 };
    static const double c2w[4][4] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, -4 }, { 0, 0, 0, 1 } };
    cr_assert(sr_pinhole_pose_from_c2w(c2w, cam.w2c, &err), "%s", err.message);
    sr_pinhole_fit_clip(&cam, &torus);
    sr_framebuffer fb;
    cr_assert(sr_framebuffer_create(&fb, 32, 24, &err) && sr_framebuffer_create_ids(&fb, &err), "%s", err.message);
    static float depth[32 * 24];
    static const sr_topology topologies[] = { SR_POINT_LIST, SR_LINE_LIST, SR_LINE_STRIP };
    for (size_t t = 0; t < sizeof topologies / sizeof *topologies; t++) {
        torus.topology = topologies[t];
        sr_draw_desc desc = { .mesh = &torus, .shade = SR_SHADE_DEPTH, .clear = true };
        sr_pinhole_matrices(&cam, &torus, &fb, &desc);
        cr_assert(sr_draw(&fb, &desc, NULL, &err), "%s", err.message);
        cr_assert(sr_pinhole_resolve(&cam, &torus, &fb, &(sr_pinhole_outputs){ .depth = depth }, &err), "%s",
                  err.message);
        int shown = 0;
        for (int at = 0; at < 32 * 24; at++) {
            if (!fb.ids[at])
                continue;
            shown++;
            uint32_t k = fb.ids[at] - 1, first = torus.topology == SR_LINE_LIST ? 2 * k : k;
            uint32_t last = torus.topology == SR_POINT_LIST ? first : first + 1;
            /* camera z = file z + 4, the file's z the torus's own (made in code, not negated) */
            float z0 = torus.positions[torus.indices[first]][2] + 4.0f;
            float z1 = torus.positions[torus.indices[last]][2] + 4.0f;
            cr_assert(depth[at] >= fminf(z0, z1) && depth[at] <= fmaxf(z0, z1), "topology %zu, pixel %d: %.9g not in %g..%g",
                      t, at, depth[at], z0, z1);
        }
        cr_assert(shown > 20, "topology %zu: %d pixels drawn", t, shown);
    }
    sr_framebuffer_destroy(&fb);
    sr_mesh_free(&torus);
}
