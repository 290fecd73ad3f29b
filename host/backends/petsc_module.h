/* backends/petsc_module.h: private to the backends layer: the interface
 * between glpgp and the dlopen'd PETSc backend module glpgp_petsc.so
 * (backends/petsc.c + backends/petsc_glue.c, loaded by backends/petsc_load.c
 * only when `--backend petsc` is chosen, so a glpgp that never uses it never
 * loads PETSc, MPI and their ~100 shared libraries).
 *
 * The loader hands the module a table of the few glpgp functions it calls
 * (error record, log); the module returns its table. Both carry
 * GLPGP_PETSC_ABI and the sizes of the shared structs, so a module of another
 * build is refused with one line. */
#ifndef GLPGP_PETSC_MODULE_H
#define GLPGP_PETSC_MODULE_H

#include "glpgp/backend.h"

#define GLPGP_PETSC_ABI 4
#define GLPGP_PETSC_ENTRY "glpgp_petsc_module_entry"

/* glpgp -> module (the loader's table: error record, log, part create / destroy) */
typedef struct glpgp_petsc_host {
    int abi;
    size_t sizeof_system, sizeof_backend, sizeof_ops, sizeof_mesh, sizeof_part;
    glpgp_status (*error_set)(const char *file, int line, glpgp_status st, const char *fmt, ...);
    void (*push_trace)(const char *file, int line);
    void (*log_msg)(glpgp_log_level level, const char *msg);
    glpgp_status (*mesh_part_create)(int nv, int nt, int sized, glpgp_mesh **out); /* a part to receive */
    void (*mesh_destroy)(glpgp_mesh **m); /* a received part that failed half-way */
} glpgp_petsc_host;

/* module -> glpgp */
typedef struct glpgp_petsc_api {
    int abi;
    /* MPI_Init + PetscInitialize (options from $PETSC_OPTIONS); idempotent */
    glpgp_status (*init)(void);
    /* PetscFinalize + MPI_Finalize (when init ran) */
    void (*finalize)(void);
    int (*rank)(void);
    int (*size)(void);
    /* a backend on PETSC_COMM_WORLD; precond: GLPGP_PRECOND_* of the linear solves */
    glpgp_status (*create)(int precond, glpgp_backend **out);
    /* logical AND of ok over the ranks (every rank must call it) */
    int (*all_ok)(int ok);
    /* per-rank numbers to rank 0: out[r * n + k] <- vals[k] of rank r (out: size*n, rank 0 only) */
    void (*gather)(const double *vals, int n, double *out);
    /* the whole-process peak resident set of this rank (bytes) */
    double (*max_rss)(void);
    /* owned and ghost vertices of backend b on this rank (b: this module's, set up) */
    void (*local_info)(const glpgp_backend *b, int *owned, int *ghosts);
    /* rank 0: send the part m (glpgp_mesh_extract_part) to rank dest; m NULL:
     * rank 0 failed, dest's mesh_recv fails */
    glpgp_status (*mesh_send)(const glpgp_mesh *m, int dest);
    /* a rank other than 0: *out <- the part rank 0 sent it (free: glpgp_mesh_destroy) */
    glpgp_status (*mesh_recv)(glpgp_mesh **out);
    /* every rank: bytes of mine to rank 0, where out (rank 0 only) receives
     * them all back to back in rank order */
    glpgp_status (*gather_bytes)(const void *mine, size_t bytes, void *out);
} glpgp_petsc_api;

typedef const glpgp_petsc_api *(*glpgp_petsc_entry_fn)(const glpgp_petsc_host *host);

#endif
