#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

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
 * sRGB, as SDL_image took them. Alpha (of a file that has it) is kept in
 * the top byte, unblended (the colours are as stored), for MASK materials.
 * Closes f. */
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
    bool alpha = (png.format & PNG_FORMAT_FLAG_ALPHA) != 0;
    png.format = texel_format();
    if (ok && !png_image_finish_read(&png, NULL, tex->texels, 0, NULL))
        ok = sr_error_set(err, "%s: not a readable image: %s", path, png.message);
    png_image_free(&png);
    fclose(f);
    if (!ok)
        return false;
    for (size_t i = 0; !alpha && i < count; i++)
        tex->texels[i] &= RGB_MASK;
    tex->width = (int)png.width;
    tex->height = (int)png.height;
    tex->alpha = alpha;
    return true;
}

/* Any other format through SDL_image (which prints nothing of its own for
 * them) but SVG: a vector image has no pixel size a mesh's texture means,
 * SDL_image rasterizes it at whatever size the file names before the size
 * limits could apply, and its SVG loader leaks on a file it fails to
 * parse. Closes f. */
static SDL_Surface *load_surface(FILE *f, const char *path, sr_error *err)
{
    SDL_RWops *rw = SDL_RWFromFP(f, SDL_TRUE);
    if (!rw) {
        fclose(f);
        sr_error_set(err, "%s: cannot open: %s", path, SDL_GetError());
        return NULL;
    }
    if (IMG_isSVG(rw)) {
        SDL_RWclose(rw);
        sr_error_set(err, "%s: an SVG (vector) image; a texture must be a raster image (PNG, JPEG, ...)", path);
        return NULL;
    }
    SDL_Surface *s = IMG_LoadTyped_RW(rw, 1, file_extension(path));
    if (!s)
        sr_error_set(err, "%s: not a readable image: %s", path, IMG_GetError());
    return s;
}

/* SDL_PIXELFORMAT_RGB888 (ARGB8888 for an image with alpha) is a packed
 * 32-bit 0xXXRRGGBB (0xAARRGGBB) word in host order, so each pixel reads
 * directly as a texel; rows are pitch bytes apart. The conversion copies,
 * it does not blend. */
static void copy_texels(uint32_t *dst, const SDL_Surface *s, bool alpha)
{
    for (int y = 0; y < s->h; y++) {
        const uint8_t *row = (const uint8_t *)s->pixels + (size_t)y * (size_t)s->pitch;
        uint32_t *out = dst + (size_t)y * (size_t)s->w;
        memcpy(out, row, (size_t)s->w * sizeof *out);
        for (int x = 0; !alpha && x < s->w; x++)
            out[x] &= RGB_MASK;
    }
}

/* tex from the loaded image; tex is left empty when that fails. */
static bool texels_from_surface(sr_texture *tex, SDL_Surface *loaded, const char *path, sr_error *err)
{
    if (!size_allowed(path, (unsigned long)loaded->w, (unsigned long)loaded->h, err))
        return false;
    bool alpha = SDL_ISPIXELFORMAT_ALPHA(loaded->format->format) || loaded->format->Amask != 0;
    SDL_Surface *rgb = SDL_ConvertSurfaceFormat(loaded, alpha ? SDL_PIXELFORMAT_ARGB8888 : SDL_PIXELFORMAT_RGB888, 0);
    if (!rgb)
        return sr_error_set(err, "%s: cannot convert the image to RGB: %s", path, SDL_GetError());
    tex->texels = malloc((size_t)rgb->w * (size_t)rgb->h * sizeof *tex->texels);
    if (!tex->texels) {
        SDL_FreeSurface(rgb);
        return sr_error_set(err, "%s: out of memory for a %dx%d texture", path, rgb->w, rgb->h);
    }
    copy_texels(tex->texels, rgb, alpha);
    tex->alpha = alpha;
    tex->width = rgb->w;
    tex->height = rgb->h;
    SDL_FreeSurface(rgb);
    return true;
}

/* n bytes at f's position into b; false at the end of the file. */
static bool read_bytes(FILE *f, unsigned char *b, size_t n)
{
    return fread(b, 1, n, f) == n;
}

/* A JPEG's size from its first frame header (SOF0..SOF15 but DHT, JPG and
 * DAC), walking the marker segments: false when there is none before the
 * scan or the file ends (the decoder then says what is wrong). */
static bool jpeg_size(FILE *f, unsigned long *width, unsigned long *height)
{
    unsigned char b[7];
    if (!read_bytes(f, b, 2) || b[0] != 0xFF || b[1] != 0xD8)
        return false;
    for (;;) {
        int c;
        while ((c = fgetc(f)) == 0xFF) /* a marker, after any fill bytes */
            ;
        if (c == EOF || c == 0xDA || c == 0xD9)
            return false;
        if (c == 0x01 || (c >= 0xD0 && c <= 0xD7)) /* segments without a length */
            continue;
        if (!read_bytes(f, b, 2))
            return false;
        long length = (long)b[0] << 8 | b[1];
        bool frame = c >= 0xC0 && c <= 0xCF && c != 0xC4 && c != 0xC8 && c != 0xCC;
        if (frame) {
            if (!read_bytes(f, b, 5))
                return false;
            *height = (unsigned long)b[1] << 8 | b[2];
            *width = (unsigned long)b[3] << 8 | b[4];
            return true;
        }
        if (length < 2 || fseek(f, length - 2, SEEK_CUR) != 0)
            return false;
    }
}

/* A TGA's size from its 18-byte header (little-endian at 12 and 14). */
static bool tga_size(FILE *f, unsigned long *width, unsigned long *height)
{
    unsigned char h[18];
    if (!read_bytes(f, h, sizeof h))
        return false;
    *width = (unsigned long)h[13] << 8 | h[12];
    *height = (unsigned long)h[15] << 8 | h[14];
    return true;
}

/* The size limits applied from the header, before SDL_image allocates the
 * whole image, for the formats whose header this reads (JPEG, and TGA,
 * which has no magic number and is known by its extension, as SDL_image
 * knows it); other formats are checked once decoded. Leaves f rewound. */
static bool header_size_allowed(FILE *f, const char *path, sr_error *err)
{
    unsigned long width = 0, height = 0;
    const char *ext = file_extension(path);
    bool known = jpeg_size(f, &width, &height);
    rewind(f);
    if (!known && ext && strcasecmp(ext, "tga") == 0)
        known = tga_size(f, &width, &height);
    rewind(f);
    return !known || size_allowed(path, width, height, err);
}

static bool load_other(sr_texture *tex, FILE *f, const char *path, sr_error *err)
{
    if (!header_size_allowed(f, path, err)) {
        fclose(f);
        return false;
    }
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
