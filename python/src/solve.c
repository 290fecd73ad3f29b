/* python/src/solve.c: glpgp.solve (the CLI's `glpgp solve` pipeline:
 * glpgp_solve_prepare, the backend selector, glpgp_solve, with the GIL
 * released and Ctrl-C polled before every Newton step) and glpgp.Result
 * (the arrays of a solve as NumPy views, its statistics as the --stats
 * JSON, writers), and glpgp.read_result. */
#include "pyglpgp.h"

#include "glpgp/phase.h"
#include "glpgp/util.h"

#include <math.h>
#include <string.h>

PyTypeObject *pg_result_type;

/* ---- glpgp.solve: the keyword arguments ------------------------------------------ */

typedef struct solve_args {
    glpgp_options o;
    int backend, device, refine;
    long long max_elements, max_pixels;
    double box[4];        /* size_image_box (NaN: the mesh's bounding box) */
    PyArrayObject *field; /* field=array: (nv, 2) float64 */
    int field_given;      /* field= not None (else a surface takes the cross field) */
} solve_args;

static int parse_field_array(solve_args *a, const glpgp_mesh *m, PyObject *value, PyObject *keep)
{
    PyArrayObject *f = (PyArrayObject *)PyArray_FROMANY(value, NPY_DOUBLE, 2, 2, NPY_ARRAY_IN_ARRAY);
    if (!f) return -1;
    if (PyArray_DIM(f, 0) != m->nv || PyArray_DIM(f, 1) != 2) {
        PyErr_Format(pg_input_error, "field: an array of shape (%d, 2) (one vector per vertex of the mesh) was expected, not (%zd, %zd)",
                     m->nv, (Py_ssize_t)PyArray_DIM(f, 0), (Py_ssize_t)PyArray_DIM(f, 1));
        Py_DECREF(f);
        return -1;
    }
    if (PyList_Append(keep, (PyObject *)f) < 0) {
        Py_DECREF(f);
        return -1;
    }
    Py_DECREF(f);
    a->o.field = GLPGP_FIELD_FILE;
    a->o.field_values = PyArray_DATA(f);
    a->o.field_file = "array";
    return 0;
}

static int parse_box(solve_args *a, PyObject *value)
{
    if (value == Py_None) return 0;
    PyObject *seq = PySequence_Fast(value, "size_image_box must be (x0, y0, x1, y1)");
    if (!seq) return -1;
    int ok = PySequence_Fast_GET_SIZE(seq) == 4;
    for (int k = 0; ok && k < 4; k++) {
        a->box[k] = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(seq, k));
        if (a->box[k] == -1.0 && PyErr_Occurred()) ok = 0;
    }
    Py_DECREF(seq);
    if (!ok && !PyErr_Occurred()) PyErr_SetString(PyExc_TypeError, "size_image_box must be (x0, y0, x1, y1)");
    if (ok && !(a->box[2] > a->box[0] && a->box[3] > a->box[1])) {
        PyErr_SetString(pg_input_error, "size_image_box: an empty box (need x1 > x0 and y1 > y0)");
        ok = 0;
    }
    return ok ? 0 : -1;
}

/* one keyword argument of solve() */
static int solve_kwarg(solve_args *a, const glpgp_mesh *m, PyObject *key, PyObject *value, PyObject *keep)
{
    const char *k = PyUnicode_AsUTF8(key);
    if (!k) return -1;
    if (!strcmp(k, "size") && value == Py_None) return 0;
    if (!strcmp(k, "field")) {
        if (value == Py_None) return 0; /* the default: boundary, a surface's cross */
        a->field_given = 1;
        if (m->xyz && !PyUnicode_Check(value)) {
            PyErr_SetString(pg_input_error, "field: a surface takes 'cross' or 'boundary', not per-vertex vectors");
            return -1;
        }
    }
    if (!strcmp(k, "field") && value != Py_None && !PyUnicode_Check(value) && !PyObject_HasAttrString(value, "__fspath__"))
        return parse_field_array(a, m, value, keep);
    if (!strcmp(k, "backend")) {
        const char *b = PyUnicode_Check(value) ? PyUnicode_AsUTF8(value) : NULL;
        a->backend = b ? glpgp_backend_kind_parse(b) : -1;
        if (a->backend < 0) {
            PyErr_Format(pg_input_error, "backend: %R is not one of auto, opencl, reference, petsc", value);
            return -1;
        }
        return 0;
    }
    if (!strcmp(k, "device")) {
        if (value == Py_None) return 0;
        long d = PyLong_Check(value) && !PyBool_Check(value) ? PyLong_AsLong(value) : -2;
        if (d == -1 && PyErr_Occurred()) return -1;
        if (d < 0 || d > 1000000) {
            PyErr_Format(pg_input_error, "device: %R is not an integer >= 0", value);
            return -1;
        }
        a->device = (int)d;
        return 0;
    }
    if (!strcmp(k, "refine")) {
        a->refine = PyObject_IsTrue(value);
        return a->refine < 0 ? -1 : 0;
    }
    if (!strcmp(k, "max_elements") || !strcmp(k, "max_pixels")) {
        long long v = PyLong_AsLongLong(value);
        if (v == -1 && PyErr_Occurred()) return -1;
        if (v < 1) {
            PyErr_Format(pg_input_error, "%s: %R is not a positive integer", k, value);
            return -1;
        }
        *(k[4] == 'e' ? &a->max_elements : &a->max_pixels) = v;
        return 0;
    }
    if (!strcmp(k, "size_image_box")) return parse_box(a, value);
    const int r = pg_set_option(glpgp_solve_option_table(), &a->o, "solve", key, value, keep);
    if (r == 0) PyErr_Format(PyExc_TypeError, "solve() got an unexpected keyword argument '%s'", k);
    return r < 0 || r == 0 ? -1 : 0;
}

