/* quads/quality.c: the quality report of a polygon mesh (glpgp/quads.h):
 * valences and irregular vertices, scaled Jacobian, inverted / degenerate /
 * non-manifold faces and edges, edge lengths, area and the boundary Hausdorff
 * distance to a domain, and its printed form. */
#include "glpgp/quads.h"
#include "glpgp/cross.h"
#include "glpgp/util.h"
#include "check.h"
#include "geom.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI_ 3.14159265358979323846

/* ---- unique edges of a polygon mesh ------------------------------------ */

typedef struct qe {
    int a, b;   /* a < b */
    int nface;  /* faces using it */
} qe;

static int cmp_pair(const void *pa, const void *pb)
{
    const int *a = pa, *b = pb;
    if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
    return (a[1] > b[1]) - (a[1] < b[1]);
}

/* Unique edges with their face counts. */
static glpgp_status face_edges(const glpgp_quadmesh *q, qe **out, int *nout)
{
    int n = q->face_start[q->nf];
    int *pr = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)2 * n + 2, sizeof(int), &pr));
    for (int f = 0; f < q->nf; f++) {
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        for (int i = 0; i < k; i++) {
            int a = q->face_vert[s + i], b = q->face_vert[s + (i + 1) % k];
            pr[2 * (s + i)] = a < b ? a : b;
            pr[2 * (s + i) + 1] = a < b ? b : a;
        }
    }
    qsort(pr, (size_t)n, 2 * sizeof(int), cmp_pair);
    qe *e = NULL;
    glpgp_status st = glpgp_malloc((size_t)n + 1, sizeof *e, &e);
    if (st != GLPGP_OK) {
        free(pr);
        return st;
    }
    int ne = 0;
    for (int i = 0; i < n;) {
        int j = i + 1;
        while (j < n && pr[2 * j] == pr[2 * i] && pr[2 * j + 1] == pr[2 * i + 1]) j++;
        e[ne].a = pr[2 * i];
        e[ne].b = pr[2 * i + 1];
        e[ne].nface = j - i;
        ne++;
        i = j;
    }
    free(pr);
    *out = e;
    *nout = ne;
    return GLPGP_OK;
}

glpgp_status glpgp_quadmesh_valences(const glpgp_quadmesh *q, int **out)
{
    qe *E = NULL;
    int ne = 0;
    int *val = NULL;
    *out = NULL;
    GLPGP_CHECK(face_edges(q, &E, &ne));
    glpgp_status st = glpgp_calloc((size_t)q->nv + 1, sizeof(int), &val);
    if (st == GLPGP_OK) {
        /* valence(v) = number of distinct edges at v */
        for (int i = 0; i < ne; i++) {
            val[E[i].a]++;
            val[E[i].b]++;
        }
        *out = val;
    }
    free(E);
    return st;
}

/* ---- nearest distance to a set of segments (uniform grid) ------------- */

typedef struct segset {
    int n;
    double *s;      /* 4 per segment */
    double x0, y0, cs;
    int nx, ny;
    int *start;     /* nx*ny + 1 */
    int *item;
} segset;

static void segset_free(segset *S)
{
    free(S->s);
    free(S->start);
    free(S->item);
    memset(S, 0, sizeof *S);
}

