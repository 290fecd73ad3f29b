/* testutil.h: the one header of the C tests: every public glpgp header, the
 * check macros (a failed check prints file:line and the expression, the test
 * exits 1 at TEST_DONE), a deterministic random generator and the solve ->
 * quads -> quality pipeline of the quad tests. */
#ifndef GLPGP_TESTUTIL_H
#define GLPGP_TESTUTIL_H

#include "glpgp/backends.h"
#include "glpgp/cross.h"
#include "glpgp/image.h"
#include "glpgp/io.h"
#include "glpgp/mesh.h"
#include "glpgp/phase.h"
#include "glpgp/quads.h"
#include "glpgp/result.h"
#include "glpgp/shapes.h"
#include "glpgp/solve.h"
#include "glpgp/status.h"
#include "glpgp/surface.h"
#include "glpgp/surfsolve.h"
#include "glpgp/system.h"
#include "glpgp/util.h"
#include "glpgp/version.h"
#include "glpgp/internal/newton.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static int tu_failures = 0;

#define CHECK(cond)                                                            \
    do {                                                                       \
        if (!(cond)) {                                                         \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
            tu_failures++;                                                     \
        }                                                                      \
    } while (0)

/* |a - b| <= atol + rtol |b| */
#define CHECK_CLOSE(a, b, atol, rtol)                                          \
    do {                                                                       \
        double ca_ = (a), cb_ = (b);                                           \
        if (!(fabs(ca_ - cb_) <= (atol) + (rtol)*fabs(cb_))) {                 \
            fprintf(stderr, "%s:%d: CHECK_CLOSE failed: %s = %.17g vs %s = %.17g\n", \
                    __FILE__, __LINE__, #a, ca_, #b, cb_);                     \
            tu_failures++;                                                     \
        }                                                                      \
    } while (0)

#define CHECK_OK(call)                                                         \
    do {                                                                       \
        glpgp_status st_ = (call);                                             \
        if (st_ != GLPGP_OK) {                                                 \
            fprintf(stderr, "%s:%d: %s failed: %s\n", __FILE__, __LINE__, #call,  \
                    glpgp_error_message());                                    \
            glpgp_error_clear();                                               \
            tu_failures++;                                                     \
        }                                                                      \
    } while (0)

#define TEST_DONE()                                                            \
    do {                                                                       \
        if (tu_failures) {                                                     \
            fprintf(stderr, "%d check(s) failed\n", tu_failures);             \
            return 1;                                                          \
        }                                                                      \
        printf("all checks passed\n");                                         \
        return 0;                                                              \
    } while (0)

/* Deterministic uniform random in [0,1) (xorshift64*). */
static unsigned long long tu_rng = 88172645463325252ULL;
static inline double tu_rand(void)
{
    tu_rng ^= tu_rng >> 12;
    tu_rng ^= tu_rng << 25;
    tu_rng ^= tu_rng >> 27;
    return (double)((tu_rng * 2685821657736338717ULL) >> 11) * (1.0 / 9007199254740992.0);
}

/* The quad tests' pipeline on the reference backend: m solved with o, its
 * quads extracted at the period h and measured into *qq. Returns 1 when a
 * quad mesh came out (then *qq is set), 0 otherwise (a failed step is a
 * failed check). */
static inline int tu_solve_quads(const glpgp_mesh *m, const glpgp_options *o, double h, glpgp_quads_report *qq)
{
    glpgp_backend *be = NULL;
    glpgp_result *r = NULL;
    glpgp_quadmesh *q = NULL;
    CHECK_OK(glpgp_backend_create_reference(&be));
    if (be) CHECK_OK(glpgp_solve(m, be, o, &r));
    if (r) CHECK_OK(glpgp_quads_build(m, r, NULL, &q, &h));
    if (q) CHECK_OK(glpgp_quads_quality(q, m, h, qq));
    const int made = q != NULL;
    glpgp_quadmesh_destroy(&q);
    glpgp_result_destroy(&r);
    glpgp_backend_destroy(&be);
    return made;
}

/* Structured grid mesh of [0, Lx] x [0, Ly] with nx x ny cells, two triangles
 * each: x coordinates through xmap (NULL: uniform; xmap maps [0,1] onto
 * itself), interior vertices moved by up to jitter / 2 cells at random
 * (tu_rand), diagonals all the same way (alternate 0) or alternating
 * (alternate 1). A mesh that cannot be made is a failed check (NULL). */
typedef struct tu_grid {
    int nx, ny;
    double Lx, Ly, jitter;
    double (*xmap)(double);
    int alternate;
} tu_grid;
static inline glpgp_mesh *tu_grid_mesh(tu_grid g)
{
    const int nx = g.nx, ny = g.ny, nv = (nx + 1) * (ny + 1), nt = 2 * nx * ny;
    double *xy = (double *)malloc(sizeof(double) * 2 * nv);
    int *tri = (int *)malloc(sizeof(int) * 3 * nt);
    glpgp_mesh *m = NULL;
    if (!xy || !tri) {
        CHECK(!"tu_grid_mesh: out of memory");
        free(xy), free(tri);
        return NULL;
    }
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= nx; i++) {
            const double s = (double)i / nx;
            double dx = 0, dy = 0;
            if (g.jitter > 0 && i > 0 && i < nx && j > 0 && j < ny) {
                dx = g.jitter * (tu_rand() - 0.5) * g.Lx / nx;
                dy = g.jitter * (tu_rand() - 0.5) * g.Ly / ny;
            }
            xy[2 * (j * (nx + 1) + i)] = g.Lx * (g.xmap ? g.xmap(s) : s) + dx;
            xy[2 * (j * (nx + 1) + i) + 1] = g.Ly * j / ny + dy;
        }
    for (int j = 0, t = 0; j < ny; j++)
        for (int i = 0; i < nx; i++, t += 2) {
            const int v0 = j * (nx + 1) + i, v1 = v0 + 1, v2 = v0 + nx + 1, v3 = v2 + 1;
            const int a[6] = {v0, v1, v3, v0, v3, v2}, c[6] = {v0, v1, v2, v1, v3, v2};
            const int *use = g.alternate && (i + j) % 2 ? c : a;
            for (int k = 0; k < 6; k++) tri[3 * t + k] = use[k];
        }
    CHECK_OK(glpgp_mesh_create(nv, xy, nt, tri, &m));
    free(xy);
    free(tri);
    return m;
}

