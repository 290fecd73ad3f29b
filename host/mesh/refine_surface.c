/* mesh/refine_surface.c: adaptive refinement of a surface mesh to a target
 * edge length (glpgp_mesh_refine_surface, glpgp/surface.h) by Rivara's
 * longest-edge propagation path (LEPP) bisection: a triangle with an edge
 * longer than the target is bisected at the midpoint of its longest edge
 * together with the neighbour across it; when that edge is not the
 * neighbour's longest, the neighbour is refined first, recursively along the
 * path of ever longer edges, whose last edge is the longest of both its
 * triangles (or on the boundary): the pair is bisected there.
 *
 * Why this and not red-green: every triangle made is the longest-edge
 * bisection of its parent, so the smallest angle is at least half the
 * input's (Rosenberg and Stenger 1975), the mesh is conforming after every
 * step (no hanging node, no green closure to undo), only edges longer than
 * the target are ever split (each path ends at an edge longer than the
 * triangle it started from), and it terminates (lengths grow strictly along
 * a path; ties broken by the vertex pair, a total order). Every new point is
 * the midpoint of an edge of the mesh being refined, so it lies on an old
 * edge or inside an old triangle, in its plane: the piecewise linear
 * surface, its sharp edges, boundary loops and topology stay exactly as
 * they were; the bisected triangles keep their orientation.
 *
 * The target is one length (glpgp_mesh_refine_surface) or one per vertex
 * (glpgp_mesh_refine_surface_sized): an edge's target is then the smaller
 * of its ends', a new vertex's the mean of its edge's ends' (the target
 * interpolated linearly along the edge). Both go through the same code: a
 * triangle is refined while one of its edges is longer than its target; a
 * uniform target gives the same mesh either way.
 *
 * The target is reached in levels (edges longer than target x sqrt 2^k, k
 * down to 0), the mesh kept after each level: when the next level would pass
 * max_triangles, the last complete level is the result (a uniform
 * resolution, not half a mesh refined). Work and memory are linear in the
 * output: per bisection O(1) with the twin half-edges updated in place.
 *
 * Every triangle made lies in one input triangle (its ancestor's plane):
 * the ancestor and the barycentric coordinates of the corners in it are
 * carried through the bisections (a midpoint's are the mean of its edge's
 * ends', exact in binary) and left in the result's surface (otri, obary):
 * where each refined vertex lies on the input, for a field computed there
 * (glpgp_surface_cross_transfer). */
#include "surface_internal.h"

#include "glpgp/util.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define SQRT2 1.41421356237309504880

typedef struct lepp {
    int nv, nt;
    size_t cap_v, cap_t, cap_tw, cap_path;
    double *xyz; /* 3 cap_v */
    int *tri;    /* 3 cap_t */
    int *tw;     /* 3 cap_t: twin half-edge (3 t + a: tri[3t+a] -> tri[3t+(a+1)%3]), -1 on the boundary */
    int *path;   /* the propagation path (triangles) */
    int npath;
    double *tv;     /* cap_v: per-vertex target (NULL: tconst everywhere) */
    size_t cap_tv;
    double tconst;
    long max_t; /* triangle limit (0: GLPGP_MESH_MAX_TRIANGLES only) */
    long splits;
    int *ot;       /* cap_ot: the input triangle holding each triangle */
    double *ob;    /* 9 cap_ob: its corners' barycentric coordinates there */
    size_t cap_ot, cap_ob;
} lepp;

static double len2(const lepp *L, int h)
{
    const int t = h / 3, a = h % 3;
    const double *p = L->xyz + 3 * (size_t)L->tri[3 * t + a], *q = L->xyz + 3 * (size_t)L->tri[3 * t + (a + 1) % 3];
    const double dx = q[0] - p[0], dy = q[1] - p[1], dz = q[2] - p[2];
    return dx * dx + dy * dy + dz * dz;
}

static uint64_t hkey(const lepp *L, int h)
{
    const uint32_t i = (uint32_t)L->tri[h], j = (uint32_t)L->tri[3 * (h / 3) + (h % 3 + 1) % 3];
    return i < j ? ((uint64_t)i << 32) | j : ((uint64_t)j << 32) | i;
}

/* The longest edge of triangle t (0..2) and its squared length; ties broken
 * by the vertex pair so that both triangles of an edge agree. */
