/* The loaders' rule for where a mesh's positions are measured from,
 * src/io/mesh_origin.c, compiled into the extension: the library's archives
 * do not export it, and a mesh from arrays follows the rule a mesh read
 * from a file does (mesh.c). Included rather than named in setup.py, which
 * takes sources inside python/ only. */
#include "io/mesh_origin.c"
