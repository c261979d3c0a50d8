/* The pinhole camera's options and outputs (pinhole_setup.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "pinhole_setup.h"

static const char *const INVALID_NAMES[] = { "zero", "nan", NULL };
static const char *const NORMAL_KIND_NAMES[] = { "geometric", "interpolated", NULL };

/* The outputs measured from the camera: what each holds, the extensions
 * a writer has for it. */
typedef enum output_kind { OUT_DEPTH, OUT_RANGE, OUT_FACE_IDS, OUT_PART_IDS, OUT_NORMALS, OUTPUTS } output_kind;

static const struct {
    const char *option, *extensions[3];
} OUTPUT_FORMATS[OUTPUTS] = {
    [OUT_DEPTH] = { "--view-depth", { ".npy", ".pfm" } },
    [OUT_RANGE] = { "--range", { ".npy", ".pfm" } },
    [OUT_FACE_IDS] = { "--face-ids", { ".npy", ".png" } },
    [OUT_PART_IDS] = { "--part-ids", { ".npy", ".png" } },
    [OUT_NORMALS] = { "--normals", { ".npy" } },
};

static void output_paths(const sr_pinhole_setup *p, const char *paths[OUTPUTS])
{
    paths[OUT_DEPTH] = p->view_depth_path;
    paths[OUT_RANGE] = p->range_path;
    paths[OUT_FACE_IDS] = p->face_ids_path;
    paths[OUT_PART_IDS] = p->part_ids_path;
    paths[OUT_NORMALS] = p->normals_path;
}

