/* solver/cg.c: the one Jacobi (2x2-block) preconditioned conjugate gradient
 * driver, written against the backend ops table. alpha and beta never leave
 * the device: the driver reads the residual norm back every `check`
 * iterations. A breakdown (p.Ap <= 0: the matrix is not SPD) or the cap is a
 * reason in the returned info, not an error: the Newton driver reacts to it. */
#include "glpgp/solve.h"
#include "glpgp/internal/newton.h"

#include <math.h>

int glpgp_cg_verdict(glpgp_cg_info *info, int k, int maxit, double rel, double rtol)
{
    if (k > maxit) {
        k = maxit;
        info->reason = GLPGP_CG_MAXIT;
    } else if (k == maxit && info->reason == GLPGP_CG_CONVERGED && !(rel <= rtol)) {
        info->reason = GLPGP_CG_MAXIT;
    }
    info->relres = rel;
    return k;
}

static glpgp_status cg_run(glpgp_backend *b, const glpgp_vec *rhs, glpgp_vec *x, double rtol, int maxit, int check,
                           glpgp_cg_info *info);

/* timed as a linear solve (glpgp/timers.h) */
glpgp_status glpgp_cg(glpgp_backend *b, const glpgp_vec *rhs, glpgp_vec *x, double rtol,
                      int maxit, int check, glpgp_cg_info *info)
{
    const int prev = glpgp_timer_enter(b, GLPGP_TM_LINEAR);
    const glpgp_status st = cg_run(b, rhs, x, rtol, maxit, check, info);
    glpgp_timer_leave(b, prev);
    return st;
}

static glpgp_status cg_run(glpgp_backend *b, const glpgp_vec *rhs, glpgp_vec *x, double rtol, int maxit, int check,
                           glpgp_cg_info *info)
{
    const glpgp_backend_ops *o = b->ops;
    const size_t n = (size_t)2 * b->sys->nv;
    glpgp_status st = GLPGP_OK;
    glpgp_vec *r = NULL, *z = NULL, *p = NULL, *q = NULL;
    double s[GLPGP_NSLOTS];
    int k = 0;
    info->iterations = 0;
    info->relres = 0.0;
    info->reason = GLPGP_CG_CONVERGED;
    if (check < 1) check = 1;
    GLPGP_CHECK_GOTO(st, glpgp_backend_scratch(b, 0, n, &r), done);
    GLPGP_CHECK_GOTO(st, glpgp_backend_scratch(b, 1, n, &z), done);
    GLPGP_CHECK_GOTO(st, glpgp_backend_scratch(b, 2, n, &p), done);
    GLPGP_CHECK_GOTO(st, glpgp_backend_scratch(b, 3, n, &q), done);

    /* x <- 0;  r <- b;  z <- D^-1 r;  p <- z */
    GLPGP_CHECK_GOTO(st, o->axpby(b, 0.0, x, 0.0, x), done);
    GLPGP_CHECK_GOTO(st, o->copy(b, r, rhs), done);
    GLPGP_CHECK_GOTO(st, o->cg_precond(b, r, z, GLPGP_S_RZ0), done);
    GLPGP_CHECK_GOTO(st, o->copy(b, p, z), done);
    GLPGP_CHECK_GOTO(st, o->get_scalars(b, s, GLPGP_NSLOTS), done);
    b->n_sync++;
    const double bnorm = sqrt(s[GLPGP_S_RR]);
    if (!isfinite(bnorm)) {
        st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "CG right-hand side is not finite");
        goto done;
    }
    if (bnorm == 0.0) goto done;
    int rz = GLPGP_S_RZ0, rzn = GLPGP_S_RZ1;
    double rel = 1.0;
    for (k = 1; k <= maxit; k++) {
        /* q <- A p;  alpha = r.z / p.q;  x += alpha p;  r -= alpha q;  z <- D^-1 r */
        GLPGP_CHECK_GOTO(st, o->cg_spmv_dot(b, p, q), done);
        GLPGP_CHECK_GOTO(st, o->cg_update(b, x, r, p, q, z, rz, rzn), done);
        b->n_spmv++;
        b->n_cg_iter++;
        if (k % check == 0 || k == maxit) {
            GLPGP_CHECK_GOTO(st, o->get_scalars(b, s, GLPGP_NSLOTS), done);
            b->n_sync++;
            if (!(s[GLPGP_S_PQ] > 0.0) || !isfinite(s[GLPGP_S_RR])) {
                info->reason = GLPGP_CG_BREAKDOWN;
                break;
            }
            rel = sqrt(s[GLPGP_S_RR]) / bnorm;
            if (rel <= rtol) break;
        }
        /* beta = r.z_new / r.z;  p <- z + beta p */
        GLPGP_CHECK_GOTO(st, o->cg_direction(b, p, z, rzn, rz), done);
        int tmp = rz;
        rz = rzn;
        rzn = tmp;
    }
    k = glpgp_cg_verdict(info, k, maxit, rel, rtol);
done:
    info->iterations = k;
    return st;
}
