/* The viewer's overlay: glyphs land on exact pixels, text/panels/lines never
 * write outside the canvas, and a clipped line draws exactly the on-canvas
 * pixels of the unclipped one, however far away its endpoints are. */
#include <criterion/criterion.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>

#include "app/view/overlay.h"

#define BG 0x00405060u
#define INK 0x00ffffffu
#define GUARD 0x00abcdefu
#define GUARD_PX 24 /* wider than a glyph, so a glyph clipped at an edge cannot jump it */
#define SUB 256     /* subpixels per pixel (SR_SUBPIXEL_BITS = 8) */
#define MAX_W 320
#define MAX_H 240

/* A canvas inside a larger buffer whose border is GUARD: any write outside the
 * canvas, including one that wraps past the end of a row, shows in the border. */
typedef struct guarded {
    uint32_t buf[(MAX_W + 2 * GUARD_PX) * (MAX_H + 2 * GUARD_PX)];
    sr_canvas c;
} guarded;

static guarded g;

static sr_canvas *guarded_canvas(int w, int h)
{
    int stride = w + 2 * GUARD_PX;
    for (int i = 0; i < stride * (h + 2 * GUARD_PX); i++)
        g.buf[i] = GUARD;
    g.c = (sr_canvas){ g.buf + GUARD_PX * stride + GUARD_PX, w, h, stride };
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            g.c.pixels[y * stride + x] = BG;
    return &g.c;
}

static uint32_t px(const sr_canvas *c, int x, int y)
{
    return c->pixels[y * c->stride + x];
}

static void assert_guard_intact(const sr_canvas *c)
{
    int stride = c->stride;
    for (int y = -GUARD_PX; y < c->height + GUARD_PX; y++)
        for (int x = -GUARD_PX; x < c->width + GUARD_PX; x++)
            if (x < 0 || y < 0 || x >= c->width || y >= c->height)
                cr_assert_eq(c->pixels[y * stride + x], GUARD, "wrote outside the canvas at (%d, %d)", x, y);
}

static void print_canvas(const sr_canvas *c)
{
    for (int y = 0; y < c->height; y++) {
        for (int x = 0; x < c->width; x++)
            fputc(px(c, x, y) == INK ? '#' : '.', stderr);
        fputc('\n', stderr);
    }
}

/* Compares the whole guarded canvas with a picture: '#' is INK, '.'
 * untouched, and nothing written around it. */
static void assert_picture(const sr_canvas *c, const char *const *rows)
{
    assert_guard_intact(c);
    for (int y = 0; y < c->height; y++) {
        cr_assert_eq((int)strlen(rows[y]), c->width, "picture row %d has the wrong width", y);
        for (int x = 0; x < c->width; x++) {
            uint32_t want = rows[y][x] == '#' ? INK : BG;
            if (px(c, x, y) != want) {
                print_canvas(c);
                cr_assert_fail("pixel (%d, %d) is %06x, expected %06x", x, y, px(c, x, y), want);
            }
        }
    }
}

static int count_ink(const sr_canvas *c)
{
    int n = 0;
    for (int y = 0; y < c->height; y++)
        for (int x = 0; x < c->width; x++)
            n += px(c, x, y) == INK;
    return n;
}

static bool same_pixels(const sr_canvas *a, const sr_canvas *b)
{
    for (int y = 0; y < a->height; y++)
        for (int x = 0; x < a->width; x++)
            if (px(a, x, y) != px(b, x, y))
                return false;
    return true;
}

/* A plain canvas (no guard) over buf, cleared to BG: the reference to compare with. */
static sr_canvas plain_canvas(uint32_t *buf, int w, int h)
{
    for (int i = 0; i < w * h; i++)
        buf[i] = BG;
    return (sr_canvas){ buf, w, h, w };
}

/* Line endpoint at the centre of pixel (i, j). */
static int64_t centre(int64_t i)
{
    return i * SUB + SUB / 2;
}

/* ---- text ---------------------------------------------------------------- */

Test(overlay, glyph_A_draws_its_exact_pixels_at_the_position)
{
    sr_canvas *c = guarded_canvas(9, 10);
    sr_overlay_text(c, 2, 1, "A", INK);
    assert_picture(c, (const char *const[]){
                          ".........",
                          "...###...",
                          "..#...#..",
                          "..#...#..",
                          "..#...#..",
                          "..#####..",
                          "..#...#..",
                          "..#...#..",
                          ".........",
                          ".........",
                      });
}

