/* image/contour.c: mask image -> boundary polygons (glpgp/image.h): mask channel
 * choice, marching squares on the pixel-center grid padded with one ring of
 * outside samples (crossing points shared by neighbouring cells, linked into
 * closed loops), speck removal, Douglas-Peucker simplification, orientation
 * (domain on the left) and hole -> outer loop assignment. Memory: two rows
 * of crossing ids plus the crossing points themselves, so a 4096 x 4096 mask
 * needs little beyond its own values. */
#include "glpgp/image.h"
#include "glpgp/internal/geom2.h"
#include "glpgp/internal/grid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void glpgp_contour_options_default(glpgp_contour_options *o)
{
    o->threshold = 0.5;
    o->invert = 0;
    o->min_area = 16.0;
    o->tolerance = 0.5;
    o->pixel_size = 1.0;
}

glpgp_status glpgp_mask_values(const glpgp_image *im, float **out)
{
    if (!im || !im->px || !out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mask_values: NULL argument");
    size_t n = (size_t)im->w * (size_t)im->h;
    int nc = im->nc;
    float *v = NULL;
    GLPGP_CHECK(glpgp_malloc(n, sizeof *v, &v));
    int use_alpha = 0;
    if (im->alpha >= 0 && im->alpha < nc) {
        float a0 = im->px[im->alpha];
        for (size_t i = 1; i < n && !use_alpha; i++)
            if (im->px[i * (size_t)nc + (size_t)im->alpha] != a0) use_alpha = 1;
    }
    for (size_t i = 0; i < n; i++) {
        const float *p = im->px + i * (size_t)nc;
        float x;
        if (use_alpha)
            x = p[im->alpha];
        else if (nc >= 3 && im->alpha != 0 && im->alpha != 1 && im->alpha != 2)
            x = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
        else
            x = p[0];
        v[i] = x;
    }
    *out = v;
    return GLPGP_OK;
}

void glpgp_polygons_destroy(glpgp_polygons **p)
{
    if (!p || !*p) return;
    free((*p)->start);
    free((*p)->xy);
    free((*p)->area);
    free((*p)->parent);
    free((*p)->size);
    free(*p);
    *p = NULL;
}

/* ---- growable arrays (glpgp_grow) ---------------------------------------- */

typedef struct dbuf {
    double *a;
    size_t n, cap;
} dbuf;
typedef struct ibuf {
    int *a;
    size_t n, cap;
} ibuf;

static glpgp_status dbuf_push2(dbuf *b, double x, double y)
{
    if (b->n + 2 > b->cap) GLPGP_CHECK(glpgp_grow(&b->a, &b->cap, b->n + 2, sizeof *b->a));
    b->a[b->n++] = x;
    b->a[b->n++] = y;
    return GLPGP_OK;
}

static glpgp_status ibuf_push(ibuf *b, int x)
{
    if (b->n + 1 > b->cap) GLPGP_CHECK(glpgp_grow(&b->a, &b->cap, b->n + 1, sizeof *b->a));
    b->a[b->n++] = x;
    return GLPGP_OK;
}

/* ---- Douglas-Peucker ----------------------------------------------------- */

glpgp_status glpgp_simplify_closed(double *xy, int *np, double tol)
{
    int n = *np;
    if (n <= 3 || !(tol > 0)) return GLPGP_OK;
    /* anchors: point 0 and the point farthest from it */
    int far = 0;
    double best = -1;
    for (int i = 1; i < n; i++) {
        double dx = xy[2 * i] - xy[0], dy = xy[2 * i + 1] - xy[1];
        if (dx * dx + dy * dy > best) best = dx * dx + dy * dy, far = i;
    }
    unsigned char *keep = NULL;
    int *stack = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)n + 1, 1, &keep));
    glpgp_status st = glpgp_malloc(2 * ((size_t)n + 2), sizeof *stack, &stack);
    if (st != GLPGP_OK) {
        free(keep);
        return st;
    }
    keep[0] = keep[far] = keep[n] = 1; /* index n is point 0 again */
    int sp = 0;
    stack[sp++] = 0, stack[sp++] = far;
    stack[sp++] = far, stack[sp++] = n;
    double tol2 = tol * tol;
    while (sp > 0) {
        int b = stack[--sp], a = stack[--sp];
        if (b - a < 2) continue;
        const double *pa = xy + 2 * (a % n), *pb = xy + 2 * (b % n);
        int imax = -1;
        double dmax = tol2;
        for (int i = a + 1; i < b; i++) {
            double d = glpgp_seg_dist2(pa, pb, xy + 2 * i);
            if (d > dmax) dmax = d, imax = i;
        }
        if (imax >= 0) {
            keep[imax] = 1;
            stack[sp++] = a, stack[sp++] = imax;
            stack[sp++] = imax, stack[sp++] = b;
        }
    }
    int m = 0;
    for (int i = 0; i < n; i++)
        if (keep[i]) {
            xy[2 * m] = xy[2 * i];
            xy[2 * m + 1] = xy[2 * i + 1];
            m++;
        }
    free(keep);
    free(stack);
    *np = m;
    return GLPGP_OK;
}

