/* quads/shape.c: the last shape pass of the planar quad pipeline
 * (glpgp_quadmesh_shape_pass, repair.h), run after the clean-up on a valid
 * mesh; what it changes the pipeline keeps only when the mesh stays as
 * valid and its worst quad is better.
 *
 * 0. Sharp tips (tips.c): the region of a boundary corner below 60 degrees
 *    re-meshed as its triangle's incircle kites, with one strip (part 1's).
 * 1. Flat boundary corners. A boundary vertex c with one face Q = (a, b, c,
 *    d) whose corner there is flat (the boundary runs nearly straight
 *    through c, SJ below the goal) makes Q a triangle a-b-d with c on its
 *    base: no vertex move helps. Q is split like a triangle, into three
 *    quads about a new center g and the midpoints of a-b and a-d; each
 *    midpoint is carried across the mesh by a strip (every quad entered
 *    through one side is cut through the midpoint of the opposite side)
 *    until the strip reaches the boundary, where its end is placed on the
 *    domain boundary half-way between the edge's ends (chords.c's rule).
 *    Through a structured part each strip is one more grid line; c gets two
 *    faces, g is a valence-3 vertex: the irregular count does not grow.
 *    Where the strips cross (each other or themselves, at right angles) the
 *    quad is cut in four; where the first strip comes back into Q it is the
 *    only one. Taken when the strips reach the boundary (not along
 *    themselves, not through Q) and the mesh, smoothed (part 2), has fewer
 *    quads below the goal or a better worst one, and that no worse.
 * 2. Optimisation smoothing: the interior vertices of quads below
 *    SHAPE_BELOW and their edge neighbours are moved by a compass search
 *    that maximises the smallest corner scaled Jacobian among the corners
 *    the vertex moves (its own and its two neighbours' in each face): a
 *    move is taken only when that minimum rises, so the mesh's worst corner
 *    never falls and no face inverts. A boundary vertex moves only when it
 *    lies on a straight piece between its two boundary neighbours, and then
 *    along that piece: the domain's boundary stays where it is. */
#include "shape_impl.h"
#include "geom.h"
#include "soup.h"
#include "check.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SHAPE_SWEEPS 12

/* ---- corner measure ----------------------------------------------------------- */

/* Scaled Jacobian of corner i of polygon v[0..n-1] (counter-clockwise). */
double glpgp_shape_corner_sj(const double *xy, const int *v, int n, int i)
{
    const double *a = xy + 2 * v[i], *b = xy + 2 * v[(i + 1) % n], *c = xy + 2 * v[(i + n - 1) % n];
    double e1x = b[0] - a[0], e1y = b[1] - a[1], e2x = c[0] - a[0], e2y = c[1] - a[1];
    double l = hypot(e1x, e1y) * hypot(e2x, e2y);
    return l > 0 ? (e1x * e2y - e1y * e2x) / l : -1.0;
}


void glpgp_vstar_free(vstar *S)
{
    free(S->vs);
    free(S->vc);
    free(S->sf);
    memset(S, 0, sizeof *S);
}

glpgp_status glpgp_vstar_build(const glpgp_quadmesh *q, vstar *S)
{
    int nv = q->nv, nc = q->face_start[q->nf];
    int *cnt = NULL;
    memset(S, 0, sizeof *S);
    glpgp_status st = glpgp_calloc((size_t)nv + 2, sizeof(int), &S->vs);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nc + 1, sizeof(int), &S->vc);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nc + 1, sizeof(int), &S->sf);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)nv + 1, sizeof(int), &cnt);
    if (st != GLPGP_OK) {
        glpgp_vstar_free(S);
        free(cnt);
        return st;
    }
    for (int f = 0; f < q->nf; f++)
        for (int c = q->face_start[f]; c < q->face_start[f + 1]; c++) S->sf[c] = f;
    for (int c = 0; c < nc; c++) S->vs[q->face_vert[c] + 1]++;
    for (int v = 0; v < nv; v++) S->vs[v + 1] += S->vs[v];
    for (int c = 0; c < nc; c++) S->vc[S->vs[q->face_vert[c]] + cnt[q->face_vert[c]]++] = c;
    free(cnt);
    return GLPGP_OK;
}

/* The smallest scaled Jacobian among the corners vertex v moves (its own
 * corner and its two neighbours' in each of its faces); *below: how many
 * of them are below the goal. */
