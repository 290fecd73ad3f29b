/* core/status.c: the thread-local error record (message + trace), the log
 * callback and the checked allocation helpers of glpgp/status.h. */
#if defined(__linux__) && !defined(_DEFAULT_SOURCE)
#define _DEFAULT_SOURCE /* madvise */
#endif
#include "glpgp/status.h"
#include "glpgp/util.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#if defined(__linux__)
#include <sys/mman.h>
#endif

/* One record per thread: a library used from several threads keeps their
 * errors apart. */
typedef struct error_record {
    glpgp_status st;
    char msg[1024];
    char trace[2048];
    size_t tlen;
    char detail[8192];
} error_record;

static _Thread_local error_record g_err;

const char *glpgp_status_name(glpgp_status st)
{
    switch (st) {
    case GLPGP_OK: return "ok";
    case GLPGP_ERR_ARG: return "invalid argument";
    case GLPGP_ERR_IO: return "I/O error";
    case GLPGP_ERR_FORMAT: return "format error";
    case GLPGP_ERR_MESH: return "mesh error";
    case GLPGP_ERR_NOMEM: return "out of memory";
    case GLPGP_ERR_NUMERIC: return "numerical failure";
    case GLPGP_ERR_OPENCL: return "OpenCL error";
    case GLPGP_ERR_UNSUPPORTED: return "unsupported";
    case GLPGP_ERR_LIMIT: return "resource limit";
    case GLPGP_ERR_CANCELLED: return "cancelled";
    }
    return "unknown error";
}

static void trace_append(const char *fmt, ...)
{
    error_record *e = &g_err;
    if (e->tlen >= sizeof e->trace - 1) return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(e->trace + e->tlen, sizeof e->trace - e->tlen, fmt, ap);
    va_end(ap);
    if (n > 0) e->tlen += (size_t)n;
    if (e->tlen > sizeof e->trace - 1) e->tlen = sizeof e->trace - 1;
}

glpgp_status glpgp_error_set(const char *file, int line, glpgp_status st, const char *fmt, ...)
{
    error_record *e = &g_err;
    if (e->st == GLPGP_OK) {
        va_list ap;
        va_start(ap, fmt);
        glpgp_vsnprintf(e->msg, sizeof e->msg, fmt, ap);
        va_end(ap);
        /* the message is one line: later lines of a formatted text are dropped */
        e->msg[strcspn(e->msg, "\n")] = '\0';
        e->st = st == GLPGP_OK ? GLPGP_ERR_ARG : st;
        trace_append("  [%s] at %s:%d\n", glpgp_status_name(st), file, line);
    } else {
        trace_append("  (then) at %s:%d\n", file, line);
    }
    return st;
}

void glpgp_error_push_trace(const char *file, int line) { trace_append("  at %s:%d\n", file, line); }

const char *glpgp_error_message(void) { return g_err.msg; }

glpgp_status glpgp_error_status(void) { return g_err.st; }

const char *glpgp_error_trace(void) { return g_err.trace; }

void glpgp_error_set_detail(const char *text)
{
    snprintf(g_err.detail, sizeof g_err.detail, "%s", text ? text : "");
}

const char *glpgp_error_detail(void) { return g_err.detail; }

void glpgp_error_clear(void)
{
    error_record *e = &g_err;
    e->st = GLPGP_OK;
    e->msg[0] = '\0';
    e->trace[0] = '\0';
    e->tlen = 0;
    e->detail[0] = '\0';
}

/* the copy holds the record's texts whole */
_Static_assert(sizeof(((glpgp_error_copy *)0)->msg) == sizeof g_err.msg &&
                   sizeof(((glpgp_error_copy *)0)->trace) == sizeof g_err.trace &&
                   sizeof(((glpgp_error_copy *)0)->detail) == sizeof g_err.detail,
               "glpgp_error_copy and the error record differ");

void glpgp_error_save(glpgp_error_copy *out)
{
    const error_record *e = &g_err;
    out->st = e->st;
    memcpy(out->msg, e->msg, sizeof out->msg);
    memcpy(out->trace, e->trace, sizeof out->trace);
    memcpy(out->detail, e->detail, sizeof out->detail);
}

