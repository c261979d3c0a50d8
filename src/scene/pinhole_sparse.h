/* pinhole_sparse.h — the point of a point or line primitive that a
 * pinhole pixel sees, for the resolve of its outputs (pinhole_resolve.c):
 * a ray meets a line only by chance, so a pixel showing one takes the
 * segment's point nearest its ray, clamped to the part drawn. Not public
 * API. */
#ifndef SOFTRAST_SCENE_PINHOLE_SPARSE_H
#define SOFTRAST_SCENE_PINHOLE_SPARSE_H

#include <stdbool.h>
#include <stdint.h>

#include "pinhole_frame.h"

/* A point or a line seen at a pixel: the primitive's point nearest the
 * pixel's ray, in the camera frame, and where it lies between the line's
 * ends idx (t, 0 for a point, whose vertex both name). */
typedef struct sr_seen_point {
    double p[3], t;
    uint32_t idx[2];
} sr_seen_point;

/* Point or line `slot` of mesh (a point list, or a line list or strip)
 * seen along the ray (ray_x, ray_y, 1) of a camera whose frame for mesh
 * is `frame` (camera_frame_of): a point is its vertex; a line, the point
 * of the part of it between cam's clip planes nearest the ray, found
 * from its nearer end. False where the primitive names a vertex the mesh
 * lacks. */
bool sr_pinhole_seen_point(const sr_pinhole *cam, const camera_frame *frame, const sr_mesh *mesh, uint32_t slot,
                           double ray_x, double ray_y, sr_seen_point *sp);

#endif
