/* quads/coarse_surface.c: the coarse last resort on a surface
 * (glpgp_quads_surface_fallback_coarse, glpgp/quads.h): the input triangulation
 * coarsened by half-edge collapses to edges of about 2 h, then every
 * triangle split into three quads (centroid and side midpoints, moved onto
 * the surface; a boundary side's midpoint stays on its chord, and so do
 * the new points of a quad the move folds). A collapse v -> u moves no
 * vertex and is made only when
 *  - v is free (on no boundary or sharp feature edge), or v is inside one
 *    boundary or feature curve (two such edges) and (v, u) is one of them,
 *    where the curve turns by under 30 degrees or (tolerant) the new edge
 *    passes within 0.1 h of v (a staircase's or a jagged rim's teeth):
 *    corners stay, curves stay within the tolerance;
 *  - the link condition holds (the common neighbours of u and v are the
 *    opposite corners of their one or two triangles), which keeps the
 *    surface manifold with its topology, and no triangle is left hanging;
 *  - every new triangle keeps its normal within 72 degrees of the one
 *    before and of the surface's under it, its smallest angle above
 *    min(amin, the smallest before) (17 degrees, then 20 when that is not
 *    valid: quads_surface.c), its edges under 1.3 x 2 h, and samples of it
 *    within 0.2 h of the input surface.
 * Tolerant, after each pass's collapses and flips, a tangential relaxation
 * moves each free vertex towards its ring's mean, onto the input surface,
 * where that raises its triangles' smallest angle (and they pass the tests
 * above): the angle floor is what stops most collapses, and relaxed
 * triangles let the next pass go on (bench/results/surface_last_resort.md).
 * Shortest edges first, in passes until none collapses, flips or moves. The
 * caller checks the quads and falls back to the stricter rules, then to
 * the input's own triangles, when they fail. */
#include "quads_surface.h"
#include "vec3.h"

#include "repair.h"

#include "glpgp/kinds.h"
#include "glpgp/surface.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>


#define CURVE_TOL 0.1 /* a curve's vertex may go where the new edge passes this near it (of h) */

typedef struct cz {
    const glpgp_mesh *m;
    const glpgp_qs_proj *P;
    double h, L, amin;    /* amin: the smallest angle a new triangle may have (radians; unless one
                             before was smaller) */
    int *tri;             /* 3 nt, a working copy */
    unsigned char *flag;  /* 3 nt: half-edge slot on a boundary or feature edge */
    unsigned char *alive; /* nt */
    int **vt, *vn, *vcap; /* per vertex: its triangles (pruned on use) */
    int *mark, stamp;     /* per vertex scratch */
    int *touched, pass;   /* per vertex: the last pass its triangles changed in */
    double *xyz;          /* 3 nv: the vertices' places (the input's, moved along it by relax) */
    int tolerant;         /* the curves' teeth cut within CURVE_TOL, the relaxation */
} cz;

static void tri_normal(const double *a, const double *b, const double *c, double *n)
{
    double e1[3], e2[3];
    sub3(b, a, e1);
    sub3(c, a, e2);
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const double l = sqrt(dot3(n, n));
    if (l > 0)
        for (int d = 0; d < 3; d++) n[d] /= l;
}
static double min_angle(const double *p0, const double *p1, const double *p2)
{
    const double *p[3] = {p0, p1, p2};
    double m = GLPGP_PI;
    for (int k = 0; k < 3; k++) {
        double e1[3], e2[3];
        sub3(p[(k + 1) % 3], p[k], e1);
        sub3(p[(k + 2) % 3], p[k], e2);
        const double l = sqrt(dot3(e1, e1) * dot3(e2, e2));
        m = fmin(m, l > 0 ? acos(fmax(-1.0, fmin(1.0, dot3(e1, e2) / l))) : 0.0);
    }
    return m;
}
static const double *X(const cz *c, int v) { return c->xyz + 3 * v; }

