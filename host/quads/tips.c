/* quads/tips.c: sharp tips in the last shape pass (glpgp_shape_tips,
 * shape_impl.h). A boundary corner T below 60 degrees in one quad, whose
 * neighbourhood the repair filled with poor quads or clusters of irregular
 * vertices (a narrow arm ending in a tip: a region with 4 and 5 boundary
 * edges on its sides and 1 across leaves no good layout), is re-meshed:
 *
 * - the region: the faces between T and a cut across the two straight
 *   domain sides from T, the cut one mesh edge A -> B or two A -> M -> B
 *   through an interior vertex, tried by the number of side points they
 *   keep (fewest first); the region is taken when its boundary is the two
 *   straight chains and the cut, it has at most TIP_MAX_FACES faces, and a
 *   quad below 0.5 that the tip does not force, or two irregular interior
 *   vertices;
 * - the triangle T-A-B split by its incircle into three kites (center c,
 *   tangent points m1, m2 on the sides, mb on A-B): the kite at T has the
 *   tip's angle at T and at c (the corner's bound), the two others right
 *   angles at the tangent points; the side points between T and A, B go;
 * - with one cut edge, mb is carried across the mesh by a strip of quads cut
 *   in two (shape.c's strips) to the boundary; with two, mb is M, no strip.
 *
 * The change is kept (glpgp_shape_try, corners' measure) when the worst
 * quad relative to its corner bound, the quads below 0.3 and 0.5 where no
 * corner forces them and the irregular interior vertices are no worse, one
 * of them better. */
#include "shape_impl.h"
#include "geom.h"
#include "check.h"
#include "glpgp/internal/geom2.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TIP_ANGLE 1.0471975511965976 /* tips below 60 degrees */
#define TIP_MAX_FACES 40              /* the largest region re-meshed at a tip */

typedef struct tip_fix {
    flat_fix F;          /* the strip from the base (strip 0; Q = -1; none when M >= 0) */
    int T, A, B, M;      /* the tip; the region's boundary inside the domain: A -> B, or A -> M -> B */
    int f0;              /* the tip's face (the kites take its origin) */
    int g, j;            /* one side: the face across A -> B and its side there (the strip's start) */
    int *list, n;        /* the region's faces */
    unsigned char *in;   /* per face: 1 in the region, 2 in the ring being added */
} tip_fix;

/* The region's boundary sides (each face side with no region face across)
 * walked as one loop from B: the chains B -> T and T -> A along the domain
 * boundary, straight (each point on the segment to within 1e-6 of its
 * length), then the nbase sides inside the domain back to B; 1 when so. */
static int tip_loop_straight(const glpgp_quadmesh *q, const qsides *E, const tip_fix *X, int nb, int nbase, int *next)
{
    for (int k = 0; k < X->n; k++)
        for (int i = 0; i < 4; i++) {
            int f = X->list[k], j = -1, g = glpgp_qsides_across(E, q, f, i, &j);
            if (g >= 0 && X->in[g] == 1) continue;
            int a = q->face_vert[4 * f + i], b = q->face_vert[4 * f + (i + 1) % 4];
            if (next[a] >= 0) return 0; /* the loop touches itself */
            next[a] = b;
        }
    int steps = 0, seen_t = 0, v = X->B, from = X->B;
    while (v != X->A && steps <= nb) {
        if (v == X->T) {
            seen_t = 1;
            from = X->T;
        } else if (v != from) { /* a chain point: on the segment from its chain's start to its end */
            const double *p = q->xy + 2 * v, *s = q->xy + 2 * from, *e = q->xy + 2 * (seen_t ? X->A : X->T);
            double ux = e[0] - s[0], uy = e[1] - s[1], L = hypot(ux, uy);
            double t = ((p[0] - s[0]) * ux + (p[1] - s[1]) * uy) / (L * L);
            if (!(L > 0) || t <= 0 || t >= 1 || fabs((p[0] - s[0]) * uy - (p[1] - s[1]) * ux) > 1e-6 * L * L) return 0;
        }
        v = next[v];
        steps++;
        if (v < 0) return 0;
    }
    return v == X->A && seen_t && steps == nb - nbase;
}

