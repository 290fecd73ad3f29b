/* quads/trisplit.c: the fallback fill of a repair region (repair.h,
 * glpgp_trisplit_fill), used where the cut mesher (qcut.c) fails:
 *  1. the loops of the region (an outer loop and its holes) are
 *     triangulated: holes bridged to the outer loop (shortest bridge that
 *     crosses nothing), ear clipping, edge flips to the constrained Delaunay
 *     triangulation, inner edges longer than 2.6 h bisected (longest edge
 *     first, then flips again);
 *  2. triangles become quads without splitting the edges shared with the
 *     kept faces: every other edge starts "split" (a new vertex: its
 *     midpoint, or for a piece of domain boundary the input vertex nearest
 *     its middle), so a triangle with no edge on K has 3 split edges and
 *     becomes 3 quads around its centroid (a, m_ab, g, m_ca); a triangle
 *     with an edge on K has an even count, which no quad split allows:
 *     these defects are paired by shortest paths in the dual graph, each
 *     crossed edge toggled (split <-> not), or sent to a domain boundary
 *     edge (toggled too). Then every triangle has 1 or 3 split edges; one
 *     split edge (m on side c a): five quads, a ring (a b pb pa), (b c pc
 *     pb), (c m pm pc), (m a pa pm) around the inner quad (pa pb pc pm),
 *     p = g + s (corner - g) -- all convex for a valid triangle. A defect
 *     left (no partner, no boundary) stays a pentagon for the closing.
 * The quads are valid but irregular (a centroid of valence 3 per triangle,
 * fans at the input's boundary points): the cut mesher is preferred. */
#include "glpgp/internal/edgekey.h"
#include "repair.h"
#include "geom.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- triangulation of a polygon with holes ---------------------------------- */

typedef struct tri_ctx {
    dvec xy;     /* points (local ids) */
    ivec kind;   /* per point: 0 interior, 1 on K (interface), 2 domain boundary */
    ivec glob;   /* per point: vertex id in the output (-1: new) */
    ivec tri;    /* 3 per triangle, CCW */
    ivec cons_a, cons_b; /* constrained (region boundary) edges a -> b and their kind: */
    ivec cons_k;         /* 1 interface with K, 2 domain boundary */
} tri_ctx;

/* Whether segment pq crosses one of the segments e[2i] -> e[2i+1] (ends
 * at skip_a / skip_b excepted), or passes through one of their ends. */
static int seg_cross_any(const double *xy, const int *e, int n, const double *p, const double *q, int skip_a,
                         int skip_b)
{
    for (int i = 0; i + 1 < n; i += 2) {
        int a = e[i], b = e[i + 1];
        if (a == skip_a || b == skip_a || a == skip_b || b == skip_b) continue;
        const double *A = xy + 2 * a, *Bp = xy + 2 * b;
        double d1 = glpgp_orient2(p, q, A), d2 = glpgp_orient2(p, q, Bp), d3 = glpgp_orient2(A, Bp, p), d4 = glpgp_orient2(A, Bp, q);
        if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 1;
        /* an end on the open segment */
        if (d1 == 0 && (A[0] - p[0]) * (A[0] - q[0]) + (A[1] - p[1]) * (A[1] - q[1]) < 0) return 1;
    }
    return 0;
}

/* Merge holes into the outer ring by bridges; *ring receives the merged
 * ring (with duplicated vertex ids: dup[] maps to the originals). */
