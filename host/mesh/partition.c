/* mesh/partition.c: vertex partitions for distributed solves (glpgp/mesh.h):
 * recursive coordinate bisection into parts of prescribed sizes, and the
 * renumbering of a mesh so that each part's vertices are contiguous; the
 * reverse Cuthill-McKee order (memory locality of one process's solve).
 * Deterministic: the same mesh gives the same partition in every process
 * (sorts break coordinate ties by vertex index); one rank's part of a
 * renumbered mesh: its vertices, one layer of ghosts, its triangles. */
#include "glpgp/mesh.h"
#include "glpgp/surface.h"

#include <stdlib.h>
#include <string.h>

/* a vertex and its coordinate along the axis being split: sorted as records
 * (no qsort context, so no static: safe from two threads) */
typedef struct axis_rec {
    double c;
    int i;
} axis_rec;

static int cmp_axis(const void *a, const void *b)
{
    const axis_rec *p = a, *q = b;
    if (p->c < q->c) return -1;
    if (p->c > q->c) return 1;
    return (p->i > q->i) - (p->i < q->i);
}

/* parts [p0, p1) get the vertices v[0 .. n) (n = sum of their sizes) */
static void rcb(const double *xy, int *v, int n, const int *size, int p0, int p1, int *part, axis_rec *rec)
{
    if (p1 - p0 == 1) {
        for (int k = 0; k < n; k++) part[v[k]] = p0;
        return;
    }
    const int pm = p0 + (p1 - p0) / 2;
    int nleft = 0;
    for (int p = p0; p < pm; p++) nleft += size[p];
    /* split across the longer extent of the set's bounding box */
    double lo[2] = {xy[2 * v[0]], xy[2 * v[0] + 1]}, hi[2] = {lo[0], lo[1]};
    for (int k = 1; k < n; k++)
        for (int d = 0; d < 2; d++) {
            const double c = xy[2 * v[k] + d];
            if (c < lo[d]) lo[d] = c;
            if (c > hi[d]) hi[d] = c;
        }
    const int axis = hi[1] - lo[1] > hi[0] - lo[0] ? 1 : 0;
    for (int k = 0; k < n; k++) rec[k] = (axis_rec){xy[2 * v[k] + axis], v[k]};
    qsort(rec, (size_t)n, sizeof *rec, cmp_axis);
    for (int k = 0; k < n; k++) v[k] = rec[k].i;
    rcb(xy, v, nleft, size, p0, pm, part, rec);
    rcb(xy, v + nleft, n - nleft, size, pm, p1, part, rec);
}

glpgp_status glpgp_mesh_partition(const glpgp_mesh *m, int nparts, const int *size, int *part)
{
    if (nparts < 1) return GLPGP_FAIL(GLPGP_ERR_ARG, "partition: %d parts", nparts);
    if (m->xyz) return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "partition: a surface is not split over ranks yet");
    long total = 0;
    for (int p = 0; p < nparts; p++) {
        if (size[p] < 0) return GLPGP_FAIL(GLPGP_ERR_ARG, "partition: part %d has size %d", p, size[p]);
        total += size[p];
    }
    if (total != m->nv)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "partition: part sizes sum to %ld, the mesh has %d vertices", total, m->nv);
    int *v = NULL;
    axis_rec *rec = NULL;
    glpgp_status st = glpgp_malloc((size_t)m->nv, sizeof *v, &v);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)m->nv, sizeof *rec, &rec);
    if (st == GLPGP_OK) {
        for (int i = 0; i < m->nv; i++) v[i] = i;
        rcb(m->xy, v, m->nv, size, 0, nparts, part, rec);
    }
    free(rec);
    free(v);
    return st;
}

/* BFS of the component of s (vertices not yet in order[0 .. *n)), neighbours by
 * increasing (degree, index), appended to order[*n ..] and marked in seen;
 * returns the last vertex reached (on the deepest level). Adjacency (ptr, adj). */
static int rcm_bfs(const int *ptr, const int *adj, int s, int *order, int *n, unsigned char *seen)
{
    int head = *n;
    order[(*n)++] = s;
    seen[s] = 1;
    while (head < *n) {
        const int u = order[head++], first = *n;
        for (int k = ptr[u]; k < ptr[u + 1]; k++) {
            const int w = adj[k];
            if (seen[w]) continue;
            seen[w] = 1;
            /* insertion by (degree, index): rows are short */
            int q = (*n)++;
            const int dw = ptr[w + 1] - ptr[w];
            while (q > first) {
                const int v = order[q - 1], dv = ptr[v + 1] - ptr[v];
                if (dv < dw || (dv == dw && v < w)) break;
                order[q] = v;
                q--;
            }
            order[q] = w;
        }
    }
    return order[*n - 1];
}

