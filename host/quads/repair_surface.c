/* quads/repair_surface.c: the local repair of a quad mesh of a 3D surface
 * (glpgp_qs_local_repair, quads_surface.h), what the planar repair
 * (repair.c) does in the plane:
 *  - bad faces: not quads, inverted (a corner's scaled Jacobian in the
 *    face's own plane <= 0.02, or the face against the surface's normal),
 *    with a side under 0.05 h, on a non-manifold edge or at a pinched
 *    vertex, or (when asked: far) with a sample (a 4 x 4 grid on each of
 *    its fan triangles, as the check samples it) over 0.22 h from the
 *    surface;
 *  - regions: the bad faces in vertex-connected parts, each grown until it
 *    is a topological disk (one simple boundary loop, V - E + F = 1; the
 *    faces at a vertex the loop passes twice, the kept faces inside its
 *    other loops, else a ring of faces); a part with an odd boundary (an
 *    odd count of odd faces) is joined to the nearest other odd part
 *    through a path of faces, or gets a point on a boundary side of the
 *    surface;
 *  - each region's faces removed, its boundary loop (its points fixed)
 *    mapped to a chart: the plane through the loop's centroid orthogonal to
 *    its vector area when the projected loop is a simple counter-clockwise
 *    polygon (and the surface under each loop point faces within 107
 *    degrees of the plane's normal), else the region's own faces flattened
 *    by the least-squares conformal map (the conformal chart: the loop's
 *    corners kept, reflex ones too), else a circle (by 3D arc length, as
 *    large as the region), else that circle with the region's own faces
 *    Tutte-embedded in it (the patch chart);
 *    meshed there by the cut mesher (qcut.c); the new points lifted by the
 *    mean-value interpolation of the loop's heights above the plane (of the
 *    loop's 3D points on the circle) and moved to their nearest points on
 *    the surface;
 *  - the region's new quads checked in 3D (every corner's scaled Jacobian
 *    above 0, along the surface's normal; the smoothing follows) and their
 *    boundary against the loop; a region that fails grows by a ring and is
 *    tried again (6 rounds); regions over half the faces: not local; when
 *    some fail to the end, the round with the fewest faces in failed
 *    regions is kept, its meshed regions replaced (a partial repair).
 * The grid's faces outside the regions are kept as they are. The caller
 * checks the whole mesh (check_surface.c) and falls back to the splits and
 * the coarse last resort when the repair fails or is not valid. */
#include "qcut.h"
#include "quads_surface.h"
#include "qvec.h"
#include "vec3.h"

#include "glpgp/kinds.h"
#include "glpgp/surface.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define LR_SJ_BAD 0.02   /* a face with a corner at or below: repaired */
#define LR_FAR 0.22      /* a face sample farther from the surface (in h): repaired */
#define LR_SJ_NEW 0.0    /* the new quads' corners must be above (the smoothing follows) */
#define LR_SJ_TANGLED -0.5 /* a lift whose worst corner is above this is untangled first */
#define LR_UNTANGLE 10   /* the untangling's Laplacian sweeps at most */
#define LR_SHORT 0.05    /* a face with a side under this (in h): repaired */
#define LR_ROUNDS 6      /* growth rounds */
#define LR_SHARE 0.5     /* regions over this share of the faces: not a local repair */
#define LR_NORMAL -0.3   /* the chart: loop normals . plane normal above this */
#define LR_WORK 2e6      /* the cut mesher's work per region (its cut searches' points squared; 1e6: 0.2-1.5 s) */
#define LR_WORK_ALL 1e7  /* and per repair: the regions after it fail (the fallbacks follow) */

typedef struct lrep {
    const glpgp_mesh *m;
    const glpgp_quadmesh *q;
    double h;
    glpgp_qs_proj *P;
    int nc, ne;
    int *twin;          /* per corner: the corner running its edge back; -1 boundary, -2 non-manifold */
    int *eid;           /* per corner: its edge */
    int *cface;         /* per corner: its face */
    int *vs, *vf;       /* per vertex: its faces (vs: nv + 1 offsets into vf) */
    unsigned char *bad; /* per face */
    unsigned char *in;  /* per face: in a region */
    int *comp;          /* per face: its region (-1: kept) */
    int ncomp;
    int *cs, *cf;       /* per region: its faces (cs: ncomp + 1 offsets into cf) */
    int *outc;          /* per vertex scratch: the region's boundary corner leaving it */
    int *mark, stamp;   /* per vertex and per edge scratch (nv + ne) */
    dvec nxyz;          /* new points (ids q->nv ...) */
    double *work_left;  /* the cut mesher's work left to this repair (LR_WORK_ALL) */
} lrep;


/* The points: q's, then the new ones (ids q->nv ...). */
static glpgp_qs_pts points(const lrep *L)
{
    return (glpgp_qs_pts){L->q->xyz, L->nxyz.p, L->q->nv, L->q->nv + L->nxyz.n / 3};
}

static const double *pos(const lrep *L, int id)
{
    const glpgp_qs_pts S = points(L);
    return glpgp_qs_pt(&S, id);
}

static int cnext(const lrep *L, int c)
{
    const int f = L->cface[c];
    return c + 1 < L->q->face_start[f + 1] ? c + 1 : L->q->face_start[f];
}

/* ---- the mesh's edges and its bad faces ---------------------------------------- */

typedef struct lhe {
    int lo, hi, c, fwd;
} lhe;

static int cmp_lhe(const void *pa, const void *pb)
{
    const lhe *a = pa, *b = pb;
    if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
    if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
    return a->c - b->c;
}

/* twin, eid, cface; the faces on a non-manifold or degenerate edge are bad. */
static glpgp_status build_edges(lrep *L)
{
    const glpgp_quadmesh *q = L->q;
    lhe *E = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)L->nc + 1, sizeof *E, &E));
    for (int f = 0; f < q->nf; f++) {
        const int s = q->face_start[f], n = q->face_start[f + 1] - s;
        for (int i = 0; i < n; i++) {
            const int a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % n];
            E[s + i] = (lhe){a < b ? a : b, a < b ? b : a, s + i, a < b};
            L->cface[s + i] = f;
            if (a == b) L->bad[f] = 1;
        }
    }
    qsort(E, (size_t)L->nc, sizeof *E, cmp_lhe);
    L->ne = 0;
    for (int i = 0; i < L->nc;) {
        int j = i;
        while (j < L->nc && E[j].lo == E[i].lo && E[j].hi == E[i].hi) j++;
        for (int k = i; k < j; k++) {
            L->eid[E[k].c] = L->ne;
            L->twin[E[k].c] = j - i == 1 ? -1 : -2;
        }
        if (j - i == 2 && E[i].fwd != E[i + 1].fwd) {
            L->twin[E[i].c] = E[i + 1].c;
            L->twin[E[i + 1].c] = E[i].c;
        } else if (j - i > 1) {
            for (int k = i; k < j; k++) L->bad[L->cface[E[k].c]] = 1;
        }
        L->ne++;
        i = j;
    }
    free(E);
    return GLPGP_OK;
}

/* The faces at a pinched vertex (its corners in more than one fan) are bad. */
static glpgp_status pinched(lrep *L)
{
    const glpgp_quadmesh *q = L->q;
    int *uf = NULL, *root = NULL;
    glpgp_status st = glpgp_malloc((size_t)L->nc + 1, sizeof(int), &uf);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)q->nv + 1, sizeof(int), &root);
    if (st != GLPGP_OK) goto done;
    for (int c = 0; c < L->nc; c++) uf[c] = c;
    for (int c = 0; c < L->nc; c++) /* c runs a -> b, its twin b -> a: a's corner there is the twin's next */
        if (L->twin[c] >= 0) uf[glpgp_uf_find(uf, c)] = glpgp_uf_find(uf, cnext(L, L->twin[c]));
    for (int v = 0; v < q->nv; v++) root[v] = -1;
    for (int c = 0; c < L->nc; c++) {
        const int v = q->face_vert[c], r = glpgp_uf_find(uf, c);
        if (root[v] == -1) root[v] = r;
        else if (root[v] != r) root[v] = -2;
    }
    for (int v = 0; v < q->nv; v++)
        if (root[v] == -2)
            for (int k = L->vs[v]; k < L->vs[v + 1]; k++) L->bad[L->vf[k]] = 1;
done:
    free(uf);
    free(root);
    return st;
}

/* Whether p is over LR_FAR h from the surface. */
static int far_point(const lrep *L, const double *p)
{
    double x[3], d[3];
    if (glpgp_qs_proj_nearest(L->P, p, x) < 0) return 1;
    sub3(p, x, d);
    return dot3(d, d) > LR_FAR * LR_FAR * L->h * L->h;
}