/* The tip's triangle T-A-B (its angle at T below TIP_ANGLE) and a quad of
 * the region below SHAPE_BELOW where the tip does not force it: 1 when the
 * region is worth re-meshing. */
/* The region's interior vertices (off the boundary, every face in the
 * region) with other than 4 faces. */
static int tip_irregular(const glpgp_quadmesh *q, const vstar *S, const tip_fix *X, const int *bnext)
{
    int n = 0;
    for (int k = 0; k < X->n; k++)
        for (int i = 0; i < 4; i++) {
            int v = q->face_vert[4 * X->list[k] + i], all = bnext[v] < 0;
            if (S->sf[S->vc[S->vs[v]]] != X->list[k]) continue; /* counted at its first face only */
            for (int t = S->vs[v]; t < S->vs[v + 1] && all; t++) all = X->in[S->sf[S->vc[t]]] != 0;
            n += all && S->vs[v + 1] - S->vs[v] != 4;
        }
    return n;
}

static int tip_worth(const glpgp_quadmesh *q, const vstar *S, const tip_fix *X, const int *bnext)
{
    const double *t = q->xy + 2 * X->T, *a = q->xy + 2 * X->A, *b = q->xy + 2 * X->B;
    double ux = a[0] - t[0], uy = a[1] - t[1], vx = b[0] - t[0], vy = b[1] - t[1];
    double al = atan2(ux * vy - uy * vx, ux * vx + uy * vy);
    if (!(al > 0 && al < TIP_ANGLE)) return 0;
    if (X->M >= 0) { /* M inside the triangle's side A-B, seen from T */
        const double *mm = q->xy + 2 * X->M;
        if (glpgp_orient2(t, a, mm) <= 0 || glpgp_orient2(t, mm, b) <= 0 || glpgp_orient2(a, b, mm) > 0) return 0;
    }
    double bound = sin(al);
    for (int k = 0; k < X->n; k++) {
        int f = X->list[k];
        double sj = glpgp_poly_min_sj(q->xy, q->face_vert + 4 * f, 4);
        if (glpgp_qcheck_unforced_below(sj, f == X->f0 ? bound : 1.0, SHAPE_BELOW)) return 1;
    }
    return tip_irregular(q, S, X, bnext) >= 2;
}

/* The domain boundary's sides of q as next / previous boundary vertex
 * (-1 off the boundary). */
static void boundary_links(const glpgp_quadmesh *q, const qsides *E, int *bnext, int *bprev)
{
    for (int v = 0; v < q->nv; v++) bnext[v] = bprev[v] = -1;
    for (int f = 0; f < q->nf; f++)
        for (int i = 0; i < 4; i++) {
            int j = -1;
            if (glpgp_qsides_across(E, q, f, i, &j) >= 0) continue;
            int a = q->face_vert[4 * f + i], b = q->face_vert[4 * f + (i + 1) % 4];
            bnext[a] = b;
            bprev[b] = a;
        }
}

/* The straight chain of boundary vertices from T through first along link
 * (at most TIP_CHAIN): its length. */
#define TIP_CHAIN 24
static int tip_chain(const glpgp_quadmesh *q, const int *link, int T, int first, int *chain)
{
    const double *t = q->xy + 2 * T, *u = q->xy + 2 * first;
    double ux = u[0] - t[0], uy = u[1] - t[1], L = hypot(ux, uy);
    int n = 0, v = first;
    while (v >= 0 && v != T && n < TIP_CHAIN && L > 0) {
        const double *p = q->xy + 2 * v;
        double along = ((p[0] - t[0]) * ux + (p[1] - t[1]) * uy) / L;
        if (fabs((p[0] - t[0]) * uy - (p[1] - t[1]) * ux) > 1e-6 * L * fmax(along, L)) break;
        if (n > 0 && along <= ((q->xy[2 * chain[n - 1]] - t[0]) * ux + (q->xy[2 * chain[n - 1] + 1] - t[1]) * uy) / L) break;
        chain[n++] = v;
        v = link[v];
    }
    return n;
}

/* The region behind cut A -> (M ->) B seen from the tip's face: faces
 * reached from T's face without crossing the cut; 1 when it holds at most
 * TIP_MAX_FACES faces, its boundary is the straight chains and the cut
 * (tip_loop_straight) and it is worth re-meshing. */
