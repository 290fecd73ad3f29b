/* solver/coupled.c: the two oscillators carried across the cross field's
 * branch cuts (issue 14, item 3; glpgp/cross.h, docs/numerics.md "Coupled
 * oscillators"): the per-corner matching of a representative field U, the
 * coupled system on 2 nv nodes (a "virtual mesh" of 2 nt triangles: the frame
 * oscillators u and v of every mesh triangle, with per-corner conjugation
 * flags and frame fields for kernels/coupled_rows.h), and the frame
 * windings that the quad extraction reads.
 *
 * Vertex i has a representative direction theta_i (U_i = (cos, sin)), V_i = U_i
 * rotated by +90 degrees, and two nodes: 2i (z_u, following U_i) and 2i + 1
 * (z_v, following V_i). Triangle t takes its corner 0's representative as its
 * frame; corner a has the quarter-turn count r_a with rot^{r_a}(U_a) ~ U_frame.
 * A quarter turn maps (U, V) to (V, -U); the oscillator of -W is the
 * conjugate of that of W (E_{-W}(conj z) = E_W(z), the phase 2 pi x.W / h
 * changes sign), so the frame oscillator k at corner a is
 *     node family k ^ (r_a & 1) of vertex a, conjugated when ((r_a + k) & 3) >= 2:
 *     r = 0: (z_u, z_v)   r = 1: (z_v, conj z_u)   r = 2: (conj z_u, conj z_v)
 *     r = 3: (conj z_v, z_u). */
#include "internal.h"

#include "glpgp/cross.h"
#include "glpgp/phase.h"
#include "glpgp/surfsolve.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int glpgp_cross_turn(const double *ua, const double *ub)
{
    /* angle from U_b to U_a, rounded to quarter turns, in 0..3 */
    const double c = ub[0] * ua[1] - ub[1] * ua[0], d = ub[0] * ua[0] + ub[1] * ua[1];
    const long r = lround(atan2(c, d) / (GLPGP_PI / 2.0));
    return (int)(((r % 4) + 4) % 4);
}

/* out <- U_a of corner a of triangle t in the frame the matching compares
 * in: the plane's (u itself) or, on a surface, t's (turned by the corner's
 * rotation phi). */
void glpgp_coupled_corner_u(const glpgp_mesh *m, const double *u, int t, int a, double *out)
{
    const double *ua = u + 2 * m->tri[3 * t + a];
    if (!m->surf) {
        out[0] = ua[0];
        out[1] = ua[1];
        return;
    }
    const double c = cos(m->surf->rot[3 * t + a]), s = sin(m->surf->rot[3 * t + a]);
    out[0] = c * ua[0] - s * ua[1];
    out[1] = s * ua[0] + c * ua[1];
}

int glpgp_coupled_corner_turn(const glpgp_mesh *m, const double *u, int t, int a)
{
    if (a == 0) return 0;
    if (!m->surf) return glpgp_cross_turn(u + 2 * m->tri[3 * t], u + 2 * m->tri[3 * t + a]);
    double u0[2], ua[2];
    glpgp_coupled_corner_u(m, u, t, 0, u0);
    glpgp_coupled_corner_u(m, u, t, a, ua);
    return glpgp_cross_turn(u0, ua);
}

void glpgp_cross_frame_map(int r, int k, int *family, int *conj)
{
    *family = k ^ (r & 1);
    *conj = ((r + k) & 3) >= 2;
}

void glpgp_coupled_frame_value(int r, int k, const double *zu, const double *zv, double *out)
{
    int fam, cj;
    glpgp_cross_frame_map(r, k, &fam, &cj);
    const double *z = fam ? zv : zu;
    out[0] = z[0];
    out[1] = cj ? -z[1] : z[1];
}

void glpgp_coupled_destroy(glpgp_coupled **pc)
{
    if (!pc || !*pc) return;
    glpgp_coupled *c = *pc;
    glpgp_system_destroy(&c->sys);
    free(c->vm.xy);
    free(c->vm.tri);
    free(c->match);
    free(c);
    *pc = NULL;
}

