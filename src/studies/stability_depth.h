/* stability_depth.h — the stability study's third section: the smallest
 * separation the depth test orders. */
#ifndef SOFTRAST_STUDIES_STABILITY_DEPTH_H
#define SOFTRAST_STUDIES_STABILITY_DEPTH_H

#include <stdbool.h>
#include <stdint.h>

#include "stability_cases.h"

/* Section 3: smallest separation s/d that the depth test orders, or NAN when
 * none up to s = d is (stability_depth.c). */
typedef struct sr_stability_depth {
    double ratio[SR_STABILITY_RATIOS];
    double fraction[SR_STABILITY_DISTANCES];
    double separation[SR_STABILITY_RATIOS][SR_STABILITY_DISTANCES][SR_STABILITY_MAPPINGS];
    double distance[SR_STABILITY_RATIOS][SR_STABILITY_DISTANCES]; /* d, as a float holds it */
    double floor[SR_STABILITY_RATIOS][SR_STABILITY_DISTANCES];    /* one float step of d, relative to d */
} sr_stability_depth;

bool sr_stability_depth_table(sr_stability_depth *out, sr_error *err);

#endif
