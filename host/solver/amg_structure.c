/* solver/amg_structure.c: the structure of the aggregation multigrid
 * hierarchy (solver/amg.c), built once per system and shared read-only by
 * every solve on it -- the guiding field, u, v and a concurrent v's backend
 * clone (glpgp_backend.amg_shared): the aggregates of every level, the
 * coarse patterns, the Galerkin index maps and the aggregate centroids.
 *
 * Aggregation: each level aggregates its graph by two passes of pairwise
 * matching (Notay's AGMG idea: the unmatched node with the fewest unmatched
 * neighbours takes its strongest unmatched neighbour; fine edge weights 1,
 * coarse weights the number of fine edges between two aggregates, which
 * keeps aggregates compact; a coupled system's edges across a conjugation
 * are never taken, conj_slot): aggregates of about 4 nodes (levels >= 1
 * with amg_coarse_passes = 3: a third pass, about 8), coarse graph =
 * quotient graph. Every vertex is aggregated, Dirichlet or not: the
 * Dirichlet set differs between the guiding field, u and v, and enters only
 * the values (a Dirichlet vertex's frame is 0, so its prolongation weight is
 * 0 and an aggregate of Dirichlet vertices only is dead: an identity row on
 * the coarse level, glpgp/backend.h amg_values). Coarsening stops at
 * o->amg_coarse nodes.
 *
 * Coarse numbering: every level >= 1 is renumbered so that the members of
 * each of its aggregates are consecutive and the aggregates in the order of
 * the next level's nodes (top-down from the coarsest), so that restriction
 * and prolongation of the coarse levels read and write in row order; level 0
 * keeps the system's numbering (its aggregates are gathered through amem). */
#include "amg_internal.h"

#include "glpgp/util.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static void wgraph_free(wgraph *g)
{
    free(g->ptr);
    free(g->adj);
    free(g->wt);
    memset(g, 0, sizeof *g);
}

/* edge k's weight; unit weights are not stored (wt NULL: a system without
 * conjugations, every planar default solve and the guiding field) */
#define WT(g, k) ((g)->wt ? (g)->wt[k] : 1.0)

/* Whether slot k of a coupled system joins two nodes whose values enter a
 * triangle's frame one conjugated, the other not (sys->cconj; none without
 * it). Such nodes never share an aggregate: the tentative prolongation
 * x_i = c_i u cannot carry the frame's phase mode i z across them (it is
 * i z on one side, -i z on the other), so an aggregate across a cut would
 * lose it on every coarser level (docs/numerics.md, "Coupled oscillators
 * across the cuts", *Multigrid*). */
static int conj_slot(const glpgp_system *sys, long k)
{
    if (!sys->cconj) return 0;
    for (int q = sys->cptr[k]; q < sys->cptr[k + 1]; q++) {
        const int e = sys->contrib[q], t = e / 9, a = (e / 3) % 3, b = e % 3;
        if (sys->cconj[3 * t + a] != sys->cconj[3 * t + b]) return 1;
    }
    return 0;
}

/* The vertex graph of the system (edges of the block pattern, weight 1;
 * -infinity where conj_slot: the quotient's sums keep it, the pairing
 * never takes it). */
static glpgp_status fine_graph(const glpgp_system *sys, wgraph *g)
{
    g->n = sys->nv;
    const long ne = sys->nnzb - sys->nv;
    GLPGP_CHECK(glpgp_malloc((size_t)sys->nv + 1, sizeof(int), &g->ptr));
    GLPGP_CHECK(glpgp_malloc((size_t)(ne > 0 ? ne : 1), sizeof(int), &g->adj));
    g->wt = NULL; /* unit weights (WT): stored only with conjugations (conj_slot) */
    if (sys->cconj) GLPGP_CHECK(glpgp_malloc((size_t)(ne > 0 ? ne : 1), sizeof(double), &g->wt));
    long e = 0;
    g->ptr[0] = 0;
    for (int i = 0; i < sys->nv; i++) {
        for (int k = sys->rowptr[i]; k < sys->rowptr[i + 1]; k++) {
            const int j = sys->col[k];
            if (j == i) continue;
            g->adj[e] = j;
            if (g->wt) g->wt[e] = conj_slot(sys, k) ? -INFINITY : 1.0;
            e++;
        }
        g->ptr[i + 1] = (int)e;
    }
    return GLPGP_OK;
}

