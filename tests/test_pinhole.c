/* Pinhole cameras in OpenCV's convention: a point the pinhole formula puts
 * at a pixel centre is drawn at that pixel, and view depth agrees with a ray
 * cast in long double, written independently of src/scene/pinhole.c (in the
 * world frame, Möller–Trumbore, from the camera-to-world pose). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "softrast_private.h"
#include "test_rng.h"

#define MAX_SIDE 64

typedef long double real;

/* A random rigid camera-to-world pose: a rotation from a random unit
 * quaternion, a translation within `spread`. */
static void random_c2w(test_rng *rng, double spread, double c2w[4][4])
{
    double r[3][3];
    rng_rotation(rng, r);
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            c2w[i][j] = r[i][j];
        c2w[i][3] = rng_uniform(rng, -spread, spread);
        c2w[3][i] = 0.0;
    }
    c2w[3][3] = 1.0;
}

/* A camera-frame point in the world (the file's frame), by c2w. */
static void camera_to_world(const double c2w[4][4], const double p[3], double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = c2w[i][0] * p[0] + c2w[i][1] * p[1] + c2w[i][2] * p[2] + c2w[i][3];
}

/* The mesh's vertex k in the file's frame. */
static void file_point(const sr_mesh *mesh, uint32_t k, real out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = (real)mesh->positions[k][i];
    if (mesh->z_negated)
        out[2] = -out[2];
}

/* The ray through pixel (x, y)'s centre, u = x and v = y, in the world:
 * from the camera centre along c2w's rotation of ((u − cx)/fx, (v − cy)/fy, 1). */
static void pixel_ray(const sr_pinhole *cam, const double c2w[4][4], int x, int y, real origin[3], real dir[3])
{
    real d[3] = { ((real)x - cam->cx) / cam->fx, ((real)y - cam->cy) / cam->fy, 1.0L };
    for (int i = 0; i < 3; i++) {
        origin[i] = c2w[i][3];
        dir[i] = c2w[i][0] * d[0] + c2w[i][1] * d[1] + c2w[i][2] * d[2];
    }
}

static void sub(const real a[3], const real b[3], real out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = a[i] - b[i];
}