Test(overlay, glyph_1_draws_its_exact_pixels_at_the_position)
{
    sr_canvas *c = guarded_canvas(7, 8);
    sr_overlay_text(c, 1, 0, "1", INK);
    assert_picture(c, (const char *const[]){
                          "...#...",
                          "..##...",
                          "...#...",
                          "...#...",
                          "...#...",
                          "...#...",
                          "..###..",
                          ".......",
                      });
}

Test(overlay, text_clipped_at_every_edge_never_writes_outside)
{
    const char *text = "Wg@#\n|M_%";
    for (int y = -20; y <= 16; y++)
        for (int x = -30; x <= 24; x++) {
            sr_canvas *c = guarded_canvas(20, 12);
            sr_overlay_text(c, x, y, text, INK);
            assert_guard_intact(c);
        }
}

Test(overlay, clipped_text_shows_exactly_the_on_canvas_part)
{
    static guarded big_g;
    const char *text = "Hi{x}\nq~?";
    int off_x = -7, off_y = -5; /* the small canvas is a window into the big one */
    sr_canvas big = plain_canvas(big_g.buf, 40, 30);
    sr_overlay_text(&big, 4, 3, text, INK);
    sr_canvas *small = guarded_canvas(12, 9);
    sr_overlay_text(small, 4 + off_x, 3 + off_y, text, INK);
    for (int y = 0; y < small->height; y++)
        for (int x = 0; x < small->width; x++)
            cr_assert_eq(px(small, x, y), px(&big, x - off_x, y - off_y), "at (%d, %d)", x, y);
    assert_guard_intact(small);
}

Test(overlay, text_at_extreme_positions_draws_nothing_and_does_not_overflow)
{
    sr_canvas *c = guarded_canvas(16, 16);
    int far[] = { INT_MIN, INT_MIN + 1, -1000000, 1000000, INT_MAX - 1, INT_MAX };
    for (size_t i = 0; i < sizeof far / sizeof far[0]; i++)
        for (size_t j = 0; j < sizeof far / sizeof far[0]; j++)
            sr_overlay_text(c, far[i], far[j], "long line of text\nand another", INK);
    cr_assert_eq(count_ink(c), 0);
    assert_guard_intact(c);
}

Test(overlay, newline_starts_the_next_line_at_x)
{
    sr_canvas *c = guarded_canvas(40, 30);
    sr_overlay_text(c, 3, 2, "AB\nC", INK);
    static uint32_t expect_buf[40 * 30];
    sr_canvas expect = plain_canvas(expect_buf, 40, 30);
    sr_overlay_text(&expect, 3, 2, "A", INK);
    sr_overlay_text(&expect, 3 + SR_FONT_W, 2, "B", INK);
    sr_overlay_text(&expect, 3, 2 + SR_FONT_H, "C", INK);
    cr_assert(same_pixels(c, &expect));
}

Test(overlay, text_width_is_the_widest_line_and_height_counts_lines)
{
    cr_assert_eq(sr_overlay_text_width(""), 0);
    cr_assert_eq(sr_overlay_text_height(""), SR_FONT_H);
    cr_assert_eq(sr_overlay_text_width("abc"), 3 * SR_FONT_W);
    cr_assert_eq(sr_overlay_text_width("ab\nabcde\nx"), 5 * SR_FONT_W);
    cr_assert_eq(sr_overlay_text_height("ab\nabcde\nx"), 3 * SR_FONT_H);
    cr_assert_eq(sr_overlay_text_width("abcd\n"), 4 * SR_FONT_W);
    cr_assert_eq(sr_overlay_text_height("abcd\n"), 2 * SR_FONT_H);
    cr_assert_eq(sr_overlay_text_height("\n\n"), 3 * SR_FONT_H);
}

Test(overlay, every_printable_character_draws_inside_its_cell)
{
    for (int ch = '!'; ch <= '~'; ch++) {
        sr_canvas *c = guarded_canvas(SR_GLYPH_W, SR_GLYPH_H);
        char text[2] = { (char)ch, '\0' };
        sr_overlay_text(c, 0, 0, text, INK);
        cr_assert_gt(count_ink(c), 0, "'%c' draws nothing", ch);
        assert_guard_intact(c); /* the glyph stays within 5x7 */
    }
    sr_canvas *c = guarded_canvas(SR_GLYPH_W, SR_GLYPH_H);
    sr_overlay_text(c, 0, 0, " ", INK);
    cr_assert_eq(count_ink(c), 0, "space draws something");
}

