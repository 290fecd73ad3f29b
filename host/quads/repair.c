/* quads/repair.c: local repair of an extracted quad mesh
 * (glpgp_quadmesh_repair, glpgp/quads.h): the regions where the
 * parametrization did not give a valid mesh are cut out and re-meshed
 * with quads, the rest of the mesh is kept as it is.
 *
 * Round r (at most 4):
 *  0. (first round) boundary vertices of the mesh within h/4 of the domain
 *     boundary but not on it (strip midpoints on boundary chords) are moved
 *     onto it, when no face around them gets a corner with SJ <= 0.05;
 *  1. every face is checked (check.c, tolerance h/4): not a quad, inverted,
 *     degenerate or flat (SJ < 1e-3), non-manifold, pinched, overlapping,
 *     outside the domain, far from it, or over a lost part of the domain
 *     boundary (a hole, a corner, a feature); when the mesh area is off by
 *     more than 1%, also the faces along boundary pieces farther than
 *     t from the mesh boundary, t the largest of h/10, h/20, ... h/80 that
 *     flags a face (smaller in later rounds): chords across fillets and
 *     rounded corners. None: done;
 *  2. B = the bad faces and every face sharing a vertex with them (r + 1
 *     rings; in the first round no ring around a face that is bad only for
 *     the boundary distance, e.g. a chord across a fillet); K = the others. The region R = domain \ K is built
 *     combinatorially: its boundary is
 *       - every edge of K that has no K face on its other side, reversed,
 *         except a "covered chord": both ends on the same domain loop,
 *         consecutive among the K vertices on that loop in loop order, and
 *         the domain boundary between them within h/4 of the edge (K
 *         covers that piece of boundary, as the extraction made it);
 *       - every piece of domain loop between consecutive K vertices on it
 *         that no covered chord spans (through the input boundary vertices,
 *         Douglas-Peucker with 0.02 h, pieces longer than 2 h split at an
 *         input vertex or their middle; domain corners kept), and whole
 *         loops with no K vertex;
 *     joined into loops (at a vertex with several ways on, the first one
 *     clockwise from the way back, so touching parts of R stay separate
 *     loops); loops with positive area are outer loops, the others holes,
 *     put into the smallest outer loop that contains them;
 *  3. each polygon with holes is triangulated: holes bridged to the outer
 *     loop (shortest bridge that crosses nothing), ear clipping, edge flips
 *     to the constrained Delaunay triangulation, inner edges longer than
 *     2.6 h bisected (longest edge first, then flips again);
 *  4. triangles become quads without splitting the edges shared with K:
 *     every other edge starts "split" (a new vertex: its midpoint, or for a
 *     piece of domain boundary the input vertex nearest its middle), so a
 *     triangle with no edge on K has 3 split edges and becomes 3 quads
 *     around its centroid (a, m_ab, g, m_ca); a triangle with an edge on K
 *     has an even count, which no quad split allows (a quad mesh of a
 *     polygon has an even number of boundary vertices): these defects are
 *     paired by shortest paths in the dual graph, each crossed edge toggled
 *     (split <-> not), or sent to a domain boundary edge (toggled too; a
 *     vertex on the domain boundary belongs to one face only). Then every
 *     triangle has 1 or 3 split edges; one split edge (m on side c a): five
 *     quads, a ring (a b pb pa), (b c pc pb), (c m pm pc), (m a pa pm)
 *     around the inner quad (pa pb pc pm), p = g + s (corner - g) (s = 0.5,
 *     0.75 for m, or the best of a few other pairs) -- all convex for a
 *     valid triangle. A defect left (no partner, no boundary: an odd hole
 *     in K) stays a pentagon for glpgp_quadmesh_close_polygons;
 *  5. K + the new quads; odd faces closed (close.c), the new vertices
 *     smoothed (glpgp_quadmesh_smooth), and the next round checks again.
 * A mesh that is still invalid after the last round is returned as it is:
 * the quality report says so (the CLI then exits with code 3). */
#include "check.h"
#include "geom.h"
#include "glpgp/quads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define REPAIR_ROUNDS 4

/* ---- growable arrays -------------------------------------------------------- */

typedef struct dvec {
    double *p;
    int n, cap; /* in doubles */
} dvec;
typedef struct ivec {
    int *p;
    int n, cap;
} ivec;

static glpgp_status dpush(dvec *v, double x)
{
    if (v->n == v->cap) {
        int c = v->cap ? 2 * v->cap : 256;
        double *q = realloc(v->p, (size_t)c * sizeof(double));
        if (!q) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
        v->p = q;
        v->cap = c;
    }
    v->p[v->n++] = x;
    return GLPGP_OK;
}
static glpgp_status ipush(ivec *v, int x)
{
    if (v->n == v->cap) {
        int c = v->cap ? 2 * v->cap : 256;
        int *q = realloc(v->p, (size_t)c * sizeof(int));
        if (!q) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
        v->p = q;
        v->cap = c;
    }
    v->p[v->n++] = x;
    return GLPGP_OK;
}

static double orient2(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/* ---- the domain boundary as loops with a parameter ---------------------------- */

typedef struct dbnd {
    const glpgp_mesh *m;
    bgrid G;      /* boundary segments */
    int nb;       /* segments = loop vertices */
    int *loop_of; /* segment -> loop */
} dbnd;

static glpgp_status dbnd_build(dbnd *D, const glpgp_mesh *m, double h)
{
    memset(D, 0, sizeof *D);
    D->m = m;
    D->nb = m->loop_start[m->nloops];
    double *box = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)D->nb + 1, sizeof(int), &D->loop_of));
    GLPGP_CHECK(glpgp_malloc((size_t)4 * D->nb + 4, sizeof(double), &box));
    for (int l = 0; l < m->nloops; l++) {
        int s = m->loop_start[l], n = m->loop_start[l + 1] - s;
        for (int i = 0; i < n; i++) {
            const double *a = m->xy + 2 * m->loop_vertices[s + i], *b = m->xy + 2 * m->loop_vertices[s + (i + 1) % n];
            box[4 * (s + i)] = fmin(a[0], b[0]);
            box[4 * (s + i) + 1] = fmin(a[1], b[1]);
            box[4 * (s + i) + 2] = fmax(a[0], b[0]);
            box[4 * (s + i) + 3] = fmax(a[1], b[1]);
            D->loop_of[s + i] = l;
        }
    }
    glpgp_status st = glpgp_bgrid_build(&D->G, box, D->nb, h);
    free(box);
    return st;
}

static void dbnd_free(dbnd *D)
{
    glpgp_bgrid_free(&D->G);
    free(D->loop_of);
    memset(D, 0, sizeof *D);
}

static const double *seg_a(const dbnd *D, int s) { return D->m->xy + 2 * D->m->loop_vertices[s]; }
static const double *seg_b(const dbnd *D, int s)
{
    const glpgp_mesh *m = D->m;
    int l = D->loop_of[s], n = m->loop_start[l + 1] - m->loop_start[l];
    return m->xy + 2 * m->loop_vertices[m->loop_start[l] + (s - m->loop_start[l] + 1) % n];
}

/* Nearest boundary point within r of p: its segment (-1: none) and
 * parameter, distance, and projection. */
