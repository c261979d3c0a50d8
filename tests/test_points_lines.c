/* Points and lines (SR_POINT_LIST, SR_LINE_LIST, SR_LINE_STRIP): Direct3D
 * 11's coverage on small scenes and against an exact diamond oracle, the
 * segment clipper against the triangle clipper's edges bit for bit, every
 * plane, the eye, w = 0, NaN and inf, the counts, the depth bias, and a
 * few dEQP clipping.point.* / clipping.line.* cases (docs/conventions.md,
 * "Points and lines"). */
#include <float.h>
#include <math.h>
#include <string.h>

#include <criterion/criterion.h>

#include "clip_helpers.h"
#include "pipeline/04_clip/clip_corner.h"
#include "pipeline/04_clip/clip_segment.h"
#include "pipeline/06_viewport.h"
#include "draw/draw_state.h"
#include "scene_helpers.h"

#define W 24
#define H 16
#define ONE 256

/* A mesh of `n` positions in pixel space (x, y, z_ndc) and indices. */
static void pixel_mesh(sr_mesh *m, const float (*xyz)[3], uint32_t n, const uint32_t *idx, uint32_t count,
                       sr_topology topology)
{
    sr_error err = { "" };
    cr_assert(sr_mesh_alloc(m, n, count, false, false, true, &err), "%s", err.message);
    memcpy(m->positions, xyz, n * sizeof(vec3));
    for (uint32_t i = 0; i < n; i++)
        m->colors[i][0] = m->colors[i][1] = m->colors[i][2] = 1.0f;
    memcpy(m->indices, idx, count * sizeof(uint32_t));
    m->topology = topology;
}

static sr_stats draw_desc(sr_framebuffer *fb, sr_draw_desc *desc)
{
    sr_stats stats = { 0 };
    sr_error err = { "" };
    cr_assert(sr_draw(fb, desc, &stats, &err), "sr_draw: %s", err.message);
    return stats;
}

/* Draws m with the pixel-space camera in `shade`, counting hits if asked. */
static sr_stats draw_pixels(sr_framebuffer *fb, const sr_mesh *m, sr_shade shade, float size, bool hits)
{
    sr_framebuffer_clear(fb, 0);
    sr_draw_desc desc = { .mesh = m, .shade = shade, .point_size = size, .line_width = size,
                          .study = &(sr_draw_study){ .count_hits = hits } };
    scene_pixel_ortho(&desc, fb->width, fb->height);
    return draw_desc(fb, &desc);
}

static uint32_t at(const sr_framebuffer *fb, int x, int y)
{
    return fb->color[y * fb->width + x];
}

/* The pixels of color c, as a string of "x,y " in row order, for exact
 * expectations that print well. */
static void pixels_of(const sr_framebuffer *fb, uint32_t c, char *out, size_t n)
{
    out[0] = '\0';
    size_t used = 0;
    for (int y = 0; y < fb->height; y++)
        for (int x = 0; x < fb->width; x++)
            if (at(fb, x, y) == c)
                used += (size_t)snprintf(out + used, n - used, "%d,%d ", x, y);
}

Test(points, a_point_covers_the_pixel_centres_of_its_square)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    const float xyz[][3] = { { 5.5f, 5.5f, 0.5f }, { 12.0f, 4.0f, 0.5f }, { 20.5f, 10.5f, 0.5f } };
    const uint32_t idx[] = { 0, 1, 2 };
    sr_mesh m;
    pixel_mesh(&m, xyz, 3, idx, 3, SR_POINT_LIST);
    char got[512];
    sr_stats s = draw_pixels(&fb, &m, SR_SHADE_ID, 1.0f, false);
    cr_assert_eq(s.points, 3);
    cr_assert_eq(s.drawn, 3);
    cr_assert_eq(s.triangles, 0);
    /* Size 1: the pixel whose square holds the point, left and top sides in. */
    pixels_of(&fb, 1, got, sizeof got);
    cr_assert_str_eq(got, "5,5 ");
    pixels_of(&fb, 2, got, sizeof got);
    cr_assert_str_eq(got, "11,3 ");
    /* Size 2 on a pixel corner: four pixels; on a centre: the centres at
     * −1 and 0 (the one at +1 is on the right and bottom sides, out). */
    s = draw_pixels(&fb, &m, SR_SHADE_ID, 2.0f, false);
    pixels_of(&fb, 2, got, sizeof got);
    cr_assert_str_eq(got, "11,3 12,3 11,4 12,4 ");
    pixels_of(&fb, 1, got, sizeof got);
    cr_assert_str_eq(got, "4,4 5,4 4,5 5,5 ");
    cr_assert_eq(s.fragments, 12);
    /* Size 3 centred on a pixel: 3 × 3, and one near the edge cut by the framebuffer. */
    s = draw_pixels(&fb, &m, SR_SHADE_ID, 5.0f, false);
    pixels_of(&fb, 3, got, sizeof got);
    cr_assert_str_eq(got, "18,8 19,8 20,8 21,8 22,8 18,9 19,9 20,9 21,9 22,9 18,10 19,10 20,10 21,10 22,10 "
                          "18,11 19,11 20,11 21,11 22,11 18,12 19,12 20,12 21,12 22,12 ");
    sr_mesh_free(&m);
    sr_framebuffer_destroy(&fb);
}

Test(lines, a_line_is_half_open_and_a_strip_draws_its_shared_vertex_once)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    const float xyz[][3] = { { 2.5f, 3.5f, 0.5f }, { 8.5f, 3.5f, 0.5f }, { 8.5f, 9.5f, 0.5f }, { 2.5f, 3.5f, 0.5f } };
    const uint32_t idx[] = { 0, 1, 2, 3 };
    sr_mesh m;
    pixel_mesh(&m, xyz, 4, idx, 4, SR_LINE_STRIP);
    char got[512];
    sr_stats s = draw_pixels(&fb, &m, SR_SHADE_ID, 1.0f, false);
    cr_assert_eq(s.lines, 3);
    pixels_of(&fb, 1, got, sizeof got);
    cr_assert_str_eq(got, "2,3 3,3 4,3 5,3 6,3 7,3 ");
    pixels_of(&fb, 2, got, sizeof got);
    cr_assert_str_eq(got, "8,3 8,4 8,5 8,6 8,7 8,8 ");
    /* The closing diagonal (slope 1: x-major) from (8.5, 9.5) back to the
     * strip's first vertex, whose pixel it leaves to the first line. */
    pixels_of(&fb, 3, got, sizeof got);
    cr_assert_str_eq(got, "3,4 4,5 5,6 6,7 7,8 8,9 ");
    /* Every pixel once. */
    s = draw_pixels(&fb, &m, SR_SHADE_ID, 1.0f, true);
    for (size_t i = 0; i < scene_pixel_count(&fb); i++)
        cr_assert_leq(fb.color[i], 1, "pixel %zu drawn %u times", i, fb.color[i]);
    cr_assert_eq(s.fragments, 18);
    sr_mesh_free(&m);
    sr_framebuffer_destroy(&fb);
}

Test(lines, lines_on_pixel_borders_follow_direct3d_diamonds)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    /* Horizontal on y = 3: each diamond's bottom corner is in (row 2);
     * vertical on x = 12: a y-major line's right corner is in (column 11). */
    const float xyz[][3] = { { 1.5f, 3.0f, 0.5f }, { 6.5f, 3.0f, 0.5f }, { 12.0f, 1.5f, 0.5f }, { 12.0f, 5.5f, 0.5f } };
    const uint32_t idx[] = { 0, 1, 2, 3 };
    sr_mesh m;
    pixel_mesh(&m, xyz, 4, idx, 4, SR_LINE_LIST);
    char got[512];
    draw_pixels(&fb, &m, SR_SHADE_ID, 1.0f, false);
    pixels_of(&fb, 1, got, sizeof got);
    cr_assert_str_eq(got, "1,2 2,2 3,2 4,2 5,2 ");
    pixels_of(&fb, 2, got, sizeof got);
    cr_assert_str_eq(got, "11,1 11,2 11,3 11,4 ");
    /* Three wide: the rows −1 … +1 of each pixel of the thin line. */
    draw_pixels(&fb, &m, SR_SHADE_ID, 3.0f, false);
    pixels_of(&fb, 2, got, sizeof got);
    cr_assert_str_eq(got, "10,1 11,1 12,1 10,2 11,2 12,2 10,3 11,3 12,3 10,4 11,4 12,4 ");
    sr_mesh_free(&m);
    sr_framebuffer_destroy(&fb);
}

/* ---- the diamond-exit rule against an exact oracle ---- */

/* p/q with q > 0. */
typedef struct ratio {
    int64_t p, q;
} ratio;

static int ratio_cmp(ratio a, ratio b)
{
    __int128 l = (__int128)a.p * b.q, r = (__int128)b.p * a.q;
    return (l > r) - (l < r);
}

/* Whether the segment a -> b meets the diamond |u| + |v| < h (open) or
 * <= h (closed) around c: Liang–Barsky on its four sides, in exact ratios. */
