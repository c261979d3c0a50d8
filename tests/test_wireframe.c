/* render --lines' hidden-line frame (app/hidden_lines.c) and the edges it
 * draws (app/wireframe.c). On every test mesh: each line pixel lies on an
 * edge of a face that the exact truth (studies/truth.h) sees at it or next
 * to it; none is a hidden line, by an oracle that knows the mesh and the
 * camera alone (line_oracle.h); the lines that show are drawn; the pixels
 * are the same on every thread count, path and SIMD level. On small
 * scenes: a face just behind another shows none of its edges, and a face
 * at a grazing angle all of its own. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "app/hidden_lines.h"
#include "app/scene_setup.h"
#include "line_oracle.h"
#include "pipeline/02_assemble.h"
#include "scene_helpers.h"
#include "studies/report_truth.h"
#include "studies/truth.h"
#include "studies/truth_outline.h"

#define SIDE_W 320
#define SIDE_H 240
#define PIXELS (SIDE_W * SIDE_H)

/* A test mesh and how it is looked at: framed as render frames it, or
 * from eye to target. */
typedef struct view {
    const char *path;
    float rotate_y;
    sr_cull cull;
    bool placed;
    double eye[3], target[3];
    float fov;
} view;

static const view VIEWS[] = {
    { "assets/cube.obj", 30.0f, SR_CULL_BACK, false, { 0 }, { 0 }, 0 },
    { "assets/sphere.obj", 0.0f, SR_CULL_BACK, false, { 0 }, { 0 }, 0 },
    { "assets/torus.obj", 20.0f, SR_CULL_BACK, false, { 0 }, { 0 }, 0 },
    { "assets/quad3x3.obj", 10.0f, SR_CULL_NONE, false, { 0 }, { 0 }, 0 },
    /* The room from outside, its near wall culled: framed as render
     * frames it (three-quarter), and from the front. */
    { "assets/room.obj", 0.0f, SR_CULL_BACK, false, { 0 }, { 0 }, 0 },
    { "assets/room.obj", 0.0f, SR_CULL_BACK, true, { 0, 3, -30.36 }, { 0, 3, 0 }, 60.0f },
    /* The viewer's first frame (app/view/view.c): pillars whose tops lie
     * in the ceiling's plane, walls and floor met at grazing angles. */
    { "assets/room.obj", 0.0f, SR_CULL_BACK, true, { -8, 3, -8 }, { 4, 1.5, 6 }, 75.0f },
    /* Low along a wall, every face of it at a grazing angle. */
    { "assets/room.obj", 0.0f, SR_CULL_BACK, true, { -9.5, 0.3, -9.5 }, { -9.5, 0.6, 9 }, 60.0f },
    /* Just under the ceiling, and at the floor's height: the far wall's
     * lines behind the pillars, the pillars' edges on snapping's ties. */
    { "assets/room.obj", 0.0f, SR_CULL_BACK, true, { 0, 3.9, -9 }, { 0, 3.8, 9 }, 90.0f },
    { "assets/room.obj", 0.0f, SR_CULL_BACK, true, { -9, 0.05, 0 }, { 9, 0.1, 1 }, 60.0f },
    /* Both faces drawn: the pillars' tops fight the ceiling for depth. */
    { "assets/room.obj", 0.0f, SR_CULL_NONE, true, { -8, 3, -8 }, { 4, 1.5, 6 }, 75.0f },
    /* The torus nearly edge-on, its far side behind its near side; and
     * from above with its inside faces drawn. */
    { "assets/torus.obj", 0.0f, SR_CULL_BACK, true, { 0, 0.3, -3 }, { 0, 0, 0 }, 60.0f },
    { "assets/torus.obj", 0.0f, SR_CULL_NONE, true, { 0.5, 1.2, -2 }, { 0, 0, 0 }, 60.0f },
};
#define VIEW_COUNT (sizeof VIEWS / sizeof VIEWS[0])

/* A view loaded, its camera, its wireframe, and the hidden-line frame in
 * id shading (line slot + 1 per pixel) on one thread. */
typedef struct framed {
    sr_scene scene;
    sr_draw_desc desc;
    sr_draw_study study;
    sr_hidden_lines lines;
    uint32_t frame[PIXELS];
} framed;

