/* An AMF file's constellations, read from the file (amf_read.h) and set
 * on the nodes Assimp made for them (amf_constellations.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "amf_constellations.h"

/* A hostile hierarchy is walked no deeper than this. */
#define MAX_NODE_DEPTH 1024

/* sin and cos of an angle in degrees, exact at quarter turns. */
static void sincos_degrees(double degrees, double *s, double *c)
{
    const double quarters = degrees / 90.0;
    if (quarters == floor(quarters) && fabs(quarters) < 1e15) {
        static const double SIN[4] = { 0, 1, 0, -1 }, COS[4] = { 1, 0, -1, 0 };
        int k = (int)fmod(quarters, 4.0);
        k += k < 0 ? 4 : 0;
        *s = SIN[k];
        *c = COS[k];
        return;
    }
    const double radians = degrees * (acos(-1.0) / 180.0);
    *s = sin(radians);
    *c = cos(radians);
}

/* translate(delta) · Rz · Ry · Rx, the instance's transform. */
static void instance_transform(const sr_amf_instance *in, struct aiMatrix4x4 *out)
{
    double sx, cx, sy, cy, sz, cz;
    sincos_degrees(in->value[3], &sx, &cx);
    sincos_degrees(in->value[4], &sy, &cy);
    sincos_degrees(in->value[5], &sz, &cz);
    const double rx[3][3] = { { 1, 0, 0 }, { 0, cx, -sx }, { 0, sx, cx } };
    const double ry[3][3] = { { cy, 0, sy }, { 0, 1, 0 }, { -sy, 0, cy } };
    const double rz[3][3] = { { cz, -sz, 0 }, { sz, cz, 0 }, { 0, 0, 1 } };
    double yx[3][3], m[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            yx[i][j] = ry[i][0] * rx[0][j] + ry[i][1] * rx[1][j] + ry[i][2] * rx[2][j];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            m[i][j] = rz[i][0] * yx[0][j] + rz[i][1] * yx[1][j] + rz[i][2] * yx[2][j];
    *out = (struct aiMatrix4x4){ (ai_real)m[0][0], (ai_real)m[0][1], (ai_real)m[0][2], (ai_real)in->value[0],
                                 (ai_real)m[1][0], (ai_real)m[1][1], (ai_real)m[1][2], (ai_real)in->value[1],
                                 (ai_real)m[2][0], (ai_real)m[2][1], (ai_real)m[2][2], (ai_real)in->value[2],
                                 0, 0, 0, 1 };
}

static int by_id(const void *a, const void *b)
{
    return strcmp(((const sr_amf_constellation *)a)->id, ((const sr_amf_constellation *)b)->id);
}

/* Assimp's node for a constellation: named by its id, one child per
 * instance, each holding one node named by the instance's object id. */
static bool is_placed_by(const sr_amf_file *file, const struct aiNode *node, const sr_amf_constellation *con)
{
    if (con->count != node->mNumChildren)
        return false;
    const sr_amf_instance *in = (const sr_amf_instance *)file->instances.data + con->first;
    for (size_t i = 0; i < con->count; i++) {
        const struct aiNode *t = node->mChildren[i];
        if (!t || t->mNumChildren != 1 || !t->mChildren[0] || strcmp(t->mChildren[0]->mName.data, in[i].objectid) != 0)
            return false;
    }
    return true;
}

static uint32_t place(const sr_amf_file *file, struct aiNode *node, unsigned depth)
{
    if (!node || depth > MAX_NODE_DEPTH)
        return 0;
    uint32_t set = 0;
    const sr_amf_constellation *con = NULL;
    if (node->mName.length > 0 && node->mName.length < SR_AMF_MAX_NAME) {
        sr_amf_constellation named = { .first = 0 };
        memcpy(named.id, node->mName.data, node->mName.length + 1);
        con = bsearch(&named, file->constellations.data, file->constellations.count, sizeof named, by_id);
    }
    if (con && is_placed_by(file, node, con)) {
        const sr_amf_instance *in = (const sr_amf_instance *)file->instances.data + con->first;
        for (size_t i = 0; i < con->count; i++, set++)
            instance_transform(&in[i], &node->mChildren[i]->mTransformation);
    }
    for (unsigned i = 0; i < node->mNumChildren; i++)
        set += place(file, node->mChildren[i], depth + 1);
    return set;
}

uint32_t sr_amf_place_instances(const struct aiScene *sc, sr_amf_file *file)
{
    sr_array *list = &file->constellations;
    sr_amf_constellation *con = list->data;
    size_t kept = 0; /* those with an id: Assimp's node for one without matches nothing */
    for (size_t i = 0; i < list->count; i++)
        if (con[i].id[0])
            con[kept++] = con[i];
    list->count = kept;
    if (kept == 0)
        return 0;
    qsort(con, kept, sizeof *con, by_id);
    return place(file, sc->mRootNode, 0); /* the child's own copy of the scene, ours to change */
}
