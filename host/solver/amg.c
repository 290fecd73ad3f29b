/* solver/amg.c: the aggregation multigrid preconditioner of the Newton
 * systems and the flexible CG that uses it, written once against the backend
 * table (glpgp/backend.h, ops amg_*). Design (host/README.md, "Multigrid
 * preconditioner", has the reasoning and the measurements):
 *
 * Near-null space. Along the phase mode dz = i alpha z the Newton matrix A is
 * a Laplacian in alpha (no mass), along the amplitude mode dz = beta z it has
 * the penalty's mass ~ 1/eps^2. Both modes are the complex multiples of the
 * current oscillator: the span of [z, iz] per vertex. The tentative
 * prolongation of an aggregate J maps its 2 coarse unknowns (one complex
 * number u) to  x_i = c_i u  on its members, c_i = z_i / ||z||_J: a scaled
 * rotation per vertex (the block [[cr, -ci], [ci, cr]]), i.e. the vertex's
 * 2x2 block rotated into the frame of z_i; [z, iz] restricted to J is then
 * exactly P times (||z||_J, 0) and (0, ||z||_J). Vertices with z_i = 0
 * (vortex cores) have c_i = 0 (left to the smoother); an aggregate with
 * ||z||_J = 0 is dead (identity coarse row). On level l >= 1 the frame is
 * the aggregate amplitude ||f||_J (a real number), so the coarse near-null
 * vectors stay exactly reproduced on every level. For the quadratic solves
 * (naive PGP, inv4e2 = 0) the near-null space is the local plane wave
 * exp(i w.x), w = 2 pi W / h: those frames are exp(i w_J . (x_i - x_J)) per
 * aggregate (w_J from the mean field of J, x_J its centroid), on every level;
 * for the guiding-field Laplacian they are constant.
 *
 * Structure, once per (mesh, Dirichlet set), on the host: each level
 * aggregates its graph by two passes of pairwise matching (Notay's AGMG
 * idea: the unmatched node with the fewest unmatched neighbours takes its
 * strongest unmatched neighbour; fine edge weights 1, coarse weights the
 * number of fine edges between two aggregates, which keeps aggregates
 * compact): aggregates of about 4 nodes, coarse graph = quotient graph.
 * Dirichlet vertices are on no coarser level (their identity rows are solved
 * exactly by the smoother). Coarsening stops at o->amg_coarse nodes. The
 * coarse patterns and the Galerkin index maps (coarse block <- list of fine
 * blocks, gather form) are built here and uploaded once (amg_setup).
 *
 * Values, per Newton step (glpgp_amg_update), on the device: weights c from
 * the frames, A_{l+1} = P^T A_l P (one pass over A_l's blocks through the
 * map: unsmoothed aggregation), l1-Jacobi smoothers M_i = A_ii +
 * (sum_{j != i} ||A_ij||_2) I weighted by o->amg_weight (1.5): M >= A, so the
 * sweep converges for any SPD A with a weight below 2 and needs no
 * eigenvalue estimate when z changes; the same formula stays usable on the
 * indefinite exact Hessian. The coarsest matrix (2 * amg_coarse unknowns at
 * most) is read back, inverted on the host by LU with complete pivoting
 * (pivots below 1e-12 of the largest are dropped: a generalised inverse,
 * which handles the exact gauge null vector of an oscillator without
 * Dirichlet vertices and the indefinite exact Hessian), and uploaded: the
 * coarse solve is one dense matrix-vector product on the device, no host
 * round trip per cycle.
 *
 * Cycle: on level l, amg_pre sweeps of l1-Jacobi from 0, restriction of the
 * residual, coarse correction, prolongation, amg_post sweeps. The coarse
 * correction on a level that is not the coarsest is a K-cycle (Notay &
 * Vassilevski): two flexible-CG steps on A_{l+1} preconditioned by the cycle
 * on l+1 (o->amg_cycle = VCYCLE, or a level below o->amg_kcycle_min nodes:
 * one plain visit). The coefficients of those steps stay in the backend's
 * scalar registers (amg_kcombine): no host round trip inside a cycle.
 * Unsmoothed aggregation needs the K-cycle: V-cycle counts grow with the
 * number of levels (host/README.md has the counts). The preconditioner is
 * not a fixed linear operator, so the outer iteration is flexible CG
 * (FCG(1)): one extra dot product per iteration compared with CG. */
#include "internal.h"

#include "glpgp/util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- host-side structure ------------------------------------------------ */

/* A weighted graph in CSR form (no self loops). */
typedef struct wgraph {
    int n;
    int *ptr, *adj;
    double *wt;
} wgraph;

static void wgraph_free(wgraph *g)
{
    free(g->ptr);
    free(g->adj);
    free(g->wt);
    memset(g, 0, sizeof *g);
}

typedef struct amg_level {
    int n;
    long nnzb;
    int *rowptr, *col, *diag;  /* levels >= 1 (level 0: the system's) */
    wgraph g;                  /* aggregation graph of this level */
    int *agg, *aptr, *amem;    /* transfer to l+1 */
    int *gptr, *gsrc;
    double *pos, *wsum;        /* 2n: centroid, summed field (plane-wave frames) */
    /* device vectors (2n doubles): K-cycle and smoothing work */
    glpgp_vec *b, *e, *v, *w, *r2, *d, *wd, *tmp;
    glpgp_vec *phase;          /* plane-wave frame of this level (NULL: none) */
} amg_level;

struct glpgp_amg {
    glpgp_backend *b;
    int cycle, pre, post, check, maxit;
    int kmin;                  /* levels below this many nodes: V-cycle */
    int L;
    amg_level lev[GLPGP_AMG_MAX_LEVELS];
    int m;                     /* coarse order 2 n_{L-1} */
    double *dense, *inv, *work;/* m*m each (work: LU) */
    int *perm_r, *perm_c;
    glpgp_vec *r, *z, *p, *q;  /* flexible CG */
    int has_phase;
    int warned;                /* the Jacobi fallback of glpgp_linear_solve was logged */
    glpgp_amg_info info;
};

