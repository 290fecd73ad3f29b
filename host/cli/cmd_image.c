/* cmd_image.c: the picture and image-domain subcommands of the CLI
 *   glpgp render RESULT.vtk -o OUT.png   picture of a finished solve;
 *   glpgp mesh MASK.png -o DOMAIN.msh    triangle mesh of a mask image (Gmsh);
 *   glpgp figure INPUT -o OUT.png        naive PGP and GL side by side;
 * and the image hooks of `glpgp solve` (--image ..., INPUT = mask image).
 * Like main.c, this is CLI code: it prints errors ("glpgp: error: ...") and
 * returns exit codes 0 ok, 1 failure, 2 usage error. */
#include "cli.h"
#include "commands.h"

#include "glpgp/backends.h"
#include "glpgp/image.h"
#include "glpgp/io.h"
#include "glpgp/mesh.h"
#include "glpgp/shapes.h"
#include "glpgp/solve.h"
#include "glpgp/util.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define EXIT_USAGE 2

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int fail_err(void) { return glpgp_cli_fail(); }

static int usage_err(const char *sub, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static int usage_err(const char *sub, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("glpgp: usage error: ", stderr);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\nTry 'glpgp %s --help' for the options.\n", sub);
    return EXIT_USAGE;
}

/* OpenImageIO / Gmsh usable (their module loaded); else the reason is
 * printed ("built without ...", or the module not found / not loadable). */
static int need_oiio(void)
{
    glpgp_error_clear();
    if (glpgp_oiio_load() == GLPGP_OK) return 1;
    fail_err();
    return 0;
}

static int need_gmsh(void)
{
    glpgp_error_clear();
    if (glpgp_gmsh_load() == GLPGP_OK) return 1;
    fail_err();
    return 0;
}

/* ---- shared option parsing ---------------------------------------------------- */

enum { G_RENDER = 1, G_MASK = 2, G_SOLVE = 4 };

typedef struct img_cli {
    const char *input, *out;
    glpgp_render_options ro;
    glpgp_mask_options mo;
    glpgp_options so;
    const char *backend;
    int device;
    int quiet;
} img_cli;

static void img_cli_init(img_cli *c)
{
    memset(c, 0, sizeof *c);
    glpgp_render_options_default(&c->ro);
    glpgp_mask_options_default(&c->mo);
    glpgp_options_default(&c->so);
    c->backend = "auto";
    c->device = -1;
}

/* Options of each group: name, takes a value. */
typedef struct opt_def {
    const char *name;
    int group;
    int valued;
} opt_def;

static const opt_def opt_defs[] = {
    {"--image-size", G_RENDER, 1}, {"--image-kind", G_RENDER, 1}, {"--background", G_RENDER, 1},
    {"--line-width", G_RENDER, 1}, {"--threshold", G_MASK, 1},    {"--invert", G_MASK, 0},
    {"--pixel-size", G_MASK, 1},   {"--mesh-size", G_MASK, 1},    {"--min-area", G_MASK, 1},
    {"--simplify", G_MASK, 1},     {"--algorithm", G_MASK, 1},    {"--size", G_SOLVE | G_MASK, 1},
    {"--field", G_SOLVE, 1},       {"--center", G_SOLVE, 1},      {"--backend", G_SOLVE, 1},
    {"--device", G_SOLVE, 1},      {NULL, 0, 0}};

/* Apply option nm (value v, NULL for flags) to c. Returns -1 or exit code 2. */
static int apply_opt(img_cli *c, const char *sub, const char *nm, const char *v)
{
    double d;
    long l;
    if (!strcmp(nm, "--image-size")) {
        if (!glpgp_cli_long(v, 16, 32768, &l)) return usage_err(sub, "--image-size: '%s' is not an integer in [16, 32768]", v);
        c->ro.size = (int)l;
    } else if (!strcmp(nm, "--image-kind")) {
        int k = glpgp_image_kind_parse(v);
        if (k < 0) return usage_err(sub, "--image-kind: '%s' is not one of grid, checker, zabs, field, theta", v);
        c->ro.kind = k;
    } else if (!strcmp(nm, "--background")) {
        if (!strcmp(v, "white"))
            c->ro.transparent = 0;
        else if (!strcmp(v, "transparent"))
            c->ro.transparent = 1;
        else
            return usage_err(sub, "--background: '%s' is not one of white, transparent", v);
    } else if (!strcmp(nm, "--line-width")) {
        if (!glpgp_cli_double(v, &d) || !(d > 0 && d <= 100)) return usage_err(sub, "--line-width: '%s' is not a number in (0, 100]", v);
        c->ro.line_width = d;
    } else if (!strcmp(nm, "--threshold")) {
        if (!glpgp_cli_double(v, &d)) return usage_err(sub, "--threshold: '%s' is not a number", v);
        c->mo.contour.threshold = d;
    } else if (!strcmp(nm, "--invert")) {
        c->mo.contour.invert = 1;
    } else if (!strcmp(nm, "--pixel-size")) {
        if (!glpgp_cli_double(v, &d) || !(d > 0)) return usage_err(sub, "--pixel-size: '%s' is not a positive number", v);
        c->mo.contour.pixel_size = d;
    } else if (!strcmp(nm, "--mesh-size")) {
        if (!glpgp_cli_double(v, &d) || !(d > 0)) return usage_err(sub, "--mesh-size: '%s' is not a positive number", v);
        c->mo.mesh_size = d;
    } else if (!strcmp(nm, "--min-area")) {
        if (!glpgp_cli_double(v, &d) || !(d >= 0)) return usage_err(sub, "--min-area: '%s' is not a number >= 0", v);
        c->mo.contour.min_area = d;
    } else if (!strcmp(nm, "--simplify")) {
        if (!glpgp_cli_double(v, &d) || !(d >= 0)) return usage_err(sub, "--simplify: '%s' is not a number >= 0", v);
        c->mo.contour.tolerance = d;
    } else if (!strcmp(nm, "--algorithm")) {
        if (!strcmp(v, "frontal"))
            c->mo.algorithm = 6;
        else if (!strcmp(v, "delaunay"))
            c->mo.algorithm = 5;
        else
            return usage_err(sub, "--algorithm: '%s' is not one of frontal, delaunay", v);
    } else if (!strcmp(nm, "--size")) {
        if (!glpgp_cli_double(v, &d) || !(d > 0)) return usage_err(sub, "--size: '%s' is not a positive number", v);
        c->so.size = d;
    } else if (!strcmp(nm, "--field")) {
        if (!strcmp(v, "boundary"))
            c->so.field = GLPGP_FIELD_BOUNDARY;
        else if (!strcmp(v, "radial"))
            c->so.field = GLPGP_FIELD_RADIAL;
        else if (*v) {
            c->so.field = GLPGP_FIELD_FILE;
            c->so.field_file = v;
        } else
            return usage_err(sub, "--field: empty value");
    } else if (!strcmp(nm, "--center")) {
        const char *comma = strchr(v, ',');
        char xs[128];
        size_t n = comma ? (size_t)(comma - v) : 0;
        if (!comma || n >= sizeof xs) return usage_err(sub, "--center: '%s' is not X,Y", v);
        memcpy(xs, v, n);
        xs[n] = '\0';
        if (!glpgp_cli_double(xs, &c->so.center[0]) || !glpgp_cli_double(comma + 1, &c->so.center[1]))
            return usage_err(sub, "--center: '%s' is not X,Y (two numbers)", v);
        c->so.has_center = 1;
    } else if (!strcmp(nm, "--backend")) {
        if (strcmp(v, "auto") && strcmp(v, "opencl") && strcmp(v, "reference"))
            return usage_err(sub, "--backend: '%s' is not one of auto, opencl, reference", v);
        c->backend = v;
    } else if (!strcmp(nm, "--device")) {
        if (!glpgp_cli_long(v, 0, INT_MAX, &l)) return usage_err(sub, "--device: '%s' is not an integer >= 0", v);
        c->device = (int)l;
    }
    return -1;
}

/* Parse argv of subcommand sub accepting option groups `groups`, -o/--out,
 * --quiet, --help (prints help_text). Returns -1 when parsed, else exit code. */
static int parse_cli(int argc, char **argv, const char *sub, int groups, const char *help_text, img_cli *c)
{
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (arg[0] != '-' || arg[1] == '\0' || !strncmp(arg, "shape:", 6)) {
            if (c->input) return usage_err(sub, "unexpected argument '%s'", arg);
            c->input = arg;
            continue;
        }
        char nm[64];
        const char *eq = !strncmp(arg, "--", 2) ? strchr(arg, '=') : NULL;
        size_t n = eq ? (size_t)(eq - arg) : strlen(arg);
        if (n >= sizeof nm) n = sizeof nm - 1;
        memcpy(nm, arg, n);
        nm[n] = '\0';
        const char *v = eq ? eq + 1 : NULL;
        if (!strcmp(nm, "--help") || !strcmp(nm, "-h")) {
            fputs(help_text, stdout);
            return 0;
        }
        if (!strcmp(nm, "--quiet")) {
            if (v) return usage_err(sub, "option %s takes no value", nm);
            c->quiet = 1;
            continue;
        }
        if (!strcmp(nm, "-o") || !strcmp(nm, "--out")) {
            if (!v) {
                if (i + 1 >= argc) return usage_err(sub, "option %s needs a value", nm);
                v = argv[++i];
            }
            if (!*v) return usage_err(sub, "%s: empty path", nm);
            c->out = v;
            continue;
        }
        const opt_def *d = NULL;
        for (int k = 0; opt_defs[k].name; k++)
            if ((opt_defs[k].group & groups) && !strcmp(opt_defs[k].name, nm)) d = &opt_defs[k];
        if (!d) return usage_err(sub, "unknown option '%s'", arg);
        if (d->valued && !v) {
            if (i + 1 >= argc) return usage_err(sub, "option %s needs a value", nm);
            v = argv[++i];
        } else if (!d->valued && v) {
            return usage_err(sub, "option %s takes no value", nm);
        }
        int rc = apply_opt(c, sub, nm, v);
        if (rc >= 0) return rc;
    }
    return -1;
}

