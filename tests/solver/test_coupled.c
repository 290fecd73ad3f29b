/* test_coupled.c: the oscillators coupled across the cross field's cuts
 * (issue 14, item 3; solver/coupled.c, kernels/coupled_rows.h):
 *  - the matching maps compose like quarter turns (map_r1 o map_r2 = map_{r1+r2});
 *  - gauge / matching invariance: the coupled E and P of one state computed
 *    with random representatives (each vertex's U turned by k_i quarter
 *    turns, its (z_u, z_v) mapped accordingly) are the same, and equal the
 *    uncoupled E_u + E_v, P_u + P_v for a smooth field;
 *  - finite differences of the coupled energy (gradient) and gradient
 *    (exact Hessian, NEWTON) at a random state, with representatives from a
 *    field with a singularity (cuts, conjugated corners);
 *  - the multigrid across cuts: with representatives turned by a quarter
 *    turn per quadrant (cuts along the axes, conjugated corners on them)
 *    the frame's phase mode i z, mapped to the nodes
 *    (+i z on one side of a conjugation, -i z on the other), and z itself
 *    are reproduced by the prolongations on every level (no aggregate
 *    joins nodes across a conjugation); with random representatives
 *    (conjugations everywhere) the coarsening still ends small;
 *  - the conformal size of a cross field with theta = a y is h e^{a x + c}. */
#include "testutil.h"
#include "amg_testutil.h"

#include <string.h>

/* out <- (wx, wy) turned by k quarter turns (+90 degrees each) */
static void quarter_turns(int k, double wx, double wy, double *out)
{
    for (int q = 0; q < k; q++) {
        const double t = -wy;
        wy = wx;
        wx = t;
    }
    out[0] = wx;
    out[1] = wy;
}

static void frame_value_r(int r, const double *zu, const double *zv, double *ou, double *ov)
{
    glpgp_coupled_frame_value(r, 0, zu, zv, ou);
    glpgp_coupled_frame_value(r, 1, zu, zv, ov);
}

static void test_maps(void)
{
    const double zu[2] = {0.3, -0.7}, zv[2] = {-0.2, 0.9};
    for (int r1 = 0; r1 < 4; r1++)
        for (int r2 = 0; r2 < 4; r2++) {
            double a[2], b[2], c[2], d[2], e[2], f[2];
            frame_value_r(r2, zu, zv, a, b);
            frame_value_r(r1, a, b, c, d);
            frame_value_r((r1 + r2) & 3, zu, zv, e, f);
            CHECK(c[0] == e[0] && c[1] == e[1] && d[0] == f[0] && d[1] == f[1]);
        }
    const double u0[2] = {1.0, 0.0}, u1[2] = {0.1, 0.995}, u2[2] = {-1.0, 0.05}, u3[2] = {0.02, -1.0};
    CHECK(glpgp_cross_turn(u0, u0) == 0);
    CHECK(glpgp_cross_turn(u1, u0) == 1); /* rot(U0) ~ U1 */
    CHECK(glpgp_cross_turn(u2, u0) == 2);
    CHECK(glpgp_cross_turn(u3, u0) == 3);
    CHECK(glpgp_cross_turn(u0, u1) == 3);
}

typedef struct cstate {
    glpgp_coupled *cp;
    glpgp_backend *b;
    glpgp_vec *x, *g, *d, *w;
    int n;
} cstate;

static void cs_open(cstate *s, const glpgp_mesh *m, const double *u, double h)
{
    memset(s, 0, sizeof *s);
    CHECK_OK(glpgp_coupled_create(m, u, &s->cp));
    CHECK_OK(glpgp_backend_create_reference(&s->b));
    CHECK_OK(s->b->ops->setup(s->b, s->cp->sys));
    s->n = 4 * m->nv;
    double *wn = calloc((size_t)s->n, sizeof(double));
    unsigned char *dir = calloc((size_t)2 * m->nv, 1);
    glpgp_coupled_node_field(u, m->nv, wn);
    CHECK_OK(s->b->ops->set_field(s->b, wn, dir));
    CHECK_OK(s->b->ops->assemble_quadratic(s->b, GLPGP_ELEM_P1, h));
    CHECK_OK(s->b->ops->vec_create(s->b, (size_t)s->n, &s->x));
    CHECK_OK(s->b->ops->vec_create(s->b, (size_t)s->n, &s->g));
    CHECK_OK(s->b->ops->vec_create(s->b, (size_t)s->n, &s->d));
    CHECK_OK(s->b->ops->vec_create(s->b, (size_t)s->n, &s->w));
    free(wn);
    free(dir);
}

