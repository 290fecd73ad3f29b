/* solve.c: the GL-PGP pipeline, written once against the backend table:
 * guiding field (boundary-aligned, harmonically interpolated angle; radial;
 * from file), Dirichlet sets, naive PGP (one linear solve) and the
 * Ginzburg-Landau Newton continuation in eps, singularity detection. */
#include "solve.h"
#include "element.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void glpgp_options_default(glpgp_options *o)
{
    memset(o, 0, sizeof *o);
    o->size = 0.0;
    o->method = GLPGP_METHOD_GL;
    o->energy = GLPGP_ELEM_P1;
    o->hess = GLPGP_HESS_MIXED;
    o->field = GLPGP_FIELD_BOUNDARY;
    o->init = GLPGP_INIT_NAIVE;
    o->eps0 = 0.5;
    o->eps_ratio = 0.5;
    o->eps_min = 2.5;
    o->newton_rtol = 1e-6;
    o->newton_max = 50;
    o->cg_rtol = 1e-8;
    o->cg_max = 20000;
    o->cg_check = 10;
    o->verbose = 1;
}

double glpgp_default_size(const glpgp_mesh *m)
{
    /* diameter / 20, raised to 10 mean edges when the mesh is too coarse for it
     * (P1 needs about 10 vertices per period, see host/README.md) */
    double dx = m->bbox[2] - m->bbox[0], dy = m->bbox[3] - m->bbox[1];
    return fmax(sqrt(dx * dx + dy * dy) / 20.0, 10.0 * m->mean_edge);
}

/* ---- guiding field ------------------------------------------------------ */

/* Angle of a direction folded into [-pi/4, pi/4] (mod pi/2). */
static double fold4(double nx, double ny)
{
    double phi = atan2(ny, nx);
    return phi - (GLPGP_PI / 2.0) * floor(phi / (GLPGP_PI / 2.0) + 0.5);
}

static glpgp_status field_boundary(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                   double *u, long *cg_iterations)
{
    const glpgp_backend_ops *op = b->ops;
    const int nv = m->nv;
    glpgp_status st = GLPGP_OK;
    double *x0 = NULL;
    glpgp_vec *x = NULL, *g = NULL, *d = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)2 * nv, sizeof(double), &x0));
    /* boundary angle alpha in [-pi/4, pi/4]: U is the normal or the tangent,
     * whichever is closer to the x axis. At a vertex the two adjacent edges'
     * angles are averaged as 4-fold directions (mean of exp(4 i alpha)). */
    for (int i = 0; i < nv; i++) {
        if (!m->on_boundary[i]) continue;
        double a1 = fold4(m->normal_prev[2 * i], m->normal_prev[2 * i + 1]);
        double a2 = fold4(m->normal_next[2 * i], m->normal_next[2 * i + 1]);
        double c = cos(4 * a1) + cos(4 * a2), s = sin(4 * a1) + sin(4 * a2);
        double a = (c * c + s * s > 1e-20) ? atan2(s, c) / 4.0 : a1;
        x0[2 * i] = a;
    }
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
    int it = 0;
    double rel = 0.0;
    GLPGP_CHECK_GOTO(st, glpgp_cg(b, g, d, o->cg_rtol, o->cg_max, o->cg_check, &it, &rel), done);
    *cg_iterations += it;
    GLPGP_CHECK_GOTO(st, op->axpby(b, 1.0, d, 1.0, x), done); /* alpha <- alpha0 + d */
    GLPGP_CHECK_GOTO(st, op->vec_read(b, x, x0), done);
    for (int i = 0; i < nv; i++) {
        u[2 * i] = cos(x0[2 * i]);
        u[2 * i + 1] = sin(x0[2 * i]);
    }
done:
    op->vec_destroy(b, &x);
    op->vec_destroy(b, &g);
    op->vec_destroy(b, &d);
    free(x0);
    return st;
}

