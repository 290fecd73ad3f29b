/* mesh/surface_fix.c: glpgp_surface_fix (glpgp/surface.h), the repairs a
 * surface read from a file may need before glpgp_mesh_create_surface, which
 * stays strict:
 *  - orientation: each connected component's triangles oriented alike
 *    (a breadth-first walk across the manifold edges); a component that
 *    needed flips is oriented outward when it is closed (positive enclosed
 *    volume), else as most of its triangles were;
 *  - pinched vertices: a vertex whose triangles form several fans (two
 *    sheets or cones touching at a point) becomes one vertex per fan, so
 *    the sheets are meshed apart (the corners at a vertex joined across
 *    their shared edges, union-find).
 * What is not a mesh these repairs are defined on (indices out of range, a
 * repeated vertex in a triangle, a non-manifold edge, a non-orientable
 * component) is left alone: glpgp_mesh_create_surface names it. */
#include "glpgp/surface.h"
#include "glpgp/util.h"

#include "surface_internal.h"

#include <stdlib.h>
#include <string.h>

static int corner_next(int h) { return h - h % 3 + (h % 3 + 1) % 3; }

/* Whether every index is in range and no triangle repeats a vertex. */
static int well_formed(int nv, int nt, const int *tri)
{
    for (int t = 0; t < nt; t++) {
        const int *c = tri + 3 * t;
        for (int i = 0; i < 3; i++)
            if (c[i] < 0 || c[i] >= nv) return 0;
        if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) return 0;
    }
    return 1;
}

/* Six times the signed volume the triangles of one component enclose, with
 * flip[t] applied (closed components only: it does not depend on the origin). */
static double volume6(const double *xyz, const int *tri, const int *list, int n, const signed char *flip)
{
    double v = 0.0;
    for (int k = 0; k < n; k++) {
        const int t = list[k];
        const double *a = xyz + 3 * tri[3 * t], *b = xyz + 3 * tri[3 * t + 1], *c = xyz + 3 * tri[3 * t + 2];
        const double d = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                         a[2] * (b[0] * c[1] - b[1] * c[0]);
        v += flip[t] ? -d : d;
    }
    return v;
}

/* One component from seed: flip[] relative to the seed (queue holds its
 * triangles); 0 when it cannot be oriented, else 1, *closed whether no edge
 * of it is a boundary edge. */
static int walk_component(const int *tri, const int *twin, int seed, signed char *flip, int *queue, int *n,
                          int *closed)
{
    int head = 0, tail = 0;
    *closed = 1;
    flip[seed] = 0;
    queue[tail++] = seed;
    while (head < tail) {
        const int t = queue[head++];
        for (int i = 0; i < 3; i++) {
            const int h = 3 * t + i, g = twin[h];
            if (g < 0) {
                *closed = 0;
                continue;
            }
            const int u = g / 3;
            const signed char want = (signed char)(tri[h] == tri[g] ? !flip[t] : flip[t]);
            if (flip[u] < 0) {
                flip[u] = want;
                queue[tail++] = u;
            } else if (flip[u] != want) {
                return 0;
            }
        }
    }
    *n = tail;
    return 1;
}

/* The orientation repair; *orientable 0 when a component cannot be
 * oriented (then nothing is changed). */
static glpgp_status orient(glpgp_mesh *m, glpgp_surface *s, int *flipped, int *orientable)
{
    const int nt = m->nt;
    signed char *flip = NULL;
    int *queue = NULL;
    glpgp_status st = GLPGP_OK;
    *flipped = 0;
    *orientable = 1;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nt, 1, &flip), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nt, sizeof(int), &queue), done);
    memset(flip, -1, (size_t)nt);
    int start = 0; /* the component's triangles: queue[start, start + n) */
    for (int seed = 0; seed < nt; seed++) {
        if (flip[seed] >= 0) continue;
        int n = 0, closed = 0, ones = 0;
        if (!walk_component(m->tri, s->twin, seed, flip, queue + start, &n, &closed)) {
            *orientable = 0;
            goto done;
        }
        for (int k = 0; k < n; k++) ones += flip[queue[start + k]];
        const int invert = ones && (closed ? volume6(m->xyz, m->tri, queue + start, n, flip) < 0.0 : 2 * ones > n);
        if (invert)
            for (int k = 0; k < n; k++) flip[queue[start + k]] ^= 1;
        start += n;
    }
    for (int t = 0; t < nt; t++)
        if (flip[t]) {
            const int a = m->tri[3 * t + 1];
            m->tri[3 * t + 1] = m->tri[3 * t + 2];
            m->tri[3 * t + 2] = a;
            (*flipped)++;
        }
