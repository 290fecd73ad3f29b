/* quads/split_surface.c: the local split of a quad mesh of a surface
 * (glpgp_qs_split_local, quads_surface.h), the Catmull-Clark split of
 * quads_surface.c kept to where it is needed:
 *  - the selected faces (any corner count) are split as Catmull-Clark does:
 *    n quads each (corner, side midpoint, centroid, side midpoint);
 *  - a side that got a midpoint makes the quad across it split in two,
 *    through the midpoint of its opposite side, which splits the quad
 *    across that one: the split runs along the quad strip until it meets
 *    a split side again, a selected face or the surface's boundary; a face
 *    that is not a quad met on the way is split as a selected one;
 *  - a quad reached by two strips (all four sides split) is split in four.
 * Every face is then a quad and every edge is split on both of its sides
 * or on none: the result is a conforming all-quad mesh with the input's
 * topology whatever the geometry (the new points, midpoints and centroids,
 * moved onto the surface). Its validity in 3D is the caller's check. */
#include "quads_surface.h"

#include "glpgp/util.h"

#include <stdlib.h>
#include <string.h>

typedef struct sl_edge {
    long long key;
    int c;
} sl_edge;

static int cmp_sl(const void *pa, const void *pb)
{
    const sl_edge *a = pa, *b = pb;
    return a->key < b->key ? -1 : a->key > b->key ? 1 : a->c - b->c;
}

/* The mesh's edges: eid per corner, ecs/ecc the corners of each edge. */
typedef struct sl_ctx {
    const glpgp_quadmesh *q;
    int nc, ne;
    int *eid, *cface, *ecs, *ecc;
    unsigned char *split; /* per edge */
    unsigned char *in;    /* per face: split as Catmull-Clark does */
    int *queue, nq;
} sl_ctx;

static glpgp_status sl_edges(sl_ctx *S)
{
    const glpgp_quadmesh *q = S->q;
    sl_edge *E = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)S->nc + 1, sizeof *E, &E));
    for (int f = 0; f < q->nf; f++) {
        const int s = q->face_start[f], n = q->face_start[f + 1] - s;
        for (int i = 0; i < n; i++) {
            const long long a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % n];
            E[s + i] = (sl_edge){a < b ? a * q->nv + b : b * q->nv + a, s + i};
            S->cface[s + i] = f;
        }
    }
    qsort(E, (size_t)S->nc, sizeof *E, cmp_sl);
    S->ne = 0;
    for (int i = 0; i < S->nc; i++) {
        if (i > 0 && E[i].key != E[i - 1].key) S->ne++;
        S->eid[E[i].c] = S->ne;
        S->ecc[i] = E[i].c;
        if (i == 0 || E[i].key != E[i - 1].key) S->ecs[S->ne] = i;
    }
    if (S->nc) S->ne++;
    S->ecs[S->ne] = S->nc;
    free(E);
    return GLPGP_OK;
}

static void flag_edge(sl_ctx *S, int e)
{
    if (S->split[e]) return;
    S->split[e] = 1;
    S->queue[S->nq++] = e;
}

static void flag_face(sl_ctx *S, int f)
{
    if (S->in[f]) return;
    S->in[f] = 1;
    for (int c = S->q->face_start[f]; c < S->q->face_start[f + 1]; c++) flag_edge(S, S->eid[c]);
}

/* The split closed along the strips: each split edge's quads split across. */
static void sl_close(sl_ctx *S)
{
    const glpgp_quadmesh *q = S->q;
    for (int head = 0; head < S->nq; head++) {
        const int e = S->queue[head];
        for (int k = S->ecs[e]; k < S->ecs[e + 1]; k++) {
            const int c = S->ecc[k], g = S->cface[c], s = q->face_start[g], n = q->face_start[g + 1] - s;
            if (S->in[g]) continue;
            if (n != 4) flag_face(S, g);
            else flag_edge(S, S->eid[s + (c - s + 2) % 4]);
        }
    }
    for (int f = 0; f < q->nf; f++) { /* a quad crossed by two strips: split in four */
        const int s = q->face_start[f];
        if (!S->in[f] && q->face_start[f + 1] - s == 4 && S->split[S->eid[s]] && S->split[S->eid[s + 1]]) S->in[f] = 1;
    }
}

static void sl_free(sl_ctx *S)
{
    free(S->eid);
    free(S->cface);
    free(S->ecs);
    free(S->ecc);
    free(S->split);
    free(S->in);
    free(S->queue);
}

