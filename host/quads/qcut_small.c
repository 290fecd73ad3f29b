/* quads/qcut_small.c: the cut mesher's small loops (qcut.c calls them when a
 * loop has few points or no cut fits): the best split into quads by its
 * diagonals or around a center, the kite at a sharp point, the five-quad
 * ring of a quad with a reflex or flat corner; each emits its quads. */
#include "qcut_impl.h"

#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- small loops ------------------------------------------------------------------ */

glpgp_status glpgp_qc_emit(qc *c, const int *q)
{
    for (int t = 0; t < 4; t++) GLPGP_CHECK(ipush(c->quads, q[t]));
    return GLPGP_OK;
}

/* Quads around a new center (x, y) joined to p[o], p[o+2], ... of the n-gon. */
static glpgp_status emit_center(qc *c, const int *p, int n, int o, double x, double y)
{
    int X = c->xy->n / 2;
    GLPGP_CHECK(dpush(c->xy, x));
    GLPGP_CHECK(dpush(c->xy, y));
    c->stats->points++;
    for (int q = 0; q < n / 2; q++) {
        int f[4] = {p[(o + 2 * q) % n], p[(o + 2 * q + 1) % n], p[(o + 2 * q + 2) % n], X};
        GLPGP_CHECK(glpgp_qc_emit(c, f));
    }
    return GLPGP_OK;
}

/* The best split of the single loop L (n <= GLPGP_POLY_SPLIT_MAX) and its
 * scaled Jacobian (split: qcut_impl.h). */

void glpgp_qc_best_split(const qc *c, const ivec *L, split *s)
{
    s->sj = glpgp_poly_quad_split(c->xy->p, L->p, L->n, s->out, &s->nq);
    s->how = 0;
    double x = 0, y = 0;
    int o = 0;
    if (L->n >= 6 && L->n <= GLPGP_POLY_SPLIT_MAX) {
        /* a center of valence n / 2: taken for an octagon when as good, else
         * only where the diagonals fail */
        double v = glpgp_qc_center_split(c->xy->p, L->p, L->n, &o, &x, &y);
        double margin = L->n == 8 ? -0.05 : L->n == 6 ? 0.05 : fmax(0.1, 0.3 - s->sj);
        if (v > s->sj + margin) *s = (split){v, 1, 0, o, x, y, {0}};
    }
}

glpgp_status glpgp_qc_emit_split(qc *c, const ivec *L, const split *s)
{
    c->stats->pieces++;
    if (s->how == 1) return emit_center(c, L->p, L->n, s->o, s->x, s->y);
    for (int q = 0; q < s->nq; q++) GLPGP_CHECK(glpgp_qc_emit(c, s->out + 4 * q));
    return GLPGP_OK;
}

/* A quad with a reflex or flat corner: five quads around a copy of it
 * shrunk towards a center g: the centroid, or (a dart, whose centroid may
 * see a side from behind) points on the inward bisectors of its corners,
 * where the shrunk copy stays inside. The best of these by the worst
 * corner; 0 when none gives positive corners. */
