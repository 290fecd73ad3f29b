/* solver/steihaug.c: the truncated (Steihaug-Toint) preconditioned conjugate
 * gradient of the trust-region Newton step, written once against the
 * backend table: with the same fused Jacobi ops as the project's CG
 * (solver/cg.c: cg_precond, cg_spmv_dot, cg_update, cg_direction), or with
 * the multigrid ops (amg_*: the symmetric multigrid cycle of solver/amg.c as the
 * preconditioner), so it works unchanged on every backend.
 *
 * It approximately minimises the model m(d) = -b.d + 1/2 d.A d (A = the
 * backend's NEWTON matrix, b = rhs) inside the trust region ||d||_M <= radius,
 * M = the block-Jacobi preconditioner (the 2x2 diagonal blocks of A, whose
 * inverses DINV the backend holds), or M = B^-1 with B the symmetric multigrid cycle
 * glpgp_amg_apply_spd (a fixed SPD operator when its hierarchy was built from
 * a positive semi-definite Hessian above A: glpgp_amg_update_spd; the
 * multigrid path needs only B r, never M itself: the recurrences below use
 * r.z). In the multigrid norm the low-frequency directions (the phase mode,
 * vortex drift) are short, so the region and the negative-curvature test see
 * them in the first few iterations. Unlike glpgp_cg it does not assume A SPD:
 *   - p.Ap <= 0 (negative curvature): follow p to the boundary, stop;
 *   - the next iterate would leave the region: stop on the boundary;
 *   - |r| <= rtol |b|: the inexact Newton step, inside the region.
 * Look-ahead (xb given): where the path leaves the region, the boundary
 * point (the Steihaug step) is saved in xb and CG goes on without the
 * region; x is then the inexact Newton step when the run converges with
 * positive curvature all along (info->crossed: the caller tries x first and
 * falls back to xb), and negative curvature or the cap after the crossing
 * stop it (xb is the step). Before the crossing the run is the same.
 * Every iterate lowers the model (Steihaug 1983; Conn, Gould, Toint,
 * Trust-Region Methods, alg. 7.5.1), as long as M is SPD; when it is not
 * (r.z <= 0: an indefinite diagonal block) the run stops with
 * GLPGP_TRCG_PRECOND and the caller uses a safer Hessian.
 *
 * The M-norms are tracked on the host by the recurrences (no extra vector
 * pass): with d_0 = 0, p_0 = z_0,
 *   ||d_{k+1}||^2 = ||d_k||^2 + 2 a_k (d_k.M p_k) + a_k^2 (p_k.M p_k)
 *   d_{k+1}.M p_{k+1} = b_k (d_k.M p_k + a_k p_k.M p_k)
 *   p_{k+1}.M p_{k+1} = r_{k+1}.z_{k+1} + b_k^2 (p_k.M p_k)
 * (a_k = r.z / p.Ap and b_k = (r.z)_{k+1} / (r.z)_k, the same divisions the
 * device does). The decisions need p.Ap before the update, so the scalars
 * are read back once per iteration, after the spmv (one host round trip per
 * iteration, where glpgp_cg reads every `check` iterations; the convergence
 * test then sees |r_k| one spmv late). */
#include "internal.h"

#include <math.h>

/* The preconditioned-CG pieces of one run: the backend's fused Jacobi ops
 * (scalars in s[]: GLPGP_S_RZ0/RZ1, GLPGP_S_PQ, GLPGP_S_RR), or, mg not
 * NULL, the multigrid ops (scalars in the AMG registers t[]: t[rz] = r.z,
 * t[rz + 1] = r.r for rz = T_RZ0 or T_RZ1, t[T_PQ] = p.Ap). */
typedef struct pcg {
    glpgp_backend *b;
    glpgp_amg *mg;
    int bad; /* the multigrid's coarse operator failed (t[GLPGP_AMG_SLOT_STATUS]) */
} pcg;

enum { T_RZ0 = 0, T_RZ1 = 2, T_PQ = 4, T_N = 8 };

