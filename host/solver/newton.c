/* solver/newton.c: the Newton step and one Newton level at fixed eps, written
 * once against the backend table. g = grad(E + P_eps)(x) (zero on Dirichlet
 * vertices), F = E + P_eps.
 *
 * Trust region (o->globalization = GLPGP_GLOBAL_TRUST_REGION, the default, on
 * every backend; the PETSc backend's line search against it: README, "Many
 * ranks"):
 *   H = H_E + exact penalty Hessian at x (indefinite in vortex states);
 *   d ~ argmin g.d + 1/2 d.H d over ||d||_M <= radius by Steihaug-Toint CG
 *     (solver/steihaug.c, inexact-Newton tolerance); M = block Jacobi, or,
 *     with the multigrid (--precond amg) and o->tr_precond AMG (the
 *     default), M^-1 = the symmetric multigrid cycle of solver/amg.c
 *     (glpgp_amg_apply_spd): its hierarchy is built from the projected
 *     Hessian H_proj >= H (PSD; a symmetric PSD inverse on the coarsest level), then H is
 *     assembled, so the cycle is a fixed SPD operator whatever H's inertia,
 *     and the region is measured in the norm of H_proj's multigrid
 *     approximation. The low-frequency directions (vortex drift, the
 *     indefinite direction at a new eps level) are short in that norm: the
 *     region CG finds them in a few iterations where block Jacobi needed
 *     hundreds (square 1M: 118 instead of 1501 CG for the whole solve);
 *     with o->tr_lookahead the CG goes on past the boundary to the Newton
 *     step, which is tried first;
 *   trial points x (+) a d: a polar update outside vortex cores (phase
 *     rotations stay rotations), the straight one inside; a = 1; a step cut
 *     by the region whose full step fails or is poor (rho = (F - F(x (+) d))
 *     / (model decrease) < tr_resolve_rho) is solved again in the region
 *     shrunk by tr_resolve_shrink, on the same Hessian (no new assembly, up
 *     to tr_resolve times: a new direction of the smaller region, where
 *     backtracking along the old one takes a fraction of a direction meant
 *     for the larger region); then backtracking while rho < tr_accept;
 *   radius from rho and the length taken; the level ends at |g| <= rtol |g0|,
 *     at the cap, or when the model decrease falls below the rounding
 *     level of F.
 *   Multigrid (--precond amg), either region: once the region is inactive
 *   (the last step was an interior Steihaug step with rho >= tr_poor, or an
 *   accepted multigrid step; never the first step of a level), the inexact
 *   Newton step by flexible CG with the K-cycle (fewer iterations than the
 *   symmetric cycle) is tried first and kept when its full step has rho >= tr_poor;
 *   otherwise (FCG breakdown, cap, poor rho) the Steihaug step. Measured and
 *   rejected: trying the multigrid step at every step converged to saddle
 *   states (disk 4k, h = 10 edges: +3/-3 singularities, E 32.8 vs 25.4):
 *   without the region CG does not see all negative curvature during vortex
 *   drift.
 * Line search (GLPGP_GLOBAL_LINE_SEARCH, the previous driver):
 *   (H_E + H~_P(x)) d = -g by PCG with the variant o->hess (`mixed` tries
 *   the exact one near convergence and falls back exact -> mixed ->
 *   projected when CG meets negative curvature or d is not a descent
 *   direction), Jacobi or the multigrid (flexible CG), backtracking (Armijo)
 *   on F, x <- x + a d. */
#include "internal.h"
#include "glpgp/util.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void glpgp_tm_leave(glpgp_backend *b, int sync, int prev)
{
    if (sync && b->ops->finish && prev != b->tm_cur) (void)b->ops->finish(b); /* a failure shows at the next call */
    glpgp_timer_leave(b, prev);
}

/* NEWTON <- the Hessian hess at x (ops->assemble_newton), timed as assembly */
static glpgp_status assemble(glpgp_backend *b, const glpgp_options *o, const glpgp_vec *x, double inv4e2, int hess)
{
    const int prev = glpgp_timer_enter(b, GLPGP_TM_ASSEMBLY);
    const glpgp_status st = b->ops->assemble_newton(b, x, inv4e2, hess);
    glpgp_tm_leave(b, o->phase_sync, prev);
    return st;
}

const char *glpgp_osc_name(int k) { return k == 0 ? "u" : k == 1 ? "v" : k == 3 ? "coupled u+v" : "cross"; }

