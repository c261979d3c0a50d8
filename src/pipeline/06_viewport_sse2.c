/* The float half's lanes at the SSE2 width: two lanes of double. */
#define VIEWPORT_LANES 2
#define VIEWPORT_FLOAT_LANES sr_viewport_float_lanes_sse2
#include "06_viewport_body.h"
