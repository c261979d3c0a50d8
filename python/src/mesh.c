/* softrast.Mesh: a triangle mesh copied from numpy arrays, or loaded from a
 * file by sr_mesh_load. Positions are given in the file's frame (the frame
 * of the poses), and a mesh from arrays is stored as a loader stores a
 * file's: z negated, winding reversed (z_negated), which sr_pinhole_* undo.
 * So the same mesh from arrays and from a file is the same sr_mesh, and the
 * colour output's light and normal shading are the command line's. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io/mesh_origin.h"    /* the loaders' rule for a mesh's origin, kept in one place */
#include "io/vertex_colours.h" /* which files' colours are sRGB, and their decoding: the command line's */
#include "softrast/files.h"
#include "softrast_py.h"

/* Frees what the mesh holds and leaves it empty. */
static void mesh_clear(sr_py_mesh *self)
{
    sr_mesh_free(&self->mesh);
    sr_texture_free(&self->texture);
    sr_material_textures_free(&self->material_textures);
    free(self->part_map);
    self->part_map = NULL;
    free(self->linear_colors);
    self->linear_colors = NULL;
    free(self->point_indices);
    self->point_indices = NULL;
}

static void mesh_dealloc(sr_py_mesh *self)
{
    mesh_clear(self);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

/* Raises ValueError "name[row, column] = value: why"; returns false. */
static bool bad_value(const char *name, npy_intp i, int columns, double value, const char *why)
{
    char text[64];
    snprintf(text, sizeof text, "%.9g", value);
    PyErr_Format(PyExc_ValueError, "%s[%zd, %zd] = %s: %s", name, i / columns, i % columns, text, why);
    return false;
}

/* z of the file's frame in softrast's world, as the loaders store it. */
static double world_coordinate(const double *p, int k)
{
    return k == 2 ? -p[k] : p[k];
}

/* The positions, read in double, stored as float relative to the origin a
 * loader would give them (io/mesh_origin.h): a mesh far from the world
 * origin keeps its float precision, and a mesh near it is stored as given,
 * so a mesh from arrays and the same mesh read from a file render alike.
 * NaN and inf stay (the draw drops their triangles and counts them). */
static void set_positions(sr_mesh *mesh, const double *p)
{
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (uint32_t i = 0; i < mesh->vertex_count; i++) {
        const double *v = p + 3 * (size_t)i;
        if (isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]))
            for (int k = 0; k < 3; k++) {
                lo[k] = fmin(lo[k], world_coordinate(v, k));
                hi[k] = fmax(hi[k], world_coordinate(v, k));
            }
    }
    if (lo[0] <= hi[0])
        sr_mesh_origin_for_bounds(lo, hi, mesh->origin);
    for (uint32_t i = 0; i < mesh->vertex_count; i++)
        for (int k = 0; k < 3; k++)
            mesh->positions[i][k] = (float)(world_coordinate(p + 3 * (size_t)i, k) - mesh->origin[k]);
    mesh->z_negated = true;
}

/* An optional per-vertex attribute of `columns` floats into dst (rows of
 * them), finite; colours (unit) in 0..1, or uint8 read as 0..255; normals
 * (columns 3, not unit) into softrast's world, z negated. */
static bool copy_attribute(PyObject *obj, const char *name, npy_intp rows, int columns, bool unit, float *dst)
{
    bool normals = columns == 3 && !unit;
    bool bytes = PyArray_Check(obj) && PyArray_TYPE((PyArrayObject *)obj) == NPY_UINT8;
    char wanted[48];
    snprintf(wanted, sizeof wanted, "(N, %d), N the positions' rows", columns);
    PyArrayObject *a = sr_py_array(obj, name, NPY_FLOAT64, 2, (npy_intp[]){ rows, columns }, wanted);
    if (!a)
        return false;
    const double *v = PyArray_DATA(a);
    bool ok = true;
    for (npy_intp i = 0; ok && i < rows * columns; i++) {
        float x = bytes ? (float)v[i] / 255.0f : (float)v[i];
        if (!isfinite(x))
            ok = bad_value(name, i, columns, v[i], "not a finite float32");
        else if (unit && !(x >= 0.0f && x <= 1.0f))
            ok = bad_value(name, i, columns, v[i], "colours are 0..1 (or uint8)");
        dst[i] = normals && i % 3 == 2 ? -x : x;
    }
    Py_DECREF(a);
    return ok;
}

