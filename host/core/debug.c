/* core/debug.c: the environment's test and debug switches read into one
 * struct (glpgp/internal/debug.h, which lists them). */
#include "glpgp/internal/debug.h"
#include "glpgp/util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A count switch in [lo, hi]; *out unchanged when unset. */
static glpgp_status count_switch(const char *name, long lo, long hi, int *out)
{
    const char *ev = getenv(name);
    if (!ev || !*ev) return GLPGP_OK;
    char *end = NULL;
    long v = strtol(ev, &end, 10);
    if (*end != '\0' || v < lo || v > hi)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "%s='%s': expected a count in [%ld, %ld]", name, ev, lo, hi);
    *out = (int)v;
    return GLPGP_OK;
}

static int flag_switch(const char *name)
{
    const char *ev = getenv(name);
    return ev && strcmp(ev, "1") == 0;
}

glpgp_status glpgp_debug_read(glpgp_debug *d)
{
    memset(d, 0, sizeof *d);
    d->cl_shape = -1;
    d->cl_amg_small = d->cl_amg_fuse = -1;
    d->cl_profile = flag_switch("GLPGP_CL_PROFILE");
    d->cl_corrupt = flag_switch("GLPGP_CL_CORRUPT");
    const char *fault = getenv("GLPGP_TEST_GMSH_FAULT");
    if (fault) snprintf(d->gmsh_fault, sizeof d->gmsh_fault, "%s", fault);
    const char *gt = getenv("GLPGP_TEST_GMSH_TIMEOUT");
    if (gt && *gt) {
        char *end = NULL;
        double v = glpgp_strtod(gt, &end);
        if (*end != '\0' || !(v > 0) || v > 1e9)
            return GLPGP_FAIL(GLPGP_ERR_ARG, "GLPGP_TEST_GMSH_TIMEOUT='%s': expected seconds > 0", gt);
        d->gmsh_timeout = v;
    }
    const char *shape = getenv("GLPGP_CL_SHAPE");
    if (shape && strcmp(shape, "cpu") == 0) d->cl_shape = 1;
    else if (shape && strcmp(shape, "gpu") == 0) d->cl_shape = 0;
    else if (shape && *shape)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "GLPGP_CL_SHAPE='%s': expected cpu or gpu", shape);
    GLPGP_CHECK(count_switch("GLPGP_CL_WORKITEMS", 1, 65536, &d->cl_workitems));
    GLPGP_CHECK(count_switch("GLPGP_CL_AMG_SMALL", 0, 1000000, &d->cl_amg_small));
    GLPGP_CHECK(count_switch("GLPGP_CL_AMG_FUSE", 0, 1000000, &d->cl_amg_fuse));
    return GLPGP_OK;
}
