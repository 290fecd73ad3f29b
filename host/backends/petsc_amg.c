/* backends/petsc_amg.c: the PETSc backend's multigrid ops (amg_* of
 * glpgp/backend.h): glpgp's own aggregation multigrid (solver/amg.c drives
 * the cycle and the flexible CG) on each rank's rows, the default
 * preconditioner of `--backend petsc` (GAMG stays behind -glpgp_mg gamg,
 * petsc_ksp.c).
 *
 * Every rank instantiates the hierarchy structure built on its own system
 * (its part of the mesh, or the whole mesh with a slice of owned rows):
 *  - level 0 is NEWTON on the owned rows with all their columns (the ghost
 *    values come by one VecScatter before a smoothing sweep or a residual
 *    that reads an iterate): the smoother and the fine residual are the
 *    global operator's, as on one process;
 *  - the coarse levels are the rank's alone (block Jacobi across ranks): a
 *    level-0 aggregate keeps only its owned members, the Galerkin map only
 *    the slots of owned rows and owned columns; an aggregate with no owned
 *    member is dead (identity row). Coarse vectors are sequential Vecs,
 *    their dot products (the K-cycle's coefficients) local;
 *  - with more than one rank the fine level's coarse correction adds a
 *    global coarse term (petsc_gc.c: aggregates of one level of every
 *    rank's hierarchy, E = Z^T A Z inverted on every rank).
 * Level-0 dot products are reduced over the ranks (partials added in rank
 * order: every rank takes the same decisions), the coarse solve's status
 * too. The arithmetic is the per-row code of kernels/amg_rows.h (the
 * reference backend's, not a copy), on one rank in the reference's order:
 * one PETSc rank gives the reference backend's iterates bit for bit. */
#include "amg_dense.h"
#include "amg_rows.h"
#include "rows.h"

#include "petsc_gc.h"
#include "petsc_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct pm_level {
    int n;
    long nnzb;
    const int *rowptr, *col, *diag; /* level 0: the system's */
    int *own_rowptr, *own_col, *own_diag;
    int *srowb;   /* row of each slot (level 0: the owned slots, shifted base below) */
    double *val;  /* 4 nnzb (levels >= 1; level 0 is NEWTON) */
    double *minvb;/* 4 n (level 0: the owned rows) */
    double *cb;   /* 2 n (level 0: the owned rows) */
    int nc;
    int *agg, *aptr, *amem, *gptr, *gsrc;
    double *amp;  /* n (levels >= 1) */
} pm_level;

struct petsc_amg {
    /* what the layout said (the check that a new layout is the same) */
    const void *key;
    double weight;
    int pre, post;
    unsigned char kcycle[GLPGP_AMG_MAX_LEVELS];
    int L;
    pm_level lev[GLPGP_AMG_MAX_LEVELS];
    int m;
    double *cinv, *dw;
    int *di;
    double t[GLPGP_AMG_NSLOTS];
    pm_gc *gc;       /* the global coarse space (more than one rank; petsc_gc.h), or NULL */
};

/* level-l arrays indexed by the level's node numbers (level 0: system
 * vertices, valid on the owned rows) */
static const int *SROW(const pimpl *p, const pm_level *v, int l) { return l ? v->srowb : v->srowb - p->slo; }
static double *MINV(const pimpl *p, pm_level *v, int l) { return l ? v->minvb : v->minvb - 4 * (long)p->lo; }
static double *CW(const pimpl *p, pm_level *v, int l) { return l ? v->cb : v->cb - 2 * (long)p->lo; }
static const double *LVAL(const pimpl *p, const pm_level *v, int l) { return l ? v->val : NEWT(p); }

/* ---- the global coarse space (more than one rank; petsc_gc.c) ------------- */

/* the levels' aggregate maps and weights as petsc_gc.c reads them (level 0
 * indexed by system vertex) */
static void level_maps(const pimpl *p, struct petsc_amg *a, const int **agg, int *n, const double **c)
{
    for (int l = 0; l < a->L; l++) {
        pm_level *v = &a->lev[l];
        agg[l] = v->agg;
        n[l] = v->n;
        if (c) c[l] = l + 1 < a->L ? CW(p, v, l) : NULL;
    }
}

