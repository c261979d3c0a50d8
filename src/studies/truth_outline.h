/* truth_outline.h — a triangle's outline on screen as the truth sees it: its
 * part between the near and far planes (view space, double), projected to
 * pixels, a convex polygon of at most 5 corners; and how far a pixel centre
 * lies from it. The report tells a coverage tie of fixed-point snapping from
 * a real error by it (report_truth.h).
 *
 * Everything is double arithmetic on the truth's view-space vertices: a
 * distance is off by a few units in the last place of the pixel
 * coordinates (about 1e-12 px at 1920 pixels), far below any tolerance it
 * is compared with. */
#ifndef SOFTRAST_STUDIES_TRUTH_OUTLINE_H
#define SOFTRAST_STUDIES_TRUTH_OUTLINE_H

#include <stdbool.h>
#include <stdint.h>

#include "truth.h"

/* A triangle cut by two planes keeps at most 3 + 2 corners. */
#define SR_TRUTH_OUTLINE_CORNERS 5

/* The corners of slot `slot`'s outline in pixels (x right, y down), in
 * order around it; their count, 0 when it has none (fewer than 3). */
int sr_truth_outline_corners(const sr_truth_image *t, uint32_t slot, double out[SR_TRUTH_OUTLINE_CORNERS][2]);

/* Where a point (pixels, as a pixel centre (x + 0.5, y + 0.5)) lies against
 * the outline of slot `slot` of t's mesh: its distance in pixels to the
 * outline, and whether it lies inside (a point on the outline counts as
 * inside). The distance is +inf, and inside false, when the slot holds no
 * triangle with a part between the planes. */
typedef struct sr_truth_outline_place {
    double distance;
    bool inside;
} sr_truth_outline_place;

sr_truth_outline_place sr_truth_outline_locate(const sr_truth_image *t, uint32_t slot, const double point[2]);

#endif
