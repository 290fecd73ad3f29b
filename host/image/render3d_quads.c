/* image/render3d_quads.c: the picture of a surface's quad mesh
 * (glpgp_render3d_quadmesh, glpgp/image.h): the faces fanned into
 * triangles and z-buffered through the surface pictures' camera
 * (render3d_impl.h), each sample shaded (two-sided Lambert of its face's
 * Newell normal) in its face's colour (by origin; scaled Jacobian in the
 * face's plane below sj_low red, <= 0 dark red), the edges dark where a
 * sample is within the line width of its face's sides (screen space), the
 * irregular interior vertices as dots where visible (valence 3 blue, 5 red,
 * 6+ dark red), a line of counts under it. */
#include "render3d_impl.h"

#include "glpgp/image.h"
#include "glpgp/quads.h"
#include "glpgp/surface.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct q3 {
    const glpgp_quadmesh *q;
    glpgp_mesh fan;   /* the faces as triangles (nv, xyz, nt, tri) */
    int *tface;       /* per triangle: its face */
    double *fn;       /* per face: unit normal (3) */
    float *fcol;      /* per face: colour (3) */
    int edges;        /* draw the edges */
} q3;

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void face_colour(const glpgp_quadmesh *q, int f, double sj_low, float *c)
{
    if (sj_low < -1.0) { /* a plain surface (the figure's input panel) */
        c[0] = c[1] = c[2] = 0.86f;
        return;
    }
    static const float by_origin[GLPGP_QFACE_KINDS][3] = {
        {0.80f, 0.85f, 0.95f}, {0.62f, 0.74f, 0.98f}, {1.00f, 0.80f, 0.50f}, {0.86f, 0.66f, 0.93f}};
    static const float other[3] = {0.55f, 0.55f, 0.55f}, low[3] = {1.00f, 0.45f, 0.38f}, bad[3] = {0.70f, 0.05f, 0.05f};
    const int k = q->face_start[f + 1] - q->face_start[f];
    const double sj = glpgp_quadmesh_face_sj_surface(q, f);
    const float *s = k != 4 ? other : sj <= 0 ? bad : sj < sj_low ? low
                   : by_origin[q->face_origin && q->face_origin[f] < GLPGP_QFACE_KINDS ? q->face_origin[f] : 0];
    memcpy(c, s, 3 * sizeof(float));
}

static glpgp_status q3_build(q3 *Q, const glpgp_quadmesh *q, double sj_low)
{
    int nt = 0;
    for (int f = 0; f < q->nf; f++) nt += q->face_start[f + 1] - q->face_start[f] - 2;
    Q->q = q;
    Q->fan.nv = q->nv;
    Q->fan.xyz = q->xyz;
    Q->fan.nt = nt;
    GLPGP_CHECK(glpgp_malloc((size_t)3 * nt + 3, sizeof(int), &Q->fan.tri));
    GLPGP_CHECK(glpgp_malloc((size_t)nt + 1, sizeof(int), &Q->tface));
    GLPGP_CHECK(glpgp_malloc((size_t)3 * q->nf + 3, sizeof(double), &Q->fn));
    GLPGP_CHECK(glpgp_malloc((size_t)3 * q->nf + 3, sizeof(float), &Q->fcol));
    for (int f = 0, t = 0; f < q->nf; f++) {
        const int s = q->face_start[f], n = q->face_start[f + 1] - s;
        glpgp_quadmesh_face_normal(q, f, 1, Q->fn + 3 * f);
        face_colour(q, f, sj_low, Q->fcol + 3 * f);
        for (int i = 1; i + 1 < n; i++, t++) {
            Q->fan.tri[3 * t] = q->face_vert[s];
            Q->fan.tri[3 * t + 1] = q->face_vert[s + i];
            Q->fan.tri[3 * t + 2] = q->face_vert[s + i + 1];
            Q->tface[t] = f;
        }
    }
    return GLPGP_OK;
}