static glpgp_status bridge_holes(tri_ctx *T, ivec *ring, const ivec *holes, int nholes, ivec *all_edges)
{
    /* holes sorted by their max x, largest first */
    for (int k = 0; k < nholes; k++) {
        int best_h = -1;
        double bx = -INFINITY;
        for (int j = 0; j < nholes; j++) {
            if (holes[j].n < 0) continue;
            for (int i = 0; i < holes[j].n; i++)
                if (T->xy.p[2 * holes[j].p[i]] > bx) {
                    bx = T->xy.p[2 * holes[j].p[i]];
                    best_h = j;
                }
        }
        if (best_h < 0) break;
        ivec *H = (ivec *)&holes[best_h];
        /* the hole's vertex M and a ring vertex V, nearest pair whose segment crosses nothing */
        int bm = -1, bv = -1;
        double bd = INFINITY;
        for (int i = 0; i < H->n; i++) {
            int M = H->p[i];
            const double *pm = T->xy.p + 2 * M;
            for (int j = 0; j < ring->n; j++) {
                int V = ring->p[j];
                const double *pv = T->xy.p + 2 * V;
                double d = hypot(pv[0] - pm[0], pv[1] - pm[1]);
                if (d >= bd) continue;
                /* inside the ring's angle at V: the bridge must leave V into the polygon */
                int pj = ring->p[(j + ring->n - 1) % ring->n], nj = ring->p[(j + 1) % ring->n];
                const double *pp = T->xy.p + 2 * pj, *pn = T->xy.p + 2 * nj;
                double o1 = glpgp_orient2(pv, pn, pm), o2 = glpgp_orient2(pp, pv, pm), conv = glpgp_orient2(pp, pv, pn);
                int in_angle = conv >= 0 ? (o1 > 0 && o2 > 0) : (o1 > 0 || o2 > 0);
                if (!in_angle) continue;
                if (seg_cross_any(T->xy.p, all_edges->p, all_edges->n, pm, pv, M, V)) continue;
                bd = d;
                bm = i;
                bv = j;
            }
        }
        if (bm < 0) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "quad repair: no bridge to a hole");
        GLPGP_CHECK(ipush(all_edges, H->p[bm]));
        GLPGP_CHECK(ipush(all_edges, ring->p[bv]));
        /* ring: ... V, M, hole from M round to M, V', ... */
        ivec nr = {0};
        for (int j = 0; j <= bv; j++) GLPGP_CHECK(ipush(&nr, ring->p[j]));
        for (int i = 0; i <= H->n; i++) GLPGP_CHECK(ipush(&nr, H->p[(bm + i) % H->n]));
        GLPGP_CHECK(ipush(&nr, ring->p[bv]));
        for (int j = bv + 1; j < ring->n; j++) GLPGP_CHECK(ipush(&nr, ring->p[j]));
        free(ring->p);
        *ring = nr;
        H->n = -1;
    }
    return GLPGP_OK;
}

/* Ear clipping of the ring (CCW, may repeat vertices at bridges). */
static glpgp_status ear_clip(tri_ctx *T, const ivec *ring)
{
    int n = ring->n;
    if (n < 3) return GLPGP_OK;
    int *prv = NULL, *nxt = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)n, sizeof(int), &prv));
    glpgp_status st = glpgp_malloc((size_t)n, sizeof(int), &nxt);
    if (st != GLPGP_OK) {
        free(prv);
        return st;
    }
    for (int i = 0; i < n; i++) {
        prv[i] = (i + n - 1) % n;
        nxt[i] = (i + 1) % n;
    }
    const double *xy = T->xy.p;
    int left = n, cur = 0, stall = 0;
    while (left > 3 && st == GLPGP_OK) {
        int a = prv[cur], c = nxt[cur];
        const double *pa = xy + 2 * ring->p[a], *pb = xy + 2 * ring->p[cur], *pc = xy + 2 * ring->p[c];
        double ar = glpgp_orient2(pa, pb, pc);
        int ear = ar > 0;
        if (ear) {
            /* no other vertex inside or on the triangle (duplicates of the corners excepted) */
            for (int j = nxt[c]; j != a && ear; j = nxt[j]) {
                int v = ring->p[j];
                if (v == ring->p[a] || v == ring->p[cur] || v == ring->p[c]) continue;
                const double *p = xy + 2 * v;
                if (glpgp_orient2(pa, pb, p) >= 0 && glpgp_orient2(pb, pc, p) >= 0 && glpgp_orient2(pc, pa, p) >= 0) ear = 0;
            }
        }
        if (!ear && stall > 2 * left) {
            /* no ear left (rounding): clip the most convex corner */
            double best = -INFINITY;
            int bi = cur, j = cur;
            for (int k = 0; k < left; k++, j = nxt[j]) {
                double o = glpgp_orient2(xy + 2 * ring->p[prv[j]], xy + 2 * ring->p[j], xy + 2 * ring->p[nxt[j]]);
                if (o > best) {
                    best = o;
                    bi = j;
                }
            }
            cur = bi;
            a = prv[cur];
            c = nxt[cur];
            ear = 1;
        }
        if (ear) {
            st = ipush(&T->tri, ring->p[a]);
            if (st == GLPGP_OK) st = ipush(&T->tri, ring->p[cur]);
            if (st == GLPGP_OK) st = ipush(&T->tri, ring->p[c]);
            nxt[a] = c;
            prv[c] = a;
            left--;
            cur = a;
            stall = 0;
        } else {
            cur = nxt[cur];
            stall++;
        }
    }
    if (st == GLPGP_OK && left == 3) {
        int a = prv[cur], c = nxt[cur];
        st = ipush(&T->tri, ring->p[a]);
        if (st == GLPGP_OK) st = ipush(&T->tri, ring->p[cur]);
        if (st == GLPGP_OK) st = ipush(&T->tri, ring->p[c]);
    }
    free(prv);
    free(nxt);
    return st;
}

