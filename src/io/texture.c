#include <fcntl.h>
#include <unistd.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <SDL.h>
#include <SDL_image.h>

#include "softrast/files.h"
#include "core/error.h"
#include "core/input_file.h"

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

/* SDL_image leaves libpng's default error handler in place, which prints
 * "libpng error: ..." on stderr before SDL_image returns its own error; that
 * would make a corrupt texture two lines where softrast promises one. stderr
 * is pointed at /dev/null for the decode only (textures load on the calling
 * thread, before any drawing), and the message comes back through
 * IMG_GetError. */
static SDL_Surface *decode_quietly(SDL_RWops *rw, const char *type)
{
    fflush(stderr);
    int saved = dup(STDERR_FILENO), null = open("/dev/null", O_WRONLY);
    if (saved >= 0 && null >= 0)
        dup2(null, STDERR_FILENO);
    SDL_Surface *s = IMG_LoadTyped_RW(rw, 1, type);
    if (saved >= 0 && null >= 0)
        dup2(saved, STDERR_FILENO);
    if (saved >= 0)
        close(saved);
    if (null >= 0)
        close(null);
    return s;
}

/* Opening the file ourselves gives a clean strerror for a missing or
 * unreadable file; SDL_image would only say "Couldn't open". IMG_Load needs
 * no SDL_Init (it initialises its own decoders), so this works headless. */
static SDL_Surface *load_surface(const char *path, sr_error *err)
{
    const char *why;
    FILE *f = sr_input_open(path, &why);
    if (!f) {
        sr_error_set(err, "%s: cannot open: %s", path, why);
        return NULL;
    }
    SDL_RWops *rw = SDL_RWFromFP(f, SDL_TRUE);
    if (!rw) {
        fclose(f);
        sr_error_set(err, "%s: cannot open: %s", path, SDL_GetError());
        return NULL;
    }
    SDL_Surface *s = decode_quietly(rw, file_extension(path));
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

static bool texels_from_surface(sr_texture *tex, SDL_Surface *loaded, const char *path, sr_error *err)
{
    if (loaded->w > SR_MAX_TEXTURE_SIDE || loaded->h > SR_MAX_TEXTURE_SIDE)
        return sr_error_set(err, "%s: texture is %dx%d, larger than %d on a side",
                            path, loaded->w, loaded->h, SR_MAX_TEXTURE_SIDE);
    if (loaded->w < 1 || loaded->h < 1)
        return sr_error_set(err, "%s: texture is empty (%dx%d)", path, loaded->w, loaded->h);
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

bool sr_texture_load(sr_texture *tex, const char *path, sr_error *err)
{
    *tex = (sr_texture){ 0 };
    SDL_Surface *loaded = load_surface(path, err);
    if (!loaded)
        return false;
    bool ok = texels_from_surface(tex, loaded, path, err);
    SDL_FreeSurface(loaded);
    if (!ok)
        sr_texture_free(tex);
    return ok;
}

void sr_texture_free(sr_texture *tex)
{
    free(tex->texels);
    *tex = (sr_texture){ 0 };
}
