/* span_kernel.h — the per-pixel work of raster.c, SPAN_LANES pixels at a
 * time, in GCC/Clang vector extensions. Included once per instruction set:
 * span_sse2.c (4 lanes), span_avx2.c (8, built with -mavx2) and
 * span_avx512.c (16, built with -mavx512f/dq/bw/vl). Each defines
 * SPAN_LANES, SPAN_LANE_INDICES (0, 1, … SPAN_LANES − 1) and
 * SPAN_KERNEL_GETTER first, SPAN_TINY_GETTER where it builds the tiny
 * queue's shaders (not span_avx512.c: simd_select.c gives the queue the
 * AVX2 ones), and may define SPAN_SQRT, SPAN_MOVEMASK, SPAN_GATHER,
 * SPAN_FLOOR and SPAN_PERMUTE with the instruction set's intrinsics (else
 * generic lane loops stand in).
 *
 * Every lane does exactly the float operations of the scalar loop and of
 * 10_shade.h, in the same order and without fused multiply-adds (the Makefile
 * passes -ffp-contract=off: clang would fuse where AVX-512 offers FMA), so the colors
 * and depths are bit-identical to the scalar path (tests/test_simd.c):
 * depth from the row's z and the per-pixel step (the pixel's column as an
 * exact float), λ = (float)E · inv_area2 with E exact in double, 1/w from
 * λ, the varyings divided by 1/w, then the mode's shading. Lanes past the row
 * or outside the triangle are masked; memory is read and written only for
 * the row's pixels (a neighbouring tile belongs to another thread). */
#include <math.h>
#include <string.h>

#include "kernels.h"

_Static_assert(SPAN_LANES <= SR_SIMD_MAX_LANES, "raster.c checks edge values exact only SR_SIMD_MAX_LANES past a box");

typedef float vf __attribute__((vector_size(SPAN_LANES * 4)));
typedef int32_t vi __attribute__((vector_size(SPAN_LANES * 4)));
/* Edge values are doubles, kept as two half-width vectors that each fit a
 * register (a full-width vector of doubles would be split through memory). */
typedef double vdh __attribute__((vector_size(SPAN_LANES * 4)));
typedef float vfh __attribute__((vector_size(SPAN_LANES * 2)));

typedef struct edge_lanes {
    vdh lo, hi; /* lanes 0 .. SPAN_LANES/2 − 1, then the rest */
} edge_lanes;

#ifndef SPAN_SQRT
static inline __attribute__((always_inline)) vf span_sqrt_lanes(vf x)
{
    for (int l = 0; l < SPAN_LANES; l++)
        x[l] = sqrtf(x[l]);
    return x;
}
#define SPAN_SQRT(x) span_sqrt_lanes(x)
#endif

/* Lane-wise mask ? a : b, masks being all ones or all zeros per lane. */
static inline __attribute__((always_inline)) vi select_i(vi mask, vi a, vi b)
{
    return (mask & a) | (~mask & b);
}

static inline __attribute__((always_inline)) vf select_f(vi mask, vf a, vf b)
{
    return (vf)select_i(mask, (vi)a, (vi)b);
}

/* The first n 32-bit values at p (depths or packed colors) as lanes, zeros
 * past n: a masked load where the instruction set has one (SPAN_LOAD_FIRST),
 * else a vector load of a whole group and a lane loop for a row's last. */
static inline __attribute__((always_inline)) vi load_lanes(const void *p, int n)
{
#ifdef SPAN_LOAD_FIRST
    return SPAN_LOAD_FIRST(p, n);
#else
    vi v = { 0 };
    if (n == SPAN_LANES)
        memcpy(&v, p, sizeof v);
    else
        for (int l = 0; l < n; l++)
            memcpy((char *)&v + 4 * l, (const char *)p + 4 * l, 4);
    return v;
#endif
}

/* v's lanes where mask is set (a subset of the first n) to p, the rest of
 * p untouched: a masked store where the instruction set has one
 * (SPAN_STORE_WHERE: no load of what stays), else load, select and store of
 * the n values. Memory past n is never written: it may be another thread's
 * tile. */
static inline __attribute__((always_inline)) void store_where(void *p, vi mask, vi v, int n)
{
#ifdef SPAN_STORE_WHERE
    (void)n;
    SPAN_STORE_WHERE(p, mask, v);
#else
    vi out = select_i(mask, v, load_lanes(p, n));
    if (n == SPAN_LANES)
        memcpy(p, &out, sizeof out);
    else
        for (int l = 0; l < n; l++)
            memcpy((char *)p + 4 * l, (const char *)&out + 4 * l, 4);
#endif
}

static inline __attribute__((always_inline)) vf edge_to_float(edge_lanes e)
{
    vfh lo = __builtin_convertvector(e.lo, vfh), hi = __builtin_convertvector(e.hi, vfh);
#if defined(__has_builtin) && __has_builtin(__builtin_shufflevector)
    return __builtin_shufflevector(lo, hi, SPAN_LANE_INDICES);
#else /* GCC before 12: slower (through memory), same values */
    vf f;
    memcpy(&f, &lo, sizeof lo);
    memcpy((char *)&f + sizeof lo, &hi, sizeof hi);
    return f;
#endif
}

static inline __attribute__((always_inline)) vi lanes_index(void)
{
    vi k;
    for (int l = 0; l < SPAN_LANES; l++)
        k[l] = l;
    return k;
}

/* One bit per lane, set where the mask is. */
static inline __attribute__((always_inline)) unsigned lane_bits(vi mask)
{
#ifdef SPAN_MOVEMASK
    return (unsigned)SPAN_MOVEMASK(mask);
#else
    unsigned bits = 0;
    for (int l = 0; l < SPAN_LANES; l++)
        bits |= (mask[l] != 0) << l;
    return bits;
#endif
}

/* The interpolants of one group of pixels. */
typedef struct lanes {
    vf l1, l2;
    vf var[SR_MAX_VARYINGS];
} lanes;

static inline __attribute__((always_inline)) vf depth_lanes(const sr_tri_setup *s, float z_row, vf k)
{
    vf z = z_row + s->dz_pixel * k;
    vf zero = { 0 };
    vf one = zero + 1.0f;
    return select_f(z > zero, select_f(z < one, z, one), zero);
}

