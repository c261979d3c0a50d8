/* softrast.Renderer: a framebuffer with an ids plane and a workspace
 * reused from call to call, and the pinhole renders over them. Each render
 * is the command line's: the draw into the reversed-z framebuffer with the
 * matrices of sr_pinhole_matrices, shaded as the colour output asks (else
 * SR_SHADE_ID) in the colour space asked for, a file's BLEND parts
 * blended over the rest (sr_draw_layered), writing colour, depth and ids
 * at once, then sr_pinhole_resolve of the ids on the renderer's threads
 * into new numpy arrays, with the GIL released around all of it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/vertex_colours.h" /* the display colours' decoding, the command line's */
#include "softrast_py.h"

enum { OUT_COLOR, OUT_DEPTH, OUT_RANGE, OUT_FACE_IDS, OUT_PART_IDS, OUT_NORMALS, OUT_COUNT };
static const char *const OUT_NAMES[OUT_COUNT] = { "color", "depth", "range", "face_ids", "part_ids", "normals" };
#define OUT_LIST "'color', 'depth', 'range', 'face_ids', 'part_ids', 'normals'"

/* The colour output's shading modes, named as the command line's --shade, in sr_shade's order. */
static const char *const SHADE_NAMES[SR_SHADE_COUNT] = { "lambert", "id", "color", "normal", "texture", "depth" };
#define SHADE_LIST "'lambert', 'id', 'color', 'normal', 'texture', 'depth'"

/* The colour spaces, named as the command line's --color-space, in sr_color_space's order. */
static const char *const COLOR_SPACE_NAMES[] = { "raw", "srgb" };

/* The draw's own limit on threads; more are drawn with this many. */
#define MAX_THREADS 64

typedef struct sr_py_renderer {
    PyObject_HEAD
    sr_framebuffer fb; /* reversed z, with the ids plane the resolve reads */
    sr_workspace *workspace;
    int threads;
    pid_t pid;  /* the process whose threads the workspace holds (a forked child has none of them) */
    bool busy;  /* a render runs with the GIL released; set and read with the GIL held */
} sr_py_renderer;

/* What one call renders: the camera but its pose, and the outputs. */
typedef struct job {
    sr_pinhole cam;
    bool wanted[OUT_COUNT];
    bool interpolated;
    float invalid;
    sr_shade shade; /* the colour output's */
    bool shade_given;
    bool points;      /* the mesh's vertices drawn as squares point_size pixels wide */
    float point_size;
    sr_color_space color_space;
    vec3 light;     /* toward the light in softrast's world; zero: SR_DEFAULT_LIGHT */
} job;

static void renderer_release(sr_py_renderer *self)
{
    if (self->workspace && self->pid == getpid())
        sr_workspace_destroy(self->workspace); /* in a forked child its threads are not there to end */
    self->workspace = NULL;
    sr_framebuffer_destroy(&self->fb);
}

static void renderer_dealloc(sr_py_renderer *self)
{
    renderer_release(self);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

static int renderer_init(sr_py_renderer *self, PyObject *args, PyObject *kwargs)
{
    static char *names[] = { "width", "height", "threads", NULL };
    int width, height, threads = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "ii|i:Renderer", names, &width, &height, &threads))
        return -1;
    if (self->busy && self->pid == getpid()) {
        PyErr_SetString(PyExc_RuntimeError, "Renderer.__init__ on a renderer another thread is rendering with");
        return -1;
    }
    if (threads < 0) {
        PyErr_Format(PyExc_ValueError, "threads: %d; 0 is one a core, else 1 or more", threads);
        return -1;
    }
    sr_framebuffer fb;
    sr_error err;
    if (!sr_framebuffer_create(&fb, width, height, &err)) {
        sr_py_raise(PyExc_ValueError, &err);
        return -1;
    }
    if (!sr_framebuffer_create_ids(&fb, &err)) {
        sr_framebuffer_destroy(&fb);
        sr_py_raise(PyExc_MemoryError, &err);
        return -1;
    }
    sr_workspace *workspace = sr_workspace_create();
    if (!workspace) {
        sr_framebuffer_destroy(&fb);
        PyErr_NoMemory();
        return -1;
    }
    renderer_release(self);
    self->fb = fb;
    self->workspace = workspace;
    self->pid = getpid();
    self->busy = false;
    if (threads == 0) {
        long cores = sysconf(_SC_NPROCESSORS_ONLN);
        threads = cores < 1 ? 1 : cores > MAX_THREADS ? MAX_THREADS : (int)cores;
    }
    self->threads = threads;
    return 0;
}

/* A number that may be a Python or numpy scalar. */
static bool parse_number(PyObject *obj, const char *name, double *out)
{
    double v = PyFloat_AsDouble(obj);
    if (v == -1.0 && PyErr_Occurred()) {
        PyErr_Clear();
        PyErr_Format(PyExc_ValueError, "%s: %R is not a number", name, obj);
        return false;
    }
    *out = v;
    return true;
}

/* fx = fy and a centred principal point from a vertical field of view in
 * degrees, as the command line's --fov without --intrinsics. */