/* Screen distance (samples) from (x, y) to the sides of face f. */
static double side_dist(const q3 *Q, const cam3 *c, int f, double x, double y)
{
    const glpgp_quadmesh *q = Q->q;
    const int s = q->face_start[f], n = q->face_start[f + 1] - s;
    double best = HUGE_VAL, a[3], b[3];
    glpgp_r3_project(c, q->xyz + 3 * q->face_vert[s + n - 1], a);
    for (int i = 0; i < n; i++) {
        glpgp_r3_project(c, q->xyz + 3 * q->face_vert[s + i], b);
        const double ex = b[0] - a[0], ey = b[1] - a[1], l2 = ex * ex + ey * ey;
        double t = l2 > 0 ? ((x - a[0]) * ex + (y - a[1]) * ey) / l2 : 0.0;
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        best = fmin(best, hypot(x - a[0] - t * ex, y - a[1] - t * ey));
        memcpy(a, b, sizeof a);
    }
    return best;
}

static void resolve(const q3 *Q, const glpgp_render_options *o, const cam3 *c, const gbuf *g, double lw,
                    glpgp_image *im, int h_img)
{
    double L[3];
    for (int e = 0; e < 3; e++) L[e] = c->dir[e] + 0.45 * c->up[e] - 0.3 * c->right[e];
    const double ln = sqrt(dot3(L, L));
    const double bg = o->transparent ? 0.0 : 1.0;
    for (int j = 0; j < im->h; j++)
        for (int i = 0; i < im->w; i++) {
            double acc[3] = {0.0, 0.0, 0.0};
            int n = 0;
            for (int sj = 0; sj < c->ss && j < h_img; sj++)
                for (int si = 0; si < c->ss; si++) {
                    const int x = c->ss * i + si, y = c->ss * j + sj;
                    const size_t s = (size_t)y * (size_t)c->W + (size_t)x;
                    if (g->tri[s] < 0) continue;
                    const int f = Q->tface[g->tri[s]];
                    const double sh = 0.3 + 0.7 * fabs(dot3(Q->fn + 3 * f, L)) / ln;
                    const double d = Q->edges ? side_dist(Q, c, f, x + 0.5, y + 0.5) : HUGE_VAL;
                    const double ink = fmax(0.0, fmin(1.0, 0.5 * lw * c->ss + 0.5 - d));
                    for (int k = 0; k < 3; k++) acc[k] += (1.0 - ink) * Q->fcol[3 * f + k] * sh + ink * 0.12;
                    n++;
                }
            float *p = im->px + 4 * ((size_t)j * (size_t)im->w + (size_t)i);
            const double a = (double)n / (c->ss * c->ss);
            for (int k = 0; k < 3; k++) p[k] = (float)(n ? (acc[k] / n) * a + bg * (1.0 - a) : bg);
            p[3] = (float)(o->transparent ? a : 1.0);
        }
}

/* The irregular interior vertices as dots where visible; returns their count. */
static int vertices(const q3 *Q, const glpgp_render_options *o, const cam3 *c, const gbuf *g, glpgp_image *im,
                    const int *val, const unsigned char *bnd)
{
    const glpgp_quadmesh *q = Q->q;
    static const float col[3][3] = {{0.05f, 0.35f, 0.95f}, {0.90f, 0.05f, 0.05f}, {0.45f, 0.0f, 0.0f}};
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int v = 0; v < q->nv; v++)
        for (int d = 0; d < 3; d++) {
            lo[d] = fmin(lo[d], q->xyz[3 * v + d]);
            hi[d] = fmax(hi[d], q->xyz[3 * v + d]);
        }
    const double tol = 2e-3 * sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                   (hi[2] - lo[2]) * (hi[2] - lo[2]));
    const double rad = fmax(2.5, o->size / 200.0);
    int n = 0;
    for (int v = 0; v < q->nv; v++) {
        if (bnd[v] || val[v] == 4 || val[v] == 0) continue;
        n++;
        double p[3];
        if (!glpgp_r3_visible(c, g, q->xyz + 3 * v, tol, p)) continue;
        const int k = val[v] < 4 ? 0 : val[v] == 5 ? 1 : 2;
        glpgp_r3_disc(im, p[0] / c->ss, p[1] / c->ss, k == 2 ? 1.3 * rad : rad, col[k]);
    }
    return n;
}

static int cmp_key(const void *pa, const void *pb)
{
    const long long a = *(const long long *)pa, b = *(const long long *)pb;
    return a < b ? -1 : a > b;
}