/* ---- triangle adjacency, flips, refinement ---------------------------------- */

typedef struct tadj {
    int *nb; /* 3 per triangle: the triangle across side j = (v_j, v_j+1), -1 none */
} tadj;

/* Constrained edge lookup (sorted keys). */
typedef struct eset {
    unsigned long long *k;
    int *val;
    int n;
} eset;
static int eset_find(const eset *E, int a, int b)
{
    unsigned long long key = glpgp_edge_key(a, b);
    int lo = 0, hi = E->n - 1;
    while (lo <= hi) {
        int mid = (lo + hi) / 2;
        if (E->k[mid] == key) return E->val[mid];
        if (E->k[mid] < key)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return 0;
}

static glpgp_status build_adj(const tri_ctx *T, int **nb)
{
    int nt = T->tri.n / 3;
    glpgp_ekv *E = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)3 * nt + 1, sizeof *E, &E));
    glpgp_status st = glpgp_malloc((size_t)3 * nt + 1, sizeof(int), nb);
    if (st != GLPGP_OK) {
        free(E);
        return st;
    }
    for (int t = 0; t < nt; t++)
        for (int j = 0; j < 3; j++) {
            E[3 * t + j].k = glpgp_edge_key(T->tri.p[3 * t + j], T->tri.p[3 * t + (j + 1) % 3]);
            E[3 * t + j].slot = 3 * t + j;
            (*nb)[3 * t + j] = -1;
        }
    qsort(E, (size_t)3 * nt, sizeof *E, glpgp_ekv_cmp);
    for (int i = 0; i + 1 < 3 * nt; i++)
        if (E[i].k == E[i + 1].k) {
            (*nb)[E[i].slot] = E[i + 1].slot / 3;
            (*nb)[E[i + 1].slot] = E[i].slot / 3;
            i++;
        }
    free(E);
    return GLPGP_OK;
}

static int incircle(const double *a, const double *b, const double *c, const double *d)
{
    double adx = a[0] - d[0], ady = a[1] - d[1], bdx = b[0] - d[0], bdy = b[1] - d[1], cdx = c[0] - d[0],
           cdy = c[1] - d[1];
    double det = (adx * adx + ady * ady) * (bdx * cdy - bdy * cdx) - (bdx * bdx + bdy * bdy) * (adx * cdy - ady * cdx) +
                 (cdx * cdx + cdy * cdy) * (adx * bdy - ady * bdx);
    double scale = (adx * adx + ady * ady + bdx * bdx + bdy * bdy + cdx * cdx + cdy * cdy);
    return det > 1e-12 * scale * scale;
}

