/* fuzz_contour.c: mask -> boundary polygons (image/contour.c: marching
 * squares, speck removal, orientation, nesting, the topology-preserving
 * Douglas-Peucker of glpgp_polygons_simplify) and, with GLPGP_FUZZ_GMSH=1 in
 * the environment, the polygons -> Gmsh -> glpgp mesh step of `glpgp mesh`
 * (glpgp_mesh_polygons: the polygon check, Gmsh in a child process; slow,
 * about 100 executions/s).
 * Input: byte 0 width (1..48), 1 height (1..48), 2 threshold (/255), 3 min
 * area, 4 tolerance, 5 flags (bit 0 invert, bit 1 pixel size 1e-6, bits 2-3
 * mesh size 0.5 / 1 / 2 / 4 px, bit 4 Delaunay), then the pixels (one byte
 * each, /255; missing ones are 0).
 * Properties: failures give one error line; accepted polygons have loops of
 * >= 3 points, outer loops counter-clockwise, holes clockwise inside an
 * outer loop, and pass glpgp_polygons_check at GLPGP_CONTOUR_MIN_DIST
 * pixels (no crossing, no contact) before and after a second, coarser
 * simplification; Gmsh never crashes on them. */
#include "fuzz_common.h"

#include "glpgp/image.h"

#include <math.h>

static void check_polygons(const glpgp_polygons *p, double px)
{
    FUZZ_ASSERT(p->n >= 1 && p->nouter >= 1 && p->nouter + p->nholes == p->n);
    for (int l = 0; l < p->n; l++) {
        FUZZ_ASSERT(p->start[l + 1] - p->start[l] >= 3);
        if (p->area[l] > 0)
            FUZZ_ASSERT(p->parent[l] == -1);
        else
            FUZZ_ASSERT(p->parent[l] >= 0 && p->parent[l] < p->n && p->area[p->parent[l]] > 0);
    }
    glpgp_status st = glpgp_polygons_check(p, GLPGP_CONTOUR_MIN_DIST * px);
    FUZZ_ASSERT(st == GLPGP_OK);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    glpgp_error_clear();
    if (size < 6) return 0;
    const int w = 1 + data[0] % 48, h = 1 + data[1] % 48;
    static const double min_areas[8] = {0, 0.25, 0.5, 1, 2, 4, 16, 64};
    static const double tols[8] = {0, 0.1, 0.5, 1, 2, 3, 5, 10};
    glpgp_contour_options o;
    glpgp_contour_options_default(&o);
    o.threshold = data[2] / 255.0;
    o.min_area = min_areas[data[3] % 8];
    o.tolerance = tols[data[4] % 8];
    o.invert = data[5] & 1;
    o.pixel_size = (data[5] & 2) ? 1e-6 : 1.0;
    float *v = calloc((size_t)w * (size_t)h, sizeof *v);
    if (!v) abort();
    for (size_t i = 0; i < (size_t)w * (size_t)h && 6 + i < size; i++) v[i] = data[6 + i] / 255.0f;
    glpgp_polygons *p = NULL;
    glpgp_status st = glpgp_contours(v, w, h, &o, &p);
    free(v);
    if (st != GLPGP_OK) {
        FUZZ_ASSERT(p == NULL);
        fuzz_check_error(st);
        return 0;
    }
    check_polygons(p, o.pixel_size);
    const double hm = o.pixel_size * (0.5 * (1 << ((data[5] >> 2) & 3)));
    st = glpgp_polygons_simplify(p, hm / 2.0, GLPGP_CONTOUR_MIN_DIST * o.pixel_size);
    FUZZ_ASSERT(st == GLPGP_OK);
    check_polygons(p, o.pixel_size);
    const char *gm = getenv("GLPGP_FUZZ_GMSH");
    if (gm && *gm == '1' && glpgp_have_gmsh()) {
        glpgp_mesh *m = NULL;
        st = glpgp_mesh_polygons(p, hm, (data[5] & 16) ? 5 : 6, &m);
        if (st != GLPGP_OK) {
            /* Gmsh may refuse a boundary, but must not die on a checked one */
            FUZZ_ASSERT(strstr(glpgp_error_message(), "Gmsh crashed") == NULL);
            FUZZ_ASSERT(strstr(glpgp_error_message(), "Gmsh failed (") == NULL);
        }
        fuzz_check_error(st);
        glpgp_mesh_destroy(&m);
    }
    glpgp_polygons_destroy(&p);
    return 0;
}
