/* backends/opencl_program.c: the OpenCL backend's program and device: the
 * kernel names, the program built from the embedded sources (or
 * GLPGP_KERNEL_DIR) with its build log on failure, the warm-up launches,
 * the device choice (glpgp_cl_options.device, GLPGP_DEVICE, the first fp64
 * GPU, the first fp64 device) and its context, queue and kernels. The rest
 * of the backend: opencl.c, opencl_amg.c (opencl_impl.h). */
#include "cl_util.h"

#ifdef GLPGP_HAVE_OPENCL

#include <dirent.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "glpgp/internal/debug.h"
#include "glpgp/util.h"

#include "opencl_impl.h"

extern const char glpgp_kernel_source[];
extern const char glpgp_kernel_prelude[];

const char *const glpgp_cl_kernel_names[K_COUNT] = {
    "glpgp_finalize",   "glpgp_asm_quad",   "glpgp_asm_newton",      "glpgp_gradient",
    "glpgp_pen_energy_part", "glpgp_axpby",    "glpgp_dot_part",
    "glpgp_spmv",       "glpgp_cg_precond", "glpgp_cg_spmv_dot",     "glpgp_cg_update",
    "glpgp_cg_direction",
    "glpgp_amg_finalize", "glpgp_amg_weights", "glpgp_amg_galerkin", "glpgp_amg_l1",
    "glpgp_amg_smooth",   "glpgp_amg_restrict", "glpgp_amg_prolong", "glpgp_amg_dense",
    "glpgp_amg_spmv_dots", "glpgp_amg_dots",   "glpgp_amg_axpby",   "glpgp_amg_kcombine",
    "glpgp_amg_bottom", "glpgp_amg_residual", "glpgp_amg_coarse_invert",
    "glpgp_amg_presmooth_restrict", "glpgp_amg_presmooth_resid", "glpgp_amg_prolong_smooth",
    "glpgp_casm_quad", "glpgp_casm_newton", "glpgp_cgradient", "glpgp_cpen_energy_part",
    "glpgp_trial_point",
};

/* ---- program ------------------------------------------------------------- */

static glpgp_status read_text(const char *path, char **out, size_t *len)
{
    FILE *f = fopen(path, "rb");
    *out = NULL;
    *len = 0;
    if (!f) return GLPGP_FAIL(GLPGP_ERR_IO, "GLPGP_KERNEL_DIR: cannot open %s", path);
    char *buf = NULL;
    size_t cap = 0, n = 0;
    for (;;) {
        if (n + 4096 + 1 > cap) {
            cap = 2 * cap + 8192;
            char *nb = realloc(buf, cap);
            if (!nb) {
                free(buf);
                fclose(f);
                return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading %s", path);
            }
            buf = nb;
        }
        size_t r = fread(buf + n, 1, 4096, f);
        n += r;
        if (r < 4096) break;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        return GLPGP_FAIL(GLPGP_ERR_IO, "GLPGP_KERNEL_DIR: error reading %s", path);
    }
    buf[n] = '\0';
    *out = buf;
    *len = n;
    return GLPGP_OK;
}

static int cl_file_filter(const struct dirent *d)
{
    size_t n = strlen(d->d_name);
    return n > 3 && strcmp(d->d_name + n - 3, ".cl") == 0;
}

/* Headers read from GLPGP_KERNEL_DIR before its .cl files, in program order. */
static const char *const kernel_dir_headers[] = {"element.h", "rows.h", "amg_rows.h", "coupled_rows.h",
                                                  "newton_rows.h", "amg_dense.h"};
#define N_KERNEL_DIR_HEADERS ((int)(sizeof kernel_dir_headers / sizeof kernel_dir_headers[0]))

/* The embedded glpgp/kinds.h, then dir/element.h, dir/rows.h, dir/amg_rows.h
 * and the .cl files of dir (name order), concatenated into *out (malloc'ed). */
