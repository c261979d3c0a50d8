/* softrast.h — a software rasterizer that never breaks.
 *
 * softrast draws indexed triangle meshes into a caller-owned framebuffer on
 * the CPU. Every triangle is clipped in homogeneous clip space against the six
 * planes -w <= x, y <= w, 0 <= z <= w (Sutherland–Hodgman, watertight cut
 * vertices), fanned before the divide, snapped to 1/256 pixel, culled on its
 * exact area, rasterized with 64-bit edge functions and the top-left rule,
 * depth-tested on z_ndc (LESS, cleared to 1) and shaded with perspective-
 * correct varyings. Conventions (left-handed, Direct3D style) are in
 * docs/conventions.md; the stages are one header each:
 *
 *   vertex.h → assemble.h → clip.h → viewport.h → cull.h → raster.h → shade.h
 *
 * and pipeline.h ties them into one call, sr_draw. The caller owns every
 * buffer; functions that can fail on input return false with a one-line
 * sr_error. Non-finite or degenerate geometry is dropped and counted in
 * sr_stats, never drawn and never a crash.
 */
#ifndef SOFTRAST_H
#define SOFTRAST_H

#include "assemble.h"
#include "camera.h"
#include "clip.h"
#include "cull.h"
#include "dmat4.h"
#include "error.h"
#include "framebuffer.h"
#include "image.h"
#include "mesh.h"
#include "obj.h"
#include "pipeline.h"
#include "raster.h"
#include "shade.h"
#include "shapes.h"
#include "texture.h"
#include "types.h"
#include "vertex.h"
#include "viewport.h"

#endif
