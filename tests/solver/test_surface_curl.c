/* test_surface_curl.c: the curl correction of a surface's local size
 * (glpgp_surface_size_curl, solver/surface_curl.c), on an annulus
 * 1 <= r <= 2 tilted in 3D, where it is known: the frame (e_r, e_theta)
 * has curl e_theta = 1 / r, and (e_r, e_theta) / r = (grad log r,
 * grad theta) is curl-free, so the factor must be c / r (the log-polar
 * grid, its size proportional to r):
 *  - U radial and U tangential (the same cross) give f r constant within 2%;
 *  - the factors keep the area in periods (sum A f^2 = sum A);
 *  - triangles within the rim gap do not count: a gap over the whole
 *    annulus gives 1, one of 0.2 a smaller spread;
 *  - a frame that is already curl-free (U constant in the plane) gets 1;
 *  - strength 0 gives 1 everywhere; a planar mesh or F < 0 is refused. */
#include "testutil.h"

#include <string.h>

static void lift(double x, double y, double *p)
{
    const double c = cos(GLPGP_PI / 5.0), s = sin(GLPGP_PI / 5.0);
    p[0] = x - 0.5;
    p[1] = c * y + 0.25;
    p[2] = s * y + 1.0;
}

/* nr x ns cells between radii 1 and 2 */
static glpgp_mesh *annulus(int nr, int ns)
{
    const int nv = (nr + 1) * ns, nt = 2 * nr * ns;
    double *xyz = malloc((size_t)3 * nv * sizeof(double));
    int *tri = malloc((size_t)3 * nt * sizeof(int)), t = 0;
    for (int i = 0; i <= nr; i++)
        for (int j = 0; j < ns; j++) {
            const double r = 1.0 + (double)i / nr, a = 2.0 * GLPGP_PI * (j + 0.5 * (i % 2)) / ns;
            lift(r * cos(a), r * sin(a), xyz + 3 * (i * ns + j));
        }
    for (int i = 0; i < nr; i++)
        for (int j = 0; j < ns; j++) {
            const int a = i * ns + j, b = i * ns + (j + 1) % ns, c = a + ns, d = b + ns;
            const int v[6] = {a, b, d, a, d, c};
            for (int k = 0; k < 6; k++) tri[3 * t + k] = v[k];
            t += 2;
        }
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_create_surface(nv, xyz, nt, tri, &m));
    free(xyz);
    free(tri);
    return m;
}

/* u (2 nv): the in-plane direction (dx, dy) of the annulus's plane at each
 * vertex, or its radial one turned by `turn` radians (dx = dy = 0), in the
 * vertex's frame */
static void frame_field(const glpgp_mesh *m, double turn, double dx, double dy, double *u)
{
    double o[3], px[3], py[3];
    lift(0, 0, o);
    lift(1, 0, px);
    lift(0, 1, py);
    for (int i = 0; i < m->nv; i++) {
        const double *x = m->xyz + 3 * i;
        double loc[2] = {0, 0};
        for (int d = 0; d < 3; d++) {
            loc[0] += (x[d] - o[d]) * (px[d] - o[d]);
            loc[1] += (x[d] - o[d]) * (py[d] - o[d]);
        }
        double a = atan2(loc[1], loc[0]) + turn, dir2[2] = {cos(a), sin(a)};
        if (dx != 0 || dy != 0) dir2[0] = dx, dir2[1] = dy;
        double d3[3];
        for (int d = 0; d < 3; d++) d3[d] = dir2[0] * (px[d] - o[d]) + dir2[1] * (py[d] - o[d]);
        const double *e = m->surf->vtangent + 3 * i, *n = m->surf->vnormal + 3 * i;
        const double f[3] = {n[1] * e[2] - n[2] * e[1], n[2] * e[0] - n[0] * e[2], n[0] * e[1] - n[1] * e[0]};
        const double th = atan2(d3[0] * f[0] + d3[1] * f[1] + d3[2] * f[2], d3[0] * e[0] + d3[1] * e[1] + d3[2] * e[2]);
        u[2 * i] = cos(th);
        u[2 * i + 1] = sin(th);
    }
}