static int dbnd_nearest(dbnd *D, const double *p, double r, double *t, double *dist, double *proj, int **cand,
                        int *ncap)
{
    int n = glpgp_bgrid_query(&D->G, p[0] - r, p[1] - r, p[0] + r, p[1] + r, cand, ncap);
    int best = -1;
    double bd = INFINITY, bt = 0;
    for (int i = 0; i < n; i++) {
        double tt, d = glpgp_seg_dist(seg_a(D, (*cand)[i]), seg_b(D, (*cand)[i]), p, &tt);
        if (d < bd) {
            bd = d;
            best = (*cand)[i];
            bt = tt;
        }
    }
    if (best < 0 || bd > r) return -1;
    *t = bt;
    *dist = bd;
    const double *a = seg_a(D, best), *b = seg_b(D, best);
    proj[0] = a[0] + bt * (b[0] - a[0]);
    proj[1] = a[1] + bt * (b[1] - a[1]);
    return best;
}

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
        double d1 = orient2(p, q, A), d2 = orient2(p, q, Bp), d3 = orient2(A, Bp, p), d4 = orient2(A, Bp, q);
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
                double o1 = orient2(pv, pn, pm), o2 = orient2(pp, pv, pm), conv = orient2(pp, pv, pn);
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
        double ar = orient2(pa, pb, pc);
        int ear = ar > 0;
        if (ear) {
            /* no other vertex inside or on the triangle (duplicates of the corners excepted) */
            for (int j = nxt[c]; j != a && ear; j = nxt[j]) {
                int v = ring->p[j];
                if (v == ring->p[a] || v == ring->p[cur] || v == ring->p[c]) continue;
                const double *p = xy + 2 * v;
                if (orient2(pa, pb, p) >= 0 && orient2(pb, pc, p) >= 0 && orient2(pc, pa, p) >= 0) ear = 0;
            }
        }
        if (!ear && stall > 2 * left) {
            /* no ear left (rounding): clip the most convex corner */
            double best = -INFINITY;
            int bi = cur, j = cur;
            for (int k = 0; k < left; k++, j = nxt[j]) {
                double o = orient2(xy + 2 * ring->p[prv[j]], xy + 2 * ring->p[j], xy + 2 * ring->p[nxt[j]]);
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

static unsigned long long ekey(int a, int b)
{
    unsigned lo = (unsigned)(a < b ? a : b), hi = (unsigned)(a < b ? b : a);
    return ((unsigned long long)lo << 32) | hi;
}

typedef struct ekv {
    unsigned long long k;
    int slot;
} ekv;
static int cmp_ekv(const void *x, const void *y)
{
    const ekv *a = x, *b = y;
    return a->k < b->k ? -1 : a->k > b->k ? 1 : a->slot - b->slot;
}

/* Constrained edge lookup (sorted keys). */
typedef struct eset {
    unsigned long long *k;
    int *val;
    int n;
} eset;
static int eset_find(const eset *E, int a, int b)
{
    unsigned long long key = ekey(a, b);
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
    ekv *E = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)3 * nt + 1, sizeof *E, &E));
    glpgp_status st = glpgp_malloc((size_t)3 * nt + 1, sizeof(int), nb);
    if (st != GLPGP_OK) {
        free(E);
        return st;
    }
    for (int t = 0; t < nt; t++)
        for (int j = 0; j < 3; j++) {
            E[3 * t + j].k = ekey(T->tri.p[3 * t + j], T->tri.p[3 * t + (j + 1) % 3]);
            E[3 * t + j].slot = 3 * t + j;
            (*nb)[3 * t + j] = -1;
        }
    qsort(E, (size_t)3 * nt, sizeof *E, cmp_ekv);
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
                if (orient2(xy + 2 * c, xy + 2 * a, xy + 2 * d) <= 0 || orient2(xy + 2 * d, xy + 2 * b, xy + 2 * c) <= 0)
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
                double hc = fabs(orient2(pa, pb, T->xy.p + 2 * c)) / L, hd = fabs(orient2(pa, pb, T->xy.p + 2 * d)) / L;
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

/* ---- one repair round ------------------------------------------------------------ */

typedef struct rbuild {
    dvec xy;         /* output vertices */
    ivec fs, fv;     /* output faces: start offsets (fs has nf + 1 entries) and corners */
    ivec newv;       /* output vertex ids added by the repair */
} rbuild;

static glpgp_status out_face(rbuild *R, const int *v, int n)
{
    for (int i = 0; i < n; i++) GLPGP_CHECK(ipush(&R->fv, v[i]));
    return ipush(&R->fs, R->fv.n);
}
static glpgp_status out_vertex(rbuild *R, double x, double y, int *id)
{
    *id = R->xy.n / 2;
    GLPGP_CHECK(dpush(&R->xy, x));
    GLPGP_CHECK(dpush(&R->xy, y));
    return ipush(&R->newv, *id);
}

/* Boundary position of a mesh vertex: segment s (-1: not on the boundary), t. */
typedef struct bpos {
    int seg;
    double t;
} bpos;

/* Loop parameter of a boundary position: local segment index + t. */
static double bparam(const glpgp_mesh *m, const dbnd *D, bpos b)
{
    return (double)(b.seg - m->loop_start[D->loop_of[b.seg]]) + b.t;
}

/* Region half-edge: a -> b; kind 1 interface, 2 domain boundary (then
 * p0, p1: loop parameters of the ends, for the split point). */
typedef struct rhe {
    int a, b, kind, used;
    double p0, p1;
    int loop;
} rhe;

typedef struct round_ctx {
    const glpgp_quadmesh *q;
    const glpgp_mesh *m;
    dbnd *D;
    double h;
    /* region vertices: mesh vertex ids 0..nv-1, then new ones (input
     * boundary points) appended in vxy */
    dvec vxy;
    ivec vkind; /* per extra vertex: 2 */
    ivec vloopvert; /* per extra vertex: the input vertex (mesh id) or -1 */
    rhe *he;
    int nhe, cap;
} round_ctx;

static glpgp_status add_he(round_ctx *C, int a, int b, int kind, int loop, double p0, double p1)
{
    if (C->nhe == C->cap) {
        int c = C->cap ? 2 * C->cap : 256;
        rhe *n = realloc(C->he, (size_t)c * sizeof *n);
        if (!n) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
        C->he = n;
        C->cap = c;
    }
    C->he[C->nhe++] = (rhe){a, b, kind, 0, p0, p1, loop};
    return GLPGP_OK;
}

static const double *rv_xy(const round_ctx *C, int v)
{
    return v < C->q->nv ? C->q->xy + 2 * v : C->vxy.p + 2 * (v - C->q->nv);
}

/* Point of loop l at parameter p (segment floor(p), fraction). */
static void loop_point(const glpgp_mesh *m, int l, double p, double *out)
{
    int s = m->loop_start[l], n = m->loop_start[l + 1] - s;
    p = fmod(p, (double)n);
    if (p < 0) p += n;
    int i = (int)floor(p);
    if (i >= n) i = n - 1;
    double t = p - i;
    const double *a = m->xy + 2 * m->loop_vertices[s + i], *b = m->xy + 2 * m->loop_vertices[s + (i + 1) % n];
    out[0] = a[0] + t * (b[0] - a[0]);
    out[1] = a[1] + t * (b[1] - a[1]);
}

/* Forward distance in parameter from p0 to p1 on a loop of n segments. */
static double fwd(double p0, double p1, int n)
{
    double d = p1 - p0;
    while (d < 0) d += n;
    while (d >= n) d -= n;
    return d;
}

/* Emit the domain boundary piece from vertex u (param pu) to w (param pw)
 * on loop l: the input vertices between (simplified), as region
 * half-edges. whole: the full loop from pu back to pu. */
