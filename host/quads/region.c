/* quads/region.c: the regions the repair re-meshes (repair.h). Given the
 * kept faces K (every face not flagged), the region R = domain \ K is
 * built combinatorially: its boundary is
 *  - every edge of K with no K face on its other side, reversed, except a
 *    "covered chord": both ends on the same domain loop, consecutive among
 *    the K vertices on that loop in loop order, and the domain boundary
 *    between them within h/4 of the edge (K covers that piece of boundary,
 *    as the extraction made it);
 *  - every piece of domain loop between consecutive K vertices on it that no
 *    covered chord spans, and whole loops with no K vertex: through the
 *    input boundary vertices, simplified (Douglas-Peucker with 0.02 h, domain
 *    corners kept) and then divided at about the length of the K edges at
 *    the piece's ends (h for a whole loop), the new points on the input
 *    polyline;
 * joined into loops (at a vertex with several ways on, the first one
 * clockwise from the way back, so touching parts of R stay separate loops);
 * loops with positive area are outer loops, the others holes, put into the
 * smallest outer loop that contains them. */
#include "glpgp/internal/edgekey.h"
#include "repair.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define RG_PI 3.14159265358979323846

/* ---- the domain boundary ----------------------------------------------------- */

glpgp_status glpgp_dbnd_build(dbnd *D, const glpgp_mesh *m, double h)
{
    memset(D, 0, sizeof *D);
    D->m = m;
    D->nb = m->loop_start[m->nloops];
    double *box = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)D->nb + 1, sizeof(int), &D->loop_of));
    GLPGP_CHECK(glpgp_malloc((size_t)4 * D->nb + 4, sizeof(double), &box));
    for (int l = 0; l < m->nloops; l++) {
        int s = m->loop_start[l], n = m->loop_start[l + 1] - s;
        for (int i = 0; i < n; i++) {
            const double *a = m->xy + 2 * m->loop_vertices[s + i], *b = m->xy + 2 * m->loop_vertices[s + (i + 1) % n];
            box[4 * (s + i)] = fmin(a[0], b[0]);
            box[4 * (s + i) + 1] = fmin(a[1], b[1]);
            box[4 * (s + i) + 2] = fmax(a[0], b[0]);
            box[4 * (s + i) + 3] = fmax(a[1], b[1]);
            D->loop_of[s + i] = l;
        }
    }
    glpgp_status st = glpgp_bgrid_build(&D->G, box, D->nb, h);
    free(box);
    return st;
}

void glpgp_dbnd_free(dbnd *D)
{
    glpgp_bgrid_free(&D->G);
    free(D->loop_of);
    memset(D, 0, sizeof *D);
}

static const double *seg_a(const dbnd *D, int s) { return D->m->xy + 2 * D->m->loop_vertices[s]; }
static const double *seg_b(const dbnd *D, int s)
{
    const glpgp_mesh *m = D->m;
    int l = D->loop_of[s], n = m->loop_start[l + 1] - m->loop_start[l];
    return m->xy + 2 * m->loop_vertices[m->loop_start[l] + (s - m->loop_start[l] + 1) % n];
}

int glpgp_dbnd_nearest(dbnd *D, const double *p, double r, double *t, double *dist, double *proj, int **cand,
                       int *ncap)
{
    int n = glpgp_bgrid_query(&D->G, p[0] - r, p[1] - r, p[0] + r, p[1] + r, cand, ncap);
    int best = -1;
    double bd = INFINITY, bt = 0;
    for (int i = 0; i < n; i++) {
        double tt, d = glpgp_seg_dist(seg_a(D, (*cand)[i]), seg_b(D, (*cand)[i]), p, &tt);
        if (d < bd) {
            bd = d;
            best = (*cand)[i];
            bt = tt;
        }
    }
    if (best < 0 || bd > r) return -1;
    *t = bt;
    *dist = bd;
    const double *a = seg_a(D, best), *b = seg_b(D, best);
    proj[0] = a[0] + bt * (b[0] - a[0]);
    proj[1] = a[1] + bt * (b[1] - a[1]);
    return best;
}

