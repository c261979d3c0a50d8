/* The sub-pixel lanes (pipeline/08_raster/subpixel.h): each lane's verdict
 * against the one-at-a-time path's own box, pixel mask and cull, and whole
 * draws of dense meshes with the lanes against draws without them
 * (sr_draw_study.one_by_one): the same ids, depths and counts, bit for bit,
 * on every path, thread count and SIMD level. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "pipeline/07_cull.h"
#include "pipeline/08_raster/raster.h"
#include "pipeline/08_raster/triangle_setup.h"
#include "pipeline/08_raster/lane_pixels.h"
#include "pipeline/08_raster/subpixel.h"
#include "softrast_private.h"
#include "test_rng.h"

/* What the one-at-a-time path does with a triangle, from the set-up's own
 * functions: culled, or kept and covering no pixel centre of the
 * framebuffer (its box empty, or tiny with an empty mask), or neither; and
 * how many pixel centres its box holds. */
typedef enum fate { FATE_CULLED, FATE_DRAWS_NOTHING, FATE_MAY_DRAW } fate;

static int64_t box_centres(const sr_screen_vertex tri[3], const sr_subpixel_rules *r)
{
    sr_raster_rect box = sr_raster_scan_box(tri, (sr_raster_rect){ 0, 0, r->width, r->height }, r->bits);
    return box.x0 >= box.x1 || box.y0 >= box.y1 ? 0 : (int64_t)(box.x1 - box.x0) * (box.y1 - box.y0);
}

static fate fate_of(const sr_screen_vertex tri[3], const sr_subpixel_rules *r, sr_cull cull, sr_front front)
{
    int64_t area2 = sr_cull_area2(&tri[0], &tri[1], &tri[2]);
    if (!sr_cull_keeps(area2, cull, front))
        return FATE_CULLED;
    sr_raster_rect box = sr_raster_scan_box(tri, (sr_raster_rect){ 0, 0, r->width, r->height }, r->bits);
    if (box.x0 >= box.x1 || box.y0 >= box.y1)
        return FATE_DRAWS_NOTHING;
    if (!sr_raster_box_is_tiny(box))
        return FATE_MAY_DRAW;
    const sr_screen_vertex *v[3] = { &tri[0], &tri[1], &tri[2] };
    return sr_raster_tiny_mask(v, area2, box, r->bits) ? FATE_MAY_DRAW : FATE_DRAWS_NOTHING;
}

/* Within SR_SUBPIXEL_SPAN pixels on each axis: what the lanes promise to
 * decide. */
static bool small(const sr_screen_vertex tri[3], int bits)
{
    int64_t span = (int64_t)SR_SUBPIXEL_SPAN << bits;
    for (int k = 0; k < 3; k++)
        for (int j = 0; j < 3; j++)
            if (llabs(tri[k].x - tri[j].x) >= span || llabs(tri[k].y - tri[j].y) >= span)
                return false;
    return true;
}

/* Lane by lane: a lane says culled only of a culled triangle and draws
 * nothing only of one that draws nothing; of a small triangle culled, or
 * whose box holds at most one pixel centre, it says which, exactly, and
 * one_pixel of such a box it covers; of a small triangle kept whose box
 * holds more, small_box; of any other it says nothing. Returns how many
 * lanes dropped their triangle, and adds to *small_boxes (unless NULL)
 * how many said small_box. */
static int check_lanes(const sr_screen_vertex (*tris)[3], int n, const sr_subpixel_rules *r, sr_cull cull,
                       sr_front front, int *small_boxes)
{
    sr_subpixel_batch b = { { { 0 } } };
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            b.x[k][i] = (int32_t)tris[i][k].x;
            b.y[k][i] = (int32_t)tris[i][k].y;
        }
    sr_subpixel_verdict v = sr_subpixel_reject(&b, n, r);
    cr_assert_eq(v.culled & v.drawn, 0, "a lane both culled and drawn");
    cr_assert_eq((v.culled | v.drawn) & (v.one_pixel | v.small_box), 0, "a lane dropped a triangle it kept");
    cr_assert_eq(v.one_pixel & v.small_box, 0, "a lane said two boxes");
    int dropped = 0;
    for (int i = 0; i < n; i++) {
        fate f = fate_of(tris[i], r, cull, front);
        bool culled = v.culled >> i & 1, drawn = v.drawn >> i & 1, one_pixel = v.one_pixel >> i & 1,
             small_box = v.small_box >> i & 1;
        int64_t centres = box_centres(tris[i], r);
        dropped += culled || drawn;
        if (small_boxes)
            *small_boxes += small_box;
        cr_assert(!culled || f == FATE_CULLED, "lane %d culled a triangle stage 7 keeps", i);
        cr_assert(!drawn || f == FATE_DRAWS_NOTHING, "lane %d dropped a triangle that draws", i);
        if (!small(tris[i], r->bits)) {
            cr_assert(!culled && !drawn && !one_pixel && !small_box, "lane %d decided a triangle too large", i);
        } else if (f == FATE_CULLED || centres <= 1) {
            cr_assert(culled == (f == FATE_CULLED) && drawn == (f == FATE_DRAWS_NOTHING),
                      "lane %d left a small triangle it decides (fate %d)", i, (int)f);
            cr_assert_eq(one_pixel, f == FATE_MAY_DRAW, "lane %d: one pixel, fate %d", i, (int)f);
        } else {
            cr_assert(small_box && !culled && !drawn, "lane %d: a kept box of %lld centres", i, (long long)centres);
            cr_assert_leq(centres, SR_LANE_PIXELS_CENTRES);
        }
    }
    return dropped;
}

