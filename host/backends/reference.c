/* backends/reference.c: the scalar C reference backend: every op of backend.h as a
 * plain single-threaded loop over host arrays. The loop bodies are the per-row
 * functions of kernels/rows.h, which the OpenCL kernels call too, so the two
 * backends store bit-identical rows; the reductions here are one sequential
 * sum over all rows (the kernels sum per-work-item partials). The multilevel
 * preconditioner's ops (amg_*) are in reference_amg.c. */
#include "glpgp/backends.h"
#include "rows.h"
#include "coupled_rows.h"
#include "newton_rows.h"

#include "reference_impl.h"

#include <stdlib.h>
#include <string.h>

_Static_assert(GLPGP_ROWS_S_PQ == GLPGP_S_PQ, "kernels/rows.h: p.Ap slot differs from glpgp/backend.h");

static void ref_destroy(glpgp_backend *b)
{
    ref_impl *r = IMPL(b);
    if (!r) return;
    free(r->wbuf);
    free(r->dir);
    free(r->size);
    free(r->quad);
    free(r->newton);
    free(r->dinv);
    free(r->pgrad);
    glpgp_ref_amg_free(r);
    free(r);
    b->impl = NULL;
}

static glpgp_status ref_setup(glpgp_backend *b, const glpgp_system *sys)
{
    ref_impl *r = IMPL(b);
    /* a backend may be set up again for another system: drop the old buffers */
    glpgp_free(&r->wbuf);
    glpgp_free(&r->dir);
    glpgp_free(&r->size);
    r->sized = 0;
    glpgp_free(&r->quad);
    glpgp_free(&r->newton);
    glpgp_free(&r->dinv);
    glpgp_free(&r->pgrad);
    glpgp_ref_amg_free(r); /* a hierarchy belongs to one system */
    r->sys = sys;
    b->sys = sys;
    GLPGP_CHECK(glpgp_calloc((size_t)2 * sys->nv, sizeof(double), &r->wbuf));
    r->w = r->wbuf;
    GLPGP_CHECK(glpgp_calloc((size_t)sys->nv, 1, &r->dir));
    GLPGP_CHECK(glpgp_calloc((size_t)sys->nv, sizeof(double), &r->size));
    GLPGP_CHECK(glpgp_calloc((size_t)4 * sys->nnzb, sizeof(double), &r->quad));
    GLPGP_CHECK(glpgp_calloc((size_t)4 * sys->nnzb, sizeof(double), &r->newton));
    GLPGP_CHECK(glpgp_calloc((size_t)4 * sys->nv, sizeof(double), &r->dinv));
    GLPGP_CHECK(glpgp_calloc((size_t)2 * sys->nv, sizeof(double), &r->pgrad));
    return GLPGP_OK;
}

static glpgp_status ref_vec_create(glpgp_backend *b, size_t n, glpgp_vec **out)
{
    (void)b;
    glpgp_vec *v = NULL;
    *out = NULL;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *v, &v));
    v->n = n;
    glpgp_status st = glpgp_calloc(n, sizeof(double), &v->a);
    if (st != GLPGP_OK) {
        free(v);
        return st;
    }
    *out = v;
    return GLPGP_OK;
}

static void ref_vec_destroy(glpgp_backend *b, glpgp_vec **v)
{
    (void)b;
    if (!v || !*v) return;
    free((*v)->a);
    free(*v);
    *v = NULL;
}

static glpgp_status ref_vec_write(glpgp_backend *b, glpgp_vec *v, const double *h)
{
    (void)b;
    memcpy(v->a, h, v->n * sizeof(double));
    return GLPGP_OK;
}

static glpgp_status ref_vec_read(glpgp_backend *b, const glpgp_vec *v, double *h)
{
    (void)b;
    memcpy(h, v->a, v->n * sizeof(double));
    return GLPGP_OK;
}

static glpgp_status ref_copy(glpgp_backend *b, glpgp_vec *d, const glpgp_vec *s)
{
    (void)b;
    memcpy(d->a, s->a, s->n * sizeof(double));
    return GLPGP_OK;
}

static glpgp_status ref_axpby(glpgp_backend *b, double a, const glpgp_vec *x, double c, glpgp_vec *y)
{
    (void)b;
    /* y <- a x + c y  (a zero coefficient does not read its vector) */
    for (size_t i = 0; i < y->n; i++) glpgp_entry_axpby((long)i, a, x->a, c, y->a);
    return GLPGP_OK;
}

