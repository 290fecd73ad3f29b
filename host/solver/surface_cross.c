/* solver/surface_cross.c: the Ginzburg-Landau cross field on a surface
 * (glpgp/surfsolve.h): boundary and sharp-feature constraints, the cross
 * system (the P1 element in each triangle's plane with the corners' crosses
 * turned by exp(4 i phi): kernels/coupled_rows.h), its initial guess
 * (harmonic from the fixed crosses, or inverse iteration towards the
 * connection Laplacian's smallest eigenvector on a closed surface), the eps
 * levels of the planar cross field, the indices with the connection, and
 * the representatives U. */
#include "internal.h"

#include "glpgp/surfsolve.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TWO_PI (2.0 * GLPGP_PI)

static double principal(double a)
{
    double d = remainder(a, TWO_PI);
    return d <= -GLPGP_PI ? d + TWO_PI : d;
}

/* The next corner counter-clockwise around corner c's vertex (the twin of
 * its incoming half-edge), -1 past a boundary fan's last corner. */
static int fan_next(const glpgp_surface *s, int c) { return s->twin[c - c % 3 + (c % 3 + 2) % 3]; }

/* The angle in vertex v's frame of corner c's incoming edge (v -> its previous corner). */
static double in_angle(const glpgp_surface *s, int c, int v) { return s->eangle[c] + s->scale[v] * s->corner[c]; }

/* ---- constraints ----------------------------------------------------------- */

void glpgp_surface_constraints_destroy(glpgp_surface_constraints **pc)
{
    if (!pc || !*pc) return;
    glpgp_surface_constraints *c = *pc;
    free(c->feature);
    free(c->fixed);
    free(c->w0);
    free(c->cptr);
    free(c->cangle);
    free(c);
    *pc = NULL;
}

/* The angles of vertex v's constraint edges in its fan order into a[]
 * (room for its degree + 1); returns their count. */
static int vertex_constraints(const glpgp_mesh *m, const unsigned char *feat, int v, double *a)
{
    const glpgp_surface *s = m->surf;
    int n = 0, c = s->vstart[v], last = c;
    do {
        if (s->twin[c] < 0 || feat[c]) a[n++] = s->eangle[c];
        last = c;
        c = fan_next(s, c);
    } while (c >= 0 && c != s->vstart[v]);
    if (c < 0) a[n++] = in_angle(s, last, v); /* the boundary fan's incoming boundary edge */
    return n;
}

void glpgp_surface_fix_cross(glpgp_surface_constraints *c, int v, double a1, double a2)
{
    const double d = principal(4.0 * (a2 - a1)), ph = 4.0 * a1 + 0.5 * d;
    c->fixed[v] = 1;
    c->w0[2 * v] = cos(ph);
    c->w0[2 * v + 1] = sin(ph);
}

glpgp_status glpgp_surface_constraints_create(const glpgp_mesh *m, double feature_deg,
                                              glpgp_surface_constraints **out)
{
    const int nv = m->nv, nt = m->nt;
    glpgp_surface_constraints *c = NULL;
    glpgp_status st = GLPGP_OK;
    double *a = NULL;
    *out = NULL;
    if (!m->surf) return GLPGP_FAIL(GLPGP_ERR_ARG, "surface constraints of a planar mesh");
    GLPGP_CHECK(glpgp_calloc(1, sizeof *c, &c));
    c->nv = nv;
    c->nt = nt;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt, 1, &c->feature), fail);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv, 1, &c->fixed), fail);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * nv, sizeof(double), &c->w0), fail);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv + 1, sizeof(int), &c->cptr), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt + (size_t)nv + 1, sizeof(double), &a), fail);
    GLPGP_CHECK_GOTO(st, glpgp_surface_features(m, feature_deg, c->feature, &c->nfeatures), fail);
    /* pass 1: counts; pass 2: angles and fixed crosses */
    for (int v = 0; v < nv; v++) c->cptr[v + 1] = c->cptr[v] + vertex_constraints(m, c->feature, v, a);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)c->cptr[nv] + 1, sizeof(double), &c->cangle), fail);
    for (int v = 0; v < nv; v++) {
        double *ang = c->cangle + c->cptr[v];
        const int n = vertex_constraints(m, c->feature, v, ang);
        double a1, a2;
        if (m->on_boundary[v]) { /* incoming boundary edge's direction, outgoing one's (0) */
            a1 = ang[n - 1] + GLPGP_PI;
            a2 = m->surf->eangle[m->surf->vstart[v]];
        } else if (n == 2) { /* a crease through v */
            a1 = ang[0];
            a2 = ang[1];
        } else {
            continue; /* free: no constraint, a crease's end or a corner of three or more */
        }
        glpgp_surface_fix_cross(c, v, a1, a2);
        c->nfixed++;
    }
    free(a);
    *out = c;
    return GLPGP_OK;
