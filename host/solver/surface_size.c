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

/* the curvature cap's sampling distance (ring_curvature): h / 4, at most 8
 * mean edges (the work per vertex grows with its square: on an 82k-vertex
 * scan at 49 mean edges per h, 4.7 s without the bound; a mesh that fine
 * is not refined) */
#define GLPGP_SURFACE_CURVATURE_SCALE 0.25
#define GLPGP_SURFACE_CURVATURE_EDGES 8.0

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
static glpgp_status grade(const glpgp_mesh *m, double g, double *s)
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

/* The chord of sagitta d on a circle of curvature kap (h where kap or d is 0). */
static double chord_cap(double kap, double d)
{
    if (!(kap > 0.0) || !(d > 0.0)) return HUGE_VAL;
    const double R = 1.0 / kap;
    return d < R ? 2.0 * sqrt(2.0 * R * d - d * d) : 2.0 * R;
}

/* fv (nv) <- 1 at the vertices on a sharp feature edge */
static void feature_vertices(const glpgp_mesh *m, const glpgp_surface_constraints *con, unsigned char *fv)
{
    memset(fv, 0, (size_t)m->nv);
    for (int h = 0; h < 3 * m->nt; h++)
        if (con->feature[h]) fv[m->tri[h]] = fv[m->tri[h - h % 3 + (h % 3 + 1) % 3]] = 1;
}

/* The curvature cap at the smooth vertices (no feature edge), measured at
 * a fixed scale r: the largest |(n_j - n_i) . (x_j - x_i)| / |x_j - x_i|^2
 * over the smooth vertices j first reached at path distance >= r (a
 * Dijkstra from i through smooth vertices, not expanded beyond r; the
 * nearer ones when none is that far), n the vertex normals. At the scale
 * of the edges instead (the one-ring), the estimate of a vertex of the
 * input grows as its edges are bisected: the refined polyhedron's new
 * vertices carry its facets' normals, which differ from the old vertex's
 * by the input's edge over R whatever the new edge's length (measured on
 * genus2:20000: h / 2.5 on the input, h / 4.0 and h / 7.9 refined to h / 16
 * and h / 32, h = 0.3). At r of the order of the input's edges or more,
 * the samples see nearly the same normal turn on the input and on any
 * refinement of it: the bias left is at most the facets' normal error (the
 * input's edge over R) over r (there h / 1.77, 1.88, 1.93; on the unit
 * sphere at h = 2, 1.303, 1.298, 1.18 for the chord 1.323: tests/solver/
 * test_surface_refine.c). */
static glpgp_status ring_curvature(const glpgp_mesh *m, const unsigned char *fv, double r, double depth, double h,
                                   double *s)
{
    const int nv = m->nv;
    const double *vn = m->surf->vnormal;
    double *d = NULL;
    int *seen = NULL;
    glpgp_heap q = {NULL, 0, 0};
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(double), &d), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(int), &seen), done);
    GLPGP_CHECK_GOTO(st, glpgp_heap_reserve(&q, 64), done);
    for (int i = 0; i < nv; i++) seen[i] = -1;
    for (int i = 0; i < nv && st == GLPGP_OK; i++) {
        if (fv[i]) continue;
        int nl = 0;
        double far = 0.0, near = 0.0; /* the largest curvature sample beyond r, and nearer */
        q.n = 0;
        d[i] = 0.0;
        seen[i] = i;
        st = glpgp_heap_push(&q, 0.0, i);
        while (st == GLPGP_OK && q.n > 0) {
            const glpgp_heap_item it = glpgp_heap_pop(&q);
            const int a = it.id;
            if (it.key > d[a]) continue; /* stale */
            if (a != i) {
                const double *xa = m->xyz + 3 * a, *xi = m->xyz + 3 * i, l = dist3(xa, xi);
                double dn = 0.0;
                for (int e = 0; e < 3; e++) dn += (vn[3 * a + e] - vn[3 * i + e]) * (xa[e] - xi[e]);
                const double k = fabs(dn) / (l * l);
                if (d[a] >= r) {
                    far = fmax(far, k);
                    nl++;
                    continue; /* a sample: not expanded */
                }
                near = fmax(near, k);
            }
            FOR_NEIGHBOURS(m, a, j, {
                const double c = d[a] + dist3(m->xyz + 3 * a, m->xyz + 3 * j);
                if (!fv[j] && (seen[j] != i || c < d[j]) && st == GLPGP_OK) {
                    seen[j] = i;
                    d[j] = c;
                    st = glpgp_heap_push(&q, c, j);
                }
            });
        }
        s[i] = fmin(s[i], chord_cap(nl ? far : near, depth * h));
    }