/* level-0 restriction with the global term: one node per rank (k = 0, the
 * default): y = E^+ Z^T t beside the local restriction of t = r - A x, the
 * two corrections added; one level's aggregates (k > 0): y first, then the
 * local restriction of t - A Z y (bench/results/petsc_glpgp_amg.md) */
static glpgp_status gc_restrict(pimpl *p, struct petsc_amg *a, const pm_level *v, const double *c, int has_x,
                                const double *A, const double *rr, const double *xs, double *rc)
{
    pm_gc *g = a->gc;
    double *T = g->tbuf;
    memset(g->yl, 0, (size_t)2 * g->ms * sizeof(double));
    if (g->k == 0) { /* one node per rank: added to the local correction, one pass */
        for (int i = p->lo; i < p->hi; i++) {
            const int J = v->agg[i];
            if (J < 0) continue;
            double t0, t1;
            glpgp_amg_row_resid(i, has_x, v->rowptr, v->col, A, rr, xs, &t0, &t1);
            double acc[2] = {rc[2 * J], rc[2 * J + 1]};
            glpgp_amg_restrict_add(c[2 * i], c[2 * i + 1], t0, t1, acc);
            rc[2 * J] = acc[0];
            rc[2 * J + 1] = acc[1];
            glpgp_petsc_gc_add(g, i - p->lo, t0, t1);
        }
        return glpgp_petsc_gc_solve(g);
    }
    for (int i = p->lo; i < p->hi; i++) {
        double t0, t1;
        glpgp_amg_row_resid(i, has_x, v->rowptr, v->col, A, rr, xs, &t0, &t1);
        T[2 * (i - p->lo)] = t0;
        T[2 * (i - p->lo) + 1] = t1;
        glpgp_petsc_gc_add(g, i - p->lo, t0, t1);
    }
    GLPGP_CHECK(glpgp_petsc_gc_solve(g));
    GLPGP_CHECK(glpgp_petsc_gc_zy(p, g)); /* xf[1] <- Z y at owned and ghost vertices */
    const double *w = p->xf[1];
    for (int i = p->lo; i < p->hi; i++) {
        const int J = v->agg[i];
        if (J < 0) continue;
        double aw0, aw1;
        glpgp_row_spmv(i, v->rowptr, v->col, A, w, &aw0, &aw1);
        double acc[2] = {rc[2 * J], rc[2 * J + 1]};
        glpgp_amg_restrict_add(c[2 * i], c[2 * i + 1], T[2 * (i - p->lo)] - aw0, T[2 * (i - p->lo) + 1] - aw1, acc);
        rc[2 * J] = acc[0];
        rc[2 * J + 1] = acc[1];
    }
    return GLPGP_OK;
}

/* level-0 prolongation with the global term after it: w = P ec, then
 * x += w + Z (y - E^+ Z^T A w), y = E^+ Z^T t from the restriction. With
 * Q = Z E^+ Z^T and C the local coarse levels' correction, the visit's
 * coarse correction is the balancing form Q + (I - Q A) C (I - A Q):
 * symmetric when C is, as the trust region's cycle needs. */
static glpgp_status gc_prolong(pimpl *p, struct petsc_amg *a, const pm_level *v, const double *c, const double *ec,
                                   double *x)
{
    pm_gc *g = a->gc;
    double *w = g->tbuf2;
    for (int i = p->lo; i < p->hi; i++) {
        double xi[2] = {0.0, 0.0};
        const int J = v->agg[i];
        if (J >= 0) glpgp_amg_prolong_add(c[2 * i], c[2 * i + 1], ec[2 * J], ec[2 * J + 1], xi);
        w[2 * (i - p->lo)] = xi[0];
        w[2 * (i - p->lo) + 1] = xi[1];
    }
    GLPGP_CHECK(glpgp_petsc_gc_exchange(p, g, w));
    memcpy(g->ysave, g->yl, (size_t)2 * g->ms * sizeof(double));
    memset(g->yl, 0, (size_t)2 * g->ms * sizeof(double));
    const double *A = NEWT(p), *wg = p->xf[1];
    for (int i = p->lo; i < p->hi; i++) {
        double aw0, aw1;
        glpgp_row_spmv(i, v->rowptr, v->col, A, wg, &aw0, &aw1);
        glpgp_petsc_gc_add(g, i - p->lo, aw0, aw1);
    }
    GLPGP_CHECK(glpgp_petsc_gc_solve(g));
    for (int q = 0; q < 2 * g->ms; q++) g->yl[q] = g->ysave[q] - g->yl[q];
    for (int i = p->lo; i < p->hi; i++) {
        x[2 * i] += w[2 * (i - p->lo)];
        x[2 * i + 1] += w[2 * (i - p->lo) + 1];
    }
    glpgp_petsc_gc_prolong(p, g, x);
    return GLPGP_OK;
}

