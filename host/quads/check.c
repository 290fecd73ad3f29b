/* quads/check.c: validity checks of a polygon mesh, per face (check.h).
 *
 * The mesh has one orientation, the sign of its total signed area (so a
 * mesh written clockwise is read as it is, and a fold is a face of the
 * other sign). A face is flagged when
 *  - it is not a quad; it is inverted (signed area <= 0, or a quad corner
 *    whose scaled Jacobian, sin of the corner angle, is < 0); degenerate
 *    (repeated vertex, an edge below 1e-9 of the face's longest, |area|
 *    below 1e-12 of its square: relative to the face, so a valid fine mesh
 *    is not degenerate at a large h);
 *  - one of its edges is used by more than two faces, or by two faces in
 *    the same direction (the two faces lie on the same side of it: a fold);
 *  - one of its corners sits at a pinched vertex (the faces around the
 *    vertex form more than one edge-connected fan);
 *  - it overlaps another face: one of its edges crosses another edge
 *    (proper crossing, 1e-9 h away from the end points), or a vertex that
 *    is not one of its corners lies inside it or on its sides (a hanging
 *    vertex);
 *  - with a domain (the triangle mesh): a corner lies outside the domain
 *    (in no triangle, farther than h/100 from the boundary), or an edge
 *    crosses a domain boundary segment (farther than h/100 from the ends); a mesh boundary edge has a point
 *    (9 samples) farther than tol from the domain boundary (a gap, or a
 *    chord cutting across a feature); a domain boundary point (vertices
 *    and segment midpoints) farther than tol from the mesh boundary lies
 *    inside it (a lost hole or feature; when no face contains it, the face
 *    of the nearest mesh boundary edge is flagged); a domain corner (the
 *    boundary turns by more than 40 degrees, as in the extraction) has no
 *    mesh vertex within 1e-3 h.
 * Neighbour queries use uniform grids of boxes (bgrid). */
#include "check.h"
#include "geom.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- the checks ----------------------------------------------------------- */

typedef struct hedge4 {
    int a, b, f, dir; /* a < b; dir 1 when the face runs a -> b */
} hedge4;

static int cmp_h4(const void *pa, const void *pb)
{
    const hedge4 *x = pa, *y = pb;
    if (x->a != y->a) return x->a < y->a ? -1 : 1;
    if (x->b != y->b) return x->b < y->b ? -1 : 1;
    return x->f - y->f;
}

void glpgp_qcheck_free(qcheck *c)
{
    free(c->flags);
    c->flags = NULL;
}

static int uf(int *p, int i)
{
    while (p[i] != i) {
        p[i] = p[p[i]];
        i = p[i];
    }
    return i;
}

/* The state of one check: the mesh's edges and incidences, the grids. */
typedef struct ckctx {
    const glpgp_quadmesh *q;
    const glpgp_mesh *dm;
    double h, tol;
    qcheck *c;
    unsigned *fl;
    int orient, ne, nbe;
    hedge4 *H;          /* half-edges sorted by (a, b) */
    int *eu, *ebf;      /* unique edges (2 per edge); boundary edge -> face (-1 inside) */
    int *vs, *vc, *sf;  /* corners per vertex (CSR), face of a corner slot */
    double *box, *fbox; /* edge and face boxes */
    int *bidx;          /* boundary edges (indices into eu) */
    double *bbox;
    int *dnext;         /* domain segment i: loop vertices i and dnext[i] */
    bgrid GE, GF, GD, GT, GB;
    int *cand, ncap;
} ckctx;

static void ck_free(ckctx *k)
{
    free(k->H);
    free(k->eu);
    free(k->ebf);
    free(k->vs);
    free(k->vc);
    free(k->sf);
    free(k->box);
    free(k->fbox);
    free(k->bidx);
    free(k->bbox);
    free(k->dnext);
    free(k->cand);
    glpgp_bgrid_free(&k->GE);
    glpgp_bgrid_free(&k->GF);
    glpgp_bgrid_free(&k->GD);
    glpgp_bgrid_free(&k->GT);
    glpgp_bgrid_free(&k->GB);
}