static bool intrinsics_from_fov(const sr_py_renderer *self, PyObject *fov, sr_pinhole *cam)
{
    double deg = SR_CAMERA_FOV;
    if (fov != Py_None && !parse_number(fov, "fov", &deg))
        return false;
    if (!(deg > 0.0 && deg < 180.0)) {
        char text[32];
        snprintf(text, sizeof text, "%g", deg);
        PyErr_Format(PyExc_ValueError, "fov: %s degrees; the vertical field of view is above 0 and below 180", text);
        return false;
    }
    /* in float degrees, as the command line's --fov (sr_camera.fov_deg) */
    cam->fx = cam->fy = 0.5 * self->fb.height / tan(0.5 * (double)(float)deg * GLM_PI / 180.0);
    cam->cx = 0.5 * (self->fb.width - 1);
    cam->cy = 0.5 * (self->fb.height - 1);
    return true;
}

/* fx, fy, cx, cy from K, from the numbers (fy defaults to fx, cx and cy to
 * the centre) or from fov (the look-at camera's default: 60 degrees);
 * sr_pinhole_check judges their values. */
static bool parse_intrinsics(const sr_py_renderer *self, PyObject *K, PyObject *const numbers[4], PyObject *fov,
                             bool look_at, sr_pinhole *cam)
{
    static const char *const names[4] = { "fx", "fy", "cx", "cy" };
    bool any = false;
    for (int k = 0; k < 4; k++)
        any = any || numbers[k] != Py_None;
    if (fov != Py_None && (any || K != Py_None)) {
        PyErr_SetString(PyExc_ValueError, "give the intrinsics as K, as fx, fy, cx, cy or as fov, not two of them");
        return false;
    }
    if (fov != Py_None || (look_at && !any && K == Py_None))
        return intrinsics_from_fov(self, fov, cam);
    if (K != Py_None) {
        if (any) {
            PyErr_SetString(PyExc_ValueError, "give the intrinsics as K or as fx, fy, cx, cy, not both");
            return false;
        }
        PyArrayObject *a = sr_py_array(K, "K", NPY_FLOAT64, 2, (npy_intp[]){ 3, 3 }, "(3, 3)");
        if (!a)
            return false;
        const double *m = PyArray_DATA(a);
        bool pinhole = m[1] == 0.0 && m[3] == 0.0 && m[6] == 0.0 && m[7] == 0.0 && m[8] == 1.0;
        cam->fx = m[0], cam->fy = m[4], cam->cx = m[2], cam->cy = m[5];
        Py_DECREF(a);
        if (!pinhole)
            PyErr_SetString(PyExc_ValueError, "K must be [[fx, 0, cx], [0, fy, cy], [0, 0, 1]] (no skew)");
        return pinhole;
    }
    if (numbers[0] == Py_None) {
        PyErr_SetString(PyExc_ValueError, any ? "fy, cx and cy need fx"
                                              : "give the intrinsics: K (3x3) or fx (and fy, cx, cy), in pixels, "
                                                "OpenCV's convention, or fov (vertical, degrees)");
        return false;
    }
    double v[4] = { 0, 0, 0.5 * (self->fb.width - 1), 0.5 * (self->fb.height - 1) };
    for (int k = 0; k < 4; k++)
        if (numbers[k] != Py_None && !parse_number(numbers[k], names[k], &v[k]))
            return false;
    if (numbers[1] == Py_None)
        v[1] = v[0];
    cam->fx = v[0], cam->fy = v[1], cam->cx = v[2], cam->cy = v[3];
    return true;
}

/* A name among `count` names, or -1. */
static int name_index(PyObject *name, const char *const *names, int count)
{
    for (int k = 0; PyUnicode_Check(name) && k < count; k++)
        if (PyUnicode_CompareWithASCIIString(name, names[k]) == 0)
            return k;
    return -1;
}

/* Three finite numbers: a point or a direction. */
static bool parse_vector(PyObject *obj, const char *name, double out[3])
{
    PyArrayObject *a = sr_py_array(obj, name, NPY_FLOAT64, 1, (npy_intp[]){ 3 }, "(3,)");
    if (!a)
        return false;
    const double *v = PyArray_DATA(a);
    bool finite = isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
    memcpy(out, v, 3 * sizeof *out);
    Py_DECREF(a);
    if (!finite)
        PyErr_Format(PyExc_ValueError, "%s: every entry must be finite", name);
    return finite;
}

/* The colour output's shading, its colour space (the command line's
 * default, sRGB) and its light: a direction in the poses' frame, into
 * softrast's world (z negated, as every mesh is stored: mesh.c). */
