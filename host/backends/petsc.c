/* backends/petsc.c: the PETSc backend (glpgp/backends.h, "PETSc backend"),
 * built into the module glpgp_petsc.so (with petsc_glue.c) that
 * backends/petsc_load.c dlopen's for `--backend petsc`.
 *
 * Distribution. Rank r owns a contiguous block of the global vertex numbering
 * (the coordinate-bisection renumbering of cli/cmd_solve.c): its vertices are
 * the block rows of its PETSc Vecs (2 unknowns each) and of the Newton
 * matrix. Two layouts of the system the driver hands to setup:
 *  - a part (sys->mesh->part, glpgp_mesh_part; the default with P > 1): the
 *    rank holds only its part of the mesh -- owned vertices first (system
 *    rows [0, nv_owned), global rows first + i), then one layer of ghosts
 *    (global ids in part->gid), and the triangles touching an owned vertex
 *    -- and the driver's host arrays are of that local length: vec_write
 *    takes the owned entries, vec_read returns owned + ghost values (one
 *    ghost scatter). Rank 0 read and split the input (glpgp_mesh_extract_part,
 *    sent by mesh_send / mesh_recv below) and keeps only the input mesh for
 *    the outputs; the results come back to it by gather_bytes.
 *  - the whole mesh on every rank (per-vertex input files, cross field, size
 *    function, one rank): rank r owns [r nv / P, (r+1) nv / P) of it and
 *    vec_read all-gathers.
 * An element op (assembly, gradient, energy, spmv, the fused CG steps) first
 * brings the vector it reads into a system-length scratch array, the owned
 * part copied and the ghost vertices (the pattern's off-rank columns of the
 * owned rows: every vertex of every triangle touching an owned vertex) by one
 * VecScatter, then runs the per-row bodies of kernels/rows.h -- the reference
 * backend's arithmetic, not a copy -- on the owned rows only: the matrices
 * are stored as the owned slice [rowptr[lo], rowptr[hi]) of the block slots.
 * So every stored row is bit-identical to the reference backend's (a part's
 * owned rows see all their triangles, in the whole mesh's order).
 *
 * Reductions: each rank sums its rows (triangles: those whose lowest vertex
 * it owns, so each triangle counts once) in increasing order, the partials
 * are all-gathered and summed in rank order: the same value on every rank
 * (the driver's decisions are taken everywhere alike) and, on one rank, the
 * reference backend's sums bit for bit. The reduce op gives the driver the
 * same sums (and max / min) for its host values on a part (solver/distributed.c:
 * Dirichlet counts, median |z|, singular triangles).
 *
 * Linear solves: precond AMG (the default), glpgp's aggregation multigrid on
 * each rank's rows (the amg_* ops, petsc_amg.c) under the drivers' flexible
 * CG: one rank is the reference backend's multigrid bit for bit. With
 * -glpgp_mg gamg ($PETSC_OPTIONS) the op linear_solve instead (petsc_ksp.c):
 * NEWTON copied into an AIJ matrix of block size 2, KSPCG with PCGAMG and the
 * near null space [z, iz] of the Newton iterate. With precond Jacobi the
 * drivers' block-Jacobi CG runs on the fused ops (one rank: the reference
 * backend's iterates bit for bit). $PETSC_OPTIONS reaches KSP
 * (KSPSetFromOptions: -ksp_view, -pc_gamg_threshold, ...).
 *
 * What stays whole: on rank 0 of a part layout, the input mesh (for the
 * writers, the quad extraction and the picture) and the gathered result;
 * in the whole-mesh layout, everything on every rank. */
#include "glpgp/backends.h"
#include "glpgp/solve.h"
#include "rows.h"
#include "newton_rows.h"

#include "petsc_module.h"

#include <petscksp.h>

#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

_Static_assert(GLPGP_ROWS_S_PQ == GLPGP_S_PQ, "kernels/rows.h: p.Ap slot differs from glpgp/backend.h");

#include "petsc_impl.h"


/* ---- process-wide: MPI / PETSc ------------------------------------------- */

static int g_init, g_we_init_mpi;

glpgp_status glpgp_petsc_m_init(void)
{
    if (g_init) return GLPGP_OK;
    int flag = 0;
    MPI_Initialized(&flag);
    if (!flag) {
        if (MPI_Init(NULL, NULL) != MPI_SUCCESS) return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "MPI_Init failed");
        g_we_init_mpi = 1;
    }
    /* glpgp keeps its own signal handlers (output cleanup on SIGINT / SIGTERM) */
    PetscOptionsSetValue(NULL, "-no_signal_handler", NULL);
    if (PetscInitialize(NULL, NULL, NULL, NULL))
        return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "PetscInitialize failed");
    /* errors come back as codes (PCHK), PETSc prints nothing */
    PetscPushErrorHandler(PetscIgnoreErrorHandler, NULL);
    g_init = 1;
    return GLPGP_OK;
}

static void m_finalize(void)
{
    if (!g_init) return;
    PetscFinalize();
    if (g_we_init_mpi) MPI_Finalize();
    g_init = 0;
}

int glpgp_petsc_m_rank(void)
{
    int r = 0;
    if (g_init) MPI_Comm_rank(PETSC_COMM_WORLD, &r);
    return r;
}

int glpgp_petsc_m_size(void)
{
    int s = 1;
    if (g_init) MPI_Comm_size(PETSC_COMM_WORLD, &s);
    return s;
}

static int m_all_ok(int ok)
{
    int in = ok ? 1 : 0, out = in;
    if (g_init) MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
    return out;
}

static void m_gather(const double *vals, int n, double *out)
{
    if (!g_init) {
        memcpy(out, vals, (size_t)n * sizeof *vals);
        return;
    }
    MPI_Gather(vals, n, MPI_DOUBLE, out, n, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
}

static double m_max_rss(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0) return 0.0;
    return 1024.0 * (double)ru.ru_maxrss; /* Linux: KiB */
}

/* ---- reductions: partials all-gathered, summed in rank order -------------- */

