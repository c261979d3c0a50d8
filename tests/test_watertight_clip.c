/* Watertightness across clip planes: meshes seen by perspective cameras
 * that cut them with the near, far and side planes, so the clipped edges are
 * shared too. Each scene is one sr_draw counted per pixel (hit_counter.h);
 * the expected region comes from intersecting each pixel-centre ray with the
 * ground plane, independently of the pipeline's matrices.
 */
#include <math.h>
#include <string.h>

#include <criterion/criterion.h>

#include "hit_counter.h"

#define SEED 0xC0FFEEull

/* ---- a ground grid under perspective cameras ---- */

#define GROUND_HALF 24.0f /* the grid spans [-24, 24]^2 in x and z, at y = 0 */
#define GROUND_CELLS 48
#define GROUND_JITTER 0.3
#define GROUND_YAW 0.37f  /* world rotation about +y, radians */
#define VIEW_W 160
#define VIEW_H 120
#define OUTLINE_PIXELS 0.02 /* region samples this far around each pixel centre */

static void ground_mesh(sr_mesh *mesh, test_rng *rng)
{
    uint32_t side = GROUND_CELLS + 1;
    scene_mesh_alloc(mesh, side * side, 2u * GROUND_CELLS * GROUND_CELLS, false);
    float step = 2.0f * GROUND_HALF / GROUND_CELLS;
    for (uint32_t r = 0; r < side; r++) {
        for (uint32_t q = 0; q < side; q++) {
            float *p = mesh->positions[r * side + q];
            p[0] = -GROUND_HALF + step * (float)q;
            p[1] = 0.0f;
            p[2] = -GROUND_HALF + step * (float)r;
            if (r > 0 && q > 0 && r < side - 1 && q < side - 1) {
                p[0] += (float)(GROUND_JITTER * (2.0 * rng_unit(rng) - 1.0));
                p[2] += (float)(GROUND_JITTER * (2.0 * rng_unit(rng) - 1.0));
            }
        }
    }
    uint32_t *ix = mesh->indices;
    for (uint32_t r = 0; r < GROUND_CELLS; r++) {
        for (uint32_t q = 0; q < GROUND_CELLS; q++) {
            /* a = (x0, z0), b = (x1, z0), d = (x0, z1), e = (x1, z1); seen from
             * above with +z up the screen, (a, d, e) and (a, d, b) are clockwise. */
            uint32_t a = r * side + q, b = a + 1, d = a + side, e = d + 1;
            uint32_t v[2][6] = { { a, d, e, a, e, b }, { a, d, b, d, e, b } };
            memcpy(ix, v[rng_next(rng) & 1], sizeof v[0]);
            ix += 6;
        }
    }
}

/* Whether the ray through image point (px, py) meets the drawn part of the
 * ground: below the horizon, within [near, far] in view depth and inside the
 * grid's square (undoing the yaw). */
static bool ground_visible_at(const sr_camera *cam, double px, double py)
{
    double dir[3];
    scene_pixel_ray(cam, VIEW_W, VIEW_H, px, py, dir);
    if (!(dir[1] < 0.0))
        return false;
    double t = -(double)cam->eye[1] / dir[1]; /* view depth: dir's forward component is 1 */
    if (t < cam->near || t > cam->far)
        return false;
    double x = cam->eye[0] + t * dir[0], z = cam->eye[2] + t * dir[2];
    /* World = R_y(yaw) * local; local = R_y(-yaw) * world. glm_rotate_make
     * about +y: x' = c x + s z, z' = -s x + c z. */
    double c = cos(GROUND_YAW), s = sin(GROUND_YAW);
    double lx = c * x - s * z, lz = s * x + c * z;
    return fabs(lx) < GROUND_HALF && fabs(lz) < GROUND_HALF;
}

/* A pixel is inside (outside) when its centre and four points around it
 * are all inside (outside); otherwise it is on the outline. */