/* Bad by its own shape: not a quad, inverted, against the surface, far from it. */
static int bad_face(const lrep *L, int f, int far)
{
    const glpgp_quadmesh *q = L->q;
    const int s = q->face_start[f], n = q->face_start[f + 1] - s;
    if (n != 4 || glpgp_quadmesh_face_sj_surface(q, f) <= LR_SJ_BAD) return 1;
    double N[3], c[3] = {0, 0, 0}, x[3];
    glpgp_quadmesh_face_normal(q, f, 0, N);
    for (int i = 0; i < n; i++)
        for (int d = 0; d < 3; d++) c[d] += q->xyz[3 * q->face_vert[s + i] + d] / n;
    const int t = glpgp_qs_proj_nearest(L->P, c, x);
    if (t < 0 || dot3(N, L->m->surf->tframe + 9 * t + 6) <= 0.0) return 1;
    for (int i = 0; i < n; i++) { /* a side under LR_SHORT h: a nearly degenerate face */
        double d[3];
        sub3(q->xyz + 3 * q->face_vert[s + i], q->xyz + 3 * q->face_vert[s + (i + 1) % n], d);
        if (dot3(d, d) < LR_SHORT * LR_SHORT * L->h * L->h) return 1;
    }
    if (!far) return 0;
    const double *A = q->xyz + 3 * q->face_vert[s]; /* the check's fan triangles, a 4 x 4 grid of samples each */
    for (int k = 1; k + 1 < n; k++) {
        const double *B = q->xyz + 3 * q->face_vert[s + k], *C = q->xyz + 3 * q->face_vert[s + k + 1];
        for (int i = 0; i <= 4; i++)
            for (int j = 0; i + j <= 4; j++) {
                const double u = 0.25 * i, v = 0.25 * j;
                double p[3];
                for (int d = 0; d < 3; d++) p[d] = (1 - u - v) * A[d] + u * B[d] + v * C[d];
                if (far_point(L, p)) return 1;
            }
    }
    return 0;
}

static glpgp_status lrep_init(lrep *L, const glpgp_mesh *m, const glpgp_quadmesh *q, double h, int far)
{
    memset(L, 0, sizeof *L);
    L->m = m;
    L->q = q;
    L->h = h;
    L->nc = q->face_start[q->nf];
    const size_t nf = (size_t)q->nf + 1, nc = (size_t)L->nc + 1, nv = (size_t)q->nv + 1;
    GLPGP_CHECK(glpgp_qs_proj_create(m, h, 2.0 * h, &L->P));
    GLPGP_CHECK(glpgp_malloc(nc, sizeof(int), &L->twin));
    GLPGP_CHECK(glpgp_malloc(nc, sizeof(int), &L->eid));
    GLPGP_CHECK(glpgp_malloc(nc, sizeof(int), &L->cface));
    GLPGP_CHECK(glpgp_calloc(nv + 1, sizeof(int), &L->vs));
    GLPGP_CHECK(glpgp_malloc(nc, sizeof(int), &L->vf));
    GLPGP_CHECK(glpgp_calloc(nf, 1, &L->bad));
    GLPGP_CHECK(glpgp_calloc(nf, 1, &L->in));
    GLPGP_CHECK(glpgp_malloc(nf, sizeof(int), &L->comp));
    GLPGP_CHECK(glpgp_malloc(nf + 1, sizeof(int), &L->cs));
    GLPGP_CHECK(glpgp_malloc(nf, sizeof(int), &L->cf));
    GLPGP_CHECK(glpgp_malloc(nv, sizeof(int), &L->outc));
    for (int c = 0; c < L->nc; c++) L->vs[q->face_vert[c] + 1]++;
    for (int v = 0; v < q->nv; v++) L->vs[v + 1] += L->vs[v];
    for (int f = 0, *fill = L->outc; f < q->nf; f++) { /* outc as the fill counters */
        if (f == 0) memset(fill, 0, nv * sizeof(int));
        for (int c = q->face_start[f]; c < q->face_start[f + 1]; c++) {
            const int v = q->face_vert[c];
            L->vf[L->vs[v] + fill[v]++] = f;
        }
    }
    for (int v = 0; v < q->nv; v++) L->outc[v] = -1;
    GLPGP_CHECK(build_edges(L));
    GLPGP_CHECK(glpgp_calloc((size_t)q->nv + L->ne + 1, sizeof(int), &L->mark));
    GLPGP_CHECK(pinched(L));
    for (int f = 0; f < q->nf; f++)
        if (!L->bad[f]) L->bad[f] = (unsigned char)bad_face(L, f, far);
    return GLPGP_OK;
}

static void lrep_free(lrep *L)
{
    glpgp_qs_proj_destroy(&L->P);
    free(L->twin);
    free(L->eid);
    free(L->cface);
    free(L->vs);
    free(L->vf);
    free(L->bad);
    free(L->in);
    free(L->comp);
    free(L->cs);
    free(L->cf);
    free(L->outc);
    free(L->mark);
    dvec_free(&L->nxyz);
}

/* ---- regions -------------------------------------------------------------------- */

/* in |= the faces sharing a vertex with a face f of sel (sel[f] != 0). */
static glpgp_status grow_ring(lrep *L, const unsigned char *sel)
{
    const glpgp_quadmesh *q = L->q;
    unsigned char *add = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)q->nf + 1, 1, &add));
    for (int f = 0; f < q->nf; f++) {
        if (!sel[f]) continue;
        for (int c = q->face_start[f]; c < q->face_start[f + 1]; c++) {
            const int v = q->face_vert[c];
            for (int k = L->vs[v]; k < L->vs[v + 1]; k++) add[L->vf[k]] = 1;
        }
    }
    for (int f = 0; f < q->nf; f++) L->in[f] |= add[f];
    free(add);
    return GLPGP_OK;
}

/* The vertex-connected parts of the faces in L->in: comp, cs, cf. */
static void components(lrep *L)
{
    const glpgp_quadmesh *q = L->q;
    int nq = 0;
    L->ncomp = 0;
    for (int f = 0; f < q->nf; f++) L->comp[f] = -1;
    for (int f0 = 0; f0 < q->nf; f0++) {
        if (!L->in[f0] || L->comp[f0] >= 0) continue;
        L->cs[L->ncomp] = nq;
        L->comp[f0] = L->ncomp;
        L->cf[nq++] = f0;
        for (int head = L->cs[L->ncomp]; head < nq; head++) { /* cf doubles as the queue */
            const int f = L->cf[head];
            for (int c = q->face_start[f]; c < q->face_start[f + 1]; c++) {
                const int v = q->face_vert[c];
                for (int k = L->vs[v]; k < L->vs[v + 1]; k++) {
                    const int g = L->vf[k];
                    if (L->in[g] && L->comp[g] < 0) {
                        L->comp[g] = L->ncomp;
                        L->cf[nq++] = g;
                    }
                }
            }
        }
        L->ncomp++;
    }
    L->cs[L->ncomp] = nq;
}

/* Whether corner c of region k's face is on the region's boundary. */
static int on_rim(const lrep *L, int k, int c)
{
    const int t = L->twin[c];
    return t == -1 || (t >= 0 && L->comp[L->cface[t]] != k);
}

/* Region k's boundary loop (vertex ids, the region on the left) when the
 * region is a topological disk (a non-manifold or degenerate one: when its
 * boundary is one simple loop; the caller's check decides); 0 otherwise. *bnd: a loop position whose
 * edge is on the surface's boundary (the longest; -1: none). */
static glpgp_status region_loop(lrep *L, int k, ivec *loop, int *bnd, int *disk)
{
    const glpgp_quadmesh *q = L->q;
    int nb = 0, nvert = 0, nedge = 0, c0 = -1;
    *disk = 0;
    *bnd = -1;
    loop->n = 0;
    const int stamp = ++L->stamp, nf = L->cs[k + 1] - L->cs[k];
    int simple = 1, broken = 0;
    for (int i = L->cs[k]; i < L->cs[k + 1]; i++) {
        const int f = L->cf[i];
        for (int c = q->face_start[f]; c < q->face_start[f + 1]; c++) {
            const int v = q->face_vert[c], e = L->eid[c];
            broken |= L->twin[c] == -2 || v == q->face_vert[cnext(L, c)];
            if (L->mark[v] != stamp) L->mark[v] = stamp, nvert++;
            if (L->mark[q->nv + e] != stamp) L->mark[q->nv + e] = stamp, nedge++;
            if (!on_rim(L, k, c)) continue;
            if (L->outc[v] >= 0) simple = 0;
            L->outc[v] = c;
            c0 = c;
            nb++;
        }
    }
    if (simple && c0 >= 0 && (broken || nvert - nedge + nf == 1)) {
        int c = c0, len = 0;
        double best = -1.0;
        do {
            GLPGP_CHECK(ipush(loop, q->face_vert[c]));
            if (L->twin[c] == -1) {
                double d[3];
                sub3(pos(L, q->face_vert[cnext(L, c)]), pos(L, q->face_vert[c]), d);
                if (dot3(d, d) > best) best = dot3(d, d), *bnd = len;
            }
            len++;
            c = L->outc[q->face_vert[cnext(L, c)]];
        } while (c >= 0 && c != c0 && len <= nb);
        *disk = c == c0 && len == nb;
    }
    for (int i = L->cs[k]; i < L->cs[k + 1]; i++) /* outc back to -1 */
        for (int c = q->face_start[L->cf[i]]; c < q->face_start[L->cf[i] + 1]; c++) L->outc[q->face_vert[c]] = -1;
    return GLPGP_OK;
}

