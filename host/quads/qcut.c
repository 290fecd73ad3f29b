/* quads/qcut.c: the cut mesher (qcut.h): an all-quad mesh of a polygonal
 * region with holes, all of whose boundary points are kept, by recursive
 * straight cuts -- the decomposition of submapping and of Joe's and
 * Talbert-Parkinson's quadrilateral meshers, with the cut points spaced so
 * that the pieces end as quads of about the local size.
 *
 * A piece is a loop (counter-clockwise) with the holes inside it (clockwise),
 * an even number of points in all. Until it is a single loop:
 *  - a hole is joined to the nearest other loop by two cuts (straight
 *    segments between a point of each, crossing nothing, with new points on
 *    them at the local spacing; the second cut's point count makes the
 *    parts even): joined to the outer loop, the piece falls into two pieces;
 *    joined to another hole, the part between the two holes is a piece and
 *    the rest keeps one merged hole.
 * A single loop of n points:
 *  - n <= 16: the best split into quads by its diagonals (dynamic
 *    programme, geom.c), or around one center point (an octagon into four
 *    quads, a hexagon into three), is taken when its smallest corner scaled
 *    Jacobian reaches SPLIT_OK;
 *  - else (or when no split is good enough) the best cut is made: cuts
 *    start at a loop point i whose angle a_i is not a corner (a_i >= 150
 *    degrees), in the directions that split a_i in half or leave 90
 *    degrees on one side, and end at a point j near where that ray first
 *    meets the loop; the score adds, for the four angles the cut leaves at
 *    i and j, the squared distance to 90 or 180 degrees (angles below 60
 *    degrees cost much more), the squared log of the cut's point spacing
 *    over the local size, and for parts of at most 8 points the quality of
 *    their best split; reflex points (above 200 degrees) earn a bonus, they
 *    must be cut sooner or later. The cut gets k points so that both parts
 *    are even;
 *  - when no cut is possible, the split of a small loop is taken if its
 *    corners are positive, a quad with a reflex or flat corner becomes five
 *    quads around a shrunk copy (shrunk towards its centroid, or for a dart
 *    towards a point on a corner's inward bisector); otherwise the mesher
 *    fails (GLPGP_ERR_NUMERIC).
 * The local size is min(h, min over the input loop points of s_p + G d),
 * s_p the mean length of the loop edges at p, G = GRADE: quads grow from the
 * loops' spacing to h. Cuts from straight loop points across a piece give
 * a structured layout where the region allows one (every cut point is met
 * from both sides); irregular points are left at reflex corners, where cuts
 * meet at an angle, and by the small-loop templates. The caller smooths
 * the new points. */
#include "qcut_impl.h"
#include "glpgp/util.h"

#include <math.h>
#include <string.h>

#define GRADE 0.5          /* size growth per unit distance from the loops */
#define SPLIT_OK 0.45      /* a small loop's split taken at once above this */
#define CORNER_DEG 150.0   /* no cut starts at a point whose angle is below this */
#define REFLEX_DEG 200.0



static void piece_free(qc_piece *p)
{
    ivec_free(&p->outer);
    for (int k = 0; k < p->nh; k++) ivec_free(&p->holes[k]);
    free(p->holes);
    memset(p, 0, sizeof *p);
}

static glpgp_status push_piece(qc *c, qc_piece *p)
{
    if (c->nstack == c->capstack) {
        int n = c->capstack ? 2 * c->capstack : 16;
        qc_piece *s = realloc(c->stack, (size_t)n * sizeof *s);
        if (!s) {
            piece_free(p);
            return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quads: out of memory");
        }
        c->stack = s;
        c->capstack = n;
    }
    c->stack[c->nstack++] = *p;
    memset(p, 0, sizeof *p);
    return GLPGP_OK;
}

static glpgp_status add_hole(qc_piece *p, ivec *h)
{
    ivec *n = realloc(p->holes, (size_t)(p->nh + 1) * sizeof *n);
    if (!n) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "quads: out of memory");
    p->holes = n;
    p->holes[p->nh++] = *h;
    memset(h, 0, sizeof *h);
    return GLPGP_OK;
}

/* ---- geometry --------------------------------------------------------------- */

static double loop_area(const qc *c, const ivec *L)
{
    double s = 0.0;
    const double *o = P(c, L->p[0]);
    for (int i = 1; i + 1 < L->n; i++) s += 0.5 * glpgp_orient2(o, P(c, L->p[i]), P(c, L->p[i + 1]));
    return s;
}

/* Angle (radians, [0, 2 pi)) from direction u counter-clockwise to v. */
static double ccw_angle(double ux, double uy, double vx, double vy)
{
    double a = atan2(ux * vy - uy * vx, ux * vx + uy * vy);
    return a < 0 ? a + 2 * QC_PI : a;
}

/* Interior angle at position i of loop L (region on the left). */
double glpgp_qc_loop_angle(const qc *c, const ivec *L, int i)
{
    const double *a = P(c, L->p[(i + L->n - 1) % L->n]), *b = P(c, L->p[i]), *n = P(c, L->p[(i + 1) % L->n]);
    double a0 = ccw_angle(n[0] - b[0], n[1] - b[1], a[0] - b[0], a[1] - b[1]);
    return a0 == 0.0 ? 2 * QC_PI : a0;
}

static int same_point(const double *a, const double *b) { return a[0] == b[0] && a[1] == b[1]; }

/* The local size at (x, y). */
static double qc_size(qc *c, double x, double y)
{
    double r = c->h / GRADE, s = c->h;
    int n = glpgp_bgrid_query(&c->G, x - r, y - r, x + r, y + r, &c->cand, &c->ncap);
    for (int i = 0; i < n; i++) {
        const double *q = c->src + 3 * c->cand[i];
        if (q[2] >= s) continue; /* cannot lower s */
        const double dx = q[0] - x, dy = q[1] - y, d2 = dx * dx + dy * dy, reach = (s - q[2]) / GRADE;
        if (d2 >= reach * reach) continue; /* too far to lower s */
        s = q[2] + GRADE * sqrt(d2);
    }
    return s;
}

