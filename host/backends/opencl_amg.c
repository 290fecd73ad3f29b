/* backends/opencl_amg.c: the OpenCL backend's multigrid ops (amg_* of
 * glpgp/backend.h; kernels/backend_multigrid.cl, per-row arithmetic in
 * kernels/amg_rows.h shared with backends/reference_amg.c): the hierarchy's
 * buffers, the per-step values and coarse inverse, smoothing, restriction,
 * prolongation, the K-cycle's register ops and the fused coarse correction
 * of the CPU shape. The rest of the backend: opencl.c (opencl_impl.h). */
#include "cl_util.h"

#ifdef GLPGP_HAVE_OPENCL

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "glpgp/util.h"

#include "amg_dense.h" /* GLPGP_DENSE_W, _I (the coarse inverse's work arrays) */
#include "amg_rows.h"  /* GLPGP_AMG_BT_* (the fused kernel's level table) */
#include "opencl_impl.h"

/* ---- multigrid (amg_* ops; kernels/backend_multigrid.cl) ------------------------
 * The hierarchy's structure is uploaded once by amg_setup; amg_values rebuilds
 * the weights, coarse values and smoothers on the device (one launch for the
 * level-0 smoother, then two per level: weights, Galerkin rows + smoother);
 * the coarsest matrix is read back and its inverse uploaded once per Newton
 * step (amg_coarse_read / amg_coarse_set). Launch shape: as the other ops,
 * except that in the CPU shape a launch over at most amg_small indices (the
 * coarse levels) is one work-item: PoCL's cost of a launch does not depend
 * on the size there, and a single work-group writes its dot products straight
 * into the registers (no finalize launch; the sum is then in the reference's
 * sequential order). */

void glpgp_cl_amg_free(cl_impl *c)
{
    cl_amg *a = c->amg;
    if (!a) return;
    for (int l = 0; l < GLPGP_AMG_MAX_LEVELS; l++) {
        cl_amg_level *v = &a->lev[l];
        cl_mem *ms[] = {&v->rowptr, &v->col, &v->diag, &v->val, &v->amp, &v->srow, &v->minv,
                        &v->c,      &v->agg, &v->aptr, &v->amem, &v->gptr, &v->gsrc};
        for (size_t k = 0; k < sizeof ms / sizeof ms[0]; k++) glpgp_cl_release_mem(ms[k]);
    }
    glpgp_cl_release_mem(&a->cinv);
    glpgp_cl_release_mem(&a->dw);
    glpgp_cl_release_mem(&a->di);
    glpgp_cl_release_mem(&a->t);
    glpgp_cl_release_mem(&a->resid);
    glpgp_cl_release_mem(&a->part);
    glpgp_cl_release_mem(&a->tab);
    glpgp_cl_release_mem(&a->ipack);
    glpgp_cl_release_mem(&a->dpack);
    free(a->crowptr);
    free(a->ccol);
    free(a->cval);
    free(a);
    c->amg = NULL;
}

/* Launch shape of a multigrid kernel over n indices (see above). */
static launch_shape amg_shape_w(const cl_impl *c, size_t n, size_t work)
{
    if (c->cpu && work <= (size_t)c->amg_small) {
        launch_shape s;
        s.n = (cl_int)n;
        s.chunk = (cl_int)(n ? n : 1);
        s.global = s.local = s.groups = 1;
        return s;
    }
    return glpgp_cl_shape_for(c, n);
}

static launch_shape amg_shape(const cl_impl *c, size_t n) { return amg_shape_w(c, n, n); }

/* Enqueue multigrid kernel kid over n indices (arguments 0, 1 = n, chunk);
 * work: the size that decides the one-work-item shape (the fine level's
 * node count for kernels indexed by aggregate or coarse row, whose work is
 * proportional to the fine level). */
static glpgp_status amg_run_w(cl_impl *c, int kid, size_t n, size_t work, size_t *groups)
{
    launch_shape s = amg_shape_w(c, n, work);
    cl_kernel k = c->k[kid];
    ARGS(k, 0, s.n, s.chunk);
    c->prof_size = work;
    GLPGP_CHECK(glpgp_cl_launch(c, kid, s.global, s.local));
    if (groups) *groups = s.groups;
    return GLPGP_OK;
}

static glpgp_status amg_run(cl_impl *c, int kid, size_t n, size_t *groups) { return amg_run_w(c, kid, n, n, groups); }

/* Where a reduction over n indices writes its partials: (buffer, stride) of
 * a->part, or, for a single work-group, the registers t + slot directly
 * (stride 1). *direct <- 1 in the latter case (no finalize needed). */
static glpgp_status amg_partials(cl_impl *c, size_t n, int slot, cl_mem *buf, cl_int *off, cl_int *stride,
                                 int *direct)
{
    cl_amg *a = c->amg;
    launch_shape s = amg_shape(c, n);
    if (s.groups == 1) {
        *buf = a->t;
        *off = slot;
        *stride = 1;
        *direct = 1;
        return GLPGP_OK;
    }
    if (s.groups > a->pstride || !a->part) {
        cl_int err;
        cl_mem m = NULL;
        GLPGP_CL((m = clCreateBuffer(c->ctx, CL_MEM_READ_WRITE, 3 * s.groups * sizeof(double), NULL, &err), err));
        glpgp_cl_release_mem(&a->part);
        a->part = m;
        a->pstride = s.groups;
    }
    *buf = a->part;
    *off = 0;
    *stride = (cl_int)a->pstride;
    *direct = 0;
    return GLPGP_OK;
}