void glpgp_petsc_amg_free(pimpl *p)
{
    struct petsc_amg *a = p->amg;
    if (!a) return;
    for (int l = 0; l < GLPGP_AMG_MAX_LEVELS; l++) {
        pm_level *v = &a->lev[l];
        free(v->own_rowptr);
        free(v->own_col);
        free(v->own_diag);
        free(v->srowb);
        free(v->val);
        free(v->minvb);
        free(v->cb);
        free(v->agg);
        free(v->aptr);
        free(v->amem);
        free(v->gptr);
        free(v->gsrc);
        free(v->amp);
    }
    free(a->cinv);
    free(a->dw);
    free(a->di);
    glpgp_petsc_gc_destroy(&a->gc);
    free(a);
    p->amg = NULL;
}

static glpgp_status copy_ints(int **dst, const int *src, size_t n)
{
    GLPGP_CHECK(glpgp_malloc(n ? n : 1, sizeof(int), dst));
    if (n) memcpy(*dst, src, n * sizeof(int));
    return GLPGP_OK;
}

static int same_layout(const struct petsc_amg *a, const glpgp_amg_layout *lay)
{
    if (!a || !lay->key || a->key != lay->key || a->L != lay->nlevels || a->weight != lay->weight ||
        a->pre != lay->pre || a->post != lay->post)
        return 0;
    for (int l = 0; l < a->L; l++)
        if (a->lev[l].n != lay->lev[l].n || a->lev[l].nnzb != lay->lev[l].nnzb || a->kcycle[l] != lay->kcycle[l])
            return 0;
    return 1;
}

/* level 0's transfer, restricted to the owned vertices: agg (-1 off the
 * rank), the owned members of each aggregate, the Galerkin map's slots of
 * owned rows and owned columns (increasing order kept) */
static glpgp_status setup_level0(pimpl *p, pm_level *v, const glpgp_amg_level *in, const glpgp_amg_level *nx)
{
    const glpgp_system *sys = p->sys;
    const int lo = p->lo, hi = p->hi, nown = hi - lo;
    const long nslot = p->shi - p->slo;
    v->rowptr = sys->rowptr;
    v->col = sys->col;
    v->diag = sys->diag;
    GLPGP_CHECK(glpgp_malloc((size_t)(nslot > 0 ? nslot : 1), sizeof(int), &v->srowb));
    for (int i = lo; i < hi; i++)
        for (int k = sys->rowptr[i]; k < sys->rowptr[i + 1]; k++) v->srowb[k - p->slo] = i;
    GLPGP_CHECK(glpgp_calloc((size_t)4 * (nown > 0 ? nown : 1), sizeof(double), &v->minvb));
    GLPGP_CHECK(glpgp_calloc((size_t)2 * (nown > 0 ? nown : 1), sizeof(double), &v->cb));
    GLPGP_CHECK(copy_ints(&v->agg, in->agg, (size_t)v->n));
    for (int i = 0; i < v->n; i++)
        if (i < lo || i >= hi) v->agg[i] = -1;
    const int nc = v->nc;
    GLPGP_CHECK(glpgp_malloc((size_t)nc + 1, sizeof(int), &v->aptr));
    GLPGP_CHECK(glpgp_malloc((size_t)(in->aptr[nc] > 0 ? in->aptr[nc] : 1), sizeof(int), &v->amem));
    int na = 0;
    for (int J = 0; J < nc; J++) {
        v->aptr[J] = na;
        for (int q = in->aptr[J]; q < in->aptr[J + 1]; q++)
            if (in->amem[q] >= lo && in->amem[q] < hi) v->amem[na++] = in->amem[q];
    }
    v->aptr[nc] = na;
    const long nb = nx->nnzb;
    GLPGP_CHECK(glpgp_malloc((size_t)nb + 1, sizeof(int), &v->gptr));
    GLPGP_CHECK(glpgp_malloc((size_t)(in->gptr[nb] > 0 ? in->gptr[nb] : 1), sizeof(int), &v->gsrc));
    int ng = 0;
    for (long K = 0; K < nb; K++) {
        v->gptr[K] = ng;
        for (int q = in->gptr[K]; q < in->gptr[K + 1]; q++) {
            const int k = in->gsrc[q];
            if (k >= p->slo && k < p->shi && sys->col[k] >= lo && sys->col[k] < hi) v->gsrc[ng++] = k;
        }
    }
    v->gptr[nb] = ng;
    return GLPGP_OK;
}

