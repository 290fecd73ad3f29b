/* mesh/surface_shapes.c: the built-in surfaces of glpgp/surface.h: sphere
 * and cube (a cube's faces as n x n grids, projected to the sphere with
 * equal-angle spacing), hemisphere (the sphere's upper half), torus (a
 * periodic grid), genus2 (a polycube with two holes, Loop-subdivided into a
 * smooth closed surface of genus 2), halfcyl and its planar twin
 * halfcyl_flat (a structured strip rolled up without stretching). All
 * deterministic, outward normals. */
#include "glpgp/kinds.h"
#include "glpgp/surface.h"
#include "glpgp/util.h"

#include "surface_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const k_surface_shapes[] = {"sphere", "torus", "genus2", "cube", "hemisphere", "halfcyl",
                                               "halfcyl_flat", NULL};

int glpgp_surface_shape_known(const char *name)
{
    for (int i = 0; k_surface_shapes[i]; i++)
        if (!strcmp(name, k_surface_shapes[i])) return 1;
    return 0;
}

/* growable vertex / triangle lists */
typedef struct sbuild {
    double *x;
    int *t;
    int nv, nt, cap_v, cap_t;
} sbuild;

static glpgp_status sb_reserve(sbuild *b, int nv, int nt)
{
    GLPGP_CHECK(glpgp_malloc((size_t)nv, 3 * sizeof(double), &b->x));
    GLPGP_CHECK(glpgp_malloc((size_t)nt, 3 * sizeof(int), &b->t));
    b->cap_v = nv;
    b->cap_t = nt;
    return GLPGP_OK;
}

static int sb_vertex(sbuild *b, double x, double y, double z)
{
    double *p = b->x + 3 * b->nv;
    p[0] = x;
    p[1] = y;
    p[2] = z;
    return b->nv++;
}

static void sb_tri(sbuild *b, int p, int q, int r)
{
    int *t = b->t + 3 * b->nt++;
    t[0] = p;
    t[1] = q;
    t[2] = r;
}

/* The quad p q r s (counter-clockwise) as two triangles over the diagonal
 * p r (alt 0) or q s (alt 1). */
static void sb_quad(sbuild *b, int p, int q, int r, int s, int alt)
{
    if (alt) {
        sb_tri(b, p, q, s);
        sb_tri(b, q, r, s);
    } else {
        sb_tri(b, p, q, r);
        sb_tri(b, p, r, s);
    }
}

static void sb_free(sbuild *b)
{
    free(b->x);
    free(b->t);
}

/* The cube [-1, 1]^3's faces as n x n grids (shared edges and corners),
 * projected to the unit sphere with equal-angle spacing (sphere) or kept
 * (cube, scaled to edge 1); z >= 0 only (hemisphere, n even). */
static glpgp_status cubed(int n, int kind, sbuild *b)
{
    /* a vertex per grid point of the cube's surface: index by (i, j, k) in
     * [0, n]^3 on the surface, through a map of (n+1)^3 entries */
    const long n1 = n + 1, np = n1 * n1 * n1;
    int *id = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK(glpgp_malloc((size_t)np, sizeof(int), &id));
    for (long q = 0; q < np; q++) id[q] = -1;
    GLPGP_CHECK_GOTO(st, sb_reserve(b, (int)(6 * n1 * n1), 12 * n * n), done);
    /* face f: axis a = f / 2, side sgn; grid (u, w) along the other two axes */
    for (int f = 0; f < 6; f++) {
        const int ax = f / 2, s = f % 2, a1 = (ax + 1) % 3, a2 = (ax + 2) % 3;
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                int c[4], g[4][3];
                const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
                int skip = 0;
                for (int k = 0; k < 4; k++) {
                    g[k][ax] = s ? n : 0;
                    g[k][a1] = i + di[k];
                    g[k][a2] = j + dj[k];
                    if (kind == 2 && g[k][2] < n / 2) skip = 1; /* hemisphere: z >= 0 only */
                }
                if (skip) continue;
                for (int k = 0; k < 4; k++) {
                    const long q = (g[k][0] * n1 + g[k][1]) * n1 + g[k][2];
                    if (id[q] < 0) {
                        double p[3];
                        for (int e = 0; e < 3; e++) {
                            const double u = 2.0 * g[k][e] / n - 1.0;
                            p[e] = kind == 1 ? 0.5 * u : tan(0.25 * GLPGP_PI * u);
                        }
                        if (kind != 1) {
                            const double r = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
                            for (int e = 0; e < 3; e++) p[e] /= r;
                        }
                        id[q] = sb_vertex(b, p[0], p[1], p[2]);
                    }
                    c[k] = id[q];
                }
                /* (a1, a2, ax) is right-handed: counter-clockwise about +ax; reversed on the - side */
                const int alt = (i + j) % 2;
                if (s)
                    sb_quad(b, c[0], c[1], c[2], c[3], alt);
                else
                    sb_quad(b, c[0], c[3], c[2], c[1], alt);
            }
    }
done:
    free(id);
    return st;
}

