/* `render` with a pinhole camera: its bad inputs, and the view depth and
 * range files read back as NumPy and PFM readers read them. */
#include <criterion/criterion.h>
#include <math.h>
#include <openexr.h>
#include <png.h>
#include <stdint.h>

#include "cli_error.h"

/* The CLI suite's triangle in the plane z = 0 of the file, and a camera 4
 * in front of it (at file z = −4, looking along +z, image y down): every
 * pixel it shows is at view depth 4 exactly. */
#define POSE "--pose-w2c 1,0,0,0,0,1,0,-0.5,0,0,1,4,0,0,0,1"
#define IDENTITY "1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1"
#define W 40
#define H 30

static void make_dir_with_triangle(void)
{
    temp_dir_make();
    write_text(temp_dir, "tri.obj", "v -1 0.2 0\nv 1 0.2 0\nv 0 1 0\nf 1 2 3\n");
}

TestSuite(cli_pinhole, .init = make_dir_with_triangle, .fini = temp_dir_remove);

Test(cli_pinhole, bad_poses_intrinsics_and_outputs_get_one_line)
{
    assert_one_error("render %s/tri.obj --pose-w2c 1,0,0", "16 comma-separated numbers");
    assert_one_error("render %s/tri.obj --pose-w2c 2,0,0,0,0,2,0,0,0,0,2,0,0,0,0,1", "not a rigid pose");
    assert_one_error("render %s/tri.obj --pose-c2w 1,0,0,0,0,1,0,0,0,0,-1,0,0,0,0,1", "not a rigid pose");
    assert_one_error("render %s/tri.obj --intrinsics 0,100,20,15 " POSE, "fx and fy");
    assert_one_error("render %s/tri.obj --intrinsics 100,100,20,nan " POSE, "--intrinsics");
    assert_one_error("render %s/tri.obj --eye 0,0,-3 " POSE, "look-at camera");
    assert_one_error("render %s/tri.obj --pose-w2c " IDENTITY " --pose-c2w " IDENTITY, "one pose");
    assert_one_error("render %s/tri.obj --view-depth %s/d.npy", "needs a camera pose");
    assert_one_error("render %s/tri.obj --intrinsics 100,100,20,15", "needs a camera pose");
    assert_one_error("render %s/tri.obj " POSE " --view-depth %s/d.tif", "no writer");
    assert_one_error("render %s/tri.obj --fov 50 --intrinsics 100,100,20,15 " POSE, "give one");
}

/* The 4-byte values of a .npy file of dtype descr and shape (H, W) or, with
 * channels > 1, (H, W, channels), checked header and all. */
static void read_npy_of(const char *path, const char *descr, int channels, void *out)
{
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "%s missing", path);
    unsigned char lead[10];
    cr_assert_eq(fread(lead, 1, 10, f), 10u);
    cr_assert_eq(memcmp(lead, "\x93NUMPY\x01\x00", 8), 0, "not a .npy 1.0 file");
    size_t dict_len = (size_t)lead[8] | (size_t)lead[9] << 8;
    cr_assert_eq((10 + dict_len) % 64, 0u, "the header is not padded to 64 bytes");
    char dict[256] = { 0 };
    cr_assert(dict_len < sizeof dict && fread(dict, 1, dict_len, f) == dict_len);
    char want[96], want_descr[32];
    snprintf(want, sizeof want, channels > 1 ? "'shape': (%d, %d, %d)" : "'shape': (%d, %d)", H, W, channels);
    snprintf(want_descr, sizeof want_descr, "'descr': '%s'", descr);
    cr_assert_not_null(strstr(dict, want_descr), "%s", dict);
    cr_assert_not_null(strstr(dict, "'fortran_order': False"), "%s", dict);
    cr_assert_not_null(strstr(dict, want), "%s", dict);
    cr_assert_eq(dict[dict_len - 1], '\n');
    size_t count = (size_t)(W * H * channels);
    cr_assert_eq(fread(out, 4, count, f), count, "short data");
    cr_assert_eq(fgetc(f), EOF, "data past W x H values");
    fclose(f);
}