static glpgp_amg_coef coef(int num, int den, double sign)
{
    glpgp_amg_coef c = {num, den, sign};
    return c;
}

/* z <- M^-1 r;  r.z -> slot rz;  r.r */
static glpgp_status pc_precond(const pcg *c, const glpgp_vec *r, glpgp_vec *z, int rz)
{
    if (!c->mg) return c->b->ops->cg_precond(c->b, r, z, rz);
    GLPGP_CHECK(glpgp_amg_apply_spd(c->mg, r, z));
    return c->b->ops->amg_dots(c->b, r, z, r, rz); /* t[rz] <- r.z;  t[rz+1] <- r.r */
}

/* q <- A p;  p.q */
static glpgp_status pc_spmv_dot(const pcg *c, const glpgp_vec *p, glpgp_vec *q)
{
    if (!c->mg) return c->b->ops->cg_spmv_dot(c->b, p, q);
    return c->b->ops->amg_spmv_dots(c->b, 0, p, q, NULL, NULL, T_PQ);
}

/* alpha = r.z / p.q;  x += alpha p;  r -= alpha q;  z <- M^-1 r;  r.z -> rzn */
static glpgp_status pc_update(const pcg *c, glpgp_vec *x, glpgp_vec *r, const glpgp_vec *p,
                              const glpgp_vec *q, glpgp_vec *z, int rz, int rzn)
{
    glpgp_backend *b = c->b;
    if (!c->mg) return b->ops->cg_update(b, x, r, p, q, z, rz, rzn);
    const glpgp_amg_coef one = {-1, -1, 1.0};
    GLPGP_CHECK(b->ops->amg_axpby(b, coef(rz, T_PQ, 1.0), p, one, x));
    GLPGP_CHECK(b->ops->amg_axpby(b, coef(rz, T_PQ, -1.0), q, one, r));
    return pc_precond(c, r, z, rzn);
}

/* p <- z + (r.z_new / r.z) p */
static glpgp_status pc_direction(const pcg *c, glpgp_vec *p, const glpgp_vec *z, int rzn, int rz)
{
    glpgp_backend *b = c->b;
    if (!c->mg) return b->ops->cg_direction(b, p, z, rzn, rz);
    const glpgp_amg_coef one = {-1, -1, 1.0};
    return b->ops->amg_axpby(b, one, z, coef(rzn, rz, 1.0), p);
}

/* read the scalars: *rr = r.r, *pq = p.Ap, *rzv = r.z of slot rz */
static glpgp_status pc_scalars(pcg *c, int rz, double *rr, double *pq, double *rzv)
{
    glpgp_backend *b = c->b;
    if (!c->mg) {
        double s[GLPGP_NSLOTS];
        GLPGP_CHECK(b->ops->get_scalars(b, s, GLPGP_NSLOTS));
        *rr = s[GLPGP_S_RR];
        *pq = s[GLPGP_S_PQ];
        *rzv = s[rz];
    } else {
        double t[T_N];
        GLPGP_CHECK(b->ops->amg_get_scalars(b, t, T_N));
        *rr = t[rz + 1];
        *pq = t[T_PQ];
        *rzv = t[rz];
        c->bad = t[GLPGP_AMG_SLOT_STATUS] != 0.0;
    }
    b->n_sync++;
    return GLPGP_OK;
}

/* tau >= 0 with ||d + tau p||_M = radius, from dd = ||d||^2, dp = d.Mp,
 * pp = ||p||^2 (dd <= radius^2): the positive root of
 * pp tau^2 + 2 dp tau + dd - radius^2 = 0, written without cancellation. */
static double to_boundary(double dd, double dp, double pp, double radius)
{
    const double c = fmax(0.0, radius * radius - dd);
    const double disc = sqrt(dp * dp + pp * c);
    if (!(pp > 0.0)) return 0.0;
    return dp > 0.0 ? c / (dp + disc) : (disc - dp) / pp;
}

