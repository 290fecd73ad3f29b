/* cli/input.c: the one INPUT loader of the CLI: a built-in shape
 * (shape:NAME[:N]), a mask image (meshed through the image layer) or a
 * triangle mesh file (.obj / .msh / .stl / .ply / .off: a planar domain or a
 * surface), for every command that takes a domain. */
#include "commands.h"

#include "cli.h"
#include "glpgp/image.h"
#include "glpgp/io.h"
#include "glpgp/shapes.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

int glpgp_cli_need_images(int oiio, int gmsh)
{
    /* load the modules now: "built without ...", or the module missing or
     * not loadable, is reported before any work */
    glpgp_error_clear();
    if ((oiio && glpgp_oiio_load() != GLPGP_OK) || (gmsh && glpgp_gmsh_load() != GLPGP_OK)) {
        glpgp_cli_fail();
        return 0;
    }
    return 1;
}

int glpgp_cli_check_elements(const char *what, long count, const char *items, int approx, long max)
{
    if (max <= 0) max = GLPGP_DEFAULT_MAX_ELEMENTS;
    if (count <= max) return -1;
    glpgp_error_clear();
    GLPGP_FAIL(GLPGP_ERR_LIMIT, "%s: %s%ld %s: more than the limit of %ld (--max-elements)", what,
               approx ? "about " : "", count, items, max);
    return glpgp_cli_fail();
}

int glpgp_cli_check_picture_size(const char *cmd, int size, int panels, long long max_pixels)
{
    long long n = (long long)size * size * panels;
    if (max_pixels <= 0) max_pixels = GLPGP_DEFAULT_MAX_PIXELS;
    if (n <= max_pixels) return -1;
    return glpgp_cli_usage_error(cmd, "--image-size %d: up to %lld pixels, more than the limit of %lld "
                                      "(--max-pixels)", size, n, max_pixels);
}

int glpgp_cli_load_input(const char *cmd, const char *input, const glpgp_mask_options *mo,
                         glpgp_mesh **m, int *is_mask)
{
    return glpgp_cli_load_input_ex(cmd, input, mo, 0, m, is_mask);
}

int glpgp_cli_load_input_ex(const char *cmd, const char *input, const glpgp_mask_options *mo, int read_flags,
                            glpgp_mesh **m, int *is_mask)
{
    *m = NULL;
    if (is_mask) *is_mask = 0;
    int rc;
    if (strncmp(input, "shape:", 6) == 0) {
        char name[64];
        long nverts;
        if (glpgp_shape_parse(input, 0, name, sizeof name, &nverts) != GLPGP_OK) {
            rc = glpgp_cli_usage_error(cmd, "INPUT %s", glpgp_error_message());
            glpgp_error_clear();
            return rc;
        }
        /* a built-in shape has about 2 triangles per vertex */
        if ((rc = glpgp_cli_check_elements(input, 2 * nverts, "triangles", 1, mo->max_triangles)) >= 0)
            return rc;
        if (glpgp_mesh_generate(name, nverts, m) != GLPGP_OK) return glpgp_cli_fail();
        return -1;
    }
    const int remesh = mo->remesh && (glpgp_has_ext(input, ".obj") || glpgp_has_ext(input, ".msh") || glpgp_has_ext(input, ".stl"));
    if (glpgp_is_image_path(input) || glpgp_is_poly_path(input) || remesh) {
        if (!glpgp_cli_need_images(!glpgp_is_poly_path(input) && !remesh, 1)) return GLPGP_EXIT_FAIL;
        glpgp_mask_info inf;
        if (glpgp_mask_mesh(input, mo, m, &inf) != GLPGP_OK) return glpgp_cli_fail();
        if (is_mask) *is_mask = 1;
        char what[64];
        if (inf.width > 0) snprintf(what, sizeof what, "%d x %d mask", inf.width, inf.height);
        else snprintf(what, sizeof what, "%s", remesh ? "remeshed" : "polygons");
        glpgp_log(GLPGP_LOG_INFO, "%s: %s -> %d vertices, %d triangles (%d hole%s, mesh size %.4g, %.2f s)", input,
                  what, (*m)->nv, (*m)->nt, inf.nholes, inf.nholes == 1 ? "" : "s", inf.mesh_size,
                  inf.seconds_read + inf.seconds_contour + inf.seconds_mesh);
        return -1;
    }
    if (glpgp_mesh_read_ex(input, read_flags, m) != GLPGP_OK) return glpgp_cli_fail();
    if ((rc = glpgp_cli_check_elements(input, (*m)->nt, "triangles", 0, mo->max_triangles)) >= 0) {
        glpgp_mesh_destroy(m);
        return rc;
    }
    return -1;
}

int glpgp_cli_check_output(const char *cmd, const char *opt, const char *path,
                           const char *const *exts)
{
    int ok = exts == NULL;
    char list[128] = "";
    for (int k = 0; exts && exts[k]; k++) {
        if (glpgp_has_ext(path, exts[k])) ok = 1;
        size_t n = strlen(list);
        snprintf(list + n, sizeof list - n, "%s%s", k ? (exts[k + 1] ? ", " : " or ") : "", exts[k]);
    }
    if (!ok) return glpgp_cli_usage_error(cmd, "%s: '%s' must end in %s", opt, path, list);
    if (glpgp_output_path_check(path) != GLPGP_OK) return glpgp_cli_fail();
    return -1;
}

int glpgp_cli_size_image(glpgp_options *o, const glpgp_mesh *m, const double box[4],
                         const glpgp_mask_options *mo, glpgp_size_image **out)
{
    *out = NULL;
    if (o->size_field != GLPGP_SIZE_FUNC || o->size_fn) return -1;
    double b[4];
    for (int k = 0; k < 4; k++) b[k] = isnan(box[0]) ? m->bbox[k] : box[k];
    glpgp_error_clear();
    if (!glpgp_cli_need_images(1, 0)) return GLPGP_EXIT_FAIL;
    if (glpgp_size_image_create(o->size_file, mo->max_pixels, b, o->size_min, 1.0, out) != GLPGP_OK)
        return glpgp_cli_fail();
    int w, h;
    glpgp_size_image_dims(*out, &w, &h);
    glpgp_log(GLPGP_LOG_INFO, "size field: %s (%d x %d pixels) over [%g, %g] x [%g, %g], black = %g h", o->size_file,
              w, h, b[0], b[2], b[1], b[3], o->size_min);
    o->size_fn = glpgp_size_image_eval;
    o->size_ctx = *out;
    return -1;
}