static glpgp_status emit_arc(round_ctx *C, int l, int u, double pu, int w, double pw, int whole)
{
    const glpgp_mesh *m = C->m;
    const double h = C->h;
    int s = m->loop_start[l], n = m->loop_start[l + 1] - s;
    double len = whole ? n : fwd(pu, pw, n);
    if (whole && len == 0) len = n;
    /* candidate points: u, the input vertices strictly inside, w */
    ivec ids = {0};
    dvec par = {0};
    GLPGP_CHECK(ipush(&ids, u));
    GLPGP_CHECK(dpush(&par, 0.0));
    double first = ceil(pu);
    if (first == pu) first += 1.0;
    for (double p = first; p - pu < len - 1e-12; p += 1.0) {
        int iv = s + ((int)fmod(p, (double)n) + n) % n;
        const double *x = m->xy + 2 * m->loop_vertices[iv];
        if (hypot(x[0] - rv_xy(C, u)[0], x[1] - rv_xy(C, u)[1]) < 1e-9 * h) continue;
        if (hypot(x[0] - rv_xy(C, w)[0], x[1] - rv_xy(C, w)[1]) < 1e-9 * h) continue;
        GLPGP_CHECK(ipush(&ids, -1 - m->loop_vertices[iv]));
        GLPGP_CHECK(dpush(&par, p - pu));
    }
    GLPGP_CHECK(ipush(&ids, w));
    GLPGP_CHECK(dpush(&par, len));
    int np = ids.n;
    /* keep: ends, corners, Douglas-Peucker 0.02 h */
    unsigned char *keep = calloc((size_t)np, 1);
    int *stack = malloc(sizeof(int) * 2 * (size_t)(np + 1));
    if (!keep || !stack) {
        free(keep);
        free(stack);
        free(ids.p);
        free(par.p);
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
    }
#define PXY(i) (ids.p[i] >= 0 ? rv_xy(C, ids.p[i]) : m->xy + 2 * (-1 - ids.p[i]))
    keep[0] = keep[np - 1] = 1;
    for (int i = 1; i + 1 < np; i++) {
        int vi = -1 - ids.p[i];
        const double *a = m->normal_prev + 2 * vi, *b = m->normal_next + 2 * vi;
        if (a[0] * b[0] + a[1] * b[1] < cos(GLPGP_CORNER_DEG * 3.14159265358979323846 / 180.0)) keep[i] = 1;
    }
    if (whole && np > 3) keep[np / 2] = keep[np / 4] = keep[3 * np / 4] = 1; /* a closed loop needs a triangle */
    int sp = 0;
    int prev = 0;
    for (int i = 1; i < np; i++) {
        if (!keep[i]) continue;
        stack[sp++] = prev;
        stack[sp++] = i;
        prev = i;
    }
    while (sp > 0) {
        int j = stack[--sp], i = stack[--sp];
        if (j - i < 2) continue;
        double dmax = 0;
        int im = -1;
        for (int k = i + 1; k < j; k++) {
            double d = glpgp_seg_dist(PXY(i), PXY(j), PXY(k), NULL);
            if (d > dmax) {
                dmax = d;
                im = k;
            }
        }
        /* also split pieces longer than 2 h at their middle input vertex */
        const double *pi = PXY(i), *pj = PXY(j);
        if (dmax <= 0.02 * h && hypot(pj[0] - pi[0], pj[1] - pi[1]) > 2.0 * h) {
            double mid = 0.5 * (par.p[i] + par.p[j]), bd = INFINITY;
            for (int k = i + 1; k < j; k++)
                if (fabs(par.p[k] - mid) < bd) {
                    bd = fabs(par.p[k] - mid);
                    im = k;
                }
            dmax = INFINITY;
        }
        if (dmax > 0.02 * h && im > 0) {
            keep[im] = 1;
            stack[sp++] = i;
            stack[sp++] = im;
            stack[sp++] = im;
            stack[sp++] = j;
        }
    }
    /* half-edges between kept points; straight pieces longer than 2 h get
     * their middle as a new point */
    int last = 0;
    int last_id = u;
    for (int i = 1; i < np; i++) {
        if (!keep[i]) continue;
        int id;
        if (i == np - 1) {
            id = w;
        } else {
            id = C->q->nv + C->vxy.n / 2;
            GLPGP_CHECK(dpush(&C->vxy, PXY(i)[0]));
            GLPGP_CHECK(dpush(&C->vxy, PXY(i)[1]));
        }
        const double *pa = PXY(last), *pb = PXY(i);
        double L = hypot(pb[0] - pa[0], pb[1] - pa[1]);
        int pieces = i == last + 1 ? (int)floor(L / (2.0 * h)) + 1 : 1;
        if (pieces > 1 && i != np - 1) {
            /* new point id must come after the intermediate ones: re-add */
            C->vxy.n -= 2;
        }
        int prev_id = last_id;
        for (int k = 1; k < pieces; k++) {
            double t = (double)k / pieces;
            int mid_id = C->q->nv + C->vxy.n / 2;
            GLPGP_CHECK(dpush(&C->vxy, pa[0] + t * (pb[0] - pa[0])));
            GLPGP_CHECK(dpush(&C->vxy, pa[1] + t * (pb[1] - pa[1])));
            double p0 = pu + par.p[last] + (k - 1.0) / pieces * (par.p[i] - par.p[last]);
            double p1 = pu + par.p[last] + (double)k / pieces * (par.p[i] - par.p[last]);
            GLPGP_CHECK(add_he(C, prev_id, mid_id, 2, l, p0, p1));
            prev_id = mid_id;
        }
        if (pieces > 1 && i != np - 1) {
            id = C->q->nv + C->vxy.n / 2;
            GLPGP_CHECK(dpush(&C->vxy, PXY(i)[0]));
            GLPGP_CHECK(dpush(&C->vxy, PXY(i)[1]));
        }
        double p0 = pu + par.p[last] + (pieces - 1.0) / pieces * (par.p[i] - par.p[last]);
        GLPGP_CHECK(add_he(C, prev_id, id, 2, l, p0, pu + par.p[i]));
        last = i;
        last_id = id;
    }
#undef PXY
    free(keep);
    free(stack);
    free(ids.p);
    free(par.p);
    return GLPGP_OK;
}

/* The split point of region boundary half-edge e on the domain boundary:
 * the input vertex nearest the middle of its parameter range, or the
 * middle. */
static void split_point(const round_ctx *C, const rhe *e, double *out)
{
    const glpgp_mesh *m = C->m;
    int n = m->loop_start[e->loop + 1] - m->loop_start[e->loop];
    double len = fwd(e->p0, e->p1, n), mid = e->p0 + 0.5 * len;
    double best = INFINITY, bp = mid;
    double first = ceil(e->p0);
    if (first == e->p0) first += 1.0;
    for (double p = first; p < e->p0 + len - 1e-12; p += 1.0)
        if (fabs(p - mid) < best) {
            best = fabs(p - mid);
            bp = p;
        }
    if (best > 0.5 * len) bp = mid;
    loop_point(m, e->loop, bp, out);
}

static int cmp_dbl_int(const void *x, const void *y)
{
    const double *a = x, *b = y;
    return (a[0] > b[0]) - (a[0] < b[0]);
}

/* One repair round on q (faces in bad[] removed with their rings). *out:
 * the new mesh, *newmark: per output vertex 1 if made here. */
