/* fuzz_image.c: a mask image file through the image module and the mask
 * values: glpgp_image_read_limited (OpenImageIO module: the header-first
 * pixel limit, here 2^20, and the quiet stderr), glpgp_mask_values,
 * glpgp_contours. Byte 0 picks the extension (.pgm, .png, .tif, .bmp, .tga,
 * .hdr), the rest is the file. Skipped (returns at once) in builds without
 * OpenImageIO. Properties: failures give one error line; an accepted image
 * has 1 .. 2^20 pixels. The image decoders themselves are OpenImageIO's
 * and their libraries' (not instrumented here). */
#include "fuzz_common.h"

#include "glpgp/image.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    glpgp_error_clear();
    if (size < 1 || !glpgp_have_oiio()) return 0;
    static const char *const ext[6] = {".pgm", ".png", ".tif", ".bmp", ".tga", ".hdr"};
    const char *path = fuzz_write_file(data[0] % 6, ext[data[0] % 6], data + 1, size - 1);
    glpgp_image *im = (glpgp_image *)&im;
    glpgp_status st = glpgp_image_read_limited(path, 1 << 20, &im);
    if (st != GLPGP_OK) {
        FUZZ_ASSERT(im == NULL);
        fuzz_check_error(st);
        return 0;
    }
    FUZZ_ASSERT(im && im->w >= 1 && im->h >= 1 && (long long)im->w * im->h <= (1 << 20));
    float *v = NULL;
    st = glpgp_mask_values(im, &v);
    if (st == GLPGP_OK) {
        glpgp_polygons *p = NULL;
        fuzz_check_error(glpgp_contours(v, im->w, im->h, NULL, &p));
        glpgp_polygons_destroy(&p);
    }
    fuzz_check_error(st);
    free(v);
    glpgp_image_destroy(&im);
    return 0;
}
