/* solver/crossfield.c: Ginzburg-Landau cross fields (glpgp/cross.h):
 * boundary-aligned crosses, the continuation in eps on the oscillators'
 * engine (W = 0, all boundary vertices Dirichlet), singularities with their
 * index and position, Poincare-Hopf with corners, and the vector field U
 * that the oscillators use.
 *
 * The energy 1/2 int |grad w|^2 + 1/(4 eps^2) int (|w|^2 - 1)^2 is the
 * oscillators' E + P_eps with omega = 0: the P1 element of kernels/element.h
 * with a zero field is the plain stiffness matrix, so QUAD, NEWTON, the
 * gradient, the energy, CG and the multigrid are the backend ops of every
 * other solve, on both backends, unchanged. */
#include "internal.h"

#include "glpgp/cross.h"
#include "glpgp/phase.h"
#include "glpgp/surface.h"
#include "glpgp/surfsolve.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

glpgp_status glpgp_cross_result_create(int nv, int nt, glpgp_cross_result **out)
{
    glpgp_cross_result *c = NULL;
    *out = NULL;
    if (nv < 1 || nt < 1) return GLPGP_FAIL(GLPGP_ERR_ARG, "cross field of %d vertices, %d triangles", nv, nt);
    GLPGP_CHECK(glpgp_calloc(1, sizeof *c, &c));
    c->nv = c->solved_nv = nv;
    c->nt = c->solved_nt = nt;
    if (glpgp_calloc((size_t)2 * nv, sizeof(double), &c->w) != GLPGP_OK ||
        glpgp_calloc((size_t)nt, 1, &c->winding) != GLPGP_OK) {
        glpgp_cross_result_destroy(&c);
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "cross field of %d vertices", nv);
    }
    *out = c;
    return GLPGP_OK;
}

void glpgp_cross_result_destroy(glpgp_cross_result **pc)
{
    if (!pc || !*pc) return;
    glpgp_cross_result *c = *pc;
    free(c->w);
    free(c->winding);
    free(c->sing);
    free(c);
    *pc = NULL;
}

/* Principal value of an angle in (-pi, pi]. */
static double principal(double a)
{
    double d = remainder(a, 2.0 * GLPGP_PI); /* [-pi, pi] */
    return d <= -GLPGP_PI ? d + 2.0 * GLPGP_PI : d;
}

void glpgp_cross_boundary(const glpgp_mesh *m, double *w)
{
    memset(w, 0, (size_t)2 * m->nv * sizeof(double));
    for (int i = 0; i < m->nv; i++) {
        if (!m->on_boundary[i]) continue;
        /* the normal's angle gives the same cross as the tangent's (4 pi/2 = 2 pi) */
        const double a1 = atan2(m->normal_prev[2 * i + 1], m->normal_prev[2 * i]);
        const double a2 = atan2(m->normal_next[2 * i + 1], m->normal_next[2 * i]);
        /* w = exp(i (4 a1 + d/2)),  d = principal(4 (a2 - a1)): the mean along the shorter arc */
        const double d = principal(4.0 * (a2 - a1));
        const double ph = 4.0 * a1 + 0.5 * d;
        w[2 * i] = cos(ph);
        w[2 * i + 1] = sin(ph);
    }
}

int glpgp_cross_expected_index4(const glpgp_mesh *m)
{
    if (m->xyz) return glpgp_surface_expected_index4(m);
    int sum = 0;
    for (int l = 0; l < m->nloops; l++) {
        double turn = 0.0;
        int k = 0;
        for (int p = m->loop_start[l]; p < m->loop_start[l + 1]; p++) {
            const int i = m->loop_vertices[p];
            const double a1 = atan2(m->normal_prev[2 * i + 1], m->normal_prev[2 * i]);
            const double a2 = atan2(m->normal_next[2 * i + 1], m->normal_next[2 * i]);
            /* turning angle tau in (-pi, pi]; k = tau rounded to quarter turns (= 2 - n_c) */
            const double tau = principal(a2 - a1);
            turn += tau;
            k += (int)lround(tau / (GLPGP_PI / 2.0));
        }
        /* a loop turns by +2 pi (outer, CCW) or -2 pi (hole, CW): 4 turn/(2 pi) - sum k */
        sum += 4 * (int)lround(turn / (2.0 * GLPGP_PI)) - k;
    }
    return sum;
}

