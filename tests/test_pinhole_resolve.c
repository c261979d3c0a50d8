/* sr_pinhole_resolve, which works in runs of pixels that show one triangle
 * with a loop per output, gives bit for bit what the per-pixel formula
 * gives: each pixel's ray ((x − cx)/fx, (y − cy)/fy, 1) met with the plane
 * of its triangle's camera-frame corners in double, the depth buffer's
 * value where the ray runs in that plane or meets it outside the clip
 * planes (by more than 1/256 of them). The formula is written out here
 * pixel by pixel; the ids planes are random runs (any length, gaps of
 * nothing), so every run length and alignment is met, on random meshes
 * (parts, z negated or not) and poses, with triangles through the camera
 * centre, whose rays all run in their planes, with a corner 2^-140 from it,
 * whose planes rays meet next to it, and in a plane x = 1 that the rays of
 * column cx meet at infinity. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pipeline/08_raster/simd_select.h"
#include "scene/pinhole_triangles.h"
#include "softrast_private.h"
#include "test_rng.h"

TestSuite(pinhole_resolve);

/* The mesh's vertex k in the camera frame, in double. */
static void camera_point(const sr_pinhole *cam, const sr_mesh *mesh, uint32_t k, double out[3])
{
    double file[3] = { mesh->origin[0] + mesh->positions[k][0], mesh->origin[1] + mesh->positions[k][1],
                       mesh->origin[2] + mesh->positions[k][2] };
    if (mesh->z_negated)
        file[2] = -file[2];
    for (int r = 0; r < 3; r++)
        out[r] = cam->w2c[r][0] * file[0] + cam->w2c[r][1] * file[1] + cam->w2c[r][2] * file[2] + cam->w2c[r][3];
}

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static void unit_into(const double v[3], float out[3])
{
    double length = sqrt(dot(v, v));
    for (int k = 0; k < 3; k++)
        out[k] = length > 0.0 ? (float)(v[k] / length) : 0.0f;
}

/* The outputs of one pixel showing triangle `slot`, by the formula. */
typedef struct pixel {
    float depth, range, normal[3], smooth[3];
    uint32_t part;
} pixel;

static pixel formula(const sr_pinhole *cam, const sr_mesh *mesh, uint32_t slot, int x, int y, float stored)
{
    pixel px;
    double v[3][3], e1[3], e2[3], c[3];
    for (int k = 0; k < 3; k++)
        camera_point(cam, mesh, mesh->indices[3 * slot + (uint32_t)k], v[k]);
    for (int k = 0; k < 3; k++) {
        e1[k] = v[1][k] - v[0][k];
        e2[k] = v[2][k] - v[0][k];
    }
    cross(e1, e2, c);
    const double ray[3] = { (x - cam->cx) / cam->fx, (y - cam->cy) / cam->fy, 1.0 };
    double z = dot(c, v[0]) / dot(c, ray);
    if (!(z >= cam->near * (1.0 - 0x1p-8) && z <= cam->far * (1.0 + 0x1p-8))) /* met outside the clip planes */
        z = cam->far * cam->near / ((double)stored * (cam->far - cam->near) + cam->near);
    double p[3] = { z * ray[0], z * ray[1], z * ray[2] };
    px.depth = (float)z;
    px.range = (float)sqrt(dot(p, p));
    double front[3]; /* the loader reversed a z-negated file's winding */
    for (int k = 0; k < 3; k++)
        front[k] = mesh->z_negated ? -c[k] : c[k];
    unit_into(front, px.normal);
    double w[3], a[3], b[3], vn[3][3], n[3];
    for (int k = 0; k < 3; k++)
        w[k] = p[k] - v[0][k];
    cross(w, e2, a);
    cross(e1, w, b);
    double cc = dot(c, c), l1 = dot(c, a) / cc, l2 = dot(c, b) / cc;
    for (int corner = 0; corner < 3; corner++) {
        const float *fn = mesh->normals[mesh->indices[3 * slot + (uint32_t)corner]];
        double file[3] = { fn[0], fn[1], mesh->z_negated ? -(double)fn[2] : fn[2] };
        for (int r = 0; r < 3; r++)
            vn[corner][r] = cam->w2c[r][0] * file[0] + cam->w2c[r][1] * file[1] + cam->w2c[r][2] * file[2];
    }
    for (int k = 0; k < 3; k++)
        n[k] = (1.0 - l1 - l2) * vn[0][k] + l1 * vn[1][k] + l2 * vn[2][k];
    unit_into(n, px.smooth);
    px.part = 1;
    for (uint32_t i = 0; i < mesh->part_count; i++)
        if (mesh->parts[i].first_triangle <= slot)
            px.part = i + 1;
    return px;
}

