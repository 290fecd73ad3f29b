/* fuzz_field.c: the guiding-field file reader of `solve --field FILE`
 * (solver/field.c, glpgp_field_compute with GLPGP_FIELD_FILE) on a fixed
 * 16-vertex square mesh. Properties: a failure gives one error line; an
 * accepted file gives 16 finite unit vectors. */
#include "fuzz_common.h"

#include "glpgp/shapes.h"
#include "glpgp/solve.h"
#include "glpgp/internal/newton.h"

#include <math.h>

static glpgp_mesh *g_mesh;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    glpgp_error_clear();
    if (!g_mesh && glpgp_mesh_generate("square", 16, &g_mesh) != GLPGP_OK) abort();
    const char *path = fuzz_write_file(0, ".txt", data, size);
    glpgp_options o;
    glpgp_options_default(&o);
    o.field = GLPGP_FIELD_FILE;
    o.field_file = path;
    double *u = malloc(2 * (size_t)g_mesh->nv * sizeof *u);
    if (!u) abort();
    long cg = 0;
    glpgp_status st = glpgp_field_compute(g_mesh, NULL, &o, u, &cg);
    if (st == GLPGP_OK) {
        for (int i = 0; i < g_mesh->nv; i++) {
            FUZZ_ASSERT(isfinite(u[2 * i]) && isfinite(u[2 * i + 1]));
            FUZZ_ASSERT(fabs(hypot(u[2 * i], u[2 * i + 1]) - 1.0) < 1e-12);
        }
    }
    fuzz_check_error(st);
    free(u);
    return 0;
}
