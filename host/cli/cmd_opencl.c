/* cmd_opencl.c: the OpenCL subcommands of the CLI:
 *   glpgp devices      list every OpenCL platform and device (the global device
 *                      index used by --device and GLPGP_DEVICE);
 *   glpgp crosscheck   run the reference and the OpenCL backend on the same mesh
 *                      and compare them stage by stage (assembly, gradient,
 *                      spmv, dot, CG, one Newton step, a whole GL solve), print
 *                      a table and exit 1 if any stage is out of tolerance.
 * The comparison is the cross-check engine of the backends layer
 * (glpgp_crosscheck_create, glpgp/backends.h: stages and tolerances); this
 * command loads the mesh and prints the engine's table. */
#include "commands.h"

#include "cli.h"
#include "glpgp/backends.h"
#include "glpgp/io.h"
#include "glpgp/mesh.h"
#include "glpgp/shapes.h"
#include "glpgp/solve.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char devices_usage[] =
    "usage: glpgp devices\n"
    "List the OpenCL platforms and devices: global index (for --device N and the\n"
    "GLPGP_DEVICE environment variable), name, vendor, version, compute units,\n"
    "global memory, double precision support and type. Exit 1 if no platform.\n";

static const char crosscheck_usage[] =
    "usage: glpgp crosscheck INPUT [--size H] [--energy p1|transport] [--device N]\n"
    "                        [--tol-scale F] [--no-solve]\n"
    "Compare the OpenCL backend with the reference backend on one mesh, stage by\n"
    "stage, and print a table; exit 1 if any stage exceeds its tolerance.\n"
    "  INPUT            a .obj/.msh mesh or shape:NAME[:N] (built-in domain, N vertices)\n"
    "  --size H         target quad size (default: bounding-box diagonal / 20)\n"
    "  --energy KIND    p1 (default) or transport\n"
    "  --device N       OpenCL device index as listed by 'glpgp devices'\n"
    "  --tol-scale F    multiply every tolerance by F (default 1)\n"
    "  --no-solve       skip the whole GL solve stage\n"
    "Tolerances (|a-b| <= atol + rtol |b|): assembly, gradient, spmv, dot rtol 1e-12;\n"
    "CG, Newton step and GL solve rtol 1e-6 on z (1e-4 for an oscillator whose GL\n"
    "levels stopped at the Newton cap: unconverged vortex drift amplifies rounding).\n"
    "The environment variable\n"
    "GLPGP_CL_CORRUPT=1 corrupts the OpenCL QUAD assembly (the check must fail).\n";

#ifndef GLPGP_HAVE_OPENCL

int glpgp_cmd_devices(int argc, char **argv)
{
    if (argc >= 2 && !strcmp(argv[1], "--help")) {
        fputs(devices_usage, stdout);
        return 0;
    }
    fprintf(stderr, "glpgp devices: this glpgp was built without OpenCL support\n");
    return 1;
}

int glpgp_cmd_crosscheck(int argc, char **argv)
{
    if (argc >= 2 && !strcmp(argv[1], "--help")) {
        fputs(crosscheck_usage, stdout);
        return 0;
    }
    fprintf(stderr, "glpgp crosscheck: this glpgp was built without OpenCL support\n");
    return 1;
}

#else /* GLPGP_HAVE_OPENCL */

static int report_error(const char *cmd)
{
    fprintf(stderr, "glpgp %s: error: %s\n", cmd, glpgp_error_message());
    glpgp_error_clear();
    return 1;
}

/* ---- glpgp devices ------------------------------------------------------- */

int glpgp_cmd_devices(int argc, char **argv)
{
    if (argc >= 2 && !strcmp(argv[1], "--help")) {
        fputs(devices_usage, stdout);
        return 0;
    }
    if (argc >= 2) {
        fprintf(stderr, "glpgp devices: usage error: unexpected argument '%s'\n", argv[1]);
        return 2;
    }
    glpgp_device_info *devs = NULL;
    int n = 0;
    if (glpgp_devices_list(&devs, &n) != GLPGP_OK) return report_error("devices");
    int last_plat = -1;
    if (n == 0) printf("OpenCL platforms found, but no devices\n");
    for (int i = 0; i < n; i++) {
        const glpgp_device_info *d = &devs[i];
        if (d->platform_index != last_plat) {
            last_plat = d->platform_index;
            printf("platform %d: %s | %s | %s\n", last_plat, d->platform, d->platform_vendor,
                   d->platform_version);
        }
        printf("  device %d: %s\n", i, d->name);
        printf("      vendor %s | %s | %u compute units | %.2f GiB global memory | fp64 %s | %s\n",
               d->vendor, d->version, d->compute_units,
               (double)d->global_mem / (1024.0 * 1024.0 * 1024.0), d->fp64 ? "yes" : "no", d->type);
    }
    free(devs);
    return 0;
}

/* ---- glpgp crosscheck ---------------------------------------------------- */

/* Read or generate the input mesh. */
static glpgp_status cc_load(const char *input, glpgp_mesh **m)
{
    if (strncmp(input, "shape:", 6) == 0) {
        char name[64];
        long nv;
        GLPGP_CHECK(glpgp_shape_parse(input, 0, name, sizeof name, &nv));
        return glpgp_mesh_generate(name, nv, m);
    }
    return glpgp_mesh_read(input, m);
}

