/* The report's verdict on a drawn pixel against the truth
 * (src/studies/report_truth.h) and the outlines it measures with
 * (src/studies/truth_outline.h), against closed forms on small scenes. */
#include <math.h>

#include "clip_helpers.h"
#include "scene_helpers.h"
#include "studies/bench_scenes.h"
#include "studies/report.h"
#include "studies/report_truth.h"
#include "studies/truth_outline.h"

#define SIDE 64
#define SUB_SNAP 0x1p-12 /* px: a sixteenth of a subpixel step at 8 bits */

/* Under this lens (x_ndc = x/z, y_ndc = y/z, near 1, far 10) a point at
 * view depth z lands at px = (x/z + 1)·32, py = (1 − y/z)·32 on 64x64. */
static void unit_lens(sr_draw_desc *desc, const sr_mesh *mesh)
{
    *desc = (sr_draw_desc){ .mesh = mesh, .shade = SR_SHADE_ID, .cull = SR_CULL_NONE };
    glm_perspective_lh_zo(glm_rad(90.0f), 1.0f, 1.0f, 10.0f, desc->projection);
    desc->projection[0][0] = desc->projection[1][1] = 1.0f;
}

static void truth_of(const sr_draw_desc *desc, sr_truth_image *t)
{
    sr_error err = { "" };
    cr_assert(sr_truth_render(desc, SIDE, SIDE, t, &err), "sr_truth_render: %s", err.message);
}

/* Slot 0, in front at z = 2: a vertical left edge at px = 20.5 − SUB_SNAP
 * from py 8 to 56, its right corner at (60, 32). Slot 1, behind at z = 4,
 * covers the whole image. */
static void front_and_back(sr_mesh *mesh, sr_draw_desc *desc, sr_truth_image *t)
{
    const float left = (float)((20.5 - SUB_SNAP) / 16.0 - 2.0); /* exact in float */
    const float pos[][3] = { { left, 1.5f, 2.0f }, { 1.75f, 0.0f, 2.0f }, { left, -1.5f, 2.0f },
                             { -8.0f, -8.0f, 4.0f }, { 0.0f, 8.0f, 4.0f }, { 8.0f, -8.0f, 4.0f } };
    const uint32_t idx[] = { 0, 1, 2, 3, 4, 5 };
    scene_mesh_make(mesh, &(scene_mesh_arrays){ .vertex_count = 6, .positions = pos, .index_count = 6, .indices = idx });
    unit_lens(desc, mesh);
    truth_of(desc, t);
}

Test(truth_judge, the_coverage_tolerance_is_the_snapping_bound_plus_the_vertex_allowance)
{
    cr_assert_eq(sr_truth_coverage_tolerance(8), sqrt(2.0) / 512.0 + SR_REPORT_VERTEX_ERROR_PX);
    cr_assert_eq(sr_truth_coverage_tolerance(12), sqrt(2.0) / 8192.0 + SR_REPORT_VERTEX_ERROR_PX);
}

Test(truth_judge, a_centre_a_sub_snap_distance_inside_the_front_triangle_is_an_edge_tie)
{
    sr_mesh mesh;
    sr_draw_desc desc;
    sr_truth_image t;
    front_and_back(&mesh, &desc, &t);
    double tolerance = sr_truth_coverage_tolerance(8), distance = -1.0;
    cr_assert_eq(t.ids[32 * SIDE + 20], 1u, "centre (20.5, 32.5) lies inside the front triangle");
    cr_assert_eq(sr_truth_judge(&t, desc.projection, 2, 20, 32, tolerance, &distance), SR_TRUTH_EDGE_TIE);
    cr_assert_float_eq(distance, SUB_SNAP, 1e-12);
    cr_assert_eq(sr_truth_judge(&t, desc.projection, 2, 20, 32, 0.5 * SUB_SNAP, &distance), SR_TRUTH_WRONG_TRIANGLE,
                 "a tolerance below the distance explains nothing");
    /* Six pixels right the back triangle shows through no tie. */
    cr_assert_eq(sr_truth_judge(&t, desc.projection, 2, 26, 32, tolerance, &distance), SR_TRUTH_WRONG_TRIANGLE);
    cr_assert_float_eq(distance, 6.0 + SUB_SNAP, 1e-12);
    /* The front triangle drawn one pixel left of its edge: 1 − SUB_SNAP outside it. */
    cr_assert_eq(t.ids[32 * SIDE + 19], 2u);
    cr_assert_eq(sr_truth_judge(&t, desc.projection, 1, 19, 32, tolerance, &distance), SR_TRUTH_WRONG_TRIANGLE);
    cr_assert_float_eq(distance, 1.0 - SUB_SNAP, 1e-12);
    cr_assert_eq(sr_truth_judge(&t, desc.projection, 2, 19, 32, tolerance, &distance), SR_TRUTH_SAME);
    cr_assert_eq(sr_truth_judge(&t, desc.projection, 0, 19, 32, tolerance, &distance), SR_TRUTH_COVERAGE);
    sr_truth_image_free(&t);
    sr_mesh_free(&mesh);
}