/* One pass of pairwise matching on g restricted to the active nodes
 * (act[i] != 0): repeatedly take the unmatched node with the fewest unmatched
 * neighbours and pair it with its strongest unmatched neighbour (ties: fewer
 * unmatched neighbours, then smaller index), or leave it alone. grp[i] <- the
 * pair's index (-1 for inactive nodes); returns the number of groups.
 * Degrees only decrease, so a bucket list per degree gives O(edges). */
static glpgp_status pair_pass(const wgraph *g, const unsigned char *act, int *grp, int *ngroups)
{
    const int n = g->n;
    int *deg = NULL, *head = NULL, *next = NULL, *prev = NULL;
    unsigned char *done = NULL;
    glpgp_status st = GLPGP_OK;
    int maxdeg = 0, ng = 0;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n + 1, sizeof(int), &deg), out);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n + 1, sizeof(int), &next), out);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n + 1, sizeof(int), &prev), out);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)n + 1, 1, &done), out);
    for (int i = 0; i < n; i++) {
        grp[i] = -1;
        deg[i] = 0;
        if (!act[i]) {
            done[i] = 1;
            continue;
        }
        for (int k = g->ptr[i]; k < g->ptr[i + 1]; k++) deg[i] += act[g->adj[k]] != 0;
        if (deg[i] > maxdeg) maxdeg = deg[i];
    }
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)maxdeg + 1, sizeof(int), &head), out);
    for (int d = 0; d <= maxdeg; d++) head[d] = -1;
    /* bucket lists, nodes inserted in decreasing index so that each bucket
     * starts with its smallest index */
    for (int i = n - 1; i >= 0; i--) {
        if (done[i]) continue;
        prev[i] = -1;
        next[i] = head[deg[i]];
        if (head[deg[i]] >= 0) prev[head[deg[i]]] = i;
        head[deg[i]] = i;
    }
#define UNLINK(i)                                            \
    do {                                                     \
        if (prev[i] >= 0) next[prev[i]] = next[i];           \
        else head[deg[i]] = next[i];                         \
        if (next[i] >= 0) prev[next[i]] = prev[i];           \
    } while (0)
    int cur = 0;
    for (;;) {
        while (cur <= maxdeg && head[cur] < 0) cur++;
        if (cur > maxdeg) break;
        int i = head[cur];
        UNLINK(i);
        done[i] = 1;
        int best = -1;
        double bw = 0.0;
        for (int k = g->ptr[i]; k < g->ptr[i + 1]; k++) {
            int j = g->adj[k];
            if (done[j] || !(WT(g, k) > 0.0)) continue; /* not across a conjugation (fine_graph) */
            if (best < 0 || WT(g, k) > bw || (WT(g, k) == bw && (deg[j] < deg[best] ||
                                                                 (deg[j] == deg[best] && j < best)))) {
                best = j;
                bw = WT(g, k);
            }
        }
        grp[i] = ng;
        if (best >= 0) {
            UNLINK(best);
            done[best] = 1;
            grp[best] = ng;
        }
        ng++;
        /* the unmatched neighbours of i and best lose one unmatched neighbour */
        for (int s = 0; s < 2; s++) {
            int u = s ? best : i;
            if (u < 0) continue;
            for (int k = g->ptr[u]; k < g->ptr[u + 1]; k++) {
                int j = g->adj[k];
                if (done[j]) continue;
                UNLINK(j);
                deg[j]--;
                prev[j] = -1;
                next[j] = head[deg[j]];
                if (head[deg[j]] >= 0) prev[head[deg[j]]] = j;
                head[deg[j]] = j;
                if (deg[j] < cur) cur = deg[j];
            }
        }
    }
#undef UNLINK
    *ngroups = ng;
out:
    free(deg);
    free(head);
    free(next);
    free(prev);
    free(done);
    return st;
}

/* Quotient graph of g under map (node -> group in [0, nc), -1: dropped):
 * edge (I, J), I != J, weight = sum of the weights of the edges between
 * them; adjacency sorted. */
