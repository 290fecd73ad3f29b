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
 * moved onto the surface). Its validity in 3D is the caller's check.
 *
 * Flat boundary corners (glpgp_qs_split_flat): a boundary vertex c in one
 * quad Q = (c, d, a, b) only, where the boundary runs nearly straight (the
 * corner obtuse, its scaled Jacobian below a goal), makes Q a triangle
 * a-b-d with c on its base: no vertex move helps (the surface's version of
 * the planar shape pass, shape.c part 1). Q is split like a triangle: three
 * quads about a new point g (the centroid of a, b, d) and the midpoints of
 * d-a and a-b, (c, d, m_da, g), (g, m_da, a, m_ab), (m_ab, b, c, g); the two
 * midpoints are carried across the mesh by the strips above. c then has two
 * faces with about right angles, g is a valence-3 vertex. */
#include "quads_surface.h"
#include "vec3.h"

#include "glpgp/util.h"

#include <math.h>
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
    unsigned char *in;    /* per face: 1 split as Catmull-Clark does, 2 split like a triangle at a
                             flat corner (flat[f]) */
    const signed char *flat; /* per face: the flat corner, -1 none (NULL: none) */
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

/* Quad f split like a triangle at its flat corner k: the two sides away from it */
static void flag_flat(sl_ctx *S, int f, int k)
{
    const int s = S->q->face_start[f];
    S->in[f] = 2;
    flag_edge(S, S->eid[s + (k + 1) % 4]);
    flag_edge(S, S->eid[s + (k + 2) % 4]);
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
    int again = 0;
    for (int f = 0; f < q->nf; f++) { /* a strip into a flat corner's sides: split as Catmull-Clark */
        const int s = q->face_start[f];
        if (S->in[f] != 2 || !(S->split[S->eid[s + S->flat[f]]] || S->split[S->eid[s + (S->flat[f] + 3) % 4]]))
            continue;
        S->in[f] = 0;
        flag_face(S, f);
        again = 1;
    }
    if (again) {
        sl_close(S);
        return;
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
        nf += S->in[f] == 2 ? 3 : S->in[f] ? n : (S->split[S->eid[s]] || S->split[S->eid[s + 1]]) ? 2 : 1;
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
        int quad[12], nqd = 0;
        if (S->in[f] == 2) { /* (c, d, m_da, g), (g, m_da, a, m_ab), (m_ab, b, c, g) */
            const int k = S->flat[f], c = v[k], d = v[(k + 1) % 4], a = v[(k + 2) % 4], b = v[(k + 3) % 4];
            const int mda = emid[S->eid[s + (k + 1) % 4]], mab = emid[S->eid[s + (k + 2) % 4]], g = fcen[f];
            for (int e = 0; e < 3; e++)
                r->xyz[3 * g + e] = (q->xyz[3 * a + e] + q->xyz[3 * b + e] + q->xyz[3 * d + e]) / 3.0;
            const int t[12] = {c, d, mda, g, g, mda, a, mab, mab, b, c, g};
            memcpy(quad, t, sizeof t);
            nqd = 3;
        } else if (fcen[f] >= 0) {
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
        if (nqd) {
            /* the flat corner's three quads */
        } else if (i < 0) {
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

static glpgp_status split_run(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, const unsigned char *sel,
                              const signed char *flat, glpgp_quadmesh **out, int *nsplit)
{
    *out = NULL;
    *nsplit = 0;
    if (!q || !q->xyz || q->nf == 0) return GLPGP_FAIL(GLPGP_ERR_ARG, "local split: an empty or planar mesh");
    sl_ctx S;
    memset(&S, 0, sizeof S);
    S.q = q;
    S.flat = flat;
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
    for (int f = 0; f < q->nf; f++) {
        const int n = q->face_start[f + 1] - q->face_start[f];
        if (flat && flat[f] >= 0 && n == 4) flag_flat(&S, f, flat[f]);
        else if ((sel && sel[f]) || n != 4) flag_face(&S, f);
    }
    sl_close(&S);
    GLPGP_CHECK_GOTO(st, sl_build(&S, out, nsplit), done);
    GLPGP_CHECK_GOTO(st, glpgp_qs_project(m, h, (*out)->xyz, q->nv, (*out)->nv), done);
    glpgp_qs_finish_from(*out, q);
done:
    if (st != GLPGP_OK) glpgp_quadmesh_destroy(out);
    sl_free(&S);
    return st;
}

glpgp_status glpgp_qs_split_local(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, const unsigned char *sel,
                                  glpgp_quadmesh **out, int *nsplit)
{
    return split_run(m, q, h, sel, NULL, out, nsplit);
}

/* The scaled Jacobian of corner k of quad v in the quad's own plane
 * (Newell's normal); 2 when the quad or the corner is degenerate (not
 * flat: left alone). *obtuse: the corner is over 90 degrees. */
static double corner_sj(const double *xyz, const int *v, int k, int *obtuse)
{
    double N[3] = {0, 0, 0}, e1[3], e2[3], x[3];
    for (int i = 0; i < 4; i++) {
        const double *a = xyz + 3 * v[i], *b = xyz + 3 * v[(i + 1) % 4];
        N[0] += (a[1] - b[1]) * (a[2] + b[2]);
        N[1] += (a[2] - b[2]) * (a[0] + b[0]);
        N[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    const double *p = xyz + 3 * v[k];
    sub3(xyz + 3 * v[(k + 1) % 4], p, e1);
    sub3(xyz + 3 * v[(k + 3) % 4], p, e2);
    const double l = sqrt(dot3(N, N) * dot3(e1, e1) * dot3(e2, e2));
    if (!(l > 0.0)) return 2.0;
    cross3(e1, e2, x);
    *obtuse = dot3(e1, e2) < 0.0;
    return dot3(x, N) / l;
}

glpgp_status glpgp_qs_find_flat(const glpgp_quadmesh *q, double goal, signed char *flat, int *nflat)
{
    int *nface = NULL;
    *nflat = 0;
    GLPGP_CHECK(glpgp_calloc((size_t)q->nv + 1, sizeof(int), &nface));
    for (int c = 0; c < q->face_start[q->nf]; c++) nface[q->face_vert[c]]++;
    for (int f = 0; f < q->nf; f++) {
        const int s = q->face_start[f];
        flat[f] = -1;
        if (q->face_start[f + 1] - s != 4) continue;
        double worst = goal;
        for (int k = 0; k < 4; k++) {
            int obtuse = 0;
            if (nface[q->face_vert[s + k]] != 1) continue; /* a boundary vertex in this face only */
            const double sj = corner_sj(q->xyz, q->face_vert + s, k, &obtuse);
            if (obtuse && sj < worst) {
                worst = sj;
                flat[f] = (signed char)k;
            }
        }
        *nflat += flat[f] >= 0;
    }
    free(nface);
    return GLPGP_OK;
}

glpgp_status glpgp_qs_split_flat(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, const signed char *flat,
                                 glpgp_quadmesh **out, int *nsplit)
{
    return split_run(m, q, h, NULL, flat, out, nsplit);
}