static void cs_close(cstate *s)
{
    s->b->ops->vec_destroy(s->b, &s->x);
    s->b->ops->vec_destroy(s->b, &s->g);
    s->b->ops->vec_destroy(s->b, &s->d);
    s->b->ops->vec_destroy(s->b, &s->w);
    glpgp_backend_destroy(&s->b);
    glpgp_coupled_destroy(&s->cp);
}

/* E, P of the coupled system at x (4 nv); g (host, may be NULL) <- gradient */
static void cs_eval(cstate *s, const double *x, double inv4e2, double *e, double *p, double *g)
{
    double sl[GLPGP_NSLOTS];
    CHECK_OK(s->b->ops->vec_write(s->b, s->x, x));
    CHECK_OK(s->b->ops->gradient(s->b, s->x, inv4e2, s->g));
    CHECK_OK(s->b->ops->get_scalars(s->b, sl, GLPGP_NSLOTS));
    *e = sl[GLPGP_S_E];
    *p = sl[GLPGP_S_P];
    if (g) CHECK_OK(s->b->ops->vec_read(s->b, s->g, g));
}

/* uncoupled E_W(z) + P(z) of one oscillator with field w (2 nv) */
static void osc_eval(const glpgp_mesh *m, const double *w, const double *z, double h, double inv4e2, double *e,
                     double *p)
{
    glpgp_system *sys = NULL;
    glpgp_backend *b = NULL;
    glpgp_vec *x = NULL, *g = NULL;
    unsigned char *dir = calloc((size_t)m->nv, 1);
    double sl[GLPGP_NSLOTS];
    CHECK_OK(glpgp_system_create(m, &sys));
    CHECK_OK(glpgp_backend_create_reference(&b));
    CHECK_OK(b->ops->setup(b, sys));
    CHECK_OK(b->ops->set_field(b, w, dir));
    CHECK_OK(b->ops->assemble_quadratic(b, GLPGP_ELEM_P1, h));
    CHECK_OK(b->ops->vec_create(b, (size_t)2 * m->nv, &x));
    CHECK_OK(b->ops->vec_create(b, (size_t)2 * m->nv, &g));
    CHECK_OK(b->ops->vec_write(b, x, z));
    CHECK_OK(b->ops->gradient(b, x, inv4e2, g));
    CHECK_OK(b->ops->get_scalars(b, sl, GLPGP_NSLOTS));
    *e = sl[GLPGP_S_E];
    *p = sl[GLPGP_S_P];
    b->ops->vec_destroy(b, &x);
    b->ops->vec_destroy(b, &g);
    glpgp_backend_destroy(&b);
    glpgp_system_destroy(&sys);
    free(dir);
}