/* Part ids per face, 1 or more: the mesh's parts become the runs of equal
 * ids (sr_mesh_part), and part_map each run's id. */
static bool set_parts(sr_py_mesh *self, PyObject *obj, npy_intp triangles)
{
    PyArrayObject *a = sr_py_array(obj, "part_ids", NPY_INT64, 1, (npy_intp[]){ triangles }, "(M,), M the faces' rows");
    if (!a)
        return false;
    const int64_t *id = PyArray_DATA(a);
    uint32_t runs = 0;
    for (npy_intp t = 0; t < triangles; t++) {
        if (id[t] < 1 || id[t] > (int64_t)UINT32_MAX) {
            PyErr_Format(PyExc_ValueError, "part_ids[%zd] = %lld: part ids are 1 to 2^32 - 1 (0 marks no surface)",
                         t, (long long)id[t]);
            Py_DECREF(a);
            return false;
        }
        runs += t == 0 || id[t] != id[t - 1];
    }
    self->mesh.parts = malloc(runs * sizeof *self->mesh.parts);
    self->part_map = malloc(runs * sizeof *self->part_map);
    if (!self->mesh.parts || !self->part_map) {
        Py_DECREF(a);
        PyErr_NoMemory();
        return false;
    }
    uint32_t run = 0;
    for (npy_intp t = 0; t < triangles; t++) {
        if (t > 0 && id[t] == id[t - 1]) {
            self->mesh.parts[run - 1].triangle_count++;
            continue;
        }
        self->mesh.parts[run] = (sr_mesh_part){ .first_triangle = (uint32_t)t, .triangle_count = 1 };
        self->part_map[run++] = (uint32_t)id[t];
    }
    self->mesh.part_count = runs;
    Py_DECREF(a);
    return true;
}

/* An H x W x 3 or 4 uint8 image (row 0 at the top; alpha is not used) as
 * the mesh's texture. */
static bool set_texture(sr_texture *tex, PyObject *obj)
{
    PyArrayObject *a = (PyArrayObject *)PyArray_FromAny(obj, NULL, 0, 0, 0, NULL);
    if (!a) {
        PyErr_Clear();
        PyErr_SetString(PyExc_ValueError, "texture: not an array (an (H, W, 3) or (H, W, 4) uint8 image)");
        return false;
    }
    PyObject *shape = NULL;
    if (PyArray_TYPE(a) != NPY_UINT8)
        PyErr_Format(PyExc_ValueError, "texture: dtype %S is not uint8", (PyObject *)PyArray_DESCR(a));
    else if (PyArray_NDIM(a) != 3 || (PyArray_DIM(a, 2) != 3 && PyArray_DIM(a, 2) != 4)) {
        if ((shape = sr_py_shape_text(a)))
            PyErr_Format(PyExc_ValueError, "texture: shape %U where (H, W, 3) or (H, W, 4) is wanted", shape);
    } else if (PyArray_DIM(a, 0) < 1 || PyArray_DIM(a, 1) < 1 || PyArray_DIM(a, 0) > SR_MAX_TEXTURE_SIDE ||
               PyArray_DIM(a, 1) > SR_MAX_TEXTURE_SIDE)
        PyErr_Format(PyExc_ValueError, "texture: %zd x %zd texels; each side 1 to %d", PyArray_DIM(a, 1),
                     PyArray_DIM(a, 0), SR_MAX_TEXTURE_SIDE);
    Py_XDECREF(shape);
    PyArrayObject *c = PyErr_Occurred() ? NULL : PyArray_GETCONTIGUOUS(a);
    Py_DECREF(a);
    if (!c)
        return false;
    npy_intp height = PyArray_DIM(c, 0), width = PyArray_DIM(c, 1), channels = PyArray_DIM(c, 2);
    tex->texels = malloc((size_t)(width * height) * sizeof *tex->texels);
    if (!tex->texels) {
        Py_DECREF(c);
        PyErr_NoMemory();
        return false;
    }
    const uint8_t *rgb = PyArray_DATA(c);
    for (npy_intp i = 0; i < width * height; i++, rgb += channels)
        tex->texels[i] = (uint32_t)rgb[0] << 16 | (uint32_t)rgb[1] << 8 | rgb[2];
    tex->width = (int)width;
    tex->height = (int)height;
    Py_DECREF(c);
    return true;
}