/* Flag the faces at vertex v. */
static void flag_vertex(const ckctx *k, int v, unsigned bit)
{
    for (int j = k->vs[v]; j < k->vs[v + 1]; j++) k->fl[k->sf[k->vc[j]]] |= bit;
}

/* 1-2. The orientation (sign of the total area); per face: corners,
 * inversion, degeneracy (relative to the face's own size), flat corners. */
static void check_local(ckctx *k)
{
    const glpgp_quadmesh *q = k->q;
    double total = 0.0;
    for (int f = 0; f < q->nf; f++) {
        int s = q->face_start[f], n = q->face_start[f + 1] - s;
        for (int i = 0; i < n; i++) {
            const double *a = q->xy + 2 * q->face_vert[s + i], *b = q->xy + 2 * q->face_vert[s + (i + 1) % n];
            total += 0.5 * (a[0] * b[1] - b[0] * a[1]);
        }
    }
    k->orient = k->c->orientation = total < 0 ? -1 : 1;
    for (int f = 0; f < q->nf; f++) {
        int s = q->face_start[f], n = q->face_start[f + 1] - s;
        const int *v = q->face_vert + s;
        if (n != 4) k->fl[f] |= QF_NONQUAD;
        double area = 0.0, msj = INFINITY, lmax = 0.0;
        for (int i = 0; i < n; i++) {
            const double *a = q->xy + 2 * v[i], *b = q->xy + 2 * v[(i + 1) % n];
            lmax = fmax(lmax, hypot(b[0] - a[0], b[1] - a[1]));
        }
        /* degenerate against the face's own size (a fine valid mesh, e.g. the
         * input's triangles split, is not degenerate for a large h) */
        for (int i = 0; i < n; i++) {
            const double *a = q->xy + 2 * v[i], *b = q->xy + 2 * v[(i + 1) % n], *p = q->xy + 2 * v[(i + n - 1) % n];
            for (int j = i + 1; j < n; j++)
                if (v[j] == v[i]) k->fl[f] |= QF_DEGENERATE;
            double e1x = b[0] - a[0], e1y = b[1] - a[1], e2x = p[0] - a[0], e2y = p[1] - a[1];
            double l1 = hypot(e1x, e1y), l2 = hypot(e2x, e2y);
            if (!(l1 > 1e-9 * lmax) || l1 < 1e-15 * k->h) k->fl[f] |= QF_DEGENERATE;
            area += 0.5 * ((a[0] - q->xy[2 * v[0]]) * (b[1] - q->xy[2 * v[0] + 1]) -
                           (b[0] - q->xy[2 * v[0]]) * (a[1] - q->xy[2 * v[0] + 1]));
            msj = fmin(msj, (l1 > 0 && l2 > 0) ? k->orient * (e1x * e2y - e1y * e2x) / (l1 * l2) : 0.0);
        }
        area *= k->orient;
        if (n < 3 || !(fabs(area) > 1e-12 * lmax * lmax)) k->fl[f] |= QF_DEGENERATE;
        if (area <= 0.0 || (n == 4 && msj < 0.0)) k->fl[f] |= QF_INVERTED;
        if (n == 4 && msj < 1e-3) k->fl[f] |= QF_FLAT;
    }
}