/* ---- marching squares ------------------------------------------------------ */

double glpgp_polygon_area(const double *xy, int n)
{
    if (n < 1) return 0;
    double a = 0, x0 = xy[0], y0 = xy[1];
    for (int i = 0; i < n; i++) {
        int j = (i + 1) % n;
        a += (xy[2 * i] - x0) * (xy[2 * j + 1] - y0) - (xy[2 * j] - x0) * (xy[2 * i + 1] - y0);
    }
    return 0.5 * a;
}

static int point_in_loop(const double *xy, int n, double px, double py)
{
    int in = 0;
    for (int i = 0, j = n - 1; i < n; j = i++) {
        double xi = xy[2 * i], yi = xy[2 * i + 1], xj = xy[2 * j], yj = xy[2 * j + 1];
        if ((yi > py) != (yj > py) && px < (xj - xi) * (py - yi) / (yj - yi) + xi) in = !in;
    }
    return in;
}

typedef struct ms_ctx {
    const float *v;
    int w, h;
    double thr;
    int invert;
    dbuf pts;  /* crossing points, sample-grid coordinates (I, J) */
    ibuf next; /* next point along the contour, -1 until linked */
} ms_ctx;

/* Signed value of padded sample (I, J): >= 0 inside. pad: outside ring. */
static double sample(const ms_ctx *c, int I, int J, int *pad)
{
    if (I < 1 || J < 1 || I > c->w || J > c->h) {
        *pad = 1;
        return -1.0;
    }
    *pad = 0;
    double x = c->v[(size_t)(J - 1) * (size_t)c->w + (size_t)(I - 1)];
    if (isnan(x)) return -1.0;
    return c->invert ? c->thr - x - 1e-12 : x - c->thr;
}

/* Create the crossing point between samples A=(I0,J0) and B=(I1,J1). */
static glpgp_status new_point(ms_ctx *c, int I0, int J0, double f0, int pad0, int I1, int J1,
                              double f1, int pad1, int *id)
{
    double t = (pad0 || pad1) ? 0.5 : f0 / (f0 - f1);
    if (!(t >= 0.01)) t = 0.01;
    if (!(t <= 0.99)) t = 0.99;
    *id = (int)(c->pts.n / 2);
    GLPGP_CHECK(dbuf_push2(&c->pts, I0 + t * (I1 - I0), J0 + t * (J1 - J0)));
    GLPGP_CHECK(ibuf_push(&c->next, -1));
    return GLPGP_OK;
}

/* Fail on a mask with no pixel inside, or with every pixel inside (no boundary). */
static glpgp_status check_mask_coverage(const ms_ctx *c, const glpgp_contour_options *o)
{
    size_t ninside = 0, npx = (size_t)c->w * (size_t)c->h;
    for (int j = 1; j <= c->h; j++)
        for (int i = 1; i <= c->w; i++) {
            int pad;
            if (sample(c, i, j, &pad) >= 0) ninside++;
        }
    if (ninside == 0)
        return GLPGP_FAIL(GLPGP_ERR_ARG,
                          "empty mask: no pixel is inside the domain (inside = value %s %g); "
                          "check --threshold or --invert",
                          o->invert ? "<" : ">=", o->threshold);
    if (ninside == npx)
        return GLPGP_FAIL(GLPGP_ERR_ARG,
                          "every pixel of the %d x %d mask is inside the domain (inside = value "
                          "%s %g), so it has no boundary in the image; the domain must be "
                          "surrounded by outside pixels (check --threshold or --invert)",
                          c->w, c->h, o->invert ? "<" : ">=", o->threshold);
    return GLPGP_OK;
}

