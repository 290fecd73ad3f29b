/* backends/reference_amg.c: the reference implementation of the multilevel
 * preconditioner's ops (amg_* in glpgp/backend.h): plain loops over host
 * arrays, the per-block arithmetic shared through amg_rows.h. The hierarchy
 * structure is copied at amg_setup (the "upload"); amg_values rebuilds every
 * value from NEWTON and the frame vectors; the cycle itself is driven by
 * solver/amg.c through these ops. Every loop is a gather (one output row per
 * iteration, no scatter), so an OpenCL kernel can run one work-item per row,
 * coarse node or coarse block with the same summation order. */
#include "amg_rows.h"
#include "reference_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct ref_level {
    int n;               /* nodes */
    long nnzb;           /* blocks of A_l */
    const int *rowptr, *col, *diag; /* pattern (level 0: the system's) */
    int *own_rowptr, *own_col, *own_diag;
    int *srow;           /* nnzb: row of each slot (for the Galerkin map) */
    double *val;         /* 4 nnzb (levels >= 1; level 0 is NEWTON) */
    double *minv;        /* 4 n: l1 block-Jacobi inverse (levels < L-1) */
    double *res;         /* 2 n: residual scratch of amg_restrict */
    /* transfer to level l+1 (levels < L-1) */
    int nc;              /* n_{l+1} */
    int *agg, *aptr, *amem;
    int *kmap;           /* nnzb: coarse slot of each slot (-1: none): the inverse of
                            the layout's gather map gptr/gsrc */
    double *c;           /* 2 n: complex prolongation weights */
    /* frame amplitude (levels >= 1) and dead coarse nodes */
    double *amp;         /* n */
    unsigned char *dead; /* n */
} ref_level;

struct ref_amg {
    int L;
    double weight; /* smoother weight */
    ref_level lev[GLPGP_AMG_MAX_LEVELS];
    int m;        /* order of the coarse operator, 2 n_{L-1} */
    double *cinv; /* m*m, row-major */
    double t[GLPGP_AMG_NSLOTS];
};

#define AMG(b) (IMPL(b)->amg)

void glpgp_ref_amg_free(ref_impl *r)
{
    struct ref_amg *a = r->amg;
    if (!a) return;
    for (int l = 0; l < GLPGP_AMG_MAX_LEVELS; l++) {
        ref_level *v = &a->lev[l];
        free(v->own_rowptr);
        free(v->own_col);
        free(v->own_diag);
        free(v->srow);
        free(v->val);
        free(v->minv);
        free(v->res);
        free(v->agg);
        free(v->aptr);
        free(v->amem);
        free(v->kmap);
        free(v->c);
        free(v->amp);
        free(v->dead);
    }
    free(a->cinv);
    free(a);
    r->amg = NULL;
}