/* cs, cf rebuilt from comp (ncomp regions). */
static void regroup(lrep *L)
{
    const int nf = L->q->nf;
    for (int k = 0; k <= L->ncomp; k++) L->cs[k] = 0;
    for (int f = 0; f < nf; f++)
        if (L->comp[f] >= 0) L->cs[L->comp[f] + 1]++;
    for (int k = 0; k < L->ncomp; k++) L->cs[k + 1] += L->cs[k];
    for (int k = L->ncomp; k > 0; k--) L->cs[k] = L->cs[k - 1]; /* cs[k + 1]: region k's cursor */
    L->cs[0] = 0;
    for (int f = 0; f < nf; f++)
        if (L->comp[f] >= 0) L->cf[L->cs[L->comp[f] + 1]++] = f;
}

/* Face f's vertex centroid less o. */
static void face_centroid(const lrep *L, int f, const double *o, double *fc)
{
    const glpgp_quadmesh *q = L->q;
    const int n = q->face_start[f + 1] - q->face_start[f];
    for (int d = 0; d < 3; d++) fc[d] = -o[d];
    for (int c = q->face_start[f]; c < q->face_start[f + 1]; c++)
        for (int d = 0; d < 3; d++) fc[d] += pos(L, q->face_vert[c])[d] / n;
}

/* Region k, not a disk, around a hole of the surface (its rim on the
 * region's boundary: corners with no twin): cut in two by the plane through
 * the rim's centroid that holds the region's normal and its farthest face
 * (each half a disk that shares the cut's edges with the other, which both
 * keep as fixed loop points: conforming), as region_fix cannot grow it over
 * the hole. Kept when both halves are disks; else undone (*split 0). */
static glpgp_status split_annulus(lrep *L, int k, ivec *loop, int *split)
{
    const glpgp_quadmesh *q = L->q;
    double cc[3] = {0, 0, 0}, N[3] = {0, 0, 0}, x[3];
    int nrim = 0;
    *split = 0;
    for (int i = L->cs[k]; i < L->cs[k + 1]; i++) {
        const int f = L->cf[i], n = q->face_start[f + 1] - q->face_start[f];
        for (int c = q->face_start[f]; c < q->face_start[f + 1]; c++) {
            cross3(pos(L, q->face_vert[c]), pos(L, q->face_vert[q->face_start[f] + (c - q->face_start[f] + 1) % n]), x);
            for (int d = 0; d < 3; d++) N[d] += x[d];
            if (L->twin[c] != -1) continue;
            for (int d = 0; d < 3; d++) cc[d] += pos(L, q->face_vert[c])[d];
            nrim++;
        }
    }
    if (nrim == 0 || L->cs[k + 1] - L->cs[k] < 2 || !(dot3(N, N) > 0)) return GLPGP_OK;
    for (int d = 0; d < 3; d++) cc[d] /= nrim;
    double far[3] = {0, 0, 0}, best = -1.0, fc[3];
    for (int i = L->cs[k]; i < L->cs[k + 1]; i++) { /* the farthest face centroid, normal to N */
        const double zero[3] = {0.0, 0.0, 0.0};
        face_centroid(L, L->cf[i], zero, fc);
        double v[3];
        sub3(fc, cc, v);
        const double t = dot3(v, N) / dot3(N, N);
        for (int d = 0; d < 3; d++) v[d] -= t * N[d];
        if (dot3(v, v) > best) best = dot3(v, v), memcpy(far, v, sizeof far);
    }
    double P[3];
    cross3(N, far, P);
    if (!(dot3(P, P) > 0)) return GLPGP_OK;
    const int nk = L->ncomp;
    int na = 0, nb = 0;
    for (int i = L->cs[k]; i < L->cs[k + 1]; i++) {
        const int f = L->cf[i];
        face_centroid(L, f, cc, fc);
        if (dot3(fc, P) < 0.0) L->comp[f] = nk, nb++;
        else na++;
    }
    if (na == 0 || nb == 0) {
        for (int i = L->cs[k]; i < L->cs[k + 1]; i++) L->comp[L->cf[i]] = k;
        return GLPGP_OK;
    }
    L->ncomp++;
    regroup(L);
    int bnd, da, db;
    GLPGP_CHECK(region_loop(L, k, loop, &bnd, &da));
    GLPGP_CHECK(region_loop(L, nk, loop, &bnd, &db));
    if (!da || !db) { /* undone */
        for (int f = 0; f < q->nf; f++)
            if (L->comp[f] == nk) L->comp[f] = k;
        L->ncomp--;
        regroup(L);
        return GLPGP_OK;
    }
    *split = 1;
    glpgp_log(GLPGP_LOG_DEBUG, "quads: surface local repair: a region around a hole cut in two (%d + %d faces)", na, nb);
    return GLPGP_OK;
}

/* Faces added to region k (into sel) that is not a disk: the faces at a
 * vertex its boundary passes twice, else across the boundary loops but the
 * longest (kept faces it encloses), else the faces at all its vertices. */
static glpgp_status region_fix(lrep *L, int k, unsigned char *sel)
{
    const glpgp_quadmesh *q = L->q;
    ivec rim = {0};
    int pinch = 0;
    for (int i = L->cs[k]; i < L->cs[k + 1]; i++)
        for (int c = q->face_start[L->cf[i]]; c < q->face_start[L->cf[i] + 1]; c++) {
            if (!on_rim(L, k, c)) continue;
            const int v = q->face_vert[c];
            if (L->outc[v] >= 0) {
                for (int j = L->vs[v]; j < L->vs[v + 1]; j++) sel[L->vf[j]] = 1;
                pinch = 1;
            }
            L->outc[v] = c;
            GLPGP_CHECK(ipush(&rim, c));
        }
    int longest = -1, nloops = 0, best = 0;
    ivec start = {0};
    glpgp_status st = GLPGP_OK;
    for (int r = 0; r < rim.n && !pinch && st == GLPGP_OK; r++) { /* the loops: outc[v] = -2 - loop once traced */
        const int c0 = rim.p[r];
        if (L->outc[q->face_vert[c0]] < 0) continue;
        int c = c0, len = 0;
        while (c >= 0 && L->outc[q->face_vert[c]] >= 0) {
            const int nxt = L->outc[q->face_vert[cnext(L, c)]];
            L->outc[q->face_vert[c]] = -2 - nloops;
            len++;
            c = nxt;
        }
        if (len > best) best = len, longest = nloops;
        nloops++;
    }
    if (!pinch && nloops > 1) {
        for (int r = 0; r < rim.n; r++) {
            const int c = rim.p[r];
            if (L->outc[q->face_vert[c]] != -2 - longest && L->twin[c] >= 0) sel[L->cface[L->twin[c]]] = 1;
        }
    } else if (!pinch) {
        for (int i = L->cs[k]; i < L->cs[k + 1]; i++)
            for (int c = q->face_start[L->cf[i]]; c < q->face_start[L->cf[i] + 1]; c++)
                for (int j = L->vs[q->face_vert[c]]; j < L->vs[q->face_vert[c] + 1]; j++) sel[L->vf[j]] = 1;
    }
    for (int r = 0; r < rim.n; r++) L->outc[q->face_vert[rim.p[r]]] = -1;
    ivec_free(&rim);
    ivec_free(&start);
    return st;
}

/* Region k (odd boundary) joined to the nearest face of another odd region
 * or with a side on the surface's boundary: the faces of the path into in.
 * *found: 0 when none is reachable. */
static glpgp_status join_odd(lrep *L, int k, const unsigned char *odd, int *found)
{
    const glpgp_quadmesh *q = L->q;
    int *par = NULL, *queue = NULL, nq = 0, end = -1;
    *found = 0;
    glpgp_status st = glpgp_malloc((size_t)q->nf + 1, sizeof(int), &par);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)q->nf + 1, sizeof(int), &queue);
    if (st != GLPGP_OK) goto done;
    for (int f = 0; f < q->nf; f++) par[f] = -2;
    for (int i = L->cs[k]; i < L->cs[k + 1]; i++) {
        par[L->cf[i]] = -1;
        queue[nq++] = L->cf[i];
    }
    for (int head = 0; head < nq && end < 0; head++) {
        const int f = queue[head];
        for (int c = q->face_start[f]; c < q->face_start[f + 1] && end < 0; c++) {
            const int t = L->twin[c];
            if (t == -1 && L->comp[f] != k) end = f;
            if (t < 0) continue;
            const int g = L->cface[t];
            if (par[g] != -2) continue;
            par[g] = f;
            queue[nq++] = g;
            if (L->comp[g] >= 0 && L->comp[g] != k && odd[L->comp[g]]) end = g;
        }
    }
    for (int f = end; f >= 0; f = par[f]) L->in[f] = 1;
    *found = end >= 0;
done:
    free(par);
    free(queue);
    return st;
}

/* ---- one region meshed -------------------------------------------------------------- */

