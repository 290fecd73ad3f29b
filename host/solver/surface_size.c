/* solver/surface_size.c: the local size h(x) on a surface
 * (glpgp_surface_size, glpgp/surfsolve.h): a per-vertex file, or the
 * smaller of the curvature cap (the chord of a quad on a curved surface
 * keeps its sagitta below size_chord_depth h, as the planar chord rule) and
 * the spacing of the constraint curves (two creases or boundary loops
 * closer than size_across periods: a chamfer, the rim of a thin plate),
 * graded along the edges. */
#include "internal.h"

#include "glpgp/surfsolve.h"
#include "glpgp/internal/heap.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* the sagitta cap's ladder of patch radii: from h / 2 down by 2^(-1/2)
 * while at least GLPGP_SAGITTA_FLOOR mean edges; each centre's cap spread
 * to the vertices of its patch within GLPGP_SAGITTA_COVER x the cap (or h
 * where none: half the patch's radius; denser centres gave the same sizes
 * for more work: bench/results/surface_refine.md) */
#define GLPGP_SAGITTA_FLOOR 2.0
#define GLPGP_SAGITTA_COVER 0.25
#define GLPGP_SAGITTA_RUNGS 24

static double dist3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Each edge's endpoints to fn: the half-edges out of each corner, plus a
 * boundary fan's incoming edge. */
#define FOR_NEIGHBOURS(m, i, j, BODY)                                                                             \
    do {                                                                                                         \
        const glpgp_surface *fs_ = (m)->surf;                                                                    \
        int c_ = fs_->vstart[i], last_ = c_;                                                                     \
        do {                                                                                                     \
            const int j = (m)->tri[c_ - c_ % 3 + (c_ % 3 + 1) % 3];                                              \
            BODY;                                                                                                \
            last_ = c_;                                                                                          \
            c_ = fs_->twin[c_ - c_ % 3 + (c_ % 3 + 2) % 3];                                                      \
        } while (c_ >= 0 && c_ != fs_->vstart[i]);                                                               \
        if (c_ < 0) {                                                                                            \
            const int j = (m)->tri[last_ - last_ % 3 + (last_ % 3 + 2) % 3];                                     \
            BODY;                                                                                                \
        }                                                                                                        \
    } while (0)

/* s_i <- min(s_i, min_j s_j + g |x_i - x_j|) over the mesh (Dijkstra). */
glpgp_status glpgp_surface_grade(const glpgp_mesh *m, double g, double *s)
{
    glpgp_heap q = {NULL, 0, 0};
    const size_t cap = (size_t)3 * m->nt + (size_t)m->nv + 1;
    GLPGP_CHECK(glpgp_heap_reserve(&q, cap));
    for (int i = 0; i < m->nv; i++) (void)glpgp_heap_push(&q, s[i], i); /* within cap: cannot fail */
    while (q.n > 0) {
        const glpgp_heap_item it = glpgp_heap_pop(&q);
        const int i = it.id;
        if (it.key > s[i]) continue; /* stale */
        FOR_NEIGHBOURS(m, i, j, {
            const double c = s[i] + g * dist3(m->xyz + 3 * i, m->xyz + 3 * j);
            if (c < s[j] && q.n < cap) {
                s[j] = c;
                (void)glpgp_heap_push(&q, c, j);
            }
        });
    }
    glpgp_heap_free(&q);
    return GLPGP_OK;
}

/* The sagitta cap's work space: a patch P(i, rho) grown triangle by
 * triangle from one sector of vertex i (its fan between feature edges)
 * across non-feature edges, nearest first (a triangle's key: its farthest
 * vertex from x_i), so that the triangles popped while the next key is
 * above rho are those reachable from the sector without leaving the ball of
 * radius rho. */
typedef struct sag_ws {
    glpgp_heap q;
    int *tstamp, *vstamp; /* nt, nv: the last patch that pushed the triangle / took the vertex */
    int *pts;             /* the patch's vertices */
    double *pd;           /* their distances from the centre */
    double *val;          /* nv: the smallest cap spread to the vertex (HUGE_VAL: none) */
    unsigned char *covered;
    int np, stamp, nr;
    double rung[GLPGP_SAGITTA_RUNGS]; /* the ladder of radii, ascending */
    double area, ns[3];               /* the patch's area and area-weighted normal sum (x 2) */
} sag_ws;