static glpgp_status repair_round(const glpgp_quadmesh *q, const glpgp_mesh *m, dbnd *D, double h,
                                 unsigned char *inB, glpgp_quad_repair *rs, glpgp_quadmesh **out,
                                 unsigned char **newmark)
{
    glpgp_status st = GLPGP_OK;
    const int nv = q->nv, nf = q->nf;
    round_ctx C;
    memset(&C, 0, sizeof C);
    C.q = q;
    C.m = m;
    C.D = D;
    C.h = h;
    bpos *bp = NULL;
    int *cand = NULL, ncap = 0;
    unsigned char *usedK = NULL;
    ekv *hk = NULL;
    int *cover = NULL;
    double *lv = NULL;
    rbuild R;
    memset(&R, 0, sizeof R);
    tri_ctx T;
    memset(&T, 0, sizeof T);
    int *loops_start = NULL;
    ivec loopv = {0}, ring = {0}, alle = {0};
    ivec *holes = NULL;
    eset CE = {0};
    int *tnb = NULL, *esplit = NULL, *epoint = NULL;

    /* vertex boundary positions */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv + 1, sizeof *bp, &bp), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv + 1, 1, &usedK), done);
    for (int f = 0; f < nf; f++)
        if (!inB[f])
            for (int s = q->face_start[f]; s < q->face_start[f + 1]; s++) usedK[q->face_vert[s]] = 1;
    for (int v = 0; v < nv; v++) {
        bp[v].seg = -1;
        if (!usedK[v]) continue;
        double t, d, pr[2];
        int s = dbnd_nearest(D, q->xy + 2 * v, 1e-8 * h, &t, &d, pr, &cand, &ncap);
        if (s >= 0) {
            bp[v].seg = s;
            bp[v].t = t;
        }
    }
    /* K half-edges, sorted by (a, b) key for the twin test */
    int nK = 0;
    for (int f = 0; f < nf; f++)
        if (!inB[f]) nK += q->face_start[f + 1] - q->face_start[f];
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nK + 1, sizeof *hk, &hk), done);
    nK = 0;
    for (int f = 0; f < nf; f++) {
        if (inB[f]) continue;
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        for (int i = 0; i < k; i++) {
            int a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % k];
            hk[nK].k = ((unsigned long long)(unsigned)a << 32) | (unsigned)b;
            hk[nK++].slot = s + i;
        }
    }
    qsort(hk, (size_t)nK, sizeof *hk, cmp_ekv);
    /* per loop: K boundary vertices sorted by parameter */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv + 1, sizeof(int), &cover), done);
    for (int v = 0; v < nv; v++) cover[v] = -1;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv + 2, sizeof(double), &lv), done);
    /* free K edges u -> w */
    for (int i = 0; i < nK; i++) {
        int a = (int)(hk[i].k >> 32), b = (int)(hk[i].k & 0xffffffffu);
        unsigned long long tw = ((unsigned long long)(unsigned)b << 32) | (unsigned)a;
        int lo = 0, hi = nK - 1, found = 0;
        while (lo <= hi) {
            int mid = (lo + hi) / 2;
            if (hk[mid].k == tw) {
                found = 1;
                break;
            }
            if (hk[mid].k < tw)
                lo = mid + 1;
            else
                hi = mid - 1;
        }
        if (found) continue;
        /* a covered chord? */
        int covered = 0;
        if (bp[a].seg >= 0 && bp[b].seg >= 0 && D->loop_of[bp[a].seg] == D->loop_of[bp[b].seg]) {
            int l = D->loop_of[bp[a].seg], n = m->loop_start[l + 1] - m->loop_start[l];
            double pa = bparam(m, D, bp[a]), pb = bparam(m, D, bp[b]), len = fwd(pa, pb, n);
            covered = len > 0 && len < 0.5 * n + 0.5;
            /* consecutive: no other K boundary vertex strictly between */
            for (int v = 0; v < nv && covered; v++) {
                if (v == a || v == b || bp[v].seg < 0 || D->loop_of[bp[v].seg] != l) continue;
                double dv = fwd(pa, bparam(m, D, bp[v]), n);
                if (dv > 1e-12 && dv < len - 1e-12) covered = 0;
            }
            /* the boundary between within h/4 of the chord */
            if (covered) {
                const double *A = q->xy + 2 * a, *Bq = q->xy + 2 * b;
                double first = ceil(pa);
                if (first == pa) first += 1.0;
                for (double p = first; p < pa + len - 1e-12 && covered; p += 1.0) {
                    double x[2];
                    loop_point(m, l, p, x);
                    if (glpgp_seg_dist(A, Bq, x, NULL) > 0.25 * h) covered = 0;
                }
            }
        }
        if (covered)
            cover[a] = b;
        else
            GLPGP_CHECK_GOTO(st, add_he(&C, b, a, 1, -1, 0, 0), done);
    }
    /* uncovered pieces of the domain loops */
    for (int l = 0; l < m->nloops; l++) {
        int n = m->loop_start[l + 1] - m->loop_start[l], cnt = 0;
        for (int v = 0; v < nv; v++)
            if (bp[v].seg >= 0 && D->loop_of[bp[v].seg] == l) {
                lv[2 * cnt] = bparam(m, D, bp[v]);
                lv[2 * cnt + 1] = v;
                cnt++;
            }
        if (cnt == 0) {
            /* the whole loop, from its first input vertex */
            int v0 = nv + C.vxy.n / 2;
            const double *x = m->xy + 2 * m->loop_vertices[m->loop_start[l]];
            GLPGP_CHECK_GOTO(st, dpush(&C.vxy, x[0]), done);
            GLPGP_CHECK_GOTO(st, dpush(&C.vxy, x[1]), done);
            GLPGP_CHECK_GOTO(st, emit_arc(&C, l, v0, 0.0, v0, (double)n, 1), done);
            continue;
        }
        qsort(lv, (size_t)cnt, 2 * sizeof(double), cmp_dbl_int);
        for (int i = 0; i < cnt; i++) {
            int u = (int)lv[2 * i + 1], w = (int)lv[2 * ((i + 1) % cnt) + 1];
            if (cover[u] == w) continue;
            if (cnt == 1)
                GLPGP_CHECK_GOTO(st, emit_arc(&C, l, u, lv[0], u, lv[0], 1), done);
            else
                GLPGP_CHECK_GOTO(st, emit_arc(&C, l, u, lv[2 * i], w, lv[2 * ((i + 1) % cnt)], 0), done);
        }
    }
    /* region loops */
    {
        const int nrv = nv + C.vxy.n / 2;
        int *ostart = NULL, *oitem = NULL, *ocnt = NULL;
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nrv + 2, sizeof(int), &ostart), done);
        st = glpgp_malloc((size_t)C.nhe + 1, sizeof(int), &oitem);
        if (st == GLPGP_OK) st = glpgp_calloc((size_t)nrv + 1, sizeof(int), &ocnt);
        if (st != GLPGP_OK) {
            free(ostart);
            free(oitem);
            free(ocnt);
            goto done;
        }
        for (int e = 0; e < C.nhe; e++) ostart[C.he[e].a + 1]++;
        for (int v = 0; v < nrv; v++) ostart[v + 1] += ostart[v];
        for (int e = 0; e < C.nhe; e++) oitem[ostart[C.he[e].a] + ocnt[C.he[e].a]++] = e;
        ivec lstart = {0};
        ipush(&lstart, 0);
        for (int e0 = 0; e0 < C.nhe && st == GLPGP_OK; e0++) {
            if (C.he[e0].used) continue;
            int e = e0, guard = 0, ok = 1;
            do {
                C.he[e].used = 1;
                st = ipush(&loopv, e);
                int v = C.he[e].b;
                const double *pv = rv_xy(&C, v), *pp = rv_xy(&C, C.he[e].a);
                double back = atan2(pp[1] - pv[1], pp[0] - pv[0]);
                int best = -1;
                double bangle = INFINITY;
                for (int j = ostart[v]; j < ostart[v + 1]; j++) {
                    int f = oitem[j];
                    if (C.he[f].used && f != e0) continue;
                    const double *pn = rv_xy(&C, C.he[f].b);
                    double ang = atan2(pn[1] - pv[1], pn[0] - pv[0]);
                    double cw = back - ang; /* clockwise turn from the way back */
                    while (cw <= 1e-12) cw += 2 * 3.14159265358979323846;
                    while (cw > 2 * 3.14159265358979323846) cw -= 2 * 3.14159265358979323846;
                    if (cw < bangle) {
                        bangle = cw;
                        best = f;
                    }
                }
                if (best < 0) {
                    ok = 0;
                    break;
                }
                e = best;
            } while (e != e0 && ++guard < 4 * C.nhe + 4 && st == GLPGP_OK);
            if (!ok || e != e0) {
                st = st != GLPGP_OK ? st : GLPGP_FAIL(GLPGP_ERR_NUMERIC, "quad repair: region boundary does not close");
                break;
            }
            ipush(&lstart, loopv.n);
        }
        free(ostart);
        free(oitem);
        free(ocnt);
        if (st != GLPGP_OK) {
            free(lstart.p);
            goto done;
        }
        loops_start = lstart.p;
        int nloops = lstart.n - 1;
        /* classify: area sign; holes into the smallest outer loop containing them */
        double *area = calloc((size_t)nloops + 1, sizeof(double));
        int *owner = malloc(sizeof(int) * ((size_t)nloops + 1));
        if (!area || !owner) {
            free(area);
            free(owner);
            st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
            goto done;
        }
        for (int L = 0; L < nloops; L++) {
            for (int i = loops_start[L]; i < loops_start[L + 1]; i++) {
                const double *a = rv_xy(&C, C.he[loopv.p[i]].a), *b = rv_xy(&C, C.he[loopv.p[i]].b);
                area[L] += 0.5 * (a[0] * b[1] - b[0] * a[1]);
            }
            owner[L] = -1;
        }
        /* map region vertex ids -> local triangulation ids */
        int *loc = malloc(sizeof(int) * ((size_t)nrv + 1));
        if (!loc) {
            free(area);
            free(owner);
            st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
            goto done;
        }
        for (int L = 0; L < nloops; L++) {
            if (area[L] >= 0) continue;
            /* a point of hole L: the middle of its first edge */
            const double *a = rv_xy(&C, C.he[loopv.p[loops_start[L]]].a), *b = rv_xy(&C, C.he[loopv.p[loops_start[L]]].b);
            double p[2] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])};
            double best = INFINITY;
            for (int O = 0; O < nloops; O++) {
                if (area[O] <= 0 || area[O] >= best) continue;
                int wn = 0;
                for (int i = loops_start[O]; i < loops_start[O + 1]; i++) {
                    const double *x = rv_xy(&C, C.he[loopv.p[i]].a), *y = rv_xy(&C, C.he[loopv.p[i]].b);
                    if (x[1] <= p[1]) {
                        if (y[1] > p[1] && orient2(x, y, p) > 0) wn++;
                    } else if (y[1] <= p[1] && orient2(x, y, p) < 0) {
                        wn--;
                    }
                }
                if (wn) {
                    best = area[O];
                    owner[L] = O;
                }
            }
        }
        /* output: K faces first */
        GLPGP_CHECK_GOTO(st, ipush(&R.fs, 0), rfree);
        for (int v = 0; v < nv; v++) {
            GLPGP_CHECK_GOTO(st, dpush(&R.xy, q->xy[2 * v]), rfree);
            GLPGP_CHECK_GOTO(st, dpush(&R.xy, q->xy[2 * v + 1]), rfree);
        }
        for (int f = 0; f < nf; f++)
            if (!inB[f]) GLPGP_CHECK_GOTO(st, out_face(&R, q->face_vert + q->face_start[f], q->face_start[f + 1] - q->face_start[f]), rfree);
        for (int v = 0; v < (int)C.vxy.n / 2; v++) {
            int id;
            GLPGP_CHECK_GOTO(st, out_vertex(&R, C.vxy.p[2 * v], C.vxy.p[2 * v + 1], &id), rfree);
        }
        /* each outer loop with its holes */
        for (int O = 0; O < nloops; O++) {
            if (area[O] <= 0) continue;
            memset(&T, 0, sizeof T);
            for (int v = 0; v <= nrv; v++) loc[v] = -1;
            ring.n = alle.n = 0;
            int nh = 0;
            for (int L = 0; L < nloops; L++) nh += owner[L] == O;
            holes = calloc((size_t)nh + 1, sizeof(ivec));
            if (!holes) {
                st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
                goto rfree;
            }
            /* local points; constrained edges */
            ivec ca = {0}, cb = {0}, ck = {0};
            int hi = 0;
            for (int L = 0; L < nloops && st == GLPGP_OK; L++) {
                if (L != O && owner[L] != O) continue;
                ivec *dst = L == O ? &ring : &holes[hi++];
                for (int i = loops_start[L]; i < loops_start[L + 1] && st == GLPGP_OK; i++) {
                    const rhe *e = &C.he[loopv.p[i]];
                    int v = e->a;
                    if (loc[v] < 0) {
                        loc[v] = T.xy.n / 2;
                        st = dpush(&T.xy, rv_xy(&C, v)[0]);
                        if (st == GLPGP_OK) st = dpush(&T.xy, rv_xy(&C, v)[1]);
                        if (st == GLPGP_OK) st = ipush(&T.kind, 1);
                        if (st == GLPGP_OK) st = ipush(&T.glob, v);
                    }
                    if (st == GLPGP_OK) st = ipush(dst, loc[v]);
                }
            }
            for (int L = 0; L < nloops && st == GLPGP_OK; L++) {
                if (L != O && owner[L] != O) continue;
                for (int i = loops_start[L]; i < loops_start[L + 1] && st == GLPGP_OK; i++) {
                    const rhe *e = &C.he[loopv.p[i]];
                    st = ipush(&ca, loc[e->a]);
                    if (st == GLPGP_OK) st = ipush(&cb, loc[e->b]);
                    if (st == GLPGP_OK) st = ipush(&ck, loopv.p[i]);
                    if (st == GLPGP_OK) st = ipush(&alle, loc[e->a]);
                    if (st == GLPGP_OK) st = ipush(&alle, loc[e->b]);
                }
            }
            if (st == GLPGP_OK) st = bridge_holes(&T, &ring, holes, nh, &alle);
            if (st == GLPGP_OK) st = ear_clip(&T, &ring);
            /* constrained edges set */
            if (st == GLPGP_OK) {
                free(CE.k);
                free(CE.val);
                CE.n = ca.n;
                CE.k = malloc(sizeof(unsigned long long) * ((size_t)ca.n + 1));
                CE.val = malloc(sizeof(int) * ((size_t)ca.n + 1));
                ekv *tmp = malloc(sizeof(ekv) * ((size_t)ca.n + 1));
                if (!CE.k || !CE.val || !tmp) {
                    free(tmp);
                    st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
                } else {
                    for (int i = 0; i < ca.n; i++) {
                        tmp[i].k = ekey(ca.p[i], cb.p[i]);
                        tmp[i].slot = ck.p[i];
                    }
                    qsort(tmp, (size_t)ca.n, sizeof *tmp, cmp_ekv);
                    for (int i = 0; i < ca.n; i++) {
                        CE.k[i] = tmp[i].k;
                        CE.val[i] = 1 + tmp[i].slot; /* region half-edge + 1 */
                    }
                    free(tmp);
                }
            }
            if (st == GLPGP_OK) st = flips(&T, &CE);
            if (st == GLPGP_OK) {
                double ar = fabs(area[O]);
                st = refine(&T, &CE, 2.6 * h, (int)(8.0 * ar / (h * h)) + 64);
            }
            free(ca.p);
            free(cb.p);
            free(ck.p);
            for (int k = 0; k < nh; k++) free(holes[k].p);
            free(holes);
            holes = NULL;
            if (st != GLPGP_OK) goto rfree;
            /* parity: per triangle edge, split (1) or not (0) */
            int nt = T.tri.n / 3;
            free(tnb);
            tnb = NULL;
            GLPGP_CHECK_GOTO(st, build_adj(&T, &tnb), rfree);
            free(esplit);
            free(epoint);
            esplit = malloc(sizeof(int) * (3 * (size_t)nt + 1));
            epoint = malloc(sizeof(int) * (3 * (size_t)nt + 1));
            if (!esplit || !epoint) {
                st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
                goto rfree;
            }
            for (int s = 0; s < 3 * nt; s++) {
                int a = T.tri.p[s], b = T.tri.p[s / 3 * 3 + (s % 3 + 1) % 3];
                int cv = eset_find(&CE, a, b);
                esplit[s] = (cv && C.he[cv - 1].kind == 1) ? 0 : 1;
                epoint[s] = -1;
            }
            /* toggle an edge (both slots) */
#define TOGGLE(t, j)                                                                   \
    do {                                                                               \
        int t_ = (t), j_ = (j);                                                        \
        esplit[3 * t_ + j_] ^= 1;                                                      \
        int u_ = tnb[3 * t_ + j_];                                                     \
        if (u_ >= 0) {                                                                 \
            int a_ = T.tri.p[3 * t_ + j_], b_ = T.tri.p[3 * t_ + (j_ + 1) % 3];         \
            for (int k_ = 0; k_ < 3; k_++)                                             \
                if (T.tri.p[3 * u_ + k_] == b_ && T.tri.p[3 * u_ + (k_ + 1) % 3] == a_) \
                    esplit[3 * u_ + k_] ^= 1;                                          \
        }                                                                              \
    } while (0)
            {
                int *pred = malloc(sizeof(int) * ((size_t)nt + 1)), *queue = malloc(sizeof(int) * ((size_t)nt + 1));
                int *predj = malloc(sizeof(int) * ((size_t)nt + 1));
                if (!pred || !queue || !predj) {
                    free(pred);
                    free(queue);
                    free(predj);
                    st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
                    goto rfree;
                }
                for (int t0 = 0; t0 < nt; t0++) {
                    int k0 = esplit[3 * t0] + esplit[3 * t0 + 1] + esplit[3 * t0 + 2];
                    if (k0 % 2) continue;
                    /* BFS over free edges to another defect or a domain boundary edge */
                    for (int t = 0; t < nt; t++) pred[t] = -2;
                    int qh = 0, qt = 0, target = -1, tb_j = -1;
                    pred[t0] = -1;
                    queue[qt++] = t0;
                    while (qh < qt && target < 0) {
                        int t = queue[qh++];
                        for (int j = 0; j < 3 && target < 0; j++) {
                            int a = T.tri.p[3 * t + j], b = T.tri.p[3 * t + (j + 1) % 3];
                            int cv = eset_find(&CE, a, b);
                            if (cv && C.he[cv - 1].kind == 1) continue; /* K: never split */
                            int u = tnb[3 * t + j];
                            if (u < 0) { /* domain boundary edge */
                                if (cv && C.he[cv - 1].kind == 2) {
                                    target = t;
                                    tb_j = j;
                                }
                                continue;
                            }
                            if (pred[u] != -2) continue;
                            pred[u] = t;
                            predj[u] = j;
                            int ku = esplit[3 * u] + esplit[3 * u + 1] + esplit[3 * u + 2];
                            if (ku % 2 == 0) {
                                target = u;
                                tb_j = -1;
                            } else {
                                queue[qt++] = u;
                            }
                        }
                    }
                    if (target < 0) continue;
                    if (tb_j >= 0) TOGGLE(target, tb_j);
                    for (int t = target; pred[t] >= 0; t = pred[t]) TOGGLE(pred[t], predj[t]);
                }
                free(pred);
                free(queue);
                free(predj);
            }
#undef TOGGLE
            /* global ids of the local points */
            for (int i = 0; i < T.xy.n / 2; i++) {
                if (T.glob.p[i] >= 0) {
                    int g = T.glob.p[i];
                    T.glob.p[i] = g < nv ? g : nv + (g - nv);
                } else {
                    int id;
                    GLPGP_CHECK_GOTO(st, out_vertex(&R, T.xy.p[2 * i], T.xy.p[2 * i + 1], &id), rfree);
                    T.glob.p[i] = id;
                }
            }
            /* split points, one per edge (shared by both slots) */
            for (int t = 0; t < nt; t++)
                for (int j = 0; j < 3; j++) {
                    int s = 3 * t + j;
                    if (!esplit[s] || epoint[s] >= 0) continue;
                    int a = T.tri.p[s], b = T.tri.p[3 * t + (j + 1) % 3];
                    double p[2] = {0.5 * (T.xy.p[2 * a] + T.xy.p[2 * b]), 0.5 * (T.xy.p[2 * a + 1] + T.xy.p[2 * b + 1])};
                    int cv = eset_find(&CE, a, b);
                    if (cv && C.he[cv - 1].kind == 2) split_point(&C, &C.he[cv - 1], p);
                    int id;
                    GLPGP_CHECK_GOTO(st, out_vertex(&R, p[0], p[1], &id), rfree);
                    epoint[s] = id;
                    int u = tnb[s];
                    if (u >= 0)
                        for (int k = 0; k < 3; k++)
                            if (T.tri.p[3 * u + k] == b && T.tri.p[3 * u + (k + 1) % 3] == a) epoint[3 * u + k] = id;
                }
            /* faces */
            for (int t = 0; t < nt; t++) {
                int gv[3], sp[3], ks = 0;
                for (int j = 0; j < 3; j++) {
                    gv[j] = T.glob.p[T.tri.p[3 * t + j]];
                    sp[j] = esplit[3 * t + j] ? epoint[3 * t + j] : -1;
                    ks += sp[j] >= 0;
                }
                const double *X = R.xy.p;
                if (ks == 3) {
                    double gx = (X[2 * gv[0]] + X[2 * gv[1]] + X[2 * gv[2]]) / 3;
                    double gy = (X[2 * gv[0] + 1] + X[2 * gv[1] + 1] + X[2 * gv[2] + 1]) / 3;
                    int g;
                    GLPGP_CHECK_GOTO(st, out_vertex(&R, gx, gy, &g), rfree);
                    for (int j = 0; j < 3; j++) {
                        int f4[4] = {gv[j], sp[j], g, sp[(j + 2) % 3]};
                        GLPGP_CHECK_GOTO(st, out_face(&R, f4, 4), rfree);
                        rs->new_quads++;
                    }
                } else if (ks == 1) {
                    int j = sp[0] >= 0 ? 0 : sp[1] >= 0 ? 1 : 2; /* split side j = (v_j, v_j+1) */
                    /* a b c with m on side c -> a: c = v_j, a = v_j+1, b = v_j+2 */
                    int c = gv[j], a = gv[(j + 1) % 3], b = gv[(j + 2) % 3], mm = sp[j];
                    double A[2] = {X[2 * a], X[2 * a + 1]}, Bv[2] = {X[2 * b], X[2 * b + 1]},
                           Cv[2] = {X[2 * c], X[2 * c + 1]}, M[2] = {X[2 * mm], X[2 * mm + 1]}, P[8];
                    ring_split(A, Bv, Cv, M, P);
                    int pi[4];
                    for (int i = 0; i < 4; i++) GLPGP_CHECK_GOTO(st, out_vertex(&R, P[2 * i], P[2 * i + 1], &pi[i]), rfree);
                    int Q[5][4] = {{a, b, pi[1], pi[0]}, {b, c, pi[2], pi[1]}, {c, mm, pi[3], pi[2]}, {mm, a, pi[0], pi[3]},
                                   {pi[0], pi[1], pi[2], pi[3]}};
                    for (int k = 0; k < 5; k++) GLPGP_CHECK_GOTO(st, out_face(&R, Q[k], 4), rfree);
                    rs->new_quads += 5;
                } else {
                    /* a defect left: the polygon as it is (closed later) */
                    int poly[6], n = 0;
                    for (int j = 0; j < 3; j++) {
                        poly[n++] = gv[j];
                        if (sp[j] >= 0) poly[n++] = sp[j];
                    }
                    GLPGP_CHECK_GOTO(st, out_face(&R, poly, n), rfree);
                }
            }
            rs->regions++;
            free(T.xy.p);
            free(T.kind.p);
            free(T.glob.p);
            free(T.tri.p);
            memset(&T, 0, sizeof T);
        }
    rfree:
        free(area);
        free(owner);
        free(loc);
        if (st != GLPGP_OK) goto done;
    }
    /* the new mesh: drop unused vertices */
    {
        int nvo = R.xy.n / 2, nfo = R.fs.n - 1;
        int *id = malloc(sizeof(int) * ((size_t)nvo + 1));
        unsigned char *isnew = calloc((size_t)nvo + 1, 1);
        glpgp_quadmesh *o = calloc(1, sizeof *o);
        if (!id || !isnew || !o) {
            free(id);
            free(isnew);
            free(o);
            st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
            goto done;
        }
        for (int i = 0; i < R.newv.n; i++) isnew[R.newv.p[i]] = 1;
        for (int v = 0; v < nvo; v++) id[v] = -1;
        o->xy = malloc(sizeof(double) * 2 * ((size_t)nvo + 1));
        o->face_start = malloc(sizeof(int) * ((size_t)nfo + 1));
        o->face_vert = malloc(sizeof(int) * ((size_t)R.fv.n + 1));
        *newmark = calloc((size_t)nvo + 1, 1);
        if (!o->xy || !o->face_start || !o->face_vert || !*newmark) {
            glpgp_quadmesh_destroy(&o);
            free(id);
            free(isnew);
            free(*newmark);
            *newmark = NULL;
            st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
            goto done;
        }
        o->face_start[0] = 0;
        for (int f = 0; f < nfo; f++) {
            for (int s = R.fs.p[f]; s < R.fs.p[f + 1]; s++) {
                int v = R.fv.p[s];
                if (id[v] < 0) {
                    id[v] = o->nv;
                    o->xy[2 * o->nv] = R.xy.p[2 * v];
                    o->xy[2 * o->nv + 1] = R.xy.p[2 * v + 1];
                    (*newmark)[o->nv] = isnew[v];
                    o->nv++;
                }
                o->face_vert[s] = id[v];
            }
            o->face_start[f + 1] = R.fs.p[f + 1];
        }
        o->nf = nfo;
        /* diagnostics carried over */
        memcpy(o->singular_tris, q->singular_tris, sizeof o->singular_tris);
        memcpy(o->inconsistent_tris, q->inconsistent_tris, sizeof o->inconsistent_tris);
        o->collapsed_edges = q->collapsed_edges;
        o->promoted_corners = q->promoted_corners;
        o->split_pentagons = q->split_pentagons;
        o->center_splits = q->center_splits;
        o->closing = q->closing;
        free(id);
        free(isnew);
        *out = o;
    }
