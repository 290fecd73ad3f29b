/* solver/backend.c: what the backend table needs beside its implementations:
 * destruction of any backend (glpgp/backend.h). */
#include "glpgp/backend.h"

#include <stdlib.h>

void glpgp_backend_destroy(glpgp_backend **pb)
{
    if (!pb || !*pb) return;
    if ((*pb)->ops && (*pb)->ops->destroy) (*pb)->ops->destroy(*pb);
    free(*pb);
    *pb = NULL;
}