/* Lawson flips to the constrained Delaunay triangulation. */
static glpgp_status flips(tri_ctx *T, const eset *C)
{
    for (int pass = 0; pass < 50; pass++) {
        int *nb = NULL;
        GLPGP_CHECK(build_adj(T, &nb));
        int nt = T->tri.n / 3, nflip = 0;
        unsigned char *touched = calloc((size_t)nt + 1, 1);
        if (!touched) {
            free(nb);
            return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
        }
        for (int t = 0; t < nt; t++) {
            if (touched[t]) continue;
            for (int j = 0; j < 3; j++) {
                int u = nb[3 * t + j];
                if (u < 0 || touched[u]) continue;
                int *A = T->tri.p + 3 * t, *Bt = T->tri.p + 3 * u;
                int a = A[j], b = A[(j + 1) % 3], c = A[(j + 2) % 3];
                if (eset_find(C, a, b)) continue;
                int k = 0;
                while (k < 3 && !(Bt[k] == b && Bt[(k + 1) % 3] == a)) k++;
                if (k == 3) continue;
                int d = Bt[(k + 2) % 3];
                const double *xy = T->xy.p;
                if (!incircle(xy + 2 * a, xy + 2 * b, xy + 2 * c, xy + 2 * d)) continue;
                /* the quad a d b c must be convex for the flip */
                if (glpgp_orient2(xy + 2 * c, xy + 2 * a, xy + 2 * d) <= 0 || glpgp_orient2(xy + 2 * d, xy + 2 * b, xy + 2 * c) <= 0)
                    continue;
                A[0] = c;
                A[1] = a;
                A[2] = d;
                Bt[0] = d;
                Bt[1] = b;
                Bt[2] = c;
                touched[t] = touched[u] = 1;
                nflip++;
                break;
            }
        }
        free(touched);
        free(nb);
        if (!nflip) break;
    }
    return GLPGP_OK;
}

/* Longest-edge bisection: a triangle whose longest edge is longer than
 * lmax and not a region boundary edge is split with its neighbour at the
 * edge's midpoint (t = a b c, u = b a d -> a m c, m b c, b m d, m a d) unless
 * c or d is closer than L/4 to the edge (slivers along a long region
 * boundary edge, which bisection cannot fix), then edge flips; repeated while something is split (at most max_new points).
 * Unlike centroids, bisection never makes a triangle thinner than its
 * parent's halves (no cascade of points in slivers). */
static glpgp_status refine(tri_ctx *T, const eset *C, double lmax, int max_new)
{
    for (int pass = 0; pass < 60 && max_new > 0; pass++) {
        int *nb = NULL;
        GLPGP_CHECK(build_adj(T, &nb));
        int nt = T->tri.n / 3, added = 0;
        unsigned char *done = calloc((size_t)nt + 1, 1);
        if (!done) {
            free(nb);
            return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
        }
        glpgp_status st = GLPGP_OK;
        for (int t = 0; t < nt && max_new > 0 && st == GLPGP_OK; t++) {
            if (done[t]) continue;
            int *v = T->tri.p + 3 * t, jl = -1;
            double L = lmax;
            for (int j = 0; j < 3; j++) {
                const double *a = T->xy.p + 2 * v[j], *b = T->xy.p + 2 * v[(j + 1) % 3];
                double l = hypot(b[0] - a[0], b[1] - a[1]);
                if (l > L) {
                    L = l;
                    jl = j;
                }
            }
            if (jl < 0) continue;
            int a = v[jl], b = v[(jl + 1) % 3], c = v[(jl + 2) % 3];
            if (eset_find(C, a, b)) continue; /* a region boundary edge: kept */
            int u = nb[3 * t + jl];
            if (u < 0 || done[u]) continue;
            int *w = T->tri.p + 3 * u, k = 0;
            while (k < 3 && !(w[k] == b && w[(k + 1) % 3] == a)) k++;
            if (k == 3) continue;
            int d = w[(k + 2) % 3];
            {   /* not next to a sliver: bisecting there only piles points onto its long side */
                const double *pa = T->xy.p + 2 * a, *pb = T->xy.p + 2 * b;
                double hc = fabs(glpgp_orient2(pa, pb, T->xy.p + 2 * c)) / L, hd = fabs(glpgp_orient2(pa, pb, T->xy.p + 2 * d)) / L;
                if (hc < 0.25 * L || hd < 0.25 * L) continue;
            }
            int mi = T->xy.n / 2;
            double mx = 0.5 * (T->xy.p[2 * a] + T->xy.p[2 * b]), my = 0.5 * (T->xy.p[2 * a + 1] + T->xy.p[2 * b + 1]);
            st = dpush(&T->xy, mx);
            if (st == GLPGP_OK) st = dpush(&T->xy, my);
            if (st == GLPGP_OK) st = ipush(&T->kind, 0);
            if (st == GLPGP_OK) st = ipush(&T->glob, -1);
            if (st != GLPGP_OK) break;
            v = T->tri.p + 3 * t; /* the two halves in place first, then the two new ones */
            w = T->tri.p + 3 * u;
            v[0] = a;
            v[1] = mi;
            v[2] = c;
            w[0] = b;
            w[1] = mi;
            w[2] = d;
            int nt4[6] = {mi, b, c, mi, a, d};
            for (int i = 0; i < 6 && st == GLPGP_OK; i++) st = ipush(&T->tri, nt4[i]);
            done[t] = done[u] = 1;
            added++;
            max_new--;
        }
        free(done);
        free(nb);
        if (st != GLPGP_OK) return st;
        if (!added) break;
        GLPGP_CHECK(flips(T, C));
    }
    return GLPGP_OK;
}

