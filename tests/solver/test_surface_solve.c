/* test_surface_solve.c: the surface pipeline (glpgp/surfsolve.h):
 *  - finite differences of the surface rows (kernels/coupled_rows.h with
 *    each triangle's plane and the corners' turns exp(4 i phi)): the
 *    gradient of E + P and the exact Hessian (NEWTON) on a sphere at a
 *    random state;
 *  - the cross field's index sums and singularities: sphere 8 x +1/4, cube
 *    8 x +1/4 (features kept, one at each corner), torus 0, genus 2 -2,
 *    hemisphere 1 (= Poincare-Hopf with its circle), each sum exactly the
 *    expected one;
 *  - the cross field's stall test on the sphere (8216 vertices): its drifting
 *    last level stops after 20 of 27 steps, the energy within 1e-3;
 *  - a developable surface (halfcyl) gives the planar result of its
 *    unrolled twin (halfcyl_flat, the coupled planar solve) to 1e-8 at a
 *    uniform size: every vertex's (z_u, z_v), read through the quarter turn
 *    between the two solves' representatives;
 *  - the coupled oscillators' linear solves on closed surfaces: at most 23
 *    CG iterations per Newton step on the torus and the sphere at their
 *    default sizes (the multigrid keeps the phase mode across the cuts;
 *    with aggregates across conjugations: 24.3 and 29.5);
 *  - the preparation (glpgp_solve_prepare) refines a surface too coarse
 *    for its size until no edge is above h / GLPGP_SURFACE_EDGES (bisection,
 *    far fewer triangles than the uniform rounds just above the old mean
 *    edge rule), not beyond --max-elements, not with --no-refine. */
#include "testutil.h"

#include "glpgp/internal/newton.h"
#include "glpgp/surfsolve.h"

#include <string.h>

/* E + P of the cross system at x (2 nv), its gradient into g (may be NULL) */
typedef struct xs {
    glpgp_backend *b;
    glpgp_system *sys;
    glpgp_vec *x, *g, *y;
    int n;
} xs;

static double xs_eval(xs *s, const double *x, double inv4e2, double *g)
{
    double sl[GLPGP_NSLOTS];
    CHECK_OK(s->b->ops->vec_write(s->b, s->x, x));
    CHECK_OK(s->b->ops->gradient(s->b, s->x, inv4e2, s->g));
    CHECK_OK(s->b->ops->get_scalars(s->b, sl, GLPGP_NSLOTS));
    if (g) CHECK_OK(s->b->ops->vec_read(s->b, s->g, g));
    return sl[GLPGP_S_E] + sl[GLPGP_S_P];
}

