/* shapes.h — meshes made in memory: the benchmark's scenes and the
 * tests' closed surfaces, at any size.
 *
 * Every shape but the cloud is an indexed TriangleList with normals and uvs, closed where
 * the shape is, its outward faces front faces (clockwise on screen seen from
 * outside, softrast's left-handed convention).
 */
#ifndef SOFTRAST_SCENE_SHAPES_H
#define SOFTRAST_SCENE_SHAPES_H

#include <stdbool.h>
#include <stdint.h>

#include "softrast/softrast.h"

/* A torus around +y: `segments` around the axis × `sides` around the tube,
 * 2·segments·sides triangles. */
bool sr_shape_torus(sr_mesh *mesh, float major, float minor, uint32_t segments, uint32_t sides, sr_error *err);

/* The segments × sides of a torus with about `triangles` triangles (sides =
 * segments / 2). */
void sr_shape_torus_grid(uint64_t triangles, uint32_t *segments, uint32_t *sides);

/* `count` axis-aligned squares of side `size` facing -z (toward a camera at
 * -z), centred on the z axis at z = first_z, first_z + step, ... */
bool sr_shape_quads(sr_mesh *mesh, uint32_t count, float size, float first_z, float step, sr_error *err);

/* `count` points spread over the surface of a torus around +y (radius
 * major, tube minor), a point list with a colour per point that follows its
 * place around the axis and the tube: a scanned surface's point cloud, the
 * same for every call (a fixed pseudo-random sequence). */
bool sr_shape_torus_cloud(sr_mesh *mesh, float major, float minor, uint32_t count, sr_error *err);

#endif
