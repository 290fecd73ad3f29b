/* mesh/surface.c: glpgp_mesh_create_surface (glpgp/surface.h): validation
 * of a 3D triangle mesh as an oriented 2-manifold with or without boundary
 * (indices, degenerate triangles, non-manifold edges and vertices,
 * orientation), its boundary loops, components, Euler characteristic and
 * genus; the geometry (frames, connection) is surface_geom.c's. Every
 * rejection is one GLPGP_ERR_MESH line naming the triangles, edge or vertex. */
#include "glpgp/surface.h"
#include "glpgp/util.h"

#include "surface_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

void glpgp_surface_destroy(struct glpgp_surface **ps)
{
    if (!ps || !*ps) return;
    glpgp_surface *s = *ps;
    free(s->twin);
    free(s->vstart);
    free(s->vnormal);
    free(s->vtangent);
    free(s->angle_sum);
    free(s->scale);
    free(s->corner);
    free(s->eangle);
    free(s->rot);
    free(s->conn);
    free(s->dihedral);
    free(s->txy);
    free(s->tframe);
    free(s->holonomy);
    free(s->otri);
    free(s->obary);
    glpgp_mesh_destroy(&s->origin);
    free(s);
    *ps = NULL;
}

double glpgp_mesh_diagonal(const glpgp_mesh *m)
{
    if (m->xyz) {
        const double *b = m->bbox3;
        return sqrt((b[3] - b[0]) * (b[3] - b[0]) + (b[4] - b[1]) * (b[4] - b[1]) + (b[5] - b[2]) * (b[5] - b[2]));
    }
    return hypot(m->bbox[2] - m->bbox[0], m->bbox[3] - m->bbox[1]);
}

/* Indices, repeated corners, coordinates, unused vertices, degenerate
 * triangles (area at most min_area_rel diag^2); the bounding boxes. */
static glpgp_status check_input(glpgp_mesh *m, double min_area_rel)
{
    const int nv = m->nv, nt = m->nt;
    const double *x = m->xyz;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int v = 0; v < nv; v++)
        for (int c = 0; c < 3; c++) {
            if (!isfinite(x[3 * v + c])) return GLPGP_FAIL(GLPGP_ERR_MESH, "vertex %d has a non-finite coordinate", v);
            lo[c] = fmin(lo[c], x[3 * v + c]);
            hi[c] = fmax(hi[c], x[3 * v + c]);
        }
    for (int c = 0; c < 3; c++) {
        m->bbox3[c] = lo[c];
        m->bbox3[3 + c] = hi[c];
    }
    m->bbox[0] = lo[0];
    m->bbox[1] = lo[1];
    m->bbox[2] = hi[0];
    m->bbox[3] = hi[1];
    const double diag = glpgp_mesh_diagonal(m), diag2 = diag * diag;
    unsigned char *used = NULL;
    GLPGP_CHECK(glpgp_calloc((size_t)nv, 1, &used));
    glpgp_status st = GLPGP_OK;
    double area = 0.0;
    for (int t = 0; t < nt && st == GLPGP_OK; t++) {
        const int a = m->tri[3 * t], b = m->tri[3 * t + 1], c = m->tri[3 * t + 2];
        if (a < 0 || a >= nv || b < 0 || b >= nv || c < 0 || c >= nv) {
            st = GLPGP_FAIL(GLPGP_ERR_MESH, "triangle %d has a vertex index out of range [0, %d): (%d, %d, %d)", t,
                            nv, a, b, c);
            break;
        }
        if (a == b || b == c || a == c) {
            st = GLPGP_FAIL(GLPGP_ERR_MESH, "triangle %d repeats a vertex: (%d, %d, %d)", t, a, b, c);
            break;
        }
        double n[3];
        glpgp_tri_normal3(x + 3 * a, x + 3 * b, x + 3 * c, n);
        const double ar = 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(ar > min_area_rel * diag2)) {
            st = GLPGP_FAIL(GLPGP_ERR_MESH, "triangle %d (%d, %d, %d) is degenerate (area %g)", t, a, b, c, ar);
            break;
        }
        area += ar;
        used[a] = used[b] = used[c] = 1;
    }
    for (int v = 0; v < nv && st == GLPGP_OK; v++)
        if (!used[v]) st = GLPGP_FAIL(GLPGP_ERR_MESH, "vertex %d is used by no triangle", v);
    free(used);
    m->area = area;
    return st;
}

