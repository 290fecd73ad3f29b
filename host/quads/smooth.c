/* quads/smooth.c: the quality-guarded smoothing (glpgp_quadmesh_smooth,
 * glpgp/quads.h): the chosen vertices and their neighbours move part of the
 * way to the mean of their edge neighbours, only when that raises the worst
 * corner around them. */
#include "soup.h"
#include "geom.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
/* ---- smoothing ------------------------------------------------------- */

/* Worst corner over the faces around vertex v (its corner slots vc[vs[v] ..
 * vs[v+1]), A->sf giving each slot's face). */
static double worst_around(const glpgp_quadmesh *q, const adjacency *A, const int *vs, const int *vc, int v)
{
    double m = INFINITY;
    for (int j = vs[v]; j < vs[v + 1]; j++) {
        int f = A->sf[vc[j]], b = q->face_start[f];
        m = fmin(m, glpgp_poly_min_sj(q->xy, q->face_vert + b, q->face_start[f + 1] - b));
    }
    return m;
}

glpgp_status glpgp_quadmesh_smooth(glpgp_quadmesh *q, const unsigned char *mark, int iterations, double sj_below,
                                   int *moved)
{
    if (moved) *moved = 0;
    if (!q || iterations <= 0 || q->nv <= 0) return GLPGP_OK;
    int nv = q->nv, nf = q->nf, nc = q->face_start[nf];
    int *vs = NULL, *vc = NULL, *cnt = NULL;
    unsigned char *act = NULL;
    psoup s;
    adjacency A;
    memset(&A, 0, sizeof A);
    /* the soup has the mesh's corner layout (slot c = face_vert index c):
     * A gives the boundary (and non-manifold) vertices and each slot's face */
    glpgp_status st = glpgp_soup_from_mesh(q, &s);
    if (st == GLPGP_OK) st = glpgp_adj_build(&s, &A);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)nv + 1, sizeof(int), &vs);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nc + 1, sizeof(int), &vc);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)nv + 1, sizeof(int), &cnt);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)nv + 1, 1, &act);
    if (st != GLPGP_OK) goto done;
    /* vertex -> its corner slots (CSR) */
    for (int c = 0; c < nc; c++) vs[q->face_vert[c] + 1]++;
    for (int v = 0; v < nv; v++) vs[v + 1] += vs[v];
    for (int c = 0; c < nc; c++) vc[vs[q->face_vert[c]] + cnt[q->face_vert[c]]++] = c;
    /* active: vertices of marked faces (a corner is marked) or of faces worse
     * than sj_below, and their edge neighbours; never boundary vertices */
    for (int f = 0; f < nf; f++) {
        int b = q->face_start[f], n = q->face_start[f + 1] - b;
        int hit = glpgp_poly_min_sj(q->xy, q->face_vert + b, n) < sj_below;
        for (int i = 0; i < n && !hit && mark; i++) hit = mark[q->face_vert[b + i]];
        if (!hit) continue;
        for (int i = 0; i < n; i++) {
            int v = q->face_vert[b + i];
            act[v] = 1;
            for (int j = vs[v]; j < vs[v + 1]; j++) { /* edge neighbours: previous and next corners */
                int c = vc[j], g = A.sf[c], gb = q->face_start[g], gn = q->face_start[g + 1] - gb;
                act[q->face_vert[gb + (c - gb + 1) % gn]] = 1;
                act[q->face_vert[gb + (c - gb + gn - 1) % gn]] = 1;
            }
        }
    }
    for (int it = 0; it < iterations; it++) {
        int changed = 0;
        for (int v = 0; v < nv; v++) {
            if (!act[v] || A.bnd[v] || vs[v + 1] - vs[v] < 2) continue;
            /* target: mean of the edge neighbours; for an interior vertex each
             * neighbour is the previous corner of one face and the next corner
             * of another, so the mean over the faces' previous and next
             * corners is that mean */
            double tx = 0.0, ty = 0.0;
            int k = 0;
            for (int j = vs[v]; j < vs[v + 1]; j++) {
                int c = vc[j], f = A.sf[c], b = q->face_start[f], n = q->face_start[f + 1] - b, i = c - b;
                int pv = q->face_vert[b + (i + n - 1) % n], nx = q->face_vert[b + (i + 1) % n];
                tx += q->xy[2 * pv] + q->xy[2 * nx];
                ty += q->xy[2 * pv + 1] + q->xy[2 * nx + 1];
                k += 2;
            }
            tx /= k;
            ty /= k;
            /* the step (1/4 .. 1 of the way to the mean) that most raises the
             * worst corner around v; none if no step raises it by 1e-3 */
            double ox = q->xy[2 * v], oy = q->xy[2 * v + 1], bw = 0.0;
            double bval = worst_around(q, &A, vs, vc, v) + 1e-3;
            for (int tr = 1; tr <= 4; tr++) {
                double w = 0.25 * tr;
                q->xy[2 * v] = ox + w * (tx - ox);
                q->xy[2 * v + 1] = oy + w * (ty - oy);
                double after = worst_around(q, &A, vs, vc, v);
                if (after > bval) {
                    bval = after;
                    bw = w;
                }
            }
            q->xy[2 * v] = ox + bw * (tx - ox);
            q->xy[2 * v + 1] = oy + bw * (ty - oy);
            if (bw > 0.0) {
                changed++;
                if (act[v] == 1) {
                    act[v] = 2; /* counted once */
                    if (moved) (*moved)++;
                }
            }
        }
        if (!changed) break;
    }
done:
    glpgp_soup_free(&s);
    glpgp_adj_free(&A);
    free(vs);
    free(vc);
    free(cnt);
    free(act);
    return st;
}

