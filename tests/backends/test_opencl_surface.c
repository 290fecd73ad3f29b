/* test_opencl_surface.c: the surface systems (glpgp/surfsolve.h: each
 * triangle's plane ctxy, the cross field's corner turns crot; the kernels of
 * kernels/backend_coupled.cl calling kernels/coupled_rows.h) on the OpenCL
 * backend against the reference:
 *  - the cross field's system on a sphere and the coupled oscillators' on a
 *    torus (a cross field with singularities: conjugated corners), random
 *    state and sizes: QUAD x, NEWTON x (exact), DINV x (mixed) and the
 *    gradient bit for bit, E and P to 1e-12;
 *  - a whole surface solve (cube: features, Dirichlet nodes) on both: the
 *    same cross-field singularities, Newton steps and frame windings, z
 *    within 1e-6.
 * Skipped (77) without an OpenCL device. */
#include "testutil.h"

#include "glpgp/surfsolve.h"

#include <string.h>

static int open_cl(glpgp_backend **b)
{
    glpgp_cl_options co = {-1, 0, NULL};
    if (glpgp_backend_create_opencl(&co, b) != GLPGP_OK) {
        printf("skipped: no OpenCL device (%s)\n", glpgp_error_message());
        glpgp_error_clear();
        return 0;
    }
    return 1;
}

/* The ops of system sys (n unknowns, nodes = n / 2) on both backends. */
static void ops_compare(const char *what, const glpgp_system *sys, glpgp_backend *bc, double h, int sized)
{
    const int nn = sys->nv, n = 2 * nn;
    double *w = calloc((size_t)n, sizeof(double)), *x = malloc((size_t)n * sizeof(double));
    double *sz = malloc((size_t)nn * sizeof(double));
    unsigned char *dir = calloc((size_t)nn, 1);
    double *out[2][4], sl[2][GLPGP_NSLOTS];
    for (int i = 0; i < n; i++) x[i] = 2.0 * tu_rand() - 1.0;
    for (int i = 0; i < n; i++) w[i] = tu_rand() - 0.5;
    for (int i = 0; i < nn; i++) {
        sz[i] = h * (0.7 + 0.3 * tu_rand());
        dir[i] = i % 11 == 0;
    }
    glpgp_backend *b[2] = {bc, NULL};
    CHECK_OK(glpgp_backend_create_reference(&b[1]));
    for (int k = 0; k < 2; k++) {
        const glpgp_backend_ops *op = b[k]->ops;
        glpgp_vec *vx = NULL, *vy = NULL, *vz = NULL;
        for (int j = 0; j < 4; j++) out[k][j] = malloc((size_t)n * sizeof(double));
        CHECK_OK(op->setup(b[k], sys));
        CHECK_OK(op->vec_create(b[k], (size_t)n, &vx));
        CHECK_OK(op->vec_create(b[k], (size_t)n, &vy));
        CHECK_OK(op->vec_create(b[k], (size_t)n, &vz));
        CHECK_OK(op->set_field(b[k], w, dir));
        if (sized) CHECK_OK(op->set_size(b[k], sz));
        CHECK_OK(op->assemble_quadratic(b[k], GLPGP_ELEM_P1, h));
        CHECK_OK(op->vec_write(b[k], vx, x));
        CHECK_OK(op->spmv(b[k], GLPGP_MAT_QUAD, vx, vy));
        CHECK_OK(op->vec_read(b[k], vy, out[k][0]));
        CHECK_OK(op->assemble_newton(b[k], vx, 6.25, GLPGP_HESS_EXACT));
        CHECK_OK(op->spmv(b[k], GLPGP_MAT_NEWTON, vx, vy));
        CHECK_OK(op->vec_read(b[k], vy, out[k][1]));
        CHECK_OK(op->assemble_newton(b[k], vx, 6.25, GLPGP_HESS_MIXED));
        CHECK_OK(op->cg_precond(b[k], vx, vy, GLPGP_S_RZ0));
        CHECK_OK(op->vec_read(b[k], vy, out[k][2]));
        CHECK_OK(op->gradient(b[k], vx, 6.25, vz));
        CHECK_OK(op->vec_read(b[k], vz, out[k][3]));
        CHECK_OK(op->get_scalars(b[k], sl[k], GLPGP_NSLOTS));
        op->vec_destroy(b[k], &vx);
        op->vec_destroy(b[k], &vy);
        op->vec_destroy(b[k], &vz);
    }
    static const char *const names[4] = {"QUAD x", "NEWTON x (exact)", "DINV x (mixed)", "gradient"};
    for (int j = 0; j < 4; j++) {
        int diff = 0;
        for (int i = 0; i < n; i++) diff += out[0][j][i] != out[1][j][i];
        printf("%s: %s: %d of %d entries differ\n", what, names[j], diff, n);
        CHECK(diff == 0);
    }
    CHECK_CLOSE(sl[0][GLPGP_S_E], sl[1][GLPGP_S_E], 0.0, 1e-12);
    CHECK_CLOSE(sl[0][GLPGP_S_P], sl[1][GLPGP_S_P], 0.0, 1e-12);
    CHECK(sl[1][GLPGP_S_E] > 0.0 && sl[1][GLPGP_S_P] > 0.0);
    for (int k = 0; k < 2; k++)
        for (int j = 0; j < 4; j++) free(out[k][j]);
    glpgp_backend_destroy(&b[1]);
    free(w);
    free(x);
    free(sz);
    free(dir);
}

