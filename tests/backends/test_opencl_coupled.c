/* test_opencl_coupled.c: the coupled cross-field system (solver/coupled.c,
 * kernels/coupled_rows.h, kernels/backend_coupled.cl) on the OpenCL backend
 * against the reference:
 *  - the ops on one coupled system (a disk, representatives of a field with
 *    a singularity, random state and field sizes): QUAD x, NEWTON x
 *    (exact and mixed Hessian), DINV (through the Jacobi step) and the
 *    gradient bit for bit (the rows are the same code), E and P to 1e-12;
 *  - a backend set up again for another system (the cross field's, then the
 *    coupled one) gives the same rows as a fresh one;
 *  - a whole `--field cross` solve (coupled) on both: the same Newton steps,
 *    the same frame windings, z within 1e-4 (the disk's minimisers form a
 *    rotation family, see test_opencl_cross).
 * Skipped (77) without an OpenCL device. */
#include "testutil.h"

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

static void ops_compare(const glpgp_mesh *m, glpgp_backend *bc)
{
    const int nv = m->nv, n = 4 * nv;
    double *w = calloc((size_t)2 * nv, sizeof(double)), *u = calloc((size_t)2 * nv, sizeof(double));
    double *x = malloc((size_t)n * sizeof(double)), *wn = malloc((size_t)n * sizeof(double));
    double *sz = malloc((size_t)2 * nv * sizeof(double));
    double *out[2][4];
    unsigned char *dir = calloc((size_t)2 * nv, 1);
    if (!w || !u || !x || !wn || !sz || !dir) {
        CHECK(0);
        return;
    }
    for (int i = 0; i < nv; i++) {
        const double dx = m->xy[2 * i] + 0.21, dy = m->xy[2 * i + 1] - 0.17, r = hypot(dx, dy);
        w[2 * i] = dx / r;
        w[2 * i + 1] = dy / r;
    }
    glpgp_cross_to_vector(m, w, u);
    for (int i = 0; i < n; i++) x[i] = 2.0 * tu_rand() - 1.0;
    for (int i = 0; i < 2 * nv; i++) {
        sz[i] = 0.3 + 0.1 * tu_rand();
        dir[i] = m->on_boundary[i / 2] && (i % 3 == 0);
    }
    glpgp_coupled_node_field(u, nv, wn);
    glpgp_coupled *cp = NULL;
    CHECK_OK(glpgp_coupled_create(m, u, &cp));
    if (!cp) return;
    glpgp_backend *b[2] = {bc, NULL};
    CHECK_OK(glpgp_backend_create_reference(&b[1]));
    double sl[2][GLPGP_NSLOTS];
    for (int k = 0; k < 2; k++) {
        const glpgp_backend_ops *op = b[k]->ops;
        glpgp_vec *vx = NULL, *vy = NULL, *vz = NULL;
        for (int j = 0; j < 4; j++) out[k][j] = malloc((size_t)n * sizeof(double));
        CHECK_OK(op->setup(b[k], cp->sys));
        CHECK_OK(op->vec_create(b[k], (size_t)n, &vx));
        CHECK_OK(op->vec_create(b[k], (size_t)n, &vy));
        CHECK_OK(op->vec_create(b[k], (size_t)n, &vz));
        CHECK_OK(op->set_field(b[k], wn, dir));
        CHECK_OK(op->set_size(b[k], sz));
        CHECK_OK(op->assemble_quadratic(b[k], GLPGP_ELEM_P1, 0.4));
        CHECK_OK(op->vec_write(b[k], vx, x));
        CHECK_OK(op->spmv(b[k], GLPGP_MAT_QUAD, vx, vy));
        CHECK_OK(op->vec_read(b[k], vy, out[k][0]));
        CHECK_OK(op->assemble_newton(b[k], vx, 6.25, GLPGP_HESS_EXACT));
        CHECK_OK(op->spmv(b[k], GLPGP_MAT_NEWTON, vx, vy));
        CHECK_OK(op->vec_read(b[k], vy, out[k][1]));
        CHECK_OK(op->assemble_newton(b[k], vx, 6.25, GLPGP_HESS_MIXED));
        CHECK_OK(op->cg_precond(b[k], vx, vy, GLPGP_S_RZ0)); /* DINV x */
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
        printf("%s: %d of %d entries differ\n", names[j], diff, n);
        CHECK(diff == 0);
    }
    CHECK_CLOSE(sl[0][GLPGP_S_E], sl[1][GLPGP_S_E], 0.0, 1e-12);
    CHECK_CLOSE(sl[0][GLPGP_S_P], sl[1][GLPGP_S_P], 0.0, 1e-12);
    CHECK(sl[1][GLPGP_S_P] > 0.0);
    for (int k = 0; k < 2; k++)
        for (int j = 0; j < 4; j++) free(out[k][j]);
    glpgp_backend_destroy(&b[1]);
    glpgp_coupled_destroy(&cp);
    free(w);
    free(u);
    free(x);
    free(wn);
    free(sz);
    free(dir);
}