/* v[0 .. n) <- sum over ranks of v (n <= 4), the same bits on every rank */
glpgp_status glpgp_petsc_reduce_sum(pimpl *p, double *v, int n)
{
    if (p->size == 1) return GLPGP_OK;
    double buf[4 * 256], *all = buf;
    if ((size_t)p->size * (size_t)n > sizeof buf / sizeof buf[0])
        GLPGP_CHECK(glpgp_malloc((size_t)p->size * (size_t)n, sizeof(double), &all));
    int rc = MPI_Allgather(v, n, MPI_DOUBLE, all, n, MPI_DOUBLE, PETSC_COMM_WORLD);
    if (rc == MPI_SUCCESS)
        for (int k = 0; k < n; k++) {
            double s = 0.0;
            for (int r = 0; r < p->size; r++) s += all[(size_t)r * n + k];
            v[k] = s;
        }
    if (all != buf) free(all);
    if (rc != MPI_SUCCESS) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "MPI_Allgather failed");
    return GLPGP_OK;
}

/* ---- ghost exchange --------------------------------------------------------- */

/* xf[k] <- x at the owned and ghost vertices (other entries stale) */
glpgp_status glpgp_petsc_load_ghosted(pimpl *p, const glpgp_vec *x, int k)
{
    const PetscScalar *a;
    PCHK(VecGetArrayRead(x->v, &a));
    memcpy(p->xf[k] + 2 * (size_t)p->lo, a, (size_t)2 * (p->hi - p->lo) * sizeof(double));
    PCHK(VecRestoreArrayRead(x->v, &a));
    if (p->size > 1) {
        PCHK(VecScatterBegin(p->sc, x->v, p->xseq[k], INSERT_VALUES, SCATTER_FORWARD));
        PCHK(VecScatterEnd(p->sc, x->v, p->xseq[k], INSERT_VALUES, SCATTER_FORWARD));
    }
    return GLPGP_OK;
}

/* ---- the ops -------------------------------------------------------------- */

static void p_free_system(pimpl *p)
{
    free(p->wbuf);
    free(p->size_);
    free(p->dir);
    free(p->quadb);
    free(p->newtonb);
    free(p->dinvb);
    free(p->ghost);
    free(p->tcount);
    free(p->rcounts);
    free(p->rdispls);
    for (int k = 0; k < 2; k++) {
        if (p->xseq[k]) VecDestroy(&p->xseq[k]);
        free(p->xf[k]);
        p->xf[k] = NULL;
    }
    if (p->sc) VecScatterDestroy(&p->sc);
    if (p->A) MatDestroy(&p->A);
    if (p->ksp) KSPDestroy(&p->ksp);
    if (p->nn) VecDestroy(&p->nn);
    glpgp_petsc_amg_free(p);
    p->wbuf = p->size_ = p->quadb = p->newtonb = p->dinvb = NULL;
    p->dir = NULL;
    p->ghost = p->tcount = p->rcounts = p->rdispls = NULL;
    p->sys = NULL;
}

static void p_destroy(glpgp_backend *b)
{
    pimpl *p = PI(b);
    if (!p) return;
    p_free_system(p);
    free(p);
    b->impl = NULL;
}

static glpgp_status p_vec_create(glpgp_backend *b, size_t n, glpgp_vec **out);
static void p_vec_destroy(glpgp_backend *b, glpgp_vec **v);

