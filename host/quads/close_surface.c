/* quads/close_surface.c: the closing of a surface's extracted polygons into
 * quads without changing the element size (quads_surface.c's first
 * candidates; the planar counterpart is close.c):
 *  - glpgp_qs_close_pairs: two odd faces across a side joined and split into
 *    quads, and the even faces split, by the split (and neighbour) leaving
 *    the fewest irregular vertices among the corners, then the best
 *    smallest scaled Jacobian; a hexagon may become three quads about a new
 *    centre (a triangle at a +1/4 singularity beside a dislocation's
 *    pentagon: one valence-3 vertex where any diagonal leaves three);
 *  - glpgp_qs_strips_closed: the odd faces left joined pairwise by strips
 *    of quads cut in two (three about a new vertex at a turn), the
 *    cheapest paths (Dijkstra: a quad 1, a turn 4 more, which leaves a
 *    3-5 pair), a lone triangle (a +1/4 singularity inside a face, which a
 *    strip cannot enter) joined with the quad across one of its sides;
 *    four passes (the T-junctions' sides or any side, lone triangles
 *    joined or not), the all-quad result with the fewest irregular
 *    interior vertices kept;
 *  - glpgp_qs_irregular_interior, glpgp_qs_count_nonquads: the counts the
 *    choices compare. */
#include "quads_surface.h"

#include "glpgp/internal/heap.h"
#include "glpgp/util.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- closing: two odd faces sharing a side, even faces ---- */