static void read_npy(const char *path, float *out)
{
    read_npy_of(path, "<f4", 1, out);
}

/* A PFM's values, its rows (stored bottom up) put top down. */
static void read_pfm(const char *path, float *out)
{
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "%s missing", path);
    int w = 0, h = 0;
    double scale = 0;
    cr_assert_eq(fscanf(f, "Pf\n%d %d\n%lf", &w, &h, &scale), 3);
    cr_assert(w == W && h == H && scale < 0, "header %d %d %g", w, h, scale);
    fgetc(f);
    for (int y = H - 1; y >= 0; y--)
        cr_assert_eq(fread(out + (size_t)y * W, sizeof *out, W, f), (size_t)W);
    fclose(f);
}

Test(cli_pinhole, view_depth_and_range_read_back_with_the_exact_values)
{
    char args[512];
    snprintf(args, sizeof args,
             "render %s/tri.obj --size %dx%d --intrinsics 30,25,19.5,14.5 " POSE
             " --view-depth %s/d.npy --range %s/r.pfm --shade lambert --out %s/c.png",
             temp_dir, W, H, temp_dir, temp_dir, temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    char path[512];
    static float depth[W * H], range[W * H];
    read_npy(temp_path(path, sizeof path, "d.npy"), depth);
    read_pfm(temp_path(path, sizeof path, "r.pfm"), range);
    int drawn = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float d = depth[y * W + x];
            cr_assert(d == 0.0f || d == 4.0f, "(%d, %d): depth %.9g, not 4 or 0", x, y, d);
            if (d == 0.0f) {
                cr_assert_eq(range[y * W + x], 0.0f);
                continue;
            }
            drawn++;
            double u = (x - 19.5) / 30.0, v = (y - 14.5) / 25.0;
            float want = (float)(4.0 * sqrt(u * u + v * v + 1.0));
            cr_assert_eq(range[y * W + x], want, "(%d, %d): range %.9g, want %.9g", x, y, range[y * W + x], want);
        }
    /* 0.8 square units at z = 4, 7.5 by 6.25 px a unit: about 37.5 px */
    cr_assert(drawn > 30 && drawn < 45, "%d pixels drawn", drawn);
}

