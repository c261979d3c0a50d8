/* Every mesh format Assimp reads (glTF 2.0, PLY, STL, FBX, COLLADA, 3DS, …)
 * -> sr_mesh, through its C API.
 *
 * Assimp triangulates, merges identical vertices and makes smooth normals
 * where a mesh has none; the scene is flattened here, not by Assimp's
 * aiProcess_PreTransformVertices, which merges the meshes that share a
 * material: each node's instance of a mesh (assimp_instances.h) is placed
 * by its node transforms in double and becomes its own part, so part ids
 * are an instance mask. Its world is right-handed y-up like OBJ's, so the
 * same flip applies: z negated (of positions and normals) and each
 * triangle (a, b, c) written as (a, c, b). Instances follow in node order,
 * faces in face order: triangle ids count them so. Points and lines are
 * left out. Each of the scene's materials becomes a mesh material (its
 * colour factor, its base-colour or diffuse texture, glTF's alpha mode and
 * cutoff), and each part names its mesh's. Positions are stored relative
 * to a far mesh's centre, as OBJ's are. A texture embedded in the file
 * (.glb, FBX) is decoded here; one beside it is named by texture_path,
 * found by texture_find.h's rules. An instance that a mirroring node
 * transform places (its determinant negative) keeps its outward faces
 * front faces (glTF requires it; a DirectX .x file exported from Blender
 * mirrors its root frame): a mesh placed mirrored alone has its winding
 * reversed before post-processing (sr_assimp_unmirror), a mesh placed both
 * ways its mirrored instances' reversed here. Morph targets are applied at
 * their default weights and skinned meshes posed by their skeletons
 * before post-processing (assimp_report.h), and an AMF file's volumes
 * and constellation instances read as the file says (amf_import.h).
 * 3MF and AMF meshes are shaded by their facets (mesh_facets.h). The
 * import runs in a child process (isolated_load.h): Assimp is not ours to
 * make crash- and hang-free.
 */
#include <assimp/GltfMaterial.h>
#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/metadata.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/error.h"
#include "core/input_file.h"
#include "isolated_load.h"
#include "mesh_facets.h"
#include "mesh_loaders.h"
#include "mesh_origin.h"
#include "obj_parse.h"
#include "amf_import.h"
#include "x3d_reuse.h"
#include "assimp_instances.h"
#include "assimp_report.h"
#include "texture_find.h"
#include "texture_read.h"

/* The steps aiImportFile would run, in two calls (Assimp orders the steps of
 * one call itself): between them, which meshes have normals of their own. */
#define SHAPE_STEPS (aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_FindInvalidData)
#define NORMAL_STEPS (aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals)

/* After aiProcess_SortByPType a mesh holds one kind of primitive (the
 * n-gon flag aside); triangles are the ones drawn. */
static bool is_triangles(const struct aiMesh *m)
{
    return (m->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) && m->mNumVertices > 0;
}

/* A point cloud: meshes of vertices and no faces (a PLY of vertices
 * alone). Its vertices are kept, for drawing as points; it has no node
 * transforms to apply and skips the post-processing, whose
 * PreTransformVertices crashes on a mesh without faces in Assimp 5.2. */
static bool is_point_cloud(const struct aiScene *sc)
{
    for (unsigned i = 0; i < sc->mNumMeshes; i++)
        if (sc->mMeshes[i]->mNumFaces > 0)
            return false;
    return sc->mNumMeshes > 0;
}

/* The meshes whose vertices the mesh gets. */
static bool is_kept(const struct aiScene *sc, const struct aiMesh *m)
{
    return is_triangles(m) || (m->mNumVertices > 0 && is_point_cloud(sc));
}

/* A mesh's vertex colours, unless every one is transparent black: Assimp's
 * AMF importer gives a mesh of no colours such a set, which would draw it
 * black. */
static bool has_colors(const struct aiMesh *m)
{
    for (unsigned j = 0; m->mColors[0] && j < m->mNumVertices; j++) {
        const struct aiColor4D c = m->mColors[0][j];
        if (c.r != 0.0f || c.g != 0.0f || c.b != 0.0f || c.a != 0.0f)
            return true;
    }
    return false;
}

static bool is_triangle(const struct aiFace *f)
{
    return f->mNumIndices == 3;
}

