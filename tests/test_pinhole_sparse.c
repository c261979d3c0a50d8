/* View depth, range, ids and normals of points and lines seen by a pinhole
 * camera: a point's pixels carry its vertex, a line's pixels the segment's
 * point nearest their ray, held to oracles written independently of
 * src/scene/pinhole_sparse.c (in long double, in the camera frame: a point's own
 * coordinates, and a golden-section search along the segment for its
 * point nearest the ray). */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "softrast_private.h"
#include "test_rng.h"

#define W 64
#define H 48

typedef long double real;

/* Looking along the file's +z from its origin, image y down: camera
 * coordinates are the file's, so an oracle in the camera frame needs no
 * pose. A second camera turned and moved checks the pose is applied. */
static sr_pinhole camera(double fx, double fy, double cx, double cy)
{
    return (sr_pinhole){ .fx = fx, .fy = fy, .cx = cx, .cy = cy,
                         .w2c = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 0, 1 } } };
}

/* Draws mesh (points or lines) in id shading with cam's matrices, then
 * resolves every output: depth, range, face ids, part ids and normals. */
typedef struct resolved {
    sr_framebuffer fb;
    float depth[W * H], range[W * H], normals[3 * W * H];
    uint32_t face_ids[W * H], part_ids[W * H];
} resolved;

static void draw_and_resolve(sr_pinhole *cam, const sr_mesh *mesh, int threads, resolved *r)
{
    sr_error err = { "" };
    cr_assert(sr_framebuffer_create(&r->fb, W, H, &err), "%s", err.message);
    sr_draw_desc desc = { .mesh = mesh, .shade = SR_SHADE_ID, .cull = SR_CULL_NONE, .clear = true,
                          .point_size = 1.0f, .threads = threads };
    sr_pinhole_fit_clip(cam, mesh);
    sr_pinhole_matrices(cam, mesh, &r->fb, &desc);
    cr_assert(sr_draw(&r->fb, &desc, NULL, &err), "%s", err.message);
    sr_pinhole_outputs out = { .depth = r->depth, .range = r->range, .face_ids = r->face_ids,
                               .part_ids = r->part_ids, .normals = r->normals, .threads = threads };
    cr_assert(sr_pinhole_resolve(cam, mesh, &r->fb, &out, &err), "%s", err.message);
}

static void unit(real v[3])
{
    real length = sqrtl(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++)
        v[k] /= length;
}

/* |got − want| within `ulps` float steps of want. */
static bool near_float(float got, real want, int ulps)
{
    float w = (float)want;
    return fabsl((real)got - want) <= ulps * (real)(nextafterf(fabsf(w), INFINITY) - fabsf(w));
}

TestSuite(pinhole_sparse);

/* Points placed exactly on pixel centres, at random depths and with random
 * normals: each one's pixel shows it, with its own z, distance and normal;
 * every other drawn pixel belongs to a point whose 1-px square covers it. */
