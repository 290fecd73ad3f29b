/* test_render3d.c: pictures of a surface's result (image/render3d.c, in
 * memory, no OpenImageIO): a sphere's GL-PGP result drawn from the default
 * camera fills a disc (background in the corners, shaded surface at the
 * center, darker towards the rim), carries grid lines of both oscillators
 * (bluish and reddish pixels), marks the cross field's singularities (pure
 * red dots); the camera moves the picture; the hidden half is hidden (a
 * singularity behind the sphere is not drawn); kinds without a 3D form are
 * refused. */
#include "testutil.h"

#include <string.h>

static const float *px(const glpgp_image *im, int i, int j) { return im->px + 4 * ((size_t)j * im->w + (size_t)i); }

int main(void)
{
    glpgp_mesh *m = NULL;
    glpgp_backend *b = NULL;
    glpgp_result *r = NULL;
    glpgp_options o;
    glpgp_options_default(&o);
    o.field = GLPGP_FIELD_CROSS;
    CHECK_OK(glpgp_mesh_generate("sphere", 6000, &m));
    CHECK_OK(glpgp_backend_create_reference(&b));
    if (!m || !b) TEST_DONE();
    CHECK_OK(glpgp_solve(m, b, &o, &r));
    if (!r) TEST_DONE();
    glpgp_render_options ro;
    glpgp_render_options_default(&ro);
    ro.size = 256;
    glpgp_image *im = NULL, *im2 = NULL;
    CHECK_OK(glpgp_render(m, r, &ro, &im));
    if (!im) TEST_DONE();
    CHECK(im->w == 256 && im->h == 256 && im->nc == 4);
    const float *c0 = px(im, 1, 1), *cc = px(im, 128, 128), *rim = px(im, 128, 12);
    CHECK(c0[0] == 1.0f && c0[1] == 1.0f && c0[2] == 1.0f);
    CHECK(cc[0] < 0.999f && cc[0] > 0.3f);
    CHECK(rim[0] + rim[1] + rim[2] < cc[0] + cc[1] + cc[2]); /* shaded towards the rim */
    int blue = 0, brown = 0, red = 0;
    for (int j = 0; j < im->h; j++)
        for (int i = 0; i < im->w; i++) {
            const float *p = px(im, i, j);
            blue += p[2] > p[0] + 0.15f;
            brown += p[0] > p[2] + 0.25f && p[1] < 0.6f;
            red += p[0] > 0.8f && p[1] < 0.15f && p[2] < 0.15f;
        }
    printf("sphere: %d bluish, %d brownish, %d red pixels (cross singularities %d)\n", blue, brown, red,
           r->cross ? r->cross->nsing : -1);
    CHECK(blue > 200 && brown > 200);
    CHECK(red > 10);
    /* another camera: another picture; from the opposite side the red dots differ */
    ro.azimuth = 215.0;
    ro.elevation = -25.0;
    CHECK_OK(glpgp_render(m, r, &ro, &im2));
    if (im2) {
        long diff = 0;
        for (size_t k = 0; k < (size_t)4 * im->w * im->h; k++) diff += fabsf(im->px[k] - im2->px[k]) > 0.2f;
        CHECK(diff > 1000);
    }
    glpgp_image_destroy(&im2);
    /* kinds without a 3D form */
    ro.kind = GLPGP_IMAGE_FIELD;
    glpgp_error_clear();
    CHECK(glpgp_render(m, r, &ro, &im2) == GLPGP_ERR_ARG && im2 == NULL);
    glpgp_error_clear();
    ro.kind = GLPGP_IMAGE_GRID;
    ro.elevation = 120.0;
    CHECK(glpgp_render(m, r, &ro, &im2) == GLPGP_ERR_ARG && im2 == NULL);
    glpgp_error_clear();
    glpgp_image_destroy(&im);
    glpgp_result_destroy(&r);
    glpgp_backend_destroy(&b);
    glpgp_mesh_destroy(&m);
    TEST_DONE();
}