static glpgp_status p_setup(glpgp_backend *b, const glpgp_system *sys)
{
    pimpl *p = PI(b);
    p_free_system(p);
    p->sys = sys;
    b->sys = sys;
    const int nv = sys->nv, P = p->size, r = p->rank;
    const glpgp_mesh_part *part = sys->mesh->part;
    if (part) { /* one rank's part: the owned vertices first, then the ghosts */
        p->lo = 0;
        p->hi = part->nv_owned;
        p->vstart = part->first;
        p->gid = part->gid;
    } else { /* the whole mesh on every rank: a slice of its rows */
        p->lo = (int)((long long)nv * r / P);
        p->hi = (int)((long long)nv * (r + 1) / P);
        p->vstart = p->lo;
        p->gid = NULL;
    }
    p->slo = sys->rowptr[p->lo];
    p->shi = sys->rowptr[p->hi];
    const long nslot = p->shi - p->slo;
    const int nown = p->hi - p->lo;
    GLPGP_CHECK(glpgp_calloc((size_t)2 * nv, sizeof(double), &p->wbuf));
    GLPGP_CHECK(glpgp_calloc((size_t)nv, sizeof(double), &p->size_));
    GLPGP_CHECK(glpgp_calloc((size_t)nv, 1, &p->dir));
    GLPGP_CHECK(glpgp_calloc((size_t)4 * (nslot > 0 ? nslot : 1), sizeof(double), &p->quadb));
    GLPGP_CHECK(glpgp_calloc((size_t)4 * (nslot > 0 ? nslot : 1), sizeof(double), &p->newtonb));
    GLPGP_CHECK(glpgp_calloc((size_t)4 * (nown > 0 ? nown : 1), sizeof(double), &p->dinvb));
    for (int k = 0; k < 2; k++) {
        GLPGP_CHECK(glpgp_calloc((size_t)2 * nv, sizeof(double), &p->xf[k]));
        PCHK(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, (PetscInt)2 * nv, p->xf[k], &p->xseq[k]));
    }
    /* ghost vertices: off-rank columns of the owned rows */
    unsigned char *mark = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)nv, 1, &mark));
    int ng = 0;
    for (int i = p->lo; i < p->hi; i++)
        for (int k = sys->rowptr[i]; k < sys->rowptr[i + 1]; k++) {
            const int j = sys->col[k];
            if ((j < p->lo || j >= p->hi) && !mark[j]) {
                mark[j] = 1;
                ng++;
            }
        }
    glpgp_status st = glpgp_malloc((size_t)(ng > 0 ? ng : 1), sizeof(int), &p->ghost);
    if (st != GLPGP_OK) {
        free(mark);
        return st;
    }
    p->nghost = 0;
    for (int j = 0; j < nv; j++)
        if (mark[j]) p->ghost[p->nghost++] = j;
    free(mark);
    /* triangles counted here: lowest (global) vertex owned */
    GLPGP_CHECK(glpgp_malloc((size_t)(sys->nt > 0 ? sys->nt : 1), sizeof(int), &p->tcount));
    p->ntcount = 0;
    for (int t = 0; t < sys->nt; t++) {
        const int *tv = sys->mesh->tri + 3 * (size_t)t;
        PetscInt mn = gcol(p, tv[0]);
        for (int a = 1; a < 3; a++)
            if (gcol(p, tv[a]) < mn) mn = gcol(p, tv[a]);
        if (mn >= p->vstart && mn < p->vstart + (p->hi - p->lo)) p->tcount[p->ntcount++] = t;
    }
    /* all-gather layout of vectors */
    GLPGP_CHECK(glpgp_malloc((size_t)P, sizeof(int), &p->rcounts));
    GLPGP_CHECK(glpgp_malloc((size_t)P, sizeof(int), &p->rdispls));
    for (int q = 0; q < P; q++) {
        const int a = (int)((long long)nv * q / P), e = (int)((long long)nv * (q + 1) / P);
        p->rcounts[q] = 2 * (e - a);
        p->rdispls[q] = 2 * a;
    }
    /* ghost scatter: global unknowns 2 gid(j), 2 gid(j) + 1 of the ghosts ->
     * positions 2 j, 2 j + 1 of the scratch */
    if (P > 1) {
        glpgp_vec *tmpl = NULL;
        PetscInt *gg = NULL;
        GLPGP_CHECK(glpgp_malloc((size_t)(p->nghost > 0 ? p->nghost : 1), sizeof(PetscInt), &gg));
        for (int g = 0; g < p->nghost; g++) gg[g] = gcol(p, p->ghost[g]);
        glpgp_status vst = p_vec_create(b, (size_t)2 * nv, &tmpl);
        if (vst != GLPGP_OK) {
            free(gg);
            return vst;
        }
        IS isg = NULL, isl = NULL;
        PetscErrorCode pe = ISCreateBlock(PETSC_COMM_SELF, 2, p->nghost, gg, PETSC_COPY_VALUES, &isg);
        if (!pe) pe = ISCreateBlock(PETSC_COMM_SELF, 2, p->nghost, p->ghost, PETSC_COPY_VALUES, &isl);
        if (!pe) pe = VecScatterCreate(tmpl->v, isg, p->xseq[0], isl, &p->sc);
        if (isg) ISDestroy(&isg);
        if (isl) ISDestroy(&isl);
        free(gg);
        p_vec_destroy(b, &tmpl);
        if (pe) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "PETSc error %d creating the ghost scatter", (int)pe);
    }
    p->A_dirty = 1;
    p->nn_valid = 0;
    glpgp_log(GLPGP_LOG_DEBUG, "petsc rank %d/%d: vertices [%d, %d) (global from %d), %d ghosts, %d triangles counted",
              p->rank, P, p->lo, p->hi, p->vstart, p->nghost, p->ntcount);
    return GLPGP_OK;
}

static glpgp_status p_vec_create(glpgp_backend *b, size_t n, glpgp_vec **out)
{
    pimpl *p = PI(b);
    *out = NULL;
    if (!p->sys) return GLPGP_FAIL(GLPGP_ERR_ARG, "vec_create before setup");
    /* 2 nv doubles: a distributed vector of the owned unknowns; any other
     * length: a sequential one of this rank alone (coarse multigrid levels) */
    glpgp_vec *v = NULL;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *v, &v));
    v->local = n != (size_t)2 * p->sys->nv;
    PetscErrorCode pe = v->local ? VecCreateSeq(PETSC_COMM_SELF, (PetscInt)n, &v->v)
                                 : VecCreateMPI(PETSC_COMM_WORLD, (PetscInt)2 * (p->hi - p->lo), PETSC_DETERMINE, &v->v);
    if (!pe && !v->local) pe = VecSetBlockSize(v->v, 2);
    if (!pe) pe = VecSet(v->v, 0.0);
    if (pe) {
        if (v->v) VecDestroy(&v->v);
        free(v);
        return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "PETSc error %d creating a vector", (int)pe);
    }
    *out = v;
    return GLPGP_OK;
}

static void p_vec_destroy(glpgp_backend *b, glpgp_vec **v)
{
    (void)b;
    if (!v || !*v) return;
    VecDestroy(&(*v)->v);
    free(*v);
    *v = NULL;
}

static glpgp_status p_vec_write(glpgp_backend *b, glpgp_vec *v, const double *h)
{
    pimpl *p = PI(b);
    PetscScalar *a;
    PetscInt n;
    PCHK(VecGetLocalSize(v->v, &n));
    PCHK(VecGetArray(v->v, &a));
    if (v->local) memcpy(a, h, (size_t)n * sizeof(double));
    else memcpy(a, h + 2 * (size_t)p->lo, (size_t)2 * (p->hi - p->lo) * sizeof(double));
    PCHK(VecRestoreArray(v->v, &a));
    return GLPGP_OK;
}

static glpgp_status p_vec_read(glpgp_backend *b, const glpgp_vec *v, double *h)
{
    pimpl *p = PI(b);
    if (v->local) {
        PetscInt n;
        const PetscScalar *a;
        PCHK(VecGetLocalSize(v->v, &n));
        PCHK(VecGetArrayRead(v->v, &a));
        memcpy(h, a, (size_t)n * sizeof(double));
        PCHK(VecRestoreArrayRead(v->v, &a));
        return GLPGP_OK;
    }
    if (p->gid) { /* a part: the owned and ghost values, one ghost scatter */
        GLPGP_CHECK(glpgp_petsc_load_ghosted(p, v, 0));
        memcpy(h, p->xf[0], (size_t)2 * p->sys->nv * sizeof(double));
        return GLPGP_OK;
    }
    const PetscScalar *a;
    PCHK(VecGetArrayRead(v->v, &a));
    int rc = MPI_SUCCESS;
    if (p->size == 1)
        memcpy(h, a, (size_t)2 * (p->hi - p->lo) * sizeof(double));
    else
        rc = MPI_Allgatherv(a, 2 * (p->hi - p->lo), MPI_DOUBLE, h, p->rcounts, p->rdispls, MPI_DOUBLE,
                            PETSC_COMM_WORLD);
    PCHK(VecRestoreArrayRead(v->v, &a));
    if (rc != MPI_SUCCESS) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "MPI_Allgatherv failed");
    return GLPGP_OK;
}

