/* fuzz/fuzz_mesh.c — libFuzzer target for meshes through Assimp.
 *
 * Byte 0 picks the format by the file's ending (.ply .stl .gltf .glb .fbx
 * .dae .3ds .off .amf .x3d, the last two read and rewritten by softrast
 * before Assimp, src/io/amf_import.h and x3d_reuse.h); the rest is written as that
 * file in a folder of this process's own. sr_mesh_load runs Assimp in a child process with a 2 s
 * limit, so whatever Assimp does with the bytes — crash, loop, block — the
 * load must end with either a consistent mesh (a TriangleList, indices in
 * range, positions finite, the bounds stored, every optional array present
 * for every vertex) that sr_draw accepts, or one line naming the file and
 * a zeroed mesh.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/mesh_loaders.h"
#include "softrast_private.h"

#include "fuzz_common.h"    /* fail(), CHECK() */
#include "fuzz_materials.h" /* check_materials() */

#define SECONDS 2u
#define DRAW_SIDE 16

static const char *const ENDINGS[] = { "ply", "stl", "gltf", "glb", "fbx", "dae", "3ds", "off", "amf", "x3d" };
#define ENDING_COUNT (sizeof ENDINGS / sizeof *ENDINGS)

static void write_file(const char *path, const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL, "cannot write %s", path);
    CHECK(fwrite(data, 1, size, f) == size && fclose(f) == 0, "cannot write %s", path);
}

static void check_mesh(const sr_mesh *m)
{
    CHECK(m->topology == SR_TRIANGLE_LIST && m->index_count % 3 == 0, "index count %u", m->index_count);
    for (uint32_t i = 0; i < m->index_count; i++)
        CHECK(m->indices[i] < m->vertex_count, "index %u = %u past %u vertices", i, m->indices[i], m->vertex_count);
    for (uint32_t v = 0; v < m->vertex_count; v++)
        for (int k = 0; k < 3; k++)
            CHECK(isfinite(m->positions[v][k]), "position %u is not finite", v);
    CHECK(m->vertex_count == 0 || m->bounded, "bounds not stored");
}

static void check_drawable(const sr_mesh *m)
{
    uint32_t color[DRAW_SIDE * DRAW_SIDE];
    float depth[DRAW_SIDE * DRAW_SIDE];
    sr_framebuffer fb = { .width = DRAW_SIDE, .height = DRAW_SIDE, .color = color, .depth = depth };
    sr_framebuffer_clear(&fb, 0);
    sr_camera cam = sr_camera_default();
    if (m->bounded)
        sr_camera_frame_bounds(&cam, m->bounds_lo, m->bounds_hi, 1.0f);
    sr_draw_desc desc = { .mesh = m, .shade = SR_SHADE_ID, .cull = SR_CULL_NONE };
    sr_camera_view(&cam, desc.view);
    sr_camera_projection(&cam, 1.0f, desc.projection);
    sr_error err = { "" };
    CHECK(sr_draw(&fb, &desc, NULL, &err), "sr_draw refused a loaded mesh: %s", err.message);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    static char dir[64], path[128];
    if (!dir[0]) {
        snprintf(dir, sizeof dir, "/tmp/softrast-fuzz-mesh-%d", (int)getpid());
        mkdir(dir, 0700);
    }
    snprintf(path, sizeof path, "%s/in.%s", dir, ENDINGS[data[0] % ENDING_COUNT]);
    write_file(path, data + 1, size - 1);
    sr_mesh mesh;
    sr_texture texture;
    sr_error err = { "" };
    if (sr_assimp_load(&mesh, &texture, path, SECONDS, &err)) {
        check_mesh(&mesh);
        check_materials(&mesh);
        check_drawable(&mesh);
        CHECK(!texture.texels || (texture.width >= 1 && texture.height >= 1 && texture.width <= SR_MAX_TEXTURE_SIDE &&
                                  texture.height <= SR_MAX_TEXTURE_SIDE),
              "texture %dx%d", texture.width, texture.height);
    } else {
        CHECK(strncmp(err.message, path, strlen(path)) == 0 && !strchr(err.message, '\n'),
              "want one line naming the file: %s", err.message);
        CHECK(mesh.positions == NULL && mesh.indices == NULL && mesh.vertex_count == 0 && !texture.texels,
              "failed load left a mesh or texture");
    }
    sr_mesh_free(&mesh);
    sr_texture_free(&texture);
    unlink(path);
    return 0;
}