/* t[slot + q] <- sum of the np partials of quantity q, for the q in mask. */
static glpgp_status amg_finalize(cl_impl *c, size_t np, int mask, int slot)
{
    cl_amg *a = c->amg;
    cl_kernel k = c->k[K_AMG_FINALIZE];
    cl_int n = (cl_int)np, st = (cl_int)a->pstride, mk = mask, sl = slot;
    ARGS(k, 0, a->part, n, st, mk, a->t, sl);
    return glpgp_cl_launch(c, K_AMG_FINALIZE, c->wg, c->wg);
}

static glpgp_status amg_check_slot(int slot, int n, const char *what)
{
    if (slot < 0 || slot + n > GLPGP_AMG_NSLOTS)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "%s: bad register %d", what, slot);
    return GLPGP_OK;
}

/* *m <- a read-only device copy of n ints (n may be 0). */
static glpgp_status upload_ints(cl_impl *c, cl_mem *m, const int *host, size_t n)
{
    const int zero = 0;
    return glpgp_cl_upload(c, m, n ? (const void *)host : (const void *)&zero, n ? n * sizeof(int) : sizeof(int));
}

/* A sub-buffer of parent: `count` elements of `elem` bytes at element offset off. */
static glpgp_status sub_buffer(cl_mem parent, size_t off, size_t count, size_t elem, cl_mem *out)
{
    cl_int err;
    cl_buffer_region reg = {off * elem, (count ? count : 1) * elem};
    GLPGP_CL((*out = clCreateSubBuffer(parent, 0, CL_BUFFER_CREATE_TYPE_REGION, &reg, &err), err));
    return GLPGP_OK;
}

/* Packed layout of the fused levels lb .. L-1 (see cl_amg): offsets of every
 * array in ints / doubles, each aligned for a sub-buffer; *cinv: offset of
 * the dense coarse inverse; *ni, *nd: totals.
 * Returns 0 when the totals would not fit an int index. */
static int bottom_layout(const cl_impl *c, const glpgp_amg_layout *lay, int lb, int *tab, long *ni, long *nd,
                         int *cinv)
{
    const long ai = (long)c->align / (long)sizeof(int), ad = (long)c->align / (long)sizeof(double);
    long oi = 0, od = 0;
#define TAKE_I(f, cnt) (tab[q * GLPGP_AMG_BT_COUNT + (f)] = (int)oi, oi += (((long)(cnt) + 1 + ai - 1) / ai) * ai)
#define TAKE_D(f, cnt) (tab[q * GLPGP_AMG_BT_COUNT + (f)] = (int)od, od += (((long)(cnt) + 1 + ad - 1) / ad) * ad)
    for (int l = lb; l < lay->nlevels; l++) {
        const int q = l - lb;
        const glpgp_amg_level *in = &lay->lev[l];
        const int last = l + 1 == lay->nlevels;
        for (int f = 0; f < GLPGP_AMG_BT_COUNT; f++) tab[q * GLPGP_AMG_BT_COUNT + f] = -1;
        tab[q * GLPGP_AMG_BT_COUNT + GLPGP_AMG_BT_N] = in->n;
        tab[q * GLPGP_AMG_BT_COUNT + GLPGP_AMG_BT_NC] = last ? 0 : lay->lev[l + 1].n;
        tab[q * GLPGP_AMG_BT_COUNT + GLPGP_AMG_BT_K] = last ? 0 : lay->kcycle[l];
        TAKE_I(GLPGP_AMG_BT_ROWPTR, in->n + 1);
        TAKE_I(GLPGP_AMG_BT_COL, in->nnzb);
        TAKE_I(GLPGP_AMG_BT_DIAG, in->n);
        TAKE_D(GLPGP_AMG_BT_VAL, 4 * in->nnzb);
        TAKE_D(GLPGP_AMG_BT_B, 2 * in->n);
        TAKE_D(GLPGP_AMG_BT_E, 2 * in->n);
        if (!last) {
            TAKE_I(GLPGP_AMG_BT_AGG, in->n);
            TAKE_I(GLPGP_AMG_BT_APTR, lay->lev[l + 1].n + 1);
            TAKE_I(GLPGP_AMG_BT_AMEM, in->aptr[lay->lev[l + 1].n]);
            TAKE_D(GLPGP_AMG_BT_MINV, 4 * in->n);
            TAKE_D(GLPGP_AMG_BT_C, 2 * in->n);
            TAKE_D(GLPGP_AMG_BT_TMP, 2 * in->n);
            if (lay->kcycle[l]) {
                TAKE_D(GLPGP_AMG_BT_V, 2 * in->n);
                TAKE_D(GLPGP_AMG_BT_W, 2 * in->n);
                TAKE_D(GLPGP_AMG_BT_R2, 2 * in->n);
                TAKE_D(GLPGP_AMG_BT_D, 2 * in->n);
                TAKE_D(GLPGP_AMG_BT_WD, 2 * in->n);
            }
        }
        if (oi > INT_MAX / 2 || od > INT_MAX / 2) return 0;
    }
    /* the dense coarse inverse, order m = 2 n_{L-1} */
    const long m = 2L * lay->lev[lay->nlevels - 1].n;
    *cinv = (int)od;
    od += ((m * m + 1 + ad - 1) / ad) * ad;
    if (od > INT_MAX / 2) return 0;
#undef TAKE_I
#undef TAKE_D
    *ni = oi;
    *nd = od;
    return 1;
}

