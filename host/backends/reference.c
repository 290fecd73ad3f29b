/* backends/reference.c: the scalar C reference backend: every op of backend.h as a
 * plain single-threaded loop over host arrays. It defines the semantics (and
 * the summation order) the OpenCL kernels reproduce. The multilevel
 * preconditioner's ops (amg_*) are in reference_amg.c. */
#include "glpgp/backends.h"
#include "element.h"

#include "reference_impl.h"

#include <stdlib.h>
#include <string.h>

/* Corner coordinates, field and z of triangle t. */
static void tri_load(const glpgp_system *sys, int t, double *x, double *y)
{
    const glpgp_mesh *m = sys->mesh;
    for (int a = 0; a < 3; a++) {
        int v = m->tri[3 * t + a];
        x[a] = m->xy[2 * v];
        y[a] = m->xy[2 * v + 1];
    }
}

static void tri_vals(const glpgp_system *sys, int t, const double *v, double *vr, double *vi)
{
    for (int a = 0; a < 3; a++) {
        int i = sys->mesh->tri[3 * t + a];
        vr[a] = v[2 * i];
        vi[a] = v[2 * i + 1];
    }
}

static void ref_destroy(glpgp_backend *b)
{
    ref_impl *r = IMPL(b);
    if (!r) return;
    free(r->wbuf);
    free(r->dir);
    free(r->quad);
    free(r->newton);
    free(r->dinv);
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
    glpgp_free(&r->quad);
    glpgp_free(&r->newton);
    glpgp_free(&r->dinv);
    glpgp_ref_amg_free(r); /* a hierarchy belongs to one system */
    r->sys = sys;
    b->sys = sys;
    GLPGP_CHECK(glpgp_calloc((size_t)2 * sys->nv, sizeof(double), &r->wbuf));
    r->w = r->wbuf;
    GLPGP_CHECK(glpgp_calloc((size_t)sys->nv, 1, &r->dir));
    GLPGP_CHECK(glpgp_calloc((size_t)4 * sys->nnzb, sizeof(double), &r->quad));
    GLPGP_CHECK(glpgp_calloc((size_t)4 * sys->nnzb, sizeof(double), &r->newton));
    GLPGP_CHECK(glpgp_calloc((size_t)4 * sys->nv, sizeof(double), &r->dinv));
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
    /* y <- a x + c y */
    for (size_t i = 0; i < y->n; i++) y->a[i] = a * x->a[i] + c * y->a[i];
    return GLPGP_OK;
}

static double dot_n(const double *x, const double *y, size_t n)
{
    double s = 0.0;
    for (size_t i = 0; i < n; i++) s += x[i] * y[i];
    return s;
}

static glpgp_status ref_dot(glpgp_backend *b, const glpgp_vec *x, const glpgp_vec *y, int slot)
{
    IMPL(b)->s[slot] = dot_n(x->a, y->a, x->n);
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
    return GLPGP_OK;
}

static glpgp_status ref_assemble_quadratic(glpgp_backend *b, int kind, double h)
{
    ref_impl *r = IMPL(b);
    const glpgp_system *sys = r->sys;
    const int *tri = sys->mesh->tri;
    r->kind = kind;
    r->h = h;
    for (long k = 0; k < sys->nnzb; k++) {
        /* block(k) = sum over contributing element entries (t,a,b), in slot-map order */
        double re = 0.0, im = 0.0;
        for (int c = sys->cptr[k]; c < sys->cptr[k + 1]; c++) {
            int e = sys->contrib[c], t = e / 9, a = (e % 9) / 3, bb = e % 3;
            double x[3], y[3], wx[3], wy[3], er, ei;
            tri_load(sys, t, x, y);
            for (int q = 0; q < 3; q++) {
                wx[q] = r->w[2 * tri[3 * t + q]];
                wy[q] = r->w[2 * tri[3 * t + q] + 1];
            }
            glpgp_elem_entry(kind, x, y, wx, wy, h, a, bb, &er, &ei);
            re += er;
            im += ei;
        }
        /* complex entry re + i im as the real 2x2 block [[re, -im], [im, re]] */
        double *blk = r->quad + 4 * k;
        blk[0] = re;
        blk[1] = -im;
        blk[2] = im;
        blk[3] = re;
    }
    return GLPGP_OK;
}