static int he_to(const int *tri, int h) { return tri[h - h % 3 + (h % 3 + 1) % 3]; }

/* twin[] and the edge count: half-edges bucketed by their smaller endpoint,
 * each bucket sorted by the larger one; more than two half-edges on an edge
 * is a non-manifold edge. *samedir <- the first pair that runs the same way
 * (-1: none; an orientation question, settled by check_orientation). */
glpgp_status glpgp_surface_twins(glpgp_mesh *m, glpgp_surface *s, int *samedir)
{
    const int nv = m->nv, nt = m->nt;
    const int *tri = m->tri;
    const long nh = 3L * nt;
    int *start = NULL, *keys = NULL;
    glpgp_status st = GLPGP_OK;
    *samedir = -1;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv + 2, sizeof(int), &start), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nh, sizeof(int), &keys), done);
    for (long h = 0; h < nh; h++) {
        const int a = tri[h], b = he_to(tri, (int)h);
        start[(a < b ? a : b) + 2]++;
    }
    for (int v = 0; v < nv; v++) start[v + 2] += start[v + 1];
    for (long h = 0; h < nh; h++) {
        const int a = tri[h], b = he_to(tri, (int)h);
        keys[start[(a < b ? a : b) + 1]++] = (int)h;
    }
    int ne = 0;
    for (int v = 0; v < nv && st == GLPGP_OK; v++) {
        int *k = keys + start[v];
        const int n = start[v + 1] - start[v];
        /* insertion sort by (larger endpoint, half-edge) */
        for (int i = 1; i < n; i++) {
            const int h = k[i], hb = tri[h] == v ? he_to(tri, h) : tri[h];
            int j = i - 1;
            while (j >= 0) {
                const int g = k[j], gb = tri[g] == v ? he_to(tri, g) : tri[g];
                if (gb < hb || (gb == hb && g < h)) break;
                k[j + 1] = k[j];
                j--;
            }
            k[j + 1] = h;
        }
        for (int i = 0; i < n;) {
            const int h0 = k[i], b0 = tri[h0] == v ? he_to(tri, h0) : tri[h0];
            int j = i + 1;
            while (j < n && (tri[k[j]] == v ? he_to(tri, k[j]) : tri[k[j]]) == b0) j++;
            if (j - i > 2) {
                st = GLPGP_FAIL(GLPGP_ERR_MESH, "non-manifold edge (%d, %d): shared by %d triangles (%d, %d, %d%s)", v,
                                b0, j - i, h0 / 3, k[i + 1] / 3, k[i + 2] / 3, j - i > 3 ? ", ..." : "");
                break;
            }
            if (j - i == 2) {
                const int h1 = k[i + 1];
                s->twin[h0] = h1;
                s->twin[h1] = h0;
                if (tri[h0] == tri[h1] && (*samedir < 0 || h0 < *samedir)) *samedir = h0;
            } else {
                s->twin[h0] = -1;
            }
            ne++;
            i = j;
        }
    }
    s->nedges = ne;
done:
    free(start);
    free(keys);
    return st;
}

int glpgp_surface_walk(const int *tri, const int *twin, int seed, signed char *flip, int *queue, int *n, int *closed)
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
                return h;
            }
        }
    }
    *n = tail;
    return -1;
}