/* 3. Edges: non-manifold, folds, the boundary and its loops. */
static glpgp_status check_edges(ckctx *k)
{
    const glpgp_quadmesh *q = k->q;
    const int nc = q->face_start[q->nf], nv = q->nv;
    int *bnext = NULL;
    unsigned char *bused = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)nc + 1, sizeof *k->H, &k->H));
    GLPGP_CHECK(glpgp_malloc((size_t)nc + 1, sizeof(int), &k->sf));
    for (int f = 0; f < q->nf; f++) {
        int s = q->face_start[f], n = q->face_start[f + 1] - s;
        for (int i = 0; i < n; i++) {
            int a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % n];
            k->H[s + i] = (hedge4){a < b ? a : b, a < b ? b : a, f, a < b};
            k->sf[s + i] = f;
        }
    }
    qsort(k->H, (size_t)nc, sizeof *k->H, cmp_h4);
    glpgp_status st = glpgp_malloc((size_t)2 * nc + 2, sizeof(int), &k->eu);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nc + 1, sizeof(int), &k->ebf);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nv + 1, sizeof(int), &bnext);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)nv + 1, 1, &bused);
    if (st != GLPGP_OK) goto done;
    for (int i = 0; i < nv; i++) bnext[i] = -1;
    const hedge4 *H = k->H;
    for (int i = 0; i < nc;) {
        int e = i + 1;
        while (e < nc && H[e].a == H[i].a && H[e].b == H[i].b) e++;
        k->eu[2 * k->ne] = H[i].a;
        k->eu[2 * k->ne + 1] = H[i].b;
        k->ebf[k->ne] = -1;
        if (e - i == 1) {
            k->ebf[k->ne] = H[i].f;
            /* boundary successor in the face direction (loops count) */
            bnext[H[i].dir ? H[i].a : H[i].b] = H[i].dir ? H[i].b : H[i].a;
        } else if (e - i > 2 || H[i].dir == H[i + 1].dir) {
            k->c->nonmanifold_edges++;
            for (int j = i; j < e; j++) k->fl[H[j].f] |= QF_NONMANIFOLD;
        }
        k->ne++;
        i = e;
    }
    for (int v = 0; v < nv; v++) { /* boundary loops: cycles of the boundary successor */
        if (bnext[v] < 0 || bused[v]) continue;
        for (int u = v, guard = 0; u >= 0 && !bused[u] && guard++ <= nv; u = bnext[u]) bused[u] = 1;
        k->c->boundary_loops++;
    }
done:
    free(bnext);
    free(bused);
    return st;
}

/* 4. Pinched vertices: the corners at v joined when they share an edge. */
static glpgp_status check_pinched(ckctx *k)
{
    const glpgp_quadmesh *q = k->q;
    const int nc = q->face_start[q->nf], nv = q->nv;
    int *cnt = NULL, *par = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)nv + 2, sizeof(int), &k->vs));
    GLPGP_CHECK(glpgp_malloc((size_t)nc + 1, sizeof(int), &k->vc));
    glpgp_status st = glpgp_calloc((size_t)nv + 1, sizeof(int), &cnt);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nc + 1, sizeof(int), &par);
    if (st != GLPGP_OK) goto done;
    for (int s = 0; s < nc; s++) k->vs[q->face_vert[s] + 1]++;
    for (int v = 0; v < nv; v++) k->vs[v + 1] += k->vs[v];
    for (int s = 0; s < nc; s++) k->vc[k->vs[q->face_vert[s]] + cnt[q->face_vert[s]]++] = s;
    for (int s = 0; s < nc; s++) par[s] = s;
    for (int v = 0; v < nv; v++) {
        int n = k->vs[v + 1] - k->vs[v];
        if (n < 2) continue;
        for (int i = 0; i < n; i++) {
            int si = k->vc[k->vs[v] + i], fi = k->sf[si], bi = q->face_start[fi], ki = q->face_start[fi + 1] - bi;
            int nxt = q->face_vert[bi + (si - bi + 1) % ki], prv = q->face_vert[bi + (si - bi + ki - 1) % ki];
            for (int j = i + 1; j < n; j++) {
                int sj = k->vc[k->vs[v] + j], fj = k->sf[sj], bj = q->face_start[fj], kj = q->face_start[fj + 1] - bj;
                int nx2 = q->face_vert[bj + (sj - bj + 1) % kj], pv2 = q->face_vert[bj + (sj - bj + kj - 1) % kj];
                if (nxt == pv2 || prv == nx2 || nxt == nx2 || prv == pv2) {
                    int ra = uf(par, si), rb = uf(par, sj);
                    if (ra != rb) par[rb] = ra;
                }
            }
        }
        int comps = 0;
        for (int i = 0; i < n; i++)
            if (uf(par, k->vc[k->vs[v] + i]) == k->vc[k->vs[v] + i]) comps++;
        if (comps > 1) {
            k->c->pinched++;
            flag_vertex(k, v, QF_PINCHED);
        }
    }
done:
    free(cnt);
    free(par);
    return st;
}