/* Smallest corner scaled Jacobian of the quad c[0..3] in its Newell plane (-1: degenerate). */
static double sj4p(const double *const c[4])
{
    double N[3] = {0, 0, 0};
    for (int i = 0; i < 4; i++) {
        const double *a = c[i], *b = c[(i + 1) % 4];
        N[0] += (a[1] - b[1]) * (a[2] + b[2]);
        N[1] += (a[2] - b[2]) * (a[0] + b[0]);
        N[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    const double nn = sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
    if (!(nn > 0)) return -1.0;
    double sj = 1.0;
    for (int i = 0; i < 4; i++) {
        const double *p = c[i], *a = c[(i + 1) % 4], *b = c[(i + 3) % 4];
        const double e1[3] = {a[0] - p[0], a[1] - p[1], a[2] - p[2]}, e2[3] = {b[0] - p[0], b[1] - p[1], b[2] - p[2]};
        const double l = sqrt((e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]) * (e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]));
        if (!(l > 0)) return -1.0;
        const double x[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        sj = fmin(sj, (x[0] * N[0] + x[1] * N[1] + x[2] * N[2]) / (nn * l));
    }
    return sj;
}

static double sj4(const double *xyz, const int *v)
{
    const double *const c[4] = {xyz + 3 * v[0], xyz + 3 * v[1], xyz + 3 * v[2], xyz + 3 * v[3]};
    return sj4p(c);
}

/* Splits of an even polygon into quads: the search's state. A split's
 * cost is the irregular vertices it leaves among the polygon's corners
 * (sum of |valence - 4| over the corners with a known valence base[k] >= 0:
 * the edges they keep outside the polygon and its sides, plus the split's
 * diagonals at them), then its smallest scaled Jacobian (higher better);
 * splits with a quad at or below `floor` are not taken. */
typedef struct even_split {
    const double *xyz;
    const int *p, *base;
    int n;
    int deg[10];     /* diagonals at each corner so far */
    int cur[16];     /* quads so far (corner positions, 4 each; at most 4 quads) */
    int best_q[16];
    int best_irr;    /* INT_MAX: none */
    int centred;     /* 1: best_q is hexagon_centre's (3 quads about a new vertex) */
    double best_sj, floor;
} even_split;

static void split_search(even_split *S, const int *idx, int m, int nq, double sj)
{
    if (nq > 3 || m > 10) return; /* at most 10 corners: 4 quads */
    if (m == 4) {
        int v[4];
        for (int k = 0; k < 4; k++) v[k] = S->p[idx[k]];
        sj = fmin(sj, sj4(S->xyz, v));
        if (!(sj > S->floor)) return;
        int irr = 0;
        for (int k = 0; k < S->n; k++)
            if (S->base[k] >= 0) irr += abs(S->base[k] + S->deg[k] - 4);
        if (irr > S->best_irr || (irr == S->best_irr && sj <= S->best_sj)) return;
        S->best_irr = irr;
        S->best_sj = sj;
        S->centred = 0;
        for (int j = 0; j < nq; j++)
            for (int k = 0; k < 4; k++) S->best_q[4 * j + k] = S->p[S->cur[4 * j + k]];
        for (int k = 0; k < 4; k++) S->best_q[4 * nq + k] = S->p[idx[k]];
        return;
    }
    for (int i = 0; i < m; i++) {
        int v[4], rest[10], r = 0;
        for (int k = 0; k < 4; k++) v[k] = S->p[idx[(i + k) % m]];
        const double a = fmin(sj, sj4(S->xyz, v));
        if (!(a > S->floor)) continue;
        for (int k = 0; k < 4; k++) S->cur[4 * nq + k] = idx[(i + k) % m];
        for (int k = 3; k <= m; k++) rest[r++] = idx[(i + k) % m]; /* idx[i+3] .. idx[i] */
        S->deg[idx[i]]++; /* the diagonal idx[i] - idx[i+3] */
        S->deg[idx[(i + 3) % m]]++;
        split_search(S, rest, r, nq + 1, a);
        S->deg[idx[i]]--;
        S->deg[idx[(i + 3) % m]]--;
    }
}

/* A hexagon's other split: three quads about a new centre (vertex id cid
 * at cxyz, the corners' mean) joined to every other corner; the centre
 * counts as one irregular vertex (valence 3). Taken over S's best when
 * cheaper (a triangle at a +1/4 singularity merged with a dislocation's
 * pentagon: valence 3 at every other corner, so any diagonal leaves three
 * irregular vertices and the centre one). */
static void hexagon_centre(even_split *S, int cid, double *cxyz)
{
    double c[3] = {0, 0, 0};
    for (int k = 0; k < 6; k++)
        for (int d = 0; d < 3; d++) c[d] += S->xyz[3 * S->p[k] + d] / 6.0;
    for (int par = 0; par < 2; par++) {
        double sj = 1.0;
        int irr = 1;
        for (int t = 0; t < 3; t++) {
            const int a = (par + 2 * t) % 6;
            const double *const qc[4] = {S->xyz + 3 * S->p[a], S->xyz + 3 * S->p[(a + 1) % 6],
                                         S->xyz + 3 * S->p[(a + 2) % 6], c};
            sj = fmin(sj, sj4p(qc));
        }
        for (int k = 0; k < 6; k++)
            if (S->base[k] >= 0) irr += abs(S->base[k] + ((k - par) % 2 == 0) - 4);
        if (!(sj > S->floor) || irr > S->best_irr || (irr == S->best_irr && sj <= S->best_sj)) continue;
        S->best_irr = irr;
        S->best_sj = sj;
        S->centred = 1;
        for (int t = 0; t < 3; t++) {
            const int a = (par + 2 * t) % 6;
            int *o = S->best_q + 4 * t;
            o[0] = S->p[a];
            o[1] = S->p[(a + 1) % 6];
            o[2] = S->p[(a + 2) % 6];
            o[3] = cid;
        }
        memcpy(cxyz, c, sizeof c);
    }
}

/* The best split of polygon p (n even, 4..10 vertices) into n/2 - 1 quads
 * (q: 4 per quad; the fewest irregular corners, then the highest smallest
 * scaled Jacobian, every quad above `floor`), cutting off one quad of
 * consecutive corners at a time, or for a hexagon when cid >= 0 three
 * quads about a new vertex cid (hexagon_centre; its position in cxyz);
 * base: per corner the valence it keeps without the polygon's diagonals
 * (-1: not counted; NULL: none counted). Returns its smallest scaled
 * Jacobian (-2 when none) and *irr its cost; q: room for 4 (n / 2) ids. */
static double split_even(const double *xyz, const int *p, int n, const int *base, double floor, int cid, double *cxyz,
                         int *q, int *irr)
{
    static const int none[10] = {-1, -1, -1, -1, -1, -1, -1, -1, -1, -1};
    even_split S;
    memset(&S, 0, sizeof S);
    S.xyz = xyz;
    S.p = p;
    S.n = n;
    S.base = base ? base : none;
    S.floor = floor;
    S.best_irr = INT_MAX;
    S.best_sj = -2.0;
    int idx[10];
    for (int k = 0; k < n; k++) idx[k] = k;
    split_search(&S, idx, n, 0, 1.0);
    if (n == 6 && cid >= 0) hexagon_centre(&S, cid, cxyz);
    if (S.best_irr == INT_MAX) return -2.0;
    for (int k = 0; k < 4 * (n / 2); k++) q[k] = -1;
    memcpy(q, S.best_q, (size_t)(n / 2 - 1 + S.centred) * 4 * sizeof *q);
    if (irr) *irr = S.best_irr;
    return S.best_sj;
}

typedef struct fedge {
    long long key;
    int f, i;
} fedge;

static int cmp_fedge(const void *pa, const void *pb)
{
    const fedge *a = pa, *b = pb;
    return a->key < b->key ? -1 : a->key > b->key ? 1 : a->f - b->f;
}

/* Every face side (edge key, face, side), sorted by key then face. */
static glpgp_status build_fedges(const glpgp_quadmesh *q, fedge **out)
{
    const int nc = q->face_start[q->nf];
    fedge *E = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)nc + 1, sizeof *E, &E));
    for (int f = 0; f < q->nf; f++) {
        const int s = q->face_start[f], n = q->face_start[f + 1] - s;
        for (int i = 0; i < n; i++) {
            long long a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % n];
            E[s + i] = (fedge){a < b ? a * q->nv + b : b * q->nv + a, f, i};
        }
    }
    qsort(E, (size_t)nc, sizeof *E, cmp_fedge);
    *out = E;
    return GLPGP_OK;
}

/* Side i of face f as its edge key (*key) and the first entry of the sorted
 * sides E[0 .. nc) with that key (nc: none larger). */
static int first_side(const glpgp_quadmesh *q, const fedge *E, int nc, int f, int i, long long *key)
{
    const int s = q->face_start[f], n = q->face_start[f + 1] - s;
    long long a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % n];
    *key = a < b ? a * q->nv + b : b * q->nv + a;
    int lo = 0, hi = nc;
    while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (E[mid].key < *key) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

/* Whether side i of face f is on the boundary (in no other face). */
static int boundary_side(const glpgp_quadmesh *q, const fedge *E, int nc, int f, int i)
{
    long long key;
    const int lo = first_side(q, E, nc, f, i, &key);
    return lo < nc && E[lo].key == key && (lo + 1 >= nc || E[lo + 1].key != key);
}

