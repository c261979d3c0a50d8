/* The studies' output files (doc_file.h). */
#include <errno.h>
#include <string.h>

#include "doc_file.h"

FILE *sr_doc_open(const char *path, sr_error *err)
{
    FILE *f = fopen(path, "w");
    if (!f)
        sr_error_set(err, "%s: cannot write: %s", path, strerror(errno));
    return f;
}

bool sr_doc_close(FILE *f, const char *path, sr_error *err)
{
    bool ok = !ferror(f);
    ok = fclose(f) == 0 && ok;
    return ok ? true : sr_error_set(err, "%s: cannot write: %s", path, strerror(errno ? errno : EIO));
}
