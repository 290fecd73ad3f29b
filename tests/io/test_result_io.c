/* test_result_io.c: a result written by glpgp_write_vtk reads back with
 * glpgp_read_result_vtk (same mesh, z, field, singularities); a VTK file
 * without oscillators and a missing file are rejected with clear errors. */
#include "glpgp/io.h"
#include "glpgp/io.h"
#include "testutil.h"

#include <string.h>
#include <unistd.h>

int main(void)
{
    char dir[] = "/tmp/glpgp_rio_XXXXXX";
    if (!mkdtemp(dir)) return 1;
    char path[256], bad[256];
    snprintf(path, sizeof path, "%s/r.vtk", dir);
    snprintf(bad, sizeof bad, "%s/bad.vtk", dir);
    glpgp_mesh *m = NULL;
    CHECK_OK(glpgp_mesh_generate("disk", 3000, &m));
    glpgp_backend *b = NULL;
    CHECK_OK(glpgp_backend_create_reference(&b));
    glpgp_options o;
    glpgp_options_default(&o);
    o.size = 0.25;
    o.newton_max = 10;
    glpgp_result *r = NULL;
    CHECK_OK(glpgp_solve(m, b, &o, &r));
    CHECK_OK(glpgp_write_vtk(m, r, path));
    glpgp_mesh *m2 = NULL;
    glpgp_result *r2 = NULL;
    CHECK_OK(glpgp_read_result_vtk(path, &m2, &r2));
    if (m2 && r2) {
        CHECK(m2->nv == m->nv && m2->nt == m->nt);
        CHECK_CLOSE(r2->size, 0.25, 1e-9, 0);
        for (int i = 0; i < 2 * m->nv; i++) {
            CHECK(m2->xy[i] == m->xy[i]);
            CHECK(r2->osc[0].z[i] == r->osc[0].z[i]);
            CHECK(r2->osc[1].z[i] == r->osc[1].z[i]);
            CHECK(r2->field[i] == r->field[i]);
        }
        for (int k = 0; k < 2; k++) {
            CHECK(r2->osc[k].plus == r->osc[k].plus && r2->osc[k].minus == r->osc[k].minus);
            CHECK(r2->osc[k].n_dirichlet == r->osc[k].n_dirichlet);
            CHECK(r2->osc[k].zabs_median == r->osc[k].zabs_median);
        }
    }
    /* geometry only: no oscillators */
    FILE *f = fopen(bad, "w");
    fprintf(f, "# vtk DataFile Version 3.0\nmesh\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 double\n"
               "0 0 0\n1 0 0\n0 1 0\nCELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n");
    fclose(f);
    glpgp_mesh *m3 = NULL;
    glpgp_result *r3 = NULL;
    glpgp_status st = glpgp_read_result_vtk(bad, &m3, &r3);
    CHECK(st == GLPGP_ERR_FORMAT && strstr(glpgp_error_message(), "without oscillators"));
    CHECK(m3 == NULL && r3 == NULL);
    glpgp_error_clear();
    CHECK(glpgp_read_result_vtk("/nonexistent/x.vtk", &m3, &r3) == GLPGP_ERR_IO);
    glpgp_error_clear();
    unlink(path);
    unlink(bad);
    rmdir(dir);
    glpgp_result_destroy(&r);
    glpgp_result_destroy(&r2);
    glpgp_mesh_destroy(&m);
    glpgp_mesh_destroy(&m2);
    glpgp_backend_destroy(&b);
    TEST_DONE();
}
