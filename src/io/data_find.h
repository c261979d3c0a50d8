/* data_find.h — where the program's data (the default scene, assets/room.*) is
 * found, so that view and bench run from any directory and from an
 * installed copy. */
#ifndef SOFTRAST_IO_DATA_FIND_H
#define SOFTRAST_IO_DATA_FIND_H

#include <stdbool.h>
#include <stddef.h>

#include "softrast/softrast.h"

/* Finds NAME (a path relative to a data directory, e.g. "assets/room.obj")
 * and writes its full path into out. The data directories, in this order:
 * beside the executable (its directory's parent and grandparent, which are
 * the source tree when it runs from build/ or build/san/, then
 * ../share/softrast for an installed copy), the prefix the program was built
 * with (PREFIX/share/softrast), then $SOFTRAST_DATA. Fails with one line
 * naming every place it looked. */
bool sr_data_find(const char *name, char *out, size_t cap, sr_error *err);

#endif