/* Mean-value interpolation at p of the values z on the polygon x (n points). */
static double mvc(const double *x, const double *z, int n, const double *p)
{
    double sw = 0.0, sz = 0.0;
    for (int i = 0; i < n; i++) {
        const double *a = x + 2 * i;
        const double r = hypot(a[0] - p[0], a[1] - p[1]);
        if (r < 1e-14) return z[i];
        double w = 0.0;
        for (int s = -1; s <= 0; s++) { /* the angles of the sides (i-1, i) and (i, i+1) seen from p */
            const double *u = x + 2 * ((i + s + n) % n), *v = x + 2 * ((i + s + 1) % n);
            const double ux = u[0] - p[0], uy = u[1] - p[1], vx = v[0] - p[0], vy = v[1] - p[1];
            w += tan(0.5 * atan2(ux * vy - uy * vx, ux * vx + uy * vy));
        }
        sw += w / r;
        sz += w / r * z[i];
    }
    return fabs(sw) > 0 ? sz / sw : 0.0;
}

/* Whether p (collinear with a, b) lies in their box. */
static int on_seg(const double *a, const double *b, const double *p)
{
    return fmin(a[0], b[0]) <= p[0] && p[0] <= fmax(a[0], b[0]) && fmin(a[1], b[1]) <= p[1] && p[1] <= fmax(a[1], b[1]);
}

/* Whether segments a b and c d cross or touch. */
static int seg_cross(const double *a, const double *b, const double *c, const double *d)
{
    const double d1 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    const double d2 = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
    const double d3 = (d[0] - c[0]) * (a[1] - c[1]) - (d[1] - c[1]) * (a[0] - c[0]);
    const double d4 = (d[0] - c[0]) * (b[1] - c[1]) - (d[1] - c[1]) * (b[0] - c[0]);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 1;
    return (d1 == 0 && on_seg(a, b, c)) || (d2 == 0 && on_seg(a, b, d)) || (d3 == 0 && on_seg(c, d, a)) ||
           (d4 == 0 && on_seg(c, d, b));
}

/* Whether polygon x (n points) is simple and counter-clockwise. */
static int simple_ccw(const double *x, int n)
{
    double area = 0.0;
    for (int i = 0; i < n; i++) {
        const double *a = x + 2 * i, *b = x + 2 * ((i + 1) % n);
        area += a[0] * b[1] - a[1] * b[0];
    }
    if (!(area > 0)) return 0;
    for (int i = 0; i < n; i++)
        for (int j = i + 2; j < n; j++) {
            if (i == 0 && j == n - 1) continue;
            if (seg_cross(x + 2 * i, x + 2 * ((i + 1) % n), x + 2 * j, x + 2 * ((j + 1) % n))) return 0;
        }
    return 1;
}

/* The chart of loop (n points): the plane (centre o, axes e1, e2, normal N),
 * the loop's plane points xy and heights z. 0 when it is not a chart. */
static int chart(const lrep *L, const int *loop, int n, double *o, double *e, double *xy, double *z)
{
    double *N = e + 6;
    o[0] = o[1] = o[2] = N[0] = N[1] = N[2] = 0.0;
    for (int i = 0; i < n; i++) {
        const double *a = pos(L, loop[i]), *b = pos(L, loop[(i + 1) % n]);
        double x[3];
        cross3(a, b, x);
        for (int d = 0; d < 3; d++) {
            N[d] += 0.5 * x[d];
            o[d] += a[d] / n;
        }
    }
    const double nn = sqrt(dot3(N, N));
    if (!(nn > 0)) return 0;
    for (int d = 0; d < 3; d++) N[d] /= nn;
    for (int i = 0; i < n; i++) { /* the surface under each loop point along N */
        double x[3];
        const int t = glpgp_qs_proj_nearest(L->P, pos(L, loop[i]), x);
        if (t < 0 || dot3(N, L->m->surf->tframe + 9 * t + 6) < LR_NORMAL) return 0;
    }
    double *e1 = e, *e2 = e + 3;
    const double a[3] = {fabs(N[0]) < 0.6 ? 1.0 : 0.0, fabs(N[0]) < 0.6 ? 0.0 : 1.0, 0.0};
    cross3(N, a, e1);
    const double l1 = sqrt(dot3(e1, e1));
    for (int d = 0; d < 3; d++) e1[d] /= l1;
    cross3(N, e1, e2);
    for (int i = 0; i < n; i++) {
        double d[3];
        sub3(pos(L, loop[i]), o, d);
        xy[2 * i] = dot3(d, e1);
        xy[2 * i + 1] = dot3(d, e2);
        z[i] = dot3(d, N);
    }
    return simple_ccw(xy, n);
}

static int cmp_ll(const void *pa, const void *pb)
{
    const long long *a = pa, *b = pb;
    return *a < *b ? -1 : *a > *b ? 1 : 0;
}

/* Whether the quads' (local ids, nq) unmatched sides are exactly the loop's
 * sides 0 -> 1 -> ... -> n-1 -> 0, each once. */
static glpgp_status conforming(const int *quads, int nq, int n, int np, int *ok)
{
    long long *k = NULL;
    *ok = 0;
    GLPGP_CHECK(glpgp_malloc((size_t)4 * nq + 1, sizeof(long long), &k));
    for (int i = 0; i < 4 * nq; i++) {
        const long long a = quads[i], b = quads[i - i % 4 + (i % 4 + 1) % 4];
        k[i] = a * np + b;
    }
    qsort(k, (size_t)4 * nq, sizeof *k, cmp_ll);
    int unmatched = 0, good = 1;
    for (int i = 0; i < 4 * nq && good; i++) {
        const long long a = k[i] / np, b = k[i] % np, rev = b * np + a;
        if (i > 0 && k[i] == k[i - 1]) good = 0; /* a side twice in one direction */
        if (bsearch(&rev, k, (size_t)4 * nq, sizeof *k, cmp_ll)) continue;
        unmatched++;
        if (!(a < n && b == (a + 1) % n)) good = 0;
    }
    *ok = good && unmatched == n;
    free(k);
    return GLPGP_OK;
}

/* ---- the disk chart: the loop on a circle by 3D arc length (the disk as
 * large as the region's faces, at most the loop's circle), the new points
 * lifted by the mean-value interpolation of the loop's 3D points (positive
 * weights on a convex loop) ---- */

/* The loop's points on the circle (uv, 2 n). */
static void disk_chart(const lrep *L, int k, const int *loop, int n, double *uv, double *acc)
{
    double len = 0.0, area = 0.0;
    for (int i = 0; i < n; i++) {
        double d[3];
        acc[i] = len;
        sub3(pos(L, loop[(i + 1) % n]), pos(L, loop[i]), d);
        len += sqrt(dot3(d, d));
    }
    for (int i = L->cs[k]; i < L->cs[k + 1]; i++) {
        double N[3];
        glpgp_quadmesh_face_normal(L->q, L->cf[i], 0, N);
        area += 0.5 * sqrt(dot3(N, N));
    }
    const double R = fmin(len / (2.0 * GLPGP_PI), sqrt(area / GLPGP_PI));
    for (int i = 0; i < n; i++) {
        uv[2 * i] = R * cos(2.0 * GLPGP_PI * acc[i] / len);
        uv[2 * i + 1] = R * sin(2.0 * GLPGP_PI * acc[i] / len);
    }
}

/* ---- one region meshed in a chart ---------------------------------------------------- */

/* A chart of a region: the plane (kind 0: o, e, z), the disk (1: uv, the
 * loop's coordinates in p3), the patch chart (2) or the conformal one (3):
 * uv the loop's points, tri / tuv / vid the region's faces in it. */
typedef struct lchart {
    int kind;
    double o[3], e[9], *z, *uv, *p3;
    int nt, *tri;   /* kind 2: the region's faces fanned into triangles (region point ids) */
    double *tuv;    /* their points' Tutte positions in the disk */
    const int *vid; /* their points' ids */
} lchart;

/* ---- the patch chart: the region's own faces (fanned into triangles)
 * embedded in the disk by Tutte's barycentric map (the loop on the circle,
 * every inner point the mean of its neighbours: one-to-one onto the disk
 * for the planar graph of a disk), a new point lifted by its barycentric
 * coordinates in the triangle of the embedding that holds it onto the
 * region's old faces, then onto the surface: the new mesh follows the
 * faces it replaces, around a handle too, where the loop's own points
 * (the disk chart) do not tell which way the surface goes ---- */

static int cmp_int(const void *pa, const void *pb)
{
    const int a = *(const int *)pa, b = *(const int *)pb;
    return a < b ? -1 : a > b;
}

static int local_id(const int *vid, int nvl, int v)
{
    const int *p = bsearch(&v, vid, (size_t)nvl, sizeof *vid, cmp_int);
    return p ? (int)(p - vid) : -1;
}

