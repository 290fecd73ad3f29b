/* solver/sizefield.c: the local target size h(x) of each oscillator, the
 * local resolution check of the input mesh (its refinement: refine.c)
 * (glpgp/solve.h; design and measurements in docs/numerics.md, "Local size").
 *
 * auto (GLPGP_SIZE_AUTO, anisotropic) and iso (GLPGP_SIZE_ISO): local feature
 * size from the boundary.
 *   1. From the midpoint p_e of every boundary edge e (outward unit normal
 *      n_e) a ray is cast inward (-n_e) to the first other boundary edge
 *      (uniform grid of boundary edges, cell walk): the chord t_e, the
 *      thickness of the domain there (a wall, a strip, a web, a tooth; rays
 *      longer than N H are not followed: they cannot lower the size below H).
 *      Gaps (slots, cracks, small holes: the chord outward) are not sized:
 *      they are not meshed, and shrinking the size next to them was measured
 *      to cost more repairs and irregular vertices (bench/results/size_field.md).
 *      Small loops (perimeter < GLPGP_SIZE_SMALL_LOOP H, holes of radius
 *      below 0.72 H) do not stop the rays of the rest of the boundary: a rim
 *      next to a row of small holes is not a wall (a rotor lamination with 16
 *      holes of radius 0.34 H 0.68 H from its rim: 1074 -> 419 irregular
 *      vertices; their own edges still seed, a ligament seen from the hole:
 *      letting them seed nothing cost the gasket's 0.17 H ligaments 460 ->
 *      593; bench/results/size_field.md).
 *   2. An oscillator with unit field W crosses that feature along W, over
 *      t_e / |W.n_e| for walls parallel to e, and needs N = size_across
 *      periods there:  s_e(W) = t_e / (N |W.n_e|)  (auto; |W.n_e| -> 0, a
 *      wave running along the feature, gives no constraint). The gradation
 *      of step 4 lets the size grow towards the feature's middle, so a strip
 *      gets about 0.8 N periods across at g = 1/2 (a wall size making it
 *      exactly N, t g / (2 (exp(g N / 2) - 1)), was measured no better on the
 *      hard domains: bench/results/size_field.md). iso uses
 *      s_e = t_e / N for both oscillators, the lower bound over W (used for
 *      the resolution check and the refinement, which come before the
 *      guiding field).
 *   3. A boundary vertex's seed is the smaller of its two edges' s_e,
 *      floored at size_min H; every other vertex starts at H.
 *   4. Gradation by Dijkstra over the mesh edges (g = size_grading):
 *        h_i = min(H, min_j (seed_j + g d(i, j))),  d the shortest mesh path,
 *      so h_i <= h_j + g |x_i - x_j| holds on every mesh edge (i, j).
 *   5. Boundary chords (size_chord_area, size_chord_depth; 0 both: off).
 *      The boundary quads cut straight chords across curved boundary parts.
 *      A chord of length h on an arc of radius R = 1 / |kappa| spans
 *      theta = 2 asin(h / 2R) and cuts the segment R^2 (theta - sin theta) / 2,
 *      per unit of arc a(h, kappa) = R (theta - sin theta) / (2 theta) ~
 *      h^2 / (12 R) (sagitta s = h^2 / 8R, segment ~ 2/3 s h). kappa_i per
 *      boundary vertex: the turning angle over an arc window of length h_i
 *      centered at i over its length, corners (turns > 40 degrees, kept as
 *      mesh vertices) excluded. Predicted error at the graded sizes (h_b the
 *      larger oscillator's, the chord along the boundary):
 *        L = sum_{convex e} a(h_e, kappa_e) |e| (lost),  G = the same over
 *        concave edges (gained: holes);
 *      the quality check compares the net area L - G. Only arcs of many
 *      chords per turn (h_e |kappa_e| <= 1/2: R >= 2 h, sagitta <= h / 16)
 *      follow the local size closely enough to be netted: S_n, O_n the parts
 *      of S, O there (few chords per turn, as on a hole of radius about h,
 *      were measured to come out far from the prediction). With B =
 *      size_chord_area x area, side S (L or G, O the other) needs capping
 *      when S - O_n > B (the net), S - S_n > B (what does not net, alone)
 *      or 1.4 S - O_n > 2 B (S at the model's measured under-prediction --
 *      the disk's real error is 1.4x the predicted -- beyond the check's
 *      tolerance 2 B). Otherwise the sizes stay exactly as they are (the
 *      motor lamination: its outer circle and its bore, R = 4.5 h and
 *      2.2 h, net out). A side that needs it gets its boundary sizes capped at
 *      h_i(c) = min(h_i, max(size_min h, c R_i)) with the largest c giving
 *      S <= B (bisection: L, G are non-decreasing in c; c >= 1/16, 100
 *      chords per turn, where B cannot be met; capping only down to the
 *      trigger was measured to break the quads' structure and gain nothing),
 *      then the other side is checked again. Features smaller than a quad
 *      (R < h_b / 2: small holes, slot ends, small rounded corners), and the
 *      boundary within h_b / 2 of them, are left out: like the gaps of step 1
 *      they are the repair's (sizing them was measured to cost vertices and
 *      irregular vertices). Independently, where the sagitta
 *      R - sqrt(R^2 - h^2 / 4) exceeds d = size_chord_depth h the size is
 *      capped at 2 sqrt(2 R d - d^2). A cap reaches about R into the
 *      domain: it grows from cap_i at the boundary with slope
 *      (h - cap_i) / R_i (at most g), so a disk gets a smaller size
 *      throughout (a thin band of smaller size at g was measured to change
 *      nothing: the oscillators keep their winding along the boundary), a
 *      small fillet only around it; the sizes become min(graded, capped).
 * function (GLPGP_SIZE_FUNC, e.g. a grey-level image): auto's seeds of step 3
 * are further limited to h f(x_i) (f clamped to [size_min, 1]) at every
 * vertex before the gradation of step 4, so the user's field refines where
 * it asks and the thin features keep auto's periods across.
 * file (GLPGP_SIZE_FILE): one positive value per line and vertex (both
 * oscillators) or two (h_u h_v); '#' comments and blank lines skipped.
 * none: H everywhere.
 *
 * Resolution: triangle T needs its longest edge L_T <= h_T / R with h_T the
 * smallest size at its corners (both oscillators, iso for auto), R =
 * size_resolution. glpgp_size_refine splits the triangles that do not
 * satisfy it by conforming longest-edge bisection (each round: the longest
 * edge of every such triangle is marked, then the longest edge of every
 * triangle with a marked edge, until closed; each triangle is bisected at its
 * longest edge and its halves at their marked edges: 2, 3 or 4 children;
 * angles stay bounded below by half the smallest input angle), recomputing the
 * sizes on the new mesh each round. */
