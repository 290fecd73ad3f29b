/* backends/crosscheck.c: the cross-check engine of glpgp/backends.h: the
 * OpenCL backend (side 0, "a") against the reference backend (side 1, "b") on
 * one mesh, op by op and stage by stage, into a table of rows (stage, max
 * abs / rel difference, tolerance, pass). The one comparison behind
 * `glpgp crosscheck` (cli/cmd_opencl.c) and tests/backends/test_opencl.c.
 * Everything goes through the ops table (matrices through glpgp_probe_matrix,
 * exact), so the engine needs no backend internals. The stage list and the
 * tolerances are documented in glpgp/backends.h. */
#include "glpgp/backends.h"
#include "glpgp/cross.h"
#include "glpgp/result.h"
#include "glpgp/solve.h"
#include "glpgp/surfsolve.h"
#include "glpgp/util.h"
#include "glpgp/internal/newton.h"
#include "glpgp/internal/probe.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Device vectors of one side. */
enum { VX, VY, VG, VD, VW, VR, VZ, VP, VQ, VS, NVEC };

typedef struct cc_side {
    glpgp_backend *b;
    glpgp_vec *v[NVEC];
} cc_side;

/* The state of one run. */
typedef struct cc {
    const glpgp_crosscheck_options *opt;
    glpgp_crosscheck *t;
    const glpgp_mesh *m;
    glpgp_system *sys;
    glpgp_options so;       /* solver options: size, energy, eps0, ... */
    cc_side S[2];           /* 0: OpenCL, 1: reference */
    size_t n2, nm, nbuf;    /* 2 nv, 4 nnzb, host buffer length */
    double *field, *z, *r, *nan;
    unsigned char *dir;
    double *h[2];           /* host copies of side 0 / side 1 (nbuf doubles each) */
    double inv4e2;
} cc;

/* Run `call` on both sides in turn: s = 0 (OpenCL), 1 (reference), with that
 * side's backend b, ops o and vectors v in scope; return on an error. */
#define BOTH(call)                                                                                           \
    for (int s = 0; s < 2; s++) {                                                                            \
        glpgp_backend *b = c->S[s].b;                                                                        \
        const glpgp_backend_ops *o = b->ops;                                                                 \
        glpgp_vec **v = c->S[s].v;                                                                           \
        (void)o;                                                                                             \
        (void)v;                                                                                             \
        GLPGP_CHECK(call);                                                                                   \
    }

void glpgp_crosscheck_options_default(glpgp_crosscheck_options *o)
{
    memset(o, 0, sizeof *o);
    o->mesh = NULL;
    o->size = 0.0;
    o->energy = GLPGP_ELEM_P1;
    o->device = -1;
    o->tol_scale = 1.0;
    o->solve = 1;
    o->seed = 12345;
    glpgp_options so;
    glpgp_options_default(&so);
    o->precond = so.precond;
}

void glpgp_crosscheck_destroy(glpgp_crosscheck **t)
{
    if (!t || !*t) return;
    free((*t)->rows);
    free(*t);
    *t = NULL;
}

/* ---- rows ------------------------------------------------------------------ */

/* A new row named by fmt (zeroed, pass = 1). */
static glpgp_status row_add(glpgp_crosscheck *t, glpgp_crosscheck_row **row, const char *fmt, ...)
{
    if ((t->nrows & (t->nrows - 1)) == 0) { /* 0, 1, 2, 4, ...: grow to the next power of two */
        size_t cap = t->nrows ? 2 * (size_t)t->nrows : 1;
        glpgp_crosscheck_row *nr = realloc(t->rows, cap * sizeof *nr);
        if (!nr) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory for the cross-check table");
        t->rows = nr;
    }
    glpgp_crosscheck_row *r = &t->rows[t->nrows++];
    memset(r, 0, sizeof *r);
    va_list ap;
    va_start(ap, fmt);
    glpgp_vsnprintf(r->stage, sizeof r->stage, fmt, ap);
    va_end(ap);
    r->pass = 1;
    *row = r;
    return GLPGP_OK;
}

/* Row `stage`: a (OpenCL) against b (reference), n entries:
 *   pass iff |a_i - b_i| <= atol + rtol |b_i| for all i,  atol = afac * scale,
 *   scale <= 0: max_i |b_i|;  rtol and afac are multiplied by tol_scale.
 * A NaN difference fails and shows as max_abs = NaN. */
static glpgp_status cmp(cc *c, const char *stage, const double *a, const double *b, size_t n, double rtol,
                        double afac, double scale)
{
    glpgp_crosscheck_row *r;
    GLPGP_CHECK(row_add(c->t, &r, "%s", stage));
    rtol *= c->opt->tol_scale;
    afac *= c->opt->tol_scale;
    double maxb = 0.0, maxd = 0.0;
    for (size_t i = 0; i < n; i++) maxb = fmax(maxb, fabs(b[i]));
    if (scale <= 0.0) scale = maxb;
    const double atol = afac * scale;
    for (size_t i = 0; i < n; i++) {
        const double d = fabs(a[i] - b[i]);
        if (!(d <= atol + rtol * fabs(b[i]))) r->pass = 0;
        if (!(d <= maxd)) maxd = d; /* keeps NaN */
    }
    r->max_abs = maxd;
    r->max_rel = maxb > 0.0 ? maxd / maxb : (maxd > 0.0 ? INFINITY : maxd);
    if (rtol == 0.0 && atol == 0.0) snprintf(r->tol, sizeof r->tol, "exact");
    else glpgp_snprintf(r->tol, sizeof r->tol, "rtol %.0e, atol %.0e", rtol, atol);
    return GLPGP_OK;
}

/* Exact comparison of two integer pairs (singularity counts +/-). */
static glpgp_status cmp_counts(cc *c, const char *stage, int a1, int a2, int b1, int b2)
{
    glpgp_crosscheck_row *r;
    GLPGP_CHECK(row_add(c->t, &r, "%s", stage));
    r->max_abs = fmax(fabs((double)a1 - b1), fabs((double)a2 - b2));
    r->max_rel = r->max_abs / fmax(1.0, fmax(fabs((double)b1), fabs((double)b2)));
    snprintf(r->tol, sizeof r->tol, "exact (%d+/%d- vs %d+/%d-)", a1, a2, b1, b2);
    r->pass = r->max_abs == 0.0;
    return GLPGP_OK;
}

/* Both sides' scalar registers into sc[side][slot]. */
static glpgp_status scalars(cc *c, double sc[2][GLPGP_NSLOTS])
{
    BOTH(o->get_scalars(b, sc[s], GLPGP_NSLOTS));
    return GLPGP_OK;
}

/* Deterministic pseudo-random numbers in [0, 1) (64-bit LCG, top 53 bits). */
static double cc_rand(unsigned long long *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) * (1.0 / 9007199254740992.0);
}

/* ---- stages ---------------------------------------------------------------- */

