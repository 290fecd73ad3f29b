/* mesh/surface_fix.c: glpgp_surface_fix (glpgp/surface.h), the repairs a
 * surface read from a file may need before glpgp_mesh_create_surface, which
 * stays strict:
 *  - duplicates (first of all): a triangle on the same three vertices as
 *    one before it (a face written twice, or once each way round) is
 *    dropped: the pair would make three edges of three triangles;
 *  - orientation (first): each connected component's triangles oriented
 *    alike (a breadth-first walk across the manifold edges); a component
 *    that needed flips is oriented outward when it is closed (positive
 *    enclosed volume), else as most of its triangles were;
 *  - degenerate triangles: zero area (the test glpgp_mesh_create_surface
 *    applies) or an angle below FIX_NEEDLE radians (a marching-cubes
 *    mesh's two vertices a hair apart: the stiffness of such a triangle's
 *    edge is 1 / FIX_NEEDLE and more, which stalls the solve's linear
 *    systems; bench/results/surface_thin.md). A cap (one vertex inside the
 *    opposite edge: a T-junction's filler) has that edge flipped with its
 *    neighbour's (or is dropped on the boundary), a needle (two vertices
 *    nearly one) has its short edge collapsed where the link condition
 *    holds and no triangle turns over; the surface moves by FIX_NEEDLE
 *    times the triangle's longest edge at most. A few passes, then the
 *    pillows the collapses folded (two triangles on one vertex set, which
 *    enclose nothing: a flat bubble, or debris) dropped; what is left
 *    stays for the validation, and a stage that would leave an edge of more
 *    than two triangles is undone whole;
 *  - pinched vertices: a vertex whose triangles form several fans (two
 *    sheets or cones touching at a point) becomes one vertex per fan, so
 *    the sheets are meshed apart (the corners at a vertex joined across
 *    their shared edges, union-find);
 *  - edges of more than two triangles (first) where bodies touch along an
 *    edge (a CAD assembly's parts, two boxes edge to edge): the triangles
 *    around such an edge, sorted by their angle about it, are paired so
 *    that each pair's wedge is behind both normals (the inside of a body
 *    oriented outward), which needs the triangles to alternate in
 *    direction around the edge; each pair is then an edge of its own and
 *    the edge's vertices are split by fans as above, so the bodies are
 *    meshed apart.
 * What is not a mesh these repairs are defined on (indices out of range, a
 * repeated vertex in a triangle, an edge of three triangles, or of more
 * that do not alternate, a non-orientable component) is left alone:
 * glpgp_mesh_create_surface names it. */
#include "glpgp/surface.h"
#include "glpgp/util.h"

#include "surface_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define FIX_PASSES 8      /* degenerate-triangle passes */
#define FIX_NEEDLE 1e-6   /* an edge this short, or a vertex this close to the edge opposite it (x the
                             triangle's longest edge): a needle, or a cap */

static int corner_next(int h) { return h - h % 3 + (h % 3 + 1) % 3; }

/* Whether every index is in range and no triangle repeats a vertex. */
static int well_formed(int nv, int nt, const int *tri)
{
    for (int t = 0; t < nt; t++) {
        const int *c = tri + 3 * t;
        for (int i = 0; i < 3; i++)
            if (c[i] < 0 || c[i] >= nv) return 0;
        if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) return 0;
    }
    return 1;
}

/* Six times the signed volume the triangles of one component enclose, with
 * flip[t] applied (closed components only: it does not depend on the origin). */
static double volume6(const double *xyz, const int *tri, const int *list, int n, const signed char *flip)
{
    double v = 0.0;
    for (int k = 0; k < n; k++) {
        const int t = list[k];
        const double *a = xyz + 3 * tri[3 * t], *b = xyz + 3 * tri[3 * t + 1], *c = xyz + 3 * tri[3 * t + 2];
        const double d = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                         a[2] * (b[0] * c[1] - b[1] * c[0]);
        v += flip[t] ? -d : d;
    }
    return v;
}

