/* image/poly.c: planar domains as polygon files (glpgp/image.h,
 * glpgp_polygons_read): Triangle's .poly format, read into the
 * glpgp_polygons of the mask pipeline so that glpgp_mask_mesh (and with it
 * `glpgp mesh` and `glpgp solve`) meshes them with Gmsh.
 *
 *   # comments run to the end of a line
 *   <vertices> 2 <attributes> <markers>
 *   <i> <x> <y> [attributes ...] [marker]        one line per vertex
 *   <segments> <markers>
 *   <i> <a> <b> [marker]                          one line per segment
 *   <holes>
 *   <i> <x> <y>                                   one line per hole point
 *
 * Vertex numbers start at 0 or 1 (the first vertex line decides). The first
 * vertex attribute, when there is one and it is > 0, is the local mesh size
 * at the vertex (Gmsh grades the mesh between the boundary points: this is
 * how graded meshes are made); the others and the markers are ignored. The
 * segments must form closed loops (every vertex in exactly two segments, or
 * in none), loops must not cross. Which loops are holes follows from their
 * nesting (even-odd: a loop inside an odd number of others is a hole); the
 * hole points, when given, must lie outside the domain so read (a check, not
 * an input). */
#include "glpgp/image.h"
#include "glpgp/util.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define POLY_MAX_VERTICES 50000000L

typedef struct ptok {
    FILE *f;
    const char *path;
    int line;
    char buf[4096];
    char *p; /* next character of buf, NULL: read a line */
} ptok;

/* Next line with content (comments stripped); 0 at the end of the file. */
static int next_line(ptok *t)
{
    while (fgets(t->buf, sizeof t->buf, t->f)) {
        t->line++;
        char *c = strchr(t->buf, '#');
        if (c) *c = 0;
        char *s = t->buf;
        while (*s && isspace((unsigned char)*s)) s++;
        if (*s) {
            t->p = s;
            return 1;
        }
    }
    return 0;
}

/* Read up to n numbers of the current line into v; returns the count. */
static int line_numbers(ptok *t, double *v, int n)
{
    int k = 0;
    char *s = t->p;
    while (k < n) {
        while (*s && isspace((unsigned char)*s)) s++;
        if (!*s) break;
        char *end = NULL;
        errno = 0;
        double x = glpgp_strtod(s, &end);
        if (end == s || errno == ERANGE || !isfinite(x) || (*end && !isspace((unsigned char)*end))) return -1;
        v[k++] = x;
        s = end;
    }
    return k;
}

static glpgp_status header(ptok *t, const char *what, double *v, int min, int max, int *got)
{
    if (!next_line(t)) return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: ends before the %s", t->path, what);
    int k = line_numbers(t, v, max);
    if (k < min) return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s:%d: bad %s line", t->path, t->line, what);
    *got = k;
    return GLPGP_OK;
}

static int is_count(double x, long max) { return x >= 0 && x <= max && x == floor(x); }

/* Nesting and orientation of the loops of P (n, start, xy, size set): the
 * parent of each hole (the smallest loop containing it), outer loops (even
 * depth) turned counter-clockwise and holes clockwise (size[] with them),
 * area[], total_area, nouter, nholes. */
