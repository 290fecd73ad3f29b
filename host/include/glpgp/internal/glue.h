/* glpgp/internal/glue.h: the module side of glpgp's dlopen'd modules (the
 * image modules' image/shim_glue.c, the PETSc module's backends/petsc_glue.c):
 * a module defines the few glpgp functions its code calls as forwarders to
 * the table its loader hands over, so it needs no glpgp symbol of the
 * program that loads it and its errors land in the caller's record. This
 * header writes the forwarders both modules share. Internal: not installed.
 * Layer: core. */
#ifndef GLPGP_INTERNAL_GLUE_H
#define GLPGP_INTERNAL_GLUE_H

#include "glpgp/status.h"

#include <stdarg.h>
#include <stdio.h>

/* Define glpgp_error_set and glpgp_error_push_trace of a module as
 * forwarders to the loader's table *HOST (its members error_set and
 * push_trace): the message is formatted here (the host's record holds 1024
 * bytes) and passed on as "%s". */
#define GLPGP_GLUE_ERRORS(HOST)                                                                  \
    glpgp_status glpgp_error_set(const char *file, int line, glpgp_status st, const char *fmt, ...) \
    {                                                                                            \
        char msg[1024];                                                                          \
        va_list ap;                                                                              \
        va_start(ap, fmt);                                                                       \
        vsnprintf(msg, sizeof msg, fmt, ap);                                                     \
        va_end(ap);                                                                              \
        return (HOST)->error_set(file, line, st, "%s", msg);                                     \
    }                                                                                            \
    void glpgp_error_push_trace(const char *file, int line) { (HOST)->push_trace(file, line); }

#endif
