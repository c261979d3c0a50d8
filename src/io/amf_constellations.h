/* src/io/amf_constellations.h — private to src/io: an AMF file's
 * constellations placed as the format means them.
 *
 * A <constellation> places <instance>s of objects and of other
 * constellations, each turned by <rx>, <ry>, <rz> (degrees, about the
 * file's axes: x first, then y, then z) and then moved by <deltax>,
 * <deltay>, <deltaz>. Assimp 5.2's AMF reader stores the three angles in
 * the displacement, over the deltas, and turns nothing, so test9.amf's
 * instances land 45 units away instead of 5. Assimp does build the node
 * tree right: a node named by the constellation's id with one child node
 * per instance, in the file's order, whose transform is the instance's.
 * This sets those transforms from the constellations the file holds
 * (amf_read.h).
 */
#ifndef SOFTRAST_IO_AMF_CONSTELLATIONS_H
#define SOFTRAST_IO_AMF_CONSTELLATIONS_H

#include <assimp/scene.h>
#include <stdint.h>

#include "amf_read.h"

/* Before the scene is post-processed, for a file Assimp read as AMF: sets
 * the transform of each instance node of every constellation of file (a
 * node named by its id with as many children as it has instances), whose
 * constellations it sorts by id. Returns the instance nodes set; 0, the
 * scene unchanged, when the file holds no constellation with an id. */
uint32_t sr_amf_place_instances(const struct aiScene *sc, sr_amf_file *file);

#endif