/* The orientation repair; *orientable 0 when a component cannot be
 * oriented (then nothing is changed). */
static glpgp_status orient(glpgp_mesh *m, glpgp_surface *s, int *flipped, int *orientable)
{
    const int nt = m->nt;
    signed char *flip = NULL;
    int *queue = NULL;
    glpgp_status st = GLPGP_OK;
    *flipped = 0;
    *orientable = 1;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nt, 1, &flip), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nt, sizeof(int), &queue), done);
    memset(flip, -1, (size_t)nt);
    int start = 0; /* the component's triangles: queue[start, start + n) */
    for (int seed = 0; seed < nt; seed++) {
        if (flip[seed] >= 0) continue;
        int n = 0, closed = 0, ones = 0;
        if (glpgp_surface_walk(m->tri, s->twin, seed, flip, queue + start, &n, &closed) >= 0) {
            *orientable = 0;
            goto done;
        }
        for (int k = 0; k < n; k++) ones += flip[queue[start + k]];
        const int invert = ones && (closed ? volume6(m->xyz, m->tri, queue + start, n, flip) < 0.0 : 2 * ones > n);
        if (invert)
            for (int k = 0; k < n; k++) flip[queue[start + k]] ^= 1;
        start += n;
    }
    for (int t = 0; t < nt; t++)
        if (flip[t]) {
            const int a = m->tri[3 * t + 1];
            m->tri[3 * t + 1] = m->tri[3 * t + 2];
            m->tri[3 * t + 2] = a;
            (*flipped)++;
        }
done:
    free(flip);
    free(queue);
    return st;
}

/* ---- duplicate triangles ---------------------------------------------- */

static int cmp_tri_key(const void *pa, const void *pb)
{
    const int *a = pa, *b = pb;
    for (int i = 0; i < 4; i++)
        if (a[i] != b[i]) return (a[i] > b[i]) - (a[i] < b[i]);
    return 0;
}

/* Triangles on the vertex set of an earlier one dropped, the rest kept in
 * order (*nt shrinks); with all, every triangle of a vertex set that has
 * two or more (the pillow a collapse folds: it encloses nothing). *dropped:
 * how many. */
static glpgp_status drop_duplicates(int *nt, int *tri, int all, int *dropped)
{
    int *key = NULL; /* per triangle: its sorted vertices, then its index */
    unsigned char *gone = NULL;
    *dropped = 0;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * *nt, sizeof(int), &key), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)*nt, 1, &gone), done);
    for (int t = 0; t < *nt; t++) {
        int a = tri[3 * t], b = tri[3 * t + 1], c = tri[3 * t + 2], x;
        if (a > b) x = a, a = b, b = x;
        if (b > c) x = b, b = c, c = x;
        if (a > b) x = a, a = b, b = x;
        key[4 * t] = a;
        key[4 * t + 1] = b;
        key[4 * t + 2] = c;
        key[4 * t + 3] = t;
    }
    qsort(key, (size_t)*nt, 4 * sizeof(int), cmp_tri_key);
    for (int i = 1; i < *nt; i++)
        if (!memcmp(key + 4 * i, key + 4 * (i - 1), 3 * sizeof(int))) {
            gone[key[4 * i + 3]] = 1; /* sorted by index within a vertex set: the first stays */
            (*dropped)++;
            if (all && !gone[key[4 * (i - 1) + 3]]) {
                gone[key[4 * (i - 1) + 3]] = 1;
                (*dropped)++;
            }
        }
    if (*dropped) {
        int n = 0;
        for (int t = 0; t < *nt; t++)
            if (!gone[t]) memmove(tri + 3 * n++, tri + 3 * t, 3 * sizeof(int));
        *nt = n;
    }
done:
    free(key);
    free(gone);
    return st;
}

/* ---- degenerate triangles --------------------------------------------- */

static int cmp_ll(const void *pa, const void *pb)
{
    const long long *a = pa, *b = pb;
    return a[0] < b[0] ? -1 : a[0] > b[0] ? 1 : (a[1] > b[1]) - (a[1] < b[1]);
}

