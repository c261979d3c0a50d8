/* Part ids are an instance mask: each node's instance of a mesh in an
 * Assimp file is its own part, placed by its node transforms, even where
 * the instances share a mesh and a material (Assimp's own flattening
 * merges those). */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "amf_two_volumes.h"
#include "gltf_square.h"
#include "run_helpers.h"
#include "softrast/files.h"
#include "temp_dir.h"

TestSuite(instances, .init = temp_dir_make, .fini = temp_dir_remove);

/* A unit square in z = 0, front side +z, without normals, placed three
 * times with one material: at x − 2, at x + 2, and mirrored in x under a
 * parent moved to z = 1. */
static const char SQUARES_GLTF[] =
    "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0,1,2]}],"
    "\"nodes\":[{\"mesh\":0,\"translation\":[-2,0,0]},{\"mesh\":0,\"translation\":[2,0,0]},"
    "{\"translation\":[0,0,1],\"children\":[3]},{\"mesh\":0,\"scale\":[-1,1,1]}],"
    "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.25,1,1]}}],"
    "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"material\":0}]}],"
    GLTF_UNIT_SQUARE_ARRAYS "}";

/* One triangle geometry instanced by two nodes, one material bound to both. */
static const char TRIANGLES_DAE[] =
    "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
    "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
    "<asset><unit meter=\"1\"/><up_axis>Y_UP</up_axis></asset>\n"
    "<library_effects><effect id=\"e\"><profile_COMMON><technique sid=\"t\"><lambert><diffuse>"
    "<color>1 0 0 1</color></diffuse></lambert></technique></profile_COMMON></effect></library_effects>\n"
    "<library_materials><material id=\"m\"><instance_effect url=\"#e\"/></material></library_materials>\n"
    "<library_geometries><geometry id=\"g\"><mesh>"
    "<source id=\"p\"><float_array id=\"pa\" count=\"9\">0 0 0 1 0 0 0 1 0</float_array><technique_common>"
    "<accessor source=\"#pa\" count=\"3\" stride=\"3\"><param name=\"X\" type=\"float\"/>"
    "<param name=\"Y\" type=\"float\"/><param name=\"Z\" type=\"float\"/></accessor></technique_common></source>"
    "<vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>"
    "<triangles count=\"1\" material=\"s\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/><p>0 1 2</p>"
    "</triangles></mesh></geometry></library_geometries>\n"
    "<library_visual_scenes><visual_scene id=\"vs\">"
    "<node id=\"a\"><translate>-2 0 0</translate><instance_geometry url=\"#g\"><bind_material><technique_common>"
    "<instance_material symbol=\"s\" target=\"#m\"/></technique_common></bind_material></instance_geometry></node>"
    "<node id=\"b\"><translate>2 0 0</translate><instance_geometry url=\"#g\"><bind_material><technique_common>"
    "<instance_material symbol=\"s\" target=\"#m\"/></technique_common></bind_material></instance_geometry></node>"
    "</visual_scene></library_visual_scenes>\n"
    "<scene><instance_visual_scene url=\"#vs\"/></scene>\n</COLLADA>\n";

/* One tetrahedron, (0,0,0) (1,0,0) (0,2,0) (0,0,3), placed by AMF
 * constellations: "2" holds it at x + 10, and turned a quarter about z
 * then moved by (−10, 0, 5); "3" holds "2" as it is, and turned a quarter
 * about x then moved by (0, 50, 0). A comment and metadata stand where a
 * careless reader would take them for instances. */
