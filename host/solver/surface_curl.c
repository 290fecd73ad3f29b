/* solver/surface_curl.c: the curl correction of a surface's local size
 * (glpgp_surface_size_curl, glpgp/surfsolve.h; Ray et al.'s periodic global
 * parametrization, "curl correction").
 *
 * The oscillators follow the frame (U, V) / h. Where the frame field is not
 * curl-free (on a curved surface a smooth cross field never is: its
 * directions turn with the connection), no seamless grid of constant size
 * h follows it: the phases slip by a period wherever the accumulated curl
 * reaches 2 pi, an iso-line ends there and the quads get a T-junction (a
 * dislocation: a pentagon and a valence-3 vertex). Scaling the frame by
 * e^phi makes it curl-free when
 *     curl(e^phi U) = e^phi (grad phi x U + curl U) = 0, the same for V,
 * i.e. grad phi . V = curl U and grad phi . U = -curl V (U, V orthonormal):
 *     G = (curl U) V - (curl V) U  per triangle,
 * and phi is the least-squares fit of grad phi = G: the cotan Laplacian's
 * Neumann problem K phi = b, b_a = sum_t A_t G_t . grad B_a (consistent:
 * sum_a grad B_a = 0), solved by Jacobi-preconditioned CG on the host.
 * The local size is h(x) e^(-F phi) (F the strength), normalised so that
 * the area in periods (the quad count) is kept, within [1/2, 2].
 *
 * Per triangle, the three corners' representatives are matched to corner
 * 0's (glpgp_coupled_corner_turn) in the triangle's plane; the circulation
 * of the P1 field by the trapezoid rule is exact. Triangles where the
 * matched directions spread over 45 degrees (a singularity's) give G = 0,
 * and so do those within rim_gap of the boundary (the caller's: 2 h): the
 * curl-free frame aligned with a hole's rim is log-polar, its quads
 * shrinking towards the rim by r / h, which a hole a few h across cannot
 * carry (bench/results/surface_curl.md). */
#include "internal.h"

#include "glpgp/surfsolve.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CURL_SPREAD 0.7071067811865476 /* cos 45 degrees: a singular triangle's matched directions */
#define CURL_TOL 1e-8                  /* CG: relative residual */
#define CURL_MAXIT 20000
#define CURL_FACTOR_MAX 2.0            /* the size's factor within [1/2, 2] */

/* Per vertex whether it is within gap of the boundary along the edges
 * (glpgp_surface_grade from the boundary vertices); all 0 when gap <= 0. */
static glpgp_status near_rim(const glpgp_mesh *m, double gap, unsigned char *near)
{
    const int nv = m->nv;
    memset(near, 0, (size_t)nv);
    if (!(gap > 0)) return GLPGP_OK;
    double *d = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)nv + 1, sizeof(double), &d));
    for (int i = 0; i < nv; i++) d[i] = m->surf->twin[m->surf->vstart[i]] < 0 ? 0.0 : gap;
    glpgp_status st = glpgp_surface_grade(m, 1.0, d);
    for (int i = 0; st == GLPGP_OK && i < nv; i++) near[i] = d[i] < gap;
    free(d);
    return st;
}

/* U_a of corner a of t matched to corner 0's, in t's plane (2 values). */
static void matched_u(const glpgp_mesh *m, const double *u, int t, int a, double *out)
{
    double x, y, c[2];
    glpgp_coupled_corner_u(m, u, t, a, c);
    x = c[0];
    y = c[1];
    for (int r = glpgp_coupled_corner_turn(m, u, t, a); r > 0; r--) { /* rot by +90 degrees */
        const double nx = -y;
        y = x;
        x = nx;
    }
    out[0] = x;
    out[1] = y;
}

/* G_t (2 values in t's plane) and the hat gradients gb (6: corner a's at
 * 2a) of triangle t; returns its area. G = 0 on a singular triangle. */
