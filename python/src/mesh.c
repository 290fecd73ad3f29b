/* python/src/mesh.c: glpgp.Mesh (a validated triangle mesh of a planar
 * domain: from arrays, a file, a built-in shape or a mask image), and the
 * module functions glpgp.read and glpgp.shape. */
#include "pyglpgp.h"

#include "glpgp/shapes.h"
#include "glpgp/util.h"

#include <string.h>

PyTypeObject *pg_mesh_type;

PyObject *pg_mesh_wrap(glpgp_mesh *m, PyObject *source, double seconds_read)
{
    pg_mesh *o = PyObject_GC_New(pg_mesh, pg_mesh_type);
    if (!o) {
        glpgp_mesh_destroy(&m);
        return NULL;
    }
    o->m = m;
    o->source = source ? source : Py_None;
    Py_INCREF(o->source);
    o->seconds_read = seconds_read;
    o->cache = NULL;
    PyObject_GC_Track(o);
    return (PyObject *)o;
}

static int mesh_traverse(pg_mesh *self, visitproc visit, void *arg)
{
    Py_VISIT(Py_TYPE(self));
    Py_VISIT(self->cache);
    return 0;
}

static int mesh_clear(pg_mesh *self)
{
    Py_CLEAR(self->cache);
    return 0;
}

static void mesh_dealloc(pg_mesh *self)
{
    PyTypeObject *tp = Py_TYPE(self);
    PyObject_GC_UnTrack(self);
    mesh_clear(self);
    Py_CLEAR(self->source);
    glpgp_mesh_destroy(&self->m);
    tp->tp_free((PyObject *)self);
    Py_DECREF(tp);
}

/* Mesh(vertices, triangles, name=None): the arrays copied in */
static PyObject *mesh_new(PyTypeObject *type, PyObject *args, PyObject *kw)
{
    static char *names[] = {"vertices", "triangles", "name", NULL};
    PyObject *vo, *to, *name = Py_None;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "OO|O:Mesh", names, &vo, &to, &name)) return NULL;
    if (name != Py_None && !PyUnicode_Check(name)) return PyErr_Format(PyExc_TypeError, "Mesh(): name must be a str");
    PyArrayObject *v = (PyArrayObject *)PyArray_FROMANY(vo, NPY_DOUBLE, 2, 2, NPY_ARRAY_IN_ARRAY);
    if (!v) return NULL;
    PyArrayObject *t = (PyArrayObject *)PyArray_FROMANY(to, NPY_INT64, 2, 2, NPY_ARRAY_IN_ARRAY);
    if (!t) {
        Py_DECREF(v);
        return NULL;
    }
    const npy_intp nv = PyArray_DIM(v, 0), dim = PyArray_DIM(v, 1), nt = PyArray_DIM(t, 0);
    int *tri = NULL;
    glpgp_mesh *m = NULL;
    glpgp_status st = GLPGP_OK;
    if (dim != 2 && dim != 3) {
        PyErr_Format(pg_input_error, "Mesh(): vertices must be an (n, 2) or (n, 3) array, not (%zd, %zd)", (Py_ssize_t)nv,
                     (Py_ssize_t)dim);
    } else if (PyArray_DIM(t, 1) != 3) {
        PyErr_Format(pg_input_error, "Mesh(): triangles must be an (m, 3) array, not (%zd, %zd)", (Py_ssize_t)nt,
                     (Py_ssize_t)PyArray_DIM(t, 1));
    } else if (nv > GLPGP_IO_MAX_ITEMS || nt > GLPGP_IO_MAX_ITEMS) {
        PyErr_Format(pg_input_error, "Mesh(): %zd vertices, %zd triangles: more than %ld", (Py_ssize_t)nv,
                     (Py_ssize_t)nt, (long)GLPGP_IO_MAX_ITEMS);
    } else if (glpgp_malloc((size_t)nt * 3 + 1, sizeof *tri, &tri) != GLPGP_OK) {
        pg_raise(GLPGP_ERR_NOMEM);
    } else {
        const long long *t64 = PyArray_DATA(t);
        for (npy_intp i = 0; i < 3 * nt; i++) /* outside [0, nv): -1, refused by the library */
            tri[i] = t64[i] >= 0 && t64[i] < nv ? (int)t64[i] : -1;
        const char *nm = name == Py_None ? "mesh" : PyUnicode_AsUTF8(name);
        const double *x = PyArray_DATA(v);
        if (nm) {
            Py_BEGIN_ALLOW_THREADS
            st = glpgp_mesh_from_arrays(nm, (int)nv, x, (int)dim, (int)nt, tri, &m);
            Py_END_ALLOW_THREADS
            if (st != GLPGP_OK) pg_raise(st);
        }
    }
    free(tri);
    Py_DECREF(v);
    Py_DECREF(t);
    if (!m) return NULL;
    (void)type;
    return pg_mesh_wrap(m, name == Py_None ? NULL : name, 0.0);
}

