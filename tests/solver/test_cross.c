/* test_cross.c: Ginzburg-Landau cross fields (glpgp/cross.h) on the
 * reference backend:
 *  - boundary crosses: exp(4 i theta) of the edges' directions, exact (= 1)
 *    on axis-aligned boundaries, corners included (square, L-shape), |w| = 1;
 *  - Poincare-Hopf with corners from the geometry alone: disk 1, annulus 0,
 *    square 0 (4 corners of 1/4), L-shape 0 (5 convex corners of 1/4, the
 *    reentrant one -1/4), a triangle 1 - 3/4... checked against the formula
 *    chi - sum (2 - n_c)/4;
 *  - singularity detection on a hand-made field w = (x - p)/|x - p|: one +1/4
 *    near p, and its conjugate -1/4;
 *  - solves: the index sum equals Poincare-Hopf on every shape; the disk has 4
 *    singularities of +1/4, 90 degrees apart (within 5) at one radius (within
 *    5%); the square and the L-shape have none and give U = (1, 0) without cuts;
 *  - the same sum on every bundled mesh (data/: annulus, L-shape, plate with
 *    holes, square);
 *  - glpgp_solve with --field cross keeps the cross field in the result. */
#include "testutil.h"

#include <string.h>

static glpgp_mesh *shape(const char *name, long n)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate(name, n, &m));
    return m;
}

static glpgp_cross_result *solve_cross(const glpgp_mesh *m, glpgp_backend **bout)
{
    glpgp_system *sys = NULL;
    glpgp_backend *b = NULL;
    glpgp_cross_result *c = NULL;
    glpgp_options o;
    glpgp_options_default(&o);
    CHECK_OK(glpgp_system_create(m, &sys));
    CHECK_OK(glpgp_backend_create_reference(&b));
    CHECK_OK(b->ops->setup(b, sys));
    CHECK_OK(glpgp_cross_solve(m, b, &o, &c));
    glpgp_backend_destroy(&b);
    glpgp_system_destroy(&sys);
    (void)bout;
    return c;
}

static void test_boundary(void)
{
    const char *names[2] = {"square", "lshape"};
    for (int s = 0; s < 2; s++) {
        glpgp_mesh *m = shape(names[s], 400);
        double *w = calloc(2 * m->nv, sizeof(double));
        glpgp_cross_boundary(m, w);
        double err = 0.0;
        for (int i = 0; i < m->nv; i++)
            if (m->on_boundary[i]) err = fmax(err, hypot(w[2 * i] - 1.0, w[2 * i + 1]));
            else CHECK(w[2 * i] == 0.0 && w[2 * i + 1] == 0.0);
        printf("%s: boundary crosses max |w - 1| = %.3g\n", names[s], err);
        CHECK(err < 1e-12);
        free(w);
        glpgp_mesh_destroy(&m);
    }
    /* disk: w = exp(4 i theta) of the tangent, |w| = 1 */
    glpgp_mesh *m = shape("disk", 1000);
    double *w = calloc(2 * m->nv, sizeof(double)), err = 0.0;
    glpgp_cross_boundary(m, w);
    for (int i = 0; i < m->nv; i++) {
        if (!m->on_boundary[i]) continue;
        double th = atan2(m->xy[2 * i + 1], m->xy[2 * i]) + GLPGP_PI / 2; /* tangent */
        err = fmax(err, hypot(w[2 * i] - cos(4 * th), w[2 * i + 1] - sin(4 * th)));
    }
    printf("disk: boundary crosses max |w - exp(4 i theta)| = %.3g\n", err);
    CHECK(err < 0.05); /* the polygon's edges are within a few degrees of the circle's tangent */
    free(w);
    glpgp_mesh_destroy(&m);
}

/* triangle mesh of a polygon fan around its centroid (convex polygons) */
static glpgp_mesh *fan(int n, const double *px, const double *py)
{
    double *xy = malloc(sizeof(double) * 2 * (n + 1));
    int *tri = malloc(sizeof(int) * 3 * n);
    double cx = 0, cy = 0;
    for (int i = 0; i < n; i++) {
        xy[2 * i] = px[i];
        xy[2 * i + 1] = py[i];
        cx += px[i] / n;
        cy += py[i] / n;
    }
    xy[2 * n] = cx;
    xy[2 * n + 1] = cy;
    for (int i = 0; i < n; i++) {
        tri[3 * i] = n;
        tri[3 * i + 1] = i;
        tri[3 * i + 2] = (i + 1) % n;
    }
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_create(n + 1, xy, n, tri, &m));
    free(xy);
    free(tri);
    return m;
}