static glpgp_status build_sizes(qc *c, const qcut_region *R)
{
    int n = R->loop_start[R->nloops];
    double *box = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)3 * n + 3, sizeof(double), &c->src));
    GLPGP_CHECK(glpgp_malloc((size_t)4 * n + 4, sizeof(double), &box));
    for (int l = 0; l < R->nloops; l++) {
        int s = R->loop_start[l], m = R->loop_start[l + 1] - s;
        for (int i = 0; i < m; i++) {
            const double *a = P(c, R->loop_v[s + (i + m - 1) % m]), *b = P(c, R->loop_v[s + i]),
                         *d = P(c, R->loop_v[s + (i + 1) % m]);
            double *q = c->src + 3 * (s + i);
            q[0] = b[0];
            q[1] = b[1];
            q[2] = fmin(c->h, 0.5 * (hypot(a[0] - b[0], a[1] - b[1]) + hypot(d[0] - b[0], d[1] - b[1])));
            box[4 * (s + i)] = box[4 * (s + i) + 2] = b[0];
            box[4 * (s + i) + 1] = box[4 * (s + i) + 3] = b[1];
        }
    }
    c->ns = n;
    glpgp_status st = glpgp_bgrid_build(&c->G, box, n, c->h);
    free(box);
    return st;
}

/* ---- visibility --------------------------------------------------------------- */

/* Whether segment a b crosses an edge of loop L or passes through one of
 * its points (points at a or b excepted). */
static int blocked_by(const qc *c, const ivec *L, const double *a, const double *b, double eps)
{
    /* an edge whose box misses the segment's (grown by eps) can neither be
     * crossed nor have its first point within eps */
    const double x0 = fmin(a[0], b[0]) - eps, x1 = fmax(a[0], b[0]) + eps;
    const double y0 = fmin(a[1], b[1]) - eps, y1 = fmax(a[1], b[1]) + eps;
    for (int i = 0; i < L->n; i++) {
        const double *p = P(c, L->p[i]), *q = P(c, L->p[(i + 1) % L->n]);
        if ((p[0] < x0 && q[0] < x0) || (p[0] > x1 && q[0] > x1) || (p[1] < y0 && q[1] < y0) ||
            (p[1] > y1 && q[1] > y1))
            continue;
        int pa = same_point(p, a) || same_point(p, b), qa = same_point(q, a) || same_point(q, b);
        if (!pa && glpgp_seg_dist(a, b, p, NULL) <= eps) return 1;
        if (pa || qa) continue;
        if (glpgp_seg_cross(a, b, p, q, 0.0)) return 1;
    }
    return 0;
}

int glpgp_qc_visible(const qc *c, const qc_piece *pc, int ia, int ib)
{
    const double *a = P(c, ia), *b = P(c, ib);
    double eps = 1e-9 * hypot(b[0] - a[0], b[1] - a[1]);
    if (same_point(a, b) || blocked_by(c, &pc->outer, a, b, eps)) return 0;
    for (int k = 0; k < pc->nh; k++)
        if (blocked_by(c, &pc->holes[k], a, b, eps)) return 0;
    return 1;
}

/* First loop edge hit by the ray from point o in direction (dx, dy):
 * *loop (-1 outer, else a hole index) and *pos (the edge from position pos
 * to pos + 1). Returns the ray parameter, or INFINITY. */
static double ray_hit(const qc *c, const qc_piece *pc, int o, double dx, double dy, int *loop, int *pos)
{
    const double *a = P(c, o);
    double best = INFINITY;
    for (int k = -1; k < pc->nh; k++) {
        const ivec *L = k < 0 ? &pc->outer : &pc->holes[k];
        for (int i = 0; i < L->n; i++) {
            const double *p = P(c, L->p[i]), *q = P(c, L->p[(i + 1) % L->n]);
            if (same_point(p, a) || same_point(q, a)) continue;
            double ex = q[0] - p[0], ey = q[1] - p[1], den = dx * ey - dy * ex;
            if (fabs(den) < 1e-300) continue;
            double wx = p[0] - a[0], wy = p[1] - a[1];
            double t = (wx * ey - wy * ex) / den, s = (wx * dy - wy * dx) / den;
            if (t > 0 && s >= 0 && s <= 1 && t < best) {
                best = t;
                *loop = k;
                *pos = i;
            }
        }
    }
    return best;
}

/* ---- cuts ------------------------------------------------------------------------ */

/* Cost of an angle left at a cut end (degrees). */
static double angle_cost(double deg)
{
    double d = fmin(fabs(deg - 90.0), fabs(deg - 180.0));
    double c = (d / 45.0) * (d / 45.0);
    if (deg < 60.0) c += 4.0 * ((60.0 - deg) / 30.0) * ((60.0 - deg) / 30.0);
    if (deg < 20.0) c += 50.0;
    return c;
}

typedef struct cut {
    int li, i, lj, j; /* loop (-1 outer) and position of the two ends */
    int k;            /* points on the cut */
    double cost;
} cut;

/* Points on the segment from point a to point b for k, spaced from the
 * local size at a to that at b; the number of cells at the local size. */
static double cut_cells(qc *c, const double *a, const double *b)
{
    double L = hypot(b[0] - a[0], b[1] - a[1]);
    double sa = qc_size(c, a[0], a[1]), sb = qc_size(c, b[0], b[1]);
    double sm = qc_size(c, 0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]));
    return L * (1.0 / sa + 4.0 / sm + 1.0 / sb) / 6.0;
}

/* k for a cut of ncell cells whose first part has base points (even
 * parts: base + k even). */
static int cut_points(double ncell, int base)
{
    int k = (int)floor(ncell + 0.5) - 1;
    if (k < 0) k = 0;
    if ((base + k) % 2) {
        /* k - 1 or k + 1, whichever spacing is closer */
        if (k > 0 && fabs(log(k / ncell)) < fabs(log((k + 2) / ncell)))
            k--;
        else
            k++;
    }
    return k;
}