/* The kernels know their varyings' layout at compile time, so the varyings
 * stay in registers: the vertex stage puts the normal first, then the
 * albedo's uv or color (01_vertex.c); a mode with one input has it at 0. */
/* A material's tint (sr_shade_context.tinted) and alpha test (alpha_min,
 * which implies a texture) are kernels of their own, so a draw without
 * them pays for neither: a MASKED kernel is tinted too (a tint of 1 gives
 * the untinted values). */
typedef enum albedo {
    ALBEDO_NONE,
    ALBEDO_GRAY, /* the context's albedo: gray, or a material's colour */
    ALBEDO_COLOR,
    ALBEDO_TEXTURE,
    ALBEDO_COLOR_TINTED,
    ALBEDO_TEXTURE_TINTED,
    ALBEDO_TEXTURE_MASKED
} albedo;

static inline __attribute__((always_inline)) bool albedo_textured(albedo a)
{
    return a == ALBEDO_TEXTURE || a == ALBEDO_TEXTURE_TINTED || a == ALBEDO_TEXTURE_MASKED;
}

static inline __attribute__((always_inline)) bool albedo_tinted(albedo a)
{
    return a == ALBEDO_COLOR_TINTED || a == ALBEDO_TEXTURE_TINTED || a == ALBEDO_TEXTURE_MASKED;
}
#define SECOND_VARYING 3 /* after the normal */

static inline __attribute__((always_inline)) int varying_count(sr_shade mode, albedo a)
{
    switch (mode) {
    case SR_SHADE_COLOR:
    case SR_SHADE_NORMAL:  return 3;
    case SR_SHADE_TEXTURE: return 2;
    case SR_SHADE_LAMBERT: return a == ALBEDO_COLOR || a == ALBEDO_COLOR_TINTED ? 6 : albedo_textured(a) ? 5 : 3;
    default:               return 0;
    }
}

/* What a triangle's kernel computes once instead of per pixel (sr_interp),
 * held in registers across its rows. */
typedef struct triangle_lanes {
    vf w;       /* when the interp does not divide (sr_interp_divides) */
    vf lambert; /* when sr_interp_flat_normal */
    vi color;   /* when color_per_triangle */
    /* c->texture, when given, copied: the compiler must assume that a
     * store of a pixel may change what c points to, so it would load the
     * texture's size again for every group of pixels. The same for the
     * albedo and the tint. */
    sr_texture texture;
    float albedo[3], tint[3];
} triangle_lanes;

static inline __attribute__((always_inline)) void triangle_lanes_init(triangle_lanes *t, const sr_shade_context *c)
{
    if (c->texture)
        t->texture = *c->texture;
    for (int i = 0; i < 3; i++) {
        t->albedo[i] = c->albedo[i];
        t->tint[i] = c->tint[i];
    }
}

/* Gray lambert with a flat normal is one color over the whole triangle. */
static inline __attribute__((always_inline)) bool color_per_triangle(sr_shade mode, albedo a, sr_interp interp)
{
    return mode == SR_SHADE_LAMBERT && a == ALBEDO_GRAY && sr_interp_flat_normal(interp);
}

/* The varyings a kernel interpolates: with a flat normal, only those after it. */
static inline __attribute__((always_inline)) int first_varying(sr_interp interp)
{
    return sr_interp_flat_normal(interp) ? SECOND_VARYING : 0;
}

/* A plane at the lanes' λ1 and λ2 (p a lanes), c0 + λ1·c1 + λ2·c2 in this
 * order, as the scalar loop rounds it; the coefficients scalars (one
 * triangle's, broadcast) or vectors (each lane's triangle's). */
#define PLANE_LANES(c0, c1, c2, p) ((c0) + (p).l1 * (c1) + (p).l2 * (c2))

static inline __attribute__((always_inline)) void varyings_lanes(const sr_tri_setup *s, const triangle_lanes *t,
                                                                 sr_interp interp, int count, lanes *p)
{
    vf w = sr_interp_divides(interp) ? 1.0f / PLANE_LANES(s->iw0, s->diw1, s->diw2, *p) : t->w;
    /* Unrolled, so the varyings stay in registers: as a loop (GCC 12 does
     * not unroll it at -O2) each went through the stack on its way to the
     * shading. 8 is SR_MAX_VARYINGS: the pragma takes no macro. */
    _Static_assert(SR_MAX_VARYINGS == 8, "the unroll count below");
#pragma GCC unroll 8
    for (int k = first_varying(interp); k < count; k++)
        p->var[k] = PLANE_LANES(s->var0[k], s->dvar1[k], s->dvar2[k], *p) * w;
}

/* sr_shade_channel per lane. */
static inline __attribute__((always_inline)) vi channel_lanes(vf c)
{
    vf zero = { 0 };
    vf one = zero + 1.0f;
    vf clamped = select_f(c > zero, select_f(c < one, c, one), zero);
    return __builtin_convertvector(clamped * 255.0f + 0.5f, vi);
}

static inline __attribute__((always_inline)) vi pack_lanes(vf r, vf g, vf b)
{
    return channel_lanes(r) << 16 | channel_lanes(g) << 8 | channel_lanes(b);
}

/* table[index] per lane: a gather where the instruction set has one. */
static inline __attribute__((always_inline)) vi gather_table(const uint32_t *table, vi index)
{
#ifdef SPAN_GATHER
    return SPAN_GATHER(table, index);
#else
    vi t;
    for (int l = 0; l < SPAN_LANES; l++)
        t[l] = (int32_t)table[index[l]];
    return t;
#endif
}

/* sr_srgb_channel per lane. */
static inline __attribute__((always_inline)) vi srgb_channel_lanes(vf c)
{
    vf zero = { 0 };
    vf one = zero + 1.0f;
    vf clamped = select_f(c > zero, select_f(c < one, c, one), zero);
    return gather_table(sr_linear_to_srgb, __builtin_convertvector(clamped * (float)SR_LINEAR_ONE + 0.5f, vi));
}

/* sr_shade_pack_colour per lane: encoded to sRGB where the kernel is. */
static inline __attribute__((always_inline)) vi pack_colour_lanes(bool srgb, vf r, vf g, vf b)
{
    if (!srgb)
        return pack_lanes(r, g, b);
    return srgb_channel_lanes(r) << 16 | srgb_channel_lanes(g) << 8 | srgb_channel_lanes(b);
}

