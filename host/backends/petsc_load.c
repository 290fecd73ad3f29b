/* backends/petsc_load.c: the glpgp side of the PETSc backend (glpgp/backends.h:
 * glpgp_petsc_*, glpgp_backend_create_petsc): finds and dlopen's the module
 * glpgp_petsc.so the first time it is needed (never for other backends, so
 * `glpgp --version` and every other command load no PETSc or MPI library),
 * hands it the error record and the log, and forwards to its table.
 *
 * Search and dlopen: glpgp_module_open (core/modload.c, the same as for the
 * image modules). Loading, MPI's
 * initialisation and finalisation run under the modules' lock
 * (glpgp_module_lock): two threads asking at once load the module once. */
#include "glpgp/backends.h"
#include "glpgp/solve.h"
#include "glpgp/internal/modload.h"
#include "glpgp/util.h"

#include "petsc_module.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef GLPGP_PETSC_MODULE_FILE
#define GLPGP_PETSC_MODULE_FILE "glpgp_petsc.so"
#endif

static const glpgp_petsc_api *g_api;
static int g_tried, g_initialised;
static glpgp_status g_st = GLPGP_OK;
static char g_why[8192];

static void host_log(glpgp_log_level level, const char *msg) { glpgp_log(level, "%s", msg); }

static const glpgp_petsc_host g_host = {GLPGP_PETSC_ABI,        sizeof(glpgp_system),   sizeof(glpgp_backend),
                                        sizeof(glpgp_backend_ops), sizeof(glpgp_mesh),    sizeof(glpgp_mesh_part),
                                        glpgp_error_set,        glpgp_error_push_trace, host_log,
                                        glpgp_mesh_part_create, glpgp_mesh_destroy};

int glpgp_have_petsc(void)
{
#ifdef GLPGP_HAVE_PETSC
    return 1;
#else
    return 0;
#endif
}

/* Find and load the module (g_api; g_why set on failure). RTLD_GLOBAL: MPI's
 * own plugins (OpenMPI's mca components) dlopen later and need libmpi's
 * symbols in the global namespace. */
static void load_module(void)
{
    void *sym = NULL;
    if (glpgp_module_open("PETSc", GLPGP_PETSC_MODULE_FILE, GLPGP_PETSC_ENTRY, 1, &sym, g_why, sizeof g_why) !=
        GLPGP_OK)
        return;
    char path[sizeof g_why];
    snprintf(path, sizeof path, "%s", g_why);
    glpgp_petsc_entry_fn entry;
    memcpy(&entry, &sym, sizeof entry); /* object pointer -> function pointer, ISO C safe */
    const glpgp_petsc_api *api = entry(&g_host);
    if (!api || api->abi != GLPGP_PETSC_ABI) {
        snprintf(g_why, sizeof g_why, "cannot load the PETSc module %.4160s: it belongs to another glpgp build", path);
        return;
    }
    g_api = api;
}

static glpgp_status load_locked(void)
{
    if (g_tried) {
        if (g_api) return GLPGP_OK;
        return glpgp_error_set(__FILE__, __LINE__, g_st, "%s", g_why);
    }
    g_tried = 1;
    if (!glpgp_have_petsc()) {
        g_st = GLPGP_ERR_UNSUPPORTED;
        snprintf(g_why, sizeof g_why, "glpgp was built without PETSc (install petsc-dev and rebuild)");
        return glpgp_error_set(__FILE__, __LINE__, g_st, "%s", g_why);
    }
    g_st = GLPGP_ERR_IO;
    load_module();
    if (g_api) return GLPGP_OK;
    return glpgp_error_set(__FILE__, __LINE__, g_st, "%s", g_why);
}

static glpgp_status load(void)
{
    glpgp_module_lock();
    glpgp_status st = load_locked();
    glpgp_module_unlock();
    return st;
}

glpgp_status glpgp_petsc_init(void)
{
    GLPGP_CHECK(load());
    glpgp_module_lock();
    glpgp_status st = g_api->init();
    if (st == GLPGP_OK) {
        if (!g_initialised) atexit(glpgp_petsc_finalize); /* a caller that forgets: MPI still ends cleanly */
        g_initialised = 1;
    }
    glpgp_module_unlock();
    if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
    return st;
}

void glpgp_petsc_finalize(void)
{
    glpgp_module_lock();
    if (g_initialised && g_api) g_api->finalize();
    g_initialised = 0;
    glpgp_module_unlock();
}

int glpgp_petsc_rank(void) { return g_initialised ? g_api->rank() : 0; }
int glpgp_petsc_size(void) { return g_initialised ? g_api->size() : 1; }
int glpgp_petsc_all_ok(int ok) { return g_initialised ? g_api->all_ok(ok) : ok; }

void glpgp_petsc_gather(const double *vals, int n, double *out)
{
    if (g_initialised) g_api->gather(vals, n, out);
    else memcpy(out, vals, (size_t)n * sizeof *vals);
}

void glpgp_petsc_backend_info(const glpgp_backend *b, int *owned, int *ghosts)
{
    *owned = *ghosts = 0;
    if (g_initialised && b && b->ops && !strcmp(b->ops->name, "petsc")) g_api->local_info(b, owned, ghosts);
}

glpgp_status glpgp_petsc_mesh_send(const glpgp_mesh *m, int dest)
{
    if (!g_initialised) return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "MPI is not initialised");
    return g_api->mesh_send(m, dest);
}

glpgp_status glpgp_petsc_mesh_recv(glpgp_mesh **out)
{
    *out = NULL;
    if (!g_initialised) return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "MPI is not initialised");
    return g_api->mesh_recv(out);
}

glpgp_status glpgp_petsc_gather_bytes(const void *mine, size_t bytes, void *out)
{
    if (!g_initialised) {
        memcpy(out, mine, bytes);
        return GLPGP_OK;
    }
    return g_api->gather_bytes(mine, bytes, out);
}

double glpgp_petsc_max_rss(void) { return g_initialised ? g_api->max_rss() : 0.0; }

glpgp_status glpgp_backend_create_petsc(int precond, glpgp_backend **out)
{
    *out = NULL;
    GLPGP_CHECK(glpgp_petsc_init());
    return g_api->create(precond, out);
}
