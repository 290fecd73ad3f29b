/* test_refine_surface.c: the adaptive refinement of a surface to a target
 * edge length (glpgp_mesh_refine_surface, mesh/refine_surface.c): every edge
 * at most the target afterwards; the same surface (area exactly up to
 * rounding, the vector area and the enclosed volume, so the orientation
 * too; every new point in an old triangle, the old points kept), its Euler
 * characteristic, genus and boundary loops (and their length); the smallest
 * angle at least half the input's (longest-edge bisection's bound); a mesh
 * already fine enough left as it is; a mesh with one coarse region refined
 * only there (a uniform subdivision would split everything); max_triangles
 * respected with the last complete level kept. The per-vertex target
 * (glpgp_mesh_refine_surface_sized): with a target affine in x (the
 * refinement interpolates it linearly along the split edges), every edge at
 * most the target at both its ends; on a strip whose target is small only
 * at one end, the other end's triangles kept and far fewer triangles than
 * the scalar refinement to the small target; a uniform target gives the
 * scalar refinement's mesh bit for bit; non-positive targets rejected. A
 * sliver just over the validation's area floor refines and subdivides (its
 * pieces under the floor are not degenerate). */
#include "testutil.h"

#include <stdlib.h>
#include <string.h>

static double elen(const glpgp_mesh *m, int a, int b)
{
    const double *p = m->xyz + 3 * a, *q = m->xyz + 3 * b;
    return sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

static double longest_edge(const glpgp_mesh *m)
{
    double l = 0.0;
    for (int t = 0; t < m->nt; t++)
        for (int a = 0; a < 3; a++) l = fmax(l, elen(m, m->tri[3 * t + a], m->tri[3 * t + (a + 1) % 3]));
    return l;
}

/* vector area (sum of a x b + b x c + c x a over triangles / 2) and the
 * signed volume (sum of a . (b x c) / 6): both unchanged by splitting a
 * triangle in its own plane, both change sign with a flipped triangle */
static void moments(const glpgp_mesh *m, double va[3], double *vol)
{
    va[0] = va[1] = va[2] = 0.0;
    *vol = 0.0;
    for (int t = 0; t < m->nt; t++) {
        const double *a = m->xyz + 3 * m->tri[3 * t], *b = m->xyz + 3 * m->tri[3 * t + 1],
                     *c = m->xyz + 3 * m->tri[3 * t + 2];
        const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        for (int e = 0; e < 3; e++) va[e] += 0.5 * n[e];
        *vol += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                 a[2] * (b[0] * c[1] - b[1] * c[0])) /
                6.0;
    }
}

static double loops_length(const glpgp_mesh *m)
{
    double s = 0.0;
    for (int l = 0; l < m->nloops; l++) {
        const int a = m->loop_start[l], b = m->loop_start[l + 1];
        for (int k = a; k < b; k++) s += elen(m, m->loop_vertices[k], m->loop_vertices[k + 1 < b ? k + 1 : a]);
    }
    return s;
}

/* every vertex of r beyond m's in one of m's triangles (on its plane,
 * barycentric coordinates >= 0): the same piecewise linear surface */
static int off_old_surface(const glpgp_mesh *m, const glpgp_mesh *r)
{
    int off = 0;
    for (int p = m->nv; p < r->nv; p++) {
        int on = 0;
        const double *x = r->xyz + 3 * p;
        for (int t = 0; t < m->nt && !on; t++) {
            const double *A = m->xyz + 3 * m->tri[3 * t], *B = m->xyz + 3 * m->tri[3 * t + 1],
                         *C = m->xyz + 3 * m->tri[3 * t + 2];
            const double *V[3] = {A, B, C};
            double u[3], v[3], n[3];
            for (int e = 0; e < 3; e++) u[e] = B[e] - A[e], v[e] = C[e] - A[e];
            n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2], n[2] = u[0] * v[1] - u[1] * v[0];
            const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2], ln = sqrt(nn);
            const double h = ((x[0] - A[0]) * n[0] + (x[1] - A[1]) * n[1] + (x[2] - A[2]) * n[2]) / ln;
            if (fabs(h) > 1e-12 * ln) continue;
            on = 1;
            for (int k = 0; k < 3; k++) { /* barycentric of the corner opposite edge (k+1, k+2) */
                const double *P = V[(k + 1) % 3], *Q = V[(k + 2) % 3];
                double a[3], b[3];
                for (int e = 0; e < 3; e++) a[e] = P[e] - x[e], b[e] = Q[e] - x[e];
                const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
                on &= (c[0] * n[0] + c[1] * n[1] + c[2] * n[2]) / nn >= -1e-12;
            }
        }
        off += !on;
    }
    return off;
}

