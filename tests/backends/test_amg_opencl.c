/* test_amg_opencl.c: the multigrid preconditioner (solver/amg.c) on the
 * OpenCL backend (kernels/backend_multigrid.cl), by counts and identities
 * only (no timings):
 *  - galerkin: on a small disk with several levels, every coarse matrix of
 *    the OpenCL hierarchy equals the dense P^T A P of the level above
 *    (prolongations recovered column by column through amg_prolong, matrices
 *    through amg_spmv_dots), and P^T P = I;
 *  - hierarchy: every level's A_l, the smoother, restriction, prolongation,
 *    the coarsest matrix and a whole cycle equal the reference backend's on
 *    random data (bit for bit for the hierarchy values, which share
 *    kernels/amg_rows.h), on a generated disk and on data/plate_holes.msh,
 *    with the fused small-level kernel and without it (GLPGP_CL_AMG_FUSE=0);
 *  - refine: CG iterations per Newton step on the same disk and h at about
 *    16k and 64k vertices: ratio <= 1.5 with multigrid on OpenCL;
 *  - spd: the trust region's symmetric cycle (glpgp_amg_update_spd on
 *    the projected Hessian at a vortex, the exact Hessian assembled, then
 *    glpgp_amg_apply_spd; every level through the driver) equals the
 *    reference backend's on random vectors and is symmetric on OpenCL;
 *  - solve: a whole GL solve with --precond amg on OpenCL and on the
 *    reference (the default trust region, multigrid region included): same
 *    Newton counts and singularities, z within 1e-6;
 *  - launch-bound: the GPU launch shape keeps the K-cycle to the levels of
 *    at least GLPGP_AMG_KCYCLE_MIN_LAUNCH_BOUND nodes: >= 2.5x fewer kernel
 *    launches per FCG iteration, <= 15% more iterations (counts, no times).
 * Exit 77 when no OpenCL device can be used. */
#include "glpgp/backends.h"
#include "glpgp/io.h"
#include "glpgp/mesh.h"
#include "glpgp/solve.h"
#include "glpgp/system.h"
#include "testutil.h"
#include "amg_testutil.h"

#include <stdlib.h>
#include <string.h>

/* an OpenCL backend, or NULL (then the test is skipped) */
static glpgp_backend *opencl(void)
{
    glpgp_backend *b = NULL;
    glpgp_cl_options co = {-1, 0, NULL};
    if (glpgp_backend_create_opencl(&co, &b) != GLPGP_OK) {
        printf("skipped: no OpenCL device (%s)\n", glpgp_error_message());
        glpgp_error_clear();
        return NULL;
    }
    return b;
}

typedef struct fixture {
    glpgp_mesh *m;
    glpgp_system *sys;
    glpgp_backend *b;
    glpgp_options o;
    double h;
    double *w;
    unsigned char *dir;
} fixture;

/* disk of about n vertices on backend b (taken), field U = (1, 0), its
 * Dirichlet set, QUAD assembled at h */
static void fixture_init(fixture *f, glpgp_backend *b, long n, double h)
{
    memset(f, 0, sizeof *f);
    CHECK_OK(glpgp_mesh_generate("disk", n, &f->m));
    CHECK_OK(glpgp_system_create(f->m, &f->sys));
    f->b = b;
    CHECK_OK(b->ops->setup(b, f->sys));
    glpgp_options_default(&f->o);
    f->o.precond = GLPGP_PRECOND_AMG;
    f->h = h > 0 ? h : 10.0 * f->m->mean_edge;
    const int nv = f->m->nv;
    f->w = calloc((size_t)2 * nv, sizeof(double));
    f->dir = calloc((size_t)nv, 1);
    for (int i = 0; i < nv; i++) f->w[2 * i] = 1.0;
    glpgp_dirichlet_set(f->m, f->w, f->dir);
    CHECK_OK(b->ops->set_field(b, f->w, f->dir));
    CHECK_OK(b->ops->assemble_quadratic(b, GLPGP_ELEM_P1, f->h));
}

static void fixture_free(fixture *f)
{
    free(f->w);
    free(f->dir);
    glpgp_backend_destroy(&f->b);
    glpgp_system_destroy(&f->sys);
    glpgp_mesh_destroy(&f->m);
}