static void cross(const real a[3], const real b[3], real out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static real dot(const real a[3], const real b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Möller–Trumbore: the ray parameter t of the hit of origin + t·dir with
 * triangle slot k, or NAN when the ray misses it (with a margin of `slack`
 * in barycentric terms for rays through its edges). With dir's camera z
 * equal to 1, t is the view depth. */
static real ray_hit_at(const sr_mesh *mesh, uint32_t k, const real origin[3], const real dir[3], real slack,
                       real weights[3])
{
    real a[3], b[3], c[3], e1[3], e2[3], p[3], s[3], q[3];
    file_point(mesh, mesh->indices[3 * k], a);
    file_point(mesh, mesh->indices[3 * k + 1], b);
    file_point(mesh, mesh->indices[3 * k + 2], c);
    sub(b, a, e1);
    sub(c, a, e2);
    cross(dir, e2, p);
    real det = dot(e1, p);
    if (det == 0.0L)
        return NAN;
    sub(origin, a, s);
    real u = dot(s, p) / det;
    cross(s, e1, q);
    real v = dot(dir, q) / det;
    if (u < -slack || v < -slack || u + v > 1.0L + slack)
        return NAN;
    if (weights) {
        weights[0] = 1.0L - u - v;
        weights[1] = u;
        weights[2] = v;
    }
    return dot(e2, q) / det;
}

static real ray_hit(const sr_mesh *mesh, uint32_t k, const real origin[3], const real dir[3], real slack)
{
    return ray_hit_at(mesh, k, origin, dir, slack, NULL);
}

/* A file-frame direction in the camera frame: the transpose of c2w's rotation. */
static void world_to_camera_dir(const double c2w[4][4], const real d[3], real out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = c2w[0][i] * d[0] + c2w[1][i] * d[1] + c2w[2][i] * d[2];
}

static void normalize(real v[3])
{
    real length = sqrtl(dot(v, v));
    for (int i = 0; i < 3; i++)
        v[i] /= length;
}

/* Draws mesh in id shading through cam at width x height into fb. */
static void draw_ids_culling(sr_framebuffer *fb, const sr_pinhole *cam, const sr_mesh *mesh, int width, int height,
                             sr_cull cull)
{
    sr_error err = { "" };
    cr_assert(sr_framebuffer_create(fb, width, height, &err), "%s", err.message);
    sr_draw_desc desc = { .mesh = mesh, .shade = SR_SHADE_ID, .cull = cull, .clear = true };
    sr_pinhole_matrices(cam, mesh, fb, &desc);
    cr_assert(sr_draw(fb, &desc, NULL, &err), "%s", err.message);
}

/* The same, culling none, as a ray caster sees both faces. */
static void draw_ids(sr_framebuffer *fb, const sr_pinhole *cam, const sr_mesh *mesh, int width, int height)
{
    draw_ids_culling(fb, cam, mesh, width, height, SR_CULL_NONE);
}

static sr_pinhole camera_of(double fx, double fy, double cx, double cy, const double c2w[4][4])
{
    sr_pinhole cam = { .fx = fx, .fy = fy, .cx = cx, .cy = cy };
    sr_error err = { "" };
    cr_assert(sr_pinhole_pose_from_c2w(c2w, cam.w2c, &err), "%s", err.message);
    return cam;
}

TestSuite(pinhole);

/* Fitted clip planes come from the bounds a mesh keeps when it has them
 * (so a view need not walk the vertices), else from its finite positions:
 * a triangle 10 in front of the camera, kept bounds reaching from 2 to 40
 * in front, the same planes to the bit once the bounds are its own, and
 * again with a fourth vertex at NaN or at inf (which keeps the mesh
 * unbounded). */
Test(pinhole, fitted_planes_take_the_bounds_the_mesh_keeps)
{
    const double c2w[4][4] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 0, 1 } };
    sr_mesh mesh = { 0 };
    sr_error err = { "" };
    cr_assert(sr_mesh_alloc(&mesh, 3, 3, false, false, false, &err), "%s", err.message);
    const float corners[3][3] = { { -1, -1, 10 }, { 1, -1, 10 }, { 0, 1, 10 } };
    for (int k = 0; k < 3; k++) {
        memcpy(mesh.positions[k], corners[k], sizeof corners[k]);
        mesh.indices[k] = (uint32_t)k;
    }
    sr_pinhole walked = camera_of(100, 100, 32, 32, c2w);
    sr_pinhole_fit_clip(&walked, &mesh);
    cr_assert(walked.near > 2.0 && walked.far < 40.0, "from the positions: near %g, far %g", walked.near, walked.far);
    mesh.bounded = true;
    glm_vec3_copy((vec3){ -1, -1, 2 }, mesh.bounds_lo);
    glm_vec3_copy((vec3){ 1, 1, 40 }, mesh.bounds_hi);
    sr_pinhole kept = camera_of(100, 100, 32, 32, c2w);
    sr_pinhole_fit_clip(&kept, &mesh);
    cr_assert(kept.near <= 2.0 && kept.far >= 40.0, "from the kept bounds: near %g, far %g", kept.near, kept.far);
    sr_mesh_update_bounds(&mesh);
    sr_pinhole own = camera_of(100, 100, 32, 32, c2w);
    sr_pinhole_fit_clip(&own, &mesh);
    cr_assert(own.near == walked.near && own.far == walked.far, "kept %g .. %g, walked %g .. %g", own.near, own.far,
              walked.near, walked.far);
    const float bad[2] = { NAN, INFINITY };
    for (int b = 0; b < 2; b++) {
        sr_mesh with_bad = { 0 };
        cr_assert(sr_mesh_alloc(&with_bad, 4, 3, false, false, false, &err), "%s", err.message);
        memcpy(with_bad.positions, mesh.positions, 3 * sizeof(vec3));
        memcpy(with_bad.indices, mesh.indices, 3 * sizeof(uint32_t));
        glm_vec3_copy((vec3){ 0.0f, bad[b], 1.0f }, with_bad.positions[3]);
        sr_mesh_update_bounds(&with_bad);
        cr_assert_not(with_bad.bounded);
        sr_pinhole bad_fit = camera_of(100, 100, 32, 32, c2w);
        sr_pinhole_fit_clip(&bad_fit, &with_bad);
        cr_assert(bad_fit.near == walked.near && bad_fit.far == walked.far, "with a vertex at %g: %g .. %g",
                  (double)bad[b], bad_fit.near, bad_fit.far);
        sr_mesh_free(&with_bad);
    }
    sr_mesh_free(&mesh);
}

/* Smooth normals are scaled by the mesh's finite extent before their cross
 * products: a triangle 1e-25 across gets its unit normal, and keeps it
 * beside a vertex at NaN that no face uses (which left the scale at 1,
 * where the products underflow to 0). */
