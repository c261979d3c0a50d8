/* dataset.h — `render MESH --poses transforms.json --out-dir DIR`: every
 * frame of a camera dataset rendered with the mesh loaded once and the
 * workspace reused, each output into a folder of DIR named after it, and
 * DIR/transforms.json describing them.
 *
 * An output option names a file without a folder, NAME.EXT: frame i goes
 * to DIR/NAME/frame_IIIII.EXT (five digits at least) and its path, from
 * DIR, into the frame's key: file_path (--out), depth_file_path
 * (--view-depth), range_file_path, face_ids_file_path, part_ids_file_path,
 * normals_file_path. Every run writes the whole transforms.json, the paths
 * of frames outside its --frame-range too (they are known without
 * rendering them), so shards of one dataset write the same file and their
 * folders' union is one run's. */
#ifndef SOFTRAST_APP_DATASET_H
#define SOFTRAST_APP_DATASET_H

#include "pinhole_setup.h"
#include "scene_setup.h"

typedef struct sr_dataset_job {
    const char *poses_path, *out_dir;
    const char *color_name; /* --out, or NULL */
    int range[2];           /* --frame-range: frames [A, B) */
    bool range_set;
} sr_dataset_job;

/* Checks the options beside --poses: an --out-dir, outputs named without a
 * folder, no pose or look-at option, none of `single` (the names of the
 * single image's outputs that were given, NULL-terminated). */
bool sr_dataset_check(const sr_dataset_job *d, const sr_pinhole_setup *p, const sr_scene_setup *s,
                      const char *const *single, sr_error *err);

/* Reads the poses, loads the scene at their size (or --size, which must
 * match every frame's w and h), renders frames [A, B) (all by default)
 * and writes DIR/transforms.json. A progress line on a terminal. */
bool sr_dataset_render(const sr_dataset_job *d, const sr_pinhole_setup *p, sr_scene_setup *s, sr_scene *scene,
                       sr_error *err);

#endif
