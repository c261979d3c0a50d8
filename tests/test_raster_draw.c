/* Coverage through the whole pipeline: triangles in pixel space (a pixel-
 * space orthographic camera, exact in float) drawn with sr_draw must cover
 * exactly the pixels of the reference in raster_reference.h, with vertices
 * snapped to the nearest 1/256 pixel.
 */
#include <string.h>

#include <criterion/criterion.h>

#include "raster_reference.h"

/* Draws the triangle at pixel coordinates xy through the whole pipeline:
 * pixel-space orthographic camera, cull none, id shading. `mesh` is a
 * one-triangle list the caller owns. */
static sr_stats draw_at(sr_framebuffer *fb, sr_mesh *mesh, const float xy[3][2])
{
    for (int k = 0; k < 3; k++) {
        mesh->positions[k][0] = xy[k][0];
        mesh->positions[k][1] = xy[k][1];
        mesh->positions[k][2] = TRIANGLE_Z;
    }
    sr_draw_desc desc = { .mesh = mesh, .shade = SR_SHADE_ID, .cull = SR_CULL_NONE };
    scene_pixel_ortho(&desc, fb->width, fb->height);
    sr_stats stats = { 0 };
    sr_error err = { "" };
    cr_assert(sr_draw(fb, &desc, &stats, &err), "sr_draw: %s", err.message);
    return stats;
}

/* v exactly (every subpixel position is a float). */
static sr_stats raster_through_draw(sr_framebuffer *fb, sr_mesh *mesh, const ref_point v[3])
{
    float xy[3][2];
    for (int k = 0; k < 3; k++) {
        xy[k][0] = (float)v[k].x / ONE;
        xy[k][1] = (float)v[k].y / ONE;
    }
    return draw_at(fb, mesh, xy);
}

static void one_triangle_mesh(sr_mesh *mesh)
{
    scene_mesh_alloc(mesh, 3, 1, false);
    for (uint32_t k = 0; k < 3; k++)
        mesh->indices[k] = k;
}

/* The pixels the pipeline must draw for v over the whole image (none when v
 * has zero area: it is culled), into want; returns how many. */
static size_t reference_mask(const ref_point v[3], unsigned char *want)
{
    if (ref_turn(v[0], v[1], v[2]) == 0) {
        memset(want, 0, (size_t)FB_W * FB_H);
        return 0;
    }
    return ref_mask(v, FB_W, full_rect, want);
}

Test(raster, draw_covers_exactly_the_reference_pixels_of_random_triangles)
{
    sr_framebuffer fb;
    sr_mesh mesh;
    scene_fb_make(&fb, FB_W, FB_H);
    one_triangle_mesh(&mesh);
    unsigned char want[FB_W * FB_H];
    test_rng rng = { RANDOM_SEED + 1 };
    for (int t = 0; t < RANDOM_TRIANGLES; t++) {
        kind k = (kind)(t % KIND_COUNT);
        ref_point v[3];
        random_triangle(&rng, k, FB_W, FB_H, v);
        bool flat = ref_turn(v[0], v[1], v[2]) == 0;
        sr_framebuffer_clear(&fb, SCENE_BACKGROUND);
        sr_stats stats = raster_through_draw(&fb, &mesh, v);
        size_t count = reference_mask(v, want);
        expect_mask("raster_draw_covers_exactly_the_reference_pixels_of_random_triangles", t, k, v, &fb, want);
        cr_assert_eq(stats.fragments, count, "triangle %d: %llu fragments, %zu pixels", t,
                     (unsigned long long)stats.fragments, count);
        cr_assert_eq(stats.clipped, 0, "triangle %d inside the viewport was clipped", t);
        cr_assert_eq(stats.culled, flat ? 1u : 0u, "triangle %d: culled %llu (zero area: %d)", t,
                     (unsigned long long)stats.culled, flat);
    }
    sr_mesh_free(&mesh);
    sr_framebuffer_destroy(&fb);
}

/* Vertices a quarter or three quarters of a subpixel off the 1/256 grid
 * (exact in float, never a tie): the pipeline must snap each coordinate to
 * the nearest subpixel, whatever the rounding of a truncating cast. */
Test(raster, draw_snaps_vertices_to_the_nearest_subpixel)
{
    enum { QUARTERS = 4 };
    sr_framebuffer fb;
    sr_mesh mesh;
    scene_fb_make(&fb, FB_W, FB_H);
    one_triangle_mesh(&mesh);
    unsigned char want[FB_W * FB_H];
    test_rng rng = { RANDOM_SEED + 5 };
    for (int t = 0; t < RANDOM_TRIANGLES; t++) {
        kind k = (kind)(t % KIND_COUNT);
        ref_point v[3], snapped[3];
        random_triangle(&rng, k, FB_W, FB_H, v);
        float xy[3][2];
        for (int i = 0; i < 3; i++) {
            int64_t *c[2] = { &v[i].x, &v[i].y }, *s_out[2] = { &snapped[i].x, &snapped[i].y };
            int64_t limit[2] = { (int64_t)FB_W * ONE * QUARTERS, (int64_t)FB_H * ONE * QUARTERS };
            for (int a = 0; a < 2; a++) {
                int64_t off = (rng_next(&rng) & 1 ? 1 : 3) * (rng_next(&rng) & 1 ? 1 : -1);
                int64_t q = clamp64(*c[a] * QUARTERS + off, 0, limit[a]); /* in 1/1024 px */
                xy[i][a] = (float)q / (ONE * QUARTERS);
                *s_out[a] = (q + QUARTERS / 2) / QUARTERS; /* nearest: q is never 2 mod 4 */
            }
        }
        sr_framebuffer_clear(&fb, SCENE_BACKGROUND);
        sr_stats stats = draw_at(&fb, &mesh, xy);
        size_t count = reference_mask(snapped, want);
        expect_mask("raster_draw_snaps_vertices_to_the_nearest_subpixel", t, k, snapped, &fb, want);
        cr_assert_eq(stats.fragments, count);
    }
    sr_mesh_free(&mesh);
    sr_framebuffer_destroy(&fb);
}