/* The embedding's sweeps (Gauss-Seidel on the uniform Laplacian; fixed: the loop). */
static void tutte_sweeps(const int *adj_s, const int *adj, const unsigned char *fixed, int nvl, double *uv)
{
    for (int it = 0; it < 4000; it++) {
        double moved = 0.0;
        for (int i = 0; i < nvl; i++) {
            if (fixed[i] || adj_s[i + 1] == adj_s[i]) continue;
            double x = 0.0, y = 0.0;
            const int d = adj_s[i + 1] - adj_s[i];
            for (int k = adj_s[i]; k < adj_s[i + 1]; k++) {
                x += uv[2 * adj[k]] / d;
                y += uv[2 * adj[k] + 1] / d;
            }
            moved = fmax(moved, fabs(x - uv[2 * i]) + fabs(y - uv[2 * i + 1]));
            uv[2 * i] = x;
            uv[2 * i + 1] = y;
        }
        if (moved < 1e-12) break;
    }
}

/* Region k's patch chart in C (kind 2; C->uv: the loop on the circle);
 * *ok 0 when the loop is not made of the region's points. */
static glpgp_status patch_chart(const lrep *L, int k, const int *loop, int n, lchart *C, int **vid_out, int *ok)
{
    const glpgp_quadmesh *q = L->q;
    int nvl = 0, nc = 0, *vid = NULL, *adj_s = NULL, *adj = NULL;
    unsigned char *fixed = NULL;
    *ok = 0;
    for (int i = L->cs[k]; i < L->cs[k + 1]; i++) nc += q->face_start[L->cf[i] + 1] - q->face_start[L->cf[i]];
    glpgp_status st = glpgp_malloc((size_t)nc + 1, sizeof(int), &vid);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)nc + 2, sizeof(int), &adj_s);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)2 * nc + 1, sizeof(int), &adj);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)nc + 1, 1, &fixed);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)3 * nc + 1, sizeof(int), &C->tri);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)2 * nc + 2, sizeof(double), &C->tuv);
    if (st != GLPGP_OK) goto done;
    for (int i = L->cs[k]; i < L->cs[k + 1]; i++)
        for (int c = q->face_start[L->cf[i]]; c < q->face_start[L->cf[i] + 1]; c++) vid[nvl++] = q->face_vert[c];
    qsort(vid, (size_t)nvl, sizeof *vid, cmp_int);
    int u = 0;
    for (int i = 0; i < nvl; i++)
        if (i == 0 || vid[i] != vid[i - 1]) vid[u++] = vid[i];
    nvl = u;
    for (int i = 0; i < n; i++) {
        const int l = local_id(vid, nvl, loop[i]);
        if (l < 0) goto done; /* a point added on a boundary side */
        fixed[l] = 1;
        C->tuv[2 * l] = C->uv[2 * i];
        C->tuv[2 * l + 1] = C->uv[2 * i + 1];
    }
    for (int pass = 0; pass < 2; pass++) /* the neighbours (each face side both ways): counts, then lists */
        for (int i = L->cs[k]; i < L->cs[k + 1]; i++) {
            const int s = q->face_start[L->cf[i]], m = q->face_start[L->cf[i] + 1] - s;
            for (int j = 0; j < m; j++) {
                const int a = local_id(vid, nvl, q->face_vert[s + j]), b = local_id(vid, nvl, q->face_vert[s + (j + 1) % m]);
                if (pass == 0) {
                    adj_s[a + 2]++;
                    adj_s[b + 2]++;
                } else {
                    adj[adj_s[a + 1]++] = b;
                    adj[adj_s[b + 1]++] = a;
                }
            }
            if (pass == 0 && i + 1 == L->cs[k + 1])
                for (int v = 0; v < nvl; v++) adj_s[v + 2] += adj_s[v + 1];
        }
    tutte_sweeps(adj_s, adj, fixed, nvl, C->tuv);
    C->nt = 0;
    for (int i = L->cs[k]; i < L->cs[k + 1]; i++) {
        const int s = q->face_start[L->cf[i]], m = q->face_start[L->cf[i] + 1] - s;
        for (int j = 1; j + 1 < m; j++, C->nt++) {
            C->tri[3 * C->nt] = local_id(vid, nvl, q->face_vert[s]);
            C->tri[3 * C->nt + 1] = local_id(vid, nvl, q->face_vert[s + j]);
            C->tri[3 * C->nt + 2] = local_id(vid, nvl, q->face_vert[s + j + 1]);
        }
    }
    C->vid = vid;
    *vid_out = vid;
    vid = NULL;
    *ok = 1;
done:
    free(vid);
    free(adj_s);
    free(adj);
    free(fixed);
    return st;
}

/* Point p of the disk lifted through the patch chart onto the old faces (x). */
static void patch_lift(const lrep *L, const lchart *C, const double *p, double *x)
{
    double best = -INFINITY, bw[3] = {1, 0, 0};
    int bt = 0;
    for (int t = 0; t < C->nt; t++) {
        const double *a = C->tuv + 2 * C->tri[3 * t], *b = C->tuv + 2 * C->tri[3 * t + 1], *c = C->tuv + 2 * C->tri[3 * t + 2];
        const double det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if (!(fabs(det) > 0)) continue;
        const double w1 = ((p[0] - a[0]) * (c[1] - a[1]) - (p[1] - a[1]) * (c[0] - a[0])) / det;
        const double w2 = ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])) / det;
        const double w0 = 1.0 - w1 - w2, mn = fmin(w0, fmin(w1, w2));
        if (mn > best) {
            best = mn;
            bt = t;
            bw[0] = w0;
            bw[1] = w1;
            bw[2] = w2;
        }
        if (mn >= 0) break;
    }
    for (int d = 0; d < 3; d++) {
        x[d] = 0.0;
        for (int j = 0; j < 3; j++) x[d] += bw[j] * pos(L, C->vid[C->tri[3 * bt + j]])[d];
    }
}

/* ---- the conformal chart: the region's own faces (fanned into triangles)
 * flattened by the least-squares conformal map (Levy et al. 2002: per
 * triangle A |df/dzbar|^2 summed, two loop points pinned at their 3D
 * distance, the boundary free), the new points lifted as in the patch
 * chart. Unlike the circle, it keeps the loop's corners: a reflex corner
 * of the region stays reflex, where the circle makes every loop point
 * convex and the quads at a reflex one fold when lifted ---- */

/* Per fan triangle t: the complex sides opposite its corners in its own
 * plane (e[6 t + 2 j], e[6 t + 2 j + 1]) and the weight 1 / (16 area) (w[t];
 * 0: degenerate). */
static void lscm_sides(const lrep *L, const lchart *C, double *e, double *w)
{
    for (int t = 0; t < C->nt; t++) {
        const double *a = pos(L, C->vid[C->tri[3 * t]]), *b = pos(L, C->vid[C->tri[3 * t + 1]]),
                     *c = pos(L, C->vid[C->tri[3 * t + 2]]);
        double ab[3], ac[3], n[3];
        sub3(b, a, ab);
        sub3(c, a, ac);
        cross3(ab, ac, n);
        const double lab = sqrt(dot3(ab, ab)), a2 = sqrt(dot3(n, n));
        w[t] = 0.0;
        for (int j = 0; j < 6; j++) e[6 * t + j] = 0.0;
        if (!(lab > 0) || !(a2 > 1e-12 * L->h * L->h)) continue;
        const double P[3][2] = {{0.0, 0.0}, {lab, 0.0}, {dot3(ab, ac) / lab, a2 / lab}};
        for (int j = 0; j < 3; j++) {
            const double *p = P[(j + 1) % 3], *q = P[(j + 2) % 3];
            e[6 * t + 2 * j] = q[0] - p[0];
            e[6 * t + 2 * j + 1] = q[1] - p[1];
        }
        w[t] = 1.0 / (8.0 * a2); /* 1 / (16 area) */
    }
}

/* y <- H x, the conformal energy's Hessian (x: u, v per point, 2 nvl). */
static void lscm_apply(const lchart *C, const double *e, const double *w, int nvl, const double *x, double *y)
{
    for (int i = 0; i < 2 * nvl; i++) y[i] = 0.0;
    for (int t = 0; t < C->nt; t++) {
        if (w[t] == 0.0) continue;
        const int *tv = C->tri + 3 * t;
        double r1 = 0.0, r2 = 0.0;
        for (int j = 0; j < 3; j++) {
            const double a = e[6 * t + 2 * j], b = e[6 * t + 2 * j + 1], u = x[2 * tv[j]], v = x[2 * tv[j] + 1];
            r1 += a * u - b * v;
            r2 += b * u + a * v;
        }
        for (int j = 0; j < 3; j++) {
            const double a = e[6 * t + 2 * j], b = e[6 * t + 2 * j + 1];
            y[2 * tv[j]] += 2.0 * w[t] * (r1 * a + r2 * b);
            y[2 * tv[j] + 1] += 2.0 * w[t] * (-r1 * b + r2 * a);
        }
    }
}

/* The conformal map by CG on the free points (pinned: fix[i] set, their
 * values in x); x holds the start and gets the result. 0: not converged. */