/* 5a. Edges crossing other edges. */
static glpgp_status check_crossings(ckctx *k)
{
    const glpgp_quadmesh *q = k->q;
    const int nc = q->face_start[q->nf], ne = k->ne;
    int *eface = NULL; /* up to 2 faces per edge */
    GLPGP_CHECK(glpgp_malloc((size_t)4 * ne + 4, sizeof(double), &k->box));
    for (int e = 0; e < ne; e++) {
        const double *a = q->xy + 2 * k->eu[2 * e], *b = q->xy + 2 * k->eu[2 * e + 1];
        double *bx = k->box + 4 * e;
        bx[0] = fmin(a[0], b[0]);
        bx[1] = fmin(a[1], b[1]);
        bx[2] = fmax(a[0], b[0]);
        bx[3] = fmax(a[1], b[1]);
    }
    GLPGP_CHECK(glpgp_bgrid_build(&k->GE, k->box, ne, k->h));
    GLPGP_CHECK(glpgp_malloc((size_t)2 * ne + 2, sizeof(int), &eface));
    for (int i = 0, e = 0; i < nc; e++) { /* the half-edges again, in the order of the unique edges */
        int j = i + 1;
        while (j < nc && k->H[j].a == k->H[i].a && k->H[j].b == k->H[i].b) j++;
        eface[2 * e] = k->H[i].f;
        eface[2 * e + 1] = j > i + 1 ? k->H[i + 1].f : -1;
        i = j;
    }
    const int *eu = k->eu;
    for (int e1 = 0; e1 < ne; e1++) {
        if ((e1 & 32767) == 0) glpgp_progress_poll();
        const double *bx = k->box + 4 * e1;
        int n = glpgp_bgrid_query(&k->GE, bx[0], bx[1], bx[2], bx[3], &k->cand, &k->ncap);
        if (n < 0) {
            free(eface);
            return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad check: out of memory");
        }
        const double *a = q->xy + 2 * eu[2 * e1], *b = q->xy + 2 * eu[2 * e1 + 1];
        for (int i = 0; i < n; i++) {
            int e2 = k->cand[i];
            if (e2 <= e1 || eu[2 * e2] == eu[2 * e1] || eu[2 * e2] == eu[2 * e1 + 1] || eu[2 * e2 + 1] == eu[2 * e1] ||
                eu[2 * e2 + 1] == eu[2 * e1 + 1])
                continue;
            if (!glpgp_seg_cross(a, b, q->xy + 2 * eu[2 * e2], q->xy + 2 * eu[2 * e2 + 1], 1e-9 * k->h)) continue;
            for (int s = 0; s < 2; s++) {
                if (eface[2 * e1 + s] >= 0) k->fl[eface[2 * e1 + s]] |= QF_OVERLAP;
                if (eface[2 * e2 + s] >= 0) k->fl[eface[2 * e2 + s]] |= QF_OVERLAP;
            }
        }
    }
    free(eface);
    return GLPGP_OK;
}

/* 5b. Vertices inside a face that is not theirs, or on its sides. */
static glpgp_status check_inside(ckctx *k)
{
    const glpgp_quadmesh *q = k->q;
    GLPGP_CHECK(glpgp_malloc((size_t)4 * q->nf + 4, sizeof(double), &k->fbox));
    for (int f = 0; f < q->nf; f++) {
        double *bx = k->fbox + 4 * f;
        bx[0] = bx[1] = INFINITY;
        bx[2] = bx[3] = -INFINITY;
        for (int s = q->face_start[f]; s < q->face_start[f + 1]; s++) {
            const double *p = q->xy + 2 * q->face_vert[s];
            bx[0] = fmin(bx[0], p[0]);
            bx[1] = fmin(bx[1], p[1]);
            bx[2] = fmax(bx[2], p[0]);
            bx[3] = fmax(bx[3], p[1]);
        }
    }
    GLPGP_CHECK(glpgp_bgrid_build(&k->GF, k->fbox, q->nf, k->h));
    for (int v = 0; v < q->nv; v++) {
        if (k->vs[v + 1] == k->vs[v]) continue;
        const double *p = q->xy + 2 * v;
        int n = glpgp_bgrid_query(&k->GF, p[0], p[1], p[0], p[1], &k->cand, &k->ncap);
        if (n < 0) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad check: out of memory");
        for (int i = 0; i < n; i++) {
            int f = k->cand[i], s = q->face_start[f], m = q->face_start[f + 1] - s, own = 0;
            const double *bx = k->fbox + 4 * f;
            for (int j = 0; j < m; j++) own |= q->face_vert[s + j] == v;
            if (own || p[0] < bx[0] || p[0] > bx[2] || p[1] < bx[1] || p[1] > bx[3]) continue;
            /* inside, or on a side (a hanging vertex) */
            int hit = glpgp_point_in_poly(q->xy, q->face_vert + s, m, p, 1e-9 * k->h);
            for (int j = 0; j < m && !hit; j++)
                hit = glpgp_seg_dist(q->xy + 2 * q->face_vert[s + j], q->xy + 2 * q->face_vert[s + (j + 1) % m], p,
                                     NULL) <= 1e-9 * k->h;
            if (hit) {
                k->fl[f] |= QF_OVERLAP;
                flag_vertex(k, v, QF_OVERLAP);
            }
        }
    }
    return GLPGP_OK;
}

