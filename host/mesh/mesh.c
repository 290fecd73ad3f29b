/* mesh/mesh.c: glpgp_mesh_create (validation, orientation repair, boundary loops
 * and outward normals, area/bbox/mean edge) and glpgp_mesh_destroy. The edge
 * table is built with a counting sort on the smaller vertex of each edge, so
 * everything here is O(n) apart from rare high-degree vertices. */
#include "glpgp/mesh.h"
#include "glpgp/surface.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

void glpgp_mesh_release_arrays(glpgp_mesh *p)
{
    if (!p) return;
    free(p->xy);
    free(p->tri);
    free(p->loop_start);
    free(p->loop_vertices);
    free(p->on_boundary);
    free(p->normal_prev);
    free(p->normal_next);
    free(p->xyz);
    glpgp_surface_destroy(&p->surf);
    if (p->part) {
        free(p->part->gid);
        free(p->part->size);
        free(p->part);
    }
    p->xy = p->normal_prev = p->normal_next = p->xyz = NULL;
    p->tri = p->loop_start = p->loop_vertices = NULL;
    p->on_boundary = NULL;
    p->part = NULL;
}

void glpgp_mesh_destroy(glpgp_mesh **m)
{
    if (!m || !*m) return;
    glpgp_mesh_release_arrays(*m);
    free(*m);
    *m = NULL;
}

/* Twice the signed area of triangle (a, b, c). */
static double tri_cross(const double *xy, int a, int b, int c)
{
    double ax = xy[2 * a], ay = xy[2 * a + 1];
    return (xy[2 * b] - ax) * (xy[2 * c + 1] - ay) - (xy[2 * b + 1] - ay) * (xy[2 * c] - ax);
}

/* Half-edge h = 3t+i runs from tri[3t+i] to tri[3t+(i+1)%3]. */
static int he_from(const int *tri, long h) { return tri[h]; }
static int he_to(const int *tri, long h) { return tri[h - h % 3 + (h % 3 + 1) % 3]; }
/* The larger endpoint of half-edge h (its sort key inside a bucket). */
static int he_hi(const int *tri, long h)
{
    int a = he_from(tri, h), b = he_to(tri, h);
    return a > b ? a : b;
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Sort the half-edges of one bucket by their larger endpoint (then by id). */
static glpgp_status sort_bucket(const int *tri, int *k, int n)
{
    if (n > 32) {
        uint64_t *tmp = NULL;
        GLPGP_CHECK(glpgp_malloc((size_t)n, sizeof *tmp, &tmp));
        for (int i = 0; i < n; i++) tmp[i] = ((uint64_t)(uint32_t)he_hi(tri, k[i]) << 32) | (uint32_t)k[i];
        qsort(tmp, (size_t)n, sizeof *tmp, cmp_u64);
        for (int i = 0; i < n; i++) k[i] = (int)(tmp[i] & 0xffffffffu);
        free(tmp);
        return GLPGP_OK;
    }
    for (int i = 1; i < n; i++) {
        int v = k[i], hv = he_hi(tri, v);
        int j = i - 1;
        while (j >= 0 && he_hi(tri, k[j]) > hv) {
            k[j + 1] = k[j];
            j--;
        }
        k[j + 1] = v;
    }
    return GLPGP_OK;
}

/* Edge table: twin[h] = opposite half-edge or -1 (boundary). Half-edges are
 * bucketed by their smaller endpoint (counting sort), then each small bucket
 * is sorted by the larger endpoint. Rejects edges shared by more than two
 * triangles. Also returns the mean unique edge length. */
static glpgp_status build_twins(int nv, const double *xy, int nt, const int *tri, int *twin,
                                double *mean_edge)
{
    glpgp_status st = GLPGP_OK;
    long nh = 3L * nt;
    int *start = NULL;
    int *keys = NULL;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv + 2, sizeof *start, &start), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nh, sizeof *keys, &keys), done);
    /* start[lo + 2] counts, prefix sums give start[lo + 1] = begin of bucket lo;
     * filling increments it to the end of bucket lo = begin of lo + 1. */
    for (long h = 0; h < nh; h++) {
        int a = he_from(tri, h), b = he_to(tri, h);
        start[(a < b ? a : b) + 2]++;
    }
    for (int v = 0; v < nv; v++) start[v + 2] += start[v + 1];
    for (long h = 0; h < nh; h++) {
        int a = he_from(tri, h), b = he_to(tri, h);
        keys[start[(a < b ? a : b) + 1]++] = (int)h;
    }
    double sum = 0.0;
    long nedges = 0;
    for (int v = 0; v < nv; v++) {
        int s = start[v], e = start[v + 1];
        GLPGP_CHECK_GOTO(st, sort_bucket(tri, keys + s, e - s), done);
        int i = s;
        while (i < e) {
            int hi = he_hi(tri, keys[i]);
            int j = i + 1;
            while (j < e && he_hi(tri, keys[j]) == hi) j++;
            int cnt = j - i;
            int h0 = keys[i];
            if (cnt > 2) {
                st = GLPGP_FAIL(GLPGP_ERR_MESH,
                                "non-manifold edge (%d, %d): shared by %d triangles (%d, %d, %d%s)", v,
                                hi, cnt, h0 / 3, keys[i + 1] / 3, keys[i + 2] / 3, cnt > 3 ? ", ..." : "");
                goto done;
            }
            if (cnt == 2) {
                int h1 = keys[i + 1];
                twin[h0] = h1;
                twin[h1] = h0;
            } else {
                twin[h0] = -1;
            }
            double dx = xy[2 * hi] - xy[2 * v], dy = xy[2 * hi + 1] - xy[2 * v + 1];
            sum += sqrt(dx * dx + dy * dy);
            nedges++;
            i = j;
        }
    }
    *mean_edge = nedges ? sum / (double)nedges : 0.0;
