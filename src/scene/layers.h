/* layers.h — a mesh drawn as its materials mean it (docs/conventions.md,
 * "Blending"): the parts of glTF's OPAQUE and MASK materials first, in one
 * draw, then each part of a BLEND material in a draw of its own, farthest
 * first by the distance from the eye of its bounds' centre, alpha-blended
 * over what is drawn, depth-tested and writing no depth and no ids. */
#ifndef SOFTRAST_SCENE_LAYERS_H
#define SOFTRAST_SCENE_LAYERS_H

#include <stdbool.h>

#include "softrast/softrast.h"

/* Draws desc so. A desc that already blends or keeps its depth, a shading
 * that ignores materials, a mesh of no BLEND part, of strips or of clip
 * positions: one sr_draw of desc as it is. stats gets every draw's counts
 * (each triangle counted once: a BLEND part's triangles are left out of
 * the first draw as degenerate slots, so ids stay the file's). */
bool sr_layers_draw(sr_framebuffer *fb, const sr_draw_desc *desc, sr_stats *stats, sr_error *err);

#endif