/* The material's colour factor: glTF's base colour, else the diffuse
 * colour, white when it has none; its emissive colour when it is drawn by
 * its emissive texture. Assimp's own material for a file that names none
 * (STL, PLY, OFF, AMF) is softrast's default instead, OBJ's: gray 0.8,
 * white over vertex colours (its gray 0.6 is Assimp's, not the file's, and
 * would darken the colours). */
static struct aiColor4D material_color(const struct aiMaterial *mat, bool emissive, bool colors)
{
    struct aiColor4D c = { 1.0f, 1.0f, 1.0f, 1.0f };
    struct aiString name;
    if (aiGetMaterialString(mat, AI_MATKEY_NAME, &name) == aiReturn_SUCCESS &&
        strcmp(name.data, AI_DEFAULT_MATERIAL_NAME) == 0) {
        float gray = colors ? 1.0f : 0.8f;
        return (struct aiColor4D){ gray, gray, gray, 1.0f };
    }
    if (emissive) {
        aiGetMaterialColor(mat, AI_MATKEY_COLOR_EMISSIVE, &c);
        c.a = 1.0f;
    } else if (aiGetMaterialColor(mat, AI_MATKEY_BASE_COLOR, &c) != aiReturn_SUCCESS)
        aiGetMaterialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &c);
    return c;
}

/* What the scene needs, counted before anything is allocated for it. */
typedef struct scene_counts {
    uint64_t vertices, indices;
    uint32_t parts; /* drawn instances: at least one triangle */
    bool normals, uvs, colors;
} scene_counts;

static bool count_scene(const struct aiScene *sc, const sr_assimp_instances *list, const char *path, scene_counts *n,
                        sr_error *err)
{
    *n = (scene_counts){ 0 };
    for (uint32_t k = 0; k < list->count; k++) {
        const unsigned i = list->at[k].mesh;
        const struct aiMesh *m = sc->mMeshes[i];
        if (!is_kept(sc, m))
            continue;
        n->vertices += m->mNumVertices;
        uint64_t before = n->indices;
        for (unsigned f = 0; f < m->mNumFaces; f++) {
            if (!is_triangle(&m->mFaces[f]))
                continue;
            /* Assimp passes on what a file names: a PLY face may name a
             * vertex the file never gave. */
            for (int c = 0; c < 3; c++)
                if (m->mFaces[f].mIndices[c] >= m->mNumVertices)
                    return sr_error_set(err, "%s: mesh %u face %u names vertex %u of %u", path, i, f,
                                        m->mFaces[f].mIndices[c], m->mNumVertices);
            n->indices += 3u;
        }
        n->parts += n->indices > before;
        n->normals |= m->mNormals != NULL;
        n->uvs |= m->mTextureCoords[0] != NULL;
        n->colors |= has_colors(m);
    }
    if (n->vertices > SR_MAX_MESH_VERTICES || n->indices / 3 > SR_MAX_MESH_TRIANGLES)
        return sr_error_set(err, "%s: %llu vertices and %llu triangles exceed the limits (%u, %u)", path,
                            (unsigned long long)n->vertices, (unsigned long long)(n->indices / 3),
                            SR_MAX_MESH_VERTICES, SR_MAX_MESH_TRIANGLES);
    return true;
}

/* The first texture of a material that a drawn mesh uses; false when none
 * has one. */
static bool first_texture(const struct aiScene *sc, struct aiString *name)
{
    bool emissive;
    for (unsigned i = 0; i < sc->mNumMeshes; i++)
        if (is_triangles(sc->mMeshes[i]) && sc->mMeshes[i]->mMaterialIndex < sc->mNumMaterials &&
            sr_assimp_material_texture(sc->mMaterials[sc->mMeshes[i]->mMaterialIndex], name, &emissive))
            return true;
    return false;
}

/* The texture a name refers to inside the file: "*N" is the N-th, any other
 * name one whose file name it is; NULL when the name is a file beside it. */
static const struct aiTexture *embedded_texture(const struct aiScene *sc, const char *name)
{
    if (name[0] == '*') {
        char *end;
        unsigned long i = strtoul(name + 1, &end, 10);
        return *end == '\0' && i < sc->mNumTextures ? sc->mTextures[i] : NULL;
    }
    for (unsigned i = 0; i < sc->mNumTextures; i++)
        if (strcmp(sc->mTextures[i]->mFilename.data, name) == 0)
            return sc->mTextures[i];
    return NULL;
}

