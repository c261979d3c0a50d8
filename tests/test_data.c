#define _XOPEN_SOURCE 700 /* realpath */
/* view and bench find the default scene wherever they run from: beside the
 * executable (the source tree, or an installed copy's share/softrast), the
 * build's install prefix, then $SOFTRAST_DATA; when they cannot, one error
 * line says where they looked. They used to read assets/room.obj relative to
 * the current directory and worked only from the repository's root. */
#include <criterion/criterion.h>
#include <limits.h>

#include "run_helpers.h"
#include "temp_dir.h"

TestSuite(data, .init = temp_dir_make, .fini = temp_dir_remove);

static char bin[PATH_MAX], script[PATH_MAX];

/* Absolute paths of the program under test and of a flight through the room. */
static void find_bin_and_script(void)
{
    cr_assert_not_null(realpath(softrast_bin(), bin), "no program at %s", softrast_bin());
    cr_assert_not_null(realpath("tests/flights/room_walls.txt", script));
}

/* Runs `cd temp_dir && ENV PROGRAM ARGS`; its stderr into err_text. */
static int run_in_temp_dir(const char *env, const char *program, const char *args, char *err_text, size_t cap)
{
    char cmd[4 * PATH_MAX], err_path[PATH_MAX];
    snprintf(cmd, sizeof cmd, "cd %s && env %s ASAN_OPTIONS=detect_leaks=0 timeout -s KILL 60 %s %s >/dev/null 2>%s",
             temp_dir, env, program, args, temp_path(err_path, sizeof err_path, "err.txt"));
    int raw = system(cmd);
    read_all(err_path, err_text, cap);
    return WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
}

/* view (no MESH, a scripted frame) and bench's fly scene from temp_dir: both
 * succeed, or (needle given) both fail with one error line holding it. */
static void view_and_bench(const char *env, const char *program, const char *needle)
{
    char view[2 * PATH_MAX];
    snprintf(view, sizeof view, "view --no-window --size 64x48 --script %s --frames 1", script);
    const char *runs[] = { view, "bench --scene fly --frames 1" };
    for (int i = 0; i < 2; i++) {
        char err_text[4096];
        int status = run_in_temp_dir(env, program, runs[i], err_text, sizeof err_text);
        if (!needle) {
            cr_expect_eq(status, 0, "`%s` failed: %s", runs[i], err_text);
            continue;
        }
        cr_expect(status != 0 && status < 128, "`%s` exited %d", runs[i], status);
        cr_expect_eq(count_lines(err_text), 1, "stderr was: %s", err_text);
        cr_expect_eq(strncmp(err_text, "softrast: error: ", 17), 0, "stderr was: %s", err_text);
        cr_expect_not_null(strstr(err_text, needle), "'%s' not in: %s", needle, err_text);
    }
}

static void copy(const char *from, const char *to_dir)
{
    char cmd[3 * PATH_MAX];
    snprintf(cmd, sizeof cmd, "mkdir -p %s/%s && cp %s %s/%s", temp_dir, to_dir, from, temp_dir, to_dir);
    cr_assert_eq(system(cmd), 0, "%s", cmd);
}

Test(data, view_and_bench_run_from_another_directory)
{
    find_bin_and_script();
    view_and_bench("", bin, NULL);
}

/* An installed copy's layout: PREFIX/bin/softrast and PREFIX/share/softrast/assets
 * (what make install writes; test-install runs the real one from /). */
Test(data, an_installed_copy_finds_its_share_directory)
{
    find_bin_and_script();
    copy(bin, "prefix/bin");
    copy("assets/room.obj assets/room.mtl assets/room.png", "prefix/share/softrast/assets");
    char program[PATH_MAX];
    view_and_bench("", temp_path(program, sizeof program, "prefix/bin/softrast"), NULL);
}

Test(data, softrast_data_is_searched_and_a_miss_says_where_it_looked)
{
    find_bin_and_script();
    copy(bin, "alone/bin");
    char program[PATH_MAX], env[2 * PATH_MAX], looked[2 * PATH_MAX];
    temp_path(program, sizeof program, "alone/bin/softrast");
    snprintf(looked, sizeof looked, "assets/room.obj: not found in %s/alone, %s, %s/alone/share/softrast", temp_dir,
             temp_dir, temp_dir);
    view_and_bench("-u SOFTRAST_DATA", program, looked);
    copy("assets/room.obj assets/room.mtl assets/room.png", "data/assets");
    snprintf(env, sizeof env, "SOFTRAST_DATA=%s/data", temp_dir);
    view_and_bench(env, program, NULL);
}