done:
    free(start);
    free(keys);
    return st;
}

/* Make every connected component consistently oriented, then CCW. Flips are
 * applied to tri in place (swapping corners 1 and 2) and counted. On return
 * twin[] is only valid as a boundary flag (twin[h] < 0). */
static glpgp_status orient(int nt, const double *xy, int *tri, int *twin, int *nflipped)
{
    glpgp_status st = GLPGP_OK;
    signed char *flip = NULL;
    int *queue = NULL;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nt, sizeof *flip, &flip), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nt, sizeof *queue, &queue), done);
    memset(flip, -1, (size_t)nt);
    int qtail = 0;
    for (int seed = 0; seed < nt; seed++) {
        if (flip[seed] >= 0) continue;
        int qhead = qtail, comp_start = qtail;
        flip[seed] = 0;
        queue[qtail++] = seed;
        while (qhead < qtail) {
            int t = queue[qhead++];
            for (int i = 0; i < 3; i++) {
                long h = 3L * t + i;
                int g = twin[h];
                if (g < 0) continue;
                int u = (int)(g / 3);
                /* Same original direction -> orientations must differ. */
                int same_dir = he_from(tri, h) == he_from(tri, g);
                signed char want = (signed char)(same_dir ? !flip[t] : flip[t]);
                if (flip[u] < 0) {
                    flip[u] = want;
                    queue[qtail++] = u;
                } else if (flip[u] != want) {
                    st = GLPGP_FAIL(GLPGP_ERR_MESH,
                                    "non-orientable mesh: triangles %d and %d (edge %d-%d) cannot "
                                    "be oriented consistently",
                                    t, u, he_from(tri, h), he_to(tri, h));
                    goto done;
                }
            }
        }
        double area2 = 0.0;
        for (int q = comp_start; q < qtail; q++) {
            int t = queue[q];
            double c = tri_cross(xy, tri[3 * t], tri[3 * t + 1], tri[3 * t + 2]);
            area2 += flip[t] ? -c : c;
        }
        if (area2 < 0.0)
            for (int q = comp_start; q < qtail; q++) flip[queue[q]] = (signed char)!flip[queue[q]];
    }
    int n = 0;
    for (int t = 0; t < nt; t++) {
        if (!flip[t]) continue;
        int tmp = tri[3 * t + 1];
        tri[3 * t + 1] = tri[3 * t + 2];
        tri[3 * t + 2] = tmp;
        /* (a,b,c) -> (a,c,b): the edge in slot 0 ({a,b}) moves to slot 2 and
         * vice versa; slot 1 keeps {b,c}. Only the boundary flag (twin < 0)
         * is used afterwards, so swapping the entries is enough. */
        int tw = twin[3L * t];
        twin[3L * t] = twin[3L * t + 2];
        twin[3L * t + 2] = tw;
        n++;
    }
    *nflipped = n;
done:
    free(flip);
    free(queue);
    return st;
}

/* Signed area of a closed polygon given by vertex indices. */
/* Signed area of a closed loop (shoelace), taken about the loop's first
 * vertex: with absolute coordinates the terms x_a y_b of a part placed far
 * from the origin (CAD drawings at (1e5, -5e4)) cancel to a rounding error
 * larger than the area's tolerance. A = 1/2 sum (p_a - p_0) x (p_b - p_0) */
