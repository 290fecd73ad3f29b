/* io/distributed.c: the distributed solve on MPI ranks with the PETSc
 * backend (glpgp/distributed.h): the mesh renumbered for the ranks, rank 0's
 * whole-mesh work and verdict, the parts sent, the solve, the per-rank
 * numbers, the result gathered to rank 0 or written as pieces, and the
 * collective verdicts that keep every rank's outcome the same. */
#include "glpgp/distributed.h"
#include "glpgp/backends.h"
#include "glpgp/util.h"
#include "glpgp/internal/newton.h"

#include <stdlib.h>
#include <string.h>

struct glpgp_dist {
    glpgp_dist_options opt;
    int split;           /* the ranks split the mesh */
    int renumber;        /* the mesh is renumbered for the ranks */
    int root, nranks;
    int announced;       /* rank 0's verdict on its input given (split runs) */
    int verdict_pending; /* pieces: this rank still owes the verdict on them */
    double *okv;         /* rank 0: every rank's verdict on its pieces */
    double *rank_info;   /* rank 0: ranks x GLPGP_RANK_INFO_N */
    double build_s;
};

glpgp_status glpgp_dist_create(const glpgp_options *o, const glpgp_dist_options *opt, glpgp_dist **out)
{
    if (!o || !opt || !out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_dist_create: NULL argument");
    *out = NULL;
    glpgp_dist *d = NULL;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *d, &d));
    d->opt = *opt;
    d->nranks = glpgp_petsc_size();
    d->root = glpgp_petsc_rank() == 0;
    /* per-vertex input files keep the input's numbering; a cross field and
     * a size function need the whole mesh */
    d->renumber = d->nranks > 1 && o->field != GLPGP_FIELD_FILE && o->field != GLPGP_FIELD_CROSS &&
                  o->size_field != GLPGP_SIZE_FILE;
    d->split = d->renumber && o->size_field != GLPGP_SIZE_FUNC;
    d->announced = !d->split || !d->root;
    *out = d;
    return GLPGP_OK;
}

int glpgp_dist_splits(const glpgp_dist *d) { return d && d->split; }
int glpgp_dist_reads(const glpgp_dist *d) { return !d || !d->split || d->root; }

const double *glpgp_dist_rank_info(const glpgp_dist *d, int *nranks)
{
    *nranks = d && d->rank_info ? d->nranks : 0;
    return d ? d->rank_info : NULL;
}

double glpgp_dist_build_seconds(const glpgp_dist *d) { return d ? d->build_s : 0.0; }

/* *mp <- m renumbered for P ranks: rank r owns the vertices [r nv / P,
 * (r+1) nv / P) of the backend's rows, filled with the part r of a
 * recursive coordinate bisection (input order kept within a part) */
static glpgp_status partition_mesh(const glpgp_mesh *m, int P, glpgp_mesh **mp, int **new_of_old)
{
    glpgp_status st = GLPGP_OK;
    int *size = NULL, *part = NULL, *next = NULL;
    *mp = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)m->nv, sizeof(int), new_of_old));
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)P, sizeof(int), &size), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)P, sizeof(int), &next), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)m->nv, sizeof(int), &part), done);
    for (int r = 0; r < P; r++) {
        next[r] = (int)((long long)m->nv * r / P);
        size[r] = (int)((long long)m->nv * (r + 1) / P) - next[r];
    }
    GLPGP_CHECK_GOTO(st, glpgp_mesh_partition(m, P, size, part), done);
    for (int i = 0; i < m->nv; i++) (*new_of_old)[i] = next[part[i]]++;
    GLPGP_CHECK_GOTO(st, glpgp_mesh_renumber(m, *new_of_old, mp), done);
done:
    free(size);
    free(next);
    free(part);
    return st;
}

/* Rank 0 of a split run: what needs the whole renumbered mesh mp (the local
 * size field and its check, the radial field's center). The other ranks
 * wait for the verdict announced after it. */