/* A random rotation into cam's pose, and the mesh's origin a million
 * units from the world's: no product exact. */
static void turn_and_move_away(test_rng *rng, sr_pinhole *cam, sr_mesh *mesh)
{
    double rotation[3][3];
    rng_rotation(rng, rotation);
    for (int r = 0; r < 3; r++) {
        mesh->origin[r] = rng_uniform(rng, -1e6, 1e6);
        for (int c = 0; c < 3; c++)
            cam->w2c[r][c] = rotation[r][c];
    }
}

#define SIDE_MAX 70
#define TRIANGLES 300 /* past the resolve's cache of 256, whose entries two triangles then share */
#define PARTS 4

/* 30 random scenes: a camera at the origin looking along +z (so a vertex
 * at the origin is the camera centre), or one at a random rotation, the
 * mesh's origin a million units away; triangles
 * in front of it, a third of them with a corner at the origin and a third
 * in the plane x = 1 (the camera's cx then a whole pixel); an ids
 * plane of random runs and a random depth buffer, half its runs showing
 * triangles 256 apart, which share an entry of the resolve's cache, so
 * rows hold both; resolved on 1 to 4 threads, both normal kinds, and held
 * to the formula bit for bit. */
Test(pinhole_resolve, runs_and_loops_per_output_give_the_per_pixel_formulas_bits)
{
    test_rng rng = { 0x5EED0034u };
    sr_error err = { "" };
    static float depth[SIDE_MAX * SIDE_MAX], range[SIDE_MAX * SIDE_MAX], normals[3 * SIDE_MAX * SIDE_MAX];
    static uint32_t face_ids[SIDE_MAX * SIDE_MAX], part_ids[SIDE_MAX * SIDE_MAX];
    size_t edge_on = 0, sharing_rows = 0;
    for (int scene = 0; scene < 30; scene++) {
        sr_mesh mesh;
        cr_assert(sr_mesh_alloc(&mesh, 3 * TRIANGLES, 3 * TRIANGLES, true, false, false, &err), "%s", err.message);
        mesh.z_negated = scene % 2;
        bool centred = scene % 3 != 2;
        for (uint32_t v = 0; v < 3 * TRIANGLES; v++) {
            mesh.indices[v] = v;
            for (int k = 0; k < 3; k++) {
                mesh.positions[v][k] = (float)rng_uniform(&rng, -3.0, 3.0);
                mesh.normals[v][k] = (float)rng_uniform(&rng, -1.0, 1.0);
            }
            mesh.positions[v][2] = (float)(mesh.z_negated ? -1.0 : 1.0) * (float)rng_uniform(&rng, 0.5, 9.0);
            if (centred && v % 9 == 0) /* the camera centre: every ray runs in this triangle's plane */
                mesh.positions[v][0] = mesh.positions[v][1] = mesh.positions[v][2] = 0.0f;
            if (centred && v % 9 >= 3 && v % 9 < 6) /* the plane x = 1: column cx's rays meet it at infinity */
                mesh.positions[v][0] = 1.0f;
            if (centred && v % 9 == 6) { /* a plane by the eye: rays meet it next to the camera centre */
                mesh.positions[v][0] = 0x1p-140f;
                mesh.positions[v][1] = mesh.positions[v][2] = 0.0f;
            }
        }
        sr_mesh_part parts[PARTS] = { { 0, 7 }, { 7, 13 }, { 20, 1 }, { 21, TRIANGLES - 21 } };
        mesh.parts = parts;
        mesh.part_count = scene % 4 == 3 ? 0 : PARTS;
        sr_pinhole cam = { .fx = rng_uniform(&rng, 20.0, 80.0), .fy = rng_uniform(&rng, 20.0, 80.0),
                           .cx = rng_uniform(&rng, 0.0, 60.0), .cy = rng_uniform(&rng, 0.0, 60.0),
                           .near = 0.25, .far = 12.0 };
        for (int k = 0; k < 4; k++)
            cam.w2c[k][k] = 1.0;
        if (centred) {
            cam.cx = rng_below(&rng, 60);
        } else {
            turn_and_move_away(&rng, &cam, &mesh);
            for (int r = 0; r < 3; r++) /* the camera near the mesh, along its rotated positions */
                cam.w2c[r][3] = -(cam.w2c[r][0] * mesh.origin[0] + cam.w2c[r][1] * mesh.origin[1] +
                                  cam.w2c[r][2] * (mesh.z_negated ? -mesh.origin[2] : mesh.origin[2])) +
                                rng_uniform(&rng, -1.0, 1.0);
        }
        int width = 1 + rng_below(&rng, SIDE_MAX), height = 1 + rng_below(&rng, SIDE_MAX);
        sr_framebuffer fb;
        cr_assert(sr_framebuffer_create(&fb, width, height, &err) && sr_framebuffer_create_ids(&fb, &err), "%s",
                  err.message);
        for (int i = 0; i < width * height;) {
            uint32_t id = rng_below(&rng, 4) == 0 ? 0
                          : rng_below(&rng, 2)    ? 1 + (uint32_t)rng_below(&rng, TRIANGLES)
                                                  : 1 + (uint32_t)rng_below(&rng, 4) + 256u * (uint32_t)rng_below(&rng, 2);
            for (int n = 1 + rng_below(&rng, 1 + rng_below(&rng, 24)); n > 0 && i < width * height; n--, i++) {
                fb.ids[i] = id;
                fb.depth[i] = (float)rng_uniform(&rng, 0.0, 1.0);
            }
        }
        for (int y = 0; y < height; y++) { /* rows where two triangles that share an entry both show */
            bool shared = false;
            for (int a = 0; a < width && !shared; a++)
                for (int b = a + 1; b < width && !shared; b++) {
                    uint32_t ia = fb.ids[y * width + a], ib = fb.ids[y * width + b];
                    shared = ia && ib && ia != ib && (ia - 1) % 256 == (ib - 1) % 256;
                }
            sharing_rows += shared;
        }
        for (int interpolated = 0; interpolated < 2; interpolated++) {
            sr_pinhole_outputs out = { depth, range, face_ids, part_ids, normals, interpolated, NAN,
                                       1 + scene % 4 };
            cr_assert(sr_pinhole_resolve(&cam, &mesh, &fb, &out, &err), "%s", err.message);
            for (int y = 0; y < height; y++)
                for (int x = 0; x < width; x++) {
                    int at = y * width + x;
                    uint32_t id = fb.ids[at];
                    cr_assert_eq(face_ids[at], id, "scene %d (%d, %d)", scene, x, y);
                    if (id == 0) {
                        cr_assert(isnan(depth[at]) && isnan(range[at]) && part_ids[at] == 0 &&
                                      normals[3 * at] == 0.0f && normals[3 * at + 1] == 0.0f &&
                                      normals[3 * at + 2] == 0.0f,
                                  "scene %d (%d, %d): nothing drawn", scene, x, y);
                        continue;
                    }
                    pixel want = formula(&cam, &mesh, id - 1, x, y, fb.depth[at]);
                    edge_on += centred && (id - 1) % 3 == 0;
                    cr_assert(memcmp(&depth[at], &want.depth, 4) == 0 && memcmp(&range[at], &want.range, 4) == 0,
                              "scene %d (%d, %d): depth %a range %a, the formula's %a %a", scene, x, y,
                              (double)depth[at], (double)range[at], (double)want.depth, (double)want.range);
                    cr_assert_eq(part_ids[at], want.part, "scene %d (%d, %d)", scene, x, y);
                    cr_assert(memcmp(&normals[3 * at], interpolated ? want.smooth : want.normal, 12) == 0,
                              "scene %d (%d, %d): normal differs (interpolated %d)", scene, x, y, interpolated);
                }
        }
        sr_framebuffer_destroy(&fb);
        mesh.parts = NULL;
        mesh.part_count = 0;
        sr_mesh_free(&mesh);
    }
    cr_assert_gt(edge_on, 1000, "too few pixels of triangles through the camera centre to test the fallback");
    cr_assert_gt(sharing_rows, 100, "too few rows showing two triangles of one cache entry");
}