/* The face across side i of face f (-1: none or more than one); *j its side. */
static int across(const glpgp_quadmesh *q, const fedge *E, int nc, int f, int i, int *j)
{
    long long key;
    const int lo = first_side(q, E, nc, f, i, &key);
    if (lo + 1 >= nc || E[lo].key != key || E[lo + 1].key != key || (lo + 2 < nc && E[lo + 2].key == key)) return -1;
    const fedge *o = E[lo].f == f ? &E[lo + 1] : &E[lo];
    *j = o->i;
    return o->f;
}

/* The polygon of faces f and g joined across f's side i (g's side j); its
 * corner count, 0 when a corner repeats. */
static int merged(const glpgp_quadmesh *q, int f, int i, int g, int j, int *p)
{
    const int sf = q->face_start[f], nf = q->face_start[f + 1] - sf;
    const int sg = q->face_start[g], ng = q->face_start[g + 1] - sg;
    int n = 0;
    for (int k = 0; k < nf - 1; k++) p[n++] = q->face_vert[sf + (i + 1 + k) % nf]; /* b .. before a */
    for (int k = 0; k < ng - 1; k++) p[n++] = q->face_vert[sg + (j + 1 + k) % ng]; /* a .. before b */
    for (int x = 0; x < n; x++)
        for (int y = x + 1; y < n; y++)
            if (p[x] == p[y]) return 0;
    return n;
}

/* Whether vertex id v is among the n ids of a. */
static int uses(const int *a, int n, int v)
{
    for (int k = 0; k < n; k++)
        if (a[k] == v) return 1;
    return 0;
}

/* Per vertex of q its valence, -1 on the boundary (E: build_fedges). */
static glpgp_status vertex_valences(const glpgp_quadmesh *q, const fedge *E, int **out)
{
    const int nc = q->face_start[q->nf];
    int *val = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)q->nv + 1, sizeof *val, &val));
    for (int k = 0; k < nc;) {
        int e = k + 1;
        while (e < nc && E[e].key == E[k].key) e++;
        const int a = (int)(E[k].key / q->nv), b = (int)(E[k].key % q->nv);
        if (val[a] >= 0) val[a]++;
        if (val[b] >= 0) val[b]++;
        if (e - k == 1) val[a] = val[b] = -1;
        k = e;
    }
    *out = val;
    return GLPGP_OK;
}

/* The valence bases of polygon p's corners for split_even (val: per
 * vertex, -1 on the boundary); the shared side's ends a, b (a merged pair:
 * that edge goes) lose one; -1: no shared side. */
static void corner_bases(const int *val, const int *p, int n, int a, int b, int *base)
{
    for (int k = 0; k < n; k++) {
        base[k] = val[p[k]];
        if (base[k] >= 0 && (p[k] == a || p[k] == b)) base[k]--;
    }
}

/* Odd faces paired with an odd neighbour across a side, and the even
 * faces (up to 10 corners), split into quads where all have a scaled
 * Jacobian above 0.05: the split and the neighbour that leave the fewest
 * irregular corners, then the best smallest scaled Jacobian (a triangle at
 * a +1/4 singularity beside a dislocation's pentagon: the split through
 * the pentagon's T-junction leaves one valence-3 vertex, at the
 * singularity); *closed: faces made quads. */
glpgp_status glpgp_qs_close_pairs(const glpgp_mesh *m, double h, const glpgp_quadmesh *q, glpgp_quadmesh **out,
                                  int *closed)
{
    *out = NULL;
    *closed = 0;
    const int nc = q->face_start[q->nf];
    fedge *E = NULL;
    unsigned char *used = NULL;
    int *newq = NULL, *val = NULL, nnew = 0, ncent = 0;
    double *cent = NULL; /* the hexagons' new centres, 3 each */
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, build_fedges(q, &E), done);
    GLPGP_CHECK_GOTO(st, vertex_valences(q, E, &val), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)q->nf + 1, 1, &used), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * nc + 8, sizeof(int), &newq), done);
    /* 3 per centre, each of at least 6 corners */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc / 2 + 3, sizeof(double), &cent), done);
    for (int f = 0; f < q->nf; f++) {
        const int sf = q->face_start[f], n = q->face_start[f + 1] - sf;
        int p[10], base[10], qd[20], bq[20], bn = 0, irr = 0, birr = INT_MAX; /* 20: 4 per quad, up to 5 */
        double best = -2.0, cx[3], bcx[3];
        const int cid = q->nv + ncent;
        int bg = -1;
        if (used[f] || n == 4 || n > 10) continue;
        if (n % 2 == 0) {
            memcpy(p, q->face_vert + sf, (size_t)n * sizeof *p);
            corner_bases(val, p, n, -1, -1, base);
            if (split_even(q->xyz, p, n, base, 0.05, cid, cx, qd, NULL) > 0.05) {
                const int nq = n / 2 - 1 + uses(qd, 4 * (n / 2), cid);
                if (nq > n / 2 - 1) memcpy(cent + 3 * ncent++, cx, sizeof cx);
                memcpy(newq + 4 * nnew, qd, (size_t)nq * 4 * sizeof *qd);
                nnew += nq;
                used[f] = 1;
                (*closed)++;
            }
            continue;
        }
        for (int i = 0; i < n; i++) { /* an odd face: the best odd neighbour across a side */
            int j, g = across(q, E, nc, f, i, &j);
            if (g < 0 || g == f || used[g]) continue;
            const int ng = q->face_start[g + 1] - q->face_start[g];
            if (ng % 2 == 0 || n + ng - 2 > 10) continue;
            const int nm = merged(q, f, i, g, j, p);
            if (nm < 4) continue;
            corner_bases(val, p, nm, q->face_vert[sf + i], q->face_vert[sf + (i + 1) % n], base);
            const double sj = split_even(q->xyz, p, nm, base, 0.05, cid, cx, qd, &irr);
            if (sj > 0.05 && (irr < birr || (irr == birr && sj > best))) {
                best = sj;
                birr = irr;
                bg = g;
                bn = nm / 2 - 1 + uses(qd, 4 * (nm / 2), cid);
                memcpy(bq, qd, sizeof qd);
                memcpy(bcx, cx, sizeof cx);
            }
        }
        if (bg >= 0) {
            used[f] = used[bg] = 1;
            if (uses(bq, 4 * bn, cid)) memcpy(cent + 3 * ncent++, bcx, sizeof bcx);
            memcpy(newq + 4 * nnew, bq, (size_t)bn * 4 * sizeof *bq);
            nnew += bn;
            *closed += 2;
        }
    }
    if (nnew) {
        glpgp_quadmesh *r = NULL;
        int nf = nnew, ncr = 4 * nnew;
        for (int f = 0; f < q->nf; f++)
            if (!used[f]) {
                nf++;
                ncr += q->face_start[f + 1] - q->face_start[f];
            }
        GLPGP_CHECK_GOTO(st, glpgp_qs_alloc(q->nv + ncent, nf, ncr, &r), done);
        memcpy(r->xyz, q->xyz, (size_t)3 * q->nv * sizeof(double));
        memcpy(r->xyz + 3 * q->nv, cent, (size_t)3 * ncent * sizeof(double));
        if (ncent) GLPGP_CHECK_GOTO(st, glpgp_qs_project(m, h, r->xyz, q->nv, q->nv + ncent), done);
        int o = 0, w = 0;
        for (int f = 0; f < q->nf; f++) {
            if (used[f]) continue;
            r->face_start[o] = w;
            r->face_origin[o++] = q->face_origin ? q->face_origin[f] : GLPGP_QFACE_GRID;
            for (int k = q->face_start[f]; k < q->face_start[f + 1]; k++) r->face_vert[w++] = q->face_vert[k];
        }
        for (int k = 0; k < nnew; k++) {
            r->face_start[o] = w;
            r->face_origin[o++] = GLPGP_QFACE_CLOSED;
            for (int c = 0; c < 4; c++) r->face_vert[w++] = newq[4 * k + c];
        }
        r->face_start[o] = w;
        glpgp_qs_finish_from(r, q);
        r->closing.closed_polygons = *closed;
        *out = r;
    }