Test(pinhole, a_vertex_at_nan_leaves_the_others_normals)
{
    for (int with_nan = 0; with_nan < 2; with_nan++) {
        sr_mesh mesh = { 0 };
        sr_error err = { "" };
        cr_assert(sr_mesh_alloc(&mesh, 4, 3, false, false, false, &err), "%s", err.message);
        const float corners[3][3] = { { 0, 0, 0 }, { 1e-25f, 0, 0 }, { 0, 1e-25f, 0 } };
        for (int k = 0; k < 3; k++) {
            memcpy(mesh.positions[k], corners[k], sizeof corners[k]);
            mesh.indices[k] = (uint32_t)k;
        }
        glm_vec3_fill(mesh.positions[3], with_nan ? NAN : 0.0f);
        cr_assert(sr_mesh_compute_normals(&mesh, &err), "%s", err.message);
        cr_assert_float_eq(fabsf(mesh.normals[0][2]), 1.0f, 1e-6f, "%s: normal (%g, %g, %g)",
                           with_nan ? "with a NaN vertex" : "alone", mesh.normals[0][0], mesh.normals[0][1],
                           mesh.normals[0][2]);
        sr_mesh_free(&mesh);
    }
}

/* A point X that the pinhole formula puts exactly at pixel centre (u, v)
 * lies inside a small triangle whose corners project 1/64 to 0.6 px around
 * it (so at least 1/128 px inside every edge, and a camera off by half a
 * pixel misses it): pixel (u, v) shows that triangle,
 * and its view depth is the ray cast's within one float ulp. Off-centre
 * principal points, fx ≠ fy, random poses, meshes read from files (z
 * negated) and made in code. */
Test(pinhole, a_point_projected_to_a_pixel_centre_is_drawn_there_at_its_depth)
{
    test_rng rng = { 20261129 };
    for (int trial = 0; trial < 400; trial++) {
        int width = 8 + rng_below(&rng, MAX_SIDE - 8), height = 8 + rng_below(&rng, MAX_SIDE - 8);
        double fx = rng_uniform(&rng, 5.0, 400.0), fy = fx * rng_uniform(&rng, 0.5, 2.0);
        double cx = rng_uniform(&rng, -0.5, 1.5) * width, cy = rng_uniform(&rng, -0.5, 1.5) * height;
        double c2w[4][4];
        random_c2w(&rng, 100.0, c2w);
        sr_pinhole cam = camera_of(fx, fy, cx, cy, c2w);
        int u = rng_below(&rng, width), v = rng_below(&rng, height);
        double z = exp(rng_uniform(&rng, log(0.5), log(500.0)));
        double turn = rng_uniform(&rng, 0.0, 2.0 * GLM_PI), r = rng_uniform(&rng, 1.0 / 64.0, 0.6);
        sr_mesh mesh = { 0 };
        sr_error err = { "" };
        cr_assert(sr_mesh_alloc(&mesh, 3, 3, false, false, false, &err), "%s", err.message);
        mesh.z_negated = trial % 2;
        for (int k = 0; k < 3; k++) {
            double du = r * cos(turn + 2.0 * GLM_PI * k / 3.0), dv = r * sin(turn + 2.0 * GLM_PI * k / 3.0);
            double zk = z * rng_uniform(&rng, 0.8, 1.25);
            double p[3] = { (u + du - cx) * zk / fx, (v + dv - cy) * zk / fy, zk }, world[3];
            camera_to_world(c2w, p, world);
            for (int i = 0; i < 3; i++)
                mesh.positions[k][i] = (float)(i == 2 && mesh.z_negated ? -world[i] : world[i]);
            mesh.indices[k] = (uint32_t)k;
        }
        sr_pinhole_fit_clip(&cam, &mesh);
        sr_framebuffer fb;
        draw_ids(&fb, &cam, &mesh, width, height);
        size_t at = (size_t)v * (size_t)width + (size_t)u;
        cr_assert_eq(fb.color[at], 1u, "trial %d: pixel (%d, %d) of %dx%d shows %#x, not the triangle", trial, u, v,
                     width, height, fb.color[at]);
        float depth[MAX_SIDE * MAX_SIDE];
        cr_assert(sr_pinhole_resolve(&cam, &mesh, &fb, &(sr_pinhole_outputs){ .depth = depth }, &err), "%s",
                  err.message);
        real origin[3], dir[3];
        pixel_ray(&cam, c2w, u, v, origin, dir);
        real want = ray_hit(&mesh, 0, origin, dir, 1e-6L);
        cr_assert(isfinite((double)want), "trial %d: the reference ray misses its own triangle", trial);
        cr_assert_leq(fabsl(depth[at] - want) / want, 0x1p-23L, "trial %d: depth %.9g, ray cast %.12Lg", trial,
                      depth[at], want);
        sr_framebuffer_destroy(&fb);
        sr_mesh_free(&mesh);
    }
}

static int compare_reals(const void *a, const void *b)
{
    real x = *(const real *)a, y = *(const real *)b;
    return (x > y) - (x < y);
}

/* Random triangles at distances from 0.02 to 5000 (near 0.01, far 1e4),
 * every fifth at a grazing angle to the rays that meet it (its corners'
 * depths 0.2, 1 and 5 times apart): wherever the pixel shows
 * the triangle a long-double ray cast finds nearest, view depth is within
 * 1.2e-7 of it (relative) at p99.9 and 1e-6 at most; range is view depth
 * times the ray's length. */