#include "internal.h"

#include "glpgp/internal/heap.h"
#include "glpgp/internal/text.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- boundary edges and the ray grid -------------------------------------- */

typedef struct bedges {
    int n;        /* boundary edges */
    int *v;       /* 2n: endpoints a, b (domain on the left of a -> b) */
    double *nrm;  /* 2n: outward unit normals */
    /* uniform grid over the edges' bounding box: cell (ix, iy) lists
     * item[start[c] .. start[c+1]), c = iy nx + ix */
    double x0, y0, cs;
    int nx, ny;
    int *start, *item;
    unsigned char *small; /* per edge: of a small loop, which rays pass through (NULL: none) */
} bedges;

static void bedges_free(bedges *be)
{
    free(be->v);
    free(be->nrm);
    free(be->start);
    free(be->item);
    free(be->small);
    memset(be, 0, sizeof *be);
}

static int clampi(int v, int lo, int hi) { return v < lo ? lo : v > hi ? hi : v; }

static glpgp_status bedges_build(const glpgp_mesh *m, bedges *be)
{
    memset(be, 0, sizeof *be);
    const int n = m->loop_start[m->nloops];
    be->n = n;
    GLPGP_CHECK(glpgp_malloc((size_t)2 * n + 2, sizeof(int), &be->v));
    GLPGP_CHECK(glpgp_malloc((size_t)2 * n + 2, sizeof(double), &be->nrm));
    double xmin = HUGE_VAL, ymin = HUGE_VAL, xmax = -HUGE_VAL, ymax = -HUGE_VAL, len = 0.0;
    int k = 0;
    for (int l = 0; l < m->nloops; l++) {
        const int s = m->loop_start[l], e = m->loop_start[l + 1];
        for (int p = s; p < e; p++) {
            const int a = m->loop_vertices[p], b = m->loop_vertices[p + 1 < e ? p + 1 : s];
            const double dx = m->xy[2 * b] - m->xy[2 * a], dy = m->xy[2 * b + 1] - m->xy[2 * a + 1];
            const double L = hypot(dx, dy);
            be->v[2 * k] = a;
            be->v[2 * k + 1] = b;
            /* domain on the left of a -> b: outward normal = direction turned clockwise */
            be->nrm[2 * k] = L > 0.0 ? dy / L : 0.0;
            be->nrm[2 * k + 1] = L > 0.0 ? -dx / L : 0.0;
            len += L;
            const int vv[2] = {a, b};
            for (int q = 0; q < 2; q++) {
                xmin = fmin(xmin, m->xy[2 * vv[q]]);
                xmax = fmax(xmax, m->xy[2 * vv[q]]);
                ymin = fmin(ymin, m->xy[2 * vv[q] + 1]);
                ymax = fmax(ymax, m->xy[2 * vv[q] + 1]);
            }
            k++;
        }
    }
    /* cell size: the mean boundary edge, raised so there are at most ~4 cells per edge */
    const double w = xmax - xmin, hgt = ymax - ymin;
    double cs = n > 0 ? len / n : 1.0;
    const double cmin = sqrt(w * hgt / (4.0 * n + 1.0));
    if (cs < cmin) cs = cmin;
    cs = fmax(cs, fmax(w, hgt) / 65000.0); /* at most 65001 cells a side */
    if (!(cs > 0.0)) cs = fmax(fmax(w, hgt), 1e-300);
    be->x0 = xmin - 1e-9 * cs;
    be->y0 = ymin - 1e-9 * cs;
    be->cs = cs;
    be->nx = (int)floor(w / cs) + 1;
    be->ny = (int)floor(hgt / cs) + 1;
    const size_t nc = (size_t)be->nx * be->ny;
    GLPGP_CHECK(glpgp_calloc(nc + 1, sizeof(int), &be->start));
    /* two passes over the cells each edge's bounding box covers: count, fill */
    for (int pass = 0; pass < 2; pass++) {
        for (int e = 0; e < n; e++) {
            const int a = be->v[2 * e], b = be->v[2 * e + 1];
            const int ix0 = clampi((int)floor((fmin(m->xy[2 * a], m->xy[2 * b]) - be->x0) / cs), 0, be->nx - 1);
            const int ix1 = clampi((int)floor((fmax(m->xy[2 * a], m->xy[2 * b]) - be->x0) / cs), 0, be->nx - 1);
            const int iy0 = clampi((int)floor((fmin(m->xy[2 * a + 1], m->xy[2 * b + 1]) - be->y0) / cs), 0, be->ny - 1);
            const int iy1 = clampi((int)floor((fmax(m->xy[2 * a + 1], m->xy[2 * b + 1]) - be->y0) / cs), 0, be->ny - 1);
            for (int iy = iy0; iy <= iy1; iy++)
                for (int ix = ix0; ix <= ix1; ix++) {
                    const size_t c = (size_t)iy * be->nx + ix;
                    if (pass == 0) be->start[c + 1]++;
                    else be->item[be->start[c]++] = e;
                }
        }
        if (pass == 0) {
            for (size_t c = 0; c < nc; c++) be->start[c + 1] += be->start[c];
            GLPGP_CHECK(glpgp_malloc((size_t)be->start[nc] + 1, sizeof(int), &be->item));
        } else {
            /* start[c] now holds the end of cell c: shift back */
            for (size_t c = nc; c > 0; c--) be->start[c] = be->start[c - 1];
            be->start[0] = 0;
        }
    }
    return GLPGP_OK;
}

/* Length of boundary loop l. */
static double loop_perimeter(const glpgp_mesh *m, int l)
{
    const int s = m->loop_start[l], e = m->loop_start[l + 1];
    double per = 0.0;
    for (int p = s; p < e; p++) {
        const int a = m->loop_vertices[p], b = m->loop_vertices[p + 1 < e ? p + 1 : s];
        per += hypot(m->xy[2 * b] - m->xy[2 * a], m->xy[2 * b + 1] - m->xy[2 * a + 1]);
    }
    return per;
}