static glpgp_status quotient(const wgraph *g, const int *map, int nc, wgraph *c)
{
    glpgp_status st = GLPGP_OK;
    int *mptr = NULL, *mem = NULL, *mark = NULL, *slot = NULL;
    c->n = nc;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nc + 1, sizeof(int), &mptr), out);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)g->n + 1, sizeof(int), &mem), out);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof(int), &mark), out);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof(int), &slot), out);
    for (int i = 0; i < g->n; i++)
        if (map[i] >= 0) mptr[map[i] + 1]++;
    for (int J = 0; J < nc; J++) mptr[J + 1] += mptr[J];
    for (int i = 0; i < g->n; i++)
        if (map[i] >= 0) mem[mptr[map[i]]++] = i;
    for (int J = nc; J > 0; J--) mptr[J] = mptr[J - 1];
    mptr[0] = 0;
    /* count, then fill */
    for (int J = 0; J < nc; J++) mark[J] = -1;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nc + 1, sizeof(int), &c->ptr), out);
    for (int I = 0; I < nc; I++) {
        int cnt = 0;
        for (int p = mptr[I]; p < mptr[I + 1]; p++) {
            int i = mem[p];
            for (int k = g->ptr[i]; k < g->ptr[i + 1]; k++) {
                int J = map[g->adj[k]];
                if (J < 0 || J == I || mark[J] == I) continue;
                mark[J] = I;
                cnt++;
            }
        }
        c->ptr[I + 1] = c->ptr[I] + cnt;
    }
    size_t ne = (size_t)c->ptr[nc];
    GLPGP_CHECK_GOTO(st, glpgp_malloc(ne ? ne : 1, sizeof(int), &c->adj), out);
    GLPGP_CHECK_GOTO(st, glpgp_calloc(ne ? ne : 1, sizeof(double), &c->wt), out);
    for (int J = 0; J < nc; J++) mark[J] = -1;
    for (int I = 0; I < nc; I++) {
        int e = c->ptr[I];
        for (int p = mptr[I]; p < mptr[I + 1]; p++) {
            int i = mem[p];
            for (int k = g->ptr[i]; k < g->ptr[i + 1]; k++) {
                int J = map[g->adj[k]];
                if (J < 0 || J == I) continue;
                if (mark[J] != I) {
                    mark[J] = I;
                    slot[J] = e;
                    c->adj[e] = J;
                    c->wt[e] = 0.0;
                    e++;
                }
                c->wt[slot[J]] += WT(g, k);
            }
        }
        /* sort the row by J (insertion sort: rows are short) */
        for (int a = c->ptr[I] + 1; a < c->ptr[I + 1]; a++) {
            int ja = c->adj[a];
            double wa = c->wt[a];
            int bpos = a - 1;
            while (bpos >= c->ptr[I] && c->adj[bpos] > ja) {
                c->adj[bpos + 1] = c->adj[bpos];
                c->wt[bpos + 1] = c->wt[bpos];
                bpos--;
            }
            c->adj[bpos + 1] = ja;
            c->wt[bpos + 1] = wa;
        }
    }
out:
    free(mptr);
    free(mem);
    free(mark);
    free(slot);
    return st;
}


/* grp <- the aggregates of graph g (`passes` pairing passes, 2 or 3, each on
 * the quotient graph of the one before; every node in one),
 * numbered by their first member (the coarse levels keep the locality of
 * the fine ordering); *nc their count. When the graph is small enough (n <=
 * coarse) every node is its own aggregate (the next level is then the
 * coarsest and solves the level exactly). */
static glpgp_status aggregate(const wgraph *g, int coarse, int passes, int *grp, int *nc)
{
    glpgp_status st = GLPGP_OK;
    const int n = g->n;
    int *pair = NULL;
    unsigned char *act = NULL;
    wgraph q[2]; /* the quotient graphs, alternating */
    memset(q, 0, sizeof q);
    if (n <= coarse) {
        for (int i = 0; i < n; i++) grp[i] = i;
        *nc = n;
        return GLPGP_OK;
    }
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n + 1, 1, &act), out);
    memset(act, 1, (size_t)n + 1);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n + 1, sizeof(int), &pair), out);
    for (int i = 0; i < n; i++) grp[i] = i;
    const wgraph *cur = g;
    int ng = n;
    /* passes beyond the second only while the graph is above the coarsest size */
    for (int p = 0; p < passes && (p < 2 || ng > coarse); p++) {
        if (p > 0) { /* pass p pairs the groups of pass p - 1: on their quotient graph */
            wgraph *nx = &q[p % 2];
            wgraph_free(nx);
            GLPGP_CHECK_GOTO(st, quotient(cur, pair, ng, nx), out);
            cur = nx;
        }
        GLPGP_CHECK_GOTO(st, pair_pass(cur, act, pair, &ng), out);
        for (int i = 0; i < n; i++) grp[i] = pair[grp[i]];
    }
    /* number the aggregates by their first member */
    for (int J = 0; J < ng; J++) pair[J] = -1;
    int next = 0;
    for (int i = 0; i < n; i++) {
        const int J = grp[i];
        if (pair[J] < 0) pair[J] = next++;
        grp[i] = pair[J];
    }
    *nc = ng;