static int longest(const lepp *L, int t, double *l2)
{
    int best = 0;
    double lb = len2(L, 3 * t);
    for (int a = 1; a < 3; a++) {
        const double l = len2(L, 3 * t + a);
        if (l > lb || (l == lb && hkey(L, 3 * t + a) > hkey(L, 3 * t + best))) {
            best = a;
            lb = l;
        }
    }
    if (l2) *l2 = lb;
    return best;
}

/* Triangle t split at its edge a (midpoint p) into t = (va, p, vc) and the
 * new triangle n = (p, vb, vc); the twins of the two outer edges and the
 * inner edge set, the split edge's halves (3t, 3n) left to the caller. */
static void bisect_one(lepp *L, int t, int a, int p, int n)
{
    /* the origin: t = (B_a, mid, B_c), n = (mid, B_b, B_c) in t's input triangle */
    double *bt = L->ob + 9 * (size_t)t, *bn = L->ob + 9 * (size_t)n, B[9];
    memcpy(B, bt, sizeof B);
    for (int k = 0; k < 3; k++) {
        const double mid = 0.5 * (B[3 * a + k] + B[3 * ((a + 1) % 3) + k]);
        bt[k] = B[3 * a + k], bt[3 + k] = mid, bt[6 + k] = B[3 * ((a + 2) % 3) + k];
        bn[k] = mid, bn[3 + k] = B[3 * ((a + 1) % 3) + k], bn[6 + k] = B[3 * ((a + 2) % 3) + k];
    }
    L->ot[n] = L->ot[t];
    int *v = L->tri + 3 * (size_t)t, *w = L->tri + 3 * (size_t)n;
    const int va = v[a], vb = v[(a + 1) % 3], vc = v[(a + 2) % 3];
    const int T1 = L->tw[3 * t + (a + 1) % 3], T2 = L->tw[3 * t + (a + 2) % 3];
    v[0] = va, v[1] = p, v[2] = vc;
    w[0] = p, w[1] = vb, w[2] = vc;
    L->tw[3 * t + 1] = 3 * n + 2;
    L->tw[3 * n + 2] = 3 * t + 1;
    L->tw[3 * t + 2] = T2;
    if (T2 >= 0) L->tw[T2] = 3 * t + 2;
    L->tw[3 * n + 1] = T1;
    if (T1 >= 0) L->tw[T1] = 3 * n + 1;
}

static glpgp_status grow(lepp *L, int more_v, int more_t)
{
    GLPGP_CHECK(glpgp_grow(&L->xyz, &L->cap_v, (size_t)L->nv + (size_t)more_v, 3 * sizeof(double)));
    if (L->tv) GLPGP_CHECK(glpgp_grow(&L->tv, &L->cap_tv, (size_t)L->nv + (size_t)more_v, sizeof(double)));
    GLPGP_CHECK(glpgp_grow(&L->tri, &L->cap_t, (size_t)L->nt + (size_t)more_t, 3 * sizeof(int)));
    GLPGP_CHECK(glpgp_grow(&L->tw, &L->cap_tw, (size_t)L->nt + (size_t)more_t, 3 * sizeof(int)));
    GLPGP_CHECK(glpgp_grow(&L->ot, &L->cap_ot, (size_t)L->nt + (size_t)more_t, sizeof(int)));
    GLPGP_CHECK(glpgp_grow(&L->ob, &L->cap_ob, (size_t)L->nt + (size_t)more_t, 9 * sizeof(double)));
    return GLPGP_OK;
}

/* Bisect edge a of triangle t and, across it, its twin's triangle: one new
 * vertex, one or two new triangles. *full when the limit forbids it. */
static glpgp_status bisect_edge(lepp *L, int t, int a, int *full)
{
    const int o = L->tw[3 * t + a], add = o >= 0 ? 2 : 1;
    if ((L->max_t > 0 && L->nt + add > L->max_t) || L->nt + add > GLPGP_MESH_MAX_TRIANGLES ||
        L->nv + 1 > GLPGP_MESH_MAX_VERTICES) {
        *full = 1;
        return GLPGP_OK;
    }
    GLPGP_CHECK(grow(L, 1, add));
    const int p = L->nv++, i = L->tri[3 * t + a], j = L->tri[3 * t + (a + 1) % 3];
    for (int e = 0; e < 3; e++)
        L->xyz[3 * (size_t)p + e] = 0.5 * (L->xyz[3 * (size_t)i + e] + L->xyz[3 * (size_t)j + e]);
    if (L->tv) L->tv[p] = 0.5 * (L->tv[i] + L->tv[j]);
    const int n = L->nt++;
    bisect_one(L, t, a, p, n);
    if (o < 0) {
        L->tw[3 * t] = L->tw[3 * n] = -1;
    } else { /* u = (vb, va, w) split at its edge b: u = (vb, p, w), m = (p, va, w) */
        const int u = o / 3, b = o % 3, m = L->nt++;
        bisect_one(L, u, b, p, m);
        L->tw[3 * t] = 3 * m, L->tw[3 * m] = 3 * t; /* va -> p and p -> va */
        L->tw[3 * n] = 3 * u, L->tw[3 * u] = 3 * n; /* p -> vb and vb -> p */
    }
    L->splits++;
    return GLPGP_OK;
}