glpgp_status glpgp_mesh_rcm_order(const glpgp_mesh *m, int *new_of_old)
{
    const int nv = m->nv, nt = m->nt;
    glpgp_status st = GLPGP_OK;
    int *ptr = NULL, *adj = NULL, *order = NULL, *mark = NULL, *tptr = NULL, *tlist = NULL;
    unsigned char *seen = NULL;
    GLPGP_CHECK_GOTO(st, glpgp_mesh_vertex_triangles(m, &tptr, &tlist), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv + 1, sizeof(int), &ptr), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)6 * nt + 1, sizeof(int), &adj), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv + 1, sizeof(int), &order), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv + 1, sizeof(int), &mark), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv + 1, 1, &seen), done);
    /* the vertex graph (each edge once per side) from the vertices' triangles */
    for (int i = 0; i < nv; i++) mark[i] = -1;
    for (int i = 0; i < nv; i++) {
        ptr[i + 1] = ptr[i];
        for (int p = tptr[i]; p < tptr[i + 1]; p++)
            for (int a = 0; a < 3; a++) {
                const int j = m->tri[3 * (size_t)tlist[p] + a];
                if (j == i || mark[j] == i) continue;
                mark[j] = i;
                adj[ptr[i + 1]++] = j;
            }
    }
    /* per component: a pseudo-peripheral start (the last vertex of a BFS,
     * twice), then the Cuthill-McKee BFS */
    int n = 0;
    for (int s0 = 0; s0 < nv; s0++) {
        if (seen[s0]) continue;
        int s = s0;
        for (int sweep = 0; sweep < 2; sweep++) {
            const int n0 = n;
            const int far = rcm_bfs(ptr, adj, s, order, &n, seen);
            for (int k = n0; k < n; k++) seen[order[k]] = 0;
            n = n0;
            s = far;
        }
        rcm_bfs(ptr, adj, s, order, &n, seen);
    }
    /* reversed: new number of order[k] = nv - 1 - k */
    for (int k = 0; k < nv; k++) new_of_old[order[k]] = nv - 1 - k;
done:
    free(ptr);
    free(adj);
    free(order);
    free(mark);
    free(tptr);
    free(tlist);
    free(seen);
    return st;
}

glpgp_status glpgp_mesh_renumber(const glpgp_mesh *m, const int *new_of_old, glpgp_mesh **out)
{
    *out = NULL;
    double *xy = NULL;
    int *tri = NULL;
    glpgp_status st = GLPGP_OK;
    const int dim = m->xyz ? 3 : 2; /* a surface: xyz, glpgp_mesh_create_surface */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)dim * m->nv, sizeof *xy, &xy), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * m->nt, sizeof *tri, &tri), done);
    /* xy'[new(i)] <- xy[i];  tri'[t] <- new(tri[t]) (triangle order and corner order kept) */
    for (int i = 0; i < m->nv; i++) {
        const int j = new_of_old[i];
        if (j < 0 || j >= m->nv) {
            st = GLPGP_FAIL(GLPGP_ERR_ARG, "renumber: vertex %d -> %d out of range", i, j);
            goto done;
        }
        for (int c = 0; c < dim; c++) xy[dim * j + c] = m->xyz ? m->xyz[3 * i + c] : m->xy[2 * i + c];
    }
    for (long k = 0; k < 3L * m->nt; k++) tri[k] = new_of_old[m->tri[k]];
    if (m->xyz)
        GLPGP_CHECK_GOTO(st, glpgp_mesh_create_surface(m->nv, xy, m->nt, tri, out), done);
    else
        GLPGP_CHECK_GOTO(st, glpgp_mesh_create(m->nv, xy, m->nt, tri, out), done);
done:
    free(xy);
    free(tri);
    return st;
}

