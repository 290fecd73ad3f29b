/* test_generate.c: tests for glpgp_mesh_generate: vertex counts, areas,
 * boundary loops, triangle quality (min angle), orientation, boundary
 * vertices on the analytic boundary, argument errors, determinism, and the
 * time to generate a 1M-vertex disk (printed, not asserted). */
#include "glpgp/io.h"
#include "glpgp/mesh.h"
#include "glpgp/phase.h"
#include "glpgp/shapes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int g_fail;
#define CHECK(c)                                                                       \
    do {                                                                               \
        if (!(c)) {                                                                    \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #c);      \
            g_fail++;                                                                  \
        }                                                                              \
    } while (0)

static const double PI = 3.14159265358979323846;

static double min_angle_deg(const glpgp_mesh *m)
{
    double mn = 180.0;
    for (int t = 0; t < m->nt; t++) {
        const int *v = m->tri + 3 * t;
        for (int k = 0; k < 3; k++) {
            const double *a = m->xy + 2 * v[k], *b = m->xy + 2 * v[(k + 1) % 3], *c = m->xy + 2 * v[(k + 2) % 3];
            double ux = b[0] - a[0], uy = b[1] - a[1], wx = c[0] - a[0], wy = c[1] - a[1];
            double ang = atan2(fabs(ux * wy - uy * wx), ux * wx + uy * wy) * 180.0 / PI;
            if (ang < mn) mn = ang;
        }
    }
    return mn;
}

