/* status.c: error recording for glpgp_status (message + file:line trace). */
#include "status.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char g_msg[4096];
static size_t g_len;

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
    }
    return "unknown error";
}

static void append(const char *fmt, ...)
{
    if (g_len >= sizeof g_msg - 1) return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(g_msg + g_len, sizeof g_msg - g_len, fmt, ap);
    va_end(ap);
    if (n > 0) g_len += (size_t)n;
    if (g_len > sizeof g_msg - 1) g_len = sizeof g_msg - 1;
}

glpgp_status glpgp_error_set(const char *file, int line, glpgp_status st, const char *fmt, ...)
{
    if (g_len == 0) {
        va_list ap;
        va_start(ap, fmt);
        int n = vsnprintf(g_msg, sizeof g_msg, fmt, ap);
        va_end(ap);
        g_len = n > 0 ? (size_t)n : 0;
        if (g_len > sizeof g_msg - 1) g_len = sizeof g_msg - 1;
        append("\n  [%s] at %s:%d", glpgp_status_name(st), file, line);
    } else {
        append("\n  (then) at %s:%d", file, line);
    }
    return st;
}

void glpgp_error_trace(const char *file, int line) { append("\n  at %s:%d", file, line); }

const char *glpgp_error_message(void) { return g_msg; }

void glpgp_error_clear(void)
{
    g_len = 0;
    g_msg[0] = '\0';
}

glpgp_status glpgp_malloc(size_t n, size_t size, void *out_ptr)
{
    void **out = (void **)out_ptr;
    *out = NULL;
    if (size && n > SIZE_MAX / size)
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "allocation of %zu x %zu bytes overflows", n, size);
    *out = malloc((n * size) != 0 ? n * size : 1);
    if (!*out) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory allocating %zu bytes", n * size);
    return GLPGP_OK;
}

glpgp_status glpgp_calloc(size_t n, size_t size, void *out_ptr)
{
    void **out = (void **)out_ptr;
    *out = NULL;
    *out = calloc(n ? n : 1, size ? size : 1);
    if (!*out) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory allocating %zu x %zu bytes", n, size);
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