static const char TETRA_AMF[] =
    "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<amf unit=\"millimeter\">\n"
    "<object id=\"1\"><mesh><vertices>"
    "<vertex><coordinates><x>0</x><y>0</y><z>0</z></coordinates></vertex>"
    "<vertex><coordinates><x>1</x><y>0</y><z>0</z></coordinates></vertex>"
    "<vertex><coordinates><x>0</x><y>2</y><z>0</z></coordinates></vertex>"
    "<vertex><coordinates><x>0</x><y>0</y><z>3</z></coordinates></vertex>"
    "</vertices><volume><triangle><v1>0</v1><v2>2</v2><v3>1</v3></triangle>"
    "<triangle><v1>0</v1><v2>1</v2><v3>3</v3></triangle><triangle><v1>0</v1><v2>3</v2><v3>2</v3></triangle>"
    "<triangle><v1>1</v1><v2>2</v2><v3>3</v3></triangle></volume></mesh></object>\n"
    "<!-- <constellation id=\"2\"><instance objectid=\"1\"><deltax>7</deltax></instance> -->\n"
    "<constellation id=\"2\"><metadata type=\"Name\">pair</metadata>"
    "<instance objectid=\"1\"><deltax>10</deltax><deltay>0</deltay><deltaz>0</deltaz></instance>"
    "<instance objectid='1'>\n  <deltax> -10 </deltax><deltaz>5</deltaz><rx>0</rx><ry>0</ry><rz>90</rz>\n</instance>"
    "</constellation>\n"
    "<constellation id=\"3\"><instance objectid=\"2\"/>"
    "<instance objectid=\"2\"><deltay>50</deltay><rx>90</rx></instance></constellation>\n</amf>\n";

/* The object of two volumes (amf_two_volumes.h), alone and placed twice
 * by a constellation: at x + 10, and turned a quarter about z then moved
 * to y + 5. Its materials are red and blue. */
#define TWO_MATERIALS                                                                                         \
    "<material id=\"2\"><color><r>1</r><g>0</g><b>0</b></color></material>"                                   \
    "<material id=\"3\"><color><r>0</r><g>0</g><b>1</b></color></material>\n"
static const char SPLIT_AMF[] = "<?xml version=\"1.0\"?>\n<amf>\n" AMF_TWO_VOLUMES("1") TWO_MATERIALS "</amf>\n";
static const char PLACED_AMF[] = "<?xml version=\"1.0\"?>\n<amf>\n" AMF_TWO_VOLUMES("1") TWO_MATERIALS
                                 "<constellation id=\"2\"><instance objectid=\"1\"><deltax>10</deltax></instance>"
                                 "<instance objectid=\"1\"><deltay>5</deltay><rz>90</rz></instance>"
                                 "</constellation>\n</amf>\n";

static void load(sr_mesh *mesh, const char *name, const char *text)
{
    char path[600];
    write_text(temp_dir, name, text);
    sr_texture tex = { 0 };
    sr_error err = { "" };
    cr_assert(sr_mesh_load(mesh, &tex, temp_path(path, sizeof path, name), &err), "%s", err.message);
    sr_texture_free(&tex);
}

/* The bounds of a part's vertices (softrast's world: the file's z negated). */
static void part_bounds(const sr_mesh *m, uint32_t part, double lo[3], double hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    const sr_mesh_part *p = &m->parts[part];
    for (uint32_t i = 3 * p->first_triangle; i < 3 * (p->first_triangle + p->triangle_count); i++)
        for (int k = 0; k < 3; k++) {
            const double c = m->origin[k] + m->positions[m->indices[i]][k];
            lo[k] = fmin(lo[k], c);
            hi[k] = fmax(hi[k], c);
        }
}

static void assert_part_at(const sr_mesh *m, uint32_t part, const double want_lo[3], const double want_hi[3])
{
    double lo[3], hi[3];
    part_bounds(m, part, lo, hi);
    for (int k = 0; k < 3; k++)
        cr_assert(lo[k] == want_lo[k] && hi[k] == want_hi[k], "part %u axis %d spans [%g, %g], not [%g, %g]", part,
                  k, lo[k], hi[k], want_lo[k], want_hi[k]);
}

Test(instances, each_gltf_node_instance_is_a_part_placed_by_its_node)
{
    sr_mesh m;
    load(&m, "squares.gltf", SQUARES_GLTF);
    cr_assert_eq(m.part_count, 3, "three instances of one mesh and material, %u parts", m.part_count);
    cr_assert_eq(m.index_count, 3 * 6);
    for (uint32_t p = 0; p < 3; p++) {
        cr_assert_eq(m.parts[p].first_triangle, 2 * p);
        cr_assert_eq(m.parts[p].triangle_count, 2);
        cr_assert_eq(m.parts[p].material, m.parts[0].material, "the instances share their material");
    }
    cr_assert_float_eq(m.materials[m.parts[0].material].base_color[1], 0.25f, 0.0f);
    assert_part_at(&m, 0, (double[]){ -2, 0, 0 }, (double[]){ -1, 1, 0 });
    assert_part_at(&m, 1, (double[]){ 2, 0, 0 }, (double[]){ 3, 1, 0 });
    assert_part_at(&m, 2, (double[]){ -1, 0, -1 }, (double[]){ 0, 1, -1 });
    sr_mesh_free(&m);
}

