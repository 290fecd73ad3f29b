/* quads/close.c: turning the polygon faces left by the extraction into quads
 * without changing the element size (glpgp_quadmesh_close_polygons), and a
 * quality-guarded smoothing of chosen vertices (glpgp_quadmesh_smooth).
 *
 * Why pairing: a dislocation of one family (an integer line that ends
 * inside the domain) leaves an odd face, usually a pentagon whose corners
 * are regular except the T-junction vertex T (valence 3) where the line
 * ends. Every face of an all-quad mesh has 4 corners, so sum(corners) over
 * the faces is even; an odd face can therefore not be split into quads on
 * its own. It can if one more vertex is put on one of its edges, which adds
 * a corner to the face on the other side too; repeating this along a strip
 * of quads moves the odd parity until it reaches another odd face or the
 * domain boundary (a new vertex on a boundary edge belongs to one face
 * only), where it disappears. That is a path in the dual graph:
 *
 *   f0 (odd) -e1- q1 -e2- q2 ... qk -e(k+1)- g (odd face, or the boundary)
 *
 * Every crossed edge e_i gets its midpoint m_i; then
 *   - a quad entered and left through opposite edges is cut in two by the
 *     segment m_in m_out (two quads, both new vertices regular);
 *   - a quad entered and left through adjacent edges (a turn around the
 *     corner B they share) becomes three quads around a new vertex X joined
 *     to m_in, m_out and the corner D opposite B (X gets valence 3, D one
 *     more edge: a 3-5 pair, so turns are avoided when possible);
 *   - an odd face with one extra corner is even and is split into quads
 *     (best minimum scaled Jacobian over all splits into quads by
 *     diagonals, dynamic programming; a hexagon may also become three
 *     quads around a center vertex).
 * For a pentagon the preferred crossing edge is the one opposite T: the
 * hexagon's diagonal m - T then splits it into two quads and gives T its
 * fourth edge, so the line that ended at T is continued through the strip
 * and no irregular vertex is left at all. A pentagon without a T vertex
 * (around a +1/4 cross-field singularity: corners of valence 3 / 4 / 3 seen
 * from the crossed edge) is instead split into three quads around one
 * valence-3 center joined to the midpoint (center_first: whichever leaves
 * fewer irregular vertices).
 *
 * Paths are shortest paths (Dijkstra over (face, entry edge) states) with
 * costs: 1 per quad cut (more when its halves get thinner than h/2),
 * TURN_COST per turn, and per end 2 for each irregular vertex the end's
 * split adds (-2 for each it removes) plus a penalty for a poor split
 * (end_cost). The nearest target (odd face or boundary) wins.
 * Paths of one round use disjoint faces (a midpoint changes exactly the two
 * faces of its edge, both on the path), so they are applied together; the
 * adjacency is rebuilt between rounds. A path whose new quads would have a
 * scaled Jacobian below MIN_SJ is not applied and the odd face stays (it is
 * then reported as a polygon).
 *
 * Before the strips: even polygons (hexagons, ...) are split directly;
 * triangles, which a midpoint cannot fix (the quad would have a flat corner
 * at it), are merged with a neighbour (merge_triangle): with an odd one the
 * union is even and split at once, with a quad it is a pentagon for the
 * strips. The same is tried for the quads the extraction made from a
 * boundary triangle by promoting a boundary vertex to a corner when that
 * corner is nearly flat (150 to 180 degrees, a gently curved boundary): the
 * vertex is dropped again if the triangle left can be merged.
 *
 * After the closing, glpgp_quadmesh_smooth (bottom of this file) moves the
 * new vertices, their neighbours and the vertices of poor quads, each to the
 * step towards its neighbours' mean that most raises the worst nearby
 * corner.
 */
#include "glpgp/internal/heap.h"
#include "glpgp/quads.h"
#include "geom.h"
#include "soup.h"
#include "glpgp/status.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TURN_COST 4.0      /* two irregular vertices */
#define MIN_SJ 0.05        /* smallest scaled Jacobian accepted for a new quad */
#define MAX_ROUNDS 32

/* ---- splitting an even polygon into quads ---------------------------- */

/* The hexagon p[0..6) as three quads (p[o+2i], p[o+2i+1], p[o+2i+2], X)
 * around a new center X = (x, y) added to s: out[0 .. 12), *nq = 3. */
static glpgp_status center_quads(psoup *s, const int *p, int o, double x, double y, int *out, int *nq)
{
    int X;
    glpgp_status st = glpgp_soup_vertex(s, x, y, &X);
    if (st != GLPGP_OK) return st;
    for (int i = 0; i < 3; i++) {
        for (int k = 0; k < 3; k++) out[4 * i + k] = p[(o + 2 * i + k) % 6];
        out[4 * i + 3] = X;
    }
    *nq = 3;
    return GLPGP_OK;
}

