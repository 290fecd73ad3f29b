/* quads/check_surface.c: the quality report and validity of a quad mesh of
 * a 3D surface (glpgp_quads_quality_surface, glpgp/quads.h).
 *
 * A face's own plane is its best fit through the Newell normal N (the
 * vector area); its corners' scaled Jacobians are measured in that plane
 * (N . (e_next x e_prev) / |e_next| |e_prev|), and the face is inverted
 * when one is <= 0 or N points against the input surface's normal (the
 * triangle nearest the face's centroid). Topology: every edge used by one
 * or two faces, two faces running it in opposite directions; every
 * vertex's faces one edge-connected fan; the Euler characteristic V - E + F
 * and the number of boundary loops those of the input. Geometry: the
 * two-sided Hausdorff distance between the quads (each face fanned into
 * triangles) and the input triangles, sampled on a barycentric grid of
 * spacing <= h/8 per triangle (at most 8 x 8), found through a uniform grid
 * of cells (about two mean edges) searched ring by ring up to 0.3 h (a
 * larger distance is reported as 0.3 h), at most h/4; the area within 2%
 * plus what flat faces lose on a curved surface
 * (glpgp_quads_surface_area_tolerance: an inscribed quad mesh of a unit
 * sphere at h = 0.29 has 0.977 of its area). */
#include "quads_surface.h"
#include "vec3.h"

#include "glpgp/kinds.h"
#include "glpgp/surface.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI_ GLPGP_PI


/* Squared distance from p to triangle (a, b, c) (Ericson, Real-Time Collision Detection 5.1.5). */
static double dist2_tri_x(const double *p, const double *a, const double *b, const double *c, double *x)
{
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    sub3(b, a, ab);
    sub3(c, a, ac);
    sub3(p, a, ap);
    double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
    if (d1 <= 0 && d2 <= 0) {
        memcpy(x, a, 3 * sizeof *x);
        return dot3(ap, ap);
    }
    sub3(p, b, bp);
    double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
    if (d3 >= 0 && d4 <= d3) {
        memcpy(x, b, 3 * sizeof *x);
        return dot3(bp, bp);
    }
    double vc = d1 * d4 - d3 * d2;
    double v, w;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        v = d1 / (d1 - d3);
        for (int i = 0; i < 3; i++) x[i] = a[i] + v * ab[i];
        goto out;
    }
    sub3(p, c, cp);
    double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
    if (d6 >= 0 && d5 <= d6) {
        memcpy(x, c, 3 * sizeof *x);
        return dot3(cp, cp);
    }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        w = d2 / (d2 - d6);
        for (int i = 0; i < 3; i++) x[i] = a[i] + w * ac[i];
        goto out;
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        for (int i = 0; i < 3; i++) x[i] = b[i] + w * (c[i] - b[i]);
        goto out;
    }
    {
        double den = 1.0 / (va + vb + vc);
        v = vb * den;
        w = vc * den;
        for (int i = 0; i < 3; i++) x[i] = a[i] + ab[i] * v + ac[i] * w;
    }
out:
    sub3(p, x, ap);
    return dot3(ap, ap);
}

static double dist2_tri(const double *p, const double *a, const double *b, const double *c)
{
    double x[3];
    return dist2_tri_x(p, a, b, c, x);
}

/* ---- a triangle soup with a uniform grid of cells ---------------------- */

typedef struct tsoup {
    int nt, npts;      /* triangles; points (xyz holds 3 npts) */
    const double *xyz;
    int *tri;          /* 3 nt */
    double lo[3], cs;  /* cell size */
    double cap;        /* distances are capped here (0.3 h: above the h/4 limit) */
    int dim[3];
    int *cstart, *clist;
    double *bb;        /* per triangle: its box (min x, y, z, max x, y, z) */
} tsoup;

static int cell_of(const tsoup *s, double x, int d)
{
    int i = (int)floor((x - s->lo[d]) / s->cs);
    return i < 0 ? 0 : i >= s->dim[d] ? s->dim[d] - 1 : i;
}

static double min3(double a, double b, double c)
{
    const double m = a < b ? a : b;
    return m < c ? m : c;
}

