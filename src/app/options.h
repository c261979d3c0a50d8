/* options.h — table-driven command-line options for the softrast subcommands.
 *
 * Each subcommand describes its options in a table of sr_option; the parser
 * fills the targets, accepts "--name value" and "--name=value", and fails with
 * one line naming the option for anything it cannot read exactly: unknown
 * options, missing values, trailing junk, non-finite numbers, values out of
 * range.
 */
#ifndef SOFTRAST_APP_OPTIONS_H
#define SOFTRAST_APP_OPTIONS_H

#include <stdbool.h>
#include <stdio.h>

#include "softrast_private.h"

typedef enum sr_option_kind {
    SR_OPT_FLOAT,  /* float *, within [lo, hi], or +inf if allow_infinity */
    SR_OPT_INT,    /* int *, within [lo, hi] */
    SR_OPT_VEC3,   /* float[3], "X,Y,Z" */
    SR_OPT_DVEC3,  /* double[3], "X,Y,Z": a point kept to double precision */
    SR_OPT_NUMBERS, /* double[count], "a,b,...": exactly count numbers (at most SR_OPT_MAX_NUMBERS) */
    SR_OPT_SIZE,   /* int[2], "WxH", each within [lo, hi] */
    SR_OPT_RANGE,  /* int[2], "A:B", lo <= A < B <= hi: the half-open range [A, B) */
    SR_OPT_STRING, /* const char ** */
    SR_OPT_FLAG,   /* bool *, takes no value */
    SR_OPT_CHOICE  /* int *, index into choices */
} sr_option_kind;

#define SR_OPT_MAX_NUMBERS 16

typedef struct sr_option {
    const char *name; /* "--size" */
    sr_option_kind kind;
    void *target;
    const char *value_name; /* "WxH" in the help */
    const char *help;
    double lo, hi;
    const char *const *choices; /* NULL-terminated, for SR_OPT_CHOICE */
    bool *seen;                 /* optional: set when the option is given */
    bool allow_infinity;        /* SR_OPT_FLOAT: "inf" is accepted (as +inf) */
    int count;                  /* SR_OPT_NUMBERS: how many */
} sr_option;

/* Parses argv[first..argc). Non-option words go to positional (at most
 * max_positional). When --help or -h is given, sets *help and prints usage
 * and the table's help on stdout (once all of argv has parsed). */
bool sr_options_parse(const sr_option *table, const char *usage, int argc, char **argv, int first,
                      const char **positional, int max_positional, int *positional_count, bool *help, sr_error *err);

#endif
