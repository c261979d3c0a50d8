/* What an Assimp scene says of itself (assimp_report.h). */
#include <assimp/cimport.h>
#include <assimp/importerdesc.h>
#include <assimp/material.h>
#include <assimp/metadata.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "assimp_report.h"
#include "texture_find.h"

/* A hostile hierarchy is walked no deeper than this. */
#define MAX_NODE_DEPTH 1024

/* ---- mirrored meshes ---- */

static double determinant3(const struct aiMatrix4x4 *m)
{
    return (double)m->a1 * ((double)m->b2 * m->c3 - (double)m->b3 * m->c2) -
           (double)m->a2 * ((double)m->b1 * m->c3 - (double)m->b3 * m->c1) +
           (double)m->a3 * ((double)m->b1 * m->c2 - (double)m->b2 * m->c1);
}

enum { PLACED_PLAIN = 1, PLACED_MIRRORED = 2 };

/* Marks how each mesh is placed: plain, mirrored or both. The sign of
 * the global determinant is the parity of the local ones' signs. */
static void mark_placements(const struct aiScene *sc, const struct aiNode *node, bool mirrored, uint8_t *placed,
                            unsigned depth)
{
    if (!node || depth > MAX_NODE_DEPTH)
        return;
    mirrored ^= determinant3(&node->mTransformation) < 0.0;
    for (unsigned i = 0; i < node->mNumMeshes; i++)
        if (node->mMeshes[i] < sc->mNumMeshes)
            placed[node->mMeshes[i]] |= mirrored ? PLACED_MIRRORED : PLACED_PLAIN;
    for (unsigned i = 0; i < node->mNumChildren; i++)
        mark_placements(sc, node->mChildren[i], mirrored, placed, depth + 1);
}

static void reverse_faces(struct aiMesh *m)
{
    for (unsigned f = 0; f < m->mNumFaces; f++) {
        unsigned *c = m->mFaces[f].mIndices, n = m->mFaces[f].mNumIndices;
        for (unsigned i = 0; c && i < n / 2; i++) {
            unsigned t = c[i];
            c[i] = c[n - 1 - i];
            c[n - 1 - i] = t;
        }
    }
}

uint32_t sr_assimp_unmirror(const struct aiScene *sc)
{
    uint8_t *placed = calloc(sc->mNumMeshes ? sc->mNumMeshes : 1, 1);
    if (!placed)
        return 0;
    mark_placements(sc, sc->mRootNode, false, placed, 0);
    uint32_t reversed = 0;
    for (unsigned i = 0; i < sc->mNumMeshes; i++)
        if (placed[i] == PLACED_MIRRORED) {
            reverse_faces(sc->mMeshes[i]); /* the child's own copy of the scene, ours to change */
            reversed++;
        }
    free(placed);
    return reversed;
}

/* ---- the static pose ---- */

static void add_scaled(struct aiVector3D *sum, float w, struct aiVector3D target, struct aiVector3D base)
{
    sum->x += w * (target.x - base.x);
    sum->y += w * (target.y - base.y);
    sum->z += w * (target.z - base.z);
}

/* One mesh's morph targets at their weights; false when it has none. */
static bool apply_morphs(struct aiMesh *m)
{
    bool any = false;
    for (unsigned j = 0; j < m->mNumVertices; j++) {
        struct aiVector3D dp = { 0, 0, 0 }, dn = { 0, 0, 0 };
        for (unsigned a = 0; a < m->mNumAnimMeshes; a++) {
            const struct aiAnimMesh *t = m->mAnimMeshes[a];
            if (!t || t->mNumVertices != m->mNumVertices || !isfinite(t->mWeight) || t->mWeight == 0.0f)
                continue;
            if (t->mVertices)
                add_scaled(&dp, t->mWeight, t->mVertices[j], m->mVertices[j]);
            if (t->mNormals && m->mNormals)
                add_scaled(&dn, t->mWeight, t->mNormals[j], m->mNormals[j]);
        }
        add_scaled(&m->mVertices[j], 1.0f, dp, (struct aiVector3D){ 0, 0, 0 });
        if (m->mNormals)
            add_scaled(&m->mNormals[j], 1.0f, dn, (struct aiVector3D){ 0, 0, 0 });
    }
    for (unsigned a = 0; a < m->mNumAnimMeshes; a++)
        any |= m->mAnimMeshes[a] != NULL;
    return any;
}

/* An affine transform in double, row-major: p' = m · (x, y, z, 1). */
typedef double affine[3][4];