static double dist2(const double *p, const double *q)
{
    return (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
}

/* Whether triangle t's area is at most 1e-14 diag^2 (the validation's
 * test), or its shortest edge or its height over the longest edge at most
 * FIX_NEEDLE times the longest edge (an angle below about FIX_NEEDLE). */
static int degenerate(const double *xyz, const int *tri, int t, double diag2, int thin)
{
    const double *p = xyz + 3 * tri[3 * t], *q = xyz + 3 * tri[3 * t + 1], *r = xyz + 3 * tri[3 * t + 2];
    double n[3];
    glpgp_tri_normal3(p, q, r, n);
    const double n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2]; /* (2 area)^2 */
    if (!(0.5 * sqrt(n2) > 1e-14 * diag2)) return 1;
    if (!thin) return 0;
    const double l0 = dist2(q, r), l1 = dist2(r, p), l2 = dist2(p, q);
    const double lmax = fmax(l0, fmax(l1, l2)), lmin = fmin(l0, fmin(l1, l2));
    const double f2 = FIX_NEEDLE * FIX_NEEDLE;
    return lmin <= f2 * lmax || n2 <= f2 * lmax * lmax; /* height = 2 area / longest */
}

/* key: (edge, half-edge) pairs of the 3 nt half-edges sorted by edge (the
 * half-edges of one edge consecutive, in increasing order); twin[h] <- -1. */
static void edge_keys(int nv, int nt, const int *tri, long long *key, int *twin)
{
    const int nh = 3 * nt;
    for (int h = 0; h < nh; h++) {
        const long long a = tri[h], b = tri[corner_next(h)];
        key[2 * h] = a < b ? a * nv + b : b * nv + a;
        key[2 * h + 1] = h;
        twin[h] = -1;
    }
    qsort(key, (size_t)nh, 2 * sizeof(long long), cmp_ll);
}

/* twin[h]: the half-edge running h's edge the other way (-1: none, -2: the
 * edge has more than two, or two the same way). key: 6 nt long longs. */
static void edge_twins(int nv, int nt, const int *tri, long long *key, int *twin)
{
    const int nh = 3 * nt;
    edge_keys(nv, nt, tri, key, twin);
    for (int i = 0; i < nh;) {
        int j = i + 1;
        while (j < nh && key[2 * j] == key[2 * i]) j++;
        const int h0 = (int)key[2 * i + 1], h1 = j - i == 2 ? (int)key[2 * i + 3] : -1;
        if (j - i == 2 && tri[h0] != tri[h1]) {
            twin[h0] = h1;
            twin[h1] = h0;
        } else if (j - i >= 2) {
            for (int k = i; k < j; k++) twin[key[2 * k + 1]] = -2;
        }
        i = j;
    }
}

/* One pass over the degenerate triangles: the triangles, their twins, the
 * vertex -> triangle lists (vptr / vtri, as at the pass's start), the
 * triangles changed this pass (busy) or dropped (gone), the collapses
 * (alias) and a per-vertex stamp for the neighbour tests. */
typedef struct fix_pass {
    const double *xyz;
    int *tri;
    const int *twin;
    int *vptr, *vtri;
    unsigned char *busy, *gone;
    int *alias;
    int *mark, stamp;
    double diag2; /* the bounding box's diagonal, squared */
    int thin;     /* the thin stage: needles and caps by angle too, collapses tested */
} fix_pass;

/* vptr / vtri: the triangles of every vertex (n vertices, nt triangles). */
static void vertex_triangles(fix_pass *p, int n, int nt)
{
    memset(p->vptr, 0, (size_t)(n + 1) * sizeof(int));
    for (int c = 0; c < 3 * nt; c++) p->vptr[p->tri[c] + 1]++;
    for (int v = 0; v < n; v++) p->vptr[v + 1] += p->vptr[v];
    for (int c = 0; c < 3 * nt; c++) p->vtri[p->vptr[p->tri[c]]++] = c / 3;
    for (int v = n; v > 0; v--) p->vptr[v] = p->vptr[v - 1];
    p->vptr[0] = 0;
}

