/* texture_read.h — decoding a texture from an open stream: a file
 * (sr_texture_load), or an image embedded in a mesh file, read through
 * fmemopen (src/io/assimp.c). */
#ifndef SOFTRAST_IO_TEXTURE_READ_H
#define SOFTRAST_IO_TEXTURE_READ_H

#include <stdio.h>

#include "softrast/files.h"

/* Decodes f (PNG through libpng, anything else through SDL_image, whose
 * format hint is name's ending) and closes it; false with "NAME: what" in
 * err, tex then empty. The size limits of sr_texture_load apply. */
bool sr_texture_read(sr_texture *tex, FILE *f, const char *name, sr_error *err);

#endif
