/* pinhole_triangles.h — the triangles a pinhole view's pixels show, in
 * the camera frame, set up four at a time in lanes of double for the
 * resolve (pinhole_resolve.c): at a pixel a triangle (a dense mesh at a
 * vision user's size) each pixel's triangle is its own, and one at a time
 * their set-up was most of the resolve. Not public API. */
#ifndef SOFTRAST_SCENE_PINHOLE_TRIANGLES_H
#define SOFTRAST_SCENE_PINHOLE_TRIANGLES_H

#include <stdint.h>

#include "pinhole_frame.h"

/* Triangle `slot` in the camera frame: its corner v0, edges e1 = v1 − v0
 * and e2 = v2 − v0, their cross product e1 × e2, and what the outputs ask
 * of it: its unit normal on the file's front side (the same for every
 * pixel, so rounded once), its part, its vertex normals. `claim`: the
 * resolve's batch of triangles that last took this entry of its cache. */
typedef struct resolved_triangle {
    uint32_t slot, part;
    uint64_t claim;
    double v0[3], e1[3], e2[3], cross[3], cross_squared, offset; /* offset: cross · v0 */
    float front[3];
    double vertex_normals[3][3];
} resolved_triangle;

/* The geometry (v0 … offset) of the n triangles whose corners are the mesh
 * vertices corners[k], into *to[k]: each corner through to_camera, then
 * the edges, cross, cross · cross and cross · v0 as sr_dvec3_cross and
 * sr_dvec3_dot take them, lane by lane, so every width gives the bits of
 * the scalar operations. Four lanes: AVX2 registers, or SSE2 ones in pairs
 * (only where the CPU has AVX2 is the AVX2 one called). */
void sr_pinhole_triangles_sse2(const camera_frame *f, const float (*positions)[3], const uint32_t (*corners)[3],
                               resolved_triangle *const *to, uint32_t n);
void sr_pinhole_triangles_avx2(const camera_frame *f, const float (*positions)[3], const uint32_t (*corners)[3],
                               resolved_triangle *const *to, uint32_t n);

#endif