/* Frames one pixel wide or tall, one 16384 pixels wide and one of fewer
 * rows than threads, resolved on 2 to 100 threads: every output the
 * same bits as on one thread (the chunks of rows and the runs of a row
 * at their extremes). */
Test(pinhole_resolve, any_thread_count_gives_one_threads_bits_on_thin_and_wide_frames)
{
    test_rng rng = { 0x7A11u };
    sr_error err = { "" };
    sr_mesh mesh;
    cr_assert(sr_mesh_alloc(&mesh, 3 * TRIANGLES, 3 * TRIANGLES, true, false, false, &err), "%s", err.message);
    for (uint32_t v = 0; v < 3 * TRIANGLES; v++) {
        mesh.indices[v] = v;
        for (int k = 0; k < 3; k++) {
            mesh.positions[v][k] = (float)rng_uniform(&rng, -3.0, 3.0);
            mesh.normals[v][k] = (float)rng_uniform(&rng, -1.0, 1.0);
        }
        mesh.positions[v][2] = (float)rng_uniform(&rng, 0.5, 9.0);
    }
    static const int sizes[][2] = { { 1, 97 }, { 97, 1 }, { 16384, 2 }, { 5, 3 } };
    static const int threads[] = { 2, 3, 64, 100 };
    for (size_t s = 0; s < sizeof sizes / sizeof *sizes; s++) {
        int width = sizes[s][0], height = sizes[s][1];
        size_t n = (size_t)width * (size_t)height;
        sr_pinhole cam = { .fx = 40.0, .fy = 40.0, .cx = (width - 1) / 2.0, .cy = (height - 1) / 2.0,
                           .near = 0.25, .far = 12.0 };
        for (int k = 0; k < 4; k++)
            cam.w2c[k][k] = 1.0;
        sr_framebuffer fb;
        cr_assert(sr_framebuffer_create(&fb, width, height, &err) && sr_framebuffer_create_ids(&fb, &err), "%s",
                  err.message);
        for (size_t i = 0; i < n;) {
            uint32_t id = rng_below(&rng, 4) == 0 ? 0 : 1 + (uint32_t)rng_below(&rng, TRIANGLES);
            for (int run = 1 + rng_below(&rng, 40); run > 0 && i < n; run--, i++) {
                fb.ids[i] = id;
                fb.depth[i] = (float)rng_uniform(&rng, 0.0, 1.0);
            }
        }
        float *one = calloc(8 * n, sizeof(float)), *many = calloc(8 * n, sizeof(float));
        cr_assert(one && many);
        for (int t = 0; t <= (int)(sizeof threads / sizeof *threads); t++) {
            float *into = t == 0 ? one : many;
            sr_pinhole_outputs out = { into, into + n, (uint32_t *)(into + 2 * n), (uint32_t *)(into + 3 * n),
                                       into + 4 * n, false, NAN, t == 0 ? 1 : threads[t - 1] };
            cr_assert(sr_pinhole_resolve(&cam, &mesh, &fb, &out, &err), "%s", err.message);
            if (t > 0)
                cr_assert_eq(memcmp(one, many, 7 * n * sizeof(float)), 0, "%dx%d on %d threads: bits differ", width,
                             height, threads[t - 1]);
        }
        free(one);
        free(many);
        sr_framebuffer_destroy(&fb);
    }
    sr_mesh_free(&mesh);
}

