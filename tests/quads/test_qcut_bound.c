/* test_qcut_bound.c: the cut mesher's work bound (quads/qcut.c,
 * qcut_region.max_work), which the surface repair sets so that one region
 * cannot take minutes (regions of the 20 jagged holes at 1000 faces searched
 * cuts for 15 minutes):
 *  - a unit square whose bottom side holds 240 points (sides of h / 240:
 *    the mesher grades its quads up from them) is meshed without a bound,
 *    all quads with positive corners, the work reported;
 *  - with a bound a tenth of that work it stops: GLPGP_ERR_NUMERIC, having
 *    done at most the bound and one piece's search more. */
#include "testutil.h"

#include "../host/quads/qcut.h"

#define NB 240 /* points on the bottom side */

/* the square's loop: NB points along the bottom, one more on each of the
 * others (an even count in all: NB + 4) */
static void square_loop(dvec *xy, ivec *ls, ivec *lv, ivec *ow)
{
    for (int i = 0; i < NB; i++) {
        CHECK_OK(dpush(xy, (double)i / NB));
        CHECK_OK(dpush(xy, 0.0));
    }
    const double rest[8] = {1.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.5};
    for (int k = 0; k < 8; k++) CHECK_OK(dpush(xy, rest[k]));
    CHECK_OK(ipush(ls, 0));
    CHECK_OK(ipush(ls, NB + 4));
    CHECK_OK(ipush(ow, -1));
    for (int i = 0; i < NB + 4; i++) CHECK_OK(ipush(lv, i));
}

/* the smallest corner sine of the quads (positive: all convex, counter-clockwise) */
static double min_corner(const dvec *xy, const ivec *q)
{
    double m = 1.0;
    for (int f = 0; f < q->n / 4; f++)
        for (int k = 0; k < 4; k++) {
            const double *a = xy->p + 2 * q->p[4 * f + (k + 3) % 4], *b = xy->p + 2 * q->p[4 * f + k],
                         *c = xy->p + 2 * q->p[4 * f + (k + 1) % 4];
            const double ux = c[0] - b[0], uy = c[1] - b[1], vx = a[0] - b[0], vy = a[1] - b[1];
            m = fmin(m, (ux * vy - uy * vx) / (hypot(ux, uy) * hypot(vx, vy)));
        }
    return m;
}

/* one run: its status, work and quads */
static glpgp_status run(double max_work, qcut_stats *qs, int *nquads, double *corner)
{
    dvec xy = {0};
    ivec ls = {0}, lv = {0}, ow = {0}, q = {0};
    square_loop(&xy, &ls, &lv, &ow);
    const qcut_region R = {1, ls.p, lv.p, ow.p, max_work};
    const glpgp_status st = glpgp_qcut_mesh(&xy, &R, 1.0, &q, qs);
    glpgp_error_clear();
    *nquads = q.n / 4;
    *corner = q.n ? min_corner(&xy, &q) : 0.0;
    dvec_free(&xy);
    ivec_free(&ls);
    ivec_free(&lv);
    ivec_free(&ow);
    ivec_free(&q);
    return st;
}

int main(void)
{
    qcut_stats all, bounded;
    int n0, n1;
    double c0, c1;
    const double t0 = glpgp_now();
    CHECK(run(0.0, &all, &n0, &c0) == GLPGP_OK);
    const double t1 = glpgp_now();
    printf("unbounded: %d quads, corners' sine >= %.3f, work %.3g, %.2f s\n", n0, c0, all.work, t1 - t0);
    CHECK(n0 > 100 && c0 > 0.0);
    const double bound = 0.1 * all.work;
    CHECK(run(bound, &bounded, &n1, &c1) == GLPGP_ERR_NUMERIC);
    printf("bounded at %.3g: stopped after %.3g, %.2f s\n", bound, bounded.work, glpgp_now() - t1);
    CHECK(bounded.work > bound && bounded.work <= bound + (double)(NB + 4) * (NB + 4));
    TEST_DONE();
}
