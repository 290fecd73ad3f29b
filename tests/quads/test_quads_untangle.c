/* test_quads_untangle.c: the local repair's untangling of a lift
 * (glpgp_qs_untangle, untangle_surface.c), without a repair, on a 4 x 4
 * grid of quads (25 points, h = 0.12) on the unit sphere's triangle mesh
 * (about 2000 points), its 16 boundary points fixed (ids below first = 16),
 * the 9 inner ones moving; the points in two arrays as the repair keeps
 * them (ids below 12 in base; 12 .. 15 in ext yet fixed):
 *  - one or two inner points pushed 0.55 h along a diagonal (a reflex
 *    corner: worst scaled Jacobian in (-0.5, 0], about -0.2) are mended:
 *    the worst corner above 0 after, returned as glpgp_qs_worst_sj
 *    measures it, the moved points on the surface (their nearest point on
 *    the mesh within 1e-12, radius within 0.01 of 1), the fixed points
 *    bit for bit as they were;
 *  - left alone, every point bit for bit and the worst corner as given:
 *    max_sweeps 0, first = n (no point may move), and untangled quads
 *    (worst corner already above the floor). */
#include "testutil.h"

#include "../host/quads/quads_surface.h"

#include <string.h>

#define GN 5    /* points per grid row */
#define NP (GN * GN)
#define NQ ((GN - 1) * (GN - 1))
#define FIRST 16 /* the inner points' first id */
#define NBASE 12 /* ids below in base, the others in ext */
#define H 0.12

typedef struct ugrid {
    double xyz[3 * NP]; /* all points by id (base: xyz, ext: xyz + 3 NBASE) */
    int id[GN][GN];     /* grid point (i, j) -> id: the boundary first */
    int quads[4 * NQ];
} ugrid;

/* The grid about the direction (0.3, 0.2, 1), each point on the mesh
 * (P's nearest point to the gnomonic one); the quads counter-clockwise
 * seen from outside. */
static void make_grid(const glpgp_qs_proj *P, ugrid *g)
{
    const double l = sqrt(0.09 + 0.04 + 1.0);
    const double c[3] = {0.3 / l, 0.2 / l, 1.0 / l};
    const double e1[3] = {c[2], 0.0, -c[0]}, n1 = sqrt(c[2] * c[2] + c[0] * c[0]);
    const double u[3] = {e1[0] / n1, 0.0, e1[2] / n1};
    const double v[3] = {c[1] * u[2] - c[2] * u[1], c[2] * u[0] - c[0] * u[2], c[0] * u[1] - c[1] * u[0]};
    int nb = 0, ni = FIRST;
    for (int i = 0; i < GN; i++)
        for (int j = 0; j < GN; j++) {
            const int inner = i > 0 && j > 0 && i < GN - 1 && j < GN - 1;
            const int k = inner ? ni++ : nb++;
            double p[3];
            for (int d = 0; d < 3; d++) p[d] = c[d] + (i - 2) * H * u[d] + (j - 2) * H * v[d];
            glpgp_qs_proj_nearest(P, p, g->xyz + 3 * k);
            g->id[i][j] = k;
        }
    for (int i = 0, q = 0; i < GN - 1; i++)
        for (int j = 0; j < GN - 1; j++, q++) {
            const int qq[4] = {g->id[i][j], g->id[i + 1][j], g->id[i + 1][j + 1], g->id[i][j + 1]};
            memcpy(g->quads + 4 * q, qq, sizeof qq);
        }
}

/* Grid point (i, j) pushed by (a, b) h along the grid's axes, back onto the mesh. */
static void push(const glpgp_qs_proj *P, ugrid *g, int i, int j, double a, double b)
{
    double *p = g->xyz + 3 * g->id[i][j], x[3];
    const double *pu = g->xyz + 3 * g->id[i + 1][j], *pv = g->xyz + 3 * g->id[i][j + 1];
    for (int d = 0; d < 3; d++) x[d] = p[d] + a * (pu[d] - p[d]) + b * (pv[d] - p[d]);
    glpgp_qs_proj_nearest(P, x, p);
}

static glpgp_qs_pts pts(ugrid *g, int n)
{
    return (glpgp_qs_pts){g->xyz, g->xyz + 3 * NBASE, NBASE, n};
}

