/* error.h — filling an sr_error (softrast/softrast.h).
 *
 * Functions that can fail on user input (files, options) take an `sr_error *`
 * and return false on failure after writing one line into it, without the
 * "softrast: error: " prefix (the program adds that). Parse errors start with
 * "FILE:LINE: ". Passing NULL is allowed and discards the message.
 */
#ifndef SOFTRAST_CORE_ERROR_H
#define SOFTRAST_CORE_ERROR_H

#include <stdbool.h>

#include "softrast/softrast.h"

/* Formats the message into err (if err is not NULL); always returns false so a
 * caller can write `return sr_error_set(err, "...");`. */
bool sr_error_set(sr_error *err, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

#endif
