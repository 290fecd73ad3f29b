/* cli/cmd_solve.c: `glpgp solve INPUT [options]`: load or mesh the domain,
 * solve with the chosen backend, then compute everything asked for (quad
 * mesh and its report, picture) before writing any file, write the outputs
 * and print the summary. A failure at any point leaves no output behind. */
#include "commands.h"

#include "cli.h"
#include "opts.h"

#include "glpgp/backends.h"
#include "glpgp/distributed.h"
#include "glpgp/image.h"
#include "glpgp/io.h"
#include "glpgp/cross.h"
#include "glpgp/quads.h"
#include "glpgp/solve.h"
#include "glpgp/surface.h"
#include "glpgp/util.h"
#include "glpgp/internal/newton.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <time.h>
#include <unistd.h>
#include <stdlib.h>
#include <string.h>

static const char *const k_result_exts[] = {".vtk", ".vtu", ".obj", ".pvtu", NULL};
static const char *const k_quad_exts[] = {".obj", ".vtk", ".vtu", ".msh", ".ply", NULL};
static const char *const k_json_exts[] = {".json", NULL};

typedef struct solve_cli {
    glpgp_options o;
    int backend, device, verbosity;
    int no_refine;
    glpgp_refine_info refined;
    glpgp_surface_denoise_info denoise; /* a surface's noise smoothed before the solve */
    double denoise_h;
    glpgp_mesh *input_mesh; /* the input as read, kept where it was denoised (the quads' distance to it) */
    double hausdorff_input; /* that distance / h (< 0: not measured) */
    const char *out, *stats, *quads, *image;
    glpgp_quads_options qo;
    int quad_opts, allow_invalid;
    glpgp_render_options ro;
    glpgp_mask_options mo;
    double size_box[4];  /* --size-image-box */
    int gather_max;      /* --gather-max: most vertices gathered to rank 0 (distributed PETSc runs) */
    int pieces;          /* --out *.pvtu: one .vtu piece per rank and the index */
    int field_seen;      /* --field given (else a surface takes the cross field) */
    int planar_face;     /* --planar-face: a 3D input's largest face in a coordinate plane */
    int gather;          /* distributed: the whole result is gathered to rank 0 (set on every rank) */
    double t_refine;     /* seconds of the refinement for the local size (prepare) */
    int image_kind_given; /* --image-kind seen: with --quads, the picture is the quad mesh otherwise */
    double faces;        /* --faces N: the target quad count (h = sqrt(area / N)); 0: not given */
    glpgp_quads_surface_steps qsteps; /* a surface's quad pipeline (--quads) */
} solve_cli;

/* Default of --gather-max: 2^26 vertices (1 GiB per gathered z array, 16
 * bytes a vertex; MPI's int counts stop at 2 GiB, 134M vertices). */
#define GATHER_MAX_DEFAULT (1 << 26)

