#include <math.h>

#include "mesh_origin.h"

void sr_mesh_origin_for_bounds(const double lo[3], const double hi[3], double origin[3])
{
    double centre[3], distance = 0.0, side = 0.0;
    for (int k = 0; k < 3; k++) {
        centre[k] = lo[k] + 0.5 * (hi[k] - lo[k]); /* no overflow for finite bounds */
        distance = fmax(distance, fabs(centre[k]));
        side = fmax(side, hi[k] - lo[k]);
    }
    bool far = distance > SR_MESH_RECENTRE_RATIO * side;
    for (int k = 0; k < 3; k++)
        origin[k] = far ? centre[k] : 0.0;
}