/* Torus of radii R = 1, r = 0.4: nu x nw periodic grid. */
static glpgp_status torus(int nu, int nw, sbuild *b)
{
    GLPGP_CHECK(sb_reserve(b, nu * nw, 2 * nu * nw));
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nw; j++) {
            const double u = 2.0 * GLPGP_PI * i / nu, w = 2.0 * GLPGP_PI * j / nw;
            const double rr = 1.0 + 0.4 * cos(w);
            sb_vertex(b, rr * cos(u), rr * sin(u), 0.4 * sin(w));
        }
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nw; j++) {
            const int i1 = (i + 1) % nu, j1 = (j + 1) % nw;
            /* d/du x d/dw points outward */
            sb_quad(b, i * nw + j, i1 * nw + j, i1 * nw + j1, i * nw + j1, (i + j) % 2);
        }
    return GLPGP_OK;
}

/* The strip of ncol x nrow cells rolled into half a cylinder of radius 2
 * and height 2 (flat = 0), or unrolled into the plane with the same
 * triangles (column width the chord 2 R sin(pi / (2 ncol))). */
static glpgp_status halfcyl(int ncol, int nrow, int flat, sbuild *b)
{
    const double R = 2.0, H = 2.0, chord = 2.0 * R * sin(GLPGP_PI / (2.0 * ncol));
    GLPGP_CHECK(sb_reserve(b, (ncol + 1) * (nrow + 1), 2 * ncol * nrow));
    for (int k = 0; k <= ncol; k++)
        for (int j = 0; j <= nrow; j++) {
            const double phi = GLPGP_PI * k / ncol, y = H * j / nrow;
            if (flat)
                sb_vertex(b, chord * k, y, 0.0);
            else
                sb_vertex(b, R * cos(phi), R * sin(phi), y);
        }
    for (int k = 0; k < ncol; k++)
        for (int j = 0; j < nrow; j++) {
            const int p = k * (nrow + 1) + j;
            sb_quad(b, p, p + nrow + 1, p + nrow + 2, p + 1, (k + j) % 2);
        }
    return GLPGP_OK;
}

/* One round of Loop subdivision of the closed surface m into b. */
static glpgp_status loop_round(const glpgp_mesh *m, sbuild *b)
{
    const glpgp_surface *s = m->surf;
    const int nv = m->nv, nt = m->nt;
    int *emid = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK(sb_reserve(b, nv + s->nedges, 4 * nt));
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt, sizeof(int), &emid), done);
    /* old vertices: (1 - n beta) v + beta sum of the ring */
    for (int v = 0; v < nv; v++) {
        double acc[3] = {0.0, 0.0, 0.0};
        int n = 0, c = s->vstart[v];
        do {
            const int q = m->tri[c - c % 3 + (c % 3 + 1) % 3];
            for (int e = 0; e < 3; e++) acc[e] += m->xyz[3 * q + e];
            n++;
            c = s->twin[c - c % 3 + (c % 3 + 2) % 3];
        } while (c >= 0 && c != s->vstart[v]);
        const double beta = n == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * n);
        const double *p = m->xyz + 3 * v;
        sb_vertex(b, (1 - n * beta) * p[0] + beta * acc[0], (1 - n * beta) * p[1] + beta * acc[1],
                  (1 - n * beta) * p[2] + beta * acc[2]);
    }
    /* edge points: 3/8 (a + b) + 1/8 (c + d), at the larger half-edge of each edge */
    for (int h = 0; h < 3 * nt; h++) {
        const int g = s->twin[h];
        if (g > h) continue;
        const int pa = m->tri[h], pb = m->tri[h - h % 3 + (h % 3 + 1) % 3];
        const int pc = m->tri[h - h % 3 + (h % 3 + 2) % 3], pd = m->tri[g - g % 3 + (g % 3 + 2) % 3];
        double p[3];
        for (int e = 0; e < 3; e++)
            p[e] = 0.375 * (m->xyz[3 * pa + e] + m->xyz[3 * pb + e]) + 0.125 * (m->xyz[3 * pc + e] + m->xyz[3 * pd + e]);
        emid[h] = emid[g] = sb_vertex(b, p[0], p[1], p[2]);
    }
    for (int t = 0; t < nt; t++) {
        const int *v = m->tri + 3 * t, *e = emid + 3 * t; /* e[a]: midpoint of edge v[a] v[a+1] */
        sb_tri(b, v[0], e[0], e[2]);
        sb_tri(b, v[1], e[1], e[0]);
        sb_tri(b, v[2], e[2], e[1]);
        sb_tri(b, e[0], e[1], e[2]);
    }
done:
    free(emid);
    return st;
}

/* The boundary of the 5 x 3 x 1 voxel slab with holes at cells (1, 1) and
 * (3, 1): a polycube of genus 2, outward quads split in two. */