/* An embedded image: a whole file in memory (mHeight 0; its format's
 * ending in achFormatHint), decoded as a texture file would be, or raw
 * BGRA texels. */
static bool decode_embedded(const struct aiTexture *t, const char *path, sr_texture *tex, sr_error *err)
{
    char name[SR_ERROR_MAX / 2];
    snprintf(name, sizeof name, "%s#texture.%s", path, t->achFormatHint[0] ? t->achFormatHint : "png");
    if (t->mHeight == 0) {
        FILE *f = fmemopen(t->pcData, t->mWidth, "rb");
        return f ? sr_texture_read(tex, f, name, err) : sr_error_set(err, "%s: out of memory", name);
    }
    uint64_t count = (uint64_t)t->mWidth * t->mHeight;
    if (t->mWidth > SR_MAX_TEXTURE_SIDE || t->mHeight > SR_MAX_TEXTURE_SIDE || count > SR_MAX_TEXTURE_TEXELS)
        return sr_error_set(err, "%s: texture is %ux%u, past the limits", name, t->mWidth, t->mHeight);
    tex->texels = malloc(count * sizeof *tex->texels);
    if (!tex->texels)
        return sr_error_set(err, "%s: out of memory", name);
    for (uint64_t i = 0; i < count; i++)
        tex->texels[i] = (uint32_t)t->pcData[i].r << 16 | (uint32_t)t->pcData[i].g << 8 | t->pcData[i].b;
    tex->width = (int)t->mWidth;
    tex->height = (int)t->mHeight;
    return true;
}

/* The mesh's texture: decoded into tex when the file embeds it, else named
 * by mesh->texture_path, resolved beside the model. */
static bool find_texture(const struct aiScene *sc, const char *path, sr_mesh *mesh, sr_texture *tex, sr_error *err)
{
    struct aiString name;
    if (!first_texture(sc, &name))
        return true;
    const struct aiTexture *inside = embedded_texture(sc, name.data);
    if (inside)
        return decode_embedded(inside, path, tex, err);
    if (name.data[0] == '*')
        return true; /* an index past the file's textures: none */
    mesh->texture_path = sr_texture_find(path, name.data);
    if (!mesh->texture_path) /* missing: named as written, for the warning */
        mesh->texture_path = sr_obj_path_beside(path, name.data);
    return mesh->texture_path || sr_error_set(err, "%s: out of memory", path);
}

/* glTF's alpha mode and cutoff (0.5 when not given); other formats' are
 * opaque. */
static void material_alpha(const struct aiMaterial *mat, sr_material *out)
{
    struct aiString mode;
    out->alpha_cutoff = 0.5f;
    if (aiGetMaterialString(mat, AI_MATKEY_GLTF_ALPHAMODE, &mode) != aiReturn_SUCCESS)
        return;
    out->alpha_mode = strcmp(mode.data, "MASK") == 0    ? SR_ALPHA_MASK
                      : strcmp(mode.data, "BLEND") == 0 ? SR_ALPHA_BLEND
                                                        : SR_ALPHA_OPAQUE;
    float cutoff;
    if (aiGetMaterialFloat(mat, AI_MATKEY_GLTF_ALPHACUTOFF, &cutoff) == aiReturn_SUCCESS && isfinite(cutoff))
        out->alpha_cutoff = cutoff;
}

/* The scene's materials, in Assimp's order: a texture embedded in the file
 * is the one decoded into tex (the first any drawn mesh uses: another
 * embedded one is left out, its material drawn in its colour), one beside
 * it a path found by texture_find.h's rules, else named as written (for
 * the warning). A scene without materials gets one, white. A material
 * that shows by emission alone (glTF's labels: a black base colour and an
 * emissive texture) draws that texture times its emissive colour: lambert
 * has no emission, and it would be black. */
