/* glpgp/backends.h: the implementations of the backend table
 * (glpgp/backend.h): the scalar C reference backend and the OpenCL backend,
 * the one backend selector every command uses (auto: OpenCL, falling back to
 * the reference backend with one warning), the OpenCL device list, the
 * backend-independent matrix probe, and the cross-check engine (OpenCL
 * against the reference, stage by stage, into a table). Layer: backends. */
#ifndef GLPGP_BACKENDS_H
#define GLPGP_BACKENDS_H

#include "glpgp/backend.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The scalar C reference backend (single-threaded, no OpenCL). */
glpgp_status glpgp_backend_create_reference(glpgp_backend **out);

/* OpenCL backend options. */
typedef struct glpgp_cl_options {
    int device;        /* global device index as listed by `glpgp devices`; -1: GLPGP_DEVICE env, else the
                          first GPU with fp64, else the first device with fp64 */
    int verbose;       /* log the chosen device (GLPGP_LOG_INFO) */
    const int *stop;   /* NULL, or a flag another thread may set (atomically) while the backend is
                          created in the background: the first launches of the kernels
                          (warm-up after the program build) then end early and the creation
                          fails with GLPGP_ERR_ARG "stopped" (the caller no longer needs it) */
} glpgp_cl_options;
/* Create the OpenCL backend (GLPGP_ERR_OPENCL / GLPGP_ERR_UNSUPPORTED with a
 * clear message when no platform/device/fp64 is available). */
glpgp_status glpgp_backend_create_opencl(const glpgp_cl_options *opt, glpgp_backend **out);
/* Whether this build has OpenCL support compiled in. */
int glpgp_have_opencl(void);

/* Which backend glpgp_backend_select creates. */
typedef enum glpgp_backend_kind {
    GLPGP_BACKEND_AUTO = 0,  /* OpenCL when usable, else reference (one warning) */
    GLPGP_BACKEND_OPENCL,    /* OpenCL or an error */
    GLPGP_BACKEND_REFERENCE, /* the scalar C reference */
    GLPGP_BACKEND_PETSC      /* PETSc on MPI ranks (glpgp_backend_create_petsc) */
} glpgp_backend_kind;

/* Parse "auto", "opencl", "reference", "petsc" (-1 when unknown). */
int glpgp_backend_kind_parse(const char *name);

/* The one backend selector. device >= 0 asks for that OpenCL device: with
 * AUTO its failure is then an error, not a fallback. With AUTO and no usable
 * OpenCL device, the reference backend is created and a warning logged
 * ("OpenCL backend unavailable (...); using the reference backend").
 * verbose: log the chosen OpenCL device. */
glpgp_status glpgp_backend_select(glpgp_backend_kind kind, int device, int verbose,
                                  glpgp_backend **out);
/* glpgp_backend_select with glpgp_cl_options.stop (NULL: the same): for a
 * backend created in a thread while the caller reads its input. */
glpgp_status glpgp_backend_select_stoppable(glpgp_backend_kind kind, int device, int verbose, const int *stop,
                                            glpgp_backend **out);

/* ---- PETSc backend (backends/petsc.c, a dlopen'd module glpgp_petsc.so) ----
 * Every rank runs the same driver (glpgp_solve); the backend distributes the
 * rows: rank r owns a contiguous block of the global vertex numbering. The
 * mesh the driver gets is either one rank's part (glpgp_mesh.part: owned
 * vertices plus one ghost layer, sent by rank 0 with glpgp_petsc_mesh_send)
 * or the whole mesh on every rank (rank r owning [r nv / P, (r+1) nv / P)).
 * Its vectors are PETSc Vecs of the owned rows, and every element op runs
 * the per-row bodies of kernels/rows.h (the reference arithmetic) on the
 * owned rows after a ghost exchange. Scalars are summed in rank order, so
 * every rank takes the same decisions; vec_read returns the owned and ghost
 * values of a part (the whole vector of a whole mesh). Linear solves:
 * precond AMG, glpgp's aggregation multigrid on each rank's rows (the amg_*
 * ops; block Jacobi across ranks) under the drivers' flexible CG, or with
 * -glpgp_mg gamg KSPCG + PCGAMG with the near null space [z, iz] (op
 * linear_solve); precond Jacobi, the drivers' block-Jacobi CG. PETSc options
 * come from $PETSC_OPTIONS (-ksp_view, ...). */

/* Whether this build has the PETSc module. */
int glpgp_have_petsc(void);
/* Load the module, MPI_Init and PetscInitialize (idempotent). Without PETSc
 * in the build: GLPGP_ERR_UNSUPPORTED, "glpgp was built without PETSc
 * (install petsc-dev and rebuild)". */