static glpgp_status setup_coarse(pm_level *v, const glpgp_amg_level *in)
{
    GLPGP_CHECK(copy_ints(&v->own_rowptr, in->rowptr, (size_t)v->n + 1));
    GLPGP_CHECK(copy_ints(&v->own_col, in->col, (size_t)v->nnzb));
    GLPGP_CHECK(copy_ints(&v->own_diag, in->diag, (size_t)v->n));
    v->rowptr = v->own_rowptr;
    v->col = v->own_col;
    v->diag = v->own_diag;
    GLPGP_CHECK(glpgp_calloc((size_t)4 * (v->nnzb ? v->nnzb : 1), sizeof(double), &v->val));
    GLPGP_CHECK(glpgp_calloc((size_t)(v->n ? v->n : 1), sizeof(double), &v->amp));
    GLPGP_CHECK(glpgp_malloc((size_t)(v->nnzb ? v->nnzb : 1), sizeof(int), &v->srowb));
    for (int i = 0; i < v->n; i++)
        for (int k = v->rowptr[i]; k < v->rowptr[i + 1]; k++) v->srowb[k] = i;
    return GLPGP_OK;
}

static glpgp_status setup_transfer(pm_level *v, const glpgp_amg_level *in, const glpgp_amg_level *nx)
{
    GLPGP_CHECK(glpgp_calloc((size_t)4 * (v->n ? v->n : 1), sizeof(double), &v->minvb));
    GLPGP_CHECK(glpgp_calloc((size_t)2 * (v->n ? v->n : 1), sizeof(double), &v->cb));
    GLPGP_CHECK(copy_ints(&v->agg, in->agg, (size_t)v->n));
    GLPGP_CHECK(copy_ints(&v->aptr, in->aptr, (size_t)v->nc + 1));
    GLPGP_CHECK(copy_ints(&v->amem, in->amem, (size_t)in->aptr[v->nc]));
    GLPGP_CHECK(copy_ints(&v->gptr, in->gptr, (size_t)nx->nnzb + 1));
    GLPGP_CHECK(copy_ints(&v->gsrc, in->gsrc, (size_t)in->gptr[nx->nnzb]));
    return GLPGP_OK;
}

static glpgp_status setup_run(pimpl *p, const glpgp_amg_layout *lay)
{
    GLPGP_CHECK(glpgp_calloc(1, sizeof(struct petsc_amg), &p->amg));
    struct petsc_amg *a = p->amg;
    a->key = lay->key;
    a->weight = lay->weight;
    a->pre = lay->pre;
    a->post = lay->post;
    memcpy(a->kcycle, lay->kcycle, sizeof a->kcycle);
    a->L = lay->nlevels;
    if (!(a->weight > 0.0 && a->weight < 2.0))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_setup: smoother weight %g not in (0, 2)", a->weight);
    for (int l = 0; l < a->L; l++) {
        const glpgp_amg_level *in = &lay->lev[l], *nx = l + 1 < a->L ? &lay->lev[l + 1] : NULL;
        pm_level *v = &a->lev[l];
        v->n = in->n;
        v->nnzb = in->nnzb;
        v->nc = nx ? nx->n : 0;
        if (l == 0 && nx) GLPGP_CHECK(setup_level0(p, v, in, nx));
        if (l > 0) GLPGP_CHECK(setup_coarse(v, in));
        if (l > 0 && nx) GLPGP_CHECK(setup_transfer(v, in, nx));
    }
    a->m = 2 * a->lev[a->L - 1].n;
    GLPGP_CHECK(glpgp_calloc((size_t)a->m * a->m, sizeof(double), &a->cinv));
    GLPGP_CHECK(glpgp_malloc((size_t)GLPGP_DENSE_W(a->m), sizeof(double), &a->dw));
    GLPGP_CHECK(glpgp_malloc((size_t)GLPGP_DENSE_I(a->m) + 1, sizeof(int), &a->di));
    if (p->size == 1) return GLPGP_OK;
    const int *agg[GLPGP_AMG_MAX_LEVELS];
    int n[GLPGP_AMG_MAX_LEVELS];
    level_maps(p, a, agg, n, NULL);
    return glpgp_petsc_gc_create(p, a->L, agg, n, &a->gc);
}

