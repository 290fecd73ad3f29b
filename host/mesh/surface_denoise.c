/* mesh/surface_denoise.c: a scan's noise taken out of the geometry the
 * solve reads (glpgp_surface_denoise, glpgp/surface.h).
 *
 * A vertex jitter of a third of an edge or more turns the normals at random
 * from triangle to triangle: the angle defects (the discrete Gauss
 * curvature the cross field's connection integrates) swing by tenths of a
 * radian per vertex and the field puts singularities on them, the
 * curvature cap of the local size reads the noise as curvature and refines
 * everything, and the principal directions are noise. Where the input
 * shows such noise (an interior edge above the feature angle that is not a
 * crease, glpgp_surface_features' three tests), its vertices and those two
 * edge rings around them are smoothed by Taubin's lambda|mu filter
 * (uniform weights: a folded triangle's cotangents would be negative),
 * which takes out the wavelengths of a few edges and leaves the shape
 * (a bump over tens of edges moves by well under a percent); a crease's
 * vertex moves along its crease only (its two crease neighbours), a crease
 * end or corner, a crease turning by more than the feature angle and a
 * boundary vertex stay; no vertex moves by more than max_move. Creases are
 * found on the smoothed surface again and the smoothing repeated once with
 * them: a cluster of noise that passed the crease tests on the rough input
 * is smooth then and no longer holds. A triangle turned over against its
 * neighbours (a sliver folded by a jitter in every direction: its three
 * edges at 100-180 degrees pass every crease test) is noise too: its edges
 * are no creases and its vertices are smoothed. A clean mesh (no such edge,
 * no fold) is not touched. */
#include "glpgp/kinds.h"
#include "glpgp/surface.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DENOISE_RINGS 2     /* the smoothed region: edge rings around the noise edges */
#define DENOISE_SWEEPS 10   /* Taubin lambda|mu pairs per round */
#define DENOISE_LAMBDA 0.5  /* (1 - lambda k)(1 - mu k): k = 2 (the jitter of single vertices) gone, */
#define DENOISE_MU (-0.53)  /* k = 1 down to 0.07 after 10 pairs, pass band k < 0.11 */
#define DENOISE_ROUNDS 4

enum { DN_FIXED = 0, DN_FREE = 1, DN_CREASE = 2 };

typedef struct dn_ws {
    int *start, *adj;      /* nv + 1, 2 nedges: every vertex's edge neighbours */
    int *cn;               /* 2 nv: a crease vertex's two crease neighbours */
    unsigned char *kind;   /* nv: DN_* */
    unsigned char *region; /* nv */
    unsigned char *flag;   /* 3 nt: features */
    double *d;             /* 3 nv: the sweep's displacement */
} dn_ws;

static void dn_free(dn_ws *w)
{
    free(w->start);
    free(w->adj);
    free(w->cn);
    free(w->kind);
    free(w->region);
    free(w->flag);
    free(w->d);
}

/* the vertex adjacency (each undirected edge once per end) */
static glpgp_status dn_adjacency(const glpgp_mesh *m, dn_ws *w)
{
    const int *twin = m->surf->twin;
    GLPGP_CHECK(glpgp_calloc((size_t)m->nv + 1, sizeof(int), &w->start));
    for (int h = 0; h < 3 * m->nt; h++)
        if (twin[h] < h) {
            w->start[m->tri[h] + 1]++;
            w->start[m->tri[h - h % 3 + (h % 3 + 1) % 3] + 1]++;
        }
    for (int v = 0; v < m->nv; v++) w->start[v + 1] += w->start[v];
    GLPGP_CHECK(glpgp_malloc((size_t)w->start[m->nv] + 1, sizeof(int), &w->adj));
    int *fill = w->cn; /* scratch: nv */
    for (int v = 0; v < m->nv; v++) fill[v] = w->start[v];
    for (int h = 0; h < 3 * m->nt; h++)
        if (twin[h] < h) {
            const int a = m->tri[h], b = m->tri[h - h % 3 + (h % 3 + 1) % 3];
            w->adj[fill[a]++] = b;
            w->adj[fill[b]++] = a;
        }
    return GLPGP_OK;
}

/* Whether triangle t is turned over: its normal against the sum of its
 * (two or three) neighbours'. A sliver folded by a jitter; its three edges
 * pass every crease test. */
static int dn_is_fold(const glpgp_mesh *m, int t)
{
    const glpgp_surface *g = m->surf;
    const double *nt = g->tframe + 9 * (size_t)t + 6;
    double s = 0.0;
    int k = 0;
    for (int a = 0; a < 3; a++) {
        const int o = g->twin[3 * t + a];
        if (o < 0) continue;
        const double *no = g->tframe + 9 * (size_t)(o / 3) + 6;
        s += nt[0] * no[0] + nt[1] * no[1] + nt[2] * no[2];
        k++;
    }
    return k >= 2 && s < 0.0;
}