/* The hidden-line frame of f on `threads` threads, path and loop. */
static void draw_frame(framed *f, int threads, sr_draw_path path, sr_simd simd, uint32_t *out)
{
    sr_error err = { "" };
    sr_stats fill, drawn;
    double ms;
    f->desc.threads = threads;
    f->study.simd = simd;
    f->study.path = path;
    cr_assert(sr_hidden_lines_frame(&f->lines, &f->scene.fb, &f->desc, &fill, &drawn, &ms, &err), "%s", err.message);
    cr_assert_eq(drawn.lines, f->lines.wire.edges.index_count / 2);
    memcpy(out, f->scene.fb.color, PIXELS * sizeof *out);
}

static framed *frame_view(const view *v)
{
    static framed f;
    sr_scene_setup setup;
    sr_error err = { "" };
    sr_scene_setup_defaults(&setup);
    setup.mesh_path = v->path;
    setup.size[0] = SIDE_W;
    setup.size[1] = SIDE_H;
    setup.rotate_y = v->rotate_y;
    setup.cull = v->cull;
    setup.shade = SR_SHADE_ID;
    if (v->placed) {
        memcpy(setup.eye, v->eye, sizeof setup.eye);
        memcpy(setup.target, v->target, sizeof setup.target);
        setup.eye_set = setup.target_set = true;
        setup.camera.fov_deg = v->fov;
    }
    cr_assert(sr_scene_load(&setup, false, &f.scene, &err), "%s", err.message);
    sr_scene_frame_camera(&setup, &f.scene);
    cr_assert(sr_scene_desc(&setup, &f.scene, &f.desc, &f.study, &err), "%s", err.message);
    f.desc.study = &f.study;
    cr_assert(sr_hidden_lines_make(&f.scene.mesh, &f.lines, &err), "%s", err.message);
    draw_frame(&f, 1, SR_PATH_BY_COST, SR_SIMD_AUTO, f.frame);
    return &f;
}

static void free_framed(framed *f)
{
    sr_hidden_lines_destroy(&f->lines);
    sr_scene_free(&f->scene);
}

/* The exact truth of a view, its oracle, and the judge's tolerance. */
typedef struct judged {
    framed *f;
    sr_truth_image truth;
    line_oracle *oracle;
    double coverage_tolerance;
} judged;

static void judge_view(const view *v, judged *j)
{
    sr_error err = { "" };
    j->f = frame_view(v);
    cr_assert(sr_truth_render(&j->f->desc, SIDE_W, SIDE_H, &j->truth, &err), "%s", err.message);
    j->oracle = line_oracle_make(&j->f->desc, SIDE_W, SIDE_H, j->f->scene.fb.reversed_z);
    cr_assert_not_null(j->oracle);
    j->coverage_tolerance = sr_truth_coverage_tolerance(SR_SUBPIXEL_BITS);
}

static void free_judged(judged *j)
{
    line_oracle_free(j->oracle);
    sr_truth_image_free(&j->truth);
    free_framed(j->f);
}

static void line_ends(const framed *f, uint32_t id, uint32_t *a, uint32_t *b)
{
    *a = f->lines.wire.edges.indices[2 * (id - 1)];
    *b = f->lines.wire.edges.indices[2 * (id - 1) + 1];
}

static bool same_place(const sr_mesh *mesh, uint32_t a, uint32_t b)
{
    return memcmp(mesh->positions[a], mesh->positions[b], sizeof(vec3)) == 0;
}

/* Whether triangle id + 1 `id` has both ends of the edge a-b, by position. */
static bool has_edge(const sr_mesh *mesh, uint32_t id, uint32_t a, uint32_t b)
{
    uint32_t idx[3];
    if (!id || !sr_assemble_triangle(mesh, id - 1, idx))
        return false;
    bool has_a = false, has_b = false;
    for (int i = 0; i < 3; i++) {
        has_a = has_a || same_place(mesh, idx[i], a);
        has_b = has_b || same_place(mesh, idx[i], b);
    }
    return has_a && has_b;
}

/* Whether the truth sees a face with the edge a-b at pixel (x, y): its
 * own triangle there, or the one the fill drew where the truth calls the
 * two a tie (a centre on an outline within snapping, or depths within
 * the tie tolerance: sr_truth_judge). */
static bool face_of_edge_at(const judged *j, uint32_t a, uint32_t b, int x, int y)
{
    const sr_mesh *mesh = &j->f->scene.mesh;
    size_t i = (size_t)y * SIDE_W + x;
    uint32_t drawn = j->f->lines.fill_ids[i];
    if (has_edge(mesh, j->truth.ids[i], a, b))
        return true;
    double edge;
    sr_truth_verdict v = sr_truth_judge(&j->truth, j->f->desc.projection, drawn, x, y, j->coverage_tolerance, &edge);
    return has_edge(mesh, drawn, a, b) && (v == SR_TRUTH_DEPTH_TIE || v == SR_TRUTH_EDGE_TIE);
}