/* The squares have no normals: Assimp makes them from the winding before
 * the placing, and a mirrored instance's (its winding turned outward for
 * glTF) come out facing the file's +z as the others', softrast's −z. */
Test(instances, made_normals_of_a_mirrored_instance_face_as_the_plain_ones)
{
    sr_mesh m;
    load(&m, "squares.gltf", SQUARES_GLTF);
    cr_assert_not_null(m.normals);
    for (uint32_t v = 0; v < m.vertex_count; v++)
        cr_assert(fabsf(m.normals[v][0]) < 1e-6f && fabsf(m.normals[v][1]) < 1e-6f &&
                      fabsf(m.normals[v][2] + 1.0f) < 1e-6f,
                  "vertex %u: normal (%g, %g, %g)", v, m.normals[v][0], m.normals[v][1], m.normals[v][2]);
    sr_mesh_free(&m);
}

Test(instances, each_collada_instance_geometry_is_a_part)
{
    sr_mesh m;
    load(&m, "triangles.dae", TRIANGLES_DAE);
    cr_assert_eq(m.part_count, 2, "two instances of one geometry and material, %u parts", m.part_count);
    cr_assert_eq(m.parts[0].material, m.parts[1].material);
    assert_part_at(&m, 0, (double[]){ -2, 0, 0 }, (double[]){ -1, 1, 0 });
    assert_part_at(&m, 1, (double[]){ 2, 0, 0 }, (double[]){ 3, 1, 0 });
    sr_mesh_free(&m);
}

/* Each instance is turned about the file's axes, in degrees, then moved:
 * the bounds of each part, in softrast's world (z negated), are exact. */
Test(instances, each_amf_constellation_instance_is_placed_at_its_offset_and_turn)
{
    sr_mesh m;
    load(&m, "tetra.amf", TETRA_AMF);
    cr_assert_eq(m.part_count, 4, "two instances of a constellation of two: %u parts", m.part_count);
    assert_part_at(&m, 0, (double[]){ 10, 0, -3 }, (double[]){ 11, 2, 0 });
    assert_part_at(&m, 1, (double[]){ -12, 0, -8 }, (double[]){ -10, 1, -5 });
    assert_part_at(&m, 2, (double[]){ 10, 47, -2 }, (double[]){ 11, 50, 0 });
    assert_part_at(&m, 3, (double[]){ -12, 42, -1 }, (double[]){ -10, 45, 0 });
    sr_mesh_free(&m);
}

/* A part's every vertex is of this colour. */
static void assert_part_colour(const sr_mesh *m, uint32_t part, const float rgb[3])
{
    cr_assert_not_null(m->colors);
    const sr_mesh_part *p = &m->parts[part];
    for (uint32_t i = 3 * p->first_triangle; i < 3 * (p->first_triangle + p->triangle_count); i++) {
        const float *c = m->colors[m->indices[i]];
        cr_assert(c[0] == rgb[0] && c[1] == rgb[1] && c[2] == rgb[2], "part %u: colour %g %g %g", part, c[0], c[1],
                  c[2]);
    }
}

static const float RED[3] = { 1, 0, 0 }, BLUE[3] = { 0, 0, 1 };

/* Assimp 5.2 reads an AMF mesh's first volume alone: the second's three
 * triangles, and its vertex down at z = −2 (2 in softrast's world), were
 * lost. Each volume is its own part, in its own material's colour. */
