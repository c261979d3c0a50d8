/* stability_clip.h — the stability study's first section: the clippers' cut
 * vertices against exact cuts. */
#ifndef SOFTRAST_STUDIES_STABILITY_CLIP_H
#define SOFTRAST_STUDIES_STABILITY_CLIP_H

#include <stdbool.h>
#include <stdint.h>

#include "stability_cases.h"

/* Section 1: error of every cut vertex against the exact cut of the same
 * float edge by the same plane, ‖Δ‖∞ / ‖exact‖∞ (= |w| inside the clip
 * volume); a triangle's error is its largest cut's (stability_clip.c). */
typedef struct sr_stability_clip_stats {
    double max, p99;       /* over triangles */
    double worst_w;        /* exact w of the cut with the largest error */
    double worst_spread;   /* and how many times larger its end points are (‖·‖∞) */
    uint64_t triangles;    /* clipped triangles measured */
    uint64_t lost;         /* of those, clipped to nothing where the exact clipper keeps a polygon */
    sr_clip_counts cuts;   /* cut vertices by the precision actually used */
} sr_stability_clip_stats;

/* The NDC tolerance the adaptive clipper gets here: a 1920-pixel draw's. */
double sr_stability_clip_tolerance(void);

bool sr_stability_clip_errors(const sr_stability_case *c, sr_stability_clip_stats out[SR_STABILITY_CLIPPERS],
                              sr_error *err);

#endif
