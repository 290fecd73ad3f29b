/* quads/quads_surface.h: the quad layer's surface files (extract_surface.c,
 * check_surface.c, quads_surface.c); their entry points are in
 * glpgp/quads.h. Internal to the quads layer. */
#ifndef GLPGP_QUADS_SURFACE_H
#define GLPGP_QUADS_SURFACE_H

#include "glpgp/quads.h"
#include "glpgp/status.h"

/* Move the points xyz[3 first .. 3 n) to their nearest points on surface m
 * (those within 2 h of it; check_surface.c). */
glpgp_status glpgp_qs_project(const glpgp_mesh *m, double h, double *xyz, int first, int n);

/* Nearest points on the input surface through a grid of cells
 * (check_surface.c): create for surface m at size h with distances capped
 * at cap; nearest: x = the nearest point of m to p within the cap (p
 * itself when none), returns its triangle (-1: none). */
typedef struct glpgp_qs_proj glpgp_qs_proj;
glpgp_status glpgp_qs_proj_create(const glpgp_mesh *m, double h, double cap, glpgp_qs_proj **out);
int glpgp_qs_proj_nearest(const glpgp_qs_proj *P, const double *p, double *x);
void glpgp_qs_proj_destroy(glpgp_qs_proj **P);



/* glpgp_quads_surface_fallback_coarse (17 degrees) with the smallest angle
 * a new triangle may have (degrees; unless one before was smaller). */
glpgp_status glpgp_qs_coarse(const glpgp_mesh *m, double h, double amin_deg, glpgp_quadmesh **out, int *ntri);

#endif