/* A consistent orientation exists (else: non-orientable, a Moebius strip)
 * and the input has it (else: the first pair of triangles that traverse
 * their edge the same way). Components are counted on the way. */
static glpgp_status check_orientation(glpgp_mesh *m, glpgp_surface *s, int samedir)
{
    const int nt = m->nt;
    signed char *flip = NULL;
    int *queue = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nt, 1, &flip), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nt, sizeof(int), &queue), done);
    memset(flip, -1, (size_t)nt);
    int ncomp = 0;
    for (int seed = 0; seed < nt; seed++) {
        if (flip[seed] >= 0) continue;
        ncomp++;
        int n = 0, closed = 0;
        const int h = glpgp_surface_walk(m->tri, s->twin, seed, flip, queue, &n, &closed);
        if (h >= 0) {
            st = GLPGP_FAIL(GLPGP_ERR_MESH,
                            "non-orientable surface (a Moebius strip or Klein bottle): triangles %d and %d "
                            "(edge %d-%d) cannot be oriented consistently",
                            h / 3, s->twin[h] / 3, m->tri[h], he_to(m->tri, h));
            break;
        }
    }
    if (st == GLPGP_OK && samedir >= 0) {
        const int g = s->twin[samedir];
        st = GLPGP_FAIL(GLPGP_ERR_MESH,
                        "inconsistent orientation: triangles %d and %d traverse their shared edge %d-%d in the same "
                        "direction (the surface is orientable: orient its triangles consistently)",
                        samedir / 3, g / 3, m->tri[samedir], he_to(m->tri, samedir));
    }
    s->ncomponents = ncomp;
done:
    free(flip);
    free(queue);
    return st;
}

/* Every vertex's corners form one fan (walked across the incoming edges);
 * the boundary loops from the boundary half-edges (surface on their left). */
static glpgp_status check_fans_loops(glpgp_mesh *m, glpgp_surface *s)
{
    const int nv = m->nv, nt = m->nt;
    glpgp_status st = GLPGP_OK;
    int *deg = NULL, *first = NULL, *next = NULL;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv, sizeof(int), &deg), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(int), &first), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(int), &next), done);
    for (int v = 0; v < nv; v++) first[v] = next[v] = -1;
    for (int c = 0; c < 3 * nt; c++) {
        const int v = m->tri[c];
        deg[v]++;
        if (s->twin[c] < 0) { /* boundary half-edge v -> next */
            if (next[v] >= 0) {
                st = GLPGP_FAIL(GLPGP_ERR_MESH,
                                "non-manifold vertex %d: two boundary edges leave it (to %d and %d): surfaces "
                                "touching at a vertex",
                                v, next[v], he_to(m->tri, c));
                goto done;
            }
            next[v] = he_to(m->tri, c);
            first[v] = c;
        } else if (first[v] < 0) {
            first[v] = c;
        }
    }
    for (int v = 0; v < nv; v++) {
        int c = first[v], n = 0;
        do {
            n++;
            const int hin = c - c % 3 + (c % 3 + 2) % 3;
            c = s->twin[hin];
        } while (c >= 0 && c != first[v] && n <= deg[v]);
        if (n != deg[v]) {
            st = GLPGP_FAIL(GLPGP_ERR_MESH,
                            "non-manifold vertex %d: its %d triangles form more than one fan (%d around one of "
                            "them): surfaces or cones touching at the vertex",
                            v, deg[v], n);
            goto done;
        }
    }
    memcpy(s->vstart, first, (size_t)nv * sizeof(int));
    GLPGP_CHECK_GOTO(st, glpgp_surface_loops(m, next), done);
done:
    free(deg);
    free(first);
    free(next);
    return st;
}

