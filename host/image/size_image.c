/* image/size_image.c: a user size field painted as a grey-level image
 * (glpgp/image.h: glpgp_size_image_*), sampled by the solver through
 * glpgp_options.size_fn (GLPGP_SIZE_FUNC, glpgp/solve.h).
 *
 * Value: the image's luminance v in [0, 1] (glpgp_mask_values without the
 * alpha rule: Rec. 709 weights of R, G, B, the first channel for grey
 * images; values outside [0, 1], e.g. from an EXR, are clamped), mapped to
 * the size fraction lo + (hi - lo) v: black = the finest (lo), white = the
 * largest (hi). Geometry: the image covers the box [x0, x1] x [y0, y1], top
 * row at y1; pixel (i, j) (column i, row j from the top) is the sample at
 * x = x0 + (i + 1/2) dx, y = y1 - (j + 1/2) dy; between samples bilinear,
 * outside the box the nearest border sample. */
#include "glpgp/image.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>

struct glpgp_size_image {
    int w, h;
    float *v;         /* w * h fractions lo + (hi - lo) lum, top row first */
    double box[4];    /* x0, y0, x1, y1 */
};

glpgp_status glpgp_size_image_create(const char *path, long long max_pixels, const double box[4], double lo,
                                     double hi, glpgp_size_image **out)
{
    *out = NULL;
    if (!(box[2] > box[0]) || !(box[3] > box[1]) || !isfinite(box[2] - box[0]) || !isfinite(box[3] - box[1]))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "size image box [%g, %g] x [%g, %g] is empty", box[0], box[2], box[1],
                          box[3]);
    if (!(lo > 0.0) || !(hi >= lo) || !isfinite(hi))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "size image range %g .. %g: need 0 < lo <= hi", lo, hi);
    glpgp_image *im = NULL;
    glpgp_size_image *s = NULL;
    GLPGP_CHECK(glpgp_image_read_limited(path, max_pixels, &im));
    glpgp_status st = glpgp_calloc(1, sizeof *s, &s);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)im->w * im->h, sizeof(float), &s->v);
    if (st != GLPGP_OK) {
        glpgp_image_destroy(&im);
        glpgp_size_image_destroy(&s);
        GLPGP_CHECK(st);
    }
    s->w = im->w;
    s->h = im->h;
    for (int k = 0; k < 4; k++) s->box[k] = box[k];
    const int nc = im->nc, colour = nc >= 3; /* RGB or RGBA; grey (+ alpha) else */
    for (size_t p = 0; p < (size_t)im->w * im->h; p++) {
        const float *px = im->px + p * nc;
        /* luminance: Rec. 709 for colour, the first channel for grey (+ alpha) */
        double lum = colour ? 0.2126 * px[0] + 0.7152 * px[1] + 0.0722 * px[2] : px[0];
        if (!(lum >= 0.0)) lum = 0.0; /* NaN and negatives: black */
        if (lum > 1.0) lum = 1.0;
        s->v[p] = (float)(lo + (hi - lo) * lum);
    }
    glpgp_image_destroy(&im);
    *out = s;
    return GLPGP_OK;
}

void glpgp_size_image_destroy(glpgp_size_image **ps)
{
    if (!ps || !*ps) return;
    free((*ps)->v);
    free(*ps);
    *ps = NULL;
}

void glpgp_size_image_dims(const glpgp_size_image *s, int *w, int *h)
{
    *w = s->w;
    *h = s->h;
}

double glpgp_size_image_eval(void *ctx, double x, double y)
{
    const glpgp_size_image *s = ctx;
    /* continuous pixel coordinates of (x, y): sample centers at integers */
    double u = (x - s->box[0]) / (s->box[2] - s->box[0]) * s->w - 0.5;
    double v = (s->box[3] - y) / (s->box[3] - s->box[1]) * s->h - 0.5;
    if (!(u >= 0.0)) u = 0.0; /* NaN too */
    if (!(v >= 0.0)) v = 0.0;
    if (u > s->w - 1) u = s->w - 1;
    if (v > s->h - 1) v = s->h - 1;
    const int i = (int)u, j = (int)v;
    const int i1 = i + 1 < s->w ? i + 1 : i, j1 = j + 1 < s->h ? j + 1 : j;
    const double a = u - i, b = v - j;
    const float *r0 = s->v + (size_t)j * s->w, *r1 = s->v + (size_t)j1 * s->w;
    /* bilinear: (1-b) ((1-a) v00 + a v10) + b ((1-a) v01 + a v11) */
    return (1.0 - b) * ((1.0 - a) * r0[i] + a * r0[i1]) + b * ((1.0 - a) * r1[i] + a * r1[i1]);
}