/* Whether edge a-b exists (a triangle of a has b). */
static int has_edge(const fix_pass *p, int a, int b)
{
    for (int k = p->vptr[a]; k < p->vptr[a + 1]; k++) {
        const int *q = p->tri + 3 * p->vtri[k];
        if (q[0] == b || q[1] == b || q[2] == b) return 1;
    }
    return 0;
}

/* Whether vertex m may collapse into e this pass: no triangle around either
 * changed this pass, the link condition (the common neighbours of m and e
 * are the apexes of the triangles on edge m-e: no edge doubled, no pinch),
 * and no triangle of m that stays and is not degenerate itself turns over
 * when m moves to e. */
static int collapse_ok(fix_pass *p, int m, int e)
{
    const int sm = ++p->stamp, sc = ++p->stamp;
    int on_edge = 0, common = 0;
    for (int k = p->vptr[m]; k < p->vptr[m + 1]; k++) {
        const int t = p->vtri[k], *q = p->tri + 3 * t;
        if (p->busy[t]) return 0;
        if (q[0] == e || q[1] == e || q[2] == e) on_edge++;
        for (int c = 0; c < 3; c++) p->mark[q[c]] = sm;
    }
    for (int k = p->vptr[e]; k < p->vptr[e + 1]; k++) {
        const int t = p->vtri[k], *q = p->tri + 3 * t;
        if (p->busy[t]) return 0;
        for (int c = 0; c < 3; c++)
            if (q[c] != m && q[c] != e && p->mark[q[c]] == sm) {
                p->mark[q[c]] = sc;
                common++;
            }
    }
    if (common != on_edge) return 0;
    for (int k = p->vptr[m]; k < p->vptr[m + 1]; k++) {
        const int *q = p->tri + 3 * p->vtri[k];
        if (q[0] == e || q[1] == e || q[2] == e || degenerate(p->xyz, p->tri, p->vtri[k], p->diag2, 1)) continue;
        const double *x[3], *y[3];
        for (int c = 0; c < 3; c++) {
            x[c] = p->xyz + 3 * q[c];
            y[c] = p->xyz + 3 * (q[c] == m ? e : q[c]);
        }
        double a[3], b[3];
        glpgp_tri_normal3(x[0], x[1], x[2], a);
        glpgp_tri_normal3(y[0], y[1], y[2], b);
        if (a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < 0.0) return 0;
    }
    return 1;
}

/* Every triangle of vertex v marked changed this pass. */
static void busy_around(fix_pass *p, int v)
{
    for (int k = p->vptr[v]; k < p->vptr[v + 1]; k++) p->busy[p->vtri[k]] = 1;
}

/* One degenerate triangle t: its longest edge h (x -> y) and the vertex m
 * opposite; a needle (m at an end) collapses m into that end (alias[m]) or
 * that end into m, a
 * cap flips x-y with the neighbour (x, c, m), (c, y, m), or is dropped on
 * the boundary. Returns 1 when changed. */
