/* draw.h — a draw with what sr_draw does not take, for the program beside
 * the library. Not public API. */
#ifndef SOFTRAST_DRAW_DRAW_H
#define SOFTRAST_DRAW_DRAW_H

#include "pipeline/08_raster/raster_lines.h"
#include "softrast/softrast.h"

/* sr_draw, with every fragment of a line list or strip put first to
 * `filter` (raster_lines.h), which must outlive the call; the same checks,
 * threads and order as sr_draw. Points and triangles ignore it. */
bool sr_draw_lines_filtered(sr_framebuffer *fb, const sr_draw_desc *desc, const sr_line_filter *filter,
                            sr_stats *stats, sr_error *err);

#endif