static bool parse_shading(PyObject *shade, PyObject *color_space, PyObject *light, job *j)
{
    int k = shade ? name_index(shade, SHADE_NAMES, SR_SHADE_COUNT) : SR_SHADE_LAMBERT;
    j->shade_given = shade != NULL;
    if (k < 0) {
        PyErr_Format(PyExc_ValueError, "shade: %R is not one of " SHADE_LIST, shade);
        return false;
    }
    j->shade = (sr_shade)k;
    int space = color_space ? name_index(color_space, COLOR_SPACE_NAMES, 2) : SR_COLOR_SRGB;
    if (space < 0) {
        PyErr_Format(PyExc_ValueError, "color_space: %R is not 'srgb' or 'raw'", color_space);
        return false;
    }
    j->color_space = (sr_color_space)space;
    double l[3] = { 0, 0, 0 };
    if (light != Py_None && !parse_vector(light, "light", l))
        return false;
    if (light != Py_None && l[0] == 0.0 && l[1] == 0.0 && l[2] == 0.0) {
        PyErr_SetString(PyExc_ValueError, "light: (0, 0, 0) has no direction");
        return false;
    }
    for (int i = 0; i < 3; i++)
        j->light[i] = (float)(i == 2 ? -l[i] : l[i]);
    return true;
}

static bool parse_outputs(PyObject *outputs, PyObject *normals, job *j)
{
    PyObject *seq = PyUnicode_Check(outputs) ? PyTuple_Pack(1, outputs)
                                             : PySequence_Fast(outputs, "outputs: a sequence of names among " OUT_LIST);
    if (!seq)
        return false;
    bool ok = true;
    for (Py_ssize_t i = 0; ok && i < PySequence_Fast_GET_SIZE(seq); i++) {
        PyObject *name = PySequence_Fast_GET_ITEM(seq, i);
        int k = name_index(name, OUT_NAMES, OUT_COUNT);
        if (k < 0) {
            PyErr_Format(PyExc_ValueError, "outputs: %R is not one of " OUT_LIST, name);
            ok = false;
        } else
            j->wanted[k] = true;
    }
    Py_DECREF(seq);
    if (!ok)
        return false;
    bool geometric = PyUnicode_Check(normals) && PyUnicode_CompareWithASCIIString(normals, "geometric") == 0;
    j->interpolated = PyUnicode_Check(normals) && PyUnicode_CompareWithASCIIString(normals, "interpolated") == 0;
    if (!geometric && !j->interpolated) {
        PyErr_Format(PyExc_ValueError, "normals: %R is not 'geometric' or 'interpolated'", normals);
        return false;
    }
    return true;
}

static double norm(const double v[3])
{
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

static void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* The world-to-camera pose w2c of a camera at eye looking at target with
 * up toward the top of the image, in the poses' frame (OpenCV's axes: x =
 * forward x up to the right, y down, z forward). In a right-handed frame
 * the image is not mirrored: a look-at from +z with up +y shows +x on the
 * right. NULL, or what is wrong with the three. */
static const char *look_at_w2c(const double eye[3], const double target[3], const double up[3], double w2c[4][4])
{
    double x[3], y[3], z[3];
    for (int k = 0; k < 3; k++)
        z[k] = target[k] - eye[k];
    double forward = norm(z), upward = norm(up);
    if (!(forward > 0.0) || !isfinite(forward))
        return "eye and target: the same point (or too far apart), no view direction";
    for (int k = 0; k < 3; k++)
        z[k] /= forward;
    cross(z, up, x);
    double side = norm(x);
    if (!(side > 1e-6 * upward))
        return "up: zero or along the view direction (target - eye)";
    for (int k = 0; k < 3; k++)
        x[k] /= side;
    cross(z, x, y);
    const double *rows[3] = { x, y, z };
    memset(w2c, 0, 4 * sizeof *w2c);
    for (int r = 0; r < 3; r++) {
        memcpy(w2c[r], rows[r], 3 * sizeof(double));
        w2c[r][3] = -(rows[r][0] * eye[0] + rows[r][1] * eye[1] + rows[r][2] * eye[2]);
    }
    w2c[3][3] = 1.0;
    return NULL;
}

/* A look-at argument: one point (3,), or for render_many one a frame
 * (N, 3) (*rows N) or one for all (3,) (*rows 1); every entry finite. */
static PyArrayObject *parse_points(PyObject *obj, const char *name, bool many, npy_intp *rows)
{
    PyArrayObject *any = many ? (PyArrayObject *)PyArray_FromAny(obj, NULL, 0, 0, 0, NULL) : NULL;
    bool stacked = any && PyArray_NDIM(any) == 2;
    Py_XDECREF(any);
    PyErr_Clear(); /* sr_py_array says what is wrong */
    const char *wanted = many ? "(N, 3) or (3,)" : "(3,)";
    PyArrayObject *a = stacked ? sr_py_array(obj, name, NPY_FLOAT64, 2, (npy_intp[]){ -1, 3 }, wanted)
                               : sr_py_array(obj, name, NPY_FLOAT64, 1, (npy_intp[]){ 3 }, wanted);
    if (!a)
        return NULL;
    *rows = stacked ? PyArray_DIM(a, 0) : 1;
    const double *v = PyArray_DATA(a);
    for (npy_intp i = 0; i < 3 * *rows; i++)
        if (!isfinite(v[i])) {
            PyErr_Format(PyExc_ValueError, "%s: every entry must be finite", name);
            Py_DECREF(a);
            return NULL;
        }
    return a;
}

