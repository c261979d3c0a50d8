/* Scripted flights of `softrast view`: through walls and pillars, with stiff
 * planes, inside a closed mesh. Every frame must draw (clean under the
 * sanitisers when the sanitised binary runs), write only finite depths in
 * [0, 1], and equal pixel for pixel what `softrast render` draws from the
 * same camera. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>

#include "run_helpers.h"
#include "temp_dir.h"

#define SIZE "96x54"
#define MAX_FRAMES 16

TestSuite(flights, .init = temp_dir_make, .fini = temp_dir_remove, .timeout = 120);

typedef struct pfm {
    int width, height;
    float data[96 * 54];
} pfm;

static void read_pfm(const char *path, pfm *p)
{
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "no %s", path);
    float scale;
    cr_assert_eq(fscanf(f, "Pf %d %d %f", &p->width, &p->height, &scale), 3);
    fgetc(f);
    cr_assert_eq(p->width * p->height, 96 * 54);
    cr_assert_eq(fread(p->data, sizeof(float), 96 * 54, f), (size_t)(96 * 54));
    fclose(f);
}

static bool files_equal(const char *a, const char *b)
{
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "cmp -s %s %s", a, b);
    return system(cmd) == 0;
}

/* Flies `script` over `mesh`, then checks each frame as the file comment says.
 * Returns the number of frames. */
static int fly_and_check(const char *mesh, const char *script, const char *shared, const char *view_only,
                         const char *env)
{
    char args[1024];
    snprintf(args, sizeof args, "view %s --size " SIZE " %s %s --script %s --shots %s", mesh, shared, view_only,
             script, temp_dir);
    run_result r = run_softrast_env(temp_dir, env, args);
    cr_assert_eq(r.status, 0, "flight %s failed: %s", script, r.err);
    int frames = 0;
    for (char *line = strtok(r.out, "\n"); line; line = strtok(NULL, "\n"), frames++) {
        int frame;
        char camera[512];
        cr_assert_eq(sscanf(line, "frame %d: %511[^\n]", &frame, camera), 2, "bad line: %s", line);
        char shot[256], render[1400], png[256], depth[256];
        snprintf(shot, sizeof shot, "%s/frame-%04d", temp_dir, frame);
        snprintf(png, sizeof png, "%s/render.png", temp_dir);
        snprintf(depth, sizeof depth, "%s/render.pfm", temp_dir);
        snprintf(render, sizeof render, "render %s --size " SIZE " %s %s --out %s --depth %s", mesh, shared, camera,
                 png, depth);
        run_result rr = run_softrast(temp_dir, render);
        cr_assert_eq(rr.status, 0, "render failed: %s", rr.err);
        char shot_png[300], shot_pfm[300];
        snprintf(shot_png, sizeof shot_png, "%s.png", shot);
        snprintf(shot_pfm, sizeof shot_pfm, "%s.pfm", shot);
        cr_assert(files_equal(png, shot_png), "frame %d of %s differs from render %s", frame, script, camera);
        cr_assert(files_equal(depth, shot_pfm), "frame %d depth of %s differs from render", frame, script);
        pfm p;
        read_pfm(shot_pfm, &p);
        for (int i = 0; i < p.width * p.height; i++)
            cr_assert(isfinite(p.data[i]) && p.data[i] >= 0.0f && p.data[i] <= 1.0f,
                      "frame %d pixel %d depth %g", frame, i, p.data[i]);
    }
    return frames;
}

Test(flights, through_walls_and_pillars_of_the_room)
{
    cr_assert_eq(fly_and_check("assets/room.obj", "tests/flights/room_walls.txt", "", "--no-window", ""), 10);
}

Test(flights, stiff_near_and_far_planes_in_the_room)
{
    cr_assert_eq(fly_and_check("assets/room.obj", "tests/flights/room_stiff.txt", "", "--no-window", ""), 6);
}

/* "inf" as far used to be "expected 12 finite numbers", though render takes
 * --far inf; each frame still equals render's with the camera it prints. */
Test(flights, infinite_far_plane_as_render_takes_it)
{
    cr_assert_eq(fly_and_check("assets/room.obj", "tests/flights/room_infinite_far.txt", "", "--no-window --frames 5",
                               ""),
                 5);
}

Test(flights, interpolated_frames_between_keys)
{
    cr_assert_eq(fly_and_check("assets/room.obj", "tests/flights/room_walls.txt", "", "--no-window --frames 16", ""),
                 16);
}

Test(flights, inside_a_closed_mesh_every_pixel_is_covered)
{
    cr_assert_eq(fly_and_check("assets/sphere.obj", "tests/flights/inside_sphere.txt", "--cull none", "--no-window", ""),
                 6);
    for (int frame = 0; frame < 3; frame++) {
        char path[256];
        pfm p;
        snprintf(path, sizeof path, "%s/frame-%04d.pfm", temp_dir, frame);
        read_pfm(path, &p);
        for (int i = 0; i < p.width * p.height; i++)
            cr_assert_lt(p.data[i], 1.0f, "frame %d: pixel %d inside the sphere is uncovered", frame, i);
    }
}

/* SDL's video drivers (dlopen'ed X11 and GL libraries) leave allocations
 * behind at exit that LeakSanitizer reports from modules it can no longer
 * name, so runs that open a window skip the leak check; the same code paths
 * minus the window run leak-checked in the flights above. */
#define WINDOW_ENV "ASAN_OPTIONS=detect_leaks=0"

/* The window path (SDL's offscreen video driver, no display needed) saves
 * the same frames as the windowless one. */