/* whether the coarse correction on level c (0 < c < L-1) is a K-cycle */
int glpgp_amg_kcycle_min(const glpgp_backend *b, const glpgp_options *o)
{
    if (o->amg_kcycle_min >= 0) return o->amg_kcycle_min;
    return b && b->launch_bound ? GLPGP_AMG_KCYCLE_MIN_LAUNCH_BOUND : 0;
}

static int kcycle_level(const glpgp_amg *a, int c)
{
    return a->cycle == GLPGP_AMG_KCYCLE && a->lev[c].n >= a->kmin;
}

/* Dirichlet-free vertex graph of the system: edges of the block pattern
 * between free vertices, weight 1. */
static glpgp_status fine_graph(const glpgp_system *sys, const unsigned char *dir, wgraph *g)
{
    g->n = sys->nv;
    GLPGP_CHECK(glpgp_malloc((size_t)sys->nv + 1, sizeof(int), &g->ptr));
    GLPGP_CHECK(glpgp_malloc((size_t)(sys->nnzb ? sys->nnzb : 1), sizeof(int), &g->adj));
    GLPGP_CHECK(glpgp_malloc((size_t)(sys->nnzb ? sys->nnzb : 1), sizeof(double), &g->wt));
    long e = 0;
    g->ptr[0] = 0;
    for (int i = 0; i < sys->nv; i++) {
        if (!(dir && dir[i]))
            for (int k = sys->rowptr[i]; k < sys->rowptr[i + 1]; k++) {
                int j = sys->col[k];
                if (j == i || (dir && dir[j])) continue;
                g->adj[e] = j;
                g->wt[e] = 1.0;
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
            if (done[j]) continue;
            if (best < 0 || g->wt[k] > bw || (g->wt[k] == bw && (deg[j] < deg[best] ||
                                                                 (deg[j] == deg[best] && j < best)))) {
                best = j;
                bw = g->wt[k];
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
                c->wt[slot[J]] += g->wt[k];
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

/* Aggregates of level lv (two pairing passes on its graph; Dirichlet /
 * inactive nodes get -1): lv->agg and the returned count. When the level is
 * small enough (n_active <= coarse) every active node is its own aggregate
 * (the next level is then the coarsest and solves the level exactly). */
static glpgp_status aggregate(amg_level *lv, const unsigned char *act, int coarse, int *nc)
{
    glpgp_status st = GLPGP_OK;
    const int n = lv->n;
    int *g1 = NULL, *g2 = NULL;
    unsigned char *act1 = NULL;
    wgraph q;
    memset(&q, 0, sizeof q);
    GLPGP_CHECK(glpgp_malloc((size_t)n + 1, sizeof(int), &lv->agg));
    int nact = 0;
    for (int i = 0; i < n; i++) nact += act[i] != 0;
    if (nact <= coarse) {
        int k = 0;
        for (int i = 0; i < n; i++) lv->agg[i] = act[i] ? k++ : -1;
        *nc = k;
        return GLPGP_OK;
    }
    int n1 = 0, n2 = 0;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n + 1, sizeof(int), &g1), out);
    GLPGP_CHECK_GOTO(st, pair_pass(&lv->g, act, g1, &n1), out);
    GLPGP_CHECK_GOTO(st, quotient(&lv->g, g1, n1, &q), out);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n1 + 1, 1, &act1), out);
    memset(act1, 1, (size_t)n1 + 1);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n1 + 1, sizeof(int), &g2), out);
    GLPGP_CHECK_GOTO(st, pair_pass(&q, act1, g2, &n2), out);
    for (int i = 0; i < n; i++) lv->agg[i] = g1[i] >= 0 ? g2[g1[i]] : -1;
    /* number the aggregates by their first member, so that the coarse levels
     * keep the locality of the fine ordering */
    for (int J = 0; J < n2; J++) g2[J] = -1;
    int next = 0;
    for (int i = 0; i < n; i++) {
        int J = lv->agg[i];
        if (J < 0) continue;
        if (g2[J] < 0) g2[J] = next++;
        lv->agg[i] = g2[J];
    }
    *nc = n2;
out:
    free(g1);
    free(g2);
    free(act1);
    wgraph_free(&q);
    return st;
}

/* Members of each aggregate (aptr/amem, increasing), the next level's
 * pattern (quotient graph + diagonal, sorted) and graph, the Galerkin map
 * from the pattern (rowptr/col) of lv, and the centroids / field sums. */
static glpgp_status build_transfer(amg_level *lv, const int *rowptr, const int *col, int nc,
                                   amg_level *nx)
{
    glpgp_status st = GLPGP_OK;
    int *pos = NULL;
    long *cnt = NULL;
    const int n = lv->n;
    nx->n = nc;
    GLPGP_CHECK(glpgp_calloc((size_t)nc + 1, sizeof(int), &lv->aptr));
    GLPGP_CHECK(glpgp_malloc((size_t)n + 1, sizeof(int), &lv->amem));
    for (int i = 0; i < n; i++)
        if (lv->agg[i] >= 0) lv->aptr[lv->agg[i] + 1]++;
    for (int J = 0; J < nc; J++) lv->aptr[J + 1] += lv->aptr[J];
    {
        int *fill = NULL;
        GLPGP_CHECK(glpgp_malloc((size_t)nc + 1, sizeof(int), &fill));
        memcpy(fill, lv->aptr, (size_t)nc * sizeof(int));
        for (int i = 0; i < n; i++)
            if (lv->agg[i] >= 0) lv->amem[fill[lv->agg[i]]++] = i;
        free(fill);
    }
    /* next level's graph and pattern: quotient + diagonal */
    GLPGP_CHECK(quotient(&lv->g, lv->agg, nc, &nx->g));
    nx->nnzb = (long)nx->g.ptr[nc] + nc;
    GLPGP_CHECK(glpgp_malloc((size_t)nc + 1, sizeof(int), &nx->rowptr));
    GLPGP_CHECK(glpgp_malloc((size_t)nx->nnzb + 1, sizeof(int), &nx->col));
    GLPGP_CHECK(glpgp_malloc((size_t)nc + 1, sizeof(int), &nx->diag));
    {
        long e = 0;
        nx->rowptr[0] = 0;
        for (int I = 0; I < nc; I++) {
            int placed = 0;
            for (int k = nx->g.ptr[I]; k < nx->g.ptr[I + 1]; k++) {
                int J = nx->g.adj[k];
                if (!placed && J > I) {
                    nx->diag[I] = (int)e;
                    nx->col[e++] = I;
                    placed = 1;
                }
                nx->col[e++] = J;
            }
            if (!placed) {
                nx->diag[I] = (int)e;
                nx->col[e++] = I;
            }
            nx->rowptr[I + 1] = (int)e;
        }
    }
    /* Galerkin map: coarse slot K = (I, J) <- level-l slots k = (i, j) with
     * agg(i) = I, agg(j) = J, listed by increasing k */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof(int), &pos), out);
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
                int i = lv->amem[p];
                for (int k = rowptr[i]; k < rowptr[i + 1]; k++) {
                    int J = lv->agg[col[k]];
                    if (J < 0) continue;
                    int K = pos[J];
                    if (K < 0) {
                        st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "multigrid: Galerkin map misses a block");
                        goto out;
                    }
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
    /* centroids and field sums (plane-wave frames) */
    if (lv->pos) {
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * nc + 1, sizeof(double), &nx->pos), out);
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * nc + 1, sizeof(double), &nx->wsum), out);
        for (int J = 0; J < nc; J++) {
            int c = lv->aptr[J + 1] - lv->aptr[J];
            for (int p = lv->aptr[J]; p < lv->aptr[J + 1]; p++) {
                int i = lv->amem[p];
                nx->pos[2 * J] += lv->pos[2 * i] / c;
                nx->pos[2 * J + 1] += lv->pos[2 * i + 1] / c;
                nx->wsum[2 * J] += lv->wsum[2 * i];
                nx->wsum[2 * J + 1] += lv->wsum[2 * i + 1];
            }
        }
    }