static const sr_cull culls[] = { SR_CULL_NONE, SR_CULL_BACK, SR_CULL_FRONT };

static sr_subpixel_rules rules_of(int bits, int width, int height, sr_cull cull, sr_front front)
{
    return (sr_subpixel_rules){ bits, width, height, sr_cull_keeps(1, cull, front), sr_cull_keeps(-1, cull, front) };
}

static sr_screen_vertex at(int64_t x, int64_t y)
{
    return (sr_screen_vertex){ .x = x, .y = y };
}

/* Random triangles of up to 5 pixels a side around the framebuffer, their
 * vertices on a grid of quarter pixels or finer, so edges run through
 * pixel centres and vertices sit on them (the top-left rule decides). */
Test(subpixel, lanes_agree_with_the_box_mask_and_cull_of_each_triangle)
{
    test_rng rng = { 35 };
    int dropped = 0, lanes = 0, small_boxes = 0;
    for (int bits = 2; bits <= SR_SUBPIXEL_LANES_MAX_BITS; bits++)
        for (int round = 0; round < 120; round++) {
            sr_screen_vertex tris[SR_SUBPIXEL_BATCH][3];
            int n = 1 + rng_below(&rng, SR_SUBPIXEL_BATCH);
            int64_t one = (int64_t)1 << bits, step = one >> rng_below(&rng, bits + 1);
            for (int i = 0; i < n; i++) {
                int64_t cx = rng_below(&rng, 20) - 2, cy = rng_below(&rng, 14) - 2;
                for (int k = 0; k < 3; k++)
                    tris[i][k] = at(cx * one + step * rng_below(&rng, (int)(5 * one / step) + 1),
                                    cy * one + step * rng_below(&rng, (int)(5 * one / step) + 1));
            }
            sr_cull cull = culls[rng_below(&rng, 3)];
            sr_front front = rng_below(&rng, 2) ? SR_FRONT_CW : SR_FRONT_CCW;
            sr_subpixel_rules r = rules_of(bits, 16, 10, cull, front);
            dropped += check_lanes(tris, n, &r, cull, front, &small_boxes);
            lanes += n;
        }
    cr_assert_gt(dropped, lanes / 4, "the lanes dropped only %d of %d triangles", dropped, lanes);
    cr_assert_gt(small_boxes, lanes / 10, "the lanes kept only %d small boxes of %d triangles", small_boxes, lanes);
}

Test(subpixel, lanes_at_the_edges_of_the_rules)
{
    const int bits = 8, one = 256, half = 128;
    const sr_screen_vertex tris[][3] = {
        /* Pixel (3, 2)'s centre on a left edge: drawn; on the mirrored
         * right edge: not; on a top edge: drawn; on a bottom one: not. */
        { at(3 * one + half, 2 * one), at(3 * one + half, 3 * one), at(4 * one, 2 * one + half) },
        { at(3 * one + half, 2 * one), at(3 * one, 2 * one + half), at(3 * one + half, 3 * one) },
        { at(3 * one, 2 * one + half), at(4 * one, 2 * one + half), at(3 * one + half, 3 * one) },
        { at(3 * one, 2 * one + half), at(3 * one + half, 2 * one), at(4 * one, 2 * one + half) },
        /* The centre on a vertex; a box that touches a centre with its side. */
        { at(3 * one + half, 2 * one + half), at(4 * one, 2 * one + half + 1), at(3 * one + half + 1, 3 * one) },
        { at(3 * one + half, 2 * one), at(3 * one + half + 100, 2 * one), at(3 * one + half + 50, 2 * one + 10) },
        /* Zero area, through a centre and beside one. */
        { at(3 * one, 2 * one), at(4 * one, 3 * one), at(5 * one, 4 * one) },
        { at(3 * one, 2 * one), at(3 * one, 2 * one), at(3 * one + 7, 2 * one + 3) },
        /* Off the framebuffer's sides, and its box clamped to its last pixel. */
        { at(-one, -one), at(-half, -one), at(-one, -half) },
        { at(15 * one + half - 3, 9 * one + half - 3), at(16 * one + 90, 9 * one + 90),
          at(15 * one + 90, 10 * one + 90) },
        /* Huge: a sliver 2^29 subpixels long under one row, and a big triangle. */
        { at(-(1 << 29), 2 * one + 10), at(1 << 29, 2 * one + 20), at(0, 2 * one + 30) },
        { at(-(1 << 29), -(1 << 29)), at(1 << 29, 0), at(0, 1 << 29) },
    };
    int n = (int)(sizeof tris / sizeof *tris);
    for (size_t c = 0; c < 3; c++)
        for (int f = 0; f < 2; f++) {
            sr_front front = f ? SR_FRONT_CW : SR_FRONT_CCW;
            sr_subpixel_rules r = rules_of(bits, 16, 10, culls[c], front);
            check_lanes(tris, n, &r, culls[c], front, NULL);
            /* Every triangle wound the other way as well. */
            sr_screen_vertex flipped[sizeof tris / sizeof *tris][3];
            for (int i = 0; i < n; i++) {
                flipped[i][0] = tris[i][0];
                flipped[i][1] = tris[i][2];
                flipped[i][2] = tris[i][1];
            }
            check_lanes(flipped, n, &r, culls[c], front, NULL);
        }
    /* The first one's left edge holds the centre, the second's right edge not. */
    sr_subpixel_rules none = rules_of(bits, 16, 10, SR_CULL_NONE, SR_FRONT_CW);
    cr_assert_eq(fate_of(tris[0], &none, SR_CULL_NONE, SR_FRONT_CW), FATE_MAY_DRAW);
    cr_assert_eq(fate_of(tris[1], &none, SR_CULL_NONE, SR_FRONT_CW), FATE_DRAWS_NOTHING);
}