/* v's alive triangles (the list pruned of dead ones and of those no longer v's). */
static int ring(cz *c, int v, int **out)
{
    int n = 0;
    for (int i = 0; i < c->vn[v]; i++) {
        const int t = c->vt[v][i];
        if (c->alive[t] && (c->tri[3 * t] == v || c->tri[3 * t + 1] == v || c->tri[3 * t + 2] == v)) c->vt[v][n++] = t;
    }
    c->vn[v] = n;
    *out = c->vt[v];
    return n;
}

/* The slot of the half-edge a -> b in an alive triangle other than ex (-1: none). */
static int slot_of(cz *c, int a, int b, int ex)
{
    int *r;
    const int n = ring(c, a, &r);
    for (int i = 0; i < n; i++) {
        const int t = r[i];
        if (t == ex) continue;
        for (int k = 0; k < 3; k++)
            if (c->tri[3 * t + k] == a && c->tri[3 * t + (k + 1) % 3] == b) return 3 * t + k;
    }
    return -1;
}

/* The flagged edges at v: their count and up to two other ends. */
static int flagged_at(cz *c, int v, int *ends)
{
    int *r, cnt = 0;
    const int n = ring(c, v, &r);
    c->stamp++;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            const int s = 3 * r[i] + k, a = c->tri[s], b = c->tri[3 * r[i] + (k + 1) % 3];
            if (!c->flag[s] || (a != v && b != v)) continue;
            const int w = a == v ? b : a;
            if (c->mark[w] == c->stamp) continue;
            c->mark[w] = c->stamp;
            if (cnt < 2) ends[cnt] = w;
            cnt++;
        }
    return cnt;
}

/* Whether v may move onto u: v free, or inside a boundary or feature
 * curve (two such edges) moving along one of them where the curve turns
 * there by under 30 degrees or, tolerant, the new edge passes within
 * CURVE_TOL h of v (a staircase's teeth, a jagged rim's: the curve kept at
 * the tolerance). */
static int movable(cz *c, int v, int u)
{
    int ends[2];
    const int nf = flagged_at(c, v, ends);
    if (nf == 0) return 1;
    if (nf != 2 || (ends[0] != u && ends[1] != u)) return 0;
    double a[3], b[3];
    sub3(X(c, v), X(c, ends[0]), a);
    sub3(X(c, ends[1]), X(c, v), b);
    const double l = sqrt(dot3(a, a) * dot3(b, b));
    if (l > 0 && dot3(a, b) / l > cos(30.0 * GLPGP_PI / 180.0)) return 1;
    if (!c->tolerant) return 0;
    const int w = ends[0] == u ? ends[1] : ends[0];
    double d[3], s[3]; /* v's distance to the segment (w, u) */
    sub3(X(c, u), X(c, w), d);
    sub3(X(c, v), X(c, w), s);
    const double dd = dot3(d, d), t = dd > 0 ? fmax(0.0, fmin(1.0, dot3(s, d) / dd)) : 0.0;
    for (int k = 0; k < 3; k++) s[k] -= t * d[k];
    return dot3(s, s) <= CURVE_TOL * CURVE_TOL * c->h * c->h;
}

/* The link condition for the edge (v, u): the common neighbours are the
 * opposite corners of the shared triangles. */
static int link_ok(cz *c, int v, int u, int nshared)
{
    int *r, common = 0;
    int n = ring(c, v, &r);
    c->stamp++;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) c->mark[c->tri[3 * r[i] + k]] = c->stamp;
    const int s1 = c->stamp;
    c->stamp++;
    n = ring(c, u, &r);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            const int w = c->tri[3 * r[i] + k];
            if (w == u || w == v || c->mark[w] < s1) continue;
            if (c->mark[w] == s1) common++;
            c->mark[w] = c->stamp;
        }
    return common == nshared;
}

/* Whether triangle (p0, p1, p2) is within 0.2 h of the surface and faces its way
 * where it is off it (samples; on a crease the nearest triangle may be either side's). */
