/* cli/cmd_image.c: the picture and image-domain commands:
 *   glpgp render RESULT.vtk -o OUT.png   picture of a finished solve;
 *   glpgp mesh MASK.png|D.poly|M.obj -o DOMAIN.msh   triangle mesh of a mask image, a polygon
 *                                         file, or a remesh of a triangle mesh (Gmsh);
 *   glpgp figure INPUT -o OUT.png        naive PGP and GL side by side. */
#include "commands.h"

#include "cli.h"
#include "opts.h"

#include "glpgp/backends.h"
#include "glpgp/cross.h"
#include "glpgp/image.h"
#include "glpgp/io.h"
#include "glpgp/solve.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* -o OUT: an image type OpenImageIO writes, in a writable directory; panels
 * pictures of at most --image-size^2 pixels each within --max-pixels. */
static int check_picture_out(const char *sub, const char *out, int size, int panels, long long max_pixels)
{
    if (!out) return glpgp_cli_usage_error(sub, "missing -o OUT.png");
    int rc = glpgp_cli_check_picture_size(sub, size, panels, max_pixels);
    if (rc >= 0) return rc;
    if (!glpgp_cli_need_images(1, 0)) return GLPGP_EXIT_FAIL;
    if (!glpgp_image_path_writable(out))
        return glpgp_cli_usage_error(sub, "-o: cannot write images of type '%s' (try .png, .exr, .tif, .jpg)", out);
    return glpgp_cli_check_output(sub, "--out", out, NULL);
}

/* ---- glpgp render ---------------------------------------------------------- */

int glpgp_cmd_render(int argc, char **argv)
{
    const char *sub = "render", *in = NULL, *out = NULL, *domain = NULL;
    double sj_below = 0.3;
    int verbosity = 1;
    long max_elements = GLPGP_DEFAULT_MAX_ELEMENTS;
    long long max_pixels = GLPGP_DEFAULT_MAX_PIXELS;
    glpgp_render_options ro;
    glpgp_render_options_default(&ro);
    glpgp_opts t;
    glpgp_opts_init(&t, sub, "glpgp render RESULT.vtk|QUADS.obj|QUADS.msh -o OUT.{png,exr,tif,jpg,...} [options]",
                    "Picture of a result written by 'glpgp solve --out RESULT.vtk': the domain with\n"
                    "the unit grid of (theta_u, theta_v), singular triangles red, the boundary drawn.\n"
                    "Of a quad mesh (.obj, .msh): its faces by origin (grid, strips, repair,\n"
                    "fallback), faces below --sj-below red, irregular vertices marked (valence 3\n"
                    "blue, 5 red, 6+ dark red), the boundary of --domain, counts under it.\n"
                    "The format follows the extension (OpenImageIO).\n");
    glpgp_opt *o = glpgp_opt_string(&t, "--out", &out, "FILE", "picture file");
    o->alias = "-o";
    glpgp_opt_string(&t, "--domain", &domain, "FILE",
                     "quad mesh input: the triangle mesh (.obj/.msh/.stl) of its\n"
                     "domain, whose boundary is drawn (default: the mesh's own)");
    glpgp_opt_double(&t, "--sj-below", &sj_below, 0.0, 0, 1.0, 1, "S",
                     "quad mesh input: faces whose smallest corner scaled\n"
                     "Jacobian is below S are drawn red");
    glpgp_opts_add_picture(&t, &ro, 1);
    glpgp_opts_add_limits(&t, &max_elements, &max_pixels);
    glpgp_opts_add_verbosity(&t, &verbosity);
    int rc = glpgp_opts_parse_input(&t, argc, argv, &in, &verbosity, "RESULT.vtk");
    if (rc >= 0) return rc;
    if ((rc = check_picture_out(sub, out, ro.size, 1, max_pixels)) >= 0) return rc;
    if (glpgp_has_ext(in, ".obj") || glpgp_has_ext(in, ".msh"))
        return glpgp_cli_render_quads(in, out, domain, sj_below, &ro, max_elements, verbosity);
    if (domain) return glpgp_cli_usage_error(sub, "--domain is for a quad mesh input (.obj, .msh)");
    glpgp_error_clear();
    glpgp_mesh *m = NULL;
    glpgp_result *r = NULL;
    glpgp_image *im = NULL;
    rc = -1;
    if (glpgp_read_result(in, &m, &r) != GLPGP_OK) rc = glpgp_cli_fail();
    if (rc < 0) rc = glpgp_cli_check_elements(in, m->nt, "triangles", 0, max_elements);
    if (rc < 0 && (glpgp_render(m, r, &ro, &im) != GLPGP_OK || glpgp_image_write(out, im) != GLPGP_OK))
        rc = glpgp_cli_fail();
    if (rc < 0) rc = 0;
    if (rc == 0 && verbosity > 0)
        printf("glpgp: %s: %d x %d %s picture -> %s (singular triangles u: %d, v: %d)\n", in, im->w,
               im->h, glpgp_image_kind_name(ro.kind), out, r->osc[0].plus + r->osc[0].minus,
               r->osc[1].plus + r->osc[1].minus);
    glpgp_image_destroy(&im);
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);
    return rc;
}

