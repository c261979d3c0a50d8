#define _DEFAULT_SOURCE /* madvise's MADV_HUGEPAGE */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#include "softrast/softrast.h"
#include "core/error.h"
#include "framebuffer.h"

/* The depth view: the nearest written depth is white, the farthest a dark gray
 * that still stands apart from the black background. */
#define SR_GRAY_NEAR 255
#define SR_GRAY_FAR 48
#define SR_GRAY_BACKGROUND 0

static size_t pixel_count(const sr_framebuffer *fb)
{
    return (size_t)fb->width * (size_t)fb->height;
}

static bool side_in_range(int side)
{
    return side >= 1 && side <= SR_MAX_FRAMEBUFFER_SIDE;
}

float sr_framebuffer_depth_clear(const sr_framebuffer *fb)
{
    return fb->reversed_z ? SR_DEPTH_CLEAR_REVERSED : SR_DEPTH_CLEAR;
}

/* A pixel holds a drawn depth only if something passed the depth test against
 * the clear value; NaN and inf never count (they cannot come from a draw). */
static bool depth_is_written(const sr_framebuffer *fb, float d)
{
    return isfinite(d) && (fb->reversed_z ? d > SR_DEPTH_CLEAR_REVERSED : d < SR_DEPTH_CLEAR);
}

/* Buffers of a few MB are walked row by row, two 4 KiB pages a 1920-pixel
 * row: on huge pages (where the kernel gives them on request) the TLB
 * stops missing. Zeroed, like calloc. */
#define HUGE_PAGE ((size_t)2 << 20)

static void *plane_alloc(size_t bytes)
{
    if (bytes < HUGE_PAGE)
        return calloc(1, bytes);
    size_t rounded = (bytes + HUGE_PAGE - 1) / HUGE_PAGE * HUGE_PAGE;
    void *p = NULL;
    if (posix_memalign(&p, HUGE_PAGE, rounded) != 0)
        return NULL;
#ifdef MADV_HUGEPAGE
    madvise(p, rounded, MADV_HUGEPAGE);
#endif
    memset(p, 0, rounded);
    return p;
}

bool sr_framebuffer_create(sr_framebuffer *fb, int width, int height, sr_error *err)
{
    *fb = (sr_framebuffer){ 0 };
    if (!side_in_range(width) || !side_in_range(height))
        return sr_error_set(err, "framebuffer size %dx%d is out of range (each side 1..%d)",
                            width, height, SR_MAX_FRAMEBUFFER_SIDE);
    size_t n = (size_t)width * (size_t)height;
    /* Only a 32-bit size_t can overflow here (16384^2 * 4 bytes = 1 GiB). */
    if (n > SIZE_MAX / sizeof(uint32_t) || n > SIZE_MAX / sizeof(float))
        return sr_error_set(err, "framebuffer size %dx%d is too large for this machine",
                            width, height);
    fb->color = plane_alloc(n * sizeof *fb->color);
    fb->depth = plane_alloc(n * sizeof *fb->depth);
    if (!fb->color || !fb->depth) {
        sr_framebuffer_destroy(fb);
        return sr_error_set(err, "out of memory for a %dx%d framebuffer", width, height);
    }
    fb->width = width;
    fb->height = height;
    return true;
}

bool sr_framebuffer_create_ids(sr_framebuffer *fb, sr_error *err)
{
    if (fb->ids)
        return true;
    fb->ids = plane_alloc(pixel_count(fb) * sizeof *fb->ids);
    return fb->ids || sr_error_set(err, "out of memory for the ids of a %dx%d framebuffer", fb->width, fb->height);
}

void sr_framebuffer_destroy(sr_framebuffer *fb)
{
    free(fb->color);
    free(fb->depth);
    free(fb->ids);
    *fb = (sr_framebuffer){ 0 };
}

/* n copies of the 4-byte value at `to`: a few stored one by one, then
 * copied onto the rest in doubling blocks (memcpy stores whole vectors; gcc
 * at -O2 stored the plain loop 4 bytes at a time). */
static void fill_words(void *to, uint32_t value, size_t n)
{
    uint32_t *w = to;
    size_t done = n < 16 ? n : 16;
    for (size_t i = 0; i < done; i++)
        w[i] = value;
    while (done < n) {
        size_t step = done < n - done ? done : n - done;
        memcpy(w + done, w, step * sizeof *w);
        done += step;
    }
}

void sr_framebuffer_clear_rows(sr_framebuffer *fb, int y0, int y1, uint32_t color)
{
    size_t first = (size_t)y0 * (size_t)fb->width, n = (size_t)(y1 - y0) * (size_t)fb->width;
    fill_words(fb->color + first, color, n);
    float clear = sr_framebuffer_depth_clear(fb);
    uint32_t clear_bits;
    memcpy(&clear_bits, &clear, sizeof clear_bits);
    fill_words(fb->depth + first, clear_bits, n);
    if (fb->ids)
        memset(fb->ids + first, 0, n * sizeof *fb->ids);
}

void sr_framebuffer_clear(sr_framebuffer *fb, uint32_t color)
{
    sr_framebuffer_clear_rows(fb, 0, fb->height, color);
}

bool sr_framebuffer_depth_range(const sr_framebuffer *fb, float *lo, float *hi)
{
    size_t n = pixel_count(fb);
    bool any = false;
    float min = 0.0f, max = 0.0f;
    for (size_t i = 0; i < n; i++) {
        float d = fb->depth[i];
        if (!depth_is_written(fb, d))
            continue;
        if (!any || d < min)
            min = d;
        if (!any || d > max)
            max = d;
        any = true;
    }
    if (any) {
        *lo = min;
        *hi = max;
    }
    return any;
}

static uint32_t gray_pixel(long g)
{
    uint32_t v = (uint32_t)g;
    return v << 16 | v << 8 | v;
}

/* Linear in the mapped value from SR_GRAY_NEAR at lo to SR_GRAY_FAR at hi,
 * rounded to nearest. Double precision keeps the end points exact. */
static uint32_t value_gray(double v, double lo, double hi)
{
    if (!(hi > lo))
        return gray_pixel(SR_GRAY_NEAR);
    double t = (v - lo) / (hi - lo);
    return gray_pixel(lround(SR_GRAY_NEAR - t * (SR_GRAY_NEAR - SR_GRAY_FAR)));
}

static double identity(float z, const void *ctx)
{
    (void)ctx;
    return z;
}

/* Reversed depth grows toward the eye; negated, it grows with distance. */
static double negated(float z, const void *ctx)
{
    (void)ctx;
    return -(double)z;
}

void sr_framebuffer_depth_to_gray_mapped(const sr_framebuffer *fb, sr_depth_map map, const void *ctx, uint32_t *out)
{
    size_t n = pixel_count(fb);
    float zlo = 0.0f, zhi = 0.0f;
    sr_framebuffer_depth_range(fb, &zlo, &zhi);
    /* The maps are monotonic, so the range maps end to end (maybe swapped). */
    double lo = map(zlo, ctx), hi = map(zhi, ctx);
    if (lo > hi) {
        double t = lo;
        lo = hi;
        hi = t;
    }
    for (size_t i = 0; i < n; i++) {
        float d = fb->depth[i];
        out[i] = depth_is_written(fb, d) ? value_gray(map(d, ctx), lo, hi) : gray_pixel(SR_GRAY_BACKGROUND);
    }
}

void sr_framebuffer_depth_to_gray(const sr_framebuffer *fb, uint32_t *out)
{
    sr_framebuffer_depth_to_gray_mapped(fb, fb->reversed_z ? negated : identity, NULL, out);
}