static void systems(glpgp_backend *bc)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("sphere", 1500, &m));
    if (m) {
        glpgp_system *sys = NULL;
        CHECK_OK(glpgp_surface_cross_system(m, &sys));
        if (sys) ops_compare("sphere, cross system", sys, bc, 1.0, 0);
        glpgp_system_destroy(&sys);
        glpgp_mesh_destroy(&m);
    }
    CHECK_OK(glpgp_mesh_generate("torus", 1500, &m));
    if (m) {
        /* representatives of a singular cross field: w from a transported field with a vortex */
        double *w = malloc((size_t)2 * m->nv * sizeof(double)), *u = malloc((size_t)2 * m->nv * sizeof(double));
        glpgp_surface_transport(m, 4, w);
        for (int i = 0; i < m->nv; i++) {
            const double a = 3.0 * atan2(m->xyz[3 * i + 1], m->xyz[3 * i]), c = cos(a), s = sin(a);
            const double r = w[2 * i];
            w[2 * i] = c * r - s * w[2 * i + 1];
            w[2 * i + 1] = s * r + c * w[2 * i + 1];
        }
        CHECK(glpgp_surface_cross_to_vector(m, w, u) > 0);
        glpgp_coupled *cp = NULL;
        CHECK_OK(glpgp_coupled_create(m, u, &cp));
        if (cp) {
            int nconj = 0;
            for (int c = 0; c < 6 * m->nt; c++) nconj += cp->sys->cconj[c];
            CHECK(nconj > 0 && cp->sys->ctxy && !cp->sys->crot && !cp->vm.xy);
            ops_compare("torus, coupled oscillators", cp->sys, bc, 0.3, 1);
        }
        glpgp_coupled_destroy(&cp);
        free(w);
        free(u);
        glpgp_mesh_destroy(&m);
    }
}

static void solve_compare(glpgp_backend *bc)
{
    glpgp_mesh *m = NULL;
    glpgp_backend *b[2] = {bc, NULL};
    glpgp_result *r[2] = {NULL, NULL};
    glpgp_options o;
    glpgp_options_default(&o);
    o.field = GLPGP_FIELD_CROSS;
    o.cg_rtol = 1e-10;
    o.size = 0.2;
    o.amg_kcycle_min = glpgp_amg_kcycle_min(bc, &o);
    CHECK_OK(glpgp_mesh_generate("cube", 3000, &m));
    CHECK_OK(glpgp_backend_create_reference(&b[1]));
    if (!m) return;
    for (int k = 0; k < 2; k++) CHECK_OK(glpgp_solve(m, b[k], &o, &r[k]));
    if (r[0] && r[1]) {
        double dz = 0.0;
        for (int s = 0; s < 2; s++)
            for (int i = 0; i < 2 * m->nv; i++) dz = fmax(dz, fabs(r[0]->osc[s].z[i] - r[1]->osc[s].z[i]));
        printf("cube solve: cross singularities %d vs %d, newton %d vs %d, frame windings u +%d-%d / +%d-%d, max "
               "|z_cl - z_ref| = %.3g\n",
               r[0]->cross->nsing, r[1]->cross->nsing, r[0]->osc[0].newton_iterations,
               r[1]->osc[0].newton_iterations, r[0]->osc[0].plus, r[0]->osc[0].minus, r[1]->osc[0].plus,
               r[1]->osc[0].minus, dz);
        CHECK(r[0]->cross->nsing == r[1]->cross->nsing && r[0]->cross->index4_sum == 8);
        CHECK(r[0]->osc[0].newton_iterations == r[1]->osc[0].newton_iterations);
        for (int s = 0; s < 2; s++)
            CHECK(r[0]->osc[s].plus == r[1]->osc[s].plus && r[0]->osc[s].minus == r[1]->osc[s].minus);
        CHECK(dz <= 1e-6);
    }
    for (int k = 0; k < 2; k++) glpgp_result_destroy(&r[k]);
    glpgp_backend_destroy(&b[1]);
    glpgp_mesh_destroy(&m);
}

int main(void)
{
    glpgp_backend *bc = NULL;
    if (!open_cl(&bc)) return 77;
    systems(bc);
    solve_compare(bc);
    glpgp_backend_destroy(&bc);
    TEST_DONE();
}
