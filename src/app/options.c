#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "options.h"

/* Largest coordinate an X,Y,Z option takes: within float range, where the
 * camera is drawn. */
#define VEC3_LIMIT 3.0e38

static bool parse_double(const char *text, double lo, double hi, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(text, &end);
    if (end == text || *end != '\0' || errno == ERANGE || !isfinite(v) || v < lo || v > hi)
        return false;
    *out = v;
    return true;
}

static bool parse_long(const char *text, double lo, double hi, int *out)
{
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (end == text || *end != '\0' || errno == ERANGE || v < lo || v > hi)
        return false;
    *out = (int)v;
    return true;
}

/* "a<sep>b<sep>c": splits into at most n fields of a copy of text. */
static int split(const char *text, char sep, char *buf, size_t cap, char **fields, int n)
{
    if (strlen(text) >= cap)
        return 0;
    strcpy(buf, text);
    int count = 0;
    for (char *p = buf; count < n; count++) {
        fields[count] = p;
        p = strchr(p, sep);
        if (!p)
            return count + 1;
        *p++ = '\0';
    }
    return n + 1; /* too many fields */
}

/* n numbers "a,b,...", each finite within ±VEC3_LIMIT. */
static bool parse_doubles(const char *text, int n, double *out)
{
    char buf[1024], *f[SR_OPT_MAX_NUMBERS];
    if (n > SR_OPT_MAX_NUMBERS || split(text, ',', buf, sizeof buf, f, n) != n)
        return false;
    for (int i = 0; i < n; i++)
        if (!parse_double(f[i], -VEC3_LIMIT, VEC3_LIMIT, &out[i]))
            return false;
    return true;
}

static bool parse_dvec3(const char *text, double *out)
{
    return parse_doubles(text, 3, out);
}

static bool parse_vec3(const char *text, float *out)
{
    double v[3];
    if (!parse_dvec3(text, v))
        return false;
    for (int i = 0; i < 3; i++)
        out[i] = (float)v[i];
    return true;
}

/* "A<sep>B", two whole numbers each within [lo, hi]. */
static bool parse_pair(const char *text, char sep, double lo, double hi, int *out)
{
    char buf[64], *f[2];
    return split(text, sep, buf, sizeof buf, f, 2) == 2 && parse_long(f[0], lo, hi, &out[0]) &&
           parse_long(f[1], lo, hi, &out[1]);
}

static bool parse_range(const char *text, double lo, double hi, int *out)
{
    int pair[2];
    if (!parse_pair(text, ':', lo, hi, pair) || pair[0] >= pair[1])
        return false;
    out[0] = pair[0];
    out[1] = pair[1];
    return true;
}

static bool parse_choice(const char *text, const char *const *choices, int *out)
{
    for (int i = 0; choices[i]; i++) {
        if (strcmp(text, choices[i]) == 0) {
            *out = i;
            return true;
        }
    }
    return false;
}

static void describe_expected(const sr_option *o, char *buf, size_t cap)
{
    switch (o->kind) {
    case SR_OPT_FLOAT:
        snprintf(buf, cap, "a finite number in [%g, %g]%s", o->lo, o->hi, o->allow_infinity ? ", or inf" : "");
        break;
    case SR_OPT_INT:   snprintf(buf, cap, "a whole number in [%g, %g]", o->lo, o->hi); break;
    case SR_OPT_VEC3:
    case SR_OPT_DVEC3:
        snprintf(buf, cap, "three numbers X,Y,Z, each in [%g, %g]", -VEC3_LIMIT, VEC3_LIMIT);
        break;
    case SR_OPT_NUMBERS:
        snprintf(buf, cap, "%d comma-separated numbers, each in [%g, %g]", o->count, -VEC3_LIMIT, VEC3_LIMIT);
        break;
    case SR_OPT_SIZE:  snprintf(buf, cap, "WxH with each side in [%g, %g]", o->lo, o->hi); break;
    case SR_OPT_RANGE:
        snprintf(buf, cap, "A:B, whole numbers with %g <= A < B <= %g (A up to, not including, B)", o->lo, o->hi);
        break;
    case SR_OPT_CHOICE: {
        size_t used = (size_t)snprintf(buf, cap, "one of");
        for (int i = 0; o->choices[i] && used < cap; i++)
            used += (size_t)snprintf(buf + used, cap - used, "%s%s", i ? "|" : " ", o->choices[i]);
        break;
    }
    default: snprintf(buf, cap, "a value"); break;
    }
}