/* A split of the even polygon p[0..n) (n >= 4) into quads: *nq quads in
 * out[0 .. 4 nq), new vertices (a hexagon's center) added to s. pref >= 0:
 * the hexagon diagonal (pref, pref + 3) is taken when its quads reach 0.3
 * (it gives the T vertex of a pentagon its fourth edge); with center = 1
 * (center_first: a pentagon around a +1/4 cross-field singularity, no T
 * vertex) the three quads around a center joined to pref, pref + 2 and
 * pref + 4 are tried first, under the same 0.3. Returns the minimum scaled
 * Jacobian of the result (-inf: no split). */
static glpgp_status split_even(psoup *s, const int *p, int n, int pref, int center, int *out, int *nq,
                               double *sj)
{
    *nq = 0;
    *sj = -INFINITY;
    if (n == 4) {
        memcpy(out, p, 4 * sizeof(int));
        *nq = 1;
        *sj = glpgp_poly_min_sj(s->xy, p, 4);
        return GLPGP_OK;
    }
    if (n < 4 || n > GLPGP_POLY_SPLIT_MAX || n % 2) return GLPGP_OK;
    if (n == 6 && pref >= 0 && center) {
        double x = 0.0, y = 0.0, c = glpgp_hex_center_split_at(s->xy, p, pref % 2, &x, &y);
        if (c >= 0.3) {
            *sj = c;
            return center_quads(s, p, pref % 2, x, y, out, nq);
        }
    }
    if (n == 6 && pref >= 0) {
        int qa[4], qb[4];
        for (int k = 0; k < 4; k++) {
            qa[k] = p[(pref + k) % 6];
            qb[k] = p[(pref + 3 + k) % 6];
        }
        double v = fmin(glpgp_poly_min_sj(s->xy, qa, 4), glpgp_poly_min_sj(s->xy, qb, 4));
        if (v >= 0.3) {
            memcpy(out, qa, sizeof qa);
            memcpy(out + 4, qb, sizeof qb);
            *nq = 2;
            *sj = v;
            return GLPGP_OK;
        }
    }
    double best = glpgp_poly_quad_split(s->xy, p, n, out, nq);
    if (best > -INFINITY) *sj = best;
    if (n == 6 && best < 0.5) {
        /* three quads around a center X joined to every other corner, when
         * clearly better */
        int o = 0;
        double x = 0.0, y = 0.0, c = glpgp_hex_center_split(s->xy, p, &o, &x, &y);
        if (c > best + 0.05) {
            *sj = c;
            return center_quads(s, p, o, x, y, out, nq);
        }
    }
    return GLPGP_OK;
}

/* Change in the number of irregular vertices when vertex v gets one more
 * edge: interior 4 -> 5 is +1, 3 -> 4 is -1; a boundary vertex counts +1
 * (end_cost's rule); a vertex newer than A (a midpoint) 0. */
static int gain_irr(const adjacency *A, int v)
{
    if (v < 0 || v >= A->nv) return 0;
    if (A->bnd[v]) return 1;
    return (A->val[v] + 1 != 4) - (A->val[v] != 4);
}

/* Hexagon p[0..6) = an odd pentagon with the midpoint p[pref] of the
 * crossed edge: 1 when the center split (X joined to p[pref], p[pref+2],
 * p[pref+4]; X of valence 3) leaves fewer irregular vertices than the
 * diagonal p[pref] - p[pref+3]. A dislocation's pentagon has its T vertex
 * (valence 3) at pref + 3 and keeps the diagonal; a pentagon around a +1/4
 * cross-field singularity (three corners of valence 3 / 4 / 3 seen from the
 * crossed edge, e.g. the singularity half a period from the boundary) gets
 * the center: one valence-3 vertex at the singularity instead of a 3-5-3
 * row. */
static int center_first(const adjacency *A, const int *p, int pref)
{
    if (pref < 0) return 0;
    int diag = gain_irr(A, p[(pref + 3) % 6]);
    int center = 1 + gain_irr(A, p[(pref + 2) % 6]) + gain_irr(A, p[(pref + 4) % 6]);
    return center < diag;
}

/* ---- shortest strip ----------------------------------------------------- */

/* Cost of ending (or starting) a strip in the odd face f through its edge
 * i: the face gets the edge's midpoint m and is split as apply_strip will
 * split it (split_even); the cost counts the irregular interior vertices
 * that this adds or removes (2 per vertex; a pentagon split through its
 * T-junction vertex removes one), plus a penalty when the worst new quad is
 * poor (< 0.3). INFINITY when the split is not acceptable (< MIN_SJ). The
 * constant END_BASE keeps every cost >= 0 (one is charged at the boundary
 * end too). */
