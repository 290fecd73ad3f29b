/* test_surface_cross_transfer.c: a surface's cross field carried from a
 * coarse mesh onto its refinement (glpgp_surface_cross_transfer,
 * glpgp_surface_cross_on_input; solver/surface_transfer.c):
 *  - the refinement's origin (otri, obary): every refined vertex is the
 *    barycentric combination of its input triangle's corners (to 1e-12 of
 *    the size), also through the solver's passes (glpgp_solve_prepare);
 *  - an analytic smooth cross field on a torus (a direction 30 degrees off
 *    the parallels, each vertex's cross read in its own frame) carried over
 *    agrees with the same field read on the refined mesh within 2 degrees
 *    at every vertex; the plain interpolation of the coarse values without
 *    the frames' conversion is checked to be off by far more (the test can
 *    fail);
 *  - an input vertex keeps its cross: the same 3D direction (one of the
 *    four branches) and |w| in both meshes' frames;
 *  - the sphere's cross field solved on the coarse mesh, carried over: the
 *    index sum on the refined mesh is Poincare-Hopf's 8/4 and there are 8
 *    singularities, as on the coarse mesh (the sum alone holds for any
 *    field: without the frames' conversion thousands of pairs appear);
 *  - the solve's path (glpgp_solve_prepare keeps an input of two eps levels, not one of one, then
 *    glpgp_surface_cross_on_input) on the sphere: solved on the input's
 *    vertices, analysed on the refined mesh with Poincare-Hopf's sum, and
 *    with the polish as well. */
#include "testutil.h"

#include "glpgp/solve.h"
#include "glpgp/surfsolve.h"

#include <math.h>
#include <string.h>

static double principal(double a)
{
    const double d = remainder(a, 2.0 * GLPGP_PI);
    return d <= -GLPGP_PI ? d + 2.0 * GLPGP_PI : d;
}

/* The largest distance of a refined vertex from the combination of its input
 * triangle's corners (every corner of every triangle). */
static double origin_error(const glpgp_mesh *coarse, const glpgp_mesh *fine)
{
    const glpgp_surface *s = fine->surf;
    double err = 0.0;
    for (int c = 0; c < 3 * fine->nt; c++) {
        const int T = s->otri[c / 3], v = fine->tri[c];
        const double *lam = s->obary + 9 * (c / 3) + 3 * (c % 3);
        for (int e = 0; e < 3; e++) {
            double x = 0.0;
            for (int k = 0; k < 3; k++) x += lam[k] * coarse->xyz[3 * coarse->tri[3 * T + k] + e];
            err = fmax(err, fabs(x - fine->xyz[3 * v + e]));
        }
    }
    return err;
}

/* The torus's field: 30 degrees off the parallel at x (3D unit vector). */
static void torus_direction(const double *x, double *d)
{
    const double u = atan2(x[1], x[0]), rr = hypot(x[0], x[1]), w = atan2(x[2], rr - 1.0);
    const double eu[3] = {-sin(u), cos(u), 0.0}, ew[3] = {-sin(w) * cos(u), -sin(w) * sin(u), cos(w)};
    const double c = cos(GLPGP_PI / 6.0), s = sin(GLPGP_PI / 6.0);
    for (int k = 0; k < 3; k++) d[k] = c * eu[k] + s * ew[k];
}

static void analytic_field(const glpgp_mesh *m, double *w)
{
    for (int v = 0; v < m->nv; v++) {
        double d[3];
        torus_direction(m->xyz + 3 * v, d);
        const double th = glpgp_surface_vertex_angle(m, v, d);
        w[2 * v] = cos(4.0 * th);
        w[2 * v + 1] = sin(4.0 * th);
    }
}

/* The largest angle (degrees, crosses: mod 90) between w and ref per vertex. */
static double max_angle(int nv, const double *w, const double *ref)
{
    double e = 0.0;
    for (int v = 0; v < nv; v++) {
        const double a = atan2(w[2 * v + 1], w[2 * v]), b = atan2(ref[2 * v + 1], ref[2 * v]);
        e = fmax(e, fabs(principal(a - b)) / 4.0 * 180.0 / GLPGP_PI);
    }
    return e;
}

