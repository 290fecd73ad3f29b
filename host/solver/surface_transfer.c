/* solver/surface_transfer.c: a surface's cross field carried from the mesh
 * it was refined from onto the refined mesh (glpgp_surface_cross_transfer,
 * glpgp/surfsolve.h), and the guiding cross field of a refined surface
 * solved on its input (glpgp_surface_cross_on_input): --cross-mesh input
 * and polish.
 *
 * Bisection keeps the piecewise linear surface: each refined triangle lies
 * in one input triangle T (surf->otri, the barycentric coordinates of its
 * corners there in surf->obary, tracked by the refinement). A refined
 * vertex inside T or on one of its edges gets the P1 interpolant of T's
 * corner crosses in T's plane, sum lambda_k w_k exp(4 i phi_k) (phi_k the
 * corner's rotation vertex frame -> triangle frame: what the cross system's
 * element does), turned into the vertex's own frame through a refined
 * triangle of its fan that lies in T (the same plane; the vertex's angle
 * sum is 2 pi there, so the corner's rotation is exact). An input vertex
 * keeps its cross, its frame's angles shifted to the refined fan's
 * reference edge (the same cone: the same scale). |w| is the interpolant's
 * (below 1 in the singularities' cores, as the solve's own). */
#include "internal.h"

#include "glpgp/surfsolve.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

double glpgp_plane_angle(const glpgp_surface *s, int T, const double *d)
{
    const double *E1 = s->tframe + 9 * (size_t)T, *E2 = E1 + 3;
    return atan2(dot3(d, E2), dot3(d, E1));
}

void glpgp_turn(double *z, double a)
{
    const double c = cos(a), s = sin(a), x = z[0], y = z[1];
    z[0] = c * x - s * y;
    z[1] = s * x + c * y;
}

/* Input vertex v (corner k of input triangle T), seen from fine corner c0
 * (of the same vertex, in T): its cross wc[v] with the frame's origin moved
 * from the input's reference edge to the refined one's. */
static void vertex_cross(const glpgp_mesh *coarse, const double *wc, const glpgp_mesh *fine, int c0, int T, int k,
                         double *out)
{
    const glpgp_surface *sc = coarse->surf, *sf = fine->surf;
    const int v = fine->tri[c0], b = fine->tri[c0 - c0 % 3 + (c0 % 3 + 1) % 3];
    const double *q = sc->txy + 6 * (size_t)T;
    const int kb = (k + 1) % 3;
    const double beta = atan2(q[2 * kb + 1] - q[2 * k + 1], q[2 * kb] - q[2 * k]); /* input edge in T */
    const double d[3] = {fine->xyz[3 * (size_t)b] - fine->xyz[3 * (size_t)v],
                         fine->xyz[3 * (size_t)b + 1] - fine->xyz[3 * (size_t)v + 1],
                         fine->xyz[3 * (size_t)b + 2] - fine->xyz[3 * (size_t)v + 2]};
    double gamma = remainder(glpgp_plane_angle(sc, T, d) - beta, 2.0 * GLPGP_PI);
    if (gamma < 0.0) gamma = 0.0; /* rounding below the input edge */
    const double offset = sf->eangle[c0] - (sc->eangle[3 * T + k] + sf->scale[v] * gamma);
    out[0] = wc[2 * v];
    out[1] = wc[2 * v + 1];
    glpgp_turn(out, 4.0 * offset);
}

/* A refined vertex at barycentric lam in input triangle T, seen from fine
 * corner c0 (whose triangle lies in T): the interpolated cross in T's plane
 * turned into the vertex's frame. */
static void interpolated_cross(const glpgp_mesh *coarse, const double *wc, const glpgp_mesh *fine, int c0, int T,
                               const double *lam, double *out)
{
    const glpgp_surface *sc = coarse->surf, *sf = fine->surf;
    double W[2] = {0.0, 0.0};
    for (int k = 0; k < 3; k++) {
        const int i = coarse->tri[3 * T + k];
        double z[2] = {wc[2 * i], wc[2 * i + 1]};
        glpgp_turn(z, 4.0 * sc->rot[3 * T + k]);
        W[0] += lam[k] * z[0];
        W[1] += lam[k] * z[1];
    }
    /* the fine triangle's x axis in T's plane: delta; theta_v = phi_T - delta - rot_f */
    const double delta = glpgp_plane_angle(sc, T, sf->tframe + 9 * (size_t)(c0 / 3));
    glpgp_turn(W, -4.0 * (delta + sf->rot[c0]));
    out[0] = W[0];
    out[1] = W[1];
}