static glpgp_status p_copy(glpgp_backend *b, glpgp_vec *d, const glpgp_vec *s)
{
    (void)b;
    PCHK(VecCopy(s->v, d->v));
    return GLPGP_OK;
}

static glpgp_status p_axpby(glpgp_backend *b, double a, const glpgp_vec *x, double c, glpgp_vec *y)
{
    (void)b;
    /* y <- a x + c y  (a zero coefficient does not read its vector: rows.h) */
    PetscInt n;
    PetscScalar *ya;
    const PetscScalar *xa;
    PCHK(VecGetLocalSize(y->v, &n));
    if (x == y) {
        PCHK(VecGetArray(y->v, &ya));
        for (PetscInt i = 0; i < n; i++) glpgp_entry_axpby((long)i, a, ya, c, ya);
        PCHK(VecRestoreArray(y->v, &ya));
        return GLPGP_OK;
    }
    PCHK(VecGetArrayRead(x->v, &xa));
    PCHK(VecGetArray(y->v, &ya));
    for (PetscInt i = 0; i < n; i++) glpgp_entry_axpby((long)i, a, xa, c, ya);
    PCHK(VecRestoreArray(y->v, &ya));
    PCHK(VecRestoreArrayRead(x->v, &xa));
    return GLPGP_OK;
}

static glpgp_status p_trial_point(glpgp_backend *b, const glpgp_vec *x, const glpgp_vec *d, double a, double r1,
                                  glpgp_vec *xt)
{
    (void)b;
    /* xt <- x (+) a d on the owned vertices (kernels/newton_rows.h) */
    PetscInt n;
    PetscScalar *ta;
    const PetscScalar *xa, *da;
    PCHK(VecGetLocalSize(xt->v, &n));
    PCHK(VecGetArrayRead(x->v, &xa));
    PCHK(VecGetArrayRead(d->v, &da));
    PCHK(VecGetArray(xt->v, &ta));
    for (PetscInt i = 0; i < n / 2; i++) glpgp_row_trial_point((int)i, xa, da, a, r1, ta);
    PCHK(VecRestoreArray(xt->v, &ta));
    PCHK(VecRestoreArrayRead(d->v, &da));
    PCHK(VecRestoreArrayRead(x->v, &xa));
    return GLPGP_OK;
}

static glpgp_status p_dot(glpgp_backend *b, const glpgp_vec *x, const glpgp_vec *y, int slot)
{
    pimpl *p = PI(b);
    if (slot < 0 || slot >= GLPGP_NSLOTS) return GLPGP_FAIL(GLPGP_ERR_ARG, "dot: bad slot %d", slot);
    PetscInt n;
    const PetscScalar *xa, *ya;
    PCHK(VecGetLocalSize(x->v, &n));
    PCHK(VecGetArrayRead(x->v, &xa));
    PCHK(VecGetArrayRead(y->v, &ya));
    /* s[slot] <- sum_i x_i y_i */
    double s = glpgp_range_dot(0, (long)n, xa, ya);
    PCHK(VecRestoreArrayRead(y->v, &ya));
    PCHK(VecRestoreArrayRead(x->v, &xa));
    if (!x->local) GLPGP_CHECK(glpgp_petsc_reduce_sum(p, &s, 1));
    p->s[slot] = s;
    return GLPGP_OK;
}

static glpgp_status p_get_scalars(glpgp_backend *b, double *out, int n)
{
    memcpy(out, PI(b)->s, (size_t)n * sizeof(double));
    return GLPGP_OK;
}

static glpgp_status p_set_field(glpgp_backend *b, const double *w, const unsigned char *dir)
{
    pimpl *p = PI(b);
    memcpy(p->wbuf, w, (size_t)2 * p->sys->nv * sizeof(double));
    memcpy(p->dir, dir, (size_t)p->sys->nv);
    p->sized = 0;
    return GLPGP_OK;
}

static glpgp_status p_set_size(glpgp_backend *b, const double *size)
{
    pimpl *p = PI(b);
    p->sized = size != NULL;
    if (size) memcpy(p->size_, size, (size_t)p->sys->nv * sizeof(double));
    return GLPGP_OK;
}

static glpgp_status p_assemble_quadratic(glpgp_backend *b, int kind, double h)
{
    pimpl *p = PI(b);
    const glpgp_system *sys = p->sys;
    const glpgp_mesh *m = sys->mesh;
    /* QUAD <- gather of the element entries into each owned block slot */
    double *quad = QUAD(p);
    p->quad_gen++;
    for (int i = p->lo; i < p->hi; i++)
        glpgp_row_asm_quad(i, kind, h, p->sized, p->size_, m->xy, m->tri, p->wbuf, sys->rowptr, sys->cptr,
                           sys->contrib, quad);
    return GLPGP_OK;
}