#define DSEG_A(k, i) ((k)->dm->xy + 2 * (k)->dm->loop_vertices[i])
#define DSEG_B(k, i) ((k)->dm->xy + 2 * (k)->dnext[i])

/* 6a. The domain's segment and triangle grids. */
static glpgp_status domain_grids(ckctx *k)
{
    const glpgp_mesh *dm = k->dm;
    const int nb = dm->loop_start[dm->nloops];
    double *dbox = NULL, *tbox = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)4 * nb + 4, sizeof(double), &dbox));
    glpgp_status st = glpgp_malloc((size_t)nb + 1, sizeof(int), &k->dnext);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)4 * dm->nt + 4, sizeof(double), &tbox);
    if (st != GLPGP_OK) goto done;
    for (int l = 0; l < dm->nloops; l++) {
        int s = dm->loop_start[l], n = dm->loop_start[l + 1] - s;
        for (int i = 0; i < n; i++) {
            const double *a = dm->xy + 2 * dm->loop_vertices[s + i], *b = dm->xy + 2 * dm->loop_vertices[s + (i + 1) % n];
            k->dnext[s + i] = dm->loop_vertices[s + (i + 1) % n];
            dbox[4 * (s + i)] = fmin(a[0], b[0]);
            dbox[4 * (s + i) + 1] = fmin(a[1], b[1]);
            dbox[4 * (s + i) + 2] = fmax(a[0], b[0]);
            dbox[4 * (s + i) + 3] = fmax(a[1], b[1]);
        }
    }
    for (int t = 0; t < dm->nt; t++) {
        const double *a = dm->xy + 2 * dm->tri[3 * t], *b = dm->xy + 2 * dm->tri[3 * t + 1], *c = dm->xy + 2 * dm->tri[3 * t + 2];
        tbox[4 * t] = fmin(a[0], fmin(b[0], c[0]));
        tbox[4 * t + 1] = fmin(a[1], fmin(b[1], c[1]));
        tbox[4 * t + 2] = fmax(a[0], fmax(b[0], c[0]));
        tbox[4 * t + 3] = fmax(a[1], fmax(b[1], c[1]));
    }
    st = glpgp_bgrid_build(&k->GD, dbox, nb, k->h);
    if (st == GLPGP_OK) st = glpgp_bgrid_build(&k->GT, tbox, dm->nt, k->h);
done:
    free(dbox);
    free(tbox);
    return st;
}

/* 6b. Corners outside the domain (in no triangle, farther than eps from its
 * boundary) and edges crossing the domain boundary. */
