/* The two halves' lanes at the SSE2 width: two lanes of double. */
#define VIEWPORT_LANES 2
#define VIEWPORT_FLOAT_LANES sr_viewport_float_lanes_sse2
#define VIEWPORT_DOUBLE_LANES sr_viewport_double_lanes_sse2
#include "06_viewport_body.h"
