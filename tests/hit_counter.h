/* tests/hit_counter.h — how many times each pixel is drawn, for the
 * watertightness tests (test_watertight.c, test_watertight_clip.c).
 *
 * scene_count_hits draws a mesh once, with the hit counter as the draw's
 * observer, and scene_expect_each_pixel_once checks the counts against the
 * regions a test computed from the geometry alone: pixels clearly inside must
 * be hit exactly once, pixels clearly outside never, and pixels on the
 * outline at most once.
 */
#ifndef SOFTRAST_TESTS_HIT_COUNTER_H
#define SOFTRAST_TESTS_HIT_COUNTER_H

#include "scene_helpers.h"

/* ---- counting hits per pixel, one fan triangle at a time ---- */

/* Counts how many fan triangles cover each pixel, within one sr_draw call:
 * install scene_hit_counter_observe as the draw's observer. The pipeline calls
 * the observer before it rasterizes each fan triangle, so at each call the
 * counter harvests the pixels the previous fan triangle wrote (inside its
 * bounding box: color != background), adds them to `counts` and resets them to
 * background color and cleared depth. Every fan triangle thus meets an empty
 * framebuffer, the depth test hides nothing, and a pixel drawn by two
 * triangles (a crack's opposite, an overlap) counts 2. Call
 * scene_hit_counter_finish after the draw. */
/* A near-cut vertex's z_ndc: a + b/w of its float w (the depth model), within
 * a·2^-24 of 0 rather than exactly 0; nothing off the near plane gets this
 * close at the scenes' depth ranges. */
#define SCENE_NEAR_CUT_Z 1e-6f

typedef struct scene_hit_counter {
    sr_framebuffer *fb;
    uint16_t *counts; /* width * height */
    bool pending;
    int x0, y0, x1, y1; /* bounding box of the pending triangle, in pixels */
    uint64_t triangles;  /* fan triangles seen */
    uint64_t clipped;    /* of those, from a clipped triangle */
    uint64_t near_cut_vertices; /* vertices of clipped fan triangles on the near plane (z_ndc <= SCENE_NEAR_CUT_Z) */
    uint64_t side_cut_vertices; /* vertices on the left or right edge of the viewport */
} scene_hit_counter;

static inline void scene_hit_counter_init(scene_hit_counter *c, sr_framebuffer *fb)
{
    *c = (scene_hit_counter){ .fb = fb };
    c->counts = calloc(scene_pixel_count(fb), sizeof *c->counts);
    cr_assert_not_null(c->counts);
}

static inline void scene_hit_counter_harvest(scene_hit_counter *c)
{
    if (!c->pending)
        return;
    sr_framebuffer *fb = c->fb;
    for (int y = c->y0; y < c->y1; y++) {
        for (int x = c->x0; x < c->x1; x++) {
            size_t i = (size_t)y * (size_t)fb->width + (size_t)x;
            if (fb->color[i] == SCENE_BACKGROUND)
                continue;
            c->counts[i]++;
            fb->color[i] = SCENE_BACKGROUND;
            fb->depth[i] = sr_framebuffer_depth_clear(fb);
        }
    }
    c->pending = false;
}

static inline int scene_clamp(int64_t v, int lo, int hi)
{
    return (int)(v < lo ? lo : v > hi ? hi : v);
}

static inline void scene_hit_counter_observe(void *user, const sr_screen_vertex tri[3], bool clipped, uint32_t id)
{
    (void)id;
    scene_hit_counter *c = user;
    scene_hit_counter_harvest(c);
    int64_t lo_x = tri[0].x, hi_x = tri[0].x, lo_y = tri[0].y, hi_y = tri[0].y;
    int64_t right = (int64_t)c->fb->width * SR_SUBPIXEL_ONE;
    for (int k = 0; k < 3; k++) {
        lo_x = tri[k].x < lo_x ? tri[k].x : lo_x;
        hi_x = tri[k].x > hi_x ? tri[k].x : hi_x;
        lo_y = tri[k].y < lo_y ? tri[k].y : lo_y;
        hi_y = tri[k].y > hi_y ? tri[k].y : hi_y;
        if (clipped && tri[k].z <= SCENE_NEAR_CUT_Z)
            c->near_cut_vertices++;
        if (clipped && (tri[k].x == 0 || tri[k].x == right))
            c->side_cut_vertices++;
    }
    /* Generous by a pixel each way: the harvest only needs to contain the triangle. */
    c->x0 = scene_clamp(lo_x / SR_SUBPIXEL_ONE - 1, 0, c->fb->width);
    c->x1 = scene_clamp(hi_x / SR_SUBPIXEL_ONE + 2, 0, c->fb->width);
    c->y0 = scene_clamp(lo_y / SR_SUBPIXEL_ONE - 1, 0, c->fb->height);
    c->y1 = scene_clamp(hi_y / SR_SUBPIXEL_ONE + 2, 0, c->fb->height);
    c->pending = true;
    c->triangles++;
    c->clipped += clipped;
}