/* LEPP bisection of triangle t: the path of longest edges walked from t to
 * its terminal edge, that edge bisected, the walk resumed from the
 * previous triangle, until t itself is bisected. */
static glpgp_status lepp_refine(lepp *L, int t, int *full)
{
    L->npath = 0;
    int c = t;
    for (;;) {
        const int e = longest(L, c, NULL), o = L->tw[3 * c + e];
        if (o >= 0 && longest(L, o / 3, NULL) != o % 3) { /* the neighbour's longest edge is longer: go on */
            GLPGP_CHECK(glpgp_grow(&L->path, &L->cap_path, (size_t)L->npath + 1, sizeof(int)));
            L->path[L->npath++] = c;
            c = o / 3;
            continue;
        }
        GLPGP_CHECK(bisect_edge(L, c, e, full));
        if (*full || L->npath == 0) return GLPGP_OK; /* c == t: bisected */
        c = L->path[--L->npath];
    }
}

/* Half-edge h's target: the smaller of its ends' (tconst without tv). */
static double htarget(const lepp *L, int h)
{
    if (!L->tv) return L->tconst;
    return fmin(L->tv[L->tri[h]], L->tv[L->tri[3 * (h / 3) + (h % 3 + 1) % 3]]);
}

/* Whether an edge of triangle t is longer than scale x its target. */
static int over(const lepp *L, int t, double scale)
{
    for (int a = 0; a < 3; a++) {
        const double l = scale * htarget(L, 3 * t + a);
        if (len2(L, 3 * t + a) > l * l) return 1;
    }
    return 0;
}

/* One level: every edge longer than scale x its target split. */
static glpgp_status refine_level(lepp *L, double scale, int *full)
{
    for (int t = 0; t < L->nt && !*full; t++)
        while (!*full && over(L, t, scale)) GLPGP_CHECK(lepp_refine(L, t, full));
    return GLPGP_OK;
}

static glpgp_status lepp_init(lepp *L, const glpgp_mesh *m, double max_triangles)
{
    memset(L, 0, sizeof *L);
    L->nv = m->nv;
    L->nt = m->nt;
    L->cap_v = (size_t)m->nv;
    L->cap_t = L->cap_tw = (size_t)m->nt;
    L->max_t = max_triangles > 0 ? (long)fmin(max_triangles, 4e9) : 0;
    GLPGP_CHECK(glpgp_malloc((size_t)m->nv, 3 * sizeof(double), &L->xyz));
    GLPGP_CHECK(glpgp_malloc((size_t)m->nt, 3 * sizeof(int), &L->tri));
    GLPGP_CHECK(glpgp_malloc((size_t)m->nt, 3 * sizeof(int), &L->tw));
    memcpy(L->xyz, m->xyz, (size_t)m->nv * 3 * sizeof(double));
    memcpy(L->tri, m->tri, (size_t)m->nt * 3 * sizeof(int));
    memcpy(L->tw, m->surf->twin, (size_t)m->nt * 3 * sizeof(int));
    L->cap_ot = L->cap_ob = (size_t)m->nt;
    GLPGP_CHECK(glpgp_malloc((size_t)m->nt, sizeof(int), &L->ot));
    GLPGP_CHECK(glpgp_calloc((size_t)m->nt, 9 * sizeof(double), &L->ob));
    for (int t = 0; t < m->nt; t++) { /* each triangle its own origin, corner a at vertex a */
        L->ot[t] = t;
        for (int a = 0; a < 3; a++) L->ob[9 * (size_t)t + 4 * a] = 1.0;
    }
    return GLPGP_OK;
}

static void lepp_free(lepp *L)
{
    glpgp_free(&L->xyz);
    glpgp_free(&L->tri);
    glpgp_free(&L->tw);
    glpgp_free(&L->path);
    glpgp_free(&L->tv);
    glpgp_free(&L->ot);
    glpgp_free(&L->ob);
}

