/* softrast truth — the truth image of a mesh (src/studies/truth.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "scene_setup.h"
#include "studies/truth.h"

typedef struct truth_job {
    sr_scene_setup scene;
    const char *ids_path, *depth_path;
} truth_job;

static const char USAGE[] =
    "usage: softrast truth MESH [options]\n"
    "For each pixel centre, the triangle exact arithmetic says is nearest and its exact\n"
    "z_ndc, with render's camera and conventions (pixel centres, top-left rule, culling,\n"
    "depth LESS, near and far planes). Perspective cameras only.";

/* What the truth image does not depend on. */
static const char *const IGNORED[] = { "--ortho", "--shade", "--texture", "--filter", "--color-space", "--threads", "--simd",
                                       NULL };

static bool parse_job(void *j, int argc, char **argv, bool *help, sr_error *err)
{
    truth_job *job = j;
    const sr_option own[] = {
        { "--out-ids", SR_OPT_STRING, &job->ids_path, "FILE.png", "write the nearest triangle's id + 1 as 0xRRGGBB (0: none)" },
        { "--out-depth", SR_OPT_STRING, &job->depth_path, "FILE.pfm", "write its z_ndc as float32 (the clear value where none)" },
        { 0 },
    };
    if (!sr_scene_setup_parse(&job->scene, own, IGNORED, USAGE, argc, argv, help, err))
        return false;
    if (!*help && !job->scene.mesh_path)
        return sr_error_set(err, "truth needs one MESH (see softrast truth --help)");
    return true;
}

static bool write_outputs(const truth_job *job, const sr_truth_image *t, const mat4 projection, sr_error *err)
{
    size_t n = (size_t)t->width * t->height;
    float *depth = job->depth_path ? malloc(n * sizeof *depth) : NULL;
    if (job->depth_path && !depth)
        return sr_error_set(err, "out of memory for the truth's depth");
    for (size_t i = 0; depth && i < n; i++)
        depth[i] = (float)sr_truth_z_ndc(projection, t->distance[i]);
    bool ok = (!job->ids_path || sr_image_write_png(job->ids_path, t->ids, t->width, t->height, err)) &&
              (!depth || sr_image_write_pfm(job->depth_path, depth, t->width, t->height, err));
    free(depth);
    return ok;
}

static bool run(void *j, sr_scene *scene, sr_error *err)
{
    truth_job *job = j;
    sr_draw_desc desc;
    sr_draw_study study;
    sr_truth_image truth;
    job->scene.shade = SR_SHADE_ID; /* loads the mesh alone */
    if (!sr_scene_load(&job->scene, false, scene, err))
        return false;
    sr_scene_frame_camera(&job->scene, scene);
    if (!sr_scene_desc(&job->scene, scene, &desc, &study, err) ||
        !sr_truth_render(&desc, scene->fb.width, scene->fb.height, &truth, err))
        return false;
    bool ok = write_outputs(job, &truth, desc.projection, err);
    sr_truth_image_free(&truth);
    return ok;
}

int sr_app_truth(int argc, char **argv)
{
    truth_job job = { 0 };
    sr_scene_setup_defaults(&job.scene);
    return sr_app_command_run(&(sr_app_command){ parse_job, run }, &job, argc, argv);
}
