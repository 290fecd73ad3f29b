/* cholmod_bench.c: the direct-solver comparison of glpgp-bench: expands the
 * 2x2-block NEWTON matrix to the lower triangle of a scalar CSC matrix and
 * times CHOLMOD's symbolic analysis, numeric factorisation and solve (what a
 * user would otherwise pick). Compiled with CHOLMOD when the build found it
 * (GLPGP_HAVE_CHOLMOD), else a stub that says so. */
#include "bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef GLPGP_HAVE_CHOLMOD

int bench_have_cholmod(void) { return 0; }

glpgp_status bench_cholmod_run(const glpgp_system *sys, const double *vals, const double *rhs,
                               const double *xcg, bench_cholmod *out)
{
    (void)sys;
    (void)vals;
    (void)rhs;
    (void)xcg;
    memset(out, 0, sizeof *out);
    snprintf(out->note, sizeof out->note, "skipped (not built with it)");
    return GLPGP_OK;
}

#else

#include <cholmod.h>

int bench_have_cholmod(void) { return 1; }

static const char *ordering_name(int o)
{
    switch (o) {
    case CHOLMOD_NATURAL: return "natural";
    case CHOLMOD_GIVEN: return "given";
    case CHOLMOD_AMD: return "AMD";
    case CHOLMOD_METIS: return "METIS";
    case CHOLMOD_NESDIS: return "NESDIS";
    case CHOLMOD_COLAMD: return "COLAMD";
    case CHOLMOD_POSTORDERED: return "postordered";
    default: return "?";
    }
}

glpgp_status bench_cholmod_run(const glpgp_system *sys, const double *vals, const double *rhs,
                               const double *xcg, bench_cholmod *out)
{
    memset(out, 0, sizeof *out);
    out->available = 1;
    const int nv = sys->nv, n = 2 * nv;
    /* lower triangle, by symmetry column J = 2j+c holds row J of block row j:
     * A[2k+r, 2j+c] = A[2j+c, 2k+r] = blk_jk[c][r], kept where 2k+r >= 2j+c */
    size_t nnz = 0;
    for (int j = 0; j < nv; j++)
        for (int k = sys->rowptr[j]; k < sys->rowptr[j + 1]; k++) {
            int col = sys->col[k];
            if (col > j) nnz += 4;
            else if (col == j) nnz += 3;
        }
    cholmod_common cc;
    cholmod_common *c = &cc;
    cholmod_start(c);
    c->print = 0;
    cholmod_sparse *A = cholmod_allocate_sparse((size_t)n, (size_t)n, nnz, 1, 1, -1, CHOLMOD_REAL, c);
    cholmod_dense *B = cholmod_allocate_dense((size_t)n, 1, (size_t)n, CHOLMOD_REAL, c);
    cholmod_factor *L = NULL;
    cholmod_dense *X = NULL;
    glpgp_status st = GLPGP_OK;
    if (!A || !B) {
        st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "CHOLMOD: cannot allocate the %d x %d matrix (%zu entries)", n, n, nnz);
        goto done;
    }
    int *Ap = A->p, *Ai = A->i;
    double *Ax = A->x;
    size_t e = 0;
    for (int j = 0; j < nv; j++) {
        for (int cc2 = 0; cc2 < 2; cc2++) {
            const int J = 2 * j + cc2;
            Ap[J] = (int)e;
            for (int k = sys->rowptr[j]; k < sys->rowptr[j + 1]; k++) {
                const int col = sys->col[k];
                for (int r = 0; r < 2; r++) {
                    const int I = 2 * col + r;
                    if (I < J) continue;
                    Ai[e] = I;
                    Ax[e] = vals[4 * (size_t)k + 2 * cc2 + r];
                    e++;
                }
            }
        }
    }
    Ap[n] = (int)e;
    memcpy(B->x, rhs, (size_t)n * sizeof(double));
    out->ran = 1;

    double t0 = bench_now();
    L = cholmod_analyze(A, c);
    out->analyze_s = bench_now() - t0;
    if (!L || c->status < CHOLMOD_OK) {
        snprintf(out->note, sizeof out->note, "analysis failed (CHOLMOD status %d)", c->status);
        goto done;
    }
    t0 = bench_now();
    int okf = cholmod_factorize(A, L, c);
    out->factorize_s = bench_now() - t0;
    if (!okf || c->status != CHOLMOD_OK) {
        snprintf(out->note, sizeof out->note, "factorisation failed (CHOLMOD status %d%s)", c->status,
                 c->status == CHOLMOD_NOT_POSDEF ? ": not positive definite" : "");
        goto done;
    }
    t0 = bench_now();
    X = cholmod_solve(CHOLMOD_A, L, B, c);
    out->solve_s = bench_now() - t0;
    if (!X) {
        snprintf(out->note, sizeof out->note, "solve failed (CHOLMOD status %d)", c->status);
        goto done;
    }
    out->ok = 1;
    out->factor_nnz = c->lnz;
    out->peak_bytes = (double)c->memory_usage;
    snprintf(out->note, sizeof out->note, "%s ordering, %s factor", ordering_name(c->method[c->selected].ordering),
             L->is_super ? "supernodal" : "simplicial");
    out->rel_diff_vs_cg = -1.0;
    if (xcg) {
        const double *x = X->x;
        double d = 0.0, s = 0.0;
        for (int i = 0; i < n; i++) {
            d += (x[i] - xcg[i]) * (x[i] - xcg[i]);
            s += x[i] * x[i];
        }
        out->rel_diff_vs_cg = s > 0.0 ? sqrt(d / s) : sqrt(d);
    }
done:
    cholmod_free_dense(&X, c);
    cholmod_free_factor(&L, c);
    cholmod_free_dense(&B, c);
    cholmod_free_sparse(&A, c);
    cholmod_finish(c);
    return st;
}

#endif