out:
    free(pair);
    free(act);
    wgraph_free(&q[0]);
    wgraph_free(&q[1]);
    return st;
}

/* A level whose aggregation stalls at the cuts (conj_slot edges around
 * small regions: under 2 nodes per aggregate) is aggregated again with
 * those edges allowed, as the weakest: returns whether g had any. */
static int allow_cuts(wgraph *g)
{
    int any = 0;
    if (!g->wt) return 0; /* unit weights: no conjugation */
    for (int k = 0; g->n > 0 && k < g->ptr[g->n]; k++)
        if (!(g->wt[k] > 0.0)) {
            g->wt[k] = 1e-6;
            any = 1;
        }
    return any;
}

/* The levels' aggregates (s->lev[l].agg, l < L-1) and sizes from the
 * system's graph: coarsen until the coarsest is small enough. */
static glpgp_status coarsen(glpgp_amg_structure *s, const glpgp_options *o)
{
    glpgp_status st = GLPGP_OK;
    wgraph g, q;
    memset(&g, 0, sizeof g);
    memset(&q, 0, sizeof q);
    GLPGP_CHECK_GOTO(st, fine_graph(s->sys, &g), out);
    int L = 1;
    s->lev[0].n = s->sys->nv;
    for (;;) {
        amg_slevel *lv = &s->lev[L - 1];
        int nc = 0;
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)lv->n + 1, sizeof(int), &lv->agg), out);
        const int passes = L > 1 ? o->amg_coarse_passes : 2;
        GLPGP_CHECK_GOTO(st, aggregate(&g, o->amg_coarse, passes, lv->agg, &nc), out);
        if (nc > o->amg_coarse && 2 * (long)nc > lv->n && allow_cuts(&g))
            GLPGP_CHECK_GOTO(st, aggregate(&g, o->amg_coarse, passes, lv->agg, &nc), out);
        s->lev[L].n = nc;
        L++;
        if (nc == 0) {
            st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "multigrid: no vertex to coarsen");
            goto out;
        }
        if (nc <= o->amg_coarse) break;
        if (L == o->amg_max_levels || nc > 0.9 * lv->n) {
            /* coarsening stalled or the level cap: the coarsest level must
             * still be small enough for the dense inverse */
            if (nc > 1024) {
                st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "multigrid: coarsening stopped at %d nodes", nc);
                goto out;
            }
            break;
        }
        GLPGP_CHECK_GOTO(st, quotient(&g, lv->agg, nc, &q), out);
        wgraph_free(&g);
        g = q;
        memset(&q, 0, sizeof q);
    }
    s->L = L;
out:
    wgraph_free(&g);
    wgraph_free(&q);
    return st;
}

/* Coarse numbering (see the file comment): from the coarsest level up to
 * level 1, level l's nodes sorted by (their aggregate, their index) -- a
 * counting sort, stable -- and the aggregate numbers of level l-1 relabelled
 * to match. */
