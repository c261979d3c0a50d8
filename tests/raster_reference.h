/* tests/raster_reference.h — which pixels a triangle covers, from the rule
 * alone, and the random triangles the raster tests draw (test_raster.c
 * directly, test_raster_draw.c through sr_draw).
 *
 * The reference is written from the rule, not from src/pipeline/raster.c:
 * vertices on the 1/256 pixel grid, pixel (i, j) sampled at its centre, exact
 * 64-bit integer side tests, and the top-left rule phrased geometrically (a
 * top edge is horizontal with the rest of the triangle below it, a left edge
 * is not horizontal and has the rest of the triangle to its right; a centre
 * exactly on an edge counts only for those). It does not reorder vertices,
 * so it is the same for either winding.
 */
#ifndef SOFTRAST_TESTS_RASTER_REFERENCE_H
#define SOFTRAST_TESTS_RASTER_REFERENCE_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <criterion/criterion.h>

#include "softrast_private.h"
#include "scene_helpers.h"

#define FB_W 64 /* powers of two: the pixel-space orthographic setup is exact */
#define FB_H 32
#define ONE SR_SUBPIXEL_ONE
#define HALF (SR_SUBPIXEL_ONE / 2)
#define RANDOM_TRIANGLES 3000
#define RANDOM_SEED 0x50F7A57ull
#define TRIANGLE_Z 0.5f
#define TINY_REACH (3 * ONE)    /* tiny triangles: vertices within 3 px of each other */
#define SLIVER_OFFSET 24        /* sliver apex: within 24/256 px of the opposite edge */

typedef struct ref_point {
    int64_t x, y; /* 1/256 pixel, top-left origin, y down */
} ref_point;

/* (q - p) x (r - p): > 0 when p -> q -> r turns clockwise on screen (y down). */
static inline int64_t ref_turn(ref_point p, ref_point q, ref_point r)
{
    return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
}

/* Edge p-q of the triangle whose third vertex is r. Top: horizontal, the
 * triangle below it (larger y). Left: not horizontal, r to the right of the
 * edge's line at r's height, i.e. sign(r.x - x_line(r.y)) > 0, multiplied
 * out by (q.y - p.y) to stay in integers. */
static inline bool ref_edge_is_top_or_left(ref_point p, ref_point q, ref_point r)
{
    if (p.y == q.y)
        return r.y > p.y;
    int64_t s = (r.x - p.x) * (q.y - p.y) - (q.x - p.x) * (r.y - p.y);
    return q.y > p.y ? s > 0 : s < 0;
}

/* Centre c is covered iff for every edge it is on the same side as the third
 * vertex, or exactly on the edge and the edge is top or left. */
static inline bool ref_covers(const ref_point v[3], ref_point c)
{
    for (int k = 0; k < 3; k++) {
        ref_point p = v[k], q = v[(k + 1) % 3], r = v[(k + 2) % 3];
        int64_t side_c = ref_turn(p, q, c), side_r = ref_turn(p, q, r);
        if (side_c == 0) {
            if (!ref_edge_is_top_or_left(p, q, r))
                return false;
        } else if ((side_c > 0) != (side_r > 0)) {
            return false;
        }
    }
    return true;
}

/* The reference mask over a width x height image, limited to rect. */
static inline size_t ref_mask(const ref_point v[3], int width, sr_raster_rect rect, unsigned char *mask)
{
    size_t n = 0;
    for (int j = rect.y0; j < rect.y1; j++) {
        for (int i = rect.x0; i < rect.x1; i++) {
            bool in = ref_covers(v, (ref_point){ (int64_t)i * ONE + HALF, (int64_t)j * ONE + HALF });
            mask[(size_t)j * (size_t)width + (size_t)i] = in;
            n += in;
        }
    }
    return n;
}

/* ---- random triangles ---- */

typedef enum kind {
    KIND_ANY,          /* anywhere in the image */
    KIND_TINY,         /* all three vertices within a few pixels */
    KIND_SLIVER,       /* apex a hair off the opposite edge */
    KIND_CENTRES,      /* every vertex on a pixel centre: edges through many centres */
    KIND_CENTRE_LINES, /* coordinates on centre rows/columns, often a shared x or y */
    KIND_CORNERS,      /* every vertex on a pixel corner */
    KIND_AXIS_EDGES,   /* right triangle with a horizontal and a vertical edge on centre lines */
    KIND_COUNT
} kind;

static inline const char *kind_name(kind k)
{
    static const char *const names[KIND_COUNT] = { "any", "tiny", "sliver", "centres", "centre lines",
                                                   "corners", "axis edges" };
    return names[k];
}