/* The world-to-camera poses of the look-at camera, a new (4, 4) array, or
 * (N, 4, 4) for render_many: N is the rows of whichever of eye, target
 * and up give one a frame; the others are the same for every frame. */
static PyObject *look_at_poses(PyObject *eye_obj, PyObject *target_obj, PyObject *up_obj, bool many)
{
    static const char *const names[3] = { "eye", "target", "up" };
    static const double default_up[3] = { 0.0, 1.0, 0.0 };
    if (eye_obj == Py_None || target_obj == Py_None) {
        PyErr_SetString(PyExc_ValueError, "the look-at camera needs eye and target (and up, default (0, 1, 0))");
        return NULL;
    }
    PyObject *objs[3] = { eye_obj, target_obj, up_obj };
    PyArrayObject *points[3] = { NULL, NULL, NULL };
    npy_intp rows[3] = { 1, 1, 1 }, frames = 1;
    bool ok = true;
    for (int k = 0; ok && k < 3; k++) {
        ok = objs[k] == Py_None || (points[k] = parse_points(objs[k], names[k], many, &rows[k])) != NULL;
        if (ok && rows[k] != 1 && frames != 1 && rows[k] != frames) {
            PyErr_Format(PyExc_ValueError, "%s: %zd rows where another of eye, target and up has %zd", names[k],
                         rows[k], frames);
            ok = false;
        }
        frames = rows[k] != 1 ? rows[k] : frames;
    }
    npy_intp dims[3] = { frames, 4, 4 };
    PyArrayObject *a = ok ? (PyArrayObject *)PyArray_SimpleNew(many ? 3 : 2, many ? dims : dims + 1, NPY_FLOAT64)
                          : NULL;
    double(*w2c)[4][4] = a ? PyArray_DATA(a) : NULL;
    for (npy_intp i = 0; a && i < frames; i++) {
        const double *p[3];
        for (int k = 0; k < 3; k++)
            p[k] = !points[k] ? default_up : (const double *)PyArray_DATA(points[k]) + (rows[k] == 1 ? 0 : 3 * i);
        const char *wrong = look_at_w2c(p[0], p[1], p[2], w2c[i]);
        if (wrong && many)
            PyErr_Format(PyExc_ValueError, "frame %zd: %s", i, wrong);
        else if (wrong)
            PyErr_SetString(PyExc_ValueError, wrong);
        if (wrong)
            Py_CLEAR(a);
    }
    for (int k = 0; k < 3; k++)
        Py_XDECREF(points[k]);
    return (PyObject *)a;
}

/* Poses, world-to-camera, from w2c or c2w (one of them, or neither: one
 * identity pose when !many), checked with the rest of the camera: a new
 * array of *count poses, or NULL with an exception set. */
static double (*parse_poses(PyObject *w2c, PyObject *c2w, bool many, const sr_pinhole *cam, npy_intp *count))[4][4]
{
    const char *w2c_name = many ? "poses" : "pose", *c2w_name = many ? "poses_c2w" : "pose_c2w";
    if (w2c != Py_None && c2w != Py_None) {
        PyErr_Format(PyExc_ValueError, "give one of %s and %s, not both", w2c_name, c2w_name);
        return NULL;
    }
    bool inverse = c2w != Py_None;
    PyObject *given = inverse ? c2w : w2c;
    PyArrayObject *a = NULL;
    if (given == Py_None && many) {
        PyErr_SetString(PyExc_ValueError, "render_many needs poses (N, 4, 4), world-to-camera, poses_c2w, "
                                          "or eye and target");
        return NULL;
    }
    if (given != Py_None) {
        a = many ? sr_py_array(given, inverse ? c2w_name : w2c_name, NPY_FLOAT64, 3, (npy_intp[]){ -1, 4, 4 },
                               "(N, 4, 4)")
                 : sr_py_array(given, inverse ? c2w_name : w2c_name, NPY_FLOAT64, 2, (npy_intp[]){ 4, 4 }, "(4, 4)");
        if (!a)
            return NULL;
    }
    *count = many ? PyArray_DIM(a, 0) : 1;
    double(*poses)[4][4] = PyMem_Malloc((*count ? (size_t)*count : 1) * sizeof *poses);
    if (!poses) {
        Py_XDECREF(a);
        PyErr_NoMemory();
        return NULL;
    }
    static const double identity[4][4] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 0, 1 } };
    sr_error err = { "" };
    bool ok = true;
    for (npy_intp i = 0; ok && i < *count; i++) {
        const double(*p)[4] = a ? (const double(*)[4])PyArray_DATA(a) + 4 * i : identity;
        sr_pinhole check = *cam;
        if (inverse)
            ok = sr_pinhole_pose_from_c2w(p, check.w2c, &err);
        else
            memcpy(check.w2c, p, sizeof check.w2c);
        ok = ok && sr_pinhole_check(&check, &err);
        memcpy(poses[i], check.w2c, sizeof poses[i]);
        if (!ok && many)
            PyErr_Format(PyExc_ValueError, "%s[%zd]: %s", inverse ? c2w_name : w2c_name, i, err.message);
        else if (!ok)
            sr_py_raise(PyExc_ValueError, &err);
    }
    Py_XDECREF(a);
    if (!ok) {
        PyMem_Free(poses);
        return NULL;
    }
    return poses;
}

