/* solver/result.c: creation and destruction of results, singular triangles
 * and |z| statistics of an oscillator (glpgp/result.h). */
#include "glpgp/result.h"
#include "glpgp/cross.h"
#include "glpgp/phase.h"
#include "internal.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

glpgp_status glpgp_result_create(int nv, int nt, glpgp_result **out)
{
    glpgp_status st = GLPGP_OK;
    glpgp_result *r = NULL;
    *out = NULL;
    if (nv < 1 || nt < 1) return GLPGP_FAIL(GLPGP_ERR_ARG, "result of %d vertices, %d triangles", nv, nt);
    GLPGP_CHECK(glpgp_calloc(1, sizeof *r, &r));
    r->nv = nv;
    r->nt = nt;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * nv, sizeof(double), &r->field), fail);
    for (int k = 0; k < 2; k++) {
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * nv, sizeof(double), &r->osc[k].z), fail);
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nv, 1, &r->osc[k].dirichlet), fail);
        GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)nt, 1, &r->osc[k].singular), fail);
    }
    *out = r;
    return GLPGP_OK;
fail:
    glpgp_result_destroy(&r);
    return st;
}

void glpgp_result_destroy(glpgp_result **pr)
{
    if (!pr || !*pr) return;
    glpgp_result *r = *pr;
    free(r->field);
    glpgp_cross_result_destroy(&r->cross);
    for (int k = 0; k < 2; k++) {
        free(r->osc[k].z);
        free(r->osc[k].dirichlet);
        free(r->osc[k].singular);
    }
    free(r);
    *pr = NULL;
}

/* The windings of z per triangle; th (may be NULL): each vertex's theta of z
 * computed beforehand (the same values as per corner, fewer atan2 calls). */
static void windings(const glpgp_mesh *m, const double *z, const double *th, signed char *sing, int *plus,
                     int *minus)
{
    int p = 0, q = 0;
    for (int t = 0; t < m->nt; t++) {
        const int *v = m->tri + 3 * t;
        const double tt[3] = {th ? th[v[0]] : glpgp_theta(z[2 * v[0]], z[2 * v[0] + 1]),
                              th ? th[v[1]] : glpgp_theta(z[2 * v[1]], z[2 * v[1] + 1]),
                              th ? th[v[2]] : glpgp_theta(z[2 * v[2]], z[2 * v[2] + 1])};
        const int w = glpgp_phase_winding(tt);
        if (sing) sing[t] = (signed char)w;
        p += w > 0;
        q += w < 0;
    }
    *plus = p;
    *minus = q;
}

void glpgp_singularities(const glpgp_mesh *m, const double *z, signed char *sing, int *plus,
                         int *minus)
{
    windings(m, z, NULL, sing, plus, minus);
}

/* qsort comparator: doubles ascending (solver/internal.h) */
int glpgp_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

glpgp_status glpgp_osc_summarize(const glpgp_mesh *m, glpgp_osc_result *o)
{
    double *s = NULL;
    const int nv = m->nv;
    GLPGP_CHECK(glpgp_malloc((size_t)nv, sizeof(double), &s));
    /* each vertex's theta once (not once per triangle corner): a sixth of the atan2 calls */
    for (int i = 0; i < nv; i++) s[i] = glpgp_theta(o->z[2 * i], o->z[2 * i + 1]);
    windings(m, o->z, s, o->singular, &o->plus, &o->minus);
    o->zabs_median = glpgp_zabs_median(o->z, nv, s, &o->zabs_min, &o->zabs_p10);
    free(s);
    return GLPGP_OK;
}

double glpgp_zabs_median(const double *z, int nv, double *scratch, double *min, double *p10)
{
    double mn = INFINITY;
    for (int i = 0; i < nv; i++) {
        scratch[i] = z[2 * i] * z[2 * i] + z[2 * i + 1] * z[2 * i + 1];
        if (scratch[i] < mn) mn = scratch[i];
    }
    if (min) *min = sqrt(mn);
    if (p10) *p10 = sqrt(glpgp_select_double(scratch, (size_t)nv, (size_t)((nv - 1) * 0.1)));
    /* the median of the squares' order: the middle one, or the mean of the middle two */
    const size_t h = (size_t)nv / 2;
    const double upper = sqrt(glpgp_select_double(scratch, (size_t)nv, h));
    if (nv % 2) return upper;
    double lower = scratch[0];
    for (size_t i = 1; i < h; i++)
        if (scratch[i] > lower) lower = scratch[i];
    return 0.5 * (sqrt(lower) + upper);
}

/* every per-vertex array: a[i] <- a'[new(i)] through one scratch copy */
glpgp_status glpgp_result_permute_vertices(glpgp_result *r, const int *new_of_old)
{
    const int nv = r->nv;
    double *t = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)2 * nv, sizeof *t, &t));
    double *vec[4] = {r->field, r->osc[0].z, r->osc[1].z, r->cross ? r->cross->w : NULL};
    for (int k = 0; k < 4; k++) {
        if (!vec[k]) continue;
        memcpy(t, vec[k], (size_t)2 * nv * sizeof *t);
        for (int i = 0; i < nv; i++) {
            vec[k][2 * i] = t[2 * new_of_old[i]];
            vec[k][2 * i + 1] = t[2 * new_of_old[i] + 1];
        }
    }
    unsigned char *f = (unsigned char *)t;
    for (int k = 0; k < 2; k++) {
        memcpy(f, r->osc[k].dirichlet, (size_t)nv);
        for (int i = 0; i < nv; i++) r->osc[k].dirichlet[i] = f[new_of_old[i]];
    }
    free(t);
    return GLPGP_OK;
}