Test(truth_judge, the_other_of_two_coincident_triangles_is_a_depth_tie)
{
    const float pos[][3] = { { -1.5f, -1.5f, 2.0f }, { 0.0f, 1.5f, 2.0f }, { 1.5f, -1.5f, 2.0f } };
    const uint32_t idx[] = { 0, 1, 2, 0, 1, 2 };
    sr_mesh mesh;
    sr_draw_desc desc;
    sr_truth_image t;
    scene_mesh_make(&mesh, &(scene_mesh_arrays){ .vertex_count = 3, .positions = pos, .index_count = 6, .indices = idx });
    unit_lens(&desc, &mesh);
    truth_of(&desc, &t);
    uint32_t shown = t.ids[32 * SIDE + 32], other = 3 - shown;
    cr_assert(shown == 1 || shown == 2);
    double distance = -1.0;
    cr_assert_eq(sr_truth_judge(&t, desc.projection, other, 32, 32, 0.0, &distance), SR_TRUTH_DEPTH_TIE);
    sr_truth_image_free(&t);
    sr_mesh_free(&mesh);
}

Test(truth_judge, the_tally_counts_each_verdict_and_the_largest_edge_distance)
{
    sr_mesh mesh;
    sr_draw_desc desc;
    sr_truth_image t;
    front_and_back(&mesh, &desc, &t);
    sr_framebuffer fb;
    scene_fb_make(&fb, SIDE, SIDE);
    for (size_t i = 0; i < SIDE * SIDE; i++) {
        fb.color[i] = t.ids[i];
        fb.depth[i] = (float)sr_truth_z_ndc(desc.projection, t.distance[i]);
    }
    fb.color[32 * SIDE + 20] = 2; /* an edge tie */
    fb.color[32 * SIDE + 26] = 2; /* a wrong triangle */
    fb.color[50 * SIDE + 10] = 0; /* coverage: the back triangle is there */
    sr_truth_tally tally = { .coverage_tolerance = sr_truth_coverage_tolerance(8) };
    sr_error err = { "" };
    cr_assert(sr_truth_tally_add(&tally, &t, desc.projection, &fb, &err), "%s", err.message);
    sr_truth_errors e = sr_truth_tally_finish(&tally);
    cr_assert_eq(e.edge_ties, 1u);
    cr_assert_eq(e.wrong_triangle, 1u);
    cr_assert_eq(e.coverage, 1u);
    cr_assert_eq(e.depth_ties, 0u);
    cr_assert_float_eq(e.edge_distance_max, 6.0 + SUB_SNAP, 1e-12);
    cr_assert_lt(e.z_max, 1e-7, "depths written as the truth's float z_ndc");
    sr_framebuffer_destroy(&fb);
    sr_truth_image_free(&t);
    sr_mesh_free(&mesh);
}

