#include <errno.h>
#include <fcntl.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "input_file.h"

const char *sr_not_regular(mode_t mode)
{
    if (S_ISDIR(mode))
        return "not a regular file (a directory)";
    if (S_ISFIFO(mode))
        return "not a regular file (a FIFO)";
    if (S_ISCHR(mode))
        return "not a regular file (a character device)";
    if (S_ISBLK(mode))
        return "not a regular file (a block device)";
    if (S_ISSOCK(mode))
        return "not a regular file (a socket)";
    return "not a regular file";
}

/* rc from stat or fstat on st: true for a regular file, else false with *why
 * (and errno) set. */
static bool stat_regular(int rc, const struct stat *st, const char **why)
{
    if (rc != 0) {
        *why = strerror(errno);
        return false;
    }
    if (S_ISREG(st->st_mode))
        return true;
    *why = sr_not_regular(st->st_mode);
    errno = EINVAL;
    return false;
}

FILE *sr_input_open(const char *path, const char **why)
{
    struct stat st;
    if (!stat_regular(stat(path, &st), &st, why))
        return NULL;
    int fd = open(path, O_RDONLY | O_NONBLOCK);
    if (fd < 0) {
        *why = strerror(errno);
        return NULL;
    }
    FILE *f = NULL;
    if (stat_regular(fstat(fd, &st), &st, why)) {
        f = fcntl(fd, F_SETFL, 0) == 0 ? fdopen(fd, "rb") : NULL; /* blocking reads again */
        if (!f)
            *why = strerror(errno);
    }
    if (!f) {
        int saved = errno;
        close(fd);
        errno = saved;
    }
    return f;
}
