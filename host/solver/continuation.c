/* solver/continuation.c: the whole pipeline of glpgp_solve: layout and
 * backend setup, guiding field, then per oscillator (W = U, then V = U
 * rotated by +90 degrees) the Dirichlet set, the quadratic form, the naive
 * PGP solve (minimise E with z = 1 on the Dirichlet set) and the
 * Ginzburg-Landau continuation: Newton levels at decreasing eps (eps0 h,
 * times eps_ratio, down to eps_min mean edges), starting from the normalised
 * naive solution (or z = 1), with one restart from z = 1 of a level that
 * collapses (median |z| < collapse_zabs). Levels stopped by the Newton cap are
 * flagged and warned about. */
#include "amg_internal.h"

#include "glpgp/cross.h"
#include "glpgp/surfsolve.h"
#include "glpgp/util.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


/* w <- the driver's vectors on backend b (set up): x, g, d, xt, work of n
 * unknowns, host (n doubles) and scratch (ns doubles); the rest of w zero.
 * Free: osc_work_free (also after a failure part-way). */
glpgp_status glpgp_osc_work_create(osc_work *w, glpgp_backend *b, const glpgp_options *o, size_t n, size_t ns)
{
    memset(w, 0, sizeof *w);
    w->b = b;
    w->o = o;
    GLPGP_CHECK(b->ops->vec_create(b, n, &w->x));
    GLPGP_CHECK(b->ops->vec_create(b, n, &w->g));
    GLPGP_CHECK(b->ops->vec_create(b, n, &w->d));
    GLPGP_CHECK(b->ops->vec_create(b, n, &w->xt));
    GLPGP_CHECK(b->ops->vec_create(b, n, &w->work));
    GLPGP_CHECK(glpgp_malloc(n, sizeof(double), &w->host));
    GLPGP_CHECK(glpgp_malloc(ns, sizeof(double), &w->scratch));
    return GLPGP_OK;
}

void glpgp_osc_work_free(osc_work *w)
{
    glpgp_amg_destroy(&w->amg);
    if (w->b && w->b->ops) {
        w->b->ops->vec_destroy(w->b, &w->x);
        w->b->ops->vec_destroy(w->b, &w->g);
        w->b->ops->vec_destroy(w->b, &w->d);
        w->b->ops->vec_destroy(w->b, &w->xt);
        w->b->ops->vec_destroy(w->b, &w->work);
    }
    free(w->host);
    free(w->scratch);
    w->host = w->scratch = NULL;
}

/* median |z| of z (2*nv; scratch: nv doubles) */
static double zabs_median(const double *z, int nv, double *scratch)
{
    return glpgp_zabs_median(z, nv, scratch, NULL, NULL);
}

/* *out <- median |z| of the mesh m (a part: over all ranks) */
static glpgp_status level_median(osc_work *w, const glpgp_mesh *m, const double *z, double *out)
{
    if (m->part) return glpgp_dist_zabs_stats(w->b, m, z, NULL, NULL, out);
    *out = zabs_median(z, m->nv, w->scratch);
    return GLPGP_OK;
}

/* x read back into w->host and its median |z| (ls->median_zabs), timed as the summary */
static glpgp_status level_read(osc_work *w, const glpgp_mesh *m, double *median)
{
    const int prev = glpgp_timer_enter(w->b, GLPGP_TM_SUMMARY);
    glpgp_status st = w->b->ops->vec_read(w->b, w->x, w->host);
    if (st == GLPGP_OK) st = level_median(w, m, w->host, median);
    glpgp_timer_leave(w->b, prev);
    return st;
}

static void fill_one(double *z, int nv)
{
    for (int i = 0; i < nv; i++) {
        z[2 * i] = 1.0;
        z[2 * i + 1] = 0.0;
    }
}

/* x <- naive PGP: x = x0 + d with x0 = 1 on the Dirichlet set, N d = -(A x0)
 * (N = A with Dirichlet rows and columns eliminated). */
static glpgp_status naive_solve(osc_work *w, int k, glpgp_osc_result *r)
{
    glpgp_backend *b = w->b;
    const glpgp_backend_ops *op = b->ops;
    const glpgp_options *o = w->o;
    int prev = glpgp_timer_enter(b, GLPGP_TM_ASSEMBLY);
    glpgp_status st = op->assemble_newton(b, w->x, 0.0, o->hess);
    glpgp_tm_leave(b, o->phase_sync, prev);
    GLPGP_CHECK(st);
    /* multigrid: plane-wave frames (x is 0 off the Dirichlet set) */
    if (w->amg && !glpgp_amg_try_update(w->amg, NULL, "naive PGP solve")) glpgp_amg_destroy(&w->amg);
    prev = glpgp_timer_enter(b, GLPGP_TM_ENERGY);
    st = op->gradient(b, w->x, 0.0, w->g);
    glpgp_tm_leave(b, o->phase_sync, prev);
    GLPGP_CHECK(st);
    GLPGP_CHECK(op->axpby(b, -1.0, w->g, 0.0, w->xt));
    glpgp_cg_info ci;
    GLPGP_CHECK(glpgp_linear_solve(b, w->amg, w->xt, w->d, o->cg_rtol, o->cg_max, o->cg_check, &ci));
    r->cg_iterations += ci.iterations;
    if (ci.reason == GLPGP_CG_BREAKDOWN)
        return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "%s: naive PGP solve: CG breakdown after %d iterations "
                                             "(the quadratic form is not SPD: folded mesh?)",
                          glpgp_osc_name(k), ci.iterations);
    if (ci.reason == GLPGP_CG_MAXIT)
        glpgp_log(GLPGP_LOG_WARNING, "%s: naive PGP solve stopped at the CG cap of %d iterations "
                                     "(relative residual %.2e)", glpgp_osc_name(k), ci.iterations,
                  ci.relres);
    GLPGP_CHECK(op->axpby(b, 1.0, w->d, 1.0, w->x));
    glpgp_log(GLPGP_LOG_INFO, "%s: naive PGP solve, %d Dirichlet vertices, %d CG iterations",
              glpgp_osc_name(k), r->n_dirichlet, ci.iterations);
    return GLPGP_OK;
}

