/* test_surface.c: surface meshes (glpgp/surface.h): the built-in surfaces'
 * topology (chi, genus, boundary loops), the discrete connection's holonomy
 * (sum = 4 pi on the sphere, 0 on the torus and on the developable half
 * cylinder, 2 pi chi minus the boundary turning in general; each triangle's
 * sum of rho congruent to its holonomy), the rotations into the triangles
 * (both edges of a corner agree on a developable surface), vertex vectors
 * and angles (round trip), feature edges of the cube, the midpoint
 * subdivision (the same surface: area, topology, boundary loops, feature
 * edges doubled, edges halved, every new point the midpoint of an old edge),
 * the rejection of bad 3D inputs with one message naming the culprit, and
 * glpgp_surface_fix (zero-area caps flipped away or dropped, needles
 * collapsed; faces flipped back, closed parts outward; a vertex
 * where two closed surfaces or two sheets touch split; what it is not
 * defined on left alone). */
#include "testutil.h"

#include <string.h>

static double principal(double a)
{
    double d = remainder(a, 2.0 * GLPGP_PI);
    return d <= -GLPGP_PI ? d + 2.0 * GLPGP_PI : d;
}

static void check_shape(const char *name, long n, int chi, int genus, int loops, double hol)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate(name, n, &m));
    if (!m) return;
    CHECK(glpgp_mesh_is_surface(m));
    const glpgp_surface *s = m->surf;
    printf("%s: %d vertices, %d triangles, chi %d, genus %d, %d loops, holonomy %.15g\n", name, m->nv, m->nt,
           s->euler, s->genus, m->nloops, glpgp_surface_total_holonomy(m));
    CHECK(s->euler == chi);
    CHECK(s->genus == genus);
    CHECK(m->nloops == loops);
    if (!isnan(hol)) CHECK_CLOSE(glpgp_surface_total_holonomy(m), hol, 1e-9, 0.0);
    /* Gauss-Bonnet: sum Omega = 2 pi chi - sum_boundary (pi - Theta) */
    double turn = 0.0;
    for (int v = 0; v < m->nv; v++)
        if (m->on_boundary[v]) turn += GLPGP_PI - s->angle_sum[v];
    CHECK_CLOSE(glpgp_surface_total_holonomy(m), 2.0 * GLPGP_PI * chi - turn, 1e-9, 0.0);
    /* per triangle: rho sum = Omega mod 2 pi; vertex vectors round trip */
    double worst = 0.0, rt = 0.0;
    for (int t = 0; t < m->nt; t++) {
        const double r = s->conn[3 * t] + s->conn[3 * t + 1] + s->conn[3 * t + 2];
        worst = fmax(worst, fabs(principal(r - s->holonomy[t])));
    }
    CHECK(worst < 1e-12);
    for (int v = 0; v < m->nv; v += 7) {
        for (int k = 0; k < 4; k++) {
            const double a = 0.3 + 1.5 * k;
            double d[3];
            glpgp_surface_vertex_vector(m, v, cos(a), sin(a), d);
            CHECK_CLOSE(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1.0, 1e-12, 0.0);
            if (!m->on_boundary[v]) rt = fmax(rt, fabs(principal(glpgp_surface_vertex_angle(m, v, d) - a)));
        }
    }
    printf("  max |rho sum - Omega| %.3g, vector round trip %.3g\n", worst, rt);
    CHECK(rt < 1e-9);
    glpgp_mesh_destroy(&m);
}

