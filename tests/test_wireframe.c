/* render --lines' hidden-line wireframe (app/wireframe.c) on every test
 * mesh: each line pixel lies on, or next to, a pixel of a triangle that
 * has the line as an edge, so no hidden line shows; render --points. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "app/scene_setup.h"
#include "app/wireframe.h"
#include "pipeline/02_assemble.h"
#include "scene/frame.h"
#include "core/dmat4.h"
#include "pipeline/01_vertex.h"

#define SIDE_W 320
#define SIDE_H 240
#define STUB 4.0

static bool same_place(const sr_mesh *mesh, uint32_t a, uint32_t b)
{
    return memcmp(mesh->positions[a], mesh->positions[b], sizeof(vec3)) == 0;
}

/* Whether the triangle has the edge a-b, by its ends' positions. */
static bool has_edge(const sr_mesh *mesh, uint32_t triangle, uint32_t a, uint32_t b)
{
    uint32_t idx[3];
    sr_assemble_triangle(mesh, triangle, idx);
    bool has_a = false, has_b = false;
    for (int k = 0; k < 3; k++) {
        has_a = has_a || same_place(mesh, idx[k], a);
        has_b = has_b || same_place(mesh, idx[k], b);
    }
    return has_a && has_b;
}

/* Where vertex i lands on the screen, in pixels, through desc's camera. */
static void screen_point(const sr_draw_desc *desc, uint32_t i, double *x, double *y)
{
    sr_dmat4 world = sr_dmat4_desc_matrix(&desc->world_d, desc->world);
    sr_dmat4 view = sr_dmat4_desc_matrix(&desc->view_d, desc->view), none = { { { 0 } } };
    sr_dmat4 projection = sr_dmat4_desc_matrix(&none, desc->projection);
    sr_vertex_transform xf;
    sr_vertex_make_transform_d(&world, &view, &projection, desc->mesh->origin, &xf);
    double c[4];
    sr_vertex_clip_d(desc->mesh->positions[i], &xf, c);
    *x = (c[0] / c[3] + 1.0) * SIDE_W / 2.0;
    *y = (1.0 - c[1] / c[3]) * SIDE_H / 2.0;
}

/* Within `px` pixels of an end of the line a-b on screen. */
static bool near_an_end(const sr_draw_desc *desc, uint32_t a, uint32_t b, int x, int y, double px)
{
    double ex, ey, fx, fy;
    screen_point(desc, a, &ex, &ey);
    screen_point(desc, b, &fx, &fy);
    return hypot(x + 0.5 - ex, y + 0.5 - ey) <= px || hypot(x + 0.5 - fx, y + 0.5 - fy) <= px;
}

/* The wireframe of `path`, framed as render frames it, against the ids of
 * its triangles drawn alone with the same camera. */