static bool build_materials(const struct aiScene *sc, const char *path, sr_mesh *mesh, sr_texture *tex,
                            sr_error *err)
{
    uint32_t n = sc->mNumMaterials ? sc->mNumMaterials : 1;
    if (n > SR_MAX_MESH_MATERIALS)
        return sr_error_set(err, "%s: %u materials, more than %u", path, n, SR_MAX_MESH_MATERIALS);
    mesh->materials = calloc(n, sizeof *mesh->materials);
    if (!mesh->materials)
        return sr_error_set(err, "%s: out of memory", path);
    mesh->material_count = n;
    struct aiString first;
    const struct aiTexture *decoded = tex && tex->texels && first_texture(sc, &first) ? embedded_texture(sc, first.data)
                                                                                       : NULL;
    for (uint32_t i = 0; i < n; i++) {
        sr_material *m = &mesh->materials[i];
        *m = (sr_material){ .base_color = { 1.0f, 1.0f, 1.0f, 1.0f }, .alpha_cutoff = 0.5f };
        if (i >= sc->mNumMaterials)
            continue;
        const struct aiMaterial *mat = sc->mMaterials[i];
        struct aiString name;
        bool emissive, textured = sr_assimp_material_texture(mat, &name, &emissive);
        struct aiColor4D c = material_color(mat, emissive, mesh->colors != NULL);
        const float rgba[4] = { c.r, c.g, c.b, c.a };
        for (int k = 0; k < 4; k++)
            m->base_color[k] = isfinite(rgba[k]) ? rgba[k] : 1.0f;
        material_alpha(mat, m);
        if (!textured)
            continue;
        const struct aiTexture *inside = embedded_texture(sc, name.data);
        if (inside || name.data[0] == '*') {
            m->texture = inside && inside == decoded ? tex : NULL;
            continue;
        }
        m->texture_path = sr_texture_find(path, name.data);
        if (!m->texture_path)
            m->texture_path = sr_obj_path_beside(path, name.data);
        if (!m->texture_path)
            return sr_error_set(err, "%s: out of memory", path);
    }
    return true;
}

/* An instance's normal in softrast's world. Assimp made a mesh's missing
 * normals from its winding before placing; an instance drawn with that
 * winding under a mirroring transform (a mesh sr_assimp_unmirror turned)
 * has them turned back (mirrored edges flip their cross product), so they
 * match normals made from the placed triangles. */
static void place_normal(const sr_assimp_instance *in, const struct aiVector3D *n, bool generated, vec3 out)
{
    double world[3];
    sr_assimp_instance_turn(in, n, world);
    const double sign = generated && in->turned ? -1.0 : 1.0;
    glm_vec3_copy((vec3){ (float)(sign * world[0]), (float)(sign * world[1]), (float)(-sign * world[2]) }, out);
}

static void copy_vertices(const struct aiScene *sc, const sr_assimp_instances *list, const bool *generated,
                          sr_mesh *mesh, const double origin[3])
{
    uint32_t v = 0, x = 0, part = 0;
    for (uint32_t k = 0; k < list->count; k++) {
        const sr_assimp_instance *in = &list->at[k];
        const struct aiMesh *m = sc->mMeshes[in->mesh];
        if (!is_kept(sc, m))
            continue;
        const bool colored = has_colors(m);
        for (unsigned j = 0; j < m->mNumVertices; j++, v++) {
            double world[3];
            sr_assimp_instance_place(in, &m->mVertices[j], world);
            world[2] = -world[2];
            for (int c = 0; c < 3; c++)
                mesh->positions[v][c] = (float)(world[c] - origin[c]);
            if (mesh->normals && m->mNormals)
                place_normal(in, &m->mNormals[j], generated[in->mesh], mesh->normals[v]);
            if (mesh->uvs && m->mTextureCoords[0])
                glm_vec2_copy((vec2){ m->mTextureCoords[0][j].x, m->mTextureCoords[0][j].y }, mesh->uvs[v]);
            if (mesh->colors) {
                const struct aiColor4D c = colored ? m->mColors[0][j] : (struct aiColor4D){ 1, 1, 1, 1 };
                glm_vec3_copy((vec3){ c.r, c.g, c.b }, mesh->colors[v]);
            }
        }
        uint32_t first = x / 3;
        for (unsigned f = 0; f < m->mNumFaces; f++) {
            if (!is_triangle(&m->mFaces[f]))
                continue;
            const unsigned *c = m->mFaces[f].mIndices;
            uint32_t base = v - m->mNumVertices;
            /* The z flip reverses the winding; a mirrored instance of a
             * mesh sr_assimp_unmirror left as it was (placed plain too)
             * reverses it back, its outward faces staying front faces. */
            const bool keep = in->mirrored && !in->turned;
            mesh->indices[x++] = base + c[0];
            mesh->indices[x++] = base + c[keep ? 1 : 2];
            mesh->indices[x++] = base + c[keep ? 2 : 1];
        }
        if (x / 3 > first)
            mesh->parts[part++] = (sr_mesh_part){ first, x / 3 - first,
                                                  m->mMaterialIndex < sc->mNumMaterials ? m->mMaterialIndex : 0 };
    }
}

