/* raster_lines.h — stages 8 and 9 for points and lines: coverage by
 * Direct3D 11's rules, the depth test and shading, one pixel at a time.
 *
 * A line covers the pixels whose diamond it exits (the diamond-exit rule):
 * pixel (i, j)'s diamond is |x − cx| + |y − cy| < ½ around its centre, with,
 * as Direct3D draws aliased lines, its two lower edges and bottom corner
 * in it (y down) and, for a y-major line, its right corner too; a segment
 * covers the pixel when it meets the diamond and its end point does not
 * lie in it, so a strip's shared vertex is drawn once. Exact in the
 * snapped coordinates (integers, 128-bit products). A line W pixels wide
 * (a whole number) repeats each pixel of the thin line over W pixels
 * across its minor axis (rows for an x-major line), from −⌊(W − 1)/2⌋.
 *
 * A point covers the pixel centres in the square of its size centred on
 * its snapped position, the left and top sides in it and the right and
 * bottom out (the top-left rule of the square's two triangles), cut to the
 * framebuffer.
 *
 * A line fragment takes the values at the pixel centre's projection on the
 * segment (the parameter t, clamped to [0, 1]): depth linear in t, the
 * varyings perspective-correct through 1/w; a point's fragments take the
 * point's. Every fragment is moved `depth_bias` nearer, then tested (LESS,
 * GREATER for reversed z) and written as a triangle's are, the id + 1
 * into the framebuffer's ids plane where it has one. The loop is
 * scalar: one thread draws every point and line, in submission order.
 */
#ifndef SOFTRAST_PIPELINE_RASTER_LINES_H
#define SOFTRAST_PIPELINE_RASTER_LINES_H

#include <stdint.h>

#include "pipeline/10_shade.h"

typedef struct sr_point_line_target {
    sr_framebuffer *fb;
    sr_shade mode; /* a shading mode or SR_RASTER_COUNT_HITS (raster.h) */
    const sr_shade_context *shade;
    int subpixel_bits;
    float depth_bias; /* >= 0, z_ndc */
} sr_point_line_target;

/* Draws the segment a -> b, `width` pixels wide (>= 1); returns the
 * fragments that passed the depth test. */
uint64_t sr_raster_line(const sr_point_line_target *t, const sr_screen_vertex *a, const sr_screen_vertex *b,
                        int width, uint32_t id);

/* Draws a point `size` pixels square (>= 1); returns the fragments that
 * passed the depth test. */
uint64_t sr_raster_point(const sr_point_line_target *t, const sr_screen_vertex *p, float size, uint32_t id);

#endif
