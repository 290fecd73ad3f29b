/* quads/smooth_surface.c: the quality-guarded smoothing of a surface's
 * quad mesh (glpgp_quads_smooth_surface, glpgp/quads.h). A free vertex (not on the
 * quad mesh's boundary, not on the input's boundary or sharp features)
 * tries a few targets, each moved back onto the input surface (its nearest
 * point): part of the way to the mean of its edge neighbours, and the
 * corner that makes its worst quad a parallelogram. A target is kept only
 * when the smallest scaled Jacobian of the vertex's faces (each in its own
 * plane) rises, no face falls below min(0.3, its value before the
 * smoothing), no face turns against its normal before, the surface
 * under the target faces the same way as the vertex's faces, and each of
 * the vertex's faces stays as the check sees it (its normal along the
 * surface's at its centre, the samples of its fan triangles within
 * max(0.2 h, their distance before) of the surface: the check's Hausdorff
 * bound is h/4); so the
 * smallest scaled Jacobian never falls and the mesh's topology is
 * untouched. A vertex of the quad mesh's boundary that lies on one of the
 * input's boundary loops, away from its corners (the loop turns by more than
 * BND_CORNER_DEG there, or a sharp feature ends there), slides along that
 * loop under the same rule: its targets (the mean of its two boundary
 * neighbours, the parallelogram corner) are moved to the nearest point of
 * the loop between the corners around it, so the boundary stays on the
 * input's. The caller checks the result (Hausdorff, area) and keeps the
 * mesh it had when the check fails. */
#include "quads_surface.h"

#include "glpgp/kinds.h"
#include "glpgp/surface.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SJ_FLOOR 0.3
#define CD_MAX 0.2 /* a face's samples within 0.2 h of the surface (the check's Hausdorff bound: h/4) */
#define BND_CORNER_DEG 40.0
#define BND_WALK 64 /* input boundary edges searched each way from a sliding vertex */

static int cmp_key(const void *pa, const void *pb)
{
    const long long a = *(const long long *)pa, b = *(const long long *)pb;
    return a < b ? -1 : a > b;
}

typedef struct sm_ctx {
    const glpgp_mesh *m;
    glpgp_quadmesh *q;
    const glpgp_qs_proj *P;
    int *vs, *vf;          /* vertex -> its faces (CSR) */
    unsigned char *locked; /* per quad vertex */
    double *floor_;        /* per face: min(0.3, its scaled Jacobian before) */
    double *fn;            /* per face: its unit normal before (3) */
    double *cd;            /* per face: its samples' distance to the surface allowed (max(CD_MAX h, before)) */
    double h;
    double feature_deg; /* the sharp edges locked (glpgp_surface_features) */
    /* the boundary slide: per input vertex its loop's next and previous
     * vertex (-1: not on a loop) and whether it is a corner; per quad vertex
     * the input boundary edge it lies on (its first vertex; -1: it does not
     * slide) and its two neighbours on the quad mesh's boundary */
    int *bnext, *bprev;
    unsigned char *corner;
    int *slide, *qbn;
} sm_ctx;


/* Barycentric coordinates of x in input triangle t. */
static void bary(const glpgp_mesh *m, int t, const double *x, double *w)
{
    const double *a = m->xyz + 3 * m->tri[3 * t], *b = m->xyz + 3 * m->tri[3 * t + 1], *c = m->xyz + 3 * m->tri[3 * t + 2];
    double v0[3], v1[3], v2[3];
    for (int d = 0; d < 3; d++) {
        v0[d] = b[d] - a[d];
        v1[d] = c[d] - a[d];
        v2[d] = x[d] - a[d];
    }
    const double d00 = v0[0] * v0[0] + v0[1] * v0[1] + v0[2] * v0[2], d01 = v0[0] * v1[0] + v0[1] * v1[1] + v0[2] * v1[2];
    const double d11 = v1[0] * v1[0] + v1[1] * v1[1] + v1[2] * v1[2], d20 = v2[0] * v0[0] + v2[1] * v0[1] + v2[2] * v0[2];
    const double d21 = v2[0] * v1[0] + v2[1] * v1[1] + v2[2] * v1[2], den = d00 * d11 - d01 * d01;
    w[1] = den > 0 ? (d11 * d20 - d01 * d21) / den : 0.0;
    w[2] = den > 0 ? (d00 * d21 - d01 * d20) / den : 0.0;
    w[0] = 1.0 - w[1] - w[2];
}

