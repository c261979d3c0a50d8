/* doc_file.h — the files the studies write (Markdown, SVG): opened and
 * closed with one error line that names the file. */
#ifndef SOFTRAST_STUDIES_DOC_FILE_H
#define SOFTRAST_STUDIES_DOC_FILE_H

#include <stdbool.h>
#include <stdio.h>

#include "softrast_private.h"

/* NULL, with err set, when path cannot be opened for writing. */
FILE *sr_doc_open(const char *path, sr_error *err);

/* Closes f; false, with err set, when a write or the close failed. */
bool sr_doc_close(FILE *f, const char *path, sr_error *err);

#endif
