/* `softrast truth` end to end: the room from render's camera, against
 * render's ids and depth. */
#include <math.h>

#include "run_helpers.h"
#include "softrast_private.h"
#include "temp_dir.h"

#define SIDE_W 96
#define SIDE_H 54
#define CAMERA "--size 96x54 --eye -8,3,-8 --target 4,1.5,6 --fov 75"

TestSuite(truth_cli, .init = temp_dir_make, .fini = temp_dir_remove);

/* The floats of a SIDE_W x SIDE_H PFM as image.c writes it, row 0 at the
 * top as the PNG's (a PFM's first row is the bottom one). */
static void read_pfm(const char *name, float *out)
{
    char path[512], header[64];
    FILE *f = fopen(temp_path(path, sizeof path, name), "rb");
    cr_assert_not_null(f, "%s missing", name);
    snprintf(header, sizeof header, "Pf\n%d %d\n-1\n", SIDE_W, SIDE_H);
    char got[64] = "";
    cr_assert_eq(fread(got, 1, strlen(header), f), strlen(header));
    cr_assert_str_eq(got, header);
    for (int y = SIDE_H - 1; y >= 0; y--)
        cr_assert_eq(fread(&out[y * SIDE_W], sizeof *out, SIDE_W, f), (size_t)SIDE_W);
    fclose(f);
}

static void read_ids(const char *name, sr_texture *ids)
{
    char path[512];
    sr_error err = { "" };
    cr_assert(sr_texture_load(ids, temp_path(path, sizeof path, name), &err), "%s", err.message);
}

Test(truth_cli, the_room_from_renders_camera_matches_render_up_to_snapping)
{
    char args[2048];
    snprintf(args, sizeof args, "truth assets/room.obj " CAMERA " --out-ids %s/t.png --out-depth %s/t.pfm", temp_dir,
             temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "%s", r.err);
    snprintf(args, sizeof args, "render assets/room.obj " CAMERA " --shade id --out %s/r.png --depth %s/r.pfm",
             temp_dir, temp_dir);
    r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "%s", r.err);
    static float truth_z[SIDE_W * SIDE_H], render_z[SIDE_W * SIDE_H];
    sr_texture truth_ids, render_ids;
    read_pfm("t.pfm", truth_z);
    read_pfm("r.pfm", render_z);
    read_ids("t.png", &truth_ids);
    read_ids("r.png", &render_ids);
    int differ = 0, drawn = 0;
    for (int i = 0; i < SIDE_W * SIDE_H; i++) {
        differ += truth_ids.texels[i] != render_ids.texels[i];
        drawn += truth_ids.texels[i] != 0;
        if (truth_ids.texels[i] == render_ids.texels[i])
            cr_assert_float_eq(truth_z[i], render_z[i], 1e-4, "pixel %d", i);
    }
    cr_assert_eq(drawn, SIDE_W * SIDE_H, "inside the room every pixel sees a wall");
    cr_assert_lt(differ, SIDE_W * SIDE_H / 100, "%d ids differ", differ);
    sr_texture_free(&truth_ids);
    sr_texture_free(&render_ids);
}

Test(truth_cli, an_orthographic_camera_is_refused_in_one_line)
{
    run_result r = run_softrast(temp_dir, "truth assets/room.obj --ortho 4 --out-ids x.png");
    cr_assert_eq(r.status, 1);
    cr_assert_eq(count_lines(r.err), 1, "%s", r.err);
}