/* The input's boundary loops (next / previous vertex along the boundary
 * half-edges) and their corners: the loop turns there by more than
 * BND_CORNER_DEG, or a sharp feature edge (hf, not a boundary) ends there. */
static void boundary_loops(sm_ctx *c, const unsigned char *hf)
{
    const glpgp_mesh *m = c->m;
    for (int v = 0; v < m->nv; v++) c->bnext[v] = c->bprev[v] = -1;
    for (int h = 0; h < 3 * m->nt; h++) {
        const int a = m->tri[h], b = m->tri[h - h % 3 + (h % 3 + 1) % 3];
        if (m->surf->twin[h] < 0) {
            c->bnext[a] = b;
            c->bprev[b] = a;
        } else if (hf[h]) {
            c->corner[a] = c->corner[b] = 1;
        }
    }
    const double cmax = cos(BND_CORNER_DEG * GLPGP_PI / 180.0);
    for (int v = 0; v < m->nv; v++) {
        const int a = c->bprev[v], b = c->bnext[v];
        if (a < 0 || b < 0) continue;
        double e0[3], e1[3];
        for (int d = 0; d < 3; d++) {
            e0[d] = m->xyz[3 * v + d] - m->xyz[3 * a + d];
            e1[d] = m->xyz[3 * b + d] - m->xyz[3 * v + d];
        }
        const double n0 = sqrt(e0[0] * e0[0] + e0[1] * e0[1] + e0[2] * e0[2]);
        const double n1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
        if (!(n0 > 0 && n1 > 0) || (e0[0] * e1[0] + e0[1] * e1[1] + e0[2] * e1[2]) < cmax * n0 * n1) c->corner[v] = 1;
    }
}

/* slide[v] for a quad vertex on the quad mesh's boundary with exactly two
 * boundary edges (qbn) whose nearest input point x (triangle t, barycentric
 * w) lies on an input boundary edge and not at a corner: that edge's first
 * vertex along its loop. */
static void slide_start(sm_ctx *c, int v, int t, const double *w)
{
    const glpgp_mesh *m = c->m;
    for (int k = 0; k < 3; k++) {
        const int h = 3 * t + (k + 1) % 3; /* the edge opposite corner k */
        if (w[k] >= 1e-6 || m->surf->twin[h] >= 0) continue;
        const int a = m->tri[h], b = m->tri[3 * t + (k + 2) % 3];
        const double wa = w[(k + 1) % 3], wb = w[(k + 2) % 3];
        if ((wa > 1.0 - 1e-6 && c->corner[a]) || (wb > 1.0 - 1e-6 && c->corner[b])) return;
        if (c->bnext[a] != b) return;
        c->slide[v] = a;
        return;
    }
}

/* locked: the quad mesh's boundary and non-manifold vertices (an edge not
 * in exactly two faces) and the vertices on the input's boundary or sharp
 * features (on such an edge or at such an edge's end); of those on the
 * boundary, the ones that may slide along the input's boundary (slide). */
