/* fuzz/fuzz_draw.c — libFuzzer target for the draw call and the clipper
 * (its parts: fuzz/draw_*.c, declared in fuzz_draw.h).
 *
 * The input decodes into one of two tests (byte 0 picks: 3 mod 4 is the
 * clipper, anything else a draw):
 *
 *   draw   a framebuffer of 1..64 × 1..64, a mesh of 1..16 vertices with raw
 *          float positions (NaN, inf, huge, denormal included), optional
 *          normals, uvs, colors and texture, 0..48 indices as a list or a
 *          strip (sometimes out of range), world/view/projection matrices
 *          either raw floats or built with cglm from decoded camera
 *          parameters (near down to 1e-30, far up to 1e30), shading, cull
 *          and front. It is drawn four times: in SR_SHADE_ID with cull none,
 *          back and front, then in the decoded shading and cull mode.
 *   clip   three finite clip-space vertices (coordinates free, or on a plane
 *          give or take a few ulps) with 0..8 varyings, and a plane mask
 *          (the OR of the outcodes, as the pipeline passes, or any mask).
 *
 * Every invariant below is one the headers or DESIGN.md promise; a broken one
 * prints what and where, then abort()s so libFuzzer saves the input.
 */
#include "fuzz_draw.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    reader r = { .data = data, .size = size };
    if ((take_u8(&r) & 3) == 3)
        fuzz_clip(&r);
    else
        fuzz_draw(&r);
    return 0;
}
