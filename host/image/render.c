/* image/render.c: the rasteriser of glpgp/image.h. One pass over the triangles fills
 * every pixel whose center lies in a triangle with the colour of the chosen
 * kind (theta unwrapped per triangle, analytic anti-aliasing of the grid
 * lines from the per-triangle gradient in pixels); then overlays: field
 * arrows, the boundary (anti-aliased strokes through a coverage buffer, so
 * joints are not drawn twice), captions with a 5x7 bitmap font. */
#include "raster.h"
#include "render3d_impl.h"

#include "glpgp/image.h"
#include "glpgp/cross.h"
#include "glpgp/kinds.h"
#include "glpgp/phase.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


void glpgp_render_options_default(glpgp_render_options *o)
{
    o->size = 1024;
    o->kind = GLPGP_IMAGE_GRID;
    o->transparent = 0;
    o->line_width = 0;
    o->boundary = 1;
    o->singular = 1;
    o->margin = -1;
    o->azimuth = 35.0;
    o->elevation = 25.0;
}

static const char *const kind_names[] = {"grid", "checker", "zabs", "field", "theta", "cross", NULL};

int glpgp_image_kind_parse(const char *name)
{
    for (int k = 0; name && kind_names[k]; k++)
        if (!strcmp(name, kind_names[k])) return k;
    return -1;
}

const char *glpgp_image_kind_name(int kind)
{
    return kind >= 0 && kind <= GLPGP_IMAGE_CROSS ? kind_names[kind] : "?";
}

/* ---- small helpers ------------------------------------------------------- */

/* Coverage of a grid line at theta t with gradient magnitude g (per pixel). */
static double line_cov(double t, double g, double lw)
{
    if (!(g > 1e-12)) return 0;
    double d = fabs(t - floor(t + 0.5)) / g;
    double c = glpgp_clamp01(0.5 * lw + 0.5 - d);
    double mean = glpgp_clamp01(lw * g); /* lines closer than a few pixels: average */
    double blend = glpgp_clamp01((g * (2 * lw + 2) - 0.5) * 2);
    return c * (1 - blend) + mean * blend;
}

/* magma-like colour map on [0, 1] */
static void heat(double x, float c[3])
{
    static const double st[6][3] = {{0.00, 0.00, 0.02}, {0.23, 0.06, 0.43}, {0.55, 0.16, 0.51},
                                    {0.87, 0.30, 0.38}, {0.99, 0.64, 0.36}, {0.99, 0.99, 0.75}};
    x = glpgp_clamp01(x) * 5;
    int k = (int)x;
    if (k > 4) k = 4;
    double f = x - k;
    for (int q = 0; q < 3; q++) c[q] = (float)(st[k][q] * (1 - f) + st[k + 1][q] * f);
}

/* ---- main render ------------------------------------------------------------- */

/* A planar picture in the making: the image, a coverage buffer for the
 * strokes, the interpolated field (FIELD, CROSS kinds), the pixel map. */
typedef struct canvas {
    glpgp_render_options o;
    glpgp_image *im;
    float *cov, *fld;
    int W, H;
    double ox, oy, scale; /* pixel (0,0) corner; pixels per unit */
    double lw;            /* line width in pixels */
} canvas;

static const float col_u[3] = {0.10f, 0.22f, 0.60f}, col_v[3] = {0.60f, 0.18f, 0.10f};
static const float col_red[3] = {0.90f, 0.05f, 0.05f};

