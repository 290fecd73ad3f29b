/* backends/petsc_ksp.c: the PETSc backend's linear solve with PETSc's GAMG
 * (op linear_solve, -glpgp_mg gamg; the default is glpgp's multigrid,
 * petsc_amg.c): NEWTON as an AIJ matrix (built lazily), KSPCG with GAMG,
 * the hierarchy kept across Newton steps, eps levels or oscillators as
 * -glpgp_gamg_rebuild says. The rest of the backend: petsc.c
 * (petsc_impl.h). */
#include "petsc_impl.h"

#include "petsc_module.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

/* ---- linear solve: KSP on NEWTON ------------------------------------------ */

/* A <- NEWTON (owned rows, global columns), created and preallocated once */
static glpgp_status newton_to_mat(pimpl *p)
{
    const glpgp_system *sys = p->sys;
    const int nown = p->hi - p->lo;
    if (!p->A) {
        /* AIJ with block size 2 (GAMG wants AIJ), preallocated per block row:
         * diagonal-part and off-diagonal-part block counts */
        PetscInt *dn = NULL, *on = NULL;
        GLPGP_CHECK(glpgp_calloc((size_t)(nown > 0 ? nown : 1), sizeof(PetscInt), &dn));
        glpgp_status st = glpgp_calloc((size_t)(nown > 0 ? nown : 1), sizeof(PetscInt), &on);
        if (st != GLPGP_OK) {
            free(dn);
            return st;
        }
        for (int i = p->lo; i < p->hi; i++)
            for (int k = sys->rowptr[i]; k < sys->rowptr[i + 1]; k++) {
                const int j = sys->col[k];
                if (j >= p->lo && j < p->hi) dn[i - p->lo]++;
                else on[i - p->lo]++;
            }
        PetscErrorCode pe = MatCreate(PETSC_COMM_WORLD, &p->A);
        if (!pe) pe = MatSetSizes(p->A, 2 * nown, 2 * nown, PETSC_DETERMINE, PETSC_DETERMINE);
        if (!pe) pe = MatSetType(p->A, MATAIJ);
        if (!pe) pe = MatSetBlockSize(p->A, 2);
        if (!pe) pe = MatXAIJSetPreallocation(p->A, 2, dn, on, NULL, NULL);
        if (!pe) pe = MatSetOption(p->A, MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE);
        if (!pe) pe = MatSetOption(p->A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE);
        free(dn);
        free(on);
        if (pe) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "PETSc error %d creating the Newton matrix", (int)pe);
    }
    /* block rows: our blocks are row-major 2x2; PETSc wants the 2 x (2 ncol)
     * row-major dense strip of the block row */
    int maxc = 0;
    for (int i = p->lo; i < p->hi; i++)
        if (sys->rowptr[i + 1] - sys->rowptr[i] > maxc) maxc = sys->rowptr[i + 1] - sys->rowptr[i];
    double *vals = NULL;
    PetscInt *cols = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)4 * (maxc > 0 ? maxc : 1), sizeof(double), &vals));
    glpgp_status st = glpgp_malloc((size_t)(maxc > 0 ? maxc : 1), sizeof(PetscInt), &cols);
    if (st != GLPGP_OK) {
        free(vals);
        return st;
    }
    const double *N = NEWT(p);
    PetscErrorCode pe = 0;
    for (int i = p->lo; i < p->hi && !pe; i++) {
        const int k0 = sys->rowptr[i], nc = sys->rowptr[i + 1] - k0;
        for (int c = 0; c < nc; c++) {
            const double *blk = N + 4 * (long)(k0 + c);
            cols[c] = gcol(p, sys->col[k0 + c]);
            vals[2 * c] = blk[0];
            vals[2 * c + 1] = blk[1];
            vals[2 * nc + 2 * c] = blk[2];
            vals[2 * nc + 2 * c + 1] = blk[3];
        }
        PetscInt row = p->vstart + (i - p->lo);
        pe = MatSetValuesBlocked(p->A, 1, &row, nc, cols, vals, INSERT_VALUES);
    }
    free(vals);
    free(cols);
    if (pe) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "PETSc error %d setting the Newton matrix", (int)pe);
    PCHK(MatAssemblyBegin(p->A, MAT_FINAL_ASSEMBLY));
    PCHK(MatAssemblyEnd(p->A, MAT_FINAL_ASSEMBLY));
    p->A_dirty = 0;
    return GLPGP_OK;
}

