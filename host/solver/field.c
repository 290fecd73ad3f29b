/* solver/field.c: the guiding field U: boundary-aligned (the boundary angle,
 * folded to the 4-fold symmetry, interpolated harmonically inside with the
 * backend's PCG, multigrid-preconditioned with --precond amg), radial about
 * a center, or read from a file (glpgp/solve.h). */
#include "internal.h"
#include "glpgp/internal/text.h"
#include "glpgp/util.h"

#include "glpgp/cross.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Angle of a direction folded into [-pi/4, pi/4] (mod pi/2). */
static double fold4(double nx, double ny)
{
    double phi = atan2(ny, nx);
    return phi - (GLPGP_PI / 2.0) * floor(phi / (GLPGP_PI / 2.0) + 0.5);
}

/* Boundary angle alpha in [-pi/4, pi/4] at boundary vertex i: U is the
 * normal or the tangent, whichever is closer to the x axis. At a vertex the
 * two adjacent edges' angles are averaged as 4-fold directions (mean of
 * exp(4 i alpha)). */
static double boundary_angle(const glpgp_mesh *m, int i)
{
    double a1 = fold4(m->normal_prev[2 * i], m->normal_prev[2 * i + 1]);
    double a2 = fold4(m->normal_next[2 * i], m->normal_next[2 * i + 1]);
    double c = cos(4 * a1) + cos(4 * a2), s = sin(4 * a1) + sin(4 * a2);
    return (c * c + s * s > 1e-20) ? atan2(s, c) / 4.0 : a1;
}

static glpgp_status field_boundary(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                   double *u, long *cg_iterations)
{
    const glpgp_backend_ops *op = b->ops;
    const int nv = m->nv;
    glpgp_status st = GLPGP_OK;
    double *x0 = NULL;
    glpgp_vec *x = NULL, *g = NULL, *d = NULL;
    glpgp_amg *amg = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)2 * nv, sizeof(double), &x0));
    for (int i = 0; i < nv; i++)
        if (m->on_boundary[i]) x0[2 * i] = boundary_angle(m, i);
    /* harmonic interpolation: L alpha = 0 inside, alpha fixed on the boundary:
     * alpha = alpha0 + d,  N d = -(L alpha0) with Dirichlet rows eliminated */
    GLPGP_CHECK_GOTO(st, op->set_field(b, u, m->on_boundary), done);
    GLPGP_CHECK_GOTO(st, op->assemble_quadratic(b, GLPGP_ELEM_LAPLACE, 1.0), done);
    GLPGP_CHECK_GOTO(st, op->vec_create(b, (size_t)2 * nv, &x), done);
    GLPGP_CHECK_GOTO(st, op->vec_create(b, (size_t)2 * nv, &g), done);
    GLPGP_CHECK_GOTO(st, op->vec_create(b, (size_t)2 * nv, &d), done);
    GLPGP_CHECK_GOTO(st, op->vec_write(b, x, x0), done);
    GLPGP_CHECK_GOTO(st, op->assemble_newton(b, x, 0.0, GLPGP_HESS_PAPER), done);
    GLPGP_CHECK_GOTO(st, op->gradient(b, x, 0.0, g), done);
    GLPGP_CHECK_GOTO(st, op->axpby(b, 0.0, g, -1.0, g), done); /* g <- -g */
    glpgp_cg_info ci;
    amg = glpgp_amg_try_create(b, o, m->on_boundary, NULL, 0.0, "guiding field");
    if (amg && !glpgp_amg_try_update(amg, NULL, "guiding field")) glpgp_amg_destroy(&amg);
    GLPGP_CHECK_GOTO(st, glpgp_linear_solve(b, amg, g, d, o->cg_rtol, o->cg_max, o->cg_check, &ci),
                     done);
    *cg_iterations += ci.iterations;
    if (ci.reason == GLPGP_CG_BREAKDOWN) {
        st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "guiding field: CG breakdown after %d iterations "
                                           "(is the mesh folded?)", ci.iterations);
        goto done;
    }
    if (ci.reason == GLPGP_CG_MAXIT)
        glpgp_log(GLPGP_LOG_WARNING, "guiding field: CG stopped at the cap of %d iterations "
                                     "(relative residual %.2e)", ci.iterations, ci.relres);
    GLPGP_CHECK_GOTO(st, op->axpby(b, 1.0, d, 1.0, x), done); /* alpha <- alpha0 + d */
    GLPGP_CHECK_GOTO(st, op->vec_read(b, x, x0), done);
    for (int i = 0; i < nv; i++) {
        u[2 * i] = cos(x0[2 * i]);
        u[2 * i + 1] = sin(x0[2 * i]);
    }
done:
    glpgp_amg_destroy(&amg);
    op->vec_destroy(b, &x);
    op->vec_destroy(b, &g);
    op->vec_destroy(b, &d);
    free(x0);
    return st;
}