/* The picture's size from the mesh's box, the image and its buffers. */
static glpgp_status canvas_create(const glpgp_mesh *m, canvas *cv)
{
    const glpgp_render_options *o = &cv->o;
    cv->lw = o->line_width > 0 ? o->line_width : fmax(1.0, 1.5 * o->size / 1024.0);
    const int margin = o->margin >= 0 ? o->margin : o->size / 64;
    const double bw = m->bbox[2] - m->bbox[0], bh = m->bbox[3] - m->bbox[1];
    const double span = fmax(bw, bh);
    if (!(span > 0)) return GLPGP_FAIL(GLPGP_ERR_ARG, "render: degenerate bounding box");
    int inner = o->size - 2 * margin;
    if (inner < 8) inner = 8;
    cv->scale = inner / span;
    cv->W = (int)ceil(bw * cv->scale - 1e-9) + 2 * margin;
    cv->H = (int)ceil(bh * cv->scale - 1e-9) + 2 * margin;
    if (cv->W < 1) cv->W = 1;
    if (cv->H < 1) cv->H = 1;
    cv->ox = m->bbox[0] - margin / cv->scale;
    cv->oy = m->bbox[3] + margin / cv->scale;
    const size_t np = (size_t)cv->W * (size_t)cv->H;
    GLPGP_CHECK(glpgp_image_create(cv->W, cv->H, 4, &cv->im));
    GLPGP_CHECK(glpgp_calloc(np, sizeof(float), &cv->cov));
    if (o->kind == GLPGP_IMAGE_FIELD || o->kind == GLPGP_IMAGE_CROSS) {
        GLPGP_CHECK(glpgp_malloc(2 * np, sizeof(float), &cv->fld));
        for (size_t i = 0; i < 2 * np; i++) cv->fld[i] = NAN;
    }
    if (!o->transparent)
        for (size_t i = 0; i < np; i++)
            cv->im->px[4 * i] = cv->im->px[4 * i + 1] = cv->im->px[4 * i + 2] = cv->im->px[4 * i + 3] = 1.0f;
    return GLPGP_OK;
}

static void canvas_free(canvas *cv)
{
    free(cv->cov);
    free(cv->fld);
    cv->cov = cv->fld = NULL;
    glpgp_image_destroy(&cv->im);
}

/* One triangle's values for its pixels: the unwrapped phases and |z| at its
 * corners, the phase gradients' lengths in pixels, its corner indices. */
typedef struct tri_vals {
    const int *tv;
    double th[2][3], za[2][3];
    double gnu, gnv;
} tri_vals;

/* The colour of one pixel at barycentrics (l0, l1, l2) of triangle T
 * (pixel index pi for the field buffers). */