static double triangle_target(const glpgp_mesh *m, const double *u, const unsigned char *near, int t, double *G,
                              double *gb)
{
    const double *p = m->surf->txy + 6 * t;
    double U[3][2], V[3][2];
    for (int a = 0; a < 3; a++) {
        matched_u(m, u, t, a, U[a]);
        V[a][0] = -U[a][1];
        V[a][1] = U[a][0];
    }
    const double area = 0.5 * ((p[2] - p[0]) * (p[5] - p[1]) - (p[4] - p[0]) * (p[3] - p[1]));
    for (int a = 0; a < 3; a++) { /* grad B_a = rot90(x_c - x_b) / 2A */
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        const double ex = p[2 * c] - p[2 * b], ey = p[2 * c + 1] - p[2 * b + 1];
        gb[2 * a] = -ey / (2.0 * area);
        gb[2 * a + 1] = ex / (2.0 * area);
    }
    G[0] = G[1] = 0.0;
    if (near[m->tri[3 * t]] || near[m->tri[3 * t + 1]] || near[m->tri[3 * t + 2]]) return area;
    for (int a = 1; a < 3; a++)
        for (int b = 0; b < a; b++)
            if (U[a][0] * U[b][0] + U[a][1] * U[b][1] < CURL_SPREAD) return area;
    double cu = 0.0, cv = 0.0, mu[2] = {0, 0};
    for (int a = 0; a < 3; a++) {
        const int b = (a + 1) % 3;
        const double dx = p[2 * b] - p[2 * a], dy = p[2 * b + 1] - p[2 * a + 1];
        cu += 0.5 * ((U[a][0] + U[b][0]) * dx + (U[a][1] + U[b][1]) * dy);
        cv += 0.5 * ((V[a][0] + V[b][0]) * dx + (V[a][1] + V[b][1]) * dy);
        mu[0] += U[a][0];
        mu[1] += U[a][1];
    }
    const double l = hypot(mu[0], mu[1]);
    if (!(l > 0) || !(area > 0)) return area;
    mu[0] /= l;
    mu[1] /= l;
    cu /= area;
    cv /= area;
    G[0] = cu * -mu[1] - cv * mu[0]; /* (curl U) V - (curl V) U, V = rot90(U) */
    G[1] = cu * mu[0] - cv * mu[1];
    return area;
}

typedef struct curl_sys {
    int nv, nnz;
    int *rs, *col; /* CSR of K (vertex rows) */
    double *val, *diag, *b;
} curl_sys;

static void curl_sys_free(curl_sys *S)
{
    free(S->rs);
    free(S->col);
    free(S->val);
    free(S->diag);
    free(S->b);
}

/* Insert or add v at (i, j) of the CSR rows (rows' columns kept unique in
 * their slots; rs from the mesh's edges, col filled -1 first). */
static void csr_add(curl_sys *S, int i, int j, double v)
{
    for (int k = S->rs[i]; k < S->rs[i + 1]; k++) {
        if (S->col[k] == j) {
            S->val[k] += v;
            return;
        }
        if (S->col[k] < 0) {
            S->col[k] = j;
            S->val[k] = v;
            return;
        }
    }
}

/* K and b: rows sized by the vertices' triangle counts (at most 2 per
 * triangle besides the diagonal). */
static glpgp_status curl_assemble(const glpgp_mesh *m, const double *u, const unsigned char *near, curl_sys *S)
{
    const int nv = m->nv;
    S->nv = nv;
    GLPGP_CHECK(glpgp_calloc((size_t)nv + 1, sizeof(int), &S->rs));
    for (int t = 0; t < m->nt; t++)
        for (int a = 0; a < 3; a++) S->rs[m->tri[3 * t + a] + 1] += 2;
    for (int i = 0; i < nv; i++) S->rs[i + 1] += S->rs[i] + 1;
    S->nnz = S->rs[nv];
    GLPGP_CHECK(glpgp_malloc((size_t)S->nnz + 1, sizeof(int), &S->col));
    GLPGP_CHECK(glpgp_calloc((size_t)S->nnz + 1, sizeof(double), &S->val));
    GLPGP_CHECK(glpgp_calloc((size_t)nv + 1, sizeof(double), &S->diag));
    GLPGP_CHECK(glpgp_calloc((size_t)nv + 1, sizeof(double), &S->b));
    for (int k = 0; k < S->nnz; k++) S->col[k] = -1;
    for (int t = 0; t < m->nt; t++) {
        double G[2], gb[6];
        const double area = triangle_target(m, u, near, t, G, gb);
        if (!(area > 0)) continue;
        for (int a = 0; a < 3; a++) {
            const int i = m->tri[3 * t + a];
            S->b[i] += area * (G[0] * gb[2 * a] + G[1] * gb[2 * a + 1]);
            for (int c = 0; c < 3; c++)
                csr_add(S, i, m->tri[3 * t + c], area * (gb[2 * a] * gb[2 * c] + gb[2 * a + 1] * gb[2 * c + 1]));
        }
    }
    for (int i = 0; i < nv; i++)
        for (int k = S->rs[i]; k < S->rs[i + 1]; k++)
            if (S->col[k] == i) S->diag[i] = S->val[k];
    return GLPGP_OK;
}