/* Ray p + t d (d unit) against boundary edge e: t of the crossing, or +inf.
 * The segment is a + s (b - a), s in [0, 1]:  t d - s (b - a) = a - p. */
static double ray_edge(const glpgp_mesh *m, const bedges *be, int e, double px, double py, double dx, double dy)
{
    const double *A = m->xy + 2 * be->v[2 * e], *B = m->xy + 2 * be->v[2 * e + 1];
    const double ex = B[0] - A[0], ey = B[1] - A[1];
    const double den = dx * ey - dy * ex; /* cross(d, b - a) */
    if (fabs(den) <= 1e-12 * hypot(ex, ey)) return HUGE_VAL; /* parallel: its neighbours are hit */
    const double wx = A[0] - px, wy = A[1] - py;
    const double t = (wx * ey - wy * ex) / den; /* cross(w, b - a) / cross(d, b - a) */
    const double s = (wx * dy - wy * dx) / den; /* cross(w, d) / cross(d, b - a) */
    if (s < -1e-9 || s > 1.0 + 1e-9) return HUGE_VAL;
    return t;
}

/* Distance from p along d (unit) to the first boundary edge other than
 * `self` with t in (tmin, tmax]; +inf when none. Walks the grid cells the
 * ray crosses (Amanatides-Woo) and stops once the best hit lies before the
 * current cell's exit. */
static double ray_cast(const glpgp_mesh *m, const bedges *be, int self, double px, double py, double dx, double dy,
                       double tmin, double tmax)
{
    const double cs = be->cs;
    int ix = clampi((int)floor((px - be->x0) / cs), 0, be->nx - 1);
    int iy = clampi((int)floor((py - be->y0) / cs), 0, be->ny - 1);
    const int sx = dx > 0.0 ? 1 : (dx < 0.0 ? -1 : 0), sy = dy > 0.0 ? 1 : (dy < 0.0 ? -1 : 0);
    double tx = sx > 0 ? (be->x0 + (ix + 1) * cs - px) / dx : sx < 0 ? (be->x0 + ix * cs - px) / dx : HUGE_VAL;
    double ty = sy > 0 ? (be->y0 + (iy + 1) * cs - py) / dy : sy < 0 ? (be->y0 + iy * cs - py) / dy : HUGE_VAL;
    const double ddx = sx ? cs / fabs(dx) : HUGE_VAL, ddy = sy ? cs / fabs(dy) : HUGE_VAL;
    double best = HUGE_VAL;
    for (;;) {
        const size_t c = (size_t)iy * be->nx + ix;
        for (int k = be->start[c]; k < be->start[c + 1]; k++) {
            const int e = be->item[k];
            if (e == self || (be->small && be->small[e])) continue;
            const double t = ray_edge(m, be, e, px, py, dx, dy);
            if (t > tmin && t < best) best = t;
        }
        const double texit = fmin(tx, ty);
        if (best <= texit || texit > tmax) break;
        if (tx < ty) {
            ix += sx;
            tx += ddx;
        } else {
            iy += sy;
            ty += ddy;
        }
        if (ix < 0 || iy < 0 || ix >= be->nx || iy >= be->ny) break;
    }
    return best <= tmax ? best : HUGE_VAL;
}

/* ---- gradation ------------------------------------------------------------- */

/* Vertex adjacency of the mesh (CSR, an interior edge listed from both of its
 * triangles: duplicates are harmless for Dijkstra). */
static glpgp_status vertex_graph(const glpgp_mesh *m, int **pptr, int **padj)
{
    int *ptr = NULL, *adj = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)m->nv + 1, sizeof(int), &ptr));
    for (int t = 0; t < m->nt; t++)
        for (int a = 0; a < 3; a++) ptr[m->tri[3 * t + a] + 1] += 2;
    for (int i = 0; i < m->nv; i++) ptr[i + 1] += ptr[i];
    glpgp_status st = glpgp_malloc((size_t)ptr[m->nv] + 1, sizeof(int), &adj);
    if (st != GLPGP_OK) {
        free(ptr);
        GLPGP_CHECK(st);
    }
    for (int t = 0; t < m->nt; t++)
        for (int a = 0; a < 3; a++) {
            const int i = m->tri[3 * t + a];
            adj[ptr[i]++] = m->tri[3 * t + (a + 1) % 3];
            adj[ptr[i]++] = m->tri[3 * t + (a + 2) % 3];
        }
    for (int i = m->nv; i > 0; i--) ptr[i] = ptr[i - 1];
    ptr[0] = 0;
    *pptr = ptr;
    *padj = adj;
    return GLPGP_OK;
}

/* s <- min(s_i, min_j s_j + g |x_i - x_j| along mesh paths) (Dijkstra, lazy heap).
 * slope (nv, may be NULL: g everywhere): per-source slopes instead, each
 * value carried on with the slope of the vertex it came from,
 *   s_j <- min(s_j, s_i + slope_i |x_i - x_j|),  slope_j <- slope_i when it wins;
 * with unequal slopes this is the label-setting approximation of
 * min_j (s_j + slope_j d(i, j)), and s_j <= s_i + slope_i |x_i - x_j| holds on
 * every mesh edge when it returns. */
static glpgp_status grade(const glpgp_mesh *m, const int *ptr, const int *adj, double g, double *s, double *slope)
{
    /* at most one push per vertex and one per adjacency entry: never grows */
    glpgp_heap heap = {NULL, 0, 0};
    GLPGP_CHECK(glpgp_heap_reserve(&heap, (size_t)m->nv + (size_t)ptr[m->nv] + 1));
    /* one slope: a vertex at the largest size lowers no neighbour (s_i + g |e|
     * > s_max >= s_j), so only the others start in the heap (a uniform
     * field: none); the result, the graph distances, is the same in any
     * order. Per-source slopes: every vertex (ties decide the slopes) */
    double smax = HUGE_VAL;
    if (!slope) {
        smax = -HUGE_VAL;
        for (int i = 0; i < m->nv; i++) smax = fmax(smax, s[i]);
    }
    for (int i = 0; i < m->nv; i++)
        if (slope || s[i] < smax) (void)glpgp_heap_push(&heap, s[i], i);
    for (long pops = 0; heap.n > 0; pops++) {
        if ((pops & 65535) == 0) glpgp_progress_poll();
        const glpgp_heap_item it = glpgp_heap_pop(&heap);
        const int i = it.id;
        if (it.key > s[i]) continue; /* stale entry */
        const double gi = slope ? slope[i] : g;
        for (int k = ptr[i]; k < ptr[i + 1]; k++) {
            const int j = adj[k];
            /* s_j <- min(s_j, s_i + g_i |x_i - x_j|) */
            const double c = s[i] + gi * hypot(m->xy[2 * j] - m->xy[2 * i], m->xy[2 * j + 1] - m->xy[2 * i + 1]);
            if (c < s[j]) {
                s[j] = c;
                if (slope) slope[j] = gi;
                (void)glpgp_heap_push(&heap, c, j);
            }
        }
    }
    glpgp_heap_free(&heap);
    return GLPGP_OK;
}

