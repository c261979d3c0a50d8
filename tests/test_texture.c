#include <stdio.h>
#include <sys/resource.h>
#include <time.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <criterion/criterion.h>
#include <SDL.h>
#include <SDL_image.h>

#include "softrast_private.h"
#include "temp_dir.h"

/* Signature (8) + IHDR chunk (25) + a few bytes of the next chunk: a PNG cut
 * off before any pixel data. */
#define TRUNCATED_PNG_BYTES 40

TestSuite(texture, .init = temp_dir_make, .fini = temp_dir_remove);


static void write_bytes(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f, "cannot create %s", path);
    cr_assert_eq(fwrite(data, 1, size, f), size);
    cr_assert_eq(fclose(f), 0);
}

/* 4x3 with distinct colours; row 0 (the top) first. */
static const uint32_t pixels[12] = {
    0xFF0000u, 0x00FF00u, 0x0000FFu, 0xFFFFFFu,
    0x010203u, 0x808080u, 0x000000u, 0xFEDCBAu,
    0x123456u, 0x7F7F80u, 0xC0FFEEu, 0x0BADF0u,
};

static void expect_load_fails(const char *path, sr_error *err)
{
    sr_texture tex = { .width = 9 };
    cr_assert_not(sr_texture_load(&tex, path, err), "%s loaded", path);
    cr_expect_null(tex.texels);
    cr_expect_eq(tex.width, 0);
    cr_expect_eq(strncmp(err->message, path, strlen(path)), 0, "message: %s", err->message);
}

/* Writes bytes as name in the temp dir: loading it fails, naming the path and
 * saying it is not a readable image. */
static void expect_unreadable_image(const char *name, const void *bytes, size_t size)
{
    char path[512];
    sr_error err = { "" };
    write_bytes(temp_path(path, sizeof path, name), bytes, size);
    expect_load_fails(path, &err);
    cr_expect_not_null(strstr(err.message, "not a readable image"), "%s: message: %s", name, err.message);
}

Test(texture, load_returns_written_texels_top_row_first)
{
    char path[512];
    sr_error err = { "" };
    cr_assert(sr_image_write_png(temp_path(path, sizeof path, "t.png"), pixels, 4, 3, &err), "%s",
              err.message);
    sr_texture tex;
    cr_assert(sr_texture_load(&tex, path, &err), "%s", err.message);
    cr_assert_eq(tex.width, 4);
    cr_assert_eq(tex.height, 3);
    for (int i = 0; i < 12; i++)
        cr_expect_eq(tex.texels[i], pixels[i], "texel %d: %#08x", i, tex.texels[i]);
    sr_texture_free(&tex);
}

/* An RGBA file keeps its colour channels unblended, and its alpha in the
 * top byte, flagged; an RGB file's top byte is 0. */
Test(texture, load_keeps_alpha_in_the_top_byte_and_rgb_unblended)
{
    char path[512];
    SDL_Surface *s = SDL_CreateRGBSurfaceWithFormat(0, 2, 1, 32, SDL_PIXELFORMAT_RGBA32);
    cr_assert_not_null(s);
    const uint8_t rgba[8] = { 0x12, 0x34, 0x56, 0x00, 0xAB, 0xCD, 0xEF, 0x80 };
    memcpy(s->pixels, rgba, sizeof rgba);
    cr_assert_eq(IMG_SavePNG(s, temp_path(path, sizeof path, "a.png")), 0, "%s", IMG_GetError());
    SDL_FreeSurface(s);
    sr_texture tex;
    sr_error err = { "" };
    cr_assert(sr_texture_load(&tex, path, &err), "%s", err.message);
    cr_expect(tex.alpha);
    cr_expect_eq(tex.texels[0], 0x00123456u, "%#08x", tex.texels[0]);
    cr_expect_eq(tex.texels[1], 0x80ABCDEFu, "%#08x", tex.texels[1]);
    sr_texture_free(&tex);
    uint32_t rgb[2] = { 0x123456, 0xABCDEF };
    cr_assert(sr_image_write_png(path, rgb, 2, 1, &err), "%s", err.message);
    cr_assert(sr_texture_load(&tex, path, &err), "%s", err.message);
    cr_expect_not(tex.alpha);
    cr_expect_eq(tex.texels[1], 0xABCDEFu, "%#08x", tex.texels[1]);
    sr_texture_free(&tex);
}

Test(texture, load_missing_file_fails_with_message_starting_with_path)
{
    char path[512];
    sr_error err = { "" };
    expect_load_fails(temp_path(path, sizeof path, "missing.png"), &err);
    cr_expect_not_null(strstr(err.message, "cannot open"), "message: %s", err.message);
}

Test(texture, load_non_image_fails_with_message)
{
    const char garbage[] = "this is not a PNG file at all \x01\x02\x03\xff";
    expect_unreadable_image("garbage.png", garbage, sizeof garbage);
}

