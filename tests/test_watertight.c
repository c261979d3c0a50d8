/* Watertightness: triangles that share edges cover every pixel once.
 *
 * Each scene is one sr_draw counting hits (sr_draw_study.count_hits, see
 * hit_counter.h), so the counts are true per-pixel hit counts and no depth
 * test hides anything. Pixels whose centre is clearly inside the mesh must be hit exactly
 * once, pixels clearly outside never, and no pixel twice; only pixels whose
 * centre is exactly on the outline may go either way (0 or 1). These flat
 * scenes use the pixel-space orthographic camera, so the outline is known
 * exactly; test_watertight_clip.c does the same across clip planes.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <criterion/criterion.h>

#include "hit_counter.h"

#define ONE SR_SUBPIXEL_ONE
#define HALF (SR_SUBPIXEL_ONE / 2)
#define FLAT_SIZE 128 /* power of two: the pixel-space camera is exact */
#define FLAT_Z 0.5f
#define SEED 0xC0FFEEull

typedef struct pt {
    int64_t x, y; /* 1/256 pixel */
} pt;

static int64_t turn(pt p, pt q, pt r)
{
    return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
}

/* Where pixel centre c lies relative to a closed polygon: on an edge, or
 * inside/outside by the crossing number, all in exact integers. */
static scene_region polygon_region(const pt *poly, int n, pt c)
{
    bool in = false;
    for (int k = 0; k < n; k++) {
        pt a = poly[k], b = poly[(k + 1) % n];
        if (turn(a, b, c) == 0 && c.x >= (a.x < b.x ? a.x : b.x) && c.x <= (a.x > b.x ? a.x : b.x) &&
            c.y >= (a.y < b.y ? a.y : b.y) && c.y <= (a.y > b.y ? a.y : b.y))
            return SCENE_REGION_EDGE;
        if ((a.y > c.y) != (b.y > c.y)) {
            /* c is left of the crossing iff (c.x - a.x)(b.y - a.y) < (c.y - a.y)(b.x - a.x), sign-corrected. */
            int64_t lhs = (c.x - a.x) * (b.y - a.y), rhs = (c.y - a.y) * (b.x - a.x);
            if (b.y > a.y ? lhs < rhs : lhs > rhs)
                in = !in;
        }
    }
    return in ? SCENE_REGION_IN : SCENE_REGION_OUT;
}

static void polygon_regions(const pt *poly, int n, int size, unsigned char *regions)
{
    for (int j = 0; j < size; j++)
        for (int i = 0; i < size; i++)
            regions[j * size + i] = (unsigned char)polygon_region(poly, n, (pt){ (int64_t)i * ONE + HALF,
                                                                                (int64_t)j * ONE + HALF });
}

static void set_vertex(sr_mesh *mesh, uint32_t i, pt p)
{
    mesh->positions[i][0] = (float)p.x / ONE;
    mesh->positions[i][1] = (float)p.y / ONE;
    mesh->positions[i][2] = FLAT_Z;
}

/* Draws mesh (back faces culled) on a FLAT_SIZE square and expects none of
 * its `what` culled and each pixel inside the polygon (n corners) hit once. */
static void draw_covers_polygon_once(const char *name, const char *what, const sr_mesh *mesh, const pt *polygon,
                                     int n)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, FLAT_SIZE, FLAT_SIZE);
    sr_draw_desc desc = { .mesh = mesh, .cull = SR_CULL_BACK };
    scene_pixel_ortho(&desc, FLAT_SIZE, FLAT_SIZE);
    scene_hit_counter counter;
    sr_stats stats = { 0 };
    scene_count_hits(&fb, &desc, &counter, &stats);
    cr_expect_eq(stats.culled, 0, "%s: %llu %s culled (wrong winding?)", name, (unsigned long long)stats.culled,
                 what);
    static unsigned char regions[FLAT_SIZE * FLAT_SIZE];
    polygon_regions(polygon, n, FLAT_SIZE, regions);
    scene_expect_each_pixel_once(name, &counter, regions);
    sr_framebuffer_destroy(&fb);
}

/* A fan of spokes (in clockwise order on screen) around centre c, drawn once. */
static void check_fan(const char *name, pt c, const pt *spokes, int n)
{
    sr_mesh mesh;
    scene_mesh_alloc(&mesh, (uint32_t)n + 1, (uint32_t)n, false);
    set_vertex(&mesh, 0, c);
    for (int k = 0; k < n; k++) {
        set_vertex(&mesh, (uint32_t)k + 1, spokes[k]);
        mesh.indices[3 * k] = 0;
        mesh.indices[3 * k + 1] = (uint32_t)k + 1;
        mesh.indices[3 * k + 2] = (uint32_t)(k + 1) % (uint32_t)n + 1;
    }
    draw_covers_polygon_once(name, "fan triangles", &mesh, spokes, n);
    sr_mesh_free(&mesh);
}

