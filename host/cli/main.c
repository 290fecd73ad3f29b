/* cli/main.c: the `glpgp` command-line tool: argument parsing and validation,
 * subcommand dispatch (solve, generate, devices, crosscheck, help), backend
 * selection with OpenCL -> reference fallback, result and statistics output,
 * and the only place that prints errors and decides exit codes:
 *   0 success, 1 failure (message "glpgp: error: ..." on stderr),
 *   2 usage error (bad/unknown option or value). */
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

#include "glpgp/backends.h"
#include "glpgp/shapes.h"
#include "glpgp/util.h"
#include "glpgp/version.h"
#include "cli.h"
#include "commands.h"
#include "glpgp/image.h"
#include "glpgp/mesh.h"
#include "glpgp/io.h"
#include "glpgp/quads.h"
#include "glpgp/solve.h"
#include "glpgp/status.h"

#define EXIT_USAGE GLPGP_EXIT_USAGE
#define DEFAULT_SHAPE_VERTICES GLPGP_SHAPE_DEFAULT_VERTICES

/* ---- small helpers ----------------------------------------------------- */

static double now_seconds(void) { return glpgp_now(); }

static int fail_with_error(void) { return glpgp_cli_fail(); }

/* Print a usage error for subcommand `sub` and return exit code 2. */
static int usage_error(const char *sub, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static int usage_error(const char *sub, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("glpgp: usage error: ", stderr);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    if (sub)
        fprintf(stderr, "\nTry 'glpgp %s --help' for the options.\n", sub);
    else
        fputs("\nTry 'glpgp --help'.\n", stderr);
    return EXIT_USAGE;
}

static void print_shapes(FILE *f)
{
    const char *const *s = glpgp_mesh_shapes();
    for (int i = 0; s && s[i]; i++) fprintf(f, "%s%s", i ? ", " : "", s[i]);
}

static int shape_known(const char *name) { return glpgp_shape_known(name); }

/* ---- help texts -------------------------------------------------------- */

static void usage_main(FILE *f)
{
    fprintf(f,
            "glpgp %s - quad-mesh parametrization of planar domains with the\n"
            "Ginzburg-Landau periodic global parametrization (GL-PGP).\n"
            "\n"
            "Usage: glpgp <command> [arguments]\n"
            "\n"
            "Commands:\n"
            "  solve INPUT [options]      compute z_u, z_v on a mesh (.obj/.msh) or a\n"
            "                             built-in domain shape:NAME[:N]; write .vtk/.obj\n"
            "                             and statistics .json\n"
            "  generate SHAPE --vertices N -o FILE\n"
            "                             write a built-in domain as .obj or .msh\n"
            "  devices                    list OpenCL platforms and devices\n"
            "  crosscheck INPUT [options] compare the OpenCL and reference paths stage by stage\n"
            "  extract RESULT.vtk --quads OUT.{obj,vtk,msh}\n"
            "                             quad mesh and its quality report from a result\n"
            "  quality MESH.msh [--size H] quality report of a quad mesh made elsewhere\n"
            "  render RESULT.vtk -o OUT.png   picture of a result (grid texture, ...)\n"
            "  mesh MASK.png -o DOMAIN.msh    triangle mesh of a mask image (Gmsh)\n"
            "  figure INPUT -o OUT.png    naive PGP and GL-PGP side by side\n"
            "  help [COMMAND]             show this overview or a command's options\n"
            "\n"
            "Options: --help (this text), --version.\n"
            "Run 'glpgp <command> --help' for the options of a command.\n"
            "Exit codes: 0 success, 1 failure, 2 usage error.\n",
            GLPGP_VERSION);
}

static void usage_solve(FILE *f)
{
    glpgp_options d;
    glpgp_options_default(&d);
    fprintf(f,
            "Usage: glpgp solve INPUT [options]\n"
            "\n"
            "INPUT is a triangle mesh of a planar domain (.obj, or Gmsh .msh 2.2/4.1 ASCII)\n"
            "or shape:NAME[:N], a built-in domain with about N vertices (default %ld);\n"
            "NAME is one of: ",
            DEFAULT_SHAPE_VERTICES);
    print_shapes(f);
    fprintf(f,
            ".\n"
            "\n"
            "Parametrization:\n"
            "  --size H            target quad size h (> 0; default: bounding-box diagonal / 20,\n"
            "                      raised to 10 mean edge lengths on coarse meshes)\n"
            "  --method gl|pgp     Ginzburg-Landau continuation or naive PGP (default: %s)\n"
            "  --energy p1|transport\n"
            "                      discretisation of the quadratic energy (default: %s)\n"
            "  --newton mixed|projected|paper\n"
            "                      penalty Hessian used by Newton: exact where |z|^2 >= 1/2 and\n"
            "                      projected in vortex cores, projected (PSD) everywhere, or\n"
            "                      the paper's eq. 8 (default: %s)\n"
            "  --field boundary|radial|FILE\n"
            "                      guiding field U: smooth field aligned with the boundary,\n"
            "                      radial about --center, or one \"ux uy\" line per vertex\n"
            "                      from FILE (default: boundary)\n"
            "  --center X,Y        centre of the radial field (default: area centroid)\n"
            "  --init naive|one    initial guess of the GL continuation (default: %s)\n"
            "\n"
            "Continuation and solvers:\n"
            "  --eps0 F            first eps, as a multiple of h (> 0; default: %g)\n"
            "  --eps-ratio F       eps_{k+1} = F eps_k (0 < F < 1; default: %g)\n"
            "  --eps-min F         last eps, as a multiple of the mean edge (> 0; default: %g)\n"
            "  --newton-rtol F     stop a level when |g| <= F |g0| (0 < F < 1; default: %g)\n"
            "  --newton-max N      Newton iterations per eps level (>= 1; default: %d)\n"
            "  --cg-rtol F         CG stops when |r| <= F |b| (0 < F < 1; default: %g)\n"
            "  --cg-max N          CG iteration cap (>= 1; default: %d)\n"
            "  --cg-check N        read the CG residual back every N iterations (>= 1; default: %d)\n"
            "  --precond jacobi|amg\n"
            "                      preconditioner: 2x2-block Jacobi CG, or aggregation multigrid\n"
            "                      in flexible CG (default: %s; backends without multigrid use\n"
            "                      Jacobi with one warning)\n"
            "\n"
            "Backend:\n"
            "  --backend auto|opencl|reference\n"
            "                      auto tries OpenCL and falls back to the reference C path\n"
            "                      with one warning (default: auto)\n"
            "  --device N          OpenCL device index as listed by 'glpgp devices'\n"
            "                      (>= 0; default: $GLPGP_DEVICE or the first fp64 device;\n"
            "                      with --device, a failing OpenCL backend is an error)\n"
            "\n"
            "Output:\n"
            "  --out FILE, -o FILE result as .vtk (ParaView) or .obj (texture coordinates)\n"
            "  --stats FILE        statistics as JSON\n"
            "  --quads FILE        extract the quad mesh (.obj/.vtk/.msh) and add its quality\n"
            "                      report to the summary and the statistics (\"quads\")\n"
            "  --keep-polygons     with --quads: keep the faces left around dislocations as\n"
            "                      polygons (default: join them pairwise or to the boundary\n"
            "                      by strips of quads cut in two: all quads, same size)\n"
            "  --smooth N          with --quads: smoothing sweeps around the new vertices and\n"
            "                      the faces with scaled Jacobian < 0.5 (default 20, 0: off;\n"
            "                      a move is kept only if no nearby corner gets worse)\n"
            "  --all-quads         with --quads: refine every face into quads (centroid +\n"
            "                      edge midpoints): half the element size\n"
            "  --quiet             no progress on stderr\n"
            "  --verbose           more progress on stderr (debug level)\n"
            "  --help, -h          this text\n"
            "\n"
            "Files are written only after a successful solve, atomically (no partial\n"
            "file is ever left). A summary is printed on stdout.\n",
            d.method == GLPGP_METHOD_PGP ? "pgp" : "gl",
            d.energy == GLPGP_ELEM_TRANSPORT ? "transport" : "p1",
            d.hess == GLPGP_HESS_PAPER       ? "paper"
            : d.hess == GLPGP_HESS_MIXED   ? "mixed"
            : d.hess == GLPGP_HESS_EXACT   ? "exact"
                                           : "projected",
            d.init == GLPGP_INIT_ONE ? "one" : "naive", d.eps0, d.eps_ratio, d.eps_min,
            d.newton_rtol, d.newton_max, d.cg_rtol, d.cg_max, d.cg_check,
            d.precond == GLPGP_PRECOND_AMG ? "amg" : "jacobi");
    fputc('\n', f);
    glpgp_solve_image_usage(f);
}

static void usage_generate(FILE *f)
{
    fprintf(f,
            "Usage: glpgp generate SHAPE [--vertices N] -o FILE\n"
            "\n"
            "Write a built-in domain meshed with about N vertices.\n"
            "  SHAPE               one of: ");
    print_shapes(f);
    fprintf(f,
            "\n"
            "  --vertices N, -n N  approximate vertex count (>= 16; default: %ld)\n"
            "  --out FILE, -o FILE output mesh, .obj or .msh (Gmsh 4.1 ASCII)\n"
            "  --help, -h          this text\n",
            DEFAULT_SHAPE_VERTICES);
}

/* ---- option scanning --------------------------------------------------- */

/* Splits argv[*i] = "--name=value" / "--name" [value]. For options taking a
 * value, *value is set (consuming the next argument when needed); returns 0 on
 * a missing value. */
typedef struct opt_arg {
    char name[64];
    const char *value; /* from "=value", else NULL */
} opt_arg;

static void split_opt(const char *arg, opt_arg *oa)
{
    const char *eq = strncmp(arg, "--", 2) == 0 ? strchr(arg, '=') : NULL;
    size_t n = eq ? (size_t)(eq - arg) : strlen(arg);
    if (n >= sizeof oa->name) n = sizeof oa->name - 1;
    memcpy(oa->name, arg, n);
    oa->name[n] = '\0';
    oa->value = eq ? eq + 1 : NULL;
}

static int take_value(int argc, char **argv, int *i, opt_arg *oa)
{
    if (oa->value) return 1;
    if (*i + 1 >= argc) return 0;
    oa->value = argv[++*i];
    return 1;
}

/* ---- solve ------------------------------------------------------------- */

typedef struct solve_cli {
    glpgp_options o;
    const char *input;
    const char *out;
    const char *stats;
    const char *quads; /* --quads: quad mesh (cmd_quads.c) */
    glpgp_quad_options qo; /* --keep-polygons, --smooth, --all-quads */
    int quad_opts;         /* one of them was given */
    const char *backend; /* auto, opencl, reference */
    int device;
    glpgp_solve_image_cli img; /* --image ..., mask-image INPUT (cmd_image.c) */
    int verbosity;
} solve_cli;

/* Returns -1 when parsing succeeded, else the exit code (0 for --help). */
static int parse_solve(int argc, char **argv, solve_cli *c)
{
    const char *sub = "solve";
    glpgp_options_default(&c->o);
    c->verbosity = 1;
    c->input = c->out = c->stats = c->quads = NULL;
    glpgp_quad_options_default(&c->qo);
    c->quad_opts = 0;
    c->backend = "auto";
    c->device = -1;
    glpgp_solve_image_init(&c->img);

    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (arg[0] != '-' || arg[1] == '\0') {
            if (c->input) return usage_error(sub, "unexpected argument '%s'", arg);
            c->input = arg;
            continue;
        }
        opt_arg oa;
        split_opt(arg, &oa);
        const char *nm = oa.name;
        int is_flag = !strcmp(nm, "--help") || !strcmp(nm, "-h") || !strcmp(nm, "--quiet") ||
                      !strcmp(nm, "--verbose") || !strcmp(nm, "--all-quads") ||
                      !strcmp(nm, "--keep-polygons");
        if (is_flag) {
            if (oa.value) return usage_error(sub, "option %s takes no value", nm);
            if (!strcmp(nm, "--all-quads") || !strcmp(nm, "--keep-polygons")) {
                if (!strcmp(nm, "--all-quads"))
                    c->qo.all_quads = 1;
                else
                    c->qo.keep_polygons = 1;
                c->quad_opts = 1;
                continue;
            }
            if (!strcmp(nm, "--help") || !strcmp(nm, "-h")) {
                usage_solve(stdout);
                return 0;
            }
            c->verbosity = !strcmp(nm, "--quiet") ? 0 : 2;
            continue;
        }
        int img_opt = glpgp_solve_image_option(nm); /* 1 flag, 2 valued (cmd_image.c) */
        if (img_opt) {
            if (img_opt == 1 && oa.value) return usage_error(sub, "option %s takes no value", nm);
            if (img_opt == 2 && !take_value(argc, argv, &i, &oa))
                return usage_error(sub, "option %s needs a value", nm);
            int irc = glpgp_solve_image_parse(&c->img, nm, oa.value);
            if (irc >= 0) return irc;
            continue;
        }
        static const char *const valued[] = {
            "--size",       "--method",   "--energy",    "--newton",   "--field",
            "--center",     "--init",     "--eps0",      "--eps-ratio", "--eps-min",
            "--newton-rtol", "--newton-max", "--cg-rtol", "--cg-max",   "--cg-check",
            "--backend",    "--device",   "--out",       "-o",         "--stats",    "--quads",
            "--smooth",     "--precond",  NULL};
        int known = 0;
        for (int k = 0; valued[k]; k++)
            if (!strcmp(nm, valued[k])) known = 1;
        if (!known) return usage_error(sub, "unknown option '%s'", arg);
        if (!take_value(argc, argv, &i, &oa))
            return usage_error(sub, "option %s needs a value", nm);
        const char *v = oa.value;
        double dv;
        long lv;

        if (!strcmp(nm, "--size")) {
            if (!glpgp_cli_double(v, &dv) || !(dv > 0))
                return usage_error(sub, "--size: '%s' is not a positive number", v);
            c->o.size = dv;
        } else if (!strcmp(nm, "--method")) {
            if (!strcmp(v, "gl"))
                c->o.method = GLPGP_METHOD_GL;
            else if (!strcmp(v, "pgp"))
                c->o.method = GLPGP_METHOD_PGP;
            else
                return usage_error(sub, "--method: '%s' is not one of gl, pgp", v);
        } else if (!strcmp(nm, "--energy")) {
            if (!strcmp(v, "p1"))
                c->o.energy = GLPGP_ELEM_P1;
            else if (!strcmp(v, "transport"))
                c->o.energy = GLPGP_ELEM_TRANSPORT;
            else
                return usage_error(sub, "--energy: '%s' is not one of p1, transport", v);
        } else if (!strcmp(nm, "--newton")) {
            if (!strcmp(v, "mixed"))
                c->o.hess = GLPGP_HESS_MIXED;
            else if (!strcmp(v, "projected"))
                c->o.hess = GLPGP_HESS_PROJECTED;
            else if (!strcmp(v, "paper"))
                c->o.hess = GLPGP_HESS_PAPER;
            else
                return usage_error(sub, "--newton: '%s' is not one of mixed, projected, paper", v);
        } else if (!strcmp(nm, "--field")) {
            if (!*v) return usage_error(sub, "--field: empty value");
            if (!strcmp(v, "boundary")) {
                c->o.field = GLPGP_FIELD_BOUNDARY;
                c->o.field_file = NULL;
            } else if (!strcmp(v, "radial")) {
                c->o.field = GLPGP_FIELD_RADIAL;
                c->o.field_file = NULL;
            } else {
                c->o.field = GLPGP_FIELD_FILE;
                c->o.field_file = v;
            }
        } else if (!strcmp(nm, "--center")) {
            const char *comma = strchr(v, ',');
            char xs[128];
            double cx, cy;
            size_t n = comma ? (size_t)(comma - v) : 0;
            if (!comma || n >= sizeof xs)
                return usage_error(sub, "--center: '%s' is not X,Y", v);
            memcpy(xs, v, n);
            xs[n] = '\0';
            if (!glpgp_cli_double(xs, &cx) || !glpgp_cli_double(comma + 1, &cy))
                return usage_error(sub, "--center: '%s' is not X,Y (two numbers)", v);
            c->o.has_center = 1;
            c->o.center[0] = cx;
            c->o.center[1] = cy;
        } else if (!strcmp(nm, "--init")) {
            if (!strcmp(v, "naive"))
                c->o.init = GLPGP_INIT_NAIVE;
            else if (!strcmp(v, "one"))
                c->o.init = GLPGP_INIT_ONE;
            else
                return usage_error(sub, "--init: '%s' is not one of naive, one", v);
        } else if (!strcmp(nm, "--eps0") || !strcmp(nm, "--eps-min")) {
            if (!glpgp_cli_double(v, &dv) || !(dv > 0))
                return usage_error(sub, "%s: '%s' is not a positive number", nm, v);
            if (!strcmp(nm, "--eps0"))
                c->o.eps0 = dv;
            else
                c->o.eps_min = dv;
        } else if (!strcmp(nm, "--eps-ratio") || !strcmp(nm, "--newton-rtol") ||
                   !strcmp(nm, "--cg-rtol")) {
            if (!glpgp_cli_double(v, &dv) || !(dv > 0 && dv < 1))
                return usage_error(sub, "%s: '%s' is not a number in (0, 1)", nm, v);
            if (!strcmp(nm, "--eps-ratio"))
                c->o.eps_ratio = dv;
            else if (!strcmp(nm, "--newton-rtol"))
                c->o.newton_rtol = dv;
            else
                c->o.cg_rtol = dv;
        } else if (!strcmp(nm, "--newton-max") || !strcmp(nm, "--cg-max") ||
                   !strcmp(nm, "--cg-check")) {
            if (!glpgp_cli_long(v, 1, INT_MAX, &lv))
                return usage_error(sub, "%s: '%s' is not an integer >= 1", nm, v);
            if (!strcmp(nm, "--newton-max"))
                c->o.newton_max = (int)lv;
            else if (!strcmp(nm, "--cg-max"))
                c->o.cg_max = (int)lv;
            else
                c->o.cg_check = (int)lv;
        } else if (!strcmp(nm, "--smooth")) {
            if (!glpgp_cli_long(v, 0, 100000, &lv))
                return usage_error(sub, "--smooth: '%s' is not an integer >= 0", v);
            c->qo.smooth = (int)lv;
            c->quad_opts = 1;
        } else if (!strcmp(nm, "--precond")) {
            if (!strcmp(v, "jacobi"))
                c->o.precond = GLPGP_PRECOND_JACOBI;
            else if (!strcmp(v, "amg"))
                c->o.precond = GLPGP_PRECOND_AMG;
            else
                return usage_error(sub, "--precond: '%s' is not one of jacobi, amg", v);
        } else if (!strcmp(nm, "--backend")) {
            if (strcmp(v, "auto") && strcmp(v, "opencl") && strcmp(v, "reference"))
                return usage_error(sub, "--backend: '%s' is not one of auto, opencl, reference",
                                   v);
            c->backend = v;
        } else if (!strcmp(nm, "--device")) {
            if (!glpgp_cli_long(v, 0, INT_MAX, &lv))
                return usage_error(sub, "--device: '%s' is not an integer >= 0", v);
            c->device = (int)lv;
        } else if (!strcmp(nm, "--out") || !strcmp(nm, "-o")) {
            if (!glpgp_result_path_supported(v))
                return usage_error(sub, "--out: '%s' must end in .vtk or .obj", v);
            c->out = v;
        } else if (!strcmp(nm, "--stats")) {
            if (!*v) return usage_error(sub, "--stats: empty path");
            c->stats = v;
        } else if (!strcmp(nm, "--quads")) {
            if (!glpgp_quads_path_supported(v))
                return usage_error(sub, "--quads: '%s' must end in .obj, .vtk or .msh", v);
            c->quads = v;
        }
    }
    if (!c->input) return usage_error(sub, "missing INPUT (a .obj/.msh file or shape:NAME[:N])");
    if (c->out && c->stats && !strcmp(c->out, c->stats))
        return usage_error(sub, "--out and --stats name the same file '%s'", c->out);
    if (c->quad_opts && !c->quads)
        return usage_error(sub, "--all-quads, --keep-polygons and --smooth need --quads FILE");
    if (c->quads && ((c->out && !strcmp(c->out, c->quads)) || (c->stats && !strcmp(c->stats, c->quads))))
        return usage_error(sub, "--quads names the same file as --out or --stats: '%s'", c->quads);
    return -1;
}

