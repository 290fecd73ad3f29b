/* quads/geom.h: small polygon-geometry helpers shared by the quad-mesh code
 * (extract.c extraction, close.c closing and smoothing, repair.c repair,
 * quality.c report). Internal to the library; defined in geom.c. */
#ifndef GLPGP_QUADS_GEOM_H
#define GLPGP_QUADS_GEOM_H

/* Smallest corner "scaled Jacobian" of the polygon xy[2 v[0]], ...,
 * xy[2 v[n-1]] (counter-clockwise): the minimum over the corners of the sine
 * of the angle between the two sides (1 for a rectangle; <= 0 at a flat or
 * reflex corner; -1 at a zero-length side). */
double glpgp_poly_min_sj(const double *xy, const int *v, int n);

/* Best split of the hexagon with corners hx[0..5] (indices into xy,
 * counter-clockwise) into three quads around a new center X joined to every
 * other corner (hx[o], hx[o+2], hx[o+4], o = 0 or 1): the quads are
 * (hx[o+2i], hx[o+2i+1], hx[o+2i+2], X). X is taken among five blends of
 * the centroids of the joined and of the other corners. Returns the
 * smallest corner scaled Jacobian of the three quads and sets *o, *x, *y. */
double glpgp_hex_center_split(const double *xy, const int *hx, int *o, double *x, double *y);

/* The same with the orientation o (0 or 1) given: X joined to hx[o],
 * hx[o+2], hx[o+4]. Returns the smallest corner scaled Jacobian and sets
 * *x, *y. */
double glpgp_hex_center_split_at(const double *xy, const int *hx, int o, double *x, double *y);

/* Largest polygon glpgp_poly_quad_split takes. */
#define GLPGP_POLY_SPLIT_MAX 16

/* Best split of the even polygon xy[2 p[0]], ..., xy[2 p[n-1]] (4 <= n <=
 * GLPGP_POLY_SPLIT_MAX, counter-clockwise) into quads by its diagonals
 * alone: the split whose smallest corner scaled Jacobian is largest
 * (dynamic programme over the sub-polygons). out: 4 * *nq corner ids
 * ((n - 2) / 2 quads). Returns that scaled Jacobian; -inf (and *nq = 0)
 * for an odd n or one out of range. */
double glpgp_poly_quad_split(const double *xy, const int *p, int n, int *out, int *nq);

#endif
