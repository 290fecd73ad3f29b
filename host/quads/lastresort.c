/* quads/lastresort.c: an all-quad mesh of the whole domain when the local
 * repair does not end valid (glpgp_quads_last_resort, repair.h). The chain:
 *  1. the domain's loops (input boundary points, Douglas-Peucker at 0.02 h,
 *     corners kept, divided at about h) meshed as one region: the cut
 *     mesher (qcut.c), the triangulation fill (trisplit.c) where it fails;
 *  2. the input triangles split into quads, each around its centroid with
 *     the midpoints of its sides: (a, m_ab, g, m_ca), (b, m_bc, g, m_ab),
 *     (c, m_ca, g, m_bc). Every such quad is convex with the triangle's
 *     orientation (its corners: a triangle angle, two angles of the
 *     triangle formed with the centroid, and the one at g, all below 180
 *     degrees), neighbouring triangles share their side midpoints, the
 *     boundary is the input's own (same points, corners, holes and area):
 *     valid for every valid triangle mesh. The elements are half the
 *     input's size, so the input is first coarsened: edges shorter than h
 *     are collapsed (shortest first) when no triangle around them turns
 *     over or gets an angle below 10 degrees, the link condition holds
 *     (the mesh stays a disc around every vertex), and on the boundary only
 *     into a boundary neighbour along the boundary, never a domain corner,
 *     with every input boundary point the new boundary edge skips within
 *     0.02 h of it and on one side; when that mesh's split is rejected by
 *     the check (it should not be), the input's own split is taken.
 * Each candidate is checked like any quad mesh (glpgp_quads_quality); the
 * first valid one is returned. */
#include "repair.h"
#include "geom.h"
#include "glpgp/quads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define LR_PI 3.14159265358979323846
#define LR_MIN_ANGLE 10.0 /* degrees: no collapse below it */

/* ---- triangles split into quads ------------------------------------------------ */

typedef struct ekey3 {
    long long k;
    int slot;
} ekey3;
static int cmp_ekey3(const void *x, const void *y)
{
    const ekey3 *a = x, *b = y;
    return a->k < b->k ? -1 : a->k > b->k ? 1 : a->slot - b->slot;
}

/* The quads of triangles tri (nt, ids into xy, counter-clockwise). */
static glpgp_status split_triangles(const double *xy, int nv, const int *tri, int nt, glpgp_quadmesh **out)
{
    ekey3 *E = NULL;
    int *mid = NULL;
    glpgp_quadmesh *q = NULL;
    glpgp_status st = glpgp_malloc((size_t)3 * nt + 1, sizeof *E, &E);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)3 * nt + 1, sizeof(int), &mid);
    if (st == GLPGP_OK) st = glpgp_calloc(1, sizeof *q, &q);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nv + 4 * (size_t)nt + 1, 2 * sizeof(double), &q->xy);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)3 * nt + 1, sizeof(int), &q->face_start);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)12 * nt + 1, sizeof(int), &q->face_vert);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)3 * nt + 1, 1, &q->face_origin);
    if (st != GLPGP_OK) goto done;
    memcpy(q->xy, xy, sizeof(double) * 2 * (size_t)nv);
    q->nv = nv;
    for (int t = 0; t < nt; t++)
        for (int j = 0; j < 3; j++) {
            long long a = tri[3 * t + j], b = tri[3 * t + (j + 1) % 3];
            E[3 * t + j] = (ekey3){(a < b ? a : b) * (long long)nv + (a < b ? b : a), 3 * t + j};
        }
    qsort(E, (size_t)3 * nt, sizeof *E, cmp_ekey3);
    for (int i = 0; i < 3 * nt;) {
        int j = i, a = (int)(E[i].k / nv), b = (int)(E[i].k % nv);
        q->xy[2 * q->nv] = 0.5 * (xy[2 * a] + xy[2 * b]);
        q->xy[2 * q->nv + 1] = 0.5 * (xy[2 * a + 1] + xy[2 * b + 1]);
        while (j < 3 * nt && E[j].k == E[i].k) mid[E[j++].slot] = q->nv;
        q->nv++;
        i = j;
    }
    q->face_start[0] = 0;
    for (int t = 0; t < nt; t++) {
        const int *v = tri + 3 * t;
        int g = q->nv++;
        q->xy[2 * g] = (xy[2 * v[0]] + xy[2 * v[1]] + xy[2 * v[2]]) / 3.0;
        q->xy[2 * g + 1] = (xy[2 * v[0] + 1] + xy[2 * v[1] + 1] + xy[2 * v[2] + 1]) / 3.0;
        for (int j = 0; j < 3; j++) {
            int *f = q->face_vert + 4 * q->nf;
            f[0] = v[j];
            f[1] = mid[3 * t + j];
            f[2] = g;
            f[3] = mid[3 * t + (j + 2) % 3];
            q->face_origin[q->nf] = GLPGP_QFACE_FALLBACK;
            q->nf++;
            q->face_start[q->nf] = 4 * q->nf;
        }
    }
    *out = q;
    q = NULL;
