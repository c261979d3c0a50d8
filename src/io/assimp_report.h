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

/* What a static scene leaves out, counted before post-processing:
 * animations, and meshes skinned or with morph targets. */
typedef struct sr_assimp_pose {
    uint32_t animations, skinned, morphed;
} sr_assimp_pose;

/* Before the scene is post-processed: poses it statically and counts what that
 * leaves out. Morph targets are applied at their default weights (glTF's
 * mesh.weights; Assimp stores each target whole, so a vertex moves by
 * weight x (target - base)), to positions and normals; skinned meshes are
 * posed by their skeletons as the node tree holds them, no animation
 * applied (no time of an animation is more the file's than another): a
 * vertex at the weighted mean of its bones' global transforms times their
 * offset matrices, glTF's skinning formula, which ignores the transform of
 * the skinned mesh's own node, as Assimp's viewer and glTF viewers draw
 * it. The vertices stored are not a pose: BCN_Epileptic.X's head would
 * float above its body, lying along the file's z. */
sr_assimp_pose sr_assimp_static_pose(const struct aiScene *sc);

/* The texture a material draws: its base-colour (glTF), else diffuse
 * texture; a material that shows by emission alone (a black base colour,
 * no such texture: glTF's labels) draws its emissive texture, and
 * *emissive is set. False when it draws none. */
bool sr_assimp_material_texture(const struct aiMaterial *mat, struct aiString *name, bool *emissive);

/* The scene's report, a part for each instance in list, with pose
 * (counted before post-processing) and an AMF file's unit in metres,
 * which Assimp does not report (amf_read.h; 0 when none is known); false
 * when out of memory. */
bool sr_assimp_report(const struct aiScene *sc, const sr_assimp_instances *list, const char *path,
                      sr_assimp_pose pose, double amf_metres, sr_load_report *report);

#endif
