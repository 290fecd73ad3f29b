/* solver/surface_refine.c: a surface refined to its local size
 * (glpgp_surface_refine_local, solver/internal.h; called by
 * glpgp_solve_prepare): every edge longer than h(x) / GLPGP_SURFACE_EDGES
 * bisected, with h(x) the local size the solve uses (glpgp_surface_size:
 * its curvature cap, graded), by
 * glpgp_mesh_refine_surface_sized. The feature spacing is left out: two
 * creases or boundary loops closer than h (a thin wall, a narrow chamfer)
 * would take the refinement to their spacing over the whole graded band
 * around them, for a result the solve's resolution limit sets anyway
 * (bench/results/surface_refine.md, the thin-walled box).
 *
 * The size is computed on the input mesh, before refinement: its vertices
 * lie on the modelled surface, the bisection's midpoints only on its
 * piecewise linear interpolant. The curvature cap is the sagitta of patches
 * of a given radius (surface_size.c, sagitta_cap), nearly the same on the
 * input and on its refinements and blind to noise under d / 2 (a normals'
 * turn per edge grew as the same polyhedron was bisected, and read a scan's
 * noise as curvature: bench/results/surface_refine.md); the targets are
 * interpolated onto the new vertices within a pass, and the size
 * recomputed on the refined mesh (what the solve uses) drives a further
 * pass where an edge is still longer than its h(x) / N, at most
 * GLPGP_SURFACE_REFINE_PASSES in all. The refined mesh's origin (otri,
 * obary: where its triangles lie) is composed through the passes: on the
 * input mesh m. */
#include "internal.h"

#include "glpgp/surfsolve.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>

/* passes of the refinement: the size recomputed on each refined mesh */
#define GLPGP_SURFACE_REFINE_PASSES 3

/* size (nv) <- m's local size (auto / iso; h where the field is none or a
 * file: the refinement then targets h / N everywhere) */
static glpgp_status local_size(const glpgp_mesh *m, const glpgp_options *o, double h, double *size)
{
    if (o->size_field != GLPGP_SIZE_AUTO && o->size_field != GLPGP_SIZE_ISO) {
        for (int i = 0; i < m->nv; i++) size[i] = h;
        return GLPGP_OK;
    }
    glpgp_surface_constraints *con = NULL;
    GLPGP_CHECK(glpgp_surface_constraints_create(m, o->feature_angle, &con));
    const glpgp_status st = glpgp_surface_size_local(m, o, con, h, 0, size);
    glpgp_surface_constraints_destroy(&con);
    return st;
}

glpgp_status glpgp_surface_edge_ratio(const glpgp_mesh *m, const glpgp_options *o, double h, double *ratio,
                                      double *min_size)
{
    double *size = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)m->nv, sizeof(double), &size));
    glpgp_status st = local_size(m, o, h, size);
    double r = 0.0, smin = HUGE_VAL;
    if (st == GLPGP_OK)
        for (int t = 0; t < m->nt; t++)
            for (int a = 0; a < 3; a++) {
                const int i = m->tri[3 * t + a], j = m->tri[3 * t + (a + 1) % 3];
                const double *p = m->xyz + 3 * (size_t)i, *q = m->xyz + 3 * (size_t)j;
                const double l = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                                      (p[2] - q[2]) * (p[2] - q[2]));
                const double s = fmin(size[i], size[j]);
                r = fmax(r, l * GLPGP_SURFACE_EDGES / s);
                smin = fmin(smin, s);
            }
    free(size);
    if (ratio) *ratio = r;
    if (min_size) *min_size = smin;
    return st;
}

/* One pass: m refined to its own local size / N (*out NULL: nothing to do). */
static glpgp_status refine_pass(const glpgp_mesh *m, const glpgp_options *o, double h, double max_triangles,
                                glpgp_mesh **out, glpgp_surface_refine_info *ri)
{
    double *target = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)m->nv, sizeof(double), &target));
    glpgp_status st = local_size(m, o, h, target);
    if (st == GLPGP_OK) {
        for (int i = 0; i < m->nv; i++) target[i] /= GLPGP_SURFACE_EDGES;
        st = glpgp_mesh_refine_surface_sized(m, target, max_triangles, out, ri);
    }
    free(target);
    return st;
}

glpgp_status glpgp_surface_refine_local(const glpgp_mesh *m, const glpgp_options *o, double h, double max_triangles,
                                        glpgp_mesh **out, glpgp_surface_refine_info *info)
{
    *out = NULL;
    if (o->size_field != GLPGP_SIZE_AUTO && o->size_field != GLPGP_SIZE_ISO)
        return glpgp_mesh_refine_surface(m, h / GLPGP_SURFACE_EDGES, max_triangles, out, info);
    glpgp_mesh *cur = NULL;
    glpgp_status st = GLPGP_OK;
    int checked = 0; /* info->ratio measured on the final mesh's own size */
    for (int pass = 0; pass < GLPGP_SURFACE_REFINE_PASSES && st == GLPGP_OK; pass++) {
        glpgp_surface_refine_info ri;
        glpgp_mesh *next = NULL;
        st = refine_pass(cur ? cur : m, o, h, max_triangles, &next, &ri);
        if (st != GLPGP_OK) break;
        if (pass == 0) {
            *info = ri;
        } else {
            info->min_target = fmin(info->min_target, ri.min_target);
            info->stopped |= ri.stopped;
        }
        if (!next) { /* nothing longer than its h(x) / N (or the limit): ratio0 is the check */
            info->ratio = ri.ratio0;
            checked = !ri.stopped;
            break;
        }
        if (pass > 0) {
            info->splits += ri.splits;
            info->nv = ri.nv, info->nt = ri.nt, info->max_edge = ri.max_edge;
        }
        info->passes = pass + 1;
        if (cur) glpgp_surface_origin_compose(next, cur); /* next's origin: on m, not on cur */
        glpgp_mesh_destroy(&cur);
        cur = next;
        if (ri.stopped) break;
    }
    if (st == GLPGP_OK && cur && !checked) st = glpgp_surface_edge_ratio(cur, o, h, &info->ratio, NULL);
    if (st != GLPGP_OK) glpgp_mesh_destroy(&cur);
    *out = cur;
    return st;
}
