/* src/io/amf_volumes.h — private to src/io: an AMF file's objects of
 * several volumes, rewritten so that Assimp 5.2 reads every volume.
 *
 * An AMF <object> holds one <mesh>: a list of vertices and one or more
 * <volume>s of triangles over them, each its own material or colour.
 * Assimp 5.2 reads the first volume of a mesh and drops the others
 * (test_with_mat.amf's second half, test7–9's lower spikes). Assimp does
 * read a <constellation>, and an instance may name a constellation as well
 * as an object: so each such object, id X, becomes one object per volume
 * (ids "X#1", "X#2", …: the object's other children, then a mesh of the
 * vertices that volume uses, renumbered, and the volume) and a
 * constellation X placing each where it is. Whatever named X names the
 * constellation, and the node Assimp makes for it is named X as the
 * object's was (amf_constellations.h matches nodes by name). A volume of
 * no triangles, which Assimp makes nothing of, is left out, and so are
 * the mesh's <edge>s (curved triangles, which Assimp does not read).
 */
#ifndef SOFTRAST_IO_AMF_VOLUMES_H
#define SOFTRAST_IO_AMF_VOLUMES_H

#include <stdbool.h>
#include <stddef.h>

#include "amf_read.h"

/* The file at path, which sr_amf_read read as file (with splits to make),
 * rewritten into *text (malloc'd, *size bytes, no terminator). False, with
 * one line in err, when it cannot be read again, an id holds '#', a
 * triangle names a vertex its mesh lacks, or the rewrite would pass
 * 8 times the file's size and 16 MiB (or 4 GiB, which Assimp's reading
 * from memory cannot pass). */
bool sr_amf_split_volumes(const char *path, const sr_amf_file *file, char **text, size_t *size, sr_error *err);

#endif