Test(truth_judge, a_near_cut_outline_ends_on_the_line_where_the_triangle_meets_the_near_plane)
{
    /* A floor at y = -0.5 from z = 0.5 (before near) to z = 3: its near cut,
     * at z = near, lies on row py = (1 + 0.5 / near)·32 across the image;
     * its sides pass about 10 px from (30.5, 47.5). */
    const float pos[3][3] = { { -4.0f, -0.5f, 0.5f }, { 0.0f, -0.5f, 3.0f }, { 4.0f, -0.5f, 0.5f } };
    sr_mesh mesh;
    sr_draw_desc desc;
    sr_truth_image t;
    scene_triangle_make(&mesh, pos);
    unit_lens(&desc, &mesh);
    truth_of(&desc, &t);
    double cut_row = (1.0 + 0.5 / t.lens.near_z) * 32.0;
    cr_assert_float_eq(cut_row, 48.0, 1e-5);
    sr_truth_outline_place above = sr_truth_outline_locate(&t, 0, (double[2]){ 30.5, 47.5 });
    sr_truth_outline_place below = sr_truth_outline_locate(&t, 0, (double[2]){ 30.5, 48.5 });
    cr_assert(above.inside);
    cr_assert_float_eq(above.distance, cut_row - 47.5, 1e-12);
    cr_assert(!below.inside);
    cr_assert_float_eq(below.distance, 48.5 - cut_row, 1e-12);
    cr_assert(isinf(sr_truth_outline_locate(&t, 1, (double[2]){ 30.5, 47.5 }).distance), "no slot 1");
    sr_truth_image_free(&t);
    sr_mesh_free(&mesh);
}

/* The exact outline of a slot cut to the image, as the side planes cut it. */
typedef struct exact_polygon {
    int count;
    double p[SR_TRUTH_OUTLINE_CORNERS + 4][2];
} exact_polygon;

/* Keeps the part of g with sign·(p[axis] − bound) >= 0. */
static void cut_side(exact_polygon *g, int axis, double bound, double sign)
{
    exact_polygon in = *g;
    g->count = 0;
    for (int i = 0; i < in.count; i++) {
        const double *a = in.p[i], *b = in.p[(i + 1) % in.count];
        double da = sign * (a[axis] - bound), db = sign * (b[axis] - bound);
        if (da >= 0.0) {
            g->p[g->count][0] = a[0], g->p[g->count][1] = a[1];
            g->count++;
        }
        if ((da >= 0.0) != (db >= 0.0)) {
            double t = da / (da - db);
            g->p[g->count][0] = a[0] + t * (b[0] - a[0]), g->p[g->count][1] = a[1] + t * (b[1] - a[1]);
            g->p[g->count++][axis] = bound;
        }
    }
}

typedef struct vertex_errors {
    const sr_truth_image *truth;
    const sr_mesh *mesh;
    sr_vertex_transform xf; /* the draw's, for the float points */
    sr_viewport vp;
    double max;
    uint64_t vertices;
} vertex_errors;

/* The points snapping rounded: the vertex phase and the viewport snap the
 * float clip positions (the clipper's cuts of them) but hand on the
 * offsets of the positions in double (for the depth plane,
 * docs/precision.md), so the triangle is transformed, clipped as the draw
 * clips it and mapped again from float here, and each drawn vertex must
 * snap to one of those points. */
static void float_points(const vertex_errors *v, uint32_t id, const sr_screen_vertex drawn[3],
                         sr_screen_vertex out[3])
{
    static const sr_varying_layout none = { .count = 0, .color = -1, .uv = -1, .normal = -1 };
    uint32_t idx[3];
    cr_assert(sr_assemble_triangle(v->mesh, id, idx));
    sr_polygon poly = { .count = 3 };
    unsigned planes = 0;
    for (int k = 0; k < 3; k++) {
        CGLM_ALIGN(16) sr_vertex_out clip; /* the vertex stage stores 16 bytes at a time */
        sr_vertex_run(v->mesh, &v->xf, &none, idx[k], 1, &clip);
        poly.vert[k] = clip;
        planes |= sr_clip_outcode_with(clip.v, &v->vp.depth);
    }
    sr_clip_config cfg = { .ndc_tolerance = draw_clip_tolerance(v->vp.width, v->vp.height), .depth = v->vp.depth };
    if (planes)
        sr_clip_polygon(&poly, planes, SR_VARYINGS_AT, &cfg);
    for (int k = 0; k < 3; k++) {
        bool found = false;
        for (int i = 0; i < poly.count && !found; i++) {
            cr_assert(sr_viewport_map(&poly.vert[i], 0, &v->vp, &out[k]));
            found = out[k].x == drawn[k].x && out[k].y == drawn[k].y;
        }
        cr_assert(found, "slot %u vertex %d snaps elsewhere", id, k);
    }
}

