/* The depth test's direction and its ties, on every per-pixel loop: the
 * scalar loop, the SSE2, AVX2 and AVX-512 span kernels and the tiny queue
 * (each vector loop's tiny triangles), on one thread and on the tiles and
 * row bands of two, in both depth conventions (LESS; GREATER for reversed
 * z). Expected pixels and counts come from the rule alone: the first of two
 * equal depths stays, the nearer of two depths wins, and the fragments
 * are the pixels that passed. A loop this CPU lacks is skipped, never
 * silently replaced by another.
 *
 * The scenes are seen in perspective from the origin along +z: a
 * triangle's world positions times 2 project to the same snapped screen
 * vertices (every product and quotient scales exactly), so it covers the
 * same pixels farther away, and its vertices' depths differ, so 1/w varies
 * across it and a tiny one takes the tiny queue. */
#include <criterion/criterion.h>
#include <criterion/parameterized.h>

#include "scene_helpers.h"

#define SIDE 64                   /* framebuffer side, pixels */
#define PIXELS_PER_UNIT (SIDE / 2) /* at fov 90: NDC ±1 is ±depth */
#define TINY_CELL 3               /* the tiny grid's quads, pixels a side: boxes of at most 4 x 4 */
#define TINY_FIRST 8              /* the tiny grid spans pixels TINY_FIRST … SIDE − TINY_FIRST */
#define TINY_CELLS ((SIDE - 2 * TINY_FIRST) / TINY_CELL)
#define FARTHER 2.0f              /* the far copy's scale: a power of two */

static const float RED[3] = { 1, 0, 0 }, GREEN[3] = { 0, 1, 0 };
#define RED_PIXEL 0xFF0000u

/* A point on the screen (pixels, y down) at a view depth. */
typedef struct screen_point {
    float px, py, depth;
} screen_point;

/* One copy of every triangle of a scene: scaled (1: as given, FARTHER:
 * behind it on the same pixels) and colored. */
typedef struct copy {
    float scale;
    const float *color;
} copy;

/* The world point that lands on pixel point (px, py) at view depth d. */
static void world_at(screen_point p, float scale, float out[3])
{
    out[0] = (p.px / PIXELS_PER_UNIT - 1.0f) * p.depth * scale;
    out[1] = (1.0f - p.py / PIXELS_PER_UNIT) * p.depth * scale;
    out[2] = p.depth * scale;
}

/* The scene's triangles, each followed by its other copies (A, A', B,
 * B', …: the copies of one triangle meet in one queue and one tile). */
static void copies_make(sr_mesh *mesh, const screen_point (*tri)[3], uint32_t n, const copy *copies, uint32_t count)
{
    scene_mesh_alloc(mesh, 3 * n * count, n * count, true);
    uint32_t v = 0;
    for (uint32_t t = 0; t < n; t++)
        for (uint32_t c = 0; c < count; c++)
            for (int k = 0; k < 3; k++, v++) {
                world_at(tri[t][k], copies[c].scale, mesh->positions[v]);
                glm_vec3_copy((float *)copies[c].color, mesh->colors[v]);
                mesh->indices[v] = v;
            }
}

/* A quad over most of the framebuffer, tilted in depth: two triangles
 * whose boxes are far wider than the widest kernel's 16 lanes. */
static uint32_t wide_scene(screen_point (*tri)[3])
{
    const screen_point a = { 4, 4, 3.0f }, b = { 60, 4, 4.0f }, c = { 60, 60, 5.0f }, d = { 4, 60, 4.0f };
    const screen_point quad[2][3] = { { a, b, c }, { a, c, d } };
    memcpy(tri, quad, sizeof quad);
    return 2;
}

/* A grid of quads TINY_CELL pixels a side, receding to the right: every
 * box tiny (narrower than the kernels take, at most 8 rows). */
static uint32_t tiny_scene(screen_point (*tri)[3])
{
    uint32_t n = 0;
    for (int r = 0; r < TINY_CELLS; r++)
        for (int q = 0; q < TINY_CELLS; q++) {
            float x0 = TINY_FIRST + TINY_CELL * q, y0 = TINY_FIRST + TINY_CELL * r;
            float x1 = x0 + TINY_CELL, y1 = y0 + TINY_CELL;
            screen_point a = { x0, y0, 3.0f + x0 / SIDE }, b = { x1, y0, 3.0f + x1 / SIDE },
                         c = { x1, y1, 3.2f + x1 / SIDE }, d = { x0, y1, 3.2f + x0 / SIDE };
            const screen_point quad[2][3] = { { a, b, c }, { a, c, d } };
            memcpy(tri + n, quad, sizeof quad);
            n += 2;
        }
    return n;
}