/* The draw's shading: the colour output's, else SR_SHADE_ID (the
 * cheapest; the ids plane is written in every mode). */
static sr_shade draw_shade(const job *j)
{
    return j->wanted[OUT_COLOR] ? j->shade : SR_SHADE_ID;
}

/* The draw a frame's outputs come from: colour, depth and ids into
 * self->fb (the ids plane is what sr_pinhole_resolve reads), a file's
 * BLEND parts blended over the rest as the command line draws them. */
static bool draw_view(sr_py_renderer *self, const sr_mesh *mesh, const sr_texture *texture, sr_pinhole *cam,
                      const job *j, sr_stats *stats, sr_error *err)
{
    sr_pinhole_fit_clip(cam, mesh);
    sr_draw_desc desc = { .mesh = mesh, .shade = draw_shade(j), .cull = SR_CULL_NONE, .threads = self->threads,
                          .workspace = self->workspace, .clear = true, .color_space = j->color_space,
                          .texture = j->wanted[OUT_COLOR] && texture->texels ? texture : NULL,
                          .point_size = j->points ? j->point_size : 0.0f };
    glm_vec3_copy((float *)j->light, desc.light_dir);
    sr_pinhole_matrices(cam, mesh, &self->fb, &desc);
    return sr_draw_layered(&self->fb, &desc, stats, err);
}

/* The colour output, (H, W, 3) uint8, from the draw's colour. */
static void write_color(sr_py_renderer *self, sr_shade shade, uint8_t *rgb)
{
    if (shade == SR_SHADE_DEPTH) /* as --shade depth: the written range from white (near) to dark gray */
        sr_framebuffer_depth_to_gray(&self->fb, self->fb.color);
    const uint32_t *packed = self->fb.color;
    for (size_t i = 0; i < (size_t)self->fb.width * (size_t)self->fb.height; i++)
        for (int k = 0; k < 3; k++)
            rgb[3 * i + k] = (uint8_t)(packed[i] >> (16 - 8 * k));
}

/* Part ids the caller gave (mesh.c's part_map) for the library's runs. */
static void map_parts(uint32_t *ids, size_t count, const uint32_t *part_map)
{
    for (size_t i = 0; i < count; i++)
        ids[i] = ids[i] ? part_map[ids[i] - 1] : 0;
}

/* One frame: clip planes fitted where 0, the view drawn, the outputs
 * resolved from its ids. Runs without the GIL. */
static bool render_one(sr_py_renderer *self, const sr_py_mesh *pm, const sr_mesh *mesh, sr_pinhole *cam,
                       const job *j, const sr_pinhole_outputs *out, uint8_t *color, sr_stats *stats, sr_error *err)
{
    if (!draw_view(self, mesh, &pm->texture, cam, j, stats, err) ||
        !sr_pinhole_resolve(cam, mesh, &self->fb, out, err))
        return false;
    if (color)
        write_color(self, j->shade, color);
    if (out->part_ids && pm->part_map && !j->points) /* a point has no face, so no part of the caller's */
        map_parts(out->part_ids, (size_t)self->fb.width * (size_t)self->fb.height, pm->part_map);
    return true;
}

static PyObject *stats_dict(const sr_stats *s)
{
    return Py_BuildValue("{sKsKsKsKsKsKsKsK}", "triangles", (unsigned long long)s->triangles, "points",
                         (unsigned long long)s->points, "rejected",
                         (unsigned long long)s->rejected, "nonfinite", (unsigned long long)s->nonfinite, "clipped",
                         (unsigned long long)s->clipped, "culled", (unsigned long long)s->culled, "drawn",
                         (unsigned long long)s->drawn, "fragments", (unsigned long long)s->fragments);
}

/* Claims the renderer for one call (refusing a second thread's), making
 * the workspace anew in a forked child. */
static bool claim(sr_py_renderer *self)
{
    if (self->pid != getpid()) {
        sr_workspace *workspace = sr_workspace_create(); /* the parent's is left: its threads are not here */
        if (!workspace) {
            PyErr_NoMemory();
            return false;
        }
        self->workspace = workspace;
        self->pid = getpid();
        self->busy = false;
    }
    if (!self->fb.color) {
        PyErr_SetString(PyExc_RuntimeError, "Renderer.__init__ was not called");
        return false;
    }
    if (self->busy) {
        PyErr_SetString(PyExc_RuntimeError, "this Renderer is rendering in another thread: "
                                            "use one Renderer per thread");
        return false;
    }
    self->busy = true;
    return true;
}

/* A mesh of display colours drawn under sRGB by a shading that reads them
 * (lambert, color) draws them decoded, as the command line does as it
 * loads a file: made once, with the GIL held (no render reads it now). */
