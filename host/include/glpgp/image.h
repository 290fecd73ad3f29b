/* glpgp/image.h: pictures and image domains. Layer: image.
 *  - image I/O: the C interface of the OpenImageIO shim (image/oiio_shim.cpp,
 *    the only C++ file, which catches every exception), built as the module
 *    glpgp_oiio.so and loaded on demand (see "Modules" below); without
 *    OpenImageIO the functions fail with GLPGP_ERR_UNSUPPORTED ("built without
 *    OpenImageIO"). Pixel buffers are float, row-major, the top row first,
 *    channels interleaved;
 *  - the software rasteriser of results (image/render.c): the paper's Fig. 4
 *    grid texture and the other --image-kind views, side-by-side figures and a
 *    built-in bitmap font;
 *  - boundary polygons of a thresholded mask image (image/contour.c);
 *  - triangle meshes of polygon domains through the Gmsh C API (the module
 *    glpgp_gmsh.so, image/gmsh_shim.c) and the whole mask image -> mesh
 *    pipeline (image/mask_mesh.c).
 *
 * Modules. OpenImageIO and Gmsh are not linked into programs: the functions
 * that need them dlopen glpgp_oiio.so / glpgp_gmsh.so the first time they are
 * called, so a program that never reads, writes or meshes an image never
 * loads them. The module is searched in $GLPGP_MODULE_DIR when that is set
 * (and only there), else in <executable dir>/../lib/glpgp (the install
 * layout: <prefix>/bin/glpgp, <prefix>/<libdir>/glpgp/), the configured
 * install directory, and the build tree. A module that was built but cannot
 * be found or loaded makes those functions fail with GLPGP_ERR_IO and one
 * line naming the module and the directories searched (or dlopen's reason). */
#ifndef GLPGP_IMAGE_H
#define GLPGP_IMAGE_H

#include "glpgp/io.h" /* GLPGP_DEFAULT_MAX_ELEMENTS */
#include "glpgp/mesh.h"
#include "glpgp/optdesc.h"
#include "glpgp/quads.h"
#include "glpgp/result.h"
#include "glpgp/status.h"
#include "glpgp/util.h" /* glpgp_is_image_path */