/* ---- loop parameters ------------------------------------------------------------- */

/* Boundary position of a mesh vertex: segment seg (-1: not on the boundary), t. */
typedef struct bpos {
    int seg;
    double t;
} bpos;

static double bparam(const glpgp_mesh *m, const dbnd *D, bpos b)
{
    return (double)(b.seg - m->loop_start[D->loop_of[b.seg]]) + b.t;
}

/* Point of loop l at parameter p (segment floor(p), fraction). */
static void loop_point(const glpgp_mesh *m, int l, double p, double *out)
{
    int s = m->loop_start[l], n = m->loop_start[l + 1] - s;
    p = fmod(p, (double)n);
    if (p < 0) p += n;
    int i = (int)floor(p);
    if (i >= n) i = n - 1;
    double t = p - i;
    const double *a = m->xy + 2 * m->loop_vertices[s + i], *b = m->xy + 2 * m->loop_vertices[s + (i + 1) % n];
    out[0] = a[0] + t * (b[0] - a[0]);
    out[1] = a[1] + t * (b[1] - a[1]);
}

/* Forward distance in parameter from p0 to p1 on a loop of n segments. */
static double fwd(double p0, double p1, int n)
{
    double d = p1 - p0;
    while (d < 0) d += n;
    while (d >= n) d -= n;
    return d;
}

const double *glpgp_region_xy(const region *R, int v)
{
    return v < R->q->nv ? R->q->xy + 2 * v : R->vxy.p + 2 * (v - R->q->nv);
}

static glpgp_status add_he(region *R, int a, int b, int kind, int loop, double p0, double p1)
{
    if (R->nhe == R->cap) {
        int c = R->cap ? 2 * R->cap : 256;
        rhe *n = realloc(R->he, (size_t)c * sizeof *n);
        if (!n) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quad repair: out of memory");
        R->he = n;
        R->cap = c;
    }
    R->he[R->nhe++] = (rhe){a, b, kind, 0, p0, p1, loop};
    return GLPGP_OK;
}

static glpgp_status new_point(region *R, double x, double y, int *id)
{
    *id = R->q->nv + R->vxy.n / 2;
    GLPGP_CHECK(dpush(&R->vxy, x));
    return dpush(&R->vxy, y);
}

void glpgp_region_split_point(const region *R, const rhe *e, double *out)
{
    const glpgp_mesh *m = R->m;
    int n = m->loop_start[e->loop + 1] - m->loop_start[e->loop];
    double len = fwd(e->p0, e->p1, n), mid = e->p0 + 0.5 * len;
    double best = INFINITY, bp = mid;
    double first = ceil(e->p0);
    if (first == e->p0) first += 1.0;
    for (double p = first; p < e->p0 + len - 1e-12; p += 1.0)
        if (fabs(p - mid) < best) {
            best = fabs(p - mid);
            bp = p;
        }
    if (best > 0.25 * len) bp = mid;
    loop_point(m, e->loop, bp, out);
}

/* ---- domain boundary pieces ------------------------------------------------------------ */

/* The points of a piece: u, the input vertices strictly between, w; their
 * loop parameters (relative to pu) and cumulative lengths. */
typedef struct arcpts {
    ivec ids;  /* >= 0: region point; < 0: -1 - input vertex */
    dvec par, len;
} arcpts;

static void arcpts_free(arcpts *A)
{
    ivec_free(&A->ids);
    dvec_free(&A->par);
    dvec_free(&A->len);
}

static const double *apt(const region *R, const arcpts *A, int i)
{
    return A->ids.p[i] >= 0 ? glpgp_region_xy(R, A->ids.p[i]) : R->m->xy + 2 * (-1 - A->ids.p[i]);
}