#define RENDER_OPTS_HELP                                                                         \
    "  --image-size N       pixels on the long side (16..32768; default 1024)\n"                 \
    "  --image-kind K       grid (unit grid of theta_u, theta_v: the paper's Fig. 4),\n"         \
    "                       checker, zabs (heat map of min |z_u|, |z_v|), field (arrows\n"       \
    "                       of the guiding field U), theta (red = theta_u, green =\n"            \
    "                       theta_v) (default grid)\n"                                          \
    "  --background B       white or transparent (default white)\n"                             \
    "  --line-width W       grid line width in pixels (default max(1, 1.5 N / 1024))\n"

#define MASK_OPTS_HELP                                                                           \
    "  --threshold T        inside = mask value >= T (alpha if the image has a varying\n"        \
    "                       alpha channel, else luminance, in [0, 1]) (default 0.5)\n"           \
    "  --invert             inside = mask value < T\n"                                           \
    "  --pixel-size S       physical size of a pixel; y points up, the image covers\n"          \
    "                       [0, width S] x [0, height S] (default 1)\n"                          \
    "  --mesh-size M        Gmsh target size, physical units (mean edge about 0.7 M)\n"         \
    "                       (default h / 8 with h = --size, or the bounding-box\n"              \
    "                       diagonal / 20)\n"                                                    \
    "  --min-area A         drop islands and fill holes under A square pixels (default 16)\n"    \
    "  --simplify P         boundary simplification tolerance in pixels (default 0.5;\n"         \
    "                       raised to mesh size / 20)\n"                                         \
    "  --algorithm A        Gmsh 2D algorithm: frontal (Frontal-Delaunay, default) or\n"         \
    "                       delaunay (faster on huge meshes)\n"