fail:
    free(a);
    glpgp_surface_constraints_destroy(&c);
    return st;
}

void glpgp_surface_lumped_mass(const glpgp_mesh *m, double *mass)
{
    memset(mass, 0, (size_t)m->nv * sizeof(double));
    for (int t = 0; t < m->nt; t++) {
        const double *q = m->surf->txy + 6 * t, a3 = 0.5 * q[2] * q[5] / 3.0; /* corner 1 on the x axis */
        for (int a = 0; a < 3; a++) mass[m->tri[3 * t + a]] += a3;
    }
}

/* ---- indices ---------------------------------------------------------------- */

void glpgp_surface_cross_windings(const glpgp_mesh *m, const double *w, signed char *wind, int *plus, int *minus)
{
    const glpgp_surface *s = m->surf;
    int p = 0, q = 0;
    for (int t = 0; t < m->nt; t++) {
        double x = 4.0 * s->holonomy[t];
        for (int a = 0; a < 3; a++) {
            /* the edge's term once, at its smaller half-edge (the other: its negative) */
            const int h = 3 * t + a, g = s->twin[h], e = g >= 0 && g < h ? g : h;
            const int te = e / 3, ae = e % 3, i = m->tri[e], j = m->tri[3 * te + (ae + 1) % 3];
            /* arg(w_j conj(w_i) exp(-4 i rho_e)) */
            const double zr = w[2 * j] * w[2 * i] + w[2 * j + 1] * w[2 * i + 1];
            const double zi = w[2 * j + 1] * w[2 * i] - w[2 * j] * w[2 * i + 1];
            const double r = -4.0 * s->conn[e], cr = cos(r), sr = sin(r);
            const double d = atan2(zr * sr + zi * cr, zr * cr - zi * sr);
            x += e == h ? d : -d;
        }
        const int k = (int)lround(x / TWO_PI);
        if (wind) wind[t] = (signed char)(k > 0 ? 1 : k < 0 ? -1 : 0);
        if (k > 0) p += k;
        if (k < 0) q -= k;
    }
    *plus = p;
    *minus = q;
}

int glpgp_surface_expected_index4(const glpgp_mesh *m)
{
    int k = 0;
    for (int v = 0; v < m->nv; v++)
        if (m->on_boundary[v]) k += (int)lround(principal(GLPGP_PI - m->surf->angle_sum[v]) / (GLPGP_PI / 2.0));
    return 4 * m->surf->euler - k;
}

int glpgp_surface_boundary_index4(const glpgp_mesh *m, const double *w)
{
    const glpgp_surface *s = m->surf;
    double x = 0.0;
    for (int t = 0; t < m->nt; t++) x += 4.0 * s->holonomy[t];
    for (int h = 0; h < 3 * m->nt; h++) {
        if (s->twin[h] >= 0) continue;
        const int i = m->tri[h], j = m->tri[h - h % 3 + (h % 3 + 1) % 3];
        const double d = atan2(w[2 * j + 1], w[2 * j]) - atan2(w[2 * i + 1], w[2 * i]) - 4.0 * s->conn[h];
        x += principal(d);
    }
    return (int)lround(x / TWO_PI);
}

