/* amg_dense.h: the multigrid's coarsest-level operator, computed where the
 * hierarchy lives (ops amg_coarse_invert of glpgp/backend.h): the coarsest
 * matrix A (order m = 2 n_{L-1}) expanded to a dense row-major array and a
 * generalised inverse of it, written once for both twins:
 *   - the OpenCL kernel glpgp_amg_coarse_invert (kernels/backend_multigrid.cl)
 *     runs it in ONE work-group of nt work-items, each calling the step
 *     functions below with its own t in [0, nt), a barrier between steps;
 *   - the reference backend (host/backends/reference_amg.c) calls the same
 *     driver with t = 0, nt = 1.
 * Every step writes each entry from the same operations in the same order
 * whatever nt (pivot searches pick the first largest entry in row-major
 * order: per work-item the first of its own entries, then the largest of
 * those, ties to the smaller index), so both store the same bits.
 *
 * Two inverses, as solver/amg.c uses them:
 *   LU:  P A Q = L U by complete pivoting; pivots below 1e-12 |u_11| end the
 *        elimination (rank r); the components beyond r are 0 (a generalised
 *        inverse: the exact gauge null vector of an oscillator without
 *        Dirichlet vertices, the indefinite exact Hessian);
 *   SPD: of the symmetric part, pivoted L D L^T (largest |d| first),
 *        inv = P^T [L^-T |D|^-1 L^-1, 0; 0, 0] P: symmetric positive
 *        semi-definite whatever the signs of D (the symmetric cycle of the
 *        trust region); for a nonsingular PSD A it is A^-1.
 * A non-finite entry of A makes the step fail (status 1).
 *
 * Compiled as C11 and as OpenCL C (embedded after amg_rows.h). GLPGP_SYNC()
 * is the work-group barrier in OpenCL C and nothing in C. */
#ifndef GLPGP_AMG_DENSE_H
#define GLPGP_AMG_DENSE_H

#ifdef __OPENCL_VERSION__
#define GLPGP_SYNC() barrier(CLK_GLOBAL_MEM_FENCE | CLK_LOCAL_MEM_FENCE)
#define GLPGP_LOCAL __local
#else
#include <math.h>
#include "rows.h" /* GLPGP_GLOBAL, GLPGP_FN */
#define GLPGP_SYNC() ((void)0)
#define GLPGP_LOCAL
#endif

/* Work arrays in one double array W (offsets in doubles) and one int array
 * I: the dense matrix (m*m), the factor (m*m), the solve columns (m*m), the
 * reciprocal pivots (m); permutations of rows, columns (m each). */
#define GLPGP_DENSE_W(m) (3 * (long)(m) * (m) + (m))
#define GLPGP_DENSE_I(m) (2 * (m))

/* dense[2I + p][2J + q] <- A[K](p, q) for every block K = (I, J) of the
 * coarsest level (CSR rowptr / col / val of n nodes), zero elsewhere: rows
 * 2I, 2I+1 by work-item t of nt. */
GLPGP_FN void glpgp_dense_expand(int t, int nt, int n, GLPGP_GLOBAL const int *rowptr, GLPGP_GLOBAL const int *col,
                                 GLPGP_GLOBAL const double *val, GLPGP_GLOBAL double *dense)
{
    const int m = 2 * n;
    for (int I = t; I < n; I += nt) {
        for (int j = 0; j < m; j++) {
            dense[(long)(2 * I) * m + j] = 0.0;
            dense[(long)(2 * I + 1) * m + j] = 0.0;
        }
        for (int K = rowptr[I]; K < rowptr[I + 1]; K++) {
            const int J = col[K];
            for (int p = 0; p < 2; p++)
                for (int q = 0; q < 2; q++) dense[(long)(2 * I + p) * m + 2 * J + q] = val[4 * (long)K + 2 * p + q];
        }
    }
}

/* Reduction of (value, index) pairs over the work-group: the largest value,
 * ties to the smaller index (idx < 0: none). buf: 2 nt entries of local
 * memory (OpenCL; unused with nt = 1). Every work-item gets the result. */
