/* image/mask_mesh.c: polygon-with-holes -> triangle mesh through the Gmsh C API
 * (gmshInitialize ... gmshFinalize around every call, terminal output off,
 * every ierr checked), and the mask image -> mesh pipeline (glpgp/image.h). */
#include "glpgp/image.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifdef GLPGP_HAVE_GMSH
#include <gmshc.h>
#endif

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

int glpgp_have_gmsh(void)
{
#ifdef GLPGP_HAVE_GMSH
    return 1;
#else
    return 0;
#endif
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

#ifndef GLPGP_HAVE_GMSH

glpgp_status glpgp_mesh_polygons(const glpgp_polygons *p, double mesh_size, int algorithm,
                                 glpgp_mesh **out)
{
    (void)p, (void)mesh_size, (void)algorithm;
    if (out) *out = NULL;
    return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED,
                      "cannot mesh the mask: glpgp was built without Gmsh (libgmsh-dev)");
}

#else

/* Record Gmsh's last error message (or a generic one) for step `what`. */
static glpgp_status gmsh_fail(const char *what, int ierr)
{
    char *msg = NULL;
    int e2 = 0;
    gmshLoggerGetLastError(&msg, &e2);
    glpgp_status st = GLPGP_FAIL(GLPGP_ERR_MESH, "Gmsh failed in %s (error %d)%s%s", what, ierr,
                                 (e2 == 0 && msg && *msg) ? ": " : "",
                                 (e2 == 0 && msg && *msg) ? msg : "");
    if (msg) gmshFree(msg);
    return st;
}

#define GMSH_DO(what, call)                                   \
    do {                                                      \
        ierr = 0;                                             \
        call;                                                 \
        if (ierr) {                                           \
            st = gmsh_fail(what, ierr);                       \
            goto fin;                                         \
        }                                                     \
    } while (0)

/* Add one polygon loop as points + lines + curve loop; returns its tag. */
static glpgp_status add_loop(const double *xy, int n, double hm, int *loop_tag)
{
    glpgp_status st = GLPGP_OK;
    int ierr = 0;
    int *pt = NULL, *ln = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)n, sizeof(int), &pt));
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n, sizeof(int), &ln), fin);
    for (int i = 0; i < n; i++) GMSH_DO("addPoint", pt[i] = gmshModelGeoAddPoint(xy[2 * i], xy[2 * i + 1], 0.0, hm, -1, &ierr));
    for (int i = 0; i < n; i++) GMSH_DO("addLine", ln[i] = gmshModelGeoAddLine(pt[i], pt[(i + 1) % n], -1, &ierr));
    GMSH_DO("addCurveLoop", *loop_tag = gmshModelGeoAddCurveLoop(ln, (size_t)n, -1, 0, &ierr));
fin:
    free(pt);
    free(ln);
    return st;
}

