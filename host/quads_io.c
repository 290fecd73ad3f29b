/* quads_io.c: everything about quad meshes besides their extraction (see
 * quads.h): the quality report (valences, scaled Jacobian, edge lengths,
 * boundary Hausdorff distance), its printed and JSON forms, the OBJ / legacy
 * VTK / Gmsh MSH 4.1 writers and the MSH 4.1/2.2 quad/triangle reader. */
#include "cli.h"
#include "quads.h"
#include "quads_geom.h"
#include "output.h"

#include <ctype.h>
#include <errno.h>
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

glpgp_status glpgp_quads_quality(const glpgp_quadmesh *q, const glpgp_mesh *domain, double h,
                                 glpgp_quad_quality *o)
{
    memset(o, 0, sizeof *o);
    if (!(h > 0)) return GLPGP_FAIL(GLPGP_ERR_ARG, "quad quality: size h must be > 0");
    if (!q || q->nf < 1) return GLPGP_FAIL(GLPGP_ERR_ARG, "quad quality: empty mesh");
    o->h = h;
    o->vertices = q->nv;
    o->faces = q->nf;
    o->singular[0] = o->singular[1] = -1;
    o->closing = q->closing;
    glpgp_status st = GLPGP_OK;
    qe *E = NULL;
    int ne = 0;
    double *sj = NULL, *angle = NULL;
    int *val = NULL;
    unsigned char *bnd = NULL;
    segset SD, SQ;
    memset(&SD, 0, sizeof SD);
    memset(&SQ, 0, sizeof SQ);
    GLPGP_CHECK_GOTO(st, face_edges(q, &E, &ne), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)q->nf + 1, sizeof(double), &sj), done);
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
        if (E[i].nface > 2) o->nonmanifold_edges++;
        double l = hypot(q->xy[2 * E[i].a] - q->xy[2 * E[i].b],
                         q->xy[2 * E[i].a + 1] - q->xy[2 * E[i].b + 1]) / h;
        lsum += l;
        o->len_min = fmin(o->len_min, l);
        o->len_max = fmax(o->len_max, l);
    }
    o->len_mean = ne ? lsum / ne : 0.0;

    /* faces: corners, area, scaled Jacobian, interior angles per vertex */
    int nsj = 0;
    double sjsum = 0.0;
    for (int f = 0; f < q->nf; f++) {
        int s = q->face_start[f], k = q->face_start[f + 1] - s;
        const int *v = q->face_vert + s;
        if (k == 4)
            o->quads++;
        else {
            o->others++;
            int b = k - 3;
            if (b < 0) b = 0;
            if (b > 7) b = 7;
            o->others_by_size[b]++;
        }
        double area = 0.0, fmin_sj = INFINITY;
        int degen = 0;
        for (int i = 0; i < k; i++) {
            int a = v[i], b = v[(i + 1) % k], c = v[(i + k - 1) % k];
            for (int j = i + 1; j < k; j++)
                if (v[j] == a) degen = 1;
            double ax = q->xy[2 * a], ay = q->xy[2 * a + 1];
            double e1x = q->xy[2 * b] - ax, e1y = q->xy[2 * b + 1] - ay;
            double e2x = q->xy[2 * c] - ax, e2y = q->xy[2 * c + 1] - ay;
            double l1 = hypot(e1x, e1y), l2 = hypot(e2x, e2y);
            if (l1 < 1e-9 * h) degen = 1;
            area += 0.5 * (ax * q->xy[2 * b + 1] - q->xy[2 * b] * ay);
            /* scaled Jacobian at corner a: sin of the angle from e1 to e2 */
            double cr = e1x * e2y - e1y * e2x;
            double sjc = (l1 > 0 && l2 > 0) ? cr / (l1 * l2) : 0.0;
            fmin_sj = fmin(fmin_sj, sjc);
            /* interior angle at a (from e1 counter-clockwise to e2) */
            double ang = atan2(cr, e1x * e2x + e1y * e2y);
            if (ang < 0) ang += 2 * PI_;
            angle[a] += ang;
        }
        o->area += area;
        if (fabs(area) < 1e-9 * h * h) degen = 1;
        if (degen) o->degenerate++;
        if (area <= 0.0 || (k == 4 && fmin_sj < 0.0)) o->inverted++;
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

    /* valences */
    for (int i = 0; i < q->nv; i++) {
        int vb = val[i] > GLPGP_QUAD_MAXVAL ? GLPGP_QUAD_MAXVAL : val[i];
        if (bnd[i]) {
            o->valence_boundary[vb]++;
            int ideal = (int)lround(angle[i] / (PI_ / 2)) + 1;
            if (val[i] != ideal) o->irregular_boundary++;
        } else {
            o->valence_interior[vb]++;
            if (val[i] != 4) o->irregular_interior++;
        }
    }
    o->irregular = o->irregular_interior + o->irregular_boundary;

    /* boundary distance */
    o->hausdorff = o->dist_quad_to_domain = o->dist_domain_to_quad = -1.0;
    o->gap_edges = -1;
    if (domain) {
        o->domain_area = domain->area;
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
            double emax = 0.0;
            for (int k = 0; k <= 8; k++) {
                double t = k / 8.0;
                double d = segset_dist(&SD, p[0] + t * (p[2] - p[0]), p[1] + t * (p[3] - p[1]));
                emax = fmax(emax, d);
            }
            dq = fmax(dq, emax);
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
    }
done:
    free(E);
    free(sj);
    free(angle);
    free(val);
    free(bnd);
    segset_free(&SD);
    segset_free(&SQ);
    return st;
}

