/* python/src/module.c: the glpgp._glpgp extension module: its exceptions
 * and warnings, the library's log callback forwarded to the Python logger
 * "glpgp", the error conversion, the keyword arguments read through the
 * library's option tables, the Ctrl-C hook, shared array helpers, and the
 * functions that need no object of their own (devices, crosscheck, the
 * option tables, version and build facts). */
#define GLPGP_PY_MODULE_C
#include "pyglpgp.h"

#include "glpgp/version.h"

#include <signal.h>
#include <stdio.h>
#include <string.h>

PyObject *pg_error, *pg_input_error, *pg_file_error, *pg_invalid_error;
PyObject *pg_convergence_warning, *pg_quality_warning;
static PyObject *g_logger;     /* logging.getLogger("glpgp") */
static PyObject *g_json_loads; /* json.loads */

/* ---- errors ------------------------------------------------------------------------ */

PyObject *pg_raise(glpgp_status st)
{
    if (st == GLPGP_ERR_CANCELLED) {
        glpgp_error_clear();
        /* the KeyboardInterrupt raised by the signal handler the hook ran */
        if (!PyErr_Occurred()) PyErr_SetNone(PyExc_KeyboardInterrupt);
        return NULL;
    }
    if (PyErr_Occurred()) { /* a Python error first (a callback's): it wins */
        glpgp_error_clear();
        return NULL;
    }
    if (st == GLPGP_OK) st = glpgp_error_status();
    PyObject *type = pg_error;
    switch (st) {
    case GLPGP_ERR_ARG:
    case GLPGP_ERR_FORMAT:
    case GLPGP_ERR_MESH:
    case GLPGP_ERR_LIMIT: type = pg_input_error; break;
    case GLPGP_ERR_IO: type = pg_file_error; break;
    case GLPGP_ERR_NOMEM: type = PyExc_MemoryError; break;
    default: break;
    }
    const char *msg = glpgp_error_message();
    PyObject *text = PyUnicode_DecodeUTF8(*msg ? msg : "unknown failure", (Py_ssize_t)strlen(*msg ? msg : "unknown failure"),
                                          "replace");
    PyObject *exc = text ? PyObject_CallOneArg(type, text) : NULL;
    if (exc && type != PyExc_MemoryError) {
        PyObject *name = PyUnicode_FromString(glpgp_status_name(st));
        PyObject *trace = PyUnicode_DecodeUTF8(glpgp_error_trace(), (Py_ssize_t)strlen(glpgp_error_trace()), "replace");
        PyObject *detail = PyUnicode_DecodeUTF8(glpgp_error_detail(), (Py_ssize_t)strlen(glpgp_error_detail()), "replace");
        if (!name || !trace || !detail || PyObject_SetAttrString(exc, "status", name) < 0 ||
            PyObject_SetAttrString(exc, "trace", trace) < 0 || PyObject_SetAttrString(exc, "detail", detail) < 0)
            Py_CLEAR(exc);
        Py_XDECREF(name);
        Py_XDECREF(trace);
        Py_XDECREF(detail);
    }
    Py_XDECREF(text);
    glpgp_error_clear();
    if (exc) {
        PyErr_SetObject(type, exc);
        Py_DECREF(exc);
    }
    return NULL;
}

/* ---- logging ------------------------------------------------------------------------ */

static volatile int g_log_live; /* cleared by _shutdown (atexit) before the interpreter goes */

/* Any thread running glpgp code (the caller's, the oscillator thread): the
 * message goes to logging.getLogger("glpgp") with the GIL taken; an
 * exception pending in this thread (a KeyboardInterrupt from the cancel
 * hook) is kept aside meanwhile. */
