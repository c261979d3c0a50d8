/* softrast render — one image without a window. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "dataset.h"
#include "transforms.h"
#include "pinhole_setup.h"
#include "scene_setup.h"
#include "hidden_lines.h"
#include "core/clock.h"
#include "scene/frame.h"

#define MAX_FRAMES 100000
#define RENDER_OPTION_COUNT 15 /* render's own, before the pinhole camera's */

typedef struct render_job {
    sr_scene_setup scene;
    sr_pinhole_setup pinhole;
    sr_dataset_job dataset;
    const char *out_path, *depth_path, *depth_png_path;
    int frames;
    bool stats, quiet;
    bool points, lines; /* draw the mesh's vertices, or its edges with hidden lines removed */
    float point_size, line_width;
    int blend, depth_write;        /* --blend (sr_blend), --depth-write (an index of DEPTH_WRITE_NAMES) */
    bool blend_set, depth_write_set; /* given: one draw of the whole mesh so, not the file's layers */
} render_job;

static const char *const BLEND_NAMES[] = { "replace", "alpha", "additive", "premultiplied", NULL }; /* sr_blend */
static const char *const DEPTH_WRITE_NAMES[] = { "on", "off", NULL };

typedef struct frame_times {
    double median, min; /* of the draws */
    double resolve;     /* the pinhole outputs' resolve after them, files aside (0: none) */
} frame_times;

static const char USAGE[] =
    "usage: softrast render MESH.obj [options]\n"
    "Draws MESH.obj into an image without a window. Without --eye/--target the camera\n"
    "looks at the centre of the mesh's bounds from its front, 30 degrees to the right and\n"
    "20 above, far enough back to see all of it.\n"
    "With --pose-w2c or --pose-c2w it is a pinhole camera in OpenCV's convention, in the\n"
    "file's own frame, and --view-depth and --range write metric depth (docs/cli.md).";

static void job_defaults(render_job *job)
{
    *job = (render_job){ .frames = 1, .pinhole = { .depth_scale = SR_DEPTH_PNG_SCALE }, .point_size = 1.0f,
                         .line_width = 1.0f };
    sr_scene_setup_defaults(&job->scene);
}

static int is_stdout(const char *path)
{
    return path && strcmp(path, "-") == 0;
}

