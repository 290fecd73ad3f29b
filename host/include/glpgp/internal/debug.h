/* glpgp/internal/debug.h: the environment's test and debug switches, in one
 * struct read from the environment in one place (core/debug.c) when a
 * component starts (the OpenCL backend at its creation, the Gmsh meshing
 * at each call): nothing else in the library calls getenv for a switch.
 * Internal: not installed. Layer: core.
 *
 *   GLPGP_CL_SHAPE=cpu|gpu     the OpenCL launch shape instead of the device type's
 *   GLPGP_CL_WORKITEMS=N       work-items of the CPU shape (1..65536) [128]
 *   GLPGP_CL_AMG_SMALL=N       multigrid levels up to N rows on one work-group [2048]
 *   GLPGP_CL_AMG_FUSE=N        fused multigrid visits up to N rows [32768]
 *   GLPGP_CL_PROFILE=1         per-kernel times in the log (profiling queue)
 *   GLPGP_CL_CORRUPT=1         corrupt one kernel's result (crosscheck's own test)
 *   GLPGP_TEST_GMSH_FAULT=abort|segv|hang|garbage|exit   the Gmsh child misbehaves
 *   GLPGP_TEST_GMSH_TIMEOUT=S  the default bound on the Gmsh child instead of
 *                              GLPGP_GMSH_DEFAULT_TIMEOUT (tests of the bound)
 */
#ifndef GLPGP_INTERNAL_DEBUG_H
#define GLPGP_INTERNAL_DEBUG_H

#include "glpgp/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct glpgp_debug {
    int cl_shape;          /* -1: from the device type, 1: cpu, 0: gpu */
    int cl_workitems;      /* 0: the default */
    int cl_amg_small;      /* -1: the default */
    int cl_amg_fuse;       /* -1: the default */
    int cl_profile;        /* 0/1 */
    int cl_corrupt;        /* 0/1 */
    char gmsh_fault[16];   /* "" or the fault's name */
    double gmsh_timeout;   /* 0: GLPGP_GMSH_DEFAULT_TIMEOUT */
} glpgp_debug;

/* Read every switch; GLPGP_ERR_ARG naming the variable on a malformed value
 * (d then holds the defaults for the ones not yet read). */
glpgp_status glpgp_debug_read(glpgp_debug *d);

#ifdef __cplusplus
}
#endif

#endif
