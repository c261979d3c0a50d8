/* softrast/image.h — writing what a draw produced: PNG and PFM files.
 *
 * PNGs are 8-bit RGB, row 0 at the top (via SDL2_image). The PFM is the raw
 * depth buffer: header "Pf\n<W> <H>\n-1\n", then float32 little-endian rows
 * from the bottom row up, as the PFM format says. Each writer returns false
 * with one line in err when the file cannot be written.
 */
#ifndef SOFTRAST_IMAGE_H
#define SOFTRAST_IMAGE_H

#include <stdbool.h>
#include <stdint.h>

#include "error.h"
#include "framebuffer.h"

bool sr_image_write_png(const char *path, const uint32_t *pixels, int width, int height, sr_error *err);
bool sr_image_write_pfm(const char *path, const float *depth, int width, int height, sr_error *err);
/* The depth buffer visualised as by sr_framebuffer_depth_to_gray. */
bool sr_image_write_depth_png(const char *path, const sr_framebuffer *fb, sr_error *err);

#endif
