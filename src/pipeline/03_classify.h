/* classify.h — stage 3: the six planes of the clip volume, a point's
 * distance to each, and its outcode.
 *
 * Classification gives each clip-space vertex a 6-bit outcode, one bit per
 * plane it is outside of (distance < 0), plus SR_OUT_NONFINITE for NaN or inf.
 * A triangle whose outcodes share a bit is rejected; one whose outcodes are
 * all zero is accepted unclipped; the rest go to the clipper (clip.h) with
 * the OR of their outcodes. Distances are exact in sign for float input, in
 * float, double or exact arithmetic (expansion.h) as each caller needs; the
 * clipper's layers (clip_exact.h, clip_corner.h, clip.h) build on them.
 */
#ifndef SOFTRAST_PIPELINE_CLASSIFY_H
#define SOFTRAST_PIPELINE_CLASSIFY_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "stages.h"

/* Planes in processing order; the outcode bit of plane p is 1 << p. */
typedef enum sr_clip_plane {
    SR_PLANE_NEAR = 0,
    SR_PLANE_FAR,
    SR_PLANE_LEFT,
    SR_PLANE_RIGHT,
    SR_PLANE_BOTTOM,
    SR_PLANE_TOP
} sr_clip_plane;

/* The one table of the planes (as Mesa's clipper keeps its plane vectors):
 * plane p is sign·c[axis] >= -w, or sign·c[axis] >= 0 for the one not
 * bounded by w, and a point's distance to it is w + sign·c[axis] (without
 * the w for that one). Under a depth model (sr_clip_depth) the planes on
 * the z axis are planes in w alone. */
typedef struct sr_clip_plane_row {
    int axis;          /* SR_X, SR_Y or SR_Z */
    int sign;          /* +1: the lower bound, -1: the upper */
    bool bounded_by_w; /* false: z >= 0 */
    const char *name;
} sr_clip_plane_row;

static const sr_clip_plane_row sr_clip_plane_table[SR_CLIP_PLANES] = {
    [SR_PLANE_NEAR] = { SR_Z, +1, false, "near" }, /* z >= 0 */
    [SR_PLANE_FAR] = { SR_Z, -1, true, "far" }, /* z <= w */
    [SR_PLANE_LEFT] = { SR_X, +1, true, "left" }, /* x >= -w */
    [SR_PLANE_RIGHT] = { SR_X, -1, true, "right" }, /* x <= w */
    [SR_PLANE_BOTTOM] = { SR_Y, +1, true, "bottom" }, /* y >= -w */
    [SR_PLANE_TOP] = { SR_Y, -1, true, "top" }, /* y <= w */
};

/* The distance from the table, given the point's coordinate on the plane's
 * axis and its w, in double (exact in sign for float input). */
static inline double sr_clip_plane_distance(sr_clip_plane plane, double coordinate, double w)
{
    const sr_clip_plane_row *row = &sr_clip_plane_table[plane];
    double along = row->sign * coordinate;
    return row->bounded_by_w ? w + along : along;
}

/* The coordinate on the plane's axis of the point of the plane at this w
 * (0 for z >= 0: the plane does not move with w). */
static inline float sr_clip_plane_coordinate_at(sr_clip_plane plane, float w)
{
    const sr_clip_plane_row *row = &sr_clip_plane_table[plane];
    return !row->bounded_by_w ? 0.0f : row->sign > 0 ? -w : w;
}

/* Whether a depth model, when on, gives the plane's distance from w. */
static inline bool sr_clip_plane_in_depth_model(sr_clip_plane plane)
{
    return sr_clip_plane_table[plane].axis == SR_Z;
}

#define SR_OUT_PLANES ((1u << SR_CLIP_PLANES) - 1u)
#define SR_OUT_NONFINITE (1u << SR_CLIP_PLANES)

/* Signed distance of a clip-space point to a plane, in double: the sign is
 * exact for float input, and a point is inside iff the distance is >= 0. */
double sr_clip_distance(sr_clip_plane plane, const float *clip);

unsigned sr_clip_outcode(const float *clip);

/* The depth model of a projection (column-major, m[col][row]; types.h): on
 * when its w row is (0, 0, ±1, 0) and its z row (0, 0, A, B), A and B
 * finite (every perspective camera, standard or reversed, finite or
 * infinite far); off for orthographic and any other projection. */
sr_clip_depth sr_clip_depth_of(const float projection[4][4]);

/* The same under a depth model (NULL or off: the functions above): near
 * and far distances come from w, a·w + b and w − a·w − b. The sign is exact
 * for float input and the value within about one double rounding of the
 * exact distance. */
double sr_clip_distance_with(sr_clip_plane plane, const float *clip, const sr_clip_depth *depth);