static const sr_shade_context depth_shade = { .layout = { .count = 0, .color = -1, .uv = -1, .normal = -1 } };

/* Pixel (i, j) of a framebuffer `width` wide, covered at depth z. */
typedef struct covered_pixel {
    int i, j;
    float z;
} covered_pixel;

/* What the set-up finds of triangle v within rect: the pixels its tiny
 * mask covers, in the mask's order, and their depths by sr_row_z and
 * sr_depth_at; returns how many. */
static int setup_pixels(const sr_screen_vertex v[3], sr_raster_rect rect, int bits, covered_pixel *out)
{
    const sr_screen_vertex *tri[3] = { &v[0], &v[1], &v[2] };
    int64_t area2 = sr_cull_area2(tri[0], tri[1], tri[2]);
    sr_raster_rect box = sr_raster_scan_box_of(tri, rect, bits);
    sr_tri_setup s;
    if (box.x0 >= box.x1 || box.y0 >= box.y1 ||
        !sr_raster_setup(tri, area2, box, bits, SR_SHADE_DEPTH, &depth_shade, &s))
        return 0;
    cr_assert(sr_raster_box_is_tiny(box));
    int n = 0;
    for (uint64_t m = sr_raster_tiny_mask(tri, area2, box, bits); m; m &= m - 1) {
        int bit = __builtin_ctzll(m), i = box.x0 + bit % SR_TINY_SIDE, j = box.y0 + bit / SR_TINY_SIDE;
        out[n++] = (covered_pixel){ i, j, sr_depth_at(&s, sr_row_z(&s, j), (float)(i - s.ref_x)) };
    }
    return n;
}

/* Random triangles of less than SR_SUBPIXEL_SPAN pixels a side, some on
 * the framebuffer's sides, with random snap offsets (slivers turned over
 * by them too) and depths: the lane pixels of each within a rectangle
 * (the framebuffer, or a band of it) are the set-up's pixels and depths,
 * bit for bit, at both widths; among them groups of one-pixel triangles,
 * told so, which the lanes do not test. */
