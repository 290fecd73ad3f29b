/* mesh/shapes.c: built-in test/benchmark shapes (square, disk, annulus, lshape)
 * at a requested vertex count. Squares and L-shapes are structured grids with
 * alternating diagonals; disks and annuli are concentric rings at uniform
 * spacing joined by a zipper triangulation. All O(n). */
#include "glpgp/shapes.h"
#include "glpgp/kinds.h"
#include "glpgp/surface.h"

#include <stdio.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI_ GLPGP_PI

static const char *const k_shapes[] = {"square", "disk", "annulus", "lshape", "sphere", "torus", "genus2",
                                       "cube", "hemisphere", "halfcyl", "halfcyl_flat", NULL};

const char *const *glpgp_mesh_shapes(void) { return k_shapes; }

int glpgp_shape_known(const char *name)
{
    for (int i = 0; k_shapes[i]; i++)
        if (!strcmp(name, k_shapes[i])) return 1;
    return 0;
}

glpgp_status glpgp_shape_parse(const char *spec, int allow_bare, char *name, size_t namelen,
                               long *nverts)
{
    const char *rest = spec;
    if (strncmp(spec, "shape:", 6) == 0)
        rest = spec + 6;
    else if (!allow_bare)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "'%s' is not of the form shape:NAME[:N]", spec);
    const char *colon = strchr(rest, ':');
    size_t n = colon ? (size_t)(colon - rest) : strlen(rest);
    if (n == 0 || n >= namelen)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "'%s': expected shape:NAME[:N]", spec);
    memcpy(name, rest, n);
    name[n] = '\0';
    if (!glpgp_shape_known(name))
        return GLPGP_FAIL(GLPGP_ERR_ARG,
                          "unknown shape '%s' (available: square, disk, annulus, lshape; surfaces: sphere, torus, "
                          "genus2, cube, hemisphere, halfcyl, halfcyl_flat)",
                          name);
    *nverts = GLPGP_SHAPE_DEFAULT_VERTICES;
    if (colon) {
        char *end = NULL;
        long v = strtol(colon + 1, &end, 10);
        if (end == colon + 1 || *end != '\0' || v < GLPGP_SHAPE_MIN_VERTICES ||
            v > GLPGP_SHAPE_MAX_VERTICES)
            return GLPGP_FAIL(GLPGP_ERR_ARG, "'%s': N must be an integer in [%ld, %ld]", spec,
                              GLPGP_SHAPE_MIN_VERTICES, GLPGP_SHAPE_MAX_VERTICES);
        *nverts = v;
    }
    return GLPGP_OK;
}

/* Grid of (N+1)^2 points on [0,1]^2 with spacing 1/N; for the L-shape the
 * points with i > N/2 and j > N/2 (and cells in [0.5,1]^2) are left out. */
static glpgp_status gen_grid(int N, int lshape, glpgp_mesh **out)
{
    glpgp_status st = GLPGP_OK;
    int *id = NULL, *tri = NULL;
    double *xy = NULL;
    int m = N / 2;
    long np = (long)(N + 1) * (N + 1);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)np, sizeof *id, &id), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)np * 2, sizeof *xy, &xy), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)N * N * 6, sizeof *tri, &tri), done);
    int nv = 0;
    for (int j = 0; j <= N; j++) {
        for (int i = 0; i <= N; i++) {
            long k = (long)j * (N + 1) + i;
            if (lshape && i > m && j > m) {
                id[k] = -1;
                continue;
            }
            id[k] = nv;
            /* i / N is exact at 0, 0.5 (even N) and 1. */
            xy[2 * nv] = (double)i / N;
            xy[2 * nv + 1] = (double)j / N;
            nv++;
        }
    }
    int nt = 0;
    for (int j = 0; j < N; j++) {
        for (int i = 0; i < N; i++) {
            if (lshape && i >= m && j >= m) continue;
            int v00 = id[(long)j * (N + 1) + i], v10 = id[(long)j * (N + 1) + i + 1];
            int v01 = id[(long)(j + 1) * (N + 1) + i], v11 = id[(long)(j + 1) * (N + 1) + i + 1];
            int *t = tri + 3L * nt;
            if ((i + j) % 2 == 0) {
                t[0] = v00, t[1] = v10, t[2] = v11;
                t[3] = v00, t[4] = v11, t[5] = v01;
            } else {
                t[0] = v00, t[1] = v10, t[2] = v01;
                t[3] = v10, t[4] = v11, t[5] = v01;
            }
            nt += 2;
        }
    }
    GLPGP_CHECK_GOTO(st, glpgp_mesh_create(nv, xy, nt, tri, out), done);
done:
    free(id);
    free(xy);
    free(tri);
    return st;
}

/* Ring layout for disk (r0 == 0) and annulus: K+1 rings at radii
 * r_k = r0 + (r1 - r0) k / K, ring k has n_k points (1 for the disk center). */
static long ring_count(double r0, double r1, int K, int k)
{
    if (r0 == 0.0 && k == 0) return 1;
    double d = (r1 - r0) / K;
    double r = r0 + (r1 - r0) * k / K;
    long n = lround(2.0 * PI_ * r / d);
    return n < 6 ? 6 : n;
}

static long rings_total(double r0, double r1, int K)
{
    long s = 0;
    for (int k = 0; k <= K; k++) s += ring_count(r0, r1, K, k);
    return s;
}