Test(pinhole, view_depth_agrees_with_a_ray_cast_near_and_far)
{
    enum { W = 64, H = 48, TRIANGLES = 120 };
    test_rng rng = { 7 };
    double c2w[4][4];
    random_c2w(&rng, 10.0, c2w);
    sr_pinhole cam = camera_of(52.0, 47.0, 30.2, 25.7, c2w);
    cam.near = 0.01;
    cam.far = 1e4;
    sr_mesh mesh = { 0 };
    sr_error err = { "" };
    cr_assert(sr_mesh_alloc(&mesh, 3 * TRIANGLES, 3 * TRIANGLES, false, false, false, &err), "%s", err.message);
    for (uint32_t t = 0; t < TRIANGLES; t++) {
        double z = exp(rng_uniform(&rng, log(0.02), log(5000.0)));
        double cu = rng_uniform(&rng, 0, W), cv = rng_uniform(&rng, 0, H), size = rng_uniform(&rng, 3.0, 30.0);
        bool edge_on = t % 5 == 0;
        for (int k = 0; k < 3; k++) {
            double du = rng_uniform(&rng, -size, size), dv = rng_uniform(&rng, -size, size);
            static const double steep[3] = { 0.2, 1.0, 5.0 }; /* a plane at a grazing angle to the rays */
            double zk = z * (edge_on ? steep[k] : rng_uniform(&rng, 0.7, 1.4));
            double p[3] = { (cu + du - cam.cx) * zk / cam.fx, (cv + dv - cam.cy) * zk / cam.fy, zk }, world[3];
            camera_to_world(c2w, p, world);
            for (int i = 0; i < 3; i++)
                mesh.positions[3 * t + k][i] = (float)world[i];
            mesh.indices[3 * t + k] = 3 * t + (uint32_t)k;
        }
    }
    sr_framebuffer fb;
    draw_ids(&fb, &cam, &mesh, W, H);
    float depth[W * H], range[W * H];
    cr_assert(sr_pinhole_resolve(&cam, &mesh, &fb, &(sr_pinhole_outputs){ .depth = depth, .range = range, .invalid = -1.0f },
                                  &err),
              "%s", err.message);
    real errors[W * H];
    int compared = 0, edge_on_compared = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            real origin[3], dir[3], best = INFINITY;
            uint32_t nearest = 0;
            pixel_ray(&cam, c2w, x, y, origin, dir);
            for (uint32_t t = 0; t < TRIANGLES; t++) {
                real hit = ray_hit(&mesh, t, origin, dir, 0.0L);
                if (hit > cam.near && hit < cam.far && hit < best) {
                    best = hit;
                    nearest = t + 1;
                }
            }
            size_t at = (size_t)y * W + (size_t)x;
            if (fb.color[at] == 0) {
                cr_assert_eq(depth[at], -1.0f, "(%d, %d): nothing drawn, depth %g", x, y, depth[at]);
                continue;
            }
            if (fb.color[at] != nearest) /* visibility: another slice's bound */
                continue;
            errors[compared++] = fabsl(depth[at] - best) / best;
            edge_on_compared += (nearest - 1) % 5 == 0;
            real length = sqrtl(dot(dir, dir));
            cr_assert_leq(fabsl(range[at] - best * length) / (best * length), 1e-6L, "(%d, %d): range %.9g", x, y,
                          range[at]);
        }
    cr_assert_gt(compared, W * H / 4, "only %d pixels compared", compared);
    cr_assert_gt(edge_on_compared, 0, "no edge-on triangle compared");
    qsort(errors, (size_t)compared, sizeof *errors, compare_reals);
    real p999 = errors[(int)(0.999 * (compared - 1))], worst = errors[compared - 1];
    cr_assert_leq(p999, 1.2e-7L, "p99.9 relative error %.3Lg", p999);
    cr_assert_leq(worst, 1e-6L, "max relative error %.3Lg", worst);
    sr_framebuffer_destroy(&fb);
    sr_mesh_free(&mesh);
}

