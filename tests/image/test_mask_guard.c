/* test_mask_guard.c: what stands between a mask and Gmsh 4.8, which aborts
 * the whole process (std::terminate inside an OpenMP region: exit 134, no
 * message) on boundaries that cross or touch:
 *  - the mask that made `glpgp mesh` abort (a 12 x 18 binary mask, --simplify
 *    2 --min-area 0.5, written here as a PGM): Douglas-Peucker loop by loop
 *    (the old pipeline) makes its boundary cross itself (glpgp_polygons_check
 *    says so), glpgp_contours / glpgp_polygons_simplify keep the topology
 *    (the check passes), and glpgp_mask_mesh meshes it;
 *  - glpgp_polygons_check on hand-made crossings, touching loops, a hole
 *    1e-9 from its outer boundary, zero-length segments;
 *  - the Gmsh child process: GLPGP_TEST_GMSH_FAULT=abort|segv|exit|garbage
 *    gives GLPGP_ERR_MESH with one line ("Gmsh crashed (signal 6 ...") and
 *    the caller lives on; =hang with a 0.5 s limit gives GLPGP_ERR_LIMIT in
 *    well under 5 s; no child is left (waitpid: ECHILD);
 *  - units: the same square with a hole 1e-4 of its size from the boundary
 *    meshes alike at 1 and at 1e-6 physical units per pixel (Gmsh gets the
 *    polygons scaled to [0, 1]^2);
 *  - limits of glpgp_mask_mesh, refused before any real work: a 20000 x
 *    20000 PGM header (GLPGP_ERR_LIMIT from the header, no pixel read) and a
 *    mesh size that would make billions of triangles (estimate), each in
 *    well under a second.
 * Skips (77) without OpenImageIO or Gmsh. */
#include "testutil.h"

#include <errno.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* the 12 x 18 mask of the abort (1 = inside) */
static const char *const k_mask[18] = {
    "000000111011", "000100000000", "101000100101", "111111100011", "111010001111",
    "000011100010", "010110010011", "110011001100", "110001001010", "000001100011",
    "100111110110", "100011101101", "111000000011", "000000010110", "111101101101",
    "100101100001", "001101011101", "101111100010"};

static int one_line(const char *m) { return m[0] && !strchr(m, '\n'); }

/* polygons from a flat list: n loops, counts[l] points each */
static glpgp_polygons make_polys(double *xy, int *start, double *area, int *parent, int n,
                                 const int *counts)
{
    glpgp_polygons p;
    memset(&p, 0, sizeof p);
    start[0] = 0;
    for (int l = 0; l < n; l++) start[l + 1] = start[l] + counts[l];
    for (int l = 0; l < n; l++) {
        double a = 0;
        const double *q = xy + 2 * start[l];
        for (int i = 0; i < counts[l]; i++) {
            int j = (i + 1) % counts[l];
            a += q[2 * i] * q[2 * j + 1] - q[2 * j] * q[2 * i + 1];
        }
        area[l] = 0.5 * a;
        parent[l] = a > 0 ? -1 : 0;
        if (a > 0) p.nouter++; else p.nholes++;
        p.total_area += area[l];
    }
    p.n = n;
    p.start = start;
    p.xy = xy;
    p.area = area;
    p.parent = parent;
    return p;
}

