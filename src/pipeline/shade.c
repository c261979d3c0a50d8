#include <math.h>
#include <stddef.h>

#include "softrast/shade.h"

#define CHANNEL_SCALE (1.0f / 255.0f)

/* The fractional part in [0, 1): wrap = repeat. Non-finite gives 0, and huge
 * values (where float has no fraction left) give 0 too, so the texel index
 * below never overflows. */
static double wrap_unit(float t)
{
    if (!isfinite(t))
        return 0.0;
    double f = (double)t - floor((double)t);
    return f < 1.0 ? f : 0.0;
}

static int wrap_index(long i, int n)
{
    long r = i % n;
    return (int)(r < 0 ? r + n : r);
}

static void texel_rgb(const sr_texture *tex, int x, int y, float rgb[3])
{
    uint32_t t = tex->texels[(size_t)y * (size_t)tex->width + (size_t)x];
    rgb[0] = (float)((t >> 16) & 0xFF) * CHANNEL_SCALE;
    rgb[1] = (float)((t >> 8) & 0xFF) * CHANNEL_SCALE;
    rgb[2] = (float)(t & 0xFF) * CHANNEL_SCALE;
}

/* Rows count from the bottom as v does, so v = k/H picks row k from the
 * bottom exactly as u = k/W picks column k (a texel's lower edge belongs to it). */
static void sample_nearest(const sr_texture *tex, double fx, double fy, float rgb[3])
{
    int x = wrap_index((long)floor(fx), tex->width);
    int from_bottom = wrap_index((long)floor((double)tex->height - fy), tex->height);
    texel_rgb(tex, x, tex->height - 1 - from_bottom, rgb);
}

/* Texel centres sit at half-integers: blend the four around (fx, fy). */
static void sample_bilinear(const sr_texture *tex, double fx, double fy, float rgb[3])
{
    double x = fx - 0.5, y = fy - 0.5;
    double x0 = floor(x), y0 = floor(y);
    float ax = (float)(x - x0), ay = (float)(y - y0);
    int xs[2] = { wrap_index((long)x0, tex->width), wrap_index((long)x0 + 1, tex->width) };
    int ys[2] = { wrap_index((long)y0, tex->height), wrap_index((long)y0 + 1, tex->height) };
    float c[4][3];
    for (int k = 0; k < 4; k++)
        texel_rgb(tex, xs[k & 1], ys[k >> 1], c[k]);
    for (int i = 0; i < 3; i++) {
        float top = c[0][i] + ax * (c[1][i] - c[0][i]);
        float bottom = c[2][i] + ax * (c[3][i] - c[2][i]);
        rgb[i] = top + ay * (bottom - top);
    }
}

void sr_shade_sample(const sr_texture *tex, sr_filter filter, float u, float v, float rgb[3])
{
    /* uv (0, 0) is the image's bottom-left; rows are stored top first. */
    double fx = wrap_unit(u) * tex->width;
    double fy = (1.0 - wrap_unit(v)) * tex->height;
    if (filter == SR_FILTER_NEAREST)
        sample_nearest(tex, fx, fy, rgb);
    else
        sample_bilinear(tex, fx, fy, rgb);
}