/* Vector ops: write/read, copy, axpby (also with zero coefficients on NaN), dot. */
static glpgp_status stage_vectors(cc *c)
{
    const size_t n2 = c->n2;
    double sc[2][GLPGP_NSLOTS], again[GLPGP_NSLOTS];
    BOTH(o->vec_write(b, v[VX], c->z));
    BOTH(o->vec_write(b, v[VR], c->r));
    BOTH(o->vec_read(b, v[VX], c->h[s]));
    GLPGP_CHECK(cmp(c, "vector write/read", c->h[0], c->h[1], n2, 0.0, 0.0, 0.0));
    /* y <- r;  y <- 0.75 z - 1.5 y */
    BOTH(o->copy(b, v[VY], v[VR]));
    BOTH(o->axpby(b, 0.75, v[VX], -1.5, v[VY]));
    BOTH(o->vec_read(b, v[VY], c->h[s]));
    GLPGP_CHECK(cmp(c, "copy, axpby 0.75 z - 1.5 r", c->h[0], c->h[1], n2, 0.0, 0.0, 0.0));
    /* a zero coefficient does not read its vector (d, w NaN-filled):
     *   w <- 0 d + 0 w = 0;   w <- r, w <- 0 d + 2 w = 2 r;   w <- NaN, w <- -3 z + 0 w = -3 z */
    BOTH(o->vec_write(b, v[VD], c->nan));
    BOTH(o->vec_write(b, v[VW], c->nan));
    BOTH(o->axpby(b, 0.0, v[VD], 0.0, v[VW]));
    BOTH(o->vec_read(b, v[VW], c->h[s]));
    BOTH(o->copy(b, v[VW], v[VR]));
    BOTH(o->axpby(b, 0.0, v[VD], 2.0, v[VW]));
    BOTH(o->vec_read(b, v[VW], c->h[s] + n2));
    BOTH(o->vec_write(b, v[VW], c->nan));
    BOTH(o->axpby(b, -3.0, v[VX], 0.0, v[VW]));
    BOTH(o->vec_read(b, v[VW], c->h[s] + 2 * n2));
    GLPGP_CHECK(cmp(c, "axpby zero coefficients (NaN)", c->h[0], c->h[1], 3 * n2, 0.0, 0.0, 0.0));
    /* s[DOT] <- z.r, scale sum |z_i r_i| */
    double scale = 0.0;
    for (size_t i = 0; i < n2; i++) scale += fabs(c->z[i] * c->r[i]);
    BOTH(o->dot(b, v[VX], v[VR], GLPGP_S_DOT));
    GLPGP_CHECK(scalars(c, sc));
    GLPGP_CHECK(cmp(c, "dot z.r", &sc[0][GLPGP_S_DOT], &sc[1][GLPGP_S_DOT], 1, 1e-12, 1e-14, scale));
    /* the OpenCL reduction order is fixed: the same dot again, bit for bit */
    glpgp_backend *cl = c->S[0].b;
    GLPGP_CHECK(cl->ops->dot(cl, c->S[0].v[VX], c->S[0].v[VR], GLPGP_S_DOT));
    GLPGP_CHECK(cl->ops->get_scalars(cl, again, GLPGP_NSLOTS));
    GLPGP_CHECK(cmp(c, "dot z.r again (OpenCL, same bits)", &again[GLPGP_S_DOT], &sc[0][GLPGP_S_DOT], 1, 0.0,
                    0.0, 0.0));
    return GLPGP_OK;
}

static const char *kind_name(int kind)
{
    return kind == GLPGP_ELEM_TRANSPORT ? "transport" : kind == GLPGP_ELEM_LAPLACE ? "laplace" : "p1";
}

/* QUAD of the chosen energy ("QUAD assembly"), then of the other kinds; QUAD
 * is left as the chosen energy's. */
static glpgp_status stage_quad(cc *c)
{
    static const int kinds[] = {GLPGP_ELEM_P1, GLPGP_ELEM_TRANSPORT, GLPGP_ELEM_LAPLACE};
    const int kind = c->opt->energy;
    const double h = c->t->h;
    char name[48];
    BOTH(o->set_field(b, c->field, c->dir));
    BOTH(o->assemble_quadratic(b, kind, h));
    BOTH(glpgp_probe_matrix(b, GLPGP_MAT_QUAD, c->h[s]));
    GLPGP_CHECK(cmp(c, "QUAD assembly", c->h[0], c->h[1], c->nm, 1e-12, 1e-14, 0.0));
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        if (kinds[k] == kind) continue;
        BOTH(o->assemble_quadratic(b, kinds[k], h));
        BOTH(glpgp_probe_matrix(b, GLPGP_MAT_QUAD, c->h[s]));
        snprintf(name, sizeof name, "QUAD assembly (%s)", kind_name(kinds[k]));
        GLPGP_CHECK(cmp(c, name, c->h[0], c->h[1], c->nm, 1e-12, 1e-14, 0.0));
    }
    /* a non-uniform size field (set_size): random sizes in [h/4, h] per vertex */
    unsigned long long seed = c->opt->seed ^ 0x5eedULL;
    for (int i = 0; i < c->sys->nv; i++) c->h[1][i] = h * (0.25 + 0.75 * cc_rand(&seed));
    static const int skinds[] = {GLPGP_ELEM_P1, GLPGP_ELEM_TRANSPORT};
    double *sz = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)c->sys->nv, sizeof(double), &sz));
    memcpy(sz, c->h[1], (size_t)c->sys->nv * sizeof(double));
    glpgp_status st = GLPGP_OK;
    for (size_t k = 0; k < sizeof skinds / sizeof skinds[0] && st == GLPGP_OK; k++) {
        for (int s = 0; s < 2 && st == GLPGP_OK; s++) {
            glpgp_backend *b = c->S[s].b;
            st = b->ops->set_size(b, sz);
            if (st == GLPGP_OK) st = b->ops->assemble_quadratic(b, skinds[k], h);
            if (st == GLPGP_OK) st = glpgp_probe_matrix(b, GLPGP_MAT_QUAD, c->h[s]);
        }
        snprintf(name, sizeof name, "QUAD assembly (%s, sized)", kind_name(skinds[k]));
        if (st == GLPGP_OK) st = cmp(c, name, c->h[0], c->h[1], c->nm, 1e-12, 1e-14, 0.0);
    }
    free(sz);
    GLPGP_CHECK(st);
    BOTH(o->set_size(b, NULL));
    BOTH(o->assemble_quadratic(b, kind, h));
    return GLPGP_OK;
}

/* NEWTON + DINV at z without penalty and for every Hessian variant (mixed last,
 * so NEWTON stays the mixed one). */