Test(pinhole_sparse, a_point_shows_its_vertex_depth_range_and_normal)
{
    enum { POINTS = 40 };
    test_rng rng = { 31 };
    sr_error err = { "" };
    sr_mesh mesh;
    cr_assert(sr_mesh_alloc(&mesh, POINTS, POINTS, true, false, false, &err), "%s", err.message);
    mesh.topology = SR_POINT_LIST;
    sr_pinhole cam = camera(41.0, 37.5, 30.25, 22.75);
    int used[W * H] = { 0 };
    real want_z[POINTS], want_n[POINTS][3];
    int px[POINTS], py[POINTS];
    for (int k = 0; k < POINTS; k++) {
        do {
            px[k] = 1 + (int)(rng_unit(&rng) * (W - 2));
            py[k] = 1 + (int)(rng_unit(&rng) * (H - 2));
        } while (used[py[k] * W + px[k]]);
        used[py[k] * W + px[k]] = 1;
        float z = (float)rng_uniform(&rng, 0.5, 50.0);
        /* (u − cx)·z/fx rounded to float moves the point off the centre by
         * far less than half a pixel */
        mesh.positions[k][0] = (float)((px[k] - cam.cx) * z / cam.fx);
        mesh.positions[k][1] = (float)((py[k] - cam.cy) * z / cam.fy);
        mesh.positions[k][2] = z;
        real n[3] = { rng_uniform(&rng, -1, 1), rng_uniform(&rng, -1, 1), rng_uniform(&rng, -1, 1) };
        unit(n);
        for (int c = 0; c < 3; c++) {
            mesh.normals[k][c] = (float)n[c];
            want_n[k][c] = mesh.normals[k][c];
        }
        unit(want_n[k]);
        want_z[k] = z;
        mesh.indices[k] = (uint32_t)k;
    }
    for (int threads = 1; threads <= 3; threads += 2) {
        static resolved r;
        draw_and_resolve(&cam, &mesh, threads, &r);
        for (int k = 0; k < POINTS; k++) {
            size_t at = (size_t)py[k] * W + (size_t)px[k];
            cr_assert_eq(r.face_ids[at], (uint32_t)k + 1, "point %d at (%d, %d) shows %u", k, px[k], py[k],
                         r.face_ids[at]);
            const float *p = mesh.positions[k];
            real range = sqrtl((real)p[0] * p[0] + (real)p[1] * p[1] + (real)p[2] * p[2]);
            cr_assert_eq(r.depth[at], (float)want_z[k], "point %d: depth %.9g, want %.9g", k, r.depth[at],
                         (float)want_z[k]);
            cr_assert(near_float(r.range[at], range, 1), "point %d: range %.9g, want %.9Lg", k, r.range[at], range);
            cr_assert_eq(r.part_ids[at], 1u);
            for (int c = 0; c < 3; c++)
                cr_assert(fabsl(r.normals[3 * at + c] - want_n[k][c]) < 1e-6L, "point %d: normal[%d] %.9g, want %.9Lg",
                          k, c, r.normals[3 * at + c], want_n[k][c]);
        }
        for (size_t at = 0; at < (size_t)W * H; at++)
            cr_assert(r.face_ids[at] == 0 ? r.depth[at] == 0.0f && r.range[at] == 0.0f && r.part_ids[at] == 0
                                          : r.depth[at] == (float)want_z[r.face_ids[at] - 1],
                      "pixel %zu: id %u, depth %.9g", at, r.face_ids[at], r.depth[at]);
        sr_framebuffer_destroy(&r.fb);
    }
    sr_mesh_free(&mesh);
}

/* A mesh of one segment, vertex 0 to vertex 1, with normals. */
static void one_segment(sr_mesh *mesh, sr_topology topology)
{
    sr_error err = { "" };
    cr_assert(sr_mesh_alloc(mesh, 2, 2, true, false, false, &err), "%s", err.message);
    mesh->topology = topology;
    mesh->indices[0] = 0;
    mesh->indices[1] = 1;
}

static real normal_length(const resolved *r, size_t at)
{
    const float *n = &r->normals[3 * at];
    return sqrtl((real)n[0] * n[0] + (real)n[1] * n[1] + (real)n[2] * n[2]);
}