static bool apply_value(const sr_option *o, const char *text)
{
    double d;
    switch (o->kind) {
    case SR_OPT_FLOAT:
        if (o->allow_infinity && (strcmp(text, "inf") == 0 || strcmp(text, "+inf") == 0)) {
            *(float *)o->target = INFINITY;
            return true;
        }
        if (!parse_double(text, o->lo, o->hi, &d))
            return false;
        *(float *)o->target = (float)d;
        return true;
    case SR_OPT_INT:    return parse_long(text, o->lo, o->hi, o->target);
    case SR_OPT_VEC3:   return parse_vec3(text, o->target);
    case SR_OPT_DVEC3:  return parse_dvec3(text, o->target);
    case SR_OPT_NUMBERS: return parse_doubles(text, o->count, o->target);
    case SR_OPT_SIZE:   return parse_pair(text, 'x', o->lo, o->hi, o->target);
    case SR_OPT_RANGE:  return parse_range(text, o->lo, o->hi, o->target);
    case SR_OPT_CHOICE: return parse_choice(text, o->choices, o->target);
    case SR_OPT_STRING:
        *(const char **)o->target = text;
        return *text != '\0';
    case SR_OPT_FLAG:
        *(bool *)o->target = true;
        return true;
    }
    return false;
}

static const sr_option *find_option(const sr_option *table, const char *name, size_t len)
{
    for (const sr_option *o = table; o->name; o++)
        if (strlen(o->name) == len && strncmp(o->name, name, len) == 0)
            return o;
    return NULL;
}

/* One "--name[=value]" at argv[*i]; advances *i past a separate value. */
static bool parse_one(const sr_option *table, int argc, char **argv, int *i, sr_error *err)
{
    const char *arg = argv[*i], *eq = strchr(arg, '=');
    const sr_option *o = find_option(table, arg, eq ? (size_t)(eq - arg) : strlen(arg));
    if (!o)
        return sr_error_set(err, "unknown option '%s' (see --help)", arg);
    const char *value = eq ? eq + 1 : NULL;
    if (o->kind == SR_OPT_FLAG && value)
        return sr_error_set(err, "%s takes no value", o->name);
    if (o->kind != SR_OPT_FLAG && !value) {
        if (*i + 1 >= argc)
            return sr_error_set(err, "%s needs a value (%s)", o->name, o->value_name);
        value = argv[++*i];
    }
    if (!apply_value(o, value ? value : "")) {
        char expected[256];
        describe_expected(o, expected, sizeof expected);
        return sr_error_set(err, "bad value '%s' for %s: expected %s", value, o->name, expected);
    }
    if (o->seen)
        *o->seen = true;
    return true;
}

static void print_help(FILE *out, const char *usage, const sr_option *table)
{
    fprintf(out, "%s\n\noptions:\n", usage);
    for (const sr_option *o = table; o->name; o++) {
        char left[64];
        snprintf(left, sizeof left, "%s%s%s", o->name, o->value_name ? " " : "", o->value_name ? o->value_name : "");
        fprintf(out, "  %-24s %s\n", left, o->help);
    }
    fprintf(out, "  %-24s %s\n", "--help", "this text");
}

bool sr_options_parse(const sr_option *table, const char *usage, int argc, char **argv, int first,
                      const char **positional, int max_positional, int *positional_count, bool *help, sr_error *err)
{
    *positional_count = 0;
    *help = false;
    for (int i = first; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            *help = true;
        } else if (strncmp(argv[i], "--", 2) == 0) {
            if (!parse_one(table, argc, argv, &i, err))
                return false;
        } else if (argv[i][0] == '-' && argv[i][1] != '\0') {
            return sr_error_set(err, "unknown option '%s' (see --help)", argv[i]);
        } else if (*positional_count < max_positional) {
            positional[(*positional_count)++] = argv[i];
        } else {
            return sr_error_set(err, "unexpected argument '%s'", argv[i]);
        }
    }
    if (*help)
        print_help(stdout, usage, table);
    return true;
}
