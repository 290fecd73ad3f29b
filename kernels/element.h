/* element.h: per-triangle formulas shared verbatim by the C reference path and
 * the OpenCL kernels (this file is compiled both as C11 and as OpenCL C, so it
 * uses only plain double arithmetic and private arrays).
 *
 * Discretisation of E(z) = 1/2 int |grad z - i w z|^2,  w = (2 pi / h) W,
 * with P1 hat functions phi_a on triangle T (area A, g_a = grad phi_a):
 *   z = sum_a z_a phi_a  and  E = 1/2 z^H H z,  H Hermitian, H = S + i K:
 *     |grad z - i w z|^2 = |grad z|^2 + |w|^2 |z|^2 - 2 Re( i z  w . grad conj(z) )
 *   - stiffness      int g_a . g_b               = A g_a . g_b
 *   - mass           int |w|^2 phi_a phi_b        = |w|^2 A (1 + delta_ab) / 12
 *   - coupling       -2 Re(i sum_ab z_a conj(z_b) (w . g_b) int phi_a)
 *                    = sum_ab conj(z_b) [ i (c_a - c_b) ] z_a,  c_a = A (w . g_a) / 3
 *     so  S_ab = A g_a.g_b + |w|^2 A (1+delta_ab)/12,   K_ab = c_b - c_a   (row a, col b).
 *   w_T is constant per triangle: (2 pi / h) * normalised mean of the three W_a.
 *   With a local size field s (one value per vertex, solver/sizefield.c) the
 *   scale 2 pi / h becomes the mean of the corner frequencies,
 *   w_T = 2 pi (1/s0 + 1/s1 + 1/s2)/3 * normalised mean W; the element is still
 *   exactly 1/2 int_T |grad z - i w_T z|^2, so H_T stays Hermitian PSD. The
 *   field w(x) = 2 pi W / s(x) is no longer a gradient (curl w != 0 where s
 *   varies across W), so no plane wave has E = 0: the GL minimiser puts what
 *   is not integrable into singularities (docs/numerics.md, "Local size").
 *   Local eps: the GL energy E + 1/(4 eps^2) int (|z|^2-1)^2 is invariant
 *   under x -> x / h only when eps scales with the period, so with a local
 *   period h_T the penalty length should be eps_T = eps h_T / h. Per
 *   triangle, E_T + P_T / (4 eps_T^2) = (h / h_T)^2 (w_T E_T + P_T / (4 eps^2))
 *   with w_T = (h_T / h)^2: the same minimiser up to the positive factor
 *   per triangle that keeps one global eps for the penalty kernels. So the
 *   sized quadratic element is weighted: H_T <- w_T H_T, h_T = 1 / mean(1/s_a)
 *   (P1), and w_e = (h_e / h)^2, h_e = 1 / mean(1/s_p, 1/s_q), for the
 *   transport edge (the energy is then sum_T w_T E_T + P, still Hermitian
 *   PSD). Measured: fewer repairs and irregular vertices on the hard domains
 *   than the unweighted field (bench/results/size_field.md).
 *   Sign check: z = exp(+i w.x) has grad z = i w z, so E is ~0 for it and large
 *   for exp(-i w.x) (tests/test_element.c checks both).
 * Edge-transport discretisation (original PGP), per triangle edge (a,b) with
 * opposite corner k and cotan weight c = cot(theta_k)/2 = (e_ka . e_kb) / (4A):
 *   1/2 c |z_b - r_ab z_a|^2,  r_ab = exp(i (2 pi / h) W_ab . (x_b - x_a)),
 *   W_ab = normalised (W_a + W_b)  (edge-based, so both triangles agree;
 *   with a size field 2 pi / h is 2 pi (1/s_a + 1/s_b)/2, also edge-based):
 *   H_aa += c, H_bb += c, H_ba += -c r_ab, H_ab += -c conj(r_ab).
 * Real unknowns X = [Re z_a, Im z_a] per vertex: the 2x2 block of a complex
 * entry h = p + i q is [[p, -q], [q, p]] and E = 1/2 X^T A X, grad E = A X.
 *
 * GL penalty P = 1/(4 eps^2) int (|z|^2 - 1)^2 is a degree-4 polynomial in the
 * barycentric coordinates on each triangle, integrated exactly by the 6-point
 * degree-4 Dunavant rule (positive weights):
 *   P_T      = A/(4 eps^2) sum_q w_q s_q^2,          s_q = |z_q|^2 - 1
 *   dP/dX_a  = A/eps^2     sum_q w_q s_q z_q phi_a(q)               (2-vector)
 *   d2P/dX_a dX_b = A/(4 eps^2) sum_q w_q phi_a phi_b M_q            (2x2)
 *     exact:     M_q = 4 (s_q I + 2 z_q z_q^T)   (indefinite where |z|^2 < 1)
 *     paper:     M_q = 4 [[3x^2, 2xy], [2xy, 3y^2]]   (eq. 8, PSD: det = 20 x^2 y^2)
 *     projected: M_q = 4 ( max(3|z|^2-1, 0) zhat zhat^T + max(|z|^2-1, 0)(I - zhat zhat^T) )
 *                (the exact M_q with its negative eigenvalues clamped to 0, per
 *                 quadrature point; sum_q w_q (phi phi^T) (x) M_q is then PSD).
 *     mixed:     exact where |z_q|^2 >= 1/2, projected where |z_q|^2 < 1/2 (vortex
 *                cores); not PSD by itself (the exact part's -(1-|z|^2) across z),
 *                but H_E + it is positive definite near a GL minimiser; the Newton
 *                driver falls back to `projected` when CG meets negative curvature.
 */
