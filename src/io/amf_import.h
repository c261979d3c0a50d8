/* src/io/amf_import.h — private to src/io: an AMF file through Assimp 5.2,
 * with what Assimp reads wrong put right.
 *
 * The file is read first (amf_read.h); an object of several volumes makes
 * Assimp read a rewrite of it from memory (amf_volumes.h), any other file
 * is read as it is; then the constellations' instances are placed
 * (amf_constellations.h).
 */
#ifndef SOFTRAST_IO_AMF_IMPORT_H
#define SOFTRAST_IO_AMF_IMPORT_H

#include <assimp/scene.h>
#include <stdbool.h>

#include "softrast/softrast.h"

/* Assimp's scene of the AMF file at path (flags as aiImportFile's), not
 * post-processed, into *scene: NULL when Assimp could not read it
 * (aiGetErrorString says why); the file's unit into *metres_per_unit (0
 * when it states none known). False, with one line in err, when softrast
 * could not read it first (amf_read.h, amf_volumes.h). */
bool sr_amf_import(const char *path, unsigned flags, const struct aiScene **scene, double *metres_per_unit,
                   sr_error *err);

#endif
