/* quads/qmesh.c: the quad mesh object (glpgp_quadmesh_destroy) and the
 * all-quad refinement (glpgp_quadmesh_subdivide, one Catmull-Clark step
 * without smoothing). */
#include "glpgp/quads.h"
#include "glpgp/status.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void glpgp_quadmesh_destroy(glpgp_quadmesh **q)
{
    if (!q || !*q) return;
    free((*q)->xy);
    free((*q)->face_start);
    free((*q)->face_vert);
    free((*q)->face_origin);
    free((*q)->xyz);
    free(*q);
    *q = NULL;
}

/* ---- refinement to an all-quad mesh ------------------------------------ */

static int cmp_ll2(const void *pa, const void *pb)
{
    const long long *a = pa, *b = pb;
    return (a[0] > b[0]) - (a[0] < b[0]);
}

void glpgp_quadmesh_face_normal(const glpgp_quadmesh *q, int f, int unit, double *N)
{
    const int s = q->face_start[f], n = q->face_start[f + 1] - s;
    N[0] = N[1] = N[2] = 0.0;
    for (int i = 0; i < n; i++) { /* Newell's formula */
        const double *a = q->xyz + 3 * q->face_vert[s + i], *b = q->xyz + 3 * q->face_vert[s + (i + 1) % n];
        N[0] += (a[1] - b[1]) * (a[2] + b[2]);
        N[1] += (a[2] - b[2]) * (a[0] + b[0]);
        N[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    const double l = sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
    if (unit && l > 0)
        for (int d = 0; d < 3; d++) N[d] /= l;
}

glpgp_status glpgp_quadmesh_subdivide(const glpgp_quadmesh *q, glpgp_quadmesh **out)
{
    *out = NULL;
    if (!q || q->nf < 1) return GLPGP_FAIL(GLPGP_ERR_ARG, "quad refinement: empty mesh");
    const int nc = q->face_start[q->nf]; /* face sides = corners */
    glpgp_status st = GLPGP_OK;
    long long *key = NULL; /* (edge key, side index) pairs, sorted */
    int *side_mid = NULL;  /* per side: index of its midpoint in the output */
    glpgp_quadmesh *r = NULL;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc, 2 * sizeof(long long), &key), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc, sizeof(int), &side_mid), done);
    for (int f = 0; f < q->nf; f++) {
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        for (int i = 0; i < k; i++) {
            long long a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % k];
            key[2 * (s + i)] = (a < b ? a : b) * (long long)q->nv + (a < b ? b : a);
            key[2 * (s + i) + 1] = s + i;
        }
    }
    qsort(key, (size_t)nc, 2 * sizeof(long long), cmp_ll2);
    GLPGP_CHECK_GOTO(st, glpgp_calloc(1, sizeof *r, &r), done);
    /* vertices: the old ones, one midpoint per edge, one center per face */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)q->nv + nc + q->nf, 2 * sizeof(double), &r->xy), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof(int), &r->face_start), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc, 4 * sizeof(int), &r->face_vert), done);
    if (q->face_origin) GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, 1, &r->face_origin), done);
    memcpy(r->xy, q->xy, (size_t)q->nv * 2 * sizeof(double));
    r->nv = q->nv;
    for (int i = 0; i < nc;) {
        int j = i;
        long long ab = key[2 * i];
        int a = (int)(ab / q->nv), b = (int)(ab % q->nv);
        r->xy[2 * r->nv] = 0.5 * (q->xy[2 * a] + q->xy[2 * b]);
        r->xy[2 * r->nv + 1] = 0.5 * (q->xy[2 * a + 1] + q->xy[2 * b + 1]);
        while (j < nc && key[2 * j] == ab) side_mid[key[2 * j++ + 1]] = r->nv;
        r->nv++;
        i = j;
    }
    int w = 0;
    r->face_start[0] = 0;
    for (int f = 0; f < q->nf; f++) {
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        double cx = 0.0, cy = 0.0;
        for (int i = 0; i < k; i++) {
            cx += q->xy[2 * q->face_vert[s + i]] / k;
            cy += q->xy[2 * q->face_vert[s + i] + 1] / k;
        }
        int c = r->nv++;
        r->xy[2 * c] = cx;
        r->xy[2 * c + 1] = cy;
        for (int i = 0; i < k; i++) { /* corner i, midpoint of side i, center, midpoint of side i-1 */
            r->face_vert[w++] = q->face_vert[s + i];
            r->face_vert[w++] = side_mid[s + i];
            r->face_vert[w++] = c;
            r->face_vert[w++] = side_mid[s + (i + k - 1) % k];
            if (r->face_origin) r->face_origin[r->nf] = q->face_origin[f];
            r->face_start[++r->nf] = w;
        }
    }
    for (int k = 0; k < 2; k++) {
        r->singular_tris[k] = q->singular_tris[k];
        r->inconsistent_tris[k] = q->inconsistent_tris[k];
    }
    r->collapsed_edges = q->collapsed_edges;
    r->promoted_corners = q->promoted_corners;
    r->split_pentagons = q->split_pentagons;
    r->center_splits = q->center_splits;
    *out = r;
    r = NULL;
done:
    glpgp_quadmesh_destroy(&r);
    free(key);
    free(side_mid);
    return st;
}
