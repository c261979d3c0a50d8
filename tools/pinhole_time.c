/* pinhole_time.c — the time of one pinhole view as a library user makes it,
 * for tools/compare_open3d.py: the id draw (what `softrast render --shade id
 * --stats` times as ms_median) and sr_pinhole_resolve of view depth and face
 * ids from it (which `render` runs after the timed frames, untimed), each
 * the median of FRAMES after one warm-up. Public API only.
 *
 *   pinhole_time MESH WIDTH HEIGHT FX,FY,CX,CY W2C(16, commas) THREADS FRAMES
 *
 * prints {"draw_ms": D, "resolve_ms": R}. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "softrast/files.h"
#include "softrast/softrast.h"

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, by_value);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* n comma-separated numbers into out; false unless exactly n. */
static int numbers(const char *s, double *out, int n)
{
    for (int i = 0; i < n; i++) {
        char *end;
        out[i] = strtod(s, &end);
        if (end == s || (*end != (i + 1 < n ? ',' : '\0')))
            return 0;
        s = end + 1;
    }
    return 1;
}

int main(int argc, char **argv)
{
    double k[4], pose[16];
    if (argc != 8 || !numbers(argv[4], k, 4) || !numbers(argv[5], pose, 16)) {
        fprintf(stderr, "usage: pinhole_time MESH WIDTH HEIGHT FX,FY,CX,CY W2C(16) THREADS FRAMES\n");
        return 2;
    }
    int width = atoi(argv[2]), height = atoi(argv[3]), threads = atoi(argv[6]), frames = atoi(argv[7]);
    sr_mesh mesh = { 0 };
    sr_texture texture = { 0 };
    sr_framebuffer fb = { 0 };
    sr_error err;
    sr_pinhole cam = { .fx = k[0], .fy = k[1], .cx = k[2], .cy = k[3] };
    memcpy(cam.w2c, pose, sizeof pose);
    if (frames < 1 || !sr_mesh_load(&mesh, &texture, argv[1], &err) || !sr_pinhole_check(&cam, &err) ||
        !sr_framebuffer_create(&fb, width, height, &err)) {
        fprintf(stderr, "pinhole_time: %s\n", frames < 1 ? "FRAMES must be at least 1" : err.message);
        return 1;
    }
    sr_pinhole_fit_clip(&cam, &mesh);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_ID, .cull = SR_CULL_NONE, .threads = threads,
                          .workspace = sr_workspace_create(), .clear = true };
    sr_pinhole_matrices(&cam, &mesh, &fb, &desc);
    size_t n = (size_t)width * (size_t)height;
    sr_pinhole_outputs out = { .depth = malloc(n * sizeof(float)), .face_ids = malloc(n * sizeof(uint32_t)) };
    double *draw = malloc(2 * (size_t)frames * sizeof *draw), *resolve = draw + frames;
    if (!desc.workspace || !out.depth || !out.face_ids || !draw) {
        fprintf(stderr, "pinhole_time: out of memory\n");
        return 1;
    }
    for (int f = -1; f < frames; f++) {
        double t0 = now_ms();
        if (!sr_draw(&fb, &desc, NULL, &err))
            break;
        double t1 = now_ms();
        if (!sr_pinhole_resolve(&cam, &mesh, &fb, &out, &err))
            break;
        if (f >= 0) {
            draw[f] = t1 - t0;
            resolve[f] = now_ms() - t1;
        }
        if (f == frames - 1) {
            printf("{\"draw_ms\": %.4f, \"resolve_ms\": %.4f}\n", median(draw, frames), median(resolve, frames));
            return 0;
        }
    }
    fprintf(stderr, "pinhole_time: %s\n", err.message);
    return 1;
}
