/* overlay.h — text, lines and panels drawn over a 0x00RRGGBB image.
 *
 * The viewer draws its help text, status line and the wireframe of clipped
 * triangles on top of the rendered image with these. They write into a plain
 * pixel array the caller owns (row 0 at the top) and need nothing beyond libc:
 * no SDL, no allocation, no errors to report. Everything is clipped to the
 * canvas, so any position is safe, however far off the canvas it lies.
 *
 *   sr_canvas c = { fb_pixels, width, height };      (stride 0 = width)
 *   sr_overlay_panel(&c, 4, 4, sr_overlay_text_width(msg) + 4,
 *                    sr_overlay_text_height(msg) + 4);
 *   sr_overlay_text(&c, 6, 6, msg, 0xffffff);
 *   sr_overlay_line(&c, v[0].x, v[0].y, v[1].x, v[1].y, 0xff00ff);
 *
 * Text uses a fixed 5x7 pixel font (font.c) with one pixel between characters
 * and two between lines.
 */
#ifndef SOFTRAST_APP_OVERLAY_H
#define SOFTRAST_APP_OVERLAY_H

#include <stdint.h>

#include "font.h"

typedef struct sr_canvas {
    uint32_t *pixels; /* 0x00RRGGBB, row 0 at the top */
    int width, height;
    int stride; /* pixels from one row to the next; 0 means width */
} sr_canvas;

/* Draws text with its top-left corner at (x, y). '\n' starts a new line at x;
 * bytes outside 32..126 draw as '?'. Only glyph pixels are written. */
void sr_overlay_text(sr_canvas *c, int x, int y, const char *text, uint32_t color);
int sr_overlay_text_width(const char *text);  /* widest line: characters * SR_FONT_W, px */
int sr_overlay_text_height(const char *text); /* lines * SR_FONT_H, px; "" is one line */

/* Darkens the rectangle to 1/4 brightness, like translucent black, so text
 * on it stays readable over any image. */
void sr_overlay_panel(sr_canvas *c, int x, int y, int w, int h);

/* A 1-px line between the pixels containing the endpoints, both included.
 * Endpoints are in 1/256 pixel units (SR_SUBPIXEL_BITS, as sr_screen_vertex),
 * pixel (i, j) spanning [i*256, i*256 + 256) x [j*256, j*256 + 256). Any int64
 * endpoint works: the line is clipped to the canvas before it is walked, and
 * the pixels drawn are exactly the on-canvas pixels of the unclipped line. */
void sr_overlay_line(sr_canvas *c, int64_t x0, int64_t y0, int64_t x1, int64_t y1, uint32_t color);

#endif
