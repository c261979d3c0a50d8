/* src/io/mtl.h — private to src/io: the part of a Wavefront material library
 * (.mtl) that softrast uses, each material's name and diffuse texture
 * (`map_Kd`). Everything else in the file (Ka, Kd, Ns, illum, other maps) is
 * read past.
 */
#ifndef SOFTRAST_IO_MTL_H
#define SOFTRAST_IO_MTL_H

#include <stdbool.h>
#include <stddef.h>

#include "obj_parse.h"

typedef struct sr_material {
    char *name;
    char *map_kd; /* resolved against the .mtl's folder; NULL if none */
} sr_material;

/* Reads the libraries that an `mtllib` statement names (`names`: the rest of
 * its line, relative to the OBJ's folder; `obj` is at that line) and appends
 * their materials to `lib`, an sr_array of sr_material. Errors are
 * "OBJ:LINE: cannot open material library 'x.mtl': …" or "MTL:LINE: what".
 * `names` is tokenized in place. */
bool sr_mtl_load(sr_array *lib, const sr_line_reader *obj, char *names, sr_error *err);

/* Index of the first material called `name`, or -1. */
ptrdiff_t sr_mtl_find(const sr_array *lib, const char *name);

void sr_mtl_free(sr_array *lib);

#endif