/* ---- transported fields, the cross system ------------------------------------ */

/* Breadth-first over the vertices, each reached vertex j from i along a
 * half-edge: fn(ctx, i, j, rho_{i->j}). queue: nv ints, seen: nv flags. */
static void bfs_edges(const glpgp_mesh *m, int *queue, unsigned char *seen,
                      void (*fn)(void *ctx, int i, int j, double rho), void (*root)(void *ctx, int r), void *ctx)
{
    const glpgp_surface *s = m->surf;
    memset(seen, 0, (size_t)m->nv);
    for (int r0 = 0; r0 < m->nv; r0++) {
        if (seen[r0]) continue;
        int head = 0, tail = 0;
        queue[tail++] = r0;
        seen[r0] = 1;
        root(ctx, r0);
        while (head < tail) {
            const int i = queue[head++];
            int c = s->vstart[i], last = c;
            do {
                const int j = m->tri[c - c % 3 + (c % 3 + 1) % 3];
                if (!seen[j]) {
                    seen[j] = 1;
                    fn(ctx, i, j, s->conn[c]);
                    queue[tail++] = j;
                }
                last = c;
                c = fan_next(s, c);
            } while (c >= 0 && c != s->vstart[i]);
            if (c < 0) { /* the boundary fan's last neighbour: across the incoming half-edge (j -> i) */
                const int hin = last - last % 3 + (last % 3 + 2) % 3, j = m->tri[hin];
                if (!seen[j]) {
                    seen[j] = 1;
                    fn(ctx, i, j, -s->conn[hin]);
                    queue[tail++] = j;
                }
            }
        }
    }
}

typedef struct transport_ctx {
    double *z;
    int mult;
} transport_ctx;

static void transport_root(void *ctx, int r)
{
    transport_ctx *c = ctx;
    c->z[2 * r] = 1.0;
    c->z[2 * r + 1] = 0.0;
}

static void transport_edge(void *ctx, int i, int j, double rho)
{
    transport_ctx *c = ctx;
    const double cr = cos(c->mult * rho), sr = sin(c->mult * rho), zr = c->z[2 * i], zi = c->z[2 * i + 1];
    c->z[2 * j] = cr * zr - sr * zi;
    c->z[2 * j + 1] = sr * zr + cr * zi;
}

void glpgp_surface_transport(const glpgp_mesh *m, int mult, double *z)
{
    int *queue = malloc((size_t)m->nv * sizeof(int));
    unsigned char *seen = malloc((size_t)m->nv);
    transport_ctx c = {z, mult};
    if (queue && seen) {
        bfs_edges(m, queue, seen, transport_edge, transport_root, &c);
    } else { /* no memory: the frames' own 1 (a worse initial guess, never wrong) */
        for (int i = 0; i < m->nv; i++) transport_root(&c, i);
    }
    free(queue);
    free(seen);
}

glpgp_status glpgp_surface_cross_system(const glpgp_mesh *m, glpgp_system **out)
{
    const int nt = m->nt;
    glpgp_system *s = NULL;
    *out = NULL;
    GLPGP_CHECK(glpgp_system_create(m, &s));
    glpgp_status st = glpgp_calloc((size_t)3 * nt, 1, &s->cconj);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)6 * nt, sizeof(double), &s->cfield);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)6 * nt, sizeof(double), &s->ctxy);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)6 * nt, sizeof(double), &s->crot);
    if (st != GLPGP_OK) {
        glpgp_system_destroy(&s);
        return st;
    }
    memcpy(s->ctxy, m->surf->txy, (size_t)6 * nt * sizeof(double));
    for (int c = 0; c < 3 * nt; c++) {
        s->crot[2 * c] = cos(4.0 * m->surf->rot[c]);
        s->crot[2 * c + 1] = sin(4.0 * m->surf->rot[c]);
    }
    *out = s;
    return GLPGP_OK;
}

/* ---- initial guesses ------------------------------------------------------- */