void glpgp_quads_print(FILE *f, const glpgp_quad_quality *qq, const char *prefix)
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
    for (int v = 0; v <= GLPGP_QUAD_MAXVAL; v++)
        if (qq->valence_interior[v]) fprintf(f, " %d:%d", v, qq->valence_interior[v]);
    fprintf(f, "   boundary");
    for (int v = 0; v <= GLPGP_QUAD_MAXVAL; v++)
        if (qq->valence_boundary[v]) fprintf(f, " %d:%d", v, qq->valence_boundary[v]);
    fprintf(f, "\n");
    fprintf(f, "%s  irregular    %d (interior %d, boundary %d)\n", p, qq->irregular,
            qq->irregular_interior, qq->irregular_boundary);
    fprintf(f, "%s  scaled jac.  min %.3f  mean %.3f  1%% %.3f;  inverted %d, degenerate %d\n", p,
            qq->sj_min, qq->sj_mean, qq->sj_p01, qq->inverted, qq->degenerate);
    fprintf(f, "%s  edge / h     mean %.3f  min %.3f  max %.3f\n", p, qq->len_mean, qq->len_min,
            qq->len_max);
    if (qq->closing.closed_polygons || qq->closing.split_even || qq->closing.smoothed_vertices)
        fprintf(f, "%s  closing      %d odd faces closed by strips (%d to the boundary), %d quads cut, "
                   "%d turns, %d even faces split; %d vertices smoothed\n",
                p, qq->closing.closed_polygons, qq->closing.strips_to_boundary, qq->closing.strip_quads, qq->closing.strip_turns,
                qq->closing.split_even, qq->closing.smoothed_vertices);
    if (qq->hausdorff >= 0)
        fprintf(f, "%s  boundary     Hausdorff %.3f h (quads->domain %.3f h, domain->quads %.3f h), "
                   "area %.5g of %.5g\n",
                p, qq->hausdorff, qq->dist_quad_to_domain, qq->dist_domain_to_quad, qq->area,
                qq->domain_area);
}

/* ---- JSON -------------------------------------------------------------- */

static void jnum(FILE *f, double v)
{
    if (!isfinite(v))
        fputs("null", f);
    else
        fprintf(f, "%.10g", v);
}