glpgp_status glpgp_mesh_extract_part(const glpgp_mesh *m, int P, int q, const double *size, const double center[2],
                                     double size_opt, glpgp_mesh **out)
{
    *out = NULL;
    if (P < 1 || q < 0 || q >= P) return GLPGP_FAIL(GLPGP_ERR_ARG, "part %d of %d", q, P);
    if (m->xyz) return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "a surface is not split over ranks yet");
    const int nv = m->nv, nt = m->nt;
    const int lo = (int)((long long)nv * q / P), hi = (int)((long long)nv * (q + 1) / P);
    glpgp_status st = GLPGP_OK;
    int *loc = NULL;
    glpgp_mesh *o = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)nv, sizeof(int), &loc));
    /* loc[g] <- local id of global vertex g: owned g - lo, ghosts (vertices of
     * triangles touching an owned vertex) after them in increasing g, -1 else */
    for (int g = 0; g < nv; g++) loc[g] = -1;
    int ntl = 0;
    for (int t = 0; t < nt; t++) {
        const int *v = m->tri + 3 * (size_t)t;
        int touch = 0;
        for (int a = 0; a < 3; a++) touch |= v[a] >= lo && v[a] < hi;
        if (!touch) continue;
        ntl++;
        for (int a = 0; a < 3; a++)
            if (v[a] < lo || v[a] >= hi) loc[v[a]] = -2; /* ghost, id below */
    }
    int nvl = hi - lo;
    for (int g = 0; g < nv; g++) {
        if (g >= lo && g < hi) loc[g] = g - lo;
        else if (loc[g] == -2) loc[g] = nvl++;
    }
    GLPGP_CHECK_GOTO(st, glpgp_mesh_part_create(nvl, ntl, size != NULL, &o), fail);
    glpgp_mesh_part *pt = o->part;
    /* per local vertex i of global g: the whole mesh's data at g */
    for (int g = 0; g < nv; g++) {
        const int i = loc[g];
        if (i < 0) continue;
        pt->gid[i] = g;
        for (int c = 0; c < 2; c++) {
            o->xy[2 * i + c] = m->xy[2 * g + c];
            o->normal_prev[2 * i + c] = m->normal_prev[2 * g + c];
            o->normal_next[2 * i + c] = m->normal_next[2 * g + c];
            if (size) pt->size[(size_t)c * nvl + i] = size[(size_t)c * nv + g];
        }
        o->on_boundary[i] = m->on_boundary[g];
    }
    int k = 0;
    for (int t = 0; t < nt; t++) {
        const int *v = m->tri + 3 * (size_t)t;
        if (!((v[0] >= lo && v[0] < hi) || (v[1] >= lo && v[1] < hi) || (v[2] >= lo && v[2] < hi))) continue;
        for (int a = 0; a < 3; a++) o->tri[3 * (size_t)k + a] = loc[v[a]];
        k++;
    }
    o->area = m->area;
    memcpy(o->bbox, m->bbox, sizeof o->bbox);
    o->mean_edge = m->mean_edge;
    pt->nv_owned = hi - lo;
    pt->first = lo;
    pt->nv_global = nv;
    pt->nt_global = nt;
    pt->center[0] = center ? center[0] : 0.0;
    pt->center[1] = center ? center[1] : 0.0;
    pt->size_opt = size_opt;
    free(loc);
    *out = o;
    return GLPGP_OK;
fail:
    free(loc);
    glpgp_mesh_destroy(&o);
    return st;
}

glpgp_status glpgp_mesh_part_create(int nv, int nt, int sized, glpgp_mesh **out)
{
    *out = NULL;
    if (nv < 0 || nt < 0) return GLPGP_FAIL(GLPGP_ERR_ARG, "a part of %d vertices and %d triangles", nv, nt);
    glpgp_status st = GLPGP_OK;
    glpgp_mesh *o = NULL;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *o, &o));
    o->nv = nv;
    o->nt = nt;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * (nv > 0 ? nv : 1), sizeof(double), &o->xy), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * (nt > 0 ? nt : 1), sizeof(int), &o->tri), fail);
    GLPGP_CHECK_GOTO(st, glpgp_calloc(1, sizeof(int), &o->loop_start), fail); /* nloops = 0 */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)(nv > 0 ? nv : 1), 1, &o->on_boundary), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * (nv > 0 ? nv : 1), sizeof(double), &o->normal_prev), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * (nv > 0 ? nv : 1), sizeof(double), &o->normal_next), fail);
    GLPGP_CHECK_GOTO(st, glpgp_calloc(1, sizeof *o->part, &o->part), fail);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)(nv > 0 ? nv : 1), sizeof(int), &o->part->gid), fail);
    if (sized) GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * (nv > 0 ? nv : 1), sizeof(double), &o->part->size), fail);
    *out = o;
    return GLPGP_OK;
fail:
    glpgp_mesh_destroy(&o);
    return st;
}
