/* Embedding softrast: draw a mesh into buffers the caller owns.
 *
 * Build (after `make install`, or in the tree as the test suite does):
 *     cc -std=c11 draw_into_buffer.c $(pkg-config --cflags --libs softrast) -o draw
 * Run:  ./draw out.ppm
 * It draws a lambert-shaded tetrahedron into a 320×240 framebuffer whose color
 * and depth arrays are this program's own, writes them as a binary PPM with
 * stdio (the core library reads and writes no files and needs no SDL), and
 * exits non-zero if nothing was drawn.
 */
#include <stdio.h>
#include <stdlib.h>

#include "softrast/softrast.h"

enum { WIDTH = 320, HEIGHT = 240 };

static bool write_ppm(const char *path, const uint32_t *pixels)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return false;
    fprintf(f, "P6\n%d %d\n255\n", WIDTH, HEIGHT);
    for (int i = 0; i < WIDTH * HEIGHT; i++) {
        unsigned char rgb[3] = { pixels[i] >> 16 & 0xFF, pixels[i] >> 8 & 0xFF, pixels[i] & 0xFF };
        fwrite(rgb, 1, 3, f);
    }
    return fclose(f) == 0;
}

static uint32_t color[WIDTH * HEIGHT];
static float depth[WIDTH * HEIGHT];

/* A tetrahedron, front faces clockwise seen from outside (softrast's convention). */
static vec3 positions[] = { { 0, 1, 0 }, { -1, -0.6f, -0.6f }, { 1, -0.6f, -0.6f }, { 0, -0.6f, 1 } };
static uint32_t indices[] = { 0, 2, 1, 0, 3, 2, 0, 1, 3, 1, 2, 3 };

int main(int argc, char **argv)
{
    sr_mesh mesh = { .vertex_count = 4, .positions = positions, .index_count = 12, .indices = indices };
    sr_error err;
    if (!sr_mesh_compute_normals(&mesh, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    sr_framebuffer fb = { .width = WIDTH, .height = HEIGHT, .color = color, .depth = depth };
    sr_framebuffer_clear(&fb, 0x202020);

    sr_camera cam = sr_camera_default();
    glm_vec3_copy((vec3){ 1.5f, 1.2f, -3.0f }, cam.eye);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_LAMBERT };
    glm_rotate_make(desc.world, glm_rad(20.0f), (vec3){ 0, 1, 0 });
    sr_camera_view(&cam, desc.view);
    sr_camera_projection(&cam, (float)WIDTH / HEIGHT, desc.projection);

    sr_stats stats = { 0 };
    bool ok = sr_draw(&fb, &desc, &stats, &err);
    free(mesh.normals); /* the only array softrast allocated for us */
    if (!ok) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    if (argc > 1 && !write_ppm(argv[1], fb.color)) {
        perror(argv[1]);
        return 1;
    }
    printf("%llu triangles, %llu fragments\n", (unsigned long long)stats.triangles,
           (unsigned long long)stats.fragments);
    return stats.fragments > 0 ? 0 : 1;
}