/* ---- glpgp.solve: the run --------------------------------------------------------- */

typedef struct solve_run {
    glpgp_mesh *refined;
    glpgp_result *r;
    glpgp_prepare_info pi;
    char device[512];
    double seconds;
} solve_run;

/* everything between the arguments and the result, without the GIL */
static glpgp_status run_solve(const glpgp_mesh *m, const char *name, solve_args *a, solve_run *out)
{
    const double t0 = glpgp_now();
    glpgp_backend *b = NULL;
    glpgp_status st = glpgp_solve_prepare(m, &a->o, name, (double)a->max_elements, a->refine, &out->refined, &out->pi);
    out->seconds = glpgp_now() - t0;
    if (st == GLPGP_OK) {
        if (a->backend == GLPGP_BACKEND_PETSC) {
            st = glpgp_petsc_init();
            if (st == GLPGP_OK) st = glpgp_backend_create_petsc(a->o.precond, &b);
        } else {
            st = glpgp_backend_select((glpgp_backend_kind)a->backend, a->device, 1, &b);
        }
    }
    if (st == GLPGP_OK) st = glpgp_solve(out->refined ? out->refined : m, b, &a->o, &out->r);
    if (st == GLPGP_OK && glpgp_cl_backend_info(b, out->device, sizeof out->device) < 0) out->device[0] = '\0';
    glpgp_backend_destroy(&b);
    if (st != GLPGP_OK) {
        glpgp_result_destroy(&out->r);
        glpgp_mesh_destroy(&out->refined);
    }
    return st;
}

static void warn_result(const glpgp_result *r, const glpgp_options *o, const glpgp_mesh *m)
{
    const glpgp_osc_result *u = &r->osc[0], *v = &r->osc[1];
    if (u->capped_levels + v->capped_levels)
        PyErr_WarnFormat(pg_convergence_warning, 2,
                         "unconverged: %d eps level(s) stopped at the Newton cap (u %d, v %d); raise newton_max",
                         u->capped_levels + v->capped_levels, u->capped_levels, v->capped_levels);
    if (o->method == GLPGP_METHOD_GL && (u->zabs_median < 0.5 || v->zabs_median < 0.5))
        PyErr_WarnFormat(pg_convergence_warning, 2,
                         "median |z| < 0.5: the oscillators collapsed towards z = 0 (h = %g is %.1f mean edges; P1 "
                         "needs about 10 per period): raise size or refine the mesh",
                         r->size, r->size / m->mean_edge);
}

static PyObject *new_result(glpgp_result *r, PyObject *mesh, const glpgp_options *o, PyObject *keep)
{
    pg_result *self = PyObject_GC_New(pg_result, pg_result_type);
    if (!self) {
        glpgp_result_destroy(&r);
        return NULL;
    }
    self->r = r;
    self->mesh = (pg_mesh *)mesh;
    Py_INCREF(mesh);
    self->has_options = o != NULL;
    if (o) self->o = *o;
    else glpgp_options_default(&self->o);
    self->o.cancel = NULL;
    self->o.cancel_ctx = NULL;
    self->o.size_fn = NULL; /* the size image is gone after the solve */
    self->o.size_ctx = NULL;
    self->keep = keep;
    Py_XINCREF(keep);
    self->device[0] = '\0';
    memset(&self->refined, 0, sizeof self->refined);
    memset(&self->denoise, 0, sizeof self->denoise);
    self->denoise_h = 0.0;
    self->seconds_read = 0.0;
    self->cache = NULL;
    PyObject_GC_Track(self);
    return (PyObject *)self;
}

