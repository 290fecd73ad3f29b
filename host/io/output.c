/* io/output.c: the atomic-file helper (temporary name + rename), the early
 * output-path check and the result writers: legacy VTK, textured OBJ,
 * statistics JSON (glpgp/io.h). Phases come from the phase module. */
#include "glpgp/io.h"
#include "glpgp/phase.h"
#include "glpgp/util.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>


/* ---- atomic file ------------------------------------------------------- */

static char *dup_str(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

static void atomic_release(glpgp_atomic_file *af)
{
    free(af->path);
    free(af->tmp);
    af->path = NULL;
    af->tmp = NULL;
    af->f = NULL;
}

glpgp_status glpgp_atomic_open(glpgp_atomic_file *af, const char *path)
{
    af->f = NULL;
    af->path = NULL;
    af->tmp = NULL;
    if (!path || !*path) return GLPGP_FAIL(GLPGP_ERR_ARG, "empty output path");
    struct stat sb;
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode))
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': it is a directory", path);

    size_t n = strlen(path) + 48;
    af->path = dup_str(path);
    af->tmp = malloc(n);
    if (!af->path || !af->tmp) {
        atomic_release(af);
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory opening '%s'", path);
    }
    static unsigned counter;
    int err = 0;
    for (int attempt = 0; attempt < 100; attempt++) {
        snprintf(af->tmp, n, "%s.tmp.%ld.%u", path, (long)getpid(), counter++);
        errno = 0;
        af->f = fopen(af->tmp, "wbx"); /* C11 exclusive creation */
        if (af->f) return GLPGP_OK;
        err = errno;
        if (err != EEXIST) break;
    }
    atomic_release(af);
    return GLPGP_FAIL(GLPGP_ERR_IO, "cannot create output file '%s': %s", path,
                      err ? strerror(err) : "unknown error");
}

glpgp_status glpgp_atomic_commit(glpgp_atomic_file *af)
{
    if (!af->f || !af->tmp || !af->path)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "commit of an output file that is not open");
    int err = 0;
    const char *what = NULL;
    if (ferror(af->f)) {
        err = EIO;
        what = "write";
    }
    errno = 0;
    if (fflush(af->f) != 0 && !what) {
        err = errno ? errno : EIO;
        what = "write";
    }
    errno = 0;
    if (fclose(af->f) != 0 && !what) {
        err = errno ? errno : EIO;
        what = "close";
    }
    af->f = NULL;
    if (!what) {
        errno = 0;
        if (rename(af->tmp, af->path) != 0) {
            err = errno ? errno : EIO;
            what = "rename";
        }
    }
    if (what) {
        remove(af->tmp);
        glpgp_status st = GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s' (%s failed: %s)", af->path,
                                     what, strerror(err));
        atomic_release(af);
        return st;
    }
    atomic_release(af);
    return GLPGP_OK;
}

void glpgp_atomic_abort(glpgp_atomic_file *af)
{
    if (af->f) fclose(af->f);
    af->f = NULL;
    if (af->tmp) remove(af->tmp);
    atomic_release(af);
}

/* ---- helpers ----------------------------------------------------------- */

glpgp_status glpgp_output_path_check(const char *path)
{
    char dir[4096];
    const char *slash = strrchr(path, '/');
    if (!*path) return GLPGP_FAIL(GLPGP_ERR_ARG, "empty output path");
    if (!slash) {
        strcpy(dir, ".");
    } else if (slash == path) {
        strcpy(dir, "/");
    } else {
        size_t n = (size_t)(slash - path);
        if (n >= sizeof dir) return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': path too long", path);
        memcpy(dir, path, n);
        dir[n] = '\0';
    }
    struct stat sb;
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': directory '%s' does not exist", path, dir);
    if (access(dir, W_OK | X_OK) != 0)
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': directory '%s' is not writable", path, dir);
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode))
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': it is a directory", path);
    return GLPGP_OK;
}