static glpgp_status lock_vertices(sm_ctx *c)
{
    const glpgp_mesh *m = c->m;
    const glpgp_quadmesh *q = c->q;
    const int nc = q->face_start[q->nf];
    unsigned char *hf = NULL, *vfeat = NULL, *bad = NULL;
    long long *key = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)3 * m->nt + 1, 1, &hf), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)m->nv + 1, 1, &vfeat), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)q->nv + 1, 1, &bad), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof *key, &key), done);
    GLPGP_CHECK_GOTO(st, glpgp_surface_features(m, c->feature_deg, hf, NULL), done);
    boundary_loops(c, hf);
    for (int h = 0; h < 3 * m->nt; h++) {
        if (m->surf->twin[h] < 0) hf[h] = 1;
        if (hf[h]) vfeat[m->tri[h]] = vfeat[m->tri[h - h % 3 + (h % 3 + 1) % 3]] = 1;
    }
    for (int f = 0; f < q->nf; f++) {
        const int s = q->face_start[f], n = q->face_start[f + 1] - s;
        for (int i = 0; i < n; i++) {
            long long a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % n];
            key[s + i] = a < b ? a * q->nv + b : b * q->nv + a;
        }
    }
    qsort(key, (size_t)nc, sizeof *key, cmp_key);
    for (int v = 0; v < 2 * q->nv; v++) c->qbn[v] = -1;
    for (int i = 0; i < nc;) {
        int j = i;
        while (j < nc && key[j] == key[i]) j++;
        const int a = (int)(key[i] / q->nv), b = (int)(key[i] % q->nv);
        if (j - i != 2) c->locked[a] = c->locked[b] = 1;
        if (j - i > 2) bad[a] = bad[b] = 1;
        for (int e = 0; e < 2 && j - i == 1; e++) { /* a boundary edge: each end's boundary neighbour */
            const int x = e ? b : a, y = e ? a : b;
            if (c->qbn[2 * x] < 0) c->qbn[2 * x] = y;
            else if (c->qbn[2 * x + 1] < 0) c->qbn[2 * x + 1] = y;
            else bad[x] = 1;
        }
        i = j;
    }
    for (int v = 0; v < q->nv; v++) {
        double x[3], w[3];
        c->slide[v] = -1;
        const int t = glpgp_qs_proj_nearest(c->P, q->xyz + 3 * v, x);
        if (t < 0) continue;
        bary(m, t, x, w);
        if (c->locked[v]) {
            if (!bad[v] && c->qbn[2 * v + 1] >= 0) slide_start(c, v, t, w);
            continue;
        }
        for (int k = 0; k < 3; k++) {
            if (w[k] < 1e-6 && hf[3 * t + (k + 1) % 3]) c->locked[v] = 1; /* on the edge opposite corner k */
            if (w[k] > 1.0 - 1e-6 && vfeat[m->tri[3 * t + k]]) c->locked[v] = 1;
        }
    }
done:
    free(hf);
    free(vfeat);
    free(bad);
    free(key);
    return st;
}

/* Smallest scaled Jacobian of v's faces with v at its current place; -2
 * when a face falls below its floor or turns. */
static double worst_at(const sm_ctx *c, int v)
{
    double w = 2.0;
    for (int j = c->vs[v]; j < c->vs[v + 1]; j++) {
        const int f = c->vf[j];
        const double sj = glpgp_quadmesh_face_sj_surface(c->q, f);
        double N[3];
        glpgp_quadmesh_face_normal(c->q, f, 1, N);
        if (sj < c->floor_[f] || N[0] * c->fn[3 * f] + N[1] * c->fn[3 * f + 1] + N[2] * c->fn[3 * f + 2] <= 0.0)
            return -2.0;
        w = fmin(w, sj);
    }
    return w;
}

/* The largest distance to the surface (nearest point within the
 * projection's cap; INFINITY: none) of face f's samples, taken as the
 * check takes them (quads_surface.h: the face fanned from its first corner
 * into triangles): each fan triangle's centroid and its sides' midpoints;
 * *tn the surface's normal at the face centre's nearest point */
static double face_dist(const sm_ctx *c, int f, const double **tn)
{
    const glpgp_quadmesh *q = c->q;
    const int s = q->face_start[f], n = q->face_start[f + 1] - s;
    const double *X = q->xyz;
    double cn[3] = {0, 0, 0}, x[3], far = 0.0;
    for (int i = 0; i < n; i++)
        for (int d = 0; d < 3; d++) cn[d] += X[3 * q->face_vert[s + i] + d] / n;
    const int t0 = glpgp_qs_proj_nearest(c->P, cn, x);
    if (t0 < 0) return INFINITY;
    *tn = c->m->surf->tframe + 9 * t0 + 6;
    for (int i = 1; i + 1 < n; i++) { /* fan triangle (0, i, i+1) */
        const double *a = X + 3 * q->face_vert[s], *b = X + 3 * q->face_vert[s + i], *e = X + 3 * q->face_vert[s + i + 1];
        for (int k = 0; k < 4; k++) {
            double p[3];
            for (int d = 0; d < 3; d++)
                p[d] = k == 0 ? (a[d] + b[d] + e[d]) / 3.0 : k == 1 ? 0.5 * (a[d] + b[d]) : k == 2 ? 0.5 * (b[d] + e[d])
                                                                                          : 0.5 * (e[d] + a[d]);
            if (glpgp_qs_proj_nearest(c->P, p, x) < 0) return INFINITY;
            far = fmax(far, sqrt((x[0] - p[0]) * (x[0] - p[0]) + (x[1] - p[1]) * (x[1] - p[1]) + (x[2] - p[2]) * (x[2] - p[2])));
        }
    }
    return far;
}

