/* clcheck.h: OpenCL error handling and device enumeration shared by the
 * OpenCL backend (backend_cl.c) and the `glpgp devices` / `glpgp crosscheck`
 * commands (cmd_opencl.c):
 *   - GLPGP_CL(call): the one macro every OpenCL call goes through; on a
 *     non-CL_SUCCESS result it records GLPGP_ERR_OPENCL with file:line, the
 *     call's text and the CL error NAME (e.g. CL_OUT_OF_RESOURCES) and returns
 *     it from the enclosing function (which must return glpgp_status). Calls
 *     that report through an errcode_ret pointer are written as a comma
 *     expression:  GLPGP_CL((buf = clCreateBuffer(..., &err), err));
 *   - glpgp_cl_devices(): every device of every platform, in the global order
 *     used by `glpgp devices`, `--device N` and GLPGP_DEVICE.
 *   - glpgp_probe_matrix(): reads QUAD / NEWTON / DINV of ANY backend back
 *     through the ops table only (for crosscheck and tests).
 * Everything but glpgp_probe_matrix needs a build with GLPGP_HAVE_OPENCL. */
#ifndef GLPGP_CLCHECK_H
#define GLPGP_CLCHECK_H

#include "backend.h"
#include "status.h"

/* Which matrix glpgp_probe_matrix reads: GLPGP_MAT_QUAD, GLPGP_MAT_NEWTON
 * (4*nnzb values, block-CSR order) or GLPGP_PROBE_DINV (4*nv values). */
#define GLPGP_PROBE_DINV 2
/* Recover every value of a matrix of backend b (setup done) exactly, using
 * only its ops: vertices get a distance-2 colouring (no two vertices of one
 * colour share a row), so spmv of the indicator vector of colour c and
 * component d returns column d of every block whose column has colour c
 * (2 spmvs per colour). DINV comes from cg_precond on the two unit fields
 * (it overwrites s[GLPGP_S_DOT] and s[GLPGP_S_RR]). Products with 0 and 1
 * are exact, so the values are bit-exact. */
glpgp_status glpgp_probe_matrix(glpgp_backend *b, int which, double *vals);

#ifdef GLPGP_HAVE_OPENCL
#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <CL/cl.h>

/* Name of an OpenCL error code ("CL_OUT_OF_RESOURCES"; "CL_ERROR_<n>" if unknown). */
const char *glpgp_cl_error_name(cl_int err);

#define GLPGP_CL(call) GLPGP_CL_WHAT(call, "")
/* The same, naming what was being done (e.g. the kernel being launched). */
#define GLPGP_CL_WHAT(call, what)                                                          \
    do {                                                                                   \
        cl_int glpgp_cle_ = (call);                                                        \
        if (glpgp_cle_ != CL_SUCCESS)                                                      \
            return GLPGP_FAIL(GLPGP_ERR_OPENCL, "OpenCL call failed with %s (%d)%s%s: %s",  \
                              glpgp_cl_error_name(glpgp_cle_), (int)glpgp_cle_,            \
                              (what)[0] ? " while " : "", (what), #call);                  \
    } while (0)

typedef struct glpgp_cl_device {
    cl_platform_id platform;
    cl_device_id device;
    int platform_index; /* index of its platform */
} glpgp_cl_device;

/* All devices of all platforms (*out: malloc'ed array of *n entries, free()
 * it). No platform -> GLPGP_ERR_OPENCL "no OpenCL platform found ...". A
 * platform with no device contributes nothing. */
glpgp_status glpgp_cl_devices(glpgp_cl_device **out, int *n);

/* Whether the device supports double precision (cl_khr_fp64 in its
 * extensions or a non-zero CL_DEVICE_DOUBLE_FP_CONFIG). */
int glpgp_cl_has_fp64(cl_device_id d);

/* String device/platform info into buf (always NUL-terminated; "?" on error). */
void glpgp_cl_device_str(cl_device_id d, cl_device_info what, char *buf, size_t len);
void glpgp_cl_platform_str(cl_platform_id p, cl_platform_info what, char *buf, size_t len);

#endif /* GLPGP_HAVE_OPENCL */

/* Describe an OpenCL backend ("device N: name (shape ...)") into buf;
 * returns its device index, or -1 (buf: "none") if b is not an OpenCL
 * backend or the build has no OpenCL. */
int glpgp_cl_backend_info(const glpgp_backend *b, char *buf, size_t len);
#endif