static void test_poincare_hopf_formula(void)
{
    /* chi - sum over corners of (2 - n_c)/4, n_c = round(interior angle / 90 deg), in quarters */
    struct { const char *name; int expect4; } cases[] = {
        {"disk", 4}, {"annulus", 0}, {"square", 0}, {"lshape", 0}};
    for (int k = 0; k < 4; k++) {
        glpgp_mesh *m = shape(cases[k].name, 2000);
        int e = glpgp_cross_expected_index4(m);
        printf("%s: Poincare-Hopf index sum %d/4 (expected %d/4)\n", cases[k].name, e, cases[k].expect4);
        CHECK(e == cases[k].expect4);
        glpgp_mesh_destroy(&m);
    }
    /* equilateral triangle: 3 corners of 60 degrees (n_c = 1, share 1/4 each): 1 - 3/4 = 1/4 */
    double tx[3] = {0, 1, 0.5}, ty[3] = {0, 0, sqrt(3) / 2};
    glpgp_mesh *m = fan(3, tx, ty);
    CHECK(glpgp_cross_expected_index4(m) == 1);
    glpgp_mesh_destroy(&m);
    /* regular hexagon: 6 corners of 120 degrees (n_c = 1): 1 - 6/4 = -1/2 */
    double hx[6], hy[6];
    for (int i = 0; i < 6; i++) {
        hx[i] = cos(i * GLPGP_PI / 3);
        hy[i] = sin(i * GLPGP_PI / 3);
    }
    m = fan(6, hx, hy);
    CHECK(glpgp_cross_expected_index4(m) == -2);
    glpgp_mesh_destroy(&m);
}

static void test_detection(void)
{
    glpgp_mesh *m = shape("square", 900);
    glpgp_cross_result *c = NULL;
    CHECK_OK(glpgp_cross_result_create(m->nv, m->nt, &c));
    const double px = 0.3141, py = 0.6718;
    for (int conj = 0; conj < 2; conj++) {
        for (int i = 0; i < m->nv; i++) {
            double dx = m->xy[2 * i] - px, dy = m->xy[2 * i + 1] - py;
            c->w[2 * i] = dx;
            c->w[2 * i + 1] = conj ? -dy : dy;
        }
        CHECK_OK(glpgp_cross_analyze(m, c));
        CHECK(c->nsing == 1);
        if (c->nsing == 1) {
            printf("w = %s(x - p): singularity %+d/4 at (%.4f, %.4f), p = (%.4f, %.4f)\n", conj ? "conj" : "",
                   c->sing[0].index4, c->sing[0].x, c->sing[0].y, px, py);
            CHECK(c->sing[0].index4 == (conj ? -1 : 1));
            CHECK(hypot(c->sing[0].x - px, c->sing[0].y - py) < 1e-9); /* linear field: exact zero */
        }
    }
    glpgp_cross_result_destroy(&c);
    glpgp_mesh_destroy(&m);
}