static void test_fd(void)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("sphere", 200, &m));
    if (!m) return;
    xs s;
    memset(&s, 0, sizeof s);
    s.n = 2 * m->nv;
    CHECK_OK(glpgp_surface_cross_system(m, &s.sys));
    CHECK_OK(glpgp_backend_create_reference(&s.b));
    CHECK_OK(s.b->ops->setup(s.b, s.sys));
    double *zero = calloc((size_t)s.n, sizeof(double)), *x = malloc((size_t)s.n * sizeof(double));
    double *g = malloc((size_t)s.n * sizeof(double)), *g2 = malloc((size_t)s.n * sizeof(double));
    double *hv = malloc((size_t)s.n * sizeof(double));
    unsigned char *dir = calloc((size_t)m->nv, 1);
    CHECK_OK(s.b->ops->set_field(s.b, zero, dir));
    CHECK_OK(s.b->ops->assemble_quadratic(s.b, GLPGP_ELEM_P1, 1.0));
    CHECK_OK(s.b->ops->vec_create(s.b, (size_t)s.n, &s.x));
    CHECK_OK(s.b->ops->vec_create(s.b, (size_t)s.n, &s.g));
    CHECK_OK(s.b->ops->vec_create(s.b, (size_t)s.n, &s.y));
    for (int k = 0; k < s.n; k++) x[k] = 1.6 * tu_rand() - 0.8;
    const double inv4e2 = 1.0 / (4.0 * 0.3 * 0.3), dl = 1e-6;
    xs_eval(&s, x, inv4e2, g);
    /* gradient: central differences of E + P */
    double gerr = 0.0, gmax = 0.0;
    for (int k = 0; k < s.n; k += 7) {
        const double x0 = x[k];
        x[k] = x0 + dl;
        const double fp = xs_eval(&s, x, inv4e2, NULL);
        x[k] = x0 - dl;
        const double fm = xs_eval(&s, x, inv4e2, NULL);
        x[k] = x0;
        gerr = fmax(gerr, fabs((fp - fm) / (2 * dl) - g[k]));
        gmax = fmax(gmax, fabs(g[k]));
    }
    /* exact Hessian: NEWTON p against (g(x + dl p) - g(x - dl p)) / 2 dl */
    double *p = malloc((size_t)s.n * sizeof(double));
    for (int k = 0; k < s.n; k++) p[k] = tu_rand() - 0.5;
    CHECK_OK(s.b->ops->vec_write(s.b, s.x, x));
    CHECK_OK(s.b->ops->assemble_newton(s.b, s.x, inv4e2, GLPGP_HESS_EXACT));
    CHECK_OK(s.b->ops->vec_write(s.b, s.x, p));
    CHECK_OK(s.b->ops->spmv(s.b, GLPGP_MAT_NEWTON, s.x, s.y));
    CHECK_OK(s.b->ops->vec_read(s.b, s.y, hv));
    for (int k = 0; k < s.n; k++) x[k] += dl * p[k];
    xs_eval(&s, x, inv4e2, g);
    for (int k = 0; k < s.n; k++) x[k] -= 2 * dl * p[k];
    xs_eval(&s, x, inv4e2, g2);
    double herr = 0.0, hmax = 0.0;
    for (int k = 0; k < s.n; k++) {
        herr = fmax(herr, fabs((g[k] - g2[k]) / (2 * dl) - hv[k]));
        hmax = fmax(hmax, fabs(hv[k]));
    }
    printf("surface rows, finite differences: gradient %.3g (of %.3g), Hessian %.3g (of %.3g)\n", gerr, gmax, herr,
           hmax);
    CHECK(gerr < 1e-6 * gmax);
    CHECK(herr < 1e-6 * hmax);
    s.b->ops->vec_destroy(s.b, &s.x);
    s.b->ops->vec_destroy(s.b, &s.g);
    s.b->ops->vec_destroy(s.b, &s.y);
    glpgp_backend_destroy(&s.b);
    glpgp_system_destroy(&s.sys);
    free(zero);
    free(x);
    free(g);
    free(g2);
    free(hv);
    free(p);
    free(dir);
    glpgp_mesh_destroy(&m);
}

/* The cross field of shape: its index sum is exactly the expected one; the
 * count of +1/4 and -1/4 singularities (-1: not checked). */
static void test_cross(const char *shape, long n, int sum4, int nplus, int nminus)
{
    glpgp_mesh *m = NULL;
    glpgp_backend *b = NULL;
    glpgp_surface_constraints *con = NULL;
    glpgp_cross_result *c = NULL;
    glpgp_options o;
    glpgp_options_default(&o);
    CHECK_OK(glpgp_mesh_generate(shape, n, &m));
    CHECK_OK(glpgp_backend_create_reference(&b));
    if (!m || !b) return;
    CHECK_OK(glpgp_surface_constraints_create(m, o.feature_angle, &con));
    CHECK_OK(glpgp_surface_cross_solve(m, b, &o, con, &c));
    if (c) {
        int np = 0, nm = 0;
        for (int k = 0; k < c->nsing; k++) {
            np += c->sing[k].index4 == 1;
            nm += c->sing[k].index4 == -1;
        }
        printf("%s (%d vertices): %d singularities (+1/4: %d, -1/4: %d), index sum %d/4, expected %d/4, median |w| "
               "%.4f\n",
               shape, m->nv, c->nsing, np, nm, c->index4_sum, c->index4_expected, c->zabs_median);
        CHECK(c->index4_sum == sum4);
        CHECK(c->index4_expected == sum4);
        if (nplus >= 0) CHECK(np == nplus && c->nsing == nplus + nminus);
        if (nminus >= 0) CHECK(nm == nminus);
        CHECK(c->zabs_median > 0.9);
    }
    glpgp_cross_result_destroy(&c);
    glpgp_surface_constraints_destroy(&con);
    glpgp_backend_destroy(&b);
    glpgp_mesh_destroy(&m);
}