static const char render_help[] =
    "Usage: glpgp render RESULT.vtk -o OUT.{png,exr,tif,jpg,...} [options]\n"
    "\n"
    "Picture of a result written by 'glpgp solve --out RESULT.vtk': the domain with\n"
    "the unit grid of (theta_u, theta_v), singular triangles red, the boundary drawn.\n"
    "The format follows the extension (OpenImageIO).\n" RENDER_OPTS_HELP
    "  --quiet              print nothing on success\n";

static const char mesh_help[] =
    "Usage: glpgp mesh MASK.{png,tif,exr,...} -o DOMAIN.{msh,obj} [options]\n"
    "\n"
    "Triangle mesh of the domain drawn in a mask image: the mask is thresholded,\n"
    "its boundary traced at sub-pixel precision (marching squares), holes kept,\n"
    "specks dropped, simplified, and meshed with Gmsh.\n" MASK_OPTS_HELP
    "  --size H             the quad size the mesh is for (sets the default mesh size)\n"
    "  --quiet              print nothing on success\n";

static const char figure_help[] =
    "Usage: glpgp figure INPUT -o OUT.{png,exr,tif,jpg,...} [options]\n"
    "\n"
    "Solve INPUT (a .obj/.msh mesh, shape:NAME[:N] or a mask image) with naive PGP\n"
    "and with GL-PGP and render both side by side with their singularity counts.\n"
    "  --size H             quad size (default: bounding-box diagonal / 20)\n"
    "  --field F            boundary, radial or FILE (default boundary)\n"
    "  --center X,Y         centre of the radial field (default: area centroid)\n"
    "  --backend B          auto, opencl or reference (default auto)\n"
    "  --device N           OpenCL device index\n" RENDER_OPTS_HELP MASK_OPTS_HELP
    "  --quiet              no progress\n";

