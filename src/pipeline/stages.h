/* stages.h — the plain structs the pipeline stages hand each other.
 *
 * Data moves forward only: the vertex stage fills sr_vertex_out, the clipper
 * turns three of them into an sr_polygon, the viewport stage turns polygon
 * vertices into sr_screen_vertex (snapped fixed point + 1/w), and the
 * rasterizer reads those. Varyings are packed per draw: sr_varying_layout says
 * which the shading mode reads and where they sit, so a mode that reads none
 * (id, depth) carries none through clipping and interpolation.
 */
#ifndef SOFTRAST_PIPELINE_STAGES_H
#define SOFTRAST_PIPELINE_STAGES_H

#include <stdbool.h>
#include <stdint.h>

#include "softrast/study.h"

/* Inlined into every caller even where the compiler would outline it (the
 * per-pixel loops' shading); a plain inline on compilers without the
 * attribute. */
#if defined(__GNUC__)
#define SR_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define SR_ALWAYS_INLINE inline
#endif

/* A vertex's snapped point as the viewport stage notes it for the
 * sub-pixel slot lanes and the row bands, one 8-byte load a corner: for a
 * vertex inside every plane (outcode 0), x in the low 32 bits and y in
 * the high 32 (each below 2^30 there, so exact); for any other,
 * SR_SNAPPED_OUTSIDE, whose x (INT32_MIN) no point inside holds. The
 * corner's outcode rides in its point: the lanes read no outcode. */
typedef uint64_t sr_snapped_point;
#define SR_SNAPPED_OUTSIDE ((sr_snapped_point)0x80000000u)

static inline sr_snapped_point sr_snapped_point_of(int64_t x, int64_t y)
{
    return (uint32_t)x | (uint64_t)(uint32_t)y << 32;
}

/* The y of a point inside every plane. */
static inline int32_t sr_snapped_point_y(sr_snapped_point p)
{
    return (int32_t)(uint32_t)(p >> 32);
}

/* Clip-space position (x, y, z, w) then the varyings, in one float array so
 * the clipper interpolates "position and every varying" in one loop. */
enum { SR_X = 0, SR_Y, SR_Z, SR_W, SR_VARYINGS_AT };

#define SR_VERTEX_FLOATS (SR_VARYINGS_AT + SR_MAX_VARYINGS)
#define SR_CLIP_PLANES 6
#define SR_MAX_CLIP_VERTS (3 + SR_CLIP_PLANES) /* each plane adds at most one vertex */
#define SR_SUBPIXEL_ONE (1 << SR_SUBPIXEL_BITS)

/* Where each varying sits in sr_vertex_out.v (an offset from SR_VARYINGS_AT),
 * or -1 when the shading mode does not read it. */
typedef struct sr_varying_layout {
    int count;
    int color, uv, normal;
} sr_varying_layout;

/* The depth model of a perspective projection (docs/precision.md): when the
 * projection's w row is (0, 0, s, 0), s = ±1, and its z row (0, 0, A, B),
 * every clip-space vertex has z = a·w + b exactly (a = A/s, b = B), whatever
 * the world and view matrices. With `on`, the clipper takes the near and far
 * distances from w (near a·w + b, far w − a·w − b) and the viewport takes
 * z_ndc = a + b/w, instead of trusting a float z that cannot hold b next to a
 * large w. a and b are floats, so a·w is exact in double. Zero: off, z as is. */
typedef struct sr_clip_depth {
    bool on;
    float a, b;
} sr_clip_depth;

typedef struct sr_vertex_out {
    float v[SR_VERTEX_FLOATS];
} sr_vertex_out;

/* A line in a clipped triangle: its edge k (vertex k to k + 1, where the
 * weight of vertex k + 2 is 0) for k < SR_CLIP_ON_PLANE, or the cut line of
 * plane l − SR_CLIP_ON_PLANE (where that plane's distance is 0). */
enum { SR_CLIP_ON_PLANE = 3 };

/* The clipper's polygon. When it was given a triangle, line[i] is the line
 * its edge i (vertex i to i + 1) runs along, so vertex i is the triangle's
 * point on lines line[i − 1] and line[i]: the viewport maps a cut vertex's
 * depth from that point in double (docs/precision.md). */
typedef struct sr_polygon {
    int count;
    sr_vertex_out vert[SR_MAX_CLIP_VERTS];
    unsigned char line[SR_MAX_CLIP_VERTS];
} sr_polygon;

#endif