/* each corner's two edges give the same rotation on a developable surface */
static void check_developable(void)
{
    glpgp_mesh *m = NULL, *f = NULL;
    CHECK_OK(glpgp_mesh_generate("halfcyl", 2000, &m));
    CHECK_OK(glpgp_mesh_generate("halfcyl_flat", 2000, &f));
    if (!m || !f) return;
    const glpgp_surface *s = m->surf;
    CHECK(!glpgp_mesh_is_surface(f) && f->nv == m->nv && f->nt == m->nt);
    double worst = 0.0, dt = 0.0;
    for (int v = 0; v < m->nv; v++) worst = fmax(worst, fabs(s->scale[v] - 1.0));
    for (int t = 0; t < m->nt; t++)
        for (int a = 0; a < 3; a++) {
            /* corner coordinates congruent to the planar twin's: edge lengths */
            const int b = (a + 1) % 3, p = f->tri[3 * t + a], q = f->tri[3 * t + b];
            const double *x = s->txy + 6 * t;
            const double l3 = hypot(x[2 * b] - x[2 * a], x[2 * b + 1] - x[2 * a + 1]);
            const double l2 = hypot(f->xy[2 * q] - f->xy[2 * p], f->xy[2 * q + 1] - f->xy[2 * p + 1]);
            dt = fmax(dt, fabs(l3 - l2));
        }
    printf("halfcyl: max |scale - 1| %.3g, max edge length difference to the planar twin %.3g\n", worst, dt);
    CHECK(worst < 1e-12);
    CHECK(dt < 1e-13);
    CHECK_CLOSE(glpgp_surface_total_holonomy(m), 0.0, 1e-12, 0.0);
    glpgp_mesh_destroy(&m);
    glpgp_mesh_destroy(&f);
}

static void check_features(void)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("cube", 600, &m));
    if (!m) return;
    unsigned char *fl = malloc((size_t)3 * m->nt);
    int n = -1;
    CHECK_OK(glpgp_surface_features(m, GLPGP_FEATURE_ANGLE_DEFAULT, fl, &n));
    /* 12 cube edges of n segments each: n = sqrt((nv - 2) / 6) */
    const int seg = (int)lround(sqrt((m->nv - 2) / 6.0));
    printf("cube: %d feature edges (%d segments per cube edge)\n", n, seg);
    CHECK(n == 12 * seg);
    free(fl);
    glpgp_mesh_destroy(&m);
}

static void bad(const char *what, const double *x, int nv, const int *t, int nt, const char *needle)
{
    glpgp_mesh *m = NULL;
    glpgp_error_clear();
    glpgp_status st = glpgp_mesh_create_surface(nv, x, nt, t, &m);
    printf("%s: %s\n", what, glpgp_error_message());
    CHECK(st == GLPGP_ERR_MESH && m == NULL);
    CHECK(strstr(glpgp_error_message(), needle) != NULL);
    glpgp_mesh_destroy(&m);
    glpgp_error_clear();
}

static void check_bad_inputs(void)
{
    /* a tetrahedron (valid), and its variants */
    const double tet[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const int tt[12] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_create_surface(4, tet, 4, tt, &m));
    CHECK(m && m->surf->euler == 2 && m->nloops == 0);
    glpgp_mesh_destroy(&m);
    /* one face flipped */
    const int flip[12] = {0, 2, 1, 0, 3, 1, 1, 2, 3, 0, 3, 2};
    bad("flipped face", tet, 4, flip, 4, "inconsistent orientation");
    /* three triangles on edge 0-1 */
    const double fan[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0.5};
    const int fe[9] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    bad("non-manifold edge", fan, 5, fe, 3, "non-manifold edge (0, 1)");
    /* two triangles touching at vertex 0 only (a bowtie) */
    const double bow[15] = {0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0.2, -1, -1, 0};
    const int bt[6] = {0, 1, 2, 0, 3, 4};
    bad("bowtie", bow, 5, bt, 2, "non-manifold vertex 0");
    /* two tetrahedra sharing a vertex: closed fans touching */
    const double tt2[21] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1};
    const int t2[24] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2, 0, 4, 5, 0, 6, 4, 4, 6, 5, 0, 5, 6};
    bad("two cones at a vertex", tt2, 7, t2, 8, "non-manifold vertex 0");
    /* degenerate: collinear */
    const double col[9] = {0, 0, 0, 1, 1, 1, 2, 2, 2};
    const int ct[3] = {0, 1, 2};
    bad("degenerate", col, 3, ct, 1, "degenerate");
    /* a Moebius strip: 6 quads around a half-twisted loop */
    enum { K = 6 };
    double mx[2 * K * 3];
    int mt[6 * K];
    for (int k = 0; k < K; k++) {
        const double u = 2.0 * GLPGP_PI * k / K;
        for (int s = 0; s < 2; s++) {
            const double w = s ? 0.3 : -0.3;
            double *p = mx + 3 * (2 * k + s);
            p[0] = (1 + w * cos(u / 2)) * cos(u);
            p[1] = (1 + w * cos(u / 2)) * sin(u);
            p[2] = w * sin(u / 2);
        }
    }
    for (int k = 0; k < K; k++) {
        const int a = 2 * k, b = 2 * k + 1;
        int c = 2 * ((k + 1) % K), d = c + 1;
        if (k == K - 1) { /* the half twist: the strip's sides swap */
            const int tmp = c;
            c = d;
            d = tmp;
        }
        mt[6 * k + 0] = a;
        mt[6 * k + 1] = c;
        mt[6 * k + 2] = d;
        mt[6 * k + 3] = a;
        mt[6 * k + 4] = d;
        mt[6 * k + 5] = b;
    }
    bad("Moebius strip", mx, 2 * K, mt, 2 * K, "non-orientable");
}

