/* core/grid.c: the uniform grid of boxes of glpgp/internal/grid.h (CSR
 * cells, queries deduplicated by a per-item stamp). */
#include "glpgp/internal/grid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void glpgp_bgrid_free(glpgp_bgrid *g)
{
    free(g->start);
    free(g->item);
    free(g->stamp);
    memset(g, 0, sizeof *g);
}

glpgp_status glpgp_bgrid_build(glpgp_bgrid *g, const double *box, int n, double cs)
{
    memset(g, 0, sizeof *g);
    g->nitems = n;
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int i = 0; i < n; i++) {
        x0 = fmin(x0, box[4 * i]);
        y0 = fmin(y0, box[4 * i + 1]);
        x1 = fmax(x1, box[4 * i + 2]);
        y1 = fmax(y1, box[4 * i + 3]);
    }
    if (n == 0) x0 = y0 = x1 = y1 = 0.0;
    double w = x1 - x0, hh = y1 - y0;
    if (!(cs > 0)) cs = fmax(w, hh) + 1.0;
    /* at most ~ 2 n + 16 cells */
    while ((w / cs + 1) * (hh / cs + 1) > 2.0 * n + 16) cs *= 1.5;
    g->x0 = x0;
    g->y0 = y0;
    g->cs = cs;
    g->nx = (int)(w / cs) + 1;
    g->ny = (int)(hh / cs) + 1;
    long nc = (long)g->nx * g->ny;
    GLPGP_CHECK(glpgp_calloc((size_t)nc + 1, sizeof(int), &g->start));
    GLPGP_CHECK(glpgp_calloc((size_t)n + 1, sizeof(int), &g->stamp));
    for (int pass = 0; pass < 2; pass++) {
        for (int i = 0; i < n; i++) {
            int ia = (int)((box[4 * i] - x0) / cs), ib = (int)((box[4 * i + 2] - x0) / cs);
            int ja = (int)((box[4 * i + 1] - y0) / cs), jb = (int)((box[4 * i + 3] - y0) / cs);
            if (ia < 0) ia = 0;
            if (ja < 0) ja = 0;
            if (ib >= g->nx) ib = g->nx - 1;
            if (jb >= g->ny) jb = g->ny - 1;
            for (int j = ja; j <= jb; j++)
                for (int k = ia; k <= ib; k++) {
                    long c = (long)j * g->nx + k;
                    if (pass == 0)
                        g->start[c + 1]++;
                    else
                        g->item[g->start[c]++] = i;
                }
        }
        if (pass == 0) {
            for (long c = 0; c < nc; c++) g->start[c + 1] += g->start[c];
            GLPGP_CHECK(glpgp_malloc((size_t)g->start[nc] + 1, sizeof(int), &g->item));
        } else {
            for (long c = nc; c > 0; c--) g->start[c] = g->start[c - 1];
            g->start[0] = 0;
        }
    }
    return GLPGP_OK;
}

int glpgp_bgrid_query(glpgp_bgrid *g, double x0, double y0, double x1, double y1, int **out, int *cap)
{
    if (g->nitems == 0) return 0;
    int ia = (int)floor((x0 - g->x0) / g->cs), ib = (int)floor((x1 - g->x0) / g->cs);
    int ja = (int)floor((y0 - g->y0) / g->cs), jb = (int)floor((y1 - g->y0) / g->cs);
    if (ia < 0) ia = 0;
    if (ja < 0) ja = 0;
    if (ib >= g->nx) ib = g->nx - 1;
    if (jb >= g->ny) jb = g->ny - 1;
    if (ia > ib || ja > jb) return 0;
    if (++g->tick == 0x7fffffff) {
        memset(g->stamp, 0, (size_t)g->nitems * sizeof(int));
        g->tick = 1;
    }
    int n = 0;
    for (int j = ja; j <= jb; j++)
        for (int k = ia; k <= ib; k++) {
            long c = (long)j * g->nx + k;
            for (int q = g->start[c]; q < g->start[c + 1]; q++) {
                int it = g->item[q];
                if (g->stamp[it] == g->tick) continue;
                g->stamp[it] = g->tick;
                if (n == *cap) {
                    int nc = *cap ? 2 * *cap : 64;
                    int *p = realloc(*out, (size_t)nc * sizeof(int));
                    if (!p) return -1;
                    *out = p;
                    *cap = nc;
                }
                (*out)[n++] = it;
            }
        }
    return n;
}