static int fix_one(fix_pass *p, int t)
{
    const int *tri = p->tri;
    int h = 3 * t;
    double best = -1.0;
    for (int i = 0; i < 3; i++) {
        const double l = dist2(p->xyz + 3 * tri[3 * t + i], p->xyz + 3 * tri[3 * t + (i + 1) % 3]);
        if (l > best) {
            best = l;
            h = 3 * t + i;
        }
    }
    const int x = tri[h], y = tri[corner_next(h)], mm = tri[corner_next(corner_next(h))];
    const double dx = dist2(p->xyz + 3 * mm, p->xyz + 3 * x), dy = dist2(p->xyz + 3 * mm, p->xyz + 3 * y);
    if (fmin(dx, dy) <= FIX_NEEDLE * FIX_NEEDLE * best) { /* a needle (roots alias roots: no cycle) */
        int a = mm, e = dx <= dy ? x : y;
        if (p->alias[a] != a || p->alias[e] != e) return 0;
        if (!p->thin) {
            p->alias[a] = e;
            p->busy[t] = 1;
            return 1;
        }
        if (!collapse_ok(p, a, e)) { /* or the other way */
            a = e;
            e = mm;
            if (!collapse_ok(p, a, e)) return 0;
        }
        p->alias[a] = e;
        busy_around(p, a);
        busy_around(p, e);
        return 1;
    }
    const int g = p->twin[h];
    if (g == -2) return 0;
    if (g == -1) { /* a cap on the boundary: nothing but a sliver to drop */
        p->gone[t] = p->busy[t] = 1;
        return 1;
    }
    const int u = g / 3, c = tri[corner_next(corner_next(g))];
    if (p->busy[u] || c == mm || (p->thin && has_edge(p, mm, c))) return 0;
    int *tt = p->tri + 3 * t, *tu = p->tri + 3 * u;
    tt[0] = x;
    tt[1] = c;
    tt[2] = mm;
    tu[0] = c;
    tu[1] = y;
    tu[2] = mm;
    p->busy[t] = p->busy[u] = 1;
    return 1;
}

/* The collapses of a pass applied: every corner to its vertex's final
 * alias; triangles that repeat a vertex, or dropped, removed (*nt). */
static void apply_pass(fix_pass *p, int *nt)
{
    int *tri = p->tri;
    for (int c = 0; c < 3 * *nt; c++) {
        int v = tri[c];
        while (p->alias[v] != v) v = p->alias[v];
        tri[c] = v;
    }
    int k = 0;
    for (int t = 0; t < *nt; t++) {
        const int *q = tri + 3 * t;
        if (p->gone[t] || q[0] == q[1] || q[1] == q[2] || q[0] == q[2]) continue;
        memmove(tri + 3 * k, q, 3 * sizeof(int));
        k++;
    }
    *nt = k;
    memset(p->gone, 0, (size_t)k);
}

/* Whether an edge has more than two triangles, or two the same way round. */
static int any_bad_edge(const int *twin, int nt)
{
    for (int h = 0; h < 3 * nt; h++)
        if (twin[h] == -2) return 1;
    return 0;
}

/* The vertices the collapses left unused compacted (*nv; alias reused). */
static void compact_vertices(int *nv, double *xyz, int nt, int *tri, int *alias)
{
    const int n = *nv;
    for (int v = 0; v < n; v++) alias[v] = -1;
    for (int c = 0; c < 3 * nt; c++) alias[tri[c]] = 0;
    int m = 0;
    for (int v = 0; v < n; v++)
        if (alias[v] == 0) {
            memmove(xyz + 3 * m, xyz + 3 * v, 3 * sizeof(double));
            alias[v] = m++;
        }
    for (int c = 0; c < 3 * nt; c++) tri[c] = alias[tri[c]];
    *nv = m;
}

/* The passes of one stage: caps flipped or dropped, needles collapsed;
 * then the pillows the collapses folded (two triangles on one vertex set)
 * dropped and the vertices compacted (*nv). The zero-area stage (thin 0) collapses
 * without tests (a cluster of vertices at one point needs several
 * collapses that are not manifold one by one); the thin stage tests each
 * (collapse_ok, a flip's new edge). Undone whole (*fixed 0) when nothing
 * is left, or when an edge had two triangles at most before and not after.
 * *fixed: the degenerate triangles handled. */