Test(subpixel, lane_pixels_are_the_setups_pixels_and_depths)
{
    enum { SIDE = 16, HEIGHT = 10 };
    test_rng rng = { 53 };
    int fragments = 0, past_two = 0, told = 0;
    for (int round = 0; round < 400; round++) {
        int bits = 2 + rng_below(&rng, SR_SUBPIXEL_LANES_MAX_BITS - 1);
        int64_t one = (int64_t)1 << bits, step = one >> rng_below(&rng, bits + 1);
        /* One round in eight at the far side of a framebuffer as wide as
         * coordinates inside every plane reach (2^29 subpixels). */
        int width = rng_below(&rng, 8) ? SIDE : 1 << (29 - bits), first = width - SIDE;
        sr_raster_rect rect = { first, 0, width, HEIGHT };
        if (rng_below(&rng, 2)) /* a band of rows, as a thread draws */
            rect.y0 = rng_below(&rng, HEIGHT), rect.y1 = rect.y0 + 1 + rng_below(&rng, HEIGHT - rect.y0);
        sr_screen_vertex v[SR_LANE_PIXELS_BATCH][3];
        uint32_t tri[SR_LANE_PIXELS_BATCH][3];
        int n = 1 + rng_below(&rng, SR_LANE_PIXELS_BATCH);
        bool one_pixel = rng_below(&rng, 3) == 0;
        for (int t = 0; t < n;) {
            int64_t cx = first + rng_below(&rng, SIDE + 2) - 2, cy = rng_below(&rng, HEIGHT + 2) - 2;
            for (int k = 0; k < 3; k++) {
                v[t][k] = at(cx * one + step * rng_below(&rng, (int)(SR_SUBPIXEL_SPAN * one / step)),
                             cy * one + step * rng_below(&rng, (int)(SR_SUBPIXEL_SPAN * one / step)));
                v[t][k].x_off = (float)rng_uniform(&rng, -0.5, 0.5);
                v[t][k].y_off = (float)rng_uniform(&rng, -0.5, 0.5);
                v[t][k].z = (float)rng_uniform(&rng, -0.1, 1.1);
                tri[t][k] = (uint32_t)(3 * t + k);
            }
            if (rng_below(&rng, 4) == 0) { /* a sliver: the offsets may turn it over */
                v[t][2].x = (v[t][0].x + v[t][1].x) / 2 + rng_below(&rng, 2);
                v[t][2].y = (v[t][0].y + v[t][1].y) / 2 + rng_below(&rng, 2);
            }
            if (sr_cull_area2(&v[t][0], &v[t][1], &v[t][2]) == 0)
                continue;
            /* A list told one_pixel holds the lanes' one_pixel triangles:
             * a box of one centre of the framebuffer, covered. */
            covered_pixel whole[SR_LANE_PIXELS_CENTRES];
            sr_subpixel_rules r = rules_of(bits, width, HEIGHT, SR_CULL_NONE, SR_FRONT_CCW);
            if (one_pixel && !(box_centres(v[t], &r) == 1 &&
                               setup_pixels(v[t], (sr_raster_rect){ 0, 0, width, HEIGHT }, bits, whole) == 1))
                continue;
            t++;
        }
        told += one_pixel ? n : 0;
        for (int wide = 0; wide < 2; wide++) {
            if (wide && !__builtin_cpu_supports("avx2"))
                continue;
            sr_lane_pixels got;
            (wide ? sr_lane_pixels_avx2 : sr_lane_pixels_sse2)((const char *)v, sizeof(sr_screen_vertex), tri, n,
                                                               one_pixel, bits, rect, width, &got);
            for (int t = 0; t < n; t++) {
                covered_pixel want[SR_LANE_PIXELS_CENTRES];
                int count = setup_pixels(v[t], rect, bits, want), k = 0;
                cr_assert_eq(__builtin_popcount(got.covered[t]), count, "round %d, triangle %d: %d centres, not %d",
                             round, t, __builtin_popcount(got.covered[t]), count);
                for (uint32_t m = got.covered[t]; m; m &= m - 1, k++) {
                    unsigned c = (unsigned)__builtin_ctz(m);
                    size_t pixel = sr_lane_pixel_at(&got, t, c, (size_t)width);
                    float z = k < 2 ? got.z[k][t] : sr_lane_pixel_z(&got, t, c);
                    cr_assert_eq(pixel, (size_t)want[k].j * (size_t)width + (size_t)want[k].i,
                                 "round %d, triangle %d", round, t);
                    cr_assert(k >= 2 || got.at[k][t] == pixel, "round %d, triangle %d: fragment %d", round, t, k);
                    cr_assert(memcmp(&z, &want[k].z, sizeof z) == 0, "round %d, triangle %d: z %a, not %a", round,
                              t, (double)z, (double)want[k].z);
                    cr_assert(memcmp(&z, (float[]){ sr_lane_pixel_z(&got, t, c) }, sizeof z) == 0);
                    fragments++;
                    past_two += k >= 2;
                }
            }
        }
    }
    cr_assert_gt(fragments, 10000, "only %d fragments", fragments);
    cr_assert_gt(past_two, 300, "only %d third or later centres", past_two);
    cr_assert_gt(told, 1000, "only %d one-pixel triangles told", told);
}

/* A dense mesh in clip space over a small framebuffer: vertices on a
 * jittered grid of about a pixel, some on pixel centres, a few past the
 * planes (clipped), one NaN and, inside every plane, one whose w is below
 * 2^-128 (1/w overflows float: refused by the mapping); triangles of
 * neighbouring vertices in random winding, and a few long ones across the
 * view. With colors, random ones, one NaN and one that overflows float once
 * divided by its vertex's w: both refused by the mapping. */