#define END_BASE 2.0
#define POOR_SPLIT 20.0
static glpgp_status end_cost(const psoup *s, const adjacency *A, int f, int i, double *cost)
{
    *cost = INFINITY;
    int n = s->fn[f];
    const int *v = s->fv + s->fs[f];
    if (n + 1 > GLPGP_POLY_SPLIT_MAX) return GLPGP_OK;
    psoup T;
    memset(&T, 0, sizeof T);
    glpgp_status st = glpgp_grow_int(&T.xy, &T.cap_v, 2 * (n + 2), sizeof(double));
    if (st != GLPGP_OK) return st;
    int p[GLPGP_POLY_SPLIT_MAX + 1], out[4 * GLPGP_POLY_SPLIT_MAX], nq = 0, gid[GLPGP_POLY_SPLIT_MAX + 2];
    /* local polygon: corners 0..n with the midpoint after corner i */
    for (int k = 0, w = 0; k < n; k++) {
        T.xy[2 * w] = s->xy[2 * v[k]];
        T.xy[2 * w + 1] = s->xy[2 * v[k] + 1];
        gid[w] = v[k];
        p[w] = w;
        w++;
        if (k == i) {
            const double *pa = s->xy + 2 * v[i], *pb = s->xy + 2 * v[(i + 1) % n];
            T.xy[2 * w] = 0.5 * (pa[0] + pb[0]);
            T.xy[2 * w + 1] = 0.5 * (pa[1] + pb[1]);
            gid[w] = -1; /* the midpoint */
            p[w] = w;
            w++;
        }
    }
    T.nv = n + 1;
    double sj;
    int pref = n + 1 == 6 ? i + 1 : -1, gp[6];
    if (pref >= 0)
        for (int k = 0; k < 6; k++) gp[k] = gid[k];
    st = split_even(&T, p, n + 1, pref, pref >= 0 && center_first(A, gp, pref), out, &nq, &sj);
    if (st == GLPGP_OK && nq > 0 && sj >= MIN_SJ) {
        /* new edges per corner: quad sides that are not polygon sides (each
         * is seen from its two quads) */
        int add[GLPGP_POLY_SPLIT_MAX + 2] = {0};
        for (int q = 0; q < nq; q++)
            for (int k = 0; k < 4; k++) {
                int a = out[4 * q + k], b = out[4 * q + (k + 1) % 4];
                int side = a <= n && b <= n && ((a + 1) % (n + 1) == b || (b + 1) % (n + 1) == a);
                if (!side) {
                    add[a]++;
                    add[b]++;
                }
            }
        int dirr = 0;
        for (int k = 0; k < T.nv; k++) {
            int d = add[k] / 2;
            if (k > n) { /* a center vertex */
                dirr += d != 4;
                continue;
            }
            if (gid[k] < 0 || d == 0) continue; /* the midpoint ends regular */
            if (A->bnd[gid[k]]) {
                dirr += 1;
                continue;
            }
            int val = A->val[gid[k]];
            dirr += (val + d != 4) - (val != 4);
        }
        *cost = END_BASE + 2.0 * dirr + (sj < 0.3 ? POOR_SPLIT : 0.0);
    }
    free(T.xy);
    return st;
}

/* Search workspace: per corner slot (fs[f] + entry edge of quad f) the
 * distance and the predecessor slot (-1 - i: entered from the start face
 * through its edge i), reset through the touched list. */
typedef struct search {
    double *dist;
    int *pred;
    double *ecost; /* end_cost of each corner slot of the odd faces */
    double size;   /* typical edge length (cost of cutting thin quads) */
    int *touched, nt, cap_t;
    glpgp_heap h;
} search;

/* One face of a strip: face f entered through edge in and left through
 * edge out (-1: none, for the two ends). */
typedef struct pstep {
    int f, in, out;
} pstep;

/* Cost of cutting quad f entered through edge j, straight to edge k: 1,
 * more when the halves get thinner than h / 2 (a strip through quads that
 * an earlier strip already halved): (h / 2 / w)^2 with w the half width. */
static double cut_cost(const psoup *s, int f, int j, int k, double h)
{
    const int *c = s->fv + s->fs[f];
    const double *a0 = s->xy + 2 * c[j], *a1 = s->xy + 2 * c[(j + 1) % 4];
    const double *b0 = s->xy + 2 * c[k], *b1 = s->xy + 2 * c[(k + 1) % 4];
    double w = 0.25 * (hypot(a1[0] - a0[0], a1[1] - a0[1]) + hypot(b1[0] - b0[0], b1[1] - b0[1]));
    if (!(w > 0)) return 1e6;
    double r = 0.5 * h / w;
    return r > 1.0 ? r * r : 1.0;
}

static glpgp_status relax(search *S, int slot, double c, int pred)
{
    if (!(c < S->dist[slot])) return GLPGP_OK;
    if (S->dist[slot] == INFINITY) {
        glpgp_status st = glpgp_grow_int(&S->touched, &S->cap_t, S->nt + 1, sizeof(int));
        if (st != GLPGP_OK) return st;
        S->touched[S->nt++] = slot;
    }
    S->dist[slot] = c;
    S->pred[slot] = pred;
    return glpgp_heap_push(&S->h, c, slot);
}

/* The strip search crosses edge k of face f (reached at cost c, from the
 * state `from`: a slot, or -1 - k for the start face f0): the boundary or
 * an odd face beyond it is a target (its end cost added; the best one is
 * kept in *best, *best_slot, *best_exit), a free quad beyond it a new state
 * (entered through its side gi, cost of cutting it straight through). */
