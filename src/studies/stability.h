/* stability.h — `softrast bench --stability`: how the pipeline holds up under
 * stiff cameras, written as docs/stability.md and docs/stability.svg.
 *
 * Three measurements, one file each:
 *   stability_clip.c   error of every cut vertex of each clipper precision
 *                      (sr_clip_precision) against the exact cut of the same
 *                      float edge by the same plane;
 *   stability_grid.c   holes (cracks, lost triangles) and double hits on a
 *                      flat grid under each case;
 *   stability_depth.c  the smallest plane separation the depth test orders,
 *                      standard against reversed z.
 * stability_cases.c defines the stiff cases the first two share;
 * stability_doc.c and stability_svg.c write the files. The declarations below sr_stability_write
 * are internal to those files.
 */
#ifndef SOFTRAST_APP_STABILITY_H
#define SOFTRAST_APP_STABILITY_H

#include <stdbool.h>
#include <stdint.h>

#include "softrast_private.h"

/* Runs every measurement and writes stability.md and stability.svg into dir. */
bool sr_stability_write(const char *dir, sr_error *err);

/* ---- internal: shared by src/app/stability*.c ---- */

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

/* Section 1: error of every cut vertex against the exact cut of the same
 * float edge by the same plane, ‖Δ‖∞ / ‖exact‖∞ (= |w| inside the clip
 * volume); a triangle's error is its largest cut's (stability_clip.c). */
typedef struct sr_stability_clip_stats {
    double max, p99;       /* over triangles */
    double worst_w;        /* exact w of the cut with the largest error */
    double worst_spread;   /* and how many times larger its end points are (‖·‖∞) */
    uint64_t triangles;    /* clipped triangles measured */
    uint64_t lost;         /* of those, clipped to nothing where the exact clipper keeps a polygon */
    sr_clip_counts cuts;   /* cut vertices by the precision actually used */
} sr_stability_clip_stats;

/* The NDC tolerance the adaptive clipper gets here: a 1920-pixel draw's. */
double sr_stability_clip_tolerance(void);

bool sr_stability_clip_errors(const sr_stability_case *c, sr_stability_clip_stats out[SR_STABILITY_CLIPPERS],
                              sr_error *err);

/* Section 2: hits per pixel of the grid (stability_grid.c). */
typedef struct sr_stability_hits {
    bool measured;        /* false: the case has no graded grid */
    uint64_t inside;      /* pixels at least 1 px inside the grid's visible region */
    uint64_t holes;       /* of those, hit 0 times (cracks, or triangles lost) */
    uint64_t double_hits; /* pixels anywhere hit 2 or more times */
    sr_stats stats;       /* the draw's */
} sr_stability_hits;

bool sr_stability_grid_hits(const sr_stability_case *c, bool graded, const sr_stability_clipper *clipper,
                            sr_stability_hits *out, sr_error *err);

/* Section 3: smallest separation s/d that the depth test orders, or NAN when
 * none up to s = d is (stability_depth.c). */
typedef struct sr_stability_depth {
    double ratio[SR_STABILITY_RATIOS];
    double fraction[SR_STABILITY_DISTANCES];
    double separation[SR_STABILITY_RATIOS][SR_STABILITY_DISTANCES][SR_STABILITY_MAPPINGS];
    double distance[SR_STABILITY_RATIOS][SR_STABILITY_DISTANCES]; /* d, as a float holds it */
    double floor[SR_STABILITY_RATIOS][SR_STABILITY_DISTANCES];    /* one float step of d, relative to d */
} sr_stability_depth;

bool sr_stability_depth_table(sr_stability_depth *out, sr_error *err);

typedef struct sr_stability_report {
    sr_stability_clip_stats clip[SR_STABILITY_CASES][SR_STABILITY_CLIPPERS];
    sr_stability_hits hits[SR_STABILITY_CASES][SR_STABILITY_GRIDS][SR_STABILITY_CLIPPERS];
    sr_stability_depth depth;
    double seconds; /* the whole run */
} sr_stability_report;

bool sr_stability_files(const char *dir, const sr_stability_report *r, sr_error *err);

/* The depth table as a plot (stability_svg.c). */
bool sr_stability_svg(const char *path, const sr_stability_depth *d, sr_error *err);

#endif