static double loop_area(const double *xy, const int *v, int n)
{
    double s = 0.0, x0 = xy[2 * v[0]], y0 = xy[2 * v[0] + 1];
    for (int i = 0; i < n; i++) {
        int a = v[i], b = v[(i + 1) % n];
        s += (xy[2 * a] - x0) * (xy[2 * b + 1] - y0) - (xy[2 * b] - x0) * (xy[2 * a + 1] - y0);
    }
    return 0.5 * s;
}

/* Boundary loops, flags and outward normals from the (oriented) triangles. */
static glpgp_status build_boundary(glpgp_mesh *m, const int *twin)
{
    glpgp_status st = GLPGP_OK;
    int nv = m->nv;
    long nh = 3L * m->nt;
    int *next = NULL;
    int *lstart = NULL;
    int nb = 0;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof *next, &next), done);
    for (int v = 0; v < nv; v++) next[v] = -1;
    /* After orientation the half-edges of boundary edges run with the domain
     * on their left (triangles are CCW); orient() kept the boundary flags
     * (twin < 0) in the right slots. */
    for (long h = 0; h < nh; h++) {
        if (twin[h] >= 0) continue;
        int a = he_from(m->tri, h), b = he_to(m->tri, h);
        if (next[a] >= 0) {
            st = GLPGP_FAIL(GLPGP_ERR_MESH,
                            "boundary is not simple at vertex %d (pinched: boundary edges to %d "
                            "and %d both leave it)",
                            a, next[a], b);
            goto done;
        }
        next[a] = b;
        nb++;
    }
    if (nb == 0) {
        st = GLPGP_FAIL(GLPGP_ERR_MESH, "mesh has no boundary");
        goto done;
    }
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nb, sizeof *m->loop_vertices, &m->loop_vertices), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv, 1, &m->on_boundary), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv * 2, sizeof(double), &m->normal_prev), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv * 2, sizeof(double), &m->normal_next), done);
    int cap = 8, nloops = 0, pos = 0;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)cap + 1, sizeof *lstart, &lstart), done);
    for (int v0 = 0; v0 < nv; v0++) {
        if (next[v0] < 0 || m->on_boundary[v0]) continue;
        if (nloops == cap) {
            int *p = realloc(lstart, ((size_t)cap * 2 + 1) * sizeof *p);
            if (!p) {
                st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory (boundary loops)");
                goto done;
            }
            lstart = p;
            cap *= 2;
        }
        lstart[nloops++] = pos;
        int v = v0;
        do {
            if (m->on_boundary[v] || pos >= nb) {
                /* Cannot happen with out-degree 1 everywhere; kept as a guard. */
                st = GLPGP_FAIL(GLPGP_ERR_MESH, "boundary is not simple at vertex %d", v);
                goto done;
            }
            m->on_boundary[v] = 1;
            m->loop_vertices[pos++] = v;
            int w = next[v];
            if (w < 0) {
                st = GLPGP_FAIL(GLPGP_ERR_MESH, "boundary chain ends at vertex %d", v);
                goto done;
            }
            double dx = m->xy[2 * w] - m->xy[2 * v], dy = m->xy[2 * w + 1] - m->xy[2 * v + 1];
            double len = sqrt(dx * dx + dy * dy);
            double nx = dy / len, ny = -dx / len;
            m->normal_next[2 * v] = nx;
            m->normal_next[2 * v + 1] = ny;
            m->normal_prev[2 * w] = nx;
            m->normal_prev[2 * w + 1] = ny;
            v = w;
        } while (v != v0);
    }
    lstart[nloops] = pos;
    /* Loop 0 = largest |signed area|: rotate the loop array so it comes first. */
    int best = 0;
    double best_a = -1.0;
    for (int l = 0; l < nloops; l++) {
        double a = fabs(loop_area(m->xy, m->loop_vertices + lstart[l], lstart[l + 1] - lstart[l]));
        if (a > best_a) {
            best_a = a;
            best = l;
        }
    }
    if (best != 0) {
        int *tmp = NULL;
        GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nb, sizeof *tmp, &tmp), done);
        int s = lstart[best], len = lstart[best + 1] - s, p = 0;
        memcpy(tmp, m->loop_vertices + s, (size_t)len * sizeof *tmp);
        p = len;
        int *ls2 = NULL;
        st = glpgp_malloc((size_t)nloops + 1, sizeof *ls2, &ls2);
        if (st != GLPGP_OK) {
            free(tmp);
            glpgp_error_push_trace(__FILE__, __LINE__);
            goto done;
        }
        ls2[0] = 0;
        int k = 1;
        for (int l = 0; l < nloops; l++) {
            if (l == best) continue;
            int ll = lstart[l + 1] - lstart[l];
            memcpy(tmp + p, m->loop_vertices + lstart[l], (size_t)ll * sizeof *tmp);
            ls2[k++] = p;
            p += ll;
        }
        ls2[nloops] = p;
        memcpy(m->loop_vertices, tmp, (size_t)nb * sizeof *tmp);
        free(tmp);
        free(lstart);
        lstart = ls2;
    }
    m->nloops = nloops;
    m->loop_start = lstart;
    lstart = NULL;