done:
    free(flip);
    free(queue);
    return st;
}

/* The pinched-vertex repair (consistent orientation, twin[] current): one
 * vertex per fan, the new ones appended to *xyz. */
static glpgp_status split_fans(glpgp_mesh *m, const int *twin, double **xyz, int *pinched, int *added)
{
    const int nv = m->nv, nc = 3 * m->nt;
    int *parent = NULL, *id = NULL, *root = NULL;
    glpgp_status st = GLPGP_OK;
    *pinched = *added = 0;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc, sizeof(int), &parent), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nc, sizeof(int), &id), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(int), &root), done);
    for (int c = 0; c < nc; c++) {
        parent[c] = c;
        id[c] = -1;
    }
    for (int v = 0; v < nv; v++) root[v] = -1;
    /* corner c's outgoing edge, run back by twin g, ends at c's vertex in g's triangle */
    for (int c = 0; c < nc; c++)
        if (twin[c] >= 0) parent[glpgp_uf_find(parent, c)] = glpgp_uf_find(parent, corner_next(twin[c]));
    int n = nv;
    for (int c = 0; c < nc; c++) {
        const int v = m->tri[c], r = glpgp_uf_find(parent, c);
        if (root[v] < 0) {
            root[v] = r;
            id[r] = v;
        } else if (id[r] < 0) { /* another fan at v (the first one keeps v) */
            id[r] = n++;
        }
    }
    if (n > nv) {
        size_t cap = (size_t)3 * nv;
        GLPGP_CHECK_GOTO(st, glpgp_grow(xyz, &cap, (size_t)3 * n, sizeof(double)), done);
        unsigned char *seen = (unsigned char *)root; /* reused: a pinched vertex counted once */
        memset(seen, 0, (size_t)nv);
        for (int c = 0; c < nc; c++) {
            const int r = glpgp_uf_find(parent, c), v = m->tri[c];
            if (id[r] == v) continue;
            if (!seen[v]) {
                seen[v] = 1;
                (*pinched)++;
            }
            memcpy(*xyz + 3 * id[r], *xyz + 3 * v, 3 * sizeof(double));
            m->tri[c] = id[r];
        }
        *added = n - nv;
    }
done:
    free(parent);
    free(id);
    free(root);
    return st;
}

glpgp_status glpgp_surface_fix(int *nv, double **xyz, int nt, int *tri, glpgp_surface_fixes *fx)
{
    glpgp_surface_fixes none = {0, 0, 0};
    if (!nv || !xyz || !*xyz || !tri || !fx) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_surface_fix: NULL argument");
    *fx = none;
    if (*nv < 3 || nt < 1 || !well_formed(*nv, nt, tri)) return GLPGP_OK;
    glpgp_mesh m;
    glpgp_surface s;
    memset(&m, 0, sizeof m);
    memset(&s, 0, sizeof s);
    m.nv = *nv;
    m.nt = nt;
    m.tri = tri;
    m.xyz = *xyz;
    glpgp_status st = GLPGP_OK;
    int samedir = -1, orientable = 1;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt, sizeof(int), &s.twin), done);
    if (glpgp_surface_twins(&m, &s, &samedir) != GLPGP_OK) { /* a non-manifold edge: left to the validation */
        glpgp_error_clear();
        goto done;
    }
    if (samedir >= 0) {
        GLPGP_CHECK_GOTO(st, orient(&m, &s, &fx->flipped, &orientable), done);
        if (!orientable) goto done;
        GLPGP_CHECK_GOTO(st, glpgp_surface_twins(&m, &s, &samedir), done);
    }
    GLPGP_CHECK_GOTO(st, split_fans(&m, s.twin, xyz, &fx->pinched, &fx->added), done);
    *nv += fx->added;
done:
    free(s.twin);
    return st;
}