static glpgp_status ref_dot(glpgp_backend *b, const glpgp_vec *x, const glpgp_vec *y, int slot)
{
    if (slot < 0 || slot >= GLPGP_NSLOTS) return GLPGP_FAIL(GLPGP_ERR_ARG, "dot: bad slot %d", slot);
    /* s[slot] <- sum_i x_i y_i */
    IMPL(b)->s[slot] = glpgp_range_dot(0, (long)x->n, x->a, y->a);
    return GLPGP_OK;
}

static glpgp_status ref_get_scalars(glpgp_backend *b, double *out, int n)
{
    memcpy(out, IMPL(b)->s, (size_t)n * sizeof(double));
    return GLPGP_OK;
}

static glpgp_status ref_set_field(glpgp_backend *b, const double *w, const unsigned char *dir)
{
    ref_impl *r = IMPL(b);
    memcpy(r->wbuf, w, (size_t)2 * r->sys->nv * sizeof(double));
    memcpy(r->dir, dir, (size_t)r->sys->nv);
    r->sized = 0;
    return GLPGP_OK;
}

static glpgp_status ref_set_size(glpgp_backend *b, const double *size)
{
    ref_impl *r = IMPL(b);
    r->sized = size != NULL;
    if (size) memcpy(r->size, size, (size_t)r->sys->nv * sizeof(double));
    return GLPGP_OK;
}

static glpgp_status ref_assemble_quadratic(glpgp_backend *b, int kind, double h)
{
    ref_impl *r = IMPL(b);
    const glpgp_system *sys = r->sys;
    const glpgp_mesh *m = sys->mesh;
    r->kind = kind;
    r->h = h;
    /* QUAD <- gather of the element entries into each block slot, row by row
     * (coupled cross-field system: pulled back through each corner's matching) */
    if (sys->cconj) {
        for (int i = 0; i < sys->nv; i++)
            glpgp_crow_asm_quad(i, kind, h, r->sized, r->size, m->xy, sys->ctxy, m->tri, sys->cconj, sys->crot, sys->cfield,
                                sys->rowptr, sys->cptr, sys->contrib, r->quad);
        return GLPGP_OK;
    }
    for (int i = 0; i < sys->nv; i++)
        glpgp_row_asm_quad(i, kind, h, r->sized, r->size, m->xy, m->tri, r->w, sys->rowptr, sys->cptr,
                           sys->contrib, r->quad);
    return GLPGP_OK;
}

static glpgp_status ref_assemble_newton(glpgp_backend *b, const glpgp_vec *xv, double inv4e2, int hess)
{
    ref_impl *r = IMPL(b);
    const glpgp_system *sys = r->sys;
    const glpgp_mesh *m = sys->mesh;
    int bad = -1;
    /* NEWTON <- QUAD + penalty Hessian (Dirichlet rows/cols -> identity);
     * DINV_i <- inverse of the 2x2 diagonal block */
    if (sys->cconj) {
        for (int i = 0; i < sys->nv; i++)
            if (glpgp_crow_asm_newton(i, hess, inv4e2, m->xy, sys->ctxy, m->tri, sys->cconj, sys->crot, xv->a, sys->rowptr, sys->col,
                                      sys->diag, sys->vptr, sys->vtri, r->dir, r->quad, r->newton, r->dinv) &&
                bad < 0)
                bad = i;
    } else {
    for (int i = 0; i < sys->nv; i++)
        if (glpgp_row_asm_newton(i, hess, inv4e2, m->xy, m->tri, xv->a, sys->rowptr, sys->col, sys->diag,
                                 sys->vptr, sys->vtri, r->dir, r->quad, r->newton, r->dinv) &&
            bad < 0)
            bad = i;
    }
    if (bad >= 0) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "singular diagonal block at vertex %d", bad);
    return GLPGP_OK;
}

/* P <- sum_t P_t(z)  (0 without penalty) */
static double penalty_sum(const glpgp_system *sys, const double *z, double inv4e2)
{
    double p = 0.0;
    if (!(inv4e2 > 0.0)) return 0.0;
    if (sys->cconj) { /* coupled: at the frame values */
        for (int t = 0; t < sys->nt; t++)
            p += glpgp_ctri_pen_energy(t, inv4e2, sys->mesh->xy, sys->ctxy, sys->mesh->tri, sys->cconj, sys->crot, z);
        return p;
    }
    for (int t = 0; t < sys->nt; t++) p += glpgp_tri_pen_energy(t, inv4e2, sys->mesh->xy, sys->mesh->tri, z);
    return p;
}