static PyObject *make_vertices(PyObject *self)
{
    glpgp_mesh *m = ((pg_mesh *)self)->m;
    npy_intp dims[2] = {m->nv, m->xyz ? 3 : 2}; /* a surface: its 3D points */
    return pg_view(self, m->xyz ? m->xyz : m->xy, 2, dims, NPY_DOUBLE);
}

static PyObject *make_triangles(PyObject *self)
{
    glpgp_mesh *m = ((pg_mesh *)self)->m;
    npy_intp dims[2] = {m->nt, 3};
    return pg_view(self, m->tri, 2, dims, NPY_INT32);
}

static PyObject *make_loops(PyObject *self)
{
    glpgp_mesh *m = ((pg_mesh *)self)->m;
    PyObject *list = PyList_New(m->nloops);
    for (int l = 0; list && l < m->nloops; l++) {
        npy_intp n = m->loop_start[l + 1] - m->loop_start[l];
        PyObject *a = pg_view(self, m->loop_vertices + m->loop_start[l], 1, &n, NPY_INT32);
        if (!a) Py_CLEAR(list);
        else PyList_SET_ITEM(list, l, a);
    }
    return list;
}

/* views are made at each access (cached, they would make a cycle through self) */
static PyObject *mesh_vertices(pg_mesh *self, void *c)
{
    (void)c;
    return make_vertices((PyObject *)self);
}
static PyObject *mesh_triangles(pg_mesh *self, void *c)
{
    (void)c;
    return make_triangles((PyObject *)self);
}
static PyObject *mesh_loops(pg_mesh *self, void *c)
{
    (void)c;
    return make_loops((PyObject *)self);
}
static PyObject *mesh_area(pg_mesh *self, void *c)
{
    (void)c;
    return PyFloat_FromDouble(self->m->area);
}
static PyObject *mesh_mean_edge(pg_mesh *self, void *c)
{
    (void)c;
    return PyFloat_FromDouble(self->m->mean_edge);
}
static PyObject *mesh_bbox(pg_mesh *self, void *c)
{
    (void)c;
    const double *b = self->m->bbox;
    return Py_BuildValue("(dddd)", b[0], b[1], b[2], b[3]);
}
static PyObject *mesh_source(pg_mesh *self, void *c)
{
    (void)c;
    Py_INCREF(self->source);
    return self->source;
}
static PyObject *mesh_nv(pg_mesh *self, void *c)
{
    (void)c;
    return PyLong_FromLong(self->m->nv);
}
static PyObject *mesh_nt(pg_mesh *self, void *c)
{
    (void)c;
    return PyLong_FromLong(self->m->nt);
}

static PyObject *mesh_write(pg_mesh *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"path", NULL};
    PyObject *p;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "O:write", names, &p)) return NULL;
    PyObject *keep = PyList_New(0);
    const char *path = keep ? pg_path(p, keep, "path") : NULL;
    glpgp_status st = GLPGP_OK;
    if (path) {
        Py_BEGIN_ALLOW_THREADS
        st = glpgp_mesh_write(self->m, path);
        Py_END_ALLOW_THREADS
    }
    Py_XDECREF(keep);
    if (!path) return NULL;
    if (st != GLPGP_OK) return pg_raise(st);
    Py_RETURN_NONE;
}

static PyObject *mesh_repr(pg_mesh *self)
{
    const glpgp_mesh *m = self->m;
    char buf[512];
    snprintf(buf, sizeof buf, "<glpgp.Mesh: %d vertices, %d triangles, %d boundary loop%s, [%.6g, %.6g] x [%.6g, %.6g]",
             m->nv, m->nt, m->nloops, m->nloops == 1 ? "" : "s", m->bbox[0], m->bbox[2], m->bbox[1], m->bbox[3]);
    if (self->source != Py_None) return PyUnicode_FromFormat("%s, %S>", buf, self->source);
    return PyUnicode_FromFormat("%s>", buf);
}