static void log_to_python(glpgp_log_level level, const char *msg, void *user)
{
    (void)user;
    if (!g_log_live || !Py_IsInitialized()) return;
    PyGILState_STATE g = PyGILState_Ensure();
    PyObject *et, *ev, *tb;
    PyErr_Fetch(&et, &ev, &tb);
    const int pylevel = level == GLPGP_LOG_WARNING ? 30 : level == GLPGP_LOG_INFO ? 20 : 10;
    PyObject *text = PyUnicode_DecodeUTF8(msg, (Py_ssize_t)strlen(msg), "replace");
    PyObject *r = text ? PyObject_CallMethod(g_logger, "log", "iO", pylevel, text) : NULL;
    if (!r && !et && PyErr_ExceptionMatches(PyExc_KeyboardInterrupt))
        PyErr_Fetch(&et, &ev, &tb); /* a Ctrl-C handled inside the logger: kept pending, the hook cancels */
    else if (!r)
        PyErr_WriteUnraisable(g_logger);
    Py_XDECREF(r);
    Py_XDECREF(text);
    PyErr_Restore(et, ev, tb);
    PyGILState_Release(g);
}

static PyObject *py_shutdown(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    g_log_live = 0;
    glpgp_log_set_callback(NULL, NULL);
    glpgp_petsc_finalize();
    Py_RETURN_NONE;
}

/* _set_logging(on): the library's messages to the logger (the default) or
 * nowhere (for the tests: no Python code runs from inside a solve) */
static PyObject *py_set_logging(PyObject *self, PyObject *on)
{
    (void)self;
    const int t = PyObject_IsTrue(on);
    if (t < 0) return NULL;
    glpgp_log_set_callback(t && g_log_live ? log_to_python : NULL, NULL);
    Py_RETURN_NONE;
}

/* ---- Ctrl-C ------------------------------------------------------------------------- */

void pg_cancel_init(pg_cancel *c)
{
    c->caller = pthread_self();
    c->cancelled = 0;
    PyObject *threading = PyImport_ImportModule("threading");
    PyObject *cur = threading ? PyObject_CallMethod(threading, "current_thread", NULL) : NULL;
    PyObject *main = threading ? PyObject_CallMethod(threading, "main_thread", NULL) : NULL;
    c->main_thread = cur && cur == main;
    Py_XDECREF(cur);
    Py_XDECREF(main);
    Py_XDECREF(threading);
    PyErr_Clear();
}

/* Before every Newton step, in each thread of the solve: once cancelled,
 * always; in the caller's thread when it is Python's main thread (where
 * signals are handled), the signal handlers run now (GIL taken): a Ctrl-C
 * raises KeyboardInterrupt there, which cancels. */
int pg_cancel_poll(void *ctx)
{
    pg_cancel *c = ctx;
    if (__atomic_load_n(&c->cancelled, __ATOMIC_RELAXED)) return 1;
    if (!c->main_thread || !pthread_equal(pthread_self(), c->caller)) return 0;
    PyGILState_STATE g = PyGILState_Ensure();
    /* a KeyboardInterrupt already pending (raised inside a log call), or one now */
    const int r = PyErr_Occurred() ? -1 : PyErr_CheckSignals();
    PyGILState_Release(g);
    if (r < 0) __atomic_store_n(&c->cancelled, 1, __ATOMIC_RELAXED);
    return r < 0;
}

/* ---- options ------------------------------------------------------------------------ */

static int set_number(const glpgp_optdesc *d, void *opts, const char *func, const char *name, PyObject *value)
{
    char text[64], why[320];
    if (PyBool_Check(value) || !PyNumber_Check(value) || PyComplex_Check(value)) {
        PyErr_Format(PyExc_TypeError, "%s(): %s must be a number, not %s", func, name, Py_TYPE(value)->tp_name);
        return -1;
    }
    if (PyFloat_Check(value) || !PyIndex_Check(value)) {
        const double v = PyFloat_AsDouble(value);
        if (v == -1.0 && PyErr_Occurred()) return -1;
        snprintf(text, sizeof text, "%.17g", v);
    } else {
        PyObject *i = PyNumber_Index(value);
        if (!i) return -1;
        int overflow = 0;
        const long long v = PyLong_AsLongLongAndOverflow(i, &overflow);
        Py_DECREF(i);
        if (v == -1 && PyErr_Occurred()) return -1;
        if (overflow) snprintf(text, sizeof text, "%s", overflow > 0 ? "99999999999999999999" : "-99999999999999999999");
        else snprintf(text, sizeof text, "%lld", v);
    }
    if (glpgp_optdesc_set(d, opts, text, why, sizeof why)) {
        PyObject *r = PyObject_Repr(value);
        PyErr_Format(pg_input_error, "%s: %s %s", name, r ? PyUnicode_AsUTF8(r) : text, why);
        Py_XDECREF(r);
        return -1;
    }
    return 1;
}

