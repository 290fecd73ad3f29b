/* quads/vec3.h: the 3D vector steps of the quad layer's surface files
 * (check_surface.c, coarse_surface.c, repair_surface.c): difference, dot
 * and cross products of double[3]. Internal to the quads layer. */
#ifndef GLPGP_QUADS_VEC3_H
#define GLPGP_QUADS_VEC3_H

static inline void sub3(const double *a, const double *b, double *o)
{
    o[0] = a[0] - b[0];
    o[1] = a[1] - b[1];
    o[2] = a[2] - b[2];
}
static inline double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline void cross3(const double *a, const double *b, double *o)
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

#endif