static glpgp_status check_result(const glpgp_mesh *m, const glpgp_result *r)
{
    if (!m || !r) return GLPGP_FAIL(GLPGP_ERR_ARG, "no mesh or no result to write");
    if (r->nv != m->nv || r->nt != m->nt)
        return GLPGP_FAIL(GLPGP_ERR_ARG,
                          "result (%d vertices, %d triangles) does not match the mesh "
                          "(%d vertices, %d triangles)",
                          r->nv, r->nt, m->nv, m->nt);
    if (!r->osc[0].z || !r->osc[1].z)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "result has no oscillator values");
    return GLPGP_OK;
}

static const char *method_name(int v)
{
    return v == GLPGP_METHOD_PGP ? "pgp" : v == GLPGP_METHOD_GL ? "gl" : "unknown";
}
static const char *energy_name(int v)
{
    return v == GLPGP_ELEM_P1 ? "p1" : v == GLPGP_ELEM_TRANSPORT ? "transport" : "unknown";
}
static const char *hess_name(int v)
{
    return v == GLPGP_HESS_PAPER       ? "paper"
           : v == GLPGP_HESS_PROJECTED ? "projected"
           : v == GLPGP_HESS_EXACT     ? "exact"
           : v == GLPGP_HESS_MIXED     ? "mixed"
                                       : "unknown";
}
static const char *field_name(int v)
{
    return v == GLPGP_FIELD_BOUNDARY ? "boundary"
           : v == GLPGP_FIELD_RADIAL ? "radial"
           : v == GLPGP_FIELD_FILE   ? "file"
                                     : "unknown";
}
static const char *init_name(int v)
{
    return v == GLPGP_INIT_NAIVE ? "naive" : v == GLPGP_INIT_ONE ? "one" : "unknown";
}

/* ---- VTK --------------------------------------------------------------- */

static void vtk_body(FILE *f, const glpgp_mesh *m, const glpgp_options *o, const glpgp_result *r)
{
    static const char *const osc_name[2] = {"u", "v"};
    const int nv = m->nv, nt = m->nt;
    fprintf(f, "# vtk DataFile Version 3.0\n");
    if (o)
        fprintf(f, "glpgp %s result: method %s, energy %s, h %.9g\n", GLPGP_VERSION,
                method_name(o->method), energy_name(o->energy), r->size);
    else
        fprintf(f, "glpgp %s result: h %.9g\n", GLPGP_VERSION, r->size);
    fprintf(f, "ASCII\nDATASET UNSTRUCTURED_GRID\n");
    fprintf(f, "POINTS %d double\n", nv);
    for (int i = 0; i < nv; i++) fprintf(f, "%.17g %.17g 0\n", m->xy[2 * i], m->xy[2 * i + 1]);
    fprintf(f, "CELLS %d %ld\n", nt, 4L * nt);
    for (int t = 0; t < nt; t++)
        fprintf(f, "3 %d %d %d\n", m->tri[3 * t], m->tri[3 * t + 1], m->tri[3 * t + 2]);
    fprintf(f, "CELL_TYPES %d\n", nt);
    for (int t = 0; t < nt; t++) fputs("5\n", f);

    fprintf(f, "POINT_DATA %d\n", nv);
    for (int k = 0; k < 2; k++) {
        const double *z = r->osc[k].z;
        fprintf(f, "SCALARS z_%s double 2\nLOOKUP_TABLE default\n", osc_name[k]);
        for (int i = 0; i < nv; i++) fprintf(f, "%.17g %.17g\n", z[2 * i], z[2 * i + 1]);
    }
    for (int k = 0; k < 2; k++) {
        const double *z = r->osc[k].z;
        fprintf(f, "SCALARS theta_%s double 1\nLOOKUP_TABLE default\n", osc_name[k]);
        for (int i = 0; i < nv; i++) fprintf(f, "%.17g\n", glpgp_theta(z[2 * i], z[2 * i + 1]));
    }
    for (int k = 0; k < 2; k++) {
        const double *z = r->osc[k].z;
        fprintf(f, "SCALARS zabs_%s double 1\nLOOKUP_TABLE default\n", osc_name[k]);
        for (int i = 0; i < nv; i++) fprintf(f, "%.17g\n", hypot(z[2 * i], z[2 * i + 1]));
    }
    for (int k = 0; k < 2; k++) {
        const unsigned char *d = r->osc[k].dirichlet;
        if (!d) continue;
        fprintf(f, "SCALARS dirichlet_%s int 1\nLOOKUP_TABLE default\n", osc_name[k]);
        for (int i = 0; i < nv; i++) fputs(d[i] ? "1\n" : "0\n", f);
    }
    if (r->field) {
        const double *u = r->field;
        fprintf(f, "VECTORS field_u double\n");
        for (int i = 0; i < nv; i++) fprintf(f, "%.17g %.17g 0\n", u[2 * i], u[2 * i + 1]);
        fprintf(f, "VECTORS field_v double\n"); /* V = U rotated by +90 degrees */
        for (int i = 0; i < nv; i++) fprintf(f, "%.17g %.17g 0\n", -u[2 * i + 1], u[2 * i]);
    }

    int have_sing = r->osc[0].singular || r->osc[1].singular;
    if (have_sing) {
        fprintf(f, "CELL_DATA %d\n", nt);
        for (int k = 0; k < 2; k++) {
            const signed char *s = r->osc[k].singular;
            fprintf(f, "SCALARS singular_%s int 1\nLOOKUP_TABLE default\n", osc_name[k]);
            for (int t = 0; t < nt; t++) fprintf(f, "%d\n", s ? (int)s[t] : 0);
        }
    }
}

