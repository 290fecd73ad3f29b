/* quads/geom.c: polygon geometry shared by the quad code (geom.h): the
 * corner scaled Jacobian of a polygon and the centre split of a hexagon. */
#include "geom.h"
#include "glpgp/quads.h"

#include <math.h>

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

double glpgp_hex_centre_split_at(const double *xy, const int *hx, int o, double *xb, double *yb)
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

double glpgp_hex_centre_split(const double *xy, const int *hx, int *o_best, double *xb, double *yb)
{
    double best = -INFINITY;
    for (int o = 0; o < 2; o++) {
        double x = 0.0, y = 0.0, sj = glpgp_hex_centre_split_at(xy, hx, o, &x, &y);
        if (sj > best) {
            best = sj;
            *o_best = o;
            *xb = x;
            *yb = y;
        }
    }
    return best;
}

/* Minimum corner scaled Jacobian of face f. */
double glpgp_quad_face_sj(const glpgp_quadmesh *q, int f)
{
    int s = q->face_start[f];
    return glpgp_poly_min_sj(q->xy, q->face_vert + s, q->face_start[f + 1] - s);
}