/* ---- glpgp render ---------------------------------------------------------- */

int glpgp_cmd_render(int argc, char **argv)
{
    img_cli c;
    img_cli_init(&c);
    int rc = parse_cli(argc, argv, "render", G_RENDER, render_help, &c);
    if (rc >= 0) return rc;
    if (!c.input) return usage_err("render", "missing RESULT.vtk");
    if (!c.out) return usage_err("render", "missing -o OUT.png");
    if (!need_oiio()) return 1;
    if (!glpgp_image_path_writable(c.out))
        return usage_err("render", "-o: cannot write images of type '%s' (try .png, .exr, .tif, .jpg)", c.out);
    glpgp_error_clear();
    if (glpgp_output_path_check(c.out) != GLPGP_OK) return fail_err();
    glpgp_mesh *m = NULL;
    glpgp_result *r = NULL;
    glpgp_image *im = NULL;
    rc = 0;
    if (glpgp_read_result_vtk(c.input, &m, &r) != GLPGP_OK || glpgp_render(m, r, &c.ro, &im) != GLPGP_OK ||
        glpgp_image_write(c.out, im) != GLPGP_OK)
        rc = fail_err();
    else if (!c.quiet)
        printf("glpgp: %s: %d x %d %s picture -> %s (singular triangles u: %d, v: %d)\n", c.input, im->w,
               im->h, glpgp_image_kind_name(c.ro.kind), c.out, r->osc[0].plus + r->osc[0].minus,
               r->osc[1].plus + r->osc[1].minus);
    glpgp_image_destroy(&im);
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);
    return rc;
}

/* ---- glpgp mesh ---------------------------------------------------------------- */

