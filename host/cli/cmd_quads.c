/* cli/cmd_quads.c: the quad-mesh commands:
 *   glpgp extract RESULT.vtk --quads OUT.{obj,vtk,msh} [--stats OUT.json] [--size H]
 *                 [--keep-polygons] [--smooth N] [--all-quads]
 *       quad mesh from a result written by `glpgp solve -o RESULT.vtk` (a
 *       plane or a surface: the surface pipeline, as solve --quads);
 *   glpgp quality MESH.{msh,obj} [--size H] [--domain DOMAIN] [--stats OUT.json] [--allow-invalid]
 *       the same quality report for a quad/triangle mesh made elsewhere (Gmsh,
 *       used by bench/gmsh_compare.sh; a surface's quad mesh by another
 *       mesher against its surface, used by bench/surface_compare.sh).
 * An invalid quad mesh exits with GLPGP_EXIT_INVALID (3) and is not written
 * (extract; the --stats report is), unless --allow-invalid. */
#include "commands.h"

#include "cli.h"
#include "opts.h"

#include "glpgp/cross.h"
#include "glpgp/io.h"
#include "glpgp/quads.h"
#include "glpgp/solve.h"
#include "glpgp/surface.h"
#include "glpgp/util.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const char *const k_quad_exts[] = {".obj", ".vtk", ".vtu", ".msh", ".ply", NULL};

void glpgp_cli_print_surface_steps(const glpgp_quads_surface_steps *s)
{
    char split[192] = "";
    if (s->split_faces)
        snprintf(split, sizeof split, "; %d faces split locally (bad regions and their quad strips)", s->split_faces);
    else if (s->refined_faces)
        snprintf(split, sizeof split, "; %d faces refined locally (3 x 3 where too far from the surface, templates around)",
                 s->refined_faces);
    printf("  surface quads  extraction %d faces (%d quads), %d odd or even faces closed, %d strips%s%s%s\n",
           s->extracted_faces, s->extracted_quads, s->closed, s->strips, split,
           s->subdivided ? "; split into quads (Catmull-Clark, h/2)" : "",
           !s->fallback          ? ""
           : s->coarse_triangles ? "; not valid: a coarsened triangulation split into quads (last resort)"
                                 : "; not valid: the input triangles split into quads (last resort)");
    if (s->parts > 1)
        printf("  parts          %d connected components meshed apart, %d of them by the last resort\n", s->parts,
               s->parts_last_resort);
    if (s->local_regions)
        printf("  repaired       %d regions of bad faces repaired locally: %d faces -> %d quads, smallest scaled "
               "Jacobian %.3f\n",
               s->local_regions, s->local_faces_in, s->local_quads_out, s->local_sj_min);
    if (s->smoothed)
        printf("  smoothed       %d vertices on the surface: smallest scaled Jacobian %.3f -> %.3f\n", s->smoothed,
               s->sj_before, s->sj_after);
    if (s->flat_corners)
        printf("  flat corners   %d boundary corners split like triangles (%d faces split along their strips): "
               "smallest scaled Jacobian %.3f -> %.3f\n",
               s->flat_corners, s->flat_faces, s->flat_sj_before, s->flat_sj_after);
}

