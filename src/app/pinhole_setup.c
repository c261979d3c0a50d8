/* The pinhole camera's options and outputs (pinhole_setup.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "pinhole_setup.h"
#include "core/clock.h"

static const char *const INVALID_NAMES[] = { "zero", "nan", NULL };
static const char *const NORMAL_KIND_NAMES[] = { "geometric", "interpolated", NULL };
static const char *const FACE_IDS_OF_NAMES[] = { "triangle", "file", NULL };

static const struct {
    const char *option, *key, *extensions[5];
} MEASURED[SR_MEASURED_COUNT] = {
    [SR_MEASURED_DEPTH] = { "--view-depth", "depth_file_path", { ".npy", ".pfm", ".png", ".exr" } },
    [SR_MEASURED_RANGE] = { "--range", "range_file_path", { ".npy", ".pfm", ".png", ".exr" } },
    [SR_MEASURED_FACE_IDS] = { "--face-ids", "face_ids_file_path", { ".npy", ".png" } },
    [SR_MEASURED_PART_IDS] = { "--part-ids", "part_ids_file_path", { ".npy", ".png" } },
    [SR_MEASURED_NORMALS] = { "--normals", "normals_file_path", { ".npy", ".exr" } },
};

const char *sr_measured_option(sr_measured k)
{
    return MEASURED[k].option;
}

const char *sr_measured_key(sr_measured k)
{
    return MEASURED[k].key;
}

void sr_pinhole_setup_options(sr_pinhole_setup *p, sr_option *table)
{
    const sr_option entries[] = {
        { "--intrinsics", SR_OPT_NUMBERS, p->intrinsics, "FX,FY,CX,CY", "pinhole intrinsics in pixels, OpenCV's (the top-left pixel's centre is 0,0; default: --fov, centred)", .count = 4, .seen = &p->intrinsics_set },
        { "--pose-w2c", SR_OPT_NUMBERS, p->pose_w2c, "16 NUMBERS", "world-to-camera pose, a row-major 4x4 in the file's frame; camera x right, y down, z forward", .count = 16, .seen = &p->w2c_set },
        { "--pose-c2w", SR_OPT_NUMBERS, p->pose_c2w, "16 NUMBERS", "camera-to-world pose, the inverse of --pose-w2c", .count = 16, .seen = &p->c2w_set },
        { "--view-depth", SR_OPT_STRING, &p->paths[SR_MEASURED_DEPTH], "FILE.npy|.pfm", "z along the optical axis in mesh units, float32 (needs a pose)" },
        { "--range", SR_OPT_STRING, &p->paths[SR_MEASURED_RANGE], "FILE.npy|.pfm", "distance from the camera centre, float32 (needs a pose)" },
        { "--face-ids", SR_OPT_STRING, &p->paths[SR_MEASURED_FACE_IDS], "FILE.npy|.png", "triangle id + 1 per pixel, 0 where nothing: uint32 .npy or 16-bit PNG (needs a pose)" },
        { "--part-ids", SR_OPT_STRING, &p->paths[SR_MEASURED_PART_IDS], "FILE.npy|.png", "the file's part (an instance of a mesh, an OBJ group) + 1 per pixel, 0 where nothing (needs a pose)" },
        { "--face-ids-of", SR_OPT_CHOICE, &p->face_ids_of, "triangle|file", "--face-ids names the triangle (default) or the file's face it was fanned from", .choices = FACE_IDS_OF_NAMES, .seen = &p->face_ids_of_set },
        { "--normals", SR_OPT_STRING, &p->paths[SR_MEASURED_NORMALS], "FILE.npy", "unit normals in the camera frame, float32 HxWx3 (needs a pose)" },
        { "--normal-kind", SR_OPT_CHOICE, &p->normal_kind, "geometric|interpolated", "the triangle's normal, or the vertex normals interpolated (default geometric)", .choices = NORMAL_KIND_NAMES },
        { "--depth-scale", SR_OPT_FLOAT, &p->depth_scale, "S", "view depth and range in .png: uint16 of the value times S (default 1000: millimetres of metres)", 1e-30, 3e38 },
        { "--invalid", SR_OPT_CHOICE, &p->invalid, "zero|nan", "view depth and range where nothing is drawn (default zero)", .choices = INVALID_NAMES },
    };
    _Static_assert(sizeof entries / sizeof *entries == SR_PINHOLE_OPTION_COUNT, "the entries' count");
    memcpy(table, entries, sizeof entries);
}

bool sr_pinhole_setup_on(const sr_pinhole_setup *p)
{
    return p->w2c_set || p->c2w_set;
}

bool sr_pinhole_setup_wants_depth(const sr_pinhole_setup *p)
{
    for (int i = 0; i < SR_MEASURED_COUNT; i++)
        if (p->paths[i])
            return true;
    return false;
}

/* Whether path ends in ext, in any case. */
static bool ends_with(const char *path, const char *ext)
{
    const char *dot = strrchr(path, '.');
    return dot && strcasecmp(dot, ext) == 0;
}