done:
    glpgp_quadmesh_destroy(&q);
    free(E);
    free(mid);
    return st;
}

/* ---- coarsening by edge collapses ------------------------------------------------ */

typedef struct cmesh3 {
    int nv, nt;
    double *xy;       /* 2 nv */
    int *tri;         /* 3 nt, -1: dead */
    int **vt, *nvt, *cvt; /* triangles per vertex */
    unsigned char *bnd, *corner, *dead;
    int *bnext, *bprev;   /* boundary successor / predecessor (current) */
    int *span0, *span1;   /* per boundary vertex: the input loop positions its outgoing edge spans */
    int *lpos;            /* per input vertex: position in loop_vertices (-1 inside) */
} cmesh3;

static void cm3_free(cmesh3 *c)
{
    if (c->vt)
        for (int v = 0; v < c->nv; v++) free(c->vt[v]);
    free(c->vt);
    free(c->nvt);
    free(c->cvt);
    free(c->xy);
    free(c->tri);
    free(c->bnd);
    free(c->corner);
    free(c->dead);
    free(c->bnext);
    free(c->bprev);
    free(c->span0);
    free(c->span1);
    free(c->lpos);
    memset(c, 0, sizeof *c);
}

static glpgp_status vt_add(cmesh3 *c, int v, int t)
{
    if (c->nvt[v] == c->cvt[v]) {
        int n = c->cvt[v] ? 2 * c->cvt[v] : 8;
        int *p = realloc(c->vt[v], sizeof(int) * (size_t)n);
        if (!p) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quads: out of memory");
        c->vt[v] = p;
        c->cvt[v] = n;
    }
    c->vt[v][c->nvt[v]++] = t;
    return GLPGP_OK;
}

static glpgp_status cm3_build(cmesh3 *c, const glpgp_mesh *m)
{
    memset(c, 0, sizeof *c);
    c->nv = m->nv;
    c->nt = m->nt;
    const size_t nv1 = (size_t)m->nv + 1;
    GLPGP_CHECK(glpgp_malloc(2 * nv1, sizeof(double), &c->xy));
    GLPGP_CHECK(glpgp_malloc((size_t)3 * m->nt, sizeof(int), &c->tri));
    GLPGP_CHECK(glpgp_calloc(nv1, sizeof(int *), &c->vt));
    GLPGP_CHECK(glpgp_calloc(nv1, sizeof(int), &c->nvt));
    GLPGP_CHECK(glpgp_calloc(nv1, sizeof(int), &c->cvt));
    GLPGP_CHECK(glpgp_calloc(nv1, 1, &c->bnd));
    GLPGP_CHECK(glpgp_calloc(nv1, 1, &c->corner));
    GLPGP_CHECK(glpgp_calloc(nv1, 1, &c->dead));
    GLPGP_CHECK(glpgp_malloc(nv1, sizeof(int), &c->bnext));
    GLPGP_CHECK(glpgp_malloc(nv1, sizeof(int), &c->bprev));
    GLPGP_CHECK(glpgp_malloc(nv1, sizeof(int), &c->span0));
    GLPGP_CHECK(glpgp_malloc(nv1, sizeof(int), &c->span1));
    GLPGP_CHECK(glpgp_malloc(nv1, sizeof(int), &c->lpos));
    memcpy(c->xy, m->xy, sizeof(double) * 2 * (size_t)m->nv);
    memcpy(c->tri, m->tri, sizeof(int) * 3 * (size_t)m->nt);
    for (int t = 0; t < m->nt; t++)
        for (int j = 0; j < 3; j++) GLPGP_CHECK(vt_add(c, c->tri[3 * t + j], t));
    const double cmin = cos(GLPGP_CORNER_DEG * LR_PI / 180.0);
    for (int v = 0; v < m->nv; v++) c->bnext[v] = c->bprev[v] = c->lpos[v] = -1;
    for (int l = 0; l < m->nloops; l++) {
        int s = m->loop_start[l], n = m->loop_start[l + 1] - s;
        for (int i = 0; i < n; i++) {
            int v = m->loop_vertices[s + i], w = m->loop_vertices[s + (i + 1) % n];
            c->bnd[v] = 1;
            c->bnext[v] = w;
            c->bprev[w] = v;
            c->span0[v] = c->span1[v] = s + i; /* the edge v -> w is input edge s + i */
            c->lpos[v] = s + i;
            const double *a = m->normal_prev + 2 * v, *b = m->normal_next + 2 * v;
            c->corner[v] = a[0] * b[0] + a[1] * b[1] < cmin;
        }
    }
    return GLPGP_OK;
}