#ifndef GLPGP_ELEMENT_H
#define GLPGP_ELEMENT_H

#ifdef __OPENCL_VERSION__
#define GLPGP_FN inline
/* glpgp/kinds.h precedes this file in the embedded program source */
#else
#include <math.h>
#include "glpgp/kinds.h"
#define GLPGP_FN static inline
#endif

/* Signed area of the triangle (positive when counter-clockwise). */
GLPGP_FN double glpgp_tri_area(const double *x, const double *y)
{
    return 0.5 * ((x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]));
}

/* Twice the signed area and the P1 gradients g_a = (gx[a], gy[a]). */
GLPGP_FN double glpgp_tri_grads(const double *x, const double *y, double *gx, double *gy)
{
    double a2 = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    for (int a = 0; a < 3; a++) {
        int b = (a + 1) % 3, c = (a + 2) % 3;
        gx[a] = (y[b] - y[c]) / a2;
        gy[a] = (x[c] - x[b]) / a2;
    }
    return a2;
}

/* Wave scales 2 pi / h of a triangle with corner sizes s[0..2] (local size
 * field): *kt = 2 pi (1/s0 + 1/s1 + 1/s2) / 3 for the P1 element (the mean
 * of the corner frequencies |W| / s_a, so w_T = kt * normalised mean W), and
 * ke[e] = 2 pi (1/s_e + 1/s_{e+1}) / 2 for the transport edge (e, e+1)
 * (edge-based: both triangles of an edge agree); the local-eps weights
 * (see the top) *wt = (h_T / h)^2 with h_T = 2 pi / kt, and
 * we[e] = (h_e / h)^2 with h_e = 2 pi / ke[e] (h: the largest size). */
GLPGP_FN void glpgp_elem_scales(const double *s, double h, double *kt, double *ke, double *wt, double *we)
{
    const double f0 = 1.0 / s[0], f1 = 1.0 / s[1], f2 = 1.0 / s[2];
    const double ft = (f0 + f1 + f2) / 3.0, fe0 = 0.5 * (f0 + f1), fe1 = 0.5 * (f1 + f2), fe2 = 0.5 * (f2 + f0);
    *kt = 2.0 * GLPGP_PI * ft;
    ke[0] = 2.0 * GLPGP_PI * fe0;
    ke[1] = 2.0 * GLPGP_PI * fe1;
    ke[2] = 2.0 * GLPGP_PI * fe2;
    /* weights (h_T / h)^2, h_T = 1 / ft: the local eps (see the top) */
    *wt = 1.0 / (ft * h * ft * h);
    we[0] = 1.0 / (fe0 * h * fe0 * h);
    we[1] = 1.0 / (fe1 * h * fe1 * h);
    we[2] = 1.0 / (fe2 * h * fe2 * h);
}