/* the size image of size_field=IMAGE (the CLI's glpgp_cli_size_image) */
static glpgp_status size_image(solve_args *a, const glpgp_mesh *m, glpgp_size_image **img)
{
    *img = NULL;
    if (a->o.size_field != GLPGP_SIZE_FUNC) return GLPGP_OK;
    double b[4];
    for (int k = 0; k < 4; k++) b[k] = isnan(a->box[0]) ? m->bbox[k] : a->box[k];
    GLPGP_CHECK(glpgp_size_image_create(a->o.size_file, a->max_pixels, b, a->o.size_min, 1.0, img));
    a->o.size_fn = glpgp_size_image_eval;
    a->o.size_ctx = *img;
    return GLPGP_OK;
}

PyObject *pg_solve(PyObject *self, PyObject *args, PyObject *kw)
{
    (void)self;
    PyObject *mesh = NULL;
    if (!PyArg_ParseTuple(args, "O:solve", &mesh)) return NULL;
    if (PyUnicode_Check(mesh) || PyObject_HasAttrString(mesh, "__fspath__")) { /* a path or shape:NAME:N */
        PyObject *a1 = PyTuple_Pack(1, mesh);
        mesh = a1 ? pg_read(NULL, a1, NULL) : NULL;
        Py_XDECREF(a1);
        if (!mesh) return NULL;
    } else if (!PyObject_TypeCheck(mesh, pg_mesh_type)) {
        return PyErr_Format(PyExc_TypeError, "solve(): mesh must be a glpgp.Mesh or a path, not %s",
                            Py_TYPE(mesh)->tp_name);
    } else {
        Py_INCREF(mesh);
    }
    pg_mesh *pm = (pg_mesh *)mesh;
    solve_args a = {.backend = GLPGP_BACKEND_AUTO, .device = -1, .refine = 1,
                    .max_elements = GLPGP_DEFAULT_MAX_ELEMENTS, .max_pixels = GLPGP_DEFAULT_MAX_PIXELS,
                    .box = {NAN, NAN, NAN, NAN}};
    glpgp_options_default(&a.o);
    PyObject *keep = PyList_New(0), *key, *value, *out = NULL;
    Py_ssize_t pos = 0;
    if (!keep) goto done;
    while (kw && PyDict_Next(kw, &pos, &key, &value))
        if (solve_kwarg(&a, pm->m, key, value, keep) < 0) goto done;
    if (pm->m->xyz && !a.field_given) a.o.field = GLPGP_FIELD_CROSS; /* a surface's default, as the CLI's */
    const char *name = pm->source != Py_None ? PyUnicode_AsUTF8(pm->source) : "mesh";
    if (!name) goto done;
    pg_cancel cancel;
    pg_cancel_init(&cancel);
    a.o.cancel = pg_cancel_poll;
    a.o.cancel_ctx = &cancel;
    solve_run run;
    memset(&run, 0, sizeof run);
    glpgp_size_image *img = NULL;
    glpgp_status st;
    Py_BEGIN_ALLOW_THREADS
    st = size_image(&a, pm->m, &img);
    if (st == GLPGP_OK) st = run_solve(pm->m, name, &a, &run);
    glpgp_size_image_destroy(&img);
    Py_END_ALLOW_THREADS
    if (st != GLPGP_OK || PyErr_Occurred()) { /* a Ctrl-C seen by a log line after the last step too */
        glpgp_result_destroy(&run.r);
        glpgp_mesh_destroy(&run.refined);
        pg_raise(st);
        goto done;
    }
    PyObject *solved = run.refined ? pg_mesh_wrap(run.refined, pm->source, 0.0) : (Py_INCREF(mesh), mesh);
    if (!solved) {
        glpgp_result_destroy(&run.r);
        goto done;
    }
    out = new_result(run.r, solved, &a.o, keep);
    Py_DECREF(solved);
    if (!out) goto done;
    pg_result *res = (pg_result *)out;
    snprintf(res->device, sizeof res->device, "%s", run.device);
    res->refined = run.pi.refined;
    res->denoise = run.pi.denoise;
    res->denoise_h = run.pi.denoise_h;
    res->seconds_read = pm->seconds_read + run.seconds;
    warn_result(res->r, &res->o, res->mesh->m);
    if (PyErr_Occurred()) Py_CLEAR(out); /* warnings turned into errors */
done:
    Py_XDECREF(keep);
    Py_DECREF(mesh);
    return out;
}

/* ---- glpgp.read_result --------------------------------------------------------------- */

