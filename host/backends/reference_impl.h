/* backends/reference_impl.h: private to the reference backend: its vector
 * and state types (shared by reference.c and reference_amg.c) and the
 * multilevel preconditioner's ops implemented in reference_amg.c. */
#ifndef GLPGP_REFERENCE_IMPL_H
#define GLPGP_REFERENCE_IMPL_H

#include "glpgp/backend.h"
#include "glpgp/internal/newton.h"

#include <stddef.h>

struct glpgp_vec {
    size_t n;
    double *a;
};

struct ref_amg; /* reference_amg.c */

typedef struct ref_impl {
    const glpgp_system *sys;
    const double *w;           /* 2*nv field (copy owned) */
    double *wbuf;
    unsigned char *dir;        /* nv Dirichlet flags */
    double *size;              /* nv target sizes (set_size) */
    int sized;                 /* assemble with size[] instead of h */
    double *quad, *newton;     /* 4*nnzb */
    double *dinv;              /* 4*nv */
    double *pgrad;             /* 2*nv: penalty gradient sums of the triangle-loop gradient */
    int kind;
    double h;
    double s[GLPGP_NSLOTS];
    struct ref_amg *amg;       /* multilevel hierarchy (NULL until amg_setup) */
} ref_impl;

#define IMPL(b) ((ref_impl *)(b)->impl)

/* Free the hierarchy of r (NULL-safe). */
void glpgp_ref_amg_free(ref_impl *r);

glpgp_status glpgp_ref_amg_setup(glpgp_backend *b, const glpgp_amg_layout *lay);
glpgp_status glpgp_ref_amg_values(glpgp_backend *b, const glpgp_vec *const *frames);
glpgp_status glpgp_ref_amg_coarse_read(glpgp_backend *b, double *dense);
glpgp_status glpgp_ref_amg_coarse_invert(glpgp_backend *b, int spd);
glpgp_status glpgp_ref_amg_smooth(glpgp_backend *b, int l, const glpgp_vec *r, const glpgp_vec *x,
                                  glpgp_vec *y);
glpgp_status glpgp_ref_amg_restrict(glpgp_backend *b, int l, const glpgp_vec *r,
                                    const glpgp_vec *x, glpgp_vec *rc);
glpgp_status glpgp_ref_amg_prolong(glpgp_backend *b, int l, const glpgp_vec *ec, glpgp_vec *x);
glpgp_status glpgp_ref_amg_coarse_solve(glpgp_backend *b, const glpgp_vec *r, glpgp_vec *x);
glpgp_status glpgp_ref_amg_spmv_dots(glpgp_backend *b, int l, const glpgp_vec *x, glpgp_vec *y,
                                     const glpgp_vec *u, const glpgp_vec *w, int slot);
glpgp_status glpgp_ref_amg_dots(glpgp_backend *b, const glpgp_vec *x, const glpgp_vec *u,
                                const glpgp_vec *w, int slot);
glpgp_status glpgp_ref_amg_axpby(glpgp_backend *b, glpgp_amg_coef a, const glpgp_vec *x,
                                 glpgp_amg_coef c, glpgp_vec *y);
glpgp_status glpgp_ref_amg_kcombine(glpgp_backend *b, const glpgp_vec *v, const glpgp_vec *d,
                                    glpgp_vec *e, int slot);
glpgp_status glpgp_ref_amg_get_scalars(glpgp_backend *b, double *out, int n);
glpgp_status glpgp_ref_amg_presmooth_restrict(glpgp_backend *b, int l, const glpgp_vec *r, glpgp_vec *y,
                                              glpgp_vec *rc);
glpgp_status glpgp_ref_amg_prolong_smooth(glpgp_backend *b, int l, const glpgp_vec *ec, const glpgp_vec *x,
                                          const glpgp_vec *r, glpgp_vec *y);

/* The amg_* entries of the reference ops table. */
#define GLPGP_REF_AMG_OPS                                                                          \
    .amg_setup = glpgp_ref_amg_setup, .amg_values = glpgp_ref_amg_values,                          \
    .amg_coarse_read = glpgp_ref_amg_coarse_read, .amg_coarse_invert = glpgp_ref_amg_coarse_invert,      \
    .amg_smooth = glpgp_ref_amg_smooth, .amg_restrict = glpgp_ref_amg_restrict,                    \
    .amg_prolong = glpgp_ref_amg_prolong, .amg_coarse_solve = glpgp_ref_amg_coarse_solve,          \
    .amg_spmv_dots = glpgp_ref_amg_spmv_dots, .amg_dots = glpgp_ref_amg_dots,                      \
    .amg_axpby = glpgp_ref_amg_axpby, .amg_kcombine = glpgp_ref_amg_kcombine,                      \
    .amg_get_scalars = glpgp_ref_amg_get_scalars, .amg_presmooth_restrict = glpgp_ref_amg_presmooth_restrict,      \
    .amg_prolong_smooth = glpgp_ref_amg_prolong_smooth,

#endif