/* Untangle the grid's quads: *worst before and after. */
static void run(const glpgp_qs_proj *P, ugrid *g, int first, int n, int sweeps, double *before, double *after)
{
    const glpgp_qs_pts S = pts(g, n);
    *before = *after = glpgp_qs_worst_sj(P, &S, g->quads, NQ);
    CHECK_OK(glpgp_qs_untangle(P, &S, first, g->quads, NQ, sweeps, 0.0, after));
}

/* A tangled grid (pushed 0.55 h along the diagonal at the inner points
 * (2, 2), and (1, 1) with two) mended. */
static void mended(const glpgp_qs_proj *P, int two)
{
    ugrid g, g0;
    make_grid(P, &g);
    const glpgp_qs_pts S = pts(&g, NP);
    CHECK(glpgp_qs_worst_sj(P, &S, g.quads, NQ) > 0.9); /* the grid itself: near squares */
    push(P, &g, 2, 2, 0.55, 0.55);
    if (two) push(P, &g, 1, 1, -0.55, -0.55);
    g0 = g;
    double before, after;
    run(P, &g, FIRST, NP, 10, &before, &after);
    printf("%s: worst corner %.4f -> %.4f\n", two ? "two points" : "one point", before, after);
    CHECK(before > -0.5 && before <= 0.0);
    CHECK(after > 0.0);
    CHECK(after == glpgp_qs_worst_sj(P, &S, g.quads, NQ));
    CHECK(memcmp(g.xyz, g0.xyz, 3 * FIRST * sizeof(double)) == 0); /* fixed, in base and in ext */
    double dmax = 0.0, rdev = 0.0;
    int moved = 0;
    for (int k = FIRST; k < NP; k++) {
        const double *p = g.xyz + 3 * k;
        double x[3], d2 = 0.0;
        glpgp_qs_proj_nearest(P, p, x);
        for (int d = 0; d < 3; d++) d2 += (x[d] - p[d]) * (x[d] - p[d]);
        dmax = fmax(dmax, sqrt(d2));
        rdev = fmax(rdev, fabs(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1.0));
        moved += memcmp(p, g0.xyz + 3 * k, 3 * sizeof(double)) != 0;
    }
    CHECK(dmax < 1e-12);
    CHECK(rdev < 0.01);
    CHECK(moved == NP - FIRST); /* every inner point swept */
}

/* What glpgp_qs_untangle must leave as it is: every point bit for bit, the
 * worst corner as given. */
static void left_alone(const glpgp_qs_proj *P)
{
    ugrid g, g0;
    double before, after;
    make_grid(P, &g);
    push(P, &g, 2, 2, 0.55, 0.55);
    g0 = g;
    run(P, &g, FIRST, NP, 0, &before, &after); /* no sweep asked */
    CHECK(before <= 0.0 && after == before);
    CHECK(memcmp(g.xyz, g0.xyz, sizeof g.xyz) == 0);
    run(P, &g, NP, NP, 10, &before, &after); /* no point may move */
    CHECK(before <= 0.0 && after == before);
    CHECK(memcmp(g.xyz, g0.xyz, sizeof g.xyz) == 0);
    make_grid(P, &g); /* untangled already */
    push(P, &g, 2, 2, 0.2, 0.1);
    g0 = g;
    run(P, &g, FIRST, NP, 10, &before, &after);
    CHECK(before > 0.0 && after == before);
    CHECK(memcmp(g.xyz, g0.xyz, sizeof g.xyz) == 0);
    const glpgp_qs_pts S = pts(&g, NP); /* first below the points in ext: refused */
    CHECK(glpgp_qs_untangle(P, &S, NBASE - 1, g.quads, NQ, 10, 0.0, &after) == GLPGP_ERR_ARG);
    glpgp_error_clear();
}

int main(void)
{
    glpgp_mesh *m = NULL;
    glpgp_qs_proj *P = NULL;
    CHECK_OK(glpgp_surface_generate("sphere", 2000, &m));
    if (m) CHECK_OK(glpgp_qs_proj_create(m, H, 2.0 * H, &P));
    if (P) {
        mended(P, 0);
        mended(P, 1);
        left_alone(P);
    }
    glpgp_qs_proj_destroy(&P);
    glpgp_mesh_destroy(&m);
    TEST_DONE();
}