static bool segment_meets_diamond(const int64_t a[2], const int64_t b[2], const int64_t c[2], int64_t h, bool open)
{
    int64_t u0 = a[0] - c[0], v0 = a[1] - c[1], du = b[0] - a[0], dv = b[1] - a[1];
    ratio lo = { 0, 1 }, hi = { 1, 1 };
    bool lo_strict = false, hi_strict = false;
    for (int su = -1; su <= 1; su += 2)
        for (int sv = -1; sv <= 1; sv += 2) {
            /* h − (su·u + sv·v) = alpha + beta·t, >= 0 or > 0 */
            int64_t alpha = h - (su * u0 + sv * v0), beta = -(su * du + sv * dv);
            if (beta == 0) {
                if (alpha < 0 || (open && alpha == 0))
                    return false;
                continue;
            }
            ratio t = beta > 0 ? (ratio){ -alpha, beta } : (ratio){ alpha, -beta };
            if (beta > 0) {
                int c2 = ratio_cmp(t, lo);
                if (c2 > 0 || (c2 == 0 && open)) {
                    lo = t;
                    lo_strict = open;
                }
            } else {
                int c2 = ratio_cmp(t, hi);
                if (c2 < 0 || (c2 == 0 && open)) {
                    hi = t;
                    hi_strict = open;
                }
            }
        }
    int c2 = ratio_cmp(lo, hi);
    return c2 < 0 || (c2 == 0 && !lo_strict && !hi_strict);
}

static bool point_in_open_diamond(const int64_t p[2], const int64_t c[2], int64_t h)
{
    return llabs(p[0] - c[0]) + llabs(p[1] - c[1]) < h;
}

static bool point_on_diamond(const int64_t p[2], const int64_t c[2], int64_t h)
{
    return llabs(p[0] - c[0]) + llabs(p[1] - c[1]) == h;
}

Test(lines, random_lines_cover_the_pixels_whose_diamond_they_exit)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    test_rng r = { 36 };
    sr_mesh m;
    const float start[][3] = { { 0, 0, 0.5f }, { 0, 0, 0.5f } };
    const uint32_t idx[] = { 0, 1 };
    pixel_mesh(&m, start, 2, idx, 2, SR_LINE_LIST);
    int checked = 0;
    for (int n = 0; n < 3000; n++) {
        int64_t e[2][2];
        for (int k = 0; k < 2; k++) {
            /* Some ends on whole or half pixels, where the ties are. */
            int grid = rng_below(&r, 3) == 0 ? ONE / 2 : 1;
            /* Inside the framebuffer: a clipped end is snapped anew. */
            e[k][0] = rng_range(&r, 0, W * ONE) / grid * grid;
            e[k][1] = rng_range(&r, 0, H * ONE) / grid * grid;
            if (n % 5 == 0 && k == 1) /* short ones */
                for (int c = 0; c < 2; c++)
                    e[1][c] = llabs(e[0][c] + rng_range(&r, -ONE, ONE)) % ((c ? H : W) * ONE);
            m.positions[k][0] = (float)e[k][0] / ONE;
            m.positions[k][1] = (float)e[k][1] / ONE;
        }
        draw_pixels(&fb, &m, SR_SHADE_ID, 1.0f, false);
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                int64_t c[2] = { x * ONE + ONE / 2, y * ONE + ONE / 2 };
                bool open = segment_meets_diamond(e[0], e[1], c, ONE / 2, true);
                bool closed = segment_meets_diamond(e[0], e[1], c, ONE / 2, false);
                if (open != closed || point_on_diamond(e[1], c, ONE / 2))
                    continue; /* on the diamond's sides: the small scenes above pin those */
                bool want = open && !point_in_open_diamond(e[1], c, ONE / 2);
                cr_assert_eq(at(&fb, x, y) == 1, want,
                             "line (%lld, %lld) -> (%lld, %lld) /256 at pixel (%d, %d): drawn %d, want %d",
                             (long long)e[0][0], (long long)e[0][1], (long long)e[1][0], (long long)e[1][1], x, y,
                             at(&fb, x, y) == 1, want);
                checked++;
            }
    }
    cr_assert_gt(checked, 3000 * W * H * 9 / 10);
    sr_mesh_free(&m);
    sr_framebuffer_destroy(&fb);
}

/* ---- clipping: a segment is cut as the triangle edge under it ---- */

/* A clip-space vertex from one of a few families: ordinary, spread over
 * decades, on a plane or an ulp off it, behind the eye, a perspective
 * projection's, with a varying that is its own x. */
static sr_vertex_out random_vertex(test_rng *r, int family, const sr_clip_depth *depth)
{
    sr_vertex_out v = vert4(rng_uniform(r, -3, 3), rng_uniform(r, -3, 3), rng_uniform(r, -2, 3), rng_uniform(r, -1, 3));
    float *c = v.v;
    if (family == 1)
        for (int k = 0; k < 4; k++)
            c[k] = (float)rng_log_signed(r, -6, 6);
    if (family == 2) {
        int plane = rng_below(r, SR_CLIP_PLANES);
        c[sr_clip_plane_table[plane].axis] = sr_clip_plane_coordinate_at((sr_clip_plane)plane, c[SR_W]);
        if (rng_below(r, 2))
            c[sr_clip_plane_table[plane].axis] = nextafterf(c[sr_clip_plane_table[plane].axis], INFINITY);
    }
    if (family == 3) {
        c[SR_W] = (float)rng_uniform(r, -20, 60);
        c[SR_X] = (float)(1.3 * rng_uniform(r, -30, 30));
        c[SR_Y] = (float)(1.7 * rng_uniform(r, -30, 30));
    }
    if (depth->on)
        sr_clip_z_from_w(depth, c);
    c[SR_VARYINGS_AT] = c[SR_X];
    return v;
}

static bool same_point(const sr_vertex_out *a, const sr_vertex_out *b, bool with_z)
{
    return memcmp(&a->v[SR_X], &b->v[SR_X], 2 * sizeof(float)) == 0 &&
           memcmp(&a->v[SR_W], &b->v[SR_W], sizeof(float)) == 0 &&
           (!with_z || memcmp(&a->v[SR_Z], &b->v[SR_Z], sizeof(float)) == 0);
}

Test(lines, segments_are_cut_as_the_triangle_edges_they_lie_on_bit_for_bit)
{
    test_rng r = { 3636 };
    const sr_clip_depth depths[2] = { { .on = false }, { .on = true, .a = 100.0f / 99.9f, .b = -10.0f / 99.9f } };
    int compared = 0, multi = 0, mapped = 0;
    for (int n = 0; n < 40000; n++) {
        const sr_clip_depth *depth = &depths[n % 2];
        sr_clip_precision precision = (sr_clip_precision)(n / 2 % SR_CLIP_PRECISIONS);
        sr_vertex_out tri[3];
        unsigned any = 0, all = SR_OUT_PLANES;
        for (int k = 0; k < 3; k++) {
            tri[k] = random_vertex(&r, rng_below(&r, 4), depth);
            unsigned code = sr_clip_outcode_with(tri[k].v, depth);
            any |= code;
            all &= code;
        }
        if ((any & SR_OUT_NONFINITE) || all || !any)
            continue;
        sr_clip_counts counts = { { 0 } };
        sr_clip_config cfg = { .precision = precision, .depth = *depth, .counts = &counts };
        sr_polygon poly = poly3(tri[0], tri[1], tri[2]);
        int count = sr_clip_polygon(&poly, any, SR_VARYINGS_AT + 1, &cfg);
        if (counts.edge_by_edge) /* a degenerate triangle, clipped edge by edge: its own cuts */
            continue;
        for (int i = 0; i < count; i++) {
            int edge = poly.line[i];
            if (edge >= SR_CLIP_ON_PLANE)
                continue;
            sr_vertex_out ends[2] = { tri[edge], tri[(edge + 1) % 3] }, out[2];
            unsigned c0 = sr_clip_outcode_with(ends[0].v, depth), c1 = sr_clip_outcode_with(ends[1].v, depth);
            unsigned planes = c0 | c1;
            /* The fixed float and double knobs may keep a sliver of an edge
             * outside a plane (a rounded cut put back inside it); the
             * segment is rejected whole there. */
            if (c0 & c1)
                continue;
            int cut[2];
            bool kept = sr_clip_segment(ends, planes, SR_VARYINGS_AT + 1, &cfg, out, cut);
            cr_assert(kept, "case %d: the triangle keeps a piece of edge %d, the segment none", n, edge);
            const sr_vertex_out *want[2] = { &poly.vert[i], &poly.vert[(i + 1) % count] };
            for (int k = 0; k < 2; k++)
                cr_assert(same_point(&out[k], want[k], !depth->on),
                          "case %d (precision %d, depth %d), edge %d end %d: segment (%a %a %a %a), triangle (%a %a %a %a)",
                          n, (int)precision, depth->on, edge, k, out[k].v[0], out[k].v[1], out[k].v[2], out[k].v[3],
                          want[k]->v[0], want[k]->v[1], want[k]->v[2], want[k]->v[3]);
            /* And mapped to the same screen points and depths as the
             * triangle's vertices there (depth from the point on the two
             * lines in double). */
            const sr_viewport vp = { 640, 480, SR_SUBPIXEL_BITS, 1.0f, *depth };
            double tri_d[3][4], seg_d[3][4];
            for (int v = 0; v < 3; v++)
                to_double4(&tri[v], tri_d[v]);
            memcpy(seg_d[0], tri_d[edge], sizeof seg_d[0]);
            memcpy(seg_d[1], tri_d[(edge + 1) % 3], sizeof seg_d[1]);
            memcpy(seg_d[2], tri_d[edge], sizeof seg_d[2]);
            sr_screen_vertex poly_screen[SR_MAX_CLIP_VERTS], seg_screen[2];
            if (sr_viewport_map_polygon(&poly, tri_d, 1, &vp, poly_screen)) {
                for (int k = 0; k < 2; k++) {
                    double point[4];
                    if (cut[k] == SR_SEGMENT_END_GIVEN)
                        memcpy(point, seg_d[k], sizeof point);
                    else
                        sr_clip_point_on_lines_d(seg_d, 0, SR_CLIP_ON_PLANE + cut[k], depth, point);
                    cr_assert(sr_viewport_map_checked_d(&out[k], point, 1, &vp, &seg_screen[k]));
                    const sr_screen_vertex *p = &poly_screen[(i + k) % count];
                    cr_assert(seg_screen[k].x == p->x && seg_screen[k].y == p->y && seg_screen[k].z == p->z &&
                                  seg_screen[k].x_off == p->x_off && seg_screen[k].y_off == p->y_off,
                              "case %d, edge %d end %d: screen (%lld %lld %a), triangle's (%lld %lld %a)", n, edge, k,
                              (long long)seg_screen[k].x, (long long)seg_screen[k].y, seg_screen[k].z,
                              (long long)p->x, (long long)p->y, p->z);
                }
                mapped++;
            }
            compared++;
            multi += __builtin_popcount(planes) > 1;
        }
    }
    cr_assert_gt(compared, 20000, "%d edges compared", compared);
    cr_assert_gt(multi, 2000, "%d edges over two planes or more", multi);
    cr_assert_gt(mapped, 10000, "%d edges mapped", mapped);
}