/* The rows of samples the marching squares keep while they walk the cells:
 * the values and padding flags of sample rows J and J+1, and the crossing
 * point already made on each horizontal edge of rows J (hid_a) and J+1
 * (hid_b) and on each vertical edge of the current cell row (vid). */
typedef struct ms_rows {
    double *f0, *f1;
    unsigned char *p0, *p1;
    int *hid_a, *hid_b, *vid;
} ms_rows;

static void ms_rows_free(ms_rows *r)
{
    free(r->f0), free(r->f1), free(r->p0), free(r->p1);
    free(r->hid_a), free(r->hid_b), free(r->vid);
}

static glpgp_status ms_rows_alloc(ms_rows *r, int w)
{
    memset(r, 0, sizeof *r);
    GLPGP_CHECK(glpgp_malloc((size_t)w + 2, sizeof(double), &r->f0));
    GLPGP_CHECK(glpgp_malloc((size_t)w + 2, sizeof(double), &r->f1));
    GLPGP_CHECK(glpgp_malloc((size_t)w + 2, 1, &r->p0));
    GLPGP_CHECK(glpgp_malloc((size_t)w + 2, 1, &r->p1));
    GLPGP_CHECK(glpgp_malloc((size_t)w + 2, sizeof(int), &r->hid_a));
    GLPGP_CHECK(glpgp_malloc((size_t)w + 2, sizeof(int), &r->hid_b));
    GLPGP_CHECK(glpgp_malloc((size_t)w + 3, sizeof(int), &r->vid));
    for (int i = 0; i < w + 2; i++) r->hid_a[i] = -1;
    return GLPGP_OK;
}

/* Cell (I, J) with corners c0 (I,J), c1 (I+1,J), c2 (I+1,J+1), c3 (I,J+1),
 * edge k joining corner k and k+1 (mod 4): make the crossing points on its
 * edges (shared with the neighbouring cells through the rows' ids) and link
 * each in->out edge to the out->in edge that continues the contour. */
static glpgp_status march_cell(ms_ctx *c, ms_rows *r, int I, int J)
{
    double f[4] = {r->f0[I], r->f0[I + 1], r->f1[I + 1], r->f1[I]};
    int in[4], mask = 0;
    for (int k = 0; k < 4; k++) {
        in[k] = f[k] >= 0;
        mask |= in[k] << k;
    }
    if (mask == 0 || mask == 15) return GLPGP_OK;
    int pad[4] = {r->p0[I], r->p0[I + 1], r->p1[I + 1], r->p1[I]};
    static const int cI[4] = {0, 1, 1, 0}, cJ[4] = {0, 0, 1, 1};
    int eid[4] = {-1, -1, -1, -1};
    for (int k = 0; k < 4; k++) {
        int k1 = (k + 1) & 3;
        if (in[k] == in[k1]) continue;
        int *slot = k == 0 ? &r->hid_a[I] : k == 1 ? &r->vid[I + 1] : k == 2 ? &r->hid_b[I] : &r->vid[I];
        if (*slot < 0)
            GLPGP_CHECK(new_point(c, I + cI[k], J + cJ[k], f[k], pad[k], I + cI[k1], J + cJ[k1], f[k1],
                                  pad[k1], slot));
        eid[k] = *slot;
    }
    /* in->out edges k (in[k] && !in[k+1]) link to an out->in edge */
    int saddle = mask == 5 || mask == 10;
    int center_in = saddle && (f[0] + f[1] + f[2] + f[3]) >= 0;
    for (int k = 0; k < 4; k++) {
        int k1 = (k + 1) & 3;
        if (!(in[k] && !in[k1])) continue;
        int target = -1;
        if (!saddle) {
            for (int q = 0; q < 4; q++)
                if (!in[q] && in[(q + 1) & 3]) target = q;
        } else {
            target = center_in ? (k + 1) & 3 : (k + 3) & 3;
        }
        if (target < 0 || eid[k] < 0 || eid[target] < 0)
            return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "marching squares: inconsistent cell");
        c->next.a[eid[k]] = eid[target];
    }
    return GLPGP_OK;
}

/* Marching squares over the cells (I, J), I in [0, w], J in [0, h], of the
 * padded sample grid: c->pts gets every crossing point, c->next its successor
 * along the contour (inside on the left). */
