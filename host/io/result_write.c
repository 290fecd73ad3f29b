/* io/result_write.c: the result writers (glpgp/io.h): legacy ASCII VTK,
 * binary VTK XML (.vtu, through vtu.c), textured OBJ, and the dispatch by
 * extension; every one adds its file to an output set. Phases come from the
 * phase module. */
#include "glpgp/io.h"
#include "glpgp/cross.h"
#include "glpgp/kinds.h"
#include "glpgp/phase.h"
#include "glpgp/util.h"

#include "names.h"
#include "vtu.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

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

/* alpha = arg(w) / 4 in [0, pi/2): the cross's direction closest above the x axis */
static double cross_alpha(const double *w)
{
    double a = atan2(w[1], w[0]) / 4.0;
    return a < 0.0 ? a + GLPGP_PI / 2.0 : a;
}

/* Matching of triangle t of a coupled result (glpgp/cross.h): r_1 + 4 r_2,
 * the quarter turns of corners 1 and 2 relative to corner 0's representative. */
static int coupled_match(const glpgp_mesh *m, const glpgp_result *r, int t)
{
    const int *v = m->tri + 3 * t;
    return glpgp_cross_turn(r->field + 2 * v[0], r->field + 2 * v[1]) +
           4 * glpgp_cross_turn(r->field + 2 * v[0], r->field + 2 * v[2]);
}

/* ---- legacy VTK ------------------------------------------------------- */

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

    if (r->cross) { /* cross field w = exp(4 i alpha), and alpha in [0, pi/2) */
        const double *w = r->cross->w;
        fprintf(f, "SCALARS cross_w double 2\nLOOKUP_TABLE default\n");
        for (int i = 0; i < nv; i++) fprintf(f, "%.17g %.17g\n", w[2 * i], w[2 * i + 1]);
        fprintf(f, "SCALARS cross_alpha double 1\nLOOKUP_TABLE default\n");
        for (int i = 0; i < nv; i++) fprintf(f, "%.17g\n", cross_alpha(w + 2 * i));
    }

    int have_sing = r->osc[0].singular || r->osc[1].singular;
    if (have_sing || r->cross) {
        fprintf(f, "CELL_DATA %d\n", nt);
        for (int k = 0; k < 2; k++) {
            const signed char *s = r->osc[k].singular;
            fprintf(f, "SCALARS singular_%s int 1\nLOOKUP_TABLE default\n", osc_name[k]);
            for (int t = 0; t < nt; t++) fprintf(f, "%d\n", s ? (int)s[t] : 0);
        }
        if (r->cross) { /* cross-field index of each triangle, in quarters (-1, 0, +1) */
            fprintf(f, "SCALARS cross_index4 int 1\nLOOKUP_TABLE default\n");
            for (int t = 0; t < nt; t++) fprintf(f, "%d\n", (int)r->cross->winding[t]);
        }
        if (r->coupled && r->field) { /* coupled solve: each triangle's matching r_1 + 4 r_2 */
            fprintf(f, "SCALARS cross_coupled int 1\nLOOKUP_TABLE default\n");
            for (int t = 0; t < nt; t++) fprintf(f, "%d\n", coupled_match(m, r, t));
        }
    }
}

/* ---- VTK XML (.vtu) ---------------------------------------------------- */

/* Tuple producers of the result arrays (vtu_fill_fn). */
typedef struct res_ctx {
    const glpgp_mesh *m;
    const glpgp_result *r;
    int k; /* oscillator */
} res_ctx;