/* The fused levels' packed arrays on the device (layout tab, ni ints, nd
 * doubles from bottom_layout): the ints from the layout, the doubles
 * zeroed, and the table. */
static glpgp_status bottom_upload(cl_impl *c, const glpgp_amg_layout *lay, const int *tab, long ni, long nd)
{
    cl_amg *a = c->amg;
    int *ihost = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK(glpgp_calloc((size_t)ni, sizeof(int), &ihost));
    for (int l = a->lb; l < a->L; l++) {
        const int q = l - a->lb, *row = tab + q * GLPGP_AMG_BT_COUNT;
        const glpgp_amg_level *in = &lay->lev[l];
        const int n = in->n;
        memcpy(ihost + row[GLPGP_AMG_BT_ROWPTR], in->rowptr, ((size_t)n + 1) * sizeof(int));
        memcpy(ihost + row[GLPGP_AMG_BT_COL], in->col, (size_t)in->nnzb * sizeof(int));
        memcpy(ihost + row[GLPGP_AMG_BT_DIAG], in->diag, (size_t)n * sizeof(int));
        if (l + 1 < a->L) {
            const int nc = lay->lev[l + 1].n;
            memcpy(ihost + row[GLPGP_AMG_BT_AGG], in->agg, (size_t)n * sizeof(int));
            memcpy(ihost + row[GLPGP_AMG_BT_APTR], in->aptr, ((size_t)nc + 1) * sizeof(int));
            memcpy(ihost + row[GLPGP_AMG_BT_AMEM], in->amem, (size_t)in->aptr[nc] * sizeof(int));
        }
    }
    st = glpgp_cl_upload(c, &a->ipack, ihost, (size_t)ni * sizeof(int));
    free(ihost);
    GLPGP_CHECK(st);
    GLPGP_CHECK(glpgp_cl_upload(c, &a->dpack, NULL, (size_t)nd * sizeof(double)));
    return upload_ints(c, &a->tab, tab, (size_t)(a->L - a->lb) * GLPGP_AMG_BT_COUNT);
}

