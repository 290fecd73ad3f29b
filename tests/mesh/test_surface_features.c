/* test_surface_features.c: sharp-feature edges of surfaces
 * (glpgp_surface_features): a noisy scan's kinks are not creases (a
 * jittered sphere has hundreds of edges above the dihedral limit and no
 * feature), a jittered cube keeps exactly its 12 edges and nothing of the
 * noise on its faces, a coarse cube (two triangles per face) keeps all 12,
 * a crease that fades out inside a sheet is trimmed at its free end only
 * (one pass: not eaten), and a refined surface that keeps its input takes
 * the input's features (the same count doubled as the bisection halves
 * every crease edge). With MESH MAX MIN (tests/CMakeLists.txt): marching
 * tetrahedra of three fused tori, whose faceting kinks bend no more than
 * the faces beside them (test 2b), keep at most MAX of their at least MIN
 * edges above the angle (before test 2b: 40 of 84). */
#include "testutil.h"

#include "glpgp/io.h"

#include <string.h>

#define LIM GLPGP_FEATURE_ANGLE_DEFAULT

/* Candidates (dihedral above LIM) and features of m; flag: 3 nt. */
static int features(const glpgp_mesh *m, unsigned char *flag, int *candidates)
{
    int n = -1, c = 0;
    for (int h = 0; h < 3 * m->nt; h++)
        c += m->surf->twin[h] > h && m->surf->dihedral[h] > LIM * GLPGP_PI / 180.0;
    CHECK_OK(glpgp_surface_features(m, LIM, flag, &n));
    CHECK(glpgp_surface_edges_above(m, LIM) == c);
    if (candidates) *candidates = c;
    return n;
}

static void check_noisy_sphere(void)
{
    glpgp_mesh *m = NULL, *j = NULL;
    CHECK_OK(glpgp_mesh_generate("sphere", 5000, &m));
    if (m) j = tu_jittered_surface(m, 0.3 * m->mean_edge, 1, 12345u);
    unsigned char *fl = j ? malloc((size_t)3 * j->nt) : NULL;
    if (fl) {
        int cand = 0;
        const int n = features(j, fl, &cand);
        printf("sphere, radial jitter 0.3 edges: %d edges above %g degrees, %d features\n", cand, LIM, n);
        CHECK(cand > 100); /* the test can fail: the noise reaches the limit */
        CHECK(n == 0);
    }
    free(fl);
    glpgp_mesh_destroy(&j);
    glpgp_mesh_destroy(&m);
}

/* 1 when x lies on an edge of the cube [-0.5, 0.5]^3 (two coordinates at +-0.5). */
static int on_cube_edge(const double *x)
{
    int k = 0;
    for (int c = 0; c < 3; c++) k += fabs(fabs(x[c]) - 0.5) < 1e-9;
    return k >= 2;
}

static void check_noisy_cube(void)
{
    glpgp_mesh *m = NULL, *j = NULL;
    CHECK_OK(glpgp_mesh_generate("cube", 2000, &m));
    if (m) j = tu_jittered_surface(m, 0.12 * m->mean_edge, 0, 12345u);
    unsigned char *fl = j ? malloc((size_t)3 * j->nt) : NULL;
    if (fl) {
        int cand = 0, off = 0;
        const int n = features(j, fl, &cand), seg = (int)lround(sqrt((m->nv - 2) / 6.0));
        for (int h = 0; h < 3 * j->nt; h++) {
            const int a = m->tri[h], b = m->tri[h - h % 3 + (h % 3 + 1) % 3];
            off += fl[h] && !(on_cube_edge(m->xyz + 3 * a) && on_cube_edge(m->xyz + 3 * b));
        }
        printf("cube, jitter 0.12 edges: %d edges above %g degrees, %d features (%d cube edges), %d off the cube's edges\n",
               cand, LIM, n, 12 * seg, off);
        CHECK(cand > 12 * seg); /* noise on the faces reaches the limit */
        CHECK(n == 12 * seg && off == 0);
    }
    free(fl);
    glpgp_mesh_destroy(&j);
    glpgp_mesh_destroy(&m);
}

/* The unit cube, two triangles per face (outward). */
static void check_coarse_cube(void)
{
    glpgp_mesh *m = tu_cube12();
    unsigned char fl[36];
    if (!m) return;
    const int n = features(m, fl, NULL);
    printf("cube of 12 triangles: %d features\n", n);
    CHECK(n == 12);
    glpgp_mesh_destroy(&m);
}

/* The sheet z = 0.6 |x| (1 + y) on [-1, 1]^2, N x N squares: a crease
 * along x = 0 from the boundary y = 1, its dihedral angle 2 atan(0.6 (1 +
 * y)) falling under the limit at y = -0.47. */