/* Inexact-Newton tolerance of the linear solve at |g| = gn: eta = forcing
 * |g| / |g_0|, but no tighter than the level's target (ns->target, set on
 * the last eps level only) needs -- with a linear residual r of 0.1 target,
 * g + H d = r leaves |g_new| <= 0.1 target + O(|d|^2), so a tighter solve
 * only oversolves the level's last steps -- within [cg_rtol, forcing_max].
 * Measured (default options, 2 cores, the same Newton counts and energies):
 * CG iterations 1344 -> 1281 on the 107k motor part, 1414 -> 1310 on the 64k
 * vortex disk, 119 -> 104 on the 250k square, 17687 -> 16282 with --precond
 * jacobi on the motor. On every level (11-17% fewer CG) it changed the
 * vortex states of radial-field solves: the annulus at h = 0.13 ended with
 * v's energy 142.49 instead of 138.39 (47 instead of 77 Newton steps), the
 * 20k disk at h = 0.05 978.46 instead of 975.15: rejected. With 0.5 target
 * the 1M square needed two more Newton steps. */
/* s <- the slots after op->energy at x (s[GLPGP_S_LIN] = b . x with a
 * linear term); returns F = E + P (- b . x) */
static glpgp_status energy_at(glpgp_backend *b, glpgp_newton_state *ns, const glpgp_vec *x, double inv4e2,
                              double *s, double *F)
{
    GLPGP_CHECK(b->ops->energy(b, x, inv4e2, ns->work));
    if (ns->lin) GLPGP_CHECK(b->ops->dot(b, x, ns->lin, GLPGP_S_LIN));
    GLPGP_CHECK(b->ops->get_scalars(b, s, GLPGP_NSLOTS));
    *F = glpgp_newton_energy(ns, s);
    return GLPGP_OK;
}

glpgp_status glpgp_newton_gradient(glpgp_backend *b, glpgp_newton_state *ns, double inv4e2)
{
    GLPGP_CHECK(b->ops->gradient(b, ns->x, inv4e2, ns->g));
    if (!ns->lin) return GLPGP_OK;
    GLPGP_CHECK(b->ops->axpby(b, -1.0, ns->lin, 1.0, ns->g));
    GLPGP_CHECK(b->ops->dot(b, ns->x, ns->lin, GLPGP_S_LIN));
    return GLPGP_OK;
}

double glpgp_newton_energy(const glpgp_newton_state *ns, const double *s)
{
    return ns->lin ? s[GLPGP_S_E] + s[GLPGP_S_P] - s[GLPGP_S_LIN] : s[GLPGP_S_E] + s[GLPGP_S_P];
}

static double newton_eta(const glpgp_options *o, const glpgp_newton_state *ns, double gn)
{
    double eta = o->forcing * gn / ns->grad0;
    if (ns->target > 0.0 && gn > 0.0) eta = fmax(eta, 0.1 * ns->target / gn);
    return fmin(o->forcing_max, fmax(o->cg_rtol, eta));
}

