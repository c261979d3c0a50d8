/* pinhole_setup.h — `render`'s pinhole camera (--intrinsics, --pose-w2c,
 * --pose-c2w) and the outputs measured from it (--view-depth, --range,
 * --face-ids, --part-ids, --normals):
 * the options, their checks against the look-at camera's, the camera, and
 * the files. */
#ifndef SOFTRAST_APP_PINHOLE_SETUP_H
#define SOFTRAST_APP_PINHOLE_SETUP_H

#include "scene_setup.h"

#define SR_PINHOLE_OPTION_COUNT 10

typedef struct sr_pinhole_setup {
    double intrinsics[4];               /* fx, fy, cx, cy */
    double pose_w2c[16], pose_c2w[16];  /* row-major */
    bool intrinsics_set, w2c_set, c2w_set;
    const char *view_depth_path, *range_path, *face_ids_path, *part_ids_path, *normals_path;
    int invalid;     /* 0: 0 where nothing is drawn, 1: NaN */
    int normal_kind; /* 0: the triangle's, 1: the vertex normals interpolated */
} sr_pinhole_setup;

/* The options' table entries, SR_PINHOLE_OPTION_COUNT of them, into table. */
void sr_pinhole_setup_options(sr_pinhole_setup *p, sr_option *table);

/* Whether a pose was given: the pinhole path. */
bool sr_pinhole_setup_on(const sr_pinhole_setup *p);

/* The options' checks once parsed: one pose, no look-at option beside it,
 * outputs with a writer's extension and a pose to measure from. */
bool sr_pinhole_setup_check(const sr_pinhole_setup *p, const sr_scene_setup *s, sr_error *err);

/* The camera of the options at s's size for the mesh: intrinsics as given
 * or from --fov, centred; near and far as given or fitted. */
bool sr_pinhole_setup_camera(const sr_pinhole_setup *p, const sr_scene_setup *s, const sr_mesh *mesh,
                             sr_pinhole *cam, sr_error *err);

/* Whether any of the outputs measured from the pinhole camera was asked for. */
bool sr_pinhole_setup_wants_depth(const sr_pinhole_setup *p);

/* View depth, range, ids and normals from ids (an SR_SHADE_ID draw with
 * cam), written to the files asked for. */
bool sr_pinhole_setup_write(const sr_pinhole_setup *p, const sr_pinhole *cam, const sr_mesh *mesh,
                            const sr_framebuffer *ids, sr_error *err);

#endif
