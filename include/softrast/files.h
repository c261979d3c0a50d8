/* softrast/files.h — meshes and textures from files, images to files.
 *
 *     #include "softrast/files.h"   // cc … $(pkg-config --cflags --libs softrast-files)
 *
 *     sr_mesh mesh = { 0 };
 *     sr_error err;
 *     if (!sr_obj_load(&mesh, "model.obj", &err))
 *         fprintf(stderr, "softrast: error: %s\n", err.message);
 *     …draw (softrast/softrast.h)…
 *     sr_image_write_png("out.png", fb.color, fb.width, fb.height, &err);
 *     sr_mesh_free(&mesh);
 *
 * The library softrast-files, on the core, libpng (PNG read and write),
 * SDL2_image (the other texture formats: JPEG, TGA, BMP, …) and Assimp
 * (mesh formats other than OBJ). Every function returns false with one
 * line in err ("FILE: what", or "FILE:LINE: what" for a parse error) and
 * never crashes on bad input.
 */
#ifndef SOFTRAST_FILES_H
#define SOFTRAST_FILES_H

#include <stdbool.h>
#include <stdint.h>

#include "softrast.h"

/* ---- meshes --------------------------------------------------------------
 *
 * sr_mesh_load opens any mesh file: `.obj` through softrast's own loader
 * (below), every other format Assimp reads (glTF 2.0 .gltf/.glb, PLY, STL,
 * FBX, COLLADA, 3DS, …) through Assimp. The scene is flattened into world
 * space (node transforms applied, instanced meshes repeated), triangulated,
 * and given smooth normals where it has none; it is right-handed y-up like
 * OBJ and flipped the same way (z negated, winding reversed). Triangle ids
 * count the meshes in file order, then their faces in order, and
 * mesh->parts gives each mesh's run of ids and its material. The file's
 * materials are mesh->materials (at least one for an Assimp format): the
 * colour factor (glTF's baseColorFactor, else the diffuse colour), glTF's
 * alphaMode and alphaCutoff, and the base-colour or diffuse texture. Of
 * the textures a file embeds (.glb, FBX) one at most is decoded into
 * *texture: that of the first mesh with triangles whose material has a
 * texture, when it is embedded (texture may be NULL to skip it, and is left
 * empty otherwise); its materials point at *texture (keep it where it is
 * while the mesh is drawn), and a material with another embedded texture is
 * drawn in its colour. A texture beside the file is the material's
 * texture_path (found as for an OBJ's map_Kd, below), which
 * sr_material_textures_load loads, and mesh->texture_path names the first
 * of them. Morph targets take their default weights and a skinned mesh is
 * posed by its skeleton as the node tree holds it; points and lines of a
 * file with triangles, animation, lights and cameras are ignored (a file of
 * vertices alone keeps them as points). A mesh that a mirroring node
 * transform places (negative determinant) has its winding reversed, so its
 * outward faces stay front faces. A file over SR_MAX_MESH_VERTICES vertices,
 * SR_MAX_MESH_TRIANGLES triangles or SR_MAX_MESH_MATERIALS materials is
 * refused before anything is allocated for it. Errors: false with "FILE:
 * reason" (Assimp's reason for its formats); the mesh is left zeroed. */
#define SR_MAX_MESH_VERTICES (1u << 28)
#define SR_MAX_MESH_TRIANGLES (1u << 28)
#define SR_MAX_MESH_MATERIALS (1u << 16)
SR_API bool sr_mesh_load(sr_mesh *mesh, sr_texture *texture, const char *path, sr_error *err);

/* ---- Wavefront OBJ ---------------------------------------------------------
 *
 * Reads `v` (optionally with r g b, or with a w that is ignored), `vt` (u v,
 * an optional w ignored), `vn`, `f` in the forms v, v/vt, v//vn and v/vt/vn
 * (mixed freely) with positive or negative (relative) indices, polygons,
 * comments (whole-line and trailing), blank lines and LF, CRLF or CR line ends;
 * `mtllib` + `usemtl` give the materials (`Kd`, `map_Kd`), and `o` / `g`
 * start groups. Runs of faces of one group and one material are the
 * mesh's parts, each naming its material in mesh->materials (each library
 * material a face uses, in order of first use: its `map_Kd` as
 * texture_path over a white base colour, else its `Kd`; faces without
 * one share a default, gray 0.8, white over vertex colours). Without a
 * library material there are no materials (groups still make parts), and
 * a single run is no part (part_count 0). Other statements (s, l, p, …)
 * are ignored. OBJ is right-handed: the
 * loader negates z (of positions and normals) and reverses each face's
 * winding, so outward faces are front faces (clockwise on screen) in
 * softrast's left-handed convention. A face c0 … c(n-1) becomes triangles
 * (c0, ck, c(k+1)), k = 1 … n-2, written as (c0, c(k+1), ck); triangle ids
 * count them in file order.
 *
 * The mesh: a TriangleList in which each distinct v/vt/vn combination used by
 * a face becomes one vertex, numbered in order of first use. A file without
 * faces is a point cloud: every `v` a vertex, in file order, with its colour,
 * no indices, and normals only when it has one `vn` a `v` (vn i is v i's);
 * draw it as points (SR_POINT_LIST over its vertices), and in a shading
 * that reads normals only once it has them (sr_mesh_compute_normals gives
 * a cloud without 0). Otherwise normals / uvs exist iff some face corner
 * gives vn / vt; corners without one get (0,0,0) / (0,0).
 * colors exist iff some `v` has r g b; the other vertices are white.
 * texture_path is the first `map_Kd` of a material that a face is drawn
 * with, resolved against the .mtl's folder (the .mtl against the OBJ's),
 * with Windows separators ('\') read as '/'; when no file is there, the
 * first file found beside the .mtl by the name's last component in any
 * case, as written or ending in .png .jpg .jpeg .tga or .bmp, then the same
 * in a "textures" folder beside it ("D:\art\Wood.JPG" finds wood.png);
 * when none is found, the path as written, which sr_texture_load then
 * reports missing.
 * Coordinates are read in double. A mesh far from the world origin — the
 * centre of its bounds more than 16 times their largest side away — is
 * stored relative to that centre (computed in double), which becomes
 * mesh->origin; any other mesh keeps its positions as written and origin
 * zero (docs/precision.md).
 *
 * Errors: false with "FILE:LINE: what" in err (or "FILE: what" when the file
 * cannot be read, or is not a regular file: a FIFO, a device or a directory
 * is refused without being read); the mesh is left zeroed, never half-filled, whatever it
 * held before (it is not freed: pass an empty or freed mesh). Errors include
 * a malformed or non-finite number, a wrong count of numbers, an index that
 * is 0 or outside the elements read so far, a malformed face corner, a face
 * of fewer than 3 vertices, a line over 64 KiB or with a NUL byte and a
 * missing material library. A `usemtl` of a material no library defines is
 * not an error: its faces are drawn with the default material (no
 * texture), as other viewers draw them, and the softrast program warns.
 * Loading is one pass, O(file size). */