/* Longest line a field file may have (a "ux uy" pair needs < 100 characters). */
#define FIELD_LINE_MAX 4096

/* One field row: "ux uy", normalised. */
static glpgp_status field_row(void *ctx, const text_reader *tr, int i, const double *v, int nv)
{
    double *u = ctx;
    if (nv != 2) return text_error(tr, GLPGP_ERR_FORMAT, 0, "expected two finite numbers 'ux uy'");
    /* u <- (ux, uy) / |(ux, uy)|, hypot: no overflow for 1e200, no underflow for 1e-200 */
    const double n = hypot(v[0], v[1]);
    if (!(n > 0.0) || !isfinite(n)) return text_error(tr, GLPGP_ERR_FORMAT, 0, "zero vector");
    u[2 * i] = v[0] / n;
    u[2 * i + 1] = v[1] / n;
    return GLPGP_OK;
}

static glpgp_status field_file(const glpgp_mesh *m, const char *path, double *u)
{
    GLPGP_CHECK(text_read_rows(path, "field", m->nv, 2, FIELD_LINE_MAX, field_row, u));
    return GLPGP_OK;
}

/* the field given in memory (glpgp_options.field_values), normalised like a file's lines */
static glpgp_status field_array(const glpgp_mesh *m, const glpgp_options *o, double *u)
{
    for (int i = 0; i < m->nv; i++) {
        const double ux = o->field_values[2 * i], uy = o->field_values[2 * i + 1], n = hypot(ux, uy);
        if (!(n > 0.0) || !isfinite(n))
            return GLPGP_FAIL(GLPGP_ERR_ARG, "%s: vertex %d: the field is %s", o->field_file ? o->field_file : "field",
                              i, isfinite(n) ? "a zero vector" : "not finite");
        u[2 * i] = ux / n;
        u[2 * i + 1] = uy / n;
    }
    return GLPGP_OK;
}

/* c <- the area centroid of m */
static void centroid(const glpgp_mesh *m, double c[2])
{
    {
        double sx = 0.0, sy = 0.0, sa = 0.0;
        for (int t = 0; t < m->nt; t++) {
            double x[3], y[3];
            for (int a = 0; a < 3; a++) {
                x[a] = m->xy[2 * m->tri[3 * t + a]];
                y[a] = m->xy[2 * m->tri[3 * t + a] + 1];
            }
            double ar = 0.5 * ((x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]));
            sx += ar * (x[0] + x[1] + x[2]) / 3.0;
            sy += ar * (y[0] + y[1] + y[2]) / 3.0;
            sa += ar;
        }
        c[0] = sx / sa;
        c[1] = sy / sa;
    }
}

static void field_radial(const glpgp_mesh *m, const glpgp_options *o, double *u)
{
    double cx = o->center[0], cy = o->center[1];
    if (!o->has_center) { /* area centroid (a part: the whole mesh's) */
        double c[2];
        if (m->part) memcpy(c, m->part->center, sizeof c);
        else centroid(m, c);
        cx = c[0];
        cy = c[1];
    }
    for (int i = 0; i < m->nv; i++) {
        double dx = m->xy[2 * i] - cx, dy = m->xy[2 * i + 1] - cy, n = sqrt(dx * dx + dy * dy);
        u[2 * i] = n > 0.0 ? dx / n : 1.0;
        u[2 * i + 1] = n > 0.0 ? dy / n : 0.0;
    }
}

glpgp_status glpgp_field_compute(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                 double *u, long *cg_iterations)
{
    if (m->xyz)
        return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "the planar guiding fields do not apply to a surface "
                                                 "(glpgp_solve_surface, glpgp/surfsolve.h)");
    if (o->field == GLPGP_FIELD_FILE) return o->field_values ? field_array(m, o, u) : field_file(m, o->field_file, u);
    if (o->field == GLPGP_FIELD_CROSS) return glpgp_cross_guiding_field(m, b, o, NULL, u, cg_iterations);
    if (o->field == GLPGP_FIELD_RADIAL) {
        field_radial(m, o, u);
        return GLPGP_OK;
    }
    return field_boundary(m, b, o, u, cg_iterations);
}

void glpgp_field_presolve(const glpgp_mesh *m, const glpgp_options *o, double *u, double center[2])
{
    centroid(m, center);
    if (o->field == GLPGP_FIELD_RADIAL) {
        field_radial(m, o, u);
        return;
    }
    /* boundary: alpha is fixed (Dirichlet) at the boundary vertices, the
     * harmonic solve leaves it there: u = (cos alpha, sin alpha) */
    for (int i = 0; i < m->nv; i++) {
        const double a = m->on_boundary[i] ? boundary_angle(m, i) : 0.0;
        u[2 * i] = cos(a);
        u[2 * i + 1] = sin(a);
    }
}
