/* backends/cl_util.h (internal to the backends layer): OpenCL error
 * handling and device enumeration shared by the OpenCL backend (opencl.c) and
 * the device list (glpgp_devices_list):
 *   - GLPGP_CL(call): the one macro every OpenCL call goes through; on a
 *     non-CL_SUCCESS result it records GLPGP_ERR_OPENCL with file:line, the
 *     call's text and the CL error NAME (e.g. CL_OUT_OF_RESOURCES) and returns
 *     it from the enclosing function (which must return glpgp_status). Calls
 *     that report through an errcode_ret pointer are written as a comma
 *     expression:  GLPGP_CL((buf = clCreateBuffer(..., &err), err));
 *   - glpgp_cl_devices(): every device of every platform, in the global order
 *     used by `glpgp devices`, `--device N` and GLPGP_DEVICE.
 * Everything here needs a build with GLPGP_HAVE_OPENCL. */
#ifndef GLPGP_CL_UTIL_H
#define GLPGP_CL_UTIL_H

#include "glpgp/backends.h"

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

/* The device chosen when none is asked for: the first GPU or accelerator
 * with fp64, else the first device with fp64; -1 if none has fp64. */
int glpgp_cl_auto_device(const glpgp_cl_device *devs, int n);

/* String device/platform info into buf (always NUL-terminated; "?" on error). */
void glpgp_cl_device_str(cl_device_id d, cl_device_info what, char *buf, size_t len);
void glpgp_cl_platform_str(cl_platform_id p, cl_platform_info what, char *buf, size_t len);

#endif /* GLPGP_HAVE_OPENCL */

#endif