static glpgp_status p_assemble_newton(glpgp_backend *b, const glpgp_vec *xv, double inv4e2, int hess)
{
    pimpl *p = PI(b);
    const glpgp_system *sys = p->sys;
    const glpgp_mesh *m = sys->mesh;
    GLPGP_CHECK(glpgp_petsc_load_ghosted(p, xv, 0));
    /* NEWTON <- QUAD + penalty Hessian (Dirichlet rows/cols -> identity);
     * DINV_i <- inverse of the 2x2 diagonal block, owned rows */
    double bad = -1.0;
    const double *x = p->xf[0];
    double *quad = QUAD(p), *newton = NEWT(p), *dinv = DINV(p);
    for (int i = p->lo; i < p->hi; i++)
        if (glpgp_row_asm_newton(i, hess, inv4e2, m->xy, m->tri, x, sys->rowptr, sys->col, sys->diag, sys->vptr,
                                 sys->vtri, p->dir, quad, newton, dinv) &&
            bad < 0)
            bad = i;
    /* every rank fails alike: the largest failing index (-1: none) */
    double badv[1] = {bad};
    if (p->size > 1) {
        double all[1];
        MPI_Allreduce(badv, all, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
        bad = all[0];
    }
    p->A_dirty = 1;
    p->newton_inv4e2 = inv4e2;
    /* the near null space of the next linear solve: the iterate, when this is a GL Newton matrix */
    p->nn_valid = inv4e2 > 0.0;
    if (p->nn_valid) {
        if (!p->nn) PCHK(VecDuplicate(xv->v, &p->nn));
        PCHK(VecCopy(xv->v, p->nn));
    }
    if (bad >= 0) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "singular diagonal block at vertex %d", (int)bad);
    return GLPGP_OK;
}

/* local part of P = sum over the counted triangles of P_t(x) (x: whole-length scratch) */
static double penalty_local(const pimpl *p, const double *x, double inv4e2)
{
    double s = 0.0;
    if (!(inv4e2 > 0.0)) return 0.0;
    for (int k = 0; k < p->ntcount; k++)
        s += glpgp_tri_pen_energy(p->tcount[k], inv4e2, p->sys->mesh->xy, p->sys->mesh->tri, x);
    return s;
}

static glpgp_status p_gradient(glpgp_backend *b, const glpgp_vec *xv, double inv4e2, glpgp_vec *g)
{
    pimpl *p = PI(b);
    const glpgp_system *sys = p->sys;
    const glpgp_mesh *m = sys->mesh;
    GLPGP_CHECK(glpgp_petsc_load_ghosted(p, xv, 0));
    const double *x = p->xf[0];
    /* g <- QUAD x + grad P (0 at Dirichlet vertices);  E = 1/2 x.QUAD x;  P = sum_t P_t */
    PetscScalar *ga;
    PCHK(VecGetArray(g->v, &ga));
    double *gg = ga - 2 * (long)p->lo;
    double e[2] = {0.0, 0.0};
    const double *quad = QUAD(p);
    for (int i = p->lo; i < p->hi; i++)
        glpgp_row_gradient(i, inv4e2, m->xy, m->tri, x, sys->rowptr, sys->col, quad, sys->vptr, sys->vtri, p->dir,
                           gg, &e[0]);
    PCHK(VecRestoreArray(g->v, &ga));
    e[1] = penalty_local(p, x, inv4e2);
    GLPGP_CHECK(glpgp_petsc_reduce_sum(p, e, 2));
    p->s[GLPGP_S_E] = 0.5 * e[0];
    p->s[GLPGP_S_P] = e[1];
    return GLPGP_OK;
}

/* y <- M x on the owned rows (x in scratch k);  returns the local x.y */
static glpgp_status spmv_rows(pimpl *p, const double *M, int k, const glpgp_vec *yv, int dot, double *s)
{
    const glpgp_system *sys = p->sys;
    PetscScalar *ya;
    PCHK(VecGetArray(yv->v, &ya));
    double *y = ya - 2 * (long)p->lo;
    const double *x = p->xf[k];
    double acc = 0.0;
    if (dot)
        for (int i = p->lo; i < p->hi; i++) glpgp_row_spmv_dot(i, sys->rowptr, sys->col, M, x, y, &acc);
    else
        for (int i = p->lo; i < p->hi; i++) glpgp_row_spmv_store(i, sys->rowptr, sys->col, M, x, y);
    PCHK(VecRestoreArray(yv->v, &ya));
    if (s) *s = acc;
    return GLPGP_OK;
}

static glpgp_status p_energy(glpgp_backend *b, const glpgp_vec *xv, double inv4e2, glpgp_vec *work)
{
    pimpl *p = PI(b);
    GLPGP_CHECK(glpgp_petsc_load_ghosted(p, xv, 0));
    /* work <- QUAD x;  E = 1/2 x.work;  P = sum_t P_t */
    double e[2];
    GLPGP_CHECK(spmv_rows(p, QUAD(p), 0, work, 1, &e[0]));
    e[1] = penalty_local(p, p->xf[0], inv4e2);
    GLPGP_CHECK(glpgp_petsc_reduce_sum(p, e, 2));
    p->s[GLPGP_S_E] = 0.5 * e[0];
    p->s[GLPGP_S_P] = e[1];
    return GLPGP_OK;
}

static glpgp_status p_spmv(glpgp_backend *b, int matrix, const glpgp_vec *x, glpgp_vec *y)
{
    pimpl *p = PI(b);
    GLPGP_CHECK(glpgp_petsc_load_ghosted(p, x, 0));
    /* y <- M x */
    return spmv_rows(p, matrix == GLPGP_MAT_QUAD ? QUAD(p) : NEWT(p), 0, y, 0, NULL);
}

static glpgp_status p_cg_precond(glpgp_backend *b, const glpgp_vec *r, glpgp_vec *z, int rz)
{
    pimpl *p = PI(b);
    /* z <- DINV r;  s[rz] <- r.z;  s[RR] <- r.r */
    const PetscScalar *ra;
    PetscScalar *za;
    PCHK(VecGetArrayRead(r->v, &ra));
    PCHK(VecGetArray(z->v, &za));
    const double *rr = ra - 2 * (long)p->lo;
    double *zz = za - 2 * (long)p->lo;
    double s[2] = {0.0, 0.0};
    const double *dinv = DINV(p);
    for (int i = p->lo; i < p->hi; i++) glpgp_row_precond(i, dinv, rr, zz, &s[0], &s[1]);
    PCHK(VecRestoreArray(z->v, &za));
    PCHK(VecRestoreArrayRead(r->v, &ra));
    GLPGP_CHECK(glpgp_petsc_reduce_sum(p, s, 2));
    p->s[rz] = s[0];
    p->s[GLPGP_S_RR] = s[1];
    return GLPGP_OK;
}

