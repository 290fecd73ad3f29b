/* quads/cleanup.c: topological clean-up of an all-quad mesh
 * (glpgp_quadmesh_cleanup, glpgp/quads.h): local operations that lower the
 * number of irregular vertices while keeping the mesh valid, run by
 * glpgp_quads_build after the repair. The repaired regions (a constrained
 * Delaunay triangulation cut into quads) and the strips of the closing
 * leave clusters of valence 3 / 5 / 6 vertices; the classical clean-up
 * operations of quad meshing (doublet removal, diagonal collapse, edge
 * rotation; e.g. Bozzo et al., "Quadrilateral mesh cleanup", and the
 * Blossom-Quad post-processing of Gmsh) remove most of them.
 *
 * Cost: c = sum over vertices of d^2 + [d > 0], d = |val(v) - ideal(v)|,
 * ideal = 4 inside and round(boundary angle / 90 deg) + 1 on the boundary
 * (the quality report's rule). An operation is applied only when it lowers
 * c, and kept only when the faces it touches (after smoothing its interior
 * vertices: 4 sweeps, each vertex to the mean of its edge neighbours) have a
 * smallest corner scaled Jacobian >= min(0.15, the smallest before) and
 * > 0.05; else it is undone. Boundary vertices never move and are never removed, so the
 * domain boundary, its corners and the covered area are unchanged; the
 * link conditions below keep the mesh a manifold; positive corners keep
 * every face convex and counter-clockwise.
 *   doublet (v interior, 2 faces (v, a, x, b), (v, b, y, a)):
 *     -> one face (a, x, b, y); val a, b -1; v removed.
 *   diagonal collapse (face (a, b, c, d), a and c interior, the common
 *     neighbours of a and c exactly b and d):
 *     -> the face removed, c merged into a; val(a) <- val(a) + val(c) - 2,
 *        val b, d -1 (a 3-5-3-5 face: four irregular vertices less).
 *   edge rotation (interior edge u-w between (u, w, p1, p2) and
 *     (w, u, q1, q2), hexagon [w, p1, p2, u, q1, q2]):
 *     -> the diagonal p1-q1 or p2-q2 (not already an edge); val u, w -1,
 *        its ends +1.
 * Passes over every candidate until a pass changes nothing (at most 16). */
#include "glpgp/quads.h"
#include "glpgp/util.h"

#include "geom.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CL_PI 3.14159265358979323846
#define CL_MAX_PASSES 16
#define CL_SMOOTH_SWEEPS 4
#define CL_SJ_KEEP 0.15  /* a face above this may go down to it (0.3: 44.2 irregular
                            per 100 quads on the hard domains, 0.15: 40.5, the
                            mean scaled Jacobian up either way) */
#define CL_SJ_FLOOR 0.05 /* never below this */
#define CL_LOCAL 64      /* vertices / faces an operation may touch */

typedef struct cmesh {
    int nv, nf;
    double *xy;             /* 2 nv */
    int *f;                 /* 4 nf */
    unsigned char *fdead;   /* nf */
    unsigned char *vdead;   /* nv */
    unsigned char *bnd;     /* nv: on the boundary (fixed) */
    int *ideal;             /* nv */
    int **vf, *nvf, *cvf;   /* incident faces per vertex */
    unsigned char *fo;      /* nf: face origin (GLPGP_QFACE_*) */
} cmesh;

/* Faces f and g were remade together: both take the higher origin. */
static void merge_origin(cmesh *c, int f, int g)
{
    unsigned char o = c->fo[f] > c->fo[g] ? c->fo[f] : c->fo[g];
    c->fo[f] = c->fo[g] = o;
}

static void cm_free(cmesh *c)
{
    if (c->vf)
        for (int i = 0; i < c->nv; i++) free(c->vf[i]);
    free(c->vf);
    free(c->nvf);
    free(c->cvf);
    free(c->xy);
    free(c->f);
    free(c->fdead);
    free(c->vdead);
    free(c->bnd);
    free(c->ideal);
    free(c->fo);
}

