/* mesh/surface_denoise.c: a scan's noise taken out of the geometry the solve
 * reads (glpgp_surface_denoise, glpgp/surface.h).
 *
 * A vertex jitter of a third of an edge or more turns the normals at random
 * from triangle to triangle: the angle defects (the discrete Gauss curvature
 * the cross field's connection integrates) swing by tenths of a radian per
 * vertex and the field puts singularities on them, the curvature cap of the
 * local size reads the noise as curvature and refines everything, and the
 * principal directions are noise. Where the input shows such noise (an
 * interior edge above the feature angle that is not a crease,
 * glpgp_surface_features' three tests, or a triangle turned over against its
 * neighbours: a sliver folded by the jitter, whose three edges pass every
 * crease test), its vertices and eight rings around them (the jitter's kinks
 * below the angle lie between: with two rings, 13% of a 0.5% jittered scan
 * kept its noise) are smoothed by bilateral normal filtering (Zheng, Fu, Au,
 * Tai 2011): the triangles' normals are averaged over the triangles that
 * share a vertex with them, weighted by area, by distance (Gaussian of the
 * mean edge) and by the difference of the normals (Gaussian of
 * DENOISE_SIGMA_R), so that across a crease (normals apart by 2 sin(theta /
 * 2): 1.41 at 90 degrees) nothing is averaged and the noise on either side
 * is; then the vertices are moved to fit the planes of those normals.
 * Creases and corners come out sharp without being told where they are
 * (pinning the vertices of what the crease tests keep on a rough input kept
 * noise ridges that pass them: bench/results/surface_features.md). A fold's
 * normal is its neighbours' mean, and its vertices take a few Laplacian
 * steps (the fit along normals cannot undo a vertex pushed across an edge).
 * Boundary vertices stay; no vertex moves by more than max_move. A clean
 * mesh (no noise edge, no fold) is not touched. */
#include "glpgp/kinds.h"
#include "glpgp/surface.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DENOISE_RINGS 8       /* the smoothed region: edge rings around the noise edges and folds */
#define DENOISE_SIGMA_R 0.35  /* the range weight's width (normal differences) */
#define DENOISE_ROUNDS 3      /* normals from the positions, filtered, the positions fitted: rounds */
#define DENOISE_NORMAL_ITERS 5
#define DENOISE_VERTEX_ITERS 10
#define DENOISE_UNFOLD_ITERS 5
#define DENOISE_FOLD_AGREE 60.0 /* a fold's neighbours: normals pairwise within this (degrees) */

typedef struct dn_ws {
    int *vstart, *vface;   /* nv + 1, 3 nt: each vertex's triangles */
    unsigned char *region; /* nv: moved (not on the boundary) */
    unsigned char *mark;   /* nv: a fold's vertices (2) and their neighbours (1) */
    unsigned char *tact;   /* nt: a triangle with a vertex in the region (its normal filtered) */
    unsigned char *flag;   /* 3 nt: features */
    int *stamp;            /* nt */
    double *n, *n2, *c, *a; /* 3 nt, 3 nt, 3 nt, nt: normals (filtered), centroids, areas */
    double *d;             /* 3 nv: a vertex step */
} dn_ws;

static void dn_free(dn_ws *w)
{
    free(w->vstart);
    free(w->vface);
    free(w->region);
    free(w->mark);
    free(w->tact);
    free(w->flag);
    free(w->stamp);
    free(w->n);
    free(w->n2);
    free(w->c);
    free(w->a);
    free(w->d);
}