static glpgp_status arc_collect(const region *R, int l, int u, double pu, int w, double len, arcpts *A)
{
    const glpgp_mesh *m = R->m;
    int s = m->loop_start[l], n = m->loop_start[l + 1] - s;
    GLPGP_CHECK(ipush(&A->ids, u));
    GLPGP_CHECK(dpush(&A->par, 0.0));
    double first = ceil(pu);
    if (first == pu) first += 1.0;
    const double *pu_xy = glpgp_region_xy(R, u), *pw_xy = glpgp_region_xy(R, w);
    for (double p = first; p - pu < len - 1e-12; p += 1.0) {
        int iv = s + ((int)fmod(p, (double)n) + n) % n;
        const double *x = m->xy + 2 * m->loop_vertices[iv];
        if (hypot(x[0] - pu_xy[0], x[1] - pu_xy[1]) < 1e-9 * R->h) continue;
        if (hypot(x[0] - pw_xy[0], x[1] - pw_xy[1]) < 1e-9 * R->h) continue;
        GLPGP_CHECK(ipush(&A->ids, -1 - m->loop_vertices[iv]));
        GLPGP_CHECK(dpush(&A->par, p - pu));
    }
    GLPGP_CHECK(ipush(&A->ids, w));
    GLPGP_CHECK(dpush(&A->par, len));
    GLPGP_CHECK(dpush(&A->len, 0.0));
    for (int i = 1; i < A->ids.n; i++) {
        const double *a = apt(R, A, i - 1), *b = apt(R, A, i);
        GLPGP_CHECK(dpush(&A->len, A->len.p[i - 1] + hypot(b[0] - a[0], b[1] - a[1])));
    }
    return GLPGP_OK;
}

/* keep[]: the ends, the domain corners, Douglas-Peucker at 0.02 h. */
static glpgp_status arc_keep(const region *R, const arcpts *A, int whole, unsigned char *keep)
{
    const glpgp_mesh *m = R->m;
    const int np = A->ids.n;
    const double cmin = cos(GLPGP_CORNER_DEG * RG_PI / 180.0);
    keep[0] = keep[np - 1] = 1;
    for (int i = 1; i + 1 < np; i++) {
        int vi = -1 - A->ids.p[i];
        const double *a = m->normal_prev + 2 * vi, *b = m->normal_next + 2 * vi;
        if (a[0] * b[0] + a[1] * b[1] < cmin) keep[i] = 1;
    }
    if (whole == 1 && np > 3) keep[np / 2] = keep[np / 4] = keep[3 * np / 4] = 1; /* a closed loop needs a triangle */
    int *stack = NULL, sp = 0, prev = 0;
    GLPGP_CHECK(glpgp_malloc((size_t)2 * np + 2, sizeof(int), &stack));
    for (int i = 1; i < np; i++) {
        if (!keep[i]) continue;
        stack[sp++] = prev;
        stack[sp++] = i;
        prev = i;
    }
    while (sp > 0) {
        int j = stack[--sp], i = stack[--sp];
        if (j - i < 2) continue;
        double dmax = 0;
        int im = -1;
        for (int k = i + 1; k < j; k++) {
            double d = glpgp_seg_dist(apt(R, A, i), apt(R, A, j), apt(R, A, k), NULL);
            if (d > dmax) {
                dmax = d;
                im = k;
            }
        }
        if (dmax > 0.02 * R->h && im > 0) {
            keep[im] = 1;
            stack[sp++] = i;
            stack[sp++] = im;
            stack[sp++] = im;
            stack[sp++] = j;
        }
    }
    free(stack);
    return GLPGP_OK;
}

/* Position and loop parameter at arc length s along the points (i .. j). */
static void arc_at(const region *R, const arcpts *A, int i, int j, double s, double pu, double *xy, double *par)
{
    int k = i;
    while (k + 1 < j && A->len.p[k + 1] < s) k++;
    double l0 = A->len.p[k], l1 = A->len.p[k + 1], t = l1 > l0 ? (s - l0) / (l1 - l0) : 0.0;
    const double *a = apt(R, A, k), *b = apt(R, A, k + 1);
    xy[0] = a[0] + t * (b[0] - a[0]);
    xy[1] = a[1] + t * (b[1] - a[1]);
    *par = pu + A->par.p[k] + t * (A->par.p[k + 1] - A->par.p[k]);
}