const char *glpgp_trcg_reason_name(glpgp_trcg_reason r)
{
    switch (r) {
    case GLPGP_TRCG_CONVERGED: return "converged";
    case GLPGP_TRCG_MAXIT: return "cap";
    case GLPGP_TRCG_BOUNDARY: return "boundary";
    case GLPGP_TRCG_NEGCURV: return "negative curvature";
    case GLPGP_TRCG_PRECOND: return "indefinite preconditioner";
    }
    return "?";
}

static glpgp_status trcg_run(glpgp_backend *b, glpgp_amg *mg, const glpgp_vec *rhs, glpgp_vec *x, double radius,
                             double rtol, int maxit, glpgp_vec *xb, glpgp_trcg_info *info);

/* timed as a linear solve (glpgp/timers.h) */
glpgp_status glpgp_trcg(glpgp_backend *b, glpgp_amg *mg, const glpgp_vec *rhs, glpgp_vec *x,
                        double radius, double rtol, int maxit, glpgp_vec *xb, glpgp_trcg_info *info)
{
    const int prev = glpgp_timer_enter(b, GLPGP_TM_LINEAR);
    const glpgp_status st = trcg_run(b, mg, rhs, x, radius, rtol, maxit, xb, info);
    glpgp_timer_leave(b, prev);
    return st;
}