/* One oscillator (k = 0, 1) on mesh m, or the coupled pair (k = 3) on the
 * coupled system's virtual mesh m with its Dirichlet set dir_given (then r
 * is not summarised: the caller splits it per vertex first). */
glpgp_status glpgp_solve_oscillator(const glpgp_mesh *m, osc_work *w, int k, const double *hostw,
                                     const double *size, glpgp_osc_result *r, double h, const double *eps,
                                     int nlevels, const unsigned char *dir_given)
{
    glpgp_backend *b = w->b;
    const glpgp_backend_ops *op = b->ops;
    const glpgp_options *o = w->o;
    const int nv = m->nv;
    double t0 = glpgp_now();
    if (dir_given) {
        memcpy(r->dirichlet, dir_given, (size_t)nv);
        r->n_dirichlet = 0;
        for (int i = 0; i < nv; i++) r->n_dirichlet += dir_given[i] != 0;
    } else {
        r->n_dirichlet = glpgp_dirichlet_set(m, hostw, r->dirichlet);
        if (m->part) GLPGP_CHECK(glpgp_dist_count(b, m, r->dirichlet, &r->n_dirichlet)); /* all ranks' */
    }
    int prev = glpgp_timer_enter(b, GLPGP_TM_ASSEMBLY);
    glpgp_status st = op->set_field(b, hostw, r->dirichlet);
    if (st == GLPGP_OK && size) st = op->set_size(b, size); /* local size h(x) (NULL: uniform h) */
    if (st == GLPGP_OK) st = op->assemble_quadratic(b, o->energy, h);
    glpgp_tm_leave(b, o->phase_sync, prev);
    GLPGP_CHECK(st);
    /* multigrid hierarchy for this Dirichlet set (NULL: Jacobi) */
    glpgp_amg_destroy(&w->amg);
    w->amg = glpgp_amg_try_create(b, o, r->dirichlet, hostw, h, glpgp_osc_name(k));

    for (int i = 0; i < nv; i++) {
        w->host[2 * i] = r->dirichlet[i] ? 1.0 : 0.0;
        w->host[2 * i + 1] = 0.0;
    }
    GLPGP_CHECK(op->vec_write(b, w->x, w->host));
    int need_naive = o->method == GLPGP_METHOD_PGP || (o->init == GLPGP_INIT_NAIVE && r->n_dirichlet > 0);
    if (w->init_free && r->n_dirichlet == 0 && (o->method == GLPGP_METHOD_PGP || o->init == GLPGP_INIT_NAIVE)) {
        /* no Dirichlet node: the naive solution is 0; the caller's (a surface's eigenvector) */
        GLPGP_CHECK(w->init_free(w, k, r));
        need_naive = 1;
    } else if (need_naive) {
        GLPGP_CHECK(naive_solve(w, k, r));
    }
    if (o->method == GLPGP_METHOD_GL) {
        /* initial guess: normalised naive solution (phase kept), or z = 1 */
        prev = glpgp_timer_enter(b, GLPGP_TM_SUMMARY);
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
            fill_one(w->host, nv);
        }
        GLPGP_CHECK(op->vec_write(b, w->x, w->host));
        glpgp_timer_leave(b, prev);
        r->nlevels = nlevels;
        glpgp_newton_state ns = {.x = w->x, .g = w->g, .d = w->d, .xt = w->xt, .work = w->work,
                                 .amg = w->amg, .stop = w->stop, .ftol = o->newton_ftol};
        for (int l = 0; l < nlevels; l++) {
            glpgp_level_stats *ls = &r->level[l];
            glpgp_log(GLPGP_LOG_INFO, "%s: level %d/%d, eps = %.4g", glpgp_osc_name(k), l + 1,
                      nlevels, eps[l]);
            /* intermediate levels only prepare the next one: looser tolerance */
            const double rtol = l + 1 < nlevels ? fmax(o->newton_rtol, o->intermediate_rtol) : o->newton_rtol;
            GLPGP_CHECK(glpgp_newton_level(b, o, &ns, k, eps[l], rtol, ls));
            GLPGP_CHECK(level_read(w, m, &ls->median_zabs));
            if (ls->median_zabs < o->collapse_zabs && !ls->restarted) {
                /* collapse towards z = 0 (a stable critical point at large eps):
                 * restart this level once from z = 1 */
                glpgp_log(GLPGP_LOG_INFO, "%s: median |z| = %.3g at eps=%.4g: collapsed, restarting from z = 1",
                          glpgp_osc_name(k), ls->median_zabs, eps[l]);
                fill_one(w->host, nv);
                GLPGP_CHECK(op->vec_write(b, w->x, w->host));
                glpgp_level_stats keep = *ls;
                GLPGP_CHECK(glpgp_newton_level(b, o, &ns, k, eps[l], rtol, ls));
                ls->newton += keep.newton;
                ls->cg += keep.cg;
                ls->restarted = 1;
                GLPGP_CHECK(level_read(w, m, &ls->median_zabs));
            }
            if (ls->stalled)
                glpgp_log(GLPGP_LOG_INFO,
                          "%s: eps level %d/%d stopped after %d Newton steps: E + P fell by at most %.0e of "
                          "itself over the last 3 (|g|/|g0| = %.2e, tolerance %.0e: a plateau)",
                          glpgp_osc_name(k), l + 1, nlevels, ls->newton, o->newton_ftol,
                          ls->grad0 > 0 ? ls->grad / ls->grad0 : 0.0, rtol);
            if (ls->capped) {
                r->capped_levels++;
                glpgp_log(GLPGP_LOG_WARNING,
                          "%s: eps level %d/%d stopped at the Newton cap of %d steps with |g|/|g0| = %.2e "
                          "(tolerance %.0e): not converged",
                          glpgp_osc_name(k), l + 1, nlevels, o->newton_max,
                          ls->grad0 > 0 ? ls->grad / ls->grad0 : 0.0, rtol);
            }
            r->newton_iterations += ls->newton;
            r->cg_iterations += ls->cg;
        }
        /* one warning per oscillator when CG hit its cap in Newton steps */
        int capped = 0;
        for (int l = 0; l < nlevels; l++) capped += r->level[l].cg_capped;
        if (capped > 0)
            glpgp_log(GLPGP_LOG_WARNING,
                      "%s: CG stopped at its cap of %d iterations in %d of %d Newton steps: the steps "
                      "were inexact (raise --cg-max)",
                      glpgp_osc_name(k), o->cg_max, capped, r->newton_iterations);
    }
    prev = glpgp_timer_enter(b, GLPGP_TM_SUMMARY);
    GLPGP_CHECK(op->energy(b, w->x, 0.0, w->work));
    double s[GLPGP_NSLOTS];
    GLPGP_CHECK(op->get_scalars(b, s, GLPGP_NSLOTS));
    r->energy = s[GLPGP_S_E];
    GLPGP_CHECK(op->vec_read(b, w->x, r->z));
    if (m->part) GLPGP_CHECK(glpgp_dist_summarize(b, m, r));
    else if (!dir_given) GLPGP_CHECK(glpgp_osc_summarize(m, r));
    else r->zabs_median = zabs_median(r->z, nv, w->scratch); /* for the log line; the caller summarises */
    glpgp_timer_leave(b, prev);
    r->seconds = glpgp_now() - t0;
    if (w->amg) {
        glpgp_amg_info ai;
        glpgp_amg_get_info(w->amg, &ai);
        glpgp_log(GLPGP_LOG_INFO,
                  "%s: multigrid %d levels (%d -> %d nodes), operator complexity %.3f; %s %.3f s "
                  "once + %.3f s in %d updates (%.1f ms each, coarsest inverse %.1f ms)",
                  glpgp_osc_name(k), ai.nlevels, ai.n[0], ai.n[ai.nlevels - 1],
                  ai.operator_complexity, ai.shared ? "instance of the shared structure" : "setup",
                  ai.seconds_structure, ai.seconds_values, ai.updates,
                  ai.updates ? 1e3 * ai.seconds_values / ai.updates : 0.0,
                  ai.updates ? 1e3 * ai.seconds_coarse / ai.updates : 0.0);
        glpgp_amg_destroy(&w->amg);
    }
    glpgp_log(GLPGP_LOG_INFO, "%s: done in %.2f s: median |z| = %.4f, singular +%d/-%d, %d Newton, %ld CG",
              glpgp_osc_name(k), r->seconds, r->zabs_median, r->plus, r->minus, r->newton_iterations,
              r->cg_iterations);
    return GLPGP_OK;
}