/* Emit the domain boundary piece from region point u (param pu) to w
 * (param pw) on loop l as half-edges of about spacing sp. whole: the full
 * loop from pu back to pu (1: three more points kept, 2: it has three
 * corners or more, which are kept anyway). */
static glpgp_status emit_arc(region *R, int l, int u, double pu, int w, double pw, int whole, double sp)
{
    const glpgp_mesh *m = R->m;
    int n = m->loop_start[l + 1] - m->loop_start[l];
    double len = whole ? n : fwd(pu, pw, n);
    if (whole && len == 0) len = n;
    arcpts A;
    memset(&A, 0, sizeof A);
    unsigned char *keep = NULL;
    glpgp_status st = arc_collect(R, l, u, pu, w, len, &A);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)A.ids.n + 1, 1, &keep);
    if (st == GLPGP_OK) st = arc_keep(R, &A, whole, keep);
    int last = 0, last_id = u;
    double last_par = pu;
    for (int i = 1; i < A.ids.n && st == GLPGP_OK; i++) {
        if (!keep[i]) continue;
        double L = A.len.p[i] - A.len.p[last];
        int pieces = (int)floor(L / sp + 0.5);
        if (pieces < 1) pieces = 1;
        for (int k = 1; k < pieces && st == GLPGP_OK; k++) {
            double xy[2], par;
            int id;
            arc_at(R, &A, last, i, A.len.p[last] + L * k / pieces, pu, xy, &par);
            st = new_point(R, xy[0], xy[1], &id);
            if (st == GLPGP_OK) st = add_he(R, last_id, id, 2, l, last_par, par);
            last_id = id;
            last_par = par;
        }
        int id = w;
        if (i != A.ids.n - 1 && st == GLPGP_OK) st = new_point(R, apt(R, &A, i)[0], apt(R, &A, i)[1], &id);
        if (st == GLPGP_OK) st = add_he(R, last_id, id, 2, l, last_par, pu + A.par.p[i]);
        last = i;
        last_id = id;
        last_par = pu + A.par.p[i];
    }
    free(keep);
    arcpts_free(&A);
    return st;
}

/* ---- the region's boundary ---------------------------------------------------------- */

static int cmp_dbl_int(const void *x, const void *y)
{
    const double *a = x, *b = y;
    return (a[0] > b[0]) - (a[0] < b[0]);
}

/* Whether the free K edge a -> b is a covered chord (see the header). */
static int covered_chord(const region *R, const bpos *bp, int a, int b)
{
    const glpgp_mesh *m = R->m;
    const dbnd *D = R->D;
    if (bp[a].seg < 0 || bp[b].seg < 0 || D->loop_of[bp[a].seg] != D->loop_of[bp[b].seg]) return 0;
    int l = D->loop_of[bp[a].seg], n = m->loop_start[l + 1] - m->loop_start[l];
    double pa = bparam(m, D, bp[a]), pb = bparam(m, D, bp[b]), len = fwd(pa, pb, n);
    if (!(len > 0 && len < 0.5 * n + 0.5)) return 0;
    for (int v = 0; v < R->q->nv; v++) { /* consecutive: no other K boundary vertex strictly between */
        if (v == a || v == b || bp[v].seg < 0 || D->loop_of[bp[v].seg] != l) continue;
        double dv = fwd(pa, bparam(m, D, bp[v]), n);
        if (dv > 1e-12 && dv < len - 1e-12) return 0;
    }
    const double *A = R->q->xy + 2 * a, *B = R->q->xy + 2 * b;
    double first = ceil(pa);
    if (first == pa) first += 1.0;
    for (double p = first; p < pa + len - 1e-12; p += 1.0) {
        double x[2];
        loop_point(m, l, p, x);
        if (glpgp_seg_dist(A, B, x, NULL) > 0.25 * R->h) return 0;
    }
    return 1;
}

