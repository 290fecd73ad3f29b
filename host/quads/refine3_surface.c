/* quads/refine3_surface.c: the local 3-refinement of a quad mesh of a
 * surface (glpgp_qs_refine3, quads_surface.h): the selected faces split
 * 3 x 3, their neighbours by transition templates, so that the refinement
 * stays where it is asked for (Schneiders' vertex-based templates; R.
 * Schneiders, "Refining quadrilateral and hexahedral element meshes",
 * 1996). A 2-refinement cannot do that: a quad with one side halved has an
 * odd count of boundary points, so the halving runs along the whole quad
 * strip (split_surface.c). With thirds, every template has an even count:
 *  - the corners of the selected faces are marked; a quad with three
 *    marked corners, or two opposite ones, gets all four marked, until no
 *    quad has such a pattern (the closure; it only grows the marked set);
 *  - a side with both ends marked gets two points (at its thirds), a side
 *    with one marked end one point (a third from that end), others none:
 *    the two quads at a side agree, so the mesh stays conforming;
 *  - a quad with no marked corner is kept; one: 3 quads (the corner's
 *    small quad and two about the new point at (1/3, 1/3)); two adjacent:
 *    7 quads (the marked side's three small quads, a row of three above
 *    them, one on top); four: 9 quads.
 * New points: on the side (thirds) or bilinear in the quad, then moved onto
 * the surface (glpgp_qs_project). On a square grid the templates' worst
 * corner has a scaled Jacobian of 0.707 before any smoothing. The input
 * must be all quads; the result's validity in 3D is the caller's check. */
#include "quads_surface.h"
#include "qvec.h"

#include "glpgp/util.h"

#include <stdlib.h>
#include <string.h>

typedef struct r3_edge {
    long long key; /* lo * nv + hi */
    int p_lo, p_hi; /* the point a third from lo / from hi (-1: none) */
} r3_edge;

static int cmp_r3(const void *pa, const void *pb)
{
    const r3_edge *a = pa, *b = pb;
    return a->key < b->key ? -1 : a->key > b->key;
}

typedef struct r3 {
    const glpgp_quadmesh *q;
    unsigned char *mark; /* per vertex */
    r3_edge *e;          /* unique sides, sorted by key */
    int ne;
    dvec xyz; /* the new mesh's points: q's, then the new ones */
} r3;

static const r3_edge *find_edge(const r3 *R, int a, int b)
{
    const long long nv = R->q->nv;
    r3_edge k = {a < b ? a * nv + b : b * nv + a, -1, -1};
    return bsearch(&k, R->e, (size_t)R->ne, sizeof *R->e, cmp_r3);
}

/* The point on side a-b a third from a (-1: none). */
static int third(const r3 *R, int a, int b)
{
    const r3_edge *e = find_edge(R, a, b);
    return !e ? -1 : a < b ? e->p_lo : e->p_hi;
}

static glpgp_status add_point(r3 *R, const double *x, int *id)
{
    *id = R->xyz.n / 3;
    for (int d = 0; d < 3; d++) GLPGP_CHECK(dpush(&R->xyz, x[d]));
    return GLPGP_OK;
}

/* Bilinear point (s along v0 -> v1, t along v0 -> v3) of quad v. */
static void bilinear(const double *xyz, const int *v, double s, double t, double *x)
{
    for (int d = 0; d < 3; d++)
        x[d] = (1 - s) * (1 - t) * xyz[3 * v[0] + d] + s * (1 - t) * xyz[3 * v[1] + d] + s * t * xyz[3 * v[2] + d] +
               (1 - s) * t * xyz[3 * v[3] + d];
}

/* The closure: marks spread to the quads with three marked corners or two
 * opposite ones. *n: the marked corners' count. */
static void closure(r3 *R, int *n)
{
    const glpgp_quadmesh *q = R->q;
    for (int changed = 1; changed;) {
        changed = 0;
        for (int f = 0; f < q->nf; f++) {
            const int *v = q->face_vert + q->face_start[f];
            const int m0 = R->mark[v[0]], m1 = R->mark[v[1]], m2 = R->mark[v[2]], m3 = R->mark[v[3]];
            const int k = m0 + m1 + m2 + m3;
            if (k == 3 || (k == 2 && m0 == m2)) {
                for (int i = 0; i < 4; i++) R->mark[v[i]] = 1;
                changed = 1;
            }
        }
    }
    *n = 0;
    for (int i = 0; i < q->nv; i++) *n += R->mark[i];
}