static void check_outside(ckctx *k, double eps)
{
    const glpgp_quadmesh *q = k->q;
    const glpgp_mesh *dm = k->dm;
    for (int v = 0; v < q->nv; v++) {
        if (k->vs[v + 1] == k->vs[v]) continue;
        const double *p = q->xy + 2 * v;
        int n = glpgp_bgrid_query(&k->GT, p[0] - eps, p[1] - eps, p[0] + eps, p[1] + eps, &k->cand, &k->ncap), in = 0;
        for (int i = 0; i < n && !in; i++) {
            const int *t = dm->tri + 3 * k->cand[i];
            const double *a = dm->xy + 2 * t[0], *b = dm->xy + 2 * t[1], *c = dm->xy + 2 * t[2];
            in = glpgp_orient2(a, b, p) >= 0 && glpgp_orient2(b, c, p) >= 0 && glpgp_orient2(c, a, p) >= 0;
        }
        if (!in) {
            n = glpgp_bgrid_query(&k->GD, p[0] - eps, p[1] - eps, p[0] + eps, p[1] + eps, &k->cand, &k->ncap);
            for (int i = 0; i < n && !in; i++) in = glpgp_seg_dist(DSEG_A(k, k->cand[i]), DSEG_B(k, k->cand[i]), p, NULL) <= eps;
        }
        if (!in) flag_vertex(k, v, QF_OUTSIDE);
    }
    const int nc = q->face_start[q->nf];
    for (int e = 0; e < k->ne; e++) {
        const double *a = q->xy + 2 * k->eu[2 * e], *b = q->xy + 2 * k->eu[2 * e + 1], *bx = k->box + 4 * e;
        int n = glpgp_bgrid_query(&k->GD, bx[0], bx[1], bx[2], bx[3], &k->cand, &k->ncap);
        for (int i = 0; i < n; i++) {
            if (!glpgp_seg_cross(a, b, DSEG_A(k, k->cand[i]), DSEG_B(k, k->cand[i]), eps)) continue;
            /* both faces of the edge: its first half-edge in H */
            int lo = 0, hi = nc - 1, ka = k->eu[2 * e], kb = k->eu[2 * e + 1];
            while (lo < hi) {
                int mid = (lo + hi) / 2;
                if (k->H[mid].a < ka || (k->H[mid].a == ka && k->H[mid].b < kb)) lo = mid + 1;
                else hi = mid;
            }
            for (int j = lo; j < nc && k->H[j].a == ka && k->H[j].b == kb; j++) k->fl[k->H[j].f] |= QF_OUTSIDE;
            break;
        }
    }
}

/* 6c. Mesh boundary edges with a point (9 samples) farther than tol from
 * the domain boundary. */