static int set_text(const glpgp_optdesc *d, void *opts, const char *func, const char *name, PyObject *value,
                    PyObject *keep)
{
    char why[320];
    PyObject *s = NULL;
    if (!strcmp(d->name, "center") && PySequence_Check(value) && !PyUnicode_Check(value)) {
        /* center=(x, y): the text the CLI would get, exactly */
        double c[2];
        if (PySequence_Size(value) != 2) {
            PyErr_Format(PyExc_TypeError, "%s(): center must be a pair (x, y)", func);
            return -1;
        }
        for (int k = 0; k < 2; k++) {
            PyObject *e = PySequence_GetItem(value, k);
            c[k] = e ? PyFloat_AsDouble(e) : -1.0;
            Py_XDECREF(e);
            if (c[k] == -1.0 && PyErr_Occurred()) return -1;
        }
        char buf[80];
        snprintf(buf, sizeof buf, "%.17g,%.17g", c[0], c[1]);
        s = PyUnicode_FromString(buf);
    } else if (PyUnicode_Check(value) || PyObject_HasAttrString(value, "__fspath__")) {
        s = PyUnicode_Check(value) ? (Py_INCREF(value), value) : PyOS_FSPath(value);
        if (s && !PyUnicode_Check(s)) {
            Py_DECREF(s);
            PyErr_Format(PyExc_TypeError, "%s(): %s must be a str or a path", func, name);
            return -1;
        }
    } else {
        PyErr_Format(PyExc_TypeError, "%s(): %s must be a str, not %s", func, name, Py_TYPE(value)->tp_name);
        return -1;
    }
    if (!s) return -1;
    const char *t = PyUnicode_AsUTF8(s);
    if (!t || PyList_Append(keep, s) < 0) {
        Py_DECREF(s);
        return -1;
    }
    Py_DECREF(s); /* kept by keep: the library may point into it */
    if (glpgp_optdesc_set(d, opts, t, why, sizeof why)) {
        PyErr_Format(pg_input_error, "%s: '%s' %s", name, t, why);
        return -1;
    }
    return 1;
}

int pg_set_option(const glpgp_optdesc *table, void *opts, const char *func, PyObject *key, PyObject *value,
                  PyObject *keep)
{
    const char *name = PyUnicode_AsUTF8(key);
    if (!name) return -1;
    const glpgp_optdesc *d = NULL;
    char py[64];
    for (const glpgp_optdesc *e = table; e->name && !d; e++) {
        glpgp_optdesc_pyname(e, py, sizeof py);
        if (!strcmp(py, name)) d = e;
    }
    if (!d) return 0;
    switch (d->kind) {
    case GLPGP_OPTK_FLAG:
        if (!PyBool_Check(value) && !(PyLong_Check(value) && (PyLong_AsLong(value) == 0 || PyLong_AsLong(value) == 1))) {
            PyErr_Format(PyExc_TypeError, "%s(): %s must be True or False, not %R", func, name, value);
            return -1;
        }
        glpgp_optdesc_set_flag(d, opts, PyObject_IsTrue(value));
        return 1;
    case GLPGP_OPTK_INT:
    case GLPGP_OPTK_DOUBLE: return set_number(d, opts, func, name, value);
    case GLPGP_OPTK_CHOICE: {
        char why[320];
        if (!PyUnicode_Check(value)) {
            char names[256];
            glpgp_optdesc_choices(d, ", ", names, sizeof names);
            PyErr_Format(PyExc_TypeError, "%s(): %s must be one of the strings %s, not %s", func, name, names,
                         Py_TYPE(value)->tp_name);
            return -1;
        }
        const char *t = PyUnicode_AsUTF8(value);
        if (!t) return -1;
        if (glpgp_optdesc_set(d, opts, t, why, sizeof why)) {
            PyErr_Format(pg_input_error, "%s: '%s' %s", name, t, why);
            return -1;
        }
        return 1;
    }
    case GLPGP_OPTK_TEXT: return set_text(d, opts, func, name, value, keep);
    }
    return 0;
}

