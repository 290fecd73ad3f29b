/* test_surface_rims.c: a surface's boundary crosses at the scale of the mesh
 * to be made (glpgp_surface_constraints_rims, glpgp_surface_rim_turns,
 * glpgp_surface_rim_corners; solver/surface_rims.c), on flat meshes tilted
 * in 3D:
 *  - a disk whose rim zigzags (its vertices alternately 4% in and out: each
 *    turns by about 80 degrees between its edges): the edges' crosses are
 *    up to 45 degrees off the circle's tangent, the ones at the scale
 *    within 1 degree; its turns at the scale are the circle's, no corner
 *    (the extraction's rule: 40 degrees);
 *  - a square: its four corners turn by 90 degrees at the scale and keep
 *    their crosses, the sides' crosses stay the sides' (the chords stop at
 *    the corners);
 *  - scale 0 changes nothing; a negative scale is refused. */
#include "testutil.h"

#include <string.h>

#define RAD2DEG (180.0 / GLPGP_PI)

/* (x, y) in the plane -> 3D: tilted 30 degrees about the x axis, shifted */
static void lift(double x, double y, double *p)
{
    const double c = cos(GLPGP_PI / 6.0), s = sin(GLPGP_PI / 6.0);
    p[0] = x + 0.25;
    p[1] = c * y - 0.5;
    p[2] = s * y + 2.0;
}

/* the cell a b c d (counter-clockwise) as triangles t and t + 1; returns t + 2 */
static int cell(int *tri, int t, int a, int b, int c, int d)
{
    const int v[6] = {a, b, c, a, c, d};
    for (int k = 0; k < 6; k++) tri[3 * t + k] = v[k];
    return t + 2;
}

/* the surface mesh of xyz and tri (both freed) */
static glpgp_mesh *surface(int nv, double *xyz, int nt, int *tri)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_create_surface(nv, xyz, nt, tri, &m));
    free(xyz);
    free(tri);
    return m;
}

/* a disk of nr rings of ns vertices; the rim's vertices alternately
 * (1 + zig) and (1 - zig) from the centre */
static glpgp_mesh *disk(int nr, int ns, double zig)
{
    const int nv = 1 + nr * ns, nt = ns + 2 * ns * (nr - 1);
    double *xyz = malloc((size_t)3 * nv * sizeof(double));
    int *tri = malloc((size_t)3 * nt * sizeof(int)), t = 0;
    lift(0.0, 0.0, xyz);
    for (int i = 1; i <= nr; i++)
        for (int j = 0; j < ns; j++) {
            const double a = 2.0 * GLPGP_PI * j / ns, r = (double)i / nr * (i == nr ? 1.0 + (j % 2 ? -zig : zig) : 1.0);
            lift(r * cos(a), r * sin(a), xyz + 3 * (1 + (i - 1) * ns + j));
        }
    for (int j = 0; j < ns; j++) {
        tri[3 * t] = 0, tri[3 * t + 1] = 1 + j, tri[3 * t + 2] = 1 + (j + 1) % ns;
        t++;
    }
    for (int i = 1; i < nr; i++)
        for (int j = 0; j < ns; j++) {
            const int a = 1 + (i - 1) * ns + j, b = 1 + (i - 1) * ns + (j + 1) % ns;
            t = cell(tri, t, a, a + ns, b + ns, b);
        }
    return surface(nv, xyz, nt, tri);
}

/* the unit square in n x n cells */
static glpgp_mesh *square(int n)
{
    const int nv = (n + 1) * (n + 1), nt = 2 * n * n;
    double *xyz = malloc((size_t)3 * nv * sizeof(double));
    int *tri = malloc((size_t)3 * nt * sizeof(int)), t = 0;
    for (int i = 0; i <= n; i++)
        for (int j = 0; j <= n; j++) lift((double)j / n, (double)i / n, xyz + 3 * (i * (n + 1) + j));
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            const int a = i * (n + 1) + j;
            t = cell(tri, t, a, a + 1, a + n + 2, a + n + 1);
        }
    return surface(nv, xyz, nt, tri);
}

/* the angle (degrees) between vertex v's fixed cross and the cross of
 * direction d (3D, in the plane), read in v's frame (its first axis, the
 * normal: a flat vertex's fan angles are the plane's) */
static double cross_gap(const glpgp_mesh *m, const glpgp_surface_constraints *c, int v, const double *d)
{
    const double *e = m->surf->vtangent + 3 * v, *n = m->surf->vnormal + 3 * v;
    const double f[3] = {n[1] * e[2] - n[2] * e[1], n[2] * e[0] - n[0] * e[2], n[0] * e[1] - n[1] * e[0]};
    const double th = atan2(d[0] * f[0] + d[1] * f[1] + d[2] * f[2], d[0] * e[0] + d[1] * e[1] + d[2] * e[2]);
    const double gap = remainder(atan2(c->w0[2 * v + 1], c->w0[2 * v]) - 4.0 * th, 2.0 * GLPGP_PI);
    return fabs(gap) / 4.0 * RAD2DEG;
}

static glpgp_surface_constraints *constraints(const glpgp_mesh *m, double scale)
{
    glpgp_surface_constraints *c = NULL;
    CHECK_OK(glpgp_surface_constraints_create(m, 30.0, &c));
    if (c) CHECK_OK(glpgp_surface_constraints_rims(m, scale, c));
    return c;
}