static glpgp_status check_far(ckctx *k)
{
    const glpgp_quadmesh *q = k->q;
    double tol = k->tol;
    for (int e = 0; e < k->ne; e++) k->nbe += k->ebf[e] >= 0;
    GLPGP_CHECK(glpgp_malloc((size_t)4 * k->nbe + 4, sizeof(double), &k->bbox));
    GLPGP_CHECK(glpgp_malloc((size_t)k->nbe + 1, sizeof(int), &k->bidx));
    int n = 0;
    for (int e = 0; e < k->ne; e++) {
        if (k->ebf[e] < 0) continue;
        memcpy(k->bbox + 4 * n, k->box + 4 * e, 4 * sizeof(double));
        k->bidx[n++] = e;
    }
    GLPGP_CHECK(glpgp_bgrid_build(&k->GB, k->bbox, k->nbe, k->h));
    for (int i = 0; i < k->nbe; i++) {
        int e = k->bidx[i];
        const double *a = q->xy + 2 * k->eu[2 * e], *b = q->xy + 2 * k->eu[2 * e + 1];
        for (int s = 0; s <= 8; s++) {
            double t = s / 8.0, p[2] = {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
            int m = glpgp_bgrid_query(&k->GD, p[0] - tol, p[1] - tol, p[0] + tol, p[1] + tol, &k->cand, &k->ncap);
            double d = INFINITY;
            for (int j = 0; j < m; j++) d = fmin(d, glpgp_seg_dist(DSEG_A(k, k->cand[j]), DSEG_B(k, k->cand[j]), p, NULL));
            if (d > tol) {
                k->fl[k->ebf[e]] |= QF_FAR;
                break;
            }
            if (s == 0 || s == 8) k->c->bnd_vertex_dist = fmax(k->c->bnd_vertex_dist, d);
        }
    }
    return GLPGP_OK;
}

/* Whether the domain boundary point p is lost: a corner without a mesh
 * vertex within 1e-3 h, or any point farther than tol from the mesh boundary. */
static int point_lost(ckctx *k, const double *p, int corner)
{
    const glpgp_quadmesh *q = k->q;
    if (corner) {
        double r = 1e-3 * k->h;
        int m = glpgp_bgrid_query(&k->GF, p[0] - r, p[1] - r, p[0] + r, p[1] + r, &k->cand, &k->ncap);
        int found = 0;
        for (int j = 0; j < m && !found; j++)
            for (int t = q->face_start[k->cand[j]]; t < q->face_start[k->cand[j] + 1] && !found; t++) {
                const double *x = q->xy + 2 * q->face_vert[t];
                found = hypot(x[0] - p[0], x[1] - p[1]) <= r;
            }
        if (!found) {
            k->c->corners_lost++;
            return 1;
        }
    }
    double tol = k->tol, d = INFINITY;
    int m = glpgp_bgrid_query(&k->GB, p[0] - tol, p[1] - tol, p[0] + tol, p[1] + tol, &k->cand, &k->ncap);
    for (int j = 0; j < m; j++) {
        int e = k->bidx[k->cand[j]];
        d = fmin(d, glpgp_seg_dist(q->xy + 2 * k->eu[2 * e], q->xy + 2 * k->eu[2 * e + 1], p, NULL));
    }
    return d > tol;
}

/* Flag the faces containing the lost point p, else the nearest boundary edge's face. */
static void flag_lost(ckctx *k, const double *p)
{
    const glpgp_quadmesh *q = k->q;
    int m = glpgp_bgrid_query(&k->GF, p[0], p[1], p[0], p[1], &k->cand, &k->ncap), any = 0;
    for (int j = 0; j < m; j++) {
        int f = k->cand[j], fs = q->face_start[f], fk = q->face_start[f + 1] - fs;
        if (glpgp_point_in_poly(q->xy, q->face_vert + fs, fk, p, 0.0)) {
            k->fl[f] |= QF_LOST;
            any = 1;
        }
    }
    if (any || k->nbe == 0) return;
    const double *bb = k->dm->bbox, lim = 1e6 * (bb[2] - bb[0] + bb[3] - bb[1] + k->h);
    double best = INFINITY;
    int bf = -1;
    for (double r2 = k->tol; bf < 0 || best > r2; r2 *= 2.0) {
        int m3 = glpgp_bgrid_query(&k->GB, p[0] - r2, p[1] - r2, p[0] + r2, p[1] + r2, &k->cand, &k->ncap);
        for (int j = 0; j < m3; j++) {
            int e = k->bidx[k->cand[j]];
            double d = glpgp_seg_dist(q->xy + 2 * k->eu[2 * e], q->xy + 2 * k->eu[2 * e + 1], p, NULL);
            if (d < best) {
                best = d;
                bf = k->ebf[e];
            }
        }
        if (r2 > lim) break;
    }
    if (bf >= 0) k->fl[bf] |= QF_LOST;
}

/* 6d. Domain boundary points (vertices, segment midpoints) lost by the mesh. */
static void check_lost(ckctx *k)
{
    const glpgp_mesh *dm = k->dm;
    const double cmin = cos(GLPGP_CORNER_DEG * 3.14159265358979323846 / 180.0);
    k->c->corners_lost = 0;
    for (int l = 0; l < dm->nloops; l++) {
        int s = dm->loop_start[l], n = dm->loop_start[l + 1] - s;
        for (int i = 0; i < n; i++) {
            int vi = dm->loop_vertices[s + i];
            const double *a = dm->xy + 2 * vi, *b = DSEG_B(k, s + i);
            const double *np = dm->normal_prev + 2 * vi, *nn = dm->normal_next + 2 * vi;
            int corner = np[0] * nn[0] + np[1] * nn[1] < cmin;
            double mid[2] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])};
            if (point_lost(k, a, corner)) flag_lost(k, a);
            if (point_lost(k, mid, 0)) flag_lost(k, mid);
        }
    }
}