/* Read or generate the input mesh. Returns -1 on success, else an exit code. */
static int load_input(const char *input, glpgp_mesh **m)
{
    if (strncmp(input, "shape:", 6) == 0) {
        char name[64];
        long nverts;
        if (glpgp_shape_parse(input, 0, name, sizeof name, &nverts) != GLPGP_OK) {
            int rc = glpgp_cli_usage_error("solve", "INPUT %s", glpgp_error_message());
            glpgp_error_clear();
            return rc;
        }
        if (glpgp_mesh_generate(name, nverts, m) != GLPGP_OK) return fail_with_error();
        return -1;
    }
    if (glpgp_mesh_read(input, m) != GLPGP_OK) return fail_with_error();
    return -1;
}

static int create_backend(const solve_cli *c, glpgp_backend **b)
{
    if (glpgp_backend_select(glpgp_backend_kind_parse(c->backend), c->device, c->verbosity > 0, b) !=
        GLPGP_OK)
        return fail_with_error();
    return -1;
}

static int cmd_solve(int argc, char **argv)
{
    solve_cli c;
    int rc = parse_solve(argc, argv, &c);
    if (rc >= 0) return rc;
    glpgp_error_clear();
    glpgp_cli_set_verbosity(c.verbosity);

    double t0 = now_seconds();
    if (c.out && glpgp_output_path_check(c.out) != GLPGP_OK) return fail_with_error();
    if (c.stats && glpgp_output_path_check(c.stats) != GLPGP_OK) return fail_with_error();
    if (c.img.image && glpgp_output_path_check(c.img.image) != GLPGP_OK) return fail_with_error();

    glpgp_mesh *m = NULL;
    glpgp_backend *b = NULL;
    glpgp_result *r = NULL;
    if (glpgp_is_image_path(c.input)) /* mask image: meshed on the fly */
        rc = glpgp_solve_image_load(&c.img, c.input, c.o.size, c.verbosity > 0, &m);
    else
        rc = load_input(c.input, &m);
    if (rc >= 0) return rc;
    double t_read = now_seconds() - t0;

    rc = create_backend(&c, &b);
    if (rc >= 0) goto done;

    if (glpgp_solve(m, b, &c.o, &r) != GLPGP_OK) {
        rc = fail_with_error();
        goto done;
    }

    /* Outputs: each atomic; if the second fails, the first is removed too so
     * a failed run leaves no output behind. */
    if (c.out && glpgp_write_result(m, &c.o, r, c.out) != GLPGP_OK) {
        rc = fail_with_error();
        goto done;
    }
    if (c.stats) {
        glpgp_stats_extra x;
        x.input = c.input;
        x.output = c.out;
        x.seconds_read = t_read;
        if (glpgp_write_stats_json(m, &c.o, r, c.stats, &x) != GLPGP_OK) {
            if (c.out) remove(c.out);
            rc = fail_with_error();
            goto done;
        }
    }

    glpgp_quad_quality qq;
    if (c.quads && (rc = glpgp_solve_quads(m, r, c.quads, c.stats, &c.qo, &qq)) >= 0) {
        if (c.out) remove(c.out);
        if (c.stats) remove(c.stats);
        goto done;
    }

    if (c.img.image && (rc = glpgp_solve_image_write(&c.img, m, r)) >= 0) {
        if (c.quads) remove(c.quads);
        if (c.out) remove(c.out);
        if (c.stats) remove(c.stats);
        goto done;
    }

    double t_all = now_seconds() - t0;
    const glpgp_osc_result *u = &r->osc[0], *v = &r->osc[1];
    printf("glpgp: %s: %d vertices, %d triangles, h = %.6g, backend %s\n", c.input, m->nv, m->nt,
           r->size, r->backend ? r->backend : "?");
    printf("  singularities  u: +%d -%d   v: +%d -%d\n", u->plus, u->minus, v->plus, v->minus);
    printf("  median |z|     u: %.4f   v: %.4f\n", u->zabs_median, v->zabs_median);
    if (u->zabs_median < 0.5 || v->zabs_median < 0.5) /* not silenced by --quiet: the result is poor */
        fprintf(stderr,
                "glpgp: warning: median |z| < 0.5: the oscillators collapsed towards z = 0 (h = %g is "
                "%.1f mean edges; P1 needs about 10 per period): raise --size or refine the mesh\n",
                r->size, r->size / m->mean_edge);
    printf("  iterations     newton %d (u %d, v %d), cg %ld\n",
           u->newton_iterations + v->newton_iterations, u->newton_iterations,
           v->newton_iterations, u->cg_iterations + v->cg_iterations + r->field_cg_iterations);
    printf("  time           %.3f s (read %.3f s, solve %.3f s)\n", t_all, t_read,
           r->seconds_total);
    if (c.out) printf("  wrote          %s\n", c.out);
    if (c.stats) printf("  wrote          %s\n", c.stats);
    if (c.quads) {
        glpgp_quads_print(stdout, &qq, "  ");
        printf("  wrote          %s\n", c.quads);
    }
    if (c.img.image) printf("  wrote          %s\n", c.img.image);
    rc = 0;

done:
    glpgp_result_destroy(&r);
    glpgp_backend_destroy(&b);
    glpgp_mesh_destroy(&m);
    return rc;
}