#ifdef __cplusplus
extern "C" {
#endif

/* An image in memory: w x h pixels, nc interleaved float channels. */
typedef struct glpgp_image {
    int w, h, nc;
    int alpha;  /* index of the alpha channel, -1 when none */
    float *px;  /* w * h * nc values; integer formats are scaled to [0, 1] */
} glpgp_image;

/* Whether image I/O is available (1) or not (0): this build has OpenImageIO
 * and the module file glpgp_oiio.so is in the search path (or loaded). Loads
 * nothing. */
int glpgp_have_oiio(void);

/* Load the OpenImageIO module now (the image functions do it themselves on
 * first use; this is for checking up front, e.g. before a long computation).
 * GLPGP_OK, or GLPGP_ERR_UNSUPPORTED ("this glpgp was built without
 * OpenImageIO ...") or GLPGP_ERR_IO (module not found: names it and the
 * directories searched; not loadable: its path and dlerror()), recorded. */
glpgp_status glpgp_oiio_load(void);

/* Read the first subimage of any format OpenImageIO reads (PNG, TIFF, EXR,
 * JPEG, PNM, ...), any bit depth and channel count, converted to float.
 * Unreadable or missing file -> GLPGP_ERR_IO; a zero-size image ->
 * GLPGP_ERR_FORMAT; no OpenImageIO -> GLPGP_ERR_UNSUPPORTED. Free the result
 * with glpgp_image_destroy. */
glpgp_status glpgp_image_read(const char *path, glpgp_image **out);

/* Default limit on the pixels (width x height) of an image glpgp reads. */
#define GLPGP_DEFAULT_MAX_PIXELS 100000000LL

/* glpgp_image_read with a limit on width x height (<= 0: the default
 * GLPGP_DEFAULT_MAX_PIXELS), checked on the header before any pixel is read
 * or memory reserved for it: GLPGP_ERR_LIMIT naming the size and the limit.
 * glpgp_image_read applies the default limit. */
glpgp_status glpgp_image_read_limited(const char *path, long long max_pixels, glpgp_image **out);

/* Write im to path; the format follows the extension (.png, .tif/.tiff,
 * .exr, .jpg/.jpeg, .ppm, ... whatever OpenImageIO writes). im->px holds
 * straight (not premultiplied) colour in [0, 1]; nc is 1 (grey), 3 (RGB) or
 * 4 (RGBA, alpha last). 8-bit formats are written as UINT8 (PNG, JPEG,
 * TIFF), EXR as HALF. A format without alpha (JPEG) gets the image composited
 * over white. Atomic: written to "<stem>.tmp.<pid>.<ext>" in the same
 * directory and renamed over path on success; on failure nothing is left and
 * an existing path is untouched (GLPGP_ERR_IO; an unknown extension ->
 * GLPGP_ERR_ARG). */
glpgp_status glpgp_image_write(const char *path, const glpgp_image *im);

/* Whether OpenImageIO can write files with the extension of path (0 without
 * OpenImageIO or its module; loads the module). For validating command lines
 * before a long computation. */
int glpgp_image_path_writable(const char *path);

/* Allocate a w x h x nc image filled with zeros (alpha = nc == 4 ? 3 : -1). */
glpgp_status glpgp_image_create(int w, int h, int nc, glpgp_image **out);
void glpgp_image_destroy(glpgp_image **im);

/* glpgp_is_image_path: glpgp/util.h (core). */


/* ---- user size field from a grey-level image (image/size_image.c) -------- */

/* A size image: the local quad size painted in grey, black = the finest.
 * Read from path (at most max_pixels pixels; <= 0: the default limit),
 * covering the box x0 = box[0], y0 = box[1], x1 = box[2], y1 = box[3] (top row
 * at y1); the luminance v in [0, 1] maps to the size fraction lo + (hi - lo) v
 * (0 < lo <= hi). Errors: the image's (unreadable, too large), an empty box
 * or a bad range (GLPGP_ERR_ARG). */
typedef struct glpgp_size_image glpgp_size_image;
glpgp_status glpgp_size_image_create(const char *path, long long max_pixels, const double box[4], double lo,
                                     double hi, glpgp_size_image **out);
void glpgp_size_image_destroy(glpgp_size_image **s);
void glpgp_size_image_dims(const glpgp_size_image *s, int *w, int *h);
/* The size fraction at (x, y): bilinear between pixel centers, the nearest
 * border sample outside the box. A glpgp_size_fn (glpgp/solve.h) with ctx the
 * glpgp_size_image. */
double glpgp_size_image_eval(void *ctx, double x, double y);

/* ---- rasteriser (image/render.c) ------------------------------------------ */

enum glpgp_image_kind {
    GLPGP_IMAGE_GRID = 0, /* unit grid of (theta_u, theta_v): lines + light cell shading */
    GLPGP_IMAGE_CHECKER,  /* checkerboard, 2 x 2 squares per unit cell (theta is known
                             modulo 1 only, so whole cells cannot alternate) */
    GLPGP_IMAGE_ZABS,     /* heat map of min(|z_u|, |z_v|) (0 black .. >= 1 yellow-white) */
    GLPGP_IMAGE_FIELD,    /* arrows of the guiding field U on a light background */
    GLPGP_IMAGE_THETA,    /* raw colour map: red = theta_u, green = theta_v (mod 1) */
    GLPGP_IMAGE_CROSS     /* the cross field of a --field cross result: short crosses
                             (alpha = arg(w)/4 of the interpolated w, both directions), its
                             singularities as dots (+1/4 red, -1/4 blue, larger for |index|
                             > 1/4); needs a result with a cross field */
};

typedef struct glpgp_render_options {
    int size;          /* pixels on the long side of the picture (default 1024) */
    int kind;          /* GLPGP_IMAGE_* (default GRID) */
    int transparent;   /* background: 0 white (default), 1 transparent */
    double line_width; /* grid line width in pixels (<= 0: max(1, 1.5 size / 1024)) */
    int boundary;      /* draw the domain boundary (default 1) */
    int singular;      /* fill singular triangles (either oscillator) red and mark each
                          with a red dot (they may be smaller than a pixel) (default 1;
                          not used by the zabs kind, where they show as dark spots) */
    int margin;        /* empty pixels around the domain (< 0: size / 64) */
    double azimuth;    /* a surface's picture (glpgp_render3d): the camera's direction, degrees
                          about z from the x axis [35] ... */
    double elevation;  /* ... and above the xy plane, |elevation| <= 90 [25] */
} glpgp_render_options;

void glpgp_render_options_default(glpgp_render_options *o);

/* The user-settable members of glpgp_render_options, one descriptor each
 * (glpgp/optdesc.h; image/render_options.c): --image-size, --image-kind,
 * --background, --line-width (Python: size, kind, background, line_width;
 * group NULL: the command places them). */
const glpgp_optdesc *glpgp_render_option_table(void);

/* Kind from its name ("grid", "checker", "zabs", "field", "theta", "cross"); -1 if unknown. */
int glpgp_image_kind_parse(const char *name);
const char *glpgp_image_kind_name(int kind);

/* Render result r on mesh m: the domain's bounding box scaled to o->size
 * pixels on the long side (plus margins), y up. Per pixel (center sample),
 * the containing triangle's theta_u, theta_v are interpolated linearly after
 * unwrapping relative to its first corner (theta_k = theta_0 + arg(z_k /
 * z_0) / 2 pi); grid lines where theta is an integer are anti-aliased with
 * the screen-space distance |theta - round(theta)| / |grad theta| (pixels).
 * Output: 4-channel straight RGBA image (alpha 0 outside the domain when
 * transparent). */
glpgp_status glpgp_render(const glpgp_mesh *m, const glpgp_result *r, const glpgp_render_options *o,
                          glpgp_image **out);

/* A surface's result (glpgp/surface.h; glpgp_render calls it for a mesh
 * with xyz): an orthographic view from (o->azimuth, o->elevation) fitted to
 * the surface (o->size pixels on the long side), z-buffered, 2 x 2 samples
 * per pixel, shaded (two-sided, creases kept sharp), coloured by o->kind
 * (grid, checker, zabs or theta; the phases of each triangle read through
 * its matching), singular triangles red and the cross field's
 * singularities as dots (+1/4 red, -1/4 blue) where visible, the boundary
 * dark. GLPGP_ERR_ARG for the kinds field and cross. */
glpgp_status glpgp_render3d(const glpgp_mesh *m, const glpgp_result *r, const glpgp_render_options *o,
                            glpgp_image **out);

/* n results on the same mesh side by side (each panel rendered with o), with
 * captions under each: labels[i] on the first line and the singularity
 * counts "U +a -b  V +c -d" on the second. */
glpgp_status glpgp_render_compare(const glpgp_mesh *m, const glpgp_result *const *r,
                                  const char *const *labels, int n, const glpgp_render_options *o,
                                  glpgp_image **out);

/* The paper's Fig. 1 for a --field cross result r on mesh m: three panels
 * side by side, each rendered with o's size and options: the cross field
 * (GLPGP_IMAGE_CROSS: crosses, singularities +1/4 red, -1/4 blue), the GL-PGP
 * grid texture (GLPGP_IMAGE_GRID), and the quad mesh q (edges, interior
 * vertices of valence 3 blue and >= 5 red; q NULL: that panel is left out),
 * with captions (the cross field's singularity counts, the oscillators',
 * the number of faces). GLPGP_ERR_ARG when r has no cross field. */
glpgp_status glpgp_render_figure1(const glpgp_mesh *m, const glpgp_result *r, const glpgp_quadmesh *q,
                                  const glpgp_render_options *o, glpgp_image **out);

/* Picture of a quad mesh (image/render_quads.c), framed like glpgp_render
 * (o's size, margin, line width, background): faces filled by origin
 * (q->face_origin: grid light blue-grey, closing strips blue, the repair's
 * region mesher orange, its fallback violet; NULL: all grid), faces whose
 * smallest corner scaled Jacobian is below sj_low red (dark red when <= 0),
 * other faces grey; the edges; the boundary of the domain dm (may be NULL:
 * the mesh's own boundary edges) thick; irregular vertices as dots
 * (interior: valence 3 blue, 5 red, 6+ dark red; boundary vertices against
 * their ideal valence round(angle / 90 deg) + 1, smaller). caption: a line of
 * counts under the picture (quads by origin, smallest scaled Jacobian, faces
 * below sj_low, irregular vertices). *out: RGBA. GLPGP_ERR_ARG on an empty
 * mesh or a size out of [16, 32768]. */
glpgp_status glpgp_render_quadmesh(const glpgp_quadmesh *q, const glpgp_mesh *dm, const glpgp_render_options *o,
                                   double sj_low, int caption, glpgp_image **out);

/* Picture of a 3D surface's quad mesh (q->xyz; image/render3d_quads.c):
 * the view of glpgp_render3d (o's azimuth, elevation, size, margin, line
 * width, background), z-buffered and shaded, faces by origin (as
 * glpgp_render_quadmesh), those whose scaled Jacobian in their own plane is
 * below sj_low red (dark red <= 0), the edges dark, the irregular interior
 * vertices as dots where visible (valence 3 blue, 5 red, 6+ dark red); with
 * caption a line of counts under it. GLPGP_ERR_ARG on an empty or planar
 * mesh, a size out of [16, 32768] or a bad view. */
glpgp_status glpgp_render3d_quadmesh(const glpgp_quadmesh *q, const glpgp_render_options *o, double sj_low,
                                     int caption, glpgp_image **out);

/* Draw text with the built-in 5x7 font (A-Z, 0-9, + - : . , ( ) / = _ and
 * space; lower case drawn as upper case, other characters as a box), each
 * font pixel a scale x scale block, top-left corner at (x, y), composited
 * over im (nc 3 or 4) with colour rgba. Returns the width drawn in pixels. */
int glpgp_draw_text(glpgp_image *im, int x, int y, int scale, const char *text,
                    const float rgba[4]);

/* ---- mask contours (image/contour.c) --------------------------------------- */

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
    double *size;      /* NULL, or start[n] local mesh sizes (<= 0: the uniform size) */
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
 * pixel-center grid by linear interpolation of v (a binary mask gives
 * midpoints; an anti-aliased one sub-pixel positions); ambiguous saddle cells
 * are resolved by the mean of their four corners. Loops are simplified by
 * glpgp_polygons_simplify (tolerance o->tolerance pixels, so the topology is
 * kept: no two loops cross or come closer than GLPGP_CONTOUR_MIN_DIST
 * pixels). Errors (GLPGP_ERR_ARG with a message for the user): no pixel
 * inside ("empty mask"), every pixel inside, nothing left after dropping
 * specks. */
glpgp_status glpgp_contours(const float *v, int w, int h, const glpgp_contour_options *o,
                            glpgp_polygons **out);

void glpgp_polygons_destroy(glpgp_polygons **p);

/* Read a polygon file in Triangle's .poly format (image/poly.c: vertices
 * "i x y [attributes] [marker]", segments "i a b [marker]", hole points):
 * the segments must form closed, non-crossing loops; holes follow from the
 * nesting of the loops (even-odd), hole points must lie outside the domain
 * so found. The first vertex attribute, when > 0, is the local mesh size
 * (size[]), which grades the Gmsh mesh. Loops come out oriented (outer
 * counter-clockwise, holes clockwise) with areas and parents.
 * GLPGP_ERR_IO (unreadable), GLPGP_ERR_FORMAT (one message with the line). */
glpgp_status glpgp_polygons_read(const char *path, glpgp_polygons **out);

/* The boundary loops of the triangle mesh m as polygons (every boundary
 * vertex a point; nesting and orientation as glpgp_polygons_read gives
 * them, no sizes): what `glpgp mesh INPUT.obj|.msh` remeshes. */
glpgp_status glpgp_polygons_from_mesh(const glpgp_mesh *m, glpgp_polygons **out);

/* Signed area of the closed polygon xy[0 .. 2n) (counter-clockwise > 0),
 * taken about its first point (no cancellation for parts far from the
 * origin); 0 for n < 1. */
double glpgp_polygon_area(const double *xy, int n);

/* Whether path ends in .poly (case-insensitive). */
int glpgp_is_poly_path(const char *path);

/* Douglas-Peucker simplification of one closed polygon in place: keeps the
 * points needed so that every dropped point lies within tol of the kept
 * polyline. *n is updated (it stays >= 3 when it was). Exposed for tests. */
glpgp_status glpgp_simplify_closed(double *xy, int *n, double tol);

/* Smallest distance (in pixels) glpgp_contours keeps between boundary
 * segments that are not neighbours: crossings of the marching squares lie
 * at least 0.01 px from a pixel center, so unsimplified contours are always
 * further apart than this. */
#define GLPGP_CONTOUR_MIN_DIST 1e-3

/* Douglas-Peucker on every loop of p (tolerance tol, p's units) without
 * changing its topology: a loop whose simplified form would cross or come
 * closer than min_dist to any boundary segment, lose its orientation or half
 * its area, or change which loops contain it, is simplified again from its
 * original points with a quarter of its tolerance, down to none. Areas and
 * total_area are updated; start/xy shrink in place. GLPGP_ERR_MESH (as
 * glpgp_polygons_check) when the unsimplified loops already have such a
 * problem. */
glpgp_status glpgp_polygons_simplify(glpgp_polygons *p, double tol, double min_dist);

/* Whether p can be meshed: every loop has >= 3 finite points, no two
 * boundary segments cross or touch, segments that are not neighbours are at
 * least min_dist apart, no zero-length segment or spike narrower than
 * min_dist. GLPGP_ERR_MESH naming the first place ("the boundary crosses
 * itself near (x, y)") and the number of places otherwise. Cost: a sweep
 * over the segments sorted by x (O(n log n) for boundaries whose segments
 * are short compared to the domain). */
glpgp_status glpgp_polygons_check(const glpgp_polygons *p, double min_dist);

/* ---- meshing polygons and masks (image/mask_mesh.c, Gmsh) ------------------ */

typedef struct glpgp_mask_options {
    glpgp_contour_options contour; /* threshold, invert, specks, tolerance, pixel size */
    double mesh_size;  /* Gmsh's target size in physical units (<= 0: default); its
                          meshes have a mean edge of about 0.7 mesh_size */
    double quad_size;  /* the h the mesh is meant for (> 0 when known, e.g. solve --size);
                          the default mesh size is h / 8, with h = quad_size or, when
                          <= 0, the solver's default h = bounding-box diagonal / 20
                          (so mesh size = diagonal / 160) */
    int algorithm;     /* Gmsh Mesh.Algorithm: 6 frontal-Delaunay (default), 5 Delaunay,
                          1 MeshAdapt, 8 frontal-Delaunay for quads is not allowed */
    long max_triangles; /* refuse, before Gmsh runs, a mesh size whose estimated triangle
                           count (GLPGP_MASK_TRIANGLES_PER_AREA area / mesh_size^2)
                           exceeds this (GLPGP_ERR_LIMIT) [GLPGP_DEFAULT_MAX_ELEMENTS] */
    long long max_pixels; /* refuse images with more pixels, read from the header before
                             any pixel is [GLPGP_DEFAULT_MAX_PIXELS] */
    double timeout;    /* seconds the Gmsh process may run (<= 0: the default)
                          [GLPGP_GMSH_DEFAULT_TIMEOUT] */
    int remesh;        /* the CLI's input loading (solve --remesh): a triangle mesh file
                          is meshed again inside its boundary points like a .poly [0] */
} glpgp_mask_options;

/* Triangles Gmsh makes per area / mesh_size^2 once the mesh is fine
 * compared to the domain (measured on a 200 x 200 px disk with a slot:
 * 2.8 to 3.2 at mesh sizes of 0.3 and 1 px with either algorithm; 4.0 to
 * 4.5 at 3 px, where the boundary starts to dominate, on meshes far too
 * small for a limit to matter). */
#define GLPGP_MASK_TRIANGLES_PER_AREA 3.5

void glpgp_mask_options_default(glpgp_mask_options *o);

/* What the pipeline found and did (for the CLI summary). */
typedef struct glpgp_mask_info {
    int width, height;    /* image size in pixels */
    int nouter, nholes;   /* boundary loops kept */
    int boundary_points;  /* polygon vertices handed to Gmsh */
    double polygon_area;  /* area enclosed by the polygons (physical units) */
    double mesh_size;     /* edge length used */
    double seconds_read, seconds_contour, seconds_mesh;
} glpgp_mask_info;

/* Whether meshing is available (1) or not (0): this build has the Gmsh C API
 * and the module file glpgp_gmsh.so is in the search path (or loaded). Loads
 * nothing. */
int glpgp_have_gmsh(void);

/* Load the Gmsh module now; as glpgp_oiio_load ("built without Gmsh",
 * module not found or not loadable). */
glpgp_status glpgp_gmsh_load(void);

/* The default mesh size for polygons p and a quad size h (<= 0: bounding-box
 * diagonal / 20): h / 8. */
double glpgp_mask_default_mesh_size(const glpgp_polygons *p, double quad_size);

/* Mesh the polygons with Gmsh (loads the module; geo kernel: points, lines, one curve loop per
 * polygon, one plane surface per outer loop with its holes; size mesh_size,
 * or p->size[i] at the points that have one (Gmsh interpolates between the
 * boundary points: graded meshes); Mesh.Algorithm algorithm, <= 0 for 6), then
 * build the glpgp mesh with glpgp_mesh_create (validated). The polygons are
 * checked first (glpgp_polygons_check with 1e-10 of their bounding-box
 * diagonal: crossing or touching boundaries are GLPGP_ERR_MESH). Gmsh runs in
 * a forked child process that sends the vertices and triangles back through a
 * pipe, with its stdout/stderr on /dev/null, so that a Gmsh abort (Gmsh 4.8
 * throws inside OpenMP regions, which ends in std::terminate) or crash
 * becomes GLPGP_ERR_MESH ("Gmsh crashed ...") in the caller instead of
 * killing it; every Gmsh error becomes GLPGP_ERR_MESH with Gmsh's last
 * message. */
glpgp_status glpgp_mesh_polygons(const glpgp_polygons *p, double mesh_size, int algorithm,
                                 glpgp_mesh **out);

/* The same with a limit on Gmsh's run time: after timeout seconds the Gmsh
 * process is killed and GLPGP_ERR_LIMIT returned. timeout <= 0 (and
 * glpgp_mesh_polygons) take GLPGP_GMSH_DEFAULT_TIMEOUT: the library never
 * forks a child without a bound. */
#define GLPGP_GMSH_DEFAULT_TIMEOUT 3600.0
glpgp_status glpgp_mesh_polygons_timeout(const glpgp_polygons *p, double mesh_size, int algorithm,
                                         double timeout, glpgp_mesh **out);

/* Read the mask image at path, extract its contours and mesh them (see the
 * option struct for the defaults and limits). A path ending in .poly is read
 * with glpgp_polygons_read instead, one ending in .obj or .msh with
 * glpgp_mesh_read and glpgp_polygons_from_mesh (a remesh of the domain it
 * covers, inside its boundary points) (no OpenImageIO needed; the contour
 * options do not apply; the default mesh size is computed the same way). The
 * Douglas-Peucker tolerance actually used is max(o->contour.tolerance,
 * mesh_size / 20 in pixels): the boundary needs no detail finer than the mesh;
 * the simplification keeps the topology (glpgp_polygons_simplify). Limits
 * (GLPGP_ERR_LIMIT, before the work): image pixels (o->max_pixels), estimated
 * triangles (o->max_triangles, at the finest point size of a .poly file), Gmsh
 * time (o->timeout). info may be NULL. */
glpgp_status glpgp_mask_mesh(const char *path, const glpgp_mask_options *o, glpgp_mesh **out,
                             glpgp_mask_info *info);

#ifdef __cplusplus
}
#endif

#endif