/* sr_clip_outcode under a depth model (NULL or off: sr_clip_outcode's).
 * Inline: the vertex phase takes one per vertex where it does not take
 * four at a time (below: a block's last few, a mesh given in clip space).
 * The planes bounded by w
 * are tested in float, s·c < −w: exact, as the sign of w + s·c is (a sum of
 * floats is zero only where they cancel), and so is z < 0 for the near
 * plane without a model. Under it, the near and far bits: a·w + b rounds
 * once, so its sign is exact; (w − a·w) − b rounds twice, by at most 2^-53
 * of |w − a·w| and of the result, so a result past 4ε|w − a·w| has the
 * exact sign and only one closer to the plane pays for the expansion. */
static inline unsigned sr_clip_outcode_with(const float *c, const sr_clip_depth *depth)
{
    _Static_assert(SR_PLANE_NEAR == 0 && SR_PLANE_FAR == 1 && SR_CLIP_PLANES == 6,
                   "near and far are the planes on z, the depth model's");
    float x = c[SR_X], y = c[SR_Y], z = c[SR_Z], w = c[SR_W];
    if (!isfinite(x) || !isfinite(y) || !isfinite(z) || !isfinite(w))
        return SR_OUT_NONFINITE;
    unsigned sides = (unsigned)(x < -w) << SR_PLANE_LEFT | (unsigned)(x > w) << SR_PLANE_RIGHT |
                     (unsigned)(y < -w) << SR_PLANE_BOTTOM | (unsigned)(y > w) << SR_PLANE_TOP;
    if (!depth || !depth->on)
        return sides | (unsigned)(z < 0.0f) << SR_PLANE_NEAR | (unsigned)(z > w) << SR_PLANE_FAR;
    double aw = (double)depth->a * w, rest = w - aw;
    double near = aw + depth->b, far = rest - depth->b;
    if (!(fabs(far) > 4.0 * DBL_EPSILON * fabs(rest)))
        far = sr_clip_distance_with(SR_PLANE_FAR, c, depth);
    return sides | (unsigned)(near < 0.0) << SR_PLANE_NEAR | (unsigned)(far < 0.0) << SR_PLANE_FAR;
}

#if defined(__SSE2__)
/* The bits of a four-lane mask, bit k into the low bit of byte k (the
 * four terms of the product cannot overlap, so nothing carries). */
static inline uint32_t sr_clip_lane_bytes(unsigned mask)
{
    return (mask * 0x00204081u) & 0x01010101u;
}

/* sr_clip_outcode_with of four clip positions at once, given by coordinate:
 * lane k of c[SR_X] .. c[SR_W] is position k. Byte k of the result (little
 * endian: codes + k once stored) is position k's outcode. The same tests in
 * the same precision, a coordinate's four lanes at a time (an exponent of
 * all ones is a NaN or an inf); the far planes too close to call in double
 * are decided as there, one at a time. One vertex at a time, the
 * outcode's compares and their bits were most of the vertex phase's
 * classifying loop where most vertices carry no varyings. */
