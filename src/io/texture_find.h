/* src/io/texture_find.h — private to src/io: a texture file a model names,
 * found where people expect it. */
#ifndef SOFTRAST_IO_TEXTURE_FIND_H
#define SOFTRAST_IO_TEXTURE_FIND_H

/* The file that `written` (a texture name as the model or its .mtl writes
 * it) refers to, looked for in order:
 *   1. the path as written, resolved against base_file's folder unless it
 *      is absolute (backslashes read as '/'); then its base name in the
 *      folder it names, in any case (a model may name its texture
 *      "../maps/Earth.jpg" where "../maps/earth.jpg" lies);
 *   2. beside base_file, by base name (after the last '/' or '\', so
 *      "D:\projects\tex.jpg" is "tex.jpg"), in any case, first as written,
 *      then with any of the endings .png .jpg .jpeg .tga .bmp;
 *   3. the same in a folder "textures" (any case) beside base_file.
 * A name Assimp makes up for a skin the file does not name
 * ("$texture_dummy.bmp", MD2) is looked for as the model's own stem with an
 * image ending ("sydney.md2": "sydney.bmp"), by steps 2 and 3.
 * A url list X3D names, which Assimp joins as a.png""b.gif, is the first
 * of its names found. Only regular files count. Malloc'd; NULL when none is found (or out of
 * memory). */
char *sr_texture_find(const char *base_file, const char *written);

#endif
