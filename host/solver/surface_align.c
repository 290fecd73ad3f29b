/* solver/surface_align.c: the principal-curvature term of a surface's
 * cross field (--cross-align, glpgp_surface_align_source in
 * glpgp/surfsolve.h).
 *
 * The cross field minimises E(w) + P(w) - lambda int Re(conj(w) q)
 * (Knoeppel, Crane, Pinkall, Schroeder 2013, "curvature alignment"): q =
 * s^2, s = (a - c) / 2 + i b the trace-free part of the second fundamental
 * form II = [a b; b c], so that q = ((k1 - k2) / 2)^2 exp(4 i theta1) is
 * the cross of the principal directions weighted by the squared
 * anisotropy (0 at an umbilic: a sphere, a plane). The term is linear in
 * w: the energy's Hessian is unchanged, its gradient gains -b with b_i =
 * lambda M_i q_i (the lumped mass |t| / 3 of i's triangles). Both E and the
 * term are invariant under scaling the surface (1/length^2 times an area):
 * lambda is a pure number.
 *
 * II of a triangle: the least-squares fit of II e = dn along its three
 * edges e (dn: the difference of the vertex normals, both projected into
 * the triangle's plane; Rusinkiewicz 2004). Per vertex, s and the mean
 * curvature H are the area-weighted means of its triangles' (s turned into
 * the vertex's frame by exp(-2 i phi) of the corner's rotation), so a
 * sliver's noisy fit weighs little, and triangles with a boundary vertex
 * do not count (that vertex's normal is its partial fan's: on a sphere
 * with round holes their fits read an anisotropy above 0.5 that is not
 * there); q_i = s_i^2 gated by the anisotropy
 * (ANISO_LO below). A refined surface's triangles take s and H from its
 * input's vertex means (interpolated at their centroids in the input
 * triangle's plane), then averaged the same way: bisection adds flat
 * triangles whose normals say nothing new, and a refined vertex inside an
 * input triangle would see one input fit only. */
#include "internal.h"

#include "glpgp/surfsolve.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A vertex whose anisotropy |k1 - k2| / (2 max(|k1|, |k2|)) (0 at an
 * umbilic, 1/2 on a cylinder, 1 at a minimal saddle) is below ANISO_LO has
 * no principal direction to follow: q = 0 there, 1 from ANISO_HI on
 * (smoothstep between). The estimate's own noise on a sphere stays below
 * 0.2 (test_surface_align: q = 0 there, refined or not); a torus of radii 1 and 0.4 is at
 * 0.36 or more everywhere. So a surface that bends the same way in every
 * direction gets b = 0, and its field is the smoothest one exactly. */
#define ANISO_LO 0.2
#define ANISO_HI 0.35

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* The trace-free part s (2 doubles, a 2-fold quantity) of triangle t's II
 * in t's frame, and its mean curvature *H. */
static void triangle_shape(const glpgp_mesh *m, int t, double *sv, double *H)
{
    const glpgp_surface *s = m->surf;
    const double *E1 = s->tframe + 9 * (size_t)t, *E2 = E1 + 3;
    /* normal equations of [ex ey 0; 0 ex ey] (a b c)' = (nx ny)' over the edges */
    double N[3][3] = {{0}}, r[3] = {0};
    for (int k = 0; k < 3; k++) {
        const int i = m->tri[3 * t + k], j = m->tri[3 * t + (k + 1) % 3];
        double e[3], dn[3];
        for (int d = 0; d < 3; d++) {
            e[d] = m->xyz[3 * (size_t)j + d] - m->xyz[3 * (size_t)i + d];
            dn[d] = s->vnormal[3 * (size_t)j + d] - s->vnormal[3 * (size_t)i + d];
        }
        const double ex = dot3(e, E1), ey = dot3(e, E2), nx = dot3(dn, E1), ny = dot3(dn, E2);
        N[0][0] += ex * ex;
        N[0][1] += ex * ey;
        N[1][1] += ex * ex + ey * ey;
        N[1][2] += ex * ey;
        N[2][2] += ey * ey;
        r[0] += ex * nx;
        r[1] += ey * nx + ex * ny;
        r[2] += ey * ny;
    }
    N[1][0] = N[0][1];
    N[2][1] = N[1][2];
    /* Cramer's rule (N is symmetric positive definite for a non-degenerate triangle) */
    const double det = N[0][0] * (N[1][1] * N[2][2] - N[1][2] * N[2][1]) - N[0][1] * (N[1][0] * N[2][2] - N[1][2] * N[2][0]) +
                       N[0][2] * (N[1][0] * N[2][1] - N[1][1] * N[2][0]);
    sv[0] = sv[1] = *H = 0.0;
    if (!(fabs(det) > 0.0) || !isfinite(det)) return;
    double x[3];
    for (int k = 0; k < 3; k++) {
        double M[3][3];
        memcpy(M, N, sizeof M);
        for (int l = 0; l < 3; l++) M[l][k] = r[l];
        x[k] = (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])) / det;
    }
    sv[0] = 0.5 * (x[0] - x[2]);
    sv[1] = x[1];
    *H = 0.5 * (x[0] + x[2]);
}

/* s and H of triangle t of a refined surface from its input's vertex means
 * vin (4 per input vertex: s in the vertex's frame, H, area): their P1
 * interpolant at t's centroid in input triangle T's plane, s turned into
 * t's frame */