/* The bounds in double of the flipped positions, and the origin they give. */
static bool scene_origin(const struct aiScene *sc, const sr_assimp_instances *list, const char *path, double origin[3],
                         sr_error *err)
{
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (uint32_t n = 0; n < list->count; n++) {
        const unsigned i = list->at[n].mesh;
        const struct aiMesh *m = sc->mMeshes[i];
        for (unsigned j = 0; is_kept(sc, m) && j < m->mNumVertices; j++) {
            double p[3];
            sr_assimp_instance_place(&list->at[n], &m->mVertices[j], p);
            p[2] = -p[2];
            for (int k = 0; k < 3; k++) {
                if (!isfinite(p[k]))
                    return sr_error_set(err, "%s: mesh %u has a non-finite position", path, i);
                lo[k] = fmin(lo[k], p[k]);
                hi[k] = fmax(hi[k], p[k]);
            }
        }
    }
    if (lo[0] > hi[0])
        memset(origin, 0, 3 * sizeof *origin);
    else
        sr_mesh_origin_for_bounds(lo, hi, origin);
    return true;
}

static bool build_mesh(const struct aiScene *sc, const sr_assimp_instances *list, const bool *generated,
                       const char *path, sr_mesh *mesh, sr_error *err)
{
    scene_counts n;
    double origin[3];
    if (!count_scene(sc, list, path, &n, err) || !scene_origin(sc, list, path, origin, err) ||
        !sr_mesh_alloc(mesh, (uint32_t)n.vertices, (uint32_t)n.indices, n.normals, n.uvs, n.colors, err))
        return false;
    mesh->parts = calloc(n.parts ? n.parts : 1, sizeof *mesh->parts);
    if (!mesh->parts)
        return sr_error_set(err, "%s: out of memory", path);
    mesh->part_count = n.parts;
    copy_vertices(sc, list, generated, mesh, origin);
    memcpy(mesh->origin, origin, sizeof mesh->origin);
    return true;
}

/* Assimp 5.2's SortByPType crashes on a mesh without faces, which a file
 * with faces elsewhere may hold (an empty STL solid): marked as points, it
 * is left alone, and not drawn. */
static void mark_faceless(const struct aiScene *sc)
{
    for (unsigned i = 0; i < sc->mNumMeshes; i++)
        if (sc->mMeshes[i]->mNumFaces == 0) /* the child's own copy of the scene, ours to change */
            sc->mMeshes[i]->mPrimitiveTypes = aiPrimitiveType_POINT;
}

/* The post-processing in two calls; generated[i] says whether mesh i's
 * normals are Assimp's own (NULL when out of memory). */
static const struct aiScene *post_process(const struct aiScene *sc, bool **generated)
{
    if (!is_point_cloud(sc)) {
        mark_faceless(sc);
        sc = aiApplyPostProcessing(sc, SHAPE_STEPS);
    }
    *generated = sc ? calloc(sc->mNumMeshes ? sc->mNumMeshes : 1, sizeof **generated) : NULL;
    if (!sc || !*generated || is_point_cloud(sc))
        return sc;
    for (unsigned i = 0; i < sc->mNumMeshes; i++)
        (*generated)[i] = sc->mMeshes[i]->mNormals == NULL;
    return aiApplyPostProcessing(sc, NORMAL_STEPS);
}

/* Assimp's reason on one line: it may quote bytes of the file (an FBX
 * type code), a newline among them. */
static bool import_error(const char *path, sr_error *err)
{
    char reason[sizeof err->message];
    snprintf(reason, sizeof reason, "%s", aiGetErrorString());
    for (char *c = reason; *c; c++)
        if (iscntrl((unsigned char)*c))
            *c = '?';
    return sr_error_set(err, "%s: %s", path, reason);
}

/* Whether path's ending is one of endings (lower case, each with its
 * dot), as Assimp picks a format. */