static int tip_flood(const glpgp_quadmesh *q, const qsides *E, const vstar *S, const int *bnext, tip_fix *X,
                     int *next)
{
    int cut[2][2] = {{X->A, X->M >= 0 ? X->M : X->B}, {X->M, X->B}}, ncut = X->M >= 0 ? 2 : 1;
    X->list[0] = X->f0;
    X->in[X->f0] = 1;
    X->n = 1;
    int ok = 1, nb = 0, nint = 0;
    for (int k = 0; k < X->n && ok; k++)
        for (int i = 0; i < 4 && ok; i++) {
            int f = X->list[k], j = -1, g = glpgp_qsides_across(E, q, f, i, &j);
            int a = q->face_vert[4 * f + i], b = q->face_vert[4 * f + (i + 1) % 4], on_cut = 0;
            for (int c = 0; c < ncut; c++) on_cut |= a == cut[c][0] && b == cut[c][1];
            if (g >= 0 && !on_cut && !X->in[g]) {
                if (X->n >= TIP_MAX_FACES) ok = 0;
                else {
                    X->in[g] = 1;
                    X->list[X->n++] = g;
                }
            }
        }
    for (int k = 0; k < X->n && ok; k++) /* the sides out of the region: the cut's inside ones */
        for (int i = 0; i < 4; i++) {
            int f = X->list[k], j = -1, g = glpgp_qsides_across(E, q, f, i, &j);
            if (g >= 0 && X->in[g]) continue;
            nb++;
            if (g < 0) continue;
            nint++;
            X->g = g;
            X->j = j;
        }
    if (ok) ok = nint == ncut && tip_loop_straight(q, E, X, nb, ncut, next);
    for (int k = 0; k < X->n; k++)
        for (int i = 0; i < 4; i++) next[q->face_vert[4 * X->list[k] + i]] = -1;
    if (ok) ok = tip_worth(q, S, X, bnext);
    if (!ok)
        for (int k = 0; k < X->n; k++) X->in[X->list[k]] = 0;
    return ok;
}

/* The region at tip T (a boundary corner in one face f0, corner i0): the
 * first cut across the straight sides from T, by the number of chain points
 * it keeps in the region, that is one mesh edge A -> B or two A -> M -> B
 * through an interior vertex and whose region tip_flood accepts; 1 when
 * found (X->A, X->M, X->B, the region in X->list). */
static int tip_region(const glpgp_quadmesh *q, const qsides *E, const vstar *S, const int *bnext, const int *bprev,
                      tip_fix *X, int i0, int *next)
{
    int fw[TIP_CHAIN], bw[TIP_CHAIN];
    const int *v0 = q->face_vert + 4 * X->f0;
    int nf = tip_chain(q, bnext, X->T, v0[(i0 + 1) % 4], fw), nbk = tip_chain(q, bprev, X->T, v0[(i0 + 3) % 4], bw);
    for (int sum = 2; sum <= nf + nbk; sum++)
        for (int i = 1; i <= nf; i++) {
            int j = sum - i;
            if (j < 1 || j > nbk) continue;
            X->A = fw[i - 1];
            X->B = bw[j - 1];
            /* A's neighbours: B itself (one side), or an interior M next to B */
            for (int s = S->vs[X->A]; s < S->vs[X->A + 1]; s++) {
                int c = S->vc[s], f = S->sf[c], k = c - 4 * f, nb = q->face_vert[4 * f + (k + 1) % 4];
                int M = nb == X->B ? -1 : nb;
                if (M >= 0) { /* M must be interior and next to B (B -> M is M's previous side... any face of M holds B next to it) */
                    if (bnext[M] >= 0 || bprev[M] >= 0) continue;
                    int adj = 0;
                    for (int t = S->vs[M]; t < S->vs[M + 1] && !adj; t++) {
                        int c2 = S->vc[t], f2 = S->sf[c2], k2 = c2 - 4 * f2;
                        adj = q->face_vert[4 * f2 + (k2 + 1) % 4] == X->B;
                    }
                    if (!adj) continue;
                }
                X->M = M;
                if (tip_flood(q, E, S, bnext, X, next)) return 1;
            }
        }
    return 0;
}