static void affine_of(const struct aiMatrix4x4 *a, affine out)
{
    const double m[3][4] = { { a->a1, a->a2, a->a3, a->a4 }, { a->b1, a->b2, a->b3, a->b4 },
                             { a->c1, a->c2, a->c3, a->c4 } };
    memcpy(out, m, sizeof m);
}

/* out = a · b (out may be either). */
static void affine_mul(const affine a, const affine b, affine out)
{
    affine r;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j] + (j == 3 ? a[i][3] : 0.0);
    memcpy(out, r, sizeof r);
}

/* The cofactors of the linear part: its inverse times its determinant,
 * transposed; the normals' transform up to scale. */
static void cofactors(const affine m, double c[3][3])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            c[i][j] = m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1];
        }
}

/* The inverse of an affine transform; false when it is singular. */
static bool affine_invert(const affine m, affine out)
{
    double c[3][3];
    cofactors(m, c);
    const double det = m[0][0] * c[0][0] + m[0][1] * c[0][1] + m[0][2] * c[0][2];
    if (!isfinite(det) || det == 0.0)
        return false;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            out[i][j] = c[j][i] / det;
    for (int i = 0; i < 3; i++)
        out[i][3] = -(out[i][0] * m[0][3] + out[i][1] * m[1][3] + out[i][2] * m[2][3]);
    return true;
}

/* A node's transform composed with its parents'. */
static void node_global(const struct aiNode *n, affine out)
{
    static const affine IDENTITY = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 } };
    memcpy(out, IDENTITY, sizeof IDENTITY);
    for (unsigned depth = 0; n && depth <= MAX_NODE_DEPTH; n = n->mParent, depth++) {
        affine local;
        affine_of(&n->mTransformation, local);
        affine_mul(local, out, out);
    }
}

/* The node named name, or that places mesh `mesh` (name NULL); NULL when none. */
static const struct aiNode *find_node(const struct aiNode *n, const char *name, unsigned mesh, unsigned depth)
{
    if (!n || depth > MAX_NODE_DEPTH)
        return NULL;
    if (name && strcmp(n->mName.data, name) == 0)
        return n;
    for (unsigned i = 0; !name && i < n->mNumMeshes; i++)
        if (n->mMeshes[i] == mesh)
            return n;
    for (unsigned i = 0; i < n->mNumChildren; i++) {
        const struct aiNode *found = find_node(n->mChildren[i], name, mesh, depth + 1);
        if (found)
            return found;
    }
    return NULL;
}

/* A skinned mesh posed by its skeleton as the node tree holds it (no
 * animation): each vertex at the weighted sum of its bones' global
 * transforms times their offset (inverse bind) matrices, glTF's skinning
 * formula, which Assimp's viewer also draws. The result is stored in the
 * mesh's own frame, of the first node that places it, so that placing
 * the mesh by that node gives the posed vertex. A vertex no bone weighs
 * stays as stored; false, the mesh as stored, when no node places it or
 * out of memory. */
static bool pose_skin(const struct aiScene *sc, unsigned mesh)
{
    struct aiMesh *m = sc->mMeshes[mesh]; /* the child's own copy of the scene, ours to change */
    const struct aiNode *placing = find_node(sc->mRootNode, NULL, mesh, 0);
    affine to_world, to_mesh;
    if (!placing || m->mNumVertices == 0)
        return false;
    node_global(placing, to_world);
    if (!affine_invert(to_world, to_mesh))
        return false;
    double(*sum)[13] = calloc(m->mNumVertices, sizeof *sum); /* the weighted transform, then the weight */
    if (!sum)
        return false;
    for (unsigned b = 0; b < m->mNumBones; b++) {
        const struct aiBone *bone = m->mBones[b];
        const struct aiNode *node = bone ? find_node(sc->mRootNode, bone->mName.data, 0, 0) : NULL;
        if (!node)
            continue;
        affine skin, offset;
        node_global(node, skin);
        affine_of(&bone->mOffsetMatrix, offset);
        affine_mul(skin, offset, skin);
        affine_mul(to_mesh, skin, skin);
        for (unsigned k = 0; k < bone->mNumWeights; k++) {
            const struct aiVertexWeight w = bone->mWeights[k];
            if (w.mVertexId >= m->mNumVertices || !isfinite(w.mWeight) || w.mWeight <= 0.0f)
                continue;
            double *s = sum[w.mVertexId];
            for (int e = 0; e < 12; e++)
                s[e] += w.mWeight * skin[e / 4][e % 4];
            s[12] += w.mWeight;
        }
    }
    for (unsigned j = 0; j < m->mNumVertices; j++) {
        const double *s = sum[j];
        if (s[12] <= 0.0)
            continue;
        affine a;
        for (int e = 0; e < 12; e++)
            a[e / 4][e % 4] = s[e] / s[12];
        const struct aiVector3D p = m->mVertices[j];
        double q[3], n[3] = { 0, 0, 0 }, c[3][3];
        for (int i = 0; i < 3; i++)
            q[i] = a[i][0] * p.x + a[i][1] * p.y + a[i][2] * p.z + a[i][3];
        if (!isfinite(q[0]) || !isfinite(q[1]) || !isfinite(q[2]))
            continue;
        m->mVertices[j] = (struct aiVector3D){ (ai_real)q[0], (ai_real)q[1], (ai_real)q[2] };
        if (!m->mNormals)
            continue;
        cofactors(a, c);
        const struct aiVector3D d = m->mNormals[j];
        double len2 = 0.0;
        for (int i = 0; i < 3; i++) {
            n[i] = c[i][0] * d.x + c[i][1] * d.y + c[i][2] * d.z;
            len2 += n[i] * n[i];
        }
        const double det = a[0][0] * c[0][0] + a[0][1] * c[0][1] + a[0][2] * c[0][2];
        const double scale = len2 > 0.0 && isfinite(len2) ? (det < 0.0 ? -1.0 : 1.0) / sqrt(len2) : 0.0;
        if (scale != 0.0)
            m->mNormals[j] = (struct aiVector3D){ (ai_real)(n[0] * scale), (ai_real)(n[1] * scale),
                                                  (ai_real)(n[2] * scale) };
    }
    free(sum);
    return true;
}