/* Positions of the k points of a cut from point ia to point ib, spaced
 * from the local size at a to that at b (cell widths interpolated along the
 * cut): out[2 t], out[2 t + 1], t < k. */
#define MAXCUT 4096
static void cut_positions(qc *c, int ia, int ib, int k, double *out)
{
    const double *a = P(c, ia), *b = P(c, ib);
    double sa = qc_size(c, a[0], a[1]), sb = qc_size(c, b[0], b[1]);
    double wsum = 0.5 * (sa + sb) * (k + 1), acc = 0.0;
    for (int t = 0; t < k; t++) {
        double u = (t + 0.5) / (k + 1);
        acc += (sa + u * (sb - sa)) / wsum;
        out[2 * t] = a[0] + acc * (b[0] - a[0]);
        out[2 * t + 1] = a[1] + acc * (b[1] - a[1]);
    }
}

/* Angles a cut from point o (loop angle aa, previous point pv, next nx)
 * in direction d leaves: *a1 between next and d, *a2 between d and prev.
 * Returns 0 when d is not inside the angle. */
static int split_angle(const double *o, const double *nx, double aa, const double *d, double *a1, double *a2)
{
    double t = ccw_angle(nx[0] - o[0], nx[1] - o[1], d[0] - o[0], d[1] - o[1]);
    if (!(t > 1e-9) || !(t < aa - 1e-9)) return 0;
    *a1 = t * 180.0 / QC_PI;
    *a2 = (aa - t) * 180.0 / QC_PI;
    return 1;
}

static const ivec *loop_of(const qc_piece *pc, int l) { return l < 0 ? &pc->outer : &pc->holes[l]; }

/* Angle cost of a cut between loop positions (li, i) and (lj, j), or
 * INFINITY when the cut leaves either angle. */
static double ends_cost(const qc *c, const qc_piece *pc, int li, int i, int lj, int j)
{
    const ivec *A = loop_of(pc, li), *B = loop_of(pc, lj);
    const double *pa = P(c, A->p[i]), *pb = P(c, B->p[j]);
    double aa = glpgp_qc_loop_angle(c, A, i), ab = glpgp_qc_loop_angle(c, B, j), a1, a2, b1, b2;
    if (!split_angle(pa, P(c, A->p[(i + 1) % A->n]), aa, pb, &a1, &a2)) return INFINITY;
    if (!split_angle(pb, P(c, B->p[(j + 1) % B->n]), ab, pa, &b1, &b2)) return INFINITY;
    double cost = angle_cost(a1) + angle_cost(a2) + angle_cost(b1) + angle_cost(b2);
    if (aa * 180.0 / QC_PI > REFLEX_DEG) cost -= 1.0;
    if (ab * 180.0 / QC_PI > REFLEX_DEG) cost -= 1.0;
    return cost;
}

/* Quads of the even polygon xy[2 p[i]] (n <= GLPGP_POLY_SPLIT_MAX) around
 * one center joined to every other corner (p[o], p[o+2], ...): n / 2
 * quads (p[o+2q], p[o+2q+1], p[o+2q+2], X). The center is the best of a
 * few blends of the centroids of the joined and of the other corners.
 * Returns the smallest corner scaled Jacobian, the center in *x, *y and
 * the offset in *ob. */
double glpgp_qc_center_split(const double *xy, const int *p, int n, int *ob, double *xb, double *yb)
{
    double best = -INFINITY;
    for (int o = 0; o < 2; o++) {
        double ax = 0, ay = 0, bx = 0, by = 0;
        for (int i = 0; i < n / 2; i++) {
            ax += xy[2 * p[(o + 2 * i) % n]] / (n / 2);
            ay += xy[2 * p[(o + 2 * i) % n] + 1] / (n / 2);
            bx += xy[2 * p[(o + 2 * i + 1) % n]] / (n / 2);
            by += xy[2 * p[(o + 2 * i + 1) % n] + 1] / (n / 2);
        }
        for (int t = 0; t <= 4; t++) {
            double w = 0.25 * t, q[8];
            int id[4] = {0, 1, 2, 3};
            q[6] = (1 - w) * ax + w * bx;
            q[7] = (1 - w) * ay + w * by;
            double sj = INFINITY;
            for (int i = 0; i < n / 2 && sj > best; i++) {
                for (int k = 0; k < 3; k++) {
                    q[2 * k] = xy[2 * p[(o + 2 * i + k) % n]];
                    q[2 * k + 1] = xy[2 * p[(o + 2 * i + k) % n] + 1];
                }
                sj = fmin(sj, glpgp_poly_min_sj(q, id, 4));
            }
            if (sj > best) {
                best = sj;
                *ob = o;
                *xb = q[6];
                *yb = q[7];
            }
        }
    }
    return best;
}

static void loop_box(const qc *c, const ivec *L, double *bb);

/* Clearance cost of the cut from point ia to ib: loop points (other than
 * the ends) closer to it than half the local size make thin parts. */
static double clearance_cost(qc *c, const qc_piece *pc, int ia, int ib)
{
    const double *a = P(c, ia), *b = P(c, ib);
    double cost = 0.0;
    /* only points within h / 2 of the cut count (the local size is at most
     * h): the cut's box grown by that, and each hole's box against it */
    const double g = 0.5 * c->h;
    const double cb[4] = {fmin(a[0], b[0]) - g, fmin(a[1], b[1]) - g, fmax(a[0], b[0]) + g, fmax(a[1], b[1]) + g};
    for (int l = -1; l < pc->nh; l++) {
        const ivec *L = loop_of(pc, l);
        if (l >= 0) {
            double lb[4];
            loop_box(c, L, lb);
            if (lb[0] > cb[2] || lb[2] < cb[0] || lb[1] > cb[3] || lb[3] < cb[1]) continue;
        }
        for (int t = 0; t < L->n; t++) {
            const double *p = P(c, L->p[t]);
            if (p[0] < cb[0] || p[0] > cb[2] || p[1] < cb[1] || p[1] > cb[3]) continue;
            if (same_point(p, a) || same_point(p, b)) continue;
            double u, d = glpgp_seg_dist(a, b, p, &u);
            if (u <= 0.0 || u >= 1.0) continue; /* beyond an end: the end angles judge it */
            double s = qc_size(c, p[0], p[1]);
            if (d < 0.5 * s) {
                double r = 0.5 * s / fmax(d, 1e-3 * s);
                cost = fmax(cost, r * r - 1.0);
            }
        }
    }
    return cost;
}