GLPGP_FN void glpgp_dense_argmax(int t, int nt, double *v, long *idx, GLPGP_LOCAL double *bv, GLPGP_LOCAL long *bi)
{
#ifdef __OPENCL_VERSION__
    bv[t] = *v;
    bi[t] = *idx;
    GLPGP_SYNC();
    for (int s = nt / 2; s > 0; s >>= 1) {
        if (t < s) {
            const double a = bv[t], b = bv[t + s];
            const long ia = bi[t], ib = bi[t + s];
            if (ib >= 0 && (ia < 0 || b > a || (b == a && ib < ia))) {
                bv[t] = b;
                bi[t] = ib;
            }
        }
        GLPGP_SYNC();
    }
    *v = bv[0];
    *idx = bi[0];
    GLPGP_SYNC();
#else
    (void)t;
    (void)nt;
    (void)v;
    (void)idx;
    (void)bv;
    (void)bi;
#endif
}

/* work-item t's first largest |lu_ij| over i, j in [k, m) in row-major order */
GLPGP_FN void glpgp_dense_lu_pivot(int t, int nt, int m, int k, GLPGP_GLOBAL const double *lu, double *bv, long *bq)
{
    const long w = m - k, tot = w * w;
    *bv = -1.0;
    *bq = -1;
    long i = t / w, j = t % w; /* q = i w + j, advanced without a division per entry */
    for (long q = t; q < tot; q += nt) {
        const double v = fabs(lu[(k + i) * m + k + j]);
        if (v > *bv) {
            *bv = v;
            *bq = q;
        }
        j += nt;
        while (j >= w) {
            j -= w;
            i++;
        }
    }
}

/* swap rows (rows = 1) or columns (rows = 0) a and b of M: entries by work-item t */
GLPGP_FN void glpgp_dense_swap(int t, int nt, int m, GLPGP_GLOBAL double *M, int a, int b, int rows)
{
    for (int k = t; k < m; k += nt) {
        GLPGP_GLOBAL double *x = rows ? M + (long)a * m + k : M + (long)k * m + a;
        GLPGP_GLOBAL double *y = rows ? M + (long)b * m + k : M + (long)k * m + b;
        const double s = *x;
        *x = *y;
        *y = s;
    }
}

/* Status 1 when an entry of the m x m matrix A is not finite (every work-item
 * scans all: a few thousand entries). */
GLPGP_FN int glpgp_dense_bad(int m, GLPGP_GLOBAL const double *A)
{
    for (long k = 0; k < (long)m * m; k++)
        if (!isfinite(A[k])) return 1;
    return 0;
}

/* inv <- the LU generalised inverse of A (see the file comment). W, I: the
 * work arrays (GLPGP_DENSE_W / _I). Returns the status (0, or 1: A not finite). */
