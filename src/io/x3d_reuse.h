/* src/io/x3d_reuse.h — private to src/io: an X3D file's reused nodes
 * written out whole, for Assimp 5.2.
 *
 * X3D names a node with DEF and draws it again wherever a USE names it
 * (<Transform USE='key'/>: the same node, under the USE's parent). Assimp
 * 5.2 places the first reuse under the wrong parent and drops the rest,
 * and a reused group's own reuses with it. So a file that reuses nodes is
 * handed to Assimp rewritten: each USE element replaced by the text of the
 * element its DEF names, whose own USEs are replaced in turn; the copies
 * keep their DEF names, which Assimp 5.2 reads again without complaint.
 *
 * A node cannot hold itself: a USE inside the element its name DEFines (or
 * inside a copy being written for it) is written as nothing, where Assimp
 * 5.2 crashes. A USE of a name no DEF gives is left for Assimp to refuse,
 * and a file that is not well-formed XML, or declares entities, is left
 * to Assimp whole.
 */
#ifndef SOFTRAST_IO_X3D_REUSE_H
#define SOFTRAST_IO_X3D_REUSE_H

#include <stdbool.h>
#include <stddef.h>

#include "softrast/softrast.h"

/* The X3D file at path with its reuses written out: into *text (malloc'd,
 * *size bytes), or *text NULL when no USE names a node it DEFines (or
 * expat cannot read it), and Assimp should read the file itself.
 * False, with one line in err, when the file cannot be read, or when the
 * rewrite would pass 16 times the file and 64 MiB (nested reuses grow
 * exponentially). */
bool sr_x3d_write_out_reuses(const char *path, char **text, size_t *size, sr_error *err);

#endif
