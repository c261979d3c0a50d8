/* fuzz/fuzz_common.h — what the fuzz targets share: reporting a broken
 * invariant. fail() prints what and where, then abort()s so libFuzzer saves
 * the input; CHECK(cond, fmt, ...) calls it when cond is false. */
#ifndef SOFTRAST_FUZZ_COMMON_H
#define SOFTRAST_FUZZ_COMMON_H

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

static inline void fail(const char *file, int line, const char *expr, const char *fmt, ...)
    __attribute__((format(printf, 4, 5), noreturn));

static inline void fail(const char *file, int line, const char *expr, const char *fmt, ...)
{
    fprintf(stderr, "\n%s:%d: invariant failed: %s\n  ", file, line, expr);
    va_list ap;
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\n");
    abort();
}

#define CHECK(cond, ...)                                            \
    do {                                                            \
        if (!(cond))                                                \
            fail(__FILE__, __LINE__, #cond, __VA_ARGS__);           \
    } while (0)

#endif