static int near_surface(const cz *c, const double *p0, const double *p1, const double *p2)
{
    double n1[3];
    tri_normal(p0, p1, p2, n1);
    const double dmax = 0.2 * c->h;
    for (int a = 0; a <= 4; a++)
        for (int b = 0; a + b <= 4; b++) {
            double s[3], x[3], e[3];
            for (int d = 0; d < 3; d++) s[d] = ((4 - a - b) * p0[d] + a * p1[d] + b * p2[d]) / 4.0;
            const int tt = glpgp_qs_proj_nearest(c->P, s, x);
            sub3(s, x, e);
            if (tt < 0 || dot3(e, e) > dmax * dmax) return 0;
            if (dot3(e, e) > 1e-6 * dmax * dmax && dot3(n1, c->m->surf->tframe + 9 * tt + 6) < 0.3) return 0;
        }
    return 1;
}


/* The geometric tests of v -> u on v's triangles not shared with u. */
static int geometry_ok(cz *c, int v, int u, const int *r, int n)
{
    double worst_before = GLPGP_PI;
    for (int i = 0; i < n; i++) {
        const int *t = c->tri + 3 * r[i];
        worst_before = fmin(worst_before, min_angle(X(c, t[0]), X(c, t[1]), X(c, t[2])));
    }
    const double amin = fmin(c->amin, worst_before), lmax = 1.3 * c->L;
    for (int pass = 0; pass < 2; pass++) /* the cheap tests on every triangle first, then the samples */
    for (int i = 0; i < n; i++) {
        const int *t = c->tri + 3 * r[i];
        if (t[0] == u || t[1] == u || t[2] == u) continue; /* shared: removed */
        const double *p[3], *o[3];
        for (int k = 0; k < 3; k++) {
            o[k] = X(c, t[k]);
            p[k] = X(c, t[k] == v ? u : t[k]);
        }
        if (pass == 1) {
            if (!near_surface(c, p[0], p[1], p[2])) return 0;
            continue;
        }
        double n0[3], n1[3];
        tri_normal(o[0], o[1], o[2], n0);
        tri_normal(p[0], p[1], p[2], n1);
        if (dot3(n0, n1) < 0.3 || min_angle(p[0], p[1], p[2]) < amin) return 0;
        for (int k = 0; k < 3; k++) {
            double e[3];
            sub3(p[(k + 1) % 3], p[k], e);
            if (dot3(e, e) > lmax * lmax) return 0;
        }
    }
    return 1;
}

