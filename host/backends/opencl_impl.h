/* backends/opencl_impl.h: the OpenCL backend's private parts, shared by
 * opencl.c (program, device, system, vectors, mesh operations, CG, the ops
 * table) and opencl_amg.c (the multigrid ops): the kernel ids, the buffer
 * and backend structs, the launch helpers. Not installed; compiled only
 * with GLPGP_HAVE_OPENCL. */
#ifndef GLPGP_OPENCL_IMPL_H
#define GLPGP_OPENCL_IMPL_H

#include "cl_util.h"

#include <stddef.h>

/* Kernels of the program, in this order. */
enum {
    K_FINALIZE,
    K_ASM_QUAD,
    K_ASM_NEWTON,
    K_GRADIENT,
    K_PEN_ENERGY,
    K_AXPBY,
    K_DOT,
    K_SPMV,
    K_CG_PRECOND,
    K_CG_SPMV_DOT,
    K_CG_UPDATE,
    K_CG_DIRECTION,
    /* multigrid (backend_multigrid.cl) */
    K_AMG_FINALIZE,
    K_AMG_WEIGHTS,
    K_AMG_GALERKIN,
    K_AMG_L1,
    K_AMG_SMOOTH,
    K_AMG_RESTRICT,
    K_AMG_PROLONG,
    K_AMG_DENSE,
    K_AMG_SPMV_DOTS,
    K_AMG_DOTS,
    K_AMG_AXPBY,
    K_AMG_KCOMBINE,
    K_AMG_BOTTOM,
    K_AMG_RESIDUAL,
    K_AMG_COARSE_INVERT,
    K_AMG_PRESMOOTH_RESTRICT,
    K_AMG_PRESMOOTH_RESID,
    K_AMG_PROLONG_SMOOTH,
    /* coupled cross-field system (backend_coupled.cl) */
    K_CASM_QUAD,
    K_CASM_NEWTON,
    K_CGRADIENT,
    K_CPEN_ENERGY,
    /* Newton driver (backend_newton.cl) */
    K_TRIAL_POINT,
    K_COUNT
};

struct glpgp_vec {
    size_t n;
    cl_mem m;
};

/* GLPGP_CL_PROFILE's size classes: index counts below 4, 4^1, ..., 4^11 and above */
#define PROF_CLASSES 13

/* One level of the multigrid hierarchy on the device (amg_setup). Level 0
 * uses the system's pattern and NEWTON; the values of the levels >= 1, the
 * weights c, the amplitudes and the smoothers are rebuilt by amg_values. */
typedef struct cl_amg_level {
    int n, nc;           /* nodes; nodes of level l+1 (0 on the coarsest) */
    long nnzb;
    cl_mem rowptr, col, diag; /* levels >= 1 (level 0: the system's) */
    cl_mem val;          /* 4 nnzb, levels >= 1 */
    cl_mem amp;          /* n, levels >= 1: frame amplitude, 0 = dead */
    cl_mem srow;         /* nnzb, levels < L-1: row of each slot */
    cl_mem minv;         /* 4 n, levels < L-1 */
    cl_mem c;            /* 2 n, levels < L-1 (zero for nodes in no aggregate) */
    cl_mem agg, aptr, amem, gptr, gsrc; /* levels < L-1 */
} cl_amg_level;

typedef struct cl_amg {
    glpgp_amg_layout lay;/* the layout it was set up from (its key and parameters; the
                            array pointers are the caller's and not used after setup) */
    int L;
    double weight;
    cl_amg_level lev[GLPGP_AMG_MAX_LEVELS];
    int m;               /* coarse order 2 n_{L-1} */
    int *crowptr, *ccol; /* host copy of the coarsest pattern (amg_coarse_read) */
    double *cval;        /* host buffer for its values */
    cl_mem cinv;         /* m*m */
    cl_mem dw, di;       /* work of the coarse inverse (kernels/amg_dense.h) */
    cl_mem t;            /* GLPGP_AMG_NSLOTS registers */
    cl_mem resid;        /* 2 n_0 doubles: the residual of the two-pass restriction */
    cl_mem part;         /* 3 * pstride partials */
    size_t pstride;
    /* fused coarse corrections (CPU shape): levels lb .. L-1 live in the
     * packed arrays ipack / dpack (their per-level buffers above, and cinv,
     * are sub-buffers of these), described by the table tab
     * (GLPGP_AMG_BT_* of kernels/amg_rows.h); lb = L: none */
    int lb;
    int pre, post;       /* smoother sweeps (layout) */
    int cinv_off;        /* offset of cinv in dpack (doubles) */
    cl_mem ipack, dpack, tab;
} cl_amg;

