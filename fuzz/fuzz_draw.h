/* fuzz/fuzz_draw.h — what the parts of the draw target share: the input
 * reader, the decoded scene, one draw's record, the invariants' helpers.
 * fuzz_draw.c is the entry point (see there for the input format);
 * draw_input.c decodes, draw_checks.c draws and checks, draw_stages.c
 * re-runs the stages by hand, draw_pinhole.c resolves a pinhole camera's
 * view, draw_clip.c tests the clipper alone. */
#ifndef SOFTRAST_FUZZ_DRAW_H
#define SOFTRAST_FUZZ_DRAW_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cglm/cglm.h>
#include <cglm/clipspace/ortho_lh_zo.h>
#include <cglm/clipspace/persp_lh_zo.h>
#include <cglm/clipspace/view_lh.h>

#include "softrast_private.h"

#include "fuzz_common.h" /* fail(), CHECK() */

#define MAX_SIDE 64
#define MAX_VERTS 16
#define MAX_INDICES 48
#define MAX_TEXTURE_SIDE 4
#define CULL_MODES 3

/* The clipper's outputs lie inside each plane it clipped against, up to
 * rounding: every cut vertex is rounded to float once per coordinate per
 * plane, a few ulps (2^-24 ≈ 6e-8) of the vertex's largest coordinate. */
#define CLIP_INSIDE_REL_TOL 1e-5
/* Interpolated values stay within the inputs' range up to float rounding of
 * the largest input magnitude (t rounds to 1 when d_out ≪ d_in). */
#define CLIP_RANGE_REL_TOL 1e-6


#define CHECK_KNOWN(tag, cond, ...)                                 \
    do {                                                            \
        if (!(cond) && !tolerated(tag))                             \
            fail(__FILE__, __LINE__, #cond " [" tag "]", __VA_ARGS__); \
    } while (0)

/* Reads the input front to back; past the end every byte is 0. */
typedef struct reader {
    const uint8_t *data;
    size_t size, pos;
    float prev; /* the anchor that "a few ulps from the previous value" uses */
} reader;

typedef struct scene {
    int width, height;
    sr_mesh mesh;
    bool indices_valid;
    mat4 world, view, projection;
    bool matrices_finite; /* all three, after the all-zero = identity default */
    sr_shade shade;
    sr_cull cull;
    sr_front front;
    sr_filter filter;
    sr_texture texture;
    bool has_texture;
    vec3 light;
    bool reversed_z; /* the framebuffer's depth convention: clear 0, GREATER */
    int threads;     /* for the threaded draw compared with one thread, or 0: none */
    bool big;        /* that comparison on a framebuffer of several tiles */
    uint32_t chunk_slots; /* its slots per chunk of the binning (sr_draw_study), 0: the draw's own */
} scene;

typedef struct draw_run {
    const scene *sc;
    sr_shade shade;
    sr_cull cull;
    sr_framebuffer fb;
    sr_stats stats;
    bool ok;
    uint64_t observed;                /* observer calls */
    bool id_seen[MAX_INDICES];        /* triangle ids the observer saw */
} draw_run;

/* draw_input.c */
bool tolerated(const char *tag); /* the tag is in FUZZ_TOLERATE (fuzz/README.md) */
uint8_t take_u8(reader *r);
float take_finite_float(reader *r);
bool scene_decode(reader *r, scene *sc);
void scene_free(scene *sc);
bool matrix_is_zero(const mat4 m);
uint32_t slot_count(const sr_mesh *m);
bool slot_triangle(const sr_mesh *m, uint32_t k, uint32_t t[3]);
bool position_finite(const sr_mesh *m, uint32_t i);
bool draw_should_succeed(const scene *sc, sr_shade shade);
bool map_vertex(const sr_vertex_out *v, int varyings, int width, int height, const sr_clip_depth *depth,
                sr_screen_vertex *out);

/* draw_checks.c: four draws of a decoded scene and their invariants */
void fuzz_draw(reader *r);

/* draw_stages.c: stages 2-6 by hand against what sr_draw counted */
bool viewport_may_refuse(const float *v, int varyings);
void check_clip_area(const sr_polygon *tri, unsigned planes, const sr_polygon *got, double vertex_tolerance,
                     const sr_clip_depth *depth, const char *what);
void check_stages(const scene *sc, const sr_stats *stats);

/* draw_pinhole.c: a pinhole camera's draw and resolve, from the bytes the scene leaves */
void check_pinhole(const scene *sc, reader *r);

/* draw_clip.c: the clipper on its own */
void fuzz_clip(reader *r);
void print_polygon(const char *name, const sr_polygon *p, int floats);

#endif