sr_assimp_pose sr_assimp_static_pose(const struct aiScene *sc)
{
    sr_assimp_pose pose = { .animations = sc->mNumAnimations };
    for (unsigned i = 0; i < sc->mNumMeshes; i++) {
        struct aiMesh *m = sc->mMeshes[i]; /* the child's own copy of the scene, ours to change */
        pose.morphed += apply_morphs(m);
        if (m->mNumBones > 0) {
            pose.skinned++;
            pose_skin(sc, i);
        }
    }
    return pose;
}

/* ---- metadata ---- */

static const struct aiMetadataEntry *metadata(const struct aiScene *sc, const char *key)
{
    const struct aiMetadata *md = sc->mMetaData;
    for (unsigned i = 0; md && i < md->mNumProperties; i++)
        if (strcmp(md->mKeys[i].data, key) == 0 && md->mValues[i].mData)
            return &md->mValues[i];
    return NULL;
}

static bool metadata_int(const struct aiScene *sc, const char *key, int *out)
{
    const struct aiMetadataEntry *e = metadata(sc, key);
    if (!e || e->mType != AI_INT32)
        return false;
    *out = *(const int32_t *)e->mData;
    return true;
}

static bool metadata_number(const struct aiScene *sc, const char *key, double *out)
{
    const struct aiMetadataEntry *e = metadata(sc, key);
    if (e && e->mType == AI_FLOAT)
        *out = *(const float *)e->mData;
    else if (e && e->mType == AI_DOUBLE)
        *out = *(const double *)e->mData;
    else if (e && e->mType == AI_INT32)
        *out = *(const int32_t *)e->mData;
    else
        return false;
    return true;
}

static const char *ending(const char *path)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    return dot && (!slash || dot > slash) ? dot + 1 : "";
}

static void report_importer(const struct aiScene *sc, const char *path, sr_load_report *r)
{
    const struct aiMetadataEntry *e = metadata(sc, "SourceAsset_Format");
    const struct aiImporterDesc *d = aiGetImporterDesc(ending(path));
    if (e && e->mType == AI_AISTRING)
        sr_report_copy(r->format, ((const struct aiString *)e->mData)->data);
    else if (d && d->mName)
        sr_report_copy(r->format, d->mName);
    else
        sr_report_copy(r->format, ending(path));
}

/* ---- axes and units, by what the file or its format says ---- */

typedef struct format_axes {
    const char *endings; /* space-separated, lower case */
    sr_axis up, front; /* front SR_AXIS_COUNT: the format says none */
    sr_found found;
    const char *why;
    double metres; /* 0: unknown */
    sr_found units_found;
    const char *units_why;
} format_axes;

/* Checked against assimp-testmodels (docs/scene-files.md, "Axes and
 * units"): which way each format's scenes arrive up from Assimp. */
