/* Reading and writing files with softrast: a mesh file in, a PNG out.
 *
 * Build (after `make install`):
 *     cc -std=c11 render_mesh.c $(pkg-config --cflags --libs softrast-files) -o render_mesh
 * Run:  ./render_mesh MESH OUT.png
 * MESH is any format sr_mesh_load opens (OBJ, glTF, PLY, STL, COLLADA, …).
 * It loads the mesh and its materials' textures, as the softrast program
 * does (each material draws its own; a file that is missing is a warning
 * and its materials draw their base colour), frames it with the default
 * camera (near and far fitted to it, so a mesh of any size shows), draws
 * it lambert-shaded at 320×240 and writes the PNG.
 */
#include <stdio.h>
#include <string.h>

#include "softrast/files.h"

static void warn_untextured(void *context, const sr_error *why)
{
    (void)context;
    fprintf(stderr, "render_mesh: warning: %s; its materials are drawn in their base colour\n", why->message);
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: render_mesh MESH OUT.png\n");
        return 2;
    }
    sr_mesh mesh = { 0 };
    sr_texture embedded = { 0 }; /* a texture the file holds: its materials point at it */
    sr_material_textures textures = { 0 };
    sr_framebuffer fb = { 0 };
    sr_error err = { "" };
    bool ok = sr_mesh_load(&mesh, &embedded, argv[1], &err) &&
              (mesh.normals || sr_mesh_compute_normals(&mesh, &err)) &&
              sr_material_textures_load(&mesh, &textures, warn_untextured, NULL, &err) &&
              sr_framebuffer_create(&fb, 320, 240, &err);
    vec3 lo, hi;
    if (ok && !sr_mesh_bounds(&mesh, lo, hi)) {
        snprintf(err.message, sizeof err.message, "%s: no finite vertex to frame", argv[1]);
        ok = false;
    }
    if (ok) {
        sr_camera cam = sr_camera_default();
        memcpy(cam.origin, mesh.origin, sizeof cam.origin);
        sr_camera_frame_bounds(&cam, lo, hi, 320.0f / 240.0f);
        sr_draw_desc desc = { .mesh = &mesh }; /* every material carries its texture */
        sr_camera_view_d(&cam, &desc.view_d);
        sr_camera_projection(&cam, 320.0f / 240.0f, desc.projection);
        sr_stats stats = { 0 };
        sr_framebuffer_clear(&fb, 0x202020);
        ok = sr_draw(&fb, &desc, &stats, &err) && sr_image_write_png(argv[2], fb.color, fb.width, fb.height, &err);
        if (ok)
            printf("%llu triangles, %llu fragments\n", (unsigned long long)stats.triangles,
                   (unsigned long long)stats.fragments);
    }
    if (!ok)
        fprintf(stderr, "render_mesh: %s\n", err.message);
    sr_framebuffer_destroy(&fb);
    sr_material_textures_free(&textures);
    sr_texture_free(&embedded);
    sr_mesh_free(&mesh);
    return ok ? 0 : 1;
}