static void test_invariance(void)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 800, &m));
    if (!m) return;
    const int nv = m->nv;
    const double h = 0.4, inv4e2 = 1.0 / (4.0 * 0.1 * 0.1);
    double *u = malloc((size_t)2 * nv * sizeof(double)), *u2 = malloc((size_t)2 * nv * sizeof(double));
    double *x = malloc((size_t)4 * nv * sizeof(double)), *x2 = malloc((size_t)4 * nv * sizeof(double));
    double *zu = malloc((size_t)2 * nv * sizeof(double)), *zv = malloc((size_t)2 * nv * sizeof(double));
    double *vv = malloc((size_t)2 * nv * sizeof(double));
    for (int i = 0; i < nv; i++) {
        const double px = m->xy[2 * i], py = m->xy[2 * i + 1], th = 0.4 * px + 0.3 * py;
        u[2 * i] = cos(th);
        u[2 * i + 1] = sin(th);
        vv[2 * i] = -u[2 * i + 1];
        vv[2 * i + 1] = u[2 * i];
        /* a state near the plane waves, with noise */
        const double pu = 2.0 * GLPGP_PI * (u[2 * i] * px + u[2 * i + 1] * py) / h + 0.3 * tu_rand();
        const double pv = 2.0 * GLPGP_PI * (vv[2 * i] * px + vv[2 * i + 1] * py) / h + 0.3 * tu_rand();
        const double au = 0.8 + 0.4 * tu_rand(), av = 0.8 + 0.4 * tu_rand();
        zu[2 * i] = au * cos(pu);
        zu[2 * i + 1] = au * sin(pu);
        zv[2 * i] = av * cos(pv);
        zv[2 * i + 1] = av * sin(pv);
        x[4 * i] = zu[2 * i];
        x[4 * i + 1] = zu[2 * i + 1];
        x[4 * i + 2] = zv[2 * i];
        x[4 * i + 3] = zv[2 * i + 1];
        /* random representative: U' = rot^k U, (z_u', z_v') = map_k(z_u, z_v) */
        const int k = (int)(4.0 * tu_rand()) & 3;
        quarter_turns(k, u[2 * i], u[2 * i + 1], u2 + 2 * i);
        frame_value_r(k, zu + 2 * i, zv + 2 * i, x2 + 4 * i, x2 + 4 * i + 2);
    }
    cstate a, b;
    double ea, pa, eb, pb;
    cs_open(&a, m, u, h);
    cs_eval(&a, x, inv4e2, &ea, &pa, NULL);
    int conj_a = 0, conj_b = 0;
    for (int c = 0; c < 6 * m->nt; c++) conj_a += a.cp->sys->cconj[c];
    cs_close(&a);
    cs_open(&b, m, u2, h);
    cs_eval(&b, x2, inv4e2, &eb, &pb, NULL);
    for (int c = 0; c < 6 * m->nt; c++) conj_b += b.cp->sys->cconj[c];
    cs_close(&b);
    CHECK(conj_a == 0); /* a smooth field with continuous representatives has no cut */
    CHECK(conj_b > 0);  /* random representatives: many conjugated corners */
    CHECK(ea > 1.0 && pa > 1.0);
    CHECK_CLOSE(eb, ea, 0.0, 1e-11);
    CHECK_CLOSE(pb, pa, 0.0, 1e-11);
    /* the uncoupled pair */
    double e_u, p_u, e_v, p_v;
    osc_eval(m, u, zu, h, inv4e2, &e_u, &p_u);
    osc_eval(m, vv, zv, h, inv4e2, &e_v, &p_v);
    CHECK_CLOSE(ea, e_u + e_v, 0.0, 1e-12);
    CHECK_CLOSE(pa, p_u + p_v, 0.0, 1e-12);
    printf("invariance: E %.15g / %.15g / %.15g, P %.15g / %.15g / %.15g, conjugated corners %d\n", ea, eb,
           e_u + e_v, pa, pb, p_u + p_v, conj_b);
    free(u);
    free(u2);
    free(x);
    free(x2);
    free(zu);
    free(zv);
    free(vv);
    glpgp_mesh_destroy(&m);
}

/* The coupled multigrid keeps the frame's near-null vectors across the cuts:
 * a state near the plane waves and its phase mode, both written with
 * representatives turned k times in quadrant k (map_k of (z_u, z_v) and of
 * (i z_u, i z_v): a conjugated node gets -i z), reproduced by P_l P_l^T on
 * every level of the hierarchy built with frames z. */
