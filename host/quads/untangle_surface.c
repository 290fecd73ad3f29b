/* quads/untangle_surface.c: the scaled Jacobian of a quad in its own plane
 * on a 3D surface (glpgp_qs_quad_sj, glpgp_qs_worst_sj) and the untangling
 * of quads lifted onto the surface (glpgp_qs_untangle: Laplacian sweeps of
 * their new points, each moved back onto the surface), the local repair's
 * (repair_surface.c) for a lift that tangled a few corners. */
#include "quads_surface.h"
#include "vec3.h"

#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

double glpgp_qs_quad_sj(const glpgp_qs_proj *P, const double *const p[4])
{
    double N[3] = {0, 0, 0}, c[3] = {0, 0, 0}, x[3];
    for (int i = 0; i < 4; i++) {
        const double *a = p[i], *b = p[(i + 1) % 4];
        cross3(a, b, x);
        for (int d = 0; d < 3; d++) {
            N[d] += x[d];
            c[d] += 0.25 * a[d];
        }
    }
    const double nn = sqrt(dot3(N, N));
    const int t = glpgp_qs_proj_nearest(P, c, x);
    if (!(nn > 0) || t < 0 || dot3(N, glpgp_qs_proj_normal(P, t)) <= 0.0) return -1.0;
    double sj = 1.0;
    for (int i = 0; i < 4; i++) {
        double e1[3], e2[3];
        sub3(p[(i + 1) % 4], p[i], e1);
        sub3(p[(i + 3) % 4], p[i], e2);
        const double l = sqrt(dot3(e1, e1) * dot3(e2, e2));
        if (!(l > 0)) return -1.0;
        cross3(e1, e2, x);
        sj = fmin(sj, dot3(x, N) / (nn * l));
    }
    return sj;
}

double glpgp_qs_worst_sj(const glpgp_qs_proj *P, const glpgp_qs_pts *S, const int *quads, int nq)
{
    double w = 1.0;
    for (int k = 0; k < nq; k++) {
        const int *v = quads + 4 * k;
        const double *p[4] = {glpgp_qs_pt(S, v[0]), glpgp_qs_pt(S, v[1]), glpgp_qs_pt(S, v[2]), glpgp_qs_pt(S, v[3])};
        w = fmin(w, glpgp_qs_quad_sj(P, p));
    }
    return w;
}

/* acc[4 j .. 4 j + 2] += the edge neighbours in the nq quads of point
 * first + j (a side of two quads counted twice), acc[4 j + 3] += their count. */
static void neighbour_sums(const glpgp_qs_pts *S, int first, const int *quads, int nq, double *acc)
{
    for (int k = 0; k < nq; k++)
        for (int i = 0; i < 4; i++) {
            const int a = quads[4 * k + i], b = quads[4 * k + (i + 1) % 4];
            for (int e = 0; e < 2; e++) {
                const int u = e ? b : a, w = e ? a : b;
                if (u < first) continue;
                for (int d = 0; d < 3; d++) acc[4 * (u - first) + d] += glpgp_qs_pt(S, w)[d];
                acc[4 * (u - first) + 3] += 1.0;
            }
        }
}

glpgp_status glpgp_qs_untangle(const glpgp_qs_proj *P, const glpgp_qs_pts *S, int first, const int *quads, int nq,
                               int max_sweeps, double floor_sj, double *worst)
{
    if (first < S->nbase || first > S->n)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "untangle: first point %d not in %d..%d", first, S->nbase, S->n);
    const int nn = S->n - first;
    double *acc = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)4 * nn + 4, sizeof(double), &acc));
    for (int sweep = 0; sweep < max_sweeps && !(*worst > floor_sj); sweep++) {
        memset(acc, 0, (size_t)4 * nn * sizeof(double));
        neighbour_sums(S, first, quads, nq, acc);
        for (int j = 0; j < nn; j++) {
            if (!(acc[4 * j + 3] > 0)) continue;
            double x[3];
            for (int d = 0; d < 3; d++) x[d] = acc[4 * j + d] / acc[4 * j + 3];
            glpgp_qs_proj_nearest(P, x, S->ext + 3 * (first - S->nbase + j));
        }
        *worst = glpgp_qs_worst_sj(P, S, quads, nq);
    }
    free(acc);
    return GLPGP_OK;
}
