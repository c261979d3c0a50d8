#include <stdarg.h>
#include <stdio.h>

#include "error.h"

/* One line, whatever a message quotes from a file (a name or value that
 * holds a newline or another control character): each becomes a space. */
bool sr_error_set(sr_error *err, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
        for (char *c = err->message; *c; c++)
            if ((unsigned char)*c < 0x20 || *c == 0x7f)
                *c = ' ';
    }
    return false;
}