static void check_fading_crease(void)
{
    enum { N = 40 };
    double *x = malloc(sizeof(double) * 3 * (N + 1) * (N + 1));
    int *t = malloc(sizeof(int) * 6 * N * N);
    glpgp_mesh *m = NULL;
    if (!x || !t) goto done;
    for (int j = 0; j <= N; j++)
        for (int i = 0; i <= N; i++) {
            double *p = x + 3 * (j * (N + 1) + i);
            p[0] = -1.0 + 2.0 * i / N;
            p[1] = -1.0 + 2.0 * j / N;
            p[2] = 0.6 * fabs(p[0]) * (1.0 + p[1]);
        }
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            const int a = j * (N + 1) + i, q[6] = {a, a + 1, a + N + 2, a, a + N + 2, a + N + 1};
            memcpy(t + 6 * (j * N + i), q, sizeof q);
        }
    CHECK_OK(glpgp_mesh_create_surface((N + 1) * (N + 1), x, 2 * N * N, t, &m));
    unsigned char *fl = m ? malloc((size_t)3 * m->nt) : NULL;
    if (fl) {
        int cand = 0, off = 0;
        const int n = features(m, fl, &cand);
        for (int h = 0; h < 3 * m->nt; h++) {
            const int a = m->tri[h], b = m->tri[h - h % 3 + (h % 3 + 1) % 3];
            off += fl[h] && (fabs(m->xyz[3 * a]) > 1e-12 || fabs(m->xyz[3 * b]) > 1e-12);
        }
        printf("fading crease: %d candidates, %d features (%d off x = 0)\n", cand, n, off);
        CHECK(cand > 20);
        CHECK(n >= cand - 3 && n < cand && off == 0); /* the free end trimmed by at most CREASE_REACH edges */
        free(fl);
    }
done:
    glpgp_mesh_destroy(&m);
    free(x);
    free(t);
}

/* A refined noisy sphere that keeps its input: the input's features (none),
 * where the refinement's flat pieces alone keep every kink as a crease. A
 * refined cube: its input's crease edges, each halved. */
static void check_refined(const char *what, glpgp_mesh *m, int expect_none)
{
    glpgp_mesh *r = NULL;
    CHECK_OK(glpgp_mesh_refine_surface(m, 0.3 * m->mean_edge, 0, &r, NULL));
    unsigned char *f0 = r ? malloc((size_t)3 * m->nt) : NULL, *f1 = r ? malloc((size_t)3 * r->nt) : NULL;
    if (f0 && f1) {
        const int n0 = features(m, f0, NULL), alone = features(r, f1, NULL);
        CHECK_OK(glpgp_surface_keep_origin(r, m));
        const int n1 = features(r, f1, NULL);
        printf("%s: input %d features, refined alone %d, refined with its input %d\n", what, n0, alone, n1);
        if (expect_none)
            CHECK(n0 == 0 && n1 == 0 && alone > 0);
        else
            CHECK(n1 > n0 && n1 == alone);
        for (int h = 0; h < 3 * r->nt; h++) CHECK(f1[h] == f1[r->surf->twin[h] >= 0 ? r->surf->twin[h] : h]);
    }
    free(f0);
    free(f1);
    glpgp_mesh_destroy(&r);
}

/* A faceted smooth surface read from a file (tests/CMakeLists.txt:
 * marching tetrahedra of three fused tori): at least min_cand edges above
 * the angle, at most max_feat of them features. */
static void check_faceted(const char *path, int max_feat, int min_cand)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_read(path, &m));
    unsigned char *fl = m ? malloc((size_t)3 * m->nt) : NULL;
    if (fl) {
        int cand = 0;
        const int n = features(m, fl, &cand);
        printf("%s: %d edges above %g degrees, %d features\n", path, cand, LIM, n);
        CHECK(cand >= min_cand); /* the test can fail: the faceting reaches the limit */
        CHECK(n <= max_feat);
    }
    free(fl);
    glpgp_mesh_destroy(&m);
}

int main(int argc, char **argv)
{
    if (argc == 4) { /* MESH MAX_FEATURES MIN_CANDIDATES */
        check_faceted(argv[1], atoi(argv[2]), atoi(argv[3]));
        TEST_DONE();
    }
    check_noisy_sphere();
    check_noisy_cube();
    check_coarse_cube();
    check_fading_crease();
    glpgp_mesh *m = NULL, *j = NULL;
    CHECK_OK(glpgp_mesh_generate("sphere", 2000, &m));
    if (m) j = tu_jittered_surface(m, 0.35 * m->mean_edge, 1, 12345u);
    if (j) check_refined("refined noisy sphere", j, 1);
    glpgp_mesh_destroy(&j);
    glpgp_mesh_destroy(&m);
    CHECK_OK(glpgp_mesh_generate("cube", 600, &m));
    if (m) check_refined("refined cube", m, 0);
    glpgp_mesh_destroy(&m);
    TEST_DONE();
}
