/* test_surface_size.c: the curvature cap of a surface's local size
 * (glpgp_surface_size, solver/surface_size.c) measured as the sagitta of
 * patches, not as the normals' turn per edge:
 *  - noise of amplitude 0.2 d (d = size_chord_depth h, the sagitta the cap
 *    allows) on a plane and on a sphere whose cap is above h gives no cap
 *    (per edge, and at a fixed distance, the noise's normals read as
 *    curvature: on the plane h / 2.6 and h / 1.9);
 *  - a crease between flat faces (the cube's edges) is no curvature (a
 *    patch across it would deviate by up to h / 2);
 *  - on a cylinder the cap is the chord of sagitta d of its radius, within
 *    15% (the sphere's, on the input and refinements: test_surface_refine.c). */
#include "testutil.h"

#include "glpgp/surfsolve.h"
#include "glpgp/util.h"

#include <stdlib.h>
#include <time.h>

/* the noisy models' creases: above 80 degrees (the noise of 0.2 d at 7 - 10
 * mean edges per h tilts neighbouring triangles by up to 50 degrees: at the
 * default 35 it would make creases, another matter than the cap) */
#define NOISE_FEATURE 80.0

/* deterministic noise in [-1, 1] */
static double noise(unsigned *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (double)(*state >> 8) / (double)(1u << 23) - 1.0;
}

/* m's smallest and largest size for h (glpgp_surface_size, auto) with
 * creases above feature_deg; returns the number of feature edges */
static int size_range(const glpgp_mesh *m, double h, double feature_deg, double *smin, double *smax)
{
    glpgp_options o;
    glpgp_options_default(&o);
    o.feature_angle = feature_deg;
    o.size = h;
    glpgp_surface_constraints *con = NULL;
    double *s = malloc(sizeof(double) * 2 * (size_t)m->nv);
    int uniform = 0;
    *smin = HUGE_VAL;
    *smax = 0.0;
    CHECK_OK(glpgp_surface_constraints_create(m, o.feature_angle, &con));
    CHECK_OK(glpgp_surface_size(m, &o, con, h, s, &uniform));
    for (int i = 0; i < m->nv; i++) {
        *smin = fmin(*smin, s[i]);
        *smax = fmax(*smax, s[i]);
    }
    const int nf = con ? con->nfeatures : -1;
    glpgp_surface_constraints_destroy(&con);
    free(s);
    return nf;
}

/* an n x n grid on [0, 1]^2 lifted by z(x, y) (+ amp noise), or wrapped
 * into a cylinder of radius R (0: flat; open at both ends, length 1) */
static glpgp_mesh *grid(int n, double amp, double R)
{
    const int cols = R > 0.0 ? n : n + 1, nv = cols * (n + 1), nt = 2 * n * n;
    double *x = malloc(sizeof(double) * 3 * (size_t)nv);
    int *t = malloc(sizeof(int) * 3 * (size_t)nt), k = 0;
    unsigned st = 12345u;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i < cols; i++) {
            const double u = (double)i / n, v = (double)j / n, z = amp * noise(&st);
            double *p = x + 3 * (j * cols + i);
            if (R > 0.0) {
                const double a = 8.0 * atan(1.0) * u;
                p[0] = (R + z) * cos(a), p[1] = (R + z) * sin(a), p[2] = v;
            } else {
                p[0] = u, p[1] = v, p[2] = z;
            }
        }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const int a = j * cols + i, b = j * cols + (i + 1) % cols, c = a + cols, d = b + cols;
            const int tt[6] = {a, b, d, a, d, c};
            for (int e = 0; e < 6; e++) t[k++] = tt[e];
        }
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_create_surface(nv, x, nt, t, &m));
    free(x);
    free(t);
    return m;
}

