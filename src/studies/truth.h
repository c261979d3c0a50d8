/* truth.h — the truth image: for every pixel centre, the triangle that exact
 * arithmetic says is nearest and its distance, from the same mesh, camera and
 * conventions as sr_draw (pixel centres, the top-left rule, culling by
 * orientation, depth LESS, only the part between the near and far planes).
 *
 * The ray through a pixel centre and the triangles, transformed to view
 * space by P·V·W·T(origin)'s V·W·T(origin) in double, are the inputs. Every
 * predicate on them (a ray against an edge, a triangle's orientation, a hit
 * against the near or far plane, two hits against each other) is decided in
 * double where its error bound allows and in exact expansion arithmetic
 * (truth_exact.h) where it does not. A screen-space grid of 8x8-pixel tiles
 * keeps the triangles each ray meets few. */
#ifndef SOFTRAST_STUDIES_TRUTH_H
#define SOFTRAST_STUDIES_TRUTH_H

#include <stdbool.h>
#include <stdint.h>

#include "softrast_private.h"

/* The perspective projection as the truth reads it: X_ndc = sx·x/z,
 * Y_ndc = sy·y/z, z_ndc = a + b/z. */
typedef struct sr_truth_lens {
    double sx, sy, a, b;
    double near_z, far_z; /* the view z of z_ndc = 0 and 1, nearer first; far_z may be +inf */
} sr_truth_lens;

typedef struct sr_truth_image {
    int width, height;
    uint32_t *ids;      /* triangle slot + 1, as --shade id writes it; 0: none */
    double *distance;   /* view-space z of the nearest hit; +inf: none */
    double *runner_up;  /* view-space z of the next hit behind it (or tied); +inf: none */
    /* The geometry the image was traced on, for truth_outline.h: the
     * desc's mesh (borrowed: it must outlive every use of the image), its
     * vertices in view space (owned) and the lens. */
    const sr_mesh *mesh;
    double (*verts)[3];
    sr_truth_lens lens;
} sr_truth_image;

/* Renders the truth of desc's mesh, world, view, projection (a perspective
 * one), cull and front at width x height; other fields are ignored. Prints a
 * progress line on stderr each second of a run longer than one. */
bool sr_truth_render(const sr_draw_desc *desc, int width, int height, sr_truth_image *out, sr_error *err);

void sr_truth_image_free(sr_truth_image *t);

/* z_ndc of a view-space distance under the perspective projection: a + b/z
 * with the projection's depth model (1 / 0 for +inf: the clear value of
 * standard / reversed z). */
double sr_truth_z_ndc(const mat4 projection, double distance);

#endif