void sr_pinhole_setup_options(sr_pinhole_setup *p, sr_option *table)
{
    const sr_option entries[] = {
        { "--intrinsics", SR_OPT_NUMBERS, p->intrinsics, "FX,FY,CX,CY", "pinhole intrinsics in pixels, OpenCV's (the top-left pixel's centre is 0,0; default: --fov, centred)", .count = 4, .seen = &p->intrinsics_set },
        { "--pose-w2c", SR_OPT_NUMBERS, p->pose_w2c, "16 NUMBERS", "world-to-camera pose, a row-major 4x4 in the file's frame; camera x right, y down, z forward", .count = 16, .seen = &p->w2c_set },
        { "--pose-c2w", SR_OPT_NUMBERS, p->pose_c2w, "16 NUMBERS", "camera-to-world pose, the inverse of --pose-w2c", .count = 16, .seen = &p->c2w_set },
        { "--view-depth", SR_OPT_STRING, &p->view_depth_path, "FILE.npy|.pfm", "z along the optical axis in mesh units, float32 (needs a pose)" },
        { "--range", SR_OPT_STRING, &p->range_path, "FILE.npy|.pfm", "distance from the camera centre, float32 (needs a pose)" },
        { "--face-ids", SR_OPT_STRING, &p->face_ids_path, "FILE.npy|.png", "triangle id + 1 per pixel, 0 where nothing: uint32 .npy or 16-bit PNG (needs a pose)" },
        { "--part-ids", SR_OPT_STRING, &p->part_ids_path, "FILE.npy|.png", "the file's mesh + 1 per pixel, 0 where nothing (needs a pose)" },
        { "--normals", SR_OPT_STRING, &p->normals_path, "FILE.npy", "unit normals in the camera frame, float32 HxWx3 (needs a pose)" },
        { "--normal-kind", SR_OPT_CHOICE, &p->normal_kind, "geometric|interpolated", "the triangle's normal, or the vertex normals interpolated (default geometric)", .choices = NORMAL_KIND_NAMES },
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
    const char *paths[OUTPUTS];
    output_paths(p, paths);
    for (int i = 0; i < OUTPUTS; i++)
        if (paths[i])
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
static const char *writer_extension(output_kind i, const char *path)
{
    for (int k = 0; k < 3 && OUTPUT_FORMATS[i].extensions[k]; k++)
        if (ends_with(path, OUTPUT_FORMATS[i].extensions[k]))
            return OUTPUT_FORMATS[i].extensions[k];
    return NULL;
}

bool sr_pinhole_setup_check(const sr_pinhole_setup *p, const sr_scene_setup *s, sr_error *err)
{
    if (p->w2c_set && p->c2w_set)
        return sr_error_set(err, "give one pose: --pose-w2c or --pose-c2w, not both");
    const char *paths[OUTPUTS];
    output_paths(p, paths);
    if (!sr_pinhole_setup_on(p)) {
        for (int i = 0; i < OUTPUTS; i++)
            if (paths[i])
                return sr_error_set(err, "%s needs a camera pose: --pose-w2c or --pose-c2w (16 numbers)",
                                    OUTPUT_FORMATS[i].option);
        if (p->intrinsics_set)
            return sr_error_set(err, "--intrinsics needs a camera pose: --pose-w2c or --pose-c2w (16 numbers)");
        return true;
    }
    if (s->eye_set || s->target_set || s->look_at_set)
        return sr_error_set(err, "a pose places the camera: --eye, --target, --up, --ortho, --rotate-y and "
                                 "--reversed-z are the look-at camera's");
    if (p->intrinsics_set && s->fov_set)
        return sr_error_set(err, "--intrinsics and --fov both give the field of view: give one");
    for (int i = 0; i < OUTPUTS; i++)
        if (paths[i] && !writer_extension((output_kind)i, paths[i]))
            return sr_error_set(err, "%s %s: no writer for this extension (%s%s%s)", OUTPUT_FORMATS[i].option,
                                paths[i], OUTPUT_FORMATS[i].extensions[0], OUTPUT_FORMATS[i].extensions[1] ? " or " : "",
                                OUTPUT_FORMATS[i].extensions[1] ? OUTPUT_FORMATS[i].extensions[1] : "");
    return true;
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
    double pose[4][4];
    memcpy(pose, p->c2w_set ? p->pose_c2w : p->pose_w2c, sizeof pose);
    if (p->c2w_set ? !sr_pinhole_pose_from_c2w(pose, cam->w2c, err) : (memcpy(cam->w2c, pose, sizeof pose), false))
        return false;
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

static bool write_output(output_kind i, const char *path, const void *values, int width, int height, sr_error *err)
{
    const char *ext = writer_extension(i, path);
    bool ids = i == OUT_FACE_IDS || i == OUT_PART_IDS;
    if (strcmp(ext, ".pfm") == 0) /* PFM's rows run bottom to top: the writer turns them */
        return sr_image_write_pfm(path, values, width, height, err);
    if (strcmp(ext, ".png") == 0)
        return write_ids_png(path, values, width, height, err);
    return sr_image_write_npy(path, values, ids ? SR_NPY_UINT32 : SR_NPY_FLOAT32, width, height,
                              i == OUT_NORMALS ? 3 : 1, err);
}

bool sr_pinhole_setup_write(const sr_pinhole_setup *p, const sr_pinhole *cam, const sr_mesh *mesh,
                            const sr_framebuffer *ids, sr_error *err)
{
    const char *paths[OUTPUTS];
    output_paths(p, paths);
    size_t n = (size_t)ids->width * (size_t)ids->height;
    void *values[OUTPUTS] = { 0 };
    bool ok = true;
    for (int i = 0; i < OUTPUTS; i++)
        if (paths[i] && !(values[i] = malloc(n * (i == OUT_NORMALS ? 3 : 1) * sizeof(float))))
            ok = false;
    if (!ok)
        sr_error_set(err, "out of memory for %dx%d outputs", ids->width, ids->height);
    sr_pinhole_outputs out = { .depth = values[OUT_DEPTH], .range = values[OUT_RANGE],
                               .face_ids = values[OUT_FACE_IDS], .part_ids = values[OUT_PART_IDS],
                               .normals = values[OUT_NORMALS], .interpolated_normals = p->normal_kind == 1,
                               .invalid = p->invalid ? NAN : 0.0f };
    ok = ok && sr_pinhole_resolve(cam, mesh, ids, &out, err);
    for (int i = 0; ok && i < OUTPUTS; i++)
        ok = !paths[i] || write_output((output_kind)i, paths[i], values[i], ids->width, ids->height, err);
    for (int i = 0; i < OUTPUTS; i++)
        free(values[i]);
    return ok;
}