done:
    free(bp);
    free(cand);
    free(usedK);
    free(hk);
    free(cover);
    free(lv);
    free(C.vxy.p);
    free(C.vkind.p);
    free(C.vloopvert.p);
    free(C.he);
    free(R.xy.p);
    free(R.fs.p);
    free(R.fv.p);
    free(R.newv.p);
    free(T.xy.p);
    free(T.kind.p);
    free(T.glob.p);
    free(T.tri.p);
    free(loops_start);
    free(loopv.p);
    free(ring.p);
    free(alle.p);
    free(CE.k);
    free(CE.val);
    free(tnb);
    free(esplit);
    free(epoint);
    return st;
}

/* Move mesh boundary vertices within h/4 of the domain boundary onto it. */
static glpgp_status snap_boundary(glpgp_quadmesh *q, dbnd *D, double h, int *snapped)
{
    int *cnt = NULL, *cand = NULL, ncap = 0;
    glpgp_status st = glpgp_calloc((size_t)q->nv + 1, sizeof(int), &cnt);
    /* boundary vertices: an edge used once */
    ekv *E = NULL;
    int nc = q->face_start[q->nf];
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nc + 1, sizeof *E, &E);
    unsigned char *bnd = NULL;
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)q->nv + 1, 1, &bnd);
    int *vs = NULL, *vf = NULL;
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)q->nv + 2, sizeof(int), &vs);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nc + 1, sizeof(int), &vf);
    if (st != GLPGP_OK) goto done;
    for (int f = 0; f < q->nf; f++) {
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        for (int i = 0; i < k; i++) {
            E[s + i].k = ekey(q->face_vert[s + i], q->face_vert[s + (i + 1) % k]);
            E[s + i].slot = s + i;
            vs[q->face_vert[s + i] + 1]++;
        }
    }
    for (int v = 0; v < q->nv; v++) vs[v + 1] += vs[v];
    for (int f = 0; f < q->nf; f++)
        for (int s = q->face_start[f]; s < q->face_start[f + 1]; s++) vf[vs[q->face_vert[s]] + cnt[q->face_vert[s]]++] = f;
    qsort(E, (size_t)nc, sizeof *E, cmp_ekv);
    for (int i = 0; i < nc;) {
        int j = i + 1;
        while (j < nc && E[j].k == E[i].k) j++;
        if (j - i == 1) {
            bnd[(int)(E[i].k >> 32)] = 1;
            bnd[(int)(E[i].k & 0xffffffffu)] = 1;
        }
        i = j;
    }
    for (int v = 0; v < q->nv; v++) {
        if (!bnd[v]) continue;
        double t, d, pr[2];
        int s = dbnd_nearest(D, q->xy + 2 * v, 0.25 * h, &t, &d, pr, &cand, &ncap);
        if (s < 0 || d <= 1e-9 * h) continue;
        double ox = q->xy[2 * v], oy = q->xy[2 * v + 1];
        q->xy[2 * v] = pr[0];
        q->xy[2 * v + 1] = pr[1];
        int ok = 1;
        for (int j = vs[v]; j < vs[v + 1] && ok; j++) {
            int f = vf[j];
            ok = glpgp_poly_min_sj(q->xy, q->face_vert + q->face_start[f], q->face_start[f + 1] - q->face_start[f]) > 0.05;
        }
        if (ok)
            (*snapped)++;
        else {
            q->xy[2 * v] = ox;
            q->xy[2 * v + 1] = oy;
        }
    }