static glpgp_status cross(const psoup *s, const adjacency *A, const unsigned char *used, search *S, int f0,
                          int f, int k, double c, int from, double *best, int *best_slot, int *best_exit)
{
    int g = A->adj[s->fs[f] + k], gi = A->adji[s->fs[f] + k];
    if (g == -1 || (g >= 0 && g != f0 && !used[g] && s->fn[g] % 2)) {
        c += g >= 0 ? S->ecost[s->fs[g] + gi] : END_BASE;
        if (c < *best) {
            *best = c;
            *best_slot = from;
            *best_exit = k;
        }
        return GLPGP_OK;
    }
    if (g >= 0 && !used[g] && s->fn[g] == 4)
        return relax(S, s->fs[g] + gi, c + cut_cost(s, g, gi, (gi + 2) % 4, S->size), from);
    return GLPGP_OK;
}

/* Shortest strip from the odd face f0 over faces not in used[]. On success
 * path[0 .. *len) holds the strip: path[0] = f0 (out = its crossed edge),
 * then the cut quads, then the odd end face (in set, out = -1) unless the
 * strip ends on the boundary (the last step's out edge is a boundary edge).
 * *len = 0: no target reachable. */
static glpgp_status find_strip(const psoup *s, const adjacency *A, const unsigned char *used, search *S,
                               int f0, pstep **path, int *cap_path, int *len, double *cost)
{
    glpgp_status st = GLPGP_OK;
    *len = 0;
    *cost = INFINITY;
    S->h.n = 0;
    double best = INFINITY;
    int best_slot = -1, best_exit = -1; /* target reached from best_slot (or f0: -1 - edge) through best_exit */
    for (int i = 0; i < s->fn[f0]; i++) {
        double c0 = S->ecost[s->fs[f0] + i];
        if (c0 < INFINITY)
            GLPGP_CHECK_GOTO(st, cross(s, A, used, S, f0, f0, i, c0, -1 - i, &best, &best_slot, &best_exit), done);
    }
    while (S->h.n > 0) {
        glpgp_heap_item it = glpgp_heap_pop(&S->h);
        if (it.key >= best) break;
        int slot = it.id;
        if (it.key > S->dist[slot]) continue;
        int f = A->sf[slot], j = slot - s->fs[f];
        for (int dk = 1; dk <= 3; dk++) /* straight through (dk = 2, the opposite edge) or a turn */
            GLPGP_CHECK_GOTO(st, cross(s, A, used, S, f0, f, (j + dk) % 4, it.key + (dk == 2 ? 0.0 : TURN_COST),
                                       slot, &best, &best_slot, &best_exit),
                             done);
    }
    if (best < INFINITY) {
        /* walk back from the target: count, then fill */
        int n = 1, sl = best_slot;
        while (sl >= 0) {
            n++;
            sl = S->pred[sl];
        }
        int exit0 = -1 - sl; /* f0's crossed edge */
        int fl = best_slot >= 0 ? A->sf[best_slot] : f0;
        int g = A->adj[s->fs[fl] + best_exit];
        int total = n + (g >= 0 ? 1 : 0);
        GLPGP_CHECK_GOTO(st, glpgp_grow_int(path, cap_path, total, sizeof(pstep)), done);
        pstep *P = *path;
        int w = n - 1, out = best_exit;
        sl = best_slot;
        while (sl >= 0) {
            int f = A->sf[sl], in = sl - s->fs[f];
            P[w--] = (pstep){f, in, out};
            out = A->adji[sl]; /* the crossed edge's index in the previous face */
            sl = S->pred[sl];
        }
        P[0] = (pstep){f0, -1, exit0};
        if (g >= 0) P[n] = (pstep){g, A->adji[s->fs[fl] + best_exit], -1};
        *len = total;
        *cost = best;
    }
done:
    for (int i = 0; i < S->nt; i++) S->dist[S->touched[i]] = INFINITY;
    S->nt = 0;
    return st;
}

/* Polygon of face f with extra corners inserted: mid_in on edge in and
 * mid_out on edge out (-1: none). Returns the corner count. */
static int with_mids(const psoup *s, int f, int in, int mid_in, int out, int mid_out, int *p)
{
    int n = 0;
    for (int i = 0; i < s->fn[f]; i++) {
        p[n++] = s->fv[s->fs[f] + i];
        if (i == in) p[n++] = mid_in;
        if (i == out) p[n++] = mid_out;
    }
    return n;
}

typedef glpgp_quads_closing pair_stats;

/* Apply the strip P[0..len): new midpoints, the faces rewritten (old ones
 * deleted, new ones appended). Nothing is changed when a new quad would
 * have a scaled Jacobian below MIN_SJ (*ok = 0; the caller restores *ps). */
