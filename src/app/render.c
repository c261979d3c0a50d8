/* softrast render — one image without a window. */
#include <stdio.h>
#include <stdlib.h>

#include "app.h"
#include "scene_setup.h"
#include "studies/timing.h"

#define MAX_FRAMES 100000

typedef struct render_job {
    sr_scene_setup scene;
    const char *out_path, *depth_path, *depth_png_path;
    int frames;
    bool stats;
} render_job;

typedef struct frame_times {
    double median, min;
} frame_times;

static const char USAGE[] =
    "usage: softrast render MESH.obj [options]\n"
    "Draws MESH.obj into an image without a window. Without --eye/--target the camera\n"
    "looks from -z at the centre of the mesh's bounds, far enough back to see all of it.";

static void job_defaults(render_job *job)
{
    *job = (render_job){ .frames = 1 };
    sr_scene_setup_defaults(&job->scene);
}

static bool parse_job(render_job *job, int argc, char **argv, bool *help, sr_error *err)
{
    const sr_option own[] = {
        { "--out", SR_OPT_STRING, &job->out_path, "FILE.png", "write the color image (8-bit RGB)" },
        { "--depth", SR_OPT_STRING, &job->depth_path, "FILE.pfm", "write the raw float32 depth buffer (PFM)" },
        { "--depth-png", SR_OPT_STRING, &job->depth_png_path, "FILE.png", "write the depth buffer, remapped to the visible range" },
        { "--frames", SR_OPT_INT, &job->frames, "N", "timed frames, after one untimed warm-up when N > 1 (default 1)", 1, MAX_FRAMES },
        { "--stats", SR_OPT_FLAG, &job->stats, NULL, "print one JSON line of per-frame statistics" },
        { 0 },
    };
    if (!sr_scene_setup_parse(&job->scene, own, USAGE, argc, argv, help, err))
        return false;
    if (!*help && !job->scene.mesh_path)
        return sr_error_set(err, "render needs one MESH.obj (see softrast render --help)");
    return true;
}

static bool run_frames(int frames, sr_scene *scene, const sr_draw_desc *desc, sr_stats *stats,
                       frame_times *times, sr_error *err)
{
    double *ms = malloc((size_t)frames * sizeof *ms), warm;
    if (!ms)
        return sr_error_set(err, "out of memory for %d frame times", frames);
    bool ok = frames == 1 || sr_study_draw_frame(&scene->fb, desc, stats, &warm, err);
    for (int f = 0; ok && f < frames; f++)
        ok = sr_study_draw_frame(&scene->fb, desc, stats, &ms[f], err);
    if (ok)
        sr_study_median_min(ms, frames, &times->median, &times->min);
    free(ms);
    return ok;
}

static bool write_outputs(const render_job *job, sr_scene *scene, sr_error *err)
{
    const sr_framebuffer *fb = &scene->fb;
    if (job->scene.shade == SR_SHADE_DEPTH)
        sr_framebuffer_depth_to_gray(fb, fb->color);
    if (job->out_path && !sr_image_write_png(job->out_path, fb->color, fb->width, fb->height, err))
        return false;
    if (job->depth_path && !sr_image_write_pfm(job->depth_path, fb->depth, fb->width, fb->height, err))
        return false;
    return !job->depth_png_path || sr_image_write_depth_png(job->depth_png_path, fb, err);
}

/* The triangle ids of each part of a multi-mesh file: [[first, count], ...]. */
static void print_parts(const sr_mesh *mesh)
{
    printf("[");
    for (uint32_t i = 0; i < mesh->part_count; i++)
        printf("%s[%u, %u]", i ? ", " : "", mesh->parts[i].first_triangle, mesh->parts[i].triangle_count);
    printf("]");
}

static void print_stats(int frames, const frame_times *t, const sr_stats *s, sr_simd simd, const sr_mesh *mesh)
{
    printf("{\"frames\": %d, \"ms_median\": %.4f, \"ms_min\": %.4f, \"triangles\": %llu, \"rejected\": %llu, "
           "\"clipped\": %llu, \"culled\": %llu, \"fragments\": %llu, \"nonfinite\": %llu, \"drawn\": %llu, "
           "\"cuts_float\": %llu, \"cuts_double\": %llu, \"cuts_exact\": %llu, \"simd\": \"%s\", \"parts\": ",
           frames, t->median, t->min, (unsigned long long)s->triangles, (unsigned long long)s->rejected,
           (unsigned long long)s->clipped, (unsigned long long)s->culled, (unsigned long long)s->fragments,
           (unsigned long long)s->nonfinite, (unsigned long long)s->drawn, (unsigned long long)s->cuts_float,
           (unsigned long long)s->cuts_double, (unsigned long long)s->cuts_exact,
           sr_simd_name(sr_raster_simd_resolve(simd)));
    print_parts(mesh);
    printf("}\n");
}

static bool render(render_job *job, sr_scene *scene, sr_error *err)
{
    sr_draw_desc desc;
    sr_draw_study study;
    sr_stats stats = { 0 };
    frame_times times = { 0 };
    if (!sr_scene_load(&job->scene, false, scene, err))
        return false;
    sr_scene_frame_camera(&job->scene, scene);
    if (!sr_scene_desc(&job->scene, scene, &desc, &study, err) ||
        !run_frames(job->frames, scene, &desc, &stats, &times, err) || !write_outputs(job, scene, err))
        return false;
    if (job->stats)
        print_stats(job->frames, &times, &stats, study.simd, &scene->mesh);
    return true;
}

int sr_app_render(int argc, char **argv)
{
    render_job job;
    sr_scene scene = { 0 };
    sr_error err = { { 0 } };
    bool help = false;
    job_defaults(&job);
    if (!parse_job(&job, argc, argv, &help, &err))
        return sr_app_fail(err.message);
    if (help)
        return 0;
    bool ok = render(&job, &scene, &err);
    sr_scene_free(&scene);
    return ok ? 0 : sr_app_fail(err.message);
}