/* The optional attributes of mesh_init, after the positions and faces. */
static bool set_attributes(sr_py_mesh *self, PyObject *const given[5], npy_intp vertices, npy_intp triangles)
{
    sr_mesh *m = &self->mesh;
    PyObject *normals = given[0], *colors = given[1], *uvs = given[2], *parts = given[3], *texture = given[4];
    if (texture != Py_None && uvs == Py_None) {
        PyErr_SetString(PyExc_ValueError, "texture: needs uvs, (N, 2) texture coordinates");
        return false;
    }
    return (normals == Py_None || copy_attribute(normals, "normals", vertices, 3, false, &m->normals[0][0])) &&
           (colors == Py_None || copy_attribute(colors, "colors", vertices, 3, true, &m->colors[0][0])) &&
           (uvs == Py_None || copy_attribute(uvs, "uvs", vertices, 2, false, &m->uvs[0][0])) &&
           (parts == Py_None || set_parts(self, parts, triangles)) &&
           (texture == Py_None || set_texture(&self->texture, texture));
}

static int mesh_init(sr_py_mesh *self, PyObject *args, PyObject *kwargs)
{
    static char *names[] = { "positions", "faces", "normals", "colors", "uvs", "part_ids", "texture", NULL };
    PyObject *positions_obj, *faces_obj = Py_None, *given[5] = { Py_None, Py_None, Py_None, Py_None, Py_None };
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O|OOO$OOO:Mesh", names, &positions_obj, &faces_obj, &given[0],
                                     &given[1], &given[2], &given[3], &given[4]))
        return -1;
    if (self->renders) {
        PyErr_SetString(PyExc_RuntimeError, "Mesh.__init__ on a mesh another thread is rendering");
        return -1;
    }
    mesh_clear(self);
    PyArrayObject *positions = sr_py_array(positions_obj, "positions", NPY_FLOAT64, 2, (npy_intp[]){ -1, 3 }, "(N, 3)");
    /* no faces: a point cloud, rendered with points=True */
    npy_intp none[2] = { 0, 3 };
    PyObject *no_faces = faces_obj == Py_None ? PyArray_ZEROS(2, none, NPY_INT64, 0) : NULL;
    PyArrayObject *faces = positions && (no_faces || faces_obj != Py_None)
                               ? sr_py_array(no_faces ? no_faces : faces_obj, "faces", NPY_INT64, 2,
                                             (npy_intp[]){ -1, 3 }, "(M, 3)")
                               : NULL;
    Py_XDECREF(no_faces);
    int status = -1;
    if (!faces)
        goto done;
    npy_intp vertices = PyArray_DIM(positions, 0), triangles = PyArray_DIM(faces, 0);
    if (vertices == 0) {
        PyErr_Format(PyExc_ValueError, "an empty mesh (0 vertices, %zd faces): nothing to render", triangles);
        goto done;
    }
    if ((uint64_t)vertices > UINT32_MAX || (uint64_t)triangles > UINT32_MAX / 3) {
        PyErr_Format(PyExc_ValueError, "a mesh of %zd vertices and %zd faces is past softrast's 32-bit indices",
                     vertices, triangles);
        goto done;
    }
    const int64_t *f = PyArray_DATA(faces);
    for (npy_intp i = 0; i < 3 * triangles; i++)
        if (f[i] < 0 || f[i] > (int64_t)UINT32_MAX) {
            PyErr_Format(PyExc_ValueError, "faces[%zd, %zd] = %lld: a vertex index must be 0 or more", i / 3, i % 3,
                         (long long)f[i]);
            goto done;
        }
    sr_error err;
    if (!sr_mesh_alloc(&self->mesh, (uint32_t)vertices, (uint32_t)(3 * triangles), given[0] != Py_None,
                       given[2] != Py_None, given[1] != Py_None, &err)) {
        sr_py_raise(PyExc_MemoryError, &err);
        goto done;
    }
    set_positions(&self->mesh, PyArray_DATA(positions));
    /* the winding reversed with z; an index past the vertices: sr_draw refuses it */
    for (npy_intp i = 0; i < 3 * triangles; i++)
        self->mesh.indices[i] = (uint32_t)f[i % 3 == 0 ? i : i % 3 == 1 ? i + 1 : i - 1];
    if (!set_attributes(self, given, vertices, triangles)) {
        mesh_clear(self);
        goto done;
    }
    self->mesh.topology = SR_TRIANGLE_LIST;
    self->display_colours = true;
    sr_mesh_update_bounds(&self->mesh);
    status = 0;