Test(instances, every_volume_of_an_amf_object_is_a_part_in_its_material)
{
    sr_mesh m;
    load(&m, "split.amf", SPLIT_AMF);
    cr_assert_eq(sr_mesh_triangle_slots(&m), 7, "4 + 3 triangles, not %u", sr_mesh_triangle_slots(&m));
    cr_assert_eq(m.part_count, 2);
    assert_part_at(&m, 0, (double[]){ 0, 0, -1 }, (double[]){ 1, 1, 0 });
    assert_part_at(&m, 1, (double[]){ 0, 0, 0 }, (double[]){ 1, 1, 2 });
    assert_part_colour(&m, 0, RED);
    assert_part_colour(&m, 1, BLUE);
    cr_assert(m.bounds_lo[2] == -1.0f && m.bounds_hi[2] == 2.0f, "z bounds [%g, %g]", m.bounds_lo[2], m.bounds_hi[2]);
    sr_mesh_free(&m);
}

Test(instances, every_volume_goes_where_its_amf_objects_instance_is_placed)
{
    sr_mesh m;
    load(&m, "placed.amf", PLACED_AMF);
    static const struct {
        double lo[3], hi[3];
    } want[] = {
        { { 10, 0, -1 }, { 11, 1, 0 } }, /* the first instance's volumes */
        { { 10, 0, 0 }, { 11, 1, 2 } },
        { { -1, 5, -1 }, { 0, 6, 0 } }, /* the second's, turned */
        { { -1, 5, 0 }, { 0, 6, 2 } },
    };
    cr_assert_eq(m.part_count, 4, "two instances of two volumes: %u parts", m.part_count);
    for (uint32_t p = 0; p < 4; p++) {
        assert_part_at(&m, p, want[p].lo, want[p].hi);
        assert_part_colour(&m, p, p % 2 ? BLUE : RED);
    }
    sr_mesh_free(&m);
}

/* Through a pinhole camera at the file's z = 4 looking down its −z, at
 * the squares' front sides: each pixel's part id names the instance it
 * shows, the nearer mirrored one over the far left one where they
 * overlap; culling back faces changes nothing (the mirrored instance of a
 * mesh also placed plain keeps its front faces). */
static void assert_parts_seen(sr_cull cull)
{
    sr_mesh m;
    load(&m, "squares.gltf", SQUARES_GLTF);
    enum { W = 64, H = 16 };
    sr_pinhole cam = { .fx = 20.0, .fy = 20.0, .cx = 31.5, .cy = 7.5 };
    static const double c2w[4][4] = { { 1, 0, 0, 0.5 }, { 0, -1, 0, 0.5 }, { 0, 0, -1, 4 }, { 0, 0, 0, 1 } };
    sr_error err = { "" };
    cr_assert(sr_pinhole_pose_from_c2w(c2w, cam.w2c, &err), "%s", err.message);
    sr_pinhole_fit_clip(&cam, &m);
    sr_framebuffer fb;
    cr_assert(sr_framebuffer_create(&fb, W, H, &err), "%s", err.message);
    sr_draw_desc desc = { .mesh = &m, .shade = SR_SHADE_ID, .cull = cull, .clear = true };
    sr_pinhole_matrices(&cam, &m, &fb, &desc);
    cr_assert(sr_draw(&fb, &desc, NULL, &err), "%s", err.message);
    static uint32_t parts[W * H];
    cr_assert(sr_pinhole_resolve(&cam, &m, &fb, &(sr_pinhole_outputs){ .part_ids = parts }, &err), "%s",
              err.message);
    /* Columns: the left square spans u 19..24 at depth 4, the mirrored one
     * u 21.5..28.2 at depth 3, the right one u 39..44; row 7 crosses all. */
    static const struct { int u; uint32_t part; } want[] = {
        { 17, 0 }, { 20, 1 }, { 23, 3 }, { 27, 3 }, { 33, 0 }, { 41, 2 }, { 46, 0 },
    };
    for (size_t i = 0; i < sizeof want / sizeof *want; i++)
        cr_assert_eq(parts[7 * W + want[i].u], want[i].part, "cull %d, pixel (%d, 7): part id %u, not %u", cull,
                     want[i].u, parts[7 * W + want[i].u], want[i].part);
    sr_framebuffer_destroy(&fb);
    sr_mesh_free(&m);
}

Test(instances, part_ids_are_an_instance_mask)
{
    assert_parts_seen(SR_CULL_NONE);
    assert_parts_seen(SR_CULL_BACK);
}