static void check_wireframe(const char *path, float rotate_y, sr_cull cull)
{
    sr_scene_setup setup;
    sr_scene scene;
    sr_error err = { "" };
    sr_scene_setup_defaults(&setup);
    setup.mesh_path = path;
    setup.size[0] = SIDE_W;
    setup.size[1] = SIDE_H;
    setup.rotate_y = rotate_y;
    setup.cull = cull;
    setup.shade = SR_SHADE_ID;
    cr_assert(sr_scene_load(&setup, false, &scene, &err), "%s", err.message);
    sr_scene_frame_camera(&setup, &scene);
    sr_draw_desc desc, lines;
    sr_draw_study study;
    cr_assert(sr_scene_desc(&setup, &scene, &desc, &study, &err), "%s", err.message);
    sr_mesh edges;
    cr_assert(sr_wireframe_edges(&scene.mesh, &edges, &err), "%s", err.message);
    lines = desc;
    lines.mesh = &edges;
    lines.depth_bias = sr_wireframe_depth_bias(&desc, SIDE_H);
    cr_assert(lines.depth_bias > 0.0f && lines.depth_bias < 0.1f, "bias %g", lines.depth_bias);
    static uint32_t triangles[SIDE_W * SIDE_H];
    double ms;
    sr_stats fill, drawn;
    cr_assert(sr_frame_draw_timed(&scene.fb, &desc, &fill, &ms, &err), "%s", err.message);
    memcpy(triangles, scene.fb.color, sizeof triangles);
    cr_assert(sr_wireframe_frame(&scene.fb, &desc, &lines, &fill, &drawn, &ms, &err), "%s", err.message);
    cr_assert_eq(drawn.lines, edges.index_count / 2);
    /* Each line pixel lies on or next to an edge of the triangle that
     * covers it (a pixel of its 3 × 3 neighbourhood is not that
     * triangle's): a line through a face's inside is a hidden one showing.
     * Nearly all lie on or next to a triangle that has the line as an edge
     * (by position); the rest are the first pixels of hidden edges that
     * leave a visible vertex, within the bias of the face in front (at
     * most STUB pixels from it). */
    size_t line_pixels = 0, own = 0;
    for (int y = 0; y < SIDE_H; y++)
        for (int x = 0; x < SIDE_W; x++) {
            uint32_t id = scene.fb.color[y * SIDE_W + x], here = triangles[y * SIDE_W + x];
            if (!id)
                continue;
            line_pixels++;
            uint32_t a = edges.indices[2 * (id - 1)], b = edges.indices[2 * (id - 1) + 1];
            bool near_own = false, on_edge = false;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int qx = x + dx, qy = y + dy;
                    uint32_t t = qx < 0 || qy < 0 || qx >= SIDE_W || qy >= SIDE_H ? 0 : triangles[qy * SIDE_W + qx];
                    near_own = near_own || (t && has_edge(&scene.mesh, t - 1, a, b));
                    on_edge = on_edge || t != here;
                }
            cr_assert(on_edge || near_own || near_an_end(&desc, a, b, x, y, STUB),
                      "%s: line %u (%u-%u) at (%d, %d) shows inside triangle %u", path, id - 1, a, b, x, y, here - 1);
            own += near_own;
        }
    cr_assert_geq(own * 100, line_pixels * 95, "%s: %zu of %zu line pixels by a triangle of their own", path, own,
                  line_pixels);
    cr_assert_gt(line_pixels, 500, "%s: %zu line pixels", path, line_pixels);
    sr_wireframe_free(&edges);
    sr_scene_free(&scene);
}

Test(wireframe, every_line_pixel_is_on_or_next_to_its_own_triangles)
{
    check_wireframe("assets/cube.obj", 30.0f, SR_CULL_BACK);
    check_wireframe("assets/sphere.obj", 0.0f, SR_CULL_BACK);
    check_wireframe("assets/torus.obj", 20.0f, SR_CULL_BACK);
    check_wireframe("assets/quad3x3.obj", 10.0f, SR_CULL_NONE);
    /* Not the room: its pillars' top faces lie in the ceiling's plane, and
     * an edge in a face's plane is within any bias of it and shows. */
}

Test(wireframe, edges_are_each_edge_once_in_order_of_first_appearance)
{
    /* Two triangles sharing the edge 1-2, a degenerate one, and a third
     * whose vertices 4 and 5 are copies of 3 and 0 (another normal). */
    const uint32_t idx[] = { 0, 1, 2, 2, 1, 3, 0, 0, 3, 4, 5, 2 };
    vec3 positions[6] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 }, { 1, 1, 0 }, { 0, 0, 0 } };
    sr_mesh mesh = { .vertex_count = 6, .positions = positions, .index_count = 12, .indices = (uint32_t *)idx,
                     .topology = SR_TRIANGLE_LIST }, edges, points;
    sr_error err;
    cr_assert(sr_wireframe_edges(&mesh, &edges, &err));
    const uint32_t want[] = { 0, 1, 1, 2, 0, 2, 1, 3, 2, 3, 4, 5 };
    cr_assert_eq(edges.index_count, 12);
    cr_assert_arr_eq(edges.indices, want, sizeof want);
    cr_assert_eq(edges.topology, SR_LINE_LIST);
    cr_assert(sr_wireframe_points(&mesh, &points, &err));
    cr_assert_eq(points.index_count, 6);
    cr_assert_eq(points.indices[5], 5);
    cr_assert_eq(points.positions, mesh.positions, "the arrays are the mesh's");
    sr_wireframe_free(&edges);
    sr_wireframe_free(&points);
}