/* The checks a caller's camera gets, one line each. */
Test(pinhole, bad_cameras_are_refused_with_one_line)
{
    double c2w[4][4] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 0, 1 } };
    sr_pinhole good = camera_of(100, 100, 31.5, 23.5, c2w);
    sr_error err = { "" };
    cr_assert(sr_pinhole_check(&good, &err), "%s", err.message);
    struct {
        const char *why, *needle;
        sr_pinhole cam;
    } bad[] = {
        { "fx 0", "fx and fy", good },          { "fy negative", "fx and fy", good },
        { "cx NaN", "finite", good },           { "scaled pose", "rigid", good },
        { "mirrored pose", "rigid", good },     { "last row", "rigid", good },
        { "inf in the pose", "finite", good },  { "near above far", "near < far", good },
    };
    bad[0].cam.fx = 0;
    bad[1].cam.fy = -1;
    bad[2].cam.cx = NAN;
    bad[3].cam.w2c[0][0] = 2;
    bad[4].cam.w2c[2][2] = -1;
    bad[5].cam.w2c[3][0] = 0.5;
    bad[6].cam.w2c[1][3] = INFINITY;
    bad[7].cam.near = 10;
    bad[7].cam.far = 1;
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        err.message[0] = '\0';
        cr_assert_not(sr_pinhole_check(&bad[i].cam, &err), "%s accepted", bad[i].why);
        cr_assert_not_null(strstr(err.message, bad[i].needle), "%s: '%s'", bad[i].why, err.message);
        cr_assert_null(strchr(err.message, '\n'), "%s: more than a line", bad[i].why);
    }
    double sheared[4][4] = { { 1, 0.1, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 0, 1 } }, w2c[4][4];
    cr_assert_not(sr_pinhole_pose_from_c2w(sheared, w2c, &err), "a sheared camera-to-world pose accepted");
}

/* The resolve takes an ids plane on trust only from a draw of its mesh:
 * a plane drawn from another mesh (an id past this one's triangles, or
 * one whose corners this one lacks), a camera sr_pinhole_check refuses or
 * one whose clip planes are unset, and a framebuffer without pixels are
 * each one line and false, on one thread and on three, for triangles and
 * for points; the plane of its own draw resolves. */
Test(pinhole, a_resolve_refuses_what_is_no_draw_of_its_mesh)
{
    double c2w[4][4] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 0, 1 } };
    sr_error err = { "" };
    sr_mesh drawn, fewer, lacking;
    /* Two triangles (or six points) in the middle of the view at z = 2,
     * and a mesh of one (or three). */
    cr_assert(sr_mesh_alloc(&drawn, 4, 6, false, false, false, &err), "%s", err.message);
    const float corners[4][3] = { { -0.6f, -0.6f, 2 }, { 0.6f, -0.6f, 2 }, { 0.6f, 0.6f, 2 }, { -0.6f, 0.6f, 2 } };
    const uint32_t quad[6] = { 0, 1, 2, 0, 2, 3 };
    memcpy(drawn.positions, corners, sizeof corners);
    memcpy(drawn.indices, quad, sizeof quad);
    cr_assert(sr_mesh_alloc(&fewer, 4, 3, false, false, false, &err), "%s", err.message);
    memcpy(fewer.positions, corners, sizeof corners);
    memcpy(fewer.indices, quad, 3 * sizeof *quad);
    /* The same indices over three vertices: the second triangle names a fourth. */
    cr_assert(sr_mesh_alloc(&lacking, 3, 6, false, false, false, &err), "%s", err.message);
    memcpy(lacking.positions, corners, 3 * sizeof *corners);
    memcpy(lacking.indices, quad, sizeof quad);
    for (int points = 0; points < 2; points++) {
        drawn.topology = fewer.topology = lacking.topology = points ? SR_POINT_LIST : SR_TRIANGLE_LIST;
        sr_pinhole cam = camera_of(8, 8, 7.5, 7.5, c2w);
        sr_pinhole_fit_clip(&cam, &drawn);
        sr_framebuffer fb;
        draw_ids(&fb, &cam, &drawn, 16, 16);
        float depth[16 * 16];
        for (int threads = 1; threads <= 3; threads += 2) {
            sr_pinhole_outputs out = { .depth = depth, .threads = threads };
            cr_assert(sr_pinhole_resolve(&cam, &drawn, &fb, &out, &err), "%s", err.message);
            const sr_mesh *strangers[2] = { &fewer, &lacking };
            for (int m = 0; m < 2; m++) {
                err.message[0] = '\0';
                cr_assert_not(sr_pinhole_resolve(&cam, strangers[m], &fb, &out, &err),
                              "points %d, threads %d: the plane of another mesh resolved (%d)", points, threads, m);
                cr_assert(strstr(err.message, "not a draw of this mesh") && !strchr(err.message, '\n'), "%s",
                          err.message);
            }
            sr_pinhole unfitted = camera_of(8, 8, 7.5, 7.5, c2w), bent = cam;
            bent.w2c[0][0] = 2;
            cr_assert_not(sr_pinhole_resolve(&unfitted, &drawn, &fb, &out, &err));
            cr_assert(strstr(err.message, "clip planes"), "%s", err.message);
            cr_assert_not(sr_pinhole_resolve(&bent, &drawn, &fb, &out, &err));
            cr_assert(strstr(err.message, "rigid"), "%s", err.message);
            sr_framebuffer empty = fb;
            empty.height = 0;
            cr_assert_not(sr_pinhole_resolve(&cam, &drawn, &empty, &out, &err));
            cr_assert(strstr(err.message, "no pixels"), "%s", err.message);
        }
        sr_framebuffer_destroy(&fb);
    }
    sr_mesh_free(&drawn);
    sr_mesh_free(&fewer);
    sr_mesh_free(&lacking);
}

