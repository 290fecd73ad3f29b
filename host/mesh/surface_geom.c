/* mesh/surface_geom.c: the discrete differential geometry of a validated
 * surface (glpgp/surface.h): each triangle's plane and corner coordinates,
 * corner angles, vertex normals and frames (the fan of corner angles scaled
 * to 2 pi inside), the rotation vertex frame -> triangle frame per corner,
 * the Levi-Civita connection per half-edge (Knoeppel et al. 2013), the
 * holonomy per triangle, dihedral angles; boundary loops; the mapping of
 * vertex-frame angles to 3D vectors and back; feature edges. */
#include "glpgp/kinds.h"
#include "glpgp/surface.h"
#include "glpgp/util.h"

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

/* Feature edges. A candidate (dihedral angle above the limit) is a crease
 * when
 *  1. it separates its two sides locally: the ball about its midpoint of
 *     CREASE_REACH times the mean length of its two triangles' edges holds
 *     no walk from one of its triangles to the other that crosses no
 *     candidate (an isolated kink of a noisy scan is walked around in one
 *     vertex's fan; a crease runs through the ball, or ends on a boundary
 *     or another crease; a crease's free end loses about CREASE_REACH
 *     edges; one pass, so a dangling crease is trimmed, not eaten), and
 *  2. it keeps its angle at that scale: the mean normals of the ball's two
 *     sides differ by more than CREASE_SIDE times the limit (a cluster of
 *     noise averages out; a crease between flat faces keeps its dihedral).
 *     The sides are the ball's triangles reached from each of the edge's
 *     triangles without crossing an edge that passed test 1 and is sharper
 *     than CREASE_BLOCK_DEG (or the limit, if higher): a coarse CAD mesh's
 *     faces beyond another sharp crease (the far walls of a hole) do not
 *     blur the sides' normals, and a sharp kink of noise does not wall a
 *     side in.
 * 2b. unless it is sharper than CREASE_BLOCK_DEG, its sides are flat
 *     beside it: their angle exceeds CREASE_FLAT times the larger spread
 *     of the normals of either side's ball triangles reached without
 *     crossing a candidate (a crease between flat or gently curved faces
 *     stands out; the kinks of a coarsely faceted curved surface, as
 *     marching cubes give, bend no more than the faces beside them).
 *  3. it belongs to a crease of CREASE_MIN_EDGES edges or more (edges
 *     joined at their ends), or to one that reaches the boundary: in heavy
 *     noise a kink walled in by other kinks passes test 1, and at test 2's
 *     tail a lone one keeps its angle.
 * CREASE_CAP bounds a walk (a fine mesh about a long edge): the edge stays
 * a candidate in test 1, and test 2 reads the triangles walked. */
#define CREASE_REACH 2.5
#define CREASE_SIDE 0.8
#define CREASE_FLAT 2.0
#define CREASE_MIN_EDGES 3
#define CREASE_BLOCK_DEG 70.0
#define CREASE_CAP 4096

static void tri_centroid(const glpgp_mesh *m, int t, double *c)
{
    const int *v = m->tri + 3 * t;
    for (int k = 0; k < 3; k++) c[k] = (m->xyz[3 * v[0] + k] + m->xyz[3 * v[1] + k] + m->xyz[3 * v[2] + k]) / 3.0;
}

static double edge_len(const glpgp_mesh *m, int h)
{
    const double *a = m->xyz + 3 * m->tri[h], *b = m->xyz + 3 * m->tri[h - h % 3 + (h % 3 + 1) % 3];
    const double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    return sqrt(dot3(d, d));
}

static void sub3(const double *a, const double *b, double *d)
{
    for (int k = 0; k < 3; k++) d[k] = a[k] - b[k];
}

/* The ball of half-edge h: its midpoint and CREASE_REACH times the mean
 * length of its two triangles' edges. */
static double edge_ball(const glpgp_mesh *m, int h, double *mid)
{
    const double *a = m->xyz + 3 * m->tri[h], *b = m->xyz + 3 * m->tri[h - h % 3 + (h % 3 + 1) % 3];
    const int t1 = h / 3, t2 = m->surf->twin[h] / 3;
    double len = 0.0;
    for (int k = 0; k < 3; k++) {
        mid[k] = (a[k] + b[k]) / 2;
        len += edge_len(m, 3 * t1 + k) + edge_len(m, 3 * t2 + k);
    }
    return CREASE_REACH * len / 6.0;
}