static glpgp_status vf_add(cmesh *c, int v, int f)
{
    if (c->nvf[v] == c->cvf[v]) {
        int nc = c->cvf[v] ? 2 * c->cvf[v] : 8;
        int *p = realloc(c->vf[v], sizeof(int) * (size_t)nc);
        if (!p) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad clean-up: out of memory");
        c->vf[v] = p;
        c->cvf[v] = nc;
    }
    c->vf[v][c->nvf[v]++] = f;
    return GLPGP_OK;
}

static void vf_del(cmesh *c, int v, int f)
{
    for (int k = 0; k < c->nvf[v]; k++)
        if (c->vf[v][k] == f) {
            c->vf[v][k] = c->vf[v][--c->nvf[v]];
            return;
        }
}

static int valence(const cmesh *c, int v) { return c->nvf[v] + (c->bnd[v] ? 1 : 0); }

/* c_v = d^2 + [d > 0], d = |val - ideal|: one irregular vertex of valence 6
 * costs more than two of valence 5 (so the operations spread a high valence
 * out, measured: 55.9 -> 40.5 irregular per 100 quads on the hard domains
 * against 53.8 with c_v = d, and 52.3 when an operation must also not
 * raise the irregular count: the perforated plate's repaired regions need
 * such steps), and an irregular vertex more than none. */
static int vcost(const cmesh *c, int v, int val)
{
    const int d = abs(val - c->ideal[v]);
    return d * d + (d > 0);
}

/* Change of the cost when v goes from valence a to b. */
#define DCOST(v, a, b) (vcost(c, (v), (b)) - vcost(c, (v), (a)))

/* Position of v in face f, -1 when absent. */
static int fpos(const cmesh *c, int f, int v)
{
    for (int k = 0; k < 4; k++)
        if (c->f[4 * f + k] == v) return k;
    return -1;
}

/* Edge neighbours of v into nb (at most cap), returns the count. */
static int neighbours(const cmesh *c, int v, int *nb, int cap)
{
    int n = 0;
    for (int k = 0; k < c->nvf[v]; k++) {
        const int f = c->vf[v][k], i = fpos(c, f, v);
        const int a = c->f[4 * f + (i + 1) % 4], b = c->f[4 * f + (i + 3) % 4];
        int ha = 0, hb = 0;
        for (int j = 0; j < n; j++) ha |= nb[j] == a, hb |= nb[j] == b;
        if (!ha && n < cap) nb[n++] = a;
        if (!hb && n < cap) nb[n++] = b;
    }
    return n;
}

static int adjacent(const cmesh *c, int a, int b)
{
    int nb[4 * CL_LOCAL];
    const int n = neighbours(c, a, nb, 4 * CL_LOCAL);
    for (int j = 0; j < n; j++)
        if (nb[j] == b) return 1;
    return 0;
}

static double face_sj(const cmesh *c, int f) { return glpgp_poly_min_sj(c->xy, c->f + 4 * f, 4); }

/* ---- one operation, with its undo record ---------------------------------- */

typedef struct trial {
    int nf, fid[CL_LOCAL], fold[CL_LOCAL][4];
    unsigned char fdead[CL_LOCAL];
    int nvx, vid[CL_LOCAL];
    double vxy[CL_LOCAL][2];
    unsigned char vdead[CL_LOCAL];
    int ok; /* 0: the record overflowed, the operation must not be tried */
} trial;

static void tr_face(trial *t, const cmesh *c, int f)
{
    for (int k = 0; k < t->nf; k++)
        if (t->fid[k] == f) return;
    if (t->nf == CL_LOCAL) {
        t->ok = 0;
        return;
    }
    t->fid[t->nf] = f;
    memcpy(t->fold[t->nf], c->f + 4 * f, sizeof(int) * 4);
    t->fdead[t->nf++] = c->fdead[f];
}

static void tr_vert(trial *t, const cmesh *c, int v)
{
    for (int k = 0; k < t->nvx; k++)
        if (t->vid[k] == v) return;
    if (t->nvx == CL_LOCAL) {
        t->ok = 0;
        return;
    }
    t->vid[t->nvx] = v;
    t->vxy[t->nvx][0] = c->xy[2 * v];
    t->vxy[t->nvx][1] = c->xy[2 * v + 1];
    t->vdead[t->nvx++] = c->vdead[v];
}