glpgp_status glpgp_petsc_init(void);
/* PetscFinalize and MPI_Finalize when glpgp_petsc_init ran (NULL-safe). */
void glpgp_petsc_finalize(void);
/* This process's rank and the number of ranks (0 and 1 before init). */
int glpgp_petsc_rank(void);
int glpgp_petsc_size(void);
/* 1 when ok is non-zero on every rank (collective; ok itself before init). */
int glpgp_petsc_all_ok(int ok);
/* out[r * n + k] <- vals[k] of rank r, on rank 0 (collective; out: size * n). */
void glpgp_petsc_gather(const double *vals, int n, double *out);
/* Owned and ghost vertices of this rank in the PETSc backend b (0, 0 for
 * another backend or before setup). */
void glpgp_petsc_backend_info(const glpgp_backend *b, int *owned, int *ghosts);
/* Peak resident set of this process, bytes (0 before init). */
double glpgp_petsc_max_rss(void);
/* Distributed meshes (glpgp_mesh.part): rank 0 sends rank dest its part
 * (glpgp_mesh_extract_part; NULL: rank 0 failed, dest's receive fails);
 * every other rank receives its own (*out, free with glpgp_mesh_destroy). */
glpgp_status glpgp_petsc_mesh_send(const glpgp_mesh *m, int dest);
glpgp_status glpgp_petsc_mesh_recv(glpgp_mesh **out);
/* Every rank: `bytes` bytes of mine to rank 0, whose out (NULL elsewhere)
 * receives all ranks' back to back in rank order. */
glpgp_status glpgp_petsc_gather_bytes(const void *mine, size_t bytes, void *out);
/* The PETSc backend (init first if needed); precond: GLPGP_PRECOND_* of its
 * linear solves (glpgp/solve.h), or GLPGP_PETSC_PRECOND_GAMG: KSPCG + GAMG
 * whatever -glpgp_mg says (the bench's anchor). */
#define GLPGP_PETSC_PRECOND_GAMG 100
glpgp_status glpgp_backend_create_petsc(int precond, glpgp_backend **out);

/* One OpenCL device, as listed by `glpgp devices`. */
typedef struct glpgp_device_info {
    int index;            /* global index (for --device and GLPGP_DEVICE) */
    int platform_index;
    char platform[256], platform_vendor[256], platform_version[256];
    char name[256], vendor[256], version[256];
    unsigned compute_units;
    unsigned long long global_mem; /* bytes */
    int fp64;
    const char *type;     /* "GPU", "CPU", "accelerator", "other" */
    int is_default;       /* the device used when none is asked for (no --device, no
                             GLPGP_DEVICE): the first fp64 GPU, else the first fp64 device */
} glpgp_device_info;

/* Every device of every platform (*out: malloc'ed, free() it). No OpenCL in
 * the build -> GLPGP_ERR_UNSUPPORTED; no platform -> GLPGP_ERR_OPENCL. */
glpgp_status glpgp_devices_list(glpgp_device_info **out, int *n);

/* Describe an OpenCL backend ("device N: name (shape ...)") into buf;
 * returns its device index, or -1 (buf: "none") if b is not an OpenCL
 * backend or the build has no OpenCL. */
int glpgp_cl_backend_info(const glpgp_backend *b, char *buf, size_t len);
/* The OpenCL backend's device lines (what glpgp_cl_options.verbose logs at
 * creation: device, launch shape, program build seconds); nothing for
 * another backend. */
void glpgp_cl_backend_log(const glpgp_backend *b);

/* (the exact matrix read-back of the cross-check, glpgp_probe_matrix: glpgp/internal/probe.h) */