/* The triangles of the ball (mid, r) reachable from triangle t without
 * crossing h's edge or a blocked half-edge (block NULL: none):
 * marked tag in stamp, listed in queue; returns their number. */
static int ball_region(const glpgp_mesh *m, const unsigned char *block, int h, int t, const double *mid, double r,
                       int tag, int *stamp, int *queue)
{
    const int *twin = m->surf->twin;
    int head = 0, tail = 0;
    stamp[t] = tag;
    queue[tail++] = t;
    while (head < tail) {
        const int s = queue[head++];
        for (int k = 3 * s; k < 3 * s + 3 && tail < CREASE_CAP; k++) {
            if (twin[k] < 0 || k == h || k == twin[h] || (block && block[k])) continue;
            const int u = twin[k] / 3;
            if (stamp[u] == tag) continue;
            double c[3];
            tri_centroid(m, u, c);
            sub3(c, mid, c);
            if (dot3(c, c) > r * r) continue;
            stamp[u] = tag;
            queue[tail++] = u;
        }
    }
    return tail;
}

/* Twice the area-weighted normal of triangle t. */
static void tri_normal(const glpgp_mesh *m, int t, double *n)
{
    const int *v = m->tri + 3 * t;
    double u[3], w[3];
    sub3(m->xyz + 3 * v[1], m->xyz + 3 * v[0], u);
    sub3(m->xyz + 3 * v[2], m->xyz + 3 * v[0], w);
    n[0] = u[1] * w[2] - u[2] * w[1];
    n[1] = u[2] * w[0] - u[0] * w[2];
    n[2] = u[0] * w[1] - u[1] * w[0];
}

/* The angle between the two sides of candidate half-edge h at the scale of
 * its ball: the area-weighted mean normals of the ball's triangles reached
 * from either of its triangles without crossing a blocked edge; one reached
 * from both sides goes by its centroid's offset from the midpoint along the
 * difference of the two triangles' inward directions. A crease keeps its
 * angle; a kink of noise averages out. */
static double side_angle(const glpgp_mesh *m, const unsigned char *block, int h, int *stamp, int *queue)
{
    const int t1 = h / 3, t2 = m->surf->twin[h] / 3, tag = -(h + 1);
    const double *a = m->xyz + 3 * m->tri[h], *b = m->xyz + 3 * m->tri[h - h % 3 + (h % 3 + 1) % 3];
    double mid[3], e[3], c1[3], c2[3], d1[3], d2[3], dir[3];
    const double r = edge_ball(m, h, mid);
    sub3(b, a, e);
    unit3(e);
    tri_centroid(m, t1, c1);
    tri_centroid(m, t2, c2);
    sub3(c1, mid, d1);
    sub3(c2, mid, d2);
    const double p1 = dot3(d1, e), p2 = dot3(d2, e);
    for (int k = 0; k < 3; k++) {
        d1[k] -= p1 * e[k];
        d2[k] -= p2 * e[k];
    }
    unit3(d1);
    unit3(d2);
    sub3(d1, d2, dir);
    int *stamp2 = stamp + m->nt, *queue2 = queue + CREASE_CAP;
    const int n1 = ball_region(m, block, h, t1, mid, r, tag, stamp, queue);
    const int n2 = ball_region(m, block, h, t2, mid, r, tag, stamp2, queue2);
    double s1[3] = {0, 0, 0}, s2[3] = {0, 0, 0}, n[3], c[3];
    for (int i = 0; i < n1 + n2; i++) {
        const int t = i < n1 ? queue[i] : queue2[i - n1];
        const int both = stamp[t] == tag && stamp2[t] == tag;
        if (both && i >= n1) continue; /* counted once */
        int one = i < n1;
        if (both) {
            tri_centroid(m, t, c);
            sub3(c, mid, c);
            one = dot3(c, dir) >= 0.0;
        }
        tri_normal(m, t, n);
        double *side = one ? s1 : s2;
        for (int k = 0; k < 3; k++) side[k] += n[k];
    }
    double x[3];
    x[0] = s1[1] * s2[2] - s1[2] * s2[1];
    x[1] = s1[2] * s2[0] - s1[0] * s2[2];
    x[2] = s1[0] * s2[1] - s1[1] * s2[0];
    return atan2(sqrt(dot3(x, x)), dot3(s1, s2));
}