/* Whether v's faces, as the check sees them, stay on the surface: each
 * face's normal along the surface's at its centre (the check's inverted
 * test), its samples no farther from the surface than allowed. */
static int surface_ok(const sm_ctx *c, int v)
{
    for (int j = c->vs[v]; j < c->vs[v + 1]; j++) {
        const int f = c->vf[j];
        double N[3];
        const double *tn = NULL;
        const double d = face_dist(c, f, &tn);
        if (!(d <= c->cd[f])) return 0;
        glpgp_quadmesh_face_normal(c->q, f, 0, N);
        if (N[0] * tn[0] + N[1] * tn[1] + N[2] * tn[2] <= 0.0) return 0;
    }
    return 1;
}

/* The targets of v: the mean of its edge neighbours at 1, 1/2, 1/4 of the
 * way, and the corner making its worst quad a parallelogram at 1, 1/2.
 * Returns their count. */
static int targets(const sm_ctx *c, int v, double (*T)[3])
{
    const glpgp_quadmesh *q = c->q;
    const double *p = q->xyz + 3 * v;
    double L[3] = {0, 0, 0}, par[3] = {0, 0, 0}, worst = 3.0;
    int k = 0, haspar = 0;
    for (int j = c->vs[v]; j < c->vs[v + 1]; j++) {
        const int f = c->vf[j], s = q->face_start[f], n = q->face_start[f + 1] - s;
        int i = 0;
        while (i < n && q->face_vert[s + i] != v) i++;
        const double *a = q->xyz + 3 * q->face_vert[s + (i + 1) % n], *b = q->xyz + 3 * q->face_vert[s + (i + n - 1) % n];
        for (int d = 0; d < 3; d++) L[d] += a[d] + b[d];
        k += 2;
        const double sj = glpgp_quadmesh_face_sj_surface(q, f);
        if (n == 4 && sj < worst) {
            const double *o = q->xyz + 3 * q->face_vert[s + (i + 2) % 4];
            worst = sj;
            haspar = 1;
            for (int d = 0; d < 3; d++) par[d] = a[d] + b[d] - o[d];
        }
    }
    int nt = 0;
    static const double wl[3] = {1.0, 0.5, 0.25}, wp[2] = {1.0, 0.5};
    for (int x = 0; x < 3 && k; x++, nt++)
        for (int d = 0; d < 3; d++) T[nt][d] = p[d] + wl[x] * (L[d] / k - p[d]);
    for (int x = 0; x < 2 && haspar; x++, nt++)
        for (int d = 0; d < 3; d++) T[nt][d] = p[d] + wp[x] * (par[d] - p[d]);
    return nt;
}

/* One try at moving v; returns 1 when it moved. */
static int move_vertex(const sm_ctx *c, int v)
{
    glpgp_quadmesh *q = c->q;
    double *p = q->xyz + 3 * v, old[3], best[3], T[5][3], vn[3] = {0, 0, 0};
    memcpy(old, p, sizeof old);
    const double before = worst_at(c, v);
    double bval = before + 1e-4;
    int found = 0;
    for (int j = c->vs[v]; j < c->vs[v + 1]; j++)
        for (int d = 0; d < 3; d++) vn[d] += c->fn[3 * c->vf[j] + d];
    const int nt = targets(c, v, T);
    for (int k = 0; k < nt; k++) {
        double x[3];
        const int t = glpgp_qs_proj_nearest(c->P, T[k], x);
        if (t < 0) continue;
        const double *tn = c->m->surf->tframe + 9 * t + 6; /* the surface there faces v's faces' way */
        if (tn[0] * vn[0] + tn[1] * vn[1] + tn[2] * vn[2] <= 0.0) continue;
        memcpy(p, x, sizeof x);
        const double w = worst_at(c, v);
        if (w > bval && surface_ok(c, v)) {
            bval = w;
            memcpy(best, x, sizeof x);
            found = 1;
        }
    }
    memcpy(p, found ? best : old, sizeof old);
    return found;
}