/* triangle t's farthest vertex from xc */
static double tri_key(const glpgp_mesh *m, int t, const double *xc)
{
    double k = 0.0;
    for (int a = 0; a < 3; a++) k = fmax(k, dist3(m->xyz + 3 * (size_t)m->tri[3 * t + a], xc));
    return k;
}

/* Triangle t into the patch: its area normal, its new vertices. */
static void patch_take(const glpgp_mesh *m, sag_ws *w, int t, const double *xc)
{
    const double *p = m->xyz + 3 * (size_t)m->tri[3 * t], *q = m->xyz + 3 * (size_t)m->tri[3 * t + 1],
                 *r = m->xyz + 3 * (size_t)m->tri[3 * t + 2];
    const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    for (int e = 0; e < 3; e++) w->ns[e] += n[e];
    w->area += sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int a = 0; a < 3; a++) {
        const int j = m->tri[3 * t + a];
        if (w->vstamp[j] == w->stamp) continue;
        w->vstamp[j] = w->stamp;
        w->pts[w->np] = j;
        w->pd[w->np++] = dist3(m->xyz + 3 * (size_t)j, xc);
    }
}

/* The patch's deviation from the plane through the centre normal to the
 * patch's area-weighted normal: its vertices' largest height above or below
 * it (the sagitta of a spherical cap; on a saddle the larger principal
 * curvature's, as the chord rule: the range above and below together would
 * add the two; noise of amplitude a: at most 2 a); *reach its farthest
 * vertex. A patch whose normals cancel (projected area under half its
 * area: more than a hemisphere, or folded) deviates without bound. */
static double patch_dev(const glpgp_mesh *m, const sag_ws *w, const double *xc, double *reach)
{
    const double nn = sqrt(w->ns[0] * w->ns[0] + w->ns[1] * w->ns[1] + w->ns[2] * w->ns[2]);
    double lo = 0.0, hi = 0.0, r = 0.0;
    for (int k = 0; k < w->np; k++) {
        const double *x = m->xyz + 3 * (size_t)w->pts[k];
        const double z = ((x[0] - xc[0]) * w->ns[0] + (x[1] - xc[1]) * w->ns[1] + (x[2] - xc[2]) * w->ns[2]) / nn;
        lo = fmin(lo, z);
        hi = fmax(hi, z);
        r = fmax(r, w->pd[k]);
    }
    *reach = r;
    return nn > 0.5 * w->area ? fmax(hi, -lo) : HUGE_VAL;
}

/* The sector of vertex i from its corner c (c0 the fan's first): its
 * triangles pushed as the patch's seeds; returns the next sector's corner
 * (-1 or c0 when none). */
static int sector_seed(const glpgp_mesh *m, const glpgp_surface_constraints *con, sag_ws *w, int c, int c0,
                       glpgp_status *st)
{
    const int *tw = m->surf->twin;
    int k = c;
    do {
        if (w->tstamp[k / 3] != w->stamp) {
            w->tstamp[k / 3] = w->stamp;
            if (*st == GLPGP_OK) *st = glpgp_heap_push(&w->q, 0.0, k / 3);
        }
        k = tw[k - k % 3 + (k % 3 + 2) % 3];
    } while (k >= 0 && k != c0 && !con->feature[k]);
    return k;
}

/* The radius of deviation d between a passing patch (reach ra, deviation
 * da <= d; ra 0: none) and the failing one (rb, db > d): dev = c rho^p
 * through both (p from the two, within [1, 4]: a fold's deviation grows
 * linearly, a sphere's with the square; with no passing patch, or one of
 * no deviation, the square law from the failing one), within [ra, rb]. */
static double rho_star(double ra, double da, double rb, double db, double d)
{
    double p = 2.0;
    if (ra > 0.0 && da > 0.0 && rb > ra) p = fmin(4.0, fmax(1.0, log(db / da) / log(rb / ra)));
    return fmin(rb, fmax(ra, rb * pow(d / db, 1.0 / p)));
}

/* The patch grown from the seeds rung by rung, stopped at the first rung
 * whose deviation exceeds d: *cap = 2 rho*, rho* = reach sqrt(d / dev) (the
 * sagitta's square law from the failing rung, within the reach of the last
 * passing one and the failing one); HUGE_VAL when even rho = h / 2 passes. */