static glpgp_status march(ms_ctx *c)
{
    ms_rows r;
    glpgp_status st = ms_rows_alloc(&r, c->w);
    if (st != GLPGP_OK) {
        ms_rows_free(&r);
        return st;
    }
    for (int I = 0; I <= c->w + 1; I++) {
        int pad;
        r.f0[I] = sample(c, I, 0, &pad);
        r.p0[I] = (unsigned char)pad;
    }
    for (int J = 0; J <= c->h && st == GLPGP_OK; J++) {
        for (int I = 0; I <= c->w + 1; I++) {
            int pad;
            r.f1[I] = sample(c, I, J + 1, &pad);
            r.p1[I] = (unsigned char)pad;
            r.hid_b[I] = -1;
            r.vid[I] = -1;
        }
        for (int I = 0; I <= c->w && st == GLPGP_OK; I++) st = march_cell(c, &r, I, J);
        /* next cell row */
        double *tf = r.f0;
        r.f0 = r.f1, r.f1 = tf;
        unsigned char *tp = r.p0;
        r.p0 = r.p1, r.p1 = tp;
        int *th = r.hid_a;
        r.hid_a = r.hid_b, r.hid_b = th;
    }
    if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
    ms_rows_free(&r);
    return st;
}

/* Follow the links into closed loops, in pixel coordinates with y up
 * (loops: x, y pairs back to back; lstart: the first point of each loop and
 * the end), dropping loops of area below min_area square pixels. */
static glpgp_status link_loops(const ms_ctx *c, double min_area, dbuf *loops, ibuf *lstart)
{
    int npts = (int)(c->pts.n / 2);
    unsigned char *seen = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)npts + 1, 1, &seen));
    glpgp_status st = GLPGP_OK;
    for (int p0 = 0; p0 < npts && st == GLPGP_OK; p0++) {
        if (seen[p0]) continue;
        size_t first = loops->n / 2;
        for (int p = p0; !seen[p];) {
            seen[p] = 1;
            double I = c->pts.a[2 * p], J = c->pts.a[2 * p + 1];
            GLPGP_CHECK_GOTO(st, dbuf_push2(loops, I - 0.5, (double)c->h - J + 0.5), done);
            p = c->next.a[p];
            if (p < 0) {
                st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "marching squares: open contour");
                goto done;
            }
        }
        int n = (int)(loops->n / 2 - first);
        if (fabs(glpgp_polygon_area(loops->a + 2 * first, n)) < min_area || n < 3) {
            loops->n = 2 * first; /* speck (or filled-in small hole) */
            continue;
        }
        /* simplified at the end, all loops together (glpgp_polygons_simplify) */
        GLPGP_CHECK_GOTO(st, ibuf_push(lstart, (int)first), done);
    }
    GLPGP_CHECK_GOTO(st, ibuf_push(lstart, (int)(loops->n / 2)), done);
done:
    free(seen);
    return st;
}

/* Orient every loop so the domain lies on its left (outer loops counter-
 * clockwise) and give each hole the smallest outer loop containing it. */
static void orient_and_nest(glpgp_polygons *P)
{
    const int nl = P->n;
    double total = 0;
    for (int l = 0; l < nl; l++) {
        P->area[l] = glpgp_polygon_area(P->xy + 2 * P->start[l], P->start[l + 1] - P->start[l]);
        total += P->area[l];
    }
    if (total < 0) {
        for (int l = 0; l < nl; l++) {
            double *xy = P->xy + 2 * P->start[l];
            int n = P->start[l + 1] - P->start[l];
            for (int i = 0, k = n - 1; i < k; i++, k--) {
                double tx = xy[2 * i], ty = xy[2 * i + 1];
                xy[2 * i] = xy[2 * k], xy[2 * i + 1] = xy[2 * k + 1];
                xy[2 * k] = tx, xy[2 * k + 1] = ty;
            }
            P->area[l] = -P->area[l];
        }
    }
    P->nouter = P->nholes = 0;
    for (int l = 0; l < nl; l++) {
        P->parent[l] = -1;
        if (P->area[l] > 0) {
            P->nouter++;
            continue;
        }
        P->nholes++;
        const double *hp = P->xy + 2 * P->start[l];
        double best = INFINITY;
        for (int q = 0; q < nl; q++) {
            if (!(P->area[q] > 0) || P->area[q] >= best) continue;
            if (point_in_loop(P->xy + 2 * P->start[q], P->start[q + 1] - P->start[q], hp[0], hp[1])) {
                best = P->area[q];
                P->parent[l] = q;
            }
        }
    }
}