/* A clip-space line list: positions[k] given as (x, y, z, w). */
static void clip_lines(sr_mesh *m, const float (*c)[4], uint32_t n, sr_topology topology)
{
    scene_mesh_alloc(m, n, 1, false);
    free(m->indices);
    m->indices = malloc(n * sizeof(uint32_t));
    m->clip_positions = malloc(n * sizeof *m->clip_positions);
    cr_assert(m->indices && m->clip_positions);
    m->index_count = n;
    for (uint32_t k = 0; k < n; k++) {
        glm_vec4_copy((float *)c[k], m->clip_positions[k]);
        m->indices[k] = k;
    }
    m->topology = topology;
}

static sr_stats draw_clip_space(sr_framebuffer *fb, const sr_mesh *m, float size)
{
    sr_framebuffer_clear(fb, 0);
    sr_draw_desc desc = { .mesh = m, .shade = SR_SHADE_ID, .point_size = size, .line_width = size };
    return draw_desc(fb, &desc);
}

Test(lines, lines_through_every_plane_the_eye_and_bad_numbers_are_clipped_or_dropped)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    const float nan = NAN, inf = INFINITY;
    const float c[][4] = {
        { 0, 0, 0.5f, 1 }, { 3, 0, 0.5f, 1 },       /* 1: out through the right plane */
        { -3, 0.5f, 0.5f, 1 }, { 0, 0.5f, 0.5f, 1 }, /* 2: in through the left */
        { 0, 3, 0.5f, 1 }, { 0, -3, 0.5f, 1 },       /* 3: across top and bottom */
        { 0.5f, 0, -1, 1 }, { 0.5f, 0, 2, 1 },       /* 4: across near and far */
        { -0.5f, -0.5f, -0.5f, -1 }, { 0.5f, 0.5f, 0.5f, 1 }, /* 5: through the eye: cut to w = 0 */
        { 0, 0, 0, 0 }, { 0.5f, 0.5f, 0.5f, 1 },     /* 6: from w = 0 at the origin */
        { nan, 0, 0.5f, 1 }, { 0.5f, 0, 0.5f, 1 },   /* 7: NaN */
        { 0, inf, 0.5f, 1 }, { 0.5f, 0, 0.5f, 1 },   /* 8: inf */
        { 2, 2, 0.5f, 1 }, { 3, 2, 0.5f, 1 },        /* 9: outside the right plane */
        { 0.2f, 0.2f, 0.5f, -1 }, { 0.3f, 0.2f, 0.5f, -1 }, /* 10: behind the eye */
    };
    sr_mesh m;
    clip_lines(&m, c, 20, SR_LINE_LIST);
    sr_stats s = draw_clip_space(&fb, &m, 1.0f);
    cr_assert_eq(s.lines, 10);
    cr_assert_eq(s.rejected, 5);
    /* NaN, inf, and the end at w = 0 inside every plane (the eye: it maps nowhere). */
    cr_assert_eq(s.nonfinite, 3);
    cr_assert_eq(s.rejected_by_plane[SR_PLANE_RIGHT], 1);
    cr_assert_eq(s.rejected_by_plane[SR_PLANE_FAR], 1, "behind the eye: past far (z > w < 0) first");
    cr_assert_eq(s.clipped, 5);
    /* Lines 1 to 4 drawn; 5, through the eye, is cut to w = 0 and dropped. */
    cr_assert_eq(s.drawn, 4);
    char got[1024];
    /* Line 1 from the centre out through the right side, on the border of
     * rows 7 and 8: the diamonds' bottom corners, row 7. */
    pixels_of(&fb, 1, got, sizeof got);
    cr_assert_str_eq(got, "12,7 13,7 14,7 15,7 16,7 17,7 18,7 19,7 20,7 21,7 22,7 23,7 ");
    pixels_of(&fb, 2, got, sizeof got);
    cr_assert_str_eq(got, "0,3 1,3 2,3 3,3 4,3 5,3 6,3 7,3 8,3 9,3 10,3 11,3 ");
    /* Line 3 across the whole height on x = 0, between columns 11 and 12,
     * but where line 2 was first at the same depth (LESS). */
    cr_assert_eq(scene_count_color(&fb, 3), H - 1);
    cr_assert_eq(at(&fb, 11, 0), 3);
    cr_assert_eq(at(&fb, 11, 3), 2);
    /* Line 4 runs along the view axis: one point on screen, no pixel. */
    cr_assert_eq(scene_count_color(&fb, 4), 0);
    cr_assert_eq(s.fragments, 12 + 12 + H - 1);
    sr_mesh_free(&m);
    sr_framebuffer_destroy(&fb);
}

Test(points, a_point_is_kept_or_dropped_by_its_position_and_its_square_cut_to_the_framebuffer)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    const float over = 1.0f + 2.0f / W; /* the centre a pixel past the right side */
    const float c[][4] = {
        { 0, 0, 0.5f, 1 },      /* 1: in view */
        { 0, 0, -0.1f, 1 },     /* 2: in front of near */
        { 0, 0, 1.1f, 1 },      /* 3: past far */
        { over, 0, 0.5f, 1 },   /* 4: past the right side; a wide square reaches in */
        { 3, 0, 0.5f, 1 },      /* 5: far past it */
        { 0, 0, 0, 0 },         /* 6: w = 0: the eye */
        { NAN, 0, 0.5f, 1 },    /* 7 */
        { 0, -INFINITY, 0.5f, 1 }, /* 8 */
        { 0.5f, 0.5f, 0.5f, -1 }, /* 9: behind the eye */
    };
    sr_mesh m;
    clip_lines(&m, c, 9, SR_POINT_LIST);
    sr_stats s = draw_clip_space(&fb, &m, 5.0f);
    cr_assert_eq(s.points, 9);
    cr_assert_eq(s.rejected, 7);
    cr_assert_eq(s.nonfinite, 3);
    cr_assert_eq(s.rejected_by_plane[SR_PLANE_NEAR], 1);
    cr_assert_eq(s.rejected_by_plane[SR_PLANE_FAR], 2, "past far, and behind the eye (z > w < 0)");
    cr_assert_eq(s.rejected_by_plane[SR_PLANE_RIGHT], 1);
    cr_assert_eq(s.clipped, 0);
    cr_assert_eq(s.drawn, 2);
    char got[1024];
    /* 5 × 5 around (12, 8): the centres in [9.5, 14.5) and [5.5, 10.5). */
    pixels_of(&fb, 1, got, sizeof got);
    cr_assert_str_eq(got, "9,5 10,5 11,5 12,5 13,5 9,6 10,6 11,6 12,6 13,6 9,7 10,7 11,7 12,7 13,7 "
                          "9,8 10,8 11,8 12,8 13,8 9,9 10,9 11,9 12,9 13,9 ");
    /* Centred on x = 25 px: the columns with centres from 22.5, two in view. */
    pixels_of(&fb, 4, got, sizeof got);
    cr_assert_str_eq(got, "22,5 23,5 22,6 23,6 22,7 23,7 22,8 23,8 22,9 23,9 ");
    /* One pixel wide, the same point reaches nothing: kept, no pixel. */
    s = draw_clip_space(&fb, &m, 1.0f);
    cr_assert_eq(s.drawn, 2);
    cr_assert_eq(scene_count_color(&fb, 4), 0);
    cr_assert_eq(s.fragments, 1);
    sr_mesh_free(&m);
    sr_framebuffer_destroy(&fb);
}