glpgp_status glpgp_qc_ring_quad(qc *c, const ivec *L, int *done)
{
    *done = 0;
    const int *p = L->p;
    double G[2 * 13], cen[2] = {0, 0};
    int ng = 0;
    for (int t = 0; t < 4; t++) {
        cen[0] += P(c, p[t])[0] / 4;
        cen[1] += P(c, p[t])[1] / 4;
    }
    G[ng++] = cen[0];
    G[ng++] = cen[1];
    for (int t = 0; t < 4; t++) { /* on the bisector of corner t, into the quad (left of its sides) */
        const double *o = P(c, p[t]), *nx = P(c, p[(t + 1) % 4]), *pv = P(c, p[(t + 3) % 4]);
        double ux = nx[0] - o[0], uy = nx[1] - o[1], vx = pv[0] - o[0], vy = pv[1] - o[1];
        double lu = hypot(ux, uy), lv = hypot(vx, vy);
        if (!(lu > 0 && lv > 0)) continue;
        /* direction: the angle from u (to the next) counter-clockwise to v (to the previous), halved */
        double a = atan2(ux * vy - uy * vx, ux * vx + uy * vy);
        if (a < 0) a += 2 * 3.14159265358979323846;
        double b = atan2(uy, ux) + 0.5 * a;
        double lmin = fmin(lu, lv);
        for (int k = 0; k < 3 && ng + 2 <= 26; k++) {
            double d = (0.15 + 0.2 * k) * lmin;
            G[ng++] = o[0] + d * cos(b);
            G[ng++] = o[1] + d * sin(b);
        }
    }
    static const int Q[5][4] = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}, {4, 5, 6, 7}};
    double best = 0.0, bxy[16];
    for (int gi = 0; gi < ng / 2; gi++) {
        const double *g = G + 2 * gi;
        double rm = 0.0;
        for (int t = 0; t < 4; t++) rm += 0.25 * hypot(P(c, p[t])[0] - g[0], P(c, p[t])[1] - g[1]);
        for (int tr = 1; tr <= 8; tr++) {
            /* the corners pulled towards g: a scaled copy (tries 1-4) or all at
             * one distance (5-8: a flat corner of the quad is not copied) */
            double f = 0.2 * ((tr - 1) % 4 + 1), xy[16];
            for (int t = 0; t < 4; t++) {
                xy[2 * t] = P(c, p[t])[0];
                xy[2 * t + 1] = P(c, p[t])[1];
                double dx = xy[2 * t] - g[0], dy = xy[2 * t + 1] - g[1], d = hypot(dx, dy);
                double s = tr <= 4 ? f : (d > 0 ? f * rm / d : 0.0);
                xy[8 + 2 * t] = g[0] + s * dx;
                xy[9 + 2 * t] = g[1] + s * dy;
            }
            double w = INFINITY;
            for (int q = 0; q < 5; q++) w = fmin(w, glpgp_poly_min_sj(xy, Q[q], 4));
            if (w > best + 1e-12) {
                best = w;
                memcpy(bxy, xy, sizeof xy);
                if (gi == 0) break; /* the centroid's first valid copy serves */
            }
        }
        if (gi == 0 && best > 0.0) break;
    }
    if (!(best > 0.0)) return GLPGP_OK;
    int id[8];
    for (int t = 0; t < 4; t++) {
        id[t] = p[t];
        id[4 + t] = c->xy->n / 2;
        GLPGP_CHECK(dpush(c->xy, bxy[8 + 2 * t]));
        GLPGP_CHECK(dpush(c->xy, bxy[9 + 2 * t]));
        c->stats->points++;
    }
    for (int q = 0; q < 5; q++) {
        int fq[4] = {id[Q[q][0]], id[Q[q][1]], id[Q[q][2]], id[Q[q][3]]};
        GLPGP_CHECK(glpgp_qc_emit(c, fq));
    }
    c->stats->pieces++;
    *done = 1;
    return GLPGP_OK;
}

/* Candidate fourth corners X of the kite (tip t, a, X, b): where the normals
 * to the sides at a and b meet (right angles at a and b), and points on the
 * bisector at 0.8, 1 and 1.2 times the mean distance of a and b (when a and
 * b are at different distances from the tip the normals meet far off).
 * Returns how many (at most 4) into X[2 k]. */
static int kite_points(const double *t, const double *a, const double *b, double *X)
{
    int n = 0;
    double da[2] = {a[0] - t[0], a[1] - t[1]}, db[2] = {b[0] - t[0], b[1] - t[1]};
    double na[2] = {-da[1], da[0]}, nb[2] = {db[1], -db[0]}; /* left of t->a, right of t->b */
    double den = na[0] * nb[1] - na[1] * nb[0];
    if (fabs(den) > 1e-300) {
        double u = ((b[0] - a[0]) * nb[1] - (b[1] - a[1]) * nb[0]) / den;
        if (u > 0.0) {
            X[2 * n] = a[0] + u * na[0];
            X[2 * n + 1] = a[1] + u * na[1];
            n++;
        }
    }
    double la = hypot(da[0], da[1]), lb = hypot(db[0], db[1]);
    double bx = da[0] / la + db[0] / lb, by = da[1] / la + db[1] / lb, bl = hypot(bx, by);
    if (!(bl > 1e-12)) return n;
    for (int k = 0; k < 3; k++) {
        double r = (0.8 + 0.2 * k) * 0.5 * (la + lb) / (0.5 * bl); /* past the chord a b */
        X[2 * n] = t[0] + r * bx / bl;
        X[2 * n + 1] = t[1] + r * by / bl;
        n++;
    }
    return n;
}

