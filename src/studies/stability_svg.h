/* stability_svg.h — the stability study's depth table as an SVG plot. */
#ifndef SOFTRAST_STUDIES_STABILITY_SVG_H
#define SOFTRAST_STUDIES_STABILITY_SVG_H

#include <stdbool.h>
#include <stdint.h>

#include "stability_depth.h"

/* The depth table as a plot (stability_svg.c). */
bool sr_stability_svg(const char *path, const sr_stability_depth *d, sr_error *err);

#endif
