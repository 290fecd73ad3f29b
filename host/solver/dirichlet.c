/* solver/dirichlet.c: the Dirichlet set of an oscillator: boundary vertices
 * where its wave runs across the boundary (glpgp/solve.h). */
#include "glpgp/solve.h"
#include "glpgp/internal/newton.h"

#include <math.h>

int glpgp_dirichlet_set(const glpgp_mesh *m, const double *w, unsigned char *dir)
{
    int n = 0;
    if (!m->normal_prev) { /* a surface: glpgp_surface_dirichlet */
        for (int i = 0; i < m->nv; i++) dir[i] = 0;
        return 0;
    }
    for (int i = 0; i < m->nv; i++) {
        dir[i] = 0;
        if (!m->on_boundary[i]) continue;
        const double *nn[2] = {m->normal_prev + 2 * i, m->normal_next + 2 * i};
        for (int e = 0; e < 2; e++) {
            /* |W.n| >= |W.t| with t = n rotated by 90 degrees */
            double wn = w[2 * i] * nn[e][0] + w[2 * i + 1] * nn[e][1];
            double wt = -w[2 * i] * nn[e][1] + w[2 * i + 1] * nn[e][0];
            if (fabs(wn) >= fabs(wt)) dir[i] = 1;
        }
        n += dir[i];
    }
    return n;
}