/* Line-search step (modified Newton; see the file comment). */
static glpgp_status ls_step(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *ns,
                            double inv4e2, double F, double gn, glpgp_newton_step_info *info)
{
    const glpgp_backend_ops *op = b->ops;
    double s[GLPGP_NSLOTS];
    /* (H_E + H~_P) d = -g.  With `mixed`, once the previous step was a full
     * step without fallback and |g| <= exact_switch |g_0|, the exact Hessian
     * is tried first (quadratic convergence around localised vortices). On CG
     * breakdown or a non-descent d the step is redone with the next safer
     * Hessian: exact -> mixed -> projected. */
    int hess = o->hess;
    if (hess == GLPGP_HESS_MIXED && ns->near) hess = GLPGP_HESS_EXACT;
    const int tried_exact = hess != o->hess;
    double slope = 0.0;
    for (;;) {
        GLPGP_CHECK(assemble(b, o, ns->x, inv4e2, hess));
        /* multigrid: values from the new matrix, frames from x */
        if (ns->amg && !glpgp_amg_try_update(ns->amg, ns->x, "Newton step")) ns->amg = NULL;
        GLPGP_CHECK(op->axpby(b, -1.0, ns->g, 0.0, ns->xt)); /* xt <- -g (rhs) */
        const double eta = newton_eta(o, ns, gn);
        glpgp_cg_info ci;
        GLPGP_CHECK(glpgp_linear_solve(b, ns->amg, ns->xt, ns->d, eta, o->cg_max, o->cg_check, &ci));
        info->cg += ci.iterations;
        info->cg_capped += ci.reason == GLPGP_CG_MAXIT;
        const int safe = hess == GLPGP_HESS_PROJECTED || hess == GLPGP_HESS_PAPER;
        if (ci.reason != GLPGP_CG_BREAKDOWN) {
            GLPGP_CHECK(op->dot(b, ns->g, ns->d, GLPGP_S_DOT));
            GLPGP_CHECK(op->get_scalars(b, s, GLPGP_NSLOTS));
            slope = s[GLPGP_S_DOT];
            if (slope < 0.0 || safe) break;
        } else if (safe) {
            return GLPGP_FAIL(GLPGP_ERR_NUMERIC,
                              "CG breakdown at iteration %d with a positive semi-definite Hessian: "
                              "the Newton matrix or its preconditioner is not SPD (a folded or degenerate "
                              "mesh, or a preconditioner option?)",
                              ci.iterations);
        }
        hess = (hess == GLPGP_HESS_EXACT && o->hess == GLPGP_HESS_MIXED) ? GLPGP_HESS_MIXED
                                                                          : GLPGP_HESS_PROJECTED;
        info->fallbacks++;
    }
    /* the full step's model decrease -g.d / 2 below F's rounding level
     * (ns->noise): F cannot judge the step; the full step is taken when F
     * does not rise beyond that level, and the level is done (as the trust
     * region does). Without this rule the Armijo test below, whose noise
     * term is F's own rounding only, accepted random fractions of d until
     * the Newton cap: shape:square:1000000 on 2 PETSc ranks, last level, 50
     * steps at |g| = 2e-8 with F's terms summing 1e6 |z|^2 */
    info->at_noise = -0.5 * slope <= ns->noise;
    /* backtracking: accept x + a d when F(x + a d) <= F + armijo a g.d, up to
     * the rounding level of F (near convergence g.d is below what F resolves) */
    const double noise = 64.0 * DBL_EPSILON * fabs(F);
    double a = 1.0, Ft = F;
    for (int ls_it = 0; ls_it < o->max_backtracks; ls_it++) {
        GLPGP_CHECK(op->copy(b, ns->xt, ns->x));
        GLPGP_CHECK(op->axpby(b, a, ns->d, 1.0, ns->xt)); /* xt <- x + a d */
        GLPGP_CHECK(energy_at(b, ns, ns->xt, inv4e2, s, &Ft));
        if (isfinite(Ft) && (info->at_noise ? Ft <= F + ns->noise : Ft <= F + o->armijo * a * slope + noise)) {
            info->accepted = 1;
            break;
        }
        if (info->at_noise) break; /* the full step only */
        a *= 0.5;
    }
    info->alpha = info->accepted ? a : 0.0;
    info->energy = Ft;
    /* after a failed exact attempt, wait a few steps before the next one */
    if (info->fallbacks > 0 && tried_exact) ns->cooldown = o->exact_cooldown;
    else if (ns->cooldown > 0) ns->cooldown--;
    ns->near = info->accepted && a == 1.0 && info->fallbacks == 0 && ns->cooldown == 0 &&
               gn <= o->exact_switch * ns->grad0;
    if (info->accepted) GLPGP_CHECK(op->copy(b, ns->x, ns->xt)); /* x <- x + a d */
    return GLPGP_OK;
}

/* xt <- x (+) a d, the trust-region trial point (see glpgp_newton_step).
 * retract_zabs 0: straight, xt = x + a d. Else polar, by the backend
 * (ops->trial_point, per vertex glpgp_polar_point of kernels/newton_rows.h:
 * z_i (1 + Re w) e^{i Im w}, w = a d_i / z_i, where |z_i| >= retract_zabs --
 * a phase rotation stays a rotation, where the straight step would lengthen
 * z and meet the quartic penalty -- z_i + a d_i below half of it (vortex
 * cores, where the phase is undefined), blended linearly between; straight
 * also where 1 + Re w <= 0; first-order equal to x + a d). No host round
 * trip. */
static glpgp_status trial_point(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *ns, double a)
{
    const glpgp_backend_ops *op = b->ops;
    if (o->retract_zabs > 0.0) {
        if (!op->trial_point)
            return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "the %s backend has no trial_point op (polar trial points, "
                                                     "retract_zabs > 0)", op->name);
        return op->trial_point(b, ns->x, ns->d, a, o->retract_zabs, ns->xt);
    }
    GLPGP_CHECK(op->copy(b, ns->xt, ns->x));
    return op->axpby(b, a, ns->d, 1.0, ns->xt); /* xt <- x + a d */
}

/* Hessian the trust region uses: exact (the region handles its negative
 * curvature), or the PSD variant the user asked for. */
static int tr_hessian(const glpgp_options *o)
{
    return (o->hess == GLPGP_HESS_PAPER || o->hess == GLPGP_HESS_PROJECTED) ? o->hess : GLPGP_HESS_EXACT;
}

/* Steihaug-Toint direction (see glpgp_newton_step): ns->d and ti.
 * Multigrid region (ns->amg and o->tr_precond AMG): the hierarchy is built
 * (glpgp_amg_update_spd) from the projected Hessian, which is positive
 * semi-definite and bounds the exact one from above, then the trust region's
 * Hessian is assembled: the symmetric cycle is then SPD (glpgp_amg_apply_spd)
 * and its norm the region's. With the projected or paper Hessian one
 * assembly serves both. Block-Jacobi region: the Hessian falls back exact ->
 * mixed -> projected when a diagonal block is indefinite (M is then no
 * norm); a multigrid region that meets r.z <= 0 (not expected) or whose setup
 * fails redoes the step in the block-Jacobi region.
 * tm: the matrix the last call left (tm->set 0: none yet at this x, assemble;
 * 1: a re-solve in a smaller region at the same x, only the Steihaug CG runs,
 * with that call's Hessian and region); set on return. */
