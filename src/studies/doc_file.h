/* doc_file.h — the files the studies write (Markdown, SVG, the peer's
 * figures): written to a temporary file and renamed into place when whole
 * (io/output_file.h), so a failed study leaves the last good file, with one
 * error line that names the file. */
#ifndef SOFTRAST_STUDIES_DOC_FILE_H
#define SOFTRAST_STUDIES_DOC_FILE_H

#include <stdbool.h>
#include <stdio.h>

#include "io/output_file.h"
#include "softrast_private.h"

typedef struct sr_doc {
    FILE *f; /* write here */
    sr_output out;
    const char *path;
} sr_doc;

bool sr_doc_open(sr_doc *d, const char *path, sr_error *err);

/* Renames the file into place; false, with err set and the old file kept,
 * when a write, the flush or the close failed. */
bool sr_doc_close(sr_doc *d, sr_error *err);

#endif
