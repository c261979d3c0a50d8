/* vertex_colours.h — a file's vertex colours in the light the draw takes
 * them in (docs/conventions.md, "Colour space"): under SR_COLOR_SRGB the
 * draw takes sr_mesh.colors as linear, as glTF's COLOR_0 is, where every
 * other format stores display values (a PLY scan's bytes, MeshLab's OBJ
 * `v x y z r g b`), which Blender 4's PLY importer and three.js's PLY and
 * OBJ loaders decode from sRGB. The command line and Python decode them so,
 * with this one rule. */
#ifndef SOFTRAST_IO_VERTEX_COLOURS_H
#define SOFTRAST_IO_VERTEX_COLOURS_H

#include <stdbool.h>

#include "softrast/softrast.h"

/* Whether the mesh file at path stores display (sRGB-encoded) vertex
 * colours: every format but glTF (.gltf, .glb). */
bool sr_vertex_colours_are_display(const char *path);

/* count colours, each component an sRGB display value 0..1, into linear
 * light (IEC 61966-2-1, in double, rounded to float once); in and out may
 * be the same array. */
void sr_vertex_colours_to_linear(const vec3 *in, vec3 *out, uint32_t count);

#endif
