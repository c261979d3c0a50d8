#include <stdarg.h>
#include <stdio.h>

#include "error.h"

bool sr_error_set(sr_error *err, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
    }
    return false;
}