out:
    free(pos);
    free(cnt);
    return st;
}

/* Plane-wave frame of level l: node i of aggregate J gets
 * exp(i (2 pi / h) W_J . (x_i - x_J)), W_J the normalised field sum of J,
 * x_J its centroid. */
static void wave_phase(const amg_level *lv, const amg_level *nx, double h, double *ph)
{
    const double k = 2.0 * GLPGP_PI / h;
    for (int i = 0; i < lv->n; i++) {
        int J = lv->agg[i];
        ph[2 * i] = 1.0;
        ph[2 * i + 1] = 0.0;
        if (J < 0) continue;
        double wx = nx->wsum[2 * J], wy = nx->wsum[2 * J + 1], wn = hypot(wx, wy);
        if (!(wn > 0.0)) continue;
        const double dx = lv->pos[2 * i] - nx->pos[2 * J], dy = lv->pos[2 * i + 1] - nx->pos[2 * J + 1];
        const double a = k * (wx * dx + wy * dy) / wn;
        ph[2 * i] = cos(a);
        ph[2 * i + 1] = sin(a);
    }
}

int glpgp_amg_supported(const glpgp_backend *b)
{
    const glpgp_backend_ops *o = b->ops;
    return o->amg_setup && o->amg_values && o->amg_coarse_read && o->amg_coarse_set &&
           o->amg_smooth && o->amg_restrict && o->amg_prolong && o->amg_coarse_solve &&
           o->amg_spmv_dots && o->amg_dots && o->amg_axpby && o->amg_kcombine && o->amg_get_scalars;
}

void glpgp_amg_destroy(glpgp_amg **pa)
{
    if (!pa || !*pa) return;
    glpgp_amg *a = *pa;
    glpgp_backend *b = a->b;
    const glpgp_backend_ops *o = b->ops;
    for (int l = 0; l < GLPGP_AMG_MAX_LEVELS; l++) {
        amg_level *v = &a->lev[l];
        free(v->rowptr);
        free(v->col);
        free(v->diag);
        wgraph_free(&v->g);
        free(v->agg);
        free(v->aptr);
        free(v->amem);
        free(v->gptr);
        free(v->gsrc);
        free(v->pos);
        free(v->wsum);
        glpgp_vec **vs[] = {&v->b, &v->e, &v->v, &v->w, &v->r2, &v->d, &v->wd, &v->tmp, &v->phase};
        for (size_t k = 0; k < sizeof vs / sizeof vs[0]; k++) o->vec_destroy(b, vs[k]);
    }
    o->vec_destroy(b, &a->r);
    o->vec_destroy(b, &a->z);
    o->vec_destroy(b, &a->p);
    o->vec_destroy(b, &a->q);
    free(a->dense);
    free(a->inv);
    free(a->work);
    free(a->perm_r);
    free(a->perm_c);
    free(a);
    *pa = NULL;
}