/* dEQP-GLES3.functional.clipping.point.point_z_clip and wide_point_clip,
 * their points (es3fClippingTests.cpp) on a 24 × 16 canvas: GL's clip
 * volume has −w <= z, softrast's (Direct3D's) 0 <= z, so the points at
 * z = −0.1 that dEQP keeps in view are dropped here; the others keep
 * dEQP's verdicts. */
Test(points, deqp_point_clip_cases_carry_over_but_for_the_depth_range)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    const float c[][4] = {
        { 0.0f, 0.0f, 0.0f, 1.0f }, { 0.1f, 0.1f, 0.1f, 1.0f }, { -0.1f, 0.1f, -0.1f, 1.0f },
        { -0.1f, -0.1f, 0.1f, 1.0f }, { 0.1f, -0.1f, -0.1f, 1.0f }, /* in GL's volume */
        { 0.1f, 0.0f, 1.1f, 1.0f }, { -0.1f, 0.0f, -1.1f, 1.0f }, { -0.0f, -0.1f, 1.1f, 1.0f },
        { 0.0f, 0.1f, -1.1f, 1.0f }, /* clipped in both */
    };
    sr_mesh m;
    clip_lines(&m, c, 9, SR_POINT_LIST);
    sr_stats s = draw_clip_space(&fb, &m, 1.0f);
    cr_assert_eq(s.drawn, 3, "the three with z >= 0 of dEQP's five");
    cr_assert_eq(s.rejected_by_plane[SR_PLANE_NEAR], 4);
    cr_assert_eq(s.rejected_by_plane[SR_PLANE_FAR], 2);
    /* On pixel corners, (12, 8) and (13.2, 7.2), (10.8, 8.8) in pixels. */
    cr_assert_eq(at(&fb, 11, 7), 1);
    cr_assert_eq(at(&fb, 13, 7), 2);
    cr_assert_eq(at(&fb, 10, 8), 4);
    sr_mesh_free(&m);
    /* wide_point_clip's last three: centres a pixel past the right side
     * (x = 25 px) or the top (y = −1 px), 5 px wide, drawn in part: the
     * centres in [22.5, 27.5) and [−3.5, 1.5). */
    const float over = 1.0f + 2.0f / W, over_y = 1.0f + 2.0f / H;
    const float edge[][4] = { { over, over_y, 0.0f, 1.0f }, { 0.0f, over_y, 0.0f, 1.0f }, { over, 0.0f, 0.0f, 1.0f } };
    clip_lines(&m, edge, 3, SR_POINT_LIST);
    s = draw_clip_space(&fb, &m, 5.0f);
    cr_assert_eq(s.drawn, 3);
    cr_assert_eq(scene_count_color(&fb, 1), 2, "the corner: 2 × 1 in view");
    cr_assert_eq(scene_count_color(&fb, 2), 5, "the top: 5 × 1");
    cr_assert_eq(scene_count_color(&fb, 3), 10, "the right: 2 × 5");
    sr_mesh_free(&m);
    sr_framebuffer_destroy(&fb);
}

/* dEQP-GLES3.functional.clipping.line.line_z_clip's lines: from the centre
 * past the far plane (z = 2w), or past near (z = −2w). Past far they keep
 * the piece up to z = w as in GL; past near, GL keeps the piece down to
 * z = −w and softrast the piece down to z = 0: the centre's pixel only. */
Test(lines, deqp_line_z_clip_cases_carry_over_but_for_the_depth_range)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, 200, 200);
    const float c[][4] = {
        { 0.0f, 0.0f, 0.0f, 1.0f }, { 1.3f, 1.0f, 2.0f, 1.0f },   { 0.0f, 0.0f, 0.0f, 1.0f }, { 1.3f, -1.0f, 2.0f, 1.0f },
        { 0.0f, 0.0f, 0.0f, 1.0f }, { -1.0f, -1.1f, -2.0f, 1.0f }, { 0.0f, 0.0f, 0.0f, 1.0f }, { -1.0f, 1.1f, -2.0f, 1.0f },
        { 0.0f, 0.0f, 0.0f, 1.0f }, { 1.0f, 0.1f, 2.0f, 0.6f },
    };
    sr_mesh m;
    clip_lines(&m, c, 10, SR_LINE_LIST);
    sr_stats s = draw_clip_space(&fb, &m, 1.0f);
    cr_assert_eq(s.clipped, 5);
    /* Past far: cut at t = ½, (0.65, ±0.5) NDC, 65 columns of x-major line. */
    cr_assert_eq(scene_count_color(&fb, 1), 65);
    cr_assert_eq(scene_count_color(&fb, 2), 65);
    cr_assert_eq(scene_count_color(&fb, 3) + scene_count_color(&fb, 4), 0, "cut to the point z = 0 at the centre");
    /* The last reaches z = w at t = 1/2.4, (0.5, 0.05) NDC: the columns
     * 100 … 149, the first of them line 1's at the same depth (LESS). */
    cr_assert_eq(scene_count_color(&fb, 5), 49);
    cr_assert_eq(at(&fb, 100, 99), 1);
    sr_mesh_free(&m);
    sr_framebuffer_destroy(&fb);
}

/* A random soup of points or lines under a perspective camera: some
 * through the near plane, the sides and behind the eye. */
static void random_soup(sr_mesh *m, sr_topology topology, uint32_t n, test_rng *r)
{
    sr_error err = { "" };
    cr_assert(sr_mesh_alloc(m, n, n, true, false, true, &err), "%s", err.message);
    for (uint32_t i = 0; i < n; i++) {
        for (int c = 0; c < 3; c++) {
            m->positions[i][c] = (float)rng_uniform(r, -4, 4);
            m->colors[i][c] = (float)rng_unit(r);
            m->normals[i][c] = (float)rng_uniform(r, -1, 1);
        }
        m->indices[i] = (uint32_t)rng_below(r, (int)n);
    }
    m->topology = topology;
}

Test(lines, points_and_lines_are_the_same_on_every_thread_count_and_path)
{
    const sr_topology topologies[] = { SR_POINT_LIST, SR_LINE_LIST, SR_LINE_STRIP };
    test_rng r = { 7 };
    for (int t = 0; t < 3; t++) {
        sr_mesh m;
        random_soup(&m, topologies[t], 3000, &r);
        sr_camera cam = scene_camera(0.5f, 0.3f, -2.5f, 0, 0, 0, 70.0f, 0.1f, 10.0f);
        sr_draw_desc desc = { .mesh = &m, .shade = SR_SHADE_LAMBERT, .point_size = 3.0f, .line_width = 2.0f };
        scene_camera_desc(&desc, &cam, 160, 120);
        sr_framebuffer one, other;
        scene_fb_make(&one, 160, 120);
        scene_fb_make(&other, 160, 120);
        sr_stats s1, s2;
        sr_framebuffer_clear(&one, 0);
        scene_draw_on_loop(&one, &desc, SR_SIMD_AUTO, 1, SR_PATH_DIRECT, &s1);
        cr_assert_gt(s1.fragments, 1000);
        cr_assert_gt(s1.clipped + s1.rejected, 0);
        const sr_draw_path paths[] = { SR_PATH_BY_COST, SR_PATH_TILES, SR_PATH_ROWS };
        for (int threads = 2; threads <= 7; threads += 5)
            for (int p = 0; p < 3; p++) {
                sr_framebuffer_clear(&other, 0);
                scene_draw_on_loop(&other, &desc, SR_SIMD_AUTO, threads, paths[p], &s2);
                cr_assert(memcmp(one.color, other.color, 160 * 120 * 4) == 0 &&
                              memcmp(one.depth, other.depth, 160 * 120 * 4) == 0 && memcmp(&s1, &s2, sizeof s1) == 0,
                          "topology %d, %d threads, path %d", (int)topologies[t], threads, (int)paths[p]);
            }
        sr_framebuffer_destroy(&one);
        sr_framebuffer_destroy(&other);
        sr_mesh_free(&m);
    }
}

/* The soup as a cloud whose slots index consecutive vertices (the
 * blocks of points_lines.c's fast path), and its twin with every vertex
 * stored twice and indexed at 2k, which no block can take: the same
 * points in the same order. Some lie outside a plane, on the eye, or
 * carry a NaN colour, some lie on an earlier one (the depth test keeps
 * the first), and the block size does not divide n. */