static double moved_corners(const glpgp_quadmesh *q, const vstar *S, int v, int *below)
{
    double m = INFINITY;
    *below = 0;
    for (int j = S->vs[v]; j < S->vs[v + 1]; j++) {
        int c = S->vc[j], f = S->sf[c], b = q->face_start[f], n = q->face_start[f + 1] - b, i = c - b;
        const int *fv = q->face_vert + b;
        for (int k = n - 1; k <= n + 1; k++) {
            double sj = glpgp_shape_corner_sj(q->xy, fv, n, (i + k) % n);
            m = fmin(m, sj);
            *below += sj < GLPGP_QUADS_SJ_GOAL;
        }
    }
    return m;
}

/* ---- optimisation smoothing --------------------------------------------------- */

/* A boundary vertex v between two boundary neighbours u, w on one straight
 * line (v not a corner): 1 and the segment's ends in *u, *w. */
static int straight_boundary(const glpgp_quadmesh *q, const vstar *S, int v, int *u, int *w)
{
    int nb = 0, ends[2] = {-1, -1};
    for (int j = S->vs[v]; j < S->vs[v + 1]; j++) {
        int c = S->vc[j], f = S->sf[c], b = q->face_start[f], n = q->face_start[f + 1] - b, i = c - b;
        int nx = q->face_vert[b + (i + 1) % n], pv = q->face_vert[b + (i + n - 1) % n];
        int nx_twin = 0, pv_twin = 0; /* does another face of v have nx as its previous (pv as its next)? */
        for (int k = S->vs[v]; k < S->vs[v + 1]; k++) {
            int c2 = S->vc[k], f2 = S->sf[c2], b2 = q->face_start[f2], n2 = q->face_start[f2 + 1] - b2, i2 = c2 - b2;
            if (k == j) continue;
            nx_twin |= q->face_vert[b2 + (i2 + n2 - 1) % n2] == nx;
            pv_twin |= q->face_vert[b2 + (i2 + 1) % n2] == pv;
        }
        if (!nx_twin && nb < 2) ends[nb++] = nx;
        if (!pv_twin && nb < 2) ends[nb++] = pv;
    }
    if (nb != 2 || ends[0] == ends[1]) return 0;
    const double *a = q->xy + 2 * ends[0], *p = q->xy + 2 * v, *b = q->xy + 2 * ends[1];
    double ux = p[0] - a[0], uy = p[1] - a[1], wx = b[0] - p[0], wy = b[1] - p[1];
    double lu = hypot(ux, uy), lw = hypot(wx, wy);
    if (!(lu > 0 && lw > 0) || fabs(ux * wy - uy * wx) > 1e-9 * lu * lw || ux * wx + uy * wy <= 0) return 0;
    *u = ends[0];
    *w = ends[1];
    return 1;
}

/* Compass search for vertex v (along the segment u-w when u >= 0, kept
 * inside its middle 90%); 1 when it moved. */
static int optimise_vertex(glpgp_quadmesh *q, const vstar *S, int v, int u, int w)
{
    double *p = q->xy + 2 * v, len = 0.0;
    int k = 0;
    for (int j = S->vs[v]; j < S->vs[v + 1]; j++) {
        int c = S->vc[j], f = S->sf[c], b = q->face_start[f], n = q->face_start[f + 1] - b;
        const double *r = q->xy + 2 * q->face_vert[b + (c - b + 1) % n];
        len += hypot(r[0] - p[0], r[1] - p[1]);
        k++;
    }
    if (k == 0 || !(len > 0)) return 0;
    len /= k;
    const double *A = u >= 0 ? q->xy + 2 * u : NULL, *B = u >= 0 ? q->xy + 2 * w : NULL;
    int nb = 0, nbw = 0, ndir = A ? 2 : 8;
    double best = moved_corners(q, S, v, &nb), step = 0.25 * len, x0 = p[0], y0 = p[1];
    int moved = 0;
    for (int it = 0; it < 60 && step > 1e-3 * len; it++) {
        double bx = p[0], by = p[1], cx = p[0], cy = p[1];
        int better = 0;
        for (int d = 0; d < ndir; d++) {
            if (A) { /* along the segment, at parameter t of A -> B */
                double L = hypot(B[0] - A[0], B[1] - A[1]);
                double t = (hypot(cx - A[0], cy - A[1]) + (d ? step : -step)) / L;
                if (t < 0.05 || t > 0.95) continue;
                p[0] = A[0] + t * (B[0] - A[0]);
                p[1] = A[1] + t * (B[1] - A[1]);
            } else {
                double an = d * (3.14159265358979323846 / 4.0);
                p[0] = cx + step * cos(an);
                p[1] = cy + step * sin(an);
            }
            double sw = moved_corners(q, S, v, &nbw);
            /* better: a higher worst corner with no more corners below the
             * goal, or fewer below it with the worst kept */
            if ((sw > best + 1e-9 && nbw <= nb) || (sw >= best && nbw < nb)) {
                best = sw;
                nb = nbw;
                bx = p[0];
                by = p[1];
                better = 1;
            }
        }
        p[0] = bx;
        p[1] = by;
        if (better) moved = 1;
        else step *= 0.5;
    }
    if (moved && hypot(p[0] - x0, p[1] - y0) < 1e-6 * len) moved = 0;
    return moved;
}