typedef struct tr_matrix {
    int set;  /* the NEWTON matrix (and, mg, the region's hierarchy) hold the values below */
    int hess; /* GLPGP_HESS_* assembled */
    int mg;   /* 1: the multigrid region (hierarchy from H_proj), 0: block Jacobi */
} tr_matrix;

static glpgp_status tr_direction(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *ns,
                                 double inv4e2, double eta, glpgp_vec *xb, tr_matrix *tm,
                                 glpgp_trcg_info *ti, glpgp_newton_step_info *info)
{
    const glpgp_backend_ops *op = b->ops;
    int reuse = tm->set;
    int hess = reuse ? tm->hess : tr_hessian(o);
    int mg = reuse ? tm->mg : ns->amg != NULL && o->tr_precond == GLPGP_PRECOND_AMG;
    for (;;) {
        const int psd = hess == GLPGP_HESS_PROJECTED || hess == GLPGP_HESS_PAPER;
        if (reuse) {
            /* re-solve: the matrix and the region of the last call */
        } else if (mg) {
            /* hierarchy from H_proj >= H (values, frames from x, SPD coarse inverse) */
            GLPGP_CHECK(assemble(b, o, ns->x, inv4e2, psd ? hess : GLPGP_HESS_PROJECTED));
            if (!glpgp_amg_try_update_spd(ns->amg, ns->x, "trust-region step")) {
                ns->amg = NULL;
                mg = 0;
            }
            if (mg && !psd) GLPGP_CHECK(assemble(b, o, ns->x, inv4e2, hess));
        }
        if (!mg && !reuse) GLPGP_CHECK(assemble(b, o, ns->x, inv4e2, hess));
        reuse = 0;
        tm->set = 1;
        tm->hess = hess;
        tm->mg = mg;
        /* d ~ argmin m(d) = F + g.d + 1/2 d.H d  subject to ||d||_M <= radius */
        GLPGP_CHECK(op->axpby(b, -1.0, ns->g, 0.0, ns->xt)); /* xt <- -g (rhs) */
        GLPGP_CHECK(glpgp_trcg(b, mg ? ns->amg : NULL, ns->xt, ns->d, ns->radius, eta, o->cg_max, xb, ti));
        info->cg += ti->iterations;
        info->cg_capped += ti->reason == GLPGP_TRCG_MAXIT;
        if (ti->reason != GLPGP_TRCG_PRECOND) return GLPGP_OK;
        if (mg) { /* the cycle was not SPD: block-Jacobi region */
            mg = 0;
            info->fallbacks++;
            continue;
        }
        if (psd) return GLPGP_OK;
        /* an indefinite diagonal block: the block-Jacobi norm is no norm; redo
         * with the Hessian projected in vortex cores, then everywhere */
        hess = hess == GLPGP_HESS_EXACT ? GLPGP_HESS_MIXED : GLPGP_HESS_PROJECTED;
        info->fallbacks++;
    }
}

/* Multigrid candidate (ns->amg, only while the region is inactive, see
 * tr_step): d <- the inexact Newton step H d = -g of the trust region's
 * Hessian by flexible CG with the multigrid preconditioner, to the same
 * tolerance eta. *ok = 0 when there is none (FCG met p.Ap <= 0, i.e.
 * negative curvature or an unusable preconditioner, or stopped at its cap).
 * A multigrid setup failure drops ns->amg (one warning, Jacobi from then
 * on). */
static glpgp_status tr_amg_direction(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *ns,
                                     double inv4e2, double eta, int *ok, glpgp_newton_step_info *info)
{
    const glpgp_backend_ops *op = b->ops;
    *ok = 0;
    GLPGP_CHECK(assemble(b, o, ns->x, inv4e2, tr_hessian(o)));
    /* multigrid: values from the new matrix, frames from x */
    if (ns->amg && !glpgp_amg_try_update(ns->amg, ns->x, "Newton step")) {
        ns->amg = NULL;
        return GLPGP_OK;
    }
    GLPGP_CHECK(op->axpby(b, -1.0, ns->g, 0.0, ns->xt)); /* xt <- -g (rhs) */
    glpgp_cg_info ci;
    if (ns->amg) {
        GLPGP_CHECK(glpgp_fcg(ns->amg, ns->xt, ns->d, eta, o->cg_max, &ci));
    } else {
        /* the backend's own multigrid solver (PETSc: KSPCG + GAMG with the
         * near null space [z, iz]); a breakdown (indefinite H) or the cap
         * rejects the candidate like FCG's */
        GLPGP_CHECK(glpgp_linear_solve(b, NULL, ns->xt, ns->d, eta, o->cg_max, o->cg_check, &ci));
    }
    info->cg += ci.iterations;
    info->cg_capped += ci.reason == GLPGP_CG_MAXIT;
    *ok = ci.reason == GLPGP_CG_CONVERGED;
    return GLPGP_OK;
}

