/* contour.h: boundary polygons of a thresholded mask image: marching squares
 * with sub-pixel interpolation, holes kept, specks dropped, Douglas-Peucker
 * simplification, physical units with the y axis pointing up. The result is
 * the polygon-with-holes set that mask_mesh.h meshes with Gmsh. */
#ifndef GLPGP_CONTOUR_H
#define GLPGP_CONTOUR_H

#include "image_io.h"
#include "status.h"

/* Closed polygons (the last point is not repeated). Loop l has the points
 * xy[2*start[l] .. 2*start[l+1]). Outer loops run counter-clockwise (area > 0),
 * holes clockwise (area < 0), i.e. the domain is on the left. */
typedef struct glpgp_polygons {
    int n;          /* number of loops */
    int *start;     /* n + 1 offsets (in points) */
    double *xy;     /* 2 * start[n] coordinates, physical units */
    double *area;   /* n signed areas, physical units */
    int *parent;    /* n: for a hole the outer loop containing it, -1 for outer loops */
    int nouter, nholes;
    double total_area; /* sum of the signed areas = area of the domain */
} glpgp_polygons;

typedef struct glpgp_contour_options {
    double threshold;  /* a pixel is inside when value >= threshold (default 0.5) */
    int invert;        /* inside when value < threshold instead (default 0) */
    double min_area;   /* loops enclosing less than this many pixels^2 are dropped,
                          holes filled (default 16) */
    double tolerance;  /* Douglas-Peucker tolerance in pixels (default 0.5; 0: none) */
    double pixel_size; /* physical size of one pixel (default 1) */
} glpgp_contour_options;

void glpgp_contour_options_default(glpgp_contour_options *o);

/* Mask values of an image, one float per pixel: the alpha channel when the
 * image has one that is not constant, else the luminance (Rec. 709 weights of
 * R, G, B; the first channel for grey images). *out is malloc'ed (w*h). */
glpgp_status glpgp_mask_values(const glpgp_image *im, float **out);

/* Contours of the region {v >= threshold} (or {v < threshold} with invert)
 * of the w x h mask v (row-major, top row first). Pixel (i, j) (column i, row
 * j from the top) is the sample at x = (i + 1/2) s, y = (h - j - 1/2) s, with
 * s = pixel_size; the image covers [0, w s] x [0, h s]. Outside the image
 * counts as outside the domain, so a region touching the image border is
 * closed half a pixel beyond the border pixels. Crossings are placed on the
 * pixel-centre grid by linear interpolation of v (a binary mask gives
 * midpoints; an anti-aliased one sub-pixel positions); ambiguous saddle cells
 * are resolved by the mean of their four corners. Errors (GLPGP_ERR_ARG with a
 * message for the user): no pixel inside ("empty mask"), every pixel inside,
 * nothing left after dropping specks. */
glpgp_status glpgp_contours(const float *v, int w, int h, const glpgp_contour_options *o,
                            glpgp_polygons **out);

void glpgp_polygons_destroy(glpgp_polygons **p);

/* Douglas-Peucker simplification of one closed polygon in place: keeps the
 * points needed so that every dropped point lies within tol of the kept
 * polyline. *n is updated (it stays >= 3 when it was). Exposed for tests. */
glpgp_status glpgp_simplify_closed(double *xy, int *n, double tol);

#endif