static bool linear_colours(sr_py_mesh *mesh, const job *j)
{
    sr_shade shade = draw_shade(j);
    if (j->color_space != SR_COLOR_SRGB || (shade != SR_SHADE_LAMBERT && shade != SR_SHADE_COLOR) ||
        !mesh->mesh.colors || !mesh->display_colours || mesh->linear_colors)
        return true;
    mesh->linear_colors = malloc((size_t)mesh->mesh.vertex_count * sizeof *mesh->linear_colors);
    if (!mesh->linear_colors) {
        PyErr_NoMemory();
        return false;
    }
    sr_vertex_colours_to_linear(mesh->mesh.colors, mesh->linear_colors, mesh->mesh.vertex_count);
    return true;
}

/* With points, the mesh's point indices, made once with the GIL held (no
 * render reads them now). */
static bool point_indices(sr_py_mesh *mesh, const job *j)
{
    if (!j->points || mesh->point_indices)
        return true;
    mesh->point_indices = malloc((size_t)mesh->mesh.vertex_count * sizeof *mesh->point_indices);
    if (!mesh->point_indices) {
        PyErr_NoMemory();
        return false;
    }
    for (uint32_t i = 0; i < mesh->mesh.vertex_count; i++)
        mesh->point_indices[i] = i;
    return true;
}

/* The outputs of `frames` poses as a dict of new arrays (stacked when many). */
static PyObject *render_frames(sr_py_renderer *self, sr_py_mesh *mesh, const job *j, double (*poses)[4][4],
                               npy_intp frames, bool many)
{
    sr_error err = { "" };
    if (mesh->mesh.vertex_count == 0 || !mesh->mesh.positions) {
        PyErr_SetString(PyExc_ValueError, "the mesh is empty (Mesh.__init__ was not called)");
        return NULL;
    }
    bool cloud = sr_mesh_triangle_slots(&mesh->mesh) == 0;
    if (!j->points && cloud) {
        PyErr_SetString(PyExc_ValueError, "the mesh has no faces (a point cloud): render it with points=True");
        return NULL;
    }
    bool lit = draw_shade(j) == SR_SHADE_LAMBERT || draw_shade(j) == SR_SHADE_NORMAL;
    /* a point's normal is its vertex's, as the command line's --points makes them */
    bool vertex_normals = j->wanted[OUT_NORMALS] && (j->interpolated || j->points);
    bool make_normals = (vertex_normals || lit) && !mesh->mesh.normals;
    /* with the GIL held: no render reads them now */
    if (make_normals && !cloud && !sr_mesh_compute_normals(&mesh->mesh, &err))
        return sr_py_raise(PyExc_ValueError, &err);
    /* A cloud without normals has no faces to make them from: 0, as the
     * command line's, for this call only, so mesh.normals stays None. */
    vec3 *no_normals = NULL;
    if (make_normals && cloud && !(no_normals = PyMem_Calloc(mesh->mesh.vertex_count, sizeof(vec3))))
        return PyErr_NoMemory();
    if (!linear_colours(mesh, j) || !point_indices(mesh, j)) {
        PyMem_Free(no_normals);
        return NULL;
    }
    npy_intp width = self->fb.width, height = self->fb.height, pixels = width * height;
    PyArrayObject *arrays[OUT_COUNT] = { 0 };
    sr_stats *stats = PyMem_Calloc(frames ? (size_t)frames : 1, sizeof *stats);
    bool ok = stats != NULL;
    if (!ok)
        PyErr_NoMemory();
    for (int k = 0; ok && k < OUT_COUNT; k++) {
        if (!j->wanted[k])
            continue;
        npy_intp dims[4] = { frames, height, width, 3 };
        int nd = (many ? 3 : 2) + (k == OUT_NORMALS || k == OUT_COLOR);
        int type = k == OUT_COLOR ? NPY_UINT8 : k == OUT_FACE_IDS || k == OUT_PART_IDS ? NPY_UINT32 : NPY_FLOAT32;
        ok = (arrays[k] = (PyArrayObject *)PyArray_SimpleNew(nd, many ? dims : dims + 1, type)) != NULL;
    }
    ok = ok && claim(self);
    if (ok) {
        mesh->renders++;
        sr_mesh m = mesh->mesh; /* a copy: Mesh's normals may be filled in meanwhile */
        if (mesh->linear_colors && j->color_space == SR_COLOR_SRGB)
            m.colors = mesh->linear_colors;
        if (no_normals)
            m.normals = no_normals;
        if (j->points) { /* the mesh's arrays under the point topology, as the command line's --points borrows them */
            m.topology = SR_POINT_LIST;
            m.index_count = m.vertex_count;
            m.indices = mesh->point_indices;
            m.parts = NULL;
            m.part_count = 0;
        }
        for (npy_intp i = 0; ok && i < frames; i++) {
            sr_pinhole cam = j->cam;
            memcpy(cam.w2c, poses[i], sizeof cam.w2c);
#define FRAME(k, type, channels) \
    (arrays[k] ? (type *)PyArray_DATA(arrays[k]) + (size_t)(i * pixels * (channels)) : NULL)
            sr_pinhole_outputs out = { .depth = FRAME(OUT_DEPTH, float, 1), .range = FRAME(OUT_RANGE, float, 1),
                                       .face_ids = FRAME(OUT_FACE_IDS, uint32_t, 1),
                                       .part_ids = FRAME(OUT_PART_IDS, uint32_t, 1),
                                       .normals = FRAME(OUT_NORMALS, float, 3),
                                       .interpolated_normals = j->interpolated, .invalid = j->invalid,
                                       .threads = self->threads };
            uint8_t *color = FRAME(OUT_COLOR, uint8_t, 3);
#undef FRAME
            Py_BEGIN_ALLOW_THREADS
            ok = render_one(self, mesh, &m, &cam, j, &out, color, &stats[i], &err);
            Py_END_ALLOW_THREADS
            if (!ok)
                sr_py_raise(PyExc_ValueError, &err);
            else if (i + 1 < frames && PyErr_CheckSignals() < 0) /* Ctrl-C between frames */
                ok = false;
        }
        mesh->renders--;
        self->busy = false;
    }
    PyObject *result = ok ? PyDict_New() : NULL;
    for (int k = 0; result && k < OUT_COUNT; k++)
        if (arrays[k] && PyDict_SetItemString(result, OUT_NAMES[k], (PyObject *)arrays[k]) < 0)
            Py_CLEAR(result);
    PyObject *counts = result ? (many ? PyList_New(frames) : stats_dict(&stats[0])) : NULL;
    for (npy_intp i = 0; many && counts && i < frames; i++) {
        PyObject *d = stats_dict(&stats[i]);
        if (!d)
            Py_CLEAR(counts);
        else
            PyList_SET_ITEM(counts, i, d);
    }
    if (result && (!counts || PyDict_SetItemString(result, "stats", counts) < 0))
        Py_CLEAR(result);
    Py_XDECREF(counts);
    for (int k = 0; k < OUT_COUNT; k++)
        Py_XDECREF(arrays[k]);
    PyMem_Free(stats);
    PyMem_Free(no_normals);
    return result;
}