static void print_mask_info(const char *input, const glpgp_mesh *m, const glpgp_mask_info *inf)
{
    printf("glpgp: %s: %d x %d mask, %d outer boundar%s, %d hole%s, %d boundary points, area %.6g\n",
           input, inf->width, inf->height, inf->nouter, inf->nouter == 1 ? "y" : "ies", inf->nholes,
           inf->nholes == 1 ? "" : "s", inf->boundary_points, inf->polygon_area);
    printf("  mesh           %d vertices, %d triangles, mesh size %.6g (mean edge %.6g), area %.6g\n",
           m->nv, m->nt, inf->mesh_size, m->mean_edge, m->area);
    printf("  time           read %.3f s, contours %.3f s, gmsh %.3f s\n", inf->seconds_read,
           inf->seconds_contour, inf->seconds_mesh);
}

int glpgp_cmd_mesh(int argc, char **argv)
{
    img_cli c;
    img_cli_init(&c);
    int rc = parse_cli(argc, argv, "mesh", G_MASK, mesh_help, &c);
    if (rc >= 0) return rc;
    /* --size is accepted by `mesh` too (it only sets the default mesh size) */
    if (!c.input) return usage_err("mesh", "missing MASK image");
    if (!c.out) return usage_err("mesh", "missing -o DOMAIN.msh");
    if (!glpgp_has_ext(c.out, ".msh") && !glpgp_has_ext(c.out, ".obj"))
        return usage_err("mesh", "-o: '%s' must end in .msh or .obj", c.out);
    if (!need_oiio() || !need_gmsh()) return 1;
    glpgp_error_clear();
    if (glpgp_output_path_check(c.out) != GLPGP_OK) return fail_err();
    glpgp_mesh *m = NULL;
    glpgp_mask_info inf;
    c.mo.quad_size = c.so.size;
    if (glpgp_mask_mesh(c.input, &c.mo, &m, &inf) != GLPGP_OK || glpgp_mesh_write(m, c.out) != GLPGP_OK) {
        rc = fail_err();
    } else {
        rc = 0;
        if (!c.quiet) {
            print_mask_info(c.input, m, &inf);
            printf("  wrote          %s\n", c.out);
        }
    }
    glpgp_mesh_destroy(&m);
    return rc;
}

/* ---- glpgp figure ---------------------------------------------------------------- */

/* Mesh for INPUT: shape:NAME[:N], a mask image, or a mesh file. */
static glpgp_status load_any(const char *input, const glpgp_mask_options *mo, glpgp_mesh **m,
                             glpgp_mask_info *inf, int *is_mask)
{
    *is_mask = 0;
    if (!strncmp(input, "shape:", 6)) {
        char name[64];
        long nv;
        GLPGP_CHECK(glpgp_shape_parse(input, 0, name, sizeof name, &nv));
        return glpgp_mesh_generate(name, nv, m);
    }
    if (glpgp_is_image_path(input)) {
        *is_mask = 1;
        return glpgp_mask_mesh(input, mo, m, inf);
    }
    return glpgp_mesh_read(input, m);
}

static glpgp_status make_backend(const img_cli *c, glpgp_backend **b)
{
    return glpgp_backend_select(glpgp_backend_kind_parse(c->backend), c->device, !c->quiet, b);
}