/* The distance from point a + t·u to the line through the origin along d. */
static real distance_to_ray(const real a[3], const real u[3], real t, const real d[3])
{
    real p[3] = { a[0] + t * u[0], a[1] + t * u[1], a[2] + t * u[2] };
    real c[3] = { p[1] * d[2] - p[2] * d[1], p[2] * d[0] - p[0] * d[2], p[0] * d[1] - p[1] * d[0] };
    return sqrtl(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

/* The camera z of the point nearest the ray through pixel (x, y) of the
 * segment's part between the clip planes (a_f's end in front of the near
 * one), and where it lies from a_f's end to b_f's (*t, unless NULL): a
 * golden-section search for t in that part (the distance is convex in
 * t), to far below a float step. From a_f's end, so a far end 1e30 away
 * costs the point no digits. */
static real nearest_z(const sr_pinhole *cam, const float a_f[3], const float b_f[3], int x, int y, real *t_out)
{
    real a[3], u[3], d[3] = { (x - cam->cx) / cam->fx, (y - cam->cy) / cam->fy, 1.0L };
    for (int k = 0; k < 3; k++) {
        a[k] = a_f[k];
        u[k] = (real)b_f[k] - a_f[k];
    }
    const real g = (sqrtl(5.0L) - 1.0L) / 2.0L;
    real lo = 0.0L, hi = 1.0L;
    if (a[2] + u[2] < cam->near)
        hi = (cam->near - a[2]) / u[2];
    if (a[2] + u[2] > cam->far)
        hi = (cam->far - a[2]) / u[2];
    for (int i = 0; i < 120; i++) {
        real m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
        if (distance_to_ray(a, u, m1, d) <= distance_to_ray(a, u, m2, d))
            hi = m2;
        else
            lo = m1;
    }
    real t = (lo + hi) / 2.0L;
    if (t_out)
        *t_out = t;
    return a[2] + t * u[2];
}

/* Random segments in front of the camera, one per draw: every pixel a
 * segment draws carries the depth of its point nearest the pixel's ray,
 * between its ends' depths, and its distance from the camera. */
Test(pinhole_sparse, a_line_shows_its_point_nearest_each_pixels_ray)
{
    test_rng rng = { 77 };
    sr_mesh mesh;
    one_segment(&mesh, SR_LINE_LIST);
    sr_pinhole cam = camera(45.0, 52.0, 33.5, 20.25);
    int checked = 0, far_half = 0;
    for (int trial = 0; trial < 60; trial++) {
        for (int e = 0; e < 2; e++) {
            float z = (float)rng_uniform(&rng, 0.3, 30.0);
            mesh.positions[e][0] = (float)(rng_uniform(&rng, -0.5, W + 0.5) - cam.cx) * z / (float)cam.fx;
            mesh.positions[e][1] = (float)(rng_uniform(&rng, -0.5, H + 0.5) - cam.cy) * z / (float)cam.fy;
            mesh.positions[e][2] = z;
            glm_vec3_copy((vec3){ 0.0f, (float)e, 1.0f - (float)e }, mesh.normals[e]);
        }
        static resolved r;
        cam.near = cam.far = 0.0;
        draw_and_resolve(&cam, &mesh, 1 + trial % 3, &r);
        float zmin = fminf(mesh.positions[0][2], mesh.positions[1][2]);
        float zmax = fmaxf(mesh.positions[0][2], mesh.positions[1][2]);
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                size_t at = (size_t)y * W + (size_t)x;
                if (r.face_ids[at] == 0)
                    continue;
                cr_assert_eq(r.face_ids[at], 1u);
                real t, want = nearest_z(&cam, mesh.positions[0], mesh.positions[1], x, y, &t);
                cr_assert(fabsl(r.depth[at] - want) <= 1e-6L * want, "trial %d, (%d, %d): depth %.9g, want %.9Lg",
                          trial, x, y, r.depth[at], want);
                cr_assert(r.depth[at] >= zmin && r.depth[at] <= zmax, "trial %d: depth %.9g outside the ends' %g..%g",
                          trial, r.depth[at], zmin, zmax);
                cr_assert(r.range[at] >= r.depth[at], "trial %d: range %.9g below depth", trial, r.range[at]);
                real n = normal_length(&r, at);
                cr_assert(fabsl(n - 1.0L) < 1e-6L, "trial %d: normal of length %.9Lg", trial, n);
                /* The ends' normals (0, 0, 1) and (0, 1, 0) weighed by where
                 * the point lies, found from either end: (0, t, 1 − t). */
                const float *got = &r.normals[3 * at];
                real sum = fabsl((real)got[1]) + fabsl((real)got[2]);
                cr_assert(got[0] == 0.0f && fabsl(got[1] / sum - t) < 1e-5L && fabsl(got[2] / sum - (1.0L - t)) < 1e-5L,
                          "trial %d, (%d, %d): normal (%g, %g, %g) at t %.9Lg", trial, x, y, got[0], got[1], got[2], t);
                far_half += t > 0.5L;
                checked++;
            }
        sr_framebuffer_destroy(&r.fb);
    }
    cr_assert(checked > 500, "only %d line pixels checked", checked);
    cr_assert(far_half > 100, "only %d pixels' points in the far half, found from the far end", far_half);
    sr_mesh_free(&mesh);
}

/* Segments nearly along one pixel's ray, from depth 2 to 8 (their ends a
 * pixel or two apart on screen), in both orders: where |u × d| is tiny,
 * every pixel drawn still carries the oracle's depth. */
Test(pinhole_sparse, a_line_nearly_along_a_ray_keeps_its_depth)
{
    sr_mesh mesh;
    one_segment(&mesh, SR_LINE_STRIP);
    sr_pinhole cam = camera(40.0, 40.0, 31.5, 23.5);
    const float d[3] = { 0.25f, -0.125f, 1.0f }, off[3] = { 0.03f, 0.01f, 0.0f };
    for (int order = 0; order < 2; order++) {
        for (int k = 0; k < 3; k++) {
            mesh.positions[order][k] = 2.0f * d[k];
            mesh.positions[1 - order][k] = 8.0f * (d[k] + off[k]);
        }
        static resolved r;
        cam.near = cam.far = 0.0;
        draw_and_resolve(&cam, &mesh, 1, &r);
        int drawn = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                size_t at = (size_t)y * W + (size_t)x;
                if (!r.face_ids[at])
                    continue;
                drawn++;
                real want = nearest_z(&cam, mesh.positions[0], mesh.positions[1], x, y, NULL);
                cr_assert(fabsl(r.depth[at] - want) <= 1e-6L * want, "order %d, (%d, %d): depth %.9g, want %.9Lg",
                          order, x, y, r.depth[at], want);
            }
        cr_assert(drawn >= 1 && drawn <= 4, "order %d: %d pixels drawn", order, drawn);
        sr_framebuffer_destroy(&r.fb);
    }
    sr_mesh_free(&mesh);
}