static glpgp_status segset_build(segset *S, double cs)
{
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int i = 0; i < S->n; i++) {
        const double *p = S->s + 4 * i;
        x0 = fmin(x0, fmin(p[0], p[2]));
        x1 = fmax(x1, fmax(p[0], p[2]));
        y0 = fmin(y0, fmin(p[1], p[3]));
        y1 = fmax(y1, fmax(p[1], p[3]));
    }
    /* keep the grid at most ~ 4 n cells */
    double w = x1 - x0, hgt = y1 - y0;
    while ((w / cs + 1) * (hgt / cs + 1) > 4.0 * S->n + 16) cs *= 2.0;
    S->cs = cs;
    S->x0 = x0;
    S->y0 = y0;
    S->nx = (int)(w / cs) + 1;
    S->ny = (int)(hgt / cs) + 1;
    long nc = (long)S->nx * S->ny;
    GLPGP_CHECK(glpgp_calloc((size_t)nc + 1, sizeof(int), &S->start));
    /* each segment goes into the cells of its bounding box */
    for (int pass = 0; pass < 2; pass++) {
        for (int i = 0; i < S->n; i++) {
            const double *p = S->s + 4 * i;
            int ia = (int)((fmin(p[0], p[2]) - x0) / cs), ib = (int)((fmax(p[0], p[2]) - x0) / cs);
            int ja = (int)((fmin(p[1], p[3]) - y0) / cs), jb = (int)((fmax(p[1], p[3]) - y0) / cs);
            if (ib >= S->nx) ib = S->nx - 1;
            if (jb >= S->ny) jb = S->ny - 1;
            for (int j = ja; j <= jb; j++)
                for (int k = ia; k <= ib; k++) {
                    long c = (long)j * S->nx + k;
                    if (pass == 0)
                        S->start[c + 1]++;
                    else
                        S->item[S->start[c]++] = i;
                }
        }
        if (pass == 0) {
            for (long c = 0; c < nc; c++) S->start[c + 1] += S->start[c];
            GLPGP_CHECK(glpgp_malloc((size_t)S->start[nc] + 1, sizeof(int), &S->item));
        } else {
            for (long c = nc; c > 0; c--) S->start[c] = S->start[c - 1];
            S->start[0] = 0;
        }
    }
    return GLPGP_OK;
}

static double seg_dist(const double *s, double x, double y)
{
    double dx = s[2] - s[0], dy = s[3] - s[1];
    double l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((x - s[0]) * dx + (y - s[1]) * dy) / l2 : 0.0;
    t = fmax(0.0, fmin(1.0, t));
    return hypot(s[0] + t * dx - x, s[1] + t * dy - y);
}

static double segset_dist(const segset *S, double x, double y)
{
    if (S->n == 0) return INFINITY;
    int ci = (int)floor((x - S->x0) / S->cs), cj = (int)floor((y - S->y0) / S->cs);
    double best = INFINITY;
    int maxr = S->nx + S->ny + 2;
    for (int r = 0; r <= maxr; r++) {
        /* cells at Chebyshev ring r around (ci, cj) */
        for (int j = cj - r; j <= cj + r; j++) {
            if (j < 0 || j >= S->ny) continue;
            int step = (j == cj - r || j == cj + r) ? 1 : 2 * r;
            if (step == 0) step = 1;
            for (int i = ci - r; i <= ci + r; i += step) {
                if (i < 0 || i >= S->nx) continue;
                long c = (long)j * S->nx + i;
                for (int q = S->start[c]; q < S->start[c + 1]; q++) {
                    double d = seg_dist(S->s + 4 * S->item[q], x, y);
                    if (d < best) best = d;
                }
            }
        }
        /* everything not yet searched is farther than r * cs from (x, y) */
        if (best <= r * S->cs) break;
    }
    return best;
}

/* ---- quality ----------------------------------------------------------- */

