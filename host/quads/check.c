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

/* ---- box grid ------------------------------------------------------------ */

void glpgp_bgrid_free(bgrid *g)
{
    free(g->start);
    free(g->item);
    free(g->stamp);
    memset(g, 0, sizeof *g);
}

glpgp_status glpgp_bgrid_build(bgrid *g, const double *box, int n, double cs)
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

int glpgp_bgrid_query(bgrid *g, double x0, double y0, double x1, double y1, int **out, int *cap)
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

/* ---- segment and polygon predicates ---------------------------------------- */

static double orient2(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

double glpgp_seg_dist(const double *a, const double *b, const double *p, double *tout)
{
    double dx = b[0] - a[0], dy = b[1] - a[1];
    double l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2 : 0.0;
    t = fmax(0.0, fmin(1.0, t));
    if (tout) *tout = t;
    return hypot(a[0] + t * dx - p[0], a[1] + t * dy - p[1]);
}

int glpgp_seg_cross(const double *a, const double *b, const double *c, const double *d, double eps)
{
    /* an end point within eps of the other segment: touching, not crossing
     * (this also settles nearly collinear pieces, whose orientation signs
     * are rounding noise) */
    if (glpgp_seg_dist(a, b, c, NULL) <= eps || glpgp_seg_dist(a, b, d, NULL) <= eps ||
        glpgp_seg_dist(c, d, a, NULL) <= eps || glpgp_seg_dist(c, d, b, NULL) <= eps)
        return 0;
    double d1 = orient2(a, b, c), d2 = orient2(a, b, d), d3 = orient2(c, d, a), d4 = orient2(c, d, b);
    if (!((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0))) return 0;
    if (!((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 0;
    /* the crossing point must be away from the four end points */
    double t = d3 / (d3 - d4);
    double x = a[0] + t * (b[0] - a[0]), y = a[1] + t * (b[1] - a[1]);
    const double *e[4] = {a, b, c, d};
    for (int i = 0; i < 4; i++)
        if (hypot(x - e[i][0], y - e[i][1]) <= eps) return 0;
    return 1;
}

int glpgp_point_in_poly(const double *xy, const int *v, int n, const double *p, double eps)
{
    int wn = 0;
    for (int i = 0; i < n; i++) {
        const double *a = xy + 2 * v[i], *b = xy + 2 * v[(i + 1) % n];
        if (glpgp_seg_dist(a, b, p, NULL) <= eps) return 0;
        if (a[1] <= p[1]) {
            if (b[1] > p[1] && orient2(a, b, p) > 0) wn++;
        } else if (b[1] <= p[1] && orient2(a, b, p) < 0) {
            wn--;
        }
    }
    return wn != 0;
}

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

/* Flag the faces at vertex v (corner slots vs/vc). */
static void flag_vertex(const glpgp_quadmesh *q, const int *vs, const int *vc, const int *slot_face, int v,
                        unsigned bit, unsigned *flags)
{
    (void)q;
    for (int j = vs[v]; j < vs[v + 1]; j++) flags[slot_face[vc[j]]] |= bit;
}

glpgp_status glpgp_qcheck_run(const glpgp_quadmesh *q, const glpgp_mesh *dm, double h, double tol, qcheck *c)
{
    memset(c, 0, sizeof *c);
    c->corners_lost = -1;
    const int nf = q->nf, nv = q->nv, nc = q->face_start[nf];
    glpgp_status st = GLPGP_OK;
    hedge4 *H = NULL;
    int *vs = NULL, *vc = NULL, *sf = NULL, *cnt = NULL, *par = NULL, *cand = NULL, *bnext = NULL;
    unsigned char *bvert = NULL, *bused = NULL;
    double *box = NULL, *fbox = NULL, *dbox = NULL, *tbox = NULL, *bbox = NULL;
    int *eu = NULL, *ebf = NULL; /* unique edges (2 per edge), boundary edge -> face */
    int ncap = 0;
    bgrid GE, GF, GD, GT, GB;
    memset(&GE, 0, sizeof GE);
    memset(&GF, 0, sizeof GF);
    memset(&GD, 0, sizeof GD);
    memset(&GT, 0, sizeof GT);
    memset(&GB, 0, sizeof GB);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nf + 1, sizeof(unsigned), &c->flags), done);
    unsigned *fl = c->flags;

    /* 1. orientation: sign of the total signed area */
    double total = 0.0;
    for (int f = 0; f < nf; f++) {
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        for (int i = 0; i < k; i++) {
            const double *a = q->xy + 2 * q->face_vert[s + i], *b = q->xy + 2 * q->face_vert[s + (i + 1) % k];
            total += 0.5 * (a[0] * b[1] - b[0] * a[1]);
        }
    }
    const int orient = total < 0 ? -1 : 1;
    c->orientation = orient;

    /* 2. per face: corners, inversion, degeneracy */
    for (int f = 0; f < nf; f++) {
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        const int *v = q->face_vert + s;
        if (k != 4) fl[f] |= QF_NONQUAD;
        double area = 0.0, msj = INFINITY, lmax = 0.0;
        for (int i = 0; i < k; i++) {
            const double *a = q->xy + 2 * v[i], *b = q->xy + 2 * v[(i + 1) % k];
            lmax = fmax(lmax, hypot(b[0] - a[0], b[1] - a[1]));
        }
        /* degenerate against the face's own size (a fine valid mesh, e.g. the
         * input's triangles split, is not degenerate for a large h) */
        for (int i = 0; i < k; i++) {
            const double *a = q->xy + 2 * v[i], *b = q->xy + 2 * v[(i + 1) % k], *p = q->xy + 2 * v[(i + k - 1) % k];
            for (int j = i + 1; j < k; j++)
                if (v[j] == v[i]) fl[f] |= QF_DEGENERATE;
            double e1x = b[0] - a[0], e1y = b[1] - a[1], e2x = p[0] - a[0], e2y = p[1] - a[1];
            double l1 = hypot(e1x, e1y), l2 = hypot(e2x, e2y);
            if (!(l1 > 1e-9 * lmax) || l1 < 1e-15 * h) fl[f] |= QF_DEGENERATE;
            area += 0.5 * ((a[0] - q->xy[2 * v[0]]) * (b[1] - q->xy[2 * v[0] + 1]) -
                           (b[0] - q->xy[2 * v[0]]) * (a[1] - q->xy[2 * v[0] + 1]));
            double sj = (l1 > 0 && l2 > 0) ? orient * (e1x * e2y - e1y * e2x) / (l1 * l2) : 0.0;
            msj = fmin(msj, sj);
        }
        area *= orient;
        if (k < 3 || !(fabs(area) > 1e-12 * lmax * lmax)) fl[f] |= QF_DEGENERATE;
        if (area <= 0.0 || (k == 4 && msj < 0.0)) fl[f] |= QF_INVERTED;
        if (k == 4 && msj < 1e-3) fl[f] |= QF_FLAT;
    }

    /* 3. edges: non-manifold, folds, boundary */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof *H, &H), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof(int), &sf), done);
    for (int f = 0; f < nf; f++) {
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        for (int i = 0; i < k; i++) {
            int a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % k];
            H[s + i] = (hedge4){a < b ? a : b, a < b ? b : a, f, a < b};
            sf[s + i] = f;
        }
    }
    qsort(H, (size_t)nc, sizeof *H, cmp_h4);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv + 1, 1, &bvert), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nc + 2, sizeof(int), &eu), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof(int), &ebf), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv + 1, sizeof(int), &bnext), done);
    for (int i = 0; i < nv; i++) bnext[i] = -1;
    int ne = 0;
    for (int k = 0; k < nc;) {
        int e = k + 1;
        while (e < nc && H[e].a == H[k].a && H[e].b == H[k].b) e++;
        eu[2 * ne] = H[k].a;
        eu[2 * ne + 1] = H[k].b;
        ebf[ne] = -1;
        if (e - k == 1) {
            bvert[H[k].a] = bvert[H[k].b] = 1;
            ebf[ne] = H[k].f;
            /* boundary successor in the face direction (loops count) */
            int from = H[k].dir ? H[k].a : H[k].b, to = H[k].dir ? H[k].b : H[k].a;
            bnext[from] = to;
        } else if (e - k > 2 || H[k].dir == H[k + 1].dir) {
            c->nonmanifold_edges++;
            for (int j = k; j < e; j++) fl[H[j].f] |= QF_NONMANIFOLD;
        }
        ne++;
        k = e;
    }
    /* boundary loops: cycles of the boundary successor */
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv + 1, 1, &bused), done);
    for (int v = 0; v < nv; v++) {
        if (bnext[v] < 0 || bused[v]) continue;
        int u = v, guard = 0;
        while (u >= 0 && !bused[u] && guard++ <= nv) {
            bused[u] = 1;
            u = bnext[u];
        }
        c->boundary_loops++;
    }

    /* 4. pinched vertices: corners at v joined when they share an edge */
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv + 2, sizeof(int), &vs), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof(int), &vc), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv + 1, sizeof(int), &cnt), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof(int), &par), done);
    for (int s = 0; s < nc; s++) vs[q->face_vert[s] + 1]++;
    for (int v = 0; v < nv; v++) vs[v + 1] += vs[v];
    for (int s = 0; s < nc; s++) vc[vs[q->face_vert[s]] + cnt[q->face_vert[s]]++] = s;
    for (int s = 0; s < nc; s++) par[s] = s;
    for (int v = 0; v < nv; v++) {
        int n = vs[v + 1] - vs[v];
        if (n < 2) continue;
        for (int i = 0; i < n; i++) {
            int si = vc[vs[v] + i], fi = sf[si], bi = q->face_start[fi], ki = q->face_start[fi + 1] - bi;
            int nxt = q->face_vert[bi + (si - bi + 1) % ki], prv = q->face_vert[bi + (si - bi + ki - 1) % ki];
            for (int j = i + 1; j < n; j++) {
                int sj = vc[vs[v] + j], fj = sf[sj], bj = q->face_start[fj], kj = q->face_start[fj + 1] - bj;
                int nx2 = q->face_vert[bj + (sj - bj + 1) % kj], pv2 = q->face_vert[bj + (sj - bj + kj - 1) % kj];
                if (nxt == pv2 || prv == nx2 || nxt == nx2 || prv == pv2) {
                    int ra = uf(par, si), rb = uf(par, sj);
                    if (ra != rb) par[rb] = ra;
                }
            }
        }
        int comps = 0;
        for (int i = 0; i < n; i++)
            if (uf(par, vc[vs[v] + i]) == vc[vs[v] + i]) comps++;
        if (comps > 1) {
            c->pinched++;
            flag_vertex(q, vs, vc, sf, v, QF_PINCHED, fl);
        }
    }

    /* 5. overlaps: edge crossings, vertices inside faces */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * ne + 4, sizeof(double), &box), done);
    for (int e = 0; e < ne; e++) {
        const double *a = q->xy + 2 * eu[2 * e], *b = q->xy + 2 * eu[2 * e + 1];
        box[4 * e] = fmin(a[0], b[0]);
        box[4 * e + 1] = fmin(a[1], b[1]);
        box[4 * e + 2] = fmax(a[0], b[0]);
        box[4 * e + 3] = fmax(a[1], b[1]);
    }
    GLPGP_CHECK_GOTO(st, glpgp_bgrid_build(&GE, box, ne, h), done);
    /* edge -> one face slot: walk H again (same order as the unique edges) */
    {
        int *eface = NULL; /* up to 2 faces per edge */
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * ne + 2, sizeof(int), &eface), done);
        int e = 0;
        for (int k = 0; k < nc;) {
            int j = k + 1;
            while (j < nc && H[j].a == H[k].a && H[j].b == H[k].b) j++;
            eface[2 * e] = H[k].f;
            eface[2 * e + 1] = j > k + 1 ? H[k + 1].f : -1;
            e++;
            k = j;
        }
        for (int e1 = 0; e1 < ne; e1++) {
            if ((e1 & 32767) == 0) glpgp_progress_poll();
            int n = glpgp_bgrid_query(&GE, box[4 * e1], box[4 * e1 + 1], box[4 * e1 + 2], box[4 * e1 + 3], &cand, &ncap);
            if (n < 0) {
                free(eface);
                st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad check: out of memory");
                goto done;
            }
            const double *a = q->xy + 2 * eu[2 * e1], *b = q->xy + 2 * eu[2 * e1 + 1];
            for (int i = 0; i < n; i++) {
                int e2 = cand[i];
                if (e2 <= e1) continue;
                if (eu[2 * e2] == eu[2 * e1] || eu[2 * e2] == eu[2 * e1 + 1] || eu[2 * e2 + 1] == eu[2 * e1] ||
                    eu[2 * e2 + 1] == eu[2 * e1 + 1])
                    continue;
                if (!glpgp_seg_cross(a, b, q->xy + 2 * eu[2 * e2], q->xy + 2 * eu[2 * e2 + 1], 1e-9 * h)) continue;
                for (int s = 0; s < 2; s++) {
                    if (eface[2 * e1 + s] >= 0) fl[eface[2 * e1 + s]] |= QF_OVERLAP;
                    if (eface[2 * e2 + s] >= 0) fl[eface[2 * e2 + s]] |= QF_OVERLAP;
                }
            }
        }
        free(eface);
    }
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * nf + 4, sizeof(double), &fbox), done);
    for (int f = 0; f < nf; f++) {
        double *bx = fbox + 4 * f;
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
    GLPGP_CHECK_GOTO(st, glpgp_bgrid_build(&GF, fbox, nf, h), done);
    for (int v = 0; v < nv; v++) {
        if (vs[v + 1] == vs[v]) continue;
        const double *p = q->xy + 2 * v;
        int n = glpgp_bgrid_query(&GF, p[0], p[1], p[0], p[1], &cand, &ncap);
        if (n < 0) {
            st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad check: out of memory");
            goto done;
        }
        for (int i = 0; i < n; i++) {
            int f = cand[i], s = q->face_start[f], k = q->face_start[f + 1] - s, own = 0;
            for (int j = 0; j < k; j++) own |= q->face_vert[s + j] == v;
            if (own || p[0] < fbox[4 * f] || p[0] > fbox[4 * f + 2] || p[1] < fbox[4 * f + 1] ||
                p[1] > fbox[4 * f + 3])
                continue;
            /* inside, or on a side (a hanging vertex) */
            int hit = glpgp_point_in_poly(q->xy, q->face_vert + s, k, p, 1e-9 * h);
            for (int j = 0; j < k && !hit; j++)
                hit = glpgp_seg_dist(q->xy + 2 * q->face_vert[s + j], q->xy + 2 * q->face_vert[s + (j + 1) % k], p,
                                     NULL) <= 1e-9 * h;
            if (hit) {
                fl[f] |= QF_OVERLAP;
                flag_vertex(q, vs, vc, sf, v, QF_OVERLAP, fl);
            }
        }
    }

    /* 6. the domain */
    if (dm) {
        const int nb = dm->loop_start[dm->nloops];
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * nb + 4, sizeof(double), &dbox), done);
        for (int l = 0; l < dm->nloops; l++) {
            int s = dm->loop_start[l], n = dm->loop_start[l + 1] - s;
            for (int i = 0; i < n; i++) {
                const double *a = dm->xy + 2 * dm->loop_vertices[s + i], *b = dm->xy + 2 * dm->loop_vertices[s + (i + 1) % n];
                dbox[4 * (s + i)] = fmin(a[0], b[0]);
                dbox[4 * (s + i) + 1] = fmin(a[1], b[1]);
                dbox[4 * (s + i) + 2] = fmax(a[0], b[0]);
                dbox[4 * (s + i) + 3] = fmax(a[1], b[1]);
            }
        }
        GLPGP_CHECK_GOTO(st, glpgp_bgrid_build(&GD, dbox, nb, h), done);
        /* segment i of the domain: loop vertices i and next(i) */
        int *dnext = NULL;
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nb + 1, sizeof(int), &dnext), done);
        for (int l = 0; l < dm->nloops; l++) {
            int s = dm->loop_start[l], n = dm->loop_start[l + 1] - s;
            for (int i = 0; i < n; i++) dnext[s + i] = dm->loop_vertices[s + (i + 1) % n];
        }