/* The levels: edges above their target x sqrt 2^k split for k from the
 * first level with unit sqrt 2^(k+1) >= top (the longest edge over the
 * target, as lengths or as a ratio with unit 1) down to 0; the
 * state before each level kept (triangles and twins; vertices only grow)
 * and put back when the level stops at the limit. */
static glpgp_status run_levels(lepp *L, double unit, double top, int *stopped)
{
    int k = 0;
    while (unit * pow(SQRT2, k + 1) < top && k < 200) k++;
    int *s_tri = NULL, *s_tw = NULL, *s_ot = NULL;
    double *s_ob = NULL;
    glpgp_status st = GLPGP_OK;
    for (; k >= 0 && st == GLPGP_OK; k--) {
        const int nv0 = L->nv, nt0 = L->nt;
        const long sp0 = L->splits;
        /* a snapshot to fall back to (also without max_triangles: GLPGP_MESH_MAX_TRIANGLES) */
        glpgp_free(&s_tri);
        glpgp_free(&s_tw);
        glpgp_free(&s_ot);
        glpgp_free(&s_ob);
        st = glpgp_malloc((size_t)nt0, 3 * sizeof(int), &s_tri);
        if (st == GLPGP_OK) st = glpgp_malloc((size_t)nt0, 3 * sizeof(int), &s_tw);
        if (st == GLPGP_OK) st = glpgp_malloc((size_t)nt0, sizeof(int), &s_ot);
        if (st == GLPGP_OK) st = glpgp_malloc((size_t)nt0, 9 * sizeof(double), &s_ob);
        if (st != GLPGP_OK) break;
        memcpy(s_tri, L->tri, (size_t)nt0 * 3 * sizeof(int));
        memcpy(s_tw, L->tw, (size_t)nt0 * 3 * sizeof(int));
        memcpy(s_ot, L->ot, (size_t)nt0 * sizeof(int));
        memcpy(s_ob, L->ob, (size_t)nt0 * 9 * sizeof(double));
        int full = 0;
        st = refine_level(L, k == 0 ? 1.0 : pow(SQRT2, k), &full);
        if (st == GLPGP_OK && full) {
            memcpy(L->tri, s_tri, (size_t)nt0 * 3 * sizeof(int));
            memcpy(L->tw, s_tw, (size_t)nt0 * 3 * sizeof(int));
            memcpy(L->ot, s_ot, (size_t)nt0 * sizeof(int));
            memcpy(L->ob, s_ob, (size_t)nt0 * 9 * sizeof(double));
            L->nv = nv0;
            L->nt = nt0;
            L->splits = sp0;
            *stopped = 1;
            break;
        }
    }
    glpgp_free(&s_tri);
    glpgp_free(&s_tw);
    glpgp_free(&s_ot);
    glpgp_free(&s_ob);
    return st;
}

double glpgp_mesh_longest_edge(const glpgp_mesh *m)
{
    double l = 0.0;
    for (int h = 0; h < 3 * m->nt; h++) {
        const double *p = m->xyz + 3 * (size_t)m->tri[h],
                     *q = m->xyz + 3 * (size_t)m->tri[3 * (h / 3) + (h % 3 + 1) % 3];
        const double dx = q[0] - p[0], dy = q[1] - p[1], dz = q[2] - p[2];
        l = fmax(l, dx * dx + dy * dy + dz * dz);
    }
    return sqrt(l);
}

/* The longest edge and the largest edge / target ratio of L's mesh. */
static void edge_stats(const lepp *L, double *lmax, double *rmax)
{
    double l = 0.0, r = 0.0;
    for (int h = 0; h < 3 * L->nt; h++) {
        const double e = len2(L, h), t = htarget(L, h);
        l = fmax(l, e);
        r = fmax(r, e / (t * t));
    }
    *lmax = sqrt(l);
    *rmax = sqrt(r);
}