static void dense_mesh(sr_mesh *m, test_rng *rng, int width, int height, bool colors)
{
    const uint32_t side = 72, tris = 2 * (side - 1) * (side - 1) + 20;
    sr_error err;
    cr_assert(sr_mesh_alloc(m, side * side, 3 * tris, false, false, colors, &err), "%s", err.message);
    m->clip_positions = calloc(m->vertex_count, sizeof *m->clip_positions);
    cr_assert_not_null(m->clip_positions);
    for (uint32_t j = 0; j < side; j++)
        for (uint32_t i = 0; i < side; i++) {
            float *p = m->clip_positions[j * side + i];
            float x = -1.1f + 2.2f * ((float)i + (float)rng_uniform(rng, -0.4, 0.4)) / (float)(side - 1);
            float y = -1.1f + 2.2f * ((float)j + (float)rng_uniform(rng, -0.4, 0.4)) / (float)(side - 1);
            if (rng_below(rng, 8) == 0) { /* on a pixel centre */
                x = (2.0f * ((float)rng_below(rng, width) + 0.5f)) / (float)width - 1.0f;
                y = 1.0f - (2.0f * ((float)rng_below(rng, height) + 0.5f)) / (float)height;
            }
            p[0] = x, p[1] = y, p[2] = (float)rng_uniform(rng, 0.05, 0.95), p[3] = 1.0f;
        }
    m->clip_positions[side * side / 2][0] = NAN;
    memcpy(m->clip_positions[side * side / 3], (float[4]){ 0.0f, 0.0f, 0.0f, 0x1p-130f }, sizeof(float[4]));
    float *big = m->clip_positions[side * side / 4]; /* inside, w = 1/4 */
    for (int k = 0; k < 4; k++)
        big[k] *= 0.25f;
    if (colors) {
        for (uint32_t i = 0; i < m->vertex_count; i++)
            for (int k = 0; k < 3; k++)
                m->colors[i][k] = (float)rng_uniform(rng, 0.0, 1.0);
        m->colors[side * side / 5][1] = NAN;
        m->colors[side * side / 4][2] = 1e38f; /* 4e38 once divided by w */
    }
    uint32_t *idx = m->indices, n = 0;
    for (uint32_t j = 0; j + 1 < side; j++)
        for (uint32_t i = 0; i + 1 < side; i++) {
            uint32_t a = j * side + i, b = a + 1, c = a + side, d = c + 1;
            bool flip = rng_below(rng, 2);
            uint32_t quad[2][3] = { { a, flip ? c : b, flip ? b : c }, { b, flip ? c : d, flip ? d : c } };
            memcpy(idx + 3 * n, quad, sizeof quad);
            n += 2;
        }
    while (n < tris) {
        for (int k = 0; k < 3; k++)
            idx[3 * n + k] = (uint32_t)rng_below(rng, (int)m->vertex_count);
        n++;
    }
    /* Degenerate slots (each pair of corners the same), skipped and not
     * counted, among the slots the lanes take eight at a time; none of
     * the refused vertices' triangles, whose count the test checks. */
    static const uint32_t first[3] = { 0, 5, 11 }, every[3] = { 29, 31, 37 }, from[3] = { 0, 2, 0 },
                          to[3] = { 2, 1, 1 };
    for (int kind = 0; kind < 3; kind++)
        for (uint32_t t = first[kind]; t < tris; t += every[kind]) {
            uint32_t *tri = idx + 3 * t;
            bool refused = false;
            for (int k = 0; k < 3; k++)
                refused = refused || tri[k] == side * side / 2 || tri[k] == side * side / 3;
            if (!refused)
                tri[to[kind]] = tri[from[kind]];
        }
}

typedef struct drawn {
    sr_framebuffer fb;
    sr_stats stats;
} drawn;

/* The framebuffer's kinds a draw writes differently: with an ids plane,
 * and with reversed z (clear 0, GREATER). */
enum { PLAIN_FB = 0, IDS_PLANE = 1, REVERSED_Z = 2 };

static void draw_dense(const sr_mesh *m, int width, int height, sr_shade shade, sr_cull cull, sr_front front,
                       const sr_draw_study *study, int threads, int fb_kind, drawn *out)
{
    sr_error err;
    cr_assert(sr_framebuffer_create(&out->fb, width, height, &err), "%s", err.message);
    if (fb_kind & IDS_PLANE)
        cr_assert(sr_framebuffer_create_ids(&out->fb, &err), "%s", err.message);
    out->fb.reversed_z = (fb_kind & REVERSED_Z) != 0;
    sr_framebuffer_clear(&out->fb, 0x123456);
    sr_draw_desc desc = { .mesh = m, .shade = shade, .cull = cull, .front = front, .threads = threads,
                          .study = study };
    glm_mat4_identity(desc.world);
    glm_mat4_identity(desc.view);
    glm_mat4_identity(desc.projection);
    out->stats = (sr_stats){ 0 };
    cr_assert(sr_draw(&out->fb, &desc, &out->stats, &err), "%s", err.message);
}

static void assert_same(const drawn *want, const drawn *got, const char *what)
{
    size_t n = (size_t)want->fb.width * want->fb.height;
    cr_assert_eq(memcmp(want->fb.color, got->fb.color, n * sizeof *want->fb.color), 0, "color differs: %s", what);
    cr_assert_eq(memcmp(want->fb.depth, got->fb.depth, n * sizeof *want->fb.depth), 0, "depth differs: %s", what);
    cr_assert_eq(memcmp(&want->stats, &got->stats, sizeof want->stats), 0, "counts differ: %s", what);
    cr_assert_eq(!want->fb.ids, !got->fb.ids);
    if (want->fb.ids)
        cr_assert_eq(memcmp(want->fb.ids, got->fb.ids, n * sizeof *want->fb.ids), 0, "ids differ: %s", what);
}

static const sr_simd simds[] = { SR_SIMD_SCALAR, SR_SIMD_SSE2, SR_SIMD_AVX2, SR_SIMD_AVX512 };
static const sr_draw_path paths[] = { SR_PATH_DIRECT, SR_PATH_TILES, SR_PATH_ROWS };

/* Every path, thread count and SIMD level with the lanes draws what one
 * thread draws without them; returns what that drew. */