static bool parse_job(void *j, int argc, char **argv, bool *help, sr_error *err)
{
    render_job *job = j;
    sr_option own[RENDER_OPTION_COUNT + SR_PINHOLE_OPTION_COUNT + 1] = {
        { "--out", SR_OPT_STRING, &job->out_path, "FILE.png", "write the color image (8-bit RGB)" },
        { "--depth", SR_OPT_STRING, &job->depth_path, "FILE.pfm", "write the raw float32 depth buffer (PFM)" },
        { "--depth-png", SR_OPT_STRING, &job->depth_png_path, "FILE.png", "write the depth buffer, remapped to the visible range" },
        { "--frames", SR_OPT_INT, &job->frames, "N", "timed frames, after one untimed warm-up when N > 1 (default 1)", 1, MAX_FRAMES },
        { "--stats", SR_OPT_FLAG, &job->stats, NULL, "print one JSON line of per-frame statistics" },
        { "--quiet", SR_OPT_FLAG, &job->quiet, NULL, "no summary line on stderr on success (warnings still print)" },
        { "--poses", SR_OPT_STRING, &job->dataset.poses_path, "transforms.json", "render every frame of a NeRF / instant-ngp / nerfstudio camera dataset (with --out-dir)" },
        { "--out-dir", SR_OPT_STRING, &job->dataset.out_dir, "DIR", "with --poses: each output NAME.EXT to DIR/NAME/frame_IIIII.EXT, and DIR/transforms.json" },
        { "--frame-range", SR_OPT_RANGE, job->dataset.range, "A:B", "with --poses: frames A up to, not including, B (a shard)", 0, SR_TRANSFORMS_MAX_FRAMES, .seen = &job->dataset.range_set },
        { "--points", SR_OPT_FLAG, &job->points, NULL, "draw the mesh's vertices as points (a point cloud: with its colors)" },
        { "--lines", SR_OPT_FLAG, &job->lines, NULL, "draw the mesh's edges, hidden lines removed" },
        { "--point-size", SR_OPT_FLOAT, &job->point_size, "PX", "with --points: each point a square this many pixels wide (default 1)", 1.0, SR_MAX_POINT_SIZE },
        { "--line-width", SR_OPT_FLOAT, &job->line_width, "PX", "with --lines: lines this many whole pixels wide (default 1)", 1.0, SR_MAX_LINE_WIDTH },
        { "--blend", SR_OPT_CHOICE, &job->blend, "replace|alpha|additive|premultiplied", "draw the whole mesh in one draw blending so, in file order (default: the file's BLEND parts blended over the rest, farthest first)", .choices = BLEND_NAMES, .seen = &job->blend_set },
        { "--depth-write", SR_OPT_CHOICE, &job->depth_write, "on|off", "with --blend: whether the draw writes depth (default on)", .choices = DEPTH_WRITE_NAMES, .seen = &job->depth_write_set },
    };
    sr_pinhole_setup_options(&job->pinhole, own + RENDER_OPTION_COUNT);
    if (!sr_scene_setup_parse(&job->scene, own, NULL, USAGE, argc, argv, help, err))
        return false;
    if (!*help && !job->scene.mesh_path)
        return sr_error_set(err, "render needs one MESH.obj (see softrast render --help)");
    int to_stdout = job->stats + is_stdout(job->out_path) + is_stdout(job->depth_path) +
                    is_stdout(job->depth_png_path);
    if (to_stdout > 1)
        return sr_error_set(err, "only one of --out -, --depth -, --depth-png - and --stats can write to stdout");
    job->dataset.color_name = job->out_path;
    const char *single[] = { job->depth_path ? "--depth" : job->depth_png_path ? "--depth-png" : NULL, NULL };
    if (*help)
        return true;
    if (job->points && job->lines)
        return sr_error_set(err, "--points and --lines draw one or the other");
    for (int k = 0; k < SR_MEASURED_COUNT; k++)
        if (job->lines && job->pinhole.paths[k])
            return sr_error_set(err, "--lines draws color and depth: not the measured outputs (--view-depth, ...)");
    if ((job->points || job->lines) && (job->dataset.poses_path || job->dataset.out_dir))
        return sr_error_set(err, "--points and --lines are not for --poses");
    if (job->blend_set && job->lines)
        return sr_error_set(err, "--blend is not for --lines (their triangles fill the depth the lines are tested by)");
    if (job->depth_write_set && !job->blend_set)
        return sr_error_set(err, "--depth-write goes with --blend (without it, BLEND parts write no depth, the others do)");
    for (int k = 0; k < SR_MEASURED_COUNT; k++)
        if (job->blend_set && (job->pinhole.paths[k] || job->dataset.poses_path || job->dataset.out_dir))
            return sr_error_set(err, "--blend draws the color image: not for --poses or the measured outputs (--view-depth, ...)");
    if (job->dataset.poses_path || job->dataset.out_dir)
        return sr_dataset_check(&job->dataset, &job->pinhole, &job->scene, single[0] ? single : NULL, err);
    return !job->dataset.range_set ? sr_pinhole_setup_check(&job->pinhole, &job->scene, err)
                                    : sr_error_set(err, "--frame-range goes with --poses");
}

/* One timed frame: desc (in the file's layers unless `one_draw`: sr_draw_layered),
 * or with `wire` the hidden-line frame of desc's triangles and their edges,
 * counted as the lines' draw. */