/* floor per lane, as a float: roundps where the instruction set has it,
 * else sr_shade_floor_int's truncate-then-step-down. Exact either way for
 * |x| < 2^31, so both agree with the scalar path. */
static inline __attribute__((always_inline)) vf floor_lanes(vf x)
{
#ifdef SPAN_FLOOR
    return SPAN_FLOOR(x);
#else
    vi i = __builtin_convertvector(x, vi);
    return __builtin_convertvector(i + (x < __builtin_convertvector(i, vf)), vf);
#endif
}

/* sr_shade_wrap_unit per lane, but for its last step: the fraction of t in
 * [0, 1], where 1 is what rounding makes of a tiny negative t. */
static inline __attribute__((always_inline)) vf fraction_lanes(vf t)
{
    vf zero = { 0 };
    vi finite = (vf)((vi)t & 0x7FFFFFFF) < SR_SHADE_NO_FRACTION;
    vf kept = select_f(finite, t, zero);
    return kept - floor_lanes(kept);
}

/* The last step, 1 wrapped to 0, which only the nearest filter needs: the
 * bilinear position at 1 is its position at 0 (bilinear_pair_lanes: both
 * give texels n − 1 and 0 at weight one half), on either axis. */
static inline __attribute__((always_inline)) vf below_one_lanes(vf f)
{
    return select_f(f < 1.0f, f, (vf){ 0 });
}

static inline __attribute__((always_inline)) vi texel_index_lanes(vf f, int n)
{
    vi i = __builtin_convertvector(f * (float)n, vi);
    return select_i(i < n, i, (vi){ 0 } + (n - 1));
}

/* The texels at index, as stored: the top byte is whatever the caller's
 * memory holds, so a reader masks it or ignores it. */
static inline __attribute__((always_inline)) vi gather_texels(const sr_texture *tex, vi index)
{
    return gather_table(tex->texels, index);
}

typedef struct rgb_lanes {
    vf c[3];
} rgb_lanes;

/* The index of row y's first texel, y · width: a shift where the width is
 * a power of two (the same for every group, so the branch is always
 * predicted): the 32-bit multiply is two operations and ten cycles of
 * latency on the way to the gathers. */
static inline __attribute__((always_inline)) vi texel_row_lanes(vi y, int width)
{
    if ((width & (width - 1)) == 0)
        return y << __builtin_ctz((unsigned)width);
    return y * width;
}

static inline __attribute__((always_inline)) vi sample_nearest_lanes(const sr_texture *tex, vf fu, vf fv)
{
    vi x = texel_index_lanes(fu, tex->width);
    vi y = (tex->height - 1) - texel_index_lanes(fv, tex->height);
    return gather_texels(tex, texel_row_lanes(y, tex->width) + x); /* the top byte as stored */
}

/* sr_shade_bilinear_pair per lane. A side of a power of two wraps by a
 * mask (the same texels: lo lies in [−1, n − 1]), one operation per
 * index where the selects take a compare and a select; n is the same for
 * every group, so the branch is always predicted. */
static inline __attribute__((always_inline)) vi bilinear_pair_lanes(vf f, int n, vi *i0, vi *i1)
{
    vi q = __builtin_convertvector(f * (float)(n * (int)SR_SHADE_WEIGHT_ONE) + 0.5f, vi) +
           (int)SR_SHADE_WEIGHT_ONE / 2;
    vi lo = (q >> SR_SHADE_WEIGHT_BITS) - 1;
    if ((n & (n - 1)) == 0) {
        *i0 = lo & (n - 1);
        *i1 = (lo + 1) & (n - 1);
    } else {
        vi zero = { 0 };
        *i0 = select_i(lo < 0, zero + (n - 1), lo);
        *i1 = select_i(lo + 1 >= n, zero, lo + 1);
    }
    return q & (int)(SR_SHADE_WEIGHT_ONE - 1);
}

/* Texels as 16-bit halves of their lanes: red and blue (0x00RR00BB) in
 * one vector, green in the low half of another (0xTT0000GG: the unused top
 * byte rides along in the high half, lerped like a channel, and is dropped
 * at the end, which costs one operation less per texel than a mask). */
typedef uint16_t vu16 __attribute__((vector_size(SPAN_LANES * 4)));

typedef struct split_texels {
    vu16 rb, g;
} split_texels;

static inline __attribute__((always_inline)) split_texels split_lanes(vi t)
{
    return (split_texels){ (vu16)(t & 0xFF00FF), (vu16)t >> 8 };
}

/* sr_shade_lerp_texels per 16-bit half: a·(ONE − w) + b·w + ONE/2, shifted
 * down, is a + floor(((b − a)·w + ONE/2) / ONE) exactly (a·ONE is a multiple
 * of ONE). With SPAN_MULHRS (pmulhrsw: (x·y + 2^14) >> 15, signed) and w2 =
 * w · 2^(15 − bits) (below 2^15), that floor is one instruction on the
 * signed difference, and a plus it lies in 0..255 as the scalar result
 * does: three operations per half, where the fallback's arithmetic modulo
 * 2^16 (right in the low byte, masked) takes six, and the lerps are much
 * of the bilinear filter's arithmetic. w2 holds the weight in both halves
 * of each lane (lerp_weight_halves). */
static inline __attribute__((always_inline)) vu16 lerp_halves(vu16 a, vu16 b, vu16 w2)
{
#ifdef SPAN_MULHRS
    return a + (vu16)SPAN_MULHRS(b - a, w2);
#else
    return ((((b - a) * w2 + (uint16_t)(SR_SHADE_WEIGHT_ONE / 2)) >> SR_SHADE_WEIGHT_BITS) + a) & 0xFF;
#endif
}

static inline __attribute__((always_inline)) split_texels lerp_split(split_texels a, split_texels b, vu16 w2)
{
    return (split_texels){ lerp_halves(a.rb, b.rb, w2), lerp_halves(a.g, b.g, w2) };
}

static inline __attribute__((always_inline)) vu16 weight_halves(vi w)
{
    return (vu16)(w | w << 16);
}