/* The cross field's stall test (--cross-ftol): on the sphere nothing pins
 * the 8 singularities, and its last level (8216 vertices, no refinement)
 * drifts for 27 Newton steps without the test, |g| above its tolerance.
 * With it, the level stops from GLPGP_STALL_STEPS steps on once E + P fell
 * by at most ftol of itself over 3 steps: fewer steps, the level marked
 * stalled above its gradient tolerance, none capped, the last energy
 * within 1e-3 of the one without the test, the same singularities. */
static void test_cross_stall(void)
{
    glpgp_mesh *m = NULL;
    glpgp_backend *b = NULL;
    glpgp_surface_constraints *con = NULL;
    glpgp_cross_result *c[2] = {NULL, NULL};
    glpgp_options o;
    glpgp_options_default(&o);
    CHECK_OK(glpgp_mesh_generate("sphere", 8000, &m));
    CHECK_OK(glpgp_backend_create_reference(&b));
    if (!m || !b) return;
    CHECK_OK(glpgp_surface_constraints_create(m, o.feature_angle, &con));
    for (int k = 0; k < 2; k++) {
        o.cross_ftol = k ? 0.0 : 1e-5;
        CHECK_OK(glpgp_surface_cross_solve(m, b, &o, con, &c[k]));
    }
    if (c[0] && c[1]) {
        int stalled = 0;
        for (int l = 0; l < c[0]->nlevels; l++) {
            const glpgp_level_stats *a = &c[0]->level[l], *z = &c[1]->level[l];
            printf("sphere cross level %d: newton %d (without the stall test %d), |g|/|g0| %.2e, stalled %d\n", l,
                   a->newton, z->newton, a->grad / a->grad0, a->stalled);
            CHECK(!a->capped && !z->stalled);
            if (a->stalled) {
                stalled++;
                CHECK(a->newton >= GLPGP_STALL_STEPS && a->newton < z->newton);
                CHECK(a->grad > a->rtol * a->grad0);
            }
        }
        const double e = c[0]->level[c[0]->nlevels - 1].energy, e0 = c[1]->level[c[1]->nlevels - 1].energy;
        printf("sphere cross: newton %d with the stall test, %d without; last energy %.8g vs %.8g\n",
               c[0]->newton_iterations, c[1]->newton_iterations, e, e0);
        CHECK(stalled == 1);
        CHECK(fabs(e - e0) <= 1e-3 * fabs(e0));
        CHECK(c[0]->nsing == 8 && c[0]->index4_sum == 8);
    }
    for (int k = 0; k < 2; k++) glpgp_cross_result_destroy(&c[k]);
    glpgp_surface_constraints_destroy(&con);
    glpgp_backend_destroy(&b);
    glpgp_mesh_destroy(&m);
}

/* The rolled-up strip against its unrolled twin: the same options, the
 * coupled solve on both; z of every vertex equal to 1e-8. */
