/* backends/petsc_glue.c: the module side of backends/petsc_module.h, compiled
 * into glpgp_petsc.so only: the few core functions backends/petsc.c calls
 * (error record, log, checked allocation, part creation and destruction) as forwarders
 * to the table the loader (backends/petsc_load.c) hands over (allocation:
 * its own, the same C library), so the module needs no glpgp
 * symbol from the program that loads it and its errors and messages land in
 * the caller's. Built with hidden visibility: these stay private. */
#include "petsc_module.h"
#include "glpgp/internal/glue.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

static const glpgp_petsc_host *g_host;

int glpgp_petsc_glue_init(const glpgp_petsc_host *host)
{
    if (!host || host->abi != GLPGP_PETSC_ABI || host->sizeof_system != sizeof(glpgp_system) ||
        host->sizeof_backend != sizeof(glpgp_backend) || host->sizeof_ops != sizeof(glpgp_backend_ops) ||
        host->sizeof_mesh != sizeof(glpgp_mesh) || host->sizeof_part != sizeof(glpgp_mesh_part))
        return 0;
    g_host = host;
    return 1;
}

GLPGP_GLUE_ERRORS(g_host)

void glpgp_mesh_destroy(glpgp_mesh **m) { g_host->mesh_destroy(m); }

glpgp_status glpgp_mesh_part_create(int nv, int nt, int sized, glpgp_mesh **out)
{
    return g_host->mesh_part_create(nv, nt, sized, out);
}

void glpgp_log(glpgp_log_level level, const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    g_host->log_msg(level, msg);
}

glpgp_status glpgp_malloc(size_t n, size_t size, void *out_ptr)
{
    void **out = (void **)out_ptr;
    *out = NULL;
    if (size && n > SIZE_MAX / size)
        return glpgp_error_set(__FILE__, __LINE__, GLPGP_ERR_NOMEM, "allocation of %zu x %zu bytes overflows", n, size);
    *out = malloc(n * size > 0 ? n * size : 1);
    if (!*out) return glpgp_error_set(__FILE__, __LINE__, GLPGP_ERR_NOMEM, "out of memory (%zu bytes)", n * size);
    return GLPGP_OK;
}

glpgp_status glpgp_calloc(size_t n, size_t size, void *out_ptr)
{
    void **out = (void **)out_ptr;
    *out = NULL;
    if (size && n > SIZE_MAX / size)
        return glpgp_error_set(__FILE__, __LINE__, GLPGP_ERR_NOMEM, "allocation of %zu x %zu bytes overflows", n, size);
    *out = calloc(n ? n : 1, size ? size : 1);
    if (!*out) return glpgp_error_set(__FILE__, __LINE__, GLPGP_ERR_NOMEM, "out of memory (%zu bytes)", n * size);
    return GLPGP_OK;
}

void glpgp_free(void *p)
{
    void **pp = (void **)p;
    if (!pp) return;
    free(*pp);
    *pp = NULL;
}