/* Quality cost of a part of at most 8 points: the loop points from
 * position from forward to to, then the k cut points cp (in reverse when
 * reverse). */
static double part_cost(const qc *c, const ivec *L, int from, int to, const double *cp, int k, int reverse)
{
    int n = (to - from + L->n) % L->n + 1 + k;
    if (n > 8 || n < 4) return 0.0;
    double xy[16];
    int id[8], m = 0;
    for (int t = from;; t = (t + 1) % L->n) {
        xy[2 * m] = P(c, L->p[t])[0];
        xy[2 * m + 1] = P(c, L->p[t])[1];
        id[m] = m;
        m++;
        if (t == to) break;
    }
    for (int t = 0; t < k; t++) {
        int u = reverse ? k - 1 - t : t;
        xy[2 * m] = cp[2 * u];
        xy[2 * m + 1] = cp[2 * u + 1];
        id[m] = m;
        m++;
    }
    int out[4 * 8], nq, o;
    double sj = glpgp_poly_quad_split(xy, id, n, out, &nq), x, y, extra = 0.0;
    if (n >= 6) { /* as best_split: a center of valence n / 2 */
        double v = glpgp_qc_center_split(xy, id, n, &o, &x, &y);
        double margin = n == 8 ? -0.05 : n == 6 ? 0.05 : fmax(0.1, 0.3 - sj);
        if (v > sj + margin) {
            sj = v;
            extra = n == 8 ? 0.0 : 0.5;
        }
    }
    if (!(sj > 0.05)) return 50.0;
    return extra + (sj < SPLIT_OK ? 6.0 * (SPLIT_OK - sj) / SPLIT_OK : 0.0);
}

/* Score the cut from outer position i to j of a single loop (in *cu). */
static void score_cut(qc *c, const qc_piece *pc, int i, int j, cut *cu)
{
    const ivec *L = &pc->outer;
    int n = L->n, arc = (j - i + n) % n; /* points i .. j: arc + 1 */
    cu->cost = INFINITY;
    if (arc < 2 || arc > n - 2) return;
    double e = ends_cost(c, pc, -1, i, -1, j);
    if (!(e < INFINITY) || !glpgp_qc_visible(c, pc, L->p[i], L->p[j])) return;
    const double *a = P(c, L->p[i]), *b = P(c, L->p[j]);
    double ncell = cut_cells(c, a, b);
    int k = cut_points(ncell, arc + 1);
    if (k > MAXCUT) return;
    double sp = log((k + 1) / fmax(ncell, 1e-9));
    cu->li = cu->lj = -1;
    cu->i = i;
    cu->j = j;
    cu->k = k;
    cu->cost = e + 3.0 * sp * sp + clearance_cost(c, pc, L->p[i], L->p[j]);
    if (k < 8 && (arc + 1 + k <= 8 || n - arc + 1 + k <= 8)) {
        double cp[16];
        cut_positions(c, L->p[i], L->p[j], k, cp);
        cu->cost += part_cost(c, L, i, j, cp, k, 1);
        cu->cost += part_cost(c, L, j, i, cp, k, 0);
    }
}

/* The rays of loop point (l, i): half the angle, 90 degrees from either side. */
static int cut_rays(const qc *c, const ivec *L, int i, double *dir)
{
    double aa = glpgp_qc_loop_angle(c, L, i), deg = aa * 180.0 / QC_PI;
    if (deg < CORNER_DEG) return 0;
    const double *o = P(c, L->p[i]), *nx = P(c, L->p[(i + 1) % L->n]);
    double base = atan2(nx[1] - o[1], nx[0] - o[0]);
    double t[3];
    int m = 0;
    if (deg < 240.0 || deg > 300.0) t[m++] = 0.5 * aa;
    if (deg >= 240.0) {
        t[m++] = 0.5 * QC_PI;
        t[m++] = aa - 0.5 * QC_PI;
    }
    for (int q = 0; q < m; q++) {
        dir[2 * q] = cos(base + t[q]);
        dir[2 * q + 1] = sin(base + t[q]);
    }
    return m;
}

/* The best cut of the single loop of pc (cost INFINITY: none). */
static void best_cut(qc *c, const qc_piece *pc, cut *best)
{
    const ivec *L = &pc->outer;
    const int n = L->n;
    *best = (cut){-1, 0, -1, 0, 0, INFINITY};
    for (int i = 0; i < n; i++) {
        double dir[6];
        int m = cut_rays(c, L, i, dir);
        for (int r = 0; r < m; r++) {
            int hl = -1, hp = -1;
            if (!(ray_hit(c, pc, L->p[i], dir[2 * r], dir[2 * r + 1], &hl, &hp) < INFINITY) || hl != -1) continue;
            /* the hit edge's ends and their outer neighbours */
            for (int d = -1; d <= 2; d++) {
                int j = (hp + d + n) % n;
                cut cu;
                score_cut(c, pc, i, j, &cu);
                if (cu.cost < best->cost) *best = cu;
            }
        }
    }
}

/* Append the k points of a cut from point ia to point ib to the points and
 * their ids to pts. */
static glpgp_status cut_make_points(qc *c, int ia, int ib, int k, ivec *pts)
{
    if (k <= 0) return GLPGP_OK;
    if (k > MAXCUT) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "quad cut mesher: a cut of %d points", k);
    double *pos = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)2 * k, sizeof(double), &pos));
    cut_positions(c, ia, ib, k, pos);
    glpgp_status st = GLPGP_OK;
    for (int t = 0; t < k && st == GLPGP_OK; t++) {
        int id = c->xy->n / 2;
        st = dpush(c->xy, pos[2 * t]);
        if (st == GLPGP_OK) st = dpush(c->xy, pos[2 * t + 1]);
        if (st == GLPGP_OK) st = ipush(pts, id);
        c->stats->points++;
    }
    free(pos);
    return st;
}