/* Set face f to (a, b, cc, d) (or dead), keeping the incidence lists. */
static glpgp_status set_face(cmesh *c, int f, const int *nf, int dead)
{
    if (!c->fdead[f])
        for (int k = 0; k < 4; k++) vf_del(c, c->f[4 * f + k], f);
    c->fdead[f] = (unsigned char)dead;
    if (dead) return GLPGP_OK;
    memcpy(c->f + 4 * f, nf, sizeof(int) * 4);
    for (int k = 0; k < 4; k++) GLPGP_CHECK(vf_add(c, nf[k], f));
    return GLPGP_OK;
}

/* Undo: faces back to their recorded state (incidences follow), vertices
 * back to their positions and liveness. */
static glpgp_status undo(cmesh *c, const trial *t)
{
    for (int k = t->nf - 1; k >= 0; k--) GLPGP_CHECK(set_face(c, t->fid[k], t->fold[k], t->fdead[k]));
    for (int k = 0; k < t->nvx; k++) {
        c->xy[2 * t->vid[k]] = t->vxy[k][0];
        c->xy[2 * t->vid[k] + 1] = t->vxy[k][1];
        c->vdead[t->vid[k]] = t->vdead[k];
    }
    return GLPGP_OK;
}

/* Smallest corner scaled Jacobian of the live faces around the vertices vs[0..n). */
static double ring_sj(const cmesh *c, const int *vs, int n)
{
    double m = 1.0;
    for (int i = 0; i < n; i++) {
        if (c->vdead[vs[i]]) continue;
        for (int k = 0; k < c->nvf[vs[i]]; k++) m = fmin(m, face_sj(c, c->vf[vs[i]][k]));
    }
    return m;
}

/* The vertices around which quality is measured: vs and their edge
 * neighbours (the faces of their rings contain every face that smoothing
 * vs can change). */
static int widen(const cmesh *c, const int *vs, int n, int *out, int cap)
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        if (c->vdead[vs[i]]) continue;
        int nb[CL_LOCAL];
        int k = neighbours(c, vs[i], nb, CL_LOCAL);
        for (int j = -1; j < k; j++) {
            const int v = j < 0 ? vs[i] : nb[j];
            int have = 0;
            for (int l = 0; l < m; l++) have |= out[l] == v;
            if (!have && m < cap) out[m++] = v;
        }
    }
    return m;
}

/* Smooth the interior vertices among vs (recorded in t first):
 * x_v <- mean of its edge neighbours, CL_SMOOTH_SWEEPS Gauss-Seidel sweeps. */
static void smooth_local(cmesh *c, trial *t, const int *vs, int n)
{
    for (int i = 0; i < n; i++)
        if (!c->bnd[vs[i]] && !c->vdead[vs[i]]) tr_vert(t, c, vs[i]);
    for (int s = 0; s < CL_SMOOTH_SWEEPS; s++)
        for (int i = 0; i < n; i++) {
            const int v = vs[i];
            if (c->bnd[v] || c->vdead[v]) continue;
            int nb[CL_LOCAL];
            const int k = neighbours(c, v, nb, CL_LOCAL);
            if (k == 0) continue;
            double x = 0, y = 0;
            for (int j = 0; j < k; j++) x += c->xy[2 * nb[j]], y += c->xy[2 * nb[j] + 1];
            c->xy[2 * v] = x / k;
            c->xy[2 * v + 1] = y / k;
        }
}

/* After an operation: smooth its interior vertices `core`, measure the ring,
 * keep (1) or undo (0) against the quality before (sj0). */
static glpgp_status settle(cmesh *c, trial *t, const int *core, int ncore, double sj0, int *kept)
{
    int ring[4 * CL_LOCAL];
    smooth_local(c, t, core, ncore);
    const int nr = widen(c, core, ncore, ring, 4 * CL_LOCAL);
    const double sj1 = ring_sj(c, ring, nr);
    *kept = t->ok && sj1 > CL_SJ_FLOOR && sj1 >= fmin(sj0, CL_SJ_KEEP);
    if (!*kept) GLPGP_CHECK(undo(c, t));
    return GLPGP_OK;
}

