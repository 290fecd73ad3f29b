/* amg_testutil.h: helpers shared by the multigrid tests of both backends
 * (tests/solver/test_amg.c on the reference backend,
 * tests/backends/test_amg_opencl.c on OpenCL): a vortex state, dense copies
 * of a hierarchy's level matrices and prolongations built from the backend
 * ops on unit vectors, the Galerkin check P^T A_l P = A_{l+1}, and the
 * check that a vector is reproduced by the prolongations on every level. Include
 * after testutil.h and glpgp/backend.h. */
#ifndef GLPGP_AMG_TESTUTIL_H
#define GLPGP_AMG_TESTUTIL_H

#include "glpgp/backend.h"
#include "glpgp/solve.h"
#include "glpgp/internal/newton.h"
#include "testutil.h"

#include <math.h>
#include <stdlib.h>

/* z_i = a(x_i) exp(i theta(x_i)): a wave along x (period h) with a vortex of
 * core radius `core` at (0.2, 0.1); |z| = 0 exactly at vertex `zero` (< 0:
 * none) */
static inline void amg_vortex_state(const glpgp_mesh *m, double h, double core, int zero, double *z)
{
    for (int i = 0; i < m->nv; i++) {
        double x = m->xy[2 * i], y = m->xy[2 * i + 1];
        double dx = x - 0.2, dy = y - 0.1, r = hypot(dx, dy);
        double a = r / sqrt(r * r + core * core);
        double th = 2 * GLPGP_PI * x / h + atan2(dy, dx);
        z[2 * i] = a * cos(th);
        z[2 * i + 1] = a * sin(th);
    }
    if (zero >= 0) z[2 * zero] = z[2 * zero + 1] = 0.0;
}

/* dense copy (order 2n, row-major) of level l's matrix through products with
 * unit vectors (level 0: the NEWTON matrix) */
static inline double *amg_dense_level(glpgp_backend *b, int l, int n)
{
    const glpgp_backend_ops *op = b->ops;
    const int m = 2 * n;
    double *A = calloc((size_t)m * m, sizeof(double)), *e = calloc((size_t)m, sizeof(double));
    double *col = calloc((size_t)m, sizeof(double));
    glpgp_vec *x = NULL, *y = NULL;
    CHECK_OK(op->vec_create(b, (size_t)m, &x));
    CHECK_OK(op->vec_create(b, (size_t)m, &y));
    for (int j = 0; j < m; j++) {
        e[j] = 1.0;
        CHECK_OK(op->vec_write(b, x, e));
        if (l == 0)
            CHECK_OK(op->spmv(b, GLPGP_MAT_NEWTON, x, y));
        else
            CHECK_OK(op->amg_spmv_dots(b, l, x, y, NULL, NULL, GLPGP_AMG_KSLOT(0)));
        CHECK_OK(op->vec_read(b, y, col));
        for (int i = 0; i < m; i++) A[(size_t)i * m + j] = col[i];
        e[j] = 0.0;
    }
    op->vec_destroy(b, &x);
    op->vec_destroy(b, &y);
    free(e);
    free(col);
    return A;
}

/* dense P_l (2 n_l x 2 n_{l+1}) through amg_prolong on unit coarse vectors */
static inline double *amg_dense_prolong(glpgp_backend *b, int l, int nf, int nc)
{
    const glpgp_backend_ops *op = b->ops;
    const int mf = 2 * nf, mc = 2 * nc;
    double *P = calloc((size_t)mf * mc, sizeof(double)), *e = calloc((size_t)mc, sizeof(double));
    double *col = calloc((size_t)mf, sizeof(double)), *zero = calloc((size_t)mf, sizeof(double));
    glpgp_vec *ec = NULL, *x = NULL;
    CHECK_OK(op->vec_create(b, (size_t)mc, &ec));
    CHECK_OK(op->vec_create(b, (size_t)mf, &x));
    for (int j = 0; j < mc; j++) {
        e[j] = 1.0;
        CHECK_OK(op->vec_write(b, ec, e));
        CHECK_OK(op->vec_write(b, x, zero));
        CHECK_OK(op->amg_prolong(b, l, ec, x));
        CHECK_OK(op->vec_read(b, x, col));
        for (int i = 0; i < mf; i++) P[(size_t)i * mc + j] = col[i];
        e[j] = 0.0;
    }
    op->vec_destroy(b, &ec);
    op->vec_destroy(b, &x);
    free(e);
    free(col);
    free(zero);
    return P;
}

/* The hierarchy `in` built on backend b (updated at a state whose vertex
 * `vortex` has z = 0, -1: none; dir the level-0 Dirichlet flags): on every
 * level, P^T A_l P equals A_{l+1} to 1e-13 of its largest entry, P^T P = I
 * (orthonormal aggregate bases), and every free level-0 vertex / every coarser
 * node lies in exactly one aggregate (two nonzero columns: z and iz), no
 * Dirichlet vertex in any (the vortex vertex, with z = 0, may have fewer);
 * a dead coarse node (an aggregate of Dirichlet vertices only: a zero
 * column pair of P) has an identity row in A_{l+1}. */