/* A bilinear weight as lerp_halves takes it: in both halves, and with
 * SPAN_MULHRS, shifted up to 15 fraction bits. */
static inline __attribute__((always_inline)) vu16 lerp_weight_halves(vi w)
{
#ifdef SPAN_MULHRS
    _Static_assert(SR_SHADE_WEIGHT_BITS <= 15, "a weight below 2^15 once scaled: pmulhrsw's factor is signed");
    return weight_halves(w << (15 - SR_SHADE_WEIGHT_BITS));
#else
    return weight_halves(w);
#endif
}

static inline __attribute__((always_inline)) vi pack_split(split_texels t)
{
    return ((vi)t.rb | (vi)t.g << 8) & 0xFFFFFF;
}

static inline __attribute__((always_inline)) split_texels sample_bilinear_lanes(const sr_texture *tex, vf fu, vf fv)
{
    vi x0, x1, y0, y1;
    vu16 wx = lerp_weight_halves(bilinear_pair_lanes(fu, tex->width, &x0, &x1));
    vu16 wy = lerp_weight_halves(bilinear_pair_lanes(1.0f - fv, tex->height, &y0, &y1));
    vi row0 = texel_row_lanes(y0, tex->width), row1 = texel_row_lanes(y1, tex->width);
    split_texels top =
        lerp_split(split_lanes(gather_texels(tex, row0 + x0)), split_lanes(gather_texels(tex, row0 + x1)), wx);
    split_texels bottom =
        lerp_split(split_lanes(gather_texels(tex, row1 + x0)), split_lanes(gather_texels(tex, row1 + x1)), wx);
    return lerp_split(top, bottom, wy);
}

/* sr_shade_sample_packed per lane, split for lit_texel_lanes: the bilinear
 * filter's texels are split already, so they are not packed to be taken
 * apart again. */
static inline __attribute__((always_inline)) split_texels sample_split_lanes(const triangle_lanes *t,
                                                                             const sr_shade_context *c, vf u, vf v)
{
    vf fu = fraction_lanes(u), fv = fraction_lanes(v);
    return c->filter == SR_FILTER_NEAREST
               ? split_lanes(sample_nearest_lanes(&t->texture, below_one_lanes(fu), below_one_lanes(fv)))
               : sample_bilinear_lanes(&t->texture, fu, fv);
}

/* The same, packed (pack_split undoes split_lanes on a 24-bit texel). */
static inline __attribute__((always_inline)) vi sample_lanes(const triangle_lanes *t, const sr_shade_context *c, vf u,
                                                             vf v)
{
    return pack_split(sample_split_lanes(t, c, u, v));
}

static inline __attribute__((always_inline)) vf lambert_lanes(const sr_shade_context *c, const vf *n)
{
    vf len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    vf zero = { 0 };
    vf d = (n[0] * c->light_dir[0] + n[1] * c->light_dir[1] + n[2] * c->light_dir[2]) / SPAN_SQRT(len2);
    vf lit = SR_LAMBERT_AMBIENT + (1.0f - SR_LAMBERT_AMBIENT) * select_f(d > zero, d, zero);
    return select_f(len2 > zero, lit, zero + SR_LAMBERT_AMBIENT);
}

/* sr_shade_lit_fixed per lane. */
static inline __attribute__((always_inline)) vi lit_fixed_lanes(vf k)
{
    vi k_fixed = __builtin_convertvector(k * (float)SR_SHADE_LIT_ONE + 0.5f, vi);
    return select_i(k_fixed < (int)SR_SHADE_LIT_ONE, k_fixed, (vi){ 0 } + (int)SR_SHADE_LIT_ONE);
}

/* sr_shade_lit_texel per lane, on a split texel: each 16-bit half (red and
 * blue; green and the top byte, dropped at the end) times its k in 8.8
 * fixed point (k_rb: blue's in the low half, red's in the high), rounded:
 * a channel times k stays below 2^16. */
static inline __attribute__((always_inline)) vi lit_split_lanes(split_texels t, vu16 k_rb, vu16 k_g)
{
    const uint16_t half = SR_SHADE_LIT_ONE / 2;
    vu16 rb = (t.rb * k_rb + half) >> SR_SHADE_LIT_BITS, g = (t.g * k_g + half) >> SR_SHADE_LIT_BITS;
    return ((vi)rb | (vi)g << 8) & 0xFFFFFF;
}

static inline __attribute__((always_inline)) vi lit_texel_lanes(split_texels t, vf k)
{
    vu16 k2 = weight_halves(lit_fixed_lanes(k));
    return lit_split_lanes(t, k2, k2);
}

/* sr_shade_lit_texel_tinted per lane: each channel's k·tint. */
static inline __attribute__((always_inline)) vi lit_texel_tinted_lanes(split_texels t, vf k, const float tint[3])
{
    vi k_r = lit_fixed_lanes(k * tint[0]), k_b = lit_fixed_lanes(k * tint[2]);
    return lit_split_lanes(t, (vu16)(k_b | k_r << 16), weight_halves(lit_fixed_lanes(k * tint[1])));
}

/* sr_shade_lit_texel_srgb per lane, on a split texel: each channel (red
 * in the high half of rb, blue in its low half, green in the low half of
 * g) decoded, times its k in 8.8 fixed point, rounded and encoded. */
static inline __attribute__((always_inline)) vi lit_srgb_lanes(split_texels t, vf k, const float tint[3], bool tinted)
{
    vi channel[3] = { ((vi)t.rb >> 16) & 0xFF, (vi)t.g & 0xFF, (vi)t.rb & 0xFF };
    vi out = { 0 };
    for (int c = 0; c < 3; c++) {
        vi k_fixed = lit_fixed_lanes(tinted ? k * tint[c] : k);
        vi linear = (gather_table(sr_srgb_to_linear, channel[c]) * k_fixed + (int)SR_SHADE_LIT_ONE / 2) >>
                    SR_SHADE_LIT_BITS;
        out |= gather_table(sr_linear_to_srgb, linear) << (16 - 8 * c);
    }
    return out;
}

/* sr_shade_albedo per lane: vertex colors (times the tint), or the
 * context's albedo. */