/* Quality before an operation around the vertices vs (and their neighbours). */
static double sj_before(const cmesh *c, const int *vs, int n)
{
    int ring[4 * CL_LOCAL];
    const int nr = widen(c, vs, n, ring, 4 * CL_LOCAL);
    return ring_sj(c, ring, nr);
}

/* ---- the three operations --------------------------------------------------- */

static glpgp_status try_doublet(cmesh *c, int v, int *done)
{
    *done = 0;
    if (c->bnd[v] || c->vdead[v] || c->nvf[v] != 2) return GLPGP_OK;
    const int f1 = c->vf[v][0], f2 = c->vf[v][1];
    const int i1 = fpos(c, f1, v), i2 = fpos(c, f2, v);
    const int a = c->f[4 * f1 + (i1 + 1) % 4], x = c->f[4 * f1 + (i1 + 2) % 4], b = c->f[4 * f1 + (i1 + 3) % 4];
    /* f2 = (v, b, y, a) */
    if (c->f[4 * f2 + (i2 + 1) % 4] != b || c->f[4 * f2 + (i2 + 3) % 4] != a) return GLPGP_OK;
    const int y = c->f[4 * f2 + (i2 + 2) % 4];
    if (x == y) return GLPGP_OK;
    /* cost change: v goes (|2 - 4| = 2), a and b lose one edge */
    const int va = valence(c, a), vb = valence(c, b);
    const int d = -vcost(c, v, 2) + DCOST(a, va, va - 1) + DCOST(b, vb, vb - 1);
    if (d >= 0) return GLPGP_OK;
    int core0[4] = {a, b, x, y};
    const double sj0 = sj_before(c, core0, 4);
    trial t = {.ok = 1};
    tr_face(&t, c, f1);
    tr_face(&t, c, f2);
    tr_vert(&t, c, v);
    const int nf[4] = {a, x, b, y};
    GLPGP_CHECK(set_face(c, f2, nf, 1));
    GLPGP_CHECK(set_face(c, f1, nf, 0));
    c->vdead[v] = 1;
    int core[2] = {a, b};
    GLPGP_CHECK(settle(c, &t, core, 2, sj0, done));
    if (*done) merge_origin(c, f1, f2);
    return GLPGP_OK;
}