static glpgp_status p_cg_spmv_dot(glpgp_backend *b, const glpgp_vec *pv, glpgp_vec *q)
{
    pimpl *p = PI(b);
    GLPGP_CHECK(glpgp_petsc_load_ghosted(p, pv, 0));
    /* q <- N p;  s[PQ] <- p.q */
    double s;
    GLPGP_CHECK(spmv_rows(p, NEWT(p), 0, q, 1, &s));
    GLPGP_CHECK(glpgp_petsc_reduce_sum(p, &s, 1));
    p->s[GLPGP_S_PQ] = s;
    return GLPGP_OK;
}

static glpgp_status p_cg_update(glpgp_backend *b, glpgp_vec *x, glpgp_vec *r, const glpgp_vec *pv,
                                const glpgp_vec *q, glpgp_vec *z, int rz, int rz_new)
{
    pimpl *p = PI(b);
    /* alpha = (r.z) / (p.Ap);  x <- x + alpha p;  r <- r - alpha q;
     * z <- DINV r;  s[rz_new] <- r.z;  s[RR] <- r.r */
    const double alpha = glpgp_cg_alpha(p->s, rz);
    PetscScalar *xa, *ra, *za;
    const PetscScalar *pa, *qa;
    PCHK(VecGetArray(x->v, &xa));
    PCHK(VecGetArray(r->v, &ra));
    PCHK(VecGetArray(z->v, &za));
    PCHK(VecGetArrayRead(pv->v, &pa));
    PCHK(VecGetArrayRead(q->v, &qa));
    const long off = 2 * (long)p->lo;
    double s[2] = {0.0, 0.0};
    const double *dinv = DINV(p);
    for (int i = p->lo; i < p->hi; i++)
        glpgp_row_cg_update(i, alpha, xa - off, ra - off, pa - off, qa - off, dinv, za - off, &s[0], &s[1]);
    PCHK(VecRestoreArrayRead(q->v, &qa));
    PCHK(VecRestoreArrayRead(pv->v, &pa));
    PCHK(VecRestoreArray(z->v, &za));
    PCHK(VecRestoreArray(r->v, &ra));
    PCHK(VecRestoreArray(x->v, &xa));
    GLPGP_CHECK(glpgp_petsc_reduce_sum(p, s, 2));
    p->s[rz_new] = s[0];
    p->s[GLPGP_S_RR] = s[1];
    return GLPGP_OK;
}

static glpgp_status p_cg_direction(glpgp_backend *b, glpgp_vec *pv, const glpgp_vec *z, int rz_new, int rz)
{
    pimpl *p = PI(b);
    /* beta = (r.z)_new / (r.z)_old;  p <- z + beta p */
    const double beta = glpgp_cg_beta(p->s, rz_new, rz);
    PetscInt n;
    PetscScalar *pa;
    const PetscScalar *za;
    PCHK(VecGetLocalSize(pv->v, &n));
    PCHK(VecGetArray(pv->v, &pa));
    PCHK(VecGetArrayRead(z->v, &za));
    for (PetscInt i = 0; i < n; i++) glpgp_entry_cg_direction((long)i, beta, pa, za);
    PCHK(VecRestoreArrayRead(z->v, &za));
    PCHK(VecRestoreArray(pv->v, &pa));
    return GLPGP_OK;
}

static glpgp_status p_reduce(glpgp_backend *b, double *v, int n, int op)
{
    pimpl *p = PI(b);
    /* sums: partials summed in rank order (the same bits everywhere) */
    if (op == GLPGP_REDUCE_SUM) {
        for (int k = 0; k < n; k += 4) GLPGP_CHECK(glpgp_petsc_reduce_sum(p, v + k, n - k < 4 ? n - k : 4));
        return GLPGP_OK;
    }
    if (p->size == 1) return GLPGP_OK;
    if (MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, op == GLPGP_REDUCE_MAX ? MPI_MAX : MPI_MIN,
                      PETSC_COMM_WORLD) != MPI_SUCCESS)
        return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "MPI_Allreduce failed");
    return GLPGP_OK;
}

/* the ops every preconditioner shares */
#define PETSC_COMMON_OPS                                                                                \
    .name = "petsc", .destroy = p_destroy, .setup = p_setup, .vec_create = p_vec_create,            \
    .vec_destroy = p_vec_destroy, .vec_write = p_vec_write, .vec_read = p_vec_read, .copy = p_copy, \
    .axpby = p_axpby, .dot = p_dot, .get_scalars = p_get_scalars, .set_field = p_set_field,        \
    .set_size = p_set_size, .assemble_quadratic = p_assemble_quadratic,                            \
    .assemble_newton = p_assemble_newton, .gradient = p_gradient, .energy = p_energy, .spmv = p_spmv, \
    .cg_precond = p_cg_precond, .cg_spmv_dot = p_cg_spmv_dot, .cg_update = p_cg_update,            \
    .cg_direction = p_cg_direction, .reduce = p_reduce, .trial_point = p_trial_point

/* --precond amg (the default): glpgp's own multigrid on each rank's rows
 * (petsc_amg.c) under the drivers' flexible CG, no linear_solve op */
static const glpgp_backend_ops petsc_ops_mg = {
    PETSC_COMMON_OPS,
    .amg_setup = glpgp_petsc_amg_setup,
    .amg_values = glpgp_petsc_amg_values,
    .amg_coarse_invert = glpgp_petsc_amg_coarse_invert,
    .amg_smooth = glpgp_petsc_amg_smooth,
    .amg_restrict = glpgp_petsc_amg_restrict,
    .amg_prolong = glpgp_petsc_amg_prolong,
    .amg_coarse_solve = glpgp_petsc_amg_coarse_solve,
    .amg_spmv_dots = glpgp_petsc_amg_spmv_dots,
    .amg_dots = glpgp_petsc_amg_dots,
    .amg_axpby = glpgp_petsc_amg_axpby,
    .amg_kcombine = glpgp_petsc_amg_kcombine,
    .amg_get_scalars = glpgp_petsc_amg_get_scalars,
};