static void build(glpgp_opts *t, solve_cli *c)
{
    memset(c, 0, sizeof *c); /* outputs NULL, no option seen */
    glpgp_options_default(&c->o);
    glpgp_quads_options_default(&c->qo);
    glpgp_render_options_default(&c->ro);
    glpgp_mask_options_default(&c->mo);
    c->backend = GLPGP_BACKEND_AUTO;
    c->device = -1;
    c->verbosity = 1;
    c->allow_invalid = 0;
    c->gather_max = GATHER_MAX_DEFAULT;
    glpgp_opts_init(t, "solve", "glpgp solve INPUT [options]",
                    "INPUT is a triangle mesh of a planar domain (.obj, .stl, or Gmsh .msh 2.2/4.1 ASCII),\n"
                    "shape:NAME[:N], a built-in domain with about N vertices (default 20000;\n"
                    "NAME is one of square, disk, annulus, lshape), or a mask image (.png, .tif,\n"
                    ".exr, ...), meshed first (see 'Mask image input').\n");
    glpgp_opts_add_solver(t, &c->o);
    for (int k = 0; k < t->n; k++)
        if (t->opt[k].name && !strcmp(t->opt[k].name, "--field")) t->opt[k].seen = &c->field_seen;
    glpgp_opts_add_size_image(t, c->size_box);
    glpgp_opt_flag(t, "--planar-face", &c->planar_face, 1,
                   "a 3D input (x, y and z vary): solve its largest face in a\n"
                   "coordinate plane (an extruded CAD part's section) instead of the\n"
                   "surface");
    glpgp_opt_flag(t, "--no-refine", &c->no_refine, 1,
                   "solve the input as it is: where its triangles are coarser\n"
                   "than the local h / 4 (auto, iso, IMAGE) the local size is limited\n"
                   "to what they resolve (a warning) instead of refining them\n"
                   "(longest-edge bisection)");
    glpgp_opt_flag(t, "--remesh", &c->mo.remesh, 1,
                   "mesh a .obj/.msh/.stl input again with Gmsh inside its boundary\n"
                   "points first (as 'glpgp mesh INPUT' does; --mesh-size, default\n"
                   "h / 8): for CAD exports whose triangles are fans of slivers");
    glpgp_opts_add_desc(t, glpgp_optdesc_find(glpgp_solve_option_table(), "input-order"), &c->o);
    glpgp_opts_add_backend(t, &c->backend, &c->device);
    glpgp_opts_group(t, "Output");
    glpgp_opt *p = glpgp_opt_string(t, "--out", &c->out, "FILE",
                                    "result: .vtu (binary VTK XML, compressed when built with\n"
                                    "zlib), .vtk (legacy ASCII VTK), .obj (texture coordinates)\n"
                                    "or, with --backend petsc, .pvtu: every MPI rank writes its\n"
                                    "vertices and triangles as FILE_pK.vtu (K = rank; .vtu arrays\n"
                                    "+ global_id, vtkGhostType) and rank 0 the index FILE.pvtu\n"
                                    "(the whole result is then not gathered to rank 0)");
    p->alias = "-o";
    glpgp_opt_int(t, "--gather-max", &c->gather_max, 1, 0x7fffffffL, "N",
                  "--backend petsc on several ranks: most vertices whose result\n"
                  "is gathered to rank 0 (--out .vtu/.vtk/.obj, --quads, --image\n"
                  "need it; above: an error before the solve, use --out FILE.pvtu)");
    glpgp_opt_string(t, "--stats", &c->stats, "FILE", "statistics as JSON");
    glpgp_opt_string(t, "--quads", &c->quads, "FILE",
                     "extract the quad mesh (.obj/.vtu/.vtk/.msh/.ply) and add its quality\n"
                     "report to the summary and the statistics (\"quads\")");
    glpgp_opts_add_quads(t, &c->qo, &c->quad_opts, &c->allow_invalid);
    glpgp_opt_double(t, "--faces", &c->faces, 0.0, 1, 1e12, 0, "N",
                     "target quad count: the size h = sqrt(area / N) (instead of --size;\n"
                     "the mesh has about N quads where the parametrization is regular;\n"
                     "a count more than 3x off N is warned about)");
    glpgp_opt_string(t, "--image", &c->image, "FILE",
                     "picture of the result (.png, .exr, .tif, .jpg, ...); with --quads and\n"
                     "no --image-kind: the quad mesh (faces by origin, poor ones red,\n"
                     "irregular vertices marked, as 'glpgp render QUADS.obj')");
    glpgp_opts_add_picture(t, &c->ro, 0);
    for (int k = 0; k < t->n; k++) /* whether --image-kind was given (the quad picture otherwise) */
        if (t->opt[k].name && !strcmp(t->opt[k].name, "--image-kind")) t->opt[k].seen = &c->image_kind_given;
    glpgp_opts_group(t, "Mask image input (INPUT = image)");
    glpgp_opts_add_mask(t, &c->mo);
    glpgp_opts_add_limits(t, &c->mo.max_triangles, &c->mo.max_pixels);
    glpgp_opts_add_verbosity(t, &c->verbosity);
    t->epilog = "Files are written only after a successful solve, atomically (no partial file is\n"
                "ever left; a failed run leaves existing files untouched). A summary is printed\n"
                "on stdout.\n";
}

/* Validate the parsed options together; -1 when fine, else the exit code. */
static int check(solve_cli *c, const char *input)
{
    const char *sub = "solve";
    if (!input) return glpgp_cli_usage_error(sub, "missing INPUT (a .obj/.msh file or shape:NAME[:N])");
    if (c->out && c->stats && !strcmp(c->out, c->stats))
        return glpgp_cli_usage_error(sub, "--out and --stats name the same file '%s'", c->out);
    if (c->faces > 0.0 && c->o.size > 0.0) return glpgp_cli_usage_error(sub, "--faces and --size both set the size: give one");
    c->qo.feature_angle = c->o.feature_angle; /* the surface smoothing and last resort keep the same creases */
    if (c->quad_opts && !c->quads)
        return glpgp_cli_usage_error(sub, "--all-quads, --keep-polygons, --smooth, --no-repair and --allow-invalid need --quads FILE");
    if (c->quads && ((c->out && !strcmp(c->out, c->quads)) || (c->stats && !strcmp(c->stats, c->quads))))
        return glpgp_cli_usage_error(sub, "--quads names the same file as --out or --stats: '%s'", c->quads);
    if (c->image && ((c->out && !strcmp(c->out, c->image)) || (c->stats && !strcmp(c->stats, c->image)) ||
                     (c->quads && !strcmp(c->quads, c->image))))
        return glpgp_cli_usage_error(sub, "--image names the same file as another output: '%s'", c->image);
    int rc;
    if (c->out && (rc = glpgp_cli_check_output(sub, "--out", c->out, k_result_exts)) >= 0) return rc;
    c->pieces = c->out && glpgp_has_ext(c->out, ".pvtu");
    if (c->pieces) {
        char piece[4096];
        if (c->backend != GLPGP_BACKEND_PETSC)
            return glpgp_cli_usage_error(sub, "--out %s: .pvtu (a piece per MPI rank) needs --backend petsc", c->out);
        const char *base = strrchr(c->out, '/') ? strrchr(c->out, '/') + 1 : c->out;
        if (strpbrk(base, "\"&<>'") || glpgp_pvtu_piece_path(c->out, 999999, piece, sizeof piece) != GLPGP_OK) {
            glpgp_error_clear();
            return glpgp_cli_usage_error(sub, "--out %s: a .pvtu name must be shorter than 4 KiB and hold no \" & < > '",
                                         c->out);
        }
    }
    if (c->stats && (rc = glpgp_cli_check_output(sub, "--stats", c->stats, NULL)) >= 0) return rc;
    if (c->quads && (rc = glpgp_cli_check_output(sub, "--quads", c->quads, k_quad_exts)) >= 0) return rc;
    if (c->image) {
        if ((rc = glpgp_cli_check_picture_size(sub, c->ro.size, 1, c->mo.max_pixels)) >= 0) return rc;
        glpgp_error_clear();
        if (glpgp_oiio_load() == GLPGP_ERR_UNSUPPORTED) {
            glpgp_error_clear();
            return glpgp_cli_usage_error(sub, "--image: this glpgp was built without OpenImageIO");
        }
        if (!glpgp_cli_need_images(1, 0)) return GLPGP_EXIT_FAIL;
        if (!glpgp_image_path_writable(c->image))
            return glpgp_cli_usage_error(sub, "--image: cannot write images of type '%s' (try .png, .exr, "
                                              ".tif, .jpg)", c->image);
        if ((rc = glpgp_cli_check_output(sub, "--image", c->image, NULL)) >= 0) return rc;
    }
    (void)k_json_exts;
    return -1;
}

