/* image/render3d.c: pictures of a surface's result (glpgp_render3d,
 * glpgp/image.h): an orthographic camera from (azimuth, elevation) fitted
 * to the surface, software rasterised with a z-buffer at 2 x 2 samples per
 * pixel (1 above about 2048 x 2048 pixels), each sample's triangle and barycentrics kept; then every sample is
 * shaded (two-sided Lambert of the triangle's normal, smoothed towards the
 * vertex normals where the surface is smooth) and coloured by the kind: the
 * (theta_u, theta_v) grid of the paper's figures read per triangle through
 * its matching (lines anti-aliased by their screen-space distance), the
 * checkerboard, |z| or the raw phases; singular triangles red, the cross
 * field's singularities as dots (+1/4 red, -1/4 blue) where visible, the
 * boundary as dark strokes; averaged down to pixels. */
#include "raster.h"
#include "render3d_impl.h"

#include "glpgp/image.h"
#include "glpgp/cross.h"
#include "glpgp/kinds.h"
#include "glpgp/phase.h"
#include "glpgp/surfsolve.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* samples per pixel side: 2 up to this many pixels (about 2048 x 2048), 1
 * above (the sample buffers take 20 bytes a sample) */
#define SS_MAX_PIXELS 4200000.0


static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

void glpgp_r3_cam_setup(const glpgp_mesh *m, const glpgp_render_options *o, int margin, cam3 *c)
{
    const double az = o->azimuth * GLPGP_PI / 180.0, el = o->elevation * GLPGP_PI / 180.0;
    c->dir[0] = cos(el) * cos(az);
    c->dir[1] = cos(el) * sin(az);
    c->dir[2] = sin(el);
    /* right = z x dir (y when looking straight down or up), up = dir x right */
    double r[3] = {-c->dir[1], c->dir[0], 0.0};
    double n = sqrt(dot3(r, r));
    if (n < 1e-9) {
        r[0] = 0.0;
        r[1] = 1.0;
        n = 1.0;
    }
    for (int k = 0; k < 3; k++) c->right[k] = r[k] / n;
    c->up[0] = c->dir[1] * c->right[2] - c->dir[2] * c->right[1];
    c->up[1] = c->dir[2] * c->right[0] - c->dir[0] * c->right[2];
    c->up[2] = c->dir[0] * c->right[1] - c->dir[1] * c->right[0];
    double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
    for (int i = 0; i < m->nv; i++) {
        const double x = dot3(m->xyz + 3 * i, c->right), y = dot3(m->xyz + 3 * i, c->up);
        x0 = fmin(x0, x);
        x1 = fmax(x1, x);
        y0 = fmin(y0, y);
        y1 = fmax(y1, y);
    }
    const double span = fmax(fmax(x1 - x0, y1 - y0), 1e-300);
    int inner = o->size - 2 * margin;
    if (inner < 8) inner = 8;
    const double s = inner / span;
    const int pw = (int)ceil((x1 - x0) * s - 1e-9) + 2 * margin, ph = (int)ceil((y1 - y0) * s - 1e-9) + 2 * margin;
    c->ss = (double)pw * ph <= SS_MAX_PIXELS ? 2 : 1;
    c->W = c->ss * (pw > 1 ? pw : 1);
    c->H = c->ss * (ph > 1 ? ph : 1);
    c->scale = c->ss * s;
    c->ox = x0 - margin / s;
    c->oy = y1 + margin / s;
}

void glpgp_r3_project(const cam3 *c, const double *p, double *q)
{
    q[0] = (dot3(p, c->right) - c->ox) * c->scale;
    q[1] = (c->oy - dot3(p, c->up)) * c->scale;
    q[2] = dot3(p, c->dir); /* larger: nearer the camera */
}