static double max3(double a, double b, double c)
{
    const double m = a > b ? a : b;
    return m > c ? m : c;
}

/* The grid's cells (one pass over the triangles for the box and the mean
 * edge, one for each triangle's cell range, kept for the two passes that
 * count and fill the cells). */
static glpgp_status soup_grid(tsoup *s, double h)
{
    double hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int d = 0; d < 3; d++) s->lo[d] = HUGE_VAL;
    double el = 0.0; /* mean edge */
    for (int t = 0; t < s->nt; t++) {
        const double *a = s->xyz + 3 * s->tri[3 * t], *b = s->xyz + 3 * s->tri[3 * t + 1],
                     *c = s->xyz + 3 * s->tri[3 * t + 2];
        for (int d = 0; d < 3; d++) {
            const double l = min3(a[d], b[d], c[d]), u = max3(a[d], b[d], c[d]);
            if (l < s->lo[d]) s->lo[d] = l;
            if (u > hi[d]) hi[d] = u;
        }
        const double *p[3] = {a, b, c};
        for (int k = 0; k < 3; k++) {
            const double *x = p[k], *y = p[(k + 1) % 3];
            el += sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) + (x[2] - y[2]) * (x[2] - y[2]));
        }
    }
    el /= 3.0 * (s->nt > 0 ? s->nt : 1);
    s->cap = 0.3 * h;
    s->cs = fmin(fmax(2.0 * el, 1e-3 * h), s->cap);
    for (;;) { /* at most ~2M cells */
        double cells = 1.0;
        for (int d = 0; d < 3; d++) cells *= floor((hi[d] - s->lo[d]) / s->cs) + 1.0;
        if (cells <= 2e6) break;
        s->cs *= 1.5;
    }
    size_t nc = 1;
    for (int d = 0; d < 3; d++) {
        s->dim[d] = (int)floor((hi[d] - s->lo[d]) / s->cs) + 1;
        nc *= (size_t)s->dim[d];
    }
    int *box = NULL; /* per triangle: its first and last cell in each direction */
    GLPGP_CHECK(glpgp_malloc((size_t)6 * s->nt + 1, sizeof(int), &box));
    glpgp_status st0 = glpgp_malloc((size_t)6 * s->nt + 1, sizeof(double), &s->bb);
    if (st0 != GLPGP_OK) {
        free(box);
        return st0;
    }
    for (int t = 0; t < s->nt; t++) {
        const double *a = s->xyz + 3 * s->tri[3 * t], *b = s->xyz + 3 * s->tri[3 * t + 1],
                     *c = s->xyz + 3 * s->tri[3 * t + 2];
        for (int d = 0; d < 3; d++) {
            s->bb[6 * t + d] = min3(a[d], b[d], c[d]);
            s->bb[6 * t + 3 + d] = max3(a[d], b[d], c[d]);
            box[6 * t + d] = cell_of(s, s->bb[6 * t + d], d);
            box[6 * t + 3 + d] = cell_of(s, s->bb[6 * t + 3 + d], d);
        }
    }
    glpgp_status st = glpgp_calloc(nc + 1, sizeof(int), &s->cstart);
    for (int pass = 0; pass < 2 && st == GLPGP_OK; pass++) {
        for (int t = 0; t < s->nt; t++) {
            const int *a = box + 6 * t, *b = a + 3;
            for (int k = a[2]; k <= b[2]; k++)
                for (int j = a[1]; j <= b[1]; j++) {
                    const size_t row = ((size_t)k * s->dim[1] + (size_t)j) * s->dim[0];
                    for (int i = a[0]; i <= b[0]; i++) {
                        if (pass == 0) s->cstart[row + i + 1]++;
                        else s->clist[s->cstart[row + i]++] = t;
                    }
                }
        }
        if (pass == 0) {
            for (size_t c = 0; c < nc; c++) s->cstart[c + 1] += s->cstart[c];
            st = glpgp_malloc((size_t)s->cstart[nc] + 1, sizeof(int), &s->clist);
        }
    }
    free(box);
    if (st != GLPGP_OK) return st;
    memmove(s->cstart + 1, s->cstart, nc * sizeof(int));
    s->cstart[0] = 0;
    return GLPGP_OK;
}