static glpgp_status stage_newton(cc *c)
{
    static const struct {
        int hess;
        const char *name;
    } hv[] = {{-1, "no penalty"},
              {GLPGP_HESS_PAPER, "paper"},
              {GLPGP_HESS_PROJECTED, "projected"},
              {GLPGP_HESS_EXACT, "exact"},
              {GLPGP_HESS_MIXED, "mixed"}};
    char name[48];
    for (size_t k = 0; k < sizeof hv / sizeof hv[0]; k++) {
        const double w = hv[k].hess < 0 ? 0.0 : c->inv4e2;
        const int hess = hv[k].hess < 0 ? GLPGP_HESS_PAPER : hv[k].hess;
        BOTH(o->assemble_newton(b, v[VX], w, hess));
        BOTH(glpgp_probe_matrix(b, GLPGP_MAT_NEWTON, c->h[s]));
        snprintf(name, sizeof name, "NEWTON assembly (%s)", hv[k].name);
        GLPGP_CHECK(cmp(c, name, c->h[0], c->h[1], c->nm, 1e-12, 1e-14, 0.0));
        BOTH(glpgp_probe_matrix(b, GLPGP_PROBE_DINV, c->h[s]));
        snprintf(name, sizeof name, "DINV (%s)", hv[k].name);
        GLPGP_CHECK(cmp(c, name, c->h[0], c->h[1], (size_t)4 * c->sys->nv, 1e-12, 1e-14, 0.0));
    }
    return GLPGP_OK;
}

/* gradient (g, E, P) and energy (E, P) at z, with the penalty and without. */
static glpgp_status stage_gradient(cc *c)
{
    double sc[2][GLPGP_NSLOTS];
    const size_t n2 = c->n2;
    /* with the penalty */
    BOTH(o->gradient(b, v[VX], c->inv4e2, v[VG]));
    BOTH(o->vec_read(b, v[VG], c->h[s]));
    GLPGP_CHECK(scalars(c, sc));
    GLPGP_CHECK(cmp(c, "gradient g", c->h[0], c->h[1], n2, 1e-12, 1e-14, 0.0));
    GLPGP_CHECK(cmp(c, "gradient: E = 1/2 x.QUAD x", &sc[0][GLPGP_S_E], &sc[1][GLPGP_S_E], 1, 1e-12, 1e-14, 0.0));
    GLPGP_CHECK(cmp(c, "gradient: P (penalty)", &sc[0][GLPGP_S_P], &sc[1][GLPGP_S_P], 1, 1e-12, 1e-14, 0.0));
    BOTH(o->energy(b, v[VX], c->inv4e2, v[VW]));
    GLPGP_CHECK(scalars(c, sc));
    GLPGP_CHECK(cmp(c, "energy: E", &sc[0][GLPGP_S_E], &sc[1][GLPGP_S_E], 1, 1e-12, 1e-14, 0.0));
    GLPGP_CHECK(cmp(c, "energy: P", &sc[0][GLPGP_S_P], &sc[1][GLPGP_S_P], 1, 1e-12, 1e-14, 0.0));
    /* without: g = QUAD x (0 at Dirichlet vertices), P = 0 exactly */
    BOTH(o->gradient(b, v[VX], 0.0, v[VG]));
    BOTH(o->vec_read(b, v[VG], c->h[s]));
    GLPGP_CHECK(scalars(c, sc));
    GLPGP_CHECK(cmp(c, "gradient g (no penalty)", c->h[0], c->h[1], n2, 1e-12, 1e-14, 0.0));
    GLPGP_CHECK(cmp(c, "gradient: P = 0 (no penalty)", &sc[0][GLPGP_S_P], &sc[1][GLPGP_S_P], 1, 0.0, 0.0, 0.0));
    BOTH(o->energy(b, v[VX], 0.0, v[VW]));
    GLPGP_CHECK(scalars(c, sc));
    GLPGP_CHECK(cmp(c, "energy: P = 0 (no penalty)", &sc[0][GLPGP_S_P], &sc[1][GLPGP_S_P], 1, 0.0, 0.0, 0.0));
    return GLPGP_OK;
}

/* spmv on both matrices, then the dot x.(NEWTON x). */
static glpgp_status stage_spmv(cc *c)
{
    double sc[2][GLPGP_NSLOTS];
    for (int mat = 0; mat < 2; mat++) {
        BOTH(o->spmv(b, mat, v[VX], v[VY]));
        BOTH(o->vec_read(b, v[VY], c->h[s]));
        GLPGP_CHECK(cmp(c, mat == GLPGP_MAT_QUAD ? "spmv QUAD" : "spmv NEWTON", c->h[0], c->h[1], c->n2, 1e-12,
                        1e-14, 0.0));
    }
    double scale = 0.0;
    for (size_t i = 0; i < c->n2; i++) scale += fabs(c->z[i] * c->h[1][i]);
    BOTH(o->dot(b, v[VX], v[VY], GLPGP_S_DOT));
    GLPGP_CHECK(scalars(c, sc));
    GLPGP_CHECK(cmp(c, "dot x.(NEWTON x)", &sc[0][GLPGP_S_DOT], &sc[1][GLPGP_S_DOT], 1, 1e-12, 1e-14, scale));
    return GLPGP_OK;
}

/* The trust region's trial point x (+) a d (ops->trial_point: polar
 * outside vortex cores, straight inside, blended between; its own sin and
 * cos) at z, d = r, for a short and a long step: the same bits. */
static glpgp_status stage_trial(cc *c)
{
    if (!c->S[0].b->ops->trial_point || !c->S[1].b->ops->trial_point) return GLPGP_OK;
    BOTH(o->vec_write(b, v[VX], c->z));
    BOTH(o->vec_write(b, v[VD], c->r));
    const double steps[2] = {0.7, 3.0};
    for (int k = 0; k < 2; k++) {
        BOTH(o->trial_point(b, v[VX], v[VD], steps[k], 0.8, v[VY]));
        BOTH(o->vec_read(b, v[VY], c->h[s]));
        GLPGP_CHECK(cmp(c, k ? "trial point x (+) 3 d" : "trial point x (+) 0.7 d", c->h[0], c->h[1], c->n2, 0.0,
                        0.0, 0.0));
    }
    return GLPGP_OK;
}

/* The fused CG ops one at a time on the projected NEWTON, right-hand side r:
 * precond, then 3 x (spmv_dot, update, direction); each quantity's values over
 * the 3 steps form one row. */
