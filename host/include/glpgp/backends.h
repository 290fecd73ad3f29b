/* glpgp/backends.h: the implementations of the backend table
 * (glpgp/backend.h): the scalar C reference backend and the OpenCL backend,
 * the one backend selector every command uses (auto: OpenCL, falling back to
 * the reference backend with one warning), the OpenCL device list, and the
 * backend-independent matrix probe used by cross-checks. Layer: backends. */
#ifndef GLPGP_BACKENDS_H
#define GLPGP_BACKENDS_H

#include "glpgp/backend.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The scalar C reference backend (single-threaded, no OpenCL). */
glpgp_status glpgp_backend_create_reference(glpgp_backend **out);

/* OpenCL backend options. */
typedef struct glpgp_cl_options {
    int device;        /* global device index as listed by `glpgp devices`; -1: GLPGP_DEVICE env or first with fp64 */
    int verbose;       /* log the chosen device (GLPGP_LOG_INFO) */
} glpgp_cl_options;
/* Create the OpenCL backend (GLPGP_ERR_OPENCL / GLPGP_ERR_UNSUPPORTED with a
 * clear message when no platform/device/fp64 is available). */
glpgp_status glpgp_backend_create_opencl(const glpgp_cl_options *opt, glpgp_backend **out);
/* Whether this build has OpenCL support compiled in. */
int glpgp_have_opencl(void);

/* Which backend glpgp_backend_select creates. */
typedef enum glpgp_backend_kind {
    GLPGP_BACKEND_AUTO = 0,  /* OpenCL when usable, else reference (one warning) */
    GLPGP_BACKEND_OPENCL,    /* OpenCL or an error */
    GLPGP_BACKEND_REFERENCE  /* the scalar C reference */
} glpgp_backend_kind;

/* Parse "auto", "opencl", "reference" (-1 when unknown). */
int glpgp_backend_kind_parse(const char *name);

/* The one backend selector. device >= 0 asks for that OpenCL device: with
 * AUTO its failure is then an error, not a fallback. With AUTO and no usable
 * OpenCL device, the reference backend is created and a warning logged
 * ("OpenCL backend unavailable (...); using the reference backend").
 * verbose: log the chosen OpenCL device. */
glpgp_status glpgp_backend_select(glpgp_backend_kind kind, int device, int verbose,
                                  glpgp_backend **out);

/* One OpenCL device, as listed by `glpgp devices`. */
typedef struct glpgp_device_info {
    int index;            /* global index (for --device and GLPGP_DEVICE) */
    int platform_index;
    char platform[256], platform_vendor[256], platform_version[256];
    char name[256], vendor[256], version[256];
    unsigned compute_units;
    unsigned long long global_mem; /* bytes */
    int fp64;
    const char *type;     /* "GPU", "CPU", "accelerator", "other" */
} glpgp_device_info;

/* Every device of every platform (*out: malloc'ed, free() it). No OpenCL in
 * the build -> GLPGP_ERR_UNSUPPORTED; no platform -> GLPGP_ERR_OPENCL. */
glpgp_status glpgp_devices_list(glpgp_device_info **out, int *n);

/* Describe an OpenCL backend ("device N: name (shape ...)") into buf;
 * returns its device index, or -1 (buf: "none") if b is not an OpenCL
 * backend or the build has no OpenCL. */
int glpgp_cl_backend_info(const glpgp_backend *b, char *buf, size_t len);

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

#ifdef __cplusplus
}
#endif

#endif