/* Both entry points: target (tv NULL) or tv[nv], checked by the caller. */
static glpgp_status refine_run(const glpgp_mesh *m, double target, const double *tv, double max_triangles,
                               glpgp_mesh **out, glpgp_surface_refine_info *info)
{
    lepp L;
    glpgp_status st = lepp_init(&L, m, max_triangles);
    L.tconst = target;
    if (st == GLPGP_OK && tv) {
        st = glpgp_malloc((size_t)m->nv, sizeof(double), &L.tv);
        if (st == GLPGP_OK) {
            L.cap_tv = (size_t)m->nv;
            memcpy(L.tv, tv, (size_t)m->nv * sizeof(double));
        }
    }
    double lmax = 0.0, rmax = 0.0;
    int stopped = 0;
    if (st == GLPGP_OK) edge_stats(&L, &lmax, &rmax);
    if (info) {
        info->nv0 = info->nv = m->nv;
        info->nt0 = info->nt = m->nt;
        info->max_edge0 = info->max_edge = lmax;
        info->ratio0 = info->ratio = rmax;
        info->min_target = target;
        if (tv) {
            info->min_target = HUGE_VAL;
            for (int i = 0; i < m->nv; i++) info->min_target = fmin(info->min_target, tv[i]);
        }
    }
    if (st == GLPGP_OK && rmax > 1.0) st = tv ? run_levels(&L, 1.0, rmax, &stopped) : run_levels(&L, target, lmax, &stopped);
    /* the bisections of a thin input triangle are as thin and smaller: only area 0 is degenerate here */
    if (st == GLPGP_OK && L.splits > 0) st = glpgp_mesh_create_surface_area(L.nv, L.xyz, L.nt, L.tri, 0.0, out);
    if (st == GLPGP_OK && *out) { /* the origin handed over (create_surface keeps the triangles' order) */
        (*out)->surf->otri = L.ot;
        (*out)->surf->obary = L.ob;
        L.ot = NULL;
        L.ob = NULL;
    }
    if (info) {
        info->stopped = stopped;
        if (*out) {
            info->splits = L.splits;
            info->passes = 1;
            info->nv = (*out)->nv;
            info->nt = (*out)->nt;
            edge_stats(&L, &info->max_edge, &info->ratio);
        }
    }
    lepp_free(&L);
    return st;
}

glpgp_status glpgp_mesh_refine_surface(const glpgp_mesh *m, double target, double max_triangles, glpgp_mesh **out,
                                       glpgp_surface_refine_info *info)
{
    *out = NULL;
    if (info) memset(info, 0, sizeof *info);
    if (!m || !m->xyz || !m->surf) return GLPGP_FAIL(GLPGP_ERR_ARG, "refine: not a surface mesh");
    if (!(target > 0.0) || !isfinite(target))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "refine: target edge %g is not positive", target);
    return refine_run(m, target, NULL, max_triangles, out, info);
}

glpgp_status glpgp_mesh_refine_surface_sized(const glpgp_mesh *m, const double *target, double max_triangles,
                                             glpgp_mesh **out, glpgp_surface_refine_info *info)
{
    *out = NULL;
    if (info) memset(info, 0, sizeof *info);
    if (!m || !m->xyz || !m->surf) return GLPGP_FAIL(GLPGP_ERR_ARG, "refine: not a surface mesh");
    if (!target) return GLPGP_FAIL(GLPGP_ERR_ARG, "refine: no per-vertex target");
    for (int i = 0; i < m->nv; i++)
        if (!(target[i] > 0.0) || !isfinite(target[i]))
            return GLPGP_FAIL(GLPGP_ERR_ARG, "refine: target edge %g at vertex %d is not positive", target[i], i);
    return refine_run(m, 0.0, target, max_triangles, out, info);
}

void glpgp_surface_origin_compose(glpgp_mesh *fine, const glpgp_mesh *mid)
{
    glpgp_surface *f = fine->surf;
    const glpgp_surface *s = mid->surf;
    if (!f->otri || !f->obary || !s->otri || !s->obary) return;
    for (int t = 0; t < fine->nt; t++) {
        const int T = f->otri[t];
        double *b = f->obary + 9 * (size_t)t, B[9] = {0};
        const double *bm = s->obary + 9 * (size_t)T;
        for (int a = 0; a < 3; a++)
            for (int j = 0; j < 3; j++)
                for (int k = 0; k < 3; k++) B[3 * a + k] += b[3 * a + j] * bm[3 * j + k];
        memcpy(b, B, sizeof B);
        f->otri[t] = s->otri[T];
    }
}

glpgp_status glpgp_surface_keep_origin(glpgp_mesh *refined, const glpgp_mesh *coarse)
{
    glpgp_surface *f = refined->surf;
    if (!f || !f->otri || !f->obary || !coarse->xyz)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "keep origin: the mesh is not a refined surface");
    glpgp_mesh_destroy(&f->origin);
    f->origin_cross = 1;
    return glpgp_mesh_create_surface(coarse->nv, coarse->xyz, coarse->nt, coarse->tri, &f->origin);
}