/* The free edges of K: interface half-edges (reversed), or covered chords
 * (cover[a] = b). klen[v]: mean length of the interface edges at v. */
static glpgp_status interface_edges(region *R, const unsigned char *inB, const bpos *bp, int *cover, double *klen)
{
    const glpgp_quadmesh *q = R->q;
    int nK = 0, *kn = NULL;
    glpgp_ekv *hk = NULL;
    for (int f = 0; f < q->nf; f++)
        if (!inB[f]) nK += q->face_start[f + 1] - q->face_start[f];
    GLPGP_CHECK(glpgp_malloc((size_t)nK + 1, sizeof *hk, &hk));
    glpgp_status st = glpgp_calloc((size_t)q->nv + 1, sizeof(int), &kn);
    nK = 0;
    for (int f = 0; f < q->nf && st == GLPGP_OK; f++) {
        if (inB[f]) continue;
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        for (int i = 0; i < k; i++) {
            int a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % k];
            hk[nK].k = ((unsigned long long)(unsigned)a << 32) | (unsigned)b;
            hk[nK++].slot = s + i;
        }
    }
    if (st == GLPGP_OK) qsort(hk, (size_t)nK, sizeof *hk, glpgp_ekv_cmp);
    for (int i = 0; i < nK && st == GLPGP_OK; i++) {
        int a = (int)(hk[i].k >> 32), b = (int)(hk[i].k & 0xffffffffu);
        unsigned long long tw = ((unsigned long long)(unsigned)b << 32) | (unsigned)a;
        glpgp_ekv key = {tw, -1};
        int lo = 0, hi = nK; /* first entry >= (tw, -1) */
        while (lo < hi) {
            int mid = (lo + hi) / 2;
            if (glpgp_ekv_cmp(&hk[mid], &key) < 0) lo = mid + 1;
            else hi = mid;
        }
        if (lo < nK && hk[lo].k == tw) continue;
        if (covered_chord(R, bp, a, b)) {
            cover[a] = b;
            continue;
        }
        st = add_he(R, b, a, 1, -1, 0, 0);
        double l = hypot(q->xy[2 * a] - q->xy[2 * b], q->xy[2 * a + 1] - q->xy[2 * b + 1]);
        klen[a] += l;
        klen[b] += l;
        kn[a]++;
        kn[b]++;
    }
    for (int v = 0; v < q->nv; v++) klen[v] = kn[v] ? klen[v] / kn[v] : 0.0;
    free(kn);
    free(hk);
    return st;
}

/* Spacing of a boundary piece between K vertices u and w. */
static double piece_spacing(const region *R, const double *klen, int u, int w)
{
    double s = 0.0;
    int n = 0;
    if (u < R->q->nv && klen[u] > 0) s += klen[u], n++;
    if (w < R->q->nv && klen[w] > 0) s += klen[w], n++;
    return n ? fmin(R->h, s / n) : R->h;
}