/* _options(table): the entries of "solve", "quads" or "render" as a list of
 * dicts (name, cli, kind, default, help, choices, range): docstrings and
 * glpgp.options() are made of it */
static PyObject *py_options(PyObject *self, PyObject *arg)
{
    (void)self;
    const char *which = PyUnicode_AsUTF8(arg);
    if (!which) return NULL;
    const glpgp_optdesc *t = NULL;
    glpgp_options so;
    glpgp_quads_options qo;
    glpgp_render_options ro;
    void *obj = NULL;
    if (!strcmp(which, "solve")) {
        t = glpgp_solve_option_table();
        glpgp_options_default(&so);
        obj = &so;
    } else if (!strcmp(which, "quads")) {
        t = glpgp_quads_option_table();
        glpgp_quads_options_default(&qo);
        obj = &qo;
    } else if (!strcmp(which, "render")) {
        t = glpgp_render_option_table();
        glpgp_render_options_default(&ro);
        obj = &ro;
    } else {
        return PyErr_Format(PyExc_ValueError, "no option table '%s'", which);
    }
    static const char *const kinds[] = {"flag", "int", "float", "choice", "text"};
    PyObject *list = PyList_New(0);
    for (const glpgp_optdesc *d = t; list && d->name; d++) {
        char py[64], def[256], val[256], range[128] = "", choices[256] = "";
        glpgp_optdesc_pyname(d, py, sizeof py);
        glpgp_optdesc_default(d, obj, def, sizeof def);
        glpgp_optdesc_value(d, obj, val, sizeof val);
        if (d->kind == GLPGP_OPTK_INT || d->kind == GLPGP_OPTK_DOUBLE) glpgp_optdesc_range(d, range, sizeof range);
        if (d->kind == GLPGP_OPTK_CHOICE) glpgp_optdesc_choices(d, "|", choices, sizeof choices);
        if (d->kind == GLPGP_OPTK_FLAG) snprintf(def, sizeof def, "%s", val);
        PyObject *e = Py_BuildValue("{s:s,s:s,s:s,s:s,s:s,s:s,s:s,s:s}", "name", py, "cli", d->name, "kind",
                                    kinds[d->kind], "default", def, "value", val, "help", d->help ? d->help : "",
                                    "range", range, "choices", d->meta && d->kind == GLPGP_OPTK_TEXT ? d->meta : choices);
        if (!e || PyList_Append(list, e) < 0) Py_CLEAR(list);
        Py_XDECREF(e);
    }
    return list;
}

/* ---- helpers ------------------------------------------------------------------------- */

PyObject *pg_view(PyObject *owner, void *data, int nd, npy_intp *dims, int typenum)
{
    PyObject *a = PyArray_SimpleNewFromData(nd, dims, typenum, data);
    if (!a) return NULL;
    Py_INCREF(owner);
    if (PyArray_SetBaseObject((PyArrayObject *)a, owner) < 0) {
        Py_DECREF(a);
        return NULL;
    }
    PyArray_CLEARFLAGS((PyArrayObject *)a, NPY_ARRAY_WRITEABLE);
    return a;
}