static glpgp_status load_kernel_dir(const char *dir, char **out)
{
    struct dirent **list = NULL;
    char path[4096];
    char *src = NULL, *piece = NULL;
    size_t len = 0, plen = 0;
    glpgp_status st = GLPGP_OK;
    *out = NULL;
    int n = scandir(dir, &list, cl_file_filter, alphasort);
    if (n < 0) return GLPGP_FAIL(GLPGP_ERR_IO, "GLPGP_KERNEL_DIR: cannot list %s", dir);
    len = strlen(glpgp_kernel_prelude);
    if (!(src = malloc(len + 2))) {
        st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory loading kernels");
        goto done;
    }
    memcpy(src, glpgp_kernel_prelude, len + 1);
    for (int i = -N_KERNEL_DIR_HEADERS; i < n; i++) {
        snprintf(path, sizeof path, "%s/%s", dir,
                 i < 0 ? kernel_dir_headers[N_KERNEL_DIR_HEADERS + i] : list[i]->d_name);
        GLPGP_CHECK_GOTO(st, read_text(path, &piece, &plen), done);
        char *ns = realloc(src, len + plen + 2);
        if (!ns) {
            free(piece);
            st = GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory loading kernels");
            goto done;
        }
        src = ns;
        memcpy(src + len, piece, plen);
        len += plen;
        src[len++] = '\n';
        src[len] = '\0';
        free(piece);
        piece = NULL;
    }
    *out = src;
    src = NULL;
done:
    for (int i = 0; i < n; i++) free(list[i]);
    free(list);
    free(src);
    return st;
}

static glpgp_status warm_up(cl_impl *c);

static glpgp_status build_program(cl_impl *c)
{
    static const char header[] = "#pragma OPENCL EXTENSION cl_khr_fp64 : enable\n"
                                 "#pragma OPENCL FP_CONTRACT OFF\n";
    char *dirsrc = NULL;
    const char *kdir = getenv("GLPGP_KERNEL_DIR");
    if (kdir && *kdir) GLPGP_CHECK(load_kernel_dir(kdir, &dirsrc));
    const char *srcs[2] = {header, dirsrc ? dirsrc : glpgp_kernel_source};
    cl_int err;
    double t0 = glpgp_cl_now_seconds();
    c->prog = clCreateProgramWithSource(c->ctx, 2, srcs, NULL, &err);
    free(dirsrc);
    GLPGP_CL(err);
    char opts[128];
    snprintf(opts, sizeof opts, "-cl-std=CL1.2 -DGLPGP_WG=%zu", c->wg);
    err = clBuildProgram(c->prog, 1, &c->dev, opts, NULL, NULL);
    if (err != CL_SUCCESS) {
        size_t loglen = 0;
        char *log = NULL;
        clGetProgramBuildInfo(c->prog, c->dev, CL_PROGRAM_BUILD_LOG, 0, NULL, &loglen);
        if (loglen > 0 && (log = malloc(loglen + 1)) != NULL) {
            if (clGetProgramBuildInfo(c->prog, c->dev, CL_PROGRAM_BUILD_LOG, loglen, log, NULL) != CL_SUCCESS)
                log[0] = '\0';
            log[loglen] = '\0';
        }
        glpgp_status st = GLPGP_FAIL(GLPGP_ERR_OPENCL,
                                     "OpenCL program build failed with %s on %s (options %s)%s; build log below",
                                     glpgp_cl_error_name(err), c->name, opts,
                                     kdir && *kdir ? " [sources from GLPGP_KERNEL_DIR]" : "");
        glpgp_error_set_detail(log ? log : "(no build log)");
        free(log);
        return st;
    }
    for (int i = 0; i < K_COUNT; i++)
        GLPGP_CL_WHAT((c->k[i] = clCreateKernel(c->prog, glpgp_cl_kernel_names[i], &err), err), glpgp_cl_kernel_names[i]);
    GLPGP_CHECK(warm_up(c));
    c->build_seconds = glpgp_cl_now_seconds() - t0;
    return GLPGP_OK;
}

/* Launch every kernel once on no work (n = 0, every buffer argument a small
 * zeroed buffer), so that a device that compiles a kernel at its first
 * launch (PoCL: per local size) does it now, as part of the program build,
 * and not in the first numerical phase that launches it (a cold cache: about
 * 0.3 s per kernel). Arguments are set by size: a buffer where one fits,
 * else an int 0 (the fused coarse correction's level count 1: a coarsest
 * level of order 0). */
