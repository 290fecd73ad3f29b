/* quads/chords.c: boundary chords that cut off too much of a curved domain,
 * fixed by new grid lines instead of a re-mesh (glpgp_quadmesh_chord_strips,
 * repair.h).
 *
 * A boundary edge of the quad mesh is a straight chord of the domain
 * boundary between its two vertices; on a coarse mesh of a curved domain
 * the chords lose more than the 1% of the area the validity check allows
 * (the 3000-vertex disk with --field cross: a clean 45-quad grid, 2.2% off;
 * the repair used to re-mesh every boundary face into fans). Here a boundary
 * edge with a large loss (the area between it and the domain boundary) is
 * split at the domain boundary point half-way along: the quad behind it is
 * cut in two through the midpoint of the opposite edge, and so on straight
 * across the mesh (each quad entered through one edge is left through the
 * opposite one) until another boundary edge is reached, which is split the
 * same way. Through a structured part this is one more grid line: every new
 * vertex is regular. Strips are taken one at a time, the largest loss
 * first (ties: the larger loss at the strip's far end), while the area is
 * off by more than CHORD_TARGET; a strip that meets itself, is longer than
 * the mesh, or whose quads would get a corner below CHORD_MIN_SJ is not
 * taken. */
#include "glpgp/internal/edgekey.h"
#include "repair.h"
#include "geom.h"
#include "glpgp/quads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CHORD_TARGET 0.008 /* relative area difference aimed at (the check allows 0.01) */
#define CHORD_MIN_SJ 0.2
#define CHORD_MAX_STRIPS 256

struct chord_hedge {
    unsigned long long k;
    int f, i; /* face, side i (corners i, i+1) */
};
static int cmp_hedge(const void *x, const void *y)
{
    const struct chord_hedge *a = x, *b = y;
    return a->k < b->k ? -1 : a->k > b->k ? 1 : a->f - b->f;
}
glpgp_status glpgp_qsides_build(const glpgp_quadmesh *q, qsides *S)
{
    S->n = 4 * q->nf;
    S->h = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)S->n + 1, sizeof *S->h, &S->h));
    for (int f = 0; f < q->nf; f++)
        for (int i = 0; i < 4; i++)
            S->h[4 * f + i] =
                (struct chord_hedge){glpgp_edge_key(q->face_vert[4 * f + i], q->face_vert[4 * f + (i + 1) % 4]), f, i};
    qsort(S->h, (size_t)S->n, sizeof *S->h, cmp_hedge);
    return GLPGP_OK;
}

void glpgp_qsides_free(qsides *S)
{
    free(S->h);
    S->h = NULL;
    S->n = 0;
}

int glpgp_qsides_across(const qsides *S, const glpgp_quadmesh *q, int f, int i, int *j)
{
    const int *v = q->face_vert + 4 * f;
    unsigned long long k = glpgp_edge_key(v[i], v[(i + 1) % 4]);
    int lo = 0, hi = S->n;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (S->h[mid].k < k) lo = mid + 1;
        else hi = mid;
    }
    for (int t = lo; t < S->n && S->h[t].k == k; t++)
        if (S->h[t].f != f) {
            *j = S->h[t].i;
            return S->h[t].f;
        }
    return -1;
}

/* The domain boundary between the ends of boundary edge a -> b: its loss
 * (area between the chord and the boundary polyline) and the boundary
 * point half-way along (*mid). 0 when a or b is not on the boundary or
 * they are on different loops. */
int glpgp_dbnd_chord(dbnd *D, const double *a, const double *b, double h, double *loss, double *mid, int **cand,
                      int *ncap)
{
    const glpgp_mesh *m = D->m;
    double ta, tb, d, pa[2], pb[2];
    int sa = glpgp_dbnd_nearest(D, a, 1e-7 * h, &ta, &d, pa, cand, ncap);
    int sb = glpgp_dbnd_nearest(D, b, 1e-7 * h, &tb, &d, pb, cand, ncap);
    if (sa < 0 || sb < 0 || D->loop_of[sa] != D->loop_of[sb]) return 0;
    int l = D->loop_of[sa], s = m->loop_start[l], n = m->loop_start[l + 1] - s;
    /* walk from a to b along the loop (the way the mesh boundary runs, a -> b) */
    int steps = (sb - sa + n) % n;
    if (steps > n / 2) return 0; /* the chord spans more than half a loop: not a chord */
    double area = 0.0, len = 0.0, prev[2] = {a[0], a[1]};
    for (int k = 1; k <= steps; k++) {
        const double *p = m->xy + 2 * m->loop_vertices[s + (sa - s + k) % n];
        area += 0.5 * ((prev[0] - a[0]) * (p[1] - a[1]) - (p[0] - a[0]) * (prev[1] - a[1]));
        len += hypot(p[0] - prev[0], p[1] - prev[1]);
        prev[0] = p[0];
        prev[1] = p[1];
    }
    len += hypot(b[0] - prev[0], b[1] - prev[1]);
    area += 0.5 * ((prev[0] - a[0]) * (b[1] - a[1]) - (b[0] - a[0]) * (prev[1] - a[1]));
    *loss = area; /* the polyline bulging out of the chord (a convex side): area lost */
    /* the point half-way along */
    double half = 0.5 * len, acc = 0.0;
    prev[0] = a[0];
    prev[1] = a[1];
    mid[0] = 0.5 * (a[0] + b[0]);
    mid[1] = 0.5 * (a[1] + b[1]);
    for (int k = 1; k <= steps + 1; k++) {
        const double *p = k <= steps ? m->xy + 2 * m->loop_vertices[s + (sa - s + k) % n] : b;
        double e = hypot(p[0] - prev[0], p[1] - prev[1]);
        if (acc + e >= half && e > 0) {
            double t = (half - acc) / e;
            mid[0] = prev[0] + t * (p[0] - prev[0]);
            mid[1] = prev[1] + t * (p[1] - prev[1]);
            break;
        }
        acc += e;
        prev[0] = p[0];
        prev[1] = p[1];
    }
    return 1;
}

