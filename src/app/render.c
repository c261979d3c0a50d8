/* softrast render — one image without a window. */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

#include "app.h"
#include "options.h"
#include "softrast/softrast.h"

#define MAX_FRAMES 100000
#define MAX_THREADS 256

static const char *const SHADE_NAMES[] = { "lambert", "id", "color", "normal", "texture", "depth", NULL };
static const char *const CULL_NAMES[] = { "back", "front", "none", NULL };
static const char *const FRONT_NAMES[] = { "cw", "ccw", NULL };
static const char *const FILTER_NAMES[] = { "bilinear", "nearest", NULL };

typedef struct render_job {
    const char *mesh_path;
    int size[2];
    sr_camera camera;
    bool eye_set, target_set;
    float rotate_y;
    int shade, cull, front, filter;
    const char *texture_path, *out_path, *depth_path, *depth_png_path;
    int frames, threads;
    bool stats;
} render_job;

/* What a draw needs that comes from files, released by inputs_free. */
typedef struct render_inputs {
    sr_mesh mesh;
    sr_texture texture;
    sr_framebuffer fb;
} render_inputs;

static const char USAGE[] =
    "usage: softrast render MESH.obj [options]\n"
    "Draws MESH.obj into an image without a window. Without --eye/--target the camera\n"
    "looks from -z at the centre of the mesh's bounds, far enough back to see all of it.";

static void job_defaults(render_job *job)
{
    *job = (render_job){ .size = { 1280, 720 }, .camera = sr_camera_default(), .frames = 1 };
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    job->threads = cores > 0 && cores <= MAX_THREADS ? (int)cores : 1;
}

static bool parse_job(render_job *job, int argc, char **argv, bool *help, sr_error *err)
{
    const sr_option table[] = {
        { "--size", SR_OPT_SIZE, job->size, "WxH", "framebuffer size (default 1280x720)", 1, SR_MAX_FRAMEBUFFER_SIDE },
        { "--eye", SR_OPT_VEC3, job->camera.eye, "X,Y,Z", "camera position (default: framed on the mesh from -z)", .seen = &job->eye_set },
        { "--target", SR_OPT_VEC3, job->camera.target, "X,Y,Z", "point looked at (default: the mesh's centre)", .seen = &job->target_set },
        { "--up", SR_OPT_VEC3, job->camera.up, "X,Y,Z", "up direction (default 0,1,0)" },
        { "--fov", SR_OPT_FLOAT, &job->camera.fov_deg, "DEG", "vertical field of view in degrees (default 60)", 1e-3, 179.999 },
        { "--near", SR_OPT_FLOAT, &job->camera.near, "N", "near clip plane distance (default 0.1)", 1e-30, 3e38 },
        { "--far", SR_OPT_FLOAT, &job->camera.far, "F", "far clip plane distance (default 100)", 1e-30, 3e38 },
        { "--ortho", SR_OPT_FLOAT, &job->camera.ortho_height, "HEIGHT", "orthographic projection of this view height", 1e-30, 3e38 },
        { "--rotate-y", SR_OPT_FLOAT, &job->rotate_y, "DEG", "turn the mesh about +y; positive turns +z toward +x", -1e6, 1e6 },
        { "--cull", SR_OPT_CHOICE, &job->cull, "back|front|none", "faces to drop (default back)", .choices = CULL_NAMES },
        { "--front", SR_OPT_CHOICE, &job->front, "cw|ccw", "winding on screen of a front face (default cw)", .choices = FRONT_NAMES },
        { "--shade", SR_OPT_CHOICE, &job->shade, "id|color|normal|texture|lambert|depth", "shading mode (default lambert)", .choices = SHADE_NAMES },
        { "--texture", SR_OPT_STRING, &job->texture_path, "FILE.png", "texture (default: the mesh's map_Kd, if any)" },
        { "--filter", SR_OPT_CHOICE, &job->filter, "bilinear|nearest", "texture filter (default bilinear)", .choices = FILTER_NAMES },
        { "--out", SR_OPT_STRING, &job->out_path, "FILE.png", "write the color image (8-bit RGB)" },
        { "--depth", SR_OPT_STRING, &job->depth_path, "FILE.pfm", "write the raw float32 depth buffer (PFM)" },
        { "--depth-png", SR_OPT_STRING, &job->depth_png_path, "FILE.png", "write the depth buffer, remapped to the visible range" },
        { "--frames", SR_OPT_INT, &job->frames, "N", "timed frames, after one untimed warm-up when N > 1 (default 1)", 1, MAX_FRAMES },
        { "--threads", SR_OPT_INT, &job->threads, "N", "threads in all (default: all cores)", 1, MAX_THREADS },
        { "--stats", SR_OPT_FLAG, &job->stats, NULL, "print one JSON line of per-frame statistics" },
        { 0 },
    };
    int positional = 0;
    if (!sr_options_parse(table, argc, argv, 2, &job->mesh_path, 1, &positional, help, err))
        return false;
    if (*help) {
        sr_options_print_help(stdout, USAGE, table);
        return true;
    }
    if (positional != 1)
        return sr_error_set(err, "render needs one MESH.obj (see softrast render --help)");
    return true;
}

static bool shade_uses_texture(sr_shade shade)
{
    return shade == SR_SHADE_TEXTURE || shade == SR_SHADE_LAMBERT;
}

