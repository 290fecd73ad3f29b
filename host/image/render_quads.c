/* image/render_quads.c: pictures of quad meshes (glpgp_render_quadmesh,
 * glpgp/image.h): the faces filled by where they come from (the
 * parametrization's grid, the closing strips, the repair's region mesher,
 * its fallback) and red where their smallest corner scaled Jacobian is below
 * a threshold, the edges, the domain boundary over them, the irregular
 * vertices as dots (valence 3 blue, 5 red, 6 and more dark red; boundary
 * vertices against their ideal valence, smaller), and a caption with the
 * counts. Faces are filled per pixel center by the crossing rule, so a
 * non-convex or folded face shows as it is. */
#include "raster.h"
#include "glpgp/image.h"
#include "glpgp/util.h"
#include "glpgp/quads.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI_ 3.14159265358979323846

typedef struct qframe {
    int W, H;
    double ox, oy, scale; /* pixel x = (x - ox) scale, pixel y = (oy - y) scale */
    double lw;
} qframe;

static void to_px(const qframe *F, const double *p, double *x, double *y)
{
    *x = (p[0] - F->ox) * F->scale;
    *y = (F->oy - p[1]) * F->scale;
}

/* Fill polygon pts (n points, pixel coordinates) with colour c: pixel
 * centers inside by the crossing rule (either orientation). */
static void fill_poly(glpgp_image *im, const qframe *F, const double *pts, int n, const float c[3], double alpha)
{
    double y0 = INFINITY, y1 = -INFINITY, x0 = INFINITY, x1 = -INFINITY;
    for (int i = 0; i < n; i++) {
        x0 = fmin(x0, pts[2 * i]);
        x1 = fmax(x1, pts[2 * i]);
        y0 = fmin(y0, pts[2 * i + 1]);
        y1 = fmax(y1, pts[2 * i + 1]);
    }
    int ja = (int)floor(y0), jb = (int)ceil(y1), ia = (int)floor(x0), ib = (int)ceil(x1);
    if (ja < 0) ja = 0;
    if (ia < 0) ia = 0;
    if (jb > F->H - 1) jb = F->H - 1;
    if (ib > F->W - 1) ib = F->W - 1;
    for (int j = ja; j <= jb; j++)
        for (int i = ia; i <= ib; i++) {
            double px = i + 0.5, py = j + 0.5;
            int in = 0;
            for (int k = 0, l = n - 1; k < n; l = k++) {
                double xk = pts[2 * k], yk = pts[2 * k + 1], xl = pts[2 * l], yl = pts[2 * l + 1];
                if ((yk > py) != (yl > py) && px < xl + (py - yl) * (xk - xl) / (yk - yl)) in = !in;
            }
            if (in) glpgp_px_over(im->px + 4 * ((size_t)j * (size_t)F->W + (size_t)i), c, alpha);
        }
}