glpgp_status glpgp_cl_amg_setup(glpgp_backend *b, const glpgp_amg_layout *lay)
{
    cl_impl *c = IMPL(b);
    const glpgp_system *sys = c->sys;
    if (!sys) return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_setup before setup");
    if (lay->nlevels < 2 || lay->nlevels > GLPGP_AMG_MAX_LEVELS)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_setup: %d levels", lay->nlevels);
    if (lay->lev[0].n != sys->nv || lay->lev[0].nnzb != sys->nnzb)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_setup: level 0 is not the system");
    if (!(lay->weight > 0.0 && lay->weight < 2.0))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_setup: smoother weight %g not in (0, 2)", lay->weight);
    if (lay->pre < 0 || lay->pre > 64 || lay->post < 0 || lay->post > 64)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_setup: %d / %d smoother sweeps", lay->pre, lay->post);
    if (c->amg && glpgp_amg_layout_same(&c->amg->lay, lay)) return GLPGP_OK; /* holds it already */
    glpgp_cl_amg_free(c);
    GLPGP_CHECK(glpgp_calloc(1, sizeof(cl_amg), &c->amg));
    cl_amg *a = c->amg;
    glpgp_status st = GLPGP_OK;
    int *srow = NULL, *tab = NULL;
    a->lay = *lay;
    a->L = lay->nlevels;
    a->weight = lay->weight;
    a->pre = lay->pre;
    a->post = lay->post;
    for (int l = 0; l < a->L; l++) {
        const glpgp_amg_level *in = &lay->lev[l];
        if (in->n < 1 || in->nnzb < in->n || in->nnzb > (long)INT_MAX - 1) {
            st = GLPGP_FAIL(GLPGP_ERR_ARG, "amg_setup: level %d has %d nodes and %ld blocks", l, in->n, in->nnzb);
            goto fail;
        }
    }

    /* fused levels: the first level >= 1 small enough, and all below it */
    a->lb = a->L;
    if (c->cpu && c->amg_fuse > 0)
        for (int l = 1; l < a->L; l++)
            if (lay->lev[l].n <= c->amg_fuse) {
                a->lb = l;
                break;
            }
    if (a->lb < a->L) {
        long ni = 0, nd = 0;
        const int nq = a->L - a->lb;
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nq * GLPGP_AMG_BT_COUNT, sizeof(int), &tab), fail);
        if (!bottom_layout(c, lay, a->lb, tab, &ni, &nd, &a->cinv_off))
            a->lb = a->L; /* too large to index: the per-op path */
        else
            GLPGP_CHECK_GOTO(st, bottom_upload(c, lay, tab, ni, nd), fail);
    }

    for (int l = 0; l < a->L; l++) {
        const glpgp_amg_level *in = &lay->lev[l];
        cl_amg_level *v = &a->lev[l];
        const int *rowptr = l ? in->rowptr : sys->rowptr;
        const int fused = l >= a->lb, *row = fused ? tab + (l - a->lb) * GLPGP_AMG_BT_COUNT : NULL;
        v->n = in->n;
        v->nnzb = in->nnzb;
        if (l > 0 && fused) {
            GLPGP_CHECK_GOTO(st, sub_buffer(a->ipack, (size_t)row[GLPGP_AMG_BT_ROWPTR], (size_t)v->n + 1, sizeof(int), &v->rowptr), fail);
            GLPGP_CHECK_GOTO(st, sub_buffer(a->ipack, (size_t)row[GLPGP_AMG_BT_COL], (size_t)v->nnzb, sizeof(int), &v->col), fail);
            GLPGP_CHECK_GOTO(st, sub_buffer(a->ipack, (size_t)row[GLPGP_AMG_BT_DIAG], (size_t)v->n, sizeof(int), &v->diag), fail);
            GLPGP_CHECK_GOTO(st, sub_buffer(a->dpack, (size_t)row[GLPGP_AMG_BT_VAL], 4 * (size_t)v->nnzb, sizeof(double), &v->val), fail);
        } else if (l > 0) {
            GLPGP_CHECK_GOTO(st, upload_ints(c, &v->rowptr, in->rowptr, (size_t)v->n + 1), fail);
            GLPGP_CHECK_GOTO(st, upload_ints(c, &v->col, in->col, (size_t)v->nnzb), fail);
            GLPGP_CHECK_GOTO(st, upload_ints(c, &v->diag, in->diag, (size_t)v->n), fail);
            GLPGP_CHECK_GOTO(st, glpgp_cl_upload(c, &v->val, NULL, (size_t)4 * v->nnzb * sizeof(double)), fail);
        }
        if (l > 0) GLPGP_CHECK_GOTO(st, glpgp_cl_upload(c, &v->amp, NULL, (size_t)v->n * sizeof(double)), fail);
        if (l + 1 < a->L) {
            const glpgp_amg_level *nx = &lay->lev[l + 1];
            v->nc = nx->n;
            /* srow[k] <- row of slot k */
            GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)v->nnzb, sizeof(int), &srow), fail);
            for (int i = 0; i < v->n; i++)
                for (int k = rowptr[i]; k < rowptr[i + 1]; k++) srow[k] = i;
            GLPGP_CHECK_GOTO(st, upload_ints(c, &v->srow, srow, (size_t)v->nnzb), fail);
            free(srow);
            srow = NULL;
            if (fused) {
                GLPGP_CHECK_GOTO(st, sub_buffer(a->dpack, (size_t)row[GLPGP_AMG_BT_MINV], 4 * (size_t)v->n, sizeof(double), &v->minv), fail);
                GLPGP_CHECK_GOTO(st, sub_buffer(a->dpack, (size_t)row[GLPGP_AMG_BT_C], 2 * (size_t)v->n, sizeof(double), &v->c), fail);
                GLPGP_CHECK_GOTO(st, sub_buffer(a->ipack, (size_t)row[GLPGP_AMG_BT_AGG], (size_t)v->n, sizeof(int), &v->agg), fail);
                GLPGP_CHECK_GOTO(st, sub_buffer(a->ipack, (size_t)row[GLPGP_AMG_BT_APTR], (size_t)v->nc + 1, sizeof(int), &v->aptr), fail);
                GLPGP_CHECK_GOTO(st, sub_buffer(a->ipack, (size_t)row[GLPGP_AMG_BT_AMEM], (size_t)in->aptr[v->nc], sizeof(int), &v->amem), fail);
            } else {
                GLPGP_CHECK_GOTO(st, glpgp_cl_upload(c, &v->minv, NULL, (size_t)4 * v->n * sizeof(double)), fail);
                GLPGP_CHECK_GOTO(st, glpgp_cl_upload(c, &v->c, NULL, (size_t)2 * v->n * sizeof(double)), fail);
                GLPGP_CHECK_GOTO(st, upload_ints(c, &v->agg, in->agg, (size_t)v->n), fail);
                GLPGP_CHECK_GOTO(st, upload_ints(c, &v->aptr, in->aptr, (size_t)v->nc + 1), fail);
                GLPGP_CHECK_GOTO(st, upload_ints(c, &v->amem, in->amem, (size_t)in->aptr[v->nc]), fail);
            }
            GLPGP_CHECK_GOTO(st, upload_ints(c, &v->gptr, in->gptr, (size_t)nx->nnzb + 1), fail);
            GLPGP_CHECK_GOTO(st, upload_ints(c, &v->gsrc, in->gsrc, (size_t)in->gptr[nx->nnzb]), fail);
        }
    }
    /* the coarsest level: host copy of its pattern, dense inverse buffer */
    {
        const glpgp_amg_level *in = &lay->lev[a->L - 1];
        const int n = in->n;
        a->m = 2 * n;
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n + 1, sizeof(int), &a->crowptr), fail);
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)in->nnzb, sizeof(int), &a->ccol), fail);
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * in->nnzb, sizeof(double), &a->cval), fail);
        memcpy(a->crowptr, in->rowptr, ((size_t)n + 1) * sizeof(int));
        memcpy(a->ccol, in->col, (size_t)in->nnzb * sizeof(int));
        if (a->lb < a->L)
            GLPGP_CHECK_GOTO(st, sub_buffer(a->dpack, (size_t)a->cinv_off, (size_t)a->m * a->m, sizeof(double), &a->cinv), fail);
        else
            GLPGP_CHECK_GOTO(st, glpgp_cl_upload(c, &a->cinv, NULL, (size_t)a->m * a->m * sizeof(double)), fail);
    }
    GLPGP_CHECK_GOTO(st, glpgp_cl_upload(c, &a->dw, NULL, (size_t)GLPGP_DENSE_W(a->m) * sizeof(double)), fail);
    GLPGP_CHECK_GOTO(st, glpgp_cl_upload(c, &a->di, NULL, ((size_t)GLPGP_DENSE_I(a->m) + 1) * sizeof(int)), fail);
    GLPGP_CHECK_GOTO(st, glpgp_cl_upload(c, &a->t, NULL, GLPGP_AMG_NSLOTS * sizeof(double)), fail);
    GLPGP_CHECK_GOTO(st, glpgp_cl_upload(c, &a->resid, NULL, (size_t)2 * lay->lev[0].n * sizeof(double)), fail);
    {
        cl_int err = clFinish(c->q);
        if (err != CL_SUCCESS) {
            st = GLPGP_FAIL(GLPGP_ERR_OPENCL, "amg_setup: clFinish failed with %s", glpgp_cl_error_name(err));
            goto fail;
        }
    }
    free(tab);
    return GLPGP_OK;
