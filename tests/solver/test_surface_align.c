/* test_surface_align.c: the principal-curvature term of a surface's cross
 * field (--cross-align; glpgp_surface_align_source, solver/surface_align.c;
 * the linear term of the Newton energy, glpgp_newton_state.lin):
 *  - on a torus (major radius 1) the source's crosses are those of the
 *    principal directions (the parallels and meridians) within 3 degrees
 *    at every vertex, on the input and (from its input triangles) on a
 *    refinement; on the sphere q is 0 everywhere, also on a refinement
 *    (from its input's normals; umbilic: the estimate's noise is gated out
 *    by the anisotropy);
 *  - the energy with the term: the gradient of F = E + P - b.x agrees with
 *    central differences of F (relative error < 1e-6);
 *  - the torus's cross field with the term (weight 5) has no singularity
 *    and follows the principal directions within 5 degrees everywhere;
 *    without it (weight 0) it is more than 20 degrees off somewhere (the
 *    smoothest field is not principal: the test can fail);
 *  - a planar mesh and a negative weight are refused. */
#include "testutil.h"

#include "glpgp/internal/newton.h"
#include "glpgp/surfsolve.h"

#include <math.h>
#include <string.h>

static double principal(double a)
{
    const double d = remainder(a, 2.0 * GLPGP_PI);
    return d <= -GLPGP_PI ? d + 2.0 * GLPGP_PI : d;
}

/* the torus's parallel direction at x */
static void parallel(const double *x, double *d)
{
    const double u = atan2(x[1], x[0]);
    d[0] = -sin(u);
    d[1] = cos(u);
    d[2] = 0.0;
}

/* The largest angle (degrees, mod 90) between the cross of w (2 nv) and the
 * principal cross at each vertex of the torus m. */
static double principal_error(const glpgp_mesh *m, const double *w)
{
    double e = 0.0;
    for (int v = 0; v < m->nv; v++) {
        double d[3];
        parallel(m->xyz + 3 * v, d);
        const double ref = 4.0 * glpgp_surface_vertex_angle(m, v, d), a = atan2(w[2 * v + 1], w[2 * v]);
        e = fmax(e, fabs(principal(a - ref)) / 4.0 * 180.0 / GLPGP_PI);
    }
    return e;
}

static void test_source(void)
{
    glpgp_mesh *t = NULL, *f = NULL, *s = NULL, *p = NULL;
    CHECK_OK(glpgp_mesh_generate("torus", 3000, &t));
    CHECK_OK(glpgp_mesh_generate("sphere", 3000, &s));
    CHECK_OK(glpgp_mesh_generate("square", 200, &p));
    if (!t || !s || !p) return;
    double *b = malloc((size_t)2 * t->nv * sizeof(double)), st[2] = {0, 0}, ss[2] = {1, 1};
    CHECK_OK(glpgp_surface_align_source(t, 1.0, NULL, b, st));
    const double et = principal_error(t, b);
    free(b);
    /* a refinement takes its input's q */
    CHECK_OK(glpgp_mesh_refine_surface(t, 0.5 * t->mean_edge, 0, &f, NULL));
    double ef = 180.0;
    if (f) {
        CHECK_OK(glpgp_surface_keep_origin(f, t));
        b = malloc((size_t)2 * f->nv * sizeof(double));
        CHECK_OK(glpgp_surface_align_source(f, 1.0, NULL, b, NULL));
        ef = principal_error(f, b);
        free(b);
    }
    b = malloc((size_t)2 * s->nv * sizeof(double));
    CHECK_OK(glpgp_surface_align_source(s, 1.0, NULL, b, ss));
    /* a refinement reads its input (the flat pieces' own fits see the input's
     * edges as creases: 35% of this refined sphere's area above the gate) */
    glpgp_mesh *sf = NULL;
    double sr[2] = {1, 1};
    CHECK_OK(glpgp_mesh_refine_surface(s, 0.5 * s->mean_edge, 0, &sf, NULL));
    if (sf) {
        double *bf = malloc((size_t)2 * sf->nv * sizeof(double));
        CHECK_OK(glpgp_surface_keep_origin(sf, s));
        CHECK_OK(glpgp_surface_align_source(sf, 1.0, NULL, bf, sr));
        free(bf);
    }
    glpgp_mesh_destroy(&sf);
    printf("source: torus %d vertices within %.2f degrees of the principal crosses, refined (%d) %.2f; "
           "largest |q| torus %.3g (on %.3f of the area), sphere %.3g (%.3f), refined sphere %.3g (%.3f)\n",
           t->nv, et, f ? f->nv : 0, ef, st[0], st[1], ss[0], ss[1], sr[0], sr[1]);
    CHECK(et < 3.0);
    CHECK(ef < 3.0);
    CHECK(st[0] > 1.0 && st[1] == 1.0);
    CHECK(ss[0] == 0.0 && ss[1] == 0.0); /* the sphere's estimate's noise is gated out */
    CHECK(sr[0] == 0.0 && sr[1] == 0.0);
    CHECK(glpgp_surface_align_source(s, -1.0, NULL, b, NULL) == GLPGP_ERR_ARG);
    CHECK(glpgp_surface_align_source(s, NAN, NULL, b, NULL) == GLPGP_ERR_ARG);
    CHECK(glpgp_surface_align_source(p, 1.0, NULL, b, NULL) == GLPGP_ERR_ARG);
    free(b);
    glpgp_mesh_destroy(&t);
    glpgp_mesh_destroy(&f);
    glpgp_mesh_destroy(&s);
    glpgp_mesh_destroy(&p);
}