PyObject *pg_read_result(PyObject *self, PyObject *args, PyObject *kw)
{
    (void)self;
    static char *names[] = {"path", NULL};
    PyObject *p;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "O:read_result", names, &p)) return NULL;
    PyObject *keep = PyList_New(0);
    const char *path = keep ? pg_path(p, keep, "path") : NULL;
    glpgp_mesh *m = NULL;
    glpgp_result *r = NULL;
    glpgp_status st = GLPGP_OK;
    if (path) {
        Py_BEGIN_ALLOW_THREADS
        st = glpgp_read_result(path, &m, &r);
        Py_END_ALLOW_THREADS
    }
    PyObject *out = NULL;
    if (!path) {
    } else if (st != GLPGP_OK || PyErr_Occurred()) {
        glpgp_mesh_destroy(&m);
        glpgp_result_destroy(&r);
        pg_raise(st);
    } else {
        PyObject *mesh = pg_mesh_wrap(m, PyList_GET_ITEM(keep, 0), 0.0);
        if (mesh) out = new_result(r, mesh, NULL, NULL);
        else glpgp_result_destroy(&r);
        Py_XDECREF(mesh);
    }
    Py_XDECREF(keep);
    return out;
}

/* ---- Result: arrays ---------------------------------------------------------------------- */

#define RES(o) (((pg_result *)(o))->r)

static PyObject *z_view(PyObject *self, int k)
{
    npy_intp n = RES(self)->nv;
    return pg_view(self, RES(self)->osc[k].z, 1, &n, NPY_COMPLEX128);
}
static PyObject *make_z_u(PyObject *self) { return z_view(self, 0); }
static PyObject *make_z_v(PyObject *self) { return z_view(self, 1); }

static PyObject *theta(PyObject *self, int k)
{
    npy_intp n = RES(self)->nv;
    PyObject *a = PyArray_SimpleNew(1, &n, NPY_DOUBLE);
    if (!a) return NULL;
    double *t = PyArray_DATA((PyArrayObject *)a);
    const double *z = RES(self)->osc[k].z;
    for (npy_intp i = 0; i < n; i++) t[i] = glpgp_theta(z[2 * i], z[2 * i + 1]);
    PyArray_CLEARFLAGS((PyArrayObject *)a, NPY_ARRAY_WRITEABLE);
    return a;
}
static PyObject *make_theta_u(PyObject *self) { return theta(self, 0); }
static PyObject *make_theta_v(PyObject *self) { return theta(self, 1); }

static PyObject *make_field(PyObject *self)
{
    npy_intp d[2] = {RES(self)->nv, 2};
    return pg_view(self, RES(self)->field, 2, d, NPY_DOUBLE);
}

static PyObject *dirichlet(PyObject *self, int k)
{
    npy_intp n = RES(self)->nv;
    return pg_view(self, RES(self)->osc[k].dirichlet, 1, &n, NPY_BOOL);
}
static PyObject *make_dir_u(PyObject *self) { return dirichlet(self, 0); }
static PyObject *make_dir_v(PyObject *self) { return dirichlet(self, 1); }

static PyObject *winding(PyObject *self, int k)
{
    npy_intp n = RES(self)->nt;
    return pg_view(self, RES(self)->osc[k].singular, 1, &n, NPY_INT8);
}
static PyObject *make_wind_u(PyObject *self) { return winding(self, 0); }
static PyObject *make_wind_v(PyObject *self) { return winding(self, 1); }

/* structured arrays: the C layouts and their dtypes */
typedef struct sing_rec {
    int triangle, index;
    double x, y, z;
} sing_rec;
typedef struct cross_rec {
    int triangle, triangles;
    double index, x, y, z;
} cross_rec;

static PyArray_Descr *record_dtype(const char *spec)
{
    /* spec: a Python literal of numpy's dict form {names, formats, offsets, itemsize} */
    PyObject *d = PyRun_String(spec, Py_eval_input, PyEval_GetBuiltins(), NULL);
    PyArray_Descr *descr = NULL;
    if (d && !PyArray_DescrConverter(d, &descr)) descr = NULL;
    Py_XDECREF(d);
    return descr;
}

static PyObject *records(void *data, npy_intp n, size_t size, const char *spec)
{
    PyArray_Descr *descr = record_dtype(spec);
    if (!descr) return NULL;
    PyObject *a = PyArray_NewFromDescr(&PyArray_Type, descr, 1, &n, NULL, NULL, 0, NULL);
    if (!a) return NULL;
    if (n) memcpy(PyArray_DATA((PyArrayObject *)a), data, (size_t)n * size);
    PyArray_CLEARFLAGS((PyArrayObject *)a, NPY_ARRAY_WRITEABLE);
    return a;
}

