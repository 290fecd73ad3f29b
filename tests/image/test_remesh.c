/* test_remesh.c: remeshing a triangle mesh inside its boundary points
 * (glpgp_polygons_from_mesh, glpgp_mask_mesh on .obj / .msh, `glpgp mesh
 * MESH.obj`), the way out for CAD exports whose triangles are STL-like fans
 * of slivers:
 *  - the polygons of an annulus mesh: two loops, the hole clockwise inside
 *    the outer one, the mesh's area;
 *  - with Gmsh: a 96-gon fanned from one corner (angles down to 1.9 degrees)
 *    remeshed: the same boundary points and area, smallest angle >= 20
 *    degrees; an annulus .msh remeshed keeps its two loops and its area. */
#include "testutil.h"

#include <string.h>
#include <unistd.h>

#define PI_D 3.14159265358979323846

static double min_angle_deg(const glpgp_mesh *m)
{
    double amin;
    int nsliver;
    glpgp_mesh_angles(m, 0.0, &amin, &nsliver);
    return amin;
}

int main(void)
{
    /* polygons of an annulus: outer CCW, hole CW with the outer as parent */
    glpgp_mesh *ann = NULL;
    CHECK_OK(glpgp_mesh_generate("annulus", 2000, &ann));
    glpgp_polygons *P = NULL;
    if (ann) CHECK_OK(glpgp_polygons_from_mesh(ann, &P));
    if (P) {
        CHECK(P->n == 2 && P->nouter == 1 && P->nholes == 1);
        int outer = P->area[0] > 0 ? 0 : 1, hole = 1 - outer;
        CHECK(P->area[outer] > 0 && P->area[hole] < 0);
        CHECK(P->parent[hole] == outer && P->parent[outer] == -1);
        CHECK_CLOSE(P->total_area, ann->area, 0, 1e-12);
        CHECK(P->start[2] == ann->loop_start[2]);
        glpgp_polygons_destroy(&P);
    }
    if (!glpgp_have_gmsh()) {
        printf("remesh: skipped the Gmsh part (built without Gmsh)\n");
        glpgp_mesh_destroy(&ann);
        TEST_DONE();
    }

    char dir[] = "/tmp/glpgp_test_remesh.XXXXXX";
    if (!mkdtemp(dir)) return 1;
    char fan[512], annp[512];
    snprintf(fan, sizeof fan, "%s/fan.obj", dir);
    snprintf(annp, sizeof annp, "%s/annulus.msh", dir);

    /* a regular 96-gon of radius 1 fanned from corner 0: the STL export of
     * a disk face */
    enum { N = 96 };
    FILE *f = fopen(fan, "w");
    CHECK(f != NULL);
    if (f) {
        for (int i = 0; i < N; i++) fprintf(f, "v %.17g %.17g 0\n", cos(2 * PI_D * i / N), sin(2 * PI_D * i / N));
        for (int i = 1; i + 1 < N; i++) fprintf(f, "f 1 %d %d\n", i + 1, i + 2);
        fclose(f);
    }
    glpgp_mesh *in = NULL, *out = NULL;
    CHECK_OK(glpgp_mesh_read(fan, &in));
    double area96 = 0.5 * N * sin(2 * PI_D / N);
    if (in) {
        printf("fan: %d triangles, smallest angle %.2f degrees\n", in->nt, min_angle_deg(in));
        CHECK(min_angle_deg(in) < 2.0);
    }
    glpgp_mask_options mo;
    glpgp_mask_options_default(&mo);
    mo.mesh_size = 0.1;
    CHECK_OK(glpgp_mask_mesh(fan, &mo, &out, NULL));
    if (out) {
        double amin = min_angle_deg(out);
        printf("remeshed: %d vertices, %d triangles, smallest angle %.2f degrees, area %.12f (96-gon %.12f)\n", out->nv,
               out->nt, amin, out->area, area96);
        CHECK(amin >= 20.0);
        CHECK(out->nloops == 1 && out->nv > 300);
        CHECK_CLOSE(out->area, area96, 0, 1e-9);
        /* every corner of the 96-gon is still a boundary point */
        int found = 0;
        for (int i = 0; i < N; i++)
            for (int b = out->loop_start[0]; b < out->loop_start[1]; b++) {
                const double *p = out->xy + 2 * out->loop_vertices[b];
                if (fabs(p[0] - cos(2 * PI_D * i / N)) < 1e-12 && fabs(p[1] - sin(2 * PI_D * i / N)) < 1e-12) {
                    found++;
                    break;
                }
            }
        CHECK(found == N);
    }
    glpgp_mesh_destroy(&out);
    glpgp_mesh_destroy(&in);

    /* an annulus .msh: two loops and its area kept */
    if (ann) {
        CHECK_OK(glpgp_mesh_write(ann, annp));
        mo.mesh_size = 0.05;
        CHECK_OK(glpgp_mask_mesh(annp, &mo, &out, NULL));
        if (out) {
            CHECK(out->nloops == 2);
            CHECK_CLOSE(out->area, ann->area, 0, 1e-9);
            glpgp_mesh_destroy(&out);
        }
    }
    glpgp_mesh_destroy(&ann);
    remove(fan);
    remove(annp);
    rmdir(dir);
    TEST_DONE();
}
