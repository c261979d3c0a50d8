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
 * point's depth and the varyings its vertex has (nothing to interpolate,
 * so no division by w and back). Every fragment is moved `depth_bias`
 * nearer, then tested (LESS, GREATER for reversed z) and written as a
 * triangle's are, the id + 1 into the framebuffer's ids plane where it
 * has one. A line draw may first put each fragment to a test of its own
 * (sr_line_filter: the hidden-line frame's, app/wireframe.h), which drops
 * it or moves its depth.
 *
 * A fragment is stored at once, or, when the target has bins, appended to
 * the bin of its band of rows, to be stored later by the thread that owns
 * the band (sr_raster_fragments): the bins of a band, taken in submission
 * order, give each pixel its fragments in the order one thread would have
 * stored them, so the pixels are the same on every thread count.
 */
#ifndef SOFTRAST_PIPELINE_RASTER_LINES_H
#define SOFTRAST_PIPELINE_RASTER_LINES_H

#include <stdint.h>

#include "core/array.h"
#include "pipeline/10_shade.h"

/* One fragment, shaded, waiting for its depth test: 16 bytes. */
typedef struct sr_fragment {
    uint32_t at;    /* y · width + x */
    float z;        /* z_ndc, biased and clamped to [0, 1] */
    uint32_t color; /* packed, its alpha (11_merge.h) in the top byte; or unused (depth shading, SR_RASTER_COUNT_HITS) */
    uint32_t id;    /* the primitive's slot */
} sr_fragment;

/* A line draw's own test of each line fragment, before the depth test:
 * keep(user, line slot, x, y, &z) with z the fragment's depth (biased)
 * drops it (false) or keeps it, with z as it leaves it. Called by the
 * threads that make fragments, several at once and in no order: it may
 * only read. */
typedef struct sr_line_filter {
    bool (*keep)(const void *user, uint32_t line, int x, int y, float *z);
    const void *user;
} sr_line_filter;

typedef struct sr_point_line_target {
    sr_framebuffer *fb;
    sr_shade mode; /* a shading mode or SR_RASTER_COUNT_HITS (raster_setup.h) */
    const sr_shade_context *shade;
    int subpixel_bits;
    float depth_bias; /* >= 0, z_ndc */
    const sr_line_filter *filter; /* NULL: none */
    sr_array *bins;   /* NULL: store each fragment at once; else one sr_fragment array per band of rows */
    int band_rows;    /* with bins: the rows of a band */
    bool out_of_memory; /* a bin could not grow: fragments were lost */
} sr_point_line_target;

/* Draws the segment a -> b, `width` pixels wide (>= 1); returns the
 * fragments that passed the depth test (none when binned). */
uint64_t sr_raster_line(sr_point_line_target *t, const sr_screen_vertex *a, const sr_screen_vertex *b, int width,
                        uint32_t id);

/* Draws a point `size` pixels square (>= 1) with the vertex's varyings
 * `var`; returns the fragments that passed the depth test (none when
 * binned). */
uint64_t sr_raster_point(sr_point_line_target *t, const sr_screen_vertex *p, const float *var, float size,
                         uint32_t id);

/* A point of size 1: the one pixel centre in its square, if on the
 * framebuffer, without the general square's set-up; the same fragment as
 * sr_raster_point's. */
uint64_t sr_raster_point_pixel(sr_point_line_target *t, const sr_screen_vertex *p, const float *var, uint32_t id);

/* Stores n fragments in order (depth test and writes); returns how many
 * passed. */
uint64_t sr_raster_fragments(const sr_point_line_target *t, const sr_fragment *f, size_t n);

#endif
