/* The studies' output files (doc_file.h). */
#include <errno.h>

#include "doc_file.h"

bool sr_doc_open(sr_doc *d, const char *path, sr_error *err)
{
    *d = (sr_doc){ .path = path };
    if (!sr_output_open(&d->out, path, err))
        return false;
    d->f = d->out.f;
    errno = 0;
    return true;
}

bool sr_doc_close(sr_doc *d, sr_error *err)
{
    bool written = !ferror(d->f);
    if (!written && !errno)
        errno = EIO;
    d->f = NULL;
    return sr_output_close(&d->out, d->path, written, err);
}
