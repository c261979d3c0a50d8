/* `render --poses transforms.json --out-dir DIR`: a camera dataset's
 * frames rendered as a single image with the same camera would be, shards
 * that add up to one run, and one line for a bad file. */
#include <criterion/criterion.h>
#include <math.h>

#include "cli_error.h"

#define W 48
#define H 36

/* Camera i of a ring of n around the torus, 3 out and 1.5 up, looking at
 * its centre: its eye and its right, up and forward axes. */
static void ring_camera(int i, int n, double eye[3], double r[3], double u[3], double f[3])
{
    double a = 2 * 3.14159265358979 * i / n, len = sqrt(9.0 + 1.5 * 1.5);
    eye[0] = 3 * sin(a), eye[1] = 1.5, eye[2] = 3 * cos(a);
    for (int k = 0; k < 3; k++)
        f[k] = -eye[k] / len;
    double rl = sqrt(f[2] * f[2] + f[0] * f[0]);
    r[0] = -f[2] / rl, r[1] = 0, r[2] = f[0] / rl; /* f x (0, 1, 0), unit */
    u[0] = r[1] * f[2] - r[2] * f[1], u[1] = r[2] * f[0] - r[0] * f[2], u[2] = r[0] * f[1] - r[1] * f[0];
}

/* The ring as a transforms.json: camera-to-world with OpenGL's axes (x
 * right, y up, z backward); cx, cy from the top-left pixel's corner. */
static void write_ring(const char *name, int n)
{
    char text[1 << 16];
    int at = snprintf(text, sizeof text, "{\"fl_x\": 40, \"fl_y\": 44, \"cx\": 24.25, \"cy\": 17.75, \"w\": %d, \"h\": %d,"
                                         " \"frames\": [", W, H);
    for (int i = 0; i < n; i++) {
        double eye[3], r[3], u[3], f[3];
        ring_camera(i, n, eye, r, u, f);
        at += snprintf(text + at, sizeof text - (size_t)at,
                       "%s{\"transform_matrix\": [[%.17g, %.17g, %.17g, %.17g], [%.17g, %.17g, %.17g, %.17g], "
                       "[%.17g, %.17g, %.17g, %.17g], [0, 0, 0, 1]]}",
                       i ? ", " : "", r[0], u[0], -f[0], eye[0], r[1], u[1], -f[1], eye[1], r[2], u[2], -f[2], eye[2]);
    }
    snprintf(text + at, sizeof text - (size_t)at, "]}\n");
    write_text(temp_dir, name, text);
}

static void make_dir_with_ring(void)
{
    temp_dir_make();
    write_ring("ring.json", 7);
}

TestSuite(dataset, .init = make_dir_with_ring, .fini = temp_dir_remove);

/* The program's absolute path, for commands run in temp_dir. */
static const char *absolute_bin(char *buf, size_t cap)
{
    const char *bin = softrast_bin();
    char root[1024];
    cr_assert_not_null(getcwd(root, sizeof root));
    snprintf(buf, cap, bin[0] == '/' ? "%.0s%s" : "%s/%s", root, bin);
    return buf;
}

static void run_ok(const char *cmd)
{
    char full[9000];
    snprintf(full, sizeof full, "cd %s && %s >out.txt 2>err.txt", temp_dir, cmd);
    int status = system(full);
    char err_text[2048];
    char path[512];
    snprintf(path, sizeof path, "%s/err.txt", temp_dir);
    read_all(path, err_text, sizeof err_text);
    cr_assert_eq(status, 0, "`%s` failed: %s", cmd, err_text);
}

/* Frame 3 of the dataset is the single image of its camera: the dataset's
 * c2w with OpenGL's y and z turned to OpenCV's, cx and cy half a pixel
 * less (from the corner to the first pixel's centre). Byte for byte. */
Test(dataset, a_frame_is_the_single_image_of_its_camera)
{
    double eye[3], r[3], u[3], f[3];
    ring_camera(3, 7, eye, r, u, f);
    char cmd[8192], root[1024], bin[1200];
    cr_assert_not_null(getcwd(root, sizeof root));
    absolute_bin(bin, sizeof bin);
    snprintf(cmd, sizeof cmd,
             "%s render %s/assets/torus.obj --poses ring.json --out-dir ds --out rgb.png --view-depth d.npy "
             "--face-ids f.npy && "
             "%s render %s/assets/torus.obj --size %dx%d --intrinsics 40,44,23.75,17.25 --pose-c2w "
             "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,0,0,0,1 "
             "--out one.png --view-depth one.npy --face-ids one_f.npy && "
             "cmp ds/rgb/frame_00003.png one.png && cmp ds/d/frame_00003.npy one.npy && "
             "cmp ds/f/frame_00003.npy one_f.npy && ! cmp -s ds/d/frame_00002.npy one.npy",
             bin, root, bin, root, W, H, r[0], -u[0], f[0], eye[0], r[1], -u[1], f[1], eye[1],
             r[2], -u[2], f[2], eye[2]);
    run_ok(cmd);
}