/* *dst <- copy of n ints (n may be 0: a 1-element buffer) */
static glpgp_status copy_ints(int **dst, const int *src, size_t n)
{
    GLPGP_CHECK(glpgp_malloc(n ? n : 1, sizeof(int), dst));
    if (n) memcpy(*dst, src, n * sizeof(int));
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_setup(glpgp_backend *b, const glpgp_amg_layout *lay)
{
    ref_impl *r = IMPL(b);
    const glpgp_system *sys = r->sys;
    if (!sys) return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_setup before setup");
    if (lay->nlevels < 2 || lay->nlevels > GLPGP_AMG_MAX_LEVELS)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_setup: %d levels", lay->nlevels);
    if (lay->lev[0].n != sys->nv || lay->lev[0].nnzb != sys->nnzb)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_setup: level 0 is not the system");
    glpgp_ref_amg_free(r);
    GLPGP_CHECK(glpgp_calloc(1, sizeof(struct ref_amg), &r->amg));
    struct ref_amg *a = r->amg;
    glpgp_status st = GLPGP_OK;
    a->L = lay->nlevels;
    a->weight = lay->weight;
    if (!(a->weight > 0.0 && a->weight < 2.0)) {
        st = GLPGP_FAIL(GLPGP_ERR_ARG, "amg_setup: smoother weight %g not in (0, 2)", a->weight);
        goto fail;
    }
    for (int l = 0; l < a->L; l++) {
        const glpgp_amg_level *in = &lay->lev[l];
        ref_level *v = &a->lev[l];
        v->n = in->n;
        v->nnzb = in->nnzb;
        if (l == 0) {
            v->rowptr = sys->rowptr;
            v->col = sys->col;
            v->diag = sys->diag;
        } else {
            GLPGP_CHECK_GOTO(st, copy_ints(&v->own_rowptr, in->rowptr, (size_t)v->n + 1), fail);
            GLPGP_CHECK_GOTO(st, copy_ints(&v->own_col, in->col, (size_t)v->nnzb), fail);
            GLPGP_CHECK_GOTO(st, copy_ints(&v->own_diag, in->diag, (size_t)v->n), fail);
            v->rowptr = v->own_rowptr;
            v->col = v->own_col;
            v->diag = v->own_diag;
            GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)4 * v->nnzb, sizeof(double), &v->val), fail);
            GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)v->n, sizeof(double), &v->amp), fail);
            GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)v->n, 1, &v->dead), fail);
        }
        /* srow[k] <- row of slot k */
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)(v->nnzb ? v->nnzb : 1), sizeof(int), &v->srow), fail);
        for (int i = 0; i < v->n; i++)
            for (int k = v->rowptr[i]; k < v->rowptr[i + 1]; k++) v->srow[k] = i;
        if (l + 1 < a->L) {
            const glpgp_amg_level *nx = &lay->lev[l + 1];
            v->nc = nx->n;
            GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)4 * v->n, sizeof(double), &v->minv), fail);
            GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * v->n, sizeof(double), &v->res), fail);
            GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * v->n, sizeof(double), &v->c), fail);
            GLPGP_CHECK_GOTO(st, copy_ints(&v->agg, in->agg, (size_t)v->n), fail);
            GLPGP_CHECK_GOTO(st, copy_ints(&v->aptr, in->aptr, (size_t)v->nc + 1), fail);
            GLPGP_CHECK_GOTO(st, copy_ints(&v->amem, in->amem, (size_t)in->aptr[v->nc]), fail);
            GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)(v->nnzb ? v->nnzb : 1), sizeof(int), &v->kmap), fail);
            for (long k = 0; k < v->nnzb; k++) v->kmap[k] = -1;
            for (long K = 0; K < nx->nnzb; K++)
                for (int q = in->gptr[K]; q < in->gptr[K + 1]; q++) v->kmap[in->gsrc[q]] = (int)K;
        }
    }
    a->m = 2 * a->lev[a->L - 1].n;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)a->m * a->m, sizeof(double), &a->cinv), fail);
    return GLPGP_OK;
fail:
    glpgp_ref_amg_free(r);
    return st;
}

/* values of A_l */
static const double *level_val(const ref_impl *r, int l)
{
    return l == 0 ? r->newton : r->amg->lev[l].val;
}

