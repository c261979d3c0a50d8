/* 07_cull.h — stage 7: back-face culling on the snapped triangle.
 *
 * The signed area is computed exactly in 64-bit integers from the snapped
 * fixed-point vertices, after clipping, so facing is never decided from a
 * vertex with w <= 0. With y down, area2 > 0 means clockwise on screen, the
 * front face by default (Direct3D). Inline: it runs once per fan triangle,
 * and its few multiplications cost less than a call.
 */
#ifndef SOFTRAST_PIPELINE_CULL_H
#define SOFTRAST_PIPELINE_CULL_H

#include <stdbool.h>
#include <stdint.h>

#include "stages.h"

/* Twice the signed area in (1/256 px)^2; > 0 for clockwise on screen. */
static inline int64_t sr_cull_area2(const sr_screen_vertex *a, const sr_screen_vertex *b, const sr_screen_vertex *c)
{
    return (b->x - a->x) * (c->y - a->y) - (b->y - a->y) * (c->x - a->x);
}

/* True if a triangle of this signed area is drawn; zero area never is. */
static inline bool sr_cull_keeps(int64_t area2, sr_cull cull, sr_front front)
{
    if (area2 == 0)
        return false;
    bool clockwise = area2 > 0;
    bool is_front = (front == SR_FRONT_CW) == clockwise;
    switch (cull) {
    case SR_CULL_BACK:  return is_front;
    case SR_CULL_FRONT: return !is_front;
    case SR_CULL_NONE:  return true;
    }
    return true;
}

#endif