static glpgp_status patch_cap(const glpgp_mesh *m, const glpgp_surface_constraints *con, sag_ws *w, int i, double d,
                              double *cap)
{
    const double *xc = m->xyz + 3 * (size_t)i;
    const int *tw = m->surf->twin;
    double pass = 0.0, dpass = 0.0; /* the last passing rung's reach and deviation */
    int r = 0;
    *cap = HUGE_VAL;
    for (;;) {
        const double next = w->q.n ? w->q.a[0].key : HUGE_VAL;
        while (r < w->nr && next > w->rung[r]) {
            double reach;
            const double dev = patch_dev(m, w, xc, &reach);
            if (dev > d) {
                *cap = 2.0 * rho_star(pass, dpass, reach, dev, d);
                return GLPGP_OK;
            }
            pass = reach;
            dpass = dev;
            r = w->q.n ? r + 1 : w->nr; /* nothing more to take: every rung passes */
        }
        if (r == w->nr) return GLPGP_OK;
        const int t = glpgp_heap_pop(&w->q).id;
        patch_take(m, w, t, xc);
        for (int a = 0; a < 3; a++) {
            const int hh = 3 * t + a, u = tw[hh];
            if (u < 0 || con->feature[hh] || w->tstamp[u / 3] == w->stamp) continue;
            w->tstamp[u / 3] = w->stamp;
            GLPGP_CHECK(glpgp_heap_push(&w->q, tri_key(m, u / 3, xc), u / 3));
        }
    }
}

/* Vertex i as a centre: each sector's patch cap spread to the patch's
 * vertices within GLPGP_SAGITTA_COVER x the cap (h where none). */
static glpgp_status centre_caps(const glpgp_mesh *m, const glpgp_surface_constraints *con, sag_ws *w, int i,
                                double d, double h)
{
    const glpgp_surface *g = m->surf;
    int c0 = g->vstart[i], c = c0;
    if (c0 < 0) return GLPGP_OK;
    if (!m->on_boundary[i]) do { /* inside: start at a feature edge where there is one */
        if (con->feature[c]) {
            c0 = c;
            break;
        }
        c = g->twin[c - c % 3 + (c % 3 + 2) % 3];
    } while (c >= 0 && c != g->vstart[i]);
    c = c0;
    do {
        glpgp_status st = GLPGP_OK;
        w->stamp++;
        w->np = 0;
        w->q.n = 0;
        w->area = w->ns[0] = w->ns[1] = w->ns[2] = 0.0;
        const int next = sector_seed(m, con, w, c, c0, &st);
        GLPGP_CHECK(st);
        double cap;
        GLPGP_CHECK(patch_cap(m, con, w, i, d, &cap));
        const double cover = GLPGP_SAGITTA_COVER * fmin(h, cap);
        for (int k = 0; k < w->np; k++)
            if (w->pd[k] <= cover || w->pts[k] == i) {
                w->val[w->pts[k]] = fmin(w->val[w->pts[k]], cap);
                w->covered[w->pts[k]] = 1;
            }
        c = next;
    } while (c >= 0 && c != c0);
    return GLPGP_OK;
}

/* The curvature cap measured as the sagitta itself (no normals' turn per
 * edge, which reads a scan's noise as curvature and grows as the same
 * polyhedron is bisected): h_curv(i) = 2 rho*, rho* the largest patch radius
 * on the ladder h / 2 x 2^(-k/2) (down to GLPGP_SAGITTA_FLOOR mean edges)
 * whose patch deviates from its plane by at most d = depth h (on a sphere of
 * radius R the chord 2 sqrt(2 R d - d^2), the planar chord rule; noise of
 * amplitude under d / 2 caps nothing). A crease is not crossed (each sector
 * of a vertex on it has its own patch: a crease between flat faces is no
 * curvature). Bounded work: the patches are grown only around centres
 * (every vertex not yet covered by one, in index order: within
 * GLPGP_SAGITTA_COVER x its cap or h), each stopped at its first failing
 * rung; a vertex takes the smallest cap of the centres covering it. Where
 * nothing caps, about 12 triangle visits per triangle (a patch of radius
 * h / 2 per centre, centres h / 4 apart). */