int glpgp_cmd_extract(int argc, char **argv)
{
    const char *sub = "extract", *in = NULL, *quads = NULL, *stats = NULL;
    double size = 0.0;
    int verbosity = 1, qgiven = 0, allow_invalid = 0;
    long max_elements = GLPGP_DEFAULT_MAX_ELEMENTS;
    glpgp_quads_options qo;
    glpgp_quads_options_default(&qo);
    glpgp_opts t;
    glpgp_opts_init(&t, sub, "glpgp extract RESULT.{vtu,vtk} --quads OUT.{obj,vtu,vtk,msh,ply} [options]",
                    "Extract the quad mesh whose edges are the integer level lines of theta_u and\n"
                    "theta_v from a result written by 'glpgp solve -o RESULT.vtk', and print its\n"
                    "quality report.\n");
    glpgp_opt_string(&t, "--quads", &quads, "FILE",
                     "quad mesh: .obj (quads as 4-vertex faces, other faces as\n"
                     "n-gons), .vtu / .vtk (VTK_QUAD / VTK_POLYGON), .msh (Gmsh\n"
                     "4.1, quadrangles; other faces split into quads + one triangle)\n"
                     "or .ply (ASCII, faces as vertex lists)");
    glpgp_opt_string(&t, "--stats", &stats, "FILE", "quality report as JSON {\"quads\": {...}}");
    glpgp_opt *o = glpgp_opt_double(&t, "--size", &size, 0.0, 1, HUGE_VAL, 0, "H", "target size h");
    o->def = "the h recorded in RESULT";
    glpgp_opts_add_quads(&t, &qo, &qgiven, &allow_invalid);
    o = glpgp_opt_double(&t, "--feature-angle", &qo.feature_angle, 0.0, 0, 180.0, 0, "DEG",
                         "a surface: the sharp features the smoothing and the last\n"
                         "resort keep (as solve's --feature-angle)");
    o->def = "35";
    glpgp_opts_add_limits(&t, &max_elements, NULL);
    glpgp_opts_add_verbosity(&t, &verbosity);
    int rc = glpgp_opts_parse_input(&t, argc, argv, &in, &verbosity, "RESULT.vtk");
    if (rc >= 0) return rc;
    if (!quads && !stats) return glpgp_cli_usage_error(sub, "nothing to do: give --quads FILE and/or --stats FILE");
    if (quads && stats && !strcmp(quads, stats))
        return glpgp_cli_usage_error(sub, "--quads and --stats name the same file '%s'", quads);
    if (quads && (rc = glpgp_cli_check_output(sub, "--quads", quads, k_quad_exts)) >= 0) return rc;
    if (stats && (rc = glpgp_cli_check_output(sub, "--stats", stats, NULL)) >= 0) return rc;
    glpgp_error_clear();
    glpgp_mesh *m = NULL;
    glpgp_result *r = NULL;
    glpgp_quadmesh *q = NULL;
    glpgp_output_set *outs = NULL;
    glpgp_quads_report qq;
    rc = GLPGP_EXIT_FAIL;
    const double t_read0 = glpgp_now();
    if (glpgp_read_result(in, &m, &r) != GLPGP_OK) goto fail;
    const double t_read = glpgp_now() - t_read0;
    if (m->xyz && !m->surf) {
        GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: a 3D mesh that is not a surface", in);
        goto fail;
    }
    if ((rc = glpgp_cli_check_elements(in, m->nt, "triangles", 0, max_elements)) >= 0) goto done;
    rc = GLPGP_EXIT_FAIL;
    if (size > 0) r->size = size;
    if (!(r->size > 0)) r->size = glpgp_default_size(m, NULL);
    {
        /* h within the limits solve uses (2 mean edges .. 100 diameters): a
         * recorded h of 1e-300 would make the extraction print 300-digit
         * numbers, one of 1e300 find no grid line */
        glpgp_options so;
        glpgp_options_default(&so);
        so.size = r->size;
        if (glpgp_options_check_mesh(&so, m) != GLPGP_OK) {
            if (size > 0) {
                rc = glpgp_cli_usage_error(sub, "--size: %s", glpgp_error_message());
                glpgp_error_clear();
                goto done;
            }
            char msg[1024];
            snprintf(msg, sizeof msg, "%s", glpgp_error_message());
            glpgp_error_clear();
            GLPGP_FAIL(GLPGP_ERR_FORMAT, "%s: the recorded %s (give --size H)", in, msg);
            goto fail;
        }
    }
    double h = r->size;
    const double t_x0 = glpgp_now();
    glpgp_quads_surface_steps steps;
    memset(&steps, 0, sizeof steps);
    if (m->surf) { /* a surface: its own pipeline and check (quads/quads_surface.c), as solve --quads */
        if (glpgp_quads_build_surface(m, r, &qo, &q, &h, &steps) != GLPGP_OK) goto fail;
        if (glpgp_quads_quality_surface(q, m, h, &qq) != GLPGP_OK) goto fail;
        qq.steps = steps;
        qq.has_steps = 1;
    } else {
        if (glpgp_quads_build(m, r, &qo, &q, &h) != GLPGP_OK) goto fail;
        if (glpgp_quads_quality(q, m, h, &qq) != GLPGP_OK) goto fail;
    }
    qq.singular[0] = r->osc[0].plus + r->osc[0].minus;
    qq.singular[1] = r->osc[1].plus + r->osc[1].minus;
    /* --field cross: irregular interior vertices within h of a cross-field singularity, and the others */
    if (r->cross && glpgp_quads_quality_cross(q, r->cross->sing, r->cross->nsing, r->size, &qq) != GLPGP_OK)
        goto fail;
    const double t_x = glpgp_now() - t_x0;
    char why[1024] = "";
    int invalid_rc = glpgp_cli_quads_verdict(&qq, qo.keep_polygons ? GLPGP_QUADS_BAD_NONQUAD : 0u, allow_invalid,
                                             why, sizeof why);
    /* both outputs or neither (an invalid mesh: the report only) */
    if (glpgp_output_set_create(&outs) != GLPGP_OK ||
        (quads && invalid_rc < 0 && glpgp_output_set_quads(outs, q, quads) != GLPGP_OK) ||
        (stats && glpgp_output_set_quads_json(outs, &qq, stats) != GLPGP_OK) ||
        glpgp_output_set_commit(outs) != GLPGP_OK)
        goto fail;
    printf("glpgp: %s: h = %.6g%s, singular triangles u %d, v %d\n", in, h,
           qo.all_quads ? " (--all-quads: half the solve's size)" : "", qq.singular[0], qq.singular[1]);
    printf("  time           read %.3f s, extraction %.3f s (quads and their check)\n", t_read, t_x);
    if (m->surf) glpgp_cli_print_surface_steps(&steps);
    glpgp_quads_print(stdout, &qq, "  ");
    if (quads && invalid_rc < 0) printf("  wrote          %s\n", quads);
    if (stats) printf("  wrote          %s\n", stats);
    rc = invalid_rc < 0 ? 0
                        : glpgp_cli_invalid(why, quads ? "not written (--allow-invalid writes it anyway)" : "");
    goto done;
fail:
    rc = glpgp_cli_fail();
done:
    glpgp_output_set_destroy(&outs);
    glpgp_quadmesh_destroy(&q);
    glpgp_result_destroy(&r);
    glpgp_mesh_destroy(&m);
    return rc;
}