/* r is m refined: the same surface, topology, orientation; edges <= target;
 * angles at least half */
static void check_same_surface(const char *name, const glpgp_mesh *m, const glpgp_mesh *r, double target)
{
    double va0[3], va1[3], vol0, vol1, a0, a1;
    int s0, s1;
    moments(m, va0, &vol0);
    moments(r, va1, &vol1);
    glpgp_mesh_angles(m, 5.0, &a0, &s0);
    glpgp_mesh_angles(r, 5.0, &a1, &s1);
    printf("%s: %d -> %d triangles, longest edge %.4g -> %.4g (target %.4g), mean edge %.4g, min angle %.3g -> %.3g\n",
           name, m->nt, r->nt, longest_edge(m), longest_edge(r), target, r->mean_edge, a0, a1);
    if (target > 0) CHECK(longest_edge(r) <= target);
    CHECK_CLOSE(r->area, m->area, 0.0, 1e-12);
    for (int e = 0; e < 3; e++) CHECK(fabs(va1[e] - va0[e]) <= 1e-12 * m->area);
    CHECK(fabs(vol1 - vol0) <= 1e-12 * fmax(fabs(vol0), m->area));
    CHECK(r->surf->euler == m->surf->euler && r->surf->genus == m->surf->genus && r->nloops == m->nloops);
    CHECK(r->surf->ncomponents == m->surf->ncomponents);
    CHECK_CLOSE(loops_length(r), loops_length(m), 0.0, 1e-12);
    CHECK(memcmp(r->xyz, m->xyz, sizeof(double) * 3 * (size_t)m->nv) == 0); /* old points kept */
    CHECK(off_old_surface(m, r) == 0);
    CHECK(a1 >= 0.5 * a0 - 1e-9);
}

static void check_shape(const char *name, long n, double frac)
{
    glpgp_mesh *m = NULL, *r = NULL;
    CHECK_OK(glpgp_mesh_generate(name, n, &m));
    if (!m) return;
    const double target = frac * longest_edge(m);
    glpgp_surface_refine_info ri;
    CHECK_OK(glpgp_mesh_refine_surface(m, target, 0, &r, &ri));
    CHECK(r != NULL);
    if (r) {
        check_same_surface(name, m, r, target);
        CHECK(ri.splits == r->nv - m->nv && ri.nt == r->nt && ri.nv0 == m->nv && !ri.stopped);
        CHECK(ri.max_edge <= target && ri.max_edge == longest_edge(r));
        /* refined again to the same target: nothing to do */
        glpgp_mesh *r2 = NULL;
        CHECK_OK(glpgp_mesh_refine_surface(r, target, 0, &r2, &ri));
        CHECK(r2 == NULL && ri.splits == 0);
        glpgp_mesh_destroy(&r2);
    }
    glpgp_mesh_destroy(&r);
    glpgp_mesh_destroy(&m);
}

/* A tilted strip (not flat) at the abscissae xs (nx of them, at most 8)
 * and ny rows dy apart (at most 5) */
static glpgp_mesh *strip_mesh(const double *xs, int nx, int ny, double dy)
{
    double xyz[3 * 8 * 5];
    int tri[6 * 7 * 4], nt = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            const double x = xs[i], y = dy * j;
            xyz[3 * (j * nx + i)] = x;
            xyz[3 * (j * nx + i) + 1] = y;
            xyz[3 * (j * nx + i) + 2] = 0.3 * x + 0.2 * y + 0.1 * x * y; /* not flat */
        }
    for (int j = 0; j + 1 < ny; j++)
        for (int i = 0; i + 1 < nx; i++) {
            const int a = j * nx + i, b = a + 1, c = a + nx + 1, d = a + nx;
            const int T[6] = {a, b, c, a, c, d};
            memcpy(tri + 3 * nt, T, sizeof T);
            nt += 2;
        }
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_create_surface(nx * ny, xyz, nt, tri, &m));
    return m;
}