#define DSEG_A(i) (dm->xy + 2 * dm->loop_vertices[i])
#define DSEG_B(i) (dm->xy + 2 * dnext[i])
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * dm->nt + 4, sizeof(double), &tbox), done);
        for (int t = 0; t < dm->nt; t++) {
            const double *a = dm->xy + 2 * dm->tri[3 * t], *b = dm->xy + 2 * dm->tri[3 * t + 1],
                         *cc = dm->xy + 2 * dm->tri[3 * t + 2];
            tbox[4 * t] = fmin(a[0], fmin(b[0], cc[0]));
            tbox[4 * t + 1] = fmin(a[1], fmin(b[1], cc[1]));
            tbox[4 * t + 2] = fmax(a[0], fmax(b[0], cc[0]));
            tbox[4 * t + 3] = fmax(a[1], fmax(b[1], cc[1]));
        }
        GLPGP_CHECK_GOTO(st, glpgp_bgrid_build(&GT, tbox, dm->nt, h), done);
        /* touching tolerance against the domain boundary: 1% of h (a mesh of
         * the exact curves, e.g. Gmsh's, is within that of the polygonal
         * domain; a face across a slot or a hole is far beyond it) */
        const double eps_in = 1e-2 * h;
        /* corners outside the domain */
        for (int v = 0; v < nv && st == GLPGP_OK; v++) {
            if (vs[v + 1] == vs[v]) continue;
            const double *p = q->xy + 2 * v;
            int n = glpgp_bgrid_query(&GT, p[0] - eps_in, p[1] - eps_in, p[0] + eps_in, p[1] + eps_in, &cand, &ncap);
            int in = 0;
            for (int i = 0; i < n && !in; i++) {
                int t = cand[i];
                const double *a = dm->xy + 2 * dm->tri[3 * t], *b = dm->xy + 2 * dm->tri[3 * t + 1],
                             *cc = dm->xy + 2 * dm->tri[3 * t + 2];
                in = orient2(a, b, p) >= 0 && orient2(b, cc, p) >= 0 && orient2(cc, a, p) >= 0;
            }
            if (!in) {
                n = glpgp_bgrid_query(&GD, p[0] - eps_in, p[1] - eps_in, p[0] + eps_in, p[1] + eps_in, &cand, &ncap);
                for (int i = 0; i < n && !in; i++) in = glpgp_seg_dist(DSEG_A(cand[i]), DSEG_B(cand[i]), p, NULL) <= eps_in;
            }
            if (!in) flag_vertex(q, vs, vc, sf, v, QF_OUTSIDE, fl);
        }
        /* edges crossing the domain boundary */
        for (int e = 0; e < ne; e++) {
            const double *a = q->xy + 2 * eu[2 * e], *b = q->xy + 2 * eu[2 * e + 1];
            int n = glpgp_bgrid_query(&GD, box[4 * e], box[4 * e + 1], box[4 * e + 2], box[4 * e + 3], &cand, &ncap);
            for (int i = 0; i < n; i++)
                if (glpgp_seg_cross(a, b, DSEG_A(cand[i]), DSEG_B(cand[i]), eps_in)) {
                    /* both faces of the edge */
                    int lo = 0, hi = nc - 1, key_a = eu[2 * e], key_b = eu[2 * e + 1];
                    while (lo < hi) { /* first half-edge of the edge in H */
                        int mid = (lo + hi) / 2;
                        if (H[mid].a < key_a || (H[mid].a == key_a && H[mid].b < key_b))
                            lo = mid + 1;
                        else
                            hi = mid;
                    }
                    for (int j = lo; j < nc && H[j].a == key_a && H[j].b == key_b; j++) fl[H[j].f] |= QF_OUTSIDE;
                    break;
                }
        }
        /* mesh boundary edges far from the domain boundary */
        int nbe = 0;
        for (int e = 0; e < ne; e++) nbe += ebf[e] >= 0;
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * nbe + 4, sizeof(double), &bbox), done);
        int *bidx = NULL;
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nbe + 1, sizeof(int), &bidx), done);
        nbe = 0;
        for (int e = 0; e < ne; e++) {
            if (ebf[e] < 0) continue;
            memcpy(bbox + 4 * nbe, box + 4 * e, 4 * sizeof(double));
            bidx[nbe++] = e;
        }
        GLPGP_CHECK_GOTO(st, glpgp_bgrid_build(&GB, bbox, nbe, h), done);
        for (int i = 0; i < nbe; i++) {
            int e = bidx[i];
            const double *a = q->xy + 2 * eu[2 * e], *b = q->xy + 2 * eu[2 * e + 1];
            for (int k = 0; k <= 8; k++) {
                double t = k / 8.0, p[2] = {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
                int n = glpgp_bgrid_query(&GD, p[0] - tol, p[1] - tol, p[0] + tol, p[1] + tol, &cand, &ncap);
                double d = INFINITY;
                for (int j = 0; j < n; j++) d = fmin(d, glpgp_seg_dist(DSEG_A(cand[j]), DSEG_B(cand[j]), p, NULL));
                if (d > tol) {
                    fl[ebf[e]] |= QF_FAR;
                    break;
                }
                if (k == 0 || k == 8) c->bnd_vertex_dist = fmax(c->bnd_vertex_dist, d);
            }
        }
        /* domain boundary points far from the mesh boundary; corners */
        c->corners_lost = 0;
        for (int l = 0; l < dm->nloops; l++) {
            int s = dm->loop_start[l], n = dm->loop_start[l + 1] - s;
            for (int i = 0; i < n; i++) {
                int vi = dm->loop_vertices[s + i];
                const double *a = dm->xy + 2 * vi, *b = DSEG_B(s + i);
                const double *np = dm->normal_prev + 2 * vi, *nn = dm->normal_next + 2 * vi;
                int corner = np[0] * nn[0] + np[1] * nn[1] < cos(GLPGP_CORNER_DEG * 3.14159265358979323846 / 180.0);
                for (int k = 0; k < 2; k++) {
                    double p[2] = {k ? 0.5 * (a[0] + b[0]) : a[0], k ? 0.5 * (a[1] + b[1]) : a[1]};
                    double r = k == 0 && corner ? 1e-3 * h : tol;
                    int lost = 0;
                    if (k == 0 && corner) { /* a mesh vertex on the corner */
                        int m2 = glpgp_bgrid_query(&GF, p[0] - r, p[1] - r, p[0] + r, p[1] + r, &cand, &ncap);
                        int found = 0;
                        for (int j = 0; j < m2 && !found; j++) {
                            int f = cand[j];
                            for (int t = q->face_start[f]; t < q->face_start[f + 1] && !found; t++) {
                                const double *x = q->xy + 2 * q->face_vert[t];
                                found = hypot(x[0] - p[0], x[1] - p[1]) <= r;
                            }
                        }
                        if (!found) {
                            c->corners_lost++;
                            lost = 1;
                        }
                    }
                    if (!lost) {
                        int m2 = glpgp_bgrid_query(&GB, p[0] - tol, p[1] - tol, p[0] + tol, p[1] + tol, &cand, &ncap);
                        double d = INFINITY;
                        for (int j = 0; j < m2; j++) {
                            int e = bidx[cand[j]];
                            d = fmin(d, glpgp_seg_dist(q->xy + 2 * eu[2 * e], q->xy + 2 * eu[2 * e + 1], p, NULL));
                        }
                        lost = d > tol;
                    }
                    if (!lost) continue;
                    /* flag the faces containing p, else the nearest boundary edge's face */
                    int m2 = glpgp_bgrid_query(&GF, p[0], p[1], p[0], p[1], &cand, &ncap);
                    int any = 0;
                    for (int j = 0; j < m2; j++) {
                        int f = cand[j], fs = q->face_start[f], fk = q->face_start[f + 1] - fs;
                        if (glpgp_point_in_poly(q->xy, q->face_vert + fs, fk, p, 0.0)) {
                            fl[f] |= QF_LOST;
                            any = 1;
                        }
                    }
                    if (!any && nbe > 0) {
                        double best = INFINITY;
                        int bf = -1;
                        for (double r2 = tol; bf < 0 || best > r2; r2 *= 2.0) {
                            int m3 = glpgp_bgrid_query(&GB, p[0] - r2, p[1] - r2, p[0] + r2, p[1] + r2, &cand, &ncap);
                            for (int j = 0; j < m3; j++) {
                                int e = bidx[cand[j]];
                                double d = glpgp_seg_dist(q->xy + 2 * eu[2 * e], q->xy + 2 * eu[2 * e + 1], p, NULL);
                                if (d < best) {
                                    best = d;
                                    bf = ebf[e];
                                }
                            }
                            if (r2 > 1e6 * (dm->bbox[2] - dm->bbox[0] + dm->bbox[3] - dm->bbox[1] + h)) break;
                        }
                        if (bf >= 0) fl[bf] |= QF_LOST;
                    }
                }
            }
        }
#undef DSEG_A
#undef DSEG_B
        free(dnext);
        free(bidx);
    }
done:
    free(H);
    free(vs);
    free(vc);
    free(sf);
    free(cnt);
    free(par);
    free(cand);
    free(bnext);
    free(bvert);
    free(bused);
    free(box);
    free(fbox);
    free(dbox);
    free(tbox);
    free(bbox);
    free(eu);
    free(ebf);
    glpgp_bgrid_free(&GE);
    glpgp_bgrid_free(&GF);
    glpgp_bgrid_free(&GD);
    glpgp_bgrid_free(&GT);
    glpgp_bgrid_free(&GB);
    if (st != GLPGP_OK) glpgp_qcheck_free(c);
    return st;
}

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