done:
    Py_XDECREF(positions);
    Py_XDECREF(faces);
    return status;
}

/* The texture files that did not load, for the UserWarnings raised once
 * the GIL is held again. */
typedef struct untextured {
    sr_error *why;
    uint32_t count;
    bool out_of_memory;
} untextured;

static void note_untextured(void *context, const sr_error *why)
{
    untextured *u = context;
    sr_error *grown = realloc(u->why, (u->count + 1) * sizeof *grown);
    if (!grown) {
        u->out_of_memory = true;
        return;
    }
    u->why = grown;
    u->why[u->count++] = *why;
}

static PyObject *mesh_load(PyObject *cls, PyObject *args)
{
    PyObject *path = NULL;
    if (!PyArg_ParseTuple(args, "O&:load", PyUnicode_FSConverter, &path))
        return NULL;
    sr_py_mesh *self = (sr_py_mesh *)((PyTypeObject *)cls)->tp_alloc((PyTypeObject *)cls, 0);
    if (!self) {
        Py_DECREF(path);
        return NULL;
    }
    sr_error err;
    untextured missing = { 0 };
    bool ok, textures = true;
    Py_BEGIN_ALLOW_THREADS
    ok = sr_mesh_load(&self->mesh, &self->texture, PyBytes_AS_STRING(path), &err);
    textures =
        !ok || sr_material_textures_load(&self->mesh, &self->material_textures, note_untextured, &missing, &err);
    Py_END_ALLOW_THREADS
    if (!ok)
        sr_py_raise(PyExc_OSError, &err);
    else if (!textures || missing.out_of_memory)
        PyErr_NoMemory();
    else if (self->mesh.vertex_count == 0 || !self->mesh.positions)
        PyErr_Format(PyExc_ValueError, "%s: an empty mesh (no vertices), nothing to render",
                     PyBytes_AS_STRING(path));
    /* as the command line: a model shared without its textures still draws */
    for (uint32_t i = 0; !PyErr_Occurred() && i < missing.count; i++)
        PyErr_WarnFormat(PyExc_UserWarning, 1, "%s; its materials are drawn untextured, in their base colour",
                         missing.why[i].message);
    free(missing.why);
    self->display_colours = sr_vertex_colours_are_display(PyBytes_AS_STRING(path));
    Py_DECREF(path);
    if (PyErr_Occurred()) {
        Py_DECREF(self);
        return NULL;
    }
    if (!self->mesh.bounded)
        sr_mesh_update_bounds(&self->mesh);
    return (PyObject *)self;
}

/* The positions in the file's frame: float32 as stored, or float64 when the
 * loader kept them relative to an origin (a mesh far from the world's). */
static PyObject *mesh_positions(sr_py_mesh *self, void *closure)
{
    (void)closure;
    const sr_mesh *m = &self->mesh;
    bool offset = m->origin[0] != 0.0 || m->origin[1] != 0.0 || m->origin[2] != 0.0;
    npy_intp dims[2] = { m->vertex_count, 3 };
    PyArrayObject *a = (PyArrayObject *)PyArray_SimpleNew(2, dims, offset ? NPY_FLOAT64 : NPY_FLOAT32);
    if (!a)
        return NULL;
    for (uint32_t i = 0; i < m->vertex_count; i++)
        for (int k = 0; k < 3; k++) {
            double sign = k == 2 && m->z_negated ? -1.0 : 1.0;
            if (offset)
                ((double *)PyArray_DATA(a))[3 * i + k] = sign * (m->origin[k] + m->positions[i][k]);
            else
                ((float *)PyArray_DATA(a))[3 * i + k] = (float)sign * m->positions[i][k];
        }
    return (PyObject *)a;
}

/* The faces in the file's winding (a loader reversed it with the z flip),
 * int64 (M, 3): the arrays Mesh(positions, faces) takes back. */