/* A tilted strip, fine for x <= 1 (spacing 1/4) and coarse beyond (x = 2,
 * 3, 4): refined to 1/2, the fine part's triangles are all kept as they are */
static void check_local(void)
{
    const double xs[] = {0, 0.25, 0.5, 0.75, 1, 2, 3, 4};
    glpgp_mesh *m = strip_mesh(xs, 8, 5, 0.25), *r = NULL;
    if (!m) return;
    glpgp_surface_refine_info ri;
    CHECK_OK(glpgp_mesh_refine_surface(m, 0.5, 0, &r, &ri));
    CHECK(r != NULL);
    if (r) {
        check_same_surface("strip", m, r, 0.5);
        int fine0 = 0, kept = 0;
        for (int t = 0; t < m->nt; t++) {
            const int *v = m->tri + 3 * t;
            if (fmax(fmax(m->xyz[3 * v[0]], m->xyz[3 * v[1]]), m->xyz[3 * v[2]]) > 1.0) continue;
            fine0++;
            for (int u = 0; u < r->nt; u++) /* the same triangle, the same corner order up to rotation */
                for (int s = 0; s < 3; s++)
                    kept += r->tri[3 * u] == v[s] && r->tri[3 * u + 1] == v[(s + 1) % 3] &&
                            r->tri[3 * u + 2] == v[(s + 2) % 3];
        }
        printf("strip: %d fine triangles, %d kept\n", fine0, kept);
        CHECK(fine0 == 32 && kept == fine0);
    }
    glpgp_mesh_destroy(&r);
    glpgp_mesh_destroy(&m);
}

/* already fine enough: NULL, nothing split */
static void check_fine(void)
{
    glpgp_mesh *m = NULL, *r = NULL;
    CHECK_OK(glpgp_mesh_generate("torus", 2000, &m));
    if (!m) return;
    glpgp_surface_refine_info ri;
    CHECK_OK(glpgp_mesh_refine_surface(m, longest_edge(m), 0, &r, &ri));
    CHECK(r == NULL && ri.splits == 0 && ri.nt == m->nt && !ri.stopped);
    CHECK(glpgp_mesh_refine_surface(m, 0.0, 0, &r, &ri) == GLPGP_ERR_ARG && r == NULL);
    glpgp_mesh_destroy(&m);
}

/* A sliver the validation accepts (its area 3.5e-14 of the bounding box's
 * diagonal squared, over the 1e-14 floor) refined to a twentieth of its
 * length and subdivided: its pieces are far under the floor, yet they are
 * bisections of an accepted triangle, as thin and smaller; both results
 * exist and keep the area. */
static void check_sliver(void)
{
    const double xyz[12] = {0, 0, 0, 1, 0, 0, 0.5, 1e-13, 0, 0.5, 1, 0};
    const int tri[9] = {0, 1, 2, 0, 2, 3, 2, 1, 3};
    glpgp_mesh *m = NULL, *r = NULL, *d = NULL;
    CHECK_OK(glpgp_mesh_create_surface(4, xyz, 3, tri, &m));
    if (!m) return;
    CHECK_OK(glpgp_mesh_refine_surface(m, 0.05, 0, &r, NULL));
    CHECK(r && r->nt > 100 && fabs(r->area - m->area) < 1e-12);
    CHECK_OK(glpgp_mesh_subdivide_surface(m, &d));
    CHECK(d && d->nt == 12);
    glpgp_mesh_destroy(&d);
    glpgp_mesh_destroy(&r);
    glpgp_mesh_destroy(&m);
}

/* max_triangles: at most that many, the last complete level (a longest
 * edge of target sqrt 2^k), still the same surface */
