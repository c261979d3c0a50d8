/* tests/line_oracle.h — which points of a mesh's edges show, judged from
 * the mesh and the camera alone in double: a hidden-line oracle that knows
 * nothing of the rasterizer (test_wireframe.c).
 *
 * Every vertex goes to clip space in double (the desc's P·V·W·T(origin),
 * sr_vertex_clip_d). A triangle is drawn where the desc's culling keeps it
 * (the sign of det[x y w] of its corners: the orientation on screen of its
 * part in front of the eye) and, through a screen point, where its plane
 * meets the ray there with 0 ≤ z ≤ w (its part between the near and far
 * planes) inside it. A point of an edge shows when it lies in 0 ≤ z ≤ w
 * and no drawn triangle but the edge's own (those with both its end
 * positions) is nearer there by more than LINE_ORACLE_MARGIN in z_ndc: a
 * tie is a surface the edge lies in, which shows it. A grid of 8 × 8-pixel
 * cells of the triangles' screen boxes keeps the triangles each point
 * meets few. A perspective or orthographic camera, standard or reversed z.
 */
#ifndef SOFTRAST_TESTS_LINE_ORACLE_H
#define SOFTRAST_TESTS_LINE_ORACLE_H

#include <stdbool.h>
#include <stdint.h>

#include "softrast_private.h"

#define LINE_ORACLE_MARGIN 1e-9
/* Points of an edge looked at per pixel of its length on screen. */
#define LINE_ORACLE_SAMPLES 16

typedef struct line_oracle line_oracle;

/* The oracle of desc's mesh, camera, cull and front in a framebuffer of
 * width × height (reversed_z: nearer is greater z_ndc). NULL when out of
 * memory. */
line_oracle *line_oracle_make(const sr_draw_desc *desc, int width, int height, bool reversed_z);
void line_oracle_free(line_oracle *o);

/* Whether triangle slot k is drawn (kept by culling; not degenerate). */
bool line_oracle_drawn(const line_oracle *o, uint32_t k);

/* Whether a point of the edge between vertices a and b shows whose screen
 * position lies in pixel (x, y)'s square widened by `slack` pixels on
 * every side (what snapping may move an edge by); its points there
 * looked at every 1/LINE_ORACLE_SAMPLES pixel. */
bool line_oracle_shows_in(const line_oracle *o, uint32_t a, uint32_t b, int x, int y, double slack);

#endif
