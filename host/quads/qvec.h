/* quads/qvec.h: growable int and double arrays of the quad layer's
 * builders (repair, region loops, the cut mesher). Internal. */
#ifndef GLPGP_QUADS_QVEC_H
#define GLPGP_QUADS_QVEC_H

#include "glpgp/status.h"

#include <stdlib.h>

typedef struct dvec {
    double *p;
    int n, cap; /* in doubles */
} dvec;
typedef struct ivec {
    int *p;
    int n, cap;
} ivec;

static inline glpgp_status dpush(dvec *v, double x)
{
    if (v->n == v->cap) {
        int c = v->cap ? 2 * v->cap : 256;
        double *q = realloc(v->p, (size_t)c * sizeof(double));
        if (!q) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quads: out of memory");
        v->p = q;
        v->cap = c;
    }
    v->p[v->n++] = x;
    return GLPGP_OK;
}

static inline glpgp_status ipush(ivec *v, int x)
{
    if (v->n == v->cap) {
        int c = v->cap ? 2 * v->cap : 256;
        int *q = realloc(v->p, (size_t)c * sizeof(int));
        if (!q) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quads: out of memory");
        v->p = q;
        v->cap = c;
    }
    v->p[v->n++] = x;
    return GLPGP_OK;
}

static inline void ivec_free(ivec *v)
{
    free(v->p);
    v->p = NULL;
    v->n = v->cap = 0;
}

static inline void dvec_free(dvec *v)
{
    free(v->p);
    v->p = NULL;
    v->n = v->cap = 0;
}

#endif