/* Point-in-loop of a hole's first point. */
static int hole_inside(const qc *c, const ivec *outer, const ivec *hole)
{
    return glpgp_point_in_poly(c->xy->p, outer->p, outer->n, P(c, hole->p[0]), 0.0);
}

/* Split the single-loop piece pc (with its holes, which go to the part
 * containing them) along cu. pc is consumed. */
static glpgp_status apply_cut(qc *c, qc_piece *pc, const cut *cu)
{
    const ivec *L = &pc->outer;
    const int n = L->n;
    ivec pts = {0};
    qc_piece A, B;
    memset(&A, 0, sizeof A);
    memset(&B, 0, sizeof B);
    glpgp_status st = cut_make_points(c, L->p[cu->i], L->p[cu->j], cu->k, &pts);
    /* A: i .. j, then the cut back from j to i; B: j .. i, then the cut from i to j */
    for (int t = cu->i; st == GLPGP_OK; t = (t + 1) % n) {
        st = ipush(&A.outer, L->p[t]);
        if (t == cu->j) break;
    }
    for (int t = pts.n - 1; t >= 0 && st == GLPGP_OK; t--) st = ipush(&A.outer, pts.p[t]);
    for (int t = cu->j; st == GLPGP_OK; t = (t + 1) % n) {
        st = ipush(&B.outer, L->p[t]);
        if (t == cu->i) break;
    }
    for (int t = 0; t < pts.n && st == GLPGP_OK; t++) st = ipush(&B.outer, pts.p[t]);
    for (int k = 0; k < pc->nh && st == GLPGP_OK; k++)
        st = add_hole(hole_inside(c, &A.outer, &pc->holes[k]) ? &A : &B, &pc->holes[k]);
    ivec_free(&pts);
    piece_free(pc);
    c->stats->cuts++;
    if (st == GLPGP_OK) st = push_piece(c, &A);
    if (st == GLPGP_OK) st = push_piece(c, &B);
    piece_free(&A);
    piece_free(&B);
    return st;
}

/* ---- holes ---------------------------------------------------------------------- */

/* Consider the cut from hole h's position i to loop hl's position j for
 * *best (ex: the first cut, when this is the second). */
static void try_hole_cut(qc *c, const qc_piece *pc, int h, int i, int hl, int j, const cut *ex, cut *best)
{
    const ivec *H = &pc->holes[h], *T = loop_of(pc, hl);
    if (ex && (j == ex->j || i == ex->i)) return;
    double e = ends_cost(c, pc, h, i, hl, j);
    if (!(e < best->cost) || !glpgp_qc_visible(c, pc, H->p[i], T->p[j])) return;
    const double *a = P(c, H->p[i]), *b = P(c, T->p[j]);
    if (ex) { /* must not touch the first cut */
        const double *ea = P(c, H->p[ex->i]), *eb = P(c, loop_of(pc, ex->lj)->p[ex->j]);
        if (glpgp_seg_cross(a, b, ea, eb, 0.0) || glpgp_seg_dist(ea, eb, a, NULL) == 0.0 ||
            glpgp_seg_dist(ea, eb, b, NULL) == 0.0 || glpgp_seg_dist(a, b, ea, NULL) == 0.0 ||
            glpgp_seg_dist(a, b, eb, NULL) == 0.0)
            return;
    }
    double ncell = cut_cells(c, a, b);
    int k = cut_points(ncell, 0);
    double sp = log((k + 1) / fmax(ncell, 1e-9)), cost = e + 3.0 * sp * sp + clearance_cost(c, pc, H->p[i], T->p[j]);
    if (ex) { /* prefer the far side of the hole */
        int arc = (i - ex->i + H->n) % H->n;
        double bal = fabs(2.0 * arc - H->n) / H->n;
        cost += 2.0 * bal * bal;
    }
    if (cost < best->cost) *best = (cut){h, i, hl, j, k, cost};
}

static void loop_box(const qc *c, const ivec *L, double *bb)
{
    bb[0] = bb[1] = INFINITY;
    bb[2] = bb[3] = -INFINITY;
    for (int t = 0; t < L->n; t++) {
        const double *p = P(c, L->p[t]);
        bb[0] = fmin(bb[0], p[0]);
        bb[1] = fmin(bb[1], p[1]);
        bb[2] = fmax(bb[2], p[0]);
        bb[3] = fmax(bb[3], p[1]);
    }
}

static double box_gap(const double *a, const double *b)
{
    double dx = fmax(0.0, fmax(a[0] - b[2], b[0] - a[2])), dy = fmax(0.0, fmax(a[1] - b[3], b[1] - a[3]));
    return hypot(dx, dy);
}

/* The best cut from a point of hole h of pc to a point of another loop:
 * ends near where the rays of the hole's points meet other loops, and the
 * three points of each nearby loop nearest each hole point. ex: the first
 * cut (then only to its loop, not touching it), or NULL. */