/* A strip from boundary side (f0, i0): faces and entry sides into *path
 * (2 ints per face), the far boundary side in *fe, *ie. 0 when it meets
 * itself or a non-quad. */
int glpgp_quadmesh_strip_trace(const qsides *S, const glpgp_quadmesh *q, int f0, int i0, int *path, int *len, int *fe, int *ie,
                 unsigned char *seen)
{
    int f = f0, i = i0, n = 0, ok = 0;
    while (n < q->nf) {
        if (seen[f]) break;
        seen[f] = 1;
        path[2 * n] = f;
        path[2 * n + 1] = i;
        n++;
        int o = (i + 2) % 4, j = -1, g = glpgp_qsides_across(S, q, f, o, &j);
        if (g < 0) {
            *fe = f;
            *ie = o;
            ok = 1;
            break;
        }
        if (q->face_start[g + 1] - q->face_start[g] != 4) break;
        f = g;
        i = j;
    }
    for (int t = 0; t < n; t++) seen[path[2 * t]] = 0;
    *len = n;
    return ok;
}

/* Apply the strip: q rebuilt with its faces cut in two; the end midpoints
 * at ma and mb (on the domain boundary). *ok 0 when a new quad would be
 * below CHORD_MIN_SJ (q unchanged). */
static glpgp_status cut_strip(glpgp_quadmesh *q, const int *path, int len, const double *ma, const double *mb, int *ok)
{
    *ok = 0;
    const int nv = q->nv, nnew = len + 1, nf = q->nf + len;
    double *xy = NULL;
    int *fv = NULL, *fs = NULL;
    unsigned char *fo = NULL, *cut = NULL;
    glpgp_status st = glpgp_malloc((size_t)(nv + nnew) + 1, 2 * sizeof(double), &xy);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)4 * nf + 1, sizeof(int), &fv);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nf + 1, sizeof(int), &fs);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nf + 1, 1, &fo);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)q->nf + 1, 1, &cut);
    if (st != GLPGP_OK) goto done;
    memcpy(xy, q->xy, sizeof(double) * 2 * (size_t)nv);
    /* midpoint t (0 .. len): the entry side of path face t, the last one the exit side of the last face */
    for (int t = 0; t <= len; t++) {
        int f = path[2 * (t < len ? t : len - 1)], i = t < len ? path[2 * t + 1] : (path[2 * (len - 1) + 1] + 2) % 4;
        const int *v = q->face_vert + 4 * f;
        const double *a = q->xy + 2 * v[i], *b = q->xy + 2 * v[(i + 1) % 4];
        const double *m = t == 0 ? ma : t == len ? mb : NULL;
        xy[2 * (nv + t)] = m ? m[0] : 0.5 * (a[0] + b[0]);
        xy[2 * (nv + t) + 1] = m ? m[1] : 0.5 * (a[1] + b[1]);
    }
    for (int t = 0; t < len; t++) cut[path[2 * t]] = 1;
    int w = 0;
    double worst = INFINITY;
    for (int f = 0; f < q->nf; f++) {
        const int *v = q->face_vert + 4 * f;
        unsigned char o = q->face_origin ? q->face_origin[f] : GLPGP_QFACE_GRID;
        if (!cut[f]) {
            memcpy(fv + 4 * w, v, 4 * sizeof(int));
            fo[w++] = o;
        }
    }
    for (int t = 0; t < len; t++) {
        int f = path[2 * t], i = path[2 * t + 1];
        const int *v = q->face_vert + 4 * f;
        unsigned char o = q->face_origin ? q->face_origin[f] : GLPGP_QFACE_GRID;
        int mi = nv + t, mo = nv + t + 1;
        int A[4] = {v[i], mi, mo, v[(i + 3) % 4]}, B[4] = {mi, v[(i + 1) % 4], v[(i + 2) % 4], mo};
        worst = fmin(worst, fmin(glpgp_poly_min_sj(xy, A, 4), glpgp_poly_min_sj(xy, B, 4)));
        memcpy(fv + 4 * w, A, sizeof A);
        fo[w++] = o > GLPGP_QFACE_CLOSED ? o : GLPGP_QFACE_CLOSED;
        memcpy(fv + 4 * w, B, sizeof B);
        fo[w++] = o > GLPGP_QFACE_CLOSED ? o : GLPGP_QFACE_CLOSED;
    }
    if (!(worst >= CHORD_MIN_SJ)) goto done;
    glpgp_qm_adopt_quads(q, &xy, nv + nnew, &fv, &fs, &fo, nf);
    *ok = 1;
