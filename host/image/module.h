/* image/module.h: the binary interface between the image layer and its two
 * dlopen'd modules (private to host/image/):
 *   glpgp_oiio.so  image/oiio_shim.cpp + image/shim_glue.c, links OpenImageIO
 *   glpgp_gmsh.so  image/gmsh_shim.c  + image/shim_glue.c, links Gmsh
 * so that a glpgp process loads OpenImageIO (a C++ library with ~300
 * dependencies) and Gmsh only when a function needs them (image/module.c).
 *
 * Protocol: the image layer dlopen's the module (RTLD_NOW | RTLD_LOCAL), looks
 * up its one exported symbol (GLPGP_OIIO_ENTRY / GLPGP_GMSH_ENTRY) and calls it
 * with the host table; the module keeps the host table (shim_glue.c routes
 * its glpgp_error_set, glpgp_error_push_trace, glpgp_malloc,
 * glpgp_image_create and glpgp_image_destroy through it, so errors land in the
 * caller's thread-local error record and buffers come from the caller's
 * allocator) and returns its function table, or NULL when host->abi differs.
 * Modules are never unloaded. Bump GLPGP_MODULE_ABI whenever a struct here or
 * a struct passed through it (glpgp_image, glpgp_polygons) changes. */
#ifndef GLPGP_IMAGE_MODULE_H
#define GLPGP_IMAGE_MODULE_H

#include "glpgp/image.h"
#include "glpgp/status.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define GLPGP_MODULE_ABI 3 /* 2: read takes max_pixels; 3: glpgp_polygons.size */

/* What the image layer lends a module. */
typedef struct glpgp_module_host {
    int abi;          /* GLPGP_MODULE_ABI */
    size_t sizeof_image, sizeof_polygons; /* cross-checks of the struct layouts */
    glpgp_status (*error_set)(const char *file, int line, glpgp_status st, const char *fmt, ...);
    void (*push_trace)(const char *file, int line);
    glpgp_status (*malloc_checked)(size_t n, size_t size, void *out_ptr);
    glpgp_status (*image_create)(int w, int h, int nc, glpgp_image **out);
    void (*image_destroy)(glpgp_image **im);
} glpgp_module_host;

/* glpgp_oiio.so: the image I/O of glpgp/image.h (same contracts; read is
 * glpgp_image_read_limited with max_pixels > 0). The image library's own
 * messages (libpng writes "libpng error: ..." lines on stderr) are kept off
 * stderr: file descriptor 2 points to /dev/null during every call into it
 * (not thread-safe with respect to other threads writing to stderr at that
 * moment; the CLI has none). */
typedef struct glpgp_oiio_api {
    int abi; /* GLPGP_MODULE_ABI */
    glpgp_status (*read)(const char *path, long long max_pixels, glpgp_image **out);
    glpgp_status (*write)(const char *path, const glpgp_image *im);
    int (*path_writable)(const char *path);
} glpgp_oiio_api;

/* glpgp_gmsh.so: polygons -> triangles. mesh_polygons meshes p with uniform
 * size mesh_size (> 0) and Gmsh algorithm algorithm (> 0) and returns the nv
 * vertices (*xy, 2 nv doubles) and nt triangles (*tri, 3 nt indices into the
 * vertices, every vertex used) in buffers from host->malloc_checked (release
 * with free()); every Gmsh error becomes GLPGP_ERR_MESH with Gmsh's message. */
typedef struct glpgp_gmsh_api {
    int abi; /* GLPGP_MODULE_ABI */
    glpgp_status (*mesh_polygons)(const glpgp_polygons *p, double mesh_size, int algorithm,
                                  int *nv, double **xy, int *nt, int **tri);
} glpgp_gmsh_api;

/* The exported entry points: `const T *NAME(const glpgp_module_host *host)`. */
#define GLPGP_OIIO_ENTRY "glpgp_oiio_module"
#define GLPGP_GMSH_ENTRY "glpgp_gmsh_module"
typedef const void *(*glpgp_module_entry_fn)(const glpgp_module_host *host);

#if defined(__GNUC__)
#define GLPGP_MODULE_EXPORT __attribute__((visibility("default")))
#else
#define GLPGP_MODULE_EXPORT
#endif

/* Module side (image/shim_glue.c): keep host for the forwarding functions.
 * Returns 0 (and the module must return NULL) when host is NULL or speaks
 * another ABI. */
int glpgp_module_glue_init(const glpgp_module_host *host);

/* Image-layer side (image/module.c): the function table of a module, loading
 * it on first use (thread-safe; the outcome is kept for the process). Records
 * no error: on failure *why is the reason, one line for the caller's message:
 * GLPGP_ERR_UNSUPPORTED "this glpgp was built without ..." when the module was
 * not built; GLPGP_ERR_IO naming the module and the directories searched when
 * it is not found, or its path and dlerror() when it does not load. */
glpgp_status glpgp_oiio_module_get(const glpgp_oiio_api **api, const char **why);
glpgp_status glpgp_gmsh_module_get(const glpgp_gmsh_api **api, const char **why);

/* Whether the module was built and its file is in the search path (no dlopen). */
int glpgp_module_available(int gmsh);

#ifdef __cplusplus
}
#endif

#endif
