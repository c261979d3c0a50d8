/* materials.h — a mesh's materials as per-material shading contexts
 * (materials.c). Not public API. */
#ifndef SOFTRAST_DRAW_MATERIALS_H
#define SOFTRAST_DRAW_MATERIALS_H

#include "draw_state.h"

/* False, with one line in err, for materials a draw cannot take: an
 * unknown alpha mode, a number that is not finite, a texture of a bad
 * size, a part naming a material past the table, parts out of order. */
bool sr_materials_check(const sr_mesh *mesh, sr_error *err);

/* Whether a material draws a texture with texels: its own, or, for one
 * with a texture_path and no texture, desc_texture. */
bool sr_materials_textured(const sr_mesh *mesh, const sr_texture *desc_texture);

/* The layout l of a draw in id, depth, normal or colour shading with the
 * uvs added after its own varyings where a MASK material (or BLEND in a
 * draw that replaces) has a texture with alpha: its alpha test reads them
 * (sr_shade_context.cut). Any other draw's l as it is. */
sr_varying_layout sr_materials_layout(sr_shade mode, const sr_draw_desc *d, sr_varying_layout l);

/* In lambert and texture shading, and in id, depth, normal and colour
 * shading of a mesh with a MASK material (or BLEND in a draw that
 * replaces), a context per material in the workspace, hung on st->shade
 * (which every other field of theirs copies); other draws ignore
 * materials. False when out of memory. */
bool sr_materials_make(sr_draw_state *st, sr_error *err);

#endif
