/* core/module_dirs.c: where glpgp's dlopen'd modules are looked for
 * (glpgp/util.h: glpgp_module_dirs_get, glpgp_module_find), one search for
 * the image modules (image/module.c) and the PETSc backend module
 * (backends/petsc_load.c): $GLPGP_MODULE_DIR alone when set; otherwise
 * <directory of the executable>/GLPGP_MODULE_EXE_REL, then, when glpgp's
 * code is in a shared object other than the executable (the Python
 * extension, glpgp/_glpgp*.so), <its directory>/modules, then
 * GLPGP_MODULE_INSTALL_DIR, then GLPGP_MODULE_BUILD_DIR (compile
 * definitions from host/CMakeLists.txt); and the one lock every module
 * loader holds while it loads (glpgp_module_lock). */
#define _GNU_SOURCE /* dladdr */
#include "glpgp/util.h"

#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef GLPGP_MODULE_EXE_REL
#define GLPGP_MODULE_EXE_REL "../lib/glpgp"
#endif

/* the modules' lock: the only mutable static, a lock */
static pthread_mutex_t g_module_lock = PTHREAD_MUTEX_INITIALIZER;

void glpgp_module_lock(void) { pthread_mutex_lock(&g_module_lock); }
void glpgp_module_unlock(void) { pthread_mutex_unlock(&g_module_lock); }

static void add_dir(glpgp_module_dirs *d, const char *dir)
{
    if (!dir || !*dir || d->n >= GLPGP_MODULE_MAX_DIRS || strlen(dir) >= GLPGP_MODULE_PATH_LEN) return;
    for (int i = 0; i < d->n; i++)
        if (!strcmp(d->dir[i], dir)) return;
    strcpy(d->dir[d->n++], dir);
}

void glpgp_module_dirs_get(glpgp_module_dirs *d)
{
    memset(d, 0, sizeof *d);
    const char *env = getenv("GLPGP_MODULE_DIR");
    if (env && *env) {
        d->from_env = 1;
        add_dir(d, env);
        return;
    }
    /* <exe dir>/<rel>: /proc/self/exe is canonical, so a leading "../" of rel
     * is resolved by dropping the last component of the directory */
    char exe[GLPGP_MODULE_PATH_LEN];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = '\0';
            const char *rel = GLPGP_MODULE_EXE_REL;
            while (!strncmp(rel, "../", 3) && (slash = strrchr(exe, '/')) != NULL) {
                *slash = '\0';
                rel += 3;
            }
            char dir[GLPGP_MODULE_PATH_LEN];
            if (snprintf(dir, sizeof dir, "%s/%s", exe, rel) < (int)sizeof dir) add_dir(d, dir);
        }
    }
    /* the shared object that holds this code, when it is not the executable:
     * the Python package keeps its modules beside its extension */
    Dl_info info;
    char obj[PATH_MAX], self[PATH_MAX];
    if (dladdr((void *)glpgp_module_dirs_get, &info) && info.dli_fname && realpath(info.dli_fname, obj) &&
        (!realpath("/proc/self/exe", self) || strcmp(obj, self) != 0)) {
        char *slash = strrchr(obj, '/');
        char dir[GLPGP_MODULE_PATH_LEN];
        if (slash) {
            *slash = '\0';
            if (snprintf(dir, sizeof dir, "%s/modules", obj) < (int)sizeof dir) add_dir(d, dir);
        }
    }
#ifdef GLPGP_MODULE_INSTALL_DIR
    add_dir(d, GLPGP_MODULE_INSTALL_DIR);
#endif
#ifdef GLPGP_MODULE_BUILD_DIR
    add_dir(d, GLPGP_MODULE_BUILD_DIR);
#endif
}

int glpgp_module_find(const glpgp_module_dirs *d, const char *file, char *path, size_t len)
{
    for (int i = 0; i < d->n; i++) {
        if (snprintf(path, len, "%s/%s", d->dir[i], file) >= (int)len) continue;
        if (access(path, F_OK) == 0) return 1;
    }
    return 0;
}