/* near null space [z, iz] of the iterate (zero at Dirichlet vertices), or none */
static glpgp_status set_near_null(pimpl *p)
{
    if (!p->nn_valid) {
        PCHK(MatSetNearNullSpace(p->A, NULL));
        return GLPGP_OK;
    }
    Vec v[2];
    PCHK(VecDuplicate(p->nn, &v[0]));
    PCHK(VecDuplicate(p->nn, &v[1]));
    const PetscScalar *z;
    PetscScalar *a0, *a1;
    PCHK(VecGetArrayRead(p->nn, &z));
    PCHK(VecGetArray(v[0], &a0));
    PCHK(VecGetArray(v[1], &a1));
    for (int i = 0; i < p->hi - p->lo; i++) {
        const int fixed = p->dir[p->lo + i];
        const double zr = fixed ? 0.0 : z[2 * i], zi = fixed ? 0.0 : z[2 * i + 1];
        a0[2 * i] = zr; /* z */
        a0[2 * i + 1] = zi;
        a1[2 * i] = -zi; /* i z */
        a1[2 * i + 1] = zr;
    }
    PCHK(VecRestoreArray(v[1], &a1));
    PCHK(VecRestoreArray(v[0], &a0));
    PCHK(VecRestoreArrayRead(p->nn, &z));
    PetscReal n0;
    PCHK(VecNorm(v[0], NORM_2, &n0)); /* |z| = |iz|, and z . iz = 0: orthonormal after scaling */
    MatNullSpace ns = NULL;
    if (n0 > 0.0) {
        PCHK(VecScale(v[0], 1.0 / n0));
        PCHK(VecScale(v[1], 1.0 / n0));
        PCHK(MatNullSpaceCreate(PETSC_COMM_WORLD, PETSC_FALSE, 2, v, &ns));
    }
    PCHK(MatSetNearNullSpace(p->A, ns));
    if (ns) MatNullSpaceDestroy(&ns);
    VecDestroy(&v[0]);
    VecDestroy(&v[1]);
    return GLPGP_OK;
}