static int count_cw(const glpgp_mesh *m)
{
    int n = 0;
    for (int t = 0; t < m->nt; t++) {
        const int *v = m->tri + 3 * t;
        const double *a = m->xy + 2 * v[0], *b = m->xy + 2 * v[1], *c = m->xy + 2 * v[2];
        if (!((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0.0)) n++;
    }
    return n;
}

/* Distance of (x, y) from the analytic boundary of the shape. */
static double boundary_dist(const char *shape, double x, double y)
{
    if (!strcmp(shape, "disk")) return fabs(hypot(x, y) - 1.0);
    if (!strcmp(shape, "annulus")) {
        double r = hypot(x, y);
        return fmin(fabs(r - 1.0), fabs(r - 0.3));
    }
    double d = fmin(fmin(fabs(x), fabs(1.0 - x)), fmin(fabs(y), fabs(1.0 - y)));
    if (!strcmp(shape, "lshape")) {
        if (x > 0.5 + 1e-12 && y > 0.5 + 1e-12) return 1.0; /* inside the removed quadrant */
        if (y >= 0.5) d = fmin(d, fabs(x - 0.5));
        if (x >= 0.5) d = fmin(d, fabs(y - 0.5));
    }
    return d;
}

static void check_shape(const char *shape, long n, double area, int loops)
{
    glpgp_mesh *m = NULL;
    glpgp_error_clear();
    glpgp_status st = glpgp_mesh_generate(shape, n, &m);
    CHECK(st == GLPGP_OK);
    if (st != GLPGP_OK || !m) {
        fprintf(stderr, "%s %ld: %s\n", shape, n, glpgp_error_message());
        return;
    }
    double ma = min_angle_deg(m);
    printf("%-8s n=%-6ld nv=%-6d nt=%-6d area=%.6f loops=%d min_angle=%.2f\n", shape, n, m->nv, m->nt, m->area,
           m->nloops, ma);
    CHECK(fabs((double)m->nv - (double)n) <= 0.15 * (double)n);
    CHECK(fabs(m->area - area) <= 0.01 * area);
    CHECK(m->nloops == loops);
    CHECK(ma >= 25.0);
    CHECK(count_cw(m) == 0);
    CHECK(m->orientation_fixed == 0);
    /* Boundary vertices on the analytic boundary; interior ones off it. */
    int off = 0, nb = 0;
    for (int l = 0; l < m->nloops; l++)
        for (int i = m->loop_start[l]; i < m->loop_start[l + 1]; i++) {
            int v = m->loop_vertices[i];
            if (boundary_dist(shape, m->xy[2 * v], m->xy[2 * v + 1]) > 1e-12) off++;
            nb++;
        }
    CHECK(off == 0);
    int inner_on = 0;
    for (int v = 0; v < m->nv; v++)
        if (!m->on_boundary[v] && boundary_dist(shape, m->xy[2 * v], m->xy[2 * v + 1]) <= 1e-12) inner_on++;
    CHECK(inner_on == 0);
    CHECK(nb == m->loop_start[m->nloops]);
    if (!strcmp(shape, "annulus") && m->nloops == 2) {
        /* Loop 0 is the outer circle, loop 1 the hole. */
        int v0 = m->loop_vertices[m->loop_start[0]], v1 = m->loop_vertices[m->loop_start[1]];
        CHECK(fabs(hypot(m->xy[2 * v0], m->xy[2 * v0 + 1]) - 1.0) < 1e-12);
        CHECK(fabs(hypot(m->xy[2 * v1], m->xy[2 * v1 + 1]) - 0.3) < 1e-12);
    }
    if (!strcmp(shape, "square") || !strcmp(shape, "lshape")) {
        /* Corners are exact vertices. */
        const double sq[] = {0, 0, 1, 0, 1, 1, 0, 1}, ls[] = {0, 0, 1, 0, 1, 0.5, 0.5, 0.5, 0.5, 1, 0, 1};
        const double *c = strcmp(shape, "square") ? ls : sq;
        int nc = strcmp(shape, "square") ? 6 : 4;
        for (int k = 0; k < nc; k++) {
            int found = 0;
            for (int v = 0; v < m->nv && !found; v++)
                found = m->xy[2 * v] == c[2 * k] && m->xy[2 * v + 1] == c[2 * k + 1] && m->on_boundary[v];
            CHECK(found);
        }
    }
    /* Deterministic. */
    glpgp_mesh *m2 = NULL;
    CHECK(glpgp_mesh_generate(shape, n, &m2) == GLPGP_OK);
    if (m2) {
        CHECK(m2->nv == m->nv && m2->nt == m->nt);
        if (m2->nv == m->nv && m2->nt == m->nt) {
            CHECK(!memcmp(m->xy, m2->xy, sizeof(double) * 2 * (size_t)m->nv));
            CHECK(!memcmp(m->tri, m2->tri, sizeof(int) * 3 * (size_t)m->nt));
        }
        glpgp_mesh_destroy(&m2);
    }
    glpgp_mesh_destroy(&m);
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(void)
{
    const char *const *shapes = glpgp_mesh_shapes();
    CHECK(shapes && shapes[0] && !strcmp(shapes[0], "square") && !strcmp(shapes[1], "disk") &&
          !strcmp(shapes[2], "annulus") && !strcmp(shapes[3], "lshape") && !strcmp(shapes[4], "sphere") &&
          !strcmp(shapes[10], "halfcyl_flat") && shapes[11] == NULL);

    const long sizes[] = {2000, 20000};
    for (int i = 0; i < 2; i++) {
        check_shape("square", sizes[i], 1.0, 1);
        check_shape("disk", sizes[i], PI, 1);
        check_shape("annulus", sizes[i], PI * (1.0 - 0.09), 2);
        check_shape("lshape", sizes[i], 0.75, 1);
    }
    /* Small meshes are still valid. */
    const char *all[] = {"square", "disk", "annulus", "lshape"};
    for (int s = 0; s < 4; s++) {
        glpgp_mesh *m = NULL;
        CHECK(glpgp_mesh_generate(all[s], 16, &m) == GLPGP_OK);
        if (m) {
            CHECK(count_cw(m) == 0 && min_angle_deg(m) >= 25.0);
            glpgp_mesh_destroy(&m);
        }
    }

    glpgp_mesh *m = (glpgp_mesh *)&m;
    glpgp_error_clear();
    CHECK(glpgp_mesh_generate("circle", 1000, &m) == GLPGP_ERR_ARG);
    CHECK(m == NULL);
    CHECK(strstr(glpgp_error_message(), "circle") && strstr(glpgp_error_message(), "annulus") &&
          strstr(glpgp_error_message(), "lshape"));
    glpgp_error_clear();
    CHECK(glpgp_mesh_generate("disk", 15, &m) == GLPGP_ERR_ARG);
    glpgp_error_clear();
    CHECK(glpgp_mesh_generate(NULL, 1000, &m) == GLPGP_ERR_ARG);
    glpgp_error_clear();

    double t0 = now_s();
    glpgp_status st = glpgp_mesh_generate("disk", 1000000, &m);
    double t1 = now_s();
    CHECK(st == GLPGP_OK);
    if (m) {
        printf("disk 1M: nv=%d nt=%d generated in %.3f s\n", m->nv, m->nt, t1 - t0);
        CHECK(fabs(m->nv - 1000000.0) <= 0.05 * 1000000.0);
        CHECK(fabs(m->area - PI) <= 1e-4 * PI);
        glpgp_mesh_destroy(&m);
    }

    if (g_fail) {
        fprintf(stderr, "test_generate: %d check(s) failed\n", g_fail);
        return 1;
    }
    printf("test_generate: all checks passed\n");
    return 0;
}