static glpgp_status sagitta_cap(const glpgp_mesh *m, const glpgp_surface_constraints *con, double d, double h,
                                double *s)
{
    if (!(d > 0.0) || m->nv == 0) return GLPGP_OK;
    sag_ws w;
    memset(&w, 0, sizeof w);
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)m->nt, sizeof(int), &w.tstamp), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)m->nv, sizeof(int), &w.vstamp), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)m->nv, sizeof(int), &w.pts), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)m->nv, sizeof(double), &w.pd), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)m->nv, sizeof(double), &w.val), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)m->nv, 1, &w.covered), done);
    GLPGP_CHECK_GOTO(st, glpgp_heap_reserve(&w.q, 256), done);
    double lad[GLPGP_SAGITTA_RUNGS], r = 0.5 * h;
    int n = 0;
    do {
        lad[n++] = r;
        r *= sqrt(0.5);
    } while (n < GLPGP_SAGITTA_RUNGS && r >= GLPGP_SAGITTA_FLOOR * m->mean_edge);
    for (int k = 0; k < n; k++) w.rung[k] = lad[n - 1 - k];
    w.nr = n;
    for (int i = 0; i < m->nv; i++) w.val[i] = HUGE_VAL;
    for (int i = 0; i < m->nv && st == GLPGP_OK; i++)
        if (!w.covered[i]) st = centre_caps(m, con, &w, i, d, h);
    if (st == GLPGP_OK)
        for (int i = 0; i < m->nv; i++) s[i] = fmin(s[i], w.val[i]);
done:
    free(w.tstamp);
    free(w.vstamp);
    free(w.pts);
    free(w.pd);
    free(w.val);
    free(w.covered);
    glpgp_heap_free(&w.q);
    return st;
}

/* The spacing of the constraint curves (maximal chains of vertices with
 * exactly two constraint edges; corners split them): a Dijkstra from every
 * curve vertex labelled by its curve; where two fronts of different curves
 * meet on an edge and the segment between their sources is within 60
 * degrees of normal to both curves (two sides of a strip, not two curves
 * meeting at a corner), the gap is that segment's length: sizes at most
 * gap / across at both sources and at the edge. */
static glpgp_status feature_spacing(const glpgp_mesh *m, const glpgp_surface_constraints *con, double across, double *s)
{
    const int nv = m->nv;
    int *lab = NULL, *src = NULL;
    double *d = NULL, *tan3 = NULL;
    glpgp_heap q = {NULL, 0, 0};
    glpgp_status st = GLPGP_OK;
    const size_t cap = (size_t)3 * m->nt + (size_t)nv + 1;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(int), &lab), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(int), &src), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(double), &d), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)6 * nv, sizeof(double), &tan3), done);
    GLPGP_CHECK_GOTO(st, glpgp_heap_reserve(&q, cap), done);
    /* curve labels: union of constraint edges between two-edge vertices; tangents */
    for (int i = 0; i < nv; i++) lab[i] = con->cptr[i + 1] - con->cptr[i] == 2 ? i : -1;
    for (int h = 0; h < 3 * m->nt; h++) {
        const int tw = m->surf->twin[h];
        if (!(tw < 0 || (con->feature[h] && tw < h))) continue; /* each constraint edge once */
        const int i = m->tri[h], j = m->tri[h - h % 3 + (h % 3 + 1) % 3];
        const double l = dist3(m->xyz + 3 * i, m->xyz + 3 * j);
        for (int e = 0; e < 2; e++) { /* the (at most two) unit edge directions of each end */
            const int v = e ? j : i;
            double *t = tan3 + 6 * v + (tan3[6 * v] == 0.0 && tan3[6 * v + 1] == 0.0 && tan3[6 * v + 2] == 0.0 ? 0 : 3);
            for (int k = 0; k < 3; k++) t[k] = (m->xyz[3 * j + k] - m->xyz[3 * i + k]) / l;
        }
        if (lab[i] >= 0 && lab[j] >= 0) {
            const int a = glpgp_uf_find(lab, i), b = glpgp_uf_find(lab, j);
            if (a != b) lab[b] = a;
        }
    }
    for (int i = 0; i < nv; i++) {
        d[i] = HUGE_VAL;
        src[i] = -1;
        if (lab[i] >= 0) {
            d[i] = 0.0;
            src[i] = i;
            (void)glpgp_heap_push(&q, 0.0, i); /* within cap */
        }
    }
    for (int i = 0; i < nv; i++)
        if (lab[i] >= 0) lab[i] = glpgp_uf_find(lab, i);
    while (q.n > 0) {
        const glpgp_heap_item it = glpgp_heap_pop(&q);
        const int i = it.id;
        if (it.key > d[i]) continue;
        FOR_NEIGHBOURS(m, i, j, {
            const double c = d[i] + dist3(m->xyz + 3 * i, m->xyz + 3 * j);
            if (c < d[j] && q.n < cap) {
                d[j] = c;
                src[j] = src[i];
                (void)glpgp_heap_push(&q, c, j);
            }
        });
    }
    for (int h = 0; h < 3 * m->nt; h++) {
        const int i = m->tri[h], j = m->tri[h - h % 3 + (h % 3 + 1) % 3];
        const int p = src[i], r = src[j];
        if (p < 0 || r < 0 || lab[p] == lab[r]) continue;
        const double *xp = m->xyz + 3 * p, *xr = m->xyz + 3 * r, gap = dist3(xp, xr);
        if (!(gap > 0.0)) continue;
        /* the segment within 60 degrees of normal to both curves' edges at its ends */
        double c[4] = {0.0, 0.0, 0.0, 0.0};
        for (int k = 0; k < 3; k++) {
            const double dk = (xr[k] - xp[k]) / gap;
            c[0] += dk * tan3[6 * p + k];
            c[1] += dk * tan3[6 * p + 3 + k];
            c[2] += dk * tan3[6 * r + k];
            c[3] += dk * tan3[6 * r + 3 + k];
        }
        if (fabs(c[0]) > 0.5 || fabs(c[1]) > 0.5 || fabs(c[2]) > 0.5 || fabs(c[3]) > 0.5) continue;
        const double v = gap / across;
        s[p] = fmin(s[p], v);
        s[r] = fmin(s[r], v);
        s[i] = fmin(s[i], v);
        s[j] = fmin(s[j], v);
    }
