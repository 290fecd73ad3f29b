/* solver/distributed.c: the driver's global quantities on one rank's part of
 * a distributed mesh (glpgp_mesh.part): counts over the owned vertices,
 * order statistics of |z| over all ranks (exact: a bisection on the value,
 * counts summed by the backend's reduce op), and the summary of an
 * oscillator (singular triangles counted once: by the rank owning their
 * lowest global vertex). On one rank of P = 1 these equal result.c's. */
#include "internal.h"

#include "glpgp/phase.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static glpgp_status reduce(glpgp_backend *b, double *v, int n, int op)
{
    if (!b->ops->reduce)
        return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "the %s backend has no distributed meshes", b->ops->name);
    return b->ops->reduce(b, v, n, op);
}

glpgp_status glpgp_dist_count(glpgp_backend *b, const glpgp_mesh *m, const unsigned char *flag, int *n)
{
    double c = 0.0;
    for (int i = 0; i < m->part->nv_owned; i++) c += flag[i] != 0;
    GLPGP_CHECK(reduce(b, &c, 1, GLPGP_REDUCE_SUM));
    *n = (int)c;
    return GLPGP_OK;
}

/* out[j] <- the k[j]-th smallest (0-based) of the values s of all ranks
 * (s: this rank's n values, sorted increasing, >= 0): per j the smallest x
 * with #{values <= x} > k[j], by bisection on the bits of x (non-negative
 * doubles order as their bit patterns); nk <= 4, in lockstep: 63 reductions */
static glpgp_status kth(glpgp_backend *b, const double *s, int n, const double *k, int nk, double *out)
{
    uint64_t lo[4], hi[4];
    for (int j = 0; j < nk; j++) {
        lo[j] = 0;
        hi[j] = UINT64_C(0x7ff0000000000000); /* +inf */
    }
    for (;;) {
        int open = 0;
        double c[4] = {0.0, 0.0, 0.0, 0.0};
        uint64_t mid[4];
        for (int j = 0; j < nk; j++) {
            mid[j] = lo[j] + (hi[j] - lo[j]) / 2;
            open |= lo[j] < hi[j];
            double x;
            memcpy(&x, &mid[j], sizeof x);
            /* #{s <= x}: upper bound in the sorted s */
            int a = 0, e = n;
            while (a < e) {
                const int q = a + (e - a) / 2;
                if (s[q] <= x) a = q + 1;
                else e = q;
            }
            c[j] = a;
        }
        if (!open) break; /* every rank leaves together: the bounds are the same everywhere */
        GLPGP_CHECK(reduce(b, c, nk, GLPGP_REDUCE_SUM));
        for (int j = 0; j < nk; j++) {
            if (lo[j] >= hi[j]) continue;
            if (c[j] > k[j]) hi[j] = mid[j];
            else lo[j] = mid[j] + 1;
        }
    }
    for (int j = 0; j < nk; j++) memcpy(&out[j], &lo[j], sizeof out[j]);
    return GLPGP_OK;
}

glpgp_status glpgp_dist_zabs_stats(glpgp_backend *b, const glpgp_mesh *m, const double *z, double *min, double *p10,
                                   double *median)
{
    const int n = m->part->nv_owned;
    double *s = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)(n > 0 ? n : 1), sizeof(double), &s));
    for (int i = 0; i < n; i++) s[i] = hypot(z[2 * i], z[2 * i + 1]);
    qsort(s, (size_t)n, sizeof(double), glpgp_cmp_double);
    double N = n;
    glpgp_status st = reduce(b, &N, 1, GLPGP_REDUCE_SUM);
    /* the ranks of result.c: min, s[(N-1) 0.1], median (mean of the middle two for even N) */
    const long nn = (long)N;
    double k[4] = {0.0, (double)(size_t)((nn - 1) * 0.1), (double)(nn / 2), (double)(nn % 2 ? nn / 2 : nn / 2 - 1)};
    double v[4] = {0.0, 0.0, 0.0, 0.0};
    if (st == GLPGP_OK) st = kth(b, s, n, k, 4, v);
    free(s);
    GLPGP_CHECK(st);
    if (min) *min = v[0];
    if (p10) *p10 = v[1];
    if (median) *median = nn % 2 ? v[2] : 0.5 * (v[3] + v[2]);
    return GLPGP_OK;
}

glpgp_status glpgp_dist_summarize(glpgp_backend *b, const glpgp_mesh *m, glpgp_osc_result *o)
{
    /* singular triangles: every local one marked, those this rank counts summed */
    double c[2] = {0.0, 0.0};
    for (int t = 0; t < m->nt; t++) {
        const int *v = m->tri + 3 * t;
        const int w = glpgp_phase_winding_z(o->z, v[0], v[1], v[2]);
        o->singular[t] = (signed char)w;
        if (w != 0 && glpgp_part_counts_tri(m->part, m->tri, t)) c[w > 0 ? 0 : 1] += 1.0;
    }
    GLPGP_CHECK(reduce(b, c, 2, GLPGP_REDUCE_SUM));
    o->plus = (int)c[0];
    o->minus = (int)c[1];
    return glpgp_dist_zabs_stats(b, m, o->z, &o->zabs_min, &o->zabs_p10, &o->zabs_median);
}