/* An ids plane with ids past the mesh's triangles on every row from row
 * 40 on, so that every thread past it meets one: the error names the
 * first in raster order, on every thread count. */
Test(pinhole, a_resolve_names_the_first_stranger_whatever_the_threads)
{
    double c2w[4][4] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 0, 1 } };
    sr_error err = { "" };
    sr_mesh mesh;
    cr_assert(sr_mesh_alloc(&mesh, 3, 3, false, false, false, &err), "%s", err.message);
    const float corners[3][3] = { { -0.6f, -0.6f, 2 }, { 0.6f, -0.6f, 2 }, { 0.6f, 0.6f, 2 } };
    memcpy(mesh.positions, corners, sizeof corners);
    for (uint32_t i = 0; i < 3; i++)
        mesh.indices[i] = i;
    sr_pinhole cam = camera_of(8, 8, 7.5, 7.5, c2w);
    sr_pinhole_fit_clip(&cam, &mesh);
    enum { W = 16, H = 96 };
    sr_framebuffer fb;
    cr_assert(sr_framebuffer_create(&fb, W, H, &err) && sr_framebuffer_create_ids(&fb, &err), "%s", err.message);
    sr_framebuffer_clear(&fb, 0);
    /* Its own triangle everywhere, then strangers: 7 at row 40, and each
     * row after one of its own, 1000 + row. */
    for (int i = 0; i < W * H; i++)
        fb.ids[i] = 1;
    fb.ids[40 * W + 12] = 7;
    for (int y = 41; y < H; y++)
        fb.ids[y * W + (y * 5) % W] = 1000 + (uint32_t)y;
    float depth[W * H];
    for (int threads = 1; threads <= 8; threads++) {
        sr_pinhole_outputs out = { .depth = depth, .threads = threads };
        cr_assert_not(sr_pinhole_resolve(&cam, &mesh, &fb, &out, &err), "threads %d: resolved", threads);
        cr_assert(strstr(err.message, "holds id 7,"), "threads %d: %s", threads, err.message);
    }
    sr_framebuffer_destroy(&fb);
    sr_mesh_free(&mesh);
}

/* The rigid inverse: w2c · c2w is the identity. */
Test(pinhole, the_pose_from_c2w_inverts_it)
{
    test_rng rng = { 99 };
    for (int trial = 0; trial < 100; trial++) {
        double c2w[4][4], w2c[4][4];
        random_c2w(&rng, 1000.0, c2w);
        sr_error err = { "" };
        cr_assert(sr_pinhole_pose_from_c2w(c2w, w2c, &err), "%s", err.message);
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) {
                double sum = 0;
                for (int k = 0; k < 4; k++)
                    sum += w2c[i][k] * c2w[k][j];
                cr_assert(fabs(sum - (i == j)) < 1e-9 * (1 + fabs(c2w[i][3])), "(%d, %d): %g", i, j, sum);
            }
    }
}

/* Two parts of random triangles, made in code and as if read from a file
 * (z negated, winding reversed as the loaders do): face ids are the id
 * view's, part ids the part + 1, and the geometric normal is the unit
 * e1 × e2 of the file's winding in the camera frame; the interpolated
 * normal is the vertex normals weighted by the ray cast's barycentrics. */