done:
    free(cnt);
    free(cand);
    free(E);
    free(bnd);
    free(vs);
    free(vf);
    return st;
}

static glpgp_quadmesh *qm_copy(const glpgp_quadmesh *q)
{
    glpgp_quadmesh *o = calloc(1, sizeof *o);
    if (!o) return NULL;
    *o = *q;
    o->face_origin = NULL;
    o->xy = malloc(sizeof(double) * 2 * ((size_t)q->nv + 1));
    o->face_start = malloc(sizeof(int) * ((size_t)q->nf + 1));
    o->face_vert = malloc(sizeof(int) * ((size_t)q->face_start[q->nf] + 1));
    if (!o->xy || !o->face_start || !o->face_vert) {
        glpgp_quadmesh_destroy(&o);
        return NULL;
    }
    /* an empty mesh may have NULL arrays: copy only what is there */
    if (q->nv > 0) memcpy(o->xy, q->xy, sizeof(double) * 2 * (size_t)q->nv);
    memcpy(o->face_start, q->face_start, sizeof(int) * ((size_t)q->nf + 1));
    if (q->face_start[q->nf] > 0)
        memcpy(o->face_vert, q->face_vert, sizeof(int) * (size_t)q->face_start[q->nf]);
    if (q->face_origin) {
        o->face_origin = malloc((size_t)q->nf + 1);
        if (!o->face_origin) {
            glpgp_quadmesh_destroy(&o);
            return NULL;
        }
        memcpy(o->face_origin, q->face_origin, (size_t)q->nf);
    }
    return o;
}

