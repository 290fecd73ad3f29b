/* image/shim_glue.c: the module side of image/module.h, compiled into each
 * module (glpgp_oiio.so, glpgp_gmsh.so) and into no static library. It defines
 * the few core/image functions the shims call (glpgp_error_set,
 * glpgp_error_push_trace, glpgp_malloc, glpgp_image_create,
 * glpgp_image_destroy) as forwarders to the host table handed over by the
 * image layer, so a module needs no glpgp symbol from the executable, errors
 * land in the caller's error record, and buffers come from the caller. The
 * modules are built with hidden visibility: these definitions stay private
 * to the module. */
#include "module.h"
#include "glpgp/internal/glue.h"

#include <stdarg.h>
#include <stdio.h>

static const glpgp_module_host *g_host;

int glpgp_module_glue_init(const glpgp_module_host *host)
{
    if (!host || host->abi != GLPGP_MODULE_ABI || host->sizeof_image != sizeof(glpgp_image) ||
        host->sizeof_polygons != sizeof(glpgp_polygons))
        return 0;
    g_host = host;
    return 1;
}

GLPGP_GLUE_ERRORS(g_host)

glpgp_status glpgp_malloc(size_t n, size_t size, void *out_ptr)
{
    return g_host->malloc_checked(n, size, out_ptr);
}

glpgp_status glpgp_image_create(int w, int h, int nc, glpgp_image **out)
{
    return g_host->image_create(w, h, nc, out);
}

void glpgp_image_destroy(glpgp_image **im) { g_host->image_destroy(im); }