/* The smoothing of part 2; *moved: vertices that moved. */
static glpgp_status optimise(glpgp_quadmesh *q, int *moved)
{
    *moved = 0;
    psoup s;
    adjacency A;
    vstar S;
    unsigned char *act = NULL;
    memset(&A, 0, sizeof A);
    memset(&S, 0, sizeof S);
    glpgp_status st = glpgp_soup_from_mesh(q, &s);
    if (st == GLPGP_OK) st = glpgp_adj_build(&s, &A);
    if (st == GLPGP_OK) st = glpgp_vstar_build(q, &S);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)q->nv + 1, 1, &act);
    if (st != GLPGP_OK) goto done;
    for (int f = 0; f < q->nf; f++) {
        int b = q->face_start[f], n = q->face_start[f + 1] - b;
        if (!(glpgp_poly_min_sj(q->xy, q->face_vert + b, n) < SHAPE_BELOW)) continue;
        for (int i = 0; i < n; i++) { /* the face's vertices and their edge neighbours */
            int v = q->face_vert[b + i];
            act[v] |= 1;
            for (int j = S.vs[v]; j < S.vs[v + 1]; j++) {
                int c = S.vc[j], g = S.sf[c], gb = q->face_start[g], gn = q->face_start[g + 1] - gb;
                act[q->face_vert[gb + (c - gb + 1) % gn]] |= 1;
                act[q->face_vert[gb + (c - gb + gn - 1) % gn]] |= 1;
            }
        }
    }
    for (int sweep = 0; sweep < SHAPE_SWEEPS; sweep++) {
        int changed = 0;
        for (int v = 0; v < q->nv; v++) {
            int u = -1, w = -1;
            if (!act[v] || (A.bnd[v] && !straight_boundary(q, &S, v, &u, &w))) continue;
            if (!optimise_vertex(q, &S, v, u, w)) continue;
            changed++;
            if (!(act[v] & 2)) {
                act[v] |= 2;
                (*moved)++;
            }
        }
        if (!changed) break;
    }
done:
    glpgp_soup_free(&s);
    glpgp_adj_free(&A);
    glpgp_vstar_free(&S);
    free(act);
    return st;
}

/* ---- flat boundary corners ---------------------------------------------------- */


/* Strip k from face f0 entered through side i0: each quad left through the
 * side opposite its entry, recorded in F->pos; a quad already passed may be
 * crossed once more at right angles. 1: it reached the boundary (side ie of
 * face fe); 2: it came back into Q through side qside; 0: it met Q
 * otherwise, a quad a third time or along its first pass, or a non-quad. */
int glpgp_shape_trace(const qsides *S, const glpgp_quadmesh *q, flat_fix *F, int k, int f0, int i0, int qside, int *fe,
                      int *ie)
{
    int f = f0, i = i0, n = 0;
    F->len[k] = 0;
    while (n < 2 * q->nf) {
        if (f == F->Q) return i == qside && k == 0 ? 2 : 0;
        if (q->face_start[f + 1] - q->face_start[f] != 4) return 0;
        int code = 2 * n + k;
        if (F->pos[0][f] < 0) F->pos[0][f] = code;
        else if (F->pos[1][f] < 0) {
            int c0 = F->pos[0][f], i1 = F->path[c0 % 2][2 * (c0 / 2) + 1];
            if ((i - i1 + 4) % 2 == 0) return 0; /* along the first pass */
            F->pos[1][f] = code;
            F->ncross++;
        } else
            return 0;
        F->path[k][2 * n] = f;
        F->path[k][2 * n + 1] = i;
        F->len[k] = ++n;
        int o = (i + 2) % 4, j = -1, g = glpgp_qsides_across(S, q, f, o, &j);
        if (g < 0) {
            *fe = f;
            *ie = o;
            return 1;
        }
        f = g;
        i = j;
    }
    return 0;
}

