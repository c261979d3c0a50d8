/* report_truth.h — the report's errors against the truth image
 * (truth.h): per knob, pixels whose visible triangle is not the truth's
 * though the truth's runner-up is more than a tie tolerance behind it,
 * pixels covered by one and not the other, and |z − truth| where both show
 * the same triangle. */
#ifndef SOFTRAST_STUDIES_REPORT_TRUTH_H
#define SOFTRAST_STUDIES_REPORT_TRUTH_H

#include <stdint.h>

#include "softrast_private.h"
#include "truth.h"

/* A gap in z_ndc (the knob's own) between the truth's nearest and
 * runner-up hits at or below this is a tie: either triangle is right. */
#define SR_REPORT_TIE_TOLERANCE 1e-6

typedef struct sr_truth_errors {
    uint64_t wrong_triangle; /* both drew, different triangles, truth's gap beyond the tie tolerance */
    uint64_t ties;           /* both drew, different triangles, within the tie tolerance */
    uint64_t coverage;       /* drawn by one of them only */
    double z_max, z_p999, z_median; /* |z_ndc − truth| where both drew the same triangle */
} sr_truth_errors;

/* The comparisons of one knob over its frames. */
typedef struct sr_truth_tally {
    sr_truth_errors counts;
    double *z_errors;
    size_t z_count, z_capacity;
} sr_truth_tally;

/* Compares the ids and depths fb holds (drawn with `projection`) with the
 * truth of the same camera. */
bool sr_truth_tally_add(sr_truth_tally *tally, const sr_truth_image *truth, const mat4 projection,
                        const sr_framebuffer *fb, sr_error *err);

/* The tally's errors, its percentiles taken; frees the tally. */
sr_truth_errors sr_truth_tally_finish(sr_truth_tally *tally);

#endif
