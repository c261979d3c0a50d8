/* softrast/study.h — measuring the pipeline: accuracy knobs and a trace.
 *
 *     sr_draw_study study = { .subpixel_bits = 4, .simd = SR_SIMD_SCALAR };
 *     desc.study = &study;               // softrast/softrast.h's sr_draw_desc
 *
 * Nothing here is needed to draw. The knobs change how a draw computes, so
 * their cost and their error can be measured (docs/report.md); every zero
 * field is the default that the conventions pin, so a zeroed study draws
 * exactly what no study draws. The trace sees the fan triangles the
 * rasterizer gets; count_hits counts how many cover each pixel; times
 * says where the draw's time went, phase by phase (docs/performance.md,
 * "Where the time goes today").
 */
#ifndef SOFTRAST_STUDY_H
#define SOFTRAST_STUDY_H

#include <stdbool.h>
#include <stdint.h>

#include "softrast.h"

/* How cut vertices are computed; the sign tests are exact in every mode.
 * ADAPTIVE (the default) picks per edge the cheapest of float, double and
 * exact whose a-priori error bound keeps the cut vertex within half a
 * subpixel step (docs/precision.md); the others force one. EXACT carries the
 * plane distances and the numerator as exact expansions and rounds once. The
 * choice depends only on the unordered edge, never on the walk direction, so
 * shared edges stay bit-identical. */
typedef enum sr_clip_precision {
    SR_CLIP_ADAPTIVE = 0,
    SR_CLIP_FLOAT,
    SR_CLIP_DOUBLE,
    SR_CLIP_EXACT,
    SR_CLIP_PRECISIONS
} sr_clip_precision;

/* The per-pixel loop's instruction set: AUTO picks the best the CPU has
 * (AVX-512, else AVX2, else SSE2); the others force one (a missing one falls
 * back to the best below). Every choice gives bit-identical pixels and
 * depths. */
typedef enum sr_simd {
    SR_SIMD_AUTO = 0,
    SR_SIMD_SCALAR,
    SR_SIMD_SSE2,
    SR_SIMD_AVX2,
    SR_SIMD_AVX512,
    SR_SIMD_COUNT
} sr_simd;

#define SR_SUBPIXEL_BITS 8     /* 1/256 px, as Direct3D 11 requires */
#define SR_MIN_SUBPIXEL_BITS 2 /* the range a study may ask for */
#define SR_MAX_SUBPIXEL_BITS 16
#define SR_MAX_GUARD_BAND 64.0f
#define SR_MAX_VARYINGS 8 /* lambert: normal 3 + color 3 (or uv 2) */

/* A fan-triangle vertex after divide, viewport and snapping: position in
 * units of 2^-subpixel_bits pixel (top-left origin, y down), z_ndc, 1/w and
 * the varyings divided by w. x_off, y_off: where the vertex lay before
 * snapping, relative to x, y in the same units (|·| <= 1/2; zero, as a
 * vertex made by hand has them, means exactly at x, y). The pipeline
 * snaps every vertex from float clip coordinates (a cut vertex: the
 * clipper's) but keeps the offsets (and z) of its position in double (a
 * mesh vertex's clip position; a clipped polygon's vertex, the triangle's
 * point on its two lines, or its float position where those lines do not
 * meet in front of the eye), which may lie past 1/2 by the float
 * transform's and the clipper's error. Coverage is decided on the snapped x, y; the
 * depth plane goes through the unsnapped points. */
typedef struct sr_screen_vertex {
    int64_t x, y;
    float x_off, y_off;
    float z;
    float inv_w;
    float var_w[SR_MAX_VARYINGS];
} sr_screen_vertex;

/* Sees every fan triangle that survives culling, before it is rasterized;
 * clipped: the triangle crossed a plane; id: its triangle slot. A draw with
 * one takes the direct path on one thread, whatever its threads and path
 * ask, and calls it in submission order. var_w holds the draw's varyings
 * (none in depth and id shading) and 0 past them. */
typedef void (*sr_triangle_observer)(void *user, const sr_screen_vertex tri[3], bool clipped, uint32_t id);

/* Where a draw's time goes, added to by every draw whose study points at
 * an sr_draw_times (the caller zeroes it first). Per phase: milliseconds of
 * wall time, and of CPU time summed over the phase's threads (on a shared
 * machine a thread may wait for a core: cpu / wall is the parallelism the
 * phase got, cpu against the one-thread draw's is the threads' overhead).
 * Two clock reads per phase and thread, never per triangle: on the direct
 * path, where set-up and rasterization interleave per triangle, both count
 * under `primitives` (perf splits them: docs/performance.md, "How to
 * measure a change"). */