static glpgp_status split_prepare(const glpgp_dist *d, const glpgp_options *o, const glpgp_mesh *mp, double **size,
                                  double center[2])
{
    *size = NULL;
    const double h = o->size > 0.0 ? o->size : glpgp_default_size(mp, o);
    if (d->opt.gather && mp->nv > d->opt.gather_max)
        return GLPGP_FAIL(GLPGP_ERR_LIMIT,
                          "%d vertices: above --gather-max %d for gathering the result to rank 0 (needed by "
                          "--out .vtu/.vtk/.obj, --quads, --image): write --out FILE.pvtu (a piece per rank) "
                          "or raise --gather-max",
                          mp->nv, d->opt.gather_max);
    /* the local resolution of the whole mesh (glpgp_solve skips it on a part) */
    GLPGP_CHECK(glpgp_options_check_mesh(o, mp));
    GLPGP_CHECK(glpgp_size_check_mesh(mp, o, h));
    /* the field where the size field reads it (the boundary), the centroid;
     * the sizes of both oscillators (NULL when uniform) */
    double *u = NULL, *sz = NULL;
    int uniform = 1;
    glpgp_status st = glpgp_malloc((size_t)2 * mp->nv, sizeof(double), &u);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)2 * mp->nv, sizeof(double), &sz);
    if (st == GLPGP_OK) {
        glpgp_field_presolve(mp, o, u, center);
        glpgp_options oc = *o;
        if (oc.field == GLPGP_FIELD_RADIAL && !oc.has_center) {
            oc.center[0] = center[0];
            oc.center[1] = center[1];
            oc.has_center = 1;
        }
        st = glpgp_size_compute(mp, &oc, h, u, sz, &uniform);
    }
    free(u);
    if (st == GLPGP_OK && !uniform) *size = sz;
    else free(sz);
    return st;
}

/* Rank 0: every other rank's part sent (after a failure the remaining ranks
 * get the NULL part: their receive fails, none waits), its own in *mine. */
static glpgp_status split_send(const glpgp_dist *d, const glpgp_options *o, const glpgp_mesh *mp, const double *size,
                               const double center[2], glpgp_mesh **mine)
{
    const int P = d->nranks;
    *mine = NULL;
    glpgp_status st = GLPGP_OK;
    for (int q = 1; q < P; q++) {
        glpgp_mesh *pq = NULL;
        if (st == GLPGP_OK) st = glpgp_mesh_extract_part(mp, P, q, size, center, o->size, &pq);
        glpgp_status sst = glpgp_petsc_mesh_send(st == GLPGP_OK ? pq : NULL, q);
        glpgp_mesh_destroy(&pq);
        if (st == GLPGP_OK) st = sst;
    }
    GLPGP_CHECK(st);
    return glpgp_mesh_extract_part(mp, P, 0, size, center, o->size, mine);
}

/* The whole result on rank 0 from the parts' results (rl: this rank's, of
 * its part pm): the per-vertex arrays of the owned vertices gathered in rank
 * order (the renumbered mesh's order), the scalars (global already) copied;
 * *out (rank 0, of nv vertices and nt triangles) then summarised by the
 * caller. Every rank calls it. */
static glpgp_status gather_result(const glpgp_result *rl, const glpgp_mesh *pm, int nv, int nt, glpgp_result **out)
{
    *out = NULL;
    const int root = glpgp_petsc_rank() == 0;
    const size_t n = (size_t)pm->part->nv_owned;
    glpgp_result *rw = NULL;
    if (root) {
        GLPGP_CHECK(glpgp_result_create(nv, nt, &rw));
        glpgp_result keep = *rw;
        *rw = *rl; /* the scalars and statistics */
        rw->nv = keep.nv;
        rw->nt = keep.nt;
        rw->field = keep.field;
        rw->cross = NULL;
        for (int k = 0; k < 2; k++) {
            rw->osc[k].z = keep.osc[k].z;
            rw->osc[k].dirichlet = keep.osc[k].dirichlet;
            rw->osc[k].singular = keep.osc[k].singular;
        }
    }
    glpgp_status st = glpgp_petsc_gather_bytes(rl->field, 2 * n * sizeof(double), root ? rw->field : NULL);
    for (int k = 0; k < 2 && st == GLPGP_OK; k++) {
        st = glpgp_petsc_gather_bytes(rl->osc[k].z, 2 * n * sizeof(double), root ? rw->osc[k].z : NULL);
        if (st == GLPGP_OK)
            st = glpgp_petsc_gather_bytes(rl->osc[k].dirichlet, n, root ? rw->osc[k].dirichlet : NULL);
    }
    if (st != GLPGP_OK) {
        glpgp_result_destroy(&rw);
        return st;
    }
    *out = rw;
    return GLPGP_OK;
}