static glpgp_status fix_stage(int *nv, double *xyz, int *nt, int *tri, int thin, int *fixed)
{
    const int n = *nv, nt0 = *nt;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int v = 0; v < n; v++)
        for (int c = 0; c < 3; c++) {
            lo[c] = fmin(lo[c], xyz[3 * v + c]);
            hi[c] = fmax(hi[c], xyz[3 * v + c]);
        }
    const double diag2 = dist2(lo, hi);
    *fixed = 0;
    int any = 0;
    for (int t = 0; t < nt0 && !any; t++) any = degenerate(xyz, tri, t, diag2, thin);
    if (!any) return GLPGP_OK;
    long long *key = NULL;
    int *twin = NULL, *keep = NULL;
    fix_pass p = {xyz, tri, NULL, NULL, NULL, NULL, NULL, NULL, NULL, 0, diag2, thin};
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt0, sizeof(int), &keep), done);
    memcpy(keep, tri, (size_t)3 * nt0 * sizeof(int));
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)6 * nt0, sizeof(long long), &key), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt0, sizeof(int), &twin), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n, sizeof(int), &p.alias), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n + 1, sizeof(int), &p.vptr), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt0, sizeof(int), &p.vtri), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)n, sizeof(int), &p.mark), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nt0, 1, &p.busy), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nt0, 1, &p.gone), done);
    p.twin = twin;
    for (int v = 0; v < n; v++) p.alias[v] = v;
    edge_twins(n, *nt, tri, key, twin);
    const int bad0 = any_bad_edge(twin, *nt);
    for (int pass = 0; pass < FIX_PASSES; pass++) {
        int changed = 0;
        if (pass > 0) edge_twins(n, *nt, tri, key, twin);
        vertex_triangles(&p, n, *nt);
        memset(p.busy, 0, (size_t)*nt);
        for (int t = 0; t < *nt; t++)
            if (!p.gone[t] && !p.busy[t] && degenerate(xyz, tri, t, diag2, thin)) changed += fix_one(&p, t);
        *fixed += changed;
        apply_pass(&p, nt);
        if (!changed) break;
    }
    int pillows = 0;
    GLPGP_CHECK_GOTO(st, drop_duplicates(nt, tri, 1, &pillows), done);
    *fixed += pillows;
    edge_twins(n, *nt, tri, key, twin);
    if (*nt == 0 || (!bad0 && any_bad_edge(twin, *nt))) { /* left for the validation to name */
        memcpy(tri, keep, (size_t)3 * nt0 * sizeof(int));
        *nt = nt0;
        *fixed = 0;
        goto done;
    }
    compact_vertices(nv, xyz, *nt, tri, p.alias);
done:
    free(keep);
    free(key);
    free(twin);
    free(p.alias);
    free(p.vptr);
    free(p.vtri);
    free(p.mark);
    free(p.busy);
    free(p.gone);
    return st;
}

/* The zero-area triangles first (what the validation refuses), then the
 * thin ones on what is left. */
static glpgp_status fix_degenerate(int *nv, double *xyz, int *nt, int *tri, int *zero, int *thin)
{
    GLPGP_CHECK(fix_stage(nv, xyz, nt, tri, 0, zero));
    return fix_stage(nv, xyz, nt, tri, 1, thin);
}

/* The pinched-vertex repair (twin[] current, any orientation): one vertex
 * per fan, the new ones appended to *xyz. */
static glpgp_status split_fans(glpgp_mesh *m, const int *twin, double **xyz, int *pinched, int *added)
{
    const int nv = m->nv, nc = 3 * m->nt;
    int *parent = NULL, *id = NULL, *root = NULL;
    glpgp_status st = GLPGP_OK;
    *pinched = *added = 0;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc, sizeof(int), &parent), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc, sizeof(int), &id), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(int), &root), done);
    for (int c = 0; c < nc; c++) {
        parent[c] = c;
        id[c] = -1;
    }
    for (int v = 0; v < nv; v++) root[v] = -1;
    /* corner c's outgoing edge and its twin g: c's vertex in g's triangle
     * is g's end (g runs back) or g's start (g runs the same way: an
     * orientation not repaired yet) */
    for (int c = 0; c < nc; c++)
        if (twin[c] >= 0) {
            const int g = twin[c], d = m->tri[g] == m->tri[c] ? g : corner_next(g);
            parent[glpgp_uf_find(parent, c)] = glpgp_uf_find(parent, d);
        }
    int n = nv;
    for (int c = 0; c < nc; c++) {
        const int v = m->tri[c], r = glpgp_uf_find(parent, c);
        if (root[v] < 0) {
            root[v] = r;
            id[r] = v;
        } else if (id[r] < 0) { /* another fan at v (the first one keeps v) */
            id[r] = n++;
        }
    }
    if (n > nv) {
        size_t cap = (size_t)3 * nv;
        GLPGP_CHECK_GOTO(st, glpgp_grow(xyz, &cap, (size_t)3 * n, sizeof(double)), done);
        unsigned char *seen = (unsigned char *)root; /* reused: a pinched vertex counted once */
        memset(seen, 0, (size_t)nv);
        for (int c = 0; c < nc; c++) {
            const int r = glpgp_uf_find(parent, c), v = m->tri[c];
            if (id[r] == v) continue;
            if (!seen[v]) {
                seen[v] = 1;
                (*pinched)++;
            }
            memcpy(*xyz + 3 * id[r], *xyz + 3 * v, 3 * sizeof(double));
            m->tri[c] = id[r];
        }
        *added = n - nv;
    }
