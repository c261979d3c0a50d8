/* softrast — subcommand dispatch. */
#include <stdio.h>
#include <string.h>

#include "app.h"

static const char USAGE[] =
    "usage: softrast <command> [options]\n"
    "\n"
    "commands:\n"
    "  render MESH.obj [options]   draw one image without a window (softrast render --help)\n"
    "  view [MESH.obj] [options]   fly a camera through a mesh in a window (softrast view --help)\n"
    "  bench [options]             time the benchmark scenes (softrast bench --help)\n"
    "  truth MESH [options]        the exactly nearest triangle and z_ndc per pixel (softrast truth --help)\n"
    "  info MESH [--json]          what a mesh file holds: bounds, up axis, parts, textures (softrast info --help)\n"
    "\n"
    "softrast is a software rasterizer: every triangle is clipped in homogeneous clip space,\n"
    "rasterized with exact fixed-point edge functions and depth-tested. See docs/cli.md.";

int main(int argc, char **argv)
{
    if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        puts(USAGE);
        return argc < 2 ? 2 : 0;
    }
    if (strcmp(argv[1], "render") == 0)
        return sr_app_render(argc, argv);
    if (strcmp(argv[1], "view") == 0)
        return sr_app_view(argc, argv);
    if (strcmp(argv[1], "bench") == 0)
        return sr_app_bench(argc, argv);
    if (strcmp(argv[1], "truth") == 0)
        return sr_app_truth(argc, argv);
    if (strcmp(argv[1], "info") == 0)
        return sr_app_info(argc, argv);
    char message[256];
    snprintf(message, sizeof message, "unknown command '%s' (see softrast --help)", argv[1]);
    return sr_app_fail(message);
}
