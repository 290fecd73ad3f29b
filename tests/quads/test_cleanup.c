/* test_cleanup.c: the topological clean-up of quad meshes
 * (glpgp_quadmesh_cleanup, quads/cleanup.c).
 *  - a regular N x N grid: nothing to do (NULL: the mesh stands);
 *  - a doublet (a grid quad split through its center into two quads sharing
 *    two edges): removed, the grid's valences restored (0 irregular);
 *  - a rotated edge (two valence 5 and two valence 3 vertices): rotated
 *    back (0 irregular);
 *  - random defects (three rotated edges on a jittered grid, bent so the
 *    quads are convex; the valid ones of 30): the irregular count drops, every face stays a convex CCW quad, the
 *    boundary vertices keep their positions and the area is unchanged;
 *  - a mesh with a non-quad face is left alone. */
#include "glpgp/quads.h"
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define N 8

/* (N+1)^2 vertices, N^2 quads, jitter j of the interior vertices. */
static glpgp_quadmesh *grid(double jitter, unsigned seed)
{
    glpgp_quadmesh *q = calloc(1, sizeof *q);
    const int nv = (N + 1) * (N + 1);
    q->nv = nv;
    q->xy = malloc(sizeof(double) * 2 * (nv + 8));
    q->face_start = malloc(sizeof(int) * (N * N + 8));
    q->face_vert = malloc(sizeof(int) * 4 * (N * N + 8));
    srand(seed);
    for (int j = 0; j <= N; j++)
        for (int i = 0; i <= N; i++) {
            const int v = j * (N + 1) + i, in = i > 0 && i < N && j > 0 && j < N;
            q->xy[2 * v] = i + (in ? jitter * (rand() / (double)RAND_MAX - 0.5) : 0);
            q->xy[2 * v + 1] = j + (in ? jitter * (rand() / (double)RAND_MAX - 0.5) : 0);
        }
    q->nf = N * N;
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            const int f = j * N + i, a = j * (N + 1) + i;
            const int fv[4] = {a, a + 1, a + N + 2, a + N + 1};
            memcpy(q->face_vert + 4 * f, fv, sizeof fv);
            q->face_start[f] = 4 * f;
        }
    q->face_start[q->nf] = 4 * q->nf;
    return q;
}

static int face_of(const glpgp_quadmesh *q, int i, int j)
{
    (void)q;
    return j * N + i;
}

/* Split quad f = (a, b, c, d) through a new center vertex into (a, b, c, v)
 * and (c, d, a, v): v has valence 2 (a doublet). */
static void make_doublet(glpgp_quadmesh *q, int f)
{
    int *fv = q->face_vert + 4 * f;
    const int a = fv[0], b = fv[1], c = fv[2], d = fv[3], v = q->nv++;
    q->xy[2 * v] = 0.25 * (q->xy[2 * a] + q->xy[2 * b] + q->xy[2 * c] + q->xy[2 * d]);
    q->xy[2 * v + 1] = 0.25 * (q->xy[2 * a + 1] + q->xy[2 * b + 1] + q->xy[2 * c + 1] + q->xy[2 * d + 1]);
    const int f1[4] = {a, b, c, v}, f2[4] = {c, d, a, v};
    memcpy(fv, f1, sizeof f1);
    memcpy(q->face_vert + 4 * q->nf, f2, sizeof f2);
    q->nf++;
    q->face_start[q->nf] = 4 * q->nf;
}

/* Rotate the vertical edge u-w between horizontally adjacent quads f1 (left)
 * and f2 (right): the hexagon [w, p1, p2, u, q1, q2] gets the diagonal p1-q1. */
static void rotate_edge(glpgp_quadmesh *q, int f1, int f2, double bend)
{
    int *a = q->face_vert + 4 * f1, *b = q->face_vert + 4 * f2;
    /* f1 = (A, u0, w0, D) with the shared edge u0 = a[1] (bottom) .. w0 = a[2] (top);
     * as a directed edge of f1 it runs a[1] -> a[2]: u = a[1], w = a[2], p1 = a[3], p2 = a[0];
     * f2 = (u, B, C, w): directed w -> u is b[3] -> b[0]: q1 = b[1], q2 = b[2] */
    const int u = a[1], w = a[2], p1 = a[3], p2 = a[0], q1 = b[1], q2 = b[2];
    const int n1[4] = {p1, p2, u, q1}, n2[4] = {q1, q2, w, p1};
    memcpy(a, n1, sizeof n1);
    memcpy(b, n2, sizeof n2);
    /* bend > 0: u down, w up, so that the two new quads are convex (bend 0: flat corners at u, w) */
    q->xy[2 * u + 1] -= bend;
    q->xy[2 * w + 1] += bend;
}

static double min_sj(const glpgp_quadmesh *r)
{
    double sjmin = 1;
    for (int f = 0; f < r->nf; f++) {
        const int *v = r->face_vert + r->face_start[f];
        for (int k = 0; k < 4; k++) {
            const int p = v[(k + 3) % 4], c = v[k], n = v[(k + 1) % 4];
            const double ax = r->xy[2 * n] - r->xy[2 * c], ay = r->xy[2 * n + 1] - r->xy[2 * c + 1];
            const double bx = r->xy[2 * p] - r->xy[2 * c], by = r->xy[2 * p + 1] - r->xy[2 * c + 1];
            sjmin = fmin(sjmin, (ax * by - ay * bx) / (hypot(ax, ay) * hypot(bx, by)));
        }
    }
    return sjmin;
}