glpgp_status glpgp_write_vtk(const glpgp_mesh *m, const glpgp_result *r, const char *path)
{
    GLPGP_CHECK(check_result(m, r));
    glpgp_atomic_file af;
    GLPGP_CHECK(glpgp_atomic_open(&af, path));
    vtk_body(af.f, m, NULL, r);
    GLPGP_CHECK(glpgp_atomic_commit(&af));
    return GLPGP_OK;
}

/* ---- OBJ --------------------------------------------------------------- */

glpgp_status glpgp_write_obj_textured(const glpgp_mesh *m, const glpgp_result *r,
                                      const char *path)
{
    GLPGP_CHECK(check_result(m, r));
    glpgp_atomic_file af;
    GLPGP_CHECK(glpgp_atomic_open(&af, path));
    FILE *f = af.f;
    const double *zu = r->osc[0].z, *zv = r->osc[1].z;
    fprintf(f, "# glpgp %s textured result: %d vertices, %d triangles, h %.9g\n", GLPGP_VERSION,
            m->nv, m->nt, r->size);
    fprintf(f, "# vt = (theta_u, theta_v) per triangle corner, unwrapped inside each triangle\n"
               "# (one period = one quad). View with a checker texture and REPEAT wrapping.\n");
    for (int i = 0; i < m->nv; i++) fprintf(f, "v %.17g %.17g 0\n", m->xy[2 * i], m->xy[2 * i + 1]);
    for (int t = 0; t < m->nt; t++) {
        const int *c = m->tri + 3 * t;
        /* per-triangle charts of theta_u and theta_v (unwrapped around corner 0) */
        double thu[3], thv[3], cu[3], cv[3];
        for (int k = 0; k < 3; k++) {
            thu[k] = glpgp_theta(zu[2 * c[k]], zu[2 * c[k] + 1]);
            thv[k] = glpgp_theta(zv[2 * c[k]], zv[2 * c[k] + 1]);
        }
        glpgp_phase_chart(thu, cu);
        glpgp_phase_chart(thv, cv);
        for (int k = 0; k < 3; k++) fprintf(f, "vt %.17g %.17g\n", cu[k], cv[k]);
    }
    for (int t = 0; t < m->nt; t++) {
        const int *c = m->tri + 3 * t;
        long vt = 3L * t + 1;
        fprintf(f, "f %d/%ld %d/%ld %d/%ld\n", c[0] + 1, vt, c[1] + 1, vt + 1, c[2] + 1, vt + 2);
    }
    GLPGP_CHECK(glpgp_atomic_commit(&af));
    return GLPGP_OK;
}