PyObject *pg_cached(PyObject **cache, const char *name, PyObject *(*make)(PyObject *), PyObject *self)
{
    if (!*cache && !(*cache = PyDict_New())) return NULL;
    PyObject *v = PyDict_GetItemString(*cache, name);
    if (v) {
        Py_INCREF(v);
        return v;
    }
    v = make(self);
    if (v && PyDict_SetItemString(*cache, name, v) < 0) Py_CLEAR(v);
    return v;
}

const char *pg_path(PyObject *obj, PyObject *keep, const char *what)
{
    PyObject *s = PyOS_FSPath(obj);
    if (!s) return NULL;
    if (!PyUnicode_Check(s)) {
        Py_DECREF(s);
        PyErr_Format(PyExc_TypeError, "%s must be a str or os.PathLike of a str", what);
        return NULL;
    }
    const char *t = PyUnicode_AsUTF8(s);
    if (t && PyList_Append(keep, s) < 0) t = NULL;
    Py_DECREF(s);
    return t;
}

PyObject *pg_json(const char *text) { return PyObject_CallFunction(g_json_loads, "s", text); }

/* ---- devices, crosscheck ---------------------------------------------------------- */

static PyObject *py_devices(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    glpgp_device_info *devs = NULL;
    int n = 0;
    glpgp_status st;
    Py_BEGIN_ALLOW_THREADS
    st = glpgp_devices_list(&devs, &n);
    Py_END_ALLOW_THREADS
    if (st == GLPGP_ERR_UNSUPPORTED || st == GLPGP_ERR_OPENCL) {
        /* no OpenCL in this build, or no platform: no device */
        glpgp_error_clear();
        return PyList_New(0);
    }
    if (st != GLPGP_OK) return pg_raise(st);
    PyObject *list = PyList_New(0);
    for (int i = 0; list && i < n; i++) {
        const glpgp_device_info *d = &devs[i];
        PyObject *e = Py_BuildValue("{s:i,s:i,s:s,s:s,s:s,s:s,s:I,s:K,s:O,s:s,s:O}", "index", d->index, "platform_index",
                                    d->platform_index, "platform", d->platform, "name", d->name, "vendor", d->vendor,
                                    "version", d->version, "compute_units", d->compute_units, "global_mem",
                                    d->global_mem, "fp64", d->fp64 ? Py_True : Py_False, "type", d->type, "default",
                                    d->is_default ? Py_True : Py_False);
        if (!e || PyList_Append(list, e) < 0) Py_CLEAR(list);
        Py_XDECREF(e);
    }
    free(devs);
    return list;
}

static PyObject *crosscheck_table(const glpgp_crosscheck *t)
{
    PyObject *rows = PyList_New(0);
    for (int i = 0; rows && i < t->nrows; i++) {
        const glpgp_crosscheck_row *r = &t->rows[i];
        PyObject *e = Py_BuildValue("{s:s,s:d,s:d,s:s,s:O}", "stage", r->stage, "max_abs", r->max_abs, "max_rel",
                                    r->max_rel, "tolerance", r->tol, "pass", r->pass ? Py_True : Py_False);
        if (!e || PyList_Append(rows, e) < 0) Py_CLEAR(rows);
        Py_XDECREF(e);
    }
    if (!rows) return NULL;
    return Py_BuildValue("{s:O,s:N,s:s,s:i,s:i,s:l,s:d,s:d}", "pass", t->pass ? Py_True : Py_False, "rows", rows,
                         "device", t->device, "vertices", t->nv, "triangles", t->nt, "blocks", t->nnzb, "size", t->h,
                         "eps", t->eps);
}

