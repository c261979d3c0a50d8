/* input_file.h — opening what softrast reads, and naming what it will not.
 *
 * Meshes, material libraries, textures and flight scripts are read only from
 * regular files: a FIFO would block the read forever, a device could be read
 * without end, a directory is no file at all. Outputs (src/io/image.c) are
 * written only over a regular file or a new path, for the same reasons.
 */
#ifndef SOFTRAST_CORE_INPUT_FILE_H
#define SOFTRAST_CORE_INPUT_FILE_H

#include <stdio.h>
#include <sys/types.h>

/* "not a regular file (a FIFO)", "… (a directory)", …: the reason in words
 * for a stat mode that is not a regular file's. */
const char *sr_not_regular(mode_t mode);

/* path opened for reading ("rb") if it is a regular file, else NULL with
 * *why the reason in words: strerror's, or sr_not_regular's (errno EINVAL).
 * The type is checked before opening (so a device is never opened) and
 * again on the descriptor, which is opened non-blocking: a FIFO put in
 * place between the two cannot block. */
FILE *sr_input_open(const char *path, const char **why);

#endif