static void pixel_colour(const canvas *cv, const glpgp_result *r, const tri_vals *T, double l0, double l1, double l2,
                         size_t pi, float c[3])
{
    const int *tv = T->tv;
    const double tu = T->th[0][0] * l0 + T->th[0][1] * l1 + T->th[0][2] * l2;
    const double tvv = T->th[1][0] * l0 + T->th[1][1] * l1 + T->th[1][2] * l2;
    switch (cv->o.kind) {
    case GLPGP_IMAGE_GRID: {
        /* theta is only known modulo 1, so cells cannot be told
         * apart: a light "pillow" shade, brightest at cell centers */
        double fu = tu - floor(tu) - 0.5, fv = tvv - floor(tvv) - 0.5;
        double sh = 1.0 - 0.12 * (fabs(fu) + fabs(fv));
        c[0] = (float)(1.00 * sh);
        c[1] = (float)(0.98 * sh);
        c[2] = (float)(0.93 * sh + 0.05 * (1 - sh));
        break;
    }
    case GLPGP_IMAGE_CHECKER: {
        /* 2 x 2 checker per unit cell (transitions at integer and
         * half-integer theta), anti-aliased over 0.75 px */
        double au = tu - floor(tu), av = tvv - floor(tvv);
        double su = au < 0.5 ? 1 : -1, sv = av < 0.5 ? 1 : -1;
        double du = T->gnu > 1e-12 ? fmin(fmin(au, 1 - au), fabs(au - 0.5)) / T->gnu : 1e9;
        double dv = T->gnv > 1e-12 ? fmin(fmin(av, 1 - av), fabs(av - 0.5)) / T->gnv : 1e9;
        double sg = su * sv * fmin(1.0, fmin(du, dv) / 0.75);
        double g = 0.5 + 0.5 * sg;
        c[0] = (float)(0.15 + 0.80 * g);
        c[1] = (float)(0.18 + 0.78 * g);
        c[2] = (float)(0.25 + 0.72 * g);
        break;
    }
    case GLPGP_IMAGE_ZABS: {
        double a = fmin(T->za[0][0] * l0 + T->za[0][1] * l1 + T->za[0][2] * l2,
                        T->za[1][0] * l0 + T->za[1][1] * l1 + T->za[1][2] * l2);
        heat(a, c);
        break;
    }
    case GLPGP_IMAGE_FIELD:
        c[0] = 0.97f, c[1] = 0.97f, c[2] = 0.95f;
        if (r->field) {
            const double *U = r->field;
            cv->fld[2 * pi] = (float)(U[2 * tv[0]] * l0 + U[2 * tv[1]] * l1 + U[2 * tv[2]] * l2);
            cv->fld[2 * pi + 1] = (float)(U[2 * tv[0] + 1] * l0 + U[2 * tv[1] + 1] * l1 + U[2 * tv[2] + 1] * l2);
        }
        break;
    case GLPGP_IMAGE_CROSS: {
        /* background: |w| (light, darker in the cores); w kept for the crosses */
        const double *w = r->cross->w;
        double wr = w[2 * tv[0]] * l0 + w[2 * tv[1]] * l1 + w[2 * tv[2]] * l2;
        double wi = w[2 * tv[0] + 1] * l0 + w[2 * tv[1] + 1] * l1 + w[2 * tv[2] + 1] * l2;
        double a = glpgp_clamp01(hypot(wr, wi));
        cv->fld[2 * pi] = (float)wr;
        cv->fld[2 * pi + 1] = (float)wi;
        c[0] = (float)(0.80 + 0.17 * a);
        c[1] = (float)(0.80 + 0.17 * a);
        c[2] = (float)(0.78 + 0.17 * a);
        break;
    }
    default: /* THETA */
        c[0] = (float)(tu - floor(tu));
        c[1] = (float)(tvv - floor(tvv));
        c[2] = 0.5f;
        break;
    }
}

/* Triangle t's corner values: phases unwrapped around corner 0 (a coupled
 * solve's read in the triangle's frame), |z|; g the barycentric gradients. */
static void tri_values(const glpgp_mesh *m, const glpgp_result *r, int t, const double g[4], tri_vals *T)
{
    const int *tv = m->tri + 3 * t;
    const double *zu = r->osc[0].z, *zv = r->osc[1].z;
    T->tv = tv;
    for (int q = 0; q < 2; q++) {
        const double *z = q == 0 ? zu : zv;
        double tc[3];
        for (int k = 0; k < 3; k++) {
            double br = z[2 * tv[k]], bi = z[2 * tv[k] + 1];
            if (r->coupled && r->field) { /* coupled solve: the triangle's frame oscillator q */
                double f[2];
                glpgp_coupled_frame_value(glpgp_cross_turn(r->field + 2 * tv[0], r->field + 2 * tv[k]), q,
                                          zu + 2 * tv[k], zv + 2 * tv[k], f);
                br = f[0];
                bi = f[1];
            }
            T->za[q][k] = hypot(br, bi);
            tc[k] = glpgp_theta(br, bi);
        }
        glpgp_phase_chart(tc, T->th[q]); /* unwrapped around corner 0 */
    }
    double gu[2], gv[2];
    gu[0] = (T->th[0][1] - T->th[0][0]) * g[0] + (T->th[0][2] - T->th[0][0]) * g[2];
    gu[1] = (T->th[0][1] - T->th[0][0]) * g[1] + (T->th[0][2] - T->th[0][0]) * g[3];
    gv[0] = (T->th[1][1] - T->th[1][0]) * g[0] + (T->th[1][2] - T->th[1][0]) * g[2];
    gv[1] = (T->th[1][1] - T->th[1][0]) * g[1] + (T->th[1][2] - T->th[1][0]) * g[3];
    T->gnu = hypot(gu[0], gu[1]);
    T->gnv = hypot(gv[0], gv[1]);
}

