/* image/mask_mesh.c: polygon-with-holes -> triangle mesh through the Gmsh
 * module (glpgp_gmsh.so, image/gmsh_shim.c, loaded on first use by
 * image/module.c), and the mask image -> mesh pipeline (glpgp/image.h). */
#include "glpgp/image.h"
#include "module.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void glpgp_mask_options_default(glpgp_mask_options *o)
{
    glpgp_contour_options_default(&o->contour);
    o->mesh_size = 0;
    o->quad_size = 0;
    o->algorithm = 6;
}

double glpgp_mask_default_mesh_size(const glpgp_polygons *p, double quad_size)
{
    double h = quad_size;
    if (!(h > 0)) {
        double b[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
        for (int i = 0; p && i < p->start[p->n]; i++) {
            double x = p->xy[2 * i], y = p->xy[2 * i + 1];
            if (x < b[0]) b[0] = x;
            if (y < b[1]) b[1] = y;
            if (x > b[2]) b[2] = x;
            if (y > b[3]) b[3] = y;
        }
        h = hypot(b[2] - b[0], b[3] - b[1]) / 20.0;
    }
    return h / 8.0;
}

glpgp_status glpgp_mesh_polygons(const glpgp_polygons *p, double hm, int algorithm,
                                 glpgp_mesh **out)
{
    if (!p || !out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mesh_polygons: NULL argument");
    *out = NULL;
    if (!(hm > 0) || !isfinite(hm)) return GLPGP_FAIL(GLPGP_ERR_ARG, "mesh size %g must be positive", hm);
    if (algorithm <= 0) algorithm = 6;
    const glpgp_gmsh_api *api;
    const char *why;
    glpgp_status st = glpgp_gmsh_module_get(&api, &why);
    if (st != GLPGP_OK) return GLPGP_FAIL(st, "cannot mesh the mask: %s", why);
    int nv = 0, nt = 0;
    double *xy = NULL;
    int *tri = NULL;
    GLPGP_CHECK(api->mesh_polygons(p, hm, algorithm, &nv, &xy, &nt, &tri));
    st = glpgp_mesh_create(nv, xy, nt, tri, out);
    if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
    free(xy);
    free(tri);
    return st;
}

/* Re-simplify every loop with a coarser tolerance (physical units) and
 * compact the arrays; loops left with fewer than 3 points are dropped. */
static glpgp_status resimplify(glpgp_polygons *p, double tol)
{
    int w = 0, nl = 0;
    for (int l = 0; l < p->n; l++) {
        int s = p->start[l], n = p->start[l + 1] - s;
        if (w != s) memmove(p->xy + 2 * w, p->xy + 2 * s, 2 * (size_t)n * sizeof(double));
        GLPGP_CHECK(glpgp_simplify_closed(p->xy + 2 * w, &n, tol));
        if (n < 3) continue;
        p->start[nl] = w;
        p->area[nl] = p->area[l];
        p->parent[nl] = p->parent[l];
        nl++;
        w += n;
        /* parents refer to old indices: fixed below */
    }
    if (nl != p->n) return GLPGP_FAIL(GLPGP_ERR_MESH, "a boundary loop vanished in simplification");
    p->start[nl] = w;
    for (int l = 0; l < nl; l++) {
        const double *xy = p->xy + 2 * p->start[l];
        int n = p->start[l + 1] - p->start[l];
        double a = 0;
        for (int i = 0; i < n; i++) {
            int j = (i + 1) % n;
            a += xy[2 * i] * xy[2 * j + 1] - xy[2 * j] * xy[2 * i + 1];
        }
        p->area[l] = 0.5 * a;
    }
    return GLPGP_OK;
}

glpgp_status glpgp_mask_mesh(const char *path, const glpgp_mask_options *opt, glpgp_mesh **out,
                             glpgp_mask_info *info)
{
    if (!path || !out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mask_mesh: NULL argument");
    *out = NULL;
    glpgp_mask_options o;
    if (opt)
        o = *opt;
    else
        glpgp_mask_options_default(&o);
    glpgp_mask_info inf;
    memset(&inf, 0, sizeof inf);
    /* fail before reading the image when Gmsh cannot be had */
    const glpgp_gmsh_api *api;
    const char *why;
    glpgp_status st = glpgp_gmsh_module_get(&api, &why);
    if (st != GLPGP_OK) return GLPGP_FAIL(st, "cannot mesh '%s': %s", path, why);
    double t0 = now_s();
    glpgp_image *im = NULL;
    float *v = NULL;
    glpgp_polygons *p = NULL;
    if (glpgp_is_poly_path(path)) { /* a polygon file: no image, no contours */
        GLPGP_CHECK(glpgp_polygons_read(path, &p));
        double t1 = now_s();
        inf.seconds_read = t1 - t0;
        double hm = o.mesh_size > 0 ? o.mesh_size : glpgp_mask_default_mesh_size(p, o.quad_size);
        inf.nouter = p->nouter;
        inf.nholes = p->nholes;
        inf.boundary_points = p->start[p->n];
        inf.polygon_area = p->total_area;
        inf.mesh_size = hm;
        st = glpgp_mesh_polygons(p, hm, o.algorithm, out);
        inf.seconds_mesh = now_s() - t1;
        if (st == GLPGP_OK && info) *info = inf;
        glpgp_polygons_destroy(&p);
        if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
        return st;
    }
    GLPGP_CHECK(glpgp_image_read(path, &im));
    inf.width = im->w;
    inf.height = im->h;
    GLPGP_CHECK_GOTO(st, glpgp_mask_values(im, &v), fin);
    glpgp_image_destroy(&im);
    double t1 = now_s();
    inf.seconds_read = t1 - t0;
    GLPGP_CHECK_GOTO(st, glpgp_contours(v, inf.width, inf.height, &o.contour, &p), fin);
    free(v);
    v = NULL;
    double hm = o.mesh_size > 0 ? o.mesh_size : glpgp_mask_default_mesh_size(p, o.quad_size);
    double tol_px = o.contour.tolerance;
    if (hm / o.contour.pixel_size / 20.0 > tol_px) {
        GLPGP_CHECK_GOTO(st, resimplify(p, hm / 20.0), fin);
    }
    inf.nouter = p->nouter;
    inf.nholes = p->nholes;
    inf.boundary_points = p->start[p->n];
    inf.polygon_area = 0;
    for (int l = 0; l < p->n; l++) inf.polygon_area += p->area[l];
    inf.mesh_size = hm;
    double t2 = now_s();
    inf.seconds_contour = t2 - t1;
    GLPGP_CHECK_GOTO(st, glpgp_mesh_polygons(p, hm, o.algorithm, out), fin);
    inf.seconds_mesh = now_s() - t2;
    if (info) *info = inf;
fin:
    glpgp_image_destroy(&im);
    free(v);
    glpgp_polygons_destroy(&p);
    return st;
}

int glpgp_is_poly_path(const char *path)
{
    size_t n = path ? strlen(path) : 0;
    if (n < 5) return 0;
    const char *e = path + n - 5;
    return e[0] == '.' && (e[1] | 32) == 'p' && (e[2] | 32) == 'o' && (e[3] | 32) == 'l' && (e[4] | 32) == 'y';
}
