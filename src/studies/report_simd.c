#include <stdlib.h>
#include <string.h>

#include "bench_time.h"
#include "report_simd.h"

#define FILL_MAX_FRAMES 2

static uint64_t pixels_differing(const sr_framebuffer *a, const sr_framebuffer *b)
{
    size_t n = (size_t)a->width * (size_t)a->height;
    uint64_t differ = 0;
    for (size_t i = 0; i < n; i++)
        differ += a->color[i] != b->color[i] || memcmp(&a->depth[i], &b->depth[i], sizeof *a->depth) != 0;
    return differ;
}

/* Each loop the CPU runs, from the scalar one up; the scalar frame is kept
 * in `scalar` as the image the others must equal. */
static bool measure_loops(const sr_bench_scene *s, int frames, sr_framebuffer fb[2], sr_report_simd_scene *out,
                          sr_error *err)
{
    *out = (sr_report_simd_scene){ .name = s->name, .what = s->what, .frames = frames };
    for (int simd = SR_SIMD_SCALAR; simd < SR_SIMD_COUNT; simd++) {
        if (sr_raster_simd_resolve((sr_simd)simd) != (sr_simd)simd)
            continue; /* not on this CPU */
        sr_bench_run run = { .frames = frames, .threads = 1, .simd = (sr_simd)simd };
        sr_bench_result r;
        sr_framebuffer *into = &fb[simd != SR_SIMD_SCALAR];
        if (!sr_bench_time(s, &run, into, &r, err))
            return false;
        out->rows[out->loops++] = (sr_report_simd_row){ .simd = (sr_simd)simd, .ms = r.median,
                                                        .pixels_differ = pixels_differing(&fb[0], into) };
        fprintf(stderr, "report: %s, %s loop: %.2f ms\n", s->name, sr_simd_name((sr_simd)simd), r.median);
    }
    return true;
}

static bool measure_scene(bool (*make)(sr_bench_scene *, sr_error *), int frames, sr_report_simd_scene *out,
                          sr_error *err)
{
    sr_bench_scene s;
    sr_framebuffer fb[2] = { 0 };
    bool ok = make(&s, err) && sr_framebuffer_create(&fb[0], s.width, s.height, err) &&
              sr_framebuffer_create(&fb[1], s.width, s.height, err) && measure_loops(&s, frames, fb, out, err);
    for (int i = 0; i < 2; i++)
        if (fb[i].color)
            sr_framebuffer_destroy(&fb[i]);
    sr_bench_scene_free(&s);
    return ok;
}

bool sr_report_simd_measure(int frames, sr_report_simd_scene out[SR_REPORT_SIMD_SCENES], sr_error *err)
{
    int fill_frames = frames < FILL_MAX_FRAMES ? frames : FILL_MAX_FRAMES;
    return measure_scene(sr_bench_fly, frames, &out[0], err) &&
           measure_scene(sr_bench_fill, fill_frames, &out[1], err);
}

void sr_report_simd_write(FILE *f, const sr_report_simd_scene scenes[SR_REPORT_SIMD_SCENES])
{
    fprintf(f, "\n## Per-pixel loops\n\n"
               "The same scenes with their own shading (not ids), 1 thread, timed with the scalar loop\n"
               "and each SIMD kernel this CPU runs (`--simd`). *pixels differing*: color or depth of\n"
               "the last frame that differ from the scalar loop's, bit for bit; the kernels compute\n"
               "exactly the scalar loop's operations, so this is 0 (tests/test_simd.c checks it too).\n");
    for (int i = 0; i < SR_REPORT_SIMD_SCENES; i++) {
        const sr_report_simd_scene *s = &scenes[i];
        fprintf(f, "\n### %s — %s (%d frames)\n\n", s->name, s->what, s->frames);
        fprintf(f, "| loop | ms median | time / scalar | pixels differing |\n| --- | ---: | ---: | ---: |\n");
        for (int k = 0; k < s->loops; k++)
            fprintf(f, "| %s | %.2f | %.3f | %llu |\n", sr_simd_name(s->rows[k].simd), s->rows[k].ms,
                    s->rows[k].ms / s->rows[0].ms, (unsigned long long)s->rows[k].pixels_differ);
    }
}