/* x <- the fixed crosses extended harmonically (N d = -(QUAD x0), Dirichlet
 * rows eliminated), then |w| = 1. QUAD assembled, the Dirichlet set given. */
static glpgp_status harmonic_init(glpgp_backend *b, const glpgp_options *o, glpgp_amg *amg, glpgp_vec *x,
                                  glpgp_vec *g, glpgp_vec *d, glpgp_vec *rhs, glpgp_cross_result *c,
                                  const glpgp_surface_constraints *con)
{
    const glpgp_backend_ops *op = b->ops;
    GLPGP_CHECK(op->vec_write(b, x, con->w0));
    GLPGP_CHECK(op->assemble_newton(b, x, 0.0, o->hess));
    GLPGP_CHECK(op->gradient(b, x, 0.0, g));
    GLPGP_CHECK(op->axpby(b, -1.0, g, 0.0, rhs));
    glpgp_cg_info ci;
    GLPGP_CHECK(glpgp_linear_solve(b, amg, rhs, d, o->cg_rtol, o->cg_max, o->cg_check, &ci));
    c->cg_iterations += ci.iterations;
    if (ci.reason == GLPGP_CG_BREAKDOWN)
        return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "cross field: harmonic solve: CG breakdown after %d iterations",
                          ci.iterations);
    GLPGP_CHECK(op->axpby(b, 1.0, d, 1.0, x));
    glpgp_log(GLPGP_LOG_INFO, "cross: harmonic initial guess, %d vertices fixed (%d feature edges), %d CG iterations",
              con->nfixed, con->nfeatures, ci.iterations);
    return GLPGP_OK;
}

glpgp_status glpgp_inverse_iteration(glpgp_backend *b, const glpgp_options *o, glpgp_amg **amg, glpgp_vec *x,
                                     glpgp_vec *y, glpgp_vec *rhs, glpgp_vec *work, const double *mass, int n,
                                     double *host, int maxsteps, long *cg, int *steps)
{
    const glpgp_backend_ops *op = b->ops;
    double lam0 = HUGE_VAL;
    *steps = 0;
    for (int k = 0; k < maxsteps; k++) {
        if (*amg && !glpgp_amg_try_update(*amg, x, "inverse iteration")) glpgp_amg_destroy(amg);
        GLPGP_CHECK(op->vec_read(b, x, host));
        for (int i = 0; i < n; i++) {
            host[2 * i] *= mass[i];
            host[2 * i + 1] *= mass[i];
        }
        GLPGP_CHECK(op->vec_write(b, rhs, host));
        glpgp_cg_info ci;
        GLPGP_CHECK(glpgp_linear_solve(b, *amg, rhs, y, 1e-4, o->cg_max, o->cg_check, &ci));
        *cg += ci.iterations;
        /* x <- y scaled to a mean |z|^2 of 1 (||x||_M^2 = sum M); lambda = y.QUAD y / y.M y */
        GLPGP_CHECK(op->vec_read(b, y, host));
        double mm = 0.0, ms = 0.0;
        for (int i = 0; i < n; i++) {
            mm += mass[i] * (host[2 * i] * host[2 * i] + host[2 * i + 1] * host[2 * i + 1]);
            ms += mass[i];
        }
        if (!(mm > 0.0) || !isfinite(mm)) break;
        const double sc = sqrt(ms / mm);
        for (int i = 0; i < 2 * n; i++) host[i] *= sc;
        GLPGP_CHECK(op->vec_write(b, x, host));
        GLPGP_CHECK(op->energy(b, x, 0.0, work));
        double sl[GLPGP_NSLOTS];
        GLPGP_CHECK(op->get_scalars(b, sl, GLPGP_NSLOTS));
        const double lam = 2.0 * sl[GLPGP_S_E] / ms;
        (*steps)++;
        glpgp_log(GLPGP_LOG_DEBUG, "inverse iteration %d: Rayleigh quotient %.6g, %d CG", k + 1, lam, ci.iterations);
        if (fabs(lam - lam0) <= 1e-3 * fabs(lam)) break;
        lam0 = lam;
    }
    return GLPGP_OK;
}

