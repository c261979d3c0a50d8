#define _XOPEN_SOURCE 700 /* symlink, lstat */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <criterion/criterion.h>
#include <SDL.h>
#include <SDL_image.h>

#include "softrast_private.h"
#include "temp_dir.h"

/* PNG layout: 8-byte signature, then the IHDR chunk (length, "IHDR", width,
 * height, bit depth, color type, compression, filter, interlace). */
#define PNG_IHDR_TAG_OFFSET 12
#define PNG_BIT_DEPTH_OFFSET 24
#define PNG_COLOR_TYPE_OFFSET 25
#define PNG_INTERLACE_OFFSET 28
#define PNG_COLOR_TYPE_RGB 2

TestSuite(image, .init = temp_dir_make, .fini = temp_dir_remove);


/* The whole file; *size gets its length. The caller frees. */
static unsigned char *read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "cannot open %s", path);
    cr_assert_eq(fseek(f, 0, SEEK_END), 0);
    long len = ftell(f);
    cr_assert_geq(len, 0);
    rewind(f);
    unsigned char *data = malloc((size_t)len + 1);
    cr_assert_not_null(data);
    *size = fread(data, 1, (size_t)len, f);
    fclose(f);
    cr_assert_eq(*size, (size_t)len, "short read of %s", path);
    return data;
}

/* Row 1 (bottom) is the first stored row. Values include -0, a subnormal and a
 * NaN payload: only a byte copy keeps them. */
static float pfm_depth[6];

static void fill_pfm_depth(void)
{
    const uint32_t bits[6] = {
        0x3E800000u, /* 0.25 */
        0x3F7FFFFFu, /* just below 1 */
        0x80000000u, /* -0.0 */
        0x00000001u, /* smallest subnormal */
        0x7FC01234u, /* NaN with payload */
        0x3F800000u, /* 1.0 (cleared) */
    };
    memcpy(pfm_depth, bits, sizeof bits);
}

static uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static const char pfm_header[] = "Pf\n3 2\n-1\n";
#define PFM_HEADER_LEN (sizeof pfm_header - 1)

/* Writes pfm_depth (3 x 2) as d.pfm and returns the file, checked to be the
 * header and six floats long. The caller frees. */
static unsigned char *write_and_read_pfm(void)
{
    char path[512];
    fill_pfm_depth();
    cr_assert(sr_image_write_pfm(temp_path(path, sizeof path, "d.pfm"), pfm_depth, 3, 2, NULL));
    size_t size;
    unsigned char *data = read_file(path, &size);
    cr_assert_eq(size, PFM_HEADER_LEN + 6 * 4, "file is %zu bytes", size);
    return data;
}

Test(image, pfm_header_is_exact)
{
    unsigned char *data = write_and_read_pfm();
    cr_expect_eq(memcmp(data, pfm_header, PFM_HEADER_LEN), 0, "header is '%.*s'", (int)PFM_HEADER_LEN, data);
    free(data);
}

Test(image, pfm_rows_are_stored_bottom_first_bit_exact)
{
    unsigned char *data = write_and_read_pfm();
    const size_t header_len = PFM_HEADER_LEN;
    const int stored_row_to_image_row[2] = { 1, 0 };
    for (int r = 0; r < 2; r++) {
        for (int x = 0; x < 3; x++) {
            uint32_t got = le32(data + header_len + 4 * (size_t)(3 * r + x));
            uint32_t want;
            memcpy(&want, &pfm_depth[3 * stored_row_to_image_row[r] + x], sizeof want);
            cr_expect_eq(memcmp(&got, &want, sizeof got), 0,
                         "stored row %d, x %d: %#010x, want %#010x", r, x, got, want);
        }
    }
    free(data);
}

static void expect_write_fails_naming(const char *path, bool ok, const sr_error *err)
{
    cr_assert_not(ok, "writing %s succeeded", path);
    cr_expect_eq(strncmp(err->message, path, strlen(path)), 0, "message: %s", err->message);
}

Test(image, pfm_into_missing_directory_fails_naming_path)
{
    char path[512];
    float depth[1] = { 0.5f };
    sr_error err = { "" };
    temp_path(path, sizeof path, "no/such/dir/d.pfm");
    expect_write_fails_naming(path, sr_image_write_pfm(path, depth, 1, 1, &err), &err);
}

static const uint32_t png_pixels[15] = {
    0xFF0000u, 0x00FF00u, 0x0000FFu, 0x010203u, 0xFEFDFCu,
    0x000000u, 0xFFFFFFu, 0x808080u, 0x123456u, 0xABCDEFu,
    0x7F0080u, 0x00807Fu, 0x3C3C3Du, 0xC0FFEEu, 0x0BADF0u,
};