/* Collapse v onto u when allowed; returns 1 when done. */
static glpgp_status collapse(cz *c, int v, int u, int *done)
{
    *done = 0;
    int *r, shared[2], ns = 0;
    const int n = ring(c, v, &r);
    for (int i = 0; i < n; i++) {
        const int *t = c->tri + 3 * r[i];
        if (t[0] == u || t[1] == u || t[2] == u) {
            if (ns == 2) return GLPGP_OK;
            shared[ns++] = r[i];
        }
    }
    if (ns == 0 || !movable(c, v, u) || !link_ok(c, v, u, ns) || !geometry_ok(c, v, u, c->vt[v], n)) return GLPGP_OK;
    int of[2][2];
    for (int i = 0; i < ns; i++) { /* the two other sides of a shared triangle become one edge */
        const int t = shared[i];
        int x = -1;
        for (int k = 0; k < 3; k++)
            if (c->tri[3 * t + k] != u && c->tri[3 * t + k] != v) x = c->tri[3 * t + k];
        int e1 = -1, e2 = -1;
        for (int k = 0; k < 3; k++) {
            const int a = c->tri[3 * t + k], b = c->tri[3 * t + (k + 1) % 3];
            if ((a == v && b == x) || (a == x && b == v)) e1 = 3 * t + k;
            if ((a == u && b == x) || (a == x && b == u)) e2 = 3 * t + k;
        }
        of[i][0] = slot_of(c, c->tri[e1 - e1 % 3 + (e1 % 3 + 1) % 3], c->tri[e1], t);
        of[i][1] = slot_of(c, c->tri[e2 - e2 % 3 + (e2 % 3 + 1) % 3], c->tri[e2], t);
        if (of[i][0] < 0 && of[i][1] < 0) return GLPGP_OK; /* a triangle left hanging */
        const unsigned char f = c->flag[e1] | c->flag[e2] | (of[i][0] >= 0 ? c->flag[of[i][0]] : 0) |
                                (of[i][1] >= 0 ? c->flag[of[i][1]] : 0);
        for (int j = 0; j < 2; j++)
            if (of[i][j] >= 0) c->flag[of[i][j]] = f;
    }
    for (int i = 0; i < ns; i++) c->alive[shared[i]] = 0;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) c->touched[c->tri[3 * c->vt[v][i] + k]] = c->pass;
    for (int i = 0; i < n; i++) {
        const int t = c->vt[v][i];
        if (!c->alive[t]) continue;
        for (int k = 0; k < 3; k++)
            if (c->tri[3 * t + k] == v) c->tri[3 * t + k] = u;
        if (c->vn[u] == c->vcap[u]) {
            const int cap = 2 * c->vcap[u] + 8;
            int *g = realloc(c->vt[u], (size_t)cap * sizeof(int));
            if (!g) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "coarse last resort: out of memory");
            c->vt[u] = g;
            c->vcap[u] = cap;
        }
        c->vt[u][c->vn[u]++] = t;
    }
    c->vn[v] = 0;
    *done = 1;
    return GLPGP_OK;
}

/* Flip the edge of slot s (a -> b of t1 = (a, b, c), t2 = (b, a, d)) to
 * (c, d) when that raises the pair's smallest angle and keeps them on the
 * surface; returns 1 when flipped. */
static int flip(cz *c, int s)
{
    const int t1 = s / 3, k = s % 3;
    if (c->flag[s]) return 0;
    const int a = c->tri[s], b = c->tri[3 * t1 + (k + 1) % 3], cc = c->tri[3 * t1 + (k + 2) % 3];
    const int o = slot_of(c, b, a, t1);
    if (o < 0) return 0;
    const int t2 = o / 3, ko = o % 3, d = c->tri[3 * t2 + (ko + 2) % 3];
    if (d == cc) return 0;
    int *r;
    const int n = ring(c, cc, &r);
    for (int i = 0; i < n; i++) /* (c, d) must not be an edge already */
        for (int j = 0; j < 3; j++)
            if (c->tri[3 * r[i] + j] == d) return 0;
    const double before = fmin(min_angle(X(c, a), X(c, b), X(c, cc)), min_angle(X(c, b), X(c, a), X(c, d)));
    const double after = fmin(min_angle(X(c, cc), X(c, a), X(c, d)), min_angle(X(c, d), X(c, b), X(c, cc)));
    if (after < before + 1e-3) return 0;
    double n0[3], n1[3], m0[3], m1[3];
    tri_normal(X(c, a), X(c, b), X(c, cc), n0);
    tri_normal(X(c, b), X(c, a), X(c, d), n1);
    tri_normal(X(c, cc), X(c, a), X(c, d), m0);
    tri_normal(X(c, d), X(c, b), X(c, cc), m1);
    if (dot3(n0, n1) < 0.7 || dot3(m0, m1) < 0.7 || dot3(m0, n0) < 0.3 || dot3(m1, n1) < 0.3) return 0;
    if (!near_surface(c, X(c, cc), X(c, a), X(c, d)) || !near_surface(c, X(c, d), X(c, b), X(c, cc))) return 0;
    const unsigned char f_ca = c->flag[3 * t1 + (k + 2) % 3], f_bc = c->flag[3 * t1 + (k + 1) % 3];
    const unsigned char f_ad = c->flag[3 * t2 + (ko + 1) % 3], f_db = c->flag[3 * t2 + (ko + 2) % 3];
    const int T1[3] = {cc, a, d}, T2[3] = {d, b, cc};
    c->touched[a] = c->touched[b] = c->touched[cc] = c->touched[d] = c->pass;
    const unsigned char F1[3] = {f_ca, f_ad, 0}, F2[3] = {f_db, f_bc, 0};
    for (int j = 0; j < 3; j++) {
        c->tri[3 * t1 + j] = T1[j];
        c->flag[3 * t1 + j] = F1[j];
        c->tri[3 * t2 + j] = T2[j];
        c->flag[3 * t2 + j] = F2[j];
    }
    const int add[2][2] = {{cc, t2}, {d, t1}};
    for (int j = 0; j < 2; j++) {
        const int v = add[j][0];
        if (c->vn[v] == c->vcap[v]) {
            const int cap = 2 * c->vcap[v] + 8;
            int *g = realloc(c->vt[v], (size_t)cap * sizeof(int));
            if (!g) return -1;
            c->vt[v] = g;
            c->vcap[v] = cap;
        }
        c->vt[v][c->vn[v]++] = add[j][1];
    }
    return 1;
}

