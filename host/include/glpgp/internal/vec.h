/* glpgp/internal/vec.h: growable arrays on top of glpgp_grow (glpgp/status.h,
 * the one growth rule: geometric, overflow-checked, ERR_NOMEM recorded):
 * glpgp_grow_int for the arrays that count in int, and the int and double
 * vectors the quad layer's builders and the mask contours push to
 * (core/vec.c). Internal: not installed. Layer: core. */
#ifndef GLPGP_INTERNAL_VEC_H
#define GLPGP_INTERNAL_VEC_H

#include "glpgp/status.h"

#include <stdlib.h>

/* glpgp_grow with an int capacity: *ptr (an array of *cap elements of elem
 * bytes) holds at least need elements (need <= INT_MAX). */
glpgp_status glpgp_grow_int(void *ptr, int *cap, int need, size_t elem);

typedef struct glpgp_dvec {
    double *p;
    int n, cap; /* in doubles */
} glpgp_dvec;
typedef struct glpgp_ivec {
    int *p;
    int n, cap;
} glpgp_ivec;

static inline glpgp_status glpgp_dvec_push(glpgp_dvec *v, double x)
{
    if (v->n == v->cap) GLPGP_CHECK(glpgp_grow_int(&v->p, &v->cap, v->n + 1, sizeof *v->p));
    v->p[v->n++] = x;
    return GLPGP_OK;
}

static inline glpgp_status glpgp_ivec_push(glpgp_ivec *v, int x)
{
    if (v->n == v->cap) GLPGP_CHECK(glpgp_grow_int(&v->p, &v->cap, v->n + 1, sizeof *v->p));
    v->p[v->n++] = x;
    return GLPGP_OK;
}

static inline void glpgp_ivec_free(glpgp_ivec *v)
{
    free(v->p);
    v->p = NULL;
    v->n = v->cap = 0;
}

static inline void glpgp_dvec_free(glpgp_dvec *v)
{
    free(v->p);
    v->p = NULL;
    v->n = v->cap = 0;
}

#endif