glpgp_status glpgp_qcheck_run(const glpgp_quadmesh *q, const glpgp_mesh *dm, double h, double tol, qcheck *c)
{
    memset(c, 0, sizeof *c);
    c->corners_lost = -1;
    ckctx k;
    memset(&k, 0, sizeof k);
    k.q = q;
    k.dm = dm;
    k.h = h;
    k.tol = tol;
    k.c = c;
    glpgp_status st = glpgp_calloc((size_t)q->nf + 1, sizeof(unsigned), &c->flags);
    if (st != GLPGP_OK) return st;
    k.fl = c->flags;
    check_local(&k);
    GLPGP_CHECK_GOTO(st, check_edges(&k), done);
    GLPGP_CHECK_GOTO(st, check_pinched(&k), done);
    GLPGP_CHECK_GOTO(st, check_crossings(&k), done);
    GLPGP_CHECK_GOTO(st, check_inside(&k), done);
    if (dm) {
        /* touching tolerance against the domain boundary: 1% of h (a mesh of
         * the exact curves, e.g. Gmsh's, is within that of the polygonal
         * domain; a face across a slot or a hole is far beyond it) */
        GLPGP_CHECK_GOTO(st, domain_grids(&k), done);
        check_outside(&k, 1e-2 * h);
        GLPGP_CHECK_GOTO(st, check_far(&k), done);
        check_lost(&k);
    }
done:
    ck_free(&k);
    if (st != GLPGP_OK) glpgp_qcheck_free(c);
    return st;
}

#undef DSEG_A
#undef DSEG_B

/* ---- sharp corners ---------------------------------------------------------- */

glpgp_status glpgp_qcheck_corner_bound(const glpgp_quadmesh *q, const glpgp_mesh *dm, double h, double *bound)
{
    for (int f = 0; f < q->nf; f++) bound[f] = 1.0;
    if (!dm || q->nf == 0) return GLPGP_OK;
    /* the domain's corners below 90 degrees: points and sin(alpha) */
    double *pts = NULL, *box = NULL;
    int n = 0, nb = dm->loop_start[dm->nloops], *cand = NULL, ncap = 0;
    GLPGP_CHECK(glpgp_malloc((size_t)3 * nb + 3, sizeof(double), &pts));
    for (int l = 0; l < dm->nloops; l++) {
        int s = dm->loop_start[l], m = dm->loop_start[l + 1] - s;
        for (int i = 0; i < m; i++) {
            const double *a = dm->xy + 2 * dm->loop_vertices[s + (i + m - 1) % m], *b = dm->xy + 2 * dm->loop_vertices[s + i],
                         *c = dm->xy + 2 * dm->loop_vertices[s + (i + 1) % m];
            double ux = c[0] - b[0], uy = c[1] - b[1], vx = a[0] - b[0], vy = a[1] - b[1];
            double al = atan2(ux * vy - uy * vx, ux * vx + uy * vy); /* interior angle, region on the left */
            if (al < 0) al += 2 * 3.14159265358979323846;
            if (al >= 0.5 * 3.14159265358979323846) continue;
            pts[3 * n] = b[0];
            pts[3 * n + 1] = b[1];
            pts[3 * n + 2] = sin(al);
            n++;
        }
    }
    glpgp_status st = GLPGP_OK;
    bgrid G;
    memset(&G, 0, sizeof G);
    if (n > 0) {
        st = glpgp_malloc((size_t)4 * n, sizeof(double), &box);
        for (int i = 0; i < n && st == GLPGP_OK; i++) {
            box[4 * i] = box[4 * i + 2] = pts[3 * i];
            box[4 * i + 1] = box[4 * i + 3] = pts[3 * i + 1];
        }
        if (st == GLPGP_OK) st = glpgp_bgrid_build(&G, box, n, h);
        const double r = 1e-6 * h;
        for (int f = 0; f < q->nf && st == GLPGP_OK; f++)
            for (int k = q->face_start[f]; k < q->face_start[f + 1]; k++) {
                const double *p = q->xy + 2 * q->face_vert[k];
                int m = glpgp_bgrid_query(&G, p[0] - r, p[1] - r, p[0] + r, p[1] + r, &cand, &ncap);
                for (int j = 0; j < m; j++) {
                    const double *c = pts + 3 * cand[j];
                    if (fabs(c[0] - p[0]) <= r && fabs(c[1] - p[1]) <= r) bound[f] = fmin(bound[f], c[2]);
                }
            }
    }
    glpgp_bgrid_free(&G);
    free(pts);
    free(box);
    free(cand);
    return st;
}