/* The strips of candidate corner (Q, i); 0 when they do not both reach the
 * boundary (or come back as one) apart from Q. F->pos is restored when not. */
static int flat_strips(const glpgp_quadmesh *q, const qsides *S, dbnd *D, double h, flat_fix *F, int **cand, int *ncap)
{
    int side[2] = {(F->i + 2) % 4, (F->i + 1) % 4}, ok = 1;
    for (int k = 0; k < 2 && ok; k++) {
        int j = -1, fe = -1, ie = -1, P = glpgp_qsides_across(S, q, F->Q, side[k], &j);
        int r = P >= 0 ? glpgp_shape_trace(S, q, F, k, P, j, side[1], &fe, &ie) : 0;
        ok = r > 0 && F->len[k] > 0;
        if (r == 2) { /* back into Q through side (d, a): one strip */
            int n = F->len[0], fl = F->path[0][2 * n - 2], o = (F->path[0][2 * n - 1] + 2) % 4;
            const int *v = q->face_vert + 4 * fl;
            for (int e = 0; e < 2; e++) F->end[0][e] = 0.5 * (q->xy[2 * v[o] + e] + q->xy[2 * v[(o + 1) % 4] + e]);
            F->loop = 1;
            break;
        }
        if (!ok) break;
        const int *v = q->face_vert + 4 * fe;
        const double *a = q->xy + 2 * v[ie], *b = q->xy + 2 * v[(ie + 1) % 4];
        double loss = 0.0;
        if (!glpgp_dbnd_chord(D, a, b, h, &loss, F->end[k], cand, ncap)) {
            F->end[k][0] = 0.5 * (a[0] + b[0]);
            F->end[k][1] = 0.5 * (a[1] + b[1]);
        }
    }
    if (!ok) /* pos is kept for flat_apply only when the strips are taken */
        for (int k = 0; k < 2; k++)
            for (int t = 0; t < F->len[k]; t++) F->pos[0][F->path[k][2 * t]] = F->pos[1][F->path[k][2 * t]] = -1;
    return ok;
}

unsigned char glpgp_shape_split_origin(const glpgp_quadmesh *q, int f)
{
    unsigned char o = q->face_origin ? q->face_origin[f] : GLPGP_QFACE_GRID;
    return o > GLPGP_QFACE_CLOSED ? o : GLPGP_QFACE_CLOSED;
}

/* The worst corner of the three quads T. */
static double three_sj(const double *xy, int T[3][4])
{
    return fmin(glpgp_poly_min_sj(xy, T[0], 4), fmin(glpgp_poly_min_sj(xy, T[1], 4), glpgp_poly_min_sj(xy, T[2], 4)));
}

/* The center g of the three quads T placed by a compass search from the
 * triangle's centroid (xy[2 g] on entry) for their best worst corner. */
static void place_center(double *xy, int T[3][4], int g)
{
    double *p = xy + 2 * g, best = three_sj(xy, T), len = 0.0;
    for (int k = 0; k < 4; k++) {
        const double *r = xy + 2 * T[2][k];
        len += 0.25 * hypot(r[0] - p[0], r[1] - p[1]);
    }
    for (double step = 0.25 * len; step > 1e-3 * len;) {
        double cx = p[0], cy = p[1], bx = cx, by = cy;
        for (int d = 0; d < 8; d++) {
            double an = d * (3.14159265358979323846 / 4.0);
            p[0] = cx + step * cos(an);
            p[1] = cy + step * sin(an);
            double w = three_sj(xy, T);
            if (w > best + 1e-9) {
                best = w;
                bx = p[0];
                by = p[1];
            }
        }
        if (bx == cx && by == cy) step *= 0.5;
        p[0] = bx;
        p[1] = by;
    }
}

/* The points of the first nk strips of F into xy (step t of strip k at
 * s0[k] + t: the midpoint of the side it enters through, the last one its
 * end on the boundary); the faces they cut marked in cut. */