/* Whether a triangle that culling keeps (the oracle's verdict) has the
 * edge a-b, and its exact outline (truth_outline.h) passes through pixel
 * (x, y)'s diamond, which a line covering the pixel meets: within half a
 * pixel of the centre, and the snapping's tolerance. */
static bool edge_of_a_drawn_face_through(const judged *j, uint32_t a, uint32_t b, int x, int y)
{
    const sr_mesh *mesh = &j->f->scene.mesh;
    double centre[2] = { x + 0.5, y + 0.5 };
    for (uint32_t k = 0; k < sr_assemble_slots(mesh); k++)
        if (line_oracle_drawn(j->oracle, k) && has_edge(mesh, k + 1, a, b) &&
            sr_truth_outline_locate(&j->truth, k, centre).distance <= 0.5 + j->coverage_tolerance)
            return true;
    return false;
}

Test(wireframe, the_oracle_culls_as_the_draw_and_the_truth_do)
{
    for (size_t v = 0; v < VIEW_COUNT; v++) {
        judged j;
        judge_view(&VIEWS[v], &j);
        for (size_t i = 0; i < PIXELS; i++) {
            uint32_t drawn = j.f->lines.fill_ids[i], exact = j.truth.ids[i];
            cr_assert(!drawn || line_oracle_drawn(j.oracle, drawn - 1), "%s view %zu: triangle %u drawn, culled",
                      VIEWS[v].path, v, drawn - 1);
            cr_assert(!exact || line_oracle_drawn(j.oracle, exact - 1), "%s view %zu: triangle %u seen, culled",
                      VIEWS[v].path, v, exact - 1);
        }
        free_judged(&j);
    }
}

Test(wireframe, every_line_pixel_lies_on_an_edge_of_a_face_drawn_through_it)
{
    for (size_t v = 0; v < VIEW_COUNT; v++) {
        judged j;
        judge_view(&VIEWS[v], &j);
        size_t line_pixels = 0;
        for (int y = 0; y < SIDE_H; y++)
            for (int x = 0; x < SIDE_W; x++) {
                uint32_t id = j.f->frame[y * SIDE_W + x], a, b;
                if (!id)
                    continue;
                line_pixels++;
                line_ends(j.f, id, &a, &b);
                cr_assert(edge_of_a_drawn_face_through(&j, a, b, x, y),
                          "%s view %zu: line %u (%u-%u) at (%d, %d) on no face drawn", VIEWS[v].path, v, id - 1, a, b,
                          x, y);
            }
        cr_assert_gt(line_pixels, 500, "%s view %zu: %zu line pixels", VIEWS[v].path, v, line_pixels);
        free_judged(&j);
    }
}

/* A line pixel is no hidden line when the face the truth sees at its
 * centre borders the line (the line bounds what the pixel shows), or a
 * point of its line in the pixel's square is hidden by no face. */
Test(wireframe, no_hidden_line_shows)
{
    for (size_t v = 0; v < VIEW_COUNT; v++) {
        judged j;
        judge_view(&VIEWS[v], &j);
        for (int y = 0; y < SIDE_H; y++)
            for (int x = 0; x < SIDE_W; x++) {
                uint32_t id = j.f->frame[y * SIDE_W + x], a, b;
                if (!id)
                    continue;
                line_ends(j.f, id, &a, &b);
                cr_assert(face_of_edge_at(&j, a, b, x, y) || line_oracle_shows_in(j.oracle, a, b, x, y, j.coverage_tolerance),
                          "%s view %zu: line %u (%u-%u) at (%d, %d) is hidden", VIEWS[v].path, v, id - 1, a, b, x, y);
            }
        free_judged(&j);
    }
}

/* Where a line alone covers a pixel whose centre the truth sees on a face
 * the line borders, and a point of the line in the pixel shows, the frame
 * draws a line. */