/* Segments from a point in front of the camera to one behind it, 10 to
 * 1e30 away: a pixel shows the point nearest its ray of the part drawn,
 * in front of the near plane, as the oracle finds it from the end in
 * front; never a point behind the camera, nor one whose digits went with
 * the far end's. */
Test(pinhole_sparse, a_line_through_the_near_plane_shows_the_part_drawn)
{
    test_rng rng = { 5 };
    sr_mesh mesh;
    one_segment(&mesh, SR_LINE_LIST);
    sr_pinhole cam = camera(45.0, 52.0, 33.5, 20.25);
    const float lengths[] = { 10.0f, 1e3f, 1e10f, 1e30f };
    int checked = 0;
    for (int trial = 0; trial < 32; trial++) {
        float z = (float)rng_uniform(&rng, 0.5, 20.0), length = lengths[trial % 4];
        int front = trial / 4 % 2; /* the index of the end in front: both orders */
        float *a = mesh.positions[front], *b = mesh.positions[1 - front];
        a[0] = (float)(rng_uniform(&rng, 8.0, W - 8.0) - cam.cx) * z / (float)cam.fx;
        a[1] = (float)(rng_uniform(&rng, 8.0, H - 8.0) - cam.cy) * z / (float)cam.fy;
        a[2] = z;
        real dir[3] = { rng_uniform(&rng, -1, 1), rng_uniform(&rng, -1, 1), rng_uniform(&rng, -1.0, -0.2) };
        unit(dir);
        for (int k = 0; k < 3; k++)
            b[k] = (float)(a[k] + length * dir[k]);
        glm_vec3_copy((vec3){ 0.0f, 0.0f, -1.0f }, mesh.normals[0]);
        glm_vec3_copy((vec3){ 1.0f, 0.0f, 0.0f }, mesh.normals[1]);
        static resolved r;
        cam.near = cam.far = 0.0;
        draw_and_resolve(&cam, &mesh, 1 + trial % 2, &r);
        int drawn = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                size_t at = (size_t)y * W + (size_t)x;
                if (r.face_ids[at] == 0)
                    continue;
                drawn++;
                real want = nearest_z(&cam, a, b, x, y, NULL);
                cr_assert(fabsl(r.depth[at] - want) <= 1e-6L * want, "trial %d, (%d, %d): depth %.9g, want %.9Lg",
                          trial, x, y, r.depth[at], want);
                cr_assert(r.depth[at] >= (float)cam.near * (1.0f - 1e-6f) && r.depth[at] <= z,
                          "trial %d: depth %.9g outside near %g .. %g", trial, r.depth[at], cam.near, z);
                cr_assert(r.range[at] >= r.depth[at], "trial %d: range %.9g below depth", trial, r.range[at]);
                real n = normal_length(&r, at);
                cr_assert(fabsl(n - 1.0L) < 1e-6L, "trial %d: normal of length %.9Lg", trial, n);
            }
        cr_assert(drawn >= 1, "trial %d: nothing drawn", trial);
        checked += drawn;
        sr_framebuffer_destroy(&r.fb);
    }
    cr_assert(checked > 200, "only %d line pixels checked", checked);
    sr_mesh_free(&mesh);
}