static glpgp_status renumber(glpgp_amg_structure *s)
{
    int *perm = NULL, *cnt = NULL, *tmp = NULL;
    glpgp_status st = GLPGP_OK;
    for (int l = s->L - 2; l >= 1; l--) {
        amg_slevel *lv = &s->lev[l];
        const int n = lv->n, nc = s->lev[l + 1].n;
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nc + 1, sizeof(int), &cnt), out);
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n + 1, sizeof(int), &perm), out);
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n + 1, sizeof(int), &tmp), out);
        for (int i = 0; i < n; i++) cnt[lv->agg[i] + 1]++;
        for (int J = 0; J < nc; J++) cnt[J + 1] += cnt[J];
        for (int i = 0; i < n; i++) perm[i] = cnt[lv->agg[i]]++; /* new index of node i */
        for (int i = 0; i < n; i++) tmp[perm[i]] = lv->agg[i];
        memcpy(lv->agg, tmp, (size_t)n * sizeof(int));
        amg_slevel *up = &s->lev[l - 1];
        for (int i = 0; i < up->n; i++) up->agg[i] = perm[up->agg[i]];
        free(perm);
        free(cnt);
        free(tmp);
        perm = cnt = tmp = NULL;
    }
out:
    free(perm);
    free(cnt);
    free(tmp);
    return st;
}

/* Level l's transfer to l+1 from its aggregates: members of each aggregate
 * (aptr / amem, increasing), level l+1's pattern (the quotient of level l's
 * pattern: blocks (agg(i), agg(j)) of its blocks (i, j), sorted, diagonal
 * included), the Galerkin map (coarse slot K <- the level-l slots mapping
 * to it, increasing) and the aggregate centroids. */
static glpgp_status build_transfer(glpgp_amg_structure *s, int l)
{
    glpgp_status st = GLPGP_OK;
    amg_slevel *lv = &s->lev[l], *nx = &s->lev[l + 1];
    const int n = lv->n, nc = nx->n;
    const int *rowptr = l ? lv->rowptr : s->sys->rowptr, *col = l ? lv->col : s->sys->col;
    int *pos = NULL, *fill = NULL;
    long *cnt = NULL;
    /* members of each aggregate */
    GLPGP_CHECK(glpgp_calloc((size_t)nc + 1, sizeof(int), &lv->aptr));
    GLPGP_CHECK(glpgp_malloc((size_t)n + 1, sizeof(int), &lv->amem));
    for (int i = 0; i < n; i++) lv->aptr[lv->agg[i] + 1]++;
    for (int J = 0; J < nc; J++) lv->aptr[J + 1] += lv->aptr[J];
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof(int), &fill), out);
    memcpy(fill, lv->aptr, (size_t)nc * sizeof(int));
    for (int i = 0; i < n; i++) lv->amem[fill[lv->agg[i]]++] = i;
    /* next level's pattern: for each aggregate I the distinct agg(j) of its
     * members' blocks, sorted (a marker per coarse column) */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof(int), &pos), out);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof(int), &nx->rowptr), out);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof(int), &nx->diag), out);
    for (int J = 0; J < nc; J++) pos[J] = -1;
    long nnz = 0;
    nx->rowptr[0] = 0;
    for (int pass = 0; pass < 2; pass++) {
        nnz = 0;
        for (int I = 0; I < nc; I++) {
            const long row0 = nnz;
            for (int p = lv->aptr[I]; p < lv->aptr[I + 1]; p++) {
                const int i = lv->amem[p];
                for (int k = rowptr[i]; k < rowptr[i + 1]; k++) {
                    const int J = lv->agg[col[k]];
                    if (pos[J] == I) continue;
                    pos[J] = I;
                    if (pass) nx->col[nnz] = J;
                    nnz++;
                }
            }
            if (pass) {
                /* sort the row (insertion: rows are short), find the diagonal */
                int *c = nx->col + row0;
                const int len = (int)(nnz - row0);
                for (int a = 1; a < len; a++) {
                    const int v = c[a];
                    int b = a - 1;
                    while (b >= 0 && c[b] > v) {
                        c[b + 1] = c[b];
                        b--;
                    }
                    c[b + 1] = v;
                }
                for (int a = 0; a < len; a++)
                    if (c[a] == I) nx->diag[I] = (int)(row0 + a);
                nx->rowptr[I + 1] = (int)nnz;
            }
        }
        if (!pass) {
            if (nnz > (long)INT_MAX - 1) {
                st = GLPGP_FAIL(GLPGP_ERR_LIMIT, "multigrid: level %d has too many blocks", l + 1);
                goto out;
            }
            GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nnz + 1, sizeof(int), &nx->col), out);
            for (int J = 0; J < nc; J++) pos[J] = -1;
        }
    }
    nx->nnzb = nnz;
    /* Galerkin map: coarse slot K = (I, J) <- level-l slots k = (i, j) with
     * agg(i) = I, agg(j) = J, listed by increasing k */
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nx->nnzb + 1, sizeof(long), &cnt), out);
    for (int J = 0; J < nc; J++) pos[J] = -1;
    long total = 0;
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1) {
            GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nx->nnzb + 1, sizeof(int), &lv->gptr), out);
            GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)(total ? total : 1), sizeof(int), &lv->gsrc), out);
            lv->gptr[0] = 0;
            for (long K = 0; K < nx->nnzb; K++) lv->gptr[K + 1] = lv->gptr[K] + (int)cnt[K];
            for (long K = 0; K < nx->nnzb; K++) cnt[K] = lv->gptr[K];
        }
        for (int I = 0; I < nc; I++) {
            for (int K = nx->rowptr[I]; K < nx->rowptr[I + 1]; K++) pos[nx->col[K]] = K;
            for (int p = lv->aptr[I]; p < lv->aptr[I + 1]; p++) {
                const int i = lv->amem[p];
                for (int k = rowptr[i]; k < rowptr[i + 1]; k++) {
                    const int K = pos[lv->agg[col[k]]];
                    if (pass == 0) {
                        cnt[K]++;
                        total++;
                    } else {
                        lv->gsrc[cnt[K]++] = k;
                    }
                }
            }
            for (int K = nx->rowptr[I]; K < nx->rowptr[I + 1]; K++) pos[nx->col[K]] = -1;
        }
    }
    /* centroids (the plane-wave frames of glpgp_amg_create) */
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * nc + 1, sizeof(double), &nx->pos), out);
    for (int J = 0; J < nc; J++) {
        const int c = lv->aptr[J + 1] - lv->aptr[J];
        for (int p = lv->aptr[J]; p < lv->aptr[J + 1]; p++) {
            const int i = lv->amem[p];
            nx->pos[2 * J] += lv->pos[2 * i] / c;
            nx->pos[2 * J + 1] += lv->pos[2 * i + 1] / c;
        }
    }