glpgp_status glpgp_petsc_amg_setup(glpgp_backend *b, const glpgp_amg_layout *lay)
{
    pimpl *p = PI(b);
    const glpgp_system *sys = p->sys;
    if (!sys) return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_setup before setup");
    if (lay->nlevels < 2 || lay->nlevels > GLPGP_AMG_MAX_LEVELS)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_setup: %d levels", lay->nlevels);
    if (lay->lev[0].n != sys->nv || lay->lev[0].nnzb != sys->nnzb)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_setup: level 0 is not the system");
    if (same_layout(p->amg, lay)) return GLPGP_OK; /* holds it already */
    glpgp_petsc_amg_free(p);
    const glpgp_status st = setup_run(p, lay);
    if (st != GLPGP_OK) glpgp_petsc_amg_free(p);
    return st;
}

/* ---- values --------------------------------------------------------------- */

glpgp_status glpgp_petsc_amg_values(glpgp_backend *b, const glpgp_vec *const *frames)
{
    pimpl *p = PI(b);
    struct petsc_amg *a = p->amg;
    if (!a) return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_values before amg_setup");
    for (int l = 0; l + 1 < a->L; l++) {
        pm_level *v = &a->lev[l], *w = &a->lev[l + 1];
        const double *A = LVAL(p, v, l);
        const PetscScalar *fa = NULL;
        if (frames[l]) PCHK(VecGetArrayRead(frames[l]->v, &fa));
        const double *fr = fa ? (l ? fa : fa - 2 * (long)p->lo) : NULL;
        double *c = CW(p, v, l);
        /* the reference backend's three passes (backends/reference_amg.c) */
        for (int J = 0; J < v->nc; J++)
            glpgp_amg_agg_weights(J, v->aptr, v->amem, l > 0, v->amp, fr != NULL, fr, l == 0, p->dir, c, w->amp);
        if (fa) PCHK(VecRestoreArrayRead(frames[l]->v, &fa));
        for (int cr = 0; cr < w->n; cr++)
            glpgp_amg_galerkin_row(cr, w->rowptr, w->diag, v->gptr, v->gsrc, SROW(p, v, l), v->col, c, A, w->amp,
                                   w->val);
        const int i0 = l ? 0 : p->lo, i1 = l ? v->n : p->hi;
        double *minv = MINV(p, v, l);
        for (int i = i0; i < i1; i++) glpgp_amg_l1_row(i, v->rowptr, v->diag, A, a->weight, minv);
    }
    if (!a->gc) return GLPGP_OK;
    const int *agg[GLPGP_AMG_MAX_LEVELS];
    int n[GLPGP_AMG_MAX_LEVELS];
    const double *c[GLPGP_AMG_MAX_LEVELS];
    level_maps(p, a, agg, n, c);
    return glpgp_petsc_gc_values(p, a->gc, agg, c, frames[0]);
}

