/* src/io/obj_parse.h — private to src/io: the text layer under the OBJ and
 * MTL readers. A bounded line reader (no line may exceed SR_OBJ_MAX_LINE, so
 * a hostile file cannot make us buffer without end), a whitespace tokenizer
 * that treats `#` as the start of a comment, strict number parsers and the
 * folder-relative path rule both formats share (their growable arrays are
 * core/array.h's).
 */
#ifndef SOFTRAST_IO_OBJ_PARSE_H
#define SOFTRAST_IO_OBJ_PARSE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "core/array.h"
#include "core/error.h"

#define SR_OBJ_MAX_LINE (64 * 1024) /* bytes, line end excluded */

typedef struct sr_line_reader {
    FILE *file;
    const char *path; /* borrowed; used in "PATH:LINE:" messages */
    const char *why;  /* after a failed open: the reason in words */
    size_t line;      /* number of the line last returned, from 1 */
    char *buf;
    size_t start, end;
    bool eof;
} sr_line_reader;

/* False (r->why says why, nothing to close) if the file cannot be opened or
 * is not a regular file (sr_input_open); the caller words the message, since
 * "cannot open" means different things for an OBJ and for the material
 * library it names. */
bool sr_line_reader_open(sr_line_reader *r, const char *path);
/* The next line, NUL-terminated, without its "\n", "\r\n" or lone "\r"; *line = NULL at
 * the end of the file. False on a read error, an over-long line or a NUL
 * byte. */
bool sr_line_reader_next(sr_line_reader *r, char **line, sr_error *err);
void sr_line_reader_close(sr_line_reader *r);
/* Writes "PATH:LINE: " + the formatted text into err; returns false. */
bool sr_line_fail(const sr_line_reader *r, sr_error *err, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Next whitespace-separated token, NUL-terminated in place; NULL at the end
 * of the line or at a '#' (a trailing comment), which also ends a token it
 * follows with no blank between ("0#c" is the token "0"). */
char *sr_obj_next_token(char **cursor);
/* The rest of the line without surrounding whitespace (file and material
 * names may contain spaces); "" if nothing is left. */
char *sr_obj_rest(char *cursor);

/* A whole token as a finite number within float range (kept in double, so
 * positions far from the origin keep their digits), else an error naming
 * the token. */
bool sr_obj_parse_number(const sr_line_reader *r, const char *tok, double *out, sr_error *err);
/* The numbers left on the line into out[0 … max-1]: how many, or -1 (err
 * set) on a bad number or more than max of them. */
int sr_obj_parse_numbers(const sr_line_reader *r, char *cursor, double *out, int max, sr_error *err);
/* An optionally signed decimal integer at *s, stopping at '/' or the end;
 * advances *s. False if there are no digits. Overflow saturates to
 * LONG_MIN/LONG_MAX, which every later range check rejects. */
bool sr_obj_parse_long(const char **s, long *out);

/* `name` resolved against the folder of `base_file` ("a/b.obj" + "c.mtl" ->
 * "a/c.mtl"); absolute names stay as they are. Backslashes in name become
 * '/' (files written on Windows). Malloc'd, or NULL. */
char *sr_obj_path_beside(const char *base_file, const char *name);

#endif