done:
    free(E);
    free(cent);
    free(val);
    free(used);
    free(newq);
    return st;
}

/* ---- strips: an odd face joined to another through a strip of quads ---- */

/* A start state's parent: -3 - 2 i from odd face A's side i, -3 - (2 i + 1)
 * from lone triangle A joined across its side i: one code for a face of
 * any number of sides. */
static int strip_from(int i, int joined) { return -3 - (2 * i + joined); }

typedef struct strip_ctx {
    const glpgp_quadmesh *q;
    const fedge *E;
    int nc;
    unsigned char *used; /* nf */
    int *par;            /* 4 nf: BFS parent state (4 g + entry side), -2 unvisited, -1 from the start */
    int *queue;          /* 4 nf */
    int *ins;            /* nf: the side after whose first corner a midpoint is inserted (-1) */
    int *insv;           /* nf: that midpoint */
    int *exit_side;      /* nf: a strip quad's exit side (-1) */
    int *entry_side;     /* nf */
    int *mid_in, *mid_out, *center; /* nf: a strip quad's new vertices */
    double *xyz;         /* new vertex positions (3 per vertex, from q->nv on) */
    int nv, capv;
    int any_side;        /* 0: strips only through the sides opposite the odd faces' flattest corners */
    int *dist;           /* 4 nf: the search's cost of a state (valid where par != -2) */
    int *mtri, *mside;   /* nf: a quad joined with a lone triangle at a strip's end: the triangle and
                            the quad's side it shares (-1: none) */
    int end_mq, end_mk;  /* the search's end joined with a lone triangle: its quad, entered at side end_mk */
    unsigned char *tri_joined; /* nf: a lone triangle joined with a quad (emitted with it) */
    int join;            /* 1: lone triangles joined with a quad (0: reached like any odd face) */
    glpgp_heap heap;     /* the search's (cost, state) items (lazy deletion) */
} strip_ctx;

static int is_odd(const glpgp_quadmesh *q, int f) { return (q->face_start[f + 1] - q->face_start[f]) % 2; }

static glpgp_status new_vertex(strip_ctx *c, const double *p, int *id)
{
    if (c->nv - c->q->nv == c->capv) {
        c->capv = c->capv ? 2 * c->capv : 256;
        double *x = realloc(c->xyz, (size_t)3 * c->capv * sizeof *x);
        if (!x) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory (surface strips)");
        c->xyz = x;
    }
    memcpy(c->xyz + 3 * (c->nv - c->q->nv), p, 3 * sizeof *p);
    *id = c->nv++;
    return GLPGP_OK;
}

static void side_mid(const glpgp_quadmesh *q, int f, int i, double *p)
{
    const int s = q->face_start[f], n = q->face_start[f + 1] - s;
    const double *a = q->xyz + 3 * q->face_vert[s + i], *b = q->xyz + 3 * q->face_vert[s + (i + 1) % n];
    for (int d = 0; d < 3; d++) p[d] = 0.5 * (a[d] + b[d]);
}

/* The strip found by the search, from A to B (entered at B's side bside
 * from the quad of state last): its quads (unique), midpoints and turn
 * centers; *found 1 when applied. */