static inline __attribute__((always_inline)) rgb_lanes albedo_lanes(albedo a, const triangle_lanes *t, const vf *var)
{
    rgb_lanes o;
    for (int i = 0; i < 3; i++)
        o.c[i] = a == ALBEDO_COLOR          ? var[SECOND_VARYING + i]
                 : a == ALBEDO_COLOR_TINTED ? var[SECOND_VARYING + i] * t->tint[i]
                                            : (vf){ 0 } + t->albedo[i];
    return o;
}

/* A texture's lit albedo, tinted and in sRGB where the kernel is. */
static inline __attribute__((always_inline)) vi lit_albedo_lanes(albedo a, bool srgb, const triangle_lanes *t,
                                                                 split_texels texel, vf k)
{
    if (srgb)
        return lit_srgb_lanes(texel, k, t->tint, albedo_tinted(a));
    return albedo_tinted(a) ? lit_texel_tinted_lanes(texel, k, t->tint) : lit_texel_lanes(texel, k);
}

/* sr_shade_fragment per lane; srgb: the context's (a constant of the kernel). */
static inline __attribute__((always_inline)) vi shade_lanes(sr_shade mode, albedo a, bool srgb, sr_interp interp,
                                                            const triangle_lanes *t, const sr_shade_context *c,
                                                            const vf *var, uint32_t id)
{
    vi zero = { 0 };
    switch (mode) {
    case SR_SHADE_ID:
        return zero + (int32_t)(id + 1u);
    case SR_SHADE_COLOR:
        return pack_colour_lanes(srgb, var[0], var[1], var[2]);
    case SR_SHADE_NORMAL:
        return pack_lanes(0.5f + 0.5f * var[0], 0.5f + 0.5f * var[1], 0.5f + 0.5f * var[2]);
    case SR_SHADE_TEXTURE:
        return sample_lanes(t, c, var[0], var[1]);
    case SR_SHADE_LAMBERT: {
        vf k = sr_interp_flat_normal(interp) ? t->lambert : lambert_lanes(c, var);
        if (albedo_textured(a))
            return lit_albedo_lanes(a, srgb, t, sample_split_lanes(t, c, var[SECOND_VARYING], var[SECOND_VARYING + 1]),
                                    k);
        rgb_lanes base = albedo_lanes(a, t, var);
        return pack_colour_lanes(srgb, k * base.c[0], k * base.c[1], k * base.c[2]);
    }
    default:
        return zero;
    }
}

/* A MASK material's group: the lanes that pass the depth test sample the
 * texture once, for its alpha (which the bilinear filter lerps in the
 * high half of the green lanes, split_lanes) and its colour; those whose
 * alpha is below alpha_min are dropped before anything is stored, as the
 * scalar loop drops them (sr_shade_alpha_passes). */
static inline __attribute__((always_inline)) uint64_t
fill_group_masked(const sr_tri_setup *s, const triangle_lanes *t, const sr_shade_context *c, float *depth,
                  uint32_t *ids, uint32_t *color, albedo a, bool srgb, sr_interp interp, bool with_ids, uint32_t id,
                  int n, vi pass, vf z, const edge_lanes e[3])
{
    lanes p;
    p.l1 = edge_to_float(e[1]) * s->inv_area2;
    p.l2 = edge_to_float(e[2]) * s->inv_area2;
    varyings_lanes(s, t, interp, varying_count(SR_SHADE_LAMBERT, a), &p);
    split_texels texel = sample_split_lanes(t, c, p.var[SECOND_VARYING], p.var[SECOND_VARYING + 1]);
    pass &= ((vi)texel.g >> 16) >= (int32_t)c->alpha_min;
    unsigned passed = lane_bits(pass);
    if (!passed)
        return 0;
    store_where(depth, pass, (vi)z, n);
    if (with_ids)
        store_where(ids, pass, (vi){ 0 } + (int32_t)(id + 1u), n);
    vf k = sr_interp_flat_normal(interp) ? t->lambert : lambert_lanes(c, p.var);
    store_where(color, pass, lit_albedo_lanes(a, srgb, t, texel, k), n);
    return (uint64_t)__builtin_popcount(passed);
}

/* Depth test, depth write, id write (with_ids) and shading of up to
 * SPAN_LANES pixels at depth, ids and color: `live` marks the lanes within
 * the row. */
static inline __attribute__((always_inline)) uint64_t
fill_group(const sr_tri_setup *s, const triangle_lanes *t, const sr_shade_context *c, float *depth, uint32_t *ids,
           uint32_t *color, sr_shade mode, albedo a, bool srgb, sr_interp interp, bool greater, bool with_ids,
           uint32_t id, int n, vi live, float z_row, vf k, const edge_lanes e[3])
{
    vf z = depth_lanes(s, z_row, k);
    vf stored = (vf)load_lanes(depth, n);
    vi pass = live & (greater ? z > stored : z < stored);
    unsigned passed = lane_bits(pass);
    if (!passed)
        return 0;
    if (a == ALBEDO_TEXTURE_MASKED)
        return fill_group_masked(s, t, c, depth, ids, color, a, srgb, interp, with_ids, id, n, pass, z, e);
    store_where(depth, pass, (vi)z, n);
    if (with_ids)
        store_where(ids, pass, (vi){ 0 } + (int32_t)(id + 1u), n);
    if (color_per_triangle(mode, a, interp)) {
        store_where(color, pass, t->color, n);
    } else if (mode != SR_SHADE_DEPTH) {
        lanes p;
        p.l1 = edge_to_float(e[1]) * s->inv_area2;
        p.l2 = edge_to_float(e[2]) * s->inv_area2;
        varyings_lanes(s, t, interp, varying_count(mode, a), &p);
        store_where(color, pass, shade_lanes(mode, a, srgb, interp, t, c, p.var, id), n);
    }
    return (uint64_t)__builtin_popcount(passed);
}

/* Asks for the depth and color PREFETCH_BYTES ahead on the row: each span
 * starts a new stream that the hardware prefetcher picks up only after a
 * few misses. Integer arithmetic, since the address may lie past the
 * framebuffer, where a prefetch is harmless but a pointer would be
 * undefined. */
#define PREFETCH_BYTES 512