/* ---- triangles -> quads --------------------------------------------------------- */

/* The five quads of a triangle a b c with one split point m on side c -> a. */
static double ring_split(const double *a, const double *b, const double *c, const double *m, double *pts)
{
    double g[2] = {(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3};
    static const double sv[4][2] = {{0.5, 0.75}, {0.4, 0.7}, {0.6, 0.85}, {0.5, 0.9}};
    double best = -INFINITY;
    for (int k = 0; k < 4; k++) {
        double s = sv[k][0], sm = sv[k][1], P[8];
        const double *cr[4] = {a, b, c, m};
        for (int i = 0; i < 4; i++) {
            double f = i == 3 ? sm : s;
            P[2 * i] = g[0] + f * (cr[i][0] - g[0]);
            P[2 * i + 1] = g[1] + f * (cr[i][1] - g[1]);
        }
        /* quads on local points 0..3 = a b c m, 4..7 = pa pb pc pm */
        double xy[16];
        for (int i = 0; i < 4; i++) {
            xy[2 * i] = cr[i][0];
            xy[2 * i + 1] = cr[i][1];
            xy[8 + 2 * i] = P[2 * i];
            xy[8 + 2 * i + 1] = P[2 * i + 1];
        }
        static const int Q[5][4] = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}, {4, 5, 6, 7}};
        double w = INFINITY;
        for (int q = 0; q < 5; q++) w = fmin(w, glpgp_poly_min_sj(xy, Q[q], 4));
        if (w > best) {
            best = w;
            memcpy(pts, P, sizeof P);
        }
    }
    return best;
}


/* ---- one region ------------------------------------------------------------------ */

static void tri_free(tri_ctx *T)
{
    dvec_free(&T->xy);
    ivec_free(&T->kind);
    ivec_free(&T->glob);
    ivec_free(&T->tri);
}

/* Local points of the loops of outer loop O and its holes (ring: the outer
 * loop, holes[]: the holes), the constrained edges (CE: key -> half-edge
 * + 1) and all loop edges (alle, pairs) for the bridges. */
