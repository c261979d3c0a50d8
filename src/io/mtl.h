/* src/io/mtl.h — private to src/io: the part of a Wavefront material library
 * (.mtl) that softrast uses, each material's name, diffuse colour (`Kd`)
 * and diffuse texture (`map_Kd`). Everything else in the file (Ka, Ns,
 * illum, d, other maps) is read past.
 */
#ifndef SOFTRAST_IO_MTL_H
#define SOFTRAST_IO_MTL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "obj_parse.h"

typedef struct sr_mtl_material {
    char *name;
    char *map_kd;         /* the name resolved against the .mtl's folder, or once
                             searched (sr_mtl_find_texture) the file found; NULL if none */
    char *map_kd_written; /* the name as the .mtl writes it */
    char *library;        /* the .mtl's path, where the search starts */
    bool map_kd_searched; /* sr_mtl_find_texture looked for it */
    bool map_kd_found;    /* map_kd is a file that exists */
    float kd[3];          /* the diffuse colour, when has_kd */
    bool has_kd;
    int64_t mesh_material; /* the loaded mesh's material made of it, or -1 before a face uses it */
} sr_mtl_material;

/* The materials of every library an OBJ names, and which files those were. */
typedef struct sr_mtl_libs {
    sr_array materials; /* sr_mtl_material */
    sr_array files;     /* sr_mtl_file_id of each library read */
} sr_mtl_libs;

typedef struct sr_mtl_file_id {
    unsigned long long dev, ino;
} sr_mtl_file_id;

/* Reads the libraries that an `mtllib` statement names (`names`: the rest of
 * its line, relative to the OBJ's folder; `obj` is at that line) and appends
 * their materials to libs. A library already read (the same file, by any
 * name) is not read again: its materials are there, and a small OBJ
 * repeating `mtllib big.mtl` would otherwise allocate the library's size
 * once per line. Errors are
 * "OBJ:LINE: cannot open material library 'x.mtl': …" or "MTL:LINE: what".
 * `names` is tokenized in place. */
bool sr_mtl_load(sr_mtl_libs *libs, const sr_line_reader *obj, char *names, sr_error *err);

/* Index of the first material called `name`, or -1. */
ptrdiff_t sr_mtl_find(const sr_mtl_libs *libs, const char *name);

/* Looks for m's texture by texture_find.h's rules, once: only the
 * materials a mesh uses are searched for, so a library of thousands
 * whose textures are missing costs no folder scans. */
void sr_mtl_find_texture(sr_mtl_material *m);

void sr_mtl_free(sr_mtl_libs *libs);

#endif