/* F(x) = E + P - b.x at x (host, 2 nv) through glpgp_newton_gradient */
static double energy(glpgp_backend *b, glpgp_newton_state *ns, const double *x, double inv4e2)
{
    double sl[GLPGP_NSLOTS];
    CHECK_OK(b->ops->vec_write(b, ns->x, x));
    CHECK_OK(glpgp_newton_gradient(b, ns, inv4e2));
    CHECK_OK(b->ops->get_scalars(b, sl, GLPGP_NSLOTS));
    return glpgp_newton_energy(ns, sl);
}

static void test_gradient(void)
{
    glpgp_mesh *m = NULL;
    glpgp_backend *b = NULL;
    glpgp_system *sys = NULL;
    CHECK_OK(glpgp_mesh_generate("torus", 800, &m));
    CHECK_OK(glpgp_backend_create_reference(&b));
    if (!m || !b) return;
    const int nv = m->nv;
    const size_t n2 = (size_t)2 * nv;
    const glpgp_backend_ops *op = b->ops;
    double *x = calloc(n2, sizeof(double)), *d = calloc(n2, sizeof(double)), *g = calloc(n2, sizeof(double));
    double *bl = calloc(n2, sizeof(double)), *xp = calloc(n2, sizeof(double));
    unsigned char *fixed = calloc((size_t)nv, 1);
    glpgp_vec *vx = NULL, *vg = NULL, *vw = NULL, *vl = NULL;
    CHECK_OK(glpgp_surface_cross_system(m, &sys));
    CHECK_OK(op->setup(b, sys));
    CHECK_OK(op->set_field(b, x, fixed));
    CHECK_OK(op->assemble_quadratic(b, GLPGP_ELEM_P1, 1.0));
    CHECK_OK(op->vec_create(b, n2, &vx));
    CHECK_OK(op->vec_create(b, n2, &vg));
    CHECK_OK(op->vec_create(b, n2, &vw));
    CHECK_OK(op->vec_create(b, n2, &vl));
    CHECK_OK(glpgp_surface_align_source(m, 5.0, fixed, bl, NULL));
    CHECK_OK(op->vec_write(b, vl, bl));
    unsigned r = 12345u;
    for (size_t i = 0; i < n2; i++) {
        r = r * 1103515245u + 12345u;
        x[i] = ((r >> 8) & 0xffff) / 32768.0 - 1.0;
        r = r * 1103515245u + 12345u;
        d[i] = ((r >> 8) & 0xffff) / 32768.0 - 1.0;
    }
    glpgp_newton_state ns = {.x = vx, .g = vg, .work = vw, .lin = vl};
    const double inv4e2 = 1.0 / (4.0 * 0.1 * 0.1), t = 1e-6;
    energy(b, &ns, x, inv4e2);
    CHECK_OK(op->vec_read(b, vg, g));
    double gd = 0.0, bd = 0.0;
    for (size_t i = 0; i < n2; i++) {
        gd += g[i] * d[i];
        bd += bl[i] * d[i];
    }
    for (size_t i = 0; i < n2; i++) xp[i] = x[i] + t * d[i];
    const double fp = energy(b, &ns, xp, inv4e2);
    for (size_t i = 0; i < n2; i++) xp[i] = x[i] - t * d[i];
    const double fm = energy(b, &ns, xp, inv4e2), fd = (fp - fm) / (2.0 * t);
    printf("gradient with the linear term: g.d %.10g, central difference %.10g (b.d %.4g)\n", gd, fd, bd);
    CHECK(fabs(gd - fd) <= 1e-6 * fabs(gd));
    CHECK(fabs(bd) > 1e-3 * fabs(gd)); /* the term counts in the check */
    op->vec_destroy(b, &vx);
    op->vec_destroy(b, &vg);
    op->vec_destroy(b, &vw);
    op->vec_destroy(b, &vl);
    glpgp_system_destroy(&sys);
    b->sys = NULL;
    free(x);
    free(d);
    free(g);
    free(bl);
    free(xp);
    free(fixed);
    glpgp_backend_destroy(&b);
    glpgp_mesh_destroy(&m);
}

/* the torus's cross field with weight lambda: singularities and the largest angle to the principal crosses */
static void torus_cross(double lambda, int *nsing, double *err)
{
    glpgp_mesh *m = NULL;
    glpgp_backend *b = NULL;
    glpgp_surface_constraints *con = NULL;
    glpgp_cross_result *c = NULL;
    glpgp_options o;
    glpgp_options_default(&o);
    o.cross_align = lambda;
    *nsing = -1;
    *err = 180.0;
    CHECK_OK(glpgp_mesh_generate("torus", 3000, &m));
    CHECK_OK(glpgp_backend_create_reference(&b));
    if (!m || !b) return;
    CHECK_OK(glpgp_surface_constraints_create(m, o.feature_angle, &con));
    CHECK_OK(glpgp_surface_cross_solve(m, b, &o, con, &c));
    if (c) {
        *nsing = c->nsing;
        *err = principal_error(m, c->w);
    }
    glpgp_cross_result_destroy(&c);
    glpgp_surface_constraints_destroy(&con);
    glpgp_backend_destroy(&b);
    glpgp_mesh_destroy(&m);
}

static void test_cross(void)
{
    int n5, n0;
    double e5, e0;
    torus_cross(5.0, &n5, &e5);
    torus_cross(0.0, &n0, &e0);
    printf("torus cross field: weight 5: %d singularities, within %.2f degrees of the principal crosses; "
           "weight 0: %d singularities, %.2f degrees\n",
           n5, e5, n0, e0);
    CHECK(n5 == 0);
    CHECK(e5 < 5.0);
    CHECK(e0 > 20.0);
}

int main(void)
{
    test_source();
    test_gradient();
    test_cross();
    TEST_DONE();
}
