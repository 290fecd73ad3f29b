/* test_image_render.c: the rasteriser (render.h) and image writing.
 * The square case: unit square, h = 0.1, z_u = exp(2 pi i x / h), z_v =
 * exp(2 pi i y / h) set at the vertices of a ~10000-vertex mesh (about 10
 * vertices per period), so theta_u = x / h exactly inside every triangle.
 *  - along a horizontal pixel row between two v-lines, the number of u-line
 *    crossings (runs of grid-line-coloured pixels) inside the domain is
 *    L/h - 1 = 9 (the lines at x = 0 and 1 are under the boundary stroke),
 *    i.e. L/h within +-1;
 *  - a result with z_u = (x - p) (one singular triangle, the one holding p):
 *    the pixel at p is red, a pixel far from p is not;
 *  - PNG/JPEG/EXR written and read back with OpenImageIO with the requested
 *    size (long side) and channels (RGBA, RGB for JPEG); transparent
 *    background: alpha 0 in a corner; no temporary file left;
 *  - every --image-kind renders; the comparison figure is two panels wide.
 * Skips (77) without OpenImageIO for the file checks only. */
#include "glpgp/image.h"
#include "glpgp/mesh.h"
#include "glpgp/solve.h"
#include "testutil.h"

#include <dirent.h>
#include <math.h>
#include <string.h>
#include <unistd.h>

#define TWO_PI 6.283185307179586

static glpgp_result *make_result(const glpgp_mesh *m)
{
    glpgp_result *r = calloc(1, sizeof *r);
    r->nv = m->nv;
    r->nt = m->nt;
    r->field = calloc(2 * (size_t)m->nv, sizeof(double));
    for (int k = 0; k < 2; k++) {
        r->osc[k].z = calloc(2 * (size_t)m->nv, sizeof(double));
        r->osc[k].singular = calloc((size_t)m->nt, 1);
    }
    for (int i = 0; i < m->nv; i++) r->field[2 * i] = 1.0;
    return r;
}

static void update_sing(const glpgp_mesh *m, glpgp_result *r)
{
    for (int k = 0; k < 2; k++)
        glpgp_singularities(m, r->osc[k].z, r->osc[k].singular, &r->osc[k].plus, &r->osc[k].minus);
}

/* pixel of physical point (x, y) for the default margin: same mapping as render.c */
static void to_pixel(const glpgp_mesh *m, const glpgp_render_options *o, double x, double y, int *i, int *j)
{
    int margin = o->size / 64;
    double span = fmax(m->bbox[2] - m->bbox[0], m->bbox[3] - m->bbox[1]);
    double scale = (o->size - 2 * margin) / span;
    *i = (int)floor((x - m->bbox[0]) * scale + margin);
    *j = (int)floor((m->bbox[3] - y) * scale + margin);
}

static int count_tmp(const char *dir)
{
    DIR *d = opendir(dir);
    int n = 0;
    if (!d) return -1;
    struct dirent *e;
    while ((e = readdir(d)))
        if (strstr(e->d_name, ".tmp")) n++;
    closedir(d);
    return n;
}