/* The polygons of the loops, oriented and nested, in physical units. */
static glpgp_status polygons_of_loops(const dbuf *loops, const ibuf *lstart, double s, glpgp_polygons **out)
{
    int nl = (int)lstart->n - 1;
    glpgp_polygons *P = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *P, &P));
    P->n = nl;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nl + 1, sizeof(int), &P->start), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(loops->n + 1, sizeof(double), &P->xy), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nl + 1, sizeof(double), &P->area), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nl + 1, sizeof(int), &P->parent), fail);
    memcpy(P->start, lstart->a, ((size_t)nl + 1) * sizeof(int));
    if (loops->n) memcpy(P->xy, loops->a, loops->n * sizeof(double));
    orient_and_nest(P);
    for (size_t i = 0; i < loops->n; i++) P->xy[i] *= s;
    P->total_area = 0;
    for (int l = 0; l < nl; l++) {
        P->area[l] *= s * s;
        P->total_area += P->area[l];
    }
    *out = P;
    return GLPGP_OK;
fail:
    glpgp_polygons_destroy(&P);
    return st;
}

glpgp_status glpgp_contours(const float *v, int w, int h, const glpgp_contour_options *opt,
                            glpgp_polygons **out)
{
    if (!v || !out || w <= 0 || h <= 0) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_contours: bad arguments");
    *out = NULL;
    glpgp_contour_options o;
    if (opt)
        o = *opt;
    else
        glpgp_contour_options_default(&o);
    if (!isfinite(o.threshold))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "threshold %g is not a finite number", o.threshold);
    if (!(o.pixel_size > 0)) return GLPGP_FAIL(GLPGP_ERR_ARG, "pixel size %g must be positive", o.pixel_size);

    ms_ctx c;
    memset(&c, 0, sizeof c);
    c.v = v;
    c.w = w;
    c.h = h;
    c.thr = o.threshold;
    c.invert = o.invert;
    GLPGP_CHECK(check_mask_coverage(&c, &o));

    glpgp_status st = GLPGP_OK;
    glpgp_polygons *P = NULL;
    dbuf loops = {0};
    ibuf lstart = {0};
    GLPGP_CHECK_GOTO(st, march(&c), done);
    GLPGP_CHECK_GOTO(st, link_loops(&c, o.min_area, &loops, &lstart), done);
    GLPGP_CHECK_GOTO(st, polygons_of_loops(&loops, &lstart, o.pixel_size, &P), done);
    if (P->nouter == 0) {
        st = GLPGP_FAIL(GLPGP_ERR_ARG, "the mask has no region of at least %g square pixels (only specks)",
                        o.min_area);
        goto done;
    }
    for (int l = 0; l < P->n; l++)
        if (P->area[l] < 0 && P->parent[l] < 0) {
            st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "contour: hole %d lies in no outer boundary", l);
            goto done;
        }
    /* Douglas-Peucker without changing the topology (a loop that would cross
     * or touch another is simplified less) */
    if (o.tolerance > 0)
        GLPGP_CHECK_GOTO(st, glpgp_polygons_simplify(P, o.tolerance * o.pixel_size,
                                                     GLPGP_CONTOUR_MIN_DIST * o.pixel_size),
                         done);
    *out = P;
    P = NULL;
done:
    glpgp_polygons_destroy(&P);
    free(loops.a);
    free(lstart.a);
    free(c.pts.a);
    free(c.next.a);
    return st;
}

/* ---- topology checks and topology-preserving simplification --------------- */

typedef struct seg_ref {
    double xmin;
    int loop, i; /* segment from point i to point i + 1 (mod n) of loop */
} seg_ref;

static int cmp_seg(const void *a, const void *b)
{
    double x = ((const seg_ref *)a)->xmin, y = ((const seg_ref *)b)->xmin;
    return (x > y) - (x < y);
}

/* Problems between the boundary segments of p: two segments that cross or
 * touch, non-adjacent segments closer than min_dist, adjacent segments that
 * fold back onto each other (a spike narrower than min_dist) or have zero
 * length. Sweep over the segments sorted by their smallest x: each segment is
 * tested against those whose x-range overlaps its own (widened by min_dist).
 * bad (p->n flags, may be NULL) marks every loop involved. Returns the number
 * of problems (-1: out of memory, recorded); the first one's position is
 * where[0..1] and *cross tells whether it is a crossing (1) or a
 * near-contact (0). */
