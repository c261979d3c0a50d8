/* The lane pixels at the SSE2 width (lane_pixels_body.h). */
#define LANE_PIXELS sr_lane_pixels_sse2
#include "lane_pixels_body.h"