int main(void)
{
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("square", 10000, &m));
    if (!m) TEST_DONE();
    const double h = 0.1;
    glpgp_result *r = make_result(m);
    for (int i = 0; i < m->nv; i++) {
        double x = m->xy[2 * i], y = m->xy[2 * i + 1];
        r->osc[0].z[2 * i] = cos(TWO_PI * x / h), r->osc[0].z[2 * i + 1] = sin(TWO_PI * x / h);
        r->osc[1].z[2 * i] = cos(TWO_PI * y / h), r->osc[1].z[2 * i + 1] = sin(TWO_PI * y / h);
    }
    update_sing(m, r);
    CHECK(r->osc[0].plus + r->osc[0].minus == 0);

    glpgp_render_options o;
    glpgp_render_options_default(&o);
    o.size = 512;
    glpgp_image *im = NULL;
    CHECK_OK(glpgp_render(m, r, &o, &im));
    if (im) {
        CHECK(im->w == 512 && im->h == 512 && im->nc == 4);
        /* row at y = 0.55 (theta_v = 5.5: between two v-lines) */
        int i0, j0;
        to_pixel(m, &o, 0.0, 0.55, &i0, &j0);
        int runs = 0, in_run = 0, first = -1, last = -1;
        for (int i = 0; i < im->w; i++) {
            const float *p = im->px + 4 * ((size_t)j0 * im->w + i);
            /* u-line colour: clearly bluer than red, darker than the cells */
            int line = p[2] - p[0] > 0.15f && p[1] < 0.8f;
            if (line && !in_run) runs++, first = first < 0 ? i : first, last = i;
            in_run = line;
        }
        printf("square h = 0.1: %d u-line crossings on row %d (L/h = 10; first x px %d, last %d)\n", runs, j0,
               first, last);
        CHECK(abs(runs - 10) <= 1);
        CHECK(runs == 9);
        /* light cell shading: a cell center is lighter than a point near its corner */
        int ia, ja, ib, jb;
        to_pixel(m, &o, 0.55, 0.55, &ia, &ja);
        to_pixel(m, &o, 0.585, 0.585, &ib, &jb);
        const float *pa = im->px + 4 * ((size_t)ja * im->w + ia), *pb = im->px + 4 * ((size_t)jb * im->w + ib);
        printf("cell center %.3f, near corner %.3f\n", pa[0], pb[0]);
        CHECK(pa[0] > pb[0] + 0.03 && pb[0] > 0.8);
        glpgp_image_destroy(&im);
    }

    /* every kind renders: the requested size, a picture that is not one
     * colour, and a different picture from every other kind */
    double sums[GLPGP_IMAGE_THETA + 1][4];
    for (int k = 0; k <= GLPGP_IMAGE_THETA; k++) {
        glpgp_render_options ok = o;
        ok.kind = k;
        ok.size = 128;
        CHECK_OK(glpgp_render(m, r, &ok, &im));
        CHECK(im && im->w == 128 && im->h == 128); /* the unit square: square picture */
        int colours = 0;
        float first[4] = {im->px[0], im->px[1], im->px[2], im->px[3]};
        for (int c = 0; c < 4; c++) sums[k][c] = 0;
        for (size_t i = 0; i < (size_t)im->w * im->h; i++) {
            const float *p = im->px + 4 * i;
            int other = 0;
            for (int c = 0; c < 4; c++) {
                sums[k][c] += p[c] * (double)((i * 2654435761u) % 97 + 1); /* position-weighted */
                other |= fabsf(p[c] - first[c]) > 0.05f;
            }
            colours += other;
        }
        printf("kind %s: %d of %d pixels differ from the corner\n", glpgp_image_kind_name(k), colours, im->w * im->h);
        CHECK(colours > im->w * im->h / 20);
        for (int j = 0; j < k; j++) {
            double d = 0;
            for (int c = 0; c < 4; c++) d += fabs(sums[k][c] - sums[j][c]);
            CHECK(d > 1.0);
        }
        glpgp_image_destroy(&im);
        CHECK(glpgp_image_kind_parse(glpgp_image_kind_name(k)) == k);
    }
    CHECK(glpgp_image_kind_parse("nope") == -1);

    /* one singular triangle: z_u = (x - p) */
    const double px = 0.5037, py = 0.4971;
    glpgp_result *rs = make_result(m);
    for (int i = 0; i < m->nv; i++) {
        rs->osc[0].z[2 * i] = m->xy[2 * i] - px;
        rs->osc[0].z[2 * i + 1] = m->xy[2 * i + 1] - py;
        rs->osc[1].z[2 * i] = 1.0;
    }
    update_sing(m, rs);
    printf("z_u = x - p: singular triangles +%d -%d\n", rs->osc[0].plus, rs->osc[0].minus);
    CHECK(rs->osc[0].plus == 1 && rs->osc[0].minus == 0);
    CHECK_OK(glpgp_render(m, rs, &o, &im));
    if (im) {
        int i, j;
        to_pixel(m, &o, px, py, &i, &j);
        const float *p = im->px + 4 * ((size_t)j * im->w + i);
        printf("pixel at p (%d, %d): %.2f %.2f %.2f %.2f\n", i, j, p[0], p[1], p[2], p[3]);
        CHECK(p[0] > 0.8f && p[1] < 0.2f && p[2] < 0.2f && p[3] == 1.0f);
        to_pixel(m, &o, 0.2, 0.8, &i, &j);
        p = im->px + 4 * ((size_t)j * im->w + i);
        CHECK(!(p[0] > 0.8f && p[1] < 0.2f && p[2] < 0.2f));
        glpgp_image_destroy(&im);
    }

    /* comparison figure */
    const glpgp_result *two[2] = {rs, r};
    const char *labels[2] = {"Naive PGP", "GL-PGP"};
    CHECK_OK(glpgp_render_compare(m, two, labels, 2, &o, &im));
    if (im) {
        CHECK(im->w == 2 * 512 + 512 / 64);
        CHECK(im->h > 512);
        /* some dark caption pixels under the first panel */
        int dark = 0;
        for (int j = 512; j < im->h; j++)
            for (int i = 0; i < 512; i++) dark += im->px[4 * ((size_t)j * im->w + i)] < 0.2f;
        CHECK(dark > 50);
        glpgp_image_destroy(&im);
    }

    if (!glpgp_have_oiio()) {
        printf("file checks skipped: built without OpenImageIO\n");
    } else {
        char dir[] = "/tmp/glpgp_test_image_render.XXXXXX";
        CHECK(mkdtemp(dir) != NULL);
        static const char *const ext[] = {".png", ".jpg", ".exr", ".tif"};
        static const int want_nc[] = {4, 3, 4, 4};
        for (int e = 0; e < 4; e++) {
            char path[512];
            snprintf(path, sizeof path, "%s/out%s", dir, ext[e]);
            CHECK(glpgp_image_path_writable(path));
            glpgp_render_options ot = o;
            ot.size = 300;
            ot.transparent = e != 1;
            CHECK_OK(glpgp_render(m, r, &ot, &im));
            CHECK_OK(glpgp_image_write(path, im));
            glpgp_image_destroy(&im);
            glpgp_image *back = NULL;
            CHECK_OK(glpgp_image_read(path, &back));
            if (back) {
                printf("%s: %d x %d x %d\n", ext[e], back->w, back->h, back->nc);
                CHECK(back->w == 300 && back->h == 300 && back->nc == want_nc[e]);
                if (back->nc == 4) CHECK(back->px[3] == 0.0f); /* transparent corner */
                if (back->nc == 3) CHECK(back->px[0] > 0.95f); /* white corner */
                glpgp_image_destroy(&back);
            }
            remove(path);
        }
        CHECK(!glpgp_image_path_writable("x.unknownext"));
        /* unwritable destination: error, nothing left behind */
        char bad[600];
        snprintf(bad, sizeof bad, "%s/nodir/out.png", dir);
        CHECK_OK(glpgp_render(m, r, &o, &im));
        CHECK(glpgp_image_write(bad, im) == GLPGP_ERR_IO);
        glpgp_error_clear();
        glpgp_image_destroy(&im);
        CHECK(count_tmp(dir) == 0);
        rmdir(dir);
    }

    glpgp_result_destroy(&r);
    glpgp_result_destroy(&rs);
    glpgp_mesh_destroy(&m);
    TEST_DONE();
}