/* The normal spread of candidate half-edge h's sides: per side, the ball's
 * triangles reached from h's triangle there without crossing a candidate
 * (cand); the larger of the two root-mean-square angles between their
 * normals and their area-weighted mean normal (from |sum n| / sum |n|). */
static double side_spread(const glpgp_mesh *m, const unsigned char *cand, int h, int *stamp, int *queue)
{
    double mid[3], worst = 0.0;
    const double r = edge_ball(m, h, mid);
    for (int side = 0; side < 2; side++) {
        const int t = side ? m->surf->twin[h] / 3 : h / 3, tag = -(3 * m->nt + 2 * h + side + 1);
        const int n = ball_region(m, cand, h, t, mid, r, tag, stamp, queue);
        double s[3] = {0, 0, 0}, a = 0.0, nn[3];
        for (int i = 0; i < n; i++) {
            tri_normal(m, queue[i], nn);
            for (int k = 0; k < 3; k++) s[k] += nn[k];
            a += sqrt(dot3(nn, nn));
        }
        if (a > 0.0) worst = fmax(worst, 1.0 - sqrt(dot3(s, s)) / a);
    }
    return sqrt(2.0 * worst);
}

/* Test 1 fails: candidate half-edge h's triangles are joined inside its
 * ball without crossing a candidate (cand). A walk that reaches
 * CREASE_CAP triangles first keeps the edge. */
static int walked_around(const glpgp_mesh *m, const unsigned char *cand, int h, int *stamp, int *queue)
{
    double mid[3];
    const double r = edge_ball(m, h, mid);
    ball_region(m, cand, h, h / 3, mid, r, h + 1, stamp, queue);
    return stamp[m->surf->twin[h] / 3] == h + 1;
}

/* Tests 2 and 2b for candidate half-edge h (cand: the candidates; walls:
 * the sides' walls): its sides' angle exceeds min_angle and, unless its
 * dihedral exceeds CREASE_BLOCK_DEG, CREASE_FLAT times their spread. */
static int keeps_angle(const glpgp_mesh *m, const unsigned char *walls, const unsigned char *cand, int h,
                       double min_angle, int *stamp, int *queue)
{
    const double ang = side_angle(m, walls, h, stamp, queue);
    if (ang <= min_angle) return 0;
    if (m->surf->dihedral[h] > CREASE_BLOCK_DEG * GLPGP_PI / 180.0) return 1;
    return ang > CREASE_FLAT * side_spread(m, cand, h, stamp, queue);
}

/* Clears the candidates (flag) that fail test 1 (walls NULL) or tests 2
 * and 2b (keeps_angle with these walls and min_angle), judged against the
 * candidates as they were before this pass; returns how many it cleared. */
static int crease_pass(const glpgp_mesh *m, unsigned char *flag, const unsigned char *walls, double min_angle,
                       int *stamp, int *queue, int *drop)
{
    const int *twin = m->surf->twin;
    int nd = 0;
    for (int h = 0; h < 3 * m->nt; h++) {
        if (!flag[h] || twin[h] < h) continue;
        const int fails = walls ? !keeps_angle(m, walls, flag, h, min_angle, stamp, queue)
                                : walked_around(m, flag, h, stamp, queue);
        if (fails) drop[nd++] = h;
    }
    for (int i = 0; i < nd; i++) flag[drop[i]] = flag[twin[drop[i]]] = 0;
    return nd;
}

/* A refined surface's features are its input's (m->surf->origin): a
 * refined half-edge on a side of its input triangle (both ends with a zero
 * barycentric coordinate at the same corner) takes that side's flag. */
static glpgp_status features_from_origin(const glpgp_mesh *m, double feature_deg, unsigned char *flag, int *count)
{
    const glpgp_surface *g = m->surf;
    const glpgp_mesh *mi = g->origin;
    unsigned char *fi = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)3 * mi->nt, 1, &fi));
    glpgp_status st = glpgp_surface_features(mi, feature_deg, fi, NULL);
    int n = 0;
    for (int h = 0; h < 3 * m->nt && st == GLPGP_OK; h++) {
        const int t = h / 3, a = h % 3, b = (a + 1) % 3;
        const double *ba = g->obary + 9 * t + 3 * a, *bb = g->obary + 9 * t + 3 * b;
        flag[h] = 0;
        if (g->twin[h] < 0) continue;
        for (int k = 0; k < 3; k++)
            if (ba[k] < 1e-12 && bb[k] < 1e-12) flag[h] = fi[3 * g->otri[t] + (k + 1) % 3];
        n += flag[h] && g->twin[h] < h;
    }
    free(fi);
    if (count && st == GLPGP_OK) *count = n;
    return st;
}