int glpgp_cmd_figure(int argc, char **argv)
{
    img_cli c;
    img_cli_init(&c);
    int rc = parse_cli(argc, argv, "figure", G_RENDER | G_MASK | G_SOLVE, figure_help, &c);
    if (rc >= 0) return rc;
    if (!c.input) return usage_err("figure", "missing INPUT");
    if (!c.out) return usage_err("figure", "missing -o OUT.png");
    if (!need_oiio()) return 1;
    if (!glpgp_image_path_writable(c.out))
        return usage_err("figure", "-o: cannot write images of type '%s' (try .png, .exr, .tif, .jpg)", c.out);
    glpgp_error_clear();
    if (glpgp_output_path_check(c.out) != GLPGP_OK) return fail_err();
    glpgp_cli_set_verbosity(0); /* the solves run silently: figure prints its own lines */
    c.mo.quad_size = c.so.size;
    glpgp_mesh *m = NULL;
    glpgp_backend *b = NULL;
    glpgp_result *res[2] = {NULL, NULL};
    glpgp_image *im = NULL;
    glpgp_mask_info inf;
    int is_mask = 0;
    rc = 1;
    double t0 = now_s();
    if (load_any(c.input, &c.mo, &m, &inf, &is_mask) != GLPGP_OK) goto err;
    if (is_mask && !c.quiet) print_mask_info(c.input, m, &inf);
    if (make_backend(&c, &b) != GLPGP_OK) goto err;
    for (int k = 0; k < 2; k++) {
        glpgp_options o = c.so;
        o.method = k == 0 ? GLPGP_METHOD_PGP : GLPGP_METHOD_GL;
        if (glpgp_solve(m, b, &o, &res[k]) != GLPGP_OK) goto err;
        if (!c.quiet)
            printf("glpgp: %-9s singularities u: +%d -%d  v: +%d -%d  (%.2f s)\n", k == 0 ? "naive PGP" : "GL-PGP",
                   res[k]->osc[0].plus, res[k]->osc[0].minus, res[k]->osc[1].plus, res[k]->osc[1].minus,
                   res[k]->seconds_total);
    }
    {
        const glpgp_result *rr[2] = {res[0], res[1]};
        static const char *const labels[2] = {"NAIVE PGP", "GL-PGP"};
        if (glpgp_render_compare(m, rr, labels, 2, &c.ro, &im) != GLPGP_OK) goto err;
    }
    if (glpgp_image_write(c.out, im) != GLPGP_OK) goto err;
    if (!c.quiet)
        printf("glpgp: %s: %d vertices, h = %.6g: %d x %d figure -> %s (%.2f s)\n", c.input, m->nv,
               res[1]->size, im->w, im->h, c.out, now_s() - t0);
    rc = 0;
    goto done;
err:
    rc = fail_err();
done:
    glpgp_image_destroy(&im);
    glpgp_result_destroy(&res[0]);
    glpgp_result_destroy(&res[1]);
    glpgp_backend_destroy(&b);
    glpgp_mesh_destroy(&m);
    return rc;
}

/* ---- solve hooks ------------------------------------------------------------------ */

void glpgp_solve_image_init(glpgp_solve_image_cli *c)
{
    glpgp_render_options ro;
    glpgp_mask_options mo;
    glpgp_render_options_default(&ro);
    glpgp_mask_options_default(&mo);
    memset(c, 0, sizeof *c);
    c->image = NULL;
    c->image_size = ro.size;
    c->image_kind = ro.kind;
    c->transparent = ro.transparent;
    c->threshold = mo.contour.threshold;
    c->invert = 0;
    c->pixel_size = mo.contour.pixel_size;
    c->mesh_size = 0;
}

int glpgp_solve_image_option(const char *name)
{
    if (!name) return 0;
    if (!strcmp(name, "--invert")) return 1;
    static const char *const valued[] = {"--image", "--image-size", "--image-kind", "--background",
                                         "--threshold", "--pixel-size", "--mesh-size", NULL};
    for (int k = 0; valued[k]; k++)
        if (!strcmp(name, valued[k])) return 2;
    return 0;
}

