/* The texture files a mesh's materials name, each loaded once,
 * src/io/material_textures.c, compiled into the extension as mesh_origin.c
 * is: the command line's rule, kept in one place. */
#include "io/material_textures.c"
