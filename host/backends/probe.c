/* backends/probe.c: the backend-agnostic matrix prober used by cross-checks
 * and the OpenCL tests (glpgp_probe_matrix, glpgp/backends.h): every value of
 * a backend matrix recovered exactly through its ops table only. */
#include "glpgp/backends.h"
#include "glpgp/internal/probe.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

glpgp_status glpgp_probe_matrix(glpgp_backend *b, int which, double *vals)
{
    const glpgp_system *sys = b->sys;
    const glpgp_backend_ops *o = b->ops;
    glpgp_status st = GLPGP_OK;
    int *color = NULL, *mark = NULL;
    double *xh = NULL, *yh = NULL;
    glpgp_vec *x = NULL, *y = NULL;
    if (!sys) return GLPGP_FAIL(GLPGP_ERR_ARG, "probe: backend not set up");
    const int nv = sys->nv;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * nv, sizeof(double), &xh), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * nv, sizeof(double), &yh), done);
    GLPGP_CHECK_GOTO(st, o->vec_create(b, (size_t)2 * nv, &x), done);
    GLPGP_CHECK_GOTO(st, o->vec_create(b, (size_t)2 * nv, &y), done);
    if (which == GLPGP_PROBE_DINV) {
        /* z <- DINV r with r = (1,0) then (0,1) at every vertex: the two block columns */
        for (int d = 0; d < 2; d++) {
            for (int i = 0; i < nv; i++) {
                xh[2 * i] = d == 0 ? 1.0 : 0.0;
                xh[2 * i + 1] = d == 1 ? 1.0 : 0.0;
            }
            GLPGP_CHECK_GOTO(st, o->vec_write(b, x, xh), done);
            GLPGP_CHECK_GOTO(st, o->cg_precond(b, x, y, GLPGP_S_DOT), done);
            GLPGP_CHECK_GOTO(st, o->vec_read(b, y, yh), done);
            for (int i = 0; i < nv; i++) {
                vals[4 * (size_t)i + d] = yh[2 * i];
                vals[4 * (size_t)i + 2 + d] = yh[2 * i + 1];
            }
        }
        goto done;
    }
    if (which != GLPGP_MAT_QUAD && which != GLPGP_MAT_NEWTON) {
        st = GLPGP_FAIL(GLPGP_ERR_ARG, "probe: unknown matrix %d", which);
        goto done;
    }
    /* greedy distance-2 colouring on the (symmetric) block pattern */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(int), &color), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv + 1, sizeof(int), &mark), done);
    int ncol = 0;
    for (int i = 0; i <= nv; i++) mark[i] = -1;
    for (int i = 0; i < nv; i++) {
        for (int k = sys->rowptr[i]; k < sys->rowptr[i + 1]; k++) {
            int j = sys->col[k];
            for (int l = sys->rowptr[j]; l < sys->rowptr[j + 1]; l++) {
                int c = sys->col[l] < i ? color[sys->col[l]] : -1;
                if (c >= 0 && c <= nv) mark[c] = i;
            }
        }
        int c = 0;
        while (mark[c] == i) c++;
        color[i] = c;
        if (c + 1 > ncol) ncol = c + 1;
    }
    for (int c = 0; c < ncol; c++)
        for (int d = 0; d < 2; d++) {
            /* x = indicator of colour c, component d;  y = M x */
            for (int i = 0; i < nv; i++) {
                xh[2 * i] = (color[i] == c && d == 0) ? 1.0 : 0.0;
                xh[2 * i + 1] = (color[i] == c && d == 1) ? 1.0 : 0.0;
            }
            GLPGP_CHECK_GOTO(st, o->vec_write(b, x, xh), done);
            GLPGP_CHECK_GOTO(st, o->spmv(b, which, x, y), done);
            GLPGP_CHECK_GOTO(st, o->vec_read(b, y, yh), done);
            for (int i = 0; i < nv; i++)
                for (int k = sys->rowptr[i]; k < sys->rowptr[i + 1]; k++)
                    if (color[sys->col[k]] == c) {
                        vals[4 * (size_t)k + d] = yh[2 * i];
                        vals[4 * (size_t)k + 2 + d] = yh[2 * i + 1];
                    }
        }
done:
    if (x) o->vec_destroy(b, &x);
    if (y) o->vec_destroy(b, &y);
    free(color);
    free(mark);
    free(xh);
    free(yh);
    return st;
}

