/* mesh/partition.c: vertex partitions for distributed solves (glpgp/mesh.h):
 * recursive coordinate bisection into parts of prescribed sizes, and the
 * renumbering of a mesh so that each part's vertices are contiguous.
 * Deterministic: the same mesh gives the same partition in every process
 * (sorts break coordinate ties by vertex index). */
#include "glpgp/mesh.h"

#include <stdlib.h>
#include <string.h>

/* qsort context (C11 qsort has none: one static per call chain; the
 * partition is computed single-threaded) */
static const double *g_xy;
static int g_axis;

static int cmp_axis(const void *a, const void *b)
{
    const int i = *(const int *)a, j = *(const int *)b;
    const double x = g_xy[2 * i + g_axis], y = g_xy[2 * j + g_axis];
    if (x < y) return -1;
    if (x > y) return 1;
    return (i > j) - (i < j);
}

/* parts [p0, p1) get the vertices v[0 .. n) (n = sum of their sizes) */
static void rcb(const double *xy, int *v, int n, const int *size, int p0, int p1, int *part)
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
    g_xy = xy;
    g_axis = hi[1] - lo[1] > hi[0] - lo[0] ? 1 : 0;
    qsort(v, (size_t)n, sizeof *v, cmp_axis);
    rcb(xy, v, nleft, size, p0, pm, part);
    rcb(xy, v + nleft, n - nleft, size, pm, p1, part);
}

glpgp_status glpgp_mesh_partition(const glpgp_mesh *m, int nparts, const int *size, int *part)
{
    if (nparts < 1) return GLPGP_FAIL(GLPGP_ERR_ARG, "partition: %d parts", nparts);
    long total = 0;
    for (int p = 0; p < nparts; p++) {
        if (size[p] < 0) return GLPGP_FAIL(GLPGP_ERR_ARG, "partition: part %d has size %d", p, size[p]);
        total += size[p];
    }
    if (total != m->nv)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "partition: part sizes sum to %ld, the mesh has %d vertices", total, m->nv);
    int *v = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)m->nv, sizeof *v, &v));
    for (int i = 0; i < m->nv; i++) v[i] = i;
    rcb(m->xy, v, m->nv, size, 0, nparts, part);
    free(v);
    return GLPGP_OK;
}

glpgp_status glpgp_mesh_renumber(const glpgp_mesh *m, const int *new_of_old, glpgp_mesh **out)
{
    *out = NULL;
    double *xy = NULL;
    int *tri = NULL;
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)2 * m->nv, sizeof *xy, &xy), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)3 * m->nt, sizeof *tri, &tri), done);
    /* xy'[new(i)] <- xy[i];  tri'[t] <- new(tri[t]) (triangle order and corner order kept) */
    for (int i = 0; i < m->nv; i++) {
        const int j = new_of_old[i];
        if (j < 0 || j >= m->nv) {
            st = GLPGP_FAIL(GLPGP_ERR_ARG, "renumber: vertex %d -> %d out of range", i, j);
            goto done;
        }
        xy[2 * j] = m->xy[2 * i];
        xy[2 * j + 1] = m->xy[2 * i + 1];
    }
    for (long k = 0; k < 3L * m->nt; k++) tri[k] = new_of_old[m->tri[k]];
    GLPGP_CHECK_GOTO(st, glpgp_mesh_create(m->nv, xy, m->nt, tri, out), done);
done:
    free(xy);
    free(tri);
    return st;
}