void glpgp_r3_raster(const glpgp_mesh *m, const cam3 *c, gbuf *g)
{
    for (int t = 0; t < m->nt; t++) {
        double P[3][3];
        for (int k = 0; k < 3; k++) glpgp_r3_project(c, m->xyz + 3 * m->tri[3 * t + k], P[k]);
        const double e1x = P[1][0] - P[0][0], e1y = P[1][1] - P[0][1], e2x = P[2][0] - P[0][0], e2y = P[2][1] - P[0][1];
        const double det = e1x * e2y - e2x * e1y;
        if (fabs(det) < 1e-18) continue;
        const double g1x = e2y / det, g1y = -e2x / det, g2x = -e1y / det, g2y = e1x / det;
        int x0 = (int)floor(fmin(P[0][0], fmin(P[1][0], P[2][0]))), x1 = (int)ceil(fmax(P[0][0], fmax(P[1][0], P[2][0])));
        int y0 = (int)floor(fmin(P[0][1], fmin(P[1][1], P[2][1]))), y1 = (int)ceil(fmax(P[0][1], fmax(P[1][1], P[2][1])));
        x0 = x0 < 0 ? 0 : x0;
        y0 = y0 < 0 ? 0 : y0;
        x1 = x1 > c->W - 1 ? c->W - 1 : x1;
        y1 = y1 > c->H - 1 ? c->H - 1 : y1;
        for (int j = y0; j <= y1; j++)
            for (int i = x0; i <= x1; i++) {
                const double dx = i + 0.5 - P[0][0], dy = j + 0.5 - P[0][1];
                const double l1 = g1x * dx + g1y * dy, l2 = g2x * dx + g2y * dy, l0 = 1.0 - l1 - l2;
                if (l0 < -1e-9 || l1 < -1e-9 || l2 < -1e-9) continue;
                const double d = l0 * P[0][2] + l1 * P[1][2] + l2 * P[2][2];
                const size_t s = (size_t)j * (size_t)c->W + (size_t)i;
                if (g->tri[s] >= 0 && d <= g->depth[s]) continue;
                g->tri[s] = t;
                g->l1[s] = (float)l1;
                g->l2[s] = (float)l2;
                g->depth[s] = d;
            }
    }
}

/* Per triangle: the unwrapped phases at its corners (through its matching
 * for a coupled result), the corners' |z|, the phases' screen gradients. */
typedef struct tri_phase {
    double th[2][3], za[2][3], gn[2];
} tri_phase;

static void phases(const glpgp_mesh *m, const glpgp_result *r, const cam3 *c, int t, tri_phase *p)
{
    const int *v = m->tri + 3 * t;
    double P[3][3];
    for (int k = 0; k < 3; k++) glpgp_r3_project(c, m->xyz + 3 * v[k], P[k]);
    const double e1x = P[1][0] - P[0][0], e1y = P[1][1] - P[0][1], e2x = P[2][0] - P[0][0], e2y = P[2][1] - P[0][1];
    const double det = e1x * e2y - e2x * e1y;
    const double g1x = e2y / det, g1y = -e2x / det, g2x = -e1y / det, g2y = e1x / det;
    for (int q = 0; q < 2; q++) {
        double tc[3];
        for (int k = 0; k < 3; k++) {
            double f[2] = {r->osc[q].z[2 * v[k]], r->osc[q].z[2 * v[k] + 1]};
            if (r->coupled && r->field)
                glpgp_coupled_frame_value(glpgp_coupled_corner_turn(m, r->field, t, k), q, r->osc[0].z + 2 * v[k],
                                          r->osc[1].z + 2 * v[k], f);
            p->za[q][k] = hypot(f[0], f[1]);
            tc[k] = glpgp_theta(f[0], f[1]);
        }
        glpgp_phase_chart(tc, p->th[q]);
        const double gx = (p->th[q][1] - p->th[q][0]) * g1x + (p->th[q][2] - p->th[q][0]) * g2x;
        const double gy = (p->th[q][1] - p->th[q][0]) * g1y + (p->th[q][2] - p->th[q][0]) * g2y;
        p->gn[q] = hypot(gx, gy);
    }
}

/* Coverage of the grid line nearest t (gradient g per sample, width lw samples). */
static double line_cov(double t, double g, double lw)
{
    if (!(g > 1e-12)) return 0.0;
    const double d = fabs(t - floor(t + 0.5)) / g;
    const double cov = glpgp_clamp01(0.5 * lw + 0.5 - d);
    return g * lw > 0.5 ? fmax(cov, glpgp_clamp01(g * lw)) * 0.7 : cov; /* lines denser than the samples: a tint */
}