/* Every pixel whose center lies in triangle t. */
static void raster_triangle(canvas *cv, const glpgp_mesh *m, const glpgp_result *r, int t)
{
    const int *tv = m->tri + 3 * t;
    double P[3][2];
    for (int k = 0; k < 3; k++) {
        P[k][0] = (m->xy[2 * tv[k]] - cv->ox) * cv->scale;
        P[k][1] = (cv->oy - m->xy[2 * tv[k] + 1]) * cv->scale;
    }
    double e1x = P[1][0] - P[0][0], e1y = P[1][1] - P[0][1];
    double e2x = P[2][0] - P[0][0], e2y = P[2][1] - P[0][1];
    double det = e1x * e2y - e2x * e1y;
    if (fabs(det) < 1e-18) return;
    /* barycentric l1, l2 = inv * (p - P0); rows of inv = gradients */
    const double g[4] = {e2y / det, -e2x / det, -e1y / det, e1x / det};
    tri_vals T;
    tri_values(m, r, t, g, &T);
    const int sing = cv->o.kind != GLPGP_IMAGE_CROSS && ((r->osc[0].singular && r->osc[0].singular[t]) ||
                                                         (r->osc[1].singular && r->osc[1].singular[t]));
    int x0 = (int)floor(fmin(P[0][0], fmin(P[1][0], P[2][0]))), x1 = (int)ceil(fmax(P[0][0], fmax(P[1][0], P[2][0])));
    int y0 = (int)floor(fmin(P[0][1], fmin(P[1][1], P[2][1]))), y1 = (int)ceil(fmax(P[0][1], fmax(P[1][1], P[2][1])));
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > cv->W - 1) x1 = cv->W - 1;
    if (y1 > cv->H - 1) y1 = cv->H - 1;
    const double eps = -1e-9;
    for (int j = y0; j <= y1; j++)
        for (int i = x0; i <= x1; i++) {
            double dx = i + 0.5 - P[0][0], dy = j + 0.5 - P[0][1];
            double l1 = g[0] * dx + g[1] * dy, l2 = g[2] * dx + g[3] * dy, l0 = 1 - l1 - l2;
            if (l0 < eps || l1 < eps || l2 < eps) continue;
            const size_t pi = (size_t)j * (size_t)cv->W + (size_t)i;
            float *p = cv->im->px + 4 * pi;
            float c[3];
            pixel_colour(cv, r, &T, l0, l1, l2, pi, c);
            p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 1.0f;
            if (cv->o.kind == GLPGP_IMAGE_GRID) {
                const double tu = T.th[0][0] * l0 + T.th[0][1] * l1 + T.th[0][2] * l2;
                const double tvv = T.th[1][0] * l0 + T.th[1][1] * l1 + T.th[1][2] * l2;
                glpgp_px_over(p, col_v, line_cov(tvv, T.gnv, cv->lw));
                glpgp_px_over(p, col_u, line_cov(tu, T.gnu, cv->lw));
            }
            if (sing && cv->o.singular && cv->o.kind != GLPGP_IMAGE_ZABS) {
                p[0] = col_red[0], p[1] = col_red[1], p[2] = col_red[2];
            }
        }
}

/* CROSS: short crosses on a regular pixel grid (alpha = arg(w)/4 and alpha
 * + 90 degrees), the singularities (+1/4 red, -1/4 blue, radius growing
 * with |index|). */