Test(pinhole, ids_parts_and_normals_follow_the_file)
{
    enum { W = 48, H = 40, TRIANGLES = 40 };
    for (int from_file = 0; from_file < 2; from_file++) {
        test_rng rng = { 31 + (uint64_t)from_file };
        double c2w[4][4];
        random_c2w(&rng, 5.0, c2w);
        sr_pinhole cam = camera_of(40.0, 44.0, 23.3, 19.9, c2w);
        sr_mesh mesh = { 0 };
        sr_error err = { "" };
        cr_assert(sr_mesh_alloc(&mesh, 3 * TRIANGLES, 3 * TRIANGLES, true, false, false, &err), "%s", err.message);
        sr_mesh_part parts[2] = { { 0, 15 }, { 15, TRIANGLES - 15 } };
        mesh.parts = parts;
        mesh.part_count = 2;
        mesh.z_negated = from_file;
        for (uint32_t v = 0; v < 3 * TRIANGLES; v++) {
            double z = rng_uniform(&rng, 2.0, 9.0);
            double p[3] = { (rng_uniform(&rng, -5, W + 5) - cam.cx) * z / cam.fx,
                            (rng_uniform(&rng, -5, H + 5) - cam.cy) * z / cam.fy, z }, world[3];
            camera_to_world(c2w, p, world);
            real n[3] = { rng_uniform(&rng, -1, 1), rng_uniform(&rng, -1, 1), rng_uniform(&rng, -1, 1) };
            normalize(n);
            for (int i = 0; i < 3; i++) {
                bool flip = i == 2 && from_file;
                mesh.positions[v][i] = (float)(flip ? -world[i] : world[i]);
                mesh.normals[v][i] = (float)(flip ? -n[i] : n[i]);
            }
            /* a file's winding is reversed by its loader */
            mesh.indices[v] = from_file ? 3 * (v / 3) + 2 - v % 3 : v;
        }
        sr_pinhole_fit_clip(&cam, &mesh);
        sr_framebuffer fb;
        draw_ids(&fb, &cam, &mesh, W, H);
        static uint32_t faces[W * H], part_ids[W * H];
        static float geometric[3 * W * H], smooth[3 * W * H];
        cr_assert(sr_pinhole_resolve(&cam, &mesh, &fb,
                                      &(sr_pinhole_outputs){ .face_ids = faces, .part_ids = part_ids,
                                                             .normals = geometric },
                                      &err),
                  "%s", err.message);
        cr_assert(sr_pinhole_resolve(&cam, &mesh, &fb,
                                      &(sr_pinhole_outputs){ .normals = smooth, .interpolated_normals = true }, &err),
                  "%s", err.message);
        int drawn = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                size_t at = (size_t)y * W + (size_t)x;
                cr_assert_eq(faces[at], fb.color[at]);
                if (!faces[at]) {
                    cr_assert_eq(part_ids[at], 0u);
                    continue;
                }
                drawn++;
                uint32_t t = faces[at] - 1;
                cr_assert_eq(part_ids[at], t < 15 ? 1u : 2u, "(%d, %d): triangle %u in part %u", x, y, t,
                             part_ids[at]);
                /* the file's own corners, in its order */
                uint32_t corner[3];
                for (int k = 0; k < 3; k++)
                    corner[k] = from_file ? mesh.indices[3 * t + 2 - k] : mesh.indices[3 * t + k];
                real a[3], b[3], c[3], e1[3], e2[3], n[3], want[3];
                file_point(&mesh, corner[0], a);
                file_point(&mesh, corner[1], b);
                file_point(&mesh, corner[2], c);
                sub(b, a, e1);
                sub(c, a, e2);
                cross(e1, e2, n);
                world_to_camera_dir(c2w, n, want);
                normalize(want);
                for (int i = 0; i < 3; i++)
                    cr_assert_leq(fabsl(geometric[3 * at + i] - want[i]), 1e-6L, "(%d, %d): geometric normal", x,
                                  y);
                real origin[3], dir[3], weights[3], sum[3] = { 0 };
                pixel_ray(&cam, c2w, x, y, origin, dir);
                real hit = ray_hit_at(&mesh, t, origin, dir, 1e-3L, weights);
                if (!isfinite((double)hit)) /* a centre on the snapped edge, off the exact triangle */
                    continue;
                for (int k = 0; k < 3; k++) {
                    uint32_t v = mesh.indices[3 * t + k];
                    real nv[3] = { mesh.normals[v][0], mesh.normals[v][1], mesh.normals[v][2] }, nc[3];
                    if (from_file)
                        nv[2] = -nv[2];
                    world_to_camera_dir(c2w, nv, nc);
                    for (int i = 0; i < 3; i++)
                        sum[i] += weights[k] * nc[i];
                }
                normalize(sum);
                for (int i = 0; i < 3; i++)
                    cr_assert_leq(fabsl(smooth[3 * at + i] - sum[i]), 1e-5L, "(%d, %d): interpolated normal %d", x,
                                  y, i);
            }
        cr_assert_gt(drawn, W * H / 3, "%d pixels drawn", drawn);
        mesh.parts = NULL;
        sr_framebuffer_destroy(&fb);
        sr_mesh_free(&mesh);
    }
}

/* The room read from its OBJ file (z negated) through a pinhole camera
 * posed in the file's frame where the look-at camera of the README stands
 * (eye −8,3,−8, target 4,1.5,6 in softrast's world: z negated in the
 * file's), with the look-at camera's vertical fov and a centred principal
 * point: both show the same triangle at all but a few pixels on edges (the
 * two projections round differently). */
