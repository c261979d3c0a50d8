/* The pinhole camera's options and outputs (pinhole_setup.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "pinhole_setup.h"

static const char *const INVALID_NAMES[] = { "zero", "nan", NULL };

void sr_pinhole_setup_options(sr_pinhole_setup *p, sr_option *table)
{
    const sr_option entries[] = {
        { "--intrinsics", SR_OPT_NUMBERS, p->intrinsics, "FX,FY,CX,CY", "pinhole intrinsics in pixels, OpenCV's (the top-left pixel's centre is 0,0; default: --fov, centred)", .count = 4, .seen = &p->intrinsics_set },
        { "--pose-w2c", SR_OPT_NUMBERS, p->pose_w2c, "16 NUMBERS", "world-to-camera pose, a row-major 4x4 in the file's frame; camera x right, y down, z forward", .count = 16, .seen = &p->w2c_set },
        { "--pose-c2w", SR_OPT_NUMBERS, p->pose_c2w, "16 NUMBERS", "camera-to-world pose, the inverse of --pose-w2c", .count = 16, .seen = &p->c2w_set },
        { "--view-depth", SR_OPT_STRING, &p->view_depth_path, "FILE.npy|.pfm", "z along the optical axis in mesh units, float32 (needs a pose)" },
        { "--range", SR_OPT_STRING, &p->range_path, "FILE.npy|.pfm", "distance from the camera centre, float32 (needs a pose)" },
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
    return p->view_depth_path || p->range_path;
}

/* The writer a metric output's name asks for: ".npy" or ".pfm", or NULL. */
static const char *extension(const char *path)
{
    const char *dot = strrchr(path, '.');
    if (dot && (strcasecmp(dot, ".npy") == 0 || strcasecmp(dot, ".pfm") == 0))
        return dot;
    return NULL;
}

bool sr_pinhole_setup_check(const sr_pinhole_setup *p, const sr_scene_setup *s, sr_error *err)
{
    if (p->w2c_set && p->c2w_set)
        return sr_error_set(err, "give one pose: --pose-w2c or --pose-c2w, not both");
    if (!sr_pinhole_setup_on(p)) {
        if (p->intrinsics_set || sr_pinhole_setup_wants_depth(p))
            return sr_error_set(err, "%s needs a camera pose: --pose-w2c or --pose-c2w (16 numbers)",
                                p->intrinsics_set ? "--intrinsics" : p->view_depth_path ? "--view-depth" : "--range");
        return true;
    }
    if (s->eye_set || s->target_set || s->look_at_set)
        return sr_error_set(err, "a pose places the camera: --eye, --target, --up, --ortho, --rotate-y and "
                                 "--reversed-z are the look-at camera's");
    if (p->intrinsics_set && s->fov_set)
        return sr_error_set(err, "--intrinsics and --fov both give the field of view: give one");
    const char *outputs[] = { p->view_depth_path, p->range_path };
    for (int i = 0; i < 2; i++)
        if (outputs[i] && !extension(outputs[i]))
            return sr_error_set(err, "%s: no writer for this extension (view depth and range: .npy or .pfm)",
                                outputs[i]);
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

static bool write_floats(const char *path, const float *v, int width, int height, sr_error *err)
{
    if (strcasecmp(extension(path), ".npy") == 0)
        return sr_image_write_npy(path, v, width, height, err);
    /* PFM's rows run bottom to top: the writer takes them top down. */
    return sr_image_write_pfm(path, v, width, height, err);
}

bool sr_pinhole_setup_write(const sr_pinhole_setup *p, const sr_pinhole *cam, const sr_mesh *mesh,
                            const sr_framebuffer *ids, sr_error *err)
{
    size_t n = (size_t)ids->width * (size_t)ids->height;
    float *depth = p->view_depth_path ? malloc(n * sizeof *depth) : NULL;
    float *range = p->range_path ? malloc(n * sizeof *range) : NULL;
    bool ok = (!p->view_depth_path || depth) && (!p->range_path || range);
    if (!ok)
        sr_error_set(err, "out of memory for %dx%d view depth", ids->width, ids->height);
    ok = ok && sr_pinhole_depth(cam, mesh, ids, p->invalid ? NAN : 0.0f, depth, range, err) &&
         (!depth || write_floats(p->view_depth_path, depth, ids->width, ids->height, err)) &&
         (!range || write_floats(p->range_path, range, ids->width, ids->height, err));
    free(depth);
    free(range);
    return ok;
}
