/* pinhole_triangles_body.h — the body of the resolve's triangle lanes
 * (pinhole_triangles.h), compiled by pinhole_triangles_sse2.c and, with
 * -mavx2 (never -mfma), by pinhole_triangles_avx2.c. The includer defines
 * PINHOLE_TRIANGLES, the name of the function it makes. */
#include <stddef.h>
#include <string.h>

#include "pinhole_triangles.h"
#include "pipeline/stages.h"

typedef double dlanes __attribute__((vector_size(4 * sizeof(double))));
typedef double two_doubles __attribute__((vector_size(2 * sizeof(double))));

_Static_assert(offsetof(resolved_triangle, offset) == offsetof(resolved_triangle, v0) + 13 * sizeof(double),
               "v0 … offset are fourteen doubles in a row: the lanes store each triangle's in four stores");

/* Corner c of the four triangles whose corners are corners[lane[0 .. 4)],
 * by coordinate, from scalar loads: a whole load of a point would read
 * past the array's end at its last vertex. */
static SR_ALWAYS_INLINE void load_corner(const float (*positions)[3], const uint32_t (*corners)[3],
                                         const uint32_t lane[4], int c, dlanes *x, dlanes *y, dlanes *z)
{
    const float *p0 = positions[corners[lane[0]][c]], *p1 = positions[corners[lane[1]][c]],
                *p2 = positions[corners[lane[2]][c]], *p3 = positions[corners[lane[3]][c]];
    *x = (dlanes){ p0[0], p1[0], p2[0], p3[0] };
    *y = (dlanes){ p0[1], p1[1], p2[1], p3[1] };
    *z = (dlanes){ p0[2], p1[2], p2[2], p3[2] };
}

/* to_camera (pinhole_frame.h) in lanes: the same sums in the same order. */
static SR_ALWAYS_INLINE void corner_to_camera(const camera_frame *f, dlanes x, dlanes y, dlanes z, dlanes *cx,
                                              dlanes *cy, dlanes *cz)
{
    x = f->origin01[0] + x;
    y = f->origin01[1] + y;
    z = f->origin2 + z;
    if (f->z_negated)
        z = -z;
    *cx = f->rows01[0][0] * x + f->rows01[1][0] * y + f->rows01[2][0] * z + f->rows01[3][0];
    *cy = f->rows01[0][1] * x + f->rows01[1][1] * y + f->rows01[2][1] * z + f->rows01[3][1];
    *cz = f->row2[0] * x + f->row2[1] * y + f->row2[2] * z + f->row2[3];
}

/* Four lanes' values a, b, c, d turned into each lane's four in a row,
 * row[j] = (a[j], b[j], c[j], d[j]). */
static SR_ALWAYS_INLINE void transpose(dlanes a, dlanes b, dlanes c, dlanes d, dlanes row[4])
{
    dlanes ab_lo = __builtin_shufflevector(a, b, 0, 4, 2, 6), ab_hi = __builtin_shufflevector(a, b, 1, 5, 3, 7);
    dlanes cd_lo = __builtin_shufflevector(c, d, 0, 4, 2, 6), cd_hi = __builtin_shufflevector(c, d, 1, 5, 3, 7);
    row[0] = __builtin_shufflevector(ab_lo, cd_lo, 0, 1, 4, 5);
    row[1] = __builtin_shufflevector(ab_hi, cd_hi, 0, 1, 4, 5);
    row[2] = __builtin_shufflevector(ab_lo, cd_lo, 2, 3, 6, 7);
    row[3] = __builtin_shufflevector(ab_hi, cd_hi, 2, 3, 6, 7);
}

void PINHOLE_TRIANGLES(const camera_frame *f, const float (*positions)[3], const uint32_t (*corners)[3],
                       resolved_triangle *const *to, uint32_t n)
{
    for (uint32_t k = 0; k < n; k += 4) {
        /* A last group of fewer takes its last triangle again: the same
         * values stored twice. */
        uint32_t lane[4];
        for (uint32_t j = 0; j < 4; j++)
            lane[j] = k + j < n ? k + j : n - 1;
        dlanes x, y, z, v0x, v0y, v0z, v1x, v1y, v1z, v2x, v2y, v2z;
        load_corner(positions, corners, lane, 0, &x, &y, &z);
        corner_to_camera(f, x, y, z, &v0x, &v0y, &v0z);
        load_corner(positions, corners, lane, 1, &x, &y, &z);
        corner_to_camera(f, x, y, z, &v1x, &v1y, &v1z);
        load_corner(positions, corners, lane, 2, &x, &y, &z);
        corner_to_camera(f, x, y, z, &v2x, &v2y, &v2z);
        dlanes e1x = v1x - v0x, e1y = v1y - v0y, e1z = v1z - v0z;
        dlanes e2x = v2x - v0x, e2y = v2y - v0y, e2z = v2z - v0z;
        dlanes cx = e1y * e2z - e1z * e2y, cy = e1z * e2x - e1x * e2z, cz = e1x * e2y - e1y * e2x;
        dlanes squared = cx * cx + cy * cy + cz * cz;
        dlanes offset = cx * v0x + cy * v0y + cz * v0z;
        dlanes row[4][4]; /* [quarter][lane]: v0, e1x | e1yz, e2xy | e2z, cross | cross², offset */
        transpose(v0x, v0y, v0z, e1x, row[0]);
        transpose(e1y, e1z, e2x, e2y, row[1]);
        transpose(e2z, cx, cy, cz, row[2]);
        transpose(squared, offset, squared, offset, row[3]);
#pragma GCC unroll 4
        for (int j = 0; j < 4; j++) {
            char *at = (char *)to[lane[j]] + offsetof(resolved_triangle, v0);
            two_doubles last = __builtin_shufflevector(row[3][j], row[3][j], 0, 1);
            memcpy(at, &row[0][j], sizeof row[0][j]);
            memcpy(at + 4 * sizeof(double), &row[1][j], sizeof row[1][j]);
            memcpy(at + 8 * sizeof(double), &row[2][j], sizeof row[2][j]);
            memcpy(at + 12 * sizeof(double), &last, sizeof last);
        }
    }
}
