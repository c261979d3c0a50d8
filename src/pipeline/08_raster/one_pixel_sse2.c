/* The one-pixel depths at the SSE2 width (one_pixel_body.h). */
#define ONE_PIXEL_DEPTHS sr_one_pixel_depths_sse2
#include "one_pixel_body.h"