/* Vertex normals that give no direction resolve to a normal of 0, never
 * NaN: a segment across the view whose first end's normal is infinite
 * (every point of it but the other end then has an infinite component),
 * or zero at both ends. The camera is turned at random, so that no entry
 * of its rotation is 0 (0 · inf would make the rotated normal NaN, which
 * resolves to 0 anyway). */
Test(pinhole_sparse, normals_without_a_direction_resolve_to_zero)
{
    test_rng rng = { 8 };
    double rot[3][3];
    rng_rotation(&rng, rot);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            cr_assert(rot[i][j] != 0.0);
    sr_pinhole cam = camera(40.0, 40.0, 31.5, 23.5);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            cam.w2c[i][j] = rot[i][j];
    /* The ends in the camera frame, placed in the file's: Rᵀ · c. */
    const double in_view[2][3] = { { -3.0, 0.4, 5.0 }, { 3.0, -0.3, 7.0 } };
    float ends[2][3];
    for (int e = 0; e < 2; e++)
        for (int j = 0; j < 3; j++)
            ends[e][j] = (float)(rot[0][j] * in_view[e][0] + rot[1][j] * in_view[e][1] + rot[2][j] * in_view[e][2]);
    static const float normal_pairs[][2][3] = { { { INFINITY, 0, 0 }, { 0, 1, 0 } },
                                                { { 0, -INFINITY, 0 }, { 0, 0, -1 } },
                                                { { 0, 0, 0 }, { 0, 0, 0 } } };
    for (size_t p = 0; p < sizeof normal_pairs / sizeof *normal_pairs; p++) {
        sr_mesh mesh;
        one_segment(&mesh, SR_LINE_LIST);
        memcpy(mesh.positions, ends, sizeof ends);
        memcpy(mesh.normals, normal_pairs[p], sizeof normal_pairs[p]);
        static resolved r;
        draw_and_resolve(&cam, &mesh, 1, &r);
        int drawn = 0;
        for (size_t at = 0; at < (size_t)W * H; at++) {
            if (r.face_ids[at] == 0)
                continue;
            drawn++;
            for (int c = 0; c < 3; c++)
                cr_assert(r.normals[3 * at + c] == 0.0f, "pair %zu, pixel %zu: normal[%d] %g", p, at, c,
                          r.normals[3 * at + c]);
        }
        cr_assert_gt(drawn, W / 2, "pair %zu: the segment drew %d pixels", p, drawn);
        sr_framebuffer_destroy(&r.fb);
        sr_mesh_free(&mesh);
    }
}

Test(pinhole_sparse, normals_of_points_without_vertex_normals_are_refused)
{
    sr_error err = { "" };
    sr_mesh mesh;
    cr_assert(sr_mesh_alloc(&mesh, 1, 1, false, false, false, &err), "%s", err.message);
    mesh.topology = SR_POINT_LIST;
    glm_vec3_copy((vec3){ 0.0f, 0.0f, 3.0f }, mesh.positions[0]);
    sr_pinhole cam = camera(40.0, 40.0, 31.5, 23.5);
    static resolved r;
    cr_assert(sr_framebuffer_create(&r.fb, W, H, &err), "%s", err.message);
    sr_pinhole_outputs out = { .normals = r.normals };
    cr_assert_not(sr_pinhole_resolve(&cam, &mesh, &r.fb, &out, &err));
    cr_assert(strstr(err.message, "vertex normals"), "%s", err.message);
    sr_framebuffer_destroy(&r.fb);
    sr_mesh_free(&mesh);
}