static PyGetSetDef k_getset[] = {
    {"vertices", (getter)mesh_vertices, NULL, "(n, 2) float64 array of the vertex coordinates (read-only).", NULL},
    {"triangles", (getter)mesh_triangles, NULL,
     "(m, 3) int32 array of vertex indices, every triangle counter-clockwise (read-only).", NULL},
    {"boundary_loops", (getter)mesh_loops, NULL,
     "List of int32 arrays of boundary vertices, one per loop: the outer loop first (counter-clockwise), then "
     "the holes (clockwise).",
     NULL},
    {"area", (getter)mesh_area, NULL, "Total area.", NULL},
    {"mean_edge", (getter)mesh_mean_edge, NULL, "Mean edge length.", NULL},
    {"bbox", (getter)mesh_bbox, NULL, "Bounding box (xmin, ymin, xmax, ymax).", NULL},
    {"source", (getter)mesh_source, NULL,
     "Where the mesh came from as the CLI names an INPUT ('shape:disk:20000', a path), or the name given to "
     "Mesh(); None when unnamed.",
     NULL},
    {"n_vertices", (getter)mesh_nv, NULL, "Number of vertices.", NULL},
    {"n_triangles", (getter)mesh_nt, NULL, "Number of triangles.", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyMethodDef k_mesh_methods[] = {
    {"write", (PyCFunction)(void (*)(void))mesh_write, METH_VARARGS | METH_KEYWORDS,
     "write(path)\n--\n\nWrite the triangles as .obj or .msh (Gmsh 4.1), atomically (no partial file on failure)."},
    {NULL, NULL, 0, NULL}};

static PyType_Slot k_slots[] = {
    {Py_tp_new, mesh_new},
    {Py_tp_dealloc, mesh_dealloc},
    {Py_tp_traverse, mesh_traverse},
    {Py_tp_clear, mesh_clear},
    {Py_tp_repr, mesh_repr},
    {Py_tp_getset, k_getset},
    {Py_tp_methods, k_mesh_methods},
    {Py_tp_doc,
     "Mesh(vertices, triangles, name=None)\n--\n\n"
     "A triangle mesh of a planar domain or a 3D surface, validated and copied in.\n\n"
     "vertices: (n, 2) or (n, 3) array-like of coordinates; 3D points are taken as a file's would be: a mesh in a "
     "plane z, y or x = const is solved in its two other coordinates, anything else is a 3D surface. triangles: "
     "(m, 3) array-like of vertex indices. Vertices used by no triangle are dropped, unwelded pieces welded; a "
     "planar mesh made counter-clockwise; on a surface, zero-area triangles flipped away or collapsed, triangles "
     "oriented against their neighbours flipped, a vertex where sheets touch split and an edge where bodies touch "
     "separated (a warning each); what remains degenerate, an edge of three triangles, pinched boundaries "
     "(planar) or a non-orientable surface raise InputError naming the culprit. "
     "name: how messages and statistics name it."},
    {0, NULL}};

static PyType_Spec k_spec = {"glpgp.Mesh", sizeof(pg_mesh), 0,
                             Py_TPFLAGS_DEFAULT | Py_TPFLAGS_HAVE_GC, k_slots};

int pg_mesh_init_type(PyObject *module)
{
    pg_mesh_type = (PyTypeObject *)PyType_FromModuleAndSpec(module, &k_spec, NULL);
    if (!pg_mesh_type) return -1;
    return PyModule_AddObjectRef(module, "Mesh", (PyObject *)pg_mesh_type);
}

/* ---- glpgp.read, glpgp.shape ----------------------------------------------------- */

static PyObject *limit_error(const char *what, long long count, const char *items, int approx, long long max)
{
    return PyErr_Format(pg_input_error, "%s: %s%lld %s: more than the limit of %lld (max_elements)", what,
                        approx ? "about " : "", count, items, max);
}

static PyObject *shape_mesh(const char *name, long n, long long max_elements, PyObject *source)
{
    if (max_elements > 0 && 2LL * n > max_elements) {
        PyObject *s = PyUnicode_FromFormat("shape:%s:%ld", name, n);
        const char *w = s ? PyUnicode_AsUTF8(s) : name;
        limit_error(w ? w : name, 2LL * n, "triangles", 1, max_elements);
        Py_XDECREF(s);
        return NULL;
    }
    glpgp_mesh *m = NULL;
    glpgp_status st;
    const double t0 = glpgp_now();
    Py_BEGIN_ALLOW_THREADS
    st = glpgp_mesh_generate(name, n, &m);
    Py_END_ALLOW_THREADS
    if (st != GLPGP_OK) return pg_raise(st);
    return pg_mesh_wrap(m, source, glpgp_now() - t0);
}

PyObject *pg_shape(PyObject *self, PyObject *args, PyObject *kw)
{
    (void)self;
    static char *names[] = {"name", "n", "max_elements", NULL};
    const char *name;
    long n = GLPGP_SHAPE_DEFAULT_VERTICES;
    long long max_elements = GLPGP_DEFAULT_MAX_ELEMENTS;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "s|l$L:shape", names, &name, &n, &max_elements)) return NULL;
    PyObject *source = PyUnicode_FromFormat("shape:%s:%ld", name, n);
    if (!source) return NULL;
    PyObject *m = shape_mesh(name, n, max_elements, source);
    Py_DECREF(source);
    return m;
}