/* q's vertices that no face uses dropped (faces renumbered). */
static glpgp_status drop_unused(double *xy, int *nv, int *fv, int nf)
{
    int *map = NULL, m = 0;
    GLPGP_CHECK(glpgp_malloc((size_t)*nv + 1, sizeof(int), &map));
    for (int v = 0; v < *nv; v++) map[v] = -1;
    for (int k = 0; k < 4 * nf; k++) map[fv[k]] = 0;
    for (int v = 0; v < *nv; v++)
        if (map[v] == 0) {
            map[v] = m;
            xy[2 * m] = xy[2 * v];
            xy[2 * m + 1] = xy[2 * v + 1];
            m++;
        }
    for (int k = 0; k < 4 * nf; k++) fv[k] = map[fv[k]];
    *nv = m;
    free(map);
    return GLPGP_OK;
}

/* The region replaced by the incircle's three kites of triangle T-A-B
 * (center c, tangent points m1 on T-A, mb on A-B, m2 on B-T; the kite at T
 * has the tip's angle at T and at c, the others right angles), mb carried
 * across the mesh by the strip; with a base A -> M -> B, M is mb and there
 * is no strip. New vertices: c, the strip's points from mb on, m1, m2, the
 * crossings' centers. */
static double tip_apply(const glpgp_quadmesh *q, const tip_fix *X, double *xy, int *fv, unsigned char *fo,
                        unsigned char *cut, int *nf)
{
    const flat_fix *F = &X->F;
    const int nv = q->nv, c = nv, s0[2] = {nv + 1, nv + 1}, m1 = nv + 2 + F->len[0], m2 = m1 + 1;
    const int mb = X->M >= 0 ? X->M : s0[0];
    memcpy(xy, q->xy, sizeof(double) * 2 * (size_t)nv);
    glpgp_shape_strip_points(q, F, X->M >= 0 ? 0 : 1, s0, xy, cut);
    const double *T = q->xy + 2 * X->T, *A = q->xy + 2 * X->A, *B = q->xy + 2 * X->B;
    double la = hypot(B[0] - A[0], B[1] - A[1]), lb = hypot(T[0] - B[0], T[1] - B[1]);
    double lc = hypot(A[0] - T[0], A[1] - T[1]), s = 0.5 * (la + lb + lc);
    for (int e = 0; e < 2; e++) {
        xy[2 * c + e] = (la * T[e] + lb * A[e] + lc * B[e]) / (la + lb + lc);
        xy[2 * m1 + e] = T[e] + (s - la) / lc * (A[e] - T[e]);
        xy[2 * m2 + e] = T[e] + (s - la) / lb * (B[e] - T[e]);
        if (X->M < 0) xy[2 * s0[0] + e] = A[e] + (s - lb) / la * (B[e] - A[e]);
        else xy[2 * s0[0] + e] = 0.0;
    }
    int w = 0;
    for (int f = 0; f < q->nf; f++)
        if (!cut[f] && !X->in[f]) {
            memcpy(fv + 4 * w, q->face_vert + 4 * f, 4 * sizeof(int));
            fo[w++] = q->face_origin ? q->face_origin[f] : GLPGP_QFACE_GRID;
        }
    int K[3][4] = {{X->T, m1, c, m2}, {m1, X->A, mb, c}, {c, mb, X->B, m2}};
    double worst = INFINITY;
    for (int k = 0; k < 3; k++) {
        memcpy(fv + 4 * w, K[k], sizeof K[k]);
        fo[w++] = glpgp_shape_split_origin(q, X->f0);
        worst = fmin(worst, glpgp_poly_min_sj(xy, K[k], 4));
    }
    worst = fmin(worst, glpgp_shape_strip_halves(q, F, s0, m2 + 1, xy, fv, fo, &w));
    *nf = w;
    return worst;
}