static const format_axes FORMATS[] = {
    { "gltf glb", SR_AXIS_PY, SR_AXIS_COUNT, SR_FOUND_READ, "glTF 2.0 defines +y up", 1.0, SR_FOUND_READ, "glTF 2.0 defines metres" },
    { "dae zae", SR_AXIS_PY, SR_AXIS_COUNT, SR_FOUND_READ, "Assimp turns COLLADA's <up_axis> to +y itself", 0, SR_FOUND_UNKNOWN, "not reported by Assimp" },
    { "3ds ifc ifczip", SR_AXIS_PY, SR_AXIS_COUNT, SR_FOUND_READ, "Assimp turns this format to +y up itself", 0, SR_FOUND_UNKNOWN, "not reported by Assimp" },
    { "md2", SR_AXIS_PY, SR_AXIS_PX, SR_FOUND_READ, "Assimp turns Quake 2's +z up to +y itself; Quake's models face +x", 0, SR_FOUND_UNKNOWN, "not reported by Assimp" },
    { "x", SR_AXIS_PY, SR_AXIS_COUNT, SR_FOUND_READ, "DirectX .x files are +y up", 0, SR_FOUND_UNKNOWN, "the format states no unit" },
    { "ac acc ac3d", SR_AXIS_PY, SR_AXIS_COUNT, SR_FOUND_GUESSED, "AC3D states no axis; the AC3D modeller is +y up", 0, SR_FOUND_UNKNOWN, "the format states no unit" },
    { "3mf", SR_AXIS_PZ, SR_AXIS_COUNT, SR_FOUND_READ, "3MF defines +z up (the build direction)", 0.001, SR_FOUND_GUESSED, "3MF's default unit, millimetres" },
    { "amf", SR_AXIS_PZ, SR_AXIS_COUNT, SR_FOUND_READ, "AMF defines +z up (the build direction)", 0.001, SR_FOUND_GUESSED, "AMF's default unit, millimetres" },
    { "stl", SR_AXIS_PZ, SR_AXIS_COUNT, SR_FOUND_GUESSED, "STL states no axis; 3D-printing tools take +z up", 0.001, SR_FOUND_GUESSED, "STL states no unit; 3D printing takes millimetres" },
    { "blend", SR_AXIS_PZ, SR_AXIS_COUNT, SR_FOUND_READ, "Blender's world is +z up", 1.0, SR_FOUND_GUESSED, "Blender's default unit, metres" },
    { "smd", SR_AXIS_PZ, SR_AXIS_COUNT, SR_FOUND_GUESSED, "SMD states no axis; the Source engine is +z up", 0, SR_FOUND_UNKNOWN, "the format states no unit" },
    { "cob scn", SR_AXIS_PZ, SR_AXIS_COUNT, SR_FOUND_GUESSED, "COB states no axis; trueSpace is +z up", 0, SR_FOUND_UNKNOWN, "the format states no unit" },
};

static bool listed(const char *endings, const char *e)
{
    size_t n = strlen(e);
    for (const char *s = endings; n > 0 && *s;) {
        size_t len = strcspn(s, " ");
        if (len == n && strncasecmp(s, e, n) == 0)
            return true;
        s += len + (s[len] == ' ');
    }
    return false;
}

static void report_axes(const struct aiScene *sc, const char *path, double amf_metres, sr_load_report *r)
{
    *r = (sr_load_report){ .up = SR_AXIS_PY, .front = SR_AXIS_COUNT, .up_found = SR_FOUND_GUESSED };
    sr_report_copy(r->up_why, "the format states no axis; +y up assumed");
    sr_report_copy(r->units_why, "the format states no unit");
    for (size_t i = 0; i < sizeof FORMATS / sizeof *FORMATS; i++) {
        const format_axes *f = &FORMATS[i];
        if (!listed(f->endings, ending(path)))
            continue;
        r->up = f->up;
        r->front = f->front;
        r->up_found = f->found;
        sr_report_copy(r->up_why, f->why);
        r->metres_per_unit = f->metres;
        r->units_found = f->units_found;
        sr_report_copy(r->units_why, f->units_why);
    }
    int axis, sign;
    if (metadata_int(sc, "UpAxis", &axis) && axis >= 0 && axis <= 2) { /* FBX's GlobalSettings */
        sign = metadata_int(sc, "UpAxisSign", &sign) && sign < 0 ? 1 : 0;
        r->up = (uint32_t)(2 * axis + sign);
        r->up_found = SR_FOUND_READ;
        sr_report_copy(r->up_why, "the file's UpAxis and UpAxisSign");
    }
    if (amf_metres > 0.0) {
        r->metres_per_unit = amf_metres;
        r->units_found = SR_FOUND_READ;
        sr_report_copy(r->units_why, "the file's <amf unit=...>");
    }
    double cm;
    if (metadata_number(sc, "UnitScaleFactor", &cm) && cm > 0.0) { /* FBX: centimetres per unit */
        r->metres_per_unit = cm / 100.0;
        r->units_found = SR_FOUND_READ;
        sr_report_copy(r->units_why, "the file's UnitScaleFactor (centimetres per unit)");
    }
}