/* The uncovered pieces of the domain loops. */
static glpgp_status boundary_pieces(region *R, const bpos *bp, const int *cover, const double *klen)
{
    const glpgp_mesh *m = R->m;
    const int nv = R->q->nv;
    double *lv = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)2 * nv + 2, sizeof(double), &lv));
    glpgp_status st = GLPGP_OK;
    for (int l = 0; l < m->nloops && st == GLPGP_OK; l++) {
        int n = m->loop_start[l + 1] - m->loop_start[l], cnt = 0;
        for (int v = 0; v < nv; v++)
            if (bp[v].seg >= 0 && R->D->loop_of[bp[v].seg] == l) {
                lv[2 * cnt] = bparam(m, R->D, bp[v]);
                lv[2 * cnt + 1] = v;
                cnt++;
            }
        if (cnt == 0) { /* the whole loop, from its first corner (else its first input vertex) */
            int s0 = 0, corners = 0;
            const double cmin = cos(GLPGP_CORNER_DEG * RG_PI / 180.0);
            for (int i = n - 1; i >= 0; i--) {
                int vi = m->loop_vertices[m->loop_start[l] + i];
                const double *a = m->normal_prev + 2 * vi, *b = m->normal_next + 2 * vi;
                if (a[0] * b[0] + a[1] * b[1] < cmin) {
                    s0 = i;
                    corners++;
                }
            }
            const double *x = m->xy + 2 * m->loop_vertices[m->loop_start[l] + s0];
            int v0;
            st = new_point(R, x[0], x[1], &v0);
            if (st == GLPGP_OK) st = emit_arc(R, l, v0, (double)s0, v0, (double)s0, corners >= 3 ? 2 : 1, R->h);
            continue;
        }
        qsort(lv, (size_t)cnt, 2 * sizeof(double), cmp_dbl_int);
        for (int i = 0; i < cnt && st == GLPGP_OK; i++) {
            int u = (int)lv[2 * i + 1], w = (int)lv[2 * ((i + 1) % cnt) + 1];
            if (cover[u] == w) continue;
            double sp = piece_spacing(R, klen, u, w);
            if (cnt == 1)
                st = emit_arc(R, l, u, lv[0], u, lv[0], 1, sp);
            else
                st = emit_arc(R, l, u, lv[2 * i], w, lv[2 * ((i + 1) % cnt)], 0, sp);
        }
    }
    free(lv);
    return st;
}

/* ---- loops ------------------------------------------------------------------------ */

/* The next half-edge at the head of e: the first one clockwise from the way back. */
static int next_he(const region *R, const int *ostart, const int *oitem, int e, int e0)
{
    int v = R->he[e].b;
    const double *pv = glpgp_region_xy(R, v), *pp = glpgp_region_xy(R, R->he[e].a);
    double back = atan2(pp[1] - pv[1], pp[0] - pv[0]), bangle = INFINITY;
    int best = -1;
    for (int j = ostart[v]; j < ostart[v + 1]; j++) {
        int f = oitem[j];
        if (R->he[f].used && f != e0) continue;
        const double *pn = glpgp_region_xy(R, R->he[f].b);
        double cw = back - atan2(pn[1] - pv[1], pn[0] - pv[0]); /* clockwise turn from the way back */
        while (cw <= 1e-12) cw += 2 * RG_PI;
        while (cw > 2 * RG_PI) cw -= 2 * RG_PI;
        if (cw < bangle) {
            bangle = cw;
            best = f;
        }
    }
    return best;
}

static glpgp_status trace_loops(region *R)
{
    const int nrv = R->q->nv + R->vxy.n / 2;
    int *ostart = NULL, *oitem = NULL, *ocnt = NULL;
    ivec lstart = {0};
    glpgp_status st = glpgp_calloc((size_t)nrv + 2, sizeof(int), &ostart);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)R->nhe + 1, sizeof(int), &oitem);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)nrv + 1, sizeof(int), &ocnt);
    if (st == GLPGP_OK) {
        for (int e = 0; e < R->nhe; e++) ostart[R->he[e].a + 1]++;
        for (int v = 0; v < nrv; v++) ostart[v + 1] += ostart[v];
        for (int e = 0; e < R->nhe; e++) oitem[ostart[R->he[e].a] + ocnt[R->he[e].a]++] = e;
        st = ipush(&lstart, 0);
    }
    for (int e0 = 0; e0 < R->nhe && st == GLPGP_OK; e0++) {
        if (R->he[e0].used) continue;
        int e = e0, guard = 0;
        do {
            R->he[e].used = 1;
            st = ipush(&R->loopv, e);
            e = next_he(R, ostart, oitem, e, e0);
        } while (e >= 0 && e != e0 && ++guard < 4 * R->nhe + 4 && st == GLPGP_OK);
        if (st == GLPGP_OK && e != e0)
            st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "quad repair: region boundary does not close");
        if (st == GLPGP_OK) st = ipush(&lstart, R->loopv.n);
    }
    free(ostart);
    free(oitem);
    free(ocnt);
    R->loop_start = lstart.p;
    R->nloops = lstart.n > 0 ? lstart.n - 1 : 0;
    return st;
}

