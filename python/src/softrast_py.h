/* softrast_py.h — the extension module softrast._softrast: numpy arrays in,
 * the library's sr_mesh and sr_pinhole_* through, numpy arrays out. One
 * file per Python type (mesh.c, renderer.c) and the module with the
 * conversions they share (module.c). */
#ifndef SOFTRAST_PY_H
#define SOFTRAST_PY_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>
#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#define PY_ARRAY_UNIQUE_SYMBOL softrast_ARRAY_API
#ifndef SOFTRAST_PY_MODULE
#define NO_IMPORT_ARRAY
#endif
#include <numpy/arrayobject.h>

#include <stdbool.h>

#include "softrast/files.h"

/* softrast.Mesh: an sr_mesh that owns its arrays, and its texture. */
typedef struct sr_py_mesh {
    PyObject_HEAD
    sr_mesh mesh;
    sr_texture texture; /* empty: none; a loaded file's embedded one */
    sr_material_textures material_textures; /* a loaded file's materials' texture files */
    /* Part ids given as arrays: mesh.parts are the runs of equal ids in
     * face order, and part_map[run] the id the caller gave that run (the
     * library's part_ids output is run + 1). NULL for a loaded mesh. */
    uint32_t *part_map;
    /* Whether its colours are display (sRGB-encoded) values, as arrays and
     * every file but glTF's are (io/vertex_colours.h), and then, made at
     * the first render under sRGB that reads them, the same in linear
     * light, which the draw takes. */
    bool display_colours;
    vec3 *linear_colors;
    /* Made at the first render with points=True: 0 .. N − 1, each vertex a
     * point in order (the command line's --points). */
    uint32_t *point_indices;
    int renders; /* renders using it with the GIL released: __init__ waits for none */
} sr_py_mesh;

extern PyTypeObject sr_py_mesh_type;
extern PyTypeObject sr_py_renderer_type;

/* obj as a C-contiguous, aligned, native array of `type` whose shape is
 * `ndim` long and matches `shape` (-1: any length there), converted from
 * any real dtype (integers only when type is an integer type). NULL with a
 * ValueError naming `name` and the shape wanted, `wanted` ("(N, 3)"). */
PyArrayObject *sr_py_array(PyObject *obj, const char *name, int type, int ndim, const npy_intp *shape,
                           const char *wanted);

/* "(5,)", "(2, 3)": an array's shape for a message (a new str, or NULL). */
PyObject *sr_py_shape_text(const PyArrayObject *a);

/* Raises `type` with the library's one line; returns NULL. */
PyObject *sr_py_raise(PyObject *type, const sr_error *err);

#endif
