/* test_image_mask.c: mask image -> mesh. Masks are generated here (4x4
 * supersampled coverage, so anti-aliased) and written with OpenImageIO in
 * several formats (8-bit grey PNG, RGBA PNG with the shape in alpha, half
 * EXR), then read back and meshed with Gmsh through glpgp_mask_mesh:
 *   disk, annulus, L shape, square with three holes, on [0, 2]^2 at 200 x 200
 *   pixels (pixel size 0.01), mesh size 0.04.
 * Checks: hole count exact; polygon area and mesh area within 0.5 % of the
 * analytic area (plus half a pixel of perimeter for corners); boundary loops
 * of the mesh = 1 + holes; the mesh passed glpgp_mesh_create validation
 * (glpgp_mask_mesh builds it with it) and every triangle is CCW; bad images
 * (unreadable, empty, all inside) fail with GLPGP_ERR_IO / GLPGP_ERR_ARG.
 * Also: Douglas-Peucker keeps a square's corners, and the contour of a
 * binary mask touching the image border closes half a pixel beyond the
 * border pixel centers (exact area without simplification).
 * Skips (77) in builds without OpenImageIO or Gmsh. */
#include "glpgp/image.h"
#include "testutil.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

#define PI 3.14159265358979323846
#define N 200
#define PX 0.01

typedef int (*inside_fn)(double x, double y);

static int in_disk(double x, double y) { return hypot(x - 1, y - 1) < 0.7; }
static int in_annulus(double x, double y)
{
    double r = hypot(x - 1, y - 1);
    return r < 0.8 && r > 0.35;
}
static int in_l(double x, double y)
{
    return x > 0.2 && x < 1.8 && y > 0.2 && y < 1.8 && !(x > 1.0 && y > 1.0);
}
static int in_holes(double x, double y)
{
    if (!(x > 0.2 && x < 1.8 && y > 0.2 && y < 1.8)) return 0;
    if (hypot(x - 0.6, y - 0.6) < 0.2 || hypot(x - 1.4, y - 0.6) < 0.2 || hypot(x - 1.0, y - 1.4) < 0.2)
        return 0;
    return 1;
}

/* Coverage of pixel (i, j) (row j from the top, y up) */
static double coverage(inside_fn f, int i, int j)
{
    int c = 0;
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++) {
            double x = (i + (a + 0.5) / 4) * PX, y = (N - j - (b + 0.5) / 4) * PX;
            c += f(x, y);
        }
    return c / 16.0;
}

/* mode 0: grey, 1: RGBA with the shape in alpha (colour constant), */
static int write_mask(const char *path, inside_fn f, int mode)
{
    glpgp_image *im = NULL;
    int nc = mode == 1 ? 4 : 1;
    if (glpgp_image_create(N, N, nc, &im) != GLPGP_OK) return 0;
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            float *p = im->px + (size_t)nc * ((size_t)j * N + (size_t)i);
            double cv = coverage(f, i, j);
            if (mode == 1) {
                p[0] = 0.2f, p[1] = 0.3f, p[2] = 0.4f, p[3] = (float)cv;
            } else {
                p[0] = (float)cv;
            }
        }
    glpgp_status st = glpgp_image_write(path, im);
    glpgp_image_destroy(&im);
    if (st != GLPGP_OK) {
        fprintf(stderr, "write %s: %s\n", path, glpgp_error_message());
        glpgp_error_clear();
        return 0;
    }
    return 1;
}

static void check_case(const char *name, const char *path, inside_fn f, int mode, double area,
                       double perimeter, int holes)
{
    CHECK(write_mask(path, f, mode));
    glpgp_mask_options o;
    glpgp_mask_options_default(&o);
    o.contour.pixel_size = PX;
    o.mesh_size = 0.04;
    glpgp_mesh *m = NULL;
    glpgp_mask_info inf;
    glpgp_status st = glpgp_mask_mesh(path, &o, &m, &inf);
    if (st != GLPGP_OK) {
        fprintf(stderr, "%s: glpgp_mask_mesh failed: %s\n", name, glpgp_error_message());
        glpgp_error_clear();
        tu_failures++;
        return;
    }
    /* tolerance: 0.5 % of the area plus a quarter pixel along the perimeter */
    double tol = 0.005 * area + 0.25 * PX * perimeter;
    printf("%-8s holes %d (want %d), polygon area %.5f, mesh area %.5f, analytic %.5f (tol %.4f), "
           "%d vertices, %.3f s gmsh\n",
           name, inf.nholes, holes, inf.polygon_area, m->area, area, tol, m->nv, inf.seconds_mesh);
    CHECK(inf.nholes == holes);
    CHECK(inf.nouter == 1);
    CHECK(m->nloops == 1 + holes);
    CHECK_CLOSE(inf.polygon_area, area, tol, 0);
    CHECK_CLOSE(m->area, area, tol, 0);
    CHECK(m->nv > 500);
    /* every triangle CCW and in the image box */
    int bad = 0;
    for (int t = 0; t < m->nt; t++) {
        const int *v = m->tri + 3 * t;
        double ax = m->xy[2 * v[0]], ay = m->xy[2 * v[0] + 1];
        double cr = (m->xy[2 * v[1]] - ax) * (m->xy[2 * v[2] + 1] - ay) -
                    (m->xy[2 * v[2]] - ax) * (m->xy[2 * v[1] + 1] - ay);
        if (!(cr > 0)) bad++;
    }
    CHECK(bad == 0);
    CHECK(m->bbox[0] >= 0 && m->bbox[1] >= 0 && m->bbox[2] <= N * PX && m->bbox[3] <= N * PX);
    glpgp_mesh_destroy(&m);
}

