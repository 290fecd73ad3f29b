/* solver/newton.c: the modified Newton step and one Newton level at fixed eps,
 * written once against the backend table:
 *   g = grad(E + P_eps)(x) (zero on Dirichlet vertices),
 *   (H_E + H~_P(x)) d = -g by PCG to the inexact-Newton tolerance (Jacobi,
 *   or the multigrid preconditioner of solver/amg.c when the state has one),
 *   backtracking (Armijo) on E + P, x <- x + a d.
 * The penalty Hessian H~_P is the variant o->hess; `mixed` tries the exact one
 * near convergence and falls back exact -> mixed -> projected when CG meets
 * negative curvature or d is not a descent direction. */
#include "internal.h"

#include <float.h>
#include <math.h>
#include <string.h>

const char *glpgp_osc_name(int k) { return k == 0 ? "u" : k == 1 ? "v" : "cross"; }

glpgp_status glpgp_newton_step(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *ns,
                               double inv4e2, double F, double gn, glpgp_newton_step_info *info)
{
    const glpgp_backend_ops *op = b->ops;
    double s[GLPGP_NSLOTS];
    memset(info, 0, sizeof *info);
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
        GLPGP_CHECK(op->assemble_newton(b, ns->x, inv4e2, hess));
        /* multigrid: values from the new matrix, frames from x */
        if (ns->amg && !glpgp_amg_try_update(ns->amg, ns->x, "Newton step")) ns->amg = NULL;
        GLPGP_CHECK(op->axpby(b, -1.0, ns->g, 0.0, ns->xt)); /* xt <- -g (rhs) */
        /* inexact Newton: eta = forcing |g|/|g_0|, within [cg_rtol, forcing_max] */
        double eta = fmin(o->forcing_max, fmax(o->cg_rtol, o->forcing * gn / ns->grad0));
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
                              "the Newton matrix is not SPD (folded or degenerate mesh?)",
                              ci.iterations);
        }
        hess = (hess == GLPGP_HESS_EXACT && o->hess == GLPGP_HESS_MIXED) ? GLPGP_HESS_MIXED
                                                                          : GLPGP_HESS_PROJECTED;
        info->fallbacks++;
    }
    /* backtracking: accept x + a d when F(x + a d) <= F + armijo a g.d, up to
     * the rounding level of F (near convergence g.d is below what F resolves) */
    const double noise = 64.0 * DBL_EPSILON * fabs(F);
    double a = 1.0, Ft = F;
    for (int ls_it = 0; ls_it < o->max_backtracks; ls_it++) {
        GLPGP_CHECK(op->copy(b, ns->xt, ns->x));
        GLPGP_CHECK(op->axpby(b, a, ns->d, 1.0, ns->xt)); /* xt <- x + a d */
        GLPGP_CHECK(op->energy(b, ns->xt, inv4e2, ns->work));
        GLPGP_CHECK(op->get_scalars(b, s, GLPGP_NSLOTS));
        Ft = s[GLPGP_S_E] + s[GLPGP_S_P];
        if (isfinite(Ft) && Ft <= F + o->armijo * a * slope + noise) {
            info->accepted = 1;
            break;
        }
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

glpgp_status glpgp_newton_level(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *ns,
                                int k, double eps, double rtol, glpgp_level_stats *ls)
{
    const glpgp_backend_ops *op = b->ops;
    const double inv4e2 = 1.0 / (4.0 * eps * eps);
    double s[GLPGP_NSLOTS];
    ns->grad0 = 0.0;
    ns->near = 0;
    ns->cooldown = 0;
    ls->eps = eps;
    ls->rtol = rtol;
    ls->newton = 0;
    ls->cg = 0;
    ls->capped = 0;
    for (int it = 0;; it++) {
        /* g <- grad(E + P)(x) (zero on Dirichlet vertices); F = E + P */
        GLPGP_CHECK(op->gradient(b, ns->x, inv4e2, ns->g));
        GLPGP_CHECK(op->dot(b, ns->g, ns->g, GLPGP_S_DOT));
        GLPGP_CHECK(op->get_scalars(b, s, GLPGP_NSLOTS));
        const double F = s[GLPGP_S_E] + s[GLPGP_S_P];
        const double gn = sqrt(s[GLPGP_S_DOT]);
        if (!isfinite(F) || !isfinite(gn))
            return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "oscillator %s: energy became non-finite at eps=%g",
                              glpgp_osc_name(k), eps);
        if (it == 0) ls->grad0 = ns->grad0 = gn;
        ls->grad = gn;
        ls->energy = F;
        if (gn <= rtol * ls->grad0 || gn == 0.0) break;
        if (it >= o->newton_max) {
            ls->capped = 1;
            break;
        }
        glpgp_newton_step_info info;
        GLPGP_CHECK(glpgp_newton_step(b, o, ns, inv4e2, F, gn, &info));
        ls->cg += info.cg;
        ls->fallbacks += info.fallbacks;
        ls->cg_capped += info.cg_capped;
        ls->newton++;
        glpgp_log(GLPGP_LOG_INFO, "  %s eps=%.4g newton %3d  |g|=%.3e  E+P=%.10g  cg=%d  step=%g",
                  glpgp_osc_name(k), eps, it + 1, gn, info.energy, info.cg, info.alpha);
        if (!info.accepted) break; /* no descent possible at this precision: level done */
    }
    return GLPGP_OK;
}