/* Without a fixed cross the global rotation w -> exp(i c) w is an exact
 * null direction of every Newton system: the cross of the vertex where the
 * initial guess is largest (far from any singularity) is fixed to it, which
 * picks one field of the family (the minimisers' energies, windings and
 * singularities are the same up to that vertex) and leaves the systems
 * definite. pin (nv) <- the new Dirichlet set; the backend and the
 * multigrid are set for it (w host: the initial guess, before |w| = 1). */
static glpgp_status pin_gauge(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o, const double *w,
                              unsigned char *pin, glpgp_amg **amg)
{
    int k = 0;
    for (int i = 1; i < m->nv; i++)
        if (hypot(w[2 * i], w[2 * i + 1]) > hypot(w[2 * k], w[2 * k + 1])) k = i;
    memset(pin, 0, (size_t)m->nv);
    pin[k] = 1;
    double *zero = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)2 * m->nv, sizeof(double), &zero));
    const glpgp_status st = b->ops->set_field(b, zero, pin);
    free(zero);
    GLPGP_CHECK(st);
    GLPGP_CHECK(b->ops->assemble_quadratic(b, GLPGP_ELEM_P1, 1.0));
    glpgp_amg_destroy(amg);
    *amg = glpgp_amg_try_create(b, o, pin, NULL, 0.0, "cross field");
    glpgp_log(GLPGP_LOG_DEBUG, "cross: the global rotation fixed at vertex %d", k);
    return GLPGP_OK;
}

/* w <- w exp(i c) with c maximising sum_i Re(conj(w_i) b_i) (the
 * curvature term's b, 2 n): the smoothest field's free global rotation
 * turned towards the principal directions before the gauge is pinned */
static void align_rotation(int n, const double *b, double *w)
{
    double re = 0.0, im = 0.0; /* sum conj(w) b */
    for (int i = 0; i < n; i++) {
        re += w[2 * i] * b[2 * i] + w[2 * i + 1] * b[2 * i + 1];
        im += w[2 * i] * b[2 * i + 1] - w[2 * i + 1] * b[2 * i];
    }
    if (!(hypot(re, im) > 0.0)) return;
    const double a = atan2(im, re), cs = cos(a), sn = sin(a);
    for (int i = 0; i < n; i++) {
        const double x = w[2 * i], y = w[2 * i + 1];
        w[2 * i] = cs * x - sn * y;
        w[2 * i + 1] = sn * x + cs * y;
    }
}

/* The cross field of a surface: the initial guess (init, 2 nv, when given:
 * kept as it is), then (levels) the GL continuation; c->w, analysed. */
