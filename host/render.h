/* render.h: software rasteriser of glpgp results into RGBA pictures (the
 * paper's Fig. 4 grid texture and the other --image-kind views), the
 * side-by-side comparison figure, and a tiny built-in bitmap font for the
 * captions. Pure C; writing the picture to a file is image_io.h's job. */
#ifndef GLPGP_RENDER_H
#define GLPGP_RENDER_H

#include "image_io.h"
#include "mesh.h"
#include "solve.h"

enum glpgp_image_kind {
    GLPGP_IMAGE_GRID = 0, /* unit grid of (theta_u, theta_v): lines + light cell shading */
    GLPGP_IMAGE_CHECKER,  /* checkerboard, 2 x 2 squares per unit cell (theta is known
                             modulo 1 only, so whole cells cannot alternate) */
    GLPGP_IMAGE_ZABS,     /* heat map of min(|z_u|, |z_v|) (0 black .. >= 1 yellow-white) */
    GLPGP_IMAGE_FIELD,    /* arrows of the guiding field U on a light background */
    GLPGP_IMAGE_THETA     /* raw colour map: red = theta_u, green = theta_v (mod 1) */
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
} glpgp_render_options;

void glpgp_render_options_default(glpgp_render_options *o);

/* Kind from its name ("grid", "checker", "zabs", "field", "theta"); -1 if unknown. */
int glpgp_image_kind_parse(const char *name);
const char *glpgp_image_kind_name(int kind);

/* Render result r on mesh m: the domain's bounding box scaled to o->size
 * pixels on the long side (plus margins), y up. Per pixel (centre sample),
 * the containing triangle's theta_u, theta_v are interpolated linearly after
 * unwrapping relative to its first corner (theta_k = theta_0 + arg(z_k /
 * z_0) / 2 pi); grid lines where theta is an integer are anti-aliased with
 * the screen-space distance |theta - round(theta)| / |grad theta| (pixels).
 * Output: 4-channel straight RGBA image (alpha 0 outside the domain when
 * transparent). */
glpgp_status glpgp_render(const glpgp_mesh *m, const glpgp_result *r, const glpgp_render_options *o,
                          glpgp_image **out);

/* n results on the same mesh side by side (each panel rendered with o), with
 * captions under each: labels[i] on the first line and the singularity
 * counts "U +a -b  V +c -d" on the second. */
glpgp_status glpgp_render_compare(const glpgp_mesh *m, const glpgp_result *const *r,
                                  const char *const *labels, int n, const glpgp_render_options *o,
                                  glpgp_image **out);

/* Draw text with the built-in 5x7 font (A-Z, 0-9, + - : . , ( ) / = _ and
 * space; lower case drawn as upper case, other characters as a box), each
 * font pixel a scale x scale block, top-left corner at (x, y), composited
 * over im (nc 3 or 4) with colour rgba. Returns the width drawn in pixels. */
int glpgp_draw_text(glpgp_image *im, int x, int y, int scale, const char *text,
                    const float rgba[4]);

#endif
