/* backends/select.c: the one backend selector (glpgp/backends.h): every
 * command that solves creates its backend here, so `--backend` and
 * `--device` behave the same everywhere. */
#include "glpgp/backends.h"
#include "glpgp/solve.h"

#include <string.h>

int glpgp_backend_kind_parse(const char *name)
{
    if (!strcmp(name, "auto")) return GLPGP_BACKEND_AUTO;
    if (!strcmp(name, "opencl")) return GLPGP_BACKEND_OPENCL;
    if (!strcmp(name, "reference")) return GLPGP_BACKEND_REFERENCE;
    if (!strcmp(name, "petsc")) return GLPGP_BACKEND_PETSC;
    return -1;
}

glpgp_status glpgp_backend_select(glpgp_backend_kind kind, int device, int verbose,
                                  glpgp_backend **out)
{
    return glpgp_backend_select_stoppable(kind, device, verbose, NULL, out);
}

glpgp_status glpgp_backend_select_stoppable(glpgp_backend_kind kind, int device, int verbose, const int *stop,
                                            glpgp_backend **out)
{
    *out = NULL;
    glpgp_cl_options clo;
    clo.device = device;
    clo.verbose = verbose;
    clo.stop = stop;
    if (kind == GLPGP_BACKEND_REFERENCE) return glpgp_backend_create_reference(out);
    if (kind == GLPGP_BACKEND_PETSC) return glpgp_backend_create_petsc(GLPGP_PRECOND_AMG, out);
    /* an explicit --device asks for OpenCL: its failure is an error, not a fallback */
    if (kind == GLPGP_BACKEND_OPENCL || device >= 0) return glpgp_backend_create_opencl(&clo, out);
    if (glpgp_have_opencl()) {
        if (glpgp_backend_create_opencl(&clo, out) == GLPGP_OK) return GLPGP_OK;
        if (stop && __atomic_load_n(stop, __ATOMIC_RELAXED)) return glpgp_error_status(); /* not needed any more */
        glpgp_log(GLPGP_LOG_WARNING, "OpenCL backend unavailable (%s); using the reference backend",
                  glpgp_error_message());
        glpgp_error_clear();
    }
    return glpgp_backend_create_reference(out);
}