static void frame_of(const glpgp_quadmesh *q, const glpgp_mesh *dm, const glpgp_render_options *o, int caption,
                     qframe *F)
{
    double bb[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    if (dm) {
        memcpy(bb, dm->bbox, sizeof bb);
    } else {
        for (int v = 0; v < q->nv; v++) {
            bb[0] = fmin(bb[0], q->xy[2 * v]);
            bb[1] = fmin(bb[1], q->xy[2 * v + 1]);
            bb[2] = fmax(bb[2], q->xy[2 * v]);
            bb[3] = fmax(bb[3], q->xy[2 * v + 1]);
        }
    }
    int margin = o->margin >= 0 ? o->margin : o->size / 64;
    double bw = bb[2] - bb[0], bh = bb[3] - bb[1], span = fmax(bw, bh);
    if (!(span > 0)) span = 1.0;
    int inner = o->size - 2 * margin;
    if (inner < 8) inner = 8;
    F->scale = inner / span;
    F->W = (int)ceil(bw * F->scale - 1e-9) + 2 * margin;
    F->H = (int)ceil(bh * F->scale - 1e-9) + 2 * margin + caption;
    if (F->W < 1) F->W = 1;
    if (F->H < 1) F->H = 1;
    F->ox = bb[0] - margin / F->scale;
    F->oy = bb[3] + margin / F->scale;
    F->lw = o->line_width > 0 ? o->line_width : fmax(1.0, 1.5 * o->size / 1024.0);
}

/* Face fill colour: red shades below sj_low, else by origin. */
static void face_colour(const glpgp_quadmesh *q, int f, double sj_low, float c[3])
{
    static const float by_origin[GLPGP_QFACE_KINDS][3] = {
        {0.93f, 0.95f, 0.99f}, {0.83f, 0.89f, 0.99f}, {1.00f, 0.88f, 0.62f}, {0.93f, 0.74f, 0.96f}};
    static const float other[3] = {0.55f, 0.55f, 0.55f}, low[3] = {1.00f, 0.45f, 0.38f},
                       bad[3] = {0.70f, 0.05f, 0.05f};
    int k = q->face_start[f + 1] - q->face_start[f];
    double sj = glpgp_quadmesh_face_sj(q, f);
    const float *s = k != 4 ? other : sj <= 0 ? bad : sj < sj_low ? low
                   : by_origin[q->face_origin && q->face_origin[f] < GLPGP_QFACE_KINDS ? q->face_origin[f] : 0];
    memcpy(c, s, 3 * sizeof(float));
}

static int cmp_ll(const void *a, const void *b)
{
    long long x = *(const long long *)a, y = *(const long long *)b;
    return (x > y) - (x < y);
}

/* Per vertex: 1 when on a boundary edge; and its angle sum over the faces. */
static glpgp_status boundary_info(const glpgp_quadmesh *q, unsigned char **bnd, double **angle)
{
    int nc = q->face_start[q->nf];
    long long *key = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)q->nv + 1, 1, bnd));
    GLPGP_CHECK(glpgp_calloc((size_t)q->nv + 1, sizeof(double), angle));
    GLPGP_CHECK(glpgp_malloc((size_t)nc + 1, sizeof(long long), &key));
    for (int f = 0; f < q->nf; f++) {
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        for (int i = 0; i < k; i++) {
            int a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % k], c = q->face_vert[s + (i + k - 1) % k];
            long long lo = a < b ? a : b, hi = a < b ? b : a;
            key[s + i] = lo * (long long)q->nv + hi;
            const double *pa = q->xy + 2 * a, *pb = q->xy + 2 * b, *pc = q->xy + 2 * c;
            double e1x = pb[0] - pa[0], e1y = pb[1] - pa[1], e2x = pc[0] - pa[0], e2y = pc[1] - pa[1];
            double ang = atan2(e1x * e2y - e1y * e2x, e1x * e2x + e1y * e2y);
            (*angle)[a] += ang < 0 ? ang + 2 * PI_ : ang;
        }
    }
    /* an edge seen once is a boundary edge */
    qsort(key, (size_t)nc, sizeof *key, cmp_ll);
    for (int i = 0; i < nc;) {
        int j = i + 1;
        while (j < nc && key[j] == key[i]) j++;
        if (j - i == 1) {
            (*bnd)[key[i] / q->nv] = 1;
            (*bnd)[key[i] % q->nv] = 1;
        }
        i = j;
    }
    free(key);
    return GLPGP_OK;
}

/* The counts of the caption. */
typedef struct qcounts {
    int quads, others, by_origin[GLPGP_QFACE_KINDS], low, irregular;
    double sj_min;
} qcounts;

static void draw_caption(glpgp_image *im, const qframe *F, int caption, const qcounts *n, double sj_low)
{
    char line[256];
    int ts = caption / 12 < 1 ? 1 : caption / 12;
    glpgp_snprintf(line, sizeof line, "%d QUADS%s  GRID %d  STRIPS %d  REPAIR %d  FALLBACK %d  SJ MIN %.2f  BELOW %.2f: %d  "
             "IRREGULAR %d", n->quads, n->others ? "(+ OTHER FACES)" : "", n->by_origin[0], n->by_origin[1],
             n->by_origin[2], n->by_origin[3], n->sj_min, sj_low, n->low, n->irregular);
    /* shrink the font until the line fits */
    while (ts > 1 && 6 * ts * (int)strlen(line) > F->W - 8) ts--;
    static const float ink[4] = {0.05f, 0.05f, 0.05f, 1.0f};
    glpgp_draw_text(im, 4, F->H - caption + (caption - 7 * ts) / 2, ts, line, ink);
}

static void draw_vertices(glpgp_image *im, float *cov, const qframe *F, const glpgp_quadmesh *q, const int *val,
                          const unsigned char *bnd, const double *angle, qcounts *n)
{
    static const float col[3][3] = {{0.05f, 0.35f, 0.95f}, {0.90f, 0.05f, 0.05f}, {0.45f, 0.0f, 0.0f}};
    double r = fmax(3.0, 2.5 * F->lw);
    for (int pass = 0; pass < 3; pass++) {
        for (int v = 0; v < q->nv; v++) {
            if (val[v] == 0) continue;
            int ideal = bnd[v] ? (int)floor(angle[v] / (0.5 * PI_) + 0.5) + 1 : 4;
            if (val[v] == ideal) continue;
            if (pass == 0) n->irregular++;
            int kind = val[v] < ideal ? 0 : val[v] == ideal + 1 ? 1 : 2;
            if (kind != pass) continue;
            double x, y, rr = bnd[v] ? 0.65 * r : r;
            to_px(F, q->xy + 2 * v, &x, &y);
            glpgp_cov_stroke(cov, F->W, F->H, x, y, x, y, 2 * (kind == 2 ? 1.3 * rr : rr));
        }
        glpgp_cov_apply(im, cov, col[pass]);
    }
}