static glpgp_status stage_cg_steps(cc *c)
{
    enum { NSTEP = 3 };
    const size_t n2 = c->n2;
    double sc[2][GLPGP_NSLOTS], pq[2][NSTEP], rz[2][NSTEP], rr[2][NSTEP];
    /* host layout per side: q, r, x, p of step k at (quantity * NSTEP + k) * n2 */
    double *q[2] = {c->h[0], c->h[1]};
    BOTH(o->assemble_newton(b, v[VX], c->inv4e2, GLPGP_HESS_PROJECTED));
    BOTH(o->vec_write(b, v[VR], c->r));
    BOTH(o->axpby(b, 0.0, v[VS], 0.0, v[VS])); /* x <- 0 */
    /* z <- DINV r;  s[RZ0] <- r.z;  s[RR] <- r.r;  p <- z */
    BOTH(o->cg_precond(b, v[VR], v[VZ], GLPGP_S_RZ0));
    BOTH(o->vec_read(b, v[VZ], c->h[s]));
    GLPGP_CHECK(scalars(c, sc));
    GLPGP_CHECK(cmp(c, "CG precond z", c->h[0], c->h[1], n2, 1e-12, 1e-14, 0.0));
    GLPGP_CHECK(cmp(c, "CG precond r.z", &sc[0][GLPGP_S_RZ0], &sc[1][GLPGP_S_RZ0], 1, 1e-12, 1e-14, 0.0));
    GLPGP_CHECK(cmp(c, "CG precond r.r", &sc[0][GLPGP_S_RR], &sc[1][GLPGP_S_RR], 1, 1e-12, 1e-14, 0.0));
    BOTH(o->copy(b, v[VP], v[VZ]));
    for (int k = 0; k < NSTEP; k++) {
        const int rzo = k % 2 ? GLPGP_S_RZ1 : GLPGP_S_RZ0, rzn = k % 2 ? GLPGP_S_RZ0 : GLPGP_S_RZ1;
        /* q <- NEWTON p;  s[PQ] <- p.q */
        BOTH(o->cg_spmv_dot(b, v[VP], v[VQ]));
        BOTH(o->vec_read(b, v[VQ], q[s] + (0 * NSTEP + k) * n2));
        GLPGP_CHECK(scalars(c, sc));
        for (int s = 0; s < 2; s++) pq[s][k] = sc[s][GLPGP_S_PQ];
        /* x += alpha p;  r -= alpha q;  z <- DINV r;  s[rzn] <- r.z;  s[RR] <- r.r */
        BOTH(o->cg_update(b, v[VS], v[VR], v[VP], v[VQ], v[VZ], rzo, rzn));
        BOTH(o->vec_read(b, v[VR], q[s] + (1 * NSTEP + k) * n2));
        BOTH(o->vec_read(b, v[VS], q[s] + (2 * NSTEP + k) * n2));
        GLPGP_CHECK(scalars(c, sc));
        for (int s = 0; s < 2; s++) {
            rz[s][k] = sc[s][rzn];
            rr[s][k] = sc[s][GLPGP_S_RR];
        }
        /* p <- z + beta p */
        BOTH(o->cg_direction(b, v[VP], v[VZ], rzn, rzo));
        BOTH(o->vec_read(b, v[VP], q[s] + (3 * NSTEP + k) * n2));
    }
    const size_t nn = NSTEP * n2;
    GLPGP_CHECK(cmp(c, "CG spmv_dot q (3 steps)", q[0], q[1], nn, 1e-12, 1e-14, 0.0));
    GLPGP_CHECK(cmp(c, "CG spmv_dot p.q (3 steps)", pq[0], pq[1], NSTEP, 1e-12, 1e-14, 0.0));
    GLPGP_CHECK(cmp(c, "CG update r.z (3 steps)", rz[0], rz[1], NSTEP, 1e-12, 1e-14, 0.0));
    GLPGP_CHECK(cmp(c, "CG update r.r (3 steps)", rr[0], rr[1], NSTEP, 1e-12, 1e-14, 0.0));
    /* after an update alpha differs by rounding: 1e-10 */
    GLPGP_CHECK(cmp(c, "CG update r (3 steps)", q[0] + nn, q[1] + nn, nn, 1e-10, 1e-10, 0.0));
    GLPGP_CHECK(cmp(c, "CG update x (3 steps)", q[0] + 2 * nn, q[1] + 2 * nn, nn, 1e-10, 1e-10, 0.0));
    GLPGP_CHECK(cmp(c, "CG direction p (3 steps)", q[0] + 3 * nn, q[1] + 3 * nn, nn, 1e-10, 1e-10, 0.0));
    return GLPGP_OK;
}

/* One CG solve NEWTON d = -g (projected Hessian: SPD), then the Newton step z + d. */
static glpgp_status stage_cg_solve(cc *c)
{
    glpgp_cg_info ci[2];
    char name[48];
    BOTH(o->assemble_newton(b, v[VX], c->inv4e2, GLPGP_HESS_PROJECTED));
    BOTH(o->gradient(b, v[VX], c->inv4e2, v[VG]));
    BOTH(o->axpby(b, -1.0, v[VG], 0.0, v[VY]));
    BOTH(glpgp_cg(b, v[VY], v[VD], 1e-10, 20000, 10, &ci[s]));
    BOTH(o->vec_read(b, v[VD], c->h[s]));
    snprintf(name, sizeof name, "CG solve (%d vs %d it)", ci[0].iterations, ci[1].iterations);
    GLPGP_CHECK(cmp(c, name, c->h[0], c->h[1], c->n2, 1e-6, 1e-6, 0.0));
    /* z <- z + d */
    BOTH(o->axpby(b, 1.0, v[VD], 1.0, v[VX]));
    BOTH(o->vec_read(b, v[VX], c->h[s]));
    GLPGP_CHECK(cmp(c, "Newton step z + d", c->h[0], c->h[1], c->n2, 1e-6, 1e-6, 0.0));
    return GLPGP_OK;
}

/* Both sides' multigrid registers into t[side][0 .. GLPGP_AMG_NSLOTS). */
static glpgp_status amg_scalars(cc *c, double t[2][GLPGP_AMG_NSLOTS])
{
    BOTH(o->amg_get_scalars(b, t[s], GLPGP_AMG_NSLOTS));
    return GLPGP_OK;
}

/* n random numbers in [-1/2, 1/2) */
static void cc_fill(unsigned long long *seed, double *x, size_t n)
{
    for (size_t i = 0; i < n; i++) x[i] = cc_rand(seed) - 0.5;
}

/* The fused visit halves of level l (the GPU shape's; ops amg_presmooth_restrict,
 * amg_prolong_smooth) on both sides: y <- M^-1 r with e' <- P^T (r - A y),
 * then y <- x' + M^-1 (r - A x'), x' = x + P e (lv[s]: x, r, y of level l,
 * e of level l+1; he: e's values; n, nc: the two levels' lengths). */
static glpgp_status amg_fused_rows(cc *c, int l, glpgp_vec *lv[2][4], const double *he, size_t n, size_t nc)
{
    char name[64];
    for (int s = 0; s < 2; s++)
        if (!c->S[s].b->ops->amg_presmooth_restrict || !c->S[s].b->ops->amg_prolong_smooth) return GLPGP_OK;
    BOTH(o->amg_presmooth_restrict(b, l, lv[s][1], lv[s][2], lv[s][3]));
    BOTH(o->vec_read(b, lv[s][2], c->h[s]));
    BOTH(o->vec_read(b, lv[s][3], c->h[s] + n));
    snprintf(name, sizeof name, "multigrid fused smoothing + restriction %d", l);
    GLPGP_CHECK(cmp(c, name, c->h[0], c->h[1], n + nc, 1e-12, 1e-14, 0.0));
    BOTH(o->vec_write(b, lv[s][3], he));
    BOTH(o->amg_prolong_smooth(b, l, lv[s][3], lv[s][0], lv[s][1], lv[s][2]));
    BOTH(o->vec_read(b, lv[s][2], c->h[s]));
    snprintf(name, sizeof name, "multigrid fused prolongation + smoothing %d", l);
    return cmp(c, name, c->h[0], c->h[1], n, 1e-12, 1e-14, 0.0);
}