static void check_fault(const char *fault, glpgp_status want, const char *needle)
{
    double xy[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    int start[2], parent[1], counts[1] = {4};
    double area[1];
    glpgp_polygons p = make_polys(xy, start, area, parent, 1, counts);
    setenv("GLPGP_TEST_GMSH_FAULT", fault, 1);
    glpgp_mesh *m = NULL;
    double t0 = now();
    glpgp_status st = glpgp_mesh_polygons_timeout(&p, 0.2, 0, 0.5, &m);
    double dt = now() - t0;
    unsetenv("GLPGP_TEST_GMSH_FAULT");
    const char *msg = glpgp_error_message();
    printf("fault %-8s -> %s (%.2f s): %s\n", fault, glpgp_status_name(st), dt, msg);
    CHECK(st == want);
    CHECK(m == NULL);
    CHECK(one_line(msg));
    CHECK(strstr(msg, needle) != NULL);
    CHECK(dt < 5.0);
    glpgp_error_clear();
    /* the child was reaped */
    errno = 0;
    CHECK(waitpid(-1, NULL, WNOHANG) == -1 && errno == ECHILD);
}

/* No timeout given (glpgp_mesh_polygons, and a timeout of 0): a hanging
 * child is still stopped, at the default bound (GLPGP_TEST_GMSH_TIMEOUT
 * stands in for GLPGP_GMSH_DEFAULT_TIMEOUT's hour), and the option struct's
 * default is that bound. */
static void check_default_bound(void)
{
    glpgp_mask_options mo;
    glpgp_mask_options_default(&mo);
    CHECK(mo.timeout == GLPGP_GMSH_DEFAULT_TIMEOUT && mo.timeout > 0);
    double xy[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    int start[2], parent[1], counts[1] = {4};
    double area[1];
    glpgp_polygons p = make_polys(xy, start, area, parent, 1, counts);
    setenv("GLPGP_TEST_GMSH_FAULT", "hang", 1);
    setenv("GLPGP_TEST_GMSH_TIMEOUT", "0.4", 1);
    for (int k = 0; k < 2; k++) {
        glpgp_mesh *m = NULL;
        double t0 = now();
        glpgp_status st = k ? glpgp_mesh_polygons_timeout(&p, 0.2, 0, 0.0, &m) : glpgp_mesh_polygons(&p, 0.2, 0, &m);
        double dt = now() - t0;
        printf("hang, no timeout given (%s) -> %s (%.2f s): %s\n", k ? "timeout 0" : "glpgp_mesh_polygons",
               glpgp_status_name(st), dt, glpgp_error_message());
        CHECK(st == GLPGP_ERR_LIMIT && m == NULL && dt < 5.0);
        CHECK(strstr(glpgp_error_message(), "time limit of 0.4 s") != NULL);
        glpgp_error_clear();
    }
    setenv("GLPGP_TEST_GMSH_TIMEOUT", "-1", 1); /* malformed: one clear error, no child */
    glpgp_mesh *m = NULL;
    CHECK(glpgp_mesh_polygons(&p, 0.2, 0, &m) == GLPGP_ERR_ARG && m == NULL);
    CHECK(strstr(glpgp_error_message(), "GLPGP_TEST_GMSH_TIMEOUT") != NULL);
    glpgp_error_clear();
    unsetenv("GLPGP_TEST_GMSH_TIMEOUT");
    unsetenv("GLPGP_TEST_GMSH_FAULT");
}

int main(void)
{
    glpgp_error_clear();
    if (glpgp_oiio_load() != GLPGP_OK || glpgp_gmsh_load() != GLPGP_OK) {
        printf("skipped: %s\n", glpgp_error_message());
        return 77;
    }
    char dir[] = "/tmp/glpgp_mask_guard.XXXXXX";
    if (!mkdtemp(dir)) return 1;
    char pgm[256], big[256];
    snprintf(pgm, sizeof pgm, "%s/abort.pgm", dir);
    snprintf(big, sizeof big, "%s/big.pgm", dir);

    /* ---- the mask that made Gmsh abort ------------------------------------ */
    FILE *f = fopen(pgm, "w");
    fprintf(f, "P2\n12 18\n255\n");
    for (int j = 0; j < 18; j++)
        for (int i = 0; i < 12; i++) fprintf(f, "%d%c", k_mask[j][i] == '1' ? 255 : 0, i == 11 ? '\n' : ' ');
    fclose(f);
    float v[12 * 18];
    for (int j = 0; j < 18; j++)
        for (int i = 0; i < 12; i++) v[j * 12 + i] = k_mask[j][i] == '1' ? 1.0f : 0.0f;
    glpgp_contour_options co;
    glpgp_contour_options_default(&co);
    co.min_area = 0.5;
    co.tolerance = 0; /* raw marching squares */
    glpgp_polygons *P = NULL;
    CHECK_OK(glpgp_contours(v, 12, 18, &co, &P));
    if (P) {
        CHECK_OK(glpgp_polygons_check(P, GLPGP_CONTOUR_MIN_DIST));
        /* the old way: each loop on its own, 2 px */
        for (int l = 0; l < P->n; l++) {
            int n = P->start[l + 1] - P->start[l];
            double *xy = malloc(2 * (size_t)n * sizeof *xy);
            memcpy(xy, P->xy + 2 * P->start[l], 2 * (size_t)n * sizeof *xy);
            CHECK_OK(glpgp_simplify_closed(xy, &n, 2.0));
            glpgp_polygons one = *P;
            int st1[2] = {0, n};
            double a1 = P->area[l];
            int p1 = -1;
            one.n = 1, one.start = st1, one.xy = xy, one.area = &a1, one.parent = &p1;
            if (n >= 3 && glpgp_polygons_check(&one, GLPGP_CONTOUR_MIN_DIST) != GLPGP_OK) {
                printf("loop %d simplified alone: %s\n", l, glpgp_error_message());
                co.invert = -1; /* remember: seen */
            }
            glpgp_error_clear();
            free(xy);
        }
        CHECK(co.invert == -1); /* the old simplification did cross itself */
        co.invert = 0;
        CHECK_OK(glpgp_polygons_simplify(P, 2.0, GLPGP_CONTOUR_MIN_DIST));
        CHECK_OK(glpgp_polygons_check(P, GLPGP_CONTOUR_MIN_DIST));
        glpgp_polygons_destroy(&P);
    }
    co.tolerance = 2.0;
    CHECK_OK(glpgp_contours(v, 12, 18, &co, &P));
    if (P) CHECK_OK(glpgp_polygons_check(P, GLPGP_CONTOUR_MIN_DIST));
    glpgp_polygons_destroy(&P);
    glpgp_mask_options mo;
    glpgp_mask_options_default(&mo);
    mo.contour.min_area = 0.5;
    mo.contour.tolerance = 2.0;
    for (int alg = 5; alg <= 6; alg++) {
        mo.algorithm = alg;
        glpgp_mesh *m = NULL;
        glpgp_mask_info inf;
        CHECK_OK(glpgp_mask_mesh(pgm, &mo, &m, &inf));
        if (m) printf("abort mask, algorithm %d: %d vertices, %d triangles, %d loops\n", alg, m->nv, m->nt,
                      inf.nouter + inf.nholes);
        glpgp_mesh_destroy(&m);
    }

    /* ---- glpgp_polygons_check ------------------------------------------- */
    {
        double xy[16];
        int start[3], parent[2];
        double area[2];
        /* bow tie */
        double bow[8] = {0, 0, 1, 1, 1, 0, 0, 1};
        int c4[1] = {4};
        memcpy(xy, bow, sizeof bow);
        glpgp_polygons p = make_polys(xy, start, area, parent, 1, c4);
        CHECK(glpgp_polygons_check(&p, 1e-9) == GLPGP_ERR_MESH);
        printf("bow tie: %s\n", glpgp_error_message());
        CHECK(strstr(glpgp_error_message(), "crosses") && strstr(glpgp_error_message(), "(0.5, 0.5)"));
        glpgp_error_clear();
        /* square with a hole 1e-9 above its bottom edge, then 0.1 */
        int c44[2] = {4, 4};
        for (int k = 0; k < 2; k++) {
            double d = k == 0 ? 1e-9 : 0.1;
            double sq[16] = {0, 0, 2, 0, 2, 2, 0, 2, 0.5, d, 0.5, 1, 1.5, 1, 1.5, d};
            memcpy(xy, sq, sizeof sq);
            p = make_polys(xy, start, area, parent, 2, c44);
            glpgp_status st = glpgp_polygons_check(&p, 1e-6);
            CHECK(st == (k == 0 ? GLPGP_ERR_MESH : GLPGP_OK));
            if (k == 0) {
                printf("hole 1e-9 from the boundary: %s\n", glpgp_error_message());
                CHECK(strstr(glpgp_error_message(), "touches"));
                glpgp_mesh *m = NULL;
                CHECK(glpgp_mesh_polygons(&p, 0.1, 0, &m) == GLPGP_ERR_MESH && !m);
            }
            glpgp_error_clear();
        }
        /* duplicate point (zero-length segment) */
        double dup[8] = {0, 0, 1, 0, 1, 0, 0, 1};
        memcpy(xy, dup, sizeof dup);
        p = make_polys(xy, start, area, parent, 1, c4);
        CHECK(glpgp_polygons_check(&p, 1e-9) == GLPGP_ERR_MESH);
        glpgp_error_clear();
    }

    /* ---- the Gmsh child: crashes, garbage, hangs ------------------------------ */
    check_default_bound();
    check_fault("abort", GLPGP_ERR_MESH, "Gmsh crashed (signal 6");
    check_fault("segv", GLPGP_ERR_MESH, "Gmsh crashed (signal 11");
    check_fault("exit", GLPGP_ERR_MESH, "exited with status 7");
    check_fault("garbage", GLPGP_ERR_MESH, "malformed reply");
    check_fault("hang", GLPGP_ERR_LIMIT, "time limit of 0.5 s");

    /* ---- units do not matter --------------------------------------------------- */
    {
        int nv[2] = {0, 0};
        for (int k = 0; k < 2; k++) {
            double s = k == 0 ? 1.0 : 1e-6;
            double sq[16] = {0, 0, 2, 0, 2, 2, 0, 2, 0.5, 2e-4, 0.5, 1, 1.5, 1, 1.5, 2e-4};
            for (int i = 0; i < 16; i++) sq[i] *= s;
            int start[3], parent[2], c44[2] = {4, 4};
            double area[2];
            glpgp_polygons p = make_polys(sq, start, area, parent, 2, c44);
            glpgp_mesh *m = NULL;
            CHECK_OK(glpgp_mesh_polygons(&p, 0.2 * s, 0, &m));
            if (m) nv[k] = m->nv;
            glpgp_mesh_destroy(&m);
        }
        printf("hole 1e-4 from the boundary: %d vertices at 1 unit/px, %d at 1e-6\n", nv[0], nv[1]);
        CHECK(nv[0] > 0 && nv[0] == nv[1]);
    }

    /* ---- limits before work ------------------------------------------------------ */
    f = fopen(big, "wb");
    fprintf(f, "P5\n20000 20000\n255\n");
    for (int i = 0; i < 1000; i++) fputc(0, f);
    fclose(f);
    double t0 = now();
    glpgp_mesh *m = NULL;
    glpgp_status st = glpgp_mask_mesh(big, NULL, &m, NULL);
    double dt = now() - t0;
    printf("20000 x 20000 header: %s (%.3f s): %s\n", glpgp_status_name(st), dt, glpgp_error_message());
    CHECK(st == GLPGP_ERR_LIMIT && !m && strstr(glpgp_error_message(), "400000000 pixels"));
    CHECK(dt < 5.0);
    glpgp_error_clear();
    glpgp_image *im = NULL;
    CHECK(glpgp_image_read_limited(big, 1000, &im) == GLPGP_ERR_LIMIT && !im);
    glpgp_error_clear();
    glpgp_mask_options_default(&mo);
    mo.mesh_size = 1e-4;
    t0 = now();
    st = glpgp_mask_mesh(pgm, &mo, &m, NULL);
    dt = now() - t0;
    printf("mesh size 1e-4 px: %s (%.3f s): %s\n", glpgp_status_name(st), dt, glpgp_error_message());
    CHECK(st == GLPGP_ERR_LIMIT && !m && strstr(glpgp_error_message(), "triangles"));
    CHECK(strstr(glpgp_error_message(), "abort.pgm") != NULL);
    CHECK(dt < 5.0);
    glpgp_error_clear();
    mo.mesh_size = 0.5;
    mo.max_triangles = 100; /* about 3.5 x 107 / 0.25 = 1500 */
    CHECK(glpgp_mask_mesh(pgm, &mo, &m, NULL) == GLPGP_ERR_LIMIT && !m);
    glpgp_error_clear();

    remove(pgm);
    remove(big);
    rmdir(dir);
    TEST_DONE();
}