/* "  phases  read 1.09, program build 3.48 (in the background, waited 0.00),
 * ... s" (phases of at least 1 ms, in the order of glpgp/timers.h, lines of
 * about 100 columns), then what the solve waited on the device */
static void print_phases(const glpgp_result *r)
{
    const glpgp_timers *t = &r->timers;
    int col = printf("  phases       ");
    int first = 1;
    for (int i = 0; i < GLPGP_TM_COUNT; i++) {
        if (!(t->s[i] >= 0.001)) continue;
        char item[160];
        if (i == GLPGP_TM_BUILD)
            snprintf(item, sizeof item, "%s %.2f (waited %.2f)", glpgp_timer_label(i), t->s[i], t->wait[i]);
        else
            snprintf(item, sizeof item, "%s %.2f", glpgp_timer_label(i), t->s[i]);
        if (!first && col + (int)strlen(item) + 2 > 100) {
            printf(",\n               ");
            col = 15;
        } else if (!first) {
            col += printf(",");
        }
        col += printf(" %s", item);
        first = 0;
    }
    printf(" s\n");
    double wait = 0.0, sum = 0.0;
    for (int i = 0; i < GLPGP_TM_COUNT; i++)
        if (glpgp_timer_in_solve(i)) {
            wait += t->wait[i];
            sum += t->s[i];
        }
    if (wait > 0.0)
        printf("  device wait    %.3f s of the solve's phases' %.3f s%s (host work %.3f s, %.0f%%)\n", wait, sum,
               r->concurrent ? ", both threads" : "", sum - wait, sum > 0.0 ? 100.0 * (sum - wait) / sum : 0.0);
}