static glpgp_status ref_gradient(glpgp_backend *b, const glpgp_vec *xv, double inv4e2, glpgp_vec *g)
{
    ref_impl *r = IMPL(b);
    const glpgp_system *sys = r->sys;
    const glpgp_mesh *m = sys->mesh;
    /* g <- QUAD x + grad P (0 at Dirichlet vertices);  E = 1/2 x.QUAD x;  P = sum_t P_t */
    double e = 0.0;
    if (sys->cconj)
        for (int i = 0; i < sys->nv; i++)
            glpgp_crow_gradient(i, inv4e2, m->xy, sys->ctxy, m->tri, sys->cconj, sys->crot, xv->a, sys->rowptr, sys->col, r->quad,
                                sys->vptr, sys->vtri, r->dir, g->a, &e);
    else {
        /* the values of glpgp_row_gradient (the OpenCL kernel's rows) and of
         * penalty_sum, bit for bit, with each triangle's quadrature evaluated
         * once instead of once per corner plus once for the energy: per
         * triangle in increasing order, the three corner gradients added to
         * their vertices (the gather's order) and P_t to P
         * (glpgp_pen_grad_tri); then per row QUAD x + that sum */
        double p = 0.0, *pg = r->pgrad;
        if (inv4e2 > 0.0) {
            for (size_t k = 0; k < (size_t)2 * sys->nv; k++) pg[k] = 0.0;
            for (int t = 0; t < m->nt; t++) {
                const int *v = m->tri + 3 * (size_t)t;
                double x[3], y[3], zr[3], zi[3], gt[6], et;
                glpgp_tri_load(m->xy, m->tri, t, x, y);
                glpgp_tri_vals(m->tri, xv->a, t, zr, zi);
                glpgp_pen_grad_tri(glpgp_tri_area(x, y), inv4e2, zr, zi, gt, &et);
                p += et;
                for (int a = 0; a < 3; a++) {
                    pg[2 * v[a]] += gt[2 * a];
                    pg[2 * v[a] + 1] += gt[2 * a + 1];
                }
            }
        }
        for (int i = 0; i < sys->nv; i++) {
            /* g_i <- (QUAD x)_i + grad_i P (0 when Dirichlet);  e += x_i . (QUAD x)_i */
            double y0, y1;
            glpgp_row_spmv(i, sys->rowptr, sys->col, r->quad, xv->a, &y0, &y1);
            glpgp_row_dot_acc(i, xv->a, y0, y1, &e);
            if (r->dir[i]) {
                y0 = 0.0;
                y1 = 0.0;
            } else if (inv4e2 > 0.0) {
                y0 += pg[2 * i];
                y1 += pg[2 * i + 1];
            }
            g->a[2 * i] = y0;
            g->a[2 * i + 1] = y1;
        }
        r->s[GLPGP_S_E] = 0.5 * e;
        r->s[GLPGP_S_P] = p;
        return GLPGP_OK;
    }
    r->s[GLPGP_S_E] = 0.5 * e;
    r->s[GLPGP_S_P] = penalty_sum(sys, xv->a, inv4e2);
    return GLPGP_OK;
}

/* y <- M x;  returns x.y */
static double spmv_dot(const glpgp_system *sys, const double *M, const double *x, double *y)
{
    double s = 0.0;
    for (int i = 0; i < sys->nv; i++) glpgp_row_spmv_dot(i, sys->rowptr, sys->col, M, x, y, &s);
    return s;
}

static glpgp_status ref_energy(glpgp_backend *b, const glpgp_vec *xv, double inv4e2, glpgp_vec *work)
{
    ref_impl *r = IMPL(b);
    /* work <- QUAD x;  E = 1/2 x.work;  P = sum_t P_t */
    r->s[GLPGP_S_E] = 0.5 * spmv_dot(r->sys, r->quad, xv->a, work->a);
    r->s[GLPGP_S_P] = penalty_sum(r->sys, xv->a, inv4e2);
    return GLPGP_OK;
}

static glpgp_status ref_spmv(glpgp_backend *b, int matrix, const glpgp_vec *x, glpgp_vec *y)
{
    ref_impl *r = IMPL(b);
    const glpgp_system *sys = r->sys;
    const double *M = matrix == GLPGP_MAT_QUAD ? r->quad : r->newton;
    /* y <- M x */
    for (int i = 0; i < sys->nv; i++) glpgp_row_spmv_store(i, sys->rowptr, sys->col, M, x->a, y->a);
    return GLPGP_OK;
}