Test(overlay, printable_characters_have_distinct_glyphs)
{
    for (int a = ' '; a <= '~'; a++)
        for (int b = a + 1; b <= '~'; b++)
            cr_assert(memcmp(sr_font_glyph(a), sr_font_glyph(b), SR_GLYPH_W) != 0, "'%c' and '%c' look the same",
                      a, b);
}

Test(overlay, non_printable_characters_draw_as_question_mark)
{
    const char *odd[] = { "\x01", "\t", "\r", "\x1f", "\x7f", "\x80", "\xff" };
    static uint32_t expect_buf[8 * 8];
    sr_canvas expect = plain_canvas(expect_buf, 8, 8);
    sr_overlay_text(&expect, 1, 1, "?", INK);
    for (size_t i = 0; i < sizeof odd / sizeof odd[0]; i++) {
        sr_canvas *c = guarded_canvas(8, 8);
        sr_overlay_text(c, 1, 1, odd[i], INK);
        cr_assert(same_pixels(c, &expect), "byte 0x%02x is not drawn as '?'", (unsigned char)odd[i][0]);
    }
}

/* ---- panel --------------------------------------------------------------- */

Test(overlay, panel_darkens_exactly_its_rectangle_to_a_quarter)
{
    sr_canvas *c = guarded_canvas(10, 8);
    c->pixels[2 * c->stride + 3] = 0x00ffffff;
    c->pixels[3 * c->stride + 4] = 0x00f0800c;
    sr_overlay_panel(c, 2, 1, 5, 4);
    for (int y = 0; y < c->height; y++)
        for (int x = 0; x < c->width; x++) {
            bool inside = x >= 2 && x < 7 && y >= 1 && y < 5;
            uint32_t want = inside ? 0x00101418 : BG; /* 0x405060 / 4 per channel */
            if (x == 3 && y == 2)
                want = 0x003f3f3f;
            if (x == 4 && y == 3)
                want = 0x003c2003;
            cr_assert_eq(px(c, x, y), want, "at (%d, %d)", x, y);
        }
    assert_guard_intact(c);
}

Test(overlay, panel_is_clipped_to_the_canvas)
{
    sr_canvas *c = guarded_canvas(10, 8);
    sr_overlay_panel(c, -5, -3, 9, 6);
    sr_overlay_panel(c, 8, 6, INT_MAX, INT_MAX);
    sr_overlay_panel(c, INT_MIN, INT_MIN, INT_MAX, INT_MAX); /* ends at -1, -1 */
    for (int y = 0; y < c->height; y++)
        for (int x = 0; x < c->width; x++) {
            bool inside = (x < 4 && y < 3) || (x >= 8 && y >= 6);
            cr_assert_eq(px(c, x, y), inside ? 0x00101418u : BG, "at (%d, %d)", x, y);
        }
    assert_guard_intact(c);
}

/* ---- lines --------------------------------------------------------------- */

Test(overlay, line_horizontal_covers_both_endpoints_exactly)
{
    sr_canvas *c = guarded_canvas(8, 3);
    sr_overlay_line(c, centre(1), centre(1), centre(6), centre(1), INK);
    assert_picture(c, (const char *const[]){ "........", ".######.", "........" });
}

Test(overlay, line_vertical_covers_both_endpoints_exactly)
{
    sr_canvas *c = guarded_canvas(3, 6);
    sr_overlay_line(c, centre(1), centre(4), centre(1), centre(0), INK);
    assert_picture(c, (const char *const[]){ ".#.", ".#.", ".#.", ".#.", ".#.", "..." });
}

Test(overlay, line_diagonal_steps_one_pixel_per_row)
{
    sr_canvas *c = guarded_canvas(6, 5);
    sr_overlay_line(c, centre(5), centre(0), centre(1), centre(4), INK);
    assert_picture(c, (const char *const[]){ ".....#", "....#.", "...#..", "..#...", ".#....", });
}

Test(overlay, line_shallow_slope_rounds_to_the_nearest_row)
{
    sr_canvas *c = guarded_canvas(9, 4);
    sr_overlay_line(c, centre(0), centre(0), centre(8), centre(3), INK); /* row = 3/8 of the column, rounded */
    assert_picture(c, (const char *const[]){ "##.......", "..##.....", "....###..", ".......##" });
}

Test(overlay, line_steep_slope_rounds_to_the_nearest_column)
{
    sr_canvas *c = guarded_canvas(3, 7);
    sr_overlay_line(c, centre(0), centre(0), centre(2), centre(6), INK);
    assert_picture(c, (const char *const[]){ "#..", "#..", ".#.", ".#.", ".#.", "..#", "..#" });
}

