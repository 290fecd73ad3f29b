/* quads/soup.c: the polygon soup of the closing (soup.h): growth, faces,
 * the conversions from and to a quad mesh, and the face adjacency. */
#include "soup.h"
#include "glpgp/status.h"

#include <stdlib.h>
#include <string.h>

/* ---- growable polygon soup ---- */

/* Origin of a face made from face f by the closing. */
unsigned char glpgp_soup_closed_origin(const psoup *s, int f)
{
    return s->fo[f] > GLPGP_QFACE_CLOSED ? s->fo[f] : GLPGP_QFACE_CLOSED;
}

glpgp_status glpgp_soup_vertex(psoup *s, double x, double y, int *id)
{
    glpgp_status st = glpgp_grow_int(&s->xy, &s->cap_v, 2 * (s->nv + 1), sizeof(double));
    if (st != GLPGP_OK) return st;
    s->xy[2 * s->nv] = x;
    s->xy[2 * s->nv + 1] = y;
    *id = s->nv++;
    return GLPGP_OK;
}

/* Append a face (n corners v[]); *id (may be NULL) receives its index. */
glpgp_status glpgp_soup_face(psoup *s, const int *v, int n, int *id)
{
    glpgp_status st = glpgp_grow_int(&s->fv, &s->cap_fv, s->nfv + n, sizeof(int));
    if (st != GLPGP_OK) return st;
    if (s->nf + 1 > s->cap_f) {
        int c = s->cap_f ? 2 * s->cap_f : 64;
        int *a = realloc(s->fs, (size_t)c * sizeof(int));
        if (a) s->fs = a;
        int *b = a ? realloc(s->fn, (size_t)c * sizeof(int)) : NULL;
        if (b) s->fn = b;
        unsigned char *o = b ? realloc(s->fo, (size_t)c) : NULL;
        if (!o) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad pairing: out of memory");
        s->fo = o;
        s->cap_f = c;
    }
    s->fo[s->nf] = s->cur;
    memcpy(s->fv + s->nfv, v, (size_t)n * sizeof(int));
    s->fs[s->nf] = s->nfv;
    s->fn[s->nf] = n;
    s->nfv += n;
    if (id) *id = s->nf;
    s->nf++;
    return GLPGP_OK;
}

void glpgp_soup_free(psoup *s)
{
    free(s->xy);
    free(s->fs);
    free(s->fn);
    free(s->fv);
    free(s->fo);
    memset(s, 0, sizeof *s);
}


/* ---- quad mesh <-> soup ---- */

glpgp_status glpgp_soup_from_mesh(const glpgp_quadmesh *q, psoup *s)
{
    memset(s, 0, sizeof *s);
    glpgp_status st = glpgp_grow_int(&s->xy, &s->cap_v, 2 * q->nv + 2, sizeof(double));
    if (st != GLPGP_OK) return st;
    memcpy(s->xy, q->xy, 2 * (size_t)q->nv * sizeof(double));
    s->nv = q->nv;
    for (int f = 0; f < q->nf && st == GLPGP_OK; f++) {
        s->cur = q->face_origin ? q->face_origin[f] : GLPGP_QFACE_GRID;
        st = glpgp_soup_face(s, q->face_vert + q->face_start[f], q->face_start[f + 1] - q->face_start[f], NULL);
    }
    return st;
}

/* The live faces of s as a new quad mesh (unused vertices dropped); the
 * extraction diagnostics are copied from ref. */