/* The multigrid ops (amg_* of the backend table) on the hierarchy of the
 * mixed NEWTON at z, built on each side by solver/amg.c (the same host
 * structure: aggregation is deterministic) with frames from z. Per level l,
 * random x, r (level l) and e (level l+1):
 *   A_l x with the dots x.(A_l x), x.r (amg_spmv_dots);
 *   M_l^-1 r and x + M_l^-1 (r - A_l x) (amg_smooth, l < L-1);
 *   P_l^T r and P_l^T (r - A_l x) (amg_restrict);  x + P_l e (amg_prolong);
 * the coarsest matrix (amg_coarse_read) and C r (amg_coarse_solve); on level
 * 0: amg_dots, amg_axpby with register coefficients, amg_kcombine; one whole
 * cycle B r (glpgp_amg_apply; the OpenCL CPU shape runs its small levels in
 * the fused kernel) and a flexible-CG solve NEWTON d = -g. Hierarchy values
 * share kernels/amg_rows.h (bit-identical in practice): rtol 1e-12; so does
 * the dense coarse inverse (kernels/amg_dense.h, on each backend); the
 * cycle (K-cycle coefficients from dot products) 1e-10; the solve 1e-6. */
#define LV(k) lv[s][k]

/* The coarsest level l (n unknowns): its dense matrix, the coarse solve C r
 * with the LU and with the SPD inverse (the trust region's), on both sides
 * (lv[s]: x, r, y). */
static glpgp_status amg_coarsest_rows(cc *c, glpgp_amg *a[2], int l, glpgp_vec *lv[2][4], size_t n)
{
    char name[64];
    const size_t mm = n * n;
    double *dn[2] = {NULL, NULL};
    glpgp_status st = GLPGP_OK;
    for (int s = 0; s < 2 && st == GLPGP_OK; s++) st = glpgp_malloc(mm ? mm : 1, sizeof(double), &dn[s]);
    for (int s = 0; s < 2 && st == GLPGP_OK; s++) st = c->S[s].b->ops->amg_coarse_read(c->S[s].b, dn[s]);
    if (st == GLPGP_OK) {
        snprintf(name, sizeof name, "multigrid coarsest A_%d (dense)", l);
        st = cmp(c, name, dn[0], dn[1], mm, 1e-12, 1e-14, 0.0);
    }
    free(dn[0]);
    free(dn[1]);
    GLPGP_CHECK(st);
    BOTH(o->amg_coarse_solve(b, LV(1), LV(2)));
    BOTH(o->vec_read(b, LV(2), c->h[s]));
    GLPGP_CHECK(cmp(c, "multigrid coarse solve C r", c->h[0], c->h[1], n, 1e-12, 1e-14, 0.0));
    /* the symmetric PSD coarse operator (glpgp_amg_update_spd: the trust region's) */
    for (int s = 0; s < 2; s++) GLPGP_CHECK(glpgp_amg_update_spd(a[s], c->S[s].v[VX]));
    BOTH(o->amg_coarse_solve(b, LV(1), LV(2)));
    BOTH(o->vec_read(b, LV(2), c->h[s]));
    GLPGP_CHECK(cmp(c, "multigrid coarse solve C r (SPD)", c->h[0], c->h[1], n, 1e-12, 1e-14, 0.0));
    for (int s = 0; s < 2; s++) GLPGP_CHECK(glpgp_amg_update(a[s], c->S[s].v[VX]));
    return GLPGP_OK;
}

/* A non-coarsest level l: smoother, restriction, prolongation and the fused
 * halves (lv[s]: x, r, y of level l, e of level l+1; he: e's values). */
static glpgp_status amg_level_rows(cc *c, int l, glpgp_vec *lv[2][4], const double *he, size_t n, size_t nc)
{
    char name[64];
    /* y <- M^-1 r;  then y <- x + M^-1 (r - A x) */
    BOTH(o->amg_smooth(b, l, LV(1), NULL, LV(2)));
    BOTH(o->vec_read(b, LV(2), c->h[s]));
    BOTH(o->amg_smooth(b, l, LV(1), LV(0), LV(2)));
    BOTH(o->vec_read(b, LV(2), c->h[s] + n));
    snprintf(name, sizeof name, "multigrid smoother level %d", l);
    GLPGP_CHECK(cmp(c, name, c->h[0], c->h[1], 2 * n, 1e-12, 1e-14, 0.0));
    /* e' <- P^T r;  e' <- P^T (r - A x)  (into the level-l+1 vector; e rewritten after) */
    BOTH(o->amg_restrict(b, l, LV(1), NULL, LV(3)));
    BOTH(o->vec_read(b, LV(3), c->h[s]));
    BOTH(o->amg_restrict(b, l, LV(1), LV(0), LV(3)));
    BOTH(o->vec_read(b, LV(3), c->h[s] + nc));
    snprintf(name, sizeof name, "multigrid restriction %d -> %d", l, l + 1);
    GLPGP_CHECK(cmp(c, name, c->h[0], c->h[1], 2 * nc, 1e-12, 1e-14, 0.0));
    /* y <- x;  y <- y + P e */
    BOTH(o->vec_write(b, LV(3), he));
    BOTH(o->copy(b, LV(2), LV(0)));
    BOTH(o->amg_prolong(b, l, LV(3), LV(2)));
    BOTH(o->vec_read(b, LV(2), c->h[s]));
    snprintf(name, sizeof name, "multigrid prolongation %d -> %d", l + 1, l);
    GLPGP_CHECK(cmp(c, name, c->h[0], c->h[1], n, 1e-12, 1e-14, 0.0));
    return amg_fused_rows(c, l, lv, he, n, nc);
}

/* Level 0 only: the K-cycle's register ops (dots, axpby with register
 * coefficients, kcombine) and one whole cycle z <- B r. */
static glpgp_status amg_level0_rows(cc *c, glpgp_amg *a[2], glpgp_vec *lv[2][4], size_t n, int S,
                                    double t[2][GLPGP_AMG_NSLOTS])
{
    /* t[S] <- x.r, t[S+1] <- x.x;  y <- r;  y <- (t[S]/t[S+1]) x - 0.5 y;
     * t[S+2..S+4] <- a few more;  y <- kcombine(x, r) */
    BOTH(o->amg_dots(b, LV(0), LV(1), LV(0), S));
    BOTH(o->copy(b, LV(2), LV(1)));
    const glpgp_amg_coef ca = {S, S + 1, 1.0}, cc2 = {-1, -1, -0.5};
    BOTH(o->amg_axpby(b, ca, LV(0), cc2, LV(2)));
    BOTH(o->vec_read(b, LV(2), c->h[s]));
    BOTH(o->amg_dots(b, LV(2), LV(0), LV(1), S + 2));
    BOTH(o->amg_dots(b, LV(2), LV(2), NULL, S + 4));
    GLPGP_CHECK(amg_scalars(c, t));
    GLPGP_CHECK(cmp(c, "multigrid dots (5)", t[0] + S, t[1] + S, 5, 1e-12, 1e-13, 0.0));
    GLPGP_CHECK(cmp(c, "multigrid axpby (coefficients)", c->h[0], c->h[1], n, 1e-12, 1e-14, 0.0));
    BOTH(o->amg_kcombine(b, LV(0), LV(1), LV(2), S));
    BOTH(o->vec_read(b, LV(2), c->h[s]));
    GLPGP_CHECK(cmp(c, "multigrid kcombine", c->h[0], c->h[1], n, 1e-10, 1e-10, 0.0));
    /* one cycle z <- B r */
    BOTH(glpgp_amg_apply(a[s], LV(1), LV(2)));
    BOTH(o->vec_read(b, LV(2), c->h[s]));
    return cmp(c, "multigrid cycle B r", c->h[0], c->h[1], n, 1e-10, 1e-10, 0.0);
}