/* Squared distance from p to the soup's triangle t. */
static double soup_tri_d2(const tsoup *s, const double *p, int t)
{
    const int *v = s->tri + 3 * t;
    return dist2_tri(p, s->xyz + 3 * v[0], s->xyz + 3 * v[1], s->xyz + 3 * v[2]);
}

/* Distance from p to the soup, capped at s->cap; *tri: the nearest
 * triangle (-1: none within the cap). Rings of cells around p's cell: after
 * ring r every triangle within r cells' width has been seen. enough >= 0:
 * the search may stop once a triangle within enough is found (the result
 * is then <= enough, not the distance); enough < 0: the exact search. */
static double soup_dist_until(const tsoup *s, const double *p, double enough, int *tri)
{
    double best = s->cap * s->cap;
    const double slack = 1e-12 * s->cs * s->cs;
    int bt = -1;
    int c0[3];
    for (int d = 0; d < 3; d++) c0[d] = cell_of(s, p[d], d);
    for (int r = 0;; r++) {
        for (int k = c0[2] - r; k <= c0[2] + r; k++)
            for (int j = c0[1] - r; j <= c0[1] + r; j++)
                for (int i = c0[0] - r; i <= c0[0] + r; i++) {
                    if (abs(i - c0[0]) != r && abs(j - c0[1]) != r && abs(k - c0[2]) != r) continue;
                    if (i < 0 || j < 0 || k < 0 || i >= s->dim[0] || j >= s->dim[1] || k >= s->dim[2]) continue;
                    size_t c = ((size_t)k * s->dim[1] + (size_t)j) * s->dim[0] + (size_t)i;
                    for (int q = s->cstart[c]; q < s->cstart[c + 1]; q++) {
                        const int t = s->clist[q];
                        /* its box farther than best (with a margin over rounding): it cannot be nearer,
                         * and skipping it changes neither the result nor which triangle wins a tie */
                        const double *bb = s->bb + 6 * t;
                        double g2 = 0.0;
                        for (int d = 0; d < 3; d++) {
                            const double g = p[d] < bb[d] ? bb[d] - p[d] : p[d] > bb[3 + d] ? p[d] - bb[3 + d] : 0.0;
                            g2 += g * g;
                        }
                        if (g2 > best + 1e-9 * best + slack) continue;
                        double d2 = soup_tri_d2(s, p, t);
                        if (d2 < best) {
                            best = d2;
                            bt = t;
                            if (enough >= 0 && sqrt(best) <= enough) goto out;
                        }
                    }
                }
        const double seen = r * s->cs;
        if (seen * seen >= best || r > s->dim[0] + s->dim[1] + s->dim[2]) break;
    }
out:
    if (tri) *tri = bt;
    return sqrt(best);
}

static double soup_dist(const tsoup *s, const double *p, int *tri) { return soup_dist_until(s, p, -1.0, tri); }

static void soup_free(tsoup *s)
{
    free(s->cstart);
    free(s->clist);
    free(s->bb);
}

/* Largest distance from samples of soup a's triangles to soup b. Exact
 * (the maximum of soup_dist over the samples) but only the samples that
 * may raise it are searched in full: a sample within the largest distance
 * so far of the triangle nearest the last searched sample (the hint: the
 * samples come triangle by triangle) cannot, nor can one that the search
 * finds within it (soup_dist_until stops there); a vertex is sampled
 * once, not once per triangle (seen: a zeroed flag per point of a). Measured on a torus of
 * 400k triangles: the check went from seconds to a fraction (bench/results/surfaces_quads.md). */
typedef void (*sample_fn)(void *ctx, const double *p);

/* The check's samples of soup a's triangles (a grid of about h / 8, 1 to 8
 * steps per side; a vertex once: seen, a zeroed flag per point of a), each
 * passed to fn. */
