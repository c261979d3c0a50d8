/* 01_vertex_lanes.h — the vertex phase's classifying loop at the AVX2
 * width (01_vertex_avx2.c), which sr_vertex_run_inside (01_vertex.c)
 * calls where the draw's SIMD level has AVX2. Not public API. */
#ifndef SOFTRAST_PIPELINE_VERTEX_LANES_H
#define SOFTRAST_PIPELINE_VERTEX_LANES_H

#include <stdint.h>

#include "03_classify.h"
#include "stages.h"

/* The positions prefetched ahead where the loop also classifies: its
 * longer body let fewer loads of the position stream run ahead, and they
 * waited for memory. The normals gained nothing from it. */
#define SR_VERTEX_POSITIONS_AHEAD 32

/* The clip positions and outcodes (not the varyings) of positions[0 ..
 * count) rounded down to eights (returned), as sr_vertex_run_inside's
 * fours make them, eight at a time in AVX2 lanes (01_vertex_avx2.c): only
 * where the CPU has AVX2. */
uint32_t sr_vertex_eights_inside(const float (*positions)[3], const float clip_from_object[4][4],
                                 const sr_clip_depth *depth, uint32_t count, sr_vertex_out *out,
                                 unsigned char *codes);

#endif
