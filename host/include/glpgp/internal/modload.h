/* glpgp/internal/modload.h: loading a dlopen'd module of glpgp (core/modload.c),
 * the one loader under the image modules (image/module.c: OpenImageIO, Gmsh)
 * and the PETSc module (backends/petsc_load.c): the file looked up in the
 * module directories (glpgp_module_dirs_get, glpgp/util.h), dlopen'd, its
 * entry symbol found; the callers keep the outcome for the process and hold
 * glpgp_module_lock() around the call, so a module is loaded once however
 * many threads ask. Internal: not installed. Layer: core. */
#ifndef GLPGP_INTERNAL_MODLOAD_H
#define GLPGP_INTERNAL_MODLOAD_H

#include "glpgp/status.h"

#include <stddef.h>

/* Load module file (what: "OpenImageIO", "PETSc", for messages) and return
 * the address of its exported entry symbol in *entry_sym. global: RTLD_GLOBAL
 * (a module whose libraries dlopen plugins needing its symbols: MPI), else
 * RTLD_LOCAL. Records no error: on failure returns GLPGP_ERR_IO with a
 * one-line reason in why[0 .. len) naming the module and the directories
 * searched (not found), or its path and dlerror() (not loadable), or the
 * missing entry (not a glpgp module); on success why holds the module's
 * path (for the caller's own messages: "belongs to another glpgp build").
 * Call under glpgp_module_lock(). */
glpgp_status glpgp_module_open(const char *what, const char *file, const char *entry, int global,
                               void **entry_sym, char *why, size_t len);

#endif