static void test_multigrid_cuts(int random)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 3000, &m));
    if (!m) return;
    const int nv = m->nv;
    const double h = 0.4;
    double *u2 = malloc((size_t)2 * nv * sizeof(double));
    double *x2 = malloc((size_t)4 * nv * sizeof(double)), *y2 = malloc((size_t)4 * nv * sizeof(double));
    for (int i = 0; i < nv; i++) {
        const double px = m->xy[2 * i], py = m->xy[2 * i + 1], th = 0.4 * px + 0.3 * py;
        const double ux = cos(th), uy = sin(th);
        const double pu = 2.0 * GLPGP_PI * (ux * px + uy * py) / h, pv = 2.0 * GLPGP_PI * (-uy * px + ux * py) / h;
        const double zu[2] = {cos(pu), sin(pu)}, zv[2] = {0.9 * cos(pv), 0.9 * sin(pv)};
        const double izu[2] = {-zu[1], zu[0]}, izv[2] = {-zv[1], zv[0]};
        /* the representative turned by k = the quadrant's index: cuts along the axes */
        const int k = random ? (int)(4.0 * tu_rand()) & 3 : py >= 0.0 ? (px >= 0.0 ? 0 : 1) : (px < 0.0 ? 2 : 3);
        quarter_turns(k, ux, uy, u2 + 2 * i);
        frame_value_r(k, zu, zv, x2 + 4 * i, x2 + 4 * i + 2);
        frame_value_r(k, izu, izv, y2 + 4 * i, y2 + 4 * i + 2);
    }
    cstate c;
    cs_open(&c, m, u2, h);
    int conj = 0;
    for (int q = 0; q < 6 * m->nt; q++) conj += c.cp->sys->cconj[q];
    glpgp_options o;
    glpgp_options_default(&o);
    o.precond = GLPGP_PRECOND_AMG;
    o.amg_coarse = 8;
    unsigned char *dir = calloc((size_t)2 * nv, 1);
    CHECK_OK(c.b->ops->vec_write(c.b, c.x, x2));
    CHECK_OK(c.b->ops->assemble_newton(c.b, c.x, 1.0 / (4 * 0.1 * 0.1), GLPGP_HESS_MIXED));
    glpgp_amg *a = NULL;
    CHECK_OK(glpgp_amg_create(c.b, &o, dir, NULL, h, &a));
    CHECK(a != NULL);
    if (a) {
        CHECK_OK(glpgp_amg_update(a, c.x));
        glpgp_amg_info in;
        glpgp_amg_get_info(a, &in);
        const double ez = amg_reproduce(c.b, &in, x2), eiz = amg_reproduce(c.b, &in, y2);
        printf("multigrid across cuts (%s representatives): %d conjugated corners, %d levels (%d -> %d nodes), "
               "defect of P P^T v = v: z %.2e, phase mode %.2e\n", random ? "random" : "quadrant", conj, in.nlevels,
               in.n[0], in.n[in.nlevels - 1], ez, eiz);
        CHECK(conj > 100);
        CHECK(in.nlevels >= 4);
        CHECK(ez <= 1e-13);
        /* random representatives (cuts everywhere): the aggregation stalls and
         * joins across them, the hierarchy still reaches a small coarsest level */
        CHECK(random ? in.n[in.nlevels - 1] <= 4 * o.amg_coarse : eiz <= 1e-13);
        glpgp_amg_destroy(&a);
    }
    cs_close(&c);
    free(dir);
    free(u2);
    free(x2);
    free(y2);
    glpgp_mesh_destroy(&m);
}