glpgp_status glpgp_quadmesh_repair(const glpgp_quadmesh *qin, const glpgp_mesh *m, double h, int smooth,
                                   int keep_polygons, glpgp_quadmesh **out)
{
    *out = NULL;
    if (!qin || !m || qin->nf < 0 || !(h > 0)) return GLPGP_FAIL(GLPGP_ERR_ARG, "quad repair: bad arguments");
    glpgp_status st = GLPGP_OK;
    dbnd D;
    memset(&D, 0, sizeof D);
    glpgp_quadmesh *q = qm_copy(qin), *n = NULL, *c = NULL;
    unsigned char *inB = NULL, *mark = NULL, *mark2 = NULL;
    int *vs = NULL, *vf = NULL;
    glpgp_quad_repair rs;
    memset(&rs, 0, sizeof rs);
    qcheck ck;
    memset(&ck, 0, sizeof ck);
    if (!q) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
    GLPGP_CHECK_GOTO(st, dbnd_build(&D, m, h), done);
    GLPGP_CHECK_GOTO(st, snap_boundary(q, &D, h, &rs.snapped), done);
    for (int round = 0; round < REPAIR_ROUNDS; round++) {
        glpgp_qcheck_free(&ck);
        GLPGP_CHECK_GOTO(st, glpgp_qcheck_run(q, m, h, 0.25 * h, &ck), done);
        /* area off by more than 1% (invalid): the boundary chords cut too much; also
         * re-mesh along the boundary pieces farther than h/10 from the mesh */
        {
            double area = 0.0;
            for (int f = 0; f < q->nf; f++) {
                int s = q->face_start[f], k = q->face_start[f + 1] - s;
                for (int i = 0; i < k; i++) {
                    const double *a = q->xy + 2 * q->face_vert[s + i], *b = q->xy + 2 * q->face_vert[s + (i + 1) % k];
                    area += 0.5 * (a[0] * b[1] - b[0] * a[1]);
                }
            }
            if (m->area > 0 && fabs(area / m->area - 1.0) > 0.01) {
                /* the largest tolerance (h/10, h/20, ... h/80) that flags something */
                for (double t = ldexp(0.1, -round); t >= 0.012; t *= 0.5) {
                    qcheck c2;
                    int hit = 0;
                    GLPGP_CHECK_GOTO(st, glpgp_qcheck_run(q, m, h, t * h, &c2), done);
                    for (int f = 0; f < q->nf; f++)
                        if (c2.flags[f] & (QF_FAR | QF_LOST)) {
                            ck.flags[f] |= c2.flags[f] & (QF_FAR | QF_LOST);
                            hit = 1;
                        }
                    glpgp_qcheck_free(&c2);
                    if (hit) break;
                }
            }
        }
        if (keep_polygons)
            for (int f = 0; f < q->nf; f++) ck.flags[f] &= ~(unsigned)QF_NONQUAD;
        int nbad = 0;
        for (int f = 0; f < q->nf; f++) nbad += ck.flags[f] != 0;
        if (nbad == 0 && q->nf > 0) break; /* an empty mesh: the whole domain is re-meshed */
        rs.rounds++;
        /* B: bad faces + (round + 1) vertex rings */
        free(inB);
        inB = calloc((size_t)q->nf + 1, 1);
        free(vs);
        free(vf);
        vs = calloc((size_t)q->nv + 2, sizeof(int));
        vf = malloc(sizeof(int) * ((size_t)q->face_start[q->nf] + 1));
        int *cnt = calloc((size_t)q->nv + 1, sizeof(int));
        unsigned char *vb = calloc((size_t)q->nv + 1, 1);
        if (!inB || !vs || !vf || !cnt || !vb) {
            free(cnt);
            free(vb);
            st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
            goto done;
        }
        for (int s = 0; s < q->face_start[q->nf]; s++) vs[q->face_vert[s] + 1]++;
        for (int v = 0; v < q->nv; v++) vs[v + 1] += vs[v];
        for (int f = 0; f < q->nf; f++)
            for (int s = q->face_start[f]; s < q->face_start[f + 1]; s++) vf[vs[q->face_vert[s]] + cnt[q->face_vert[s]]++] = f;
        free(cnt);
        for (int f = 0; f < q->nf; f++) inB[f] = ck.flags[f] != 0;
        for (int ring = 0; ring <= round; ring++) {
            memset(vb, 0, (size_t)q->nv + 1);
            /* first round: a face that is only too far from the boundary (a
             * chord across a feature, a lost hole) is fine in itself and gets
             * no ring; the others do */
            for (int f = 0; f < q->nf; f++)
                if (inB[f] && (round > 0 || ring > 0 || (ck.flags[f] & ~(unsigned)(QF_FAR | QF_LOST))))
                    for (int s = q->face_start[f]; s < q->face_start[f + 1]; s++) vb[q->face_vert[s]] = 1;
            for (int v = 0; v < q->nv; v++)
                if (vb[v])
                    for (int j = vs[v]; j < vs[v + 1]; j++) inB[vf[j]] = 1;
        }
        free(vb);
        int removed = 0;
        for (int f = 0; f < q->nf; f++) removed += inB[f];
        rs.removed_faces += removed;
        free(mark);
        mark = NULL;
        st = repair_round(q, m, &D, h, inB, &rs, &n, &mark);
        if (st != GLPGP_OK) {
            /* the region could not be built: keep the mesh as it is (reported invalid) */
            glpgp_log(GLPGP_LOG_DEBUG, "quad repair: %s", glpgp_error_message());
            glpgp_error_clear();
            st = GLPGP_OK;
            break;
        }
        /* smooth the new vertices; odd faces left: close them, smooth again */
        if (smooth > 0) GLPGP_CHECK_GOTO(st, glpgp_quadmesh_smooth(n, mark, smooth, 0.5, NULL), done);
        int odd = 0;
        for (int f = 0; f < n->nf; f++) odd += (n->face_start[f + 1] - n->face_start[f]) != 4;
        if (odd && !keep_polygons) {
            free(mark2);
            mark2 = NULL;
            GLPGP_CHECK_GOTO(st, glpgp_quadmesh_close_polygons(n, &c, &mark2), done);
            glpgp_quadmesh_destroy(&n);
            n = c;
            c = NULL;
            if (smooth > 0) GLPGP_CHECK_GOTO(st, glpgp_quadmesh_smooth(n, mark2, smooth, 0.5, NULL), done);
        }
        n->closing = q->closing;
        glpgp_quadmesh_destroy(&q);
        q = n;
        n = NULL;
    }
    q->repair = rs;
    *out = q;
    q = NULL;
done:
    dbnd_free(&D);
    glpgp_qcheck_free(&ck);
    glpgp_quadmesh_destroy(&q);
    glpgp_quadmesh_destroy(&n);
    glpgp_quadmesh_destroy(&c);
    free(inB);
    free(mark);
    free(mark2);
    free(vs);
    free(vf);
    return st;
}