static glpgp_status polycube2(sbuild *b)
{
    enum { X = 5, Y = 3, Z = 1 };
    int id[(X + 1) * (Y + 1) * (Z + 1)];
    for (int q = 0; q < (X + 1) * (Y + 1) * (Z + 1); q++) id[q] = -1;
    GLPGP_CHECK(sb_reserve(b, (X + 1) * (Y + 1) * (Z + 1), 200));
#define FULL(i, j, k) ((i) >= 0 && (i) < X && (j) >= 0 && (j) < Y && (k) >= 0 && (k) < Z && \
                       !((j) == 1 && ((i) == 1 || (i) == 3)))
    for (int i = 0; i < X; i++)
        for (int j = 0; j < Y; j++)
            for (int k = 0; k < Z; k++) {
                if (!FULL(i, j, k)) continue;
                for (int f = 0; f < 6; f++) {
                    const int ax = f / 2, s = f % 2, a1 = (ax + 1) % 3, a2 = (ax + 2) % 3;
                    int g[3] = {i, j, k};
                    g[ax] += s ? 1 : -1;
                    if (FULL(g[0], g[1], g[2])) continue;
                    int c[4];
                    const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
                    for (int q = 0; q < 4; q++) {
                        int p[3] = {i, j, k};
                        p[ax] += s;
                        p[a1] += di[q];
                        p[a2] += dj[q];
                        const int key = (p[0] * (Y + 1) + p[1]) * (Z + 1) + p[2];
                        if (id[key] < 0) id[key] = sb_vertex(b, p[0], p[1], p[2]);
                        c[q] = id[key];
                    }
                    if (s)
                        sb_quad(b, c[0], c[1], c[2], c[3], 0);
                    else
                        sb_quad(b, c[0], c[3], c[2], c[1], 0);
                }
            }
#undef FULL
    return GLPGP_OK;
}

/* genus2: the polycube, Loop-subdivided until about nverts vertices. */
static glpgp_status genus2(long nverts, glpgp_mesh **out)
{
    sbuild b;
    memset(&b, 0, sizeof b);
    glpgp_mesh *m = NULL;
    GLPGP_CHECK(polycube2(&b));
    glpgp_status st = glpgp_mesh_create_surface(b.nv, b.x, b.nt, b.t, &m);
    sb_free(&b);
    GLPGP_CHECK(st);
    /* each round: about 4x the vertices; stop nearest to nverts */
    while (st == GLPGP_OK && fabs(log((double)4 * m->nv / nverts)) < fabs(log((double)m->nv / nverts))) {
        memset(&b, 0, sizeof b);
        glpgp_mesh *n = NULL;
        st = loop_round(m, &b);
        if (st == GLPGP_OK) st = glpgp_mesh_create_surface(b.nv, b.x, b.nt, b.t, &n);
        sb_free(&b);
        glpgp_mesh_destroy(&m);
        m = n;
    }
    if (st != GLPGP_OK) {
        glpgp_mesh_destroy(&m);
        return st;
    }
    *out = m;
    return GLPGP_OK;
}

glpgp_status glpgp_surface_generate(const char *shape, long nverts, glpgp_mesh **out)
{
    *out = NULL;
    if (!glpgp_surface_shape_known(shape)) return GLPGP_FAIL(GLPGP_ERR_ARG, "unknown surface shape '%s'", shape);
    if (nverts < 16) nverts = 16;
    if (!strcmp(shape, "genus2")) return genus2(nverts, out);
    sbuild b;
    memset(&b, 0, sizeof b);
    glpgp_status st;
    const double nd = (double)nverts;
    if (!strcmp(shape, "sphere") || !strcmp(shape, "cube")) {
        const int n = (int)fmax(2.0, round(sqrt((nd - 2.0) / 6.0)));
        st = cubed(n, !strcmp(shape, "cube"), &b);
    } else if (!strcmp(shape, "hemisphere")) {
        /* about 3 n^2 + n vertices above the equator */
        int n = 2 * (int)fmax(1.0, round(sqrt(nd / 3.0) / 2.0));
        st = cubed(n, 2, &b);
    } else if (!strcmp(shape, "torus")) {
        const int nw = (int)fmax(4.0, round(sqrt(nd / 2.5))), nu = (int)fmax(6.0, round(nd / nw));
        st = torus(nu, nw, &b);
    } else {
        const int ncol = (int)fmax(6.0, round(sqrt(nd * GLPGP_PI / 2.0)));
        const int nrow = (int)fmax(2.0, round(nd / ncol));
        st = halfcyl(ncol, nrow, !strcmp(shape, "halfcyl_flat"), &b);
    }
    if (st == GLPGP_OK) {
        if (!strcmp(shape, "halfcyl_flat")) { /* a planar mesh: the plane z = 0 */
            double *xy = NULL;
            st = glpgp_malloc((size_t)b.nv, 2 * sizeof(double), &xy);
            if (st == GLPGP_OK) {
                for (int v = 0; v < b.nv; v++) {
                    xy[2 * v] = b.x[3 * v];
                    xy[2 * v + 1] = b.x[3 * v + 1];
                }
                st = glpgp_mesh_create(b.nv, xy, b.nt, b.t, out);
            }
            free(xy);
        } else {
            st = glpgp_mesh_create_surface(b.nv, b.x, b.nt, b.t, out);
        }
    }
    sb_free(&b);
    return st;
}