/* Pieces: every rank's verdict on its files (ok: its output set prepared),
 * gathered to rank 0, which names the first rank that failed. Returns the
 * verdict agreed by all ranks (1: every rank commits). Every rank calls it. */
static int pieces_verdict(glpgp_dist *d, int ok)
{
    const double mine = ok ? 1.0 : 0.0;
    d->verdict_pending = 0;
    glpgp_petsc_gather(&mine, 1, d->root ? d->okv : NULL);
    if (d->root && ok)
        for (int q = 1; q < d->nranks; q++)
            if (d->okv[q] == 0.0) {
                char piece[4096];
                if (glpgp_pvtu_piece_path(d->opt.pvtu, q, piece, sizeof piece) != GLPGP_OK) piece[0] = '\0';
                GLPGP_FAIL(GLPGP_ERR_IO, "MPI rank %d could not write its piece '%s' (no output was written)", q,
                           piece);
                ok = 0;
                break;
            }
    return glpgp_petsc_all_ok(ok);
}

/* Every rank's verdict on st (the same everywhere: a rank that failed alone
 * fails all); why: the message of a rank whose own step succeeded. */
static glpgp_status agree(glpgp_status st, glpgp_status other, const char *why)
{
    if (glpgp_petsc_all_ok(st == GLPGP_OK)) return GLPGP_OK;
    if (st == GLPGP_OK) return glpgp_error_set(__FILE__, __LINE__, other, "%s", why);
    glpgp_error_push_trace(__FILE__, __LINE__);
    return st;
}

/* Per-rank sizes, time and memory gathered to rank 0. */
static glpgp_status rank_numbers(glpgp_dist *d, const glpgp_backend *b, const glpgp_result *r)
{
    int owned = 0, ghosts = 0;
    glpgp_petsc_backend_info(b, &owned, &ghosts);
    const double mine[GLPGP_RANK_INFO_N] = {owned, ghosts, r->seconds_total, glpgp_petsc_max_rss()};
    /* an allocation failure on one rank is every rank's, so no rank waits in the gather alone */
    GLPGP_CHECK(agree(glpgp_malloc((size_t)d->nranks * GLPGP_RANK_INFO_N, sizeof(double), &d->rank_info),
                      GLPGP_ERR_NOMEM, "out of memory on another MPI rank"));
    glpgp_petsc_gather(mine, GLPGP_RANK_INFO_N, d->rank_info);
    if (!d->root) {
        free(d->rank_info);
        d->rank_info = NULL;
    }
    return GLPGP_OK;
}

/* A split run after the solve: the pieces into outs, the whole result to
 * rank 0 when gathered; a rank other than 0 commits its piece with the
 * others and is done (*finished). r: this rank's part's result in, the
 * gathered one out on rank 0. */