/* What the engine compared (the lines it got to), then the table. */
static void cc_print(const char *input, const glpgp_crosscheck *t)
{
    if (t->device[0]) {
        printf("glpgp crosscheck: %s: %d vertices, %d triangles, %ld blocks, h = %.6g, energy %s\n", input, t->nv,
               t->nt, t->nnzb, t->h, t->energy == GLPGP_ELEM_TRANSPORT ? "transport" : "p1");
        printf("OpenCL %s\n\n", t->device);
    }
    if (t->eps > 0.0)
        printf("field: boundary (%ld CG iterations), %d Dirichlet vertices; eps = %.4g\n\n", t->field_cg,
               t->ndirichlet, t->eps);
    if (t->solved)
        printf("GL solve: OpenCL %.2f s, reference %.2f s (CG iterations %ld+%ld vs %ld+%ld)\n\n",
               t->solve_seconds[0], t->solve_seconds[1], t->solve_cg[0][0], t->solve_cg[0][1], t->solve_cg[1][0],
               t->solve_cg[1][1]);
    if (t->nrows == 0) return;
    printf("%-34s | %-12s | %-12s | %-30s | %s\n", "stage", "max abs diff", "max rel diff", "tolerance",
           "result");
    printf("-----------------------------------+--------------+--------------+--------------------------------+-------\n");
    for (int i = 0; i < t->nrows; i++) {
        const glpgp_crosscheck_row *r = &t->rows[i];
        printf("%-34s | %12.3e | %12.3e | %-30s | %s\n", r->stage, r->max_abs, r->max_rel, r->tol,
               r->pass ? "PASS" : "FAIL");
    }
}

typedef struct cc_args {
    const char *input;
    double size;
    int kind;
    int device;
    double tscale;
    int solve;
} cc_args;

static int cc_usage(const char *fmt, const char *arg)
{
    fprintf(stderr, "glpgp crosscheck: usage error: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, "\n(see glpgp crosscheck --help)\n");
    return 2;
}

int glpgp_cmd_crosscheck(int argc, char **argv)
{
    cc_args a = {NULL, 0.0, GLPGP_ELEM_P1, -1, 1.0, 1};
    for (int i = 1; i < argc; i++) {
        const char *s = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        char *end = NULL;
        if (!strcmp(s, "--help") || !strcmp(s, "-h")) {
            fputs(crosscheck_usage, stdout);
            return 0;
        } else if (!strcmp(s, "--no-solve")) {
            a.solve = 0;
        } else if (!strcmp(s, "--size") || !strcmp(s, "--tol-scale")) {
            if (!v) return cc_usage("%s needs a value", s);
            double x = strtod(v, &end);
            if (end == v || *end != '\0' || !(x > 0.0) || !isfinite(x))
                return cc_usage("expected a positive number, got '%s'", v);
            if (!strcmp(s, "--size")) a.size = x;
            else a.tscale = x;
            i++;
        } else if (!strcmp(s, "--energy")) {
            if (!v) return cc_usage("%s needs a value", s);
            if (!strcmp(v, "p1")) a.kind = GLPGP_ELEM_P1;
            else if (!strcmp(v, "transport")) a.kind = GLPGP_ELEM_TRANSPORT;
            else return cc_usage("--energy: '%s' is not p1 or transport", v);
            i++;
        } else if (!strcmp(s, "--device")) {
            if (!v) return cc_usage("%s needs a value", s);
            long d = strtol(v, &end, 10);
            if (end == v || *end != '\0' || d < 0 || d > 1000000)
                return cc_usage("--device: '%s' is not an integer >= 0", v);
            a.device = (int)d;
            i++;
        } else if (s[0] == '-' && s[1] != '\0') {
            return cc_usage("unknown option '%s'", s);
        } else if (!a.input) {
            a.input = s;
        } else {
            return cc_usage("unexpected argument '%s'", s);
        }
    }
    if (!a.input) return cc_usage("%s", "missing INPUT (a .obj/.msh file or shape:NAME[:N])");
    glpgp_mesh *m = NULL;
    if (cc_load(a.input, &m) != GLPGP_OK) return report_error("crosscheck");
    glpgp_crosscheck_options co;
    glpgp_crosscheck_options_default(&co);
    co.mesh = m;
    co.size = a.size;
    co.energy = a.kind;
    co.device = a.device;
    co.tol_scale = a.tscale;
    co.solve = a.solve;
    glpgp_crosscheck *t = NULL;
    glpgp_status st = glpgp_crosscheck_create(&co, &t);
    if (t) cc_print(a.input, t);
    const int pass = t && t->pass;
    glpgp_crosscheck_destroy(&t);
    glpgp_mesh_destroy(&m);
    if (st != GLPGP_OK) return report_error("crosscheck");
    printf("\ncrosscheck: %s\n", pass ? "all stages PASS" : "FAILED");
    return pass ? 0 : 1;
}

#endif /* GLPGP_HAVE_OPENCL */
