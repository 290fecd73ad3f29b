/* fuzz_quadmsh.c: the quad-mesh MSH reader of `glpgp quality`
 * (glpgp_quads_read_msh, io/quadmesh_io.c over io/msh_read.c) and the quality
 * report on what it accepts (glpgp_quads_quality with h = the mean edge, as
 * the command does). Properties: a failure returns no mesh and one error
 * line; accepted faces have 3 or 4 corners within the vertices. */
#include "fuzz_common.h"

#include "glpgp/io.h"
#include "glpgp/quads.h"

#include <math.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    glpgp_error_clear();
    const char *path = fuzz_write_file(0, ".msh", data, size);
    glpgp_quadmesh *q = (glpgp_quadmesh *)&q;
    glpgp_status st = glpgp_quads_read_msh(path, &q);
    if (st != GLPGP_OK) {
        FUZZ_ASSERT(q == NULL);
        fuzz_check_error(st);
        return 0;
    }
    FUZZ_ASSERT(q != NULL);
    double s = 0.0;
    long n = 0;
    for (int f = 0; f < q->nf; f++) {
        int b = q->face_start[f], k = q->face_start[f + 1] - b;
        FUZZ_ASSERT(k == 3 || k == 4);
        for (int j = 0; j < k; j++) {
            int p = q->face_vert[b + j], r = q->face_vert[b + (j + 1) % k];
            FUZZ_ASSERT(p >= 0 && p < q->nv && r >= 0 && r < q->nv);
            s += hypot(q->xy[2 * p] - q->xy[2 * r], q->xy[2 * p + 1] - q->xy[2 * r + 1]);
            n++;
        }
    }
    double h = n && s > 0 && isfinite(s) ? s / (double)n : 1.0;
    glpgp_quads_report qq;
    st = glpgp_quads_quality(q, NULL, h, &qq);
    fuzz_check_error(st);
    glpgp_quadmesh_destroy(&q);
    return 0;
}
