/* The resolve's triangle lanes in SSE2 registers, two to a lane group. */
#define PINHOLE_TRIANGLES sr_pinhole_triangles_sse2
#include "pinhole_triangles_body.h"
