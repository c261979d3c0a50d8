/* 06_viewport_lanes.h — the float half of the vertex mapping
 * (sr_viewport_map_float_block, 06_viewport.h), and the double half
 * (sr_viewport_map_double_block), in lanes of double: what
 * its two widths share (06_viewport_body.h, compiled by 06_viewport_sse2.c
 * and 06_viewport_avx2.c) and the viewport's side of it. Not public API. */
#ifndef SOFTRAST_PIPELINE_VIEWPORT_LANES_H
#define SOFTRAST_PIPELINE_VIEWPORT_LANES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "stages.h"

/* The viewport's numbers as 06_viewport.c's scalar map uses them: the
 * guard band, the subpixel units per NDC unit on each axis, the depth
 * model (a, b, on), and the bounds its slack gives x and y (xy_lo .. hi)
 * and z (z_lo .. hi). */
typedef struct sr_viewport_lanes {
    double guard, x_units, y_units;
    double a, b;
    bool depth_on;
    double xy_lo, z_lo, hi;
} sr_viewport_lanes;

/* The float half of each v[k] whose codes[k] is 0, for k below n rounded
 * down to whole groups of lanes (returned): as 06_viewport.c's map_float,
 * lane by lane, into the screen vertex k·stride bytes into out, codes[k]
 * made SR_OUT_NONFINITE where refused; and, with points, each k's snapped
 * point there (SR_SNAPPED_OUTSIDE where codes[k] ends up not 0). Two lanes
 * of SSE2, four of AVX2 (only where the draw's SIMD level has it); the
 * same bits. */
uint32_t sr_viewport_float_lanes_sse2(const sr_vertex_out *v, uint32_t n, int varyings, const sr_viewport_lanes *r,
                                      unsigned char *codes, void *out, size_t stride, sr_snapped_point *points);
uint32_t sr_viewport_float_lanes_avx2(const sr_vertex_out *v, uint32_t n, int varyings, const sr_viewport_lanes *r,
                                      unsigned char *codes, void *out, size_t stride, sr_snapped_point *points);

/* The double half of the mesh vertices index[k], for k below n rounded
 * down to whole groups of lanes (returned): their positions' clip
 * positions in double under m (sr_vertex_transform.clip_from_object_d),
 * mapped as 06_viewport.c's map_double and place map them, into the
 * screen vertices index[k]·stride bytes into screen, lane by lane. Two
 * lanes of SSE2, four of AVX2; the same bits. */
uint32_t sr_viewport_double_lanes_sse2(const float (*positions)[3], const double m[4][4], const uint32_t *index,
                                       uint32_t n, const sr_viewport_lanes *r, char *screen, size_t stride);
uint32_t sr_viewport_double_lanes_avx2(const float (*positions)[3], const double m[4][4], const uint32_t *index,
                                       uint32_t n, const sr_viewport_lanes *r, char *screen, size_t stride);

#endif