/* Level l's vectors on both sides (x, r filled with hx, hr; e of level
 * l+1 with he) and its rows compared; the vectors freed. */
static glpgp_status amg_level(cc *c, glpgp_amg *a[2], int l, int L, const glpgp_amg_info *in, const double *hx,
                              const double *hr, const double *he)
{
    char name[64];
    double t[2][GLPGP_AMG_NSLOTS];
    glpgp_vec *lv[2][4] = {{NULL}}; /* per side: x, r, y (level l), e (level l+1) */
    const size_t n = (size_t)2 * in->n[l], nc = l + 1 < L ? (size_t)2 * in->n[l + 1] : 0;
    const int S = GLPGP_AMG_KSLOT(0);
    glpgp_status st = GLPGP_OK;
    for (int s = 0; s < 2 && st == GLPGP_OK; s++) {
        glpgp_backend *b = c->S[s].b;
        for (int k = 0; k < 3 && st == GLPGP_OK; k++) st = b->ops->vec_create(b, n, &lv[s][k]);
        if (nc && st == GLPGP_OK) st = b->ops->vec_create(b, nc, &lv[s][3]);
        if (st == GLPGP_OK) st = b->ops->vec_write(b, lv[s][0], hx);
        if (st == GLPGP_OK) st = b->ops->vec_write(b, lv[s][1], hr);
        if (nc && st == GLPGP_OK) st = b->ops->vec_write(b, lv[s][3], he);
    }
    /* y <- A_l x;  t[S] <- x.y;  t[S+1] <- x.r */
    for (int s = 0; s < 2 && st == GLPGP_OK; s++) {
        glpgp_backend *b = c->S[s].b;
        st = b->ops->amg_spmv_dots(b, l, LV(0), LV(2), LV(1), NULL, S);
        if (st == GLPGP_OK) st = b->ops->vec_read(b, LV(2), c->h[s]);
    }
    if (st == GLPGP_OK) st = amg_scalars(c, t);
    if (st == GLPGP_OK) {
        snprintf(name, sizeof name, "multigrid A_%d x", l);
        st = cmp(c, name, c->h[0], c->h[1], n, 1e-12, 1e-14, 0.0);
    }
    if (st == GLPGP_OK) {
        snprintf(name, sizeof name, "multigrid A_%d x: x.Ax, x.r", l);
        double d0[2] = {t[0][S], t[0][S + 1]}, d1[2] = {t[1][S], t[1][S + 1]};
        st = cmp(c, name, d0, d1, 2, 1e-12, 1e-13, 0.0);
    }
    if (st == GLPGP_OK) st = nc ? amg_level_rows(c, l, lv, he, n, nc) : amg_coarsest_rows(c, a, l, lv, n);
    if (st == GLPGP_OK && l == 0) st = amg_level0_rows(c, a, lv, n, S, t);
    for (int s = 0; s < 2; s++)
        for (int k = 0; k < 4; k++)
            if (lv[s][k]) c->S[s].b->ops->vec_destroy(c->S[s].b, &lv[s][k]);
    return st;
}
#undef LV

/* Both sides' hierarchies must have the same levels and sizes (a row). */
static glpgp_status amg_levels_row(cc *c, const glpgp_amg_info in[2], int *same)
{
    glpgp_crosscheck_row *r;
    GLPGP_CHECK(row_add(c->t, &r, "multigrid levels (%d, %d -> %d)", in[1].nlevels, in[1].n[0],
                        in[1].n[in[1].nlevels - 1]));
    snprintf(r->tol, sizeof r->tol, "exact");
    r->pass = in[0].nlevels == in[1].nlevels;
    for (int l = 0; r->pass && l < in[1].nlevels; l++)
        r->pass = in[0].n[l] == in[1].n[l] && in[0].nnzb[l] == in[1].nnzb[l];
    r->max_abs = r->max_rel = r->pass ? 0.0 : 1.0;
    *same = r->pass;
    return GLPGP_OK;
}

/* The multigrid ops level by level on random vectors, then a flexible CG
 * solve with the multigrid, on both sides. */
static glpgp_status stage_amg(cc *c)
{
    glpgp_status st = GLPGP_OK;
    glpgp_amg *a[2] = {NULL, NULL};
    double *hx = NULL, *hr = NULL, *he = NULL;
    char name[48];
    unsigned long long seed = c->opt->seed ^ 0x9e3779b97f4a7c15ull;
    glpgp_options so = c->so;
    so.precond = GLPGP_PRECOND_AMG;
    for (int s = 0; s < 2; s++)
        if (!glpgp_amg_supported(c->S[s].b)) return GLPGP_OK;
    /* the same z on both sides (the Newton step stage moved it by rounding) */
    BOTH(o->vec_write(b, v[VX], c->z));
    BOTH(o->assemble_newton(b, v[VX], c->inv4e2, GLPGP_HESS_MIXED));
    for (int s = 0; s < 2; s++) {
        GLPGP_CHECK_GOTO(st, glpgp_amg_create(c->S[s].b, &so, c->dir, NULL, 0.0, &a[s]), done);
        GLPGP_CHECK_GOTO(st, glpgp_amg_update(a[s], c->S[s].v[VX]), done);
    }
    glpgp_amg_info in[2];
    for (int s = 0; s < 2; s++) glpgp_amg_get_info(a[s], &in[s]);
    int same = 0;
    GLPGP_CHECK_GOTO(st, amg_levels_row(c, in, &same), done);
    if (!same) goto done;
    const int L = in[1].nlevels;
    GLPGP_CHECK_GOTO(st, glpgp_malloc(c->n2, sizeof(double), &hx), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(c->n2, sizeof(double), &hr), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(c->n2, sizeof(double), &he), done);
    for (int l = 0; l < L; l++) {
        const size_t n = (size_t)2 * in[1].n[l], nc = l + 1 < L ? (size_t)2 * in[1].n[l + 1] : 0;
        cc_fill(&seed, hx, n);
        cc_fill(&seed, hr, n);
        cc_fill(&seed, he, nc);
        GLPGP_CHECK_GOTO(st, amg_level(c, a, l, L, &in[1], hx, hr, he), done);
    }
    {
        /* flexible CG + multigrid: NEWTON d = -g */
        glpgp_cg_info ci[2];
        for (int s = 0; s < 2 && st == GLPGP_OK; s++) {
            glpgp_backend *b = c->S[s].b;
            glpgp_vec **v = c->S[s].v;
            st = b->ops->gradient(b, v[VX], c->inv4e2, v[VG]);
            if (st == GLPGP_OK) st = b->ops->axpby(b, -1.0, v[VG], 0.0, v[VY]);
            if (st == GLPGP_OK) st = glpgp_fcg(a[s], v[VY], v[VD], 1e-10, 1000, &ci[s]);
            if (st == GLPGP_OK) st = b->ops->vec_read(b, v[VD], c->h[s]);
        }
        if (st != GLPGP_OK) goto done;
        snprintf(name, sizeof name, "FCG+multigrid solve (%d vs %d it)", ci[0].iterations, ci[1].iterations);
        GLPGP_CHECK_GOTO(st, cmp(c, name, c->h[0], c->h[1], c->n2, 1e-6, 1e-6, 0.0), done);
    }
done:
    for (int s = 0; s < 2; s++) glpgp_amg_destroy(&a[s]);
    free(hx);
    free(hr);
    free(he);
    return st;
}