static glpgp_status field_file(const glpgp_mesh *m, const char *path, double *u)
{
    FILE *f = fopen(path, "r");
    if (!f) return GLPGP_FAIL(GLPGP_ERR_IO, "cannot open field file '%s': %s", path, strerror(errno));
    char line[512];
    int i = 0, lineno = 0;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        char *p = line;
        while (*p == ' ' || *p == '\t') p++;
        if (*p == '#' || *p == '\n' || *p == '\r' || *p == '\0') continue;
        double ux, uy;
        char extra;
        if (sscanf(p, "%lf %lf %c", &ux, &uy, &extra) != 2 || !isfinite(ux) || !isfinite(uy)) {
            fclose(f);
            return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s:%d: expected two numbers 'ux uy'", path, lineno);
        }
        if (i >= m->nv) {
            fclose(f);
            return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: more than %d field lines (one per vertex expected)",
                              path, m->nv);
        }
        double n = sqrt(ux * ux + uy * uy);
        if (n < 1e-300) {
            fclose(f);
            return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s:%d: zero vector", path, lineno);
        }
        u[2 * i] = ux / n;
        u[2 * i + 1] = uy / n;
        i++;
    }
    fclose(f);
    if (i != m->nv)
        return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: %d field lines for %d vertices", path, i, m->nv);
    return GLPGP_OK;
}

glpgp_status glpgp_field_compute(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                 double *u, long *cg_iterations)
{
    if (o->field == GLPGP_FIELD_FILE) return field_file(m, o->field_file, u);
    if (o->field == GLPGP_FIELD_RADIAL) {
        double cx = o->center[0], cy = o->center[1];
        if (!o->has_center) { /* area centroid */
            double sx = 0.0, sy = 0.0, sa = 0.0;
            for (int t = 0; t < m->nt; t++) {
                double x[3], y[3];
                for (int a = 0; a < 3; a++) {
                    x[a] = m->xy[2 * m->tri[3 * t + a]];
                    y[a] = m->xy[2 * m->tri[3 * t + a] + 1];
                }
                double ar = glpgp_tri_area(x, y);
                sx += ar * (x[0] + x[1] + x[2]) / 3.0;
                sy += ar * (y[0] + y[1] + y[2]) / 3.0;
                sa += ar;
            }
            cx = sx / sa;
            cy = sy / sa;
        }
        for (int i = 0; i < m->nv; i++) {
            double dx = m->xy[2 * i] - cx, dy = m->xy[2 * i + 1] - cy, n = sqrt(dx * dx + dy * dy);
            u[2 * i] = n > 0.0 ? dx / n : 1.0;
            u[2 * i + 1] = n > 0.0 ? dy / n : 0.0;
        }
        return GLPGP_OK;
    }
    return field_boundary(m, b, o, u, cg_iterations);
}

int glpgp_dirichlet_set(const glpgp_mesh *m, const double *w, unsigned char *dir)
{
    int n = 0;
    for (int i = 0; i < m->nv; i++) {
        dir[i] = 0;
        if (!m->on_boundary[i]) continue;
        const double *nn[2] = {m->normal_prev + 2 * i, m->normal_next + 2 * i};
        for (int e = 0; e < 2; e++) {
            /* |W.n| >= |W.t| with t = n rotated by 90 degrees */
            double wn = w[2 * i] * nn[e][0] + w[2 * i + 1] * nn[e][1];
            double wt = -w[2 * i] * nn[e][1] + w[2 * i + 1] * nn[e][0];
            if (fabs(wn) >= fabs(wt)) dir[i] = 1;
        }
        n += dir[i];
    }
    return n;
}