/* ---- generate ---------------------------------------------------------- */

static int cmd_generate(int argc, char **argv)
{
    const char *sub = "generate";
    const char *shape = NULL, *out = NULL;
    long nverts = DEFAULT_SHAPE_VERTICES;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (arg[0] != '-' || arg[1] == '\0') {
            if (shape) return usage_error(sub, "unexpected argument '%s'", arg);
            shape = arg;
            continue;
        }
        opt_arg oa;
        split_opt(arg, &oa);
        const char *nm = oa.name;
        if (!strcmp(nm, "--help") || !strcmp(nm, "-h")) {
            if (oa.value) return usage_error(sub, "option %s takes no value", nm);
            usage_generate(stdout);
            return 0;
        }
        if (strcmp(nm, "--vertices") && strcmp(nm, "-n") && strcmp(nm, "--out") &&
            strcmp(nm, "-o"))
            return usage_error(sub, "unknown option '%s'", arg);
        if (!take_value(argc, argv, &i, &oa))
            return usage_error(sub, "option %s needs a value", nm);
        if (!strcmp(nm, "--vertices") || !strcmp(nm, "-n")) {
            if (!glpgp_cli_long(oa.value, 16, 100000000L, &nverts))
                return usage_error(sub, "%s: '%s' is not an integer >= 16", nm, oa.value);
        } else {
            if (!glpgp_has_ext(oa.value, ".obj") && !glpgp_has_ext(oa.value, ".msh"))
                return usage_error(sub, "%s: '%s' must end in .obj or .msh", nm, oa.value);
            out = oa.value;
        }
    }
    if (!shape) return usage_error(sub, "missing SHAPE");
    if (!out) return usage_error(sub, "missing -o FILE");
    if (strncmp(shape, "shape:", 6) == 0) shape += 6;
    if (!shape_known(shape)) {
        fprintf(stderr, "glpgp: usage error: unknown shape '%s' (available: ", shape);
        print_shapes(stderr);
        fputs(")\n", stderr);
        return EXIT_USAGE;
    }
    glpgp_error_clear();
    glpgp_mesh *m = NULL;
    if (glpgp_mesh_generate(shape, nverts, &m) != GLPGP_OK) return fail_with_error();
    int rc = 0;
    if (glpgp_mesh_write(m, out) != GLPGP_OK)
        rc = fail_with_error();
    else
        printf("glpgp: %s: %d vertices, %d triangles -> %s\n", shape, m->nv, m->nt, out);
    glpgp_mesh_destroy(&m);
    return rc;
}