/* The keywords render and render_many share: the intrinsics, and after the poses the rest. */
#define CAMERA_KEYWORDS "K", "fx", "fy", "cx", "cy", "fov"
#define OUTPUT_KEYWORDS \
    "near", "far", "outputs", "normals", "invalid", "shade", "light", "color_space", "points", "point_size"

static PyObject *render_call(sr_py_renderer *self, PyObject *args, PyObject *kwargs, bool many)
{
    static char *single[] = { "mesh", CAMERA_KEYWORDS, "pose", "pose_c2w", "eye", "target", "up", OUTPUT_KEYWORDS,
                              NULL };
    static char *stacked[] = { "mesh", "poses", CAMERA_KEYWORDS, "poses_c2w", "eye", "target", "up", OUTPUT_KEYWORDS,
                               NULL };
    sr_py_mesh *mesh;
    PyObject *K = Py_None, *numbers[4] = { Py_None, Py_None, Py_None, Py_None }, *fov = Py_None;
    PyObject *w2c = Py_None, *c2w = Py_None, *eye = Py_None, *target = Py_None, *up = Py_None;
    PyObject *outputs = NULL, *normals = NULL, *shade = NULL, *light = Py_None, *color_space = NULL;
    double near = 0.0, far = 0.0;
    float invalid = 0.0f, point_size = 1.0f;
    int points = 0;
    int parsed = many ? PyArg_ParseTupleAndKeywords(args, kwargs, "O!|O$OOOOOOOOOOddOOfOOOpf:render_many", stacked,
                                                    &sr_py_mesh_type, &mesh, &w2c, &K, &numbers[0], &numbers[1],
                                                    &numbers[2], &numbers[3], &fov, &c2w, &eye, &target, &up, &near,
                                                    &far, &outputs, &normals, &invalid, &shade, &light,
                                                    &color_space, &points, &point_size)
                      : PyArg_ParseTupleAndKeywords(args, kwargs, "O!|$OOOOOOOOOOOddOOfOOOpf:render", single,
                                                    &sr_py_mesh_type, &mesh, &K, &numbers[0], &numbers[1],
                                                    &numbers[2], &numbers[3], &fov, &w2c, &c2w, &eye, &target, &up,
                                                    &near, &far, &outputs, &normals, &invalid, &shade, &light,
                                                    &color_space, &points, &point_size);
    if (!parsed)
        return NULL;
    if (!(point_size >= 1.0f && point_size <= SR_MAX_POINT_SIZE)) {
        char text[32];
        snprintf(text, sizeof text, "%.9g", (double)point_size);
        PyErr_Format(PyExc_ValueError, "point_size: %s is not within 1 .. %d pixels", text, (int)SR_MAX_POINT_SIZE);
        return NULL;
    }
    bool look_at = eye != Py_None || target != Py_None || up != Py_None;
    if (look_at && (w2c != Py_None || c2w != Py_None)) {
        PyErr_SetString(PyExc_ValueError, "a pose and the look-at camera (eye, target, up) both place the camera: "
                                          "give one");
        return NULL;
    }
    job j = { .cam = { .near = near, .far = far }, .invalid = invalid, .points = points, .point_size = point_size };
    PyObject *depth_only = outputs ? NULL : PyUnicode_FromString("depth");
    PyObject *geometric = normals ? NULL : PyUnicode_FromString("geometric");
    bool ok = (outputs || depth_only) && (normals || geometric) &&
              parse_outputs(outputs ? outputs : depth_only, normals ? normals : geometric, &j) &&
              parse_shading(shade, color_space, light, &j) && parse_intrinsics(self, K, numbers, fov, look_at, &j.cam);
    Py_XDECREF(depth_only);
    Py_XDECREF(geometric);
    if (ok && j.points && !j.shade_given && mesh->mesh.colors)
        j.shade = SR_SHADE_COLOR; /* a point cloud's own colours, as the command line's --points */
    PyObject *looking = ok && look_at ? look_at_poses(eye, target, up, many) : NULL;
    npy_intp frames = 0;
    double(*poses)[4][4] = ok && (looking || !look_at) ? parse_poses(looking ? looking : w2c, c2w, many, &j.cam,
                                                                     &frames)
                                                       : NULL;
    Py_XDECREF(looking);
    if (!poses)
        return NULL;
    PyObject *result = render_frames(self, mesh, &j, poses, frames, many);
    PyMem_Free(poses);
    return result;
}