/* Entry (a,b) (row a, column b) of the complex element matrix of kind `kind`
 * on the triangle with corners (x,y) and unit field (wx,wy) at its corners,
 * with wave scales kt (P1: w_T = kt * normalised mean W) and ke[e]
 * (transport edge (e, e+1): phase ke[e] W_e . (x_{e+1} - x_e)) and the
 * local-eps weights wt (P1) and we[e] (transport edge e); the uniform size h
 * has kt = ke[e] = 2 pi / h and weights 1 (glpgp_elem_entry). For every kt
 * the P1 element matrix is exactly wt/2 int_T |grad z - i w_T z|^2 for P1 z,
 * so it is Hermitian positive semi-definite whatever the size field (the
 * Laplace kind is not weighted).
 * Returns the real part in *re and the imaginary part in *im. */
GLPGP_FN void glpgp_elem_entry_k(int kind, const double *x, const double *y,
                                 const double *wx, const double *wy, double kt, double wt,
                                 const double *ke, const double *we, int a, int b, double *re,
                                 double *im)
{
    double gx[3], gy[3];
    double a2 = glpgp_tri_grads(x, y, gx, gy);
    double area = 0.5 * a2;
    if (kind == GLPGP_ELEM_P1 || kind == GLPGP_ELEM_LAPLACE) {
        double s = area * (gx[a] * gx[b] + gy[a] * gy[b]);
        double k = 0.0;
        if (kind == GLPGP_ELEM_P1) {
            /* w_T = kt * normalised mean field  (kt = 2 pi / h for a uniform size) */
            double mx = wx[0] + wx[1] + wx[2], my = wy[0] + wy[1] + wy[2];
            double mn = sqrt(mx * mx + my * my);
            double ox = 0.0, oy = 0.0;
            if (mn > 0.0) {
                ox = kt * mx / mn;
                oy = kt * my / mn;
            }
            s += (ox * ox + oy * oy) * area * (a == b ? 2.0 : 1.0) / 12.0;
            /* K_ab = c_b - c_a,  c_j = A (w . g_j) / 3 */
            double ca = area * (ox * gx[a] + oy * gy[a]) / 3.0;
            double cb = area * (ox * gx[b] + oy * gy[b]) / 3.0;
            k = cb - ca;
            s *= wt;
            k *= wt;
        }
        *re = s;
        *im = k;
        return;
    }
    /* transport: sum over the triangle's edges touching a and b */
    double sre = 0.0, sim = 0.0;
    for (int e = 0; e < 3; e++) {
        int p = e, q = (e + 1) % 3, o = (e + 2) % 3; /* edge (p,q), opposite o */
        double ex1 = x[p] - x[o], ey1 = y[p] - y[o];
        double ex2 = x[q] - x[o], ey2 = y[q] - y[o];
        double c = (ex1 * ex2 + ey1 * ey2) / (2.0 * a2) * we[e]; /* weight cot(theta_o)/2 */
        if (a == b) {
            if (a == p || a == q) sre += c;
            continue;
        }
        if (!((a == p && b == q) || (a == q && b == p))) continue;
        /* r_pq = exp(i phase), phase = ke[p] W_pq . (x_q - x_p)  (ke = 2 pi / h uniform) */
        double mx = wx[p] + wx[q], my = wy[p] + wy[q];
        double mn = sqrt(mx * mx + my * my);
        double ph = 0.0;
        if (mn > 0.0) ph = ke[p] * (mx * (x[q] - x[p]) + my * (y[q] - y[p])) / mn;
        /* H_qp = -c r_pq, H_pq = -c conj(r_pq) */
        double cr = cos(ph), sr = sin(ph);
        sre += -c * cr;
        sim += (a == q) ? -c * sr : c * sr;
    }
    *re = sre;
    *im = sim;
}

/* Entry (a,b) with the uniform target size h: glpgp_elem_entry_k with
 * kt = ke[e] = 2 pi / h (the same arithmetic as before size fields existed). */
GLPGP_FN void glpgp_elem_entry(int kind, const double *x, const double *y,
                               const double *wx, const double *wy, double h,
                               int a, int b, double *re, double *im)
{
    const double k = 2.0 * GLPGP_PI / h;
    double ke[3], we[3];
    ke[0] = k;
    ke[1] = k;
    ke[2] = k;
    we[0] = 1.0;
    we[1] = 1.0;
    we[2] = 1.0;
    /* weights 1: x * 1.0 is exact, so this is the arithmetic of the uniform size bit for bit */
    glpgp_elem_entry_k(kind, x, y, wx, wy, k, 1.0, ke, we, a, b, re, im);
}