/* Apply tip fix X to q when its new quads are not inverted (*done 1). */
static glpgp_status tip_commit(glpgp_quadmesh *q, const void *fix, int *done, double *worst)
{
    const tip_fix *X = fix;
    *done = 0;
    *worst = -INFINITY;
    int nv = q->nv + 4 + X->F.len[0] + X->F.ncross, nf = q->nf + 3 + X->F.len[0] + X->F.ncross;
    shape_arrays N;
    glpgp_status st = glpgp_shape_arrays_alloc(q, nv, nf, &N);
    if (st == GLPGP_OK) *worst = tip_apply(q, X, N.xy, N.fv, N.fo, N.cut, &nf);
    if (st == GLPGP_OK && *worst > SHAPE_FLAT_NEW) st = drop_unused(N.xy, &nv, N.fv, nf);
    if (st == GLPGP_OK && *worst > SHAPE_FLAT_NEW) {
        glpgp_qm_adopt_quads(q, &N.xy, nv, &N.fv, &N.fs, &N.fo, nf);
        *done = 1;
    }
    glpgp_shape_arrays_free(&N);
    return st;
}

/* The sharp tip to re-mesh next: T not refused (by its position), in one
 * face, with a region worth it whose strip reaches the boundary; its strip's
 * end in X->F.end[0]. -1 when none. */
static int tip_find(const glpgp_quadmesh *q, const vstar *S, const qsides *E, dbnd *D, double h, const double *refused,
                    int nref, tip_fix *X, int *next, int **cand, int *ncap)
{
    const int *bnext = next + q->nv, *bprev = next + 2 * q->nv;
    for (int T = 0; T < q->nv; T++) {
        if (S->vs[T + 1] - S->vs[T] != 1) continue;
        int slot = S->vc[S->vs[T]], f0 = S->sf[slot], r = 0;
        const double *p = q->xy + 2 * T;
        for (int k = 0; k < nref && !r; k++) r = refused[2 * k] == p[0] && refused[2 * k + 1] == p[1];
        if (r) continue;
        if (glpgp_shape_corner_sj(q->xy, q->face_vert + 4 * f0, 4, slot - 4 * f0) > sin(TIP_ANGLE)) continue;
        X->T = T;
        X->f0 = f0;
        X->n = 0;
        X->F.Q = -1;
        X->F.len[0] = X->F.len[1] = X->F.loop = X->F.ncross = 0;
        int ok = tip_region(q, E, S, bnext, bprev, X, slot - 4 * f0, next), fe = -1, ie = -1;
        if (ok && X->M >= 0) return T; /* two sides inside: their middle point is the base's */
        if (ok) ok = glpgp_shape_trace(E, q, &X->F, 0, X->g, X->j, -1, &fe, &ie) == 1 && X->F.len[0] > 0;
        if (ok) {
            const int *v = q->face_vert + 4 * fe;
            const double *a = q->xy + 2 * v[ie], *b = q->xy + 2 * v[(ie + 1) % 4];
            double loss = 0.0;
            if (!glpgp_dbnd_chord(D, a, b, h, &loss, X->F.end[0], cand, ncap))
                for (int e = 0; e < 2; e++) X->F.end[0][e] = 0.5 * (a[e] + b[e]);
            return T;
        }
        for (int t = 0; t < X->F.len[0]; t++) X->F.pos[0][X->F.path[0][2 * t]] = X->F.pos[1][X->F.path[0][2 * t]] = -1;
        for (int k = 0; k < X->n; k++) X->in[X->list[k]] = 0;
    }
    return -1;
}

static void tip_free(tip_fix *X)
{
    free(X->F.path[0]);
    free(X->F.pos[0]);
    free(X->F.pos[1]);
    free(X->list);
    free(X->in);
    memset(X, 0, sizeof *X);
}

static glpgp_status tip_alloc(const glpgp_quadmesh *q, tip_fix *X)
{
    memset(X, 0, sizeof *X);
    glpgp_status st = glpgp_malloc((size_t)4 * q->nf + 2, sizeof(int), &X->F.path[0]);
    for (int k = 0; k < 2 && st == GLPGP_OK; k++) {
        st = glpgp_malloc((size_t)q->nf + 1, sizeof(int), &X->F.pos[k]);
        for (int f = 0; f < q->nf && st == GLPGP_OK; f++) X->F.pos[k][f] = -1;
    }
    if (st == GLPGP_OK) st = glpgp_malloc(TIP_MAX_FACES + 1, sizeof(int), &X->list);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)q->nf + 1, 1, &X->in);
    return st;
}

