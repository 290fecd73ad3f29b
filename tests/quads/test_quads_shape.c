/* test_quads_shape.c: the last shape pass of the quad pipeline
 * (quads/shape.c, glpgp_quadmesh_shape_pass):
 *  - a flat boundary corner (a quad with two boundary sides on one line, a
 *    triangle with a point on its base) is split with two grid lines: all
 *    quads, valid, the same area and boundary, its worst corner from 0 to
 *    >= 0.3, the irregular vertices not more;
 *  - the optimisation smoothing raises the worst corner of a distorted
 *    grid, never lowers it, keeps the boundary, and slides a boundary
 *    vertex only along a straight side;
 *  - a sharp tip whose quad has a nearly flat corner (a 20-degree wedge
 *    meshed by a 2-wide column whose middle line ends just short of the
 *    tip's triangle) is re-meshed as its triangle's incircle kites: valid,
 *    the same area, the poor quad gone (every quad at or above what the
 *    tip's corner allows it), the tip kept as a corner of one quad;
 *  - a mesh with nothing to do is left as it is, bit for bit. */
#include "glpgp/quads.h"
#include "testutil.h"
#include "../host/quads/repair.h"
#include "../host/quads/geom.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A quad mesh from arrays (all quads). */
static glpgp_quadmesh *qm(const double *xy, int nv, const int *fv, int nf)
{
    glpgp_quadmesh *q = calloc(1, sizeof *q);
    CHECK(q != NULL);
    if (!q) return NULL;
    q->nv = nv;
    q->nf = nf;
    q->xy = malloc(sizeof(double) * 2 * (size_t)nv);
    q->face_vert = malloc(sizeof(int) * 4 * (size_t)nf);
    q->face_start = malloc(sizeof(int) * ((size_t)nf + 1));
    memcpy(q->xy, xy, sizeof(double) * 2 * (size_t)nv);
    memcpy(q->face_vert, fv, sizeof(int) * 4 * (size_t)nf);
    for (int f = 0; f <= nf; f++) q->face_start[f] = 4 * f;
    return q;
}

/* The n x n unit grid's points (interior ones moved by up to jitter / 2 at
 * random) and quads into xy, fv. */
static void unit_grid(int n, double jitter, double *xy, int *fv)
{
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            int v = j * (n + 1) + i, in = i > 0 && i < n && j > 0 && j < n;
            xy[2 * v] = i + (in ? jitter * (tu_rand() - 0.5) : 0);
            xy[2 * v + 1] = j + (in ? jitter * (tu_rand() - 0.5) : 0);
        }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int a = j * (n + 1) + i, f[4] = {a, a + 1, a + n + 2, a + n + 1};
            memcpy(fv + 4 * (j * n + i), f, sizeof f);
        }
}

static double min_sj(const glpgp_quadmesh *q)
{
    double m = INFINITY;
    for (int f = 0; f < q->nf; f++)
        for (int i = 0; i < 4; i++) {
            const double *a = q->xy + 2 * q->face_vert[4 * f + i], *b = q->xy + 2 * q->face_vert[4 * f + (i + 1) % 4],
                         *c = q->xy + 2 * q->face_vert[4 * f + (i + 3) % 4];
            double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - a[0], vy = c[1] - a[1];
            m = fmin(m, (ux * vy - uy * vx) / (hypot(ux, uy) * hypot(vx, vy)));
        }
    return m;
}

/* [0, 3] x [0, 2] with a triangle-shaped quad at the bottom: Q = (1,0),
 * (1.5,0), (2,0), (1.5,1), its corner at (1.5,0) flat. */
