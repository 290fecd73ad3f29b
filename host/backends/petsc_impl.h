/* backends/petsc_impl.h: what the PETSc backend's files share (petsc.c: the
 * process, reductions, ghosts, the ops, distributed meshes; petsc_ksp.c: the
 * linear solve on NEWTON with KSP): the error macro, the backend's state,
 * the owned-slice macros and the helpers each calls in the other. Part of
 * the module glpgp_petsc.so; not installed. */
#ifndef GLPGP_PETSC_IMPL_H
#define GLPGP_PETSC_IMPL_H

#include "glpgp/backends.h"
#include "glpgp/solve.h"

#include <petscksp.h>

/* a PETSc call: its error becomes a glpgp error */
#define PCHK(call)                                                                                 \
    do {                                                                                           \
        PetscErrorCode pe_ = (call);                                                               \
        if (pe_) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "PETSc error %d in %s", (int)pe_, #call);     \
    } while (0)

struct glpgp_vec {
    Vec v;
    int local; /* 1: a sequential Vec of this rank alone (a coarse multigrid level) */
};

typedef struct pimpl {
    const glpgp_system *sys;
    int rank, size;
    int lo, hi;                 /* owned vertices [lo, hi) (system numbering) */
    int vstart;                 /* global id of vertex lo (the PETSc numbering: block rows) */
    const int *gid;             /* global id of each system vertex (a part's), NULL: the identity */
    long slo, shi;              /* owned block slots [rowptr[lo], rowptr[hi]) */
    double *wbuf, *size_;       /* 2 nv field, nv sizes (as the driver hands them) */
    unsigned char *dir;         /* nv Dirichlet flags */
    int sized;
    double *quadb, *newtonb, *dinvb; /* owned slices */
    int nghost;
    int *ghost;                 /* ghost vertices, increasing */
    int *tcount;                /* triangles counted here (lowest vertex owned), increasing */
    int ntcount;
    double *xf[2];              /* system-length scratch arrays (owned + ghost values valid) */
    Vec xseq[2];                /* Seq Vecs over xf */
    VecScatter sc;              /* owned parts of a global Vec -> ghost entries of xseq */
    int *rcounts, *rdispls;     /* all-gather of vectors (doubles) */
    Mat A;                      /* NEWTON as MATMPIBAIJ (lazily) */
    int A_dirty;
    KSP ksp;
    Vec nn;                     /* the Newton iterate of the last assemble_newton with penalty */
    int nn_valid;
    long quad_gen;              /* assemble_quadratic calls so far (a new QUAD: field, oscillator) */
    double newton_inv4e2;       /* 1/(4 eps^2) of the last assemble_newton */
    long ksp_gen;               /* the (quad_gen, newton_inv4e2, nn_valid) the KSP's hierarchy was built for */
    double ksp_inv4e2;
    int ksp_nn;
    int rebuild;                /* -glpgp_gamg_rebuild: 1 step, 2 level, 3 oscillator (0: not read yet) */
    int precond;
    struct petsc_amg *amg;      /* glpgp's multigrid on this rank's rows (petsc_amg.c), or NULL */
    double s[GLPGP_NSLOTS];
} pimpl;

#define PI(b) ((pimpl *)(b)->impl)

/* base pointers shifted so that global indices address the owned slices */
#define QUAD(p) ((p)->quadb - 4 * (p)->slo)
#define NEWT(p) ((p)->newtonb - 4 * (p)->slo)
#define DINV(p) ((p)->dinvb - 4 * (long)(p)->lo)

/* the global (PETSc) block index of system vertex j */
static inline PetscInt gcol(const pimpl *p, int j) { return p->gid ? p->gid[j] : j; }

glpgp_status glpgp_petsc_m_init(void);
int glpgp_petsc_m_rank(void);
int glpgp_petsc_m_size(void);
glpgp_status glpgp_petsc_reduce_sum(pimpl *p, double *v, int n);
glpgp_status glpgp_petsc_m_create(int precond, glpgp_backend **out);
void glpgp_petsc_m_local_info(const glpgp_backend *b, int *owned, int *ghosts);

/* xf[k] <- x at the owned and ghost vertices (one VecScatter; petsc.c) */
glpgp_status glpgp_petsc_load_ghosted(pimpl *p, const glpgp_vec *x, int k);

/* the multigrid ops (petsc_amg.c) */
void glpgp_petsc_amg_free(pimpl *p);
glpgp_status glpgp_petsc_amg_setup(glpgp_backend *b, const glpgp_amg_layout *lay);
glpgp_status glpgp_petsc_amg_values(glpgp_backend *b, const glpgp_vec *const *frames);
glpgp_status glpgp_petsc_amg_coarse_invert(glpgp_backend *b, int spd);
glpgp_status glpgp_petsc_amg_smooth(glpgp_backend *b, int l, const glpgp_vec *r, const glpgp_vec *x, glpgp_vec *y);
glpgp_status glpgp_petsc_amg_restrict(glpgp_backend *b, int l, const glpgp_vec *r, const glpgp_vec *x,
                                      glpgp_vec *rc);
glpgp_status glpgp_petsc_amg_prolong(glpgp_backend *b, int l, const glpgp_vec *ec, glpgp_vec *x);
glpgp_status glpgp_petsc_amg_coarse_solve(glpgp_backend *b, const glpgp_vec *r, glpgp_vec *x);
glpgp_status glpgp_petsc_amg_spmv_dots(glpgp_backend *b, int l, const glpgp_vec *x, glpgp_vec *y,
                                       const glpgp_vec *u, const glpgp_vec *w, int slot);
glpgp_status glpgp_petsc_amg_dots(glpgp_backend *b, const glpgp_vec *x, const glpgp_vec *u, const glpgp_vec *w,
                                  int slot);
glpgp_status glpgp_petsc_amg_axpby(glpgp_backend *b, glpgp_amg_coef ca, const glpgp_vec *x, glpgp_amg_coef cc,
                                   glpgp_vec *y);
glpgp_status glpgp_petsc_amg_kcombine(glpgp_backend *b, const glpgp_vec *v, const glpgp_vec *d, glpgp_vec *e,
                                      int slot);
glpgp_status glpgp_petsc_amg_get_scalars(glpgp_backend *b, double *out, int n);

/* op linear_solve (petsc_ksp.c) */
glpgp_status glpgp_petsc_linear_solve(glpgp_backend *b, const glpgp_vec *rhs, glpgp_vec *x, double rtol, int maxit,
                                   int *iterations, double *relres, int *reason);

#endif