Test(image, png_round_trip_is_exact)
{
    char path[512];
    cr_assert(sr_image_write_png(temp_path(path, sizeof path, "c.png"), png_pixels, 5, 3, NULL));
    SDL_Surface *loaded = IMG_Load(path);
    cr_assert_not_null(loaded, "IMG_Load: %s", IMG_GetError());
    SDL_Surface *rgb = SDL_ConvertSurfaceFormat(loaded, SDL_PIXELFORMAT_RGB888, 0);
    SDL_FreeSurface(loaded);
    cr_assert_not_null(rgb);
    cr_assert_eq(rgb->w, 5);
    cr_assert_eq(rgb->h, 3);
    for (int y = 0; y < 3; y++) {
        const uint32_t *row = (const uint32_t *)((const uint8_t *)rgb->pixels + y * rgb->pitch);
        for (int x = 0; x < 5; x++)
            cr_expect_eq(row[x] & 0xFFFFFFu, png_pixels[5 * y + x], "(%d, %d): %#08x", x, y, row[x]);
    }
    SDL_FreeSurface(rgb);
}

Test(image, png_is_8_bit_rgb_color_type_2_non_interlaced)
{
    char path[512];
    cr_assert(sr_image_write_png(temp_path(path, sizeof path, "c.png"), png_pixels, 5, 3, NULL));
    size_t size;
    unsigned char *data = read_file(path, &size);
    cr_assert_gt(size, (size_t)PNG_INTERLACE_OFFSET);
    cr_expect_eq(memcmp(data, "\x89PNG\r\n\x1a\n", 8), 0, "no PNG signature");
    cr_expect_eq(memcmp(data + PNG_IHDR_TAG_OFFSET, "IHDR", 4), 0, "IHDR is not first");
    cr_expect_eq(data[PNG_BIT_DEPTH_OFFSET], 8, "bit depth %d", data[PNG_BIT_DEPTH_OFFSET]);
    cr_expect_eq(data[PNG_COLOR_TYPE_OFFSET], PNG_COLOR_TYPE_RGB, "color type %d",
                 data[PNG_COLOR_TYPE_OFFSET]);
    cr_expect_eq(data[PNG_INTERLACE_OFFSET], 0, "interlaced");
    free(data);
}

Test(image, png_into_missing_directory_fails_naming_path)
{
    char path[512];
    sr_error err = { "" };
    temp_path(path, sizeof path, "no/such/dir/c.png");
    expect_write_fails_naming(path, sr_image_write_png(path, png_pixels, 5, 3, &err), &err);
}

Test(image, png_rejects_empty_size_with_message)
{
    char path[512];
    sr_error err = { "" };
    temp_path(path, sizeof path, "empty.png");
    expect_write_fails_naming(path, sr_image_write_png(path, png_pixels, 0, 3, &err), &err);
    cr_expect_neq(access(path, F_OK), 0, "a file was left behind");
}

Test(image, depth_png_is_the_gray_view)
{
    char path[512];
    float depth[4] = { 0.25f, SR_DEPTH_CLEAR, 0.75f, 0.375f };
    uint32_t color[4] = { 0 };
    sr_framebuffer fb = { .width = 2, .height = 2, .color = color, .depth = depth };
    uint32_t gray[4];
    sr_framebuffer_depth_to_gray(&fb, gray);
    cr_assert(sr_image_write_depth_png(temp_path(path, sizeof path, "z.png"), &fb, NULL));
    SDL_Surface *loaded = IMG_Load(path);
    cr_assert_not_null(loaded, "IMG_Load: %s", IMG_GetError());
    SDL_Surface *rgb = SDL_ConvertSurfaceFormat(loaded, SDL_PIXELFORMAT_RGB888, 0);
    SDL_FreeSurface(loaded);
    cr_assert_not_null(rgb);
    for (int y = 0; y < 2; y++) {
        const uint32_t *row = (const uint32_t *)((const uint8_t *)rgb->pixels + y * rgb->pitch);
        for (int x = 0; x < 2; x++)
            cr_expect_eq(row[x] & 0xFFFFFFu, gray[2 * y + x], "(%d, %d): %#08x", x, y, row[x]);
    }
    SDL_FreeSurface(rgb);
}

/* The write goes to a temporary file renamed onto the file the link names:
 * the link stays a link, the file keeps its permissions, nothing is left. */
Test(image, png_through_a_symlink_replaces_the_file_it_names)
{
    char file[512], link[512];
    temp_path(file, sizeof file, "old.png");
    FILE *f = fopen(file, "wb");
    cr_assert_not_null(f);
    fclose(f);
    cr_assert_eq(chmod(file, 0640), 0);
    cr_assert_eq(symlink(file, temp_path(link, sizeof link, "link.png")), 0);
    cr_assert(sr_image_write_png(link, png_pixels, 5, 3, NULL));
    struct stat st;
    cr_assert_eq(lstat(link, &st), 0);
    cr_expect(S_ISLNK(st.st_mode), "the link was replaced");
    cr_assert_eq(stat(file, &st), 0);
    cr_expect_eq(st.st_mode & 0777, 0640, "mode %o", (unsigned)(st.st_mode & 0777));
    cr_expect_gt(st.st_size, 8, "old.png was not written");
    char cmd[600];
    snprintf(cmd, sizeof cmd, "test $(ls %s | wc -l) -eq 2", temp_dir);
    cr_expect_eq(system(cmd), 0, "a temporary file was left in %s", temp_dir);
}