static void check_noisy_plane(void)
{
    const double h = 0.2, d = 0.125 * h; /* size_chord_depth's default */
    glpgp_mesh *m = grid(60, 0.2 * d, 0.0);
    if (!m) return;
    double smin, smax;
    const int nf = size_range(m, h, NOISE_FEATURE, &smin, &smax);
    printf("noisy plane (%d x %d, noise +-0.2 d, %.1f mean edges per h, %d feature edges): h(x) in [h / %.3g, h / %.3g]\n",
           60, 60, h / m->mean_edge, nf, h / smax, h / smin);
    CHECK(nf == 0); /* the noise makes no crease */
    CHECK(smin >= 0.999 * h && smax <= 1.001 * h);
    glpgp_mesh_destroy(&m);
}

/* the unit sphere at h = 0.3 (its cap 2 sqrt(2 d - d^2) = 0.54 is above h)
 * with radial noise of 0.2 d */
static void check_noisy_sphere(void)
{
    glpgp_mesh *s = NULL, *m = NULL;
    CHECK_OK(glpgp_mesh_generate("sphere", 12000, &s));
    if (!s) return;
    const double h = 0.3, d = 0.125 * h;
    double *x = malloc(sizeof(double) * 3 * (size_t)s->nv);
    unsigned st = 777u;
    for (int i = 0; i < s->nv; i++) {
        const double *p = s->xyz + 3 * i, r = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        const double f = (1.0 + 0.2 * d * noise(&st)) / r;
        for (int e = 0; e < 3; e++) x[3 * i + e] = f * p[e];
    }
    CHECK_OK(glpgp_mesh_create_surface(s->nv, x, s->nt, s->tri, &m));
    free(x);
    if (m) {
        double smin, smax;
        const int nf = size_range(m, h, NOISE_FEATURE, &smin, &smax);
        printf("noisy unit sphere (%d vertices, noise +-0.2 d, %.1f mean edges per h, %d feature edges): h(x) in [h / "
               "%.3g, h / %.3g]\n",
               m->nv, h / m->mean_edge, nf, h / smax, h / smin);
        CHECK(nf == 0);
        CHECK(smin >= 0.999 * h);
    }
    glpgp_mesh_destroy(&m);
    glpgp_mesh_destroy(&s);
}

/* the cube's creases between flat faces: no cap */
static void check_crease(void)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("cube", 5000, &m));
    if (!m) return;
    const double h = 0.2;
    double smin, smax;
    size_range(m, h, GLPGP_FEATURE_ANGLE_DEFAULT, &smin, &smax);
    printf("cube (%d vertices, %.1f mean edges per h): h(x) in [h / %.3g, h / %.3g]\n", m->nv, h / m->mean_edge,
           h / smax, h / smin);
    CHECK(smin >= 0.999 * h);
    glpgp_mesh_destroy(&m);
}

/* a cylinder of radius 0.3 at h = 0.5: the chord of sagitta d = h / 8,
 * 2 sqrt(2 R d - d^2), at every vertex within 15% (its open ends are
 * boundary loops 1 apart: no spacing cap at this h) */
static void check_cylinder(void)
{
    const double R = 0.3, h = 0.5, d = 0.125 * h, cap = 2.0 * sqrt(2.0 * R * d - d * d);
    glpgp_mesh *m = grid(64, 0.0, R);
    if (!m) return;
    double smin, smax;
    clock_t t0 = clock();
    size_range(m, h, GLPGP_FEATURE_ANGLE_DEFAULT, &smin, &smax);
    printf("cylinder R %.2g at h %.2g: h(x) in [%.4g, %.4g], the chord of sagitta h / 8 %.4g (%.2f s)\n", R, h, smin,
           smax, cap, (double)(clock() - t0) / CLOCKS_PER_SEC);
    CHECK(fabs(smin / cap - 1.0) < 0.15 && fabs(smax / cap - 1.0) < 0.15);
    glpgp_mesh_destroy(&m);
}

int main(void)
{
    check_noisy_plane();
    check_noisy_sphere();
    check_crease();
    check_cylinder();
    TEST_DONE();
}
