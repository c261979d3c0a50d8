/* sr_draw_study.count_hits: each pixel's color ends as the number of fan
 * triangles covering it, by the reference coverage of raster_reference.h
 * (the rule alone, not raster.c), and the same at every thread count.
 */
#include <string.h>

#include <criterion/criterion.h>

#include "raster_reference.h"

#define COUNT_W 328 /* rows of many pixels; counting hits takes the scalar loop alone */
#define COUNT_H (6 * SR_TILE_ROWS_MAX + 2) /* six tiles (strips of rows) and a partial seventh */
#define COUNT_TRIANGLES 400

/* A triangle list in pixel space from subpixel vertices (exact in float);
 * `shaded`: with vertex colors and a depth that varies per vertex. */
static void mesh_of(sr_mesh *mesh, const ref_point (*tris)[3], uint32_t n, bool shaded)
{
    scene_mesh_alloc(mesh, 3 * n, n, shaded);
    for (uint32_t t = 0; t < n; t++) {
        for (uint32_t k = 0; k < 3; k++) {
            uint32_t v = 3 * t + k;
            mesh->positions[v][0] = (float)tris[t][k].x / ONE;
            mesh->positions[v][1] = (float)tris[t][k].y / ONE;
            mesh->positions[v][2] = shaded ? 0.1f + 0.8f * (float)((v * 7) % 11) / 10.0f : TRIANGLE_Z;
            for (int c = 0; shaded && c < 3; c++)
                mesh->colors[v][c] = (float)((v * 5 + (uint32_t)c * 3) % 8) / 7.0f;
            mesh->indices[v] = v;
        }
    }
}

/* The mesh drawn counting hits, on the direct path for threads 0, else on
 * the tiles at that thread count; returns the stats. */
static sr_stats count_hits(sr_framebuffer *fb, const sr_mesh *mesh, int threads)
{
    sr_draw_path path = threads == 0 ? SR_PATH_DIRECT : SR_PATH_TILES;
    sr_draw_desc desc = { .mesh = mesh, .cull = SR_CULL_NONE, .threads = threads,
                          .study = &(sr_draw_study){ .count_hits = true, .path = path } };
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

/* Counts on the direct path and on the tiles at 1, 2 and 3 threads against
 * the reference; returns the largest count. */
static uint32_t expect_reference_counts(const ref_point (*tris)[3], uint32_t n, int width, int height)
{
    sr_mesh mesh;
    sr_framebuffer fb;
    mesh_of(&mesh, tris, n, false);
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
    for (int threads = 0; threads <= 3; threads++) { /* 0: the direct path */
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

/* The binned path sets a triangle that spans tiles up once and sends it only
 * to the tiles its edges reach, each flagged covered whole or not. Tiles are
 * strips of whole rows (SR_TILE_ROWS). These put edges along tile borders,
 * through the pixel centres of a tile's first row (the top-left rule decides
 * which tile draws them) and half a pixel either side, and triangles over
 * every tile, on a framebuffer 3 tiles tall; the vertical edges at the same
 * spacing test shared vertical edges on the way. */
#define BORDER_T ((int64_t)SR_TILE_ROWS_MAX)
#define BORDER_W ((int)(4 * BORDER_T))
#define BORDER_H ((int)(3 * BORDER_T))
_Static_assert(SR_TILE_ROWS(BORDER_W) == BORDER_T, "the border framebuffer's strips are BORDER_T rows");
#define TS (BORDER_T * ONE) /* a tile's rows in subpixels */
#define PS(n) ((int64_t)(n) * ONE) /* n pixels in subpixels */
static const ref_point tile_border_tris[][3] = {
    /* a quad split on its diagonal, its sides on tile borders */
    { { TS, TS }, { 3 * TS, TS }, { 3 * TS, 2 * TS } },
    { { TS, TS }, { 3 * TS, 2 * TS }, { TS, 2 * TS } },
    /* two triangles sharing a vertical edge through the centres of a tile's
     * first column, two sharing a horizontal one through a first row */
    { { TS + HALF, PS(8) }, { TS + HALF, 3 * TS - PS(5) }, { PS(10), 2 * TS } },
    { { TS + HALF, PS(8) }, { 2 * TS + PS(30), TS }, { TS + HALF, 3 * TS - PS(5) } },
    { { PS(5), 2 * TS + HALF }, { 4 * TS - PS(3), 2 * TS + HALF }, { 2 * TS, 3 * TS - PS(1) } },
    { { PS(5), 2 * TS + HALF }, { 2 * TS, TS + PS(3) }, { 4 * TS - PS(3), 2 * TS + HALF } },
    /* slivers on a border: one subpixel wide, and half a pixel tall */
    { { 2 * TS, 0 }, { 2 * TS + 1, 0 }, { 2 * TS + HALF, 3 * TS } },
    { { 0, TS + PS(1) }, { 4 * TS, TS }, { 0, TS + PS(1) - HALF } },
    /* over every tile, both windings, corners on tile corners or past the screen */
    { { 0, 0 }, { 4 * TS, 0 }, { 0, 3 * TS } },
    { { 4 * TS, 3 * TS }, { 0, 3 * TS }, { 4 * TS, 0 } },
    { { PS(-20), PS(-30) }, { 4 * TS + PS(40), TS }, { TS, 3 * TS + PS(50) } },
};
#define BORDER_TRIS ((uint32_t)(sizeof tile_border_tris / sizeof *tile_border_tris))

Test(count_hits, triangles_on_tile_borders_match_the_reference)
{
    cr_assert_gt(expect_reference_counts(tile_border_tris, BORDER_TRIS, BORDER_W, BORDER_H), 2);
}

/* The same triangles shaded (colors, depth per vertex): the tiles at every
 * thread count and per-pixel loop give the direct path's scalar picture, bit
 * for bit. */
Test(count_hits, triangles_on_tile_borders_shade_the_same_on_every_path)
{
    sr_mesh mesh;
    mesh_of(&mesh, tile_border_tris, BORDER_TRIS, true);
    sr_framebuffer want, got;
    scene_fb_make(&want, BORDER_W, BORDER_H);
    scene_fb_make(&got, BORDER_W, BORDER_H);
    sr_error err = { "" };
    size_t pixels = scene_pixel_count(&want);
    for (int s = SR_SIMD_SCALAR; s < SR_SIMD_COUNT; s++) {
        for (int threads = 0; threads <= 3; threads++) { /* 0: the reference */
            sr_draw_path path = threads == 0 ? SR_PATH_DIRECT : SR_PATH_TILES;
            sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_COLOR, .cull = SR_CULL_NONE, .threads = threads,
                                  .study = &(sr_draw_study){ .simd = (sr_simd)s, .path = path } };
            scene_pixel_ortho(&desc, BORDER_W, BORDER_H);
            sr_framebuffer *fb = s == SR_SIMD_SCALAR && threads == 0 ? &want : &got;
            sr_framebuffer_clear(fb, 0);
            cr_assert(sr_draw(fb, &desc, NULL, &err), "sr_draw: %s", err.message);
            cr_assert_eq(memcmp(fb->color, want.color, pixels * sizeof *fb->color), 0, "%s, %d threads: color",
                         sr_simd_name((sr_simd)s), threads);
            cr_assert_eq(memcmp(fb->depth, want.depth, pixels * sizeof *fb->depth), 0, "%s, %d threads: depth",
                         sr_simd_name((sr_simd)s), threads);
        }
    }
    sr_framebuffer_destroy(&want);
    sr_framebuffer_destroy(&got);
    sr_mesh_free(&mesh);
}
