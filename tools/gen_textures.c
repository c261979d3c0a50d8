/* tools/gen_textures.c — procedural textures of gen-assets.
 *
 * Each texture is a painter: a function from a pixel (x right, y down, row 0
 * at the top of the image, as PNG stores it) of a TEXTURE_SIZE square to a
 * colour. Every pattern repeats exactly over TEXTURE_SIZE pixels, so a
 * texture tiles without a seam. Randomness is an integer hash of the
 * position: the same bytes every run.
 */
#include "gen_assets.h"

#include <math.h>
#include <stdint.h>

#include <SDL.h>
#include <SDL_image.h>

typedef void (*painter)(int x, int y, vec3 rgb);

/* ---- helpers ------------------------------------------------------------ */

static uint32_t hash3(uint32_t x, uint32_t y, uint32_t seed)
{
    uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ seed * 0xcb1ab31fu;
    h ^= h >> 16; /* "lowbias32" finaliser: good avalanche, integer-exact */
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

/* A hash as a float in [0, 1). */
static float hash_unit(uint32_t x, uint32_t y, uint32_t seed)
{
    return (float)(hash3(x, y, seed) >> 8) / 16777216.0f;
}

/* Smooth value noise in [0, 1) on a lattice of `cell` pixels that wraps
 * at TEXTURE_SIZE, so it tiles like the patterns drawn over it. */
static float value_noise(int x, int y, int cell, uint32_t seed)
{
    uint32_t period = TEXTURE_SIZE / cell;
    uint32_t gx = (uint32_t)(x / cell), gy = (uint32_t)(y / cell);
    float fx = ((float)(x % cell) + 0.5f) / (float)cell;
    float fy = ((float)(y % cell) + 0.5f) / (float)cell;
    fx = fx * fx * (3.0f - 2.0f * fx); /* smoothstep hides the lattice */
    fy = fy * fy * (3.0f - 2.0f * fy);
    float a = hash_unit(gx % period, gy % period, seed);
    float b = hash_unit((gx + 1) % period, gy % period, seed);
    float c = hash_unit(gx % period, (gy + 1) % period, seed);
    float d = hash_unit((gx + 1) % period, (gy + 1) % period, seed);
    return glm_lerp(glm_lerp(a, b, fx), glm_lerp(c, d, fx), fy);
}

/* Hue in turns [0, 1), saturation and value in [0, 1]. */
static void hsv_to_rgb(float h, float s, float v, vec3 rgb)
{
    for (int k = 0; k < 3; k++) {
        /* the standard closed form: channel k peaks at hue k/3 */
        float t = fmodf(h * 6.0f + (float)(4 - 2 * k) + 1.0f, 6.0f);
        float ramp = glm_clamp(fminf(t, 4.0f - t), 0.0f, 1.0f);
        rgb[k] = v * (1.0f - s * ramp);
    }
}

static void shade(vec3 base, float factor, vec3 rgb)
{
    glm_vec3_scale(base, factor, rgb);
}

/* ---- painters ----------------------------------------------------------- */

#define CHECKER_CELLS 8
#define CHECKER_PX (TEXTURE_SIZE / CHECKER_CELLS)
#define ORIGIN_MARK_PX (CHECKER_PX / 2) /* legs of the origin cell's corner mark */

/* Column cu runs with u, row cv with v (cv 0 at the bottom, where OBJ puts
 * v = 0): hue follows the column, brightness the row, so a mirrored or
 * turned texture is obvious. The cell at u, v in [0, 1/8] is white with a
 * black corner pointing at uv (0, 0). */
static void paint_checker(int x, int y, vec3 rgb)
{
    int cu = x / CHECKER_PX;
    int cv = CHECKER_CELLS - 1 - y / CHECKER_PX;
    if (cu == 0 && cv == 0) {
        int from_left = x % CHECKER_PX, from_bottom = CHECKER_PX - 1 - y % CHECKER_PX;
        float c = from_left + from_bottom < ORIGIN_MARK_PX ? 0.0f : 1.0f;
        glm_vec3_fill(rgb, c);
        return;
    }
    float hue = (float)cu / (float)CHECKER_CELLS;
    float lift = 0.05f * (float)cv; /* brighter toward v = 1 */
    if ((cu + cv) % 2 == 0)
        hsv_to_rgb(hue, 0.85f, 0.30f + lift, rgb);
    else
        hsv_to_rgb(hue, 0.30f, 0.62f + lift, rgb);
}

#define FLOOR_TILES 4 /* tiles per texture side */
#define FLOOR_TILE_PX (TEXTURE_SIZE / FLOOR_TILES)
#define FLOOR_GROUT_PX 2 /* on each side of a joint */

static void paint_floor(int x, int y, vec3 rgb)
{
    int tx = x / FLOOR_TILE_PX, ty = y / FLOOR_TILE_PX;
    int lx = x % FLOOR_TILE_PX, ly = y % FLOOR_TILE_PX;
    bool grout = lx < FLOOR_GROUT_PX || ly < FLOOR_GROUT_PX
                 || lx >= FLOOR_TILE_PX - FLOOR_GROUT_PX
                 || ly >= FLOOR_TILE_PX - FLOOR_GROUT_PX;
    if (grout) {
        glm_vec3_copy((vec3){0.20f, 0.19f, 0.18f}, rgb);
        return;
    }
    vec3 cream = {0.80f, 0.74f, 0.62f}, slate = {0.40f, 0.44f, 0.50f};
    float tile = 0.92f + 0.10f * hash_unit((uint32_t)tx, (uint32_t)ty, 1);
    float grain = 0.92f + 0.12f * value_noise(x, y, 8, 2);
    shade((tx + ty) % 2 ? slate : cream, tile * grain, rgb);
}

/* A wall of w × h blocks laid in running bond: every other course shifted
 * by half a block. Gives the block's column and course under (x, y); true
 * when (x, y) lies in the joint, the first joint_px rows or columns of a block. */
static bool running_bond(int x, int y, int w, int h, int joint_px, uint32_t *column, uint32_t *course)
{
    int row = y / h;
    int sx = (x + (row % 2) * (w / 2)) % TEXTURE_SIZE;
    *column = (uint32_t)(sx / w);
    *course = (uint32_t)row;
    return y % h < joint_px || sx % w < joint_px;
}

#define BRICK_W 64
#define BRICK_H 32
#define BRICK_MORTAR_PX 3

static void paint_brick(int x, int y, vec3 rgb)
{
    uint32_t column, course;
    if (running_bond(x, y, BRICK_W, BRICK_H, BRICK_MORTAR_PX, &column, &course)) {
        float grain = 0.9f + 0.1f * value_noise(x, y, 4, 3);
        shade((vec3){0.70f, 0.67f, 0.62f}, grain, rgb);
        return;
    }
    vec3 clay = {0.62f, 0.28f, 0.19f};
    float brick = 0.80f + 0.35f * hash_unit(column, course, 4);
    float grain = 0.88f + 0.16f * value_noise(x, y, 8, 5);
    shade(clay, brick * grain, rgb);
}

#define STONE_W 128
#define STONE_H 64
#define STONE_JOINT_PX 2

static void paint_stone(int x, int y, vec3 rgb)
{
    uint32_t column, course;
    if (running_bond(x, y, STONE_W, STONE_H, STONE_JOINT_PX, &column, &course)) {
        glm_vec3_copy((vec3){0.24f, 0.25f, 0.27f}, rgb);
        return;
    }
    vec3 granite = {0.58f, 0.60f, 0.64f};
    float block = 0.88f + 0.16f * hash_unit(column, course, 6);
    float grain = 0.80f + 0.14f * value_noise(x, y, 32, 7)
                  + 0.10f * value_noise(x, y, 4, 8); /* two octaves */
    shade(granite, block * grain, rgb);
}

static const painter ATLAS_PAINTERS[ATLAS_COUNT] = {
    [ATLAS_FLOOR] = paint_floor,
    [ATLAS_BRICK] = paint_brick,
    [ATLAS_CHECKER] = paint_checker,
    [ATLAS_STONE] = paint_stone,
};

/* ---- surfaces and PNG --------------------------------------------------- */

static uint8_t to_byte(float c)
{
    return (uint8_t)lroundf(glm_clamp(c, 0.0f, 1.0f) * 255.0f);
}

static SDL_Surface *new_rgb_surface(int size)
{
    SDL_Surface *s = SDL_CreateRGBSurfaceWithFormat(0, size, size, 24,
                                                    SDL_PIXELFORMAT_RGB24);
    if (!s)
        gen_fail("cannot create a %dx%d surface: %s", size, size, SDL_GetError());
    return s;
}

/* Paints one TEXTURE_SIZE square with its top-left pixel at (x0, y0). */
static void paint_square(SDL_Surface *s, int x0, int y0, painter paint)
{
    for (int y = 0; y < TEXTURE_SIZE; y++) {
        uint8_t *row = (uint8_t *)s->pixels + (size_t)(y0 + y) * (size_t)s->pitch;
        for (int x = 0; x < TEXTURE_SIZE; x++) {
            vec3 rgb;
            paint(x, y, rgb);
            uint8_t *px = row + 3 * (size_t)(x0 + x);
            for (int k = 0; k < 3; k++)
                px[k] = to_byte(rgb[k]);
        }
    }
}

static void save_png(SDL_Surface *s, const char *path)
{
    if (IMG_SavePNG(s, path) != 0)
        gen_fail("cannot write %s: %s", path, IMG_GetError());
    printf("wrote %s: %dx%d RGB\n", path, s->w, s->h);
    SDL_FreeSurface(s);
}

void write_checker_png(const char *path)
{
    SDL_Surface *s = new_rgb_surface(TEXTURE_SIZE);
    paint_square(s, 0, 0, paint_checker);
    save_png(s, path);
}

void write_room_png(const char *path)
{
    SDL_Surface *s = new_rgb_surface(TEXTURE_SIZE * ATLAS_CELLS);
    for (int c = 0; c < ATLAS_COUNT; c++)
        paint_square(s, TEXTURE_SIZE * (c % ATLAS_CELLS),
                     TEXTURE_SIZE * (c / ATLAS_CELLS), ATLAS_PAINTERS[c]);
    save_png(s, path);
}

uv_map atlas_uv(atlas_cell cell)
{
    float span = 1.0f / ATLAS_CELLS;
    float inset = 0.5f / (float)(TEXTURE_SIZE * ATLAS_CELLS); /* half a texel */
    int col = (int)cell % ATLAS_CELLS;
    int row_up = ATLAS_CELLS - 1 - (int)cell / ATLAS_CELLS; /* uv v runs up */
    return (uv_map){span * (float)col + inset, span * (float)row_up + inset,
                    span - 2.0f * inset, span - 2.0f * inset};
}
