/* mesh/subdivide.c: a surface mesh's triangles split in four at their edge
 * midpoints (glpgp_mesh_subdivide_surface, glpgp/surface.h): every new point
 * lies on an old triangle's edge, so the piecewise linear surface, its sharp
 * edges, boundary loops and topology stay exactly what they were; edges are
 * halved. The solve's preparation uses it for a surface too coarse for its
 * size (solver/prepare.c). */
#include "surface_internal.h"

#include "glpgp/util.h"
#include "glpgp/internal/edgekey.h"

#include <stdlib.h>
#include <string.h>

glpgp_status glpgp_mesh_subdivide_surface(const glpgp_mesh *m, glpgp_mesh **out)
{
    *out = NULL;
    if (!m || !m->xyz) return GLPGP_FAIL(GLPGP_ERR_ARG, "subdivide: not a surface mesh");
    const long long nc = 3LL * m->nt;
    GLPGP_CHECK(glpgp_mesh_check_size((long long)m->nv + nc, 4LL * m->nt));
    glpgp_ekv *E = NULL;
    int *mid = NULL, *tri = NULL;
    double *xyz = NULL;
    glpgp_status st = glpgp_malloc((size_t)nc, sizeof *E, &E);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nc, sizeof *mid, &mid);
    for (long long c = 0; c < nc && st == GLPGP_OK; c++) { /* corner c: the edge from it to the next corner */
        long long t = c / 3;
        E[c].k = glpgp_edge_key(m->tri[c], m->tri[3 * t + (c % 3 + 1) % 3]);
        E[c].slot = (int)c;
    }
    if (st == GLPGP_OK) qsort(E, (size_t)nc, sizeof *E, glpgp_ekv_cmp);
    int nv = m->nv;
    for (long long i = 0; i < nc && st == GLPGP_OK; i++) { /* one new point per distinct edge */
        if (i > 0 && E[i].k == E[i - 1].k) mid[E[i].slot] = mid[E[i - 1].slot];
        else mid[E[i].slot] = nv++;
    }
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)nv, 3 * sizeof(double), &xyz);
    if (st == GLPGP_OK) st = glpgp_malloc((size_t)(4 * nc), sizeof(int), &tri);
    if (st == GLPGP_OK) {
        memcpy(xyz, m->xyz, sizeof(double) * 3 * (size_t)m->nv);
        for (long long c = 0; c < nc; c++) {
            int a = m->tri[c], b = m->tri[3 * (c / 3) + (c % 3 + 1) % 3], p = mid[c];
            for (int e = 0; e < 3; e++) xyz[3 * p + e] = 0.5 * (m->xyz[3 * a + e] + m->xyz[3 * b + e]);
        }
        for (int t = 0; t < m->nt; t++) { /* corners a b c, midpoints ab bc ca: three corner triangles and the middle */
            const int *v = m->tri + 3 * t, *md = mid + 3 * t;
            int T[12] = {v[0], md[0], md[2], md[0], v[1], md[1], md[2], md[1], v[2], md[0], md[1], md[2]};
            memcpy(tri + 12 * (size_t)t, T, sizeof T);
        }
        /* a quarter of a thin triangle is as thin and smaller: only area 0 is degenerate */
        st = glpgp_mesh_create_surface_area(nv, xyz, 4 * m->nt, tri, 0.0, out);
    }
    free(E);
    free(mid);
    free(tri);
    free(xyz);
    return st;
}