/* Test 3: clears the creases of fewer than CREASE_MIN_EDGES edges that do
 * not reach the boundary; parent, size: nv ints each. Returns how many it
 * cleared. */
static int short_creases(const glpgp_mesh *m, unsigned char *flag, int *parent, int *size)
{
    const int *twin = m->surf->twin;
    int nd = 0;
    for (int v = 0; v < m->nv; v++) {
        parent[v] = v;
        size[v] = 0;
    }
    for (int h = 0; h < 3 * m->nt; h++)
        if (flag[h] && twin[h] > h) {
            const int a = glpgp_uf_find(parent, m->tri[h]);
            const int b = glpgp_uf_find(parent, m->tri[h - h % 3 + (h % 3 + 1) % 3]);
            if (a != b) {
                parent[a] = b;
                size[b] += size[a];
            }
            size[b]++;
        }
    for (int v = 0; v < m->nv; v++) /* a boundary vertex makes its crease long enough */
        if (m->on_boundary[v]) size[glpgp_uf_find(parent, v)] += CREASE_MIN_EDGES;
    for (int h = 0; h < 3 * m->nt; h++)
        if (flag[h] && twin[h] > h && size[glpgp_uf_find(parent, m->tri[h])] < CREASE_MIN_EDGES) {
            flag[h] = flag[twin[h]] = 0;
            nd++;
        }
    return nd;
}

glpgp_status glpgp_surface_features(const glpgp_mesh *m, double feature_deg, unsigned char *flag, int *count)
{
    const glpgp_surface *g = m->surf;
    if (g->origin && g->otri && g->obary) return features_from_origin(m, feature_deg, flag, count);
    const double lim = feature_deg * GLPGP_PI / 180.0, block = fmax(lim, CREASE_BLOCK_DEG * GLPGP_PI / 180.0);
    int *stamp = NULL, *queue = NULL, *drop = NULL, n = 0;
    unsigned char *sharp = NULL;
    for (int h = 0; h < 3 * m->nt; h++) {
        flag[h] = g->twin[h] >= 0 && g->dihedral[h] > lim;
        n += flag[h] && g->twin[h] < h;
    }
    if (count) *count = n;
    if (!n) return GLPGP_OK;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * (m->nt > m->nv ? m->nt : m->nv), sizeof(int), &stamp), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(2 * CREASE_CAP, sizeof(int), &queue), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n, sizeof(int), &drop), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * m->nt, 1, &sharp), done);
    n -= crease_pass(m, flag, NULL, 0.0, stamp, queue, drop);
    for (int h = 0; h < 3 * m->nt; h++) sharp[h] = flag[h] && g->dihedral[h] > block;
    n -= crease_pass(m, flag, sharp, CREASE_SIDE * lim, stamp, queue, drop);
    n -= short_creases(m, flag, stamp, stamp + m->nv);
    if (count) *count = n;
done:
    free(stamp);
    free(queue);
    free(drop);
    free(sharp);
    return st;
}

int glpgp_surface_edges_above(const glpgp_mesh *m, double feature_deg)
{
    const glpgp_surface *g = m->surf;
    const double lim = feature_deg * GLPGP_PI / 180.0;
    int n = 0;
    for (int h = 0; h < 3 * m->nt; h++) n += g->twin[h] > h && g->dihedral[h] > lim;
    return n;
}

double glpgp_surface_defect_rms(const glpgp_mesh *m)
{
    double s = 0.0;
    int n = 0;
    for (int v = 0; v < m->nv; v++)
        if (!m->on_boundary[v]) {
            const double d = TWO_PI - m->surf->angle_sum[v];
            s += d * d;
            n++;
        }
    return n ? sqrt(s / n) : 0.0;
}

double glpgp_surface_total_holonomy(const glpgp_mesh *m)
{
    double s = 0.0;
    for (int t = 0; t < m->nt; t++) s += m->surf->holonomy[t];
    return s;
}
