/* python/src/quads.c: Result.quads (the CLI's quad pipeline:
 * glpgp_quads_build, the quality report, the validity verdict) and
 * glpgp.QuadMesh (its arrays, report and writer), and glpgp.render (the
 * rasteriser: a picture as an array, written when a path is given). */
#include "pyglpgp.h"

#include <string.h>

PyTypeObject *pg_quadmesh_type;

/* ---- QuadMesh ------------------------------------------------------------------------ */

static int all_quads(const glpgp_quadmesh *q)
{
    for (int f = 0; f < q->nf; f++)
        if (q->face_start[f + 1] - q->face_start[f] != 4) return 0;
    return 1;
}

static PyObject *qm_vertices(pg_quadmesh *self, void *c)
{
    (void)c;
    npy_intp d[2] = {self->q->nv, self->q->xyz ? 3 : 2}; /* a surface's quads: 3D points */
    return pg_view((PyObject *)self, self->q->xyz ? self->q->xyz : self->q->xy, 2, d, NPY_DOUBLE);
}

static PyObject *qm_faces(pg_quadmesh *self, void *c)
{
    (void)c;
    const glpgp_quadmesh *q = self->q;
    if (all_quads(q)) {
        npy_intp d[2] = {q->nf, 4};
        return pg_view((PyObject *)self, q->face_vert, 2, d, NPY_INT32);
    }
    PyObject *list = PyList_New(q->nf);
    for (int f = 0; list && f < q->nf; f++) {
        npy_intp n = q->face_start[f + 1] - q->face_start[f];
        PyObject *a = pg_view((PyObject *)self, q->face_vert + q->face_start[f], 1, &n, NPY_INT32);
        if (!a) Py_CLEAR(list);
        else PyList_SET_ITEM(list, f, a);
    }
    return list;
}

static PyObject *qm_offsets(pg_quadmesh *self, void *c)
{
    (void)c;
    npy_intp n = self->q->nf + 1;
    return pg_view((PyObject *)self, self->q->face_start, 1, &n, NPY_INT32);
}

static PyObject *qm_face_vertices(pg_quadmesh *self, void *c)
{
    (void)c;
    npy_intp n = self->q->face_start[self->q->nf];
    return pg_view((PyObject *)self, self->q->face_vert, 1, &n, NPY_INT32);
}

static PyObject *make_report(PyObject *self)
{
    char *text = NULL;
    glpgp_status st = glpgp_quads_json_text(&((pg_quadmesh *)self)->qq, &text);
    if (st != GLPGP_OK) return pg_raise(st);
    PyObject *d = pg_json(text);
    free(text);
    return d;
}

static PyObject *qm_report(pg_quadmesh *self, void *c)
{
    (void)c;
    return pg_cached(&self->cache, "report", make_report, (PyObject *)self);
}
static PyObject *qm_valid(pg_quadmesh *self, void *c)
{
    (void)c;
    return PyBool_FromLong(self->valid);
}
static PyObject *qm_why(pg_quadmesh *self, void *c)
{
    (void)c;
    return PyUnicode_FromString(self->why);
}
static PyObject *qm_h(pg_quadmesh *self, void *c)
{
    (void)c;
    return PyFloat_FromDouble(self->h);
}

static PyObject *qm_write(pg_quadmesh *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"path", "allow_invalid", NULL};
    PyObject *p;
    int allow = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "O|$p:write", names, &p, &allow)) return NULL;
    if (!self->valid && !allow)
        return PyErr_Format(pg_invalid_error,
                            "the quad mesh is invalid (%s): not written (allow_invalid=True writes it anyway)",
                            self->why);
    PyObject *keep = PyList_New(0);
    const char *path = keep ? pg_path(p, keep, "path") : NULL;
    if (!path) {
        Py_XDECREF(keep);
        return NULL;
    }
    if (!self->valid)
        glpgp_log(GLPGP_LOG_WARNING, "the quad mesh is invalid (%s): written anyway (allow_invalid)", self->why);
    glpgp_status st;
    Py_BEGIN_ALLOW_THREADS
    st = glpgp_quads_write(self->q, path);
    Py_END_ALLOW_THREADS
    Py_DECREF(keep);
    if (st != GLPGP_OK || PyErr_Occurred()) return pg_raise(st);
    Py_RETURN_NONE;
}

static PyObject *qm_repr(pg_quadmesh *self)
{
    const glpgp_quads_report *qq = &self->qq;
    char buf[1400];
    snprintf(buf, sizeof buf, "<glpgp.QuadMesh: %d vertices, %d faces (%d quads), %d irregular, min scaled Jacobian %.3f, %s%s%s>",
             qq->vertices, qq->faces, qq->quads, qq->irregular, qq->sj_min, self->valid ? "valid" : "INVALID: ",
             self->valid ? "" : self->why, "");
    return PyUnicode_FromString(buf);
}