/* ---- dispatch ---------------------------------------------------------- */

int main(int argc, char **argv)
{
    glpgp_cli_set_verbosity(1);
    if (argc < 2) {
        usage_main(stderr);
        return EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h")) {
        usage_main(stdout);
        return 0;
    }
    if (!strcmp(cmd, "help")) {
        if (argc < 3) {
            usage_main(stdout);
            return 0;
        }
        if (!strcmp(argv[2], "solve")) {
            usage_solve(stdout);
            return 0;
        }
        if (!strcmp(argv[2], "generate")) {
            usage_generate(stdout);
            return 0;
        }
        if (!strcmp(argv[2], "render") || !strcmp(argv[2], "mesh") || !strcmp(argv[2], "figure")) {
            char *hargv[] = {argv[2], (char *)"--help", NULL};
            return !strcmp(argv[2], "render") ? glpgp_cmd_render(2, hargv)
                   : !strcmp(argv[2], "mesh") ? glpgp_cmd_mesh(2, hargv)
                                              : glpgp_cmd_figure(2, hargv);
        }
        if (!strcmp(argv[2], "extract") || !strcmp(argv[2], "quality")) {
            char *hargv[] = {argv[2], (char *)"--help", NULL};
            return !strcmp(argv[2], "extract") ? glpgp_cmd_extract(2, hargv)
                                               : glpgp_cmd_quality(2, hargv);
        }
        if (!strcmp(argv[2], "devices") || !strcmp(argv[2], "crosscheck")) {
            char *hargv[] = {argv[2], (char *)"--help", NULL};
            return !strcmp(argv[2], "devices") ? glpgp_cmd_devices(2, hargv)
                                               : glpgp_cmd_crosscheck(2, hargv);
        }
        return usage_error(NULL, "no help for unknown command '%s'", argv[2]);
    }
    if (!strcmp(cmd, "--version") || !strcmp(cmd, "version")) {
        printf("glpgp %s (OpenCL backend: %s; OpenImageIO: %s; Gmsh: %s)\n", GLPGP_VERSION,
               glpgp_have_opencl() ? "built in" : "not built", glpgp_have_oiio() ? "yes" : "no",
               glpgp_have_gmsh() ? "yes" : "no");
        return 0;
    }
    if (!strcmp(cmd, "solve")) return cmd_solve(argc - 1, argv + 1);
    if (!strcmp(cmd, "generate")) return cmd_generate(argc - 1, argv + 1);
    if (!strcmp(cmd, "devices")) return glpgp_cmd_devices(argc - 1, argv + 1);
    if (!strcmp(cmd, "crosscheck")) return glpgp_cmd_crosscheck(argc - 1, argv + 1);
    if (!strcmp(cmd, "render")) return glpgp_cmd_render(argc - 1, argv + 1);
    if (!strcmp(cmd, "mesh")) return glpgp_cmd_mesh(argc - 1, argv + 1);
    if (!strcmp(cmd, "figure")) return glpgp_cmd_figure(argc - 1, argv + 1);
    if (!strcmp(cmd, "extract")) return glpgp_cmd_extract(argc - 1, argv + 1);
    if (!strcmp(cmd, "quality")) return glpgp_cmd_quality(argc - 1, argv + 1);
    return usage_error(NULL, "unknown command '%s'", cmd);
}