static void best_hole_cut(qc *c, const qc_piece *pc, int h, const cut *ex, cut *best)
{
    const ivec *H = &pc->holes[h];
    *best = (cut){h, 0, -1, 0, 0, INFINITY};
    double hb[4], tb[4], gmin = INFINITY, ex_len = 0.0;
    if (ex) {
        const double *ea = P(c, H->p[ex->i]), *eb = P(c, loop_of(pc, ex->lj)->p[ex->j]);
        ex_len = hypot(eb[0] - ea[0], eb[1] - ea[1]);
    }
    loop_box(c, H, hb);
    for (int l = -1; l < pc->nh; l++) {
        if (l == h) continue;
        loop_box(c, loop_of(pc, l), tb);
        gmin = fmin(gmin, l < 0 ? 0.0 : box_gap(hb, tb));
    }
    for (int i = 0; i < H->n; i++) {
        double dir[6];
        int m = cut_rays(c, H, i, dir);
        for (int r = 0; r < m; r++) {
            int hl = -2, hp = -1;
            if (!(ray_hit(c, pc, H->p[i], dir[2 * r], dir[2 * r + 1], &hl, &hp) < INFINITY) || hl == h) continue;
            if (ex && hl != ex->lj) continue;
            const ivec *T = loop_of(pc, hl);
            for (int d = -1; d <= 2; d++) try_hole_cut(c, pc, h, i, hl, (hp + d + T->n) % T->n, ex, best);
        }
        for (int l = -1; l < pc->nh; l++) {
            if (l == h || (ex && l != ex->lj)) continue;
            const ivec *T = loop_of(pc, l);
            if (l >= 0) {
                loop_box(c, T, tb);
                if (box_gap(hb, tb) > gmin + 2.0 * c->h) continue;
            }
            if (ex) { /* the second cut: every point of the first cut's loop near enough */
                const double *a = P(c, H->p[i]);
                double lim = 3.0 * ex_len + 2.0 * c->h;
                for (int j = 0; j < T->n; j++) {
                    const double *b = P(c, T->p[j]);
                    if (hypot(b[0] - a[0], b[1] - a[1]) <= lim) try_hole_cut(c, pc, h, i, l, j, ex, best);
                }
                continue;
            }
            int near[3] = {-1, -1, -1};
            double nd[3] = {INFINITY, INFINITY, INFINITY};
            const double *a = P(c, H->p[i]);
            for (int j = 0; j < T->n; j++) {
                const double *b = P(c, T->p[j]);
                double d = hypot(b[0] - a[0], b[1] - a[1]);
                for (int q = 0; q < 3; q++)
                    if (d < nd[q]) {
                        for (int z = 2; z > q; z--) nd[z] = nd[z - 1], near[z] = near[z - 1];
                        nd[q] = d;
                        near[q] = j;
                        break;
                    }
            }
            for (int q = 0; q < 3; q++)
                if (near[q] >= 0) try_hole_cut(c, pc, h, i, l, near[q], ex, best);
        }
    }
}

/* Loop of arc of L from position a forward to b (both included). */
static glpgp_status push_arc(ivec *dst, const ivec *L, int a, int b)
{
    for (int t = a;; t = (t + 1) % L->n) {
        GLPGP_CHECK(ipush(dst, L->p[t]));
        if (t == b) break;
    }
    return GLPGP_OK;
}

/* Points of loop X plus of the holes of pc (other than h and lj) inside it. */
static int count_with_holes(const qc *c, const qc_piece *pc, const ivec *X, int h, int lj)
{
    int n = X->n;
    for (int k = 0; k < pc->nh; k++)
        if (k != h && k != lj && hole_inside(c, X, &pc->holes[k])) n += pc->holes[k].n;
    return n;
}

/* Join hole h of pc to loop c1.lj by the cuts c1 and c2 (see the header);
 * pc is consumed. */
static glpgp_status join_hole(qc *c, qc_piece *pc, const cut *c1, cut *c2)
{
    const ivec *H = &pc->holes[c1->li], *T = loop_of(pc, c1->lj);
    ivec p1 = {0}, p2 = {0}, X = {0}, Y = {0};
    glpgp_status st = cut_make_points(c, H->p[c1->i], T->p[c1->j], c1->k, &p1);
    /* X: T from j1 to j2, c2 reversed (T[j2] -> H[i2]), H from i2 to i1, c1 (H[i1] -> T[j1]) */
    if (st == GLPGP_OK) st = push_arc(&X, T, c1->j, c2->j);
    if (st == GLPGP_OK) {
        /* parity: the part that is a piece (positive area; X when both are)
         * with the holes inside it must be even. The loops without the cut
         * points have the same area (the points lie on the straight cuts). */
        ivec tx = {0}, ty = {0};
        st = push_arc(&tx, T, c1->j, c2->j);
        if (st == GLPGP_OK) st = push_arc(&tx, H, c2->i, c1->i);
        if (st == GLPGP_OK) st = push_arc(&ty, T, c2->j, c1->j);
        if (st == GLPGP_OK) st = push_arc(&ty, H, c1->i, c2->i);
        if (st == GLPGP_OK) {
            const ivec *piece = loop_area(c, &tx) > 0 ? &tx : &ty;
            int n = count_with_holes(c, pc, piece, c1->li, c1->lj) + p1.n;
            double ncell = cut_cells(c, P(c, H->p[c2->i]), P(c, T->p[c2->j]));
            c2->k = cut_points(ncell, n);
        }
        ivec_free(&tx);
        ivec_free(&ty);
    }
    if (st == GLPGP_OK) st = cut_make_points(c, H->p[c2->i], T->p[c2->j], c2->k, &p2);
    for (int t = p2.n - 1; t >= 0 && st == GLPGP_OK; t--) st = ipush(&X, p2.p[t]);
    if (st == GLPGP_OK) st = push_arc(&X, H, c2->i, c1->i);
    for (int t = 0; t < p1.n && st == GLPGP_OK; t++) st = ipush(&X, p1.p[t]);
    /* Y: T from j2 to j1, c1 reversed, H from i1 to i2, c2 */
    if (st == GLPGP_OK) st = push_arc(&Y, T, c2->j, c1->j);
    for (int t = p1.n - 1; t >= 0 && st == GLPGP_OK; t--) st = ipush(&Y, p1.p[t]);
    if (st == GLPGP_OK) st = push_arc(&Y, H, c1->i, c2->i);
    for (int t = 0; t < p2.n && st == GLPGP_OK; t++) st = ipush(&Y, p2.p[t]);
    ivec_free(&p1);
    ivec_free(&p2);
    if (st != GLPGP_OK) goto done;
    c->stats->cuts += 2;
    /* positive loops are pieces; a negative one (the holes joined) stays a hole */
    qc_piece parts[2];
    memset(parts, 0, sizeof parts);
    ivec *loops[2] = {&X, &Y};
    int np = 0, merged = -1;
    for (int q = 0; q < 2; q++) {
        if (loop_area(c, loops[q]) > 0) {
            parts[np].outer = *loops[q];
            memset(loops[q], 0, sizeof(ivec));
            np++;
        } else {
            merged = q;
        }
    }
    if (np == 0 || (np == 1 && c1->lj < 0) || (np == 2 && c1->lj >= 0)) {
        st = GLPGP_FAIL(GLPGP_ERR_NUMERIC, "quad cut mesher: a hole's cuts do not split its piece");
        for (int q = 0; q < np; q++) piece_free(&parts[q]);
        goto done;
    }
    if (np == 1) { /* two holes joined: parts[1] = pc's outer loop with the merged hole */
        parts[1].outer = pc->outer;
        memset(&pc->outer, 0, sizeof pc->outer);
        st = add_hole(&parts[1], loops[merged]);
        np = 2;
    }
    for (int k = 0; k < pc->nh && st == GLPGP_OK; k++) {
        if (k == c1->li || k == c1->lj) continue;
        int in0 = hole_inside(c, &parts[0].outer, &pc->holes[k]);
        st = add_hole(in0 ? &parts[0] : &parts[1], &pc->holes[k]);
    }
    for (int q = 0; q < np; q++) {
        if (st == GLPGP_OK) st = push_piece(c, &parts[q]);
        piece_free(&parts[q]);
    }
done:
    ivec_free(&X);
    ivec_free(&Y);
    piece_free(pc);
    return st;
}

