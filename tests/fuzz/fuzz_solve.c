/* fuzz_solve.c: a small whole solve on the reference backend: the input is
 * an OBJ mesh (read by glpgp_mesh_read, so everything the validation lets
 * through reaches the solver) after one option byte; meshes of more than 300
 * vertices are skipped. Byte 0: bit 0 method (gl / pgp), bit 1 energy
 * (p1 / transport), bits 2-3 Newton Hessian (mixed / projected / paper),
 * bit 4 field (boundary / radial), bit 5 init (naive / one), bits 6-7 size
 * (default h, 2.5, 6 or 40 mean edges). Newton is capped at 3 steps per
 * level and CG at 200 iterations, so an execution stays in milliseconds.
 * Then the quad extraction of the result. Properties: failures give one
 * error line; a result has finite z, |z| statistics in [0, inf), and
 * singularity counts >= 0. */
#include "fuzz_common.h"

#include "glpgp/backends.h"
#include "glpgp/io.h"
#include "glpgp/quads.h"
#include "glpgp/solve.h"

#include <math.h>

static glpgp_backend *g_ref;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    glpgp_error_clear();
    if (size < 1) return 0;
    if (!g_ref && glpgp_backend_create_reference(&g_ref) != GLPGP_OK) abort();
    const char *path = fuzz_write_file(0, ".obj", data + 1, size - 1);
    glpgp_mesh *m = NULL;
    glpgp_status st = glpgp_mesh_read(path, &m);
    if (st != GLPGP_OK || m->nv > 300) {
        fuzz_check_error(st);
        glpgp_mesh_destroy(&m);
        return 0;
    }
    const int f = data[0];
    glpgp_options o;
    glpgp_options_default(&o);
    o.method = (f & 1) ? GLPGP_METHOD_PGP : GLPGP_METHOD_GL;
    o.energy = (f & 2) ? GLPGP_ELEM_TRANSPORT : GLPGP_ELEM_P1;
    static const int hess[4] = {GLPGP_HESS_MIXED, GLPGP_HESS_PROJECTED, GLPGP_HESS_PAPER, GLPGP_HESS_MIXED};
    o.hess = hess[(f >> 2) & 3];
    o.field = (f & 16) ? GLPGP_FIELD_RADIAL : GLPGP_FIELD_BOUNDARY;
    o.init = (f & 32) ? GLPGP_INIT_ONE : GLPGP_INIT_NAIVE;
    static const double edges[4] = {0, 2.5, 6, 40};
    o.size = edges[(f >> 6) & 3] * m->mean_edge;
    o.newton_max = 3;
    o.cg_max = 200;
    glpgp_result *r = NULL;
    st = glpgp_options_check_mesh(&o, m);
    if (st == GLPGP_OK) st = glpgp_solve(m, g_ref, &o, &r);
    if (st == GLPGP_OK) {
        for (int k = 0; k < 2; k++) {
            for (int i = 0; i < 2 * m->nv; i++) FUZZ_ASSERT(isfinite(r->osc[k].z[i]));
            FUZZ_ASSERT(r->osc[k].plus >= 0 && r->osc[k].minus >= 0);
            FUZZ_ASSERT(r->osc[k].zabs_median >= 0 && isfinite(r->osc[k].zabs_median));
        }
        glpgp_quads_options qo;
        glpgp_quads_options_default(&qo);
        qo.smooth = 2;
        glpgp_quadmesh *q = NULL;
        double h = r->size;
        if (!m->xyz) fuzz_check_error(glpgp_quads_build(m, r, &qo, &q, &h)); /* quads: planar only yet */
        glpgp_quadmesh_destroy(&q);
    }
    fuzz_check_error(st);
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);
    return 0;
}
