/* test_phase.c: the phase module (glpgp/phase.h) at its edge cases: theta on
 * the axes, at z = 0, -0 and non-finite values, principal steps of exactly
 * +-1/2, charts that unwrap across the 0/1 seam, windings of z - p, its
 * conjugate, a plane wave and random triples (always -1, 0 or +1, and equal
 * to the sum of the chart steps). */
#include "testutil.h"

#include <float.h>

static void test_theta(void)
{
    CHECK(glpgp_theta(1.0, 0.0) == 0.0);
    CHECK(glpgp_theta(1.0, -0.0) == 0.0 && !signbit(glpgp_theta(1.0, -0.0)));
    CHECK(glpgp_theta(0.0, 0.0) == 0.0);
    CHECK(glpgp_theta(-0.0, -0.0) == 0.0);
    CHECK(glpgp_theta(NAN, 1.0) == 0.0);
    CHECK(glpgp_theta(1.0, INFINITY) == 0.0);
    CHECK_CLOSE(glpgp_theta(0.0, 1.0), 0.25, 1e-16, 0.0);
    CHECK_CLOSE(glpgp_theta(-1.0, 0.0), 0.5, 1e-16, 0.0);
    CHECK_CLOSE(glpgp_theta(-1.0, -0.0), 0.5, 1e-16, 0.0); /* atan2(-0, -1) = -pi -> 1/2 */
    CHECK_CLOSE(glpgp_theta(0.0, -1.0), 0.75, 1e-16, 0.0);
    /* just below the positive axis: close to 1 but never 1 */
    double t = glpgp_theta(1.0, -1e-300);
    CHECK(t >= 0.0 && t < 1.0);
    t = glpgp_theta(1.0, -1e-17);
    CHECK(t >= 0.0 && t < 1.0);
    for (int i = 0; i < 10000; i++) {
        double re = 2 * tu_rand() - 1, im = 2 * tu_rand() - 1;
        t = glpgp_theta(re, im);
        CHECK(t >= 0.0 && t < 1.0);
        CHECK_CLOSE(cos(2 * GLPGP_PI * t), re / hypot(re, im), 1e-12, 0.0);
    }
}

static void test_step(void)
{
    CHECK(glpgp_phase_step(0.5) == -0.5);  /* +1/2 is taken as -1/2 */
    CHECK(glpgp_phase_step(-0.5) == -0.5);
    CHECK(glpgp_phase_step(1.5) == -0.5);
    CHECK(glpgp_phase_step(0.25) == 0.25);
    CHECK(glpgp_phase_step(-0.75) == 0.25);
    CHECK(glpgp_phase_step(NAN) == 0.0);
    CHECK(glpgp_phase_step(0.5 - DBL_EPSILON) > 0.0);
    for (int i = 0; i < 10000; i++) {
        double d = 20 * tu_rand() - 10, s = glpgp_phase_step(d);
        CHECK(s >= -0.5 && s < 0.5);
        CHECK(fabs(s - d - round(s - d)) < 1e-12); /* differs from d by an integer */
    }
}

static void test_chart_winding(void)
{
    /* a triangle across the seam: 0.95, 0.05, 0.1 unwraps to 0.95, 1.05, 1.1 */
    double th[3] = {0.95, 0.05, 0.1}, c[3];
    glpgp_phase_chart(th, c);
    CHECK_CLOSE(c[0], 0.95, 1e-15, 0);
    CHECK_CLOSE(c[1], 1.05, 1e-15, 0);
    CHECK_CLOSE(c[2], 1.10, 1e-15, 0);
    CHECK(glpgp_phase_winding(th) == 0);
    /* three phases a third apart: +1 counter-clockwise, -1 the other way */
    double w1[3] = {0.0, 1.0 / 3, 2.0 / 3}, w2[3] = {0.0, 2.0 / 3, 1.0 / 3};
    CHECK(glpgp_phase_winding(w1) == 1);
    CHECK(glpgp_phase_winding(w2) == -1);
    /* z - p and its conjugate around a triangle containing p; a plane wave */
    const double x[3] = {0.0, 1.0, 0.0}, y[3] = {0.0, 0.0, 1.0}, px = 0.3, py = 0.3;
    double z[6], zc[6], zw[6];
    for (int a = 0; a < 3; a++) {
        z[2 * a] = x[a] - px;
        z[2 * a + 1] = y[a] - py;
        zc[2 * a] = x[a] - px;
        zc[2 * a + 1] = -(y[a] - py);
        zw[2 * a] = cos(2 * GLPGP_PI * 0.4 * x[a]);
        zw[2 * a + 1] = sin(2 * GLPGP_PI * 0.4 * x[a]);
    }
    CHECK(glpgp_phase_winding_z(z, 0, 1, 2) == 1);
    CHECK(glpgp_phase_winding_z(zc, 0, 1, 2) == -1);
    CHECK(glpgp_phase_winding_z(zw, 0, 1, 2) == 0);
    /* a zero corner counts as phase 0; the winding stays in {-1, 0, 1} */
    double z0[6] = {0.0, 0.0, -1.0, 1e-300, -1.0, -1e-300};
    int w = glpgp_phase_winding_z(z0, 0, 1, 2);
    CHECK(w >= -1 && w <= 1);
    /* random triples: winding = sum of the chart steps, always in {-1, 0, 1} */
    for (int i = 0; i < 20000; i++) {
        double t3[3] = {tu_rand(), tu_rand(), tu_rand()};
        if (i % 7 == 0) t3[1] = fmod(t3[0] + 0.5, 1.0); /* exact half steps */
        int k = glpgp_phase_winding(t3);
        CHECK(k >= -1 && k <= 1);
        glpgp_phase_chart(t3, c);
        double sum = (c[1] - c[0]) + glpgp_phase_step(t3[2] - t3[1]) + glpgp_phase_step(t3[0] - t3[2]);
        CHECK(fabs(sum - k) < 1e-9);
    }
}

int main(void)
{
    test_theta();
    test_step();
    test_chart_winding();
    TEST_DONE();
}