static void for_samples(const tsoup *a, double h, unsigned char *seen, sample_fn fn, void *ctx)
{
    for (int t = 0; t < a->nt; t++) {
        const double *A = a->xyz + 3 * a->tri[3 * t], *B = a->xyz + 3 * a->tri[3 * t + 1],
                     *C = a->xyz + 3 * a->tri[3 * t + 2];
        double e[3], L = 0.0;
        sub3(B, A, e);
        L = fmax(L, sqrt(dot3(e, e)));
        sub3(C, A, e);
        L = fmax(L, sqrt(dot3(e, e)));
        int n = (int)ceil(L / (h / 8.0));
        n = n < 1 ? 1 : n > 8 ? 8 : n;
        for (int i = 0; i <= n; i++)
            for (int j = 0; i + j <= n; j++) {
                const int corner = i == 0 && j == 0 ? 0 : i == n && j == 0 ? 1 : i == 0 && j == n ? 2 : -1;
                if (corner >= 0) { /* a vertex (the sample is its point exactly): once for all its triangles */
                    const int vx = a->tri[3 * t + corner];
                    if (seen[vx]) continue;
                    seen[vx] = 1;
                }
                const double u = (double)i / n, v = (double)j / n;
                double p[3];
                for (int d = 0; d < 3; d++) p[d] = (1 - u - v) * A[d] + u * B[d] + v * C[d];
                fn(ctx, p);
            }
    }
}

typedef struct worst_ctx {
    const tsoup *b;
    double worst;
    int hint;
} worst_ctx;

static void worst_sample(void *ctx, const double *p)
{
    worst_ctx *w = ctx;
    if (w->hint >= 0 && sqrt(soup_tri_d2(w->b, p, w->hint)) <= w->worst) return;
    int bt = -1;
    w->worst = fmax(w->worst, soup_dist_until(w->b, p, w->worst, &bt));
    if (bt >= 0) w->hint = bt;
}

static double one_sided(const tsoup *a, const tsoup *b, double h, unsigned char *seen)
{
    worst_ctx w = {b, 0.0, -1};
    for_samples(a, h, seen, worst_sample, &w);
    return w.worst;
}

/* ---- topology ---------------------------------------------------------- */

typedef struct dedge {
    int a, b, f, i; /* min, max vertex; face, corner of the directed edge's start */
    int fwd;        /* 1: the face runs a -> b */
} dedge;

static int cmp_dedge(const void *pa, const void *pb)
{
    const dedge *x = pa, *y = pb;
    if (x->a != y->a) return x->a < y->a ? -1 : 1;
    if (x->b != y->b) return x->b < y->b ? -1 : 1;
    return 0;
}

/* Edges, boundary, manifoldness, pinched vertices, loops, valences. */
static glpgp_status topology(const glpgp_quadmesh *q, glpgp_quads_report *qq, unsigned char *onb)
{
    const int nc = q->face_start[q->nf];
    dedge *E = NULL;
    int *uf = NULL, *vuf = NULL, *root = NULL, *val = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof *E, &E), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc + 1, sizeof(int), &uf), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)q->nv + 1, sizeof(int), &vuf), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)q->nv + 1, sizeof(int), &root), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)q->nv + 1, sizeof(int), &val), done);
    for (int f = 0; f < q->nf; f++) {
        const int s = q->face_start[f], n = q->face_start[f + 1] - s;
        for (int i = 0; i < n; i++) {
            const int a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % n];
            E[s + i] = (dedge){a < b ? a : b, a < b ? b : a, f, i, a < b};
        }
    }
    for (int i = 0; i < nc; i++) uf[i] = i;
    for (int i = 0; i < q->nv; i++) vuf[i] = i;
    qsort(E, (size_t)nc, sizeof *E, cmp_dedge);
    for (int i = 0; i < nc;) {
        int j = i;
        while (j < nc && E[j].a == E[i].a && E[j].b == E[i].b) j++;
        qq->edges++;
        val[E[i].a]++;
        val[E[i].b]++;
        if (j - i == 1) {
            qq->boundary_edges++;
            onb[E[i].a] = onb[E[i].b] = 1;
            vuf[glpgp_uf_find(vuf, E[i].a)] = glpgp_uf_find(vuf, E[i].b);
        } else if (j - i > 2 || E[i].fwd == E[i + 1].fwd) {
            qq->nonmanifold_edges++;
        } else { /* join the corners of both faces at each end */
            for (int end = 0; end < 2; end++) {
                int cidx[2];
                for (int k = 0; k < 2; k++) {
                    const dedge *d = &E[i + k];
                    const int s = q->face_start[d->f], n = q->face_start[d->f + 1] - s;
                    const int start_is_a = d->fwd; /* the directed edge starts at a when fwd */
                    const int at_start = (end == 0) == start_is_a;
                    cidx[k] = s + (at_start ? d->i : (d->i + 1) % n);
                }
                uf[glpgp_uf_find(uf, cidx[0])] = glpgp_uf_find(uf, cidx[1]);
            }
        }
        i = j;
    }
    for (int i = 0; i < q->nv; i++) root[i] = -1;
    for (int c = 0; c < nc; c++) {
        const int v = q->face_vert[c], r = glpgp_uf_find(uf, c);
        if (root[v] < 0) root[v] = r;
        else if (root[v] != r && root[v] != -2) {
            qq->pinched++;
            root[v] = -2;
        }
    }
    for (int v = 0; v < q->nv; v++) {
        if (onb[v] && glpgp_uf_find(vuf, v) == v) qq->boundary_loops++;
        const int b = val[v] > GLPGP_QUADS_MAXVAL ? GLPGP_QUADS_MAXVAL : val[v];
        if (onb[v]) qq->valence_boundary[b]++;
        else qq->valence_interior[b]++;
        if (!onb[v] && val[v] != 4) qq->irregular_interior++;
    }
    qq->euler = q->nv - qq->edges + q->nf;
