/* image_io.h: the C interface of glpgp's image I/O. The implementation is the
 * only C++ file of the project, host/image_oiio.cpp, a thin shim over
 * OpenImageIO that catches every exception; builds without OpenImageIO get
 * the stubs in host/image.c instead, whose functions fail with GLPGP_ERR_UNSUPPORTED
 * ("built without OpenImageIO"). Pixel buffers are float, row-major, the top
 * row first, channels interleaved. */
#ifndef GLPGP_IMAGE_IO_H
#define GLPGP_IMAGE_IO_H

#ifdef __cplusplus
extern "C" { /* status.h has no C++ guards of its own */
#endif

#include "status.h"

/* An image in memory: w x h pixels, nc interleaved float channels. */
typedef struct glpgp_image {
    int w, h, nc;
    int alpha;  /* index of the alpha channel, -1 when none */
    float *px;  /* w * h * nc values; integer formats are scaled to [0, 1] */
} glpgp_image;

/* Whether this build has OpenImageIO (1) or not (0). */
int glpgp_have_oiio(void);

/* Read the first subimage of any format OpenImageIO reads (PNG, TIFF, EXR,
 * JPEG, PNM, ...), any bit depth and channel count, converted to float.
 * Unreadable or missing file -> GLPGP_ERR_IO; a zero-size image ->
 * GLPGP_ERR_FORMAT; no OpenImageIO -> GLPGP_ERR_UNSUPPORTED. Free the result
 * with glpgp_image_destroy. */
glpgp_status glpgp_image_read(const char *path, glpgp_image **out);

/* Write im to path; the format follows the extension (.png, .tif/.tiff,
 * .exr, .jpg/.jpeg, .ppm, ... whatever OpenImageIO writes). im->px holds
 * straight (not premultiplied) colour in [0, 1]; nc is 1 (grey), 3 (RGB) or
 * 4 (RGBA, alpha last). 8-bit formats are written as UINT8 (PNG, JPEG,
 * TIFF), EXR as HALF. A format without alpha (JPEG) gets the image composited
 * over white. Atomic: written to "<stem>.tmp.<pid>.<ext>" in the same
 * directory and renamed over path on success; on failure nothing is left and
 * an existing path is untouched (GLPGP_ERR_IO; an unknown extension ->
 * GLPGP_ERR_ARG). */
glpgp_status glpgp_image_write(const char *path, const glpgp_image *im);

/* Whether OpenImageIO can write files with the extension of path (0 without
 * OpenImageIO). For validating command lines before a long computation. */
int glpgp_image_path_writable(const char *path);

/* Allocate a w x h x nc image filled with zeros (alpha = nc == 4 ? 3 : -1). */
glpgp_status glpgp_image_create(int w, int h, int nc, glpgp_image **out);
void glpgp_image_destroy(glpgp_image **im);

/* Whether path ends in an image extension glpgp treats as a mask/picture
 * (.png .tif .tiff .exr .jpg .jpeg .bmp .pgm .ppm .pnm .tga .gif .webp .hdr),
 * case-insensitive. Independent of OpenImageIO being built in. */
int glpgp_is_image_path(const char *path);

#ifdef __cplusplus
}
#endif

#endif
