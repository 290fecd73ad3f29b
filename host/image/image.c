/* image/image.c: the plain-C half of the image I/O of glpgp/image.h: image
 * buffers (create/destroy), the image-extension test, and glpgp_image_read,
 * glpgp_image_write and glpgp_image_path_writable, which load the OpenImageIO
 * module (glpgp_oiio.so, image/oiio_shim.cpp) on first use through
 * image/module.c and fail with its reason ("built without OpenImageIO", module
 * not found, not loadable) when it cannot be had. */
#include "glpgp/util.h"
#include "glpgp/image.h"
#include "module.h"

#include <stdlib.h>
#include <string.h>

glpgp_status glpgp_image_create(int w, int h, int nc, glpgp_image **out)
{
    if (!out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_image_create: NULL output");
    *out = NULL;
    if (w <= 0 || h <= 0 || nc <= 0 || nc > 64)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "invalid image size %d x %d x %d", w, h, nc);
    glpgp_image *im = NULL;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *im, &im));
    size_t n = (size_t)w * (size_t)h;
    if (n > ((size_t)-1) / sizeof(float) / (size_t)nc) {
        free(im);
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "image %d x %d x %d too large", w, h, nc);
    }
    glpgp_status st = glpgp_calloc(n * (size_t)nc, sizeof(float), &im->px);
    if (st != GLPGP_OK) {
        free(im);
        glpgp_error_push_trace(__FILE__, __LINE__);
        return st;
    }
    im->w = w;
    im->h = h;
    im->nc = nc;
    im->alpha = nc == 4 || nc == 2 ? nc - 1 : -1;
    *out = im;
    return GLPGP_OK;
}

void glpgp_image_destroy(glpgp_image **im)
{
    if (!im || !*im) return;
    free((*im)->px);
    free(*im);
    *im = NULL;
}

glpgp_status glpgp_image_read_limited(const char *path, long long max_pixels, glpgp_image **out)
{
    if (!path || !out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_image_read: NULL argument");
    *out = NULL;
    const glpgp_oiio_api *api;
    const char *why;
    glpgp_status st = glpgp_oiio_module_get(&api, &why);
    if (st != GLPGP_OK) return GLPGP_FAIL(st, "cannot read image '%s': %s", path, why);
    GLPGP_CHECK(api->read(path, max_pixels > 0 ? max_pixels : GLPGP_DEFAULT_MAX_PIXELS, out));
    return GLPGP_OK;
}

glpgp_status glpgp_image_read(const char *path, glpgp_image **out)
{
    GLPGP_CHECK(glpgp_image_read_limited(path, 0, out));
    return GLPGP_OK;
}

glpgp_status glpgp_image_write(const char *path, const glpgp_image *im)
{
    if (!path || !*path) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_image_write: empty path");
    const glpgp_oiio_api *api;
    const char *why;
    glpgp_status st = glpgp_oiio_module_get(&api, &why);
    if (st != GLPGP_OK) return GLPGP_FAIL(st, "cannot write image '%s': %s", path, why);
    GLPGP_CHECK(api->write(path, im));
    return GLPGP_OK;
}

int glpgp_image_path_writable(const char *path)
{
    const glpgp_oiio_api *api;
    const char *why;
    if (!path || glpgp_oiio_module_get(&api, &why) != GLPGP_OK) return 0;
    return api->path_writable(path);
}
