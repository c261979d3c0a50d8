/* subpixel_lanes.h — what the sub-pixel lanes (subpixel.h) read and say,
 * shared by their widths (subpixel_body.h) and the choice between them
 * (subpixel.c). Not public API. */
#ifndef SOFTRAST_PIPELINE_SUBPIXEL_LANES_H
#define SOFTRAST_PIPELINE_SUBPIXEL_LANES_H

#include <stdbool.h>
#include <stdint.h>

#include "pipeline/stages.h"

/* Triangles per call: bits of a 64-bit mask. */
#define SR_SUBPIXEL_BATCH 64
/* The finest snap the lanes hold exactly (subpixel.h); finer draws skip them. */
#define SR_SUBPIXEL_LANES_MAX_BITS 12

/* Lane i's vertex k at (x[k][i], y[k][i]): the snapped screen position in
 * subpixel units, as an int32 (exact: below 2^30 inside every plane). */
typedef struct sr_subpixel_batch {
    int32_t x[3][SR_SUBPIXEL_BATCH], y[3][SR_SUBPIXEL_BATCH];
} sr_subpixel_batch;

/* What decides a lane: the snap, the framebuffer, and which windings stage
 * 7 keeps (sr_cull_keeps of a positive area, of a negative one); and the
 * width of the lanes: eight of AVX2 where the draw's SIMD level has it,
 * else four of SSE2 (the same verdicts). */
typedef struct sr_subpixel_rules {
    int bits, width, height;
    bool keep_cw, keep_ccw;
    bool avx2, avx512; /* avx512: and the slot lanes sixteen slots a group */
} sr_subpixel_rules;

/* The most pixels a triangle the lanes decide spans on each axis (subpixel.h). */
#define SR_SUBPIXEL_SPAN 4

/* The lanes of the triangles that draw no pixel, by how stage 7 counts
 * them: culled (its area or winding), or drawn (kept, but no centre
 * covered). Every other lane is kept and may draw, and of those, one_pixel
 * are the triangles whose scan box holds one pixel centre, which they
 * cover (their coverage is known, a one-bit mask), and small_box those
 * whose scan box holds two to SR_SUBPIXEL_SPAN × SR_SUBPIXEL_SPAN centres
 * (lane_pixels.h finds which they cover). The rest go on to the
 * per-triangle path as they are. */
typedef struct sr_subpixel_verdict {
    uint64_t culled, drawn, one_pixel, small_box;
} sr_subpixel_verdict;

/* Eight slots of a triangle list decided at once from the draw's own
 * arrays (sr_subpixel_slot_group_avx2): plain when each slot's triangle
 * has three distinct indices and all three vertices inside every plane,
 * as sr_slot_verdict would keep it with no plane to clip against; then
 * the lanes' verdict of each, bits 0 .. 7. Not plain, the verdict is
 * empty and the caller takes the slots one at a time. */
typedef struct sr_subpixel_slots {
    bool plain;
    sr_subpixel_verdict verdict;
} sr_subpixel_slots;

/* Slots whose indices start at indices[0] (24 of them, i0 i1 i2 of each),
 * against the snapped points of the vertices, every index below 2^31.
 * AVX2 only: the lanes gather. */
sr_subpixel_slots sr_subpixel_slot_group_avx2(const uint32_t *indices, const sr_snapped_point *points,
                                              const sr_subpixel_rules *rules);
/* The slots a group holds. */
#define SR_SUBPIXEL_SLOT_GROUP 8

/* The same for sixteen slots (48 indices) at once, AVX-512 only. */
sr_subpixel_slots sr_subpixel_slot_group_avx512(const uint32_t *indices, const sr_snapped_point *points,
                                                const sr_subpixel_rules *rules);
#define SR_SUBPIXEL_SLOT_GROUP_AVX512 16

/* The three widths (subpixel_body.h, compiled by subpixel_sse2.c,
 * subpixel_avx2.c and subpixel_avx512.c): the verdicts of lanes [0, n)
 * rounded up to a group, lanes past n included. */
sr_subpixel_verdict sr_subpixel_groups_sse2(const sr_subpixel_batch *b, int n, const sr_subpixel_rules *rules);
sr_subpixel_verdict sr_subpixel_groups_avx2(const sr_subpixel_batch *b, int n, const sr_subpixel_rules *rules);
sr_subpixel_verdict sr_subpixel_groups_avx512(const sr_subpixel_batch *b, int n, const sr_subpixel_rules *rules);

#endif