static glpgp_status polygons_orient(glpgp_polygons *P)
{
    const int nl = P->n;
    int *depth = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)nl, sizeof(int), &depth));
    P->nouter = P->nholes = 0;
    /* nesting: depth = number of loops containing a vertex of the loop */
    for (int l = 0; l < nl; l++) {
        const double *p = P->xy + 2 * P->start[l];
        double bestA = INFINITY;
        P->parent[l] = -1;
        for (int o = 0; o < nl; o++) {
            if (o == l) continue;
            int in = 0, s = P->start[o], n = P->start[o + 1] - s;
            for (int i = 0, j = n - 1; i < n; j = i++) {
                const double *a = P->xy + 2 * (s + i), *b = P->xy + 2 * (s + j);
                if ((a[1] > p[1]) != (b[1] > p[1]) && p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0])
                    in = !in;
            }
            if (!in) continue;
            depth[l]++;
            double A = glpgp_polygon_area(P->xy + 2 * s, n);
            if (fabs(A) < bestA) {
                bestA = fabs(A);
                P->parent[l] = o;
            }
        }
    }
    /* orientation: outer loops (even depth) counter-clockwise, holes clockwise */
    P->total_area = 0;
    for (int l = 0; l < nl; l++) {
        int s = P->start[l], n = P->start[l + 1] - s;
        double A = glpgp_polygon_area(P->xy + 2 * s, n);
        int hole_l = depth[l] % 2;
        if ((A < 0) != hole_l) {
            for (int i = 0; i < n / 2; i++)
                for (int c = 0; c < 2; c++) {
                    double tmp = P->xy[2 * (s + i) + c];
                    P->xy[2 * (s + i) + c] = P->xy[2 * (s + n - 1 - i) + c];
                    P->xy[2 * (s + n - 1 - i) + c] = tmp;
                }
            if (P->size)
                for (int i = 0; i < n / 2; i++) {
                    double tmp = P->size[s + i];
                    P->size[s + i] = P->size[s + n - 1 - i];
                    P->size[s + n - 1 - i] = tmp;
                }
            A = -A;
        }
        P->area[l] = A;
        P->total_area += A;
        if (hole_l)
            P->nholes++;
        else {
            P->nouter++;
            P->parent[l] = -1;
        }
    }
    free(depth);
    return GLPGP_OK;
}

/* A .poly file as read: vertices (numbered from base), the loops' adjacency,
 * hole points. */
typedef struct poly_file {
    ptok t;
    int nv, base, nholes;
    double *vxy, *vsize;    /* 2 nv, nv (0: no size) */
    int *deg, *adj;         /* nv, 2 nv: each vertex's segments (at most two) */
    double *hole;           /* 2 nholes */
} poly_file;

/* The vertex section: "<n> 2 <attributes> <0|1>", then "i x y [size]". */
static glpgp_status poly_vertices(poly_file *F)
{
    ptok *t = &F->t;
    double v[64];
    int k;
    GLPGP_CHECK(header(t, "vertex count", v, 4, 4, &k));
    if (!is_count(v[0], POLY_MAX_VERTICES) || v[0] < 3 || v[1] != 2 || !is_count(v[2], 60) || !is_count(v[3], 1))
        return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s:%d: expected '<vertices >= 3> 2 <attributes> <0|1>'", t->path, t->line);
    const int nv = (int)v[0], nattr = (int)v[2];
    F->nv = nv;
    GLPGP_CHECK(glpgp_malloc((size_t)2 * nv, sizeof(double), &F->vxy));
    GLPGP_CHECK(glpgp_malloc((size_t)nv, sizeof(double), &F->vsize));
    F->base = -1;
    for (int i = 0; i < nv; i++) {
        GLPGP_CHECK(header(t, "vertex", v, 3, 3 + nattr + 1, &k));
        if (F->base < 0) F->base = v[0] == 1 ? 1 : 0;
        if (v[0] != i + F->base)
            return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s:%d: vertex number %g, expected %d", t->path, t->line, v[0],
                              i + F->base);
        F->vxy[2 * i] = v[1];
        F->vxy[2 * i + 1] = v[2];
        F->vsize[i] = (nattr > 0 && k > 3 && v[3] > 0) ? v[3] : 0.0;
    }
    return GLPGP_OK;
}