static PyObject *singular(PyObject *self, int k)
{
    const glpgp_result *r = RES(self);
    const glpgp_mesh *m = ((pg_result *)self)->mesh->m;
    npy_intp n = 0;
    for (int t = 0; t < r->nt; t++) n += r->osc[k].singular[t] != 0;
    sing_rec *rec = PyMem_Malloc(sizeof *rec * (size_t)(n + 1));
    if (!rec) return PyErr_NoMemory();
    npy_intp j = 0;
    for (int t = 0; t < r->nt; t++) {
        if (!r->osc[k].singular[t]) continue;
        double x = 0.0, y = 0.0, z = 0.0; /* the centroid (a surface's in 3D) */
        for (int c = 0; c < 3; c++) {
            const int v = m->tri[3 * t + c];
            x += (m->xyz ? m->xyz[3 * v] : m->xy[2 * v]) / 3.0;
            y += (m->xyz ? m->xyz[3 * v + 1] : m->xy[2 * v + 1]) / 3.0;
            z += m->xyz ? m->xyz[3 * v + 2] / 3.0 : 0.0;
        }
        rec[j++] = (sing_rec){t, r->osc[k].singular[t], x, y, z};
    }
    PyObject *a = records(rec, n, sizeof *rec,
                          "{'names': ['triangle', 'index', 'x', 'y', 'z'], 'formats': ['<i4', '<i4', '<f8', '<f8', '<f8'], "
                          "'offsets': [0, 4, 8, 16, 24], 'itemsize': 32}");
    PyMem_Free(rec);
    return a;
}
static PyObject *make_sing_u(PyObject *self) { return singular(self, 0); }
static PyObject *make_sing_v(PyObject *self) { return singular(self, 1); }

static PyObject *make_cross(PyObject *self)
{
    const glpgp_cross_result *c = RES(self)->cross;
    if (!c) Py_RETURN_NONE;
    npy_intp nv = c->nv, nt = c->nt, ns = c->nsing;
    PyObject *w = pg_view(self, c->w, 1, &nv, NPY_COMPLEX128);
    PyObject *wind = pg_view(self, c->winding, 1, &nt, NPY_INT8);
    PyObject *alpha = PyArray_SimpleNew(1, &nv, NPY_DOUBLE);
    cross_rec *rec = PyMem_Malloc(sizeof *rec * (size_t)(ns + 1));
    PyObject *sing = NULL, *out = NULL;
    if (w && wind && alpha && rec) {
        double *al = PyArray_DATA((PyArrayObject *)alpha);
        for (npy_intp i = 0; i < nv; i++) {
            double a = atan2(c->w[2 * i + 1], c->w[2 * i]) / 4.0;
            al[i] = a < 0.0 ? a + M_PI / 2.0 : a;
        }
        PyArray_CLEARFLAGS((PyArrayObject *)alpha, NPY_ARRAY_WRITEABLE);
        for (npy_intp k = 0; k < ns; k++)
            rec[k] = (cross_rec){c->sing[k].tri, c->sing[k].ntri, c->sing[k].index4 / 4.0, c->sing[k].x, c->sing[k].y,
                                 c->sing[k].z};
        sing = records(rec, ns, sizeof *rec,
                       "{'names': ['triangle', 'triangles', 'index', 'x', 'y', 'z'], 'formats': ['<i4', '<i4', '<f8', "
                       "'<f8', '<f8', '<f8'], 'offsets': [0, 4, 8, 16, 24, 32], 'itemsize': 40}");
    }
    if (sing)
        out = Py_BuildValue("{s:O,s:O,s:O,s:O,s:d,s:d,s:O,s:d}", "w", w, "alpha", alpha, "winding", wind,
                            "singularities", sing, "index_sum", c->index4_sum / 4.0, "index_expected",
                            c->index4_expected / 4.0, "poincare_hopf",
                            c->index4_sum == c->index4_expected ? Py_True : Py_False, "median_abs_w", c->zabs_median);
    PyMem_Free(rec);
    Py_XDECREF(w);
    Py_XDECREF(wind);
    Py_XDECREF(alpha);
    Py_XDECREF(sing);
    if (!out && !PyErr_Occurred()) PyErr_NoMemory();
    return out;
}

static PyObject *make_stats(PyObject *self)
{
    pg_result *res = (pg_result *)self;
    const char *input = res->mesh->source != Py_None ? PyUnicode_AsUTF8(res->mesh->source) : NULL;
    if (PyErr_Occurred()) return NULL;
    glpgp_stats_extra x;
    memset(&x, 0, sizeof x);
    x.input = input;
    x.seconds_read = res->has_options ? res->seconds_read : -1.0;
    x.device = res->device[0] ? res->device : NULL;
    x.denoise = res->denoise.rounds ? &res->denoise : NULL;
    x.denoise_h = res->denoise_h;
    x.hausdorff_input = -1.0;
    char *text = NULL;
    glpgp_status st = glpgp_stats_json_text(res->mesh->m, res->has_options ? &res->o : NULL, res->r, &x, &text);
    if (st != GLPGP_OK) return pg_raise(st);
    PyObject *d = pg_json(text);
    free(text);
    return d;
}

