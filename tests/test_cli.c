#define _XOPEN_SOURCE 700 /* mknod, S_IFMT */
/* The program's command line: every bad input gets exactly one
 * "softrast: error: ..." line and a non-zero exit that is not a crash. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include "cli_error.h"
#include "softrast/files.h"

/* A fresh directory holding the one-triangle mesh every test draws. */
static void make_dir_with_triangle(void)
{
    temp_dir_make();
    write_text(temp_dir, "tri.obj", "v -1 0.2 0\nv 1 0.2 0\nv 0 1 0\nf 1 2 3\n");
}

TestSuite(cli, .init = make_dir_with_triangle, .fini = temp_dir_remove);

Test(cli, missing_mesh_file_names_the_path)
{
    assert_one_error("render %s/missing.obj", "missing.obj");
}

Test(cli, malformed_obj_gives_file_and_line)
{
    write_text(temp_dir, "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n");
    assert_one_error("render %s/bad.obj", "bad.obj:4:");
}

Test(cli, unknown_option_is_named)
{
    assert_one_error("render %s/tri.obj --no-such-option", "--no-such-option");
}

Test(cli, bad_size_is_refused)
{
    assert_one_error("render %s/tri.obj --size 0x-3", "--size");
    assert_one_error("render %s/tri.obj --size 100000x10", "--size");
    assert_one_error("render %s/tri.obj --size 10x10x10", "--size");
}

Test(cli, non_finite_numbers_are_refused)
{
    assert_one_error("render %s/tri.obj --near nan", "--near");
    assert_one_error("render %s/tri.obj --fov inf", "--fov");
    assert_one_error("render %s/tri.obj --eye 0,0,1e999", "--eye");
}

/* "--eye 1e300,0,0" was "expected three finite numbers", which 1e300 is:
 * the message now gives the range. */
Test(cli, out_of_range_coordinates_name_the_range)
{
    assert_one_error("render %s/tri.obj --eye 1e300,0,0", "three numbers X,Y,Z, each in [-3e+38, 3e+38]");
    assert_one_error("render %s/tri.obj --up 0,-1e39,0", "each in [-3e+38, 3e+38]");
}

Test(cli, absurd_camera_is_refused)
{
    assert_one_error("render %s/tri.obj --near 10 --far 1", "far");
    assert_one_error("render %s/tri.obj --eye 0,0,0 --target 0,0,0", "same point");
    assert_one_error("render %s/tri.obj --fov 180", "--fov");
    assert_one_error("render %s/tri.obj --eye 0,5,0 --target 0,0,0 --up 0,1,0", "parallel");
}

Test(cli, missing_value_is_named)
{
    assert_one_error("render %s/tri.obj --out", "--out");
}

Test(cli, unknown_choice_lists_the_choices)
{
    assert_one_error("render %s/tri.obj --shade shiny", "one of lambert|id|color|normal|texture|depth");
}

Test(cli, unwritable_output_is_an_error)
{
    assert_one_error("render %s/tri.obj --out %s/no/such/temp_dir/a.png", "a.png");
}

Test(cli, missing_texture_is_an_error)
{
    assert_one_error("render %s/tri.obj --shade texture --texture %s/none.png", "none.png");
}

Test(cli, texture_shading_without_uvs_is_an_error)
{
    write_text(temp_dir, "t.png", "not a png");
    assert_one_error("render %s/tri.obj --shade texture --texture %s/t.png", "t.png");
}

/* libpng would print its own line before ours; a corrupt texture is still
 * one error line. */
