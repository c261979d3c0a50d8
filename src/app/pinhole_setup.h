/* pinhole_setup.h — `render`'s pinhole camera (--intrinsics, --pose-w2c,
 * --pose-c2w) and the outputs measured from it (--view-depth, --range,
 * --face-ids, --face-ids-of, --part-ids, --normals):
 * the options, their checks against the look-at camera's, the camera, and
 * the files. */
#ifndef SOFTRAST_APP_PINHOLE_SETUP_H
#define SOFTRAST_APP_PINHOLE_SETUP_H

#include "scene_setup.h"

#define SR_PINHOLE_OPTION_COUNT 12

/* --depth-scale's default: millimetres of metres. */
#define SR_DEPTH_PNG_SCALE 1000.0f

/* The outputs measured from the camera. */
typedef enum sr_measured {
    SR_MEASURED_DEPTH,
    SR_MEASURED_RANGE,
    SR_MEASURED_FACE_IDS,
    SR_MEASURED_PART_IDS,
    SR_MEASURED_NORMALS,
    SR_MEASURED_COUNT
} sr_measured;

/* An output's option ("--view-depth") and its key in a transforms.json
 * frame ("depth_file_path"). */
const char *sr_measured_option(sr_measured k);
const char *sr_measured_key(sr_measured k);

typedef struct sr_pinhole_setup {
    double intrinsics[4];               /* fx, fy, cx, cy */
    double pose_w2c[16], pose_c2w[16];  /* row-major */
    bool intrinsics_set, w2c_set, c2w_set, face_ids_of_set;
    const char *paths[SR_MEASURED_COUNT]; /* NULL: not asked for */
    int invalid;     /* 0: 0 where nothing is drawn, 1: NaN */
    float depth_scale; /* .png depth and range: uint16 of the value times this */
    int normal_kind; /* 0: the triangle's, 1: the vertex normals interpolated */
    int face_ids_of; /* 0: --face-ids names triangles, 1: the file's faces */
} sr_pinhole_setup;

/* The options' table entries, SR_PINHOLE_OPTION_COUNT of them, into table. */
void sr_pinhole_setup_options(sr_pinhole_setup *p, sr_option *table);

/* Whether a pose was given: the pinhole path. */
bool sr_pinhole_setup_on(const sr_pinhole_setup *p);

/* The options' checks once parsed: one pose, no look-at option beside it,
 * outputs with a writer's extension and a pose to measure from. */
bool sr_pinhole_setup_check(const sr_pinhole_setup *p, const sr_scene_setup *s, sr_error *err);

/* The outputs' extensions against the writers'. */
bool sr_pinhole_setup_check_outputs(const sr_pinhole_setup *p, sr_error *err);

/* The camera of the options at s's size for the mesh: intrinsics as given
 * or from --fov, centred; near and far as given or fitted. */
bool sr_pinhole_setup_camera(const sr_pinhole_setup *p, const sr_scene_setup *s, const sr_mesh *mesh,
                             sr_pinhole *cam, sr_error *err);

/* cam's clip planes: --near and --far where given, else fitted to the
 * mesh; false, with one line, for a camera sr_pinhole_check refuses. */
bool sr_pinhole_setup_clip(const sr_scene_setup *s, const sr_mesh *mesh, sr_pinhole *cam, sr_error *err);

/* Whether any of the outputs measured from the pinhole camera was asked for. */
bool sr_pinhole_setup_wants_depth(const sr_pinhole_setup *p);

/* desc (sr_scene_desc's) for cam at the framebuffer's size: its matrices,
 * the framebuffer reversed z as they are, and culling off unless --cull
 * asked for it (a ray caster sees both faces, and scans are not always
 * wound one way). When the draw's colour is not used (color_used: the
 * image is written, or points or lines are drawn) and no --shade was
 * asked, shaded in ids, the cheapest mode, as Python's render without a
 * colour output is: the measured outputs then depend on the geometry
 * alone, not on attributes a shading would read (docs/cli.md). */
void sr_pinhole_setup_desc(const sr_scene_setup *s, const sr_pinhole *cam, sr_scene *scene, bool color_used,
                           sr_draw_desc *desc);

/* Gives the scene's framebuffer an ids plane where outputs are asked for:
 * then the draw that makes the color image also says what each pixel
 * shows, and no second draw is needed. */
bool sr_pinhole_setup_ids(const sr_pinhole_setup *p, sr_scene *scene, sr_error *err);

/* The outputs asked for, resolved on desc's threads from the frame just
 * drawn with desc into the framebuffer and its ids plane
 * (sr_pinhole_setup_ids); *resolve_ms is the resolve's time, files aside
 * (0 when nothing was asked for). */
bool sr_pinhole_setup_write(const sr_pinhole_setup *p, const sr_pinhole *cam, sr_scene *scene,
                            const sr_draw_desc *desc, double *resolve_ms, sr_error *err);

#endif