Test(cli_pinhole, invalid_nan_marks_the_pixels_where_nothing_is_drawn)
{
    char args[512];
    snprintf(args, sizeof args, "render %s/tri.obj --size %dx%d " POSE " --view-depth %s/d.npy --invalid nan",
             temp_dir, W, H, temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    char path[512];
    static float depth[W * H];
    read_npy(temp_path(path, sizeof path, "d.npy"), depth);
    int nan = 0, four = 0;
    for (int i = 0; i < W * H; i++) {
        nan += isnan(depth[i]);
        four += depth[i] == 4.0f;
    }
    cr_assert_eq(nan + four, W * H, "a value neither NaN nor 4");
    cr_assert(nan > 0 && four > 0, "%d NaN, %d at 4", nan, four);
}

/* A 16-bit gray PNG's values, through libpng's simplified reader. */
static void read_png16(const char *path, uint16_t *out)
{
    png_image png = { .version = PNG_IMAGE_VERSION };
    cr_assert(png_image_begin_read_from_file(&png, path), "%s: %s", path, png.message);
    cr_assert(png.width == W && png.height == H, "%ux%u", png.width, png.height);
    png.format = PNG_FORMAT_LINEAR_Y;
    cr_assert(png_image_finish_read(&png, NULL, out, 0, NULL), "%s: %s", path, png.message);
}

/* Face ids as uint32 .npy and part ids as a 16-bit PNG mark the pixels view
 * depth marks, and the normals are the triangle's (its file winding faces
 * +z, as does the camera: 0, 0, 1). */
Test(cli_pinhole, ids_and_normals_read_back_beside_view_depth)
{
    char args[768];
    snprintf(args, sizeof args,
             "render %s/tri.obj --size %dx%d " POSE " --view-depth %s/d.npy --face-ids %s/f.npy --part-ids %s/p.png "
             "--normals %s/n.npy",
             temp_dir, W, H, temp_dir, temp_dir, temp_dir, temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    char path[512];
    static float depth[W * H], normals[3 * W * H];
    static uint32_t faces[W * H];
    static uint16_t parts[W * H];
    read_npy(temp_path(path, sizeof path, "d.npy"), depth);
    read_npy_of(temp_path(path, sizeof path, "f.npy"), "<u4", 1, faces);
    read_npy_of(temp_path(path, sizeof path, "n.npy"), "<f4", 3, normals);
    read_png16(temp_path(path, sizeof path, "p.png"), parts);
    int drawn = 0;
    for (int i = 0; i < W * H; i++) {
        bool on = depth[i] > 0.0f;
        drawn += on;
        cr_assert_eq(faces[i], (uint32_t)on, "pixel %d: face id %u, depth %g", i, faces[i], depth[i]);
        cr_assert_eq(parts[i], (uint16_t)on, "pixel %d: part id %u", i, parts[i]);
        cr_assert(normals[3 * i] == 0.0f && normals[3 * i + 1] == 0.0f && normals[3 * i + 2] == (on ? 1.0f : 0.0f),
                  "pixel %d: normal %g %g %g", i, normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
    }
    cr_assert_gt(drawn, 0);
    assert_one_error("render %s/tri.obj " POSE " --normals %s/n.pfm", "no writer");
    assert_one_error("render %s/tri.obj --face-ids %s/f.npy", "needs a camera pose");
}

/* Without a colour output and without --shade the draw is in ids, so what
 * is measured depends on the geometry alone: a triangle whose colours
 * (3e38) overflow once divided by w (at depth 0.5) is measured in front of
 * one behind it, where a lambert draw, which reads the colours, drops it
 * as not finite; --shade lambert and --out keep that draw. */
Test(cli_pinhole, without_a_colour_output_the_geometry_alone_is_measured)
{
    write_text(temp_dir, "nf.obj",
               "v -0.2 -0.2 0.5 3e38 0 0\nv 0.2 -0.2 0.5 3e38 0 0\nv 0 0.2 0.5 3e38 0 0\n"
               "v -0.2 -0.2 1 0.5 0.5 0.5\nv 0.2 -0.2 1 0.5 0.5 0.5\nv 0 0.2 1 0.5 0.5 0.5\nf 1 2 3\nf 4 5 6\n");
    static const struct {
        const char *options;
        uint32_t centre;
    } runs[] = { { "", 1 }, { "--shade lambert", 2 }, { "--out '%s/c.png'", 2 } };
    for (size_t k = 0; k < sizeof runs / sizeof *runs; k++) {
        char options[600], args[1400], path[512];
        snprintf(options, sizeof options, runs[k].options, temp_dir);
        snprintf(args, sizeof args,
                 "render %s/nf.obj --size %dx%d --intrinsics 40,40,19.5,14.5 --pose-w2c " IDENTITY
                 " %s --face-ids %s/f.npy --quiet",
                 temp_dir, W, H, options, temp_dir);
        run_result r = run_softrast(temp_dir, args);
        cr_assert_eq(r.status, 0, "%s: %s", args, r.err);
        static uint32_t faces[W * H];
        read_npy_of(temp_path(path, sizeof path, "f.npy"), "<u4", 1, faces);
        cr_assert_eq(faces[15 * W + 20], runs[k].centre, "%s: the centre shows face %u", args, faces[15 * W + 20]);
    }
}

/* An EXR's float channels, interleaved (one: "Y"; three: "R", "G", "B"),
 * through OpenEXRCore's reader. */
static void read_exr(const char *path, int channels, float *out)
{
    static const char *const names[2][3] = { { "Y" }, { "R", "G", "B" } };
    exr_context_t ctxt;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    cr_assert_eq(exr_start_read(&ctxt, path, &init), EXR_ERR_SUCCESS, "%s: not an EXR", path);
    int32_t lines;
    cr_assert_eq(exr_get_scanlines_per_chunk(ctxt, 0, &lines), EXR_ERR_SUCCESS);
    exr_decode_pipeline_t decode = { 0 };
    for (int y = 0; y < H; y += lines) {
        exr_chunk_info_t chunk;
        cr_assert_eq(exr_read_scanline_chunk_info(ctxt, 0, y, &chunk), EXR_ERR_SUCCESS);
        cr_assert_eq(y ? exr_decoding_update(ctxt, 0, &chunk, &decode) : exr_decoding_initialize(ctxt, 0, &chunk, &decode),
                     EXR_ERR_SUCCESS);
        cr_assert_eq(decode.channel_count, channels, "%s: %d channels", path, decode.channel_count);
        for (int c = 0; c < decode.channel_count; c++) {
            exr_coding_channel_info_t *ch = &decode.channels[c];
            int k = 0;
            while (k < channels && strcmp(ch->channel_name, names[channels == 3][k]) != 0)
                k++;
            cr_assert_lt(k, channels, "%s: channel %s", path, ch->channel_name);
            ch->user_pixel_stride = channels * (int32_t)sizeof(float);
            ch->user_line_stride = W * channels * (int32_t)sizeof(float);
            ch->user_bytes_per_element = sizeof(float);
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->decode_to_ptr = (uint8_t *)(out + (size_t)chunk.start_y * W * channels + k);
        }
        if (!y)
            cr_assert_eq(exr_decoding_choose_default_routines(ctxt, 0, &decode), EXR_ERR_SUCCESS);
        cr_assert_eq(exr_decoding_run(ctxt, 0, &decode), EXR_ERR_SUCCESS);
    }
    exr_decoding_destroy(ctxt, &decode);
    exr_finish(&ctxt);
}

/* View depth and normals as EXR and depth in millimetres as a 16-bit PNG
 * hold the .npy's values: the floats bit for bit, the PNG rounded. */
Test(cli_pinhole, exr_and_millimetre_png_hold_the_npy_values)
{
    char args[768];
    snprintf(args, sizeof args,
             "render %s/tri.obj --size %dx%d " POSE " --view-depth %s/d.npy --range %s/r.exr --normals %s/n.exr "
             "--normal-kind interpolated --quiet && %s render %s/tri.obj --size %dx%d " POSE
             " --view-depth %s/d.exr --range %s/r.npy --normals %s/n.npy --normal-kind interpolated --quiet && "
             "%s render %s/tri.obj --size %dx%d " POSE " --range %s/r.png --quiet",
             temp_dir, W, H, temp_dir, temp_dir, temp_dir, softrast_bin(), temp_dir, W, H, temp_dir, temp_dir, temp_dir,
             softrast_bin(), temp_dir, W, H, temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    char path[512];
    static float npy[3 * W * H], exr[3 * W * H], range[W * H];
    static uint16_t mm[W * H];
    read_npy(temp_path(path, sizeof path, "d.npy"), npy);
    read_exr(temp_path(path, sizeof path, "d.exr"), 1, exr);
    cr_assert_eq(memcmp(npy, exr, W * H * sizeof *npy), 0, "EXR depth differs from .npy");
    read_npy(temp_path(path, sizeof path, "r.npy"), range);
    read_exr(temp_path(path, sizeof path, "r.exr"), 1, exr);
    cr_assert_eq(memcmp(range, exr, W * H * sizeof *range), 0, "EXR range differs from .npy");
    read_png16(temp_path(path, sizeof path, "r.png"), mm);
    for (int i = 0; i < W * H; i++)
        cr_assert_eq(mm[i], (uint16_t)(range[i] * 1000.0 + 0.5), "pixel %d: %u mm for %.9g", i, mm[i], range[i]);
    read_npy_of(temp_path(path, sizeof path, "n.npy"), "<f4", 3, npy);
    read_exr(temp_path(path, sizeof path, "n.exr"), 3, exr);
    cr_assert_eq(memcmp(npy, exr, 3 * W * H * sizeof *npy), 0, "EXR normals differ from .npy");
}

/* A quad (triangles 0, 1) left and a pentagon (triangles 2, 3, 4) right
 * in the plane z = 0, seen as the triangle is: --face-ids names the
 * triangle each pixel shows, and with --face-ids-of file the file's face
 * it was fanned from, pixel for pixel. */
Test(cli_pinhole, face_ids_of_file_name_the_polygon_each_pixel_shows)
{
    write_text(temp_dir, "polys.obj",
               "v -1.5 0.2 0\nv -0.5 0.2 0\nv -0.5 1 0\nv -1.5 1 0\n"
               "v 0.2 0.2 0\nv 1.4 0.2 0\nv 1.4 0.7 0\nv 0.8 1 0\nv 0.2 0.7 0\n"
               "f 1 2 3 4\nf 5 6 7 8 9\n");
    static const char *const kinds[] = { "triangle", "file" };
    static uint32_t ids[2][W * H];
    for (int k = 0; k < 2; k++) {
        char args[768], path[512], name[16];
        snprintf(name, sizeof name, "%s.npy", kinds[k]);
        snprintf(args, sizeof args,
                 "render %s/polys.obj --size %dx%d --intrinsics 40,40,19.5,14.5 " POSE " --face-ids %s "
                 "--face-ids-of %s --out %s/c.png",
                 temp_dir, W, H, temp_path(path, sizeof path, name), kinds[k], temp_dir);
        run_result r = run_softrast(temp_dir, args);
        cr_assert_eq(r.status, 0, "stderr: %s", r.err);
        read_npy_of(temp_path(path, sizeof path, name), "<u4", 1, ids[k]);
    }
    int seen[6] = { 0 };
    for (int i = 0; i < W * H; i++) {
        uint32_t triangle = ids[0][i];
        cr_assert_leq(triangle, 5u, "pixel %d: triangle id %u", i, triangle);
        seen[triangle]++;
        uint32_t face = triangle == 0 ? 0 : triangle <= 2 ? 1 : 2;
        cr_assert_eq(ids[1][i], face, "pixel %d: triangle %u of face %u, written as face %u", i, triangle, face,
                     ids[1][i]);
    }
    for (int t = 1; t <= 5; t++)
        cr_assert_gt(seen[t], 0, "triangle %d is seen nowhere: the test proves less than it says", t - 1);
    assert_one_error("render %s/polys.obj " POSE " --face-ids-of file", "give --face-ids too");
}

/* `render --points` writes view depth and ids: each vertex's pixel
 * carries its z (the OBJ loader's z negation undone by the pose). */
Test(cli_pinhole, points_write_their_view_depth)
{
    write_text(temp_dir, "pts.obj", "v 0 0 2\nv 0.5 0 4\nv 0 -0.4 8\nf 1 2 3\n");
    char args[512];
    snprintf(args, sizeof args,
             "render %s/pts.obj --points --size %dx%d --intrinsics 40,40,19,14 --pose-w2c " IDENTITY
             " --view-depth %s/d.npy --face-ids %s/f.npy --quiet",
             temp_dir, W, H, temp_dir, temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    static float depth[W * H];
    static uint32_t ids[W * H];
    char path[512];
    read_npy(temp_path(path, sizeof path, "d.npy"), depth);
    read_npy_of(temp_path(path, sizeof path, "f.npy"), "<u4", 1, ids);
    /* pixel (19 + 40x/z, 14 + 40y/z) */
    const struct {
        int x, y;
        float z;
    } want[] = { { 19, 14, 2.0f }, { 24, 14, 4.0f }, { 19, 12, 8.0f } };
    int drawn = 0;
    for (size_t at = 0; at < (size_t)W * H; at++)
        drawn += ids[at] != 0;
    cr_assert_eq(drawn, 3, "%d pixels drawn", drawn);
    for (int k = 0; k < 3; k++) {
        size_t at = (size_t)want[k].y * W + (size_t)want[k].x;
        cr_assert_eq(ids[at], (uint32_t)k + 1, "point %d: pixel (%d, %d) shows %u", k, want[k].x, want[k].y, ids[at]);
        cr_assert_eq(depth[at], want[k].z, "point %d: depth %.9g", k, depth[at]);
    }
}
