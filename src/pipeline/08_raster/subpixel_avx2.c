/* The sub-pixel lanes at the AVX2 width, built with -mavx2 (the Makefile
 * adds it for this file on x86-64) and chosen only where the draw's SIMD
 * level has AVX2 (sr_subpixel_rules.avx2). */
#if defined(__AVX2__)
#define SUBPIXEL_LANES 8
#define SUBPIXEL_GROUPS sr_subpixel_groups_avx2
#include "subpixel_body.h"
#else
#include "subpixel_lanes.h"

sr_subpixel_verdict sr_subpixel_groups_avx2(const sr_subpixel_batch *b, int n, const sr_subpixel_rules *rules)
{
    return sr_subpixel_groups_sse2(b, n, rules);
}

/* Without AVX2 no group is taken whole: the caller decides each slot. */
sr_subpixel_slots sr_subpixel_slot_group_avx2(const uint32_t *indices, const sr_snapped_point *points,
                                              const sr_subpixel_rules *rules)
{
    (void)indices, (void)points, (void)rules;
    return (sr_subpixel_slots){ .plain = false };
}
#endif