/* Zero of the linear interpolant of w on triangle t: barycentric (l1, l2)
 * from w0 + l1 (w1 - w0) + l2 (w2 - w0) = 0; the centroid when the zero is
 * outside the triangle or the system is singular. On a surface the corner
 * values are turned into the triangle's frame first (exp(4 i rot)) and the
 * point is in 3D (*pz; 0 in the plane). */
static void tri_zero(const glpgp_mesh *m, const double *w, int t, double *px, double *py, double *pz)
{
    const int *v = m->tri + 3 * t;
    double wr[3], wi[3];
    for (int a = 0; a < 3; a++) {
        wr[a] = w[2 * v[a]];
        wi[a] = w[2 * v[a] + 1];
        if (m->surf) {
            const double ph = 4.0 * m->surf->rot[3 * t + a], c = cos(ph), sn = sin(ph), r = wr[a];
            wr[a] = c * r - sn * wi[a];
            wi[a] = sn * r + c * wi[a];
        }
    }
    const double ar = wr[1] - wr[0], ai = wi[1] - wi[0];
    const double br = wr[2] - wr[0], bi = wi[2] - wi[0];
    const double det = ar * bi - br * ai;
    double l1 = 1.0 / 3.0, l2 = 1.0 / 3.0;
    if (det != 0.0) {
        /* [ar br; ai bi] (l1, l2) = -(w0r, w0i) */
        const double r0 = -wr[0], r1 = -wi[0];
        const double x1 = (r0 * bi - br * r1) / det, x2 = (ar * r1 - r0 * ai) / det;
        if (x1 >= -1e-9 && x2 >= -1e-9 && x1 + x2 <= 1.0 + 1e-9) {
            l1 = x1;
            l2 = x2;
        }
    }
    const double l0 = 1.0 - l1 - l2;
    if (m->xyz) {
        const double *X = m->xyz;
        *px = l0 * X[3 * v[0]] + l1 * X[3 * v[1]] + l2 * X[3 * v[2]];
        *py = l0 * X[3 * v[0] + 1] + l1 * X[3 * v[1] + 1] + l2 * X[3 * v[2] + 1];
        *pz = l0 * X[3 * v[0] + 2] + l1 * X[3 * v[1] + 2] + l2 * X[3 * v[2] + 2];
        return;
    }
    *px = l0 * m->xy[2 * v[0]] + l1 * m->xy[2 * v[1]] + l2 * m->xy[2 * v[2]];
    *py = l0 * m->xy[2 * v[0] + 1] + l1 * m->xy[2 * v[1] + 1] + l2 * m->xy[2 * v[2] + 1];
    *pz = 0.0;
}

