/* src/io/assimp_report.h — private to src/io: what an Assimp scene says of
 * itself (importer, axes, units, parts, textures, what is left out), and
 * its mirrored meshes turned outward. Run in the import's child process. */
#ifndef SOFTRAST_IO_ASSIMP_REPORT_H
#define SOFTRAST_IO_ASSIMP_REPORT_H

#include <assimp/scene.h>
#include <stdint.h>

#include "assimp_instances.h"
#include "load_report.h"

/* Before the scene is post-processed: reverses the faces of every mesh
 * that mirroring node transforms alone place (their global determinant
 * negative), so its outward faces stay outward and its made normals point
 * out. A mesh placed both mirrored and not is left as it is: assimp.c
 * reverses its mirrored instances. Returns the meshes reversed. */
uint32_t sr_assimp_unmirror(const struct aiScene *sc);

/* The scene's report, a part for each instance in list; false when out of
 * memory. */
bool sr_assimp_report(const struct aiScene *sc, const sr_assimp_instances *list, const char *path,
                      sr_load_report *report);

#endif