/* The colour of sample (t, l) by the kind (before shading). */
static void sample_colour(const glpgp_render_options *o, const tri_phase *p, double l0, double l1, double l2,
                          double lw, float *c)
{
    const double tu = p->th[0][0] * l0 + p->th[0][1] * l1 + p->th[0][2] * l2;
    const double tv = p->th[1][0] * l0 + p->th[1][1] * l1 + p->th[1][2] * l2;
    if (o->kind == GLPGP_IMAGE_ZABS) {
        const double a = fmin(p->za[0][0] * l0 + p->za[0][1] * l1 + p->za[0][2] * l2,
                              p->za[1][0] * l0 + p->za[1][1] * l1 + p->za[1][2] * l2);
        c[0] = (float)glpgp_clamp01(1.5 * a);
        c[1] = (float)glpgp_clamp01(1.5 * a - 0.5);
        c[2] = (float)glpgp_clamp01(3.0 * a - 2.0);
        return;
    }
    if (o->kind == GLPGP_IMAGE_THETA) {
        c[0] = (float)(tu - floor(tu));
        c[1] = (float)(tv - floor(tv));
        c[2] = 0.3f;
        return;
    }
    if (o->kind == GLPGP_IMAGE_CHECKER) {
        const double au = tu - floor(tu), av = tv - floor(tv);
        const double g = (au < 0.5) == (av < 0.5) ? 0.95 : 0.2;
        c[0] = c[1] = (float)g;
        c[2] = (float)(g + 0.03);
        return;
    }
    /* grid: a light cell, lines of u blue and of v red */
    static const float cu[3] = {0.10f, 0.22f, 0.60f}, cv[3] = {0.60f, 0.18f, 0.10f};
    const double fu = tu - floor(tu) - 0.5, fv = tv - floor(tv) - 0.5;
    const double sh = 1.0 - 0.12 * (fabs(fu) + fabs(fv));
    c[0] = (float)(1.00 * sh);
    c[1] = (float)(0.98 * sh);
    c[2] = (float)(0.93 * sh);
    const double au = line_cov(tu, p->gn[0], lw), av = line_cov(tv, p->gn[1], lw);
    for (int k = 0; k < 3; k++) {
        c[k] = (float)(c[k] * (1.0 - au) + cu[k] * au);
        c[k] = (float)(c[k] * (1.0 - av) + cv[k] * av);
    }
}

/* The lit normal of sample (t, l): the vertex normals where they are within
 * 30 degrees of the face's, the face's elsewhere (creases stay sharp). */
static double shade(const glpgp_mesh *m, const cam3 *c, int t, double l0, double l1, double l2)
{
    const double *N = m->surf->tframe + 9 * t + 6;
    double n[3] = {0.0, 0.0, 0.0};
    const double w[3] = {l0, l1, l2};
    for (int k = 0; k < 3; k++) {
        const double *vn = m->surf->vnormal + 3 * m->tri[3 * t + k];
        const double *use = dot3(vn, N) > 0.866 ? vn : N;
        for (int e = 0; e < 3; e++) n[e] += w[k] * use[e];
    }
    const double nn = sqrt(dot3(n, n));
    double L[3];
    for (int e = 0; e < 3; e++) L[e] = c->dir[e] + 0.45 * c->up[e] - 0.3 * c->right[e];
    const double ln = sqrt(dot3(L, L));
    return 0.3 + 0.7 * fabs(dot3(n, L)) / (nn * ln + 1e-300);
}

/* Whether point p (3D) is in front of what the samples around it show. */
void glpgp_r3_gbuf_free(gbuf *g)
{
    free(g->tri);
    free(g->l1);
    free(g->l2);
    free(g->depth);
}

int glpgp_r3_visible(const cam3 *c, const gbuf *g, const double *p, double tol, double *q)
{
    glpgp_r3_project(c, p, q);
    const int i = (int)floor(q[0]), j = (int)floor(q[1]);
    for (int dj = -1; dj <= 1; dj++)
        for (int di = -1; di <= 1; di++) {
            const int x = i + di, y = j + dj;
            if (x < 0 || y < 0 || x >= c->W || y >= c->H) continue;
            const size_t s = (size_t)y * (size_t)c->W + (size_t)x;
            if (g->tri[s] < 0 || q[2] >= g->depth[s] - tol) return 1;
        }
    return 0;
}