static int cmp_double(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

/* Per face: corners, area, scaled Jacobian (quads), interior angle sums
 * per vertex; the face flags of the check. */
static glpgp_status face_stats(const glpgp_quadmesh *q, const qcheck *ck, glpgp_quads_report *o, double *angle)
{
    double *sj = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)q->nf + 1, sizeof(double), &sj));
    int nsj = 0;
    double sjsum = 0.0;
    for (int f = 0; f < q->nf; f++) {
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        const int *v = q->face_vert + s;
        if (k == 4) {
            o->quads++;
        } else {
            o->others++;
            int b = k - 3;
            o->others_by_size[b < 0 ? 0 : b > 7 ? 7 : b]++;
        }
        double area = 0.0, fmin_sj = INFINITY;
        for (int i = 0; i < k; i++) {
            int a = v[i], b = v[(i + 1) % k], c = v[(i + k - 1) % k];
            double ax = q->xy[2 * a], ay = q->xy[2 * a + 1];
            double e1x = q->xy[2 * b] - ax, e1y = q->xy[2 * b + 1] - ay;
            double e2x = q->xy[2 * c] - ax, e2y = q->xy[2 * c + 1] - ay;
            double l1 = hypot(e1x, e1y), l2 = hypot(e2x, e2y);
            area += 0.5 * ck->orientation * (ax * q->xy[2 * b + 1] - q->xy[2 * b] * ay);
            /* scaled Jacobian at corner a: sin of the angle from e1 to e2
             * (in the mesh orientation) */
            double cr = ck->orientation * (e1x * e2y - e1y * e2x);
            fmin_sj = fmin(fmin_sj, (l1 > 0 && l2 > 0) ? cr / (l1 * l2) : 0.0);
            /* interior angle at a (from e1 counter-clockwise to e2) */
            double ang = atan2(cr, e1x * e2x + e1y * e2y);
            angle[a] += ang < 0 ? ang + 2 * PI_ : ang;
        }
        o->area += area;
        if (ck->flags[f] & QF_DEGENERATE) o->degenerate++;
        if (ck->flags[f] & QF_INVERTED) o->inverted++;
        if (ck->flags[f] & QF_OVERLAP) o->overlaps++;
        if (ck->flags[f] & QF_OUTSIDE) o->outside++;
        if (ck->flags[f] & (QF_FAR | QF_LOST)) o->far_faces++;
        if (k == 4) {
            sj[nsj++] = fmin_sj;
            sjsum += fmin_sj;
        }
    }
    if (nsj > 0) {
        qsort(sj, (size_t)nsj, sizeof(double), cmp_double);
        o->sj_min = sj[0];
        o->sj_mean = sjsum / nsj;
        o->sj_p01 = sj[(int)floor(0.01 * (nsj - 1))];
    } else {
        o->sj_min = o->sj_mean = o->sj_p01 = NAN;
    }
    free(sj);
    return GLPGP_OK;
}

/* Quads by origin, the repaired share, and the scaled Jacobian against
 * what the domain's sharp corners allow. */
static glpgp_status origin_stats(const glpgp_quadmesh *q, const glpgp_mesh *domain, double h, glpgp_quads_report *o)
{
    double *bound = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)q->nf + 1, sizeof(double), &bound));
    glpgp_status st = glpgp_qcheck_corner_bound(q, domain, h, bound);
    o->sj_min_corner = INFINITY;
    for (int f = 0; f < q->nf && st == GLPGP_OK; f++) {
        if (q->face_start[f + 1] - q->face_start[f] != 4) continue;
        int org = q->face_origin && q->face_origin[f] < GLPGP_QFACE_KINDS ? q->face_origin[f] : GLPGP_QFACE_GRID;
        o->quads_by_origin[org]++;
        double sj = glpgp_quadmesh_face_sj(q, f);
        o->sj_min_corner = fmin(o->sj_min_corner, sj / bound[f]);
        if (glpgp_qcheck_unforced_below(sj, bound[f], GLPGP_QUADS_SJ_GOAL)) o->below_sj_goal++;
    }
    if (!(o->sj_min_corner < INFINITY)) o->sj_min_corner = NAN;
    int rep = o->quads_by_origin[GLPGP_QFACE_PAVED] + o->quads_by_origin[GLPGP_QFACE_FALLBACK];
    o->repaired_share = o->quads > 0 ? (double)rep / o->quads : 0.0;
    free(bound);
    return st;
}