/* The segment section: every vertex in at most two segments. */
static glpgp_status poly_segments(poly_file *F)
{
    ptok *t = &F->t;
    double v[64];
    int k;
    const int nv = F->nv, base = F->base;
    GLPGP_CHECK(header(t, "segment count", v, 1, 2, &k));
    if (!is_count(v[0], 4 * (long)nv) || v[0] < 3)
        return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s:%d: bad segment count", t->path, t->line);
    const int ns = (int)v[0];
    GLPGP_CHECK(glpgp_calloc((size_t)nv, sizeof(int), &F->deg));
    GLPGP_CHECK(glpgp_malloc((size_t)2 * nv, sizeof(int), &F->adj));
    int *deg = F->deg, *adj = F->adj;
    for (int i = 0; i < ns; i++) {
        GLPGP_CHECK(header(t, "segment", v, 3, 4, &k));
        int a = (int)v[1] - base, b = (int)v[2] - base;
        if (v[1] != floor(v[1]) || v[2] != floor(v[2]) || a < 0 || a >= nv || b < 0 || b >= nv || a == b)
            return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s:%d: segment with bad vertex numbers", t->path, t->line);
        if (deg[a] >= 2 || deg[b] >= 2)
            return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s:%d: vertex %d is in more than two segments (loops must be simple)",
                              t->path, t->line, (deg[a] >= 2 ? a : b) + base);
        adj[2 * a + deg[a]++] = b;
        adj[2 * b + deg[b]++] = a;
    }
    return GLPGP_OK;
}

/* The optional hole section: "<n>", then "i x y". */
static glpgp_status poly_holes(poly_file *F)
{
    ptok *t = &F->t;
    double v[64];
    int k;
    F->nholes = 0;
    if (!next_line(t)) return GLPGP_OK;
    k = line_numbers(t, v, 1);
    if (k != 1 || !is_count(v[0], 10000000)) return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s:%d: bad hole count", t->path, t->line);
    F->nholes = (int)v[0];
    GLPGP_CHECK(glpgp_malloc((size_t)2 * F->nholes + 2, sizeof(double), &F->hole));
    for (int i = 0; i < F->nholes; i++) {
        GLPGP_CHECK(header(t, "hole", v, 3, 3, &k));
        F->hole[2 * i] = v[1];
        F->hole[2 * i + 1] = v[2];
    }
    return GLPGP_OK;
}

/* The closed loops of segments, in P (start, n, xy, size; a size array
 * only where a vertex has one). */
static glpgp_status poly_loops(const poly_file *F, glpgp_polygons *P)
{
    const char *path = F->t.path;
    const int nv = F->nv, *deg = F->deg, *adj = F->adj;
    for (int i = 0; i < nv; i++)
        if (deg[i] == 1)
            return GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: vertex %d ends an open chain of segments (loops must close)", path,
                              i + F->base);
    int *vloop = NULL, *order = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv + 1, sizeof(int), &vloop), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv + 1, sizeof(int), &order), done);
    for (int i = 0; i < nv; i++) vloop[i] = -1;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv + 1, sizeof(int), &P->start), done);
    int nl = 0, w = 0;
    for (int i = 0; i < nv; i++) {
        if (deg[i] != 2 || vloop[i] >= 0) continue;
        P->start[nl] = w;
        int prev = -1, cur = i;
        do {
            vloop[cur] = nl;
            order[w++] = cur;
            int nx = adj[2 * cur] != prev ? adj[2 * cur] : adj[2 * cur + 1];
            if (adj[2 * cur] == adj[2 * cur + 1]) nx = adj[2 * cur];
            prev = cur;
            cur = nx;
        } while (cur != i && w <= nv);
        if (w - P->start[nl] < 3) {
            st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: a loop with fewer than 3 vertices", path);
            goto done;
        }
        nl++;
    }
    if (nl == 0) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: no closed loop of segments", path);
        goto done;
    }
    P->start[nl] = w;
    P->n = nl;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * w, sizeof(double), &P->xy), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)w, sizeof(double), &P->size), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nl, sizeof(double), &P->area), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nl, sizeof(int), &P->parent), done);
    int any_size = 0;
    for (int j = 0; j < w; j++) {
        P->xy[2 * j] = F->vxy[2 * order[j]];
        P->xy[2 * j + 1] = F->vxy[2 * order[j] + 1];
        P->size[j] = F->vsize[order[j]];
        any_size |= P->size[j] > 0;
    }
    if (!any_size) {
        free(P->size);
        P->size = NULL;
    }