/* The zigzag rim against the tangent of its circle. */
static void test_zigzag(void)
{
    glpgp_mesh *m = disk(6, 64, 0.04);
    glpgp_surface_constraints *raw = constraints(m, 0.0), *smooth = constraints(m, 0.3);
    double *turn = malloc((size_t)m->nv * sizeof(double));
    CHECK_OK(glpgp_surface_rim_turns(m, 0.3, turn));
    double gap_raw = 0.0, gap = 0.0, tmax = 0.0, tmin = HUGE_VAL, rawturn = 0.0, o[3], p[3];
    lift(0.0, 0.0, o);
    for (int v = 0; v < m->nv; v++) {
        if (!m->on_boundary[v]) continue;
        CHECK(raw->fixed[v] && smooth->fixed[v]);
        for (int k = 0; k < 3; k++) p[k] = m->xyz[3 * v + k] - o[k];
        /* the tangent: the plane's normal (lift's tilt) x the radius */
        const double nrm[3] = {0.0, -sin(GLPGP_PI / 6.0), cos(GLPGP_PI / 6.0)};
        const double tan3[3] = {nrm[1] * p[2] - nrm[2] * p[1], nrm[2] * p[0] - nrm[0] * p[2],
                                nrm[0] * p[1] - nrm[1] * p[0]};
        gap_raw = fmax(gap_raw, cross_gap(m, raw, v, tan3));
        gap = fmax(gap, cross_gap(m, smooth, v, tan3));
        tmax = fmax(tmax, turn[v]);
        tmin = fmin(tmin, turn[v]);
        rawturn = fmax(rawturn, fabs(m->surf->angle_sum[v] - GLPGP_PI));
    }
    printf("zigzag: edges turn up to %.1f deg; cross off the tangent %.1f deg (edges), %.2f deg (scale); "
           "turn at the scale %.1f .. %.1f deg\n",
           rawturn * RAD2DEG, gap_raw, gap, tmin * RAD2DEG, tmax * RAD2DEG);
    CHECK(rawturn * RAD2DEG > 60.0);
    CHECK(gap_raw > 30.0);
    CHECK(gap < 1.0);
    /* the circle's turn over 0.3 of the zigzag's length (its teeth 1.3 times
     * the circle's arc): about 0.3 / 1.3 radians, 13 degrees; no corner */
    CHECK(tmin * RAD2DEG > 10.0 && tmax * RAD2DEG < 17.0);
    /* no corner at 40 degrees (every tooth turns more between its edges) */
    unsigned char *corner = malloc((size_t)m->nv);
    CHECK_OK(glpgp_surface_rim_corners(m, 0.3, 40.0 / RAD2DEG, corner));
    int nc = 0;
    for (int v = 0; v < m->nv; v++) nc += corner[v];
    CHECK(nc == 0);
    free(corner);
    free(turn);
    glpgp_surface_constraints_destroy(&raw);
    glpgp_surface_constraints_destroy(&smooth);
    glpgp_mesh_destroy(&m);
}

/* The square's corners: a right angle's turn at the scale, crosses along
 * the sides everywhere (the corners' too: the chords stop there). */
static void test_square(void)
{
    glpgp_mesh *m = square(20);
    glpgp_surface_constraints *raw = constraints(m, 0.0), *smooth = constraints(m, 0.3);
    double *turn = malloc((size_t)m->nv * sizeof(double));
    CHECK_OK(glpgp_surface_rim_turns(m, 0.3, turn));
    double gap = 0.0, side = 0.0, o[3], x[3];
    int corners = 0;
    lift(0.0, 0.0, o);
    lift(1.0, 0.0, x);
    for (int k = 0; k < 3; k++) x[k] -= o[k];
    for (int v = 0; v < m->nv; v++) {
        if (!m->on_boundary[v]) continue;
        gap = fmax(gap, fmax(cross_gap(m, smooth, v, x), cross_gap(m, raw, v, x)));
        const int corner = fabs(m->surf->angle_sum[v] - GLPGP_PI) > 1.0;
        /* a right angle between the mean points: 2 atan(7 / 1) - 90 degrees,
         * 73.7 (the middle one is L / 8 inside the corner on both legs) */
        if (corner) {
            corners++;
            CHECK(fabs(turn[v] * RAD2DEG - 73.74) < 0.5);
        } else if (turn[v] >= 0.98 * 73.74 / RAD2DEG) /* the sides turn less, a corner's neighbours too */
            side = turn[v];
    }
    printf("square: %d corners, crosses off the edges' %.2g deg\n", corners, gap);
    CHECK(corners == 4);
    /* the corners at the scale: the square's four, one each */
    unsigned char *corner = malloc((size_t)m->nv);
    CHECK_OK(glpgp_surface_rim_corners(m, 0.3, 40.0 / RAD2DEG, corner));
    int same = 0, nc = 0;
    for (int v = 0; v < m->nv; v++) {
        nc += corner[v];
        same += corner[v] && fabs(m->surf->angle_sum[v] - GLPGP_PI) > 1.0;
    }
    CHECK(nc == 4 && same == 4);
    free(corner);
    CHECK(side == 0.0);
    CHECK(gap < 1e-6);
    free(turn);
    glpgp_surface_constraints_destroy(&raw);
    glpgp_surface_constraints_destroy(&smooth);
    glpgp_mesh_destroy(&m);
}

static void test_args(void)
{
    glpgp_mesh *m = disk(3, 16, 0.04);
    glpgp_surface_constraints *a = constraints(m, 0.0), *b = constraints(m, 0.0);
    CHECK(a && b && memcmp(a->w0, b->w0, (size_t)2 * m->nv * sizeof(double)) == 0);
    CHECK(glpgp_surface_constraints_rims(m, -1.0, a) == GLPGP_ERR_ARG);
    glpgp_surface_constraints_destroy(&a);
    glpgp_surface_constraints_destroy(&b);
    glpgp_mesh_destroy(&m);
}

int main(void)
{
    test_zigzag();
    test_square();
    test_args();
    TEST_DONE();
}
