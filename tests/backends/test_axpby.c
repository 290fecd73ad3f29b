/* test_axpby.c: y <- a x + c y on every available backend (the reference
 * always; OpenCL, at both launch shapes, when a device is usable) against
 * host-computed values, bit for bit:
 *   - a zero coefficient does not read its vector: NaN- or Inf-filled x with
 *     a = 0, or y with c = 0, leaves no NaN (0 * NaN = NaN otherwise), and
 *     a = c = 0 gives exact zeros;
 *   - the general case is a x_i + c y_i rounded as written (no fused
 *     multiply-add), also in place (x and y the same vector, as in g <- -g).
 * Plus dot and copy on the same vectors. The backends are set up on a
 * generated disk (vectors of 2 nv entries, as in a solve). */
#include "testutil.h"

#include <string.h>

static int N; /* 2 nv */
static double *xs, *ys, *nanv, *infv, *got, *want;

/* Host expectation of a x_i + c y_i (each product rounded, then the sum). */
static double expect(double a, double x, double c, double y)
{
    const double p = a * x, q = c * y;
    return p + q;
}

/* Bitwise equality of got[] and want[] (so -0 vs +0 and NaN count). */
static void check_same(const char *backend, const char *what, const double *w)
{
    int bad = 0, first = 0;
    for (int i = 0; i < N; i++)
        if (memcmp(&got[i], &w[i], sizeof(double)) != 0 && !bad++) first = i;
    if (bad) {
        fprintf(stderr, "%s: %s: %d of %d entries differ (entry %d: %.17g, expected %.17g)\n", backend, what, bad, N,
                first, got[first], w[first]);
        tu_failures++;
    }
}

static void test_backend(const char *label, glpgp_backend *b, const glpgp_system *sys)
{
    const glpgp_backend_ops *o = b->ops;
    glpgp_vec *x = NULL, *y = NULL;
    CHECK_OK(o->setup(b, sys));
    CHECK_OK(o->vec_create(b, N, &x));
    CHECK_OK(o->vec_create(b, N, &y));
    if (!x || !y) return;

    /* a = c = 0 on NaN x and NaN y: exact zeros */
    CHECK_OK(o->vec_write(b, x, nanv));
    CHECK_OK(o->vec_write(b, y, nanv));
    CHECK_OK(o->axpby(b, 0.0, x, 0.0, y));
    CHECK_OK(o->vec_read(b, y, got));
    for (int i = 0; i < N; i++) want[i] = 0.0;
    check_same(label, "axpby(0, NaN, 0, NaN)", want);

    /* a = 0 on NaN x and on Inf x: c y */
    for (int k = 0; k < 2; k++) {
        CHECK_OK(o->vec_write(b, x, k ? infv : nanv));
        CHECK_OK(o->vec_write(b, y, ys));
        CHECK_OK(o->axpby(b, 0.0, x, -2.5, y));
        CHECK_OK(o->vec_read(b, y, got));
        for (int i = 0; i < N; i++) want[i] = -2.5 * ys[i];
        check_same(label, k ? "axpby(0, Inf, -2.5, y)" : "axpby(0, NaN, -2.5, y)", want);
    }

    /* c = 0 on NaN y: a x */
    CHECK_OK(o->vec_write(b, x, xs));
    CHECK_OK(o->vec_write(b, y, nanv));
    CHECK_OK(o->axpby(b, 0.75, x, 0.0, y));
    CHECK_OK(o->vec_read(b, y, got));
    for (int i = 0; i < N; i++) want[i] = 0.75 * xs[i];
    check_same(label, "axpby(0.75, x, 0, NaN)", want);

    /* general: a x + c y, rounded as written */
    CHECK_OK(o->vec_write(b, y, ys));
    CHECK_OK(o->axpby(b, 1.0 / 3.0, x, -0.7, y));
    CHECK_OK(o->vec_read(b, y, got));
    for (int i = 0; i < N; i++) want[i] = expect(1.0 / 3.0, xs[i], -0.7, ys[i]);
    check_same(label, "axpby(1/3, x, -0.7, y)", want);

    /* in place, x = y:  g <- 0 g - g  (solver/field.c) and  g <- 0 g + 0 g */
    CHECK_OK(o->vec_write(b, y, ys));
    CHECK_OK(o->axpby(b, 0.0, y, -1.0, y));
    CHECK_OK(o->vec_read(b, y, got));
    for (int i = 0; i < N; i++) want[i] = -ys[i];
    check_same(label, "axpby(0, g, -1, g)", want);
    CHECK_OK(o->vec_write(b, y, nanv));
    CHECK_OK(o->axpby(b, 0.0, y, 0.0, y));
    CHECK_OK(o->vec_read(b, y, got));
    for (int i = 0; i < N; i++) want[i] = 0.0;
    check_same(label, "axpby(0, NaN, 0, same NaN)", want);

    /* copy, then dot against the host sum (different order on OpenCL: 1e-13) */
    CHECK_OK(o->vec_write(b, y, ys));
    CHECK_OK(o->copy(b, x, y));
    CHECK_OK(o->vec_read(b, x, got));
    check_same(label, "copy", ys);
    double sc[GLPGP_NSLOTS], dot = 0.0, scale = 0.0;
    CHECK_OK(o->vec_write(b, x, xs));
    CHECK_OK(o->dot(b, x, y, GLPGP_S_DOT));
    CHECK_OK(o->get_scalars(b, sc, GLPGP_NSLOTS));
    for (int i = 0; i < N; i++) {
        dot += xs[i] * ys[i];
        scale += fabs(xs[i] * ys[i]);
    }
    CHECK_CLOSE(sc[GLPGP_S_DOT], dot, 1e-13 * scale, 0.0);
    o->vec_destroy(b, &x);
    o->vec_destroy(b, &y);
    CHECK(x == NULL && y == NULL);
    printf("%s: axpby, copy, dot checked\n", label);
}