/* *best / x / *a0 <- the squared distance, the point and the edge's first
 * vertex when edge (a, b) holds a point nearer to T than *best */
static void seg_nearest(const glpgp_mesh *m, int a, int b, const double *T, double *best, double *x, int *a0)
{
    const double *pa = m->xyz + 3 * a, *pb = m->xyz + 3 * b;
    double e[3], d2 = 0.0, s = 0.0, y[3];
    for (int d = 0; d < 3; d++) {
        e[d] = pb[d] - pa[d];
        d2 += e[d] * e[d];
        s += (T[d] - pa[d]) * e[d];
    }
    s = d2 > 0.0 ? fmin(1.0, fmax(0.0, s / d2)) : 0.0;
    double r = 0.0;
    for (int d = 0; d < 3; d++) {
        y[d] = pa[d] + s * e[d];
        r += (T[d] - y[d]) * (T[d] - y[d]);
    }
    if (r < *best) {
        *best = r;
        memcpy(x, y, sizeof y);
        *a0 = a;
    }
}

/* x <- the point nearest to T on the input boundary loop through edge (a,
 * bnext[a]), between the corners around it (at most BND_WALK edges each
 * way); returns the first vertex of x's edge */
static int loop_nearest(const sm_ctx *c, int a, const double *T, double *x)
{
    double best = INFINITY;
    int a0 = a;
    for (int u = a, k = 0; k < BND_WALK; k++) { /* forward: edges (u, next u) */
        const int b = c->bnext[u];
        seg_nearest(c->m, u, b, T, &best, x, &a0);
        if (c->corner[b] || b == a) break;
        u = b;
    }
    for (int u = a, k = 0; k < BND_WALK && !c->corner[u]; k++) { /* backward: edges (prev u, u) */
        const int p = c->bprev[u];
        if (p == c->bnext[a]) break; /* the whole loop seen */
        seg_nearest(c->m, p, u, T, &best, x, &a0);
        u = p;
        if (u == a) break;
    }
    return a0;
}

/* One try at sliding boundary vertex v along its input boundary loop:
 * targets the mean of its two boundary neighbours (1, 1/2, 1/4 of the way)
 * and those of an interior vertex (targets()), each moved onto the loop;
 * returns 1 when it moved. */
static int slide_vertex(const sm_ctx *c, int v)
{
    glpgp_quadmesh *q = c->q;
    double *p = q->xyz + 3 * v, old[3], best[3], T[8][3];
    memcpy(old, p, sizeof old);
    double bval = worst_at(c, v) + 1e-4;
    int found = 0, bseg = c->slide[v];
    const double *n0 = q->xyz + 3 * c->qbn[2 * v], *n1 = q->xyz + 3 * c->qbn[2 * v + 1];
    static const double wl[3] = {1.0, 0.5, 0.25};
    for (int x = 0; x < 3; x++)
        for (int d = 0; d < 3; d++) T[x][d] = p[d] + wl[x] * (0.5 * (n0[d] + n1[d]) - p[d]);
    const int nt = 3 + targets(c, v, T + 3);
    for (int k = 0; k < nt; k++) {
        double x[3];
        const int a0 = loop_nearest(c, c->slide[v], T[k], x);
        memcpy(p, x, sizeof x);
        const double w = worst_at(c, v);
        if (w > bval && surface_ok(c, v)) {
            bval = w;
            memcpy(best, x, sizeof x);
            bseg = a0;
            found = 1;
        }
    }
    memcpy(p, found ? best : old, sizeof old);
    c->slide[v] = bseg;
    return found;
}