static inline __attribute__((always_inline)) void prefetch_ahead(const float *depth, const uint32_t *ids,
                                                                 const uint32_t *color, bool with_ids)
{
    __builtin_prefetch((const void *)((uintptr_t)depth + PREFETCH_BYTES), 1);
    if (with_ids)
        __builtin_prefetch((const void *)((uintptr_t)ids + PREFETCH_BYTES), 1);
    __builtin_prefetch((const void *)((uintptr_t)color + PREFETCH_BYTES), 1);
}

static inline __attribute__((always_inline)) uint64_t
span_row(const sr_tri_setup *s, const triangle_lanes *t, const sr_shade_context *c, sr_framebuffer *fb,
         sr_shade mode, albedo a, bool srgb, sr_interp interp, bool greater, bool with_ids, uint32_t id,
         const sr_row_range *r)
{
    vi lane = lanes_index();
    vf column = r->k + __builtin_convertvector(lane, vf); /* exact: small integers */
    vdh lane_lo, lane_hi;
    for (int l = 0; l < SPAN_LANES / 2; l++) {
        lane_lo[l] = l;
        lane_hi[l] = l + SPAN_LANES / 2;
    }
    edge_lanes e[3] = { { { 0 } } }; /* e[0] unused: λ needs edges 1 and 2 only */
    vdh step[3] = { { 0 } };
    for (int k = 1; k < 3; k++) {
        double first = (double)r->e[k], per_pixel = (double)s->step_x[k];
        e[k] = (edge_lanes){ first + lane_lo * per_pixel, first + lane_hi * per_pixel };
        step[k] = (vdh){ 0 } + per_pixel * SPAN_LANES;
    }
    /* The row's pixels, held apart from fb, so the compiler need not load
     * fb->depth, fb->ids and fb->color again after each store. */
    float *depth = fb->depth + r->at;
    uint32_t *ids = with_ids ? fb->ids + r->at : NULL;
    uint32_t *color = fb->color + r->at;
    uint64_t fragments = 0;
    for (int d = 0; d < r->count; d += SPAN_LANES, column += (float)SPAN_LANES) {
        int n = r->count - d < SPAN_LANES ? r->count - d : SPAN_LANES;
        uint32_t *ids_at = with_ids ? ids + d : NULL;
        prefetch_ahead(depth + d, ids_at, color + d, with_ids);
        fragments += fill_group(s, t, c, depth + d, ids_at, color + d, mode, a, srgb, interp, greater, with_ids, id,
                                n, lane < n, r->z, column, e);
        for (int k = 1; k < 3; k++) {
            e[k].lo += step[k];
            e[k].hi += step[k];
        }
    }
    return fragments;
}

static inline __attribute__((always_inline)) uint64_t
span_rows(const sr_tri_setup *s, const sr_shade_context *c, sr_framebuffer *fb, sr_shade mode, albedo a, bool srgb,
          sr_interp interp, bool greater, bool with_ids, uint32_t id)
{
    triangle_lanes t = { .w = (vf){ 0 } + s->w, .lambert = (vf){ 0 } + s->lambert };
    triangle_lanes_init(&t, c);
    if (color_per_triangle(mode, a, interp))
        t.color = shade_lanes(mode, a, srgb, interp, &t, c, (vf[SR_MAX_VARYINGS]){ { 0 } }, id);
    uint64_t fragments = 0;
    for (int j = s->box.y0; j < s->box.y1; j++) {
        sr_row_range r;
        sr_row_make(s, fb, true, j, &r);
        if (r.count > 0)
            fragments += span_row(s, &t, c, fb, mode, a, srgb, interp, greater, with_ids, id, &r);
    }
    return fragments;
}

/* One loop per interp for the modes that read varyings. */
static inline __attribute__((always_inline)) uint64_t
span_triangle(const sr_tri_setup *s, const sr_shade_context *c, sr_framebuffer *fb, sr_shade mode, albedo a,
              bool srgb, bool greater, bool with_ids, uint32_t id)
{
    if (mode == SR_SHADE_LAMBERT && s->interp == SR_INTERP_FLAT_NORMAL)
        return span_rows(s, c, fb, mode, a, srgb, SR_INTERP_FLAT_NORMAL, greater, with_ids, id);
    if (mode == SR_SHADE_LAMBERT && s->interp == SR_INTERP_PERSPECTIVE_FLAT_NORMAL)
        return span_rows(s, c, fb, mode, a, srgb, SR_INTERP_PERSPECTIVE_FLAT_NORMAL, greater, with_ids, id);
    if (varying_count(mode, a) > 0 && !sr_interp_divides(s->interp))
        return span_rows(s, c, fb, mode, a, srgb, SR_INTERP_AFFINE, greater, with_ids, id);
    return span_rows(s, c, fb, mode, a, srgb, SR_INTERP_PERSPECTIVE, greater, with_ids, id);
}

#define SPAN_KERNEL(mode, a, srgb, greater, with_ids, name)                                                   \
    static uint64_t name(const sr_tri_setup *s, const sr_shade_context *c, sr_framebuffer *fb, uint32_t id)  \
    {                                                                                                         \
        return span_triangle(s, c, fb, mode, a, srgb, greater, with_ids, id);                                 \
    }

/* A mode's kernels for each depth test, without and with an ids plane
 * (a constant, so a draw without one pays no test per pixel for it), in
 * one colour space (srgb: SR_COLOR_SRGB's, a constant too). */
