/* transforms.h — camera datasets in the transforms.json convention of NeRF,
 * instant-ngp and nerfstudio: read the cameras of its frames, write the
 * file that describes what was rendered for them.
 *
 * The camera: fl_x, fl_y, cx, cy, w, h at the top level or per frame (a
 * frame's own override the top's), or camera_angle_x (and
 * camera_angle_y) with w and h; cx and cy measure from the top-left
 * pixel's corner (its centre is at 0.5, 0.5), as those tools cast rays
 * through pixel centres i + 0.5. Per frame, transform_matrix is
 * camera-to-world with OpenGL's camera axes (x right, y up, z backward).
 */
#ifndef SOFTRAST_APP_TRANSFORMS_H
#define SOFTRAST_APP_TRANSFORMS_H

#include <stdbool.h>

#include "softrast_private.h"

/* The largest file read, and the most frames. */
#define SR_TRANSFORMS_MAX_BYTES (256u << 20)
#define SR_TRANSFORMS_MAX_FRAMES 1000000

typedef struct sr_transforms sr_transforms; /* the parsed file, kept to write it back */

/* Reads path; false, with one line naming the file (and the frame) for a
 * file that is not JSON, lacks a field, or holds a number that is not
 * finite. */
bool sr_transforms_read(const char *path, sr_transforms **out, sr_error *err);
void sr_transforms_free(sr_transforms *t);

int sr_transforms_count(const sr_transforms *t);

/* Frame i's camera in OpenCV's convention (softrast.h, sr_pinhole; near and
 * far 0) and its size; false, with one line naming the frame, when its
 * pose is not rigid. */
bool sr_transforms_camera(const sr_transforms *t, int i, sr_pinhole *cam, int size[2], sr_error *err);

/* The outputs a frame gets, by their transforms.json key ("file_path",
 * "depth_file_path", ...): sets frame i's key to `relative` (a path from the
 * written file's folder). */
bool sr_transforms_set_path(sr_transforms *t, int i, const char *key, const char *relative, sr_error *err);

/* Writes the frames, with their paths, to path (safely: a temporary file
 * renamed into place). Other keys are kept as they were. */
bool sr_transforms_write(const sr_transforms *t, const char *path, sr_error *err);

#endif