glpgp_status glpgp_amg_create(glpgp_backend *b, const glpgp_options *o, const unsigned char *dir,
                              const double *w, double h, glpgp_amg **out)
{
    *out = NULL;
    const glpgp_system *sys = b->sys;
    if (!sys) return GLPGP_FAIL(GLPGP_ERR_ARG, "multigrid: backend not set up");
    if (!glpgp_amg_supported(b))
        return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "the %s backend has no multigrid ops", b->ops->name);
    const double t0 = glpgp_now();
    const glpgp_backend_ops *op = b->ops;
    glpgp_status st = GLPGP_OK;
    glpgp_amg *a = NULL;
    unsigned char *act = NULL;
    double *host = NULL;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *a, &a));
    a->b = b;
    a->cycle = o->amg_cycle;
    a->pre = o->amg_pre;
    a->post = o->amg_post;
    a->kmin = glpgp_amg_kcycle_min(b, o);
    a->check = o->amg_check;
    a->maxit = o->amg_maxit < o->cg_max ? o->amg_maxit : o->cg_max;
    a->has_phase = w != NULL && h > 0.0 && sys->mesh->xy != NULL; /* a surface: no plane waves of a global x */

    /* level 0: the system; graph without Dirichlet vertices */
    amg_level *l0 = &a->lev[0];
    l0->n = sys->nv;
    l0->nnzb = sys->nnzb;
    GLPGP_CHECK_GOTO(st, fine_graph(sys, dir, &l0->g), fail);
    if (a->has_phase) {
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * sys->nv, sizeof(double), &l0->pos), fail);
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * sys->nv, sizeof(double), &l0->wsum), fail);
        memcpy(l0->pos, sys->mesh->xy, (size_t)2 * sys->nv * sizeof(double));
        memcpy(l0->wsum, w, (size_t)2 * sys->nv * sizeof(double));
    }
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)sys->nv + 1, 1, &act), fail);
    for (int i = 0; i < sys->nv; i++) act[i] = !(dir && dir[i]);

    /* coarsen: level l -> l+1 until the coarsest is small enough */
    int L = 1;
    for (;;) {
        amg_level *lv = &a->lev[L - 1], *nx = &a->lev[L];
        int nc = 0;
        GLPGP_CHECK_GOTO(st, aggregate(lv, act, o->amg_coarse, &nc), fail);
        const int *rp = L == 1 ? sys->rowptr : lv->rowptr, *cl = L == 1 ? sys->col : lv->col;
        GLPGP_CHECK_GOTO(st, build_transfer(lv, rp, cl, nc, nx), fail);
        L++;
        if (nc == 0) {
            st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "multigrid: no free vertex to coarsen");
            goto fail;
        }
        if (nc <= o->amg_coarse) break;
        if (L == o->amg_max_levels || nc > 0.9 * lv->n) {
            /* coarsening stalled or the level cap: the coarsest level must
             * still be small enough for the dense inverse */
            if (nc > 1024) {
                st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "multigrid: coarsening stopped at %d nodes", nc);
                goto fail;
            }
            break;
        }
        free(act);
        act = NULL;
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, 1, &act), fail);
        memset(act, 1, (size_t)nc + 1);
    }
    a->L = L;

    /* upload the structure */
    glpgp_amg_layout lay;
    memset(&lay, 0, sizeof lay);
    lay.nlevels = L;
    lay.weight = o->amg_weight;
    lay.pre = a->pre;
    lay.post = a->post;
    for (int l = 1; l + 1 < L; l++) lay.kcycle[l] = (unsigned char)kcycle_level(a, l);
    for (int l = 0; l < L; l++) {
        amg_level *lv = &a->lev[l];
        glpgp_amg_level *d = &lay.lev[l];
        d->n = lv->n;
        d->nnzb = lv->nnzb;
        d->rowptr = l ? lv->rowptr : NULL;
        d->col = l ? lv->col : sys->col;
        d->diag = l ? lv->diag : sys->diag;
        if (l + 1 < L) {
            d->agg = lv->agg;
            d->aptr = lv->aptr;
            d->amem = lv->amem;
            d->gptr = lv->gptr;
            d->gsrc = lv->gsrc;
        }
    }
    GLPGP_CHECK_GOTO(st, op->amg_setup(b, &lay), fail);

    /* device work vectors */
    for (int l = 0; l < L; l++) {
        amg_level *lv = &a->lev[l];
        const size_t n2 = (size_t)2 * lv->n;
        if (l + 1 < L) GLPGP_CHECK_GOTO(st, op->vec_create(b, n2, &lv->tmp), fail);
        if (l >= 1) {
            GLPGP_CHECK_GOTO(st, op->vec_create(b, n2, &lv->b), fail);
            GLPGP_CHECK_GOTO(st, op->vec_create(b, n2, &lv->e), fail);
        }
        if (l >= 1 && l + 1 < L && kcycle_level(a, l)) {
            glpgp_vec **vs[] = {&lv->v, &lv->w, &lv->r2, &lv->d, &lv->wd};
            for (size_t k = 0; k < sizeof vs / sizeof vs[0]; k++)
                GLPGP_CHECK_GOTO(st, op->vec_create(b, n2, vs[k]), fail);
        }
    }
    const size_t n0 = (size_t)2 * sys->nv;
    GLPGP_CHECK_GOTO(st, op->vec_create(b, n0, &a->r), fail);
    GLPGP_CHECK_GOTO(st, op->vec_create(b, n0, &a->z), fail);
    GLPGP_CHECK_GOTO(st, op->vec_create(b, n0, &a->p), fail);
    GLPGP_CHECK_GOTO(st, op->vec_create(b, n0, &a->q), fail);

    /* plane-wave frames (quadratic problems) */
    if (a->has_phase) {
        GLPGP_CHECK_GOTO(st, glpgp_malloc(n0, sizeof(double), &host), fail);
        for (int l = 0; l + 1 < L; l++) {
            amg_level *lv = &a->lev[l];
            wave_phase(lv, &a->lev[l + 1], h, host);
            GLPGP_CHECK_GOTO(st, op->vec_create(b, (size_t)2 * lv->n, &lv->phase), fail);
            GLPGP_CHECK_GOTO(st, op->vec_write(b, lv->phase, host), fail);
        }
    }

    /* coarse solve buffers */
    a->m = 2 * a->lev[L - 1].n;
    const size_t mm = (size_t)a->m * a->m;
    GLPGP_CHECK_GOTO(st, glpgp_malloc(mm, sizeof(double), &a->dense), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(mm, sizeof(double), &a->inv), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(mm, sizeof(double), &a->work), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)a->m, sizeof(int), &a->perm_r), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)a->m, sizeof(int), &a->perm_c), fail);

    /* facts */
    glpgp_amg_info *in = &a->info;
    in->nlevels = L;
    double oc = 0.0, gc = 0.0;
    for (int l = 0; l < L; l++) {
        in->n[l] = a->lev[l].n;
        in->nnzb[l] = a->lev[l].nnzb;
        oc += (double)a->lev[l].nnzb;
        gc += a->lev[l].n;
    }
    in->operator_complexity = oc / (double)sys->nnzb;
    in->grid_complexity = gc / sys->nv;
    in->seconds_structure = glpgp_now() - t0;
    free(act);
    free(host);
    *out = a;
    return GLPGP_OK;
fail:
    free(act);
    free(host);
    glpgp_amg_destroy(&a);
    return st;
}

void glpgp_amg_get_info(const glpgp_amg *a, glpgp_amg_info *info) { *info = a->info; }

/* Swap rows (rows = 1) or columns (rows = 0) a and b of the dense row-major
 * m x m matrix M, and entries a and b of the permutation p (may be NULL). */