done:
    free(next);
    free(lstart);
    return st;
}

glpgp_status glpgp_mesh_check_size(long long nv, long long nt)
{
    if (nt > GLPGP_MESH_MAX_TRIANGLES)
        return GLPGP_FAIL(GLPGP_ERR_LIMIT, "too many triangles (%lld; glpgp handles at most %d)", nt,
                          GLPGP_MESH_MAX_TRIANGLES);
    if (nv > GLPGP_MESH_MAX_VERTICES)
        return GLPGP_FAIL(GLPGP_ERR_LIMIT, "too many vertices (%lld; glpgp handles at most %d)", nv,
                          GLPGP_MESH_MAX_VERTICES);
    return GLPGP_OK;
}

glpgp_status glpgp_mesh_create(int nv, const double *xy, int nt, const int *tri, glpgp_mesh **out)
{
    glpgp_status st = GLPGP_OK;
    glpgp_mesh *m = NULL;
    int *twin = NULL;
    unsigned char *used = NULL;
    if (!out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mesh_create: out is NULL");
    *out = NULL;
    if (nv < 3) return GLPGP_FAIL(GLPGP_ERR_MESH, "mesh needs at least 3 vertices (got %d)", nv);
    if (nt < 1) return GLPGP_FAIL(GLPGP_ERR_MESH, "mesh needs at least 1 triangle (got %d)", nt);
    if (!xy || !tri) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mesh_create: NULL array");
    GLPGP_CHECK(glpgp_mesh_check_size(nv, nt));

    GLPGP_CHECK_GOTO(st, glpgp_calloc(1, sizeof *m, &m), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv * 2, sizeof *m->xy, &m->xy), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nt * 3, sizeof *m->tri, &m->tri), fail);
    memcpy(m->xy, xy, (size_t)nv * 2 * sizeof *xy);
    memcpy(m->tri, tri, (size_t)nt * 3 * sizeof *tri);
    m->nv = nv;
    m->nt = nt;

    double xmin = HUGE_VAL, ymin = HUGE_VAL, xmax = -HUGE_VAL, ymax = -HUGE_VAL;
    for (int v = 0; v < nv; v++) {
        double x = xy[2 * v], y = xy[2 * v + 1];
        if (!isfinite(x) || !isfinite(y)) {
            st = GLPGP_FAIL(GLPGP_ERR_MESH, "vertex %d has a non-finite coordinate", v);
            goto fail;
        }
        if (x < xmin) xmin = x;
        if (x > xmax) xmax = x;
        if (y < ymin) ymin = y;
        if (y > ymax) ymax = y;
    }
    m->bbox[0] = xmin;
    m->bbox[1] = ymin;
    m->bbox[2] = xmax;
    m->bbox[3] = ymax;
    double diag2 = (xmax - xmin) * (xmax - xmin) + (ymax - ymin) * (ymax - ymin);

    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv, 1, &used), fail);
    for (int t = 0; t < nt; t++) {
        int a = tri[3 * t], b = tri[3 * t + 1], c = tri[3 * t + 2];
        if (a < 0 || a >= nv || b < 0 || b >= nv || c < 0 || c >= nv) {
            st = GLPGP_FAIL(GLPGP_ERR_MESH, "triangle %d has a vertex index out of range [0, %d): (%d, %d, %d)",
                            t, nv, a, b, c);
            goto fail;
        }
        if (a == b || b == c || a == c) {
            st = GLPGP_FAIL(GLPGP_ERR_MESH, "triangle %d repeats a vertex: (%d, %d, %d)", t, a, b, c);
            goto fail;
        }
        double area = 0.5 * tri_cross(xy, a, b, c);
        if (!(fabs(area) > 1e-14 * diag2)) {
            st = GLPGP_FAIL(GLPGP_ERR_MESH, "triangle %d (%d, %d, %d) is degenerate (area %g)", t, a,
                            b, c, area);
            goto fail;
        }
        used[a] = used[b] = used[c] = 1;
    }
    for (int v = 0; v < nv; v++) {
        if (!used[v]) {
            st = GLPGP_FAIL(GLPGP_ERR_MESH, "vertex %d is used by no triangle", v);
            goto fail;
        }
    }
    free(used);
    used = NULL;

    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nt * 3, sizeof *twin, &twin), fail);
    glpgp_progress_poll(); /* a progress line of the caller's phase when one is due */
    GLPGP_CHECK_GOTO(st, build_twins(nv, m->xy, nt, m->tri, twin, &m->mean_edge), fail);
    glpgp_progress_poll();
    GLPGP_CHECK_GOTO(st, orient(nt, m->xy, m->tri, twin, &m->orientation_fixed), fail);
    GLPGP_CHECK_GOTO(st, build_boundary(m, twin), fail);
    free(twin);
    twin = NULL;

    /* Folds: after the orientation repair every triangle must be counter-
     * clockwise; one that is not lies on the same side of an edge as its
     * neighbour (the mesh folds over itself). Overlaps without a fold show as
     * a triangle area larger than the area enclosed by the boundary loops. */
    double area = 0.0;
    for (int t = 0; t < nt; t++) {
        const int *v = m->tri + 3 * t;
        double c = tri_cross(m->xy, v[0], v[1], v[2]);
        if (!(c > 0.0)) {
            st = GLPGP_FAIL(GLPGP_ERR_MESH,
                            "the mesh folds over itself: triangle %d (%d, %d, %d) is inverted relative "
                            "to its neighbours",
                            t, v[0], v[1], v[2]);
            goto fail;
        }
        area += 0.5 * c;
    }
    double enclosed = 0.0;
    for (int l = 0; l < m->nloops; l++)
        enclosed += loop_area(m->xy, m->loop_vertices + m->loop_start[l], m->loop_start[l + 1] - m->loop_start[l]);
    if (area > enclosed * (1.0 + 1e-9) + 1e-12 * diag2) {
        st = GLPGP_FAIL(GLPGP_ERR_MESH,
                        "the mesh overlaps itself: its triangles cover %.6g but its boundary encloses %.6g",
                        area, enclosed);
        goto fail;
    }
    m->area = area;
    *out = m;
    return GLPGP_OK;
