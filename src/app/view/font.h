/* font.h — the overlay's 5x7 pixel font for printable ASCII (font.c). */
#ifndef SOFTRAST_VIEW_FONT_H
#define SOFTRAST_VIEW_FONT_H

#include <stdint.h>

#define SR_GLYPH_W 5 /* glyph bitmap size, px */
#define SR_GLYPH_H 7
#define SR_FONT_W 6 /* advance per character, px (5 px glyph + 1 px gap) */
#define SR_FONT_H 9 /* line height, px (7 px glyph + 2 px gap) */
#define SR_FONT_FIRST 32 /* ' ', the first printable ASCII character */
#define SR_FONT_LAST 126 /* '~', the last */

/* The 5 column bitmaps of a character's glyph (bit 0 = top row); '?' for
 * anything outside 32..126. */
const uint8_t *sr_font_glyph(int ch);

#endif