GLPGP_FN int glpgp_dense_lu_inverse(int t, int nt, int m, GLPGP_GLOBAL const double *A, GLPGP_GLOBAL double *inv,
                                    GLPGP_GLOBAL double *W, GLPGP_GLOBAL int *I, GLPGP_LOCAL double *bv,
                                    GLPGP_LOCAL long *bi)
{
    GLPGP_GLOBAL double *lu = W + (long)m * m, *ys = W + 2 * (long)m * m;
    GLPGP_GLOBAL int *pr = I, *pc = I + m;
    if (glpgp_dense_bad(m, A)) return 1;
    for (long q = t; q < (long)m * m; q += nt) lu[q] = A[q];
    for (int i = t; i < m; i += nt) {
        pr[i] = i;
        pc[i] = i;
    }
    GLPGP_SYNC();
    /* no early exit from a loop with barriers: once a pivot is too small the
     * remaining steps do nothing (go = 0), the same on every work-item */
    int r = 0, go = 1;
    double piv0 = 0.0;
    for (int k = 0; k < m; k++) {
        double v;
        long q;
        glpgp_dense_lu_pivot(t, nt, m, k, lu, &v, &q);
        glpgp_dense_argmax(t, nt, &v, &q, bv, bi);
        if (k == 0) piv0 = v;
        if (!(v > 1e-12 * piv0) || v == 0.0) go = 0;
        const int w = m - k, pi = go ? k + (int)(q / w) : k, pj = go ? k + (int)(q % w) : k;
        if (pi != k) glpgp_dense_swap(t, nt, m, lu, k, pi, 1);
        GLPGP_SYNC();
        if (pj != k) glpgp_dense_swap(t, nt, m, lu, k, pj, 0);
        GLPGP_SYNC(); /* a phase of its own (see glpgp_dense_spd_inverse) */
        if (go && t == 0) {
            int sw = pr[k];
            pr[k] = pr[pi];
            pr[pi] = sw;
            sw = pc[k];
            pc[k] = pc[pj];
            pc[pj] = sw;
        }
        GLPGP_SYNC();
        /* eliminate below the pivot: l_ik = a_ik / a_kk;  a_ij -= l_ik a_kj */
        const double pk = lu[(long)k * m + k];
        for (int i = k + 1 + t; go && i < m; i += nt) {
            GLPGP_GLOBAL double *ri = lu + (long)i * m;
            GLPGP_GLOBAL const double *rk = lu + (long)k * m;
            const double l = ri[k] / pk;
            ri[k] = l;
            if (l != 0.0)
                for (int j = k + 1; j < m; j++) ri[j] -= l * rk[j];
        }
        GLPGP_SYNC();
        if (go) r = k + 1;
    }
    /* column c of the inverse: L y = P e_c,  U x' = y (first r components),  x = Q x' */
    for (int c = t; c < m; c += nt) {
        GLPGP_GLOBAL double *y = ys + (long)c * m;
        for (int i = 0; i < m; i++) y[i] = pr[i] == c ? 1.0 : 0.0;
        for (int i = 0; i < r; i++) {
            GLPGP_GLOBAL const double *ri = lu + (long)i * m;
            double s = y[i];
            for (int j = 0; j < i; j++) s -= ri[j] * y[j];
            y[i] = s;
        }
        for (int i = r; i < m; i++) y[i] = 0.0;
        for (int i = r - 1; i >= 0; i--) {
            GLPGP_GLOBAL const double *ri = lu + (long)i * m;
            double s = y[i];
            for (int j = i + 1; j < r; j++) s -= ri[j] * y[j];
            y[i] = s / ri[i];
        }
        for (int i = 0; i < m; i++) inv[(long)pc[i] * m + c] = y[i];
    }
    GLPGP_SYNC();
    return 0;
}

/* inv <- the symmetric positive semi-definite generalised inverse of A
 * (see the file comment). Returns the status. */