static glpgp_status apply_strip(strip_ctx *c, int A, int B, int bside, int last, int *found)
{
    const glpgp_quadmesh *q = c->q;
    int path[64], entry[64], ex[64], n = 0, st = last, e = -1, startSide = -1;
    const int emq = c->end_mq, emk = c->end_mk;
    if (B < 0) e = -1 - B; /* to the boundary: the last quad's exit side */
    else { /* B's side (or, B joined with quad emq, emq's side emk) is entered through the last quad's side across it */
        const int g = last / 4;
        for (int k = 0; k < 4; k++) {
            int jj, gg = across(q, c->E, c->nc, g, k, &jj);
            if (emq >= 0 ? gg == emq && jj == emk : gg == B && jj == bside) e = k;
        }
    }
    for (;;) {
        const int g = st / 4, p = c->par[st];
        if (n == 64 || e < 0) return GLPGP_OK;
        for (int i = 0; i < n; i++)
            if (path[i] == g) return GLPGP_OK; /* a strip through a quad twice: not used */
        path[n] = g;
        entry[n] = st % 4;
        ex[n++] = e;
        if (p < 0) {
            startSide = -p - 3;
            break;
        }
        e = -1;
        for (int k = 0; k < 4; k++) {
            int jj, gg = across(q, c->E, c->nc, p / 4, k, &jj);
            if (gg == g && jj == st % 4) e = k;
        }
        st = p;
    }
    /* path[n-1] is next to A: reverse into A -> B order */
    for (int i = 0; i < n / 2; i++) {
        int t = path[i]; path[i] = path[n - 1 - i]; path[n - 1 - i] = t;
        t = entry[i]; entry[i] = entry[n - 1 - i]; entry[n - 1 - i] = t;
        t = ex[i]; ex[i] = ex[n - 1 - i]; ex[n - 1 - i] = t;
    }
    int sA = A, sq = -1, sj = -1; /* the face whose side startSide gets the first midpoint */
    const int joined = startSide & 1;
    startSide >>= 1;
    if (joined) { /* lone triangle A joined with quad sq (side sj): the strip starts beyond sq */
        sq = across(q, c->E, c->nc, A, startSide, &sj);
        if (sq < 0) return GLPGP_OK;
        sA = sq;
        startSide = (sj + 2) % 4;
    }
    for (int i = 0; i < n; i++)
        if (path[i] == sq || path[i] == emq) return GLPGP_OK; /* through a joined quad: not used */
    if (sq >= 0 && sq == emq) return GLPGP_OK;
    double p3[3];
    int m;
    side_mid(q, sA, startSide, p3);
    GLPGP_CHECK(new_vertex(c, p3, &m));
    c->ins[sA] = startSide;
    c->insv[sA] = m;
    if (sq >= 0) {
        c->mtri[sq] = A;
        c->mside[sq] = sj;
        c->used[sq] = 1;
        c->tri_joined[A] = 1;
    }
    for (int i = 0; i < n; i++) {
        const int g = path[i];
        c->used[g] = 1;
        c->entry_side[g] = entry[i];
        c->exit_side[g] = ex[i];
        c->mid_in[g] = m;
        side_mid(q, g, ex[i], p3);
        GLPGP_CHECK(new_vertex(c, p3, &m));
        c->mid_out[g] = m;
        c->center[g] = -1;
        if ((ex[i] - entry[i] + 4) % 4 != 2) { /* a turn: a center vertex */
            const int s0 = q->face_start[g];
            for (int d = 0; d < 3; d++) {
                p3[d] = 0.0;
                for (int k = 0; k < 4; k++) p3[d] += 0.25 * q->xyz[3 * q->face_vert[s0 + k] + d];
            }
            GLPGP_CHECK(new_vertex(c, p3, &c->center[g]));
        }
    }
    c->used[A] = 1;
    if (B >= 0 && emq >= 0) { /* B joined with quad emq, entered at its side emk */
        c->used[B] = c->used[emq] = 1;
        c->ins[emq] = emk;
        c->insv[emq] = m;
        c->mtri[emq] = B;
        c->mside[emq] = (emk + 2) % 4;
        c->tri_joined[B] = 1;
    } else if (B >= 0) {
        c->used[B] = 1;
        c->ins[B] = bside;
        c->insv[B] = m;
    }
    *found = 1;
    return GLPGP_OK;
}

/* The side of odd face f (at least 5 corners) opposite its flattest
 * corner (a dislocation's T-junction): a strip through it continues the
 * line that ended there; -1 for a triangle (a midpoint would make a flat
 * quad). */
static int strip_side(const strip_ctx *c, int f)
{
    const glpgp_quadmesh *q = c->q;
    const int s = q->face_start[f], n = q->face_start[f + 1] - s;
    if (n < 5) return -1;
    int best = 0;
    double bc = 2.0;
    for (int i = 0; i < n; i++) {
        const double *p = q->xyz + 3 * q->face_vert[s + i], *a = q->xyz + 3 * q->face_vert[s + (i + 1) % n],
                     *b = q->xyz + 3 * q->face_vert[s + (i + n - 1) % n];
        double e1[3], e2[3];
        for (int d = 0; d < 3; d++) {
            e1[d] = a[d] - p[d];
            e2[d] = b[d] - p[d];
        }
        const double l = sqrt((e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]) * (e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]));
        const double cs = l > 0 ? (e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / l : 2.0;
        if (cs < bc) { /* the most negative cosine: the widest angle */
            bc = cs;
            best = i;
        }
    }
    return (best + (n - 1) / 2) % n;
}