/* The extension of output i's path that a writer has, or NULL. */
static const char *writer_extension(sr_measured i, const char *path)
{
    for (int k = 0; k < 5 && MEASURED[i].extensions[k]; k++)
        if (ends_with(path, MEASURED[i].extensions[k]))
            return MEASURED[i].extensions[k];
    return NULL;
}

/* An output's extensions in words: ".npy, .pfm, .png". */
static const char *extension_list(sr_measured i)
{
    static char list[64];
    list[0] = '\0';
    for (int k = 0; k < 5 && MEASURED[i].extensions[k]; k++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k ? ", " : "", MEASURED[i].extensions[k]);
    return list;
}

bool sr_pinhole_setup_check_outputs(const sr_pinhole_setup *p, sr_error *err)
{
    for (int i = 0; i < SR_MEASURED_COUNT; i++)
        if (p->paths[i] && !writer_extension((sr_measured)i, p->paths[i]))
            return sr_error_set(err, "%s %s: no writer for this extension (%s)", MEASURED[i].option, p->paths[i],
                                extension_list((sr_measured)i));
    return true;
}

bool sr_pinhole_setup_check(const sr_pinhole_setup *p, const sr_scene_setup *s, sr_error *err)
{
    if (p->w2c_set && p->c2w_set)
        return sr_error_set(err, "give one pose: --pose-w2c or --pose-c2w, not both");
    const char *const *paths = p->paths;
    if (!sr_pinhole_setup_on(p)) {
        for (int i = 0; i < SR_MEASURED_COUNT; i++)
            if (paths[i])
                return sr_error_set(err, "%s needs a camera pose: --pose-w2c or --pose-c2w (16 numbers)",
                                    MEASURED[i].option);
        if (p->intrinsics_set)
            return sr_error_set(err, "--intrinsics needs a camera pose: --pose-w2c or --pose-c2w (16 numbers)");
        return true;
    }
    if (p->face_ids_of_set && !paths[SR_MEASURED_FACE_IDS])
        return sr_error_set(err, "--face-ids-of says what --face-ids names: give --face-ids too");
    if (s->eye_set || s->target_set || s->look_at_set)
        return sr_error_set(err, "a pose places the camera in the file's frame: --eye, --target, --up, --ortho, --rotate-y, "
                                 "--up-axis and --reversed-z are the look-at camera's");
    if (p->intrinsics_set && s->fov_set)
        return sr_error_set(err, "--intrinsics and --fov both give the field of view: give one");
    return sr_pinhole_setup_check_outputs(p, err);
}

bool sr_pinhole_setup_camera(const sr_pinhole_setup *p, const sr_scene_setup *s, const sr_mesh *mesh,
                             sr_pinhole *cam, sr_error *err)
{
    int width = s->size[0], height = s->size[1];
    *cam = (sr_pinhole){ 0 };
    if (p->intrinsics_set) {
        cam->fx = p->intrinsics[0];
        cam->fy = p->intrinsics[1];
        cam->cx = p->intrinsics[2];
        cam->cy = p->intrinsics[3];
    } else {
        cam->fy = cam->fx = 0.5 * height / tan(0.5 * (double)s->camera.fov_deg * GLM_PI / 180.0);
        cam->cx = 0.5 * (width - 1);
        cam->cy = 0.5 * (height - 1);
    }
    if (p->c2w_set) {
        double c2w[4][4];
        memcpy(c2w, p->pose_c2w, sizeof c2w);
        if (!sr_pinhole_pose_from_c2w(c2w, cam->w2c, err))
            return false;
    } else {
        memcpy(cam->w2c, p->pose_w2c, sizeof cam->w2c);
    }
    return sr_pinhole_setup_clip(s, mesh, cam, err);
}

bool sr_pinhole_setup_clip(const sr_scene_setup *s, const sr_mesh *mesh, sr_pinhole *cam, sr_error *err)
{
    if (s->near_set || s->far_set) {
        cam->near = s->camera.near;
        cam->far = s->camera.far;
    }
    if (!sr_pinhole_check(cam, err))
        return false;
    sr_pinhole_fit_clip(cam, mesh);
    return true;
}

/* Ids as a 16-bit PNG, refused with one line past 65535. */
static bool write_ids_png(const char *path, const uint32_t *ids, int width, int height, sr_error *err)
{
    size_t n = (size_t)width * (size_t)height;
    uint16_t *gray = malloc(n * sizeof *gray);
    if (!gray)
        return sr_error_set(err, "%s: out of memory for a %dx%d image", path, width, height);
    bool fits = true;
    for (size_t i = 0; i < n && fits; i++) {
        fits = ids[i] <= UINT16_MAX;
        gray[i] = (uint16_t)ids[i];
    }
    bool ok = fits ? sr_image_write_png16(path, gray, width, height, err)
                   : sr_error_set(err, "%s: an id passes 65535, past a 16-bit PNG: write .npy (uint32)", path);
    free(gray);
    return ok;
}

/* Depth or range as a 16-bit PNG of the value times scale, rounded: 0
 * where nothing is drawn, values past 65535 saturated with one warning
 * that counts them. */
