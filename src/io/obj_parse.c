#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "obj_parse.h"
#include "core/error.h"
#include "core/input_file.h"

/* Room for a few maximal lines per read, so compacting the unread tail to
 * the front costs little next to reading. */
#define READER_CAP (4 * SR_OBJ_MAX_LINE)

static const char utf8_bom[] = "\xEF\xBB\xBF";

bool sr_line_reader_open(sr_line_reader *r, const char *path)
{
    *r = (sr_line_reader){ .path = path };
    r->file = sr_input_open(path, &r->why);
    if (!r->file)
        return false;
    r->buf = malloc(READER_CAP + 1); /* +1: a final line without "\n" still gets its NUL */
    if (!r->buf) {
        fclose(r->file);
        *r = (sr_line_reader){ .why = strerror(ENOMEM) };
        return false;
    }
    return true;
}

void sr_line_reader_close(sr_line_reader *r)
{
    if (r->file)
        fclose(r->file);
    free(r->buf);
    *r = (sr_line_reader){ 0 };
}

bool sr_line_fail(const sr_line_reader *r, sr_error *err, const char *fmt, ...)
{
    char what[SR_ERROR_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    return sr_error_set(err, "%s:%zu: %s", r->path, r->line, what);
}

static bool line_too_long(sr_line_reader *r, size_t line, sr_error *err)
{
    return sr_error_set(err, "%s:%zu: line longer than %d bytes", r->path, line,
                        SR_OBJ_MAX_LINE);
}

/* Moves the unread tail to the front and appends what the file has next. */
static bool refill(sr_line_reader *r, sr_error *err)
{
    memmove(r->buf, r->buf + r->start, r->end - r->start);
    r->end -= r->start;
    r->start = 0;
    size_t n = fread(r->buf + r->end, 1, READER_CAP - r->end, r->file);
    if (n == 0) {
        if (ferror(r->file))
            return sr_error_set(err, "%s: read error: %s", r->path, strerror(errno));
        r->eof = true;
    }
    r->end += n;
    return true;
}

/* The first line end in the unread bytes: "\n", "\r\n" or a lone "\r" (old
 * Mac files). NULL when there is none yet, or when a "\r" ends what was read
 * so far: the "\n" that may follow is still in the file. */
static char *line_end(const sr_line_reader *r)
{
    char *s = r->buf + r->start;
    size_t n = r->end - r->start;
    char *nl = memchr(s, '\n', n);
    char *cr = memchr(s, '\r', nl ? (size_t)(nl - s) : n);
    if (!cr)
        return nl;
    return cr + 1 == r->buf + r->end && !r->eof ? NULL : cr;
}

bool sr_line_reader_next(sr_line_reader *r, char **line, sr_error *err)
{
    char *nl;
    *line = NULL;
    while (!(nl = line_end(r)) && !r->eof) {
        /* Give up before buffering more than a line may hold ("+1": a "\r"). */
        if (r->end - r->start > SR_OBJ_MAX_LINE + 1)
            return line_too_long(r, r->line + 1, err);
        if (!refill(r, err))
            return false;
    }
    if (!nl && r->start == r->end)
        return true;
    char *s = r->buf + r->start;
    size_t len = nl ? (size_t)(nl - s) : r->end - r->start;
    bool crlf = nl && *nl == '\r' && nl + 1 < r->buf + r->end && nl[1] == '\n';
    r->start += len + (nl != NULL) + crlf;
    r->line++;
    if (len > 0 && s[len - 1] == '\r')
        len--;
    if (len > SR_OBJ_MAX_LINE)
        return line_too_long(r, r->line, err);
    /* A NUL would silently cut the line short for every string function. */
    if (memchr(s, '\0', len))
        return sr_line_fail(r, err, "NUL byte in line (not a text file?)");
    s[len] = '\0';
    if (r->line == 1 && strncmp(s, utf8_bom, 3) == 0)
        s += 3;
    *line = s;
    return true;
}

static bool is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

char *sr_obj_next_token(char **cursor)
{
    char *s = *cursor;
    while (is_blank(*s))
        s++;
    if (*s == '\0' || *s == '#') {
        *cursor = s;
        return NULL;
    }
    char *tok = s;
    while (*s && !is_blank(*s) && *s != '#')
        s++;
    if (*s == '#')
        *s = '\0'; /* a comment right after the token: the next call ends the line */
    else if (*s)
        *s++ = '\0';
    *cursor = s;
    return tok;
}

char *sr_obj_rest(char *cursor)
{
    while (is_blank(*cursor))
        cursor++;
    size_t len = strlen(cursor);
    while (len > 0 && is_blank(cursor[len - 1]))
        len--;
    cursor[len] = '\0';
    return cursor;
}

bool sr_obj_parse_number(const sr_line_reader *r, const char *tok, double *out, sr_error *err)
{
    char *end;
    double d = strtod(tok, &end);
    if (end == tok || *end != '\0')
        return sr_line_fail(r, err, "'%.40s' is not a number", tok);
    if (!isfinite(d))
        return sr_line_fail(r, err, "number '%.40s' is not finite", tok);
    /* Every number ends up in a float (a position relative to its mesh's
     * origin, a uv, a normal, a color): keep them all within float range. */
    if (fabs(d) > FLT_MAX)
        return sr_line_fail(r, err, "number '%.40s' is out of float range", tok);
    *out = d;
    return true;
}

int sr_obj_parse_numbers(const sr_line_reader *r, char *cursor, double *out, int max, sr_error *err)
{
    int n = 0;
    for (char *tok; (tok = sr_obj_next_token(&cursor)); n++) {
        if (n == max) {
            sr_line_fail(r, err, "too many numbers (at most %d)", max);
            return -1;
        }
        if (!sr_obj_parse_number(r, tok, &out[n], err))
            return -1;
    }
    return n;
}

bool sr_obj_parse_long(const char **s, long *out)
{
    const char *p = *s;
    if (*p == '+' || *p == '-')
        p++;
    /* strtol alone would also take leading blanks and an empty string as 0. */
    if (*p < '0' || *p > '9')
        return false;
    char *end;
    *out = strtol(*s, &end, 10);
    *s = end;
    return true;
}

char *sr_obj_path_beside(const char *base_file, const char *name)
{
    const char *slash = strrchr(base_file, '/');
    size_t dir_len = (name[0] == '/' || !slash) ? 0 : (size_t)(slash - base_file) + 1;
    size_t name_len = strlen(name);
    char *path = malloc(dir_len + name_len + 1);
    if (!path)
        return NULL;
    memcpy(path, base_file, dir_len);
    memcpy(path + dir_len, name, name_len + 1);
    for (char *c = path + dir_len; (c = strchr(c, '\\'));)
        *c = '/'; /* files written on Windows: ".\tex\wood.png" */
    return path;
}