/* ---- cross-check engine (backends/crosscheck.c) ----------------------------
 * Runs the OpenCL backend (a) and the reference backend (b) side by side on
 * one mesh and compares every op of the backend table, then CG, one Newton
 * step and (optionally) a whole GL solve. Data: the boundary-aligned guiding
 * field and its Dirichlet set (computed on the reference backend), random z
 * (|z| in [0.3, 1.3], random phase) and a random vector r, from `seed`.
 * Matrices are read back exactly through the ops table (glpgp_probe_matrix).
 * Stages, one table row each, in this order:
 *   vector write/read, copy + axpby, axpby with zero coefficients on
 *   NaN-filled vectors, dot z.r (and the same OpenCL dot again: bit for bit);
 *   QUAD assembly of the chosen energy ("QUAD assembly") and of the other
 *   element kinds, then of p1 and transport with a non-uniform size field
 *   ("sized": set_size, random sizes in [h/4, h]); NEWTON assembly and
 *   DINV without penalty and for every Hessian variant; gradient g, E, P
 *   with and without penalty, energy E, P; spmv QUAD / NEWTON, dot x.(NEWTON x); the fused CG steps (precond, then
 *   3 x spmv_dot, update, direction on the projected NEWTON); a CG solve
 *   NEWTON d = -g; the Newton step z + d; when both backends have the
 *   multigrid ops, the hierarchy of the mixed NEWTON at z (levels and sizes
 *   exactly; per level A_l x with its dots, the smoother, restriction and
 *   prolongation on random vectors; the coarsest matrix and its solve;
 *   register dots, axpby, kcombine; one whole cycle; a flexible-CG solve);
 *   with `solve`, the whole GL solve with `precond` (z of both oscillators,
 *   singularity counts exactly) and the cross field (glpgp/cross.h, on the
 *   line-search Newton: w at 1e-3, its final energy at 1e-7 relative, the
 *   +1/4 and -1/4 singularity counts exactly; its minimisers can form
 *   families, e.g. rotated on a disk, along which rounding moves w).
 * Tolerance per entry: |a - b| <= atol + rtol |b|, atol = afac * max|b| over
 * the stage (a dot: afac * sum |x_i y_i|); rtol 1e-12, afac 1e-14 for
 * assembly, gradient, energies, spmv, dot and the first CG products; 1e-10
 * for CG iterates after an update (alpha differs by rounding); 1e-6 for the
 * CG solve, the Newton step and the GL solve (1e-4 for an oscillator whose
 * GL levels stopped at the Newton cap); vectors, axpby: exact. Multigrid:
 * 1e-12 for the hierarchy ops and register dots, 1e-8 for the coarse solve
 * (an inverse computed on the host), 1e-10 for kcombine and the cycle, 1e-6
 * for the flexible-CG solve. A NaN fails. */

/* What to compare. */
typedef struct glpgp_crosscheck_options {
    const glpgp_mesh *mesh;  /* the mesh (borrowed; required) */
    double size;             /* target quad size h; <= 0: glpgp_default_size [0] */
    int energy;              /* GLPGP_ELEM_P1 or GLPGP_ELEM_TRANSPORT [P1] */
    int device;              /* OpenCL device index (glpgp devices); -1: GLPGP_DEVICE env, else
                              * the first GPU with fp64, else the first device with fp64 [-1] */
    double tol_scale;        /* every tolerance times this, > 0 [1] */
    int solve;               /* also run the whole GL solve on both backends [1] */
    unsigned long long seed; /* random z and r [12345] */
    int precond;             /* GLPGP_PRECOND_* of the whole GL solve stage [the solver's
                              * default, glpgp_options_default] */
} glpgp_crosscheck_options;

/* Fill the defaults above (mesh NULL). */
void glpgp_crosscheck_options_default(glpgp_crosscheck_options *o);

/* One stage of the table. */
typedef struct glpgp_crosscheck_row {
    char stage[48];  /* "QUAD assembly", "CG solve (170 vs 170 it)", ... */
    double max_abs;  /* max |a - b| over the stage (NaN if any difference is NaN) */
    double max_rel;  /* max_abs / max |b| (normwise; 0 if both are 0, inf if only b is) */
    char tol[48];    /* the tolerance as text: "rtol 1e-12, atol 4e-14", "exact", "exact (1+/1- vs 1+/1-)" */
    int pass;        /* every entry within tolerance */
} glpgp_crosscheck_row;

/* The result table, with what was compared. */
typedef struct glpgp_crosscheck {
    int nrows;
    glpgp_crosscheck_row *rows;
    int pass;              /* every stage ran and every row passes */
    /* the problem */
    int nv, nt;
    long nnzb;
    double h;              /* target size used */
    int energy;            /* GLPGP_ELEM_* */
    char device[512];      /* glpgp_cl_backend_info of the OpenCL backend ("" before it exists) */
    long field_cg;         /* CG iterations of the guiding field */
    int ndirichlet;        /* Dirichlet vertices of the U field */
    double eps;            /* GL eps of the penalty stages (0 before the field exists) */
    /* the whole GL solve (solved = 1 when it ran); index 0: OpenCL, 1: reference */
    int solved;
    double solve_seconds[2];
    long solve_cg[2][2];   /* [backend][oscillator u, v] CG iterations */
} glpgp_crosscheck;

/* Run every stage and return the table in *out (destroy it with
 * glpgp_crosscheck_destroy). Returns GLPGP_OK when every stage ran (rows may
 * still fail: see (*out)->pass). An error (no OpenCL in the build or no usable
 * device: GLPGP_ERR_UNSUPPORTED / GLPGP_ERR_OPENCL; an op failing) stops the
 * run: *out then still holds the rows completed so far, with pass = 0, so a
 * caller can show them; *out is NULL only for invalid options
 * (GLPGP_ERR_ARG) or when memory for the table ran out. */
glpgp_status glpgp_crosscheck_create(const glpgp_crosscheck_options *o, glpgp_crosscheck **out);
/* Free a table (NULL-safe, sets *t = NULL). */
void glpgp_crosscheck_destroy(glpgp_crosscheck **t);

#ifdef __cplusplus
}
#endif

#endif