static glpgp_status ref_cg_precond(glpgp_backend *b, const glpgp_vec *r, glpgp_vec *z, int rz)
{
    ref_impl *im = IMPL(b);
    /* z <- DINV r;  s[rz] <- r.z;  s[RR] <- r.r */
    double s1 = 0.0, s2 = 0.0;
    for (int i = 0; i < im->sys->nv; i++) glpgp_row_precond(i, im->dinv, r->a, z->a, &s1, &s2);
    im->s[rz] = s1;
    im->s[GLPGP_S_RR] = s2;
    return GLPGP_OK;
}

static glpgp_status ref_cg_spmv_dot(glpgp_backend *b, const glpgp_vec *p, glpgp_vec *q)
{
    ref_impl *im = IMPL(b);
    /* q <- N p;  s[PQ] <- p.q */
    im->s[GLPGP_S_PQ] = spmv_dot(im->sys, im->newton, p->a, q->a);
    return GLPGP_OK;
}

static glpgp_status ref_cg_update(glpgp_backend *b, glpgp_vec *x, glpgp_vec *r, const glpgp_vec *p,
                                  const glpgp_vec *q, glpgp_vec *z, int rz, int rz_new)
{
    ref_impl *im = IMPL(b);
    /* alpha = (r.z) / (p.Ap);  x <- x + alpha p;  r <- r - alpha q;
     * z <- DINV r;  s[rz_new] <- r.z;  s[RR] <- r.r */
    const double alpha = glpgp_cg_alpha(im->s, rz);
    double s1 = 0.0, s2 = 0.0;
    for (int i = 0; i < im->sys->nv; i++)
        glpgp_row_cg_update(i, alpha, x->a, r->a, p->a, q->a, im->dinv, z->a, &s1, &s2);
    im->s[rz_new] = s1;
    im->s[GLPGP_S_RR] = s2;
    return GLPGP_OK;
}

static glpgp_status ref_cg_direction(glpgp_backend *b, glpgp_vec *p, const glpgp_vec *z, int rz_new, int rz)
{
    ref_impl *im = IMPL(b);
    /* beta = (r.z)_new / (r.z)_old;  p <- z + beta p */
    const double beta = glpgp_cg_beta(im->s, rz_new, rz);
    for (size_t i = 0; i < p->n; i++) glpgp_entry_cg_direction((long)i, beta, p->a, z->a);
    return GLPGP_OK;
}

/* a second reference backend with b's ops (a test may have replaced some) */
static glpgp_status ref_trial_point(glpgp_backend *b, const glpgp_vec *x, const glpgp_vec *d, double a, double r1,
                                    glpgp_vec *xt)
{
    /* xt <- x (+) a d per vertex (kernels/newton_rows.h) */
    const int nv = IMPL(b)->sys->nv;
    for (int i = 0; i < nv; i++) glpgp_row_trial_point(i, x->a, d->a, a, r1, xt->a);
    return GLPGP_OK;
}

static glpgp_status ref_clone(glpgp_backend *b, glpgp_backend **out)
{
    GLPGP_CHECK(glpgp_backend_create_reference(out));
    (*out)->ops = b->ops;
    (*out)->launch_bound = b->launch_bound;
    (*out)->overlap = b->overlap;
    return GLPGP_OK;
}

static const glpgp_backend_ops ref_ops = {
    .name = "reference",
    .coupled_systems = 1,
    .destroy = ref_destroy,
    .clone = ref_clone,
    .setup = ref_setup,
    .vec_create = ref_vec_create,
    .vec_destroy = ref_vec_destroy,
    .vec_write = ref_vec_write,
    .vec_read = ref_vec_read,
    .copy = ref_copy,
    .axpby = ref_axpby,
    .dot = ref_dot,
    .get_scalars = ref_get_scalars,
    .set_field = ref_set_field,
    .set_size = ref_set_size,
    .assemble_quadratic = ref_assemble_quadratic,
    .assemble_newton = ref_assemble_newton,
    .gradient = ref_gradient,
    .energy = ref_energy,
    .spmv = ref_spmv,
    .cg_precond = ref_cg_precond,
    .cg_spmv_dot = ref_cg_spmv_dot,
    .cg_update = ref_cg_update,
    .cg_direction = ref_cg_direction,
    GLPGP_REF_AMG_OPS
    .trial_point = ref_trial_point,
};

glpgp_status glpgp_backend_create_reference(glpgp_backend **out)
{
    glpgp_backend *b = NULL;
    *out = NULL;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *b, &b));
    glpgp_status st = glpgp_calloc(1, sizeof(ref_impl), &b->impl);
    if (st != GLPGP_OK) {
        free(b);
        return st;
    }
    b->ops = &ref_ops;
    b->overlap = GLPGP_OVERLAP_ALWAYS; /* single-threaded */
    *out = b;
    return GLPGP_OK;
}