static void fill_points(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    double *o = out;
    for (size_t i = 0; i < n; i++) {
        o[3 * i] = x->m->xy[2 * (first + i)];
        o[3 * i + 1] = x->m->xy[2 * (first + i) + 1];
        o[3 * i + 2] = 0.0;
    }
}
static void fill_conn(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    memcpy(out, x->m->tri + first, n * sizeof(int)); /* one index per tuple */
}
static void fill_offsets(const void *c, size_t first, size_t n, void *out)
{
    (void)c;
    int *o = out;
    for (size_t i = 0; i < n; i++) o[i] = (int)(3 * (first + i + 1));
}
static void fill_types(const void *c, size_t first, size_t n, void *out)
{
    (void)c;
    (void)first;
    memset(out, 5, n); /* VTK_TRIANGLE */
}
static void fill_z(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    memcpy(out, x->r->osc[x->k].z + 2 * first, 2 * n * sizeof(double));
}
static void fill_theta(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    const double *z = x->r->osc[x->k].z + 2 * first;
    double *o = out;
    for (size_t i = 0; i < n; i++) o[i] = glpgp_theta(z[2 * i], z[2 * i + 1]);
}
static void fill_zabs(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    const double *z = x->r->osc[x->k].z + 2 * first;
    double *o = out;
    for (size_t i = 0; i < n; i++) o[i] = hypot(z[2 * i], z[2 * i + 1]);
}
static void fill_dirichlet(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    const unsigned char *d = x->r->osc[x->k].dirichlet + first;
    signed char *o = out;
    for (size_t i = 0; i < n; i++) o[i] = d[i] ? 1 : 0;
}
static void fill_field(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    const double *u = x->r->field + 2 * first;
    double *o = out;
    for (size_t i = 0; i < n; i++) {
        if (x->k == 0) { /* U */
            o[3 * i] = u[2 * i];
            o[3 * i + 1] = u[2 * i + 1];
        } else { /* V = U rotated by +90 degrees */
            o[3 * i] = -u[2 * i + 1];
            o[3 * i + 1] = u[2 * i];
        }
        o[3 * i + 2] = 0.0;
    }
}
static void fill_singular(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    const signed char *s = x->r->osc[x->k].singular;
    if (s)
        memcpy(out, s + first, n);
    else
        memset(out, 0, n);
}
static void fill_cross_w(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    memcpy(out, x->r->cross->w + 2 * first, 2 * n * sizeof(double));
}
static void fill_cross_alpha(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    double *o = out;
    for (size_t i = 0; i < n; i++) o[i] = cross_alpha(x->r->cross->w + 2 * (first + i));
}
static void fill_cross_index(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    memcpy(out, x->r->cross->winding + first, n);
}
static void fill_coupled(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    signed char *o = out;
    for (size_t t = 0; t < n; t++) o[t] = (signed char)coupled_match(x->m, x->r, (int)(first + t));
}
static void fill_h(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    (void)first;
    (void)n;
    *(double *)out = x->r->size;
}

static glpgp_status vtu_result(FILE *f, const glpgp_mesh *m, const glpgp_options *o, const glpgp_result *r,
                               int level)
{
    static const char *const zn[2] = {"z_u", "z_v"}, *const tn[2] = {"theta_u", "theta_v"},
                             *const an[2] = {"zabs_u", "zabs_v"}, *const dn[2] = {"dirichlet_u", "dirichlet_v"},
                             *const fn[2] = {"field_u", "field_v"}, *const sn[2] = {"singular_u", "singular_v"};
    res_ctx ctx[2] = {{m, r, 0}, {m, r, 1}};
    const size_t nv = (size_t)m->nv, nt = (size_t)m->nt;
    vtu_array a[24];
    int na = 0;
#define ARR(sec, nm, ty, es, nc, cnt, fl, cx) \
    a[na++] = (vtu_array){(sec), (nm), (ty), (es), (nc), (cnt), (fl), (cx)}
    ARR(VTU_FIELD, "h", "Float64", 8, 1, 1, fill_h, &ctx[0]);
    for (int k = 0; k < 2; k++) ARR(VTU_POINTDATA, zn[k], "Float64", 8, 2, nv, fill_z, &ctx[k]);
    for (int k = 0; k < 2; k++) ARR(VTU_POINTDATA, tn[k], "Float64", 8, 1, nv, fill_theta, &ctx[k]);
    for (int k = 0; k < 2; k++) ARR(VTU_POINTDATA, an[k], "Float64", 8, 1, nv, fill_zabs, &ctx[k]);
    for (int k = 0; k < 2; k++)
        if (r->osc[k].dirichlet) ARR(VTU_POINTDATA, dn[k], "Int8", 1, 1, nv, fill_dirichlet, &ctx[k]);
    if (r->field)
        for (int k = 0; k < 2; k++) ARR(VTU_POINTDATA, fn[k], "Float64", 8, 3, nv, fill_field, &ctx[k]);
    if (r->osc[0].singular || r->osc[1].singular)
        for (int k = 0; k < 2; k++) ARR(VTU_CELLDATA, sn[k], "Int8", 1, 1, nt, fill_singular, &ctx[k]);
    if (r->cross) {
        ARR(VTU_POINTDATA, "cross_w", "Float64", 8, 2, nv, fill_cross_w, &ctx[0]);
        ARR(VTU_POINTDATA, "cross_alpha", "Float64", 8, 1, nv, fill_cross_alpha, &ctx[0]);
        ARR(VTU_CELLDATA, "cross_index4", "Int8", 1, 1, nt, fill_cross_index, &ctx[0]);
    }
    if (r->coupled && r->field) ARR(VTU_CELLDATA, "cross_coupled", "Int8", 1, 1, nt, fill_coupled, &ctx[0]);
    ARR(VTU_POINTS, "Points", "Float64", 8, 3, nv, fill_points, &ctx[0]);
    ARR(VTU_CELLS, "connectivity", "Int32", 4, 1, 3 * nt, fill_conn, &ctx[0]);
    ARR(VTU_CELLS, "offsets", "Int32", 4, 1, nt, fill_offsets, &ctx[0]);
    ARR(VTU_CELLS, "types", "UInt8", 1, 1, nt, fill_types, &ctx[0]);
#undef ARR
    char comment[256];
    if (o)
        snprintf(comment, sizeof comment, "glpgp %s result: method %s, energy %s, h %.17g", GLPGP_VERSION,
                 method_name(o->method), energy_name(o->energy), r->size);
    else
        snprintf(comment, sizeof comment, "glpgp %s result: h %.17g", GLPGP_VERSION, r->size);
    GLPGP_CHECK(vtu_write(f, comment, nv, nt, a, na, level));
    return GLPGP_OK;
}