/* ---- boundary curvature and the chord budget -------------------------------- */

/* A domain corner (turn > GLPGP_CORNER_DEG, glpgp/mesh.h: the extraction's and
 * the quality check's) is kept as a mesh vertex, so its turn is no curvature. */

/* The smallest cap c (h <= c R): 100 chords per full turn, which cut
 * c^2 R / 12 per unit of arc, c^2 / 6 ~ 0.07% of a whole circle's area;
 * where the budget asks for less the sizes stop there. */
#define CHORD_C_MIN 0.0625

/* Arcs whose chord turns at most this (h |kappa| <= 1/2: R >= 2 h, at least
 * 4 pi chords per turn, sagitta <= h / 16, a quarter of the check's
 * Hausdorff h / 4) follow the local size closely enough for their error to
 * be netted against the other side's. Fewer chords per turn are not: the
 * annulus of data/ (hole R = 1.2 h, turn 0.83) is predicted to gain 1.03%
 * at the hole and lose 1.02% outside, but its uncapped quads put as many
 * chords on the hole as on the outer circle and lose 1.2% net. Measured
 * window: the motor lamination's bore (R = 2.2 h, 0.45) must be netted,
 * that hole must not (bench/results/chord.md). */
#define CHORD_NET_TURN 0.5

/* The model under-predicts the real chord error: the disk at its default
 * size loses 1.15% where 0.80% is predicted (the extraction's boundary chords
 * are uneven). */
#define CHORD_UNDER 1.4

/* Area between an arc of radius R = 1 / kappa and its chord of length h,
 * per unit of arc length: the chord spans theta = 2 asin(h / 2R) (h >= 2R:
 * theta = pi, the whole arc), the segment's area is R^2 (theta - sin theta) / 2
 * over an arc of R theta:
 *   a(h, kappa) = R (theta - sin theta) / (2 theta)  ~  h^2 kappa / 12  (h << R),
 * bounded by R / 2 (a circle of radius R chorded away entirely: pi R^2). */
static double chord_area_rate(double h, double kappa)
{
    if (!(kappa > 0.0)) return 0.0;
    const double th = 2.0 * asin(fmin(1.0, 0.5 * h * kappa));
    /* (theta - sin theta) / theta = theta^2 / 6 - theta^4 / 120 + ...: the series where it cancels */
    const double q = th < 1e-3 ? th * th / 6.0 * (1.0 - th * th / 20.0) : (th - sin(th)) / th;
    return 0.5 * q / kappa;
}

/* Largest chord whose sagitta on an arc of radius R is at most d:
 *   s(h) = R - sqrt(R^2 - h^2 / 4) <= d  <=>  h <= 2 sqrt(2 R d - d^2);
 * +inf when d >= R (no chord of the arc is deeper than R). */
static double chord_max_for_depth(double R, double d)
{
    return d < R ? 2.0 * sqrt(d * (2.0 * R - d)) : HUGE_VAL;
}

/* Last index p of the increasing a[0 .. n) (a[0] = 0) with a[p] <= r, r >= 0. */
static int arc_index(const double *a, int n, double r)
{
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        const int mid = (lo + hi + 1) / 2;
        if (a[mid] <= r) lo = mid;
        else hi = mid - 1;
    }
    return lo;
}

/* Signed curvature kappa_i of every boundary vertex (0 elsewhere): the
 * boundary's turning angle over an arc window of length hb_i centered at i
 * (the whole loop when that is shorter) over the window's length,
 *   kappa_i = (sum_{p in window} tau_p) / |window|,
 * tau_p the signed turn at boundary vertex p (> 0: a left turn, a convex part
 * of the domain, which lies on the left), 0 at corners (|tau_p| >
 * GLPGP_CORNER_DEG). Per loop, with arc positions a_p and T(s) = sum of
 * tau_p over a_p <= s extended periodically (T(s + P) = T(s) + T_loop, P the
 * loop's length), the window sum is T(a_i + hb_i / 2) - T(a_i - hb_i / 2):
 * O(log n) per vertex whatever the window holds. Features smaller than a
 * quad (|kappa_i| hb_i > 2: R_i < hb_i / 2, a small hole, a slot end) and
 * every vertex whose window reaches one get kappa_i = 0: no chord of the size
 * follows them, and their turn would show as a false curvature of the
 * boundary next to them (they are left to the repair, as the gaps of step 1). */