/* ---- concurrent oscillators ---------------------------------------------
 * u and v are independent solves with the same field, mesh and schedule: v
 * runs on a clone of the backend (its own queue and buffers, ops->clone) in a
 * second host thread while u runs on b. The result is the sequential one bit
 * for bit (nothing is shared that either writes). What it buys: a CPU device
 * whose multigrid runs its small levels on one core (the fused coarse
 * correction, backends/opencl.c) or a single-threaded backend (reference)
 * leaves the other core idle half the time; a GPU overlaps one thread's
 * kernel launches and host work with the other's. */

/* v's solve in the second thread: the clone, its setup and vectors, the
 * oscillator; the outcome, the error record and the clone's counters. */
typedef struct osc_job {
    const glpgp_mesh *m;
    glpgp_backend *parent;
    const glpgp_system *sys;
    const glpgp_options *o;
    int k;
    const double *wv, *size;
    glpgp_osc_result *r;
    double h;
    const double *eps;
    int nlev;
    int ready;          /* the clone was set up and solved k (outcome st); 0: not
                           started (st: why), the caller solves k on b */
    int *stop;          /* shared with the caller's osc_work (osc_work.stop) */
    glpgp_status st;
    glpgp_error_copy err;
    long n_spmv, n_cg_iter, n_sync, n_launch;
    glpgp_timers tm;    /* the clone's phase accounts */
} osc_job;