static void print_summary(const solve_cli *c, const char *input, const glpgp_mesh *m, const glpgp_result *r,
                          const char *device, double t_all, double t_read, const glpgp_quads_report *qq,
                          int quads_written)
{
    const glpgp_osc_result *u = &r->osc[0], *v = &r->osc[1];
    /* "device N: NAME" of the OpenCL info, without its launch-shape details
     * (names have parentheses of their own: "Intel(R) Xeon(R)") */
    int dl = 0;
    if (device) {
        const char *cut = strstr(device, " (cpu shape");
        if (!cut) cut = strstr(device, " (gpu shape");
        dl = cut ? (int)(cut - device) : (int)strlen(device);
    }
    printf("glpgp: %s: %d vertices, %d triangles, h = %.6g, backend %s%s%.*s%s\n", input, m->nv, m->nt, r->size,
           r->backend ? r->backend : "?", dl ? " (" : "", dl, dl ? device : "", dl ? ")" : "");
    printf("  singularities  u: +%d -%d   v: +%d -%d\n", u->plus, u->minus, v->plus, v->minus);
    if (r->cross) { /* --field cross: the cross field's singularities, index sum vs Poincare-Hopf */
        int np = 0, nm = 0;
        for (int k = 0; k < r->cross->nsing; k++) {
            if (r->cross->sing[k].index4 > 0) np++;
            else nm++;
        }
        char on[96] = ""; /* --cross-mesh input / polish: solved on the input, carried over */
        if (r->cross->solved_nv != r->cross->nv)
            snprintf(on, sizeof on, ", solved on the input (%d vertices)%s", r->cross->solved_nv,
                     r->cross->polished ? " + polished" : "");
        printf("  cross field    %d singularities (+%d -%d), index sum %g (Poincare-Hopf %g), %d Newton, %.2f s%s\n",
               r->cross->nsing, np, nm, r->cross->index4_sum / 4.0, r->cross->index4_expected / 4.0,
               r->cross->newton_iterations, r->cross->seconds, on);
    }
    printf("  median |z|     u: %.4f   v: %.4f\n", u->zabs_median, v->zabs_median);
    if (r->coupled) /* one system for both (--cross-coupling): its counts are in u */
        printf("  iterations     newton %d (u and v coupled across the cross field's cuts), cg %ld\n",
               u->newton_iterations, u->cg_iterations + r->field_cg_iterations);
    else
        printf("  iterations     newton %d (u %d, v %d), cg %ld\n", u->newton_iterations + v->newton_iterations,
               u->newton_iterations, v->newton_iterations,
               u->cg_iterations + v->cg_iterations + r->field_cg_iterations);
    if (u->capped_levels + v->capped_levels)
        printf("  unconverged    %d eps level(s) stopped at the Newton cap (u %d, v %d)\n",
               u->capped_levels + v->capped_levels, u->capped_levels, v->capped_levels);
    int stalled[2] = {0, 0};
    for (int l = 0; l < u->nlevels; l++) stalled[0] += u->level[l].stalled;
    for (int l = 0; l < v->nlevels; l++) stalled[1] += v->level[l].stalled;
    if (stalled[0] + stalled[1])
        printf("  plateau        %d eps level(s) stopped with |g| above the tolerance: E + P no longer fell "
               "(--newton-ftol; u %d, v %d)\n",
               stalled[0] + stalled[1], stalled[0], stalled[1]);
    if (m->surf)
        printf("  surface        chi %d, genus %d, %d boundary loop(s), %d component(s)\n", m->surf->euler,
               m->surf->genus, m->nloops, m->surf->ncomponents);
    char hin[96] = "";
    if (c->hausdorff_input >= 0.0)
        snprintf(hin, sizeof hin, "; to the input as read: Hausdorff %.3f h", c->hausdorff_input);
    if (c->denoise.rounds)
        printf("  denoised       %d edges above %g degrees that are not creases (a scan's noise) -> %d: %d vertices "
               "smoothed, largest move %.3f h (mean %.3f h), angle defects rms %.3g -> %.3g rad; the quads' "
               "distances below are to the smoothed surface%s\n",
               c->denoise.noise_edges, c->o.feature_angle, c->denoise.noise_edges_after, c->denoise.moved,
               c->denoise.max_move / c->denoise_h, c->denoise.mean_move / c->denoise_h, c->denoise.defect_rms,
               c->denoise.defect_rms_after, hin);
    if (c->refined.rounds)
        printf("  refined        %d -> %d vertices, %d -> %d triangles (%d rounds: too coarse for the local h)\n",
               c->refined.nv0, c->refined.nv, c->refined.nt0, c->refined.nt, c->refined.rounds);
    else if (c->refined.split_edges && c->refined.local)
        printf("  refined        %d -> %d vertices, %d -> %d triangles (%ld edges bisected: longer than h(x) / %g, "
               "the local size; smallest target h / %.3g; longest edge %.2f x h(x) / %g)\n",
               c->refined.nv0, c->refined.nv, c->refined.nt0, c->refined.nt, c->refined.split_edges,
               GLPGP_SURFACE_EDGES, r->size / c->refined.target_edge, c->refined.edge_ratio, GLPGP_SURFACE_EDGES);
    else if (c->refined.split_edges)
        printf("  refined        %d -> %d vertices, %d -> %d triangles (%ld edges bisected: longer than h / %g)\n",
               c->refined.nv0, c->refined.nv, c->refined.nt0, c->refined.nt, c->refined.split_edges,
               GLPGP_SURFACE_EDGES);
    printf("  time           %.3f s (read %.3f s, solve %.3f s%s)\n", t_all, t_read, r->seconds_total,
           r->concurrent ? "; u and v concurrently" : "");
    print_phases(r);
    if (c->out) printf("  wrote          %s\n", c->out);
    if (c->stats) printf("  wrote          %s\n", c->stats);
    if (c->quads) {
        if (m->surf) glpgp_cli_print_surface_steps(&c->qsteps);
        glpgp_quads_print(stdout, qq, "  ");
        if (quads_written) printf("  wrote          %s\n", c->quads);
    }
    if (c->image) printf("  wrote          %s\n", c->image);
}

static int solve_ranks(solve_cli *c, const char *input);
static int solve_main(solve_cli *c, const char *input, glpgp_dist *dd);