static glpgp_status apply_strip(psoup *s, const adjacency *A, const pstep *P, int len, int *ok, pair_stats *ps)
{
    glpgp_status st = GLPGP_OK;
    *ok = 0;
    int nv0 = s->nv, nf0 = s->nf, nfv0 = s->nfv;
    int last = len - 1;
    int ends_on_boundary = P[last].out >= 0;
    /* midpoints: mid[i] on the edge between P[i] and P[i+1] (i < len - 1),
     * plus the boundary midpoint mid[last] */
    int *mid = NULL;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)len + 1, sizeof(int), &mid), done);
    for (int i = 0; i < len; i++) {
        mid[i] = -1;
        if (P[i].out < 0) continue;
        int f = P[i].f, e = P[i].out, n = s->fn[f];
        const double *a = s->xy + 2 * s->fv[s->fs[f] + e], *b = s->xy + 2 * s->fv[s->fs[f] + (e + 1) % n];
        double ax = a[0], ay = a[1], bx = b[0], by = b[1]; /* s->xy may move */
        GLPGP_CHECK_GOTO(st, glpgp_soup_vertex(s, 0.5 * (ax + bx), 0.5 * (ay + by), &mid[i]), done);
    }
    double worst = INFINITY;
    for (int i = 0; i < len; i++) {
        int f = P[i].f;
        int min_ = i > 0 ? mid[i - 1] : -1, mout = mid[i];
        int p[GLPGP_POLY_SPLIT_MAX + 4], out[4 * (GLPGP_POLY_SPLIT_MAX + 4)], nq = 0;
        if (s->fn[f] != 4 || i == 0 || (i == last && !ends_on_boundary)) {
            /* an end face: one extra corner, then split the even polygon */
            int n = with_mids(s, f, P[i].in, min_, P[i].out, mout, p);
            int e = P[i].in >= 0 ? P[i].in : P[i].out; /* the crossed edge */
            int pref = -1;
            if (n == 6) pref = e + 1; /* the midpoint's position in p */
            double sj;
            if (n > GLPGP_POLY_SPLIT_MAX) goto done;
            GLPGP_CHECK_GOTO(st, split_even(s, p, n, pref, n == 6 && center_first(A, p, pref), out, &nq, &sj),
                             done);
            if (nq == 0) goto done;
            worst = fmin(worst, sj);
            if (s->fn[f] % 2) ps->closed_polygons++;
        } else {
            const int *c = s->fv + s->fs[f];
            int j = P[i].in, k = P[i].out, dk = (k - j + 4) % 4;
            if (dk == 2) {
                /* straight: (c_j, m_j, m_k, c_k+1), (m_j, c_j+1, c_k, m_k) */
                int qa[4] = {c[j], min_, mout, c[(k + 1) % 4]};
                int qb[4] = {min_, c[(j + 1) % 4], c[k], mout};
                memcpy(out, qa, sizeof qa);
                memcpy(out + 4, qb, sizeof qb);
                nq = 2;
            } else {
                /* turn around the shared corner B; X joined to m_j, m_k and
                 * the opposite corner D */
                int mA, mB, B, D, C1, C2; /* m on the edge before B, m after B (CCW) */
                if (dk == 1) { /* B = c_j+1 */
                    mA = min_; mB = mout; B = c[(j + 1) % 4];
                    C2 = c[(j + 2) % 4]; D = c[(j + 3) % 4]; C1 = c[j];
                } else { /* dk == 3: B = c_j, edge k = j - 1 comes before it */
                    mA = mout; mB = min_; B = c[j];
                    C2 = c[(j + 1) % 4]; D = c[(j + 2) % 4]; C1 = c[(j + 3) % 4];
                }
                /* quads (mA, B, mB, X), (X, mB, C2, D), (C1, mA, X, D) */
                const double *pB = s->xy + 2 * B, *pD = s->xy + 2 * D;
                double bestsj = -INFINITY, bx = 0, by = 0;
                for (int t = 0; t <= 6; t++) {
                    double w = 0.3 + 0.05 * t;
                    double x = pD[0] + w * (pB[0] - pD[0]), y = pD[1] + w * (pB[1] - pD[1]);
                    double xy[14] = {s->xy[2 * mA], s->xy[2 * mA + 1], pB[0], pB[1],
                                     s->xy[2 * mB], s->xy[2 * mB + 1], x, y,
                                     s->xy[2 * C2], s->xy[2 * C2 + 1], pD[0], pD[1],
                                     s->xy[2 * C1], s->xy[2 * C1 + 1]};
                    int q1[4] = {0, 1, 2, 3}, q2[4] = {3, 2, 4, 5}, q3[4] = {6, 0, 3, 5};
                    double v = fmin(glpgp_poly_min_sj(xy, q1, 4), fmin(glpgp_poly_min_sj(xy, q2, 4), glpgp_poly_min_sj(xy, q3, 4)));
                    if (v > bestsj) {
                        bestsj = v;
                        bx = x;
                        by = y;
                    }
                }
                int X;
                GLPGP_CHECK_GOTO(st, glpgp_soup_vertex(s, bx, by, &X), done);
                int q1[4] = {mA, B, mB, X}, q2[4] = {X, mB, C2, D}, q3[4] = {C1, mA, X, D};
                memcpy(out, q1, sizeof q1);
                memcpy(out + 4, q2, sizeof q2);
                memcpy(out + 8, q3, sizeof q3);
                nq = 3;
                ps->strip_turns++;
            }
            for (int q = 0; q < nq; q++) worst = fmin(worst, glpgp_poly_min_sj(s->xy, out + 4 * q, 4));
            ps->strip_quads++;
        }
        s->cur = glpgp_soup_closed_origin(s, f);
        for (int q = 0; q < nq; q++) GLPGP_CHECK_GOTO(st, glpgp_soup_face(s, out + 4 * q, 4, NULL), done);
    }
    if (!(worst >= MIN_SJ)) {
        /* undo: drop the new vertices and faces; statistics restored by the caller */
        s->nv = nv0;
        s->nf = nf0;
        s->nfv = nfv0;
        goto done;
    }
    for (int i = 0; i < len; i++) s->fn[P[i].f] = 0; /* the old faces are replaced */
    if (ends_on_boundary) ps->strips_to_boundary++;
    *ok = 1;