/* One hole of pc joined to another loop: the hole and first cut with the
 * best cost whose second cut exists (each hole's best first cut is tried,
 * best first). */
static glpgp_status cut_hole(qc *c, qc_piece *pc)
{
    cut *first = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)pc->nh + 1, sizeof *first, &first));
    for (int h = 0; h < pc->nh; h++) best_hole_cut(c, pc, h, NULL, &first[h]);
    for (int tries = 0; tries < pc->nh; tries++) {
        int b = -1;
        for (int h = 0; h < pc->nh; h++)
            if (first[h].cost < INFINITY && (b < 0 || first[h].cost < first[b].cost)) b = h;
        if (b < 0) break;
        cut c1 = first[b], c2;
        first[b].cost = INFINITY;
        best_hole_cut(c, pc, c1.li, &c1, &c2);
        if (!(c2.cost < INFINITY)) continue;
        free(first);
        return join_hole(c, pc, &c1, &c2);
    }
    free(first);
    return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "quad cut mesher: no pair of cuts from a hole");
}

/* ---- driver --------------------------------------------------------------------------- */

static glpgp_status mesh_loop(qc *c, qc_piece *pc)
{
    const ivec *L = &pc->outer;
    if (L->n % 2) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "quad cut mesher: a piece with %d points (odd)", L->n);
    if (L->n < 4) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "quad cut mesher: a piece with %d points", L->n);
    for (int guard = 0; guard < L->n; guard++) { /* sharp points first */
        int done = 0;
        GLPGP_CHECK(glpgp_qc_kite_cut(c, pc, &done));
        if (!done) break;
    }
    split s;
    s.sj = -INFINITY;
    if (L->n <= GLPGP_POLY_SPLIT_MAX) {
        glpgp_qc_best_split(c, L, &s);
        if (s.sj >= SPLIT_OK || (L->n == 4 && s.sj > 0.15)) {
            GLPGP_CHECK(glpgp_qc_emit_split(c, L, &s));
            piece_free(pc);
            return GLPGP_OK;
        }
    }
    cut cu = {-1, 0, -1, 0, 0, INFINITY};
    c->work += (double)L->n * L->n; /* best_cut's cost, about */
    if (c->max_work > 0.0 && c->work > c->max_work)
        return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "quad cut mesher: over its work bound (%.3g point pairs)", c->max_work);
    if (L->n > 4) best_cut(c, pc, &cu);
    /* a cut whose part has no valid split (cost >= 50) only when the piece itself has none */
    if (cu.cost < INFINITY && c->budget-- > 0 && !(s.sj > 0.2 && cu.cost > 6.0) && !(s.sj > 0.0 && cu.cost >= 40.0))
        return apply_cut(c, pc, &cu);
    if (s.sj > 0.0) {
        GLPGP_CHECK(glpgp_qc_emit_split(c, L, &s));
        piece_free(pc);
        return GLPGP_OK;
    }
    if (L->n == 4) {
        int done = 0;
        GLPGP_CHECK(glpgp_qc_ring_quad(c, L, &done));
        if (done) {
            piece_free(pc);
            return GLPGP_OK;
        }
    }
    return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "quad cut mesher: no cut or split for a piece of %d points", L->n);
}

/* Distance from p to the nearest side of loop L. */
static double loop_dist(const qc *c, const ivec *L, const double *p)
{
    double d = INFINITY;
    for (int i = 0; i < L->n; i++) d = fmin(d, glpgp_seg_dist(P(c, L->p[i]), P(c, L->p[(i + 1) % L->n]), p, NULL));
    return d;
}

/* One ring of quads around hole k of pc, its points moved out along their
 * normals by their spacing (about square quads); the hole becomes the outer
 * ring. *done 0 (nothing changed) when a quad would be poor or a new side
 * would come near another loop. */