void glpgp_singularities(const glpgp_mesh *m, const double *z, signed char *sing, int *plus,
                         int *minus)
{
    int p = 0, q = 0;
    for (int t = 0; t < m->nt; t++) {
        double zr[3], zi[3];
        for (int a = 0; a < 3; a++) {
            zr[a] = z[2 * m->tri[3 * t + a]];
            zi[a] = z[2 * m->tri[3 * t + a] + 1];
        }
        int w = glpgp_tri_winding(zr, zi);
        if (w > 1) w = 1;
        if (w < -1) w = -1;
        if (sing) sing[t] = (signed char)w;
        if (w > 0) p++;
        if (w < 0) q++;
    }
    *plus = p;
    *minus = q;
}

/* ---- oscillators --------------------------------------------------------- */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* |z| statistics: min, 10th percentile, median (scratch: nv doubles). */
static void zabs_stats(const double *z, int nv, double *scratch, double *mn, double *p10, double *med)
{
    for (int i = 0; i < nv; i++) scratch[i] = hypot(z[2 * i], z[2 * i + 1]);
    qsort(scratch, (size_t)nv, sizeof(double), cmp_double);
    *mn = scratch[0];
    *p10 = scratch[(size_t)((nv - 1) * 0.1)];
    *med = nv % 2 ? scratch[nv / 2] : 0.5 * (scratch[nv / 2 - 1] + scratch[nv / 2]);
}

typedef struct osc_work {
    glpgp_backend *b;
    const glpgp_options *o;
    int nv;
    glpgp_vec *x, *g, *d, *xt, *work;
    double *host, *scratch;
} osc_work;

/* |g| / |g_0| below which `mixed` tries the exact Hessian (see newton_level) */
#ifndef GLPGP_EXACT_SWITCH
#define GLPGP_EXACT_SWITCH 0.05
#endif

/* Newton tolerance of the levels before the last one */
#ifndef GLPGP_INTERMEDIATE_RTOL
#define GLPGP_INTERMEDIATE_RTOL 1e-3
#endif

static const char *osc_name(int k) { return k == 0 ? "u" : "v"; }