done:
    free(mid);
    return st;
}

/* Triangles: a midpoint on one of their sides would make a quad with a
 * flat corner, so a triangle t (sides t_i -> t_i+1 with the neighbour faces
 * nb[i], side nbi[i] in them; -1: none) is merged with a neighbour g across
 * a side a b (merged face: a, g's corners from a round to b, c): with an
 * odd g the result is even and is split into quads at once (taken if its
 * quads reach 0.3), with a quad it is a pentagon (taken if no corner is
 * within 6 degrees of flat), which the strips then close like any other.
 * f_old (the triangle's face) and g are deleted on success (*merged = 1). */
static glpgp_status merge_triangle(psoup *s, unsigned char *used, const int *t_in, const int *nb,
                                   const int *nbi, int f_old, int *merged, pair_stats *ps)
{
    *merged = 0;
    int t[3] = {t_in[0], t_in[1], t_in[2]}; /* t_in may point into s->fv, which may move */
    double best_even = 0.3, best_pent = 0.1;
    int be[GLPGP_POLY_SPLIT_MAX], bp[5], nbe = 0, ge = -1, gp = -1;
    glpgp_status st = GLPGP_OK;
    for (int i = 0; i < 3; i++) {
        int g = nb[i], gi = nbi[i], ng = g >= 0 ? s->fn[g] : 0;
        if (g < 0 || g == f_old || used[g] || ng + 1 > GLPGP_POLY_SPLIT_MAX || ng < 3) continue;
        int pm[GLPGP_POLY_SPLIT_MAX], n = 0;
        pm[n++] = t[i];                                                    /* a */
        for (int k = 2; k < ng; k++) pm[n++] = s->fv[s->fs[g] + (gi + k) % ng]; /* g from a to b */
        pm[n++] = t[(i + 1) % 3];                                          /* b */
        pm[n++] = t[(i + 2) % 3];                                          /* c */
        if (ng % 2) {
            int outq[4 * GLPGP_POLY_SPLIT_MAX], nq = 0, nv0 = s->nv;
            double sj;
            st = split_even(s, pm, n, -1, 0, outq, &nq, &sj);
            if (st != GLPGP_OK) return st;
            s->nv = nv0; /* evaluation only */
            if (nq > 0 && sj > best_even) {
                best_even = sj;
                ge = g;
                nbe = n;
                memcpy(be, pm, (size_t)n * sizeof(int));
            }
        } else if (ng == 4) {
            double v = glpgp_poly_min_sj(s->xy, pm, 5);
            if (v > best_pent) {
                best_pent = v;
                gp = g;
                memcpy(bp, pm, sizeof bp);
            }
        }
    }
    if (ge >= 0) {
        int outq[4 * GLPGP_POLY_SPLIT_MAX], nq = 0;
        double sj;
        st = split_even(s, be, nbe, -1, 0, outq, &nq, &sj);
        unsigned char o1 = glpgp_soup_closed_origin(s, f_old), o2 = glpgp_soup_closed_origin(s, ge);
        s->cur = o1 > o2 ? o1 : o2;
        for (int k = 0; k < nq && st == GLPGP_OK; k++) st = glpgp_soup_face(s, outq + 4 * k, 4, NULL);
        if (st != GLPGP_OK) return st;
        ps->closed_polygons += 1 + (s->fn[f_old] % 2);
        s->fn[f_old] = s->fn[ge] = 0;
        used[f_old] = used[ge] = 1;
        *merged = 1;
    } else if (gp >= 0) {
        unsigned char o1 = glpgp_soup_closed_origin(s, f_old), o2 = glpgp_soup_closed_origin(s, gp);
        s->cur = o1 > o2 ? o1 : o2;
        st = glpgp_soup_face(s, bp, 5, NULL);
        if (st != GLPGP_OK) return st;
        s->fn[f_old] = s->fn[gp] = 0;
        used[f_old] = used[gp] = 1;
        *merged = 1;
    }
    return GLPGP_OK;
}

/* ---- driver ------------------------------------------------------------ */

typedef struct odd_item {
    double cost;
    int f;
} odd_item;

static int cmp_odd(const void *pa, const void *pb)
{
    const odd_item *a = pa, *b = pb;
    if (a->cost != b->cost) return a->cost < b->cost ? -1 : 1;
    return a->f - b->f;
}

/* The state of a closing. */
typedef struct closing {
    psoup s;
    adjacency A;
    search S;
    pair_stats ps;
    unsigned char *used, *failed;
    odd_item *odd;
    pstep *path;
    int cap_path, cap_failed;
} closing;