glpgp_status glpgp_petsc_amg_coarse_invert(glpgp_backend *b, int spd)
{
    pimpl *p = PI(b);
    struct petsc_amg *a = p->amg;
    if (!a) return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_coarse_invert before amg_setup");
    const pm_level *v = &a->lev[a->L - 1];
    double status = glpgp_dense_coarse_invert(0, 1, v->n, v->rowptr, v->col, v->val, spd, a->cinv, a->dw, a->di,
                                              NULL, NULL);
    if (a->gc && glpgp_petsc_gc_invert(a->gc, spd)) status = 1.0;
    /* every rank sees a failure anywhere: the outer solver stops everywhere alike */
    if (p->size > 1 && MPI_Allreduce(MPI_IN_PLACE, &status, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD) != MPI_SUCCESS)
        return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "MPI_Allreduce failed");
    a->t[GLPGP_AMG_SLOT_STATUS] = status;
    return GLPGP_OK;
}

/* ---- the cycle's ops ------------------------------------------------------ */

/* a vector's array addressed by level-l node numbers: level 0 shifted by the
 * first owned vertex */
static double *lvl(const pimpl *p, int l, PetscScalar *a) { return l ? a : a - 2 * (long)p->lo; }

/* *xs <- x readable at every column of the owned rows (level 0): one rank
 * reads the Vec's own array (release with view_end), more ranks the
 * ghosted scratch p->xf[1] */
static glpgp_status view_begin(pimpl *p, const glpgp_vec *x, const double **xs, const PetscScalar **arr)
{
    *arr = NULL;
    if (p->size == 1) {
        PCHK(VecGetArrayRead(x->v, arr));
        *xs = *arr - 2 * (long)p->lo;
        return GLPGP_OK;
    }
    GLPGP_CHECK(glpgp_petsc_load_ghosted(p, x, 1));
    *xs = p->xf[1];
    return GLPGP_OK;
}

/* view_begin on level 0, the array itself on a coarse level */
static glpgp_status view_level(pimpl *p, int l, const glpgp_vec *x, const double **xs, const PetscScalar **arr)
{
    if (l == 0) return view_begin(p, x, xs, arr);
    PCHK(VecGetArrayRead(x->v, arr));
    *xs = *arr;
    return GLPGP_OK;
}

static glpgp_status view_end(const glpgp_vec *x, const PetscScalar **arr)
{
    if (*arr) PCHK(VecRestoreArrayRead(x->v, arr));
    return GLPGP_OK;
}

static void row_range(const pimpl *p, int l, const pm_level *v, int *i0, int *i1)
{
    *i0 = l ? 0 : p->lo;
    *i1 = l ? v->n : p->hi;
}

glpgp_status glpgp_petsc_amg_smooth(glpgp_backend *b, int l, const glpgp_vec *r, const glpgp_vec *x, glpgp_vec *y)
{
    pimpl *p = PI(b);
    pm_level *v = &p->amg->lev[l];
    const double *A = LVAL(p, v, l), *xs = NULL;
    const PetscScalar *xarr = NULL, *ra;
    PetscScalar *ya;
    if (x) GLPGP_CHECK(view_level(p, l, x, &xs, &xarr));
    PCHK(VecGetArrayRead(r->v, &ra));
    PCHK(VecGetArray(y->v, &ya));
    const double *rr = lvl(p, l, (PetscScalar *)ra);
    double *yy = lvl(p, l, ya), *minv = MINV(p, v, l);
    int i0, i1;
    row_range(p, l, v, &i0, &i1);
    /* y_i <- x_i + M_i^-1 (r_i - (A x)_i) */
    for (int i = i0; i < i1; i++) glpgp_amg_row_smooth(i, x != NULL, v->rowptr, v->col, A, minv, rr, xs, yy);
    PCHK(VecRestoreArray(y->v, &ya));
    PCHK(VecRestoreArrayRead(r->v, &ra));
    if (x) GLPGP_CHECK(view_end(x, &xarr));
    return GLPGP_OK;
}