static glpgp_status gen_rings(double r0, double r1, long nverts, glpgp_mesh **out)
{
    glpgp_status st = GLPGP_OK;
    long *start = NULL, *cnt = NULL;
    double *xy = NULL, *phase = NULL;
    int *tri = NULL;
    /* Total is ~ pi K^2 (disk) or ~ 2 pi K^2 (r1+r0)/(2(r1-r0)) (annulus). */
    double c = r0 == 0.0 ? PI_ : PI_ * (r1 + r0) / (r1 - r0);
    int K = (int)lround(sqrt((double)nverts / c));
    if (K < 2) K = 2;
    while (K > 2 && rings_total(r0, r1, K) > nverts &&
           labs(rings_total(r0, r1, K - 1) - nverts) < labs(rings_total(r0, r1, K) - nverts))
        K--;
    while (rings_total(r0, r1, K) < nverts &&
           labs(rings_total(r0, r1, K + 1) - nverts) < labs(rings_total(r0, r1, K) - nverts))
        K++;
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)K + 2, sizeof *start, &start), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)K + 1, sizeof *cnt, &cnt), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)K + 1, sizeof *phase, &phase), done);
    start[0] = 0;
    for (int k = 0; k <= K; k++) {
        cnt[k] = ring_count(r0, r1, K, k);
        start[k + 1] = start[k] + cnt[k];
        /* Odd rings are rotated by half a spacing so the zipper makes
         * near-equilateral triangles instead of right ones. */
        phase[k] = (k % 2) ? PI_ / (double)cnt[k] : 0.0;
    }
    long nv = start[K + 1];
    if (nv > 0x7fffffffL / 2) {
        st = GLPGP_FAIL(GLPGP_ERR_ARG, "too many vertices requested (%ld)", nverts);
        goto done;
    }
    long nt_max = 0;
    for (int k = 0; k < K; k++) nt_max += (cnt[k] == 1 ? 0 : cnt[k]) + cnt[k + 1];
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv * 2, sizeof *xy, &xy), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nt_max * 3, sizeof *tri, &tri), done);
    for (int k = 0; k <= K; k++) {
        double r = k == 0 ? r0 : (k == K ? r1 : r0 + (r1 - r0) * k / K);
        for (long j = 0; j < cnt[k]; j++) {
            long v = start[k] + j;
            if (cnt[k] == 1) {
                xy[2 * v] = 0.0;
                xy[2 * v + 1] = 0.0;
            } else {
                double th = phase[k] + 2.0 * PI_ * (double)j / (double)cnt[k];
                xy[2 * v] = r * cos(th);
                xy[2 * v + 1] = r * sin(th);
            }
        }
    }
    long nt = 0;
    for (int k = 0; k < K; k++) {
        long na = cnt[k], nb = cnt[k + 1], sa = start[k], sb = start[k + 1];
        if (na == 1) { /* disk center: fan */
            for (long j = 0; j < nb; j++) {
                int *t = tri + 3 * nt++;
                t[0] = (int)sa, t[1] = (int)(sb + j), t[2] = (int)(sb + (j + 1) % nb);
            }
            continue;
        }
        /* Zipper: advance on the ring whose next point has the smaller angle. */
        long i = 0, j = 0;
        double da = 2.0 * PI_ / (double)na, db = 2.0 * PI_ / (double)nb;
        while (i < na || j < nb) {
            double ta = phase[k] + da * (double)(i + 1), tb = phase[k + 1] + db * (double)(j + 1);
            int *t = tri + 3 * nt++;
            t[0] = (int)(sa + i % na);
            t[1] = (int)(sb + j % nb);
            if (j == nb || (i < na && ta < tb)) {
                t[2] = (int)(sa + (i + 1) % na);
                i++;
            } else {
                t[2] = (int)(sb + (j + 1) % nb);
                j++;
            }
        }
    }
    GLPGP_CHECK_GOTO(st, glpgp_mesh_create((int)nv, xy, (int)nt, tri, out), done);
done:
    free(start);
    free(cnt);
    free(phase);
    free(xy);
    free(tri);
    return st;
}

glpgp_status glpgp_mesh_generate(const char *shape, long nverts, glpgp_mesh **out)
{
    if (!out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mesh_generate: out is NULL");
    *out = NULL;
    if (!shape) shape = "";
    int which = -1;
    for (int i = 0; k_shapes[i]; i++)
        if (!strcmp(shape, k_shapes[i])) which = i;
    if (which < 0)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "unknown shape '%s' (shapes: square, disk, annulus, lshape)", shape);
    if (nverts < 16) return GLPGP_FAIL(GLPGP_ERR_ARG, "nverts must be at least 16 (got %ld)", nverts);
    if (nverts > GLPGP_SHAPE_MAX_VERTICES) return GLPGP_FAIL(GLPGP_ERR_ARG, "nverts too large (%ld)", nverts);
    if (glpgp_surface_shape_known(shape)) return glpgp_surface_generate(shape, nverts, out);
    switch (which) {
    case 0: { /* square: (N+1)^2 vertices */
        int N = (int)lround(sqrt((double)nverts)) - 1;
        if (N < 3) N = 3;
        GLPGP_CHECK(gen_grid(N, 0, out));
        break;
    }
    case 3: { /* L-shape with N = 2m: 3 m^2 + 4 m + 1 vertices */
        int best = 2;
        long best_err = -1;
        int m0 = (int)lround(sqrt((double)nverts / 3.0));
        for (int m = m0 - 2; m <= m0 + 2; m++) {
            if (m < 2) continue;
            long err = labs(3L * m * m + 4L * m + 1 - nverts);
            if (best_err < 0 || err < best_err) {
                best_err = err;
                best = m;
            }
        }
        GLPGP_CHECK(gen_grid(2 * best, 1, out));
        break;
    }
    case 1: GLPGP_CHECK(gen_rings(0.0, 1.0, nverts, out)); break;
    case 2: GLPGP_CHECK(gen_rings(0.3, 1.0, nverts, out)); break;
    }
    return GLPGP_OK;
}