static void test_galerkin(glpgp_backend *b)
{
    fixture f;
    fixture_init(&f, b, 600, 0.0);
    f.o.amg_coarse = 6; /* several levels on a small mesh */
    const int nv = f.m->nv;
    const glpgp_backend_ops *op = f.b->ops;
    double *z = calloc((size_t)2 * nv, sizeof(double));
    amg_vortex_state(f.m, f.h, 0.05, -1, z);
    glpgp_vec *x = NULL;
    CHECK_OK(op->vec_create(f.b, (size_t)2 * nv, &x));
    CHECK_OK(op->vec_write(f.b, x, z));
    CHECK_OK(op->assemble_newton(f.b, x, 1.0 / (4 * 0.05 * 0.05), GLPGP_HESS_MIXED));
    glpgp_amg *a = NULL;
    CHECK_OK(glpgp_amg_create(f.b, &f.o, f.dir, f.w, f.h, &a));
    if (a) {
        CHECK_OK(glpgp_amg_update(a, x));
        glpgp_amg_info in;
        glpgp_amg_get_info(a, &in);
        printf("galerkin (OpenCL): %d vertices, %d levels, operator complexity %.3f\n", nv, in.nlevels,
               in.operator_complexity);
        CHECK(in.nlevels >= 4);
        amg_check_galerkin("galerkin (OpenCL)", f.b, &in, f.dir, -1);
    }
    glpgp_amg_destroy(&a);
    op->vec_destroy(f.b, &x);
    free(z);
    fixture_free(&f);
}

/* the cross-check engine's multigrid rows on mesh m: all pass, the
 * hierarchy values bit for bit */
static void hierarchy_rows(const char *label, const glpgp_mesh *m)
{
    glpgp_crosscheck_options o;
    glpgp_crosscheck_options_default(&o);
    o.mesh = m;
    o.solve = 0;
    o.seed = 777;
    glpgp_crosscheck *t = NULL;
    CHECK_OK(glpgp_crosscheck_create(&o, &t));
    if (!t) return;
    int nmg = 0, nexact = 0, levels = 0;
    for (int i = 0; i < t->nrows; i++) {
        const glpgp_crosscheck_row *r = &t->rows[i];
        if (strncmp(r->stage, "multigrid", 9) != 0 && strncmp(r->stage, "FCG+multigrid", 13) != 0) continue;
        nmg++;
        if (!r->pass) fprintf(stderr, "%s: %s FAILED (%.3e)\n", label, r->stage, r->max_abs);
        CHECK(r->pass);
        if (sscanf(r->stage, "multigrid levels (%d", &levels) == 1) continue;
        /* values that only go through kernels/amg_rows.h on identical inputs */
        if (strstr(r->stage, " x") && !strstr(r->stage, ":") ) {
            nexact++;
            CHECK(r->max_abs == 0.0);
        }
        if (strstr(r->stage, "smoother") || strstr(r->stage, "restriction") || strstr(r->stage, "prolongation") ||
            strstr(r->stage, "coarsest") || strstr(r->stage, "coarse solve")) {
            nexact++;
            if (r->max_abs != 0.0) fprintf(stderr, "%s: %s differs by %.3e\n", label, r->stage, r->max_abs);
            CHECK(r->max_abs == 0.0);
        }
    }
    printf("%s: %d multigrid rows (%d levels), %d bit-identical, all pass\n", label, nmg, levels, nexact);
    CHECK(levels >= 2);
    CHECK(nmg >= 5 * levels + 4);
    CHECK(nexact >= 4 * levels - 1); /* A_l x, smoother, restriction, prolongation; coarsest: A, dense, solve */
    glpgp_crosscheck_destroy(&t);
}

static void test_hierarchy(void)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 4000, &m));
    if (m) {
        hierarchy_rows("disk:4000", m);
        setenv("GLPGP_CL_AMG_FUSE", "0", 1); /* every level through the per-op kernels */
        setenv("GLPGP_CL_AMG_SMALL", "0", 1);
        hierarchy_rows("disk:4000 (no fused levels)", m);
        unsetenv("GLPGP_CL_AMG_FUSE");
        unsetenv("GLPGP_CL_AMG_SMALL");
    }
    glpgp_mesh_destroy(&m);
    const char *data = getenv("GLPGP_DATA");
    if (data) {
        char path[512];
        snprintf(path, sizeof path, "%s/plate_holes.msh", data);
        if (glpgp_mesh_read(path, &m) == GLPGP_OK) hierarchy_rows("plate_holes.msh", m);
        else glpgp_error_clear();
        glpgp_mesh_destroy(&m);
    }
}

/* mean CG iterations of the first `steps` projected-Hessian Newton steps on
 * the first eps level from z = the normalised naive PGP solution, disk of n
 * vertices, size h, OpenCL backend */
