/* expansion.h — exact floating-point sums and products for the clipper and
 * the studies that measure it (Shewchuk, "Adaptive Precision Floating-Point
 * Arithmetic"): a value is an expansion, an array of doubles whose exact sum
 * it is, smallest first and nonoverlapping. Not public API. */
#ifndef SOFTRAST_EXPANSION_H
#define SOFTRAST_EXPANSION_H

#include <math.h>

/* s + e = a + b exactly (Knuth). */
static inline void two_sum(double a, double b, double *s, double *e)
{
    *s = a + b;
    double bv = *s - a;
    *e = (a - (*s - bv)) + (b - bv);
}

/* p + e = a · b exactly (the fused multiply-add gives the rounding error). */
static inline void two_product(double a, double b, double *p, double *e)
{
    *p = a * b;
    *e = fma(a, b, -*p);
}

/* s + e = a + b exactly, given |a| >= |b| or a = 0 (Dekker). */
static inline void fast_two_sum(double a, double b, double *s, double *e)
{
    *s = a + b;
    *e = b - (*s - a);
}

/* Adds b to the expansion e[0..n), exactly: Grow-Expansion, in place.
 * Returns the new length. */
static inline int grow(double *e, int n, double b)
{
    double q = b;
    for (int i = 0; i < n; i++) {
        double s, err;
        two_sum(q, e[i], &s, &err);
        e[i] = err;
        q = s;
    }
    e[n] = q;
    return n + 1;
}

/* The same value in as few parts as it needs, in place (Shewchuk's
 * Compress; the zeros Grow-Expansion leaves go with it). Returns the new
 * length. */
static inline int compress(double *e, int n)
{
    if (n == 0)
        return 0;
    int bottom = n - 1;
    double q = e[bottom];
    for (int i = n - 2; i >= 0; i--) {
        double s, err;
        fast_two_sum(q, e[i], &s, &err);
        if (err != 0.0) {
            e[bottom--] = s;
            q = err;
        } else {
            q = s;
        }
    }
    int top = 0;
    for (int i = bottom + 1; i < n; i++) {
        double s, err;
        fast_two_sum(e[i], q, &s, &err);
        if (err != 0.0)
            e[top++] = err;
        q = s;
    }
    e[top] = q;
    return top + 1;
}

/* The expansion's value to about one rounding: smallest parts first. */
static inline double expansion_value(const double *e, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        s += e[i];
    return s;
}

/* The same in long double, to measure a double result against. */
static inline long double expansion_value_long(const double *e, int n)
{
    long double s = 0.0L;
    for (int i = 0; i < n; i++)
        s += e[i];
    return s;
}

/* The same with its sign exact: the parts below the largest nonzero one sum
 * to less than it, so the sum smallest first has its sign or, when the
 * rounding of those parts reaches it exactly, is 0; then the largest part
 * stands in. */
static inline double expansion_signed_value(const double *e, int n)
{
    double v = expansion_value(e, n), top = 0.0;
    for (int i = 0; i < n; i++)
        top = e[i] != 0.0 ? e[i] : top;
    return v != 0.0 ? v : top;
}

#endif