/* One pass of flips over the alive triangles' edges; the flips made (-1: out of memory). */
static int flips(cz *c, int nt)
{
    int made = 0;
    for (int t = 0; t < nt; t++)
        for (int k = 0; k < 3 && c->alive[t]; k++) {
            const int f = flip(c, 3 * t + k);
            if (f < 0) return -1;
            made += f;
        }
    return made;
}

/* The smallest angle of v's alive triangles (r, n: its ring). */
static double ring_min_angle(const cz *c, const int *r, int n)
{
    double a = GLPGP_PI;
    for (int i = 0; i < n; i++) {
        const int *t = c->tri + 3 * r[i];
        a = fmin(a, min_angle(X(c, t[0]), X(c, t[1]), X(c, t[2])));
    }
    return a;
}

/* Tangential relaxation: each free vertex (on no boundary or feature
 * edge) moved towards the mean of its ring's vertices and onto the input
 * surface, kept only where its triangles' smallest angle grows and each of
 * them keeps its normal within 72 degrees of the one before and lies near
 * the surface (the collapses' tests). Short edges between well-shaped
 * triangles are what the next pass can collapse. Returns the vertices
 * moved by more than h / 20. */
static int relax(cz *c)
{
    int moved = 0, ends[2];
    for (int v = 0; v < c->m->nv; v++) {
        int *r;
        const int n = ring(c, v, &r);
        if (n < 3 || n > 16 || flagged_at(c, v, ends)) continue; /* 16: the normals' room */
        double mean[3] = {0, 0, 0}, x[3], old[3], nb[3 * 16];
        int cnt = 0;
        c->stamp++;
        for (int i = 0; i < n; i++)
            for (int k = 0; k < 3; k++) {
                const int w = c->tri[3 * r[i] + k];
                if (w == v || c->mark[w] == c->stamp) continue;
                c->mark[w] = c->stamp;
                for (int d = 0; d < 3; d++) mean[d] += X(c, w)[d];
                cnt++;
            }
        for (int d = 0; d < 3; d++) mean[d] /= cnt;
        if (glpgp_qs_proj_nearest(c->P, mean, x) < 0) continue;
        for (int i = 0; i < n; i++) {
            const int *t = c->tri + 3 * r[i];
            tri_normal(X(c, t[0]), X(c, t[1]), X(c, t[2]), nb + 3 * i);
        }
        const double before = ring_min_angle(c, r, n);
        memcpy(old, X(c, v), sizeof old);
        memcpy(c->xyz + 3 * v, x, sizeof x);
        int ok = ring_min_angle(c, r, n) > before;
        for (int i = 0; i < n && ok; i++) {
            const int *t = c->tri + 3 * r[i];
            double n1[3];
            tri_normal(X(c, t[0]), X(c, t[1]), X(c, t[2]), n1);
            ok = dot3(n1, nb + 3 * i) >= 0.3 && near_surface(c, X(c, t[0]), X(c, t[1]), X(c, t[2]));
        }
        if (!ok) {
            memcpy(c->xyz + 3 * v, old, sizeof old);
            continue;
        }
        double e[3];
        sub3(x, old, e);
        if (dot3(e, e) > 0.0025 * c->h * c->h) {
            moved++;
            for (int i = 0; i < n; i++)
                for (int k = 0; k < 3; k++) c->touched[c->tri[3 * r[i] + k]] = c->pass;
        }
    }
    return moved;
}