static void *osc_job_run(void *arg)
{
    osc_job *j = arg;
    glpgp_backend *c = NULL;
    osc_work w;
    memset(&w, 0, sizeof w);
    glpgp_error_clear();
    const size_t nv = (size_t)j->m->nv;
    glpgp_status st = j->parent->ops->clone(j->parent, &c);
    if (st == GLPGP_OK) {
        c->amg_shared = j->parent->amg_shared; /* the multigrid structure: built once */
        glpgp_timer_reset(c);
        const int prev = glpgp_timer_enter(c, GLPGP_TM_UPLOAD);
        st = c->ops->setup(c, j->sys);
        if (st == GLPGP_OK) st = glpgp_osc_work_create(&w, c, j->o, 2 * nv, nv);
        glpgp_tm_leave(c, j->o->phase_sync, prev);
    }
    if (st == GLPGP_OK) {
        j->ready = 1;
        w.stop = j->stop;
        st = glpgp_solve_oscillator(j->m, &w, j->k, j->wv, j->size, j->r, j->h, j->eps, j->nlev, NULL);
        int none = 0; /* the first failure stops the other oscillator */
        if (st != GLPGP_OK)
            __atomic_compare_exchange_n(j->stop, &none, 1 + j->k, 0, __ATOMIC_RELAXED, __ATOMIC_RELAXED);
    }
    j->st = st;
    if (st != GLPGP_OK) glpgp_error_save(&j->err);
    glpgp_osc_work_free(&w);
    if (c) {
        j->n_spmv = c->n_spmv;
        j->n_cg_iter = c->n_cg_iter;
        j->n_sync = c->n_sync;
        j->n_launch = c->n_launch;
        glpgp_timer_read(c, &j->tm);
    }
    glpgp_backend_destroy(&c);
    glpgp_error_clear();
    return NULL;
}

/* Whether the oscillators run concurrently (o->oscillators): auto when the
 * backend can be cloned and expects a gain (b->overlap: always on the
 * single-threaded reference backend, with the multigrid up to 500k vertices
 * on the OpenCL CPU shape, always on the GPU shape: 1.48x on an H200), the host has two processors or more and, for a
 * host-memory backend, room for a second copy of one oscillator's data in
 * half the available memory (the estimate below, with the multigrid; 1290
 * MiB at 1M vertices, measured 1460); a GPU backend checks its device at the
 * clone's setup. Why not: a warning when asked for, a debug line in auto. */
static int want_concurrent(const glpgp_mesh *m, const glpgp_backend *b, const glpgp_options *o,
                           const glpgp_system *sys)
{
    if (o->oscillators == GLPGP_OSC_SEQUENTIAL) return 0;
    const int asked = o->oscillators == GLPGP_OSC_CONCURRENT;
    char why[256] = "";
    const double mib = 1024.0 * 1024.0;
    /* one oscillator's copy: two 2x2-block matrices and ~20 vectors of 2 nv
     * doubles, the multigrid at half that again, the pattern and gather maps */
    const double need = 1.5 * 8.0 * (8.0 * (double)sys->nnzb + 40.0 * m->nv) +
                        4.0 * (2.0 * (double)sys->nnzb + 15.0 * m->nt + 3.0 * m->nv);
    const unsigned long long avail = glpgp_mem_available();
    if (m->part || !b->ops->clone)
        snprintf(why, sizeof why, "the %s backend runs one oscillator at a time", b->ops->name);
    else if (!asked && b->overlap == GLPGP_OVERLAP_NEVER)
        snprintf(why, sizeof why, "not measured to pay on this backend (--oscillators concurrent tries it)");
    else if (!asked && b->overlap == GLPGP_OVERLAP_AMG && o->precond != GLPGP_PRECOND_AMG)
        snprintf(why, sizeof why, "Jacobi-CG keeps every core busy (two at once measured 0.67-1.0x)");
    else if (!asked && b->overlap == GLPGP_OVERLAP_AMG && m->nv > GLPGP_OVERLAP_AMG_MAX_VERTICES)
        snprintf(why, sizeof why, "above %d vertices the multigrid's per-op levels keep every core busy "
                 "(1M: 0.99x)", GLPGP_OVERLAP_AMG_MAX_VERTICES);
    else if (!asked && glpgp_cpu_count() < 2)
        snprintf(why, sizeof why, "one processor");
    else if (!asked && !b->launch_bound && avail > 0 && 2.0 * need > (double)avail)
        glpgp_snprintf(why, sizeof why, "a second copy needs about %.0f MiB, auto takes it from no more than half "
                 "of the %.0f MiB available", need / mib, (double)avail / mib);
    if (why[0]) {
        glpgp_log(asked ? GLPGP_LOG_WARNING : GLPGP_LOG_DEBUG, "u and v solved one after the other: %s", why);
        return 0;
    }
    return 1;
}

/* Whether --field cross solves the coupled pair: --cross-coupling on, or
 * auto (default) when the representatives have cuts (the cross field has
 * singularities); auto falls back to the uncoupled oscillators, with one
 * warning, on a backend without coupled systems. */
static int use_coupling(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o, const glpgp_result *r)
{
    if (o->cross_coupling == GLPGP_COUPLING_OFF) return 0;
    int cuts = 0;
    for (int t = 0; t < m->nt && !cuts; t++)
        for (int a = 1; a < 3; a++)
            if (glpgp_cross_turn(r->field + 2 * m->tri[3 * t], r->field + 2 * m->tri[3 * t + a]) != 0) cuts = 1;
    if (o->cross_coupling == GLPGP_COUPLING_AUTO && !cuts) return 0;
    if (o->cross_coupling == GLPGP_COUPLING_AUTO && !b->ops->coupled_systems) {
        glpgp_log(GLPGP_LOG_WARNING, "the %s backend does not support the coupled cross-field solve: the "
                                     "oscillators are solved separately and see the cuts (--backend reference "
                                     "couples them)", b->ops->name);
        return 0;
    }
    return 1; /* on: a backend without coupled systems refuses it at setup */
}

/* The coupled pair (z_u, z_v) across the cross field's cuts (solver/coupled.c;
 * declared in internal.h, the surface pipeline's too):
 * one GL solve on the 2 nv-node coupled system, then split per vertex into
 * r->osc[0] (z_u) and r->osc[1] (z_v), each in its vertex's own frame;
 * r->osc[0] carries the coupled solve's statistics (its Newton / CG counts,
 * levels, seconds and quadratic energy E_u + E_v), r->osc[1] none (zeros), so
 * sums over u and v stay right; their singular triangles are the frame
 * windings (glpgp_coupled_windings). */
