/* src/io/assimp_instances.h — private to src/io: the drawn placements of an
 * Assimp scene's meshes. A node that names a mesh places one instance of
 * it, with the node's transform composed with its parents'; a mesh two
 * nodes name is two instances, each its own part (an instance mask, not a
 * mesh mask). A mesh no node names is not drawn. */
#ifndef SOFTRAST_IO_ASSIMP_INSTANCES_H
#define SOFTRAST_IO_ASSIMP_INSTANCES_H

#include <assimp/scene.h>
#include <stdbool.h>
#include <stdint.h>

typedef struct sr_assimp_instance {
    unsigned mesh;           /* an index of the scene's meshes */
    double to_world[3][4];   /* row-major: world = to_world · (x, y, z, 1), in the file's frame */
    bool mirrored;           /* the transform's determinant is negative */
    bool turned;             /* every instance of the mesh is mirrored: sr_assimp_unmirror reversed its faces */
} sr_assimp_instance;

typedef struct sr_assimp_instances {
    sr_assimp_instance *at;
    uint32_t count;
} sr_assimp_instances;

/* The scene's instances in node order (depth first, a node's own meshes
 * before its children's); a scene without faces (a point cloud) has one
 * instance of each mesh, unplaced. False when out of memory or past
 * max_instances. */
bool sr_assimp_instances_find(const struct aiScene *sc, uint32_t max_instances, sr_assimp_instances *out);
void sr_assimp_instances_free(sr_assimp_instances *list);

/* A position placed in the world (in double, rounded once by the caller). */
void sr_assimp_instance_place(const sr_assimp_instance *in, const struct aiVector3D *p, double world[3]);

/* A normal placed by the inverse transpose of the transform, unit length;
 * zero stays zero. */
void sr_assimp_instance_turn(const sr_assimp_instance *in, const struct aiVector3D *n, double world[3]);

#endif
