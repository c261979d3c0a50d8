/* flight.h — scripted camera flights for `softrast view --script`.
 *
 * A script is text, one key frame per line: twelve numbers
 *     eye_x eye_y eye_z  target_x target_y target_z  up_x up_y up_z  fov near far
 * separated by spaces or commas; '#' starts a comment, blank lines are
 * skipped. far may be inf (an infinite far plane, as --far inf). Frame i of
 * N sits at key position i·(K−1)/(N−1) and interpolates every number
 * linearly between the two keys around it; a far of inf on either key is
 * inf between them.
 */
#ifndef SOFTRAST_SCENE_FLIGHT_H
#define SOFTRAST_SCENE_FLIGHT_H

#include <stdbool.h>

#include "softrast/softrast.h"
#include "softrast/softrast.h"

#define SR_FLIGHT_NUMBERS 12
#define SR_FLIGHT_MAX_KEYS 100000

typedef struct sr_flight {
    int count;
    float (*keys)[SR_FLIGHT_NUMBERS];
} sr_flight;

bool sr_flight_load(sr_flight *s, const char *path, sr_error *err);
void sr_flight_free(sr_flight *s);

/* The camera of frame `frame` of `frames` (perspective). */
void sr_flight_camera(const sr_flight *s, int frame, int frames, sr_camera *cam);

#endif