/* ---- JSON -------------------------------------------------------------- */

#define JW_MAX_DEPTH 32

typedef struct jw {
    FILE *f;
    int depth;
    unsigned char used[JW_MAX_DEPTH]; /* container at this depth already has a member */
} jw;

static void jw_indent(jw *w)
{
    fputc('\n', w->f);
    for (int i = 0; i < w->depth; i++) fputs("  ", w->f);
}

/* Separator + indentation before a new member/element. */
static void jw_sep(jw *w)
{
    if (w->depth == 0) return;
    if (w->used[w->depth]) fputc(',', w->f);
    w->used[w->depth] = 1;
    jw_indent(w);
}

/* JSON string with escapes; invalid UTF-8 bytes become U+FFFD. */
static void jw_string(jw *w, const char *s)
{
    FILE *f = w->f;
    const unsigned char *p = (const unsigned char *)s;
    fputc('"', f);
    while (*p) {
        unsigned char c = *p;
        if (c == '"' || c == '\\') {
            fputc('\\', f);
            fputc(c, f);
            p++;
        } else if (c == '\n') {
            fputs("\\n", f);
            p++;
        } else if (c == '\t') {
            fputs("\\t", f);
            p++;
        } else if (c == '\r') {
            fputs("\\r", f);
            p++;
        } else if (c < 0x20 || c == 0x7f) {
            fprintf(f, "\\u%04x", c);
            p++;
        } else if (c < 0x80) {
            fputc(c, f);
            p++;
        } else {
            int len = (c & 0xe0) == 0xc0 ? 2 : (c & 0xf0) == 0xe0 ? 3 : (c & 0xf8) == 0xf0 ? 4 : 0;
            int ok = len > 0 && c != 0xc0 && c != 0xc1 && c < 0xf5;
            for (int k = 1; ok && k < len; k++)
                if ((p[k] & 0xc0) != 0x80) ok = 0;
            if (ok) {
                fwrite(p, 1, (size_t)len, f);
                p += len;
            } else {
                fputs("\\ufffd", f);
                p++;
            }
        }
    }
    fputc('"', f);
}

static void jw_key(jw *w, const char *key)
{
    jw_sep(w);
    if (key) {
        jw_string(w, key);
        fputs(": ", w->f);
    }
}

static void jw_open(jw *w, const char *key, char c)
{
    jw_key(w, key);
    fputc(c, w->f);
    if (w->depth < JW_MAX_DEPTH - 1) w->depth++;
    w->used[w->depth] = 0;
}

static void jw_close(jw *w, char c)
{
    int had = w->used[w->depth];
    if (w->depth > 0) w->depth--;
    if (had) jw_indent(w);
    fputc(c, w->f);
}

static void jw_num(jw *w, const char *key, double v)
{
    jw_key(w, key);
    if (!isfinite(v)) {
        fputs("null", w->f);
        return;
    }
    /* shortest of %.15g / %.16g / %.17g that reads back exactly (lossless) */
    char buf[40];
    for (int prec = 15; prec <= 17; prec++) {
        snprintf(buf, sizeof buf, "%.*g", prec, v);
        if (prec == 17 || strtod(buf, NULL) == v) break;
    }
    fputs(buf, w->f);
}

static void jw_int(jw *w, const char *key, long v)
{
    jw_key(w, key);
    fprintf(w->f, "%ld", v);
}

static void jw_str(jw *w, const char *key, const char *v)
{
    jw_key(w, key);
    if (v)
        jw_string(w, v);
    else
        fputs("null", w->f);
}

static void jw_null(jw *w, const char *key)
{
    jw_key(w, key);
    fputs("null", w->f);
}

static void jw_bool(jw *w, const char *key, int v)
{
    jw_key(w, key);
    fputs(v ? "true" : "false", w->f);
}