static void cloud_and_twin(sr_mesh *cloud, sr_mesh *twin, uint32_t n, test_rng *r)
{
    sr_error err = { "" };
    cr_assert(sr_mesh_alloc(cloud, n, n, true, false, true, &err), "%s", err.message);
    cr_assert(sr_mesh_alloc(twin, 2 * n, n, true, false, true, &err), "%s", err.message);
    for (uint32_t i = 0; i < n; i++) {
        for (int c = 0; c < 3; c++) {
            cloud->positions[i][c] = (float)rng_uniform(r, -1.5, 1.5);
            cloud->colors[i][c] = (float)rng_unit(r);
            cloud->normals[i][c] = (float)rng_uniform(r, -1, 1);
        }
        if (i % 997 == 5)
            cloud->colors[i][1] = NAN;
        if (i % 1009 == 7)
            glm_vec3_copy((vec3){ 0.5f, 0.3f, -2.5f }, cloud->positions[i]); /* the eye */
        if (i % 7 == 3 && i >= n / 2) /* on an earlier point, in another thread's run: the first drawn stays */
            glm_vec3_copy(cloud->positions[i - n / 2], cloud->positions[i]);
        cloud->indices[i] = i;
        for (uint32_t k = 2 * i; k <= 2 * i + 1; k++) {
            glm_vec3_copy(cloud->positions[i], twin->positions[k]);
            glm_vec3_copy(cloud->colors[i], twin->colors[k]);
            glm_vec3_copy(cloud->normals[i], twin->normals[k]);
        }
        twin->indices[i] = 2 * i;
    }
    cloud->topology = twin->topology = SR_POINT_LIST;
}

Test(points, one_pixel_points_in_blocks_match_the_point_by_point_loop_on_every_thread_count)
{
    test_rng r = { 36 };
    sr_mesh cloud, twin;
    cloud_and_twin(&cloud, &twin, 20011, &r);
    const sr_shade shades[] = { SR_SHADE_COLOR, SR_SHADE_LAMBERT, SR_SHADE_DEPTH };
    sr_framebuffer want, got;
    scene_fb_make(&want, 97, 61);
    scene_fb_make(&got, 97, 61);
    for (int k = 0; k < 3; k++) {
        sr_camera cam = scene_camera(0.5f, 0.3f, -2.5f, 0, 0, 0, 70.0f, 0.1f, 10.0f);
        sr_draw_desc desc = { .mesh = &twin, .shade = shades[k], .depth_bias = k == 1 ? 1e-3f : 0.0f };
        scene_camera_desc(&desc, &cam, 97, 61);
        sr_stats s1, s2;
        sr_framebuffer_clear(&want, 0);
        scene_draw_on_loop(&want, &desc, SR_SIMD_AUTO, 1, SR_PATH_DIRECT, &s1);
        cr_assert_gt(s1.fragments, 2000);
        cr_assert(shades[k] == SR_SHADE_DEPTH || s1.nonfinite > 0, "the NaN colours are read");
        cr_assert_gt(s1.rejected, s1.nonfinite);
        desc.mesh = &cloud;
        for (int threads = 1; threads <= 16; threads++) {
            sr_framebuffer_clear(&got, 0);
            scene_draw_on_loop(&got, &desc, SR_SIMD_AUTO, threads, SR_PATH_BY_COST, &s2);
            cr_assert(memcmp(want.color, got.color, sizeof(uint32_t) * 97 * 61) == 0 &&
                          memcmp(want.depth, got.depth, sizeof(float) * 97 * 61) == 0 &&
                          memcmp(&s1, &s2, sizeof s1) == 0,
                      "shade %d, %d threads", (int)shades[k], threads);
        }
    }
    sr_framebuffer_destroy(&want);
    sr_framebuffer_destroy(&got);
    sr_mesh_free(&cloud);
    sr_mesh_free(&twin);
}

/* A cloud given in clip space, in blocks (consecutive vertices), against
 * its twin whose point k is vertex 2k, drawn point by point: the blocks
 * map their own clip positions, the same bits. */
Test(points, a_clip_space_cloud_in_blocks_matches_the_point_by_point_loop)
{
    enum { N = 300, SIDE = 64 };
    sr_mesh cloud = { .vertex_count = N, .index_count = N, .topology = SR_POINT_LIST },
            twin = { .vertex_count = 2 * N, .index_count = N, .topology = SR_POINT_LIST };
    cloud.clip_positions = calloc(N, sizeof(vec4));
    twin.clip_positions = calloc(2 * N, sizeof(vec4));
    cloud.indices = calloc(N, sizeof(uint32_t));
    twin.indices = calloc(N, sizeof(uint32_t));
    cr_assert(cloud.clip_positions && twin.clip_positions && cloud.indices && twin.indices);
    test_rng r = { 5 };
    for (uint32_t i = 0; i < N; i++) {
        /* NDC inside the view, times a w of its own: the divisions matter */
        float w = (float)rng_uniform(&r, 0.5, 2.0);
        vec4 c = { (float)rng_uniform(&r, -0.9, 0.9) * w, (float)rng_uniform(&r, -0.9, 0.9) * w,
                   (float)rng_uniform(&r, 0.05, 0.95) * w, w };
        glm_vec4_copy(c, cloud.clip_positions[i]);
        glm_vec4_copy(c, twin.clip_positions[2 * i]);
        glm_vec4_copy(c, twin.clip_positions[2 * i + 1]);
        cloud.indices[i] = i;
        twin.indices[i] = 2 * i;
    }
    sr_framebuffer want, got;
    scene_fb_make(&want, SIDE, SIDE);
    scene_fb_make(&got, SIDE, SIDE);
    sr_draw_desc desc = { .mesh = &twin, .shade = SR_SHADE_ID };
    sr_stats s1, s2;
    sr_framebuffer_clear(&want, 0);
    scene_draw_on_loop(&want, &desc, SR_SIMD_AUTO, 1, SR_PATH_DIRECT, &s1);
    cr_assert_gt(s1.fragments, 100);
    desc.mesh = &cloud;
    sr_framebuffer_clear(&got, 0);
    scene_draw_on_loop(&got, &desc, SR_SIMD_AUTO, 1, SR_PATH_DIRECT, &s2);
    cr_assert(memcmp(want.color, got.color, sizeof(uint32_t) * SIDE * SIDE) == 0 &&
                  memcmp(want.depth, got.depth, sizeof(float) * SIDE * SIDE) == 0 && memcmp(&s1, &s2, sizeof s1) == 0,
              "the blocks differ from the point-by-point loop");
    sr_framebuffer_destroy(&want);
    sr_framebuffer_destroy(&got);
    free(cloud.clip_positions);
    free(twin.clip_positions);
    free(cloud.indices);
    free(twin.indices);
}

/* The room a workspace's bins keep, in fragments, over its first
 * `threads` threads. */
static size_t bins_room(sr_workspace *ws, int threads)
{
    size_t room = 0;
    for (int t = 0; t < threads; t++)
        for (size_t b = 0; b < ws->threads[t].fragment_bin_count; b++)
            room += ws->threads[t].fragment_bins[b].capacity;
    return room;
}

/* 400 points 256 pixels wide over a 512 x 512 frame make 26M fragments,
 * more than a draw on several threads bins at once (16 bytes each): it
 * bins and stores them in rounds of slots, so the bins never hold room
 * for much more than the budget, and the picture and the counts are the
 * one thread's; a draw that fits in one round next, on the same
 * workspace, too. */
Test(points, points_too_large_to_bin_at_once_are_binned_in_rounds)
{
    enum { N = 400, SIDE = 512 };
    sr_mesh pts = { .vertex_count = N, .index_count = N, .topology = SR_POINT_LIST };
    pts.clip_positions = calloc(N, sizeof(vec4));
    pts.indices = calloc(N, sizeof(uint32_t));
    cr_assert(pts.clip_positions && pts.indices);
    test_rng r = { 17 };
    for (uint32_t i = 0; i < N; i++) {
        glm_vec4_copy((vec4){ (float)rng_uniform(&r, -0.5, 0.5), (float)rng_uniform(&r, -0.5, 0.5),
                              (float)rng_uniform(&r, 0.05, 0.95), 1.0f },
                      pts.clip_positions[i]);
        pts.indices[i] = i;
    }
    sr_framebuffer one, two;
    scene_fb_make(&one, SIDE, SIDE);
    scene_fb_make(&two, SIDE, SIDE);
    sr_draw_desc desc = { .mesh = &pts, .shade = SR_SHADE_ID, .point_size = 256.0f };
    sr_stats s1, s2;
    sr_framebuffer_clear(&one, 0);
    scene_draw_on_loop(&one, &desc, SR_SIMD_AUTO, 1, SR_PATH_DIRECT, &s1);
    cr_assert_gt(s1.fragments, (uint64_t)SIDE * SIDE / 2, "%llu fragments passed", (unsigned long long)s1.fragments);
    sr_draw_times times = { 0 };
    sr_workspace *ws = sr_workspace_create();
    cr_assert_not_null(ws);
    sr_draw_desc many = desc;
    many.study = &(sr_draw_study){ .times = &times };
    many.threads = 2;
    many.workspace = ws;
    sr_error err = { "" };
    s2 = (sr_stats){ 0 };
    sr_framebuffer_clear(&two, 0);
    cr_assert(sr_draw(&two, &many, &s2, &err), "%s", err.message);
    cr_assert_eq(times.path, SR_PATH_ROWS, "the draw took path %d", (int)times.path);
    cr_assert_leq(bins_room(ws, 2), 2 * SR_FRAGMENT_BIN_BUDGET + 2 * SR_ROW_BANDS * 64, "the bins keep room for %zu",
                  bins_room(ws, 2));
    cr_assert(memcmp(one.color, two.color, sizeof(uint32_t) * SIDE * SIDE) == 0 &&
                  memcmp(one.depth, two.depth, sizeof(float) * SIDE * SIDE) == 0 && memcmp(&s1, &s2, sizeof s1) == 0,
              "two threads differ from one");
    /* a draw that fits the bins on the same workspace still takes them */
    desc.point_size = 1.0f;
    many.point_size = 1.0f;
    times = (sr_draw_times){ 0 };
    cr_assert(sr_draw(&two, &many, &s2, &err), "%s", err.message);
    cr_assert_eq(times.path, SR_PATH_ROWS);
    sr_workspace_destroy(ws);
    sr_framebuffer_destroy(&one);
    sr_framebuffer_destroy(&two);
    free(pts.clip_positions);
    free(pts.indices);
}

