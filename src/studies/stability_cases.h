/* stability_cases.h — the stiff cases the stability study measures: cameras, grids,
 * random triangles with each case's trouble, and the sizes of its tables. */
#ifndef SOFTRAST_STUDIES_STABILITY_CASES_H
#define SOFTRAST_STUDIES_STABILITY_CASES_H

#include <stdbool.h>
#include <stdint.h>

#include "softrast_private.h"

#define SR_STABILITY_CASES 7
#define SR_STABILITY_WIDTH 320 /* the grid's framebuffer; its aspect is the clip tests' too */
#define SR_STABILITY_HEIGHT 240
#define SR_STABILITY_CLIPPERS 4   /* the clipper precisions compared, the default first */
#define SR_STABILITY_GRIDS 2      /* even cells, then graded (where the case grades) */
#define SR_STABILITY_RATIOS 8     /* far/near = 1e2 … 1e9 */
#define SR_STABILITY_DISTANCES 4  /* fractions of the way from near to far */
#define SR_STABILITY_MAPPINGS 2   /* standard, reversed */

/* One clipper precision under test (sr_clip_precision; 0 is the library's default). */
typedef struct sr_stability_clipper {
    const char *name;
    sr_clip_precision precision;
} sr_stability_clipper;

extern const sr_stability_clipper sr_stability_clippers[SR_STABILITY_CLIPPERS];

/* A fixed-seed generator, so every run measures the same triangles. */
typedef struct sr_stability_rng {
    uint64_t state;
} sr_stability_rng;

double sr_stability_uniform(sr_stability_rng *rng, double lo, double hi);
double sr_stability_log_uniform(sr_stability_rng *rng, double lo, double hi); /* 0 < lo < hi */

/* A stiff case: a camera, a flat grid it looks at, and a maker of random
 * triangles with the case's trouble. The grid is centre + a·u + b·v for a, b
 * in [-1, 1], its lines evenly spaced (huge cells around the eye), or, for a
 * case with grid_inner > 0, also spaced geometrically out from the centre
 * with the innermost cell grid_inner of the half-extent (many cells on
 * screen however many decades the grid spans). Its normal is a
 * coordinate axis, so float grid vertices lie exactly in the plane. */
typedef struct sr_stability_case sr_stability_case;
struct sr_stability_case {
    const char *name, *what, *triangles; /* what: camera and grid; triangles: the random ones */
    sr_camera camera;
    vec3 grid_centre, grid_u, grid_v;
    double grid_inner;
    void (*triangle)(const sr_stability_case *c, sr_stability_rng *rng, vec3 out[3]);
};

const sr_stability_case *sr_stability_cases(void); /* SR_STABILITY_CASES of them */

/* The camera's orthonormal basis in double (left-handed: right = up × forward). */
typedef struct sr_stability_frame {
    double eye[3], right[3], up[3], forward[3];
} sr_stability_frame;

sr_stability_frame sr_stability_frame_of(const sr_camera *cam);

/* clip_from_world = P·V as the draw builds it, at the grid's aspect. */
void sr_stability_clip_matrix(const sr_camera *cam, mat4 clip_from_world);

#endif