typedef struct cedge {
    double len;
    int a, b;
} cedge;

static int cmp_cedge(const void *pa, const void *pb)
{
    const cedge *x = pa, *y = pb;
    return x->len < y->len ? -1 : x->len > y->len ? 1 : (x->a != y->a ? x->a - y->a : x->b - y->b);
}

/* Passes over the edges shorter than L, shortest first, until none collapses. */
static glpgp_status coarsen(cz *c, int nt)
{
    cedge *E = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)3 * nt + 1, sizeof *E, &E));
    glpgp_status st = GLPGP_OK;
    for (int pass = 0; pass < 50 && st == GLPGP_OK; pass++) {
        int ne = 0, made = 0;
        c->pass = pass + 1; /* an edge whose ends saw no change since the pass before is not tried again */
        for (int t = 0; t < nt; t++) {
            if (!c->alive[t]) continue;
            for (int k = 0; k < 3; k++) {
                const int a = c->tri[3 * t + k], b = c->tri[3 * t + (k + 1) % 3];
                double e[3];
                sub3(X(c, a), X(c, b), e);
                const double l = sqrt(dot3(e, e));
                if (a < b && l < c->L && (pass == 0 || c->touched[a] >= pass || c->touched[b] >= pass))
                    E[ne++] = (cedge){l, a, b};
            }
        }
        qsort(E, (size_t)ne, sizeof *E, cmp_cedge);
        for (int i = 0; i < ne && st == GLPGP_OK; i++) {
            int done = 0;
            if (!c->vn[E[i].a] || !c->vn[E[i].b]) continue; /* an end collapsed in this pass */
            st = collapse(c, E[i].a, E[i].b, &done);
            if (st == GLPGP_OK && !done) st = collapse(c, E[i].b, E[i].a, &done);
            made += done;
        }
        const int nflip = st == GLPGP_OK ? flips(c, nt) : 0;
        if (nflip < 0) st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "coarse last resort: out of memory");
        const int moved = st == GLPGP_OK && c->tolerant ? relax(c) : 0;
        if (!made && nflip <= 0 && !moved) break;
    }
    free(E);
    return st;
}

/* The new points (ids from first) on a boundary side of the all-quad q put
 * back at chord (their place before the projection: a side's midpoint).
 * Moved onto a concave rim (a round hole's), the midpoint bent its side out
 * and left one of its two quads a reflex corner (a sphere with 20 round
 * holes: inverted, so the last resort was the input's triangles split); on
 * the chord both keep their corners, and the chord stays as near the rim
 * as the coarse triangle's own side. */
static glpgp_status keep_rim_midpoints(glpgp_quadmesh *q, int first, const double *chord)
{
    qsides S;
    GLPGP_CHECK(glpgp_qsides_build(q, &S));
    for (int f = 0; f < q->nf; f++)
        for (int i = 0, j; i < 4; i++) {
            if (glpgp_qsides_across(&S, q, f, i, &j) >= 0) continue;
            for (int e = 0; e < 2; e++) {
                const int v = q->face_vert[4 * f + (i + e) % 4];
                if (v >= first) memcpy(q->xyz + 3 * v, chord + 3 * v, 3 * sizeof(double));
            }
        }
    glpgp_qsides_free(&S);
    return GLPGP_OK;
}