done:
    free(parent);
    free(id);
    free(root);
    return st;
}

/* ---- edges of more than two triangles ---------------------------------- */

typedef struct nm_side {
    double phi; /* the angle of the triangle about the edge */
    int h, dir; /* half-edge; +1 along the edge's first half-edge, -1 against */
} nm_side;

static int cmp_side(const void *pa, const void *pb)
{
    const nm_side *a = pa, *b = pb;
    return a->phi < b->phi ? -1 : a->phi > b->phi ? 1 : a->h - b->h;
}

/* The half-edges S[0, n) of one edge paired in twin[]: sorted by angle
 * about the edge (from the first half-edge's start to its end, right-handed),
 * a triangle along the edge has its normal towards increasing angle, one
 * against it towards decreasing; each triangle along the edge is paired
 * with the one before it, which must run against it (the wedge between them
 * behind both normals). Returns 0 when they do not alternate. */
static int pair_edge(const double *xyz, const int *tri, nm_side *S, int n, int *twin)
{
    const int a = tri[S[0].h], b = tri[corner_next(S[0].h)];
    double e[3], p[3] = {0, 0, 0}, q[3];
    for (int d = 0; d < 3; d++) e[d] = xyz[3 * b + d] - xyz[3 * a + d];
    const double l = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    if (!(l > 0.0) || n % 2) return 0;
    for (int d = 0; d < 3; d++) e[d] /= l;
    const int ax = fabs(e[0]) < fabs(e[1]) ? (fabs(e[0]) < fabs(e[2]) ? 0 : 2) : (fabs(e[1]) < fabs(e[2]) ? 1 : 2);
    p[ax] = 1.0; /* p <- the axis least along e, made normal to it (|q| = |p|); q = e x p */
    for (int d = 0; d < 3; d++) p[d] -= e[ax] * e[d];
    q[0] = e[1] * p[2] - e[2] * p[1];
    q[1] = e[2] * p[0] - e[0] * p[2];
    q[2] = e[0] * p[1] - e[1] * p[0];
    for (int k = 0; k < n; k++) {
        const int h = S[k].h, c = tri[corner_next(corner_next(h))];
        double u[3];
        for (int d = 0; d < 3; d++) u[d] = xyz[3 * c + d] - xyz[3 * a + d];
        S[k].phi = atan2(u[0] * q[0] + u[1] * q[1] + u[2] * q[2], u[0] * p[0] + u[1] * p[1] + u[2] * p[2]);
        S[k].dir = tri[h] == a ? 1 : -1;
    }
    qsort(S, (size_t)n, sizeof *S, cmp_side);
    for (int k = 0; k < n; k++)
        if (S[k].dir == S[(k + 1) % n].dir) return 0;
    for (int k = 0; k < n; k++)
        if (S[k].dir > 0) {
            const int g = S[(k + n - 1) % n].h;
            twin[S[k].h] = g;
            twin[g] = S[k].h;
        }
    return 1;
}

/* The edges of more than two triangles separated (see the file comment):
 * *edges of them, their vertices split by fans (*pinched, *added as
 * split_fans); *ok 0 when one cannot be paired (nothing changed). */