/* Mean edge length of a quad mesh (3D when it has xyz): the default h. */
static double quads_mean_edge(const glpgp_quadmesh *q)
{
    double s = 0.0;
    long n = 0;
    for (int f = 0; f < q->nf; f++) {
        int b = q->face_start[f], k = q->face_start[f + 1] - b;
        for (int j = 0; j < k; j++) {
            int p = q->face_vert[b + j], r = q->face_vert[b + (j + 1) % k];
            double dx = q->xy[2 * p] - q->xy[2 * r], dy = q->xy[2 * p + 1] - q->xy[2 * r + 1], dz = 0.0;
            if (q->xyz) {
                dx = q->xyz[3 * p] - q->xyz[3 * r];
                dy = q->xyz[3 * p + 1] - q->xyz[3 * r + 1];
                dz = q->xyz[3 * p + 2] - q->xyz[3 * r + 2];
            }
            s += sqrt(dx * dx + dy * dy + dz * dz);
            n++;
        }
    }
    return n ? s / (double)n : 1.0;
}

/* The domain of `glpgp quality`: a surface for a surface's quad mesh (its
 * report needs one), else the planar reading. rc >= 0: exit with it. */
static int quality_domain(const char *sub, const char *in, const char *domain, const glpgp_quadmesh *q,
                          long max_elements, glpgp_mesh **dm)
{
    int rc;
    if (q->xyz && !domain)
        return glpgp_cli_usage_error(sub, "%s is a surface's quad mesh: give --domain SURFACE (the triangle mesh "
                                          "it was made of) for its check", in);
    if (!domain) return -1;
    if (glpgp_mesh_read_ex(domain, q->xyz ? 0 : GLPGP_READ_PLANAR_FACE, dm) != GLPGP_OK) return glpgp_cli_fail();
    if ((rc = glpgp_cli_check_elements(domain, (*dm)->nt, "triangles", 0, max_elements)) >= 0) return rc;
    if (q->xyz && !glpgp_mesh_is_surface(*dm))
        return glpgp_cli_usage_error(sub, "--domain %s is planar, %s is a surface's quad mesh", domain, in);
    return -1;
}