static double newton_cg_mean_k(glpgp_backend *b, long n, double h, int steps, int kmin, double *launches_per_it)
{
    fixture f;
    fixture_init(&f, b, n, h);
    f.o.amg_kcycle_min = kmin;
    long launches = 0;
    const int nv = f.m->nv;
    const size_t n2 = (size_t)2 * nv;
    const glpgp_backend_ops *op = f.b->ops;
    glpgp_vec *v[4];
    for (int k = 0; k < 4; k++) CHECK_OK(op->vec_create(f.b, n2, &v[k]));
    double *hx = calloc(n2, sizeof(double));
    for (int i = 0; i < nv; i++) hx[2 * i] = f.dir[i] ? 1.0 : 0.0;
    CHECK_OK(op->vec_write(f.b, v[0], hx));
    glpgp_amg *a = NULL;
    CHECK_OK(glpgp_amg_create(f.b, &f.o, f.dir, f.w, f.h, &a));
    long cg = 0;
    if (a) {
        /* naive PGP: x <- x + d, N d = -grad E(x); then normalise */
        glpgp_cg_info ci;
        CHECK_OK(op->assemble_newton(f.b, v[0], 0.0, GLPGP_HESS_PROJECTED));
        CHECK_OK(glpgp_amg_update(a, NULL));
        CHECK_OK(op->gradient(f.b, v[0], 0.0, v[1]));
        CHECK_OK(op->axpby(f.b, -1.0, v[1], 0.0, v[3]));
        CHECK_OK(glpgp_fcg(a, v[3], v[2], 1e-8, 1000, &ci));
        CHECK_OK(op->axpby(f.b, 1.0, v[2], 1.0, v[0]));
        CHECK_OK(op->vec_read(f.b, v[0], hx));
        for (int i = 0; i < nv; i++) {
            double r = hypot(hx[2 * i], hx[2 * i + 1]);
            hx[2 * i] = r > 0 ? hx[2 * i] / r : 1.0;
            hx[2 * i + 1] = r > 0 ? hx[2 * i + 1] / r : 0.0;
        }
        CHECK_OK(op->vec_write(f.b, v[0], hx));
        /* Newton steps on the projected Hessian, solved to 1e-6 */
        const double eps = f.o.eps0 * f.h, inv4e2 = 1.0 / (4 * eps * eps);
        for (int it = 0; it < steps; it++) {
            CHECK_OK(op->assemble_newton(f.b, v[0], inv4e2, GLPGP_HESS_PROJECTED));
            CHECK_OK(glpgp_amg_update(a, v[0]));
            CHECK_OK(op->gradient(f.b, v[0], inv4e2, v[1]));
            CHECK_OK(op->axpby(f.b, -1.0, v[1], 0.0, v[3]));
            const long l0 = f.b->n_launch;
            CHECK_OK(glpgp_fcg(a, v[3], v[2], 1e-6, 1000, &ci));
            launches += f.b->n_launch - l0;
            CHECK(ci.reason == GLPGP_CG_CONVERGED);
            cg += ci.iterations;
            CHECK_OK(op->axpby(f.b, 1.0, v[2], 1.0, v[0]));
        }
    }
    glpgp_amg_destroy(&a);
    for (int k = 0; k < 4; k++) op->vec_destroy(f.b, &v[k]);
    free(hx);
    fixture_free(&f);
    if (launches_per_it) *launches_per_it = cg ? (double)launches / cg : 0.0;
    return (double)cg / steps;
}

/* CG iterations per Newton step with the default K-cycle threshold */
static double newton_cg_mean(glpgp_backend *b, long n, double h, int steps)
{
    return newton_cg_mean_k(b, n, h, steps, -1, NULL);
}

/* an OpenCL backend in launch shape `shape` (GLPGP_CL_SHAPE), or NULL */
static glpgp_backend *opencl_shape(const char *shape)
{
    const char *old = getenv("GLPGP_CL_SHAPE");
    char *keep = old ? strdup(old) : NULL;
    setenv("GLPGP_CL_SHAPE", shape, 1);
    glpgp_backend *b = opencl();
    if (keep) setenv("GLPGP_CL_SHAPE", keep, 1);
    else unsetenv("GLPGP_CL_SHAPE");
    free(keep);
    return b;
}

/* launch-bound: in the GPU launch shape (forced on any device) the backend
 * is launch-bound and the K-cycle stops at GLPGP_AMG_KCYCLE_MIN_LAUNCH_BOUND
 * nodes; on a 64k disk (7 levels) an FCG iteration then enqueues at most
 * 1/2.5 of the full K-cycle's kernel launches, for at most 15% (+1) more CG
 * iterations per Newton step. The CPU launch shape is not launch-bound (its
 * small levels run fused: glpgp_amg_kcycle_min stays 0). */