static PyObject *py_crosscheck(PyObject *self, PyObject *args, PyObject *kw)
{
    (void)self;
    static char *names[] = {"mesh", "size", "energy", "device", "tol_scale", "solve", "seed", "precond", NULL};
    PyObject *mesh, *size = Py_None, *device = Py_None;
    const char *energy = "p1", *precond = NULL;
    double tol_scale = 1.0;
    int solve = 1;
    unsigned long long seed = 12345;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "O!|O$sOdpKs:crosscheck", names, pg_mesh_type, &mesh, &size, &energy,
                                     &device, &tol_scale, &solve, &seed, &precond))
        return NULL;
    glpgp_crosscheck_options co;
    glpgp_crosscheck_options_default(&co);
    co.mesh = ((pg_mesh *)mesh)->m;
    co.solve = solve;
    co.seed = seed;
    co.tol_scale = tol_scale;
    if (!(tol_scale > 0.0)) return PyErr_Format(pg_input_error, "tol_scale: %g is not a positive number", tol_scale);
    if (size != Py_None) {
        co.size = PyFloat_AsDouble(size);
        if (co.size == -1.0 && PyErr_Occurred()) return NULL;
        if (!(co.size > 0.0)) return PyErr_Format(pg_input_error, "size: %R is not a positive number", size);
    }
    if (device != Py_None) {
        co.device = (int)PyLong_AsLong(device);
        if (co.device == -1 && PyErr_Occurred()) return NULL;
        if (co.device < 0) return PyErr_Format(pg_input_error, "device: %R is not an integer >= 0", device);
    }
    /* energy and precond: the names and values of the solve options */
    glpgp_options so;
    glpgp_options_default(&so);
    char why[320];
    const glpgp_optdesc *t = glpgp_solve_option_table();
    if (glpgp_optdesc_set(glpgp_optdesc_find(t, "energy"), &so, energy, why, sizeof why))
        return PyErr_Format(pg_input_error, "energy: '%s' %s", energy, why);
    if (precond && glpgp_optdesc_set(glpgp_optdesc_find(t, "precond"), &so, precond, why, sizeof why))
        return PyErr_Format(pg_input_error, "precond: '%s' %s", precond, why);
    co.energy = so.energy;
    if (precond) co.precond = so.precond;
    glpgp_crosscheck *tab = NULL;
    glpgp_status st;
    Py_INCREF(mesh);
    Py_BEGIN_ALLOW_THREADS
    st = glpgp_crosscheck_create(&co, &tab);
    Py_END_ALLOW_THREADS
    Py_DECREF(mesh);
    PyObject *out = NULL;
    if (st != GLPGP_OK) pg_raise(st);
    else out = crosscheck_table(tab);
    glpgp_crosscheck_destroy(&tab);
    return out;
}

static PyObject *py_build_info(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    return Py_BuildValue("{s:s,s:O,s:O,s:O,s:O,s:O}", "version", GLPGP_VERSION, "opencl",
                         glpgp_have_opencl() ? Py_True : Py_False, "openimageio", glpgp_have_oiio() ? Py_True : Py_False,
                         "gmsh", glpgp_have_gmsh() ? Py_True : Py_False, "petsc",
                         glpgp_have_petsc() ? Py_True : Py_False, "zlib", glpgp_io_have_zlib() ? Py_True : Py_False);
}

/* ---- the module ------------------------------------------------------------------------ */

