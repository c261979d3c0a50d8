/* stability_doc.h — the stability study's results, written as docs/stability.md. */
#ifndef SOFTRAST_STUDIES_STABILITY_DOC_H
#define SOFTRAST_STUDIES_STABILITY_DOC_H

#include <stdbool.h>
#include <stdint.h>

#include "stability_clip.h"
#include "stability_depth.h"
#include "stability_grid.h"

typedef struct sr_stability_report {
    sr_stability_clip_stats clip[SR_STABILITY_CASES][SR_STABILITY_CLIPPERS];
    sr_stability_hits hits[SR_STABILITY_CASES][SR_STABILITY_GRIDS][SR_STABILITY_CLIPPERS];
    sr_stability_depth depth;
    double seconds; /* the whole run */
} sr_stability_report;

bool sr_stability_files(const char *dir, const sr_stability_report *r, sr_error *err);

#endif