/* The new points (ids from first) of every quad of q that the projection
 * left inverted, degenerate or against the surface (glpgp_qs_quad_sj at or
 * below 0), or below UNFOLD_SJ where its points on their chords give it a
 * larger one, put back at chord, pass after pass while one moves (each
 * moves at most once, so the passes end; a quad whose new points are all
 * on their chords lies in its coarse triangle's plane, convex: a coarse
 * triangle across a staircase crease of marching cubes, where the
 * projection folds it, keeps its quads flat; a large one on a strongly
 * curved part, where the centroid's move nearly flattens a corner, keeps
 * its corners). */
#define UNFOLD_SJ 0.1
static void unfold_to_chords(const cz *c, glpgp_quadmesh *q, int first, const double *chord)
{
    for (int changed = 1; changed;) {
        changed = 0;
        for (int f = 0; f < q->nf; f++) {
            const int *fv = q->face_vert + 4 * f;
            const double *p[4], *pc[4];
            for (int i = 0; i < 4; i++) {
                p[i] = q->xyz + 3 * fv[i];
                pc[i] = fv[i] >= first ? chord + 3 * fv[i] : p[i];
            }
            const double sj = glpgp_qs_quad_sj(c->P, p);
            if (sj > UNFOLD_SJ || (sj > 0.0 && glpgp_qs_quad_sj(c->P, pc) <= sj)) continue;
            for (int i = 0; i < 4; i++)
                if (fv[i] >= first && memcmp(q->xyz + 3 * fv[i], chord + 3 * fv[i], 3 * sizeof(double))) {
                    memcpy(q->xyz + 3 * fv[i], chord + 3 * fv[i], 3 * sizeof(double));
                    changed = 1;
                }
        }
    }
}

/* The alive triangles of c split into three quads each: side midpoints
 * and centroids moved onto the surface (boundary sides' midpoints kept on
 * their chords; those of quads the move folds too). */
static glpgp_status split3(const cz *c, int nt, double h, glpgp_quadmesh **out)
{
    const glpgp_mesh *m = c->m;
    int *vid = NULL, *T = NULL, ntri = 0, nvert = 0;
    double *P = NULL, *chord = NULL;
    glpgp_status st = GLPGP_OK;
    for (int t = 0; t < nt; t++) ntri += c->alive[t];
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)m->nv + 1, sizeof(int), &vid), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * ntri + 1, sizeof(int), &T), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * m->nv + 1, sizeof(double), &P), done);
    for (int v = 0; v < m->nv; v++) vid[v] = -1;
    for (int t = 0, o = 0; t < nt; t++)
        if (c->alive[t])
            for (int k = 0; k < 3; k++, o++) {
                const int v = c->tri[3 * t + k];
                if (vid[v] < 0) {
                    memcpy(P + 3 * nvert, X(c, v), 3 * sizeof(double));
                    vid[v] = nvert++;
                }
                T[o] = vid[v];
            }
    GLPGP_CHECK_GOTO(st, glpgp_qs_split_triangles(P, nvert, T, ntri, out), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * (*out)->nv + 1, sizeof(double), &chord), done);
    memcpy(chord, (*out)->xyz, (size_t)3 * (*out)->nv * sizeof(double));
    st = glpgp_qs_project(m, h, (*out)->xyz, nvert, (*out)->nv);
    if (st == GLPGP_OK) st = keep_rim_midpoints(*out, nvert, chord);
    if (st == GLPGP_OK) unfold_to_chords(c, *out, nvert, chord);
    for (int i = 0; i < (*out)->nv && st == GLPGP_OK; i++) {
        (*out)->xy[2 * i] = (*out)->xyz[3 * i];
        (*out)->xy[2 * i + 1] = (*out)->xyz[3 * i + 1];
    }
    if (st != GLPGP_OK) glpgp_quadmesh_destroy(out);
done:
    free(vid);
    free(T);
    free(P);
    free(chord);
    return st;
}