static glpgp_status ref_assemble_newton(glpgp_backend *b, const glpgp_vec *xv, double inv4e2, int hess)
{
    ref_impl *r = IMPL(b);
    const glpgp_system *sys = r->sys;
    const double *z = xv->a;
    for (int i = 0; i < sys->nv; i++) {
        for (int k = sys->rowptr[i]; k < sys->rowptr[i + 1]; k++) {
            int j = sys->col[k];
            double *blk = r->newton + 4 * k;
            if (r->dir[i] || r->dir[j]) {
                /* Dirichlet row or column: identity on the diagonal, zero elsewhere */
                double d = (i == j) ? 1.0 : 0.0;
                blk[0] = d;
                blk[1] = 0.0;
                blk[2] = 0.0;
                blk[3] = d;
                continue;
            }
            double m0 = 0.0, m1 = 0.0, m2 = 0.0, m3 = 0.0;
            if (inv4e2 > 0.0) {
                /* penalty Hessian blocks of the contributing elements, slot-map order */
                for (int c = sys->cptr[k]; c < sys->cptr[k + 1]; c++) {
                    int e = sys->contrib[c], t = e / 9, a = (e % 9) / 3, bb = e % 3;
                    double x[3], y[3], zr[3], zi[3], hm[4];
                    tri_load(sys, t, x, y);
                    tri_vals(sys, t, z, zr, zi);
                    glpgp_pen_hess(hess, glpgp_tri_area(x, y), inv4e2, zr, zi, a, bb, hm);
                    m0 += hm[0];
                    m1 += hm[1];
                    m2 += hm[2];
                    m3 += hm[3];
                }
            }
            const double *qb = r->quad + 4 * k;
            blk[0] = qb[0] + m0;
            blk[1] = qb[1] + m1;
            blk[2] = qb[2] + m2;
            blk[3] = qb[3] + m3;
        }
        /* DINV_i <- inverse of the 2x2 diagonal block */
        const double *d = r->newton + 4 * sys->diag[i];
        double det = d[0] * d[3] - d[1] * d[2];
        double *o = r->dinv + 4 * i;
        if (det == 0.0) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "singular diagonal block at vertex %d", i);
        o[0] = d[3] / det;
        o[1] = -d[1] / det;
        o[2] = -d[2] / det;
        o[3] = d[0] / det;
    }
    return GLPGP_OK;
}

/* y <- M x, 2x2-block CSR */
static void spmv_blocks(const glpgp_system *sys, const double *val, const double *x, double *y)
{
    for (int i = 0; i < sys->nv; i++) {
        double y0 = 0.0, y1 = 0.0;
        for (int k = sys->rowptr[i]; k < sys->rowptr[i + 1]; k++) {
            const double *blk = val + 4 * k;
            const double *xj = x + 2 * sys->col[k];
            y0 += blk[0] * xj[0] + blk[1] * xj[1];
            y1 += blk[2] * xj[0] + blk[3] * xj[1];
        }
        y[2 * i] = y0;
        y[2 * i + 1] = y1;
    }
}

static double penalty_sum(const glpgp_system *sys, const double *z, double inv4e2)
{
    /* P <- sum_t P_t */
    double p = 0.0;
    if (inv4e2 <= 0.0) return 0.0;
    for (int t = 0; t < sys->nt; t++) {
        double x[3], y[3], zr[3], zi[3];
        tri_load(sys, t, x, y);
        tri_vals(sys, t, z, zr, zi);
        p += glpgp_pen_energy(glpgp_tri_area(x, y), inv4e2, zr, zi);
    }
    return p;
}

static glpgp_status ref_gradient(glpgp_backend *b, const glpgp_vec *xv, double inv4e2, glpgp_vec *g)
{
    ref_impl *r = IMPL(b);
    const glpgp_system *sys = r->sys;
    const double *z = xv->a;
    /* g <- QUAD x;  E = 1/2 x.g */
    spmv_blocks(sys, r->quad, z, g->a);
    r->s[GLPGP_S_E] = 0.5 * dot_n(z, g->a, g->n);
    r->s[GLPGP_S_P] = penalty_sum(sys, z, inv4e2);
    for (int i = 0; i < sys->nv; i++) {
        if (r->dir[i]) {
            g->a[2 * i] = 0.0;
            g->a[2 * i + 1] = 0.0;
            continue;
        }
        if (inv4e2 <= 0.0) continue;
        /* g_i += sum over incident triangles of dP_t/dX_i */
        double gr = 0.0, gi = 0.0;
        for (int p = sys->vptr[i]; p < sys->vptr[i + 1]; p++) {
            int t = sys->vtri[p] / 3, a = sys->vtri[p] % 3;
            double x[3], y[3], zr[3], zi[3], er, ei;
            tri_load(sys, t, x, y);
            tri_vals(sys, t, z, zr, zi);
            glpgp_pen_grad(glpgp_tri_area(x, y), inv4e2, zr, zi, a, &er, &ei);
            gr += er;
            gi += ei;
        }
        g->a[2 * i] += gr;
        g->a[2 * i + 1] += gi;
    }
    return GLPGP_OK;
}