int glpgp_cmd_quality(int argc, char **argv)
{
    const char *sub = "quality", *in = NULL, *domain = NULL, *stats = NULL;
    double size = 0.0;
    int verbosity = 1, allow_invalid = 0;
    long max_elements = GLPGP_DEFAULT_MAX_ELEMENTS;
    glpgp_opts t;
    glpgp_opts_init(&t, sub, "glpgp quality MESH.{msh,obj} [options]",
                    "Quality report (valences, scaled Jacobian, edge lengths, distance to the domain)\n"
                    "of a quad/triangle mesh made elsewhere: Gmsh MSH 4.1 or 2.2 ASCII, or OBJ;\n"
                    "a mesh of a 3D surface (e.g. by another quad mesher) is checked against the\n"
                    "surface it was made of (--domain), as glpgp checks its own.\n");
    glpgp_opt *o = glpgp_opt_double(&t, "--size", &size, 0.0, 1, HUGE_VAL, 0, "H", "target size h");
    o->def = "mean edge length";
    glpgp_opt_string(&t, "--domain", &domain, "FILE",
                     "triangle mesh (.obj/.msh/.stl/.ply/.off) of the domain: adds the\n"
                     "Hausdorff distance (of the boundaries in the plane, two-sided on a\n"
                     "surface); required for a surface's quad mesh");
    glpgp_opt_string(&t, "--stats", &stats, "FILE", "report as JSON {\"quads\": {...}}");
    glpgp_opt_flag(&t, "--allow-invalid", &allow_invalid, 1,
                   "exit 0 on an invalid mesh, with a warning (default: exit code 3)");
    glpgp_opts_add_limits(&t, &max_elements, NULL);
    glpgp_opts_add_verbosity(&t, &verbosity);
    t.epilog = "Faces are read in the file's orientation; the report takes one orientation for the\n"
               "whole mesh (the sign of its total area), so a folded face counts as inverted.\n"
               "Exit code 3 when the mesh is invalid (inverted, degenerate, non-quad, overlapping\n"
               "faces, non-manifold edges, pinched vertices; with --domain also faces outside it,\n"
               "lost holes or corners, area off by > 1%, Hausdorff distance > h/4). On a surface:\n"
               "faces against the surface's normal, non-manifold edges or vertices, Euler\n"
               "characteristic or boundary loops not the surface's, area off by > 2%, two-sided\n"
               "Hausdorff distance > h/4; the scaled Jacobian in each face's best-fit plane.\n";
    int rc = glpgp_opts_parse_input(&t, argc, argv, &in, &verbosity, "MESH");
    if (rc >= 0) return rc;
    if (stats && (rc = glpgp_cli_check_output(sub, "--stats", stats, NULL)) >= 0) return rc;
    glpgp_error_clear();
    glpgp_quadmesh *q = NULL;
    glpgp_mesh *dm = NULL;
    rc = GLPGP_EXIT_FAIL;
    /* OBJ by its extension; anything else is read as MSH (a pipe too) */
    if ((glpgp_has_ext(in, ".obj") ? glpgp_quads_read(in, &q) : glpgp_quads_read_msh(in, &q)) != GLPGP_OK) goto fail;
    if ((rc = glpgp_cli_check_elements(in, q->nf, "faces", 0, max_elements)) >= 0) goto done;
    if ((rc = quality_domain(sub, in, domain, q, max_elements, &dm)) >= 0) goto done;
    rc = GLPGP_EXIT_FAIL;
    {
        double mean = quads_mean_edge(q);
        if (!(size > 0)) {
            size = mean;
        } else if (mean > 0 && !(size >= 1e-3 * mean && size <= 1e3 * mean)) {
            /* the report divides lengths by h: keep them readable */
            rc = glpgp_cli_usage_error(sub, "--size: h = %g is %.3g mean edge lengths of '%s': it must be "
                                            "within 1e-3 .. 1e3 of them", size, size / mean, in);
            goto done;
        }
    }
    glpgp_quads_report qq;
    if ((q->xyz ? glpgp_quads_quality_surface(q, dm, size, &qq) : glpgp_quads_quality(q, dm, size, &qq)) != GLPGP_OK)
        goto fail;
    if (stats && glpgp_quads_write_json_file(&qq, stats) != GLPGP_OK) goto fail;
    printf("glpgp: %s: h = %.6g%s\n", in, size, q->xyz ? " (a surface's quad mesh)" : "");
    glpgp_quads_print(stdout, &qq, "  ");
    if (stats) printf("  wrote          %s\n", stats);
    char why[1024] = "";
    rc = glpgp_cli_quads_verdict(&qq, 0u, allow_invalid, why, sizeof why) < 0 ? 0 : glpgp_cli_invalid(why, "");
    goto done;
fail:
    rc = glpgp_cli_fail();
done:
    glpgp_quadmesh_destroy(&q);
    glpgp_mesh_destroy(&dm);
    return rc;
}