static glpgp_status boundary_curvature(const glpgp_mesh *m, const double *hb, double *kappa)
{
    const int nb = m->loop_start[m->nloops];
    double *pos = NULL, *cum = NULL;
    unsigned char *small = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)nb + 1, sizeof(double), &pos));
    glpgp_status st = glpgp_malloc((size_t)nb + 1, sizeof(double), &cum);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nb + 1, 1, &small);
    if (st != GLPGP_OK) {
        free(pos);
        free(cum);
        GLPGP_CHECK(st);
    }
    const double corner = GLPGP_CORNER_DEG * 3.14159265358979323846 / 180.0;
    memset(kappa, 0, (size_t)m->nv * sizeof(double));
    for (int l = 0; l < m->nloops; l++) {
        const int s = m->loop_start[l], n = m->loop_start[l + 1] - s;
        if (n < 3) continue;
        const int *lv = m->loop_vertices + s;
        double *a = pos + s, *T = cum + s, P = 0.0, Tl = 0.0;
        for (int p = 0; p < n; p++) {
            const double *x0 = m->xy + 2 * lv[(p + n - 1) % n], *x1 = m->xy + 2 * lv[p];
            const double *x2 = m->xy + 2 * lv[(p + 1) % n];
            const double ux = x1[0] - x0[0], uy = x1[1] - x0[1], vx = x2[0] - x1[0], vy = x2[1] - x1[1];
            /* tau_p = angle from (x_p - x_{p-1}) to (x_{p+1} - x_p) */
            double tau = atan2(ux * vy - uy * vx, ux * vx + uy * vy);
            if (fabs(tau) > corner) tau = 0.0;
            a[p] = P;
            Tl += tau;
            T[p] = Tl;
            P += hypot(vx, vy);
        }
        if (!(P > 0.0)) continue;
        for (int p = 0; p < n; p++) {
            const double w = fmin(hb[lv[p]], P);
            if (!(w > 0.0)) continue;
            double Ts[2];
            for (int k = 0; k < 2; k++) {
                /* T(s) = per T_loop + T[index of s - per P] */
                const double lim = a[p] + (k ? 0.5 : -0.5) * w, per = floor(lim / P);
                Ts[k] = per * Tl + T[arc_index(a, n, lim - per * P)];
            }
            /* |turn| under 1e-9: a straight part whose collinear vertices left rounding noise */
            const double turn = Ts[1] - Ts[0];
            kappa[lv[p]] = fabs(turn) > 1e-9 ? turn / w : 0.0;
        }
        /* features smaller than a quad: R_p < hb_p / 2 (|kappa_p| hb_p > 2: no chord of
         * that size follows them); every vertex whose window reaches one is not sized
         * either (its window's turn is mostly the feature's), kappa <- 0. T becomes the
         * count of such vertices at positions <= s, extended periodically the same way */
        int tot = 0;
        for (int p = 0; p < n; p++) {
            tot += fabs(kappa[lv[p]]) * hb[lv[p]] > 2.0;
            T[p] = tot;
        }
        for (int p = 0; p < n && tot > 0; p++) {
            const double w = fmin(hb[lv[p]], P);
            double Cs[2];
            for (int k = 0; k < 2; k++) {
                const double lim = a[p] + (k ? 0.5 : -0.5) * w, per = floor(lim / P);
                Cs[k] = per * tot + T[arc_index(a, n, lim - per * P)];
            }
            /* the count over positions in (lo, hi]; the vertex itself by its own test */
            small[s + p] = Cs[1] - Cs[0] > 0.5 || fabs(kappa[lv[p]]) * hb[lv[p]] > 2.0;
        }
        for (int p = 0; p < n && tot > 0; p++)
            if (small[s + p]) kappa[lv[p]] = 0.0;
    }
    free(pos);
    free(cum);
    free(small);
    return GLPGP_OK;
}

/* The chord length at boundary vertex i under the cap c:
 * h_i(c) = min(hb_i, max(floor_h, c R_i)), R_i = 1 / |kappa_i|. */
static double chord_h(double hb, double kappa, double c, double floor_h)
{
    return kappa != 0.0 ? fmin(hb, fmax(floor_h, c / fabs(kappa))) : hb;
}

/* Predicted chord area error at the caps c[0] (convex parts) and c[1]
 * (concave parts) (HUGE_VAL: none), split by sign:
 *   err[0] = sum_{e: kappa_e > 0} a(h_e, kappa_e) |e|    (convex arcs: the quads miss it),
 *   err[1] = sum_{e: kappa_e < 0} a(h_e, |kappa_e|) |e|  (concave: the quads cover a hole's cap),
 * kappa_e, h_e the means over the edge's ends; net[0], net[1] the same sums
 * over the edges whose chord turns at most CHORD_NET_TURN (h_e |kappa_e|:
 * arcs of many chords per turn, whose error may be netted). */
static void chord_error(const glpgp_mesh *m, const double *hb, const double *kappa, const double c[2],
                        double floor_h, double err[2], double net[2])
{
    err[0] = err[1] = net[0] = net[1] = 0.0;
    for (int l = 0; l < m->nloops; l++) {
        const int s = m->loop_start[l], e = m->loop_start[l + 1];
        for (int p = s; p < e; p++) {
            const int a = m->loop_vertices[p], b = m->loop_vertices[p + 1 < e ? p + 1 : s];
            const double k = 0.5 * (kappa[a] + kappa[b]);
            if (k == 0.0) continue;
            const int sg = k < 0.0;
            const double he = 0.5 * (chord_h(hb[a], kappa[a], c[sg], floor_h) + chord_h(hb[b], kappa[b], c[sg], floor_h));
            const double len = hypot(m->xy[2 * b] - m->xy[2 * a], m->xy[2 * b + 1] - m->xy[2 * a + 1]);
            const double de = len * chord_area_rate(he, fabs(k));
            err[sg] += de;
            if (he * fabs(k) <= CHORD_NET_TURN) net[sg] += de;
        }
    }
}

/* The chord caps of the graded field size (2 nv): the boundary vertices'
 * sizes lowered where the chords of the boundary quads would cut too much
 * area or too deep (see the top, step 5). Returns in *ncap the number of
 * values lowered (0: size unchanged). */