glpgp_status glpgp_newton_step(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *ns,
                               double inv4e2, double F, double gn, glpgp_newton_step_info *info)
{
    const glpgp_backend_ops *op = b->ops;
    double s[GLPGP_NSLOTS];
    memset(info, 0, sizeof *info);
    /* (H_E + H~_P) d = -g.  With `mixed`, once the previous step was a full
     * step without fallback and |g| <= GLPGP_EXACT_SWITCH |g_0|, the exact
     * Hessian is tried first (quadratic convergence around localised
     * vortices). On CG breakdown or a non-descent d the step is redone with
     * the next safer Hessian: exact -> mixed -> projected. */
    int hess = o->hess;
    if (hess == GLPGP_HESS_MIXED && ns->near) hess = GLPGP_HESS_EXACT;
    const int tried_exact = hess != o->hess;
    double slope = 0.0;
    for (;;) {
        GLPGP_CHECK(op->assemble_newton(b, ns->x, inv4e2, hess));
        GLPGP_CHECK(op->axpby(b, -1.0, ns->g, 0.0, ns->xt)); /* xt <- -g (rhs) */
        double rel = 0.0;
        int it_cg = 0;
        /* inexact Newton: CG tolerance eta = 0.1 |g|/|g_0|, within [cg_rtol, 1e-2] */
        double eta = fmin(1e-2, fmax(o->cg_rtol, 0.1 * gn / ns->grad0));
        glpgp_status cst = glpgp_cg(b, ns->xt, ns->d, eta, o->cg_max, o->cg_check, &it_cg, &rel);
        info->cg += it_cg;
        if (cst == GLPGP_OK) {
            GLPGP_CHECK(op->dot(b, ns->g, ns->d, GLPGP_S_DOT));
            GLPGP_CHECK(op->get_scalars(b, s, GLPGP_NSLOTS));
            slope = s[GLPGP_S_DOT];
            if (slope < 0.0 || hess == GLPGP_HESS_PROJECTED || hess == GLPGP_HESS_PAPER) break;
        } else if (cst != GLPGP_ERR_NUMERIC || hess == GLPGP_HESS_PROJECTED || hess == GLPGP_HESS_PAPER) {
            GLPGP_CHECK(cst);
        } else {
            glpgp_error_clear();
        }
        hess = (hess == GLPGP_HESS_EXACT && o->hess == GLPGP_HESS_MIXED) ? GLPGP_HESS_MIXED
                                                                          : GLPGP_HESS_PROJECTED;
        info->fallbacks++;
    }
    /* backtracking: accept x + a d when F(x + a d) <= F + 1e-4 a g.d, up to the
     * rounding level of F (near convergence g.d is below what F can resolve) */
    const double noise = 64.0 * DBL_EPSILON * fabs(F);
    double a = 1.0, Ft = F;
    for (int ls_it = 0; ls_it < 40; ls_it++) {
        GLPGP_CHECK(op->copy(b, ns->xt, ns->x));
        GLPGP_CHECK(op->axpby(b, a, ns->d, 1.0, ns->xt)); /* xt <- x + a d */
        GLPGP_CHECK(op->energy(b, ns->xt, inv4e2, ns->work));
        GLPGP_CHECK(op->get_scalars(b, s, GLPGP_NSLOTS));
        Ft = s[GLPGP_S_E] + s[GLPGP_S_P];
        if (isfinite(Ft) && Ft <= F + 1e-4 * a * slope + noise) {
            info->accepted = 1;
            break;
        }
        a *= 0.5;
    }
    info->alpha = info->accepted ? a : 0.0;
    info->energy = Ft;
    /* after a failed exact attempt, wait a few steps before the next one */
    if (info->fallbacks > 0 && tried_exact) ns->cooldown = 5;
    else if (ns->cooldown > 0) ns->cooldown--;
    ns->near = info->accepted && a == 1.0 && info->fallbacks == 0 && ns->cooldown == 0 &&
               gn <= GLPGP_EXACT_SWITCH * ns->grad0;
    if (info->accepted) GLPGP_CHECK(op->copy(b, ns->x, ns->xt)); /* x <- x + a d */
    return GLPGP_OK;
}

/* One Newton level at eps: x <- argmin E + P_eps (modified Newton steps until
 * |g| <= rtol |g_0|, the cap, or no descent). */
static glpgp_status newton_level(osc_work *w, int k, double eps, double rtol, glpgp_level_stats *ls)
{
    glpgp_backend *b = w->b;
    const glpgp_backend_ops *op = b->ops;
    const glpgp_options *o = w->o;
    const double inv4e2 = 1.0 / (4.0 * eps * eps);
    double s[GLPGP_NSLOTS];
    glpgp_newton_state ns = {w->x, w->g, w->d, w->xt, w->work, 0.0, 0, 0};
    ls->eps = eps;
    ls->newton = 0;
    ls->cg = 0;
    for (int it = 0;; it++) {
        /* g <- grad(E + P)(x) (zero on Dirichlet vertices); F = E + P */
        GLPGP_CHECK(op->gradient(b, w->x, inv4e2, w->g));
        GLPGP_CHECK(op->dot(b, w->g, w->g, GLPGP_S_DOT));
        GLPGP_CHECK(op->get_scalars(b, s, GLPGP_NSLOTS));
        const double F = s[GLPGP_S_E] + s[GLPGP_S_P];
        const double gn = sqrt(s[GLPGP_S_DOT]);
        if (!isfinite(F) || !isfinite(gn))
            return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "oscillator %s: energy became non-finite at eps=%g",
                              osc_name(k), eps);
        if (it == 0) ls->grad0 = ns.grad0 = gn;
        ls->grad = gn;
        ls->energy = F;
        if (gn <= rtol * ls->grad0 || gn == 0.0 || it >= o->newton_max) break;
        glpgp_newton_step_info info;
        GLPGP_CHECK(glpgp_newton_step(b, o, &ns, inv4e2, F, gn, &info));
        ls->cg += info.cg;
        ls->fallbacks += info.fallbacks;
        ls->newton++;
        if (o->verbose >= 1)
            fprintf(stderr, "glpgp:   %s eps=%.4g newton %3d  |g|=%.3e  E+P=%.10g  cg=%d  step=%g\n",
                    osc_name(k), eps, it + 1, gn, info.energy, info.cg, info.alpha);
        if (!info.accepted) break; /* no descent possible at this precision: level done */
    }
    return GLPGP_OK;
}

