/* The module softrast._softrast and the conversions its types share. */
#define SOFTRAST_PY_MODULE
#include "softrast_py.h"

PyObject *sr_py_raise(PyObject *type, const sr_error *err)
{
    PyErr_SetString(type, err->message);
    return NULL;
}

PyObject *sr_py_shape_text(const PyArrayObject *a)
{
    PyObject *dims = PyTuple_New(PyArray_NDIM(a));
    for (int k = 0; dims && k < PyArray_NDIM(a); k++)
        PyTuple_SET_ITEM(dims, k, PyLong_FromSsize_t(PyArray_DIM(a, k)));
    if (!dims)
        return NULL;
    PyObject *text = PyObject_Repr(dims);
    Py_DECREF(dims);
    return text;
}

PyArrayObject *sr_py_array(PyObject *obj, const char *name, int type, int ndim, const npy_intp *shape,
                           const char *wanted)
{
    bool integers = PyTypeNum_ISINTEGER(type);
    const char *kinds = integers ? "an integer type (int32 or int64)" : "a real number type (float32 or float64)";
    PyArrayObject *any = (PyArrayObject *)PyArray_FromAny(obj, NULL, 0, 0, 0, NULL);
    if (!any) { /* a ragged list, an object numpy cannot read */
        PyObject *type_, *value, *trace;
        PyErr_Fetch(&type_, &value, &trace);
        PyErr_Format(PyExc_ValueError, "%s: not an array of %s %s: %S", name, kinds, wanted,
                     value ? value : Py_None);
        Py_XDECREF(type_);
        Py_XDECREF(value);
        Py_XDECREF(trace);
        return NULL;
    }
    char kind = PyArray_DESCR(any)->kind;
    if (!(kind == 'i' || kind == 'u' || (!integers && kind == 'f'))) {
        PyErr_Format(PyExc_ValueError, "%s: dtype %S is not %s", name, (PyObject *)PyArray_DESCR(any), kinds);
        Py_DECREF(any);
        return NULL;
    }
    bool fits = PyArray_NDIM(any) == ndim;
    for (int k = 0; fits && k < ndim; k++)
        fits = shape[k] < 0 || PyArray_DIM(any, k) == shape[k];
    if (!fits) {
        PyObject *got = sr_py_shape_text(any);
        if (got)
            PyErr_Format(PyExc_ValueError, "%s: shape %U where %s is wanted", name, got, wanted);
        Py_XDECREF(got);
        Py_DECREF(any);
        return NULL;
    }
    /* A copy only where the layout, alignment, byte order or dtype asks for one. */
    PyArrayObject *out = (PyArrayObject *)PyArray_FromArray(any, PyArray_DescrFromType(type),
                                                            NPY_ARRAY_IN_ARRAY | NPY_ARRAY_FORCECAST);
    Py_DECREF(any);
    return out;
}

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT,
    .m_name = "softrast._softrast",
    .m_doc = "softrast's extension: Mesh and Renderer over the C library (see the package softrast).",
    .m_size = -1,
};

PyMODINIT_FUNC PyInit__softrast(void)
{
    import_array();
    if (PyType_Ready(&sr_py_mesh_type) < 0 || PyType_Ready(&sr_py_renderer_type) < 0)
        return NULL;
    PyObject *m = PyModule_Create(&module);
    if (!m)
        return NULL;
    if (PyModule_AddObjectRef(m, "Mesh", (PyObject *)&sr_py_mesh_type) < 0 ||
        PyModule_AddObjectRef(m, "Renderer", (PyObject *)&sr_py_renderer_type) < 0 ||
        PyModule_AddIntConstant(m, "MAX_SIDE", SR_MAX_FRAMEBUFFER_SIDE) < 0) {
        Py_DECREF(m);
        return NULL;
    }
    return m;
}
