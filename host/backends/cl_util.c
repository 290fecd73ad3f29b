/* backends/cl_util.c: OpenCL error names, device enumeration and device
 * info helpers (cl_util.h), and the public device list (glpgp_devices_list,
 * glpgp/backends.h). */
#include "cl_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef GLPGP_HAVE_OPENCL

#ifndef CL_PLATFORM_NOT_FOUND_KHR
#define CL_PLATFORM_NOT_FOUND_KHR -1001
#endif

const char *glpgp_cl_error_name(cl_int err)
{
    switch (err) {
#define N(e) case e: return #e
    N(CL_SUCCESS);
    N(CL_DEVICE_NOT_FOUND);
    N(CL_DEVICE_NOT_AVAILABLE);
    N(CL_COMPILER_NOT_AVAILABLE);
    N(CL_MEM_OBJECT_ALLOCATION_FAILURE);
    N(CL_OUT_OF_RESOURCES);
    N(CL_OUT_OF_HOST_MEMORY);
    N(CL_PROFILING_INFO_NOT_AVAILABLE);
    N(CL_MEM_COPY_OVERLAP);
    N(CL_IMAGE_FORMAT_MISMATCH);
    N(CL_IMAGE_FORMAT_NOT_SUPPORTED);
    N(CL_BUILD_PROGRAM_FAILURE);
    N(CL_MAP_FAILURE);
    N(CL_MISALIGNED_SUB_BUFFER_OFFSET);
    N(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST);
    N(CL_COMPILE_PROGRAM_FAILURE);
    N(CL_LINKER_NOT_AVAILABLE);
    N(CL_LINK_PROGRAM_FAILURE);
    N(CL_DEVICE_PARTITION_FAILED);
    N(CL_KERNEL_ARG_INFO_NOT_AVAILABLE);
    N(CL_INVALID_VALUE);
    N(CL_INVALID_DEVICE_TYPE);
    N(CL_INVALID_PLATFORM);
    N(CL_INVALID_DEVICE);
    N(CL_INVALID_CONTEXT);
    N(CL_INVALID_QUEUE_PROPERTIES);
    N(CL_INVALID_COMMAND_QUEUE);
    N(CL_INVALID_HOST_PTR);
    N(CL_INVALID_MEM_OBJECT);
    N(CL_INVALID_IMAGE_FORMAT_DESCRIPTOR);
    N(CL_INVALID_IMAGE_SIZE);
    N(CL_INVALID_SAMPLER);
    N(CL_INVALID_BINARY);
    N(CL_INVALID_BUILD_OPTIONS);
    N(CL_INVALID_PROGRAM);
    N(CL_INVALID_PROGRAM_EXECUTABLE);
    N(CL_INVALID_KERNEL_NAME);
    N(CL_INVALID_KERNEL_DEFINITION);
    N(CL_INVALID_KERNEL);
    N(CL_INVALID_ARG_INDEX);
    N(CL_INVALID_ARG_VALUE);
    N(CL_INVALID_ARG_SIZE);
    N(CL_INVALID_KERNEL_ARGS);
    N(CL_INVALID_WORK_DIMENSION);
    N(CL_INVALID_WORK_GROUP_SIZE);
    N(CL_INVALID_WORK_ITEM_SIZE);
    N(CL_INVALID_GLOBAL_OFFSET);
    N(CL_INVALID_EVENT_WAIT_LIST);
    N(CL_INVALID_EVENT);
    N(CL_INVALID_OPERATION);
    N(CL_INVALID_GL_OBJECT);
    N(CL_INVALID_BUFFER_SIZE);
    N(CL_INVALID_MIP_LEVEL);
    N(CL_INVALID_GLOBAL_WORK_SIZE);
    N(CL_INVALID_PROPERTY);
    N(CL_INVALID_IMAGE_DESCRIPTOR);
    N(CL_INVALID_COMPILER_OPTIONS);
    N(CL_INVALID_LINKER_OPTIONS);
    N(CL_INVALID_DEVICE_PARTITION_COUNT);
    N(CL_PLATFORM_NOT_FOUND_KHR);
#undef N
    }
    return "an unknown OpenCL error"; /* a constant: no static buffer (GLPGP_CL prints the code) */
}