#define SPAN_KERNELS(mode, a, srgb, name)                                                                     \
    SPAN_KERNEL(mode, a, srgb, false, false, name##_less) SPAN_KERNEL(mode, a, srgb, true, false, name##_greater) \
    SPAN_KERNEL(mode, a, srgb, false, true, name##_less_ids)                                                  \
    SPAN_KERNEL(mode, a, srgb, true, true, name##_greater_ids)
/* [with ids][greater] */
typedef sr_span_kernel kernel_set[2][2];
#define KERNEL_SET(name) { { name##_less, name##_greater }, { name##_less_ids, name##_greater_ids } }

/* The modes and layouts with varyings: each has span kernels and, where
 * the file builds them (SPAN_TINY_GETTER, below), a tiny queue shader. */
#define WITH_VARYINGS(X)                                                                                      \
    X(SR_SHADE_LAMBERT, ALBEDO_GRAY, false, span_lambert_gray)                                                \
    X(SR_SHADE_LAMBERT, ALBEDO_COLOR, false, span_lambert_color)                                              \
    X(SR_SHADE_LAMBERT, ALBEDO_TEXTURE, false, span_lambert_texture)                                          \
    X(SR_SHADE_LAMBERT, ALBEDO_COLOR_TINTED, false, span_lambert_color_tinted)                                \
    X(SR_SHADE_LAMBERT, ALBEDO_TEXTURE_TINTED, false, span_lambert_texture_tinted)                            \
    X(SR_SHADE_COLOR, ALBEDO_NONE, false, span_color)                                                         \
    X(SR_SHADE_NORMAL, ALBEDO_NONE, false, span_normal)                                                       \
    X(SR_SHADE_TEXTURE, ALBEDO_NONE, false, span_texture)                                                     \
    X(SR_SHADE_LAMBERT, ALBEDO_GRAY, true, span_lambert_gray_srgb)                                            \
    X(SR_SHADE_LAMBERT, ALBEDO_COLOR, true, span_lambert_color_srgb)                                          \
    X(SR_SHADE_LAMBERT, ALBEDO_TEXTURE, true, span_lambert_texture_srgb)                                      \
    X(SR_SHADE_LAMBERT, ALBEDO_COLOR_TINTED, true, span_lambert_color_tinted_srgb)                            \
    X(SR_SHADE_LAMBERT, ALBEDO_TEXTURE_TINTED, true, span_lambert_texture_tinted_srgb)                        \
    X(SR_SHADE_COLOR, ALBEDO_NONE, true, span_color_srgb)

WITH_VARYINGS(SPAN_KERNELS)
/* No tiny queue shader: the queue writes depths before it shades, so a
 * MASK material's tiny triangles take the scalar tiny loop. */
SPAN_KERNELS(SR_SHADE_LAMBERT, ALBEDO_TEXTURE_MASKED, false, span_lambert_texture_masked)
SPAN_KERNELS(SR_SHADE_LAMBERT, ALBEDO_TEXTURE_MASKED, true, span_lambert_texture_masked_srgb)
SPAN_KERNELS(SR_SHADE_ID, ALBEDO_NONE, false, span_id)
SPAN_KERNELS(SR_SHADE_DEPTH, ALBEDO_NONE, false, span_depth)

/* The layout each kernel was compiled for, as sr_vertex_layout makes it. */
static bool layout_is(const sr_varying_layout *l, int count, int color, int uv, int normal)
{
    return l->count == count && l->color == color && l->uv == uv && l->normal == normal;
}

/* The albedo of a lambert context: its layout (a material without a
 * texture keeps the draw's count of varyings with uv -1, so the gray
 * kernel, which reads the normal alone, takes every count) and its tint
 * and alpha test. */
static albedo lambert_albedo(const sr_shade_context *c)
{
    const sr_varying_layout *l = &c->layout;
    if (layout_is(l, 5, -1, SECOND_VARYING, 0))
        return c->alpha_min ? ALBEDO_TEXTURE_MASKED : c->tinted ? ALBEDO_TEXTURE_TINTED : ALBEDO_TEXTURE;
    if (c->alpha_min)
        return ALBEDO_NONE;
    if (layout_is(l, 6, SECOND_VARYING, -1, 0))
        return c->tinted ? ALBEDO_COLOR_TINTED : ALBEDO_COLOR;
    bool gray = l->normal == 0 && l->uv < 0 && l->color < 0;
    return gray && (l->count == 3 || l->count == 5 || l->count == 6) ? ALBEDO_GRAY : ALBEDO_NONE;
}

/* A layout of the mode's three varyings at 0 (color or normal, the other
 * -1), alone or followed by the uvs a MASK material's alpha test reads in
 * a draw that cuts (draw/materials.c: its triangles never come here), or
 * their slots unused (a material without a texture): the kernel reads the
 * three alone. */
static bool three_first(const sr_varying_layout *l, int color, int normal)
{
    return layout_is(l, 3, color, -1, normal) ||
           (l->count == 5 && l->color == color && l->normal == normal && (l->uv == 3 || l->uv < 0));
}

/* Only the draw's own context (no material's) in the modes without an
 * albedo; texture shading's kernel takes a material's texture untinted. */
static bool plain(const sr_shade_context *c)
{
    return !c->tinted && !c->alpha_min;
}

/* Lambert's and color's kernels come in both colour spaces ([srgb]);
 * texture shading's draws a texel as it is in either (10_shade.h), and the
 * other modes write no colour of a mesh's. */
static const kernel_set *kernel_set_of(sr_shade mode, const sr_shade_context *c)
{
    static const kernel_set lambert[2][ALBEDO_TEXTURE_MASKED + 1] = {
        { [ALBEDO_GRAY] = KERNEL_SET(span_lambert_gray),
          [ALBEDO_COLOR] = KERNEL_SET(span_lambert_color),
          [ALBEDO_TEXTURE] = KERNEL_SET(span_lambert_texture),
          [ALBEDO_COLOR_TINTED] = KERNEL_SET(span_lambert_color_tinted),
          [ALBEDO_TEXTURE_TINTED] = KERNEL_SET(span_lambert_texture_tinted),
          [ALBEDO_TEXTURE_MASKED] = KERNEL_SET(span_lambert_texture_masked) },
        { [ALBEDO_GRAY] = KERNEL_SET(span_lambert_gray_srgb),
          [ALBEDO_COLOR] = KERNEL_SET(span_lambert_color_srgb),
          [ALBEDO_TEXTURE] = KERNEL_SET(span_lambert_texture_srgb),
          [ALBEDO_COLOR_TINTED] = KERNEL_SET(span_lambert_color_tinted_srgb),
          [ALBEDO_TEXTURE_TINTED] = KERNEL_SET(span_lambert_texture_tinted_srgb),
          [ALBEDO_TEXTURE_MASKED] = KERNEL_SET(span_lambert_texture_masked_srgb) },
    };
    static const kernel_set id = KERNEL_SET(span_id), depth = KERNEL_SET(span_depth),
                            color[2] = { KERNEL_SET(span_color), KERNEL_SET(span_color_srgb) },
                            normal = KERNEL_SET(span_normal), texture = KERNEL_SET(span_texture);
    const sr_varying_layout *l = &c->layout;
    switch (mode) {
    case SR_SHADE_LAMBERT: {
        albedo a = lambert_albedo(c);
        return a == ALBEDO_NONE ? NULL : &lambert[c->srgb][a];
    }
    case SR_SHADE_ID:      return &id;
    case SR_SHADE_DEPTH:   return &depth;
    case SR_SHADE_COLOR:   return three_first(l, 0, -1) ? &color[c->srgb] : NULL;
    case SR_SHADE_NORMAL:  return three_first(l, -1, 0) ? &normal : NULL;
    case SR_SHADE_TEXTURE: return layout_is(l, 2, -1, 0, -1) && plain(c) ? &texture : NULL;
    default:               return NULL;
    }
}

sr_span_kernel SPAN_KERNEL_GETTER(sr_shade mode, bool greater, bool with_ids, const sr_shade_context *c)
{
    const kernel_set *set = kernel_set_of(mode, c);
    return set ? (*set)[with_ids][greater] : NULL;
}

#ifdef SPAN_TINY_GETTER
/* The tiny queue's shaders, where the file builds them (not span_avx512.c). */

/* v's lanes picked by index (each in [0, SPAN_LANES)). */
static inline __attribute__((always_inline)) vf permute_lanes(vf v, vi index)
{
#ifdef SPAN_PERMUTE
    return SPAN_PERMUTE(v, index);
#else
    vf out;
    for (int l = 0; l < SPAN_LANES; l++)
        out[l] = v[index[l]];
    return out;
#endif
}

/* Interpolant k of each lane's triangle: the row from the group's first
 * triangle on, picked by each lane's offset from it. */
static inline __attribute__((always_inline)) vf tiny_param(const sr_tiny_queue *q, int k, int base, vi offset)
{
    vf row;
    memcpy(&row, &q->param[k][base], sizeof row);
    return permute_lanes(row, offset);
}

/* The tiny queue's pixels (tiny_queue.h, sr_tiny_queue), SPAN_LANES at a
 * time: λ1 and λ2 as queued, 1/w and the varyings from each lane's
 * triangle in varyings_lanes's operations, then the mode's shading. */
static inline __attribute__((always_inline)) void tiny_queue_shade(const sr_tiny_queue *q, const sr_shade_context *c,
                                                                   sr_framebuffer *fb, sr_shade mode, albedo a,
                                                                   bool srgb)
{
    triangle_lanes t = { .w = { 0 } };
    triangle_lanes_init(&t, c);
    for (int g = 0; g < q->pixels; g += SPAN_LANES) {
        int base = q->triangle[g];
        vi offset;
        memcpy(&offset, q->triangle + g, sizeof offset);
        offset -= base;
        lanes p;
        memcpy(&p.l1, q->l1 + g, sizeof p.l1);
        memcpy(&p.l2, q->l2 + g, sizeof p.l2);
        vf w = 1.0f / PLANE_LANES(tiny_param(q, SR_TINY_IW0, base, offset), tiny_param(q, SR_TINY_DIW1, base, offset),
                                  tiny_param(q, SR_TINY_DIW2, base, offset), p);
        _Static_assert(SR_MAX_VARYINGS == 8, "the unroll count below");
#pragma GCC unroll 8
        for (int k = 0; k < varying_count(mode, a); k++)
            p.var[k] = PLANE_LANES(tiny_param(q, SR_TINY_VAR0 + k, base, offset),
                                   tiny_param(q, SR_TINY_DVAR1 + k, base, offset),
                                   tiny_param(q, SR_TINY_DVAR2 + k, base, offset), p) *
                       w;
        vi colors = shade_lanes(mode, a, srgb, SR_INTERP_PERSPECTIVE, &t, c, p.var, 0);
        int live = q->pixels - g < SPAN_LANES ? q->pixels - g : SPAN_LANES;
        for (int l = 0; l < live; l++)
            fb->color[q->at[g + l]] = (uint32_t)colors[l];
    }
}

#define TINY_SHADER(mode, a, srgb, name)                                                                       \
    static void name##_tiny(const sr_tiny_queue *q, const sr_shade_context *c, sr_framebuffer *fb)            \
    {                                                                                                         \
        tiny_queue_shade(q, c, fb, mode, a, srgb);                                                            \
    }

WITH_VARYINGS(TINY_SHADER)

sr_tiny_shader SPAN_TINY_GETTER(sr_shade mode, const sr_shade_context *c)
{
    static const sr_tiny_shader lambert[2][ALBEDO_TEXTURE_MASKED + 1] = {
        { [ALBEDO_GRAY] = span_lambert_gray_tiny,
          [ALBEDO_COLOR] = span_lambert_color_tiny,
          [ALBEDO_TEXTURE] = span_lambert_texture_tiny,
          [ALBEDO_COLOR_TINTED] = span_lambert_color_tinted_tiny,
          [ALBEDO_TEXTURE_TINTED] = span_lambert_texture_tinted_tiny,
          [ALBEDO_TEXTURE_MASKED] = NULL },
        { [ALBEDO_GRAY] = span_lambert_gray_srgb_tiny,
          [ALBEDO_COLOR] = span_lambert_color_srgb_tiny,
          [ALBEDO_TEXTURE] = span_lambert_texture_srgb_tiny,
          [ALBEDO_COLOR_TINTED] = span_lambert_color_tinted_srgb_tiny,
          [ALBEDO_TEXTURE_TINTED] = span_lambert_texture_tinted_srgb_tiny,
          [ALBEDO_TEXTURE_MASKED] = NULL },
    };
    static const sr_tiny_shader color[2] = { span_color_tiny, span_color_srgb_tiny };
    if (!kernel_set_of(mode, c)) /* the layouts the kernels were compiled for */
        return NULL;
    switch (mode) {
    case SR_SHADE_LAMBERT: return lambert[c->srgb][lambert_albedo(c)];
    case SR_SHADE_COLOR:   return color[c->srgb];
    case SR_SHADE_NORMAL:  return span_normal_tiny;
    case SR_SHADE_TEXTURE: return span_texture_tiny;
    default:               return NULL; /* no varyings: nothing to defer */
    }
}
#endif
