#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <SDL.h>
#include <SDL_image.h>

#include "softrast/files.h"
#include "core/error.h"

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

/* Flushes and closes f, reporting the first failure (errno from a failed
 * write, or from flush/close: buffered data can still hit a full disk there).
 * A half-written file is removed so nobody mistakes it for a result. */
static bool finish_file(FILE *f, const char *path, bool ok, sr_error *err)
{
    int code = ok ? 0 : errno;
    if (fflush(f) != 0 && ok) {
        ok = false;
        code = errno;
    }
    if (fclose(f) != 0 && ok) {
        ok = false;
        code = errno;
    }
    if (ok)
        return true;
    remove(path);
    return sr_error_set(err, "%s: cannot write: %s", path, strerror(code ? code : EIO));
}

/* 0x00RRGGBB words → R, G, B bytes, the memory order of SDL_PIXELFORMAT_RGB24
 * and of a PNG of color type 2. Writing the bytes ourselves (rather than
 * letting SDL convert) keeps the layout independent of host byte order. */
static void fill_rgb24(SDL_Surface *s, const uint32_t *pixels)
{
    for (int y = 0; y < s->h; y++) {
        uint8_t *row = (uint8_t *)s->pixels + (size_t)y * (size_t)s->pitch;
        const uint32_t *src = pixels + (size_t)y * (size_t)s->w;
        for (int x = 0; x < s->w; x++) {
            row[RGB24_BYTES * x + 0] = (uint8_t)(src[x] >> 16);
            row[RGB24_BYTES * x + 1] = (uint8_t)(src[x] >> 8);
            row[RGB24_BYTES * x + 2] = (uint8_t)src[x];
        }
    }
}

/* IMG_SavePNG keeps a 24-bit surface without alpha as color type 2 (RGB). */
static bool save_surface(SDL_Surface *s, FILE *f)
{
    SDL_RWops *rw = SDL_RWFromFP(f, SDL_FALSE); /* we close f ourselves, to see fclose errors */
    if (!rw)
        return false;
    return IMG_SavePNG_RW(s, rw, 1) == 0;
}

bool sr_image_write_png(const char *path, const uint32_t *pixels, int width, int height, sr_error *err)
{
    if (!size_ok(path, width, height, err))
        return false;
    SDL_Surface *s = SDL_CreateRGBSurfaceWithFormat(0, width, height, 24, SDL_PIXELFORMAT_RGB24);
    if (!s)
        return sr_error_set(err, "%s: cannot write PNG: %s", path, SDL_GetError());
    fill_rgb24(s, pixels);
    FILE *f = fopen(path, "wb");
    if (!f) {
        int saved = errno;
        SDL_FreeSurface(s);
        return sr_error_set(err, "%s: cannot write: %s", path, strerror(saved));
    }
    bool saved_png = save_surface(s, f);
    SDL_FreeSurface(s);
    if (!saved_png) {
        fclose(f);
        remove(path);
        return sr_error_set(err, "%s: cannot write PNG: %s", path, SDL_GetError());
    }
    return finish_file(f, path, true, err);
}

/* Little-endian bytes of each float's bit pattern, whatever the host order. */
static void pack_le_floats(uint8_t *out, const float *src, int count)
{
    for (int i = 0; i < count; i++) {
        uint32_t bits;
        memcpy(&bits, &src[i], sizeof bits);
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
        pack_le_floats(row, depth + (size_t)y * (size_t)width, width);
        ok = fwrite(row, 1, row_bytes, f) == row_bytes;
    }
    free(row);
    return ok;
}

bool sr_image_write_pfm(const char *path, const float *depth, int width, int height, sr_error *err)
{
    if (!size_ok(path, width, height, err))
        return false;
    FILE *f = fopen(path, "wb");
    if (!f)
        return sr_error_set(err, "%s: cannot write: %s", path, strerror(errno));
    errno = 0;
    bool written = write_pfm_rows(f, depth, width, height);
    return finish_file(f, path, written, err);
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
