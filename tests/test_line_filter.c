/* A line draw's own fragment test (sr_line_filter, draw/draw.h): it drops
 * fragments and moves their depth before the depth test, on every thread
 * count and path alike. */
#include <criterion/criterion.h>
#include <string.h>

#include "draw/draw.h"
#include "scene_helpers.h"

#define W 32
#define H 8

/* Line 1 (slot 1) lies over line 0, nearer; the filter drops line 1 in
 * odd columns and moves line 0 nearest of all left of column 6. */
static bool keep(const void *user, uint32_t line, int x, int y, float *z)
{
    (void)y;
    int *calls = (int *)user;
    __atomic_add_fetch(calls, 1, __ATOMIC_RELAXED);
    if (line == 0 && x < 6)
        *z = 0.1f;
    return line == 0 || x % 2 == 0;
}

static void draw_filtered(sr_framebuffer *fb, int threads, int *calls)
{
    const float pos[][3] = { { 1.0f, 4.5f, 0.8f }, { 23.0f, 4.5f, 0.8f }, { 1.0f, 4.5f, 0.3f }, { 23.0f, 4.5f, 0.3f } };
    const uint32_t idx[] = { 0, 1, 2, 3 };
    sr_mesh mesh;
    scene_mesh_make(&mesh, &(scene_mesh_arrays){ .vertex_count = 4, .positions = pos, .index_count = 4,
                                                 .indices = idx, .topology = SR_LINE_LIST });
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_ID, .threads = threads, .clear = true };
    scene_pixel_ortho(&desc, W, H);
    sr_line_filter filter = { keep, calls };
    sr_error err = { "" };
    sr_stats stats = { 0 };
    cr_assert(sr_draw_lines_filtered(fb, &desc, &filter, &stats, &err), "%s", err.message);
    cr_assert_eq(stats.lines, 2);
    sr_mesh_free(&mesh);
}

Test(line_filter, drops_and_moves_fragments_before_the_depth_test_on_every_thread_count)
{
    sr_framebuffer fb;
    scene_fb_make(&fb, W, H);
    for (int threads = 1; threads <= 16; threads++) {
        int calls = 0;
        draw_filtered(&fb, threads, &calls);
        cr_assert_eq(calls, 2 * 22, "%d threads: each line's 22 fragments, once", threads);
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                uint32_t id = fb.color[y * W + x];
                float z = fb.depth[y * W + x];
                if (y != 4 || x < 1 || x > 22) {
                    cr_assert_eq(id, 0, "(%d, %d): %u", x, y, id);
                    continue;
                }
                /* Line 0 at 0.1 left of column 6; line 1 at 0.3 in even
                 * columns; line 0 at 0.8 in the odd ones. */
                uint32_t want = x < 6 ? 1 : x % 2 == 0 ? 2 : 1;
                float want_z = x < 6 ? 0.1f : x % 2 == 0 ? 0.3f : 0.8f;
                cr_assert(id == want && z == want_z, "%d threads, (%d, %d): line %u at %g, not %u at %g", threads, x,
                          y, id, z, want, want_z);
            }
    }
    sr_framebuffer_destroy(&fb);
}