static void origin_shape(const glpgp_mesh *m, const double *vin, int t, double *sv, double *H)
{
    const glpgp_surface *s = m->surf;
    const glpgp_mesh *mi = s->origin;
    const int T = s->otri[t];
    double S[2] = {0.0, 0.0};
    *H = 0.0;
    for (int k = 0; k < 3; k++) {
        const double lam = (s->obary[9 * (size_t)t + k] + s->obary[9 * (size_t)t + 3 + k] +
                            s->obary[9 * (size_t)t + 6 + k]) / 3.0;
        const double *p = vin + 4 * (size_t)mi->tri[3 * T + k];
        if (!(p[3] > 0.0)) continue;
        double z[2] = {p[0] / p[3], p[1] / p[3]};
        glpgp_turn(z, 2.0 * mi->surf->rot[3 * T + k]); /* vertex frame -> T's */
        S[0] += lam * z[0];
        S[1] += lam * z[1];
        *H += lam * p[2] / p[3];
    }
    /* t's x axis at angle delta in T's plane: an angle a in T's frame is a - delta in t's */
    glpgp_turn(S, -2.0 * glpgp_plane_angle(mi->surf, T, s->tframe + 9 * (size_t)t));
    sv[0] = S[0];
    sv[1] = S[1];
}

/* acc (4 nv) <- per vertex of m the area-weighted sums of its triangles' s
 * (turned into the vertex's frame), H and the area, over the triangles
 * without a boundary vertex; a triangle's s and H its own fit, or (vin
 * given: m refined from m->surf->origin, whose vertex means vin are) the
 * input's vertex means interpolated */
static void vertex_means(const glpgp_mesh *m, const double *vin, double *acc)
{
    const glpgp_surface *s = m->surf;
    memset(acc, 0, (size_t)4 * m->nv * sizeof(double));
    for (int t = 0; t < m->nt; t++) {
        const int *v = m->tri + 3 * (size_t)t;
        if (m->on_boundary[v[0]] || m->on_boundary[v[1]] || m->on_boundary[v[2]]) continue;
        double sv[2], H;
        if (vin)
            origin_shape(m, vin, t, sv, &H);
        else
            triangle_shape(m, t, sv, &H);
        const double area = 0.5 * s->txy[6 * (size_t)t + 2] * s->txy[6 * (size_t)t + 5];
        for (int a = 0; a < 3; a++) {
            const int c = 3 * t + a;
            double z[2] = {sv[0], sv[1]};
            glpgp_turn(z, -2.0 * s->rot[c]); /* t's frame -> the vertex's */
            double *p = acc + 4 * (size_t)v[a];
            p[0] += area * z[0];
            p[1] += area * z[1];
            p[2] += area * H;
            p[3] += area;
        }
    }
}

/* the gate's weight of anisotropy a (smoothstep from ANISO_LO to ANISO_HI) */
static double gate(double a)
{
    const double g = (a - ANISO_LO) / (ANISO_HI - ANISO_LO);
    return g <= 0.0 ? 0.0 : g >= 1.0 ? 1.0 : g * g * (3.0 - 2.0 * g);
}

glpgp_status glpgp_surface_align_source(const glpgp_mesh *m, double lambda, const unsigned char *fixed, double *b,
                                        double *stats)
{
    if (!m->surf) return GLPGP_FAIL(GLPGP_ERR_ARG, "curvature alignment of a planar mesh");
    if (!(lambda >= 0.0) || !isfinite(lambda))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "curvature alignment: the weight must be finite and >= 0 (got %g)", lambda);
    const glpgp_surface *s = m->surf;
    const glpgp_mesh *mi = s->origin;
    const int from_input = mi && mi->surf && s->otri && s->obary;
    double *acc = NULL, *vin = NULL; /* per vertex: s (2), H, area */
    GLPGP_CHECK(glpgp_malloc((size_t)4 * m->nv, sizeof(double), &acc));
    if (from_input) {
        for (int t = 0; t < m->nt; t++)
            if (s->otri[t] < 0 || s->otri[t] >= mi->nt) {
                free(acc);
                return GLPGP_FAIL(GLPGP_ERR_ARG, "curvature alignment: triangle %d's origin %d is not an input "
                                                 "triangle", t, s->otri[t]);
            }
        const glpgp_status st = glpgp_malloc((size_t)4 * mi->nv, sizeof(double), &vin);
        if (st != GLPGP_OK) {
            free(acc);
            return st;
        }
        vertex_means(mi, NULL, vin);
    }
    vertex_means(m, vin, acc);
    free(vin);
    double mx = 0.0, on = 0.0, all = 0.0;
    for (int i = 0; i < m->nv; i++) {
        const double *p = acc + 4 * (size_t)i, A = p[3];
        b[2 * (size_t)i] = b[2 * (size_t)i + 1] = 0.0;
        if (!(A > 0.0)) continue;
        const double sr = p[0] / A, si = p[1] / A, sa = hypot(sr, si), H = fabs(p[2] / A);
        const double wt = sa > 0.0 ? gate(sa / (H + sa)) : 0.0;
        all += A;
        if (wt > 0.0) on += A;
        mx = fmax(mx, wt * sa * sa);
        /* b_i = lambda (A / 3) q_i, q_i = wt s_i^2 */
        b[2 * (size_t)i] = lambda * A / 3.0 * wt * (sr * sr - si * si);
        b[2 * (size_t)i + 1] = lambda * A / 3.0 * wt * 2.0 * sr * si;
    }
    free(acc);
    if (fixed)
        for (int i = 0; i < m->nv; i++)
            if (fixed[i]) b[2 * (size_t)i] = b[2 * (size_t)i + 1] = 0.0;
    if (stats) {
        stats[0] = mx;
        stats[1] = all > 0.0 ? on / all : 0.0;
    }
    return GLPGP_OK;
}
