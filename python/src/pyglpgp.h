/* python/src/pyglpgp.h: what the files of the glpgp._glpgp extension share:
 * the object types (Mesh, Result, QuadMesh), the error conversion
 * (glpgp.Error and its ValueError / OSError subclasses from the library's
 * error record), the keyword-argument setter over the library's option
 * tables (glpgp/optdesc.h) and the cancellation hook that polls Ctrl-C.
 * The extension sits on the library like the CLI: public headers only. */
#ifndef GLPGP_PY_H
#define GLPGP_PY_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>

#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#define PY_ARRAY_UNIQUE_SYMBOL glpgp_py_ARRAY_API
#ifndef GLPGP_PY_MODULE_C
#define NO_IMPORT_ARRAY
#endif
#include <numpy/arrayobject.h>

#include "glpgp/backends.h"
#include "glpgp/cross.h"
#include "glpgp/image.h"
#include "glpgp/io.h"
#include "glpgp/mesh.h"
#include "glpgp/optdesc.h"
#include "glpgp/quads.h"
#include "glpgp/solve.h"

#include <pthread.h>

/* ---- objects ----------------------------------------------------------------- */

typedef struct pg_mesh {
    PyObject_HEAD
    glpgp_mesh *m;
    PyObject *source;   /* str: the input as the CLI would name it ("shape:disk:20000", a path), or None */
    double seconds_read;
    PyObject *cache;    /* dict of the arrays made so far */
} pg_mesh;

typedef struct pg_result {
    PyObject_HEAD
    glpgp_result *r;
    pg_mesh *mesh;      /* the mesh solved (the input, or its refinement) */
    glpgp_options o;    /* the options of the solve (has_options: 0 for a result read back) */
    int has_options;
    PyObject *keep;     /* objects whose buffers o points into (strings, the field array) */
    char device[512];   /* the OpenCL device ("" on other backends) */
    glpgp_refine_info refined;
    glpgp_surface_denoise_info denoise; /* a surface's noise smoothed before the solve */
    double denoise_h;
    double seconds_read;
    PyObject *cache;    /* dict of the arrays and the stats made so far */
} pg_result;

typedef struct pg_quadmesh {
    PyObject_HEAD
    glpgp_quadmesh *q;
    glpgp_quads_report qq;
    double h;
    int valid;
    char why[1024];     /* why it is invalid ("" when valid) */
    PyObject *cache;
} pg_quadmesh;

extern PyTypeObject *pg_mesh_type, *pg_result_type, *pg_quadmesh_type;

/* exception types: glpgp.Error, glpgp.InputError (ValueError), glpgp.FileError
 * (OSError), glpgp.InvalidQuadMeshError (InputError) */
extern PyObject *pg_error, *pg_input_error, *pg_file_error, *pg_invalid_error;
/* warnings: glpgp.ConvergenceWarning, glpgp.QualityWarning */
extern PyObject *pg_convergence_warning, *pg_quality_warning;

/* Raise the exception of st from this thread's error record (and clear it);
 * GLPGP_ERR_CANCELLED: the pending KeyboardInterrupt. Returns NULL. */
PyObject *pg_raise(glpgp_status st);

/* ---- keyword arguments over an option table ---------------------------------- */

/* Set the member of opts named by the Python keyword key (a table entry's
 * pyname) to value: flags take a bool, numbers an int or float (checked by
 * glpgp_optdesc_set), choices and text a str (center: also a pair of
 * numbers). Strings stay referenced in keep (a list). Returns 1 when set,
 * 0 when key is not in the table, -1 with an exception (InputError naming
 * the keyword, the value and the reason; TypeError for a wrong type). */
int pg_set_option(const glpgp_optdesc *table, void *opts, const char *func, PyObject *key, PyObject *value,
                  PyObject *keep);

/* ---- cancellation (Ctrl-C) ------------------------------------------------------ */

typedef struct pg_cancel {
    pthread_t caller;    /* the thread that polls Python's signals */
    int main_thread;     /* the caller is the main Python thread (signals arrive there) */
    int cancelled;       /* set once (atomically): every thread of the solve stops */
} pg_cancel;
void pg_cancel_init(pg_cancel *c);
int pg_cancel_poll(void *ctx); /* the glpgp_options.cancel hook */

/* ---- helpers --------------------------------------------------------------------- */

/* A read-only array of the memory at data (shape nd dims, type typenum),
 * whose base keeps owner alive. */
PyObject *pg_view(PyObject *owner, void *data, int nd, npy_intp *dims, int typenum);
/* The array cached in *cache under name, or made by make(self) and cached. */
PyObject *pg_cached(PyObject **cache, const char *name, PyObject *(*make)(PyObject *), PyObject *self);
/* The UTF-8 of a str or os.PathLike (bytes refused), kept alive in keep; NULL with TypeError. */
const char *pg_path(PyObject *obj, PyObject *keep, const char *what);
/* json.loads(text) */
PyObject *pg_json(const char *text);

/* a Mesh object owning m (stolen), named source (may be NULL) */
PyObject *pg_mesh_wrap(glpgp_mesh *m, PyObject *source, double seconds_read);

/* module functions of the other files */
PyObject *pg_read(PyObject *self, PyObject *args, PyObject *kw);
PyObject *pg_shape(PyObject *self, PyObject *args, PyObject *kw);
PyObject *pg_solve(PyObject *self, PyObject *args, PyObject *kw);
PyObject *pg_read_result(PyObject *self, PyObject *args, PyObject *kw);
PyObject *pg_render(PyObject *self, PyObject *args, PyObject *kw);
PyObject *pg_quads(pg_result *self, PyObject *args, PyObject *kw);
int pg_mesh_init_type(PyObject *module);
int pg_result_init_type(PyObject *module);
int pg_quadmesh_init_type(PyObject *module);

#endif