/* midpoint subdivision: the same piecewise linear surface, edges halved */
static void check_subdivide(const char *name)
{
    glpgp_mesh *m = NULL, *r = NULL;
    CHECK_OK(glpgp_mesh_generate(name, 600, &m));
    if (!m) return;
    CHECK_OK(glpgp_mesh_subdivide_surface(m, &r));
    if (!r) {
        glpgp_mesh_destroy(&m);
        return;
    }
    printf("%s subdivided: %d -> %d vertices, %d -> %d triangles, area %.15g -> %.15g, mean edge %.4g -> %.4g\n",
           name, m->nv, r->nv, m->nt, r->nt, m->area, r->area, m->mean_edge, r->mean_edge);
    CHECK(r->nt == 4 * m->nt && r->nv == m->nv + m->surf->nedges);
    CHECK_CLOSE(r->area, m->area, 1e-12, 0.0);
    CHECK(r->surf->euler == m->surf->euler && r->surf->genus == m->surf->genus && r->nloops == m->nloops);
    CHECK_CLOSE(r->mean_edge, 0.5 * m->mean_edge, 0.35, 0.0); /* halved up to the new edges' lengths */
    CHECK(memcmp(r->xyz, m->xyz, sizeof(double) * 3 * (size_t)m->nv) == 0); /* old points kept */
    /* every new point the midpoint of one of its two old neighbours' edge */
    int off = 0;
    for (int t = 0; t < r->nt; t += 4) { /* the corner triangle (a, ab, ca) of old triangle t / 4 */
        const int *v = m->tri + 3 * (t / 4), *w = r->tri + 3 * t;
        for (int e = 0; e < 3; e++) off += fabs(r->xyz[3 * w[1] + e] - 0.5 * (m->xyz[3 * v[0] + e] + m->xyz[3 * v[1] + e])) > 1e-15;
    }
    CHECK(off == 0);
    unsigned char *f0 = malloc((size_t)3 * m->nt), *f1 = malloc((size_t)3 * r->nt);
    int n0 = -1, n1 = -2;
    if (f0 && f1) {
        CHECK_OK(glpgp_surface_features(r, GLPGP_FEATURE_ANGLE_DEFAULT, f1, &n1));
        CHECK_OK(glpgp_surface_features(m, GLPGP_FEATURE_ANGLE_DEFAULT, f0, &n0));
        CHECK(n1 == 2 * n0);
    }
    free(f0);
    free(f1);
    glpgp_mesh_destroy(&r);
    glpgp_mesh_destroy(&m);
}