fail:
    free(srow);
    free(tab);
    glpgp_cl_amg_free(c);
    return st;
}

/* values of A_l and its pattern */
static cl_mem amg_val(cl_impl *c, int l) { return l == 0 ? c->newton : c->amg->lev[l].val; }
static cl_mem amg_rowptr(cl_impl *c, int l) { return l == 0 ? c->rowptr : c->amg->lev[l].rowptr; }
static cl_mem amg_col(cl_impl *c, int l) { return l == 0 ? c->col : c->amg->lev[l].col; }

static glpgp_status amg_ready(const cl_impl *c, const char *what)
{
    if (!c->amg) return GLPGP_FAIL(GLPGP_ERR_ARG, "%s before amg_setup", what);
    return GLPGP_OK;
}

static glpgp_status amg_level_ok(const cl_impl *c, int l, int coarse_ok, const char *what)
{
    GLPGP_CHECK(amg_ready(c, what));
    if (l < 0 || l >= c->amg->L - (coarse_ok ? 0 : 1))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "%s: bad level %d", what, l);
    return GLPGP_OK;
}

glpgp_status glpgp_cl_amg_values(glpgp_backend *b, const glpgp_vec *const *frames)
{
    cl_impl *c = IMPL(b);
    GLPGP_CHECK(amg_ready(c, "amg_values"));
    cl_amg *a = c->amg;
    const cl_int one = 1, zero = 0;
    /* M_0^-1 <- w (A_ii + sum_{j != i} ||A_ij||_2 I)^-1 on NEWTON */
    {
        cl_kernel k = c->k[K_AMG_L1];
        ARGS(k, 2, c->rowptr, c->diag, c->newton, a->weight, a->lev[0].minv);
        GLPGP_CHECK(amg_run(c, K_AMG_L1, (size_t)a->lev[0].n, NULL));
    }
    for (int l = 0; l + 1 < a->L; l++) {
        cl_amg_level *v = &a->lev[l], *w = &a->lev[l + 1];
        if (frames[l] && frames[l]->n != (size_t)2 * v->n)
            return GLPGP_FAIL(GLPGP_ERR_ARG, "amg_values: frame %d has the wrong length", l);
        /* per aggregate J: s_J = sqrt(sum_{i in J} |a_i frame_i|^2), c_i = a_i frame_i / s_J */
        cl_kernel k = c->k[K_AMG_WEIGHTS];
        const cl_int has_amp = l > 0, has_frame = frames[l] != NULL;
        cl_mem amp = l > 0 ? v->amp : v->c; /* not read on level 0 */
        cl_mem fr = frames[l] ? frames[l]->m : v->c;
        const cl_int has_dir = l == 0;
        ARGS(k, 2, v->aptr, v->amem, has_amp, amp, has_frame, fr, has_dir, c->dir, v->c, w->amp);
        GLPGP_CHECK(amg_run_w(c, K_AMG_WEIGHTS, (size_t)v->nc, (size_t)v->n, NULL));
        /* A_{l+1} <- P^T A_l P (Galerkin rows), M_{l+1}^-1 unless coarsest */
        k = c->k[K_AMG_GALERKIN];
        cl_mem A = amg_val(c, l), col = amg_col(c, l);
        const cl_int do_l1 = l + 2 < a->L ? one : zero;
        cl_mem minv = do_l1 ? w->minv : w->val; /* not written on the coarsest level */
        ARGS(k, 2, w->rowptr, w->diag, v->gptr, v->gsrc, v->srow, col, v->c, A, w->amp, w->val, do_l1, a->weight,
             minv);
        GLPGP_CHECK(amg_run_w(c, K_AMG_GALERKIN, (size_t)w->n, (size_t)v->n, NULL));
    }
    return GLPGP_OK;
}