static void json_body(FILE *f, const glpgp_mesh *m, const glpgp_options *o, const glpgp_result *r,
                      const glpgp_stats_extra *x)
{
    static const char *const oname[2] = {"u", "v"};
    jw w0 = {f, 0, {0}}, *w = &w0;
    const glpgp_osc_result *ou = &r->osc[0], *ov = &r->osc[1];

    jw_open(w, NULL, '{');
    jw_str(w, "version", GLPGP_VERSION);
    jw_str(w, "input", x ? x->input : NULL);
    jw_str(w, "output", x ? x->output : NULL);
    jw_int(w, "vertices", m->nv);
    jw_int(w, "triangles", m->nt);
    jw_num(w, "size", r->size);
    if (o) {
        jw_str(w, "method", method_name(o->method));
        jw_str(w, "energy", energy_name(o->energy));
        jw_str(w, "newton", hess_name(o->hess));
    } else {
        jw_null(w, "method");
        jw_null(w, "energy");
        jw_null(w, "newton");
    }
    jw_str(w, "backend", r->backend);
    if (o) {
        jw_str(w, "field", field_name(o->field));
        jw_str(w, "field_file", o->field == GLPGP_FIELD_FILE ? o->field_file : NULL);
        jw_str(w, "init", init_name(o->init));
        jw_open(w, "options", '{');
        jw_num(w, "eps0", o->eps0);
        jw_num(w, "eps_ratio", o->eps_ratio);
        jw_num(w, "eps_min", o->eps_min);
        jw_num(w, "newton_rtol", o->newton_rtol);
        jw_int(w, "newton_max", o->newton_max);
        jw_num(w, "cg_rtol", o->cg_rtol);
        jw_int(w, "cg_max", o->cg_max);
        jw_int(w, "cg_check", o->cg_check);
        if (o->has_center) {
            jw_open(w, "center", '[');
            jw_num(w, NULL, o->center[0]);
            jw_num(w, NULL, o->center[1]);
            jw_close(w, ']');
        } else {
            jw_null(w, "center");
        }
        jw_close(w, '}');
    } else {
        jw_null(w, "field");
        jw_null(w, "field_file");
        jw_null(w, "init");
        jw_null(w, "options");
    }

    jw_open(w, "mesh", '{');
    jw_num(w, "area", m->area);
    jw_num(w, "mean_edge", m->mean_edge);
    jw_int(w, "boundary_loops", m->nloops);
    jw_open(w, "bbox", '[');
    for (int i = 0; i < 4; i++) jw_num(w, NULL, m->bbox[i]);
    jw_close(w, ']');
    jw_int(w, "orientation_fixed", m->orientation_fixed);
    jw_close(w, '}');

    jw_open(w, "singularities", '{');
    for (int k = 0; k < 2; k++) {
        jw_open(w, oname[k], '{');
        jw_int(w, "plus", r->osc[k].plus);
        jw_int(w, "minus", r->osc[k].minus);
        jw_close(w, '}');
    }
    jw_close(w, '}');

    jw_open(w, "zabs", '{');
    for (int k = 0; k < 2; k++) {
        jw_open(w, oname[k], '{');
        jw_num(w, "min", r->osc[k].zabs_min);
        jw_num(w, "p10", r->osc[k].zabs_p10);
        jw_num(w, "median", r->osc[k].zabs_median);
        jw_close(w, '}');
    }
    jw_close(w, '}');

    jw_open(w, "final_energy", '{');
    jw_num(w, "u", ou->energy);
    jw_num(w, "v", ov->energy);
    jw_close(w, '}');

    jw_open(w, "dirichlet", '{');
    jw_int(w, "u", ou->n_dirichlet);
    jw_int(w, "v", ov->n_dirichlet);
    jw_close(w, '}');

    jw_open(w, "newton_iterations", '{');
    jw_int(w, "total", (long)ou->newton_iterations + ov->newton_iterations);
    jw_int(w, "u", ou->newton_iterations);
    jw_int(w, "v", ov->newton_iterations);
    jw_close(w, '}');

    jw_open(w, "cg_iterations", '{');
    jw_int(w, "total", ou->cg_iterations + ov->cg_iterations + r->field_cg_iterations);
    jw_int(w, "u", ou->cg_iterations);
    jw_int(w, "v", ov->cg_iterations);
    jw_int(w, "field", r->field_cg_iterations);
    jw_close(w, '}');

    jw_open(w, "eps_schedule", '{');
    for (int k = 0; k < 2; k++) {
        const glpgp_osc_result *os = &r->osc[k];
        int nl = os->nlevels;
        if (nl < 0) nl = 0;
        if (nl > GLPGP_MAX_LEVELS) nl = GLPGP_MAX_LEVELS;
        jw_open(w, oname[k], '[');
        for (int l = 0; l < nl; l++) {
            const glpgp_level_stats *ls = &os->level[l];
            jw_open(w, NULL, '{');
            jw_int(w, "level", l);
            jw_num(w, "eps", ls->eps);
            jw_int(w, "newton", ls->newton);
            jw_int(w, "cg", ls->cg);
            jw_num(w, "grad0", ls->grad0);
            jw_num(w, "grad", ls->grad);
            jw_num(w, "energy", ls->energy);
            jw_num(w, "median_zabs", ls->median_zabs);
            jw_bool(w, "restarted", ls->restarted);
            jw_int(w, "fallbacks", ls->fallbacks);
            jw_int(w, "backtracked", ls->backtracked);
            jw_num(w, "rtol", ls->rtol);
            jw_bool(w, "capped", ls->capped);
            jw_close(w, '}');
        }
        jw_close(w, ']');
    }
    jw_close(w, '}');

    jw_open(w, "seconds", '{');
    if (x && x->seconds_read >= 0)
        jw_num(w, "read", x->seconds_read);
    else
        jw_null(w, "read");
    jw_num(w, "setup", r->seconds_setup);
    jw_num(w, "field", r->seconds_field);
    jw_num(w, "u", ou->seconds);
    jw_num(w, "v", ov->seconds);
    jw_num(w, "total", r->seconds_total);
    jw_close(w, '}');

    jw_close(w, '}');
    fputc('\n', f);
}