/* Boundary vertices (on an edge of one face). */
static glpgp_status boundary(const glpgp_quadmesh *q, unsigned char *bnd)
{
    const int nc = q->face_start[q->nf];
    long long *key = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)nc + 1, sizeof *key, &key));
    for (int f = 0; f < q->nf; f++) {
        const int s = q->face_start[f], n = q->face_start[f + 1] - s;
        for (int i = 0; i < n; i++) {
            const long long a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % n];
            key[s + i] = a < b ? a * q->nv + b : b * q->nv + a;
        }
    }
    qsort(key, (size_t)nc, sizeof *key, cmp_key);
    for (int i = 0; i < nc;) {
        int j = i;
        while (j < nc && key[j] == key[i]) j++;
        if (j - i == 1) bnd[key[i] / q->nv] = bnd[key[i] % q->nv] = 1;
        i = j;
    }
    free(key);
    return GLPGP_OK;
}

/* sj_low < -1: a plain picture (grey faces, no dots, no caption). */
static glpgp_status render(const glpgp_quadmesh *q, const glpgp_render_options *opt, double sj_low, int caption,
                           glpgp_image **out)
{
    if (!q || !out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_render3d_quadmesh: NULL argument");
    *out = NULL;
    if (!q->xyz || q->nf <= 0) return GLPGP_FAIL(GLPGP_ERR_ARG, "render: an empty or planar quad mesh");
    glpgp_render_options o;
    if (opt) o = *opt;
    else glpgp_render_options_default(&o);
    if (o.size < 16 || o.size > 32768) return GLPGP_FAIL(GLPGP_ERR_ARG, "image size %d out of range [16, 32768]", o.size);
    if (!isfinite(o.azimuth) || !isfinite(o.elevation) || fabs(o.elevation) > 90.0)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "view: azimuth and elevation in degrees, |elevation| <= 90");
    const double lw = o.line_width > 0 ? o.line_width : fmax(1.0, 1.5 * o.size / 1024.0);
    const int margin = o.margin >= 0 ? o.margin : o.size / 64, cap = caption ? (o.size / 40 > 14 ? o.size / 40 : 14) : 0;
    q3 Q;
    memset(&Q, 0, sizeof Q);
    gbuf g = {NULL, NULL, NULL, NULL};
    glpgp_image *im = NULL;
    int *val = NULL;
    unsigned char *bnd = NULL;
    cam3 c;
    glpgp_status st = q3_build(&Q, q, sj_low);
    Q.edges = sj_low >= -1.0 || (double)q->nf * 400.0 <= (double)o.size * o.size; /* a plain surface's dense edges: none */
    if (st != GLPGP_OK) goto done;
    glpgp_r3_cam_setup(&Q.fan, &o, margin, &c);
    const size_t ns = (size_t)c.W * (size_t)c.H;
    GLPGP_CHECK_GOTO(st, glpgp_malloc(ns, sizeof(int), &g.tri), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(ns, sizeof(float), &g.l1), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(ns, sizeof(float), &g.l2), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(ns, sizeof(double), &g.depth), done);
    for (size_t s = 0; s < ns; s++) g.tri[s] = -1;
    glpgp_r3_raster(&Q.fan, &c, &g);
    GLPGP_CHECK_GOTO(st, glpgp_image_create(c.W / c.ss, c.H / c.ss + cap, 4, &im), done);
    resolve(&Q, &o, &c, &g, lw, im, c.H / c.ss);
    GLPGP_CHECK_GOTO(st, glpgp_quadmesh_valences(q, &val), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)q->nv + 1, 1, &bnd), done);
    GLPGP_CHECK_GOTO(st, boundary(q, bnd), done);
    const int irr = sj_low < -1.0 ? 0 : vertices(&Q, &o, &c, &g, im, val, bnd);
    if (cap) {
        int quads = 0, low = 0;
        double sjmin = 1.0;
        for (int f = 0; f < q->nf; f++) {
            if (q->face_start[f + 1] - q->face_start[f] != 4) continue;
            const double sj = glpgp_quadmesh_face_sj_surface(q, f);
            quads++;
            low += sj < sj_low;
            sjmin = fmin(sjmin, sj);
        }
        char line[160];
        snprintf(line, sizeof line, "%d QUADS%s  SJ MIN %.2f  BELOW %.2f: %d  IRREGULAR INTERIOR %d", quads,
                 quads < q->nf ? " (+ OTHER FACES)" : "", sjmin, sj_low, low, irr);
        int ts = cap / 12 < 1 ? 1 : cap / 12;
        while (ts > 1 && 6 * ts * (int)strlen(line) > im->w - 8) ts--;
        static const float ink[4] = {0.05f, 0.05f, 0.05f, 1.0f};
        glpgp_draw_text(im, 4, im->h - cap + (cap - 7 * ts) / 2, ts, line, ink);
    }
    *out = im;
    im = NULL;
