/* quads/quads_surface.c: the quad pipeline on a 3D surface
 * (glpgp_quads_build_surface, glpgp/quads.h): the extraction
 * (extract_surface.c), the closing, the local repair (repair_surface.c),
 * the local split of the bad faces and their quad strips (split_surface.c),
 * one Catmull-Clark split in 3D when those leave it invalid, the check
 * (check_surface.c), and the last resort that cannot fail: the input
 * triangles split into three quads each; then the smoothing and the split
 * of flat boundary corners (split_surface.c). */
#include "quads_surface.h"

#include "glpgp/surface.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

glpgp_status glpgp_qs_alloc(int nv, int nf, int ncorner, glpgp_quadmesh **out)
{
    glpgp_quadmesh *q = NULL;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *q, &q));
    q->nv = nv;
    q->nf = nf;
    glpgp_status st = glpgp_malloc((size_t)3 * nv + 1, sizeof(double), &q->xyz);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)2 * nv + 1, sizeof(double), &q->xy);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nf + 1, sizeof(int), &q->face_start);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)ncorner + 1, sizeof(int), &q->face_vert);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)nf + 1, 1, &q->face_origin);
    if (st != GLPGP_OK) {
        glpgp_quadmesh_destroy(&q);
        return st;
    }
    *out = q;
    return GLPGP_OK;
}

static void set_xy(glpgp_quadmesh *q)
{
    for (int i = 0; i < q->nv; i++) {
        q->xy[2 * i] = q->xyz[3 * i];
        q->xy[2 * i + 1] = q->xyz[3 * i + 1];
    }
}

void glpgp_qs_finish_from(glpgp_quadmesh *r, const glpgp_quadmesh *q)
{
    set_xy(r);
    memcpy(r->singular_tris, q->singular_tris, sizeof r->singular_tris);
    memcpy(r->inconsistent_tris, q->inconsistent_tris, sizeof r->inconsistent_tris);
}

static int cmp_ll(const void *pa, const void *pb)
{
    const long long *a = pa, *b = pb;
    return a[0] < b[0] ? -1 : a[0] > b[0] ? 1 : 0;
}

glpgp_status glpgp_qs_split_triangles(const double *xyz, int np, const int *tri, int nt, glpgp_quadmesh **out)
{
    *out = NULL;
    long long *key = NULL; /* (edge key, slot) pairs */
    int *mid = NULL;
    glpgp_quadmesh *q = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)6 * nt + 2, sizeof(long long), &key), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt + 1, sizeof(int), &mid), done);
    for (int s = 0; s < 3 * nt; s++) {
        const long long a = tri[s], b = tri[s - s % 3 + (s % 3 + 1) % 3];
        key[2 * s] = a < b ? a * np + b : b * np + a;
        key[2 * s + 1] = s;
    }
    qsort(key, (size_t)3 * nt, 2 * sizeof(long long), cmp_ll);
    int nv = np;
    for (int i = 0; i < 3 * nt; i++) {
        if (i == 0 || key[2 * i] != key[2 * i - 2]) nv++;
        mid[key[2 * i + 1]] = nv - 1;
    }
    const int cen = nv;
    nv += nt;
    GLPGP_CHECK_GOTO(st, glpgp_qs_alloc(nv, 3 * nt, 12 * nt, &q), done);
    memcpy(q->xyz, xyz, (size_t)3 * np * sizeof(double));
    for (int t = 0; t < nt; t++) {
        const int *v = tri + 3 * t;
        for (int d = 0; d < 3; d++) {
            q->xyz[3 * (cen + t) + d] = (xyz[3 * v[0] + d] + xyz[3 * v[1] + d] + xyz[3 * v[2] + d]) / 3.0;
            for (int k = 0; k < 3; k++)
                q->xyz[3 * mid[3 * t + k] + d] = 0.5 * (xyz[3 * v[k] + d] + xyz[3 * v[(k + 1) % 3] + d]);
        }
        for (int a = 0; a < 3; a++) {
            const int f = 3 * t + a;
            q->face_start[f] = 4 * f;
            q->face_vert[4 * f] = v[a];
            q->face_vert[4 * f + 1] = mid[3 * t + a];
            q->face_vert[4 * f + 2] = cen + t;
            q->face_vert[4 * f + 3] = mid[3 * t + (a + 2) % 3];
            q->face_origin[f] = GLPGP_QFACE_FALLBACK;
        }
    }
    q->face_start[q->nf] = 4 * q->nf;
    set_xy(q);
    *out = q;
done:
    free(key);
    free(mid);
    return st;
}

glpgp_status glpgp_quads_surface_fallback(const glpgp_mesh *m, glpgp_quadmesh **out)
{
    *out = NULL;
    if (!glpgp_mesh_is_surface(m) || !m->surf) return GLPGP_FAIL(GLPGP_ERR_ARG, "surface fallback: not a surface");
    return glpgp_qs_split_triangles(m->xyz, m->nv, m->tri, m->nt, out);
}