static void flat_corner(void)
{
    const double xy[] = {0, 0, 1, 0, 1.5, 0, 2, 0, 3, 0, 0, 1, 1.5, 1, 3, 1, 0, 2, 1.5, 2, 3, 2};
    const int fv[] = {0, 1, 6, 5, 1, 2, 3, 6, 3, 4, 7, 6, 5, 6, 9, 8, 6, 7, 10, 9};
    glpgp_quadmesh *q = qm(xy, 11, fv, 5);
    glpgp_mesh *m = tu_grid_mesh((tu_grid){.nx = 6, .ny = 4, .Lx = 3, .Ly = 2});
    if (!q || !m) return;
    glpgp_quads_report q0, q1;
    CHECK_OK(glpgp_quads_quality(q, m, 1.0, &q0));
    CHECK(fabs(q0.sj_min) < 1e-12); /* the flat corner */
    int tips = 0, flat = 0, moved = 0;
    CHECK_OK(glpgp_quadmesh_shape_pass(q, m, 1.0, &tips, &flat, &moved));
    CHECK_OK(glpgp_quads_quality(q, m, 1.0, &q1));
    printf("flat corner: %d split, %d moved: %d quads, SJ min %.3f -> %.3f, irregular %d -> %d, invalid 0x%x\n", flat,
           moved, q1.quads, q0.sj_min, q1.sj_min, q0.irregular, q1.irregular, q1.invalid);
    CHECK(flat == 1);
    CHECK(q1.invalid == 0 && q1.others == 0);
    CHECK(q1.quads == 5 + 2 + 2); /* Q in 3, one quad cut by each strip */
    CHECK(q1.sj_min >= GLPGP_QUADS_SJ_GOAL);
    CHECK(fabs(q1.area - 6.0) < 1e-12);
    CHECK(q1.irregular <= q0.irregular);
    glpgp_quadmesh_destroy(&q);
    glpgp_mesh_destroy(&m);
}

/* A distorted grid: interior vertices jittered, one boundary vertex of the
 * bottom side (straight) shifted along it. The worst corner rises; the
 * boundary polygon is the same. */
static void optimise(void)
{
    enum { N = 6 };
    double xy[2 * (N + 1) * (N + 1)];
    int fv[4 * N * N];
    unit_grid(N, 0.7, xy, fv);
    xy[2 * 3] = 3.42; /* bottom vertex (3, 0) slid along the side */
    glpgp_quadmesh *q = qm(xy, (N + 1) * (N + 1), fv, N * N);
    glpgp_mesh *m = tu_grid_mesh((tu_grid){.nx = N, .ny = N, .Lx = N, .Ly = N});
    if (!q || !m) return;
    double before = min_sj(q);
    int tips = 0, flat = 0, moved = 0;
    CHECK_OK(glpgp_quadmesh_shape_pass(q, m, 1.0, &tips, &flat, &moved));
    double after = min_sj(q);
    printf("optimise: %d moved, SJ min %.3f -> %.3f, bottom vertex x %.3f\n", moved, before, after, q->xy[6]);
    CHECK(flat == 0 && moved > 0);
    CHECK(after > before + 0.05);
    for (int j = 0; j <= N; j++)
        for (int i = 0; i <= N; i++) {
            int v = j * (N + 1) + i;
            if (i == 0 || i == N) CHECK(q->xy[2 * v] == i); /* the sides stay on their lines */
            if (j == 0 || j == N) CHECK(q->xy[2 * v + 1] == j);
        }
    CHECK(q->xy[0] == 0 && q->xy[1] == 0 && q->xy[2 * N] == N); /* corners stay */
    CHECK(q->xy[6] != 3.42 && q->xy[6] > 2 && q->xy[6] < 4); /* the slid vertex moved, between its neighbours */
    glpgp_quadmesh_destroy(&q);
    glpgp_mesh_destroy(&m);
}

/* Signed area of an all-quad mesh. */
static double quad_area(const glpgp_quadmesh *q)
{
    double a = 0.0;
    for (int f = 0; f < q->nf; f++)
        for (int i = 0; i < 4; i++) {
            const double *p = q->xy + 2 * q->face_vert[4 * f + i], *r = q->xy + 2 * q->face_vert[4 * f + (i + 1) % 4];
            a += 0.5 * (p[0] * r[1] - r[0] * p[1]);
        }
    return a;
}