#define GETTER(fn, key, maker)                                                                                         \
    static PyObject *fn(pg_result *self, void *c)                                                                      \
    {                                                                                                                  \
        (void)c;                                                                                                       \
        return pg_cached(&self->cache, key, maker, (PyObject *)self);                                                  \
    }
/* views of the result's memory are made at each access (cached, they would
 * make a cycle through self); the arrays computed once are cached */
#define VIEW(fn, maker)                                                                                                \
    static PyObject *fn(pg_result *self, void *c)                                                                      \
    {                                                                                                                  \
        (void)c;                                                                                                       \
        return maker((PyObject *)self);                                                                                \
    }
VIEW(res_z_u, make_z_u)
VIEW(res_z_v, make_z_v)
GETTER(res_theta_u, "theta_u", make_theta_u)
GETTER(res_theta_v, "theta_v", make_theta_v)
VIEW(res_field, make_field)
VIEW(res_dir_u, make_dir_u)
VIEW(res_dir_v, make_dir_v)
VIEW(res_wind_u, make_wind_u)
VIEW(res_wind_v, make_wind_v)
GETTER(res_sing_u, "singular_u", make_sing_u)
GETTER(res_sing_v, "singular_v", make_sing_v)
VIEW(res_cross, make_cross)
GETTER(res_stats, "stats", make_stats)

static PyObject *res_mesh(pg_result *self, void *c)
{
    (void)c;
    Py_INCREF(self->mesh);
    return (PyObject *)self->mesh;
}
static PyObject *res_size(pg_result *self, void *c)
{
    (void)c;
    return PyFloat_FromDouble(self->r->size);
}
static PyObject *res_backend(pg_result *self, void *c)
{
    (void)c;
    if (!self->r->backend) Py_RETURN_NONE;
    return PyUnicode_FromString(self->r->backend);
}
static PyObject *res_device(pg_result *self, void *c)
{
    (void)c;
    if (!self->device[0]) Py_RETURN_NONE;
    return PyUnicode_FromString(self->device);
}
static PyObject *res_converged(pg_result *self, void *c)
{
    (void)c;
    return PyBool_FromLong(self->r->osc[0].capped_levels + self->r->osc[1].capped_levels == 0);
}
static PyObject *res_refined(pg_result *self, void *c)
{
    (void)c;
    const glpgp_refine_info *f = &self->refined;
    if (!f->rounds && !f->split_edges) Py_RETURN_NONE;
    return Py_BuildValue("{s:i,s:l,s:i,s:i,s:i,s:i}", "rounds", f->rounds, "split_edges", f->split_edges,
                         "vertices_before", f->nv0, "vertices", f->nv, "triangles_before", f->nt0, "triangles", f->nt);
}

/* ---- Result: methods ---------------------------------------------------------------------- */

static PyObject *res_write(pg_result *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"path", NULL};
    PyObject *p;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "O:write", names, &p)) return NULL;
    PyObject *keep = PyList_New(0);
    const char *path = keep ? pg_path(p, keep, "path") : NULL;
    if (!path) {
        Py_XDECREF(keep);
        return NULL;
    }
    const char *input = self->mesh->source != Py_None ? PyUnicode_AsUTF8(self->mesh->source) : NULL;
    const glpgp_options *o = self->has_options ? &self->o : NULL;
    glpgp_stats_extra x;
    memset(&x, 0, sizeof x);
    x.input = input;
    x.seconds_read = self->has_options ? self->seconds_read : -1.0;
    x.device = self->device[0] ? self->device : NULL;
    x.denoise = self->denoise.rounds ? &self->denoise : NULL;
    x.denoise_h = self->denoise_h;
    x.hausdorff_input = -1.0;
    glpgp_status st;
    Py_BEGIN_ALLOW_THREADS
    if (glpgp_has_ext(path, ".json"))
        st = glpgp_write_stats_json(self->mesh->m, o, self->r, path, &x);
    else
        st = glpgp_write_result(self->mesh->m, o, self->r, path);
    Py_END_ALLOW_THREADS
    Py_DECREF(keep);
    if (st != GLPGP_OK || PyErr_Occurred()) return pg_raise(st);
    Py_RETURN_NONE;
}