Test(wireframe, the_lines_that_show_are_drawn)
{
    static uint32_t alone[PIXELS];
    for (size_t v = 0; v < VIEW_COUNT; v++) {
        judged j;
        judge_view(&VIEWS[v], &j);
        sr_error err = { "" };
        sr_draw_desc lines = j.f->desc;
        lines.mesh = &j.f->lines.wire.edges;
        lines.clear = true;
        cr_assert(sr_draw(&j.f->scene.fb, &lines, NULL, &err), "%s", err.message);
        memcpy(alone, j.f->scene.fb.color, sizeof alone);
        size_t showing = 0;
        for (int y = 0; y < SIDE_H; y++)
            for (int x = 0; x < SIDE_W; x++) {
                uint32_t id = alone[y * SIDE_W + x], a, b;
                if (!id)
                    continue;
                line_ends(j.f, id, &a, &b);
                if (!face_of_edge_at(&j, a, b, x, y) || !line_oracle_shows_in(j.oracle, a, b, x, y, j.coverage_tolerance))
                    continue;
                showing++;
                cr_assert_neq(j.f->frame[y * SIDE_W + x], 0, "%s view %zu: line %u (%u-%u) at (%d, %d) shows, not drawn",
                              VIEWS[v].path, v, id - 1, a, b, x, y);
            }
        cr_assert_gt(showing, 500, "%s view %zu: %zu pixels of lines that show", VIEWS[v].path, v, showing);
        free_judged(&j);
    }
}

Test(wireframe, the_same_pixels_on_every_thread_count_path_and_simd_level)
{
    static uint32_t other[PIXELS];
    const int threads[] = { 1, 2, 3, 8 };
    const sr_draw_path paths[] = { SR_PATH_BY_COST, SR_PATH_TILES, SR_PATH_ROWS };
    sr_simd loops[SCENE_LOOPS];
    size_t loop_count = scene_available_loops(loops);
    for (size_t v = 0; v < VIEW_COUNT; v++) {
        framed *f = frame_view(&VIEWS[v]);
        for (size_t l = 0; l < loop_count; l++)
            for (size_t t = 0; t < sizeof threads / sizeof *threads; t++)
                for (size_t p = 0; p < sizeof paths / sizeof *paths; p++) {
                    if (threads[t] == 1 && paths[p] == SR_PATH_ROWS)
                        continue; /* the row bands take several threads */
                    draw_frame(f, threads[t], paths[p], loops[l], other);
                    cr_assert_arr_eq(other, f->frame, sizeof other, "%s view %zu: %d threads, path %d, %s differ",
                                     VIEWS[v].path, v, threads[t], (int)paths[p], sr_simd_name(loops[l]));
                }
        free_framed(f);
    }
}

/* ---- small scenes ---- */

#define SMALL 64

/* The hidden-line frame and the lines alone (nearest line per pixel) of
 * `mesh` seen from the origin along +z, both faces drawn, in id shading. */
static void small_frames(const sr_mesh *mesh, uint32_t *frame, uint32_t *alone)
{
    sr_framebuffer fb;
    sr_error err = { "" };
    sr_hidden_lines h;
    sr_stats fill, drawn;
    double ms;
    scene_fb_make(&fb, SMALL, SMALL);
    sr_camera cam = scene_camera(0, 0, 0, 0, 0, 1, 60.0f, 0.5f, 50.0f);
    sr_draw_desc desc = { .mesh = mesh, .shade = SR_SHADE_ID, .cull = SR_CULL_NONE };
    scene_camera_desc(&desc, &cam, SMALL, SMALL);
    cr_assert(sr_hidden_lines_make(mesh, &h, &err), "%s", err.message);
    cr_assert(sr_hidden_lines_frame(&h, &fb, &desc, &fill, &drawn, &ms, &err), "%s", err.message);
    memcpy(frame, fb.color, SMALL * SMALL * sizeof *frame);
    desc.mesh = &h.wire.edges;
    desc.clear = true;
    cr_assert(sr_draw(&fb, &desc, NULL, &err), "%s", err.message);
    memcpy(alone, fb.color, SMALL * SMALL * sizeof *alone);
    sr_hidden_lines_destroy(&h);
    sr_framebuffer_destroy(&fb);
}

Test(wireframe, a_face_just_behind_another_shows_none_of_its_edges)
{
    /* A square at z = 5 and a smaller one 0.01 behind it, far less than
     * the three pixels' depth (0.27) a constant bias needed: lines 1-5
     * are the front square's edges, 6-10 the back one's. */
    const float pos[][3] = { { -1, -1, 5 },       { 1, -1, 5 },       { 1, 1, 5 },       { -1, 1, 5 },
                             { -0.5, -0.5, 5.01 }, { 0.5, -0.5, 5.01 }, { 0.5, 0.5, 5.01 }, { -0.5, 0.5, 5.01 } };
    const uint32_t idx[] = { 0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7 };
    sr_mesh mesh;
    scene_mesh_make(&mesh, &(scene_mesh_arrays){ .vertex_count = 8, .positions = pos, .index_count = 12,
                                                 .indices = idx, .topology = SR_TRIANGLE_LIST });
    static uint32_t frame[SMALL * SMALL], alone[SMALL * SMALL];
    small_frames(&mesh, frame, alone);
    size_t front = 0;
    for (int i = 0; i < SMALL * SMALL; i++) {
        cr_assert(frame[i] <= 5, "pixel (%d, %d): line %u of the hidden square shows", i % SMALL, i / SMALL,
                  frame[i] - 1);
        cr_assert_eq(frame[i] != 0, alone[i] >= 1 && alone[i] <= 5, "pixel (%d, %d): %u drawn, %u alone", i % SMALL,
                     i / SMALL, frame[i], alone[i]);
        front += frame[i] != 0;
    }
    cr_assert_gt(front, SMALL);
    sr_mesh_free(&mesh);
}