/* ---- glpgp mesh ---------------------------------------------------------------- */

static void print_mask_info(const char *input, const glpgp_mesh *m, const glpgp_mask_info *inf)
{
    if (inf->width > 0)
        printf("glpgp: %s: %d x %d mask, ", input, inf->width, inf->height);
    else
        printf("glpgp: %s: polygons, ", input);
    printf("%d outer boundar%s, %d hole%s, %d boundary points, area %.6g\n", inf->nouter, inf->nouter == 1 ? "y" : "ies", inf->nholes,
           inf->nholes == 1 ? "" : "s", inf->boundary_points, inf->polygon_area);
    printf("  mesh           %d vertices, %d triangles, mesh size %.6g (mean edge %.6g), area %.6g\n",
           m->nv, m->nt, inf->mesh_size, m->mean_edge, m->area);
    printf("  time           read %.3f s, contours %.3f s, gmsh %.3f s\n", inf->seconds_read,
           inf->seconds_contour, inf->seconds_mesh);
}

int glpgp_cmd_mesh(int argc, char **argv)
{
    static const char *const exts[] = {".msh", ".obj", NULL};
    const char *sub = "mesh", *in = NULL, *out = NULL;
    int verbosity = 1;
    glpgp_mask_options mo;
    glpgp_mask_options_default(&mo);
    glpgp_opts t;
    glpgp_opts_init(&t, sub, "glpgp mesh {MASK.png,...|DOMAIN.poly|MESH.obj|MESH.msh} -o DOMAIN.{msh,obj} [options]",
                    "Triangle mesh of the domain drawn in a mask image: the mask is thresholded,\n"
                    "its boundary traced at sub-pixel precision (marching squares), holes kept,\n"
                    "specks dropped, simplified, and meshed with Gmsh. Or of the polygons of a\n"
                    "Triangle .poly file (closed loops of segments, holes by nesting; the first\n"
                    "vertex attribute, when > 0, is the local mesh size: graded meshes). Or a\n"
                    "remesh of a triangle mesh (.obj, .msh) inside its boundary points: for CAD\n"
                    "exports (STL-like fans of slivers) that are poor input for the solver.\n");
    glpgp_opt *o = glpgp_opt_string(&t, "--out", &out, "FILE", "mesh file, .msh or .obj");
    o->alias = "-o";
    glpgp_opts_add_mask(&t, &mo);
    o = glpgp_opt_double(&t, "--size", &mo.quad_size, 0.0, 1, HUGE_VAL, 0, "H",
                         "the quad size the mesh is for (sets the default mesh size)");
    o->def = "";
    glpgp_opts_add_limits(&t, &mo.max_triangles, &mo.max_pixels);
    glpgp_opts_add_verbosity(&t, &verbosity);
    int rc = glpgp_opts_parse_input(&t, argc, argv, &in, &verbosity, "MASK image, .poly file or mesh");
    if (rc >= 0) return rc;
    if (!out) return glpgp_cli_usage_error(sub, "missing -o DOMAIN.msh");
    if ((rc = glpgp_cli_check_output(sub, "--out", out, exts)) >= 0) return rc;
    const int polygons = glpgp_is_poly_path(in) || glpgp_has_ext(in, ".obj") || glpgp_has_ext(in, ".msh") ||
                         glpgp_has_ext(in, ".stl");
    if (!glpgp_cli_need_images(!polygons, 1)) return GLPGP_EXIT_FAIL;
    glpgp_error_clear();
    glpgp_mesh *m = NULL;
    glpgp_mask_info inf;
    if (glpgp_mask_mesh(in, &mo, &m, &inf) != GLPGP_OK || glpgp_mesh_write(m, out) != GLPGP_OK) {
        rc = glpgp_cli_fail();
    } else {
        rc = 0;
        if (verbosity > 0) {
            print_mask_info(in, m, &inf);
            printf("  wrote          %s\n", out);
        }
    }
    glpgp_mesh_destroy(&m);
    return rc;
}