/* a deep copy of r without its cross field */
static glpgp_status result_copy(const glpgp_result *r, glpgp_result **out)
{
    glpgp_result *c = NULL;
    GLPGP_CHECK(glpgp_result_create(r->nv, r->nt, &c));
    glpgp_result keep = *c;
    *c = *r;
    c->field = keep.field;
    c->cross = NULL;
    memcpy(c->field, r->field, sizeof(double) * 2 * (size_t)r->nv);
    for (int k = 0; k < 2; k++) {
        c->osc[k].z = keep.osc[k].z;
        c->osc[k].dirichlet = keep.osc[k].dirichlet;
        c->osc[k].singular = keep.osc[k].singular;
        memcpy(c->osc[k].z, r->osc[k].z, sizeof(double) * 2 * (size_t)r->nv);
        memcpy(c->osc[k].dirichlet, r->osc[k].dirichlet, (size_t)r->nv);
        memcpy(c->osc[k].singular, r->osc[k].singular, (size_t)r->nt);
    }
    *out = c;
    return GLPGP_OK;
}

static PyObject *res_with_z(pg_result *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"z_u", "z_v", NULL};
    PyObject *zo[2] = {Py_None, Py_None};
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|OO:with_z", names, &zo[0], &zo[1])) return NULL;
    const glpgp_mesh *m = self->mesh->m;
    PyArrayObject *z[2] = {NULL, NULL};
    for (int k = 0; k < 2; k++) {
        if (zo[k] == Py_None) continue;
        z[k] = (PyArrayObject *)PyArray_FROMANY(zo[k], NPY_COMPLEX128, 1, 1, NPY_ARRAY_IN_ARRAY);
        if (z[k] && PyArray_DIM(z[k], 0) != m->nv) {
            PyErr_Format(pg_input_error, "with_z: %s must have %d values (one per vertex), not %zd", names[k], m->nv,
                         (Py_ssize_t)PyArray_DIM(z[k], 0));
            Py_CLEAR(z[k]);
        }
        if (!z[k]) {
            Py_XDECREF(z[0]);
            return NULL;
        }
    }
    glpgp_result *c = NULL;
    glpgp_status st = result_copy(self->r, &c);
    for (int k = 0; k < 2 && st == GLPGP_OK; k++) {
        if (!z[k]) continue;
        memcpy(c->osc[k].z, PyArray_DATA(z[k]), sizeof(double) * 2 * (size_t)m->nv);
        st = glpgp_osc_summarize(m, &c->osc[k]);
    }
    Py_XDECREF(z[0]);
    Py_XDECREF(z[1]);
    if (st != GLPGP_OK) {
        glpgp_result_destroy(&c);
        return pg_raise(st);
    }
    PyObject *out = new_result(c, (PyObject *)self->mesh, self->has_options ? &self->o : NULL, self->keep);
    if (out) {
        pg_result *res = (pg_result *)out;
        memcpy(res->device, self->device, sizeof res->device);
        res->refined = self->refined;
        res->denoise = self->denoise;
        res->denoise_h = self->denoise_h;
        res->seconds_read = self->seconds_read;
    }
    return out;
}

static PyObject *res_repr(pg_result *self)
{
    const glpgp_result *r = self->r;
    const glpgp_osc_result *u = &r->osc[0], *v = &r->osc[1];
    char buf[512];
    snprintf(buf, sizeof buf,
             "<glpgp.Result: %d vertices, h = %.6g, backend %s, singularities u +%d -%d, v +%d -%d, median |z| %.4f / "
             "%.4f, %s%s>",
             r->nv, r->size, r->backend ? r->backend : "?", u->plus, u->minus, v->plus, v->minus, u->zabs_median,
             v->zabs_median, u->capped_levels + v->capped_levels ? "UNCONVERGED" : "converged",
             r->cross ? ", cross field" : "");
    return PyUnicode_FromString(buf);
}

static int res_traverse(pg_result *self, visitproc visit, void *arg)
{
    Py_VISIT(Py_TYPE(self));
    Py_VISIT(self->mesh);
    Py_VISIT(self->keep);
    Py_VISIT(self->cache);
    return 0;
}

static int res_clear(pg_result *self)
{
    Py_CLEAR(self->cache);
    Py_CLEAR(self->keep);
    return 0;
}

static void res_dealloc(pg_result *self)
{
    PyTypeObject *tp = Py_TYPE(self);
    PyObject_GC_UnTrack(self);
    res_clear(self);
    glpgp_result_destroy(&self->r);
    Py_CLEAR(self->mesh);
    tp->tp_free((PyObject *)self);
    Py_DECREF(tp);
}

