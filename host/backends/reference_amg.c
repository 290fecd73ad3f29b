/* backends/reference_amg.c: the reference implementation of the multilevel
 * preconditioner's ops (amg_* in glpgp/backend.h): plain loops over host
 * arrays calling the per-row / per-aggregate / per-entry bodies of
 * kernels/amg_rows.h, the same functions the OpenCL kernels
 * (kernels/backend_multigrid.cl) call on their index ranges, so both store the
 * same bits. The hierarchy structure is copied at amg_setup (the "upload");
 * amg_values rebuilds every value from NEWTON and the frame vectors; the
 * cycle itself is driven by solver/amg.c through these ops. Every loop is a
 * gather (one output row, aggregate or coarse row per iteration, no
 * scatter). Dot products are one sequential sum (glpgp_range_dot). */
#include "amg_dense.h"
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
    /* transfer to level l+1 (levels < L-1) */
    int nc;              /* n_{l+1} */
    int *agg, *aptr, *amem;
    int *gptr, *gsrc;    /* Galerkin map of A_{l+1} (gather form, see backend.h) */
    double *c;           /* 2 n: complex prolongation weights */
    /* frame amplitude (levels >= 1); 0: dead coarse node */
    double *amp;         /* n */
} ref_level;

struct ref_amg {
    glpgp_amg_layout lay; /* the layout it was set up from (key and parameters) */
    int L;
    double weight; /* smoother weight */
    ref_level lev[GLPGP_AMG_MAX_LEVELS];
    int m;        /* order of the coarse operator, 2 n_{L-1} */
    double *cinv; /* m*m, row-major */
    double *dw;   /* GLPGP_DENSE_W(m): work of amg_coarse_invert (kernels/amg_dense.h) */
    int *di;      /* GLPGP_DENSE_I(m) */
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
        free(v->agg);
        free(v->aptr);
        free(v->amem);
        free(v->gptr);
        free(v->gsrc);
        free(v->c);
        free(v->amp);
    }
    free(a->cinv);
    free(a->dw);
    free(a->di);
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
    if (r->amg && glpgp_amg_layout_same(&r->amg->lay, lay)) return GLPGP_OK; /* holds it already */
    glpgp_ref_amg_free(r);
    GLPGP_CHECK(glpgp_calloc(1, sizeof(struct ref_amg), &r->amg));
    struct ref_amg *a = r->amg;
    glpgp_status st = GLPGP_OK;
    a->lay = *lay;
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
        }
        /* srow[k] <- row of slot k */
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)(v->nnzb ? v->nnzb : 1), sizeof(int), &v->srow), fail);
        for (int i = 0; i < v->n; i++)
            for (int k = v->rowptr[i]; k < v->rowptr[i + 1]; k++) v->srow[k] = i;
        if (l + 1 < a->L) {
            const glpgp_amg_level *nx = &lay->lev[l + 1];
            v->nc = nx->n;
            GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)4 * v->n, sizeof(double), &v->minv), fail);
            GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * v->n, sizeof(double), &v->c), fail);
            GLPGP_CHECK_GOTO(st, copy_ints(&v->agg, in->agg, (size_t)v->n), fail);
            GLPGP_CHECK_GOTO(st, copy_ints(&v->aptr, in->aptr, (size_t)v->nc + 1), fail);
            GLPGP_CHECK_GOTO(st, copy_ints(&v->amem, in->amem, (size_t)in->aptr[v->nc]), fail);
            GLPGP_CHECK_GOTO(st, copy_ints(&v->gptr, in->gptr, (size_t)nx->nnzb + 1), fail);
            GLPGP_CHECK_GOTO(st, copy_ints(&v->gsrc, in->gsrc, (size_t)in->gptr[nx->nnzb]), fail);
        }
    }
    a->m = 2 * a->lev[a->L - 1].n;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)a->m * a->m, sizeof(double), &a->cinv), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)GLPGP_DENSE_W(a->m), sizeof(double), &a->dw), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)GLPGP_DENSE_I(a->m) + 1, sizeof(int), &a->di), fail);
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
         * when none);  s_J = sqrt(sum_{i in J} |f_i|^2);  c_i = f_i / s_J
         * (nodes in no aggregate keep c = 0 from amg_setup) */
        for (int J = 0; J < v->nc; J++)
            glpgp_amg_agg_weights(J, v->aptr, v->amem, l > 0, v->amp, fr != NULL, fr, l == 0, r->dir, v->c, w->amp);
        /* A_{l+1}[K] = sum over the mapped level-l slots k = (i, j) of
         * P_i^T A_l[k] P_j (gather, increasing k); dead coarse node:
         * identity diagonal block */
        for (int I = 0; I < w->n; I++)
            glpgp_amg_galerkin_row(I, w->rowptr, w->diag, v->gptr, v->gsrc, v->srow, v->col, v->c, A, w->amp,
                                   w->val);
        /* M_l^-1 <- w (A_ii + sum_{j != i} ||A_ij||_2 I)^-1 */
        for (int i = 0; i < v->n; i++) glpgp_amg_l1_row(i, v->rowptr, v->diag, A, a->weight, v->minv);
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