typedef struct cl_impl {
    cl_context ctx;
    cl_command_queue q;
    cl_device_id dev;
    cl_program prog;
    cl_kernel k[K_COUNT];
    int index;           /* global device index */
    int cpu;             /* CPU launch shape */
    size_t wg;           /* local size (1 in the CPU shape) */
    size_t nwi;          /* CPU shape: number of work-items */
    cl_device_type type;
    cl_ulong global_mem, max_alloc;
    char name[256];
    double build_seconds;
    int corrupt;         /* GLPGP_CL_CORRUPT=1 */
    int verbose;

    const glpgp_system *sys;
    cl_mem xy, tri, rowptr, col, diag, cptr, contrib, vptr, vtri; /* mesh + pattern */
    cl_mem cconj, cfield;  /* coupled cross-field system (sys->cconj): per-corner matching, else 0 */
    cl_mem ctxy, crot;     /* a surface's triangle planes and corner rotations (sys->ctxy, crot), else 0 */
    cl_mem w, dir;                                                /* field */
    cl_mem size;                                                  /* nv target sizes */
    int sized;                                                    /* set_size given */
    cl_mem quad, newton, dinv;                                    /* matrices */
    cl_mem s;                                                     /* GLPGP_NSLOTS scalars */
    cl_mem part;                                                  /* 2 * pstride partials */
    cl_mem bad;                                                   /* 1 int */
    size_t pstride;
    cl_amg *amg;         /* multigrid hierarchy (NULL before amg_setup) */
    int amg_small;       /* CPU shape: multigrid launches over at most this many
                            indices run as one work-item (GLPGP_CL_AMG_SMALL) */
    int amg_fuse;        /* CPU shape: coarse corrections of levels with at most
                            this many nodes run in one launch (GLPGP_CL_AMG_FUSE;
                            0: never) */
    cl_uint align;       /* CL_DEVICE_MEM_BASE_ADDR_ALIGN in bytes (sub-buffers) */
    long *launches;      /* the backend's n_launch: kernel launches enqueued */
    glpgp_backend *owner;/* the backend this is the implementation of (its phase accounts) */
    int bad_pending;     /* an assembly's singular-block flag not yet read (sync_read) */
    int prof;            /* GLPGP_CL_PROFILE=1: per-kernel device times (launch) */
    const int *stop;     /* glpgp_cl_options.stop (creation only) */
    double prof_ns[K_COUNT][PROF_CLASSES]; /* by kernel and index count class (log4 of n) */
    long prof_n[K_COUNT][PROF_CLASSES];
    size_t prof_size;    /* the index count of the launch being enqueued (run, amg_run_w) */
    double need;         /* device memory estimate of the system set up (bytes) */
    double other_need;   /* a clone: device memory its parent holds (its estimate, with
                            room for the multigrid), counted at setup */
    const struct cl_impl *parent; /* a clone: the backend it was cloned from (its
                            read-only mesh and pattern buffers are shared when
                            the clone is set up for the same system) */
} cl_impl;

#define IMPL(b) ((cl_impl *)(b)->impl)

/* A blocking OpenCL call: its time is the host's wait on the device, booked
 * to the owner's current phase (glpgp_backend_waited). */
#define CL_WAIT(c, call)                                                                                   \
    do {                                                                                                   \
        const double t_wait_ = glpgp_cl_now_seconds();                                                              \
        GLPGP_CL(call);                                                                                    \
        if ((c)->owner) glpgp_backend_waited((c)->owner, glpgp_cl_now_seconds() - t_wait_);                         \
    } while (0)

/* clSetKernelArg of an lvalue. */
#define ARG(kern, i, v) GLPGP_CL(clSetKernelArg((kern), (i), sizeof(v), &(v)))
/* A kernel's arguments first, first + 1, ... set from the lvalues given, in
 * order (at most 16): ARGS(k, 0, n, v->rowptr, v->col, x->m) is ARG(k, 0, n);
 * ARG(k, 1, v->rowptr); ... one statement. */
#define ARGS_1(k, i, a) ARG(k, i, a)
#define ARGS_2(k, i, a, ...) ARG(k, i, a); ARGS_1(k, (i) + 1, __VA_ARGS__)
#define ARGS_3(k, i, a, ...) ARG(k, i, a); ARGS_2(k, (i) + 1, __VA_ARGS__)
#define ARGS_4(k, i, a, ...) ARG(k, i, a); ARGS_3(k, (i) + 1, __VA_ARGS__)
#define ARGS_5(k, i, a, ...) ARG(k, i, a); ARGS_4(k, (i) + 1, __VA_ARGS__)
#define ARGS_6(k, i, a, ...) ARG(k, i, a); ARGS_5(k, (i) + 1, __VA_ARGS__)
#define ARGS_7(k, i, a, ...) ARG(k, i, a); ARGS_6(k, (i) + 1, __VA_ARGS__)
#define ARGS_8(k, i, a, ...) ARG(k, i, a); ARGS_7(k, (i) + 1, __VA_ARGS__)
#define ARGS_9(k, i, a, ...) ARG(k, i, a); ARGS_8(k, (i) + 1, __VA_ARGS__)
#define ARGS_10(k, i, a, ...) ARG(k, i, a); ARGS_9(k, (i) + 1, __VA_ARGS__)
#define ARGS_11(k, i, a, ...) ARG(k, i, a); ARGS_10(k, (i) + 1, __VA_ARGS__)
#define ARGS_12(k, i, a, ...) ARG(k, i, a); ARGS_11(k, (i) + 1, __VA_ARGS__)
#define ARGS_13(k, i, a, ...) ARG(k, i, a); ARGS_12(k, (i) + 1, __VA_ARGS__)
#define ARGS_14(k, i, a, ...) ARG(k, i, a); ARGS_13(k, (i) + 1, __VA_ARGS__)
#define ARGS_15(k, i, a, ...) ARG(k, i, a); ARGS_14(k, (i) + 1, __VA_ARGS__)
#define ARGS_16(k, i, a, ...) ARG(k, i, a); ARGS_15(k, (i) + 1, __VA_ARGS__)
#define ARGS_PICK(_1, _2, _3, _4, _5, _6, _7, _8, _9, _10, _11, _12, _13, _14, _15, _16, NAME, ...) NAME
#define ARGS(kern, first, ...)                                                        \
    do {                                                                           \
        ARGS_PICK(__VA_ARGS__, ARGS_16, ARGS_15, ARGS_14, ARGS_13, ARGS_12, ARGS_11, ARGS_10, ARGS_9, ARGS_8, ARGS_7, ARGS_6, ARGS_5, ARGS_4, ARGS_3, ARGS_2, ARGS_1, 0)       \
        (kern, first, __VA_ARGS__);                                               \
    } while (0)