static void check_limit(void)
{
    glpgp_mesh *m = NULL, *r = NULL;
    CHECK_OK(glpgp_mesh_generate("sphere", 1000, &m));
    if (!m) return;
    const double target = 0.2 * longest_edge(m), maxt = 4.0 * m->nt;
    glpgp_surface_refine_info ri;
    CHECK_OK(glpgp_mesh_refine_surface(m, target, maxt, &r, &ri));
    CHECK(r != NULL && ri.stopped);
    if (r) {
        check_same_surface("sphere (limited)", m, r, 0.0);
        CHECK(r->nt <= maxt && ri.max_edge > target && ri.max_edge < longest_edge(m));
        const double k = 2.0 * log(ri.max_edge / target) / log(2.0); /* levels above the target */
        printf("limited: %d triangles (max %.0f), longest edge target x 2^(%.3g / 2)\n", r->nt, maxt, k);
        CHECK(ri.max_edge <= target * pow(2.0, 0.5 * ceil(k - 1e-9)) * (1 + 1e-12));
    }
    glpgp_mesh_destroy(&r);
    /* below the first level: nothing */
    CHECK_OK(glpgp_mesh_refine_surface(m, target, m->nt + 1.0, &r, &ri));
    CHECK(r == NULL && ri.stopped);
    glpgp_mesh_destroy(&m);
}

/* the strip of check_local at spacing 1 in x (0 .. 5), 0.5 in y (0 .. 1) */
static glpgp_mesh *strip(void)
{
    const double xs[] = {0, 1, 2, 3, 4, 5};
    return strip_mesh(xs, 6, 3, 0.5);
}

/* target affine in position: a + b z on a sphere (small at the bottom) */
static void check_sized_affine(void)
{
    glpgp_mesh *m = NULL, *r = NULL;
    CHECK_OK(glpgp_mesh_generate("sphere", 800, &m));
    if (!m) return;
    const double L = longest_edge(m), a = 0.6 * L, b = 0.45 * L; /* z in [-1, 1]: 0.15 L .. 1.05 L */
    double *t = malloc(sizeof(double) * (size_t)m->nv);
    for (int i = 0; i < m->nv; i++) t[i] = a + b * m->xyz[3 * i + 2];
    glpgp_surface_refine_info ri;
    CHECK_OK(glpgp_mesh_refine_surface_sized(m, t, 0, &r, &ri));
    CHECK(r != NULL && !ri.stopped && ri.ratio <= 1.0 && ri.ratio0 > 1.0);
    if (r) {
        check_same_surface("sphere (sized)", m, r, 0.0);
        double worst = 0.0, top = 0.0, bottom = HUGE_VAL;
        for (int tt = 0; tt < r->nt; tt++)
            for (int k = 0; k < 3; k++) {
                const int i = r->tri[3 * tt + k], j = r->tri[3 * tt + (k + 1) % 3];
                const double l = elen(r, i, j), zi = r->xyz[3 * i + 2], zj = r->xyz[3 * j + 2];
                worst = fmax(worst, l / fmin(a + b * zi, a + b * zj));
                if (zi > 0.8 && zj > 0.8) top = fmax(top, l);
                if (zi < -0.8 && zj < -0.8) bottom = fmin(bottom, l);
            }
        /* graded: edges near the top (target ~ L) longer than all near the bottom */
        printf("sphere (sized): %d -> %d triangles, largest edge / target %.4f, top edge %.3g, bottom edge %.3g\n",
               m->nt, r->nt, worst, top, bottom);
        CHECK(worst <= 1.0 + 1e-9);
        CHECK(top > 0.5 * L && bottom < 0.16 * L);
        /* the scalar refinement to the smallest target: far more triangles */
        glpgp_mesh *u = NULL;
        CHECK_OK(glpgp_mesh_refine_surface(m, a - b, 0, &u, NULL));
        CHECK(u != NULL && r->nt < 0.6 * u->nt);
        if (u) printf("  scalar to the smallest target: %d triangles\n", u->nt);
        glpgp_mesh_destroy(&u);
    }
    glpgp_mesh_destroy(&r);
    free(t);
    glpgp_mesh_destroy(&m);
}

