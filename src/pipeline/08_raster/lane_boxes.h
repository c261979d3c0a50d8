/* lane_boxes.h — a triangle's scan box and its edge functions at pixel
 * centres in lanes of 32-bit integers, a triangle a lane, for the bodies
 * that test centres so (subpixel_body.h, lane_pixels_body.h): the same
 * integers as the set-up's (triangle_setup.h). The includer defines
 * `lanes` (int32_t lanes) and `ulanes` (uint32_t lanes of the same width)
 * first. Not public API. */
#ifndef SOFTRAST_PIPELINE_LANE_BOXES_H
#define SOFTRAST_PIPELINE_LANE_BOXES_H

/* a where m is all ones, b where it is 0. */
static SR_ALWAYS_INLINE lanes pick(lanes m, lanes a, lanes b)
{
    return (a & m) | (b & ~m);
}

static SR_ALWAYS_INLINE lanes min_of(lanes a, lanes b)
{
    return pick(a < b, a, b);
}

static SR_ALWAYS_INLINE lanes max_of(lanes a, lanes b)
{
    return pick(a > b, a, b);
}

/* a − b, wrapping. */
static SR_ALWAYS_INLINE ulanes minus(lanes a, lanes b)
{
    return (ulanes)a - (ulanes)b;
}

/* sr_raster_scan_box_of on one axis: the pixels [*from, *to) whose
 * centres lie from lo to hi (subpixel coordinates), clamped to
 * [first, end]. */
static SR_ALWAYS_INLINE void scan_span(lanes lo, lanes hi, int bits, int first, int end, lanes *from, lanes *to)
{
    const lanes zero = { 0 }, one = zero + ((int32_t)1 << bits), half = zero + ((int32_t)1 << bits) / 2;
    *from = min_of(max_of((lo - half + one - 1) >> bits, zero + first), zero + end);
    *to = min_of(max_of(((hi - half) >> bits) + 1, zero + first), zero + end);
}

/* E − bias for edge p → q of a clockwise triangle at the pixel centre
 * (cx, cy), >= 0 where the edge holds the centre: E = dx·(cy − py) −
 * dy·(cx − px) is sr_edge_make's a·cx + b·cy + c, and the bias is 0 on a top
 * (dy = 0, dx > 0) or left (dy < 0) edge and 1 otherwise (E >= bias). */
static SR_ALWAYS_INLINE lanes edge_at(lanes px, lanes py, lanes qx, lanes qy, lanes cx, lanes cy)
{
    lanes dx = qx - px, dy = qy - py, zero = { 0 };
    lanes top_left = ((dy == zero) & (dx > zero)) | (dy < zero); /* all ones where the bias is 0 */
    return (lanes)((ulanes)dx * minus(cy, py) - (ulanes)dy * minus(cx, px) - (ulanes)(top_left + 1));
}

#endif