/* How far each fan-triangle vertex, before snapping, lies from where it
 * moves coverage: from the nearest corner of its triangle's exact outline
 * cut to the image; on the image's border (a side-plane cut), from the
 * exact outline itself, since sliding along the border moves no edge
 * inside the image. */
static void measure_vertices(void *user, const sr_screen_vertex drawn[3], bool clipped, uint32_t id)
{
    (void)clipped;
    vertex_errors *v = user;
    sr_screen_vertex tri[3];
    float_points(v, id, drawn, tri);
    exact_polygon g;
    g.count = sr_truth_outline_corners(v->truth, id, g.p);
    cut_side(&g, 0, 0.0, 1.0);
    cut_side(&g, 0, v->truth->width, -1.0);
    cut_side(&g, 1, 0.0, 1.0);
    cut_side(&g, 1, v->truth->height, -1.0);
    cr_assert_gt(g.count, 2, "slot %u is drawn, so its exact outline meets the image", id);
    double scale = 0x1p-8; /* SR_SUBPIXEL_BITS */
    for (int k = 0; k < 3; k++) {
        double p[2] = { ((double)tri[k].x + tri[k].x_off) * scale, ((double)tri[k].y + tri[k].y_off) * scale };
        double error = INFINITY;
        for (int c = 0; c < g.count; c++)
            error = fmin(error, hypot(p[0] - g.p[c][0], p[1] - g.p[c][1]));
        if (p[0] == 0.0 || p[1] == 0.0 || p[0] == v->truth->width || p[1] == v->truth->height)
            error = fmin(error, sr_truth_outline_locate(v->truth, id, p).distance);
        v->max = fmax(v->max, error);
        v->vertices++;
    }
}

Test(truth_judge, the_report_scenes_vertices_before_snapping_lie_within_the_vertex_allowance)
{
    bool (*make[])(sr_bench_scene *, sr_error *) = { sr_bench_fly, sr_bench_stiff };
    for (size_t m = 0; m < sizeof make / sizeof *make; m++) {
        sr_bench_scene s;
        sr_error err = { "" };
        cr_assert(make[m](&s, &err), "%s", err.message);
        int frames = sr_report_scene_frames(&s);
        vertex_errors v = { .mesh = &s.mesh };
        for (int f = 0; f < frames; f++) {
            sr_camera cam;
            sr_bench_scene_camera(&s, f, frames, &cam);
            sr_draw_study study = { .observer = measure_vertices, .observer_user = &v };
            sr_draw_desc desc = { .mesh = &s.mesh, .shade = SR_SHADE_ID, .study = &study };
            sr_camera_view(&cam, desc.view);
            sr_camera_projection(&cam, (float)s.width / (float)s.height, desc.projection);
            sr_dmat4 world = sr_dmat4_identity(), view = sr_dmat4_from_mat4(desc.view),
                     projection = sr_dmat4_from_mat4(desc.projection);
            sr_vertex_make_transform_d(&world, &view, &projection, s.mesh.origin, &v.xf);
            v.vp = (sr_viewport){ s.width, s.height, SR_SUBPIXEL_BITS, 1.0f, sr_clip_depth_of(desc.projection) };
            sr_truth_image t;
            cr_assert(sr_truth_render(&desc, s.width, s.height, &t, &err), "%s", err.message);
            v.truth = &t;
            sr_framebuffer fb;
            scene_fb_make(&fb, s.width, s.height);
            cr_assert(sr_draw(&fb, &desc, NULL, &err), "%s", err.message);
            sr_framebuffer_destroy(&fb);
            sr_truth_image_free(&t);
        }
        if (getenv("SOFTRAST_TRUTH_VERBOSE"))
            printf("%s: %llu fan-triangle vertices, largest error before snapping %.3g px\n", s.name,
                   (unsigned long long)v.vertices, v.max);
        cr_assert_gt(v.vertices, 1000);
        cr_assert_leq(v.max, SR_REPORT_VERTEX_ERROR_PX, "%s: a vertex %g px from the exact one", s.name, v.max);
        sr_bench_scene_free(&s);
    }
}