static glpgp_status solve_oscillator(const glpgp_mesh *m, osc_work *w, int k,
                                     const double *hostw, glpgp_osc_result *r, double h,
                                     const double *eps, int nlevels)
{
    glpgp_backend *b = w->b;
    const glpgp_backend_ops *op = b->ops;
    const glpgp_options *o = w->o;
    const int nv = m->nv;
    double t0 = now();
    r->n_dirichlet = glpgp_dirichlet_set(m, hostw, r->dirichlet);
    GLPGP_CHECK(op->set_field(b, hostw, r->dirichlet));
    GLPGP_CHECK(op->assemble_quadratic(b, o->energy, h));

    /* naive PGP: minimise E with z = 1 on the Dirichlet set:
     * x = x0 + d,  N d = -(A x0) with N = A with Dirichlet rows/cols eliminated */
    for (int i = 0; i < nv; i++) {
        w->host[2 * i] = r->dirichlet[i] ? 1.0 : 0.0;
        w->host[2 * i + 1] = 0.0;
    }
    GLPGP_CHECK(op->vec_write(b, w->x, w->host));
    int need_naive = o->method == GLPGP_METHOD_PGP || (o->init == GLPGP_INIT_NAIVE && r->n_dirichlet > 0);
    if (need_naive) {
        GLPGP_CHECK(op->assemble_newton(b, w->x, 0.0, o->hess));
        GLPGP_CHECK(op->gradient(b, w->x, 0.0, w->g));
        GLPGP_CHECK(op->axpby(b, -1.0, w->g, 0.0, w->xt));
        int cgit = 0;
        double rel = 0.0;
        GLPGP_CHECK(glpgp_cg(b, w->xt, w->d, o->cg_rtol, o->cg_max, o->cg_check, &cgit, &rel));
        r->cg_iterations += cgit;
        GLPGP_CHECK(op->axpby(b, 1.0, w->d, 1.0, w->x));
        if (o->verbose >= 1)
            fprintf(stderr, "glpgp: %s: naive PGP solve, %d Dirichlet vertices, %d CG iterations\n",
                    osc_name(k), r->n_dirichlet, cgit);
    }
    if (o->method == GLPGP_METHOD_GL) {
        /* initial guess: normalised naive solution (phase kept), or z = 1 */
        if (need_naive) {
            GLPGP_CHECK(op->vec_read(b, w->x, w->host));
            for (int i = 0; i < nv; i++) {
                double a = hypot(w->host[2 * i], w->host[2 * i + 1]);
                if (a > 1e-300) {
                    w->host[2 * i] /= a;
                    w->host[2 * i + 1] /= a;
                } else {
                    w->host[2 * i] = 1.0;
                    w->host[2 * i + 1] = 0.0;
                }
            }
        } else {
            for (int i = 0; i < nv; i++) {
                w->host[2 * i] = 1.0;
                w->host[2 * i + 1] = 0.0;
            }
        }
        GLPGP_CHECK(op->vec_write(b, w->x, w->host));
        r->nlevels = nlevels;
        for (int l = 0; l < nlevels; l++) {
            glpgp_level_stats *ls = &r->level[l];
            if (o->verbose >= 1)
                fprintf(stderr, "glpgp: %s: level %d/%d, eps = %.4g\n", osc_name(k), l + 1, nlevels, eps[l]);
            /* intermediate levels only prepare the next one: looser tolerance */
            const double rtol = l + 1 < nlevels ? fmax(o->newton_rtol, GLPGP_INTERMEDIATE_RTOL) : o->newton_rtol;
            GLPGP_CHECK(newton_level(w, k, eps[l], rtol, ls));
            GLPGP_CHECK(op->vec_read(b, w->x, w->host));
            double mn, p10, med;
            zabs_stats(w->host, nv, w->scratch, &mn, &p10, &med);
            ls->median_zabs = med;
            if (med < 0.5 && !ls->restarted) {
                /* collapse towards z = 0 (a stable critical point at large eps):
                 * restart this level once from z = 1 */
                if (o->verbose >= 1)
                    fprintf(stderr, "glpgp: %s: median |z| = %.3g at eps=%.4g: collapsed, restarting from z = 1\n",
                            osc_name(k), med, eps[l]);
                for (int i = 0; i < nv; i++) {
                    w->host[2 * i] = 1.0;
                    w->host[2 * i + 1] = 0.0;
                }
                GLPGP_CHECK(op->vec_write(b, w->x, w->host));
                glpgp_level_stats keep = *ls;
                GLPGP_CHECK(newton_level(w, k, eps[l], rtol, ls));
                ls->newton += keep.newton;
                ls->cg += keep.cg;
                ls->restarted = 1;
                GLPGP_CHECK(op->vec_read(b, w->x, w->host));
                zabs_stats(w->host, nv, w->scratch, &mn, &p10, &med);
                ls->median_zabs = med;
            }
            r->newton_iterations += ls->newton;
            r->cg_iterations += ls->cg;
        }
    }
    GLPGP_CHECK(op->energy(b, w->x, 0.0, w->work));
    double s[GLPGP_NSLOTS];
    GLPGP_CHECK(op->get_scalars(b, s, GLPGP_NSLOTS));
    r->energy = s[GLPGP_S_E];
    GLPGP_CHECK(op->vec_read(b, w->x, r->z));
    glpgp_singularities(m, r->z, r->singular, &r->plus, &r->minus);
    zabs_stats(r->z, nv, w->scratch, &r->zabs_min, &r->zabs_p10, &r->zabs_median);
    r->seconds = now() - t0;
    if (o->verbose >= 1)
        fprintf(stderr, "glpgp: %s: done in %.2f s: median |z| = %.4f, singular +%d/-%d, %d Newton, %ld CG\n",
                osc_name(k), r->seconds, r->zabs_median, r->plus, r->minus, r->newton_iterations,
                r->cg_iterations);
    return GLPGP_OK;
}