/* A filled disc of radius rad (pixels) at pixel position (x, y), colour col, anti-aliased. */
void glpgp_r3_disc(glpgp_image *im, double x, double y, double rad, const float *col)
{
    for (int j = (int)floor(y - rad - 1); j <= (int)ceil(y + rad + 1); j++)
        for (int i = (int)floor(x - rad - 1); i <= (int)ceil(x + rad + 1); i++) {
            if (i < 0 || j < 0 || i >= im->w || j >= im->h) continue;
            const double a = glpgp_clamp01(rad + 0.5 - hypot(i + 0.5 - x, j + 0.5 - y));
            float *p = im->px + 4 * ((size_t)j * (size_t)im->w + (size_t)i);
            for (int k = 0; k < 3; k++) p[k] = (float)(p[k] * (1.0 - a) + col[k] * a);
            p[3] = (float)fmax(p[3], a);
        }
}

/* The boundary loops as dark strokes and the cross field's singularities as
 * dots, where visible. */
static void overlays(const glpgp_mesh *m, const glpgp_result *r, const glpgp_render_options *o, const cam3 *c,
                     const gbuf *g, double lw, glpgp_image *im)
{
    const double tol = 2e-3 * glpgp_mesh_diagonal(m);
    static const float dark[3] = {0.1f, 0.1f, 0.1f}, red[3] = {0.9f, 0.05f, 0.05f}, blue[3] = {0.1f, 0.25f, 0.95f};
    for (int l = 0; o->boundary && l < m->nloops; l++)
        for (int k = m->loop_start[l]; k < m->loop_start[l + 1]; k++) {
            const int a = m->loop_vertices[k], b = m->loop_vertices[k + 1 < m->loop_start[l + 1] ? k + 1 : m->loop_start[l]];
            double qa[3], qb[3];
            glpgp_r3_project(c, m->xyz + 3 * a, qa);
            glpgp_r3_project(c, m->xyz + 3 * b, qb);
            const int n = 1 + (int)(hypot(qb[0] - qa[0], qb[1] - qa[1]) / c->ss * 2.0);
            for (int s = 0; s <= n; s++) {
                double p[3], q[3];
                for (int e = 0; e < 3; e++) p[e] = m->xyz[3 * a + e] + (m->xyz[3 * b + e] - m->xyz[3 * a + e]) * s / n;
                if (glpgp_r3_visible(c, g, p, tol, q)) glpgp_r3_disc(im, q[0] / c->ss, q[1] / c->ss, 0.5 * lw, dark);
            }
        }
    if (!r->cross || !o->singular) return;
    const double rad = fmax(2.0, o->size / 180.0);
    for (int k = 0; k < r->cross->nsing; k++) {
        const glpgp_cross_sing *s = &r->cross->sing[k];
        const double p[3] = {s->x, s->y, s->z};
        double q[3];
        if (glpgp_r3_visible(c, g, p, tol, q))
            glpgp_r3_disc(im, q[0] / c->ss, q[1] / c->ss, rad * (abs(s->index4) > 1 ? 1.4 : 1.0), s->index4 > 0 ? red : blue);
    }
}