static void test_torus(void)
{
    glpgp_mesh *c = NULL, *f = NULL;
    CHECK_OK(glpgp_mesh_generate("torus", 800, &c));
    if (!c) return;
    CHECK_OK(glpgp_mesh_refine_surface(c, 0.45 * c->mean_edge, 0, &f, NULL));
    CHECK(f != NULL);
    if (!f) {
        glpgp_mesh_destroy(&c);
        return;
    }
    CHECK(f->nv > 4 * c->nv);
    CHECK(f->surf->otri && f->surf->obary);
    const double oe = origin_error(c, f);
    CHECK(oe < 1e-12 * glpgp_mesh_diagonal(c));
    double *wc = malloc(2 * sizeof(double) * c->nv), *wf = malloc(2 * sizeof(double) * f->nv);
    double *ref = malloc(2 * sizeof(double) * f->nv), *naive = malloc(2 * sizeof(double) * f->nv);
    analytic_field(c, wc);
    analytic_field(f, ref);
    CHECK_OK(glpgp_surface_cross_transfer(c, wc, f, wf));
    /* without the frames: the corners' values interpolated as they are */
    for (int v = 0; v < f->nv; v++) {
        const int t = f->surf->vstart[v] / 3, a = f->surf->vstart[v] % 3, T = f->surf->otri[t];
        naive[2 * v] = naive[2 * v + 1] = 0.0;
        for (int k = 0; k < 3; k++) {
            const double l = f->surf->obary[9 * t + 3 * a + k];
            naive[2 * v] += l * wc[2 * c->tri[3 * T + k]];
            naive[2 * v + 1] += l * wc[2 * c->tri[3 * T + k] + 1];
        }
    }
    double wmin = HUGE_VAL;
    for (int v = 0; v < f->nv; v++) wmin = fmin(wmin, hypot(wf[2 * v], wf[2 * v + 1]));
    const double e = max_angle(f->nv, wf, ref), en = max_angle(f->nv, naive, ref);
    printf("torus %d -> %d vertices: origin error %.2g; transferred field within %.3g degrees of the analytic one "
           "(without the frames' conversion %.3g), smallest |w| %.4f\n",
           c->nv, f->nv, oe, e, en, wmin);
    CHECK(e < 2.0);
    CHECK(en > 10.0);
    CHECK(wmin > 0.9); /* a smooth field: the interpolant's |w| stays near 1 */
    /* an input vertex keeps its cross: the same 3D direction and |w| */
    double dv = 0.0, dm = 0.0;
    for (int v = 0; v < c->nv; v++) {
        const double ac = atan2(wc[2 * v + 1], wc[2 * v]) / 4.0, af = atan2(wf[2 * v + 1], wf[2 * v]) / 4.0;
        /* the fine frame's branch af + j pi/2 nearest (at a cone vertex the four
         * branches are not 90 degrees apart in 3D: compared as vectors) */
        double pc[3], best = HUGE_VAL;
        glpgp_surface_vertex_vector(c, v, cos(ac), sin(ac), pc);
        for (int j = 0; j < 4; j++) {
            double pf[3];
            const double a = af + j * GLPGP_PI / 2.0;
            glpgp_surface_vertex_vector(f, v, cos(a), sin(a), pf);
            const double cr[3] = {pc[1] * pf[2] - pc[2] * pf[1], pc[2] * pf[0] - pc[0] * pf[2],
                                  pc[0] * pf[1] - pc[1] * pf[0]};
            const double dot = pc[0] * pf[0] + pc[1] * pf[1] + pc[2] * pf[2];
            best = fmin(best, atan2(sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]), dot));
        }
        dv = fmax(dv, best);
        dm = fmax(dm, fabs(hypot(wc[2 * v], wc[2 * v + 1]) - hypot(wf[2 * v], wf[2 * v + 1])));
    }
    printf("torus: input vertices' crosses kept to %.2g rad, |w| to %.2g\n", dv, dm);
    CHECK(dv < 1e-9);
    CHECK(dm < 1e-12);
    free(wc);
    free(wf);
    free(ref);
    free(naive);
    glpgp_mesh_destroy(&f);
    glpgp_mesh_destroy(&c);
}