static glpgp_status trcg_run(glpgp_backend *b, glpgp_amg *mg, const glpgp_vec *rhs, glpgp_vec *x, double radius,
                             double rtol, int maxit, glpgp_vec *xb, glpgp_trcg_info *info)
{
    pcg pc = {b, mg, 0};
    const glpgp_backend_ops *o = b->ops;
    const size_t n = (size_t)2 * b->sys->nv;
    int bounded = radius > 0.0 && isfinite(radius);
    glpgp_status st = GLPGP_OK;
    glpgp_vec *r = NULL, *z = NULL, *p = NULL, *q = NULL;
    double rr = 0.0, pq = 0.0, rzv = 0.0;
    int k = 0, nspmv = 0;
    info->iterations = 0;
    info->relres = 0.0;
    info->norm = 0.0;
    info->reason = GLPGP_TRCG_CONVERGED;
    info->crossed = 0;
    GLPGP_CHECK_GOTO(st, glpgp_backend_scratch(b, 4, n, &r), done);
    GLPGP_CHECK_GOTO(st, glpgp_backend_scratch(b, 5, n, &z), done);
    GLPGP_CHECK_GOTO(st, glpgp_backend_scratch(b, 6, n, &p), done);
    GLPGP_CHECK_GOTO(st, glpgp_backend_scratch(b, 7, n, &q), done);

    /* x <- 0;  r <- b;  z <- M^-1 r;  p <- z */
    GLPGP_CHECK_GOTO(st, o->axpby(b, 0.0, x, 0.0, x), done);
    GLPGP_CHECK_GOTO(st, o->copy(b, r, rhs), done);
    int rz = mg ? T_RZ0 : GLPGP_S_RZ0, rzn = mg ? T_RZ1 : GLPGP_S_RZ1;
    GLPGP_CHECK_GOTO(st, pc_precond(&pc, r, z, rz), done);
    GLPGP_CHECK_GOTO(st, o->copy(b, p, z), done);
    GLPGP_CHECK_GOTO(st, pc_scalars(&pc, rz, &rr, &pq, &rzv), done);
    if (pc.bad) { /* no multigrid this step (a non-finite coarsest matrix): the caller's safer region */
        info->reason = GLPGP_TRCG_PRECOND;
        goto done;
    }
    const double bnorm = sqrt(rr);
    if (!isfinite(bnorm) || !isfinite(rzv)) {
        st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "trust-region CG right-hand side is not finite");
        goto done;
    }
    if (bnorm == 0.0) goto done;
    double dd = 0.0, dp = 0.0, pp = rzv; /* ||d||_M^2, d.Mp, ||p||_M^2 */
    double rzk = rzv, alpha = 0.0, rel = 1.0;
    for (k = 0;; k++) {
        if (k >= maxit) {
            info->reason = GLPGP_TRCG_MAXIT;
            break;
        }
        /* q <- A p;  s[PQ] <- p.q   (then read p.Ap, r.z and r.r of this iterate) */
        GLPGP_CHECK_GOTO(st, pc_spmv_dot(&pc, p, q), done);
        b->n_spmv++;
        nspmv++;
        GLPGP_CHECK_GOTO(st, pc_scalars(&pc, rz, &rr, &pq, &rzv), done);
        if (!isfinite(rr) || !isfinite(pq) || !isfinite(rzv)) {
            st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "trust-region CG: non-finite residual at iteration %d", k);
            goto done;
        }
        if (k > 0) {
            /* beta_{k-1} = (r.z)_k / (r.z)_{k-1} (as the device computed p_k):
             * d_k.M p_k = beta (d.Mp + alpha ||p||^2);  ||p_k||^2 = r.z + beta^2 ||p||^2 */
            const double beta = rzv / rzk;
            dp = beta * (dp + alpha * pp);
            pp = rzv + beta * beta * pp;
            rzk = rzv;
        }
        rel = sqrt(rr) / bnorm;
        if (rel <= rtol) break; /* |r_k| <= rtol |b|: d_k is the inexact Newton step */
        if (!(rzk > 0.0)) { /* r.z <= 0 with r != 0: M is not SPD */
            info->reason = GLPGP_TRCG_PRECOND;
            break;
        }
        const double kappa = pq;
        if (!(kappa > 0.0) && info->crossed) { /* look-ahead failed: xb is the step */
            info->reason = GLPGP_TRCG_NEGCURV;
            break;
        }
        if (!(kappa > 0.0) && !bounded) {
            /* negative curvature without a region: the last iterate (k > 0:
             * it lowered the model), or the preconditioned gradient p_0 */
            info->reason = GLPGP_TRCG_NEGCURV;
            if (k == 0) {
                GLPGP_CHECK_GOTO(st, o->copy(b, x, p), done);
                dd = pp;
            }
            break;
        }
        if (!(kappa > 0.0)) { /* d <- d + tau p on the boundary */
            const double tau = to_boundary(dd, dp, pp, radius);
            GLPGP_CHECK_GOTO(st, o->axpby(b, tau, p, 1.0, x), done);
            dd = radius * radius;
            info->reason = GLPGP_TRCG_NEGCURV;
            break;
        }
        alpha = rzk / kappa;
        const double dd_next = dd + 2.0 * alpha * dp + alpha * alpha * pp;
        if (bounded && dd_next >= radius * radius) {
            const double tau = to_boundary(dd, dp, pp, radius);
            if (xb) {
                /* look-ahead: xb <- d + tau p (the Steihaug point), then go
                 * on without the region towards the Newton step */
                GLPGP_CHECK_GOTO(st, o->copy(b, xb, x), done);
                GLPGP_CHECK_GOTO(st, o->axpby(b, tau, p, 1.0, xb), done);
                info->crossed = 1;
                bounded = 0;
            } else {
                GLPGP_CHECK_GOTO(st, o->axpby(b, tau, p, 1.0, x), done);
                dd = radius * radius;
                info->reason = GLPGP_TRCG_BOUNDARY;
                break;
            }
        }
        /* alpha = r.z / p.Ap;  x += alpha p;  r -= alpha q;  z <- M^-1 r */
        GLPGP_CHECK_GOTO(st, pc_update(&pc, x, r, p, q, z, rz, rzn), done);
        /* beta = r.z_new / r.z;  p <- z + beta p */
        GLPGP_CHECK_GOTO(st, pc_direction(&pc, p, z, rzn, rz), done);
        b->n_cg_iter++;
        dd = dd_next;
        int tmp = rz;
        rz = rzn;
        rzn = tmp;
    }
    info->relres = rel;
    info->norm = sqrt(dd);
done:
    info->iterations = nspmv;
    return st;
}
