/* view_script.h — scripted camera flights for `softrast view --script`.
 *
 * A script is text, one key frame per line: twelve numbers
 *     eye_x eye_y eye_z  target_x target_y target_z  up_x up_y up_z  fov near far
 * separated by spaces or commas; '#' starts a comment, blank lines are
 * skipped. Frame i of N sits at key position i·(K−1)/(N−1) and interpolates
 * every number linearly between the two keys around it.
 */
#ifndef SOFTRAST_APP_VIEW_SCRIPT_H
#define SOFTRAST_APP_VIEW_SCRIPT_H

#include <stdbool.h>

#include "softrast/camera.h"
#include "softrast/error.h"

#define SR_SCRIPT_NUMBERS 12
#define SR_SCRIPT_MAX_KEYS 100000

typedef struct sr_script {
    int count;
    float (*keys)[SR_SCRIPT_NUMBERS];
} sr_script;

bool sr_script_load(sr_script *s, const char *path, sr_error *err);
void sr_script_free(sr_script *s);

/* The camera of frame `frame` of `frames` (perspective). */
void sr_script_camera(const sr_script *s, int frame, int frames, sr_camera *cam);

#endif