static sr_stats assert_lanes_draw_alike(const sr_mesh *m, int width, int height, sr_shade shade, sr_cull cull,
                                    sr_front front, int fb_kind, bool count_hits, float guard_band)
{
    sr_draw_study reference = { .path = SR_PATH_DIRECT, .one_by_one = true, .count_hits = count_hits,
                                .guard_band = guard_band };
    drawn want;
    draw_dense(m, width, height, shade, cull, front, &reference, 1, fb_kind, &want);
    cr_assert_gt(want.stats.fragments, 0, "the mesh drew nothing: the comparison would prove nothing");
    static const int threads[] = { 1, 2, 3 };
    for (size_t s = 0; s < sizeof simds / sizeof *simds; s++)
        for (size_t p = 0; p < sizeof paths / sizeof *paths; p++)
            for (size_t t = 0; t < sizeof threads / sizeof *threads; t++) {
                sr_draw_study lanes = { .path = paths[p], .simd = simds[s], .chunk_slots = t == 2 ? 5 : 0,
                                        .count_hits = count_hits, .guard_band = guard_band };
                drawn got;
                draw_dense(m, width, height, shade, cull, front, &lanes, threads[t], fb_kind, &got);
                char what[96];
                snprintf(what, sizeof what, "simd %d, path %d, %d threads, cull %d, front %d", (int)simds[s],
                         (int)paths[p], threads[t], (int)cull, (int)front);
                assert_same(&want, &got, what);
                sr_framebuffer_destroy(&got.fb);
            }
    sr_framebuffer_destroy(&want.fb);
    return want.stats;
}

Test(subpixel, dense_random_meshes_draw_alike_with_and_without_the_lanes, .timeout = 120)
{
    test_rng rng = { 3535 };
    for (int round = 0; round < 2; round++) {
        sr_mesh m;
        int width = round ? 64 : 48, height = round ? 48 : 40;
        dense_mesh(&m, &rng, width, height, round == 1);
        sr_stats ids = { 0 };
        for (size_t c = 0; c < 3; c++) {
            sr_stats got = assert_lanes_draw_alike(&m, width, height, c == 1 ? SR_SHADE_DEPTH : SR_SHADE_ID,
                                                     culls[c], round ? SR_FRONT_CCW : SR_FRONT_CW, PLAIN_FB, false, 0.0f);
            if (c == 0)
                ids = got;
        }
        /* A triangle the lanes find covering its one pixel is drawn by its
         * own loop in the modes without varyings: into an ids plane, with
         * reversed z, and counting hits too. */
        assert_lanes_draw_alike(&m, width, height, SR_SHADE_ID, SR_CULL_NONE, SR_FRONT_CCW,
                                round ? IDS_PLANE | REVERSED_Z : IDS_PLANE, false, 0.0f);
        assert_lanes_draw_alike(&m, width, height, SR_SHADE_DEPTH, SR_CULL_BACK, SR_FRONT_CCW, REVERSED_Z, false,
                                0.0f);
        assert_lanes_draw_alike(&m, width, height, SR_SHADE_ID, SR_CULL_NONE, SR_FRONT_CCW, PLAIN_FB, true, 0.0f);
        /* In a guard band the triangles across the framebuffer's sides are
         * inside every plane, and a box the framebuffer cuts to one pixel
         * takes the lanes' one-pixel draw. */
        assert_lanes_draw_alike(&m, width, height, SR_SHADE_ID, SR_CULL_NONE, SR_FRONT_CCW, IDS_PLANE, false, 2.0f);
        /* The NaN and the vertex whose 1/w overflows, on the grid's edge: three triangles each refused. */
        cr_assert_geq(ids.nonfinite, 6, "%llu", (unsigned long long)ids.nonfinite);
        if (round == 1) { /* three varyings through the mapping's lanes, two of them refused */
            sr_stats lit = assert_lanes_draw_alike(&m, width, height, SR_SHADE_COLOR, SR_CULL_NONE, SR_FRONT_CCW,
                                                   PLAIN_FB, false, 0.0f);
            cr_assert_gt(lit.nonfinite, ids.nonfinite, "the refused colors refused no triangle");
        }
        sr_mesh_free(&m);
    }
}

/* A mesh of `tris` triangles sharing no vertex, triangle t's corners
 * vertices 3t .. 3t + 2, in clip space (the caller sets the positions). */
static void separate_triangles(sr_mesh *m, uint32_t tris)
{
    sr_error err;
    cr_assert(sr_mesh_alloc(m, 3 * tris, 3 * tris, false, false, false, &err), "%s", err.message);
    m->clip_positions = calloc(m->vertex_count, sizeof *m->clip_positions);
    cr_assert_not_null(m->clip_positions);
    for (uint32_t i = 0; i < 3 * tris; i++)
        m->indices[i] = i;
}

/* Small triangles across the framebuffer's left and top sides, inside
 * every plane of a guard band: a box the framebuffer cuts down to its
 * first column or row holds one pixel centre there, and the lanes' one-pixel
 * draw must find that pixel as sr_raster_scan_box_of does. */
