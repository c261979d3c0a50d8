/* overlay.c — text, panels and clipped lines over a 0x00RRGGBB image.
 *
 * Positions are widened to int64 before any arithmetic so that text or panels
 * placed near INT_MAX, and lines with endpoints anywhere in int64, never
 * overflow; everything is clipped against the canvas before pixels are
 * visited, so the work is bounded by the canvas size, not by the input.
 */
#include "overlay.h"

#include <stdbool.h>

#include "softrast_private.h"

#define PANEL_SHIFT 2                /* panel keeps 1/4 brightness: each channel >> 2 */
#define PANEL_MASK 0x003f3f3fu       /* drops the bits shifted in from the next channel */

static int canvas_stride(const sr_canvas *c)
{
    return c->stride > 0 ? c->stride : c->width;
}

static bool canvas_contains(const sr_canvas *c, int64_t x, int64_t y)
{
    return x >= 0 && y >= 0 && x < c->width && y < c->height;
}

/* Callers have checked canvas_contains. */
static void canvas_put(sr_canvas *c, int64_t x, int64_t y, uint32_t color)
{
    c->pixels[y * canvas_stride(c) + x] = color;
}

static int64_t max64(int64_t a, int64_t b) { return a > b ? a : b; }
static int64_t min64(int64_t a, int64_t b) { return a < b ? a : b; }

/* ---- text ---------------------------------------------------------------- */

static void draw_glyph(sr_canvas *c, int64_t x, int64_t y, int ch, uint32_t color)
{
    const uint8_t *columns = sr_font_glyph(ch);
    for (int col = 0; col < SR_GLYPH_W; col++)
        for (int row = 0; row < SR_GLYPH_H; row++)
            if ((columns[col] >> row) & 1 && canvas_contains(c, x + col, y + row))
                canvas_put(c, x + col, y + row, color);
}

static bool glyph_may_show(const sr_canvas *c, int64_t x, int64_t y)
{
    return x + SR_GLYPH_W > 0 && y + SR_GLYPH_H > 0 && x < c->width && y < c->height;
}

void sr_overlay_text(sr_canvas *c, int x, int y, const char *text, uint32_t color)
{
    int64_t pen_x = x, pen_y = y;
    /* Lines only move down, so once below the canvas nothing more can show. */
    for (const char *p = text; *p && pen_y < c->height; p++) {
        if (*p == '\n') {
            pen_x = x;
            pen_y += SR_FONT_H;
            continue;
        }
        if (glyph_may_show(c, pen_x, pen_y))
            draw_glyph(c, pen_x, pen_y, (unsigned char)*p, color);
        pen_x += SR_FONT_W;
    }
}

int sr_overlay_text_width(const char *text)
{
    int widest = 0, chars = 0;
    for (const char *p = text;; p++) {
        if (*p == '\n' || *p == '\0') {
            widest = chars > widest ? chars : widest;
            chars = 0;
            if (*p == '\0')
                return widest * SR_FONT_W;
        } else {
            chars++;
        }
    }
}

int sr_overlay_text_height(const char *text)
{
    int lines = 1;
    for (const char *p = text; *p; p++)
        lines += *p == '\n';
    return lines * SR_FONT_H;
}

/* ---- panel --------------------------------------------------------------- */

void sr_overlay_panel(sr_canvas *c, int x, int y, int w, int h)
{
    int64_t x0 = max64(x, 0), x1 = min64((int64_t)x + w, c->width);
    int64_t y0 = max64(y, 0), y1 = min64((int64_t)y + h, c->height);
    for (int64_t py = y0; py < y1; py++) {
        uint32_t *row = c->pixels + py * canvas_stride(c);
        for (int64_t px = x0; px < x1; px++)
            row[px] = (row[px] >> PANEL_SHIFT) & PANEL_MASK;
    }
}

/* ---- line ---------------------------------------------------------------- */

/* The line is walked one pixel at a time along its major axis (the one with
 * the larger extent). After t steps the minor axis has moved
 *     offset(t) = floor((2 t rise + len) / (2 len))     (t * rise / len, rounded half up)
 * pixels, the pixel-centre DDA that Bresenham computes incrementally. Because
 * offset(t) is a closed form, clipping can jump straight to the first visible
 * t and draw exactly the pixels the unclipped walk would have drawn there. */
typedef struct line_walk {
    int64_t major0, minor0; /* start pixel; the major coordinate grows with t */
    int64_t len;            /* major steps from start to end pixel, >= 0 */
    int64_t rise;           /* |minor steps|, <= len */
    int minor_dir;          /* +1 or -1 */
    bool x_major;
} line_walk;

/* Which pixel a subpixel coordinate falls in: floor(v / 256), without relying
 * on how >> treats negative numbers. */
static int64_t pixel_of(int64_t v)
{
    int64_t q = v / SR_SUBPIXEL_ONE;
    return q - (v % SR_SUBPIXEL_ONE < 0);
}

