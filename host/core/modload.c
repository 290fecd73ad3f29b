/* core/modload.c: glpgp_module_open (glpgp/internal/modload.h): find a module
 * in the module directories (core/module_dirs.c; the first directory that
 * holds the file wins; a file found but not loadable is an error, not a
 * reason to look further), dlopen it, look up its entry. */
#include "glpgp/internal/modload.h"
#include "glpgp/util.h"

#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

glpgp_status glpgp_module_open(const char *what, const char *file, const char *entry, int global,
                               void **entry_sym, char *why, size_t len)
{
    *entry_sym = NULL;
    glpgp_module_dirs d;
    glpgp_module_dirs_get(&d);
    char path[GLPGP_MODULE_PATH_LEN + 64];
    if (!glpgp_module_find(&d, file, path, sizeof path)) {
        char dirs[GLPGP_MODULE_MAX_DIRS * (GLPGP_MODULE_PATH_LEN + 2)] = "";
        for (int i = 0; i < d.n; i++) {
            if (i) strcat(dirs, ", ");
            strcat(dirs, d.dir[i]);
        }
        snprintf(why, len,
                 d.from_env ? "the %s module %s is not in %s ($GLPGP_MODULE_DIR)"
                            : "the %s module %s is not in %s (set GLPGP_MODULE_DIR to its directory)",
                 what, file, d.n ? dirs : "(no directory)");
        return GLPGP_ERR_IO;
    }
    /* RTLD_NOW: a missing dependency fails here, not at the first call */
    void *h = dlopen(path, RTLD_NOW | (global ? RTLD_GLOBAL : RTLD_LOCAL));
    if (!h) {
        const char *e = dlerror();
        snprintf(why, len, "cannot load the %s module %s: %s", what, path, e ? e : "dlopen failed");
        return GLPGP_ERR_IO;
    }
    void *sym = dlsym(h, entry);
    if (!sym) {
        snprintf(why, len, "cannot load the %s module %s: it has no %s (not a glpgp module)", what, path, entry);
        dlclose(h);
        return GLPGP_ERR_IO;
    }
    *entry_sym = sym;
    snprintf(why, len, "%s", path);
    return GLPGP_OK;
}