done:
    free(E);
    free(uf);
    free(vuf);
    free(root);
    free(val);
    return st;
}

/* ---- faces ------------------------------------------------------------- */


double glpgp_quadmesh_face_sj_surface(const glpgp_quadmesh *q, int f)
{
    double N[3];
    glpgp_quadmesh_face_normal(q, f, 0, N);
    const double nn = sqrt(dot3(N, N));
    if (!(nn > 0)) return -1.0;
    const int s = q->face_start[f], n = q->face_start[f + 1] - s;
    double sj = 1.0;
    for (int i = 0; i < n; i++) {
        const double *p = q->xyz + 3 * q->face_vert[s + i];
        double e1[3], e2[3], x[3];
        sub3(q->xyz + 3 * q->face_vert[s + (i + 1) % n], p, e1);
        sub3(q->xyz + 3 * q->face_vert[s + (i + n - 1) % n], p, e2);
        const double l = sqrt(dot3(e1, e1) * dot3(e2, e2));
        if (!(l > 1e-9 * nn)) return -1.0; /* a side of ~1e-9 of the face's size: its direction is rounding */
        cross3(e1, e2, x);
        sj = fmin(sj, dot3(x, N) / (nn * l));
    }
    return sj;
}

/* Per face: scaled Jacobian, orientation against the surface, area; the
 * boundary vertices' ideal valence from their corner angles. */
