/* framebuffer.h — the framebuffer's private part: what the pipeline needs
 * beyond softrast.h. Not public API. */
#ifndef SR_TARGET_FRAMEBUFFER_H
#define SR_TARGET_FRAMEBUFFER_H

#include <stdint.h>

#include "softrast/softrast.h"

/* sr_framebuffer_clear for rows [y0, y1) alone (the tiled path clears each
 * tile, a strip of whole rows, as it draws it). */
void sr_framebuffer_clear_rows(sr_framebuffer *fb, int y0, int y1, uint32_t color);

#endif