/* a mask image, a .poly or a remeshed mesh file: meshed by Gmsh */
static PyObject *read_meshed(const char *path, PyObject *source, double mesh_size, long long max_elements,
                             long long max_pixels, int remesh)
{
    glpgp_mask_options mo;
    glpgp_mask_options_default(&mo);
    if (mesh_size > 0) mo.mesh_size = mesh_size;
    if (max_elements > 0) mo.max_triangles = (long)max_elements;
    if (max_pixels > 0) mo.max_pixels = max_pixels;
    mo.remesh = remesh;
    glpgp_mesh *m = NULL;
    glpgp_mask_info inf;
    glpgp_status st;
    const double t0 = glpgp_now();
    Py_BEGIN_ALLOW_THREADS
    st = glpgp_mask_mesh(path, &mo, &m, &inf);
    if (st == GLPGP_OK)
        glpgp_log(GLPGP_LOG_INFO, "%s: %d vertices, %d triangles (%d hole%s, mesh size %.4g, %.2f s)", path, m->nv,
                  m->nt, inf.nholes, inf.nholes == 1 ? "" : "s", inf.mesh_size,
                  inf.seconds_read + inf.seconds_contour + inf.seconds_mesh);
    Py_END_ALLOW_THREADS
    if (st != GLPGP_OK) return pg_raise(st);
    return pg_mesh_wrap(m, source, glpgp_now() - t0);
}

PyObject *pg_read(PyObject *self, PyObject *args, PyObject *kw)
{
    (void)self;
    static char *names[] = {"path", "mesh_size", "remesh", "max_elements", "max_pixels", NULL};
    PyObject *p;
    double mesh_size = 0.0;
    int remesh = 0;
    long long max_elements = GLPGP_DEFAULT_MAX_ELEMENTS, max_pixels = GLPGP_DEFAULT_MAX_PIXELS;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "O|$dpLL:read", names, &p, &mesh_size, &remesh, &max_elements,
                                     &max_pixels))
        return NULL;
    PyObject *keep = PyList_New(0);
    const char *path = keep ? pg_path(p, keep, "path") : NULL;
    if (!path) {
        Py_XDECREF(keep);
        return NULL;
    }
    PyObject *source = PyList_GET_ITEM(keep, 0), *out = NULL;
    if (!strncmp(path, "shape:", 6)) {
        char name[64];
        long n;
        if (glpgp_shape_parse(path, 0, name, sizeof name, &n) != GLPGP_OK) pg_raise(GLPGP_ERR_ARG);
        else out = shape_mesh(name, n, max_elements, source);
    } else if (glpgp_is_image_path(path) || glpgp_is_poly_path(path) ||
               (remesh && (glpgp_has_ext(path, ".obj") || glpgp_has_ext(path, ".msh") || glpgp_has_ext(path, ".stl")))) {
        out = read_meshed(path, source, mesh_size, max_elements, max_pixels, remesh);
    } else {
        glpgp_mesh *m = NULL;
        glpgp_status st;
        const double t0 = glpgp_now();
        Py_BEGIN_ALLOW_THREADS
        st = glpgp_mesh_read(path, &m);
        Py_END_ALLOW_THREADS
        if (st != GLPGP_OK) pg_raise(st);
        else if (max_elements > 0 && m->nt > max_elements) {
            limit_error(path, m->nt, "triangles", 0, max_elements);
            glpgp_mesh_destroy(&m);
        } else
            out = pg_mesh_wrap(m, source, glpgp_now() - t0);
    }
    Py_DECREF(keep);
    return out;
}
