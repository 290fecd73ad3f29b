/* status.h: the status enum every fallible glpgp function returns, and the one
 * error-recording macro (file:line + message) that library code uses instead of
 * printing or exiting. Only main() decides what to do with a failure. */
#ifndef GLPGP_STATUS_H
#define GLPGP_STATUS_H

#include <stddef.h>

typedef enum glpgp_status {
    GLPGP_OK = 0,
    GLPGP_ERR_ARG,        /* bad argument or option value */
    GLPGP_ERR_IO,         /* file missing, unreadable or unwritable */
    GLPGP_ERR_FORMAT,     /* file readable but malformed */
    GLPGP_ERR_MESH,       /* mesh rejected by validation */
    GLPGP_ERR_NOMEM,      /* allocation failed */
    GLPGP_ERR_NUMERIC,    /* solver breakdown (NaN, negative curvature, ...) */
    GLPGP_ERR_OPENCL,     /* OpenCL platform/device/runtime failure */
    GLPGP_ERR_UNSUPPORTED /* feature not available in this build/device */
} glpgp_status;

/* Human-readable name of a status ("mesh error", ...). Never NULL. */
const char *glpgp_status_name(glpgp_status st);

/* Record an error: formats the message, stores it with file:line (the first
 * error recorded since the last glpgp_error_clear() wins; later calls append
 * a "  at file:line" trace line). Returns st so it can be used in return. */
glpgp_status glpgp_error_set(const char *file, int line, glpgp_status st,
                             const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
/* Append a trace line "at file:line" to the current error (used by GLPGP_CHECK). */
void glpgp_error_trace(const char *file, int line);
/* The recorded message ("" when none), including the trace lines. */
const char *glpgp_error_message(void);
void glpgp_error_clear(void);

/* return GLPGP_FAIL(GLPGP_ERR_MESH, "triangle %d is degenerate", t); */
#define GLPGP_FAIL(st, ...) glpgp_error_set(__FILE__, __LINE__, (st), __VA_ARGS__)

/* Propagate a failing status, recording where it passed through. */
#define GLPGP_CHECK(call)                                  \
    do {                                                   \
        glpgp_status glpgp_st_ = (call);                   \
        if (glpgp_st_ != GLPGP_OK) {                       \
            glpgp_error_trace(__FILE__, __LINE__);         \
            return glpgp_st_;                              \
        }                                                  \
    } while (0)

/* Same, but jump to a cleanup label after storing the status in `st`. */
#define GLPGP_CHECK_GOTO(st, call, label)                  \
    do {                                                   \
        (st) = (call);                                     \
        if ((st) != GLPGP_OK) {                            \
            glpgp_error_trace(__FILE__, __LINE__);         \
            goto label;                                    \
        }                                                  \
    } while (0)

/* malloc/calloc that record GLPGP_ERR_NOMEM; n*size overflow checked. */
glpgp_status glpgp_malloc(size_t n, size_t size, void *out_ptr);
glpgp_status glpgp_calloc(size_t n, size_t size, void *out_ptr);
/* free(*p) and set *p = NULL (p is a pointer to any pointer). */
void glpgp_free(void *p);

#endif
