/* triangle_setup.c — the set-up of one triangle (triangle_setup.h) where
 * it is a call: the binned path's, and the choices that run out of line. */
#include <math.h>

#include "triangle_setup.h"

/* Boxes smaller than this are not worth sr_raster_classify's twelve
 * evaluations: they count as partial. */
#define CLASSIFY_MIN_PIXELS 64

sr_box_cover sr_raster_classify(const sr_tri_setup *s, sr_raster_rect b)
{
    if ((int64_t)(b.x1 - b.x0) * (b.y1 - b.y0) < CLASSIFY_MIN_PIXELS)
        return SR_COVER_PARTIAL;
    int64_t xs[2] = { sr_subpixel_centre(b.x0, s->bits), sr_subpixel_centre(b.x1 - 1, s->bits) };
    int64_t ys[2] = { sr_subpixel_centre(b.y0, s->bits), sr_subpixel_centre(b.y1 - 1, s->bits) };
    bool covered = true;
    for (int k = 0; k < 3; k++) {
        int inside = 0;
        for (int c = 0; c < 4; c++)
            inside += sr_edge_at(&s->e[k], xs[c & 1], ys[c >> 1]) >= s->e[k].bias;
        if (inside == 0)
            return SR_COVER_NONE;
        covered = covered && inside == 4;
    }
    return covered ? SR_COVER_ALL : SR_COVER_PARTIAL;
}

/* A stored set-up serves every material's triangle: in a draw that cuts
 * by texels (its layout has uvs in a mode that reads none), with the
 * varyings. */
bool sr_raster_setup(const sr_screen_vertex *const tri[3], int64_t area2, sr_raster_rect box, int subpixel_bits,
                     sr_shade mode, const sr_shade_context *shade, sr_tri_setup *s)
{
    return sr_setup_triangle(tri, area2, box, subpixel_bits, mode, shade->layout.uv >= 0, shade, false, 0, s);
}

void sr_raster_setup_share(sr_tri_setup *s, sr_raster_rect share, bool covered)
{
    s->box = share;
    s->covered = covered;
    s->tiny = 0; /* the mask is the whole box's */
}

uint64_t sr_raster_tiny_mask(const sr_screen_vertex *const tri[3], int64_t area2, sr_raster_rect box,
                             int subpixel_bits)
{
    const sr_screen_vertex *v[3];
    sr_tri_setup s;
    sr_order_clockwise(tri, area2, v);
    sr_setup_edges(v, box, subpixel_bits, &s);
    return sr_tiny_coverage(&s);
}

/* The dot product of a and b, in double, where the products of floats are
 * exact. */
static double dot_d(const float a[3], const float b[3])
{
    return (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2];
}

/* Normals a and b point the same way: within about 2^-20 radians, which
 * the rounding of a normal/w varying to float (2^-24 relative per
 * component) stays inside, and which no mesh's smooth normals come near (a
 * torus of 10M triangles turns hers by 2^-8 to 2^-9 from vertex to
 * vertex). A subnormal varying (w past about 1e32) rounds more coarsely
 * and may fail the test: that triangle is lit per pixel. */
#define PARALLEL_SIN2 0x1p-40 /* the squared sine of that angle */

static bool normals_parallel(const float a[3], const float b[3])
{
    double c[3] = { (double)a[1] * b[2] - (double)a[2] * b[1], (double)a[2] * b[0] - (double)a[0] * b[2],
                    (double)a[0] * b[1] - (double)a[1] * b[0] };
    double sin2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    return dot_d(a, b) > 0.0 && sin2 <= PARALLEL_SIN2 * dot_d(a, a) * dot_d(b, b);
}

/* Under a perspective camera, only triangles of at least this many pixels
 * are tested for a flat normal. The test is two cross products and six
 * dot products in double, of the order of lighting one pixel (a dot
 * product, a square root, a division); on a dense mesh, whose smooth
 * triangles are a pixel or two and never pass, testing every triangle
 * cost a share of the frame and saved nothing; with this floor it costs
 * nothing visible, while fly's walls still pass. The triangle's area
 * decides, not its box (which a tile clips), so every path and thread
 * count decides alike; a face's triangles under the limit are lit per
 * pixel, which may differ from the once-per-triangle value by one step of
 * a channel (sr_interp). */
#define FLAT_TEST_MIN_PIXELS 32

void sr_interp_choose(sr_tri_setup *s, const sr_screen_vertex *const v[3], int64_t area2, sr_shade mode,
                      const sr_shade_context *shade)
{
    s->interp = SR_INTERP_PERSPECTIVE;
    if (s->varyings == 0)
        return;
    int at = shade->layout.normal;
    bool lambert = mode == SR_SHADE_LAMBERT && at >= 0;
    if (s->diw1 != 0.0f || s->diw2 != 0.0f) {
        int64_t min_area2 = (int64_t)2 * FLAT_TEST_MIN_PIXELS << (2 * s->bits);
        if (!lambert || area2 < min_area2)
            return;
        /* normal/w at each vertex: parallel where the normals are. */
        const float *n0 = v[0]->var_w + at;
        if (normals_parallel(n0, v[1]->var_w + at) && normals_parallel(n0, v[2]->var_w + at)) {
            /* Unit length in double first: normal/w may be too long or
             * short for its squared length in float. */
            double length = sqrt(dot_d(n0, n0));
            float n[3] = { (float)(n0[0] / length), (float)(n0[1] / length), (float)(n0[2] / length) };
            s->interp = SR_INTERP_PERSPECTIVE_FLAT_NORMAL;
            s->lambert = sr_shade_lambert_intensity(shade, n);
        }
        return;
    }
    s->interp = SR_INTERP_AFFINE;
    s->w = 1.0f / s->iw0;
    if (!lambert)
        return;
    float n[3];
    for (int k = 0; k < 3; k++) {
        if (s->dvar1[at + k] != 0.0f || s->dvar2[at + k] != 0.0f)
            return;
        /* var0 + λ1·0 + λ2·0 is var0 up to the sign of a zero, which the
         * intensity does not see. */
        n[k] = s->var0[at + k] * s->w;
    }
    s->interp = SR_INTERP_FLAT_NORMAL;
    s->lambert = sr_shade_lambert_intensity(shade, n);
}