done:
    free(vloop);
    free(order);
    return st;
}

/* Hole points must be outside the domain (even-odd over every loop). */
static glpgp_status poly_check_holes(const poly_file *F, const glpgp_polygons *P)
{
    for (int i = 0; i < F->nholes; i++) {
        const double *p = F->hole + 2 * i;
        int in = 0;
        for (int l = 0; l < P->n; l++) {
            int s = P->start[l], n = P->start[l + 1] - s;
            for (int a = 0, b = n - 1; a < n; b = a++) {
                const double *A = P->xy + 2 * (s + a), *B = P->xy + 2 * (s + b);
                if ((A[1] > p[1]) != (B[1] > p[1]) && p[0] < (B[0] - A[0]) * (p[1] - A[1]) / (B[1] - A[1]) + A[0])
                    in = !in;
            }
        }
        if (in)
            return GLPGP_FAIL(GLPGP_ERR_FORMAT,
                              "%s: hole point %d (%g, %g) lies inside the domain (holes are found from the nesting "
                              "of the loops)", F->t.path, i + F->base, p[0], p[1]);
    }
    return GLPGP_OK;
}

glpgp_status glpgp_polygons_read(const char *path, glpgp_polygons **out)
{
    *out = NULL;
    poly_file F;
    memset(&F, 0, sizeof F);
    F.t.path = path;
    F.t.f = fopen(path, "r");
    if (!F.t.f) return GLPGP_FAIL(GLPGP_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
    glpgp_status st = GLPGP_OK;
    glpgp_polygons *P = NULL;
    GLPGP_CHECK_GOTO(st, poly_vertices(&F), done);
    GLPGP_CHECK_GOTO(st, poly_segments(&F), done);
    GLPGP_CHECK_GOTO(st, poly_holes(&F), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc(1, sizeof *P, &P), done);
    GLPGP_CHECK_GOTO(st, poly_loops(&F, P), done);
    GLPGP_CHECK_GOTO(st, polygons_orient(P), done);
    GLPGP_CHECK_GOTO(st, poly_check_holes(&F, P), done);
    if (!(P->total_area > 0)) {
        st = GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: the loops enclose no area", path);
        goto done;
    }
    *out = P;
    P = NULL;
done:
    fclose(F.t.f);
    free(F.vxy);
    free(F.vsize);
    free(F.deg);
    free(F.adj);
    free(F.hole);
    glpgp_polygons_destroy(&P);
    return st;
}

glpgp_status glpgp_polygons_from_mesh(const glpgp_mesh *m, glpgp_polygons **out)
{
    *out = NULL;
    glpgp_polygons *P = NULL;
    glpgp_status st = GLPGP_OK;
    const int nl = m->nloops, np = m->loop_start[nl];
    GLPGP_CHECK(glpgp_calloc(1, sizeof *P, &P));
    P->n = nl;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nl + 1, sizeof(int), &P->start), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * np, sizeof(double), &P->xy), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nl, sizeof(double), &P->area), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nl, sizeof(int), &P->parent), done);
    for (int l = 0; l <= nl; l++) P->start[l] = m->loop_start[l];
    for (int i = 0; i < np; i++) {
        P->xy[2 * i] = m->xy[2 * m->loop_vertices[i]];
        P->xy[2 * i + 1] = m->xy[2 * m->loop_vertices[i] + 1];
    }
    GLPGP_CHECK_GOTO(st, polygons_orient(P), done);
    *out = P;
    P = NULL;
done:
    glpgp_polygons_destroy(&P);
    return st;
}