static bool load_inputs(const render_job *job, render_inputs *in, sr_error *err)
{
    if (!sr_obj_load(&in->mesh, job->mesh_path, err))
        return false;
    const char *tex = job->texture_path ? job->texture_path : in->mesh.texture_path;
    if (tex && shade_uses_texture((sr_shade)job->shade) && !sr_texture_load(&in->texture, tex, err))
        return false;
    bool needs_normals = job->shade == SR_SHADE_LAMBERT || job->shade == SR_SHADE_NORMAL;
    if (needs_normals && !sr_mesh_compute_normals(&in->mesh, err))
        return false;
    return sr_framebuffer_create(&in->fb, job->size[0], job->size[1], err);
}

static void inputs_free(render_inputs *in)
{
    sr_mesh_free(&in->mesh);
    sr_texture_free(&in->texture);
    sr_framebuffer_destroy(&in->fb);
}

static bool make_desc(render_job *job, render_inputs *in, sr_draw_desc *desc, sr_error *err)
{
    float aspect = (float)job->size[0] / (float)job->size[1];
    vec3 lo, hi;
    if (!job->eye_set && !job->target_set && sr_mesh_bounds(&in->mesh, lo, hi))
        sr_camera_frame_bounds(&job->camera, lo, hi, aspect);
    if (!sr_camera_check(&job->camera, err))
        return false;
    *desc = (sr_draw_desc){ .mesh = &in->mesh, .shade = (sr_shade)job->shade, .cull = (sr_cull)job->cull,
                            .front = (sr_front)job->front, .filter = (sr_filter)job->filter,
                            .texture = in->texture.texels ? &in->texture : NULL };
    glm_rotate_make(desc->world, glm_rad(job->rotate_y), (vec3){ 0.0f, 1.0f, 0.0f });
    sr_camera_view(&job->camera, desc->view);
    sr_camera_projection(&job->camera, aspect, desc->projection);
    return true;
}

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

/* A timed frame is what a viewer pays: clear color and depth, then the draw. */
static bool draw_frame(render_inputs *in, const sr_draw_desc *desc, sr_stats *stats, double *ms, sr_error *err)
{
    double start = now_ms();
    *stats = (sr_stats){ 0 };
    sr_framebuffer_clear(&in->fb, 0x000000);
    bool ok = sr_draw(&in->fb, desc, stats, err);
    *ms = now_ms() - start;
    return ok;
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static bool run_frames(const render_job *job, render_inputs *in, const sr_draw_desc *desc, sr_stats *stats,
                       double *median, double *min, sr_error *err)
{
    double *ms = malloc((size_t)job->frames * sizeof *ms), warm;
    if (!ms)
        return sr_error_set(err, "out of memory for %d frame times", job->frames);
    bool ok = job->frames == 1 || draw_frame(in, desc, stats, &warm, err);
    for (int f = 0; ok && f < job->frames; f++)
        ok = draw_frame(in, desc, stats, &ms[f], err);
    if (ok) {
        qsort(ms, (size_t)job->frames, sizeof *ms, compare_double);
        *min = ms[0];
        *median = job->frames % 2 ? ms[job->frames / 2] : 0.5 * (ms[job->frames / 2 - 1] + ms[job->frames / 2]);
    }
    free(ms);
    return ok;
}

static bool write_outputs(const render_job *job, render_inputs *in, sr_error *err)
{
    if (job->shade == SR_SHADE_DEPTH)
        sr_framebuffer_depth_to_gray(&in->fb, in->fb.color);
    const sr_framebuffer *fb = &in->fb;
    if (job->out_path && !sr_image_write_png(job->out_path, fb->color, fb->width, fb->height, err))
        return false;
    if (job->depth_path && !sr_image_write_pfm(job->depth_path, fb->depth, fb->width, fb->height, err))
        return false;
    return !job->depth_png_path || sr_image_write_depth_png(job->depth_png_path, fb, err);
}

static void print_stats(int frames, double median, double min, const sr_stats *s)
{
    printf("{\"frames\": %d, \"ms_median\": %.4f, \"ms_min\": %.4f, \"triangles\": %llu, \"rejected\": %llu, "
           "\"clipped\": %llu, \"culled\": %llu, \"fragments\": %llu, \"nonfinite\": %llu}\n",
           frames, median, min, (unsigned long long)s->triangles, (unsigned long long)s->rejected,
           (unsigned long long)s->clipped, (unsigned long long)s->culled, (unsigned long long)s->fragments,
           (unsigned long long)s->nonfinite);
}

int sr_app_render(int argc, char **argv)
{
    render_job job;
    render_inputs in = { 0 };
    sr_error err = { { 0 } };
    sr_draw_desc desc;
    sr_stats stats = { 0 };
    double median = 0.0, min = 0.0;
    bool help = false;
    job_defaults(&job);
    bool ok = parse_job(&job, argc, argv, &help, &err);
    if (ok && help)
        return 0;
    ok = ok && load_inputs(&job, &in, &err) && make_desc(&job, &in, &desc, &err) &&
         run_frames(&job, &in, &desc, &stats, &median, &min, &err) && write_outputs(&job, &in, &err);
    if (ok && job.stats)
        print_stats(job.frames, median, min, &stats);
    inputs_free(&in);
    return ok ? 0 : sr_app_fail(err.message);
}