static int lscm_solve(const lchart *C, const double *e, const double *w, int nvl, const unsigned char *fix,
                      double *x, double *wk)
{
    double *r = wk, *d = wk + 2 * nvl, *q = wk + 4 * nvl;
    const int m = 2 * nvl;
    lscm_apply(C, e, w, nvl, x, q);
    double rr = 0.0, r0;
    for (int i = 0; i < m; i++) {
        r[i] = fix[i / 2] ? 0.0 : -q[i];
        d[i] = r[i];
        rr += r[i] * r[i];
    }
    r0 = rr;
    for (int it = 0; it < 20 * m + 100 && rr > 1e-24 * r0 && rr > 0; it++) {
        lscm_apply(C, e, w, nvl, d, q);
        double dq = 0.0;
        for (int i = 0; i < m; i++) {
            if (fix[i / 2]) q[i] = 0.0;
            dq += d[i] * q[i];
        }
        if (!(dq > 0)) return 0;
        const double al = rr / dq;
        double rn = 0.0;
        for (int i = 0; i < m; i++) {
            x[i] += al * d[i];
            r[i] -= al * q[i];
            rn += r[i] * r[i];
        }
        for (int i = 0; i < m; i++) d[i] = r[i] + rn / rr * d[i];
        rr = rn;
    }
    return rr <= 1e-16 * r0;
}

/* The region's points in a patch chart C (its faces' points; every one is
 * a corner of a fan triangle). */
static int chart_points(const lchart *C)
{
    int nvl = 0;
    for (int t = 0; t < 3 * C->nt; t++) nvl = C->tri[t] + 1 > nvl ? C->tri[t] + 1 : nvl;
    return nvl;
}

/* The patch chart C (its Tutte map in C->tuv: the start) made the
 * conformal chart (kind 3; C->tuv the conformal map, C->uv the loop's
 * points in it, a simple counter-clockwise polygon); *ok 0 when it is not
 * one (C->tuv then holds no map to use). */
static glpgp_status conformal_map(const lrep *L, const int *loop, int n, lchart *C, int *ok)
{
    const int nvl = chart_points(C);
    double *e = NULL, *w = NULL, *wk = NULL;
    unsigned char *fix = NULL;
    *ok = 0;
    glpgp_status st = glpgp_malloc((size_t)6 * C->nt + 1, sizeof(double), &e);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)C->nt + 1, sizeof(double), &w);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)6 * nvl + 1, sizeof(double), &wk);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)nvl + 1, 1, &fix);
    if (st != GLPGP_OK) goto done;
    lscm_sides(L, C, e, w);
    /* the pins: loop point 0 and the loop point farthest from it in 3D */
    int far = 0;
    double dfar = -1.0;
    for (int i = 1; i < n; i++) {
        double d[3];
        sub3(pos(L, loop[i]), pos(L, loop[0]), d);
        if (dot3(d, d) > dfar) {
            dfar = dot3(d, d);
            far = i;
        }
    }
    const int l0 = local_id(C->vid, nvl, loop[0]), l1 = local_id(C->vid, nvl, loop[far]);
    if (l0 < 0 || l1 < 0 || l0 == l1 || !(dfar > 0)) goto done;
    /* the start: the Tutte map turned and scaled so the pins sit where they are pinned */
    const double *p0 = C->tuv + 2 * l0, *p1 = C->tuv + 2 * l1;
    const double dx = p1[0] - p0[0], dy = p1[1] - p0[1], dd = dx * dx + dy * dy, D = sqrt(dfar);
    if (!(dd > 0)) goto done;
    const double cr = D * dx / dd, ci = -D * dy / dd, ox = p0[0], oy = p0[1]; /* z -> (z - p0) D conj(p1 - p0) / |p1 - p0|^2 */
    for (int l = 0; l < nvl; l++) {
        const double x = C->tuv[2 * l] - ox, y = C->tuv[2 * l + 1] - oy;
        C->tuv[2 * l] = cr * x - ci * y;
        C->tuv[2 * l + 1] = ci * x + cr * y;
    }
    C->tuv[2 * l0] = C->tuv[2 * l0 + 1] = 0.0;
    C->tuv[2 * l1] = D;
    C->tuv[2 * l1 + 1] = 0.0;
    fix[l0] = fix[l1] = 1;
    if (!lscm_solve(C, e, w, nvl, fix, C->tuv, wk)) goto done;
    for (int i = 0; i < n; i++) { /* every loop point is a region point (patch_chart) */
        const int l = local_id(C->vid, nvl, loop[i]);
        C->uv[2 * i] = C->tuv[2 * l];
        C->uv[2 * i + 1] = C->tuv[2 * l + 1];
    }
    *ok = simple_ccw(C->uv, n);
done:
    free(e);
    free(w);
    free(wk);
    free(fix);
    return st;
}

/* The quads of the cut mesher on the loop's chart points xy (n, then the
 * new ones); *ok 0 when it failed. */
static glpgp_status cut_loop(const lrep *L, dvec *xy, int n, ivec *quads, int *ok)
{
    ivec ls = {0}, lv = {0}, ow = {0};
    *ok = 0;
    glpgp_status st = ipush(&ls, 0);
    if (st == GLPGP_OK) st = ipush(&ls, n);
    if (st == GLPGP_OK) st = ipush(&ow, -1);
    for (int i = 0; i < n && st == GLPGP_OK; i++) st = ipush(&lv, i);
    qcut_stats qs;
    /* bounded work: the cut searches (each about the piece's points
     * squared) within LR_WORK per region and what is left of LR_WORK_ALL
     * (a grown region of 500 loop points with sides of h / 1000 searched for
     * minutes); a region over it fails and grows or is left to the fallbacks */
    qcut_region QR = {1, ls.p, lv.p, ow.p, fmin(LR_WORK, *L->work_left)};
    if (st == GLPGP_OK && !(*L->work_left > 0.0))
        st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "the repair's work bound is spent");
    if (st == GLPGP_OK) {
        memset(&qs, 0, sizeof qs);
        st = glpgp_qcut_mesh(xy, &QR, L->h, quads, &qs);
        *L->work_left -= qs.work;
    }
    if (st == GLPGP_ERR_NUMERIC) {
        glpgp_log(GLPGP_LOG_DEBUG, "quads: surface local repair: %s", glpgp_error_message());
        glpgp_error_clear();
        st = GLPGP_OK;
    } else if (st == GLPGP_OK && quads->n) {
        st = conforming(quads->p, quads->n / 4, n, xy->n / 2, ok);
        if (st == GLPGP_OK && !*ok) glpgp_log(GLPGP_LOG_DEBUG, "quads: surface local repair: quads not on the loop");
    }
    ivec_free(&ls);
    ivec_free(&lv);
    ivec_free(&ow);
    return st;
}

/* The worst corner of nq quads (ids), each in its own plane. */
static double worst_sj(const lrep *L, const int *quads, int nq)
{
    const glpgp_qs_pts S = points(L);
    return glpgp_qs_worst_sj(L->P, &S, quads, nq);
}

/* Laplacian sweeps (at most LR_UNTANGLE) on the region's new points (ids
 * from first on), each moved to its nearest point on the surface, while a
 * corner is at or below LR_SJ_NEW (glpgp_qs_untangle); mends a lift that
 * tangled a few corners (a chart a little off the surface). Returns the
 * worst corner after. */
static glpgp_status untangle(lrep *L, const int *quads, int nq, int first, double *worst)
{
    const glpgp_qs_pts S = points(L);
    return glpgp_qs_untangle(L->P, &S, first, quads, nq, LR_UNTANGLE, LR_SJ_NEW, worst);
}

/* The cut mesher's quads of the loop in chart C, the new points lifted onto
 * the surface (into L->nxyz), checked in 3D; see mesh_loop. */
static glpgp_status mesh_in_chart(lrep *L, const int *loop, int n, lchart *C, ivec *out, double *sjmin, int *ok)
{
    dvec xy = {0};
    ivec quads = {0}, gid = {0};
    *ok = 0;
    glpgp_status st = GLPGP_OK;
    for (int i = 0; i < n && st == GLPGP_OK; i++) {
        st = dpush(&xy, C->kind ? C->uv[2 * i] : 0.0);
        if (st == GLPGP_OK) st = dpush(&xy, C->kind ? C->uv[2 * i + 1] : 0.0);
    }
    if (st == GLPGP_OK && !C->kind && !chart(L, loop, n, C->o, C->e, xy.p, C->z)) goto done;
    const int first = L->q->nv + L->nxyz.n / 3; /* the region's new points' first id */
    int cut = 0;
    if (st == GLPGP_OK) st = cut_loop(L, &xy, n, &quads, &cut);
    if (st != GLPGP_OK || !cut) goto done;
    for (int i = 0; i < xy.n / 2 && st == GLPGP_OK; i++) { /* the new points lifted onto the surface */
        if (i < n) {
            st = ipush(&gid, loop[i]);
            continue;
        }
        const double *p = xy.p + 2 * i;
        double x[3], y[3];
        if (C->kind >= 2) {
            patch_lift(L, C, p, x);
        } else if (C->kind) {
            for (int d = 0; d < 3; d++) x[d] = mvc(xy.p, C->p3 + d * n, n, p);
        } else {
            const double hz = mvc(xy.p, C->z, n, p);
            for (int d = 0; d < 3; d++) x[d] = C->o[d] + p[0] * C->e[d] + p[1] * C->e[3 + d] + hz * C->e[6 + d];
        }
        glpgp_qs_proj_nearest(L->P, x, y);
        st = ipush(&gid, L->q->nv + L->nxyz.n / 3);
        for (int d = 0; d < 3 && st == GLPGP_OK; d++) st = dpush(&L->nxyz, y[d]);
    }
    if (st != GLPGP_OK) goto done;
    for (int k = 0; k < quads.n; k++) quads.p[k] = gid.p[quads.p[k]];
    double worst = worst_sj(L, quads.p, quads.n / 4);
    if (!(worst > LR_SJ_NEW) && worst > LR_SJ_TANGLED) st = untangle(L, quads.p, quads.n / 4, first, &worst);
    if (st == GLPGP_OK && !(worst > LR_SJ_NEW)) {
        glpgp_log(GLPGP_LOG_DEBUG, "quads: surface local repair: %d quads in the %s chart, scaled Jacobian %.3f on the surface",
                  quads.n / 4, C->kind == 3 ? "conformal" : C->kind == 2 ? "patch" : C->kind ? "disk" : "plane", worst);
        goto done;
    }
    for (int k = 0; k < quads.n && st == GLPGP_OK; k++) st = ipush(out, quads.p[k]);
    *sjmin = worst;
    *ok = st == GLPGP_OK;
done:
    dvec_free(&xy);
    ivec_free(&quads);
    ivec_free(&gid);
    return st;
}