Test(subpixel, one_pixel_boxes_cut_by_the_framebuffers_sides_draw_alike)
{
    enum { SIDE = 8, TRIS = 400, GUARD = 2 };
    test_rng rng = { 808 };
    sr_mesh m;
    separate_triangles(&m, TRIS);
    for (uint32_t t = 0; t < TRIS; t++) {
        /* A corner up to 1.2 px past the side (or inside), the others up to
         * 1.6 px right of and below it: small enough for the lanes. */
        double x = t % 3 == 1 ? rng_uniform(&rng, 1.0, SIDE - 2.0) : rng_uniform(&rng, -1.2, 0.4);
        double y = t % 3 == 2 ? rng_uniform(&rng, 1.0, SIDE - 2.0) : rng_uniform(&rng, -1.2, 0.4);
        for (int k = 0; k < 3; k++) {
            double sx = x + (k ? rng_uniform(&rng, 0.0, 1.6) : 0.0), sy = y + (k ? rng_uniform(&rng, 0.0, 1.6) : 0.0);
            float *p = m.clip_positions[3 * t + (uint32_t)k];
            /* In clip space, which the guard band's viewport scales by GUARD. */
            p[0] = (float)((2.0 * sx / SIDE - 1.0) / GUARD), p[1] = (float)((1.0 - 2.0 * sy / SIDE) / GUARD);
            p[2] = (float)rng_uniform(&rng, 0.05, 0.95), p[3] = 1.0f;
        }
    }
    sr_stats got = assert_lanes_draw_alike(&m, SIDE, SIDE, SR_SHADE_ID, SR_CULL_NONE, SR_FRONT_CCW, IDS_PLANE, false,
                                           (float)GUARD);
    cr_assert_eq(got.rejected, 0, "a triangle left the guard band: the lanes would not see it");
    sr_mesh_free(&m);
}

/* Slivers through a pixel centre, one of whose corners snapping carries
 * across the line of the other two, or off it (sr_depth_plane then takes
 * the snapped corners' plane), in both windings: the lanes' one-pixel
 * draw must take that plane whichever way the triangle winds, as the
 * set-up does. */
Test(subpixel, one_pixel_slivers_turned_over_by_snapping_draw_alike)
{
    enum { SIDE = 8, TRIS = 3000, SUB = 256 };
    test_rng rng = { 4242 };
    sr_mesh m;
    separate_triangles(&m, TRIS);
    for (uint32_t t = 0; t < TRIS; t++) {
        /* In subpixels: two corners on a line of small integer slope
         * through the centre, the third a fraction of a subpixel off it. */
        double cx = SUB * (rng_below(&rng, SIDE) + 0.5), cy = SUB * (rng_below(&rng, SIDE) + 0.5);
        double dx = 1 + rng_below(&rng, 3), dy = (1 + rng_below(&rng, 3)) * (rng_below(&rng, 2) ? 1 : -1);
        double step = 20 + rng_below(&rng, 20), off = t % 3 == 0 ? 0.0 : 0.5; /* 0: on the line, unsnapped */
        double corner[3][2] = { { cx - dx * step, cy - dy * step },
                                { cx + dx * step * 0.4 + rng_uniform(&rng, -off, off),
                                  cy + dy * step * 0.4 + rng_uniform(&rng, -off, off) },
                                { cx + dx * step, cy + dy * step } };
        bool swap = rng_below(&rng, 2);
        for (int k = 0; k < 3; k++) {
            const double *c = corner[swap && k ? 3 - k : k];
            float *p = m.clip_positions[3 * t + (uint32_t)k];
            p[0] = (float)(2.0 * c[0] / (SUB * SIDE) - 1.0), p[1] = (float)(1.0 - 2.0 * c[1] / (SUB * SIDE));
            p[2] = (float)rng_uniform(&rng, 0.05, 0.95), p[3] = 1.0f;
        }
    }
    assert_lanes_draw_alike(&m, SIDE, SIDE, SR_SHADE_DEPTH, SR_CULL_NONE, SR_FRONT_CCW, IDS_PLANE, false, 0.0f);
    sr_mesh_free(&m);
}

/* The tests' toruses as a default camera at eye sees them, for a frame of
 * width × height. */
static sr_draw_desc seen_from(const sr_mesh *torus, const float eye[3], int width, int height, sr_shade shade,
                              sr_cull cull)
{
    sr_camera cam = sr_camera_default();
    glm_vec3_copy((float *)eye, cam.eye);
    sr_draw_desc desc = { .mesh = torus, .shade = shade, .cull = cull };
    sr_camera_view(&cam, desc.view);
    sr_camera_projection(&cam, (float)width / (float)height, desc.projection);
    glm_mat4_identity(desc.world);
    return desc;
}

/* desc drawn with study on `threads` threads (and workspace ws, or a
 * fresh one) into a new width × height framebuffer cleared to 0. */
static void draw_view(sr_draw_desc desc, const sr_draw_study *study, int threads, sr_workspace *ws, int width,
                      int height, drawn *out)
{
    sr_error err;
    desc.study = study;
    desc.threads = threads;
    desc.workspace = ws;
    cr_assert(sr_framebuffer_create(&out->fb, width, height, &err), "%s", err.message);
    sr_framebuffer_clear(&out->fb, 0);
    out->stats = (sr_stats){ 0 };
    cr_assert(sr_draw(&out->fb, &desc, &out->stats, &err), "%s", err.message);
}

/* desc drawn with study on `threads` threads, as the one-by-one reference
 * draws it on one: the same color, depth and counts; returns the
 * reference's counts. */
