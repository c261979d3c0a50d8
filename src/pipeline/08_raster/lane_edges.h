/* lane_edges.h — an edge function at pixel centres in lanes of 32-bit
 * integers, a triangle a lane, for the bodies that test centres so
 * (subpixel_body.h, lane_pixels_body.h). The includer defines `lanes`
 * (int32_t lanes) and `ulanes` (uint32_t lanes of the same width) first.
 * Not public API. */
#ifndef SOFTRAST_PIPELINE_LANE_EDGES_H
#define SOFTRAST_PIPELINE_LANE_EDGES_H

/* a − b, wrapping. */
static SR_ALWAYS_INLINE ulanes minus(lanes a, lanes b)
{
    return (ulanes)a - (ulanes)b;
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