/* The folds' edges lose their feature flags and their vertices seed the
 * region; returns how many folds. */
static int dn_folds(const glpgp_mesh *m, dn_ws *w)
{
    const glpgp_surface *g = m->surf;
    int n = 0;
    for (int t = 0; t < m->nt; t++) {
        if (!dn_is_fold(m, t)) continue;
        n++;
        for (int a = 0; a < 3; a++) {
            const int h = 3 * t + a;
            w->flag[h] = 0;
            if (g->twin[h] >= 0) w->flag[g->twin[h]] = 0;
            w->region[m->tri[h]] = 1;
        }
    }
    return n;
}

/* Features of m into w->flag (a fold's edges not: dn_folds); the noise
 * edges' ends and the folds' vertices marked in region and grown by
 * DENOISE_RINGS rings; *noise the noise edges, *folds the folds. */
static glpgp_status dn_region(const glpgp_mesh *m, double feature_deg, dn_ws *w, int *noise, int *folds)
{
    const glpgp_surface *g = m->surf;
    const double lim = feature_deg * GLPGP_PI / 180.0;
    GLPGP_CHECK(glpgp_surface_features(m, feature_deg, w->flag, NULL));
    int n = 0;
    memset(w->region, 0, (size_t)m->nv);
    *folds = dn_folds(m, w);
    for (int h = 0; h < 3 * m->nt; h++)
        if (g->twin[h] > h && g->dihedral[h] > lim && !w->flag[h]) {
            w->region[m->tri[h]] = w->region[m->tri[h - h % 3 + (h % 3 + 1) % 3]] = 1;
            n++;
        }
    for (int r = 1; r <= DENOISE_RINGS; r++)
        for (int v = 0; v < m->nv; v++)
            if (w->region[v] == r)
                for (int k = w->start[v]; k < w->start[v + 1]; k++)
                    if (!w->region[w->adj[k]]) w->region[w->adj[k]] = (unsigned char)(r + 1);
    *noise = n;
    return GLPGP_OK;
}

/* Each vertex's kind from the features (w->flag) and the region. */
static void dn_kinds(const glpgp_mesh *m, const double *xyz, double feature_deg, dn_ws *w)
{
    const int *twin = m->surf->twin;
    const double cmin = cos(feature_deg * GLPGP_PI / 180.0);
    for (int v = 0; v < m->nv; v++) {
        w->cn[2 * v] = w->cn[2 * v + 1] = -1;
        w->kind[v] = w->region[v] && !m->on_boundary[v] ? DN_FREE : DN_FIXED;
    }
    for (int h = 0; h < 3 * m->nt; h++) {
        if (!w->flag[h] || twin[h] < h) continue;
        const int e[2] = {m->tri[h], m->tri[h - h % 3 + (h % 3 + 1) % 3]};
        for (int s = 0; s < 2; s++) {
            const int v = e[s], o = e[1 - s];
            if (w->kind[v] == DN_FREE) {
                w->kind[v] = DN_CREASE;
                w->cn[2 * v] = o;
            } else if (w->kind[v] == DN_CREASE && w->cn[2 * v + 1] < 0) {
                w->cn[2 * v + 1] = o;
            } else {
                w->kind[v] = DN_FIXED; /* a third crease edge: a corner */
            }
        }
    }
    for (int v = 0; v < m->nv; v++) {
        if (w->kind[v] != DN_CREASE) continue;
        const int a = w->cn[2 * v], b = w->cn[2 * v + 1];
        if (b < 0) { /* a crease's end */
            w->kind[v] = DN_FIXED;
            continue;
        }
        const double *x = xyz + 3 * (size_t)v, *p = xyz + 3 * (size_t)a, *q = xyz + 3 * (size_t)b;
        const double u[3] = {x[0] - p[0], x[1] - p[1], x[2] - p[2]}, t[3] = {q[0] - x[0], q[1] - x[1], q[2] - x[2]};
        const double uu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]), tt = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
        if (!((u[0] * t[0] + u[1] * t[1] + u[2] * t[2]) > cmin * uu * tt)) w->kind[v] = DN_FIXED; /* it turns */
    }
}

/* One Jacobi sweep x <- x + f (mean of the neighbours - x) over the moving
 * vertices (a crease vertex's neighbours: its two along the crease). */