static glpgp_status warm_up(cl_impl *c)
{
    cl_int err;
    cl_mem dummy = NULL;
    GLPGP_CL((dummy = clCreateBuffer(c->ctx, CL_MEM_READ_WRITE, 65536, NULL, &err), err));
    const cl_int zero = 0;
    glpgp_status st = GLPGP_OK;
    err = clEnqueueFillBuffer(c->q, dummy, &zero, sizeof zero, 0, 65536, 0, NULL, NULL);
    for (int kid = 0; kid < K_COUNT && err == CL_SUCCESS; kid++) {
        if (c->stop && __atomic_load_n(c->stop, __ATOMIC_RELAXED)) {
            st = GLPGP_FAIL(GLPGP_ERR_ARG, "stopped");
            break;
        }
        if (kid == K_AMG_BOTTOM && !c->cpu) continue; /* one work-item: the CPU shape's only */
        /* the coupled cross-field kernels: compiled at their first use (most runs have none) */
        if (kid == K_CASM_QUAD || kid == K_CASM_NEWTON || kid == K_CGRADIENT || kid == K_CPEN_ENERGY) continue;
        cl_kernel k = c->k[kid];
        cl_uint nargs = 0;
        err = clGetKernelInfo(k, CL_KERNEL_NUM_ARGS, sizeof nargs, &nargs, NULL);
        for (cl_uint a = 0; a < nargs && err == CL_SUCCESS; a++) {
            const cl_int v = kid == K_AMG_BOTTOM && a == 1 ? 1 : 0;
            err = clSetKernelArg(k, a, sizeof dummy, &dummy);
            if (err == CL_INVALID_ARG_SIZE) err = clSetKernelArg(k, a, sizeof v, &v);
        }
        size_t g = c->wg, l = c->wg;
        if (err == CL_SUCCESS) err = clEnqueueNDRangeKernel(c->q, k, 1, NULL, &g, &l, 0, NULL, NULL);
        if (err != CL_SUCCESS)
            st = GLPGP_FAIL(GLPGP_ERR_OPENCL, "OpenCL: the first launch of %s failed with %s", glpgp_cl_kernel_names[kid],
                            glpgp_cl_error_name(err));
    }
    if (st == GLPGP_OK && err == CL_SUCCESS) err = clFinish(c->q);
    if (st == GLPGP_OK && err != CL_SUCCESS)
        st = GLPGP_FAIL(GLPGP_ERR_OPENCL, "OpenCL: kernel warm-up failed with %s", glpgp_cl_error_name(err));
    clReleaseMemObject(dummy);
    return st;
}

/* ---- device choice ----------------------------------------------------- */

static glpgp_status pick_device(const glpgp_cl_options *opt, glpgp_cl_device *devs, int n, int *idx)
{
    int want = opt ? opt->device : -1;
    const char *env = getenv("GLPGP_DEVICE");
    const char *from = "--device";
    if (want < 0 && env && *env) {
        char *end = NULL;
        long v = strtol(env, &end, 10);
        if (*end != '\0' || v < 0 || v > INT_MAX)
            return GLPGP_FAIL(GLPGP_ERR_ARG, "GLPGP_DEVICE='%s' is not a device index (see glpgp devices)", env);
        want = (int)v;
        from = "GLPGP_DEVICE";
    }
    if (want >= 0) {
        if (want >= n)
            return GLPGP_FAIL(GLPGP_ERR_ARG, "%s %d: no such OpenCL device (%d available, see glpgp devices)",
                              from, want, n);
        if (!glpgp_cl_has_fp64(devs[want].device)) {
            char name[256];
            glpgp_cl_device_str(devs[want].device, CL_DEVICE_NAME, name, sizeof name);
            return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED,
                              "OpenCL device %d (%s) has no double precision (cl_khr_fp64), which glpgp "
                              "needs; choose another with --device (see glpgp devices)",
                              want, name);
        }
        *idx = want;
        return GLPGP_OK;
    }
    *idx = glpgp_cl_auto_device(devs, n); /* the first fp64 GPU, else the first fp64 device */
    if (*idx >= 0) return GLPGP_OK;
    if (n == 0) return GLPGP_FAIL(GLPGP_ERR_OPENCL, "OpenCL platforms exist but expose no device");
    return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED,
                      "none of the %d OpenCL devices supports double precision (cl_khr_fp64), which "
                      "glpgp needs (install pocl-opencl-icd for the CPU)",
                      n);
}