/* The sphere's solved cross field carried onto its refinement: 8 x +1/4. */
static void test_sphere_index(void)
{
    glpgp_mesh *c = NULL, *f = NULL;
    glpgp_backend *b = NULL;
    glpgp_surface_constraints *con = NULL;
    glpgp_cross_result *cc = NULL, *cf = NULL;
    glpgp_options o;
    glpgp_options_default(&o);
    CHECK_OK(glpgp_mesh_generate("sphere", 1500, &c));
    CHECK_OK(glpgp_backend_create_reference(&b));
    if (!c || !b) return;
    CHECK_OK(glpgp_mesh_refine_surface(c, 0.45 * c->mean_edge, 0, &f, NULL));
    CHECK_OK(glpgp_surface_constraints_create(c, o.feature_angle, &con));
    CHECK_OK(glpgp_surface_cross_solve(c, b, &o, con, &cc));
    if (f && cc) {
        CHECK_OK(glpgp_cross_result_create(f->nv, f->nt, &cf));
        CHECK_OK(glpgp_surface_cross_transfer(c, cc->w, f, cf->w));
        CHECK_OK(glpgp_cross_analyze(f, cf));
        printf("sphere %d -> %d vertices: %d singularities on the coarse mesh, %d carried over, index sum %d/4 "
               "(expected %d/4), median |w| %.4f\n",
               c->nv, f->nv, cc->nsing, cf->nsing, cf->index4_sum, cf->index4_expected, cf->zabs_median);
        CHECK(cc->index4_sum == 8);
        CHECK(cf->index4_sum == 8 && cf->index4_expected == 8);
        CHECK(cf->nsing == 8); /* a frame error scatters thousands of +-1/4 pairs (the sum stays 8/4) */
        CHECK(cf->zabs_median > 0.9);
    }
    glpgp_cross_result_destroy(&cf);
    glpgp_cross_result_destroy(&cc);
    glpgp_surface_constraints_destroy(&con);
    glpgp_backend_destroy(&b);
    glpgp_mesh_destroy(&f);
    glpgp_mesh_destroy(&c);
}

/* glpgp_solve_prepare keeps the input; glpgp_surface_cross_on_input. */
static void test_on_input(int polish)
{
    glpgp_mesh *m = NULL, *mr = NULL;
    glpgp_backend *b = NULL;
    glpgp_surface_constraints *con = NULL;
    glpgp_cross_result *c = NULL;
    glpgp_options o;
    glpgp_prepare_info pi;
    glpgp_options_default(&o);
    o.field = GLPGP_FIELD_CROSS;
    /* an input of one eps level (too coarse for a continuation) is not kept */
    CHECK_OK(glpgp_mesh_generate("sphere", 1500, &m));
    if (!m) return;
    o.size = 3.0 * m->mean_edge; /* edges above h / 6: refined */
    CHECK_OK(glpgp_solve_prepare(m, &o, "sphere", 0, 1, &mr, &pi));
    CHECK(mr && mr->surf->origin && !mr->surf->origin_cross); /* kept for the curvature term only */
    glpgp_mesh_destroy(&mr);
    glpgp_mesh_destroy(&m);
    CHECK_OK(glpgp_mesh_generate("sphere", 8000, &m)); /* two eps levels */
    CHECK_OK(glpgp_backend_create_reference(&b));
    if (!m || !b) return;
    o.size = 3.0 * m->mean_edge;
    CHECK_OK(glpgp_solve_prepare(m, &o, "sphere", 0, 1, &mr, &pi));
    CHECK(mr && mr->surf->origin && mr->surf->origin_cross);
    if (mr && mr->surf->origin) {
        CHECK(mr->surf->origin->nv == m->nv && mr->surf->origin->nt == m->nt);
        CHECK(origin_error(m, mr) < 1e-12 * glpgp_mesh_diagonal(m));
        CHECK_OK(glpgp_surface_constraints_create(mr, o.feature_angle, &con));
        CHECK_OK(glpgp_surface_cross_on_input(mr, b, &o, con, polish, &c));
    }
    if (c) {
        printf("on the input%s: %d -> %d vertices, solved on %d; %d singularities, index sum %d/4 "
               "(expected %d/4), %d levels\n",
               polish ? " + polish" : "", m->nv, mr->nv, c->solved_nv, c->nsing, c->index4_sum,
               c->index4_expected, c->nlevels);
        CHECK(c->nv == mr->nv && c->solved_nv == m->nv);
        CHECK(c->index4_sum == 8 && c->index4_expected == 8);
        CHECK(c->nsing == 8); /* the sum holds for any field (discrete Stokes): the count does not */
        CHECK(c->polished == polish);
    }
    glpgp_cross_result_destroy(&c);
    glpgp_surface_constraints_destroy(&con);
    glpgp_backend_destroy(&b);
    glpgp_mesh_destroy(&mr);
    glpgp_mesh_destroy(&m);
}

int main(void)
{
    test_torus();
    test_sphere_index();
    test_on_input(0);
    test_on_input(1);
    TEST_DONE();
}
