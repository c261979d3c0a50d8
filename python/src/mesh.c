/* softrast.Mesh: a triangle mesh copied from numpy arrays, or loaded from a
 * file by sr_mesh_load. Positions are in the file's frame (the frame of the
 * poses): a mesh from arrays is stored as given (z_negated false); a loaded
 * one as the loader stores it, which sr_pinhole_* undo. */
#include <string.h>

#include "softrast/files.h"
#include "softrast_py.h"

static void mesh_dealloc(sr_py_mesh *self)
{
    sr_mesh_free(&self->mesh);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

/* An optional per-vertex N x 3 float attribute into dst (vertex_count rows);
 * colors given as uint8 are read as 0..255. */
static bool copy_attribute(PyObject *obj, const char *name, npy_intp rows, vec3 *dst)
{
    bool bytes = PyArray_Check(obj) && PyArray_TYPE((PyArrayObject *)obj) == NPY_UINT8;
    PyArrayObject *a = sr_py_array(obj, name, NPY_FLOAT32, 2, (npy_intp[]){ rows, 3 }, "(N, 3), N the positions' rows");
    if (!a)
        return false;
    const float *v = PyArray_DATA(a);
    for (npy_intp i = 0; i < rows; i++)
        for (int k = 0; k < 3; k++)
            dst[i][k] = bytes ? v[3 * i + k] / 255.0f : v[3 * i + k];
    Py_DECREF(a);
    return true;
}

static int mesh_init(sr_py_mesh *self, PyObject *args, PyObject *kwargs)
{
    static char *names[] = { "positions", "faces", "normals", "colors", NULL };
    PyObject *positions_obj, *faces_obj, *normals_obj = Py_None, *colors_obj = Py_None;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OO|OO:Mesh", names, &positions_obj, &faces_obj, &normals_obj,
                                     &colors_obj))
        return -1;
    if (self->renders) {
        PyErr_SetString(PyExc_RuntimeError, "Mesh.__init__ on a mesh another thread is rendering");
        return -1;
    }
    sr_mesh_free(&self->mesh);
    PyArrayObject *positions = sr_py_array(positions_obj, "positions", NPY_FLOAT32, 2, (npy_intp[]){ -1, 3 }, "(N, 3)");
    PyArrayObject *faces = positions ? sr_py_array(faces_obj, "faces", NPY_INT64, 2, (npy_intp[]){ -1, 3 }, "(M, 3)")
                                     : NULL;
    int status = -1;
    if (!faces)
        goto done;
    npy_intp vertices = PyArray_DIM(positions, 0), triangles = PyArray_DIM(faces, 0);
    if (vertices == 0 || triangles == 0) {
        PyErr_Format(PyExc_ValueError, "an empty mesh (%zd vertices, %zd faces): nothing to render", vertices,
                     triangles);
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
    if (!sr_mesh_alloc(&self->mesh, (uint32_t)vertices, (uint32_t)(3 * triangles), normals_obj != Py_None, false,
                       colors_obj != Py_None, &err)) {
        sr_py_raise(PyExc_MemoryError, &err);
        goto done;
    }
    memcpy(self->mesh.positions, PyArray_DATA(positions), (size_t)vertices * sizeof(vec3));
    for (npy_intp i = 0; i < 3 * triangles; i++) /* an index past the vertices: sr_draw refuses it */
        self->mesh.indices[i] = (uint32_t)f[i];
    if ((normals_obj != Py_None && !copy_attribute(normals_obj, "normals", vertices, self->mesh.normals)) ||
        (colors_obj != Py_None && !copy_attribute(colors_obj, "colors", vertices, self->mesh.colors))) {
        sr_mesh_free(&self->mesh);
        goto done;
    }
    self->mesh.topology = SR_TRIANGLE_LIST;
    sr_mesh_update_bounds(&self->mesh);
    status = 0;
done:
    Py_XDECREF(positions);
    Py_XDECREF(faces);
    return status;
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
    bool ok;
    Py_BEGIN_ALLOW_THREADS
    ok = sr_mesh_load(&self->mesh, NULL, PyBytes_AS_STRING(path), &err);
    Py_END_ALLOW_THREADS
    if (!ok)
        sr_py_raise(PyExc_OSError, &err);
    else if (sr_mesh_triangle_slots(&self->mesh) == 0 || !self->mesh.positions)
        PyErr_Format(PyExc_ValueError, "%s: no faces: an empty mesh, nothing to render", PyBytes_AS_STRING(path));
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
    return PyLong_FromUnsignedLong(self->mesh.part_count ? self->mesh.part_count : 1);
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
    { "vertex_count", (getter)mesh_vertex_count, NULL, "number of vertices", NULL },
    { "triangle_count", (getter)mesh_triangle_count, NULL, "number of triangles (face ids run 1 to this)", NULL },
    { "part_count", (getter)mesh_part_count, NULL, "the file's meshes (part ids run 1 to this)", NULL },
    { NULL },
};

PyTypeObject sr_py_mesh_type = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "softrast.Mesh",
    .tp_doc = "Mesh(positions, faces, normals=None, colors=None): a triangle mesh, copied.\n\n"
              "positions (N, 3) float32/float64 in the frame of the poses; faces (M, 3) int32/int64 vertex\n"
              "indices, face id k + 1 in the outputs; the geometric normal is e1 x e2 of the given order\n"
              "(e1 = p1 - p0, e2 = p2 - p0); normals (N, 3) optional; colors (N, 3) 0..1 (or uint8).",
    .tp_basicsize = sizeof(sr_py_mesh),
    .tp_flags = Py_TPFLAGS_DEFAULT | Py_TPFLAGS_BASETYPE,
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)mesh_init,
    .tp_dealloc = (destructor)mesh_dealloc,
    .tp_repr = (reprfunc)mesh_repr,
    .tp_methods = mesh_methods,
    .tp_getset = mesh_getset,
};