/* Smallest angle (degrees) of triangle a b c; negative when not counter-clockwise. */
static double tri_min_angle(const double *a, const double *b, const double *c)
{
    double ar = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if (!(ar > 0)) return -1.0;
    const double *p[3] = {a, b, c};
    double amin = 180.0;
    for (int i = 0; i < 3; i++) {
        const double *o = p[i], *u = p[(i + 1) % 3], *w = p[(i + 2) % 3];
        double x1 = u[0] - o[0], y1 = u[1] - o[1], x2 = w[0] - o[0], y2 = w[1] - o[1];
        amin = fmin(amin, atan2(fabs(x1 * y2 - y1 * x2), x1 * x2 + y1 * y2) * 180.0 / LR_PI);
    }
    return amin;
}

/* Neighbours of v (from its triangles) into nb (at most cap); -1 when more. */
static int neighbours3(const cmesh3 *c, int v, int *nb, int cap)
{
    int n = 0;
    for (int i = 0; i < c->nvt[v]; i++) {
        const int *t = c->tri + 3 * c->vt[v][i];
        for (int j = 0; j < 3; j++) {
            int x = t[j], seen = x == v;
            for (int k = 0; k < n && !seen; k++) seen = nb[k] == x;
            if (seen) continue;
            if (n == cap) return -1;
            nb[n++] = x;
        }
    }
    return n;
}

/* Whether collapsing v into w keeps the mesh a disc around every vertex
 * (link condition: the common neighbours of v and w are exactly the third
 * corners of the triangles on the edge) and every triangle of v that stays
 * counter-clockwise with angles >= LR_MIN_ANGLE. */
static int collapse_ok(const cmesh3 *c, int v, int w)
{
    int nv_[64], nw_[64], opp = 0, common = 0;
    int a = neighbours3(c, v, nv_, 64), b = neighbours3(c, w, nw_, 64);
    if (a < 0 || b < 0) return 0;
    for (int i = 0; i < c->nvt[v]; i++) {
        const int *t = c->tri + 3 * c->vt[v][i];
        opp += t[0] == w || t[1] == w || t[2] == w;
    }
    for (int i = 0; i < a; i++)
        for (int j = 0; j < b; j++) common += nv_[i] == nw_[j];
    if (opp == 0 || common != opp) return 0;
    for (int i = 0; i < c->nvt[v]; i++) {
        const int *t = c->tri + 3 * c->vt[v][i];
        if (t[0] == w || t[1] == w || t[2] == w) continue;
        const double *p[3];
        for (int j = 0; j < 3; j++) p[j] = c->xy + 2 * (t[j] == v ? w : t[j]);
        if (tri_min_angle(p[0], p[1], p[2]) < LR_MIN_ANGLE) return 0;
    }
    return 1;
}

/* A boundary collapse of v into its boundary neighbour w: v is no corner,
 * and the new boundary edge u -> x (the loop without v) stays within tol of
 * every input boundary point it skips, all of them on one side of it. */