glpgp_status glpgp_petsc_linear_solve(glpgp_backend *b, const glpgp_vec *rhs, glpgp_vec *x, double rtol, int maxit,
                                   int *iterations, double *relres, int *reason)
{
    pimpl *p = PI(b);
    *iterations = 0;
    *relres = 0.0;
    *reason = 0;
    if (p->A_dirty || !p->A) GLPGP_CHECK(newton_to_mat(p));
    /* GAMG's hierarchy: built anew for each new system (a new QUAD, a new
     * eps level: its aggregates and prolongator from the current near null
     * space [z, iz]) and reused within an eps level, where z moves little:
     * only the Galerkin products are recomputed (-pc_gamg_reuse_interpolation
     * below). -glpgp_gamg_rebuild step|level|oscillator ($PETSC_OPTIONS)
     * rebuilds it every linear solve (before), per eps level (default) or
     * once per oscillator's GL levels. shape:square:100000, one rank, line
     * search: 32.4 s, 537 CG (step) -> 21.9 s, 212 CG (level)
     * (bench/results/petsc_gamg.md) */
    if (!p->rebuild) {
        char mode[32] = "level";
        PetscBool set = PETSC_FALSE;
        PCHK(PetscOptionsGetString(NULL, NULL, "-glpgp_gamg_rebuild", mode, sizeof mode, &set));
        p->rebuild = !strcmp(mode, "step") ? 1 : !strcmp(mode, "level") ? 2 : !strcmp(mode, "oscillator") ? 3 : -1;
        if (p->rebuild < 0)
            return GLPGP_FAIL(GLPGP_ERR_ARG, "-glpgp_gamg_rebuild '%s': expected step, level or oscillator", mode);
    }
    if (p->ksp && p->precond == GLPGP_PRECOND_AMG &&
        (p->rebuild == 1 || p->ksp_gen != p->quad_gen || p->ksp_nn != p->nn_valid ||
         (p->rebuild == 2 && p->ksp_inv4e2 != p->newton_inv4e2)))
        KSPDestroy(&p->ksp);
    if (!p->ksp) {
        p->ksp_gen = p->quad_gen;
        p->ksp_inv4e2 = p->newton_inv4e2;
        p->ksp_nn = p->nn_valid;
        PCHK(KSPCreate(PETSC_COMM_WORLD, &p->ksp));
        PCHK(KSPSetType(p->ksp, KSPCG));
        PCHK(KSPSetNormType(p->ksp, KSP_NORM_UNPRECONDITIONED));
        PC pc;
        PCHK(KSPGetPC(p->ksp, &pc));
        PCHK(PCSetType(pc, PCGAMG));
        /* smoother: PETSc's default Chebyshev, from a short eigenvalue
         * estimate, made the preconditioner indefinite on the naive PGP
         * system (CG stopped with DIVERGED_INDEFINITE_PC after 3 iterations
         * on shape:disk:3000); damped point-block Jacobi is SPD for these
         * matrices. Defaults only: $PETSC_OPTIONS wins. */
        /* the prolongator kept for the KSP's life (one eps level, above):
         * rebuilt per Newton step it costs its setup again (shape:square:
         * 100000: 15.3 of 32.4 s in PCSetUp); kept for the whole run, the
         * naive solve's (no near null space) served every level (square
         * 40000: 898 CG iterations against 661) */
        static const char *const defaults[][2] = {{"-mg_levels_ksp_type", "richardson"},
                                                  {"-mg_levels_pc_type", "pbjacobi"},
                                                  {"-mg_levels_ksp_richardson_scale", "0.6"},
                                                  {"-pc_gamg_reuse_interpolation", "true"}};
        for (size_t k = 0; k < sizeof defaults / sizeof defaults[0]; k++) {
            PetscBool set = PETSC_FALSE;
            PCHK(PetscOptionsHasName(NULL, NULL, defaults[k][0], &set));
            if (!set) PCHK(PetscOptionsSetValue(NULL, defaults[k][0], defaults[k][1]));
        }
        PCHK(KSPSetFromOptions(p->ksp)); /* $PETSC_OPTIONS */
    }
    if (p->precond == GLPGP_PRECOND_AMG) GLPGP_CHECK(set_near_null(p));
    PCHK(KSPSetOperators(p->ksp, p->A, p->A));
    PCHK(KSPSetTolerances(p->ksp, rtol, 0.0, PETSC_DEFAULT, maxit));
    PCHK(KSPSetInitialGuessNonzero(p->ksp, PETSC_FALSE));
    /* x <- NEWTON^-1 rhs */
    PCHK(KSPSolve(p->ksp, rhs->v, x->v));
    PetscInt it;
    KSPConvergedReason why;
    PetscReal rn, bn;
    PCHK(KSPGetIterationNumber(p->ksp, &it));
    PCHK(KSPGetConvergedReason(p->ksp, &why));
    PCHK(KSPGetResidualNorm(p->ksp, &rn));
    PCHK(VecNorm(rhs->v, NORM_2, &bn));
    *iterations = (int)it;
    *relres = bn > 0.0 ? rn / bn : 0.0;
    if (why > 0) *reason = 0;
    else if (why == KSP_DIVERGED_ITS) *reason = 1;
    else *reason = 2;
    /* a breakdown (KSP_DIVERGED_INDEFINITE_MAT or _PC: GAMG built from an
     * indefinite Newton matrix is itself indefinite) is routine: the driver
     * falls back to a safer Hessian; logged with --verbose only */
    if (why < 0 && why != KSP_DIVERGED_ITS)
        glpgp_log(GLPGP_LOG_DEBUG, "PETSc KSP stopped after %d iterations: %s", (int)it, KSPConvergedReasons[why]);
    return GLPGP_OK;
}