static glpgp_status split_outputs(glpgp_dist *d, glpgp_mesh **part, const glpgp_mesh *m, const glpgp_options *o,
                                  glpgp_output_set *outs, glpgp_result **r, int *finished)
{
    glpgp_status pst = GLPGP_OK;
    if (d->opt.pvtu) { /* written under temporary names; committed by every rank once all agree */
        if (d->root) pst = glpgp_malloc((size_t)d->nranks, sizeof(double), &d->okv);
        if (pst == GLPGP_OK) pst = glpgp_output_set_result_piece(outs, *part, o, *r, d->opt.pvtu, glpgp_petsc_rank());
        if (pst == GLPGP_OK && d->root) pst = glpgp_output_set_pvtu(outs, *r, d->opt.pvtu, d->nranks);
    }
    if (d->opt.gather) {
        glpgp_result *rw = NULL;
        GLPGP_CHECK(agree(gather_result(*r, *part, d->root ? m->nv : 0, d->root ? m->nt : 0, &rw), GLPGP_ERR_IO,
                          "gathering the result failed on another MPI rank"));
        if (d->root) {
            glpgp_result_destroy(r);
            *r = rw;
        }
    }
    glpgp_mesh_destroy(part);
    d->verdict_pending = d->opt.pvtu != NULL;
    if (d->root) {
        if (pst != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
        return pst; /* its verdict on the pieces comes with the commit */
    }
    *finished = 1;
    if (d->opt.pvtu) {
        if (pst == GLPGP_OK) pst = glpgp_output_set_prepare(outs);
        if (!pieces_verdict(d, pst == GLPGP_OK)) {
            if (pst == GLPGP_OK) GLPGP_FAIL(GLPGP_ERR_IO, "another MPI rank could not write its files");
            return pst == GLPGP_OK ? GLPGP_ERR_IO : pst;
        }
        GLPGP_CHECK(agree(glpgp_output_set_commit(outs), GLPGP_ERR_IO, "another MPI rank could not commit"));
    }
    return GLPGP_OK;
}

/* Rank 0 of a split run: the whole-mesh work, its verdict, the parts; then
 * only m stays whole here (its arrays released when nothing is gathered). */
static glpgp_status split_root(glpgp_dist *d, glpgp_mesh *m, glpgp_mesh **mp, int **new_of_old,
                               const glpgp_options *o, glpgp_mesh **part)
{
    double *size = NULL, center[2] = {0.0, 0.0};
    glpgp_status st = split_prepare(d, o, *mp, &size, center);
    d->announced = 1;
    if (!glpgp_petsc_all_ok(st == GLPGP_OK)) {
        free(size);
        if (st == GLPGP_OK) st = GLPGP_FAIL(GLPGP_ERR_ARG, "another MPI rank failed");
        return st;
    }
    st = split_send(d, o, *mp, size, center, part);
    free(size);
    GLPGP_CHECK(st);
    glpgp_mesh_destroy(mp);
    if (!d->opt.gather) {
        /* no gathered output: rank 0 keeps of the whole mesh only the counts
         * and scalars the summary and the statistics report (1M vertices,
         * --precond jacobi --newton-max 1 --cg-max 50, 2 ranks: rank 0
         * 619 -> 571 MiB, rank 1 554) */
        glpgp_mesh_release_arrays(m);
        free(*new_of_old);
        *new_of_old = NULL;
    }
    return GLPGP_OK;
}

/* Before the solve: the part (split runs: received, or rank 0's after its
 * work) or the renumbered whole mesh; the backend. */
static glpgp_status setup(glpgp_dist *d, glpgp_mesh *m, glpgp_options *o, glpgp_mesh **mp, glpgp_mesh **part,
                          int **new_of_old, glpgp_backend **b)
{
    if (d->split && !d->root) {
        d->announced = 1;
        if (!glpgp_petsc_all_ok(1)) return GLPGP_FAIL(GLPGP_ERR_ARG, "MPI rank 0 failed before the solve");
        GLPGP_CHECK(glpgp_petsc_mesh_recv(part));
        o->size = (*part)->part->size_opt; /* rank 0's (set by the refinement) */
    } else if (!m) {
        return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_solve_distributed: no mesh on a rank that reads it");
    }
    const double tb = glpgp_now();
    GLPGP_CHECK(glpgp_backend_create_petsc(o->precond, b));
    d->build_s = glpgp_now() - tb;
    /* the vertices renumbered so that each rank's rows are a compact region;
     * the result comes back in the input's vertex order (otherwise
     * glpgp_solve renumbers for memory locality; a split mesh keeps that order) */
    if (d->renumber && (d->root || !d->split)) GLPGP_CHECK(partition_mesh(m, d->nranks, mp, new_of_old));
    if (*new_of_old) o->vertex_order = GLPGP_ORDER_INPUT;
    if (d->split && d->root) GLPGP_CHECK(split_root(d, m, mp, new_of_old, o, part));
    return GLPGP_OK;
}

glpgp_status glpgp_solve_distributed(glpgp_dist *d, glpgp_mesh *m, glpgp_options *o, glpgp_output_set *outs,
                                     glpgp_result **out, int *finished)
{
    if (!d || !o || !outs || !out || !finished) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_solve_distributed: NULL argument");
    *out = NULL;
    *finished = 0;
    glpgp_mesh *mp = NULL, *part = NULL;
    int *new_of_old = NULL;
    glpgp_backend *b = NULL;
    glpgp_result *r = NULL;
    glpgp_status st = setup(d, m, o, &mp, &part, &new_of_old, &b);
    if (st == GLPGP_OK) {
        st = agree(glpgp_solve(d->split ? part : mp ? mp : m, b, o, &r), GLPGP_ERR_NUMERIC,
                   "the solve failed on another MPI rank");
    }
    if (st == GLPGP_OK) st = rank_numbers(d, b, r);
    if (st == GLPGP_OK && d->split) st = split_outputs(d, &part, m, o, outs, &r, finished);
    /* back to the input's vertex order; a gathered result: its singular
     * triangles and |z| statistics on the whole mesh (recomputed) */
    if (st == GLPGP_OK && !*finished && new_of_old && (!d->split || d->opt.gather)) {
        st = glpgp_result_permute_vertices(r, new_of_old);
        for (int k = 0; k < 2 && st == GLPGP_OK && d->split; k++) st = glpgp_osc_summarize(m, &r->osc[k]);
    }
    /* pieces of a run that does not split: rank 0's whole mesh as the one piece */
    if (st == GLPGP_OK && !d->split && d->root && d->opt.pvtu) {
        st = glpgp_output_set_result_piece(outs, m, o, r, d->opt.pvtu, 0);
        if (st == GLPGP_OK) st = glpgp_output_set_pvtu(outs, r, d->opt.pvtu, 1);
    }
    glpgp_backend_destroy(&b);
    glpgp_mesh_destroy(&mp);
    glpgp_mesh_destroy(&part);
    free(new_of_old);
    if (st != GLPGP_OK) {
        glpgp_result_destroy(&r);
        glpgp_error_push_trace(__FILE__, __LINE__);
        return st;
    }
    *out = r;
    return GLPGP_OK;
}

glpgp_status glpgp_dist_commit(glpgp_dist *d, glpgp_output_set *outs)
{
    if (!d || !d->verdict_pending) return glpgp_output_set_commit(outs);
    const glpgp_status pst = glpgp_output_set_prepare(outs);
    if (!pieces_verdict(d, pst == GLPGP_OK)) {
        if (pst != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
        return pst != GLPGP_OK ? pst : GLPGP_ERR_IO; /* rank 0 named the rank that failed */
    }
    return agree(glpgp_output_set_commit(outs), GLPGP_ERR_IO, "another MPI rank could not rename its piece into place");
}

void glpgp_dist_destroy(glpgp_dist **dp)
{
    if (!dp || !*dp) return;
    glpgp_dist *d = *dp;
    if (!d->announced) glpgp_petsc_all_ok(0); /* the other ranks wait for rank 0's verdict */
    if (d->verdict_pending) pieces_verdict(d, 0); /* ... or for the verdict on the pieces */
    free(d->okv);
    free(d->rank_info);
    free(d);
    *dp = NULL;
}
