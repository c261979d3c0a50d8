/* The sub-pixel lanes (subpixel.h): the width a draw chose, and only the
 * lanes asked for. */
#include "subpixel.h"

sr_subpixel_verdict sr_subpixel_reject(const sr_subpixel_batch *b, int n, const sr_subpixel_rules *rules)
{
    sr_subpixel_verdict v = rules->avx512 ? sr_subpixel_groups_avx512(b, n, rules)
                            : rules->avx2 ? sr_subpixel_groups_avx2(b, n, rules)
                                          : sr_subpixel_groups_sse2(b, n, rules);
    uint64_t used = n >= SR_SUBPIXEL_BATCH ? ~(uint64_t)0 : ((uint64_t)1 << n) - 1;
    v.culled &= used;
    v.drawn &= used;
    v.one_pixel &= used;
    v.small_box &= used;
    return v;
}