static inline uint32_t sr_clip_outcodes_four(const __m128 c[4], const sr_clip_depth *depth)
{
    __m128i exponent = _mm_set1_epi32(0x7F800000), all_ones = _mm_setzero_si128();
#pragma GCC unroll 4
    for (int k = 0; k < 4; k++)
        all_ones = _mm_or_si128(all_ones,
                                _mm_cmpeq_epi32(_mm_and_si128(_mm_castps_si128(c[k]), exponent), exponent));
    unsigned nonfinite = (unsigned)_mm_movemask_ps(_mm_castsi128_ps(all_ones));
    __m128 w = c[SR_W], minus_w = _mm_xor_ps(w, _mm_castsi128_ps(_mm_set1_epi32((int)0x80000000u)));
    uint32_t codes = sr_clip_lane_bytes((unsigned)_mm_movemask_ps(_mm_cmplt_ps(c[SR_X], minus_w))) << SR_PLANE_LEFT |
                     sr_clip_lane_bytes((unsigned)_mm_movemask_ps(_mm_cmpgt_ps(c[SR_X], w))) << SR_PLANE_RIGHT |
                     sr_clip_lane_bytes((unsigned)_mm_movemask_ps(_mm_cmplt_ps(c[SR_Y], minus_w))) << SR_PLANE_BOTTOM |
                     sr_clip_lane_bytes((unsigned)_mm_movemask_ps(_mm_cmpgt_ps(c[SR_Y], w))) << SR_PLANE_TOP;
    unsigned near = 0, far = 0;
    if (!depth || !depth->on) {
        near = (unsigned)_mm_movemask_ps(_mm_cmplt_ps(c[SR_Z], _mm_setzero_ps()));
        far = (unsigned)_mm_movemask_ps(_mm_cmpgt_ps(c[SR_Z], w));
    } else {
        __m128d a = _mm_set1_pd((double)depth->a), b = _mm_set1_pd((double)depth->b), zero = _mm_setzero_pd();
        __m128d margin = _mm_set1_pd(4.0 * DBL_EPSILON), magnitude = _mm_castsi128_pd(_mm_set1_epi64x(INT64_MAX));
        unsigned doubt = 0;
#pragma GCC unroll 2
        for (int half = 0; half < 2; half++) {
            __m128d wd = _mm_cvtps_pd(half ? _mm_movehl_ps(w, w) : w);
            __m128d aw = _mm_mul_pd(a, wd), rest = _mm_sub_pd(wd, aw);
            __m128d near_d = _mm_add_pd(aw, b), far_d = _mm_sub_pd(rest, b);
            near |= (unsigned)_mm_movemask_pd(_mm_cmplt_pd(near_d, zero)) << 2 * half;
            far |= (unsigned)_mm_movemask_pd(_mm_cmplt_pd(far_d, zero)) << 2 * half;
            doubt |= (unsigned)_mm_movemask_pd(_mm_cmpngt_pd(_mm_and_pd(far_d, magnitude),
                                                             _mm_mul_pd(margin, _mm_and_pd(rest, magnitude))))
                     << 2 * half;
        }
        for (doubt &= ~nonfinite; doubt; doubt &= doubt - 1) {
            int lane = __builtin_ctz(doubt);
            float lanes[4][4], position[4];
            for (int k = 0; k < 4; k++) {
                _mm_storeu_ps(lanes[k], c[k]);
                position[k] = lanes[k][lane];
            }
            far = (far & ~(1u << lane)) |
                  (unsigned)(sr_clip_distance_with(SR_PLANE_FAR, position, depth) < 0.0) << lane;
        }
    }
    codes |= sr_clip_lane_bytes(near) << SR_PLANE_NEAR | sr_clip_lane_bytes(far) << SR_PLANE_FAR;
    uint32_t nonfinite_bytes = sr_clip_lane_bytes(nonfinite);
    return (codes & ~(nonfinite_bytes * 0xFFu)) | nonfinite_bytes * SR_OUT_NONFINITE;
}
#endif

/* The distance of a point in double (depth as above; a·w rounds too, as
 * does w − a·w), within a few roundings of the exact one. */
double sr_clip_distance_d(sr_clip_plane plane, const double c[4], const sr_clip_depth *depth);

/* The longest distance expansion: far under the depth model, w − a·w − b. */
#define SR_CLIP_DISTANCE_TERMS 3

/* The plane distance of a clip-space point, exactly, as an expansion d[0..n)
 * (smallest first); under the depth model (depth on, NULL: off) near and far
 * come from w. Returns n. */
int sr_clip_distance_exact(sr_clip_plane plane, const float *c, const sr_clip_depth *depth,
                           double d[SR_CLIP_DISTANCE_TERMS]);

/* Where an object-space box lies against the clip volume under a transform:
 * every point inside every plane (the draw can skip classification and
 * clipping), every point outside one plane (the draw can skip the mesh), or
 * neither / unknown. Decided on the 8 corners with a margin of
 * SR_CLIP_BOX_MARGIN times the size of the terms summed into a coordinate, so
 * the float rounding of the vertices cannot cross a plane the corners clear. */
typedef enum sr_clip_box { SR_BOX_CROSSES = 0, SR_BOX_INSIDE, SR_BOX_OUTSIDE } sr_clip_box;
#define SR_CLIP_BOX_MARGIN 1e-4
sr_clip_box sr_clip_classify_box(const float clip_from_object[4][4], const float lo[3], const float hi[3]);
/* The same, with the outcode bits of the planes the whole box is outside. */
sr_clip_box sr_clip_classify_box_planes(const float clip_from_object[4][4], const float lo[3], const float hi[3],
                                        unsigned *outside);

/* n triangles rejected whole, all corners outside the planes whose bits are
 * set in `planes` (at least one): counted under the first of them. */
static inline void sr_clip_count_rejected(sr_stats *stats, unsigned planes, uint64_t n)
{
    _Static_assert(sizeof stats->rejected_by_plane / sizeof stats->rejected_by_plane[0] == SR_CLIP_PLANES,
                   "one count per clip plane");
    stats->rejected += n;
    stats->rejected_by_plane[__builtin_ctz(planes)] += n;
}

/* Sets the cut vertex's coordinate for the plane exactly on it (x = −w for
 * left, z = 0 for near, ...; under the depth model near and far are planes
 * in w alone and z follows w, a·w + b rounded once). */
void sr_clip_place_on_plane(sr_clip_plane plane, const sr_clip_depth *depth, float *clip);

/* Under the depth model, z is a·w + b of the point's w, rounded once. */
void sr_clip_z_from_w(const sr_clip_depth *depth, float *clip);

#endif