done:
    free(lab);
    free(src);
    free(d);
    free(tan3);
    glpgp_heap_free(&q);
    return st;
}

glpgp_status glpgp_surface_size_local(const glpgp_mesh *m, const glpgp_options *o,
                                      const glpgp_surface_constraints *con, double h, int spacing, double *size)
{
    for (int i = 0; i < m->nv; i++) size[i] = h;
    GLPGP_CHECK(sagitta_cap(m, con, o->size_chord_depth * h, h, size));
    if (spacing) GLPGP_CHECK(feature_spacing(m, con, o->size_across, size));
    for (int i = 0; i < m->nv; i++) size[i] = fmax(size[i], o->size_min * h);
    return glpgp_surface_grade(m, o->size_grading, size);
}

glpgp_status glpgp_surface_size(const glpgp_mesh *m, const glpgp_options *o, const glpgp_surface_constraints *con,
                                double h, double *size, int *uniform)
{
    const int nv = m->nv;
    *uniform = 1;
    for (int i = 0; i < 2 * nv; i++) size[i] = h;
    if (o->size_field == GLPGP_SIZE_NONE) return GLPGP_OK;
    if (o->size_field == GLPGP_SIZE_FILE) {
        GLPGP_CHECK(glpgp_size_file_read(m, o->size_file, size));
    } else {
        GLPGP_CHECK(glpgp_surface_size_local(m, o, con, h, 1, size));
        memcpy(size + nv, size, (size_t)nv * sizeof(double));
    }
    /* what the mesh carries: at least min(h, size_resolution x the longest edge at the vertex) */
    for (int t = 0; t < m->nt; t++)
        for (int a = 0; a < 3; a++) {
            const int i = m->tri[3 * t + a], j = m->tri[3 * t + (a + 1) % 3];
            const double l = fmin(h, o->size_resolution * dist3(m->xyz + 3 * i, m->xyz + 3 * j));
            for (int k = 0; k < 2; k++) {
                size[k * nv + i] = fmax(size[k * nv + i], l);
                size[k * nv + j] = fmax(size[k * nv + j], l);
            }
        }
    for (int i = 0; i < 2 * nv; i++)
        if (size[i] != h) *uniform = 0;
    return GLPGP_OK;
}