static PyGetSetDef k_getset[] = {
    {"mesh", (getter)res_mesh, NULL,
     "The Mesh that was solved: the input, or its refinement for the local size (the arrays below are per vertex "
     "and triangle of this mesh).",
     NULL},
    {"size", (getter)res_size, NULL, "The target quad size h used.", NULL},
    {"backend", (getter)res_backend, NULL, "The backend that solved ('reference', 'opencl', 'petsc').", NULL},
    {"device", (getter)res_device, NULL, "The OpenCL device and its launch shape, or None.", NULL},
    {"z_u", (getter)res_z_u, NULL, "complex128 array: the oscillator along U per vertex (read-only).", NULL},
    {"z_v", (getter)res_z_v, NULL, "complex128 array: the oscillator along V per vertex (read-only).", NULL},
    {"theta_u", (getter)res_theta_u, NULL, "float64 array: arg(z_u) / 2 pi in [0, 1) per vertex.", NULL},
    {"theta_v", (getter)res_theta_v, NULL, "float64 array: arg(z_v) / 2 pi in [0, 1) per vertex.", NULL},
    {"field", (getter)res_field, NULL, "(n, 2) float64 array: the unit guiding field U (V is U turned by +90 degrees).",
     NULL},
    {"dirichlet_u", (getter)res_dir_u, NULL, "bool array: vertices where z_u is fixed on the boundary.", NULL},
    {"dirichlet_v", (getter)res_dir_v, NULL, "bool array: vertices where z_v is fixed on the boundary.", NULL},
    {"winding_u", (getter)res_wind_u, NULL, "int8 array: winding of z_u around each triangle (-1, 0, +1).", NULL},
    {"winding_v", (getter)res_wind_v, NULL, "int8 array: winding of z_v around each triangle (-1, 0, +1).", NULL},
    {"singular_u", (getter)res_sing_u, NULL,
     "Structured array of the singular triangles of z_u: fields triangle (its index), index (the winding, +1 or "
     "-1), x, y (its centroid).",
     NULL},
    {"singular_v", (getter)res_sing_v, NULL, "As singular_u, for z_v.", NULL},
    {"cross", (getter)res_cross, NULL,
     "field='cross': a dict with w (complex128, exp(4 i alpha) per vertex), alpha (in [0, pi/2)), winding (per "
     "triangle), singularities (structured: triangle, triangles, index (+-0.25, ...), x, y), index_sum, "
     "index_expected (Poincare-Hopf), poincare_hopf, median_abs_w; None otherwise.",
     NULL},
    {"stats", (getter)res_stats, NULL,
     "The statistics as a dict: the same object `glpgp solve --stats` writes, from the same writer (input is the "
     "mesh's source, output None).",
     NULL},
    {"converged", (getter)res_converged, NULL,
     "False when an eps level stopped at the Newton cap (a ConvergenceWarning was issued).", NULL},
    {"refined", (getter)res_refined, NULL,
     "How the input was refined for the local size (rounds, vertices_before, vertices, ...), or None.", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyMethodDef k_methods[] = {
    {"quads", (PyCFunction)(void (*)(void))pg_quads, METH_VARARGS | METH_KEYWORDS, NULL},
    {"write", (PyCFunction)(void (*)(void))res_write, METH_VARARGS | METH_KEYWORDS,
     "write(path)\n--\n\nWrite the result by extension: .vtu (binary VTK XML), .vtk (legacy VTK), .obj (texture "
     "coordinates), or .json (the statistics, as --stats). Atomic: a failure leaves no partial file and an existing "
     "file unchanged."},
    {"with_z", (PyCFunction)(void (*)(void))res_with_z, METH_VARARGS | METH_KEYWORDS,
     "with_z(z_u=None, z_v=None)\n--\n\nA new Result with z_u and/or z_v replaced (complex arrays, one value per "
     "vertex), their singularities and |z| statistics recomputed: for the quad extraction of a modified field. "
     "The cross field is not carried over."},
    {NULL, NULL, 0, NULL}};

static PyType_Slot k_slots[] = {
    {Py_tp_dealloc, res_dealloc},
    {Py_tp_traverse, res_traverse},
    {Py_tp_clear, res_clear},
    {Py_tp_repr, res_repr},
    {Py_tp_getset, k_getset},
    {Py_tp_methods, k_methods},
    {Py_tp_doc, "The result of glpgp.solve or glpgp.read_result: the oscillators z_u, z_v per vertex of Result.mesh, "
                "the guiding field, singularities, statistics."},
    {0, NULL}};

static PyType_Spec k_spec = {"glpgp.Result", sizeof(pg_result), 0, Py_TPFLAGS_DEFAULT | Py_TPFLAGS_HAVE_GC, k_slots};

int pg_result_init_type(PyObject *module)
{
    pg_result_type = (PyTypeObject *)PyType_FromModuleAndSpec(module, &k_spec, NULL);
    if (!pg_result_type) return -1;
    return PyModule_AddObjectRef(module, "Result", (PyObject *)pg_result_type);
}