Test(texture, load_truncated_png_fails_without_crash)
{
    char path[512];
    cr_assert(sr_image_write_png(temp_path(path, sizeof path, "full.png"), pixels, 4, 3, NULL));
    unsigned char head[TRUNCATED_PNG_BYTES];
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f);
    cr_assert_eq(fread(head, 1, sizeof head, f), sizeof head);
    fclose(f);
    expect_unreadable_image("cut.png", head, sizeof head);
}

Test(texture, load_empty_file_fails_with_message)
{
    expect_unreadable_image("empty.png", "", 0);
}

Test(texture, free_zeroes_struct)
{
    char path[512];
    cr_assert(sr_image_write_png(temp_path(path, sizeof path, "t.png"), pixels, 4, 3, NULL));
    sr_texture tex;
    cr_assert(sr_texture_load(&tex, path, NULL));
    sr_texture_free(&tex);
    cr_expect_null(tex.texels);
    cr_expect_eq(tex.width, 0);
    cr_expect_eq(tex.height, 0);
}

/* PNG's CRC-32 (ISO 3309) of the chunk type and data. */
static uint32_t png_crc(const unsigned char *bytes, size_t size)
{
    uint32_t crc = 0xFFFFFFFFu;
    for (size_t i = 0; i < size; i++) {
        crc ^= bytes[i];
        for (int k = 0; k < 8; k++)
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

static size_t put_be32(unsigned char *out, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        out[i] = (unsigned char)(v >> (24 - 8 * i));
    return 4;
}

/* One chunk at out: length, type, data, CRC; returns its size. */
static size_t put_chunk(unsigned char *out, const char *type, const unsigned char *data, uint32_t size)
{
    size_t n = put_be32(out, size);
    memcpy(out + n, type, 4);
    memcpy(out + n + 4, data, size);
    n += put_be32(out + n + 4 + size, png_crc(out + n, 4 + (size_t)size));
    return n + 4 + size;
}

/* A valid PNG header claiming width x height (8-bit RGB), then a few bytes
 * of pixel data and IEND: 87 bytes that would decode to gigabytes. */
static void write_huge_png_header(const char *path, uint32_t width, uint32_t height)
{
    unsigned char png[128] = "\x89PNG\r\n\x1a\n", ihdr[13] = { 0 };
    static const unsigned char idat[] = { 0x78, 0x9c, 0x63, 0x60, 0x18, 0x05, 0xa3, 0x60, 0x14, 0x0c, 0x77 };
    put_be32(ihdr, width);
    put_be32(ihdr + 4, height);
    ihdr[8] = 8; /* bit depth */
    ihdr[9] = 2; /* RGB */
    size_t n = 8;
    n += put_chunk(png + n, "IHDR", ihdr, sizeof ihdr);
    n += put_chunk(png + n, "IDAT", idat, sizeof idat);
    n += put_chunk(png + n, "IEND", ihdr, 0);
    write_bytes(path, png, n);
}

static double seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* A JPEG's start and first frame header (SOF0, 8-bit, 3 components) claiming
 * width x height after an APP0 segment the size reader walks past, then its
 * end: no tables, no scan. */
static void write_huge_jpeg_header(const char *path, uint32_t width, uint32_t height)
{
    const unsigned char jpeg[] = {
        0xFF, 0xD8, 0xFF, 0xE0, 0x00, 0x10, 'J', 'F', 'I', 'F', 0, 1, 1, 0, 0, 1, 0, 1, 0, 0,
        0xFF, 0xC0, 0x00, 0x11, 8, (unsigned char)(height >> 8), (unsigned char)height,
        (unsigned char)(width >> 8), (unsigned char)width, 3, 1, 0x11, 0, 2, 0x11, 1, 3, 0x11, 1,
        0xFF, 0xD9,
    };
    write_bytes(path, jpeg, sizeof jpeg);
}

/* An uncompressed 24-bit TGA header claiming width x height, then a few texels. */
static void write_huge_tga_header(const char *path, uint32_t width, uint32_t height)
{
    unsigned char tga[18 + 12] = { 0, 0, 2 };
    tga[12] = (unsigned char)width;
    tga[13] = (unsigned char)(width >> 8);
    tga[14] = (unsigned char)height;
    tga[15] = (unsigned char)(height >> 8);
    tga[16] = 24;
    write_bytes(path, tga, sizeof tga);
}

/* Loading NAME, written by `write` claiming width x height, fails at once,
 * saying `what`, without the memory the image would take: each test runs in
 * a process of its own, so its peak resident size tells. */
static void expect_refused_from_header(void (*write)(const char *, uint32_t, uint32_t), const char *name,
                                       uint32_t width, uint32_t height, const char *what)
{
    char path[512];
    sr_error err = { "" };
    write(temp_path(path, sizeof path, name), width, height);
    double start = seconds_now();
    expect_load_fails(path, &err);
    double elapsed = seconds_now() - start;
    cr_expect_not_null(strstr(err.message, what), "message: %s", err.message);
    cr_expect_lt(elapsed, 0.25, "took %.2f s", elapsed);
    struct rusage use;
    cr_assert_eq(getrusage(RUSAGE_SELF, &use), 0);
    cr_expect_lt(use.ru_maxrss, 256L * 1024, "peak resident size %ld KiB", use.ru_maxrss);
}

Test(texture, png_header_over_the_side_limit_is_refused_before_decoding)
{
    expect_refused_from_header(write_huge_png_header, "huge.png", 40000, 40000, "larger than 16384 on a side");
}

Test(texture, png_header_over_the_texel_limit_is_refused_before_decoding)
{
    expect_refused_from_header(write_huge_png_header, "huge.png", 16384, 16384, "more than 67108864 texels");
}

/* JPEG and TGA go through SDL_image, which allocated the whole image before
 * the limits were checked: their headers are read first now. */
Test(texture, jpeg_and_tga_headers_over_the_side_limit_are_refused_before_decoding, .timeout = 20)
{
    expect_refused_from_header(write_huge_jpeg_header, "huge.jpg", 60000, 60000, "larger than 16384 on a side");
    expect_refused_from_header(write_huge_tga_header, "huge.tga", 65535, 65535, "larger than 16384 on a side");
    expect_refused_from_header(write_huge_tga_header, "HUGE.TGA", 20000, 10, "larger than 16384 on a side");
}

Test(texture, jpeg_and_tga_headers_over_the_texel_limit_are_refused_before_decoding, .timeout = 20)
{
    expect_refused_from_header(write_huge_jpeg_header, "huge.jpeg", 16384, 16384, "more than 67108864 texels");
    expect_refused_from_header(write_huge_tga_header, "huge.tga", 16384, 16384, "more than 67108864 texels");
}

/* An SVG is refused before SDL_image sees it: it would rasterize one of
 * 100000² px whole before the size limits apply, and its loader leaked on
 * a file it could not parse (the fuzzer's find: an MTL whose map_Kd is
 * itself, holding "<svg"). */
Test(texture, svg_is_refused_before_decoding)
{
    static const struct {
        const char *name, *text;
    } svgs[] = {
        { "huge.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100000\" height=\"100000\">"
                      "<rect width=\"100000\" height=\"100000\" fill=\"red\"/></svg>" },
        { "small.png", "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"4\" height=\"4\"></svg>" },
        { "broken.mtl", "newmtl a\n<svg map_Kd a.mtl\n" },
    };
    for (size_t i = 0; i < sizeof svgs / sizeof *svgs; i++) {
        char path[512];
        sr_error err = { "" };
        write_bytes(temp_path(path, sizeof path, svgs[i].name), svgs[i].text, strlen(svgs[i].text));
        expect_load_fails(path, &err);
        cr_expect_not_null(strstr(err.message, "SVG"), "%s: message: %s", svgs[i].name, err.message);
    }
}

/* What the header reader lets through still decodes: a JPEG SDL_image wrote
 * and a hand-made 2x1 TGA (bottom-up, BGR). */
Test(texture, small_jpeg_and_tga_still_load)
{
    char path[512];
    SDL_Surface *s = SDL_CreateRGBSurfaceWithFormat(0, 8, 8, 32, SDL_PIXELFORMAT_RGBA32);
    cr_assert_not_null(s);
    SDL_FillRect(s, NULL, SDL_MapRGB(s->format, 200, 100, 50));
    cr_assert_eq(IMG_SaveJPG(s, temp_path(path, sizeof path, "a.jpg"), 95), 0, "%s", IMG_GetError());
    SDL_FreeSurface(s);
    sr_texture tex;
    sr_error err = { "" };
    cr_assert(sr_texture_load(&tex, path, &err), "%s", err.message);
    cr_expect(tex.width == 8 && tex.height == 8, "%dx%d", tex.width, tex.height);
    sr_texture_free(&tex);
    const unsigned char tga[18 + 6] = { 0, 0, 2, [12] = 2, [14] = 1, [16] = 24, [18] = 0x56, 0x34, 0x12, 0xEF, 0xCD, 0xAB };
    write_bytes(temp_path(path, sizeof path, "a.tga"), tga, sizeof tga);
    cr_assert(sr_texture_load(&tex, path, &err), "%s", err.message);
    cr_assert(tex.width == 2 && tex.height == 1, "%dx%d", tex.width, tex.height);
    cr_expect_eq(tex.texels[0], 0x123456u, "%#08x", tex.texels[0]);
    cr_expect_eq(tex.texels[1], 0xABCDEFu, "%#08x", tex.texels[1]);
    sr_texture_free(&tex);
}