void glpgp_result_destroy(glpgp_result **pr)
{
    if (!pr || !*pr) return;
    glpgp_result *r = *pr;
    free(r->field);
    for (int k = 0; k < 2; k++) {
        free(r->osc[k].z);
        free(r->osc[k].dirichlet);
        free(r->osc[k].singular);
    }
    free(r);
    *pr = NULL;
}

glpgp_status glpgp_solve(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                         glpgp_result **out)
{
    glpgp_status st = GLPGP_OK;
    glpgp_result *r = NULL;
    glpgp_system *sys = NULL;
    osc_work w;
    double *wv = NULL;
    memset(&w, 0, sizeof w);
    *out = NULL;
    const double t0 = now();
    const int nv = m->nv, nt = m->nt;

    double h = o->size > 0.0 ? o->size : glpgp_default_size(m);
    if (!isfinite(h) || h <= 0.0) return GLPGP_FAIL(GLPGP_ERR_ARG, "invalid target size h = %g", h);
    if (o->eps_ratio <= 0.0 || o->eps_ratio >= 1.0)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "eps ratio must be in (0,1), got %g", o->eps_ratio);
    if (o->eps0 <= 0.0 || o->eps_min <= 0.0)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "eps0 and eps-min must be positive");

    GLPGP_CHECK(glpgp_calloc(1, sizeof *r, &r));
    r->nv = nv;
    r->nt = nt;
    r->size = h;
    r->backend = b->ops->name;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv, sizeof(double), &r->field), fail);
    for (int k = 0; k < 2; k++) {
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * nv, sizeof(double), &r->osc[k].z), fail);
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv, 1, &r->osc[k].dirichlet), fail);
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nt, 1, &r->osc[k].singular), fail);
    }

    /* layout + upload */
    GLPGP_CHECK_GOTO(st, glpgp_system_create(m, &sys), fail);
    if (o->verbose >= 1)
        fprintf(stderr, "glpgp: %d vertices, %d triangles, %ld blocks, h = %g (%.1f edges per period), backend %s\n",
                nv, nt, sys->nnzb, h, h / m->mean_edge, b->ops->name);
    if (o->verbose >= 1 && h < 6.0 * m->mean_edge)
        fprintf(stderr, "glpgp: warning: h = %g is only %.1f mean edges: P1 needs about 10 vertices per "
                        "period (refine the mesh, raise --size, or use --energy transport)\n",
                h, h / m->mean_edge);
    GLPGP_CHECK_GOTO(st, b->ops->setup(b, sys), fail);
    w.b = b;
    w.o = o;
    w.nv = nv;
    const size_t n2 = (size_t)2 * nv;
    GLPGP_CHECK_GOTO(st, b->ops->vec_create(b, n2, &w.x), fail);
    GLPGP_CHECK_GOTO(st, b->ops->vec_create(b, n2, &w.g), fail);
    GLPGP_CHECK_GOTO(st, b->ops->vec_create(b, n2, &w.d), fail);
    GLPGP_CHECK_GOTO(st, b->ops->vec_create(b, n2, &w.xt), fail);
    GLPGP_CHECK_GOTO(st, b->ops->vec_create(b, n2, &w.work), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n2, sizeof(double), &w.host), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(double), &w.scratch), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n2, sizeof(double), &wv), fail);
    r->seconds_setup = now() - t0;

    /* guiding field U */
    double t1 = now();
    GLPGP_CHECK_GOTO(st, glpgp_field_compute(m, b, o, r->field, &r->field_cg_iterations), fail);
    r->seconds_field = now() - t1;

    /* eps schedule: eps0*h, then *ratio, down to eps_min * mean edge */
    double eps[GLPGP_MAX_LEVELS];
    int nlev = 0;
    double e = o->eps0 * h, emin = o->eps_min * m->mean_edge;
    eps[nlev++] = e;
    /* the last level sits at emin; a level closer than 25% to its predecessor is dropped */
    while (e > emin * 1.25 && nlev < GLPGP_MAX_LEVELS) {
        e = fmax(e * o->eps_ratio, emin);
        eps[nlev++] = e;
    }

    for (int k = 0; k < 2; k++) {
        /* W = U (k = 0) or V = U rotated by +90 degrees (k = 1) */
        for (int i = 0; i < nv; i++) {
            double ux = r->field[2 * i], uy = r->field[2 * i + 1];
            wv[2 * i] = k == 0 ? ux : -uy;
            wv[2 * i + 1] = k == 0 ? uy : ux;
        }
        GLPGP_CHECK_GOTO(st, solve_oscillator(m, &w, k, wv, &r->osc[k], h, eps, nlev), fail);
    }
    r->seconds_total = now() - t0;
    goto cleanup;
fail:
    glpgp_result_destroy(&r);
cleanup:
    if (b->ops) {
        b->ops->vec_destroy(b, &w.x);
        b->ops->vec_destroy(b, &w.g);
        b->ops->vec_destroy(b, &w.d);
        b->ops->vec_destroy(b, &w.xt);
        b->ops->vec_destroy(b, &w.work);
    }
    free(w.host);
    free(w.scratch);
    free(wv);
    glpgp_system_destroy(&sys);
    *out = r;
    return st;
}