/* Region k's loop (n ids, even) meshed in the plane chart, else in the
 * conformal chart, else in the disk chart, else in the patch chart: its quads (ids) appended to out, new points into L->nxyz;
 * *sjmin their worst corner; *ok 0 when both failed (nothing added). */
static glpgp_status mesh_loop(lrep *L, int k, const int *loop, int n, ivec *out, double *sjmin, int *ok)
{
    lchart C;
    memset(&C, 0, sizeof C);
    const int nx0 = L->nxyz.n;
    *ok = 0;
    glpgp_status st = glpgp_malloc((size_t)n + 1, sizeof(double), &C.z);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)2 * n + 2, sizeof(double), &C.uv);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)3 * n + 3, sizeof(double), &C.p3);
    if (st == GLPGP_OK) st = mesh_in_chart(L, loop, n, &C, out, sjmin, ok);
    int *vid = NULL, pok = 0;
    double *tutte = NULL; /* the patch chart's map, kept while the conformal chart overwrites it */
    if (st == GLPGP_OK && !*ok) { /* the region's faces embedded once (the loop on the circle) */
        disk_chart(L, k, loop, n, C.uv, C.z);
        st = patch_chart(L, k, loop, n, &C, &vid, &pok);
        if (st == GLPGP_OK && pok) st = glpgp_malloc((size_t)2 * chart_points(&C) + 2, sizeof(double), &tutte);
        if (st == GLPGP_OK && pok) memcpy(tutte, C.tuv, (size_t)2 * chart_points(&C) * sizeof(double));
    }
    if (st == GLPGP_OK && !*ok && pok) { /* the conformal chart: the region's faces flattened, the loop's corners kept */
        int cok = 0;
        L->nxyz.n = nx0;
        C.kind = 3;
        st = conformal_map(L, loop, n, &C, &cok);
        if (st == GLPGP_OK && cok) st = mesh_in_chart(L, loop, n, &C, out, sjmin, ok);
    }
    if (st == GLPGP_OK && !*ok) {
        L->nxyz.n = nx0;
        C.kind = 1;
        disk_chart(L, k, loop, n, C.uv, C.z);
        for (int i = 0; i < n; i++)
            for (int d = 0; d < 3; d++) C.p3[d * n + i] = pos(L, loop[i])[d];
        st = mesh_in_chart(L, loop, n, &C, out, sjmin, ok);
    }
    if (st == GLPGP_OK && !*ok && pok) { /* the patch chart: the disk's points lifted onto the region's own faces */
        L->nxyz.n = nx0;
        C.kind = 2;
        memcpy(C.tuv, tutte, (size_t)2 * chart_points(&C) * sizeof(double));
        st = mesh_in_chart(L, loop, n, &C, out, sjmin, ok);
    }
    free(vid);
    free(tutte);
    free(C.tri);
    free(C.tuv);
    if (!*ok) L->nxyz.n = nx0;
    free(C.z);
    free(C.uv);
    free(C.p3);
    return st;
}

/* ---- the rounds -------------------------------------------------------------------- */

/* Region k's worst corner and size noted in the report. */
static void note(glpgp_quads_repair *rs, const lrep *L, int k, const int *quads, int nq, double sj, int round)
{
    glpgp_quads_region g = {L->cs[k + 1] - L->cs[k], nq, sj, 0.0, 0.0, {INFINITY, INFINITY, -INFINITY, -INFINITY},
                            GLPGP_QFACE_PAVED, round};
    for (int i = 0; i < 4 * nq; i++) {
        const double *p = pos(L, quads[i]);
        g.x += p[0] / (4 * nq);
        g.y += p[1] / (4 * nq);
        g.box[0] = fmin(g.box[0], p[0]);
        g.box[1] = fmin(g.box[1], p[1]);
        g.box[2] = fmax(g.box[2], p[0]);
        g.box[3] = fmax(g.box[3], p[1]);
    }
    rs->regions++;
    rs->paved_regions++;
    rs->removed_faces += g.faces_in;
    rs->new_quads += nq;
    if (rs->nlisted < GLPGP_QUADS_REGIONS_LISTED) {
        rs->region[rs->nlisted++] = g;
        return;
    }
    int w = 0; /* full: the worst kept, the best listed one replaced */
    for (int i = 1; i < rs->nlisted; i++)
        if (rs->region[i].sj_min > rs->region[w].sj_min) w = i;
    if (sj < rs->region[w].sj_min) rs->region[w] = g;
}

/* Region k's loop with one new point on its longest side on the surface's
 * boundary (position b), moved onto the surface. */
static glpgp_status split_boundary_side(lrep *L, ivec *loop, int b)
{
    const double *a = pos(L, loop->p[b]), *c = pos(L, loop->p[(b + 1) % loop->n]);
    const double mid[3] = {0.5 * (a[0] + c[0]), 0.5 * (a[1] + c[1]), 0.5 * (a[2] + c[2])};
    double x[3];
    glpgp_qs_proj_nearest(L->P, mid, x);
    const int id = L->q->nv + L->nxyz.n / 3;
    for (int d = 0; d < 3; d++) GLPGP_CHECK(dpush(&L->nxyz, x[d]));
    GLPGP_CHECK(ipush(loop, 0));
    memmove(loop->p + b + 2, loop->p + b + 1, (size_t)(loop->n - b - 2) * sizeof(int));
    loop->p[b + 1] = id;
    return GLPGP_OK;
}

/* The regions' shapes: *grown 1 when one was not a disk (grown by a ring)
 * or odd ones were joined; *fail 1 when an odd one has no partner. */
static glpgp_status shape_regions(lrep *L, unsigned char *sel, ivec *loop, int *grown, int *fail)
{
    const glpgp_quadmesh *q = L->q;
    unsigned char *odd = NULL;
    *grown = *fail = 0;
    GLPGP_CHECK(glpgp_calloc((size_t)q->nf + 1, 1, &odd)); /* regions split in two add to ncomp */
    glpgp_status st = GLPGP_OK;
    int nodd = 0;
    memset(sel, 0, (size_t)q->nf);
    for (int k = 0; k < L->ncomp && st == GLPGP_OK; k++) {
        int bnd, disk, split = 0;
        st = region_loop(L, k, loop, &bnd, &disk);
        if (st == GLPGP_OK && !disk) st = split_annulus(L, k, loop, &split);
        if (st == GLPGP_OK && split) st = region_loop(L, k, loop, &bnd, &disk);
        if (st == GLPGP_OK && !disk) {
            st = region_fix(L, k, sel);
            *grown = 1;
        } else if (st == GLPGP_OK && loop->n % 2 && bnd < 0) {
            odd[k] = 1;
            nodd++;
        }
    }
    for (int f = 0; f < q->nf && *grown; f++) L->in[f] |= sel[f];
    const int fixed = *grown; /* regions grown to disks: the odd ones joined next time */
    for (int k = 0; k < L->ncomp && st == GLPGP_OK && !fixed && nodd; k++) { /* every odd region joined */
        if (!odd[k]) continue;
        int found = 0;
        st = join_odd(L, k, odd, &found);
        if (st == GLPGP_OK && !found) *fail = 1;
        if (st == GLPGP_OK && found) *grown = 1;
        odd[k] = 0;
        for (int j = 0; j < L->ncomp; j++) /* a partner reached by the path is even now */
            for (int i = L->cs[j]; i < L->cs[j + 1] && odd[j]; i++)
                for (int c = q->face_start[L->cf[i]]; c < q->face_start[L->cf[i] + 1]; c++) {
                    const int t = L->twin[c];
                    if (t >= 0 && L->in[L->cface[t]] && L->comp[L->cface[t]] != j) odd[j] = 0;
                }
    }
    free(odd);
    return st;
}