static void test_developable(void)
{
    glpgp_mesh *ms = NULL, *mp = NULL;
    glpgp_backend *b = NULL;
    glpgp_result *rs = NULL, *rp = NULL;
    glpgp_options o;
    glpgp_options_default(&o);
    o.field = GLPGP_FIELD_CROSS;
    o.cross_coupling = GLPGP_COUPLING_ON;
    o.size_field = GLPGP_SIZE_NONE;
    o.cross_size = GLPGP_CROSS_SIZE_OFF;
    o.size = 0.5;
    o.newton_rtol = 1e-12;
    o.cg_rtol = 1e-13;
    o.vertex_order = GLPGP_ORDER_INPUT;
    CHECK_OK(glpgp_mesh_generate("halfcyl", 3000, &ms));
    CHECK_OK(glpgp_mesh_generate("halfcyl_flat", 3000, &mp));
    CHECK_OK(glpgp_backend_create_reference(&b));
    if (!ms || !mp || !b) return;
    CHECK_OK(glpgp_solve(ms, b, &o, &rs));
    CHECK_OK(glpgp_solve(mp, b, &o, &rp));
    if (rs && rp) {
        CHECK(rs->coupled && rp->coupled);
        double err = 0.0, zmax = 0.0;
        for (int i = 0; i < ms->nv; i++) {
            /* U of the surface's vertex i in the plane: into the triangle of its
             * first corner (rot), whose x axis is its edge 0 -> 1, at the angle
             * of that edge in the planar twin (the same triangle) */
            const int c = ms->surf->vstart[i], t = c / 3, *v = mp->tri + 3 * t;
            const double e01 = atan2(mp->xy[2 * v[1] + 1] - mp->xy[2 * v[0] + 1], mp->xy[2 * v[1]] - mp->xy[2 * v[0]]);
            const double a = atan2(rs->field[2 * i + 1], rs->field[2 * i]) + ms->surf->rot[c] + e01;
            const double us[2] = {cos(a), sin(a)};
            const int r = glpgp_cross_turn(rp->field + 2 * i, us); /* rot^r(U_surface) ~ U_plane */
            double zu[2], zv[2];
            glpgp_coupled_frame_value(r, 0, rs->osc[0].z + 2 * i, rs->osc[1].z + 2 * i, zu);
            glpgp_coupled_frame_value(r, 1, rs->osc[0].z + 2 * i, rs->osc[1].z + 2 * i, zv);
            for (int k = 0; k < 2; k++) {
                err = fmax(err, fabs(zu[k] - rp->osc[0].z[2 * i + k]));
                err = fmax(err, fabs(zv[k] - rp->osc[1].z[2 * i + k]));
                zmax = fmax(zmax, fabs(rp->osc[0].z[2 * i + k]));
            }
        }
        printf("developable: halfcyl vs halfcyl_flat (%d vertices, h %g): max |z difference| %.3g (max |z| %.3g), "
               "energies %.12g / %.12g, Newton %d / %d\n",
               ms->nv, o.size, err, zmax, rs->osc[0].energy, rp->osc[0].energy, rs->osc[0].newton_iterations,
               rp->osc[0].newton_iterations);
        CHECK(err < 1e-8);
        CHECK(zmax > 0.9);
    }
    glpgp_result_destroy(&rs);
    glpgp_result_destroy(&rp);
    glpgp_backend_destroy(&b);
    glpgp_mesh_destroy(&ms);
    glpgp_mesh_destroy(&mp);
}

/* The coupled solve of a closed surface at its default size: CG iterations
 * per Newton step of u+v (reported in osc[0]) */
static void test_coupled_cg(const char *shape)
{
    glpgp_mesh *m = NULL;
    glpgp_backend *b = NULL;
    glpgp_result *r = NULL;
    glpgp_options o;
    glpgp_options_default(&o);
    o.field = GLPGP_FIELD_CROSS; /* the surfaces' default in glpgp solve */
    CHECK_OK(glpgp_mesh_generate(shape, 3000, &m));
    CHECK_OK(glpgp_backend_create_reference(&b));
    if (!m || !b) return;
    CHECK_OK(glpgp_solve(m, b, &o, &r));
    if (r) {
        const int newton = r->osc[0].newton_iterations;
        const long cg = r->osc[0].cg_iterations;
        printf("coupled CG on %s (%d vertices): %d Newton, %ld CG, %.1f per step\n", shape, m->nv, newton, cg,
               (double)cg / (newton > 0 ? newton : 1));
        CHECK(r->coupled);
        CHECK(newton > 0 && newton <= 25);
        CHECK(cg <= 23L * newton);
    }
    glpgp_result_destroy(&r);
    glpgp_backend_destroy(&b);
    glpgp_mesh_destroy(&m);
}

/* glpgp_solve_prepare on a surface 3 mean edges per period: refined by
 * bisection until no edge is above h / GLPGP_SURFACE_EDGES, the same surface,
 * fewer triangles than the uniform rounds' 16x; with --max-elements at 4x
 * the input, the last level within it (a warning), at 1x the input as it
 * is; on a torus 7 mean edges per period (one uniform round short of the old
 * rule: 4x) only the long edges split (the global rule h / N, --size-field
 * none); with a size file (its values belong to the input's vertices) not
 * refined */