glpgp_status glpgp_write_stats_json(const glpgp_mesh *m, const glpgp_options *opts,
                                    const glpgp_result *r, const char *path,
                                    const glpgp_stats_extra *extra)
{
    if (!m || !r) return GLPGP_FAIL(GLPGP_ERR_ARG, "no mesh or no result to write");
    glpgp_atomic_file af;
    GLPGP_CHECK(glpgp_atomic_open(&af, path));
    json_body(af.f, m, opts, r, extra);
    GLPGP_CHECK(glpgp_atomic_commit(&af));
    return GLPGP_OK;
}

/* ---- dispatch ---------------------------------------------------------- */

int glpgp_result_path_supported(const char *path)
{
    return path && (glpgp_has_ext(path, ".vtk") || glpgp_has_ext(path, ".obj"));
}

glpgp_status glpgp_write_result(const glpgp_mesh *m, const glpgp_options *opts,
                                const glpgp_result *r, const char *path)
{
    if (!path) return GLPGP_FAIL(GLPGP_ERR_ARG, "no output path");
    if (glpgp_has_ext(path, ".vtk")) {
        GLPGP_CHECK(check_result(m, r));
        glpgp_atomic_file af;
        GLPGP_CHECK(glpgp_atomic_open(&af, path));
        vtk_body(af.f, m, opts, r);
        GLPGP_CHECK(glpgp_atomic_commit(&af));
        return GLPGP_OK;
    }
    if (glpgp_has_ext(path, ".obj")) {
        GLPGP_CHECK(glpgp_write_obj_textured(m, r, path));
        return GLPGP_OK;
    }
    return GLPGP_FAIL(GLPGP_ERR_ARG, "unsupported output format '%s' (use .vtk or .obj)", path);
}