static void csr_mul(const curl_sys *S, const double *x, double *y)
{
    for (int i = 0; i < S->nv; i++) {
        double s = 0.0;
        for (int k = S->rs[i]; k < S->rs[i + 1] && S->col[k] >= 0; k++) s += S->val[k] * x[S->col[k]];
        y[i] = s;
    }
}

/* Jacobi-PCG on the consistent Neumann system K phi = b from phi = 0;
 * returns the iterations. */
static int curl_cg(const curl_sys *S, double *phi, double *work)
{
    const int n = S->nv;
    double *r = work, *z = work + n, *p = work + 2 * n, *q = work + 3 * n;
    double bb = 0.0, rz = 0.0;
    for (int i = 0; i < n; i++) {
        phi[i] = 0.0;
        r[i] = S->b[i];
        z[i] = S->diag[i] > 0 ? r[i] / S->diag[i] : 0.0;
        p[i] = z[i];
        bb += r[i] * r[i];
        rz += r[i] * z[i];
    }
    if (!(bb > 0)) return 0;
    int it = 0;
    for (; it < CURL_MAXIT; it++) {
        csr_mul(S, p, q);
        double pq = 0.0;
        for (int i = 0; i < n; i++) pq += p[i] * q[i];
        if (!(pq > 0)) break;
        const double alpha = rz / pq;
        double rr = 0.0, rz1 = 0.0;
        for (int i = 0; i < n; i++) {
            phi[i] += alpha * p[i];
            r[i] -= alpha * q[i];
            z[i] = S->diag[i] > 0 ? r[i] / S->diag[i] : 0.0;
            rr += r[i] * r[i];
            rz1 += r[i] * z[i];
        }
        if (rr <= CURL_TOL * CURL_TOL * bb) break;
        const double beta = rz1 / rz;
        rz = rz1;
        for (int i = 0; i < n; i++) p[i] = z[i] + beta * p[i];
    }
    return it + 1;
}

glpgp_status glpgp_surface_size_curl(const glpgp_mesh *m, const double *u, double strength, double rim_gap,
                                     double *factor, double *range)
{
    const int nv = m->nv;
    curl_sys S;
    memset(&S, 0, sizeof S);
    double *phi = NULL, *work = NULL, *mass = NULL;
    unsigned char *near = NULL;
    glpgp_status st = GLPGP_OK;
    if (!m->surf || !(strength >= 0.0)) return GLPGP_FAIL(GLPGP_ERR_ARG, "curl correction: a surface and F >= 0");
    const double t0 = glpgp_now();
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv + 1, 1, &near), done);
    GLPGP_CHECK_GOTO(st, near_rim(m, rim_gap, near), done);
    GLPGP_CHECK_GOTO(st, curl_assemble(m, u, near, &S), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv + 1, sizeof(double), &phi), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * nv + 4, sizeof(double), &work), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv + 1, sizeof(double), &mass), done);
    const int it = curl_cg(&S, phi, work);
    glpgp_surface_lumped_mass(m, mass);
    /* f = e^(F phi + c), c keeping sum A / f^2 (the periods' area): the quad count */
    double a0 = 0.0, a1 = 0.0, mean = 0.0;
    for (int i = 0; i < nv; i++) mean += phi[i] / nv;
    for (int i = 0; i < nv; i++) {
        const double e = fmin(fmax(strength * (phi[i] - mean), -log(CURL_FACTOR_MAX)), log(CURL_FACTOR_MAX));
        factor[i] = exp(e);
        a0 += mass[i];
        a1 += mass[i] * factor[i] * factor[i];
    }
    const double c = a1 > 0 ? sqrt(a0 / a1) : 1.0;
    range[0] = HUGE_VAL;
    range[1] = 0.0;
    for (int i = 0; i < nv; i++) {
        factor[i] = fmin(fmax(factor[i] * c, 1.0 / CURL_FACTOR_MAX), CURL_FACTOR_MAX);
        range[0] = fmin(range[0], factor[i]);
        range[1] = fmax(range[1], factor[i]);
    }
    glpgp_log(GLPGP_LOG_DEBUG, "surface: curl correction: %d CG iterations, frame scale %.3f .. %.3f, %.3f s", it,
              range[0], range[1], glpgp_now() - t0);
done:
    curl_sys_free(&S);
    free(phi);
    free(work);
    free(mass);
    free(near);
    return st;
}