/* The resolve's triangle lanes (pinhole_triangles.h), SSE2 and, where the
 * CPU has it, AVX2: 1 to 9 triangles (so a last group of fewer), of
 * random corners of a mesh far from the world's origin, z negated or not,
 * some coordinates tiny or huge, under a random pose, into entries in a
 * random order. Each entry's geometry has the bits of to_camera and
 * the scalar products, and no byte else of it or of another entry
 * changes. */
Test(pinhole_resolve, triangle_lanes_give_the_scalar_set_ups_bits)
{
    enum { VERTICES = 40, MOST = 9 };
    test_rng rng = { 0x1A7E5u };
    static float positions[VERTICES][3];
    bool avx2 = sr_raster_simd_resolve(SR_SIMD_AUTO) >= SR_SIMD_AVX2;
    for (int round = 0; round < 400; round++) {
        sr_mesh mesh = { .vertex_count = VERTICES, .positions = (vec3 *)positions, .z_negated = round % 2 };
        for (int v = 0; v < VERTICES; v++)
            for (int k = 0; k < 3; k++) {
                double scale = rng_below(&rng, 8) == 0 ? (rng_below(&rng, 2) ? 0x1p-100 : 1e18) : 3.0;
                positions[v][k] = (float)rng_uniform(&rng, -scale, scale);
            }
        sr_pinhole cam = { .fx = 50.0, .fy = 50.0 };
        turn_and_move_away(&rng, &cam, &mesh);
        for (int r = 0; r < 3; r++)
            cam.w2c[r][3] = rng_uniform(&rng, -1e6, 1e6);
        cam.w2c[3][3] = 1.0;
        camera_frame frame = camera_frame_of(&cam, &mesh);
        uint32_t n = 1 + (uint32_t)rng_below(&rng, MOST), corners[MOST][3];
        resolved_triangle entries[MOST], before[MOST], *to[MOST];
        memset(entries, 0xA5, sizeof entries);
        memcpy(before, entries, sizeof entries);
        for (uint32_t k = 0; k < MOST; k++)
            to[k] = &entries[k];
        for (uint32_t k = MOST - 1; k > 0; k--) { /* the entries in a random order */
            uint32_t j = (uint32_t)rng_below(&rng, (int)k + 1);
            resolved_triangle *swap = to[k];
            to[k] = to[j];
            to[j] = swap;
        }
        for (uint32_t k = 0; k < n; k++)
            for (int c = 0; c < 3; c++)
                corners[k][c] = (uint32_t)rng_below(&rng, VERTICES);
        for (int width = 0; width < 1 + avx2; width++) {
            memcpy(entries, before, sizeof entries);
            (width ? sr_pinhole_triangles_avx2 : sr_pinhole_triangles_sse2)(&frame, (const float(*)[3])positions,
                                                                             (const uint32_t(*)[3])corners, to, n);
            for (uint32_t k = 0; k < MOST; k++) {
                resolved_triangle want; /* copied bytewise: padding included */
                memcpy(&want, &before[to[k] - entries], sizeof want);
                if (k < n) {
                    double v[3][3];
                    for (int c = 0; c < 3; c++)
                        to_camera(&frame, positions[corners[k][c]], v[c]);
                    for (int i = 0; i < 3; i++) {
                        want.v0[i] = v[0][i];
                        want.e1[i] = v[1][i] - v[0][i];
                        want.e2[i] = v[2][i] - v[0][i];
                    }
                    cross(want.e1, want.e2, want.cross);
                    want.cross_squared = dot(want.cross, want.cross);
                    want.offset = dot(want.cross, want.v0);
                }
                cr_assert(memcmp(to[k], &want, sizeof want) == 0, "round %d, %s lanes, triangle %u of %u: bits differ",
                          round, width ? "AVX2" : "SSE2", k, n);
            }
        }
    }
}