/* Six times the volume a closed mesh encloses. */
static double volume6(const double *x, const int *t, int nt)
{
    double v = 0.0;
    for (int k = 0; k < nt; k++) {
        const double *a = x + 3 * t[3 * k], *b = x + 3 * t[3 * k + 1], *c = x + 3 * t[3 * k + 2];
        v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
             a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return v;
}

/* The smallest corner angle of m, radians. */
static double min_angle(const glpgp_mesh *m)
{
    double amin = 4.0;
    for (int t = 0; t < m->nt; t++)
        for (int c = 0; c < 3; c++) {
            const double *a = m->xyz + 3 * m->tri[3 * t + c], *b = m->xyz + 3 * m->tri[3 * t + (c + 1) % 3],
                         *d = m->xyz + 3 * m->tri[3 * t + (c + 2) % 3];
            double u[3], v[3], uu = 0, vv = 0, uv = 0;
            for (int k = 0; k < 3; k++) {
                u[k] = b[k] - a[k];
                v[k] = d[k] - a[k];
                uu += u[k] * u[k];
                vv += v[k] * v[k];
                uv += u[k] * v[k];
            }
            amin = fmin(amin, acos(fmax(-1.0, fmin(1.0, uv / sqrt(uu * vv)))));
        }
    return amin;
}

/* glpgp_surface_fix on nt triangles t (copied) and nv points x (copied):
 * the fixes, then glpgp_mesh_create_surface's verdict; *mo the mesh. */
static glpgp_surface_fixes fix(const double *x, int nv, const int *t, int nt, glpgp_mesh **mo)
{
    glpgp_surface_fixes fx = {-1, -1, -1, -1, -1, -1, -1, -1};
    double *xyz = NULL;
    int *tri = malloc((size_t)3 * nt * sizeof(int));
    *mo = NULL;
    CHECK_OK(glpgp_malloc((size_t)3 * nv, sizeof(double), &xyz));
    if (!xyz || !tri) return fx;
    memcpy(xyz, x, (size_t)3 * nv * sizeof(double));
    memcpy(tri, t, (size_t)3 * nt * sizeof(int));
    CHECK_OK(glpgp_surface_fix(&nv, &xyz, &nt, tri, &fx));
    if (glpgp_mesh_create_surface(nv, xyz, nt, tri, mo) != GLPGP_OK) glpgp_error_clear();
    free(xyz);
    free(tri);
    return fx;
}

static void check_fix(void)
{
    const double tet[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const int tt[12] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    glpgp_mesh *m = NULL;
    /* one face flipped: flipped back, outward */
    const int flip[12] = {0, 2, 1, 0, 3, 1, 1, 2, 3, 0, 3, 2};
    glpgp_surface_fixes fx = fix(tet, 4, flip, 4, &m);
    CHECK(fx.flipped == 1 && fx.pinched == 0 && fx.added == 0);
    CHECK(m && m->surf->euler == 2 && memcmp(m->tri, tt, sizeof tt) == 0);
    glpgp_mesh_destroy(&m);
    /* a face written twice, the same way round or the other: dropped (the
     * pair makes three edges of three triangles, which the validation refuses) */
    const int twice[15] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 1, 3, 0, 3, 2};
    const int back[15] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2, 1, 2, 0};
    fx = fix(tet, 4, twice, 5, &m);
    CHECK(fx.duplicate == 1 && fx.flipped == 0 && m && m->nt == 4 && memcmp(m->tri, tt, sizeof tt) == 0);
    glpgp_mesh_destroy(&m);
    fx = fix(tet, 4, back, 5, &m);
    CHECK(fx.duplicate == 1 && fx.flipped == 0 && m && m->nt == 4 && m->surf->euler == 2);
    glpgp_mesh_destroy(&m);
    /* inside out with one face right: the three others flipped (outward
     * wins over the majority on a closed part) */
    const int inv[12] = {0, 2, 1, 0, 3, 1, 1, 3, 2, 0, 2, 3};
    fx = fix(tet, 4, inv, 4, &m);
    CHECK(fx.flipped == 3);
    CHECK(m && volume6(m->xyz, m->tri, m->nt) > 0.0);
    glpgp_mesh_destroy(&m);
    /* consistent and inside out: left as it is (nothing to repair) */
    const int allinv[12] = {0, 1, 2, 0, 3, 1, 1, 3, 2, 0, 2, 3};
    fx = fix(tet, 4, allinv, 4, &m);
    CHECK(fx.flipped == 0 && m && volume6(m->xyz, m->tri, m->nt) < 0.0);
    glpgp_mesh_destroy(&m);
    /* an open strip of four triangles, one against the others: it is the one flipped */
    const double strip[18] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0.1, 1, 1, 0.2, 2, 1, 0.3};
    const int st4[12] = {0, 1, 4, 0, 4, 3, 1, 5, 4, 1, 2, 5};
    const int st4b[12] = {0, 1, 4, 0, 3, 4, 1, 5, 4, 1, 2, 5};
    fx = fix(strip, 6, st4b, 4, &m);
    CHECK(fx.flipped == 1 && m && memcmp(m->tri, st4, sizeof st4) == 0 && m->nloops == 1);
    glpgp_mesh_destroy(&m);
    /* two tetrahedra sharing a vertex: split, two closed components */
    const double tt2[21] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1};
    const int t2[24] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2, 0, 4, 5, 0, 6, 4, 4, 6, 5, 0, 5, 6};
    fx = fix(tt2, 7, t2, 8, &m);
    CHECK(fx.flipped == 0 && fx.pinched == 1 && fx.added == 1);
    CHECK(m && m->nv == 8 && m->surf->euler == 4 && m->surf->ncomponents == 2);
    CHECK(m && m->xyz[3 * 7] == 0.0 && m->xyz[3 * 7 + 1] == 0.0 && m->xyz[3 * 7 + 2] == 0.0);
    glpgp_mesh_destroy(&m);
    /* a bowtie (two triangles at one vertex): two open sheets */
    const double bow[15] = {0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0.2, -1, -1, 0};
    const int bt[6] = {0, 1, 2, 0, 3, 4};
    fx = fix(bow, 5, bt, 2, &m);
    CHECK(fx.pinched == 1 && fx.added == 1 && m && m->nloops == 2 && m->surf->ncomponents == 2);
    glpgp_mesh_destroy(&m);
    /* a T-junction's zero-area filler (vertex 4 inside edge 0-1): the edge flipped */
    const double capx[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5, 0, 0};
    const int capt[18] = {0, 2, 4, 4, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2, 0, 4, 1};
    fx = fix(capx, 5, capt, 6, &m);
    CHECK(fx.degenerate == 1 && fx.flipped == 0 && m && m->nt == 6 && m->nv == 5 && m->surf->euler == 2);
    CHECK(m && volume6(m->xyz, m->tri, m->nt) > 0.0);
    glpgp_mesh_destroy(&m);
    /* ... with the face across its edge oriented against the others: both repaired */
    const int capf[18] = {0, 2, 4, 4, 2, 1, 0, 3, 1, 1, 2, 3, 0, 3, 2, 0, 4, 1};
    fx = fix(capx, 5, capf, 6, &m);
    CHECK(fx.degenerate == 1 && fx.flipped == 1 && m && m->nt == 6 && m->surf->euler == 2);
    glpgp_mesh_destroy(&m);
    /* the same filler on the boundary (edge 0-1 of nothing else): dropped */
    const double bcx[15] = {0, 0, 0, 2, 0, 0, 2, 1, 0.1, 0, 1, 0.1, 1, 0, 0};
    const int bct[12] = {4, 1, 2, 4, 2, 3, 0, 4, 3, 0, 1, 4};
    fx = fix(bcx, 5, bct, 4, &m);
    CHECK(fx.degenerate == 1 && m && m->nt == 3 && m->nloops == 1 && m->surf->euler == 1);
    glpgp_mesh_destroy(&m);
    /* needles: vertex 4 a hair from vertex 1 (two zero-area triangles): collapsed, the tetrahedron again */
    const double ndx[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1 + 1e-15, 0, 0};
    const int ndt[18] = {0, 2, 1, 0, 1, 3, 4, 2, 3, 1, 4, 3, 1, 2, 4, 0, 3, 2};
    fx = fix(ndx, 5, ndt, 6, &m);
    CHECK(fx.degenerate >= 1 && m && m->nt == 4 && m->nv == 4 && m->surf->euler == 2);
    glpgp_mesh_destroy(&m);
    /* thin, not zero area (marching cubes' two vertices a hair apart): the
     * same needle with vertex 4 1.4e-8 from vertex 1, collapsed; a cap whose
     * vertex is 1.4e-9 off the edge, flipped; an angle of 1e-4 left alone */
    const double ndy[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1e-8, 1e-8};
    fx = fix(ndy, 5, ndt, 6, &m);
    CHECK(fx.degenerate == 0 && fx.thin >= 1 && m && m->nt == 4 && m->nv == 4 && m->surf->euler == 2);
    CHECK(m && volume6(m->xyz, m->tri, m->nt) > 0.0);
    glpgp_mesh_destroy(&m);
    const double capy[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5, -1e-9, -1e-9};
    fx = fix(capy, 5, capt, 6, &m);
    CHECK(fx.degenerate == 0 && fx.thin == 1 && m && m->nt == 6 && m->nv == 5 && m->surf->euler == 2);
    CHECK(m && volume6(m->xyz, m->tri, m->nt) > 0.0 && min_angle(m) > 1e-3);
    glpgp_mesh_destroy(&m);
    const double capz[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5, -1e-4, -1e-4};
    fx = fix(capz, 5, capt, 6, &m);
    CHECK(fx.degenerate == 0 && fx.thin == 0 && m && m->nt == 6 && min_angle(m) < 1e-3);
    glpgp_mesh_destroy(&m);
    /* a tetrahedron and, apart, a flat one (vertex 5 a hair from vertex 4:
     * two needles and two faces on the same three points once collapsed, a
     * pillow that encloses nothing): the flat one dropped whole, with
     * vertex 5 1e-17 away (zero area) and 1e-9 away (thin) */
    for (int k = 0; k < 2; k++) {
        const double d = k ? 1e-9 : 1e-17;
        const double ttd[24] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 3, 0, 0, 3, -d, -d, 3, 1, 0, 3, 0, 1};
        const int tdt[24] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2, 4, 6, 5, 4, 5, 7, 5, 6, 7, 4, 7, 6};
        fx = fix(ttd, 8, tdt, 8, &m);
        CHECK(fx.degenerate + fx.thin >= 1 && m && m->nt == 4 && m->nv == 4 && m->surf->euler == 2);
        glpgp_mesh_destroy(&m);
    }
    /* two tetrahedra sharing edge 0-1 (the second the first turned half a
     * turn about it): the edge separated, its two vertices split, two
     * closed components */
    const double te2[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1};
    const int tb[24] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2, 0, 4, 1, 0, 1, 5, 1, 4, 5, 0, 5, 4};
    fx = fix(te2, 6, tb, 8, &m);
    CHECK(fx.nonmanifold == 1 && fx.nonmanifold_added == 2 && fx.flipped == 0);
    CHECK(m && m->nv == 8 && m->surf->euler == 4 && m->surf->ncomponents == 2 && m->nloops == 0);
    CHECK(m && volume6(m->xyz, m->tri, m->nt) > 0.0);
    glpgp_mesh_destroy(&m);
    /* ... the second one inside out (not a body's inside between the pairs): left alone */
    const int tbi[24] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2, 0, 1, 4, 0, 5, 1, 1, 5, 4, 0, 4, 5};
    fx = fix(te2, 6, tbi, 8, &m);
    CHECK(fx.nonmanifold == 0 && m == NULL);
    /* four sheets on one edge, two along it then two against it: left alone */
    const double fs4[18] = {0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, 0, 1, 0.5, -1, 0, 0.5, 0, -1};
    const int f4[12] = {0, 1, 2, 0, 1, 3, 1, 0, 4, 1, 0, 5};
    fx = fix(fs4, 6, f4, 4, &m);
    CHECK(fx.nonmanifold == 0 && m == NULL);
    /* not defined on: a non-manifold edge of three triangles, an index out of range: left alone, still rejected */
    const double fan[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0.5};
    const int fe[9] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    fx = fix(fan, 5, fe, 3, &m);
    CHECK(fx.flipped == 0 && fx.pinched == 0 && fx.added == 0 && m == NULL);
    const int oor[3] = {0, 1, 7};
    fx = fix(tet, 4, oor, 1, &m);
    CHECK(fx.flipped == 0 && fx.added == 0 && m == NULL);
}

int main(void)
{
    check_shape("sphere", 2000, 2, 0, 0, 4.0 * GLPGP_PI);
    check_shape("torus", 2000, 0, 1, 0, 0.0);
    check_shape("genus2", 2000, -2, 2, 0, -4.0 * GLPGP_PI);
    check_shape("cube", 2000, 2, 0, 0, 4.0 * GLPGP_PI);
    check_shape("hemisphere", 2000, 1, 0, 1, NAN);
    check_shape("halfcyl", 2000, 1, 0, 1, 0.0);
    check_developable();
    check_features();
    check_subdivide("sphere");
    check_subdivide("cube");
    check_subdivide("hemisphere");
    check_bad_inputs();
    check_fix();
    TEST_DONE();
}