static glpgp_status setup(sm_ctx *c)
{
    glpgp_quadmesh *q = c->q;
    const int nc = q->face_start[q->nf];
    int *cnt = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)q->nv + 2, sizeof(int), &c->vs));
    GLPGP_CHECK(glpgp_malloc((size_t)nc + 1, sizeof(int), &c->vf));
    GLPGP_CHECK(glpgp_calloc((size_t)q->nv + 1, 1, &c->locked));
    GLPGP_CHECK(glpgp_malloc((size_t)q->nf + 1, sizeof(double), &c->floor_));
    GLPGP_CHECK(glpgp_malloc((size_t)3 * q->nf + 3, sizeof(double), &c->fn));
    GLPGP_CHECK(glpgp_malloc((size_t)q->nf + 1, sizeof(double), &c->cd));
    GLPGP_CHECK(glpgp_malloc((size_t)c->m->nv + 1, sizeof(int), &c->bnext));
    GLPGP_CHECK(glpgp_malloc((size_t)c->m->nv + 1, sizeof(int), &c->bprev));
    GLPGP_CHECK(glpgp_calloc((size_t)c->m->nv + 1, 1, &c->corner));
    GLPGP_CHECK(glpgp_malloc((size_t)q->nv + 1, sizeof(int), &c->slide));
    GLPGP_CHECK(glpgp_malloc((size_t)2 * q->nv + 2, sizeof(int), &c->qbn));
    GLPGP_CHECK(glpgp_calloc((size_t)q->nv + 1, sizeof(int), &cnt));
    for (int k = 0; k < nc; k++) c->vs[q->face_vert[k] + 1]++;
    for (int v = 0; v < q->nv; v++) c->vs[v + 1] += c->vs[v];
    for (int f = 0; f < q->nf; f++)
        for (int k = q->face_start[f]; k < q->face_start[f + 1]; k++) {
            const int v = q->face_vert[k];
            c->vf[c->vs[v] + cnt[v]++] = f;
        }
    free(cnt);
    for (int f = 0; f < q->nf; f++) {
        c->floor_[f] = fmin(SJ_FLOOR, glpgp_quadmesh_face_sj_surface(q, f));
        glpgp_quadmesh_face_normal(q, f, 1, c->fn + 3 * f);
        const double *tn = NULL;
        c->cd[f] = fmax(CD_MAX * c->h, face_dist(c, f, &tn));
    }
    return lock_vertices(c);
}

glpgp_status glpgp_quads_smooth_surface(const glpgp_mesh *m, double h, double feature_deg, int sweeps,
                                        glpgp_quadmesh *q, int *moved)
{
    if (moved) *moved = 0;
    if (!q || !q->xyz || q->nf == 0 || sweeps <= 0) return GLPGP_OK;
    sm_ctx c;
    memset(&c, 0, sizeof c);
    c.m = m;
    c.q = q;
    c.h = h;
    c.feature_deg = feature_deg;
    glpgp_qs_proj *P = NULL;
    unsigned char *did = NULL;
    glpgp_status st = glpgp_qs_proj_create(m, h, 0.5 * h, &P);
    c.P = P;
    if (st == GLPGP_OK) st = setup(&c);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)q->nv + 1, 1, &did);
    for (int it = 0; it < sweeps && st == GLPGP_OK; it++) {
        int changed = 0;
        for (int v = 0; v < q->nv; v++) {
            if (c.vs[v + 1] - c.vs[v] < 1 || (c.locked[v] && c.slide[v] < 0)) continue;
            if (c.locked[v] ? slide_vertex(&c, v) : c.vs[v + 1] - c.vs[v] >= 2 && move_vertex(&c, v)) {
                changed++;
                if (!did[v] && moved) (*moved)++;
                did[v] = 1;
            }
        }
        if (!changed) break;
    }
    for (int v = 0; v < q->nv; v++) { /* the planar copy the writers and the pictures read */
        q->xy[2 * v] = q->xyz[3 * v];
        q->xy[2 * v + 1] = q->xyz[3 * v + 1];
    }
    glpgp_qs_proj_destroy(&P);
    free(c.vs);
    free(c.vf);
    free(c.locked);
    free(c.floor_);
    free(c.fn);
    free(c.cd);
    free(c.bnext);
    free(c.bprev);
    free(c.corner);
    free(c.slide);
    free(c.qbn);
    free(did);
    return st;
}