static inline void amg_check_galerkin(const char *label, glpgp_backend *b, const glpgp_amg_info *in,
                               const unsigned char *dir, int vortex)
{
    double *A = amg_dense_level(b, 0, in->n[0]);
    unsigned char *dead = NULL; /* the dead nodes of level l >= 1 */
    for (int l = 0; l + 1 < in->nlevels; l++) {
        const int mf = 2 * in->n[l], mc = 2 * in->n[l + 1];
        double *P = amg_dense_prolong(b, l, in->n[l], in->n[l + 1]);
        double *Ac = amg_dense_level(b, l + 1, in->n[l + 1]);
        /* T = A P, G = P^T T; compare with A_{l+1} */
        double *T = calloc((size_t)mf * mc, sizeof(double));
        double amax = 0.0, dmax = 0.0, ortho = 0.0;
        for (int i = 0; i < mf; i++)
            for (int k = 0; k < mf; k++) {
                double aik = A[(size_t)i * mf + k];
                if (aik == 0.0) continue;
                for (int j = 0; j < mc; j++) T[(size_t)i * mc + j] += aik * P[(size_t)k * mc + j];
            }
        /* a dead coarse node (an aggregate of Dirichlet vertices only, or
         * of dead nodes): a zero column pair of P, an identity row of A_c */
        unsigned char *dead_c = calloc((size_t)in->n[l + 1] + 1, 1);
        for (int I = 0; I < in->n[l + 1]; I++) {
            int nzc = 0;
            for (int k = 0; k < mf; k++) nzc += P[(size_t)k * mc + 2 * I] != 0.0 || P[(size_t)k * mc + 2 * I + 1] != 0.0;
            dead_c[I] = nzc == 0;
        }
        int dead_bad = 0;
        for (int I = 0; I < mc; I++)
            for (int J = 0; J < mc; J++) {
                if (dead_c[I / 2] || dead_c[J / 2]) {
                    dead_bad += Ac[(size_t)I * mc + J] != (I == J ? 1.0 : 0.0);
                    continue;
                }
                double g = 0.0, pp = 0.0;
                for (int k = 0; k < mf; k++) {
                    g += P[(size_t)k * mc + I] * T[(size_t)k * mc + J];
                    pp += P[(size_t)k * mc + I] * P[(size_t)k * mc + J];
                }
                amax = fmax(amax, fabs(g));
                dmax = fmax(dmax, fabs(g - Ac[(size_t)I * mc + J]));
                ortho = fmax(ortho, fabs(pp - (I == J ? 1.0 : 0.0)));
            }
        CHECK(dead_bad == 0);
        /* every live node of level l in exactly one aggregate (two nonzero
         * columns), a Dirichlet vertex / dead node in none */
        int bad = 0;
        for (int i = 0; i < in->n[l]; i++) {
            int nz = 0;
            for (int j = 0; j < mc; j++)
                nz += P[(size_t)(2 * i) * mc + j] != 0.0 || P[(size_t)(2 * i + 1) * mc + j] != 0.0;
            int off = l == 0 ? dir[i] : dead[i];
            int at_vortex = l == 0 && i == vortex;
            if (off ? nz != 0 : (!at_vortex && nz != 2)) bad++;
        }
        free(dead);
        dead = dead_c;
        printf("%s: level %d -> %d: max |P^T A P - A_c| = %.2e (max entry %.2e), "
               "max |P^T P - I| = %.2e, bad rows %d\n", label, l, l + 1, dmax, amax, ortho, bad);
        CHECK(amax > 0.0);
        CHECK(dmax <= 1e-13 * amax);
        CHECK(ortho <= 1e-13);
        CHECK(bad == 0);
        free(T);
        free(P);
        free(A);
        A = Ac;
    }
    free(A);
    free(dead);
}

/* for v on level 0 (2 nv), checks P_l P_l^T v_l = v_l on every level with
 * v_{l+1} = P_l^T v_l; returns the largest relative defect */
static inline double amg_reproduce(glpgp_backend *b, const glpgp_amg_info *in, const double *v0)
{
    const glpgp_backend_ops *op = b->ops;
    double worst = 0.0;
    glpgp_vec *v = NULL;
    CHECK_OK(op->vec_create(b, (size_t)2 * in->n[0], &v));
    CHECK_OK(op->vec_write(b, v, v0));
    for (int l = 0; l + 1 < in->nlevels; l++) {
        const int mf = 2 * in->n[l], mc = 2 * in->n[l + 1];
        glpgp_vec *vc = NULL, *back = NULL;
        CHECK_OK(op->vec_create(b, (size_t)mc, &vc));
        CHECK_OK(op->vec_create(b, (size_t)mf, &back));
        CHECK_OK(op->amg_restrict(b, l, v, NULL, vc));
        CHECK_OK(op->amg_prolong(b, l, vc, back)); /* back = 0 + P vc */
        double *hv = calloc((size_t)mf, sizeof(double)), *hb = calloc((size_t)mf, sizeof(double));
        CHECK_OK(op->vec_read(b, v, hv));
        CHECK_OK(op->vec_read(b, back, hb));
        double d = 0.0, nrm = 0.0;
        for (int i = 0; i < mf; i++) {
            d = fmax(d, fabs(hb[i] - hv[i]));
            nrm = fmax(nrm, fabs(hv[i]));
        }
        worst = fmax(worst, d / nrm);
        free(hv);
        free(hb);
        op->vec_destroy(b, &back);
        op->vec_destroy(b, &v);
        v = vc;
    }
    op->vec_destroy(b, &v);
    return worst;
}

#endif