static void test_fd(void)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 300, &m));
    if (!m) return;
    const int nv = m->nv, n = 4 * nv;
    const double h = 0.5, inv4e2 = 1.0 / (4.0 * 0.2 * 0.2);
    double *w = malloc((size_t)2 * nv * sizeof(double)), *u = malloc((size_t)2 * nv * sizeof(double));
    double *x = malloc((size_t)n * sizeof(double)), *d = malloc((size_t)n * sizeof(double));
    double *xp = malloc((size_t)n * sizeof(double)), *g = malloc((size_t)n * sizeof(double));
    double *gp = malloc((size_t)n * sizeof(double)), *gm = malloc((size_t)n * sizeof(double));
    double *hd = malloc((size_t)n * sizeof(double));
    /* a cross field with one +1/4 singularity: w = (x - p) / |x - p| */
    for (int i = 0; i < nv; i++) {
        const double dx = m->xy[2 * i] - 0.13, dy = m->xy[2 * i + 1] - 0.21, r = hypot(dx, dy);
        w[2 * i] = dx / r;
        w[2 * i + 1] = dy / r;
    }
    CHECK(glpgp_cross_to_vector(m, w, u) > 0);
    for (int i = 0; i < n; i++) {
        x[i] = 2.0 * tu_rand() - 1.0;
        d[i] = 2.0 * tu_rand() - 1.0;
    }
    cstate s;
    cs_open(&s, m, u, h);
    int conj = 0;
    for (int c = 0; c < 6 * m->nt; c++) conj += s.cp->sys->cconj[c];
    CHECK(conj > 0);
    double e0, p0, e1, p1, e2, p2;
    cs_eval(&s, x, inv4e2, &e0, &p0, g);
    /* gradient: (F(x + t d) - F(x - t d)) / 2t = g.d */
    const double t = 1e-5;
    for (int i = 0; i < n; i++) xp[i] = x[i] + t * d[i];
    cs_eval(&s, xp, inv4e2, &e1, &p1, gp);
    for (int i = 0; i < n; i++) xp[i] = x[i] - t * d[i];
    cs_eval(&s, xp, inv4e2, &e2, &p2, gm);
    double gd = 0.0;
    for (int i = 0; i < n; i++) gd += g[i] * d[i];
    const double fd = ((e1 + p1) - (e2 + p2)) / (2.0 * t);
    CHECK_CLOSE(fd, gd, 1e-6, 1e-6);
    /* Hessian: NEWTON (exact, no Dirichlet) d = (g(x + t d) - g(x - t d)) / 2t */
    CHECK_OK(s.b->ops->vec_write(s.b, s.x, x));
    CHECK_OK(s.b->ops->assemble_newton(s.b, s.x, inv4e2, GLPGP_HESS_EXACT));
    CHECK_OK(s.b->ops->vec_write(s.b, s.d, d));
    CHECK_OK(s.b->ops->spmv(s.b, GLPGP_MAT_NEWTON, s.d, s.w));
    CHECK_OK(s.b->ops->vec_read(s.b, s.w, hd));
    double err = 0.0, ref = 0.0;
    for (int i = 0; i < n; i++) {
        const double f = (gp[i] - gm[i]) / (2.0 * t);
        err = fmax(err, fabs(f - hd[i]));
        ref = fmax(ref, fabs(hd[i]));
    }
    CHECK(ref > 1.0);
    CHECK(err <= 1e-6 * ref);
    /* the Hessian is symmetric: d.H e = e.H d */
    double *e = malloc((size_t)n * sizeof(double)), *he = malloc((size_t)n * sizeof(double));
    for (int i = 0; i < n; i++) e[i] = 2.0 * tu_rand() - 1.0;
    CHECK_OK(s.b->ops->vec_write(s.b, s.d, e));
    CHECK_OK(s.b->ops->spmv(s.b, GLPGP_MAT_NEWTON, s.d, s.w));
    CHECK_OK(s.b->ops->vec_read(s.b, s.w, he));
    double dhe = 0.0, ehd = 0.0;
    for (int i = 0; i < n; i++) {
        dhe += d[i] * he[i];
        ehd += e[i] * hd[i];
    }
    CHECK_CLOSE(dhe, ehd, 1e-10, 1e-12);
    printf("fd: gradient %.12g vs %.12g, Hessian max error %.3g of %.3g, %d conjugated corners\n", fd, gd, err,
           ref, conj);
    cs_close(&s);
    free(w);
    free(u);
    free(x);
    free(d);
    free(xp);
    free(g);
    free(gp);
    free(gm);
    free(hd);
    free(e);
    free(he);
    glpgp_mesh_destroy(&m);
}