static long polygon_problems(const glpgp_polygons *p, double min_dist, unsigned char *bad,
                             double where[2], int *cross)
{
    const int ns = p->start[p->n];
    seg_ref *sg = NULL;
    if (ns <= 0) return 0;
    if (glpgp_malloc((size_t)ns, sizeof *sg, &sg) != GLPGP_OK) return -1;
    for (int l = 0; l < p->n; l++)
        for (int k = p->start[l]; k < p->start[l + 1]; k++) {
            int n = p->start[l + 1] - p->start[l], i = k - p->start[l];
            int k1 = p->start[l] + (i + 1) % n;
            sg[k].xmin = fmin(p->xy[2 * k], p->xy[2 * k1]);
            sg[k].loop = l;
            sg[k].i = i;
        }
    qsort(sg, (size_t)ns, sizeof *sg, cmp_seg);
    const double d2 = min_dist * min_dist;
    long count = 0;
    for (int s = 0; s < ns; s++) {
        const int la = sg[s].loop, na = p->start[la + 1] - p->start[la];
        const double *a0 = p->xy + 2 * (p->start[la] + sg[s].i);
        const double *a1 = p->xy + 2 * (p->start[la] + (sg[s].i + 1) % na);
        const double axmax = fmax(a0[0], a1[0]) + min_dist;
        const double aymin = fmin(a0[1], a1[1]) - min_dist, aymax = fmax(a0[1], a1[1]) + min_dist;
        int problem = 0, is_cross = 0;
        double px = a0[0], py = a0[1];
        if ((a1[0] - a0[0]) * (a1[0] - a0[0]) + (a1[1] - a0[1]) * (a1[1] - a0[1]) < d2) problem = 1;
        for (int t = s + 1; t < ns && !problem && sg[t].xmin <= axmax; t++) {
            const int lb = sg[t].loop, nb = p->start[lb + 1] - p->start[lb];
            const double *b0 = p->xy + 2 * (p->start[lb] + sg[t].i);
            const double *b1 = p->xy + 2 * (p->start[lb] + (sg[t].i + 1) % nb);
            if (fmax(b0[1], b1[1]) < aymin || fmin(b0[1], b1[1]) > aymax) continue;
            int next = la == lb && (sg[t].i == (sg[s].i + 1) % na); /* a1 == b0 */
            int prev = la == lb && (sg[s].i == (sg[t].i + 1) % na); /* b1 == a0 */
            if (next && prev) { /* a loop of two points */
                problem = 1;
            } else if (next) { /* fold back: b1 close to segment a, or a0 close to b */
                problem = glpgp_seg_dist2(a0, a1, b1) < d2 || glpgp_seg_dist2(b0, b1, a0) < d2;
            } else if (prev) {
                problem = glpgp_seg_dist2(b0, b1, a1) < d2 || glpgp_seg_dist2(a0, a1, b0) < d2;
            } else {
                double o1 = glpgp_orient2(a0, a1, b0), o2 = glpgp_orient2(a0, a1, b1);
                double o3 = glpgp_orient2(b0, b1, a0), o4 = glpgp_orient2(b0, b1, a1);
                if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) {
                    problem = is_cross = 1;
                } else {
                    double m = fmin(fmin(glpgp_seg_dist2(a0, a1, b0), glpgp_seg_dist2(a0, a1, b1)),
                                    fmin(glpgp_seg_dist2(b0, b1, a0), glpgp_seg_dist2(b0, b1, a1)));
                    problem = m < d2;
                }
            }
            if (problem) {
                if (is_cross) { /* the crossing point: a0 + t (a1 - a0), t = o3 / (o3 - o4) */
                    double o3 = glpgp_orient2(b0, b1, a0), o4 = glpgp_orient2(b0, b1, a1), tc = o3 / (o3 - o4);
                    px = a0[0] + tc * (a1[0] - a0[0]);
                    py = a0[1] + tc * (a1[1] - a0[1]);
                } else { /* the endpoint closest to the other segment */
                    const double *cand[4] = {b0, b1, a0, a1};
                    const double *s0[4] = {a0, a0, b0, b0}, *s1[4] = {a1, a1, b1, b1};
                    double best = INFINITY;
                    for (int c = 0; c < 4; c++) {
                        double d = glpgp_seg_dist2(s0[c], s1[c], cand[c]);
                        if (d < best) best = d, px = cand[c][0], py = cand[c][1];
                    }
                }
                if (bad) bad[lb] = 1;
            }
        }
        if (problem) {
            if (bad) bad[la] = 1;
            if (count == 0) {
                where[0] = px;
                where[1] = py;
                *cross = is_cross;
            }
            count++;
        }
    }
    free(sg);
    return count;
}

