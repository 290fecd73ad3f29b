/* image/raster.c: compositing, anti-aliased strokes and the options check
 * shared by the pictures (raster.h). */
#include "raster.h"

#include <math.h>
#include <stddef.h>

void glpgp_px_over(float *p, const float c[3], double a)
{
    if (a <= 0) return;
    if (a > 1) a = 1;
    double pa = p[3];
    double oa = a + pa * (1 - a);
    if (oa <= 0) return;
    for (int k = 0; k < 3; k++) p[k] = (float)((c[k] * a + p[k] * pa * (1 - a)) / oa);
    p[3] = (float)oa;
}

void glpgp_cov_stroke(float *cov, int W, int H, double ax, double ay, double bx, double by, double width)
{
    double r = 0.5 * width + 1.0;
    int x0 = (int)floor(fmin(ax, bx) - r), x1 = (int)ceil(fmax(ax, bx) + r);
    int y0 = (int)floor(fmin(ay, by) - r), y1 = (int)ceil(fmax(ay, by) + r);
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > W - 1) x1 = W - 1;
    if (y1 > H - 1) y1 = H - 1;
    double dx = bx - ax, dy = by - ay, L2 = dx * dx + dy * dy;
    for (int j = y0; j <= y1; j++)
        for (int i = x0; i <= x1; i++) {
            double px = i + 0.5, py = j + 0.5;
            double t = L2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / L2 : 0;
            t = t < 0 ? 0 : t > 1 ? 1 : t;
            double ex = ax + t * dx - px, ey = ay + t * dy - py;
            double c = glpgp_clamp01(0.5 * width + 0.5 - sqrt(ex * ex + ey * ey));
            float *q = cov + (size_t)j * (size_t)W + (size_t)i;
            if (c > *q) *q = (float)c;
        }
}

void glpgp_cov_apply(glpgp_image *im, float *cov, const float c[3])
{
    size_t n = (size_t)im->w * (size_t)im->h;
    for (size_t i = 0; i < n; i++)
        if (cov[i] > 0) {
            glpgp_px_over(im->px + 4 * i, c, cov[i]);
            cov[i] = 0;
        }
}

glpgp_status glpgp_render_options_take(const glpgp_render_options *opt, glpgp_render_options *o)
{
    if (opt)
        *o = *opt;
    else
        glpgp_render_options_default(o);
    if (o->size < 16 || o->size > 32768)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "image size %d out of range [16, 32768]", o->size);
    return GLPGP_OK;
}