glpgp_status glpgp_error_restore(const glpgp_error_copy *in)
{
    error_record *e = &g_err;
    e->st = in->st;
    memcpy(e->msg, in->msg, sizeof e->msg);
    memcpy(e->trace, in->trace, sizeof e->trace);
    memcpy(e->detail, in->detail, sizeof e->detail);
    e->msg[sizeof e->msg - 1] = e->trace[sizeof e->trace - 1] = e->detail[sizeof e->detail - 1] = '\0';
    e->tlen = strlen(e->trace);
    return e->st;
}

/* ---- log ----------------------------------------------------------------- */

static glpgp_log_fn g_log_fn;
static void *g_log_user;

void glpgp_log_set_callback(glpgp_log_fn fn, void *user)
{
    g_log_fn = fn;
    g_log_user = user;
}

int glpgp_log_enabled(void) { return g_log_fn != NULL; }

void glpgp_log(glpgp_log_level level, const char *fmt, ...)
{
    if (!g_log_fn) return;
    char buf[1024];
    va_list ap;
    va_start(ap, fmt);
    glpgp_vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    g_log_fn(level, buf, g_log_user);
}

/* ---- allocation ------------------------------------------------------------ */

/* Large arrays (a mesh's, a system's, a hierarchy's: tens to hundreds of MB
 * at millions of vertices) on transparent huge pages where the kernel offers
 * them on request (THP "madvise"): their first touch then costs one fault per
 * 2 MiB instead of one per 4 KiB (docs/numerics.md, "Where the time goes").
 * Only the 2 MiB-aligned interior is advised; free() is unchanged; a kernel
 * without THP ignores it. */
#define BIG_PAGE ((size_t)2 << 20)
#define BIG_MIN (2 * BIG_PAGE) /* the smallest array advised: one whole big page inside */
static void big_pages(void *p, size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (!p || bytes < BIG_MIN) return;
    const uintptr_t a = ((uintptr_t)p + BIG_PAGE - 1) & ~(uintptr_t)(BIG_PAGE - 1);
    const uintptr_t e = ((uintptr_t)p + bytes) & ~(uintptr_t)(BIG_PAGE - 1);
    if (e > a) (void)madvise((void *)a, e - a, MADV_HUGEPAGE);
#else
    (void)p;
    (void)bytes;
#endif
}

glpgp_status glpgp_malloc(size_t n, size_t size, void *out_ptr)
{
    void **out = (void **)out_ptr;
    *out = NULL;
    if (size && n > SIZE_MAX / size)
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "allocation of %zu x %zu bytes overflows", n, size);
    *out = malloc((n * size) != 0 ? n * size : 1);
    if (!*out) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory allocating %zu bytes", n * size);
    big_pages(*out, n * size);
    return GLPGP_OK;
}

glpgp_status glpgp_calloc(size_t n, size_t size, void *out_ptr)
{
    void **out = (void **)out_ptr;
    *out = NULL;
    if (size && n > SIZE_MAX / size)
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "allocation of %zu x %zu bytes overflows", n, size);
    const size_t bytes = n * size;
    if (bytes >= BIG_MIN) { /* advised before the zeroing touches it (calloc may memset) */
        *out = malloc(bytes);
        if (*out) {
            big_pages(*out, bytes);
            memset(*out, 0, bytes);
        }
    } else {
        *out = calloc(n ? n : 1, size ? size : 1);
    }
    if (!*out) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory allocating %zu x %zu bytes", n, size);
    return GLPGP_OK;
}

glpgp_status glpgp_grow(void *ptr, size_t *cap, size_t need, size_t elem)
{
    void **p = (void **)ptr;
    if (need <= *cap && *p) return GLPGP_OK;
    size_t nc = *cap ? *cap : 16;
    while (nc < need) {
        if (nc > SIZE_MAX / 2) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "array size overflows");
        nc *= 2;
    }
    if (elem && nc > SIZE_MAX / elem) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "array size overflows");
    void *q = realloc(*p, nc * elem);
    if (!q) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory allocating %zu bytes", nc * elem);
    big_pages(q, nc * elem);
    *p = q;
    *cap = nc;
    return GLPGP_OK;
}

void glpgp_free(void *p)
{
    void **pp = (void **)p;
    if (pp) {
        free(*pp);
        *pp = NULL;
    }
}