static glpgp_status try_collapse(cmesh *c, int f, int diag, int *done)
{
    *done = 0;
    if (c->fdead[f]) return GLPGP_OK;
    const int *q = c->f + 4 * f;
    const int a = q[diag], b = q[diag + 1], cc = q[diag + 2], d = q[(diag + 3) % 4];
    if (c->bnd[a] || c->bnd[cc]) return GLPGP_OK;
    const int va = valence(c, a), vc = valence(c, cc), vb = valence(c, b), vd = valence(c, d);
    const int delta = DCOST(a, va, va + vc - 2) - vcost(c, cc, vc) + DCOST(b, vb, vb - 1) + DCOST(d, vd, vd - 1);
    if (delta >= 0 || va + vc - 2 > CL_LOCAL / 2) return GLPGP_OK;
    /* link condition: the common neighbours of a and c are exactly b and d */
    int na[CL_LOCAL], nc[CL_LOCAL];
    const int ka = neighbours(c, a, na, CL_LOCAL), kc = neighbours(c, cc, nc, CL_LOCAL);
    for (int i = 0; i < ka; i++) {
        if (na[i] == cc) return GLPGP_OK; /* a-c an edge elsewhere */
        for (int j = 0; j < kc; j++)
            if (na[i] == nc[j] && na[i] != b && na[i] != d) return GLPGP_OK;
    }
    /* b and d keep at least 2 faces (interior) / 1 face (boundary) */
    if (c->nvf[b] < (c->bnd[b] ? 2 : 3) || c->nvf[d] < (c->bnd[d] ? 2 : 3)) return GLPGP_OK;
    int core0[2] = {a, cc};
    const double sj0 = sj_before(c, core0, 2);
    trial t = {.ok = 1};
    tr_face(&t, c, f);
    tr_vert(&t, c, a);
    tr_vert(&t, c, cc);
    int cf[CL_LOCAL], ncf = c->nvf[cc];
    if (ncf > CL_LOCAL) return GLPGP_OK;
    memcpy(cf, c->vf[cc], sizeof(int) * (size_t)ncf);
    for (int k = 0; k < ncf; k++) tr_face(&t, c, cf[k]);
    if (!t.ok) return GLPGP_OK;
    const double mx = 0.5 * (c->xy[2 * a] + c->xy[2 * cc]), my = 0.5 * (c->xy[2 * a + 1] + c->xy[2 * cc + 1]);
    GLPGP_CHECK(set_face(c, f, q, 1));
    for (int k = 0; k < ncf; k++) {
        if (cf[k] == f) continue;
        int nf[4];
        memcpy(nf, c->f + 4 * cf[k], sizeof nf);
        for (int j = 0; j < 4; j++)
            if (nf[j] == cc) nf[j] = a;
        GLPGP_CHECK(set_face(c, cf[k], nf, 0));
    }
    c->vdead[cc] = 1;
    c->xy[2 * a] = mx;
    c->xy[2 * a + 1] = my;
    int core[3] = {a, b, d};
    return settle(c, &t, core, 3, sj0, done);
}

static glpgp_status try_rotate(cmesh *c, int f1, int e, int *done)
{
    *done = 0;
    if (c->fdead[f1]) return GLPGP_OK;
    const int u = c->f[4 * f1 + e], w = c->f[4 * f1 + (e + 1) % 4];
    const int p1 = c->f[4 * f1 + (e + 2) % 4], p2 = c->f[4 * f1 + (e + 3) % 4];
    if (u > w) return GLPGP_OK; /* each edge once: from the face where u < w */
    int f2 = -1, i2 = -1;
    for (int k = 0; k < c->nvf[w] && f2 < 0; k++) {
        const int g = c->vf[w][k];
        if (g == f1) continue;
        const int j = fpos(c, g, w);
        if (c->f[4 * g + (j + 1) % 4] == u) f2 = g, i2 = j;
    }
    if (f2 < 0) return GLPGP_OK; /* boundary edge */
    const int q1 = c->f[4 * f2 + (i2 + 2) % 4], q2 = c->f[4 * f2 + (i2 + 3) % 4];
    const int vu = valence(c, u), vw = valence(c, w);
    /* u and w keep at least 2 faces (interior) / 1 (boundary) */
    if (c->nvf[u] < (c->bnd[u] ? 2 : 3) || c->nvf[w] < (c->bnd[w] ? 2 : 3)) return GLPGP_OK;
    const int base = DCOST(u, vu, vu - 1) + DCOST(w, vw, vw - 1);
    /* hexagon [w, p1, p2, u, q1, q2]: option 0 diagonal p1-q1, option 1 p2-q2 */
    for (int o = 0; o < 2; o++) {
        const int s = o ? p2 : p1, t2 = o ? q2 : q1;
        if (s == t2) continue;
        const int vs = valence(c, s), vt = valence(c, t2);
        const int delta = base + DCOST(s, vs, vs + 1) + DCOST(t2, vt, vt + 1);
        if (delta >= 0 || adjacent(c, s, t2)) continue;
        int core0[2] = {u, w};
        const double sj0 = sj_before(c, core0, 2);
        trial t = {.ok = 1};
        tr_face(&t, c, f1);
        tr_face(&t, c, f2);
        int n1[4], n2[4];
        if (o == 0) {
            const int a1[4] = {p1, p2, u, q1}, a2[4] = {q1, q2, w, p1};
            memcpy(n1, a1, sizeof n1), memcpy(n2, a2, sizeof n2);
        } else {
            const int a1[4] = {p2, u, q1, q2}, a2[4] = {q2, w, p1, p2};
            memcpy(n1, a1, sizeof n1), memcpy(n2, a2, sizeof n2);
        }
        GLPGP_CHECK(set_face(c, f1, n1, 0));
        GLPGP_CHECK(set_face(c, f2, n2, 0));
        int core[4] = {u, w, s, t2};
        GLPGP_CHECK(settle(c, &t, core, 4, sj0, done));
        if (*done) {
            merge_origin(c, f1, f2);
            return GLPGP_OK;
        }
    }
    return GLPGP_OK;
}