int glpgp_solve_image_parse(glpgp_solve_image_cli *sc, const char *name, const char *value)
{
    if (!strcmp(name, "--image")) {
        if (!value || !*value) return usage_err("solve", "--image: empty path");
        glpgp_error_clear();
        glpgp_status st = glpgp_oiio_load();
        if (st == GLPGP_ERR_UNSUPPORTED) {
            fprintf(stderr, "glpgp: usage error: --image: this glpgp was built without OpenImageIO\n");
            glpgp_error_clear();
            return EXIT_USAGE;
        }
        if (st != GLPGP_OK) return fail_err(); /* module missing or not loadable */
        if (!glpgp_image_path_writable(value))
            return usage_err("solve", "--image: cannot write images of type '%s' (try .png, .exr, .tif, .jpg)", value);
        sc->image = value;
        return -1;
    }
    img_cli c;
    img_cli_init(&c);
    c.ro.size = sc->image_size;
    c.ro.kind = sc->image_kind;
    c.ro.transparent = sc->transparent;
    c.mo.contour.threshold = sc->threshold;
    c.mo.contour.invert = sc->invert;
    c.mo.contour.pixel_size = sc->pixel_size;
    c.mo.mesh_size = sc->mesh_size;
    int rc = apply_opt(&c, "solve", name, value);
    if (rc >= 0) return rc;
    sc->image_size = c.ro.size;
    sc->image_kind = c.ro.kind;
    sc->transparent = c.ro.transparent;
    sc->threshold = c.mo.contour.threshold;
    sc->invert = c.mo.contour.invert;
    sc->pixel_size = c.mo.contour.pixel_size;
    sc->mesh_size = c.mo.mesh_size;
    return -1;
}

int glpgp_solve_image_load(const glpgp_solve_image_cli *sc, const char *input, double size, int verbose,
                           struct glpgp_mesh **m)
{
    if (!need_oiio() || !need_gmsh()) return 1;
    glpgp_mask_options mo;
    glpgp_mask_options_default(&mo);
    mo.contour.threshold = sc->threshold;
    mo.contour.invert = sc->invert;
    mo.contour.pixel_size = sc->pixel_size;
    mo.mesh_size = sc->mesh_size;
    mo.quad_size = size;
    glpgp_mask_info inf;
    if (glpgp_mask_mesh(input, &mo, m, &inf) != GLPGP_OK) return fail_err();
    if (verbose)
        fprintf(stderr,
                "glpgp: %s: %d x %d mask -> %d vertices, %d triangles (%d hole%s, mesh size %.4g, "
                "%.2f s)\n",
                input, inf.width, inf.height, (*m)->nv, (*m)->nt, inf.nholes, inf.nholes == 1 ? "" : "s",
                inf.mesh_size, inf.seconds_read + inf.seconds_contour + inf.seconds_mesh);
    return -1;
}

int glpgp_solve_image_write(const glpgp_solve_image_cli *sc, const struct glpgp_mesh *m,
                            const struct glpgp_result *r)
{
    if (!sc->image) return -1;
    glpgp_render_options ro;
    glpgp_render_options_default(&ro);
    ro.size = sc->image_size;
    ro.kind = sc->image_kind;
    ro.transparent = sc->transparent;
    glpgp_image *im = NULL;
    if (glpgp_render(m, r, &ro, &im) != GLPGP_OK || glpgp_image_write(sc->image, im) != GLPGP_OK) {
        glpgp_image_destroy(&im);
        return fail_err();
    }
    glpgp_image_destroy(&im);
    return -1;
}

void glpgp_solve_image_usage(FILE *f)
{
    fputs("Pictures and image domains:\n"
          "  --image FILE        picture of the result (.png, .exr, .tif, .jpg, ...)\n"
          "  --image-size N      pixels on the long side (default 1024)\n"
          "  --image-kind K      grid, checker, zabs, field or theta (default grid)\n"
          "  --background B      white or transparent (default white)\n"
          "  INPUT may be a mask image (.png, .tif, .exr, ...): it is meshed first with\n"
          "  --threshold T (0.5), --invert, --pixel-size S (1), --mesh-size M (h / 8);\n"
          "  see 'glpgp mesh --help'.\n",
          f);
}
