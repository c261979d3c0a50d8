/* Camera datasets rendered frame by frame (dataset.h). */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dataset.h"
#include "io/output_file.h"
#include "transforms.h"

/* The frame numbers' digits in file names, at least; more for a dataset
 * whose last frame needs them, so the files list in frame order. */
#define FRAME_DIGITS 5

static int frame_digits(int count)
{
    int digits = 1;
    for (int n = count - 1; n >= 10; n /= 10)
        digits++;
    return digits > FRAME_DIGITS ? digits : FRAME_DIGITS;
}

bool sr_dataset_check(const sr_dataset_job *d, const sr_pinhole_setup *p, const sr_scene_setup *s,
                      const char *const *single, sr_error *err)
{
    if (!d->poses_path)
        return d->out_dir ? sr_error_set(err, "--out-dir goes with --poses transforms.json") : true;
    if (!d->out_dir)
        return sr_error_set(err, "--poses needs --out-dir DIR, the folder of the frames' files");
    if (p->w2c_set || p->c2w_set || p->intrinsics_set)
        return sr_error_set(err, "--poses gives every frame's camera: --pose-w2c, --pose-c2w and --intrinsics "
                                 "are a single image's");
    if (s->eye_set || s->target_set || s->look_at_set || s->fov_set)
        return sr_error_set(err, "--poses gives every frame's camera: --eye, --target, --up, --fov, --ortho, "
                                 "--rotate-y, --up-axis and --reversed-z are the look-at camera's");
    if (single && *single)
        return sr_error_set(err, "%s is a single image's: a dataset's outputs are --out, --view-depth, --range, "
                                 "--face-ids, --part-ids and --normals",
                            *single);
    const char *names[1 + SR_MEASURED_COUNT] = { d->color_name };
    memcpy(names + 1, p->paths, sizeof p->paths);
    for (int i = 0; i < 1 + SR_MEASURED_COUNT; i++)
        if (names[i] && (strchr(names[i], '/') || !strrchr(names[i], '.') || names[i][0] == '.'))
            return sr_error_set(err, "%s: with --poses an output is a name and an extension, NAME.EXT, without a "
                                     "folder: frame i goes to DIR/NAME/frame_%0*d.EXT",
                                names[i], FRAME_DIGITS, 0);
    return sr_pinhole_setup_check_outputs(p, err);
}

/* NAME.EXT's folder DIR/NAME, and frame i's file in it, relative to DIR
 * (rel) and whole (path). */
static bool frame_file(const char *dir, const char *name, int frame, int digits, char rel[PATH_MAX],
                       char path[PATH_MAX], sr_error *err)
{
    const char *dot = strrchr(name, '.');
    int n = snprintf(rel, PATH_MAX, "%.*s/frame_%0*d%s", (int)(dot - name), name, digits, frame, dot);
    int m = snprintf(path, PATH_MAX, "%s/%s", dir, rel);
    return (n < PATH_MAX && m < PATH_MAX) || sr_error_set(err, "%s/%s: path too long", dir, name);
}

/* The folders of the outputs asked for. */
static bool make_output_dirs(const sr_dataset_job *d, const char *const *names, sr_error *err)
{
    if (!sr_output_make_dir(d->out_dir, err))
        return false;
    for (int i = 0; i < 1 + SR_MEASURED_COUNT; i++) {
        if (!names[i])
            continue;
        char folder[PATH_MAX];
        const char *dot = strrchr(names[i], '.');
        if (snprintf(folder, sizeof folder, "%s/%.*s", d->out_dir, (int)(dot - names[i]), names[i]) >=
                (int)sizeof folder ||
            !sr_output_make_dir(folder, err))
            return false;
    }
    return true;
}

/* The scene's size: --size, which must match every frame's, or the first
 * frame's. */
static bool dataset_size(const sr_transforms *t, const sr_dataset_job *d, sr_scene_setup *s, sr_error *err)
{
    for (int i = 0; i < sr_transforms_count(t); i++) {
        sr_pinhole cam;
        int size[2];
        if (!sr_transforms_camera(t, i, &cam, size, err))
            return false;
        if (i == 0 && !s->size_set)
            memcpy(s->size, size, sizeof size);
        if (size[0] != s->size[0] || size[1] != s->size[1])
            return sr_error_set(err, "%s: frame %d is %dx%d, not %dx%d%s: one size a dataset", d->poses_path, i,
                                size[0], size[1], s->size[0], s->size[1], s->size_set ? " (--size)" : "");
    }
    return true;
}

