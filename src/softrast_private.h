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
#include "pipeline/assemble.h"
#include "pipeline/clip.h"
#include "pipeline/cull.h"
#include "pipeline/raster.h"
#include "pipeline/shade.h"
#include "pipeline/simd_select.h"
#include "pipeline/stages.h"
#include "pipeline/vertex.h"
#include "pipeline/viewport.h"
#include "scene/shapes.h"

#endif