static void faces(const glpgp_quadmesh *q, const glpgp_mesh *m, const tsoup *in, double h,
                  const unsigned char *onb, double *angle, glpgp_quads_report *qq)
{
    double sum = 0.0;
    qq->sj_min = 1.0;
    for (int f = 0; f < q->nf; f++) {
        const int s = q->face_start[f], n = q->face_start[f + 1] - s;
        double N[3], c[3] = {0, 0, 0};
        glpgp_quadmesh_face_normal(q, f, 0, N);
        qq->area += 0.5 * sqrt(dot3(N, N));
        for (int i = 0; i < n; i++)
            for (int d = 0; d < 3; d++) c[d] += q->xyz[3 * q->face_vert[s + i] + d] / n;
        int t = -1;
        soup_dist(in, c, &t);
        const int against = t >= 0 && dot3(N, m->surf->tframe + 9 * t + 6) <= 0.0;
        const double sj = glpgp_quadmesh_face_sj_surface(q, f);
        int degen = !(sqrt(dot3(N, N)) > 1e-12 * h * h);
        for (int i = 0; i < n; i++) {
            const int a = q->face_vert[s + i];
            const double *p = q->xyz + 3 * a;
            double e1[3], e2[3];
            sub3(q->xyz + 3 * q->face_vert[s + (i + 1) % n], p, e1);
            sub3(q->xyz + 3 * q->face_vert[s + (i + n - 1) % n], p, e2);
            const double l1 = sqrt(dot3(e1, e1)), l2 = sqrt(dot3(e2, e2));
            if (!(l1 > 1e-9 * h) || a == q->face_vert[s + (i + 1) % n]) degen = 1;
            if (onb[a] && l1 > 0 && l2 > 0) angle[a] += acos(fmax(-1.0, fmin(1.0, dot3(e1, e2) / (l1 * l2))));
            qq->len_mean += l1 / h;
            qq->len_min = fmin(qq->len_min, l1 / h);
            qq->len_max = fmax(qq->len_max, l1 / h);
        }
        qq->degenerate += degen;
        if (n == 4) {
            qq->quads++;
            sum += sj;
            qq->sj_min = fmin(qq->sj_min, sj);
            if (sj < GLPGP_QUADS_SJ_GOAL) qq->below_sj_goal++;
        } else {
            qq->others++;
            qq->others_by_size[n - 3 > 7 ? 7 : n - 3 < 0 ? 0 : n - 3]++;
        }
        if (against || sj <= 0.0) qq->inverted++;
        const int o = q->face_origin ? q->face_origin[f] : GLPGP_QFACE_GRID;
        if (n == 4) qq->quads_by_origin[o < GLPGP_QFACE_KINDS ? o : 0]++;
    }
    qq->sj_mean = qq->quads ? sum / qq->quads : 0.0;
    qq->sj_p01 = qq->sj_min;
    qq->sj_min_corner = qq->sj_min;
    if (q->face_start[q->nf]) qq->len_mean /= q->face_start[q->nf];
    const int nrep = qq->quads_by_origin[GLPGP_QFACE_PAVED] + qq->quads_by_origin[GLPGP_QFACE_FALLBACK];
    qq->repaired_share = qq->quads ? (double)nrep / qq->quads : 0.0;
}

static void boundary_valence(const glpgp_quadmesh *q, const unsigned char *onb, const double *angle,
                             glpgp_quads_report *qq)
{
    int *val = NULL;
    if (glpgp_quadmesh_valences(q, &val) != GLPGP_OK) return;
    for (int v = 0; v < q->nv; v++)
        if (onb[v] && val[v] != (int)lround(angle[v] / (0.5 * PI_)) + 1) qq->irregular_boundary++;
    free(val);
}

/* The soup of q's faces fanned into triangles (tface: per triangle its
 * face, may be NULL), with its grid of cells for size h; quad_soup_free
 * releases it (also after a failure). */
static glpgp_status quad_soup(const glpgp_quadmesh *q, double h, tsoup *qs, int **tface)
{
    int nt = 0;
    memset(qs, 0, sizeof *qs);
    for (int f = 0; f < q->nf; f++) nt += q->face_start[f + 1] - q->face_start[f] - 2;
    GLPGP_CHECK(glpgp_malloc((size_t)3 * nt + 3, sizeof(int), &qs->tri));
    if (tface) GLPGP_CHECK(glpgp_malloc((size_t)nt + 1, sizeof(int), tface));
    qs->xyz = q->xyz;
    qs->npts = q->nv;
    for (int f = 0; f < q->nf; f++) {
        const int s = q->face_start[f], n = q->face_start[f + 1] - s;
        for (int i = 1; i + 1 < n; i++) {
            qs->tri[3 * qs->nt] = q->face_vert[s];
            qs->tri[3 * qs->nt + 1] = q->face_vert[s + i];
            qs->tri[3 * qs->nt + 2] = q->face_vert[s + i + 1];
            if (tface) (*tface)[qs->nt] = f;
            qs->nt++;
        }
    }
    return soup_grid(qs, h);
}

static void quad_soup_free(tsoup *qs)
{
    free(qs->tri);
    qs->tri = NULL;
    soup_free(qs);
}