/* A temporary directory for a test's files (mkdtemp; removed by the test
 * itself or left in TMPDIR) and paths inside it: tu_tmp_path returns one of
 * 8 rotating buffers, so up to 8 paths can be in use at once. */
static char tu_tmp_dir[256];
static inline int tu_tmp_init(const char *name)
{
    const char *base = getenv("TMPDIR");
    snprintf(tu_tmp_dir, sizeof tu_tmp_dir, "%s/glpgp_%s.XXXXXX", base && *base ? base : "/tmp", name);
    if (!mkdtemp(tu_tmp_dir)) {
        perror("mkdtemp");
        return 0;
    }
    return 1;
}
static inline const char *tu_tmp_path(const char *file)
{
    static char buf[8][512];
    static int k;
    k = (k + 1) % 8;
    snprintf(buf[k], sizeof buf[k], "%s/%s", tu_tmp_dir, file);
    return buf[k];
}

/* The unit cube [0, 1]^3 as 12 triangles, two per face, outward (NULL when
 * it fails): a coarse CAD surface whose every edge of the cube is sharp. */
static inline glpgp_mesh *tu_cube12(void)
{
    const double x[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
    const int t[] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                     1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_create_surface(8, x, 12, t, &m));
    return m;
}

/* Surface m's vertices moved by amp x a uniform jitter in [-1, 1) (a
 * linear congruential sequence from seed: the same surface every run),
 * radially from the origin (radial) or in each coordinate, as a new
 * surface (NULL when it fails). A scan's noise for the feature and
 * denoising tests. */
static inline glpgp_mesh *tu_jittered_surface(const glpgp_mesh *m, double amp, int radial, unsigned seed)
{
    double *x = (double *)malloc(sizeof(double) * 3 * (size_t)m->nv);
    glpgp_mesh *out = NULL;
    if (!x) return NULL;
    for (int i = 0; i < m->nv; i++) {
        const double *p = m->xyz + 3 * i;
        double f[3];
        for (int k = 0; k < (radial ? 1 : 3); k++) {
            seed = seed * 1664525u + 1013904223u;
            f[k] = (seed >> 8) / 8388608.0 - 1.0;
        }
        for (int k = 0; k < 3; k++) x[3 * i + k] = radial ? (1.0 + amp * f[0]) * p[k] : p[k] + amp * f[k];
    }
    CHECK_OK(glpgp_mesh_create_surface(m->nv, x, m->nt, m->tri, &out));
    free(x);
    return out;
}

#endif
