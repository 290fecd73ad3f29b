/* test_newton_rows.c: the trial-point arithmetic of kernels/newton_rows.h
 * that every backend shares: its sine and cosine against the C library's
 * (within 2 ulp where the argument is reduced exactly, bounded beyond,
 * NaN for a non-finite argument), the polar trial point against the formula
 * it implements (straight in vortex cores, a rotation of z outside them,
 * first-order agreement with z + a d), and the reference backend's op. */
#include "glpgp/backends.h"
#include "glpgp/shapes.h"
#include "newton_rows.h"
#include "testutil.h"

#include <float.h>
#include <string.h>

/* |a - b| in units of the last place of b */
static double ulps(double a, double b)
{
    const double u = nextafter(fabs(b), INFINITY) - fabs(b);
    return fabs(a - b) / (u > 0.0 ? u : DBL_MIN);
}

static void test_sincos(void)
{
    double worst = 0.0;
    const double special[] = {0.0, -0.0, 1e-300, 0.5, GLPGP_PI / 4, GLPGP_PI / 2, GLPGP_PI, 3 * GLPGP_PI / 4,
                              -GLPGP_PI / 2, 10.0, -33.3, 1000.0, 12345.678, 8e5};
    for (size_t k = 0; k < sizeof special / sizeof special[0]; k++) {
        double s, c;
        glpgp_sincos(special[k], &s, &c);
        /* values near a zero of sin or cos: absolute error instead of ulps */
        CHECK(fabs(s - sin(special[k])) <= 4e-16 * fmax(1.0, fabs(special[k]) * 1e-5) || ulps(s, sin(special[k])) <= 2);
        CHECK(fabs(c - cos(special[k])) <= 4e-16 * fmax(1.0, fabs(special[k]) * 1e-5) || ulps(c, cos(special[k])) <= 2);
    }
    for (int k = 0; k < 200000; k++) {
        const double x = 100.0 * (tu_rand() - 0.5);
        double s, c;
        glpgp_sincos(x, &s, &c);
        const double es = fabs(sin(x)) > 1e-3 ? ulps(s, sin(x)) : fabs(s - sin(x)) / DBL_EPSILON;
        const double ec = fabs(cos(x)) > 1e-3 ? ulps(c, cos(x)) : fabs(c - cos(x)) / DBL_EPSILON;
        worst = fmax(worst, fmax(es, ec));
    }
    printf("sincos: worst error over [-50, 50]: %.2f ulp\n", worst);
    CHECK(worst <= 3.0);
    double s, c;
    glpgp_sincos(1e17, &s, &c); /* no quadrant: bounded */
    CHECK(fabs(s) <= 1.0 && fabs(c) <= 1.0);
    glpgp_sincos(INFINITY, &s, &c);
    CHECK(isnan(s) && isnan(c));
    glpgp_sincos(NAN, &s, &c);
    CHECK(isnan(s) && isnan(c));
}