/* ---- textured OBJ ------------------------------------------------------ */

static void obj_body(FILE *f, const glpgp_mesh *m, const glpgp_result *r)
{
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
}

/* ---- writers and dispatch ------------------------------------------------ */

enum { FMT_NONE = 0, FMT_VTK, FMT_VTU, FMT_OBJ };

static int result_format(const char *path)
{
    if (!path) return FMT_NONE;
    return glpgp_has_ext(path, ".vtk") ? FMT_VTK
           : glpgp_has_ext(path, ".vtu") ? FMT_VTU
           : glpgp_has_ext(path, ".obj") ? FMT_OBJ
                                         : FMT_NONE;
}

/* Add the result file in format fmt (level: .vtu compression) to s. */
static glpgp_status add_result(glpgp_output_set *s, const glpgp_mesh *m, const glpgp_options *opts,
                               const glpgp_result *r, const char *path, int fmt, int level)
{
    FILE *f;
    if (!path) return GLPGP_FAIL(GLPGP_ERR_ARG, "no output path");
    if (fmt == FMT_NONE)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "unsupported output format '%s' (use .vtk, .vtu or .obj)", path);
    GLPGP_CHECK(check_result(m, r));
    GLPGP_CHECK(glpgp_output_set_open(s, path, &f));
    if (fmt == FMT_VTK)
        vtk_body(f, m, opts, r);
    else if (fmt == FMT_OBJ)
        obj_body(f, m, r);
    else
        GLPGP_CHECK(vtu_result(f, m, opts, r, level < 0 ? (glpgp_io_have_zlib() ? GLPGP_VTU_DEFAULT_LEVEL : 0) : level));
    return GLPGP_OK;
}

/* An output set of one file. */
static glpgp_status write_one(const glpgp_mesh *m, const glpgp_options *opts, const glpgp_result *r,
                              const char *path, int fmt, int level)
{
    glpgp_output_set *s = NULL;
    GLPGP_CHECK(glpgp_output_set_create(&s));
    glpgp_status st = add_result(s, m, opts, r, path, fmt, level);
    if (st == GLPGP_OK) st = glpgp_output_set_commit(s);
    glpgp_output_set_destroy(&s);
    if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
    return st;
}

glpgp_status glpgp_write_vtk(const glpgp_mesh *m, const glpgp_result *r, const char *path)
{
    return write_one(m, NULL, r, path, FMT_VTK, 0);
}

glpgp_status glpgp_write_vtu(const glpgp_mesh *m, const glpgp_options *opts, const glpgp_result *r,
                             const char *path, int level)
{
    return write_one(m, opts, r, path, FMT_VTU, level);
}

glpgp_status glpgp_write_obj_textured(const glpgp_mesh *m, const glpgp_result *r, const char *path)
{
    return write_one(m, NULL, r, path, FMT_OBJ, 0);
}

int glpgp_result_path_supported(const char *path) { return result_format(path) != FMT_NONE; }

glpgp_status glpgp_output_set_result(glpgp_output_set *s, const glpgp_mesh *m, const glpgp_options *opts,
                                     const glpgp_result *r, const char *path)
{
    return add_result(s, m, opts, r, path, result_format(path), -1);
}

glpgp_status glpgp_write_result(const glpgp_mesh *m, const glpgp_options *opts, const glpgp_result *r,
                                const char *path)
{
    return write_one(m, opts, r, path, result_format(path), -1);
}
