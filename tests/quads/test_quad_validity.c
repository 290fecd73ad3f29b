/* test_quad_validity.c: the quality report finds what makes a quad mesh
 * invalid, on meshes made by hand against built-in domains (no solve, no
 * Gmsh):
 *  - a 4 x 4 grid on the unit square is valid (all counts 0, loops 1 of 1,
 *    area ratio 1), also when written clockwise (one orientation for the
 *    whole mesh);
 *  - a folded quad (one vertex pulled across the opposite side) is counted
 *    inverted and makes the mesh invalid; a face written in the other
 *    orientation than the rest is inverted and its shared edges are folds
 *    (non-manifold); the same read back from an MSH file (the reader keeps
 *    the file's orientation);
 *  - a non-manifold edge (three quads on one edge), a pinched vertex (two
 *    quads touching at a corner), an overlapping face (a quad on top of the
 *    grid), a non-quad face, a quad sticking out of the domain;
 *  - a lost hole: quads covering the annulus' hole (boundary loops 1 of 2,
 *    faces over the lost hole), a gap (a missing face: loops 2 of 1);
 *  - glpgp_quads_invalid_text names the reasons; ignoring the non-quad bit
 *    (--keep-polygons) leaves a polygon mesh valid;
 *  - glpgp_quadmesh_repair turns the broken grids (folded vertex, missing
 *    face, overlapping face, a face across the annulus' hole) into valid
 *    all-quad meshes that cover the domain, keeping the good faces. */
#include "testutil.h"

#include <string.h>
#include <unistd.h>

/* A quad mesh from arrays (faces of 4 corners unless fn given). */
static glpgp_quadmesh *make_q(int nv, const double *xy, int nf, const int *fv, const int *fn)
{
    glpgp_quadmesh *q = calloc(1, sizeof *q);
    q->nv = nv;
    q->xy = malloc(sizeof(double) * 2 * (size_t)nv);
    memcpy(q->xy, xy, sizeof(double) * 2 * (size_t)nv);
    q->nf = nf;
    q->face_start = malloc(sizeof(int) * ((size_t)nf + 1));
    q->face_start[0] = 0;
    for (int f = 0; f < nf; f++) q->face_start[f + 1] = q->face_start[f] + (fn ? fn[f] : 4);
    q->face_vert = malloc(sizeof(int) * (size_t)q->face_start[nf]);
    memcpy(q->face_vert, fv, sizeof(int) * (size_t)q->face_start[nf]);
    return q;
}

/* n x n grid on [0,1]^2: vertices (i, j) -> j (n+1) + i, faces CCW. */
static glpgp_quadmesh *grid(int n, int extra_faces, const int *extra, int skip_face)
{
    int nv = (n + 1) * (n + 1);
    double *xy = malloc(sizeof(double) * 2 * (size_t)nv);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            xy[2 * (j * (n + 1) + i)] = (double)i / n;
            xy[2 * (j * (n + 1) + i) + 1] = (double)j / n;
        }
    int *fv = malloc(sizeof(int) * 4 * (size_t)(n * n + extra_faces));
    int nf = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            if (j * n + i == skip_face) continue;
            int a = j * (n + 1) + i;
            int *f = fv + 4 * nf++;
            f[0] = a;
            f[1] = a + 1;
            f[2] = a + n + 2;
            f[3] = a + n + 1;
        }
    for (int k = 0; k < extra_faces; k++) memcpy(fv + 4 * nf++, extra + 4 * k, 4 * sizeof(int));
    glpgp_quadmesh *q = make_q(nv, xy, nf, fv, NULL);
    free(xy);
    free(fv);
    return q;
}

static glpgp_quads_report report(const glpgp_quadmesh *q, const glpgp_mesh *m, double h, const char *what)
{
    glpgp_quads_report qq;
    memset(&qq, 0, sizeof qq);
    CHECK_OK(glpgp_quads_quality(q, m, h, &qq));
    char why[512];
    glpgp_quads_invalid_text(&qq, 0, why, sizeof why);
    printf("%-28s invalid 0x%03x: %s\n", what, qq.invalid, qq.invalid ? why : "(valid)");
    return qq;
}

/* Repair and check the result: valid, all quads, area kept. */
static void repaired_valid(const glpgp_quadmesh *q, const glpgp_mesh *m, double h, const char *what)
{
    glpgp_quadmesh *r = NULL;
    CHECK_OK(glpgp_quadmesh_repair(q, m, h, 20, 0, &r));
    if (!r) return;
    glpgp_quads_report qq = report(r, m, h, what);
    CHECK(qq.invalid == 0);
    CHECK(qq.others == 0 && qq.inverted == 0 && qq.degenerate == 0 && qq.nonmanifold_edges == 0);
    CHECK(qq.boundary_loops == m->nloops);
    CHECK_CLOSE(qq.area, m->area, 0, 0.01);
    CHECK(qq.repair.rounds >= 1 && qq.repair.new_quads > 0);
    glpgp_quadmesh_destroy(&r);
}

