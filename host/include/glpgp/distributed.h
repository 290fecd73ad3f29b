/* glpgp/distributed.h: a solve on several MPI ranks with the PETSc backend
 * (issue 30, item 4), as a library entry point: every rank calls the same
 * functions after glpgp_petsc_init (glpgp/backends.h):
 *
 *     glpgp_dist *d = NULL;
 *     glpgp_dist_options dopt = {.gather = 1, .gather_max = 1 << 24};
 *     st = glpgp_dist_create(&o, &dopt, &d);
 *     // rank 0 (or every rank when !glpgp_dist_splits(d)): read the mesh m
 *     st = glpgp_output_set_create(&outs);          // every rank (pieces)
 *     st = glpgp_solve_distributed(d, m, &o, outs, &r, &finished);
 *     // rank 0: add its other files to outs; a rank with finished set is done
 *     st = glpgp_dist_commit(d, outs);              // every rank's files or none
 *     glpgp_dist_destroy(&d);                       // after a failure: tells the others
 *
 * Split runs (glpgp_dist_splits: several ranks, no per-vertex input file, no
 * cross field, no size function): rank 0 renumbers the mesh by recursive
 * coordinate bisection, computes what needs the whole mesh (the local size
 * field, the radial center), announces its verdict and sends every rank its
 * part; after the solve the result is gathered to rank 0 in the input's
 * vertex order (gather) and/or every rank writes its piece of a .pvtu
 * (pvtu; a run that does not split: rank 0 writes the whole mesh as one
 * piece); the pieces and rank 0's files are committed together once every
 * rank has prepared its own (a failure anywhere leaves no file). Otherwise
 * (one rank, or per-vertex inputs) every rank holds the whole mesh and the
 * result comes back in the input's order. A failure on any rank fails every
 * rank (collective verdicts: no rank waits in a collective the others never
 * reach). Layer: io. */
#ifndef GLPGP_DISTRIBUTED_H
#define GLPGP_DISTRIBUTED_H

#include "glpgp/io.h"
#include "glpgp/solve.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct glpgp_dist_options {
    int gather;       /* rank 0 needs the whole result (outputs other than pieces) */
    int gather_max;   /* most vertices gathered to rank 0 (GLPGP_ERR_LIMIT above) */
    const char *pvtu; /* a .pvtu: every rank writes its piece into the output set (NULL: none) */
} glpgp_dist_options;

typedef struct glpgp_dist glpgp_dist;

/* One rank's state of a distributed solve of options o (the same on every
 * rank). */
glpgp_status glpgp_dist_create(const glpgp_options *o, const glpgp_dist_options *opt, glpgp_dist **out);
/* Whether the ranks split the mesh (rank 0 alone reads it). */
int glpgp_dist_splits(const glpgp_dist *d);
/* Whether this rank reads the input (rank 0, or every rank of a run that
 * does not split). */
int glpgp_dist_reads(const glpgp_dist *d);

/* The solve (see the top): m is this rank's whole mesh (rank 0 of a split
 * run may see its arrays released when nothing is gathered; NULL on the
 * other ranks of a split run); o->size is set from rank 0's on those ranks.
 * *out: the result (rank 0: the whole one in m's vertex order when gathered
 * or not split; else this rank's part's, with the global counts and |z|
 * statistics). *finished = 1 on a rank other than 0 of a split run, whose
 * part of the work (its piece committed with the others) is then done. */
glpgp_status glpgp_solve_distributed(glpgp_dist *d, glpgp_mesh *m, glpgp_options *o, glpgp_output_set *outs,
                                     glpgp_result **out, int *finished);

/* Commit outs: with pieces, once every rank has prepared its files (rank 0
 * names the first rank that failed), by every rank; otherwise a plain
 * commit. */
glpgp_status glpgp_dist_commit(glpgp_dist *d, glpgp_output_set *outs);

/* Per-rank numbers on rank 0 (ranks x GLPGP_RANK_INFO_N: owned and ghost
 * vertices, solve seconds, max RSS bytes; NULL before the solve), their
 * rank count, and the backend's creation time on this rank. */
const double *glpgp_dist_rank_info(const glpgp_dist *d, int *nranks);
double glpgp_dist_build_seconds(const glpgp_dist *d);

/* Free d; a verdict this rank still owes (rank 0's on its input, the one on
 * the pieces) is given as a failure first, so that no rank waits (NULL ok). */
void glpgp_dist_destroy(glpgp_dist **d);

#ifdef __cplusplus
}
#endif

#endif