/* 1500 lines 12 pixels wide across a 512 x 512 frame, many through the
 * near plane and past the sides (so cut, and counted by precision), bin
 * more fragments than a draw on several threads may: it is made on one
 * thread instead, the same picture and counts as one thread's, cleared or
 * drawn over; and a draw that fits the bins next, on the same workspace,
 * is still binned and still the one thread's. */
Test(lines, lines_too_many_to_bin_are_drawn_on_one_thread)
{
    enum { N = 1500, SIDE = 512 };
    sr_mesh lines = { .vertex_count = 2 * N, .index_count = 2 * N, .topology = SR_LINE_LIST };
    lines.clip_positions = calloc(2 * N, sizeof(vec4));
    lines.indices = calloc(2 * N, sizeof(uint32_t));
    cr_assert(lines.clip_positions && lines.indices);
    test_rng r = { 23 };
    for (uint32_t i = 0; i < 2 * N; i++) {
        glm_vec4_copy((vec4){ (float)rng_uniform(&r, -1.6, 1.6), (float)rng_uniform(&r, -1.6, 1.6),
                              (float)rng_uniform(&r, -0.3, 0.9), 1.0f },
                      lines.clip_positions[i]);
        lines.indices[i] = i;
    }
    sr_framebuffer one, many;
    scene_fb_make(&one, SIDE, SIDE);
    scene_fb_make(&many, SIDE, SIDE);
    sr_workspace *ws = sr_workspace_create();
    cr_assert_not_null(ws);
    const struct {
        float width;
        bool clear;
    } draws[] = { { 32.0f, true }, { 32.0f, false }, { 1.0f, true } };
    for (size_t d = 0; d < sizeof draws / sizeof *draws; d++) {
        sr_draw_desc desc = { .mesh = &lines, .shade = SR_SHADE_ID, .line_width = draws[d].width,
                              .clear = draws[d].clear };
        sr_framebuffer_clear(&one, 0x123456);
        sr_framebuffer_clear(&many, 0x123456);
        sr_stats s1, s2 = { 0 };
        scene_draw_on_loop(&one, &desc, SR_SIMD_AUTO, 1, SR_PATH_DIRECT, &s1);
        cr_assert_gt(s1.cuts_float + s1.cuts_double + s1.cuts_exact, 100u, "draw %zu: few cuts", d);
        sr_draw_times times = { 0 };
        desc.study = &(sr_draw_study){ .times = &times };
        desc.threads = 2;
        desc.workspace = ws;
        sr_error err = { "" };
        cr_assert(sr_draw(&many, &desc, &s2, &err), "%s", err.message);
        cr_assert_eq(times.path, SR_PATH_ROWS, "draw %zu took path %d", d, (int)times.path);
        cr_assert(memcmp(one.color, many.color, sizeof(uint32_t) * SIDE * SIDE) == 0 &&
                      memcmp(one.depth, many.depth, sizeof(float) * SIDE * SIDE) == 0 &&
                      memcmp(&s1, &s2, sizeof s1) == 0,
                  "draw %zu: two threads differ from one", d);
    }
    sr_workspace_destroy(ws);
    sr_framebuffer_destroy(&one);
    sr_framebuffer_destroy(&many);
    free(lines.clip_positions);
    free(lines.indices);
}

Test(lines, a_line_over_its_triangle_needs_the_depth_bias_and_a_hidden_one_stays_hidden)
{
    sr_framebuffer fb, alone;
    scene_fb_make(&fb, W, H);
    scene_fb_make(&alone, W, H);
    /* A triangle tilted in depth (0.03 per pixel at most), its edges as
     * lines 1, 2 and 4, and line 3 at z = 0.9 across it, behind it where
     * it covers (0.32 … 0.54 there). */
    const float xyz[][3] = { { 2.0f, 2.0f, 0.2f }, { 20.0f, 3.0f, 0.7f }, { 4.0f, 14.0f, 0.4f },
                             { 0.5f, 9.0f, 0.9f }, { 23.5f, 9.0f, 0.9f } };
    const uint32_t tri_idx[] = { 0, 1, 2 }, line_idx[] = { 0, 1, 1, 2, 3, 4, 2, 0 };
    sr_mesh tri, lines;
    pixel_mesh(&tri, xyz, 5, tri_idx, 3, SR_TRIANGLE_LIST);
    pixel_mesh(&lines, xyz, 5, line_idx, 8, SR_LINE_LIST);
    sr_draw_desc fill = { .mesh = &tri, .shade = SR_SHADE_DEPTH, .cull = SR_CULL_NONE };
    sr_draw_desc desc = { .mesh = &lines, .shade = SR_SHADE_ID };
    scene_pixel_ortho(&fill, W, H);
    scene_pixel_ortho(&desc, W, H);
    sr_framebuffer_clear(&alone, 0);
    draw_desc(&alone, &desc);
    float filled[W * H];
    for (int bias = 0; bias < 2; bias++) {
        sr_framebuffer_clear(&fb, 0);
        draw_desc(&fb, &fill);
        memcpy(filled, fb.depth, sizeof filled);
        /* More than the plane's depth over the 0.7 px a line pixel's
         * centre may lie off the edge. */
        desc.depth_bias = bias ? 1.0f / 16.0f : 0.0f;
        draw_desc(&fb, &desc);
        size_t edge_lost = 0;
        for (int i = 0; i < W * H; i++) {
            bool edge = alone.color[i] == 1 || alone.color[i] == 2 || alone.color[i] == 4;
            edge_lost += edge && fb.color[i] != alone.color[i];
            cr_assert(fb.color[i] != 3 || filled[i] == 1.0f, "pixel (%d, %d): a hidden line shows", i % W, i / W);
            cr_assert_eq(fb.color[i] == 3, alone.color[i] == 3 && filled[i] == 1.0f);
        }
        /* Without a bias an edge loses where the triangle's plane at the
         * pixel centre, off the edge's line, is nearer; with it, never. */
        if (bias)
            cr_assert_eq(edge_lost, 0);
        else
            cr_assert_gt(edge_lost, 0);
    }
    sr_mesh_free(&tri);
    sr_mesh_free(&lines);
    sr_framebuffer_destroy(&fb);
    sr_framebuffer_destroy(&alone);
}

Test(lines, colors_are_interpolated_perspective_correctly)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, 64, 8);
    /* Clip space: from x = −1 at w = 1 (red) to x = 3 at w = 3 (blue), on
     * y = 0.25 w: x_ndc runs −1 → 1 while the color, linear in clip
     * space, runs as t_clip = t_s / (3 − 2 t_s) in screen t_s. */
    const float c[][4] = { { -1.0f, 0.25f, 0.5f, 1.0f }, { 3.0f, 0.75f, 1.5f, 3.0f } };
    sr_mesh m;
    clip_lines(&m, c, 2, SR_LINE_LIST);
    m.colors = calloc(2, sizeof(vec3));
    m.colors[0][0] = 1.0f;
    m.colors[1][2] = 1.0f;
    sr_framebuffer_clear(&fb, 0);
    sr_draw_desc desc = { .mesh = &m, .shade = SR_SHADE_COLOR };
    sr_stats s = draw_desc(&fb, &desc);
    cr_assert_eq(s.fragments, 64);
    for (int x = 0; x < 64; x++) {
        double ts = (x + 0.5) / 64.0, tc = ts / (3.0 - 2.0 * ts);
        uint32_t px = at(&fb, x, 2);
        int red = (int)(px >> 16), blue = (int)(px & 0xFF);
        cr_assert(abs(red - (int)lrint(255.0 * (1.0 - tc))) <= 1 && abs(blue - (int)lrint(255.0 * tc)) <= 1,
                  "pixel %d: %06x, want t = %f", x, px, tc);
    }
    sr_mesh_free(&m);
    sr_framebuffer_destroy(&fb);
}