void glpgp_quads_write_json(FILE *f, const glpgp_quad_quality *qq)
{
    fprintf(f, "{\"vertices\": %d, \"faces\": %d, \"quads\": %d, \"other_faces\": %d, ",
            qq->vertices, qq->faces, qq->quads, qq->others);
    fputs("\"other_faces_by_corners\": {", f);
    int first = 1;
    for (int b = 0; b < 8; b++) {
        if (b == 1 || !qq->others_by_size[b]) continue;
        fprintf(f, "%s\"%s%d\": %d", first ? "" : ", ", b == 7 ? ">=" : "", b + 3,
                qq->others_by_size[b]);
        first = 0;
    }
    fputs("}, \"valence\": {", f);
    for (int s = 0; s < 2; s++) {
        const int *h = s ? qq->valence_boundary : qq->valence_interior;
        fprintf(f, "%s\"%s\": {", s ? ", " : "", s ? "boundary" : "interior");
        first = 1;
        for (int v = 0; v <= GLPGP_QUAD_MAXVAL; v++) {
            if (!h[v]) continue;
            fprintf(f, "%s\"%s%d\": %d", first ? "" : ", ", v == GLPGP_QUAD_MAXVAL ? ">=" : "", v,
                    h[v]);
            first = 0;
        }
        fputs("}", f);
    }
    fprintf(f, "}, \"irregular_vertices\": {\"interior\": %d, \"boundary\": %d, \"total\": %d}, ",
            qq->irregular_interior, qq->irregular_boundary, qq->irregular);
    fputs("\"scaled_jacobian\": {\"min\": ", f);
    jnum(f, qq->sj_min);
    fputs(", \"mean\": ", f);
    jnum(f, qq->sj_mean);
    fputs(", \"p01\": ", f);
    jnum(f, qq->sj_p01);
    fprintf(f, "}, \"inverted\": %d, \"degenerate\": %d, ", qq->inverted, qq->degenerate);
    fprintf(f, "\"edges\": {\"count\": %d, \"boundary\": %d, \"nonmanifold\": %d}, ", qq->edges,
            qq->boundary_edges, qq->nonmanifold_edges);
    fputs("\"edge_length_over_h\": {\"mean\": ", f);
    jnum(f, qq->len_mean);
    fputs(", \"min\": ", f);
    jnum(f, qq->len_min);
    fputs(", \"max\": ", f);
    jnum(f, qq->len_max);
    fputs("}, \"h\": ", f);
    jnum(f, qq->h);
    fputs(", \"area\": ", f);
    jnum(f, qq->area);
    fputs(", \"domain_area\": ", f);
    if (qq->hausdorff >= 0)
        jnum(f, qq->domain_area);
    else
        fputs("null", f);
    fputs(", \"boundary_distance_over_h\": ", f);
    if (qq->hausdorff >= 0) {
        fputs("{\"hausdorff\": ", f);
        jnum(f, qq->hausdorff);
        fputs(", \"quads_to_domain\": ", f);
        jnum(f, qq->dist_quad_to_domain);
        fputs(", \"domain_to_quads\": ", f);
        jnum(f, qq->dist_domain_to_quad);
        fputs("}, \"gap_edges\": ", f);
        jnum(f, qq->gap_edges);
    } else {
        fputs("null, \"gap_edges\": null", f);
    }
    fputs(", \"singular_triangles\": ", f);
    if (qq->singular[0] >= 0)
        fprintf(f, "{\"u\": %d, \"v\": %d}", qq->singular[0], qq->singular[1]);
    else
        fputs("null", f);
    fprintf(f,
            ", \"closing\": {\"odd_faces_closed\": %d, \"strips_to_boundary\": %d, \"quads_cut\": %d, "
            "\"turns\": %d, \"even_faces_split\": %d, \"smoothed_vertices\": %d}",
            qq->closing.closed_polygons, qq->closing.strips_to_boundary, qq->closing.strip_quads, qq->closing.strip_turns, qq->closing.split_even,
            qq->closing.smoothed_vertices);
    fputs("}", f);
}

glpgp_status glpgp_quads_write_json_file(const glpgp_quad_quality *qq, const char *path)
{
    glpgp_atomic_file af;
    GLPGP_CHECK(glpgp_atomic_open(&af, path));
    fputs("{\"quads\": ", af.f);
    glpgp_quads_write_json(af.f, qq);
    fputs("}\n", af.f);
    GLPGP_CHECK(glpgp_atomic_commit(&af));
    return GLPGP_OK;
}