/* Even polygons (hexagons, ...) need no partner: split them. */
static glpgp_status split_even_faces(closing *C)
{
    psoup *s = &C->s;
    for (int f = 0, nf0 = s->nf; f < nf0; f++) {
        int n = s->fn[f];
        if (n < 6 || n % 2 || n > GLPGP_POLY_SPLIT_MAX) continue;
        int p[GLPGP_POLY_SPLIT_MAX], outq[4 * GLPGP_POLY_SPLIT_MAX], nq = 0, nv0 = s->nv;
        double sj;
        memcpy(p, s->fv + s->fs[f], (size_t)n * sizeof(int));
        GLPGP_CHECK(split_even(s, p, n, -1, 0, outq, &nq, &sj));
        if (nq == 0 || !(sj >= MIN_SJ)) {
            s->nv = nv0;
            continue;
        }
        s->cur = glpgp_soup_closed_origin(s, f);
        for (int k = 0; k < nq; k++) GLPGP_CHECK(glpgp_soup_face(s, outq + 4 * k, 4, NULL));
        s->fn[f] = 0;
        C->ps.split_even++;
    }
    return GLPGP_OK;
}

/* Triangles (see merge_triangle); first the quads that are triangles with
 * a boundary vertex promoted to a corner by the extraction: a boundary
 * vertex of valence 2 with a corner angle above 150 degrees (on a gently
 * curved boundary the promoted vertex is nearly flat) is dropped again if
 * the triangle left can be merged. */
static glpgp_status merge_triangles(closing *C)
{
    psoup *s = &C->s;
    const adjacency *A = &C->A;
    GLPGP_CHECK(glpgp_adj_build(s, &C->A));
    int nf0 = s->nf;
    GLPGP_CHECK(glpgp_calloc((size_t)nf0 + 1, 1, &C->used));
    for (int f = 0; f < nf0; f++) {
        if (s->fn[f] != 4 || C->used[f]) continue;
        const int *c = s->fv + s->fs[f];
        for (int k = 0; k < 4; k++) {
            int v = c[k];
            if (!A->bnd[v] || A->val[v] != 2) continue;
            if (A->adj[s->fs[f] + k] != -1 || A->adj[s->fs[f] + (k + 3) % 4] != -1) continue;
            const double *pv = s->xy + 2 * v, *pa = s->xy + 2 * c[(k + 1) % 4], *pb = s->xy + 2 * c[(k + 3) % 4];
            double e1x = pa[0] - pv[0], e1y = pa[1] - pv[1], e2x = pb[0] - pv[0], e2y = pb[1] - pv[1];
            double sine = (e1x * e2y - e1y * e2x) / (hypot(e1x, e1y) * hypot(e2x, e2y) + 1e-300);
            /* only wide convex corners (150 to 180 deg): the chord b a then stays inside a convex arc */
            if (!(sine < 0.5 && sine >= 0.0) || e1x * e2x + e1y * e2y > 0) continue;
            /* triangle a -> c2 -> b (sides: f's two other sides, and the new boundary chord b -> a) */
            int t[3] = {c[(k + 1) % 4], c[(k + 2) % 4], c[(k + 3) % 4]};
            int nb[3] = {A->adj[s->fs[f] + (k + 1) % 4], A->adj[s->fs[f] + (k + 2) % 4], -1};
            int nbi[3] = {A->adji[s->fs[f] + (k + 1) % 4], A->adji[s->fs[f] + (k + 2) % 4], -1};
            int merged = 0;
            GLPGP_CHECK(merge_triangle(s, C->used, t, nb, nbi, f, &merged, &C->ps));
            if (merged) break;
        }
    }
    for (int f = 0; f < nf0; f++) {
        if (s->fn[f] != 3 || C->used[f]) continue;
        int nb[3], nbi[3];
        for (int i = 0; i < 3; i++) {
            nb[i] = A->adj[s->fs[f] + i];
            nbi[i] = A->adji[s->fs[f] + i];
        }
        int merged = 0;
        GLPGP_CHECK(merge_triangle(s, C->used, s->fv + s->fs[f], nb, nbi, f, &merged, &C->ps));
    }
    return GLPGP_OK;
}

/* The round's work arrays and the end costs of the odd faces. */
static glpgp_status round_setup(closing *C)
{
    psoup *s = &C->s;
    search *S = &C->S;
    const int nf0 = s->nf, old = C->cap_failed;
    GLPGP_CHECK(glpgp_grow_int(&C->failed, &C->cap_failed, nf0, 1));
    if (C->cap_failed > old) memset(C->failed + old, 0, (size_t)(C->cap_failed - old));
    glpgp_free(&C->used);
    glpgp_free(&C->odd);
    glpgp_free(&S->dist);
    glpgp_free(&S->pred);
    glpgp_free(&S->ecost);
    GLPGP_CHECK(glpgp_calloc((size_t)nf0 + 1, 1, &C->used));
    GLPGP_CHECK(glpgp_malloc((size_t)nf0 + 1, sizeof *C->odd, &C->odd));
    GLPGP_CHECK(glpgp_malloc((size_t)s->nfv + 1, sizeof(double), &S->dist));
    GLPGP_CHECK(glpgp_malloc((size_t)s->nfv + 1, sizeof(int), &S->pred));
    GLPGP_CHECK(glpgp_malloc((size_t)s->nfv + 1, sizeof(double), &S->ecost));
    for (int i = 0; i <= s->nfv; i++) S->dist[i] = S->ecost[i] = INFINITY;
    for (int f = 0; f < nf0; f++)
        if (s->fn[f] % 2)
            for (int i = 0; i < s->fn[f]; i++) GLPGP_CHECK(end_cost(s, &C->A, f, i, &S->ecost[s->fs[f] + i]));
    return GLPGP_OK;
}