/* The whole GL solve on fresh backends (glpgp_solve does its own setup),
 * converged tightly so both paths reach the same minimiser (at the default
 * 1e-6 they may stop one iteration apart, ~1e-6 apart in z). */
static glpgp_status stage_gl_solve(cc *c)
{
    glpgp_status st = GLPGP_OK;
    glpgp_backend *sb[2] = {NULL, NULL};
    glpgp_result *res[2] = {NULL, NULL};
    glpgp_options so = c->so;
    glpgp_cl_options clo = {c->opt->device, 0, NULL};
    char name[48];
    so.newton_rtol = 1e-8;
    so.cg_rtol = 1e-10;
    so.precond = c->opt->precond;
    GLPGP_CHECK_GOTO(st, glpgp_backend_create_opencl(&clo, &sb[0]), done);
    GLPGP_CHECK_GOTO(st, glpgp_backend_create_reference(&sb[1]), done);
    for (int s = 0; s < 2; s++) {
        const double t0 = glpgp_now();
        GLPGP_CHECK_GOTO(st, glpgp_solve(c->m, sb[s], &so, &res[s]), done);
        c->t->solve_seconds[s] = glpgp_now() - t0;
        for (int k = 0; k < 2; k++) c->t->solve_cg[s][k] = res[s]->osc[k].cg_iterations;
    }
    c->t->solved = 1;
    for (int k = 0; k < 2; k++) {
        /* a level stopped by the Newton cap (drifting vortices) is not converged:
         * reduction-order rounding is amplified along the drift, so 1e-4 there */
        int capped = 0;
        for (int l = 0; l < res[1]->osc[k].nlevels; l++) capped |= res[1]->osc[k].level[l].newton >= so.newton_max;
        const double gtol = capped ? 1e-4 : 1e-6;
        snprintf(name, sizeof name, "GL solve z_%s (newton %d vs %d%s)", k ? "v" : "u",
                 res[0]->osc[k].newton_iterations, res[1]->osc[k].newton_iterations, capped ? ", capped" : "");
        GLPGP_CHECK_GOTO(st, cmp(c, name, res[0]->osc[k].z, res[1]->osc[k].z, c->n2, gtol, gtol, 0.0), done);
        snprintf(name, sizeof name, "GL singularities %s", k ? "v" : "u");
        GLPGP_CHECK_GOTO(st,
                         cmp_counts(c, name, res[0]->osc[k].plus, res[0]->osc[k].minus, res[1]->osc[k].plus,
                                    res[1]->osc[k].minus),
                         done);
    }
done:
    for (int s = 0; s < 2; s++) {
        glpgp_result_destroy(&res[s]);
        glpgp_backend_destroy(&sb[s]);
    }
    return st;
}

/* The Ginzburg-Landau cross field (glpgp_cross_solve: the same ops with W = 0
 * and every boundary vertex fixed) on fresh backends. Its minimisers can form
 * families (on a disk, the four singularities rotated together), along which
 * reduction-order rounding moves the result (2e-4 on a 3000-vertex disk):
 * w is compared at 1e-3, the final energy F_eps (constant along such a family)
 * at 1e-7 relative (the levels stop at --cross-rtol, 1e-3), the singularity
 * counts (+1/4 .. and -1/4 ..) exactly. */
static glpgp_status stage_cross_solve(cc *c)
{
    glpgp_status st = GLPGP_OK;
    glpgp_backend *sb[2] = {NULL, NULL};
    glpgp_cross_result *cr[2] = {NULL, NULL};
    glpgp_surface_constraints *con = NULL;
    glpgp_options so = c->so;
    glpgp_cl_options clo = {c->opt->device, 0, NULL};
    char name[64];
    so.cg_rtol = 1e-10;
    /* the line-search Newton: the trust region's accept / reject decisions
     * near its thresholds can send the two backends along different paths
     * into such a family (3000-vertex disk: 39 vs 42 steps, w apart by 6e-2
     * with the same energy to 6e-7); this stage checks the ops, not the
     * globalization (the oscillator stage above runs the default) */
    so.globalization = GLPGP_GLOBAL_LINE_SEARCH;
    GLPGP_CHECK_GOTO(st, glpgp_backend_create_opencl(&clo, &sb[0]), done);
    GLPGP_CHECK_GOTO(st, glpgp_backend_create_reference(&sb[1]), done);
    int np[2] = {0, 0}, nm[2] = {0, 0};
    if (c->m->xyz) GLPGP_CHECK_GOTO(st, glpgp_surface_constraints_create(c->m, so.feature_angle, &con), done);
    for (int s = 0; s < 2; s++) {
        if (c->m->xyz) { /* a surface's (sets the backend up itself) */
            GLPGP_CHECK_GOTO(st, glpgp_surface_cross_solve(c->m, sb[s], &so, con, &cr[s]), done);
        } else {
            GLPGP_CHECK_GOTO(st, sb[s]->ops->setup(sb[s], c->sys), done);
            GLPGP_CHECK_GOTO(st, glpgp_cross_solve(c->m, sb[s], &so, &cr[s]), done);
        }
        for (int k = 0; k < cr[s]->nsing; k++) {
            if (cr[s]->sing[k].index4 > 0) np[s]++;
            else nm[s]++;
        }
    }
    snprintf(name, sizeof name, "cross field w (newton %d vs %d)", cr[0]->newton_iterations,
             cr[1]->newton_iterations);
    GLPGP_CHECK_GOTO(st, cmp(c, name, cr[0]->w, cr[1]->w, c->n2, 1e-3, 1e-3, 0.0), done);
    const double fe[2] = {cr[0]->level[cr[0]->nlevels - 1].energy, cr[1]->level[cr[1]->nlevels - 1].energy};
    GLPGP_CHECK_GOTO(st, cmp(c, "cross field energy", &fe[0], &fe[1], 1, 1e-7, 0.0, 0.0), done);
    GLPGP_CHECK_GOTO(st, cmp_counts(c, "cross field singularities", np[0], nm[0], np[1], nm[1]), done);
done:
    glpgp_surface_constraints_destroy(&con);
    for (int s = 0; s < 2; s++) {
        glpgp_cross_result_destroy(&cr[s]);
        glpgp_backend_destroy(&sb[s]);
    }
    return st;
}

/* ---- driver ------------------------------------------------------------------ */

