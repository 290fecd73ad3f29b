/* backends/petsc_gc.c: the global coarse space of the PETSc backend's
 * multigrid with more than one rank (see petsc_gc.h): which level's
 * aggregates span it, Z's entries (the composed prolongation, exchanged to
 * the ghosts), E = Z^T A Z gathered on every rank and its generalised
 * inverse, and the correction's restriction / solve / prolongation.
 *
 * Why (bench/results/petsc_glpgp_amg.md): with block Jacobi below the fine
 * level, the error components smooth across a rank boundary are left to
 * the outer CG. One node per rank (the first version) catches only the
 * constant-frame mode of each part: 21-28 CG per Newton step on two ranks
 * against 6 on one. With nodes of diameter H inside each part, additive
 * Schwarz theory bounds the condition number by about H / h instead of
 * (part diameter) / h.
 *
 * Costs: per Newton step one ghost exchange of Z, one pass over the owned
 * rows and an all-gather of E (4 M^2 doubles in all), E's dense inverse
 * (order 2M) on every rank; per cycle an all-gather of 2M doubles, a dense
 * product of this rank's 2 ms rows and, with one level's aggregates, two
 * more fine-level passes with their ghost exchanges (A Z y, A w). On two
 * ranks of 2 cores that costs more than the iterations it saves at 1M, so
 * the default stays one node per rank, added (the first version). */
#include "amg_dense.h"
#include "amg_rows.h"

#include "petsc_gc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* xf[1] <- own (2 doubles per owned vertex) at the owned and ghost vertices */
glpgp_status glpgp_petsc_gc_exchange(pimpl *p, pm_gc *g, const double *own)
{
    PetscScalar *a;
    PCHK(VecGetArray(g->zv, &a));
    memcpy(a, own, (size_t)2 * (p->hi - p->lo) * sizeof(double));
    PCHK(VecRestoreArray(g->zv, &a));
    glpgp_vec w = {g->zv, 0};
    return glpgp_petsc_load_ghosted(p, &w, 1);
}

/* the node of level k that owned vertex i belongs to (-1: none) */
static int node_at(const int *const *agg, int k, int i)
{
    int J = agg[0][i];
    for (int l = 1; l < k && J >= 0; l++) J = agg[l][J];
    return J;
}

/* the level of Z's columns: the finest whose live nodes over all ranks are
 * at most the bound (0: none) */
static glpgp_status choose_level(pimpl *p, int L, const int *const *agg, const int *n, int *k)
{
    double cnt[GLPGP_AMG_MAX_LEVELS] = {0};
    unsigned char *mark = NULL;
    for (int l = 1; l < L; l++) {
        GLPGP_CHECK(glpgp_calloc((size_t)(n[l] > 0 ? n[l] : 1), 1, &mark));
        for (int i = p->lo; i < p->hi; i++) {
            const int J = node_at(agg, l, i);
            if (J >= 0 && !mark[J]) {
                mark[J] = 1;
                cnt[l] += 1.0;
            }
        }
        free(mark);
        mark = NULL;
    }
    GLPGP_CHECK(glpgp_petsc_reduce_sum(p, cnt, GLPGP_AMG_MAX_LEVELS));
    /* the default: one node per rank (on 2 cores the aggregates' space cost
     * more time than it saved: bench/results/petsc_glpgp_amg.md); E's dense
     * inverse is of order 2N, on every rank, per Newton step */
    PetscInt bound = 0;
    PetscBool set = PETSC_FALSE;
    PCHK(PetscOptionsGetInt(NULL, NULL, "-glpgp_mg_global", &bound, &set));
    if (bound < 0) bound = 0; /* refused at the backend's creation (petsc.c) */
    /* a level every rank's hierarchy has (the parts' hierarchies may differ in depth) */
    int lmin = L;
    if (MPI_Allreduce(MPI_IN_PLACE, &lmin, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD) != MPI_SUCCESS)
        return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "MPI_Allreduce failed");
    *k = 0;
    for (int l = 1; l < lmin && !*k; l++)
        if (cnt[l] <= (double)bound) *k = l;
    return GLPGP_OK;
}

/* node[] and ms: this rank's live nodes of level k numbered in increasing order */
static glpgp_status number_nodes(pimpl *p, pm_gc *g, const int *const *agg, const int *n)
{
    const int nown = p->hi - p->lo;
    if (g->k == 0) { /* one node per rank */
        g->ms = 1;
        for (int i = 0; i < nown; i++) g->node[i] = 0;
        return GLPGP_OK;
    }
    int *loc = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)(n[g->k] > 0 ? n[g->k] : 1), sizeof(int), &loc));
    for (int J = 0; J < n[g->k]; J++) loc[J] = -1;
    for (int i = p->lo; i < p->hi; i++) {
        const int J = node_at(agg, g->k, i);
        if (J >= 0) loc[J] = 0;
    }
    g->ms = 0;
    for (int J = 0; J < n[g->k]; J++)
        if (loc[J] == 0) loc[J] = g->ms++;
    for (int i = p->lo; i < p->hi; i++) {
        const int J = node_at(agg, g->k, i);
        g->node[i - p->lo] = J >= 0 ? loc[J] : -1;
    }
    free(loc);
    return GLPGP_OK;
}