/* Every region meshed (*done 1; quads: the new quads), or the ones that
 * failed grown by a ring (*done 0). */
static glpgp_status mesh_regions(lrep *L, int round, unsigned char *sel, ivec *loop, ivec *quads,
                                 glpgp_quads_repair *rs, int *done)
{
    const glpgp_quadmesh *q = L->q;
    int failed = 0;
    *done = 0;
    quads->n = 0;
    L->nxyz.n = 0;
    memset(rs, 0, sizeof *rs);
    memset(sel, 0, (size_t)q->nf);
    for (int k = 0; k < L->ncomp; k++) {
        int bnd, disk, ok = 0;
        double sj = 0.0;
        const int q0 = quads->n;
        glpgp_progress_poll();
        GLPGP_CHECK(region_loop(L, k, loop, &bnd, &disk));
        if (disk && loop->n % 2 && bnd >= 0) GLPGP_CHECK(split_boundary_side(L, loop, bnd));
        if (disk && loop->n % 2 == 0) GLPGP_CHECK(mesh_loop(L, k, loop->p, loop->n, quads, &sj, &ok));
        if (ok) {
            note(rs, L, k, quads->p + q0, (quads->n - q0) / 4, sj, round);
            continue;
        }
        failed = 1;
        for (int i = L->cs[k]; i < L->cs[k + 1]; i++) sel[L->cf[i]] = 1;
    }
    rs->rounds = round + 1;
    *done = !failed;
    return GLPGP_OK;
}

/* A round's regions that were meshed while others failed (sel): the
 * partial repair kept when no round meshes them all. */
typedef struct lpart {
    unsigned char *in; /* the faces removed (the meshed regions') */
    ivec quads;
    dvec nxyz;
    glpgp_quads_repair rs;
    int failed; /* faces of the failed regions (-1: none kept) */
} lpart;

/* The round's meshed regions kept in P when its failed regions are smaller than those kept before. */
static glpgp_status keep_part(const lrep *L, const unsigned char *sel, const ivec *quads, const glpgp_quads_repair *rs,
                              lpart *P)
{
    int failed = 0;
    for (int f = 0; f < L->q->nf; f++) failed += sel[f];
    if (rs->regions == 0 || (P->failed >= 0 && failed >= P->failed)) return GLPGP_OK;
    if (!P->in) GLPGP_CHECK(glpgp_malloc((size_t)L->q->nf + 1, 1, &P->in));
    for (int f = 0; f < L->q->nf; f++) P->in[f] = L->in[f] && !sel[f];
    P->quads.n = P->nxyz.n = 0;
    for (int k = 0; k < quads->n; k++) GLPGP_CHECK(ipush(&P->quads, quads->p[k]));
    for (int k = 0; k < L->nxyz.n; k++) GLPGP_CHECK(dpush(&P->nxyz, L->nxyz.p[k]));
    P->rs = *rs;
    P->failed = failed;
    return GLPGP_OK;
}

/* The kept faces and the new quads as one mesh (unused points dropped). */
static glpgp_status assemble(const lrep *L, const ivec *quads, glpgp_quadmesh **out)
{
    const glpgp_quadmesh *q = L->q;
    const int nall = q->nv + L->nxyz.n / 3;
    int *id = NULL, nv = 0, nf = quads->n / 4, ncr = quads->n;
    GLPGP_CHECK(glpgp_malloc((size_t)nall + 1, sizeof(int), &id));
    for (int v = 0; v < nall; v++) id[v] = -1;
    for (int f = 0; f < q->nf; f++) {
        if (L->in[f]) continue;
        nf++;
        for (int c = q->face_start[f]; c < q->face_start[f + 1]; c++, ncr++)
            if (id[q->face_vert[c]] < 0) id[q->face_vert[c]] = nv++;
    }
    for (int k = 0; k < quads->n; k++)
        if (id[quads->p[k]] < 0) id[quads->p[k]] = nv++;
    glpgp_quadmesh *r = NULL;
    glpgp_status st = glpgp_qs_alloc(nv, nf, ncr, &r);
    if (st != GLPGP_OK) {
        free(id);
        return st;
    }
    for (int v = 0; v < nall; v++)
        if (id[v] >= 0) memcpy(r->xyz + 3 * id[v], pos(L, v), 3 * sizeof(double));
    int o = 0, w = 0;
    for (int f = 0; f < q->nf; f++) {
        if (L->in[f]) continue;
        r->face_start[o] = w;
        r->face_origin[o++] = q->face_origin ? q->face_origin[f] : GLPGP_QFACE_GRID;
        for (int c = q->face_start[f]; c < q->face_start[f + 1]; c++) r->face_vert[w++] = id[q->face_vert[c]];
    }
    for (int k = 0; k < quads->n; k += 4) {
        r->face_start[o] = w;
        r->face_origin[o++] = GLPGP_QFACE_PAVED;
        for (int c = 0; c < 4; c++) r->face_vert[w++] = id[quads->p[k + c]];
    }
    r->face_start[o] = w;
    glpgp_qs_finish_from(r, q);
    free(id);
    *out = r;
    return GLPGP_OK;
}

glpgp_status glpgp_qs_bad_faces(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, int far, unsigned char *bad,
                                int *nbad)
{
    lrep L;
    *nbad = 0;
    glpgp_status st = lrep_init(&L, m, q, h, far);
    if (st == GLPGP_OK)
        for (int f = 0; f < q->nf; f++) *nbad += bad[f] = L.bad[f];
    lrep_free(&L);
    return st;
}

glpgp_status glpgp_qs_local_repair(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, int far,
                                   glpgp_quadmesh **out, glpgp_quads_repair *rs)
{
    *out = NULL;
    memset(rs, 0, sizeof *rs);
    if (!q || !q->xyz || q->nf == 0) return GLPGP_OK;
    lrep L;
    ivec loop = {0}, quads = {0};
    unsigned char *sel = NULL;
    int nbad = 0, done = 0;
    double work_left = LR_WORK_ALL;
    const double t0 = glpgp_now();
    lpart part = {NULL, {0}, {0}, {0}, -1};
    glpgp_status st = lrep_init(&L, m, q, h, far);
    L.work_left = &work_left;
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)q->nf + 1, 1, &sel);
    if (st != GLPGP_OK) goto end;
    for (int f = 0; f < q->nf; f++) nbad += L.bad[f];
    glpgp_log(GLPGP_LOG_DEBUG, "quads: surface local repair: %d bad faces of %d", nbad, q->nf);
    if (nbad == 0) goto end;
    memcpy(L.in, L.bad, (size_t)q->nf);
    for (int round = 0; round < LR_ROUNDS && !done; round++) {
        int grown = 1, fail = 0;
        for (int k = 0; k < 2 * LR_ROUNDS && grown && !fail; k++) { /* disks, even boundaries */
            components(&L);
            if (L.cs[L.ncomp] > LR_SHARE * q->nf) fail = 1;
            else GLPGP_CHECK_GOTO(st, shape_regions(&L, sel, &loop, &grown, &fail), end);
        }
        if (fail || grown) {
            glpgp_log(GLPGP_LOG_DEBUG, "quads: surface local repair: %s (%d regions, %d faces)",
                      fail ? "not local" : "no disks", L.ncomp, L.cs[L.ncomp]);
            break;
        }
        GLPGP_CHECK_GOTO(st, mesh_regions(&L, round, sel, &loop, &quads, rs, &done), end);
        glpgp_log(GLPGP_LOG_DEBUG, "quads: surface local repair round %d: %d regions, %d faces%s", round, L.ncomp,
                  L.cs[L.ncomp], done ? "" : ", some grown");
        if (!done) GLPGP_CHECK_GOTO(st, keep_part(&L, sel, &quads, rs, &part), end);
        if (!done) GLPGP_CHECK_GOTO(st, grow_ring(&L, sel), end);
    }
    if (done) st = assemble(&L, &quads, out);
    else if (part.failed >= 0) { /* the meshed regions of the best round; the failed ones' faces kept */
        glpgp_log(GLPGP_LOG_DEBUG, "quads: surface local repair: partial, %d regions meshed, %d faces of failed regions kept",
                  part.rs.regions, part.failed);
        memcpy(L.in, part.in, (size_t)q->nf);
        dvec t = L.nxyz;
        L.nxyz = part.nxyz;
        part.nxyz = t;
        *rs = part.rs;
        st = assemble(&L, &part.quads, out);
    } else memset(rs, 0, sizeof *rs);
end:
    glpgp_log(GLPGP_LOG_DEBUG, "quads: surface local repair: cut mesher work %.3g of %.3g, %.2f s", LR_WORK_ALL - work_left,
              LR_WORK_ALL, glpgp_now() - t0);
    free(part.in);
    ivec_free(&part.quads);
    dvec_free(&part.nxyz);
    lrep_free(&L);
    ivec_free(&loop);
    ivec_free(&quads);
    free(sel);
    return st;
}
