/* tools/gen_assets.c — writes softrast's meshes and textures into a folder.
 *
 *     gen-assets DIR      (make assets: DIR = assets)
 *
 * Prints one line per file written; the same bytes every run. The OBJ writer
 * is in gen_obj.c, the shapes in gen_meshes.c, the textures in
 * gen_textures.c (see gen_assets.h).
 */
#include "gen_assets.h"

#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <SDL.h>
#include <SDL_image.h>

#define PATH_SIZE 4096

/* ---- errors and checked output ------------------------------------------ */

_Noreturn void gen_fail(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("gen-assets: error: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    exit(EXIT_FAILURE);
}

void gen_path(char *buf, size_t size, const char *dir, const char *name)
{
    int n = snprintf(buf, size, "%s/%s", dir, name);
    if (n < 0 || (size_t)n >= size)
        gen_fail("path too long: %s/%s", dir, name);
}

FILE *gen_open(const char *path)
{
    FILE *file = fopen(path, "w");
    if (!file)
        gen_fail("cannot open %s for writing: %s", path, strerror(errno));
    return file;
}

void gen_printf(FILE *file, const char *path, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vfprintf(file, fmt, ap);
    va_end(ap);
    if (n < 0)
        gen_fail("cannot write %s: %s", path, strerror(errno));
}

void gen_close(FILE *file, const char *path)
{
    if (ferror(file) | fclose(file)) /* both run: the file is closed either way */
        gen_fail("cannot write %s: %s", path, strerror(errno));
}

/* ---- materials ---------------------------------------------------------- */

static void write_material(const char *dir, const char *file_name,
                           const char *material, const char *texture)
{
    char path[PATH_SIZE];
    gen_path(path, sizeof path, dir, file_name);
    FILE *file = gen_open(path);
    gen_printf(file, path,
               "# softrast material, written by tools/gen_assets.c (make assets); do not edit\n"
               "newmtl %s\n"
               "Ka 1.000000 1.000000 1.000000\n"
               "Kd 1.000000 1.000000 1.000000\n"
               "Ks 0.000000 0.000000 0.000000\n"
               "d 1.000000\n"
               "illum 1\n"
               "map_Kd %s\n",
               material, texture);
    gen_close(file, path);
    printf("wrote %s: material %s, map_Kd %s\n", path, material, texture);
}

/* ---- single meshes ------------------------------------------------------ */

#define CUBE_HALF 1.0f
#define SPHERE_SEGMENTS 32
#define SPHERE_RINGS 16
#define TORUS_MAJOR 1.0f
#define TORUS_MINOR 0.35f
#define TORUS_SEGMENTS 48
#define TORUS_SIDES 24

/* Opens DIR/NAME.obj with mtllib NAME.mtl (a "checker" material) and writes
 * that material file too. */
static void open_checker_mesh(obj_writer *w, char *path, const char *dir,
                              const char *name)
{
    char file_name[PATH_SIZE], mtl_name[PATH_SIZE];
    snprintf(file_name, sizeof file_name, "%s.obj", name);
    snprintf(mtl_name, sizeof mtl_name, "%s.mtl", name);
    write_material(dir, mtl_name, "checker", "checker.png");
    gen_path(path, PATH_SIZE, dir, file_name);
    obj_open(w, path, mtl_name);
    obj_object(w, name);
    obj_usemtl(w, "checker");
}

/* Side 2 so that one face is one tile: uv 0..1 on every face. */
static void write_cube(const char *dir)
{
    obj_writer w;
    char path[PATH_SIZE];
    open_checker_mesh(&w, path, dir, "cube");
    emit_box(&w, (vec3){-CUBE_HALF, -CUBE_HALF, -CUBE_HALF},
             (vec3){CUBE_HALF, CUBE_HALF, CUBE_HALF}, 2.0f * CUBE_HALF, false);
    obj_close(&w);
}

static void write_sphere(const char *dir)
{
    obj_writer w;
    char path[PATH_SIZE];
    open_checker_mesh(&w, path, dir, "sphere");
    emit_uv_sphere(&w, 1.0f, SPHERE_SEGMENTS, SPHERE_RINGS);
    obj_close(&w);
}

static void write_torus(const char *dir)
{
    obj_writer w;
    char path[PATH_SIZE];
    open_checker_mesh(&w, path, dir, "torus");
    emit_torus(&w, TORUS_MAJOR, TORUS_MINOR, TORUS_SEGMENTS, TORUS_SIDES);
    obj_close(&w);
}

/* ---- quad3x3: the course's 3x3-vertex quad ------------------------------ */

#define QUAD_SIDE 3 /* vertices per row and per column */

/* Triangles (a, b, c) as the strip 3,0,4,1,5,2,2,6,6,3,7,4,8,5 assembles
 * them: clockwise seen from -z in softrast's left-handed space, which is
 * what the loader makes of a face (a, c, b) in this right-handed file. */
static const int QUAD_TRIANGLES[8][3] = {
    {3, 0, 4}, {0, 1, 4}, {4, 1, 5}, {1, 2, 5},
    {6, 3, 7}, {3, 4, 7}, {7, 4, 8}, {4, 5, 8},
};
static const int QUAD_STRIP[14] = {3, 0, 4, 1, 5, 2, 2, 6, 6, 3, 7, 4, 8, 5};

/* Vertex i = row * 3 + col, row 0 at y = +1, col 0 at x = -1; colour
 * (col/2, row/2, 1 - (col+row)/4) differs at every vertex. */
static void write_quad3x3_obj(const char *dir)
{
    obj_writer w;
    char path[PATH_SIZE];
    open_checker_mesh(&w, path, dir, "quad3x3");
    obj_corner corner[QUAD_SIDE * QUAD_SIDE];
    vec3 normal = {0.0f, 0.0f, 1.0f};
    for (int i = 0; i < QUAD_SIDE * QUAD_SIDE; i++) {
        int row = i / QUAD_SIDE, col = i % QUAD_SIDE;
        vec3 p = {(float)(col - 1), (float)(1 - row), 0.0f};
        vec3 rgb = {0.5f * (float)col, 0.5f * (float)row,
                    1.0f - 0.25f * (float)(col + row)};
        corner[i].v = obj_vertex_rgb(&w, p, rgb);
    }
    for (int i = 0; i < QUAD_SIDE * QUAD_SIDE; i++) {
        corner[i].vt = obj_uv(&w, 0.5f * (float)(i % QUAD_SIDE),
                              1.0f - 0.5f * (float)(i / QUAD_SIDE));
        corner[i].vn = obj_normal(&w, normal);
    }
    for (int t = 0; t < 8; t++) {
        const int *tri = QUAD_TRIANGLES[t];
        obj_tri(&w, corner[tri[0]], corner[tri[2]], corner[tri[1]]);
    }
    obj_close(&w);
}

static void print_indices(FILE *file, const char *path, const int *idx, int n)
{
    for (int i = 0; i < n; i++)
        gen_printf(file, path, "%d%s", idx[i], i + 1 < n ? "," : "\n");
}

static void write_quad3x3_txt(const char *dir)
{
    char path[PATH_SIZE];
    gen_path(path, sizeof path, dir, "quad3x3.txt");
    FILE *file = gen_open(path);
    gen_printf(file, path,
               "quad3x3: the 3x3-vertex quad (written by tools/gen_assets.c; documentation only,\n"
               "the tests build these index arrays themselves)\n\n"
               "vertex i = row*3 + col, row 0 at y = +1, col 0 at x = -1, z = 0:\n\n"
               "    0 --- 1 --- 2     y = +1\n"
               "    |     |     |\n"
               "    3 --- 4 --- 5     y =  0\n"
               "    |     |     |\n"
               "    6 --- 7 --- 8     y = -1\n"
               "  x=-1   x=0   x=+1\n\n"
               "TriangleList, 24 indices (8 triangles):\n");
    print_indices(file, path, &QUAD_TRIANGLES[0][0], 24);
    gen_printf(file, path,
               "\nTriangleStrip, 14 indices (triangle k = (k, k+1, k+2), odd k swaps its\n"
               "last two; k = 4..7 repeat an index and are skipped as degenerate):\n");
    print_indices(file, path, QUAD_STRIP, 14);
    gen_printf(file, path,
               "\nBoth give the same 8 triangles in the same order. Seen from -z in\n"
               "softrast's left-handed space (the default camera) they are clockwise on\n"
               "screen, i.e. front faces. quad3x3.obj is the same quad as a right-handed\n"
               "OBJ: each triangle (a,b,c) is written as face (a,c,b), counter-clockwise\n"
               "seen from +z, which the loader turns back into (a,b,c).\n");
    gen_close(file, path);
    printf("wrote %s: index list and strip\n", path);
}

/* ---- the room ----------------------------------------------------------- */

#define ROOM_HALF 10.0f  /* the floor spans -10..10 in x and z */
#define ROOM_HEIGHT 6.0f /* floor at y = 0, ceiling at y = 6 */
#define ROOM_TILE 2.0f   /* one texture repeat per 2 units */
#define PILLAR_HALF 0.4f
#define PILLAR_RADIUS 0.45f
#define PILLAR_SEGMENTS 24

typedef struct pillar {
    float x, z;
    bool round;
} pillar;

/* A ring of 8 around the centre; positions kept off the 2-unit grid so no
 * pillar edge coincides with a floor edge. */
static const pillar ROOM_PILLARS[] = {
    {-5.0f, -5.0f, false}, {0.0f, -5.0f, true}, {5.0f, -5.0f, false},
    {-5.0f, 0.0f, true},                        {5.0f, 0.0f, true},
    {-5.0f, 5.0f, false},  {0.0f, 5.0f, true},  {5.0f, 5.0f, false},
};

/* Every room object uses the one material, as Blender would write it. */
static void room_object(obj_writer *w, const char *name)
{
    obj_object(w, name);
    obj_usemtl(w, "room");
}

static void place(obj_writer *w, vec3 at, float degrees, vec3 axis,
                  float scale, atlas_cell cell)
{
    mat4 m;
    glm_translate_make(m, at);
    glm_rotate(m, glm_rad(degrees), axis);
    glm_scale_uni(m, scale);
    obj_place(w, m, atlas_uv(cell));
}

/* The inside of a box: tiles below, stone above, bricks around. Faces of
 * one box share their edge vertices, so the shell is closed. */
static void emit_room_shell(obj_writer *w)
{
    vec3 lo = {-ROOM_HALF, 0.0f, -ROOM_HALF}, hi = {ROOM_HALF, ROOM_HEIGHT, ROOM_HALF};
    vec3 up = {0.0f, 1.0f, 0.0f};
    static const float SIDES[2] = {-1.0f, 1.0f};
    room_object(w, "shell");
    for (int axis = 0; axis < 3; axis++) {
        for (int s = 0; s < 2; s++) {
            atlas_cell cell = axis != 1 ? ATLAS_BRICK
                              : SIDES[s] < 0.0f ? ATLAS_FLOOR : ATLAS_STONE;
            place(w, GLM_VEC3_ZERO, 0.0f, up, 1.0f, cell);
            emit_box_face(w, lo, hi, axis, SIDES[s], ROOM_TILE, true);
        }
    }
}

static void emit_room_pillars(obj_writer *w)
{
    vec3 up = {0.0f, 1.0f, 0.0f};
    char name[32];
    for (size_t i = 0; i < sizeof ROOM_PILLARS / sizeof ROOM_PILLARS[0]; i++) {
        const pillar *p = &ROOM_PILLARS[i];
        snprintf(name, sizeof name, "pillar_%zu", i);
        room_object(w, name);
        place(w, (vec3){p->x, 0.0f, p->z}, 0.0f, up, 1.0f, ATLAS_STONE);
        if (p->round)
            emit_cylinder(w, PILLAR_RADIUS, ROOM_HEIGHT, PILLAR_SEGMENTS, ROOM_TILE);
        else
            emit_box(w, (vec3){-PILLAR_HALF, 0.0f, -PILLAR_HALF},
                     (vec3){PILLAR_HALF, ROOM_HEIGHT, PILLAR_HALF}, ROOM_TILE, false);
    }
}

/* Unit shapes placed by a model matrix: where, turned how, how big. */
typedef enum prop_shape { PROP_BOX, PROP_SPHERE, PROP_TORUS } prop_shape;

typedef struct prop {
    const char *name;
    prop_shape shape;
    vec3 at, axis;
    float degrees, scale;
    atlas_cell cell;
    float height; /* PROP_BOX: a pedestal of this height standing on `at` */
} prop;

/* Pedestals stand on the floor; the sphere and the small cube rest on
 * them, the rest float. Scales keep everything clear of the pillars. */
static const prop ROOM_PROPS[] = {
    {"pedestal_centre", PROP_BOX, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 0.0f, 0.7f, ATLAS_BRICK, 1.2f},
    {"sphere_centre", PROP_SPHERE, {0.0f, 2.2f, 0.0f}, {0, 1, 0}, 0.0f, 1.0f, ATLAS_CHECKER, 0},
    {"torus_upright", PROP_TORUS, {0.0f, 3.2f, 7.5f}, {1, 0, 0}, 90.0f, 1.0f, ATLAS_CHECKER, 0},
    {"torus_tilted", PROP_TORUS, {7.5f, 2.5f, -7.5f}, {0, 0, 1}, 20.0f, 1.2f, ATLAS_CHECKER, 0},
    {"cube_floating", PROP_BOX, {-7.5f, 3.0f, 7.5f}, {1, 1, 0}, 40.0f, 0.8f, ATLAS_CHECKER, 0},
    {"pedestal_corner", PROP_BOX, {7.5f, 0.0f, 7.5f}, {0, 1, 0}, 0.0f, 0.7f, ATLAS_STONE, 1.0f},
    {"cube_on_pedestal", PROP_BOX, {7.5f, 1.5f, 7.5f}, {0, 1, 0}, 30.0f, 0.5f, ATLAS_CHECKER, 0},
    {"sphere_floor", PROP_SPHERE, {-7.5f, 1.0f, -7.5f}, {0, 1, 0}, 0.0f, 1.0f, ATLAS_CHECKER, 0},
};

/* A prop box is the unit cube (-1..1, one tile per face) or, with a
 * height, a pedestal of half-width `scale` from y = 0 up to `height`. */
static void emit_prop(obj_writer *w, const prop *p)
{
    vec3 axis;
    glm_vec3_copy((float *)p->axis, axis);
    glm_vec3_normalize(axis);
    room_object(w, p->name);
    if (p->height > 0.0f) {
        place(w, (float *)p->at, p->degrees, axis, 1.0f, p->cell);
        emit_box(w, (vec3){-p->scale, 0.0f, -p->scale},
                 (vec3){p->scale, p->height, p->scale}, ROOM_TILE, false);
        return;
    }
    place(w, (float *)p->at, p->degrees, axis, p->scale, p->cell);
    if (p->shape == PROP_SPHERE)
        emit_uv_sphere(w, 1.0f, SPHERE_SEGMENTS, SPHERE_RINGS);
    else if (p->shape == PROP_TORUS)
        emit_torus(w, TORUS_MAJOR, TORUS_MINOR, TORUS_SEGMENTS, TORUS_SIDES);
    else
        emit_box(w, (vec3){-CUBE_HALF, -CUBE_HALF, -CUBE_HALF},
                 (vec3){CUBE_HALF, CUBE_HALF, CUBE_HALF}, 2.0f * CUBE_HALF, false);
}

/* One material, one texture (room.png, a 2x2 atlas): the loader keeps a
 * single texture per mesh. Every face's uv stays inside one atlas cell. */
static void write_room(const char *dir)
{
    char path[PATH_SIZE];
    obj_writer w;
    write_material(dir, "room.mtl", "room", "room.png");
    gen_path(path, sizeof path, dir, "room.obj");
    obj_open(&w, path, "room.mtl");
    emit_room_shell(&w);
    emit_room_pillars(&w);
    for (size_t i = 0; i < sizeof ROOM_PROPS / sizeof ROOM_PROPS[0]; i++)
        emit_prop(&w, &ROOM_PROPS[i]);
    obj_close(&w);
}

/* ---- main --------------------------------------------------------------- */

static void write_textures(const char *dir)
{
    char path[PATH_SIZE];
    if ((IMG_Init(IMG_INIT_PNG) & IMG_INIT_PNG) == 0)
        gen_fail("cannot initialise PNG support: %s", IMG_GetError());
    gen_path(path, sizeof path, dir, "checker.png");
    write_checker_png(path);
    gen_path(path, sizeof path, dir, "room.png");
    write_room_png(path);
    IMG_Quit();
}

int main(int argc, char **argv)
{
    if (argc != 2)
        gen_fail("usage: gen-assets DIR");
    const char *dir = argv[1];
    if (mkdir(dir, 0777) != 0 && errno != EEXIST)
        gen_fail("cannot create %s: %s", dir, strerror(errno));
    write_textures(dir);
    write_cube(dir);
    write_sphere(dir);
    write_torus(dir);
    write_quad3x3_obj(dir);
    write_quad3x3_txt(dir);
    write_room(dir);
    return EXIT_SUCCESS;
}