static void sides_free(cc *c)
{
    for (int s = 0; s < 2; s++) {
        cc_side *sd = &c->S[s];
        if (sd->b)
            for (int k = 0; k < NVEC; k++) sd->b->ops->vec_destroy(sd->b, &sd->v[k]);
        glpgp_backend_destroy(&sd->b);
    }
}

/* Backends, vectors, host buffers, the guiding field, z and r. */
static glpgp_status prepare(cc *c)
{
    const glpgp_crosscheck_options *opt = c->opt;
    const glpgp_mesh *m = c->m;
    glpgp_crosscheck *t = c->t;
    glpgp_cl_options clo = {opt->device, 0, NULL};
    /* a surface: the cross field's system (its rows turn each corner's value
     * into the triangle's plane, kernels/coupled_rows.h) */
    if (m->xyz)
        GLPGP_CHECK(glpgp_surface_cross_system(m, &c->sys));
    else
        GLPGP_CHECK(glpgp_system_create(m, &c->sys));
    c->n2 = (size_t)2 * m->nv;
    c->nm = (size_t)4 * c->sys->nnzb;
    c->nbuf = c->nm > 12 * c->n2 ? c->nm : 12 * c->n2; /* matrices; CG steps: 4 vectors x 3 steps */
    t->nv = m->nv;
    t->nt = m->nt;
    t->nnzb = c->sys->nnzb;
    t->energy = opt->energy;
    t->h = opt->size > 0.0 ? opt->size : glpgp_default_size(m, NULL);
    GLPGP_CHECK(glpgp_backend_create_opencl(&clo, &c->S[0].b));
    GLPGP_CHECK(glpgp_backend_create_reference(&c->S[1].b));
    glpgp_cl_backend_info(c->S[0].b, t->device, sizeof t->device);
    for (int s = 0; s < 2; s++) {
        glpgp_backend *b = c->S[s].b;
        GLPGP_CHECK(b->ops->setup(b, c->sys));
        for (int k = 0; k < NVEC; k++) GLPGP_CHECK(b->ops->vec_create(b, c->n2, &c->S[s].v[k]));
        GLPGP_CHECK(glpgp_malloc(c->nbuf, sizeof(double), &c->h[s]));
    }
    GLPGP_CHECK(glpgp_malloc(c->n2, sizeof(double), &c->field));
    GLPGP_CHECK(glpgp_malloc(c->n2, sizeof(double), &c->z));
    GLPGP_CHECK(glpgp_malloc(c->n2, sizeof(double), &c->r));
    GLPGP_CHECK(glpgp_malloc(c->n2, sizeof(double), &c->nan));
    GLPGP_CHECK(glpgp_malloc((size_t)m->nv, 1, &c->dir));

    /* guiding field (boundary-aligned, on the reference backend) and its Dirichlet set */
    glpgp_options_default(&c->so);
    c->so.size = t->h;
    /* one cycle on both sides: the OpenCL backend's (a GPU keeps the K-cycle
     * to the large levels, glpgp_amg_kcycle_min) */
    c->so.amg_kcycle_min = glpgp_amg_kcycle_min(c->S[0].b, &c->so);
    c->so.energy = opt->energy;
    long fit = 0;
    if (m->xyz) { /* a surface: a transported field, its boundary and creases fixed */
        glpgp_surface_constraints *con = NULL;
        GLPGP_CHECK(glpgp_surface_constraints_create(m, c->so.feature_angle, &con));
        glpgp_surface_transport(m, 1, c->field);
        memcpy(c->dir, con->fixed, (size_t)m->nv);
        t->ndirichlet = con->nfixed;
        glpgp_surface_constraints_destroy(&con);
        c->so.field = GLPGP_FIELD_CROSS; /* the whole solve: a surface's default */
    } else {
        GLPGP_CHECK(glpgp_field_compute(m, c->S[1].b, &c->so, c->field, &fit));
        t->ndirichlet = glpgp_dirichlet_set(m, c->field, c->dir);
    }
    t->field_cg = fit;
    /* z_i = rho exp(i phi), rho in [0.3, 1.3], phi in [0, 2 pi); then r_i in [-1/2, 1/2)^2 */
    unsigned long long seed = opt->seed;
    for (int i = 0; i < m->nv; i++) {
        const double rho = 0.3 + cc_rand(&seed), ph = 2.0 * GLPGP_PI * cc_rand(&seed);
        c->z[2 * i] = rho * cos(ph);
        c->z[2 * i + 1] = rho * sin(ph);
    }
    for (size_t i = 0; i < c->n2; i++) {
        c->r[i] = cc_rand(&seed) - 0.5;
        c->nan[i] = NAN;
    }
    const double eps = c->so.eps0 * t->h;
    c->inv4e2 = 1.0 / (4.0 * eps * eps);
    t->eps = eps;
    return GLPGP_OK;
}

glpgp_status glpgp_crosscheck_create(const glpgp_crosscheck_options *opt, glpgp_crosscheck **out)
{
    *out = NULL;
    if (!opt || !opt->mesh) return GLPGP_FAIL(GLPGP_ERR_ARG, "crosscheck: no mesh given");
    if (opt->energy != GLPGP_ELEM_P1 && opt->energy != GLPGP_ELEM_TRANSPORT)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "crosscheck: energy %d is not p1 or transport", opt->energy);
    if (!(opt->tol_scale > 0.0) || !isfinite(opt->tol_scale))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "crosscheck: tolerance scale %g is not a positive number", opt->tol_scale);
    if (!isfinite(opt->size)) return GLPGP_FAIL(GLPGP_ERR_ARG, "crosscheck: size %g is not finite", opt->size);
    glpgp_crosscheck *t = NULL;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *t, &t));
    cc c;
    memset(&c, 0, sizeof c);
    c.opt = opt;
    c.t = t;
    c.m = opt->mesh;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, prepare(&c), done);
    GLPGP_CHECK_GOTO(st, stage_vectors(&c), done);
    GLPGP_CHECK_GOTO(st, stage_quad(&c), done);
    GLPGP_CHECK_GOTO(st, stage_newton(&c), done);
    GLPGP_CHECK_GOTO(st, stage_gradient(&c), done);
    GLPGP_CHECK_GOTO(st, stage_spmv(&c), done);
    GLPGP_CHECK_GOTO(st, stage_trial(&c), done);
    GLPGP_CHECK_GOTO(st, stage_cg_steps(&c), done);
    GLPGP_CHECK_GOTO(st, stage_cg_solve(&c), done);
    GLPGP_CHECK_GOTO(st, stage_amg(&c), done);
    sides_free(&c); /* the GL solve makes its own backends */
    if (opt->solve) GLPGP_CHECK_GOTO(st, stage_gl_solve(&c), done);
    if (opt->solve) GLPGP_CHECK_GOTO(st, stage_cross_solve(&c), done);
done:
    sides_free(&c);
    for (int s = 0; s < 2; s++) free(c.h[s]);
    free(c.field);
    free(c.z);
    free(c.r);
    free(c.nan);
    free(c.dir);
    glpgp_system_destroy(&c.sys);
    t->pass = st == GLPGP_OK;
    for (int i = 0; i < t->nrows; i++) t->pass &= t->rows[i].pass;
    *out = t;
    return st;
}