/* Degree-4 Dunavant rule: barycentric point q (0..5), weight (sums to 1). */
GLPGP_FN double glpgp_quad4(int q, double *l0, double *l1, double *l2)
{
    const double a1 = 0.445948490915964886318, w1 = 0.223381589678011065396;
    const double a2 = 0.091576213509770743460;
    double a = q < 3 ? a1 : a2;
    double b = 1.0 - 2.0 * a;
    int r = q % 3;
    *l0 = r == 0 ? b : a;
    *l1 = r == 1 ? b : a;
    *l2 = r == 2 ? b : a;
    return q < 3 ? w1 : (1.0 / 3.0 - w1);
}

/* Quadrature point q of the penalty's rule (glpgp_quad4) in one triangle:
 * barycentrics l[0..2], z_q = (*x, *y) interpolated from the corners and
 * *s = |z_q|^2 - 1; returns the weight w_q. One copy of the arithmetic for
 * the energy and gradients below, so their values agree bit for bit. */
GLPGP_FN double glpgp_pen_point(int q, const double *zr, const double *zi, double *l, double *x, double *y,
                                double *s)
{
    double w = glpgp_quad4(q, &l[0], &l[1], &l[2]);
    *x = l[0] * zr[0] + l[1] * zr[1] + l[2] * zr[2];
    *y = l[0] * zi[0] + l[1] * zi[1] + l[2] * zi[2];
    *s = *x * *x + *y * *y - 1.0;
    return w;
}

/* Penalty energy of one triangle: A/(4 eps^2) sum_q w_q (|z_q|^2 - 1)^2.
 * area = triangle area, inv4e2 = 1/(4 eps^2), zr/zi the corner values. */
GLPGP_FN double glpgp_pen_energy(double area, double inv4e2, const double *zr, const double *zi)
{
    double e = 0.0;
    for (int q = 0; q < 6; q++) {
        double l[3], x, y, s;
        double w = glpgp_pen_point(q, zr, zi, l, &x, &y, &s);
        e += w * s * s;
    }
    return area * inv4e2 * e;
}

/* Penalty gradient at corner a: (*gr, *gi) = dP_T / d(Re z_a, Im z_a). */
GLPGP_FN void glpgp_pen_grad(double area, double inv4e2, const double *zr, const double *zi,
                             int a, double *gr, double *gi)
{
    double sr = 0.0, si = 0.0;
    for (int q = 0; q < 6; q++) {
        double l[3], x, y, s;
        double w = glpgp_pen_point(q, zr, zi, l, &x, &y, &s);
        sr += w * s * x * l[a];
        si += w * s * y * l[a];
    }
    *gr = 4.0 * area * inv4e2 * sr;
    *gi = 4.0 * area * inv4e2 * si;
}

/* Penalty gradient at the three corners and the penalty energy of one
 * triangle at once: (g[2a], g[2a+1]) as glpgp_pen_grad(.., a, ..) stores it,
 * *e as glpgp_pen_energy returns it, with exactly their arithmetic (the
 * quadrature values once per triangle instead of once per corner), so the
 * values agree bit for bit. For a loop over triangles that scatters each
 * corner's gradient to its vertex in increasing triangle order (the
 * reference backend's gradient: the sums of the per-vertex gather). */
GLPGP_FN void glpgp_pen_grad_tri(double area, double inv4e2, const double *zr, const double *zi, double *g,
                                 double *e)
{
    double sr[3] = {0.0, 0.0, 0.0}, si[3] = {0.0, 0.0, 0.0}, en = 0.0;
    for (int q = 0; q < 6; q++) {
        double l[3], x, y, s;
        double w = glpgp_pen_point(q, zr, zi, l, &x, &y, &s);
        en += w * s * s;
        for (int a = 0; a < 3; a++) {
            sr[a] += w * s * x * l[a];
            si[a] += w * s * y * l[a];
        }
    }
    for (int a = 0; a < 3; a++) {
        g[2 * a] = 4.0 * area * inv4e2 * sr[a];
        g[2 * a + 1] = 4.0 * area * inv4e2 * si[a];
    }
    *e = area * inv4e2 * en;
}