/* ---- driver ------------------------------------------------------------------- */

typedef struct ekey {
    int a, b, f; /* a < b */
} ekey;

static int cmp_ekey(const void *x, const void *y)
{
    const ekey *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return 0;
}

static int total_cost(const cmesh *c)
{
    int s = 0;
    for (int v = 0; v < c->nv; v++)
        if (!c->vdead[v] && c->nvf[v] > 0) s += vcost(c, v, valence(c, v));
    return s;
}

glpgp_status glpgp_quadmesh_cleanup(const glpgp_quadmesh *q, glpgp_quadmesh **out)
{
    *out = NULL;
    int all_quads = q->nf > 0;
    for (int f = 0; f < q->nf && all_quads; f++) {
        all_quads = q->face_start[f + 1] - q->face_start[f] == 4;
        const int *v = q->face_vert + q->face_start[f];
        for (int k = 0; k < 4 && all_quads; k++) /* a repeated corner, or an index out of range */
            all_quads = v[k] >= 0 && v[k] < q->nv && v[k] != v[(k + 1) % 4] && v[k] != v[(k + 2) % 4];
    }
    if (!all_quads) return GLPGP_OK; /* polygons kept (--keep-polygons), degenerate faces, or nothing to do */
    cmesh c;
    memset(&c, 0, sizeof c);
    glpgp_status st = GLPGP_OK;
    glpgp_quadmesh *r = NULL;
    ekey *ek = NULL;
    int *map = NULL;
    double *angle = NULL;
    c.nv = q->nv;
    c.nf = q->nf;
    const size_t nv1 = (size_t)c.nv + 1;
    GLPGP_CHECK_GOTO(st, glpgp_malloc(2 * nv1, sizeof(double), &c.xy), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * c.nf, sizeof(int), &c.f), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)c.nf, 1, &c.fdead), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)c.nf + 1, 1, &c.fo), done);
    if (q->face_origin) memcpy(c.fo, q->face_origin, (size_t)c.nf);
    GLPGP_CHECK_GOTO(st, glpgp_calloc(nv1, 1, &c.vdead), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc(nv1, 1, &c.bnd), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc(nv1, sizeof(int), &c.ideal), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc(nv1, sizeof(int *), &c.vf), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc(nv1, sizeof(int), &c.nvf), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc(nv1, sizeof(int), &c.cvf), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc(nv1, sizeof(double), &angle), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * c.nf, sizeof(ekey), &ek), done);
    memcpy(c.xy, q->xy, sizeof(double) * 2 * (size_t)c.nv);
    memcpy(c.f, q->face_vert, sizeof(int) * 4 * (size_t)c.nf);
    for (int f = 0; f < c.nf; f++)
        for (int k = 0; k < 4; k++) GLPGP_CHECK_GOTO(st, vf_add(&c, c.f[4 * f + k], f), done);
    /* boundary: the edges of one face; their ends never move */
    for (int f = 0; f < c.nf; f++)
        for (int k = 0; k < 4; k++) {
            const int a = c.f[4 * f + k], b = c.f[4 * f + (k + 1) % 4];
            ek[4 * f + k] = (ekey){a < b ? a : b, a < b ? b : a, f};
        }
    qsort(ek, (size_t)4 * c.nf, sizeof(ekey), cmp_ekey);
    for (size_t i = 0; i < (size_t)4 * c.nf;) {
        size_t j = i + 1;
        while (j < (size_t)4 * c.nf && ek[j].a == ek[i].a && ek[j].b == ek[i].b) j++;
        if (j - i == 1) c.bnd[ek[i].a] = c.bnd[ek[i].b] = 1;
        if (j - i > 2) { /* a non-manifold edge: not a mesh these operations are defined on */
            st = GLPGP_OK;
            goto done;
        }
        i = j;
    }
    /* ideal valences: 4 inside, round(angle / 90 deg) + 1 on the boundary */
    for (int f = 0; f < c.nf; f++)
        for (int k = 0; k < 4; k++) {
            const int v = c.f[4 * f + k], p = c.f[4 * f + (k + 3) % 4], n = c.f[4 * f + (k + 1) % 4];
            const double ax = c.xy[2 * n] - c.xy[2 * v], ay = c.xy[2 * n + 1] - c.xy[2 * v + 1];
            const double bx = c.xy[2 * p] - c.xy[2 * v], by = c.xy[2 * p + 1] - c.xy[2 * v + 1];
            angle[v] += atan2(ax * by - ay * bx, ax * bx + ay * by);
        }
    for (int v = 0; v < c.nv; v++) c.ideal[v] = c.bnd[v] ? (int)lround(angle[v] / (CL_PI / 2)) + 1 : 4;

    glpgp_quads_cleanup stats;
    memset(&stats, 0, sizeof stats);
    stats.cost_before = total_cost(&c);
    for (int pass = 0; pass < CL_MAX_PASSES; pass++) {
        glpgp_progress_poll();
        int changed = 0, done1 = 0;
        for (int v = 0; v < c.nv; v++) {
            GLPGP_CHECK_GOTO(st, try_doublet(&c, v, &done1), done);
            stats.doublets += done1, changed += done1;
        }
        for (int f = 0; f < c.nf; f++)
            for (int d = 0; d < 2; d++) {
                GLPGP_CHECK_GOTO(st, try_collapse(&c, f, d, &done1), done);
                stats.collapses += done1, changed += done1;
            }
        for (int f = 0; f < c.nf; f++)
            for (int e = 0; e < 4; e++) {
                GLPGP_CHECK_GOTO(st, try_rotate(&c, f, e, &done1), done);
                stats.rotations += done1, changed += done1;
            }
        stats.passes = pass + 1;
        if (!changed) break;
    }
    stats.cost_after = total_cost(&c);
    if (stats.doublets + stats.collapses + stats.rotations == 0) goto done;

    /* compact: live vertices (in their order), live faces */
    GLPGP_CHECK_GOTO(st, glpgp_malloc(nv1, sizeof(int), &map), done);
    int nv = 0, nf = 0;
    for (int v = 0; v < c.nv; v++) map[v] = c.vdead[v] ? -1 : nv++;
    for (int f = 0; f < c.nf; f++) nf += !c.fdead[f];
    GLPGP_CHECK_GOTO(st, glpgp_calloc(1, sizeof *r, &r), done);
    *r = *q; /* diagnostics */
    r->xy = NULL;
    r->face_start = r->face_vert = NULL;
    r->face_origin = NULL;
    r->nv = nv;
    r->nf = nf;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv + 2, sizeof(double), &r->xy), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nf + 1, sizeof(int), &r->face_start), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * nf + 1, sizeof(int), &r->face_vert), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nf + 1, 1, &r->face_origin), done);
    for (int v = 0; v < c.nv; v++)
        if (map[v] >= 0) r->xy[2 * map[v]] = c.xy[2 * v], r->xy[2 * map[v] + 1] = c.xy[2 * v + 1];
    int k = 0;
    for (int f = 0; f < c.nf; f++) {
        if (c.fdead[f]) continue;
        r->face_start[k] = 4 * k;
        r->face_origin[k] = c.fo[f];
        for (int j = 0; j < 4; j++) r->face_vert[4 * k + j] = map[c.f[4 * f + j]];
        k++;
    }
    r->face_start[nf] = 4 * nf;
    r->cleanup = stats;
    *out = r;
    r = NULL;
done:
    free(map);
    free(ek);
    free(angle);
    cm_free(&c);
    glpgp_quadmesh_destroy(&r);
    return st;
}