/* One round of strips: the cheapest first, on disjoint faces. *progress:
 * strips applied. */
static glpgp_status strip_round(closing *C, int *progress)
{
    psoup *s = &C->s;
    int nf0 = s->nf, nodd = 0, len;
    double cost;
    *progress = 0;
    GLPGP_CHECK(glpgp_adj_build(s, &C->A));
    GLPGP_CHECK(round_setup(C));
    for (int f = 0; f < nf0; f++) {
        if (s->fn[f] == 0 || s->fn[f] % 2 == 0 || s->fn[f] > GLPGP_POLY_SPLIT_MAX - 1) continue;
        if (f < C->cap_failed && C->failed[f]) continue;
        GLPGP_CHECK(find_strip(s, &C->A, C->used, &C->S, f, &C->path, &C->cap_path, &len, &cost));
        if (len > 0) C->odd[nodd++] = (odd_item){cost, f};
    }
    qsort(C->odd, (size_t)nodd, sizeof *C->odd, cmp_odd);
    for (int k = 0; k < nodd; k++) {
        int f = C->odd[k].f;
        if (C->used[f]) continue;
        GLPGP_CHECK(find_strip(s, &C->A, C->used, &C->S, f, &C->path, &C->cap_path, &len, &cost));
        if (len == 0) continue;
        /* a strip that visits a face twice is not applied (marks: used) */
        int rep = 0;
        for (int i = 0; i < len && !rep; i++) {
            if (C->used[C->path[i].f]) rep = 1;
            C->used[C->path[i].f] = 1;
        }
        if (rep) {
            for (int i = 0; i < len; i++) C->used[C->path[i].f] = 1;
            continue;
        }
        pair_stats save = C->ps;
        int ok = 0;
        GLPGP_CHECK(apply_strip(s, &C->A, C->path, len, &ok, &C->ps));
        if (!ok) {
            C->ps = save;
            C->failed[f] = 1;
        } else {
            (*progress)++;
        }
    }
    return GLPGP_OK;
}

glpgp_status glpgp_quadmesh_close_polygons(const glpgp_quadmesh *q, glpgp_quadmesh **out,
                                           unsigned char **new_vertices)
{
    *out = NULL;
    if (new_vertices) *new_vertices = NULL;
    unsigned char *mark = NULL, *omark = NULL;
    if (!q || q->nf <= 0) return GLPGP_FAIL(GLPGP_ERR_ARG, "quad pairing: empty mesh");
    closing C;
    memset(&C, 0, sizeof C);
    glpgp_quadmesh *r = NULL;
    glpgp_status st = glpgp_soup_from_mesh(q, &C.s);
    if (st != GLPGP_OK) goto done;
    { /* typical size: mean edge length */
        const psoup *s = &C.s;
        double sum = 0.0;
        for (int f = 0; f < s->nf; f++)
            for (int i = 0; i < s->fn[f]; i++) {
                const double *a = s->xy + 2 * s->fv[s->fs[f] + i], *b = s->xy + 2 * s->fv[s->fs[f] + (i + 1) % s->fn[f]];
                sum += hypot(b[0] - a[0], b[1] - a[1]);
            }
        C.S.size = s->nfv ? sum / s->nfv : 1.0;
    }
    GLPGP_CHECK_GOTO(st, split_even_faces(&C), done);
    GLPGP_CHECK_GOTO(st, merge_triangles(&C), done);
    for (int round = 0; round < MAX_ROUNDS; round++) {
        int progress = 0;
        glpgp_progress_poll();
        GLPGP_CHECK_GOTO(st, strip_round(&C, &progress), done);
        if (!progress) break;
    }
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)C.s.nv + 1, 1, &mark), done);
    for (int v = q->nv; v < C.s.nv; v++) mark[v] = 1; /* every vertex added here */
    GLPGP_CHECK_GOTO(st, glpgp_soup_to_mesh(&C.s, q, mark, &omark, &r), done);
    r->closing = C.ps;
    *out = r;
    r = NULL;
    if (new_vertices) {
        *new_vertices = omark;
        omark = NULL;
    }
done:
    glpgp_soup_free(&C.s);
    glpgp_adj_free(&C.A);
    free(C.S.dist);
    free(C.S.pred);
    free(C.S.ecost);
    free(C.S.touched);
    glpgp_heap_free(&C.S.h);
    free(C.used);
    free(C.failed);
    free(C.odd);
    free(C.path);
    free(mark);
    free(omark);
    glpgp_quadmesh_destroy(&r);
    return st;
}