/* --precond amg with -glpgp_mg gamg: KSPCG + PCGAMG (petsc_ksp.c) */
static const glpgp_backend_ops petsc_ops_gamg = {PETSC_COMMON_OPS, .linear_solve = glpgp_petsc_linear_solve};

/* --precond jacobi: no linear_solve op, so the drivers' own block-Jacobi CG
 * (solver/cg.c) runs on the fused ops above: the reference backend's
 * iteration, bit for bit on one rank */
static const glpgp_backend_ops petsc_ops_jacobi = {PETSC_COMMON_OPS};

/* -glpgp_mg glpgp|gamg ($PETSC_OPTIONS): *gamg <- 1 for GAMG; a negative
 * -glpgp_mg_global fails here, before any solve */
static glpgp_status mg_choice(int *gamg)
{
    char mode[32] = "glpgp";
    PetscBool set = PETSC_FALSE;
    PCHK(PetscOptionsGetString(NULL, NULL, "-glpgp_mg", mode, sizeof mode, &set));
    if (strcmp(mode, "glpgp") && strcmp(mode, "gamg"))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "-glpgp_mg '%s': expected glpgp or gamg", mode);
    *gamg = !strcmp(mode, "gamg");
    PetscInt nodes = 0; /* the bound on the global coarse nodes (petsc_gc.c) */
    PCHK(PetscOptionsGetInt(NULL, NULL, "-glpgp_mg_global", &nodes, &set));
    if (set && nodes < 0)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "-glpgp_mg_global %d: expected a node count >= 0", (int)nodes);
    return GLPGP_OK;
}

glpgp_status glpgp_petsc_m_create(int precond, glpgp_backend **out)
{
    *out = NULL;
    GLPGP_CHECK(glpgp_petsc_m_init());
    glpgp_backend *b = NULL;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *b, &b));
    pimpl *p = NULL;
    glpgp_status st = glpgp_calloc(1, sizeof *p, &p);
    if (st != GLPGP_OK) {
        free(b);
        return st;
    }
    p->rank = glpgp_petsc_m_rank();
    p->size = glpgp_petsc_m_size();
    int gamg = precond == GLPGP_PETSC_PRECOND_GAMG;
    if (gamg) precond = GLPGP_PRECOND_AMG;
    p->precond = precond;
    b->impl = p;
    if (!gamg && precond != GLPGP_PRECOND_JACOBI && (st = mg_choice(&gamg)) != GLPGP_OK) {
        free(p);
        free(b);
        return st;
    }
    b->ops = precond == GLPGP_PRECOND_JACOBI ? &petsc_ops_jacobi : gamg ? &petsc_ops_gamg : &petsc_ops_mg;
    *out = b;
    return GLPGP_OK;
}

void glpgp_petsc_m_local_info(const glpgp_backend *b, int *owned, int *ghosts)
{
    const pimpl *p = PI(b);
    *owned = p->sys ? p->hi - p->lo : 0;
    *ghosts = p->sys ? p->nghost : 0;
}

/* ---- distributed meshes: parts sent by rank 0, results gathered --------- */

enum { TAG_MESH = 7301 };

/* one message per array; a header first (sizes, flags) and the scalars */
static glpgp_status m_mesh_send(const glpgp_mesh *m, int dest)
{
    if (!m) { /* rank 0 failed: the header nv = -1 ends the receiver's wait */
        int hdr[7] = {-1, 0, 0, 0, 0, 0, 0};
        double sc[9] = {0};
        if (MPI_Send(hdr, 7, MPI_INT, dest, TAG_MESH, PETSC_COMM_WORLD) != MPI_SUCCESS ||
            MPI_Send(sc, 9, MPI_DOUBLE, dest, TAG_MESH, PETSC_COMM_WORLD) != MPI_SUCCESS)
            return GLPGP_FAIL(GLPGP_ERR_IO, "MPI_Send to rank %d failed", dest);
        return GLPGP_OK;
    }
    const glpgp_mesh_part *pt = m->part;
    if (!pt) return GLPGP_FAIL(GLPGP_ERR_ARG, "mesh_send: not a part");
    int hdr[7] = {m->nv, m->nt, pt->nv_owned, pt->first, pt->nv_global, pt->nt_global, pt->size != NULL};
    double sc[9] = {m->area, m->bbox[0], m->bbox[1], m->bbox[2], m->bbox[3], m->mean_edge,
                    pt->center[0], pt->center[1], pt->size_opt};
    const MPI_Comm cw = PETSC_COMM_WORLD;
    int rc = MPI_Send(hdr, 7, MPI_INT, dest, TAG_MESH, cw);
    if (rc == MPI_SUCCESS) rc = MPI_Send(sc, 9, MPI_DOUBLE, dest, TAG_MESH, cw);
    if (rc == MPI_SUCCESS) rc = MPI_Send(m->xy, 2 * m->nv, MPI_DOUBLE, dest, TAG_MESH, cw);
    if (rc == MPI_SUCCESS) rc = MPI_Send(m->tri, 3 * m->nt, MPI_INT, dest, TAG_MESH, cw);
    if (rc == MPI_SUCCESS) rc = MPI_Send(m->on_boundary, m->nv, MPI_UNSIGNED_CHAR, dest, TAG_MESH, cw);
    if (rc == MPI_SUCCESS) rc = MPI_Send(m->normal_prev, 2 * m->nv, MPI_DOUBLE, dest, TAG_MESH, cw);
    if (rc == MPI_SUCCESS) rc = MPI_Send(m->normal_next, 2 * m->nv, MPI_DOUBLE, dest, TAG_MESH, cw);
    if (rc == MPI_SUCCESS) rc = MPI_Send(pt->gid, m->nv, MPI_INT, dest, TAG_MESH, cw);
    if (rc == MPI_SUCCESS && pt->size) rc = MPI_Send(pt->size, 2 * m->nv, MPI_DOUBLE, dest, TAG_MESH, cw);
    if (rc != MPI_SUCCESS) return GLPGP_FAIL(GLPGP_ERR_IO, "MPI_Send of the mesh part to rank %d failed", dest);
    return GLPGP_OK;
}