static void overlay_cross(canvas *cv, const glpgp_result *r)
{
    const int W = cv->W, H = cv->H;
    const double lw = cv->lw;
    int step = cv->o.size / 40 < 8 ? 8 : cv->o.size / 40;
    double len = 0.75 * step;
    for (int j = step / 2; j < H; j += step)
        for (int i = step / 2; i < W; i += step) {
            size_t pi = (size_t)j * (size_t)W + (size_t)i;
            double wr = cv->fld[2 * pi], wi = cv->fld[2 * pi + 1];
            if (isnan(wr) || !(hypot(wr, wi) > 1e-12)) continue;
            double al = atan2(wi, wr) / 4.0;
            double cx = i + 0.5, cy = j + 0.5;
            for (int q = 0; q < 2; q++) {
                double ux = cos(al + q * GLPGP_PI / 2), uy = -sin(al + q * GLPGP_PI / 2); /* y down */
                glpgp_cov_stroke(cv->cov, W, H, cx - 0.5 * len * ux, cy - 0.5 * len * uy, cx + 0.5 * len * ux,
                       cy + 0.5 * len * uy, lw);
            }
        }
    static const float col_cross[3] = {0.10f, 0.20f, 0.45f};
    glpgp_cov_apply(cv->im, cv->cov, col_cross);
    if (!cv->o.singular) return;
    static const float col_pos[3] = {0.90f, 0.05f, 0.05f}, col_neg[3] = {0.05f, 0.35f, 0.95f};
    for (int sgn = 0; sgn < 2; sgn++) {
        for (int k = 0; k < r->cross->nsing; k++) {
            const glpgp_cross_sing *q = &r->cross->sing[k];
            if ((q->index4 > 0) != (sgn == 0)) continue;
            double rad = fmax(4.0, 3.0 * lw) * sqrt((double)abs(q->index4));
            double cx = (q->x - cv->ox) * cv->scale, cy = (cv->oy - q->y) * cv->scale;
            glpgp_cov_stroke(cv->cov, W, H, cx, cy, cx, cy, 2 * rad);
        }
        glpgp_cov_apply(cv->im, cv->cov, sgn == 0 ? col_pos : col_neg);
    }
}

/* Singular triangles can be smaller than a pixel: a red dot on each. */
static void overlay_singular(canvas *cv, const glpgp_mesh *m, const glpgp_result *r)
{
    double rad = fmax(2.5, 1.5 * cv->lw);
    for (int t = 0; t < m->nt; t++) {
        if (!((r->osc[0].singular && r->osc[0].singular[t]) || (r->osc[1].singular && r->osc[1].singular[t])))
            continue;
        const int *tv = m->tri + 3 * t;
        double cx = 0, cy = 0;
        for (int k = 0; k < 3; k++) {
            cx += (m->xy[2 * tv[k]] - cv->ox) * cv->scale / 3;
            cy += (cv->oy - m->xy[2 * tv[k] + 1]) * cv->scale / 3;
        }
        glpgp_cov_stroke(cv->cov, cv->W, cv->H, cx, cy, cx, cy, 2 * rad);
    }
    glpgp_cov_apply(cv->im, cv->cov, col_red);
}

/* FIELD: arrows of U on a regular pixel grid. */
static void overlay_arrows(canvas *cv)
{
    const int W = cv->W, H = cv->H;
    int step = cv->o.size / 40 < 8 ? 8 : cv->o.size / 40;
    double len = 0.8 * step;
    for (int j = step / 2; j < H; j += step)
        for (int i = step / 2; i < W; i += step) {
            size_t pi = (size_t)j * (size_t)W + (size_t)i;
            double ux = cv->fld[2 * pi], uy = cv->fld[2 * pi + 1];
            if (isnan(ux)) continue;
            double n = hypot(ux, uy);
            if (!(n > 1e-12)) continue;
            ux /= n;
            uy = -uy / n; /* pixel y points down */
            double cx = i + 0.5, cy = j + 0.5;
            double ax = cx - 0.5 * len * ux, ay = cy - 0.5 * len * uy;
            double bx = cx + 0.5 * len * ux, by = cy + 0.5 * len * uy;
            glpgp_cov_stroke(cv->cov, W, H, ax, ay, bx, by, cv->lw);
            double hl = 0.3 * len;
            for (int s = -1; s <= 1; s += 2) {
                double ca = cos(2.6), sa = s * sin(2.6);
                double hx = ux * ca - uy * sa, hy = ux * sa + uy * ca;
                glpgp_cov_stroke(cv->cov, W, H, bx, by, bx + hl * hx, by + hl * hy, cv->lw);
            }
        }
    static const float col_arrow[3] = {0.08f, 0.18f, 0.50f};
    glpgp_cov_apply(cv->im, cv->cov, col_arrow);
}

