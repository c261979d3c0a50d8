/* softrast/camera.h — a look-at camera and its projection (cglm underneath).
 *
 * Left-handed (+x right, +y up, +z forward): view = glm_lookat_lh, projection
 * = glm_perspective_lh_zo (vertical fov) or glm_ortho_lh_zo, mapping view
 * depth near → z_ndc 0 and far → 1. Two variants keep the clip volume
 * 0 ≤ z ≤ w and change only the z row: reversed_z maps near → 1 and far → 0
 * (draw into a reversed_z framebuffer), and far = +inf (perspective only)
 * puts the far plane at infinity (z_ndc = 1 − n/d, or n/d reversed), both
 * computed directly rather than by rounding 1 − f/(f − n). sr_camera_check
 * rejects what no matrix can be built from, with one line in err.
 *
 * eye and target are float and relative to the camera's double `origin`
 * (world point = origin + eye; zero, the default, makes them absolute), so
 * a camera 1e7 from the world origin still moves in small steps: put the
 * origin at or near the eye. sr_camera_view_d gives the view in double for
 * sr_draw_desc.view_d, where it cancels a mesh's origin (docs/precision.md);
 * sr_camera_view is the same matrix rounded to float.
 */
#ifndef SOFTRAST_CAMERA_H
#define SOFTRAST_CAMERA_H

#include <stdbool.h>
#include <cglm/cglm.h>

#include "dmat4.h"
#include "error.h"

#define SR_CAMERA_FOV 60.0f
#define SR_CAMERA_NEAR 0.1f
#define SR_CAMERA_FAR 100.0f

typedef struct sr_camera {
    double origin[3];   /* eye and target are relative to it */
    vec3 eye, target, up;
    float fov_deg;      /* vertical */
    float near, far;
    float ortho_height; /* > 0: orthographic with this view height */
    bool reversed_z;    /* near → z_ndc 1, far → 0 */
} sr_camera;

/* Defaults: at -z looking at the origin, up +y, 60°, near 0.1, far 100. */
sr_camera sr_camera_default(void);

/* Points the camera from -z at the centre of [lo, hi] (relative to the
 * camera's origin, as eye and target are), far enough back that the
 * bounding sphere fits the vertical and horizontal fov. */
void sr_camera_frame_bounds(sr_camera *cam, const vec3 lo, const vec3 hi, float aspect);

bool sr_camera_check(const sr_camera *cam, sr_error *err);
void sr_camera_view(const sr_camera *cam, mat4 out);
/* look-at from eye to target, after a translation by -origin, in double. */
void sr_camera_view_d(const sr_camera *cam, sr_dmat4 *out);
void sr_camera_projection(const sr_camera *cam, float aspect, mat4 out);

/* The view-space distance along the view axis of a point stored with depth
 * z_ndc (inverts the projection: n·f / (f − z·(f − n)) for perspective,
 * n + z·(f − n) for orthographic, with z → 1 − z when reversed).
 * ctx is the sr_camera; fits sr_depth_map. */
double sr_camera_view_distance(float z_ndc, const void *camera);

#endif
