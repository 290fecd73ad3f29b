/* test_surface_denoise.c: a scan's noise smoothed out of a surface
 * (glpgp_surface_denoise): a sphere with a radial jitter of half an edge
 * loses 99% of its kinks and 95% of its angle defects' spread (the Gauss
 * curvature the cross field integrates) and keeps its radius; a jittered
 * cube ends with exactly its crease edges as features (sharp, no noise
 * ridge beside them) and its corners no farther off, its faces without
 * kinks; an
 * open jittered hemisphere keeps its boundary where it was; a sliver folded
 * over on a clean sphere is unfolded, only its neighbourhood moves, and
 * tetrahedra and a 12-triangle cube are no folds; no vertex moves
 * farther than asked; a clean mesh is not touched. */
#include "testutil.h"

#include <string.h>

#define LIM GLPGP_FEATURE_ANGLE_DEFAULT


static double dist3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* the largest displacement from a to b (same vertices) */
static double largest_move(const glpgp_mesh *a, const glpgp_mesh *b)
{
    double mx = 0.0;
    for (int v = 0; v < a->nv; v++) mx = fmax(mx, dist3(a->xyz + 3 * v, b->xyz + 3 * v));
    return mx;
}

/* the same vertices, triangles and topology */
static void check_same_mesh(const glpgp_mesh *a, const glpgp_mesh *b)
{
    CHECK(a->nv == b->nv && a->nt == b->nt);
    CHECK(memcmp(a->tri, b->tri, sizeof(int) * 3 * (size_t)a->nt) == 0);
    CHECK(a->surf->euler == b->surf->euler && a->nloops == b->nloops);
}

static void check_sphere(void)
{
    glpgp_mesh *m = NULL, *j = NULL, *d = NULL;
    glpgp_surface_denoise_info in;
    CHECK_OK(glpgp_mesh_generate("sphere", 5000, &m));
    if (m) j = tu_jittered_surface(m, 0.5 * m->mean_edge, 1, 4321u);
    if (!j) goto done;
    const double cap = 2.0 * m->mean_edge;
    CHECK_OK(glpgp_surface_denoise(j, LIM, cap, &d, &in));
    CHECK(d != NULL);
    if (!d) goto done;
    check_same_mesh(j, d);
    double r = 0.0, rmax = 0.0;
    for (int v = 0; v < d->nv; v++) {
        const double o[3] = {0, 0, 0}, rv = dist3(d->xyz + 3 * v, o);
        r += rv / d->nv;
        rmax = fmax(rmax, fabs(rv - 1.0));
    }
    printf("sphere, radial jitter 0.5 edges: %d noise edges -> %d, %d vertices moved (largest %.3g edges), angle "
           "defect rms %.4f -> %.4f (clean %.4f), mean radius %.5f, farthest from it %.3g edges\n",
           in.noise_edges, in.noise_edges_after, in.moved, in.max_move / m->mean_edge, glpgp_surface_defect_rms(j), glpgp_surface_defect_rms(d),
           glpgp_surface_defect_rms(m), r, rmax / m->mean_edge);
    CHECK(in.noise_edges > 100); /* the test can fail: the jitter reaches the feature angle */
    CHECK(in.noise_edges_after <= in.noise_edges / 100);
    CHECK(glpgp_surface_defect_rms(d) < 0.05 * glpgp_surface_defect_rms(j));
    CHECK(in.defect_rms == glpgp_surface_defect_rms(j) && in.defect_rms_after == glpgp_surface_defect_rms(d));
    CHECK(fabs(r - 1.0) < 0.01);               /* no shrinking */
    CHECK(rmax < 0.3 * m->mean_edge);          /* nearer the sphere than the jitter put it */
    CHECK(largest_move(j, d) <= cap * (1 + 1e-12) && fabs(largest_move(j, d) - in.max_move) < 1e-12);
    glpgp_mesh_destroy(&d);
    /* a tight cap holds every vertex */
    const double tight = 0.05 * m->mean_edge;
    CHECK_OK(glpgp_surface_denoise(j, LIM, tight, &d, &in));
    if (d) {
        CHECK(in.capped > 0 && largest_move(j, d) <= tight * (1 + 1e-9));
        printf("cap 0.05 edges: %d of %d moved vertices held, largest move %.4g edges\n", in.capped, in.moved,
               largest_move(j, d) / m->mean_edge);
    }
    /* a clean sphere: nothing to do */
    glpgp_mesh_destroy(&d);
    CHECK_OK(glpgp_surface_denoise(m, LIM, cap, &d, &in));
    CHECK(d == NULL && in.noise_edges == 0 && in.moved == 0);
done:
    glpgp_mesh_destroy(&d);
    glpgp_mesh_destroy(&j);
    glpgp_mesh_destroy(&m);
}

