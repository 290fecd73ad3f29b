/* core/geom2.c: the 2D predicates of glpgp/internal/geom2.h (distance to a
 * segment, proper crossing, point in polygon). */
#include "glpgp/internal/geom2.h"

#include <math.h>
#include <stddef.h>

double glpgp_seg_dist(const double *a, const double *b, const double *p, double *tout)
{
    double dx = b[0] - a[0], dy = b[1] - a[1];
    double l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2 : 0.0;
    t = fmax(0.0, fmin(1.0, t));
    if (tout) *tout = t;
    const double ex = a[0] + t * dx - p[0], ey = a[1] + t * dy - p[1];
    return sqrt(ex * ex + ey * ey);
}

int glpgp_seg_cross(const double *a, const double *b, const double *c, const double *d, double eps)
{
    /* an end point within eps of the other segment: touching, not crossing
     * (this also settles nearly collinear pieces, whose orientation signs
     * are rounding noise) */
    if (glpgp_seg_dist(a, b, c, NULL) <= eps || glpgp_seg_dist(a, b, d, NULL) <= eps ||
        glpgp_seg_dist(c, d, a, NULL) <= eps || glpgp_seg_dist(c, d, b, NULL) <= eps)
        return 0;
    double d1 = glpgp_orient2(a, b, c), d2 = glpgp_orient2(a, b, d), d3 = glpgp_orient2(c, d, a), d4 = glpgp_orient2(c, d, b);
    if (!((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0))) return 0;
    if (!((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 0;
    /* the crossing point must be away from the four end points */
    double t = d3 / (d3 - d4);
    double x = a[0] + t * (b[0] - a[0]), y = a[1] + t * (b[1] - a[1]);
    const double *e[4] = {a, b, c, d};
    for (int i = 0; i < 4; i++)
        if (hypot(x - e[i][0], y - e[i][1]) <= eps) return 0;
    return 1;
}

int glpgp_point_in_poly(const double *xy, const int *v, int n, const double *p, double eps)
{
    int wn = 0;
    for (int i = 0; i < n; i++) {
        const double *a = xy + 2 * v[i], *b = xy + 2 * v[(i + 1) % n];
        if (glpgp_seg_dist(a, b, p, NULL) <= eps) return 0;
        if (a[1] <= p[1]) {
            if (b[1] > p[1] && glpgp_orient2(a, b, p) > 0) wn++;
        } else if (b[1] <= p[1] && glpgp_orient2(a, b, p) < 0) {
            wn--;
        }
    }
    return wn != 0;
}

double glpgp_seg_dist2(const double *a, const double *b, const double *p)
{
    double dx = b[0] - a[0], dy = b[1] - a[1];
    double L2 = dx * dx + dy * dy;
    double t = L2 > 0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / L2 : 0.0;
    if (t < 0) t = 0;
    if (t > 1) t = 1;
    double ex = a[0] + t * dx - p[0], ey = a[1] + t * dy - p[1];
    return ex * ex + ey * ey;
}
