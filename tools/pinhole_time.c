/* pinhole_time.c — the time of one pinhole view as a library user makes it,
 * for tools/compare_open3d.py and docs/cli.md's one-draw table, each the
 * median of FRAMES after one warm-up, on THREADS. Public API only.
 *
 *   draw_ms     the id draw (what `softrast render --shade id --stats`
 *               times as ms_median): depth and ids, no color
 *   resolve_ms  sr_pinhole_resolve of view depth and face ids from it
 *   one_ms      what `render --out --view-depth --range --face-ids
 *               --part-ids --normals` does, files aside: one lambert draw
 *               writing the ids plane, and the resolve of all five outputs
 *
 *   pinhole_time MESH WIDTH HEIGHT FX,FY,CX,CY W2C(16, commas) THREADS FRAMES
 *
 * prints {"draw_ms": D, "resolve_ms": R, "one_ms": O}. */
#include <stdbool.h>
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

/* The three things timed, each a function of its own so that callgrind
 * can count each one's instructions (--toggle-collect=one_view), which
 * other processes' load does not move as it moves times. */
static __attribute__((noinline)) bool id_draw(sr_framebuffer *fb, const sr_draw_desc *desc, sr_error *err)
{
    return sr_draw(fb, desc, NULL, err);
}

static __attribute__((noinline)) bool id_resolve(const sr_pinhole *cam, const sr_mesh *mesh,
                                                 const sr_framebuffer *fb, const sr_pinhole_outputs *out,
                                                 sr_error *err)
{
    return sr_pinhole_resolve(cam, mesh, fb, out, err);
}

static __attribute__((noinline)) bool one_view(const sr_pinhole *cam, const sr_mesh *mesh, sr_framebuffer *fb,
                                               const sr_draw_desc *desc, const sr_pinhole_outputs *out,
                                               sr_error *err)
{
    return sr_draw(fb, desc, NULL, err) && sr_pinhole_resolve(cam, mesh, fb, out, err);
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
    sr_framebuffer fb = { 0 }, one_fb = { 0 }; /* without an ids plane, and with one */
    sr_error err;
    sr_pinhole cam = { .fx = k[0], .fy = k[1], .cx = k[2], .cy = k[3] };
    memcpy(cam.w2c, pose, sizeof pose);
    if (frames < 1 || !sr_mesh_load(&mesh, &texture, argv[1], &err) || !sr_pinhole_check(&cam, &err) ||
        !sr_framebuffer_create(&fb, width, height, &err) || !sr_framebuffer_create(&one_fb, width, height, &err) ||
        !sr_framebuffer_create_ids(&one_fb, &err)) {
        fprintf(stderr, "pinhole_time: %s\n", frames < 1 ? "FRAMES must be at least 1" : err.message);
        return 1;
    }
    sr_pinhole_fit_clip(&cam, &mesh);
    if (!sr_mesh_compute_normals(&mesh, &err)) { /* lambert's, for a scan without them */
        fprintf(stderr, "pinhole_time: %s\n", err.message);
        return 1;
    }
    sr_workspace *ws = sr_workspace_create();
    sr_draw_desc id_desc = { .mesh = &mesh, .shade = SR_SHADE_ID, .cull = SR_CULL_NONE, .threads = threads,
                             .workspace = ws, .clear = true };
    sr_pinhole_matrices(&cam, &mesh, &fb, &id_desc);
    sr_draw_desc one_desc = id_desc;
    one_desc.shade = SR_SHADE_LAMBERT;
    one_fb.reversed_z = fb.reversed_z;
    size_t n = (size_t)width * (size_t)height;
    sr_pinhole_outputs out = { .depth = malloc(n * sizeof(float)), .face_ids = malloc(n * sizeof(uint32_t)),
                               .threads = threads };
    sr_pinhole_outputs all = { .depth = malloc(n * sizeof(float)), .range = malloc(n * sizeof(float)),
                               .face_ids = malloc(n * sizeof(uint32_t)), .part_ids = malloc(n * sizeof(uint32_t)),
                               .normals = malloc(3 * n * sizeof(float)), .threads = threads };
    double *draw = malloc(3 * (size_t)frames * sizeof *draw), *resolve = draw + frames, *one = resolve + frames;
    if (!ws || !out.depth || !out.face_ids || !all.depth || !all.range || !all.face_ids || !all.part_ids ||
        !all.normals || !draw) {
        fprintf(stderr, "pinhole_time: out of memory\n");
        return 1;
    }
    for (int f = -1; f < frames; f++) {
        double t0 = now_ms();
        if (!id_draw(&fb, &id_desc, &err))
            break;
        double t1 = now_ms();
        if (!id_resolve(&cam, &mesh, &fb, &out, &err))
            break;
        double t2 = now_ms();
        if (!one_view(&cam, &mesh, &one_fb, &one_desc, &all, &err))
            break;
        if (f >= 0) {
            draw[f] = t1 - t0;
            resolve[f] = t2 - t1;
            one[f] = now_ms() - t2;
        }
        if (f == frames - 1) {
            printf("{\"draw_ms\": %.4f, \"resolve_ms\": %.4f, \"one_ms\": %.4f}\n", median(draw, frames),
                   median(resolve, frames), median(one, frames));
            return 0;
        }
    }
    fprintf(stderr, "pinhole_time: %s\n", err.message);
    return 1;
}