/* M, moff and the all-gather layouts from every rank's ms */
static glpgp_status layouts(pimpl *p, pm_gc *g)
{
    const int P = g->P;
    GLPGP_CHECK(glpgp_malloc((size_t)P, sizeof(int), &g->ecnt));
    GLPGP_CHECK(glpgp_malloc((size_t)P, sizeof(int), &g->edsp));
    GLPGP_CHECK(glpgp_malloc((size_t)P, sizeof(int), &g->ycnt));
    GLPGP_CHECK(glpgp_malloc((size_t)P, sizeof(int), &g->ydsp));
    if (MPI_Allgather(&g->ms, 1, MPI_INT, g->ycnt, 1, MPI_INT, PETSC_COMM_WORLD) != MPI_SUCCESS)
        return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "MPI_Allgather failed");
    g->M = 0;
    for (int s = 0; s < P; s++) {
        if (s == p->rank) g->moff = g->M;
        g->M += g->ycnt[s];
    }
    const int M = g->M;
    for (int s = 0, off = 0; s < P; s++) {
        const int ms = g->ycnt[s];
        g->ycnt[s] = 2 * ms;
        g->ydsp[s] = 2 * off;
        g->ecnt[s] = 4 * ms * M;
        g->edsp[s] = 4 * off * M;
        off += ms;
    }
    return GLPGP_OK;
}

/* gidx: the global node of every owned and ghost vertex (one exchange) */
static glpgp_status global_nodes(pimpl *p, pm_gc *g)
{
    const int nown = p->hi - p->lo, nv = p->sys->nv;
    double *own = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)2 * (nown > 0 ? nown : 1), sizeof(double), &own));
    for (int i = 0; i < nown; i++) own[2 * i] = g->node[i] >= 0 ? (double)(g->moff + g->node[i]) : -1.0;
    const glpgp_status st = glpgp_petsc_gc_exchange(p, g, own);
    free(own);
    GLPGP_CHECK(st);
    for (int j = 0; j < nv; j++) g->gidx[j] = -1;
    for (int i = p->lo; i < p->hi; i++) g->gidx[i] = (int)p->xf[1][2 * i];
    for (int q = 0; q < p->nghost; q++) g->gidx[p->ghost[q]] = (int)p->xf[1][2 * p->ghost[q]];
    return GLPGP_OK;
}

static glpgp_status alloc_dense(pm_gc *g)
{
    const int M = g->M, m = 2 * M;
    GLPGP_CHECK(glpgp_calloc((size_t)4 * (g->ms > 0 ? g->ms : 1) * M, sizeof(double), &g->eloc));
    GLPGP_CHECK(glpgp_calloc((size_t)m * m, sizeof(double), &g->e));
    GLPGP_CHECK(glpgp_malloc((size_t)M + 1, sizeof(int), &g->erp));
    GLPGP_CHECK(glpgp_malloc((size_t)M * M, sizeof(int), &g->ecol));
    GLPGP_CHECK(glpgp_calloc((size_t)4 * M * M, sizeof(double), &g->eval));
    GLPGP_CHECK(glpgp_calloc((size_t)m * m, sizeof(double), &g->einv));
    GLPGP_CHECK(glpgp_malloc((size_t)GLPGP_DENSE_W(m), sizeof(double), &g->ew));
    GLPGP_CHECK(glpgp_malloc((size_t)GLPGP_DENSE_I(m) + 1, sizeof(int), &g->ei));
    GLPGP_CHECK(glpgp_calloc((size_t)2 * (g->ms > 0 ? g->ms : 1), sizeof(double), &g->yl));
    GLPGP_CHECK(glpgp_calloc((size_t)2 * (g->ms > 0 ? g->ms : 1), sizeof(double), &g->ysave));
    GLPGP_CHECK(glpgp_calloc((size_t)m, sizeof(double), &g->g));
    for (int q = 0; q <= M; q++) g->erp[q] = q * M;
    for (long k = 0; k < (long)M * M; k++) g->ecol[k] = (int)(k % M);
    return GLPGP_OK;
}