/* Whether face f is a triangle whose three neighbours are unused quads (a
 * +1/4 singularity inside a face): a strip cannot enter it (its midpoint
 * would make a quad with a flat corner), so it is joined with the quad
 * across one of its sides into a pentagon, the strip leaving or entering
 * through that quad's far side; the hexagon the midpoint makes has its
 * valence-3 corners (the joined side's ends, the midpoint) alternating,
 * and its split about a centre (hexagon_centre) leaves one valence-3
 * vertex: the singularity. */
static int lone_triangle(const strip_ctx *c, int f)
{
    const glpgp_quadmesh *q = c->q;
    if (!c->join || q->face_start[f + 1] - q->face_start[f] != 3 || c->used[f]) return 0;
    for (int i = 0; i < 3; i++) {
        int j, g = across(q, c->E, c->nc, f, i, &j);
        if (g < 0 || c->used[g] || q->face_start[g + 1] - q->face_start[g] != 4) return 0;
    }
    return 1;
}

/* A strip's costs: one per quad cut in two, STRIP_TURN more for a quad
 * turned through (three quads about a new vertex: a 3-5 pair). */
#define STRIP_TURN 4

/* Whether quad g is across a side of face A. */
static int joined_quad(const strip_ctx *c, int A, int g)
{
    const int n = c->q->face_start[A + 1] - c->q->face_start[A];
    for (int i = 0; i < n; i++) {
        int j;
        if (across(c->q, c->E, c->nc, A, i, &j) == g) return 1;
    }
    return 0;
}

/* Whether lone triangle T joins the quad across its side i into a pentagon
 * (merged: the quad's far corners are not T's; a triangle folded onto its
 * quad, or one sharing two sides with it, is not joined). */
static int joinable(const strip_ctx *c, int T, int i)
{
    int j, p[10];
    const int g = across(c->q, c->E, c->nc, T, i, &j);
    return g >= 0 && c->q->face_start[g + 1] - c->q->face_start[g] == 4 && merged(c->q, T, i, g, j, p) == 5;
}

/* Cheapest path (Dijkstra over (quad, entry side) states) from odd face A
 * through unused quads (straight on, or turning at STRIP_TURN more) to
 * another unused odd face or the boundary; applies the strip (marks, new
 * vertices). *found 1 when one was found. */