int main(void)
{
    glpgp_mesh *m = NULL;
    glpgp_system *sys = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 1000, &m));
    if (m) CHECK_OK(glpgp_system_create(m, &sys));
    if (!sys) TEST_DONE();
    N = 2 * m->nv;
    xs = malloc(N * sizeof *xs);
    ys = malloc(N * sizeof *ys);
    nanv = malloc(N * sizeof *nanv);
    infv = malloc(N * sizeof *infv);
    got = malloc(N * sizeof *got);
    want = malloc(N * sizeof *want);
    if (!xs || !ys || !nanv || !infv || !got || !want) return 1;
    for (int i = 0; i < N; i++) {
        xs[i] = tu_rand() - 0.5;
        ys[i] = 4.0 * tu_rand() - 2.0;
        nanv[i] = NAN;
        infv[i] = i % 2 ? INFINITY : -INFINITY;
    }
    xs[0] = -0.0; /* zero signs: a x of -0 stays -0 with c = 0 */
    ys[1] = -0.0;

    glpgp_backend *b = NULL;
    CHECK_OK(glpgp_backend_create_reference(&b));
    if (b) test_backend("reference", b, sys);
    glpgp_backend_destroy(&b);

    if (!glpgp_have_opencl()) printf("OpenCL: not in this build, reference only\n");
    static const char *const shapes[] = {"cpu", "gpu"};
    for (int s = 0; s < 2 && glpgp_have_opencl(); s++) {
        glpgp_cl_options co = {-1, 0, NULL};
        setenv("GLPGP_CL_SHAPE", shapes[s], 1);
        if (glpgp_backend_create_opencl(&co, &b) != GLPGP_OK) {
            printf("OpenCL: no usable device (%s), reference only\n", glpgp_error_message());
            glpgp_error_clear();
            break;
        }
        char label[64];
        snprintf(label, sizeof label, "opencl (%s shape)", shapes[s]);
        test_backend(label, b, sys);
        glpgp_backend_destroy(&b);
    }
    unsetenv("GLPGP_CL_SHAPE");
    glpgp_system_destroy(&sys);
    glpgp_mesh_destroy(&m);
    free(xs);
    free(ys);
    free(nanv);
    free(infv);
    free(got);
    free(want);
    TEST_DONE();
}