static glpgp_status m_mesh_recv(glpgp_mesh **out)
{
    *out = NULL;
    const MPI_Comm cw = PETSC_COMM_WORLD;
    int hdr[7];
    double sc[9];
    if (MPI_Recv(hdr, 7, MPI_INT, 0, TAG_MESH, cw, MPI_STATUS_IGNORE) != MPI_SUCCESS ||
        MPI_Recv(sc, 9, MPI_DOUBLE, 0, TAG_MESH, cw, MPI_STATUS_IGNORE) != MPI_SUCCESS)
        return GLPGP_FAIL(GLPGP_ERR_IO, "MPI_Recv of the mesh part failed");
    if (hdr[0] < 0) return GLPGP_FAIL(GLPGP_ERR_IO, "rank 0 failed to send this rank's part of the mesh");
    glpgp_status st = GLPGP_OK;
    glpgp_mesh *m = NULL;
    const int nv = hdr[0], nt = hdr[1];
    GLPGP_CHECK(glpgp_mesh_part_create(nv, nt, hdr[6] != 0, &m));
    glpgp_mesh_part *pt = m->part;
    int rc = MPI_Recv(m->xy, 2 * nv, MPI_DOUBLE, 0, TAG_MESH, cw, MPI_STATUS_IGNORE);
    if (rc == MPI_SUCCESS) rc = MPI_Recv(m->tri, 3 * nt, MPI_INT, 0, TAG_MESH, cw, MPI_STATUS_IGNORE);
    if (rc == MPI_SUCCESS) rc = MPI_Recv(m->on_boundary, nv, MPI_UNSIGNED_CHAR, 0, TAG_MESH, cw, MPI_STATUS_IGNORE);
    if (rc == MPI_SUCCESS) rc = MPI_Recv(m->normal_prev, 2 * nv, MPI_DOUBLE, 0, TAG_MESH, cw, MPI_STATUS_IGNORE);
    if (rc == MPI_SUCCESS) rc = MPI_Recv(m->normal_next, 2 * nv, MPI_DOUBLE, 0, TAG_MESH, cw, MPI_STATUS_IGNORE);
    if (rc == MPI_SUCCESS) rc = MPI_Recv(pt->gid, nv, MPI_INT, 0, TAG_MESH, cw, MPI_STATUS_IGNORE);
    if (rc == MPI_SUCCESS && pt->size) rc = MPI_Recv(pt->size, 2 * nv, MPI_DOUBLE, 0, TAG_MESH, cw, MPI_STATUS_IGNORE);
    if (rc != MPI_SUCCESS) {
        st = GLPGP_FAIL(GLPGP_ERR_IO, "MPI_Recv of the mesh part failed");
        goto fail;
    }
    pt->nv_owned = hdr[2];
    pt->first = hdr[3];
    pt->nv_global = hdr[4];
    pt->nt_global = hdr[5];
    m->area = sc[0];
    memcpy(m->bbox, sc + 1, sizeof m->bbox);
    m->mean_edge = sc[5];
    pt->center[0] = sc[6];
    pt->center[1] = sc[7];
    pt->size_opt = sc[8];
    *out = m;
    return GLPGP_OK;
fail:
    glpgp_mesh_destroy(&m);
    return st;
}

static glpgp_status m_gather_bytes(const void *mine, size_t bytes, void *out)
{
    const int P = glpgp_petsc_m_size(), r = glpgp_petsc_m_rank();
    if (bytes > (size_t)INT_MAX) return GLPGP_FAIL(GLPGP_ERR_LIMIT, "gather of %zu bytes from one rank", bytes);
    int n = (int)bytes, *cnt = NULL, *dsp = NULL;
    if (r == 0) {
        GLPGP_CHECK(glpgp_malloc((size_t)P, sizeof(int), &cnt));
        glpgp_status st = glpgp_malloc((size_t)P, sizeof(int), &dsp);
        if (st != GLPGP_OK) {
            free(cnt);
            return st;
        }
    }
    int rc = MPI_Gather(&n, 1, MPI_INT, cnt, 1, MPI_INT, 0, PETSC_COMM_WORLD);
    if (rc == MPI_SUCCESS && r == 0) {
        long long at = 0;
        for (int q = 0; q < P; q++) {
            dsp[q] = (int)at;
            at += cnt[q];
        }
        if (at > INT_MAX) rc = MPI_ERR_COUNT; /* the other ranks still take part below */
    }
    int rc2 = MPI_Gatherv(mine, n, MPI_BYTE, out, cnt, dsp, MPI_BYTE, 0, PETSC_COMM_WORLD);
    free(cnt);
    free(dsp);
    if (rc != MPI_SUCCESS || rc2 != MPI_SUCCESS) return GLPGP_FAIL(GLPGP_ERR_IO, "MPI_Gatherv to rank 0 failed");
    return GLPGP_OK;
}

static const glpgp_petsc_api g_api = {GLPGP_PETSC_ABI, glpgp_petsc_m_init,      m_finalize,  glpgp_petsc_m_rank,         glpgp_petsc_m_size,
                                      glpgp_petsc_m_create,        m_all_ok,    m_gather,    m_max_rss,      glpgp_petsc_m_local_info,
                                      m_mesh_send,     m_mesh_recv, m_gather_bytes};

/* glue (petsc_glue.c) */
int glpgp_petsc_glue_init(const glpgp_petsc_host *host);

__attribute__((visibility("default"))) const glpgp_petsc_api *glpgp_petsc_module_entry(const glpgp_petsc_host *host)
{
    if (!glpgp_petsc_glue_init(host)) return NULL;
    return &g_api;
}