/* Trust-region step (see glpgp_newton_step). */
/* One direction's trial of the trust region: its model and trial points. */
typedef struct tr_trial {
    double gd, dhd;  /* g.d, d.H d */
    double step;     /* |d|_M of a Steihaug step (0: a multigrid step) */
    double a, Fa;    /* the last trial point's fraction of d and energy */
    double rho;      /* actual / predicted decrease there */
    int take;        /* the point is accepted */
    int at_noise;    /* the predicted decrease is below F's rounding level */
    int resolve;     /* the cut step is to be solved again in a smaller region */
} tr_trial;

/* Trial points x (+) a d: the full step, then backtracking along d with
 * a from the minimiser of the quadratic through F, a g.d and F(x (+) a d),
 * clamped to [tr_shrink_min, tr_shrink] times the previous a.
 * rho = (F - F(x (+) a d)) / pred(a); a point is taken when rho >=
 * tr_accept, or, when pred(a) is below the rounding level of F (where
 * rho means nothing), when F does not visibly rise; the level then
 * ends (converged to the rounding level).
 * The look-ahead candidate gets the full step only.
 * A Steihaug step cut by the region (boundary, negative curvature)
 * whose full step fails or is poor (rho < tr_resolve_rho) is solved
 * again in the region shrunk by tr_resolve_shrink (at most
 * tr_resolve times per Newton step, on the same matrix) before
 * backtracking: backtracking along d takes a fraction of a direction
 * meant for the larger region (measured: the region's full step
 * fails at twice the length of the last good one, the backtrack
 * then lands at 0.2-0.4 of it and the radius oscillates). */
static glpgp_status tr_trials(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *ns, double inv4e2,
                              double F, int candidate, int cut, const glpgp_newton_step_info *info, tr_trial *t)
{
    double s[GLPGP_NSLOTS];
    t->a = 1.0;
    t->Fa = F;
    t->rho = -HUGE_VAL;
    t->take = t->at_noise = t->resolve = 0;
    const int maxbt = candidate ? 0 : o->max_backtracks;
    for (int j = 0; j <= maxbt; j++) {
        if (j > 0) {
            const double c = isfinite(t->Fa) ? (t->Fa - F - t->a * t->gd) / (t->a * t->a) : HUGE_VAL;
            double an = c > 0.0 ? -t->gd / (2.0 * c) : o->tr_shrink * t->a;
            t->a = fmax(o->tr_shrink_min * t->a, fmin(o->tr_shrink * t->a, an));
        }
        GLPGP_CHECK(trial_point(b, o, ns, t->a));
        GLPGP_CHECK(energy_at(b, ns, ns->xt, inv4e2, s, &t->Fa));
        const double pred = -(t->a * t->gd + 0.5 * t->a * t->a * t->dhd);
        t->at_noise = pred <= ns->noise;
        t->rho = pred > 0.0 && isfinite(t->Fa) ? (F - t->Fa) / pred : -HUGE_VAL;
        t->take = isfinite(t->Fa) && (t->at_noise ? F - t->Fa >= -ns->noise : t->rho >= o->tr_accept);
        if (j == 0 && cut && t->step > 0.0 && !t->at_noise && info->resolves < o->tr_resolve &&
            (!t->take || t->rho < o->tr_resolve_rho)) {
            t->resolve = 1;
            break;
        }
        if (t->take || t->at_noise) break;
    }
    return GLPGP_OK;
}

/* The region after a Steihaug step (not a candidate): a backtracked step
 * sets it to the length taken (tr_grow times that after a good model, rho >
 * tr_good); after a full step, shrink it after a poor model (rho < tr_poor;
 * to a* |d|, a* as in tr_trials within [tr_shrink_min, tr_shrink]), grow it
 * by tr_grow after a good step (rho > tr_good) that the region cut, unless
 * the region was shrunk in this step (re-solved: the larger one just
 * failed); the first region is tr_grow |d| of the first (unbounded) step
 * taken. */