#define MAX_TRIANGLES (2 * TINY_CELLS * TINY_CELLS)

typedef uint32_t scene_maker(screen_point (*tri)[3]);

static const struct {
    scene_maker *make;
    const char *name;
    size_t least_pixels; /* the pixels it covers at least: a quarter of its area */
} scenes[] = {
    { wide_scene, "wide", 56 * 56 / 4 },
    { tiny_scene, "tiny", TINY_CELLS * TINY_CELLS * TINY_CELL * TINY_CELL / 4 },
};

static const struct {
    int threads;
    sr_draw_path path;
    const char *name;
} paths[] = { { 1, SR_PATH_DIRECT, "one thread" }, { 2, SR_PATH_TILES, "tiles" }, { 2, SR_PATH_ROWS, "row bands" } };

/* A per-pixel loop and a depth convention. */
typedef struct loop_case {
    sr_simd simd;
    bool reversed;
} loop_case;

static struct loop_case loop_cases[] = {
    { SR_SIMD_SCALAR, false }, { SR_SIMD_SSE2, false }, { SR_SIMD_AVX2, false }, { SR_SIMD_AVX512, false },
    { SR_SIMD_SCALAR, true },  { SR_SIMD_SSE2, true },  { SR_SIMD_AVX2, true },  { SR_SIMD_AVX512, true },
};

static void fb_for(sr_framebuffer *fb, const loop_case *c)
{
    scene_fb_make(fb, SIDE, SIDE);
    fb->reversed_z = c->reversed;
    sr_framebuffer_clear(fb, SCENE_BACKGROUND);
}

/* Draws mesh into fb on the case's loop and the path's threads, asserting
 * that the loop ran: a vector loop whose draw passed a fragment called its
 * kernels (on the tiny scene, whose boxes are all tiny, its tiny queue's
 * shaders; the queue counts only triangles with a pixel that passed), the
 * scalar loop none. Returns the draw's fragments. */
static uint64_t draw_case(sr_framebuffer *fb, const sr_mesh *mesh, const loop_case *c, size_t path,
                          const char *what)
{
    sr_camera cam = scene_camera(0, 0, 0, 0, 0, 1, 90.0f, 1.0f, 20.0f);
    cam.reversed_z = c->reversed;
    sr_draw_desc desc = { .mesh = mesh, .shade = SR_SHADE_COLOR, .cull = SR_CULL_NONE };
    scene_camera_desc(&desc, &cam, SIDE, SIDE);
    sr_stats stats;
    uint64_t calls = scene_draw_on_loop(fb, &desc, c->simd, paths[path].threads, paths[path].path, &stats);
    if (c->simd == SR_SIMD_SCALAR)
        cr_assert_eq(calls, 0u, "%s: the scalar loop called a kernel", what);
    else if (stats.fragments > 0)
        cr_assert_gt(calls, 0u, "%s: the %s loop never ran", what, sr_simd_name(c->simd));
    return stats.fragments;
}

/* Every drawn pixel red, at least `least` of them; returns how many. */
static size_t assert_all_red(const sr_framebuffer *fb, size_t least, const char *what)
{
    size_t reds = scene_count_color(fb, RED_PIXEL), drawn = scene_count_drawn(fb);
    cr_assert_eq(drawn, reds, "%s: %zu of %zu drawn pixels are not red", what, drawn - reds, drawn);
    cr_assert_geq(reds, least, "%s: only %zu pixels drawn", what, reds);
    return reds;
}

static void describe(char *what, size_t size, const loop_case *c, size_t scene, size_t path, const char *how)
{
    snprintf(what, size, "%s loop%s, %s scene, %s, %s", sr_simd_name(c->simd), c->reversed ? ", reversed z" : "",
             scenes[scene].name, paths[path].name, how);
}

/* check() on each scene, on the case's loop (skipped where the CPU lacks it). */
typedef void scene_check(const loop_case *c, size_t scene, const screen_point (*tri)[3], uint32_t n);