static glpgp_status chord_cap(const glpgp_mesh *m, int **ptr, int **adj, const glpgp_options *o, double h,
                              double *size, int *ncap)
{
    const int nv = m->nv, nb = m->loop_start[m->nloops];
    const double floor_h = o->size_min * h, A = m->area;
    double *hb = NULL, *kappa = NULL, *capv = NULL, *slope = NULL;
    *ncap = 0;
    if (nb == 0 || !(A > 0.0)) return GLPGP_OK;
    GLPGP_CHECK(glpgp_malloc((size_t)nv, sizeof(double), &hb));
    glpgp_status st = glpgp_malloc((size_t)nv, sizeof(double), &kappa);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nv, sizeof(double), &capv);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nv, sizeof(double), &slope);
    if (st != GLPGP_OK) goto done;
    /* hb_i: the chord along the boundary, the larger of the two oscillators' sizes */
    for (int p = 0; p < nb; p++) {
        const int i = m->loop_vertices[p];
        hb[i] = fmax(size[i], size[(size_t)nv + i]);
    }
    st = boundary_curvature(m, hb, kappa);
    if (st != GLPGP_OK) goto done;
    for (int i = 0; i < nv; i++) capv[i] = HUGE_VAL;
    /* area: the check compares the net area. With S = err_s (side s; 0:
     * convex, lost; 1: concave, gained), S_n its part on arcs of many chords
     * per turn (nettable) and O_n the other side's, side s needs capping when
     *   S - O_n > budget                 (the predicted net, netting only what nets),
     *   S - S_n > budget                 (what does not net meets the budget alone), or
     *   CHORD_UNDER S - O_n > 2 budget   (S at the model's measured under-prediction
     *                                     would fail the check's tolerance, 2 budget);
     * a side that needs it is brought to S <= budget (partial caps were
     * measured to break the quads' structure and gain nothing), c_s <- the
     * largest meeting that; a second pass for the other side, whose net may
     * now exceed */
    double c[2] = {HUGE_VAL, HUGE_VAL}, e0[2], err[2], net[2], en[2];
    if (o->size_chord_area > 0.0) {
        const double budget = o->size_chord_area * A;
        chord_error(m, hb, kappa, c, floor_h, err, net);
        e0[0] = err[0];
        e0[1] = err[1];
        for (int pass = 0; pass < 2; pass++)
            for (int sg = 0; sg < 2; sg++) {
                const double S = err[sg], Sn = net[sg], On = net[1 - sg];
                if (c[sg] < HUGE_VAL ||
                    !(S - On > budget || S - Sn > budget || CHORD_UNDER * S - On > 2.0 * budget))
                    continue;
                double chi = 0.0, cc[2] = {c[0], c[1]}, e[2];
                for (int p = 0; p < nb; p++) {
                    const int i = m->loop_vertices[p];
                    if (kappa[i] != 0.0 && (kappa[i] < 0.0) == sg) chi = fmax(chi, hb[i] * fabs(kappa[i]));
                }
                double clo = CHORD_C_MIN;
                cc[sg] = clo;
                chord_error(m, hb, kappa, cc, floor_h, e, en);
                if (e[sg] <= budget && clo < chi) {
                    /* bisection: err(clo) <= budget < err(chi), err non-decreasing in c */
                    for (int it = 0; it < 60 && chi - clo > 1e-6 * chi; it++) {
                        cc[sg] = 0.5 * (clo + chi);
                        chord_error(m, hb, kappa, cc, floor_h, e, en);
                        if (e[sg] <= budget) clo = cc[sg];
                        else chi = cc[sg];
                    }
                }
                c[sg] = clo;
                chord_error(m, hb, kappa, c, floor_h, err, net);
            }
        if (c[0] < HUGE_VAL || c[1] < HUGE_VAL)
            glpgp_log(GLPGP_LOG_DEBUG,
                      "local size: boundary chords would cut %.3g%% / add %.3g%% of the area (budget %.3g%% net): "
                      "sizes capped at %.3g / %.3g x the radius of curvature, predicted %.3g%% / %.3g%%",
                      100.0 * e0[0] / A, 100.0 * e0[1] / A, 100.0 * o->size_chord_area, c[0], c[1],
                      100.0 * err[0] / A, 100.0 * err[1] / A);
    }
    /* caps: h_i(c), and the sagitta s(h_i) <= d = size_chord_depth h */
    const double d = o->size_chord_depth * h;
    for (int p = 0; p < nb; p++) {
        const int i = m->loop_vertices[p];
        if (kappa[i] == 0.0) continue;
        double cap = chord_h(hb[i], kappa[i], c[kappa[i] < 0.0], floor_h);
        if (d > 0.0) cap = fmin(cap, fmax(floor_h, chord_max_for_depth(1.0 / fabs(kappa[i]), d)));
        if (cap < hb[i]) {
            capv[i] = cap;
            (*ncap)++;
        }
    }
    if (*ncap > 0) {
        /* the cap reaches about R into the domain: from c R at the boundary to h at distance R,
         * slope_i = (h - cap_i) / R_i, at most g (the cap field then grades like the rest) */
        for (int i = 0; i < nv; i++) slope[i] = o->size_grading;
        for (int p = 0; p < nb; p++) {
            const int i = m->loop_vertices[p];
            if (capv[i] < HUGE_VAL) slope[i] = fmin(o->size_grading, (h - capv[i]) * fabs(kappa[i]));
        }
        if (!*ptr) st = vertex_graph(m, ptr, adj);
        if (st == GLPGP_OK) st = grade(m, *ptr, *adj, o->size_grading, capv, slope);
        for (int i = 0; i < nv && st == GLPGP_OK; i++)
            for (int k = 0; k < 2; k++)
                if (capv[i] < size[(size_t)k * nv + i]) size[(size_t)k * nv + i] = capv[i];
    }
done:
    free(hb);
    free(kappa);
    free(capv);
    free(slope);
    GLPGP_CHECK(st);
    return GLPGP_OK;
}

/* ---- the size field -------------------------------------------------------- */