static glpgp_status distances(const glpgp_quadmesh *q, const tsoup *in, double h, glpgp_quads_report *qq)
{
    tsoup qs;
    unsigned char *seen = NULL;
    glpgp_status st = quad_soup(q, h, &qs, NULL);
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)q->nv + 1, 1, &seen);
    if (st == GLPGP_OK) qq->dist_quad_to_domain = one_sided(&qs, in, h, seen) / h;
    free(seen);
    seen = NULL;
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)in->npts + 1, 1, &seen);
    if (st == GLPGP_OK) {
        qq->dist_domain_to_quad = one_sided(in, &qs, h, seen) / h;
        qq->hausdorff = fmax(qq->dist_quad_to_domain, qq->dist_domain_to_quad);
    }
    free(seen);
    quad_soup_free(&qs);
    return st;
}

typedef struct uncovered_ctx {
    const tsoup *qs;
    const int *tface;
    double thr;
    unsigned char *sel;
    int n;
} uncovered_ctx;

static void uncovered_sample(void *ctx, const double *p)
{
    uncovered_ctx *u = ctx;
    int bt = -1;
    if (soup_dist_until(u->qs, p, u->thr, &bt) <= u->thr || bt < 0) return;
    u->n += !u->sel[u->tface[bt]];
    u->sel[u->tface[bt]] = 1;
}

glpgp_status glpgp_qs_mark_uncovered(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, double thr,
                                     unsigned char *sel, int *n)
{
    tsoup qs, in;
    memset(&in, 0, sizeof in);
    in.nt = m->nt; /* its triangles sampled only: no grid */
    in.npts = m->nv;
    in.xyz = m->xyz;
    in.tri = m->tri;
    int *tface = NULL;
    unsigned char *seen = NULL;
    *n = 0;
    glpgp_status st = quad_soup(q, h, &qs, &tface);
    qs.cap = 2.0 * h; /* a far sample still finds its nearest face */
    if (st == GLPGP_OK) st = glpgp_calloc((size_t)m->nv + 1, 1, &seen);
    if (st == GLPGP_OK) {
        uncovered_ctx u = {&qs, tface, thr, sel, 0};
        for_samples(&in, h, seen, uncovered_sample, &u);
        *n = u.n;
    }
    free(seen);
    free(tface);
    quad_soup_free(&qs);
    return st;
}

struct glpgp_qs_proj {
    tsoup in;
    const glpgp_mesh *m; /* the surface (its triangles' normals) */
};

glpgp_status glpgp_qs_proj_create(const glpgp_mesh *m, double h, double cap, glpgp_qs_proj **out)
{
    *out = NULL;
    glpgp_qs_proj *P = NULL;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *P, &P));
    P->in.nt = m->nt;
    P->in.npts = m->nv;
    P->in.xyz = m->xyz;
    P->in.tri = m->tri;
    P->m = m;
    glpgp_status st = soup_grid(&P->in, h);
    P->in.cap = cap;
    if (st != GLPGP_OK) {
        glpgp_qs_proj_destroy(&P);
        return st;
    }
    *out = P;
    return GLPGP_OK;
}

int glpgp_qs_proj_nearest(const glpgp_qs_proj *P, const double *p, double *x)
{
    int t = -1;
    memcpy(x, p, 3 * sizeof *x);
    soup_dist(&P->in, p, &t);
    if (t >= 0) {
        const int *v = P->in.tri + 3 * t;
        dist2_tri_x(p, P->in.xyz + 3 * v[0], P->in.xyz + 3 * v[1], P->in.xyz + 3 * v[2], x);
    }
    return t;
}

const double *glpgp_qs_proj_normal(const glpgp_qs_proj *P, int t)
{
    return P->m->surf->tframe + 9 * t + 6;
}

void glpgp_qs_proj_destroy(glpgp_qs_proj **P)
{
    if (!P || !*P) return;
    (*P)->in.tri = NULL;
    soup_free(&(*P)->in);
    free(*P);
    *P = NULL;
}

glpgp_status glpgp_qs_project(const glpgp_mesh *m, double h, double *xyz, int first, int n)
{
    glpgp_qs_proj *P = NULL; /* cap 2 h: a chord's midpoint of a coarse mesh may be farther than the check's cap */
    GLPGP_CHECK(glpgp_qs_proj_create(m, h, 2.0 * h, &P));
    for (int i = first; i < n; i++) {
        double x[3];
        glpgp_qs_proj_nearest(P, xyz + 3 * i, x);
        memcpy(xyz + 3 * i, x, sizeof x);
    }
    glpgp_qs_proj_destroy(&P);
    return GLPGP_OK;
}

