/* pinhole_frame.h — a mesh's points in a pinhole camera's frame, in
 * double: for the clip planes' fit (pinhole.c) and the resolve
 * (pinhole_resolve.c). Not public API. */
#ifndef SOFTRAST_SCENE_PINHOLE_FRAME_H
#define SOFTRAST_SCENE_PINHOLE_FRAME_H

#include <stdbool.h>

#include "softrast/softrast.h"

/* Two lanes of doubles, SSE2's (and every 64-bit x86's): each lane rounds
 * as its scalar does, with the same operations in the same order. */
typedef double camera_v2 __attribute__((vector_size(16)));

/* How a mesh's points reach the camera frame: the pose's rows 0 and 1
 * column by column, a lane each, and row 2; the mesh's origin; whether
 * the loader negated the file's z. Loaded once, not per point. */
typedef struct camera_frame {
    camera_v2 rows01[4];
    double row2[4];
    camera_v2 origin01;
    double origin2;
    bool z_negated;
} camera_frame;

static inline camera_frame camera_frame_of(const sr_pinhole *cam, const sr_mesh *mesh)
{
    camera_frame f = { .origin01 = { mesh->origin[0], mesh->origin[1] }, .origin2 = mesh->origin[2],
                       .z_negated = mesh->z_negated };
    for (int c = 0; c < 4; c++) {
        f.rows01[c] = (camera_v2){ cam->w2c[0][c], cam->w2c[1][c] };
        f.row2[c] = cam->w2c[2][c];
    }
    return f;
}

/* A point of the mesh (its vertex, or a corner of its bounds, relative to
 * its origin) in the camera frame, in double: each row's dot product
 * summed left to right, rows 0 and 1 in two lanes. */
static inline void to_camera(const camera_frame *f, const float p[3], double out[3])
{
    camera_v2 file01 = f->origin01 + (camera_v2){ p[0], p[1] };
    double z = f->origin2 + p[2];
    z = f->z_negated ? -z : z;
    camera_v2 out01 = f->rows01[0] * file01[0] + f->rows01[1] * file01[1] + f->rows01[2] * z + f->rows01[3];
    out[0] = out01[0];
    out[1] = out01[1];
    out[2] = f->row2[0] * file01[0] + f->row2[1] * file01[1] + f->row2[2] * z + f->row2[3];
}

#endif