/* The 2x2 matrix M_q / 4 of variant `hess` (see the top) at the quadrature
 * value z_q = (x, y): (*h00, *h01 = *h10, *h11). */
GLPGP_FN void glpgp_pen_hess_point(int hess, double x, double y, double *h00, double *h01, double *h11)
{
    double r2 = x * x + y * y;
    if (hess == GLPGP_HESS_PAPER) {
        *h00 = 3.0 * x * x;
        *h01 = 2.0 * x * y;
        *h11 = 3.0 * y * y;
    } else if (hess == GLPGP_HESS_EXACT || (hess == GLPGP_HESS_MIXED && r2 >= 0.5)) {
        *h00 = r2 - 1.0 + 2.0 * x * x;
        *h01 = 2.0 * x * y;
        *h11 = r2 - 1.0 + 2.0 * y * y;
    } else {
        /* eigen-decomposition of s I + 2 z z^T: along zhat 3r2-1, across r2-1 */
        double lp = 3.0 * r2 - 1.0, lt = r2 - 1.0;
        lp = lp > 0.0 ? lp : 0.0;
        lt = lt > 0.0 ? lt : 0.0;
        if (r2 > 0.0) {
            double ux = x * x / r2, uxy = x * y / r2, uy = y * y / r2;
            *h00 = lp * ux + lt * (1.0 - ux);
            *h01 = (lp - lt) * uxy;
            *h11 = lp * uy + lt * (1.0 - uy);
        } else {
            *h00 = 0.0;
            *h01 = 0.0;
            *h11 = 0.0;
        }
    }
}

/* Penalty Hessian block (a,b) (2x2, row-major into m[4]) of variant `hess`. */
GLPGP_FN void glpgp_pen_hess(int hess, double area, double inv4e2, const double *zr,
                             const double *zi, int a, int b, double *m)
{
    double m0 = 0.0, m1 = 0.0, m2 = 0.0, m3 = 0.0;
    for (int q = 0; q < 6; q++) {
        double l[3], x, y, s2;
        double w = glpgp_pen_point(q, zr, zi, l, &x, &y, &s2); /* s2 unused here */
        double f = w * l[a] * l[b];
        double h00, h01, h11;
        glpgp_pen_hess_point(hess, x, y, &h00, &h01, &h11);
        m0 += f * h00;
        m1 += f * h01;
        m3 += f * h11;
    }
    m2 = m1;
    double c = 4.0 * area * inv4e2;
    m[0] = c * m0;
    m[1] = c * m1;
    m[2] = c * m2;
    m[3] = c * m3;
}

/* The three penalty Hessian blocks (a,0), (a,1), (a,2) of one triangle at once:
 * block (a,b) -> m[3b] = m_00, m[3b+1] = m_01 = m_10, m[3b+2] = m_11.
 * The quadrature values z_q and M_q are evaluated once for the three blocks
 * (glpgp_pen_hess evaluates them per block); every block is computed with
 * exactly the arithmetic of glpgp_pen_hess(hess, .., a, b, ..), so the two
 * agree bit for bit (tests/backends/test_element.c checks it). */
GLPGP_FN void glpgp_pen_hess_row(int hess, double area, double inv4e2, const double *zr,
                                 const double *zi, int a, double *m)
{
    double s[9];
    for (int k = 0; k < 9; k++) s[k] = 0.0;
    for (int q = 0; q < 6; q++) {
        double l[3], x, y, s2;
        double w = glpgp_pen_point(q, zr, zi, l, &x, &y, &s2); /* s2 unused here */
        double h00, h01, h11;
        glpgp_pen_hess_point(hess, x, y, &h00, &h01, &h11);
        const double wa = w * l[a];
        for (int b = 0; b < 3; b++) {
            /* f = w l_a l_b, the same product order as glpgp_pen_hess */
            const double f = wa * l[b];
            s[3 * b] += f * h00;
            s[3 * b + 1] += f * h01;
            s[3 * b + 2] += f * h11;
        }
    }
    double c = 4.0 * area * inv4e2;
    for (int k = 0; k < 9; k++) m[k] = c * s[k];
}

#endif