/* The sides and their points. */
static glpgp_status sides(r3 *R)
{
    const glpgp_quadmesh *q = R->q;
    const long long nv = q->nv;
    GLPGP_CHECK(glpgp_malloc((size_t)4 * q->nf + 1, sizeof *R->e, &R->e));
    int n = 0;
    for (int f = 0; f < q->nf; f++)
        for (int i = 0; i < 4; i++) {
            const int a = q->face_vert[4 * f + i], b = q->face_vert[4 * f + (i + 1) % 4];
            R->e[n].key = a < b ? a * nv + b : b * nv + a;
            R->e[n].p_lo = R->e[n].p_hi = -1;
            n++;
        }
    qsort(R->e, (size_t)n, sizeof *R->e, cmp_r3);
    R->ne = 0;
    for (int i = 0; i < n; i++)
        if (R->ne == 0 || R->e[i].key != R->e[R->ne - 1].key) R->e[R->ne++] = R->e[i];
    for (int i = 0; i < R->ne; i++) {
        const int lo = (int)(R->e[i].key / nv), hi = (int)(R->e[i].key % nv);
        const double *a = q->xyz + 3 * lo, *b = q->xyz + 3 * hi;
        double x[3];
        if (R->mark[lo]) {
            for (int d = 0; d < 3; d++) x[d] = (2.0 * a[d] + b[d]) / 3.0;
            GLPGP_CHECK(add_point(R, x, &R->e[i].p_lo));
        }
        if (R->mark[hi]) {
            for (int d = 0; d < 3; d++) x[d] = (a[d] + 2.0 * b[d]) / 3.0;
            GLPGP_CHECK(add_point(R, x, &R->e[i].p_hi));
        }
    }
    return GLPGP_OK;
}

/* Quad v's template quads appended to fv (4 ids each); *nq their count. */
static glpgp_status templ(r3 *R, const int *v0, int *fv, int *nq)
{
    int k = 0, r = 0;
    for (int i = 0; i < 4; i++) k += R->mark[v0[i]];
    /* rotated so that the marked corner (one) or the marked side's first corner (two) is v[0] */
    for (r = 0; r < 4; r++) {
        const int a = R->mark[v0[r]], b = R->mark[v0[(r + 1) % 4]];
        if (k == 1 && a) break;
        if (k == 2 && a && b) break;
        if ((k == 0 || k == 4) && r == 0) break;
    }
    const int v[4] = {v0[r % 4], v0[(r + 1) % 4], v0[(r + 2) % 4], v0[(r + 3) % 4]};
    const int A = v[0], B = v[1], C = v[2], D = v[3];
    double x[3];
    *nq = 0;
    if (k == 0) {
        memcpy(fv, v, sizeof v);
        *nq = 1;
        return GLPGP_OK;
    }
    if (k == 1) {
        int O = -1;
        bilinear(R->q->xyz, v, 1.0 / 3, 1.0 / 3, x);
        GLPGP_CHECK(add_point(R, x, &O));
        const int P = third(R, A, B), Q = third(R, A, D);
        const int t[12] = {A, P, O, Q, P, B, C, O, Q, O, C, D};
        memcpy(fv, t, sizeof t);
        *nq = 3;
        return GLPGP_OK;
    }
    if (k == 2) {
        int O1 = -1, O2 = -1, X = -1, Y = -1;
        bilinear(R->q->xyz, v, 1.0 / 3, 1.0 / 3, x);
        GLPGP_CHECK(add_point(R, x, &O1));
        bilinear(R->q->xyz, v, 2.0 / 3, 1.0 / 3, x);
        GLPGP_CHECK(add_point(R, x, &O2));
        bilinear(R->q->xyz, v, 1.0 / 3, 2.0 / 3, x);
        GLPGP_CHECK(add_point(R, x, &X));
        bilinear(R->q->xyz, v, 2.0 / 3, 2.0 / 3, x);
        GLPGP_CHECK(add_point(R, x, &Y));
        const int P1 = third(R, A, B), P2 = third(R, B, A), Q = third(R, A, D), Rr = third(R, B, C);
        const int t[28] = {A, P1, O1, Q, P1, P2, O2, O1, P2, B, Rr, O2, Q, O1, X, D,
                           O1, O2, Y, X, O2, Rr, C, Y, X, Y, C, D};
        memcpy(fv, t, sizeof t);
        *nq = 7;
        return GLPGP_OK;
    }
    /* four: the 4 x 4 lattice of the quad, 9 quads */
    int g[16];
    g[0] = A;
    g[3] = B;
    g[15] = C;
    g[12] = D;
    g[1] = third(R, A, B);
    g[2] = third(R, B, A);
    g[7] = third(R, B, C);
    g[11] = third(R, C, B);
    g[14] = third(R, C, D);
    g[13] = third(R, D, C);
    g[8] = third(R, D, A);
    g[4] = third(R, A, D);
    for (int j = 1; j < 3; j++)
        for (int i = 1; i < 3; i++) {
            bilinear(R->q->xyz, v, i / 3.0, j / 3.0, x);
            GLPGP_CHECK(add_point(R, x, &g[4 * j + i]));
        }
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++) {
            int *w = fv + 4 * (*nq)++;
            w[0] = g[4 * j + i];
            w[1] = g[4 * j + i + 1];
            w[2] = g[4 * (j + 1) + i + 1];
            w[3] = g[4 * (j + 1) + i];
        }
    return GLPGP_OK;
}