glpgp_status glpgp_ref_amg_values(glpgp_backend *b, const glpgp_vec *const *frames)
{
    ref_impl *r = IMPL(b);
    struct ref_amg *a = r->amg;
    if (!a) return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_values before amg_setup");
    for (int l = 0; l + 1 < a->L; l++) {
        ref_level *v = &a->lev[l], *w = &a->lev[l + 1];
        const double *A = level_val(r, l);
        const double *fr = frames[l] ? frames[l]->a : NULL;
        if (frames[l] && frames[l]->n != (size_t)2 * v->n)
            return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_values: frame %d has the wrong length", l);
        /* per aggregate J: f_i = a_i * frame_i (a = 1 on level 0, frame = 1
         * when none);  s_J = sqrt(sum_{i in J} |f_i|^2);  c_i = f_i / s_J */
        for (int J = 0; J < v->nc; J++) {
            double ss = 0.0;
            for (int p = v->aptr[J]; p < v->aptr[J + 1]; p++) {
                int i = v->amem[p];
                double am = l == 0 ? 1.0 : v->amp[i];
                double fx = fr ? am * fr[2 * i] : am, fy = fr ? am * fr[2 * i + 1] : 0.0;
                ss += fx * fx + fy * fy;
            }
            double s = sqrt(ss);
            int dead = !(s > 0.0) || !isfinite(s);
            w->amp[J] = dead ? 0.0 : s;
            w->dead[J] = (unsigned char)dead;
            for (int p = v->aptr[J]; p < v->aptr[J + 1]; p++) {
                int i = v->amem[p];
                double am = l == 0 ? 1.0 : v->amp[i];
                double fx = fr ? am * fr[2 * i] : am, fy = fr ? am * fr[2 * i + 1] : 0.0;
                v->c[2 * i] = dead ? 0.0 : fx / s;
                v->c[2 * i + 1] = dead ? 0.0 : fy / s;
            }
        }
        for (int i = 0; i < v->n; i++)
            if (v->agg[i] < 0) v->c[2 * i] = v->c[2 * i + 1] = 0.0;
        /* A_{l+1}[K] = sum over the mapped level-l slots k = (i, j) of
         * P_i^T A_l[k] P_j.  The reference streams A_l in slot order and adds
         * into K = kmap[k]: per K this is the increasing-k order of the gather
         * map gsrc, so a gather kernel (one work-item per K) gives the same
         * bits. Dead coarse node: identity diagonal block. */
        memset(w->val, 0, 4 * (size_t)w->nnzb * sizeof(double));
        for (int i = 0; i < v->n; i++) {
            const double ir = v->c[2 * i], ii = v->c[2 * i + 1];
            for (int k = v->rowptr[i]; k < v->rowptr[i + 1]; k++) {
                const int K = v->kmap[k];
                if (K < 0) continue;
                const int j = v->col[k];
                glpgp_amg_ptap(ir, ii, A + 4 * (size_t)k, v->c[2 * j], v->c[2 * j + 1],
                               w->val + 4 * (size_t)K);
            }
        }
        for (int J = 0; J < w->n; J++)
            if (w->dead[J]) {
                double *d = w->val + 4 * (size_t)w->diag[J];
                d[0] = d[3] = 1.0;
                d[1] = d[2] = 0.0;
            }
        /* M_l^-1 <- w (A_ii + sum_{j != i} ||A_ij||_2 I)^-1 */
        for (int i = 0; i < v->n; i++) {
            double s = 0.0;
            for (int k = v->rowptr[i]; k < v->rowptr[i + 1]; k++)
                if (k != v->diag[i]) s += glpgp_amg_norm2(A + 4 * (size_t)k);
            glpgp_amg_l1_inverse(A + 4 * (size_t)v->diag[i], s, a->weight, v->minv + 4 * (size_t)i);
        }
    }
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_coarse_read(glpgp_backend *b, double *dense)
{
    struct ref_amg *a = AMG(b);
    const ref_level *v = &a->lev[a->L - 1];
    const double *A = level_val(IMPL(b), a->L - 1);
    const int m = a->m;
    memset(dense, 0, (size_t)m * m * sizeof(double));
    /* dense[2I + p][2J + q] <- A[K](p, q) for every block K = (I, J) */
    for (int I = 0; I < v->n; I++)
        for (int K = v->rowptr[I]; K < v->rowptr[I + 1]; K++) {
            int J = v->col[K];
            for (int p = 0; p < 2; p++)
                for (int q = 0; q < 2; q++)
                    dense[(size_t)(2 * I + p) * m + 2 * J + q] = A[4 * (size_t)K + 2 * p + q];
        }
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_coarse_set(glpgp_backend *b, const double *inv)
{
    struct ref_amg *a = AMG(b);
    memcpy(a->cinv, inv, (size_t)a->m * a->m * sizeof(double));
    return GLPGP_OK;
}

/* (A_l x)_i, 2 components */
static void row_product(const ref_level *v, const double *A, const double *x, int i, double *y)
{
    double y0 = 0.0, y1 = 0.0;
    for (int k = v->rowptr[i]; k < v->rowptr[i + 1]; k++) {
        const double *blk = A + 4 * (size_t)k;
        const double *xj = x + 2 * (size_t)v->col[k];
        y0 += blk[0] * xj[0] + blk[1] * xj[1];
        y1 += blk[2] * xj[0] + blk[3] * xj[1];
    }
    y[0] = y0;
    y[1] = y1;
}

glpgp_status glpgp_ref_amg_smooth(glpgp_backend *b, int l, const glpgp_vec *r, const glpgp_vec *x,
                                  glpgp_vec *y)
{
    struct ref_amg *a = AMG(b);
    const ref_level *v = &a->lev[l];
    const double *A = level_val(IMPL(b), l);
    /* y_i <- x_i + M_i^-1 (r_i - (A x)_i) */
    for (int i = 0; i < v->n; i++) {
        double ax[2] = {0.0, 0.0}, x0 = 0.0, x1 = 0.0;
        if (x) {
            row_product(v, A, x->a, i, ax);
            x0 = x->a[2 * i];
            x1 = x->a[2 * i + 1];
        }
        glpgp_amg_smooth_row(v->minv + 4 * (size_t)i, r->a[2 * i], r->a[2 * i + 1], ax[0], ax[1], x0,
                             x1, y->a + 2 * (size_t)i);
    }
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_restrict(glpgp_backend *b, int l, const glpgp_vec *r,
                                    const glpgp_vec *x, glpgp_vec *rc)
{
    struct ref_amg *a = AMG(b);
    const ref_level *v = &a->lev[l];
    const double *A = level_val(IMPL(b), l);
    /* res <- r - A x, row by row (streams A in order), then
     * rc_J <- sum_{i in J} P_i^T res_i  (gather over the members) */
    const double *t = r->a;
    if (x) {
        for (int i = 0; i < v->n; i++) {
            double ax[2];
            row_product(v, A, x->a, i, ax);
            v->res[2 * i] = r->a[2 * i] - ax[0];
            v->res[2 * i + 1] = r->a[2 * i + 1] - ax[1];
        }
        t = v->res;
    }
    for (int J = 0; J < v->nc; J++) {
        double acc[2] = {0.0, 0.0};
        for (int p = v->aptr[J]; p < v->aptr[J + 1]; p++) {
            int i = v->amem[p];
            glpgp_amg_restrict_add(v->c[2 * i], v->c[2 * i + 1], t[2 * i], t[2 * i + 1], acc);
        }
        rc->a[2 * J] = acc[0];
        rc->a[2 * J + 1] = acc[1];
    }
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_prolong(glpgp_backend *b, int l, const glpgp_vec *ec, glpgp_vec *x)
{
    struct ref_amg *a = AMG(b);
    const ref_level *v = &a->lev[l];
    /* x_i <- x_i + P_i ec_agg(i) */
    for (int i = 0; i < v->n; i++) {
        int J = v->agg[i];
        if (J < 0) continue;
        glpgp_amg_prolong_add(v->c[2 * i], v->c[2 * i + 1], ec->a[2 * J], ec->a[2 * J + 1],
                              x->a + 2 * (size_t)i);
    }
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_coarse_solve(glpgp_backend *b, const glpgp_vec *r, glpgp_vec *x)
{
    struct ref_amg *a = AMG(b);
    const int m = a->m;
    /* x <- C r (dense) */
    for (int i = 0; i < m; i++) {
        const double *ci = a->cinv + (size_t)i * m;
        double s = 0.0;
        for (int j = 0; j < m; j++) s += ci[j] * r->a[j];
        x->a[i] = s;
    }
    return GLPGP_OK;
}

static double dot_n(const double *x, const double *y, size_t n)
{
    double s = 0.0;
    for (size_t i = 0; i < n; i++) s += x[i] * y[i];
    return s;
}

glpgp_status glpgp_ref_amg_spmv_dots(glpgp_backend *b, int l, const glpgp_vec *x, glpgp_vec *y,
                                     const glpgp_vec *u, const glpgp_vec *w, int slot)
{
    struct ref_amg *a = AMG(b);
    const ref_level *v = &a->lev[l];
    const double *A = level_val(IMPL(b), l);
    /* y <- A_l x;  t[slot] <- x.y;  t[slot+1] <- x.u;  t[slot+2] <- x.w */
    for (int i = 0; i < v->n; i++) row_product(v, A, x->a, i, y->a + 2 * (size_t)i);
    a->t[slot] = dot_n(x->a, y->a, x->n);
    if (u) a->t[slot + 1] = dot_n(x->a, u->a, x->n);
    if (w) a->t[slot + 2] = dot_n(x->a, w->a, x->n);
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_dots(glpgp_backend *b, const glpgp_vec *x, const glpgp_vec *u,
                                const glpgp_vec *w, int slot)
{
    struct ref_amg *a = AMG(b);
    if (u) a->t[slot] = dot_n(x->a, u->a, x->n);
    if (w) a->t[slot + 1] = dot_n(x->a, w->a, x->n);
    return GLPGP_OK;
}

static double coef(const struct ref_amg *a, glpgp_amg_coef c)
{
    return c.num < 0 ? c.sign : glpgp_amg_ratio(c.sign, a->t[c.num], a->t[c.den]);
}

glpgp_status glpgp_ref_amg_axpby(glpgp_backend *b, glpgp_amg_coef ca, const glpgp_vec *x,
                                 glpgp_amg_coef cc, glpgp_vec *y)
{
    struct ref_amg *a = AMG(b);
    const double p = coef(a, ca), q = coef(a, cc);
    /* y <- p x + q y; a zero coefficient does not read its vector (so
     * y <- 0 x + 0 y clears a y that holds NaN) */
    for (size_t i = 0; i < y->n; i++) {
        double v = 0.0;
        if (p != 0.0) v += p * x->a[i];
        if (q != 0.0) v += q * y->a[i];
        y->a[i] = v;
    }
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_kcombine(glpgp_backend *b, const glpgp_vec *v, const glpgp_vec *d,
                                    glpgp_vec *e, int slot)
{
    struct ref_amg *a = AMG(b);
    const double *t = a->t + slot;
    double c[2];
    glpgp_amg_kcoef(t[0], t[1], t[2], t[3], t[4], c);
    /* e <- c0 v + c1 d  (c1 = 0: d is not read) */
    if (c[1] == 0.0)
        for (size_t i = 0; i < e->n; i++) e->a[i] = c[0] * v->a[i];
    else
        for (size_t i = 0; i < e->n; i++) e->a[i] = c[0] * v->a[i] + c[1] * d->a[i];
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_get_scalars(glpgp_backend *b, double *out, int n)
{
    struct ref_amg *a = AMG(b);
    if (n > GLPGP_AMG_NSLOTS) n = GLPGP_AMG_NSLOTS;
    memcpy(out, a->t, (size_t)n * sizeof(double));
    return GLPGP_OK;
}
