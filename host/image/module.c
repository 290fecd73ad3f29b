/* image/module.c: finding and loading the image layer's modules (image/module.h)
 * on first use, and the public glpgp_oiio_load / glpgp_gmsh_load.
 *
 * Search (glpgp_module_dirs_get, core/module_dirs.c, shared with the PETSc
 * module; the first directory that holds the module file wins; a file found
 * but not loadable is an error, not a reason to look further):
 *   1. $GLPGP_MODULE_DIR when set and not empty: that directory only;
 *   2. the install location relative to the running executable,
 *      <dir of /proc/self/exe>/GLPGP_MODULE_EXE_REL (e.g. bin/../lib/glpgp);
 *   3. the configured install directory GLPGP_MODULE_INSTALL_DIR (programs
 *      outside the prefix's bin/ linking the installed libraries);
 *   4. the build tree, GLPGP_MODULE_BUILD_DIR (tests, build/glpgp).
 * Nothing here dlopen's anything before a function needs the module; the
 * outcome (table or error text) is kept for the life of the process. */
#include "module.h"

#include "glpgp/internal/modload.h"
#include "glpgp/util.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef GLPGP_OIIO_MODULE_FILE
#define GLPGP_OIIO_MODULE_FILE "glpgp_oiio.so"
#endif
#ifndef GLPGP_GMSH_MODULE_FILE
#define GLPGP_GMSH_MODULE_FILE "glpgp_gmsh.so"
#endif

#ifdef GLPGP_HAVE_OIIO
#define OIIO_BUILT 1
#else
#define OIIO_BUILT 0
#endif
#ifdef GLPGP_HAVE_GMSH
#define GMSH_BUILT 1
#else
#define GMSH_BUILT 0
#endif

enum { PATH_LEN = GLPGP_MODULE_PATH_LEN };

typedef struct module_slot {
    const char *what;    /* "OpenImageIO" */
    const char *file;    /* "glpgp_oiio.so" */
    const char *entry;   /* exported symbol */
    const char *package; /* Debian package to build with */
    int built;
    int state;           /* 0 not tried, 1 loaded, -1 failed */
    const void *api;
    glpgp_status st;
    char why[3 * PATH_LEN];
} module_slot;

static module_slot g_slots[2] = {
    {"OpenImageIO", GLPGP_OIIO_MODULE_FILE, GLPGP_OIIO_ENTRY, "libopenimageio-dev", OIIO_BUILT, 0,
     NULL, GLPGP_OK, ""},
    {"Gmsh", GLPGP_GMSH_MODULE_FILE, GLPGP_GMSH_ENTRY, "libgmsh-dev", GMSH_BUILT, 0, NULL,
     GLPGP_OK, ""},
};

static const glpgp_module_host g_host = {
    GLPGP_MODULE_ABI,     sizeof(glpgp_image),  sizeof(glpgp_polygons), glpgp_error_set,
    glpgp_error_push_trace, glpgp_malloc,       glpgp_image_create,     glpgp_image_destroy,
};

static void slot_fail(module_slot *s, glpgp_status st, const char *fmt, const char *a, const char *b)
{
    s->state = -1;
    s->st = st;
    snprintf(s->why, sizeof s->why, fmt, s->what, a, b);
}

/* Load s (under g_lock). */
static void slot_load(module_slot *s)
{
    if (!s->built) {
        s->state = -1;
        s->st = GLPGP_ERR_UNSUPPORTED;
        snprintf(s->why, sizeof s->why,
                 "this glpgp was built without %s (install %s and rebuild)", s->what, s->package);
        return;
    }
    void *sym = NULL;
    glpgp_status st = glpgp_module_open(s->what, s->file, s->entry, 0, &sym, s->why, sizeof s->why);
    if (st != GLPGP_OK) { /* RTLD_LOCAL: OpenImageIO, libstdc++, Gmsh stay out of the global namespace */
        s->state = -1;
        s->st = st;
        return;
    }
    char path[sizeof s->why];
    snprintf(path, sizeof path, "%s", s->why);
    glpgp_module_entry_fn entry;
    memcpy(&entry, &sym, sizeof entry); /* object pointer -> function pointer, ISO C safe */
    const void *api = entry(&g_host);
    if (!api || *(const int *)api != GLPGP_MODULE_ABI) {
        slot_fail(s, GLPGP_ERR_IO,
                  "cannot load the %s module %.4160s: it belongs to another glpgp build (%s)", path,
                  "module interface version mismatch");
        /* not dlclose'd: the entry ran code of the module */
        return;
    }
    s->api = api;
    s->state = 1;
}

static glpgp_status slot_get(module_slot *s, const void **api, const char **why)
{
    glpgp_module_lock();
    if (s->state == 0) slot_load(s);
    glpgp_status st = s->state == 1 ? GLPGP_OK : s->st;
    *api = s->api;
    if (why) *why = s->why;
    glpgp_module_unlock();
    return st;
}

glpgp_status glpgp_oiio_module_get(const glpgp_oiio_api **api, const char **why)
{
    const void *a = NULL;
    glpgp_status st = slot_get(&g_slots[0], &a, why);
    *api = (const glpgp_oiio_api *)a;
    return st;
}

glpgp_status glpgp_gmsh_module_get(const glpgp_gmsh_api **api, const char **why)
{
    const void *a = NULL;
    glpgp_status st = slot_get(&g_slots[1], &a, why);
    *api = (const glpgp_gmsh_api *)a;
    return st;
}

int glpgp_module_available(int gmsh)
{
    module_slot *s = &g_slots[gmsh ? 1 : 0];
    if (!s->built) return 0;
    glpgp_module_lock();
    int state = s->state;
    glpgp_module_unlock();
    if (state != 0) return state == 1;
    glpgp_module_dirs d;
    glpgp_module_dirs_get(&d);
    char path[PATH_LEN + 64];
    return glpgp_module_find(&d, s->file, path, sizeof path);
}

glpgp_status glpgp_oiio_load(void)
{
    const glpgp_oiio_api *api;
    const char *why = "";
    glpgp_status st = glpgp_oiio_module_get(&api, &why);
    return st == GLPGP_OK ? GLPGP_OK : GLPGP_FAIL(st, "%s", why);
}

glpgp_status glpgp_gmsh_load(void)
{
    const glpgp_gmsh_api *api;
    const char *why = "";
    glpgp_status st = glpgp_gmsh_module_get(&api, &why);
    return st == GLPGP_OK ? GLPGP_OK : GLPGP_FAIL(st, "%s", why);
}

int glpgp_have_oiio(void) { return glpgp_module_available(0); }

int glpgp_have_gmsh(void) { return glpgp_module_available(1); }
