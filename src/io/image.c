#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <png.h>

#include "softrast/files.h"
#include "core/error.h"
#include "output_file.h"

#define RGB24_BYTES 3
#define FLOAT32_BYTES 4
/* Largest image side the writers accept; matches the framebuffer limit. */
#define SR_MAX_IMAGE_SIDE SR_MAX_FRAMEBUFFER_SIDE

static bool size_ok(const char *path, int width, int height, sr_error *err)
{
    if (width < 1 || height < 1 || width > SR_MAX_IMAGE_SIDE || height > SR_MAX_IMAGE_SIDE)
        return sr_error_set(err, "%s: cannot write an image of size %dx%d", path, width, height);
    return true;
}

/* 0x00RRGGBB words → R, G, B bytes, the layout of libpng's PNG_FORMAT_RGB
 * (color type 2), whatever the host byte order. */
static void pack_rgb24(uint8_t *out, const uint32_t *pixels, size_t count)
{
    for (size_t i = 0; i < count; i++) {
        out[RGB24_BYTES * i + 0] = (uint8_t)(pixels[i] >> 16);
        out[RGB24_BYTES * i + 1] = (uint8_t)(pixels[i] >> 8);
        out[RGB24_BYTES * i + 2] = (uint8_t)pixels[i];
    }
}

/* libpng's simplified writer with PNG_IMAGE_FLAG_FAST: zlib's fastest level
 * and cheap row filters. A flight's --shots spent most of its time in the
 * default compression, for files not much smaller (docs/batch.md). */
/* One PNG of the simplified API's `format` from its buffer, through the
 * safe output file. */
static bool write_png_format(const char *path, const void *buffer, png_uint_32 format, int width, int height,
                             sr_error *err)
{
    sr_output o;
    if (!sr_output_open(&o, path, err))
        return false;
    png_image png = { .version = PNG_IMAGE_VERSION, .width = (png_uint_32)width, .height = (png_uint_32)height,
                      .format = format, .flags = PNG_IMAGE_FLAG_FAST };
    errno = 0;
    bool written = png_image_write_to_stdio(&png, o.f, 0, buffer, 0, NULL) != 0;
    if (!written && !errno)
        errno = EIO;
    if (!written && png.message[0])
        sr_error_set(err, "%s: cannot write PNG: %s", path, png.message);
    png_image_free(&png);
    return sr_output_close(&o, path, written, written || !png.message[0] ? err : NULL);
}

bool sr_image_write_png(const char *path, const uint32_t *pixels, int width, int height, sr_error *err)
{
    if (!size_ok(path, width, height, err))
        return false;
    size_t count = (size_t)width * (size_t)height;
    uint8_t *rgb = malloc(count * RGB24_BYTES);
    if (!rgb)
        return sr_error_set(err, "%s: out of memory for a %dx%d image", path, width, height);
    pack_rgb24(rgb, pixels, count);
    bool ok = write_png_format(path, rgb, PNG_FORMAT_RGB, width, height, err);
    free(rgb);
    return ok;
}

bool sr_image_write_png16(const char *path, const uint16_t *values, int width, int height, sr_error *err)
{
    return size_ok(path, width, height, err) &&
           write_png_format(path, values, PNG_FORMAT_LINEAR_Y, width, height, err);
}

/* Little-endian bytes of each 4-byte word (a float's bit pattern, or a
 * uint32), whatever the host order. */
static void pack_le_words(uint8_t *out, const void *src, size_t count)
{
    for (size_t i = 0; i < count; i++) {
        uint32_t bits;
        memcpy(&bits, (const uint8_t *)src + FLOAT32_BYTES * i, sizeof bits);
        for (int b = 0; b < FLOAT32_BYTES; b++)
            out[FLOAT32_BYTES * i + b] = (uint8_t)(bits >> (8 * b));
    }
}