static glpgp_status ref_energy(glpgp_backend *b, const glpgp_vec *xv, double inv4e2, glpgp_vec *work)
{
    ref_impl *r = IMPL(b);
    /* E = 1/2 x.(QUAD x), P = sum_t P_t */
    spmv_blocks(r->sys, r->quad, xv->a, work->a);
    r->s[GLPGP_S_E] = 0.5 * dot_n(xv->a, work->a, xv->n);
    r->s[GLPGP_S_P] = penalty_sum(r->sys, xv->a, inv4e2);
    return GLPGP_OK;
}

static glpgp_status ref_spmv(glpgp_backend *b, int matrix, const glpgp_vec *x, glpgp_vec *y)
{
    ref_impl *r = IMPL(b);
    spmv_blocks(r->sys, matrix == GLPGP_MAT_QUAD ? r->quad : r->newton, x->a, y->a);
    return GLPGP_OK;
}

/* z_i <- DINV_i r_i for all i; returns r.z, r.r in *rz, *rr */
static void precond(const ref_impl *r, const double *rv, double *z, size_t nv, double *rz, double *rr)
{
    double s1 = 0.0, s2 = 0.0;
    for (size_t i = 0; i < nv; i++) {
        const double *d = r->dinv + 4 * i;
        double r0 = rv[2 * i], r1 = rv[2 * i + 1];
        double z0 = d[0] * r0 + d[1] * r1, z1 = d[2] * r0 + d[3] * r1;
        z[2 * i] = z0;
        z[2 * i + 1] = z1;
        s1 += r0 * z0 + r1 * z1;
        s2 += r0 * r0 + r1 * r1;
    }
    *rz = s1;
    *rr = s2;
}

static glpgp_status ref_cg_precond(glpgp_backend *b, const glpgp_vec *r, glpgp_vec *z, int rz)
{
    ref_impl *im = IMPL(b);
    precond(im, r->a, z->a, (size_t)im->sys->nv, &im->s[rz], &im->s[GLPGP_S_RR]);
    return GLPGP_OK;
}

static glpgp_status ref_cg_spmv_dot(glpgp_backend *b, const glpgp_vec *p, glpgp_vec *q)
{
    ref_impl *im = IMPL(b);
    /* q <- N p;  s[PQ] <- p.q */
    spmv_blocks(im->sys, im->newton, p->a, q->a);
    im->s[GLPGP_S_PQ] = dot_n(p->a, q->a, p->n);
    return GLPGP_OK;
}

static glpgp_status ref_cg_update(glpgp_backend *b, glpgp_vec *x, glpgp_vec *r, const glpgp_vec *p,
                                  const glpgp_vec *q, glpgp_vec *z, int rz, int rz_new)
{
    ref_impl *im = IMPL(b);
    /* alpha = (r.z) / (p.Ap);  x <- x + alpha p;  r <- r - alpha q */
    double alpha = im->s[rz] / im->s[GLPGP_S_PQ];
    for (size_t i = 0; i < x->n; i++) {
        x->a[i] += alpha * p->a[i];
        r->a[i] -= alpha * q->a[i];
    }
    /* z <- DINV r;  s[rz_new] <- r.z;  s[RR] <- r.r */
    precond(im, r->a, z->a, (size_t)im->sys->nv, &im->s[rz_new], &im->s[GLPGP_S_RR]);
    return GLPGP_OK;
}

static glpgp_status ref_cg_direction(glpgp_backend *b, glpgp_vec *p, const glpgp_vec *z, int rz_new, int rz)
{
    ref_impl *im = IMPL(b);
    /* beta = (r.z)_new / (r.z)_old;  p <- z + beta p */
    double beta = im->s[rz_new] / im->s[rz];
    for (size_t i = 0; i < p->n; i++) p->a[i] = z->a[i] + beta * p->a[i];
    return GLPGP_OK;
}

static const glpgp_backend_ops ref_ops = {
    .name = "reference",
    .destroy = ref_destroy,
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
    *out = b;
    return GLPGP_OK;
}
