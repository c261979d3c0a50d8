/* scene_setup.h — what `render` and `view` share: the mesh, camera and
 * shading options, loading the files they name, and building a draw desc. */
#ifndef SOFTRAST_APP_SCENE_SETUP_H
#define SOFTRAST_APP_SCENE_SETUP_H

#include "io/load_report.h"
#include "options.h"
#include "softrast_private.h"

#define SR_MAX_THREAD_OPTION 64

typedef struct sr_scene_setup {
    const char *mesh_path;
    int size[2];
    sr_camera camera;
    double eye[3], target[3]; /* world points of --eye and --target, kept in double */
    bool size_set, eye_set, target_set, near_set, far_set, fov_set, cull_set, shade_set;
    bool look_at_set; /* an option of the look-at camera alone: --up, --ortho, --rotate-y, --up-axis, --reversed-z */
    float rotate_y;
    int up_axis; /* --up-axis: an sr_axis of the file's frame, or -1: what the file says */
    int shade, cull, front, filter, simd; /* sr_shade, sr_cull, sr_front, sr_filter, sr_simd */
    int color_space;                      /* sr_color_space */
    const char *texture_path;
    int threads; /* threads in all for each draw */
} sr_scene_setup;

/* What the files gave, owned here and released by sr_scene_free. */
typedef struct sr_scene {
    sr_mesh mesh;
    sr_load_report report; /* what the loader found besides the mesh */
    mat4 upright;          /* the world turn that shows the file's up axis as +y (upright.h) */
    sr_texture texture;
    sr_material_textures material_textures; /* the mesh's materials' textures, each file once */
    sr_framebuffer fb;
    sr_workspace *workspace; /* reused by every draw of the scene */
} sr_scene;

extern const char *const SR_SHADE_NAMES[];
#define SR_SIMD_CHOICES "auto|scalar|sse2|avx2|avx512"
#define SR_SIMD_HELP "per-pixel loop; every choice draws the same pixels (default auto: the best the CPU has)"
extern const char *const SR_CULL_NAMES[];

void sr_scene_setup_defaults(sr_scene_setup *s);

/* The machine's cores (at least 1, at most SR_MAX_THREAD_OPTION). */
int sr_scene_default_threads(void);

/* Parses a subcommand's command line, argv[2..]: the shared scene options
 * into s, but those named in `skip` (NULL-terminated, or NULL), then `own`
 * (the subcommand's, ended by { 0 }); one positional MESH goes to
 * s->mesh_path. */
bool sr_scene_setup_parse(sr_scene_setup *s, const sr_option *own, const char *const *skip, const char *usage,
                          int argc, char **argv, bool *help, sr_error *err);

/* Loads the mesh, then the texture (or its materials' textures, each file
 * once; --texture instead drops the materials and draws the whole mesh
 * with it) and normals: all of them when `everything`
 * (the viewer switches modes), else only what s->shade reads. Prints the
 * loader's warnings, one line each. Turns the scene upright (--up-axis, else
 * the file's up axis). Creates the framebuffer at s->size. */
bool sr_scene_load(const sr_scene_setup *s, bool everything, sr_scene *scene, sr_error *err);
void sr_scene_free(sr_scene *scene);

/* The loader's warnings on stderr, "softrast: warning: …", one line each. */
void sr_scene_print_warnings(const sr_load_report *r);

/* Places the camera: framed on the upright mesh (from the mesh's origin) when
 * neither --eye nor --target was given; then, unless --near or --far was
 * given, near and far stay 0.1 and 100 if the mesh lies between them and
 * are fitted to its bounding sphere if it does not. Else, for a mesh with an origin (one
 * far from the world origin), the camera's origin goes to the eye (to the
 * target if only that was given) and eye and target are relative to it, so
 * an eye 1e7 away keeps its digits (docs/precision.md); for any other mesh
 * eye and target are floats as given, as the mesh's positions are. */
void sr_scene_frame_camera(sr_scene_setup *s, const sr_scene *scene);

/* The draw desc for s's camera and shading at the framebuffer's size; its
 * world is --rotate-y after the upright turn. */
bool sr_scene_desc(const sr_scene_setup *s, const sr_scene *scene, sr_draw_desc *desc, sr_draw_study *study,
                   sr_error *err);

/* True if the mesh and texture have what `shade` reads (normals, uvs and
 * texels, colors). */
bool sr_shade_supported(const sr_mesh *mesh, const sr_texture *texture, sr_shade shade);

#endif