int glpgp_cmd_solve(int argc, char **argv)
{
    solve_cli c;
    glpgp_opts t;
    build(&t, &c);
    const char *input = NULL;
    int npos = 0;
    int rc = glpgp_opts_parse(&t, argc, argv, &input, 1, &npos);
    if (rc >= 0) return rc;
    glpgp_cli_set_verbosity(c.verbosity);
    glpgp_error_clear();
    if ((rc = check(&c, input)) >= 0) return rc;
    if (c.backend == GLPGP_BACKEND_PETSC) {
        /* MPI + PETSc first: every rank runs this command alike (reads the
         * input, solves its rows); only rank 0 prints and writes */
        if (glpgp_petsc_init() != GLPGP_OK) return glpgp_cli_fail();
        rc = solve_ranks(&c, input);
        glpgp_petsc_finalize();
        return rc;
    }
    return solve_main(&c, input, NULL);
}

/* The PETSc run on every rank: ranks other than 0 print nothing (stdout and
 * stderr to /dev/null) and write no file; every rank returns the same code
 * (a failure on any rank fails all). */
static int solve_ranks(solve_cli *c, const char *input)
{
    const int rank = glpgp_petsc_rank();
    /* distributed: whether rank 0 needs the whole result (decided alike on every rank) */
    c->gather = (c->out && !c->pieces) || c->quads || c->image;
    const glpgp_dist_options dopt = {c->gather, c->gather_max, c->pieces ? c->out : NULL};
    glpgp_dist *dd = NULL;
    if (glpgp_dist_create(&c->o, &dopt, &dd) != GLPGP_OK) return glpgp_cli_fail();
    if (rank != 0) {
        if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr)) {
            /* nothing to do: the output of this rank is lost either way */
        }
        /* a distributed .pvtu: this rank writes its piece */
        if (!(c->pieces && glpgp_dist_splits(dd))) c->out = NULL;
        c->stats = c->quads = c->image = NULL;
    }
    int rc = solve_main(c, input, dd);
    glpgp_dist_destroy(&dd); /* after a failure: the verdicts this rank owes */
    /* the same exit code everywhere (a rank that failed alone: all fail) */
    if (!glpgp_petsc_all_ok(rc == 0) && rc == 0) rc = GLPGP_EXIT_FAIL;
    return rc;
}

/* Read the input, check the options against it and refine it for the
 * local size: *pm (and *psimg, --size-field IMAGE). -1 when fine, else the
 * exit code (the error reported, nothing left allocated). */
static int prepare(solve_cli *c, const char *input, glpgp_mesh **pm, glpgp_size_image **psimg)
{
    int rc;
    glpgp_mesh *m = NULL;
    *pm = NULL;
    *psimg = NULL;
    c->mo.quad_size = c->o.size;
    if ((rc = glpgp_cli_load_input_ex("solve", input, &c->mo, c->planar_face ? GLPGP_READ_PLANAR_FACE : 0, &m,
                                      NULL)) >= 0)
        return rc;
    /* --quads on a planar domain: the cross field unless --field says
     * otherwise (fewer irregular vertices on every measured set,
     * bench/results/quads_fields.md); not on several PETSc ranks, which it
     * would keep from splitting the mesh */
    if (!m->xyz && c->quads && !c->field_seen && !(c->backend == GLPGP_BACKEND_PETSC && glpgp_petsc_size() > 1)) {
        c->o.field = GLPGP_FIELD_CROSS;
        glpgp_log(GLPGP_LOG_DEBUG, "quads: the cross field (the default with --quads; --field boundary for the other)");
    }
    if (c->faces > 0.0) { /* --faces N: h from the input's area */
        c->o.size = sqrt(m->area / c->faces);
        c->mo.quad_size = c->o.size;
    }
    if (m->xyz) {
        /* a surface: the cross field unless --field says otherwise */
        if (!c->field_seen) c->o.field = GLPGP_FIELD_CROSS;
        const double diag = glpgp_mesh_diagonal(m), hd = glpgp_default_size(m, &c->o);
        if (!(c->o.size > 0.0) && hd > diag / GLPGP_SIZE_DEFAULT_MIN_QUADS)
            glpgp_log(GLPGP_LOG_WARNING,
                      "%s: the surface is too coarse for the default size (mean edge %.3g): h = 10 mean edges = "
                      "%.4g gives a handful of quads: give --size or --faces (the surface is subdivided for them) or a finer mesh",
                      input, m->mean_edge, hd);
    }
    if ((rc = glpgp_cli_size_image(&c->o, m, c->size_box, &c->mo, psimg)) >= 0) {
        glpgp_mesh_destroy(&m);
        return rc;
    }
    /* the same preparation as every front end: slivers, the default size
     * of a coarse input, the size checks, the refinement */
    const double max_tri = c->mo.max_triangles > 0 ? (double)c->mo.max_triangles : (double)GLPGP_DEFAULT_MAX_ELEMENTS;
    glpgp_prepare_info pi;
    glpgp_mesh *mr = NULL;
    if (glpgp_solve_prepare(m, &c->o, input, max_tri, !c->no_refine, &mr, &pi) != GLPGP_OK) {
        c->refined = pi.refined;
        if (!pi.usage) goto fail;
        rc = glpgp_cli_usage_error("solve", "--size: %s", glpgp_error_message());
        glpgp_error_clear();
        glpgp_mesh_destroy(&m);
        glpgp_size_image_destroy(psimg);
        return rc;
    }
    c->refined = pi.refined;
    c->denoise = pi.denoise;
    c->denoise_h = pi.denoise_h;
    c->t_refine = pi.seconds_refine;
    if (mr) {
        if (c->denoise.rounds && c->quads) c->input_mesh = m; /* the quads' distance to it */
        else glpgp_mesh_destroy(&m);
        m = mr;
    }
    *pm = m;
    return -1;
fail:
    rc = glpgp_cli_fail();
    glpgp_mesh_destroy(&m);
    glpgp_size_image_destroy(psimg);
    return rc;
}