glpgp_status glpgp_cl_devices(glpgp_cl_device **out, int *n)
{
    cl_uint np = 0;
    *out = NULL;
    *n = 0;
    cl_int err = clGetPlatformIDs(0, NULL, &np);
    if (err == CL_PLATFORM_NOT_FOUND_KHR || (err == CL_SUCCESS && np == 0))
        return GLPGP_FAIL(GLPGP_ERR_OPENCL,
                          "no OpenCL platform found (install pocl-opencl-icd for the CPU)");
    GLPGP_CL(err);
    cl_platform_id *plats = NULL;
    GLPGP_CHECK(glpgp_malloc(np, sizeof *plats, &plats));
    err = clGetPlatformIDs(np, plats, NULL);
    if (err != CL_SUCCESS) {
        free(plats);
        GLPGP_CL(err);
    }
    /* count, then fill */
    int total = 0;
    for (cl_uint p = 0; p < np; p++) {
        cl_uint nd = 0;
        if (clGetDeviceIDs(plats[p], CL_DEVICE_TYPE_ALL, 0, NULL, &nd) == CL_SUCCESS) total += (int)nd;
    }
    glpgp_cl_device *devs = NULL;
    glpgp_status st = glpgp_calloc(total > 0 ? (size_t)total : 1, sizeof *devs, &devs);
    if (st != GLPGP_OK) {
        free(plats);
        return st;
    }
    int k = 0;
    for (cl_uint p = 0; p < np && k < total; p++) {
        cl_uint nd = 0;
        if (clGetDeviceIDs(plats[p], CL_DEVICE_TYPE_ALL, 0, NULL, &nd) != CL_SUCCESS || nd == 0) continue;
        if (nd > (cl_uint)(total - k)) nd = (cl_uint)(total - k);
        cl_device_id *ids = NULL;
        st = glpgp_malloc(nd, sizeof *ids, &ids);
        if (st != GLPGP_OK) {
            free(plats);
            free(devs);
            return st;
        }
        if (clGetDeviceIDs(plats[p], CL_DEVICE_TYPE_ALL, nd, ids, NULL) == CL_SUCCESS)
            for (cl_uint d = 0; d < nd; d++) {
                devs[k].platform = plats[p];
                devs[k].device = ids[d];
                devs[k].platform_index = (int)p;
                k++;
            }
        free(ids);
    }
    free(plats);
    *out = devs;
    *n = k;
    return GLPGP_OK;
}

int glpgp_cl_has_fp64(cl_device_id d)
{
    cl_device_fp_config cfg = 0;
    if (clGetDeviceInfo(d, CL_DEVICE_DOUBLE_FP_CONFIG, sizeof cfg, &cfg, NULL) == CL_SUCCESS && cfg != 0)
        return 1;
    size_t len = 0;
    if (clGetDeviceInfo(d, CL_DEVICE_EXTENSIONS, 0, NULL, &len) != CL_SUCCESS || len == 0) return 0;
    char *ext = malloc(len + 1);
    if (!ext) return 0;
    int has = 0;
    if (clGetDeviceInfo(d, CL_DEVICE_EXTENSIONS, len, ext, NULL) == CL_SUCCESS) {
        ext[len] = '\0';
        has = strstr(ext, "cl_khr_fp64") != NULL;
    }
    free(ext);
    return has;
}

/* Copy a queried string into buf, truncating (the query itself needs the full size). */
static void copy_info(char *buf, size_t len, const char *s, size_t n)
{
    if (n > len - 1) n = len - 1;
    memcpy(buf, s, n);
    buf[n] = '\0';
    /* trim trailing NULs/spaces */
    size_t l = strlen(buf);
    while (l > 0 && buf[l - 1] == ' ') buf[--l] = '\0';
}

void glpgp_cl_device_str(cl_device_id d, cl_device_info what, char *buf, size_t len)
{
    size_t n = 0;
    char *tmp = NULL;
    if (len == 0) return;
    snprintf(buf, len, "?");
    if (clGetDeviceInfo(d, what, 0, NULL, &n) != CL_SUCCESS || n == 0 || !(tmp = malloc(n))) return;
    if (clGetDeviceInfo(d, what, n, tmp, NULL) == CL_SUCCESS) copy_info(buf, len, tmp, n);
    free(tmp);
}

