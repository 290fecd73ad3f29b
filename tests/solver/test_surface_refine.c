/* test_surface_refine.c: a surface refined to its local size
 * (glpgp_solve_prepare with --size-field auto, solver/surface_refine.c):
 *  - on a genus-2 surface at a coarse size, where the curvature cap makes
 *    the local size h(x) smaller than h, every edge of the refined mesh is
 *    at most h(x) / GLPGP_SURFACE_EDGES (within 10%), h(x) computed on the
 *    refined mesh as the solve computes it (glpgp_surface_size); the global
 *    rule (every edge at most h / N) leaves edges near 1.5 h(x) / N there;
 *  - the same surface (area, Euler characteristic), and fewer triangles
 *    than refining everything to the smallest h(x) / N;
 *  - the local size is the same on the input and on refinements of it (the
 *    curvature measured as the sagitta of patches of a given radius, not
 *    per edge: per edge it grew as the edges were bisected): on the unit
 *    sphere the analytic cap;
 *  - within --max-elements (the ratio then reported above 1);
 *  - with --size-field none the refinement is the global one (h / N);
 *  - with a size file none (its values belong to the input's vertices). */
#include "testutil.h"

#include "glpgp/surfsolve.h"

#include <stdlib.h>

static double elen(const glpgp_mesh *m, int i, int j)
{
    const double *p = m->xyz + 3 * i, *q = m->xyz + 3 * j;
    return sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

/* the largest edge / (h(x) / N) of m with the solve's size, the smallest
 * size and the share of vertices below h */
static double edge_ratio(const glpgp_mesh *m, const glpgp_options *o, double h, double *smin, double *below)
{
    glpgp_surface_constraints *con = NULL;
    double *size = malloc(sizeof(double) * 2 * (size_t)m->nv), r = 0.0;
    int uniform = 0, nb = 0;
    CHECK_OK(glpgp_surface_constraints_create(m, o->feature_angle, &con));
    CHECK_OK(glpgp_surface_size(m, o, con, h, size, &uniform));
    *smin = HUGE_VAL;
    for (int i = 0; i < m->nv; i++) {
        *smin = fmin(*smin, size[i]);
        nb += size[i] < 0.999 * h;
    }
    *below = (double)nb / m->nv;
    for (int t = 0; t < m->nt; t++)
        for (int a = 0; a < 3; a++) {
            const int i = m->tri[3 * t + a], j = m->tri[3 * t + (a + 1) % 3];
            r = fmax(r, elen(m, i, j) * GLPGP_SURFACE_EDGES / fmin(size[i], size[j]));
        }
    glpgp_surface_constraints_destroy(&con);
    free(size);
    return r;
}

static void check_genus2(void)
{
    glpgp_mesh *m = NULL, *r = NULL, *g = NULL;
    CHECK_OK(glpgp_mesh_generate("genus2", 3000, &m));
    if (!m) return;
    glpgp_options o;
    glpgp_options_default(&o);
    CHECK(o.size_field == GLPGP_SIZE_AUTO);
    o.size = 0.6; /* about 100 quads on its area of 36.8 */
    const double h = o.size;
    glpgp_prepare_info pi;
    CHECK_OK(glpgp_solve_prepare(m, &o, "genus2", 0, 1, &r, &pi));
    CHECK(r != NULL && pi.refined.local && pi.refined.split_edges > 0);
    if (!r) {
        glpgp_mesh_destroy(&m);
        return;
    }
    double smin, below, smin0, below0, sming, belowg;
    const double ratio = edge_ratio(r, &o, h, &smin, &below);
    /* the input's own local size (on its coarse edges the resolution limit
     * min(h, 4 edges) may raise it) and the global rule's mesh */
    edge_ratio(m, &o, h, &smin0, &below0);
    CHECK_OK(glpgp_mesh_refine_surface(m, h / GLPGP_SURFACE_EDGES, 0, &g, NULL));
    const double ratio_g = g ? edge_ratio(g, &o, h, &sming, &belowg) : 0.0;
    printf("genus2 local: %d -> %d triangles (global rule %d), largest edge / (h(x) / %g) %.3f (global rule %.3f; "
           "reported %.3f), smallest h(x) h / %.2f (input h / %.2f, global rule h / %.2f), %.1f%% below h\n",
           m->nt, r->nt, g ? g->nt : 0, GLPGP_SURFACE_EDGES, ratio, ratio_g, pi.refined.edge_ratio, h / smin,
           h / smin0, g ? h / sming : 0.0, 100.0 * below);
    CHECK(below > 0.05 && smin < 0.7 * h); /* the curvature cap is active */
    CHECK(ratio <= 1.1);
    CHECK(fabs(pi.refined.edge_ratio - ratio) <= 1e-9 * ratio);
    CHECK(ratio_g > 1.3); /* the global rule does not reach N edges per local period */
    CHECK(pi.refined.target_edge < h / GLPGP_SURFACE_EDGES);
    CHECK_CLOSE(r->area, m->area, 0.0, 1e-12);
    CHECK(r->surf->euler == m->surf->euler && r->nloops == m->nloops);
    /* fewer triangles than everything refined to the smallest target */
    glpgp_mesh *u = NULL;
    CHECK_OK(glpgp_mesh_refine_surface(m, pi.refined.target_edge, 0, &u, NULL));
    CHECK(u && r->nt < u->nt / 2);
    if (u) printf("  everything to the smallest target: %d triangles\n", u->nt);
    glpgp_mesh_destroy(&u);
    glpgp_mesh_destroy(&r);
    /* --max-elements: within it (the last level that fits), said so */
    CHECK_OK(glpgp_solve_prepare(m, &o, "genus2", 2.0 * m->nt, 1, &r, &pi));
    CHECK(r && r->nt <= 2 * m->nt && pi.refined.edge_ratio > 1.1);
    if (r) printf("  within 2x the input: %d triangles, largest edge / (h(x) / %g) %.3f\n", r->nt, GLPGP_SURFACE_EDGES,
                  pi.refined.edge_ratio);
    glpgp_mesh_destroy(&r);
    /* --size-field none: h / N everywhere, the global rule's mesh */
    o.size_field = GLPGP_SIZE_NONE;
    CHECK_OK(glpgp_solve_prepare(m, &o, "genus2", 0, 1, &r, &pi));
    CHECK(r && g && !pi.refined.local && r->nt == g->nt);
    glpgp_mesh_destroy(&r);
    /* a size file (one value per input vertex): not refined, a warning */
    o.size_field = GLPGP_SIZE_FILE;
    o.size_file = "sizes-of-the-input.txt";
    CHECK_OK(glpgp_solve_prepare(m, &o, "genus2", 0, 1, &r, &pi));
    CHECK(r == NULL && pi.refined.split_edges == 0);
    glpgp_mesh_destroy(&r);
    glpgp_mesh_destroy(&g);
    glpgp_mesh_destroy(&m);
}

/* the unit sphere at h = 2: the cap is the chord of sagitta d = h / 8,
 * 2 sqrt(2 d - d^2) = 1.32 = h / 1.51, on the input and on its refinements
 * to h / 12 and h / 24 alike (measured per edge, the estimate grew as the
 * edges of the same polyhedron were bisected: on genus2:20000 at h = 0.3,
 * h / 2.5 on the input, h / 4.0 and h / 7.9 refined to h / 16 and h / 32) */
static void check_sphere_scale(void)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("sphere", 800, &m));
    if (!m) return;
    glpgp_options o;
    glpgp_options_default(&o);
    const double h = 2.0, d = h * o.size_chord_depth, cap = 2.0 * sqrt(2.0 * d - d * d);
    for (int k = 0; k < 3; k++) {
        glpgp_mesh *f = NULL;
        if (k) CHECK_OK(glpgp_mesh_refine_surface(m, h / (12.0 * k), 0, &f, NULL));
        const glpgp_mesh *g = k ? f : m;
        double smin, below;
        if (g) edge_ratio(g, &o, h, &smin, &below);
        if (g) printf("sphere %s: %d triangles, smallest h(x) %.4g (the chord of sagitta h / 8: %.4g), %.1f%% below h\n",
                      k ? (k == 1 ? "to h / 12" : "to h / 24") : "input", g->nt, smin, cap, 100.0 * below);
        CHECK(g && fabs(smin / cap - 1.0) < 0.15 && below > 0.99);
        glpgp_mesh_destroy(&f);
    }
    glpgp_mesh_destroy(&m);
}

int main(void)
{
    check_genus2();
    check_sphere_scale();
    TEST_DONE();
}