/* Boundary distances (Hausdorff, gaps) of q against the domain. */
static glpgp_status boundary_stats(const glpgp_quadmesh *q, const glpgp_mesh *domain, double h, const qe *E, int ne,
                                   glpgp_quads_report *o)
{
    segset SD, SQ;
    memset(&SD, 0, sizeof SD);
    memset(&SQ, 0, sizeof SQ);
    glpgp_status st = GLPGP_OK;
    int nb = domain->loop_start[domain->nloops];
    SD.n = nb;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * nb + 4, sizeof(double), &SD.s), done);
    for (int l = 0; l < domain->nloops; l++) {
        int s = domain->loop_start[l], n = domain->loop_start[l + 1] - s;
        for (int i = 0; i < n; i++) {
            int a = domain->loop_vertices[s + i], b = domain->loop_vertices[s + (i + 1) % n];
            double *p = SD.s + 4 * (s + i);
            p[0] = domain->xy[2 * a];
            p[1] = domain->xy[2 * a + 1];
            p[2] = domain->xy[2 * b];
            p[3] = domain->xy[2 * b + 1];
        }
    }
    SQ.n = o->boundary_edges;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)4 * SQ.n + 4, sizeof(double), &SQ.s), done);
    int w = 0;
    for (int i = 0; i < ne; i++) {
        if (E[i].nface != 1) continue;
        double *p = SQ.s + 4 * w++;
        p[0] = q->xy[2 * E[i].a];
        p[1] = q->xy[2 * E[i].a + 1];
        p[2] = q->xy[2 * E[i].b];
        p[3] = q->xy[2 * E[i].b + 1];
    }
    GLPGP_CHECK_GOTO(st, segset_build(&SD, h), done);
    if (SQ.n > 0) GLPGP_CHECK_GOTO(st, segset_build(&SQ, h), done);
    double dq = 0.0, dd = 0.0;
    int gaps = 0;
    for (int i = 0; i < SQ.n; i++) {
        const double *p = SQ.s + 4 * i;
        for (int k = 0; k <= 8; k++) {
            double t = k / 8.0;
            dq = fmax(dq, segset_dist(&SD, p[0] + t * (p[2] - p[0]), p[1] + t * (p[3] - p[1])));
        }
        /* midpoint far from the domain boundary: an interior hole */
        if (segset_dist(&SD, 0.5 * (p[0] + p[2]), 0.5 * (p[1] + p[3])) > 0.25 * h) gaps++;
    }
    for (int i = 0; i < SD.n; i++) {
        const double *p = SD.s + 4 * i;
        dd = fmax(dd, segset_dist(&SQ, p[0], p[1]));
        dd = fmax(dd, segset_dist(&SQ, 0.5 * (p[0] + p[2]), 0.5 * (p[1] + p[3])));
    }
    o->dist_quad_to_domain = dq / h;
    o->dist_domain_to_quad = dd / h;
    o->hausdorff = fmax(dq, dd) / h;
    o->gap_edges = gaps;
done:
    segset_free(&SD);
    segset_free(&SQ);
    return st;
}

static void validity(const glpgp_mesh *domain, glpgp_quads_report *o)
{
    unsigned b = 0;
    if (o->inverted) b |= GLPGP_QUADS_BAD_INVERTED;
    if (o->degenerate) b |= GLPGP_QUADS_BAD_DEGENERATE;
    if (o->nonmanifold_edges) b |= GLPGP_QUADS_BAD_NONMANIFOLD;
    if (o->others) b |= GLPGP_QUADS_BAD_NONQUAD;
    if (o->pinched) b |= GLPGP_QUADS_BAD_PINCHED;
    if (o->overlaps) b |= GLPGP_QUADS_BAD_OVERLAP;
    if (domain) {
        if (o->outside) b |= GLPGP_QUADS_BAD_OUTSIDE;
        if (o->boundary_loops != o->domain_loops) b |= GLPGP_QUADS_BAD_LOOPS;
        if (!(fabs(o->area_ratio - 1.0) <= 0.01)) b |= GLPGP_QUADS_BAD_AREA;
        if (!(o->hausdorff <= 0.25)) b |= GLPGP_QUADS_BAD_HAUSDORFF;
        if (o->gap_edges > 0) b |= GLPGP_QUADS_BAD_GAPS;
        if (o->corners_lost > 0) b |= GLPGP_QUADS_BAD_CORNERS;
    }
    o->invalid = b;
}

