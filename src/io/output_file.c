/* Safe output files (output_file.h). */
#define _XOPEN_SOURCE 700 /* realpath */
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/input_file.h"
#include "output_file.h"

#define TMP_NAME_TRIES 100

static void output_free(sr_output *o)
{
    free(o->target);
    free(o->tmp);
    *o = (sr_output){ 0 };
}

/* An exclusive new file "TARGET.tmp-PID-N" (O_EXCL: never an existing one). */
static int create_tmp(sr_output *o)
{
    size_t size = strlen(o->target) + 64;
    o->tmp = malloc(size);
    if (!o->tmp) {
        errno = ENOMEM;
        return -1;
    }
    int fd = -1;
    for (int n = 0; fd < 0 && n < TMP_NAME_TRIES; n++) {
        snprintf(o->tmp, size, "%s.tmp-%ld-%d", o->target, (long)getpid(), n);
        fd = open(o->tmp, O_WRONLY | O_CREAT | O_EXCL, 0666);
        if (fd < 0 && errno != EEXIST)
            break;
    }
    return fd;
}

bool sr_output_open(sr_output *o, const char *path, sr_error *err)
{
    *o = (sr_output){ 0 };
    if (strcmp(path, "-") == 0) {
        if (isatty(STDOUT_FILENO))
            return sr_error_set(err, "-: stdout is a terminal; redirect it to a file or name one");
        o->f = stdout;
        return true;
    }
    struct stat st;
    bool exists = stat(path, &st) == 0;
    if (exists && !S_ISREG(st.st_mode))
        return sr_error_set(err, "%s: cannot write: %s; softrast writes only regular files", path,
                            sr_not_regular(st.st_mode));
    o->target = exists ? realpath(path, NULL) : strdup(path);
    int fd = o->target ? create_tmp(o) : -1;
    if (fd >= 0 && exists)
        fchmod(fd, st.st_mode & 07777);
    o->f = fd >= 0 ? fdopen(fd, "wb") : NULL;
    if (o->f)
        return true;
    int code = errno;
    if (fd >= 0) {
        close(fd);
        remove(o->tmp);
    }
    output_free(o);
    return sr_error_set(err, "%s: cannot write: %s", path, strerror(code));
}

bool sr_output_close(sr_output *o, const char *path, bool ok, sr_error *err)
{
    int code = ok ? 0 : errno;
    bool file = o->tmp != NULL;
    if (fflush(o->f) != 0 && ok) {
        ok = false;
        code = errno;
    }
    if (file && fclose(o->f) != 0 && ok) {
        ok = false;
        code = errno;
    }
    if (file && ok && rename(o->tmp, o->target) != 0) {
        ok = false;
        code = errno;
    }
    if (file && !ok)
        remove(o->tmp);
    output_free(o);
    return ok || sr_error_set(err, "%s: cannot write: %s", path, strerror(code ? code : EIO));
}


bool sr_output_make_dir(const char *path, sr_error *err)
{
    if (mkdir(path, 0777) == 0 || errno == EEXIST) {
        struct stat st;
        if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
            return true;
        return sr_error_set(err, "%s: exists and is not a folder", path);
    }
    return sr_error_set(err, "%s: cannot make the folder: %s", path, strerror(errno));
}