static glpgp_status create_run(pimpl *p, int L, const int *const *agg, const int *n, pm_gc *g)
{
    const int nown = p->hi - p->lo;
    g->P = p->size;
    GLPGP_CHECK(choose_level(p, L, agg, n, &g->k));
    GLPGP_CHECK(glpgp_malloc((size_t)(nown > 0 ? nown : 1), sizeof(int), &g->node));
    GLPGP_CHECK(glpgp_malloc((size_t)p->sys->nv, sizeof(int), &g->gidx));
    GLPGP_CHECK(glpgp_calloc((size_t)2 * (nown > 0 ? nown : 1), sizeof(double), &g->zeta));
    if (g->k > 0) { /* the fine residual and A w of the symmetric form */
        GLPGP_CHECK(glpgp_calloc((size_t)2 * (nown > 0 ? nown : 1), sizeof(double), &g->tbuf));
        GLPGP_CHECK(glpgp_calloc((size_t)2 * (nown > 0 ? nown : 1), sizeof(double), &g->tbuf2));
    }
    GLPGP_CHECK(number_nodes(p, g, agg, n));
    GLPGP_CHECK(layouts(p, g));
    PCHK(VecCreateMPI(PETSC_COMM_WORLD, (PetscInt)2 * nown, PETSC_DETERMINE, &g->zv));
    PCHK(VecSetBlockSize(g->zv, 2));
    GLPGP_CHECK(global_nodes(p, g));
    GLPGP_CHECK(alloc_dense(g));
    if (p->rank == 0)
        glpgp_log(GLPGP_LOG_DEBUG, "petsc multigrid: global coarse space of %d nodes (%s)", g->M,
                  g->k ? "aggregates of one level" : "one per rank");
    return GLPGP_OK;
}

glpgp_status glpgp_petsc_gc_create(pimpl *p, int L, const int *const *agg, const int *n, pm_gc **out)
{
    *out = NULL;
    pm_gc *g = NULL;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *g, &g));
    const glpgp_status st = create_run(p, L, agg, n, g);
    if (st != GLPGP_OK) {
        glpgp_petsc_gc_destroy(&g);
        return st;
    }
    *out = g;
    return GLPGP_OK;
}

void glpgp_petsc_gc_destroy(pm_gc **gp)
{
    if (!gp || !*gp) return;
    pm_gc *g = *gp;
    free(g->node);
    free(g->gidx);
    free(g->zeta);
    free(g->tbuf);
    free(g->tbuf2);
    free(g->ecnt);
    free(g->edsp);
    free(g->ycnt);
    free(g->ydsp);
    free(g->eloc);
    free(g->e);
    free(g->erp);
    free(g->ecol);
    free(g->eval);
    free(g->einv);
    free(g->ew);
    free(g->ei);
    free(g->yl);
    free(g->ysave);
    free(g->g);
    if (g->zv) VecDestroy(&g->zv);
    free(g);
    *gp = NULL;
}

/* zeta of the owned vertices: the frame (k = 0) or the composed
 * prolongation weights c_0(i) c_1(J_1) ... c_{k-1}(J_{k-1}) */
static glpgp_status owned_zeta(pimpl *p, pm_gc *g, const int *const *agg, const double *const *c,
                               const glpgp_vec *frame)
{
    const PetscScalar *fa = NULL;
    if (g->k == 0 && frame) PCHK(VecGetArrayRead(frame->v, &fa));
    const double *fr = fa ? fa - 2 * (long)p->lo : NULL;
    for (int i = p->lo; i < p->hi; i++) {
        double zr = 0.0, zi = 0.0;
        if (g->k == 0) {
            glpgp_amg_frame(i, 0, NULL, fr != NULL, fr, 1, p->dir, &zr, &zi);
        } else if (agg[0][i] >= 0) {
            zr = c[0][2 * i];
            zi = c[0][2 * i + 1];
            for (int l = 1, J = agg[0][i]; l < g->k; J = agg[l][J], l++) {
                const double cr = c[l][2 * J], ci = c[l][2 * J + 1], t = zr * cr - zi * ci;
                zi = zr * ci + zi * cr;
                zr = t;
            }
        }
        g->zeta[2 * (i - p->lo)] = zr;
        g->zeta[2 * (i - p->lo) + 1] = zi;
    }
    if (fa) PCHK(VecRestoreArrayRead(frame->v, &fa));
    return GLPGP_OK;
}

/* this rank's rows of E: sum over the owned rows i and their columns j of
 * Z_i^T A_ij Z_j (Z_j from the exchange in xf[1]) */