fail:
    free(twin);
    free(used);
    glpgp_mesh_destroy(&m);
    return st;
}

void glpgp_mesh_angles(const glpgp_mesh *m, double sliver_deg, double *min_angle, int *nslivers)
{
    double amin = 180.0;
    int n = 0;
    if (m->surf) { /* a surface: its corner angles */
        for (int t = 0; t < m->nt; t++) {
            double tmin = 180.0;
            for (int k = 0; k < 3; k++) tmin = fmin(tmin, m->surf->corner[3 * t + k] * (180.0 / 3.14159265358979323846));
            amin = fmin(amin, tmin);
            n += tmin < sliver_deg;
        }
        *min_angle = amin;
        *nslivers = n;
        return;
    }
    for (int t = 0; t < m->nt; t++) {
        double tmin = 180.0;
        for (int k = 0; k < 3; k++) {
            const double *a = m->xy + 2 * m->tri[3 * t + k], *b = m->xy + 2 * m->tri[3 * t + (k + 1) % 3],
                         *c = m->xy + 2 * m->tri[3 * t + (k + 2) % 3];
            const double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - a[0], vy = c[1] - a[1];
            /* angle at a = atan2(|u x v|, u . v) */
            const double ang = atan2(fabs(ux * vy - uy * vx), ux * vx + uy * vy) * (180.0 / 3.14159265358979323846);
            if (ang < tmin) tmin = ang;
        }
        if (tmin < amin) amin = tmin;
        n += tmin < sliver_deg;
    }
    *min_angle = amin;
    *nslivers = n;
}

glpgp_status glpgp_mesh_vertex_triangles(const glpgp_mesh *m, int **ptr, int **list)
{
    *ptr = *list = NULL;
    glpgp_status st = glpgp_calloc((size_t)m->nv + 1, sizeof(int), ptr);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)3 * m->nt + 1, sizeof(int), list);
    if (st != GLPGP_OK) {
        free(*ptr);
        *ptr = NULL;
        return st;
    }
    int *p = *ptr, *l = *list;
    for (long k = 0; k < 3L * m->nt; k++) p[m->tri[k] + 1]++;
    for (int i = 0; i < m->nv; i++) p[i + 1] += p[i];
    for (long k = 0; k < 3L * m->nt; k++) l[p[m->tri[k]]++] = (int)(k / 3);
    for (int i = m->nv; i > 0; i--) p[i] = p[i - 1]; /* each start moved to its end: back */
    p[0] = 0;
    return GLPGP_OK;
}
