/* tests/test_rng.h — the tests' deterministic random numbers: splitmix64,
 * the same sequence on every libc, a fixed seed per test. Shared by
 * clip_helpers.h and scene_helpers.h (and so by every test that uses them).
 *
 * Everything here is static inline so each test file takes what it uses. */
#ifndef SOFTRAST_TESTS_TEST_RNG_H
#define SOFTRAST_TESTS_TEST_RNG_H

#include <math.h>
#include <stdint.h>

typedef struct test_rng {
    uint64_t state;
} test_rng;

static inline uint64_t rng_next(test_rng *r)
{
    uint64_t z = (r->state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1). */
static inline double rng_unit(test_rng *r)
{
    return (double)(rng_next(r) >> 11) * 0x1.0p-53;
}

/* Uniform in [lo, hi). */
static inline double rng_uniform(test_rng *r, double lo, double hi)
{
    return lo + (hi - lo) * (double)(rng_next(r) >> 11) * 0x1.0p-53;
}

/* Uniform in [0, n). */
static inline int rng_below(test_rng *r, int n)
{
    return (int)(rng_next(r) % (uint64_t)n);
}

/* Uniform in [lo, hi] (inclusive). */
static inline int64_t rng_range(test_rng *r, int64_t lo, int64_t hi)
{
    return lo + (int64_t)(rng_next(r) % (uint64_t)(hi - lo + 1));
}

/* A random rotation, from a random unit quaternion. */
static inline void rng_rotation(test_rng *r, double out[3][3])
{
    double q[4], n = 0.0;
    for (int k = 0; k < 4; k++) {
        q[k] = rng_uniform(r, -1.0, 1.0);
        n += q[k] * q[k];
    }
    n = sqrt(n);
    double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    const double m[3][3] = {
        { 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y) },
        { 2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x) },
        { 2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y) },
    };
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            out[i][j] = m[i][j];
}

#endif