/* The wedge T = (0, 0), half-angle 10 degrees, cut at x = 3: a 2-wide
 * column (rungs at x = 1, 2, 3 through their middle points) whose tip quad
 * T, L1, M1, R1 has M1 = (1.01, 0) just beyond the rung: its corner there
 * 173.5 degrees, SJ 0.11, where the tip allows sin 20 = 0.34. */
static void sharp_tip(void)
{
    const double t = tan(10.0 * 3.14159265358979323846 / 180.0);
    const double xy[] = {0, 0, 1, -t, 1.01, 0, 1, t, 2, -2 * t, 2, 0, 2, 2 * t, 3, -3 * t, 3, 0, 3, 3 * t};
    const int fv[] = {0, 1, 2, 3, 1, 4, 5, 2, 2, 5, 6, 3, 4, 7, 8, 5, 5, 8, 9, 6};
    int tri[2 * 3 * 5];
    for (int f = 0; f < 5; f++) {
        const int *v = fv + 4 * f, T2[6] = {v[0], v[1], v[2], v[0], v[2], v[3]};
        memcpy(tri + 6 * f, T2, sizeof T2);
    }
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_create(10, xy, 10, tri, &m));
    glpgp_quadmesh *q = qm(xy, 10, fv, 5);
    if (!q || !m) return;
    double area0 = quad_area(q), before = min_sj(q), bound = sin(20.0 * 3.14159265358979323846 / 180.0);
    int tips = 0, flat = 0, moved = 0;
    CHECK_OK(glpgp_quadmesh_shape_pass(q, m, 1.0, &tips, &flat, &moved));
    double after = min_sj(q);
    printf("sharp tip: %d re-meshed, %d quads, SJ min %.3f -> %.3f (the tip allows %.3f)\n", tips, q->nf, before, after,
           bound);
    CHECK(tips == 1 && flat == 0);
    CHECK(fabs(quad_area(q) - area0) < 1e-9 * area0);
    CHECK(before < 0.12 && after > bound - 1e-6);
    int at_tip = 0;
    double away = INFINITY; /* the worst quad away from the tip */
    for (int f = 0; f < q->nf; f++) {
        int has = 0;
        for (int i = 0; i < 4; i++) has += q->xy[2 * q->face_vert[4 * f + i]] == 0 && q->xy[2 * q->face_vert[4 * f + i] + 1] == 0;
        at_tip += has;
        if (!has) away = fmin(away, glpgp_poly_min_sj(q->xy, q->face_vert + 4 * f, 4));
    }
    printf("sharp tip: the worst quad away from the tip %.3f\n", away);
    CHECK(at_tip == 1);
    CHECK(away > 0.8); /* the kites at A and B and the column */
    glpgp_quadmesh_destroy(&q);
    glpgp_mesh_destroy(&m);
}

/* A regular grid: nothing to do, nothing changed. */
static void untouched(void)
{
    enum { N = 4 };
    double xy[2 * (N + 1) * (N + 1)];
    int fv[4 * N * N];
    unit_grid(N, 0.0, xy, fv);
    glpgp_quadmesh *q = qm(xy, (N + 1) * (N + 1), fv, N * N);
    glpgp_mesh *m = tu_grid_mesh((tu_grid){.nx = N, .ny = N, .Lx = N, .Ly = N});
    if (!q || !m) return;
    int tips = 1, flat = 1, moved = 1;
    CHECK_OK(glpgp_quadmesh_shape_pass(q, m, 1.0, &tips, &flat, &moved));
    CHECK(tips == 0 && flat == 0 && moved == 0 && q->nv == (N + 1) * (N + 1) && q->nf == N * N);
    CHECK(memcmp(q->xy, xy, sizeof xy) == 0 && memcmp(q->face_vert, fv, sizeof fv) == 0);
    glpgp_quadmesh_destroy(&q);
    glpgp_mesh_destroy(&m);
}

int main(void)
{
    flat_corner();
    optimise();
    sharp_tip();
    untouched();
    TEST_DONE();
}