typedef struct sr_phase_time {
    double wall, cpu;
} sr_phase_time;

typedef enum sr_draw_path {
    SR_PATH_BY_COST = 0,
    SR_PATH_DIRECT,
    SR_PATH_TILES,
    SR_PATH_ROWS
} sr_draw_path;

typedef struct sr_draw_times {
    sr_phase_time vertex;     /* stage 1, outcodes, mapping of the inside vertices */
    /* stages 2-7; tiled path: and binning; direct path: and rasterization;
     * row bands: stages 2-3 (each slot's verdict) */
    sr_phase_time primitives;
    sr_phase_time raster; /* tiled path (at any thread count): the tiles; row bands: stages 4-10 */
    double total;         /* wall ms of the whole sr_draw, its serial checks and set-up included */
    sr_draw_path path;    /* the path the last draw took (SR_PATH_DIRECT for a mesh out of view) */
    bool subpixel_lanes;  /* whether it dropped triangles that cover no pixel centre in lanes (below) */
} sr_draw_times;

typedef struct sr_draw_study {
    int subpixel_bits;                /* 0: SR_SUBPIXEL_BITS; else SR_MIN..SR_MAX_SUBPIXEL_BITS */
    sr_clip_precision clip_precision; /* SR_CLIP_ADAPTIVE: per edge, within half a subpixel step */
    float guard_band;                 /* 0 or 1: clip x, y at the viewport; G > 1: at ±G·w */
    sr_simd simd;                     /* SR_SIMD_AUTO: the best per-pixel loop the CPU has */
    sr_triangle_observer observer;    /* optional */
    void *observer_user;
    bool count_hits;                  /* count coverage instead of shading: see below */
    sr_draw_times *times;             /* optional: the phases' wall time is added here */
    sr_draw_path path;                /* SR_PATH_BY_COST: the path by the cost estimate (below) */
    uint32_t chunk_slots;             /* 0: the draw's own; else slots per chunk of the binning or the verdicts */
    bool one_by_one;                  /* no sub-pixel lanes: every triangle set up on its own (below) */
} sr_draw_study;

/* path: a draw takes several threads (the row bands, or the tiles), or the
 * tiles on one, only when its cost estimate says they pay (many triangle
 * slots or a large framebuffer, and not every vertex outside one plane),
 * and takes the tiles on one thread when its triangles are few for its
 * pixels (docs/performance.md, "Which path a draw takes"). SR_PATH_DIRECT
 * draws on one thread without tiles, SR_PATH_TILES on the tiles at the
 * draw's thread count, one included, and SR_PATH_ROWS with each thread
 * drawing its band of rows (the estimate's choice for triangle slots many
 * for the pixels on several threads), so tests keep every path exercised
 * on small scenes. All draw the same pixels. A draw
 * of more than 2^31 triangle slots (a strip's) takes the direct path
 * whatever its path asks.
 *
 * chunk_slots: the tiles' binning, and the row bands' verdicts, hand
 * triangle slots to the threads in chunks (binning: about 8 a thread of
 * 256 to 16384 slots; verdicts: 16384); a few slots a chunk split a small
 * mesh among the threads as a large one is (tests, the fuzzer). */

/* one_by_one: a draw of many triangles for its pixels first tests them
 * four or eight at a time, in SIMD lanes, for a scan box that holds no pixel
 * centre or one they miss, and counts those as culled or drawn as stage 7
 * would, without setting them up (docs/performance.md, "Sub-pixel
 * triangles"); this sends every triangle through its own set-up instead,
 * as the reference the lanes are tested against. Both draw and count the
 * same. */

/* count_hits: every pixel a fan triangle covers gets color += 1 (the caller
 * clears color to 0 first), so after the draw each pixel holds the number of
 * fan triangles that cover it: 1 inside a watertight mesh, 0 in a crack, 2
 * where two overlap. Coverage is the rasterizer's own (the same exact edge
 * functions and top-left rule); nothing is depth tested, depth is not
 * written, desc.shade is not used and no vertex attribute is read, and
 * sr_stats.fragments counts the hits. It runs on any number of threads
 * (each tile, or each thread's band of rows, is counted by one) and gives
 * the same counts on all; only the scalar per-pixel loop counts
 * (sr_workspace_simd_draws stays 0). */

/* How many rasterizer calls of the last draw with this workspace a SIMD
 * kernel made (a call is a fan triangle, or on the tiles its share of one
 * tile, on the row bands its share of one thread's rows; narrow ones take
 * the scalar loop, and a tiny one whose pixels a SIMD shader colors counts
 * if any pixel passed): tests check the kernels ran. */
SR_API uint64_t sr_workspace_simd_draws(const sr_workspace *ws);

#endif
