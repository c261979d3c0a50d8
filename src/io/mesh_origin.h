/* mesh_origin.h — where a loader measures a mesh from: a mesh far from the
 * world origin keeps its float precision relative to its own centre
 * (sr_mesh.origin, docs/precision.md). */
#ifndef SOFTRAST_IO_MESH_ORIGIN_H
#define SOFTRAST_IO_MESH_ORIGIN_H

#include "softrast/softrast.h"

/* A loader stores positions relative to the centre of their bounds when the
 * centre is more than this many times the bounds' largest side from the
 * world origin (largest coordinate, ∞-norm): there absolute float positions
 * would lose over 4 of their 24 bits to the offset. Nearer meshes keep their
 * positions as written. */
#define SR_MESH_RECENTRE_RATIO 16.0

/* The origin a loader gives positions with bounds [lo, hi] (in double):
 * their centre if it lies over SR_MESH_RECENTRE_RATIO times the largest
 * side from the world origin, else zero. */
void sr_mesh_origin_for_bounds(const double lo[3], const double hi[3], double origin[3]);

#endif