/* glpgp_cross_conformal_size on theta = a y (harmonic, no singularity):
 * phi = a x + c, so log s = a x + const (exact for P1 up to the Neumann
 * solve's discretisation: theta is linear, grad phi constant). --cross-size
 * on: the largest size is h; auto: log s = clamp(a (x - x_q), -log c, 0),
 * x_q the q-quantile of x over the vertices (phi is increasing in x). */
static int cmp_dbl(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void test_conformal_size(void)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 800, &m));
    if (!m) return;
    const int nv = m->nv;
    const double a = 0.3;
    double *w = malloc((size_t)2 * nv * sizeof(double)), *sz = malloc((size_t)nv * sizeof(double));
    for (int i = 0; i < nv; i++) {
        w[2 * i] = cos(4.0 * a * m->xy[2 * i + 1]);
        w[2 * i + 1] = sin(4.0 * a * m->xy[2 * i + 1]);
    }
    glpgp_system *sys = NULL;
    glpgp_backend *b = NULL;
    glpgp_options o;
    glpgp_options_default(&o);
    CHECK_OK(glpgp_system_create(m, &sys));
    CHECK_OK(glpgp_backend_create_reference(&b));
    CHECK_OK(b->ops->setup(b, sys));
    long cg = 0;
    o.cross_size = GLPGP_CROSS_SIZE_ON;
    CHECK_OK(glpgp_cross_conformal_size(m, b, &o, w, 1.0, sz, &cg));
    /* log s_i - a x_i is constant; the largest size is h = 1 */
    double lo = HUGE_VAL, hi = -HUGE_VAL, smax = 0.0;
    for (int i = 0; i < nv; i++) {
        const double r = log(sz[i]) - a * m->xy[2 * i];
        lo = fmin(lo, r);
        hi = fmax(hi, r);
        smax = fmax(smax, sz[i]);
    }
    printf("conformal size: log s - a x in [%.3g, %.3g], max s %.6g, %ld CG\n", lo, hi, smax, cg);
    CHECK(hi - lo <= 1e-6);
    CHECK_CLOSE(smax, 1.0, 1e-12, 0.0);
    CHECK(cg > 0);
    /* auto: s = clamp(e^{a (x - x_q)}, 1/c, 1); the disk's range e^{2a} = 1.8 > c */
    o.cross_size = GLPGP_CROSS_SIZE_AUTO;
    CHECK_OK(glpgp_cross_conformal_size(m, b, &o, w, 1.0, sz, &cg));
    double *xs = malloc((size_t)nv * sizeof(double));
    for (int i = 0; i < nv; i++) xs[i] = m->xy[2 * i];
    qsort(xs, (size_t)nv, sizeof(double), cmp_dbl);
    const double xq = xs[(int)lround(o.cross_size_quantile * (nv - 1))];
    double err = 0.0;
    int at_h = 0, at_lo = 0;
    for (int i = 0; i < nv; i++) {
        const double e = fmin(0.0, fmax(-log(o.cross_size_ratio), a * (m->xy[2 * i] - xq)));
        err = fmax(err, fabs(log(sz[i]) - e));
        at_h += sz[i] >= 1.0 - 1e-12;
        at_lo += sz[i] <= 1.0 / o.cross_size_ratio + 1e-12;
    }
    printf("conformal size, auto: |log s - clamp| <= %.3g, %d of %d vertices at h, %d at h / %g\n", err, at_h, nv,
           at_lo, o.cross_size_ratio);
    CHECK(err <= 1e-5);
    CHECK(at_h >= (int)(0.1 * nv) - 1 && at_lo > 0);
    free(xs);
    glpgp_backend_destroy(&b);
    glpgp_system_destroy(&sys);
    free(w);
    free(sz);
    glpgp_mesh_destroy(&m);
}

int main(void)
{
    test_maps();
    test_invariance();
    test_multigrid_cuts(0);
    test_multigrid_cuts(1);
    test_fd();
    test_conformal_size();
    TEST_DONE();
}
