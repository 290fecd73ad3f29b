/* image/render_options.c: the table of the user-settable picture options
 * (glpgp_render_option_table, glpgp/image.h; descriptors: glpgp/optdesc.h),
 * read by the CLI (--image-size, --image-kind, --background, --view, --line-width)
 * and the Python keyword arguments of glpgp.render (size, kind, ...). */
#include "glpgp/image.h"
#include "glpgp/util.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#define OFF(m) offsetof(glpgp_render_options, m)

static const char *const k_kinds[] = {"grid", "checker", "zabs", "field", "theta", "cross", NULL};
static const int k_kind_vals[] = {GLPGP_IMAGE_GRID, GLPGP_IMAGE_CHECKER, GLPGP_IMAGE_ZABS,
                                  GLPGP_IMAGE_FIELD, GLPGP_IMAGE_THETA, GLPGP_IMAGE_CROSS};
static const char *const k_backgrounds[] = {"white", "transparent", NULL};

/* --view AZ,EL: a surface's camera, degrees */
static const char *parse_view(void *opts, const char *v)
{
    glpgp_render_options *r = opts;
    const char *comma = strchr(v, ',');
    char a[128];
    const size_t n = comma ? (size_t)(comma - v) : 0;
    if (!comma || n >= sizeof a) return "is not AZ,EL (two numbers, degrees)";
    memcpy(a, v, n);
    a[n] = '\0';
    double az, el;
    if (!glpgp_parse_double(a, &az) || !glpgp_parse_double(comma + 1, &el)) return "is not AZ,EL (two numbers, degrees)";
    if (!(fabs(el) <= 90.0)) return "has an elevation outside [-90, 90] degrees";
    r->azimuth = az;
    r->elevation = el;
    return NULL;
}

static const glpgp_optdesc k_table[] = {
    {.name = "image-size", .pyname = "size", .kind = GLPGP_OPTK_INT, .offset = OFF(size), .lo = 16, .hi = 32768,
     .meta = "N", .help = "pixels on the long side"},
    {.name = "image-kind", .pyname = "kind", .kind = GLPGP_OPTK_CHOICE, .offset = OFF(kind), .names = k_kinds,
     .values = k_kind_vals,
     .help = "grid (unit grid of theta_u, theta_v: the paper's Fig. 4),\n"
             "checker, zabs (heat map of min |z_u|, |z_v|), field (arrows of\n"
             "the guiding field U), theta (red = theta_u, green = theta_v),\n"
             "cross (the cross field of a --field cross result, singularities\n"
             "marked: +1/4 red, -1/4 blue)"},
    {.name = "background", .kind = GLPGP_OPTK_CHOICE, .offset = OFF(transparent), .names = k_backgrounds,
     .help = "picture background"},
    {.name = "view", .kind = GLPGP_OPTK_TEXT, .parse = parse_view, .meta = "AZ,EL", .def = "35,25",
     .help = "a surface's picture: the camera's azimuth about z (from +x) and\n"
             "elevation above the xy plane, degrees (an orthographic view fitted\n"
             "to the surface, z-buffered and shaded)"},
    {.name = "line-width", .kind = GLPGP_OPTK_DOUBLE, .offset = OFF(line_width), .lo = 0.0, .lo_open = 1,
     .hi = 100.0, .meta = "W", .help = "grid line width in pixels", .def = "max(1, 1.5 N / 1024)"},
    {.name = NULL}};

const glpgp_optdesc *glpgp_render_option_table(void) { return k_table; }