/* ---- glpgp figure ---------------------------------------------------------------- */

int glpgp_cmd_figure(int argc, char **argv)
{
    const char *sub = "figure", *in = NULL, *out = NULL;
    int verbosity = 1, backend = GLPGP_BACKEND_AUTO, device = -1;
    glpgp_options so;
    glpgp_render_options ro;
    glpgp_mask_options mo;
    glpgp_options_default(&so);
    glpgp_render_options_default(&ro);
    glpgp_mask_options_default(&mo);
    glpgp_opts t;
    int fig1 = 0, figs = 0;
    glpgp_opts_init(&t, sub, "glpgp figure INPUT -o OUT.{png,exr,tif,jpg,...} [options]",
                    "Solve INPUT (a .obj/.msh mesh, shape:NAME[:N] or a mask image) with naive PGP\n"
                    "and with GL-PGP and render both side by side with their singularity counts;\n"
                    "with --cross: the paper's Fig. 1 (cross field, GL-PGP texture, quads);\n"
                    "with --surface (a 3D surface): the input, the grid texture and the quads.\n");
    glpgp_opt *o = glpgp_opt_string(&t, "--out", &out, "FILE", "picture file");
    o->alias = "-o";
    glpgp_opt_flag(&t, "--cross", &fig1, 1,
                   "the paper's Fig. 1 instead: one GL-PGP solve with --field cross,\n"
                   "then the cross field (singularities +1/4 red, -1/4 blue), the\n"
                   "grid texture and the quad mesh (valence 3 blue, 5+ red) side by side\n"
                   "(on a surface: as --surface)");
    glpgp_opt_flag(&t, "--surface", &figs, 1,
                   "a 3D surface's figure: one GL-PGP solve with the cross field, then\n"
                   "the input shaded, the grid texture and the quad mesh (valence 3\n"
                   "blue, 5 red, 6+ dark red) side by side, from --view");
    glpgp_opts_add_picture(&t, &ro, 1);
    glpgp_opts_add_solver(&t, &so);
    int field_seen = 0;
    for (int k = 0; k < t.n; k++)
        if (t.opt[k].name && !strcmp(t.opt[k].name, "--field")) t.opt[k].seen = &field_seen;
    double size_box[4];
    glpgp_opts_add_size_image(&t, size_box);
    glpgp_opts_add_backend(&t, &backend, &device);
    glpgp_opts_group(&t, "Mask image input (INPUT = image)");
    glpgp_opts_add_mask(&t, &mo);
    glpgp_opts_add_limits(&t, &mo.max_triangles, &mo.max_pixels);
    glpgp_opts_add_verbosity(&t, &verbosity);
    int rc = glpgp_opts_parse_input(&t, argc, argv, &in, &verbosity, "INPUT");
    if (rc >= 0) return rc;
    if (backend == GLPGP_BACKEND_PETSC)
        return glpgp_cli_usage_error(sub, "--backend petsc: only 'glpgp solve' runs on MPI ranks");
    fig1 |= figs;
    if ((rc = check_picture_out(sub, out, ro.size, fig1 ? 3 : 2, mo.max_pixels)) >= 0) return rc;
    glpgp_error_clear();
    mo.quad_size = so.size;
    glpgp_mesh *m = NULL;
    glpgp_backend *b = NULL;
    glpgp_result *res[2] = {NULL, NULL};
    glpgp_image *im = NULL;
    double t0 = glpgp_now();
    glpgp_size_image *simg = NULL; /* --size-field IMAGE */
    if ((rc = glpgp_cli_load_input(sub, in, &mo, &m, NULL)) >= 0) return rc;
    if (!m->xyz && figs) {
        rc = glpgp_cli_usage_error(sub, "--surface: %s is not a 3D surface (--cross: the planar Fig. 1)", in);
        goto done;
    }
    if (m->xyz && !field_seen) so.field = GLPGP_FIELD_CROSS; /* a surface's default */
    if ((rc = glpgp_cli_size_image(&so, m, size_box, &mo, &simg)) >= 0) goto done;
    rc = GLPGP_EXIT_FAIL;
    if (glpgp_backend_select(backend, device, verbosity > 0, &b) != GLPGP_OK) goto err;
    /* the solves' own progress only with --verbose: figure prints a line per solve */
    glpgp_cli_set_verbosity(verbosity > 1 ? verbosity : 0);
    if (fig1) {
        /* Fig. 1: cross field, texture, quads of one --field cross solve */
        glpgp_options oo = so;
        oo.method = GLPGP_METHOD_GL;
        oo.field = GLPGP_FIELD_CROSS;
        if (glpgp_solve(m, b, &oo, &res[1]) != GLPGP_OK) goto err;
        glpgp_quadmesh *q = NULL;
        double hq = res[1]->size;
        if (glpgp_quads_build(m, res[1], NULL, &q, &hq) != GLPGP_OK) {
            fprintf(stderr, "glpgp: warning: no quad mesh (%s): its panel is left out\n", glpgp_error_message());
            glpgp_error_clear();
        }
        if (verbosity > 0)
            printf("glpgp: cross field: %d singularities (index sum %g), GL-PGP singularities u: +%d -%d  "
                   "v: +%d -%d, %d quads (%.2f s)\n",
                   res[1]->cross->nsing, res[1]->cross->index4_sum / 4.0, res[1]->osc[0].plus,
                   res[1]->osc[0].minus, res[1]->osc[1].plus, res[1]->osc[1].minus, q ? q->nf : 0,
                   glpgp_now() - t0);
        glpgp_status fs = glpgp_render_figure1(m, res[1], q, &ro, &im);
        glpgp_quadmesh_destroy(&q);
        if (fs != GLPGP_OK) goto err;
    }
    for (int k = 0; k < 2 && !fig1; k++) {
        glpgp_options oo = so;
        oo.method = k == 0 ? GLPGP_METHOD_PGP : GLPGP_METHOD_GL;
        if (glpgp_solve(m, b, &oo, &res[k]) != GLPGP_OK) goto err;
        if (verbosity > 0)
            printf("glpgp: %-9s singularities u: +%d -%d  v: +%d -%d  (%.2f s)\n", k == 0 ? "naive PGP" : "GL-PGP",
                   res[k]->osc[0].plus, res[k]->osc[0].minus, res[k]->osc[1].plus, res[k]->osc[1].minus,
                   res[k]->seconds_total);
    }
    if (!fig1) {
        const glpgp_result *rr[2] = {res[0], res[1]};
        static const char *const labels[2] = {"NAIVE PGP", "GL-PGP"};
        if (glpgp_render_compare(m, rr, labels, 2, &ro, &im) != GLPGP_OK) goto err;
    }
    if (glpgp_image_write(out, im) != GLPGP_OK) goto err;
    if (verbosity > 0)
        printf("glpgp: %s: %d vertices, h = %.6g: %d x %d figure -> %s (%.2f s)\n", in, m->nv,
               res[1]->size, im->w, im->h, out, glpgp_now() - t0);
    rc = 0;
    goto done;
err:
    rc = glpgp_cli_fail();
done:
    glpgp_image_destroy(&im);
    glpgp_result_destroy(&res[0]);
    glpgp_result_destroy(&res[1]);
    glpgp_backend_destroy(&b);
    glpgp_mesh_destroy(&m);
    glpgp_size_image_destroy(&simg);
    return rc;
}