static PyObject *mesh_faces(sr_py_mesh *self, void *closure)
{
    (void)closure;
    const sr_mesh *m = &self->mesh;
    if (m->topology != SR_TRIANGLE_LIST) {
        PyErr_SetString(PyExc_ValueError, "faces: the mesh is a triangle strip");
        return NULL;
    }
    npy_intp dims[2] = { m->index_count / 3, 3 };
    PyArrayObject *a = (PyArrayObject *)PyArray_SimpleNew(2, dims, NPY_INT64);
    if (!a)
        return NULL;
    int64_t *f = PyArray_DATA(a);
    for (npy_intp t = 0; t < dims[0]; t++)
        for (int k = 0; k < 3; k++)
            f[3 * t + k] = m->indices[3 * t + (m->z_negated && k ? 3 - k : k)];
    return (PyObject *)a;
}

enum { ATTRIBUTE_NORMALS, ATTRIBUTE_UVS, ATTRIBUTE_COLORS };

/* A copy of a per-vertex attribute, float32 (N, 3) or (N, 2), in the
 * file's frame (normals' z as given); None when the mesh has none. */
static PyObject *mesh_attribute(sr_py_mesh *self, void *closure)
{
    const sr_mesh *m = &self->mesh;
    int which = *(const int *)closure, columns = which == ATTRIBUTE_UVS ? 2 : 3;
    const float *v = which == ATTRIBUTE_NORMALS ? (const float *)m->normals
                     : which == ATTRIBUTE_UVS   ? (const float *)m->uvs
                                                : (const float *)m->colors;
    if (!v)
        Py_RETURN_NONE;
    npy_intp dims[2] = { m->vertex_count, columns };
    PyArrayObject *a = (PyArrayObject *)PyArray_SimpleNew(2, dims, NPY_FLOAT32);
    if (!a)
        return NULL;
    float *out = PyArray_DATA(a);
    for (size_t i = 0; i < (size_t)m->vertex_count * (size_t)columns; i++)
        out[i] = which == ATTRIBUTE_NORMALS && i % 3 == 2 && m->z_negated ? -v[i] : v[i];
    return (PyObject *)a;
}

static const int NORMALS = ATTRIBUTE_NORMALS, UVS = ATTRIBUTE_UVS, COLORS = ATTRIBUTE_COLORS;

/* The texture `texture` gives: the one given as an array or embedded in the
 * file, else the first material's that has one (in the materials' order;
 * a file's parts may each draw their own); NULL for none. */
static const sr_texture *first_texture(const sr_py_mesh *self)
{
    if (self->texture.texels)
        return &self->texture;
    for (uint32_t i = 0; i < self->mesh.material_count; i++) {
        const sr_texture *t = self->mesh.materials[i].texture;
        if (t && t->texels)
            return t;
    }
    return NULL;
}

/* A copy of the texture, (H, W, 3) uint8, row 0 at the top; None without one. */
static PyObject *mesh_texture(sr_py_mesh *self, void *closure)
{
    (void)closure;
    const sr_texture *t = first_texture(self);
    if (!t)
        Py_RETURN_NONE;
    npy_intp dims[3] = { t->height, t->width, 3 };
    PyArrayObject *a = (PyArrayObject *)PyArray_SimpleNew(3, dims, NPY_UINT8);
    if (!a)
        return NULL;
    uint8_t *rgb = PyArray_DATA(a);
    for (size_t i = 0; i < (size_t)t->width * (size_t)t->height; i++)
        for (int k = 0; k < 3; k++)
            rgb[3 * i + k] = (uint8_t)(t->texels[i] >> (16 - 8 * k));
    return (PyObject *)a;
}

/* The file's face of each triangle, int64 (M,) from 0: a polygon fanned
 * into triangles names one face for all of them (identity where the
 * loader kept no map: a mesh from arrays, or a file of triangles). */
static PyObject *mesh_file_faces(sr_py_mesh *self, void *closure)
{
    (void)closure;
    npy_intp count = sr_mesh_triangle_slots(&self->mesh);
    PyArrayObject *a = (PyArrayObject *)PyArray_SimpleNew(1, &count, NPY_INT64);
    if (!a)
        return NULL;
    int64_t *out = PyArray_DATA(a);
    for (npy_intp i = 0; i < count; i++)
        out[i] = self->mesh.file_faces ? self->mesh.file_faces[i] : i;
    return (PyObject *)a;
}