done:
    glpgp_image_destroy(&im);
    glpgp_r3_gbuf_free(&g);
    free(Q.fan.tri);
    free(Q.tface);
    free(Q.fn);
    free(Q.fcol);
    free(val);
    free(bnd);
    return st;
}

glpgp_status glpgp_render3d_quadmesh(const glpgp_quadmesh *q, const glpgp_render_options *o, double sj_low,
                                     int caption, glpgp_image **out)
{
    return render(q, o, sj_low < -1.0 ? -1.0 : sj_low, caption, out);
}

glpgp_status glpgp_r_figure_surface(const glpgp_mesh *m, const glpgp_result *r, const glpgp_quadmesh *q,
                                    const glpgp_render_options *opt, glpgp_image **out)
{
    *out = NULL;
    glpgp_render_options o;
    if (opt) o = *opt;
    else glpgp_render_options_default(&o);
    glpgp_render_options og = o;
    og.kind = GLPGP_IMAGE_GRID;
    glpgp_quadmesh in; /* the input's triangles as faces of 3 corners (its arrays borrowed) */
    memset(&in, 0, sizeof in);
    int *fs = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)m->nt + 1, sizeof(int), &fs));
    for (int t = 0; t <= m->nt; t++) fs[t] = 3 * t;
    in.nv = m->nv;
    in.nf = m->nt;
    in.xyz = m->xyz;
    in.face_start = fs;
    in.face_vert = m->tri;
    glpgp_image *panel[3] = {NULL, NULL, NULL};
    const int n = q ? 3 : 2;
    glpgp_status st = render(&in, &o, -2.0, 0, &panel[0]);
    if (st == GLPGP_OK) st = glpgp_render3d(m, r, &og, &panel[1]);
    if (st == GLPGP_OK && q) st = render(q, &o, 0.3, 0, &panel[2]);
    char l1[3][64], l2[3][96];
    int irr = 0;
    int *val = NULL;
    if (st == GLPGP_OK && q && glpgp_quadmesh_valences(q, &val) == GLPGP_OK) {
        unsigned char *bnd = NULL;
        if (glpgp_calloc((size_t)q->nv + 1, 1, &bnd) == GLPGP_OK && boundary(q, bnd) == GLPGP_OK)
            for (int v = 0; v < q->nv; v++) irr += !bnd[v] && val[v] && val[v] != 4;
        free(bnd);
    }
    free(val);
    snprintf(l1[0], sizeof l1[0], "INPUT");
    snprintf(l2[0], sizeof l2[0], "%d TRIANGLES  GENUS %d  LOOPS %d", m->nt, m->surf ? m->surf->genus : 0, m->nloops);
    snprintf(l1[1], sizeof l1[1], "GL-PGP");
    snprintf(l2[1], sizeof l2[1], "U +%d -%d   V +%d -%d", r->osc[0].plus, r->osc[0].minus, r->osc[1].plus,
             r->osc[1].minus);
    snprintf(l1[2], sizeof l1[2], "QUADS");
    snprintf(l2[2], sizeof l2[2], "%d FACES  %d IRREGULAR", q ? q->nf : 0, irr);
    const char *c1[3] = {l1[0], l1[1], l1[2]}, *c2[3] = {l2[0], l2[1], l2[2]};
    if (st == GLPGP_OK) st = glpgp_r_compose_panels(panel, n, c1, c2, &o, out);
    for (int i = 0; i < 3; i++) glpgp_image_destroy(&panel[i]);
    free(fs);
    return st;
}