glpgp_status glpgp_quads_quality(const glpgp_quadmesh *q, const glpgp_mesh *domain, double h,
                                 glpgp_quads_report *o)
{
    memset(o, 0, sizeof *o);
    if (q && q->xyz && domain && domain->xyz) return glpgp_quads_quality_surface(q, domain, h, o); /* a surface's */
    if (!(h > 0)) return GLPGP_FAIL(GLPGP_ERR_ARG, "quad quality: size h must be > 0");
    if (!q || q->nf < 1) return GLPGP_FAIL(GLPGP_ERR_ARG, "quad quality: empty mesh");
    o->h = h;
    o->vertices = q->nv;
    o->faces = q->nf;
    o->singular[0] = o->singular[1] = -1;
    o->cross_singularities = o->irregular_near_cross = o->irregular_far_cross = o->cross_matched = -1;
    o->cross_radius = -1.0;
    o->closing = q->closing;
    o->repair = q->repair;
    o->cleanup = q->cleanup;
    glpgp_status st = GLPGP_OK;
    qcheck ck;
    memset(&ck, 0, sizeof ck);
    qe *E = NULL;
    int ne = 0;
    double *angle = NULL;
    int *val = NULL;
    unsigned char *bnd = NULL;
    GLPGP_CHECK_GOTO(st, glpgp_qcheck_run(q, domain, h, 0.25 * h, &ck), done);
    GLPGP_CHECK_GOTO(st, face_edges(q, &E, &ne), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)q->nv + 1, sizeof(double), &angle), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)q->nv + 1, sizeof(int), &val), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)q->nv + 1, 1, &bnd), done);
    /* edges: valence, boundary, lengths */
    o->edges = ne;
    o->len_min = INFINITY;
    o->len_max = 0.0;
    double lsum = 0.0;
    for (int i = 0; i < ne; i++) {
        val[E[i].a]++;
        val[E[i].b]++;
        if (E[i].nface == 1) {
            o->boundary_edges++;
            bnd[E[i].a] = bnd[E[i].b] = 1;
        }
        double l = hypot(q->xy[2 * E[i].a] - q->xy[2 * E[i].b], q->xy[2 * E[i].a + 1] - q->xy[2 * E[i].b + 1]) / h;
        lsum += l;
        o->len_min = fmin(o->len_min, l);
        o->len_max = fmax(o->len_max, l);
    }
    o->len_mean = ne ? lsum / ne : 0.0;
    GLPGP_CHECK_GOTO(st, face_stats(q, &ck, o, angle), done);
    GLPGP_CHECK_GOTO(st, origin_stats(q, domain, h, o), done);
    /* valences */
    for (int i = 0; i < q->nv; i++) {
        int vb = val[i] > GLPGP_QUADS_MAXVAL ? GLPGP_QUADS_MAXVAL : val[i];
        if (bnd[i]) {
            o->valence_boundary[vb]++;
            if (val[i] != (int)lround(angle[i] / (PI_ / 2)) + 1) o->irregular_boundary++;
        } else {
            o->valence_interior[vb]++;
            if (val[i] != 4) o->irregular_interior++;
        }
    }
    o->irregular = o->irregular_interior + o->irregular_boundary;
    o->orientation = ck.orientation;
    o->nonmanifold_edges = ck.nonmanifold_edges;
    o->pinched = ck.pinched;
    o->boundary_loops = ck.boundary_loops;
    o->domain_loops = domain ? domain->nloops : -1;
    o->corners_lost = ck.corners_lost;
    if (!domain) o->outside = o->far_faces = -1;
    o->bnd_vertex_dist = domain ? ck.bnd_vertex_dist / h : -1.0;
    o->area_ratio = -1.0;
    o->hausdorff = o->dist_quad_to_domain = o->dist_domain_to_quad = -1.0;
    o->gap_edges = -1;
    if (domain) {
        o->area_ratio = domain->area > 0 ? o->area / domain->area : -1.0;
        o->domain_area = domain->area;
        GLPGP_CHECK_GOTO(st, boundary_stats(q, domain, h, E, ne, o), done);
    }
    validity(domain, o);
done:
    glpgp_qcheck_free(&ck);
    free(E);
    free(angle);
    free(val);
    free(bnd);
    return st;
}