static inline int64_t clamp64(int64_t v, int64_t lo, int64_t hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

static inline int64_t random_centre(test_rng *r, int64_t pixels)
{
    return rng_range(r, 0, pixels - 1) * ONE + HALF;
}

/* A triangle of the given kind with every vertex in [lo, hi]^2 (subpixels of
 * an image of w x h pixels), either winding. */
static inline void random_triangle(test_rng *r, kind k, int w, int h, ref_point v[3])
{
    int64_t xmax = (int64_t)w * ONE, ymax = (int64_t)h * ONE;
    for (int i = 0; i < 3; i++)
        v[i] = (ref_point){ rng_range(r, 0, xmax), rng_range(r, 0, ymax) };
    switch (k) {
    case KIND_ANY:
        break;
    case KIND_TINY:
        for (int i = 1; i < 3; i++) {
            v[i].x = clamp64(v[0].x + rng_range(r, -TINY_REACH, TINY_REACH), 0, xmax);
            v[i].y = clamp64(v[0].y + rng_range(r, -TINY_REACH, TINY_REACH), 0, ymax);
        }
        break;
    case KIND_SLIVER: {
        double t = rng_unit(r);
        v[2].x = clamp64(v[0].x + (int64_t)(t * (double)(v[1].x - v[0].x)) +
                             rng_range(r, -SLIVER_OFFSET, SLIVER_OFFSET), 0, xmax);
        v[2].y = clamp64(v[0].y + (int64_t)(t * (double)(v[1].y - v[0].y)) +
                             rng_range(r, -SLIVER_OFFSET, SLIVER_OFFSET), 0, ymax);
        break;
    }
    case KIND_CENTRES:
        for (int i = 0; i < 3; i++)
            v[i] = (ref_point){ random_centre(r, w), random_centre(r, h) };
        break;
    case KIND_CENTRE_LINES:
        for (int i = 0; i < 3; i++) {
            if (rng_next(r) & 1)
                v[i].x = random_centre(r, w);
            if (rng_next(r) & 1)
                v[i].y = random_centre(r, h);
        }
        if (rng_next(r) & 1)
            v[1].y = v[0].y; /* a horizontal edge */
        if (rng_next(r) & 1)
            v[2].x = v[rng_next(r) & 1].x; /* a vertical edge */
        break;
    case KIND_CORNERS:
        for (int i = 0; i < 3; i++)
            v[i] = (ref_point){ rng_range(r, 0, w) * ONE, rng_range(r, 0, h) * ONE };
        break;
    case KIND_AXIS_EDGES:
        v[0] = (ref_point){ random_centre(r, w), random_centre(r, h) };
        v[1] = (ref_point){ random_centre(r, w), v[0].y };
        v[2] = (ref_point){ v[0].x, random_centre(r, h) };
        break;
    default:
        break;
    }
    if (rng_next(r) & 1) {
        ref_point t = v[1];
        v[1] = v[2];
        v[2] = t;
    }
}

/* Moves every vertex up to half the image size outside it, for rect clamping. */
static inline void overhang(test_rng *r, int w, int h, ref_point v[3])
{
    for (int i = 0; i < 3; i++) {
        v[i].x += rng_range(r, -(int64_t)w * HALF, (int64_t)w * HALF);
        v[i].y += rng_range(r, -(int64_t)h * HALF, (int64_t)h * HALF);
    }
}

/* ---- comparing ---- */

/* Fatal on the first mismatch: pictures and the triangle in the log. */
static inline void expect_mask(const char *test, int index, kind k, const ref_point v[3], const sr_framebuffer *fb,
                        const unsigned char *want)
{
    size_t n = scene_pixel_count(fb);
    size_t bad = 0;
    for (size_t i = 0; i < n; i++)
        bad += (fb->color[i] != SCENE_BACKGROUND) != want[i];
    if (bad == 0)
        return;
    uint32_t *drawn = malloc(n * sizeof *drawn), *expected = malloc(n * sizeof *expected);
    cr_assert(drawn && expected);
    for (size_t i = 0; i < n; i++)
        drawn[i] = fb->color[i] != SCENE_BACKGROUND ? 0xFFFFFFu : SCENE_BACKGROUND;
    scene_mask_to_image(want, n, expected);
    char name[128], first[256];
    snprintf(name, sizeof name, "%s_%d", test, index);
    scene_compare_images(name, drawn, expected, fb->width, fb->height, first, sizeof first);
    free(drawn);
    free(expected);
    cr_assert_fail("%s: triangle %d (%s) (%lld,%lld) (%lld,%lld) (%lld,%lld) [1/256 px]: %zu pixels differ, %s; "
                   "see " SCENE_OUTPUT_DIR "/%s*",
                   test, index, kind_name(k), (long long)v[0].x, (long long)v[0].y, (long long)v[1].x,
                   (long long)v[1].y, (long long)v[2].x, (long long)v[2].y, bad, first, name);
}

static const sr_raster_rect full_rect = { 0, 0, FB_W, FB_H };

#endif