Test(wireframe, a_face_at_a_grazing_angle_shows_every_pixel_of_its_edges)
{
    /* A square turned 80° about y: its plane's depth changes by some 5.7
     * pixels' width per pixel across, so over the 0.7 pixel a line pixel's
     * centre may lie off its edge by more than a constant bias of three
     * pixels' width covers. */
    double c = cos(80.0 * GLM_PI / 180.0), s = sin(80.0 * GLM_PI / 180.0);
    float pos[4][3];
    for (int k = 0; k < 4; k++) {
        double u = (k == 1 || k == 2) ? 1.0 : -1.0, v = k >= 2 ? 1.0 : -1.0;
        pos[k][0] = (float)(u * c);
        pos[k][1] = (float)v;
        pos[k][2] = (float)(4.0 + u * s);
    }
    const uint32_t idx[] = { 0, 1, 2, 0, 2, 3 };
    sr_mesh mesh;
    scene_mesh_make(&mesh, &(scene_mesh_arrays){ .vertex_count = 4, .positions = (const float(*)[3])pos,
                                                 .index_count = 6, .indices = idx, .topology = SR_TRIANGLE_LIST });
    static uint32_t frame[SMALL * SMALL], alone[SMALL * SMALL];
    small_frames(&mesh, frame, alone);
    size_t drawn = 0;
    for (int i = 0; i < SMALL * SMALL; i++) {
        cr_assert_eq(frame[i] != 0, alone[i] != 0, "pixel (%d, %d): %u drawn, %u alone", i % SMALL, i / SMALL,
                     frame[i], alone[i]);
        drawn += frame[i] != 0;
    }
    cr_assert_gt(drawn, SMALL);
    sr_mesh_free(&mesh);
}

Test(wireframe, edges_are_each_edge_once_in_order_of_first_appearance_with_their_triangles)
{
    /* Two triangles sharing the edge 1-2, a degenerate one, and a third
     * whose vertices 4 and 5 are copies of 3 and 0 (another normal). */
    const uint32_t idx[] = { 0, 1, 2, 2, 1, 3, 0, 0, 3, 4, 5, 2 };
    vec3 positions[6] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 }, { 1, 1, 0 }, { 0, 0, 0 } };
    sr_mesh mesh = { .vertex_count = 6, .positions = positions, .index_count = 12, .indices = (uint32_t *)idx,
                     .topology = SR_TRIANGLE_LIST }, points;
    sr_wireframe wire;
    sr_error err;
    cr_assert(sr_wireframe_make(&mesh, &wire, &err));
    const uint32_t want[] = { 0, 1, 1, 2, 0, 2, 1, 3, 2, 3, 4, 5 };
    cr_assert_eq(wire.edges.index_count, 12);
    cr_assert_arr_eq(wire.edges.indices, want, sizeof want);
    cr_assert_eq(wire.edges.topology, SR_LINE_LIST);
    /* Each triangle's edges v0-v1, v1-v2, v2-v0 as lines; the degenerate
     * slot none; 4-5 is 3-0 and 5-2 is 0-2. */
    const uint32_t owners[] = { 0, 1, 2, 1, 3, 4, SR_WIREFRAME_NO_EDGE, SR_WIREFRAME_NO_EDGE, SR_WIREFRAME_NO_EDGE,
                                5, 2, 4 };
    cr_assert_eq(wire.triangle_slots, 4);
    cr_assert_arr_eq(wire.triangle_edges, owners, sizeof owners);
    cr_assert(sr_wireframe_points(&mesh, &points, &err));
    cr_assert_eq(points.index_count, 6);
    cr_assert_eq(points.indices[5], 5);
    cr_assert_eq(points.positions, mesh.positions, "the arrays are the mesh's");
    sr_wireframe_destroy(&wire);
    sr_wireframe_free(&points);
}