static glpgp_status local_loops(const region *R, int O, tri_ctx *T, int *loc, ivec *ring, ivec *holes, eset *CE,
                                ivec *alle)
{
    glpgp_status st = GLPGP_OK;
    int hi = 0, ncons = 0;
    for (int L = 0; L < R->nloops && st == GLPGP_OK; L++) {
        if (L != O && R->owner[L] != O) continue;
        ivec *dst = L == O ? ring : &holes[hi++];
        for (int i = R->loop_start[L]; i < R->loop_start[L + 1] && st == GLPGP_OK; i++) {
            int v = R->he[R->loopv.p[i]].a;
            if (loc[v] < 0) {
                loc[v] = T->xy.n / 2;
                st = dpush(&T->xy, glpgp_region_xy(R, v)[0]);
                if (st == GLPGP_OK) st = dpush(&T->xy, glpgp_region_xy(R, v)[1]);
                if (st == GLPGP_OK) st = ipush(&T->kind, 1);
                if (st == GLPGP_OK) st = ipush(&T->glob, v);
            }
            if (st == GLPGP_OK) st = ipush(dst, loc[v]);
            ncons++;
        }
    }
    glpgp_ekv *tmp = NULL;
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)ncons + 1, sizeof *tmp, &tmp);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)ncons + 1, sizeof *CE->k, &CE->k);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)ncons + 1, sizeof *CE->val, &CE->val);
    int n = 0;
    for (int L = 0; L < R->nloops && st == GLPGP_OK; L++) {
        if (L != O && R->owner[L] != O) continue;
        for (int i = R->loop_start[L]; i < R->loop_start[L + 1] && st == GLPGP_OK; i++) {
            const rhe *e = &R->he[R->loopv.p[i]];
            tmp[n].k = glpgp_edge_key(loc[e->a], loc[e->b]);
            tmp[n++].slot = R->loopv.p[i];
            st = ipush(alle, loc[e->a]);
            if (st == GLPGP_OK) st = ipush(alle, loc[e->b]);
        }
    }
    if (st == GLPGP_OK) {
        qsort(tmp, (size_t)n, sizeof *tmp, glpgp_ekv_cmp);
        for (int i = 0; i < n; i++) {
            CE->k[i] = tmp[i].k;
            CE->val[i] = 1 + tmp[i].slot;
        }
        CE->n = n;
    }
    free(tmp);
    return st;
}

/* Toggle the split flag of side j of triangle t and of its twin. */
static void toggle(const tri_ctx *T, const int *tnb, int *esplit, int t, int j)
{
    esplit[3 * t + j] ^= 1;
    int u = tnb[3 * t + j];
    if (u < 0) return;
    int a = T->tri.p[3 * t + j], b = T->tri.p[3 * t + (j + 1) % 3];
    for (int k = 0; k < 3; k++)
        if (T->tri.p[3 * u + k] == b && T->tri.p[3 * u + (k + 1) % 3] == a) esplit[3 * u + k] ^= 1;
}

/* Kind of triangle side s (1 interface, 2 domain boundary, 0 inner). */
static int side_kind(const region *R, const tri_ctx *T, const eset *CE, int t, int j)
{
    int cv = eset_find(CE, T->tri.p[3 * t + j], T->tri.p[3 * t + (j + 1) % 3]);
    return cv ? R->he[cv - 1].kind : 0;
}

/* Parity: every triangle with an even number of split sides is paired
 * with another by a path of toggled sides, or sent to the domain boundary. */
static glpgp_status parity_paths(const region *R, const tri_ctx *T, const eset *CE, const int *tnb, int *esplit)
{
    const int nt = T->tri.n / 3;
    int *pred = NULL, *queue = NULL, *predj = NULL;
    glpgp_status st = glpgp_malloc((size_t)nt + 1, sizeof(int), &pred);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nt + 1, sizeof(int), &queue);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nt + 1, sizeof(int), &predj);
    for (int t0 = 0; t0 < nt && st == GLPGP_OK; t0++) {
        if ((esplit[3 * t0] + esplit[3 * t0 + 1] + esplit[3 * t0 + 2]) % 2) continue;
        for (int t = 0; t < nt; t++) pred[t] = -2;
        int qh = 0, qt = 0, target = -1, tb_j = -1;
        pred[t0] = -1;
        queue[qt++] = t0;
        while (qh < qt && target < 0) {
            int t = queue[qh++];
            for (int j = 0; j < 3 && target < 0; j++) {
                int kind = side_kind(R, T, CE, t, j), u = tnb[3 * t + j];
                if (kind == 1) continue; /* K: never split */
                if (u < 0) {
                    if (kind == 2) target = t, tb_j = j;
                    continue;
                }
                if (pred[u] != -2) continue;
                pred[u] = t;
                predj[u] = j;
                if ((esplit[3 * u] + esplit[3 * u + 1] + esplit[3 * u + 2]) % 2 == 0)
                    target = u, tb_j = -1;
                else
                    queue[qt++] = u;
            }
        }
        if (target < 0) continue;
        if (tb_j >= 0) toggle(T, tnb, esplit, target, tb_j);
        for (int t = target; pred[t] >= 0; t = pred[t]) toggle(T, tnb, esplit, pred[t], predj[t]);
    }
    free(pred);
    free(queue);
    free(predj);
    return st;
}