Test(lines, bad_point_and_line_fields_are_refused)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    const float xyz[][3] = { { 1, 1, 0.5f }, { 5, 5, 0.5f } };
    const uint32_t idx[] = { 0, 1 }, past[] = { 0, 2 };
    sr_mesh m;
    pixel_mesh(&m, xyz, 2, idx, 2, SR_LINE_LIST);
    sr_error err = { "" };
    sr_draw_desc bad[] = { { .mesh = &m, .point_size = 0.5f }, { .mesh = &m, .point_size = NAN },
                           { .mesh = &m, .line_width = 65.0f }, { .mesh = &m, .depth_bias = -1e-3f },
                           { .mesh = &m, .depth_bias = INFINITY } };
    sr_framebuffer_clear(&fb, 0x123456);
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        bad[k].shade = SR_SHADE_ID;
        cr_assert_not(sr_draw(&fb, &bad[k], NULL, &err), "desc %zu drew", k);
        cr_assert_neq(err.message[0], '\0');
    }
    m.topology = (sr_topology)9;
    cr_assert_not(sr_draw(&fb, &(sr_draw_desc){ .mesh = &m }, NULL, &err));
    cr_assert_str_eq(err.message, "unknown topology 9");
    m.topology = SR_LINE_STRIP;
    memcpy(m.indices, past, sizeof past);
    cr_assert_not(sr_draw(&fb, &(sr_draw_desc){ .mesh = &m, .shade = SR_SHADE_ID, .clear = true }, NULL, &err));
    cr_assert_str_eq(err.message, "mesh has an index past its 2 vertices");
    cr_assert_eq(scene_count_color(&fb, 0x123456), (size_t)W * H, "nothing drawn or cleared");
    sr_mesh_free(&m);
    sr_framebuffer_destroy(&fb);
}

/* ---- dEQP-GLES3.functional.clipping.line.*, under Direct3D's rules ---- */

enum { REF_NO, REF_YES, REF_EITHER }; /* a reference pixel; either: its centre on a diamond's side */

/* The part of the clip-space segment a -> b inside −w <= x, y <= w and
 * Direct3D's 0 <= z <= w, in double (Liang–Barsky); false if none. */
static bool ref_visible(const float a[4], const float b[4], double out[2][4])
{
    double t0 = 0.0, t1 = 1.0;
    for (int plane = 0; plane < 6; plane++) {
        int axis = plane / 2;
        double sign = plane % 2 ? -1.0 : 1.0, w_weight = axis == 2 && plane == 4 ? 0.0 : 1.0;
        double da = w_weight * a[3] + sign * a[axis], db = w_weight * b[3] + sign * b[axis];
        if (da < 0 && db < 0)
            return false;
        if (da < 0)
            t0 = fmax(t0, da / (da - db));
        else if (db < 0)
            t1 = fmin(t1, da / (da - db));
    }
    if (t0 > t1)
        return false;
    for (int c = 0; c < 4; c++) {
        out[0][c] = a[c] + t0 * ((double)b[c] - a[c]);
        out[1][c] = a[c] + t1 * ((double)b[c] - a[c]);
    }
    return true;
}

/* The reference picture of one line `width` pixels wide on a w × h canvas:
 * its visible part snapped to 1/256 pixel, then the diamond-exit oracle,
 * each pixel repeated across the minor axis. */
static void ref_line(const float a[4], const float b[4], int width, int w, int h, unsigned char *ref)
{
    double vis[2][4];
    if (!ref_visible(a, b, vis) || !(vis[0][3] > 0.0 && vis[1][3] > 0.0))
        return;
    int64_t e[2][2];
    for (int k = 0; k < 2; k++) {
        e[k][0] = llround((vis[k][0] / vis[k][3] + 1.0) * w / 2.0 * ONE);
        e[k][1] = llround((1.0 - vis[k][1] / vis[k][3]) * h / 2.0 * ONE);
    }
    bool y_major = llabs(e[1][1] - e[0][1]) > llabs(e[1][0] - e[0][0]);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int64_t c[2] = { x * ONE + ONE / 2, y * ONE + ONE / 2 };
            bool open = segment_meets_diamond(e[0], e[1], c, ONE / 2, true);
            bool closed = segment_meets_diamond(e[0], e[1], c, ONE / 2, false);
            int state = open != closed || point_on_diamond(e[1], c, ONE / 2)
                            ? REF_EITHER
                            : open && !point_in_open_diamond(e[1], c, ONE / 2);
            if (state == REF_NO)
                continue;
            for (int k = -(width - 1) / 2; k <= width / 2; k++) {
                int px = y_major ? x + k : x, py = y_major ? y : y + k;
                if (px >= 0 && py >= 0 && px < w && py < h && ref[py * w + px] != REF_YES)
                    ref[py * w + px] = (unsigned char)state;
            }
        }
}

/* dEQP's compareBlackNonBlackImages: a pixel drawn in one picture and not
 * the other is a deviation when, within `radius`, each picture has a
 * pixel in the other's state (or it lies within radius of the border),
 * else faulty. Returns the faulty pixels; *deviating gets the others. */
static int deqp_compare(const sr_framebuffer *fb, const unsigned char *ref, int radius, int *deviating)
{
    int w = fb->width, h = fb->height, faulty = 0;
    *deviating = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int want = ref[y * w + x];
            bool drawn = fb->color[y * w + x] != 0;
            if (want == REF_EITHER || drawn == (want == REF_YES))
                continue;
            bool found_ref = false, found_test = false;
            if (x < radius || y < radius || x + radius >= w || y + radius >= h)
                found_ref = found_test = true;
            for (int ky = y - radius; ky <= y + radius && !(found_ref && found_test); ky++)
                for (int kx = x - radius; kx <= x + radius; kx++) {
                    if (kx < 0 || ky < 0 || kx >= w || ky >= h)
                        continue;
                    found_ref = found_ref || (fb->color[ky * w + kx] != 0) == (want == REF_YES);
                    found_test = found_test || ref[ky * w + kx] == (drawn ? REF_YES : REF_NO) ||
                                 ref[ky * w + kx] == REF_EITHER;
                }
            if (found_ref && found_test)
                (*deviating)++;
            else
                faulty++;
        }
    return faulty;
}

/* The reference picture of one point `size` pixels wide on a w × h canvas:
 * kept inside 0 <= z <= w (Direct3D; GL keeps −w <= z), its square's
 * pixel centres, those within a subpixel of its sides either way (the
 * snap may move them). */
static void ref_point(const float c[4], int size, int w, int h, unsigned char *ref)
{
    if (!(c[3] > 0.0f) || c[2] < 0.0f || c[2] > c[3])
        return;
    double px = ((double)c[0] / c[3] + 1.0) * w / 2.0, py = (1.0 - (double)c[1] / c[3]) * h / 2.0, half = size / 2.0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double dx = x + 0.5 - px, dy = y + 0.5 - py, slack = 1.0 / ONE;
            bool in = dx >= -half && dx < half && dy >= -half && dy < half;
            bool near_side = fabs(fabs(dx) - half) <= slack || fabs(fabs(dy) - half) <= slack;
            if (near_side && ref[y * w + x] != REF_YES)
                ref[y * w + x] = REF_EITHER;
            else if (in)
                ref[y * w + x] = REF_YES;
        }
}

/* Draws dEQP's clip-space points, or lines (pairs), `width` wide on a
 * size × size canvas (200: VIEWPORT_WHOLE; 100: the centre and corner
 * viewports, which are a 100 × 100 viewport) and holds the picture to the
 * reference by dEQP's comparison; returns the pixels drawn. */
static size_t deqp_case(const float (*c)[4], uint32_t n, sr_topology topology, int width, int size, int radius,
                        const char *name)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, size, size);
    sr_mesh m;
    clip_lines(&m, c, n, topology);
    draw_clip_space(&fb, &m, (float)width);
    unsigned char *ref = calloc((size_t)size * size, 1);
    cr_assert_not_null(ref);
    for (uint32_t k = 0; k < n; k++)
        if (topology == SR_POINT_LIST)
            ref_point(c[k], width, size, size, ref);
        else if (k % 2 == 0 && k + 1 < n)
            ref_line(c[k], c[k + 1], width, size, size, ref);
    int deviating, faulty = deqp_compare(&fb, ref, radius, &deviating);
    cr_assert_eq(faulty, 0, "%s at %d px: %d faulty pixels, %d deviating", name, size, faulty, deviating);
    cr_assert_leq(deviating, (int)n * width, "%s at %d px: %d deviating pixels", name, size, deviating);
    size_t drawn = (size_t)size * size - scene_count_color(&fb, 0);
    free(ref);
    sr_mesh_free(&m);
    sr_framebuffer_destroy(&fb);
    return drawn;
}

static size_t deqp_lines(const float (*c)[4], uint32_t n, int width, int size, int radius, const char *name)
{
    return deqp_case(c, n, SR_LINE_LIST, width, size, radius, name);
}

/* line_clip, wide_line_clip and their viewport variants: lines from the
 * centre out, from outside in, and outside to outside. The last two lie a
 * pixel outside the view, where GL's wide lines leave fragments; Direct3D
 * cuts a line at the view's sides whatever its width, so softrast draws
 * none of them (docs/conventions.md, "Points and lines"). */