glpgp_status glpgp_coupled_create(const glpgp_mesh *m, const double *u, glpgp_coupled **out)
{
    glpgp_status st = GLPGP_OK;
    glpgp_coupled *c = NULL;
    const int nv = m->nv, nt = m->nt;
    unsigned char *cconj = NULL;
    double *cfield = NULL;
    *out = NULL;
    if (nv > (1 << 29) || nt > (1 << 27))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "coupled cross-field system: mesh too large (%d vertices)", nv);
    GLPGP_CHECK(glpgp_calloc(1, sizeof *c, &c));
    c->nv = nv;
    c->nt = nt;
    /* a surface: no plane (vm.xy NULL), each virtual triangle its own (ctxy) */
    if (m->xy) GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * nv, sizeof(double), &c->vm.xy), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)6 * nt, sizeof(int), &c->vm.tri), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt, 1, &c->match), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)6 * nt, 1, &cconj), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)12 * nt, sizeof(double), &cfield), fail);
    /* virtual mesh: node 2i + s at x_i; only nv, nt, xy, tri are used by the
     * system layout and the backends (no boundary data) */
    c->vm.nv = 2 * nv;
    c->vm.nt = 2 * nt;
    for (int i = 0; i < nv && m->xy; i++)
        for (int s = 0; s < 2; s++) {
            c->vm.xy[2 * (2 * i + s)] = m->xy[2 * i];
            c->vm.xy[2 * (2 * i + s) + 1] = m->xy[2 * i + 1];
        }
    c->vm.area = m->area;
    memcpy(c->vm.bbox, m->bbox, sizeof m->bbox);
    c->vm.mean_edge = m->mean_edge;
    for (int t = 0; t < nt; t++) {
        const int *v = m->tri + 3 * t;
        for (int a = 0; a < 3; a++) {
            /* r_a: rot^{r_a}(U_a) ~ U_{corner 0} (the frame) */
            const int r = glpgp_coupled_corner_turn(m, u, t, a);
            c->match[3 * t + a] = (unsigned char)r;
            for (int s = 0; s < 2; s++) {
                int fam, cj;
                glpgp_cross_frame_map(r, s, &fam, &cj);
                const int tv = 2 * t + s;
                c->vm.tri[3 * tv + a] = 2 * v[a] + fam;
                cconj[3 * tv + a] = (unsigned char)cj;
                /* frame field of oscillator s at corner a: rot^{r_a + s}(U_a), exact rotations */
                double uc[2];
                glpgp_coupled_corner_u(m, u, t, a, uc);
                double wx = uc[0], wy = uc[1];
                for (int q = 0; q < ((r + s) & 3); q++) {
                    const double tx = -wy;
                    wy = wx;
                    wx = tx;
                }
                cfield[2 * (3 * tv + a)] = wx;
                cfield[2 * (3 * tv + a) + 1] = wy;
            }
        }
    }
    GLPGP_CHECK_GOTO(st, glpgp_system_create(&c->vm, &c->sys), fail);
    c->sys->cconj = cconj;
    c->sys->cfield = cfield;
    if (m->surf) { /* both oscillators of triangle t in t's plane */
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)12 * nt, sizeof(double), &c->sys->ctxy), fail_sys);
        for (int t = 0; t < nt; t++)
            for (int s = 0; s < 2; s++) memcpy(c->sys->ctxy + 6 * (2 * t + s), m->surf->txy + 6 * t, 6 * sizeof(double));
    }
    *out = c;
    return GLPGP_OK;
fail_sys: /* cconj, cfield belong to the system now */
    glpgp_coupled_destroy(&c);
    return st;
fail:
    free(cconj);
    free(cfield);
    glpgp_coupled_destroy(&c);
    return st;
}

void glpgp_coupled_node_field(const double *u, int nv, double *w)
{
    for (int i = 0; i < nv; i++) {
        const double ux = u[2 * i], uy = u[2 * i + 1];
        w[4 * i] = ux; /* node 2i: U_i */
        w[4 * i + 1] = uy;
        w[4 * i + 2] = -uy; /* node 2i + 1: V_i = U_i rotated by +90 degrees */
        w[4 * i + 3] = ux;
    }
}

void glpgp_coupled_windings(const glpgp_mesh *m, const double *u, const double *zu, const double *zv, int k,
                            signed char *sing, int *plus, int *minus)
{
    *plus = *minus = 0;
    for (int t = 0; t < m->nt; t++) {
        const int *v = m->tri + 3 * t;
        double z[6];
        for (int a = 0; a < 3; a++) {
            const int r = glpgp_coupled_corner_turn(m, u, t, a);
            glpgp_coupled_frame_value(r, k, zu + 2 * v[a], zv + 2 * v[a], z + 2 * a);
        }
        /* winding = sum of principal arg(z_b / z_a) over the edges / 2 pi */
        double s = 0.0;
        for (int a = 0; a < 3; a++) {
            const double *p = z + 2 * a, *q = z + 2 * ((a + 1) % 3);
            s += atan2(p[0] * q[1] - p[1] * q[0], p[0] * q[0] + p[1] * q[1]);
        }
        const int w = (int)lround(s / (2.0 * GLPGP_PI));
        sing[t] = (signed char)(w > 0 ? 1 : w < 0 ? -1 : 0);
        if (w > 0) (*plus)++;
        if (w < 0) (*minus)++;
    }
}