static void local_rows(pimpl *p, pm_gc *g)
{
    const glpgp_system *sys = p->sys;
    const int M2 = 2 * g->M;
    const double *N = NEWT(p), *zx = p->xf[1];
    memset(g->eloc, 0, (size_t)4 * g->ms * g->M * sizeof(double));
    for (int i = p->lo; i < p->hi; i++) {
        const int nd = g->node[i - p->lo];
        const double zr = g->zeta[2 * (i - p->lo)], zi = g->zeta[2 * (i - p->lo) + 1];
        if (nd < 0 || (zr == 0.0 && zi == 0.0)) continue;
        double *r0 = g->eloc + (long)(2 * nd) * M2, *r1 = r0 + M2;
        for (int k = sys->rowptr[i]; k < sys->rowptr[i + 1]; k++) {
            const int j = sys->col[k], o = g->gidx[j];
            if (o < 0) continue;
            const double fx = zx[2 * j], fy = zx[2 * j + 1];
            const double *b = N + 4 * (long)k;
            /* A z_j and A (i z_j) */
            const double u0 = b[0] * fx + b[1] * fy, u1 = b[2] * fx + b[3] * fy;
            const double w0 = -b[0] * fy + b[1] * fx, w1 = -b[2] * fy + b[3] * fx;
            r0[2 * o] += zr * u0 + zi * u1;
            r0[2 * o + 1] += zr * w0 + zi * w1;
            r1[2 * o] += -zi * u0 + zr * u1;
            r1[2 * o + 1] += -zi * w0 + zr * w1;
        }
    }
}

glpgp_status glpgp_petsc_gc_values(pimpl *p, pm_gc *g, const int *const *agg, const double *const *c,
                                   const glpgp_vec *frame)
{
    const int M = g->M, m = 2 * M;
    GLPGP_CHECK(owned_zeta(p, g, agg, c, frame));
    GLPGP_CHECK(glpgp_petsc_gc_exchange(p, g, g->zeta));
    local_rows(p, g);
    if (MPI_Allgatherv(g->eloc, g->ecnt[p->rank], MPI_DOUBLE, g->e, g->ecnt, g->edsp, MPI_DOUBLE,
                       PETSC_COMM_WORLD) != MPI_SUCCESS)
        return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "MPI_Allgatherv failed");
    /* the dense block CSR, E symmetrised (the two triangles were summed on
     * different ranks); a node with no weight gets the identity block */
    for (int q = 0; q < M; q++)
        for (int J = 0; J < M; J++) {
            double *blk = g->eval + 4 * ((long)q * M + J);
            for (int u = 0; u < 2; u++)
                for (int v = 0; v < 2; v++) {
                    const long r = 2 * q + u, cc = 2 * J + v;
                    blk[2 * u + v] = 0.5 * (g->e[r * m + cc] + g->e[cc * m + r]);
                }
        }
    for (int q = 0; q < M; q++) {
        double *blk = g->eval + 4 * ((long)q * M + q);
        if (blk[0] == 0.0 && blk[1] == 0.0 && blk[2] == 0.0 && blk[3] == 0.0) blk[0] = blk[3] = 1.0;
    }
    return GLPGP_OK;
}

int glpgp_petsc_gc_invert(pm_gc *g, int spd)
{
    return glpgp_dense_coarse_invert(0, 1, g->M, g->erp, g->ecol, g->eval, spd, g->einv, g->ew, g->ei, NULL, NULL);
}

glpgp_status glpgp_petsc_gc_solve(pm_gc *g)
{
    const int m = 2 * g->M;
    int rank = 0;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    if (MPI_Allgatherv(g->yl, g->ycnt[rank], MPI_DOUBLE, g->g, g->ycnt, g->ydsp, MPI_DOUBLE, PETSC_COMM_WORLD) !=
        MPI_SUCCESS)
        return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "MPI_Allgatherv failed");
    for (int r = 0; r < 2 * g->ms; r++) {
        const double *row = g->einv + (long)(2 * g->moff + r) * m;
        double s = 0.0;
        for (int j = 0; j < m; j++) s += row[j] * g->g[j];
        g->yl[r] = s;
    }
    return GLPGP_OK;
}

void glpgp_petsc_gc_prolong(const pimpl *p, const pm_gc *g, double *x)
{
    for (int i = p->lo; i < p->hi; i++) {
        const int nd = g->node[i - p->lo];
        if (nd < 0) continue;
        const double zr = g->zeta[2 * (i - p->lo)], zi = g->zeta[2 * (i - p->lo) + 1];
        const double ya = g->yl[2 * nd], yb = g->yl[2 * nd + 1];
        x[2 * i] += ya * zr - yb * zi;
        x[2 * i + 1] += ya * zi + yb * zr;
    }
}

glpgp_status glpgp_petsc_gc_zy(pimpl *p, pm_gc *g)
{
    double *w = g->tbuf2;
    for (int i = 0; i < p->hi - p->lo; i++) {
        const int nd = g->node[i];
        const double zr = g->zeta[2 * i], zi = g->zeta[2 * i + 1];
        const double ya = nd < 0 ? 0.0 : g->yl[2 * nd], yb = nd < 0 ? 0.0 : g->yl[2 * nd + 1];
        w[2 * i] = ya * zr - yb * zi;
        w[2 * i + 1] = ya * zi + yb * zr;
    }
    return glpgp_petsc_gc_exchange(p, g, w);
}