glpgp_status glpgp_cross_analyze(const glpgp_mesh *m, glpgp_cross_result *c)
{
    glpgp_status st = GLPGP_OK;
    const int nv = m->nv, nt = m->nt;
    int *parent = NULL, *vs = NULL, *root_id = NULL;
    double *acc = NULL, *s = NULL;
    int plus, minus;
    if (m->xyz) /* a surface: with the connection (glpgp/surfsolve.h) */
        glpgp_surface_cross_windings(m, c->w, c->winding, &plus, &minus);
    else
        glpgp_singularities(m, c->w, c->winding, &plus, &minus);
    free(c->sing);
    c->sing = NULL;
    c->nsing = 0;
    c->index4_sum = plus - minus;
    /* a surface with a boundary: what its fixed crosses imply (at a scale,
     * they need not be the edges' own: glpgp_surface_constraints_rims) */
    c->index4_expected = !m->xyz        ? glpgp_cross_expected_index4(m)
                         : m->nloops > 0 ? glpgp_surface_boundary_index4(m, c->w)
                                         : glpgp_surface_expected_index4(m);
    /* median |w| */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(double), &s), done);
    for (int i = 0; i < nv; i++) s[i] = hypot(c->w[2 * i], c->w[2 * i + 1]);
    c->zabs_median = glpgp_median_double(s, (size_t)nv);
    if (plus + minus == 0) goto done;
    /* merge singular triangles of one sign that share a vertex (union-find;
     * vs[v] = the last singular triangle of each sign seen at vertex v) */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nt, sizeof(int), &parent), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv, sizeof(int), &vs), done);
    for (int t = 0; t < nt; t++) parent[t] = t;
    for (int i = 0; i < 2 * nv; i++) vs[i] = -1;
    for (int t = 0; t < nt; t++) {
        if (!c->winding[t]) continue;
        const int sg = c->winding[t] > 0;
        for (int a = 0; a < 3; a++) {
            int *slot = &vs[2 * m->tri[3 * t + a] + sg];
            if (*slot >= 0) {
                int ra = glpgp_uf_find(parent, *slot), rb = glpgp_uf_find(parent, t);
                if (ra != rb) parent[ra < rb ? rb : ra] = ra < rb ? ra : rb;
            }
            *slot = t;
        }
    }
    /* one singularity per root, numbered by its first triangle */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nt, sizeof(int), &root_id), done);
    int n = 0;
    for (int t = 0; t < nt; t++) {
        root_id[t] = -1;
        if (c->winding[t] && glpgp_uf_find(parent, t) == t) root_id[t] = n++;
    }
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)n, sizeof *c->sing, &c->sing), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)3 * n, sizeof(double), &acc), done);
    c->nsing = n;
    for (int t = 0; t < nt; t++) {
        if (!c->winding[t]) continue;
        const int k = root_id[glpgp_uf_find(parent, t)];
        glpgp_cross_sing *q = &c->sing[k];
        double px, py, pz;
        tri_zero(m, c->w, t, &px, &py, &pz);
        if (q->ntri == 0) q->tri = t;
        q->ntri++;
        q->index4 += c->winding[t];
        acc[3 * k] += px;
        acc[3 * k + 1] += py;
        acc[3 * k + 2] += pz;
    }
    /* position: mean of the members' zeros */
    for (int k = 0; k < n; k++) {
        c->sing[k].x = acc[3 * k] / c->sing[k].ntri;
        c->sing[k].y = acc[3 * k + 1] / c->sing[k].ntri;
        c->sing[k].z = acc[3 * k + 2] / c->sing[k].ntri;
    }
done:
    free(parent);
    free(vs);
    free(root_id);
    free(acc);
    free(s);
    return st;
}

int glpgp_cross_to_vector(const glpgp_mesh *m, const double *w, double *u)
{
    if (m->xyz) return glpgp_surface_cross_to_vector(m, w, u); /* a surface: with its connection */
    const int nv = m->nv, nt = m->nt;
    int *deg = calloc((size_t)nv + 1, sizeof(int)), *adj = malloc((size_t)6 * nt * sizeof(int));
    int *queue = malloc((size_t)nv * sizeof(int));
    unsigned char *seen = calloc((size_t)nv, 1);
    double *alpha = malloc((size_t)nv * sizeof(double));
    int cuts = -1;
    if (!deg || !adj || !queue || !seen || !alpha) goto done;
    /* vertex adjacency (each interior edge listed twice, harmless) */
    for (int t = 0; t < nt; t++)
        for (int a = 0; a < 3; a++) deg[m->tri[3 * t + a] + 1] += 2;
    for (int i = 0; i < nv; i++) deg[i + 1] += deg[i];
    {
        int *fill = calloc((size_t)nv, sizeof(int));
        if (!fill) goto done;
        for (int t = 0; t < nt; t++)
            for (int a = 0; a < 3; a++) {
                const int i = m->tri[3 * t + a];
                adj[deg[i] + fill[i]++] = m->tri[3 * t + (a + 1) % 3];
                adj[deg[i] + fill[i]++] = m->tri[3 * t + (a + 2) % 3];
            }
        free(fill);
    }
    /* alpha_i = arg(w_i) / 4 + k pi/2, k chosen closest to the neighbour that
     * reached i (breadth-first from the vertex nearest the bounding-box center,
     * each component from its first vertex) */
    const double cx = 0.5 * (m->bbox[0] + m->bbox[2]), cy = 0.5 * (m->bbox[1] + m->bbox[3]);
    int root = 0;
    double best = HUGE_VAL;
    for (int i = 0; i < nv; i++) {
        double d = hypot(m->xy[2 * i] - cx, m->xy[2 * i + 1] - cy);
        if (d < best) {
            best = d;
            root = i;
        }
    }
    for (int start = -1; start < nv; start++) {
        const int r0 = start < 0 ? root : start;
        if (seen[r0]) continue;
        int head = 0, tail = 0;
        queue[tail++] = r0;
        seen[r0] = 1;
        alpha[r0] = atan2(w[2 * r0 + 1], w[2 * r0]) / 4.0;
        while (head < tail) {
            const int i = queue[head++];
            for (int p = deg[i]; p < deg[i + 1]; p++) {
                const int j = adj[p];
                if (seen[j]) continue;
                seen[j] = 1;
                const double a = atan2(w[2 * j + 1], w[2 * j]) / 4.0;
                /* a + k pi/2 closest to alpha_i */
                alpha[j] = a + (GLPGP_PI / 2.0) * round((alpha[i] - a) / (GLPGP_PI / 2.0));
                queue[tail++] = j;
            }
        }
    }
    for (int i = 0; i < nv; i++) {
        u[2 * i] = cos(alpha[i]);
        u[2 * i + 1] = sin(alpha[i]);
    }
    /* cuts: edges where U turns by more than 45 degrees; each triangle edge
     * i -> next is counted when i < next, so an interior edge (seen once in each
     * orientation) counts once (a boundary edge only when its start is the
     * smaller index) */
    cuts = 0;
    for (int i = 0; i < nv; i++)
        for (int p = deg[i]; p < deg[i + 1]; p += 2) { /* pairs (next, prev) of one triangle */
            const int j = adj[p];
            if (j < i) continue;
            const double dot = u[2 * i] * u[2 * j] + u[2 * i + 1] * u[2 * j + 1];
            if (dot < sqrt(0.5)) cuts++;
        }
done:
    free(deg);
    free(adj);
    free(queue);
    free(seen);
    free(alpha);
    return cuts;
}