static bool draw_frame(sr_scene *scene, const sr_draw_desc *desc, sr_hidden_lines *wire, bool one_draw,
                       sr_stats *stats, double *ms, sr_error *err)
{
    sr_stats fill;
    if (wire)
        return sr_hidden_lines_frame(wire, &scene->fb, desc, &fill, stats, ms, err);
    return one_draw ? sr_frame_draw_timed(&scene->fb, desc, stats, ms, err)
                    : sr_frame_draw_layers_timed(&scene->fb, desc, stats, ms, err);
}

static bool run_frames(int frames, sr_scene *scene, const sr_draw_desc *desc, sr_hidden_lines *lines, bool one_draw,
                       sr_stats *stats, frame_times *times, sr_error *err)
{
    double *ms = malloc((size_t)frames * sizeof *ms), warm;
    if (!ms)
        return sr_error_set(err, "out of memory for %d frame times", frames);
    bool ok = frames == 1 || draw_frame(scene, desc, lines, one_draw, stats, &warm, err);
    for (int f = 0; ok && f < frames; f++)
        ok = draw_frame(scene, desc, lines, one_draw, stats, &ms[f], err);
    if (ok)
        sr_median_min(ms, frames, &times->median, &times->min);
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

/* What the draw counted: "triangles", "points" or "lines", and how many. */
static const char *primitives_of(const sr_stats *s, unsigned long long *count)
{
    *count = s->points ? s->points : s->lines ? s->lines : s->triangles;
    return s->points ? "points" : s->lines ? "lines" : "triangles";
}

/* Why no pixel was drawn, in words, or NULL when some were. */
static const char *nothing_drawn(const sr_stats *s)
{
    if (s->fragments > 0)
        return NULL;
    if (s->points || s->lines) {
        unsigned long long n;
        primitives_of(s, &n);
        if (s->nonfinite == n)
            return "every point or line has a non-finite position or varying (NaN, inf or past float range)";
        if (s->rejected == n)
            return "every point or line lies outside the view volume (or is non-finite)";
        return "the points or lines drawn cover no pixel centre";
    }
    if (s->triangles == 0)
        return "the mesh has no triangles";
    if (s->nonfinite == s->triangles)
        return "every triangle has a non-finite position or varying (NaN, inf or past float range)";
    if (s->rejected == s->triangles)
        return "every triangle lies outside the view volume (or is non-finite)";
    if (s->drawn == 0)
        return "every triangle inside the view faces away or has no area";
    return "the triangles drawn cover no pixel centre";
}

/* The rejected counts by plane: " (far 3, left 1)" for the warning (the
 * planes with any, nothing when none), {"near": 0, ...} for --stats. */
static void print_rejected_by_plane(FILE *out, const sr_stats *s, bool json)
{
    int n = 0;
    for (int p = 0; p < SR_CLIP_PLANES; p++) {
        unsigned long long count = s->rejected_by_plane[p];
        const char *name = sr_clip_plane_table[p].name;
        if (json)
            fprintf(out, "%s\"%s\": %llu", n++ ? ", " : "{", name, count);
        else if (count)
            fprintf(out, "%s%s %llu", n++ ? ", " : " (", name, count);
    }
    fputs(json ? "}" : n ? ")" : "", out);
}

/* One line on stderr when nothing was drawn: the counts, where the mesh lies
 * in softrast's world (the file's z negated, --rotate-y not applied) and
 * where the camera looks from, so the fix can be read off. */
static void explain_nothing_drawn(const sr_scene_setup *setup, const sr_scene *scene, const sr_stats *s)
{
    const char *why = nothing_drawn(s);
    if (!why)
        return;
    vec3 lo = { 0 }, hi = { 0 };
    sr_mesh_bounds(&scene->mesh, lo, hi);
    const double *m = scene->mesh.origin, *c = setup->camera.origin;
    const float *eye = setup->camera.eye, *at = setup->camera.target;
    unsigned long long count;
    const char *noun = primitives_of(s, &count);
    fprintf(stderr, "softrast: warning: nothing drawn: %s (%llu %s: %llu rejected outside", why, count, noun,
            (unsigned long long)s->rejected);
    print_rejected_by_plane(stderr, s, false);
    fprintf(stderr,
            ", %llu of them non-finite, %llu culled); the mesh spans %g,%g,%g to %g,%g,%g in softrast's world (the file's z negated), the eye "
            "is at %g,%g,%g looking at %g,%g,%g with near %g, far %g: see --eye, --target, --near, --far, --cull\n",
            (unsigned long long)s->nonfinite, (unsigned long long)s->culled, lo[0] + m[0], lo[1] + m[1],
            lo[2] + m[2], hi[0] + m[0], hi[1] + m[1], hi[2] + m[2], eye[0] + c[0], eye[1] + c[1], eye[2] + c[2],
            at[0] + c[0], at[1] + c[1], at[2] + c[2], setup->camera.near, setup->camera.far);
}

static void print_stats(int frames, const frame_times *t, const sr_stats *s, sr_simd simd, const sr_mesh *mesh)
{
    const char *why = nothing_drawn(s);
    printf("{\"frames\": %d, \"ms_median\": %.4f, \"ms_min\": %.4f, \"resolve_ms\": %.4f, \"triangles\": %llu, "
           "\"rejected\": %llu, "
           "\"clipped\": %llu, \"culled\": %llu, \"fragments\": %llu, \"nonfinite\": %llu, \"drawn\": %llu, "
           "\"cuts_float\": %llu, \"cuts_double\": %llu, \"cuts_exact\": %llu, \"simd\": \"%s\", "
           "\"nothing_drawn\": %s%s%s, \"rejected_by_plane\": ",
           frames, t->median, t->min, t->resolve, (unsigned long long)s->triangles, (unsigned long long)s->rejected,
           (unsigned long long)s->clipped, (unsigned long long)s->culled, (unsigned long long)s->fragments,
           (unsigned long long)s->nonfinite, (unsigned long long)s->drawn, (unsigned long long)s->cuts_float,
           (unsigned long long)s->cuts_double, (unsigned long long)s->cuts_exact,
           sr_simd_name(sr_raster_simd_resolve(simd)), why ? "\"" : "", why ? why : "null", why ? "\"" : "");
    print_rejected_by_plane(stdout, s, true);
    printf(", \"parts\": ");
    print_parts(mesh);
    printf(", \"points\": %llu, \"lines\": %llu}\n", (unsigned long long)s->points, (unsigned long long)s->lines);
}

/* The one line a successful render prints on stderr, stdout being for the
 * image or the stats: what was written (or that nothing was), the size and
 * the triangles drawn. */
static void report_done(const render_job *job, const sr_framebuffer *fb, const sr_stats *s)
{
    const sr_pinhole_setup *p = &job->pinhole;
    const char *paths[3 + SR_MEASURED_COUNT] = { job->out_path, job->depth_path, job->depth_png_path };
    memcpy(paths + 3, p->paths, sizeof p->paths);
    char line[8 * SR_ERROR_MAX];
    int n = snprintf(line, sizeof line, "softrast: "), written = 0;
    for (size_t i = 0; i < sizeof paths / sizeof *paths; i++)
        if (paths[i] && n < (int)sizeof line)
            n += snprintf(line + n, sizeof line - (size_t)n, "%s%s", written++ ? ", " : "wrote ",
                          is_stdout(paths[i]) ? "stdout" : paths[i]);
    const char *format = written ? " (%dx%d, %llu %s drawn)\n"
                                 : "drew %dx%d (%llu %s drawn); nothing written: name a file with --out, "
                                   "--depth, --depth-png, --view-depth or --range\n";
    unsigned long long count;
    if (n < (int)sizeof line)
        snprintf(line + n, sizeof line - (size_t)n, format, fb->width, fb->height, (unsigned long long)s->drawn,
                 primitives_of(s, &count));
    fputs(line, stderr);
}

/* The pinhole camera of the options, into desc, and the framebuffer's ids
 * plane for its outputs: the frames draw color and ids at once. */
static bool use_pinhole(render_job *job, sr_scene *scene, sr_pinhole *cam, sr_draw_desc *desc, sr_error *err)
{
    if (!sr_pinhole_setup_camera(&job->pinhole, &job->scene, &scene->mesh, cam, err) ||
        !sr_pinhole_setup_ids(&job->pinhole, scene, err))
        return false;
    /* Points and lines keep their shading: their draw has no lanes that ids would speed up. */
    sr_pinhole_setup_desc(&job->scene, cam, scene, job->out_path || job->points || job->lines, desc);
    return true;
}

/* With --points, desc draws the mesh's vertices; with --lines, *lines
 * holds its edges, drawn after desc's triangles (sr_hidden_lines_frame). */
static bool primitives_desc(const render_job *job, const sr_scene *scene, sr_mesh *primitives, sr_draw_desc *desc,
                            sr_hidden_lines *lines, sr_error *err)
{
    if (job->points) {
        if (!sr_wireframe_points(&scene->mesh, primitives, err))
            return false;
        desc->mesh = primitives;
        desc->point_size = job->point_size;
    } else if (job->lines) {
        if (!sr_hidden_lines_make(&scene->mesh, lines, err))
            return false;
        lines->line_width = job->line_width;
    }
    return true;
}

static bool render(void *j, sr_scene *scene, sr_error *err)
{
    render_job *job = j;
    sr_draw_desc desc;
    sr_draw_study study;
    sr_pinhole cam;
    sr_stats stats = { 0 };
    frame_times times = { 0 };
    bool pinhole = sr_pinhole_setup_on(&job->pinhole);
    if (job->dataset.poses_path) {
        if (!sr_dataset_render(&job->dataset, &job->pinhole, &job->scene, scene, err))
            return false;
        if (!job->quiet)
            fprintf(stderr, "softrast: wrote %s/transforms.json and its frames' files\n", job->dataset.out_dir);
        return true;
    }
    if (!sr_scene_load(&job->scene, false, scene, err))
        return false;
    if (job->points && !job->scene.shade_set && scene->mesh.colors)
        job->scene.shade = SR_SHADE_COLOR; /* a point cloud's own colors */
    if (!pinhole)
        sr_scene_frame_camera(&job->scene, scene);
    sr_mesh primitives = { 0 };
    sr_hidden_lines lines = { 0 };
    /* A point's normal is its vertex's: made before the points borrow them
     * (0 for a cloud without, which has no faces to make them from). */
    bool point_normals = job->points && job->pinhole.paths[SR_MEASURED_NORMALS];
    if (!sr_scene_desc(&job->scene, scene, &desc, &study, err) || (pinhole && !use_pinhole(job, scene, &cam, &desc, err)) ||
        (point_normals && !sr_mesh_compute_normals(&scene->mesh, err)) ||
        !primitives_desc(job, scene, &primitives, &desc, &lines, err))
        return false;
    desc.blend = (sr_blend)job->blend;
    desc.no_depth_write = job->depth_write == 1;
    bool ok = run_frames(job->frames, scene, &desc, job->lines ? &lines : NULL, job->blend_set, &stats, &times, err) &&
              write_outputs(job, scene, err) &&
              (!pinhole || sr_pinhole_setup_write(&job->pinhole, &cam, scene, &desc, &times.resolve, err));
    sr_wireframe_free(&primitives);
    sr_hidden_lines_destroy(&lines);
    if (!ok)
        return false;
    if (!pinhole)
        explain_nothing_drawn(&job->scene, scene, &stats);
    if (job->stats)
        print_stats(job->frames, &times, &stats, study.simd, &scene->mesh);
    if (!job->quiet)
        report_done(job, &scene->fb, &stats);
    return true;
}

int sr_app_render(int argc, char **argv)
{
    render_job job;
    job_defaults(&job);
    return sr_app_command_run(&(sr_app_command){ parse_job, render }, &job, argc, argv);
}