Test(pinhole, a_pose_in_the_files_frame_sees_what_the_look_at_camera_sees)
{
    enum { W = 160, H = 120 };
    sr_mesh mesh;
    sr_error err = { "" };
    cr_assert(sr_obj_load(&mesh, "assets/room.obj", &err), "%s", err.message);
    cr_assert(mesh.z_negated, "a loaded mesh is z-negated");
    sr_camera look = sr_camera_default();
    glm_vec3_copy((vec3){ -8, 3, -8 }, look.eye);
    glm_vec3_copy((vec3){ 4, 1.5f, 6 }, look.target);
    look.fov_deg = 75;
    sr_framebuffer a, b;
    cr_assert(sr_framebuffer_create(&a, W, H, &err), "%s", err.message);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_ID, .clear = true };
    sr_camera_view(&look, desc.view);
    sr_camera_projection(&look, (float)W / H, desc.projection);
    cr_assert(sr_draw(&a, &desc, NULL, &err), "%s", err.message);
    /* OpenCV's axes in the file's frame: forward, right = forward x up, down */
    double eye[3] = { -8, 3, 8 }, f[3] = { 12, -1.5, -14 }, len = sqrt(12 * 12 + 1.5 * 1.5 + 14 * 14);
    for (int k = 0; k < 3; k++)
        f[k] /= len;
    double r[3] = { -f[2], 0, f[0] }, rl = sqrt(f[0] * f[0] + f[2] * f[2]);
    for (int k = 0; k < 3; k++)
        r[k] /= rl;
    double up[3] = { r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0] };
    double c2w[4][4] = { { r[0], -up[0], f[0], eye[0] }, { r[1], -up[1], f[1], eye[1] },
                         { r[2], -up[2], f[2], eye[2] }, { 0, 0, 0, 1 } };
    double fy = 0.5 * H / tan(0.5 * 75 * GLM_PI / 180);
    sr_pinhole cam = camera_of(fy, fy, 0.5 * (W - 1), 0.5 * (H - 1), c2w);
    sr_pinhole_fit_clip(&cam, &mesh);
    draw_ids_culling(&b, &cam, &mesh, W, H, SR_CULL_BACK); /* as the look-at camera culls */
    int differ = 0, drawn = 0;
    for (int i = 0; i < W * H; i++) {
        differ += a.color[i] != b.color[i];
        drawn += a.color[i] != 0;
    }
    cr_assert_gt(drawn, W * H / 2, "the look-at camera drew %d pixels", drawn);
    cr_assert_lt(differ, W * H / 100, "%d of %d pixels show another triangle", differ, W * H);
    sr_framebuffer_destroy(&a);
    sr_framebuffer_destroy(&b);
    sr_mesh_free(&mesh);
}

/* A closed torus 1000 units away (near 1, far 2000, culling off), seen
 * with a long lens: at its silhouettes the back of the tube comes within
 * float depth steps of the front. No pixel may show a triangle whose
 * exact depth at the pixel centre lies more than 1e-6 (relative) behind
 * the nearest triangle's there (a long-double ray cast over all of them). */
Test(pinhole, far_away_no_back_face_wins_over_the_front)
{
    enum { W = 40, H = 40 };
    sr_mesh mesh;
    sr_error err = { "" };
    cr_assert(sr_shape_torus(&mesh, 1.0f, 0.4f, 48, 24, &err), "%s", err.message);
    /* 1000 away at -z, 30 degrees up, looking at the centre: x right (-x of the
     * world, seen from -z), y down, z forward */
    double c = cos(30 * GLM_PI / 180), s = sin(30 * GLM_PI / 180);
    double c2w[4][4] = { { -1, 0, 0, 0 }, { 0, -c, -s, 1000 * s }, { 0, -s, c, -1000 * c }, { 0, 0, 0, 1 } };
    sr_pinhole cam = camera_of(14000, 14000, 19.5, 19.5, c2w);
    cam.near = 1;
    cam.far = 2000;
    sr_framebuffer fb;
    draw_ids(&fb, &cam, &mesh, W, H);
    int drawn = 0, behind = 0;
    real worst = 0;
    uint32_t slots = sr_mesh_triangle_slots(&mesh);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            uint32_t id = fb.color[(size_t)y * W + (size_t)x];
            if (!id)
                continue;
            drawn++;
            real origin[3], dir[3], best = INFINITY;
            pixel_ray(&cam, c2w, x, y, origin, dir);
            for (uint32_t k = 0; k < slots; k++) {
                real hit = ray_hit(&mesh, k, origin, dir, 0.0L);
                if (hit > 0 && hit < best)
                    best = hit;
            }
            real shown = ray_hit(&mesh, id - 1, origin, dir, 1e-3L); /* its plane, near its edges too */
            if (!isfinite((double)best) || !isfinite((double)shown))
                continue;
            real gap = (shown - best) / best;
            worst = gap > worst ? gap : worst;
            behind += gap > 1e-6L;
        }
    cr_assert_gt(drawn, W * H / 8, "%d pixels drawn", drawn);
    cr_assert_eq(behind, 0, "%d pixels show a triangle behind the nearest (worst %.3Lg relative)", behind, worst);
    sr_framebuffer_destroy(&fb);
    sr_mesh_free(&mesh);
}