/* The faces of the triangles: 3 quads (three split sides), 5 (one), or the
 * polygon as it is (a defect left). gid: local point -> output vertex. */
static glpgp_status emit_faces(const region *R, const tri_ctx *T, const eset *CE, const int *tnb, const int *esplit,
                               int *epoint, const int *gid, rbuild *B, int origin, int *nquads)
{
    const int nt = T->tri.n / 3;
    for (int s = 0; s < 3 * nt; s++) epoint[s] = -1;
    for (int t = 0; t < nt; t++) /* split points, one per edge (shared by both slots) */
        for (int j = 0; j < 3; j++) {
            int s = 3 * t + j;
            if (!esplit[s] || epoint[s] >= 0) continue;
            int a = T->tri.p[s], b = T->tri.p[3 * t + (j + 1) % 3], id;
            double p[2] = {0.5 * (T->xy.p[2 * a] + T->xy.p[2 * b]), 0.5 * (T->xy.p[2 * a + 1] + T->xy.p[2 * b + 1])};
            int cv = eset_find(CE, a, b);
            if (cv && R->he[cv - 1].kind == 2) glpgp_region_split_point(R, &R->he[cv - 1], p);
            GLPGP_CHECK(glpgp_rbuild_vertex(B, p[0], p[1], &id));
            epoint[s] = id;
            int u = tnb[s];
            if (u >= 0)
                for (int k = 0; k < 3; k++)
                    if (T->tri.p[3 * u + k] == b && T->tri.p[3 * u + (k + 1) % 3] == a) epoint[3 * u + k] = id;
        }
    for (int t = 0; t < nt; t++) {
        int gv[3], sp[3], ks = 0;
        for (int j = 0; j < 3; j++) {
            gv[j] = gid[T->tri.p[3 * t + j]];
            sp[j] = esplit[3 * t + j] ? epoint[3 * t + j] : -1;
            ks += sp[j] >= 0;
        }
        const double *X = B->xy.p;
        if (ks == 3) {
            int g;
            GLPGP_CHECK(glpgp_rbuild_vertex(B, (X[2 * gv[0]] + X[2 * gv[1]] + X[2 * gv[2]]) / 3,
                                            (X[2 * gv[0] + 1] + X[2 * gv[1] + 1] + X[2 * gv[2] + 1]) / 3, &g));
            for (int j = 0; j < 3; j++) {
                int f4[4] = {gv[j], sp[j], g, sp[(j + 2) % 3]};
                GLPGP_CHECK(glpgp_rbuild_face(B, f4, 4, origin));
            }
            *nquads += 3;
        } else if (ks == 1) {
            int j = sp[0] >= 0 ? 0 : sp[1] >= 0 ? 1 : 2; /* split side j = (v_j, v_j+1) */
            int c = gv[j], a = gv[(j + 1) % 3], b = gv[(j + 2) % 3], mm = sp[j], pi[4];
            double A[2] = {X[2 * a], X[2 * a + 1]}, Bv[2] = {X[2 * b], X[2 * b + 1]}, Cv[2] = {X[2 * c], X[2 * c + 1]},
                   M[2] = {X[2 * mm], X[2 * mm + 1]}, P[8];
            ring_split(A, Bv, Cv, M, P);
            for (int i = 0; i < 4; i++) GLPGP_CHECK(glpgp_rbuild_vertex(B, P[2 * i], P[2 * i + 1], &pi[i]));
            int Q[5][4] = {{a, b, pi[1], pi[0]}, {b, c, pi[2], pi[1]}, {c, mm, pi[3], pi[2]}, {mm, a, pi[0], pi[3]},
                           {pi[0], pi[1], pi[2], pi[3]}};
            for (int k = 0; k < 5; k++) GLPGP_CHECK(glpgp_rbuild_face(B, Q[k], 4, origin));
            *nquads += 5;
        } else { /* a defect left: the polygon as it is (closed later) */
            int poly[6], n = 0;
            for (int j = 0; j < 3; j++) {
                poly[n++] = gv[j];
                if (sp[j] >= 0) poly[n++] = sp[j];
            }
            GLPGP_CHECK(glpgp_rbuild_face(B, poly, n, origin));
        }
    }
    return GLPGP_OK;
}