int glpgp_cross_eps_schedule(const glpgp_mesh *m, const glpgp_options *o,
                             double eps[GLPGP_CROSS_MAX_LEVELS])
{
    const double diag = glpgp_mesh_diagonal(m); /* 3D for a surface */
    /* eps_0 = cross_eps0 D;  eps_{k+1} = max(ratio eps_k, emin) while eps_k > merge emin */
    int n = 0;
    double e = o->cross_eps0 * diag, emin = o->cross_eps_min * m->mean_edge;
    eps[n++] = e;
    while (e > emin * o->eps_merge && n < GLPGP_CROSS_MAX_LEVELS) {
        e = fmax(e * o->eps_ratio, emin);
        eps[n++] = e;
    }
    return n;
}

void glpgp_cross_log_done(const glpgp_cross_result *c)
{
    glpgp_log(GLPGP_LOG_INFO,
              "cross: done in %.2f s: %d singularities (index sum %d/4, Poincare-Hopf %d/4), median |w| = %.4f, "
              "%d Newton, %ld CG",
              c->seconds, c->nsing, c->index4_sum, c->index4_expected, c->zabs_median, c->newton_iterations,
              c->cg_iterations);
}

glpgp_status glpgp_cross_levels(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                glpgp_newton_state *ns, glpgp_cross_result *c)
{
    const glpgp_backend_ops *op = b->ops;
    const int nv = b->sys->nv;
    glpgp_vec *g = ns->g;
    double eps[GLPGP_CROSS_MAX_LEVELS];
    c->nlevels = glpgp_cross_eps_schedule(m, o, eps);
    for (int l = 0; l < c->nlevels; l++) {
        glpgp_level_stats *ls = &c->level[l];
        const double rtol = o->cross_rtol;
        glpgp_log(GLPGP_LOG_INFO, "cross: level %d/%d, eps = %.4g", l + 1, c->nlevels, eps[l]);
        /* a level that starts at a critical point up to rounding (e.g. w = 1 on a
         * domain with axis-aligned edges only) has nothing to do: the relative
         * test would chase rounding noise to the Newton cap. The entries of g
         * are O(1) (cotan weights, penalty (edge/eps)^2), so |g| <= 1e-10 sqrt(nv)
         * is rounding. */
        double sg[GLPGP_NSLOTS];
        GLPGP_CHECK(glpgp_newton_gradient(b, ns, 1.0 / (4.0 * eps[l] * eps[l])));
        GLPGP_CHECK(op->dot(b, g, g, GLPGP_S_DOT));
        GLPGP_CHECK(op->get_scalars(b, sg, GLPGP_NSLOTS));
        if (sqrt(sg[GLPGP_S_DOT]) <= 1e-10 * sqrt((double)nv)) {
            ls->eps = eps[l];
            ls->rtol = rtol;
            ls->grad0 = ls->grad = sqrt(sg[GLPGP_S_DOT]);
            ls->energy = glpgp_newton_energy(ns, sg);
            continue;
        }
        ns->ftol = o->cross_ftol;
        const glpgp_status st = glpgp_newton_level(b, o, ns, 2, eps[l], rtol, ls);
        ns->ftol = 0.0;
        GLPGP_CHECK(st);
        if (ls->stalled)
            glpgp_log(GLPGP_LOG_INFO,
                      "cross: eps level %d/%d stopped after %d Newton steps: E + P fell by at most %.0e of itself "
                      "over the last 3 (|g|/|g0| = %.2e; the singularities' drift stalls)",
                      l + 1, c->nlevels, ls->newton, o->cross_ftol, ls->grad0 > 0 ? ls->grad / ls->grad0 : 0.0);
        if (ls->capped) {
            c->capped_levels++;
            glpgp_log(GLPGP_LOG_WARNING,
                      "cross: eps level %d/%d stopped at the Newton cap of %d steps with |g|/|g0| = %.2e "
                      "(tolerance %.0e): not converged",
                      l + 1, c->nlevels, o->newton_max, ls->grad0 > 0 ? ls->grad / ls->grad0 : 0.0, rtol);
        }
        c->newton_iterations += ls->newton;
        c->cg_iterations += ls->cg;
    }
    return GLPGP_OK;
}