static void check_bad(const char *what, const char *path, glpgp_status want, const char *needle)
{
    glpgp_mesh *m = NULL;
    glpgp_status st = glpgp_mask_mesh(path, NULL, &m, NULL);
    const char *msg = glpgp_error_message();
    printf("%s -> %s: %.200s\n", what, glpgp_status_name(st), msg);
    CHECK(st == want);
    CHECK(m == NULL);
    CHECK(strstr(msg, needle) != NULL);
    glpgp_error_clear();
}

int main(void)
{
    if (!glpgp_have_oiio() || !glpgp_have_gmsh()) {
        printf("skipped: built without OpenImageIO or Gmsh\n");
        return 77;
    }
    char dir[] = "/tmp/glpgp_test_image_mask.XXXXXX";
    if (!mkdtemp(dir)) return 1;
    char p[4][512];
    snprintf(p[0], sizeof p[0], "%s/disk.png", dir);
    snprintf(p[1], sizeof p[1], "%s/annulus.exr", dir);
    snprintf(p[2], sizeof p[2], "%s/lshape.png", dir);
    snprintf(p[3], sizeof p[3], "%s/holes.png", dir);

    check_case("disk", p[0], in_disk, 0, PI * 0.49, 2 * PI * 0.7, 0);
    check_case("annulus", p[1], in_annulus, 0, PI * (0.64 - 0.35 * 0.35), 2 * PI * 1.15, 1);
    check_case("L", p[2], in_l, 1, 1.6 * 1.6 - 0.8 * 0.8, 6.4, 0);
    check_case("holes", p[3], in_holes, 0, 1.6 * 1.6 - 3 * PI * 0.04, 6.4 + 3 * 2 * PI * 0.2, 3);

    /* bad images */
    char bad[512], empty[512], full[512];
    snprintf(bad, sizeof bad, "%s/garbage.png", dir);
    FILE *f = fopen(bad, "wb");
    CHECK(f != NULL);
    if (f) {
        fputs("this is not a png\n", f);
        fclose(f);
    }
    check_bad("garbage", bad, GLPGP_ERR_IO, "cannot read image");
    snprintf(empty, sizeof empty, "%s/missing.png", dir);
    check_bad("missing", empty, GLPGP_ERR_IO, "cannot read image");
    glpgp_image *im = NULL;
    CHECK_OK(glpgp_image_create(32, 24, 1, &im));
    snprintf(empty, sizeof empty, "%s/empty.png", dir);
    CHECK_OK(glpgp_image_write(empty, im));
    check_bad("empty", empty, GLPGP_ERR_ARG, "empty mask");
    for (int i = 0; i < 32 * 24; i++) im->px[i] = 1.0f;
    snprintf(full, sizeof full, "%s/full.png", dir);
    CHECK_OK(glpgp_image_write(full, im));
    check_bad("full", full, GLPGP_ERR_ARG, "every pixel");
    /* only a speck */
    for (int i = 0; i < 32 * 24; i++) im->px[i] = 0.0f;
    im->px[10 * 32 + 10] = 1.0f;
    CHECK_OK(glpgp_image_write(full, im));
    check_bad("speck", full, GLPGP_ERR_ARG, "only specks");

    /* a mask touching the border: closed half a pixel beyond the border */
    for (int j = 0; j < 24; j++)
        for (int i = 0; i < 32; i++) im->px[j * 32 + i] = i < 16 ? 1.0f : 0.0f;
    glpgp_polygons *P = NULL;
    glpgp_contour_options co;
    glpgp_contour_options_default(&co);
    co.tolerance = 0; /* exact marching-squares polygon */
    CHECK_OK(glpgp_contours(im->px, 32, 24, &co, &P));
    if (P) {
        /* x from 0 to 16 (the crossing between columns 15 and 16), y from 0
         * to 24, minus four corner chamfers of 1/8 pixel^2 */
        printf("border mask: %d loop(s), area %.3f (want 383.5), %d points\n", P->n, P->total_area,
               P->start[P->n]);
        CHECK(P->n == 1);
        CHECK_CLOSE(P->total_area, 383.5, 1e-9, 0);
        CHECK(P->start[P->n] == 80);
        glpgp_polygons_destroy(&P);
    }
    /* default simplification (0.5 px): area within 0.5 px x perimeter, few points */
    CHECK_OK(glpgp_contours(im->px, 32, 24, NULL, &P));
    if (P) {
        CHECK(P->total_area <= 384.0 && P->total_area >= 384.0 - 0.5 * 80);
        CHECK(P->start[P->n] <= 8);
        glpgp_polygons_destroy(&P);
    }
    glpgp_image_destroy(&im);

    /* Douglas-Peucker on a densely sampled square keeps exactly the corners */
    double sq[2 * 40];
    int n = 0;
    for (int s = 0; s < 4; s++)
        for (int k = 0; k < 10; k++) {
            double t = k / 10.0;
            double x = s == 0 ? t : s == 1 ? 1 : s == 2 ? 1 - t : 0;
            double y = s == 0 ? 0 : s == 1 ? t : s == 2 ? 1 : 1 - t;
            sq[2 * n] = x, sq[2 * n + 1] = y, n++;
        }
    CHECK_OK(glpgp_simplify_closed(sq, &n, 1e-6));
    CHECK(n == 4);

    for (int k = 0; k < 4; k++) remove(p[k]);
    remove(bad);
    remove(empty);
    remove(full);
    rmdir(dir);
    TEST_DONE();
}