static int compare_angle(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Centre on a pixel centre, spokes along rational directions (axes,
 * diagonals, 1:2 slopes...) ending on pixel centres: the shared edges pass
 * through many pixel centres, where only the top-left rule decides. */
Test(watertight, fan_with_edges_through_pixel_centres_covers_each_pixel_once)
{
    static const int dirs[][2] = { { 1, 0 }, { 2, 1 }, { 1, 1 }, { 1, 2 }, { 0, 1 }, { -1, 2 }, { -1, 1 },
                                   { -2, 1 }, { -1, 0 }, { -2, -1 }, { -1, -1 }, { -1, -2 }, { 0, -1 },
                                   { 1, -2 }, { 1, -1 }, { 2, -1 } };
    enum { N = sizeof dirs / sizeof dirs[0], REACH = 27 };
    pt c = { 64 * ONE + HALF, 63 * ONE + HALF }, spokes[N];
    for (int k = 0; k < N; k++) /* increasing angle with y down: clockwise on screen */
        spokes[k] = (pt){ c.x + (int64_t)dirs[k][0] * REACH * ONE, c.y + (int64_t)dirs[k][1] * REACH * ONE };
    check_fan("watertight_fan_with_edges_through_pixel_centres", c, spokes, N);
}

Test(watertight, fan_of_random_spokes_covers_each_pixel_once)
{
    enum { N = 29 };
    test_rng rng = { SEED };
    int fans = 0;
    for (int round = 0; round < 8; round++) {
        pt c = { 64 * ONE + rng_range(&rng, -4 * ONE, 4 * ONE),
                 64 * ONE + rng_range(&rng, -4 * ONE, 4 * ONE) };
        double angles[N];
        for (int k = 0; k < N; k++)
            angles[k] = rng_unit(&rng) * 2.0 * GLM_PI;
        qsort(angles, N, sizeof angles[0], compare_angle);
        pt spokes[N];
        for (int k = 0; k < N; k++) {
            double radius = 20.0 + 36.0 * rng_unit(&rng);
            spokes[k] = (pt){ c.x + (int64_t)llround(radius * cos(angles[k]) * ONE),
                              c.y + (int64_t)llround(radius * sin(angles[k]) * ONE) };
        }
        /* Spokes can leave a gap over pi; such a "fan" is not a simple
         * polygon, so only test star-shaped ones. */
        bool star = true;
        for (int k = 0; k < N; k++)
            star = star && turn(c, spokes[k], spokes[(k + 1) % N]) > 0;
        if (!star)
            continue;
        char name[96];
        snprintf(name, sizeof name, "watertight_fan_of_random_spokes_%d", round);
        check_fan(name, c, spokes, N);
        fans++;
    }
    cr_assert_geq(fans, 4, "only %d of 8 random fans were star-shaped and checked", fans);
}

/* An n x n grid of cells over [lo, hi]^2 (subpixels), each cell split along
 * a diagonal chosen by the rng, interior vertices moved by up to `jitter`. */
static void check_grid(const char *name, int n, int64_t lo, int64_t hi, int64_t jitter, bool centres,
                       test_rng *rng)
{
    uint32_t side = (uint32_t)n + 1;
    sr_mesh mesh;
    scene_mesh_alloc(&mesh, side * side, 2u * (uint32_t)(n * n), false);
    pt *grid = malloc(side * side * sizeof *grid);
    cr_assert_not_null(grid);
    for (uint32_t r = 0; r < side; r++) {
        for (uint32_t q = 0; q < side; q++) {
            pt p = { lo + (hi - lo) * (int64_t)q / n, lo + (hi - lo) * (int64_t)r / n };
            if (centres) { /* snap to the pixel centre below-right */
                p.x = p.x / ONE * ONE + HALF;
                p.y = p.y / ONE * ONE + HALF;
            }
            if (r > 0 && q > 0 && r < side - 1 && q < side - 1) {
                p.x += rng_range(rng, -jitter, jitter);
                p.y += rng_range(rng, -jitter, jitter);
            }
            grid[r * side + q] = p;
            set_vertex(&mesh, r * side + q, p);
        }
    }
    uint32_t t = 0;
    for (uint32_t r = 0; r < (uint32_t)n; r++) {
        for (uint32_t q = 0; q < (uint32_t)n; q++) {
            uint32_t a = r * side + q, b = a + 1, d = a + side, e = d + 1; /* a b on top, d e below */
            uint32_t *ix = &mesh.indices[6 * t++];
            if (rng_next(rng) & 1) { /* diagonal a-e; clockwise on screen (y down) */
                uint32_t v[6] = { a, b, e, a, e, d };
                memcpy(ix, v, sizeof v);
            } else { /* diagonal b-d */
                uint32_t v[6] = { a, b, d, b, e, d };
                memcpy(ix, v, sizeof v);
            }
        }
    }
    pt outline[4] = { grid[0], grid[side - 1], grid[side * side - 1], grid[(side - 1) * side] };
    draw_covers_polygon_once(name, "triangles", &mesh, outline, 4);
    free(grid);
    sr_mesh_free(&mesh);
}

Test(watertight, grid_of_jittered_triangles_covers_each_pixel_once)
{
    test_rng rng = { SEED + 1 };
    check_grid("watertight_grid_of_jittered_triangles", 13, 4 * ONE + 77, 123 * ONE + 190, 3 * ONE, false, &rng);
}

Test(watertight, grid_with_vertices_on_pixel_centres_covers_each_pixel_once)
{
    test_rng rng = { SEED + 2 };
    check_grid("watertight_grid_with_vertices_on_pixel_centres", 15, 4 * ONE, 124 * ONE, 0, true, &rng);
}

Test(watertight, grid_of_thin_cells_covers_each_pixel_once)
{
    test_rng rng = { SEED + 3 };
    /* 61 cells over 121 px, about 2 px wide: jitter of up to 0.4 px keeps
     * every cell convex (so no triangle folds over) while slanting all edges. */
    check_grid("watertight_grid_of_thin_cells", 61, 3 * ONE + 5, 124 * ONE + 251, 2 * ONE / 5, false, &rng);
}