static void check_prepare_subdivides(void)
{
    glpgp_mesh *m = NULL, *r = NULL;
    CHECK_OK(glpgp_mesh_generate("torus", 2000, &m));
    if (!m) return;
    glpgp_options o;
    glpgp_options_default(&o);
    o.size = 3.0 * m->mean_edge;
    glpgp_prepare_info pi;
    CHECK_OK(glpgp_solve_prepare(m, &o, "torus", 0, 1, &r, &pi));
    CHECK(r != NULL && pi.refined.rounds == 0 && pi.refined.split_edges > 0);
    if (r) {
        printf("prepare: %d -> %d triangles, %ld edges bisected, longest edge h / %.3g, mean edge h / %.3g\n", m->nt,
               r->nt, pi.refined.split_edges, o.size / glpgp_mesh_longest_edge(r), o.size / r->mean_edge);
        CHECK(glpgp_mesh_longest_edge(r) <= o.size / GLPGP_SURFACE_EDGES);
        CHECK(r->nt < 16 * m->nt && pi.refined.nt == r->nt && pi.refined.nv - pi.refined.nv0 == pi.refined.split_edges);
        CHECK_CLOSE(r->area, m->area, 0.0, 1e-12);
        CHECK(r->surf->euler == m->surf->euler);
    }
    glpgp_mesh_destroy(&r);
    CHECK_OK(glpgp_solve_prepare(m, &o, "torus", 4.0 * m->nt, 1, &r, &pi));
    CHECK(r != NULL && r->nt <= 4 * m->nt);
    if (r) CHECK(glpgp_mesh_longest_edge(r) > o.size / GLPGP_SURFACE_EDGES);
    glpgp_mesh_destroy(&r);
    CHECK_OK(glpgp_solve_prepare(m, &o, "torus", 1.0 * m->nt, 1, &r, &pi));
    CHECK(r == NULL && pi.refined.split_edges == 0);
    CHECK_OK(glpgp_solve_prepare(m, &o, "torus", 0, 0, &r, &pi)); /* --no-refine */
    CHECK(r == NULL);
    /* a size file (one value per input vertex): not refined (a warning) */
    o.size_field = GLPGP_SIZE_FILE;
    o.size_file = "sizes-of-the-input.txt";
    CHECK_OK(glpgp_solve_prepare(m, &o, "torus", 0, 1, &r, &pi));
    CHECK(r == NULL && pi.refined.split_edges == 0);
    glpgp_mesh_destroy(&r);
    o.size_field = GLPGP_SIZE_AUTO;
    o.size_file = NULL;
    /* just above the old rule's mean edge: 4x triangles for the rounds (the
     * global rule, --size-field none: at this h the torus's curvature cap
     * asks for more, test_surface_refine.c) */
    o.size = 7.0 * m->mean_edge;
    o.size_field = GLPGP_SIZE_NONE;
    CHECK_OK(glpgp_solve_prepare(m, &o, "torus", 0, 1, &r, &pi));
    CHECK(r != NULL);
    if (r) {
        printf("prepare at 7 mean edges: %d -> %d triangles, longest edge h / %.3g\n", m->nt, r->nt,
               o.size / glpgp_mesh_longest_edge(r));
        CHECK(r->nt < 3 * m->nt && glpgp_mesh_longest_edge(r) <= o.size / GLPGP_SURFACE_EDGES);
    }
    glpgp_mesh_destroy(&r);
    glpgp_mesh_destroy(&m);
}

int main(void)
{
    test_fd();
    test_cross("sphere", 3000, 8, 8, 0);
    test_cross("cube", 1500, 8, 8, 0);
    test_cross("torus", 3000, 0, -1, -1);
    test_cross("genus2", 3000, -8, -1, -1);
    test_cross("hemisphere", 3000, 4, -1, -1);
    test_cross_stall();
    test_developable();
    test_coupled_cg("torus");
    test_coupled_cg("sphere");
    check_prepare_subdivides();
    TEST_DONE();
}
