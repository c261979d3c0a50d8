/* tests/exact_cut.h — the clipper tests' GNU MP references: the exact
 * plane distance of a point, and the exact cut of an edge on a plane,
 * a + t(b − a) with t = da / (da − db), da and db the end points' exact
 * plane distances, rounded once to double. */
#ifndef SOFTRAST_TESTS_EXACT_CUT_H
#define SOFTRAST_TESTS_EXACT_CUT_H

#include <gmp.h>

#include "pipeline/04_clip/clip.h"

/* The plane distance of an exact point; under the depth model near and far
 * come from w (a·w + b, w − a·w − b), as the clipper takes them. */
static inline void exact_distance(int plane, mpq_t *const c, const sr_clip_depth *depth, mpq_t d)
{
    const sr_clip_plane_row *row = &sr_clip_plane_table[plane];
    if (depth->on && row->axis == SR_Z) {
        mpq_t t;
        mpq_init(t);
        mpq_set_d(t, depth->a);
        mpq_mul(t, t, c[SR_W]);
        mpq_set_d(d, depth->b);
        mpq_add(d, d, t); /* near: a·w + b */
        if (row->bounded_by_w)
            mpq_sub(d, c[SR_W], d);
        mpq_clear(t);
        return;
    }
    mpq_set(d, c[row->axis]);
    if (row->sign < 0)
        mpq_neg(d, d);
    if (row->bounded_by_w)
        mpq_add(d, d, c[SR_W]);
}

static inline double exact_cut_coordinate(mpq_t da, mpq_t db, float a, float b)
{
    mpq_t t, ai, v;
    mpq_inits(t, ai, v, NULL);
    mpq_sub(t, da, db);
    mpq_div(t, da, t);
    mpq_set_d(ai, a);
    mpq_set_d(v, b);
    mpq_sub(v, v, ai);
    mpq_mul(v, v, t);
    mpq_add(v, v, ai);
    double r = mpq_get_d(v);
    mpq_clears(t, ai, v, NULL);
    return r;
}

#endif