/* The backend created in a second thread while the input is read (an OpenCL
 * device's program build and first launches: about a second on a cold
 * cache, booked as the program build, not to the first numerical phase). */
typedef struct backend_job {
    int kind, device, verbose;
    int stop;             /* set when the input failed: the creation may end early */
    int done;             /* set by the thread when it ends */
    glpgp_backend *b;
    glpgp_status st;
    glpgp_error_copy err; /* the thread's error record, for the caller */
    double seconds;       /* the creation */
    pthread_t th;
    int started;
} backend_job;

static void *backend_job_run(void *arg)
{
    backend_job *j = arg;
    glpgp_error_clear();
    const double t0 = glpgp_now();
    j->st = glpgp_backend_select_stoppable((glpgp_backend_kind)j->kind, j->device, j->verbose, &j->stop, &j->b);
    j->seconds = glpgp_now() - t0;
    if (j->st != GLPGP_OK) glpgp_error_save(&j->err);
    glpgp_error_clear();
    __atomic_store_n(&j->done, 1, __ATOMIC_RELEASE);
    return NULL;
}

/* Start the backend's creation in a thread (or, when no thread can be
 * started, nothing: backend_job_join creates it then). */
static void backend_job_start(backend_job *j, const solve_cli *c)
{
    memset(j, 0, sizeof *j);
    j->kind = c->backend;
    j->device = c->device;
    j->verbose = 0; /* the device's lines come from the caller once it is used (glpgp_cl_backend_log) */
    j->started = pthread_create(&j->th, NULL, backend_job_run, j) == 0;
}

/* The backend (*b) once created; *wait <- seconds this thread waited for it.
 * A failure is the caller's error record. */
static glpgp_status backend_job_join(backend_job *j, glpgp_backend **b, double *wait)
{
    const double t0 = glpgp_now();
    if (j->started) pthread_join(j->th, NULL);
    else backend_job_run(j);
    j->started = 0;
    *wait = glpgp_now() - t0;
    *b = j->b;
    j->b = NULL;
    return j->st == GLPGP_OK ? GLPGP_OK : glpgp_error_restore(&j->err);
}

/* The input failed while the backend was being created in its thread: the
 * backend is not needed. The thread stops at its next check (before the
 * program build, between first launches) but cannot leave the OpenCL
 * runtime's initialisation early (PoCL: about 0.3 s); after 20 ms of waiting
 * the command ends without it (_exit after flushing: no atexit handler may
 * race with a thread inside the runtime). Returns rc otherwise. */
static int backend_job_abandon(backend_job *j, int rc)
{
    __atomic_store_n(&j->stop, 1, __ATOMIC_RELAXED);
    if (j->started) {
        for (int k = 0; k < 20 && !__atomic_load_n(&j->done, __ATOMIC_ACQUIRE); k++) {
            const struct timespec ms = {0, 1000000};
            nanosleep(&ms, NULL);
        }
        if (!__atomic_load_n(&j->done, __ATOMIC_ACQUIRE)) {
            fflush(stdout);
            fflush(stderr);
            _exit(rc);
        }
    }
    glpgp_error_copy keep; /* the input's error, not the backend's */
    glpgp_error_save(&keep);
    glpgp_backend *b = NULL;
    double w = 0.0;
    if (backend_job_join(j, &b, &w) == GLPGP_OK) glpgp_backend_destroy(&b);
    glpgp_error_restore(&keep);
    return rc;
}

/* A quad count this many times off --faces (either way) is warned about. */
#define GLPGP_FACES_OFF 3.0

/* The one flow of every run: read, solve (serial, or glpgp_solve_distributed
 * on MPI ranks: dd), compute the outputs, write them together. */
/* --quads: the quad mesh of result r on mesh m, its report (a surface's:
 * also the distance to the input as read where it was denoised), and the
 * verdict (*invalid_rc: an invalid mesh is not written, exit 3, unless
 * --allow-invalid; why: the reasons). */