static glpgp_status build(r3 *R, const glpgp_mesh *m, double h, glpgp_quadmesh **out, int *nref)
{
    const glpgp_quadmesh *q = R->q;
    int *fv = NULL, *org = NULL, nf = 0;
    glpgp_status st = glpgp_malloc((size_t)36 * q->nf + 1, sizeof(int), &fv);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)9 * q->nf + 1, sizeof(int), &org);
    *nref = 0;
    for (int f = 0; f < q->nf && st == GLPGP_OK; f++) {
        int nq = 0;
        st = templ(R, q->face_vert + 4 * f, fv + 4 * nf, &nq);
        for (int i = 0; i < nq; i++) org[nf + i] = q->face_origin ? q->face_origin[f] : GLPGP_QFACE_GRID;
        nf += nq;
        *nref += nq > 1;
    }
    glpgp_quadmesh *r = NULL;
    if (st == GLPGP_OK) st = glpgp_qs_alloc(R->xyz.n / 3, nf, 4 * nf, &r);
    if (st == GLPGP_OK) {
        memcpy(r->xyz, R->xyz.p, (size_t)R->xyz.n * sizeof(double));
        memcpy(r->face_vert, fv, (size_t)4 * nf * sizeof(int));
        for (int f = 0; f <= nf; f++) r->face_start[f] = 4 * f;
        for (int f = 0; f < nf; f++) r->face_origin[f] = (unsigned char)org[f];
        st = glpgp_qs_project(m, h, r->xyz, q->nv, r->nv);
    }
    if (st == GLPGP_OK) {
        glpgp_qs_finish_from(r, q);
        *out = r;
    } else {
        glpgp_quadmesh_destroy(&r);
    }
    free(fv);
    free(org);
    return st;
}

glpgp_status glpgp_qs_refine3(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, const unsigned char *sel,
                              glpgp_quadmesh **out, int *nref)
{
    *out = NULL;
    *nref = 0;
    if (!q || !q->xyz || q->nf == 0) return GLPGP_FAIL(GLPGP_ERR_ARG, "3-refinement: an empty or planar mesh");
    for (int f = 0; f < q->nf; f++)
        if (q->face_start[f + 1] - q->face_start[f] != 4 || q->face_start[f] != 4 * f) return GLPGP_OK; /* quads only */
    r3 R;
    memset(&R, 0, sizeof R);
    R.q = q;
    int nmark = 0;
    glpgp_status st = glpgp_calloc((size_t)q->nv + 1, 1, &R.mark);
    if (st == GLPGP_OK) {
        for (int f = 0; f < q->nf; f++)
            if (sel[f])
                for (int i = 0; i < 4; i++) R.mark[q->face_vert[4 * f + i]] = 1;
        closure(&R, &nmark);
    }
    for (int i = 0; i < 3 * q->nv && st == GLPGP_OK && nmark; i++) st = dpush(&R.xyz, q->xyz[i]);
    if (st == GLPGP_OK && nmark) st = sides(&R);
    if (st == GLPGP_OK && nmark) st = build(&R, m, h, out, nref);
    free(R.mark);
    free(R.e);
    dvec_free(&R.xyz);
    return st;
}
