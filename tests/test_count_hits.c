/* sr_draw_study.count_hits: each pixel's color ends as the number of fan
 * triangles covering it, by the reference coverage of raster_reference.h
 * (the rule alone, not raster.c), and the same at every thread count.
 */
#include <string.h>

#include <criterion/criterion.h>

#include "raster_reference.h"

#define COUNT_W 200 /* several tiles each way, the last ones partial */
#define COUNT_H 130
#define COUNT_TRIANGLES 400

/* A triangle list in pixel space from subpixel vertices (exact in float). */
static void mesh_of(sr_mesh *mesh, const ref_point (*tris)[3], uint32_t n)
{
    scene_mesh_alloc(mesh, 3 * n, n, false);
    for (uint32_t t = 0; t < n; t++) {
        for (uint32_t k = 0; k < 3; k++) {
            mesh->positions[3 * t + k][0] = (float)tris[t][k].x / ONE;
            mesh->positions[3 * t + k][1] = (float)tris[t][k].y / ONE;
            mesh->positions[3 * t + k][2] = TRIANGLE_Z;
            mesh->indices[3 * t + k] = 3 * t + k;
        }
    }
}

/* The mesh drawn counting hits with `threads` threads; returns the stats. */
static sr_stats count_hits(sr_framebuffer *fb, const sr_mesh *mesh, int threads)
{
    sr_draw_desc desc = { .mesh = mesh, .cull = SR_CULL_NONE, .threads = threads,
                          .study = &(sr_draw_study){ .count_hits = true, .force_tiles = true } };
    scene_pixel_ortho(&desc, fb->width, fb->height);
    sr_framebuffer_clear(fb, 0);
    sr_stats stats = { 0 };
    sr_error err = { "" };
    cr_assert(sr_draw(fb, &desc, &stats, &err), "sr_draw: %s", err.message);
    return stats;
}

/* Per pixel, how many of the triangles the reference says cover it. */
static void reference_counts(const ref_point (*tris)[3], uint32_t n, int width, int height, uint32_t *want)
{
    for (int j = 0; j < height; j++)
        for (int i = 0; i < width; i++) {
            ref_point c = { (int64_t)i * ONE + HALF, (int64_t)j * ONE + HALF };
            uint32_t hits = 0;
            for (uint32_t t = 0; t < n; t++)
                hits += ref_turn(tris[t][0], tris[t][1], tris[t][2]) != 0 && ref_covers(tris[t], c);
            want[(size_t)j * (size_t)width + (size_t)i] = hits;
        }
}

/* Counts at 1, 2 and 3 threads against the reference; returns the largest count. */
static uint32_t expect_reference_counts(const ref_point (*tris)[3], uint32_t n, int width, int height)
{
    sr_mesh mesh;
    sr_framebuffer fb;
    mesh_of(&mesh, tris, n);
    scene_fb_make(&fb, width, height);
    size_t pixels = scene_pixel_count(&fb);
    uint32_t *want = malloc(pixels * sizeof *want);
    cr_assert_not_null(want);
    reference_counts(tris, n, width, height, want);
    uint64_t total = 0;
    uint32_t most = 0;
    for (size_t i = 0; i < pixels; i++) {
        total += want[i];
        most = want[i] > most ? want[i] : most;
    }
    for (int threads = 1; threads <= 3; threads++) {
        sr_stats stats = count_hits(&fb, &mesh, threads);
        for (size_t i = 0; i < pixels; i++)
            cr_assert_eq(fb.color[i], want[i], "%d threads: pixel (%zu, %zu) counted %u, the reference %u",
                         threads, i % (size_t)width, i / (size_t)width, fb.color[i], want[i]);
        cr_assert_eq(stats.fragments, total, "%d threads: %llu fragments, %llu hits", threads,
                     (unsigned long long)stats.fragments, (unsigned long long)total);
    }
    free(want);
    sr_framebuffer_destroy(&fb);
    sr_mesh_free(&mesh);
    return most;
}

static ref_point px(int64_t x, int64_t y)
{
    return (ref_point){ x * ONE, y * ONE };
}

Test(count_hits, two_triangles_sharing_an_edge_count_each_pixel_once)
{
    /* A quad split on its diagonal, whose centres lie on the shared edge. */
    const ref_point quad[2][3] = { { px(4, 4), px(60, 4), px(60, 60) }, { px(4, 4), px(60, 60), px(4, 60) } };
    cr_assert_eq(expect_reference_counts(quad, 2, 64, 64), 1);
}

Test(count_hits, overlapping_triangles_count_two_where_they_overlap)
{
    const ref_point pair[2][3] = { { px(2, 2), px(90, 10), px(20, 70) }, { px(30, 5), px(95, 60), px(10, 50) } };
    cr_assert_eq(expect_reference_counts(pair, 2, 100, 80), 2);
}

Test(count_hits, random_triangles_match_the_reference_at_every_thread_count)
{
    static ref_point tris[COUNT_TRIANGLES][3];
    test_rng rng = { RANDOM_SEED + 3 };
    for (int t = 0; t < COUNT_TRIANGLES; t++)
        random_triangle(&rng, (kind)(t % KIND_COUNT), COUNT_W, COUNT_H, tris[t]);
    cr_assert_gt(expect_reference_counts(tris, COUNT_TRIANGLES, COUNT_W, COUNT_H), 2);
}
