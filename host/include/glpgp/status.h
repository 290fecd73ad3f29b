/* glpgp/status.h: the status every fallible glpgp function returns, the error
 * record (one per thread: message + file:line trace), the one checking macro
 * family that records where a failure passed through, the log callback through
 * which library code reports progress (it never prints or exits), and the
 * checked allocation helpers. Layer: core. */
#ifndef GLPGP_STATUS_H
#define GLPGP_STATUS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum glpgp_status {
    GLPGP_OK = 0,
    GLPGP_ERR_ARG,        /* bad argument or option value */
    GLPGP_ERR_IO,         /* file missing, unreadable or unwritable */
    GLPGP_ERR_FORMAT,     /* file readable but malformed */
    GLPGP_ERR_MESH,       /* mesh rejected by validation */
    GLPGP_ERR_NOMEM,      /* allocation failed */
    GLPGP_ERR_NUMERIC,    /* solver breakdown (NaN, negative curvature, ...) */
    GLPGP_ERR_OPENCL,     /* OpenCL platform/device/runtime failure */
    GLPGP_ERR_UNSUPPORTED,/* feature not available in this build/device */
    GLPGP_ERR_LIMIT,      /* input above a documented resource limit */
    GLPGP_ERR_CANCELLED   /* stopped by the caller (glpgp_options.cancel: Ctrl-C in Python) */
} glpgp_status;

/* Human-readable name of a status ("mesh error", ...). Never NULL. */
const char *glpgp_status_name(glpgp_status st);

/* ---- error record (thread-local) ----------------------------------------
 * The first error recorded since the last glpgp_error_clear() sets the
 * message; every later record or trace point appends a trace line
 * "at FILE:LINE" (FILE relative to the source tree). */

/* Record an error (formats the message). Returns st, for `return GLPGP_FAIL(...)`. */
glpgp_status glpgp_error_set(const char *file, int line, glpgp_status st, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
/* Append a trace line (used by GLPGP_CHECK). */
void glpgp_error_push_trace(const char *file, int line);
/* The message of the first error ("" when none): one line, no trace. */
const char *glpgp_error_message(void);
/* The status of the first error (GLPGP_OK when none). */
glpgp_status glpgp_error_status(void);
/* Attach a multi-line detail to the current error (e.g. an OpenCL build
 * log; kept to its first 8 KiB). Replaces an earlier detail. */
void glpgp_error_set_detail(const char *text);
/* The detail ("" when none). */
const char *glpgp_error_detail(void);
/* The trace lines ("" when none), each "  at FILE:LINE\n". */
const char *glpgp_error_trace(void);
void glpgp_error_clear(void);

/* An error record carried from one thread to another: a worker thread saves
 * its record before it ends, the thread that joins it restores the record as
 * its own (replacing the one it had) and returns its status. */
typedef struct glpgp_error_copy {
    glpgp_status st;
    char msg[1024];
    char trace[2048];
    char detail[8192];
} glpgp_error_copy;
void glpgp_error_save(glpgp_error_copy *out);
glpgp_status glpgp_error_restore(const glpgp_error_copy *in);

/* return GLPGP_FAIL(GLPGP_ERR_MESH, "triangle %d is degenerate", t); */
#define GLPGP_FAIL(st, ...) glpgp_error_set(__FILE__, __LINE__, (st), __VA_ARGS__)

/* Propagate a failing status, recording where it passed through. */
#define GLPGP_CHECK(call)                                  \
    do {                                                   \
        glpgp_status glpgp_st_ = (call);                   \
        if (glpgp_st_ != GLPGP_OK) {                       \
            glpgp_error_push_trace(__FILE__, __LINE__);    \
            return glpgp_st_;                              \
        }                                                  \
    } while (0)

/* Same, but jump to a cleanup label after storing the status in `st`. */
#define GLPGP_CHECK_GOTO(st, call, label)                  \
    do {                                                   \
        (st) = (call);                                     \
        if ((st) != GLPGP_OK) {                            \
            glpgp_error_push_trace(__FILE__, __LINE__);    \
            goto label;                                    \
        }                                                  \
    } while (0)

/* ---- log callback ---------------------------------------------------------
 * Library code reports progress and warnings through glpgp_log(); nothing is
 * printed unless the embedding program installs a callback (the CLI installs
 * one that writes "glpgp: ..." lines to stderr, filtered by --quiet/--verbose).
 * The callback is process-wide; it may be called from any thread that runs
 * glpgp code. */
typedef enum glpgp_log_level {
    GLPGP_LOG_WARNING = 0, /* the result may be poor or unconverged */
    GLPGP_LOG_INFO = 1,    /* progress of long runs (levels, Newton steps) */
    GLPGP_LOG_DEBUG = 2    /* details */
} glpgp_log_level;

typedef void (*glpgp_log_fn)(glpgp_log_level level, const char *message, void *user);

/* Install fn (NULL: silence). Returns nothing; the previous callback is dropped.
 * fn may be called from two threads at once (glpgp_solve runs the oscillators
 * concurrently, glpgp_options.oscillators): one whole message per call. */
void glpgp_log_set_callback(glpgp_log_fn fn, void *user);
/* Whether a callback is installed (lets callers skip expensive formatting). */
int glpgp_log_enabled(void);
/* Format and pass one message (no trailing newline needed) to the callback. */
void glpgp_log(glpgp_log_level level, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* ---- checked allocation ---------------------------------------------------- */

/* malloc/calloc that record GLPGP_ERR_NOMEM; n*size overflow checked. */
glpgp_status glpgp_malloc(size_t n, size_t size, void *out_ptr);
glpgp_status glpgp_calloc(size_t n, size_t size, void *out_ptr);
/* Grow *ptr (an array of *cap elements of elem bytes) to hold at least need
 * elements (geometric growth, new elements uninitialised). */
glpgp_status glpgp_grow(void *ptr, size_t *cap, size_t need, size_t elem);
/* free(*p) and set *p = NULL (p is a pointer to any pointer). */
void glpgp_free(void *p);

#ifdef __cplusplus
}
#endif

#endif