glpgp_status glpgp_quadmesh_subdivide_surface(const glpgp_quadmesh *q, glpgp_quadmesh **out)
{
    *out = NULL;
    if (!q || !q->xyz || q->nf == 0) return GLPGP_FAIL(GLPGP_ERR_ARG, "surface subdivision: an empty or planar mesh");
    const int nc = q->face_start[q->nf];
    long long *key = NULL; /* (edge key, corner) pairs */
    int *mid = NULL;
    glpgp_quadmesh *r = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nc + 2, sizeof(long long), &key), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof(int), &mid), done);
    for (int f = 0; f < q->nf; f++) {
        const int s = q->face_start[f], n = q->face_start[f + 1] - s;
        for (int i = 0; i < n; i++) {
            long long a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % n];
            key[2 * (s + i)] = a < b ? a * q->nv + b : b * q->nv + a;
            key[2 * (s + i) + 1] = s + i;
        }
    }
    qsort(key, (size_t)nc, 2 * sizeof(long long), cmp_ll);
    int nv = q->nv;
    for (int i = 0; i < nc; i++) {
        if (i == 0 || key[2 * i] != key[2 * i - 2]) nv++;
        mid[key[2 * i + 1]] = nv - 1;
    }
    const int nedge_v = nv;
    nv += q->nf;
    GLPGP_CHECK_GOTO(st, glpgp_qs_alloc(nv, nc, 4 * nc, &r), done);
    memcpy(r->xyz, q->xyz, (size_t)3 * q->nv * sizeof(double));
    for (int f = 0, o = 0; f < q->nf; f++) {
        const int s = q->face_start[f], n = q->face_start[f + 1] - s, c = nedge_v + f;
        for (int d = 0; d < 3; d++) r->xyz[3 * c + d] = 0.0;
        for (int i = 0; i < n; i++) {
            const int a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % n];
            for (int d = 0; d < 3; d++) {
                r->xyz[3 * mid[s + i] + d] = 0.5 * (q->xyz[3 * a + d] + q->xyz[3 * b + d]);
                r->xyz[3 * c + d] += q->xyz[3 * a + d] / n;
            }
        }
        for (int i = 0; i < n; i++, o++) {
            r->face_start[o] = 4 * o;
            r->face_vert[4 * o] = q->face_vert[s + i];
            r->face_vert[4 * o + 1] = mid[s + i];
            r->face_vert[4 * o + 2] = c;
            r->face_vert[4 * o + 3] = mid[s + (i + n - 1) % n];
            r->face_origin[o] = q->face_origin ? q->face_origin[f] : GLPGP_QFACE_GRID;
        }
    }
    r->face_start[nc] = 4 * nc;
    glpgp_qs_finish_from(r, q);
    *out = r;
    r = NULL;
done:
    glpgp_quadmesh_destroy(&r);
    free(key);
    free(mid);
    return st;
}

/* ---- closing: two odd faces sharing a side, even faces ---- */