out:
    free(pos);
    free(fill);
    free(cnt);
    return st;
}

void glpgp_amg_structure_destroy(glpgp_amg_structure **ps)
{
    if (!ps || !*ps) return;
    glpgp_amg_structure *s = *ps;
    for (int l = 0; l < GLPGP_AMG_MAX_LEVELS; l++) {
        amg_slevel *v = &s->lev[l];
        free(v->rowptr);
        free(v->col);
        free(v->diag);
        free(v->agg);
        free(v->aptr);
        free(v->amem);
        free(v->gptr);
        free(v->gsrc);
        free(v->pos);
    }
    free(s);
    *ps = NULL;
}

glpgp_status glpgp_amg_structure_create(const glpgp_system *sys, const glpgp_options *o, glpgp_amg_structure **out)
{
    *out = NULL;
    const double t0 = glpgp_now();
    glpgp_amg_structure *s = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *s, &s));
    s->sys = sys;
    s->coarse = o->amg_coarse;
    s->max_levels = o->amg_max_levels;
    GLPGP_CHECK_GOTO(st, coarsen(s, o), fail);
    GLPGP_CHECK_GOTO(st, renumber(s), fail);
    s->lev[0].nnzb = sys->nnzb;
    /* positions for the plane-wave frames (a surface has no plane: zeros, unused) */
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * sys->nv + 1, sizeof(double), &s->lev[0].pos), fail);
    if (sys->mesh->xy) memcpy(s->lev[0].pos, sys->mesh->xy, (size_t)2 * sys->nv * sizeof(double));
    for (int l = 0; l + 1 < s->L; l++) GLPGP_CHECK_GOTO(st, build_transfer(s, l), fail);
    double oc = 0.0, gc = 0.0;
    for (int l = 0; l < s->L; l++) {
        oc += (double)s->lev[l].nnzb;
        gc += s->lev[l].n;
    }
    s->operator_complexity = oc / (double)sys->nnzb;
    s->grid_complexity = gc / sys->nv;
    s->seconds = glpgp_now() - t0;
    *out = s;
    return GLPGP_OK;
fail:
    glpgp_amg_structure_destroy(&s);
    return st;
}