glpgp_status glpgp_cl_amg_coarse_read(glpgp_backend *b, double *dense)
{
    cl_impl *c = IMPL(b);
    GLPGP_CHECK(amg_ready(c, "amg_coarse_read"));
    cl_amg *a = c->amg;
    const cl_amg_level *v = &a->lev[a->L - 1];
    const int m = a->m;
    GLPGP_CHECK(glpgp_cl_sync_read(c, v->val, 0, (size_t)4 * v->nnzb * sizeof(double), a->cval));
    memset(dense, 0, (size_t)m * m * sizeof(double));
    /* dense[2I + p][2J + q] <- A[K](p, q) for every block K = (I, J) */
    for (int I = 0; I < v->n; I++)
        for (int K = a->crowptr[I]; K < a->crowptr[I + 1]; K++) {
            const int J = a->ccol[K];
            for (int p = 0; p < 2; p++)
                for (int q = 0; q < 2; q++)
                    dense[(size_t)(2 * I + p) * m + 2 * J + q] = a->cval[4 * (size_t)K + 2 * p + q];
        }
    return GLPGP_OK;
}

glpgp_status glpgp_cl_amg_coarse_invert(glpgp_backend *b, int spd)
{
    cl_impl *c = IMPL(b);
    GLPGP_CHECK(amg_ready(c, "amg_coarse_invert"));
    cl_amg *a = c->amg;
    const cl_amg_level *v = &a->lev[a->L - 1];
    /* C <- the coarse operator, one work-group (kernels/amg_dense.h) */
    cl_kernel k = c->k[K_AMG_COARSE_INVERT];
    const cl_int n = v->n, sp = spd != 0, slot = GLPGP_AMG_SLOT_STATUS;
    ARGS(k, 0, n, sp, v->rowptr, v->col, v->val, a->cinv, a->dw, a->di, a->t, slot);
    return glpgp_cl_launch(c, K_AMG_COARSE_INVERT, c->wg, c->wg);
}

glpgp_status glpgp_cl_amg_smooth(glpgp_backend *b, int l, const glpgp_vec *r, const glpgp_vec *x, glpgp_vec *y)
{
    cl_impl *c = IMPL(b);
    GLPGP_CHECK(amg_level_ok(c, l, 0, "amg_smooth"));
    /* y_i <- x_i + M_i^-1 (r_i - (A x)_i) */
    cl_kernel k = c->k[K_AMG_SMOOTH];
    const cl_int has_x = x != NULL;
    cl_mem rp = amg_rowptr(c, l), col = amg_col(c, l), A = amg_val(c, l), xm = x ? x->m : r->m;
    ARGS(k, 2, has_x, rp, col, A, c->amg->lev[l].minv, r->m, xm, y->m);
    return amg_run(c, K_AMG_SMOOTH, (size_t)c->amg->lev[l].n, NULL);
}

glpgp_status glpgp_cl_amg_restrict(glpgp_backend *b, int l, const glpgp_vec *r, const glpgp_vec *x,
                                    glpgp_vec *rc)
{
    cl_impl *c = IMPL(b);
    GLPGP_CHECK(amg_level_ok(c, l, 0, "amg_restrict"));
    const cl_amg_level *v = &c->amg->lev[l];
    /* rc_J <- sum_{i in J} P_i^T (r - A x)_i, in two passes when x is given:
     * t <- r - A x (rows in order), then rc_J <- sum_{i in J} P_i^T t_i */
    cl_mem rp = amg_rowptr(c, l), col = amg_col(c, l), A = amg_val(c, l);
    cl_mem rin = r->m;
    if (x && l > 0 && c->cpu) {
        /* the coarse levels' aggregates are consecutive rows (solver/amg_structure.c):
         * one pass, each aggregate forming its rows' residuals (glpgp_amg_agg_restrict) */
        cl_kernel k = c->k[K_AMG_RESTRICT];
        const cl_int has_x = 1;
        ARGS(k, 2, v->aptr, v->amem, v->c, has_x, rp, col, A, r->m, x->m, rc->m);
        return amg_run_w(c, K_AMG_RESTRICT, (size_t)v->nc, (size_t)v->n, NULL);
    }
    if (x) {
        cl_kernel kr = c->k[K_AMG_RESIDUAL];
        ARGS(kr, 2, rp, col, A, r->m, x->m, c->amg->resid);
        GLPGP_CHECK(amg_run(c, K_AMG_RESIDUAL, (size_t)v->n, NULL));
        rin = c->amg->resid;
    }
    cl_kernel k = c->k[K_AMG_RESTRICT];
    const cl_int has_x = 0;
    cl_mem xm = rin;
    ARGS(k, 2, v->aptr, v->amem, v->c, has_x, rp, col, A, rin, xm, rc->m);
    return amg_run_w(c, K_AMG_RESTRICT, (size_t)v->nc, (size_t)v->n, NULL);
}