/* The domain's boundary loops, dark. */
static void overlay_boundary(canvas *cv, const glpgp_mesh *m)
{
    for (int l = 0; l < m->nloops; l++) {
        int s = m->loop_start[l], e = m->loop_start[l + 1];
        for (int k = s; k < e; k++) {
            int a = m->loop_vertices[k], b = m->loop_vertices[k + 1 < e ? k + 1 : s];
            glpgp_cov_stroke(cv->cov, cv->W, cv->H, (m->xy[2 * a] - cv->ox) * cv->scale, (cv->oy - m->xy[2 * a + 1]) * cv->scale,
                   (m->xy[2 * b] - cv->ox) * cv->scale, (cv->oy - m->xy[2 * b + 1]) * cv->scale,
                   fmax(1.5, cv->lw * 1.3));
        }
    }
    static const float col_b[3] = {0.12f, 0.12f, 0.12f};
    glpgp_cov_apply(cv->im, cv->cov, col_b);
}

glpgp_status glpgp_render(const glpgp_mesh *m, const glpgp_result *r, const glpgp_render_options *opt,
                          glpgp_image **out)
{
    if (!m || !r || !out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_render: NULL argument");
    *out = NULL;
    if (m->xyz) return glpgp_render3d(m, r, opt, out); /* a surface (image/render3d.c) */
    if (r->nv != m->nv || r->nt != m->nt)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "render: result (%d vertices, %d triangles) does not match "
                                         "the mesh (%d, %d)", r->nv, r->nt, m->nv, m->nt);
    canvas cv;
    memset(&cv, 0, sizeof cv);
    GLPGP_CHECK(glpgp_render_options_take(opt, &cv.o));
    const glpgp_render_options *o = &cv.o;
    if (o->kind < 0 || o->kind > GLPGP_IMAGE_CROSS) return GLPGP_FAIL(GLPGP_ERR_ARG, "unknown image kind %d", o->kind);
    if (o->kind == GLPGP_IMAGE_CROSS && !r->cross)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "render: the result has no cross field (solve with --field cross)");
    if (!r->osc[0].z || !r->osc[1].z) return GLPGP_FAIL(GLPGP_ERR_ARG, "render: result has no z");
    const glpgp_status st = canvas_create(m, &cv);
    if (st != GLPGP_OK) {
        canvas_free(&cv);
        return st;
    }
    for (int t = 0; t < m->nt; t++) raster_triangle(&cv, m, r, t);
    if (o->kind == GLPGP_IMAGE_CROSS) overlay_cross(&cv, r);
    if (o->singular && o->kind != GLPGP_IMAGE_ZABS && o->kind != GLPGP_IMAGE_CROSS) overlay_singular(&cv, m, r);
    if (o->kind == GLPGP_IMAGE_FIELD && r->field) overlay_arrows(&cv);
    if (o->boundary) overlay_boundary(&cv, m);
    *out = cv.im;
    cv.im = NULL;
    canvas_free(&cv);
    return GLPGP_OK;
}

/* ---- font ------------------------------------------------------------------ */