static bool write_depth_png(const char *path, const float *values, int width, int height, float scale,
                            sr_error *err)
{
    size_t n = (size_t)width * (size_t)height, saturated = 0;
    uint16_t *gray = malloc(n * sizeof *gray);
    if (!gray)
        return sr_error_set(err, "%s: out of memory for a %dx%d image", path, width, height);
    for (size_t i = 0; i < n; i++) {
        double v = (double)values[i] * scale;
        saturated += v >= UINT16_MAX + 0.5;
        gray[i] = !(v > 0.0) ? 0 : v >= UINT16_MAX + 0.5 ? UINT16_MAX : (uint16_t)(v + 0.5);
    }
    if (saturated)
        fprintf(stderr, "softrast: warning: %s: %zu pixels past %g units (65535 at --depth-scale %g) saturated\n",
                path, saturated, UINT16_MAX / (double)scale, (double)scale);
    bool ok = sr_image_write_png16(path, gray, width, height, err);
    free(gray);
    return ok;
}

static bool write_output(const sr_pinhole_setup *p, sr_measured i, const char *path, const void *values, int width,
                         int height, sr_error *err)
{
    const char *ext = writer_extension(i, path);
    bool ids = i == SR_MEASURED_FACE_IDS || i == SR_MEASURED_PART_IDS;
    if (strcmp(ext, ".exr") == 0)
        return sr_image_write_exr(path, values, width, height, i == SR_MEASURED_NORMALS ? 3 : 1, err);
    if (strcmp(ext, ".pfm") == 0) /* PFM's rows run bottom to top: the writer turns them */
        return sr_image_write_pfm(path, values, width, height, err);
    if (strcmp(ext, ".png") == 0)
        return ids ? write_ids_png(path, values, width, height, err)
                   : write_depth_png(path, values, width, height, p->depth_scale, err);
    return sr_image_write_npy(path, values, ids ? SR_NPY_UINT32 : SR_NPY_FLOAT32, width, height,
                              i == SR_MEASURED_NORMALS ? 3 : 1, err);
}

/* The outputs asked for, resolved on `threads` from fb (a draw with cam
 * into fb and its ids plane); the resolve's time to *resolve_ms. */
static bool write_resolved(const sr_pinhole_setup *p, const sr_pinhole *cam, const sr_mesh *mesh,
                           const sr_framebuffer *fb, int threads, double *resolve_ms, sr_error *err)
{
    size_t n = (size_t)fb->width * (size_t)fb->height;
    void *values[SR_MEASURED_COUNT] = { 0 };
    bool ok = true;
    for (int i = 0; i < SR_MEASURED_COUNT; i++)
        if (p->paths[i] && !(values[i] = malloc(n * (i == SR_MEASURED_NORMALS ? 3 : 1) * sizeof(float))))
            ok = false;
    if (!ok)
        sr_error_set(err, "out of memory for %dx%d outputs", fb->width, fb->height);
    sr_pinhole_outputs out = { .depth = values[SR_MEASURED_DEPTH], .range = values[SR_MEASURED_RANGE],
                               .face_ids = values[SR_MEASURED_FACE_IDS], .part_ids = values[SR_MEASURED_PART_IDS],
                               .normals = values[SR_MEASURED_NORMALS], .interpolated_normals = p->normal_kind == 1,
                               .file_faces = p->face_ids_of == 1, .invalid = p->invalid ? NAN : 0.0f, .threads = threads };
    double start = sr_now_ms();
    ok = ok && sr_pinhole_resolve(cam, mesh, fb, &out, err);
    *resolve_ms = sr_now_ms() - start;
    for (int i = 0; ok && i < SR_MEASURED_COUNT; i++)
        ok = !p->paths[i] || write_output(p, (sr_measured)i, p->paths[i], values[i], fb->width, fb->height, err);
    for (int i = 0; i < SR_MEASURED_COUNT; i++)
        free(values[i]);
    return ok;
}

void sr_pinhole_setup_desc(const sr_scene_setup *s, const sr_pinhole *cam, sr_scene *scene, bool color_used,
                           sr_draw_desc *desc)
{
    sr_pinhole_matrices(cam, &scene->mesh, &scene->fb, desc);
    if (!s->cull_set)
        desc->cull = SR_CULL_NONE;
    if (!color_used && !s->shade_set)
        desc->shade = SR_SHADE_ID;
}

bool sr_pinhole_setup_ids(const sr_pinhole_setup *p, sr_scene *scene, sr_error *err)
{
    return !sr_pinhole_setup_wants_depth(p) || sr_framebuffer_create_ids(&scene->fb, err);
}

bool sr_pinhole_setup_write(const sr_pinhole_setup *p, const sr_pinhole *cam, sr_scene *scene,
                            const sr_draw_desc *desc, double *resolve_ms, sr_error *err)
{
    *resolve_ms = 0.0;
    if (!sr_pinhole_setup_wants_depth(p))
        return true;
    if (p->paths[SR_MEASURED_NORMALS] && p->normal_kind && desc->mesh == &scene->mesh &&
        !sr_mesh_compute_normals(&scene->mesh, err))
        return false;
    return write_resolved(p, cam, desc->mesh, &scene->fb, desc->threads, resolve_ms, err);
}
