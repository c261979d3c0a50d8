/* stability_grid.h — the stability study's second section: holes and double
 * hits on a flat grid. */
#ifndef SOFTRAST_STUDIES_STABILITY_GRID_H
#define SOFTRAST_STUDIES_STABILITY_GRID_H

#include <stdbool.h>
#include <stdint.h>

#include "stability_cases.h"

/* Section 2: hits per pixel of the grid (stability_grid.c). */
typedef struct sr_stability_hits {
    bool measured;        /* false: the case has no graded grid */
    uint64_t inside;      /* pixels at least 1 px inside the grid's visible region */
    uint64_t holes;       /* of those, hit 0 times (cracks, or triangles lost) */
    uint64_t double_hits; /* pixels anywhere hit 2 or more times */
    sr_stats stats;       /* the draw's */
} sr_stability_hits;

bool sr_stability_grid_hits(const sr_stability_case *c, bool graded, const sr_stability_clipper *clipper,
                            sr_stability_hits *out, sr_error *err);

#endif