glpgp_status glpgp_surface_cross_transfer(const glpgp_mesh *coarse, const double *wc, const glpgp_mesh *fine,
                                          double *wf)
{
    const glpgp_surface *sf = fine->surf;
    if (!sf || !coarse->surf || !sf->otri || !sf->obary)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "cross transfer: the fine mesh has no origin (not refined by bisection)");
    for (int t = 0; t < fine->nt; t++)
        if (sf->otri[t] < 0 || sf->otri[t] >= coarse->nt)
            return GLPGP_FAIL(GLPGP_ERR_ARG, "cross transfer: triangle %d's origin %d is not a triangle of the "
                                             "input (%d)", t, sf->otri[t], coarse->nt);
    for (int v = 0; v < fine->nv; v++) {
        const int c0 = sf->vstart[v], T = sf->otri[c0 / 3];
        const double *lam = sf->obary + 9 * (size_t)(c0 / 3) + 3 * (c0 % 3);
        int k = -1;
        for (int j = 0; j < 3; j++)
            if (coarse->tri[3 * T + j] == v && lam[j] > 1.0 - 1e-12) k = j;
        if (k >= 0)
            vertex_cross(coarse, wc, fine, c0, T, k, wf + 2 * (size_t)v);
        else
            interpolated_cross(coarse, wc, fine, c0, T, lam, wf + 2 * (size_t)v);
    }
    return GLPGP_OK;
}

/* c's levels and counts from the input's solve ci (the polish's, when
 * given, after them) */
static void copy_levels(glpgp_cross_result *c, const glpgp_cross_result *ci, const glpgp_cross_result *cp)
{
    c->nlevels = ci->nlevels;
    memcpy(c->level, ci->level, sizeof c->level);
    c->newton_iterations = ci->newton_iterations;
    c->capped_levels = ci->capped_levels;
    c->cg_iterations = ci->cg_iterations;
    if (!cp) return;
    for (int l = 0; l < cp->nlevels && c->nlevels < GLPGP_CROSS_MAX_LEVELS; l++) c->level[c->nlevels++] = cp->level[l];
    c->newton_iterations += cp->newton_iterations;
    c->capped_levels += cp->capped_levels;
    c->cg_iterations += cp->cg_iterations;
    c->polished = 1;
}

glpgp_status glpgp_surface_cross_on_input(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                          const glpgp_surface_constraints *con, int polish,
                                          glpgp_cross_result **out)
{
    const glpgp_mesh *mi = m->surf ? m->surf->origin : NULL;
    const double t0 = glpgp_now();
    glpgp_surface_constraints *coni = NULL;
    glpgp_cross_result *ci = NULL, *c = NULL, *cp = NULL;
    glpgp_status st = GLPGP_OK;
    *out = NULL;
    if (!mi) return GLPGP_FAIL(GLPGP_ERR_ARG, "cross field on the input: the refined surface did not keep it");
    glpgp_log(GLPGP_LOG_INFO, "cross: solved on the input mesh (%d vertices), carried onto the refined one (%d)",
              mi->nv, m->nv);
    GLPGP_CHECK_GOTO(st, glpgp_surface_constraints_create(mi, o->feature_angle, &coni), done);
    GLPGP_CHECK_GOTO(st, glpgp_surface_constraints_rims(mi, con->rim_scale, coni), done);
    GLPGP_CHECK_GOTO(st, glpgp_surface_cross_solve(mi, b, o, coni, &ci), done);
    GLPGP_CHECK_GOTO(st, glpgp_cross_result_create(m->nv, m->nt, &c), done);
    GLPGP_CHECK_GOTO(st, glpgp_surface_cross_transfer(mi, ci->w, m, c->w), done);
    for (int i = 0; i < m->nv; i++) /* the constraints' crosses exactly (the interpolant's up to rounding) */
        if (con->fixed[i]) {
            c->w[2 * i] = con->w0[2 * i];
            c->w[2 * i + 1] = con->w0[2 * i + 1];
        }
    if (polish) {
        GLPGP_CHECK_GOTO(st, glpgp_surface_cross_polish(m, b, o, con, c->w, &cp), done);
        memcpy(c->w, cp->w, (size_t)2 * m->nv * sizeof(double));
    }
    copy_levels(c, ci, cp);
    c->solved_nv = mi->nv;
    c->solved_nt = mi->nt;
    GLPGP_CHECK_GOTO(st, glpgp_cross_analyze(m, c), done);
    c->seconds = glpgp_now() - t0;
    glpgp_log(GLPGP_LOG_INFO, "cross: carried onto the refined mesh%s: %d singularities there (on the input %d), "
              "index sum %d/4 (Poincare-Hopf %d/4), median |w| = %.4f, %.2f s in all",
              polish ? " and polished" : "", c->nsing, ci->nsing, c->index4_sum, c->index4_expected, c->zabs_median,
              c->seconds);
done:
    if (st != GLPGP_OK) glpgp_cross_result_destroy(&c);
    glpgp_cross_result_destroy(&ci);
    glpgp_cross_result_destroy(&cp);
    glpgp_surface_constraints_destroy(&coni);
    *out = c;
    return st;
}