static void test_launch_bound(void)
{
    glpgp_backend *cpu = opencl_shape("cpu");
    glpgp_backend *g1 = opencl_shape("gpu"), *g2 = opencl_shape("gpu");
    glpgp_options o;
    glpgp_options_default(&o);
    if (cpu) {
        CHECK(!cpu->launch_bound);
        CHECK(glpgp_amg_kcycle_min(cpu, &o) == 0);
    }
    glpgp_backend_destroy(&cpu);
    if (!g1 || !g2) {
        glpgp_backend_destroy(&g1);
        glpgp_backend_destroy(&g2);
        return;
    }
    CHECK(g1->launch_bound);
    CHECK(glpgp_amg_kcycle_min(g1, &o) == GLPGP_AMG_KCYCLE_MIN_LAUNCH_BOUND);
    o.amg_kcycle_min = 7;
    CHECK(glpgp_amg_kcycle_min(g1, &o) == 7); /* an explicit threshold wins */
    double la = 0.0, lf = 0.0;
    const double ca = newton_cg_mean_k(g1, 64000, 0.15, 3, -1, &la); /* takes g1 */
    const double cf = newton_cg_mean_k(g2, 64000, 0.15, 3, 0, &lf);  /* takes g2 */
    printf("launch-bound (GPU shape, 64k disk): K-cycle from %d nodes %.1f CG it/step, %.0f launches/it; "
           "on every level %.1f CG it/step, %.0f launches/it\n",
           GLPGP_AMG_KCYCLE_MIN_LAUNCH_BOUND, ca, la, cf, lf);
    CHECK(la > 0.0 && 2.5 * la <= lf);
    CHECK(ca <= 1.15 * cf + 1.0);
}

static void test_refine(void)
{
    /* the same disk and h (10 mean edges at 16k vertices, 20 at 64k) */
    const double h = 0.15;
    const int steps = 4;
    glpgp_backend *b1 = opencl(), *b2 = opencl();
    if (!b1 || !b2) {
        glpgp_backend_destroy(&b1);
        glpgp_backend_destroy(&b2);
        return;
    }
    double a1 = newton_cg_mean(b1, 16000, h, steps);
    double a2 = newton_cg_mean(b2, 64000, h, steps);
    printf("refine (OpenCL): CG iterations per Newton step (first %d steps), 16k -> 64k vertices: "
           "multigrid %.1f -> %.1f (ratio %.2f)\n", steps, a1, a2, a2 / a1);
    CHECK(a1 > 0.0);
    CHECK(a2 <= 1.5 * a1);
    CHECK(a2 <= 30.0);
}

/* B v for the random vectors v[0..1] on backend b (taken): hb[k] */
static void spd_apply(glpgp_backend *b, double *const hv[2], double *hb[2])
{
    fixture f;
    fixture_init(&f, b, 4000, 0.0);
    const int nv = f.m->nv;
    const size_t n2 = (size_t)2 * nv;
    const glpgp_backend_ops *op = f.b->ops;
    double *z = calloc(n2, sizeof(double));
    amg_vortex_state(f.m, f.h, 0.25, -1, z);
    glpgp_vec *x = NULL, *v = NULL, *bv = NULL;
    CHECK_OK(op->vec_create(f.b, n2, &x));
    CHECK_OK(op->vec_create(f.b, n2, &v));
    CHECK_OK(op->vec_create(f.b, n2, &bv));
    CHECK_OK(op->vec_write(f.b, x, z));
    glpgp_amg *a = NULL;
    CHECK_OK(glpgp_amg_create(f.b, &f.o, f.dir, f.w, f.h, &a));
    const double eps = 2.5 * f.m->mean_edge, inv4e2 = 1.0 / (4 * eps * eps);
    if (a) {
        CHECK_OK(op->assemble_newton(f.b, x, inv4e2, GLPGP_HESS_PROJECTED));
        CHECK_OK(glpgp_amg_update_spd(a, x));
        CHECK_OK(op->assemble_newton(f.b, x, inv4e2, GLPGP_HESS_EXACT));
        for (int k = 0; k < 2; k++) {
            CHECK_OK(op->vec_write(f.b, v, hv[k]));
            CHECK_OK(glpgp_amg_apply_spd(a, v, bv));
            CHECK_OK(op->vec_read(f.b, bv, hb[k]));
        }
    }
    glpgp_amg_destroy(&a);
    op->vec_destroy(f.b, &x);
    op->vec_destroy(f.b, &v);
    op->vec_destroy(f.b, &bv);
    free(z);
    fixture_free(&f);
}