/* 5x7 glyphs, one byte per row (bit 4 = leftmost column). */
static const char font_chars[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789+-:.,()/=_";
static const unsigned char font_rows[][7] = {
    {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}, {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E},
    {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}, {0x1E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1E},
    {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}, {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10},
    {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}, {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11},
    {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}, {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C},
    {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}, {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F},
    {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}, {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11},
    {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}, {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10},
    {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}, {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11},
    {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}, {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04},
    {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}, {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04},
    {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}, {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11},
    {0x11, 0x11, 0x0A, 0x04, 0x04, 0x04, 0x04}, {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F},
    {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}, {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E},
    {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}, {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E},
    {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}, {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E},
    {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}, {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08},
    {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}, {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C},
    {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}, {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00},
    {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}, {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C},
    {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08}, {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02},
    {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}, {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00},
    {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}, {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F},
};
static const unsigned char font_box[7] = {0x1F, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1F};

int glpgp_draw_text(glpgp_image *im, int x, int y, int scale, const char *text, const float rgba[4])
{
    if (!im || !text || scale < 1 || (im->nc != 3 && im->nc != 4)) return 0;
    int cx = x;
    for (const char *s = text; *s; s++, cx += 6 * scale) {
        char ch = *s;
        if (ch >= 'a' && ch <= 'z') ch = (char)(ch - 'a' + 'A');
        if (ch == ' ') continue;
        const char *f = strchr(font_chars, ch);
        const unsigned char *rows = f ? font_rows[f - font_chars] : font_box;
        for (int ry = 0; ry < 7; ry++)
            for (int rx = 0; rx < 5; rx++) {
                if (!(rows[ry] & (0x10 >> rx))) continue;
                for (int sy = 0; sy < scale; sy++)
                    for (int sx = 0; sx < scale; sx++) {
                        int px = cx + rx * scale + sx, py = y + ry * scale + sy;
                        if (px < 0 || py < 0 || px >= im->w || py >= im->h) continue;
                        float *p = im->px + (size_t)im->nc * ((size_t)py * (size_t)im->w + (size_t)px);
                        if (im->nc == 4) {
                            glpgp_px_over(p, rgba, rgba[3]);
                        } else {
                            for (int k = 0; k < 3; k++) p[k] = p[k] * (1 - rgba[3]) + rgba[k] * rgba[3];
                        }
                    }
            }
    }
    return cx - x;
}

/* Panels side by side (the first panel's size; a smaller panel is drawn
 * from the top left) on white (unless o->transparent), each with two
 * centered caption lines l1[k], l2[k] below it: *out (RGBA). */
glpgp_status glpgp_r_compose_panels(glpgp_image *const *panel, int n, const char *const *l1, const char *const *l2,
                                    const glpgp_render_options *o, glpgp_image **out)
{
    const int pw = panel[0]->w, ph = panel[0]->h;
    const int ts = o->size / 300 < 2 ? 2 : o->size / 300; /* font scale */
    const int cap = 2 * 9 * ts + 4 * ts + 8;
    const int gap = o->size / 64 < 2 ? 2 : o->size / 64;
    const int W = n * pw + (n - 1) * gap, H = ph + cap;
    glpgp_image *im = NULL;
    GLPGP_CHECK(glpgp_image_create(W, H, 4, &im));
    if (!o->transparent)
        for (size_t i = 0; i < 4 * (size_t)W * (size_t)H; i++) im->px[i] = 1.0f;
    static const float ink[4] = {0.05f, 0.05f, 0.05f, 1.0f};
    for (int k = 0; k < n; k++) {
        const int x0 = k * (pw + gap), w = panel[k]->w < pw ? panel[k]->w : pw;
        for (int j = 0; j < ph && j < panel[k]->h; j++)
            memcpy(im->px + 4 * ((size_t)j * (size_t)W + (size_t)x0), panel[k]->px + 4 * (size_t)j * (size_t)panel[k]->w,
                   4 * (size_t)w * sizeof(float));
        const int w1 = 6 * ts * (int)strlen(l1[k]), w2 = 6 * ts * (int)strlen(l2[k]);
        glpgp_draw_text(im, x0 + (pw - w1) / 2, ph + 4, ts, l1[k], ink);
        glpgp_draw_text(im, x0 + (pw - w2) / 2, ph + 4 + 9 * ts + 2 * ts, ts, l2[k], ink);
    }
    *out = im;
    return GLPGP_OK;
}

/* ---- comparison figure -------------------------------------------------------- */

glpgp_status glpgp_render_compare(const glpgp_mesh *m, const glpgp_result *const *r,
                                  const char *const *labels, int n, const glpgp_render_options *opt,
                                  glpgp_image **out)
{
    if (!m || !r || !out || n < 1 || n > 16)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_render_compare: bad arguments");
    *out = NULL;
    glpgp_render_options o;
    GLPGP_CHECK(glpgp_render_options_take(opt, &o));
    glpgp_image *panel[16] = {0};
    glpgp_image *im = NULL;
    glpgp_status st = GLPGP_OK;
    for (int i = 0; i < n; i++) GLPGP_CHECK_GOTO(st, glpgp_render(m, r[i], &o, &panel[i]), fin);
    const char *l1[16], *l2[16];
    char line2[16][128];
    for (int k = 0; k < n; k++) {
        snprintf(line2[k], sizeof line2[k], "U +%d -%d   V +%d -%d", r[k]->osc[0].plus, r[k]->osc[0].minus,
                 r[k]->osc[1].plus, r[k]->osc[1].minus);
        l1[k] = labels && labels[k] ? labels[k] : "";
        l2[k] = line2[k];
    }
    GLPGP_CHECK_GOTO(st, glpgp_r_compose_panels(panel, n, l1, l2, &o, &im), fin);
    *out = im;
    im = NULL;
fin:
    for (int i = 0; i < n; i++) glpgp_image_destroy(&panel[i]);
    glpgp_image_destroy(&im);
    return st;
}

/* ---- the paper's Fig. 1: cross field, texture, quads -------------------------- */

glpgp_status glpgp_render_figure1(const glpgp_mesh *m, const glpgp_result *r, const glpgp_quadmesh *q,
                                  const glpgp_render_options *opt, glpgp_image **out)
{
    if (!m || !r || !out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_render_figure1: bad arguments");
    if (!r->cross) return GLPGP_FAIL(GLPGP_ERR_ARG, "figure: the result has no cross field");
    if (m->surf) return glpgp_r_figure_surface(m, r, q, opt, out); /* input, texture, quads (render3d_quads.c) */
    *out = NULL;
    glpgp_render_options o;
    GLPGP_CHECK(glpgp_render_options_take(opt, &o));
    const int n = q ? 3 : 2;
    glpgp_image *panel[3] = {0};
    glpgp_image *im = NULL;
    glpgp_status st = GLPGP_OK;
    glpgp_render_options oc = o, og = o;
    oc.kind = GLPGP_IMAGE_CROSS;
    og.kind = GLPGP_IMAGE_GRID;
    GLPGP_CHECK_GOTO(st, glpgp_render(m, r, &oc, &panel[0]), fin);
    GLPGP_CHECK_GOTO(st, glpgp_render(m, r, &og, &panel[1]), fin);
    if (q) GLPGP_CHECK_GOTO(st, glpgp_render_quadmesh(q, m, &o, 0.0, 0, &panel[2]), fin);
    /* captions: the cross field's singularities, the parametrization's, the quads' irregular vertices */
    char l1[3][64], l2[3][96];
    int sp = 0, sm = 0;
    for (int k = 0; k < r->cross->nsing; k++) {
        if (r->cross->sing[k].index4 > 0) sp += r->cross->sing[k].index4;
        else sm -= r->cross->sing[k].index4;
    }
    snprintf(l1[0], sizeof l1[0], "CROSS FIELD");
    snprintf(l2[0], sizeof l2[0], "+1/4 X %d   -1/4 X %d", sp, sm);
    snprintf(l1[1], sizeof l1[1], "GL-PGP");
    snprintf(l2[1], sizeof l2[1], "U +%d -%d   V +%d -%d", r->osc[0].plus, r->osc[0].minus, r->osc[1].plus,
             r->osc[1].minus);
    if (q) {
        snprintf(l1[2], sizeof l1[2], "QUADS");
        snprintf(l2[2], sizeof l2[2], "%d FACES", q->nf);
    }
    const char *c1[3] = {l1[0], l1[1], l1[2]}, *c2[3] = {l2[0], l2[1], l2[2]};
    GLPGP_CHECK_GOTO(st, glpgp_r_compose_panels(panel, n, c1, c2, &o, &im), fin);
    *out = im;
    im = NULL;
fin:
    for (int i = 0; i < 3; i++) glpgp_image_destroy(&panel[i]);
    glpgp_image_destroy(&im);
    return st;
}