static glpgp_status find_strip(strip_ctx *c, int A, int *found)
{
    const glpgp_quadmesh *q = c->q;
    *found = 0;
    int ntouch = 0, endB = -1000000, endBside = -1, endState = -1, endCost = INT_MAX; /* endB < 0: the boundary */
    const int nA = q->face_start[A + 1] - q->face_start[A];
    const int sA = strip_side(c, A);
    glpgp_status st = GLPGP_OK;
    const int loneA = lone_triangle(c, A);
    c->heap.n = 0;
    c->end_mq = -1;
    for (int i = 0; i < nA; i++) {
        if (!c->any_side && !loneA && i != sA) continue;
        int j, g = across(q, c->E, c->nc, A, i, &j), from = strip_from(i, 0); /* from A's side i */
        if (loneA && g >= 0 && !joinable(c, A, i)) continue;
        if (loneA && g >= 0) { /* A joined with g: the strip starts at g's far side */
            from = strip_from(i, 1);
            g = across(q, c->E, c->nc, g, (j + 2) % 4, &j);
        }
        if (g < 0 || c->used[g] || q->face_start[g + 1] - q->face_start[g] != 4 || c->par[4 * g + j] != -2) continue;
        c->par[4 * g + j] = from;
        c->dist[4 * g + j] = 1;
        c->queue[ntouch++] = 4 * g + j;
        if (st == GLPGP_OK) st = glpgp_heap_push(&c->heap, 1.0, 4 * g + j);
    }
    while (st == GLPGP_OK && c->heap.n) {
        const glpgp_heap_item it = glpgp_heap_pop(&c->heap);
        const int d = (int)it.key, s = it.id;
        if (d >= endCost) break;
        if (d > c->dist[s]) continue;
        const int g = s / 4, j = s % 4;
        for (int turn = 0; turn < 3; turn++) {
            const int e = (j + (turn == 0 ? 2 : turn == 1 ? 1 : 3)) % 4, dd = d + (turn ? STRIP_TURN : 0);
            int k, hf = across(q, c->E, c->nc, g, e, &k);
            if (hf < 0 && boundary_side(q, c->E, c->nc, g, e)) { /* a strip to the boundary */
                if (dd < endCost) endCost = dd, endB = -1 - e, endState = s, c->end_mq = -1; /* -1 - the exit side */
                continue;
            }
            if (hf < 0 || hf == A || c->used[hf]) continue;
            const int nh = q->face_start[hf + 1] - q->face_start[hf];
            if (nh == 4 && turn == 0 && dd + 1 < endCost) { /* straight on through hf into a lone triangle */
                int kb, B = across(q, c->E, c->nc, hf, (k + 2) % 4, &kb);
                if (B >= 0 && B != A && lone_triangle(c, B) && joinable(c, B, kb) && !(loneA && joined_quad(c, A, hf)))
                    endCost = dd + 1, endB = B, endBside = -1, endState = s, c->end_mq = hf, c->end_mk = k;
            }
            if (nh == 3 && lone_triangle(c, hf)) continue; /* entered only through a quad joined to it */
            if (nh % 2 && (c->any_side || k == strip_side(c, hf))) {
                if (dd < endCost) endCost = dd, endB = hf, endBside = k, endState = s, c->end_mq = -1;
            } else if (nh == 4) {
                const int ns = 4 * hf + k;
                if (c->par[ns] != -2 && c->dist[ns] <= dd + 1) continue;
                if (c->par[ns] == -2) c->queue[ntouch++] = ns;
                c->par[ns] = s;
                c->dist[ns] = dd + 1;
                if ((st = glpgp_heap_push(&c->heap, dd + 1.0, ns)) != GLPGP_OK) break;
            }
        }
    }
    if (st == GLPGP_OK && endB != -1000000) st = apply_strip(c, A, endB, endBside, endState, found);
    for (int i = 0; i < ntouch; i++) c->par[c->queue[i]] = -2;
    return st;
}
/* Face f of the strips' result into r (its corners from w on); returns the new w. */
static int emit_face(const strip_ctx *c, int f, glpgp_quadmesh *r, int *o, int w)
{
    const glpgp_quadmesh *q = c->q;
    const int s = q->face_start[f], n = q->face_start[f + 1] - s;
    const unsigned char org = q->face_origin ? q->face_origin[f] : GLPGP_QFACE_GRID;
    if (c->exit_side[f] >= 0) {
        const int *G = q->face_vert + s, j = c->entry_side[f], e = c->exit_side[f];
        const int mi = c->mid_in[f], mo = c->mid_out[f], C = c->center[f];
        int qs[3][4], nq;
        if ((e - j + 4) % 4 == 2) {
            int a[2][4] = {{G[(j + 1) % 4], G[(j + 2) % 4], mo, mi}, {G[(j + 3) % 4], G[j], mi, mo}};
            memcpy(qs, a, sizeof a);
            nq = 2;
        } else if ((e - j + 4) % 4 == 1) {
            int a[3][4] = {{mi, G[(j + 1) % 4], mo, C}, {G[(j + 3) % 4], G[j], mi, C}, {G[(j + 2) % 4], G[(j + 3) % 4], C, mo}};
            memcpy(qs, a, sizeof a);
            nq = 3;
        } else {
            int a[3][4] = {{G[j], mi, C, mo}, {mi, G[(j + 1) % 4], G[(j + 2) % 4], C}, {C, G[(j + 2) % 4], G[(j + 3) % 4], mo}};
            memcpy(qs, a, sizeof a);
            nq = 3;
        }
        for (int k = 0; k < nq; k++) {
            r->face_start[*o] = w;
            r->face_origin[(*o)++] = GLPGP_QFACE_CLOSED;
            for (int x = 0; x < 4; x++) r->face_vert[w++] = qs[k][x];
        }
        return w;
    }
    if (c->tri_joined[f]) return w; /* a lone triangle: in its quad's hexagon */
    if (c->mtri[f] >= 0) { /* the quad and its lone triangle: (b, c, a, y, x) and the midpoint */
        const int T = c->mtri[f], jg = c->mside[f];
        int iT = -1, p[10];
        for (int i = 0; i < 3; i++) {
            int jj;
            if (across(q, c->E, c->nc, T, i, &jj) == f && jj == jg) iT = i;
        }
        if (iT < 0 || merged(q, T, iT, f, jg, p) != 5) return -1;
        const int after = 1 + (c->ins[f] - jg + 4) % 4; /* g's side jg + d is the pentagon's side 1 + d */
        r->face_start[*o] = w;
        r->face_origin[(*o)++] = GLPGP_QFACE_CLOSED;
        for (int i = 0; i < 5; i++) {
            r->face_vert[w++] = p[i];
            if (i == after) r->face_vert[w++] = c->insv[f];
        }
        return w;
    }
    r->face_start[*o] = w;
    r->face_origin[(*o)++] = c->ins[f] >= 0 ? GLPGP_QFACE_CLOSED : org;
    for (int i = 0; i < n; i++) {
        r->face_vert[w++] = q->face_vert[s + i];
        if (i == c->ins[f]) r->face_vert[w++] = c->insv[f];
    }
    return w;
}

static void strip_free(strip_ctx *c)
{
    free(c->used);
    free(c->par);
    free(c->queue);
    free(c->ins);
    free(c->insv);
    free(c->exit_side);
    free(c->entry_side);
    free(c->mid_in);
    free(c->mid_out);
    free(c->center);
    free(c->xyz);
    free(c->dist);
    glpgp_heap_free(&c->heap);
    free(c->mtri);
    free(c->mside);
    free(c->tri_joined);
}

/* Odd faces joined pairwise by strips of quads cut in two (three at a
 * turn; any_side 0: leaving and entering the odd faces only through the
 * side opposite their flattest corner, so the new quads keep no flat
 * corner; 1: any side, pentagons and triangles alike), through the nearest other odd face or boundary side
 * (breadth-first over the quads; a new boundary vertex on the side's
 * chord, moved onto the surface); the odd faces become even (close_pairs splits them). *out NULL
 * when no strip was found; *nstrips: strips made. */