/* ---- parts, textures, what is left out ---- */

/* The colour factor a material has: glTF's base colour, else the diffuse
 * colour; false when it gives neither. */
static bool material_factor(const struct aiMaterial *mat, struct aiColor4D *c)
{
    return aiGetMaterialColor(mat, AI_MATKEY_BASE_COLOR, c) == aiReturn_SUCCESS ||
           aiGetMaterialColor(mat, AI_MATKEY_COLOR_DIFFUSE, c) == aiReturn_SUCCESS;
}

static bool texture_of_kind(const struct aiMaterial *mat, enum aiTextureType kind, struct aiString *name)
{
    return aiGetMaterialTexture(mat, kind, 0, name, NULL, NULL, NULL, NULL, NULL, NULL) == aiReturn_SUCCESS &&
           name->length > 0;
}

bool sr_assimp_material_texture(const struct aiMaterial *mat, struct aiString *name, bool *emissive)
{
    *emissive = false;
    if (texture_of_kind(mat, aiTextureType_BASE_COLOR, name) || texture_of_kind(mat, aiTextureType_DIFFUSE, name))
        return true;
    struct aiColor4D c;
    bool black = material_factor(mat, &c) && c.r == 0.0f && c.g == 0.0f && c.b == 0.0f;
    return *emissive = black && texture_of_kind(mat, aiTextureType_EMISSIVE, name);
}

static int32_t part_texture(const struct aiScene *sc, const struct aiMaterial *mat, const char *path,
                            sr_load_report *r)
{
    struct aiString name;
    bool emissive;
    if (!sr_assimp_material_texture(mat, &name, &emissive))
        return -1;
    bool embedded = name.data[0] == '*';
    for (unsigned i = 0; !embedded && i < sc->mNumTextures; i++)
        embedded = strcmp(sc->mTextures[i]->mFilename.data, name.data) == 0;
    if (embedded)
        return sr_report_add_texture(r, name.data, NULL, SR_TEXTURE_EMBEDDED);
    char *found = sr_texture_find(path, name.data);
    int32_t t = sr_report_add_texture(r, name.data, found, found ? SR_TEXTURE_FOUND : SR_TEXTURE_MISSING);
    free(found);
    return t;
}

bool sr_assimp_report(const struct aiScene *sc, const sr_assimp_instances *list, const char *path,
                      sr_assimp_pose pose, double amf_metres, sr_load_report *r)
{
    uint32_t mirrored = r->mirrored_meshes, warnings = r->warning_count;
    char kept[SR_REPORT_MAX_WARNINGS][SR_REPORT_TEXT];
    memcpy(kept, r->warnings, sizeof kept);
    report_axes(sc, path, amf_metres, r);
    report_importer(sc, path, r);
    r->mirrored_meshes = mirrored;
    r->warning_count = warnings;
    memcpy(r->warnings, kept, sizeof kept);
    r->animations = pose.animations; /* flattening drops them: counted before */
    r->skinned_meshes = pose.skinned;
    r->morphed_meshes = pose.morphed;
    r->cameras = sc->mNumCameras;
    r->lights = sc->mNumLights;
    uint32_t first = 0;
    for (uint32_t i = 0; i < list->count; i++) {
        const struct aiMesh *m = sc->mMeshes[list->at[i].mesh];
        if (!(m->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || m->mNumVertices == 0) {
            for (unsigned f = 0; f < m->mNumFaces; f++) {
                r->points += m->mFaces[f].mNumIndices == 1;
                r->lines += m->mFaces[f].mNumIndices == 2;
            }
            continue;
        }
        uint32_t count = 0;
        for (unsigned f = 0; f < m->mNumFaces; f++)
            count += m->mFaces[f].mNumIndices == 3;
        if (count == 0)
            continue;
        const struct aiMaterial *mat = m->mMaterialIndex < sc->mNumMaterials ? sc->mMaterials[m->mMaterialIndex] : NULL;
        struct aiString name = { 0 };
        if (mat)
            aiGetMaterialString(mat, AI_MATKEY_NAME, &name);
        int32_t texture = mat ? part_texture(sc, mat, path, r) : -1;
        if (!sr_report_add_part(r, first, count, name.data, texture))
            return false;
        first += count;
    }
    return true;
}