static void check_mesh(const glpgp_quadmesh *q, const glpgp_quadmesh *r, const char *what)
{
    /* convex CCW quads, the boundary square kept, area N^2 */
    double area = 0;
    const double sjmin = min_sj(r);
    for (int f = 0; f < r->nf; f++) {
        CHECK(r->face_start[f + 1] - r->face_start[f] == 4);
        const int *v = r->face_vert + r->face_start[f];
        for (int k = 0; k < 4; k++)
            area += 0.5 * (r->xy[2 * v[k]] * r->xy[2 * v[(k + 1) % 4] + 1] -
                           r->xy[2 * v[(k + 1) % 4]] * r->xy[2 * v[k] + 1]);
    }
    printf("%s: %d -> %d faces, area %.12g, min scaled Jacobian %.3f\n", what, q->nf, r->nf, area, sjmin);
    CHECK(fabs(area - N * N) < 1e-9);
    CHECK(sjmin > 0.05);
    /* every boundary vertex of the square is still there, unmoved */
    int found = 0;
    for (int v = 0; v < r->nv; v++) {
        const double x = r->xy[2 * v], y = r->xy[2 * v + 1];
        if (x == 0 || y == 0 || x == N || y == N) found++;
    }
    CHECK(found == 4 * N);
}

static int irregular(const glpgp_quadmesh *q)
{
    glpgp_quads_report qq;
    CHECK_OK(glpgp_quads_quality(q, NULL, 1.0, &qq));
    return qq.irregular;
}

static void free_q(glpgp_quadmesh *q)
{
    glpgp_quadmesh_destroy(&q);
}

int main(void)
{
    glpgp_log_set_callback(NULL, NULL);
    glpgp_quadmesh *q = grid(0.0, 1), *r = NULL;
    CHECK(irregular(q) == 0);
    CHECK_OK(glpgp_quadmesh_cleanup(q, &r));
    CHECK(r == NULL); /* nothing to improve */
    free_q(q);

    /* a doublet */
    q = grid(0.0, 1);
    make_doublet(q, face_of(q, 3, 4));
    CHECK(irregular(q) == 3);
    CHECK_OK(glpgp_quadmesh_cleanup(q, &r));
    CHECK(r != NULL);
    if (r) {
        check_mesh(q, r, "doublet");
        CHECK(r->cleanup.doublets == 1 && r->nf == N * N && r->nv == (N + 1) * (N + 1));
        CHECK(irregular(r) == 0);
        glpgp_quadmesh_destroy(&r);
    }
    free_q(q);

    /* a rotated edge */
    q = grid(0.0, 1);
    rotate_edge(q, face_of(q, 3, 3), face_of(q, 4, 3), 0.0);
    CHECK(irregular(q) == 4);
    CHECK_OK(glpgp_quadmesh_cleanup(q, &r));
    CHECK(r != NULL);
    if (r) {
        check_mesh(q, r, "rotated edge");
        CHECK(irregular(r) == 0);
        CHECK(r->cleanup.rotations >= 1 && r->cleanup.cost_after < r->cleanup.cost_before);
        glpgp_quadmesh_destroy(&r);
    }
    free_q(q);

    /* random defects on jittered grids */
    int used = 0;
    for (unsigned seed = 1; seed <= 30; seed++) {
        q = grid(0.1, seed);
        for (int k = 0; k < 3; k++) { /* rows 1, 3, 5: the defects apart */
            const int i = 1 + rand() % (N - 3), j = 1 + 2 * k;
            /* (a doublet has a corner >= 180 degrees: never a valid input) */
            rotate_edge(q, face_of(q, i, j), face_of(q, i + 1, j), 0.1 + 0.2 * (rand() / (double)RAND_MAX));
        }
        const int irr0 = irregular(q);
        if (min_sj(q) <= 0.05) { /* the defects inverted a jittered quad: not a valid input */
            free_q(q);
            continue;
        }
        used++;
        CHECK_OK(glpgp_quadmesh_cleanup(q, &r));
        if (r) {
            char what[64];
            snprintf(what, sizeof what, "random %u", seed);
            check_mesh(q, r, what);
            const int irr1 = irregular(r);
            printf("  irregular %d -> %d\n", irr0, irr1);
            CHECK(irr1 < irr0);
            CHECK(r->cleanup.cost_after < r->cleanup.cost_before);
            glpgp_quadmesh_destroy(&r);
        } else {
            CHECK(irr0 == 0); /* only a mesh without defect stands (two defects may cancel) */
        }
        free_q(q);
    }

    printf("random: %d valid inputs of 30\n", used);
    CHECK(used >= 10);

    /* a non-quad face: left alone */
    q = grid(0.0, 1);
    q->face_start[q->nf - 1] = 4 * (q->nf - 1);
    q->face_start[q->nf] = 4 * q->nf - 1; /* the last face a triangle */
    CHECK_OK(glpgp_quadmesh_cleanup(q, &r));
    CHECK(r == NULL);
    free_q(q);
    TEST_DONE();
}