/* Frame i: its camera, its draw (color and ids, the file's BLEND parts
 * blended over the rest as `render` draws them: sr_draw_layered), its files. */
static bool render_frame(const sr_dataset_job *d, const sr_pinhole_setup *p, const sr_scene_setup *s,
                         const sr_transforms *t, int i, sr_scene *scene, sr_error *err)
{
    sr_pinhole cam;
    int size[2], digits = frame_digits(sr_transforms_count(t));
    sr_draw_desc desc;
    sr_draw_study study;
    if (!sr_transforms_camera(t, i, &cam, size, err) || !sr_pinhole_setup_clip(s, &scene->mesh, &cam, err) ||
        !sr_scene_desc(s, scene, &desc, &study, err))
        return false;
    sr_pinhole_setup_desc(s, &cam, scene, d->color_name != NULL, &desc);
    desc.clear = true;
    char rel[PATH_MAX], path[PATH_MAX];
    if (!sr_draw_layered(&scene->fb, &desc, NULL, err) ||
        (d->color_name && !(frame_file(d->out_dir, d->color_name, i, digits, rel, path, err) &&
                            sr_image_write_png(path, scene->fb.color, scene->fb.width, scene->fb.height, err))))
        return false;
    sr_pinhole_setup frame = *p;
    char paths[SR_MEASURED_COUNT][PATH_MAX];
    for (int k = 0; k < SR_MEASURED_COUNT; k++)
        if (p->paths[k]) {
            if (!frame_file(d->out_dir, p->paths[k], i, digits, rel, paths[k], err))
                return false;
            frame.paths[k] = paths[k];
        }
    double resolve_ms;
    return sr_pinhole_setup_write(&frame, &cam, scene, &desc, &resolve_ms, err);
}

/* Every frame's keys, its range's or not, and the file into DIR. */
static bool write_transforms(const sr_dataset_job *d, const sr_pinhole_setup *p, sr_transforms *t, sr_error *err)
{
    static const char *const COLOR_KEY = "file_path";
    char rel[PATH_MAX], path[PATH_MAX];
    int digits = frame_digits(sr_transforms_count(t));
    for (int i = 0; i < sr_transforms_count(t); i++) {
        if (d->color_name && !(frame_file(d->out_dir, d->color_name, i, digits, rel, path, err) &&
                               sr_transforms_set_path(t, i, COLOR_KEY, rel, err)))
            return false;
        for (int k = 0; k < SR_MEASURED_COUNT; k++)
            if (p->paths[k] && !(frame_file(d->out_dir, p->paths[k], i, digits, rel, path, err) &&
                                 sr_transforms_set_path(t, i, sr_measured_key((sr_measured)k), rel, err)))
                return false;
    }
    if (snprintf(path, sizeof path, "%s/transforms.json", d->out_dir) >= (int)sizeof path)
        return sr_error_set(err, "%s: path too long", d->out_dir);
    return sr_transforms_write(t, path, err);
}

bool sr_dataset_render(const sr_dataset_job *d, const sr_pinhole_setup *p, sr_scene_setup *s, sr_scene *scene,
                       sr_error *err)
{
    sr_transforms *t;
    if (!sr_transforms_read(d->poses_path, &t, err))
        return false;
    int count = sr_transforms_count(t), first = d->range_set ? d->range[0] : 0,
        end = d->range_set ? d->range[1] : count;
    const char *names[1 + SR_MEASURED_COUNT] = { d->color_name };
    memcpy(names + 1, p->paths, sizeof p->paths);
    bool ok = end <= count || sr_error_set(err, "--frame-range %d:%d ends past the %d frames of %s (B is at most %d)",
                                            first, end, count, d->poses_path, count);
    ok = ok && dataset_size(t, d, s, err) && sr_scene_load(s, false, scene, err) &&
         sr_pinhole_setup_ids(p, scene, err) && make_output_dirs(d, names, err);
    bool progress = isatty(STDERR_FILENO);
    for (int i = first; ok && i < end; i++) {
        ok = render_frame(d, p, s, t, i, scene, err);
        if (progress)
            fprintf(stderr, "\rsoftrast: frame %d of %d (%d to %d)", i + 1 - first, end - first, first, end - 1);
    }
    if (progress)
        fputc('\n', stderr);
    ok = ok && write_transforms(d, p, t, err);
    sr_transforms_free(t);
    return ok;
}