glpgp_status glpgp_quads_quality_cross(const glpgp_quadmesh *q, const glpgp_cross_sing *sing, int nsing,
                                       double radius, glpgp_quads_report *qq)
{
    if (!(radius > 0) || !isfinite(radius))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "quad quality: singularity radius must be > 0");
    if (nsing < 0 || (nsing > 0 && !sing))
        return GLPGP_FAIL(GLPGP_ERR_ARG, "quad quality: bad singularity list");
    if (!q || q->nf < 1) return GLPGP_FAIL(GLPGP_ERR_ARG, "quad quality: empty mesh");
    qe *E = NULL;
    int ne = 0, *val = NULL;
    unsigned char *bnd = NULL, *hit = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, face_edges(q, &E, &ne), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)q->nv + 1, sizeof(int), &val), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)q->nv + 1, 1, &bnd), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nsing + 1, 1, &hit), done);
    /* valence = distinct edges at the vertex; boundary = on an edge of one face
     * (as in glpgp_quads_quality) */
    for (int i = 0; i < ne; i++) {
        val[E[i].a]++;
        val[E[i].b]++;
        if (E[i].nface == 1) bnd[E[i].a] = bnd[E[i].b] = 1;
    }
    /* an irregular interior vertex p is near when min_s |p - s| <= radius */
    int near = 0, far = 0;
    const double r2 = radius * radius;
    for (int i = 0; i < q->nv; i++) {
        if (bnd[i] || val[i] == 4) continue;
        const double x = q->xy[2 * i], y = q->xy[2 * i + 1];
        int is_near = 0;
        for (int k = 0; k < nsing; k++) {
            const double dx = x - sing[k].x, dy = y - sing[k].y;
            if (dx * dx + dy * dy <= r2) {
                is_near = 1;
                hit[k] = 1;
            }
        }
        if (is_near)
            near++;
        else
            far++;
    }
    qq->cross_singularities = nsing;
    qq->cross_radius = radius;
    qq->irregular_near_cross = near;
    qq->irregular_far_cross = far;
    qq->cross_matched = 0;
    for (int k = 0; k < nsing; k++) qq->cross_matched += hit[k];
done:
    free(E);
    free(val);
    free(bnd);
    free(hit);
    return st;
}