glpgp_status glpgp_polygons_check(const glpgp_polygons *p, double min_dist)
{
    if (!p) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_polygons_check: NULL argument");
    for (int l = 0; l < p->n; l++)
        if (p->start[l + 1] - p->start[l] < 3)
            return GLPGP_FAIL(GLPGP_ERR_MESH, "boundary loop %d has fewer than 3 points", l);
    for (int i = 0; i < 2 * p->start[p->n]; i++)
        if (!isfinite(p->xy[i]))
            return GLPGP_FAIL(GLPGP_ERR_MESH, "boundary point %d is not finite", i / 2);
    double where[2] = {0, 0};
    int cross = 0;
    long n = polygon_problems(p, min_dist, NULL, where, &cross);
    if (n < 0) {
        glpgp_error_push_trace(__FILE__, __LINE__);
        return GLPGP_ERR_NOMEM;
    }
    if (n > 0 && cross)
        return GLPGP_FAIL(GLPGP_ERR_MESH, "the boundary crosses itself near (%.6g, %.6g) (%ld place%s)",
                          where[0], where[1], n, n == 1 ? "" : "s");
    if (n > 0)
        return GLPGP_FAIL(GLPGP_ERR_MESH,
                          "the boundary touches itself near (%.6g, %.6g): points closer than %.3g (%ld place%s)",
                          where[0], where[1], min_dist, n, n == 1 ? "" : "s");
    return GLPGP_OK;
}

/* Loop bounding boxes in a grid of boxes (glpgp/internal/grid.h), to find
 * the loops that may contain a point. */
typedef struct loop_grid {
    glpgp_bgrid g;
    double *box; /* 4 per loop: xmin, ymin, xmax, ymax */
    int *cand, ncap;
} loop_grid;

static void grid_free(loop_grid *G)
{
    glpgp_bgrid_free(&G->g);
    free(G->box);
    free(G->cand);
    memset(G, 0, sizeof *G);
}

