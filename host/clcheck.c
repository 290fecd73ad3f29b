/* clcheck.c: OpenCL error names, device enumeration and device info helpers
 * (OpenCL builds only), and the backend-agnostic matrix prober used by
 * `glpgp crosscheck` and the OpenCL tests (see clcheck.h). */
#include "clcheck.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

glpgp_status glpgp_probe_matrix(glpgp_backend *b, int which, double *vals)
{
    const glpgp_system *sys = b->sys;
    const glpgp_backend_ops *o = b->ops;
    glpgp_status st = GLPGP_OK;
    int *color = NULL, *mark = NULL;
    double *xh = NULL, *yh = NULL;
    glpgp_vec *x = NULL, *y = NULL;
    if (!sys) return GLPGP_FAIL(GLPGP_ERR_ARG, "probe: backend not set up");
    const int nv = sys->nv;
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * nv, sizeof(double), &xh), done);
    GLPGP_CHECK_GOTO(st, glpgp_calloc((size_t)2 * nv, sizeof(double), &yh), done);
    GLPGP_CHECK_GOTO(st, o->vec_create(b, (size_t)2 * nv, &x), done);
    GLPGP_CHECK_GOTO(st, o->vec_create(b, (size_t)2 * nv, &y), done);
    if (which == GLPGP_PROBE_DINV) {
        /* z <- DINV r with r = (1,0) then (0,1) at every vertex: the two block columns */
        for (int d = 0; d < 2; d++) {
            for (int i = 0; i < nv; i++) {
                xh[2 * i] = d == 0 ? 1.0 : 0.0;
                xh[2 * i + 1] = d == 1 ? 1.0 : 0.0;
            }
            GLPGP_CHECK_GOTO(st, o->vec_write(b, x, xh), done);
            GLPGP_CHECK_GOTO(st, o->cg_precond(b, x, y, GLPGP_S_DOT), done);
            GLPGP_CHECK_GOTO(st, o->vec_read(b, y, yh), done);
            for (int i = 0; i < nv; i++) {
                vals[4 * (size_t)i + d] = yh[2 * i];
                vals[4 * (size_t)i + 2 + d] = yh[2 * i + 1];
            }
        }
        goto done;
    }
    if (which != GLPGP_MAT_QUAD && which != GLPGP_MAT_NEWTON) {
        st = GLPGP_FAIL(GLPGP_ERR_ARG, "probe: unknown matrix %d", which);
        goto done;
    }
    /* greedy distance-2 colouring on the (symmetric) block pattern */
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv, sizeof(int), &color), done);
    GLPGP_CHECK_GOTO(st, glpgp_malloc((size_t)nv + 1, sizeof(int), &mark), done);
    int ncol = 0;
    for (int i = 0; i <= nv; i++) mark[i] = -1;
    for (int i = 0; i < nv; i++) {
        for (int k = sys->rowptr[i]; k < sys->rowptr[i + 1]; k++) {
            int j = sys->col[k];
            for (int l = sys->rowptr[j]; l < sys->rowptr[j + 1]; l++) {
                int c = sys->col[l] < i ? color[sys->col[l]] : -1;
                if (c >= 0 && c <= nv) mark[c] = i;
            }
        }
        int c = 0;
        while (mark[c] == i) c++;
        color[i] = c;
        if (c + 1 > ncol) ncol = c + 1;
    }
    for (int c = 0; c < ncol; c++)
        for (int d = 0; d < 2; d++) {
            /* x = indicator of colour c, component d;  y = M x */
            for (int i = 0; i < nv; i++) {
                xh[2 * i] = (color[i] == c && d == 0) ? 1.0 : 0.0;
                xh[2 * i + 1] = (color[i] == c && d == 1) ? 1.0 : 0.0;
            }
            GLPGP_CHECK_GOTO(st, o->vec_write(b, x, xh), done);
            GLPGP_CHECK_GOTO(st, o->spmv(b, which, x, y), done);
            GLPGP_CHECK_GOTO(st, o->vec_read(b, y, yh), done);
            for (int i = 0; i < nv; i++)
                for (int k = sys->rowptr[i]; k < sys->rowptr[i + 1]; k++)
                    if (color[sys->col[k]] == c) {
                        vals[4 * (size_t)k + d] = yh[2 * i];
                        vals[4 * (size_t)k + 2 + d] = yh[2 * i + 1];
                    }
        }
done:
    if (x) o->vec_destroy(b, &x);
    if (y) o->vec_destroy(b, &y);
    free(color);
    free(mark);
    free(xh);
    free(yh);
    return st;
}

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
    static char buf[32]; /* unknown codes only */
    snprintf(buf, sizeof buf, "CL_ERROR_%d", (int)err);
    return buf;
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

#endif