static glpgp_status build_quads(solve_cli *c, const glpgp_mesh *m, const glpgp_result *r, glpgp_quadmesh **q,
                                glpgp_quads_report *qq, int *invalid_rc, char *why, size_t nwhy)
{
    double h = r->size;
    if (m->surf) { /* a surface: its own pipeline and check (quads/quads_surface.c) */
        GLPGP_CHECK(glpgp_quads_build_surface(m, r, &c->qo, q, &h, &c->qsteps));
        GLPGP_CHECK(glpgp_quads_quality_surface(*q, m, h, qq));
        if (c->input_mesh) { /* denoised: the distance to the input as read */
            glpgp_quads_report qi;
            GLPGP_CHECK(glpgp_quads_quality_surface(*q, c->input_mesh, h, &qi));
            c->hausdorff_input = qi.hausdorff;
        }
        qq->steps = c->qsteps;
        qq->has_steps = 1;
    } else {
        GLPGP_CHECK(glpgp_quads_build(m, r, &c->qo, q, &h));
        GLPGP_CHECK(glpgp_quads_quality(*q, m, h, qq));
    }
    qq->singular[0] = r->osc[0].plus + r->osc[0].minus;
    qq->singular[1] = r->osc[1].plus + r->osc[1].minus;
    /* --field cross: irregular interior vertices within h of a cross-field singularity, and the others */
    if (r->cross) GLPGP_CHECK(glpgp_quads_quality_cross(*q, r->cross->sing, r->cross->nsing, r->size, qq));
    /* --faces N far from the count made: said, with the step it came from */
    const int nf = qq->quads + qq->others;
    if (c->faces > 0.0 && (nf > GLPGP_FACES_OFF * c->faces || GLPGP_FACES_OFF * nf < c->faces))
        glpgp_log(GLPGP_LOG_WARNING, "quads: %d faces for the %.0f asked (--faces)%s", nf, c->faces,
                  m->surf && c->qsteps.fallback     ? ": the last resort's (no valid mesh from the parametrization)"
                  : m->surf && c->qsteps.subdivided ? ": the extraction split once (h/2)"
                                                    : "");
    *invalid_rc = glpgp_cli_quads_verdict(qq, c->qo.keep_polygons ? GLPGP_QUADS_BAD_NONQUAD : 0u, c->allow_invalid,
                                          why, nwhy);
    return GLPGP_OK;
}