static void ground_regions(const sr_camera *cam, unsigned char *regions)
{
    static const double offsets[5][2] = { { 0, 0 }, { -OUTLINE_PIXELS, 0 }, { OUTLINE_PIXELS, 0 },
                                          { 0, -OUTLINE_PIXELS }, { 0, OUTLINE_PIXELS } };
    for (int j = 0; j < VIEW_H; j++) {
        for (int i = 0; i < VIEW_W; i++) {
            int in = 0;
            for (int k = 0; k < 5; k++)
                in += ground_visible_at(cam, i + 0.5 + offsets[k][0], j + 0.5 + offsets[k][1]);
            regions[j * VIEW_W + i] = in == 5 ? SCENE_REGION_IN : in == 0 ? SCENE_REGION_OUT : SCENE_REGION_EDGE;
        }
    }
}

static void check_ground(const char *name, const sr_camera *cam, scene_hit_counter *counter)
{
    sr_mesh mesh;
    test_rng rng = { SEED + 4 };
    ground_mesh(&mesh, &rng);
    sr_framebuffer fb;
    scene_fb_make(&fb, VIEW_W, VIEW_H);
    sr_draw_desc desc = { .mesh = &mesh, .cull = SR_CULL_BACK };
    scene_camera_desc(&desc, cam, VIEW_W, VIEW_H);
    glm_rotate_make(desc.world, GROUND_YAW, (vec3){ 0.0f, 1.0f, 0.0f });
    sr_stats stats = { 0 };
    scene_count_hits(&fb, &desc, counter, &stats);
    cr_expect_gt(stats.clipped, 0, "%s: nothing was clipped", name);
    static unsigned char regions[VIEW_W * VIEW_H];
    ground_regions(cam, regions);
    scene_expect_each_pixel_once(name, counter, regions);
    sr_framebuffer_destroy(&fb);
    sr_mesh_free(&mesh);
}

/* The eye 0.05 over the ground with near = 0.1: the near plane cuts the
 * ground inside the picture, the side and far planes cut it too. */
Test(watertight, ground_grid_cut_by_near_side_and_far_planes_covers_each_pixel_once)
{
    sr_camera cam = scene_camera(0.37f, 0.05f, -0.21f, 3.1f, -0.25f, 9.0f, 75.0f, 0.1f, 14.0f);
    scene_hit_counter counter;
    check_ground("watertight_ground_grid_cut_by_near_side_and_far_planes", &cam, &counter);
    cr_expect_gt(counter.near_cut_vertices, 0, "the near plane cut nothing on screen");
    cr_expect_gt(counter.side_cut_vertices, 0, "the side planes cut nothing");
}

/* From above and outside, toward a corner of the grid: its outline is in the
 * picture and the side and far planes cut it. */
Test(watertight, ground_grid_seen_from_above_across_side_planes_covers_each_pixel_once)
{
    sr_camera cam = scene_camera(14.9f, 3.0f, -33.8f, 8.9f, 0.0f, -27.6f, 60.0f, 0.5f, 12.0f);
    scene_hit_counter counter;
    check_ground("watertight_ground_grid_seen_from_above_across_side_planes", &cam, &counter);
    cr_expect_gt(counter.side_cut_vertices, 0, "the side planes cut nothing");
}

Test(watertight, ground_grid_at_grazing_angle_with_wide_fov_covers_each_pixel_once)
{
    sr_camera cam = scene_camera(0.5f, 0.02f, 0.5f, 10.0f, -0.5f, 3.0f, 100.0f, 0.05f, 30.0f);
    scene_hit_counter counter;
    check_ground("watertight_ground_grid_at_grazing_angle_with_wide_fov", &cam, &counter);
    cr_expect_gt(counter.near_cut_vertices, 0, "the near plane cut nothing on screen");
}

/* ---- long triangles through the near plane ---- */

/* A strip of long, thin ground triangles from z = -3000 (behind the eye) to
 * z = +3000, its edges passing a few centimetres beside the eye: each cut
 * vertex on the near plane is a small difference of huge end points, so
 * its rounding is large, and the two triangles of a seam must still make
 * their shared cut vertex alike or the seam cracks or overlaps. Which end
 * a cut is interpolated from is pinned by the clipper's unit tests
 * (test_clip.c, test_clip_corners.c: cuts bit-identical both ways and to
 * the formula), not here: a clipper that cut every edge from its outside
 * end would still be watertight. */