static glpgp_status separate_edges(glpgp_mesh *m, double **xyz, int *edges, int *pinched, int *added, int *ok)
{
    const int nh = 3 * m->nt;
    long long *key = NULL;
    int *twin = NULL;
    nm_side *S = NULL;
    glpgp_status st = GLPGP_OK;
    *edges = *pinched = *added = 0;
    *ok = 1;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nh, 2 * sizeof(long long), &key), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nh, sizeof(int), &twin), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nh, sizeof *S, &S), done);
    edge_keys(m->nv, m->nt, m->tri, key, twin);
    for (int i = 0; i < nh && *ok;) {
        int j = i + 1;
        while (j < nh && key[2 * j] == key[2 * i]) j++;
        if (j - i == 2) {
            twin[key[2 * i + 1]] = (int)key[2 * i + 3];
            twin[key[2 * i + 3]] = (int)key[2 * i + 1];
        } else if (j - i > 2) {
            for (int k = i; k < j; k++) S[k - i].h = (int)key[2 * k + 1];
            *ok = pair_edge(m->xyz, m->tri, S, j - i, twin);
            (*edges)++;
        }
        i = j;
    }
    if (*ok && *edges) st = split_fans(m, twin, xyz, pinched, added);
done:
    free(key);
    free(twin);
    free(S);
    return st;
}

/* twin[] of m (s->twin allocated); 0 when an edge is not manifold (left
 * to the validation, its message not kept here). */
static int twins_or_leave(glpgp_mesh *m, glpgp_surface *s, int *samedir)
{
    if (glpgp_surface_twins(m, s, samedir) == GLPGP_OK) return 1;
    glpgp_error_clear();
    return 0;
}

glpgp_status glpgp_surface_fix(int *nv, double **xyz, int *ntp, int *tri, glpgp_surface_fixes *fx)
{
    glpgp_surface_fixes none = {0, 0, 0, 0, 0, 0, 0, 0};
    if (!nv || !xyz || !*xyz || !ntp || !tri || !fx)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_surface_fix: NULL argument");
    *fx = none;
    if (*nv < 3 || *ntp < 1 || !well_formed(*nv, *ntp, tri)) return GLPGP_OK;
    GLPGP_CHECK(drop_duplicates(ntp, tri, 0, &fx->duplicate));
    glpgp_mesh m;
    glpgp_surface s;
    memset(&m, 0, sizeof m);
    memset(&s, 0, sizeof s);
    m.nv = *nv;
    m.nt = *ntp;
    m.tri = tri;
    m.xyz = *xyz;
    glpgp_status st = GLPGP_OK;
    int samedir = -1, orientable = 1;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * m.nt, sizeof(int), &s.twin), done);
    if (!twins_or_leave(&m, &s, &samedir)) {
        int ok = 0, pinched = 0, added = 0;
        GLPGP_CHECK_GOTO(st, separate_edges(&m, xyz, &fx->nonmanifold, &pinched, &added, &ok), done);
        if (!ok) {
            fx->nonmanifold = 0;
            goto done;
        }
        fx->nonmanifold_added = added;
        *nv += added;
        m.nv = *nv;
        m.xyz = *xyz;
        if (!twins_or_leave(&m, &s, &samedir)) goto done;
    }
    if (samedir >= 0) { /* first, so that a degenerate triangle's flip keeps the orientation */
        GLPGP_CHECK_GOTO(st, orient(&m, &s, &fx->flipped, &orientable), done);
        if (!orientable) goto done;
    }
    GLPGP_CHECK_GOTO(st, fix_degenerate(nv, *xyz, ntp, tri, &fx->degenerate, &fx->thin), done);
    m.nv = *nv;
    m.nt = *ntp;
    if (!twins_or_leave(&m, &s, &samedir)) goto done;
    GLPGP_CHECK_GOTO(st, split_fans(&m, s.twin, xyz, &fx->pinched, &fx->added), done);
    *nv += fx->added;
done:
    free(s.twin);
    return st;
}