glpgp_status glpgp_quads_append_json(const char *path, const glpgp_quad_quality *qq)
{
    FILE *f = fopen(path, "rb");
    if (!f) return GLPGP_FAIL(GLPGP_ERR_IO, "cannot read '%s': %s", path, strerror(errno));
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    if (!buf) {
        fclose(f);
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading '%s'", path);
    }
    size_t k;
    while ((k = fread(buf + n, 1, cap - n, f)) > 0) {
        n += k;
        if (n == cap) {
            char *nb = realloc(buf, cap *= 2);
            if (!nb) {
                free(buf);
                fclose(f);
                return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading '%s'", path);
            }
            buf = nb;
        }
    }
    fclose(f);
    /* last non-space character must be the object's closing brace */
    size_t end = n;
    while (end > 0 && isspace((unsigned char)buf[end - 1])) end--;
    size_t open = 0;
    while (open < n && isspace((unsigned char)buf[open])) open++;
    if (end == 0 || buf[end - 1] != '}' || open >= n || buf[open] != '{') {
        free(buf);
        return GLPGP_FAIL(GLPGP_ERR_FORMAT, "'%s' does not hold a JSON object", path);
    }
    size_t close = end - 1;
    size_t before = close;
    while (before > 0 && isspace((unsigned char)buf[before - 1])) before--;
    int empty = buf[before - 1] == '{';
    glpgp_atomic_file af;
    glpgp_status st = glpgp_atomic_open(&af, path);
    if (st != GLPGP_OK) {
        free(buf);
        glpgp_error_trace(__FILE__, __LINE__);
        return st;
    }
    fwrite(buf, 1, before, af.f);
    fputs(empty ? "\"quads\": " : ",\n  \"quads\": ", af.f);
    glpgp_quads_write_json(af.f, qq);
    fputs("\n}\n", af.f);
    free(buf);
    GLPGP_CHECK(glpgp_atomic_commit(&af));
    return GLPGP_OK;
}

/* ---- writers ----------------------------------------------------------- */

int glpgp_quads_path_supported(const char *path)
{
    return path && (glpgp_has_ext(path, ".obj") || glpgp_has_ext(path, ".vtk") || glpgp_has_ext(path, ".msh"));
}

double glpgp_poly_min_sj(const double *xy, const int *v, int n)
{
    double m = INFINITY;
    for (int i = 0; i < n; i++) {
        const double *a = xy + 2 * v[i], *b = xy + 2 * v[(i + 1) % n], *c = xy + 2 * v[(i + n - 1) % n];
        double e1x = b[0] - a[0], e1y = b[1] - a[1], e2x = c[0] - a[0], e2y = c[1] - a[1];
        double l = hypot(e1x, e1y) * hypot(e2x, e2y);
        m = fmin(m, l > 0 ? (e1x * e2y - e1y * e2x) / l : -1.0);
    }
    return m;
}

double glpgp_hex_centre_split(const double *xy, const int *hx, int *o_best, double *xb, double *yb)
{
    double best = -INFINITY;
    for (int o = 0; o < 2; o++) {
        double ax = 0, ay = 0, bx = 0, by = 0; /* centroids of the joined / the other corners */
        for (int i = 0; i < 3; i++) {
            ax += xy[2 * hx[(o + 2 * i) % 6]] / 3;
            ay += xy[2 * hx[(o + 2 * i) % 6] + 1] / 3;
            bx += xy[2 * hx[(o + 2 * i + 1) % 6]] / 3;
            by += xy[2 * hx[(o + 2 * i + 1) % 6] + 1] / 3;
        }
        for (int t = 0; t <= 4; t++) {
            double w = 0.25 * t;
            /* local copy: the three corners of each quad, then X */
            double pq[8];
            int id[4] = {0, 1, 2, 3};
            pq[6] = (1 - w) * ax + w * bx;
            pq[7] = (1 - w) * ay + w * by;
            double sj = INFINITY;
            for (int i = 0; i < 3; i++) {
                for (int k = 0; k < 3; k++) {
                    pq[2 * k] = xy[2 * hx[(o + 2 * i + k) % 6]];
                    pq[2 * k + 1] = xy[2 * hx[(o + 2 * i + k) % 6] + 1];
                }
                sj = fmin(sj, glpgp_poly_min_sj(pq, id, 4));
            }
            if (sj > best) {
                best = sj;
                *o_best = o;
                *xb = pq[6];
                *yb = pq[7];
            }
        }
    }
    return best;
}