static void dense_swap(double *M, int m, int a, int b, int rows, int *p)
{
    for (int k = 0; k < m; k++) {
        double *x = rows ? M + (size_t)a * m + k : M + (size_t)k * m + a;
        double *y = rows ? M + (size_t)b * m + k : M + (size_t)k * m + b;
        const double t = *x;
        *x = *y;
        *y = t;
    }
    if (p) {
        const int t = p[a];
        p[a] = p[b];
        p[b] = t;
    }
}

/* inv <- a generalised inverse of the m x m matrix A (row-major) by LU with
 * complete pivoting: P A Q = L U; pivots below 1e-12 |u_11| end the
 * elimination (rank r), the solution components beyond r are set to 0.
 * lu, pr, pc: work (m*m, m, m). Fails on non-finite entries. */
static glpgp_status dense_inverse(int m, const double *A, double *inv, double *lu, int *pr, int *pc)
{
    memcpy(lu, A, (size_t)m * m * sizeof(double));
    for (int i = 0; i < m; i++) {
        pr[i] = i;
        pc[i] = i;
    }
    for (size_t k = 0; k < (size_t)m * m; k++)
        if (!isfinite(lu[k]))
            return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "multigrid: coarsest matrix is not finite");
    int r = 0;
    double piv0 = 0.0;
    for (int k = 0; k < m; k++) {
        /* pivot: the largest |entry| of the remaining block */
        int bi = k, bj = k;
        double bv = -1.0;
        for (int i = k; i < m; i++)
            for (int j = k; j < m; j++) {
                double v = fabs(lu[(size_t)i * m + j]);
                if (v > bv) {
                    bv = v;
                    bi = i;
                    bj = j;
                }
            }
        if (k == 0) piv0 = bv;
        if (!(bv > 1e-12 * piv0) || bv == 0.0) break;
        if (bi != k) dense_swap(lu, m, k, bi, 1, pr);
        if (bj != k) dense_swap(lu, m, k, bj, 0, pc);
        /* eliminate below the pivot: l_ik = a_ik / a_kk;  a_ij -= l_ik a_kj */
        const double pk = lu[(size_t)k * m + k];
        for (int i = k + 1; i < m; i++) {
            double *ri = lu + (size_t)i * m;
            const double *rk = lu + (size_t)k * m;
            double l = ri[k] / pk;
            ri[k] = l;
            if (l != 0.0)
                for (int j = k + 1; j < m; j++) ri[j] -= l * rk[j];
        }
        r = k + 1;
    }
    /* column c of the inverse: solve A x = e_c:  L y = P e_c,  U x' = y
     * (first r components),  x = Q x' */
    double *y = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)m + 1, sizeof(double), &y));
    for (int c = 0; c < m; c++) {
        for (int i = 0; i < m; i++) y[i] = pr[i] == c ? 1.0 : 0.0;
        for (int i = 0; i < r; i++) {
            const double *ri = lu + (size_t)i * m;
            double s = y[i];
            for (int j = 0; j < i; j++) s -= ri[j] * y[j];
            y[i] = s;
        }
        for (int i = r; i < m; i++) y[i] = 0.0;
        for (int i = r - 1; i >= 0; i--) {
            const double *ri = lu + (size_t)i * m;
            double s = y[i];
            for (int j = i + 1; j < r; j++) s -= ri[j] * y[j];
            y[i] = s / ri[i];
        }
        for (int i = 0; i < m; i++) inv[(size_t)pc[i] * m + c] = y[i];
    }
    free(y);
    return GLPGP_OK;
}

/* inv <- a symmetric positive semi-definite generalised inverse of the
 * m x m matrix A (row-major), for the symmetric cycle's coarse solve: with
 * A_s = (A + A^T)/2, symmetric pivoted LDL^T (the largest remaining |d| on
 * the diagonal first: P A_s P^T = L D L^T, stable for the positive
 * semi-definite coarse matrices of the projected Hessian; pivots below
 * 1e-12 of the first end it at rank r), then
 *   inv = P^T [L11^-T |D|^-1 L11^-1, 0; 0, 0] P
 * (the components beyond r set to 0, as dense_inverse does). Symmetric by
 * construction (entry (j, i) is written as entry (i, j)) and positive
 * semi-definite whatever the signs of D; for a nonsingular PSD A it is A^-1.
 * O(m^3) like dense_inverse. S: m*m work (overwritten). Fails on non-finite
 * entries. */