glpgp_status glpgp_cross_vecs_create(glpgp_backend *b, size_t n2, glpgp_vec **x, glpgp_vec **g, glpgp_vec **d,
                                     glpgp_vec **xt, glpgp_vec **work)
{
    glpgp_vec **v[5] = {x, g, d, xt, work};
    for (int k = 0; k < 5; k++) {
        glpgp_status st = b->ops->vec_create(b, n2, v[k]);
        if (st != GLPGP_OK) {
            glpgp_cross_vecs_destroy(b, x, g, d, xt, work);
            glpgp_error_push_trace(__FILE__, __LINE__);
            return st;
        }
    }
    return GLPGP_OK;
}

void glpgp_cross_vecs_destroy(glpgp_backend *b, glpgp_vec **x, glpgp_vec **g, glpgp_vec **d, glpgp_vec **xt,
                              glpgp_vec **work)
{
    glpgp_vec **v[5] = {x, g, d, xt, work};
    for (int k = 0; k < 5; k++) b->ops->vec_destroy(b, v[k]);
}

void glpgp_cross_unit(double *w, int nv)
{
    for (int i = 0; i < nv; i++) {
        const double a = hypot(w[2 * i], w[2 * i + 1]);
        w[2 * i] = a > 1e-300 ? w[2 * i] / a : 1.0;
        w[2 * i + 1] = a > 1e-300 ? w[2 * i + 1] / a : 0.0;
    }
}

glpgp_status glpgp_cross_finish(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                glpgp_newton_state *ns, int levels, double t0, glpgp_cross_result *c)
{
    if (levels) {
        GLPGP_CHECK(glpgp_cross_levels(m, b, o, ns, c));
        GLPGP_CHECK(b->ops->vec_read(b, ns->x, c->w));
    }
    GLPGP_CHECK(glpgp_cross_analyze(m, c));
    c->seconds = glpgp_now() - t0;
    glpgp_cross_log_done(c);
    return GLPGP_OK;
}

