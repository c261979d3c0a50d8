/* src/io/mesh_facets.h — private to src/io: a mesh shaded by its facets,
 * for formats whose triangles are a solid's faces and carry no normals
 * (3MF, AMF: slicers shade each triangle by its own normal). Smooth
 * normals made over shared corners would turn a box's flat sides into
 * gradients, and no smoothing angle helps while the corners are shared. */
#ifndef SOFTRAST_IO_MESH_FACETS_H
#define SOFTRAST_IO_MESH_FACETS_H

#include "softrast/softrast.h"

/* Gives each triangle of a triangle-list mesh three vertices of its own
 * (a repeated index stays repeated), whose normal is the triangle's
 * outward one (clockwise front faces in softrast's left-handed world, as
 * sr_mesh_compute_normals makes them); uvs and colours are copied. The
 * triangles, their order and their ids stay. False, the mesh unchanged,
 * when out of memory or past SR_MAX_MESH_VERTICES. */
bool sr_mesh_facet(sr_mesh *mesh, sr_error *err);

#endif