Test(cli, truncated_png_texture_is_one_error_line)
{
    char cmd[256];
    snprintf(cmd, sizeof cmd, "head -c 60 assets/checker.png > %s/cut.png", temp_dir);
    cr_assert_eq(system(cmd), 0);
    char args[512];
    snprintf(args, sizeof args, "render assets/cube.obj --shade texture --texture %s/cut.png", temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert(r.status != 0 && r.status < 128, "exit %d", r.status);
    cr_assert_eq(count_lines(r.err), 1, "stderr was: %s", r.err);
    cr_assert_eq(strncmp(r.err, "softrast: error: ", 17), 0, "stderr was: %s", r.err);
    cr_assert_not_null(strstr(r.err, "cut.png"), "%s", r.err);
}

Test(cli, unknown_command_is_an_error)
{
    assert_one_error("paint %s", "paint");
}

Test(cli, help_lists_every_render_option)
{
    static const char *const options[] = { "--size", "--eye", "--target", "--up", "--fov", "--near", "--far",
                                           "--ortho", "--rotate-y", "--cull", "--front", "--shade", "--texture",
                                           "--filter", "--out", "--depth", "--depth-png", "--frames",
                                           "--threads", "--stats" };
    run_result r = run_softrast(temp_dir, "render --help");
    cr_assert_eq(r.status, 0);
    for (size_t i = 0; i < sizeof options / sizeof *options; i++)
        cr_assert_not_null(strstr(r.out, options[i]), "render --help lacks %s", options[i]);
}

Test(cli, stats_is_one_json_line_with_the_named_keys)
{
    static const char *const keys[] = { "\"frames\"", "\"ms_median\"", "\"ms_min\"", "\"triangles\": 1,",
                                        "\"rejected\"", "\"clipped\"", "\"culled\"", "\"fragments\"" };
    char args[256];
    snprintf(args, sizeof args, "render %s/tri.obj --size 32x32 --frames 3 --stats", temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    cr_assert_eq(count_lines(r.out), 1, "stdout: %s", r.out);
    cr_assert_eq(r.out[0], '{');
    for (size_t i = 0; i < sizeof keys / sizeof *keys; i++)
        cr_assert_not_null(strstr(r.out, keys[i]), "stats lack %s: %s", keys[i], r.out);
}

static mode_t file_type(const char *name)
{
    char path[512];
    struct stat st;
    cr_assert_eq(stat(temp_path(path, sizeof path, name), &st), 0, "%s is gone", name);
    return st.st_mode & S_IFMT;
}

static void assert_no_temporary_file_left(void)
{
    DIR *d = opendir(temp_dir);
    cr_assert_not_null(d);
    for (struct dirent *e; (e = readdir(d));)
        cr_expect_null(strstr(e->d_name, ".tmp-"), "%s was left behind", e->d_name);
    closedir(d);
}

/* A FIFO, a directory or a device node at an output path is refused at once
 * and survives; a FIFO used to block the write forever and a failed write
 * used to remove() whatever was at the path. */
Test(cli, output_that_is_not_a_regular_file_survives)
{
    char path[512];
    cr_assert_eq(mkfifo(temp_path(path, sizeof path, "fifo.png"), 0666), 0);
    cr_assert_eq(mkdir(temp_path(path, sizeof path, "dir.pfm"), 0777), 0);
    assert_one_error("render %s/tri.obj --out %s/fifo.png", "fifo.png: cannot write: not a regular file (a FIFO)");
    assert_one_error("render %s/tri.obj --depth %s/dir.pfm", "dir.pfm: cannot write: not a regular file (a directory)");
    cr_expect_eq(file_type("fifo.png"), S_IFIFO);
    cr_expect_eq(file_type("dir.pfm"), S_IFDIR);
    if (geteuid() == 0) { /* /dev/full's numbers: every write fails */
        cr_assert_eq(mknod(temp_path(path, sizeof path, "node"), S_IFCHR | 0666, makedev(1, 7)), 0);
        assert_one_error("render %s/tri.obj --depth-png %s/node", "node: cannot write: not a regular file (a character device)");
        cr_expect_eq(file_type("node"), S_IFCHR);
    }
    assert_no_temporary_file_left();
}

/* A FIFO, a device or a directory as the mesh, its material library, the
 * texture or a flight script gets its error at once: a FIFO used to block
 * the open (or the read) forever. */
Test(cli, input_that_is_not_a_regular_file_is_refused_at_once)
{
    static const char *const fifos[] = { "in.obj", "lib.mtl", "tex.png", "fly.txt" };
    char path[512];
    for (size_t i = 0; i < sizeof fifos / sizeof *fifos; i++)
        cr_assert_eq(mkfifo(temp_path(path, sizeof path, fifos[i]), 0666), 0);
    cr_assert_eq(mkdir(temp_path(path, sizeof path, "dir.obj"), 0777), 0);
    write_text(temp_dir, "lib.obj", "mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const char *fifo = "cannot open: not a regular file (a FIFO)";
    assert_one_error("render %s/in.obj", fifo);
    assert_one_error("render %s/lib.obj", "cannot open material library 'lib.mtl': not a regular file (a FIFO)");
    assert_one_error("render assets/cube.obj --texture %s/tex.png", fifo);
    assert_one_error("view %s/tri.obj --no-window --script %s/fly.txt", fifo);
    assert_one_error("render %s/dir.obj", "dir.obj: cannot open: not a regular file (a directory)");
    assert_one_error("render /dev/zero", "/dev/zero: cannot open: not a regular file (a character device)");
}

/* With no display SDL used to fall back to its offscreen driver: the viewer
 * ran for ever with no window. Now it fails at once, naming the ways out. */
Test(cli, view_without_a_display_fails_at_once_naming_the_ways_out)
{
    run_result r = run_softrast_env(temp_dir,
                                    "env -u DISPLAY -u WAYLAND_DISPLAY -u XDG_RUNTIME_DIR -u SDL_VIDEODRIVER "
                                    "ASAN_OPTIONS=detect_leaks=0 timeout -s KILL 2",
                                    "view");
    cr_assert(r.status != 0 && r.status < 128, "exit %d, stderr: %s", r.status, r.err);
    cr_assert_eq(count_lines(r.err), 1, "stderr was: %s", r.err);
    cr_assert_eq(strncmp(r.err, "softrast: error: ", 17), 0, "stderr was: %s", r.err);
    cr_expect_not_null(strstr(r.err, "--no-window"), "%s", r.err);
    cr_expect_not_null(strstr(r.err, "xvfb-run"), "%s", r.err);
}

/* The default camera frames a mesh 1000 units across and 1000 units from
 * the origin; near and far used to stay 0.1 and 100, so every triangle was
 * rejected and the image was black with exit 0. */
/* Renders `obj` (text) with the default camera and `options`, expecting
 * success, something drawn and nothing on stderr (--quiet: no summary line,
 * so any warning would show); returns the run. */
static run_result render_draws_something(const char *obj, const char *options)
{
    write_text(temp_dir, "mesh.obj", obj);
    char args[512];
    snprintf(args, sizeof args, "render %s/mesh.obj --cull none --stats --quiet %s", temp_dir, options);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    cr_expect_eq(r.err[0], '\0', "stderr: %s", r.err);
    cr_expect_not_null(strstr(r.out, "\"nothing_drawn\": null,"), "%s", r.out);
    return r;
}

Test(cli, default_camera_draws_a_big_mesh_far_from_the_origin)
{
    run_result r = render_draws_something("v 500 -500 0\nv 1500 -500 0\nv 1500 500 0\nv 500 500 0\nf 1 2 3 4\n",
                                          "--size 64x64 --shade id");
    cr_expect_not_null(strstr(r.out, "\"rejected\": 0,"), "%s", r.out);
    const char *fragments = strstr(r.out, "\"fragments\": ");
    cr_assert_not_null(fragments, "%s", r.out);
    long drawn = strtol(fragments + strlen("\"fragments\": "), NULL, 10);
    cr_expect_gt(drawn, 64 * 64 / 4, "%ld of %d pixels drawn: %s", drawn, 64 * 64, r.out);
}

/* A tiny mesh seen from an eye the user places: the target is the mesh's
 * centre and near and far are fitted to it, as --help says (the contract's
 * near 0.1 cut it whole). */
Test(cli, eye_without_target_looks_at_the_mesh_with_fitted_planes)
{
    run_result r = render_draws_something("v 0 0 0\nv 0.001 0 0\nv 0 0.001 0\nf 1 2 3\n",
                                          "--size 32x32 --shade id --eye 0.0003,0.0003,-0.01");
    cr_expect_not_null(strstr(r.out, "\"rejected\": 0,"), "%s", r.out);
}

/* A render that draws nothing used to be silent with exit 0; now one
 * warning line says why, with the numbers, and --stats says it too. The
 * far plane is given, so it is not fitted to the mesh. */
Test(cli, nothing_drawn_says_why)
{
    char args[256];
    snprintf(args, sizeof args,
             "render %s/tri.obj --size 32x32 --eye 0,0,-500 --target 0,0,0 --far 100 --stats --quiet", temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    cr_assert_eq(count_lines(r.err), 1, "stderr: %s", r.err);
    const char *start = "softrast: warning: nothing drawn: every triangle lies outside the view volume "
                        "(or is non-finite) (1 triangles: 1 rejected outside (far 1), 0 of them non-finite";
    cr_expect_eq(strncmp(r.err, start, strlen(start)), 0, "stderr: %s", r.err);
    cr_expect_not_null(strstr(r.err, "the eye is at 0,0,-500 looking at 0,0,0 with near 0.1, far 100"), "%s", r.err);
    cr_expect_not_null(strstr(r.out, "\"nothing_drawn\": \"every triangle lies outside the view volume "
                                     "(or is non-finite)\", \"rejected_by_plane\": {\"near\": 0, \"far\": 1, "
                                     "\"left\": 0, \"right\": 0, \"bottom\": 0, \"top\": 0}"),
                       "%s", r.out);
}

/* "--out -" used to write a file named "-"; it is stdout, as users expect. */
Test(cli, out_dash_writes_the_png_to_stdout)
{
    char args[256];
    snprintf(args, sizeof args, "render %s/tri.obj --size 8x4 --out -", temp_dir);
    run_result r = run_softrast(temp_dir, args);
    int left_a_file = access("-", F_OK) == 0;
    remove("-");
    cr_expect_not(left_a_file, "a file named '-' was written");
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    cr_expect_eq(memcmp(r.out, "\x89PNG\r\n\x1a\n", 8), 0, "stdout is no PNG");
}

Test(cli, only_one_output_can_use_stdout)
{
    assert_one_error("render %s/tri.obj --out - --depth -", "only one of");
    assert_one_error("render %s/tri.obj --depth-png - --stats", "only one of");
}

/* "--keys ,,," used to be accepted, pressing nothing. */
Test(cli, empty_key_names_are_refused)
{
    write_text(temp_dir, "fly.txt", "0 0 -3  0 0 0  0 1 0  60 0.1 100\n");
    assert_one_error("view %s/tri.obj --no-window --script %s/fly.txt --keys ,,,", "--keys: an empty key name");
    assert_one_error("view %s/tri.obj --no-window --script %s/fly.txt --keys F2,,L", "--keys: an empty key name");
    assert_one_error("view %s/tri.obj --no-window --script %s/fly.txt --keys F2,", "--keys: an empty key name");
}

/* A shard of a flight is A:B, whole numbers with A < B, and B no more than
 * the flight's frames (--frames, else one per key frame: two here). */
Test(cli, frame_ranges_outside_the_flight_are_refused)
{
    write_text(temp_dir, "fly.txt", "0 0 -3  0 0 0  0 1 0  60 0.1 100\n0 0 -4  0 0 0  0 1 0  60 0.1 100\n");
    const char *bad[] = { "2:1", "1:1", "-1:1", "0:x", "0", "0:1:2", ":1", "0:100001" };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char args[256];
        snprintf(args, sizeof args, "view %%s/tri.obj --no-window --script %%s/fly.txt --frame-range %s", bad[i]);
        assert_one_error(args, "for --frame-range: expected A:B");
    }
    assert_one_error("view %s/tri.obj --no-window --script %s/fly.txt --frame-range 1:3",
                     "--frame-range 1:3 ends past the flight's 2 frames");
    assert_one_error("view %s/tri.obj --no-window --script %s/fly.txt --frames 4 --frame-range 0:5",
                     "--frame-range 0:5 ends past the flight's 4 frames");
    assert_one_error("view %s/tri.obj --frame-range 0:1", "go with --script");
}

/* Vertices at ±2e19: framing squared the bounds' half-diagonal in float
 * ("camera eye, target and up must be finite"), the projection multiplied
 * near by far in float and the normals crossed edges in float, each past
 * float's range. The default camera and shading now draw it. */
Test(cli, default_camera_and_normals_near_float_range)
{
    render_draws_something("v -2e19 -2e19 -2e19\nv 2e19 -2e19 0\nv 0 2e19 2e19\nf 1 2 3\n", "--size 16x16");
}

/* A triangle whose clip coordinates overflow float is not "outside the
 * view": the warning says what it is. */
Test(cli, nothing_drawn_names_non_finite_triangles)
{
    write_text(temp_dir, "wide.obj", "v -3e38 0 5\nv 3e38 0 5\nv 0 3e38 5\nf 1 2 3\n");
    char args[256];
    snprintf(args, sizeof args, "render %s/wide.obj --size 8x8 --eye 0,0,-3 --target 0,0,0 --stats", temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    const char *why = "every triangle has a non-finite position or varying";
    cr_expect_not_null(strstr(r.err, why), "%s", r.err);
    cr_expect_not_null(strstr(r.out, why), "%s", r.out);
}

/* A missing report folder used to fail only after the whole study ran
 * (9 s for --stability); now at once. */
Test(cli, missing_report_dir_fails_before_measuring)
{
    assert_one_error("bench --stability --report-dir %s/none", "none: cannot write the report there");
    assert_one_error("bench --report --report-dir %s/tri.obj", "tri.obj: cannot write the report there: not a directory");
    assert_one_error("bench --cost-model --report-dir %s/none", "none: cannot write the report there");
}

/* A model shared without its textures used to stop the render at the
 * missing map_Kd; now it warns once, naming the file, and draws lit gray.
 * A texture named with --texture must still load. */
Test(cli, missing_or_unreadable_map_kd_warns_and_draws_untextured)
{
    write_text(temp_dir, "m.mtl", "newmtl skin\nmap_Kd gone.png\nnewmtl cloth\nmap_Kd junk.png\n");
    write_text(temp_dir, "junk.png", "not a png at all");
    static const char *const materials[] = { "skin", "cloth" }, *const files[] = { "gone.png", "junk.png" };
    for (int i = 0; i < 2; i++) {
        char obj[256], args[1024], out[256];
        snprintf(obj, sizeof obj, "mtllib m.mtl\nusemtl %s\nv -1 -1 0\nv 1 -1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                 "f 1/1 2/2 3/3\n", materials[i]);
        write_text(temp_dir, "m.obj", obj);
        snprintf(args, sizeof args, "render %s/m.obj --cull none --size 32x32 --stats --quiet --out %s", temp_dir,
                 temp_path(out, sizeof out, "m.png"));
        run_result r = run_softrast(temp_dir, args);
        cr_assert_eq(r.status, 0, "stderr: %s", r.err);
        cr_expect_eq(count_lines(r.err), 1, "stderr: %s", r.err);
        cr_expect_eq(strncmp(r.err, "softrast: warning: ", 19), 0, "stderr: %s", r.err);
        cr_expect_not_null(strstr(r.err, files[i]), "stderr: %s", r.err);
        cr_expect_not_null(strstr(r.err, "untextured"), "stderr: %s", r.err);
        cr_expect_not_null(strstr(r.out, "\"nothing_drawn\": null"), "%s", r.out);
        cr_expect(access(out, F_OK) == 0, "no image written");
        snprintf(args, sizeof args, "render %s/m.obj --texture %s/%s", temp_dir, temp_dir, files[i]);
        assert_one_error(args, files[i]);
    }
}

/* render used to print nothing on success, even when it wrote nothing; now
 * one line on stderr says what it wrote (stdout stays the image's or the
 * stats'), or that nothing was written; --quiet drops it. */
Test(cli, render_says_what_it_wrote_in_one_line)
{
    char args[512], png[256];
    snprintf(args, sizeof args, "render %s/tri.obj --size 32x16 --out %s", temp_dir, temp_path(png, sizeof png, "a.png"));
    run_result r = run_softrast(temp_dir, args);
    char want[512];
    snprintf(want, sizeof want, "softrast: wrote %s (32x16, 1 triangles drawn)\n", png);
    cr_expect_str_eq(r.err, want);
    cr_expect_str_eq(r.out, "");
    snprintf(args, sizeof args, "render %s/tri.obj --size 32x16", temp_dir);
    r = run_softrast(temp_dir, args);
    cr_expect_str_eq(r.err, "softrast: drew 32x16 (1 triangles drawn); nothing written: name a file with --out, "
                            "--depth, --depth-png, --view-depth or --range\n");
    snprintf(args, sizeof args, "render %s/tri.obj --size 32x16 --out -", temp_dir);
    r = run_softrast(temp_dir, args);
    cr_expect_eq(memcmp(r.out, "\x89PNG\r\n", 6), 0, "stdout is not the PNG");
    cr_expect_str_eq(r.err, "softrast: wrote stdout (32x16, 1 triangles drawn)\n");
    snprintf(args, sizeof args, "render %s/tri.obj --size 32x16 --out %s --quiet", temp_dir, png);
    r = run_softrast(temp_dir, args);
    cr_expect_eq(r.status, 0);
    cr_expect_str_eq(r.err, "");
}

/* bench --shade draws every scene in one mode (the "every shading
 * mode"): the fly scene, lambert + texture of its own, runs in id, and a
 * mode it lacks the attributes of is a skipped line, not an error. */
Test(cli, bench_shade_replaces_the_scenes_shading_or_skips)
{
    run_result r = run_softrast_env(temp_dir, "timeout -s KILL 60", "bench --scene fly --frames 1 --shade id");
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    cr_expect_not_null(strstr(r.out, "fly "), "%s", r.out);
    cr_expect_null(strstr(r.out, "skipped"), "%s", r.out);
    r = run_softrast_env(temp_dir, "timeout -s KILL 60", "bench --scene fly --frames 1 --shade color");
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    cr_expect_not_null(strstr(r.out, "fly       skipped: it lacks what --shade color reads"), "%s", r.out);
}

/* render --points draws a PLY point cloud (vertices alone) in its own
 * colors; --lines a mesh's edges, each once. */
Test(cli, points_draw_a_point_cloud_in_its_colors_and_lines_the_edges)
{
    write_text(temp_dir, "cloud.ply",
               "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n"
               "-0.5 0 0 255 0 0\n0.5 0 0 0 255 0\n0 0.5 0 0 0 255\n");
    char args[1024], png[512];
    snprintf(args, sizeof args, "render %s/cloud.ply --points --point-size 3 --size 48x48 --stats --out %s", temp_dir,
             temp_path(png, sizeof png, "cloud.png"));
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_assert_not_null(strstr(r.out, "\"points\": 3, \"lines\": 0}"), "%s", r.out);
    cr_assert_not_null(strstr(r.out, "\"fragments\": 27,"), "%s", r.out);
    sr_texture image = { 0 };
    sr_error err;
    cr_assert(sr_texture_load(&image, png, &err), "%s", err.message);
    int counts[3] = { 0 }, others = 0;
    for (int i = 0; i < image.width * image.height; i++) {
        uint32_t c = image.texels[i] & 0xFFFFFF;
        counts[0] += c == 0xFF0000;
        counts[1] += c == 0x00FF00;
        counts[2] += c == 0x0000FF;
        others += c != 0 && c != 0xFF0000 && c != 0x00FF00 && c != 0x0000FF;
    }
    cr_assert(counts[0] == 9 && counts[1] == 9 && counts[2] == 9 && others == 0, "%d %d %d red green blue, %d others",
              counts[0], counts[1], counts[2], others);
    sr_texture_free(&image);
    /* A cube's 12 edges and 6 face diagonals, each once (its OBJ repeats
     * every corner per face). */
    snprintf(args, sizeof args, "render assets/cube.obj --lines --stats --quiet --size 64x64");
    r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_assert_not_null(strstr(r.out, "\"lines\": 18}"), "%s", r.out);
}

Test(cli, points_and_lines_options_are_checked)
{
    assert_one_error("render %s/tri.obj --points --lines", "--points and --lines");
    assert_one_error("render %s/tri.obj --points --point-size 0.5", "--point-size");
    assert_one_error("render %s/tri.obj --lines --line-width 65", "--line-width");
}