glpgp_status glpgp_solve_coupled(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o, glpgp_result *r,
                                 const double *size, double h, const double *eps, int nlev, const unsigned char *dn_given,
                                 glpgp_status (*init_free)(osc_work *w, int k, glpgp_osc_result *r), void *init_ctx)
{
    glpgp_status st = GLPGP_OK;
    const int nv = m->nv, nt = m->nt;
    const size_t n4 = (size_t)4 * nv;
    glpgp_coupled *cp = NULL;
    osc_work w;
    glpgp_osc_result co;
    double *wn = NULL, *sn = NULL, *wu = NULL;
    unsigned char *dn = NULL, *du = NULL;
    memset(&w, 0, sizeof w);
    memset(&co, 0, sizeof co);
    int prev = glpgp_timer_enter(b, GLPGP_TM_PATTERN);
    st = glpgp_coupled_create(m, r->field, &cp);
    glpgp_timer_leave(b, prev);
    GLPGP_CHECK(st);
    prev = glpgp_timer_enter(b, GLPGP_TM_UPLOAD);
    st = b->ops->setup(b, cp->sys);
    if (st == GLPGP_OK) st = glpgp_osc_work_create(&w, b, o, n4, (size_t)2 * nv);
    glpgp_tm_leave(b, o->phase_sync, prev);
    if (st != GLPGP_OK) goto done;
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n4, sizeof(double), &co.z), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv, 1, &co.dirichlet), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n4, sizeof(double), &wn), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv, sizeof(double), &wu), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv, 1, &dn), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, 1, &du), done);
    w.init_free = init_free;
    w.init_ctx = init_ctx;
    /* node fields and Dirichlet sets: node (i, s) fixed where its own direction
     * is normal to the boundary (the rule of glpgp_dirichlet_set per family;
     * a surface's: given) */
    glpgp_coupled_node_field(r->field, nv, wn);
    if (dn_given) memcpy(dn, dn_given, (size_t)2 * nv);
    for (int s = 0; s < 2 && !dn_given; s++) {
        for (int i = 0; i < nv; i++) {
            wu[2 * i] = wn[4 * i + 2 * s];
            wu[2 * i + 1] = wn[4 * i + 2 * s + 1];
        }
        glpgp_dirichlet_set(m, wu, du);
        for (int i = 0; i < nv; i++) dn[2 * i + s] = du[i];
    }
    if (size) { /* per-node sizes: node (i, s) takes oscillator s's size at i */
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv, sizeof(double), &sn), done);
        for (int i = 0; i < nv; i++) {
            sn[2 * i] = size[i];
            sn[2 * i + 1] = size[nv + i];
        }
    }
    glpgp_log(GLPGP_LOG_INFO, "coupled u+v: %d nodes, %ld blocks across the cross field's cuts", 2 * nv,
              cp->sys->nnzb);
    GLPGP_CHECK_GOTO(st, glpgp_solve_oscillator(&cp->vm, &w, 3, wn, sn, &co, h, eps, nlev, dn), done);
    /* split per vertex; the statistics go to both */
    for (int s = 0; s < 2; s++) {
        glpgp_osc_result *os = &r->osc[s];
        for (int i = 0; i < nv; i++) {
            os->z[2 * i] = co.z[4 * i + 2 * s];
            os->z[2 * i + 1] = co.z[4 * i + 2 * s + 1];
            os->dirichlet[i] = co.dirichlet[2 * i + s];
        }
        os->n_dirichlet = 0;
        for (int i = 0; i < nv; i++) os->n_dirichlet += os->dirichlet[i];
        if (s == 0) { /* the coupled solve's statistics, once (totals u + v stay right) */
            os->energy = co.energy;
            os->newton_iterations = co.newton_iterations;
            os->cg_iterations = co.cg_iterations;
            os->nlevels = co.nlevels;
            memcpy(os->level, co.level, sizeof co.level);
            os->capped_levels = co.capped_levels;
            os->seconds = co.seconds;
        }
        GLPGP_CHECK_GOTO(st, glpgp_osc_summarize(m, os), done);
    }
    for (int s = 0; s < 2; s++)
        glpgp_coupled_windings(m, r->field, r->osc[0].z, r->osc[1].z, s, r->osc[s].singular, &r->osc[s].plus,
                               &r->osc[s].minus);
    r->coupled = 1;
    glpgp_log(GLPGP_LOG_INFO, "coupled u+v: frame windings u +%d/-%d, v +%d/-%d (%d triangles)", r->osc[0].plus,
              r->osc[0].minus, r->osc[1].plus, r->osc[1].minus, nt);
done:
    glpgp_osc_work_free(&w);
    free(co.z);
    free(co.dirichlet);
    free(wn);
    free(sn);
    free(wu);
    free(dn);
    free(du);
    /* the backend keeps a pointer to cp->sys: glpgp_solve's caller sets it up
     * again before any further use, as after every solve */
    glpgp_coupled_destroy(&cp);
    return st;
}

/* solve_mesh's state: what its phases share */
typedef struct solve_ctx {
    const glpgp_mesh *m;
    glpgp_backend *b;
    const glpgp_options *o;
    glpgp_result *r;
    glpgp_system *sys;
    glpgp_amg_structure *amgs;
    osc_work w;
    double *wv, *size; /* W for u then V (2 x 2 nv); local sizes (2 nv) */
    int uniform;       /* 1: h everywhere (size unused) */
    double h;
} solve_ctx;