/* Every pixel: the mean of its samples' shaded colours (background where none). */
static glpgp_status resolve(const glpgp_mesh *m, const glpgp_result *r, const glpgp_render_options *o, const cam3 *c,
                            const gbuf *g, double lw, glpgp_image *im)
{
    int *slot = NULL;
    tri_phase *tp = NULL;
    size_t ntp = 0, cap = 0;
    GLPGP_CHECK(glpgp_malloc((size_t)m->nt, sizeof(int), &slot));
    for (int t = 0; t < m->nt; t++) slot[t] = -1;
    static const float red[3] = {0.90f, 0.05f, 0.05f};
    glpgp_status st = GLPGP_OK;
    for (int j = 0; j < im->h && st == GLPGP_OK; j++)
        for (int i = 0; i < im->w; i++) {
            double acc[3] = {0.0, 0.0, 0.0};
            int n = 0;
            for (int sj = 0; sj < c->ss; sj++)
                for (int si = 0; si < c->ss; si++) {
                    const size_t s = (size_t)(c->ss * j + sj) * (size_t)c->W + (size_t)(c->ss * i + si);
                    const int t = g->tri[s];
                    if (t < 0) continue;
                    if (slot[t] < 0) { /* the triangle's phases, once */
                        if ((st = glpgp_grow(&tp, &cap, ntp + 1, sizeof *tp)) != GLPGP_OK) goto out;
                        phases(m, r, c, t, &tp[ntp]);
                        slot[t] = (int)ntp++;
                    }
                    const double l1 = g->l1[s], l2 = g->l2[s], l0 = 1.0 - l1 - l2;
                    float col[3];
                    sample_colour(o, &tp[slot[t]], l0, l1, l2, lw * c->ss, col);
                    if (o->singular && o->kind != GLPGP_IMAGE_ZABS &&
                        ((r->osc[0].singular && r->osc[0].singular[t]) || (r->osc[1].singular && r->osc[1].singular[t])))
                        for (int k = 0; k < 3; k++) col[k] = (float)(0.25 * col[k] + 0.75 * red[k]);
                    const double sh = shade(m, c, t, l0, l1, l2);
                    for (int k = 0; k < 3; k++) acc[k] += col[k] * sh;
                    n++;
                }
            float *p = im->px + 4 * ((size_t)j * (size_t)im->w + (size_t)i);
            const double a = (double)n / (c->ss * c->ss), bg = o->transparent ? 0.0 : 1.0;
            for (int k = 0; k < 3; k++) p[k] = (float)(n ? (acc[k] / n) * a + bg * (1.0 - a) : bg);
            p[3] = (float)(o->transparent ? a : 1.0);
        }
out:
    free(slot);
    free(tp);
    return st;
}

glpgp_status glpgp_render3d(const glpgp_mesh *m, const glpgp_result *r, const glpgp_render_options *opt,
                            glpgp_image **out)
{
    if (!m || !r || !out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_render3d: NULL argument");
    *out = NULL;
    if (!m->surf) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_render3d: not a surface");
    if (r->nv != m->nv || r->nt != m->nt || !r->osc[0].z || !r->osc[1].z)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "render: the result does not match the surface");
    glpgp_render_options o;
    GLPGP_CHECK(glpgp_render_options_take(opt, &o));
    if (o.kind != GLPGP_IMAGE_GRID && o.kind != GLPGP_IMAGE_CHECKER && o.kind != GLPGP_IMAGE_ZABS &&
        o.kind != GLPGP_IMAGE_THETA)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "a surface's picture is of kind grid, checker, zabs or theta (not %s)",
                          glpgp_image_kind_name(o.kind));
    if (!isfinite(o.azimuth) || !isfinite(o.elevation) || fabs(o.elevation) > 90.0)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "view: azimuth and elevation in degrees, |elevation| <= 90");
    const double lw = o.line_width > 0 ? o.line_width : fmax(1.0, 1.5 * o.size / 1024.0);
    const int margin = o.margin >= 0 ? o.margin : o.size / 64;
    cam3 c;
    glpgp_r3_cam_setup(m, &o, margin, &c);
    gbuf g = {NULL, NULL, NULL, NULL};
    glpgp_image *im = NULL;
    const size_t ns = (size_t)c.W * (size_t)c.H;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc(ns, sizeof(int), &g.tri), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(ns, sizeof(float), &g.l1), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(ns, sizeof(float), &g.l2), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(ns, sizeof(double), &g.depth), done);
    for (size_t s = 0; s < ns; s++) g.tri[s] = -1;
    glpgp_r3_raster(m, &c, &g);
    GLPGP_CHECK_GOTO(st, glpgp_image_create(c.W / c.ss, c.H / c.ss, 4, &im), done);
    GLPGP_CHECK_GOTO(st, resolve(m, r, &o, &c, &g, lw, im), done);
    overlays(m, r, &o, &c, &g, lw, im);
    *out = im;
    im = NULL;
done:
    glpgp_image_destroy(&im);
    glpgp_r3_gbuf_free(&g);
    return st;
}