void glpgp_shape_strip_points(const glpgp_quadmesh *q, const flat_fix *F, int nk, const int *s0, double *xy,
                         unsigned char *cut)
{
    for (int k = 0; k < nk; k++)
        for (int t = 0; t <= F->len[k]; t++) {
            int last = t == F->len[k], f = F->path[k][2 * (last ? t - 1 : t)], i = F->path[k][2 * (last ? t - 1 : t) + 1];
            const int *v = q->face_vert + 4 * f;
            const double *a = q->xy + 2 * v[last ? (i + 2) % 4 : i], *b = q->xy + 2 * v[last ? (i + 3) % 4 : (i + 1) % 4];
            xy[2 * (s0[k] + t)] = last ? F->end[k][0] : 0.5 * (a[0] + b[0]);
            xy[2 * (s0[k] + t) + 1] = last ? F->end[k][1] : 0.5 * (a[1] + b[1]);
            cut[f] = 1;
        }
}

/* The faces the strips of F cut, in two (in four about the midpoints' mean
 * where two passes cross, centers from X on) into fv / fo from slot *w;
 * their smallest corner scaled Jacobian. */
double glpgp_shape_strip_halves(const glpgp_quadmesh *q, const flat_fix *F, const int *s0, int X, double *xy, int *fv,
                           unsigned char *fo, int *w)
{
    double halves = INFINITY;
    for (int k = 0; k < 2; k++)
        for (int t = 0; t < F->len[k]; t++) {
            int f = F->path[k][2 * t], i = F->path[k][2 * t + 1], mi = s0[k] + t, mo = mi + 1;
            const int *v = q->face_vert + 4 * f;
            if (F->pos[1][f] >= 0) { /* crossed twice: four quads about the midpoints' mean */
                if (F->pos[1][f] != 2 * t + k) continue; /* made at its second pass */
                int c0 = F->pos[0][f], k0 = c0 % 2, t0 = c0 / 2, i0 = F->path[k0][2 * t0 + 1], M[4];
                M[i] = mi;
                M[(i + 2) % 4] = mo;
                M[i0] = s0[k0] + t0;
                M[(i0 + 2) % 4] = s0[k0] + t0 + 1;
                for (int e = 0; e < 2; e++)
                    xy[2 * X + e] = 0.25 * (xy[2 * M[0] + e] + xy[2 * M[1] + e] + xy[2 * M[2] + e] + xy[2 * M[3] + e]);
                for (int r = 0; r < 4; r++) {
                    int C[4] = {v[r], M[r], X, M[(r + 3) % 4]};
                    memcpy(fv + 4 * *w, C, sizeof C);
                    fo[(*w)++] = glpgp_shape_split_origin(q, f);
                    halves = fmin(halves, glpgp_poly_min_sj(xy, C, 4));
                }
                X++;
                continue;
            }
            int A[4] = {v[i], mi, mo, v[(i + 3) % 4]}, B[4] = {mi, v[(i + 1) % 4], v[(i + 2) % 4], mo};
            memcpy(fv + 4 * *w, A, sizeof A);
            fo[(*w)++] = glpgp_shape_split_origin(q, f);
            memcpy(fv + 4 * *w, B, sizeof B);
            fo[(*w)++] = glpgp_shape_split_origin(q, f);
            halves = fmin(halves, fmin(glpgp_poly_min_sj(xy, A, 4), glpgp_poly_min_sj(xy, B, 4)));
        }
    return halves;
}

/* The mesh with F applied into the new arrays; the smallest corner scaled
 * Jacobian of the new quads. */
static double flat_apply(const glpgp_quadmesh *q, const flat_fix *F, double *xy, int *fv, unsigned char *fo,
                         unsigned char *cut)
{
    const int nv = q->nv, g = nv, s0[2] = {nv + 1, F->loop ? nv + 1 + F->len[0] : nv + 2 + F->len[0]};
    memcpy(xy, q->xy, sizeof(double) * 2 * (size_t)nv);
    glpgp_shape_strip_points(q, F, 2 - F->loop, s0, xy, cut);
    const int *Qv = q->face_vert + 4 * F->Q;
    int c = Qv[F->i], d = Qv[(F->i + 1) % 4], a = Qv[(F->i + 2) % 4], b = Qv[(F->i + 3) % 4];
    for (int e = 0; e < 2; e++)
        xy[2 * g + e] = (q->xy[2 * a + e] + q->xy[2 * b + e] + q->xy[2 * d + e]) / 3.0;
    int w = 0;
    for (int f = 0; f < q->nf; f++)
        if (!cut[f] && f != F->Q) {
            memcpy(fv + 4 * w, q->face_vert + 4 * f, 4 * sizeof(int));
            fo[w++] = q->face_origin ? q->face_origin[f] : GLPGP_QFACE_GRID;
        }
    double worst = INFINITY;
    int mab = s0[0], mad = s0[1];
    int T[3][4] = {{mab, b, c, g}, {g, c, d, mad}, {a, mab, g, mad}};
    place_center(xy, T, g);
    for (int k = 0; k < 3; k++) {
        memcpy(fv + 4 * w, T[k], sizeof T[k]);
        fo[w++] = glpgp_shape_split_origin(q, F->Q);
        worst = fmin(worst, glpgp_poly_min_sj(xy, T[k], 4));
    }
    return fmin(worst, glpgp_shape_strip_halves(q, F, s0, s0[1] + F->len[1] + 1, xy, fv, fo, &w));
}