/* Minimum corner scaled Jacobian of face f. */
static double face_sj(const glpgp_quadmesh *q, int f)
{
    int s = q->face_start[f];
    return glpgp_poly_min_sj(q->xy, q->face_vert + s, q->face_start[f + 1] - s);
}

static void write_obj(FILE *f, const glpgp_quadmesh *q)
{
    fprintf(f, "# glpgp %s quad mesh: %d vertices, %d faces\n", GLPGP_VERSION, q->nv, q->nf);
    for (int i = 0; i < q->nv; i++) fprintf(f, "v %.17g %.17g 0\n", q->xy[2 * i], q->xy[2 * i + 1]);
    for (int fa = 0; fa < q->nf; fa++) {
        fputc('f', f);
        for (int j = q->face_start[fa]; j < q->face_start[fa + 1]; j++)
            fprintf(f, " %d", q->face_vert[j] + 1);
        fputc('\n', f);
    }
}

static void write_vtk(FILE *f, const glpgp_quadmesh *q)
{
    fprintf(f, "# vtk DataFile Version 3.0\nglpgp %s quad mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n",
            GLPGP_VERSION);
    fprintf(f, "POINTS %d double\n", q->nv);
    for (int i = 0; i < q->nv; i++) fprintf(f, "%.17g %.17g 0\n", q->xy[2 * i], q->xy[2 * i + 1]);
    int nfv = q->face_start[q->nf];
    fprintf(f, "CELLS %d %d\n", q->nf, q->nf + nfv);
    for (int fa = 0; fa < q->nf; fa++) {
        fprintf(f, "%d", q->face_start[fa + 1] - q->face_start[fa]);
        for (int j = q->face_start[fa]; j < q->face_start[fa + 1]; j++)
            fprintf(f, " %d", q->face_vert[j]);
        fputc('\n', f);
    }
    fprintf(f, "CELL_TYPES %d\n", q->nf);
    for (int fa = 0; fa < q->nf; fa++)
        fprintf(f, "%d\n", q->face_start[fa + 1] - q->face_start[fa] == 4 ? 9 : 7);
    fprintf(f, "CELL_DATA %d\nSCALARS corners int 1\nLOOKUP_TABLE default\n", q->nf);
    for (int fa = 0; fa < q->nf; fa++) fprintf(f, "%d\n", q->face_start[fa + 1] - q->face_start[fa]);
    fprintf(f, "SCALARS scaled_jacobian double 1\nLOOKUP_TABLE default\n");
    for (int fa = 0; fa < q->nf; fa++) fprintf(f, "%.6g\n", face_sj(q, fa));
}

static glpgp_status write_vtk_valence(FILE *f, const glpgp_quadmesh *q)
{
    qe *E = NULL;
    int ne = 0;
    int *val = NULL;
    GLPGP_CHECK(face_edges(q, &E, &ne));
    glpgp_status st = glpgp_calloc((size_t)q->nv + 1, sizeof(int), &val);
    if (st == GLPGP_OK) {
        for (int i = 0; i < ne; i++) {
            val[E[i].a]++;
            val[E[i].b]++;
        }
        fprintf(f, "POINT_DATA %d\nSCALARS valence int 1\nLOOKUP_TABLE default\n", q->nv);
        for (int i = 0; i < q->nv; i++) fprintf(f, "%d\n", val[i]);
    }
    free(E);
    free(val);
    return st;
}

