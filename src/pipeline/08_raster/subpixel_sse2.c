/* The sub-pixel lanes at the SSE2 width (subpixel_body.h). */
#define SUBPIXEL_LANES 4
#define SUBPIXEL_GROUPS sr_subpixel_groups_sse2
#include "subpixel_body.h"