glpgp_status glpgp_shape_arrays_alloc(const glpgp_quadmesh *q, int nv, int nf, shape_arrays *N)
{
    memset(N, 0, sizeof *N);
    glpgp_status st = glpgp_malloc((size_t)nv + 1, 2 * sizeof(double), &N->xy);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)4 * nf + 1, sizeof(int), &N->fv);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nf + 1, sizeof(int), &N->fs);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nf + 1, 1, &N->fo);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)q->nf + 1, 1, &N->cut);
    return st;
}

void glpgp_shape_arrays_free(shape_arrays *N)
{
    free(N->xy);
    free(N->fv);
    free(N->fs);
    free(N->fo);
    free(N->cut);
    memset(N, 0, sizeof *N);
}

/* Apply F to q when none of its new quads is below SHAPE_FLAT_NEW (*done 1). */
static glpgp_status flat_commit(glpgp_quadmesh *q, const flat_fix *F, int *done, double *worst)
{
    *done = 0;
    *worst = -INFINITY;
    const int nv = q->nv + 3 - F->loop + F->len[0] + F->len[1] + F->ncross;
    const int nf = q->nf + 2 + F->len[0] + F->len[1] + F->ncross;
    shape_arrays N;
    glpgp_status st = glpgp_shape_arrays_alloc(q, nv, nf, &N);
    if (st == GLPGP_OK) *worst = flat_apply(q, F, N.xy, N.fv, N.fo, N.cut);
    if (st == GLPGP_OK && *worst > SHAPE_FLAT_NEW) {
        glpgp_qm_adopt_quads(q, &N.xy, nv, &N.fv, &N.fs, &N.fo, nf);
        *done = 1;
    }
    glpgp_shape_arrays_free(&N);
    return st;
}

/* The worst corner scaled Jacobian of q, and in *below the quads under the goal. */
static double mesh_worst(const glpgp_quadmesh *q, int *below)
{
    double m = INFINITY;
    *below = 0;
    for (int f = 0; f < q->nf; f++) {
        double sj = glpgp_poly_min_sj(q->xy, q->face_vert + q->face_start[f], q->face_start[f + 1] - q->face_start[f]);
        m = fmin(m, sj);
        *below += sj < GLPGP_QUADS_SJ_GOAL;
    }
    return m;
}

/* The mesh's quality as a tip fix is judged: the worst quad relative to
 * what the domain's sharp corners allow it (sin of the corner), and the
 * quads below the goal and below SHAPE_BELOW where no corner forces it. */
typedef struct shape_score {
    double worst;
    int below, below_half, irregular;
} shape_score;

/* Interior vertices of q whose face count is not 4. */
static glpgp_status irregular_interior(const glpgp_quadmesh *q, int *count)
{
    qsides E = {NULL, 0};
    int *deg = NULL;
    *count = 0;
    glpgp_status st = glpgp_qsides_build(q, &E);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)q->nv + 1, sizeof(int), &deg);
    for (int f = 0; f < q->nf && st == GLPGP_OK; f++)
        for (int i = 0; i < 4; i++) {
            int j = -1, v = q->face_vert[4 * f + i];
            if (deg[v] >= 0) deg[v]++;
            if (glpgp_qsides_across(&E, q, f, i, &j) < 0) deg[v] = deg[q->face_vert[4 * f + (i + 1) % 4]] = -1000000;
        }
    for (int v = 0; v < q->nv && st == GLPGP_OK; v++) *count += deg[v] > 0 && deg[v] != 4;
    glpgp_qsides_free(&E);
    free(deg);
    return st;
}

