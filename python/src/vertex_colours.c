/* Which files store sRGB vertex colours, and their decoding to linear
 * light, src/io/vertex_colours.c, compiled into the extension as
 * mesh_origin.c is: the command line's rule, kept in one place. */
#include "io/vertex_colours.c"