glpgp_status glpgp_render_quadmesh(const glpgp_quadmesh *q, const glpgp_mesh *dm, const glpgp_render_options *opt,
                                   double sj_low, int caption_on, glpgp_image **out)
{
    if (!q || !out || q->nf < 1 || q->nv < 3) return GLPGP_FAIL(GLPGP_ERR_ARG, "render: empty quad mesh");
    *out = NULL;
    glpgp_render_options o;
    GLPGP_CHECK(glpgp_render_options_take(opt, &o));
    qframe F;
    int caption = caption_on ? (o.size / 48 < 12 ? 12 : o.size / 48) : 0;
    frame_of(q, dm, &o, caption, &F);
    glpgp_status st = GLPGP_OK;
    glpgp_image *im = NULL;
    float *cov = NULL;
    double *pts = NULL, *angle = NULL;
    int *val = NULL, maxk = 0;
    unsigned char *bnd = NULL;
    qcounts n;
    memset(&n, 0, sizeof n);
    n.sj_min = INFINITY;
    GLPGP_CHECK(glpgp_image_create(F.W, F.H, 4, &im));
    for (size_t i = 0; i < (size_t)F.W * (size_t)F.H; i++) {
        float *p = im->px + 4 * i;
        p[0] = p[1] = p[2] = 1.0f;
        p[3] = o.transparent ? 0.0f : 1.0f;
    }
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)F.W * (size_t)F.H, sizeof(float), &cov), done);
    for (int f = 0; f < q->nf; f++)
        if (q->face_start[f + 1] - q->face_start[f] > maxk) maxk = q->face_start[f + 1] - q->face_start[f];
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * maxk + 2, sizeof(double), &pts), done);
    /* faces, then their edges */
    for (int f = 0; f < q->nf; f++) {
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        float c[3];
        face_colour(q, f, sj_low, c);
        for (int i = 0; i < k; i++) to_px(&F, q->xy + 2 * q->face_vert[s + i], &pts[2 * i], &pts[2 * i + 1]);
        fill_poly(im, &F, pts, k, c, 1.0);
        if (k == 4) {
            double sj = glpgp_quadmesh_face_sj(q, f);
            n.quads++;
            n.sj_min = fmin(n.sj_min, sj);
            n.low += sj < sj_low;
            n.by_origin[q->face_origin && q->face_origin[f] < GLPGP_QFACE_KINDS ? q->face_origin[f] : 0]++;
        } else {
            n.others++;
        }
        for (int i = 0; i < k; i++)
            glpgp_cov_stroke(cov, F.W, F.H, pts[2 * i], pts[2 * i + 1], pts[2 * ((i + 1) % k)], pts[2 * ((i + 1) % k) + 1],
                        fmax(1.0, 0.8 * F.lw));
    }
    static const float col_e[3] = {0.15f, 0.15f, 0.20f}, col_b[3] = {0.0f, 0.0f, 0.0f};
    glpgp_cov_apply(im, cov, col_e);
    GLPGP_CHECK_GOTO(st, boundary_info(q, &bnd, &angle), done);
    /* the domain boundary (or the mesh's own), thicker */
    double bw = fmax(1.5, 1.6 * F.lw);
    if (dm) {
        for (int l = 0; l < dm->nloops; l++)
            for (int k = dm->loop_start[l]; k < dm->loop_start[l + 1]; k++) {
                int a = dm->loop_vertices[k], b = dm->loop_vertices[k + 1 < dm->loop_start[l + 1] ? k + 1 : dm->loop_start[l]];
                double ax, ay, bx, by;
                to_px(&F, dm->xy + 2 * a, &ax, &ay);
                to_px(&F, dm->xy + 2 * b, &bx, &by);
                glpgp_cov_stroke(cov, F.W, F.H, ax, ay, bx, by, bw);
            }
    } else {
        for (int f = 0; f < q->nf; f++) {
            int s = q->face_start[f], k = q->face_start[f + 1] - s;
            for (int i = 0; i < k; i++) {
                int a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % k];
                if (!bnd[a] || !bnd[b]) continue;
                double ax, ay, bx, by;
                to_px(&F, q->xy + 2 * a, &ax, &ay);
                to_px(&F, q->xy + 2 * b, &bx, &by);
                glpgp_cov_stroke(cov, F.W, F.H, ax, ay, bx, by, bw);
            }
        }
    }
    glpgp_cov_apply(im, cov, col_b);
    GLPGP_CHECK_GOTO(st, glpgp_quadmesh_valences(q, &val), done);
    draw_vertices(im, cov, &F, q, val, bnd, angle, &n);
    if (caption) {
        if (!(n.sj_min < INFINITY)) n.sj_min = 0.0;
        draw_caption(im, &F, caption, &n, sj_low);
    }
    *out = im;
    im = NULL;
done:
    glpgp_image_destroy(&im);
    free(cov);
    free(pts);
    free(angle);
    free(val);
    free(bnd);
    return st;
}