static glpgp_status dn_alloc(const glpgp_mesh *m, dn_ws *w)
{
    const size_t nt = (size_t)m->nt, nv = (size_t)m->nv;
    GLPGP_CHECK(glpgp_mesh_vertex_triangles(m, &w->vstart, &w->vface));
    GLPGP_CHECK(glpgp_malloc(nv, 1, &w->region));
    GLPGP_CHECK(glpgp_malloc(nv, 1, &w->mark));
    GLPGP_CHECK(glpgp_calloc(nt, 1, &w->tact));
    GLPGP_CHECK(glpgp_malloc(3 * nt, 1, &w->flag));
    GLPGP_CHECK(glpgp_calloc(nt, sizeof(int), &w->stamp));
    GLPGP_CHECK(glpgp_malloc(3 * nt, sizeof(double), &w->n));
    GLPGP_CHECK(glpgp_malloc(3 * nt, sizeof(double), &w->n2));
    GLPGP_CHECK(glpgp_malloc(3 * nt, sizeof(double), &w->c));
    GLPGP_CHECK(glpgp_malloc(nt, sizeof(double), &w->a));
    GLPGP_CHECK(glpgp_malloc(3 * nv, sizeof(double), &w->d));
    return GLPGP_OK;
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* The fold rule on triangle t, the unit normal of triangle x at n +
 * stride x: two of t's neighbours agree (normals within DENOISE_FOLD_AGREE
 * degrees: a smooth piece of surface) and t's normal is against both (more
 * than 90 degrees from each): a sliver folded by a jitter, whose three
 * edges pass every crease test (the third neighbour may be folded too). A
 * polyhedron's face is not one: its neighbours disagree with each other (a
 * tetrahedron's, a cube corner's) or it agrees with one (a knife edge). */
static int fold_rule(const glpgp_mesh *m, const double *n, size_t stride, int t)
{
    const int *twin = m->surf->twin;
    const double *nb[3];
    int k = 0;
    for (int a = 0; a < 3; a++)
        if (twin[3 * t + a] >= 0) nb[k++] = n + stride * (size_t)(twin[3 * t + a] / 3);
    const double agree = cos(DENOISE_FOLD_AGREE * GLPGP_PI / 180.0), *nt = n + stride * (size_t)t;
    for (int i = 0; i < k; i++)
        for (int j = i + 1; j < k; j++)
            if (dot3(nb[i], nb[j]) > agree && dot3(nt, nb[i]) < 0.0 && dot3(nt, nb[j]) < 0.0) return 1;
    return 0;
}

/* whether triangle t of m is a fold (m's own normals) */
static int dn_is_fold(const glpgp_mesh *m, int t) { return fold_rule(m, m->surf->tframe + 6, 9, t); }

/* The region: the ends of the noise edges (above the angle, not features)
 * and the folds' vertices, grown by DENOISE_RINGS rings through the
 * triangles, less the boundary; tact: the triangles with a vertex in it.
 * *noise, *folds: their counts. */
static glpgp_status dn_region(const glpgp_mesh *m, double feature_deg, dn_ws *w, int *noise, int *folds)
{
    const glpgp_surface *g = m->surf;
    const double lim = feature_deg * GLPGP_PI / 180.0;
    GLPGP_CHECK(glpgp_surface_features(m, feature_deg, w->flag, NULL));
    int n = 0, f = 0;
    memset(w->region, 0, (size_t)m->nv);
    for (int h = 0; h < 3 * m->nt; h++)
        if (g->twin[h] > h && g->dihedral[h] > lim && !w->flag[h]) {
            w->region[m->tri[h]] = w->region[m->tri[h - h % 3 + (h % 3 + 1) % 3]] = 1;
            n++;
        }
    for (int t = 0; t < m->nt; t++)
        if (dn_is_fold(m, t)) {
            f++;
            for (int a = 0; a < 3; a++) w->region[m->tri[3 * t + a]] = 1;
        }
    for (int r = 1; r <= DENOISE_RINGS; r++)
        for (int v = 0; v < m->nv; v++)
            if (w->region[v] == r)
                for (int k = w->vstart[v]; k < w->vstart[v + 1]; k++)
                    for (int a = 0; a < 3; a++) {
                        const int u = m->tri[3 * w->vface[k] + a];
                        if (!w->region[u]) w->region[u] = (unsigned char)(r + 1);
                    }
    for (int v = 0; v < m->nv; v++)
        if (m->on_boundary[v]) w->region[v] = 0;
    for (int t = 0; t < m->nt; t++)
        w->tact[t] = w->region[m->tri[3 * t]] || w->region[m->tri[3 * t + 1]] || w->region[m->tri[3 * t + 2]];
    *noise = n;
    *folds = f;
    return GLPGP_OK;
}