static int boundary_ok(const cmesh3 *c, const glpgp_mesh *m, int v, int w, double tol)
{
    if (c->corner[v]) return 0;
    int u = w == c->bnext[v] ? c->bprev[v] : w, x = w == c->bnext[v] ? w : c->bnext[v];
    if (u == x || u < 0 || x < 0) return 0;
    int p0 = c->span0[u], p1 = c->span1[v];
    int l = 0;
    while (!(m->loop_start[l + 1] > p0)) l++;
    const int s = m->loop_start[l], n = m->loop_start[l + 1] - s;
    const double *A = c->xy + 2 * u, *B = c->xy + 2 * x;
    int side = 0;
    for (int p = p0; p != p1; p = s + (p - s + 1) % n) { /* the end of input edge p is skipped */
        const double *y = m->xy + 2 * m->loop_vertices[s + (p - s + 1) % n];
        double o = (B[0] - A[0]) * (y[1] - A[1]) - (B[1] - A[1]) * (y[0] - A[0]);
        int sg = o > 0 ? 1 : o < 0 ? -1 : 0;
        if (glpgp_seg_dist(A, B, y, NULL) > tol || (sg && side && sg != side)) return 0;
        if (sg) side = sg;
    }
    return 1;
}

/* Collapse v into w (checked). */
static glpgp_status do_collapse(cmesh3 *c, int v, int w)
{
    for (int i = 0; i < c->nvt[v]; i++) {
        int t = c->vt[v][i];
        int *tv = c->tri + 3 * t;
        if (tv[0] == w || tv[1] == w || tv[2] == w) { /* dies */
            for (int j = 0; j < 3; j++) {
                int x = tv[j];
                if (x == v) continue;
                for (int k = 0; k < c->nvt[x]; k++)
                    if (c->vt[x][k] == t) {
                        c->vt[x][k] = c->vt[x][--c->nvt[x]];
                        break;
                    }
            }
            tv[0] = tv[1] = tv[2] = -1;
        } else {
            for (int j = 0; j < 3; j++)
                if (tv[j] == v) tv[j] = w;
            GLPGP_CHECK(vt_add(c, w, t));
        }
    }
    c->nvt[v] = 0;
    c->dead[v] = 1;
    if (c->bnd[v]) {
        int pv = c->bprev[v], nx = c->bnext[v];
        if (w == nx) { /* pv -> w spans pv's and v's input edges */
            c->bnext[pv] = w;
            c->bprev[w] = pv;
            c->span1[pv] = c->span1[v];
        } else { /* w = pv: w -> nx */
            c->bnext[w] = nx;
            c->bprev[nx] = w;
            c->span1[w] = c->span1[v];
        }
    }
    return GLPGP_OK;
}

typedef struct cedge {
    double len;
    int a, b;
} cedge;
static int cmp_cedge(const void *x, const void *y)
{
    const cedge *p = x, *q = y;
    return (p->len > q->len) - (p->len < q->len);
}

/* Collapse edges shorter than target, shortest first, a few passes. */
static glpgp_status coarsen(cmesh3 *c, const glpgp_mesh *m, double target, double tol)
{
    for (int pass = 0; pass < 12; pass++) {
        cedge *E = NULL;
        int ne = 0, done = 0;
        GLPGP_CHECK(glpgp_malloc((size_t)3 * c->nt + 1, sizeof *E, &E));
        for (int t = 0; t < c->nt; t++) {
            const int *tv = c->tri + 3 * t;
            if (tv[0] < 0) continue;
            for (int j = 0; j < 3; j++) {
                int a = tv[j], b = tv[(j + 1) % 3];
                double l = hypot(c->xy[2 * a] - c->xy[2 * b], c->xy[2 * a + 1] - c->xy[2 * b + 1]);
                if (l < target && a < b) E[ne++] = (cedge){l, a, b};
            }
        }
        qsort(E, (size_t)ne, sizeof *E, cmp_cedge);
        glpgp_status st = GLPGP_OK;
        for (int i = 0; i < ne && st == GLPGP_OK; i++) {
            int a = E[i].a, b = E[i].b;
            if (c->dead[a] || c->dead[b]) continue;
            for (int o = 0; o < 2; o++) { /* v into w */
                int v = o ? b : a, w = o ? a : b;
                if (c->bnd[v] && (!c->bnd[w] || (c->bnext[v] != w && c->bprev[v] != w))) continue;
                if (c->bnd[v] && !boundary_ok(c, m, v, w, tol)) continue;
                if (!collapse_ok(c, v, w)) continue;
                st = do_collapse(c, v, w);
                done++;
                break;
            }
        }
        free(E);
        if (st != GLPGP_OK) return st;
        if (!done) break;
    }
    return GLPGP_OK;
}

