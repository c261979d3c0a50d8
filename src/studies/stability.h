/* stability.h — `softrast bench --stability`: how the pipeline holds up under
 * stiff cameras, written as docs/stability.md and docs/stability.svg.
 *
 * Three measurements, one file each:
 *   stability_clip.c   error of every cut vertex of each clipper precision
 *                      (sr_clip_precision) against the exact cut of the same
 *                      float edge by the same plane;
 *   stability_grid.c   holes (cracks, lost triangles) and double hits on a
 *                      flat grid under each case;
 *   stability_depth.c  the smallest plane separation the depth test orders,
 *                      standard against reversed z.
 * stability_cases.c defines the stiff cases the first two share;
 * stability_doc.c and stability_svg.c write the files. Each has its header.
 */
#ifndef SOFTRAST_APP_STABILITY_H
#define SOFTRAST_APP_STABILITY_H

#include <stdbool.h>
#include <stdint.h>

#include "softrast_private.h"

/* Runs every measurement and writes stability.md and stability.svg into dir. */
bool sr_stability_write(const char *dir, sr_error *err);

#endif