GLPGP_FN int glpgp_dense_spd_inverse(int t, int nt, int m, GLPGP_GLOBAL const double *A, GLPGP_GLOBAL double *inv,
                                     GLPGP_GLOBAL double *W, GLPGP_GLOBAL int *I, GLPGP_LOCAL double *bv,
                                     GLPGP_LOCAL long *bi)
{
    GLPGP_GLOBAL double *S = W + (long)m * m, *dinv = W + 3 * (long)m * m;
    GLPGP_GLOBAL int *perm = I;
    if (glpgp_dense_bad(m, A)) return 1;
    for (int i = t; i < m; i += nt) {
        perm[i] = i;
        for (int j = 0; j < m; j++) S[(long)i * m + j] = 0.5 * (A[(long)i * m + j] + A[(long)j * m + i]);
    }
    GLPGP_SYNC();
    /* P A_s P^T = L D L^T: l_ik in S's lower part (i > k), d_k on its diagonal */
    int r = 0, go = 1; /* go: as in glpgp_dense_lu_inverse */
    double piv0 = 0.0;
    for (int k = 0; k < m; k++) {
        double v = -1.0;
        long q = -1;
        for (int j = k + t; j < m; j += nt)
            if (fabs(S[(long)j * m + j]) > v) {
                v = fabs(S[(long)j * m + j]);
                q = j;
            }
        glpgp_dense_argmax(t, nt, &v, &q, bv, bi);
        if (k == 0) piv0 = v;
        if (!(v > 1e-12 * piv0) || v == 0.0) go = 0;
        const int bj = go ? (int)q : k;
        /* symmetric swap of rows and columns k, bj; every phase ends at a
         * barrier (PoCL's work-group loops lost a column swap's writes when
         * the permutation update shared its phase) */
        if (bj != k) glpgp_dense_swap(t, nt, m, S, k, bj, 1);
        GLPGP_SYNC();
        if (bj != k) glpgp_dense_swap(t, nt, m, S, k, bj, 0);
        GLPGP_SYNC();
        if (bj != k && t == 0) {
            const int sw = perm[k];
            perm[k] = perm[bj];
            perm[bj] = sw;
        }
        GLPGP_SYNC();
        /* d = s_kk;  l_ik = s_ik / d;  s_ij -= l_ik d l_jk  (i, j > k, lower part) */
        const double d = S[(long)k * m + k];
        for (int i = k + 1 + t; go && i < m; i += nt) S[(long)i * m + k] /= d;
        GLPGP_SYNC();
        for (int i = k + 1 + t; go && i < m; i += nt) {
            const double lid = S[(long)i * m + k] * d;
            if (lid == 0.0) continue;
            for (int j = k + 1; j <= i; j++) S[(long)i * m + j] -= lid * S[(long)j * m + k];
        }
        GLPGP_SYNC();
        /* keep the trailing block symmetric for the next pivot search and swaps */
        for (int i = k + 1 + t; go && i < m; i += nt)
            for (int j = k + 1; j < i; j++) S[(long)j * m + i] = S[(long)i * m + j];
        GLPGP_SYNC();
        if (go) r = k + 1;
    }
    /* X = L11^-1 (unit lower triangular, r x r) into inv's lower part, column by column */
    for (long q = t; q < (long)m * m; q += nt) inv[q] = 0.0;
    GLPGP_SYNC();
    for (int c = t; c < r; c += nt) {
        inv[(long)c * m + c] = 1.0;
        for (int i = c + 1; i < r; i++) {
            double sum = 0.0;
            for (int j = c; j < i; j++) sum += S[(long)i * m + j] * inv[(long)j * m + c];
            inv[(long)i * m + c] = -sum;
        }
    }
    for (int k = t; k < r; k += nt) dinv[k] = 1.0 / fabs(S[(long)k * m + k]);
    GLPGP_SYNC();
    /* C = X^T |D|^-1 X (r x r):  C_ij = sum_{k >= max(i,j)} x_ki x_kj / |d_k|, in S's upper part */
    for (long q = t; q < (long)r * r; q += nt) {
        const int i = (int)(q / r), j = (int)(q % r);
        if (j < i) continue;
        double sum = 0.0;
        for (int k = j; k < r; k++) sum += inv[(long)k * m + i] * inv[(long)k * m + j] * dinv[k];
        S[(long)i * m + j] = sum;
    }
    GLPGP_SYNC();
    for (long q = t; q < (long)m * m; q += nt) inv[q] = 0.0;
    GLPGP_SYNC();
    for (long q = t; q < (long)r * r; q += nt) {
        const int i = (int)(q / r), j = (int)(q % r);
        if (j < i) continue;
        const double v = S[(long)i * m + j];
        inv[(long)perm[i] * m + perm[j]] = v;
        inv[(long)perm[j] * m + perm[i]] = v;
    }
    GLPGP_SYNC();
    return 0;
}

/* The coarse operator of the coarsest level (n nodes, CSR): expanded into
 * W's first m*m doubles, then its LU (spd = 0) or SPD (spd = 1) generalised
 * inverse into inv; the status (0 / 1) is returned. */
GLPGP_FN int glpgp_dense_coarse_invert(int t, int nt, int n, GLPGP_GLOBAL const int *rowptr, GLPGP_GLOBAL const int *col,
                                       GLPGP_GLOBAL const double *val, int spd, GLPGP_GLOBAL double *inv,
                                       GLPGP_GLOBAL double *W, GLPGP_GLOBAL int *I, GLPGP_LOCAL double *bv,
                                       GLPGP_LOCAL long *bi)
{
    const int m = 2 * n;
    glpgp_dense_expand(t, nt, n, rowptr, col, val, W);
    GLPGP_SYNC();
    return spd ? glpgp_dense_spd_inverse(t, nt, m, W, inv, W, I, bv, bi)
               : glpgp_dense_lu_inverse(t, nt, m, W, inv, W, I, bv, bi);
}

#endif
