/* tests/quads/halfcyl_waves.h: the plane waves of the half cylinder
 * (radius 2, axis z; shape "halfcyl"), shared by the surface quad tests:
 * u's phase 2 pi (s / hu + 1/2) along the arc length s, v's 2 pi (z / hv +
 * 1/2) along the axis, so the extraction's grid lines fall half a period
 * from the rims; r->size = hv. NULL when the result cannot be created
 * (the failed check is recorded). */
#ifndef GLPGP_TESTS_HALFCYL_WAVES_H
#define GLPGP_TESTS_HALFCYL_WAVES_H

#include "testutil.h"

static inline glpgp_result *halfcyl_waves(const glpgp_mesh *m, double hu, double hv)
{
    glpgp_result *r = NULL;
    CHECK_OK(glpgp_result_create(m->nv, m->nt, &r));
    if (!r) return NULL;
    r->size = hv;
    for (int i = 0; i < m->nv; i++) {
        const double *p = m->xyz + 3 * i;
        const double s = 2.0 * atan2(p[1], p[0]), y = p[2]; /* arc length on radius 2 */
        const double a = 2.0 * GLPGP_PI * (s / hu + 0.5), b = 2.0 * GLPGP_PI * (y / hv + 0.5);
        r->osc[0].z[2 * i] = cos(a);
        r->osc[0].z[2 * i + 1] = sin(a);
        r->osc[1].z[2 * i] = cos(b);
        r->osc[1].z[2 * i + 1] = sin(b);
    }
    return r;
}

#endif