static bool ends_in(const char *path, const char *const *endings)
{
    const char *dot = strrchr(path, '.');
    for (; dot && !strchr(dot, '/') && *endings; endings++)
        if (strcasecmp(dot, *endings) == 0)
            return true;
    return false;
}

static const char *const AMF[] = { ".amf", NULL };
static const char *const X3D[] = { ".x3d", NULL };

/* Assimp's scene of the X3D file at path, read from its rewrite when it
 * reuses nodes (x3d_reuse.h), into *scene (NULL when Assimp could not
 * read it); false with err set when softrast could not rewrite it. */
static bool import_x3d(const char *path, const struct aiScene **scene, sr_error *err)
{
    char *text;
    size_t size;
    if (!sr_x3d_write_out_reuses(path, &text, &size, err))
        return false;
    if (!text) {
        *scene = aiImportFile(path, 0);
        return true;
    }
    *scene = size <= UINT_MAX ? aiImportFileFromMemory(text, (unsigned)size, 0, "x3d") : NULL;
    free(text);
    return true;
}

/* Assimp's scene of the file at path, not post-processed, AMF's and X3D's
 * mended; false with err set when softrast could not read it first. */
static bool import_scene(const char *path, const struct aiScene **scene, double *amf_metres, sr_error *err)
{
    if (ends_in(path, AMF))
        return sr_amf_import(path, 0, scene, amf_metres, err);
    if (ends_in(path, X3D))
        return import_x3d(path, scene, err);
    *scene = aiImportFile(path, 0);
    return true;
}

/* Formats whose meshes are a solid's facets, shaded flat (mesh_facets.h). */
static const char *const FACETED[] = { ".3mf", ".amf", NULL };

/* In the child process: Assimp's import, AMF's and X3D's mended, its
 * mirrored meshes turned outward, flattened and converted; what it found
 * into report. */
static bool import_here(sr_mesh *mesh, sr_texture *texture, const char *path, sr_load_report *report, sr_error *err)
{
    *mesh = (sr_mesh){ 0 };
    const struct aiScene *sc = NULL;
    double amf_metres = 0.0;
    if (!import_scene(path, &sc, &amf_metres, err))
        return false;
    if (!sc)
        return import_error(path, err);
    uint32_t mirrored = sr_assimp_unmirror(sc);
    sr_assimp_pose pose = sr_assimp_static_pose(sc);
    bool *generated = NULL;
    sc = post_process(sc, &generated);
    if (!sc) {
        free(generated);
        return import_error(path, err);
    }
    sr_assimp_instances list = { 0 };
    bool ok = (generated && sr_assimp_instances_find(sc, SR_MAX_MESH_TRIANGLES, &list)) ||
              sr_error_set(err, "%s: out of memory, or more than %u mesh instances", path, SR_MAX_MESH_TRIANGLES);
    ok = ok && build_mesh(sc, &list, generated, path, mesh, err) &&
         (!ends_in(path, FACETED) || sr_mesh_facet(mesh, err)) && find_texture(sc, path, mesh, texture, err) &&
         build_materials(sc, path, mesh, texture, err);
    if (ok && report) {
        report->mirrored_meshes = mirrored;
        ok = sr_assimp_report(sc, &list, path, pose, amf_metres, report) || sr_error_set(err, "%s: out of memory", path);
    }
    sr_assimp_instances_free(&list);
    free(generated);
    aiReleaseImport(sc);
    if (!ok)
        sr_mesh_free(mesh);
    return ok;
}

static bool import_plain(sr_mesh *mesh, sr_texture *texture, const char *path, sr_error *err)
{
    return import_here(mesh, texture, path, NULL, err);
}

bool sr_assimp_load_report(sr_mesh *mesh, sr_texture *texture, const char *path, unsigned seconds,
                           sr_load_report *report, sr_error *err)
{
    bool ok = report ? sr_isolated_load_report(mesh, texture, path, import_here, seconds, report, err)
                     : sr_isolated_load(mesh, texture, path, import_plain, seconds, err);
    if (ok)
        sr_mesh_update_bounds(mesh);
    return ok;
}

bool sr_assimp_load(sr_mesh *mesh, sr_texture *texture, const char *path, unsigned seconds, sr_error *err)
{
    return sr_assimp_load_report(mesh, texture, path, seconds, NULL, err);
}