static glpgp_status spd_inverse(int m, const double *A, double *inv, double *S)
{
    int *perm = NULL;
    for (size_t k = 0; k < (size_t)m * m; k++)
        if (!isfinite(A[k])) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "multigrid: coarsest matrix is not finite");
    GLPGP_CHECK(glpgp_malloc((size_t)m + 1, sizeof(int), &perm));
    for (int i = 0; i < m; i++) {
        perm[i] = i;
        for (int j = 0; j < m; j++) S[(size_t)i * m + j] = 0.5 * (A[(size_t)i * m + j] + A[(size_t)j * m + i]);
    }
    /* P A_s P^T = L D L^T: l_ik in S's lower part (i > k), d_k on its diagonal */
    int r = 0;
    double piv0 = 0.0;
    for (int k = 0; k < m; k++) {
        int bj = k;
        for (int j = k + 1; j < m; j++)
            if (fabs(S[(size_t)j * m + j]) > fabs(S[(size_t)bj * m + bj])) bj = j;
        const double bv = fabs(S[(size_t)bj * m + bj]);
        if (k == 0) piv0 = bv;
        if (!(bv > 1e-12 * piv0) || bv == 0.0) break;
        if (bj != k) { /* symmetric swap of rows and columns k, bj */
            dense_swap(S, m, k, bj, 1, NULL);
            dense_swap(S, m, k, bj, 0, perm);
        }
        /* d = s_kk;  l_ik = s_ik / d;  s_ij -= l_ik d l_jk  (i, j > k, lower part) */
        const double d = S[(size_t)k * m + k];
        for (int i = k + 1; i < m; i++) S[(size_t)i * m + k] /= d;
        for (int i = k + 1; i < m; i++) {
            const double lid = S[(size_t)i * m + k] * d;
            if (lid == 0.0) continue;
            for (int j = k + 1; j <= i; j++) S[(size_t)i * m + j] -= lid * S[(size_t)j * m + k];
        }
        /* keep the trailing block symmetric for the next pivot search and swaps */
        for (int i = k + 1; i < m; i++)
            for (int j = k + 1; j < i; j++) S[(size_t)j * m + i] = S[(size_t)i * m + j];
        r = k + 1;
    }
    /* X = L11^-1 (unit lower triangular, r x r) into inv's lower part:
     * column c: x_c = c, x_i = -sum_{c <= j < i} l_ij x_j */
    for (size_t k = 0; k < (size_t)m * m; k++) inv[k] = 0.0;
    for (int c = 0; c < r; c++) {
        inv[(size_t)c * m + c] = 1.0;
        for (int i = c + 1; i < r; i++) {
            double sum = 0.0;
            for (int j = c; j < i; j++) sum += S[(size_t)i * m + j] * inv[(size_t)j * m + c];
            inv[(size_t)i * m + c] = -sum;
        }
    }
    /* C = X^T |D|^-1 X (r x r, symmetric):  C_ij = sum_{k >= max(i,j)} x_ki x_kj / |d_k|;
     * built in S's upper part (i <= j; S's strict lower part, L, is no longer
     * needed after X), then scattered to inv through the permutation */
    double *dinv = NULL;
    glpgp_status st = glpgp_malloc((size_t)m + 1, sizeof(double), &dinv);
    if (st != GLPGP_OK) {
        free(perm);
        return st;
    }
    for (int k = 0; k < r; k++) dinv[k] = 1.0 / fabs(S[(size_t)k * m + k]);
    for (int i = 0; i < r; i++)
        for (int j = i; j < r; j++) {
            double sum = 0.0;
            for (int k = j; k < r; k++) sum += inv[(size_t)k * m + i] * inv[(size_t)k * m + j] * dinv[k];
            S[(size_t)i * m + j] = sum;
        }
    for (size_t k = 0; k < (size_t)m * m; k++) inv[k] = 0.0;
    for (int i = 0; i < r; i++)
        for (int j = i; j < r; j++) {
            const double v = S[(size_t)i * m + j];
            inv[(size_t)perm[i] * m + perm[j]] = v;
            inv[(size_t)perm[j] * m + perm[i]] = v;
        }
    free(dinv);
    free(perm);
    return GLPGP_OK;
}

/* glpgp_amg_update (spd = 0) and glpgp_amg_update_spd (spd = 1: the coarse
 * operator is symmetric PSD, see spd_inverse) */
static glpgp_status update(glpgp_amg *a, const glpgp_vec *x, int spd)
{
    glpgp_backend *b = a->b;
    const glpgp_backend_ops *op = b->ops;
    const double t0 = glpgp_now();
    const glpgp_vec *frames[GLPGP_AMG_MAX_LEVELS];
    for (int l = 0; l < GLPGP_AMG_MAX_LEVELS; l++) frames[l] = NULL;
    /* GL: frame = the oscillator on level 0, amplitudes below; quadratic
     * problems: the plane-wave phases on every level (or constants) */
    if (x)
        frames[0] = x;
    else if (a->has_phase)
        for (int l = 0; l + 1 < a->L; l++) frames[l] = a->lev[l].phase;
    GLPGP_CHECK(op->amg_values(b, frames));
    const double t1 = glpgp_now();
    GLPGP_CHECK(op->amg_coarse_read(b, a->dense));
    b->n_sync++;
    if (spd)
        GLPGP_CHECK(spd_inverse(a->m, a->dense, a->inv, a->work));
    else
        GLPGP_CHECK(dense_inverse(a->m, a->dense, a->inv, a->work, a->perm_r, a->perm_c));
    GLPGP_CHECK(op->amg_coarse_set(b, a->inv));
    const double t2 = glpgp_now();
    a->info.seconds_values += t2 - t0;
    a->info.seconds_coarse += t2 - t1;
    a->info.updates++;
    return GLPGP_OK;
}

glpgp_status glpgp_amg_update(glpgp_amg *a, const glpgp_vec *x) { return update(a, x, 0); }

glpgp_status glpgp_amg_update_spd(glpgp_amg *a, const glpgp_vec *x) { return update(a, x, 1); }

/* ---- the cycle ---------------------------------------------------------- */

static const glpgp_amg_coef ONE = {-1, -1, 1.0}, ZERO = {-1, -1, 0.0};

static glpgp_amg_coef ratio(int num, int den, double sign)
{
    glpgp_amg_coef c = {num, den, sign};
    return c;
}

static glpgp_status cycle(glpgp_amg *a, int l, const glpgp_vec *r, glpgp_vec *out, int sym);


/* e[c] <- approximate solution of A_c e = b[c]; sym: the symmetric cycle
 * of glpgp_amg_apply_spd (a W-visit where the layout has a K-cycle, a plain
 * visit elsewhere; never the backend's fused coarse correction unless the
 * layout is itself a symmetric V-cycle) */