static void test_solves(void)
{
    const char *names[4] = {"disk", "annulus", "square", "lshape"};
    for (int s = 0; s < 4; s++) {
        glpgp_mesh *m = shape(names[s], 6000);
        glpgp_cross_result *c = solve_cross(m, NULL);
        if (!c) {
            glpgp_mesh_destroy(&m);
            continue;
        }
        printf("%s: %d singularities, index sum %d/4, Poincare-Hopf %d/4, median |w| %.4f, newton %d, cg %ld\n",
               names[s], c->nsing, c->index4_sum, c->index4_expected, c->zabs_median, c->newton_iterations,
               c->cg_iterations);
        CHECK(c->index4_sum == c->index4_expected);
        int sum = 0;
        for (int k = 0; k < c->nsing; k++) sum += c->sing[k].index4;
        CHECK(sum == c->index4_sum);
        /* |w|^2 ~ 1 - eps^2 |grad arg w|^2: the annulus's inner circle (r = 0.3,
         * |grad arg w| = 4/r) costs a few percent at eps = 2.5 mean edges */
        CHECK(c->zabs_median > (strcmp(names[s], "annulus") ? 0.95 : 0.85));
        if (!strcmp(names[s], "disk")) {
            CHECK(c->nsing == 4);
            if (c->nsing == 4) {
                double ang[4], rad[4], rmin = HUGE_VAL, rmax = 0.0;
                for (int k = 0; k < 4; k++) {
                    CHECK(c->sing[k].index4 == 1);
                    ang[k] = atan2(c->sing[k].y, c->sing[k].x);
                    rad[k] = hypot(c->sing[k].x, c->sing[k].y);
                    rmin = fmin(rmin, rad[k]);
                    rmax = fmax(rmax, rad[k]);
                    printf("  +1/4 at r = %.4f, angle %.2f deg\n", rad[k], ang[k] * 180 / GLPGP_PI);
                }
                /* sorted by angle, consecutive gaps are 90 degrees within 5 */
                for (int i = 1; i < 4; i++)
                    for (int j = i; j > 0 && ang[j] < ang[j - 1]; j--) {
                        double t = ang[j];
                        ang[j] = ang[j - 1];
                        ang[j - 1] = t;
                    }
                for (int k = 0; k < 4; k++) {
                    double gap = (k < 3 ? ang[k + 1] - ang[k] : ang[0] + 2 * GLPGP_PI - ang[3]) * 180 / GLPGP_PI;
                    CHECK(fabs(gap - 90.0) <= 5.0);
                }
                CHECK(rmax <= 1.05 * rmin);
                CHECK(rmin > 0.3 && rmax < 0.98); /* inside, away from the center */
            }
        }
        if (!strcmp(names[s], "square") || !strcmp(names[s], "lshape")) {
            CHECK(c->nsing == 0);
            double *u = calloc(2 * m->nv, sizeof(double)), dev = 0.0;
            CHECK(glpgp_cross_to_vector(m, c->w, u) == 0);
            for (int i = 0; i < m->nv; i++) dev = fmax(dev, fabs(u[2 * i + 1]));
            printf("  U = (1, 0) within %.3g\n", dev);
            CHECK(dev < 1e-6);
            free(u);
        }
        glpgp_cross_result_destroy(&c);
        glpgp_mesh_destroy(&m);
    }
}

/* every bundled mesh: the measured index sum is the Poincare-Hopf value */
static void test_bundled(void)
{
    const char *data = getenv("GLPGP_DATA");
    const char *files[4] = {"annulus.msh", "lshape.msh", "plate_holes.msh", "square.obj"};
    for (int k = 0; k < 4; k++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", data ? data : "data", files[k]);
        glpgp_mesh *m = NULL;
        CHECK_OK(glpgp_mesh_read(path, &m));
        if (!m) continue;
        glpgp_cross_result *c = solve_cross(m, NULL);
        if (c) {
            printf("%s: %d singularities, index sum %d/4, Poincare-Hopf %d/4\n", files[k], c->nsing,
                   c->index4_sum, c->index4_expected);
            CHECK(c->index4_sum == c->index4_expected);
        }
        glpgp_cross_result_destroy(&c);
        glpgp_mesh_destroy(&m);
    }
}

static void test_pipeline(void)
{
    glpgp_mesh *m = shape("square", 2500);
    glpgp_backend *b = NULL;
    glpgp_result *r = NULL;
    glpgp_options o;
    glpgp_options_default(&o);
    o.field = GLPGP_FIELD_CROSS;
    o.size = 0.2;
    CHECK_OK(glpgp_backend_create_reference(&b));
    CHECK_OK(glpgp_solve(m, b, &o, &r));
    CHECK(r && r->cross);
    if (r && r->cross) {
        CHECK(r->cross->nsing == 0);
        CHECK(r->osc[0].plus + r->osc[0].minus + r->osc[1].plus + r->osc[1].minus == 0);
        CHECK(r->osc[0].zabs_median > 0.9 && r->osc[1].zabs_median > 0.9);
    }
    glpgp_result_destroy(&r);
    glpgp_backend_destroy(&b);
    glpgp_mesh_destroy(&m);
}

int main(void)
{
    test_boundary();
    test_poincare_hopf_formula();
    test_detection();
    test_solves();
    test_bundled();
    test_pipeline();
    TEST_DONE();
}