glpgp_status glpgp_petsc_amg_restrict(glpgp_backend *b, int l, const glpgp_vec *r, const glpgp_vec *x,
                                      glpgp_vec *rc)
{
    pimpl *p = PI(b);
    pm_level *v = &p->amg->lev[l];
    const double *A = LVAL(p, v, l), *xs = NULL;
    const PetscScalar *xarr = NULL, *ra;
    PetscScalar *ca;
    if (x) GLPGP_CHECK(view_level(p, l, x, &xs, &xarr));
    PCHK(VecGetArrayRead(r->v, &ra));
    PCHK(VecGetArray(rc->v, &ca));
    const double *rr = lvl(p, l, (PetscScalar *)ra), *c = CW(p, v, l);
    /* rc <- 0, then the rows in order, each added to its aggregate */
    for (int J = 0; J < 2 * v->nc; J++) ca[J] = 0.0;
    int i0, i1;
    row_range(p, l, v, &i0, &i1);
    glpgp_status st = GLPGP_OK;
    if (l == 0 && p->amg->gc) /* the global term, then the local sums */
        st = gc_restrict(p, p->amg, v, c, x != NULL, A, rr, xs, ca);
    else
        for (int i = i0; i < i1; i++)
            glpgp_amg_row_restrict_scatter(i, v->agg, c, x != NULL, v->rowptr, v->col, A, rr, xs, ca);
    PCHK(VecRestoreArray(rc->v, &ca));
    PCHK(VecRestoreArrayRead(r->v, &ra));
    if (x) GLPGP_CHECK(view_end(x, &xarr));
    return st;
}

glpgp_status glpgp_petsc_amg_prolong(glpgp_backend *b, int l, const glpgp_vec *ec, glpgp_vec *x)
{
    pimpl *p = PI(b);
    pm_level *v = &p->amg->lev[l];
    const PetscScalar *ea;
    PetscScalar *xa;
    PCHK(VecGetArrayRead(ec->v, &ea));
    PCHK(VecGetArray(x->v, &xa));
    double *xx = lvl(p, l, xa), *c = CW(p, v, l);
    int i0, i1;
    row_range(p, l, v, &i0, &i1);
    glpgp_status st = GLPGP_OK;
    if (l == 0 && p->amg->gc && p->amg->gc->k > 0) {
        st = gc_prolong(p, p->amg, v, c, ea, xx);
    } else {
        for (int i = i0; i < i1; i++) glpgp_amg_row_prolong(i, v->agg, c, ea, xx);
        if (l == 0 && p->amg->gc) glpgp_petsc_gc_prolong(p, p->amg->gc, xx);
    }
    PCHK(VecRestoreArray(x->v, &xa));
    PCHK(VecRestoreArrayRead(ec->v, &ea));
    return st;
}

glpgp_status glpgp_petsc_amg_coarse_solve(glpgp_backend *b, const glpgp_vec *r, glpgp_vec *x)
{
    struct petsc_amg *a = PI(b)->amg;
    const PetscScalar *ra;
    PetscScalar *xa;
    PCHK(VecGetArrayRead(r->v, &ra));
    PCHK(VecGetArray(x->v, &xa));
    for (int i = 0; i < a->m; i++) glpgp_amg_row_dense(i, a->m, a->cinv, ra, xa);
    PCHK(VecRestoreArray(x->v, &xa));
    PCHK(VecRestoreArrayRead(r->v, &ra));
    return GLPGP_OK;
}

/* s[0..n) <- local dot products of x with ys[k] (NULL: 0), then summed over
 * the ranks when x is a level-0 (distributed) vector */
static glpgp_status dots(pimpl *p, const glpgp_vec *x, const glpgp_vec *const *ys, int n, double *s)
{
    PetscInt len;
    const PetscScalar *xa, *ya;
    PCHK(VecGetLocalSize(x->v, &len));
    PCHK(VecGetArrayRead(x->v, &xa));
    for (int k = 0; k < n; k++) {
        s[k] = 0.0;
        if (!ys[k]) continue;
        PCHK(VecGetArrayRead(ys[k]->v, &ya));
        s[k] = glpgp_range_dot(0, (long)len, xa, ya);
        PCHK(VecRestoreArrayRead(ys[k]->v, &ya));
    }
    PCHK(VecRestoreArrayRead(x->v, &xa));
    if (!x->local) GLPGP_CHECK(glpgp_petsc_reduce_sum(p, s, n));
    return GLPGP_OK;
}