/* auto / iso: seeds from the boundary chords, then gradation (see the top). */
static glpgp_status size_feature(const glpgp_mesh *m, const glpgp_options *o, double h, const double *u,
                                 double *size)
{
    const int nv = m->nv;
    glpgp_status st = GLPGP_OK;
    bedges be;
    int *ptr = NULL, *adj = NULL;
    const double N = o->size_across, floor_h = o->size_min * h;
    const int aniso = u && o->size_field != GLPGP_SIZE_ISO;
    for (int i = 0; i < 2 * nv; i++) size[i] = h;
    GLPGP_CHECK(bedges_build(m, &be));
    /* small loops (perimeter < GLPGP_SIZE_SMALL_LOOP h: holes of radius
     * below 0.72 h): the rays of the rest of the boundary pass through them,
     * so a rim or a wall next to a row of small holes is not sized by them
     * (their own edges still seed: a ligament seen from the hole) */
    for (int l = 0; l < m->nloops; l++) {
        if (!(loop_perimeter(m, l) < GLPGP_SIZE_SMALL_LOOP * h)) continue;
        if (!be.small && (st = glpgp_calloc((size_t)be.n + 1, 1, &be.small)) != GLPGP_OK) {
            bedges_free(&be);
            return st;
        }
        /* boundary edge k is loop position k (bedges_build) */
        for (int p = m->loop_start[l]; p < m->loop_start[l + 1]; p++) be.small[p] = 1;
    }
    for (int e = 0; e < be.n; e++) {
        const int a = be.v[2 * e], b = be.v[2 * e + 1];
        const double px = 0.5 * (m->xy[2 * a] + m->xy[2 * b]), py = 0.5 * (m->xy[2 * a + 1] + m->xy[2 * b + 1]);
        const double nx = be.nrm[2 * e], ny = be.nrm[2 * e + 1];
        const double len = hypot(m->xy[2 * b] - m->xy[2 * a], m->xy[2 * b + 1] - m->xy[2 * a + 1]);
        const double tmin = 1e-9 * len, tmax = N * h;
        /* t_e = t_in: the domain's thickness along n_e. The gap outside
         * (t_out: a slot, a crack, a small hole) needs no periods across it
         * -- it is not meshed -- and shrinking the size next to it was
         * measured to cost more repairs, not fewer (bench/results/size_field.md) */
        const double t = ray_cast(m, &be, e, px, py, -nx, -ny, tmin, tmax);
        if (!(t < HUGE_VAL)) continue;
        double c[2] = {1.0, 1.0};
        if (aniso) {
            /* |W.n_e| for W = U (u) and V = U rotated by +90 degrees (v) at the edge */
            double wx = u[2 * a] + u[2 * b], wy = u[2 * a + 1] + u[2 * b + 1], wn = hypot(wx, wy);
            if (wn > 0.0) {
                wx /= wn;
                wy /= wn;
            } else {
                wx = 1.0;
                wy = 0.0;
            }
            c[0] = fabs(wx * nx + wy * ny);
            c[1] = fabs(-wy * nx + wx * ny);
        }
        for (int k = 0; k < 2; k++) {
            /* s_e(W) = t_e / (N |W.n_e|), floored, at most h */
            double s = c[k] > 0.0 ? t / (N * c[k]) : HUGE_VAL;
            if (s < floor_h) s = floor_h;
            if (s < size[k * nv + a]) size[k * nv + a] = s;
            if (s < size[k * nv + b]) size[k * nv + b] = s;
        }
    }
    bedges_free(&be);
    if (o->size_field == GLPGP_SIZE_FUNC) {
        /* the user's field: s_i <- min(s_i, h clamp(f(x_i), size_min, 1)) */
        for (int i = 0; i < nv; i++) {
            double f = o->size_fn(o->size_ctx, m->xy[2 * i], m->xy[2 * i + 1]);
            if (!isfinite(f) || f < o->size_min) f = o->size_min; /* NaN: the finest, never a crash */
            if (f > 1.0) f = 1.0;
            for (int k = 0; k < 2; k++)
                if (f * h < size[(size_t)k * nv + i]) size[(size_t)k * nv + i] = f * h;
        }
    }
    /* the vertex graph (built when first needed): every size still h grades
     * to itself, so a uniform field and a chord cap that caps nothing need none */
    int below = 0;
    for (size_t i = 0; i < (size_t)2 * nv && !below; i++) below = size[i] < h;
    if (below) st = vertex_graph(m, &ptr, &adj);
    for (int k = 0; k < 2 && below && st == GLPGP_OK; k++)
        st = grade(m, ptr, adj, o->size_grading, size + (size_t)k * nv, NULL);
    if (st == GLPGP_OK && (o->size_chord_area > 0.0 || o->size_chord_depth > 0.0)) {
        /* step 5: the chord caps, min(graded, capped): both grow at most g per unit length
         * along mesh edges, so the result does too (no second gradation) */
        int ncap = 0;
        st = chord_cap(m, &ptr, &adj, o, h, size, &ncap);
    }
    free(ptr);
    free(adj);
    GLPGP_CHECK(st);
    return GLPGP_OK;
}

/* Longest line a size file may have. */
#define SIZE_LINE_MAX 4096

/* One size row: "h" or "h_u h_v" (as many numbers as the first row), into
 * size[i] and size[nv + i]. The solver's surface path reads the same format
 * (surface_size.c). */
typedef struct size_rows {
    double *size;
    int nv, cols;
} size_rows;

static glpgp_status size_row(void *ctx, const text_reader *tr, int i, const double *v, int nv)
{
    size_rows *r = ctx;
    if (nv != 1 && nv != 2) return text_error(tr, GLPGP_ERR_FORMAT, 0, "expected one size 'h' or two 'h_u h_v'");
    if (r->cols == 0) r->cols = nv;
    if (nv != r->cols)
        return text_error(tr, GLPGP_ERR_FORMAT, 0, "%d value(s) where the first line had %d", nv, r->cols);
    const double a = v[0], b = nv == 2 ? v[1] : v[0];
    if (!(a > 0.0) || !(b > 0.0)) return text_error(tr, GLPGP_ERR_FORMAT, 0, "sizes must be positive finite numbers");
    r->size[i] = a;
    r->size[r->nv + i] = b;
    return GLPGP_OK;
}

glpgp_status glpgp_size_file_read(const glpgp_mesh *m, const char *path, double *size)
{
    size_rows r = {size, m->nv, 0};
    GLPGP_CHECK(text_read_rows(path, "size", m->nv, 2, SIZE_LINE_MAX, size_row, &r));
    return GLPGP_OK;
}

/* auto / iso on a mesh that cannot resolve them: s_i <- max(s_i, min(h, R l_i))
 * with l_i the longest mesh edge at vertex i and R = size_resolution, so that
 * every triangle keeps q_T >= R (the input is not refined here: glpgp_solve
 * keeps the caller's vertices; glpgp_size_refine refines first). Returns the
 * number of values raised. */
static int size_clamp_to_mesh(const glpgp_mesh *m, double R, double h, double *size)
{
    const int nv = m->nv;
    double *l = NULL;
    int raised = 0;
    if (glpgp_calloc((size_t)nv, sizeof(double), &l) != GLPGP_OK) return -1;
    /* l_i^2 first, one square root per vertex */
    for (int t = 0; t < m->nt; t++)
        for (int a = 0; a < 3; a++) {
            const int i = m->tri[3 * t + a], j = m->tri[3 * t + (a + 1) % 3];
            const double dx = m->xy[2 * j] - m->xy[2 * i], dy = m->xy[2 * j + 1] - m->xy[2 * i + 1];
            const double e = dx * dx + dy * dy;
            if (e > l[i]) l[i] = e;
            if (e > l[j]) l[j] = e;
        }
    for (int i = 0; i < nv; i++) l[i] = sqrt(l[i]);
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < nv; i++) {
            const double lo = fmin(h, R * l[i]);
            if (size[(size_t)k * nv + i] < lo) {
                size[(size_t)k * nv + i] = lo;
                raised++;
            }
        }
    free(l);
    return raised;
}