double glpgp_quads_surface_area_tolerance(const glpgp_quads_report *qq)
{
    const double d = qq->dist_quad_to_domain > 0 ? qq->dist_quad_to_domain : 0.0;
    return 0.02 + 2.0 * d * d;
}

static void verdict(glpgp_quads_report *qq)
{
    if (qq->faces == 0) qq->invalid |= GLPGP_QUADS_BAD_EMPTY;
    if (qq->inverted) qq->invalid |= GLPGP_QUADS_BAD_INVERTED;
    if (qq->degenerate) qq->invalid |= GLPGP_QUADS_BAD_DEGENERATE;
    if (qq->nonmanifold_edges) qq->invalid |= GLPGP_QUADS_BAD_NONMANIFOLD;
    if (qq->others) qq->invalid |= GLPGP_QUADS_BAD_NONQUAD;
    if (qq->pinched) qq->invalid |= GLPGP_QUADS_BAD_PINCHED;
    if (qq->boundary_loops != qq->domain_loops) qq->invalid |= GLPGP_QUADS_BAD_LOOPS;
    if (qq->euler != qq->domain_euler) qq->invalid |= GLPGP_QUADS_BAD_TOPOLOGY;
    if (fabs(qq->area_ratio - 1.0) > glpgp_quads_surface_area_tolerance(qq)) qq->invalid |= GLPGP_QUADS_BAD_AREA;
    if (qq->hausdorff > 0.25) qq->invalid |= GLPGP_QUADS_BAD_HAUSDORFF;
}

glpgp_status glpgp_quads_quality_surface(const glpgp_quadmesh *q, const glpgp_mesh *m, double h,
                                         glpgp_quads_report *qq)
{
    memset(qq, 0, sizeof *qq);
    if (!q || !q->xyz || !glpgp_mesh_is_surface(m) || !m->surf || !(h > 0))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "surface quad quality: a surface quad mesh, its surface and h > 0 are needed");
    qq->surface = 1;
    qq->h = h;
    qq->vertices = q->nv;
    qq->faces = q->nf;
    qq->len_min = HUGE_VAL;
    qq->singular[0] = q->singular_tris[0];
    qq->singular[1] = q->singular_tris[1];
    qq->closing = q->closing;
    qq->repair = q->repair;
    qq->cleanup = q->cleanup;
    qq->cross_singularities = qq->irregular_near_cross = qq->irregular_far_cross = qq->cross_matched = -1;
    qq->outside = qq->far_faces = qq->corners_lost = -1;
    qq->gap_edges = -1;
    qq->bnd_vertex_dist = -1;
    qq->orientation = 1;
    qq->domain_euler = m->surf->euler;
    qq->domain_loops = m->nloops;
    qq->domain_area = m->area;
    tsoup in;
    memset(&in, 0, sizeof in);
    in.nt = m->nt;
    in.npts = m->nv;
    in.xyz = m->xyz;
    in.tri = m->tri;
    unsigned char *onb = NULL;
    double *angle = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)q->nv + 1, 1, &onb), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)q->nv + 1, sizeof(double), &angle), done);
    if (q->nf == 0) {
        qq->len_min = 0;
        verdict(qq);
        goto done;
    }
    GLPGP_CHECK_GOTO(st, soup_grid(&in, h), done);
    GLPGP_CHECK_GOTO(st, topology(q, qq, onb), done);
    faces(q, m, &in, h, onb, angle, qq);
    boundary_valence(q, onb, angle, qq);
    qq->irregular = qq->irregular_interior + qq->irregular_boundary;
    qq->area_ratio = qq->domain_area > 0 ? qq->area / qq->domain_area : -1.0;
    GLPGP_CHECK_GOTO(st, distances(q, &in, h, qq), done);
    verdict(qq);
done:
    in.tri = NULL;
    soup_free(&in);
    free(onb);
    free(angle);
    return st;
}