Test(overlay, line_endpoint_uses_the_pixel_containing_it)
{
    sr_canvas *c = guarded_canvas(6, 3);
    /* 1*256 + 255 is still pixel 1; -1 is pixel -1 (off canvas), not 0. */
    sr_overlay_line(c, 1 * SUB + 255, 1 * SUB, 4 * SUB, 1 * SUB + 255, INK);
    sr_overlay_line(c, -1, 0, -1, 2 * SUB, INK);
    sr_overlay_line(c, 5 * SUB, -1, 5 * SUB, -SUB, INK);
    assert_picture(c, (const char *const[]){ "......", ".####.", "......" });
}

Test(overlay, line_single_pixel_when_endpoints_share_a_pixel)
{
    sr_canvas *c = guarded_canvas(4, 3);
    sr_overlay_line(c, 2 * SUB + 3, SUB + 200, 2 * SUB + 250, SUB + 9, INK);
    assert_picture(c, (const char *const[]){ "....", "..#.", "...." });
}

Test(overlay, line_draws_the_same_pixels_in_both_directions)
{
    int64_t ends[][4] = { { 0, 0, 8, 3 }, { 0, 0, 3, 8 }, { 7, 1, 0, 6 }, { 2, 9, 5, 0 }, { 0, 0, 4, 2 } };
    for (size_t i = 0; i < sizeof ends / sizeof ends[0]; i++) {
        static uint32_t fwd_buf[10 * 10];
        sr_canvas fwd = plain_canvas(fwd_buf, 10, 10);
        int64_t *e = ends[i];
        sr_overlay_line(&fwd, centre(e[0]), centre(e[1]), centre(e[2]), centre(e[3]), INK);
        sr_canvas *back = guarded_canvas(10, 10);
        sr_overlay_line(back, centre(e[2]), centre(e[3]), centre(e[0]), centre(e[1]), INK);
        cr_assert(same_pixels(&fwd, back), "line %zu differs when reversed", i);
    }
}

Test(overlay, line_entirely_off_canvas_draws_nothing)
{
    sr_canvas *c = guarded_canvas(16, 12);
    sr_overlay_line(c, centre(-5), centre(-3), centre(-1), centre(40), INK);   /* left */
    sr_overlay_line(c, centre(-10), centre(-1), centre(40), centre(-1), INK);  /* above */
    sr_overlay_line(c, centre(16), centre(0), centre(30), centre(11), INK);    /* right */
    sr_overlay_line(c, centre(0), centre(12), centre(15), centre(200), INK);   /* below */
    sr_overlay_line(c, centre(-2), centre(1), centre(1), centre(-2), INK);     /* past the corner */
    sr_overlay_line(c, centre(15), centre(13), centre(17), centre(11), INK);   /* past the far corner */
    cr_assert_eq(count_ink(c), 0);
    assert_guard_intact(c);
}

/* A simple pseudo-random sequence so the property runs on the same lines every time. */
static uint32_t next_random(uint32_t *state)
{
    *state = *state * 1664525u + 1013904223u;
    return *state >> 8;
}

Test(overlay, clipped_line_draws_exactly_the_unclipped_lines_pixels)
{
    /* The small canvas is a window at (win_x, win_y) into the big one, which
     * holds every line whole: the window must match pixel for pixel. */
    static guarded big_g;
    enum { BIG = 200, WIN_W = 37, WIN_H = 23, WIN_X = 81, WIN_Y = 90 };
    uint32_t seed = 12345;
    for (int n = 0; n < 1000; n++) {
        sr_canvas big = plain_canvas(big_g.buf, BIG, BIG);
        int64_t e[4];
        for (int k = 0; k < 4; k++)
            e[k] = next_random(&seed) % (BIG * SUB);
        sr_overlay_line(&big, e[0], e[1], e[2], e[3], INK);
        sr_canvas *win = guarded_canvas(WIN_W, WIN_H);
        sr_overlay_line(win, e[0] - WIN_X * SUB, e[1] - WIN_Y * SUB, e[2] - WIN_X * SUB, e[3] - WIN_Y * SUB, INK);
        for (int y = 0; y < WIN_H; y++)
            for (int x = 0; x < WIN_W; x++)
                cr_assert_eq(px(win, x, y), px(&big, x + WIN_X, y + WIN_Y),
                             "line (%lld,%lld)-(%lld,%lld): window pixel (%d, %d) differs", (long long)e[0],
                             (long long)e[1], (long long)e[2], (long long)e[3], x, y);
        assert_guard_intact(win);
    }
}