/* unit normal, centroid and area of every triangle at positions x */
static void dn_geometry(const glpgp_mesh *m, const double *x, dn_ws *w, int normals)
{
    for (int t = 0; t < m->nt; t++) {
        const double *p = x + 3 * (size_t)m->tri[3 * t], *q = x + 3 * (size_t)m->tri[3 * t + 1],
                     *r = x + 3 * (size_t)m->tri[3 * t + 2];
        const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
        const double nn[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        const double l = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
        w->a[t] = 0.5 * l;
        for (int k = 0; k < 3; k++) {
            w->c[3 * (size_t)t + k] = (p[k] + q[k] + r[k]) / 3.0;
            if (normals) w->n[3 * (size_t)t + k] = l > 0.0 ? nn[k] / l : 0.0;
        }
    }
}

/* One pass of the bilateral filter over the active triangles' normals:
 * each the normalised sum over the triangles sharing a vertex with it of
 * area x exp(-|dc|^2 / 2 ss^2) x exp(-|dn|^2 / 2 sr^2) x normal. */
static void dn_filter_normals(const glpgp_mesh *m, dn_ws *w, double ss, int *tick)
{
    const double is = 1.0 / (2.0 * ss * ss), ir = 1.0 / (2.0 * DENOISE_SIGMA_R * DENOISE_SIGMA_R);
    for (int t = 0; t < m->nt; t++) {
        const double *nt = w->n + 3 * (size_t)t, *ct = w->c + 3 * (size_t)t;
        double *o = w->n2 + 3 * (size_t)t, s[3] = {0.0, 0.0, 0.0};
        if (!w->tact[t]) {
            memcpy(o, nt, 3 * sizeof(double));
            continue;
        }
        const int st = ++*tick;
        for (int a = 0; a < 3; a++) {
            const int v = m->tri[3 * t + a];
            for (int k = w->vstart[v]; k < w->vstart[v + 1]; k++) {
                const int f = w->vface[k];
                if (w->stamp[f] == st) continue;
                w->stamp[f] = st;
                const double *nf = w->n + 3 * (size_t)f, *cf = w->c + 3 * (size_t)f;
                double dc = 0.0, dn = 0.0;
                for (int e = 0; e < 3; e++) {
                    dc += (ct[e] - cf[e]) * (ct[e] - cf[e]);
                    dn += (nt[e] - nf[e]) * (nt[e] - nf[e]);
                }
                const double wt = w->a[f] * exp(-dc * is - dn * ir);
                for (int e = 0; e < 3; e++) s[e] += wt * nf[e];
            }
        }
        const double l = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        for (int e = 0; e < 3; e++) o[e] = l > 0.0 ? s[e] / l : nt[e];
    }
    double *sw = w->n;
    w->n = w->n2;
    w->n2 = sw;
}

/* One pass of the vertex fit: each region vertex moved by the mean of its
 * triangles' n (n . (c - x)) (towards their planes through their
 * centroids, along their filtered normals). */
static void dn_fit_vertices(const glpgp_mesh *m, dn_ws *w, double *x)
{
    dn_geometry(m, x, w, 0);
    for (int v = 0; v < m->nv; v++) {
        double *d = w->d + 3 * (size_t)v;
        d[0] = d[1] = d[2] = 0.0;
        if (!w->region[v]) continue;
        const int cnt = w->vstart[v + 1] - w->vstart[v];
        for (int k = w->vstart[v]; k < w->vstart[v + 1]; k++) {
            const int f = w->vface[k];
            const double *nf = w->n + 3 * (size_t)f, *cf = w->c + 3 * (size_t)f;
            const double h = nf[0] * (cf[0] - x[3 * (size_t)v]) + nf[1] * (cf[1] - x[3 * (size_t)v + 1]) +
                             nf[2] * (cf[2] - x[3 * (size_t)v + 2]);
            for (int e = 0; e < 3; e++) d[e] += nf[e] * h / cnt;
        }
    }
    for (size_t i = 0; i < (size_t)3 * m->nv; i++) x[i] += w->d[i];
}

/* x moved by at most max_move from x0; returns how many were cut */
static int dn_cap(int nv, const double *x0, double max_move, double *x)
{
    int cut = 0;
    for (int v = 0; v < nv; v++) {
        double d[3], l = 0.0;
        for (int c = 0; c < 3; c++) {
            d[c] = x[3 * (size_t)v + c] - x0[3 * (size_t)v + c];
            l += d[c] * d[c];
        }
        l = sqrt(l);
        if (l > max_move) {
            for (int c = 0; c < 3; c++) x[3 * (size_t)v + c] = x0[3 * (size_t)v + c] + d[c] * (max_move / l);
            cut++;
        }
    }
    return cut;
}

/* the displacement statistics and the after counts of *out (d) against m */
static glpgp_status dn_report(const glpgp_mesh *m, const glpgp_mesh *d, double feature_deg, dn_ws *w,
                              glpgp_surface_denoise_info *info)
{
    double sum = 0.0;
    for (int v = 0; v < m->nv; v++) {
        double l = 0.0;
        for (int c = 0; c < 3; c++) {
            const double e = d->xyz[3 * (size_t)v + c] - m->xyz[3 * (size_t)v + c];
            l += e * e;
        }
        if (!(l > 0.0)) continue;
        l = sqrt(l);
        info->moved++;
        sum += l;
        info->max_move = fmax(info->max_move, l);
    }
    info->mean_move = info->moved ? sum / info->moved : 0.0;
    int nf = 0;
    GLPGP_CHECK(glpgp_surface_features(d, feature_deg, w->flag, &nf));
    info->noise_edges_after = glpgp_surface_edges_above(d, feature_deg) - nf;
    for (int t = 0; t < d->nt; t++) info->folds_after += dn_is_fold(d, t);
    info->defect_rms = glpgp_surface_defect_rms(m);
    info->defect_rms_after = glpgp_surface_defect_rms(d);
    return GLPGP_OK;
}

/* A fold's normal (against its neighbours': the range weight would keep
 * it as a crease) replaced by its neighbours' area-weighted mean; its
 * region vertices marked 2 in mark (nv; others 0). Returns the folds. */
static int dn_unfold_normals(const glpgp_mesh *m, dn_ws *w, unsigned char *mark)
{
    int folds = 0;
    memset(mark, 0, (size_t)m->nv);
    const int *twin = m->surf->twin;
    for (int t = 0; t < m->nt; t++) {
        if (!w->tact[t]) continue;
        if (!fold_rule(m, w->n, 3, t)) continue;
        double s[3] = {0.0, 0.0, 0.0};
        for (int a = 0; a < 3; a++) {
            if (twin[3 * t + a] < 0) continue;
            const int o = twin[3 * t + a] / 3;
            for (int e = 0; e < 3; e++) s[e] += w->a[o] * w->n[3 * (size_t)o + e];
        }
        const double l = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        if (!(l > 0.0)) continue;
        for (int e = 0; e < 3; e++) w->n[3 * (size_t)t + e] = s[e] / l;
        for (int a = 0; a < 3; a++) mark[m->tri[3 * t + a]] = w->region[m->tri[3 * t + a]] ? 2 : 0;
        folds++;
    }
    return folds;
}

/* A fold is a tangential fault (a vertex pushed across an opposite edge),
 * which the fit along normals cannot undo: the marked vertices and their
 * neighbours in the region take DENOISE_UNFOLD_ITERS uniform Laplacian
 * steps (each to the mean of its triangles' other corners). */
static void dn_unfold_vertices(const glpgp_mesh *m, dn_ws *w, unsigned char *mark, double *x)
{
    for (int v = 0; v < m->nv; v++) /* grow the mark by one ring */
        if (mark[v] == 2)
            for (int k = w->vstart[v]; k < w->vstart[v + 1]; k++)
                for (int a = 0; a < 3; a++) {
                    const int u = m->tri[3 * w->vface[k] + a];
                    if (!mark[u] && w->region[u]) mark[u] = 1;
                }
    for (int it = 0; it < DENOISE_UNFOLD_ITERS; it++) {
        for (int v = 0; v < m->nv; v++) {
            double *d = w->d + 3 * (size_t)v, s[3] = {0.0, 0.0, 0.0};
            d[0] = d[1] = d[2] = 0.0;
            if (!mark[v]) continue;
            int n = 0;
            for (int k = w->vstart[v]; k < w->vstart[v + 1]; k++)
                for (int a = 0; a < 3; a++) {
                    const int u = m->tri[3 * w->vface[k] + a];
                    if (u == v) continue;
                    for (int e = 0; e < 3; e++) s[e] += x[3 * (size_t)u + e];
                    n++;
                }
            for (int e = 0; e < 3; e++) d[e] = n ? s[e] / n - x[3 * (size_t)v + e] : 0.0;
        }
        for (size_t i = 0; i < (size_t)3 * m->nv; i++) x[i] += w->d[i];
    }
}

/* DENOISE_ROUNDS rounds of normals filtered and vertices fitted, from m's
 * positions into x, held within max_move of them after every pass;
 * *capped: the vertices held after the last */
static void dn_smooth(const glpgp_mesh *m, dn_ws *w, double max_move, double *x, int *capped)
{
    int tick = 0;
    memcpy(x, m->xyz, (size_t)3 * m->nv * sizeof(double));
    for (int r = 0; r < DENOISE_ROUNDS; r++) {
        dn_geometry(m, x, w, 1);
        if (dn_unfold_normals(m, w, w->mark)) {
            dn_unfold_vertices(m, w, w->mark, x);
            dn_geometry(m, x, w, 1);
            (void)dn_unfold_normals(m, w, w->mark);
        }
        for (int k = 0; k < DENOISE_NORMAL_ITERS; k++) dn_filter_normals(m, w, m->mean_edge, &tick);
        for (int k = 0; k < DENOISE_VERTEX_ITERS; k++) {
            dn_fit_vertices(m, w, x);
            *capped = dn_cap(m->nv, m->xyz, max_move, x); /* held within every pass: its neighbours adapt */
        }
    }
}

glpgp_status glpgp_surface_denoise(const glpgp_mesh *m, double feature_deg, double max_move, glpgp_mesh **out,
                                   glpgp_surface_denoise_info *info)
{
    *out = NULL;
    memset(info, 0, sizeof *info);
    if (!m->surf) return GLPGP_FAIL(GLPGP_ERR_ARG, "denoise: not a surface");
    if (!(max_move > 0.0) || !(feature_deg >= 0.0 && feature_deg <= 180.0))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "denoise: max_move %g must be > 0, the feature angle in [0, 180]", max_move);
    dn_ws w;
    memset(&w, 0, sizeof w);
    double *x = NULL;
    glpgp_mesh *d = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, dn_alloc(m, &w), done);
    GLPGP_CHECK_GOTO(st, dn_region(m, feature_deg, &w, &info->noise_edges, &info->folds), done);
    if (!info->noise_edges && !info->folds) goto done;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * m->nv, sizeof(double), &x), done);
    dn_smooth(m, &w, max_move, x, &info->capped);
    st = glpgp_mesh_create_surface(m->nv, x, m->nt, m->tri, &d);
    if (st == GLPGP_ERR_NOMEM) goto done;
    if (st != GLPGP_OK) { /* a triangle made degenerate: the input kept as it is */
        glpgp_error_clear();
        st = GLPGP_OK;
        info->capped = 0;
        goto done;
    }
    info->rounds = DENOISE_ROUNDS;
    GLPGP_CHECK_GOTO(st, dn_report(m, d, feature_deg, &w, info), done);
    *out = d;
    d = NULL;
done:
    glpgp_mesh_destroy(&d);
    dn_free(&w);
    free(x);
    return st;
}
