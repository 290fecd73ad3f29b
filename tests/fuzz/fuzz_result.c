/* fuzz_result.c: the result readers of `glpgp extract` and `glpgp render`
 * (glpgp_read_result: legacy VTK and VTK XML .vtu, raw or zlib-compressed,
 * recognised by the content; io/result_read.c, io/vtu.c), then what those
 * commands do with an accepted result on small meshes: the h check of
 * extract (glpgp_options_check_mesh), the quad extraction with its closing
 * and smoothing (glpgp_quads_build) and quality report, and a 64-pixel
 * picture (glpgp_render). Properties: a failure returns neither mesh nor
 * result and one error line; an accepted result has finite z. */
#include "fuzz_common.h"

#include "glpgp/image.h"
#include "glpgp/io.h"
#include "glpgp/quads.h"
#include "glpgp/solve.h"

#include <math.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    glpgp_error_clear();
    const char *path = fuzz_write_file(0, ".vtk", data, size);
    glpgp_mesh *m = (glpgp_mesh *)&m;
    glpgp_result *r = (glpgp_result *)&r;
    glpgp_status st = glpgp_read_result(path, &m, &r);
    if (st != GLPGP_OK) {
        FUZZ_ASSERT(m == NULL && r == NULL);
        fuzz_check_error(st);
        return 0;
    }
    FUZZ_ASSERT(m && r && r->nv == m->nv && r->nt == m->nt);
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < 2 * m->nv; i++) FUZZ_ASSERT(isfinite(r->osc[k].z[i]));
    if (m->nt <= 2000) {
        if (!(r->size > 0)) r->size = glpgp_default_size(m, NULL);
        glpgp_options so;
        glpgp_options_default(&so);
        so.size = r->size;
        st = glpgp_options_check_mesh(&so, m);
        fuzz_check_error(st);
        if (st == GLPGP_OK && !m->xyz) { /* quads: planar results only (not yet on surfaces) */
            glpgp_quads_options qo;
            glpgp_quads_options_default(&qo);
            qo.smooth = 3;
            glpgp_quadmesh *q = NULL;
            double h = r->size;
            st = glpgp_quads_build(m, r, &qo, &q, &h);
            fuzz_check_error(st);
            if (st == GLPGP_OK) {
                glpgp_quads_report qq;
                fuzz_check_error(glpgp_quads_quality(q, m, h, &qq));
            }
            glpgp_quadmesh_destroy(&q);
        }
        glpgp_render_options ro;
        glpgp_render_options_default(&ro);
        ro.size = 64;
        glpgp_image *im = NULL;
        fuzz_check_error(glpgp_render(m, r, &ro, &im));
        glpgp_image_destroy(&im);
    }
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);
    return 0;
}