static int qm_traverse(pg_quadmesh *self, visitproc visit, void *arg)
{
    Py_VISIT(Py_TYPE(self));
    Py_VISIT(self->cache);
    return 0;
}

static int qm_clear(pg_quadmesh *self)
{
    Py_CLEAR(self->cache);
    return 0;
}

static void qm_dealloc(pg_quadmesh *self)
{
    PyTypeObject *tp = Py_TYPE(self);
    PyObject_GC_UnTrack(self);
    qm_clear(self);
    glpgp_quadmesh_destroy(&self->q);
    tp->tp_free((PyObject *)self);
    Py_DECREF(tp);
}

static PyGetSetDef k_getset[] = {
    {"vertices", (getter)qm_vertices, NULL, "(n, 2) float64 array of the vertex coordinates (read-only).", NULL},
    {"faces", (getter)qm_faces, NULL,
     "(f, 4) int32 array of the faces' vertices (counter-clockwise) when every face is a quad; otherwise a list "
     "of int32 arrays, one per face (face_offsets and face_vertices hold the same in two arrays).",
     NULL},
    {"face_offsets", (getter)qm_offsets, NULL, "int32 array: face f is face_vertices[face_offsets[f]:face_offsets[f+1]].",
     NULL},
    {"face_vertices", (getter)qm_face_vertices, NULL, "int32 array: the faces' vertices back to back.", NULL},
    {"report", (getter)qm_report, NULL,
     "The quality report as a dict: the same object as the 'quads' member of `glpgp solve --quads --stats`.", NULL},
    {"valid", (getter)qm_valid, NULL, "Whether the quad mesh passed the validity checks (see invalid_reasons).", NULL},
    {"invalid_reasons", (getter)qm_why, NULL, "Why the mesh is invalid, one line ('' when valid).", NULL},
    {"h", (getter)qm_h, NULL, "The size the mesh is made for (the solve's h; half of it with all_quads).", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyMethodDef k_methods[] = {
    {"write", (PyCFunction)(void (*)(void))qm_write, METH_VARARGS | METH_KEYWORDS,
     "write(path, *, allow_invalid=False)\n--\n\nWrite the quad mesh by extension (.obj, .vtu, .vtk, .msh), "
     "atomically. An invalid mesh raises InvalidQuadMeshError and is not written, unless allow_invalid=True."},
    {NULL, NULL, 0, NULL}};

static PyType_Slot k_slots[] = {
    {Py_tp_dealloc, qm_dealloc},  {Py_tp_traverse, qm_traverse}, {Py_tp_clear, qm_clear},
    {Py_tp_repr, qm_repr},        {Py_tp_getset, k_getset},      {Py_tp_methods, k_methods},
    {Py_tp_doc, "A quad mesh extracted from a Result (Result.quads): vertices, faces, its quality report and "
                "validity."},
    {0, NULL}};

static PyType_Spec k_spec = {"glpgp.QuadMesh", sizeof(pg_quadmesh), 0, Py_TPFLAGS_DEFAULT | Py_TPFLAGS_HAVE_GC,
                             k_slots};

int pg_quadmesh_init_type(PyObject *module)
{
    pg_quadmesh_type = (PyTypeObject *)PyType_FromModuleAndSpec(module, &k_spec, NULL);
    if (!pg_quadmesh_type) return -1;
    return PyModule_AddObjectRef(module, "QuadMesh", (PyObject *)pg_quadmesh_type);
}

/* ---- Result.quads ----------------------------------------------------------------------- */

/* the CLI's pipeline: build, report, the cross-field report, the verdict */
static glpgp_status build_quads(const glpgp_mesh *m, const glpgp_result *r, const glpgp_quads_options *qo,
                                pg_quadmesh *out)
{
    double h = r->size;
    glpgp_quads_surface_steps steps;
    memset(&steps, 0, sizeof steps);
    if (m->xyz) GLPGP_CHECK(glpgp_quads_build_surface(m, r, qo, &out->q, &h, &steps));
    else GLPGP_CHECK(glpgp_quads_build(m, r, qo, &out->q, &h));
    out->h = h;
    GLPGP_CHECK(glpgp_quads_quality(out->q, m, h, &out->qq));
    if (m->xyz) { /* the report's quads.surface.steps, as the CLI's */
        out->qq.steps = steps;
        out->qq.has_steps = 1;
    }
    out->qq.singular[0] = r->osc[0].plus + r->osc[0].minus;
    out->qq.singular[1] = r->osc[1].plus + r->osc[1].minus;
    if (r->cross) GLPGP_CHECK(glpgp_quads_quality_cross(out->q, r->cross->sing, r->cross->nsing, r->size, &out->qq));
    out->valid = !glpgp_quads_invalid_text(&out->qq, qo->keep_polygons ? GLPGP_QUADS_BAD_NONQUAD : 0u, out->why,
                                           sizeof out->why);
    if (out->valid) out->why[0] = '\0';
    return GLPGP_OK;
}

PyObject *pg_quads(pg_result *self, PyObject *args, PyObject *kw)
{
    if (PyTuple_GET_SIZE(args) != 0) return PyErr_Format(PyExc_TypeError, "quads() takes keyword arguments only");
    glpgp_quads_options qo;
    glpgp_quads_options_default(&qo);
    if (self->has_options) qo.feature_angle = self->o.feature_angle; /* the solve's creases */
    PyObject *key, *value, *keep = PyList_New(0);
    Py_ssize_t pos = 0;
    if (!keep) return NULL;
    while (kw && PyDict_Next(kw, &pos, &key, &value)) {
        const int r = pg_set_option(glpgp_quads_option_table(), &qo, "quads", key, value, keep);
        if (r == 0) PyErr_Format(PyExc_TypeError, "quads() got an unexpected keyword argument '%U'", key);
        if (r <= 0) {
            Py_DECREF(keep);
            return NULL;
        }
    }
    Py_DECREF(keep);
    pg_quadmesh *q = PyObject_GC_New(pg_quadmesh, pg_quadmesh_type);
    if (!q) return NULL;
    q->q = NULL;
    q->cache = NULL;
    q->valid = 0;
    q->why[0] = '\0';
    memset(&q->qq, 0, sizeof q->qq);
    PyObject_GC_Track(q);
    glpgp_status st;
    Py_BEGIN_ALLOW_THREADS
    st = build_quads(self->mesh->m, self->r, &qo, q);
    Py_END_ALLOW_THREADS
    if (st != GLPGP_OK || PyErr_Occurred()) {
        Py_DECREF(q);
        return pg_raise(st);
    }
    if (!q->valid && PyErr_WarnFormat(pg_quality_warning, 1, "the quad mesh is invalid (%s)", q->why) < 0) {
        Py_DECREF(q);
        return NULL;
    }
    return (PyObject *)q;
}

/* ---- glpgp.render ------------------------------------------------------------------------ */

PyObject *pg_render(PyObject *self, PyObject *args, PyObject *kw)
{
    (void)self;
    PyObject *res = NULL, *path = Py_None;
    if (!PyArg_ParseTuple(args, "O!|O:render", pg_result_type, &res, &path)) return NULL;
    glpgp_render_options ro;
    glpgp_render_options_default(&ro);
    PyObject *key, *value, *keep = PyList_New(0), *out = NULL;
    Py_ssize_t pos = 0;
    if (!keep) return NULL;
    while (kw && PyDict_Next(kw, &pos, &key, &value)) {
        const char *k = PyUnicode_AsUTF8(key);
        if (!k) goto done;
        if (!strcmp(k, "path")) {
            path = value;
            continue;
        }
        if (!strcmp(k, "boundary") || !strcmp(k, "singular")) {
            const int t = PyObject_IsTrue(value);
            if (t < 0) goto done;
            *(k[0] == 'b' ? &ro.boundary : &ro.singular) = t;
            continue;
        }
        const int r = pg_set_option(glpgp_render_option_table(), &ro, "render", key, value, keep);
        if (r == 0) PyErr_Format(PyExc_TypeError, "render() got an unexpected keyword argument '%s'", k);
        if (r <= 0) goto done;
    }
    const char *p = path == Py_None ? NULL : pg_path(path, keep, "path");
    if (path != Py_None && !p) goto done;
    const pg_result *r = (const pg_result *)res;
    glpgp_image *im = NULL;
    glpgp_status st;
    Py_BEGIN_ALLOW_THREADS
    st = glpgp_render(r->mesh->m, r->r, &ro, &im);
    if (st == GLPGP_OK && p) st = glpgp_image_write(p, im);
    Py_END_ALLOW_THREADS
    if (st != GLPGP_OK || PyErr_Occurred()) {
        glpgp_image_destroy(&im);
        pg_raise(st);
        goto done;
    }
    npy_intp d[3] = {im->h, im->w, im->nc};
    out = PyArray_SimpleNew(3, d, NPY_FLOAT32);
    if (out) memcpy(PyArray_DATA((PyArrayObject *)out), im->px, sizeof(float) * (size_t)im->w * im->h * im->nc);
    glpgp_image_destroy(&im);
done:
    Py_DECREF(keep);
    return out;
}