static void dn_sweep(const glpgp_mesh *m, dn_ws *w, double f, double *xyz)
{
    for (int v = 0; v < m->nv; v++) {
        double *d = w->d + 3 * (size_t)v;
        d[0] = d[1] = d[2] = 0.0;
        if (w->kind[v] == DN_FIXED) continue;
        double s[3] = {0.0, 0.0, 0.0};
        int n = 0;
        if (w->kind[v] == DN_CREASE) {
            for (int k = 0; k < 2; k++, n++)
                for (int c = 0; c < 3; c++) s[c] += xyz[3 * (size_t)w->cn[2 * v + k] + c];
        } else {
            for (int k = w->start[v]; k < w->start[v + 1]; k++, n++)
                for (int c = 0; c < 3; c++) s[c] += xyz[3 * (size_t)w->adj[k] + c];
        }
        if (n)
            for (int c = 0; c < 3; c++) d[c] = f * (s[c] / n - xyz[3 * (size_t)v + c]);
    }
    for (size_t i = 0; i < (size_t)3 * m->nv; i++) xyz[i] += w->d[i];
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

/* one round: the kinds from cur's features, DENOISE_SWEEPS lambda|mu pairs
 * on xyz (cur's positions on entry), capped against the input's x0 */
static glpgp_status dn_round(const glpgp_mesh *cur, const double *x0, double feature_deg, double max_move, dn_ws *w,
                             double *xyz, int *noise, int *folds, int *capped)
{
    GLPGP_CHECK(dn_region(cur, feature_deg, w, noise, folds));
    if (!*noise && !*folds) return GLPGP_OK;
    dn_kinds(cur, cur->xyz, feature_deg, w);
    for (int s = 0; s < DENOISE_SWEEPS; s++) {
        dn_sweep(cur, w, DENOISE_LAMBDA, xyz);
        dn_sweep(cur, w, DENOISE_MU, xyz);
    }
    *capped = dn_cap(cur->nv, x0, max_move, xyz);
    return GLPGP_OK;
}

static void dn_moves(const glpgp_mesh *m, const double *xyz, glpgp_surface_denoise_info *info)
{
    double sum = 0.0;
    for (int v = 0; v < m->nv; v++) {
        double l = 0.0;
        for (int c = 0; c < 3; c++) {
            const double d = xyz[3 * (size_t)v + c] - m->xyz[3 * (size_t)v + c];
            l += d * d;
        }
        if (!(l > 0.0)) continue;
        l = sqrt(l);
        info->moved++;
        sum += l;
        info->max_move = fmax(info->max_move, l);
    }
    info->mean_move = info->moved ? sum / info->moved : 0.0;
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
    double *xyz = NULL;
    glpgp_mesh *cur = NULL;
    glpgp_status st = GLPGP_OK;
    const size_t n3 = (size_t)3 * m->nv;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * m->nv, sizeof(int), &w.cn), done);
    GLPGP_CHECK_GOTO(st, dn_adjacency(m, &w), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)m->nv, 1, &w.kind), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)m->nv, 1, &w.region), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * m->nt, 1, &w.flag), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n3, sizeof(double), &w.d), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n3, sizeof(double), &xyz), done);
    memcpy(xyz, m->xyz, n3 * sizeof(double));
    for (int r = 0; r < DENOISE_ROUNDS; r++) {
        const glpgp_mesh *src = cur ? cur : m;
        int noise = 0, folds = 0, capped = 0;
        GLPGP_CHECK_GOTO(st, dn_round(src, m->xyz, feature_deg, max_move, &w, xyz, &noise, &folds, &capped), done);
        if (r == 0) {
            info->noise_edges = noise;
            info->folds = folds;
        }
        if (!noise && !folds) break;
        info->capped = capped; /* the last round's cap holds every vertex cut */
        info->rounds++;
        glpgp_mesh *next = NULL;
        st = glpgp_mesh_create_surface(m->nv, xyz, m->nt, m->tri, &next);
        if (st != GLPGP_OK) { /* smoothing made a triangle degenerate: keep the last good one */
            glpgp_error_clear();
            st = GLPGP_OK;
            info->rounds--;
            if (cur) memcpy(xyz, cur->xyz, n3 * sizeof(double));
            break;
        }
        glpgp_mesh_destroy(&cur);
        cur = next;
    }
    if (cur) {
        info->noise_edges_after = glpgp_surface_edges_above(cur, feature_deg);
        int nf = 0;
        GLPGP_CHECK_GOTO(st, glpgp_surface_features(cur, feature_deg, w.flag, &nf), done);
        info->noise_edges_after -= nf;
        for (int t = 0; t < cur->nt; t++) info->folds_after += dn_is_fold(cur, t);
        dn_moves(m, cur->xyz, info);
        info->defect_rms = glpgp_surface_defect_rms(m);
        info->defect_rms_after = glpgp_surface_defect_rms(cur);
        *out = cur;
        cur = NULL;
    }
done:
    glpgp_mesh_destroy(&cur);
    dn_free(&w);
    free(xyz);
    return st;
}