Test(flights, offscreen_window_saves_the_same_frames)
{
    fly_and_check("assets/room.obj", "tests/flights/room_walls.txt", "", "--frames 3",
                  WINDOW_ENV " SDL_VIDEODRIVER=offscreen");
    char keep[128], cmd[512];
    snprintf(keep, sizeof keep, "%s/windowed", temp_dir);
    snprintf(cmd, sizeof cmd, "mkdir %s && mv %s/frame-* %s", keep, temp_dir, keep);
    cr_assert_eq(system(cmd), 0);
    fly_and_check("assets/room.obj", "tests/flights/room_walls.txt", "", "--frames 3 --no-window", "");
    for (int frame = 0; frame < 3; frame++) {
        char a[256], b[256];
        snprintf(a, sizeof a, "%s/frame-%04d.png", temp_dir, frame);
        snprintf(b, sizeof b, "%s/frame-%04d.png", keep, frame);
        cr_assert(files_equal(a, b), "frame %d differs between window and no window", frame);
    }
}

/* A real X window under Xvfb, read back as a screenshot: the same pixels as
 * the render of that camera. */
Test(flights, xvfb_window_screenshot_equals_the_render)
{
    cr_assert_eq(system("command -v xvfb-run >/dev/null"), 0, "xvfb-run is missing (tools/deps.sh installs xvfb)");
    char cmd[1024];
    snprintf(cmd, sizeof cmd,
             WINDOW_ENV " xvfb-run -a -s '-screen 0 640x480x24' %s view assets/room.obj --size " SIZE
             " --script tests/flights/room_walls.txt --frames 2 --shots %s --grab %s >/dev/null 2>%s/xvfb.err",
             softrast_bin(), temp_dir, temp_dir, temp_dir);
    cr_assert_eq(system(cmd), 0, "xvfb-run failed (see %s/xvfb.err)", temp_dir);
    for (int frame = 0; frame < 2; frame++) {
        char shot[256], grab[256];
        snprintf(shot, sizeof shot, "%s/frame-%04d.png", temp_dir, frame);
        snprintf(grab, sizeof grab, "%s/window-%04d.png", temp_dir, frame);
        cr_assert(files_equal(shot, grab), "window screenshot %d differs from the frame", frame);
    }
}

/* A flight rendered in three shards by GNU parallel, with the shell of
 * docs/batch.md (the last shard cut at the flight's end), writes exactly the
 * files of one unsharded run, byte for byte: the ten frames' PNG and PFM,
 * none missing and none extra; with -k it prints the same camera lines too.
 * Anything on stderr (a sanitiser report, a failed job) fails. */
Test(flights, three_shards_through_parallel_equal_one_run)
{
    cr_assert_eq(system("command -v parallel >/dev/null"), 0,
                 "GNU parallel is missing (tools/deps.sh installs the Debian package parallel)");
    char view[512], cmd[2048], err_text[4096], err_path[256];
    snprintf(view, sizeof view,
             "%s view assets/room.obj --size " SIZE " --script tests/flights/room_walls.txt --frames 10 --no-window",
             softrast_bin());
    snprintf(err_path, sizeof err_path, "%s/stderr.txt", temp_dir);
    snprintf(cmd, sizeof cmd,
             "{ D=%s && mkdir $D/one $D/shards && %s --shots $D/one >$D/one.txt && "
             "seq 0 4 9 | parallel -k --halt now,fail=1 '%s --frame-range {}:$(( {} + 4 < 10 ? {} + 4 : 10 )) "
             "--shots '$D/shards >$D/shards.txt && diff -r $D/one $D/shards && cmp $D/one.txt $D/shards.txt && "
             "test $(ls $D/one | wc -l) -eq 20; } 2>%s",
             temp_dir, view, view, err_path);
    int status = system(cmd);
    read_all(err_path, err_text, sizeof err_text);
    cr_assert_eq(status, 0, "the shards differ from one run, or a run failed: %s", err_text);
    cr_assert_str_empty(err_text, "a run wrote on stderr: %s", err_text);
}

/* Frame numbers of a flight past 10000 frames widen to its last frame's
 * digits, so `ls` lists frame-09999 before frame-10000 (with four digits
 * 10000 sorted before 9999); flights up to 10000 frames keep four. */
Test(flights, frame_numbers_widen_to_the_last_frame)
{
    char cmd[2048];
    const char *fly = "view assets/room.obj --size 8x8 --script tests/flights/room_walls.txt --no-window";
    snprintf(cmd, sizeof cmd,
             "D=%s && %s %s --frames 10001 --frame-range 9999:10001 --shots $D >$D/out.txt && "
             "test \"$(cd $D && ls frame-*.png | tr '\\n' ' ')\" = 'frame-09999.png frame-10000.png ' && "
             "grep -q '^frame 09999: ' $D/out.txt && "
             "%s %s --frames 10000 --frame-range 9999:10000 --shots $D >/dev/null && test -f $D/frame-9999.png",
             temp_dir, softrast_bin(), fly, softrast_bin(), fly);
    cr_assert_eq(system(cmd), 0, "%s", cmd);
}

/* --shots into a folder that does not exist yet makes it and writes every
 * frame there; a path that is a file is one error line. */
Test(flights, shots_into_a_missing_folder_make_it)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd,
             "D=%s && %s view assets/room.obj --size " SIZE " --script tests/flights/room_walls.txt --frames 3 "
             "--no-window --shots $D/new >/dev/null 2>$D/err.txt && test $(ls $D/new | wc -l) -eq 6 && "
             "touch $D/file && ! %s view assets/room.obj --size " SIZE " --script tests/flights/room_walls.txt "
             "--frames 1 --no-window --shots $D/file >/dev/null 2>$D/err2.txt && grep -q 'is not a folder' $D/err2.txt",
             temp_dir, softrast_bin(), softrast_bin());
    cr_assert_eq(system(cmd), 0, "the flight into a missing folder failed");
}