/* Three shards through GNU parallel write the files of one run, and every
 * shard the same transforms.json, which names every frame's files. */
Test(dataset, three_shards_through_parallel_equal_one_run)
{
    cr_assert_eq(system("command -v parallel >/dev/null"), 0,
                 "GNU parallel is missing (tools/deps.sh installs the Debian package parallel)");
    char cmd[8192], root[1024], bin[1200];
    cr_assert_not_null(getcwd(root, sizeof root));
    absolute_bin(bin, sizeof bin);
    const char *outputs = "--out rgb.png --view-depth depth.npy --range range.pfm --part-ids parts.png --normals n.npy";
    snprintf(cmd, sizeof cmd,
             "R='%s render %s/assets/torus.obj --poses ring.json --quiet %s' && $R --out-dir one && "
             "echo 0:3 3:5 5:7 | tr ' ' '\\n' | parallel -k --halt now,fail=1 \"$R --out-dir shards --frame-range {}\" && "
             "diff -r one shards && test $(ls one/depth | wc -l) -eq 7 && "
             "test $(grep -c '\"depth_file_path\":' one/transforms.json) -eq 7 && "
             "grep -q '\"normals_file_path\":.*\"n/frame_00006.npy\"' one/transforms.json",
             bin, root, outputs);
    run_ok(cmd);
}

Test(dataset, bad_datasets_get_one_line)
{
    write_text(temp_dir, "broken.json", "{\"frames\": [ {\"transform_matrix\": ");
    write_text(temp_dir, "nothing.json", "{\"w\": 10, \"h\": 10, \"fl_x\": 10}");
    write_text(temp_dir, "no_focal.json", "{\"w\": 10, \"h\": 10, \"frames\": [{\"transform_matrix\": "
                                          "[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}]}");
    write_text(temp_dir, "short.json", "{\"w\": 10, \"h\": 10, \"fl_x\": 10, \"frames\": [{\"transform_matrix\": "
                                       "[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}, {\"transform_matrix\": [[1,0,0]]}]}");
    write_text(temp_dir, "scaled.json", "{\"w\": 10, \"h\": 10, \"fl_x\": 10, \"frames\": [{\"transform_matrix\": "
                                        "[[2,0,0,0],[0,2,0,0],[0,0,2,0],[0,0,0,1]]}]}");
    write_text(temp_dir, "tri.obj", "v -1 0.2 0\nv 1 0.2 0\nv 0 1 0\nf 1 2 3\n");
    assert_one_error("render %s/tri.obj --poses %s/broken.json --out-dir d --out c.png", "not JSON (at byte");
    assert_one_error("render %s/tri.obj --poses %s/nothing.json --out-dir d --out c.png", "\"frames\" array");
    assert_one_error("render %s/tri.obj --poses %s/no_focal.json --out-dir d --out c.png", "frame 0: needs fl_x");
    assert_one_error("render %s/tri.obj --poses %s/short.json --out-dir d --out c.png", "frame 1: transform_matrix");
    assert_one_error("render %s/tri.obj --poses %s/scaled.json --out-dir d --out c.png", "frame 0: transform_matrix");
    assert_one_error("render %s/tri.obj --poses %s/ring.json --out-dir d --size 10x10 --out c.png", "not 10x10");
    assert_one_error("render %s/tri.obj --poses %s/ring.json --out-dir d --frame-range 5:9 --out c.png",
                     "ends past the 7 frames");
    assert_one_error("render %s/tri.obj --poses %s/ring.json --out-dir d --out x/c.png", "without a folder");
    assert_one_error("render %s/tri.obj --poses %s/ring.json --out c.png", "--out-dir");
    assert_one_error("render %s/tri.obj --poses %s/ring.json --out-dir d --depth c.pfm", "single image");
    assert_one_error("render %s/tri.obj --poses %s/ring.json --out-dir d --eye 1,2,3", "look-at");
}
