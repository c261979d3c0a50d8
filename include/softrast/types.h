/* softrast/types.h — the plain structs the pipeline stages hand each other.
 *
 * Data moves forward only: the vertex stage fills sr_vertex_out, the clipper
 * turns three of them into an sr_polygon, the viewport stage turns polygon
 * vertices into sr_screen_vertex (snapped fixed point + 1/w), and the
 * rasterizer reads those. Varyings are packed per draw: sr_varying_layout says
 * which the shading mode reads and where they sit, so a mode that reads none
 * (id, depth) carries none through clipping and interpolation.
 */
#ifndef SOFTRAST_TYPES_H
#define SOFTRAST_TYPES_H

#include <stdbool.h>
#include <stdint.h>

/* Inlined into every caller even where the compiler would outline it (the
 * per-pixel loops' shading); a plain inline on compilers without the
 * attribute. */
#if defined(__GNUC__)
#define SR_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define SR_ALWAYS_INLINE inline
#endif

/* Clip-space position (x, y, z, w) then the varyings, in one float array so
 * the clipper interpolates "position and every varying" in one loop. */
enum { SR_X = 0, SR_Y, SR_Z, SR_W, SR_VARYINGS_AT };

#define SR_MAX_VARYINGS 8 /* lambert: normal 3 + color 3 (or uv 2) */
#define SR_VERTEX_FLOATS (SR_VARYINGS_AT + SR_MAX_VARYINGS)
#define SR_CLIP_PLANES 6
#define SR_MAX_CLIP_VERTS (3 + SR_CLIP_PLANES) /* each plane adds at most one vertex */
#define SR_SUBPIXEL_BITS 8                      /* 1/256 px, as Direct3D 11 requires */
#define SR_SUBPIXEL_ONE (1 << SR_SUBPIXEL_BITS)
#define SR_MIN_SUBPIXEL_BITS 2                  /* the range a draw may ask for (accuracy studies) */
#define SR_MAX_SUBPIXEL_BITS 16

typedef enum sr_shade {
    SR_SHADE_LAMBERT = 0, /* one directional light on the albedo (texture, vertex color or gray) */
    SR_SHADE_ID,          /* triangle id + 1 as 0xRRGGBB */
    SR_SHADE_COLOR,       /* vertex colors */
    SR_SHADE_NORMAL,      /* world normal mapped to 0.5 + 0.5 n */
    SR_SHADE_TEXTURE,     /* texture at the interpolated uv */
    SR_SHADE_DEPTH,       /* depth only; color is filled from depth after the draw */
    SR_SHADE_COUNT
} sr_shade;

typedef enum sr_cull { SR_CULL_BACK = 0, SR_CULL_FRONT, SR_CULL_NONE } sr_cull;
typedef enum sr_front { SR_FRONT_CW = 0, SR_FRONT_CCW } sr_front;
typedef enum sr_filter { SR_FILTER_BILINEAR = 0, SR_FILTER_NEAREST } sr_filter;

/* The per-pixel loop's instruction set: AUTO picks the best the CPU has
 * (AVX-512, else AVX2, else SSE2); the others force one, for tests and the
 * report. Every choice gives bit-identical pixels and depths. */
typedef enum sr_simd {
    SR_SIMD_AUTO = 0,
    SR_SIMD_SCALAR,
    SR_SIMD_SSE2,
    SR_SIMD_AVX2,
    SR_SIMD_AVX512,
    SR_SIMD_COUNT
} sr_simd;

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

typedef struct sr_polygon {
    int count;
    sr_vertex_out vert[SR_MAX_CLIP_VERTS];
} sr_polygon;

/* A vertex after divide, viewport and snapping: position in 1/256 pixel
 * units (top-left origin, y down), z_ndc, 1/w and the varyings divided by w. */
typedef struct sr_screen_vertex {
    int64_t x, y;
    float z;
    float inv_w;
    float var_w[SR_MAX_VARYINGS];
} sr_screen_vertex;

typedef struct sr_stats {
    uint64_t triangles; /* assembled (non-degenerate) */
    uint64_t rejected;  /* dropped whole: outside one plane, or non-finite */
    uint64_t nonfinite; /* of those, dropped for NaN or inf in a position or a read varying,
                           or a divide past float range */
    uint64_t clipped;   /* crossed at least one plane */
    uint64_t culled;    /* fan triangles dropped as facing away or zero area */
    uint64_t drawn;     /* fan triangles rasterized */
    uint64_t fragments; /* pixels that passed the depth test */
    uint64_t cuts_float, cuts_double, cuts_exact; /* cut vertices by the precision the clipper used */
} sr_stats;

#endif