/* The new mesh: the points, one per split edge, one per split face; the faces. */
static glpgp_status sl_build(const sl_ctx *S, glpgp_quadmesh **out, int *nsplit)
{
    const glpgp_quadmesh *q = S->q;
    int *emid = NULL, *fcen = NULL, nv = q->nv, nf = 0;
    glpgp_quadmesh *r = NULL;
    glpgp_status st = glpgp_malloc((size_t)S->ne + 1, sizeof(int), &emid);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)q->nf + 1, sizeof(int), &fcen);
    if (st != GLPGP_OK) goto done;
    for (int e = 0; e < S->ne; e++) emid[e] = S->split[e] ? nv++ : -1;
    *nsplit = 0;
    for (int f = 0; f < q->nf; f++) {
        const int s = q->face_start[f], n = q->face_start[f + 1] - s;
        fcen[f] = S->in[f] ? nv++ : -1;
        nf += S->in[f] ? n : (S->split[S->eid[s]] || S->split[S->eid[s + 1]]) ? 2 : 1;
        *nsplit += S->in[f] || S->split[S->eid[s]] || S->split[S->eid[s + 1]];
    }
    GLPGP_CHECK_GOTO(st, glpgp_qs_alloc(nv, nf, 4 * nf, &r), done);
    memcpy(r->xyz, q->xyz, (size_t)3 * q->nv * sizeof(double));
    for (int e = 0; e < S->ne; e++) {
        if (emid[e] < 0) continue;
        const int c = S->ecc[S->ecs[e]], f = S->cface[c], s = q->face_start[f], n = q->face_start[f + 1] - s;
        const double *a = q->xyz + 3 * q->face_vert[c], *b = q->xyz + 3 * q->face_vert[s + (c - s + 1) % n];
        for (int d = 0; d < 3; d++) r->xyz[3 * emid[e] + d] = 0.5 * (a[d] + b[d]);
    }
    int o = 0;
    for (int f = 0; f < q->nf; f++) {
        const int s = q->face_start[f], n = q->face_start[f + 1] - s, *v = q->face_vert + s;
        const unsigned char org = q->face_origin ? q->face_origin[f] : GLPGP_QFACE_GRID;
        int quad[8], nqd = 0;
        if (fcen[f] >= 0) {
            for (int d = 0; d < 3; d++) {
                double x = 0.0;
                for (int i = 0; i < n; i++) x += q->xyz[3 * v[i] + d];
                r->xyz[3 * fcen[f] + d] = x / n;
            }
            for (int i = 0; i < n; i++, o++) {
                int *w = r->face_vert + 4 * o;
                w[0] = v[i];
                w[1] = emid[S->eid[s + i]];
                w[2] = fcen[f];
                w[3] = emid[S->eid[s + (i + n - 1) % n]];
                r->face_start[o] = 4 * o;
                r->face_origin[o] = org;
            }
            continue;
        }
        const int i = S->split[S->eid[s]] ? 0 : S->split[S->eid[s + 1]] ? 1 : -1;
        if (i < 0) {
            memcpy(quad, v, 4 * sizeof *v);
            nqd = 1;
        } else { /* sides i and i + 2 split: (a, m1, m2, d), (m1, b, c, m2) */
            const int a = v[i], b = v[(i + 1) % 4], c = v[(i + 2) % 4], dd = v[(i + 3) % 4];
            const int m1 = emid[S->eid[s + i]], m2 = emid[S->eid[s + (i + 2) % 4]];
            const int t[8] = {a, m1, m2, dd, m1, b, c, m2};
            memcpy(quad, t, sizeof t);
            nqd = 2;
        }
        for (int k = 0; k < nqd; k++, o++) {
            memcpy(r->face_vert + 4 * o, quad + 4 * k, 4 * sizeof *quad);
            r->face_start[o] = 4 * o;
            r->face_origin[o] = org;
        }
    }
    r->face_start[nf] = 4 * nf;
    *out = r;
    r = NULL;
done:
    glpgp_quadmesh_destroy(&r);
    free(emid);
    free(fcen);
    return st;
}

glpgp_status glpgp_qs_split_local(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, const unsigned char *sel,
                                  glpgp_quadmesh **out, int *nsplit)
{
    *out = NULL;
    *nsplit = 0;
    if (!q || !q->xyz || q->nf == 0) return GLPGP_FAIL(GLPGP_ERR_ARG, "local split: an empty or planar mesh");
    sl_ctx S;
    memset(&S, 0, sizeof S);
    S.q = q;
    S.nc = q->face_start[q->nf];
    glpgp_status st = glpgp_malloc((size_t)S.nc + 1, sizeof(int), &S.eid);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)S.nc + 1, sizeof(int), &S.cface);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)S.nc + 2, sizeof(int), &S.ecs);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)S.nc + 1, sizeof(int), &S.ecc);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)S.nc + 1, 1, &S.split);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)q->nf + 1, 1, &S.in);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)S.nc + 1, sizeof(int), &S.queue);
    if (st == GLPGP_OK) st = sl_edges(&S);
    if (st != GLPGP_OK) goto done;
    for (int f = 0; f < q->nf; f++)
        if (sel[f] || q->face_start[f + 1] - q->face_start[f] != 4) flag_face(&S, f);
    sl_close(&S);
    GLPGP_CHECK_GOTO(st, sl_build(&S, out, nsplit), done);
    GLPGP_CHECK_GOTO(st, glpgp_qs_project(m, h, (*out)->xyz, q->nv, (*out)->nv), done);
    glpgp_qs_finish_from(*out, q);
done:
    if (st != GLPGP_OK) glpgp_quadmesh_destroy(out);
    sl_free(&S);
    return st;
}