static void test_spd(void)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 4000, &m));
    if (!m) return;
    const size_t n2 = (size_t)2 * m->nv;
    glpgp_mesh_destroy(&m);
    double *hv[2], *hc[2], *hr[2];
    unsigned long long seed = 777;
    for (int k = 0; k < 2; k++) {
        hv[k] = calloc(n2, sizeof(double));
        hc[k] = calloc(n2, sizeof(double));
        hr[k] = calloc(n2, sizeof(double));
        for (size_t i = 0; i < n2; i++) {
            seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
            hv[k][i] = (double)(seed >> 11) / 9007199254740992.0 - 0.5;
        }
    }
    glpgp_backend *bc = opencl(), *br = NULL;
    CHECK_OK(glpgp_backend_create_reference(&br));
    if (bc && br) {
        spd_apply(bc, hv, hc);
        spd_apply(br, hv, hr);
        double dmax = 0.0, nmax = 0.0, xy = 0.0, yx = 0.0, xx = 0.0;
        for (size_t i = 0; i < n2; i++)
            for (int k = 0; k < 2; k++) {
                dmax = fmax(dmax, fabs(hc[k][i] - hr[k][i]));
                nmax = fmax(nmax, fabs(hr[k][i]));
            }
        for (size_t i = 0; i < n2; i++) {
            xy += hv[0][i] * hc[1][i];
            yx += hv[1][i] * hc[0][i];
            xx += hv[0][i] * hc[0][i];
        }
        printf("spd: symmetric cycle OpenCL vs reference max |diff| / max |Bv| = %.3g, "
               "OpenCL |x.By - y.Bx| / x.Bx = %.3g, x.Bx = %.6g\n", dmax / nmax, fabs(xy - yx) / xx, xx);
        CHECK(nmax > 0.0 && dmax <= 1e-10 * nmax);
        CHECK(fabs(xy - yx) <= 1e-12 * xx);
        CHECK(xx > 0.0);
    } else {
        glpgp_backend_destroy(&bc);
        glpgp_backend_destroy(&br);
    }
    for (int k = 0; k < 2; k++) {
        free(hv[k]);
        free(hc[k]);
        free(hr[k]);
    }
}

static void test_solve(void)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("annulus", 4000, &m));
    glpgp_backend *bc = opencl(), *br = NULL;
    CHECK_OK(glpgp_backend_create_reference(&br));
    glpgp_options o;
    glpgp_options_default(&o);
    o.precond = GLPGP_PRECOND_AMG;
    o.newton_rtol = 1e-8;
    o.cg_rtol = 1e-10;
    if (bc) o.amg_kcycle_min = glpgp_amg_kcycle_min(bc, &o); /* the same cycle on both (a GPU's) */
    glpgp_result *rc = NULL, *rr = NULL;
    if (bc && m) {
        CHECK_OK(glpgp_solve(m, bc, &o, &rc));
        CHECK_OK(glpgp_solve(m, br, &o, &rr));
    }
    if (rc && rr)
        for (int k = 0; k < 2; k++) {
            double dmax = 0.0;
            for (int i = 0; i < 2 * m->nv; i++) dmax = fmax(dmax, fabs(rc->osc[k].z[i] - rr->osc[k].z[i]));
            printf("solve (amg) %c: max |z_cl - z_ref| = %.3g, newton %d vs %d, cg %ld vs %ld, "
                   "singular +%d-%d vs +%d-%d\n", "uv"[k], dmax, rc->osc[k].newton_iterations,
                   rr->osc[k].newton_iterations, rc->osc[k].cg_iterations, rr->osc[k].cg_iterations,
                   rc->osc[k].plus, rc->osc[k].minus, rr->osc[k].plus, rr->osc[k].minus);
            int capped = 0;
            for (int l = 0; l < rr->osc[k].nlevels; l++) capped |= rr->osc[k].level[l].newton >= o.newton_max;
            CHECK(dmax <= (capped ? 1e-4 : 1e-6));
            CHECK(rc->osc[k].newton_iterations == rr->osc[k].newton_iterations);
            CHECK(rc->osc[k].plus == rr->osc[k].plus && rc->osc[k].minus == rr->osc[k].minus);
        }
    glpgp_result_destroy(&rc);
    glpgp_result_destroy(&rr);
    glpgp_backend_destroy(&bc);
    glpgp_backend_destroy(&br);
    glpgp_mesh_destroy(&m);
}

int main(void)
{
    glpgp_backend *b = opencl();
    if (!b) return 77;
    test_galerkin(b); /* takes b */
    test_hierarchy();
    test_refine();
    test_spd();
    test_solve();
    test_launch_bound();
    TEST_DONE();
}
