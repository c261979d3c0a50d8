/* The slot lanes at the AVX-512 width, sixteen slots a group, built with
 * AVX-512 (the Makefile adds it for this file on x86-64) and chosen only
 * where the draw's SIMD level has it (sr_subpixel_rules.avx512). */
#if defined(__AVX512F__)
#define SUBPIXEL_LANES 16
#define SUBPIXEL_GROUPS sr_subpixel_groups_avx512
#include "subpixel_body.h"
#else
#include "subpixel_lanes.h"

sr_subpixel_verdict sr_subpixel_groups_avx512(const sr_subpixel_batch *b, int n, const sr_subpixel_rules *rules)
{
    return sr_subpixel_groups_avx2(b, n, rules);
}

/* Without AVX-512 no group is taken whole: the caller decides each slot. */
sr_subpixel_slots sr_subpixel_slot_group_avx512(const uint32_t *indices, const sr_snapped_point *points,
                                                const sr_subpixel_rules *rules)
{
    (void)indices, (void)points, (void)rules;
    return (sr_subpixel_slots){ .plain = false };
}
#endif
