/* softrast_private.h — every header of the library, public and private, for
 * the code that lives beside it: the program, the studies, the tests, the
 * fuzzers and the tools. Nothing installed includes it. */
#ifndef SOFTRAST_PRIVATE_H
#define SOFTRAST_PRIVATE_H

#include "softrast/files.h"
#include "softrast/softrast.h"
#include "softrast/study.h"

#include "core/dmat4.h"
#include "core/error.h"
#include "pipeline/02_assemble.h"
#include "pipeline/04_clip/clip.h"
#include "pipeline/07_cull.h"
#include "pipeline/08_raster/raster.h"
#include "pipeline/10_shade.h"
#include "pipeline/08_raster/simd_select.h"
#include "pipeline/stages.h"
#include "pipeline/01_vertex.h"
#include "pipeline/06_viewport.h"
#include "scene/shapes.h"

#endif