static void solve_compare(const glpgp_mesh *m, glpgp_backend *bc)
{
    glpgp_backend *b[2] = {bc, NULL};
    glpgp_result *r[2] = {NULL, NULL};
    glpgp_options o;
    glpgp_options_default(&o);
    o.field = GLPGP_FIELD_CROSS;
    o.cross_coupling = GLPGP_COUPLING_ON;
    o.cg_rtol = 1e-10;
    o.amg_kcycle_min = glpgp_amg_kcycle_min(bc, &o); /* one cycle on both (a GPU keeps fewer K levels) */
    CHECK_OK(glpgp_backend_create_reference(&b[1]));
    for (int k = 0; k < 2; k++) CHECK_OK(glpgp_solve(m, b[k], &o, &r[k]));
    if (r[0] && r[1]) {
        CHECK(r[0]->coupled && r[1]->coupled);
        double dz = 0.0;
        for (int s = 0; s < 2; s++)
            for (int i = 0; i < 2 * m->nv; i++) dz = fmax(dz, fabs(r[0]->osc[s].z[i] - r[1]->osc[s].z[i]));
        printf("solve: newton %d vs %d, cg %ld vs %ld, frame windings u +%d-%d / +%d-%d, v +%d-%d / +%d-%d, "
               "max |z_cl - z_ref| = %.3g\n",
               r[0]->osc[0].newton_iterations, r[1]->osc[0].newton_iterations, r[0]->osc[0].cg_iterations,
               r[1]->osc[0].cg_iterations, r[0]->osc[0].plus, r[0]->osc[0].minus, r[1]->osc[0].plus,
               r[1]->osc[0].minus, r[0]->osc[1].plus, r[0]->osc[1].minus, r[1]->osc[1].plus, r[1]->osc[1].minus,
               dz);
        CHECK(r[0]->osc[0].newton_iterations == r[1]->osc[0].newton_iterations);
        for (int s = 0; s < 2; s++)
            CHECK(r[0]->osc[s].plus == r[1]->osc[s].plus && r[0]->osc[s].minus == r[1]->osc[s].minus);
        CHECK(dz <= 1e-4);
    }
    for (int k = 0; k < 2; k++) glpgp_result_destroy(&r[k]);
    glpgp_backend_destroy(&b[1]);
}

int main(void)
{
    glpgp_backend *bc = NULL;
    if (!open_cl(&bc)) return 77;
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 2000, &m));
    if (m) {
        /* set the OpenCL backend up for the plain system first: the coupled
         * one then replaces it (the path of glpgp_solve) */
        glpgp_system *sys = NULL;
        CHECK_OK(glpgp_system_create(m, &sys));
        CHECK_OK(bc->ops->setup(bc, sys));
        ops_compare(m, bc);
        glpgp_system_destroy(&sys);
    }
    glpgp_backend_destroy(&bc);
    glpgp_mesh_destroy(&m);
    if (!open_cl(&bc)) return 77;
    CHECK_OK(glpgp_mesh_generate("disk", 4000, &m));
    if (m) solve_compare(m, bc);
    glpgp_backend_destroy(&bc);
    glpgp_mesh_destroy(&m);
    TEST_DONE();
}