static PyMethodDef k_methods[] = {
    {"read", (PyCFunction)(void (*)(void))pg_read, METH_VARARGS | METH_KEYWORDS, NULL},
    {"shape", (PyCFunction)(void (*)(void))pg_shape, METH_VARARGS | METH_KEYWORDS, NULL},
    {"solve", (PyCFunction)(void (*)(void))pg_solve, METH_VARARGS | METH_KEYWORDS, NULL},
    {"read_result", (PyCFunction)(void (*)(void))pg_read_result, METH_VARARGS | METH_KEYWORDS, NULL},
    {"render", (PyCFunction)(void (*)(void))pg_render, METH_VARARGS | METH_KEYWORDS, NULL},
    {"crosscheck", (PyCFunction)(void (*)(void))py_crosscheck, METH_VARARGS | METH_KEYWORDS, NULL},
    {"devices", py_devices, METH_NOARGS, NULL},
    {"build_info", py_build_info, METH_NOARGS, NULL},
    {"_options", py_options, METH_O, NULL},
    {"_shutdown", py_shutdown, METH_NOARGS, NULL},
    {"_set_logging", py_set_logging, METH_O, NULL},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef k_module = {PyModuleDef_HEAD_INIT, "glpgp._glpgp",
                                      "The C extension of the glpgp package (use the package glpgp).", -1,
                                      k_methods, NULL, NULL, NULL, NULL};

/* a new exception or warning class glpgp.NAME (module glpgp) with bases */
static PyObject *new_class(PyObject *m, const char *name, PyObject *bases, const char *doc)
{
    char full[64];
    snprintf(full, sizeof full, "glpgp.%s", name);
    PyObject *c = PyErr_NewExceptionWithDoc(full, doc, bases, NULL);
    if (c && PyModule_AddObjectRef(m, name, c) < 0) Py_CLEAR(c);
    return c;
}

PyMODINIT_FUNC PyInit__glpgp(void)
{
    import_array();
    PyObject *m = PyModule_Create(&k_module);
    if (!m) return NULL;
    PyObject *b1 = NULL, *b2 = NULL, *b3 = NULL, *logging = NULL, *json = NULL;
    pg_error = new_class(m, "Error", NULL,
                         "A glpgp failure: the library's one-line message; .status names the kind ('numerical "
                         "failure', 'OpenCL error', ...), .trace where it passed, .detail more (a build log).");
    if (!pg_error) goto fail;
    b1 = PyTuple_Pack(2, pg_error, PyExc_ValueError);
    b2 = PyTuple_Pack(2, pg_error, PyExc_OSError);
    if (!b1 || !b2) goto fail;
    pg_input_error = new_class(m, "InputError", b1,
                               "Bad input: an option value, a malformed or rejected mesh, a limit exceeded.");
    pg_file_error = new_class(m, "FileError", b2, "A file that cannot be read or written.");
    if (!pg_input_error || !pg_file_error) goto fail;
    b3 = PyTuple_Pack(1, pg_input_error);
    if (!b3) goto fail;
    pg_invalid_error = new_class(m, "InvalidQuadMeshError", b3,
                                 "An invalid quad mesh asked to be written (QuadMesh.write(allow_invalid=True) "
                                 "writes it anyway).");
    pg_convergence_warning = new_class(m, "ConvergenceWarning", PyExc_UserWarning,
                                       "A solve ended unconverged: an eps level stopped at the Newton cap.");
    pg_quality_warning = new_class(m, "QualityWarning", PyExc_UserWarning,
                                   "A quad mesh is invalid (see QuadMesh.invalid_reasons).");
    if (!pg_invalid_error || !pg_convergence_warning || !pg_quality_warning) goto fail;
    if (pg_mesh_init_type(m) < 0 || pg_result_init_type(m) < 0 || pg_quadmesh_init_type(m) < 0) goto fail;
    logging = PyImport_ImportModule("logging");
    json = PyImport_ImportModule("json");
    if (!logging || !json) goto fail;
    g_logger = PyObject_CallMethod(logging, "getLogger", "s", "glpgp");
    g_json_loads = PyObject_GetAttrString(json, "loads");
    if (!g_logger || !g_json_loads) goto fail;
    if (PyModule_AddStringConstant(m, "__version__", GLPGP_VERSION) < 0) goto fail;
    Py_DECREF(b1);
    Py_DECREF(b2);
    Py_DECREF(b3);
    Py_DECREF(logging);
    Py_DECREF(json);
    g_log_live = 1;
    glpgp_log_set_callback(log_to_python, NULL);
    return m;
fail:
    Py_XDECREF(b1);
    Py_XDECREF(b2);
    Py_XDECREF(b3);
    Py_XDECREF(logging);
    Py_XDECREF(json);
    Py_DECREF(m);
    return NULL;
}