int main(void)
{
    glpgp_mesh *sq = NULL, *an = NULL;
    CHECK_OK(glpgp_mesh_generate("square", 2000, &sq));
    CHECK_OK(glpgp_mesh_generate("annulus", 3000, &an));
    if (!sq || !an) TEST_DONE();
    const double h = 0.25;

    /* valid grid, and the same clockwise */
    glpgp_quadmesh *q = grid(4, 0, NULL, -1);
    glpgp_quads_report qq = report(q, sq, h, "grid");
    CHECK(qq.invalid == 0 && qq.inverted == 0 && qq.overlaps == 0 && qq.pinched == 0);
    CHECK(qq.boundary_loops == 1 && qq.domain_loops == 1 && qq.orientation == 1);
    CHECK_CLOSE(qq.area_ratio, 1.0, 1e-12, 0);
    for (int f = 0; f < q->nf; f++) { /* reverse every face */
        int *v = q->face_vert + 4 * f, t = v[1];
        v[1] = v[3];
        v[3] = t;
    }
    qq = report(q, sq, h, "grid clockwise");
    CHECK(qq.invalid == 0 && qq.orientation == -1 && qq.area > 0);
    glpgp_quadmesh_destroy(&q);

    /* folded quad: vertex (1,1) (index 6) pulled across to (0.5, 0.1) */
    q = grid(4, 0, NULL, -1);
    q->xy[12] = 0.5 * 0.25 + 0.01;
    q->xy[13] = 0.1;
    qq = report(q, sq, h, "folded vertex");
    CHECK(qq.inverted > 0 && (qq.invalid & GLPGP_QUADS_BAD_INVERTED));
    repaired_valid(q, sq, h, "  repaired");
    glpgp_quadmesh_destroy(&q);

    /* one face in the other orientation: inverted, and its inner edges are folds */
    q = grid(4, 0, NULL, -1);
    {
        int *v = q->face_vert + 4 * 5, t = v[1];
        v[1] = v[3];
        v[3] = t;
    }
    qq = report(q, sq, h, "one face reversed");
    CHECK(qq.inverted == 1 && qq.nonmanifold_edges == 4);
    CHECK((qq.invalid & GLPGP_QUADS_BAD_INVERTED) && (qq.invalid & GLPGP_QUADS_BAD_NONMANIFOLD));
    /* the same read back from MSH: the orientation of the file is kept */
    {
        char path[] = "/tmp/glpgp_validity_XXXXXX";
        int fd = mkstemp(path);
        CHECK(fd >= 0);
        if (fd >= 0) close(fd);
        char msh[64];
        snprintf(msh, sizeof msh, "%s.msh", path);
        CHECK_OK(glpgp_quads_write(q, msh));
        glpgp_quadmesh *r = NULL;
        CHECK_OK(glpgp_quads_read_msh(msh, &r));
        if (r) {
            glpgp_quads_report q2 = report(r, sq, h, "  read back from MSH");
            CHECK(q2.inverted == 1 && (q2.invalid & GLPGP_QUADS_BAD_INVERTED));
            glpgp_quadmesh_destroy(&r);
        }
        unlink(msh);
        unlink(path);
    }
    glpgp_quadmesh_destroy(&q);

    /* non-manifold edge: a third quad on the edge 1-4 of two unit quads */
    {
        double xy[] = {0, 0, 1, 0, 2, 0, 0, 1, 1, 1, 2, 1, 0.5, 0.5};
        int fv[] = {0, 1, 4, 3, 1, 2, 5, 4, 6, 1, 4, 0};
        glpgp_quadmesh *n = make_q(7, xy, 3, fv, NULL);
        qq = report(n, NULL, 1.0, "non-manifold edge");
        CHECK(qq.nonmanifold_edges >= 1 && (qq.invalid & GLPGP_QUADS_BAD_NONMANIFOLD));
        glpgp_quadmesh_destroy(&n);
    }

    /* pinched vertex: two quads touching at one corner */
    {
        double xy[] = {0, 0, 1, 0, 1, 1, 0, 1, 2, 1, 2, 2, 1, 2};
        int fv[] = {0, 1, 2, 3, 2, 4, 5, 6};
        glpgp_quadmesh *n = make_q(7, xy, 2, fv, NULL);
        qq = report(n, NULL, 1.0, "pinched vertex");
        CHECK(qq.pinched == 1 && (qq.invalid & GLPGP_QUADS_BAD_PINCHED));
        CHECK(qq.boundary_loops == 1 || qq.boundary_loops == 2);
        glpgp_quadmesh_destroy(&n);
    }

    /* overlapping face: an extra quad on top of the grid */
    {
        int extra[] = {0, 2, 12, 10}; /* (0,0) (0.5,0) (0.5,0.5) (0,0.5) */
        q = grid(4, 1, extra, -1);
        qq = report(q, sq, h, "overlapping quad");
        CHECK(qq.overlaps > 0 && (qq.invalid & GLPGP_QUADS_BAD_OVERLAP));
        repaired_valid(q, sq, h, "  repaired");
        glpgp_quadmesh_destroy(&q);
    }

    /* non-quad face: two grid quads merged into a hexagon; valid once the
     * non-quad bit is ignored (--keep-polygons) */
    {
        q = grid(4, 0, NULL, -1);
        int nf = q->nf;
        int *fv = malloc(sizeof(int) * 4 * (size_t)nf), *fn = malloc(sizeof(int) * (size_t)nf);
        int w = 0, k = 0;
        for (int f = 0; f < nf; f++) {
            if (f == 0) { /* faces 0 and 1 -> hexagon 0 1 2 7 6 5 */
                int hx[6] = {0, 1, 2, 7, 6, 5};
                memcpy(fv + w, hx, sizeof hx);
                w += 6;
                fn[k++] = 6;
                continue;
            }
            if (f == 1) continue;
            memcpy(fv + w, q->face_vert + 4 * f, 4 * sizeof(int));
            w += 4;
            fn[k++] = 4;
        }
        glpgp_quadmesh *n = make_q(q->nv, q->xy, k, fv, fn);
        qq = report(n, sq, h, "hexagon");
        CHECK(qq.others == 1 && qq.invalid == GLPGP_QUADS_BAD_NONQUAD);
        char why[256];
        CHECK(glpgp_quads_invalid_text(&qq, GLPGP_QUADS_BAD_NONQUAD, why, sizeof why) == 0);
        CHECK(glpgp_quads_invalid_text(&qq, 0, why, sizeof why) != 0 && strstr(why, "non-quad") != NULL);
        repaired_valid(n, sq, h, "  repaired");
        glpgp_quadmesh_destroy(&n);
        glpgp_quadmesh_destroy(&q);
        free(fv);
        free(fn);
    }

    /* a quad out of the domain: a vertex of the top row pushed up */
    q = grid(4, 0, NULL, -1);
    q->xy[2 * 22 + 1] = 1.2;
    qq = report(q, sq, h, "vertex outside");
    CHECK(qq.outside > 0 && (qq.invalid & GLPGP_QUADS_BAD_OUTSIDE));
    repaired_valid(q, sq, h, "  repaired");
    glpgp_quadmesh_destroy(&q);

    /* a gap: one face missing */
    q = grid(4, 0, NULL, 5);
    qq = report(q, sq, h, "missing face");
    CHECK(qq.boundary_loops == 2 && (qq.invalid & GLPGP_QUADS_BAD_LOOPS) && (qq.invalid & GLPGP_QUADS_BAD_GAPS));
    repaired_valid(q, sq, h, "  repaired");
    glpgp_quadmesh_destroy(&q);

    /* lost hole: 8 x 8 grid over [-1,1]^2 restricted to the faces whose
     * corners are all inside the unit disk, the hole of the annulus (r 0.3)
     * covered */
    {
        int n = 8;
        q = grid(n, 0, NULL, -1);
        for (int i = 0; i < 2 * q->nv; i++) q->xy[i] = 2.0 * q->xy[i] - 1.0;
        int w = 0, k = 0;
        for (int f = 0; f < q->nf; f++) {
            int in = 1;
            for (int j = 0; j < 4; j++) {
                const double *p = q->xy + 2 * q->face_vert[4 * f + j];
                in &= hypot(p[0], p[1]) <= 1.0;
            }
            if (!in) continue;
            memmove(q->face_vert + w, q->face_vert + 4 * f, 4 * sizeof(int));
            w += 4;
            k++;
        }
        q->nf = k;
        for (int f = 0; f <= k; f++) q->face_start[f] = 4 * f;
        qq = report(q, an, 0.25, "hole covered");
        CHECK(qq.boundary_loops == 1 && qq.domain_loops == 2 && (qq.invalid & GLPGP_QUADS_BAD_LOOPS));
        CHECK(qq.far_faces > 0);
        repaired_valid(q, an, 0.25, "  repaired");
        glpgp_quadmesh_destroy(&q);
    }

    glpgp_mesh_destroy(&sq);
    glpgp_mesh_destroy(&an);
    TEST_DONE();
}
