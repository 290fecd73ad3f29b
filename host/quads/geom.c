/* quads/geom.c: polygon geometry shared by the quad code (geom.h): the
 * corner scaled Jacobian of a polygon and the center split of a hexagon. */
#include "geom.h"
#include "glpgp/quads.h"

#include <math.h>
#include <stdlib.h>

double glpgp_poly_min_sj(const double *xy, const int *v, int n)
{
    double m = INFINITY;
    for (int i = 0; i < n; i++) {
        const double *a = xy + 2 * v[i], *b = xy + 2 * v[(i + 1) % n], *c = xy + 2 * v[(i + n - 1) % n];
        double e1x = b[0] - a[0], e1y = b[1] - a[1], e2x = c[0] - a[0], e2y = c[1] - a[1];
        double l = hypot(e1x, e1y) * hypot(e2x, e2y);
        m = fmin(m, l > 0 ? (e1x * e2y - e1y * e2x) / l : -1.0);
    }
    return m;
}

double glpgp_hex_center_split_at(const double *xy, const int *hx, int o, double *xb, double *yb)
{
    double best = -INFINITY;
    double ax = 0, ay = 0, bx = 0, by = 0; /* centroids of the joined / the other corners */
    for (int i = 0; i < 3; i++) {
        ax += xy[2 * hx[(o + 2 * i) % 6]] / 3;
        ay += xy[2 * hx[(o + 2 * i) % 6] + 1] / 3;
        bx += xy[2 * hx[(o + 2 * i + 1) % 6]] / 3;
        by += xy[2 * hx[(o + 2 * i + 1) % 6] + 1] / 3;
    }
    for (int t = 0; t <= 4; t++) {
        double w = 0.25 * t;
        /* local copy: the three corners of each quad, then X */
        double pq[8];
        int id[4] = {0, 1, 2, 3};
        pq[6] = (1 - w) * ax + w * bx;
        pq[7] = (1 - w) * ay + w * by;
        double sj = INFINITY;
        for (int i = 0; i < 3; i++) {
            for (int k = 0; k < 3; k++) {
                pq[2 * k] = xy[2 * hx[(o + 2 * i + k) % 6]];
                pq[2 * k + 1] = xy[2 * hx[(o + 2 * i + k) % 6] + 1];
            }
            sj = fmin(sj, glpgp_poly_min_sj(pq, id, 4));
        }
        if (sj > best) {
            best = sj;
            *xb = pq[6];
            *yb = pq[7];
        }
    }
    return best;
}

double glpgp_hex_center_split(const double *xy, const int *hx, int *o_best, double *xb, double *yb)
{
    double best = -INFINITY;
    for (int o = 0; o < 2; o++) {
        double x = 0.0, y = 0.0, sj = glpgp_hex_center_split_at(xy, hx, o, &x, &y);
        if (sj > best) {
            best = sj;
            *o_best = o;
            *xb = x;
            *yb = y;
        }
    }
    return best;
}

#define QMAXN GLPGP_POLY_SPLIT_MAX

/* best[i][j]: best minimum scaled Jacobian of a split of the sub-polygon
 * p[i], p[i+1], ..., p[j] (closed by the chord j -> i) into quads;
 * choice[i][j] = a * QMAXN + b for its quad (p[i], p[a], p[b], p[j]). */
typedef struct qdp {
    double best[QMAXN][QMAXN];
    int choice[QMAXN][QMAXN];
} qdp;

static double qdp_solve(qdp *D, const double *xy, const int *p, int i, int j)
{
    if (j - i < 3) return INFINITY; /* an edge (j = i + 1): nothing to split */
    if (D->choice[i][j] != -2) return D->best[i][j];
    double best = -INFINITY;
    int ch = -1;
    /* the quad on chord (i, j): (i, a, b, j), with i..a, a..b, b..j of
     * even length (odd vertex count difference) */
    for (int a = i + 1; a < j - 1; a += 2)
        for (int b = a + 1; b < j; b += 2) {
            int q[4] = {p[i], p[a], p[b], p[j]};
            double s = glpgp_poly_min_sj(xy, q, 4);
            if (s <= best) continue;
            s = fmin(s, qdp_solve(D, xy, p, i, a));
            if (s <= best) continue;
            s = fmin(s, qdp_solve(D, xy, p, a, b));
            if (s <= best) continue;
            s = fmin(s, qdp_solve(D, xy, p, b, j));
            if (s > best) {
                best = s;
                ch = a * QMAXN + b;
            }
        }
    D->best[i][j] = best;
    D->choice[i][j] = ch;
    return best;
}

static int qdp_emit(const qdp *D, const int *p, int i, int j, int *out, int w)
{
    if (j - i < 3) return w;
    int a = D->choice[i][j] / QMAXN, b = D->choice[i][j] % QMAXN;
    out[w++] = p[i];
    out[w++] = p[a];
    out[w++] = p[b];
    out[w++] = p[j];
    w = qdp_emit(D, p, i, a, out, w);
    w = qdp_emit(D, p, a, b, out, w);
    return qdp_emit(D, p, b, j, out, w);
}

double glpgp_poly_quad_split(const double *xy, const int *p, int n, int *out, int *nq)
{
    *nq = 0;
    if (n < 4 || n > QMAXN || n % 2) return -INFINITY;
    qdp D; /* 16 x 16 doubles and ints: on the stack */
    /* the chord (0, n-1) is the closing edge p[n-1] -> p[0], which must be a
     * quad side: one DP covers all splits */
    for (int i = 0; i < QMAXN; i++)
        for (int j = 0; j < QMAXN; j++) D.choice[i][j] = -2;
    double best = qdp_solve(&D, xy, p, 0, n - 1);
    if (best > -INFINITY) *nq = qdp_emit(&D, p, 0, n - 1, out, 0) / 4;
    return best;
}

/* Minimum corner scaled Jacobian of face f. */
double glpgp_quadmesh_face_sj(const glpgp_quadmesh *q, int f)
{
    int s = q->face_start[f];
    return glpgp_poly_min_sj(q->xy, q->face_vert + s, q->face_start[f + 1] - s);
}