static sr_stats draws_as_one_by_one(sr_draw_desc desc, const sr_draw_study *study, int threads, sr_workspace *ws,
                                    int width, int height, const char *what)
{
    static const sr_draw_study reference = { .path = SR_PATH_DIRECT, .one_by_one = true };
    drawn want, got;
    draw_view(desc, &reference, 1, NULL, width, height, &want);
    draw_view(desc, study, threads, ws, width, height, &got);
    assert_same(&want, &got, what);
    sr_framebuffer_destroy(&want.fb);
    sr_framebuffer_destroy(&got.fb);
    return want.stats;
}

/* The dense torus seen small, lit, where the tiny queue takes the
 * triangles the lanes leave, and in ids. */
Test(subpixel, dense_torus_draws_alike_with_and_without_the_lanes, .timeout = 120)
{
    sr_mesh torus;
    sr_error err;
    cr_assert(sr_shape_torus(&torus, 1.0f, 0.4f, 120, 60, &err), "%s", err.message);
    for (int lit = 0; lit < 2; lit++) {
        sr_draw_desc desc = seen_from(&torus, (vec3){ 0, 1.1f, -1.9f }, 96, 64, lit ? SR_SHADE_LAMBERT : SR_SHADE_ID,
                                      lit ? SR_CULL_BACK : SR_CULL_NONE);
        for (size_t p = 0; p < sizeof paths / sizeof *paths; p++)
            for (int threads = 1; threads <= 2; threads++) {
                sr_draw_study lanes = { .path = paths[p] };
                draws_as_one_by_one(desc, &lanes, threads, NULL, 96, 64, lit ? "lit torus" : "torus ids");
            }
    }
    sr_mesh_free(&torus);
}

/* A torus of 4096 triangles, the fewest the estimate samples, in a frame
 * of more pixels than that: seen whole in a corner, most of its triangles
 * (back faces too, culling off) are smaller than a pixel, and the draw's
 * sampled estimate takes the lanes, which draw what the one-by-one path
 * draws; seen close, filling the frame with triangles of several pixels,
 * it does not. */
Test(subpixel, a_dense_mesh_small_in_a_larger_frame_takes_the_lanes, .timeout = 120)
{
    sr_mesh torus;
    sr_error err;
    cr_assert(sr_shape_torus(&torus, 1.0f, 0.4f, 64, 32, &err), "%s", err.message);
    cr_assert_eq(sr_assemble_slots(&torus), 4096u);
    const float distance[2] = { 9.0f, 1.6f }; /* whole in a corner; close, over the frame */
    for (int close = 0; close < 2; close++) {
        sr_draw_desc desc = seen_from(&torus, (vec3){ 0, 0.6f * distance[close], -distance[close] }, 320, 240,
                                      SR_SHADE_ID, SR_CULL_NONE);
        sr_draw_times times = { 0 };
        sr_draw_study by_cost = { .times = &times };
        sr_stats want = draws_as_one_by_one(desc, &by_cost, 0, NULL, 320, 240, /* the default threads */
                                            close ? "torus close" : "torus whole");
        cr_assert_gt(want.fragments, close ? 40000u : 1000u, "the torus drew %llu fragments",
                     (unsigned long long)want.fragments);
        cr_assert_eq(times.subpixel_lanes, !close, "seen %s, the lanes %s taken", close ? "close" : "whole",
                     times.subpixel_lanes ? "were" : "were not");
    }
    sr_mesh_free(&torus);
}

/* One workspace kept across draws of a torus of more vertices than a
 * chunk of the double halves' phase, from two views, on one thread (the
 * verdicts map each vertex's double half as they keep it) and on two and
 * three (they mark it, and the phase maps it, chunks to any thread): each
 * draw is what a fresh one-by-one draw gives, so no draw keeps the last
 * one's flags or offsets. */
Test(subpixel, a_kept_workspace_maps_every_draws_double_halves, .timeout = 120)
{
    sr_mesh torus;
    sr_error err;
    cr_assert(sr_shape_torus(&torus, 1.0f, 0.4f, 200, 100, &err), "%s", err.message);
    cr_assert_gt(torus.vertex_count, 16384u, "one chunk of the double halves would hold every vertex");
    sr_workspace *ws = sr_workspace_create();
    cr_assert_not_null(ws);
    static const float eyes[2][3] = { { 0, 1.1f, -1.9f }, { 1.3f, -0.6f, 1.4f } };
    static const int threads[] = { 2, 1, 3, 1, 2 };
    for (size_t d = 0; d < sizeof threads / sizeof *threads; d++) {
        sr_draw_desc desc = seen_from(&torus, eyes[d % 2], 96, 64, SR_SHADE_ID, SR_CULL_NONE);
        sr_draw_study kept = { .path = threads[d] > 1 ? SR_PATH_ROWS : SR_PATH_DIRECT };
        char what[64];
        snprintf(what, sizeof what, "draw %zu, %d threads", d, threads[d]);
        draws_as_one_by_one(desc, &kept, threads[d], ws, 96, 64, what);
    }
    sr_workspace_destroy(ws);
    sr_mesh_free(&torus);
}