static glpgp_status hole_ring(qc *c, qc_piece *pc, int k, int *done)
{
    ivec *H = &pc->holes[k];
    const int n = H->n, base = c->xy->n;
    *done = 0;
    for (int i = 0; i < n; i++) {
        const double *a = P(c, H->p[(i + n - 1) % n]), *b = P(c, H->p[i]), *d = P(c, H->p[(i + 1) % n]);
        double l1 = hypot(b[0] - a[0], b[1] - a[1]), l2 = hypot(d[0] - b[0], d[1] - b[1]);
        /* left normals of the two sides (into the region) */
        double nx = -(b[1] - a[1]) / l1 - (d[1] - b[1]) / l2, ny = (b[0] - a[0]) / l1 + (d[0] - b[0]) / l2;
        double nn = hypot(nx, ny), s = 0.5 * (l1 + l2);
        if (!(nn > 1e-12)) return GLPGP_OK;
        GLPGP_CHECK(dpush(c->xy, b[0] + s * nx / nn));
        GLPGP_CHECK(dpush(c->xy, b[1] + s * ny / nn));
    }
    int ok = 1;
    for (int i = 0; i < n && ok; i++) {
        int q0 = base / 2 + i, q1 = base / 2 + (i + 1) % n;
        int f[4] = {H->p[i], H->p[(i + 1) % n], q1, q0};
        ok = glpgp_poly_min_sj(c->xy->p, f, 4) > 0.3;
        const double *qa = P(c, q0), *qb = P(c, q1);
        double e = hypot(qb[0] - qa[0], qb[1] - qa[1]);
        for (int l = -1; l < pc->nh && ok; l++) { /* clear of the other loops */
            if (l == k) continue;
            const ivec *L = loop_of(pc, l);
            ok = !blocked_by(c, L, qa, qb, 0.0) && !blocked_by(c, L, P(c, H->p[i]), qa, 0.0) && loop_dist(c, L, qa) > 0.7 * e;
            if (ok && l == -1) ok = glpgp_point_in_poly(c->xy->p, L->p, L->n, qa, 0.0);
        }
    }
    if (!ok) {
        c->xy->n = base;
        return GLPGP_OK;
    }
    for (int i = 0; i < n; i++) {
        int f[4] = {H->p[i], H->p[(i + 1) % n], base / 2 + (i + 1) % n, base / 2 + i};
        GLPGP_CHECK(glpgp_qc_emit(c, f));
    }
    for (int i = 0; i < n; i++) H->p[i] = base / 2 + i;
    c->stats->points += n;
    c->stats->pieces++;
    *done = 1;
    return GLPGP_OK;
}

/* Holes much smaller than the size get rings of quads around them (an
 * O-grid) until their spacing reaches about 0.7 h or a ring would come near
 * another loop: the cuts then start from a loop of about the local size. */
static glpgp_status grow_holes(qc *c, qc_piece *pc)
{
    for (int k = 0; k < pc->nh; k++)
        for (int ring = 0; ring < 8; ring++) {
            const ivec *H = &pc->holes[k];
            double len = 0.0;
            for (int i = 0; i < H->n; i++) {
                const double *a = P(c, H->p[i]), *b = P(c, H->p[(i + 1) % H->n]);
                len += hypot(b[0] - a[0], b[1] - a[1]);
            }
            if (H->n < 4 || len / H->n >= 0.7 * c->h) break;
            int done = 0;
            GLPGP_CHECK(hole_ring(c, pc, k, &done));
            if (!done) break;
        }
    return GLPGP_OK;
}

static glpgp_status initial_pieces(qc *c, const qcut_region *R)
{
    for (int l = 0; l < R->nloops; l++) {
        if (R->owner[l] >= 0) continue;
        qc_piece pc;
        memset(&pc, 0, sizeof pc);
        glpgp_status st = GLPGP_OK;
        for (int t = R->loop_start[l]; t < R->loop_start[l + 1] && st == GLPGP_OK; t++)
            st = ipush(&pc.outer, R->loop_v[t]);
        for (int k = 0; k < R->nloops && st == GLPGP_OK; k++) {
            if (R->owner[k] != l) continue;
            ivec h = {0};
            for (int t = R->loop_start[k]; t < R->loop_start[k + 1] && st == GLPGP_OK; t++)
                st = ipush(&h, R->loop_v[t]);
            if (st == GLPGP_OK) st = add_hole(&pc, &h);
            ivec_free(&h);
        }
        if (st == GLPGP_OK) st = grow_holes(c, &pc);
        if (st == GLPGP_OK) st = push_piece(c, &pc);
        piece_free(&pc);
        if (st != GLPGP_OK) return st;
    }
    return GLPGP_OK;
}

glpgp_status glpgp_qcut_mesh(dvec *xy, const qcut_region *R, double h, ivec *quads, qcut_stats *stats)
{
    qc c;
    memset(&c, 0, sizeof c);
    memset(stats, 0, sizeof *stats);
    if (!(h > 0) || R->nloops < 1) return GLPGP_FAIL(GLPGP_ERR_ARG, "quad cut mesher: bad arguments");
    c.xy = xy;
    c.quads = quads;
    c.stats = stats;
    c.h = h;
    c.max_work = R->max_work;
    glpgp_status st = build_sizes(&c, R);
    /* work bound: the cuts a region of this area and boundary can need, with room */
    double area = 0.0;
    for (int l = 0; l < R->nloops; l++) {
        int s = R->loop_start[l], m = R->loop_start[l + 1] - s;
        for (int i = 0; i < m; i++) {
            const double *a = P(&c, R->loop_v[s + i]), *b = P(&c, R->loop_v[s + (i + 1) % m]);
            area += 0.5 * (a[0] * b[1] - b[0] * a[1]);
        }
    }
    double smin = h;
    for (int i = 0; i < c.ns; i++) smin = fmin(smin, c.src[3 * i + 2]);
    c.budget = 64 + 4L * R->loop_start[R->nloops] + (long)fmin(1e7, 8.0 * fabs(area) / (smin * smin));
    if (st == GLPGP_OK) st = initial_pieces(&c, R);
    for (long k = 0; st == GLPGP_OK && c.nstack > 0; k++) {
        if ((k & 255) == 0) glpgp_progress_poll();
        qc_piece pc = c.stack[--c.nstack];
        st = pc.nh > 0 ? cut_hole(&c, &pc) : mesh_loop(&c, &pc);
        piece_free(&pc);
    }
    stats->work = c.work;
    for (int i = 0; i < c.nstack; i++) piece_free(&c.stack[i]);
    free(c.stack);
    free(c.src);
    free(c.cand);
    glpgp_bgrid_free(&c.G);
    return st;
}
