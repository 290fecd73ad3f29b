/* image/gmsh_shim.c: the module glpgp_gmsh.so (with image/shim_glue.c), built
 * when CMake finds the Gmsh C API: polygons with holes -> triangles through
 * gmshc.h (gmshInitialize ... gmshFinalize around every call, terminal output
 * off, every ierr checked). glpgp_mesh_polygons (image/mask_mesh.c) dlopen's
 * it on first use (image/module.c) and builds the glpgp mesh from the arrays
 * returned here. Its one exported symbol glpgp_gmsh_module returns the
 * function table of image/module.h. */
#include "module.h"

#include <gmshc.h>

#include <stdlib.h>

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
static glpgp_status add_loop(const double *xy, const double *size, int n, double hm, int *loop_tag)
{
    glpgp_status st = GLPGP_OK;
    int ierr = 0;
    int *pt = NULL, *ln = NULL;
    GLPGP_CHECK(glpgp_malloc((size_t)n, sizeof(int), &pt));
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)n, sizeof(int), &ln), fin);
    for (int i = 0; i < n; i++) GMSH_DO("addPoint", pt[i] = gmshModelGeoAddPoint(xy[2 * i], xy[2 * i + 1], 0.0, size && size[i] > 0 ? size[i] : hm, -1, &ierr));
    for (int i = 0; i < n; i++) GMSH_DO("addLine", ln[i] = gmshModelGeoAddLine(pt[i], pt[(i + 1) % n], -1, &ierr));
    GMSH_DO("addCurveLoop", *loop_tag = gmshModelGeoAddCurveLoop(ln, (size_t)n, -1, 0, &ierr));
fin:
    free(pt);
    free(ln);
    return st;
}

/* glpgp_gmsh_api.mesh_polygons (image/module.h): p meshed by Gmsh, as
 * vertices *xy (2 nv) and triangles *tri (3 nt), both numbered from 0 in the
 * order the triangles first use them. */
static glpgp_status mesh_polygons(const glpgp_polygons *p, double hm, int algorithm, int *out_nv,
                                  double **out_xy, int *out_nt, int **out_tri)
{
    *out_xy = NULL;
    *out_tri = NULL;
    *out_nv = *out_nt = 0;
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
                GLPGP_CHECK_GOTO(st, add_loop(p->xy + 2 * p->start[l], p->size ? p->size + p->start[l] : NULL, p->start[l + 1] - p->start[l], hm, &loops[nl]), fin);
                nl++;
            }
        GMSH_DO("addPlaneSurface", gmshModelGeoAddPlaneSurface(loops, (size_t)nl, -1, &ierr));
    }
    GMSH_DO("synchronize", gmshModelGeoSynchronize(&ierr));
    double hmax = hm; /* graded: the largest point size */
    for (int i = 0; p->size && i < p->start[p->n]; i++)
        if (p->size[i] > hmax) hmax = p->size[i];
    GMSH_DO("option Mesh.MeshSizeMax", gmshOptionSetNumber("Mesh.MeshSizeMax", hmax, &ierr));
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
        *out_nv = nv;
        *out_nt = (int)nt;
        *out_xy = vxy;
        *out_tri = tri;
        vxy = NULL;
        tri = NULL;
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
    if (ierr && st == GLPGP_OK) st = GLPGP_FAIL(GLPGP_ERR_MESH, "Gmsh failed to finalise (error %d)", ierr);
    if (st != GLPGP_OK) {
        free(*out_xy);
        free(*out_tri);
        *out_xy = NULL;
        *out_tri = NULL;
        *out_nv = *out_nt = 0;
    }
    return st;
}

static const glpgp_gmsh_api gmsh_api = {GLPGP_MODULE_ABI, mesh_polygons};

GLPGP_MODULE_EXPORT const void *glpgp_gmsh_module(const glpgp_module_host *host);
GLPGP_MODULE_EXPORT const void *glpgp_gmsh_module(const glpgp_module_host *host)
{
    return glpgp_module_glue_init(host) ? &gmsh_api : NULL;
}
