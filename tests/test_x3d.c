/* An X3D file's reused nodes (DEF / USE), which softrast writes out before
 * Assimp 5.2 reads the file (src/io/x3d_reuse.h): each USE drawn under
 * its own parent, reuses of reuses too, a node that holds itself drawn
 * once, and a file whose reuses grow past the bound refused in one line.
 * tests/scenes_manifest.json holds the keyboard of Assimp's own models. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "load_refused.h"
#include "run_helpers.h"
#include "temp_dir.h"

TestSuite(x3d, .init = temp_dir_make, .fini = temp_dir_remove);

/* One triangle (0,0,0) (1,0,0) (0,1,0), DEFined as `name`. */
#define TRIANGLE(name)                                                                                        \
    "<Transform DEF='" name "'><Shape><IndexedFaceSet coordIndex='0 1 2 -1'>"                                 \
    "<Coordinate point='0 0 0 1 0 0 0 1 0'/></IndexedFaceSet></Shape></Transform>\n"
#define X3D(scene) "<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Immersive' version='3.2'><Scene>\n" scene "</Scene></X3D>\n"

/* `softrast info` of the file holding text: its output, which must succeed. */
static run_result info_of(const char *name, const char *text)
{
    write_text(temp_dir, name, text);
    char args[700];
    snprintf(args, sizeof args, "info %s/%s", temp_dir, name);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "%s", r.err);
    return r;
}

static void assert_holds(const run_result *r, const char *line)
{
    cr_assert_not_null(strstr(r->out, line), "'%s' not in: %s", line, r->out);
}

/* Assimp 5.2 alone drew the first reuse and dropped the second. */
Test(x3d, each_use_draws_the_node_under_its_own_parent)
{
    run_result r = info_of("two.x3d", X3D(TRIANGLE("tri") "<Transform translation='5 0 0'><Transform USE='tri'/></Transform>\n"
                                                          "<Transform translation='0 7 0'><Transform USE='tri'/></Transform>\n"));
    assert_holds(&r, "9 vertices, 3 triangles");
    assert_holds(&r, "file's frame 0,0,0 to 6,8,0;");
}

/* A group DEFined of reuses, reused in turn: its reuses go with it. */
Test(x3d, a_reused_group_brings_its_own_reuses)
{
    run_result r = info_of("row.x3d", X3D(TRIANGLE("key") "<Group DEF='row'>"
                                                          "<Transform translation='2 0 0'><Transform USE='key'/></Transform>"
                                                          "<Transform translation='4 0 0'><Transform USE='key'/></Transform>"
                                                          "</Group>\n"
                                                          "<Transform translation='0 10 0'><Group USE='row'/></Transform>\n"));
    assert_holds(&r, "15 vertices, 5 triangles");
    assert_holds(&r, "file's frame 0,0,0 to 5,11,0;");
}

/* A USE inside the node it names would hold itself: it is written as
 * nothing, where Assimp 5.2 crashed on it. */
Test(x3d, a_node_that_holds_itself_is_drawn_once)
{
    run_result r = info_of("self.x3d", X3D("<Transform DEF='tri'><Shape><IndexedFaceSet coordIndex='0 1 2 -1'>"
                                           "<Coordinate point='0 0 0 1 0 0 0 1 0'/></IndexedFaceSet></Shape>"
                                           "<Transform translation='3 0 0'><Transform USE='tri'/></Transform>"
                                           "</Transform>\n"));
    assert_holds(&r, "3 vertices, 1 triangles");
}

/* Thirty groups each of two reuses of the one before: 2^30 triangles'
 * worth of text, stopped at the bound in one line. */
Test(x3d, reuses_that_double_past_the_bound_are_refused)
{
    char text[8192] = "<?xml version='1.0'?>\n<X3D><Scene>\n" TRIANGLE("n0");
    for (int i = 1; i <= 30; i++) {
        char group[128];
        snprintf(group, sizeof group, "<Group DEF='n%d'><Group USE='n%d'/><Group USE='n%d'/></Group>\n", i, i - 1,
                 i - 1);
        strcat(text, group);
    }
    strcat(text, "</Scene></X3D>\n");
    write_text(temp_dir, "doubling.x3d", text);
    assert_load_refused("doubling.x3d", "its reused nodes (USE) written out pass 64 MiB");
}