/* max / min of f r over the vertices */
static double spread_fr(const glpgp_mesh *m, const double *f)
{
    double o[3], lo = HUGE_VAL, hi = 0;
    lift(0, 0, o);
    for (int i = 0; i < m->nv; i++) {
        const double *x = m->xyz + 3 * i;
        const double d[3] = {x[0] - o[0], x[1] - o[1], x[2] - o[2]};
        const double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        lo = fmin(lo, f[i] * r);
        hi = fmax(hi, f[i] * r);
    }
    return hi / lo;
}

int main(void)
{
    glpgp_mesh *m = annulus(24, 150);
    const int nv = m->nv;
    double *u = malloc((size_t)2 * nv * sizeof(double)), *f = malloc((size_t)nv * sizeof(double)), range[2];
    double *mass = malloc((size_t)nv * sizeof(double));
    glpgp_surface_lumped_mass(m, mass);
    for (int k = 0; k < 2; k++) { /* U radial, then tangential */
        frame_field(m, k * GLPGP_PI / 2.0, 0, 0, u);
        CHECK_OK(glpgp_surface_size_curl(m, u, 1.0, 0.0, f, range));
        const double s = spread_fr(m, f);
        printf("%s U: f r within %.4f (f %.3f .. %.3f)\n", k ? "tangential" : "radial", s, range[0], range[1]);
        CHECK(s < 1.02);
        CHECK(range[1] / range[0] > 1.9); /* f ~ 1 / r over 1 <= r <= 2 */
        double a0 = 0, a1 = 0;
        for (int i = 0; i < nv; i++) a0 += mass[i], a1 += mass[i] * f[i] * f[i];
        CHECK(fabs(a1 / a0 - 1.0) < 1e-9);
    }
    /* every triangle within the rim gap (the annulus is 1 wide): nothing counts */
    frame_field(m, 0.0, 0, 0, u);
    CHECK_OK(glpgp_surface_size_curl(m, u, 1.0, 0.6, f, range));
    printf("gap 0.6: f %.6f .. %.6f\n", range[0], range[1]);
    CHECK(range[0] > 0.999 && range[1] < 1.001);
    /* a gap of 0.2 leaves the middle: f r still falls with r there, less over the whole */
    CHECK_OK(glpgp_surface_size_curl(m, u, 1.0, 0.2, f, range));
    printf("gap 0.2: f %.3f .. %.3f\n", range[0], range[1]);
    CHECK(range[1] / range[0] > 1.2 && range[1] / range[0] < 1.9);
    frame_field(m, 0.0, 0.6, 0.8, u); /* constant: curl-free already */
    CHECK_OK(glpgp_surface_size_curl(m, u, 1.0, 0.0, f, range));
    printf("constant U: f %.6f .. %.6f\n", range[0], range[1]);
    CHECK(range[0] > 0.999 && range[1] < 1.001);
    frame_field(m, 0.0, 0, 0, u);
    CHECK_OK(glpgp_surface_size_curl(m, u, 0.0, 0.0, f, range));
    CHECK(range[0] == 1.0 && range[1] == 1.0);
    CHECK(glpgp_surface_size_curl(m, u, -1.0, 0.0, f, range) == GLPGP_ERR_ARG);
    glpgp_error_clear();
    /* a planar mesh */
    double xy[6] = {0, 0, 1, 0, 0, 1};
    int t3[3] = {0, 1, 2};
    glpgp_mesh *p = NULL;
    CHECK_OK(glpgp_mesh_create(3, xy, 1, t3, &p));
    CHECK(glpgp_surface_size_curl(p, u, 1.0, 0.0, f, range) == GLPGP_ERR_ARG);
    glpgp_error_clear();
    glpgp_mesh_destroy(&p);
    glpgp_mesh_destroy(&m);
    free(u);
    free(f);
    free(mass);
    TEST_DONE();
}