static int solve_main(solve_cli *cc, const char *input, glpgp_dist *dd)
{
    solve_cli c = *cc;
    int rc;
    double t0 = glpgp_now();
    glpgp_mesh *m = NULL;
    glpgp_backend *b = NULL;
    char device_buf[512];
    const char *device = NULL; /* the OpenCL device (summary, stats), NULL on other backends */
    glpgp_result *r = NULL;
    glpgp_quadmesh *q = NULL;
    glpgp_image *im = NULL;
    glpgp_output_set *outs = NULL;
    glpgp_quads_report qq;
    memset(&qq, 0, sizeof qq);
    int invalid_rc = -1;
    int nranks = 0;             /* --backend petsc: MPI ranks, per-rank numbers */
    const double *rank_info = NULL;
    char why[1024] = "";
    glpgp_size_image *simg = NULL; /* --size-field IMAGE */
    double t_read = 0.0, t_build_wait = 0.0, t_build = 0.0;
    glpgp_timers cli_tm; /* the phases measured here (read, program build, outputs) */
    memset(&cli_tm, 0, sizeof cli_tm);
    backend_job bj;
    memset(&bj, 0, sizeof bj);
    memset(&c.refined, 0, sizeof c.refined);
    memset(&c.denoise, 0, sizeof c.denoise);
    c.input_mesh = NULL;
    c.hausdorff_input = -1.0;
    if (glpgp_dist_reads(dd)) { /* (a split run's other ranks get their part from rank 0) */
        /* the backend (program build) in a thread while the input is read */
        if (!dd) backend_job_start(&bj, &c);
        if ((rc = prepare(&c, input, &m, &simg)) >= 0) return dd ? rc : backend_job_abandon(&bj, rc);
        t_read = glpgp_now() - t0;
    }
    cli_tm.s[GLPGP_TM_READ] = t_read - c.t_refine;
    cli_tm.s[GLPGP_TM_REFINE] = c.t_refine;
    rc = GLPGP_EXIT_FAIL;

    if (dd) { /* MPI ranks: scatter, solve, gather or pieces, verdicts (glpgp/distributed.h) */
        if (glpgp_output_set_create(&outs) != GLPGP_OK) goto fail;
        int finished = 0;
        if (glpgp_solve_distributed(dd, m, &c.o, outs, &r, &finished) != GLPGP_OK) goto fail;
        t_build = t_build_wait = glpgp_dist_build_seconds(dd);
        rank_info = glpgp_dist_rank_info(dd, &nranks);
        if (rank_info && c.verbosity > 0)
            for (int k = 0; k < nranks; k++) {
                const double *ri = rank_info + (size_t)k * GLPGP_RANK_INFO_N;
                glpgp_log(GLPGP_LOG_INFO, "rank %d: %.0f owned + %.0f ghost vertices, solve %.3f s, max RSS %.1f MiB",
                          k, ri[0], ri[1], ri[2], ri[3] / 1048576.0);
            }
        if (finished) { /* a rank other than 0: its piece committed with the others */
            rc = 0;
            goto done;
        }
    } else {
        if (backend_job_join(&bj, &b, &t_build_wait) != GLPGP_OK) goto fail;
        t_build = bj.seconds;
        if (c.verbosity > 0) glpgp_cl_backend_log(b);
        if (glpgp_solve(m, b, &c.o, &r) != GLPGP_OK) goto fail;
        if (glpgp_cl_backend_info(b, device_buf, sizeof device_buf) >= 0) device = device_buf;
    }
    /* program build: the backend's creation (in the background); its wait: what the run waited for it */
    cli_tm.s[GLPGP_TM_BUILD] = t_build;
    cli_tm.wait[GLPGP_TM_BUILD] = t_build_wait;
    /* everything computed before anything is written */
    double tp = glpgp_now();
    if (c.quads && build_quads(&c, m, r, &q, &qq, &invalid_rc, why, sizeof why) != GLPGP_OK) goto fail;
    cli_tm.s[GLPGP_TM_EXTRACT] = glpgp_now() - tp;
    tp = glpgp_now();
    if (c.image && c.quads && !c.image_kind_given && !m->surf) { /* a surface: the grid picture (render3d) */
        if (glpgp_render_quadmesh(q, m, &c.ro, GLPGP_QUADS_SJ_GOAL, 1, &im) != GLPGP_OK) goto fail;
    } else if (c.image && glpgp_render(m, r, &c.ro, &im) != GLPGP_OK) {
        goto fail;
    }
    cli_tm.s[GLPGP_TM_IMAGE] = glpgp_now() - tp;

    /* outputs: one set, committed together (all or nothing: a failure leaves
     * every existing file as it was and no temporary behind) */
    if (!outs && glpgp_output_set_create(&outs) != GLPGP_OK) goto fail;
    tp = glpgp_now();
    if (c.out && !c.pieces && glpgp_output_set_result(outs, m, &c.o, r, c.out) != GLPGP_OK) goto fail;
    cli_tm.s[GLPGP_TM_OUT_RESULT] += glpgp_now() - tp;
    tp = glpgp_now();
    if (c.quads && invalid_rc < 0 && glpgp_output_set_quads(outs, q, c.quads) != GLPGP_OK) goto fail;
    cli_tm.s[GLPGP_TM_OUT_QUADS] = glpgp_now() - tp;
    tp = glpgp_now();
    if (c.image) { /* the picture is written under the set's temporary name */
        const char *tmp = NULL;
        if (glpgp_output_set_reserve(outs, c.image, &tmp) != GLPGP_OK) goto fail;
        if (glpgp_image_write(tmp, im) != GLPGP_OK) goto fail;
    }
    cli_tm.s[GLPGP_TM_OUT_IMAGE] = glpgp_now() - tp;
    /* the run's phases: the solve's and this command's (the statistics last:
     * they report every phase before them) */
    glpgp_timers_add(&r->timers, &cli_tm);
    if (c.stats) {
        glpgp_stats_extra x = {input, c.out, t_read, c.quads ? &qq : NULL, nranks, rank_info, device,
                               c.denoise.rounds ? &c.denoise : NULL, c.denoise_h, c.hausdorff_input};
        if (glpgp_output_set_stats(outs, m, &c.o, r, c.stats, &x) != GLPGP_OK) goto fail;
    }
    /* distributed .pvtu: every rank's files complete, then every rank commits */
    if (glpgp_dist_commit(dd, outs) != GLPGP_OK) goto fail;

    if (c.o.method == GLPGP_METHOD_GL && (r->osc[0].zabs_median < 0.5 || r->osc[1].zabs_median < 0.5))
        glpgp_log(GLPGP_LOG_WARNING,
                  "median |z| < 0.5: the oscillators collapsed towards z = 0 (h = %g is %.1f mean edges; "
                  "P1 needs about 10 per period): raise --size or refine the mesh",
                  r->size, r->size / m->mean_edge);
    print_summary(&c, input, m, r, device, glpgp_now() - t0, t_read, &qq, invalid_rc < 0);
    rc = invalid_rc < 0 ? 0 : glpgp_cli_invalid(why, "not written (--allow-invalid writes it anyway)");
    goto done;
fail:
    if (bj.started) { /* a failure before the backend was needed: wait for its thread */
        glpgp_error_copy keep;
        glpgp_error_save(&keep);
        __atomic_store_n(&bj.stop, 1, __ATOMIC_RELAXED);
        glpgp_backend *bb = NULL;
        double w = 0.0;
        if (backend_job_join(&bj, &bb, &w) == GLPGP_OK) glpgp_backend_destroy(&bb);
        glpgp_error_restore(&keep);
    }
    rc = glpgp_cli_fail();
done:
    glpgp_output_set_destroy(&outs);
    glpgp_image_destroy(&im);
    glpgp_quadmesh_destroy(&q);
    glpgp_result_destroy(&r);
    glpgp_backend_destroy(&b);
    glpgp_mesh_destroy(&m);
    glpgp_mesh_destroy(&c.input_mesh);
    glpgp_size_image_destroy(&simg);
    return rc;
}