static void tr_update_radius(const glpgp_options *o, glpgp_newton_state *ns, const tr_trial *t, double F, int cut,
                             int resolves)
{
    if (!t->take || t->at_noise) return;
    if (t->a < 1.0) {
        ns->radius = (t->rho > o->tr_good ? o->tr_grow : 1.0) * t->a * t->step;
    } else if (t->rho < o->tr_poor) {
        const double c = t->Fa - F - t->gd;
        double as = c > 0.0 ? -t->gd / (2.0 * c) : o->tr_shrink;
        ns->radius = fmax(o->tr_shrink_min, fmin(o->tr_shrink, as)) * t->step;
    } else if (ns->radius <= 0.0) {
        ns->radius = o->tr_grow * t->step;
    } else if (t->rho > o->tr_good && cut && resolves == 0) {
        ns->radius *= o->tr_grow;
    }
}

static glpgp_status tr_step(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *ns,
                            double inv4e2, double F, double gn, glpgp_newton_step_info *info)
{
    const glpgp_backend_ops *op = b->ops;
    double s[GLPGP_NSLOTS];
    glpgp_trcg_info ti;
    memset(&ti, 0, sizeof ti);
    glpgp_status st = GLPGP_OK;
    const double eta = newton_eta(o, ns, gn);
    /* look-ahead (tr_lookahead): where the Steihaug path leaves the region,
     * CG goes on to the inexact Newton step, which is tried first and kept
     * when its full step has rho >= tr_poor; else the boundary point */
    glpgp_vec *xb = NULL;
    if (o->tr_lookahead && ns->radius > 0.0 && isfinite(ns->radius))
        GLPGP_CHECK_GOTO(st, op->vec_create(b, (size_t)2 * b->sys->nv, &xb), done);
    /* multigrid (ns->amg): while the region is inactive (the last step was
     * an interior Steihaug step, i.e. the plain inexact Newton step, with a
     * good model, or an accepted multigrid step), the inexact Newton step by
     * flexible CG with the multigrid is tried first, kept when its full
     * step has rho >= tr_poor; else the Steihaug step */
    /* the candidate's multigrid: glpgp's (ns->amg) or the backend's linear
     * solver (PETSc's GAMG, b->ops->linear_solve) */
    int multigrid = (ns->amg != NULL || b->ops->linear_solve != NULL) && ns->inside, candidate = 0;
    tr_trial t;
    memset(&t, 0, sizeof t);
    t.a = 1.0;
    t.Fa = F;
    t.rho = -HUGE_VAL;
    tr_matrix tm = {0, 0, 0}; /* what the NEWTON matrix holds for tr_direction */
    for (;;) {
        if (multigrid) {
            GLPGP_CHECK_GOTO(st, tr_amg_direction(b, o, ns, inv4e2, eta, &multigrid, info), done);
            tm.set = 0; /* the trust region's Hessian and hierarchy are assembled anew */
            if (!multigrid) info->amg_rejected++;
            candidate = multigrid;
        }
        if (multigrid) {
            /* d from the multigrid */
        } else if (candidate) {
            /* the look-ahead Newton step failed: d <- the boundary point */
            GLPGP_CHECK_GOTO(st, op->copy(b, ns->d, xb), done);
            ti.reason = GLPGP_TRCG_BOUNDARY;
            ti.norm = ns->radius;
            candidate = 0;
        } else {
            GLPGP_CHECK_GOTO(st, tr_direction(b, o, ns, inv4e2, eta, xb, &tm, &ti, info), done);
            if (ti.crossed && ti.reason == GLPGP_TRCG_CONVERGED) {
                candidate = 1;
            } else if (ti.crossed) { /* negative curvature or the cap beyond the region */
                GLPGP_CHECK_GOTO(st, op->copy(b, ns->d, xb), done);
                ti.reason = GLPGP_TRCG_BOUNDARY;
                ti.norm = ns->radius;
            }
        }
        /* model along d:  m(a d) - F = a g.d + a^2/2 d.H d;  pred(a) = -(that) */
        GLPGP_CHECK_GOTO(st, op->spmv(b, GLPGP_MAT_NEWTON, ns->d, ns->work), done);
        GLPGP_CHECK_GOTO(st, op->dot(b, ns->g, ns->d, GLPGP_S_DOT), done);
        GLPGP_CHECK_GOTO(st, op->dot(b, ns->d, ns->work, GLPGP_S_DOT2), done);
        GLPGP_CHECK_GOTO(st, op->get_scalars(b, s, GLPGP_NSLOTS), done);
        t.gd = s[GLPGP_S_DOT];
        t.dhd = s[GLPGP_S_DOT2];
        t.step = multigrid ? 0.0 : ti.norm;
        const int cut = !candidate && (ti.reason == GLPGP_TRCG_BOUNDARY || ti.reason == GLPGP_TRCG_NEGCURV);
        GLPGP_CHECK_GOTO(st, tr_trials(b, o, ns, inv4e2, F, candidate, cut, info, &t), done);
        if (t.resolve) {
            /* radius <- tr_resolve_shrink |d|_M;  d <- Steihaug step in it */
            ns->radius = o->tr_resolve_shrink * t.step;
            info->resolves++;
            continue;
        }
        if (!candidate) break;
        /* a candidate: kept when the model held (rho >= tr_poor) or at the
         * rounding level */
        if (t.take && (t.at_noise || t.rho >= o->tr_poor)) break;
        if (multigrid) {
            multigrid = candidate = 0;
            info->amg_rejected++;
        } else {
            info->lookahead_rejected++;
        }
    }
    info->amg_step = multigrid;
    info->lookahead_step = candidate && !multigrid;
    /* region inactive: an accepted multigrid step, or a full interior
     * Steihaug step with a good model */
    ns->inside = t.take && (multigrid || (!candidate && ti.reason == GLPGP_TRCG_CONVERGED && t.a == 1.0 &&
                                          (t.at_noise || t.rho >= o->tr_poor)));
    if (candidate) {
        /* a Newton step longer than the region held: the region grows to it
         * (the multigrid step's M-length is unknown: the region stays) */
        if (!multigrid && t.take && !t.at_noise) ns->radius = fmax(ns->radius, t.step);
    } else {
        tr_update_radius(o, ns, &t, F, ti.reason == GLPGP_TRCG_BOUNDARY || ti.reason == GLPGP_TRCG_NEGCURV,
                         info->resolves);
    }
    info->accepted = t.take;
    info->at_noise = t.at_noise;
    info->alpha = t.take ? t.a : 0.0;
    info->energy = t.take ? t.Fa : F;
    info->rho = t.rho;
    info->step = t.step;
    info->radius = ns->radius;
    info->reason = (int)ti.reason;
    if (t.take) GLPGP_CHECK_GOTO(st, op->copy(b, ns->x, ns->xt), done); /* x <- x (+) a d */
done:
    op->vec_destroy(b, &xb);
    return st;
}