static void write_msh(FILE *f, const glpgp_quadmesh *q)
{
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int i = 0; i < q->nv; i++) {
        x0 = fmin(x0, q->xy[2 * i]);
        x1 = fmax(x1, q->xy[2 * i]);
        y0 = fmin(y0, q->xy[2 * i + 1]);
        y1 = fmax(y1, q->xy[2 * i + 1]);
    }
    /* split every face into quads (0, 2i+1, 2i+2, 2i+3) plus one triangle
     * (0, n-2, n-1) when the corner count n is odd */
    long nquad = 0, ntri = 0;
    for (int fa = 0; fa < q->nf; fa++) {
        int k = q->face_start[fa + 1] - q->face_start[fa];
        nquad += (k - 2) / 2;
        ntri += (k % 2);
    }
    int nblocks = (nquad > 0) + (ntri > 0);
    fprintf(f, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
    fprintf(f, "$Entities\n0 0 1 0\n1 %.17g %.17g 0 %.17g %.17g 0 0 0\n$EndEntities\n", x0, y0, x1,
            y1);
    fprintf(f, "$Nodes\n1 %d 1 %d\n2 1 0 %d\n", q->nv, q->nv, q->nv);
    for (int i = 0; i < q->nv; i++) fprintf(f, "%d\n", i + 1);
    for (int i = 0; i < q->nv; i++) fprintf(f, "%.17g %.17g 0\n", q->xy[2 * i], q->xy[2 * i + 1]);
    fprintf(f, "$EndNodes\n$Elements\n%d %ld 1 %ld\n", nblocks, nquad + ntri, nquad + ntri);
    long tag = 1;
    if (nquad > 0) {
        fprintf(f, "2 1 3 %ld\n", nquad);
        for (int fa = 0; fa < q->nf; fa++) {
            const int *v = q->face_vert + q->face_start[fa];
            int k = q->face_start[fa + 1] - q->face_start[fa];
            for (int i = 0; 2 * i + 3 < k; i++)
                fprintf(f, "%ld %d %d %d %d\n", tag++, v[0] + 1, v[2 * i + 1] + 1, v[2 * i + 2] + 1,
                        v[2 * i + 3] + 1);
        }
    }
    if (ntri > 0) {
        fprintf(f, "2 1 2 %ld\n", ntri);
        for (int fa = 0; fa < q->nf; fa++) {
            const int *v = q->face_vert + q->face_start[fa];
            int k = q->face_start[fa + 1] - q->face_start[fa];
            if (k % 2) fprintf(f, "%ld %d %d %d\n", tag++, v[0] + 1, v[k - 2] + 1, v[k - 1] + 1);
        }
    }
    fprintf(f, "$EndElements\n");
}

glpgp_status glpgp_quads_write(const glpgp_quadmesh *q, const char *path)
{
    if (!q || !path) return GLPGP_FAIL(GLPGP_ERR_ARG, "quad writer: no mesh or path");
    int kind = glpgp_has_ext(path, ".obj") ? 1 : glpgp_has_ext(path, ".vtk") ? 2 : glpgp_has_ext(path, ".msh") ? 3 : 0;
    if (!kind)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "quad mesh output '%s': extension must be .obj, .vtk or .msh",
                          path);
    glpgp_atomic_file af;
    GLPGP_CHECK(glpgp_atomic_open(&af, path));
    if (kind == 1)
        write_obj(af.f, q);
    else if (kind == 2) {
        write_vtk(af.f, q);
        glpgp_status st = write_vtk_valence(af.f, q);
        if (st != GLPGP_OK) {
            glpgp_atomic_abort(&af);
            return st;
        }
    } else
        write_msh(af.f, q);
    GLPGP_CHECK(glpgp_atomic_commit(&af));
    return GLPGP_OK;
}

/* ---- MSH reader -------------------------------------------------------- */

typedef struct growi {
    int *v;
    size_t n, cap;
} growi;

static int growi_push(growi *g, int x)
{
    if (g->n == g->cap) {
        size_t nc = g->cap ? 2 * g->cap : 4096;
        int *p = realloc(g->v, nc * sizeof *p);
        if (!p) return 0;
        g->v = p;
        g->cap = nc;
    }
    g->v[g->n++] = x;
    return 1;
}

static int find_section(FILE *f, const char *name)
{
    char line[512];
    while (fgets(line, sizeof line, f)) {
        size_t n = strcspn(line, "\r\n");
        line[n] = '\0';
        if (!strcmp(line, name)) return 1;
    }
    return 0;
}