static glpgp_status score_mesh(const glpgp_quadmesh *q, const glpgp_mesh *m, double h, shape_score *sc)
{
    double *bound = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)q->nf + 1, sizeof(double), &bound));
    glpgp_status st = glpgp_qcheck_corner_bound(q, m, h, bound);
    sc->worst = INFINITY;
    sc->below = sc->below_half = 0;
    for (int f = 0; f < q->nf && st == GLPGP_OK; f++) {
        double sj = glpgp_poly_min_sj(q->xy, q->face_vert + q->face_start[f], q->face_start[f + 1] - q->face_start[f]);
        sc->worst = fmin(sc->worst, sj / bound[f]);
        sc->below += glpgp_qcheck_unforced_below(sj, bound[f], GLPGP_QUADS_SJ_GOAL);
        sc->below_half += glpgp_qcheck_unforced_below(sj, bound[f], SHAPE_BELOW);
    }
    free(bound);
    if (st == GLPGP_OK) st = irregular_interior(q, &sc->irregular);
    return st;
}

/* Kept by the corners' measure: the worst quad relative to its bound, the
 * quads below the goal and below SHAPE_BELOW and the irregular interior
 * vertices all no worse, one of them better. */
static glpgp_status better_bounded(const glpgp_quadmesh *before, const glpgp_quadmesh *after, const glpgp_mesh *m,
                                   double h, int *done, double *worst)
{
    shape_score s0, s1;
    GLPGP_CHECK(score_mesh(before, m, h, &s0));
    GLPGP_CHECK(score_mesh(after, m, h, &s1));
    *worst = s1.worst;
    *done = s1.worst >= s0.worst - 1e-12 && s1.below <= s0.below && s1.below_half <= s0.below_half &&
            s1.irregular <= s0.irregular &&
            (s1.below < s0.below || s1.below_half < s0.below_half || s1.irregular < s0.irregular ||
             s1.worst > s0.worst + 1e-9);
    return GLPGP_OK;
}

/* A change applied by commit (on *done 1) and the mesh smoothed; kept
 * (*done 1) when the mesh has then fewer quads below the goal or a better
 * worst one, and that no worse (m NULL), or when better_bounded says so
 * (m given); else q restored. */

glpgp_status glpgp_shape_try(glpgp_quadmesh *q, shape_commit commit, const void *fix, const glpgp_mesh *m, double h,
                              int *done, double *worst, int *nmoved)
{
    glpgp_quadmesh *save = glpgp_qm_copy(q);
    if (!save) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quads: no memory for the shape pass");
    int moved = 0;
    glpgp_status st = commit(q, fix, done, worst);
    if (st == GLPGP_OK && *done) st = optimise(q, &moved);
    if (st == GLPGP_OK && *done) *nmoved += moved;
    if (st == GLPGP_OK && *done && m) st = better_bounded(save, q, m, h, done, worst);
    else if (st == GLPGP_OK && *done) { /* better: fewer quads below the goal or a better worst, that no worse */
        int b0 = 0, b1 = 0;
        double m0 = mesh_worst(save, &b0), m1 = mesh_worst(q, &b1);
        *worst = m1;
        *done = m1 >= m0 - 1e-12 && (b1 < b0 || m1 > m0 + 1e-9);
    }
    if (st == GLPGP_OK && !*done) { /* back to the mesh before */
        glpgp_quadmesh tmp = *q;
        *q = *save;
        *save = tmp;
    }
    glpgp_quadmesh_destroy(&save);
    return st;
}

static glpgp_status flat_commit_any(glpgp_quadmesh *q, const void *F, int *done, double *worst)
{
    return flat_commit(q, (const flat_fix *)F, done, worst);
}

/* The worst flat boundary corner not refused yet: (Q, i) and its scaled
 * Jacobian; -1 when none. */
static int flat_find(const glpgp_quadmesh *q, const vstar *S, const unsigned char *refused, int *Q, int *ci,
                     double *sjq)
{
    int best = -1;
    *sjq = INFINITY;
    for (int c = 0; c < q->nv; c++) {
        if (refused[c] || S->vs[c + 1] - S->vs[c] != 1) continue;
        int slot = S->vc[S->vs[c]], f = S->sf[slot], i = slot - 4 * f;
        const int *v = q->face_vert + 4 * f;
        const double *p = q->xy + 2 * c, *b = q->xy + 2 * v[(i + 3) % 4], *d = q->xy + 2 * v[(i + 1) % 4];
        double sj = glpgp_shape_corner_sj(q->xy, v, 4, i);
        double dot = (b[0] - p[0]) * (d[0] - p[0]) + (b[1] - p[1]) * (d[1] - p[1]);
        if (!(sj < GLPGP_QUADS_SJ_GOAL) || !(dot < 0) || !(sj < *sjq)) continue;
        *sjq = sj;
        *Q = f;
        *ci = i;
        best = c;
    }
    return best;
}

