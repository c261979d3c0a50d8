/* tests/case_format.h — the edge-case scenes of tests/cases/NAME.case, parsed.
 *
 * A case file is a small line-based scene description: a mesh (inline
 * triangles, an OBJ file or a generated shape), a camera or raw matrices,
 * a framebuffer size, draw options, and the invariants it must hold. The
 * format is documented in tests/cases/README.md; test_cases.c runs every
 * file it finds as one Criterion test. This module only reads files and
 * builds the mesh and matrices; it asserts nothing.
 */
#ifndef SOFTRAST_TESTS_CASE_FORMAT_H
#define SOFTRAST_TESTS_CASE_FORMAT_H

#include <stdbool.h>
#include <stdint.h>

#include <cglm/cglm.h>

#include "core/array.h"
#include "softrast_private.h"

#define CASE_PATH_MAX 512
#define CASE_TEXT_MAX 256
#define CASE_MAX_EXPECT 32
#define CASE_MAX_STATS 8          /* comparisons on one `expect stats` line */
#define CASE_CLIP_TOLERANCE 1e-6  /* default relative tolerance of clip-inside */

typedef enum case_mesh_kind {
    CASE_MESH_INLINE = 0, /* v / t / strip lines */
    CASE_MESH_OBJ,        /* sr_obj_load(path) */
    CASE_MESH_TORUS,      /* sr_shape_torus(major, minor, segments, sides) */
    CASE_MESH_QUADS       /* sr_shape_quads(count, size, first_z, step) */
} case_mesh_kind;

typedef enum case_matrix { CASE_WORLD = 0, CASE_VIEW, CASE_PROJECTION, CASE_MATRICES } case_matrix;

typedef enum case_expect_kind {
    CASE_EXPECT_STATS,           /* stats NAME=V NAME<=V NAME>=V ... */
    CASE_EXPECT_AREA,            /* area A TOL: summed fan area in px² */
    CASE_EXPECT_COVERED_ALL,     /* every pixel hit at least once */
    CASE_EXPECT_HIT_AT_MOST_ONCE,/* no pixel hit twice */
    CASE_EXPECT_RAYCAST,         /* hits per pixel agree with a ray cast in double */
    CASE_EXPECT_CLIP_VERTICES,   /* the largest clipper output has exactly N vertices */
    CASE_EXPECT_CROSSES,         /* a triangle that survives clipping crossed each named plane */
    CASE_EXPECT_ON_PLANE,        /* a vertex lies exactly on each named plane (distance 0) */
    CASE_EXPECT_DEPTH_AT,        /* depth-at X Y Z TOL */
    CASE_EXPECT_CAMERA_INVALID   /* sr_camera_check refuses the camera; nothing is drawn */
} case_expect_kind;

typedef enum case_stat {
    CASE_STAT_TRIANGLES = 0, CASE_STAT_REJECTED, CASE_STAT_NONFINITE, CASE_STAT_CLIPPED,
    CASE_STAT_CULLED, CASE_STAT_DRAWN, CASE_STAT_FRAGMENTS, CASE_STAT_COUNT
} case_stat;

typedef enum case_op { CASE_OP_EQ = 0, CASE_OP_LE, CASE_OP_GE } case_op;

typedef struct case_stat_check {
    case_stat stat;
    case_op op;
    uint64_t value;
} case_stat_check;

typedef struct case_expect {
    case_expect_kind kind;
    int line;                 /* in the case file, for messages */
    char text[CASE_TEXT_MAX]; /* the line as written */
    double a, b, c, d;        /* area: a ± b; depth-at: (a, b) z = c ± d; clip-vertices: a */
    unsigned planes;          /* crosses, on-plane: bit 1 << sr_clip_plane */
    int stat_count;
    case_stat_check stats[CASE_MAX_STATS];
} case_expect;

/* Growable inline vertex data; attributes exist iff some `v` line gave them. */
typedef struct case_vertex {
    float pos[4]; /* x y z, and w for vclip */
    float rgb[3], uv[2], nrm[3];
} case_vertex;

typedef struct case_inline {
    sr_array vertices; /* of case_vertex */
    bool has_rgb, has_uv, has_nrm;
    bool clip_space;  /* the vertices are `vclip` lines: clip space, no matrices */
    sr_array indices; /* of uint32_t */
    bool strip;       /* the indices came from a `strip` line */
} case_inline;

typedef struct case_desc {
    char path[CASE_PATH_MAX];
    char title[CASE_TEXT_MAX];
    case_mesh_kind mesh_kind;
    char mesh_path[CASE_PATH_MAX];
    double mesh_args[4];
    case_inline in;
    bool has_camera;
    sr_camera camera;
    bool matrix_set[CASE_MATRICES];
    mat4 matrix[CASE_MATRICES];
    int width, height;
    sr_shade shade;
    sr_cull cull;
    sr_front front;
    int reversed_z; /* -1: as the camera says (standard without one); 0 or 1: `draw depth ...` */
    double clip_tolerance;
    int expect_count;
    case_expect expect[CASE_MAX_EXPECT];
} case_desc;

/* Reads and parses a case file (path as given, e.g. "tests/cases/x.case").
 * False with "PATH:LINE: what" in err on a syntax error. */
bool case_load(case_desc *c, const char *path, sr_error *err);
void case_free(case_desc *c);

/* A path relative to the project root: under $SOFTRAST_ROOT when it is set
 * (as scene_helpers.h places its output), else as given. */
void case_root_path(const char *relative, char out[CASE_PATH_MAX]);

/* The mesh the case describes (the caller frees it with sr_mesh_free). */
bool case_make_mesh(const case_desc *c, sr_mesh *mesh, sr_error *err);

/* World, view and projection: the camera's (world = identity), then any
 * `matrix` lines on top; identity where neither says anything. */
void case_make_matrices(const case_desc *c, mat4 world, mat4 view, mat4 projection);

/* True if the case has an expectation of this kind. */
bool case_wants(const case_desc *c, case_expect_kind kind);

const char *case_stat_name(case_stat s);
const char *case_plane_name(int plane);

#endif