glpgp_status glpgp_soup_to_mesh(const psoup *s, const glpgp_quadmesh *ref, const unsigned char *mark,
                                 unsigned char **omark, glpgp_quadmesh **out)
{
    glpgp_quadmesh *q = NULL;
    int *id = NULL;
    glpgp_status st = glpgp_calloc(1, sizeof *q, &q);
    if (st != GLPGP_OK) return st;
    *q = *ref; /* diagnostics; the arrays are replaced below */
    q->xy = NULL;
    q->face_start = NULL;
    q->face_vert = NULL;
    q->face_origin = NULL;
    st = glpgp_malloc((size_t)s->nv + 1, sizeof(int), &id);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)s->nf + 1, sizeof(int), &q->face_start);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)s->nfv + 1, sizeof(int), &q->face_vert);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)s->nv + 1, 2 * sizeof(double), &q->xy);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)s->nv + 1, 1, omark);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)s->nf + 1, 1, &q->face_origin);
    if (st != GLPGP_OK) {
        glpgp_quadmesh_destroy(&q);
        free(id);
        return st;
    }
    for (int v = 0; v < s->nv; v++) id[v] = -1;
    q->nv = 0;
    q->nf = 0;
    int w = 0;
    q->face_start[0] = 0;
    for (int f = 0; f < s->nf; f++) {
        if (s->fn[f] == 0) continue;
        for (int i = 0; i < s->fn[f]; i++) {
            int v = s->fv[s->fs[f] + i];
            if (id[v] < 0) {
                id[v] = q->nv;
                q->xy[2 * q->nv] = s->xy[2 * v];
                q->xy[2 * q->nv + 1] = s->xy[2 * v + 1];
                (*omark)[q->nv] = mark[v];
                q->nv++;
            }
            q->face_vert[w++] = id[v];
        }
        q->face_origin[q->nf] = s->fo[f];
        q->face_start[++q->nf] = w;
    }
    free(id);
    *out = q;
    return GLPGP_OK;
}

/* ---- adjacency ------------------------------------------------------- */



static int cmp_hedge(const void *pa, const void *pb)
{
    const hedge *x = pa, *y = pb;
    if (x->a != y->a) return x->a < y->a ? -1 : 1;
    if (x->b != y->b) return x->b < y->b ? -1 : 1;
    if (x->f != y->f) return x->f < y->f ? -1 : 1;
    return x->i - y->i;
}

/* adj[fs[f] + i]: the face across edge i of f (-1 boundary, -2 an edge
 * used by more than two faces); adji: the edge's index in that face.
 * val[v]: vertex valence (number of distinct edges), bnd[v]: on a boundary
 * or non-manifold edge. */


void glpgp_adj_free(adjacency *A)
{
    free(A->adj);
    free(A->adji);
    free(A->val);
    free(A->sf);
    free(A->bnd);
    memset(A, 0, sizeof *A);
}

glpgp_status glpgp_adj_build(const psoup *s, adjacency *A)
{
    glpgp_adj_free(A);
    hedge *H = NULL;
    int nh = 0;
    glpgp_status st = glpgp_malloc((size_t)s->nfv + 1, sizeof *H, &H);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)s->nfv + 1, sizeof(int), &A->adj);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)s->nfv + 1, sizeof(int), &A->adji);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)s->nfv + 1, sizeof(int), &A->sf);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)s->nv + 1, sizeof(int), &A->val);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)s->nv + 1, 1, &A->bnd);
    if (st != GLPGP_OK) {
        free(H);
        glpgp_adj_free(A);
        return st;
    }
    for (int f = 0; f < s->nf; f++)
        for (int i = 0; i < s->fn[f]; i++) {
            int a = s->fv[s->fs[f] + i], b = s->fv[s->fs[f] + (i + 1) % s->fn[f]];
            H[nh++] = (hedge){a < b ? a : b, a < b ? b : a, f, i};
            A->sf[s->fs[f] + i] = f;
        }
    qsort(H, (size_t)nh, sizeof *H, cmp_hedge);
    for (int k = 0; k < nh;) {
        int e = k + 1;
        while (e < nh && H[e].a == H[k].a && H[e].b == H[k].b) e++;
        A->val[H[k].a]++;
        A->val[H[k].b]++;
        if (e - k == 1) {
            A->adj[s->fs[H[k].f] + H[k].i] = -1;
            A->bnd[H[k].a] = A->bnd[H[k].b] = 1;
        } else if (e - k == 2) {
            A->adj[s->fs[H[k].f] + H[k].i] = H[k + 1].f;
            A->adji[s->fs[H[k].f] + H[k].i] = H[k + 1].i;
            A->adj[s->fs[H[k + 1].f] + H[k + 1].i] = H[k].f;
            A->adji[s->fs[H[k + 1].f] + H[k + 1].i] = H[k].i;
        } else { /* non-manifold: treated like the boundary */
            for (int j = k; j < e; j++) A->adj[s->fs[H[j].f] + H[j].i] = -2;
            A->bnd[H[k].a] = A->bnd[H[k].b] = 1;
        }
        k = e;
    }
    free(H);
    A->nv = s->nv;
    return GLPGP_OK;
}