/* The coarsened live triangles, renumbered: *xy, *tri, counts. */
static glpgp_status coarse_triangles(const cmesh3 *c, double **xy, int *nv, int **tri, int *nt)
{
    int *id = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)c->nv + 1, sizeof(int), &id));
    GLPGP_CHECK(glpgp_malloc((size_t)c->nv + 1, 2 * sizeof(double), xy));
    GLPGP_CHECK(glpgp_malloc((size_t)3 * c->nt + 1, sizeof(int), tri));
    *nv = *nt = 0;
    for (int v = 0; v < c->nv; v++) {
        id[v] = -1;
        if (c->dead[v]) continue;
        id[v] = (*nv)++;
        (*xy)[2 * id[v]] = c->xy[2 * v];
        (*xy)[2 * id[v] + 1] = c->xy[2 * v + 1];
    }
    for (int t = 0; t < c->nt; t++) {
        if (c->tri[3 * t] < 0) continue;
        for (int j = 0; j < 3; j++) (*tri)[3 * *nt + j] = id[c->tri[3 * t + j]];
        (*nt)++;
    }
    free(id);
    return GLPGP_OK;
}

/* ---- the chain ----------------------------------------------------------------------- */

static glpgp_status accept(glpgp_quadmesh **cand, const glpgp_mesh *m, double h, glpgp_quadmesh **out)
{
    glpgp_quads_report qq;
    if (!*cand || (*cand)->nf == 0) return GLPGP_OK;
    GLPGP_CHECK(glpgp_quads_quality(*cand, m, h, &qq));
    if (qq.invalid) {
        glpgp_log(GLPGP_LOG_DEBUG, "quads last resort: a candidate rejected (0x%x)", qq.invalid);
        glpgp_quadmesh_destroy(cand);
        return GLPGP_OK;
    }
    *out = *cand;
    *cand = NULL;
    return GLPGP_OK;
}

/* Step 1: the whole domain as one repair region (an empty mesh repaired). */
static glpgp_status whole_region(const glpgp_mesh *m, double h, glpgp_quadmesh **cand, int *paved)
{
    glpgp_quadmesh *e = NULL;
    *paved = 0;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *e, &e));
    glpgp_status st = glpgp_calloc(1, sizeof(int), &e->face_start);
    if (st == GLPGP_OK) st = glpgp_repair_rounds(e, m, h, 20, 2, cand);
    if (st == GLPGP_OK && *cand) {
        *paved = 1;
        for (int f = 0; f < (*cand)->nf && *paved; f++)
            *paved = !(*cand)->face_origin || (*cand)->face_origin[f] == GLPGP_QFACE_PAVED;
    }
    glpgp_quadmesh_destroy(&e);
    return st;
}

glpgp_status glpgp_quads_last_resort(const glpgp_mesh *m, double h, glpgp_quadmesh **out, int *level)
{
    *out = NULL;
    *level = 0;
    glpgp_quadmesh *cand = NULL;
    int paved = 0;
    glpgp_status st = whole_region(m, h, &cand, &paved);
    if (st == GLPGP_ERR_NUMERIC) {
        glpgp_error_clear();
        st = GLPGP_OK;
    }
    if (st == GLPGP_OK) st = accept(&cand, m, h, out);
    if (st != GLPGP_OK || *out) {
        *level = paved ? 1 : 2;
        return st;
    }
    /* the input triangles, coarsened, split */
    cmesh3 c;
    double *xy = NULL;
    int *tri = NULL, nv = 0, nt = 0;
    st = cm3_build(&c, m);
    if (st == GLPGP_OK) st = coarsen(&c, m, h, 0.02 * h);
    if (st == GLPGP_OK) st = coarse_triangles(&c, &xy, &nv, &tri, &nt);
    if (st == GLPGP_OK) st = split_triangles(xy, nv, tri, nt, &cand);
    if (st == GLPGP_OK) st = accept(&cand, m, h, out);
    cm3_free(&c);
    free(xy);
    free(tri);
    if (st != GLPGP_OK || *out) {
        *level = 3;
        return st;
    }
    /* the input's own triangles */
    GLPGP_CHECK(split_triangles(m->xy, m->nv, m->tri, m->nt, &cand));
    GLPGP_CHECK(accept(&cand, m, h, out));
    *level = *out ? 4 : 0;
    return GLPGP_OK;
}