/* Layout and upload: the system's pattern, the local resolution check, the
 * backend's setup and driver vectors, the multigrid structure (once for the
 * guiding field, u and v). */
static glpgp_status setup_system(solve_ctx *c)
{
    const glpgp_mesh *m = c->m;
    glpgp_backend *b = c->b;
    const glpgp_options *o = c->o;
    const int nv = m->nv, nt = m->nt;
    int prev = glpgp_timer_enter(b, GLPGP_TM_PATTERN);
    glpgp_status st = glpgp_system_create(m, &c->sys);
    glpgp_timer_leave(b, prev);
    GLPGP_CHECK(st);
    const glpgp_system *sys = c->sys;
    if (m->part)
        glpgp_log(GLPGP_LOG_INFO, "%d vertices, %d triangles (this rank: %d owned + %d ghost vertices, %d triangles, "
                  "%ld blocks), h = %g (%.1f edges per period), backend %s", m->part->nv_global, m->part->nt_global,
                  m->part->nv_owned, nv - m->part->nv_owned, nt, sys->nnzb, c->h, c->h / m->mean_edge, b->ops->name);
    else
        glpgp_log(GLPGP_LOG_INFO, "%d vertices, %d triangles, %ld blocks, h = %g (%.1f edges per period), backend %s",
                  nv, nt, sys->nnzb, c->h, c->h / m->mean_edge, b->ops->name);
    /* local resolution: longest edges against the local size (error /
     * warning); a part: checked on the whole mesh before it was split */
    prev = glpgp_timer_enter(b, GLPGP_TM_SIZE);
    if (!m->part) st = glpgp_size_check_mesh(m, o, c->h);
    glpgp_timer_leave(b, prev);
    GLPGP_CHECK(st);
    const size_t n2 = (size_t)2 * nv;
    prev = glpgp_timer_enter(b, GLPGP_TM_UPLOAD);
    st = b->ops->setup(b, sys);
    if (st == GLPGP_OK) st = glpgp_osc_work_create(&c->w, b, o, n2, (size_t)nv);
    glpgp_tm_leave(b, o->phase_sync, prev);
    GLPGP_CHECK(st);
    /* the multigrid structure, once for the guiding field, u and v */
    if (o->precond == GLPGP_PRECOND_AMG && glpgp_amg_supported(b) && !b->ops->linear_solve) {
        prev = glpgp_timer_enter(b, GLPGP_TM_STRUCTURE);
        glpgp_amg_structure *amgs = NULL;
        if (glpgp_amg_structure_create(sys, o, &amgs) == GLPGP_OK) {
            glpgp_log(GLPGP_LOG_DEBUG, "multigrid structure: %d levels, %d -> %d nodes, operator complexity %.3f, "
                      "%.3f s (shared by the guiding field, u and v)", amgs->L, amgs->lev[0].n,
                      amgs->lev[amgs->L - 1].n, amgs->operator_complexity, amgs->seconds);
            c->amgs = amgs;
            b->amg_shared = amgs;
        } else { /* each hierarchy tries its own (and warns) */
            glpgp_error_clear();
        }
        glpgp_timer_leave(b, prev);
    }
    return glpgp_malloc(2 * n2, sizeof(double), &c->wv);
}

/* The guiding field U (a cross field kept in the result). */
static glpgp_status guiding_field(solve_ctx *c)
{
    const double t1 = glpgp_now();
    const int prev = glpgp_timer_enter(c->b, GLPGP_TM_FIELD);
    glpgp_result *r = c->r;
    glpgp_status st;
    if (c->o->field == GLPGP_FIELD_CROSS) /* keep the cross field in the result */
        st = glpgp_cross_guiding_field(c->m, c->b, c->o, &r->cross, r->field, &r->field_cg_iterations);
    else
        st = glpgp_field_compute(c->m, c->b, c->o, r->field, &r->field_cg_iterations);
    glpgp_tm_leave(c->b, c->o->phase_sync, prev);
    GLPGP_CHECK(st);
    r->seconds_field = glpgp_now() - t1;
    return GLPGP_OK;
}

/* The local size h(x) per oscillator (uniform: NULL, today's arithmetic),
 * with --cross-size the cross field's conformal size for both. */
static glpgp_status local_sizes(solve_ctx *c)
{
    const glpgp_mesh *m = c->m;
    const glpgp_options *o = c->o;
    glpgp_result *r = c->r;
    const int nv = m->nv;
    const size_t n2 = (size_t)2 * nv;
    GLPGP_CHECK(glpgp_malloc(n2, sizeof(double), &c->size));
    double *size = c->size;
    if (m->part) { /* a part: the sizes computed on the whole mesh, see glpgp_field_presolve */
        c->uniform = m->part->size == NULL;
        if (!c->uniform) memcpy(size, m->part->size, n2 * sizeof(double));
    } else {
        GLPGP_CHECK(glpgp_size_compute(m, o, c->h, r->field, size, &c->uniform));
    }
    if (o->field == GLPGP_FIELD_CROSS && o->cross_size != GLPGP_CROSS_SIZE_OFF && r->cross) {
        /* --cross-size: the cross field's conformal size, the smaller of the two, both oscillators */
        double *cs = NULL;
        GLPGP_CHECK(glpgp_malloc((size_t)nv, sizeof(double), &cs));
        const glpgp_status st = glpgp_cross_conformal_size(m, c->b, o, r->cross->w, c->h, cs, &r->field_cg_iterations);
        if (st == GLPGP_OK)
            for (int k = 0; k < 2; k++)
                for (int i = 0; i < nv; i++) size[(size_t)k * nv + i] = fmin(size[(size_t)k * nv + i], cs[i]);
        free(cs);
        GLPGP_CHECK(st);
        c->uniform = 0;
    }
    if (!c->uniform && !m->part) glpgp_size_log(m, size, c->h);
    return GLPGP_OK;
}

