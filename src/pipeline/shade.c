#include <math.h>
#include <stddef.h>

#include "softrast/shade.h"

#define CHANNEL_SCALE (1.0f / 255.0f)

/* Float has no fraction left from here on, and int conversion stays safe. */
#define NO_FRACTION 8388608.0f /* 2^23 */

/* floor for |x| < 2^31, without a libm call in the per-pixel path. */
static inline int floor_int(float x)
{
    int i = (int)x;
    return i - (x < (float)i);
}

/* The fractional part in [0, 1): wrap = repeat. NaN, inf and values too big
 * to have a fraction give 0, so the texel indices below never overflow. */
static inline float wrap_unit(float t)
{
    if (!(fabsf(t) < NO_FRACTION))
        return 0.0f;
    float f = t - (float)floor_int(t);
    return f < 1.0f ? f : 0.0f;
}

static inline void texel_rgb(const sr_texture *tex, int x, int y, float rgb[3])
{
    uint32_t t = tex->texels[(size_t)y * (size_t)tex->width + (size_t)x];
    rgb[0] = (float)((t >> 16) & 0xFF) * CHANNEL_SCALE;
    rgb[1] = (float)((t >> 8) & 0xFF) * CHANNEL_SCALE;
    rgb[2] = (float)(t & 0xFF) * CHANNEL_SCALE;
}

/* The texel a wrapped coordinate in [0, 1) falls in; a texel's lower edge
 * belongs to it. Rounding may carry f·n up to n, hence the clamp. */
static inline int texel_index(float f, int n)
{
    int i = (int)(f * (float)n);
    return i < n ? i : n - 1;
}

/* Rows count from the bottom as v does, so v = k/H picks row k from the
 * bottom exactly as u = k/W picks column k. */
static void sample_nearest(const sr_texture *tex, float fu, float fv, float rgb[3])
{
    texel_rgb(tex, texel_index(fu, tex->width), tex->height - 1 - texel_index(fv, tex->height), rgb);
}

/* The two texels around coordinate c (texel centres at half-integers), wrapped,
 * and the weight of the second. c lies in [-0.5, n - 0.5]. */
static inline float bilinear_pair(float c, int n, int *i0, int *i1)
{
    int lo = floor_int(c);
    *i0 = lo < 0 ? n - 1 : lo;
    *i1 = lo + 1 >= n ? 0 : lo + 1;
    return c - (float)lo;
}

static void sample_bilinear(const sr_texture *tex, float fu, float fv, float rgb[3])
{
    int x0, x1, y0, y1;
    float ax = bilinear_pair(fu * (float)tex->width - 0.5f, tex->width, &x0, &x1);
    /* Image rows run top down, v bottom up. */
    float ay = bilinear_pair((1.0f - fv) * (float)tex->height - 0.5f, tex->height, &y0, &y1);
    float c[4][3];
    texel_rgb(tex, x0, y0, c[0]);
    texel_rgb(tex, x1, y0, c[1]);
    texel_rgb(tex, x0, y1, c[2]);
    texel_rgb(tex, x1, y1, c[3]);
    for (int i = 0; i < 3; i++) {
        float top = c[0][i] + ax * (c[1][i] - c[0][i]);
        float bottom = c[2][i] + ax * (c[3][i] - c[2][i]);
        rgb[i] = top + ay * (bottom - top);
    }
}

void sr_shade_sample(const sr_texture *tex, sr_filter filter, float u, float v, float rgb[3])
{
    float fu = wrap_unit(u), fv = wrap_unit(v);
    if (filter == SR_FILTER_NEAREST)
        sample_nearest(tex, fu, fv, rgb);
    else
        sample_bilinear(tex, fu, fv, rgb);
}
