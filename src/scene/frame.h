/* frame.h — one frame as a viewer pays for it, timed: what `render
 * --frames`, the viewer's frame time and the benchmark all measure, so
 * their figures mean the same thing. */
#ifndef SOFTRAST_SCENE_FRAME_H
#define SOFTRAST_SCENE_FRAME_H

#include <stdbool.h>

#include "softrast/softrast.h"

/* Clears color (to 0) and depth, then draws, timed into *ms. stats, when
 * given, is zeroed first. */
bool sr_frame_draw_timed(sr_framebuffer *fb, const sr_draw_desc *desc, sr_stats *stats, double *ms, sr_error *err);

/* The same, desc drawn as its materials mean it: BLEND parts blended
 * over the others, farthest first (sr_draw_layered). */
bool sr_frame_draw_layers_timed(sr_framebuffer *fb, const sr_draw_desc *desc, sr_stats *stats, double *ms,
                                sr_error *err);

#endif