/* Whether the kite (tip i of L, X at point Xi) can be cut off: convex, X
 * inside, a X and X b crossing nothing, no angle below 20 degrees left at
 * a, X, b. Returns the smallest scaled Jacobian at a, X, b (-1: not). */
static double kite_fit(qc *c, qc_piece *pc, int i, int Xi)
{
    ivec *L = &pc->outer;
    const int n = L->n, it = L->p[i], ia = L->p[(i + 1) % n], ib = L->p[(i + n - 1) % n];
    const double *X = P(c, Xi);
    int f[4] = {it, ia, Xi, ib};
    if (!(glpgp_poly_min_sj(c->xy->p, f, 4) > 0.0)) return -1.0;
    if (!glpgp_point_in_poly(c->xy->p, L->p, n, X, 0.0) || !glpgp_qc_visible(c, pc, ia, Xi) || !glpgp_qc_visible(c, pc, Xi, ib)) return -1.0;
    L->p[i] = Xi;
    int ok = 1;
    for (int d = -1; d <= 1 && ok; d++) ok = glpgp_qc_loop_angle(c, L, (i + d + n) % n) * 180.0 / QC_PI > 20.0;
    L->p[i] = it;
    if (!ok) return -1.0;
    int g[4] = {ia, Xi, ib, it}; /* corners a, X, b (the tip's is sin of its angle whatever X) */
    double m = INFINITY;
    for (int k = 0; k < 3; k++) {
        const double *o = P(c, g[k]), *nx = P(c, g[k + 1]), *pv = P(c, g[(k + 3) % 4]);
        double e1x = nx[0] - o[0], e1y = nx[1] - o[1], e2x = pv[0] - o[0], e2y = pv[1] - o[1];
        m = fmin(m, (e1x * e2y - e1y * e2x) / (hypot(e1x, e1y) * hypot(e2x, e2y)));
    }
    return m;
}

/* A sharp point (angle below SHARP_DEG) of a loop of more than 4 points,
 * with its neighbours a and b, becomes a kite (tip, a, X, b), X the best of
 * kite_points; the loop keeps its count with X in place of the tip.
 * *done: 1 when one was cut (pc then changed). */
#define SHARP_DEG 50.0
glpgp_status glpgp_qc_kite_cut(qc *c, qc_piece *pc, int *done)
{
    *done = 0;
    ivec *L = &pc->outer;
    const int n = L->n;
    if (n <= 4) return GLPGP_OK;
    for (int i = 0; i < n; i++) {
        if (glpgp_qc_loop_angle(c, L, i) * 180.0 / QC_PI >= SHARP_DEG) continue;
        const int it = L->p[i], ia = L->p[(i + 1) % n], ib = L->p[(i + n - 1) % n];
        double X[8], best = 0.05;
        int m = kite_points(P(c, it), P(c, ia), P(c, ib), X), bk = -1, Xi = c->xy->n / 2;
        for (int k = 0; k < m; k++) {
            GLPGP_CHECK(dpush(c->xy, X[2 * k]));
            GLPGP_CHECK(dpush(c->xy, X[2 * k + 1]));
            double v = kite_fit(c, pc, i, Xi);
            c->xy->n -= 2;
            if (v > best) {
                best = v;
                bk = k;
            }
        }
        if (bk < 0) continue;
        GLPGP_CHECK(dpush(c->xy, X[2 * bk]));
        GLPGP_CHECK(dpush(c->xy, X[2 * bk + 1]));
        c->stats->points++;
        int f[4] = {it, ia, Xi, ib};
        GLPGP_CHECK(glpgp_qc_emit(c, f));
        L->p[i] = Xi;
        c->stats->pieces++;
        *done = 1;
        return GLPGP_OK;
    }
    return GLPGP_OK;
}