/* The pixel the line from pixel (i0, j0) to (i1, j1) draws in major column
 * `at`, straight from the definition (round t * rise / len half up, from the
 * lower major end), in 128-bit arithmetic. Swapped roles for y-major lines. */
static int64_t reference_minor(int64_t a0, int64_t b0, int64_t a1, int64_t b1, int64_t at)
{
    if (a1 < a0) {
        int64_t ta = a0, tb = b0;
        a0 = a1, b0 = b1, a1 = ta, b1 = tb;
    }
    __int128 len = a1 - a0, t = at - a0, rise = b1 >= b0 ? b1 - b0 : b0 - b1;
    int64_t off = (int64_t)((2 * t * rise + len) / (2 * len));
    return b1 >= b0 ? b0 + off : b0 - off;
}

static int64_t floor_pixel(int64_t v)
{
    return v >= 0 ? v / SUB : -((-v + SUB - 1) / SUB);
}

/* Draws a line with far endpoints and checks every canvas pixel against the
 * reference; returns how many pixels it drew. */
static int check_far_line(int64_t x0, int64_t y0, int64_t x1, int64_t y1)
{
    sr_canvas *c = guarded_canvas(64, 48);
    sr_overlay_line(c, x0, y0, x1, y1, INK);
    int64_t i0 = floor_pixel(x0), j0 = floor_pixel(y0), i1 = floor_pixel(x1), j1 = floor_pixel(y1);
    int64_t di = i1 > i0 ? i1 - i0 : i0 - i1, dj = j1 > j0 ? j1 - j0 : j0 - j1;
    bool x_major = di >= dj;
    for (int y = 0; y < c->height; y++)
        for (int x = 0; x < c->width; x++) {
            int64_t minor = x_major ? reference_minor(i0, j0, i1, j1, x) : reference_minor(j0, i0, j1, i1, y);
            bool on = x_major ? minor == y : minor == x;
            cr_assert_eq(px(c, x, y), on ? INK : BG, "far line: pixel (%d, %d) should be %s", x, y,
                         on ? "drawn" : "untouched");
        }
    assert_guard_intact(c);
    return count_ink(c);
}

Test(overlay, line_with_far_endpoints_draws_exactly_its_canvas_segment, .timeout = 2)
{
    const int64_t far = (int64_t)1 << 36;
    /* Through pixel (20, 15): shallow and steep, rising to the right. */
    cr_assert_eq(check_far_line(centre(20) - 3 * far, centre(15) - far + 77, centre(20) + 3 * far + 5,
                                centre(15) + far - 901),
                 64);
    cr_assert_eq(check_far_line(centre(20) - far / 6, centre(15) - far, centre(20) + far / 6 + 3, centre(15) + far),
                 48);
    /* Through pixel (30, 20) and (40, 30), falling to the left. */
    cr_assert_gt(check_far_line(centre(30) - far, centre(20) + far + 1234, centre(30) + far, centre(20) - far + 99), 0);
    cr_assert_eq(check_far_line(centre(40) + far / 3 + 17, centre(30) - far, centre(40) - far / 3, centre(30) + far),
                 48);
}

Test(overlay, line_with_extreme_int64_endpoints_is_safe, .timeout = 2)
{
    sr_canvas *c = guarded_canvas(32, 24);
    sr_overlay_line(c, INT64_MIN, INT64_MIN, INT64_MAX, INT64_MAX, INK);
    sr_overlay_line(c, INT64_MIN, INT64_MAX, INT64_MAX, INT64_MIN, INK);
    sr_overlay_line(c, INT64_MIN, centre(5), INT64_MAX, centre(5), INK);
    sr_overlay_line(c, centre(7), INT64_MAX, centre(7), INT64_MIN, INK);
    sr_overlay_line(c, INT64_MAX, INT64_MAX, INT64_MAX, INT64_MIN, INK);
    /* The horizontal and vertical ones cross the whole canvas. */
    for (int x = 0; x < c->width; x++)
        cr_assert_eq(px(c, x, 5), INK, "row 5 missing at x = %d", x);
    for (int y = 0; y < c->height; y++)
        cr_assert_eq(px(c, 7, y), INK, "column 7 missing at y = %d", y);
    assert_guard_intact(c);
}