glpgp_status glpgp_cross_solve(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                               glpgp_cross_result **out)
{
    const glpgp_backend_ops *op = b->ops;
    const int nv = m->nv;
    const size_t n2 = (size_t)2 * nv;
    glpgp_status st = GLPGP_OK;
    glpgp_cross_result *c = NULL;
    glpgp_vec *x = NULL, *g = NULL, *d = NULL, *xt = NULL, *work = NULL;
    glpgp_amg *amg = NULL;
    double *zero = NULL;
    const double t0 = glpgp_now();
    *out = NULL;
    if (m->xyz)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "cross field of a surface: glpgp_surface_cross_solve (glpgp/surfsolve.h)");
    if (!b->sys || b->sys->mesh != m)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "cross field: the backend is not set up for this mesh");
    GLPGP_CHECK(glpgp_cross_result_create(nv, m->nt, &c));
    GLPGP_CHECK_GOTO(st, glpgp_calloc(n2, sizeof(double), &zero), fail);
    GLPGP_CHECK_GOTO(st, glpgp_cross_vecs_create(b, n2, &x, &g, &d, &xt, &work), fail);

    /* the oscillators' energy with W = 0 (omega = 0): QUAD = stiffness;
     * Dirichlet set = every boundary vertex */
    GLPGP_CHECK_GOTO(st, op->set_field(b, zero, m->on_boundary), fail);
    GLPGP_CHECK_GOTO(st, op->assemble_quadratic(b, GLPGP_ELEM_P1, 1.0), fail);
    amg = glpgp_amg_try_create(b, o, m->on_boundary, NULL, 0.0, "cross field");

    /* initial guess: w0 = boundary crosses, harmonic inside:
     * w = w0 + d,  N d = -(QUAD w0) with the Dirichlet rows eliminated */
    glpgp_cross_boundary(m, c->w);
    GLPGP_CHECK_GOTO(st, op->vec_write(b, x, c->w), fail);
    GLPGP_CHECK_GOTO(st, op->assemble_newton(b, x, 0.0, o->hess), fail);
    if (amg && !glpgp_amg_try_update(amg, NULL, "cross field")) glpgp_amg_destroy(&amg);
    GLPGP_CHECK_GOTO(st, op->gradient(b, x, 0.0, g), fail);
    GLPGP_CHECK_GOTO(st, op->axpby(b, -1.0, g, 0.0, xt), fail);
    glpgp_cg_info ci;
    GLPGP_CHECK_GOTO(st, glpgp_linear_solve(b, amg, xt, d, o->cg_rtol, o->cg_max, o->cg_check, &ci), fail);
    c->cg_iterations += ci.iterations;
    if (ci.reason == GLPGP_CG_BREAKDOWN) {
        st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "cross field: harmonic solve: CG breakdown after %d iterations "
                                           "(folded mesh?)", ci.iterations);
        goto fail;
    }
    GLPGP_CHECK_GOTO(st, op->axpby(b, 1.0, d, 1.0, x), fail);
    /* |w| <- 1 (phase kept; w = 1 where the harmonic field vanishes) */
    GLPGP_CHECK_GOTO(st, op->vec_read(b, x, c->w), fail);
    glpgp_cross_unit(c->w, nv);
    GLPGP_CHECK_GOTO(st, op->vec_write(b, x, c->w), fail);
    glpgp_log(GLPGP_LOG_INFO, "cross: harmonic initial guess, %d boundary vertices fixed, %d CG iterations",
              m->loop_start[m->nloops], ci.iterations);

    /* Ginzburg-Landau continuation: Newton levels at decreasing eps */
    glpgp_newton_state ns = {.x = x, .g = g, .d = d, .xt = xt, .work = work, .amg = amg};
    GLPGP_CHECK_GOTO(st, glpgp_cross_finish(m, b, o, &ns, 1, t0, c), fail);
    goto done;
fail:
    glpgp_cross_result_destroy(&c);
done:
    glpgp_amg_destroy(&amg);
    glpgp_cross_vecs_destroy(b, &x, &g, &d, &xt, &work);
    free(zero);
    *out = c;
    return st;
}

glpgp_status glpgp_cross_guiding_field(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                       glpgp_cross_result **keep, double *u, long *cg_iterations)
{
    glpgp_cross_result *c = NULL;
    if (keep) *keep = NULL;
    GLPGP_CHECK(glpgp_cross_solve(m, b, o, &c));
    *cg_iterations += c->cg_iterations;
    const int cuts = glpgp_cross_to_vector(m, c->w, u);
    if (cuts < 0) {
        glpgp_cross_result_destroy(&c);
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "cross field: no memory for the vector field");
    }
    if ((c->nsing > 0 || cuts > 0) && o->cross_coupling != GLPGP_COUPLING_OFF)
        glpgp_log(GLPGP_LOG_INFO,
                  "cross field has %d singularities: U (alpha = arg(w)/4) turns by 90 degrees across %d edges; "
                  "the oscillators are coupled across them (--cross-coupling)",
                  c->nsing, cuts);
    else if (c->nsing > 0 || cuts > 0)
        glpgp_log(GLPGP_LOG_WARNING,
                  "cross field has %d singularities: U (alpha = arg(w)/4, branches chosen outward from the "
                  "center) turns by 90 degrees across %d edges, which the oscillators see as cuts",
                  c->nsing, cuts);
    if (keep)
        *keep = c;
    else
        glpgp_cross_result_destroy(&c);
    return GLPGP_OK;
}