static PyObject *mesh_vertex_count(sr_py_mesh *self, void *closure)
{
    (void)closure;
    return PyLong_FromUnsignedLong(self->mesh.vertex_count);
}

static PyObject *mesh_triangle_count(sr_py_mesh *self, void *closure)
{
    (void)closure;
    return PyLong_FromUnsignedLong(sr_mesh_triangle_slots(&self->mesh));
}

static PyObject *mesh_part_count(sr_py_mesh *self, void *closure)
{
    (void)closure;
    uint32_t count = self->mesh.part_count ? self->mesh.part_count : 1;
    for (uint32_t run = 0; self->part_map && run < self->mesh.part_count; run++)
        count = run == 0 || self->part_map[run] > count ? self->part_map[run] : count;
    return PyLong_FromUnsignedLong(count);
}

static PyObject *mesh_repr(sr_py_mesh *self)
{
    return PyUnicode_FromFormat("<softrast.Mesh: %u vertices, %u triangles>", self->mesh.vertex_count,
                                sr_mesh_triangle_slots(&self->mesh));
}

static PyMethodDef mesh_methods[] = {
    { "load", mesh_load, METH_VARARGS | METH_CLASS,
      "Mesh.load(path): any mesh file `softrast render` opens (OBJ, glTF, PLY, STL, ...); OSError when it "
      "cannot be read." },
    { NULL },
};

static PyGetSetDef mesh_getset[] = {
    { "positions", (getter)mesh_positions, NULL, "a copy of the positions, (N, 3), in the file's frame", NULL },
    { "faces", (getter)mesh_faces, NULL, "a copy of the faces, int64 (M, 3), in the file's winding", NULL },
    { "normals", (getter)mesh_attribute, NULL, "a copy of the vertex normals, (N, 3), in the file's frame, or None",
      (void *)&NORMALS },
    { "uvs", (getter)mesh_attribute, NULL, "a copy of the texture coordinates, (N, 2), or None", (void *)&UVS },
    { "colors", (getter)mesh_attribute, NULL, "a copy of the vertex colours, (N, 3) 0..1, or None", (void *)&COLORS },
    { "texture", (getter)mesh_texture, NULL, "a copy of the texture, (H, W, 3) uint8, or None", NULL },
    { "file_faces", (getter)mesh_file_faces, NULL,
      "int64 (M,): the file's face (from 0) of each triangle; face_ids k + 1 came from file face file_faces[k]",
      NULL },
    { "vertex_count", (getter)mesh_vertex_count, NULL, "number of vertices", NULL },
    { "triangle_count", (getter)mesh_triangle_count, NULL, "number of triangles (face ids run 1 to this)", NULL },
    { "part_count", (getter)mesh_part_count, NULL, "the largest part id: the file's meshes, or the largest given",
      NULL },
    { NULL },
};

PyTypeObject sr_py_mesh_type = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "softrast.Mesh",
    .tp_doc = "Mesh(positions, faces=None, normals=None, colors=None, *, uvs=None, part_ids=None, texture=None):\n"
              "a triangle mesh, or without faces a point cloud (render it with points=True), copied.\n\n"
              "positions (N, 3) float32/float64 in the frame of the poses; faces (M, 3) int32/int64 vertex\n"
              "indices, face id k + 1 in the outputs; the geometric normal is e1 x e2 of the given order\n"
              "(e1 = p1 - p0, e2 = p2 - p0). Optional: normals (N, 3); colors (N, 3) 0..1 (or uint8);\n"
              "uvs (N, 2), (0, 0) the texture's bottom left; part_ids (M,) 1 or more, the part_ids output;\n"
              "texture (H, W, 3 or 4) uint8, row 0 at the top.",
    .tp_basicsize = sizeof(sr_py_mesh),
    .tp_flags = Py_TPFLAGS_DEFAULT | Py_TPFLAGS_BASETYPE,
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)mesh_init,
    .tp_dealloc = (destructor)mesh_dealloc,
    .tp_repr = (reprfunc)mesh_repr,
    .tp_methods = mesh_methods,
    .tp_getset = mesh_getset,
};