/* Area sign; holes into the smallest outer loop containing them. */
static glpgp_status classify_loops(region *R)
{
    GLPGP_CHECK(glpgp_calloc((size_t)R->nloops + 1, sizeof(double), &R->area));
    GLPGP_CHECK(glpgp_malloc((size_t)R->nloops + 1, sizeof(int), &R->owner));
    for (int L = 0; L < R->nloops; L++) {
        const double *o = glpgp_region_xy(R, R->he[R->loopv.p[R->loop_start[L]]].a);
        for (int i = R->loop_start[L]; i < R->loop_start[L + 1]; i++) {
            const double *a = glpgp_region_xy(R, R->he[R->loopv.p[i]].a), *b = glpgp_region_xy(R, R->he[R->loopv.p[i]].b);
            R->area[L] += 0.5 * ((a[0] - o[0]) * (b[1] - o[1]) - (b[0] - o[0]) * (a[1] - o[1]));
        }
        R->owner[L] = -1;
    }
    for (int L = 0; L < R->nloops; L++) {
        if (R->area[L] >= 0) continue;
        const double *a = glpgp_region_xy(R, R->he[R->loopv.p[R->loop_start[L]]].a),
                     *b = glpgp_region_xy(R, R->he[R->loopv.p[R->loop_start[L]]].b);
        double p[2] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])}, best = INFINITY;
        for (int O = 0; O < R->nloops; O++) {
            if (R->area[O] <= 0 || R->area[O] >= best) continue;
            int wn = 0;
            for (int i = R->loop_start[O]; i < R->loop_start[O + 1]; i++) {
                const double *x = glpgp_region_xy(R, R->he[R->loopv.p[i]].a), *y = glpgp_region_xy(R, R->he[R->loopv.p[i]].b);
                double o = (y[0] - x[0]) * (p[1] - x[1]) - (y[1] - x[1]) * (p[0] - x[0]);
                if (x[1] <= p[1]) {
                    if (y[1] > p[1] && o > 0) wn++;
                } else if (y[1] <= p[1] && o < 0) {
                    wn--;
                }
            }
            if (wn) {
                best = R->area[O];
                R->owner[L] = O;
            }
        }
    }
    return GLPGP_OK;
}

glpgp_status glpgp_region_build(region *R, const glpgp_quadmesh *q, const glpgp_mesh *m, dbnd *D, double h,
                                const unsigned char *inB)
{
    memset(R, 0, sizeof *R);
    R->q = q;
    R->m = m;
    R->D = D;
    R->h = h;
    const int nv = q->nv;
    bpos *bp = NULL;
    int *cand = NULL, ncap = 0, *cover = NULL;
    unsigned char *usedK = NULL;
    double *klen = NULL;
    glpgp_status st = glpgp_malloc((size_t)nv + 1, sizeof *bp, &bp);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)nv + 1, 1, &usedK);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nv + 1, sizeof(int), &cover);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)nv + 1, sizeof(double), &klen);
    if (st != GLPGP_OK) goto done;
    for (int f = 0; f < q->nf; f++)
        if (!inB[f])
            for (int s = q->face_start[f]; s < q->face_start[f + 1]; s++) usedK[q->face_vert[s]] = 1;
    for (int v = 0; v < nv; v++) { /* boundary positions of the K vertices */
        bp[v].seg = -1;
        cover[v] = -1;
        if (!usedK[v]) continue;
        double t, d, pr[2];
        int s = glpgp_dbnd_nearest(D, q->xy + 2 * v, 1e-8 * h, &t, &d, pr, &cand, &ncap);
        if (s >= 0) {
            bp[v].seg = s;
            bp[v].t = t;
        }
    }
    GLPGP_CHECK_GOTO(st, interface_edges(R, inB, bp, cover, klen), done);
    GLPGP_CHECK_GOTO(st, boundary_pieces(R, bp, cover, klen), done);
    GLPGP_CHECK_GOTO(st, trace_loops(R), done);
    GLPGP_CHECK_GOTO(st, classify_loops(R), done);