glpgp_status glpgp_cross_conformal_size(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                        const double *w, double h, double *size, long *cg_iterations)
{
    const glpgp_backend_ops *op = b->ops;
    const int nv = m->nv, nt = m->nt;
    const size_t n2 = (size_t)2 * nv;
    glpgp_status st = GLPGP_OK;
    double *f = NULL, *zero = NULL, *l = NULL;
    unsigned char *dir = NULL;
    glpgp_vec *x = NULL, *rhs = NULL, *d = NULL;
    GLPGP_CHECK_GOTO(st, glpgp_calloc(n2, sizeof(double), &f), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc(n2, sizeof(double), &zero), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv, sizeof(double), &l), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv, 1, &dir), done);
    /* f_a = sum_T A_T g_a . R(grad theta)_T,  R(gx, gy) = (gy, -gx),
     * theta = arg(w) / 4 unwrapped on each triangle from corner 0 (the
     * cross-field singular triangles, where it does not close, add nothing) */
    for (int t = 0; t < nt; t++) {
        const int *v = m->tri + 3 * t;
        double x3[3], y3[3], gx[3], gy[3], ar[3];
        for (int a = 0; a < 3; a++) {
            x3[a] = m->xy[2 * v[a]];
            y3[a] = m->xy[2 * v[a] + 1];
            ar[a] = atan2(w[2 * v[a] + 1], w[2 * v[a]]);
        }
        const double d1 = remainder(ar[1] - ar[0], 2.0 * GLPGP_PI), d2 = remainder(ar[2] - ar[1], 2.0 * GLPGP_PI),
                     d3 = remainder(ar[0] - ar[2], 2.0 * GLPGP_PI);
        if (fabs(d1 + d2 + d3) > 1.0) continue; /* w winds: singular */
        const double a2 = (x3[1] - x3[0]) * (y3[2] - y3[0]) - (x3[2] - x3[0]) * (y3[1] - y3[0]);
        for (int a = 0; a < 3; a++) {
            gx[a] = (y3[(a + 1) % 3] - y3[(a + 2) % 3]) / a2;
            gy[a] = (x3[(a + 2) % 3] - x3[(a + 1) % 3]) / a2;
        }
        const double th1 = d1 / 4.0, th2 = (d1 + d2) / 4.0;
        const double tx = th1 * gx[1] + th2 * gx[2], ty = th1 * gy[1] + th2 * gy[2];
        for (int a = 0; a < 3; a++) f[2 * v[a]] += 0.5 * a2 * (gx[a] * ty - gy[a] * tx);
    }
    /* K phi = f (cotan Laplacian, Neumann; phi fixed to 0 at vertex 0 for the
     * constant), solved by the backend: QUAD = the Laplacian, NEWTON = QUAD
     * with vertex 0's identity row (real parts carry phi, imaginary parts 0) */
    dir[0] = 1;
    f[0] = 0.0;
    GLPGP_CHECK_GOTO(st, op->set_field(b, zero, dir), done);
    GLPGP_CHECK_GOTO(st, op->assemble_quadratic(b, GLPGP_ELEM_LAPLACE, h), done);
    GLPGP_CHECK_GOTO(st, op->vec_create(b, n2, &x), done);
    GLPGP_CHECK_GOTO(st, op->vec_create(b, n2, &rhs), done);
    GLPGP_CHECK_GOTO(st, op->vec_create(b, n2, &d), done);
    GLPGP_CHECK_GOTO(st, op->assemble_newton(b, x, 0.0, o->hess), done);
    GLPGP_CHECK_GOTO(st, op->vec_write(b, rhs, f), done);
    glpgp_cg_info ci;
    GLPGP_CHECK_GOTO(st, glpgp_linear_solve(b, NULL, rhs, d, o->cg_rtol, o->cg_max, o->cg_check, &ci), done);
    *cg_iterations += ci.iterations;
    if (ci.reason == GLPGP_CG_BREAKDOWN) {
        st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "cross size field: CG breakdown after %d iterations", ci.iterations);
        goto done;
    }
    GLPGP_CHECK_GOTO(st, op->vec_read(b, d, f), done);
    /* s_i = h clamp(exp(phi_i - phi_q), 1/c, 1): on, q = 1 (phi_q = max phi)
     * and c = inf; auto, q and c from the options (the conformal scale kept
     * where it is within a factor c below its q-quantile, h above it). Then at
     * least size_min h and what the mesh resolves, min(h, size_resolution
     * l_i) (l_i: longest edge at i) */
    const int automode = o->cross_size == GLPGP_CROSS_SIZE_AUTO;
    const double q = automode ? o->cross_size_quantile : 1.0, lo = automode ? -log(o->cross_size_ratio) : -HUGE_VAL;
    for (int i = 0; i < nv; i++) l[i] = f[2 * i];
    const double mx = glpgp_select_double(l, (size_t)nv, (size_t)lround(q * (nv - 1))); /* phi_q */
    memset(l, 0, (size_t)nv * sizeof(double));
    for (int t = 0; t < nt; t++)
        for (int a = 0; a < 3; a++) {
            const int i = m->tri[3 * t + a], j = m->tri[3 * t + (a + 1) % 3];
            const double e = hypot(m->xy[2 * j] - m->xy[2 * i], m->xy[2 * j + 1] - m->xy[2 * i + 1]);
            l[i] = fmax(l[i], e);
            l[j] = fmax(l[j], e);
        }
    for (int i = 0; i < nv; i++) {
        const double s = h * exp(fmin(0.0, fmax(lo, f[2 * i] - mx)));
        size[i] = fmax(s, fmax(o->size_min * h, fmin(h, o->size_resolution * l[i])));
    }
done:
    op->vec_destroy(b, &x);
    op->vec_destroy(b, &rhs);
    op->vec_destroy(b, &d);
    free(f);
    free(zero);
    free(l);
    free(dir);
    return st;
}