done:
    free(xy);
    free(fv);
    free(fs);
    free(fo);
    free(cut);
    return st;
}

static double mesh_area(const glpgp_quadmesh *q)
{
    double a = 0.0;
    for (int f = 0; f < q->nf; f++) {
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        for (int i = 0; i < k; i++) {
            const double *p = q->xy + 2 * q->face_vert[s + i], *r = q->xy + 2 * q->face_vert[s + (i + 1) % k];
            a += 0.5 * (p[0] * r[1] - r[0] * p[1]);
        }
    }
    return a;
}

/* The boundary sides with their losses, largest first; the best strip's
 * path (the first whose cut is accepted) applied. *done 0: none. */
static glpgp_status one_strip(glpgp_quadmesh *q, dbnd *D, double h, int *done)
{
    *done = 0;
    qsides S = {NULL, 0};
    int *path = NULL, *order = NULL, *cand = NULL, ncap = 0, nb = 0;
    double *loss = NULL, *mids = NULL;
    unsigned char *seen = NULL;
    glpgp_status st = glpgp_qsides_build(q, &S);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)2 * q->nf + 2, sizeof(int), &path);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)S.n + 1, sizeof(int), &order);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)S.n + 1, sizeof(double), &loss);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)2 * S.n + 2, sizeof(double), &mids);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)q->nf + 1, 1, &seen);
    if (st != GLPGP_OK) goto done;
    for (int f = 0; f < q->nf; f++)
        for (int i = 0; i < 4; i++) {
            int j, s = 4 * f + i;
            loss[s] = 0.0;
            if (glpgp_qsides_across(&S, q, f, i, &j) >= 0) continue;
            const double *a = q->xy + 2 * q->face_vert[4 * f + i], *b = q->xy + 2 * q->face_vert[4 * f + (i + 1) % 4];
            int okc = glpgp_dbnd_chord(D, a, b, h, &loss[s], mids + 2 * s, &cand, &ncap);
            if (!okc || !(loss[s] > 0)) continue;
            order[nb++] = s;
        }
    /* the strip that gains most per quad cut: (loss at both ends) / length */
    int bs = -1, bse = -1, blen = 0;
    double bgain = 0.0;
    for (int k = 0; k < nb; k++) {
        int s = order[k], len = 0, fe = -1, ie = -1;
        if (!glpgp_quadmesh_strip_trace(&S, q, s / 4, s % 4, path, &len, &fe, &ie, seen) || len < 1) continue;
        int se = 4 * fe + ie;
        if (!(loss[se] > 0)) continue; /* ends on an edge with nothing to gain (a hole: more area) */
        double gain = (loss[s] + loss[se]) / len;
        if (gain > bgain) {
            bgain = gain;
            bs = s;
            bse = se;
            blen = len;
        }
    }
    if (bs >= 0) {
        int len = 0, fe = -1, ie = -1;
        glpgp_quadmesh_strip_trace(&S, q, bs / 4, bs % 4, path, &len, &fe, &ie, seen);
        GLPGP_CHECK_GOTO(st, cut_strip(q, path, len, mids + 2 * bs, mids + 2 * bse, done), done);
        glpgp_log(GLPGP_LOG_DEBUG, "quad chords: strip of %d quads, losses %.3g and %.3g: %s", blen, loss[bs], loss[bse],
                  *done ? "cut" : "not cut (poor quads)");
    }
done:
    glpgp_qsides_free(&S);
    free(path);
    free(order);
    free(loss);
    free(mids);
    free(seen);
    free(cand);
    return st;
}

glpgp_status glpgp_quadmesh_chord_strips(glpgp_quadmesh *q, const glpgp_mesh *m, double h, int *nstrips)
{
    *nstrips = 0;
    if (q->nf == 0 || !(m->area > 0)) return GLPGP_OK;
    for (int f = 0; f < q->nf; f++)
        if (q->face_start[f + 1] - q->face_start[f] != 4 || q->face_start[f] != 4 * f) return GLPGP_OK;
    dbnd D;
    GLPGP_CHECK(glpgp_dbnd_build(&D, m, h));
    glpgp_status st = GLPGP_OK;
    while (st == GLPGP_OK && *nstrips < CHORD_MAX_STRIPS && fabs(mesh_area(q) / m->area - 1.0) > CHORD_TARGET &&
           mesh_area(q) < m->area) {
        int done = 0;
        st = one_strip(q, &D, h, &done);
        if (!done) break;
        (*nstrips)++;
    }
    glpgp_dbnd_free(&D);
    return st;
}