/* u and v (apart): v in a second thread on a backend copy when
 * want_concurrent says so, else after u. */
static glpgp_status oscillators(solve_ctx *c, const double *eps, int nlev)
{
    const glpgp_mesh *m = c->m;
    glpgp_backend *b = c->b;
    const glpgp_options *o = c->o;
    glpgp_result *r = c->r;
    const int nv = m->nv;
    const size_t n2 = (size_t)2 * nv;
    double *wv = c->wv, *size = c->uniform ? NULL : c->size;
    /* W = U (k = 0) or V = U rotated by +90 degrees (k = 1) */
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < nv; i++) {
            double ux = r->field[2 * i], uy = r->field[2 * i + 1];
            wv[n2 * k + 2 * i] = k == 0 ? ux : -uy;
            wv[n2 * k + 2 * i + 1] = k == 0 ? uy : ux;
        }
    osc_job job = {.m = m, .parent = b, .sys = c->sys, .o = o, .k = 1, .wv = wv + n2,
                   .size = size ? size + (size_t)nv : NULL, .r = &r->osc[1], .h = c->h, .eps = eps,
                   .nlev = nlev};
    pthread_t th;
    int stop = 0; /* 1 + the oscillator that failed first */
    job.stop = &stop;
    int started = want_concurrent(m, b, o, c->sys) && pthread_create(&th, NULL, osc_job_run, &job) == 0;
    c->w.stop = started ? &stop : NULL;
    glpgp_status st = glpgp_solve_oscillator(m, &c->w, 0, wv, size, &r->osc[0], c->h, eps, nlev, NULL);
    c->w.stop = NULL;
    if (started) {
        if (st != GLPGP_OK) { /* stop v at its next Newton step; the first failure is reported */
            int none = 0;
            __atomic_compare_exchange_n(&stop, &none, 1, 0, __ATOMIC_RELAXED, __ATOMIC_RELAXED);
        }
        pthread_join(th, NULL);
        b->n_spmv += job.n_spmv;
        b->n_cg_iter += job.n_cg_iter;
        b->n_sync += job.n_sync;
        b->n_launch += job.n_launch;
        glpgp_timers_add(&b->tm, &job.tm);
        if (st != GLPGP_OK || (job.ready && job.st != GLPGP_OK)) {
            /* this thread's record is u's; v's replaces it when v failed
             * first (u then only stopped) or alone */
            if (job.ready && job.st != GLPGP_OK && (st == GLPGP_OK || stop == 2)) st = glpgp_error_restore(&job.err);
            glpgp_error_push_trace(__FILE__, __LINE__);
            return st;
        }
        if (!job.ready)
            glpgp_log(o->oscillators == GLPGP_OSC_CONCURRENT ? GLPGP_LOG_WARNING : GLPGP_LOG_INFO,
                      "v solved after u: its backend copy failed (%s)", job.err.msg);
        r->concurrent = job.ready;
        started = job.ready;
    } else if (st != GLPGP_OK) {
        glpgp_error_push_trace(__FILE__, __LINE__);
        return st;
    }
    if (!started)
        GLPGP_CHECK(glpgp_solve_oscillator(m, &c->w, 1, wv + n2, size ? size + (size_t)nv : NULL, &r->osc[1], c->h,
                                           eps, nlev, NULL));
    return GLPGP_OK;
}

/* The whole planar solve on m (in its numbering): setup, guiding field,
 * local sizes, then the coupled pair or u and v apart. */
static glpgp_status solve_mesh(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                               glpgp_result **out)
{
    *out = NULL;
    const double t0 = glpgp_now();
    GLPGP_CHECK(glpgp_options_check_mesh(o, m));
    if (m->part && (o->field == GLPGP_FIELD_FILE || o->field == GLPGP_FIELD_CROSS || o->size_field == GLPGP_SIZE_FILE ||
                    o->size_field == GLPGP_SIZE_FUNC))
        return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "a distributed mesh takes the boundary or radial guiding field and "
                                                 "no per-vertex input file or size function");
    glpgp_options ojac;
    if (o->precond == GLPGP_PRECOND_AMG && !glpgp_amg_supported(b) && !b->ops->linear_solve) {
        /* one warning for the whole solve, then Jacobi everywhere */
        glpgp_log(GLPGP_LOG_WARNING, "the %s backend has no multigrid preconditioner; using Jacobi-PCG",
                  b->ops->name);
        ojac = *o;
        ojac.precond = GLPGP_PRECOND_JACOBI;
        o = &ojac;
    }
    solve_ctx c;
    memset(&c, 0, sizeof c);
    c.m = m;
    c.b = b;
    c.o = o;
    c.uniform = 1;
    c.h = o->size > 0.0 ? o->size : glpgp_default_size(m, o);
    GLPGP_CHECK(glpgp_result_create(m->nv, m->nt, &c.r));
    c.r->size = c.h;
    c.r->backend = b->ops->name;
    glpgp_status st = setup_system(&c);
    if (st == GLPGP_OK) {
        c.r->seconds_setup = glpgp_now() - t0;
        st = guiding_field(&c);
    }
    if (st == GLPGP_OK) {
        const int prev = glpgp_timer_enter(b, GLPGP_TM_SIZE);
        st = local_sizes(&c);
        glpgp_timer_leave(b, prev);
    }
    if (st == GLPGP_OK) {
        double eps[GLPGP_MAX_LEVELS];
        const int nlev = glpgp_eps_schedule(m, o, c.h, eps);
        if (o->field == GLPGP_FIELD_CROSS && c.r->cross && use_coupling(m, b, o, c.r)) {
            st = glpgp_solve_coupled(m, b, o, c.r, c.uniform ? NULL : c.size, c.h, eps, nlev, NULL, NULL, NULL);
            if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
        } else {
            st = oscillators(&c, eps, nlev);
        }
    }
    if (st == GLPGP_OK) c.r->seconds_total = glpgp_now() - t0;
    else glpgp_result_destroy(&c.r);
    glpgp_osc_work_free(&c.w);
    free(c.wv);
    free(c.size);
    if (b->amg_shared == c.amgs) b->amg_shared = NULL;
    glpgp_amg_structure_destroy(&c.amgs);
    glpgp_system_destroy(&c.sys);
    *out = c.r;
    return st;
}