done:
    free(d);
    free(seen);
    glpgp_heap_free(&q);
    return st;
}

/* The curvature cap: R_i = 1 / the largest normal curvature |(n_j - n_i) .
 * e| / |e|^2 over the vertex's edges e = x_j - x_i, with the normals of the
 * smooth sectors the edge lies in (each vertex's fan split at its feature
 * edges, a sector's normal the angle-weighted mean of its triangles'): a
 * crease between two flat faces is no curvature (the plain vertex normal,
 * averaged across it, would make it one); chord of sagitta d = depth h. */
static glpgp_status curvature_cap(const glpgp_mesh *m, const glpgp_surface_constraints *con, const unsigned char *fv,
                                  double depth, double h, double *s)
{
    const glpgp_surface *g = m->surf;
    double *sn = NULL; /* 3 per corner: its sector's normal */
    GLPGP_CHECK(glpgp_malloc((size_t)9 * m->nt, sizeof(double), &sn));
    for (int i = 0; i < m->nv; i++) {
        /* inside, start the walk at a feature edge where there is one (a sector's
         * first corner); a boundary fan starts at its first corner anyway */
        int c0 = g->vstart[i], c = c0;
        if (!m->on_boundary[i]) do {
            if (con->feature[c]) {
                c0 = c;
                break;
            }
            c = g->twin[c - c % 3 + (c % 3 + 2) % 3];
        } while (c >= 0 && c != g->vstart[i]);
        c = c0;
        do { /* one sector: from c0 (or a feature edge) to the next feature edge */
            double acc[3] = {0.0, 0.0, 0.0};
            int k = c, n = 0;
            do {
                const double *N = g->tframe + 9 * (k / 3) + 6;
                for (int e = 0; e < 3; e++) acc[e] += g->corner[k] * N[e];
                n++;
                k = g->twin[k - k % 3 + (k % 3 + 2) % 3];
            } while (k >= 0 && k != c0 && !con->feature[k]);
            const double an = sqrt(acc[0] * acc[0] + acc[1] * acc[1] + acc[2] * acc[2]);
            for (int q = 0, kk = c; q < n; q++) {
                for (int e = 0; e < 3; e++) sn[3 * kk + e] = acc[e] / an;
                kk = g->twin[kk - kk % 3 + (kk % 3 + 2) % 3];
            }
            c = k;
        } while (c >= 0 && c != c0);
    }
    for (int t = 0; t < m->nt; t++)
        for (int a = 0; a < 3; a++) {
            const int ca = 3 * t + a, cb = 3 * t + (a + 1) % 3, i = m->tri[ca], j = m->tri[cb];
            if (!fv[i] && !fv[j]) continue; /* both smooth: ring_curvature */
            const double *xi = m->xyz + 3 * i, *xj = m->xyz + 3 * j, l = dist3(xi, xj);
            double dn = 0.0;
            for (int e = 0; e < 3; e++) dn += (sn[3 * cb + e] - sn[3 * ca + e]) * (xj[e] - xi[e]);
            const double cap = chord_cap(fabs(dn) / (l * l), depth * h);
            if (fv[i]) s[i] = fmin(s[i], cap);
            if (fv[j]) s[j] = fmin(s[j], cap);
        }
    free(sn);
    return GLPGP_OK;
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
                                      const glpgp_surface_constraints *con, double h, double *size)
{
    for (int i = 0; i < m->nv; i++) size[i] = h;
    unsigned char *fv = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)m->nv, 1, &fv));
    feature_vertices(m, con, fv);
    glpgp_status st = curvature_cap(m, con, fv, o->size_chord_depth, h, size);
    if (st == GLPGP_OK) st = ring_curvature(m, fv, fmin(GLPGP_SURFACE_CURVATURE_SCALE * h, GLPGP_SURFACE_CURVATURE_EDGES * m->mean_edge),
                                               o->size_chord_depth, h, size);
    free(fv);
    GLPGP_CHECK(st);
    GLPGP_CHECK(feature_spacing(m, con, o->size_across, size));
    for (int i = 0; i < m->nv; i++) size[i] = fmax(size[i], o->size_min * h);
    return grade(m, o->size_grading, size);
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
        GLPGP_CHECK(glpgp_surface_size_local(m, o, con, h, size));
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