Test(lines, deqp_line_clip_cases_match_the_reference_but_for_wide_lines_outside_the_view)
{
    const float over = 1.0f + 2.0f / 200.0f;
    const float c[][4] = {
        { 0, 0, 0, 1 }, { 0, 1.5f, 0, 1 },      { 0, 0, 0, 1 }, { -1.5f, 1, 0, 1 },   { 0, 0, 0, 1 }, { -1.5f, 0, 0, 1 },
        { 0, 0, 0, 1 }, { 0.2f, 0.4f, 1.5f, 1 }, { 0, 0, 0, 1 }, { -2, -1, 0, 1 },   { 0, 0, 0, 1 }, { 1, 0.1f, 0, 0.6f },
        { 1.5f, 0, 0, 1 }, { 0.8f, -0.2f, 0, 1 }, { 0, -1.5f, 0, 1 }, { 0.9f, -0.7f, 0, 1 },
        { 0, -1.3f, 0, 1 }, { 1.3f, 0, 0, 1 },
        { -0.8f, -over, 0, 1 }, { 0, -over, 0, 1 }, { -over - 1, 0, 0, 1 }, { 0, -over - 1, 0, 1 },
    };
    for (int size = 200; size >= 100; size -= 100)
        for (int width = 1; width <= 5; width += 4) {
            size_t all = deqp_lines(c, 22, width, size, 1, width == 1 ? "line_clip" : "wide_line_clip");
            size_t inside = deqp_lines(c, 18, width, size, 1, "line_clip without the lines outside");
            cr_assert_gt(all, (size_t)size, "the lines are drawn");
            cr_assert_eq(all, inside, "the lines outside the view leave no fragment, whatever their width");
        }
}

/* line_z_clip and wide_line_z_clip and their viewport variants: past far
 * as in GL; past near cut at z = 0 instead of GL's z = −w (the test above
 * of the same lines counts that). long_line_clip and long_wide_line_clip
 * (kernel radius 2 in dEQP): lines across a million units of z, of which
 * Direct3D's depth range keeps the half from z = 0. */
Test(lines, deqp_line_z_and_long_line_cases_match_the_reference_in_direct3d_depth)
{
    const float depth[][4] = {
        { 0, 0, 0, 1 }, { 1.3f, 1, 2, 1 },     { 0, 0, 0, 1 }, { 1.3f, -1, 2, 1 }, { 0, 0, 0, 1 }, { -1, -1.1f, -2, 1 },
        { 0, 0, 0, 1 }, { -1, 1.1f, -2, 1 },   { 0, 0, 0, 1 }, { 1, 0.1f, 2, 0.6f },
    };
    const float longs[][4] = {
        { -41000, -40000, -1000000, 1 }, { 41000, 40000, 1000000, 1 },
        { 41000, -40000, 1000000, 1 },   { -41000, 40000, -1000000, 1 },
        { 0.5f, -40000, 100000, 1 },     { 0.5f, 40000, -100000, 1 },
        { -0.5f, 40000, 100000, 1 },     { -0.5f, -40000, -100000, 1 },
    };
    for (int size = 200; size >= 100; size -= 100)
        for (int width = 1; width <= 5; width += 4)
            cr_assert_gt(deqp_lines(depth, 10, width, size, 1, "line_z_clip"), (size_t)size / 2);
    for (int width = 1; width <= 5; width += 4)
        cr_assert_gt(deqp_lines(longs, 8, width, 200, 2, "long_line_clip"), 80u * (size_t)width, "40 px on each of x = ±0.5");
}

/* line_attrib_clip: red at the centre to yellow or light blue past far
 * (z = 2w) or near (z = −2w); dEQP wants each drawn pixel within 20/255
 * of the reference's colour. Past far, the colour at a pixel is the
 * original segment's at the pixel centre's projection; past near,
 * Direct3D keeps only the centre point, no pixel. */
Test(lines, deqp_line_attrib_clip_colours_match_the_unclipped_segment)
{
    const float c[][4] = { { 0, 0, 0, 1 }, { 1.3f, 1, 2, 1 }, { 0, 0, 0, 1 }, { 1.3f, -1, 2, 1 },
                           { 0, 0, 0, 1 }, { -1, -1, -2, 1 }, { 0, 0, 0, 1 }, { -1, 1, -2, 1 } };
    const float colors[][3] = { { 1, 0, 0 }, { 1, 1, 0 }, { 1, 0, 0 }, { 0.3f, 0.3f, 1 },
                                { 1, 0, 0 }, { 1, 1, 0 }, { 1, 0, 0 }, { 0.3f, 0.3f, 1 } };
    sr_framebuffer fb;
    scene_fb_make(&fb, 200, 200);
    sr_mesh m;
    clip_lines(&m, c, 8, SR_LINE_LIST);
    m.colors = malloc(8 * sizeof *m.colors);
    cr_assert_not_null(m.colors);
    memcpy(m.colors, colors, sizeof colors);
    sr_framebuffer_clear(&fb, 0);
    draw_desc(&fb, &(sr_draw_desc){ .mesh = &m, .shade = SR_SHADE_COLOR });
    int checked = 0;
    for (int y = 0; y < 200; y++)
        for (int x = 0; x < 200; x++) {
            uint32_t got = at(&fb, x, y);
            if (!got)
                continue;
            /* Which line: the upper one (y < 100) is line 0, the lower line 1. */
            int line = y < 100 ? 0 : 1;
            double ax = 100.0, ay = 100.0, bx = (1.3 + 1.0) * 100.0, by = (1.0 - (line ? -1.0 : 1.0)) * 100.0;
            double t = ((x + 0.5 - ax) * (bx - ax) + (y + 0.5 - ay) * (by - ay)) /
                       ((bx - ax) * (bx - ax) + (by - ay) * (by - ay));
            t = t < 0 ? 0 : t;
            for (int ch = 0; ch < 3; ch++) {
                double want = colors[2 * line][ch] + t * (colors[2 * line + 1][ch] - colors[2 * line][ch]);
                int got_ch = (int)((got >> (16 - 8 * ch)) & 0xFF);
                cr_assert_leq(abs(got_ch - (int)lround(want * 255.0)), 20, "pixel (%d, %d) channel %d: %d, want %.1f",
                              x, y, ch, got_ch, want * 255.0);
            }
            checked++;
        }
    cr_assert_eq(checked, 130, "65 pixels on each line past far, none past near");
    sr_mesh_free(&m);
    sr_framebuffer_destroy(&fb);
}

/* point_z_clip, point_clip, wide_point_z_clip, wide_point_clip and their
 * viewport variants (a 100 × 100 canvas), every point of dEQP's lists:
 * dEQP's verdicts but for the points at −w <= z < 0, which Direct3D's
 * depth range drops. */
Test(points, deqp_point_clip_cases_match_the_reference_in_direct3d_depth)
{
    const float over = 1.0f + 2.0f / 200.0f;
    const float viewport[][4] = {
        { 0, 0, 0, 1 },        { 0.1f, 0.1f, 0.1f, 1 },   { -0.1f, 0.1f, -0.1f, 1 },  { -0.1f, -0.1f, 0.1f, 1 },
        { 0.1f, -0.1f, -0.1f, 1 }, { 2, 2, 2, 3 },         { -2, -2, 2, 3 },           { 0.5f, -0.5f, 0.5f, 0.7f },
        { -0.5f, 0.5f, -0.5f, 0.7f }, { -2, -2, 0, 2.2f }, { 1, -1, 0, 1.1f },         { -1, 1, 0, 1.1f },
        { 1.3f, 0, 0, 1 },     { -1.3f, 0, 0, 1 },        { 0, 1.3f, 0, 1 },          { 0, -1.3f, 0, 1 },
        { -1.3f, -1.3f, 0, 1 }, { -1.3f, 1.3f, 0, 1 },    { 1.3f, 1.3f, 0, 1 },       { 1.3f, -1.3f, 0, 1 },
        { over, over, 0, 1 },  { 0, over, 0, 1 },         { over, 0, 0, 1 },
    };
    const float depth[][4] = {
        { 0, 0, 0, 1 },           { 0.1f, 0.1f, 0.1f, 1 },  { -0.1f, 0.1f, -0.1f, 1 }, { -0.1f, -0.1f, 0.1f, 1 },
        { 0.1f, -0.1f, -0.1f, 1 }, { 0.1f, 0, 1.1f, 1 },    { -0.1f, 0, -1.1f, 1 },    { -0.0f, -0.1f, 1.1f, 1 },
        { 0, 0.1f, -1.1f, 1 },
    };
    for (int size = 200; size >= 100; size -= 100)
        for (int width = 1; width <= 5; width += 4) {
            size_t in_view = deqp_case(viewport, 23, SR_POINT_LIST, width, size, 1,
                                       width == 1 ? "point_clip" : "wide_point_clip");
            size_t in_depth = deqp_case(depth, 9, SR_POINT_LIST, width, size, 1,
                                        width == 1 ? "point_z_clip" : "wide_point_z_clip");
            cr_assert_geq(in_view, (size_t)(9 * width * width) - 2 * (size_t)width, "%d px, %d wide", size, width);
            cr_assert_geq(in_depth, (size_t)(3 * width * width) - 2 * (size_t)width, "%d px, %d wide", size, width);
        }
}