/* target 0.3 at x >= 4, 10 elsewhere: the end x <= 2 untouched */
static void check_sized_local(void)
{
    glpgp_mesh *m = strip(), *r = NULL;
    if (!m) return;
    double t[18];
    for (int i = 0; i < m->nv; i++) t[i] = m->xyz[3 * i] >= 4.0 ? 0.3 : 10.0;
    glpgp_surface_refine_info ri;
    CHECK_OK(glpgp_mesh_refine_surface_sized(m, t, 0, &r, &ri));
    CHECK(r != NULL && ri.min_target == 0.3);
    if (r) {
        check_same_surface("strip (sized)", m, r, 0.0);
        int far0 = 0, kept = 0;
        double lfar = 0.0;
        for (int u = 0; u < m->nt; u++) {
            const int *v = m->tri + 3 * u;
            if (fmax(fmax(m->xyz[3 * v[0]], m->xyz[3 * v[1]]), m->xyz[3 * v[2]]) > 2.0) continue;
            far0++;
            for (int w = 0; w < r->nt; w++)
                for (int k = 0; k < 3; k++)
                    kept += r->tri[3 * w] == v[k] && r->tri[3 * w + 1] == v[(k + 1) % 3] &&
                            r->tri[3 * w + 2] == v[(k + 2) % 3];
        }
        for (int w = 0; w < r->nt; w++)
            for (int k = 0; k < 3; k++) {
                const int i = r->tri[3 * w + k], j = r->tri[3 * w + (k + 1) % 3];
                if (r->xyz[3 * i] >= 4.0 && r->xyz[3 * j] >= 4.0) lfar = fmax(lfar, elen(r, i, j));
            }
        glpgp_mesh *u = NULL;
        CHECK_OK(glpgp_mesh_refine_surface(m, 0.3, 0, &u, NULL));
        printf("strip (sized): %d -> %d triangles (scalar to 0.3: %d), %d of %d far triangles kept, longest edge "
               "at x >= 4: %.3g\n",
               m->nt, r->nt, u ? u->nt : 0, kept, far0, lfar);
        CHECK(far0 == 8 && kept == far0 && lfar <= 0.3 && u && r->nt < u->nt / 2);
        glpgp_mesh_destroy(&u);
    }
    glpgp_mesh_destroy(&r);
    glpgp_mesh_destroy(&m);
}

/* a uniform per-vertex target: the scalar refinement's mesh; bad targets */
static void check_sized_uniform(void)
{
    glpgp_mesh *m = NULL, *r = NULL, *u = NULL;
    CHECK_OK(glpgp_mesh_generate("torus", 800, &m));
    if (!m) return;
    const double target = 0.4 * longest_edge(m);
    double *t = malloc(sizeof(double) * (size_t)m->nv);
    for (int i = 0; i < m->nv; i++) t[i] = target;
    CHECK_OK(glpgp_mesh_refine_surface_sized(m, t, 0, &r, NULL));
    CHECK_OK(glpgp_mesh_refine_surface(m, target, 0, &u, NULL));
    CHECK(r && u && r->nv == u->nv && r->nt == u->nt);
    if (r && u && r->nv == u->nv && r->nt == u->nt)
        CHECK(memcmp(r->tri, u->tri, sizeof(int) * 3 * (size_t)r->nt) == 0 &&
              memcmp(r->xyz, u->xyz, sizeof(double) * 3 * (size_t)r->nv) == 0);
    glpgp_mesh_destroy(&r);
    t[7] = 0.0;
    CHECK(glpgp_mesh_refine_surface_sized(m, t, 0, &r, NULL) == GLPGP_ERR_ARG && r == NULL);
    t[7] = NAN;
    CHECK(glpgp_mesh_refine_surface_sized(m, t, 0, &r, NULL) == GLPGP_ERR_ARG && r == NULL);
    CHECK(glpgp_mesh_refine_surface_sized(m, NULL, 0, &r, NULL) == GLPGP_ERR_ARG && r == NULL);
    free(t);
    glpgp_mesh_destroy(&u);
    glpgp_mesh_destroy(&m);
}

int main(void)
{
    check_shape("sphere", 600, 0.3);
    check_shape("cube", 600, 0.4);
    check_shape("hemisphere", 600, 0.3);
    check_shape("torus", 800, 0.5);
    check_shape("genus2", 1500, 0.6);
    check_local();
    check_fine();
    check_sliver();
    check_limit();
    check_sized_affine();
    check_sized_local();
    check_sized_uniform();
    TEST_DONE();
}