static glpgp_status coarse_correction(glpgp_amg *a, int c, int sym)
{
    glpgp_backend *b = a->b;
    const glpgp_backend_ops *op = b->ops;
    amg_level *lv = &a->lev[c];
    if (op->amg_coarse_correction) {
        /* the backend may run this level and all below itself (same sequence) */
        int done = 0;
        GLPGP_CHECK(op->amg_coarse_correction(b, c, sym, lv->b, lv->e, &done));
        if (done) return GLPGP_OK;
    }
    if (c == a->L - 1) return op->amg_coarse_solve(b, lv->b, lv->e);
    if (sym && kcycle_level(a, c)) {
        /* symmetric cycle on a K-cycle level: a W-visit, two stationary
         * steps of the cycle on c (fixed and symmetric, unlike the K-cycle's
         * Krylov steps; positive definite when B_c A_c < 2, which holds on
         * the positive semi-definite hierarchy of glpgp_amg_update_spd):
         *   e = B b;  r2 = b - A e;  d = B r2;  e <- e + d   (e = (2B - BAB) b) */
        const int S = GLPGP_AMG_KSLOT(c);
        const glpgp_amg_coef MINUS = {-1, -1, -1.0};
        GLPGP_CHECK(cycle(a, c, lv->b, lv->e, 1));
        GLPGP_CHECK(op->amg_spmv_dots(b, c, lv->e, lv->w, NULL, NULL, S));
        GLPGP_CHECK(op->amg_axpby(b, ONE, lv->b, ZERO, lv->r2));
        GLPGP_CHECK(op->amg_axpby(b, MINUS, lv->w, ONE, lv->r2));
        GLPGP_CHECK(cycle(a, c, lv->r2, lv->d, 1));
        return op->amg_axpby(b, ONE, lv->d, ONE, lv->e);
    }
    if (sym || !kcycle_level(a, c)) return cycle(a, c, lv->b, lv->e, sym);
    /* K-cycle: two flexible-CG steps on A_c, preconditioned by the cycle on c
     *   v = B b;  w = A v;  rho1 = v.w;  alpha1 = v.b;  r2 = b - (alpha1/rho1) w
     *   d = B r2; wd = A d; beta = d.wd; gamma = d.w;   alpha2 = d.r2
     *   e = combination of v and d (amg_kcombine) */
    const int S = GLPGP_AMG_KSLOT(c);
    GLPGP_CHECK(cycle(a, c, lv->b, lv->v, 0));
    GLPGP_CHECK(op->amg_spmv_dots(b, c, lv->v, lv->w, lv->b, NULL, S));
    GLPGP_CHECK(op->amg_axpby(b, ONE, lv->b, ZERO, lv->r2));
    GLPGP_CHECK(op->amg_axpby(b, ratio(S + 1, S, -1.0), lv->w, ONE, lv->r2));
    GLPGP_CHECK(cycle(a, c, lv->r2, lv->d, 0));
    GLPGP_CHECK(op->amg_spmv_dots(b, c, lv->d, lv->wd, lv->w, lv->r2, S + 2));
    return op->amg_kcombine(b, lv->v, lv->d, lv->e, S);
}

/* out <- B_l r on level l < L-1: `pre` sweeps of l1-Jacobi from 0 (none:
 * x = 0), coarse correction, `post` sweeps. The iterate alternates between
 * tmp and out, starting so that the last write lands in out.
 * sym: max(pre, post) sweeps before and after, W- or plain visits below
 * (the symmetric cycle of glpgp_amg_apply_spd). */
static glpgp_status cycle(glpgp_amg *a, int l, const glpgp_vec *r, glpgp_vec *out, int sym)
{
    glpgp_backend *b = a->b;
    const glpgp_backend_ops *op = b->ops;
    amg_level *lv = &a->lev[l];
    glpgp_vec *buf[2] = {lv->tmp, out};
    const int nu = a->pre > a->post ? a->pre : a->post;
    const int pre = sym ? nu : a->pre, post = sym ? nu : a->post;
    const int writes = (pre > 0 ? pre : 1) + post;
    int k = writes % 2; /* buf[k] receives the first write */
    glpgp_vec *cur = buf[k];
    if (pre > 0) {
        /* x <- M^-1 r, then x <- x + M^-1 (r - A x) */
        GLPGP_CHECK(op->amg_smooth(b, l, r, NULL, cur));
        for (int s = 1; s < pre; s++) {
            k ^= 1;
            GLPGP_CHECK(op->amg_smooth(b, l, r, cur, buf[k]));
            cur = buf[k];
        }
        /* b_{l+1} <- P^T (r - A x) */
        GLPGP_CHECK(op->amg_restrict(b, l, r, cur, a->lev[l + 1].b));
    } else {
        /* x <- 0;  b_{l+1} <- P^T r */
        GLPGP_CHECK(op->amg_axpby(b, ZERO, cur, ZERO, cur));
        GLPGP_CHECK(op->amg_restrict(b, l, r, NULL, a->lev[l + 1].b));
    }
    /* e_{l+1} ~ A_{l+1}^-1 b_{l+1};  x <- x + P e */
    GLPGP_CHECK(coarse_correction(a, l + 1, sym));
    GLPGP_CHECK(op->amg_prolong(b, l, a->lev[l + 1].e, cur));
    for (int s = 0; s < post; s++) {
        k ^= 1;
        GLPGP_CHECK(op->amg_smooth(b, l, r, cur, buf[k]));
        cur = buf[k];
    }
    return GLPGP_OK;
}

glpgp_status glpgp_amg_apply(glpgp_amg *a, const glpgp_vec *r, glpgp_vec *z)
{
    return cycle(a, 0, r, z, 0);
}

glpgp_status glpgp_amg_apply_spd(glpgp_amg *a, const glpgp_vec *r, glpgp_vec *z)
{
    return cycle(a, 0, r, z, 1);
}

/* ---- flexible CG -------------------------------------------------------- */

enum { T_ZQ = 0, T_PQ = 2, T_PR = 3, T_RR = 4, T_N = 8 };