#define LONG_REACH 3000.0f
#define LONG_COLUMNS 24
#define LONG_SPACING 0.02f
#define LONG_SHEAR 0.37f  /* the front row is shifted this far in x */
#define LONG_X0 (-0.3f)   /* x of the first behind vertex */
/* The float vertex transform of end points 3000 away already moves the
 * strip's outline and its near-plane cut by ~0.2 px from the exact geometry
 * (the same for both sides of a seam, so no crack): sample the outline
 * wider here. Interior seams are still checked pixel by pixel. */
#define LONG_OUTLINE_PIXELS 0.5

static bool long_strip_visible_at(const sr_camera *cam, double px, double py)
{
    double dir[3];
    scene_pixel_ray(cam, VIEW_W, VIEW_H, px, py, dir);
    if (!(dir[1] < 0.0))
        return false;
    double t = -(double)cam->eye[1] / dir[1];
    if (t < cam->near || t > cam->far)
        return false;
    double x = cam->eye[0] + t * dir[0], z = cam->eye[2] + t * dir[2];
    double left = LONG_X0 + LONG_SHEAR * (z + LONG_REACH) / (2.0 * LONG_REACH);
    return fabs(z) < LONG_REACH && x > left && x < left + LONG_COLUMNS * (double)LONG_SPACING;
}

Test(watertight, long_triangles_cut_by_the_near_plane_beside_the_eye_cover_each_pixel_once)
{
    uint32_t side = LONG_COLUMNS + 1;
    sr_mesh mesh;
    scene_mesh_alloc(&mesh, 2 * side, 2 * LONG_COLUMNS, false);
    for (uint32_t i = 0; i < side; i++) {
        float x = LONG_X0 + LONG_SPACING * (float)i;
        glm_vec3_copy((vec3){ x, 0.0f, -LONG_REACH }, mesh.positions[i]);                  /* behind */
        glm_vec3_copy((vec3){ x + LONG_SHEAR, 0.0f, LONG_REACH }, mesh.positions[side + i]); /* in front */
    }
    for (uint32_t i = 0; i < LONG_COLUMNS; i++) {
        /* Seen from above, +z up the screen: both clockwise. */
        uint32_t v[6] = { i, side + i, side + i + 1, i, side + i + 1, i + 1 };
        memcpy(&mesh.indices[6 * i], v, sizeof v);
    }
    sr_camera cam = scene_camera(0.0f, 0.04f, 0.0f, 0.15f, -0.6f, 1.0f, 90.0f, 0.1f, 10000.0f);
    sr_framebuffer fb;
    scene_fb_make(&fb, VIEW_W, VIEW_H);
    sr_draw_desc desc = { .mesh = &mesh, .cull = SR_CULL_BACK };
    scene_camera_desc(&desc, &cam, VIEW_W, VIEW_H);
    scene_hit_counter counter;
    sr_stats stats = { 0 };
    scene_count_hits(&fb, &desc, &counter, &stats);
    cr_expect_gt(counter.near_cut_vertices, LONG_COLUMNS, "the near plane cut too little on screen");
    static const double offsets[5][2] = { { 0, 0 }, { -LONG_OUTLINE_PIXELS, 0 }, { LONG_OUTLINE_PIXELS, 0 },
                                          { 0, -LONG_OUTLINE_PIXELS }, { 0, LONG_OUTLINE_PIXELS } };
    static unsigned char regions[VIEW_W * VIEW_H];
    for (int j = 0; j < VIEW_H; j++) {
        for (int i = 0; i < VIEW_W; i++) {
            int in = 0;
            for (int k = 0; k < 5; k++)
                in += long_strip_visible_at(&cam, i + 0.5 + offsets[k][0], j + 0.5 + offsets[k][1]);
            regions[j * VIEW_W + i] = in == 5 ? SCENE_REGION_IN : in == 0 ? SCENE_REGION_OUT : SCENE_REGION_EDGE;
        }
    }
    scene_expect_each_pixel_once("watertight_long_triangles_cut_by_the_near_plane_beside_the_eye", &counter, regions);
    sr_framebuffer_destroy(&fb);
    sr_mesh_free(&mesh);
}
