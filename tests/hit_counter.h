/* tests/hit_counter.h — how many times each pixel is drawn, for the
 * watertightness tests (test_watertight.c, test_watertight_clip.c).
 *
 * scene_count_hits draws a mesh once counting hits (sr_draw_study.count_hits),
 * and scene_expect_each_pixel_once checks the counts against the
 * regions a test computed from the geometry alone: pixels clearly inside must
 * be hit exactly once, pixels clearly outside never, and pixels on the
 * outline at most once.
 */
#ifndef SOFTRAST_TESTS_HIT_COUNTER_H
#define SOFTRAST_TESTS_HIT_COUNTER_H

#include "scene_helpers.h"

/* ---- counting hits per pixel ---- */

/* A draw with sr_draw_study.count_hits leaves in each pixel's color the
 * number of fan triangles covering it: a pixel drawn by two (a crack's
 * opposite, an overlap) counts 2. The counter also watches the fan triangles
 * (an observer, which keeps the draw on one thread) for the vertices the
 * clipper cut on the near plane and on the viewport's sides. */
/* A near-cut vertex's z_ndc: a + b/w of its float w (the depth model), within
 * a·2^-24 of 0 rather than exactly 0; nothing off the near plane gets this
 * close at the scenes' depth ranges. */
#define SCENE_NEAR_CUT_Z 1e-6f

typedef struct scene_hit_counter {
    const sr_framebuffer *fb;
    const uint32_t *counts;     /* fb's color: hits per pixel */
    uint64_t near_cut_vertices; /* vertices of clipped fan triangles on the near plane (z_ndc <= SCENE_NEAR_CUT_Z) */
    uint64_t side_cut_vertices; /* vertices on the left or right edge of the viewport */
} scene_hit_counter;

static inline void scene_hit_counter_observe(void *user, const sr_screen_vertex tri[3], bool clipped, uint32_t id)
{
    (void)id;
    scene_hit_counter *c = user;
    int64_t right = (int64_t)c->fb->width * SR_SUBPIXEL_ONE;
    for (int k = 0; k < 3 && clipped; k++) {
        c->near_cut_vertices += tri[k].z <= SCENE_NEAR_CUT_Z;
        c->side_cut_vertices += tri[k].x == 0 || tri[k].x == right;
    }
}

/* Hit counts as a picture: 0 black, 1 gray, 2 or more red; pixels that must be
 * covered once but are not get blue. */
static inline void scene_counts_to_image(const uint32_t *counts, const unsigned char *must_be_one, size_t n,
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

/* Draws the mesh once counting hits into fb's color, which c reads. */
static inline void scene_count_hits(sr_framebuffer *fb, sr_draw_desc *desc, scene_hit_counter *c, sr_stats *stats)
{
    *c = (scene_hit_counter){ .fb = fb, .counts = fb->color };
    sr_framebuffer_clear(fb, 0);
    desc->study = &(sr_draw_study){ .count_hits = true, .observer = scene_hit_counter_observe, .observer_user = c };
    sr_error err = { "" };
    cr_assert(sr_draw(fb, desc, stats, &err), "sr_draw: %s", err.message);
}

#endif