glpgp_status glpgp_quads_read_msh(const char *path, glpgp_quadmesh **out)
{
    *out = NULL;
    FILE *f = fopen(path, "r");
    if (!f) return GLPGP_FAIL(GLPGP_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
    glpgp_status st = GLPGP_OK;
    double ver = 0;
    int filetype = 0, dsize = 0;
    long maxtag = 0;
    double *nxy = NULL;  /* by tag */
    growi fs = {0}, fv = {0};
    int *used = NULL;
    glpgp_quadmesh *q = NULL;
    if (!find_section(f, "$MeshFormat") || fscanf(f, "%lf %d %d", &ver, &filetype, &dsize) != 3) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: not a Gmsh MSH file (no $MeshFormat)", path);
        goto done;
    }
    if (filetype != 0) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: binary MSH not supported, save as ASCII", path);
        goto done;
    }
    int v4 = ver >= 4.0;
    if (!find_section(f, "$Nodes")) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: no $Nodes section", path);
        goto done;
    }
    if (v4) {
        long nblk, nnodes, mintag;
        if (fscanf(f, "%ld %ld %ld %ld", &nblk, &nnodes, &mintag, &maxtag) != 4 || maxtag < 1 ||
            maxtag > 100000000L) {
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad $Nodes header", path);
            goto done;
        }
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)maxtag + 1, 2 * sizeof(double), &nxy), done);
        long *tags = NULL;
        for (long b = 0; b < nblk; b++) {
            int edim, etag, par;
            long nin;
            if (fscanf(f, "%d %d %d %ld", &edim, &etag, &par, &nin) != 4 || nin < 0) {
                st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad node block", path);
                goto done;
            }
            long *nt = realloc(tags, (size_t)(nin + 1) * sizeof *nt);
            if (!nt) {
                free(tags);
                st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory");
                goto done;
            }
            tags = nt;
            for (long i = 0; i < nin; i++)
                if (fscanf(f, "%ld", &tags[i]) != 1 || tags[i] < 1 || tags[i] > maxtag) {
                    free(tags);
                    st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad node tag", path);
                    goto done;
                }
            int npar = par ? edim : 0;
            for (long i = 0; i < nin; i++) {
                double x, y, z, u;
                if (fscanf(f, "%lf %lf %lf", &x, &y, &z) != 3) {
                    free(tags);
                    st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad node coordinates", path);
                    goto done;
                }
                for (int k = 0; k < npar; k++)
                    if (fscanf(f, "%lf", &u) != 1) break;
                nxy[2 * tags[i]] = x;
                nxy[2 * tags[i] + 1] = y;
            }
        }
        free(tags);
    } else {
        long nnodes;
        if (fscanf(f, "%ld", &nnodes) != 1 || nnodes < 1 || nnodes > 100000000L) {
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad $Nodes header", path);
            goto done;
        }
        long pos = ftell(f);
        maxtag = 0;
        for (long i = 0; i < nnodes; i++) {
            long t;
            double x, y, z;
            if (fscanf(f, "%ld %lf %lf %lf", &t, &x, &y, &z) != 4 || t < 1) {
                st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad node line", path);
                goto done;
            }
            if (t > maxtag) maxtag = t;
        }
        if (maxtag > 100000000L) {
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: node tag too large", path);
            goto done;
        }
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)maxtag + 1, 2 * sizeof(double), &nxy), done);
        fseek(f, pos, SEEK_SET);
        for (long i = 0; i < nnodes; i++) {
            long t;
            double x, y, z;
            if (fscanf(f, "%ld %lf %lf %lf", &t, &x, &y, &z) != 4) break;
            nxy[2 * t] = x;
            nxy[2 * t + 1] = y;
        }
    }
    if (!find_section(f, "$Elements")) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: no $Elements section", path);
        goto done;
    }
    if (!growi_push(&fs, 0)) goto nomem;
    if (v4) {
        long nblk, nel, a, b;
        if (fscanf(f, "%ld %ld %ld %ld", &nblk, &nel, &a, &b) != 4) {
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad $Elements header", path);
            goto done;
        }
        for (long bl = 0; bl < nblk; bl++) {
            int edim, etag, type;
            long nin;
            if (fscanf(f, "%d %d %d %ld", &edim, &etag, &type, &nin) != 4) {
                st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad element block", path);
                goto done;
            }
            int nper = type == 15 ? 1 : type == 1 ? 2 : type == 2 ? 3 : type == 3 ? 4 : -1;
            if (nper < 0) {
                st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: element type %d not supported (only points, "
                                                  "lines, triangles, quadrangles)", path, type);
                goto done;
            }
            for (long i = 0; i < nin; i++) {
                long t, nd[4];
                if (fscanf(f, "%ld", &t) != 1) goto badel;
                for (int k = 0; k < nper; k++)
                    if (fscanf(f, "%ld", &nd[k]) != 1 || nd[k] < 1 || nd[k] > maxtag) goto badel;
                if (type == 2 || type == 3) {
                    for (int k = 0; k < nper; k++)
                        if (!growi_push(&fv, (int)nd[k])) goto nomem;
                    if (!growi_push(&fs, (int)fv.n)) goto nomem;
                }
            }
        }
    } else {
        long nel;
        if (fscanf(f, "%ld", &nel) != 1) {
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad $Elements header", path);
            goto done;
        }
        for (long i = 0; i < nel; i++) {
            long t, type, ntag, tg, nd[4];
            if (fscanf(f, "%ld %ld %ld", &t, &type, &ntag) != 3) goto badel;
            for (long k = 0; k < ntag; k++)
                if (fscanf(f, "%ld", &tg) != 1) goto badel;
            int nper = type == 15 ? 1 : type == 1 ? 2 : type == 2 ? 3 : type == 3 ? 4 : -1;
            if (nper < 0) {
                st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: element type %ld not supported", path, type);
                goto done;
            }
            for (int k = 0; k < nper; k++)
                if (fscanf(f, "%ld", &nd[k]) != 1 || nd[k] < 1 || nd[k] > maxtag) goto badel;
            if (type == 2 || type == 3) {
                for (int k = 0; k < nper; k++)
                    if (!growi_push(&fv, (int)nd[k])) goto nomem;
                if (!growi_push(&fs, (int)fv.n)) goto nomem;
            }
        }
    }
    if (fs.n < 2) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: no triangles or quadrangles", path);
        goto done;
    }
    /* renumber the used nodes, orient faces counter-clockwise */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)maxtag + 1, sizeof(int), &used), done);
    for (long i = 0; i <= maxtag; i++) used[i] = -1;
    GLPGP_CHECK_GOTO(st, glpgp_calloc(1, sizeof *q, &q), done);
    int nv = 0;
    for (size_t i = 0; i < fv.n; i++)
        if (used[fv.v[i]] < 0) used[fv.v[i]] = nv++;
    q->nv = nv;
    q->nf = (int)fs.n - 1;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * nv, sizeof(double), &q->xy), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(fs.n, sizeof(int), &q->face_start), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(fv.n, sizeof(int), &q->face_vert), done);
    for (long t = 1; t <= maxtag; t++)
        if (used[t] >= 0) {
            q->xy[2 * used[t]] = nxy[2 * t];
            q->xy[2 * used[t] + 1] = nxy[2 * t + 1];
        }
    memcpy(q->face_start, fs.v, fs.n * sizeof(int));
    for (size_t i = 0; i < fv.n; i++) q->face_vert[i] = used[fv.v[i]];
    for (int fa = 0; fa < q->nf; fa++) {
        int s = q->face_start[fa], k = q->face_start[fa + 1] - s;
        int *v = q->face_vert + s;
        double a = 0.0;
        for (int i = 0; i < k; i++) {
            int p = v[i], r = v[(i + 1) % k];
            a += q->xy[2 * p] * q->xy[2 * r + 1] - q->xy[2 * r] * q->xy[2 * p + 1];
        }
        if (a < 0)
            for (int i = 0; i < k / 2; i++) {
                int tmp = v[i];
                v[i] = v[k - 1 - i];
                v[k - 1 - i] = tmp;
            }
    }
    *out = q;
    q = NULL;
    goto done;
badel:
    st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: bad element line", path);
    goto done;
nomem:
    st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading '%s'", path);
done:
    fclose(f);
    free(nxy);
    free(fs.v);
    free(fv.v);
    free(used);
    glpgp_quadmesh_destroy(&q);
    return st;
}
