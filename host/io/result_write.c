/* io/result_write.c: the result writers (glpgp/io.h): legacy ASCII VTK,
 * binary VTK XML (.vtu, through vtu.c), textured OBJ, and the dispatch by
 * extension; every one adds its file to an output set. Phases come from the
 * phase module. */
#include "glpgp/io.h"
#include "glpgp/cross.h"
#include "glpgp/kinds.h"
#include "glpgp/phase.h"
#include "glpgp/surface.h"
#include "glpgp/surfsolve.h"
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

/* out <- the point of vertex i (z = 0 in the plane) */
static void point3(const glpgp_mesh *m, size_t i, double *out)
{
    if (m->xyz) {
        memcpy(out, m->xyz + 3 * i, 3 * sizeof(double));
        return;
    }
    out[0] = m->xy[2 * i];
    out[1] = m->xy[2 * i + 1];
    out[2] = 0.0;
}

/* out <- the direction (c, s) of vertex i as a 3D vector: in the plane as it
 * is, on a surface from the vertex's frame (glpgp_surface_vertex_vector). */
static void vector3(const glpgp_mesh *m, size_t i, double c, double s, double *out)
{
    if (m->surf) {
        glpgp_surface_vertex_vector(m, (int)i, c, s, out);
        return;
    }
    out[0] = c;
    out[1] = s;
    out[2] = 0.0;
}

/* Matching of triangle t of a coupled result (glpgp/cross.h): r_1 + 4 r_2,
 * the quarter turns of corners 1 and 2 relative to corner 0's representative. */