static line_walk line_walk_make(int64_t i0, int64_t j0, int64_t i1, int64_t j1)
{
    /* Pixel coordinates are within ±2^55, so these differences cannot overflow. */
    int64_t di = i1 - i0, dj = j1 - j0;
    line_walk l = { .x_major = (di < 0 ? -di : di) >= (dj < 0 ? -dj : dj) };
    int64_t a0 = l.x_major ? i0 : j0, b0 = l.x_major ? j0 : i0;
    int64_t a1 = l.x_major ? i1 : j1, b1 = l.x_major ? j1 : i1;
    if (a1 < a0) { /* walk from the lower end, so A->B and B->A draw the same pixels */
        int64_t ta = a0, tb = b0;
        a0 = a1, b0 = b1, a1 = ta, b1 = tb;
    }
    l.major0 = a0;
    l.minor0 = b0;
    l.len = a1 - a0;
    l.rise = b1 >= b0 ? b1 - b0 : b0 - b1;
    l.minor_dir = b1 >= b0 ? 1 : -1;
    return l;
}

/* a * b = *quot * n + *rem, for 0 <= a and 0 <= b <= n, without forming a * b
 * (which can need 113 bits): long multiplication in base 2, keeping the
 * running product as quotient and remainder. Every intermediate stays < 2n. */
static void mul_divmod(int64_t a, int64_t b, int64_t n, int64_t *quot, int64_t *rem)
{
    int64_t q = 0, r = 0;
    for (int bit = 62; bit >= 0; bit--) {
        q *= 2, r *= 2;
        if (r >= n)
            q++, r -= n;
        if ((a >> bit) & 1) {
            r += b;
            if (r >= n)
                q++, r -= n;
        }
    }
    *quot = q;
    *rem = r;
}

/* Walk state at step t: offset(t) = q + (r >= len), with t * 2 rise = q * 2 len + r. */
typedef struct walk_pos {
    int64_t q, r;
} walk_pos;

static walk_pos walk_at(const line_walk *l, int64_t t)
{
    walk_pos w = { 0, 0 };
    if (l->len > 0)
        mul_divmod(t, 2 * l->rise, 2 * l->len, &w.q, &w.r);
    return w;
}

static int64_t walk_offset(const line_walk *l, walk_pos w)
{
    return w.q + (l->len > 0 && w.r >= l->len);
}

/* The smallest t in [0, len] with offset(t) >= k, or len + 1 if none:
 * offset never decreases, so a binary search finds it. */
static int64_t first_step_reaching(const line_walk *l, int64_t k)
{
    int64_t lo = 0, hi = l->len + 1;
    while (lo < hi) {
        int64_t mid = lo + (hi - lo) / 2;
        if (walk_offset(l, walk_at(l, mid)) >= k)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

/* The steps [*t_first, *t_last] whose pixels lie on the canvas (empty when
 * *t_first > *t_last): the major bound is direct, the minor bound inverts
 * the monotonic offset. */
static void walk_clip(const line_walk *l, int64_t major_size, int64_t minor_size, int64_t *t_first,
                      int64_t *t_last)
{
    /* Offsets that keep minor0 + minor_dir * offset inside [0, minor_size). */
    int64_t k_lo = l->minor_dir > 0 ? -l->minor0 : l->minor0 - (minor_size - 1);
    int64_t k_hi = l->minor_dir > 0 ? minor_size - 1 - l->minor0 : l->minor0;
    *t_first = max64(max64(0, -l->major0), first_step_reaching(l, k_lo));
    *t_last = min64(min64(l->len, major_size - 1 - l->major0), first_step_reaching(l, k_hi + 1) - 1);
}

void sr_overlay_line(sr_canvas *c, int64_t x0, int64_t y0, int64_t x1, int64_t y1, uint32_t color)
{
    if (c->width <= 0 || c->height <= 0)
        return;
    line_walk l = line_walk_make(pixel_of(x0), pixel_of(y0), pixel_of(x1), pixel_of(y1));
    int64_t major_size = l.x_major ? c->width : c->height;
    int64_t minor_size = l.x_major ? c->height : c->width;
    int64_t t_first, t_last;
    walk_clip(&l, major_size, minor_size, &t_first, &t_last);
    if (t_first > t_last)
        return;
    walk_pos w = walk_at(&l, t_first);
    int64_t step = 2 * l.rise, period = 2 * l.len;
    for (int64_t t = t_first; t <= t_last; t++) {
        int64_t major = l.major0 + t;
        int64_t minor = l.minor0 + l.minor_dir * walk_offset(&l, w);
        canvas_put(c, l.x_major ? major : minor, l.x_major ? minor : major, color);
        /* Bresenham's increment: offset(t + 1) from offset(t) without a multiply. */
        w.r += step;
        if (w.r >= period)
            w.q++, w.r -= period;
    }
}