glpgp_status glpgp_mesh_polygons(const glpgp_polygons *p, double hm, int algorithm,
                                 glpgp_mesh **out)
{
    if (!p || !out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_mesh_polygons: NULL argument");
    *out = NULL;
    if (!(hm > 0) || !isfinite(hm)) return GLPGP_FAIL(GLPGP_ERR_ARG, "mesh size %g must be positive", hm);
    if (algorithm <= 0) algorithm = 6;
    glpgp_status st = GLPGP_OK;
    int ierr = 0;
    int *loops = NULL;
    size_t *ntags = NULL, *etags = NULL, *enodes = NULL;
    size_t ntags_n = 0, etags_n = 0, enodes_n = 0, coord_n = 0, par_n = 0;
    double *coord = NULL, *par = NULL;
    int *map = NULL, *tri = NULL;
    double *vxy = NULL;

    gmshInitialize(0, NULL, 0, &ierr);
    if (ierr) return GLPGP_FAIL(GLPGP_ERR_MESH, "cannot initialise Gmsh (error %d)", ierr);
    GMSH_DO("option General.Terminal", gmshOptionSetNumber("General.Terminal", 0, &ierr));
    GMSH_DO("option General.Verbosity", gmshOptionSetNumber("General.Verbosity", 1, &ierr));
    GMSH_DO("model add", gmshModelAdd("glpgp_mask", &ierr));
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)p->n + 1, sizeof(int), &loops), fin);
    for (int q = 0; q < p->n; q++) {
        if (!(p->area[q] > 0)) continue;
        int nl = 0;
        for (int pass = 0; pass < 2; pass++)
            for (int l = 0; l < p->n; l++) {
                if (pass == 0 ? l != q : p->parent[l] != q) continue;
                GLPGP_CHECK_GOTO(st, add_loop(p->xy + 2 * p->start[l], p->start[l + 1] - p->start[l], hm, &loops[nl]), fin);
                nl++;
            }
        GMSH_DO("addPlaneSurface", gmshModelGeoAddPlaneSurface(loops, (size_t)nl, -1, &ierr));
    }
    GMSH_DO("synchronize", gmshModelGeoSynchronize(&ierr));
    GMSH_DO("option Mesh.MeshSizeMax", gmshOptionSetNumber("Mesh.MeshSizeMax", hm, &ierr));
    GMSH_DO("option Mesh.MeshSizeFromCurvature", gmshOptionSetNumber("Mesh.MeshSizeFromCurvature", 0, &ierr));
    GMSH_DO("option Mesh.Algorithm", gmshOptionSetNumber("Mesh.Algorithm", algorithm, &ierr));
    GMSH_DO("mesh generate", gmshModelMeshGenerate(2, &ierr));
    GMSH_DO("getNodes", gmshModelMeshGetNodes(&ntags, &ntags_n, &coord, &coord_n, &par, &par_n, -1, -1, 0, 0, &ierr));
    GMSH_DO("getElementsByType", gmshModelMeshGetElementsByType(2, &etags, &etags_n, &enodes, &enodes_n, -1, 0, 1, &ierr));
    if (enodes_n < 3 || ntags_n < 3 || coord_n < 3 * ntags_n) {
        st = GLPGP_FAIL(GLPGP_ERR_MESH, "Gmsh produced no triangles (mesh size %g too large?)", hm);
        goto fin;
    }
    {
        size_t maxtag = 0;
        for (size_t i = 0; i < ntags_n; i++)
            if (ntags[i] > maxtag) maxtag = ntags[i];
        if (maxtag > (size_t)2147483000) {
            st = GLPGP_FAIL(GLPGP_ERR_MESH, "Gmsh node tags too large");
            goto fin;
        }
        size_t nt = enodes_n / 3;
        if (nt > (size_t)2147483000 / 3) {
            st = GLPGP_FAIL(GLPGP_ERR_MESH, "too many triangles (%zu)", nt);
            goto fin;
        }
        int *pos = NULL; /* node tag -> index into coord */
        GLPGP_CHECK_GOTO(st, glpgp_malloc(maxtag + 1, sizeof(int), &pos), fin);
        GLPGP_CHECK_GOTO(st, glpgp_malloc(maxtag + 1, sizeof(int), &map), fin_pos);
        for (size_t i = 0; i <= maxtag; i++) pos[i] = map[i] = -1;
        for (size_t i = 0; i < ntags_n; i++) pos[ntags[i]] = (int)i;
        GLPGP_CHECK_GOTO(st, glpgp_malloc(3 * nt, sizeof(int), &tri), fin_pos);
        GLPGP_CHECK_GOTO(st, glpgp_malloc(2 * ntags_n, sizeof(double), &vxy), fin_pos);
        int nv = 0;
        for (size_t k = 0; k < 3 * nt; k++) {
            size_t tag = enodes[k];
            if (tag > maxtag || pos[tag] < 0) {
                st = GLPGP_FAIL(GLPGP_ERR_MESH, "Gmsh triangle refers to unknown node %zu", tag);
                goto fin_pos;
            }
            if (map[tag] < 0) {
                map[tag] = nv;
                vxy[2 * nv] = coord[3 * (size_t)pos[tag]];
                vxy[2 * nv + 1] = coord[3 * (size_t)pos[tag] + 1];
                nv++;
            }
            tri[k] = map[tag];
        }
        GLPGP_CHECK_GOTO(st, glpgp_mesh_create(nv, vxy, (int)nt, tri, out), fin_pos);
    fin_pos:
        free(pos);
    }
fin:
    if (ntags) gmshFree(ntags);
    if (coord) gmshFree(coord);
    if (par) gmshFree(par);
    if (etags) gmshFree(etags);
    if (enodes) gmshFree(enodes);
    free(loops);
    free(map);
    free(tri);
    free(vxy);
    ierr = 0;
    gmshFinalize(&ierr);
    if (ierr && st == GLPGP_OK) {
        glpgp_mesh_destroy(out);
        st = GLPGP_FAIL(GLPGP_ERR_MESH, "Gmsh failed to finalise (error %d)", ierr);
    }
    return st;
}

#endif /* GLPGP_HAVE_GMSH */

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
    if (!glpgp_have_gmsh())
        return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED,
                          "cannot mesh '%s': glpgp was built without Gmsh (libgmsh-dev)", path);
    double t0 = now_s();
    glpgp_status st = GLPGP_OK;
    glpgp_image *im = NULL;
    float *v = NULL;
    glpgp_polygons *p = NULL;
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