static int coupled_match(const glpgp_mesh *m, const glpgp_result *r, int t)
{
    return glpgp_coupled_corner_turn(m, r->field, t, 1) + 4 * glpgp_coupled_corner_turn(m, r->field, t, 2);
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
    for (int i = 0; i < nv; i++) {
        if (m->xyz)
            fprintf(f, "%.17g %.17g %.17g\n", m->xyz[3 * i], m->xyz[3 * i + 1], m->xyz[3 * i + 2]);
        else
            fprintf(f, "%.17g %.17g 0\n", m->xy[2 * i], m->xy[2 * i + 1]);
    }
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
    if (r->field && m->surf) { /* a surface: the vertices' frames' directions in 3D */
        const double *u = r->field;
        for (int k = 0; k < 2; k++) {
            fprintf(f, "VECTORS field_%s double\n", osc_name[k]);
            for (int i = 0; i < nv; i++) {
                double d[3];
                vector3(m, (size_t)i, k ? -u[2 * i + 1] : u[2 * i], k ? u[2 * i] : u[2 * i + 1], d);
                fprintf(f, "%.17g %.17g %.17g\n", d[0], d[1], d[2]);
            }
        }
        /* and U as the solve holds it, (cos, sin) in each vertex's frame: the
         * 3D vector of a boundary vertex is clamped to its fan, this is exact
         * (what glpgp extract reads back) */
        fprintf(f, "SCALARS field_frame double 2\nLOOKUP_TABLE default\n");
        for (int i = 0; i < nv; i++) fprintf(f, "%.17g %.17g\n", u[2 * i], u[2 * i + 1]);
    } else if (r->field) {
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
        if (m->surf) { /* the cross's direction alpha as a 3D vector */
            fprintf(f, "VECTORS cross_dir double\n");
            for (int i = 0; i < nv; i++) {
                double d[3];
                const double a = cross_alpha(w + 2 * i);
                vector3(m, (size_t)i, cos(a), sin(a), d);
                fprintf(f, "%.17g %.17g %.17g\n", d[0], d[1], d[2]);
            }
        }
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
    const int *gid;   /* piece: global id of each point (NULL: the point's index) */
    int nv_owned;     /* piece: points >= nv_owned are ghosts (vtkGhostType 1) */
} res_ctx;

static void fill_points(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    double *o = out;
    for (size_t i = 0; i < n; i++) point3(x->m, first + i, o + 3 * i);
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
    if (x->m && x->m->surf) { /* a surface: the vertices' frames' directions in 3D */
        for (size_t i = 0; i < n; i++)
            vector3(x->m, first + i, x->k ? -u[2 * i + 1] : u[2 * i], x->k ? u[2 * i] : u[2 * i + 1], o + 3 * i);
        return;
    }
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
static void fill_field_frame(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    memcpy(out, x->r->field + 2 * first, 2 * n * sizeof(double));
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
static void fill_cross_dir(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    double *o = out;
    for (size_t i = 0; i < n; i++) {
        const double a = cross_alpha(x->r->cross->w + 2 * (first + i));
        vector3(x->m, first + i, cos(a), sin(a), o + 3 * i);
    }
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
static void fill_gid(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    long long *o = out;
    for (size_t i = 0; i < n; i++) o[i] = x->gid ? x->gid[first + i] : (long long)(first + i);
}
static void fill_ghost(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    unsigned char *o = out;
    for (size_t i = 0; i < n; i++) o[i] = first + i >= (size_t)x->nv_owned; /* 1: DUPLICATEPOINT */
}
static void fill_h(const void *c, size_t first, size_t n, void *out)
{
    const res_ctx *x = c;
    (void)first;
    (void)n;
    *(double *)out = x->r->size;
}

/* The arrays of a result file (ctx[0..1]: the producers' contexts, one per
 * oscillator) into a[] (room for 28), their count returned. piece: a part's
 * piece, with the point arrays global_id (Int64) and vtkGhostType (UInt8,
 * 1 = a ghost point: VTK's DUPLICATEPOINT) added. */
static int result_arrays(const res_ctx ctx[2], const glpgp_result *r, size_t nv, size_t nt, int piece, vtu_array *a)
{
    static const char *const zn[2] = {"z_u", "z_v"}, *const tn[2] = {"theta_u", "theta_v"},
                             *const an[2] = {"zabs_u", "zabs_v"}, *const dn[2] = {"dirichlet_u", "dirichlet_v"},
                             *const fn[2] = {"field_u", "field_v"}, *const sn[2] = {"singular_u", "singular_v"};
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
    if (r->field && ctx[0].m && ctx[0].m->surf) /* U in the vertices' frames, exact (see the legacy writer) */
        ARR(VTU_POINTDATA, "field_frame", "Float64", 8, 2, nv, fill_field_frame, &ctx[0]);
    if (piece) {
        ARR(VTU_POINTDATA, "global_id", "Int64", 8, 1, nv, fill_gid, &ctx[0]);
        ARR(VTU_POINTDATA, "vtkGhostType", "UInt8", 1, 1, nv, fill_ghost, &ctx[0]);
    }
    if (r->osc[0].singular || r->osc[1].singular)
        for (int k = 0; k < 2; k++) ARR(VTU_CELLDATA, sn[k], "Int8", 1, 1, nt, fill_singular, &ctx[k]);
    if (r->cross) {
        ARR(VTU_POINTDATA, "cross_w", "Float64", 8, 2, nv, fill_cross_w, &ctx[0]);
        ARR(VTU_POINTDATA, "cross_alpha", "Float64", 8, 1, nv, fill_cross_alpha, &ctx[0]);
        if (ctx[0].m && ctx[0].m->surf) ARR(VTU_POINTDATA, "cross_dir", "Float64", 8, 3, nv, fill_cross_dir, &ctx[0]);
        ARR(VTU_CELLDATA, "cross_index4", "Int8", 1, 1, nt, fill_cross_index, &ctx[0]);
    }
    if (r->coupled && r->field) ARR(VTU_CELLDATA, "cross_coupled", "Int8", 1, 1, nt, fill_coupled, &ctx[0]);
    ARR(VTU_POINTS, "Points", "Float64", 8, 3, nv, fill_points, &ctx[0]);
    ARR(VTU_CELLS, "connectivity", "Int32", 4, 1, 3 * nt, fill_conn, &ctx[0]);
    ARR(VTU_CELLS, "offsets", "Int32", 4, 1, nt, fill_offsets, &ctx[0]);
    ARR(VTU_CELLS, "types", "UInt8", 1, 1, nt, fill_types, &ctx[0]);
#undef ARR
    return na;
}

/* The .vtu of mesh m and result r; piece: a piece of a parallel file (its
 * points' global ids gid, NULL: the point's index; points >= nv_owned are
 * ghosts). */
static glpgp_status vtu_result(FILE *f, const glpgp_mesh *m, const glpgp_options *o, const glpgp_result *r,
                               int level, int piece, const int *gid, int nv_owned)
{
    res_ctx ctx[2] = {{m, r, 0, gid, nv_owned}, {m, r, 1, gid, nv_owned}};
    const size_t nv = (size_t)m->nv, nt = (size_t)m->nt;
    vtu_array a[28];
    const int na = result_arrays(ctx, r, nv, nt, piece, a);
    char comment[256];
    if (o)
        glpgp_snprintf(comment, sizeof comment, "glpgp %s result: method %s, energy %s, h %.17g", GLPGP_VERSION,
                 method_name(o->method), energy_name(o->energy), r->size);
    else
        glpgp_snprintf(comment, sizeof comment, "glpgp %s result: h %.17g", GLPGP_VERSION, r->size);
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
    for (int i = 0; i < m->nv; i++) {
        double p[3];
        point3(m, (size_t)i, p);
        if (m->xyz)
            fprintf(f, "v %.17g %.17g %.17g\n", p[0], p[1], p[2]);
        else
            fprintf(f, "v %.17g %.17g 0\n", p[0], p[1]);
    }
    for (int t = 0; t < m->nt; t++) {
        const int *c = m->tri + 3 * t;
        /* per-triangle charts of theta_u and theta_v (unwrapped around corner 0);
         * a surface's coupled result through the triangle's matching */
        double thu[3], thv[3], cu[3], cv[3];
        for (int k = 0; k < 3; k++) {
            if (m->surf && r->coupled && r->field) {
                double fu[2], fv[2];
                const int rk = glpgp_coupled_corner_turn(m, r->field, t, k);
                glpgp_coupled_frame_value(rk, 0, zu + 2 * c[k], zv + 2 * c[k], fu);
                glpgp_coupled_frame_value(rk, 1, zu + 2 * c[k], zv + 2 * c[k], fv);
                thu[k] = glpgp_theta(fu[0], fu[1]);
                thv[k] = glpgp_theta(fv[0], fv[1]);
                continue;
            }
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

/* level -1: the default compression (zlib level 1 when built with zlib) */
static int default_level(int level)
{
    return level < 0 ? (glpgp_io_have_zlib() ? GLPGP_VTU_DEFAULT_LEVEL : 0) : level;
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
    glpgp_status st = GLPGP_OK;
    glpgp_cnum cn; /* '.' whatever the locale */
    glpgp_cnum_begin(&cn);
    if (fmt == FMT_VTK)
        vtk_body(f, m, opts, r);
    else if (fmt == FMT_OBJ)
        obj_body(f, m, r);
    else
        st = vtu_result(f, m, opts, r, default_level(level), 0, NULL, 0);
    glpgp_cnum_end(&cn);
    if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
    return st;
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

/* ---- parallel VTK XML: one .vtu piece per rank and the .pvtu index -------- */

glpgp_status glpgp_pvtu_piece_path(const char *pvtu, int k, char *buf, size_t n)
{
    if (!pvtu || !glpgp_has_ext(pvtu, ".pvtu"))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "'%s' is no .pvtu path", pvtu ? pvtu : "(null)");
    const int w = snprintf(buf, n, "%.*s_p%d.vtu", (int)(strlen(pvtu) - 5), pvtu, k);
    if (w < 0 || (size_t)w >= n) return GLPGP_FAIL(GLPGP_ERR_LIMIT, "output path too long: '%s'", pvtu);
    return GLPGP_OK;
}

/* The piece of part m (result r of its local vertices and triangles):
 * points = the owned vertices (same order), then the ghosts that the
 * counted triangles touch (same order); cells = the triangles the part
 * counts (glpgp_part_counts_tri: those whose lowest global vertex it owns,
 * so every triangle is in exactly one piece). *pm, *pr, *gid: the piece's
 * mesh (xy, tri, nv, nt only: free pm->xy, pm->tri), result and global ids. */
static glpgp_status extract_piece(const glpgp_mesh *m, const glpgp_result *r, glpgp_mesh *pm, glpgp_result **pr,
                                  int **gid)
{
    const glpgp_mesh_part *p = m->part;
    glpgp_status st = GLPGP_OK;
    int *map = NULL, np = p->nv_owned, nc = 0;
    memset(pm, 0, sizeof *pm);
    *pr = NULL;
    *gid = NULL;
    if (r->cross) return GLPGP_FAIL(GLPGP_ERR_ARG, "a cross-field result has no parallel pieces");
    GLPGP_CHECK(glpgp_malloc((size_t)m->nv, sizeof *map, &map));
    /* map[i]: the piece's point of local vertex i (-1: not in the piece) */
    for (int i = 0; i < m->nv; i++) map[i] = i < p->nv_owned ? i : -1;
    for (int t = 0; t < m->nt; t++) {
        if (!glpgp_part_counts_tri(p, m->tri, t)) continue;
        nc++;
        for (int a = 0; a < 3; a++)
            if (map[m->tri[3 * t + a]] == -1) map[m->tri[3 * t + a]] = -2; /* a ghost the piece needs */
    }
    for (int i = p->nv_owned; i < m->nv; i++)
        if (map[i] == -2) map[i] = np++;
    if (nc == 0) {
        st = GLPGP_FAIL(GLPGP_ERR_ARG, "a part with no triangle of its own");
        goto fail;
    }
    pm->nv = np;
    pm->nt = nc;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * np, sizeof(double), &pm->xy), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nc, sizeof(int), &pm->tri), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)np, sizeof(int), gid), fail);
    GLPGP_CHECK_GOTO(st, glpgp_result_create(np, nc, pr), fail);
    glpgp_result *q = *pr, keep = *q;
    *q = *r; /* h, flags, statistics; the arrays below */
    q->nv = np;
    q->nt = nc;
    q->field = keep.field;
    for (int k = 0; k < 2; k++) {
        q->osc[k].z = keep.osc[k].z;
        q->osc[k].dirichlet = keep.osc[k].dirichlet;
        q->osc[k].singular = keep.osc[k].singular;
    }
    for (int i = 0; i < m->nv; i++) {
        const int j = map[i];
        if (j < 0) continue;
        /* point j <- local vertex i */
        (*gid)[j] = p->gid[i];
        memcpy(pm->xy + 2 * j, m->xy + 2 * i, 2 * sizeof(double));
        if (r->field) memcpy(q->field + 2 * j, r->field + 2 * i, 2 * sizeof(double));
        for (int k = 0; k < 2; k++) {
            memcpy(q->osc[k].z + 2 * j, r->osc[k].z + 2 * i, 2 * sizeof(double));
            if (r->osc[k].dirichlet) q->osc[k].dirichlet[j] = r->osc[k].dirichlet[i];
        }
    }
    for (int t = 0, c = 0; t < m->nt; t++) {
        if (!glpgp_part_counts_tri(p, m->tri, t)) continue;
        for (int a = 0; a < 3; a++) pm->tri[3 * c + a] = map[m->tri[3 * t + a]];
        for (int k = 0; k < 2; k++)
            if (r->osc[k].singular) q->osc[k].singular[c] = r->osc[k].singular[t];
        c++;
    }
    /* the arrays the result has not: absent in the piece too (the same
     * arrays in every piece and the index) */
    if (!r->field) {
        free(q->field);
        q->field = NULL;
    }
    for (int k = 0; k < 2; k++) {
        if (!r->osc[k].dirichlet) {
            free(q->osc[k].dirichlet);
            q->osc[k].dirichlet = NULL;
        }
        if (!r->osc[k].singular) {
            free(q->osc[k].singular);
            q->osc[k].singular = NULL;
        }
    }
    free(map);
    return GLPGP_OK;
fail:
    free(map);
    free(pm->xy);
    free(pm->tri);
    memset(pm, 0, sizeof *pm);
    free(*gid);
    *gid = NULL;
    glpgp_result_destroy(pr);
    return st;
}

glpgp_status glpgp_output_set_result_piece(glpgp_output_set *s, const glpgp_mesh *m, const glpgp_options *opts,
                                           const glpgp_result *r, const char *pvtu, int rank)
{
    char path[4096];
    FILE *f;
    GLPGP_CHECK(check_result(m, r));
    GLPGP_CHECK(glpgp_pvtu_piece_path(pvtu, rank, path, sizeof path));
    if (!m->part) { /* the whole mesh: one piece, every point owned */
        GLPGP_CHECK(glpgp_output_set_open(s, path, &f));
        return vtu_result(f, m, opts, r, default_level(-1), 1, NULL, m->nv);
    }
    glpgp_mesh pm;
    glpgp_result *pr = NULL;
    int *gid = NULL;
    GLPGP_CHECK(extract_piece(m, r, &pm, &pr, &gid));
    glpgp_status st = glpgp_output_set_open(s, path, &f);
    if (st == GLPGP_OK) st = vtu_result(f, &pm, opts, pr, default_level(-1), 1, gid, m->part->nv_owned);
    free(pm.xy);
    free(pm.tri);
    free(gid);
    glpgp_result_destroy(&pr);
    return st;
}

glpgp_status glpgp_output_set_pvtu(glpgp_output_set *s, const glpgp_result *r, const char *pvtu, int npieces)
{
    static const char *const tag[VTU_NSECTIONS] = {NULL, "PPointData", "PCellData", "PPoints", NULL};
    FILE *f;
    char piece[4096];
    if (!r || npieces < 1) return GLPGP_FAIL(GLPGP_ERR_ARG, "no result or no piece for '%s'", pvtu);
    GLPGP_CHECK(glpgp_pvtu_piece_path(pvtu, 0, piece, sizeof piece)); /* checks the name */
    const char *slash = strrchr(pvtu, '/'), *base = slash ? slash + 1 : pvtu;
    if (strpbrk(base, "\"&<>'"))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "'%s': a .pvtu name cannot hold \" & < > '", pvtu);
    res_ctx ctx[2] = {{NULL, r, 0, NULL, 0}, {NULL, r, 1, NULL, 0}};
    vtu_array a[28];
    const int na = result_arrays(ctx, r, 0, 0, 1, a);
    GLPGP_CHECK(glpgp_output_set_open(s, pvtu, &f));
    const unsigned one = 1;
    char h[40];
    glpgp_snprintf(h, sizeof h, "%.17g", r->size);
    fprintf(f, "<?xml version=\"1.0\"?>\n<!-- glpgp %s result in %d pieces, h %s -->\n", GLPGP_VERSION,
            npieces, h);
    fprintf(f, "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"%s\" header_type=\"UInt64\">\n",
            *(const unsigned char *)&one ? "LittleEndian" : "BigEndian");
    fprintf(f, "  <PUnstructuredGrid GhostLevel=\"0\">\n");
    for (int sec = VTU_POINTDATA; sec <= VTU_POINTS; sec++) { /* (cells: in the pieces only) */
        fprintf(f, "    <%s>\n", tag[sec]);
        for (int i = 0; i < na; i++) {
            if (a[i].section != sec) continue;
            fprintf(f, "      <PDataArray type=\"%s\"", a[i].type);
            if (a[i].name) fprintf(f, " Name=\"%s\"", a[i].name);
            if (a[i].ncomp != 1) fprintf(f, " NumberOfComponents=\"%d\"", a[i].ncomp);
            fprintf(f, "/>\n");
        }
        fprintf(f, "    </%s>\n", tag[sec]);
    }
    /* the pieces beside the index: Source relative to its directory */
    for (int k = 0; k < npieces; k++) {
        GLPGP_CHECK(glpgp_pvtu_piece_path(base, k, piece, sizeof piece));
        fprintf(f, "    <Piece Source=\"%s\"/>\n", piece);
    }
    fprintf(f, "  </PUnstructuredGrid>\n</VTKFile>\n");
    return GLPGP_OK;
}