static glpgp_status flat_corners(glpgp_quadmesh *q, const glpgp_mesh *m, double h, int *nfixed, int *nmoved)
{
    *nfixed = 0;
    for (int f = 0; f < q->nf; f++)
        if (q->face_start[f] != 4 * f || q->face_start[f + 1] != 4 * f + 4) return GLPGP_OK;
    dbnd D;
    GLPGP_CHECK(glpgp_dbnd_build(&D, m, h));
    unsigned char *refused = NULL;
    int *cand = NULL, ncap = 0;
    flat_fix F;
    memset(&F, 0, sizeof F);
    glpgp_status st = glpgp_calloc((size_t)q->nv + 1, 1, &refused);
    for (int round = 0; round < SHAPE_FLAT_MAX && st == GLPGP_OK; round++) {
        vstar S;
        qsides E = {NULL, 0};
        double sjq = 0.0, worst = -INFINITY;
        int done = 0, c = -1;
        st = glpgp_vstar_build(q, &S);
        if (st == GLPGP_OK) st = glpgp_qsides_build(q, &E);
        for (int k = 0; k < 2; k++) {
            free(F.path[k]);
            free(F.pos[k]);
            F.path[k] = F.pos[k] = NULL;
        }
        for (int k = 0; k < 2 && st == GLPGP_OK; k++) {
            st = glpgp_malloc((size_t)q->nf + 1, sizeof(int), &F.pos[k]);
            for (int f = 0; f < q->nf && st == GLPGP_OK; f++) F.pos[k][f] = -1;
        }
        if (st == GLPGP_OK) st = glpgp_malloc((size_t)4 * q->nf + 2, sizeof(int), &F.path[0]);
        if (st == GLPGP_OK) st = glpgp_malloc((size_t)4 * q->nf + 2, sizeof(int), &F.path[1]);
        if (st == GLPGP_OK) c = flat_find(q, &S, refused, &F.Q, &F.i, &sjq);
        F.len[0] = F.len[1] = F.loop = F.ncross = 0;
        if (st == GLPGP_OK && c >= 0 && flat_strips(q, &E, &D, h, &F, &cand, &ncap))
            st = glpgp_shape_try(q, flat_commit_any, &F, NULL, 0.0, &done, &worst, nmoved);
        glpgp_vstar_free(&S);
        glpgp_qsides_free(&E);
        if (st != GLPGP_OK || c < 0) break;
        if (!done) {
            glpgp_log(GLPGP_LOG_DEBUG, "quads: flat corner at (%.4g, %.4g), SJ %.3f: not split (strips %d, %d; new quads %.3f)",
                      q->xy[2 * c], q->xy[2 * c + 1], sjq, F.len[0], F.len[1], worst);
            refused[c] = 1;
            continue;
        }
        (*nfixed)++;
        unsigned char *r2 = NULL; /* room for the new vertices (never refused) */
        st = glpgp_calloc((size_t)q->nv + 1, 1, &r2);
        if (st == GLPGP_OK) memcpy(r2, refused, (size_t)(q->nv - 3 + F.loop - F.len[0] - F.len[1] - F.ncross));
        free(refused);
        refused = r2;
    }
    glpgp_dbnd_free(&D);
    free(refused);
    free(cand);
    for (int k = 0; k < 2; k++) {
        free(F.path[k]);
        free(F.pos[k]);
    }
    return st;
}

glpgp_status glpgp_quadmesh_shape_pass(glpgp_quadmesh *q, const glpgp_mesh *m, double h, int *tips, int *flat,
                                       int *moved)
{
    *tips = *flat = *moved = 0;
    if (!q || q->nf <= 0) return GLPGP_OK;
    int m0 = 0, m1 = 0, m2 = 0;
    GLPGP_CHECK(glpgp_shape_tips(q, m, h, tips, &m0));
    GLPGP_CHECK(flat_corners(q, m, h, flat, &m1));
    GLPGP_CHECK(optimise(q, &m2));
    *moved = m0 + m1 + m2; /* moves (a vertex moved in two sweeps counts twice) */
    return GLPGP_OK;
}