/* The field of glpgp_size_compute; clamp: auto / iso limited to what m resolves. */
glpgp_status glpgp_size_compute_field(const glpgp_mesh *m, const glpgp_options *o, double h, const double *u,
                                 double *size, int *uniform, int clamp, int *raised)
{
    const int nv = m->nv;
    if (raised) *raised = 0;
    if (!(h > 0.0) || !isfinite(h)) return GLPGP_FAIL(GLPGP_ERR_ARG, "size field: h = %g is not positive", h);
    if (o->size_field == GLPGP_SIZE_FILE) {
        GLPGP_CHECK(glpgp_size_file_read(m, o->size_file, size));
    } else if (o->size_field == GLPGP_SIZE_AUTO || o->size_field == GLPGP_SIZE_ISO ||
               o->size_field == GLPGP_SIZE_FUNC) {
        GLPGP_CHECK(size_feature(m, o, h, u, size));
        if (clamp) {
            const int n = size_clamp_to_mesh(m, o->size_resolution, h, size);
            if (n < 0) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "size field: out of memory");
            if (raised) *raised = n;
        }
    } else {
        for (int i = 0; i < 2 * nv; i++) size[i] = h;
    }
    int uni = 1;
    for (int i = 0; i < 2 * nv && uni; i++) uni = size[i] == h;
    if (uniform) *uniform = uni;
    return GLPGP_OK;
}

glpgp_status glpgp_size_compute(const glpgp_mesh *m, const glpgp_options *o, double h, const double *u,
                                double *size, int *uniform)
{
    glpgp_progress pr;
    glpgp_progress_start(&pr, "size field");
    glpgp_progress_set(&pr, "%d vertices", m->nv);
    glpgp_status st = glpgp_size_compute_field(m, o, h, u, size, uniform, 1, NULL);
    glpgp_progress_done(&pr, "%d vertices", m->nv);
    return st;
}

/* ---- resolution ------------------------------------------------------------- */

/* Local resolution of triangle t: (smallest corner size over both oscillators) / longest edge. */
double glpgp_size_tri_resolution(const glpgp_mesh *m, const double *size, int t, double *lmax)
{
    const int *v = m->tri + 3 * t;
    double L2 = 0.0, s = HUGE_VAL;
    for (int a = 0; a < 3; a++) {
        const int i = v[a], j = v[(a + 1) % 3];
        const double dx = m->xy[2 * j] - m->xy[2 * i], dy = m->xy[2 * j + 1] - m->xy[2 * i + 1];
        L2 = fmax(L2, dx * dx + dy * dy);
        s = fmin(s, fmin(size[i], size[m->nv + i]));
    }
    const double L = sqrt(L2);
    if (lmax) *lmax = L;
    return s / L;
}

glpgp_status glpgp_size_resolution(const glpgp_mesh *m, const double *size, double R, glpgp_size_res *res)
{
    memset(res, 0, sizeof *res);
    res->worst = HUGE_VAL;
    res->tri = -1;
    for (int t = 0; t < m->nt; t++) {
        double L;
        const double q = glpgp_size_tri_resolution(m, size, t, &L);
        if (q < R) res->coarse++;
        if (q < res->worst) {
            const int *v = m->tri + 3 * t;
            res->worst = q;
            res->tri = t;
            res->lmax = L;
            res->x = (m->xy[2 * v[0]] + m->xy[2 * v[1]] + m->xy[2 * v[2]]) / 3.0;
            res->y = (m->xy[2 * v[0] + 1] + m->xy[2 * v[1] + 1] + m->xy[2 * v[2] + 1]) / 3.0;
            res->h = q * L;
        }
    }
    return GLPGP_OK;
}

glpgp_status glpgp_size_check_mesh(const glpgp_mesh *m, const glpgp_options *o, double h)
{
    double *size = NULL;
    glpgp_size_res res;
    glpgp_options oi = *o;
    /* the isotropic sizes: a lower bound of both oscillators' (no guiding field yet) */
    if (oi.size_field == GLPGP_SIZE_AUTO) oi.size_field = GLPGP_SIZE_ISO;
    GLPGP_CHECK(glpgp_malloc((size_t)2 * m->nv, sizeof(double), &size));
    int raised = 0;
    glpgp_status st = glpgp_size_compute_field(m, &oi, h, NULL, size, NULL, 1, &raised);
    if (st == GLPGP_OK) st = glpgp_size_resolution(m, size, o->size_resolution, &res);
    free(size);
    GLPGP_CHECK(st);
    if (raised > 0)
        glpgp_log(GLPGP_LOG_WARNING,
                  "the local size is limited by the mesh at %d vertex value(s): features thinner than the mesh "
                  "resolves (h_local < %g x the longest edge there) keep the coarser size; refine the input there "
                  "(glpgp solve refines it unless --no-refine)",
                  raised, o->size_resolution);
    /* none: today's pipeline on any input (a warning, below); a local size
     * the mesh cannot carry at all is an error */
    if (res.worst < GLPGP_SIZE_MIN_EDGES && o->size_field != GLPGP_SIZE_NONE)
        return GLPGP_FAIL(GLPGP_ERR_MESH,
                          "the mesh is too coarse for the local size: near (%.6g, %.6g) triangle %d has an edge of "
                          "%.3g for h = %.3g there (%.2f edges per period, at least %g needed, %g wanted; %d "
                          "triangles under %g): refine the mesh there (glpgp solve refines it unless --no-refine)",
                          res.x, res.y, res.tri, res.lmax, res.h, res.worst, GLPGP_SIZE_MIN_EDGES,
                          o->size_resolution, res.coarse, o->size_resolution);
    if (res.coarse > 0)
        glpgp_log(GLPGP_LOG_WARNING,
                  "%d triangle(s) are coarser than the local h / %g (P1 needs about 10 vertices per period); "
                  "worst near (%.6g, %.6g): edge %.3g for h = %.3g (%.2f edges per period): refine the mesh "
                  "there, raise --size, or use --energy transport",
                  res.coarse, o->size_resolution, res.x, res.y, res.lmax, res.h, res.worst);
    return GLPGP_OK;
}

void glpgp_size_log(const glpgp_mesh *m, const double *size, double h)
{
    double mn[2] = {HUGE_VAL, HUGE_VAL};
    int below[2] = {0, 0};
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < m->nv; i++) {
            const double s = size[(size_t)k * m->nv + i];
            mn[k] = fmin(mn[k], s);
            below[k] += s < h;
        }
    glpgp_log(GLPGP_LOG_INFO,
              "local size: u min %.4g (h / %.1f), %.1f%% of the vertices below h; v min %.4g (h / %.1f), %.1f%% below",
              mn[0], h / mn[0], 100.0 * below[0] / m->nv, mn[1], h / mn[1], 100.0 * below[1] / m->nv);
}