glpgp_status glpgp_cl_amg_presmooth_restrict(glpgp_backend *b, int l, const glpgp_vec *r, glpgp_vec *y,
                                              glpgp_vec *rc)
{
    cl_impl *c = IMPL(b);
    GLPGP_CHECK(amg_level_ok(c, l, 0, "amg_presmooth_restrict"));
    const cl_amg_level *v = &c->amg->lev[l];
    cl_mem rp = amg_rowptr(c, l), col = amg_col(c, l), A = amg_val(c, l);
    if (c->cpu) {
        /* one pass by aggregates: y and rc (glpgp_amg_agg_presmooth_restrict) */
        cl_kernel k = c->k[K_AMG_PRESMOOTH_RESTRICT];
        ARGS(k, 2, v->aptr, v->amem, v->c, rp, col, A, v->minv, r->m, y->m, rc->m);
        return amg_run_w(c, K_AMG_PRESMOOTH_RESTRICT, (size_t)v->nc, (size_t)v->n, NULL);
    }
    /* rows (y and the residual t), then the aggregates gather t */
    cl_kernel k = c->k[K_AMG_PRESMOOTH_RESID];
    ARGS(k, 2, rp, col, A, v->minv, r->m, y->m, c->amg->resid);
    GLPGP_CHECK(amg_run(c, K_AMG_PRESMOOTH_RESID, (size_t)v->n, NULL));
    k = c->k[K_AMG_RESTRICT];
    const cl_int has_x = 0;
    ARGS(k, 2, v->aptr, v->amem, v->c, has_x, rp, col, A, c->amg->resid, c->amg->resid, rc->m);
    return amg_run_w(c, K_AMG_RESTRICT, (size_t)v->nc, (size_t)v->n, NULL);
}

glpgp_status glpgp_cl_amg_prolong_smooth(glpgp_backend *b, int l, const glpgp_vec *ec, const glpgp_vec *x,
                                          const glpgp_vec *r, glpgp_vec *y)
{
    cl_impl *c = IMPL(b);
    GLPGP_CHECK(amg_level_ok(c, l, 0, "amg_prolong_smooth"));
    const cl_amg_level *v = &c->amg->lev[l];
    /* y <- x' + M^-1 (r - A x'), x' = x + P ec (glpgp_amg_row_prolong_smooth) */
    cl_kernel k = c->k[K_AMG_PROLONG_SMOOTH];
    cl_mem rp = amg_rowptr(c, l), col = amg_col(c, l), A = amg_val(c, l);
    ARGS(k, 2, v->agg, v->c, ec->m, rp, col, A, v->minv, r->m, x->m, y->m);
    return amg_run(c, K_AMG_PROLONG_SMOOTH, (size_t)v->n, NULL);
}

glpgp_status glpgp_cl_amg_prolong(glpgp_backend *b, int l, const glpgp_vec *ec, glpgp_vec *x)
{
    cl_impl *c = IMPL(b);
    GLPGP_CHECK(amg_level_ok(c, l, 0, "amg_prolong"));
    const cl_amg_level *v = &c->amg->lev[l];
    /* x_i <- x_i + P_i ec_agg(i) */
    cl_kernel k = c->k[K_AMG_PROLONG];
    ARGS(k, 2, v->agg, v->c, ec->m, x->m);
    return amg_run(c, K_AMG_PROLONG, (size_t)v->n, NULL);
}

glpgp_status glpgp_cl_amg_coarse_solve(glpgp_backend *b, const glpgp_vec *r, glpgp_vec *x)
{
    cl_impl *c = IMPL(b);
    GLPGP_CHECK(amg_ready(c, "amg_coarse_solve"));
    /* x <- C r */
    cl_kernel k = c->k[K_AMG_DENSE];
    ARGS(k, 2, c->amg->cinv, r->m, x->m);
    return amg_run(c, K_AMG_DENSE, (size_t)c->amg->m, NULL);
}

glpgp_status glpgp_cl_amg_spmv_dots(glpgp_backend *b, int l, const glpgp_vec *x, glpgp_vec *y,
                                     const glpgp_vec *u, const glpgp_vec *w, int slot)
{
    cl_impl *c = IMPL(b);
    GLPGP_CHECK(amg_level_ok(c, l, 1, "amg_spmv_dots"));
    GLPGP_CHECK(amg_check_slot(slot, 3, "amg_spmv_dots"));
    const size_t n = (size_t)c->amg->lev[l].n;
    /* y <- A_l x;  t[slot] <- x.y;  t[slot+1] <- x.u;  t[slot+2] <- x.w */
    cl_mem part;
    cl_int off, stride;
    int direct;
    size_t groups;
    GLPGP_CHECK(amg_partials(c, n, slot, &part, &off, &stride, &direct));
    cl_kernel k = c->k[K_AMG_SPMV_DOTS];
    const cl_int has_u = u != NULL, has_w = w != NULL;
    cl_mem rp = amg_rowptr(c, l), col = amg_col(c, l), A = amg_val(c, l), um = u ? u->m : x->m,
           wm = w ? w->m : x->m;
    ARGS(k, 2, rp, col, A, x->m, y->m, has_u, um, has_w, wm, part, off, stride);
    GLPGP_CHECK(amg_run(c, K_AMG_SPMV_DOTS, n, &groups));
    if (!direct) GLPGP_CHECK(amg_finalize(c, groups, 1 | (u ? 2 : 0) | (w ? 4 : 0), slot));
    return GLPGP_OK;
}

