/* tests/exact_cut.h — the exact cut of an edge on a plane, for the clipper
 * tests' GNU MP references: a + t(b − a) with t = da / (da − db), da and db
 * the end points' exact plane distances, rounded once to double. */
#ifndef SOFTRAST_TESTS_EXACT_CUT_H
#define SOFTRAST_TESTS_EXACT_CUT_H

#include <gmp.h>

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