static glpgp_status cz_init(cz *c, const glpgp_mesh *m, double feature_deg)
{
    const int nt = m->nt;
    GLPGP_CHECK(glpgp_malloc((size_t)3 * nt + 1, sizeof(int), &c->tri));
    GLPGP_CHECK(glpgp_calloc((size_t)3 * nt + 1, 1, &c->flag));
    GLPGP_CHECK(glpgp_malloc((size_t)nt + 1, 1, &c->alive));
    GLPGP_CHECK(glpgp_calloc((size_t)m->nv + 1, sizeof(int *), &c->vt));
    GLPGP_CHECK(glpgp_calloc((size_t)m->nv + 1, sizeof(int), &c->vn));
    GLPGP_CHECK(glpgp_calloc((size_t)m->nv + 1, sizeof(int), &c->vcap));
    GLPGP_CHECK(glpgp_calloc((size_t)m->nv + 1, sizeof(int), &c->mark));
    GLPGP_CHECK(glpgp_calloc((size_t)m->nv + 1, sizeof(int), &c->touched));
    GLPGP_CHECK(glpgp_malloc((size_t)3 * m->nv + 1, sizeof(double), &c->xyz));
    memcpy(c->xyz, m->xyz, (size_t)3 * m->nv * sizeof(double));
    memcpy(c->tri, m->tri, (size_t)3 * nt * sizeof(int));
    memset(c->alive, 1, (size_t)nt);
    GLPGP_CHECK(glpgp_surface_features(m, feature_deg, c->flag, NULL));
    for (int s = 0; s < 3 * nt; s++) {
        if (m->surf->twin[s] < 0) c->flag[s] = 1;
        c->vcap[m->tri[s]]++;
    }
    for (int v = 0; v < m->nv; v++)
        if (c->vcap[v]) GLPGP_CHECK(glpgp_malloc((size_t)c->vcap[v], sizeof(int), &c->vt[v]));
    for (int s = 0; s < 3 * nt; s++) c->vt[m->tri[s]][c->vn[m->tri[s]]++] = s / 3;
    return GLPGP_OK;
}

static void cz_free(cz *c, int nv)
{
    for (int v = 0; v < nv && c->vt; v++) free(c->vt[v]);
    free(c->vt);
    free(c->vn);
    free(c->vcap);
    free(c->mark);
    free(c->touched);
    free(c->xyz);
    free(c->tri);
    free(c->flag);
    free(c->alive);
}

glpgp_status glpgp_qs_coarse(const glpgp_mesh *m, double h, double feature_deg, double amin_deg, int tolerant,
                             glpgp_quadmesh **out, int *ntri)
{
    *out = NULL;
    if (ntri) *ntri = 0;
    if (!glpgp_mesh_is_surface(m) || !m->surf || !(h > 0))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "coarse last resort: a surface and h > 0 are needed");
    cz c;
    memset(&c, 0, sizeof c);
    c.m = m;
    c.h = h;
    c.L = 2.0 * h;
    c.amin = amin_deg * GLPGP_PI / 180.0;
    c.tolerant = tolerant;
    glpgp_qs_proj *P = NULL;
    glpgp_status st = glpgp_qs_proj_create(m, h, 0.3 * h, &P);
    c.P = P;
    if (st == GLPGP_OK) st = cz_init(&c, m, feature_deg);
    if (st == GLPGP_OK) st = coarsen(&c, m->nt);
    if (st == GLPGP_OK) st = split3(&c, m->nt, h, out);
    if (st == GLPGP_OK && ntri) *ntri = (*out)->nf / 3;
    cz_free(&c, m->nv);
    glpgp_qs_proj_destroy(&P);
    return st;
}

glpgp_status glpgp_quads_surface_fallback_coarse(const glpgp_mesh *m, double h, glpgp_quadmesh **out, int *ntri)
{
    return glpgp_qs_coarse(m, h, GLPGP_FEATURE_ANGLE_DEFAULT, 17.0, 1, out, ntri);
}