/* glpgp_solve: the vertices renumbered for memory locality (reverse
 * Cuthill-McKee), unless the caller asked for its own numbering, the mesh
 * is a part of a distributed one, a per-vertex input file follows m's
 * numbering, or the field is a cross field (the coupled solve's cuts and
 * per-vertex frames follow the numbering: another, equivalent
 * parametrization, not the same one -- a 3000-vertex disk ended 0.08%
 * apart in energy). Mesh generators such as Gmsh's Delaunay number vertices almost
 * at random (median |i - j| over the edges of a 107k-vertex CAD part: 17k):
 * every matrix row then gathers its neighbours from all over the vectors
 * (that part's whole solve: 1.2-1.5x the CPU, either preconditioner,
 * docs/numerics.md). Triangles keep their order: the result is the same up to
 * rounding (rows and dot products are summed in another order, the
 * multigrid's aggregates differ); it comes back in m's order. */
static glpgp_status solve_ordered(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                  glpgp_result **out);

glpgp_status glpgp_solve(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o, glpgp_result **out)
{
    *out = NULL;
    const long s0 = b->n_sync, l0 = b->n_launch;
    glpgp_timer_reset(b);
    if (m->xyz) /* a surface (glpgp/surfsolve.h) */
        GLPGP_CHECK(glpgp_solve_surface(m, b, o, out));
    else
        GLPGP_CHECK(solve_ordered(m, b, o, out));
    (*out)->host_round_trips = b->n_sync - s0;
    (*out)->kernel_launches = b->n_launch - l0;
    glpgp_timer_read(b, &(*out)->timers);
    return GLPGP_OK;
}

/* An input numbered for locality already: the mean |i - j| over the
 * triangles' edges at most GLPGP_RENUMBER_SPAN sqrt(nv). A row-by-row grid
 * (the generated square: 0.67 sqrt(nv), against 0.89 after reverse
 * Cuthill-McKee) or ring (disk 1.6, RCM 0.7) keeps its order: the renumbering
 * and the result's permutation back cost more than they save (4M square:
 * 2.2 s of a 25 s solve on an H200 host); a Gmsh mesh (10 to 28 sqrt(nv) on
 * data/) is renumbered. */
#define GLPGP_RENUMBER_SPAN 3.0
static int needs_renumbering(const glpgp_mesh *m)
{
    double span = 0.0;
    for (long k = 0; k < 3L * m->nt; k++) {
        const int i = m->tri[k], j = m->tri[k % 3 == 2 ? k - 2 : k + 1];
        span += i > j ? i - j : j - i;
    }
    return span / (3.0 * m->nt) > GLPGP_RENUMBER_SPAN * sqrt((double)m->nv);
}

/* glpgp_solve: in the input's numbering, or renumbered and back */
static glpgp_status solve_ordered(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                  glpgp_result **out)
{
    GLPGP_CHECK(glpgp_options_check_mesh(o, m));
    if (o->vertex_order == GLPGP_ORDER_INPUT || m->part || o->field == GLPGP_FIELD_FILE ||
        o->field == GLPGP_FIELD_CROSS || o->size_field == GLPGP_SIZE_FILE || m->nv < 2)
        return solve_mesh(m, b, o, out);
    if (!needs_renumbering(m)) {
        glpgp_log(GLPGP_LOG_DEBUG, "vertex order kept: already local (mean edge span <= %g sqrt(vertices))",
                  GLPGP_RENUMBER_SPAN);
        return solve_mesh(m, b, o, out);
    }
    glpgp_status st = GLPGP_OK;
    int *new_of_old = NULL;
    glpgp_mesh *mr = NULL;
    const double t0 = glpgp_now();
    int prev = glpgp_timer_enter(b, GLPGP_TM_RENUMBER);
    GLPGP_CHECK(glpgp_malloc((size_t)m->nv, sizeof(int), &new_of_old));
    GLPGP_CHECK_GOTO(st, glpgp_mesh_rcm_order(m, new_of_old), done);
    GLPGP_CHECK_GOTO(st, glpgp_mesh_renumber(m, new_of_old, &mr), done);
    glpgp_timer_leave(b, prev);
    glpgp_log(GLPGP_LOG_DEBUG, "vertices renumbered (reverse Cuthill-McKee) in %.3f s", glpgp_now() - t0);
    GLPGP_CHECK_GOTO(st, solve_mesh(mr, b, o, out), done);
    /* back to m's numbering: a[i] <- a'[new(i)] */
    prev = glpgp_timer_enter(b, GLPGP_TM_RENUMBER);
    st = glpgp_result_permute_vertices(*out, new_of_old);
    glpgp_timer_leave(b, prev);
    if (st != GLPGP_OK) glpgp_result_destroy(out);
    else (*out)->seconds_total = glpgp_now() - t0;
done:
    glpgp_mesh_destroy(&mr);
    free(new_of_old);
    return st;
}
