/* tests/case_oracle.h — what test_cases.c compares a case's draw against.
 *
 * case_clip_run runs stages 1 to 4 itself, mirroring src/draw/draw.c
 * and primitives.c (one thread, default accuracy knobs) through the public
 * stage headers (01_vertex.h, 02_assemble.h, clip.h, 06_viewport.h), and
 * measures the clipper's output: its vertex count against the bound
 * SR_MAX_CLIP_VERTS, and every output vertex against the six planes, using
 * plane distances written from the convention table (clip_helpers.h), not
 * the clipper's own.
 *
 * case_raycast is independent of the pipeline: it casts the ray through
 * each pixel (scene_pixel_ray) against the mesh in double precision and
 * counts the triangles it meets within [near, far] that culling keeps. It
 * samples the centre and four points 1/32 pixel around it, so a pixel whose
 * samples disagree (an outline, a near- or far-plane cut) gets a range.
 */
#ifndef SOFTRAST_TESTS_CASE_ORACLE_H
#define SOFTRAST_TESTS_CASE_ORACLE_H

#include <stdbool.h>
#include <stdint.h>

#include <cglm/cglm.h>

#include "softrast_private.h"

#define CASE_RAY_OFFSET (1.0 / 32.0) /* pixels between the centre and the other samples */

typedef struct case_clip_report {
    uint64_t triangles;  /* assembled (non-degenerate) */
    uint64_t rejected;   /* by outcodes or non-finite position */
    uint64_t clipped;    /* crossed at least one plane */
    int max_vertices;    /* largest clipper output */
    unsigned crossed;    /* planes crossed by a triangle that kept some polygon */
    unsigned on_plane;   /* planes some finite vertex lies exactly on */
    uint64_t bad;        /* output vertices outside beyond the tolerance, non-finite, or over the bound */
    char first_bad[256];
} case_clip_report;

/* tolerance: a vertex (x, y, z, w) is inside a plane if its distance is at
 * least -tolerance · max(|x|, |y|, |z|, |w|). */
void case_clip_run(const sr_mesh *mesh, const mat4 world, const mat4 view, const mat4 projection, sr_shade shade,
                   int width, int height, double tolerance, case_clip_report *r);

/* Fills lo[i], hi[i] (width * height) with the range of hits the pixel may
 * take. world is applied to the positions; the camera gives the rays. */
void case_raycast(const sr_mesh *mesh, const mat4 world, const sr_camera *cam, int width, int height, sr_cull cull,
                  sr_front front, uint8_t *lo, uint8_t *hi);

#endif