static double sj4(const double *xyz, const int *v)
{
    double N[3] = {0, 0, 0};
    for (int i = 0; i < 4; i++) {
        const double *a = xyz + 3 * v[i], *b = xyz + 3 * v[(i + 1) % 4];
        N[0] += (a[1] - b[1]) * (a[2] + b[2]);
        N[1] += (a[2] - b[2]) * (a[0] + b[0]);
        N[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    const double nn = sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
    if (!(nn > 0)) return -1.0;
    double sj = 1.0;
    for (int i = 0; i < 4; i++) {
        const double *p = xyz + 3 * v[i], *a = xyz + 3 * v[(i + 1) % 4], *b = xyz + 3 * v[(i + 3) % 4];
        const double e1[3] = {a[0] - p[0], a[1] - p[1], a[2] - p[2]}, e2[3] = {b[0] - p[0], b[1] - p[1], b[2] - p[2]};
        const double l = sqrt((e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]) * (e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]));
        if (!(l > 0)) return -1.0;
        const double x[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        sj = fmin(sj, (x[0] * N[0] + x[1] * N[1] + x[2] * N[2]) / (nn * l));
    }
    return sj;
}

/* The best split of polygon p (n even, 4..10 vertices) into n/2 - 1 quads
 * (q: 4 per quad), cutting off one quad of consecutive corners at a time;
 * returns its smallest scaled Jacobian (-2 when none). */
static double split_even(const double *xyz, const int *p, int n, int *q)
{
    if (n == 4) {
        memcpy(q, p, 4 * sizeof *p);
        return sj4(xyz, p);
    }
    double best = -2.0;
    int rest[10], sub[16], cut[4];
    for (int i = 0; i < n; i++) {
        for (int k = 0; k < 4; k++) cut[k] = p[(i + k) % n];
        const double a = sj4(xyz, cut);
        if (a <= best) continue;
        int m = 0;
        for (int k = 3; k <= n; k++) rest[m++] = p[(i + k) % n]; /* p[i+3] .. p[i] */
        const double b = split_even(xyz, rest, m, sub);
        if (fmin(a, b) > best) {
            best = fmin(a, b);
            memcpy(q, cut, sizeof cut);
            memcpy(q + 4, sub, (size_t)(m / 2 - 1) * 4 * sizeof *q);
        }
    }
    return best;
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

/* Odd faces paired with an odd neighbour across a side, and the even
 * faces (up to 10 corners), split into quads where all have a scaled
 * Jacobian above 0.05 (the best split); *closed: faces made quads. */
static glpgp_status close_pairs(const glpgp_quadmesh *q, glpgp_quadmesh **out, int *closed)
{
    *out = NULL;
    *closed = 0;
    const int nc = q->face_start[q->nf];
    fedge *E = NULL;
    unsigned char *used = NULL;
    int *newq = NULL, nnew = 0;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, build_fedges(q, &E), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)q->nf + 1, 1, &used), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * nc + 8, sizeof(int), &newq), done);
    for (int f = 0; f < q->nf; f++) {
        const int n = q->face_start[f + 1] - q->face_start[f];
        int p[10], qd[16], bq[16], bn = 0;
        double best = 0.05;
        int bg = -1;
        if (used[f] || n == 4 || n > 10) continue;
        if (n % 2 == 0) {
            memcpy(p, q->face_vert + q->face_start[f], (size_t)n * sizeof *p);
            if (split_even(q->xyz, p, n, qd) > best) {
                memcpy(newq + 4 * nnew, qd, (size_t)(n / 2 - 1) * 4 * sizeof *qd);
                nnew += n / 2 - 1;
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
            const double sj = split_even(q->xyz, p, nm, qd);
            if (sj > best) {
                best = sj;
                bg = g;
                bn = nm;
                memcpy(bq, qd, sizeof qd);
            }
        }
        if (bg >= 0) {
            used[f] = used[bg] = 1;
            memcpy(newq + 4 * nnew, bq, (size_t)(bn / 2 - 1) * 4 * sizeof *bq);
            nnew += bn / 2 - 1;
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
        GLPGP_CHECK_GOTO(st, glpgp_qs_alloc(q->nv, nf, ncr, &r), done);
        memcpy(r->xyz, q->xyz, (size_t)3 * q->nv * sizeof(double));
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
    free(used);
    free(newq);
    return st;
}

/* ---- strips: an odd face joined to another through a strip of quads ---- */

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
    if (B < 0) e = -1 - B; /* to the boundary: the last quad's exit side */
    else { /* B's side is entered through the last quad's side across it */
        const int g = last / 4;
        for (int k = 0; k < 4; k++) {
            int jj, gg = across(q, c->E, c->nc, g, k, &jj);
            if (gg == B && jj == bside) e = k;
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
    double p3[3];
    int m;
    side_mid(q, A, startSide, p3);
    GLPGP_CHECK(new_vertex(c, p3, &m));
    c->ins[A] = startSide;
    c->insv[A] = m;
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
    if (B >= 0) {
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
static int strip_side(const glpgp_quadmesh *q, int f)
{
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

/* Breadth-first from odd face A through unused quads (straight on or
 * turning) to another unused odd face; applies the strip (marks, new
 * vertices). Returns 1 when one was found. */
static glpgp_status find_strip(strip_ctx *c, int A, int *found)
{
    const glpgp_quadmesh *q = c->q;
    *found = 0;
    int head = 0, tail = 0, endB = -1000000, endBside = -1, endState = -1; /* endB < 0: the boundary */
    const int nA = q->face_start[A + 1] - q->face_start[A];
    const int sA = strip_side(q, A);
    for (int i = 0; i < nA; i++) {
        if (!c->any_side && i != sA) continue;
        int j, g = across(q, c->E, c->nc, A, i, &j);
        if (g < 0 || c->used[g] || q->face_start[g + 1] - q->face_start[g] != 4 || c->par[4 * g + j] != -2) continue;
        c->par[4 * g + j] = -3 - i; /* from A's side i */
        c->queue[tail++] = 4 * g + j;
    }
    while (head < tail && endB == -1000000) {
        const int st = c->queue[head++], g = st / 4, j = st % 4;
        for (int turn = 0; turn < 3 && endB == -1000000; turn++) {
            const int e = (j + (turn == 0 ? 2 : turn == 1 ? 1 : 3)) % 4;
            int k, h = across(q, c->E, c->nc, g, e, &k);
            if (h < 0 && boundary_side(q, c->E, c->nc, g, e)) { /* a strip to the boundary */
                endB = -1 - e; /* -1 - the exit side */
                endState = st;
                break;
            }
            if (h < 0 || h == A || c->used[h]) continue;
            const int nh = q->face_start[h + 1] - q->face_start[h];
            if (nh % 2 && (c->any_side || k == strip_side(q, h))) {
                endB = h;
                endBside = k;
                endState = st;
            } else if (nh == 4 && c->par[4 * h + k] == -2) {
                c->par[4 * h + k] = st;
                c->queue[tail++] = 4 * h + k;
            }
        }
    }
    glpgp_status st = GLPGP_OK;
    if (endB != -1000000) st = apply_strip(c, A, endB, endBside, endState, found);
    for (int i = 0; i < tail; i++) c->par[c->queue[i]] = -2;
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
}

/* Odd faces joined pairwise by strips of quads cut in two (three at a
 * turn; any_side 0: leaving and entering the odd faces only through the
 * side opposite their flattest corner, so the new quads keep no flat
 * corner; 1: any side, pentagons and triangles alike), through the nearest other odd face or boundary side
 * (breadth-first over the quads; a new boundary vertex on the side's
 * chord, moved onto the surface); the odd faces become even (close_pairs splits them). *out NULL
 * when no strip was found; *nstrips: strips made. */
static glpgp_status strips(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, int any_side, glpgp_quadmesh **out,
                           int *nstrips)
{
    *out = NULL;
    *nstrips = 0;
    strip_ctx c;
    memset(&c, 0, sizeof c);
    c.any_side = any_side;
    c.q = q;
    c.nc = q->face_start[q->nf];
    c.nv = q->nv;
    fedge *E = NULL;
    glpgp_quadmesh *r = NULL;
    const size_t nf = (size_t)q->nf + 1;
    glpgp_status st = build_fedges(q, &E);
    c.E = E;
    if (st == GLPGP_OK) st = glpgp_calloc(nf, 1, &c.used);
    int **arr[] = {&c.ins, &c.insv, &c.exit_side, &c.entry_side, &c.mid_in, &c.mid_out, &c.center};
    for (int k = 0; k < 7 && st == GLPGP_OK; k++) st = glpgp_malloc(nf, sizeof(int), arr[k]);
    if (st == GLPGP_OK) st = glpgp_malloc(4 * nf, sizeof(int), &c.par);
    if (st == GLPGP_OK) st = glpgp_malloc(4 * nf, sizeof(int), &c.queue);
    if (st != GLPGP_OK) goto done;
    for (size_t i = 0; i < nf; i++) c.ins[i] = c.exit_side[i] = -1;
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
    for (int f = 0; f < q->nf; f++) w = emit_face(&c, f, r, &o, w);
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

static int count_nonquads(const glpgp_quadmesh *q)
{
    int n = 0;
    for (int f = 0; f < q->nf; f++) n += q->face_start[f + 1] - q->face_start[f] != 4;
    return n;
}

/* Its Catmull-Clark split with the new points on the surface. */
static glpgp_status split_onto(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, glpgp_quadmesh **out)
{
    glpgp_status st = glpgp_quadmesh_subdivide_surface(q, out);
    if (st == GLPGP_OK) st = glpgp_qs_project(m, h, (*out)->xyz, q->nv, (*out)->nv);
    if (st == GLPGP_OK) set_xy(*out);
    else glpgp_quadmesh_destroy(out);
    return st;
}

/* The names of the GLPGP_QUADS_BAD_* bits in bad, comma-separated. */
static void bad_names(unsigned bad, char *why, size_t n)
{
    size_t w = 0;
    why[0] = 0;
    for (int b = 0; b < GLPGP_QUADS_BAD_COUNT && w < n; b++)
        if (bad & (1u << b)) {
            int k = snprintf(why + w, n - w, "%s%s", w ? ", " : "", glpgp_quads_bad_name(1u << b));
            if (k > 0) w += (size_t)k;
        }
}

/* The invalidity bits of q (less non-quads with keep_polygons). */
static glpgp_status verdict_of(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, int keep_polygons,
                               unsigned *bad)
{
    glpgp_quads_report qq;
    GLPGP_CHECK(glpgp_quads_quality_surface(q, m, h, &qq));
    *bad = qq.invalid & ~(keep_polygons ? (unsigned)GLPGP_QUADS_BAD_NONQUAD : 0u);
    if (*bad) { /* which checks failed, by name */
        char why[256];
        bad_names(*bad, why, sizeof why);
        glpgp_log(GLPGP_LOG_DEBUG,
                  "quads: surface candidate of %d faces not valid: %s (Hausdorff %.3f h, area ratio %.4f, %d inverted, "
                  "%d not quads)",
                  q->nf, why, qq.hausdorff, qq.area_ratio, qq.inverted, qq.others);
    }
    return GLPGP_OK;
}

/* The regions of a local repair pass b added to those of the passes before (a). */
static void add_regions(glpgp_quads_repair *a, const glpgp_quads_repair *b, int pass)
{
    a->rounds += b->rounds;
    a->regions += b->regions;
    a->paved_regions += b->paved_regions;
    a->removed_faces += b->removed_faces;
    a->new_quads += b->new_quads;
    for (int i = 0; i < b->nlisted && a->nlisted < GLPGP_QUADS_REGIONS_LISTED; i++) {
        a->region[a->nlisted] = b->region[i];
        a->region[a->nlisted++].round = pass;
    }
}

/* The local repair of q (glpgp_qs_local_repair; far: faces far from the
 * surface repaired too), run again on what a pass left bad (3 passes):
 * *out the last pass's mesh (NULL: no region repaired), *bad its
 * invalidity bits, *rs the regions of every pass. */
static glpgp_status local_repair(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, int far, glpgp_quadmesh **out,
                                 unsigned *bad, glpgp_quads_repair *rs)
{
    glpgp_quads_repair one;
    glpgp_quads_report qq;
    memset(rs, 0, sizeof *rs);
    *out = NULL;
    *bad = 0;
    for (int pass = 0; pass < 3; pass++) {
        glpgp_quadmesh *r = NULL;
        GLPGP_CHECK(glpgp_qs_local_repair(m, *out ? *out : q, h, far, &r, &one));
        if (!r) break;
        glpgp_quadmesh_destroy(out);
        *out = r;
        add_regions(rs, &one, pass);
        GLPGP_CHECK(glpgp_quads_quality_surface(*out, m, h, &qq));
        *bad = qq.invalid;
        glpgp_log(GLPGP_LOG_DEBUG,
                  "quads: surface local repair (pass %d%s): %d regions, %d faces -> %d quads; %s (0x%x: %d inverted, "
                  "Hausdorff %.3f h (quads->surface %.3f, surface->quads %.3f), area ratio %.4f)",
                  pass, far ? ", far faces too" : "", one.regions, one.removed_faces, one.new_quads,
                  *bad ? "not valid" : "valid", *bad, qq.inverted, qq.hausdorff, qq.dist_quad_to_domain,
                  qq.dist_domain_to_quad, qq.area_ratio);
        if (!*bad) break;
    }
    if (*out) {
        memset(&(*out)->closing, 0, sizeof (*out)->closing);
        (*out)->repair = *rs;
    }
    return GLPGP_OK;
}

/* The local repair's regions into stp. */
static void note_local(glpgp_quads_surface_steps *stp, const glpgp_quads_repair *rs)
{
    stp->local_regions = rs->regions;
    stp->local_faces_in = rs->removed_faces;
    stp->local_quads_out = rs->new_quads;
    stp->local_sj_min = 1.0;
    for (int i = 0; i < rs->nlisted; i++) stp->local_sj_min = fmin(stp->local_sj_min, rs->region[i].sj_min);
}

static glpgp_status split_local_repair(const glpgp_mesh *m, const glpgp_quadmesh *base, double h,
                                       glpgp_quads_surface_steps *stp, glpgp_quadmesh **out);

/* The local repair's candidates: the repaired mesh (bad faces but the far
 * ones); with split, when only the distance or the area fails (a grid too
 * coarse for the surface somewhere): the local split of its far faces, the
 * repair with the far faces too, then its whole split; last (or without
 * split) the repair with the far faces too. *out NULL: none is valid. */
static glpgp_status repaired(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, int split,
                             glpgp_quads_surface_steps *stp, glpgp_quadmesh **out)
{
    glpgp_quadmesh *r = NULL, *s = NULL;
    glpgp_quads_repair rs;
    unsigned bad = 0;
    int tried_far = 0;
    *out = NULL;
    glpgp_status st = local_repair(m, q, h, 0, &r, &bad, &rs);
    if (st == GLPGP_OK && r && !bad) goto keep_r;
    if (st == GLPGP_OK && r && split && !(bad & ~(unsigned)(GLPGP_QUADS_BAD_HAUSDORFF | GLPGP_QUADS_BAD_AREA))) {
        st = split_local_repair(m, r, h, stp, &s); /* the far faces split with their strips */
        if (st == GLPGP_OK && s) {
            glpgp_quadmesh_destroy(&r);
            *out = s;
            return GLPGP_OK;
        }
    }
    if (st == GLPGP_OK && r && split && !(bad & ~(unsigned)(GLPGP_QUADS_BAD_HAUSDORFF | GLPGP_QUADS_BAD_AREA))) {
        /* the far faces repaired too, before the whole mesh is split (4x the quads) */
        glpgp_quadmesh *f = NULL;
        glpgp_quads_repair fs;
        unsigned fbad = 0;
        tried_far = 1;
        st = local_repair(m, q, h, 1, &f, &fbad, &fs);
        if (st == GLPGP_OK && f && !fbad) {
            glpgp_quadmesh_destroy(&r);
            r = f;
            rs = fs;
            goto keep_r;
        }
        glpgp_quadmesh_destroy(&f);
    }
    if (st == GLPGP_OK && r && split && !(bad & ~(unsigned)(GLPGP_QUADS_BAD_HAUSDORFF | GLPGP_QUADS_BAD_AREA))) {
        st = split_onto(m, r, h, &s);
        if (st == GLPGP_OK) st = verdict_of(m, s, h, 0, &bad);
        if (st == GLPGP_OK && bad) { /* the split's own bad faces repaired locally */
            glpgp_quadmesh *t = NULL;
            glpgp_quads_surface_steps st2;
            memset(&st2, 0, sizeof st2);
            st = repaired(m, s, h, 0, &st2, &t);
            if (st == GLPGP_OK && t) {
                glpgp_quadmesh_destroy(&s);
                s = t;
                bad = 0;
                add_regions(&rs, &s->repair, 1);
            }
        }
        if (st == GLPGP_OK && !bad) {
            s->repair = rs;
            stp->subdivided = 1;
            note_local(stp, &rs);
            glpgp_quadmesh_destroy(&r);
            *out = s;
            return GLPGP_OK;
        }
        glpgp_quadmesh_destroy(&s);
    }
    glpgp_quadmesh_destroy(&r);
    if (st == GLPGP_OK && !tried_far) st = local_repair(m, q, h, 1, &r, &bad, &rs);
    if (st == GLPGP_OK && r && !bad) goto keep_r;
    glpgp_quadmesh_destroy(&r);
    return st;
keep_r:
    note_local(stp, &rs);
    *out = r;
    return GLPGP_OK;
}

/* The local split (glpgp_qs_split_local) of base's bad faces (the far ones
 * too) and the quad strips through them, then the local repair of what it
 * leaves bad; again (twice at most) on the partial repair of the split.
 * A split of over half the faces is left to the global split. *out NULL:
 * none is valid. */
static glpgp_status split_local_repair(const glpgp_mesh *m, const glpgp_quadmesh *base, double h,
                                       glpgp_quads_surface_steps *stp, glpgp_quadmesh **out)
{
    glpgp_quadmesh *own = NULL, *s = NULL, *t = NULL;
    unsigned char *sel = NULL;
    const glpgp_quadmesh *b = base;
    int split = 0;
    *out = NULL;
    glpgp_status st = glpgp_malloc((size_t)base->nf + 1, 1, &sel);
    for (int level = 0; level < 2 && st == GLPGP_OK && !*out; level++) {
        int nbad = 0, ns = 0;
        unsigned bad = 0;
        unsigned char *grown = realloc(sel, (size_t)b->nf + 1);
        if (!grown) st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory (local split)");
        else sel = grown;
        if (st == GLPGP_OK) st = glpgp_qs_bad_faces(m, b, h, 1, sel, &nbad);
        if (st != GLPGP_OK || nbad == 0) break;
        if (st == GLPGP_OK) st = glpgp_qs_split_local(m, b, h, sel, &s, &ns);
        if (st == GLPGP_OK && 2 * ns > b->nf) { /* the strips ran through most of the mesh: the global split's job */
            glpgp_log(GLPGP_LOG_DEBUG, "quads: local split %d: %d of %d faces split, not local", level, ns, b->nf);
            break;
        }
        if (st == GLPGP_OK) st = verdict_of(m, s, h, 0, &bad);
        if (st != GLPGP_OK) break;
        split += ns;
        glpgp_log(GLPGP_LOG_DEBUG, "quads: local split %d: %d bad faces of %d, %d faces split -> %d quads; %s", level,
                  nbad, b->nf, ns, s->nf, bad ? "not valid" : "valid");
        if (!bad) {
            *out = s;
            s = NULL;
            break;
        }
        glpgp_quads_surface_steps st2;
        memset(&st2, 0, sizeof st2);
        st = repaired(m, s, h, 0, &st2, &t);
        if (st == GLPGP_OK && t) {
            stp->local_regions = st2.local_regions;
            stp->local_faces_in = st2.local_faces_in;
            stp->local_quads_out = st2.local_quads_out;
            stp->local_sj_min = st2.local_sj_min;
            *out = t;
            t = NULL;
            break;
        }
        glpgp_quads_repair rs; /* the next level on the split's partial repair */
        glpgp_quadmesh *r = NULL;
        if (st == GLPGP_OK) st = local_repair(m, s, h, 1, &r, &bad, &rs);
        glpgp_quadmesh_destroy(&own);
        if (r) {
            own = r;
            glpgp_quadmesh_destroy(&s);
        } else {
            own = s;
            s = NULL;
        }
        b = own;
    }
    if (*out) stp->split_faces = split;
    glpgp_quadmesh_destroy(&own);
    glpgp_quadmesh_destroy(&s);
    glpgp_quadmesh_destroy(&t);
    free(sel);
    return st;
}

/* The candidates in order, the first valid one kept: the extraction (all
 * quads, or polygons with keep_polygons), the closed mesh when all quads,
 * the split of the closed mesh, the split of the extraction. *out NULL:
 * none is valid (*bad: the extraction's reasons). */
static glpgp_status candidates(const glpgp_mesh *m, glpgp_quadmesh **pq, const glpgp_quads_options *o, double h,
                               glpgp_quads_surface_steps *stp, glpgp_quadmesh **out, unsigned *bad0)
{
    glpgp_quadmesh *q = *pq, *c = NULL, *s = NULL;
    unsigned bad;
    *out = NULL;
    GLPGP_CHECK(verdict_of(m, q, h, o->keep_polygons, bad0));
    if (!*bad0 || o->keep_polygons || !o->repair) {
        *out = q;
        *pq = NULL;
        return GLPGP_OK;
    }
    glpgp_status st = close_pairs(q, &c, &stp->closed);
    if (st == GLPGP_OK)
        glpgp_log(GLPGP_LOG_DEBUG, "quads: surface closing: %d faces made quads, %d of %d faces not quads left",
                  stp->closed, c ? count_nonquads(c) : count_nonquads(q), c ? c->nf : q->nf);
    if (st == GLPGP_OK && count_nonquads(c ? c : q)) { /* strips between the odd faces left */
        glpgp_quadmesh *t = NULL, *t2 = NULL;
        int ns = 0, cl = 0;
        for (int any = 0; any < 2 && st == GLPGP_OK; any++) { /* through the T-junctions first, then any side */
            glpgp_quadmesh_destroy(&t);
            glpgp_quadmesh_destroy(&t2);
            st = strips(m, c ? c : q, h, any, &t, &ns);
            if (st == GLPGP_OK && t) st = close_pairs(t, &t2, &cl);
            if (st == GLPGP_OK && t2 && !count_nonquads(t2)) break;
        }
        if (st == GLPGP_OK && t2 && !count_nonquads(t2)) {
            glpgp_quadmesh_destroy(&c);
            c = t2;
            t2 = NULL;
            stp->strips = ns;
            stp->closed += cl;
        }
        glpgp_quadmesh_destroy(&t);
        glpgp_quadmesh_destroy(&t2);
        glpgp_log(GLPGP_LOG_DEBUG, "quads: surface strips: %d, %d faces not quads left", ns,
                  count_nonquads(c ? c : q));
    }
    if (st == GLPGP_OK && c && !count_nonquads(c)) {
        st = verdict_of(m, c, h, 0, &bad);
        if (st == GLPGP_OK && !bad) goto keep_c;
    }
    if (st == GLPGP_OK) {
        st = repaired(m, c ? c : q, h, 1, stp, &s);
        if (st == GLPGP_OK && s) goto keep_r;
    }
    if (st == GLPGP_OK) { /* the bad regions split with their quad strips, then repaired */
        st = split_local_repair(m, c ? c : q, h, stp, &s);
        if (st == GLPGP_OK && s) goto keep_r;
    }
    if (st == GLPGP_OK && c && count_nonquads(c) < count_nonquads(q)) {
        st = split_onto(m, c, h, &s);
        if (st == GLPGP_OK) st = verdict_of(m, s, h, 0, &bad);
        if (st == GLPGP_OK && !bad) goto keep_s;
        glpgp_log(GLPGP_LOG_DEBUG, "quads: the closed mesh's split is not valid (0x%x)", bad);
        if (st == GLPGP_OK) { /* its bad faces repaired locally */
            glpgp_quadmesh *r = NULL;
            st = repaired(m, s, h, 0, stp, &r);
            if (st == GLPGP_OK && r) {
                glpgp_quadmesh_destroy(&s);
                s = r;
                goto keep_s;
            }
        }
        glpgp_quadmesh_destroy(&s);
    }
    stp->closed = 0;
    if (st == GLPGP_OK) st = split_onto(m, q, h, &s);
    if (st == GLPGP_OK) st = verdict_of(m, s, h, 0, &bad);
    if (st == GLPGP_OK && !bad) goto keep_s;
    glpgp_quadmesh_destroy(&s);
    glpgp_quadmesh_destroy(&c);
    return st;
keep_c:
    memset(&c->closing, 0, sizeof c->closing); /* the surface's steps are in stp */
    *out = c;
    return GLPGP_OK;
keep_r:
    *out = s;
    glpgp_quadmesh_destroy(&c);
    return GLPGP_OK;
keep_s:
    stp->subdivided = 1;
    *out = s;
    glpgp_quadmesh_destroy(&c);
    return GLPGP_OK;
}

/* The smoothing on the surface (o->smooth sweeps, glpgp_quads_smooth_surface) of a
 * valid mesh, undone when the smoothed mesh is not valid (the check's
 * Hausdorff distance or area). */
static glpgp_status smooth_valid(const glpgp_mesh *m, double h, const glpgp_quads_options *o, glpgp_quadmesh *q,
                                 glpgp_quads_surface_steps *stp)
{
    glpgp_quads_report qq;
    GLPGP_CHECK(glpgp_quads_quality_surface(q, m, h, &qq));
    stp->sj_before = stp->sj_after = qq.sj_min;
    if (o->smooth <= 0 || o->keep_polygons || !o->repair || qq.invalid) return GLPGP_OK;
    double *keep = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)3 * q->nv + 1, sizeof(double), &keep));
    memcpy(keep, q->xyz, (size_t)3 * q->nv * sizeof(double));
    int moved = 0;
    glpgp_status st = glpgp_quads_smooth_surface(m, h, o->smooth, q, &moved);
    if (st == GLPGP_OK && moved) st = glpgp_quads_quality_surface(q, m, h, &qq);
    if (st == GLPGP_OK && moved && !qq.invalid) {
        stp->smoothed = moved;
        stp->sj_after = qq.sj_min;
        q->closing.smoothed_vertices = moved; /* the report's closing.smoothed_vertices */
    } else if (moved) {
        glpgp_log(GLPGP_LOG_DEBUG,
                  "quads: the surface smoothing undone: the smoothed mesh is not valid (0x%x, Hausdorff %.3f h: quads "
                  "to surface %.3f h, surface to quads %.3f h; area ratio %.4f)",
                  qq.invalid, qq.hausdorff, qq.dist_quad_to_domain, qq.dist_domain_to_quad, qq.area_ratio);
        memcpy(q->xyz, keep, (size_t)3 * q->nv * sizeof(double));
        set_xy(q);
    }
    free(keep);
    glpgp_log(GLPGP_LOG_DEBUG, "quads: surface smoothing: %d vertices moved, smallest scaled Jacobian %.3f -> %.3f",
              stp->smoothed, stp->sj_before, stp->sj_after);
    return st;
}

/* Flat boundary corners (glpgp_qs_find_flat, split_surface.c) of a valid
 * mesh below FLAT_GOAL, split like triangles and smoothed; the result kept
 * when it is valid and its smallest scaled Jacobian higher. */
#define FLAT_GOAL 0.3

static glpgp_status flat_corners(const glpgp_mesh *m, double h, const glpgp_quads_options *o, glpgp_quadmesh **pq,
                                 glpgp_quads_surface_steps *stp)
{
    glpgp_quadmesh *q = *pq, *r = NULL;
    if (o->keep_polygons || !o->repair) return GLPGP_OK;
    signed char *flat = NULL;
    int nflat = 0, nsplit = 0, moved = 0;
    glpgp_quads_report before, after;
    GLPGP_CHECK(glpgp_malloc((size_t)q->nf + 1, 1, &flat));
    glpgp_status st = glpgp_qs_find_flat(q, FLAT_GOAL, flat, &nflat);
    if (st == GLPGP_OK && nflat) st = glpgp_quads_quality_surface(q, m, h, &before);
    if (st == GLPGP_OK && nflat && !before.invalid) st = glpgp_qs_split_flat(m, q, h, flat, &r, &nsplit);
    if (st == GLPGP_OK && r && o->smooth > 0) st = glpgp_quads_smooth_surface(m, h, o->smooth, r, &moved);
    if (st == GLPGP_OK && r) st = glpgp_quads_quality_surface(r, m, h, &after);
    if (st == GLPGP_OK && r && !after.invalid && after.sj_min > before.sj_min) {
        glpgp_log(GLPGP_LOG_INFO,
                  "quads: %d flat boundary corners split (%d faces split, %d -> %d quads): smallest scaled "
                  "Jacobian %.3f -> %.3f",
                  nflat, nsplit, q->nf, r->nf, before.sj_min, after.sj_min);
        r->collapsed_edges = q->collapsed_edges;
        r->promoted_corners = q->promoted_corners;
        r->split_pentagons = q->split_pentagons;
        r->center_splits = q->center_splits;
        r->closing = q->closing;
        r->repair = q->repair;
        r->cleanup = q->cleanup;
        stp->flat_corners = nflat;
        stp->flat_faces = nsplit;
        stp->flat_sj_before = before.sj_min;
        stp->flat_sj_after = after.sj_min;
        glpgp_quadmesh_destroy(pq);
        *pq = r;
        r = NULL;
    } else if (st == GLPGP_OK && r) {
        glpgp_log(GLPGP_LOG_DEBUG, "quads: %d flat boundary corners: the split is %s (smallest scaled Jacobian %.3f -> %.3f)",
                  nflat, after.invalid ? "not valid" : "no better", before.sj_min, after.sj_min);
    }
    glpgp_quadmesh_destroy(&r);
    free(flat);
    return st;
}

/* The last resort: the coarse triangulation split into quads when it is
 * valid (a 17 degree angle floor, then 20: measured on genus 2, the torus
 * and a 20-hole sphere, 17 gives 2-4x fewer quads with a higher smallest
 * scaled Jacobian, but 16 already failed once), else the input's own
 * triangles split (valid by construction). */
static glpgp_status last_resort(const glpgp_mesh *m, double h, glpgp_quadmesh **out, glpgp_quads_surface_steps *stp)
{
    static const double amin[2] = {17.0, 20.0};
    int nt = 0;
    unsigned bad = 0;
    for (int k = 0; k < 2; k++) {
        glpgp_status st = glpgp_qs_coarse(m, h, amin[k], out, &nt);
        if (st == GLPGP_OK) st = verdict_of(m, *out, h, 0, &bad);
        if (st == GLPGP_OK && !bad) {
            stp->coarse_triangles = nt;
            glpgp_log(GLPGP_LOG_INFO, "quads: the last resort: %d triangles of the %d input ones, split into quads",
                      nt, m->nt);
            return GLPGP_OK;
        }
        glpgp_quadmesh_destroy(out);
        if (st != GLPGP_OK) return st;
        glpgp_log(GLPGP_LOG_INFO, "quads: the coarse last resort (%g degrees, %d triangles) is not valid (0x%x)",
                  amin[k], nt, bad);
    }
    return glpgp_quads_surface_fallback(m, out);
}

glpgp_status glpgp_qs_build_one(const glpgp_mesh *m, const glpgp_result *r, const glpgp_quads_options *o,
                                glpgp_quadmesh **out, double *h, glpgp_quads_surface_steps *steps)
{
    glpgp_quads_options def;
    glpgp_quads_surface_steps stp;
    if (!o) {
        glpgp_quads_options_default(&def);
        o = &def;
    }
    memset(&stp, 0, sizeof stp);
    *out = NULL;
    glpgp_quadmesh *q = NULL;
    glpgp_status st = glpgp_quads_extract_surface(m, r, &q);
    if (st == GLPGP_ERR_NUMERIC && o->repair) {
        glpgp_log(GLPGP_LOG_DEBUG, "quads: %s; the input triangles are split into quads", glpgp_error_message());
        glpgp_error_clear();
        st = GLPGP_OK;
    }
    if (st != GLPGP_OK) return st;
    if (q) {
        stp.extracted_faces = q->nf;
        stp.extracted_quads = q->nf - count_nonquads(q);
        unsigned bad = 0;
        st = candidates(m, &q, o, *h, &stp, out, &bad);
        if (st == GLPGP_OK && *out) st = smooth_valid(m, *h, o, *out, &stp);
        if (st == GLPGP_OK && *out) st = flat_corners(m, *h, o, out, &stp);
        if (st != GLPGP_OK) glpgp_quadmesh_destroy(out);
        if (st != GLPGP_OK || *out) {
            glpgp_quadmesh_destroy(&q);
            if (st == GLPGP_OK && steps) *steps = stp;
            return st;
        }
        char why[256]; /* the reasons by name (the counts are in the report) */
        bad_names(bad & ~(unsigned)GLPGP_QUADS_BAD_NONQUAD, why, sizeof why);
        glpgp_log(GLPGP_LOG_WARNING,
                  "quads: the extracted mesh is not valid%s%s%s: the input triangles are split into quads",
                  why[0] ? " (" : "", why, why[0] ? ")" : "");
        stp.invalid_before = bad;
        glpgp_quadmesh_destroy(&q);
    }
    stp.fallback = 1;
    st = last_resort(m, *h, out, &stp);
    if (st == GLPGP_OK) st = smooth_valid(m, *h, o, *out, &stp);
    if (st == GLPGP_OK) st = flat_corners(m, *h, o, out, &stp);
    if (st != GLPGP_OK) glpgp_quadmesh_destroy(out);
    if (st == GLPGP_OK && steps) *steps = stp;
    return st;
}