static void test_polar_point(void)
{
    const double r1 = 0.8;
    double xr, xi;
    /* vortex core (|z| <= r1 / 2): straight z + a d, bit for bit */
    glpgp_polar_point(0.1, -0.2, 0.3, 0.05, r1, &xr, &xi);
    CHECK(xr == 0.1 + 0.3 && xi == -0.2 + 0.05);
    /* outside: a pure phase step (d = i t z) keeps |z| */
    const double zr = 0.6, zi = 0.8, t = 0.4;
    glpgp_polar_point(zr, zi, -t * zi, t * zr, r1, &xr, &xi);
    CHECK_CLOSE(hypot(xr, xi), 1.0, 1e-15, 0.0);
    CHECK_CLOSE(atan2(xi, xr) - atan2(zi, zr), t, 1e-15, 0.0);
    /* against the formula with the C library's sin and cos, over |z| in [0.3, 1.3] */
    double worst = 0.0, first = 0.0;
    for (int k = 0; k < 20000; k++) {
        const double rho = 0.3 + tu_rand(), ph = 2.0 * GLPGP_PI * tu_rand();
        const double ar = rho * cos(ph), ai = rho * sin(ph), dr = tu_rand() - 0.5, di = tu_rand() - 0.5;
        glpgp_polar_point(ar, ai, dr, di, r1, &xr, &xi);
        const double m2 = ar * ar + ai * ai, m = sqrt(m2), r0 = 0.5 * r1;
        const double tt = m >= r1 ? 1.0 : m <= r0 ? 0.0 : (m - r0) / (r1 - r0);
        double er = ar + dr, ei = ai + di;
        const double wr = (dr * ar + di * ai) / m2, wi = (di * ar - dr * ai) / m2, amp = 1.0 + wr;
        if (tt > 0.0 && amp > 0.0) {
            const double pr = amp * (ar * cos(wi) - ai * sin(wi)), pi = amp * (ar * sin(wi) + ai * cos(wi));
            er = tt * pr + (1.0 - tt) * er;
            ei = tt * pi + (1.0 - tt) * ei;
        }
        worst = fmax(worst, hypot(xr - er, xi - ei) / fmax(1.0, hypot(er, ei)));
        /* first order: x (+) s d = z + s d + O(s^2) */
        const double s = 1e-4;
        double yr, yi;
        glpgp_polar_point(ar, ai, s * dr, s * di, r1, &yr, &yi);
        first = fmax(first, hypot(yr - (ar + s * dr), yi - (ai + s * di)) / (s * s * (1.0 + 1.0 / m2)));
    }
    printf("polar point: against the libm formula %.2e, second-order term / s^2 <= %.3f\n", worst, first);
    CHECK(worst <= 1e-15);
    CHECK(first <= 10.0);
}

/* the reference backend's op is the per-vertex function over the mesh */
static void test_reference_op(void)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 500, &m));
    glpgp_system *sys = NULL;
    CHECK_OK(glpgp_system_create(m, &sys));
    glpgp_backend *b = NULL;
    CHECK_OK(glpgp_backend_create_reference(&b));
    CHECK_OK(b->ops->setup(b, sys));
    CHECK(b->ops->trial_point != NULL);
    const size_t n2 = (size_t)2 * m->nv;
    double *x = malloc(n2 * sizeof(double)), *d = malloc(n2 * sizeof(double)), *y = malloc(n2 * sizeof(double));
    for (size_t i = 0; i < n2; i++) {
        x[i] = 2.0 * tu_rand() - 1.0;
        d[i] = tu_rand() - 0.5;
    }
    glpgp_vec *vx = NULL, *vd = NULL, *vy = NULL;
    CHECK_OK(b->ops->vec_create(b, n2, &vx));
    CHECK_OK(b->ops->vec_create(b, n2, &vd));
    CHECK_OK(b->ops->vec_create(b, n2, &vy));
    CHECK_OK(b->ops->vec_write(b, vx, x));
    CHECK_OK(b->ops->vec_write(b, vd, d));
    CHECK_OK(b->ops->trial_point(b, vx, vd, 0.5, 0.8, vy));
    CHECK_OK(b->ops->vec_read(b, vy, y));
    int same = 1;
    for (int i = 0; i < m->nv; i++) {
        double xr, xi;
        glpgp_polar_point(x[2 * i], x[2 * i + 1], 0.5 * d[2 * i], 0.5 * d[2 * i + 1], 0.8, &xr, &xi);
        same &= xr == y[2 * i] && xi == y[2 * i + 1];
    }
    CHECK(same);
    b->ops->vec_destroy(b, &vx);
    b->ops->vec_destroy(b, &vd);
    b->ops->vec_destroy(b, &vy);
    free(x);
    free(d);
    free(y);
    glpgp_backend_destroy(&b);
    glpgp_system_destroy(&sys);
    glpgp_mesh_destroy(&m);
}

int main(void)
{
    test_sincos();
    test_polar_point();
    test_reference_op();
    TEST_DONE();
}