/* 1 when x lies on an edge of the cube [-0.5, 0.5]^3 within tol */
static int near_cube_edge(const double *x, double tol)
{
    int k = 0;
    for (int c = 0; c < 3; c++) k += fabs(fabs(x[c]) - 0.5) < tol;
    return k >= 2;
}

static void check_cube(void)
{
    glpgp_mesh *m = NULL, *j = NULL, *d = NULL;
    glpgp_surface_denoise_info in;
    CHECK_OK(glpgp_mesh_generate("cube", 2000, &m));
    if (m) j = tu_jittered_surface(m, 0.2 * m->mean_edge, 0, 4321u);
    if (!j) goto done;
    CHECK_OK(glpgp_surface_denoise(j, LIM, 2.0 * m->mean_edge, &d, &in));
    CHECK(d != NULL);
    if (!d) goto done;
    check_same_mesh(j, d);
    unsigned char *fj = malloc((size_t)3 * j->nt), *fd = malloc((size_t)3 * d->nt);
    int nj = 0, nd = 0, lost = 0;
    double corner_before = 0.0, corner_after = 0.0; /* the corners' distances from the clean cube's */
    const int seg = (int)lround(sqrt((m->nv - 2) / 6.0));
    if (fj && fd) {
        CHECK_OK(glpgp_surface_features(j, LIM, fj, &nj));
        CHECK_OK(glpgp_surface_features(d, LIM, fd, &nd));
        for (int h = 0; h < 3 * m->nt; h++) {
            const int a = m->tri[h], b = m->tri[h - h % 3 + (h % 3 + 1) % 3];
            lost += h < m->surf->twin[h] && near_cube_edge(m->xyz + 3 * a, 1e-9) &&
                    near_cube_edge(m->xyz + 3 * b, 1e-9) && !fd[h];
        }
        for (int v = 0; v < m->nv; v++) { /* the 8 corners: three coordinates at +-0.5 */
            int k = 0;
            for (int c = 0; c < 3; c++) k += fabs(fabs(m->xyz[3 * v + c]) - 0.5) < 1e-9;
            if (k == 3) {
                corner_before = fmax(corner_before, dist3(j->xyz + 3 * v, m->xyz + 3 * v));
                corner_after = fmax(corner_after, dist3(d->xyz + 3 * v, m->xyz + 3 * v));
            }
        }
    }
    printf("cube, jitter 0.2 edges: %d noise edges -> %d, features %d -> %d (%d cube edges, %d lost), corners at "
           "most %.3g -> %.3g edges from the cube's, angle defect rms %.4f -> %.4f\n",
           in.noise_edges, in.noise_edges_after, nj, nd, 12 * seg, lost, corner_before / m->mean_edge,
           corner_after / m->mean_edge, glpgp_surface_defect_rms(j), glpgp_surface_defect_rms(d));
    CHECK(in.noise_edges > 50);
    CHECK(lost == 0 && nd == 12 * seg);     /* the creases kept sharp, no noise ridge left */
    CHECK(corner_after <= corner_before);   /* the corners stay where the faces meet */
    CHECK(in.noise_edges_after < in.noise_edges / 10);
    free(fj);
    free(fd);
done:
    glpgp_mesh_destroy(&d);
    glpgp_mesh_destroy(&j);
    glpgp_mesh_destroy(&m);
}

static void check_hemisphere(void)
{
    glpgp_mesh *m = NULL, *j = NULL, *d = NULL;
    glpgp_surface_denoise_info in;
    CHECK_OK(glpgp_mesh_generate("hemisphere", 4000, &m));
    if (m) j = tu_jittered_surface(m, 0.5 * m->mean_edge, 1, 4321u);
    if (!j) goto done;
    CHECK_OK(glpgp_surface_denoise(j, LIM, 2.0 * m->mean_edge, &d, &in));
    CHECK(d != NULL);
    if (!d) goto done;
    check_same_mesh(j, d);
    int bmoved = 0, nb = 0;
    for (int v = 0; v < j->nv; v++)
        if (j->on_boundary[v]) {
            nb++;
            bmoved += dist3(j->xyz + 3 * v, d->xyz + 3 * v) > 0.0;
        }
    printf("hemisphere, radial jitter 0.5 edges: %d noise edges -> %d, %d vertices moved, %d of %d boundary vertices\n",
           in.noise_edges, in.noise_edges_after, in.moved, bmoved, nb);
    CHECK(in.moved > j->nv / 2 && bmoved == 0 && nb > 0);
    CHECK(in.noise_edges_after < in.noise_edges / 20);
done:
    glpgp_mesh_destroy(&d);
    glpgp_mesh_destroy(&j);
    glpgp_mesh_destroy(&m);
}