/* Work decomposition of n indices: chunk per work-item, global/local sizes. */
typedef struct launch_shape {
    size_t global, local, groups;
    cl_int n, chunk;
} launch_shape;

/* ---- launch helpers and buffers (opencl.c) ---- */
void glpgp_cl_release_mem(cl_mem *m);
launch_shape glpgp_cl_shape_for(const cl_impl *c, size_t n);
glpgp_status glpgp_cl_launch(cl_impl *c, int kid, size_t global, size_t local);
glpgp_status glpgp_cl_upload(cl_impl *c, cl_mem *m, const void *host, size_t bytes);
glpgp_status glpgp_cl_sync_read(cl_impl *c, cl_mem buf, size_t off, size_t bytes, void *host);
void glpgp_cl_amg_free(cl_impl *c);
double glpgp_cl_now_seconds(void);

/* ---- program and device (opencl_program.c) ---- */
extern const char *const glpgp_cl_kernel_names[K_COUNT];
glpgp_status glpgp_cl_init_device(cl_impl *c, const glpgp_cl_options *opt);
void glpgp_cl_log_device(const cl_impl *c);

/* ---- the multigrid ops (opencl_amg.c) ---- */
glpgp_status glpgp_cl_amg_axpby(glpgp_backend *b, glpgp_amg_coef ca, const glpgp_vec *x, glpgp_amg_coef cc,
                                 glpgp_vec *y);
glpgp_status glpgp_cl_amg_coarse_correction(glpgp_backend *b, int lc, int sym, const glpgp_vec *rhs,
                                             glpgp_vec *e, int *done);
glpgp_status glpgp_cl_amg_coarse_invert(glpgp_backend *b, int spd);
glpgp_status glpgp_cl_amg_coarse_read(glpgp_backend *b, double *dense);
glpgp_status glpgp_cl_amg_coarse_solve(glpgp_backend *b, const glpgp_vec *r, glpgp_vec *x);
glpgp_status glpgp_cl_amg_dots(glpgp_backend *b, const glpgp_vec *x, const glpgp_vec *u, const glpgp_vec *w,
                                int slot);
glpgp_status glpgp_cl_amg_get_scalars(glpgp_backend *b, double *out, int n);
glpgp_status glpgp_cl_amg_kcombine(glpgp_backend *b, const glpgp_vec *v, const glpgp_vec *d, glpgp_vec *e,
                                    int slot);
glpgp_status glpgp_cl_amg_presmooth_restrict(glpgp_backend *b, int l, const glpgp_vec *r, glpgp_vec *y,
                                              glpgp_vec *rc);
glpgp_status glpgp_cl_amg_prolong(glpgp_backend *b, int l, const glpgp_vec *ec, glpgp_vec *x);
glpgp_status glpgp_cl_amg_prolong_smooth(glpgp_backend *b, int l, const glpgp_vec *ec, const glpgp_vec *x,
                                          const glpgp_vec *r, glpgp_vec *y);
glpgp_status glpgp_cl_amg_restrict(glpgp_backend *b, int l, const glpgp_vec *r, const glpgp_vec *x,
                                    glpgp_vec *rc);
glpgp_status glpgp_cl_amg_setup(glpgp_backend *b, const glpgp_amg_layout *lay);
glpgp_status glpgp_cl_amg_smooth(glpgp_backend *b, int l, const glpgp_vec *r, const glpgp_vec *x, glpgp_vec *y);
glpgp_status glpgp_cl_amg_spmv_dots(glpgp_backend *b, int l, const glpgp_vec *x, glpgp_vec *y,
                                     const glpgp_vec *u, const glpgp_vec *w, int slot);
glpgp_status glpgp_cl_amg_values(glpgp_backend *b, const glpgp_vec *const *frames);

#endif