glpgp_status glpgp_newton_step(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *ns,
                               double inv4e2, double F, double gn, glpgp_newton_step_info *info)
{
    memset(info, 0, sizeof *info);
    if (o->globalization == GLPGP_GLOBAL_TRUST_REGION) return tr_step(b, o, ns, inv4e2, F, gn, info);
    return ls_step(b, o, ns, inv4e2, F, gn, info);
}

static glpgp_status newton_level(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *ns, int k,
                                 double eps, double rtol, glpgp_level_stats *ls);

/* the level's own work (gradients, energies, trial points) is timed as
 * energies; assembly, multigrid values and linear solves as theirs */
glpgp_status glpgp_newton_level(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *ns,
                                int k, double eps, double rtol, glpgp_level_stats *ls)
{
    const int prev = glpgp_timer_enter(b, GLPGP_TM_ENERGY);
    const glpgp_status st = newton_level(b, o, ns, k, eps, rtol, ls);
    glpgp_timer_leave(b, prev);
    return st;
}

static glpgp_status newton_level(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *ns, int k,
                                 double eps, double rtol, glpgp_level_stats *ls)
{
    const glpgp_backend_ops *op = b->ops;
    const double inv4e2 = 1.0 / (4.0 * eps * eps);
    const int tr = o->globalization == GLPGP_GLOBAL_TRUST_REGION;
    double s[GLPGP_NSLOTS];
    ns->grad0 = 0.0;
    ns->near = 0;
    ns->cooldown = 0;
    ls->eps = eps;
    ls->rtol = rtol;
    ls->newton = 0;
    ls->cg = 0;
    ls->capped = 0;
    ls->at_noise = 0;
    ls->stalled = 0;
    double fhist[3] = {0.0, 0.0, 0.0}; /* E + P at the start of the last 3 steps (the stall test) */
    for (int it = 0;; it++) {
        /* g <- grad(E + P)(x) (zero on Dirichlet vertices); F = E + P */
        GLPGP_CHECK(glpgp_newton_gradient(b, ns, inv4e2));
        GLPGP_CHECK(op->dot(b, ns->g, ns->g, GLPGP_S_DOT));
        GLPGP_CHECK(op->dot(b, ns->x, ns->x, GLPGP_S_DOT2));
        GLPGP_CHECK(op->get_scalars(b, s, GLPGP_NSLOTS));
        const double F = glpgp_newton_energy(ns, s);
        const double gn = sqrt(s[GLPGP_S_DOT]);
        if (!isfinite(F) || !isfinite(gn))
            return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "oscillator %s: energy became non-finite at eps=%g",
                              glpgp_osc_name(k), eps);
        /* rounding level of F: its terms are about |z_i|^2 per vertex, so
         * 64 eps (|F| + |x|^2) (64 eps |F| misses the cancellation when the
         * energy is small against its terms) */
        ns->noise = 64.0 * DBL_EPSILON * (fabs(F) + s[GLPGP_S_DOT2]);
        if (it == 0) {
            ls->grad0 = ns->grad0 = gn;
            /* the floor of newton_eta on the last level only (rtol = newton_rtol):
             * on the levels before it the looser last steps moved vortex states
             * (radial annulus: v's energy 138.39 -> 142.49) */
            ns->target = rtol <= o->newton_rtol ? rtol * gn : 0.0;
            /* ns->inside carries over from the previous eps level: a level
             * that ended on a Newton step (the region inactive) starts with
             * the multigrid candidate, one NEWTON assembly instead of the
             * Steihaug step's two (projected for the hierarchy, then exact);
             * a rejected candidate falls back to the Steihaug step. Same
             * Newton steps and final energies (one more step on the 250k
             * square), measured alternately on an idle machine (solve s):
             * shape:square:1000000 OpenCL 29.0, 28.1 -> 27.3, 26.6, reference
             * 40.4 -> 37.6; shape:disk:64000 --size 0.07734642 13.9 -> 11.8;
             * the 107k motor part 19.6, 20.0 -> 21.4, 19.9 (noise); square
             * 250k 17 -> 18 Newton, 5.9 -> 6.3 s (docs/numerics.md) */
        }
        ls->grad = gn;
        ls->energy = F;
        if (gn <= rtol * ls->grad0 || gn == 0.0) break;
        if (ns->stop && __atomic_load_n(ns->stop, __ATOMIC_RELAXED))
            return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "%s: stopped (the other oscillator failed)", glpgp_osc_name(k));
        if (o->cancel && o->cancel(o->cancel_ctx))
            return GLPGP_FAIL(GLPGP_ERR_CANCELLED, "%s: cancelled at eps=%g, Newton step %d", glpgp_osc_name(k), eps,
                              it + 1);
        if (it >= o->newton_max) {
            ls->capped = 1;
            break;
        }
        glpgp_newton_step_info info;
        fhist[it % 3] = F;
        GLPGP_CHECK(glpgp_newton_step(b, o, ns, inv4e2, F, gn, &info));
        ls->cg += info.cg;
        ls->fallbacks += info.fallbacks;
        ls->backtracked += info.accepted && info.alpha < 1.0;
        ls->cg_capped += info.cg_capped;
        ls->newton++;
        if (tr) {
            /* |d|: the Steihaug step's length in its preconditioner's norm
             * (a multigrid step's is not computed: "-") */
            char dn[32] = "-";
            if (!info.amg_step) glpgp_snprintf(dn, sizeof dn, "%.3g", info.step);
            glpgp_log(GLPGP_LOG_INFO,
                      "  %s eps=%.4g newton %3d  |g|=%.3e  E+P=%.10g  cg=%d  |d|=%s  a=%.3g  rho=%.3g  "
                      "radius=%.3g  re-solved %d  %s%s%s",
                      glpgp_osc_name(k), eps, it + 1, gn, info.energy, info.cg, dn, info.alpha,
                      info.rho, info.radius, info.resolves,
                      info.amg_step         ? "multigrid"
                      : info.lookahead_step ? "look-ahead"
                                            : glpgp_trcg_reason_name((glpgp_trcg_reason)info.reason),
                      info.amg_rejected ? "  (multigrid step rejected)" : "",
                      info.at_noise ? "  (at the rounding level)" : "");
        } else
            glpgp_log(GLPGP_LOG_INFO, "  %s eps=%.4g newton %3d  |g|=%.3e  E+P=%.10g  cg=%d  step=%g%s",
                      glpgp_osc_name(k), eps, it + 1, gn, info.energy, info.cg, info.alpha,
                      info.at_noise ? "  (at the rounding level)" : "");
        /* no descent possible at this precision (the line search failed, or
         * the trust-region model promises less than the rounding level of F):
         * level done */
        if (!info.accepted || info.at_noise) {
            ls->at_noise = 1;
            break;
        }
        /* the stall test (ns->ftol > 0), from GLPGP_STALL_STEPS steps on: E + P
         * fell by at most ftol |E + P| over the last 3 steps (fhist[(it + 1) % 3]:
         * the start of step it - 2) */
        if (ns->ftol > 0.0 && it + 1 >= GLPGP_STALL_STEPS &&
            fhist[(it + 1) % 3] - info.energy <= ns->ftol * fabs(info.energy)) {
            ls->stalled = 1;
            ls->energy = info.energy;
            GLPGP_CHECK(glpgp_newton_gradient(b, ns, inv4e2));
            GLPGP_CHECK(op->dot(b, ns->g, ns->g, GLPGP_S_DOT));
            GLPGP_CHECK(op->get_scalars(b, s, GLPGP_NSLOTS));
            ls->grad = sqrt(s[GLPGP_S_DOT]);
            break;
        }
    }
    return GLPGP_OK;
}