static glpgp_status surface_cross(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                  const glpgp_surface_constraints *con, int levels, const double *init,
                                  glpgp_cross_result **out)
{
    const glpgp_backend_ops *op = b->ops;
    const int nv = m->nv;
    const size_t n2 = (size_t)2 * nv;
    glpgp_status st = GLPGP_OK;
    glpgp_cross_result *c = NULL;
    glpgp_system *sys = NULL;
    glpgp_vec *x = NULL, *g = NULL, *d = NULL, *xt = NULL, *work = NULL, *lin = NULL;
    glpgp_amg *amg = NULL;
    double *zero = NULL, *mass = NULL, *bl = NULL;
    unsigned char *pin = NULL;
    const double t0 = glpgp_now();
    *out = NULL;
    GLPGP_CHECK(glpgp_cross_result_create(nv, m->nt, &c));
    GLPGP_CHECK_GOTO(st, glpgp_surface_cross_system(m, &sys), fail);
    GLPGP_CHECK_GOTO(st, op->setup(b, sys), fail);
    GLPGP_CHECK_GOTO(st, glpgp_calloc(n2, sizeof(double), &zero), fail);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv, sizeof(double), &mass), fail);
    GLPGP_CHECK_GOTO(st, glpgp_cross_vecs_create(b, n2, &x, &g, &d, &xt, &work), fail);
    GLPGP_CHECK_GOTO(st, op->set_field(b, zero, con->fixed), fail);
    GLPGP_CHECK_GOTO(st, op->assemble_quadratic(b, GLPGP_ELEM_P1, 1.0), fail);
    /* multigrid frames: the transported field (vertex frames are unrelated to their neighbours') */
    amg = glpgp_amg_try_create(b, o, con->fixed, NULL, 0.0, "cross field");
    if (init)
        memcpy(c->w, init, n2 * sizeof(double));
    else
        glpgp_surface_transport(m, 4, c->w);
    GLPGP_CHECK_GOTO(st, op->vec_write(b, x, c->w), fail);
    if (init) {
        GLPGP_CHECK_GOTO(st, op->assemble_newton(b, x, 0.0, o->hess), fail);
        if (amg && !glpgp_amg_try_update(amg, x, "cross field")) glpgp_amg_destroy(&amg);
    } else if (con->nfixed > 0) {
        GLPGP_CHECK_GOTO(st, op->assemble_newton(b, x, 0.0, o->hess), fail);
        if (amg && !glpgp_amg_try_update(amg, x, "cross field")) glpgp_amg_destroy(&amg);
        GLPGP_CHECK_GOTO(st, harmonic_init(b, o, amg, x, g, d, xt, c, con), fail);
    } else {
        glpgp_surface_lumped_mass(m, mass);
        long cg = 0;
        int steps = 0;
        GLPGP_CHECK_GOTO(st, op->assemble_newton(b, x, 0.0, o->hess), fail);
        GLPGP_CHECK_GOTO(st, glpgp_inverse_iteration(b, o, &amg, x, d, xt, work, mass, nv, zero, 4, &cg, &steps), fail);
        c->cg_iterations += cg;
        glpgp_log(GLPGP_LOG_INFO, "cross: no fixed cross: initial guess by %d steps of inverse iteration (%ld CG)",
                  steps, cg);
    }
    GLPGP_CHECK_GOTO(st, op->vec_read(b, x, c->w), fail);
    if (levels && o->cross_align > 0.0) {
        GLPGP_CHECK_GOTO(st, glpgp_malloc(n2, sizeof(double), &bl), fail);
        double as[2];
        GLPGP_CHECK_GOTO(st, glpgp_surface_align_source(m, o->cross_align, con->fixed, bl, as), fail);
        glpgp_log(GLPGP_LOG_INFO, "cross: principal-curvature term (--cross-align %g) on %.1f%% of the area "
                  "(largest ((k1 - k2) / 2)^2 %.3g)", o->cross_align, 100.0 * as[1], as[0]);
    }
    if (con->nfixed == 0 && levels) {
        if (o->cross_align > 0.0 && !init) align_rotation(nv, bl, c->w);
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, 1, &pin), fail);
        GLPGP_CHECK_GOTO(st, pin_gauge(m, b, o, c->w, pin, &amg), fail);
    }
    if (!init) glpgp_cross_unit(c->w, nv);
    GLPGP_CHECK_GOTO(st, op->vec_write(b, x, c->w), fail);
    glpgp_newton_state ns = {.x = x, .g = g, .d = d, .xt = xt, .work = work, .amg = amg};
    if (bl) {
        /* the curvature term's b, zero at the pinned vertex too */
        for (int i = 0; pin && i < nv; i++)
            if (pin[i]) bl[2 * i] = bl[2 * i + 1] = 0.0;
        GLPGP_CHECK_GOTO(st, op->vec_create(b, n2, &lin), fail);
        GLPGP_CHECK_GOTO(st, op->vec_write(b, lin, bl), fail);
        ns.lin = lin;
    }
    GLPGP_CHECK_GOTO(st, glpgp_cross_finish(m, b, o, &ns, levels, t0, c), fail);
    goto done;
fail:
    glpgp_cross_result_destroy(&c);
