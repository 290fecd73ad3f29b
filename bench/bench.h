/* bench.h: shared declarations of the glpgp-bench program (the bench/ sources):
 * timing helpers, the STREAM bandwidth probe (stream.c), the optional
 * CHOLMOD comparison (cholmod_bench.c) and the flattening JSON reader used
 * by --compare (json_flat.c). See bench/README.md for what is measured. */
#ifndef GLPGP_BENCH_H
#define GLPGP_BENCH_H

#include <stddef.h>

#include "glpgp/backends.h"
#include "glpgp/io.h"
#include "glpgp/shapes.h"
#include "glpgp/solve.h"
#include "glpgp/status.h"
#include "glpgp/util.h"
#include "glpgp/system.h"
#include "glpgp/internal/newton.h"
#include "glpgp/internal/probe.h"

/* Monotonic wall clock in seconds. */
double bench_now(void);

/* ---- preconditioner ladder (bench_precond.c) -------------------------------- */

typedef struct bench_precond_opts {
    int which;            /* 0 jacobi, 1 amg, 2 both */
    long sizes[16];
    int nsizes;           /* 0: 64k, 256k, 1M (+ 4M with with_4m) */
    int with_4m;
    int steps;            /* Newton steps per case */
    const char *shape;
    int no_opencl, no_reference;
    int device;
    const char *json;     /* NULL: no JSON */
    int kcycle_min;       /* glpgp_options.amg_kcycle_min (-1: by the backend) */
    int amg_pre, amg_post; /* glpgp_options.amg_pre / amg_post (-1: the default) */
    int amg_passes;        /* glpgp_options.amg_coarse_passes (-1: the default) */
    int no_petsc;         /* leave the PETSc GAMG anchor out */
    int no_cholmod;       /* leave the CHOLMOD anchor out */
    long max_cholmod;     /* CHOLMOD anchor up to this many vertices (0: no limit) */
    int hcases;           /* bit 0: h = 10 mean edges, bit 1: the default size (0: both) */
} bench_precond_opts;

/* Run the ladder, print Markdown, write JSON; returns the exit code. */
int bench_precond_run(const bench_precond_opts *o);

/* ---- STREAM ---------------------------------------------------------------- */

typedef struct bench_stream {
    int threads;
    size_t array_bytes; /* bytes of each of the three arrays */
    int reps;
    double copy_gbs, triad_gbs;         /* best of reps */
    double copy_gbs_med, triad_gbs_med; /* median of reps */
} bench_stream;

/* Copy c = a and triad a = b + s c over `threads` pthreads (each thread
 * first-touches and works on its own contiguous chunk), arrays of n doubles,
 * `reps` timed repetitions after one warm-up. Bytes counted as in STREAM:
 * copy 16 n, triad 24 n (write-allocate traffic not counted). */
glpgp_status bench_stream_run(int threads, size_t n, int reps, bench_stream *out);

/* ---- CHOLMOD --------------------------------------------------------------- */

typedef struct bench_cholmod {
    int available;      /* built with CHOLMOD */
    int ran;            /* factorisation attempted */
    int ok;             /* factorised and solved */
    char note[256];     /* why not, or the ordering used */
    double analyze_s, factorize_s, solve_s;
    double factor_nnz;  /* nonzeros of L */
    double rel_diff_vs_cg; /* |x_chol - x_cg| / |x_chol| */
    double peak_bytes;  /* CHOLMOD's own peak memory (Common->memory_usage) */
} bench_cholmod;

/* Whether this build has CHOLMOD. */
int bench_have_cholmod(void);
/* Expand the 2x2-block NEWTON matrix `vals` (4 * nnzb values on sys's
 * pattern, symmetric) into the lower triangle of a scalar CSC matrix,
 * analyse (CHOLMOD's default ordering), factorise and solve with rhs (2 nv);
 * compare with xcg (2 nv, may be NULL). Failures are reported in out->note
 * (not as an error status) except allocation failures. */
glpgp_status bench_cholmod_run(const glpgp_system *sys, const double *vals, const double *rhs,
                               const double *xcg, bench_cholmod *out);

/* ---- JSON (for --compare) --------------------------------------------------- */

typedef struct bench_flat {
    size_t n, cap;
    char **path;   /* "sizes.0.reference.cg_iter_s.median" */
    double *value; /* numeric leaves only */
    char **spath;  /* string leaves (for labels) */
    char **svalue;
    size_t ns, scap;
} bench_flat;

/* Parse JSON text into numeric (and string) leaves keyed by dotted paths
 * (array elements by index). GLPGP_ERR_FORMAT on malformed input. */
glpgp_status bench_json_flatten(const char *text, bench_flat *out);
void bench_flat_free(bench_flat *f);
/* Numeric leaf by path (NULL if absent). */
const double *bench_flat_get(const bench_flat *f, const char *path);

#endif
