/* Reading and writing files with softrast: an OBJ in, a PNG out.
 *
 * Build (after `make install`):
 *     cc -std=c11 render_obj.c $(pkg-config --cflags --libs softrast-files) -o render_obj
 * Run:  ./render_obj MESH.obj out.png
 * It loads the mesh (and its map_Kd texture, if it has one), frames it with
 * the default camera, draws it lambert-shaded at 320×240 and writes the PNG.
 */
#include <stdio.h>

#include "softrast/files.h"

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: render_obj MESH.obj OUT.png\n");
        return 2;
    }
    sr_mesh mesh = { 0 };
    sr_texture texture = { 0 };
    sr_framebuffer fb = { 0 };
    sr_error err = { "" };
    bool ok = sr_obj_load(&mesh, argv[1], &err) && (mesh.normals || sr_mesh_compute_normals(&mesh, &err)) &&
              (!mesh.texture_path || !mesh.uvs || sr_texture_load(&texture, mesh.texture_path, &err)) &&
              sr_framebuffer_create(&fb, 320, 240, &err);
    if (ok) {
        sr_camera cam = sr_camera_default();
        sr_camera_frame_bounds(&cam, mesh.bounds_lo, mesh.bounds_hi, 320.0f / 240.0f);
        sr_draw_desc desc = { .mesh = &mesh, .texture = texture.texels ? &texture : NULL };
        sr_camera_view(&cam, desc.view);
        sr_camera_projection(&cam, 320.0f / 240.0f, desc.projection);
        sr_stats stats = { 0 };
        sr_framebuffer_clear(&fb, 0x202020);
        ok = sr_draw(&fb, &desc, &stats, &err) && sr_image_write_png(argv[2], fb.color, fb.width, fb.height, &err);
        if (ok)
            printf("%llu triangles, %llu fragments\n", (unsigned long long)stats.triangles,
                   (unsigned long long)stats.fragments);
    }
    if (!ok)
        fprintf(stderr, "render_obj: %s\n", err.message);
    sr_framebuffer_destroy(&fb);
    sr_texture_free(&texture);
    sr_mesh_free(&mesh);
    return ok ? 0 : 1;
}