glpgp_status glpgp_cl_amg_dots(glpgp_backend *b, const glpgp_vec *x, const glpgp_vec *u, const glpgp_vec *w,
                                int slot)
{
    cl_impl *c = IMPL(b);
    GLPGP_CHECK(amg_ready(c, "amg_dots"));
    GLPGP_CHECK(amg_check_slot(slot, 2, "amg_dots"));
    if (!u && !w) return GLPGP_OK;
    /* t[slot] <- x.u;  t[slot+1] <- x.w */
    cl_mem part;
    cl_int off, stride;
    int direct;
    size_t groups;
    GLPGP_CHECK(amg_partials(c, x->n, slot, &part, &off, &stride, &direct));
    cl_kernel k = c->k[K_AMG_DOTS];
    const cl_int has_u = u != NULL, has_w = w != NULL;
    cl_mem um = u ? u->m : x->m, wm = w ? w->m : x->m;
    ARGS(k, 2, x->m, has_u, um, has_w, wm, part, off, stride);
    GLPGP_CHECK(amg_run(c, K_AMG_DOTS, x->n, &groups));
    if (!direct) GLPGP_CHECK(amg_finalize(c, groups, (u ? 1 : 0) | (w ? 2 : 0), slot));
    return GLPGP_OK;
}

static glpgp_status amg_check_coef(glpgp_amg_coef cf, const char *what)
{
    if (cf.num >= 0) {
        GLPGP_CHECK(amg_check_slot(cf.num, 1, what));
        GLPGP_CHECK(amg_check_slot(cf.den, 1, what));
    }
    return GLPGP_OK;
}

glpgp_status glpgp_cl_amg_axpby(glpgp_backend *b, glpgp_amg_coef ca, const glpgp_vec *x, glpgp_amg_coef cc,
                                 glpgp_vec *y)
{
    cl_impl *c = IMPL(b);
    GLPGP_CHECK(amg_ready(c, "amg_axpby"));
    GLPGP_CHECK(amg_check_coef(ca, "amg_axpby"));
    GLPGP_CHECK(amg_check_coef(cc, "amg_axpby"));
    if (y->n == 0) return GLPGP_OK;
    /* y <- a x + c y, coefficients from the registers */
    cl_kernel k = c->k[K_AMG_AXPBY];
    const cl_int an = ca.num, ad = ca.den, cn = cc.num, cd = cc.den;
    ARGS(k, 2, c->amg->t, an, ad, ca.sign, x->m, cn, cd, cc.sign, y->m);
    return amg_run(c, K_AMG_AXPBY, y->n, NULL);
}

glpgp_status glpgp_cl_amg_kcombine(glpgp_backend *b, const glpgp_vec *v, const glpgp_vec *d, glpgp_vec *e,
                                    int slot)
{
    cl_impl *c = IMPL(b);
    GLPGP_CHECK(amg_ready(c, "amg_kcombine"));
    GLPGP_CHECK(amg_check_slot(slot, 5, "amg_kcombine"));
    if (e->n == 0) return GLPGP_OK;
    /* e <- c0 v + c1 d from t[slot .. slot + 4] */
    cl_kernel k = c->k[K_AMG_KCOMBINE];
    const cl_int sl = slot;
    ARGS(k, 2, c->amg->t, sl, v->m, d->m, e->m);
    return amg_run(c, K_AMG_KCOMBINE, e->n, NULL);
}

glpgp_status glpgp_cl_amg_coarse_correction(glpgp_backend *b, int lc, int sym, const glpgp_vec *rhs,
                                             glpgp_vec *e, int *done)
{
    cl_impl *c = IMPL(b);
    *done = 0;
    GLPGP_CHECK(amg_ready(c, "amg_coarse_correction"));
    cl_amg *a = c->amg;
    if (lc != a->lb || a->lb >= a->L) return GLPGP_OK; /* the driver runs this level */
    /* e <- coarse correction of levels lb .. L-1, one work-item (glpgp_amg_bottom) */
    cl_kernel k = c->k[K_AMG_BOTTOM];
    /* the symmetric cycle: max(pre, post) sweeps on both sides, W-visits */
    const cl_int nu = a->pre > a->post ? a->pre : a->post;
    const cl_int lb = a->lb, L = a->L, pre = sym ? nu : a->pre, post = sym ? nu : a->post, m = a->m,
                 ci = a->cinv_off, sy = sym != 0;
    ARGS(k, 0, lb, L, pre, post, m, ci, a->tab, a->ipack, a->dpack, a->t, rhs->m, e->m, sy);
    GLPGP_CHECK(glpgp_cl_launch(c, K_AMG_BOTTOM, 1, 1));
    *done = 1;
    return GLPGP_OK;
}

glpgp_status glpgp_cl_amg_get_scalars(glpgp_backend *b, double *out, int n)
{
    cl_impl *c = IMPL(b);
    GLPGP_CHECK(amg_ready(c, "amg_get_scalars"));
    if (n <= 0) return GLPGP_OK;
    if (n > GLPGP_AMG_NSLOTS) n = GLPGP_AMG_NSLOTS;
    return glpgp_cl_sync_read(c, c->amg->t, 0, (size_t)n * sizeof(double), out);
}

#endif /* GLPGP_HAVE_OPENCL */