static PyObject *renderer_render(sr_py_renderer *self, PyObject *args, PyObject *kwargs)
{
    return render_call(self, args, kwargs, false);
}

static PyObject *renderer_render_many(sr_py_renderer *self, PyObject *args, PyObject *kwargs)
{
    return render_call(self, args, kwargs, true);
}

static PyObject *renderer_width(sr_py_renderer *self, void *closure)
{
    (void)closure;
    return PyLong_FromLong(self->fb.width);
}

static PyObject *renderer_height(sr_py_renderer *self, void *closure)
{
    (void)closure;
    return PyLong_FromLong(self->fb.height);
}

static PyObject *renderer_threads(sr_py_renderer *self, void *closure)
{
    (void)closure;
    return PyLong_FromLong(self->threads);
}

static PyObject *renderer_repr(sr_py_renderer *self)
{
    return PyUnicode_FromFormat("<softrast.Renderer %dx%d, %d threads>", self->fb.width, self->fb.height,
                                self->threads);
}

static PyMethodDef renderer_methods[] = {
    { "render", (PyCFunction)(void (*)(void))renderer_render, METH_VARARGS | METH_KEYWORDS,
      "render(mesh, *, K=None, fx=None, fy=None, cx=None, cy=None, fov=None, pose=None, pose_c2w=None,\n"
      "       eye=None, target=None, up=None, near=0, far=0, outputs=('depth',), normals='geometric',\n"
      "       invalid=0.0, shade='lambert', light=None, color_space='srgb', points=False, point_size=1) -> dict\n\n"
      "One pinhole view of mesh (OpenCV's convention; pose world-to-camera, identity if not given, or\n"
      "the look-at camera eye, target, up). Returns new arrays for the outputs asked for among 'color',\n"
      "'depth', 'range', 'face_ids', 'part_ids', 'normals', and 'stats' (the draw's counts). points=True\n"
      "draws the mesh's vertices (a point cloud's) as squares point_size pixels wide, face_ids then\n"
      "vertex index + 1; shade defaults to 'color' for a mesh with colours." },
    { "render_many", (PyCFunction)(void (*)(void))renderer_render_many, METH_VARARGS | METH_KEYWORDS,
      "render_many(mesh, poses, *, K=None, ..., poses_c2w=None, eye=None, target=None, up=None, ...) -> dict\n\n"
      "render() for each of N poses (N, 4, 4), or of N look-at cameras (eye, target, up each (N, 3),\n"
      "or (3,) for all): the outputs stacked (N, H, W[, 3]), 'stats' a list." },
    { NULL },
};

static PyGetSetDef renderer_getset[] = {
    { "width", (getter)renderer_width, NULL, "image width in pixels", NULL },
    { "height", (getter)renderer_height, NULL, "image height in pixels", NULL },
    { "threads", (getter)renderer_threads, NULL, "threads a draw uses, the caller's included", NULL },
    { NULL },
};

PyTypeObject sr_py_renderer_type = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "softrast.Renderer",
    .tp_doc = "Renderer(width, height, threads=0): renders width x height images, reusing its buffers and\n"
              "threads from call to call (threads 0: one a core). One call at a time: a second thread's\n"
              "call while one runs raises RuntimeError; give each thread its own Renderer.",
    .tp_basicsize = sizeof(sr_py_renderer),
    .tp_flags = Py_TPFLAGS_DEFAULT | Py_TPFLAGS_BASETYPE,
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)renderer_init,
    .tp_dealloc = (destructor)renderer_dealloc,
    .tp_repr = (reprfunc)renderer_repr,
    .tp_methods = renderer_methods,
    .tp_getset = renderer_getset,
};