void glpgp_cl_log_device(const cl_impl *c)
{
    glpgp_log(GLPGP_LOG_INFO, "OpenCL device %d: %s, %s launch shape (%s), program built in %.2f s", c->index, c->name,
              c->cpu ? "cpu" : "gpu", c->cpu ? "chunked work-items, local size 1" : "one row per work-item",
              c->build_seconds);
    if (c->cpu)
        glpgp_log(GLPGP_LOG_INFO, "OpenCL cpu shape: up to %zu work-items", c->nwi);
    else
        glpgp_log(GLPGP_LOG_INFO, "OpenCL gpu shape: local size %zu", c->wg);
}

glpgp_status glpgp_cl_init_device(cl_impl *c, const glpgp_cl_options *opt)
{
    glpgp_cl_device *devs = NULL;
    int n = 0, idx = -1;
    GLPGP_CHECK(glpgp_cl_devices(&devs, &n));
    glpgp_status st = pick_device(opt, devs, n, &idx);
    if (st != GLPGP_OK) {
        free(devs);
        glpgp_error_push_trace(__FILE__, __LINE__);
        return st;
    }
    cl_platform_id plat = devs[idx].platform;
    c->dev = devs[idx].device;
    c->index = idx;
    free(devs);

    glpgp_cl_device_str(c->dev, CL_DEVICE_NAME, c->name, sizeof c->name);
    GLPGP_CL(clGetDeviceInfo(c->dev, CL_DEVICE_TYPE, sizeof c->type, &c->type, NULL));
    GLPGP_CL(clGetDeviceInfo(c->dev, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof c->global_mem, &c->global_mem, NULL));
    GLPGP_CL(clGetDeviceInfo(c->dev, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof c->max_alloc, &c->max_alloc, NULL));
    size_t maxwg = 1;
    GLPGP_CL(clGetDeviceInfo(c->dev, CL_DEVICE_MAX_WORK_GROUP_SIZE, sizeof maxwg, &maxwg, NULL));

    /* launch shape from the device type (GLPGP_CL_SHAPE=cpu|gpu overrides), the
     * environment's switches read once (glpgp/internal/debug.h) */
    glpgp_debug dbg;
    GLPGP_CHECK(glpgp_debug_read(&dbg));
    c->cpu = dbg.cl_shape >= 0 ? dbg.cl_shape : (c->type & CL_DEVICE_TYPE_CPU) != 0;
    c->nwi = dbg.cl_workitems > 0 ? (size_t)dbg.cl_workitems : 128;
    if (c->cpu) {
        c->wg = 1;
    } else {
        c->wg = 128; /* power of two, at most the device limit */
        while (c->wg > maxwg && c->wg > 1) c->wg /= 2;
    }
    c->amg_small = dbg.cl_amg_small >= 0 ? dbg.cl_amg_small : 2048;
    c->amg_fuse = dbg.cl_amg_fuse >= 0 ? dbg.cl_amg_fuse : 32768;
    cl_uint bits = 1024;
    GLPGP_CL(clGetDeviceInfo(c->dev, CL_DEVICE_MEM_BASE_ADDR_ALIGN, sizeof bits, &bits, NULL));
    c->align = bits / 8 < 8 ? 8 : bits / 8;
    c->verbose = opt ? opt->verbose : 0;
    c->corrupt = dbg.cl_corrupt;
    c->stop = opt ? opt->stop : NULL;
    c->prof = dbg.cl_profile;

    cl_int err;
    cl_context_properties props[] = {CL_CONTEXT_PLATFORM, (cl_context_properties)plat, 0};
    GLPGP_CL((c->ctx = clCreateContext(props, 1, &c->dev, NULL, NULL, &err), err));
    GLPGP_CL((c->q = clCreateCommandQueue(c->ctx, c->dev, c->prof ? CL_QUEUE_PROFILING_ENABLE : 0, &err), err));
    if (c->stop && __atomic_load_n(c->stop, __ATOMIC_RELAXED)) return GLPGP_FAIL(GLPGP_ERR_ARG, "stopped");
    GLPGP_CHECK(build_program(c));
    if (opt && opt->verbose) glpgp_cl_log_device(c);
    return GLPGP_OK;
}

#endif /* GLPGP_HAVE_OPENCL */
