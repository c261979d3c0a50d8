#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <SDL.h>
#include <SDL_image.h>
#include <png.h>

#include "softrast/files.h"
#include "core/error.h"
#include "core/input_file.h"
#include "texture_read.h"

#define RGB_MASK 0x00FFFFFFu

/* The extension as IMG_Load would pass it, so formats without a magic number
 * (TGA) are still recognised when the file is read through our own stream. */
static const char *file_extension(const char *path)
{
    const char *dot = strrchr(path, '.');
    const char *slash = strrchr(path, '/');
    if (!dot || (slash && dot < slash))
        return NULL;
    return dot + 1;
}

/* Refused before any texel is allocated: an empty image, a side over
 * SR_MAX_TEXTURE_SIDE or more than SR_MAX_TEXTURE_TEXELS in all. */
static bool size_allowed(const char *path, unsigned long width, unsigned long height, sr_error *err)
{
    if (width < 1 || height < 1)
        return sr_error_set(err, "%s: texture is empty (%lux%lu)", path, width, height);
    if (width > SR_MAX_TEXTURE_SIDE || height > SR_MAX_TEXTURE_SIDE)
        return sr_error_set(err, "%s: texture is %lux%lu, larger than %d on a side", path, width, height,
                            SR_MAX_TEXTURE_SIDE);
    if (width * height > SR_MAX_TEXTURE_TEXELS)
        return sr_error_set(err, "%s: texture is %lux%lu, more than %lu texels in all", path, width, height,
                            (unsigned long)SR_MAX_TEXTURE_TEXELS);
    return true;
}

/* libpng's byte order for a 0x00RRGGBB word as this host stores it. */
static png_uint_32 texel_format(void)
{
    const uint32_t probe = 1;
    return *(const unsigned char *)&probe ? PNG_FORMAT_BGRA : PNG_FORMAT_ARGB;
}

/* A PNG through libpng's simplified API, which reads the header alone first
 * (so the size is checked before anything is allocated) and reports every
 * error through png.message: nothing on stderr, which SDL_image's libpng
 * use would print to. 16-bit files without gamma information are taken as
 * sRGB, as SDL_image took them. Alpha is dropped, not blended. Closes f. */
static bool load_png(sr_texture *tex, FILE *f, const char *path, sr_error *err)
{
    png_image png = { .version = PNG_IMAGE_VERSION, .flags = PNG_IMAGE_FLAG_16BIT_sRGB };
    bool ok = png_image_begin_read_from_stdio(&png, f) ||
              sr_error_set(err, "%s: not a readable image: %s", path, png.message);
    ok = ok && size_allowed(path, png.width, png.height, err);
    size_t count = (size_t)png.width * png.height;
    if (ok && !(tex->texels = malloc(count * sizeof *tex->texels)))
        ok = sr_error_set(err, "%s: out of memory for a %ux%u texture", path, (unsigned)png.width,
                          (unsigned)png.height);
    png.format = texel_format();
    if (ok && !png_image_finish_read(&png, NULL, tex->texels, 0, NULL))
        ok = sr_error_set(err, "%s: not a readable image: %s", path, png.message);
    png_image_free(&png);
    fclose(f);
    if (!ok)
        return false;
    for (size_t i = 0; i < count; i++)
        tex->texels[i] &= RGB_MASK;
    tex->width = (int)png.width;
    tex->height = (int)png.height;
    return true;
}

/* Any other format through SDL_image (which prints nothing of its own for
 * them). Closes f. */
static SDL_Surface *load_surface(FILE *f, const char *path, sr_error *err)
{
    SDL_RWops *rw = SDL_RWFromFP(f, SDL_TRUE);
    if (!rw) {
        fclose(f);
        sr_error_set(err, "%s: cannot open: %s", path, SDL_GetError());
        return NULL;
    }
    SDL_Surface *s = IMG_LoadTyped_RW(rw, 1, file_extension(path));
    if (!s)
        sr_error_set(err, "%s: not a readable image: %s", path, IMG_GetError());
    return s;
}

/* SDL_PIXELFORMAT_RGB888 is a packed 32-bit 0xXXRRGGBB word in host order, so
 * each pixel reads directly as a texel; rows are pitch bytes apart. Alpha, if
 * the file had any, is dropped (the conversion copies, it does not blend). */
static void copy_texels(uint32_t *dst, const SDL_Surface *s)
{
    for (int y = 0; y < s->h; y++) {
        const uint8_t *row = (const uint8_t *)s->pixels + (size_t)y * (size_t)s->pitch;
        uint32_t *out = dst + (size_t)y * (size_t)s->w;
        memcpy(out, row, (size_t)s->w * sizeof *out);
        for (int x = 0; x < s->w; x++)
            out[x] &= RGB_MASK;
    }
}

/* tex from the loaded image; tex is left empty when that fails. */
static bool texels_from_surface(sr_texture *tex, SDL_Surface *loaded, const char *path, sr_error *err)
{
    if (!size_allowed(path, (unsigned long)loaded->w, (unsigned long)loaded->h, err))
        return false;
    SDL_Surface *rgb = SDL_ConvertSurfaceFormat(loaded, SDL_PIXELFORMAT_RGB888, 0);
    if (!rgb)
        return sr_error_set(err, "%s: cannot convert the image to RGB: %s", path, SDL_GetError());
    tex->texels = malloc((size_t)rgb->w * (size_t)rgb->h * sizeof *tex->texels);
    if (!tex->texels) {
        SDL_FreeSurface(rgb);
        return sr_error_set(err, "%s: out of memory for a %dx%d texture", path, rgb->w, rgb->h);
    }
    copy_texels(tex->texels, rgb);
    tex->width = rgb->w;
    tex->height = rgb->h;
    SDL_FreeSurface(rgb);
    return true;
}

static bool load_other(sr_texture *tex, FILE *f, const char *path, sr_error *err)
{
    SDL_Surface *loaded = load_surface(f, path, err);
    bool ok = loaded && texels_from_surface(tex, loaded, path, err);
    SDL_FreeSurface(loaded); /* NULL is fine */
    return ok;
}

static bool is_png(FILE *f)
{
    png_byte signature[8];
    bool png = fread(signature, 1, sizeof signature, f) == sizeof signature &&
               png_sig_cmp(signature, 0, sizeof signature) == 0;
    rewind(f);
    return png;
}

bool sr_texture_read(sr_texture *tex, FILE *f, const char *name, sr_error *err)
{
    *tex = (sr_texture){ 0 };
    bool ok = is_png(f) ? load_png(tex, f, name, err) : load_other(tex, f, name, err);
    if (!ok)
        sr_texture_free(tex);
    return ok;
}

/* Opening the file ourselves gives a clean strerror for a missing or
 * unreadable file (SDL_image would only say "Couldn't open") and refuses
 * what is not a regular file. Neither decoder needs SDL_Init, so this works
 * headless. */
bool sr_texture_load(sr_texture *tex, const char *path, sr_error *err)
{
    *tex = (sr_texture){ 0 };
    const char *why;
    FILE *f = sr_input_open(path, &why);
    if (!f)
        return sr_error_set(err, "%s: cannot open: %s", path, why);
    return sr_texture_read(tex, f, path, err);
}

void sr_texture_free(sr_texture *tex)
{
    free(tex->texels);
    *tex = (sr_texture){ 0 };
}