void glpgp_cl_platform_str(cl_platform_id p, cl_platform_info what, char *buf, size_t len)
{
    size_t n = 0;
    char *tmp = NULL;
    if (len == 0) return;
    snprintf(buf, len, "?");
    if (clGetPlatformInfo(p, what, 0, NULL, &n) != CL_SUCCESS || n == 0 || !(tmp = malloc(n))) return;
    if (clGetPlatformInfo(p, what, n, tmp, NULL) == CL_SUCCESS) copy_info(buf, len, tmp, n);
    free(tmp);
}

static const char *type_name(cl_device_type t)
{
    if (t & CL_DEVICE_TYPE_GPU) return "GPU";
    if (t & CL_DEVICE_TYPE_CPU) return "CPU";
    if (t & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
    return "other";
}

int glpgp_cl_auto_device(const glpgp_cl_device *devs, int n)
{
    /* with both PoCL and a GPU driver registered, the GPU (an H200 solved the
     * 1M square in 7.3 s, PoCL on its host's 16 cores in 18.9 s:
     * bench/results/gpu_h200) */
    int first = -1;
    for (int i = 0; i < n; i++) {
        if (!glpgp_cl_has_fp64(devs[i].device)) continue;
        cl_device_type t = 0;
        if (clGetDeviceInfo(devs[i].device, CL_DEVICE_TYPE, sizeof t, &t, NULL) == CL_SUCCESS &&
            (t & (CL_DEVICE_TYPE_GPU | CL_DEVICE_TYPE_ACCELERATOR)))
            return i;
        if (first < 0) first = i;
    }
    return first;
}

glpgp_status glpgp_devices_list(glpgp_device_info **out, int *nout)
{
    glpgp_cl_device *devs = NULL;
    glpgp_device_info *info = NULL;
    int n = 0;
    *out = NULL;
    *nout = 0;
    GLPGP_CHECK(glpgp_cl_devices(&devs, &n));
    glpgp_status st = glpgp_calloc((size_t)(n > 0 ? n : 1), sizeof *info, &info);
    if (st != GLPGP_OK) {
        free(devs);
        return st;
    }
    for (int i = 0; i < n; i++) {
        glpgp_device_info *d = &info[i];
        cl_device_id id = devs[i].device;
        cl_uint cu = 0;
        cl_ulong mem = 0;
        cl_device_type type = 0;
        d->index = i;
        d->platform_index = devs[i].platform_index;
        glpgp_cl_platform_str(devs[i].platform, CL_PLATFORM_NAME, d->platform, sizeof d->platform);
        glpgp_cl_platform_str(devs[i].platform, CL_PLATFORM_VENDOR, d->platform_vendor,
                              sizeof d->platform_vendor);
        glpgp_cl_platform_str(devs[i].platform, CL_PLATFORM_VERSION, d->platform_version,
                              sizeof d->platform_version);
        glpgp_cl_device_str(id, CL_DEVICE_NAME, d->name, sizeof d->name);
        glpgp_cl_device_str(id, CL_DEVICE_VENDOR, d->vendor, sizeof d->vendor);
        glpgp_cl_device_str(id, CL_DEVICE_VERSION, d->version, sizeof d->version);
        clGetDeviceInfo(id, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof cu, &cu, NULL);
        clGetDeviceInfo(id, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof mem, &mem, NULL);
        clGetDeviceInfo(id, CL_DEVICE_TYPE, sizeof type, &type, NULL);
        d->compute_units = cu;
        d->global_mem = mem;
        d->fp64 = glpgp_cl_has_fp64(id);
        d->type = type_name(type);
    }
    const int def = glpgp_cl_auto_device(devs, n);
    if (def >= 0) info[def].is_default = 1;
    free(devs);
    *out = info;
    *nout = n;
    return GLPGP_OK;
}

#else /* no OpenCL in this build */

glpgp_status glpgp_devices_list(glpgp_device_info **out, int *n)
{
    *out = NULL;
    *n = 0;
    return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "this glpgp was built without OpenCL support");
}

#endif