static void quads_print(FILE *f, const glpgp_quads_report *qq, const char *prefix)
{
    const char *p = prefix ? prefix : "";
    fprintf(f, "%squads          %d quads, %d other faces (", p, qq->quads, qq->others);
    int first = 1;
    for (int b = 0; b < 8; b++) {
        if (b == 1 || !qq->others_by_size[b]) continue;
        fprintf(f, "%s%d x %s%d-gon", first ? "" : ", ", qq->others_by_size[b], b == 7 ? ">=" : "",
                b + 3);
        first = 0;
    }
    fprintf(f, "%s), %d vertices\n", first ? "none" : "", qq->vertices);
    fprintf(f, "%s  valence      interior", p);
    for (int v = 0; v <= GLPGP_QUADS_MAXVAL; v++)
        if (qq->valence_interior[v]) fprintf(f, " %d:%d", v, qq->valence_interior[v]);
    fprintf(f, "   boundary");
    for (int v = 0; v <= GLPGP_QUADS_MAXVAL; v++)
        if (qq->valence_boundary[v]) fprintf(f, " %d:%d", v, qq->valence_boundary[v]);
    fprintf(f, "\n");
    fprintf(f, "%s  irregular    %d (interior %d, boundary %d)\n", p, qq->irregular,
            qq->irregular_interior, qq->irregular_boundary);
    if (qq->cross_singularities >= 0)
        fprintf(f, "%s  near cross   irregular interior %d within %.4g of the %d cross-field singularities, "
                   "%d farther; %d of %d singularities have one\n",
                p, qq->irregular_near_cross, qq->cross_radius, qq->cross_singularities, qq->irregular_far_cross,
                qq->cross_matched, qq->cross_singularities);
    fprintf(f, "%s  scaled jac.  min %.3f  mean %.3f  1%% %.3f;  inverted %d, degenerate %d\n", p,
            qq->sj_min, qq->sj_mean, qq->sj_p01, qq->inverted, qq->degenerate);
    fprintf(f, "%s  corners      min %.3f of what the sharp domain corners allow; %d quads below %.1f that none limits\n",
            p, qq->sj_min_corner, qq->below_sj_goal, GLPGP_QUADS_SJ_GOAL);
    fprintf(f, "%s  origin       grid %d, strips %d, repair %d, fallback %d: %.1f%% from the repair%s\n", p,
            qq->quads_by_origin[GLPGP_QFACE_GRID], qq->quads_by_origin[GLPGP_QFACE_CLOSED],
            qq->quads_by_origin[GLPGP_QFACE_PAVED], qq->quads_by_origin[GLPGP_QFACE_FALLBACK], 100.0 * qq->repaired_share,
            qq->repaired_share > GLPGP_QUADS_MOSTLY_REPAIRED ? " (mostly repaired)" : "");
    fprintf(f, "%s  edge / h     mean %.3f  min %.3f  max %.3f\n", p, qq->len_mean, qq->len_min,
            qq->len_max);
    if (qq->closing.closed_polygons || qq->closing.split_even || qq->closing.smoothed_vertices)
        fprintf(f, "%s  closing      %d odd faces closed by strips (%d to the boundary), %d quads cut, "
                   "%d turns, %d even faces split; %d vertices smoothed\n",
                p, qq->closing.closed_polygons, qq->closing.strips_to_boundary, qq->closing.strip_quads, qq->closing.strip_turns,
                qq->closing.split_even, qq->closing.smoothed_vertices);
    if (qq->repair.rounds || qq->repair.chord_strips)
        fprintf(f, "%s  repair       %d faces removed, %d regions re-meshed with %d quads (%d by the region mesher, "
                   "%d by the fallback), %d boundary vertices snapped, %d grid lines for boundary chords (%d rounds)%s\n",
                p, qq->repair.removed_faces, qq->repair.regions, qq->repair.new_quads, qq->repair.paved_regions,
                qq->repair.fallback_regions, qq->repair.snapped, qq->repair.chord_strips, qq->repair.rounds,
                qq->repair.whole_domain == 2   ? "; the whole domain from the input triangles"
                : qq->repair.whole_domain == 1 ? "; the whole domain meshed again"
                                                : "");
    if (qq->cleanup.doublets + qq->cleanup.collapses + qq->cleanup.rotations)
        fprintf(f, "%s  cleanup      %d doublets removed, %d quads collapsed, %d edges rotated (valence cost %d -> %d)\n",
                p, qq->cleanup.doublets, qq->cleanup.collapses, qq->cleanup.rotations, qq->cleanup.cost_before,
                qq->cleanup.cost_after);
    if (qq->repair.sharp_tips || qq->repair.flat_corners || qq->repair.shaped_vertices)
        fprintf(f, "%s  shape        %d sharp tips re-meshed, %d flat boundary corners split, %d vertices moved to raise the worst corner\n",
                p, qq->repair.sharp_tips, qq->repair.flat_corners, qq->repair.shaped_vertices);
    if (qq->surface)
        fprintf(f, "%s  surface      Hausdorff %.3f h (quads->surface %.3f h, surface->quads %.3f h), "
                   "area %.5g of %.5g (ratio %.4f), Euler %d of %d, boundary loops %d of %d\n",
                p, qq->hausdorff, qq->dist_quad_to_domain, qq->dist_domain_to_quad, qq->area, qq->domain_area,
                qq->area_ratio, qq->euler, qq->domain_euler, qq->boundary_loops, qq->domain_loops);
    else if (qq->hausdorff >= 0)
        fprintf(f, "%s  boundary     Hausdorff %.3f h (quads->domain %.3f h, domain->quads %.3f h), "
                   "area %.5g of %.5g (ratio %.4f), loops %d of %d\n",
                p, qq->hausdorff, qq->dist_quad_to_domain, qq->dist_domain_to_quad, qq->area,
                qq->domain_area, qq->area_ratio, qq->boundary_loops, qq->domain_loops);
    else
        fprintf(f, "%s  boundary     %d loops (no domain given)\n", p, qq->boundary_loops);
    fprintf(f, "%s  topology     non-manifold edges %d, pinched vertices %d, overlapping faces %d", p,
            qq->nonmanifold_edges, qq->pinched, qq->overlaps);
    if (qq->outside >= 0) fprintf(f, ", outside %d, corners lost %d", qq->outside, qq->corners_lost);
    fprintf(f, "\n");
    char why[512];
    if (glpgp_quads_invalid_text(qq, 0, why, sizeof why))
        fprintf(f, "%s  valid        no: %s\n", p, why);
    else
        fprintf(f, "%s  valid        yes\n", p);
}