/* PFM stores rows bottom to top; scale -1 in the header means little-endian. */
static bool write_pfm_rows(FILE *f, const float *depth, int width, int height)
{
    size_t row_bytes = (size_t)width * FLOAT32_BYTES;
    uint8_t *row = malloc(row_bytes);
    if (!row) {
        errno = ENOMEM;
        return false;
    }
    bool ok = fprintf(f, "Pf\n%d %d\n-1\n", width, height) > 0;
    for (int y = height - 1; ok && y >= 0; y--) {
        pack_le_words(row, depth + (size_t)y * (size_t)width, (size_t)width);
        ok = fwrite(row, 1, row_bytes, f) == row_bytes;
    }
    free(row);
    return ok;
}

bool sr_image_write_pfm(const char *path, const float *depth, int width, int height, sr_error *err)
{
    if (!size_ok(path, width, height, err))
        return false;
    sr_output o;
    if (!sr_output_open(&o, path, err))
        return false;
    errno = 0;
    bool written = write_pfm_rows(o.f, depth, width, height);
    return sr_output_close(&o, path, written, err);
}

/* NumPy's format, version 1.0: magic, version, a little-endian header
 * length, then a Python dict literal padded with spaces to a multiple of 64
 * bytes and ended by a newline; the values follow in C order, each 4 bytes
 * little-endian (a float's bit pattern, or a uint32). */
static bool write_npy_values(FILE *f, const void *words, const char *descr, int width, int height,
                             int channels)
{
    char dict[160], shape[64];
    snprintf(shape, sizeof shape, channels > 1 ? "(%d, %d, %d)" : "(%d, %d)", height, width, channels);
    int n = snprintf(dict, sizeof dict, "{'descr': '%s', 'fortran_order': False, 'shape': %s, }", descr, shape);
    int header = 10 + n + 1, padded = (header + 63) / 64 * 64;
    uint16_t dict_len = (uint16_t)(padded - 10);
    uint8_t lead[10] = { 0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0, (uint8_t)dict_len, (uint8_t)(dict_len >> 8) };
    bool ok = fwrite(lead, 1, sizeof lead, f) == sizeof lead && fputs(dict, f) >= 0 &&
              fprintf(f, "%*s\n", padded - header, "") > 0;
    size_t row_words = (size_t)width * (size_t)channels, row_bytes = row_words * FLOAT32_BYTES;
    uint8_t *row = ok ? malloc(row_bytes) : NULL;
    if (ok && !row) {
        errno = ENOMEM;
        return false;
    }
    for (int y = 0; ok && y < height; y++) {
        pack_le_words(row, (const uint8_t *)words + (size_t)y * row_bytes, row_words);
        ok = fwrite(row, 1, row_bytes, f) == row_bytes;
    }
    free(row);
    return ok;
}

bool sr_image_write_npy(const char *path, const void *values, sr_npy_type type, int width, int height,
                        int channels, sr_error *err)
{
    if (!size_ok(path, width, height, err))
        return false;
    if (channels < 1 || channels > 4)
        return sr_error_set(err, "%s: cannot write %d channels", path, channels);
    sr_output o;
    if (!sr_output_open(&o, path, err))
        return false;
    errno = 0;
    bool written = write_npy_values(o.f, values, type == SR_NPY_UINT32 ? "<u4" : "<f4", width, height, channels);
    return sr_output_close(&o, path, written, err);
}

bool sr_image_write_depth_png(const char *path, const sr_framebuffer *fb, sr_error *err)
{
    if (!size_ok(path, fb->width, fb->height, err))
        return false;
    uint32_t *gray = malloc((size_t)fb->width * (size_t)fb->height * sizeof *gray);
    if (!gray)
        return sr_error_set(err, "%s: out of memory for a %dx%d depth image", path,
                            fb->width, fb->height);
    sr_framebuffer_depth_to_gray(fb, gray);
    bool ok = sr_image_write_png(path, gray, fb->width, fb->height, err);
    free(gray);
    return ok;
}