static glpgp_status grid_build(loop_grid *G, const glpgp_polygons *p)
{
    memset(G, 0, sizeof *G);
    const int nl = p->n;
    GLPGP_CHECK(glpgp_malloc(4 * (size_t)nl + 4, sizeof(double), &G->box));
    double all[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (int l = 0; l < nl; l++) {
        double *b = G->box + 4 * l;
        b[0] = b[1] = INFINITY;
        b[2] = b[3] = -INFINITY;
        for (int k = p->start[l]; k < p->start[l + 1]; k++) {
            b[0] = fmin(b[0], p->xy[2 * k]);
            b[1] = fmin(b[1], p->xy[2 * k + 1]);
            b[2] = fmax(b[2], p->xy[2 * k]);
            b[3] = fmax(b[3], p->xy[2 * k + 1]);
        }
        for (int c = 0; c < 2; c++) {
            all[c] = fmin(all[c], b[c]);
            all[c + 2] = fmax(all[c + 2], b[c + 2]);
        }
    }
    /* about sqrt(nl) cells a side */
    const double g = fmin(256.0, ceil(sqrt((double)nl)) + 1);
    glpgp_status st = glpgp_bgrid_build(&G->g, G->box, nl, fmax(all[2] - all[0], all[3] - all[1]) / g);
    if (st != GLPGP_OK) {
        grid_free(G);
        glpgp_error_push_trace(__FILE__, __LINE__);
    }
    return st;
}

/* Number of loops of p other than l containing point x (grid G of p); -1
 * when out of memory (recorded). */
static int containing_loops(loop_grid *G, const glpgp_polygons *p, int l, const double *x)
{
    const int n = glpgp_bgrid_query(&G->g, x[0], x[1], x[0], x[1], &G->cand, &G->ncap);
    if (n < 0) {
        GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory");
        return -1;
    }
    int depth = 0;
    for (int k = 0; k < n; k++) {
        int q = G->cand[k];
        const double *b = G->box + 4 * q;
        if (q == l || x[0] < b[0] || x[0] > b[2] || x[1] < b[1] || x[1] > b[3]) continue;
        depth += point_in_loop(p->xy + 2 * p->start[q], p->start[q + 1] - p->start[q], x[0], x[1]);
    }
    return depth;
}

glpgp_status glpgp_polygons_simplify(glpgp_polygons *p, double tol, double min_dist)
{
    if (!p) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_polygons_simplify: NULL argument");
    if (!(tol > 0) || p->n == 0) return GLPGP_OK;
    const int nl = p->n, np = p->start[nl];
    glpgp_status st = GLPGP_OK;
    double *raw = NULL, *ltol = NULL;
    int *rstart = NULL, *depth = NULL;
    unsigned char *bad = NULL;
    loop_grid G;
    memset(&G, 0, sizeof G);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(2 * (size_t)np + 2, sizeof(double), &raw), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nl + 1, sizeof(int), &rstart), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nl + 1, sizeof(double), &ltol), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nl + 1, sizeof(int), &depth), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nl + 1, 1, &bad), done);
    memcpy(raw, p->xy, 2 * (size_t)np * sizeof(double));
    memcpy(rstart, p->start, ((size_t)nl + 1) * sizeof(int));
    /* nesting depth of every loop's first point (kept by the simplification) */
    GLPGP_CHECK_GOTO(st, grid_build(&G, p), done);
    for (int l = 0; l < nl; l++) {
        depth[l] = containing_loops(&G, p, l, raw + 2 * rstart[l]);
        ltol[l] = tol;
        if (depth[l] < 0) GLPGP_CHECK_GOTO(st, GLPGP_ERR_NOMEM, done);
    }
    grid_free(&G);
    for (int round = 0;; round++) {
        /* every loop simplified from its raw points with its own tolerance */
        int w = 0;
        for (int l = 0; l < nl; l++) {
            int n = rstart[l + 1] - rstart[l];
            memmove(p->xy + 2 * (size_t)w, raw + 2 * (size_t)rstart[l], 2 * (size_t)n * sizeof(double));
            GLPGP_CHECK_GOTO(st, glpgp_simplify_closed(p->xy + 2 * (size_t)w, &n, ltol[l]), done);
            p->start[l] = w;
            double a0 = glpgp_polygon_area(raw + 2 * (size_t)rstart[l], rstart[l + 1] - rstart[l]);
            double a1 = glpgp_polygon_area(p->xy + 2 * (size_t)w, n);
            /* a loop must keep 3 points, its orientation and most of its area */
            bad[l] = n < 3 || !(a0 * a1 > 0) || !(fabs(a1) >= 0.5 * fabs(a0));
            w += n;
        }
        p->start[nl] = w;
        double where[2];
        int cross;
        if (polygon_problems(p, min_dist, bad, where, &cross) < 0) {
            st = GLPGP_ERR_NOMEM;
            glpgp_error_push_trace(__FILE__, __LINE__);
            goto done;
        }
        GLPGP_CHECK_GOTO(st, grid_build(&G, p), done);
        for (int l = 0; l < nl; l++) {
            const int d = containing_loops(&G, p, l, p->xy + 2 * (size_t)p->start[l]);
            if (d < 0) GLPGP_CHECK_GOTO(st, GLPGP_ERR_NOMEM, done);
            if (d != depth[l]) bad[l] = 1;
        }
        grid_free(&G);
        int nbad = 0, stuck = 0;
        for (int l = 0; l < nl; l++) {
            if (!bad[l]) continue;
            nbad++;
            if (ltol[l] == 0.0) stuck++;
            /* a quarter of the tolerance, down to none */
            ltol[l] = ltol[l] < tol / 1000.0 ? 0.0 : 0.25 * ltol[l];
        }
        if (nbad == 0) break;
        if (stuck == nbad) { /* the loops themselves are the problem */
            memcpy(p->xy, raw, 2 * (size_t)np * sizeof(double));
            memcpy(p->start, rstart, ((size_t)nl + 1) * sizeof(int));
            GLPGP_CHECK_GOTO(st, glpgp_polygons_check(p, min_dist), done);
            /* (only a loop's own area or orientation: not a topology problem) */
            break;
        }
    }
    p->total_area = 0;
    for (int l = 0; l < nl; l++) {
        p->area[l] = glpgp_polygon_area(p->xy + 2 * (size_t)p->start[l], p->start[l + 1] - p->start[l]);
        p->total_area += p->area[l];
    }
done:
    grid_free(&G);
    free(raw);
    free(rstart);
    free(ltol);
    free(depth);
    free(bad);
    return st;
}
