/* The drawn placements of an Assimp scene's meshes (assimp_instances.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assimp_instances.h"
#include "core/array.h"

/* A hostile hierarchy is walked no deeper than this. */
#define MAX_NODE_DEPTH 1024

typedef struct walk {
    const struct aiScene *sc;
    uint32_t max_instances;
    sr_array list; /* of sr_assimp_instance */
    bool failed;
} walk;

/* parent · local, both affine (row-major, the last row 0 0 0 1). */
static void compose(const double parent[3][4], const struct aiMatrix4x4 *local, double out[3][4])
{
    const double m[3][4] = { { local->a1, local->a2, local->a3, local->a4 },
                             { local->b1, local->b2, local->b3, local->b4 },
                             { local->c1, local->c2, local->c3, local->c4 } };
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            out[r][c] = parent[r][0] * m[0][c] + parent[r][1] * m[1][c] + parent[r][2] * m[2][c] +
                        (c == 3 ? parent[r][3] : 0.0);
}

static double determinant(const double m[3][4])
{
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

static void visit(walk *w, const struct aiNode *node, const double parent[3][4], unsigned depth)
{
    if (!node || depth > MAX_NODE_DEPTH || w->failed)
        return;
    double to_world[3][4];
    compose(parent, &node->mTransformation, to_world);
    for (unsigned i = 0; i < node->mNumMeshes; i++) {
        if (node->mMeshes[i] >= w->sc->mNumMeshes)
            continue;
        sr_assimp_instance *in = w->list.count < w->max_instances ? sr_array_push(&w->list, sizeof *in) : NULL;
        if (!in) {
            w->failed = true;
            return;
        }
        in->mesh = node->mMeshes[i];
        memcpy(in->to_world, to_world, sizeof to_world);
        in->mirrored = determinant(to_world) < 0.0;
    }
    for (unsigned i = 0; i < node->mNumChildren; i++)
        visit(w, node->mChildren[i], to_world, depth + 1);
}

static bool has_faces(const struct aiScene *sc)
{
    for (unsigned i = 0; i < sc->mNumMeshes; i++)
        if (sc->mMeshes[i]->mNumFaces > 0)
            return true;
    return false;
}

/* Marks the instances of the meshes that are placed mirrored alone. */
static bool mark_turned(const struct aiScene *sc, sr_assimp_instance *at, uint32_t count)
{
    bool *plain = calloc(sc->mNumMeshes ? sc->mNumMeshes : 1, sizeof *plain);
    if (!plain)
        return false;
    for (uint32_t i = 0; i < count; i++)
        plain[at[i].mesh] |= !at[i].mirrored;
    for (uint32_t i = 0; i < count; i++)
        at[i].turned = !plain[at[i].mesh];
    free(plain);
    return true;
}

bool sr_assimp_instances_find(const struct aiScene *sc, uint32_t max_instances, sr_assimp_instances *out)
{
    static const double identity[3][4] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 } };
    walk w = { .sc = sc, .max_instances = max_instances };
    if (has_faces(sc)) {
        visit(&w, sc->mRootNode, identity, 0);
    } else { /* a point cloud's meshes as they are, as its loader keeps them */
        for (unsigned i = 0; i < sc->mNumMeshes && !w.failed; i++) {
            sr_assimp_instance *in = w.list.count < max_instances ? sr_array_push(&w.list, sizeof *in) : NULL;
            w.failed = !in;
            if (in) {
                *in = (sr_assimp_instance){ .mesh = i };
                memcpy(in->to_world, identity, sizeof identity);
            }
        }
    }
    if (!w.failed)
        w.failed = !mark_turned(sc, w.list.data, (uint32_t)w.list.count);
    if (w.failed) {
        sr_array_free(&w.list);
        *out = (sr_assimp_instances){ 0 };
        return false;
    }
    *out = (sr_assimp_instances){ w.list.data, (uint32_t)w.list.count };
    return true;
}

void sr_assimp_instances_free(sr_assimp_instances *list)
{
    free(list->at);
    *list = (sr_assimp_instances){ 0 };
}

void sr_assimp_instance_place(const sr_assimp_instance *in, const struct aiVector3D *p, double world[3])
{
    for (int r = 0; r < 3; r++)
        world[r] = in->to_world[r][0] * p->x + in->to_world[r][1] * p->y + in->to_world[r][2] * p->z +
                   in->to_world[r][3];
}

void sr_assimp_instance_turn(const sr_assimp_instance *in, const struct aiVector3D *n, double world[3])
{
    /* The inverse transpose is the cofactor matrix over the determinant:
     * only the determinant's sign survives normalizing. */
    const double(*m)[4] = in->to_world;
    const double cof[3][3] = {
        { m[1][1] * m[2][2] - m[1][2] * m[2][1], m[1][2] * m[2][0] - m[1][0] * m[2][2],
          m[1][0] * m[2][1] - m[1][1] * m[2][0] },
        { m[0][2] * m[2][1] - m[0][1] * m[2][2], m[0][0] * m[2][2] - m[0][2] * m[2][0],
          m[0][1] * m[2][0] - m[0][0] * m[2][1] },
        { m[0][1] * m[1][2] - m[0][2] * m[1][1], m[0][2] * m[1][0] - m[0][0] * m[1][2],
          m[0][0] * m[1][1] - m[0][1] * m[1][0] },
    };
    const double sign = in->mirrored ? -1.0 : 1.0;
    double len2 = 0.0;
    for (int r = 0; r < 3; r++) {
        world[r] = sign * (cof[r][0] * n->x + cof[r][1] * n->y + cof[r][2] * n->z);
        len2 += world[r] * world[r];
    }
    const double scale = len2 > 0.0 ? 1.0 / sqrt(len2) : 0.0;
    for (int r = 0; r < 3; r++)
        world[r] *= scale;
}