/* Harvests the last triangle; returns the number of pixels still drawn
 * afterwards (written outside their triangle's bounding box: should be 0). */
static inline size_t scene_hit_counter_finish(scene_hit_counter *c)
{
    scene_hit_counter_harvest(c);
    return scene_count_drawn(c->fb);
}

static inline void scene_hit_counter_free(scene_hit_counter *c)
{
    free(c->counts);
    c->counts = NULL;
}

/* Hit counts as a picture: 0 black, 1 gray, 2 or more red; pixels that must be
 * covered once but are not get blue. */
static inline void scene_counts_to_image(const uint16_t *counts, const unsigned char *must_be_one, size_t n,
                                         uint32_t *out)
{
    for (size_t i = 0; i < n; i++) {
        out[i] = counts[i] == 0 ? SCENE_BACKGROUND : counts[i] == 1 ? 0x808080u : SCENE_DIFF_EXTRA;
        if (must_be_one && must_be_one[i] && counts[i] == 0)
            out[i] = SCENE_DIFF_MISSING;
    }
}

typedef enum scene_region {
    SCENE_REGION_OUT = 0, /* must not be hit */
    SCENE_REGION_IN,      /* must be hit exactly once */
    SCENE_REGION_EDGE     /* on the outline: hit at most once */
} scene_region;

/* Asserts the counts against the regions; on failure (or always, with
 * SOFTRAST_TEST_PICTURES set) writes NAME.png (counts: gray once, red twice
 * or more, blue missing) and on failure NAME.txt. */
static inline void scene_expect_each_pixel_once(const char *name, const scene_hit_counter *c,
                                                const unsigned char *regions)
{
    const sr_framebuffer *fb = c->fb;
    size_t n = scene_pixel_count(fb), inside = 0, bad = 0;
    char first[160] = "";
    FILE *report = NULL;
    for (size_t i = 0; i < n; i++) {
        inside += regions[i] == SCENE_REGION_IN;
        unsigned hits = c->counts[i];
        bool ok = regions[i] == SCENE_REGION_IN ? hits == 1 : regions[i] == SCENE_REGION_OUT ? hits == 0 : hits <= 1;
        if (ok)
            continue;
        int x = (int)(i % (size_t)fb->width), y = (int)(i / (size_t)fb->width);
        static const char *const region_names[] = { "outside", "inside", "on the outline" };
        if (bad == 0) {
            snprintf(first, sizeof first, "first at (%d, %d), %s, hit %u times", x, y, region_names[regions[i]],
                     hits);
            report = scene_report_open(name);
        }
        if (report && bad < SCENE_REPORT_PIXELS)
            fprintf(report, "%d %d: %s, hit %u times\n", x, y, region_names[regions[i]], hits);
        bad++;
    }
    if (report)
        fclose(report);
    if (bad || getenv("SOFTRAST_TEST_PICTURES")) { /* set it to see the passing scenes too */
        uint32_t *img = malloc(n * sizeof *img);
        unsigned char *must = malloc(n);
        cr_assert(img && must);
        for (size_t i = 0; i < n; i++)
            must[i] = regions[i] == SCENE_REGION_IN;
        scene_counts_to_image(c->counts, must, n, img);
        scene_write_png(name, "", img, fb->width, fb->height);
        free(img);
        free(must);
    }
    cr_expect_eq(bad, 0, "%s: %zu pixels wrong, %s; see " SCENE_OUTPUT_DIR "/%s*", name, bad, first, name);
    cr_expect_gt(inside, n / 10, "%s: the scene covers too little to test (%zu inside)", name, inside);
}

/* Draws the mesh once, with id shading, counting hits into c (which the caller frees). */
static inline void scene_count_hits(sr_framebuffer *fb, sr_draw_desc *desc, scene_hit_counter *c, sr_stats *stats)
{
    scene_hit_counter_init(c, fb);
    desc->shade = SR_SHADE_ID;
    desc->study = &(sr_draw_study){ .observer = scene_hit_counter_observe, .observer_user = c };
    sr_error err = { "" };
    cr_assert(sr_draw(fb, desc, stats, &err), "sr_draw: %s", err.message);
    size_t stray = scene_hit_counter_finish(c);
    cr_expect_eq(stray, 0, "%zu pixels written outside their triangle's bounding box", stray);
}

#endif