/* FCG(1) on NEWTON; *nonfinite <- 1 when it stopped on a non-finite value */
static glpgp_status fcg_run(glpgp_amg *a, const glpgp_vec *rhs, glpgp_vec *x, double rtol, int maxit,
                            glpgp_cg_info *info, int *nonfinite)
{
    glpgp_backend *b = a->b;
    const glpgp_backend_ops *op = b->ops;
    glpgp_vec *r = a->r, *z = a->z, *p = a->p, *q = a->q;
    double t[T_N];
    int k = 0;
    *nonfinite = 0;
    info->iterations = 0;
    info->relres = 0.0;
    info->reason = GLPGP_CG_CONVERGED;
    if (maxit > a->maxit) maxit = a->maxit;
    /* x <- 0;  r <- b */
    GLPGP_CHECK(op->amg_axpby(b, ZERO, x, ZERO, x));
    GLPGP_CHECK(op->copy(b, r, rhs));
    GLPGP_CHECK(op->amg_dots(b, r, r, NULL, T_RR));
    GLPGP_CHECK(op->amg_get_scalars(b, t, T_N));
    b->n_sync++;
    const double bnorm = sqrt(t[T_RR]);
    if (!isfinite(bnorm)) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "CG right-hand side is not finite");
    if (bnorm == 0.0) return GLPGP_OK;
    double rel = 1.0;
    for (k = 1; k <= maxit; k++) {
        /* z <- B r;  p <- z - (z.q / p.q) p  (q = A p of the previous step) */
        GLPGP_CHECK(cycle(a, 0, r, z, 0));
        if (k == 1) {
            GLPGP_CHECK(op->amg_axpby(b, ONE, z, ZERO, p));
        } else {
            GLPGP_CHECK(op->amg_dots(b, z, q, NULL, T_ZQ));
            GLPGP_CHECK(op->amg_axpby(b, ONE, z, ratio(T_ZQ, T_PQ, -1.0), p));
        }
        /* q <- A p;  alpha = p.r / p.q;  x += alpha p;  r -= alpha q */
        GLPGP_CHECK(op->amg_spmv_dots(b, 0, p, q, r, NULL, T_PQ));
        GLPGP_CHECK(op->amg_axpby(b, ratio(T_PR, T_PQ, 1.0), p, ONE, x));
        GLPGP_CHECK(op->amg_axpby(b, ratio(T_PR, T_PQ, -1.0), q, ONE, r));
        GLPGP_CHECK(op->amg_dots(b, r, r, NULL, T_RR));
        b->n_spmv++;
        b->n_cg_iter++;
        if (k % a->check == 0 || k == maxit) {
            GLPGP_CHECK(op->amg_get_scalars(b, t, T_N));
            b->n_sync++;
            if (!isfinite(t[T_RR]) || !isfinite(t[T_PQ])) {
                *nonfinite = 1;
                info->reason = GLPGP_CG_BREAKDOWN;
                break;
            }
            if (!(t[T_PQ] > 0.0)) {
                info->reason = GLPGP_CG_BREAKDOWN;
                break;
            }
            rel = sqrt(t[T_RR]) / bnorm;
            if (rel <= rtol) break;
        }
    }
    if (k > maxit) {
        k = maxit;
        info->reason = GLPGP_CG_MAXIT;
    } else if (k == maxit && info->reason == GLPGP_CG_CONVERGED && !(rel <= rtol)) {
        info->reason = GLPGP_CG_MAXIT;
    }
    info->relres = rel;
    info->iterations = k;
    return GLPGP_OK;
}

glpgp_status glpgp_fcg(glpgp_amg *a, const glpgp_vec *rhs, glpgp_vec *x, double rtol, int maxit,
                       glpgp_cg_info *info)
{
    int nonfinite;
    return fcg_run(a, rhs, x, rtol, maxit, info, &nonfinite);
}

glpgp_status glpgp_linear_solve(glpgp_backend *b, glpgp_amg *a, const glpgp_vec *rhs,
                                glpgp_vec *x, double rtol, int maxit, int check,
                                glpgp_cg_info *info)
{
    if (b->ops->linear_solve) {
        /* the backend's own solver (PETSc: KSP); the reason values are glpgp_cg_reason's */
        int it = 0, reason = 0;
        double relres = 0.0;
        GLPGP_CHECK(b->ops->linear_solve(b, rhs, x, rtol, maxit, &it, &relres, &reason));
        info->iterations = it;
        info->relres = relres;
        info->reason = reason == 0 ? GLPGP_CG_CONVERGED : reason == 1 ? GLPGP_CG_MAXIT : GLPGP_CG_BREAKDOWN;
        b->n_cg_iter += it;
        b->n_spmv += it;
        return GLPGP_OK;
    }
    if (!a) return glpgp_cg(b, rhs, x, rtol, maxit, check, info);
    int nonfinite = 0;
    GLPGP_CHECK(fcg_run(a, rhs, x, rtol, maxit, info, &nonfinite));
    if (!nonfinite) return GLPGP_OK;
    /* the preconditioner produced a non-finite value (p.Ap <= 0 is a
     * property of the matrix and is reported as is): redo with Jacobi */
    if (!a->warned)
        glpgp_log(GLPGP_LOG_WARNING, "multigrid preconditioner produced a non-finite value; "
                                     "using Jacobi-PCG for this system");
    a->warned = 1;
    const int it = info->iterations;
    GLPGP_CHECK(glpgp_cg(b, rhs, x, rtol, maxit, check, info));
    info->iterations += it;
    return GLPGP_OK;
}

static int glpgp_amg_try_update_mode(glpgp_amg *a, const glpgp_vec *x, int spd, const char *what);

glpgp_amg *glpgp_amg_try_create(glpgp_backend *b, const glpgp_options *o, const unsigned char *dir,
                                const double *w, double h, const char *what)
{
    glpgp_amg *a = NULL;
    if (o->precond != GLPGP_PRECOND_AMG) return NULL;
    if (b->ops->linear_solve) return NULL; /* the backend's own solver preconditions */
    if (glpgp_amg_create(b, o, dir, w, h, &a) != GLPGP_OK) {
        glpgp_log(GLPGP_LOG_WARNING, "%s: multigrid setup failed (%s); using Jacobi-PCG", what,
                  glpgp_error_message());
        glpgp_error_clear();
        return NULL;
    }
    const glpgp_amg_info *in = &a->info;
    char kc[64] = "";
    if (a->cycle == GLPGP_AMG_KCYCLE && a->kmin > 0)
        snprintf(kc, sizeof kc, ", K-cycle on levels of >= %d nodes", a->kmin);
    glpgp_log(GLPGP_LOG_DEBUG,
              "%s: multigrid %d levels, %d -> %d nodes, operator complexity %.3f, structure %.3f s%s",
              what, in->nlevels, in->n[0], in->n[in->nlevels - 1], in->operator_complexity,
              in->seconds_structure, kc);
    return a;
}

int glpgp_amg_try_update(glpgp_amg *a, const glpgp_vec *x, const char *what)
{
    return glpgp_amg_try_update_mode(a, x, 0, what);
}

int glpgp_amg_try_update_spd(glpgp_amg *a, const glpgp_vec *x, const char *what)
{
    return glpgp_amg_try_update_mode(a, x, 1, what);
}

static int glpgp_amg_try_update_mode(glpgp_amg *a, const glpgp_vec *x, int spd, const char *what)
{
    if (update(a, x, spd) == GLPGP_OK) return 1;
    glpgp_log(GLPGP_LOG_WARNING, "%s: multigrid setup failed (%s); using Jacobi-PCG", what,
              glpgp_error_message());
    glpgp_error_clear();
    return 0;
}