const char *glpgp_quads_bad_name(unsigned b)
{
    switch (b) {
    case GLPGP_QUADS_BAD_INVERTED: return "inverted";
    case GLPGP_QUADS_BAD_DEGENERATE: return "degenerate";
    case GLPGP_QUADS_BAD_NONMANIFOLD: return "non-manifold";
    case GLPGP_QUADS_BAD_NONQUAD: return "non-quad";
    case GLPGP_QUADS_BAD_PINCHED: return "pinched";
    case GLPGP_QUADS_BAD_OVERLAP: return "overlap";
    case GLPGP_QUADS_BAD_OUTSIDE: return "outside";
    case GLPGP_QUADS_BAD_LOOPS: return "boundary-loops";
    case GLPGP_QUADS_BAD_AREA: return "area";
    case GLPGP_QUADS_BAD_HAUSDORFF: return "hausdorff";
    case GLPGP_QUADS_BAD_GAPS: return "gaps";
    case GLPGP_QUADS_BAD_CORNERS: return "corners";
    case GLPGP_QUADS_BAD_EMPTY: return "empty";
    case GLPGP_QUADS_BAD_TOPOLOGY: return "topology";
    default: return NULL;
    }
}

/* The report's numbers are written with '.' whatever the process's locale
 * (glpgp_cnum: this thread alone in the "C" locale meanwhile). */
void glpgp_quads_print(FILE *f, const glpgp_quads_report *qq, const char *prefix)
{
    glpgp_cnum cn;
    glpgp_cnum_begin(&cn);
    quads_print(f, qq, prefix);
    glpgp_cnum_end(&cn);
}

static unsigned invalid_text(const glpgp_quads_report *qq, unsigned ignore, char *buf, size_t n);

unsigned glpgp_quads_invalid_text(const glpgp_quads_report *qq, unsigned ignore, char *buf, size_t n)
{
    glpgp_cnum cn;
    glpgp_cnum_begin(&cn);
    const unsigned b = invalid_text(qq, ignore, buf, n);
    glpgp_cnum_end(&cn);
    return b;
}

static unsigned invalid_text(const glpgp_quads_report *qq, unsigned ignore, char *buf, size_t n)
{
    unsigned b = qq->invalid & ~ignore;
    size_t w = 0;
    if (n) buf[0] = 0;
#define ADD(...)                                                                       \
    do {                                                                               \
        if (w < n) {                                                                   \
            int r_ = snprintf(buf + w, n - w, "%s", w ? ", " : "");                    \
            if (r_ > 0) w += (size_t)r_;                                               \
        }                                                                              \
        if (w < n) {                                                                   \
            int r_ = snprintf(buf + w, n - w, __VA_ARGS__);                            \
            if (r_ > 0) w += (size_t)r_;                                               \
        }                                                                              \
    } while (0)
    if (b & GLPGP_QUADS_BAD_EMPTY) ADD("no face");
    if (b & GLPGP_QUADS_BAD_INVERTED) ADD("%d inverted faces", qq->inverted);
    if (b & GLPGP_QUADS_BAD_DEGENERATE) ADD("%d degenerate faces", qq->degenerate);
    if (b & GLPGP_QUADS_BAD_NONMANIFOLD) ADD("%d non-manifold edges", qq->nonmanifold_edges);
    if (b & GLPGP_QUADS_BAD_NONQUAD) ADD("%d non-quad faces", qq->others);
    if (b & GLPGP_QUADS_BAD_PINCHED) ADD("%d pinched vertices", qq->pinched);
    if (b & GLPGP_QUADS_BAD_OVERLAP) ADD("%d overlapping faces", qq->overlaps);
    if (b & GLPGP_QUADS_BAD_OUTSIDE) ADD("%d faces outside the domain", qq->outside);
    if (b & GLPGP_QUADS_BAD_LOOPS) ADD("boundary loops %d of %d", qq->boundary_loops, qq->domain_loops);
    if (b & GLPGP_QUADS_BAD_AREA) ADD("area ratio %.4f", qq->area_ratio);
    if (b & GLPGP_QUADS_BAD_HAUSDORFF) ADD("Hausdorff %.3f h", qq->hausdorff);
    if (b & GLPGP_QUADS_BAD_GAPS) ADD("%d boundary edges away from the domain boundary", (int)qq->gap_edges);
    if (b & GLPGP_QUADS_BAD_CORNERS) ADD("%d domain corners lost", qq->corners_lost);
    if (b & GLPGP_QUADS_BAD_TOPOLOGY) ADD("Euler characteristic %d of %d", qq->euler, qq->domain_euler);
#undef ADD
    return b;
}