/* A clean sphere with one sliver folded over (a vertex moved across the
 * opposite edge of one of its triangles): the fold is found and smoothed
 * out, and only the vertices around it move. */
static void check_fold(void)
{
    glpgp_mesh *m = NULL, *f = NULL, *d = NULL;
    glpgp_surface_denoise_info in;
    CHECK_OK(glpgp_mesh_generate("sphere", 3000, &m));
    if (!m) return;
    double *x = malloc(sizeof(double) * 3 * (size_t)m->nv);
    const int t = m->nt / 2, a = m->tri[3 * t], b = m->tri[3 * t + 1], c = m->tri[3 * t + 2];
    if (x) {
        memcpy(x, m->xyz, sizeof(double) * 3 * (size_t)m->nv);
        for (int k = 0; k < 3; k++) x[3 * c + k] = 0.6 * (x[3 * a + k] + x[3 * b + k]) - 0.2 * x[3 * c + k];
        CHECK_OK(glpgp_mesh_create_surface(m->nv, x, m->nt, m->tri, &f));
    }
    free(x);
    if (f) CHECK_OK(glpgp_surface_denoise(f, LIM, 2.0 * m->mean_edge, &d, &in));
    if (d) {
        const double before = dist3(f->xyz + 3 * c, m->xyz + 3 * c), after = dist3(d->xyz + 3 * c, m->xyz + 3 * c);
        printf("sphere with a fold: %d folds -> %d, %d vertices moved, the folded vertex %.3g -> %.3g edges from "
               "where it was\n", in.folds, in.folds_after, in.moved, before / m->mean_edge, after / m->mean_edge);
        CHECK(in.folds >= 1 && in.folds_after == 0);
        CHECK(in.moved < f->nv / 10 && after < 0.5 * before); /* its neighbourhood only */
    } else {
        CHECK(!"the fold was left as it is");
    }
    glpgp_mesh_destroy(&d);
    glpgp_mesh_destroy(&f);
    glpgp_mesh_destroy(&m);
}

/* the unit cube of 12 triangles: each of its 8 vertices a defect of pi / 2 */
static void check_defect_cube(void)
{
    glpgp_mesh *m = tu_cube12();
    if (m) CHECK_CLOSE(glpgp_surface_defect_rms(m), 0.5 * GLPGP_PI, 1e-12, 0.0);
    glpgp_mesh_destroy(&m);
}

int main(void)
{
    check_defect_cube();
    check_fold();
    check_sphere();
    check_cube();
    check_hemisphere();
    glpgp_mesh *m = NULL, *d = NULL;
    glpgp_surface_denoise_info in;
    CHECK_OK(glpgp_mesh_generate("cube", 600, &m)); /* clean creases: nothing is noise */
    if (m) {
        CHECK_OK(glpgp_surface_denoise(m, LIM, 1.0, &d, &in));
        CHECK(d == NULL && in.noise_edges == 0);
        CHECK(glpgp_surface_denoise(m, LIM, 0.0, &d, &in) == GLPGP_ERR_ARG); /* a cap must be given */
        glpgp_error_clear();
    }
    glpgp_mesh_destroy(&m);
    /* coarse polyhedra are not folds: a corner tetrahedron (its slanted face
     * against all three neighbours, which are at right angles to each
     * other), a regular one, the 12-triangle cube */
    const double xc[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const double xr[] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1};
    const int tt[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    for (int k = 0; k < 3; k++) {
        m = NULL;
        if (k < 2) CHECK_OK(glpgp_mesh_create_surface(4, k ? xr : xc, 4, tt, &m));
        else m = tu_cube12();
        if (!m) continue;
        CHECK_OK(glpgp_surface_denoise(m, LIM, 1.0, &d, &in));
        printf("polyhedron %d: %d noise edges, %d folds\n", k, in.noise_edges, in.folds);
        CHECK(d == NULL && in.folds == 0 && in.noise_edges == 0);
        glpgp_mesh_destroy(&d);
        glpgp_mesh_destroy(&m);
    }
    TEST_DONE();
}