done:
    free(bp);
    free(cand);
    free(cover);
    free(usedK);
    free(klen);
    return st;
}

void glpgp_region_free(region *R)
{
    dvec_free(&R->vxy);
    free(R->he);
    free(R->loop_start);
    ivec_free(&R->loopv);
    free(R->area);
    free(R->owner);
    memset(R, 0, sizeof *R);
}

/* ---- parity ------------------------------------------------------------------------ */

/* Split half-edge e at point id: e becomes a -> id, a new half-edge id -> b
 * follows it in its loop. */
static glpgp_status split_he(region *R, int L, int pos, int id, double pmid)
{
    rhe e = R->he[R->loopv.p[pos]];
    GLPGP_CHECK(add_he(R, id, e.b, e.kind, e.loop, pmid, e.p1));
    int ne = R->nhe - 1;
    R->he[R->loopv.p[pos]].b = id;
    R->he[R->loopv.p[pos]].p1 = pmid;
    /* insert ne after pos in loopv; later loops' starts move by one */
    GLPGP_CHECK(ipush(&R->loopv, 0));
    memmove(R->loopv.p + pos + 2, R->loopv.p + pos + 1, sizeof(int) * (size_t)(R->loopv.n - pos - 2));
    R->loopv.p[pos + 1] = ne;
    for (int k = L + 1; k <= R->nloops; k++) R->loop_start[k]++;
    return GLPGP_OK;
}

glpgp_status glpgp_region_make_even(region *R, int O, int *kedge, int *kmid)
{
    *kmid = -1;
    int count = 0, bestk[2] = {-1, -1}, bestl[2] = {-1, -1};
    double bestlen[2] = {-1.0, -1.0};
    for (int L = 0; L < R->nloops; L++) {
        if (L != O && R->owner[L] != O) continue;
        count += R->loop_start[L + 1] - R->loop_start[L];
        for (int i = R->loop_start[L]; i < R->loop_start[L + 1]; i++) {
            const rhe *e = &R->he[R->loopv.p[i]];
            const double *a = glpgp_region_xy(R, e->a), *b = glpgp_region_xy(R, e->b);
            double l = hypot(b[0] - a[0], b[1] - a[1]);
            int k = e->kind == 2 ? 0 : 1;
            if (l > bestlen[k]) {
                bestlen[k] = l;
                bestk[k] = i;
                bestl[k] = L;
            }
        }
    }
    if (count % 2 == 0) return GLPGP_OK;
    int k = bestk[0] >= 0 ? 0 : 1;
    if (bestk[k] < 0) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "quad repair: an empty region loop");
    const rhe e = R->he[R->loopv.p[bestk[k]]];
    double p[2], pmid = 0.0;
    if (k == 0) {
        glpgp_region_split_point(R, &e, p);
        int n = R->m->loop_start[e.loop + 1] - R->m->loop_start[e.loop];
        pmid = e.p0 + 0.5 * fwd(e.p0, e.p1, n);
    } else {
        const double *a = glpgp_region_xy(R, e.a), *b = glpgp_region_xy(R, e.b);
        p[0] = 0.5 * (a[0] + b[0]);
        p[1] = 0.5 * (a[1] + b[1]);
    }
    int id;
    GLPGP_CHECK(new_point(R, p[0], p[1], &id));
    GLPGP_CHECK(split_he(R, bestl[k], bestk[k], id, pmid));
    if (k == 1) {
        kedge[0] = e.a;
        kedge[1] = e.b;
        *kmid = id;
    }
    return GLPGP_OK;
}