glpgp_status glpgp_petsc_amg_spmv_dots(glpgp_backend *b, int l, const glpgp_vec *x, glpgp_vec *y,
                                       const glpgp_vec *u, const glpgp_vec *w, int slot)
{
    pimpl *p = PI(b);
    struct petsc_amg *a = p->amg;
    pm_level *v = &a->lev[l];
    const double *A = LVAL(p, v, l), *xs;
    const PetscScalar *xarr = NULL;
    PetscScalar *ya;
    GLPGP_CHECK(view_level(p, l, x, &xs, &xarr));
    PCHK(VecGetArray(y->v, &ya));
    double *yy = lvl(p, l, ya);
    int i0, i1;
    row_range(p, l, v, &i0, &i1);
    /* y <- A_l x (level 0: the global operator's owned rows) */
    for (int i = i0; i < i1; i++) glpgp_row_spmv_store(i, v->rowptr, v->col, A, xs, yy);
    PCHK(VecRestoreArray(y->v, &ya));
    GLPGP_CHECK(view_end(x, &xarr));
    const glpgp_vec *ys[3] = {y, u, w};
    double s[3];
    GLPGP_CHECK(dots(p, x, ys, 3, s));
    a->t[slot] = s[0];
    if (u) a->t[slot + 1] = s[1];
    if (w) a->t[slot + 2] = s[2];
    return GLPGP_OK;
}

glpgp_status glpgp_petsc_amg_dots(glpgp_backend *b, const glpgp_vec *x, const glpgp_vec *u, const glpgp_vec *w,
                                  int slot)
{
    pimpl *p = PI(b);
    const glpgp_vec *ys[2] = {u, w};
    double s[2];
    GLPGP_CHECK(dots(p, x, ys, 2, s));
    if (u) p->amg->t[slot] = s[0];
    if (w) p->amg->t[slot + 1] = s[1];
    return GLPGP_OK;
}

glpgp_status glpgp_petsc_amg_axpby(glpgp_backend *b, glpgp_amg_coef ca, const glpgp_vec *x, glpgp_amg_coef cc,
                                   glpgp_vec *y)
{
    const double *t = PI(b)->amg->t;
    const double pc = glpgp_amg_coef_value(t, ca.num, ca.den, ca.sign);
    const double qc = glpgp_amg_coef_value(t, cc.num, cc.den, cc.sign);
    PetscInt n;
    PetscScalar *ya;
    const PetscScalar *xa = NULL;
    PCHK(VecGetLocalSize(y->v, &n));
    PCHK(VecGetArray(y->v, &ya));
    if (x != y) PCHK(VecGetArrayRead(x->v, &xa));
    /* y <- p x + q y (a zero coefficient does not read its vector) */
    for (PetscInt i = 0; i < n; i++) glpgp_amg_entry_axpby((long)i, pc, x == y ? ya : xa, qc, ya);
    if (x != y) PCHK(VecRestoreArrayRead(x->v, &xa));
    PCHK(VecRestoreArray(y->v, &ya));
    return GLPGP_OK;
}

glpgp_status glpgp_petsc_amg_kcombine(glpgp_backend *b, const glpgp_vec *v, const glpgp_vec *d, glpgp_vec *e,
                                      int slot)
{
    const double *t = PI(b)->amg->t + slot;
    double c[2];
    glpgp_amg_kcoef(t[0], t[1], t[2], t[3], t[4], c);
    PetscInt n;
    const PetscScalar *va, *da;
    PetscScalar *ea;
    PCHK(VecGetLocalSize(e->v, &n));
    PCHK(VecGetArrayRead(v->v, &va));
    PCHK(VecGetArrayRead(d->v, &da));
    PCHK(VecGetArray(e->v, &ea));
    for (PetscInt i = 0; i < n; i++) glpgp_amg_entry_kcombine((long)i, c[0], c[1], va, da, ea);
    PCHK(VecRestoreArray(e->v, &ea));
    PCHK(VecRestoreArrayRead(d->v, &da));
    PCHK(VecRestoreArrayRead(v->v, &va));
    return GLPGP_OK;
}

glpgp_status glpgp_petsc_amg_get_scalars(glpgp_backend *b, double *out, int n)
{
    const struct petsc_amg *a = PI(b)->amg;
    if (!a) return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_get_scalars before amg_setup");
    if (n > GLPGP_AMG_NSLOTS) n = GLPGP_AMG_NSLOTS;
    memcpy(out, a->t, (size_t)n * sizeof(double));
    return GLPGP_OK;
}