/* Euler characteristic, and genus from each component's chi and loops. */
static glpgp_status topology(glpgp_mesh *m, glpgp_surface *s)
{
    const int nv = m->nv, nt = m->nt;
    int *parent = NULL, *chi = NULL, *loops = NULL;
    glpgp_status st = GLPGP_OK;
    s->euler = nv - s->nedges + nt;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(int), &parent), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv, sizeof(int), &chi), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv, sizeof(int), &loops), done);
    for (int v = 0; v < nv; v++) parent[v] = v;
    for (int t = 0; t < nt; t++)
        for (int a = 1; a < 3; a++) {
            const int r0 = glpgp_uf_find(parent, m->tri[3 * t]), r1 = glpgp_uf_find(parent, m->tri[3 * t + a]);
            if (r0 != r1) parent[r1] = r0;
        }
    /* chi per component: V - E + F, each edge counted once (at its half-edge
     * with the larger id, or its only one) */
    for (int v = 0; v < nv; v++) chi[glpgp_uf_find(parent, v)]++;
    for (int h = 0; h < 3 * nt; h++) {
        const int r = glpgp_uf_find(parent, m->tri[h]);
        if (s->twin[h] < h) chi[r]--;
        if (h % 3 == 0) chi[r]++;
    }
    for (int l = 0; l < m->nloops; l++) loops[glpgp_uf_find(parent, m->loop_vertices[m->loop_start[l]])]++;
    s->genus = 0;
    for (int v = 0; v < nv; v++)
        if (glpgp_uf_find(parent, v) == v) s->genus += (2 - chi[v] - loops[v]) / 2;
done:
    free(parent);
    free(chi);
    free(loops);
    return st;
}

glpgp_status glpgp_mesh_create_surface(int nv, const double *xyz, int nt, const int *tri, glpgp_mesh **out)
{
    return glpgp_mesh_create_surface_area(nv, xyz, nt, tri, 1e-14, out);
}

glpgp_status glpgp_mesh_create_surface_area(int nv, const double *xyz, int nt, const int *tri, double min_area_rel,
                                            glpgp_mesh **out)
{
    glpgp_status st = GLPGP_OK;
    glpgp_mesh *m = NULL;
    glpgp_surface *s = NULL;
    int samedir = -1;
    if (!out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mesh_create_surface: out is NULL");
    *out = NULL;
    if (nv < 3) return GLPGP_FAIL(GLPGP_ERR_MESH, "mesh needs at least 3 vertices (got %d)", nv);
    if (nt < 1) return GLPGP_FAIL(GLPGP_ERR_MESH, "mesh needs at least 1 triangle (got %d)", nt);
    if (!xyz || !tri) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mesh_create_surface: NULL array");
    GLPGP_CHECK(glpgp_mesh_check_size(nv, nt));
    GLPGP_CHECK_GOTO(st, glpgp_calloc(1, sizeof *m, &m), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv * 3, sizeof(double), &m->xyz), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nt * 3, sizeof(int), &m->tri), fail);
    memcpy(m->xyz, xyz, (size_t)nv * 3 * sizeof(double));
    memcpy(m->tri, tri, (size_t)nt * 3 * sizeof(int));
    m->nv = nv;
    m->nt = nt;
    GLPGP_CHECK_GOTO(st, check_input(m, min_area_rel), fail);
    GLPGP_CHECK_GOTO(st, glpgp_calloc(1, sizeof *s, &s), fail);
    m->surf = s;
    s->nv = nv;
    s->nt = nt;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * nt, sizeof(int), &s->twin), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(int), &s->vstart), fail);
    GLPGP_CHECK_GOTO(st, glpgp_surface_twins(m, s, &samedir), fail);
    GLPGP_CHECK_GOTO(st, check_orientation(m, s, samedir), fail);
    GLPGP_CHECK_GOTO(st, check_fans_loops(m, s), fail);
    GLPGP_CHECK_GOTO(st, topology(m, s), fail);
    GLPGP_CHECK_GOTO(st, glpgp_surface_geometry(m), fail);
    *out = m;
    return GLPGP_OK;
fail:
    glpgp_mesh_destroy(&m);
    return st;
}