static void each_scene(const loop_case *c, scene_check *check)
{
    if (sr_raster_simd_resolve(c->simd) != c->simd)
        cr_skip_test("this CPU has no %s loop", sr_simd_name(c->simd));
    static screen_point tri[MAX_TRIANGLES][3];
    for (size_t s = 0; s < sizeof scenes / sizeof *scenes; s++)
        check(c, s, (const screen_point(*)[3])tri, scenes[s].make(tri));
}

/* A test, one per loop case, of `check` on each scene. */
#define ON_EVERY_LOOP(name, check)                                                                            \
    ParameterizedTestParameters(depth_loops, name)                                                            \
    {                                                                                                         \
        return cr_make_param_array(loop_case, loop_cases, sizeof loop_cases / sizeof *loop_cases);            \
    }                                                                                                         \
    ParameterizedTest(loop_case *c, depth_loops, name)                                                        \
    {                                                                                                         \
        each_scene(c, check);                                                                                 \
    }

/* Each triangle drawn twice at exactly the same depths, red then green,
 * in one draw and in two: LESS (GREATER) fails every green fragment, so
 * the picture is red and the green copy passes no fragment. */
static void first_of_twins_stays(const loop_case *c, size_t s, const screen_point (*tri)[3], uint32_t n)
{
    sr_mesh twins, red, green;
    copies_make(&twins, tri, n, (const copy[]){ { 1.0f, RED }, { 1.0f, GREEN } }, 2);
    copies_make(&red, tri, n, (const copy[]){ { 1.0f, RED } }, 1);
    copies_make(&green, tri, n, (const copy[]){ { 1.0f, GREEN } }, 1);
    for (size_t p = 0; p < sizeof paths / sizeof *paths; p++) {
        char what[128];
        sr_framebuffer fb;
        describe(what, sizeof what, c, s, p, "twins in one draw");
        fb_for(&fb, c);
        uint64_t fragments = draw_case(&fb, &twins, c, p, what);
        cr_assert_eq(fragments, assert_all_red(&fb, scenes[s].least_pixels, what), "%s: %llu fragments", what,
                     (unsigned long long)fragments);
        sr_framebuffer_destroy(&fb);
        describe(what, sizeof what, c, s, p, "twins in two draws");
        fb_for(&fb, c);
        draw_case(&fb, &red, c, p, what);
        fragments = draw_case(&fb, &green, c, p, what);
        assert_all_red(&fb, scenes[s].least_pixels, what);
        cr_assert_eq(fragments, 0u, "%s: %llu green fragments passed", what, (unsigned long long)fragments);
        sr_framebuffer_destroy(&fb);
    }
    sr_mesh_free(&twins);
    sr_mesh_free(&red);
    sr_mesh_free(&green);
}


/* Each triangle red, and green twice as far on the same pixels, near
 * first and far first: red everywhere; near first, the green copy passes
 * nothing, far first, it passes where red then passes again. */
static void nearer_wins(const loop_case *c, size_t s, const screen_point (*tri)[3], uint32_t n)
{
    for (int far_first = 0; far_first < 2; far_first++) {
        const copy near = { 1.0f, RED }, far = { FARTHER, GREEN };
        sr_mesh mesh;
        copies_make(&mesh, tri, n, far_first ? (const copy[]){ far, near } : (const copy[]){ near, far }, 2);
        for (size_t p = 0; p < sizeof paths / sizeof *paths; p++) {
            char what[128];
            describe(what, sizeof what, c, s, p, far_first ? "far first" : "near first");
            sr_framebuffer fb;
            fb_for(&fb, c);
            uint64_t fragments = draw_case(&fb, &mesh, c, p, what);
            size_t reds = assert_all_red(&fb, scenes[s].least_pixels, what);
            cr_assert_eq(fragments, (far_first ? 2 : 1) * (uint64_t)reds, "%s: %llu fragments for %zu pixels", what,
                         (unsigned long long)fragments, reds);
            sr_framebuffer_destroy(&fb);
        }
        sr_mesh_free(&mesh);
    }
}

ON_EVERY_LOOP(equal_depths_keep_the_first_triangle, first_of_twins_stays)
ON_EVERY_LOOP(the_nearer_triangle_wins_in_either_order, nearer_wins)
