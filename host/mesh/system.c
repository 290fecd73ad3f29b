/* mesh/system.c: block-CSR pattern and gather maps of a mesh (glpgp/system.h). */
#include "glpgp/system.h"

#include <stdlib.h>

/* The vertices of the triangles at vertex i (i among them), each once
 * (cnt[j] == i marks j seen; start with cnt[] = -1 and rows in increasing
 * order); col (may be NULL) receives them in increasing order. Returns
 * their count. */
static int row_neighbours(const glpgp_system *s, const glpgp_mesh *m, int i, int *cnt, int *col)
{
    int n = 0;
    for (int p = s->vptr[i]; p < s->vptr[i + 1]; p++) {
        const int t = s->vtri[p] / 3;
        for (int b = 0; b < 3; b++) {
            const int j = m->tri[3 * t + b];
            if (cnt[j] == i) continue;
            cnt[j] = i;
            if (col) { /* insertion sort into the row */
                int q = n;
                while (q > 0 && col[q - 1] > j) {
                    col[q] = col[q - 1];
                    q--;
                }
                col[q] = j;
            }
            n++;
        }
    }
    return n;
}

glpgp_status glpgp_system_create(const glpgp_mesh *m, glpgp_system **out)
{
    glpgp_status st = GLPGP_OK;
    glpgp_system *s = NULL;
    int *cnt = NULL, *fill = NULL;
    *out = NULL;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *s, &s));
    s->nv = m->nv;
    s->nt = m->nt;
    s->mesh = m;
    const int nv = m->nv, nt = m->nt;

    /* vertex -> triangle corners */
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv + 1, sizeof(int), &s->vptr), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt, sizeof(int), &s->vtri), fail);
    for (int t = 0; t < nt; t++)
        for (int a = 0; a < 3; a++) s->vptr[m->tri[3 * t + a] + 1]++;
    for (int i = 0; i < nv; i++) s->vptr[i + 1] += s->vptr[i];
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(int), &fill), fail);
    for (int i = 0; i < nv; i++) fill[i] = s->vptr[i];
    for (int t = 0; t < nt; t++) /* increasing t within each vertex list */
        for (int a = 0; a < 3; a++) s->vtri[fill[m->tri[3 * t + a]]++] = 3 * t + a;

    /* row pattern: neighbours of i = vertices of its triangles (sorted, unique).
     * Collect per row with a marker array. */
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv + 1, sizeof(int), &s->rowptr), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(int), &cnt), fail);
    for (int i = 0; i < nv; i++) cnt[i] = -1;
    for (int i = 0; i < nv; i++) s->rowptr[i + 1] = s->rowptr[i] + row_neighbours(s, m, i, cnt, NULL);
    s->nnzb = s->rowptr[nv];
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)s->nnzb, sizeof(int), &s->col), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(int), &s->diag), fail);
    for (int i = 0; i < nv; i++) cnt[i] = -1;
    for (int i = 0; i < nv; i++) {
        row_neighbours(s, m, i, cnt, s->col + s->rowptr[i]);
        for (int q = s->rowptr[i]; q < s->rowptr[i + 1]; q++)
            if (s->col[q] == i) s->diag[i] = q;
    }

    /* gather map: each element entry (t,a,b) -> slot of (tri[a], tri[b]) */
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)s->nnzb + 1, sizeof(int), &s->cptr), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)9 * nt, sizeof(int), &s->contrib), fail);
    int *slot = NULL;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)9 * nt, sizeof(int), &slot), fail);
    for (int t = 0; t < nt; t++)
        for (int a = 0; a < 3; a++) {
            int i = m->tri[3 * t + a];
            for (int b = 0; b < 3; b++) {
                int j = m->tri[3 * t + b];
                int lo = s->rowptr[i], hi = s->rowptr[i + 1] - 1;
                while (lo < hi) { /* binary search j in row i */
                    int mid = (lo + hi) / 2;
                    if (s->col[mid] < j) lo = mid + 1;
                    else hi = mid;
                }
                slot[9 * t + 3 * a + b] = lo;
                s->cptr[lo + 1]++;
            }
        }
    for (long k = 0; k < s->nnzb; k++) s->cptr[k + 1] += s->cptr[k];
    free(fill);
    fill = NULL;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)s->nnzb, sizeof(int), &fill), fail2);
    for (long k = 0; k < s->nnzb; k++) fill[k] = s->cptr[k];
    for (int e = 0; e < 9 * nt; e++) s->contrib[fill[slot[e]]++] = e; /* increasing t */
    free(slot);
    free(fill);
    free(cnt);
    *out = s;
    return GLPGP_OK;
fail2:
    free(slot);
fail:
    free(fill);
    free(cnt);
    glpgp_system_destroy(&s);
    return st;
}

void glpgp_system_destroy(glpgp_system **ps)
{
    if (!ps || !*ps) return;
    glpgp_system *s = *ps;
    free(s->rowptr);
    free(s->col);
    free(s->diag);
    free(s->cptr);
    free(s->contrib);
    free(s->vptr);
    free(s->vtri);
    free(s->cconj);
    free(s->cfield);
    free(s->ctxy);
    free(s->crot);
    free(s);
    *ps = NULL;
}
