/* softrast/flycam.h — a fly camera: a position, a heading and a pitch.
 *
 * Left-handed like the rest of softrast: yaw 0 looks along +z, a positive yaw
 * turns toward +x, a positive pitch looks up. Pitch stops just short of ±90°
 * so the look-at basis stays defined when looking straight up or down. No
 * collision: the camera flies through anything, which is the point.
 */
#ifndef SOFTRAST_FLYCAM_H
#define SOFTRAST_FLYCAM_H

#include <cglm/cglm.h>

#include "softrast_private.h"

#define SR_FLYCAM_MAX_PITCH 89.9f /* degrees */

typedef struct sr_flycam {
    vec3 position;
    float yaw, pitch; /* degrees */
} sr_flycam;

/* Position and heading that look from cam->eye toward cam->target. */
sr_flycam sr_flycam_from_camera(const sr_camera *cam);

/* The look direction, and the right and up of the camera's frame (unit). */
void sr_flycam_basis(const sr_flycam *fly, vec3 forward, vec3 right, vec3 up);

/* Moves by `amount` along forward, right and world up. */
void sr_flycam_move(sr_flycam *fly, float forward, float right, float up);

/* Turns by degrees; pitch is clamped to ±SR_FLYCAM_MAX_PITCH, yaw wraps. */
void sr_flycam_turn(sr_flycam *fly, float yaw_deg, float pitch_deg);

/* Writes eye, target (one unit ahead) and up into cam; keeps fov/near/far. */
void sr_flycam_apply(const sr_flycam *fly, sr_camera *cam);

#endif