done:
    glpgp_amg_destroy(&amg);
    glpgp_cross_vecs_destroy(b, &x, &g, &d, &xt, &work);
    op->vec_destroy(b, &lin);
    /* the backend keeps a pointer to sys: the caller sets it up again first */
    glpgp_system_destroy(&sys);
    b->sys = NULL;
    free(zero);
    free(mass);
    free(bl);
    free(pin);
    *out = c;
    return st;
}

glpgp_status glpgp_surface_cross_solve(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                       const glpgp_surface_constraints *con, glpgp_cross_result **out)
{
    return surface_cross(m, b, o, con, 1, NULL, out);
}

glpgp_status glpgp_surface_cross_polish(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                        const glpgp_surface_constraints *con, const double *w,
                                        glpgp_cross_result **out)
{
    /* one level: the schedule from eps_min (cross_eps0 x diagonal = cross_eps_min x mean edge) */
    glpgp_options one = *o;
    one.cross_eps0 = o->cross_eps_min * m->mean_edge / glpgp_mesh_diagonal(m);
    return surface_cross(m, b, &one, con, 1, w, out);
}

glpgp_status glpgp_surface_boundary_field(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                          const glpgp_surface_constraints *con, glpgp_cross_result **out)
{
    *out = NULL;
    if (con->nfixed == 0)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "--field boundary: this surface has no boundary and no sharp feature "
                                         "(--feature-angle %g) to align with: use --field cross",
                          o->feature_angle);
    return surface_cross(m, b, o, con, 0, NULL, out);
}

/* ---- representatives ---------------------------------------------------------- */

typedef struct rep_ctx {
    const double *w;
    double *alpha;
} rep_ctx;

static void rep_root(void *ctx, int r)
{
    rep_ctx *c = ctx;
    c->alpha[r] = atan2(c->w[2 * r + 1], c->w[2 * r]) / 4.0;
}

static void rep_edge(void *ctx, int i, int j, double rho)
{
    rep_ctx *c = ctx;
    const double a = atan2(c->w[2 * j + 1], c->w[2 * j]) / 4.0, target = c->alpha[i] + rho;
    c->alpha[j] = a + (GLPGP_PI / 2.0) * round((target - a) / (GLPGP_PI / 2.0));
}

int glpgp_surface_cross_to_vector(const glpgp_mesh *m, const double *w, double *u)
{
    const int nv = m->nv;
    int *queue = malloc((size_t)nv * sizeof(int));
    unsigned char *seen = malloc((size_t)nv);
    double *alpha = malloc((size_t)nv * sizeof(double));
    int cuts = -1;
    if (queue && seen && alpha) {
        rep_ctx c = {w, alpha};
        bfs_edges(m, queue, seen, rep_edge, rep_root, &c);
        for (int i = 0; i < nv; i++) {
            u[2 * i] = cos(alpha[i]);
            u[2 * i + 1] = sin(alpha[i]);
        }
        /* edges whose transported representative is not the other end's (within 45 degrees) */
        cuts = 0;
        const glpgp_surface *s = m->surf;
        for (int h = 0; h < 3 * m->nt; h++) {
            if (s->twin[h] > h) continue;
            const int i = m->tri[h], j = m->tri[h - h % 3 + (h % 3 + 1) % 3];
            if (fabs(principal(alpha[i] + s->conn[h] - alpha[j])) > GLPGP_PI / 4.0) cuts++;
        }
    }
    free(queue);
    free(seen);
    free(alpha);
    return cuts;
}

int glpgp_surface_dirichlet(const glpgp_mesh *m, const glpgp_surface_constraints *con, const double *u,
                            unsigned char *dir)
{
    int n = 0;
    for (int i = 0; i < m->nv; i++)
        for (int s = 0; s < 2; s++) {
            const double psi = atan2(u[2 * i + 1], u[2 * i]) + s * (GLPGP_PI / 2.0);
            unsigned char f = 0;
            for (int k = con->cptr[i]; k < con->cptr[i + 1]; k++)
                if (fabs(sin(psi - con->cangle[k])) >= fabs(cos(psi - con->cangle[k]))) f = 1;
            dir[2 * i + s] = f;
            n += f;
        }
    return n;
}
