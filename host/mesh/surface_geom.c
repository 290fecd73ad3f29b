/* mesh/surface_geom.c: the discrete differential geometry of a validated
 * surface (glpgp/surface.h): each triangle's plane and corner coordinates,
 * corner angles, vertex normals and frames (the fan of corner angles scaled
 * to 2 pi inside), the rotation vertex frame -> triangle frame per corner,
 * the Levi-Civita connection per half-edge (Knoeppel et al. 2013), the
 * holonomy per triangle, dihedral angles; boundary loops; the mapping of
 * vertex-frame angles to 3D vectors and back; feature edges. */
#include "glpgp/kinds.h"
#include "glpgp/surface.h"

#include "surface_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TWO_PI (2.0 * GLPGP_PI)

/* Principal value of an angle in (-pi, pi]. */
static double principal(double a)
{
    double d = remainder(a, TWO_PI);
    return d <= -GLPGP_PI ? d + TWO_PI : d;
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void unit3(double *a)
{
    const double n = sqrt(dot3(a, a));
    if (n > 0.0) {
        a[0] /= n;
        a[1] /= n;
        a[2] /= n;
    }
}

glpgp_status glpgp_surface_loops(glpgp_mesh *m, const int *next)
{
    const int nv = m->nv;
    int nb = 0, nl = 0;
    for (int v = 0; v < nv; v++) nb += next[v] >= 0;
    GLPGP_CHECK(glpgp_calloc((size_t)nv, 1, &m->on_boundary));
    GLPGP_CHECK(glpgp_malloc((size_t)nb + 1, sizeof(int), &m->loop_vertices));
    /* at most nb / 3 loops (each has 3 vertices at least; a lone triangle has one) */
    GLPGP_CHECK(glpgp_malloc((size_t)nb / 3 + 2, sizeof(int), &m->loop_start));
    int pos = 0;
    for (int v0 = 0; v0 < nv; v0++) {
        if (next[v0] < 0 || m->on_boundary[v0]) continue;
        m->loop_start[nl++] = pos;
        int v = v0;
        do {
            if (m->on_boundary[v] || pos >= nb)
                return GLPGP_FAIL(GLPGP_ERR_MESH, "boundary is not simple at vertex %d", v);
            m->on_boundary[v] = 1;
            m->loop_vertices[pos++] = v;
            v = next[v];
            if (v < 0) return GLPGP_FAIL(GLPGP_ERR_MESH, "boundary chain ends at vertex %d", m->loop_vertices[pos - 1]);
        } while (v != v0);
    }
    m->loop_start[nl] = pos;
    m->nloops = nl;
    return GLPGP_OK;
}

/* Per triangle: its plane's axes, the corner coordinates in it, the corner
 * angles; the mean edge length. */
static void triangle_planes(glpgp_mesh *m, glpgp_surface *s)
{
    const double *X = m->xyz;
    double esum = 0.0;
    for (int t = 0; t < m->nt; t++) {
        const int *v = m->tri + 3 * t;
        const double *p0 = X + 3 * v[0], *p1 = X + 3 * v[1], *p2 = X + 3 * v[2];
        double *E1 = s->tframe + 9 * t, *E2 = E1 + 3, *N = E1 + 6;
        const double d1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        const double d2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        memcpy(E1, d1, sizeof d1);
        unit3(E1);
        glpgp_tri_normal3(p0, p1, p2, N);
        unit3(N);
        E2[0] = N[1] * E1[2] - N[2] * E1[1];
        E2[1] = N[2] * E1[0] - N[0] * E1[2];
        E2[2] = N[0] * E1[1] - N[1] * E1[0];
        double *q = s->txy + 6 * t;
        q[0] = 0.0;
        q[1] = 0.0;
        q[2] = sqrt(dot3(d1, d1));
        q[3] = 0.0;
        q[4] = dot3(d2, E1);
        q[5] = dot3(d2, E2);
        for (int a = 0; a < 3; a++) {
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            const double ux = q[2 * b] - q[2 * a], uy = q[2 * b + 1] - q[2 * a + 1];
            const double wx = q[2 * c] - q[2 * a], wy = q[2 * c + 1] - q[2 * a + 1];
            s->corner[3 * t + a] = atan2(ux * wy - uy * wx, ux * wx + uy * wy);
            if (s->twin[3 * t + a] < 3 * t + a) esum += sqrt(ux * ux + uy * uy); /* each edge once */
        }
    }
    m->mean_edge = s->nedges ? esum / s->nedges : 0.0;
}

/* Per vertex: angle sum, scale, normal; per corner the angle of its
 * outgoing edge in the vertex's frame (the fan walked from vstart); the
 * reference tangent. */
static void vertex_frames(glpgp_mesh *m, glpgp_surface *s)
{
    const double *X = m->xyz;
    memset(s->angle_sum, 0, (size_t)m->nv * sizeof(double));
    memset(s->vnormal, 0, (size_t)3 * m->nv * sizeof(double));
    for (int c = 0; c < 3 * m->nt; c++) {
        const int v = m->tri[c];
        const double *N = s->tframe + 9 * (c / 3) + 6;
        s->angle_sum[v] += s->corner[c];
        for (int k = 0; k < 3; k++) s->vnormal[3 * v + k] += s->corner[c] * N[k];
    }
    for (int v = 0; v < m->nv; v++) {
        unit3(s->vnormal + 3 * v);
        s->scale[v] = m->on_boundary[v] ? 1.0 : TWO_PI / s->angle_sum[v];
        /* the fan from vstart, counter-clockwise */
        int c = s->vstart[v];
        double th = 0.0;
        do {
            s->eangle[c] = th;
            th += s->scale[v] * s->corner[c];
            const int hin = c - c % 3 + (c % 3 + 2) % 3;
            c = s->twin[hin];
        } while (c >= 0 && c != s->vstart[v]);
        /* e_v: the reference (first outgoing) edge projected into the tangent plane */
        const int c0 = s->vstart[v];
        const int b = m->tri[c0 - c0 % 3 + (c0 % 3 + 1) % 3];
        const double *n = s->vnormal + 3 * v;
        double d[3] = {X[3 * b] - X[3 * v], X[3 * b + 1] - X[3 * v + 1], X[3 * b + 2] - X[3 * v + 2]};
        const double dn = dot3(d, n);
        for (int k = 0; k < 3; k++) d[k] -= dn * n[k];
        unit3(d);
        memcpy(s->vtangent + 3 * v, d, sizeof d);
    }
}

/* Per corner the rotation into its triangle; per half-edge the connection
 * and the dihedral angle; per triangle the holonomy. */
static void connection(glpgp_mesh *m, glpgp_surface *s)
{
    for (int t = 0; t < m->nt; t++) {
        const double *q = s->txy + 6 * t;
        double hol = 0.0;
        for (int a = 0; a < 3; a++) {
            const int c = 3 * t + a, b = (a + 1) % 3, v = m->tri[c], vb = m->tri[3 * t + b];
            const double sv = s->scale[v], al = s->corner[c];
            /* angle of the outgoing edge in t's plane */
            const double beta = atan2(q[2 * b + 1] - q[2 * a + 1], q[2 * b] - q[2 * a]);
            s->rot[c] = principal(beta - s->eangle[c] + 0.5 * al * (1.0 - sv));
            /* rho = theta_b(v) + pi - theta_v(b); theta_b(v) = the incoming edge of b's corner */
            const double thb = s->eangle[3 * t + b] + s->scale[vb] * s->corner[3 * t + b];
            s->conn[c] = principal(thb + GLPGP_PI - s->eangle[c]);
            hol += al * (sv - 1.0);
            const int g = s->twin[c];
            if (g < 0) {
                s->dihedral[c] = 0.0;
            } else {
                const double *N = s->tframe + 9 * t + 6, *M = s->tframe + 9 * (g / 3) + 6;
                const double x[3] = {N[1] * M[2] - N[2] * M[1], N[2] * M[0] - N[0] * M[2], N[0] * M[1] - N[1] * M[0]};
                s->dihedral[c] = atan2(sqrt(dot3(x, x)), dot3(N, M));
            }
        }
        s->holonomy[t] = hol;
    }
}

glpgp_status glpgp_surface_geometry(glpgp_mesh *m)
{
    glpgp_surface *s = m->surf;
    const size_t nv = (size_t)m->nv, nt = (size_t)m->nt;
    GLPGP_CHECK(glpgp_malloc(3 * nv, sizeof(double), &s->vnormal));
    GLPGP_CHECK(glpgp_malloc(3 * nv, sizeof(double), &s->vtangent));
    GLPGP_CHECK(glpgp_malloc(nv, sizeof(double), &s->angle_sum));
    GLPGP_CHECK(glpgp_malloc(nv, sizeof(double), &s->scale));
    GLPGP_CHECK(glpgp_malloc(3 * nt, sizeof(double), &s->corner));
    GLPGP_CHECK(glpgp_malloc(3 * nt, sizeof(double), &s->eangle));
    GLPGP_CHECK(glpgp_malloc(3 * nt, sizeof(double), &s->rot));
    GLPGP_CHECK(glpgp_malloc(3 * nt, sizeof(double), &s->conn));
    GLPGP_CHECK(glpgp_malloc(3 * nt, sizeof(double), &s->dihedral));
    GLPGP_CHECK(glpgp_malloc(6 * nt, sizeof(double), &s->txy));
    GLPGP_CHECK(glpgp_malloc(9 * nt, sizeof(double), &s->tframe));
    GLPGP_CHECK(glpgp_malloc(nt, sizeof(double), &s->holonomy));
    triangle_planes(m, s);
    vertex_frames(m, s);
    connection(m, s);
    return GLPGP_OK;
}

/* ---- queries --------------------------------------------------------------- */

void glpgp_surface_vertex_vector(const glpgp_mesh *m, int i, double c, double s, double *out)
{
    const glpgp_surface *g = m->surf;
    double psi = atan2(s, c);
    if (psi < 0.0) psi += TWO_PI;
    /* the corner whose sector holds psi (the last one whose outgoing edge is at or below it) */
    int k = g->vstart[i], best = k;
    do {
        if (g->eangle[k] <= psi) best = k;
        const int hin = k - k % 3 + (k % 3 + 2) % 3;
        k = g->twin[hin];
    } while (k >= 0 && k != g->vstart[i]);
    const int t = best / 3, a = best % 3, b = (a + 1) % 3;
    double d = (psi - g->eangle[best]) / g->scale[i];
    if (d > g->corner[best]) d = g->corner[best]; /* beyond a boundary fan: its last edge */
    const double *q = g->txy + 6 * t, *E1 = g->tframe + 9 * t, *E2 = E1 + 3;
    const double beta = atan2(q[2 * b + 1] - q[2 * a + 1], q[2 * b] - q[2 * a]) + d;
    const double cb = cos(beta), sb = sin(beta);
    for (int j = 0; j < 3; j++) out[j] = cb * E1[j] + sb * E2[j];
}

double glpgp_surface_vertex_angle(const glpgp_mesh *m, int i, const double *v)
{
    const glpgp_surface *g = m->surf;
    /* per corner: v in its triangle's plane (qual: the share of |v|^2 there),
     * its angle delta from the outgoing edge clamped into the sector [0, alpha]
     * (out: by how much it was outside); the corner with the least out (1e-6
     * ties: the most in-plane) gives theta + s delta */
    const double vv = dot3(v, v);
    if (!(vv > 0.0)) return 0.0;
    int k = g->vstart[i];
    double best_out = HUGE_VAL, best_qual = -1.0, ang = 0.0;
    do {
        const int t = k / 3, a = k % 3, b = (a + 1) % 3;
        const double *q = g->txy + 6 * t, *E1 = g->tframe + 9 * t, *E2 = E1 + 3;
        const double x = dot3(v, E1), y = dot3(v, E2), qual = (x * x + y * y) / vv;
        const double beta = atan2(q[2 * b + 1] - q[2 * a + 1], q[2 * b] - q[2 * a]);
        double d = principal(atan2(y, x) - beta), out = 0.0;
        const double al = g->corner[k];
        if (d < 0.0 || d > al) { /* outside: the nearer sector edge */
            const double e0 = fabs(d), e1 = fabs(principal(d - al));
            out = e0 < e1 ? e0 : e1;
            d = e0 < e1 ? 0.0 : al;
        }
        if (out < best_out - 1e-6 || (fabs(out - best_out) <= 1e-6 && qual > best_qual)) {
            best_out = out;
            best_qual = qual;
            ang = g->eangle[k] + g->scale[i] * d;
        }
        const int hin = k - k % 3 + (k % 3 + 2) % 3;
        k = g->twin[hin];
    } while (k >= 0 && k != g->vstart[i]);
    ang = fmod(ang, 2.0 * GLPGP_PI);
    return ang < 0.0 ? ang + 2.0 * GLPGP_PI : ang;
}

int glpgp_surface_features(const glpgp_mesh *m, double feature_deg, unsigned char *flag)
{
    const glpgp_surface *g = m->surf;
    const double lim = feature_deg * GLPGP_PI / 180.0;
    int n = 0;
    for (int h = 0; h < 3 * m->nt; h++) {
        flag[h] = g->twin[h] >= 0 && g->dihedral[h] > lim;
        if (flag[h] && g->twin[h] < h) n++;
    }
    return n;
}

double glpgp_surface_total_holonomy(const glpgp_mesh *m)
{
    double s = 0.0;
    for (int t = 0; t < m->nt; t++) s += m->surf->holonomy[t];
    return s;
}