static glpgp_status strips(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, int any_side, int join,
                           glpgp_quadmesh **out, int *nstrips)
{
    *out = NULL;
    *nstrips = 0;
    strip_ctx c;
    memset(&c, 0, sizeof c);
    c.any_side = any_side;
    c.join = join;
    c.q = q;
    c.nc = q->face_start[q->nf];
    c.nv = q->nv;
    fedge *E = NULL;
    glpgp_quadmesh *r = NULL;
    const size_t nf = (size_t)q->nf + 1;
    glpgp_status st = build_fedges(q, &E);
    c.E = E;
    if (st == GLPGP_OK) st = glpgp_calloc(nf, 1, &c.used);
    int **arr[] = {&c.ins, &c.insv, &c.exit_side, &c.entry_side, &c.mid_in, &c.mid_out, &c.center, &c.mtri, &c.mside};
    for (int k = 0; k < 9 && st == GLPGP_OK; k++) st = glpgp_malloc(nf, sizeof(int), arr[k]);
    if (st == GLPGP_OK) st = glpgp_calloc(nf, 1, &c.tri_joined);
    if (st == GLPGP_OK) st = glpgp_malloc(4 * nf, sizeof(int), &c.par);
    if (st == GLPGP_OK) st = glpgp_malloc(4 * nf, sizeof(int), &c.queue);
    if (st == GLPGP_OK) st = glpgp_malloc(4 * nf, sizeof(int), &c.dist);
    if (st != GLPGP_OK) goto done;
    for (size_t i = 0; i < nf; i++) c.ins[i] = c.exit_side[i] = c.mtri[i] = c.mside[i] = -1;
    for (size_t i = 0; i < 4 * nf; i++) c.par[i] = -2;
    for (int f = 0; f < q->nf; f++) {
        if (!is_odd(q, f) || c.used[f]) continue;
        int found = 0;
        GLPGP_CHECK_GOTO(st, find_strip(&c, f, &found), done);
        *nstrips += found;
    }
    if (!*nstrips) goto done;
    int nfo = 0, ncr = 0;
    for (int f = 0; f < q->nf; f++) {
        const int n = q->face_start[f + 1] - q->face_start[f];
        if (c.exit_side[f] >= 0) {
            nfo += 3;
            ncr += 12;
        } else {
            nfo++;
            ncr += n + 1;
        }
    }
    GLPGP_CHECK_GOTO(st, glpgp_qs_alloc(c.nv, nfo, ncr, &r), done);
    memcpy(r->xyz, q->xyz, (size_t)3 * q->nv * sizeof(double));
    if (c.nv > q->nv) memcpy(r->xyz + 3 * q->nv, c.xyz, (size_t)3 * (c.nv - q->nv) * sizeof(double));
    int o = 0, w = 0;
    for (int f = 0; f < q->nf && w >= 0; f++) w = emit_face(&c, f, r, &o, w);
    if (w < 0) { /* a joined quad that is not across its triangle (joinable prevents it): no strips */
        glpgp_log(GLPGP_LOG_DEBUG, "quads: surface strips: a lone triangle's quad lost; the strips not used");
        *nstrips = 0;
        goto done;
    }
    r->nf = o;
    r->face_start[o] = w;
    GLPGP_CHECK_GOTO(st, glpgp_qs_project(m, h, r->xyz, q->nv, r->nv), done);
    glpgp_qs_finish_from(r, q);
    *out = r;
    r = NULL;
done:
    glpgp_quadmesh_destroy(&r);
    free(E);
    strip_free(&c);
    return st;
}

int glpgp_qs_count_nonquads(const glpgp_quadmesh *q)
{
    int n = 0;
    for (int f = 0; f < q->nf; f++) n += q->face_start[f + 1] - q->face_start[f] != 4;
    return n;
}

/* Irregular interior vertices of q (valence not 4; -1 without memory). */
int glpgp_qs_irregular_interior(const glpgp_quadmesh *q)
{
    fedge *E = NULL;
    int *val = NULL, n = -1;
    if (build_fedges(q, &E) == GLPGP_OK && vertex_valences(q, E, &val) == GLPGP_OK) {
        n = 0;
        for (int v = 0; v < q->nv; v++) n += val[v] >= 0 && val[v] != 4;
    }
    glpgp_error_clear();
    free(E);
    free(val);
    return n;
}

/* The odd faces of q joined by strips and closed (close_pairs), in four
 * passes: through the T-junctions' sides or any side, each joining the
 * lone triangles with a quad (lone_triangle) or reaching them like any odd
 * face. *out: of the all-quad results the one with the fewest irregular
 * interior vertices, the earlier pass on a tie (NULL: none); *nstrips,
 * *nclosed its counts. */
glpgp_status glpgp_qs_strips_closed(const glpgp_mesh *m, double h, const glpgp_quadmesh *q, glpgp_quadmesh **out,
                                    int *nstrips, int *nclosed)
{
    static const int pass_any[4] = {0, 1, 0, 1}, pass_join[4] = {1, 1, 0, 0};
    glpgp_quadmesh *t = NULL, *t2 = NULL;
    int best = INT_MAX;
    *out = NULL;
    *nstrips = *nclosed = 0;
    glpgp_status st = GLPGP_OK;
    for (int k = 0; k < 4 && st == GLPGP_OK; k++) {
        int ns = 0, cl = 0;
        glpgp_quadmesh_destroy(&t);
        glpgp_quadmesh_destroy(&t2);
        st = strips(m, q, h, pass_any[k], pass_join[k], &t, &ns);
        if (st == GLPGP_OK && t) st = glpgp_qs_close_pairs(m, h, t, &t2, &cl);
        if (st != GLPGP_OK || !t2 || glpgp_qs_count_nonquads(t2)) continue;
        const int irr = glpgp_qs_irregular_interior(t2);
        glpgp_log(GLPGP_LOG_DEBUG, "quads: surface strips (pass %d): %d strips, all quads, %d irregular interior", k,
                  ns, irr);
        if (irr >= 0 && irr < best) {
            best = irr;
            glpgp_quadmesh_destroy(out);
            *out = t2;
            t2 = NULL;
            *nstrips = ns;
            *nclosed = cl;
        }
    }
    glpgp_quadmesh_destroy(&t);
    glpgp_quadmesh_destroy(&t2);
    return st;
}