glpgp_status glpgp_ref_amg_coarse_invert(glpgp_backend *b, int spd)
{
    struct ref_amg *a = AMG(b);
    if (!a) return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_coarse_invert before amg_setup");
    const ref_level *v = &a->lev[a->L - 1];
    /* the dense coarsest matrix and its inverse (kernels/amg_dense.h, one worker) */
    a->t[GLPGP_AMG_SLOT_STATUS] = glpgp_dense_coarse_invert(0, 1, v->n, v->rowptr, v->col,
                                                            level_val(IMPL(b), a->L - 1), spd, a->cinv, a->dw, a->di,
                                                            NULL, NULL);
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_smooth(glpgp_backend *b, int l, const glpgp_vec *r, const glpgp_vec *x,
                                  glpgp_vec *y)
{
    struct ref_amg *a = AMG(b);
    const ref_level *v = &a->lev[l];
    const double *A = level_val(IMPL(b), l);
    /* y_i <- x_i + M_i^-1 (r_i - (A x)_i) */
    for (int i = 0; i < v->n; i++)
        glpgp_amg_row_smooth(i, x != NULL, v->rowptr, v->col, A, v->minv, r->a, x ? x->a : NULL, y->a);
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_restrict(glpgp_backend *b, int l, const glpgp_vec *r,
                                    const glpgp_vec *x, glpgp_vec *rc)
{
    struct ref_amg *a = AMG(b);
    const ref_level *v = &a->lev[l];
    const double *A = level_val(IMPL(b), l);
    /* rc_J <- sum_{i in J} P_i^T (r_i - (A x)_i): rc <- 0, then the rows in
     * order, each added to its aggregate (the gather's sums, bit for bit) */
    for (int J = 0; J < 2 * v->nc; J++) rc->a[J] = 0.0;
    for (int i = 0; i < v->n; i++)
        glpgp_amg_row_restrict_scatter(i, v->agg, v->c, x != NULL, v->rowptr, v->col, A, r->a, x ? x->a : NULL,
                                       rc->a);
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_presmooth_restrict(glpgp_backend *b, int l, const glpgp_vec *r, glpgp_vec *y,
                                              glpgp_vec *rc)
{
    struct ref_amg *a = AMG(b);
    const ref_level *v = &a->lev[l];
    const double *A = level_val(IMPL(b), l);
    /* rows in order: y_i and t_i = r_i - (A y)_i, t added to its aggregate
     * (rc <- 0 first; members in increasing order: the gather's sums) */
    for (int J = 0; J < 2 * v->nc; J++) rc->a[J] = 0.0;
    for (int i = 0; i < v->n; i++) {
        double t0, t1;
        glpgp_amg_row_presmooth_resid(i, v->rowptr, v->col, A, v->minv, r->a, y->a, &t0, &t1);
        const int J = v->agg[i];
        if (J < 0) continue;
        double acc[2] = {rc->a[2 * J], rc->a[2 * J + 1]};
        glpgp_amg_restrict_add(v->c[2 * i], v->c[2 * i + 1], t0, t1, acc);
        rc->a[2 * J] = acc[0];
        rc->a[2 * J + 1] = acc[1];
    }
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_prolong_smooth(glpgp_backend *b, int l, const glpgp_vec *ec, const glpgp_vec *x,
                                          const glpgp_vec *r, glpgp_vec *y)
{
    struct ref_amg *a = AMG(b);
    const ref_level *v = &a->lev[l];
    const double *A = level_val(IMPL(b), l);
    for (int i = 0; i < v->n; i++)
        glpgp_amg_row_prolong_smooth(i, v->agg, v->c, ec->a, v->rowptr, v->col, A, v->minv, r->a, x->a, y->a);
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_prolong(glpgp_backend *b, int l, const glpgp_vec *ec, glpgp_vec *x)
{
    struct ref_amg *a = AMG(b);
    const ref_level *v = &a->lev[l];
    /* x_i <- x_i + P_i ec_agg(i) */
    for (int i = 0; i < v->n; i++) glpgp_amg_row_prolong(i, v->agg, v->c, ec->a, x->a);
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_coarse_solve(glpgp_backend *b, const glpgp_vec *r, glpgp_vec *x)
{
    struct ref_amg *a = AMG(b);
    /* x <- C r (dense) */
    for (int i = 0; i < a->m; i++) glpgp_amg_row_dense(i, a->m, a->cinv, r->a, x->a);
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_spmv_dots(glpgp_backend *b, int l, const glpgp_vec *x, glpgp_vec *y,
                                     const glpgp_vec *u, const glpgp_vec *w, int slot)
{
    struct ref_amg *a = AMG(b);
    const ref_level *v = &a->lev[l];
    const double *A = level_val(IMPL(b), l);
    /* y <- A_l x;  t[slot] <- x.y;  t[slot+1] <- x.u;  t[slot+2] <- x.w */
    for (int i = 0; i < v->n; i++) glpgp_row_spmv_store(i, v->rowptr, v->col, A, x->a, y->a);
    a->t[slot] = glpgp_range_dot(0, (long)x->n, x->a, y->a);
    if (u) a->t[slot + 1] = glpgp_range_dot(0, (long)x->n, x->a, u->a);
    if (w) a->t[slot + 2] = glpgp_range_dot(0, (long)x->n, x->a, w->a);
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_dots(glpgp_backend *b, const glpgp_vec *x, const glpgp_vec *u,
                                const glpgp_vec *w, int slot)
{
    struct ref_amg *a = AMG(b);
    if (u) a->t[slot] = glpgp_range_dot(0, (long)x->n, x->a, u->a);
    if (w) a->t[slot + 1] = glpgp_range_dot(0, (long)x->n, x->a, w->a);
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_axpby(glpgp_backend *b, glpgp_amg_coef ca, const glpgp_vec *x,
                                 glpgp_amg_coef cc, glpgp_vec *y)
{
    struct ref_amg *a = AMG(b);
    const double p = glpgp_amg_coef_value(a->t, ca.num, ca.den, ca.sign);
    const double q = glpgp_amg_coef_value(a->t, cc.num, cc.den, cc.sign);
    /* y <- p x + q y; a zero coefficient does not read its vector (so
     * y <- 0 x + 0 y clears a y that holds NaN) */
    for (size_t i = 0; i < y->n; i++) glpgp_amg_entry_axpby((long)i, p, x->a, q, y->a);
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
    for (size_t i = 0; i < e->n; i++) glpgp_amg_entry_kcombine((long)i, c[0], c[1], v->a, d->a, e->a);
    return GLPGP_OK;
}

glpgp_status glpgp_ref_amg_get_scalars(glpgp_backend *b, double *out, int n)
{
    struct ref_amg *a = AMG(b);
    if (n > GLPGP_AMG_NSLOTS) n = GLPGP_AMG_NSLOTS;
    memcpy(out, a->t, (size_t)n * sizeof(double));
    return GLPGP_OK;
}
