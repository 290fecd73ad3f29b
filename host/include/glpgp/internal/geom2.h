/* glpgp/internal/geom2.h: the 2D geometry predicates every layer shares
 * (core/geom2.c): orientation of three points, distance from a point to a
 * segment, proper crossing of two segments, point in polygon. Plain double
 * arithmetic in a fixed order, so a caller in any layer gets the same bits.
 * Internal: not installed. Layer: core. */
#ifndef GLPGP_INTERNAL_GEOM2_H
#define GLPGP_INTERNAL_GEOM2_H

/* Twice the signed area of (a, b, c): > 0 counter-clockwise, < 0 clockwise,
 * 0 collinear. */
static inline double glpgp_orient2(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/* Distance from p to segment ab; *t (may be NULL): parameter of the nearest
 * point (0 at a, 1 at b). */
double glpgp_seg_dist(const double *a, const double *b, const double *p, double *t);

/* The squared distance from p to segment ab (no square root). */
double glpgp_seg_dist2(const double *a, const double *b, const double *p);

/* 1 when the open segments ab and cd cross properly (their intersection is
 * a single point interior to both, farther than eps from the four end
 * points). */
int glpgp_seg_cross(const double *a, const double *b, const double *c, const double *d, double eps);

/* Winding test: 1 when p is inside polygon xy[2 v[i]] (n corners, either
 * orientation) and farther than eps from its sides. */
int glpgp_point_in_poly(const double *xy, const int *v, int n, const double *p, double eps);

#endif