SR_API bool sr_obj_load(sr_mesh *mesh, const char *path, sr_error *err);

/* ---- textures ----------------------------------------------------------- */

/* At most this many texels (8192 x 8192; 256 MiB as 0x00RRGGBB) in a loaded
 * texture: a PNG's, a JPEG's or a TGA's size is read from its header and
 * checked before anything is allocated, so a small file claiming a huge
 * image costs nothing. */
#define SR_MAX_TEXTURE_TEXELS (1ul << 26)

/* A PNG (read by libpng) or any other image SDL2_image reads (JPEG, TGA,
 * BMP, …), as 0x00RRGGBB texels, row 0 at the top; an image with an alpha
 * channel as 0xAARRGGBB with tex->alpha set (colours unblended), for MASK
 * materials; false for a missing
 * file or one that is not a regular file, anything that is not a readable
 * image, a side over
 * SR_MAX_TEXTURE_SIDE or more than SR_MAX_TEXTURE_TEXELS texels. Free with
 * sr_texture_free. */
SR_API bool sr_texture_load(sr_texture *tex, const char *path, sr_error *err);
SR_API void sr_texture_free(sr_texture *tex);

/* The textures of a mesh's materials, as the softrast program and Python's
 * Mesh.load load them: sr_material_textures_load loads the file of every
 * material with a texture_path, each distinct path once, into out (emptied
 * first) and points those materials at it (sr_material.texture). A file
 * that does not load is dropped from its materials (their texture_path
 * freed and NULL, so a draw does not give them desc's texture, which an
 * embedded one may be: they draw their base colour), and warn, if not
 * NULL, is called once for it with sr_texture_load's line. Keep out, and
 * the embedded texture sr_mesh_load gave, while the mesh is drawn;
 * sr_material_textures_free frees the textures (free the mesh too, or
 * load again) and empties out. False only when out of memory (out is
 * left empty). */
typedef struct sr_material_textures {
    sr_texture *textures;
    uint32_t count;
} sr_material_textures;
typedef void sr_material_texture_warning(void *context, const sr_error *why);
SR_API bool sr_material_textures_load(sr_mesh *mesh, sr_material_textures *out, sr_material_texture_warning *warn,
                                      void *context, sr_error *err);
SR_API void sr_material_textures_free(sr_material_textures *t);

/* ---- images -------------------------------------------------------------
 *
 * path must be a regular file or not exist yet (a directory, FIFO or device
 * there is refused and left alone). The image is written to a temporary file
 * beside it, renamed into place when complete: a failed write leaves what
 * was at path untouched. An existing file keeps its permissions; a symbolic
 * link at path keeps pointing at the file it names, which is replaced. The
 * path "-" is stdout (flushed, not closed), refused when it is a terminal. */

/* 8-bit RGB PNG of 0x00RRGGBB pixels, row 0 at the top. */
SR_API bool sr_image_write_png(const char *path, const uint32_t *pixels, int width, int height, sr_error *err);
/* The raw depth buffer as PFM: header "Pf\n<W> <H>\n-1\n", then float32
 * little-endian rows from the bottom row up, as the PFM format says. */
SR_API bool sr_image_write_pfm(const char *path, const float *depth, int width, int height, sr_error *err);
/* width x height x channels values (row 0 first, a pixel's channels
 * together) as a NumPy .npy file of shape (height, width), or (height,
 * width, channels) for more than one, dtype '<f4' or '<u4': numpy.load
 * reads it as it is. */
typedef enum sr_npy_type { SR_NPY_FLOAT32 = 0, SR_NPY_UINT32 } sr_npy_type;
SR_API bool sr_image_write_npy(const char *path, const void *values, sr_npy_type type, int width, int height,
                               int channels, sr_error *err);
/* width x height x channels float32 values (row 0 first) as an OpenEXR
 * file, ZIP-compressed scanlines: one channel is "Y" (gray), three are "R",
 * "G", "B". */
SR_API bool sr_image_write_exr(const char *path, const float *values, int width, int height, int channels,
                               sr_error *err);
/* A 16-bit gray PNG of width x height values, row 0 at the top: ids, or
 * depth in millimetres. */
SR_API bool sr_image_write_png16(const char *path, const uint16_t *values, int width, int height, sr_error *err);
/* The depth buffer visualised as by sr_framebuffer_depth_to_gray. */
SR_API bool sr_image_write_depth_png(const char *path, const sr_framebuffer *fb, sr_error *err);

#endif