glpgp_status glpgp_trisplit_fill(const region *R, int O, int *gid, rbuild *B, int origin, int *nquads)
{
    const int nrv = R->q->nv + R->vxy.n / 2;
    tri_ctx T;
    memset(&T, 0, sizeof T);
    ivec ring = {0}, alle = {0};
    ivec *holes = NULL;
    eset CE = {0};
    int *loc = NULL, *tnb = NULL, *esplit = NULL, *epoint = NULL, *lgid = NULL, nh = 0;
    *nquads = 0;
    for (int L = 0; L < R->nloops; L++) nh += R->owner[L] == O;
    glpgp_status st = glpgp_calloc((size_t)nh + 1, sizeof(ivec), &holes);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nrv + 1, sizeof(int), &loc);
    if (st != GLPGP_OK) goto done;
    for (int v = 0; v <= nrv; v++) loc[v] = -1;
    GLPGP_CHECK_GOTO(st, local_loops(R, O, &T, loc, &ring, holes, &CE, &alle), done);
    GLPGP_CHECK_GOTO(st, bridge_holes(&T, &ring, holes, nh, &alle), done);
    GLPGP_CHECK_GOTO(st, ear_clip(&T, &ring), done);
    GLPGP_CHECK_GOTO(st, flips(&T, &CE), done);
    GLPGP_CHECK_GOTO(st, refine(&T, &CE, 2.6 * R->h, (int)(8.0 * fabs(R->area[O]) / (R->h * R->h)) + 64), done);
    int nt = T.tri.n / 3;
    GLPGP_CHECK_GOTO(st, build_adj(&T, &tnb), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt + 1, sizeof(int), &esplit), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt + 1, sizeof(int), &epoint), done);
    for (int t = 0; t < nt; t++)
        for (int j = 0; j < 3; j++) esplit[3 * t + j] = side_kind(R, &T, &CE, t, j) == 1 ? 0 : 1;
    GLPGP_CHECK_GOTO(st, parity_paths(R, &T, &CE, tnb, esplit), done);
    /* output ids of the local points: the region's own (gid), or new */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)T.xy.n / 2 + 1, sizeof(int), &lgid), done);
    for (int i = 0; i < T.xy.n / 2; i++) {
        int g = T.glob.p[i];
        if (g >= 0 && gid[g] < 0) {
            GLPGP_CHECK_GOTO(st, glpgp_rbuild_vertex(B, T.xy.p[2 * i], T.xy.p[2 * i + 1], &gid[g]), done);
        }
        if (g >= 0) {
            lgid[i] = gid[g];
        } else {
            GLPGP_CHECK_GOTO(st, glpgp_rbuild_vertex(B, T.xy.p[2 * i], T.xy.p[2 * i + 1], &lgid[i]), done);
        }
    }
    st = emit_faces(R, &T, &CE, tnb, esplit, epoint, lgid, B, origin, nquads);
done:
    tri_free(&T);
    ivec_free(&ring);
    ivec_free(&alle);
    for (int k = 0; k < nh && holes; k++) ivec_free(&holes[k]);
    free(holes);
    free(CE.k);
    free(CE.val);
    free(loc);
    free(tnb);
    free(esplit);
    free(epoint);
    free(lgid);
    return st;
}
