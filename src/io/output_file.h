/* output_file.h — writing an output file safely: the image writers' and the
 * studies' reports. */
#ifndef SOFTRAST_IO_OUTPUT_FILE_H
#define SOFTRAST_IO_OUTPUT_FILE_H

#include <stdbool.h>
#include <stdio.h>

#include "core/error.h"

/* An output being written. softrast never writes into the path itself: the
 * bytes go to a temporary file beside the target (same folder, so the rename
 * stays on one file system), renamed over the target once complete. A failed
 * write removes only that temporary file, which softrast created; whatever
 * was at the path is left as it was. */
typedef struct sr_output {
    FILE *f;
    char *target; /* the path, or the file a symbolic link at it points to */
    char *tmp;
} sr_output;

/* Only a regular file (an existing one keeps its permissions) or a path that
 * does not exist yet is an output: never a device, FIFO or directory. "-"
 * is stdout, unless that is a terminal. */
bool sr_output_open(sr_output *o, const char *path, sr_error *err);

/* Flushes and closes the temporary file, reporting the first failure (errno
 * from a failed write when ok is false, or from flush/close: buffered data
 * can still hit a full disk there), then renames it into place or removes
 * it. stdout is flushed only. */
bool sr_output_close(sr_output *o, const char *path, bool ok, sr_error *err);

/* A folder for outputs, made where missing (its parent must exist); an
 * existing path that is not a folder is an error. */
bool sr_output_make_dir(const char *path, sr_error *err);

#endif