/* Sharp boundary tips whose regions hold quads below the goal that the tip
 * does not force: each region re-meshed as its triangle's incircle kites
 * with one strip (tip_apply); kept as flat_corners keeps a split. */
/* 1 when some vertex is in one face only with a corner below TIP_ANGLE. */
static glpgp_status any_tip(const glpgp_quadmesh *q, int *any)
{
    int *cnt = NULL;
    *any = 0;
    GLPGP_CHECK(glpgp_calloc((size_t)q->nv + 1, sizeof(int), &cnt));
    for (int k = 0; k < 4 * q->nf; k++) cnt[q->face_vert[k]]++;
    for (int k = 0; k < 4 * q->nf && !*any; k++)
        if (cnt[q->face_vert[k]] == 1) {
            const double *t = q->xy + 2 * q->face_vert[k], *a = q->xy + 2 * q->face_vert[4 * (k / 4) + (k + 1) % 4],
                         *b = q->xy + 2 * q->face_vert[4 * (k / 4) + (k + 3) % 4];
            double ux = a[0] - t[0], uy = a[1] - t[1], vx = b[0] - t[0], vy = b[1] - t[1];
            double al = atan2(ux * vy - uy * vx, ux * vx + uy * vy);
            *any = al > 0 && al < TIP_ANGLE;
        }
    free(cnt);
    return GLPGP_OK;
}

glpgp_status glpgp_shape_tips(glpgp_quadmesh *q, const glpgp_mesh *m, double h, int *nfixed, int *nmoved)
{
    *nfixed = 0;
    for (int f = 0; f < q->nf; f++)
        if (q->face_start[f] != 4 * f || q->face_start[f + 1] != 4 * f + 4) return GLPGP_OK;
    int any = 0;
    GLPGP_CHECK(any_tip(q, &any));
    if (!any) return GLPGP_OK;
    dbnd D;
    GLPGP_CHECK(glpgp_dbnd_build(&D, m, h));
    double *refused = NULL;
    int nref = 0, *cand = NULL, ncap = 0, *next = NULL;
    glpgp_status st = glpgp_malloc(2 * SHAPE_FLAT_MAX + 2, sizeof(double), &refused);
    for (int round = 0; round < SHAPE_FLAT_MAX && st == GLPGP_OK; round++) {
        vstar S;
        qsides E = {NULL, 0};
        tip_fix X;
        double worst = -INFINITY;
        int done = 0, T = -1;
        memset(&S, 0, sizeof S);
        st = tip_alloc(q, &X);
        if (st == GLPGP_OK) st = glpgp_vstar_build(q, &S);
        if (st == GLPGP_OK) st = glpgp_qsides_build(q, &E);
        if (st == GLPGP_OK) st = glpgp_malloc((size_t)3 * q->nv + 1, sizeof(int), &next);
        for (int v = 0; v < q->nv && st == GLPGP_OK; v++) next[v] = -1;
        if (st == GLPGP_OK) boundary_links(q, &E, next + q->nv, next + 2 * q->nv);
        if (st == GLPGP_OK) T = tip_find(q, &S, &E, &D, h, refused, nref, &X, next, &cand, &ncap);
        double tx = T >= 0 ? q->xy[2 * T] : 0.0, ty = T >= 0 ? q->xy[2 * T + 1] : 0.0;
        if (T >= 0) st = glpgp_shape_try(q, tip_commit, &X, m, h, &done, &worst, nmoved);
        glpgp_vstar_free(&S);
        glpgp_qsides_free(&E);
        tip_free(&X);
        free(next);
        next = NULL;
        if (st != GLPGP_OK || T < 0) break;
        glpgp_log(GLPGP_LOG_DEBUG, "quads: sharp tip at (%.4g, %.4g): %s (worst %.3f)", tx, ty,
                  done ? "re-meshed" : "not re-meshed", worst);
        if (done) (*nfixed)++;
        refused[2 * nref] = tx; /* done or not, a tip is tried once */
        refused[2 * nref + 1] = ty;
        nref++;
    }
    glpgp_dbnd_free(&D);
    free(refused);
    free(cand);
    return st;
}
