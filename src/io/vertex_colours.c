/* A file's vertex colours in linear light (vertex_colours.h). */
#include <math.h>
#include <string.h>
#include <strings.h>

#include "vertex_colours.h"

bool sr_vertex_colours_are_display(const char *path)
{
    const char *dot = strrchr(path, '.');
    return !(dot && (strcasecmp(dot, ".gltf") == 0 || strcasecmp(dot, ".glb") == 0));
}

void sr_vertex_colours_to_linear(const vec3 *in, vec3 *out, uint32_t count)
{
    for (uint32_t i = 0; i < count; i++)
        for (int k = 0; k < 3; k++) {
            double v = in[i][k];
            out[i][k] = (float)(v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4));
        }
}
